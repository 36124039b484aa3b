//! The lowest eigenpairs of a banded symmetric pencil `K x = λ M x` (`M` positive definite) by
//! shift-invert block Lanczos with full reorthogonalisation and thick restarts, each cycle ended by
//! a Rayleigh–Ritz step and a residual check (docs/model.md §11.4).
//!
//! Why this way: the lowest modes of `K x = λ M x` are the largest of the operator `K⁻¹M`, which
//! is self-adjoint in the M inner product and whose eigenvalues `1/λ` fall off fast (a beam's
//! `λ` grows with the fourth power of the mode number), so a Krylov space of `K⁻¹M` holds them
//! after a few dozen products. Each product is one banded solve with the Cholesky factor of `K`
//! (O(n·band)), against the O(n³) of a dense decomposition. A block of several vectors finds
//! every copy of a repeated eigenvalue (a single-vector Krylov space holds only one), and the
//! projected operator `Vᵀ M K⁻¹ M V` never forms `K x`: each eigenvalue keeps a precision
//! relative to itself, where a dense reduction `L⁻¹KL⁻ᵀ` (`M = LLᵀ`) errs relative to the
//! largest eigenvalue of the pencil, orders of magnitude above the first ones on a fine mesh.
//!
//! Convergence is checked, not assumed: the result is returned only once every wanted Ritz pair
//! has a residual `‖K⁻¹M x − x/λ‖_M · λ ≤` [`RESIDUAL`]; otherwise an error after
//! [`MAX_CYCLES`] restarts.

use super::banded::{BandCholesky, SymmetricBand};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, SymmetricEigen};

/// Vectors per Krylov block: more than the multiplicity of any eigenvalue the pencils here have
/// (a section symmetric in flap and edge doubles a bending mode; two can coincide with a twist
/// mode by chance).
const BLOCK: usize = 4;

/// Residual `‖K⁻¹M x − x/λ‖_M · λ` (x M-normalised) a Ritz pair must reach. The eigenvalue's
/// error is about the residual squared over the relative gap to its neighbours, so this leaves
/// λ at round-off for any gap above 1e-4, and a residual this small is reached in one or two
/// cycles more than a looser one.
pub const RESIDUAL: f64 = 1e-9;

/// Restart cycles before giving up. A cycle adds about `count` Krylov vectors; the blades'
/// pencils converge in one to three.
const MAX_CYCLES: usize = 50;

/// A new vector whose M-norm falls below this fraction of its norm before orthogonalisation lies
/// in the space already built and is dropped.
const DEPENDENT: f64 = 1e-10;

/// Shifts tried when `K` is not positive definite: `K + τM` with `τ = 1, 8, 64, …` in the
/// pencil's units, at most this many. Each try that fails shows `λ_min < −τ`, so the shift
/// that works is within a factor 8 of the lowest eigenvalue's size and costs no more than a
/// digit of its precision.
const SHIFTS: usize = 40;

/// The lowest eigenpairs of `K x = λ M x`.
#[derive(Debug, Clone)]
pub struct LowestModes {
    /// Ascending.
    pub values: Vec<f64>,
    /// Columns M-orthonormal, in the order of `values`.
    pub vectors: DMatrix<f64>,
    /// The largest residual of the pairs returned (see [`RESIDUAL`]).
    pub residual: f64,
    /// Rayleigh–Ritz cycles used.
    pub cycles: usize,
}

/// The Krylov basis under construction: `V` (M-orthonormal columns), `M V` and `W = (K + τM)⁻¹ M V`.
struct Basis<'a> {
    k: &'a BandCholesky,
    m: &'a SymmetricBand,
    v: DMatrix<f64>,
    mv: DMatrix<f64>,
    w: DMatrix<f64>,
    /// Columns in use.
    len: usize,
}

