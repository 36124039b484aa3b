//! A static airfoil polar: lift, drag and pitching-moment coefficients against angle of attack
//! (docs/model.md §12.1), looked up linearly as AeroDyn's default `InterpOrd = 1` does, with the
//! attached-flow line (lift slope and zero-lift angle) fitted from the polar itself.
//!
//! Inputs: the tabulated coefficients (α in radians, strictly increasing, covering ±180° for a
//! full polar). Outputs: the coefficients and their slopes at any α ([`Polar::at`]), and the
//! attached line `C_l ≈ a0 (α − α0)` ([`Polar::attached`]), and the separation point of
//! Kirchhoff's flow inverted on that line with the fully separated lift it implies
//! ([`Polar::separation`], docs/model.md §12.8).

use crate::error::{Error, Result};

/// Coefficients at one angle of attack with their slopes ∂/∂α (1/rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Coefficients {
    pub cl: f64,
    pub cd: f64,
    /// About the quarter chord, nose-up positive.
    pub cm: f64,
    pub dcl: f64,
    pub dcd: f64,
    pub dcm: f64,
}

/// The attached-flow line fitted to a polar: `C_l ≈ slope (α − zero_lift)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AttachedLine {
    /// a0 (1/rad).
    pub slope: f64,
    /// α0 (rad).
    pub zero_lift: f64,
}

impl AttachedLine {
    pub fn lift(&self, alpha: f64) -> f64 {
        self.slope * (alpha - self.zero_lift)
    }
}

/// The steady separation point `f_st` and the fully separated lift `C_l,fs` at one angle of
/// attack, with their slopes ∂/∂α (1/rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Separation {
    pub f: f64,
    pub cl_fs: f64,
    pub df: f64,
    pub dcl_fs: f64,
}

/// The dynamic-stall constants of the Hansen–Gaunaa–Madsen model (docs/model.md §12.8): Jones-type
/// indicial constants `A1, A2, b1, b2` and the time constants `τ_p` (pressure lag) and `τ_f`
/// (separation lag), in semichord travel times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnsteadyConstants {
    pub a1: f64,
    pub a2: f64,
    pub b1: f64,
    pub b2: f64,
    pub tau_p: f64,
    pub tau_f: f64,
}

impl UnsteadyConstants {
    /// `Ok` when every constant lies in its range (`A1, A2 ≥ 0` with `A1 + A2 ≤ 1`, `b1, b2` in
    /// (0, 10], `τ_p, τ_f` in (0, 100]), else which one does not and where it may lie.
    pub fn check(&self) -> std::result::Result<(), String> {
        let ranged = [
            ("A1", self.a1, 0.0, 1.0, false),
            ("A2", self.a2, 0.0, 1.0, false),
            ("b1", self.b1, 0.0, 10.0, true),
            ("b2", self.b2, 0.0, 10.0, true),
            ("tau_p", self.tau_p, 0.0, 100.0, true),
            ("tau_f", self.tau_f, 0.0, 100.0, true),
        ];
        for (name, v, lo, hi, open) in ranged {
            let above = if open { v > lo } else { v >= lo };
            if !(v.is_finite() && above && v <= hi) {
                let bracket = if open { "(" } else { "[" };
                return Err(format!("{name} = {v}; allowed: {bracket}{lo}, {hi}]"));
            }
        }
        if self.a1 + self.a2 > 1.0 {
            return Err(format!(
                "A1 + A2 = {} + {} = {}; allowed: at most 1 (the direct part 1 − A1 − A2 of the \
                 indicial response is not negative)",
                self.a1,
                self.a2,
                self.a1 + self.a2
            ));
        }
        Ok(())
    }

    /// `(1 − t)·self + t·other`, constant by constant.
    fn mix(&self, other: &UnsteadyConstants, t: f64) -> UnsteadyConstants {
        let m = |a: f64, b: f64| (1.0 - t) * a + t * b;
        UnsteadyConstants {
            a1: m(self.a1, other.a1),
            a2: m(self.a2, other.a2),
            b1: m(self.b1, other.b1),
            b2: m(self.b2, other.b2),
            tau_p: m(self.tau_p, other.tau_p),
            tau_f: m(self.tau_f, other.tau_f),
        }
    }
}

