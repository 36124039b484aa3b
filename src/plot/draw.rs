//! The plotters backend: draws a [`Figure`] on any plotters drawing area (the SVG string and the
//! in-memory bitmap behind `output`), panel by panel, where `layout` says things go.

use super::figure::{Dash, Figure, Guide, GuideKind, Mark, Panel, Rgb, GUIDE_GREY};
use super::layout::{
    clip_segment, far_end, format_tick, guide_ends, inside, legend_line_height, legend_size,
    notes_width, text_width, visible_runs, Corner, LegendEntry, Occupancy, PanelLayout,
    AXIS_DESC_SIZE, CAPTION_SIZE, FONT, LEGEND_PAD, LEGEND_SIZE, LEGEND_SWATCH, NOTE_SIZE,
    TICK_SIZE, TITLE_SIZE, X_TICKS, Y_TICKS,
};
use crate::error::{Error, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

fn draw_error<E: std::error::Error + Send + Sync>(e: DrawingAreaErrorKind<E>) -> Error {
    Error::Io(format!("cannot draw plot: {e}"))
}

fn color(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// Draw `fig` on `root` and present it (the fonts must be registered: text is measured).
pub(super) fn draw_figure<DB: DrawingBackend>(
    fig: &Figure,
    root: &DrawingArea<DB, Shift>,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
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
    root.present().map_err(draw_error)
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

    for (series, &rgb) in panel.series.iter().zip(colors) {
        let c = color(rgb);
        let line_style = c.stroke_width(series.style.width.max(1));
        let mark = series.style.mark;
        if matches!(mark, Mark::Line | Mark::LinePoints) {
            for run in visible_runs(&series.points, xr, yr) {
                match dash_pattern(series.style.dash) {
                    None => chart.draw_series(std::iter::once(PathElement::new(run, line_style))),
                    Some((on, off)) => {
                        chart.draw_series(DashedLineSeries::new(run, on, off, line_style))
                    }
                }
                .map_err(draw_error)?;
            }
        }
        if matches!(mark, Mark::Points | Mark::LinePoints) {
            let radius = if mark == Mark::Points { 5 } else { 4 };
            let pts = series.points.iter().copied().filter(|&p| inside(p, xr, yr));
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
        let size = (
            notes_width(&panel.notes) + 12.0,
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

/// Draw a guide's line, thin, solid and grey (dashes and dots tell a rotor's whirls apart);
/// return where its label goes (drawn later, over the data).
fn draw_guide_line<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    guide: &Guide,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<Option<LabelPlacement>>
where
    DB::ErrorType: 'static,
{
    let (a, b) = guide_ends(guide.kind, xr, yr);
    if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
        return Ok(None);
    }
    let Some((a, b)) = clip_segment(a, b, xr, yr) else {
        return Ok(None);
    };
    let c = color(guide.color.unwrap_or(GUIDE_GREY));
    chart
        .draw_series(LineSeries::new([a, b], c.stroke_width(1)))
        .map_err(draw_error)?;
    if guide.label.is_empty() {
        return Ok(None);
    }
    // Label at the end of the line that lies furthest right/up, nudged inside the plot.
    let end = far_end(a, b);
    let (h, v, offset) = match guide.kind {
        GuideKind::Vertical(_) => (HPos::Left, VPos::Top, (6, 6)),
        GuideKind::Horizontal(_) => (HPos::Right, VPos::Bottom, (-6, -4)),
        GuideKind::Segment { .. } => {
            // Leaving through the right edge: label above-left of the end; through the top
            // (or bottom): label beside the end, inside the plot; ending inside: right of the
            // end, centred on the line's height (a label above it sits nearer the next line up
            // when harmonics run close, as 1P, 3P and 6P of a slow rotor do).
            let at_right = (end.0 - xr.0) / (xr.1 - xr.0) > 0.98;
            let at_top = (end.1 - yr.0) / (yr.1 - yr.0) > 0.98;
            match (at_right, at_top) {
                (true, _) => (HPos::Right, VPos::Bottom, (-6, -4)),
                (false, true) => (HPos::Right, VPos::Top, (-8, 4)),
                (false, false) => (HPos::Left, VPos::Center, (6, 0)),
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

/// Write the notes, one per line, in `corner` of the plot on a translucent box.
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
    let width = notes_width(notes) as i32 + 8;
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
            let swatch = LEGEND_SWATCH as i32;
            let (on, off) = dash_pattern(e.dash).unwrap_or((swatch, 0));
            let mut x = sx;
            while x < sx + swatch {
                let end = (x + on).min(sx + swatch);
                target
                    .draw(&Rectangle::new(
                        [(x, cy - 2), (end, cy + 2)],
                        color(e.color).filled(),
                    ))
                    .map_err(draw_error)?;
                x = end + off.max(1);
            }
        } else {
            target
                .draw(&Circle::new(
                    (sx + LEGEND_SWATCH as i32 / 2, cy),
                    5,
                    color(e.color).filled(),
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

/// A stroke's dash and gap lengths (pixels), none for a solid line.
fn dash_pattern(dash: Dash) -> Option<(i32, i32)> {
    match dash {
        Dash::Solid => None,
        Dash::Dashed => Some((10, 6)),
        Dash::Dotted => Some((3, 5)),
    }
}
