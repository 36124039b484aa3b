//! The modes table: each structural mode's name (in its family's colour), frequency with the
//! in-vacuo frequency of the mode it is named after beside it (so a root far shifted by the air
//! still reads naturally), damping ratio, and the trend (↑ ↓) since the last parameter change.
//! An overdamped mode shows no frequency. The least-damped mode is highlighted.

use super::{pane, sig, Theme};
use crate::analysis::mode::Mode;
use crate::explorer::state::AppState;
use ratatui::layout::{Constraint, Rect};
use ratatui::style::Style;
use ratatui::text::Line;
use ratatui::widgets::{Cell, Paragraph, Row, Table};
use ratatui::Frame;

/// Changes smaller than this (relative for frequency, absolute for ζ) show no arrow.
const TREND_TOL: f64 = 1e-6;

/// ↑, ↓ or blank comparing `now` with `before`.
pub fn trend(now: f64, before: Option<f64>, relative: bool) -> &'static str {
    let Some(b) = before else {
        return " ";
    };
    let tol = if relative {
        TREND_TOL * b.abs().max(1e-300)
    } else {
        TREND_TOL
    };
    if now > b + tol {
        "↑"
    } else if now < b - tol {
        "↓"
    } else {
        "·"
    }
}

/// The mode of the same label before the last change.
fn previous<'a>(prev: &'a [Mode], m: &Mode) -> Option<&'a Mode> {
    prev.iter().find(|p| p.label == m.label)
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let Some(solved) = state.solved.as_ref() else {
        let block = pane(" Modes ", theme);
        frame.render_widget(
            Paragraph::new(Line::styled("—", theme.dim())).block(block),
            area,
        );
        return;
    };
    let stab = &solved.stability;
    let title = if stab.aero_lags.is_empty() {
        " Modes ".to_string()
    } else {
        format!(" Modes (+{} aero lags) ", stab.aero_lags.len())
    };
    let block = pane(title, theme);
    let mut modes: Vec<&Mode> = stab.eigenvalues.iter().collect();
    // In the order of the in-vacuo modes they are named after (flap 1, flap 2, torsion 1, … by
    // in-vacuo frequency): a row keeps its place while the air shifts its root, and a root far
    // from its in-vacuo frequency still sits among its family. Unnamed roots last.
    modes.sort_by(|a, b| {
        let f0 = |m: &Mode| m.in_vacuo_hz.unwrap_or(f64::INFINITY);
        f0(a)
            .total_cmp(&f0(b))
            .then(a.frequency_hz.total_cmp(&b.frequency_hz))
    });
    let critical = stab
        .eigenvalues
        .iter()
        .map(|m| m.re)
        .fold(f64::NEG_INFINITY, f64::max);
    // Below this the table squeezes ζ to 5 characters and cuts its left: see `zeta_text`.
    let narrow = area.width < 36;
    // The name column's width: the pane less its borders, the other columns and the spacing.
    let name_width = usize::from(area.width).saturating_sub(2 + 8 + 6 + 8 + 3);
    let rows: Vec<Row> = modes
        .iter()
        .map(|m| {
            let p = previous(&state.prev_modes, m);
            let style = if m.re >= 0.0 {
                theme.flutter()
            } else if m.re == critical {
                theme.title()
            } else {
                Style::new()
            };
            let swatch = match m.family {
                Some(f) if theme.colored() => Style::new().fg(theme.family(f)),
                _ => Style::new(),
            };
            let frequency = if m.overdamped() {
                "—".to_string()
            } else {
                sig(m.frequency_hz, 4)
            };
            let f_trend = trend(m.frequency_hz, p.map(|p| p.frequency_hz), true);
            let z_trend = trend(m.damping_ratio, p.map(|p| p.damping_ratio), false);
            Row::new(vec![
                Cell::from(Line::styled(fitted(&m.label, name_width), swatch)),
                Cell::from(Line::from(format!("{frequency}{f_trend}")).right_aligned()),
                Cell::from(
                    Line::from(m.in_vacuo_hz.map(|f| sig(f, 3)).unwrap_or_default())
                        .right_aligned(),
                ),
                Cell::from(
                    Line::from(format!("{}{z_trend}", zeta_text(m.damping_ratio, narrow)))
                        .right_aligned(),
                ),
            ])
            .style(style)
        })
        .collect();
    let header = Row::new(vec![
        Cell::from("mode"),
        Cell::from(Line::from("f Hz ").right_aligned()),
        Cell::from(Line::from("f₀").right_aligned()),
        Cell::from(Line::from("ζ ").right_aligned()),
    ])
    .style(theme.dim());
    let table = Table::new(
        rows,
        [
            Constraint::Min(9),
            Constraint::Length(8),
            Constraint::Length(6),
            Constraint::Length(8),
        ],
    )
    .header(header)
    .column_spacing(1)
    .block(block);
    frame.render_widget(table, area);
}

