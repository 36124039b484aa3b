//! The status line: the verdict (stable / flutter / divergence), the least-damped mode, the
//! margin from the background boundary search along the selected parameter, and on the second
//! row any error from the worker (or a notice, or the main keys).

use super::{sig, Theme};
use crate::analysis::eigen::Verdict;
use crate::analysis::flutter::BoundaryKind;
use crate::explorer::state::ParamKind;
use crate::explorer::state::{unit, AppState, ViewMode, PARAMS};
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
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
    let u = unit(job.key);
    let d = decimals(job.key);
    let with_unit = |v: f64| {
        if u.is_empty() {
            format!("{v:.d$}")
        } else {
            format!("{v:.d$} {u}")
        }
    };
    let label = param_label(job.key);
    let body = match &job.result {
        None if job.empty_range => format!("at the end of its range ({})", with_unit(job.current)),
        None => "searching…".to_string(),
        Some(Err(_)) => "search failed (below)".to_string(),
        Some(Ok(b)) => match b.critical {
            Some(c) => {
                let kind = match b.kind {
                    Some(BoundaryKind::Divergence) => "divergence",
                    _ => "flutter",
                };
                let pct = if job.current.abs() > 1e-12 {
                    format!(", {:+.0} %", 100.0 * (c - job.current) / job.current.abs())
                } else {
                    String::new()
                };
                let mode = b
                    .mode
                    .as_ref()
                    .map(|m| format!(" ({m})"))
                    .unwrap_or_default();
                if job.unstable {
                    format!("{kind} from {}{pct}{mode}", with_unit(c))
                } else {
                    format!("{kind} at {}{pct}{mode}", with_unit(c))
                }
            }
            None if job.unstable => format!(
                "unstable over {} … {}",
                with_unit(job.from),
                with_unit(job.to)
            ),
            None => format!("no flutter up to {}", with_unit(job.to)),
        },
    };
    Some(format!("{label}: {body}"))
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

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let [top, bottom] =
        Layout::vertical([Constraint::Length(1), Constraint::Length(1)]).areas(area);
    let mut spans: Vec<Span> = Vec::new();
    let (badge, style): (&str, Style) = match (&state.solved, &state.solve_error) {
        (_, Some(_)) => (" ERROR ", theme.error()),
        (None, None) => (" SOLVING… ", theme.dim()),
        (Some(s), None) => match s.stability.verdict {
            Verdict::Stable => (" STABLE ", theme.stable()),
            Verdict::Flutter => (" FLUTTER ", theme.flutter()),
            Verdict::Divergence => (" DIVERGENCE ", theme.divergence()),
        },
    };
    spans.push(Span::styled(
        badge,
        style.add_modifier(ratatui::style::Modifier::REVERSED),
    ));
    if let (Some(s), None) = (&state.solved, &state.solve_error) {
        if let Some(m) = s.stability.critical() {
            spans.push(Span::raw(format!(
                " least damped: {} {} Hz, ζ = {}",
                m.label,
                sig(m.frequency_hz, 3),
                sig(m.damping_ratio, 2)
            )));
        }
    }
    if let Some(margin) = margin_text(state) {
        spans.push(Span::styled("  │  margin ", theme.dim()));
        spans.push(Span::styled(margin, theme.accent()));
    }
    if state.solving() && state.solved.is_some() {
        spans.push(Span::styled("  solving…", theme.dim()));
    }
    frame.render_widget(Paragraph::new(Line::from(spans)), top);

    let line = if let Some(e) = error_text(state) {
        Line::styled(format!("error: {e}"), theme.error())
    } else if let Some(n) = &state.notice {
        Line::styled(n.clone(), theme.accent())
    } else {
        let mut hints = String::from(
            "←→ adjust  S-←→ coarse  ↑↓ select  a aero  k kick  f boundary  c Campbell  space pause  ? help  q quit",
        );
        if state.paused {
            hints = format!("PAUSED  {hints}");
        }
        Line::styled(hints, theme.dim())
    };
    frame.render_widget(Paragraph::new(line), bottom);
}
