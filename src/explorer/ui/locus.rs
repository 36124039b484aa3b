//! The root locus: the eigenvalues in the σ–ω plane (upper half, one pole per conjugate pair),
//! the σ = 0 stability line, the current poles marked and labelled, and fading trails of where
//! they were while a parameter moved.
//!
//! Structural roots of one blade span decades (flap near 1P, torsion far above), so ω is on a log
//! axis and σ on an asinh axis: linear within ±σ₀ around the stability line (σ₀ = the least-damped
//! oscillatory mode's |σ|), logarithmic beyond, so the critical pole and the heavily damped ones
//! are all visible. Real roots (ω = 0) sit on a separate bottom row, labelled at its right end.

use super::{marker, pane, short_label, sig, Theme};
use crate::explorer::state::AppState;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::{Line as TextLine, Span};
use ratatui::widgets::canvas::{Canvas, Line, Points};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

/// Below this fraction of the largest ω a root counts as real.
const REAL_ROOT_FRACTION: f64 = 1e-9;

/// The mapping from (σ, ω) to canvas coordinates.
#[derive(Debug, Clone, Copy)]
pub struct Axes {
    /// σ₀ (1/s): the asinh axis is linear within ±σ₀.
    pub s0: f64,
    /// Largest ω still drawn on the real-root row.
    pub real_below: f64,
    /// log10 ω of the lowest and highest decade shown.
    pub dec_lo: f64,
    pub dec_hi: f64,
    pub x: [f64; 2],
    pub y: [f64; 2],
    /// y of the real-root row.
    pub y_real: f64,
}

impl Axes {
    /// Axes holding every pole in `sets`.
    pub fn fit(sets: &[&[(f64, f64)]]) -> Axes {
        let all = || sets.iter().flat_map(|s| s.iter().copied());
        let w_max = all().map(|(_, w)| w).fold(0.0, f64::max);
        let real_below = w_max * REAL_ROOT_FRACTION;
        let osc = || all().filter(move |(_, w)| *w > real_below);
        // σ₀: the least-damped oscillatory pole of the *current* set (first), else any.
        let s0 = sets
            .first()
            .and_then(|cur| {
                cur.iter()
                    .filter(|(_, w)| *w > real_below)
                    .map(|(s, _)| s.abs())
                    .filter(|s| *s > 0.0)
                    .min_by(f64::total_cmp)
            })
            .or_else(|| {
                all()
                    .map(|(s, _)| s.abs())
                    .filter(|s| *s > 0.0)
                    .min_by(f64::total_cmp)
            })
            .unwrap_or(1.0)
            .max(1e-9);
        let (mut dec_lo, mut dec_hi) = osc().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
            let l = p.1.log10();
            (a.0.min(l), a.1.max(l))
        });
        if !dec_lo.is_finite() {
            dec_lo = -1.0;
            dec_hi = 1.0;
        }
        dec_lo = dec_lo.floor();
        dec_hi = dec_hi.ceil().max(dec_lo + 1.0);
        let span = dec_hi - dec_lo;
        let y_real = dec_lo - 0.12 * span;
        let tx = |s: f64| (s / s0).asinh();
        let (mut xl, mut xh) = all().fold((0.0f64, 0.0f64), |a, (s, _)| {
            (a.0.min(tx(s)), a.1.max(tx(s)))
        });
        // Room on both sides of σ = 0: the unstable half-plane stays visible.
        let width = (xh - xl).max(2.0);
        xl = xl.min(-0.25 * width) - 0.08 * width;
        xh = xh.max(0.25 * width) + 0.08 * width;
        Axes {
            s0,
            real_below,
            dec_lo,
            dec_hi,
            x: [xl, xh],
            y: [y_real - 0.06 * span, dec_hi + 0.04 * span],
            y_real,
        }
    }

    pub fn tx(&self, sigma: f64) -> f64 {
        (sigma / self.s0).asinh()
    }

    pub fn ty(&self, omega: f64) -> f64 {
        if omega > self.real_below && omega > 0.0 {
            omega.log10()
        } else {
            self.y_real
        }
    }

    /// σ at canvas x.
    pub fn sigma_at(&self, x: f64) -> f64 {
        self.s0 * x.sinh()
    }
}

