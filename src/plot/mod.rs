//! Publication-quality plots: a small declarative figure model and one writer.
//!
//! The commands build a [`Figure`] from their results (this module computes no physics, it only
//! draws the numbers it is given) and call [`write`], which picks SVG or PNG from the file's
//! extension. A figure is a grid of [`Panel`]s (one column by default: stacked panels, e.g. a
//! Campbell diagram with frequency above damping); each panel has axes with units, data
//! [`Series`], reference [`Guide`] lines (1P/3P, a flutter boundary, zero damping), labelled
//! [`Marker`]s and free-text notes.
//!
//! Rendering never needs a system font: DejaVu Sans is registered from bytes embedded in the
//! binary (the `dejavu` crate) for plotters' `ab_glyph` text path. Figures are drawn in memory
//! and written in one `std::fs::write`, so a bad path gives an [`Error::Io`] naming it and never
//! leaves a half-written file from a drawing failure.
//!
//! [`figures`] turns the engine's results (sweeps, flutter searches, time responses, section
//! grids) into figures; the commands call it for `--plot FILE`.
//!
//! SVG structure (the tests rely on it): every maximal run of finite, in-range points of a line
//! series (`Mark::Line` or `Mark::LinePoints`) is exactly one `<polyline>`; legend swatches,
//! frames and the grid are `<rect>`/`<line>`; guides are drawn as dashes (several short
//! `<polyline>`s) and points as `<circle>`s.

use crate::error::{Error, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;
use std::sync::OnceLock;

pub mod figures;
pub mod text;

/// Default size of a figure of up to two rows and two columns, in pixels (PNG) or SVG units.
pub const DEFAULT_SIZE: (u32, u32) = (1200, 800);
/// Height given to each row beyond the second, and width to each column beyond the second.
const ROW_HEIGHT: u32 = 420;
const COLUMN_WIDTH: u32 = 640;

const FONT: &str = "sans-serif";
const TITLE_SIZE: f64 = 34.0;
const CAPTION_SIZE: f64 = 26.0;
const AXIS_DESC_SIZE: f64 = 23.0;
const TICK_SIZE: f64 = 20.0;
const LEGEND_SIZE: f64 = 19.0;
const NOTE_SIZE: f64 = 19.0;

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// Colour-blind-safe qualitative palette (Okabe–Ito, then Tableau tones); series without a
/// colour take the next one in order.
pub const PALETTE: [Rgb; 12] = [
    Rgb(0, 114, 178),   // blue
    Rgb(213, 94, 0),    // vermillion
    Rgb(0, 158, 115),   // bluish green
    Rgb(204, 121, 167), // reddish purple
    Rgb(230, 159, 0),   // orange
    Rgb(86, 180, 233),  // sky blue
    Rgb(0, 0, 0),       // black
    Rgb(140, 86, 75),   // brown
    Rgb(127, 127, 127), // grey
    Rgb(188, 189, 34),  // olive
    Rgb(148, 103, 189), // purple
    Rgb(23, 190, 207),  // cyan
];

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A solid line through the points.
    Line,
    /// Unconnected points (e.g. eigenvalues in the complex plane).
    Points,
    /// A solid line with a dot at every point (e.g. a quantity at a few ply angles).
    LinePoints,
}

/// The look of a series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    pub mark: Mark,
    /// `None`: the next palette colour.
    pub color: Option<Rgb>,
    /// Line width in pixels at the default size.
    pub width: u32,
}

impl Style {
    pub fn new(mark: Mark) -> Self {
        Style {
            mark,
            color: None,
            width: 2,
        }
    }
}

/// One named data series. Non-finite points are gaps (a line is broken there).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry; an empty name keeps the series out of the legend.
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

impl Series {
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::new(mark),
        }
    }
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::Line)
    }
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::Points)
    }
    pub fn line_points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self::new(name, points, Mark::LinePoints)
    }
    /// Pair `xs` with `ys` (the shorter length wins).
    pub fn from_xy(name: impl Into<String>, xs: &[f64], ys: &[f64], mark: Mark) -> Self {
        Self::new(
            name,
            xs.iter().copied().zip(ys.iter().copied()).collect(),
            mark,
        )
    }
    pub fn with_color(mut self, color: Rgb) -> Self {
        self.style.color = Some(color);
        self
    }
    pub fn with_width(mut self, width: u32) -> Self {
        self.style.width = width.max(1);
        self
    }
}

/// Where a reference line runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GuideKind {
    /// x = const over the whole panel height; its x is kept inside the panel's range.
    Vertical(f64),
    /// y = const over the whole panel width; its y is kept inside the panel's range.
    Horizontal(f64),
    /// A straight segment in data coordinates, clipped to the panel; does not widen the range
    /// (e.g. a 3P line on a Campbell diagram).
    Segment { from: (f64, f64), to: (f64, f64) },
}

/// A dashed reference line with its label written beside it (not in the legend).
#[derive(Debug, Clone, PartialEq)]
pub struct Guide {
    pub kind: GuideKind,
    pub label: String,
    /// `None`: dark grey.
    pub color: Option<Rgb>,
}

