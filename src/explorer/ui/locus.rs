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
    // Canvas units per terminal column, to right-align the ω = 0 label.
    let per_col = (ax.x[1] - ax.x[0]) / f64::from(inner_w.max(1));

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
    let labels: Vec<String> = stab
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
            let mut d = ax.dec_lo as i32;
            while d <= ax.dec_hi as i32 {
                ctx.print(ax.x[0], d as f64, TextLine::styled(decade(d), dim));
                d += 1;
            }
            if has_real {
                ctx.print(
                    ax.x[1] - 3.5 * per_col,
                    ax.y_real,
                    TextLine::styled("ω=0", dim),
                );
            }
            ctx.print(0.0, ax.y[1], TextLine::styled("σ=0", dim));
            for (i, &(x, y)) in pole_pts.iter().enumerate() {
                let style = label_styles[i];
                ctx.print(x, y, TextLine::styled(format!("×{}", labels[i]), style));
            }
        });
    frame.render_widget(canvas, area);
}

#[cfg(test)]
mod tests {
    use super::*;

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
