//! The curved reference axis of a blade (docs/model.md §11.9): its prebend (out of the rotor
//! plane, downwind positive) and sweep (in the plane, toward the leading edge positive) along
//! the straight pitch axis, in the blade's own frame (turning with the pitch).
//!
//! Between the file's points the axis is the monotone piecewise cubic of Fritsch and Carlson
//! (SIAM J. Numer. Anal. 17, 1980): smooth enough for the curvature the elements need, and,
//! unlike a global spline, it puts no wiggle between points where a table is flat (the straight
//! inboard part of a prebent blade stays straight).

use super::hermite::hermite;
use crate::error::{Error, Result};

/// The reference axis's offset from the straight pitch axis along the span.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CurvedAxis {
    /// Span positions from the root (m), strictly increasing.
    span: Vec<f64>,
    /// `[prebend, sweep]` at each span (m).
    offset: Vec<[f64; 2]>,
    /// `d offset / d span` at each span, Fritsch–Carlson.
    slope: Vec<[f64; 2]>,
}

/// The offset and its slope at one span position, measured from the root's tangent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPoint {
    /// `[prebend, sweep]` (m).
    pub offset: [f64; 2],
    /// Their rates along the span.
    pub slope: [f64; 2],
}

impl CurvedAxis {
    /// The straight blade.
    pub fn straight() -> CurvedAxis {
        CurvedAxis::default()
    }

    /// The axis through `points` (`(span, [prebend, sweep])`, span strictly increasing, every
    /// value finite); `origin` names the file in errors.
    pub fn new(origin: &str, points: &[(f64, [f64; 2])]) -> Result<CurvedAxis> {
        let invalid = |message: String| Error::Invalid {
            origin: origin.to_string(),
            message,
        };
        if let Some((k, p)) = points
            .iter()
            .enumerate()
            .find(|(_, (s, o))| !(s.is_finite() && o.iter().all(|v| v.is_finite())))
        {
            return Err(invalid(format!(
                "reference-axis point {} (span {} m, offset {:?} m) is not finite",
                k + 1,
                p.0,
                p.1
            )));
        }
        if let Some(k) = points.windows(2).position(|w| w[1].0 <= w[0].0) {
            return Err(invalid(format!(
                "reference-axis points {} and {} are not in increasing span order ({} m, then {} m)",
                k + 1,
                k + 2,
                points[k].0,
                points[k + 1].0
            )));
        }
        let span: Vec<f64> = points.iter().map(|p| p.0).collect();
        let offset: Vec<[f64; 2]> = points.iter().map(|p| p.1).collect();
        let slope = match points.len() {
            0 | 1 => vec![[0.0; 2]; points.len()],
            _ => {
                let [a, b] = [0, 1].map(|c| {
                    monotone_slopes(&span, &offset.iter().map(|o| o[c]).collect::<Vec<_>>())
                });
                a.into_iter().zip(b).map(|(x, y)| [x, y]).collect()
            }
        };
        Ok(CurvedAxis {
            span,
            offset,
            slope,
        })
    }

    /// Whether the axis is the pitch axis itself: no points, or every offset zero.
    pub fn is_straight(&self) -> bool {
        self.offset.iter().all(|o| o[0] == 0.0 && o[1] == 0.0)
    }