impl Basis<'_> {
    /// `c` less its M-projection on the basis, twice: once is not enough in floating point when
    /// `c` lies mostly in the basis, as Krylov vectors do.
    fn project_out(&self, c: &mut DVector<f64>) {
        for _ in 0..2 {
            let used = self.len;
            let h = self.mv.columns(0, used).tr_mul(c);
            c.gemv(-1.0, &self.v.columns(0, used), &h, 1.0);
        }
    }

    /// Orthogonalise `c` against the basis (twice: once is not enough in floating point when `c`
    /// lies mostly in the basis, as Krylov vectors do) and append it with its `M c` and
    /// `K⁻¹ M c`; false when it depends on the basis or the basis is full.
    fn push(&mut self, mut c: DVector<f64>) -> bool {
        let n = c.len();
        if self.len == self.v.ncols() {
            return false;
        }
        let mut mc = DVector::zeros(n);
        self.m.mul_into(c.as_slice(), mc.as_mut_slice());
        let start = c.dot(&mc).sqrt();
        if !(start > 0.0 && start.is_finite()) {
            return false;
        }
        self.project_out(&mut c);
        self.m.mul_into(c.as_slice(), mc.as_mut_slice());
        let norm = c.dot(&mc).sqrt();
        // NaN fails the comparison too and is dropped.
        if norm.partial_cmp(&(DEPENDENT * start)) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        c /= norm;
        mc /= norm;
        let mut w = mc.clone();
        self.k.solve_in_place(w.as_mut_slice());
        let j = self.len;
        self.v.set_column(j, &c);
        self.mv.set_column(j, &mc);
        self.w.set_column(j, &w);
        self.len += 1;
        true
    }
}

/// Deterministic start vectors (a fixed pseudo-random pattern, so a run repeats exactly):
/// `count` of them, the `offset`-th onward.
fn start_vectors(n: usize, count: usize, offset: usize) -> Vec<DVector<f64>> {
    (offset..offset + count)
        .map(|c| {
            DVector::from_fn(n, |i, _| {
                let t = (i as f64 + 1.0) * (0.618_033_988_749 + 0.1 * c as f64);
                (t * 12.9898 + c as f64 * 78.233).sin() * 43.758_5 % 1.0
            })
        })
        .collect()
}

