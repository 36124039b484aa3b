//! Reduction of a real square matrix to upper Hessenberg form, `B = Q H Qᵀ`, by faer's
//! Householder reduction: the first step of the fast eigendecomposition in [`super::eigen`]
//! (docs/model.md §6.1). faer's reduction runs fused SIMD kernels and, from n² ≥ 65 536 (the
//! ONERA system of a real blade, 264 states), a blocked algorithm; nalgebra's, which this
//! replaced, applies one reflector at a time and was about a fifth of the ONERA eigen-analysis.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::evd::hessenberg;
use faer::linalg::householder;
use faer::{Conj, Mat, Par};
use nalgebra::DMatrix;

/// `(Q, H)` with `b = Q H Qᵀ`, `Q` orthogonal and `H` upper Hessenberg (exact zeros below the
/// subdiagonal). Sequential: the matrices are small and sweeps use every core across points.
pub(super) fn hessenberg_reduction(b: &DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = b.nrows();
    if n < 3 {
        return (DMatrix::identity(n, n), b.clone());
    }
    let par = Par::Seq;
    let block = faer::linalg::qr::no_pivoting::factor::recommended_block_size::<f64>(n - 1, n - 1);
    let mut h = Mat::<f64>::from_fn(n, n, |i, j| b[(i, j)]);
    let mut reflectors = Mat::<f64>::zeros(block, n - 1);
    let mut buffer = MemBuffer::new(StackReq::any_of(&[
        hessenberg::hessenberg_in_place_scratch::<f64>(n, block, par, Default::default()),
        householder::apply_block_householder_sequence_on_the_right_in_place_scratch::<f64>(
            n - 1,
            block,
            n - 1,
        ),
    ]));
    let stack = MemStack::new(&mut buffer);
    hessenberg::hessenberg_in_place(
        h.as_mut(),
        reflectors.as_mut(),
        par,
        stack,
        Default::default(),
    );
    // Q = I · (the reflector sequence), the reflectors' essential parts below the subdiagonal.
    let mut q = Mat::<f64>::identity(n, n);
    householder::apply_block_householder_sequence_on_the_right_in_place_with_conj(
        h.as_ref().submatrix(1, 0, n - 1, n - 1),
        reflectors.as_ref(),
        Conj::No,
        q.as_mut().submatrix_mut(1, 1, n - 1, n - 1),
        par,
        stack,
    );
    let h = DMatrix::from_fn(n, n, |i, j| if i > j + 1 { 0.0 } else { h[(i, j)] });
    let q = DMatrix::from_fn(n, n, |i, j| q[(i, j)]);
    (q, h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_h_qt_is_the_matrix_and_q_is_orthogonal() {
        // Sizes on both sides of faer's blocking threshold (n² = 65 536).
        for n in [1, 2, 3, 7, 84, 264] {
            let b = DMatrix::from_fn(n, n, |i, j| {
                ((i * 31 + j * 17) % 23) as f64 - 11.0 + (i == j) as u8 as f64 * 5.0
            });
            let (q, h) = hessenberg_reduction(&b);
            let scale = b.norm().max(1.0);
            assert!(
                (&q * &h * q.transpose() - &b).norm() < 1e-12 * scale,
                "n = {n}"
            );
            assert!((q.transpose() * &q - DMatrix::identity(n, n)).norm() < 1e-12 * n as f64);
            for j in 0..n {
                for i in j + 2..n {
                    assert_eq!(h[(i, j)], 0.0);
                }
            }
        }
    }
}
