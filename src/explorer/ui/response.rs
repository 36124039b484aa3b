//! The tip response: twist (deg) and flap (m) streaming as line plots with axes and units,
//! autoscaled, the time window scrolling; a diverging run is said so plainly.

use super::{marker, pane, sig, Theme};
use crate::explorer::state::AppState;
use crate::preset::TurbineModel;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Chart, Dataset, GraphType, Paragraph, Wrap};
use ratatui::Frame;

/// Reduce `pts` (ordered in x) to at most about `2 × buckets` points, keeping each bucket's
/// minimum and maximum in order, so peaks survive.
pub fn decimate(pts: &[(f64, f64)], buckets: usize) -> Vec<(f64, f64)> {
    let buckets = buckets.max(1);
    if pts.len() <= 2 * buckets {
        return pts.to_vec();
    }
    let mut out = Vec::with_capacity(2 * buckets + 1);
    let size = pts.len().div_ceil(buckets);
    for chunk in pts.chunks(size) {
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = i;
            }
            if p.1 > chunk[hi].1 {
                hi = i;
            }
        }
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(chunk[a]);
        if b != a {
            out.push(chunk[b]);
        }
    }
    out
}

/// y bounds holding `pts` with a margin; a flat signal gets a small band around its value.
pub fn autoscale(pts: &[(f64, f64)], floor: f64) -> [f64; 2] {
    let (lo, hi) = pts
        .iter()
        .filter(|p| p.1.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
            (a.0.min(p.1), a.1.max(p.1))
        });
    if !lo.is_finite() {
        return [-floor, floor];
    }
    let span = hi - lo;
    let pad = if span > floor {
        0.08 * span
    } else {
        (0.1 * hi.abs().max(lo.abs())).max(floor)
    };
    [lo - pad, hi + pad]
}

/// One plotted signal.
struct Series<'a> {
    data: &'a [(f64, f64)],
    name: &'a str,
    unit: &'a str,
    /// Smallest y band (in `unit`) a flat signal is drawn in.
    floor: f64,
    color: ratatui::style::Color,
}

fn chart<'a>(s: Series<'a>, t: [f64; 2], tall: bool, state: &AppState, theme: &Theme) -> Chart<'a> {
    let Series {
        data,
        name,
        unit,
        floor,
        color,
    } = s;
    let y = autoscale(data, floor);
    let style = if theme.colored() {
        Style::new().fg(color)
    } else {
        Style::new()
    };
    let ds = Dataset::default()
        .marker(marker(state.opts.marker))
        .graph_type(GraphType::Line)
        .style(style)
        .data(data);
    let dim = theme.dim();
    // The name and unit sit under the time axis, where they stay visible at any height.
    let y_labels: Vec<Span> = if tall {
        vec![
            Span::raw(sig(y[0], 3)),
            Span::raw(sig(0.5 * (y[0] + y[1]), 3)),
            Span::raw(sig(y[1], 3)),
        ]
    } else {
        vec![Span::raw(sig(y[0], 3)), Span::raw(sig(y[1], 3))]
    };
    Chart::new(vec![ds])
        .x_axis(Axis::default().bounds(t).style(dim).labels([
            Span::raw(format!("{} s", sig(t[0], 3))),
            Span::styled(format!("{name} ({unit})"), theme.title()),
            Span::raw(format!("{} s", sig(t[1], 3))),
        ]))
        .y_axis(Axis::default().bounds(y).style(dim).labels(y_labels))
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let r = &state.response;
    let p = &state.preset;
    let mut title = vec![Span::raw(if p.turbine.model == TurbineModel::Blade {
        " Tip response "
    } else {
        " Blade 1 tip response "
    })];
    if p.stall_linearised_in_time() {
        title.push(Span::styled("(stall linearised) ", theme.dim()));
    }
    if r.diverging {
        title.push(Span::styled(" DIVERGING ", theme.flutter()));
        title.push(Span::raw(" "));
    }
    if state.paused {
        title.push(Span::styled("paused ", theme.dim()));
    }
    let block = pane(Line::from(title), theme);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    if let Some(e) = &r.error {
        frame.render_widget(
            Paragraph::new(Line::styled(format!("no response: {e}"), theme.error()))
                .wrap(Wrap { trim: true }),
            inner,
        );
        return;
    }
    if r.samples.is_empty() {
        frame.render_widget(
            Paragraph::new(Line::styled("waiting for the simulation…", theme.dim())),
            inner,
        );
        return;
    }
    let t_last = r.samples.last().map(|s| s.t).unwrap_or(0.0);
    let window = state.preset.simulation.duration;
    let t0 = (t_last - window).max(r.samples[0].t.min(t_last));
    let t = [t0, t0 + window];
    let (body, note) = if r.diverging {
        let [a, b] = Layout::vertical([Constraint::Min(0), Constraint::Length(1)]).areas(inner);
        (a, Some(b))
    } else {
        (inner, None)
    };
    let side_by_side = body.width >= 100;
    let [twist_area, flap_area] = if side_by_side {
        Layout::horizontal([Constraint::Percentage(50), Constraint::Percentage(50)])
            .spacing(2)
            .areas(body)
    } else {
        Layout::vertical([Constraint::Percentage(50), Constraint::Percentage(50)]).areas(body)
    };
    let buckets = twist_area.width as usize * 2;
    let twist: Vec<(f64, f64)> = r
        .samples
        .iter()
        .map(|s| (s.t, s.tip_twist.to_degrees()))
        .collect();
    let flap: Vec<(f64, f64)> = r.samples.iter().map(|s| (s.t, s.tip_flap)).collect();
    let twist = decimate(&twist, buckets);
    let flap = decimate(&flap, buckets);
    let twist = Series {
        data: &twist,
        name: "twist",
        unit: "deg",
        floor: 1e-6,
        color: theme.series(0),
    };
    let flap = Series {
        data: &flap,
        name: "flap",
        unit: "m",
        floor: 1e-9,
        color: theme.series(1),
    };
    let tall = twist_area.height >= 8;
    frame.render_widget(chart(twist, t, tall, state, theme), twist_area);
    frame.render_widget(chart(flap, t, tall, state, theme), flap_area);
    if let Some(note) = note {
        frame.render_widget(
            Paragraph::new(Line::styled(
                format!(
                    "diverging: grew past the bound at t = {} s, run stopped (r restarts)",
                    sig(t_last, 3)
                ),
                theme.flutter(),
            )),
            note,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimation_keeps_extremes_in_order() {
        let pts: Vec<(f64, f64)> = (0..1000)
            .map(|i| (i as f64, ((i as f64) * 0.37).sin()))
            .collect();
        let d = decimate(&pts, 50);
        assert!(d.len() <= 100);
        assert!(d.windows(2).all(|w| w[0].0 < w[1].0));
        let max = pts.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        assert!(d.iter().any(|p| p.1 == max));
    }

    #[test]
    fn autoscale_pads_and_handles_flat_signals() {
        let y = autoscale(&[(0.0, 1.0), (1.0, 3.0)], 1e-9);
        assert!(y[0] < 1.0 && y[1] > 3.0);
        let flat = autoscale(&[(0.0, 2.0), (1.0, 2.0)], 1e-9);
        assert!(flat[0] < 2.0 && flat[1] > 2.0);
        assert_eq!(autoscale(&[], 1.0), [-1.0, 1.0]);
    }
}
