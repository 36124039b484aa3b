//! The status line: the verdict (stable / flutter / divergence), the least-damped mode, the
//! margin from the background boundary search along the selected parameter, and on the second
//! row any error from the worker (or a notice, or the main keys).

use super::{sig, Theme};
use crate::analysis::eigen::{Mode, Stability, Verdict};
use crate::analysis::flutter::{Boundary, BoundaryKind, Search};
use crate::explorer::state::{
    unit, AppState, BoundaryJob, MarginKind, ParamKind, ViewMode, PARAMS, SOLVE_BUDGET_S,
};
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

fn decimals(key: &str) -> usize {
    PARAMS
        .iter()
        .find_map(|p| match p.kind {
            ParamKind::Number {
                key: k, decimals, ..
            } if k == key => Some(decimals),
            _ => None,
        })
        .unwrap_or(2)
}

/// "flutter at 87 rpm, +45 %" and the like; `None` before the first solve.
pub fn margin_text(state: &AppState) -> Option<String> {
    let job = state.boundary.as_ref()?;
    let label = param_label(job.key);
    let body = match &job.result {
        None if job.empty_range => format!(
            "at the end of its range ({})",
            with_unit(job.key, job.current)
        ),
        None => "searching…".to_string(),
        Some(Err(_)) => "search failed (below)".to_string(),
        Some(Ok(searches)) => match job.kind {
            MarginKind::Onward => {
                let search = searches.first()?;
                match onward(state, job, &search.boundary) {
                    Onward::Whole(text) => return Some(text),
                    Onward::Body(text) => text,
                }
            }
            MarginKind::Schedule => along_schedule(job, searches),
            MarginKind::BothWays => both_ways(job, searches),
        },
    };
    Some(format!("{label}: {body}"))
}

/// `v` in `key`'s unit with the parameters pane's decimals.
fn with_unit(key: &str, v: f64) -> String {
    let (u, d) = (unit(key), decimals(key));
    if u.is_empty() {
        format!("{v:.d$}")
    } else {
        format!("{v:.d$} {u}")
    }
}

/// "flutter" or "divergence".
fn kind_word(b: &Boundary) -> &'static str {
    match b.kind {
        Some(BoundaryKind::Divergence) => "divergence",
        _ => "flutter",
    }
}

/// " (flap 1)" after a crossing, if the mode is named.
fn mode_note(b: &Boundary) -> String {
    b.mode
        .as_ref()
        .map(|m| format!(" ({m})"))
        .unwrap_or_default()
}

enum Onward {
    /// The whole margin, label included.
    Whole(String),
    /// The part after the label.
    Body(String),
}

/// The margin from the current value toward the stable end (or from below, when unstable).
fn onward(state: &AppState, job: &BoundaryJob, b: &Boundary) -> Onward {
    let label = param_label(job.key);
    let Some(c) = b.critical else {
        return Onward::Body(if job.unstable {
            format!(
                "unstable over {} … {}",
                with_unit(job.key, job.from),
                with_unit(job.key, job.to)
            )
        } else {
            format!("no flutter up to {}", with_unit(job.key, job.to))
        });
    };
    let kind = kind_word(b);
    let pct = distance(job.key, job.current, c);
    // Overspeed: a real blade's margin is a multiple of its rated rotor speed.
    let rated = state.preset.operating.rated_rotor_speed;
    if job.key == "operating.rotor_speed" && rated > 0.0 && !job.unstable {
        let mode = b
            .mode
            .as_ref()
            .map(|m| format!(", {m}"))
            .unwrap_or_default();
        return Onward::Whole(format!(
            "{label}: {kind} at {:.2}× rated, {}{mode}",
            c / rated,
            with_unit(job.key, c)
        ));
    }
    Onward::Body(if job.unstable {
        // The search ran up from the slider's low end, so its mode label is the mode's
        // identity there; the verdict beside this already names the mode that is unstable
        // here, and two names for one root only confuse.
        format!("{kind} from {}{pct}", with_unit(job.key, c))
    } else {
        format!("{kind} at {}{pct}{}", with_unit(job.key, c), mode_note(b))
    })
}

