//! The status line: the verdict (stable / flutter / divergence), the least-damped mode, the
//! margin from the background boundary search along the selected parameter, and on the second
//! row any error from the worker (or a notice, or the main keys).

use super::{sig, Theme};
use crate::analysis::campbell::ROTOR_SPEED_KEY;
use crate::analysis::eigen::{Stability, Verdict};
use crate::analysis::flutter::{Boundary, BoundaryKind, Search};
use crate::analysis::mode::Mode;
use crate::explorer::state::jobs::{BoundaryJob, Side};
use crate::explorer::state::params::{
    shown_decimals, unit, value_text, ParamKind, COUPLING_KEY, PARAMS,
};
use crate::explorer::state::{AppState, ViewMode, SOLVE_BUDGET_S};
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

/// The label of a parameter key, as the parameters pane shows it.
fn param_label(key: &str) -> &'static str {
    PARAMS
        .iter()
        .find_map(|p| match p.kind {
            ParamKind::Number { key: k, .. } if k == key => Some(p.label),
            _ => None,
        })
        .unwrap_or("parameter")
}

/// How much a margin says, longest first: the status line shows the longest that fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Detail {
    /// Each boundary with how far it is and the mode that crosses there.
    Full,
    /// Without the modes.
    Distances,
    /// The values alone.
    Bare,
}

/// The margin with its parameter, in full: "rotor speed: flutter at 11.27 rpm (1.49× rated,
/// torsion 1), none below"; `None` before the first solve.
pub fn margin_text(state: &AppState) -> Option<String> {
    margin_forms(state).into_iter().next()
}

/// The margin in the forms the status line tries, longest first: in full, without the modes,
/// then the values alone.
pub fn margin_forms(state: &AppState) -> Vec<String> {
    let Some(job) = state.boundary.as_ref() else {
        return Vec::new();
    };
    let label = param_label(job.key);
    let mut forms: Vec<String> = match &job.result {
        None if job.sides.is_empty() => vec![format!(
            "nothing to search (the slider's range is {})",
            value(job.key, job.current)
        )],
        None => vec!["searching…".to_string()],
        Some(Err(_)) => vec!["search failed (below)".to_string()],
        Some(Ok(searches)) => [Detail::Full, Detail::Distances, Detail::Bare]
            .map(|d| margin_body(state, job, searches, d))
            .to_vec(),
    };
    forms.dedup();
    forms.into_iter().map(|b| format!("{label}: {b}")).collect()
}

/// A value of `key` as the margin names it: the parameters pane's text, the coupling (a number
/// without unit) as `α -0.11`.
fn value(key: &str, v: f64) -> String {
    if key == COUPLING_KEY {
        format!("α {}", value_text(key, v))
    } else {
        value_text(key, v)
    }
}

/// "flutter", "divergence" or "runaway".
fn kind_word(b: &Boundary) -> &'static str {
    b.kind.map_or("flutter", BoundaryKind::word)
}

/// How far the boundary `c` is from the current value: for the rotor speed of a preset with a
/// rated speed, the multiple of it (`1.49× rated`: an overspeed margin); else [`distance`].
fn how_far(state: &AppState, job: &BoundaryJob, c: f64) -> String {
    let rated = state.preset.operating.rated_rotor_speed;
    if job.key == ROTOR_SPEED_KEY && rated > 0.0 {
        format!("{:.2}× rated", c / rated)
    } else {
        distance(job.key, job.current, c)
    }
}