/// Dynamic-stall constants a polar's file gives, with the file (and table) they come from.
#[derive(Debug, Clone, PartialEq)]
pub struct UnsteadyBlock {
    pub constants: UnsteadyConstants,
    pub origin: String,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Polar {
    /// α (rad), strictly increasing.
    alpha: Vec<f64>,
    cl: Vec<f64>,
    cd: Vec<f64>,
    cm: Vec<f64>,
    attached: AttachedLine,
    /// `f_st` at every row.
    separation: Vec<f64>,
    /// `C_l,fs` at every row.
    separated_lift: Vec<f64>,
    unsteady: Option<UnsteadyBlock>,
}

/// Half-width of the window, around the zero-lift angle, over which the attached line is fitted:
/// ±4° stays below stall on every thick or thin wind-turbine profile and is wide enough that the
/// table's own steps (0.5°–1° near zero lift) do not set the slope.
const ATTACHED_HALF_WINDOW: f64 = 4.0 * std::f64::consts::PI / 180.0;

/// Largest |C_l| of a non-lifting section (a cylinder): a hundred times the token lift cylinder
/// polars carry, a thousandth of an airfoil's maximum lift.
const NON_LIFTING: f64 = 1e-3;

impl Polar {
    /// A polar from columns in radians; `origin` names it in errors (file and table).
    pub fn new(
        alpha: Vec<f64>,
        cl: Vec<f64>,
        cd: Vec<f64>,
        cm: Vec<f64>,
        origin: &str,
    ) -> Result<Polar> {
        let n = alpha.len();
        if n < 2 || cl.len() != n || cd.len() != n || cm.len() != n {
            return Err(Error::numerical(format!(
                "{origin}: a polar needs at least two rows and equal columns (α {n}, Cl {}, Cd {}, Cm {})",
                cl.len(),
                cd.len(),
                cm.len()
            )));
        }
        if let Some(w) = alpha.windows(2).position(|w| w[1] <= w[0]) {
            return Err(Error::numerical(format!(
                "{origin}: angles of attack must increase; row {} ({}°) does not exceed row {} ({}°)",
                w + 2,
                alpha[w + 1].to_degrees(),
                w + 1,
                alpha[w].to_degrees()
            )));
        }
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !(finite(&alpha) && finite(&cl) && finite(&cd) && finite(&cm)) {
            return Err(Error::numerical(format!(
                "{origin}: the polar has non-finite coefficients"
            )));
        }
        // A section that lifts nowhere (a cylinder at the root) has the attached line C_l = 0;
        // any other polar must have an attached range. Cylinder files often hold a token lift
        // (the IEA 15MW's AeroDyn polars 00 and 01: C_l = 1e-4 at every angle, for tools that
        // divide by it), so "nowhere" is |C_l| ≤ NON_LIFTING everywhere, far below any airfoil's.
        let attached = if cl.iter().all(|&c| c.abs() <= NON_LIFTING) {
            Some(AttachedLine {
                slope: 0.0,
                zero_lift: 0.0,
            })
        } else {
            attached_line(&alpha, &cl)
        }
        .ok_or_else(|| {
            Error::numerical(format!(
                "{origin}: no attached-flow range: the lift coefficient never rises through zero \
                 between −30° and 30° (and is not within ±{NON_LIFTING} throughout, as a \
                 cylinder's)"
            ))
        })?;
        let (separation, separated_lift) = separation_columns(&alpha, &cl, attached);
        Ok(Polar {
            alpha,
            cl,
            cd,
            cm,
            attached,
            separation,
            separated_lift,
            unsteady: None,
        })
    }

    /// This polar with the dynamic-stall constants its file gives.
    pub fn with_unsteady(mut self, block: UnsteadyBlock) -> Polar {
        self.unsteady = Some(block);
        self
    }

    /// The dynamic-stall constants the polar's file gives, if it gives any.
    pub fn unsteady(&self) -> Option<&UnsteadyBlock> {
        self.unsteady.as_ref()
    }

