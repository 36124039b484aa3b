//! The symmetric generalised eigenproblem `K x = λ M x` (M positive definite) reduced to a
//! standard one through the Cholesky factor of M: the uniform blade's natural modes and the
//! tabulated blade's both take this road.

use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// `L⁻¹ K L⁻ᵀ` with `M = LLᵀ` (Cholesky), symmetrised against round-off, and `L`. The
/// eigenvectors `y` of the result map back as `x = L⁻ᵀ y`.
pub fn cholesky_reduce(
    mass: &DMatrix<f64>,
    k: &DMatrix<f64>,
) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let chol = mass
        .clone()
        .cholesky()
        .ok_or_else(|| Error::numerical("mass matrix is not positive definite"))?;
    let l = chol.unpack();
    let lk = l
        .solve_lower_triangular(k)
        .ok_or_else(|| Error::numerical("singular mass factor"))?;
    let a = l
        .solve_lower_triangular(&lk.transpose())
        .ok_or_else(|| Error::numerical("singular mass factor"))?;
    Ok((symmetrised(a), l))
}

/// `(A + Aᵀ)/2`: a matrix symmetric in exact arithmetic, made so in floating point.
pub fn symmetrised(mut a: DMatrix<f64>) -> DMatrix<f64> {
    let at = a.transpose();
    a += at;
    a *= 0.5;
    a
}