/// The lowest `count` eigenpairs of `K x = λ M x` (both symmetric, `M` positive definite), from
/// `start`'s columns (e.g. the modes of a nearby pencil; may be empty) and fixed pseudo-random
/// vectors. Errors when neither `K` nor a shifted `K + τM` can be factored, or when the residual
/// check fails after [`MAX_CYCLES`] cycles.
pub fn lowest_modes(
    k: &SymmetricBand,
    m: &SymmetricBand,
    count: usize,
    start: &DMatrix<f64>,
) -> Result<LowestModes> {
    let n = k.size();
    assert_eq!(m.size(), n, "pencil of different sizes");
    let count = count.min(n);
    if count == 0 {
        return Ok(LowestModes {
            values: vec![],
            vectors: DMatrix::zeros(n, 0),
            residual: 0.0,
            cycles: 0,
        });
    }
    let (factor, shift) = factor_shifted(k, m)?;

    // The basis holds the wanted pairs, a block of spare Ritz vectors (their convergence pulls
    // the wanted ones along), and room for about `count` new Krylov vectors per cycle.
    let capacity = (2 * count + 3 * BLOCK).min(n);
    let keep = (count + BLOCK).min(capacity.saturating_sub(BLOCK).max(count));
    let mut basis = Basis {
        k: &factor,
        m,
        v: DMatrix::zeros(n, capacity),
        mv: DMatrix::zeros(n, capacity),
        w: DMatrix::zeros(n, capacity),
        len: 0,
    };
    let mut pending: Vec<DVector<f64>> = start.column_iter().map(|c| c.into_owned()).collect();
    pending.extend(start_vectors(n, BLOCK, 0));
    let mut fresh = BLOCK;
    let mut worst = f64::INFINITY;
    for cycle in 1..=MAX_CYCLES {
        // Extend the basis block by block: each block is K⁻¹M of the previous one.
        while basis.len < capacity {
            if pending.is_empty() {
                // The space is invariant (every new vector depended on it): continue from new
                // directions, or stop if there are none (the space is the whole one).
                if fresh > 8 * BLOCK + n {
                    break;
                }
                pending = start_vectors(n, BLOCK, fresh);
                fresh += BLOCK;
            }
            // A block cut short by the capacity keeps its remaining vectors for after the
            // restart: the Ritz vectors' residuals lie in the images of both the last block and
            // the one before, and a direction lost there stalls the convergence.
            let first = basis.len;
            let mut next = Vec::new();
            for c in std::mem::take(&mut pending) {
                if basis.len < capacity {
                    basis.push(c);
                } else {
                    next.push(c);
                }
            }
            next.extend((first..basis.len).map(|j| basis.w.column(j).into_owned()));
            pending = next;
        }
        let used = basis.len;
        if used < count {
            return Err(Error::numerical(format!(
                "lowest modes: only {used} independent vectors for {count} modes"
            )));
        }

        // Rayleigh–Ritz on K⁻¹M: T = Vᵀ M W, eigenvalues μ = 1/(λ + τ), largest first.
        let (v, mv, w) = (
            basis.v.columns(0, used),
            basis.mv.columns(0, used),
            basis.w.columns(0, used),
        );
        let t = mv.tr_mul(&w);
        let t = (&t + t.transpose()) * 0.5;
        let eig = SymmetricEigen::try_new(t, f64::EPSILON, 10_000)
            .ok_or_else(|| Error::numerical("lowest modes: Ritz eigensolver did not converge"))?;
        let mut order: Vec<usize> = (0..used).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[b].total_cmp(&eig.eigenvalues[a]));
        let kept = keep.min(used);
        let s = DMatrix::from_fn(used, kept, |i, c| eig.eigenvectors[(i, order[c])]);
        let mu: Vec<f64> = order[..kept].iter().map(|&j| eig.eigenvalues[j]).collect();
        let x = v * &s;
        let mx = mv * &s;
        let wx = w * &s;

        // Residual of each wanted pair in the inverted problem, relative to its eigenvalue.
        let mut r = DVector::zeros(n);
        let mut mr = DVector::zeros(n);
        worst = 0.0_f64;
        for (i, &mu_i) in mu.iter().enumerate().take(count) {
            if !(mu_i > 0.0 && mu_i.is_finite()) {
                return Err(Error::numerical(format!(
                    "lowest modes: Ritz value {mu_i:e} of a positive definite operator"
                )));
            }
            r.copy_from(&wx.column(i));
            r.axpy(-mu_i, &x.column(i), 1.0);
            m.mul_into(r.as_slice(), mr.as_mut_slice());
            worst = worst.max(r.dot(&mr).max(0.0).sqrt() / mu_i);
        }
        if worst <= RESIDUAL {
            return Ok(LowestModes {
                values: mu[..count].iter().map(|u| 1.0 / u - shift).collect(),
                vectors: x.columns(0, count).into_owned(),
                residual: worst,
                cycles: cycle,
            });
        }
        if used == n {
            // The basis is the whole space: the Ritz pairs are exact up to round-off, which is
            // then all the residual shows.
            return Err(Error::numerical(format!(
                "lowest modes: residual {worst:.1e} on the whole space (tolerance {RESIDUAL:e}): \
                 the pencil is too ill-conditioned"
            )));
        }
        // Thick restart: keep the leading Ritz vectors (with their M x and K⁻¹M x, so no new
        // solves) and continue from the last block's K⁻¹M images less their part in the whole
        // basis, the directions the residuals lie in. (Only orthogonal to the kept vectors, they
        // would bring back the discarded Ritz directions and the convergence stalls.)
        for c in &mut pending {
            basis.project_out(c);
        }
        basis.v.columns_mut(0, kept).copy_from(&x);
        basis.mv.columns_mut(0, kept).copy_from(&mx);
        basis.w.columns_mut(0, kept).copy_from(&wx);
        basis.len = kept;
    }
    Err(Error::numerical(format!(
        "lowest {count} modes did not converge in {MAX_CYCLES} cycles: residual {worst:.1e} \
         (tolerance {RESIDUAL:e})"
    )))
}