/// A decade as text: 0.01, 0.1, 1, 10, 100, 1000, else 1e5.
fn decade(d: i32) -> String {
    match d {
        -3..=-1 => format!("{:.*}", (-d) as usize, 10f64.powi(d)),
        0..=4 => format!("{}", 10i64.pow(d as u32)),
        _ => format!("1e{d}"),
    }
}

pub fn render(state: &AppState, theme: &Theme, frame: &mut Frame, area: Rect) {
    let mut title = vec![Span::raw(" Root locus  σ–ω ")];
    if state.solving() {
        title.push(Span::styled("solving… ", theme.dim()));
    }
    let Some(solved) = state.solved.as_ref() else {
        let text = match &state.solve_error {
            Some(e) => TextLine::styled(format!("no solution: {e}"), theme.error()),
            None => TextLine::styled("solving…", theme.dim()),
        };
        let block = pane(TextLine::from(title), theme);
        frame.render_widget(
            Paragraph::new(text)
                .wrap(ratatui::widgets::Wrap { trim: true })
                .block(block),
            area,
        );
        return;
    };
    let stab = &solved.stability;
    let poles: Vec<(f64, f64)> = stab.eigenvalues.iter().map(|m| (m.re, m.im)).collect();
    let lags: Vec<(f64, f64)> = stab.aero_lags.iter().map(|m| (m.re, m.im)).collect();
    let steps = theme.trail_steps(state.trails.len());
    let trails = &state.trails[..steps];
    let mut sets: Vec<&[(f64, f64)]> = vec![&poles, &lags];
    sets.extend(trails.iter().map(|t| t.as_slice()));
    let ax = Axes::fit(&sets);

    let (lo, hi, lin) = (
        sig(ax.sigma_at(ax.x[0]), 2),
        sig(ax.sigma_at(ax.x[1]), 2),
        sig(ax.s0, 2),
    );
    let inner_w = area.width.saturating_sub(2);
    let long = format!(" σ 1/s: {lo} … 0 … {hi}  (linear within ±{lin})   ω rad/s, log ");
    let bottom = if long.chars().count() + 2 <= inner_w as usize {
        long
    } else {
        format!(" σ {lo}…{hi} 1/s (asinh) · ω rad/s (log) ")
    };
    let block =
        pane(TextLine::from(title), theme).title_bottom(TextLine::styled(bottom, theme.dim()));
    // Canvas units per terminal column as the canvas maps its labels, to right-align the ω = 0
    // label and to start a name exactly its length before its pole's marker.
    let per_col = (ax.x[1] - ax.x[0]) / f64::from(inner_w.saturating_sub(1).max(1));

    let guide = theme.guide();
    let dim = theme.dim();
    // Letters (F, E, T) and, with colour, the family's colour tell flap, edge and torsion apart.
    let label_styles: Vec<Style> = stab
        .eigenvalues
        .iter()
        .map(|m| match m.family {
            _ if m.re >= 0.0 => theme.flutter(),
            Some(f) if theme.colored() => Style::new().fg(theme.family(f)),
            _ => Style::new(),
        })
        .collect();
    let names: Vec<String> = stab
        .eigenvalues
        .iter()
        .map(|m| short_label(&m.label))
        .collect();
    let trail_colors: Vec<Color> = (0..trails.len())
        .map(|age| theme.trail(age, trails.len()))
        .collect();
    let lag_pts: Vec<(f64, f64)> = lags.iter().map(|&(s, w)| (ax.tx(s), ax.ty(w))).collect();
    let trail_pts: Vec<Vec<(f64, f64)>> = trails
        .iter()
        .map(|t| t.iter().map(|&(s, w)| (ax.tx(s), ax.ty(w))).collect())
        .collect();
    let pole_pts: Vec<(f64, f64)> = poles.iter().map(|&(s, w)| (ax.tx(s), ax.ty(w))).collect();
    let has_real = poles
        .iter()
        .chain(lags.iter())
        .any(|&(_, w)| w <= ax.real_below);
    // The axes' own words: each decade at the left edge, σ = 0 at the top, ω = 0 at the right.
    let mut guides: Vec<(f64, f64, String)> = (ax.dec_lo as i32..=ax.dec_hi as i32)
        .map(|d| (ax.x[0], f64::from(d), decade(d)))
        .collect();
    if has_real {
        guides.push((ax.x[1] - 3.5 * per_col, ax.y_real, "ω=0".to_string()));
    }
    guides.push((0.0, ax.y[1], "σ=0".to_string()));
    let inner = Rect::new(0, 0, inner_w, area.height.saturating_sub(2));
    let guide_cells: Vec<(u16, u16)> = guides
        .iter()
        .flat_map(|(x, y, text)| {
            let (col, row) = canvas_cell(&ax, inner, *x, *y);
            (0..text.chars().count() as u16).map(move |k| (col + k, row))
        })
        .collect();
    let cells: Vec<(u16, u16)> = pole_pts
        .iter()
        .map(|&(x, y)| canvas_cell(&ax, inner, x, y))
        .collect();
    let labels = placed_labels(&cells, &names, &guide_cells, inner_w);

    let canvas = Canvas::default()
        .block(block)
        .marker(marker(state.opts.marker))
        .x_bounds(ax.x)
        .y_bounds(ax.y)
        .paint(move |ctx| {
            // Stability line and the real-root row.
            ctx.draw(&Line {
                x1: 0.0,
                y1: ax.y[0],
                x2: 0.0,
                y2: ax.y[1],
                color: guide,
            });
            // Oldest trails first so newer ones draw over them.
            for (pts, color) in trail_pts.iter().zip(&trail_colors).rev() {
                ctx.draw(&Points {
                    coords: pts,
                    color: *color,
                });
            }
            ctx.draw(&Points {
                coords: &lag_pts,
                color: guide,
            });
            ctx.layer();
            for (x, y, text) in &guides {
                ctx.print(*x, *y, TextLine::styled(text.clone(), dim));
            }
            for (i, &(x, y)) in pole_pts.iter().enumerate() {
                let style = label_styles[i];
                let (text, before) = &labels[i];
                let x = x - f64::from(*before) * per_col;
                ctx.print(x, y, TextLine::styled(text.clone(), style));
            }
        });
    frame.render_widget(canvas, area);
}