impl Guide {
    pub fn vertical(x: f64, label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Vertical(x),
            label: label.into(),
            color: None,
        }
    }
    pub fn horizontal(y: f64, label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Horizontal(y),
            label: label.into(),
            color: None,
        }
    }
    pub fn segment(from: (f64, f64), to: (f64, f64), label: impl Into<String>) -> Self {
        Guide {
            kind: GuideKind::Segment { from, to },
            label: label.into(),
            color: None,
        }
    }
    pub fn with_color(mut self, color: Rgb) -> Self {
        self.color = Some(color);
        self
    }
}

/// A highlighted point with a label (e.g. the flutter boundary on the σ = 0 line).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub x: f64,
    pub y: f64,
    pub label: String,
}

impl Marker {
    pub fn new(x: f64, y: f64, label: impl Into<String>) -> Self {
        Marker {
            x,
            y,
            label: label.into(),
        }
    }
}

/// One set of axes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Caption above the axes, e.g. "(a) classical flutter"; empty for none.
    pub title: String,
    /// Axis descriptions with their units, e.g. "rotor speed (rpm)".
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub guides: Vec<Guide>,
    pub markers: Vec<Marker>,
    /// Free text lines written in a corner of the axes.
    pub notes: Vec<String>,
    /// Fixed axis ranges; `None`: fitted to the series, markers and vertical/horizontal guides.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Draw the legend (when at least one series has a name).
    pub legend: bool,
}

impl Panel {
    pub fn new(x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Panel {
            x_label: x_label.into(),
            y_label: y_label.into(),
            legend: true,
            ..Panel::default()
        }
    }
    pub fn titled(mut self, title: impl Into<String>) -> Self {
        self.title = title.into();
        self
    }
    pub fn with_series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
    pub fn with_guide(mut self, guide: Guide) -> Self {
        self.guides.push(guide);
        self
    }
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.markers.push(marker);
        self
    }
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
    pub fn with_x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }
    pub fn with_y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }
}

/// A titled grid of panels, filled row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub title: String,
    pub panels: Vec<Panel>,
    /// Panels per row (1: stacked).
    pub columns: usize,
    /// Pixel size; `None`: 1200×800, grown by 420 px per row beyond two and 640 px per column
    /// beyond two.
    pub size: Option<(u32, u32)>,
}

impl Figure {
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            panels: Vec::new(),
            columns: 1,
            size: None,
        }
    }
    pub fn with_panel(mut self, panel: Panel) -> Self {
        self.panels.push(panel);
        self
    }
    pub fn with_columns(mut self, columns: usize) -> Self {
        self.columns = columns;
        self
    }
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.size = Some((width, height));
        self
    }

    /// Rows of the panel grid.
    pub fn rows(&self) -> usize {
        self.panels.len().div_ceil(self.columns.max(1))
    }

    /// The pixel size the figure is drawn at.
    pub fn pixel_size(&self) -> (u32, u32) {
        if let Some(size) = self.size {
            return size;
        }
        let rows = self.rows() as u32;
        let cols = self.columns.max(1) as u32;
        (
            DEFAULT_SIZE.0 + COLUMN_WIDTH * cols.saturating_sub(2),
            DEFAULT_SIZE.1 + ROW_HEIGHT * rows.saturating_sub(2),
        )
    }
}

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
    std::fs::write(path, bytes)
        .map_err(|e| Error::Io(format!("cannot write plot '{}': {e}", path.display())))
}

/// The figure as an SVG document.
pub fn render_svg(fig: &Figure) -> Result<String> {
    check(fig)?;
    let size = fig.pixel_size();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        draw_figure(fig, &root)?;
        root.present().map_err(draw_error)?;
    }
    Ok(out)
}

/// The figure as PNG bytes (8-bit RGB).
pub fn render_png(fig: &Figure) -> Result<Vec<u8>> {
    check(fig)?;
    let (w, h) = fig.pixel_size();
    let mut pixels = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
        draw_figure(fig, &root)?;
        root.present().map_err(draw_error)?;
    }
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

fn draw_error<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> Error {
    Error::Io(format!("cannot draw plot: {e}"))
}

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

fn color(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

const GUIDE_GREY: Rgb = Rgb(90, 90, 90);

fn draw_figure<DB: DrawingBackend>(fig: &Figure, root: &DrawingArea<DB, Shift>) -> Result<()>
where
    DB::ErrorType: 'static,
{
    ensure_fonts()?;
    root.fill(&WHITE).map_err(draw_error)?;
    let body = if fig.title.is_empty() {
        root.clone()
    } else {
        // A top margin keeps the title's ascenders inside the image.
        // Shrink a long title to fit the width.
        let width = f64::from(root.dim_in_pixel().0);
        let size = TITLE_SIZE * (0.96 * width / text_width(&fig.title, TITLE_SIZE)).min(1.0);
        root.margin(10, 0, 0, 0)
            .titled(&fig.title, (FONT, size).into_font().color(&BLACK))
            .map_err(draw_error)?
    };
    let cols = fig.columns.max(1);
    let areas = body.split_evenly((fig.rows(), cols));
    let mut layouts: Vec<PanelLayout> = fig
        .panels
        .iter()
        .zip(areas.iter())
        .map(|(panel, area)| PanelLayout::new(panel, area.dim_in_pixel()))
        .collect();
    // Panels in one grid column share the y-label width and the legend column's width, so
    // their plots line up.
    let mut reserve = vec![0.0f64; cols];
    let mut y_area = vec![0u32; cols];
    for (i, l) in layouts.iter().enumerate() {
        reserve[i % cols] = reserve[i % cols].max(l.legend_column.unwrap_or(0.0));
        y_area[i % cols] = y_area[i % cols].max(l.y_area);
    }
    for (i, l) in layouts.iter_mut().enumerate() {
        l.y_area = y_area[i % cols];
    }
    for (i, ((panel, area), layout)) in fig
        .panels
        .iter()
        .zip(areas.iter())
        .zip(&layouts)
        .enumerate()
    {
        draw_panel(panel, layout, area, reserve[i % cols])?;
    }
    Ok(())
}

/// Axis range fitted to the data, widened by 5 % each side; a flat or empty range gets a
/// sensible width.
fn fit_range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return (0.0, 1.0);
    }
    if hi - lo <= 1e-12 * lo.abs().max(hi.abs()).max(1e-300) {
        let half = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return (lo - half, hi + half);
    }
    let pad = pad * (hi - lo);
    (lo - pad, hi + pad)
}