/// The Cholesky factor of `K`, or of `K + τM` with the smallest `τ` of 1, 8, 64, … that makes
/// it positive definite ([`SHIFTS`]), and `τ`.
fn factor_shifted(k: &SymmetricBand, m: &SymmetricBand) -> Result<(BandCholesky, f64)> {
    if let Some(f) = k.cholesky() {
        return Ok((f, 0.0));
    }
    let mut shift = 1.0;
    for _ in 0..SHIFTS {
        if let Some(f) = k.plus(shift, m).cholesky() {
            return Ok((f, shift));
        }
        shift *= 8.0;
    }
    Err(Error::numerical(
        "lowest modes: the stiffness is not positive definite even shifted by 8^40 mass",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fixed–fixed string on `n` interior nodes: `K` tridiagonal (2, −1), `M` the identity;
    /// `λ_j = 4 sin²(jπ / 2(n+1))`.
    fn string(n: usize) -> (DMatrix<f64>, Vec<f64>) {
        let k = DMatrix::from_fn(n, n, |i, j| match i.abs_diff(j) {
            0 => 2.0,
            1 => -1.0,
            _ => 0.0,
        });
        let exact = (1..=n)
            .map(|j| {
                let s = (j as f64 * std::f64::consts::PI / (2.0 * (n as f64 + 1.0))).sin();
                4.0 * s * s
            })
            .collect();
        (k, exact)
    }

    fn band(a: &DMatrix<f64>) -> SymmetricBand {
        SymmetricBand::from_dense(a, super::super::banded::half_bandwidth(a))
    }

    fn check(k: &DMatrix<f64>, m: &DMatrix<f64>, modes: &LowestModes, exact: &[f64]) {
        for (i, (got, want)) in modes.values.iter().zip(exact).enumerate() {
            assert!(
                (got - want).abs() <= 1e-10 * want.abs(),
                "mode {i}: {got} vs {want}"
            );
            let x = modes.vectors.column(i);
            let r = k * x - m * x * *got;
            assert!(
                r.norm() < 1e-7 * k.norm(),
                "mode {i}: residual {}",
                r.norm()
            );
        }
        let gram = modes.vectors.transpose() * m * &modes.vectors;
        let count = modes.values.len();
        assert!((gram - DMatrix::identity(count, count)).norm() < 1e-9);
    }

    /// The string's spectrum is clustered at the bottom (`λ` grows as `j²`, not as a beam's
    /// `j⁴`): the slowest case for a Krylov method of `K⁻¹`, converged by restarts.
    #[test]
    fn the_lowest_modes_of_a_string_are_exact() {
        let (k, exact) = string(400);
        let m = DMatrix::identity(400, 400);
        let modes = lowest_modes(&band(&k), &band(&m), 20, &DMatrix::zeros(400, 0)).unwrap();
        assert!(modes.residual <= RESIDUAL);
        check(&k, &m, &modes, &exact[..20]);
    }

    /// Two uncoupled copies of the string with different masses interleaved dof by dof: every
    /// eigenvalue of the second copy (`M = 2`) is half of one of the first's, and with masses
    /// equal every eigenvalue is double; the block finds both copies.
    #[test]
    fn repeated_eigenvalues_are_found_twice() {
        let (s, exact) = string(150);
        let n = 300;
        let k = DMatrix::from_fn(n, n, |i, j| {
            if i % 2 == j % 2 {
                s[(i / 2, j / 2)]
            } else {
                0.0
            }
        });
        let m = DMatrix::identity(n, n);
        let modes = lowest_modes(&band(&k), &band(&m), 12, &DMatrix::zeros(n, 0)).unwrap();
        let doubled: Vec<f64> = exact.iter().flat_map(|e| [*e, *e]).collect();
        check(&k, &m, &modes, &doubled[..12]);
    }

    /// A stiffness that is not positive definite (a string under compression past its first
    /// buckling load) is shifted, and its negative eigenvalue comes out.
    #[test]
    fn an_indefinite_stiffness_is_shifted() {
        let (k, exact) = string(50);
        let m = DMatrix::identity(50, 50);
        let load = 0.5 * (exact[0] + exact[1]);
        let k = k - &m * load;
        let modes = lowest_modes(&band(&k), &band(&m), 5, &DMatrix::zeros(50, 0)).unwrap();
        assert!(modes.values[0] < 0.0);
        let shifted: Vec<f64> = exact.iter().map(|e| e - load).collect();
        check(&k, &m, &modes, &shifted[..5]);
    }

    /// The whole space asked for: the basis fills, and the Rayleigh–Ritz step is then exact.
    #[test]
    fn every_mode_of_a_small_pencil() {
        let (k, exact) = string(7);
        let m = DMatrix::identity(7, 7);
        let modes = lowest_modes(&band(&k), &band(&m), 7, &DMatrix::zeros(7, 0)).unwrap();
        check(&k, &m, &modes, &exact);
    }
}
