//! Dense eigendecomposition of a real non-symmetric matrix (docs/model.md §6.1, §10): every
//! eigenvalue with its right and, when asked, left eigenvector, one entry per real root or
//! conjugate pair. This is the solver behind the stability analysis; nalgebra alone would not do
//! (it has no non-symmetric eigenvectors, and its eigenvalue-only Schur solver can spin on NaN
//! input). Isolation by permutation first takes out the roots that need no iteration (the
//! still-air aerodynamic states); on the rest the fast path (balancing, Hessenberg QR, inverse
//! iteration) falls back on faer's full decomposition.

use super::balance::{balanced, balancing_scale};
use super::eigenpairs::eigenpairs;
use super::faer_evd::real_evd;
use super::hessenberg_reduction::hessenberg_reduction;
use super::isolate::Isolation;
use super::roots::{Roots, Solver};
use crate::error::{Error, Result};
use nalgebra::{Complex, DMatrix};

/// All eigenvalues with right and left eigenvectors of a real square matrix.
///
/// Errors: a non-square or non-finite matrix, no convergence of the QR iteration, or non-finite
/// output. See [`decompose`] for the method.
pub fn eigen_decomposition(a: &DMatrix<f64>) -> Result<Roots> {
    decompose(a, true)
}

/// Eigenvalues with right eigenvectors, and left eigenvectors when `want_left` (otherwise
/// [`Roots::left`] is empty, n × 0).
///
/// Method. First, isolation by permutation (`isolate.rs`, LAPACK `gebal` job 'P') moves out every
/// row and column that is exactly zero off the diagonal within the rest: their roots are
/// diagonal entries, found without iteration, and only the active block B goes on (B is the
/// matrix itself when nothing isolates, and then nothing below changes); every vector of the
/// whole matrix follows from B's by block back-substitution. This is what makes still air
/// solvable: there the aerodynamic states have no dynamics, hundreds of exactly zero roots in one
/// defective cluster that fails inverse iteration and made faer's deflation spin forever;
/// isolated, they reach neither solver, and B is the structure alone.
///
/// Then B is balanced (D⁻¹BD), and one of two solvers, chosen by the active block's size
/// ([`SCHUR_FROM`], measured), finds its roots; each is the other's fallback.
///
/// *The fast path*, below [`SCHUR_FROM`] states (a blade's 20–84): reduction to Hessenberg form
/// H = QᵀD⁻¹BDQ (faer's Householder reduction, `hessenberg_reduction.rs`); the eigenvalues from
/// the double-shift QR iteration on H *without* accumulating the Schur form or its vectors (a
/// port of LAPACK's `dlahqr` with `wantt = wantz = false`: Ahues–Tisseur deflation, exceptional
/// shifts, an iteration cap of 30·max(10, n) per eigenvalue). Each eigenvector, one per real
/// root or conjugate pair, then comes from inverse iteration with the converged eigenvalue as
/// shift (LAPACK `dhsein`/`dlaein`): one LU factorisation of the Hessenberg H − λI, O(n²), with
/// tiny pivots replaced by ε‖H‖, then one or two solves; the left vector reuses the same factors
/// (transposed solve). Both are accepted only when their residual ‖Hx − λx‖ is at round-off
/// level; vectors map back by Q and D. On small matrices this does a fraction of faer's flops:
/// measured single-threaded, 20-state quasi-steady system ≈ 110 µs → ≈ 65 µs without left
/// vectors (what the stability analysis asks for when there are no aero states), 56-state
/// theodorsen system ≈ 1.7 ms → ≈ 1.2 ms with both (`part_eigen_*` in the stability bench).
/// nalgebra's bounded `Schur::try_new` was also measured and is slower than faer here (it
/// always accumulates Q, and it has no exceptional shifts). Roots of (nearly) equal value get
/// different start vectors and are orthogonalised against each other, so an exactly repeated
/// root still returns a basis of its eigenspace.
///
/// *faer's full decomposition* (Francis QR with small bulges and aggressive early deflation,
/// the Schur vectors, back-substitution for every vector), from [`SCHUR_FROM`] states up (HGM
/// and ONERA blades, a rotor, a turbine): one inverse iteration per root costs O(n²) each, O(n³)
/// in all with poor locality, where faer's blocked sweeps run at matrix-product speed.
///
/// Whenever the first choice fails — the QR iteration hits its cap, a residual check fails
/// (defective or extremely ill-conditioned roots), faer reports no convergence or returns
/// non-finite values or vectors — B goes to the
/// other ([`Solver::Fallback`]); B never has a row or column that is zero off the diagonal, the
/// structure on which faer's deflation spun. If both fail the result is an
/// [`Error::Numerical`]. Non-finite input is rejected up front, so neither path can spin on NaN.
pub fn decompose(a: &DMatrix<f64>, want_left: bool) -> Result<Roots> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(Error::numerical(format!(
            "eigen-analysis needs a square matrix, got {}×{}",
            n,
            a.ncols()
        )));
    }
    if let Some(((i, j), v)) = a
        .iter()
        .enumerate()
        .map(|(k, v)| ((k % n.max(1), k / n.max(1)), v))
        .find(|(_, v)| !v.is_finite())
    {
        return Err(Error::numerical(format!(
            "state matrix entry ({i}, {j}) is {v}; cannot compute eigenvalues"
        )));
    }
    let isolation = Isolation::of(a);
    let roots = if isolation.is_trivial() {
        active_roots(a, want_left)?
    } else {
        let active = active_roots(&isolation.active_block(a), want_left)?;
        isolation.roots(a, active, want_left)
    };
    let finite = |c: &Complex<f64>| c.re.is_finite() && c.im.is_finite();
    if !roots.values.iter().all(finite)
        || !roots.vectors.iter().all(finite)
        || !roots.left.iter().all(finite)
    {
        return Err(Error::numerical(
            "eigen-analysis produced non-finite eigenvalues or eigenvectors",
        ));
    }
    Ok(roots)
}