/// The panel's axis ranges: fixed ones as given, the rest fitted to the data plus `pad` (a
/// fraction of the span) on each side.
fn panel_ranges(panel: &Panel, pad: f64) -> ((f64, f64), (f64, f64)) {
    let x = panel.x_range.unwrap_or_else(|| {
        fit_range(
            panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().filter(|p| p.1.is_finite()).map(|p| p.0))
                .chain(panel.markers.iter().map(|m| m.x))
                .chain(panel.guides.iter().filter_map(|g| match g.kind {
                    GuideKind::Vertical(x) => Some(x),
                    _ => None,
                })),
            pad,
        )
    });
    let y = panel.y_range.unwrap_or_else(|| {
        let in_x = |px: f64| px >= x.0 && px <= x.1;
        fit_range(
            panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().filter(|p| in_x(p.0)).map(|p| p.1))
                .chain(panel.markers.iter().map(|m| m.y))
                .chain(panel.guides.iter().filter_map(|g| match g.kind {
                    GuideKind::Horizontal(y) => Some(y),
                    _ => None,
                })),
            pad,
        )
    });
    (x, y)
}

/// Liang–Barsky: the part of segment a→b inside the box, if any.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    // Unclipped ends are returned exactly, so consecutive segments join into one run.
    let start = if t0 == 0.0 {
        a
    } else {
        (a.0 + t0 * dx, a.1 + t0 * dy)
    };
    let end = if t1 == 1.0 {
        b
    } else {
        (a.0 + t1 * dx, a.1 + t1 * dy)
    };
    Some((start, end))
}

/// Split a polyline into runs that are finite and inside the box (clipping at the edges).
pub fn visible_runs(points: &[(f64, f64)], xr: (f64, f64), yr: (f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let clipped = if finite(&a) && finite(&b) {
            clip_segment(a, b, xr, yr)
        } else {
            None
        };
        match clipped {
            Some((ca, cb)) => {
                if current.last() != Some(&ca) {
                    if current.len() >= 2 {
                        runs.push(std::mem::take(&mut current));
                    }
                    current.clear();
                    current.push(ca);
                }
                current.push(cb);
            }
            None => {
                if current.len() >= 2 {
                    runs.push(std::mem::take(&mut current));
                }
                current.clear();
            }
        }
    }
    if current.len() >= 2 {
        runs.push(current);
    }
    // A single visible point draws no line; `Mark::LinePoints` still shows it as a dot.
    runs
}

/// Tick labels asked of plotters per axis (its maximum number of key points).
const X_TICKS: usize = 8;
const Y_TICKS: usize = 7;

/// The tick step plotters picks for a range: the smallest of 1, 2, 5 × 10^k giving at most
/// `max_points` ticks (the rule of plotters' `compute_f64_key_points`).
fn tick_step(lo: f64, hi: f64, max_points: usize) -> f64 {
    let span = hi - lo;
    let mut exp = span.log10().floor() as i32 + 1;
    let mut best = 10f64.powi(exp);
    loop {
        for mult in [5.0, 2.0, 1.0] {
            let step = mult * 10f64.powi(exp - 1);
            let count = (hi / step).floor() - (lo / step).ceil() + 1.0;
            if count > max_points as f64 || exp < -320 {
                return best;
            }
            best = step;
        }
        exp -= 1;
    }
}

/// Decimal places for tick labels over a range, or `None` for scientific notation.
fn tick_decimals(lo: f64, hi: f64, max_points: usize) -> Option<usize> {
    let span = hi - lo;
    let mag = lo.abs().max(hi.abs());
    if !(span.is_finite() && span > 0.0 && (1e-3..1e5).contains(&mag)) {
        return None;
    }
    let step = tick_step(lo, hi, max_points);
    let decimals = -(step.log10() + 1e-9).floor();
    if decimals > 9.0 {
        None
    } else {
        Some(decimals.max(0.0) as usize)
    }
}

fn format_tick(v: f64, decimals: Option<usize>) -> String {
    let v = if v.abs() < 1e-300 { 0.0 } else { v };
    match decimals {
        Some(d) => {
            let s = format!("{v:.d$}");
            if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
                s[1..].to_string()
            } else {
                s
            }
        }
        None if v == 0.0 => "0".to_string(),
        None => format!("{v:.2e}"),
    }
}

