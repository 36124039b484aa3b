//! The same [`Panel`]s drawn as terminal text: a ratatui `Chart` with braille markers rendered
//! into an off-screen `Buffer` (no terminal needed), printed line by line. Used by the commands
//! that show a figure in the terminal (`reproduce fig2..fig5`).

use super::figure::{Mark, Panel, Rgb, GUIDE_GREY, PALETTE};
use super::layout::{
    clip_segment, format_tick, guide_ends, inside, panel_ranges, series_colors, tick_decimals,
    tick_step, visible_runs, Corner, Occupancy,
};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker as Symbol;
use ratatui::text::Line;
use ratatui::widgets::{Axis, Chart, Dataset, GraphType, LegendPosition, Widget};

/// Smallest panel drawn: below this the axes and legend leave no room for data.
pub const MIN_SIZE: (u16, u16) = (30, 8);

/// One ratatui dataset's owned data: points, colour, kind and legend name.
type Layer = (Vec<(f64, f64)>, Color, GraphType, Option<String>);

/// `(lo, hi)` rounded outward to multiples of a 1-2-5 step giving about four intervals.
fn nice_bounds((lo, hi): (f64, f64)) -> (f64, f64) {
    let step = tick_step(lo, hi, 5);
    let (a, b) = ((lo / step).floor() * step, (hi / step).ceil() * step);
    if a.is_finite() && b.is_finite() && a < b {
        (a, b)
    } else {
        (lo, hi)
    }
}

/// Decimals that print the two bounds and the middle exactly (`None`: scientific notation).
fn label_decimals((lo, hi): (f64, f64)) -> Option<usize> {
    tick_decimals(lo, hi, 5)?;
    let tol = 1e-9 * (hi - lo);
    (0..=9).find(|&d| {
        let scale = 10f64.powi(d as i32);
        [lo, 0.5 * (lo + hi), hi]
            .iter()
            .all(|v| ((v * scale).round() / scale - v).abs() <= tol)
    })
}

/// The 16-colour terminal colour closest in role to a palette colour (safe on any terminal).
fn ansi(c: Rgb) -> Color {
    let idx = PALETTE.iter().position(|&p| p == c);
    match idx.map(|i| i % 12) {
        Some(0) => Color::Blue,
        Some(1) => Color::Red,
        Some(2) => Color::Green,
        Some(3) => Color::Magenta,
        Some(4) => Color::Yellow,
        Some(5) => Color::Cyan,
        Some(6) => Color::White,
        Some(7) => Color::LightRed,
        Some(8) => Color::Gray,
        Some(9) => Color::LightGreen,
        Some(10) => Color::LightMagenta,
        Some(11) => Color::LightCyan,
        _ => Color::Rgb(c.0, c.1, c.2),
    }
}

fn sgr(c: Color) -> Option<&'static str> {
    Some(match c {
        Color::Black => "30",
        Color::Red => "31",
        Color::Green => "32",
        Color::Yellow => "33",
        Color::Blue => "34",
        Color::Magenta => "35",
        Color::Cyan => "36",
        Color::Gray => "37",
        Color::DarkGray => "90",
        Color::LightRed => "91",
        Color::LightGreen => "92",
        Color::LightYellow => "93",
        Color::LightBlue => "94",
        Color::LightMagenta => "95",
        Color::LightCyan => "96",
        Color::White => "97",
        _ => return None,
    })
}