/// The terminal cell (column, row within `inner`) where the canvas prints a text at (x, y),
/// as ratatui's `Canvas` places its labels.
fn canvas_cell(ax: &Axes, inner: Rect, x: f64, y: f64) -> (u16, u16) {
    let (w, h) = (ax.x[1] - ax.x[0], ax.y[1] - ax.y[0]);
    let col = (x - ax.x[0]) * f64::from(inner.width.saturating_sub(1)) / w;
    let row = (ax.y[1] - y) * f64::from(inner.height.saturating_sub(1)) / h;
    (col.max(0.0) as u16, row.max(0.0) as u16)
}

/// Each pole's text and the canvas columns it starts before its marker: the marker `×` and,
/// where the cells after it are free, its name (`×F4`), else where the cells before it are
/// (`F5×`). Every marker is kept; names go to the poles in order (the least stable first), never
/// over a marker, another name or the axes' words (`words`), and never touching another name or
/// marker at the name's far end, so a crowded row reads `F5× ×F4`, never `×F5F4` or `×F5×`.
fn placed_labels(
    marks: &[(u16, u16)],
    names: &[String],
    words: &[(u16, u16)],
    width: u16,
) -> Vec<(String, u16)> {
    use std::collections::HashSet;
    // Markers, the axes' words and the names placed so far: the cells a name may not take.
    let mut taken: HashSet<(u16, u16)> = marks.iter().chain(words).copied().collect();
    marks
        .iter()
        .zip(names)
        .map(|(&(col, row), name)| {
            let n = name.chars().count() as u16;
            // The name's cells, nearest its marker first, then the cell beyond its far end.
            let after: Vec<Option<u16>> = (1..=n + 1).map(|k| col.checked_add(k)).collect();
            let before: Vec<Option<u16>> = (1..=n + 1).map(|k| col.checked_sub(k)).collect();
            let fits = |span: &[Option<u16>], taken: &HashSet<(u16, u16)>| {
                let (name_cells, beyond) = span.split_at(n as usize);
                name_cells
                    .iter()
                    .all(|c| c.is_some_and(|c| c < width && !taken.contains(&(c, row))))
                    && beyond[0].is_none_or(|c| !taken.contains(&(c, row)))
            };
            let (span, placed) = if fits(&after, &taken) {
                (&after, (format!("×{name}"), 0))
            } else if fits(&before, &taken) {
                (&before, (format!("{name}×"), n))
            } else {
                return ("×".to_string(), 0);
            };
            taken.extend(span[..n as usize].iter().flatten().map(|&c| (c, row)));
            placed
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_never_overwrite_another_pole_or_name() {
        let cells = [(10, 2), (12, 2), (20, 2), (10, 3)];
        let names = ["CT3", "FF5", "CE1", "BE1"].map(String::from);
        let texts = |placed: Vec<(String, u16)>| -> Vec<String> {
            placed.into_iter().map(|(t, _)| t).collect()
        };
        assert_eq!(
            texts(placed_labels(&cells, &names, &[], 40)),
            ["CT3×", "×FF5", "×CE1", "×BE1"]
        );
        assert_eq!(placed_labels(&cells, &names, &[], 40)[0].1, 3);
        // With no room either side the marker stands alone; at the pane's edge a name that
        // would be cut goes before its marker.
        let crowded = [(2, 0), (0, 0), (4, 0)];
        assert_eq!(texts(placed_labels(&crowded, &names[..3], &[], 40))[0], "×");
        assert_eq!(
            texts(placed_labels(&[(38, 0)], &names[..1], &[], 40)),
            ["CT3×"]
        );
        // A name never touches another marker or name at its far end, nor covers the axes' words.
        let f = ["F5", "F4"].map(String::from);
        assert_eq!(
            texts(placed_labels(&[(10, 0), (13, 0)], &f, &[], 40)),
            ["F5×", "×F4"]
        );
        let words: Vec<(u16, u16)> = (0..4).map(|c| (c, 0)).collect();
        assert_eq!(
            texts(placed_labels(&[(5, 0), (7, 0)], &f, &words, 40)),
            ["×", "×F4"]
        );
    }

    #[test]
    fn axes_hold_every_pole_and_the_stability_line() {
        let poles = [(-0.05, 6.0), (-40.0, 800.0), (0.02, 30.0), (-3.0, 0.0)];
        let ax = Axes::fit(&[&poles]);
        assert!(ax.x[0] < 0.0 && ax.x[1] > 0.0);
        for &(s, w) in &poles {
            let (x, y) = (ax.tx(s), ax.ty(w));
            assert!(ax.x[0] <= x && x <= ax.x[1], "σ {s} outside");
            assert!(ax.y[0] <= y && y <= ax.y[1], "ω {w} outside");
        }
        // σ₀ is the least-damped oscillatory |σ|, the real root lies on its own row.
        assert_eq!(ax.s0, 0.02);
        assert_eq!(ax.ty(0.0), ax.y_real);
        assert!(ax.y_real < ax.dec_lo);
        assert!((ax.sigma_at(ax.tx(-40.0)) + 40.0).abs() < 1e-9);
    }

    #[test]
    fn decades_read_naturally() {
        assert_eq!(decade(-2), "0.01");
        assert_eq!(decade(0), "1");
        assert_eq!(decade(3), "1000");
        assert_eq!(decade(6), "1e6");
    }
}