#[derive(Clone, Copy)]
enum Corner {
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
}

const CORNERS: [Corner; 4] = [
    Corner::UpperRight,
    Corner::UpperLeft,
    Corner::LowerRight,
    Corner::LowerLeft,
];

/// What a box in a corner of the plot would cover: the series drawn there (lines sampled
/// every few pixels), markers and guide labels. Used to place the legend and the notes.
struct Occupancy {
    /// Samples in pixel coordinates of the plotting area (y down).
    data: Vec<(f64, f64)>,
    /// Label anchors in pixel coordinates; they weigh more than a data sample.
    labels: Vec<(f64, f64)>,
    size: (f64, f64),
}

impl Occupancy {
    fn new(panel: &Panel, xr: (f64, f64), yr: (f64, f64), size: (u32, u32)) -> Self {
        let (w, h) = (size.0 as f64, size.1 as f64);
        let px = |(x, y): (f64, f64)| {
            (
                (x - xr.0) / (xr.1 - xr.0) * w,
                (yr.1 - y) / (yr.1 - yr.0) * h,
            )
        };
        let mut data = Vec::new();
        for s in &panel.series {
            if matches!(s.style.mark, Mark::Line | Mark::LinePoints) {
                for run in visible_runs(&s.points, xr, yr) {
                    for pair in run.windows(2) {
                        let (a, b) = (px(pair[0]), px(pair[1]));
                        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
                        let n = (len / 4.0).ceil().clamp(1.0, 400.0) as usize;
                        for k in 0..n {
                            let t = k as f64 / n as f64;
                            data.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                        }
                    }
                }
            }
            for &p in &s.points {
                if p.0.is_finite() && p.1.is_finite() {
                    data.push(px(p));
                }
            }
        }
        let mut labels: Vec<(f64, f64)> = panel.markers.iter().map(|m| px((m.x, m.y))).collect();
        for g in &panel.guides {
            // The dashed line itself, sampled like a series.
            let (a, b) = match g.kind {
                GuideKind::Vertical(x) => ((x, yr.0), (x, yr.1)),
                GuideKind::Horizontal(y) => ((xr.0, y), (xr.1, y)),
                GuideKind::Segment { from, to } => (from, to),
            };
            if let Some((a, b)) = clip_segment(a, b, xr, yr) {
                let (a, b) = (px(a), px(b));
                let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
                let n = (len / 4.0).ceil().clamp(1.0, 400.0) as usize;
                for k in 0..=n {
                    let t = k as f64 / n as f64;
                    data.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                }
            }
            let at =
                match g.kind {
                    GuideKind::Vertical(x) => Some((x, yr.1)),
                    GuideKind::Horizontal(y) => Some((xr.1, y)),
                    GuideKind::Segment { from, to } => clip_segment(from, to, xr, yr)
                        .map(|(a, b)| if (b.0, b.1) >= (a.0, a.1) { b } else { a }),
                };
            if let (Some(at), false) = (at, g.label.is_empty()) {
                labels.push(px(at));
            }
        }
        Occupancy {
            data,
            labels,
            size: (w, h),
        }
    }

    /// The box of `size` pixels placed in `corner` (with a 10 px margin).
    fn rect(&self, corner: Corner, size: (f64, f64)) -> (f64, f64, f64, f64) {
        let (w, h) = self.size;
        let m = 10.0;
        let (x0, y0) = match corner {
            Corner::UpperRight => (w - m - size.0, m),
            Corner::UpperLeft => (m, m),
            Corner::LowerRight => (w - m - size.0, h - m - size.1),
            Corner::LowerLeft => (m, h - m - size.1),
        };
        (x0, y0, x0 + size.0, y0 + size.1)
    }

    fn cost(&self, rect: (f64, f64, f64, f64)) -> usize {
        let inside =
            |&(x, y): &(f64, f64)| x >= rect.0 && x <= rect.2 && y >= rect.1 && y <= rect.3;
        // Labels are padded by their approximate text extent.
        let near = |&(x, y): &(f64, f64)| {
            x >= rect.0 - 160.0 && x <= rect.2 + 20.0 && y >= rect.1 - 25.0 && y <= rect.3 + 25.0
        };
        self.data.iter().filter(|p| inside(p)).count()
            + 200 * self.labels.iter().filter(|p| near(p)).count()
    }

    /// The corner where a box of `size` covers least, avoiding `taken` boxes.
    fn best_corner(&self, size: (f64, f64), taken: &[(f64, f64, f64, f64)]) -> Corner {
        let overlaps = |a: (f64, f64, f64, f64), b: &(f64, f64, f64, f64)| {
            a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
        };
        CORNERS
            .iter()
            .copied()
            .min_by_key(|&c| {
                let r = self.rect(c, size);
                let clash = taken.iter().any(|t| overlaps(r, t));
                (clash, self.cost(r))
            })
            .unwrap_or(Corner::UpperRight)
    }
}