    /// A linear polar `C_l = a0 (α − α0)`, constant drag, no moment: the paper's section and the
    /// uniform test blades.
    pub fn linear(slope: f64, zero_lift: f64, drag: f64) -> Polar {
        let alpha = vec![-std::f64::consts::PI, std::f64::consts::PI];
        let cl: Vec<f64> = alpha.iter().map(|a| slope * (a - zero_lift)).collect();
        let attached = AttachedLine { slope, zero_lift };
        let (separation, separated_lift) = separation_columns(&alpha, &cl, attached);
        Polar {
            alpha,
            cl,
            cd: vec![drag; 2],
            cm: vec![0.0; 2],
            attached,
            separation,
            separated_lift,
            unsteady: None,
        }
    }

    /// Where `alpha` falls in the table: the row below it, the fraction of the way to the next,
    /// and whether it lies inside (beyond the table the end row holds).
    fn between(&self, alpha: f64) -> Between {
        let n = self.alpha.len();
        let (i, t, inside) = if alpha <= self.alpha[0] {
            (0, 0.0, false)
        } else if alpha >= self.alpha[n - 1] {
            (n - 2, 1.0, false)
        } else {
            let i = self.alpha.partition_point(|&a| a <= alpha) - 1;
            let t = (alpha - self.alpha[i]) / (self.alpha[i + 1] - self.alpha[i]);
            (i, t, true)
        };
        Between {
            i,
            t,
            h: self.alpha[i + 1] - self.alpha[i],
            inside,
        }
    }

    /// Coefficients and slopes at `alpha` (rad): linear between rows, held constant beyond the
    /// table (slopes zero there).
    pub fn at(&self, alpha: f64) -> Coefficients {
        let at = self.between(alpha);
        Coefficients {
            cl: at.value(&self.cl),
            cd: at.value(&self.cd),
            cm: at.value(&self.cm),
            dcl: at.slope(&self.cl),
            dcd: at.slope(&self.cd),
            dcm: at.slope(&self.cm),
        }
    }

    /// `f_st` and `C_l,fs` at `alpha` (rad), linear between rows as the coefficients are.
    pub fn separation(&self, alpha: f64) -> Separation {
        let at = self.between(alpha);
        Separation {
            f: at.value(&self.separation),
            cl_fs: at.value(&self.separated_lift),
            df: at.slope(&self.separation),
            dcl_fs: at.slope(&self.separated_lift),
        }
    }

    /// The attached-flow line fitted to this polar.
    pub fn attached(&self) -> AttachedLine {
        self.attached
    }

    /// Angles of attack (rad) of the rows.
    pub fn alphas(&self) -> &[f64] {
        &self.alpha
    }

