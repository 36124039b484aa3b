//! The axial induction a blade element's loading asks for (docs/model.md §12.2): momentum theory
//! where the rotor is lightly loaded and, where it is heavily loaded, one of two empirical
//! relations between the local thrust coefficient and the induction (`aero.high_thrust`):
//!
//! - `buhl`: momentum theory up to a = 0.4, Buhl's quadratic thrust beyond it (CCBlade and
//!   AeroDyn's convention; Buhl 2005, NREL/TP-500-36834);
//! - `madsen`: HAWC2's cubic `a = k3 C_T³ + k2 C_T² + k1 C_T` in the local thrust coefficient
//!   divided by the loss factor (Madsen, Larsen, Pirrung, Li, Zahle, Wind Energ. Sci. 5, 1–27,
//!   2020), which gives less induction than momentum theory near C_T ≈ 0.9.
//!
//! Input: the element's `k = σ' c_n / (4 F sin²φ)` at its inflow angle and the loss factor F.
//! Output: the axial induction a. Both relations are used inside the BEM's one residual in φ,
//! so each returns a finite a for every finite k.

use serde::{Deserialize, Serialize};

/// `aero.high_thrust`: the thrust–induction relation of a heavily loaded element.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum HighThrust {
    /// Momentum theory, Buhl's empirical thrust beyond a = 0.4.
    #[default]
    Buhl,
    /// HAWC2's cubic polynomial a(C_T / F) (Madsen et al. 2020).
    Madsen,
}

impl HighThrust {
    pub fn name(self) -> &'static str {
        match self {
            HighThrust::Buhl => "buhl",
            HighThrust::Madsen => "madsen",
        }
    }

    /// The axial induction of an element with `k = σ' c_n / (4 F sin²φ)` and loss factor `loss`.
    pub fn axial_induction(self, k: f64, loss: f64) -> f64 {
        match self {
            HighThrust::Buhl => buhl(k, loss),
            HighThrust::Madsen => madsen(k),
        }
    }
}

/// Momentum theory `a = k/(1 + k)` up to a = 0.4 (k = 2/3), Buhl's quadratic empirical thrust
/// beyond it, which meets momentum theory with equal slope at a = 0.4 and reaches C_T = 2 at
/// a = 1 (F = 1).
fn buhl(k: f64, loss: f64) -> f64 {
    if k <= 2.0 / 3.0 {
        return k / (1.0 + k);
    }
    let g1 = 2.0 * loss * k - (10.0 / 9.0 - loss);
    let g2 = (2.0 * loss * k - loss * (4.0 / 3.0 - loss)).max(0.0);
    let g3 = 2.0 * loss * k - (25.0 / 9.0 - 2.0 * loss);
    if g3.abs() < 1e-6 {
        1.0 - 1.0 / (2.0 * g2.sqrt())
    } else {
        (g1 - g2.sqrt()) / g3
    }
}

/// Coefficients `k1, k2, k3` of Madsen et al. (2020)'s `a = k3 C_T³ + k2 C_T² + k1 C_T` (their
/// k0 is 0), fitted to actuator-disc computations and used by HAWC2's BEM.
const MADSEN: [f64; 3] = [0.2460, 0.0586, 0.0883];

/// Madsen's polynomial in the local thrust coefficient over the loss factor.
fn madsen_polynomial(ct: f64) -> f64 {
    let [k1, k2, k3] = MADSEN;
    ct * (k1 + ct * (k2 + ct * k3))
}

/// The Newton step below which the implicit solve stops: it converges quadratically, with
/// `|g''/2g'|` of order one on [0, 1), so the induction after a step of 1e-8 is within about
/// 1e-16 of the root (far below what the inflow angle's 1e-10 rad resolves).
const LAST_NEWTON_STEP: f64 = 1e-8;
/// Newton steps allowed (from momentum theory's induction the solve takes a handful).
const MAX_NEWTON_STEPS: usize = 200;