/// How far the boundary `c` lies from the current value: relative for a speed (", +45 %"), whose
/// zero is physical; in the key's own unit for an angle (", +18.1 deg"), whose zero is only a
/// convention (a pitch of 0.5° would read +7000 %).
fn distance(key: &str, current: f64, c: f64) -> String {
    if unit(key) == "deg" {
        let d = decimals(key);
        format!(", {:+.d$} deg", c - current)
    } else if current.abs() > 1e-12 {
        format!(", {:+.0} %", 100.0 * (c - current) / current.abs())
    } else {
        String::new()
    }
}

/// The wind-speed margin along the schedule: the lowest wind between cut-in and cut-out at
/// which a mode is unstable.
fn along_schedule(job: &BoundaryJob, searches: &[Search]) -> String {
    let Some(search) = searches.first() else {
        return "no search".to_string();
    };
    let b = &search.boundary;
    match b.critical {
        Some(c) => format!(
            "{} at {} along the schedule{}",
            kind_word(b),
            with_unit(job.key, c),
            mode_note(b)
        ),
        None if search.unstable_at_start => {
            format!("unstable at cut-in {}", with_unit(job.key, job.from))
        }
        None => format!("stable to cut-out {}", with_unit(job.key, job.to)),
    }
}

/// The coupling margin: the nearest value on either side at which flutter begins, or the
/// slider range it is stable over.
fn both_ways(job: &BoundaryJob, searches: &[Search]) -> String {
    let nearest = searches
        .iter()
        .filter_map(|s| s.boundary.critical.map(|c| (c, &s.boundary)))
        .min_by(|a, b| {
            (a.0 - job.current)
                .abs()
                .total_cmp(&(b.0 - job.current).abs())
        });
    match nearest {
        Some((c, b)) => format!(
            "{} at α {}{}",
            kind_word(b),
            with_unit(job.key, c),
            mode_note(b)
        ),
        None => format!(
            "stable over α {}…{}",
            with_unit(job.key, job.from),
            with_unit(job.key, job.to)
        ),
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
    let [top, bottom] =
        Layout::vertical([Constraint::Length(1), Constraint::Length(1)]).areas(area);
    let width = area.width as usize;
    let (badge, style): (&str, Style) = match (&state.solved, &state.solve_error) {
        (_, Some(_)) => (" ERROR ", theme.error()),
        (None, None) => (" SOLVING… ", theme.dim()),
        (Some(s), None) => match s.stability.verdict {
            Verdict::Stable => (" STABLE ", theme.stable()),
            Verdict::Flutter => (" FLUTTER ", theme.flutter()),
            Verdict::Divergence => (" DIVERGENCE ", theme.divergence()),
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
    let margin = margin_text(state).map(|m| format!("margin along {m}"));
    let solving = (state.solving() && state.solved.is_some()).then(|| solving_text(state));
    // The badge and the margin always; the least-damped mode in the room that is left.
    let used = badge.chars().count()
        + margin.as_ref().map_or(0, |m| m.chars().count() + 5)
        + solving.as_ref().map_or(0, |t| t.chars().count());
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

    let line = if let Some(e) = error_text(state) {
        Line::styled(format!("error: {e}"), theme.error())
    } else if let Some(n) = &state.notice {
        Line::styled(n.clone(), theme.accent())
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
        Line::from(spans)
    };
    frame.render_widget(Paragraph::new(line), bottom);
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
    use super::distance;

    #[test]
    fn a_margin_in_angle_is_a_difference_and_in_speed_a_ratio() {
        // A pitch of 0.5° with flutter at 35.5°: 35 degrees away, not "+7000 %".
        assert_eq!(distance("operating.pitch", 0.5, 35.5), ", +35.0 deg");
        assert_eq!(distance("section.ply_angle", 45.0, 30.0), ", -15.0 deg");
        assert_eq!(distance("operating.wind_speed", 10.0, 15.0), ", +50 %");
        // No ratio to a zero speed.
        assert_eq!(distance("operating.tunnel_speed", 0.0, 137.0), "");
    }
}