    /// The offset and slope at `z` from the pitch axis, held at the end values (and zero slope)
    /// beyond the points. The elements take the curvature from it, which a root offset or slope
    /// does not change, and the centrifugal pull from the slopes against the radial pitch axis
    /// (docs/model.md §11.9).
    pub fn at(&self, z: f64) -> AxisPoint {
        let n = self.span.len();
        let held = |k: usize| AxisPoint {
            offset: self.offset.get(k).copied().unwrap_or([0.0; 2]),
            slope: [0.0; 2],
        };
        if n < 2 || z < self.span[0] {
            return held(0);
        }
        if z > self.span[n - 1] {
            return held(n - 1);
        }
        let k = (self.span.partition_point(|&s| s <= z) - 1).min(n - 2);
        let h = self.span[k + 1] - self.span[k];
        // The cubic through both points' offsets and slopes, as the elements interpolate.
        let (value, rate, _) = hermite((z - self.span[k]) / h, h);
        let (a, b) = (k, k + 1);
        let through = |w: [f64; 4], c: usize| {
            w[0] * self.offset[a][c]
                + w[1] * self.slope[a][c]
                + w[2] * self.offset[b][c]
                + w[3] * self.slope[b][c]
        };
        AxisPoint {
            offset: [0, 1].map(|c| through(value, c)),
            slope: [0, 1].map(|c| through(rate, c)),
        }
    }
}

/// Fritsch–Carlson slopes of the monotone piecewise cubic through `(x, y)` (at least two
/// points): the harmonic mean of the neighbouring secants where they agree in sign, zero at a
/// local extremum, one-sided at the ends.
fn monotone_slopes(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let secant: Vec<f64> = (0..n - 1)
        .map(|k| (y[k + 1] - y[k]) / (x[k + 1] - x[k]))
        .collect();
    (0..n)
        .map(|k| {
            if k == 0 {
                return secant[0];
            }
            if k == n - 1 {
                return secant[n - 2];
            }
            let (a, b) = (secant[k - 1], secant[k]);
            if a * b <= 0.0 {
                return 0.0;
            }
            // Weighted harmonic mean (Fritsch & Butland): never overshoots either secant.
            let (h0, h1) = (x[k] - x[k - 1], x[k + 1] - x[k]);
            let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
            (w1 + w2) / (w1 / a + w2 / b)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parabola_is_followed() {
        let points: Vec<(f64, [f64; 2])> = (0..=200)
            .map(|k| {
                let z = k as f64 * 0.5;
                (z, [1.0 + 0.1 * z + 0.002 * z * z, -0.5])
            })
            .collect();
        let axis = CurvedAxis::new("test", &points).unwrap();
        for z in [3.3, 47.0, 88.8] {
            let p = axis.at(z);
            assert!(
                (p.offset[0] - (1.0 + 0.1 * z + 0.002 * z * z)).abs() < 1e-4,
                "{z}: {p:?}"
            );
            assert!((p.slope[0] - (0.1 + 0.004 * z)).abs() < 1e-3, "{z}: {p:?}");
            assert_eq!(p.offset[1], -0.5);
        }
        assert!(!axis.is_straight());
    }

    #[test]
    fn a_flat_inboard_part_stays_flat() {
        let axis = CurvedAxis::new(
            "test",
            &[
                (0.0, [0.0, 0.0]),
                (10.0, [0.0, 0.0]),
                (20.0, [0.0, 0.0]),
                (30.0, [-1.0, 0.0]),
                (40.0, [-3.0, 0.0]),
            ],
        )
        .unwrap();
        for z in [1.0, 9.0, 15.0, 19.9] {
            assert_eq!(axis.at(z).offset, [0.0, 0.0], "{z}");
        }
        // Monotone between the points: no overshoot past the next value.
        assert!((-1.0..=0.0).contains(&axis.at(25.0).offset[0]));
        assert!(CurvedAxis::new("test", &[(0.0, [0.0; 2]), (5.0, [0.0; 2])])
            .unwrap()
            .is_straight());
    }

    #[test]
    fn bad_points_are_named() {
        let e = CurvedAxis::new("f.dat", &[(0.0, [0.0; 2]), (0.0, [1.0, 0.0])]).unwrap_err();
        assert!(e.to_string().contains("points 1 and 2"), "{e}");
        let e = CurvedAxis::new("f.dat", &[(0.0, [f64::NAN, 0.0])]).unwrap_err();
        assert!(e.to_string().contains("not finite"), "{e}");
    }
}
