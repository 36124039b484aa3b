//! Dense products of tall, thin nalgebra matrices on faer's matrix-product kernels.
//!
//! Why: a blade's reduced matrices `Φᵀ A Φ` multiply a basis of a few hundred rows by about 80
//! columns by itself, five Fourier samples and six matrices each whenever the blade's sections
//! change (docs/model.md §11.8). nalgebra's `tr_mul` forms each entry as one dot product; faer's
//! blocked kernels do the same product several times faster.

use faer::linalg::matmul::matmul;
use faer::{Accum, MatMut, MatRef, Par};
use nalgebra::DMatrix;

/// `aᵀ b`, on the calling thread (callers run several at once on the cores).
pub fn tr_mul(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    assert_eq!(a.nrows(), b.nrows(), "tr_mul: row counts differ");
    let mut out = DMatrix::zeros(a.ncols(), b.ncols());
    let (m, n) = (out.nrows(), out.ncols());
    matmul(
        MatMut::from_column_major_slice_mut(out.as_mut_slice(), m, n),
        Accum::Replace,
        MatRef::from_column_major_slice(a.as_slice(), a.nrows(), a.ncols()).transpose(),
        MatRef::from_column_major_slice(b.as_slice(), b.nrows(), b.ncols()),
        1.0,
        Par::Seq,
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tr_mul_is_the_transposed_product() {
        let a = DMatrix::from_fn(300, 17, |i, j| {
            ((i * 7 + j * 3) % 11) as f64 - 5.0 + 0.1 * j as f64
        });
        let b = DMatrix::from_fn(300, 9, |i, j| ((i * 5 + j) % 13) as f64 * 0.5 - 3.0);
        let expected = a.transpose() * &b;
        let got = tr_mul(&a, &b);
        assert_eq!(got.shape(), (17, 9));
        let scale = expected.abs().max();
        assert!((got - expected).abs().max() <= 1e-13 * scale);
    }
}