/// `panel` as `height` lines of at most `width` characters: title line, braille plot with
/// axes, tick labels at both ends and the middle, axis titles, and a legend where it fits.
/// With `color`, series are told apart by 16-colour ANSI escapes; without, the text is plain.
pub fn render(panel: &Panel, width: u16, height: u16, color: bool) -> String {
    let (width, height) = (width.max(MIN_SIZE.0), height.max(MIN_SIZE.1));
    // Ratatui spreads the labels evenly over the axis: round the bounds of the data (unpadded,
    // so a time axis starts at 0) out to a tick step so the end labels are round numbers.
    let (xr, yr) = panel_ranges(panel, 0.0);
    let (xr, yr) = (nice_bounds(xr), nice_bounds(yr));
    let (xd, yd) = (label_decimals(xr), label_decimals(yr));

    // Own the visible runs: ratatui datasets borrow their points.
    let mut owned: Vec<Layer> = Vec::new();
    for g in &panel.guides {
        let (a, b) = guide_ends(g.kind, xr, yr);
        if let Some((a, b)) = clip_segment(a, b, xr, yr) {
            let c = ansi(g.color.unwrap_or(GUIDE_GREY));
            let c = if c == Color::Rgb(90, 90, 90) {
                Color::DarkGray
            } else {
                c
            };
            let name = (!g.label.is_empty()).then(|| format!("┄ {}", g.label));
            owned.push((vec![a, b], c, GraphType::Line, name));
        }
    }
    for (s, rgb) in panel.series.iter().zip(series_colors(panel)) {
        let c = ansi(rgb);
        let mut name = (panel.legend && !s.name.is_empty()).then(|| s.name.clone());
        if matches!(s.style.mark, Mark::Line | Mark::LinePoints) {
            for run in visible_runs(&s.points, xr, yr) {
                owned.push((run, c, GraphType::Line, name.take()));
            }
        }
        if matches!(s.style.mark, Mark::Points | Mark::LinePoints) || name.is_some() {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|&p| inside(p, xr, yr))
                .collect();
            owned.push((pts, c, GraphType::Scatter, name.take()));
        }
    }
    for m in &panel.markers {
        if m.x.is_finite() && m.y.is_finite() {
            let name = (!m.label.is_empty()).then(|| format!("● {}", m.label));
            owned.push((vec![(m.x, m.y)], Color::White, GraphType::Scatter, name));
        }
    }

    let datasets: Vec<Dataset> = owned
        .iter()
        .map(|(pts, c, kind, name)| {
            let marker = if *kind == GraphType::Scatter && pts.len() == 1 {
                Symbol::Dot
            } else {
                Symbol::Braille
            };
            let d = Dataset::default()
                .data(pts)
                .marker(marker)
                .graph_type(*kind)
                .style(Style::default().fg(*c));
            match name {
                Some(n) => d.name(n.clone()),
                None => d,
            }
        })
        .collect();

    let x_labels = [xr.0, 0.5 * (xr.0 + xr.1), xr.1].map(|v| format_tick(v, xd));
    let y_labels = [yr.0, 0.5 * (yr.0 + yr.1), yr.1].map(|v| format_tick(v, yd));
    let legend_rows = owned.iter().filter(|o| o.3.is_some()).count() as f64;
    let legend_cols = owned
        .iter()
        .filter_map(|o| o.3.as_ref().map(|n| n.chars().count()))
        .max()
        .unwrap_or(0) as f64
        + 2.0;
    // Corner choice in pixel-like units (a cell is about 8 × 16 px), as for the image legend.
    let (cw, ch) = (8.0, 16.0);
    let occupancy = Occupancy::new(
        panel,
        xr,
        yr,
        (u32::from(width) * 8, u32::from(height) * 16),
    );
    // Ratatui writes the x-axis title in the bottom-right corner.
    let x_title = (panel.x_label.chars().count() as f64 * cw, ch);
    let taken = [occupancy.rect(Corner::LowerRight, x_title)];
    let legend_size = (legend_cols * cw, (legend_rows + 2.0) * ch);
    let legend_position = match occupancy.best_corner(legend_size, &taken) {
        Corner::UpperRight => LegendPosition::TopRight,
        Corner::UpperLeft => LegendPosition::TopLeft,
        Corner::LowerRight => LegendPosition::BottomRight,
        Corner::LowerLeft => LegendPosition::BottomLeft,
    };
    let chart = Chart::new(datasets)
        .x_axis(
            Axis::default()
                .title(panel.x_label.as_str())
                .bounds([xr.0, xr.1])
                .labels(x_labels.map(Line::from)),
        )
        .y_axis(
            // The y title goes on its own line above the chart: ratatui would draw it over the
            // top row of the data.
            Axis::default()
                .bounds([yr.0, yr.1])
                .labels(y_labels.map(Line::from)),
        )
        .legend_position(Some(legend_position))
        .hidden_legend_constraints((Constraint::Percentage(60), Constraint::Percentage(70)));

    let title_rows = u16::from(!panel.title.is_empty()) + 1;
    let area = Rect::new(0, 0, width, height - title_rows);
    let mut buf = Buffer::empty(area);
    chart.render(area, &mut buf);

    let mut out = String::new();
    if !panel.title.is_empty() {
        out.push_str(&panel.title);
        out.push('\n');
    }
    out.push_str(&panel.y_label);
    out.push('\n');
    for y in 0..area.height {
        let mut line = String::new();
        let mut current: Option<&'static str> = None;
        for x in 0..area.width {
            let cell = &buf[(x, y)];
            if color {
                let want = sgr(cell.fg);
                if want != current {
                    // Reset first so a colour never leaks into the next cell.
                    if current.is_some() {
                        line.push_str("\x1b[0m");
                    }
                    if let Some(code) = want {
                        line.push_str("\x1b[");
                        line.push_str(code);
                        line.push('m');
                    }
                    current = want;
                }
            }
            line.push_str(cell.symbol());
        }
        if current.is_some() {
            line.push_str("\x1b[0m");
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{Guide, Series};

    pub(super) fn panel() -> Panel {
        Panel::new("ply angle (deg)", "Re λ (1/s)")
            .titled("(a) classical")
            .with_series(Series::line_points(
                "1st",
                vec![(15.0, -1.0), (30.0, -0.5), (45.0, -0.2), (60.0, -0.6)],
            ))
            .with_series(Series::line(
                "2nd",
                vec![(15.0, -2.0), (30.0, -1.5), (45.0, -1.2), (60.0, -1.6)],
            ))
            .with_guide(Guide::horizontal(0.0, "σ = 0"))
    }

    #[test]
    fn plain_text_has_title_axes_braille_and_legend() {
        let text = render(&panel(), 72, 18, false);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 18);
        assert_eq!(lines[0], "(a) classical");
        assert_eq!(lines[1], "Re λ (1/s)");
        assert!(lines.iter().all(|l| l.chars().count() <= 72));
        assert!(!text.contains('\x1b'));
        let braille = text
            .chars()
            .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
            .count();
        assert!(braille > 40, "{braille} braille cells\n{text}");
        for want in ["1st", "2nd", "┄ σ = 0", "ply angle (deg)"] {
            assert!(text.contains(want), "no '{want}' in\n{text}");
        }
        // Axis bounds are the data's (no padding) rounded out to a tick step: x 15..60 → 10..60
        // with 35 in the middle, y −2..−0.2 (and the σ = 0 guide) → −2..0.
        let x_labels: Vec<&str> = lines[17].split_whitespace().collect();
        assert_eq!(x_labels, ["10", "35", "60"], "\n{text}");
        assert!(
            lines[2].starts_with("0 │") && text.contains("\n-2│"),
            "\n{text}"
        );
    }

    #[test]
    fn colour_text_uses_ansi_and_resets() {
        let text = render(&panel(), 72, 18, true);
        assert!(text.contains("\x1b[34m"), "{text:?}");
        assert!(text.contains("\x1b[31m"), "{text:?}");
        // Every line that sets a colour resets it before it ends.
        for line in text.lines().filter(|l| l.contains('\x1b')) {
            let last = line.rfind('\x1b').unwrap();
            assert!(line[last..].starts_with("\x1b[0m"), "{line:?}");
        }
    }
}
