//! A station's airfoil between the listed ones (docs/model.md §11.10): its relative thickness
//! along the span, and its shape interpolated in relative thickness, as the ontology prescribes.
//!
//! - The relative thickness at span η is the outer shape's `rthick` where the file gives it
//!   (linear between its grid points), else the monotone cubic (PCHIP, Fritsch and Carlson 1980)
//!   through the thicknesses of the airfoils `airfoil_position` places: a monotone interpolant
//!   never overshoots between two stations of equal thickness, as a spline would.
//! - The shape at thickness r is linear in r between the two airfoils the positions use whose
//!   thicknesses bracket it (the thinnest or the thickest beyond them). Both contours are
//!   resampled on one parameter first: each surface by its arc length from the leading edge
//!   (the point of least x), at cosine-spaced fractions so the nose and the trailing edge keep
//!   their points.

use super::{Airfoil, WindIo};
use crate::error::{Error, Result};
use std::f64::consts::PI;

/// The two listed airfoils a station's shape is blended from.
#[derive(Debug, Clone, Copy)]
pub struct ThicknessBlend<'a> {
    /// The station's relative thickness.
    pub thickness: f64,
    pub thinner: &'a Airfoil,
    pub thicker: &'a Airfoil,
    /// Weight of `thicker` (0 … 1).
    pub weight: f64,
}

/// Points per surface, trailing edge to leading edge, of a resampled contour.
pub const SURFACE_POINTS: usize = 100;

impl WindIo {
    /// Relative thickness of the blade at span fraction `eta` (held at the end values beyond
    /// [0, 1]).
    pub fn relative_thickness_at(&self, eta: f64) -> f64 {
        let shape = &self.blade.outer_shape;
        if let Some(r) = &shape.relative_thickness {
            return r.linear(eta);
        }
        let p = &shape.airfoil_position;
        let r: Vec<f64> = p
            .labels
            .iter()
            .map(|l| {
                self.airfoil(l)
                    .expect("the reader checks every position names an airfoil")
                    .relative_thickness
            })
            .collect();
        pchip(&p.grid, &r, eta)
    }