/// Approximate pixel width of `text` at `size` (DejaVu Sans averages ~0.55 em per character;
/// plotters' font size is 1.24 × the em).
fn text_width(text: &str, size: f64) -> f64 {
    // Measured with the registered font; the estimate is the fallback before registration.
    match (FONT, size).into_font().box_size(text) {
        Ok((w, _)) => f64::from(w),
        Err(_) => text.chars().count() as f64 * 0.6 * size / 1.24,
    }
}

/// One legend row.
struct LegendEntry {
    name: String,
    color: RGBColor,
    mark: Mark,
}

const LEGEND_PAD: f64 = 8.0;
const LEGEND_SWATCH: f64 = 30.0;

fn legend_line_height() -> f64 {
    (LEGEND_SIZE / 1.24 * 1.35).round()
}

/// Width and height of a legend box for `entries` (at most `rows` rows).
fn legend_size(entries: &[LegendEntry], rows: usize) -> (f64, f64) {
    let text = entries
        .iter()
        .take(rows)
        .map(|e| text_width(&e.name, LEGEND_SIZE))
        .fold(0.0, f64::max);
    (
        text + LEGEND_SWATCH + 3.0 * LEGEND_PAD,
        rows.min(entries.len()) as f64 * legend_line_height() + 2.0 * LEGEND_PAD,
    )
}

/// Draw a legend box with its top-left corner at `origin` (pixels of `target`), at most `rows`
/// rows (the last says how many more were left out when they do not all fit), names cut to
/// `max_text` pixels.
fn draw_legend<DB: DrawingBackend>(
    target: &DrawingArea<DB, Shift>,
    origin: (i32, i32),
    entries: &[LegendEntry],
    rows: usize,
    max_text: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let rows = rows.max(1);
    let (listed, more) = if entries.len() > rows {
        (rows - 1, entries.len() - (rows - 1))
    } else {
        (entries.len(), 0)
    };
    let cut = |name: &str| -> String {
        if text_width(name, LEGEND_SIZE) <= max_text {
            return name.to_string();
        }
        let keep = (max_text / text_width("m", LEGEND_SIZE)).floor().max(2.0) as usize - 1;
        format!("{}…", name.chars().take(keep).collect::<String>())
    };
    let names: Vec<String> = entries[..listed].iter().map(|e| cut(&e.name)).collect();
    let more_text = format!("+ {more} more");
    let text_w = names
        .iter()
        .map(|n| text_width(n, LEGEND_SIZE))
        .chain((more > 0).then(|| text_width(&more_text, LEGEND_SIZE)))
        .fold(0.0, f64::max)
        .min(max_text);
    let line = legend_line_height();
    let n_rows = listed + usize::from(more > 0);
    let w = (text_w + LEGEND_SWATCH + 3.0 * LEGEND_PAD) as i32;
    let h = (n_rows as f64 * line + 2.0 * LEGEND_PAD) as i32;
    let (x0, y0) = origin;
    target
        .draw(&Rectangle::new(
            [(x0, y0), (x0 + w, y0 + h)],
            WHITE.mix(0.85).filled(),
        ))
        .map_err(draw_error)?;
    target
        .draw(&Rectangle::new(
            [(x0, y0), (x0 + w, y0 + h)],
            RGBColor(160, 160, 160).stroke_width(1),
        ))
        .map_err(draw_error)?;
    let font = (FONT, LEGEND_SIZE)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let sx = x0 + LEGEND_PAD as i32;
    let tx = sx + (LEGEND_SWATCH + LEGEND_PAD) as i32;
    for (i, (e, name)) in entries[..listed].iter().zip(&names).enumerate() {
        let cy = y0 + (LEGEND_PAD + (i as f64 + 0.5) * line) as i32;
        // Swatches are rectangles and circles, never polylines (one polyline per data run).
        if matches!(e.mark, Mark::Line | Mark::LinePoints) {
            target
                .draw(&Rectangle::new(
                    [(sx, cy - 2), (sx + LEGEND_SWATCH as i32, cy + 2)],
                    e.color.filled(),
                ))
                .map_err(draw_error)?;
        } else {
            target
                .draw(&Circle::new(
                    (sx + LEGEND_SWATCH as i32 / 2, cy),
                    5,
                    e.color.filled(),
                ))
                .map_err(draw_error)?;
        }
        target
            .draw(&Text::new(name.as_str(), (tx, cy), font.clone()))
            .map_err(draw_error)?;
    }
    if more > 0 {
        let cy = y0 + (LEGEND_PAD + (listed as f64 + 0.5) * line) as i32;
        target
            .draw(&Text::new(more_text.as_str(), (tx, cy), font.clone()))
            .map_err(draw_error)?;
    }
    Ok(())
}

/// What a panel needs before it is drawn: ranges, tick formats, colours, legend entries, and
/// whether its legend needs a column right of the plot (its width).
struct PanelLayout {
    xr: (f64, f64),
    yr: (f64, f64),
    xd: Option<usize>,
    yd: Option<usize>,
    y_area: u32,
    colors: Vec<RGBColor>,
    entries: Vec<LegendEntry>,
    legend_column: Option<f64>,
}

