//! Layout: pure geometry for drawing a [`Panel`] — axis ranges and ticks, clipping lines to the
//! plot, where a legend or notes fit, and text sizes. Nothing here draws; the plotters backend
//! (`draw`) and the terminal renderer (`text`) both place things by these rules.

use super::figure::{Dash, GuideKind, Mark, Panel, Rgb, PALETTE};
use plotters::style::IntoFont;

/// Typography, in plotters' font size (1.24 × the em): the layout measures text at these sizes
/// and the backend writes it at them.
pub(super) const FONT: &str = "sans-serif";
pub(super) const TITLE_SIZE: f64 = 34.0;
pub(super) const CAPTION_SIZE: f64 = 26.0;
pub(super) const AXIS_DESC_SIZE: f64 = 23.0;
pub(super) const TICK_SIZE: f64 = 20.0;
pub(super) const LEGEND_SIZE: f64 = 19.0;
pub(super) const NOTE_SIZE: f64 = 19.0;

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
pub(super) fn panel_ranges(panel: &Panel, pad: f64) -> ((f64, f64), (f64, f64)) {
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
pub(super) fn clip_segment(
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

/// The segment a guide runs along before clipping: a vertical or horizontal one spans the range.
pub(super) fn guide_ends(
    kind: GuideKind,
    xr: (f64, f64),
    yr: (f64, f64),
) -> ((f64, f64), (f64, f64)) {
    match kind {
        GuideKind::Vertical(x) => ((x, yr.0), (x, yr.1)),
        GuideKind::Horizontal(y) => ((xr.0, y), (xr.1, y)),
        GuideKind::Segment { from, to } => (from, to),
    }
}

/// The end of a guide that its label goes at: the one furthest right, then up.
pub(super) fn far_end(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    if (b.0, b.1) >= (a.0, a.1) {
        b
    } else {
        a
    }
}

/// Whether a point lies in the box (edges included): only those are drawn as dots.
pub(super) fn inside((x, y): (f64, f64), xr: (f64, f64), yr: (f64, f64)) -> bool {
    x >= xr.0 && x <= xr.1 && y >= yr.0 && y <= yr.1
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
pub(super) const X_TICKS: usize = 8;
pub(super) const Y_TICKS: usize = 7;

/// The tick step plotters picks for a range: the smallest of 1, 2, 5 × 10^k giving at most
/// `max_points` ticks (the rule of plotters' `compute_f64_key_points`).
pub(super) fn tick_step(lo: f64, hi: f64, max_points: usize) -> f64 {
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
pub(super) fn tick_decimals(lo: f64, hi: f64, max_points: usize) -> Option<usize> {
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

/// A tick label with `decimals` places (`None`: scientific notation); never "-0".
pub(super) fn format_tick(v: f64, decimals: Option<usize>) -> String {
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

/// A corner of the plot, where a legend or notes box goes.
#[derive(Clone, Copy)]
pub(super) enum Corner {
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
pub(super) struct Occupancy {
    /// Samples in pixel coordinates of the plotting area (y down).
    data: Vec<(f64, f64)>,
    /// Label anchors in pixel coordinates; they weigh more than a data sample.
    labels: Vec<(f64, f64)>,
    size: (f64, f64),
}

impl Occupancy {
    pub(super) fn new(panel: &Panel, xr: (f64, f64), yr: (f64, f64), size: (u32, u32)) -> Self {
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
                        data.extend(samples(px(pair[0]), px(pair[1]), false));
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
            let (a, b) = guide_ends(g.kind, xr, yr);
            if let Some((a, b)) = clip_segment(a, b, xr, yr) {
                data.extend(samples(px(a), px(b), true));
            }
            let at = match g.kind {
                GuideKind::Vertical(x) => Some((x, yr.1)),
                GuideKind::Horizontal(y) => Some((xr.1, y)),
                GuideKind::Segment { from, to } => {
                    clip_segment(from, to, xr, yr).map(|(a, b)| far_end(a, b))
                }
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
    pub(super) fn rect(&self, corner: Corner, size: (f64, f64)) -> (f64, f64, f64, f64) {
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
    pub(super) fn best_corner(&self, size: (f64, f64), taken: &[(f64, f64, f64, f64)]) -> Corner {
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

/// Points every ~4 px (at most 400) along a→b in pixel coordinates, from `a`; `b` as well if
/// `with_end`.
fn samples(a: (f64, f64), b: (f64, f64), with_end: bool) -> impl Iterator<Item = (f64, f64)> {
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let n = (len / 4.0).ceil().clamp(1.0, 400.0) as usize;
    (0..n + usize::from(with_end)).map(move |k| {
        let t = k as f64 / n as f64;
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    })
}

/// Approximate pixel width of `text` at `size` (DejaVu Sans averages ~0.55 em per character;
/// plotters' font size is 1.24 × the em).
pub(super) fn text_width(text: &str, size: f64) -> f64 {
    // Measured with the registered font; the estimate is the fallback before registration.
    match (FONT, size).into_font().box_size(text) {
        Ok((w, _)) => f64::from(w),
        Err(_) => text.chars().count() as f64 * 0.6 * size / 1.24,
    }
}

/// Width of the widest note line at the notes' size.
pub(super) fn notes_width(notes: &[String]) -> f64 {
    notes
        .iter()
        .map(|n| text_width(n, NOTE_SIZE))
        .fold(0.0, f64::max)
}

/// One legend row.
pub(super) struct LegendEntry {
    pub(super) name: String,
    pub(super) color: Rgb,
    pub(super) mark: Mark,
    pub(super) dash: Dash,
}

pub(super) const LEGEND_PAD: f64 = 8.0;
pub(super) const LEGEND_SWATCH: f64 = 30.0;

pub(super) fn legend_line_height() -> f64 {
    (LEGEND_SIZE / 1.24 * 1.35).round()
}

/// Width and height of a legend box for `entries` (at most `rows` rows).
pub(super) fn legend_size(entries: &[LegendEntry], rows: usize) -> (f64, f64) {
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

/// Each series' colour: its own, or the next palette colour for those without one.
pub(super) fn series_colors(panel: &Panel) -> Vec<Rgb> {
    let mut palette = PALETTE.iter().cycle();
    panel
        .series
        .iter()
        .map(|s| {
            s.style
                .color
                .unwrap_or_else(|| *palette.next().unwrap_or(&PALETTE[0]))
        })
        .collect()
}

/// What a panel needs before it is drawn: ranges, tick formats, colours, legend entries, and
/// whether its legend needs a column right of the plot (its width).
pub(super) struct PanelLayout {
    pub(super) xr: (f64, f64),
    pub(super) yr: (f64, f64),
    pub(super) xd: Option<usize>,
    pub(super) yd: Option<usize>,
    /// Width of the y tick labels' area, in pixels.
    pub(super) y_area: u32,
    pub(super) colors: Vec<Rgb>,
    pub(super) entries: Vec<LegendEntry>,
    pub(super) legend_column: Option<f64>,
}

impl PanelLayout {
    pub(super) fn new(panel: &Panel, (aw, ah): (u32, u32)) -> Self {
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

        let colors = series_colors(panel);
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
                    dash: s.style.dash,
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