/// From this many states of the active block up, faer's complete decomposition comes first and
/// the fast path is its fallback; below, the other way round: the two take the same time at 84
/// states, faer less from 104 (measured, docs/model.md §6.1 step 2).
const SCHUR_FROM: usize = 96;

/// Balancing, then the fast path or faer's decomposition, each the other's fallback, on a matrix
/// with nothing to isolate (see [`decompose`]); vectors in the matrix's own coordinates.
fn active_roots(a: &DMatrix<f64>, want_left: bool) -> Result<Roots> {
    let n = a.nrows();
    if n == 0 {
        return Ok(Roots {
            values: Vec::new(),
            vectors: DMatrix::zeros(0, 0),
            left: DMatrix::zeros(0, 0),
            solver: Solver::Fast,
        });
    }
    // Balance first: D⁻¹AD has the same eigenvalues, rows and columns of comparable norm, and
    // the QR iteration converges faster and more accurately on it (state matrices mix 1 and
    // 10⁵ rad/s roots). Right vectors map back as D r, left vectors as D⁻¹ l.
    let scale = balancing_scale(a);
    let b = balanced(a, &scale);
    let ((values, right, left), solver) = if n >= SCHUR_FROM {
        match faer_decomposition(&b, want_left) {
            Ok(r) => (r, Solver::Schur),
            Err(e) => (
                fast_decomposition(&b, want_left).ok_or(e)?,
                Solver::Fallback,
            ),
        }
    } else {
        match fast_decomposition(&b, want_left) {
            Some(r) => (r, Solver::Fast),
            None => (faer_decomposition(&b, want_left)?, Solver::Fallback),
        }
    };
    Ok(Roots {
        values,
        vectors: DMatrix::from_fn(n, right.ncols(), |i, k| right[(i, k)] * scale[i]),
        left: DMatrix::from_fn(n, left.ncols(), |i, k| left[(i, k)] / scale[i]),
        solver,
    })
}

pub(crate) type Decomposition = (
    Vec<Complex<f64>>,
    DMatrix<Complex<f64>>,
    DMatrix<Complex<f64>>,
);

/// Hessenberg reduction, eigenvalue-only QR, inverse iteration (see [`decompose`]). `None` when
/// the QR iteration does not converge or a vector fails its residual check.
pub(crate) fn fast_decomposition(b: &DMatrix<f64>, want_left: bool) -> Option<Decomposition> {
    let n = b.nrows();
    let (q, h) = hessenberg_reduction(b);
    let hnorm = h.norm().max(f64::MIN_POSITIVE);
    // One entry per real root and per conjugate pair (the member with ω > 0), with its vectors
    // (real roots in real arithmetic, pairs in complex; on two threads, `eigenpairs.rs`).
    let (values, vectors) = eigenpairs(&h, hnorm, want_left)?;
    let k = values.len();
    let mut xr = DMatrix::<f64>::zeros(n, k);
    let mut xi = DMatrix::<f64>::zeros(n, k);
    let (mut yr, mut yi) = if want_left {
        (DMatrix::<f64>::zeros(n, k), DMatrix::<f64>::zeros(n, k))
    } else {
        (DMatrix::zeros(n, 0), DMatrix::zeros(n, 0))
    };
    for (c, (x, w)) in vectors.into_iter().enumerate() {
        for i in 0..n {
            xr[(i, c)] = x[i].re;
            xi[(i, c)] = x[i].im;
        }
        if let Some(w) = w {
            // wᵀH = λwᵀ, so l = w̄ satisfies lᴴH = λlᴴ.
            for i in 0..n {
                yr[(i, c)] = w[i].re;
                yi[(i, c)] = -w[i].im;
            }
        }
    }
    let combine = |re: DMatrix<f64>, im: DMatrix<f64>| {
        DMatrix::from_fn(re.nrows(), re.ncols(), |i, j| {
            Complex::new(re[(i, j)], im[(i, j)])
        })
    };
    let right = combine(&q * xr, &q * xi);
    let left = combine(&q * yr, &q * yi);
    Some((values, right, left))
}