impl PanelLayout {
    fn new(panel: &Panel, (aw, ah): (u32, u32)) -> Self {
        let (xr, yr) = panel_ranges(panel, 0.05);
        let (xd, yd) = (
            tick_decimals(xr.0, xr.1, X_TICKS),
            tick_decimals(yr.0, yr.1, Y_TICKS),
        );
        let y_label_chars = [yr.0, yr.1, 0.5 * (yr.0 + yr.1)]
            .iter()
            .map(|&v| format_tick(v, yd).chars().count())
            .max()
            .unwrap_or(4) as u32;
        let y_area = 12 * y_label_chars + 44;

        // Series colours: given, or the palette in order.
        let mut palette = PALETTE.iter().cycle();
        let colors: Vec<RGBColor> = panel
            .series
            .iter()
            .map(|s| {
                color(
                    s.style
                        .color
                        .unwrap_or_else(|| *palette.next().unwrap_or(&PALETTE[0])),
                )
            })
            .collect();
        let entries: Vec<LegendEntry> = if panel.legend {
            panel
                .series
                .iter()
                .zip(&colors)
                .filter(|(s, _)| !s.name.is_empty())
                .map(|(s, &c)| LegendEntry {
                    name: s.name.clone(),
                    color: c,
                    mark: s.style.mark,
                })
                .collect()
        } else {
            Vec::new()
        };

        // A legend that would cover much of the plot goes in a column to its right.
        let (aw, ah) = (f64::from(aw), f64::from(ah));
        let caption_h = if panel.title.is_empty() {
            0.0
        } else {
            CAPTION_SIZE * 1.4
        };
        let plot_h = (ah - caption_h - 24.0 - 62.0).max(40.0);
        let plot_w = (aw - f64::from(y_area) - 36.0).max(40.0);
        let (legend_w, legend_h) = legend_size(&entries, entries.len());
        let outside = !entries.is_empty() && (legend_h > 0.5 * plot_h || legend_w > 0.4 * plot_w);
        let legend_column = outside.then(|| legend_w.min(0.3 * aw).ceil());
        PanelLayout {
            xr,
            yr,
            xd,
            yd,
            y_area,
            colors,
            entries,
            legend_column,
        }
    }
}

/// Draw one panel; `reserve` is the width of the legend column kept right of the plot (0: none).
fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    layout: &PanelLayout,
    area: &DrawingArea<DB, Shift>,
    reserve: f64,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let PanelLayout {
        xr,
        yr,
        xd,
        yd,
        y_area,
        ref colors,
        ref entries,
        ..
    } = *layout;
    let outside = reserve > 0.0 && !entries.is_empty();
    let column = reserve;

    let mut builder = ChartBuilder::on(area);
    builder
        .margin(12)
        .margin_right(if reserve > 0.0 {
            reserve as u32 + 20
        } else {
            24
        })
        .x_label_area_size(62)
        .y_label_area_size(y_area);
    if !panel.title.is_empty() {
        builder.caption(&panel.title, (FONT, CAPTION_SIZE));
    }
    let mut chart = builder
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(draw_error)?;

    let x_fmt = move |v: &f64| format_tick(*v, xd);
    let y_fmt = move |v: &f64| format_tick(*v, yd);
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_labels(X_TICKS)
        .y_labels(Y_TICKS)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style((FONT, TICK_SIZE))
        .axis_desc_style((FONT, AXIS_DESC_SIZE))
        .bold_line_style(RGBColor(200, 200, 200).stroke_width(1))
        .light_line_style(TRANSPARENT)
        .axis_style(BLACK.stroke_width(1))
        .draw()
        .map_err(draw_error)?;

    // Guide lines first, so the data is drawn over them; their labels last, over the data.
    let mut guide_labels = Vec::new();
    for guide in &panel.guides {
        if let Some(place) = draw_guide_line(&mut chart, guide, xr, yr)? {
            guide_labels.push((place, guide));
        }
    }

    for (series, &c) in panel.series.iter().zip(colors) {
        let line_style = c.stroke_width(series.style.width.max(1));
        let mark = series.style.mark;
        if matches!(mark, Mark::Line | Mark::LinePoints) {
            for run in visible_runs(&series.points, xr, yr) {
                chart
                    .draw_series(std::iter::once(PathElement::new(run, line_style)))
                    .map_err(draw_error)?;
            }
        }
        if matches!(mark, Mark::Points | Mark::LinePoints) {
            let radius = if mark == Mark::Points { 5 } else { 4 };
            let pts = series
                .points
                .iter()
                .copied()
                .filter(|&(x, y)| x >= xr.0 && x <= xr.1 && y >= yr.0 && y <= yr.1);
            chart
                .draw_series(pts.map(|p| Circle::new(p, radius, c.filled())))
                .map_err(draw_error)?;
        }
    }

    for m in &panel.markers {
        if !(m.x.is_finite() && m.y.is_finite()) {
            continue;
        }
        let p = (m.x, m.y);
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(p)
                    + Circle::new((0, 0), 7, RGBColor(255, 255, 255).filled())
                    + Circle::new((0, 0), 7, BLACK.stroke_width(2))
                    + Circle::new((0, 0), 3, BLACK.filled()),
            ))
            .map_err(draw_error)?;
        if !m.label.is_empty() {
            // Write the label toward the middle of the plot so it stays inside it.
            let right_half = (m.x - xr.0) / (xr.1 - xr.0) > 0.6;
            let upper_half = (m.y - yr.0) / (yr.1 - yr.0) > 0.5;
            let h = if right_half { HPos::Right } else { HPos::Left };
            let v = if upper_half { VPos::Top } else { VPos::Bottom };
            let dx = if right_half { -12 } else { 12 };
            let dy = if upper_half { 10 } else { -10 };
            let place = LabelPlacement {
                at: p,
                h,
                v,
                offset: (dx, dy),
            };
            draw_label(&mut chart, &place, &m.label, BLACK)?;
        }
    }
    for (place, guide) in &guide_labels {
        let ink = color(guide.color.unwrap_or(GUIDE_GREY));
        draw_label(&mut chart, place, &guide.label, ink)?;
    }

    let plot_area = chart.plotting_area().strip_coord_spec();
    let plot_px = plot_area.dim_in_pixel();
    let occupancy = Occupancy::new(panel, xr, yr, plot_px);
    let mut taken = Vec::new();
    if !panel.notes.is_empty() {
        let width = panel
            .notes
            .iter()
            .map(|n| text_width(n, NOTE_SIZE))
            .fold(0.0, f64::max);
        let size = (
            width + 12.0,
            NOTE_SIZE * 1.15 * panel.notes.len() as f64 + 10.0,
        );
        let corner = occupancy.best_corner(size, &[]);
        taken.push(occupancy.rect(corner, size));
        draw_notes(&chart, &panel.notes, corner)?;
    }

    if outside {
        // The column right of the plot, top-aligned with it, in the panel's pixels.
        let (bx, by) = plot_area.get_base_pixel();
        let (ox, oy) = area.get_base_pixel();
        let x = bx - ox + plot_px.0 as i32 + 12;
        let y = by - oy;
        let rows = ((plot_px.1 as f64 - 2.0 * LEGEND_PAD) / legend_line_height()).floor() as usize;
        let max_text = column - LEGEND_SWATCH - 3.0 * LEGEND_PAD;
        draw_legend(area, (x, y), entries, rows, max_text)?;
    } else if !entries.is_empty() {
        let size = legend_size(entries, entries.len());
        let corner = occupancy.best_corner(size, &taken);
        let r = occupancy.rect(corner, size);
        draw_legend(
            &plot_area,
            (r.0 as i32, r.1 as i32),
            entries,
            entries.len(),
            f64::INFINITY,
        )?;
    }
    Ok(())
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Where a guide's label goes: the anchor in data coordinates, the text anchor and a pixel offset.
struct LabelPlacement {
    at: (f64, f64),
    h: HPos,
    v: VPos,
    offset: (i32, i32),
}