/// The margin after the parameter's label. From a stable point, the nearest boundary found on
/// each side of it (`none below` when the search down to the slider's end found none); from an
/// unstable one, the unstable stretch it lies in: where it begins, and where it ends if that
/// is before the slider's end.
fn margin_body(state: &AppState, job: &BoundaryJob, searches: &[Search], detail: Detail) -> String {
    let search = |side: Side| {
        job.sides
            .iter()
            .zip(searches)
            .find_map(|(s, x)| (*s == side).then_some(x))
    };
    let (below, above) = (search(Side::Below), search(Side::Above));
    let (down, up) = (crossing(below), crossing(above));
    let key = job.key;
    if job.unstable {
        let Some((begin, _)) = down else {
            let end = up.map_or(job.to, |(c, _)| c);
            return format!(
                "unstable over {} … {}",
                value(key, job.from),
                value(key, end)
            );
        };
        let mut text = format!("unstable from {}", value(key, begin));
        let far = how_far(state, job, begin);
        if detail != Detail::Bare && !far.is_empty() {
            text += &format!(", {far}");
        }
        if let Some((end, _)) = up {
            text += &format!(", to {}", value(key, end));
        }
        return text;
    }
    // One boundary: its value, then how far and which mode as the detail allows.
    let at = |(c, b): (f64, &Boundary)| {
        let mut notes = Vec::new();
        if detail != Detail::Bare {
            notes.push(how_far(state, job, c));
        }
        if detail == Detail::Full {
            notes.extend(b.mode.clone());
        }
        notes.retain(|n| !n.is_empty());
        if notes.is_empty() {
            value(key, c)
        } else {
            format!("{} ({})", value(key, c), notes.join(", "))
        }
    };
    match (down, up) {
        (Some(d), Some(u)) if kind_word(d.1) == kind_word(u.1) => {
            format!("{} at {} and {}", kind_word(d.1), at(d), at(u))
        }
        (Some(d), Some(u)) => format!(
            "{} at {} and {} at {}",
            kind_word(d.1),
            at(d),
            kind_word(u.1),
            at(u)
        ),
        (Some(d), None) => {
            let none = if above.is_some() { ", none above" } else { "" };
            format!("{} at {}{none}", kind_word(d.1), at(d))
        }
        (None, Some(u)) => {
            let none = if below.is_some() { ", none below" } else { "" };
            format!("{} at {}{none}", kind_word(u.1), at(u))
        }
        (None, None) => format!(
            "stable over {} … {}",
            value(key, job.from),
            value(key, job.to)
        ),
    }
}

/// The crossing a side's search found, if any.
fn crossing(s: Option<&Search>) -> Option<(f64, &Boundary)> {
    s.and_then(|s| s.boundary.critical.map(|c| (c, &s.boundary)))
}

/// How far the boundary `c` lies from the current value: relative for a speed (`+45 %`), whose
/// zero is physical; a difference in the key's own unit for an angle (`+18.1 deg`), whose zero is
/// only a convention (a pitch of 0.5° would read +7000 %), and for the coupling α (`-0.22`).
fn distance(key: &str, current: f64, c: f64) -> String {
    if current == 0.0 {
        // From zero the value itself says how far.
        String::new()
    } else if unit(key) == "deg" || key == COUPLING_KEY {
        let d = shown_decimals(key, c);
        let u = if unit(key).is_empty() { "" } else { " deg" };
        format!("{:+.d$}{u}", c - current)
    } else {
        format!("{:+.0} %", 100.0 * (c - current) / current.abs())
    }
}

/// The most important error to show, if any.
pub fn error_text(state: &AppState) -> Option<String> {
    if let Some(e) = &state.solve_error {
        return Some(e.clone());
    }
    if let Some(e) = &state.worker_error {
        return Some(e.clone());
    }
    if let Some(e) = &state.response.error {
        return Some(e.clone());
    }
    if let Some(Some(Err(e))) = state.boundary.as_ref().map(|b| &b.result) {
        return Some(e.clone());
    }
    if state.view == ViewMode::Campbell {
        if let Some(Some(Err(e))) = state.campbell.as_ref().map(|c| &c.result) {
            return Some(e.clone());
        }
    }
    None
}