    /// The polar whose every coefficient is `(1 − t)·self + t·other` at each angle (the union of
    /// both tables' angles): HAWC2's interpolation in relative thickness and the blend between
    /// neighbouring AeroDyn nodes' airfoils.
    pub fn blend(&self, other: &Polar, t: f64, origin: &str) -> Result<Polar> {
        let mut alpha: Vec<f64> = self.alpha.iter().chain(&other.alpha).copied().collect();
        alpha.sort_by(f64::total_cmp);
        alpha.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
        let mix = |f: fn(&Coefficients) -> f64| -> Vec<f64> {
            alpha
                .iter()
                .map(|&a| (1.0 - t) * f(&self.at(a)) + t * f(&other.at(a)))
                .collect()
        };
        let (cl, cd, cm) = (mix(|c| c.cl), mix(|c| c.cd), mix(|c| c.cm));
        let blended = Polar::new(alpha, cl, cd, cm, origin)?;
        // Between an airfoil whose file gives dynamic-stall constants and one whose file gives
        // none, the constants given hold.
        let unsteady = match (&self.unsteady, &other.unsteady) {
            (Some(a), Some(b)) => Some(UnsteadyBlock {
                constants: a.constants.mix(&b.constants, t),
                origin: if a.origin == b.origin {
                    a.origin.clone()
                } else {
                    format!("{} and {}", a.origin, b.origin)
                },
            }),
            (Some(a), None) | (None, Some(a)) => Some(a.clone()),
            (None, None) => None,
        };
        Ok(Polar {
            unsteady,
            ..blended
        })
    }
}

/// The steady separation point of Kirchhoff's flow, `C_l = a0 (α − α0) ((1 + √f)/2)²`, inverted
/// on the attached line at every row: `f = (2 √(C_l / a0(α − α0)) − 1)²`, 1 where the polar lies
/// on or above the line (and at α0 itself), and 0 from the first row on each side of α0 where
/// the ratio falls to ¼ or below, outward to the table's ends (the flow does not reattach
/// beyond full separation). A section that lifts nowhere is separated everywhere. With it the
/// fully separated lift `C_l,fs = (C_l − a0 (α − α0) f)/(1 − f)`, written through `√f` so that it
/// stays exact as `f → 1` (`a0 (α − α0) (1 + 3√f)/(4 (1 + √f))`), `C_l/2` at `f = 1` and `C_l`
/// at `f = 0`.
fn separation_columns(alpha: &[f64], cl: &[f64], line: AttachedLine) -> (Vec<f64>, Vec<f64>) {
    let n = alpha.len();
    let mut f = vec![0.0; n];
    if line.slope > 0.0 {
        let kirchhoff = |k: usize| {
            if (alpha[k] - line.zero_lift).abs() <= 1e-9 {
                return 1.0;
            }
            let ratio = cl[k] / line.lift(alpha[k]);
            if ratio >= 1.0 {
                1.0
            } else if ratio <= 0.25 {
                0.0
            } else {
                (2.0 * ratio.sqrt() - 1.0).powi(2)
            }
        };
        let start = alpha.partition_point(|&a| a < line.zero_lift);
        let mut walk = |rows: &mut dyn Iterator<Item = usize>| {
            for k in rows {
                f[k] = kirchhoff(k);
                if f[k] == 0.0 {
                    break;
                }
            }
        };
        walk(&mut (start..n));
        walk(&mut (0..start).rev());
    }
    let separated = (0..n)
        .map(|k| {
            if f[k] >= 1.0 {
                0.5 * cl[k]
            } else if f[k] <= 0.0 {
                cl[k]
            } else {
                let root = f[k].sqrt();
                line.lift(alpha[k]) * (1.0 + 3.0 * root) / (4.0 * (1.0 + root))
            }
        })
        .collect();
    (f, separated)
}

/// The attached line: the zero-lift angle where lift rises through zero nearest α = 0 (within
/// ±30°), the slope a least-squares fit of the rows within ±[`ATTACHED_HALF_WINDOW`] of it
/// (the two rows around the crossing when the table is coarser than that).
fn attached_line(alpha: &[f64], cl: &[f64]) -> Option<AttachedLine> {
    let limit = 30f64.to_radians();
    let zero_lift = alpha
        .windows(2)
        .zip(cl.windows(2))
        .filter(|(a, c)| a[0] >= -limit && a[1] <= limit && c[0] <= 0.0 && c[1] > 0.0)
        .map(|(a, c)| a[0] + (a[1] - a[0]) * (-c[0]) / (c[1] - c[0]))
        .min_by(|x, y| x.abs().total_cmp(&y.abs()))?;
    let window: Vec<(f64, f64)> = alpha
        .iter()
        .zip(cl)
        .filter(|(a, _)| (*a - zero_lift).abs() <= ATTACHED_HALF_WINDOW)
        .map(|(a, c)| (*a, *c))
        .collect();
    let slope = if window.len() >= 2 {
        // Fit through the zero-lift point: C_l = a0 (α − α0).
        let (num, den) = window.iter().fold((0.0, 0.0), |(n, d), (a, c)| {
            let x = a - zero_lift;
            (n + x * c, d + x * x)
        });
        num / den
    } else {
        let i = alpha
            .partition_point(|&a| a <= zero_lift)
            .clamp(1, alpha.len() - 1);
        (cl[i] - cl[i - 1]) / (alpha[i] - alpha[i - 1])
    };
    (slope.is_finite() && slope > 0.0).then_some(AttachedLine { slope, zero_lift })
}

/// A place in a polar's table ([`Polar::between`]), to read any column there.
struct Between {
    i: usize,
    t: f64,
    h: f64,
    inside: bool,
}

impl Between {
    /// The column's value, linear between the rows.
    fn value(&self, v: &[f64]) -> f64 {
        v[self.i] + self.t * (v[self.i + 1] - v[self.i])
    }

