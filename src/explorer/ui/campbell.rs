//! The Campbell view: frequency and damping ratio of the tracked modes against rotor speed (with
//! the 1P and 3P excitation lines), or against wind speed along the operating schedule (with the
//! 1P, 3P and 6P lines of the scheduled rotor speed, as HAWCStab2 draws it), and the current
//! operating point.

use super::{marker, pane, sig, Theme};
use crate::analysis::campbell::{oscillates, ROTOR_SPEED_KEY};
use crate::analysis::sweep::TrackedMode;
use crate::explorer::state::jobs::CampbellAxis;
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

/// What the Campbell view's axis is, in words and units.
struct AxisText {
    name: &'static str,
    unit: &'static str,
    /// "speeds", "winds": what the points are, for the failed-points title.
    points: &'static str,
}

fn axis_text(axis: CampbellAxis) -> AxisText {
    match axis {
        CampbellAxis::RotorSpeed => AxisText {
            name: "rotor speed",
            unit: "rpm",
            points: "speeds",
        },
        CampbellAxis::WindSpeed => AxisText {
            name: "wind speed",
            unit: "m/s",
            points: "winds",
        },
    }
}

/// The pane shown while there is no diagram: computing (with the sweep it runs), or why not.
fn placeholder(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let job = state.campbell.as_ref();
    let text = match job.and_then(|j| j.result.as_ref()) {
        Some(Err(e)) => Line::styled(format!("no Campbell diagram: {e}"), theme.error()),
        Some(Ok(c)) => {
            let a = axis_text(job.map_or(state.campbell_axis, |j| j.axis));
            Line::styled(
                match c.sweep.failed.first() {
                    Some(f) => format!(
                        "no Campbell diagram: none of the {} {} could be solved; at {} {}: {}",
                        c.sweep.values.len(),
                        a.points,
                        sig(f.value, 4),
                        a.unit,
                        f.error
                    ),
                    None => "no Campbell diagram: no structural modes".to_string(),
                },
                theme.error(),
            )
        }
        None => {
            let (from, to, points) = job.map_or((0.0, 0.0, 0), |j| (j.from, j.to, j.points));
            let a = axis_text(job.map_or(state.campbell_axis, |j| j.axis));
            let along = match a.name {
                "wind speed" => " along the schedule",
                _ => "",
            };
            Line::styled(
                format!(
                    "computing… sweeping {} {}–{} {}{along}, {points} points, tracked \
                     (in the background: keys keep working)",
                    a.name,
                    sig(from, 3),
                    sig(to, 3),
                    a.unit
                ),
                theme.dim(),
            )
        }
    };
    frame.render_widget(
        Paragraph::new(text)
            .wrap(Wrap { trim: true })
            .block(pane(" Campbell diagram ", theme)),
        area,
    );
}