/// The mode to name beside the verdict: the least-damped structural mode, unless an aerodynamic
/// lag root is the one that is unstable (slow, real lag roots near σ = 0 are not news).
pub fn least_damped(s: &Stability) -> Option<&Mode> {
    let structural = s.eigenvalues.iter().max_by(|a, b| a.re.total_cmp(&b.re));
    match s.critical() {
        Some(c) if c.re >= 0.0 => Some(c),
        _ => structural.or(s.critical()),
    }
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let [top, bottom] = Layout::vertical([Constraint::Length(1), Constraint::Min(1)]).areas(area);
    let width = area.width as usize;
    let (badge, style): (&str, Style) = match (&state.solved, &state.solve_error) {
        (_, Some(_)) => (" ERROR ", theme.error()),
        (None, None) => (" SOLVING… ", theme.dim()),
        (Some(s), None) => match s.stability.verdict {
            Verdict::Stable => (" STABLE ", theme.stable()),
            Verdict::Flutter => (" FLUTTER ", theme.flutter()),
            Verdict::Divergence => (" DIVERGENCE ", theme.divergence()),
            Verdict::Runaway => (" RUNAWAY ", theme.divergence()),
        },
    };
    // Longest first, the first that fits is shown: the mode named with the shares of its motion
    // (as `eigen` and `flutter` report it), then by name alone, then name and ζ only. A
    // non-oscillatory root has no frequency and ζ ≥ 1: its decay rate σ tells how stable it is.
    let least: Vec<String> = match (&state.solved, &state.solve_error) {
        (Some(s), None) => least_damped(&s.stability)
            .map(|m| {
                let forms = [m.described(), m.label.clone()];
                if m.im == 0.0 {
                    let kind = if m.overdamped() {
                        "overdamped"
                    } else {
                        "real root"
                    };
                    let mut v: Vec<String> = forms
                        .iter()
                        .map(|name| {
                            format!(" least damped: {name} ({kind}) σ = {} 1/s", sig(m.re, 3))
                        })
                        .collect();
                    v.push(format!(" {} σ = {} 1/s", m.label, sig(m.re, 2)));
                    v
                } else {
                    let mut v: Vec<String> = forms
                        .iter()
                        .map(|name| {
                            format!(
                                " least damped: {name} {} Hz, ζ = {}",
                                sig(m.frequency_hz, 3),
                                sig(m.damping_ratio, 2)
                            )
                        })
                        .collect();
                    v.push(format!(" {} ζ = {}", m.label, sig(m.damping_ratio, 2)));
                    v
                }
            })
            .unwrap_or_default(),
        _ => Vec::new(),
    };
    let solving = state
        .checking_text()
        .map(|t| format!("  {t}"))
        .or_else(|| (state.solving() && state.solved.is_some()).then(|| solving_text(state)));
    let fixed = badge.chars().count() + solving.as_ref().map_or(0, |t| t.chars().count());
    // The badge and the margin always, the margin in the longest form that fits (its
    // "margin along" dropped before its details); the least-damped mode in the room left.
    let forms: Vec<String> = margin_forms(state)
        .into_iter()
        .flat_map(|m| [format!("margin along {m}"), m])
        .collect();
    let margin = forms
        .iter()
        .find(|m| fixed + 5 + m.chars().count() <= width)
        .or(forms.last())
        .cloned();
    let used = fixed + margin.as_ref().map_or(0, |m| m.chars().count() + 5);
    let mut spans = vec![Span::styled(badge, style.add_modifier(Modifier::REVERSED))];
    if let Some(text) = least
        .into_iter()
        .find(|t| used + t.chars().count() <= width)
    {
        spans.push(Span::raw(text));
    }
    if let Some(margin) = margin {
        spans.push(Span::styled("  │  ", theme.dim()));
        spans.push(Span::styled(margin, theme.accent()));
    }
    if let Some(text) = solving {
        spans.push(Span::styled(text, theme.dim()));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), top);

    let lines: Vec<Line> = if let Some((text, error)) = message(state) {
        let style = if error { theme.error() } else { theme.accent() };
        wrapped(&text, width, bottom.height as usize)
            .into_iter()
            .map(|l| Line::styled(l, style))
            .collect()
    } else {
        let hints = HINTS
            .iter()
            .find(|h| h.chars().count() + if state.paused { 8 } else { 0 } <= width)
            .unwrap_or(&HINTS[HINTS.len() - 1]);
        let mut spans = Vec::new();
        if state.paused {
            spans.push(Span::styled("PAUSED", theme.title()));
            spans.push(Span::raw("  "));
        }
        spans.push(Span::styled(*hints, theme.dim()));
        vec![Line::from(spans)]
    };
    frame.render_widget(Paragraph::new(lines), bottom);
}

