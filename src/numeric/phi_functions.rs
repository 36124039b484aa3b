//! Exact propagators of the linear system `ẏ = A y + g(t)` over a step `h`: the matrix
//! exponential `e^{hA}` and the φ-functions `hφ1(hA)`, `h²φ2(hA)` that integrate a constant and
//! a linear forcing, for a ladder of step sizes at once, by balancing and scaling and squaring.
//! The exponential time stepper of the tip response is built on them.

use super::balance::{balanced, balancing_scale};
use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// The exact propagators of `ẏ = A y + g(t)` over a step `h`: `E = e^{hA}`,
/// `F1 = ∫₀ʰ e^{σA} dσ = hφ1(hA)` and `F2 = ∫₀ʰ e^{(h−σ)A} σ dσ = h²φ2(hA)`.
#[derive(Debug, Clone)]
pub struct Propagator {
    pub h: f64,
    pub e: DMatrix<f64>,
    pub f1: DMatrix<f64>,
    pub f2: DMatrix<f64>,
}

/// Propagators for the steps `h, h/2, …, h/2^levels` (index `j` is `h/2^j`), by scaling and
/// squaring: a Taylor series of `φ2` at `hA/2^s` small, then `s` doublings
/// `E(2t) = E²`, `F1(2t) = (I + E) F1`, `F2(2t) = (I + E) F2 + t F1`, which pass through every
/// finer level on the way. `A` is first balanced by a diagonal similarity (powers of two, so
/// exactly), which brings the norm that sets `s` from `~10⁴/h` to near the spectral radius on
/// the badly scaled aeroelastic matrices.
pub fn propagators(a: &DMatrix<f64>, h: f64, levels: usize) -> Result<Vec<Propagator>> {
    finite("state matrix", a)?;
    if !(h.is_finite() && h > 0.0) {
        return Err(Error::numerical(format!("time step {h} must be positive")));
    }
    let n = a.nrows();
    let d = balancing_scale(a);
    let balanced = balanced(a, &d);
    // ‖hA/2^s‖₁ ≤ ¼ makes the degree-11 Taylor remainder of φ2 below 1e-17.
    let norm = norm1(&balanced) * h;
    let mut s = levels;
    while norm / f64::powi(2.0, s as i32) > 0.25 {
        s += 1;
    }
    let tau = h / f64::powi(2.0, s as i32);
    let x = &balanced * tau;
    let id = DMatrix::<f64>::identity(n, n);
    let mut p2 = &id * taylor_coefficient(TAYLOR_DEGREE + 2);
    for j in (0..TAYLOR_DEGREE).rev() {
        p2 = &x * p2 + &id * taylor_coefficient(j + 2);
    }
    let p1 = &id + &x * &p2;
    let mut e = &id + &x * &p1;
    let mut f1 = p1 * tau;
    let mut f2 = p2 * (tau * tau);
    let mut t = tau;
    let unbalance = |m: &DMatrix<f64>| DMatrix::from_fn(n, n, |i, j| m[(i, j)] * d[i] / d[j]);
    let mut out = Vec::with_capacity(levels + 1);
    for k in 0..=s {
        if s - k <= levels {
            out.push(Propagator {
                h: t,
                e: unbalance(&e),
                f1: unbalance(&f1),
                f2: unbalance(&f2),
            });
        }
        if k == s {
            break;
        }
        let i_plus_e = &id + &e;
        f2 = &i_plus_e * &f2 + &f1 * t;
        f1 = &i_plus_e * &f1;
        e = &e * &e;
        t *= 2.0;
    }
    out.reverse();
    for p in &out {
        finite("step matrix e^(A h)", &p.e)?;
        finite("step matrix h φ1(A h)", &p.f1)?;
        finite("step matrix h² φ2(A h)", &p.f2)?;
    }
    Ok(out)
}

/// Degree of the Taylor polynomial of `φ2` at the scaled matrix.
const TAYLOR_DEGREE: usize = 11;

/// `1/k!`.
fn taylor_coefficient(k: usize) -> f64 {
    1.0 / (1..=k).map(|v| v as f64).product::<f64>()
}

/// Largest column sum.
fn norm1(m: &DMatrix<f64>) -> f64 {
    m.column_iter()
        .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Every entry finite, or a numerical error naming the matrix.
fn finite(what: &str, m: &DMatrix<f64>) -> Result<()> {
    if m.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::numerical(format!("{what} has non-finite entries")))
    }
}
