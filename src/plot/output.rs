//! Files: the output [`Format`] from a path's extension, the figure rendered to SVG text or PNG
//! bytes, and the embedded font registered before anything is measured or drawn.

use super::draw::draw_figure;
use super::figure::Figure;
use crate::error::{Error, Result};
use plotters::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Output format, chosen by the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Svg,
    Png,
}

/// The format for `path` from its extension (case-insensitive): `.svg` or `.png`.
pub fn format_for(path: &Path) -> Result<Format> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(Format::Svg),
        Some("png") => Ok(Format::Png),
        Some(other) => Err(Error::usage(format!(
            "--plot '{}': unsupported extension '.{other}' (allowed: .svg, .png)",
            path.display()
        ))),
        None => Err(Error::usage(format!(
            "--plot '{}': no file extension (allowed: .svg, .png)",
            path.display()
        ))),
    }
}

/// Draw `fig` and write it to `path` as SVG or PNG by the extension.
pub fn write(fig: &Figure, path: &Path) -> Result<()> {
    let format = format_for(path)?;
    let bytes = match format {
        Format::Svg => render_svg(fig)?.into_bytes(),
        Format::Png => render_png(fig)?,
    };
    write_whole(path, &bytes)
        .map_err(|e| Error::Io(format!("cannot write plot '{}': {e}", path.display())))
}

/// `bytes` into a temporary file beside `path`, then renamed onto it: a write that fails (a full
/// disk, a quota, a file-size limit) leaves no truncated plot and the file that was there as it
/// was.
fn write_whole(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"))?;
    let mut temporary = std::ffi::OsString::from(".");
    temporary.push(name);
    temporary.push(format!(".{}.tmp", std::process::id()));
    let temporary = path.with_file_name(temporary);
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&temporary)
        .and_then(|mut file| {
            file.write_all(bytes)?;
            file.sync_all()
        })
        .and_then(|()| std::fs::rename(&temporary, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    written
}

/// The figure as an SVG document.
pub fn render_svg(fig: &Figure) -> Result<String> {
    check(fig)?;
    ensure_fonts()?;
    let mut out = String::new();
    draw_figure(
        fig,
        &SVGBackend::with_string(&mut out, fig.pixel_size()).into_drawing_area(),
    )?;
    Ok(out)
}

/// The figure as PNG bytes (8-bit RGB).
pub fn render_png(fig: &Figure) -> Result<Vec<u8>> {
    check(fig)?;
    ensure_fonts()?;
    let (w, h) = fig.pixel_size();
    let mut pixels = vec![255u8; w as usize * h as usize * 3];
    draw_figure(
        fig,
        &BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area(),
    )?;
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let mut writer = encoder.write_header().map_err(png_error)?;
        writer.write_image_data(&pixels).map_err(png_error)?;
        writer.finish().map_err(png_error)?;
    }
    Ok(bytes)
}

fn png_error(e: png::EncodingError) -> Error {
    Error::Io(format!("cannot encode PNG: {e}"))
}

/// Refuse, as usage errors, figures that cannot be drawn: no panels, no columns, an absurd size
/// or a malformed fixed range.
fn check(fig: &Figure) -> Result<()> {
    if fig.panels.is_empty() {
        return Err(Error::usage(format!(
            "plot '{}': the figure has no panels",
            fig.title
        )));
    }
    if fig.columns == 0 {
        return Err(Error::usage(format!(
            "plot '{}': a figure needs at least one column",
            fig.title
        )));
    }
    let (w, h) = fig.pixel_size();
    if !(100..=20_000).contains(&w) || !(100..=20_000).contains(&h) {
        return Err(Error::usage(format!(
            "plot '{}': size {w}x{h} out of range (allowed: 100..20000 pixels each way)",
            fig.title
        )));
    }
    for (i, p) in fig.panels.iter().enumerate() {
        for (axis, range) in [("x", p.x_range), ("y", p.y_range)] {
            if let Some((lo, hi)) = range {
                if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                    return Err(Error::usage(format!(
                        "plot '{}', panel {}: {axis} range {lo}..{hi} must be finite and increasing",
                        fig.title,
                        i + 1
                    )));
                }
            }
        }
    }
    Ok(())
}

/// Register the embedded font once for every family name plotters may ask for.
fn ensure_fonts() -> Result<()> {
    static FONTS: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let regular = dejavu::sans::regular();
            for family in ["sans-serif", "serif", "monospace"] {
                plotters::style::register_font(family, FontStyle::Normal, regular)
                    .map_err(|_| "the embedded DejaVu Sans font could not be read".to_string())?;
            }
            Ok(())
        })
        .clone()
        .map_err(Error::Io)
}