/// Rows a message below the verdict may take in a window `rows` high: an error wraps rather
/// than being cut at the window's edge (a numerical failure's account runs to 500 characters,
/// seven rows at 80 columns), but the panes keep two thirds of the screen.
fn message_rows(rows: u16) -> usize {
    usize::from(rows / 3).max(1)
}

/// The error (true) or notice (false) to show below the verdict, if any.
fn message(state: &AppState) -> Option<(String, bool)> {
    error_text(state)
        .map(|e| (format!("error: {e}"), true))
        .or_else(|| state.notice.clone().map(|n| (n, false)))
}

/// Rows the status line takes in a window `width × rows`: the verdict's, and the message's as
/// wrapped (one for the key hints).
pub fn height(state: &AppState, width: u16, rows: u16) -> u16 {
    let below = message(state).map_or(1, |(text, _)| {
        wrapped(&text, width as usize, message_rows(rows)).len()
    });
    1 + below as u16
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word is cut), at
/// most `rows` of them, the last ending in `…` when the text does not fit.
fn wrapped(text: &str, width: usize, rows: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let mut word: Vec<char> = word.chars().collect();
        loop {
            let used = line.chars().count();
            let gap = usize::from(used > 0);
            if used + gap + word.len() <= width {
                if gap == 1 {
                    line.push(' ');
                }
                line.extend(word.iter());
                break;
            }
            if used > 0 {
                lines.push(std::mem::take(&mut line));
                continue;
            }
            // A word wider than the window: cut it.
            let rest = word.split_off(width);
            lines.push(word.iter().collect());
            word = rest;
        }
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    if lines.len() > rows {
        lines.truncate(rows);
        let last = &mut lines[rows - 1];
        let keep: String = last.chars().take(width - 1).collect();
        *last = keep + "…";
    }
    lines
}

/// The solving mark: with its running time once the solve is over its budget (the last result
/// stays on screen, and keys keep working).
fn solving_text(state: &AppState) -> String {
    if state.solve_seconds >= SOLVE_BUDGET_S {
        format!("  solving… {:.1} s", state.solve_seconds)
    } else {
        "  solving…".to_string()
    }
}

/// The key hints, longest first; the first that fits is shown.
const HINTS: [&str; 3] = [
    "←→ adjust  S-←→ coarse  ↑↓ select  a aero  k kick  f boundary  c Campbell  s shape  space pause  ? help  q quit",
    "←→ adjust  ↑↓ select  a aero  k kick  f boundary  c Campbell  s shape  space pause  ? help  q quit",
    "←→ adjust ↑↓ select a aero k kick c Campbell s shape ? help q quit",
];

#[cfg(test)]
mod tests {
    use super::{distance, wrapped};

    #[test]
    fn a_message_wraps_at_spaces_and_says_when_it_is_cut() {
        assert_eq!(wrapped("error: a bb ccc", 8, 4), ["error: a", "bb ccc"]);
        assert_eq!(wrapped("abcdefghij", 4, 4), ["abcd", "efgh", "ij"]);
        assert_eq!(wrapped("a b c d e f", 3, 2), ["a b", "c …"]);
        assert_eq!(wrapped("", 10, 4), [""]);
    }

    #[test]
    fn a_margin_in_angle_is_a_difference_and_in_speed_a_ratio() {
        // A pitch of 0.5° with flutter at 35.5°: 35 degrees away, not "+7000 %".
        assert_eq!(distance("operating.pitch", 0.5, 35.5), "+35.0 deg");
        assert_eq!(distance("section.ply_angle", 45.0, 30.0), "-15.0 deg");
        assert_eq!(distance("operating.wind_speed", 10.0, 15.0), "+50 %");
        // The coupling's zero is the uncoupled blade: no ratio to it either.
        assert_eq!(distance("blade.bend_twist_coupling", -0.1, -0.22), "-0.12");
        // No ratio to a zero speed, and no difference from a zero angle (the value says it).
        assert_eq!(distance("operating.tunnel_speed", 0.0, 137.0), "");
        assert_eq!(distance("operating.pitch", 0.0, 35.5), "");
    }
}