/// The induction `a = P(C_T/F)` where the element's own thrust sets the local thrust coefficient:
/// `C_T/F = σ' c_n W² / (F U²) = 4 k (1 − a)²`, since `W = U (1 − a) / sin φ`. So a is the root
/// of `g(a) = P(4k(1 − a)²) − a`. For k > 0 on [0, 1), g falls (P rises for C_T ≥ 0 and 4k(1 − a)²
/// falls) and is convex (`g'' = P''(C) C'² + 8k P'(C) > 0`), `g(0) = P(4k) > 0` and `g(1) = −1`:
/// one root. Newton's method from any a below it (g ≥ 0) then climbs to it monotonically, never
/// past it (the tangent of a convex, falling g meets zero left of g's root), so it needs no
/// bracket; it is used rather than a bracketing search because it runs inside every evaluation
/// of the BEM's residual and converges in a few steps. The polynomial is a fit for positive
/// thrust; an element pushed upwind (k < 0: feathered, or the propeller-brake side) keeps
/// momentum theory, `a = k/(1 + k)`, whose slope at zero (¼) the polynomial's (0.246) matches to
/// 1.6 %.
fn madsen(k: f64) -> f64 {
    if k.is_nan() {
        return k;
    }
    if k <= 0.0 {
        return k / (1.0 + k);
    }
    if k == f64::INFINITY {
        // The fully blocked element (F·sin²φ underflowing): a → 1.
        return 1.0;
    }
    let [k1, k2, k3] = MADSEN;
    // Start at momentum theory's induction, within a few per cent of the root. From above the
    // root one Newton step lands below it (the tangent of a convex g lies under g), and from
    // there the climb is monotone; a step that lands further down than `bound` is lifted to it:
    // where `4k(1 − a)² = 2`, P = 1.43 > a so g > 0, a bound below the root that nears it as k
    // grows (at the bracket ends of the BEM's residual, φ → 0, k is huge and a → 1).
    let bound = (1.0 - (0.5 / k).sqrt()).max(0.0);
    let mut a = k / (1.0 + k);
    for _ in 0..MAX_NEWTON_STEPS {
        let b = 1.0 - a;
        let c = 4.0 * k * b * b;
        let g = madsen_polynomial(c) - a;
        let slope = -(k1 + c * (2.0 * k2 + 3.0 * k3 * c)) * 8.0 * k * b - 1.0;
        let step = -g / slope;
        a = (a + step).clamp(bound, 1.0);
        if step.abs() <= LAST_NEWTON_STEP {
            break;
        }
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The local thrust coefficient over F the element carries at induction a: `4k(1 − a)²`.
    fn thrust_coefficient(k: f64, a: f64) -> f64 {
        4.0 * k * (1.0 - a) * (1.0 - a)
    }

    #[test]
    fn buhl_meets_momentum_theory_at_a_04() {
        let below = buhl(2.0 / 3.0, 1.0);
        let above = buhl(2.0 / 3.0 + 1e-9, 1.0);
        assert!((below - 0.4).abs() < 1e-12);
        assert!((above - 0.4).abs() < 1e-6, "{above}");
        // Monotonic in k beyond.
        assert!(buhl(1.0, 1.0) > 0.4);
        assert!(buhl(2.0, 1.0) > buhl(1.0, 1.0));
    }

    /// The induction returned satisfies Madsen's relation at the thrust it implies, rises with
    /// the loading and stays below 1.
    #[test]
    fn madsen_solves_its_relation() {
        let mut last = 0.0;
        for k in [1e-6, 0.01, 0.1, 0.3, 0.6667, 1.0, 2.0, 10.0, 1e3, 1e8] {
            let a = madsen(k);
            let ct = thrust_coefficient(k, a);
            // g(a) = P(4k(1 − a)²) − a steepens with k: its value at the root is the induction
            // tolerance times that slope.
            let slope = 1.0 + 8.0 * k * (1.0 - a);
            assert!(
                (madsen_polynomial(ct) - a).abs() < 1e-13 * slope,
                "k {k}: a {a}"
            );
            assert!(a > last && a < 1.0, "k {k}: a {a}");
            last = a;
        }
        assert_eq!(madsen(0.0), 0.0);
        assert_eq!(madsen(f64::INFINITY), 1.0);
    }

    /// Against momentum theory `C_T = 4a(1 − a)`: within 2 % of a up to C_T = 0.5, and less
    /// induction where the rotor is heavily loaded: at C_T = 0.9 a = 0.333 against 0.342; at
    /// the element loading k where Buhl's a = 0.446 (C_T = 1, F = 1), 0.430.
    #[test]
    fn madsen_against_momentum_theory() {
        let momentum = |ct: f64| 0.5 * (1.0 - (1.0 - ct).sqrt());
        for ct in [0.1, 0.3, 0.5] {
            let (p, m) = (madsen_polynomial(ct), momentum(ct));
            assert!((p / m - 1.0).abs() < 0.02, "C_T {ct}: {p} against {m}");
        }
        let (p, m) = (madsen_polynomial(0.9), momentum(0.9));
        assert!(p < m - 0.008, "{p} against {m}");
        // Buhl at C_T = 1 (F = 1): the a where 8/9 − (4/9) a + (14/9) a² = 1, and the k that
        // gives it; Madsen at the same k induces less.
        let a_buhl = (4.0 / 9.0 + (16.0 / 81.0 + 4.0 * 14.0 / 81.0_f64).sqrt()) / (28.0 / 9.0);
        let k = 1.0 / (4.0 * (1.0 - a_buhl) * (1.0 - a_buhl));
        assert!((buhl(k, 1.0) - a_buhl).abs() < 1e-9, "{}", buhl(k, 1.0));
        assert!(madsen(k) < a_buhl - 0.015, "{} against {a_buhl}", madsen(k));
        // Negative loading keeps momentum theory under both relations.
        assert_eq!(madsen(-0.2), buhl(-0.2, 1.0));
    }
}
