//! The Campbell view: frequency and damping ratio of the tracked modes against rotor speed, with
//! the 1P and 3P excitation lines and the current rotor speed.

use super::{marker, pane, sig, Theme};
use crate::analysis::sweep::{TrackedMode, TrackedSweep};
use crate::explorer::state::AppState;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Chart, Dataset, GraphType, Paragraph, Wrap};
use ratatui::Frame;

/// At most this many modes are drawn (the lowest); more would be an unreadable tangle.
const MAX_SHOWN: usize = 8;
/// Modes starting above this multiple of the lowest mode's top frequency (or of 3P at the top
/// rotor speed, if higher) are left off the frequency scale so the low modes stay readable.
const SCALE_FACTOR: f64 = 5.0;

/// The modes worth drawing, lowest first, and how many were left off.
pub fn shown_modes(sweep: &TrackedSweep) -> (Vec<(usize, &TrackedMode)>, usize) {
    let lo = |m: &TrackedMode| m.frequency_hz.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = |m: &TrackedMode| m.frequency_hz.iter().copied().fold(0.0, f64::max);
    let mut order: Vec<(usize, &TrackedMode)> = sweep.modes.iter().enumerate().collect();
    order.sort_by(|a, b| lo(a.1).total_cmp(&lo(b.1)));
    let Some(first) = order.first() else {
        return (order, 0);
    };
    let rpm_max = sweep.values.iter().copied().fold(0.0, f64::max);
    let limit = (SCALE_FACTOR * hi(first.1)).max(3.0 * rpm_max / 60.0);
    let total = order.len();
    let shown: Vec<_> = order
        .into_iter()
        .filter(|(_, m)| lo(m) <= limit)
        .take(MAX_SHOWN)
        .collect();
    let left = total - shown.len();
    (shown, left)
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let job = state.campbell.as_ref();
    let result = job.and_then(|j| j.result.as_ref());
    let sweep = match result {
        Some(Ok(s)) => s,
        other => {
            let text = match other {
                Some(Err(e)) => Line::styled(format!("no Campbell diagram: {e}"), theme.error()),
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
    let (shown, left_off) = shown_modes(sweep);
    let rpm: Vec<f64> = sweep.values.clone();
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
    let legend: Vec<Span> = shown
        .iter()
        .zip(&colors)
        .flat_map(|((_, m), c)| {
            [
                Span::styled(format!(" {}", m.label), style_of(*c)),
                Span::raw(" "),
            ]
        })
        .collect();

    let freq: Vec<Vec<(f64, f64)>> = shown
        .iter()
        .map(|(_, m)| {
            rpm.iter()
                .copied()
                .zip(m.frequency_hz.iter().copied())
                .collect()
        })
        .collect();
    let zeta: Vec<Vec<(f64, f64)>> = shown
        .iter()
        .map(|(_, m)| {
            rpm.iter()
                .copied()
                .zip(m.damping_ratio.iter().copied())
                .collect()
        })
        .collect();
    let f_max = freq
        .iter()
        .flatten()
        .map(|p| p.1)
        .fold(0.0, f64::max)
        .max(1e-9)
        * 1.1;
    let (z_lo, z_hi) = zeta
        .iter()
        .flatten()
        .map(|p| p.1)
        .filter(|z| z.is_finite())
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
    let dim = theme.dim();
    let x_axis = || {
        Axis::default()
            .title(Span::styled("rotor speed (rpm)", dim))
            .bounds([0.0, rpm_max])
            .style(dim)
            .labels([
                Span::raw("0"),
                Span::raw(sig(rpm_max / 2.0, 3)),
                Span::raw(sig(rpm_max, 3)),
            ])
    };

    let mut f_sets: Vec<Dataset> = vec![
        Dataset::default()
            .marker(mk)
            .graph_type(GraphType::Line)
            .style(guide)
            .data(&one_p),
        Dataset::default()
            .marker(mk)
            .graph_type(GraphType::Line)
            .style(guide)
            .data(&three_p),
        Dataset::default()
            .marker(mk)
            .graph_type(GraphType::Line)
            .style(guide)
            .data(&now_f),
    ];
    let mut z_sets: Vec<Dataset> = vec![
        Dataset::default()
            .marker(mk)
            .graph_type(GraphType::Line)
            .style(guide)
            .data(&zero),
        Dataset::default()
            .marker(mk)
            .graph_type(GraphType::Line)
            .style(guide)
            .data(&now_z),
    ];
    for ((f, zz), c) in freq.iter().zip(&zeta).zip(&colors) {
        f_sets.push(
            Dataset::default()
                .marker(mk)
                .graph_type(GraphType::Line)
                .style(style_of(*c))
                .data(f),
        );
        z_sets.push(
            Dataset::default()
                .marker(mk)
                .graph_type(GraphType::Line)
                .style(style_of(*c))
                .data(zz),
        );
    }
    let mut f_title = vec![Span::raw(" Campbell diagram: frequency ")];
    f_title.push(Span::styled(
        "(1P, 3P and the current rotor speed in grey",
        dim,
    ));
    if left_off > 0 {
        f_title.push(Span::styled(
            format!("; {left_off} higher modes off scale"),
            dim,
        ));
    }
    f_title.push(Span::styled(") ", dim));
    let [f_area, z_area] =
        Layout::vertical([Constraint::Percentage(58), Constraint::Percentage(42)]).areas(area);
    let f_chart = Chart::new(f_sets)
        .block(pane(Line::from(f_title), theme).title_bottom(Line::from(legend.clone())))
        .x_axis(x_axis())
        .y_axis(
            Axis::default()
                .title(Span::styled("f (Hz)", dim))
                .bounds([0.0, f_max])
                .style(dim)
                .labels([
                    Span::raw("0"),
                    Span::raw(sig(f_max / 2.0, 3)),
                    Span::raw(sig(f_max, 3)),
                ]),
        );
    let z_chart = Chart::new(z_sets)
        .block(
            pane(" damping ratio ζ (flutter where a mode crosses 0) ", theme)
                .title_bottom(Line::from(legend)),
        )
        .x_axis(x_axis())
        .y_axis(
            Axis::default()
                .title(Span::styled("ζ", dim))
                .bounds(z)
                .style(dim)
                .labels([
                    Span::raw(sig(z[0], 2)),
                    Span::raw(sig(0.5 * (z[0] + z[1]), 2)),
                    Span::raw(sig(z[1], 2)),
                ]),
        );
    frame.render_widget(f_chart, f_area);
    frame.render_widget(z_chart, z_area);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(label: &str, f: [f64; 3]) -> TrackedMode {
        TrackedMode {
            label: label.into(),
            frequency_hz: f.to_vec(),
            damping_ratio: vec![0.01; 3],
            re: vec![-0.1; 3],
        }
    }

    #[test]
    fn far_modes_are_left_off_the_scale() {
        let sweep = TrackedSweep {
            parameter: "operating.rotor_speed".into(),
            values: vec![0.0, 60.0, 120.0],
            modes: vec![
                mode("torsion 1", [400.0, 401.0, 402.0]),
                mode("flap 1", [0.1, 1.0, 2.0]),
                mode("flap 2", [0.6, 2.5, 4.9]),
            ],
        };
        let (shown, left) = shown_modes(&sweep);
        let labels: Vec<&str> = shown.iter().map(|(_, m)| m.label.as_str()).collect();
        assert_eq!(labels, ["flap 1", "flap 2"]);
        assert_eq!(left, 1);
    }
}