/// The rotor harmonics nP as polylines over the axis: straight along rotor speed, following
/// the scheduled rotor speed along wind speed.
fn harmonics(x: &[f64], rpm: &[f64], orders: &[f64]) -> Vec<Vec<(f64, f64)>> {
    orders
        .iter()
        .map(|n| {
            x.iter()
                .zip(rpm)
                .filter(|(x, r)| x.is_finite() && r.is_finite())
                .map(|(&x, &r)| (x, n * r / 60.0))
                .collect()
        })
        .collect()
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let Some(job) = state.campbell.as_ref() else {
        return placeholder(state, theme, frame, area);
    };
    let diagram = match job.result.as_ref() {
        Some(Ok(c)) if !c.sweep.modes.is_empty() => c,
        _ => return placeholder(state, theme, frame, area),
    };
    let sweep = &diagram.sweep;
    let a = axis_text(job.axis);
    let wind = job.axis == CampbellAxis::WindSpeed;
    // Which modes to draw is decided with the sweep, as for `--plot`: lowest first.
    let selection = sweep.campbell_modes();
    let left_off = selection.left_off;
    let shown: Vec<(usize, &TrackedMode)> = selection
        .shown
        .iter()
        .map(|&i| (i, &sweep.modes[i]))
        .collect();
    let x = &sweep.values;
    let x_lo = x
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
        .min(job.from);
    let x_hi = x.iter().copied().fold(0.0, f64::max).max(x_lo + 1e-9);
    // The operating point: the wind, or the rotor speed the solve ran at (the schedule's).
    let now = if wind {
        state.preset.operating.wind_speed
    } else {
        state
            .scheduled_value(ROTOR_SPEED_KEY)
            .unwrap_or(state.preset.operating.rotor_speed)
    };
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
    let orders: &[f64] = if wind { &[1.0, 3.0, 6.0] } else { &[1.0, 3.0] };
    // The notes only where they fit whole: a legend cut mid-word reads as nonsense.
    let room = (area.width as usize).saturating_sub(4);
    let used = |l: &[Span]| l.iter().map(|s| s.content.chars().count()).sum::<usize>();
    let grey = format!(
        "  · grey: {}, now",
        if wind { "1P, 3P, 6P" } else { "1P, 3P" }
    );
    if used(&legend) + grey.chars().count() <= room {
        legend.push(Span::styled(grey, dim));
    }
    let more = format!(" · {left_off} more off scale");
    if left_off > 0 && used(&legend) + more.chars().count() <= room {
        legend.push(Span::styled(more, dim));
    }
    // Points that could not be solved are gaps in every curve: the title says how many, and
    // where the first is (the status line shows solve errors of the current point only).
    let narrow = area.width < 70;
    let scheduled = crate::analysis::campbell::schedule_wind_range(&state.preset).is_some();
    let title = match (sweep.failed.first(), wind, narrow) {
        (Some(f), _, _) => format!(
            " Campbell · {}/{} {} not solved, first {} {} ",
            sweep.failed.len(),
            sweep.values.len(),
            a.points,
            sig(f.value, 4),
            a.unit
        ),
        (None, true, true) => " Campbell along the schedule ".to_string(),
        (None, true, false) => {
            " Campbell along the schedule: frequency against wind speed (w: rotor speed) "
                .to_string()
        }
        (None, false, false) if scheduled => {
            " Campbell diagram: frequency against rotor speed (w: wind speed) ".to_string()
        }
        (None, false, _) => " Campbell diagram: frequency against rotor speed ".to_string(),
    };
    legend.push(Span::raw(" "));

    let freq: Vec<Vec<Vec<(f64, f64)>>> = shown
        .iter()
        .map(|(_, m)| segments(x, &m.frequency_hz, &m.frequency_hz))
        .collect();
    let zeta: Vec<Vec<Vec<(f64, f64)>>> = shown
        .iter()
        .map(|(_, m)| segments(x, &m.frequency_hz, &m.damping_ratio))
        .collect();
    // Along rotor speed the harmonics are straight lines through the origin.
    let lines = if wind {
        harmonics(x, &diagram.rotor_speed_rpm, orders)
    } else {
        harmonics(&[0.0, x_hi], &[0.0, x_hi], orders)
    };
    // Along the schedule the scale reaches the top harmonic, as HAWCStab2 draws it; along rotor
    // speed the modes set it (the 3P line runs off the top).
    let harmonic_top = if wind {
        lines.iter().flatten().map(|p| p.1).fold(0.0, f64::max)
    } else {
        0.0
    };
    let f_max = freq
        .iter()
        .flatten()
        .flatten()
        .map(|p| p.1)
        .fold(harmonic_top, f64::max)
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
    let now_f = [(now, 0.0), (now, f_max)];
    let now_z = [(now, z[0]), (now, z[1])];
    let zero = [(x_lo, 0.0), (x_hi, 0.0)];
    let mk = marker(state.opts.marker);
    let guide = style_of(theme.guide());
    let line = |data, style| polyline(data, style, mk);
    let x_axis = || {
        Axis::default().bounds([x_lo, x_hi]).style(dim).labels([
            Span::raw(format!("{} {}", sig(x_lo, 3), a.unit)),
            Span::styled(a.name, theme.title()),
            Span::raw(format!("{} {}", sig(x_hi, 3), a.unit)),
        ])
    };
    let mut f_sets: Vec<Dataset> = lines.iter().map(|l| line(l, guide)).collect();
    f_sets.push(line(&now_f, guide));
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
    // The operating point, marked by the vertical line, in numbers.
    let now_text = format!("now {} {}", sig(now, 3), a.unit);
    let z_title = if narrow {
        format!(" ζ (below 0: unstable) · {now_text} ")
    } else {
        format!(" damping ratio ζ (a mode below 0 is unstable) · {now_text} ")
    };
    let z_chart = Chart::new(z_sets)
        .block(pane(z_title, theme))
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