    /// The airfoils and weight that make the shape at span fraction `eta`.
    pub fn thickness_blend(&self, eta: f64) -> ThicknessBlend<'_> {
        let thickness = self.relative_thickness_at(eta);
        let mut used: Vec<&Airfoil> = Vec::new();
        for l in &self.blade.outer_shape.airfoil_position.labels {
            let a = self.airfoil(l).expect("checked by the reader");
            if !used.iter().any(|u| u.name == a.name) {
                used.push(a);
            }
        }
        used.sort_by(|a, b| a.relative_thickness.total_cmp(&b.relative_thickness));
        let k = used.partition_point(|a| a.relative_thickness <= thickness);
        let (thinner, thicker) = match k {
            0 => (used[0], used[0]),
            k if k == used.len() => (used[k - 1], used[k - 1]),
            k => (used[k - 1], used[k]),
        };
        let span = thicker.relative_thickness - thinner.relative_thickness;
        let weight = if span > 0.0 {
            ((thickness - thinner.relative_thickness) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        ThicknessBlend {
            thickness,
            thinner,
            thicker,
            weight,
        }
    }

    /// The station's contour at span fraction `eta` in chord units, listed as WindIO lists an
    /// airfoil (trailing edge, suction side, leading edge, pressure side): `2·SURFACE_POINTS + 1`
    /// points. `file` is the name errors give.
    pub fn station_shape(&self, eta: f64, file: &str) -> Result<(Vec<f64>, Vec<f64>)> {
        let b = self.thickness_blend(eta);
        let (xa, ya) = resampled(b.thinner, file)?;
        let (xb, yb) = resampled(b.thicker, file)?;
        let mix = |a: &[f64], c: &[f64]| -> Vec<f64> {
            a.iter()
                .zip(c)
                .map(|(p, q)| (1.0 - b.weight) * p + b.weight * q)
                .collect()
        };
        Ok((mix(&xa, &xb), mix(&ya, &yb)))
    }
}

/// An airfoil's contour on the common parameter: each surface from the trailing edge to the
/// leading edge at cosine-spaced fractions of its arc length, the leading edge once.
fn resampled(a: &Airfoil, file: &str) -> Result<(Vec<f64>, Vec<f64>)> {
    let le = (0..a.x.len())
        .min_by(|&i, &j| a.x[i].total_cmp(&a.x[j]))
        .expect("an airfoil has at least three points");
    if le == 0 || le == a.x.len() - 1 {
        return Err(Error::format(
            file,
            a.line,
            format!(
                "airfoils `{}`: expected the leading edge (least x) inside the contour, found it \
                 at its end; the contour runs from the trailing edge round the leading edge and back",
                a.name
            ),
        ));
    }
    let suction: Vec<[f64; 2]> = (0..=le).rev().map(|i| [a.x[i], a.y[i]]).collect();
    let pressure: Vec<[f64; 2]> = (le..a.x.len()).map(|i| [a.x[i], a.y[i]]).collect();
    let fractions: Vec<f64> = (0..=SURFACE_POINTS)
        .map(|j| 0.5 * (1.0 - (PI * j as f64 / SURFACE_POINTS as f64).cos()))
        .collect();
    let on_suction = along(&suction, &fractions);
    let on_pressure = along(&pressure, &fractions);
    let points = on_suction
        .iter()
        .rev()
        .chain(on_pressure.iter().skip(1))
        .copied();
    Ok(points.map(|p| (p[0], p[1])).unzip())
}

/// Points at the given fractions (0 … 1) of a polyline's arc length.
fn along(line: &[[f64; 2]], fractions: &[f64]) -> Vec<[f64; 2]> {
    let mut arc = vec![0.0];
    for w in line.windows(2) {
        arc.push(arc[arc.len() - 1] + (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]));
    }
    let total = arc[arc.len() - 1];
    fractions
        .iter()
        .map(|f| {
            let s = f * total;
            let i = arc.partition_point(|&a| a <= s).clamp(1, line.len() - 1);
            let step = arc[i] - arc[i - 1];
            let t = if step > 0.0 {
                ((s - arc[i - 1]) / step).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (p, q) = (line[i - 1], line[i]);
            [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]
        })
        .collect()
}

/// The monotone piecewise-cubic Hermite interpolant through `(x, y)` at `at` (x strictly
/// increasing; held at the end values beyond it): Fritsch–Carlson slopes, the weighted harmonic
/// mean of the neighbouring secants inside, zero at a local extremum, and the one-sided
/// three-point slope at the ends, limited to keep the shape.
fn pchip(x: &[f64], y: &[f64], at: f64) -> f64 {
    let n = x.len();
    if at <= x[0] {
        return y[0];
    }
    if at >= x[n - 1] {
        return y[n - 1];
    }
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let d: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    let slope = |k: usize| -> f64 {
        if n == 2 {
            return d[0];
        }
        if k == 0 || k == n - 1 {
            let (h0, h1, d0, d1) = if k == 0 {
                (h[0], h[1], d[0], d[1])
            } else {
                (h[n - 2], h[n - 3], d[n - 2], d[n - 3])
            };
            let m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
            return if m.signum() != d0.signum() || d0 == 0.0 {
                0.0
            } else if d0.signum() != d1.signum() && m.abs() > 3.0 * d0.abs() {
                3.0 * d0
            } else {
                m
            };
        }
        let (dl, dr) = (d[k - 1], d[k]);
        if dl == 0.0 || dr == 0.0 || dl.signum() != dr.signum() {
            return 0.0;
        }
        let (w1, w2) = (2.0 * h[k] + h[k - 1], h[k] + 2.0 * h[k - 1]);
        (w1 + w2) / (w1 / dl + w2 / dr)
    };
    let k = x.partition_point(|&v| v <= at).clamp(1, n - 1) - 1;
    let t = (at - x[k]) / h[k];
    let (m0, m1) = (slope(k) * h[k], slope(k + 1) * h[k]);
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * y[k]
        + (t3 - 2.0 * t2 + t) * m0
        + (-2.0 * t3 + 3.0 * t2) * y[k + 1]
        + (t3 - t2) * m1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pchip_passes_through_its_points_and_never_overshoots() {
        let x = [0.0, 0.02, 0.15, 0.245, 0.44, 0.77, 1.0];
        let y = [1.0, 1.0, 0.5, 0.36, 0.301, 0.211, 0.211];
        for (a, b) in x.iter().zip(&y) {
            assert!((pchip(&x, &y, *a) - b).abs() < 1e-15);
        }
        for i in 0..=1000 {
            let at = i as f64 / 1000.0;
            let v = pchip(&x, &y, at);
            let k = x.partition_point(|&p| p <= at).clamp(1, x.len() - 1);
            let (lo, hi) = (y[k - 1].min(y[k]), y[k - 1].max(y[k]));
            assert!(v >= lo - 1e-15 && v <= hi + 1e-15, "{at}: {v}");
        }
        // A cubic Hermite between the flat 0.77–1.0 pair stays flat.
        assert_eq!(pchip(&x, &y, 0.9), 0.211);
    }

    #[test]
    fn pchip_is_exact_on_a_straight_line() {
        let x = [0.0, 0.1, 0.5, 0.6, 1.0];
        let y: Vec<f64> = x.iter().map(|v| 2.0 - 3.0 * v).collect();
        for i in 0..=50 {
            let at = i as f64 / 50.0;
            assert!((pchip(&x, &y, at) - (2.0 - 3.0 * at)).abs() < 1e-14);
        }
    }
}