/// Draw a guide's dashed line; return where its label goes (drawn later, over the data).
fn draw_guide_line<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    guide: &Guide,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<Option<LabelPlacement>>
where
    DB::ErrorType: 'static,
{
    let (a, b) = match guide.kind {
        GuideKind::Vertical(x) => ((x, yr.0), (x, yr.1)),
        GuideKind::Horizontal(y) => ((xr.0, y), (xr.1, y)),
        GuideKind::Segment { from, to } => (from, to),
    };
    if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
        return Ok(None);
    }
    let Some((a, b)) = clip_segment(a, b, xr, yr) else {
        return Ok(None);
    };
    let c = color(guide.color.unwrap_or(GUIDE_GREY));
    chart
        .draw_series(DashedLineSeries::new([a, b], 10, 6, c.stroke_width(2)))
        .map_err(draw_error)?;
    if guide.label.is_empty() {
        return Ok(None);
    }
    // Label at the end of the line that lies furthest right/up, nudged inside the plot.
    let end = if (b.0, b.1) >= (a.0, a.1) { b } else { a };
    let (h, v, offset) = match guide.kind {
        GuideKind::Vertical(_) => (HPos::Left, VPos::Top, (6, 6)),
        GuideKind::Horizontal(_) => (HPos::Right, VPos::Bottom, (-6, -4)),
        GuideKind::Segment { .. } => {
            // Leaving through the right edge: label above-left of the end; through the top
            // (or bottom): label beside the end, inside the plot.
            let at_right = (end.0 - xr.0) / (xr.1 - xr.0) > 0.98;
            let at_top = (end.1 - yr.0) / (yr.1 - yr.0) > 0.98;
            match (at_right, at_top) {
                (true, _) => (HPos::Right, VPos::Bottom, (-6, -4)),
                (false, true) => (HPos::Right, VPos::Top, (-8, 4)),
                (false, false) => (HPos::Left, VPos::Bottom, (6, -4)),
            }
        }
    };
    Ok(Some(LabelPlacement {
        at: end,
        h,
        v,
        offset,
    }))
}

/// A text label on a translucent white box, anchored at a data point plus a pixel offset.
fn draw_label<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    place: &LabelPlacement,
    text: &str,
    ink: RGBColor,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let w = text_width(text, NOTE_SIZE) as i32 + 6;
    let h = (NOTE_SIZE / 1.24 * 1.25) as i32;
    let (ox, oy) = place.offset;
    let x0 = match place.h {
        HPos::Left => ox - 3,
        HPos::Center => ox - w / 2,
        HPos::Right => ox - w + 3,
    };
    let y0 = match place.v {
        VPos::Top => oy - 2,
        VPos::Center => oy - h / 2,
        VPos::Bottom => oy - h + 2,
    };
    let style = (FONT, NOTE_SIZE)
        .into_font()
        .color(&ink)
        .pos(Pos::new(place.h, place.v));
    chart
        .draw_series(std::iter::once(
            EmptyElement::at(place.at)
                + Rectangle::new([(x0, y0), (x0 + w, y0 + h)], WHITE.mix(0.8).filled())
                + Text::new(text.to_string(), place.offset, style),
        ))
        .map_err(draw_error)?;
    Ok(())
}