/// A rotor's or a turbine's long names shortened to fit `width`, a step at a time
/// (`collective flap 1` → `coll flap 1` → `coll fl 1` → `C fl 1`), and cut before the mode's
/// number rather than through it, so that two modes never read alike; a blade's own names
/// (`torsion 1`) as they are: the table shows them past `width`.
fn fitted(label: &str, width: usize) -> String {
    let fits = |s: &str| s.chars().count() <= width;
    let mut words: Vec<&str> = label.split(' ').collect();
    let rotors = ["collective", "tower", "drivetrain", "rotor", "BW", "FW"];
    if fits(label) || !rotors.contains(&words[0]) {
        return label.to_string();
    }
    for step in SHORTER {
        for w in words.iter_mut() {
            if let Some((_, short)) = step.iter().find(|(long, _)| long == w) {
                *w = short;
            }
        }
        words.retain(|w| !w.is_empty());
        let short = words.join(" ");
        if fits(&short) {
            return short;
        }
    }
    match words.split_last() {
        Some((number, head)) if number.chars().all(|c| c.is_ascii_digit()) => {
            let keep = width.saturating_sub(number.len() + 1);
            format!(
                "{} {number}",
                head.join(" ").chars().take(keep).collect::<String>()
            )
        }
        _ => words.join(" "),
    }
}

/// The words of a rotor's names, shorter at each step, until a name fits its column.
const SHORTER: [&[(&str, &str)]; 3] = [
    &[
        ("collective", "coll"),
        ("tower", "twr"),
        ("drivetrain", "drive"),
        ("rotor", ""),
    ],
    &[("flap", "fl"), ("edge", "ed"), ("torsion", "tor")],
    &[("coll", "C"), ("twr", "T"), ("BW", "B"), ("FW", "F")],
];

/// ζ with 3 significant digits; in a narrow pane, where the column shows 5 characters and
/// cuts from the left (0.0221 reads .0221), a ζ below 0.01 takes 2, so 0.00831 reads .0083
/// rather than 00831.
fn zeta_text(zeta: f64, narrow: bool) -> String {
    let digits = if narrow && zeta.abs() < 0.01 { 2 } else { 3 };
    sig(zeta, digits)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_names_keep_their_number() {
        assert_eq!(fitted("collective flap 1", 11), "coll flap 1");
        assert_eq!(fitted("tower SS 2", 9), "twr SS 2");
        assert_eq!(fitted("collective torsion 2", 10), "coll tor 2");
        assert_eq!(fitted("collective torsion 2", 9), "C tor 2");
        assert_eq!(fitted("collective flap 1", 7), "C fl 1");
        assert_eq!(fitted("collective edge 1", 7), "C ed 1");
        assert_eq!(fitted("BW edge 12", 7), "B ed 12");
        assert_eq!(fitted("tower torsion 1", 8), "T tor 1");
        assert_eq!(fitted("drivetrain 1", 9), "drive 1");
        assert_eq!(fitted("rotor rotation", 9), "rotation");
        assert_eq!(fitted("flap 1", 9), "flap 1");
        assert_eq!(fitted("torsion 1", 7), "torsion 1");
    }

    #[test]
    fn trend_arrows() {
        assert_eq!(trend(2.0, Some(1.0), true), "↑");
        assert_eq!(trend(1.0, Some(2.0), false), "↓");
        assert_eq!(trend(1.0, Some(1.0), true), "·");
        assert_eq!(trend(1.0, None, true), " ");
    }
}
