//! Drawing: [`render`] is a pure function of [`AppState`] into a frame. One file per pane.

pub mod campbell;
pub mod help;
pub mod locus;
pub mod modes;
pub mod params;
pub mod response;
pub mod shape;
pub mod status;
pub mod theme;

use crate::explorer::display::MarkerKind;
use crate::explorer::state::{AppState, ViewMode};
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::{Block, Borders, Paragraph, Wrap};
use ratatui::Frame;
pub use theme::Theme;

/// The smallest window the layout is designed for.
pub const MIN_COLS: u16 = 80;
pub const MIN_ROWS: u16 = 24;

/// Draw the whole screen.
pub fn render(state: &AppState, frame: &mut Frame) {
    let area = frame.area();
    let theme = Theme::new(state.opts.color);
    if area.width < MIN_COLS || area.height < MIN_ROWS {
        let text = vec![
            Line::styled("window too small", theme.title()),
            Line::from(format!(
                "{}×{}: the explorer needs at least {MIN_COLS}×{MIN_ROWS}",
                area.width, area.height
            )),
            Line::from("enlarge the window, or press q to quit"),
        ];
        frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), area);
        return;
    }
    let [body, status_area] = Layout::vertical([
        Constraint::Min(0),
        Constraint::Length(status::height(state, area.width, area.height)),
    ])
    .areas(area);
    let left_w = (area.width * 3 / 10).clamp(34, 44);
    let [left, right] =
        Layout::horizontal([Constraint::Length(left_w), Constraint::Min(0)]).areas(body);
    let [params_area, modes_area] = Layout::vertical([
        Constraint::Length(params::height(&state.preset, left.height)),
        Constraint::Min(0),
    ])
    .areas(left);
    params::render(state, &theme, frame, params_area);
    modes::render(state, &theme, frame, modes_area);
    match state.view {
        ViewMode::Main | ViewMode::Shape => {
            // The shape pane gets half: it needs rows for its legend and its three curves.
            let locus_share = if state.view == ViewMode::Shape {
                50
            } else {
                55
            };
            let [locus_area, lower_area] = Layout::vertical([
                Constraint::Percentage(locus_share),
                Constraint::Percentage(100 - locus_share),
            ])
            .areas(right);
            locus::render(state, &theme, frame, locus_area);
            if state.view == ViewMode::Shape {
                shape::render(state, &theme, frame, lower_area);
            } else {
                response::render(state, &theme, frame, lower_area);
            }
        }
        ViewMode::Campbell => campbell::render(state, &theme, frame, right),
    }
    status::render(state, &theme, frame, status_area);
    if state.help {
        help::render(&theme, frame, area);
    }
}

/// A bordered pane with a title.
pub fn pane<'a>(title: impl Into<Line<'a>>, theme: &Theme) -> Block<'a> {
    Block::default()
        .borders(Borders::ALL)
        .border_style(theme.border())
        .title(title.into().style(theme.title()))
}

/// The ratatui marker for a `--marker` choice.
pub fn marker(kind: MarkerKind) -> Marker {
    match kind {
        MarkerKind::Braille => Marker::Braille,
        MarkerKind::Halfblock => Marker::HalfBlock,
        MarkerKind::Block => Marker::Block,
        MarkerKind::Dot => Marker::Dot,
    }
}

/// `v` with `digits` significant digits: fixed notation for ordinary magnitudes, else exponent.
pub fn sig(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let mut mag = v.abs().log10().floor() as i32;
    // A value that rounds up into the next decade (0.99996 to 2 digits) takes that decade's
    // decimals, so round-off about 1 never shows as `1.00` against `1.0`.
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    if format!("{:.decimals$}", v.abs())
        .parse::<f64>()
        .is_ok_and(|r| r >= 10f64.powi(mag + 1))
    {
        mag += 1;
    }
    if (-3..5).contains(&mag) {
        let decimals = (digits as i32 - 1 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{:.*e}", digits.saturating_sub(1), v)
    }
}

/// A short pole label: `flap 2` → `F2`, `torsion 1` → `T1`; a rotor's `BW edge 1` → `BE1`,
/// `collective flap 2` → `CF2`, a tower's `tower SS 1` → `SS1`.
pub fn short_label(label: &str) -> String {
    let words: Vec<&str> = label.split_whitespace().collect();
    let initial = |w: &str| {
        w.chars()
            .next()
            .map(|c| c.to_ascii_uppercase())
            .unwrap_or('?')
    };
    let number = words
        .last()
        .filter(|w| w.chars().all(|c| c.is_ascii_digit()))
        .copied()
        .unwrap_or("");
    match words.as_slice() {
        ["tower", plane, ..] => format!("{plane}{number}"),
        [whirl @ ("BW" | "FW" | "collective"), family, ..] => {
            format!("{}{}{number}", initial(whirl), initial(family))
        }
        [first, ..] => format!("{}{number}", initial(first)),
        [] => "?".to_string(),
    }
}

/// Centre a `w × h` rectangle in `area` (clipped to it).
pub fn centered(area: Rect, w: u16, h: u16) -> Rect {
    let w = w.min(area.width);
    let h = h.min(area.height);
    Rect::new(
        area.x + (area.width - w) / 2,
        area.y + (area.height - h) / 2,
        w,
        h,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sig_formats_across_magnitudes() {
        assert_eq!(sig(0.905_09, 4), "0.9051");
        assert_eq!(sig(-0.159_19, 3), "-0.159");
        assert_eq!(sig(123.456, 4), "123.5");
        assert_eq!(sig(2.3e-6, 3), "2.30e-6");
        assert_eq!(sig(1.5e7, 2), "1.5e7");
        assert_eq!(sig(0.0, 3), "0");
        // Round-off on either side of a decade prints the same.
        assert_eq!(sig(0.999_999_999_9, 2), "1.0");
        assert_eq!(sig(1.000_000_000_1, 2), "1.0");
        assert_eq!(sig(-9.9996, 4), "-10.00");
        assert_eq!(sig(99_999.7, 3), "1.00e5");
    }

    #[test]
    fn short_labels() {
        assert_eq!(short_label("flap 2"), "F2");
        assert_eq!(short_label("torsion 1"), "T1");
        assert_eq!(short_label("aero lag 3"), "A3");
        assert_eq!(short_label("BW edge 1"), "BE1");
        assert_eq!(short_label("collective flap 2"), "CF2");
        assert_eq!(short_label("tower SS 1"), "SS1");
        assert_eq!(short_label("drivetrain 1"), "D1");
        assert_eq!(short_label("rotor rotation"), "R");
    }
}
