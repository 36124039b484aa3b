//! Diagonal balancing of a real square matrix: D⁻¹AD, with rows and columns of comparable norm,
//! has the same eigenvalues and a far smaller norm on badly scaled state matrices (which mix 1 and
//! 10⁵ rad/s roots). The eigendecomposition balances before its QR iteration, the simulator
//! before scaling and squaring; both use this one routine.

use nalgebra::DMatrix;

/// Sweep cap of [`balancing_scale`]: a few sweeps suffice in practice (LAPACK's `gebal` has no
/// cap at all); the cap only bounds the work on pathological input.
const MAX_SWEEPS: usize = 100;

/// Scale factors are powers of the radix, so scaling is exact in floating point.
const RADIX: f64 = 2.0;

/// A scale changes only when it brings its row + column norm sum below this fraction of what it
/// was (LAPACK's 0.95).
const MIN_REDUCTION: f64 = 0.95;

/// Diagonal scaling D (powers of two) such that D⁻¹AD has comparable off-diagonal row and column
/// 1-norms (Parlett & Reinsch, as LAPACK's `gebal`; its permutation step is `isolate.rs`, which
/// the eigendecomposition runs first).
///
/// Sweeps over the rows until a sweep changes no scale, at most [`MAX_SWEEPS`]; tolerance: a
/// scale changes only when that cuts its row + column sum by at least 5 % ([`MIN_REDUCTION`]).
pub(crate) fn balancing_scale(a: &DMatrix<f64>) -> Vec<f64> {
    let n = a.nrows();
    let mut d = vec![1.0; n];
    // D⁻¹AD as it stands (exact: every update is by a power of two).
    let mut m = a.clone();
    for _ in 0..MAX_SWEEPS {
        let mut changed = false;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in (0..n).filter(|&j| j != i) {
                c += m[(j, i)].abs();
                r += m[(i, j)].abs();
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let before = c + r;
            let mut f = 1.0;
            while c < r / RADIX {
                (c, r, f) = (c * RADIX, r / RADIX, f * RADIX);
            }
            while c >= r * RADIX {
                (c, r, f) = (c / RADIX, r * RADIX, f / RADIX);
            }
            if c + r < MIN_REDUCTION * before {
                changed = true;
                d[i] *= f;
                for j in 0..n {
                    m[(j, i)] *= f;
                    m[(i, j)] /= f;
                }
            }
        }
        if !changed {
            break;
        }
    }
    d
}

/// D⁻¹AD for the scale `d` of [`balancing_scale`].
pub(crate) fn balanced(a: &DMatrix<f64>, d: &[f64]) -> DMatrix<f64> {
    let n = a.nrows();
    DMatrix::from_fn(n, n, |i, j| a[(i, j)] * d[j] / d[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balancing_evens_out_a_badly_scaled_matrix_exactly() {
        // An oscillator written in units 10⁴ apart: off-diagonal entries 1e-4 and 1e4.
        let a = DMatrix::from_row_slice(2, 2, &[-0.1, 1e-4, -1e4, -0.2]);
        let d = balancing_scale(&a);
        assert!(d.iter().all(|s| s.log2().fract() == 0.0), "{d:?}");
        let b = balanced(&a, &d);
        let ratio = (b[(0, 1)] / b[(1, 0)]).abs();
        assert!((0.25..4.0).contains(&ratio), "{ratio}");
        // The diagonal is untouched and the product of the off-diagonal pair is kept.
        assert_eq!((b[(0, 0)], b[(1, 1)]), (a[(0, 0)], a[(1, 1)]));
        assert_eq!(b[(0, 1)] * b[(1, 0)], a[(0, 1)] * a[(1, 0)]);
    }
}