    /// The column's slope in α: the rows' difference inside the table, zero beyond it.
    fn slope(&self, v: &[f64]) -> f64 {
        if self.inside {
            (v[self.i + 1] - v[self.i]) / self.h
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thin_airfoil() -> Polar {
        // Thin-airfoil line 2π(α + 2°) up to ±10°, flat beyond: stall.
        let alpha: Vec<f64> = (-20..=20).map(|d| (d as f64).to_radians()).collect();
        let cl = alpha
            .iter()
            .map(|&a| 2.0 * std::f64::consts::PI * (a.clamp(-0.17, 0.17) + 2f64.to_radians()))
            .collect();
        let cd = alpha.iter().map(|a| 0.01 + a * a).collect();
        let cm = alpha.iter().map(|a| -0.1 * a).collect();
        Polar::new(alpha, cl, cd, cm, "test").unwrap()
    }

    #[test]
    fn attached_line_is_read_off_the_polar() {
        let line = thin_airfoil().attached();
        assert!((line.zero_lift + 2f64.to_radians()).abs() < 1e-12);
        assert!((line.slope - 2.0 * std::f64::consts::PI).abs() < 1e-9);
    }

    #[test]
    fn lookup_is_linear_with_segment_slopes() {
        let p = thin_airfoil();
        let a = 0.5f64.to_radians();
        let c = p.at(a);
        let expected = 2.0 * std::f64::consts::PI * (a + 2f64.to_radians());
        assert!((c.cl - expected).abs() < 1e-12);
        assert!((c.dcl - 2.0 * std::f64::consts::PI).abs() < 1e-9);
        // Beyond the table: held, no slope.
        let far = p.at(1.0);
        assert_eq!(far.dcl, 0.0);
        assert_eq!(far.cl, p.at(20f64.to_radians()).cl);
    }

    #[test]
    fn blend_mixes_coefficients() {
        let p = thin_airfoil();
        let q = Polar::linear(5.0, 0.0, 0.02);
        let m = p.blend(&q, 0.25, "mix").unwrap();
        let a = 0.05;
        let expected = 0.75 * p.at(a).cl + 0.25 * q.at(a).cl;
        assert!((m.at(a).cl - expected).abs() < 1e-12);
    }

    #[test]
    fn a_cylinder_lifts_nowhere() {
        let alpha = vec![-std::f64::consts::PI, 0.0, std::f64::consts::PI];
        let p = Polar::new(alpha, vec![0.0; 3], vec![0.5; 3], vec![0.0; 3], "cyl").unwrap();
        assert_eq!(p.attached().slope, 0.0);
        assert_eq!(p.at(0.3).cd, 0.5);
        // The token lift of the IEA 15MW's cylinder polars (C_l = 1e-4, C_m = −1e-4) is a
        // cylinder too, and its line is exactly zero lift.
        let alpha = vec![-std::f64::consts::PI, 0.0, std::f64::consts::PI];
        let token = Polar::new(alpha, vec![1e-4; 3], vec![0.35; 3], vec![-1e-4; 3], "cyl");
        let line = token.unwrap().attached();
        assert_eq!((line.slope, line.zero_lift), (0.0, 0.0));
    }

    #[test]
    fn a_polar_without_lift_is_refused() {
        let alpha = vec![-0.1, 0.0, 0.1];
        let flat = vec![0.0; 3];
        assert!(Polar::new(
            alpha.clone(),
            vec![-0.1; 3],
            flat.clone(),
            flat.clone(),
            "x"
        )
        .is_err());
        assert!(Polar::new(
            vec![0.0, 0.0, 0.1],
            flat.clone(),
            flat.clone(),
            flat.clone(),
            "x"
        )
        .is_err());
        // A constant lift larger than a cylinder's token one is not a cylinder.
        let err = Polar::new(alpha, vec![0.01; 3], flat.clone(), flat, "x").unwrap_err();
        assert!(err.to_string().contains("±0.001"), "{err}");
    }
}
