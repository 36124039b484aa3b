//! The Campbell view: frequency and damping ratio of the tracked modes against rotor speed, with
//! the 1P and 3P excitation lines and the current rotor speed.

use super::{marker, pane, sig, Theme};
use crate::analysis::campbell::oscillates;
use crate::analysis::sweep::TrackedMode;
use crate::explorer::state::AppState;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Chart, Dataset, GraphType, Paragraph, Wrap};
use ratatui::Frame;

/// The pieces of a curve where the mode oscillates, as separate polylines (no line is drawn
/// across a gap).
fn segments(x: &[f64], f: &[f64], y: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    for ((&x, &f), &y) in x.iter().zip(f).zip(y) {
        if oscillates(f) && y.is_finite() {
            cur.push((x, y));
        } else if !cur.is_empty() {
            out.push(std::mem::take(&mut cur));
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

fn polyline(data: &[(f64, f64)], style: Style, mk: ratatui::symbols::Marker) -> Dataset<'_> {
    Dataset::default()
        .marker(mk)
        .graph_type(GraphType::Line)
        .style(style)
        .data(data)
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let job = state.campbell.as_ref();
    let result = job.and_then(|j| j.result.as_ref());
    let sweep = match result {
        Some(Ok(s)) if !s.modes.is_empty() => s,
        other => {
            let text = match other {
                Some(Err(e)) => Line::styled(format!("no Campbell diagram: {e}"), theme.error()),
                Some(Ok(s)) => Line::styled(
                    match s.failed.first() {
                        Some(f) => format!(
                            "no Campbell diagram: none of the {} rotor speeds could be solved; \
                             at {} rpm: {}",
                            s.values.len(),
                            sig(f.value, 4),
                            f.error
                        ),
                        None => "no Campbell diagram: no structural modes".to_string(),
                    },
                    theme.error(),
                ),
                _ => Line::styled("sweeping rotor speed…", theme.dim()),
            };
            frame.render_widget(
                Paragraph::new(text)
                    .wrap(Wrap { trim: true })
                    .block(pane(" Campbell diagram ", theme)),
                area,
            );
            return;
        }
    };
    // Which modes to draw is decided with the sweep, as for `--plot`: lowest first.
    let selection = sweep.campbell_modes();
    let left_off = selection.left_off;
    let shown: Vec<(usize, &TrackedMode)> = selection
        .shown
        .iter()
        .map(|&i| (i, &sweep.modes[i]))
        .collect();
    let rpm = &sweep.values;
    let rpm_max = rpm.iter().copied().fold(0.0, f64::max).max(1e-9);
    let now = state.preset.operating.rotor_speed;
    let colors: Vec<Color> = shown.iter().map(|(i, _)| theme.series(*i)).collect();
    let style_of = |c: Color| {
        if theme.colored() {
            Style::new().fg(c)
        } else {
            Style::new()
        }
    };
    let dim = theme.dim();
    let mut legend: Vec<Span> = shown
        .iter()
        .zip(&colors)
        .flat_map(|((_, m), c)| [Span::raw(" "), Span::styled(m.label.clone(), style_of(*c))])
        .collect();
    legend.push(Span::styled("  · grey: 1P, 3P, now", dim));
    if left_off > 0 {
        legend.push(Span::styled(format!(" · {left_off} more off scale"), dim));
    }
    // Points that could not be solved are gaps in every curve: the title says how many, and
    // where the first is (the status line shows solve errors of the current point only).
    let title = match sweep.failed.first() {
        Some(f) => format!(
            " Campbell · {}/{} speeds not solved, first {} rpm ",
            sweep.failed.len(),
            sweep.values.len(),
            sig(f.value, 4)
        ),
        None => " Campbell diagram: frequency against rotor speed ".to_string(),
    };
    legend.push(Span::raw(" "));

    let freq: Vec<Vec<Vec<(f64, f64)>>> = shown
        .iter()
        .map(|(_, m)| segments(rpm, &m.frequency_hz, &m.frequency_hz))
        .collect();
    let zeta: Vec<Vec<Vec<(f64, f64)>>> = shown
        .iter()
        .map(|(_, m)| segments(rpm, &m.frequency_hz, &m.damping_ratio))
        .collect();
    let f_max = freq
        .iter()
        .flatten()
        .flatten()
        .map(|p| p.1)
        .fold(0.0, f64::max)
        .max(1e-9)
        * 1.1;
    let (z_lo, z_hi) = zeta
        .iter()
        .flatten()
        .flatten()
        .map(|p| p.1)
        .fold((0.0f64, 0.0f64), |a, z| (a.0.min(z), a.1.max(z)));
    let z_pad = 0.08 * (z_hi - z_lo).max(1e-6);
    let z = [z_lo - z_pad, z_hi + z_pad];
    let one_p = [(0.0, 0.0), (rpm_max, rpm_max / 60.0)];
    let three_p = [(0.0, 0.0), (rpm_max, 3.0 * rpm_max / 60.0)];
    let now_f = [(now, 0.0), (now, f_max)];
    let now_z = [(now, z[0]), (now, z[1])];
    let zero = [(0.0, 0.0), (rpm_max, 0.0)];
    let mk = marker(state.opts.marker);
    let guide = style_of(theme.guide());
    let line = |data, style| polyline(data, style, mk);
    let x_axis = || {
        Axis::default().bounds([0.0, rpm_max]).style(dim).labels([
            Span::raw("0 rpm"),
            Span::styled("rotor speed", theme.title()),
            Span::raw(format!("{} rpm", sig(rpm_max, 3))),
        ])
    };
    let mut f_sets = vec![
        line(&one_p, guide),
        line(&three_p, guide),
        line(&now_f, guide),
    ];
    let mut z_sets = vec![line(&zero, guide), line(&now_z, guide)];
    for ((f, zz), c) in freq.iter().zip(&zeta).zip(&colors) {
        f_sets.extend(f.iter().map(|seg| line(seg, style_of(*c))));
        z_sets.extend(zz.iter().map(|seg| line(seg, style_of(*c))));
    }
    let [f_area, z_area] =
        Layout::vertical([Constraint::Percentage(58), Constraint::Percentage(42)]).areas(area);
    let f_chart = Chart::new(f_sets)
        .block(pane(title, theme).title_bottom(Line::from(legend)))
        .x_axis(x_axis())
        .y_axis(Axis::default().bounds([0.0, f_max]).style(dim).labels([
            Span::raw("0 Hz"),
            Span::raw(format!("{} Hz", sig(f_max / 2.0, 3))),
            Span::raw(format!("{} Hz", sig(f_max, 3))),
        ]));
    let z_chart = Chart::new(z_sets)
        .block(pane(
            " damping ratio ζ (a mode below 0 is unstable) ",
            theme,
        ))
        .x_axis(x_axis())
        .y_axis(Axis::default().bounds(z).style(dim).labels([
            Span::raw(sig(z[0], 2)),
            Span::raw(mid_label(z)),
            Span::raw(sig(z[1], 2)),
        ]));
    frame.render_widget(f_chart, f_area);
    frame.render_widget(z_chart, z_area);
}

/// The middle tick of an axis: at a terminal's resolution a midpoint within 2 % of the range
/// from zero is drawn on the zero line, so call it 0 rather than print round-off like -0.0098.
fn mid_label(range: [f64; 2]) -> String {
    let mid = 0.5 * (range[0] + range[1]);
    if mid.abs() < 0.02 * (range[1] - range[0]) {
        "0".to_string()
    } else {
        sig(mid, 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_split_curves() {
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let f = [1.0, f64::NAN, 2.0, 3.0, 0.0];
        let segs = segments(&x, &f, &f);
        assert_eq!(segs, vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]);
    }
}
