//! Galerkin trial functions and quadrature (docs/model.md §4).
//!
//! Torsion: `Φ_j = sin((2j−1)πx/2L)`. Flap: the clamped–free beam functions
//! `U_j = cosh βx − cos βx − σ(sinh βx − sin βx)` with `cos βL cosh βL = −1`. Written as printed,
//! `U_j` subtracts two numbers of size `e^{βL}` and loses every digit beyond j ≈ 8; here the growing
//! and decaying exponentials are separated (`U = A e^{βx} + B e^{−βx} − cos βx + σ sin βx` with the
//! `e^{βL}` folded into `A`), so every term stays O(1) for any j.

use nalgebra::DVector;
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::{Arc, OnceLock};

/// Largest Gauss rule kept in [`gauss_rule`]'s cache (the basis needs 3N + 12 ≤ 132 for N ≤ 40).
const CACHED_RULES: usize = 256;

/// Largest j whose root [`bending_root`] caches.
const CACHED_ROOTS: usize = 256;

/// A Gauss–Legendre rule on `[-1, 1]`: (nodes, weights).
pub type GaussRule = (Vec<f64>, Vec<f64>);

/// [`gauss_legendre`] computed once per n and shared: every assembly and every strip-theory
/// evaluation reuses the rule instead of re-running Newton on `P_n` (whose recurrence divides
/// at every step). Write-once cells, so sharing across threads needs no lock after the first call.
pub fn gauss_rule(n: usize) -> Arc<GaussRule> {
    static RULES: [OnceLock<Arc<GaussRule>>; CACHED_RULES + 1] =
        [const { OnceLock::new() }; CACHED_RULES + 1];
    match RULES.get(n) {
        Some(cell) => cell.get_or_init(|| Arc::new(gauss_legendre(n))).clone(),
        None => Arc::new(gauss_legendre(n)),
    }
}

/// Gauss–Legendre rule with `n` points on `[-1, 1]`: (nodes ascending, weights) (docs/model.md §4).
/// Exact for polynomials of degree ≤ 2n−1. Newton on `P_n` from Tricomi's initial guesses, which
/// converge in a few steps for any n; symmetric nodes are mirrored so the rule is exactly symmetric.
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        // Tricomi's approximation of the (i+1)-th largest root.
        let theta = PI * (4.0 * i as f64 + 3.0) / (4.0 * nf + 2.0);
        let mut x = (1.0 - (nf - 1.0) / (8.0 * nf * nf * nf)) * theta.cos();
        // Newton converges quadratically from Tricomi's guess; once a step is below 1e-13 the
        // next one reaches round-off, so take exactly one more (a tighter test could wait forever
        // on round-off noise).
        for _ in 0..20 {
            let (p, d) = legendre_with_derivative(n, x);
            let dx = p / d;
            x -= dx;
            if dx.abs() <= 1e-13 {
                let (p, d) = legendre_with_derivative(n, x);
                x -= p / d;
                break;
            }
        }
        let dp = legendre_with_derivative(n, x).1;
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = w;
        weights[n - 1 - i] = w;
    }
    if n % 2 == 1 {
        nodes[n / 2] = 0.0;
    }
    (nodes, weights)
}

/// `(P_n(x), P_n'(x))` by the three-term recurrence.
fn legendre_with_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let nf = n as f64;
    (p1, nf * (x * p1 - p0) / (x * x - 1.0))
}

/// `β_j L`, the j-th root (j ≥ 1) of `cos βL cosh βL = −1` (docs/model.md §4).
///
/// Newton on the equivalent `cos z + sech z = 0`, which stays O(1) for any j (cosh overflows
/// near j ≈ 230, sech just underflows to 0 and the root becomes `(2j−1)π/2` exactly, as it should).
/// Starts from the asymptotic root `(2j−1)π/2`; converges in ≤ 6 steps for every j. Computed once
/// per j (≤ 256) and cached, since every basis evaluation needs it.
pub fn bending_root(j: usize) -> f64 {
    static ROOTS: [OnceLock<f64>; CACHED_ROOTS + 1] = [const { OnceLock::new() }; CACHED_ROOTS + 1];
    let j = j.max(1);
    match ROOTS.get(j) {
        Some(cell) => *cell.get_or_init(|| newton_bending_root(j)),
        None => newton_bending_root(j),
    }
}

