//! faer's dense real eigendecomposition behind one call. Two solvers need it: the robust fallback
//! of the fast eigendecomposition in [`super::eigen`], and the natural modes of the strong form's
//! non-symmetric structural problem; this file sets faer up once for both.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::{self, ComputeEigenvectors, EvdError};
use faer::Auto;
use nalgebra::DMatrix;

/// Eigenvalues and eigenvectors of a real square matrix in faer's real form.
pub(crate) struct RealEvd {
    /// Real parts of the eigenvalues.
    pub(crate) re: Vec<f64>,
    /// Imaginary parts; a complex pair occupies two adjacent entries.
    pub(crate) im: Vec<f64>,
    /// Right eigenvectors, n × n: column j for a real root; for a complex pair at j, j + 1,
    /// columns j and j + 1 hold the real and imaginary parts of the vector of `re[j] + i·im[j]`.
    pub(crate) right: faer::Mat<f64>,
    /// Left eigenvectors in the same form, n × n when asked for, n × 0 otherwise.
    pub(crate) left: faer::Mat<f64>,
}

/// faer's full real eigendecomposition (Hessenberg reduction, Francis QR with aggressive early
/// deflation, back-substitution for the vectors). Its iteration cap and deflation tolerance are
/// faer's own defaults (the QR iteration stops at machine precision and gives up with
/// [`EvdError::NoConvergence`] past 30·max(10, n) sweeps). The reordering inside its deflation
/// has no cap of its own and spun forever on the defective clusters of exactly zero roots of
/// still air; neither caller passes such structure any more (the eigendecomposition isolates it
/// first, the strong form's M⁻¹K is dense). Sequential: our matrices are small (a thread pool's
/// start-up would dominate) and sweeps already use every core across points.
pub(crate) fn real_evd(a: &DMatrix<f64>, want_left: bool) -> Result<RealEvd, EvdError> {
    let n = a.nrows();
    let fa = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)]);
    let mut s_re = faer::diag::Diag::<f64>::zeros(n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(n);
    let mut right = faer::Mat::<f64>::zeros(n, n);
    let mut left = faer::Mat::<f64>::zeros(n, if want_left { n } else { 0 });
    let par = faer::Par::Seq;
    let left_flag = if want_left {
        ComputeEigenvectors::Yes
    } else {
        ComputeEigenvectors::No
    };
    let mut params: evd::EvdParams = Auto::<f64>::auto();
    params.schur.recommended_shift_count = shift_count;
    params.schur.recommended_deflation_window = deflation_window;
    let mut buffer = MemBuffer::new(evd::evd_scratch::<f64>(
        n,
        left_flag,
        ComputeEigenvectors::Yes,
        par,
        params.into(),
    ));
    evd::evd_real(
        fa.as_ref(),
        s_re.as_mut(),
        s_im.as_mut(),
        if want_left { Some(left.as_mut()) } else { None },
        Some(right.as_mut()),
        par,
        MemStack::new(&mut buffer),
        params.into(),
    )?;
    Ok(RealEvd {
        re: (0..n).map(|j| s_re[j]).collect(),
        im: (0..n).map(|j| s_im[j]).collect(),
        right,
        left,
    })
}

/// The sizes from which faer's own shift count and deflation window (LAPACK's `iparmq` table:
/// 32 of each from 150 to 590 states) are replaced by [`TUNED`].
const TUNED_SIZES: std::ops::Range<usize> = 150..300;

/// Shifts per QR sweep and the aggressive-early-deflation window in [`TUNED_SIZES`]: the
/// state matrices of a rotor, a turbine and an ONERA blade (256–264 states) decompose 10–15 %
/// faster with 20 than with 32 (docs/model.md §6.1); above 300 states (a turbine with the
/// dynamic-stall states, 444) no choice measured faster than faer's.
const TUNED: usize = 20;

extern "C" fn shift_count(n: usize, active: usize) -> usize {
    if TUNED_SIZES.contains(&n) {
        TUNED
    } else {
        faer_default(n, active, false)
    }
}

extern "C" fn deflation_window(n: usize, active: usize) -> usize {
    if TUNED_SIZES.contains(&n) {
        TUNED
    } else {
        faer_default(n, active, true)
    }
}

/// faer's default shift count (or window), read from its own parameters.
fn faer_default(n: usize, active: usize, window: bool) -> usize {
    let defaults: evd::EvdParams = Auto::<f64>::auto();
    if window {
        (defaults.schur.recommended_deflation_window)(n, active)
    } else {
        (defaults.schur.recommended_shift_count)(n, active)
    }
}
