//! The mode-shape pane: flap, edge and twist of one mode along the span on a canvas (the plot
//! marker the user chose), each normalised to its own peak, with the mode's name, frequency,
//! damping ratio and each component's size and phase relative to the dominant one. A rotor's or
//! turbine's mode is drawn on one part at a time (a blade at its azimuth, or the tower's
//! fore–aft, side–side and torsion along its height). The shapes come with the solve
//! (`Solved::shapes`, docs/model.md §6.5); this pane only draws them.

use super::{marker, pane, sig, Theme};
use crate::analysis::mode::Mode;
use crate::analysis::mode_shape::{ModeShape, ModeShapes};
use crate::explorer::state::{frequency_order, AppState};
use crate::physics::structure::{Family, PartKind};
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line};
use ratatui::widgets::{Paragraph, Wrap};
use ratatui::Frame;

/// The unit of each component's amplitude.
const UNITS: [&str; 3] = ["m", "m", "rad"];

/// Each component's name on a part, and the letter it is marked with on the canvas and in the
/// legend (it tells the curves apart without colour).
fn component_names(kind: PartKind) -> [(&'static str, &'static str); 3] {
    match kind {
        PartKind::Blade => [("F", "flap"), ("E", "edge"), ("T", "twist")],
        PartKind::Tower => [("A", "fore–aft"), ("S", "side–side"), ("T", "torsion")],
    }
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let shown = state.shape_index().and_then(|i| {
        let solved = state.solved.as_ref()?;
        Some((
            i,
            &solved.stability.eigenvalues[i],
            solved.shapes.get(i)?,
            frequency_order(&solved.stability.eigenvalues),
        ))
    });
    let Some((index, mode, shapes, order)) = shown else {
        let block = pane(" Mode shape ", theme);
        let why = match (&state.solved, &state.solve_error) {
            (_, Some(_)) => "no solve: see the status line",
            (None, None) => "waiting for the solve…",
            (Some(_), None) => "no mode shapes from this solve",
        };
        frame.render_widget(
            Paragraph::new(TextLine::styled(why, theme.dim())).block(block),
            area,
        );
        return;
    };
    let part = state.shape_part_index(shapes);
    let shape = &shapes.parts[part];
    let title_style = if mode.re >= 0.0 {
        theme.flutter()
    } else {
        theme.title()
    };
    let mut title = vec![
        Span::raw(" Mode shape · "),
        Span::styled(mode.label.clone(), title_style),
    ];
    if shapes.parts.len() > 1 {
        title.push(Span::raw(format!(" · {}", shape.part)));
    }
    title.push(Span::raw(" "));
    let block = pane(TextLine::from(title), theme);
    let inner = block.inner(area);
    frame.render_widget(block, area);
    let position = order.iter().position(|&i| i == index).unwrap_or(0) + 1;
    let text = vec![
        about(state, mode, position, order.len(), theme),
        legend(shapes, part, theme),
    ];
    // The text wraps on narrow panes: give it the rows it needs.
    let width = inner.width.max(1) as usize;
    let rows: u16 = text
        .iter()
        .map(|l| l.width().div_ceil(width).max(1) as u16)
        .sum();
    let [text_area, canvas_area, axis_area] = Layout::vertical([
        Constraint::Length(rows),
        Constraint::Min(1),
        Constraint::Length(1),
    ])
    .areas(inner);
    frame.render_widget(Paragraph::new(text).wrap(Wrap { trim: true }), text_area);
    // One cell along the span: the letters stand side by side at the tip.
    let cell = shape.span.last().copied().unwrap_or(0.0) / f64::from(canvas_area.width.max(1));
    frame.render_widget(canvas(state, shape, cell, theme), canvas_area);
    let length = shape.span.last().copied().unwrap_or(0.0);
    let mut axis = match shape.kind {
        PartKind::Blade => format!("root 0 m · span (m) · tip {} m", sig(length, 3)),
        PartKind::Tower => format!("base 0 m · height (m) · top {} m", sig(length, 3)),
    };
    if shapes.parts.len() > 1 {
        axis.push_str("   p: next part");
    }
    frame.render_widget(
        Paragraph::new(TextLine::styled(axis, theme.dim())),
        axis_area,
    );
}