fn newton_bending_root(j: usize) -> f64 {
    let mut z = (2 * j - 1) as f64 * FRAC_PI_2;
    for _ in 0..50 {
        let sech = 1.0 / z.cosh();
        let g = z.cos() + sech;
        let dg = -z.sin() - sech * z.tanh();
        let dz = g / dg;
        z -= dz;
        if dz.abs() <= 4.0 * f64::EPSILON * z {
            break;
        }
    }
    z
}

/// The trial functions of one blade: N torsion sines and N cantilever bending functions on `[0, L]`.
#[derive(Debug, Clone)]
pub struct Basis {
    pub n: usize,
    pub length: f64,
}

/// The constants of one bending function in the cancellation-free form
/// `U = A e^{β(x−L)} + B e^{−βx} − cos βx + σ sin βx` (`A` already carries `e^{βL}`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct BendingMode {
    /// β (1/m).
    pub beta: f64,
    /// Coefficient of `e^{β(x−L)}`: `½(1−σ)e^{βL}`, O(1).
    pub a: f64,
    /// Coefficient of `e^{−βx}`: `½(1+σ)`.
    pub b: f64,
    /// σ_j.
    pub sigma: f64,
}

impl BendingMode {
    /// Constants of `U_j` for a blade of length `length` (docs/model.md §4). With `D = 1 + e^{−2b} +
    /// 2 cos b e^{−b}` (`b = β_jL`): `σ = (1 − e^{−2b} − 2 sin b e^{−b})/D` and
    /// `½(1−σ)e^{b} = (e^{−b} + cos b + sin b)/D`, neither of which cancels.
    pub(crate) fn new(j: usize, length: f64) -> BendingMode {
        let bl = bending_root(j);
        let (s, c) = bl.sin_cos();
        let e = (-bl).exp();
        let d = 1.0 + e * e + 2.0 * c * e;
        let sigma = (1.0 - e * e - 2.0 * s * e) / d;
        BendingMode {
            beta: bl / length,
            a: (e + c + s) / d,
            b: 0.5 * (1.0 + sigma),
            sigma,
        }
    }

    /// `U^(deriv)(x)`, deriv 0..=3.
    #[inline]
    pub(crate) fn eval(&self, x: f64, length: f64, deriv: usize) -> f64 {
        let xi = self.beta * x;
        let grow = self.a * (self.beta * (x - length)).exp();
        let decay = self.b * (-xi).exp();
        let (s, c) = xi.sin_cos();
        // k-th derivatives of cos and sin with respect to their argument.
        let (dcos, dsin) = match deriv % 4 {
            0 => (c, s),
            1 => (-s, c),
            2 => (-c, -s),
            _ => (s, -c),
        };
        let sign = if deriv % 2 == 0 { 1.0 } else { -1.0 };
        self.beta.powi(deriv as i32) * (grow + sign * decay - dcos + self.sigma * dsin)
    }

    /// `(U, U', U'')` at `x` sharing one set of transcendental evaluations (assembly hot path).
    #[inline]
    pub(crate) fn eval012(&self, x: f64, length: f64) -> [f64; 3] {
        let xi = self.beta * x;
        let grow = self.a * (self.beta * (x - length)).exp();
        let decay = self.b * (-xi).exp();
        let (s, c) = xi.sin_cos();
        let beta = self.beta;
        [
            grow + decay - c + self.sigma * s,
            beta * (grow - decay + s + self.sigma * c),
            beta * beta * (grow + decay + c - self.sigma * s),
        ]
    }
}

/// Wavenumber of `Φ_j`: `(2j−1)π/2L`.
#[inline]
pub(crate) fn torsion_wavenumber(j: usize, length: f64) -> f64 {
    (2 * j - 1) as f64 * FRAC_PI_2 / length
}