/// faer's full real eigendecomposition (see [`decompose`]), packed one entry per real root and
/// per conjugate pair (the member with ω > 0).
pub(crate) fn faer_decomposition(b: &DMatrix<f64>, want_left: bool) -> Result<Decomposition> {
    let n = b.nrows();
    let evd = real_evd(b, want_left)
        .map_err(|e| Error::numerical(format!("eigenvalue iteration failed: {e:?}")))?;
    // Each root's first column in faer's real form and, for a pair (whose imaginary part is the
    // next column), the sign that makes its ω positive.
    let mut roots: Vec<(usize, Option<f64>)> = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        if evd.im[j] == 0.0 || j + 1 == n {
            roots.push((j, None));
            j += 1;
        } else {
            roots.push((j, Some(evd.im[j].signum())));
            j += 2;
        }
    }
    let values: Vec<Complex<f64>> = roots
        .iter()
        .map(|&(j, sign)| Complex::new(evd.re[j], sign.map_or(0.0, |s| s * evd.im[j])))
        .collect();
    let non_finite = || {
        Error::numerical(
            "faer's eigendecomposition produced non-finite eigenvalues or eigenvectors",
        )
    };
    if !values.iter().all(|c| c.re.is_finite() && c.im.is_finite()) {
        return Err(non_finite());
    }
    // faer's back-substitution divides by differences of eigenvalues: inside a cluster of
    // exactly repeated roots (many identical stations) its vectors grow towards overflow (their
    // participation products overflowed), or overflow, and extreme scaling can give NaN: each
    // vector is scaled by its largest component, and one that is not finite is an error (on
    // which `decompose` turns to the fast path where faer came first).
    let pack = |m: &faer::Mat<f64>| -> Option<DMatrix<Complex<f64>>> {
        let columns = if m.ncols() == 0 { 0 } else { roots.len() };
        let mut out = DMatrix::<Complex<f64>>::zeros(n, columns);
        for (mut column, &(j, sign)) in out.column_iter_mut().zip(&roots) {
            let re = m.col_as_slice(j);
            let im = sign.map(|s| (s, m.col_as_slice(j + 1)));
            let mut largest = 0.0f64;
            for (i, c) in column.iter_mut().enumerate() {
                *c = Complex::new(re[i], im.map_or(0.0, |(s, im)| s * im[i]));
                let size = c.re.abs().max(c.im.abs());
                if !size.is_finite() {
                    return None;
                }
                largest = largest.max(size);
            }
            if largest > 0.0 {
                column.unscale_mut(largest);
            }
        }
        Some(out)
    };
    let right = pack(&evd.right).ok_or_else(non_finite)?;
    let left = pack(&evd.left).ok_or_else(non_finite)?;
    Ok((values, right, left))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn decomposes_a_damped_oscillator_and_a_real_root() {
        // ẍ + 2ζω ẋ + ω² x = 0 (ζ = 0.1, ω = 3) plus ẏ = −2y.
        let (z, w) = (0.1, 3.0);
        let a = DMatrix::from_row_slice(
            3,
            3,
            &[0.0, 1.0, 0.0, -w * w, -2.0 * z * w, 0.0, 0.0, 0.0, -2.0],
        );
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.values.len(), 2);
        let osc = r.values.iter().find(|l| l.im > 0.0).unwrap();
        assert!((osc.re + z * w).abs() < 1e-12);
        assert!((osc.im - w * (1.0 - z * z).sqrt()).abs() < 1e-12);
        // A r = λ r and lᴴ A = λ lᴴ for every returned root.
        let ac = a.map(|v| Complex::new(v, 0.0));
        for (k, l) in r.values.iter().enumerate() {
            let v = r.vectors.column(k);
            let res = &ac * v - v * *l;
            assert!(res.norm() < 1e-10 * v.norm());
            let w = r.left.column(k);
            let res = w.adjoint() * &ac - w.adjoint() * *l;
            assert!(res.norm() < 1e-10 * w.norm());
        }
        // The real root lives in the third state only.
        let k = r.values.iter().position(|l| l.im == 0.0).unwrap();
        let p = r.participation(k);
        assert!((p[2] - 1.0).abs() < 1e-12);
    }

    /// An `n × n` state matrix whose first states are `oscillators` identical decoupled
    /// oscillators `ẍ = k x + c ẋ` (`[k, c]`), then `reals` identical real roots `root`; the rest
    /// zero, for the caller to fill.
    pub(crate) fn repeated_roots(
        n: usize,
        oscillators: usize,
        [k, c]: [f64; 2],
        reals: usize,
        root: f64,
    ) -> DMatrix<f64> {
        let mut a = DMatrix::<f64>::zeros(n, n);
        for o in 0..oscillators {
            a[(2 * o, 2 * o + 1)] = 1.0;
            a[(2 * o + 1, 2 * o)] = k;
            a[(2 * o + 1, 2 * o + 1)] = c;
        }
        for r in 2 * oscillators..2 * oscillators + reals {
            a[(r, r)] = root;
        }
        a
    }

    /// Every returned pair satisfies A r = λ r (and lᴴ A = λ lᴴ) to round-off.
    /// Deterministic entries in (−1, 1).
    pub(crate) fn noise(i: usize, j: usize, seed: usize) -> f64 {
        ((i * 31 + j * 17 + seed * 7) as f64 * 0.618_034).sin()
    }

    pub(crate) fn assert_eigenpairs(a: &DMatrix<f64>, r: &Roots, tol: f64) {
        let ac = a.map(|v| Complex::new(v, 0.0));
        let scale = a.norm();
        for (k, l) in r.values.iter().enumerate() {
            let v = r.vectors.column(k);
            let res = &ac * v - v * *l;
            assert!(
                res.norm() <= tol * scale * v.norm(),
                "right {k}: {}",
                res.norm()
            );
            if r.left.ncols() > 0 {
                let w = r.left.column(k);
                let res = w.adjoint() * &ac - w.adjoint() * *l;
                assert!(res.norm() <= tol * scale * w.norm(), "left {k}");
            }
        }
    }

    #[test]
    fn repeated_roots_get_independent_vectors() {
        // Two identical decoupled oscillators and a triple real root.
        let a = repeated_roots(7, 2, [-4.0, -0.2], 3, -3.0);
        assert!(fast_decomposition(&a, true).is_some());
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.values.len(), 5);
        assert_eigenpairs(&a, &r, 1e-10);
        // The eigenvectors of each repeated root span its eigenspace.
        let rank = |cols: Vec<usize>| {
            let m = DMatrix::from_fn(7, cols.len(), |i, j| r.vectors[(i, cols[j])]);
            m.svd(false, false)
                .singular_values
                .iter()
                .filter(|s| **s > 1e-8)
                .count()
        };
        let osc: Vec<usize> = (0..5).filter(|&k| r.values[k].im > 0.0).collect();
        let real: Vec<usize> = (0..5).filter(|&k| r.values[k].im == 0.0).collect();
        assert_eq!((rank(osc), rank(real)), (2, 3));
    }

    #[test]
    fn rejects_non_finite_and_non_square() {
        let mut a = DMatrix::<f64>::identity(4, 4);
        a[(2, 1)] = f64::NAN;
        assert!(matches!(eigen_decomposition(&a), Err(Error::Numerical(_))));
        a[(2, 1)] = f64::INFINITY;
        assert!(matches!(eigen_decomposition(&a), Err(Error::Numerical(_))));
        assert!(matches!(
            eigen_decomposition(&DMatrix::<f64>::zeros(2, 3)),
            Err(Error::Numerical(_))
        ));
    }

    #[test]
    fn the_active_blocks_size_chooses_the_solver() {
        // Dense, so nothing isolates: the whole matrix is the active block.
        for (n, solver) in [(SCHUR_FROM - 1, Solver::Fast), (SCHUR_FROM, Solver::Schur)] {
            let a = DMatrix::from_fn(n, n, |i, j| noise(i, j, 0) + if i == j { 2.0 } else { 0.0 });
            let r = eigen_decomposition(&a).unwrap();
            assert_eq!(r.solver, solver, "{n} states");
            assert_eigenpairs(&a, &r, 1e-10);
        }
    }
}