/// Frequency, damping ratio, which mode of how many, and whether the pane follows the
/// least-damped one.
fn about<'a>(
    state: &AppState,
    mode: &Mode,
    position: usize,
    count: usize,
    theme: &Theme,
) -> TextLine<'a> {
    let mut spans = vec![Span::raw(format!(
        "{} Hz  ζ = {}  {position}/{count}",
        sig(mode.frequency_hz, 4),
        sig(mode.damping_ratio, 3)
    ))];
    if state.shape_pick.is_none() {
        let why = if mode.re >= 0.0 {
            "  unstable"
        } else {
            "  least damped"
        };
        spans.push(Span::styled(why, theme.dim()));
    }
    TextLine::from(spans)
}

/// `F flap 1 m · E edge 0.21 m ∠3° · T twist 9.4e-3 rad ∠−12°`: each component's peak on the
/// drawn part per unit of the reference and its phase there (absent components are left out),
/// and on another part than the reference's, what they are relative to.
fn legend<'a>(shapes: &ModeShapes, part: usize, theme: &Theme) -> TextLine<'a> {
    let shape = &shapes.parts[part];
    let names = component_names(shape.kind);
    let mut spans = Vec::new();
    for f in Family::ALL {
        let k = f.index();
        if shape.peaks[k] <= 0.0 {
            continue;
        }
        if !spans.is_empty() {
            spans.push(Span::styled(" · ", theme.dim()));
        }
        let phase = shape.phases[k].round();
        let phase = if (part == shapes.main && f == shapes.reference) || phase == 0.0 {
            String::new()
        } else {
            format!(" ∠{phase}°")
        };
        let (letter, name) = names[k];
        spans.push(Span::styled(
            format!(
                "{letter} {name} {} {}{phase}",
                sig(shape.peaks[k], 2),
                UNITS[k]
            ),
            series_style(theme, k),
        ));
    }
    if part != shapes.main {
        let main = &shapes.parts[shapes.main];
        let reference = component_names(main.kind)[shapes.reference.index()].1;
        spans.push(Span::styled(
            format!(
                "  per {} of {}'s {reference}",
                UNITS[shapes.reference.index()],
                main.part
            ),
            theme.dim(),
        ));
    }
    TextLine::from(spans)
}

fn series_style(theme: &Theme, k: usize) -> Style {
    if theme.colored() {
        Style::new().fg(theme.series(k))
    } else {
        Style::new()
    }
}

/// The three components against the span, ±1 with the zero line, each marked with its letter
/// at its tip value, the letters `cell` (m) apart (F, E, T from the left) so none hides another.
fn canvas<'a>(
    state: &AppState,
    shape: &'a ModeShape,
    cell: f64,
    theme: &Theme,
) -> Canvas<'a, impl Fn(&mut Context) + 'a> {
    let length = shape
        .span
        .last()
        .copied()
        .unwrap_or(1.0)
        .max(f64::MIN_POSITIVE);
    let guide = theme.guide();
    let colors: [Color; 3] = [0, 1, 2].map(|k| {
        if theme.colored() {
            theme.series(k)
        } else {
            theme.plot()
        }
    });
    Canvas::default()
        .marker(marker(state.opts.marker))
        .x_bounds([0.0, length])
        .y_bounds([-1.1, 1.1])
        .paint(move |ctx| {
            ctx.draw(&Line {
                x1: 0.0,
                y1: 0.0,
                x2: length,
                y2: 0.0,
                color: guide,
            });
            let drawn = shape.peaks.iter().zip(&shape.components).zip(colors);
            for ((_, values), color) in drawn.filter(|((peak, _), _)| **peak > 0.0) {
                for (x, y) in shape.span.windows(2).zip(values.windows(2)) {
                    ctx.draw(&Line {
                        x1: x[0],
                        y1: y[0],
                        x2: x[1],
                        y2: y[1],
                        color,
                    });
                }
            }
            ctx.layer();
            let names = component_names(shape.kind);
            for k in 0..3 {
                if let (true, Some(&tip)) = (shape.peaks[k] > 0.0, shape.components[k].last()) {
                    ctx.print(
                        length - cell * (2 - k) as f64,
                        tip,
                        TextLine::styled(names[k].0, Style::new().fg(colors[k])),
                    );
                }
            }
        })
}