impl Basis {
    pub fn new(n: usize, length: f64) -> Basis {
        Basis { n, length }
    }

    /// `Φ_j^(deriv)(x)` for j = 1..N, deriv 0..=2 (docs/model.md §4).
    pub fn torsion(&self, x: f64, deriv: usize) -> DVector<f64> {
        DVector::from_iterator(
            self.n,
            (1..=self.n).map(|j| {
                let k = torsion_wavenumber(j, self.length);
                let (s, c) = (k * x).sin_cos();
                match deriv {
                    0 => s,
                    1 => k * c,
                    2 => -k * k * s,
                    _ => -k * k * k * c,
                }
            }),
        )
    }

    /// `U_j^(deriv)(x)` for j = 1..N, deriv 0..=3 (docs/model.md §4), stable for any j.
    pub fn bending(&self, x: f64, deriv: usize) -> DVector<f64> {
        DVector::from_iterator(
            self.n,
            (1..=self.n).map(|j| BendingMode::new(j, self.length).eval(x, self.length, deriv)),
        )
    }

    /// Gauss points for the Galerkin integrals of this basis, mapped to `[0, L]`: (x, weight).
    /// The richest integrand, `U''_N U''_N`, oscillates like `cos(2β_N x)`, i.e. `(2N−1)π/2` radians
    /// over the half-span; Gauss–Legendre resolves `e^{iωt}` on `[−1, 1]` to round-off once
    /// `n ≳ 0.7ω + 10`, so `3N + 12` points leave a wide margin (checked against a doubled rule
    /// in the tests).
    pub fn quadrature(&self) -> (Vec<f64>, Vec<f64>) {
        let rule = gauss_rule(Self::quadrature_points(self.n));
        let (t, w) = (&rule.0, &rule.1);
        let h = 0.5 * self.length;
        (
            t.iter().map(|t| h * (t + 1.0)).collect(),
            w.iter().map(|w| h * w).collect(),
        )
    }

    /// Number of Gauss points used for a basis of N functions per field.
    pub fn quadrature_points(n: usize) -> usize {
        3 * n + 12
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_match_model_table() {
        let expected = [1.8751041, 4.6940911, 7.8547574, 10.9955407, 14.1371684];
        for (j, e) in expected.iter().enumerate() {
            assert!((bending_root(j + 1) - e).abs() < 1e-7, "j={}", j + 1);
        }
        for j in [6, 20, 100, 1000] {
            // cos z + sech z = 0 is the same equation without cosh's overflow.
            let z = bending_root(j);
            assert!((z.cos() + 1.0 / z.cosh()).abs() < 1e-13, "j={j}");
            assert!((z - (2 * j - 1) as f64 * FRAC_PI_2).abs() < 0.02);
        }
    }

    #[test]
    fn gauss_integrates_polynomials_exactly() {
        for n in [1, 2, 5, 12, 40] {
            let (x, w) = gauss_legendre(n);
            for deg in 0..2 * n {
                let s: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(deg as i32)).sum();
                let exact = if deg % 2 == 1 {
                    0.0
                } else {
                    2.0 / (deg as f64 + 1.0)
                };
                assert!((s - exact).abs() < 1e-13, "n={n} deg={deg}: {s} vs {exact}");
            }
        }
    }

    #[test]
    fn bending_matches_textbook_form_for_low_modes() {
        let l = 2.0;
        let basis = Basis::new(4, l);
        for &x in &[0.0, 0.3, 1.1, 2.0] {
            let u = basis.bending(x, 0);
            for j in 1..=4 {
                let b = bending_root(j);
                let beta = b / l;
                let sigma = (b.sinh() - b.sin()) / (b.cosh() + b.cos());
                let naive = (beta * x).cosh()
                    - (beta * x).cos()
                    - sigma * ((beta * x).sinh() - (beta * x).sin());
                assert!((u[j - 1] - naive).abs() < 1e-9, "j={j} x={x}");
            }
        }
    }
}