fn draw_notes<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    notes: &[String],
    corner: Corner,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let area = chart.plotting_area().strip_coord_spec();
    let (w, h) = area.dim_in_pixel();
    let line = (NOTE_SIZE * 1.15) as i32;
    let total = line * notes.len() as i32;
    let (x, h_pos) = match corner {
        Corner::UpperLeft | Corner::LowerLeft => (12, HPos::Left),
        Corner::UpperRight | Corner::LowerRight => (w as i32 - 12, HPos::Right),
    };
    let y0 = match corner {
        Corner::UpperLeft | Corner::UpperRight => 10,
        Corner::LowerLeft | Corner::LowerRight => h as i32 - 10 - total,
    };
    // A translucent box keeps the text readable over lines.
    let width = notes
        .iter()
        .map(|n| text_width(n, NOTE_SIZE))
        .fold(0.0, f64::max) as i32
        + 8;
    let bx = match h_pos {
        HPos::Right => x - width + 4,
        _ => x - 4,
    };
    area.draw(&Rectangle::new(
        [(bx, y0 - 4), (bx + width, y0 + total + 2)],
        WHITE.mix(0.85).filled(),
    ))
    .map_err(draw_error)?;
    let style = (FONT, NOTE_SIZE)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(h_pos, VPos::Top));
    for (i, note) in notes.iter().enumerate() {
        area.draw(&Text::new(
            note.as_str(),
            (x, y0 + line * i as i32),
            style.clone(),
        ))
        .map_err(draw_error)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_keeps_inside_and_cuts_at_edges() {
        let r = (0.0, 1.0);
        assert_eq!(
            clip_segment((0.2, 0.2), (0.8, 0.8), r, r),
            Some(((0.2, 0.2), (0.8, 0.8)))
        );
        let (a, b) = clip_segment((-1.0, 0.5), (2.0, 0.5), r, r).unwrap();
        assert_eq!((a, b), ((0.0, 0.5), (1.0, 0.5)));
        assert_eq!(clip_segment((2.0, 2.0), (3.0, 3.0), r, r), None);
    }

    #[test]
    fn runs_join_across_inexact_arithmetic() {
        // 0.1 + (0.45 - 0.1) != 0.45 in floating point; the run must not break there.
        assert_ne!(0.1 + (0.45 - 0.1), 0.45);
        let pts = [(0.1, 0.1), (0.45, 0.3), (0.9, 0.2)];
        assert_eq!(visible_runs(&pts, (0.0, 1.0), (0.0, 1.0)).len(), 1);
    }

    #[test]
    fn runs_break_at_gaps_and_outside() {
        let pts = [
            (0.0, 0.0),
            (0.5, 0.5),
            (f64::NAN, 0.0),
            (0.6, 0.6),
            (0.7, 0.7),
            (0.8, 5.0),
            (0.9, 0.1),
        ];
        let runs = visible_runs(&pts, (0.0, 1.0), (0.0, 1.0));
        assert_eq!(runs.len(), 3, "{runs:?}");
        assert_eq!(runs[0], vec![(0.0, 0.0), (0.5, 0.5)]);
        assert_eq!(runs[1].first(), Some(&(0.6, 0.6)));
        assert!((runs[1].last().unwrap().1 - 1.0).abs() < 1e-12);
        assert!((runs[2][0].1 - 1.0).abs() < 1e-12);
        assert_eq!(runs[2].last(), Some(&(0.9, 0.1)));
    }

    #[test]
    fn ranges_pad_data_and_handle_flat_or_empty() {
        assert_eq!(fit_range([].into_iter(), 0.05), (0.0, 1.0));
        let (lo, hi) = fit_range([2.0, 2.0].into_iter(), 0.05);
        assert!(lo < 2.0 && hi > 2.0);
        let (lo, hi) = fit_range([0.0, 10.0, f64::NAN].into_iter(), 0.05);
        assert_eq!((lo, hi), (-0.5, 10.5));
    }

    #[test]
    fn tick_labels_are_short() {
        // Steps 20, 0.2, 0.05 for eight ticks: as many decimals as the step needs.
        assert_eq!(tick_step(0.0, 100.0, 8), 20.0);
        assert_eq!(format_tick(40.0, tick_decimals(0.0, 100.0, 8)), "40");
        assert_eq!(format_tick(0.4, tick_decimals(0.0, 1.0, 8)), "0.4");
        assert_eq!(format_tick(0.15, tick_decimals(0.0, 0.3, 8)), "0.15");
        assert_eq!(format_tick(-0.0001, tick_decimals(0.0, 1.0, 8)), "0.0");
        assert_eq!(format_tick(2.5e-6, tick_decimals(0.0, 1e-5, 8)), "2.50e-6");
        assert_eq!(format_tick(2.0e5, tick_decimals(0.0, 3e5, 8)), "2.00e5");
    }
}
