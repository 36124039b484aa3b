//! Eigenvalue isolation by permutation (the permutation step of LAPACK's `gebal`, job 'P') and
//! the way back to eigenvectors of the whole matrix (block back-substitution, the part of
//! `gebak` that undoes it, extended to the isolated roots' own vectors).
//!
//! A state matrix in still air has hundreds of states with no dynamics: rows that are zero off
//! the diagonal, or columns that are. Their eigenvalues are simply diagonal entries, and they
//! form one huge, exactly defective cluster that neither inverse iteration nor faer's multishift
//! QR survives (the latter spun forever in its deflation). Moving them out by a symmetric
//! permutation, found in O(n²), leaves the QR iteration only the active block B, which has none
//! of that structure; when nothing isolates, B is the matrix itself.

use super::lu::Lu;
use super::roots::Roots;
use nalgebra::{Complex, DMatrix, DVector};
use std::ops::Range;

/// A symmetric permutation P with PᵀAP = [[T1, X, Y], [0, B, Z], [0, 0, T2]], T1 and T2 upper
/// triangular: the eigenvalues are diag(T1), eig(B), diag(T2).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Isolation {
    /// Original index of each permuted position.
    order: Vec<usize>,
    /// The active block B occupies permuted positions `lo..hi`.
    lo: usize,
    hi: usize,
}

impl Isolation {
    /// Isolates every eigenvalue that a permutation can: repeatedly moves to the bottom a row
    /// whose off-diagonal entries among the still-active indices are all exactly zero, and to the
    /// top such a column (rows first, as LAPACK), until neither is left. Exact zeros only: no
    /// tolerance, so nothing is perturbed. Each index leaves the active set once and updates the
    /// counts of the indices it touches, O(n²) in all.
    ///
    /// Why the result is block triangular: a row isolated at some point is zero in every column
    /// still active then, which includes every column isolated later, and symmetrically for
    /// columns; so nothing isolated ever sits below the diagonal of what is isolated after it.
    pub(crate) fn of(a: &DMatrix<f64>) -> Isolation {
        let n = a.nrows();
        let off = |i: usize, j: usize| i != j && a[(i, j)] != 0.0;
        let mut row_count: Vec<usize> = (0..n)
            .map(|i| (0..n).filter(|&j| off(i, j)).count())
            .collect();
        let mut col_count: Vec<usize> = (0..n)
            .map(|j| (0..n).filter(|&i| off(i, j)).count())
            .collect();
        let mut active = vec![true; n];
        let (mut top, mut bottom) = (Vec::new(), Vec::new());
        loop {
            let row = (0..n).rev().find(|&i| active[i] && row_count[i] == 0);
            let (k, is_row) = match row {
                Some(i) => (i, true),
                None => match (0..n).find(|&j| active[j] && col_count[j] == 0) {
                    Some(j) => (j, false),
                    None => break,
                },
            };
            active[k] = false;
            for i in 0..n {
                if off(i, k) {
                    row_count[i] -= 1;
                }
                if off(k, i) {
                    col_count[i] -= 1;
                }
            }
            if is_row {
                bottom.push(k);
            } else {
                top.push(k);
            }
        }
        let (lo, hi) = (top.len(), n - bottom.len());
        let mut order = top;
        order.extend((0..n).filter(|&i| active[i]));
        order.extend(bottom.into_iter().rev());
        Isolation { order, lo, hi }
    }

    /// True when nothing isolates (B is A itself, in its own order).
    pub(crate) fn is_trivial(&self) -> bool {
        self.lo == 0 && self.hi == self.order.len()
    }

    /// The active block B, in A's relative order.
    pub(crate) fn active_block(&self, a: &DMatrix<f64>) -> DMatrix<f64> {
        let idx = &self.order[self.lo..self.hi];
        DMatrix::from_fn(idx.len(), idx.len(), |i, j| a[(idx[i], idx[j])])
    }

    /// Every root of A from the roots of B (`active`, right and, when `want_left`, left vectors
    /// in B's coordinates): values in the order diag(T1), eig(B), diag(T2), each vector extended
    /// by block back-substitution through the triangular structure and normalised.
    ///
    /// For λ of B with right vector v: [x1; v; 0] with (T1 − λI)x1 = −Xv. For an isolated λ of
    /// T2: its unit vector within T2 back-substituted, then (B − λI)x2 = −Zx3 (dense LU), then
    /// x1. Left vectors likewise on Aᵀ (block lower triangular), forward. Where a triangular
    /// pivot or an LU pivot is exactly zero — λ repeated on the diagonal, a defective root, as
    /// the still-air zeros are — the component is taken as 0: there is no eigenvector
    /// independent of the one already found, and one vector per root is all the callers need.
    pub(crate) fn roots(&self, a: &DMatrix<f64>, active: Roots, want_left: bool) -> Roots {
        let n = a.nrows();
        let (lo, hi) = (self.lo, self.hi);
        let c = DMatrix::from_fn(n, n, |i, j| a[(self.order[i], self.order[j])]);
        let mut sub = Substitution {
            c: &c,
            lo,
            hi,
            lu: Vec::new(),
        };
        let diagonal = |p: usize| Complex::new(c[(p, p)] + 0.0, 0.0); // −0 prints as 0
        let mut values = Vec::with_capacity(n);
        let mut right: Vec<DVector<Complex<f64>>> = Vec::with_capacity(n);
        let mut left: Vec<DVector<Complex<f64>>> = Vec::new();
        for k in 0..lo {
            let lambda = diagonal(k);
            values.push(lambda);
            right.push(sub.right_of_upper(k, lambda));
            if want_left {
                left.push(sub.left_of_upper(k, lambda));
            }
        }
        for (j, &lambda) in active.values.iter().enumerate() {
            values.push(lambda);
            let mut x = DVector::zeros(n);
            x.rows_mut(lo, hi - lo).copy_from(&active.vectors.column(j));
            sub.back(&mut x, 0..lo, hi, lambda);
            right.push(normalised(x));
            if want_left {
                // lᴴB = λlᴴ: w = l̄ satisfies wᵀB = λwᵀ, and wᵀA = λwᵀ is solved forward.
                let mut w = DVector::zeros(n);
                w.rows_mut(lo, hi - lo)
                    .copy_from(&active.left.column(j).map(|l| l.conj()));
                sub.forward(&mut w, hi..n, lo, lambda);
                left.push(normalised(w).map(|w| w.conj()));
            }
        }
        for k in hi..n {
            let lambda = diagonal(k);
            values.push(lambda);
            right.push(sub.right_of_lower(k, lambda));
            if want_left {
                let mut w = DVector::zeros(n);
                w[k] = Complex::new(1.0, 0.0);
                sub.forward(&mut w, k + 1..n, k, lambda);
                left.push(normalised(w).map(|w| w.conj()));
            }
        }
        let unpermute = |cols: Vec<DVector<Complex<f64>>>| {
            let mut m = DMatrix::zeros(n, cols.len());
            for (j, col) in cols.iter().enumerate() {
                for (p, &i) in self.order.iter().enumerate() {
                    m[(i, j)] = col[p];
                }
            }
            m
        };
        Roots {
            values,
            vectors: unpermute(right),
            left: unpermute(left),
            solver: active.solver,
        }
    }
}

/// The triangular and LU solves of [`Isolation::roots`] on the permuted matrix C = PᵀAP, in
/// place on a full permuted vector x (right: (C − λI)x = 0 row by row) or w (left:
/// wᵀ(C − λI) = 0 column by column).
struct Substitution<'a> {
    c: &'a DMatrix<f64>,
    lo: usize,
    hi: usize,
    /// `P(B − λI) = LU`, one per distinct isolated λ that needs one (still air: only λ = 0).
    lu: Vec<(f64, Lu)>,
}

impl Substitution<'_> {
    /// Right vector of the T1 root at position k: e_k, back-substituted through T1.
    fn right_of_upper(&mut self, k: usize, lambda: Complex<f64>) -> DVector<Complex<f64>> {
        let mut x = DVector::zeros(self.c.nrows());
        x[k] = Complex::new(1.0, 0.0);
        self.back(&mut x, 0..k, k + 1, lambda);
        normalised(x)
    }

    /// Left vector of the T1 root at position k: e_k forward through T1, then B, then T2.
    fn left_of_upper(&mut self, k: usize, lambda: Complex<f64>) -> DVector<Complex<f64>> {
        let (n, lo, hi) = (self.c.nrows(), self.lo, self.hi);
        let mut w = DVector::zeros(n);
        w[k] = Complex::new(1.0, 0.0);
        self.forward(&mut w, k + 1..lo, k, lambda);
        // (B − λI)ᵀ w2 = −Xᵀ w1.
        for i in lo..hi {
            w[i] = -(k..lo).fold(Complex::new(0.0, 0.0), |s, q| s + w[q] * self.c[(q, i)]);
        }
        self.solve_active(&mut w, lambda.re, true);
        self.forward(&mut w, hi..n, k, lambda);
        normalised(w).map(|w| w.conj())
    }

    /// Right vector of the T2 root at position k: e_k back through T2, then B, then T1.
    fn right_of_lower(&mut self, k: usize, lambda: Complex<f64>) -> DVector<Complex<f64>> {
        let (lo, hi) = (self.lo, self.hi);
        let mut x = DVector::zeros(self.c.nrows());
        x[k] = Complex::new(1.0, 0.0);
        self.back(&mut x, hi..k, k + 1, lambda);
        // (B − λI) x2 = −Z x3.
        for i in lo..hi {
            x[i] = -(hi..=k).fold(Complex::new(0.0, 0.0), |s, q| s + x[q] * self.c[(i, q)]);
        }
        self.solve_active(&mut x, lambda.re, false);
        self.back(&mut x, 0..lo, k + 1, lambda);
        normalised(x)
    }

    /// Rows `rows` (descending) of (C − λI)x = 0 for upper-triangular rows, given x beyond
    /// them; x is zero from `end` on.
    fn back(
        &self,
        x: &mut DVector<Complex<f64>>,
        rows: Range<usize>,
        end: usize,
        lambda: Complex<f64>,
    ) {
        for p in rows.rev() {
            let s = (p + 1..end).fold(Complex::new(0.0, 0.0), |s, q| s + x[q] * self.c[(p, q)]);
            divide(x, p, s, self.c[(p, p)] - lambda);
        }
    }

    /// Columns `cols` (ascending) of wᵀ(C − λI) = 0 for upper-triangular columns, given w
    /// before them; w is zero before `start`.
    fn forward(
        &self,
        w: &mut DVector<Complex<f64>>,
        cols: Range<usize>,
        start: usize,
        lambda: Complex<f64>,
    ) {
        for p in cols {
            let s = (start..p).fold(Complex::new(0.0, 0.0), |s, q| s + w[q] * self.c[(q, p)]);
            divide(w, p, s, self.c[(p, p)] - lambda);
        }
    }

    /// Solves (B − λI) y = r (or (B − λI)ᵀ y = r when `transposed`) in place on the B part of
    /// the full vector v, which holds r there. A zero right-hand side needs no factorisation.
    fn solve_active(&mut self, v: &mut DVector<Complex<f64>>, lambda: f64, transposed: bool) {
        let (lo, m) = (self.lo, self.hi - self.lo);
        if v.rows(lo, m).iter().all(|r| *r == Complex::new(0.0, 0.0)) {
            return;
        }
        let k = match self.lu.iter().position(|(l, _)| *l == lambda) {
            Some(k) => k,
            None => {
                let b = faer::Mat::<f64>::from_fn(m, m, |i, j| {
                    self.c[(lo + i, lo + j)] - if i == j { lambda } else { 0.0 }
                });
                self.lu.push((lambda, Lu::of(b)));
                self.lu.len() - 1
            }
        };
        let factors = &self.lu[k].1;
        let (l, u, from) = (&factors.lu, &factors.lu, &factors.from);
        let one = Complex::new(1.0, 0.0);
        if transposed {
            // (B − λI)ᵀ = UᵀLᵀP: Uᵀz = r forward, Lᵀy' = z backward (unit), y = P⁻¹y'.
            for i in 0..m {
                let s = (0..i).fold(-v[lo + i], |s, j| s + v[lo + j] * u[(j, i)]);
                divide(v, lo + i, s, u[(i, i)] * one);
            }
            for i in (0..m).rev() {
                let s = (i + 1..m).fold(Complex::new(0.0, 0.0), |s, j| s + v[lo + j] * l[(j, i)]);
                v[lo + i] -= s;
            }
            let y = v.rows(lo, m).clone_owned();
            for (i, &f) in from.iter().enumerate() {
                v[lo + f] = y[i];
            }
        } else {
            // P(B − λI) = LU: Ly' = Pr forward (unit), Uy = y' backward.
            let r = v.rows(lo, m).clone_owned();
            for (i, &f) in from.iter().enumerate() {
                v[lo + i] = r[f];
            }
            for i in 0..m {
                let s = (0..i).fold(Complex::new(0.0, 0.0), |s, j| s + v[lo + j] * l[(i, j)]);
                v[lo + i] -= s;
            }
            for i in (0..m).rev() {
                let s = (i + 1..m).fold(-v[lo + i], |s, j| s + v[lo + j] * u[(i, j)]);
                divide(v, lo + i, s, u[(i, i)] * one);
            }
        }
    }
}

/// A quotient beyond this modulus rescales the vector first (see [`divide`]).
const GROWTH_LIMIT: f64 = 1e100;

/// Sets v[p] = −s/d, the one division of every substitution step. A zero pivot d (λ repeated
/// on the diagonal: defective) gives 0. A quotient that would exceed [`GROWTH_LIMIT`] in modulus
/// first rescales the whole vector so that the new entry has modulus 1 (the equations are
/// homogeneous in v, so that is exact): near-singular pivots can never overflow a vector.
fn divide(v: &mut DVector<Complex<f64>>, p: usize, s: Complex<f64>, d: Complex<f64>) {
    let (sn, dn) = (s.norm(), d.norm());
    if dn == 0.0 {
        v[p] = Complex::new(0.0, 0.0);
    } else if sn > dn * GROWTH_LIMIT {
        *v *= Complex::new(dn / sn, 0.0);
        v[p] = -(s / sn) / (d / dn);
    } else {
        v[p] = -s / d;
    }
}

/// Unit 2-norm (a zero vector, which the substitutions never produce, stays zero).
fn normalised(mut v: DVector<Complex<f64>>) -> DVector<Complex<f64>> {
    let norm = v.norm();
    if norm > 0.0 {
        v.unscale_mut(norm);
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::eigen::eigen_decomposition;
    use crate::numeric::eigen::tests::noise;
    use crate::numeric::roots::Solver;

    /// S D S⁻¹ for the real Schur-like D with roots `reals` and pairs σ ± iω: a dense block with
    /// known eigenvalues and no structure to isolate.
    fn dense_block(reals: &[f64], pairs: &[(f64, f64)]) -> DMatrix<f64> {
        let m = reals.len() + 2 * pairs.len();
        let mut d = DMatrix::zeros(m, m);
        for (k, &(s, w)) in pairs.iter().enumerate() {
            let i = 2 * k;
            d[(i, i)] = s;
            d[(i + 1, i + 1)] = s;
            d[(i, i + 1)] = w;
            d[(i + 1, i)] = -w;
        }
        for (k, &r) in reals.iter().enumerate() {
            let i = 2 * pairs.len() + k;
            d[(i, i)] = r;
        }
        let s = DMatrix::from_fn(m, m, |i, j| {
            f64::from(u8::from(i == j)) + 0.3 * noise(i, j, 1)
        });
        &s * d * s.try_inverse().unwrap()
    }

    /// [[T1, X, Y], [0, B, Z], [0, 0, T2]] with diag(T1) = `upper`, diag(T2) = `lower`, dense
    /// couplings (T1, T2 strictly upper parts included), then hidden by a symmetric permutation.
    fn hidden(upper: &[f64], b: &DMatrix<f64>, lower: &[f64]) -> DMatrix<f64> {
        let (lo, m) = (upper.len(), b.nrows());
        let (hi, n) = (lo + m, lo + m + lower.len());
        let c = DMatrix::from_fn(n, n, |i, j| match (i, j) {
            (i, j) if i == j && i < lo => upper[i],
            (i, j) if i == j && i >= hi => lower[i - hi],
            (i, j) if (lo..hi).contains(&i) && (lo..hi).contains(&j) => b[(i - lo, j - lo)],
            (i, j) if j > i && (i < lo || j >= hi) => noise(i, j, 2),
            _ => 0.0,
        });
        let order: Vec<usize> = (0..n).map(|p| (p * 37 + 5) % n).collect();
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert!(sorted.into_iter().eq(0..n), "37 and {n} must be coprime");
        let mut a = DMatrix::zeros(n, n);
        for p in 0..n {
            for q in 0..n {
                a[(order[p], order[q])] = c[(p, q)];
            }
        }
        a
    }

    fn residuals(a: &DMatrix<f64>, r: &Roots, k: usize) -> (f64, f64) {
        let ac = a.map(|v| Complex::new(v, 0.0));
        let (x, l, lambda) = (r.vectors.column(k), r.left.column(k), r.values[k]);
        let right = (&ac * x - x * lambda).norm() / (a.norm() * x.norm());
        let left = (l.adjoint() * &ac - l.adjoint() * lambda).norm() / (a.norm() * l.norm());
        (right, left)
    }

    fn assert_unit_and_finite(r: &Roots) {
        for m in [&r.vectors, &r.left] {
            for col in m.column_iter() {
                assert!(col.iter().all(|c| c.re.is_finite() && c.im.is_finite()));
                assert!((col.norm() - 1.0).abs() < 1e-12, "{}", col.norm());
            }
        }
    }

    #[test]
    fn isolation_finds_the_block_triangular_form() {
        let b = dense_block(&[-1.0, -4.0], &[(-0.5, 3.0)]);
        let a = hidden(&[1.0, 2.0, 3.0], &b, &[4.0, 5.0]);
        let iso = Isolation::of(&a);
        assert_eq!((iso.lo, iso.hi), (3, 7));
        let n = a.nrows();
        let c = DMatrix::from_fn(n, n, |i, j| a[(iso.order[i], iso.order[j])]);
        for i in 0..n {
            for j in 0..i {
                // Below the diagonal only B has entries.
                let in_b = (3..7).contains(&i) && (3..7).contains(&j);
                assert!(in_b || c[(i, j)] == 0.0, "({i}, {j})");
            }
        }
        // No row or column of B is zero off its diagonal.
        let active = iso.active_block(&a);
        assert!(Isolation::of(&active).is_trivial());
        // A dense matrix isolates nothing and keeps its order.
        let iso = Isolation::of(&b);
        assert!(iso.is_trivial() && iso.order == (0..4).collect::<Vec<_>>());
    }

    #[test]
    fn defective_zero_cluster_around_a_dense_block() {
        // 200 exactly zero roots, coupled among themselves (nilpotent T1, T2) and to a dense
        // block with known roots: the still-air pattern, which used to hang faer.
        let b = dense_block(&[-2.0, -30.0], &[(-0.1, 5.0), (-1.5, 40.0), (-0.02, 0.7)]);
        let a = hidden(&[0.0; 120], &b, &[0.0; 80]);
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.solver, Solver::Fast);
        assert_eq!(r.values.len(), 200 + 5);
        let zeros = r.values.iter().filter(|l| l.norm() == 0.0).count();
        assert_eq!(zeros, 200);
        let known = [
            Complex::new(-2.0, 0.0),
            Complex::new(-30.0, 0.0),
            Complex::new(-0.1, 5.0),
            Complex::new(-1.5, 40.0),
            Complex::new(-0.02, 0.7),
        ];
        for want in known {
            let k = r
                .values
                .iter()
                .position(|l| (l - want).norm() <= 1e-10 * want.norm())
                .unwrap_or_else(|| panic!("{want} missing: {:?}", r.values));
            let (right, left) = residuals(&a, &r, k);
            assert!(right <= 1e-8 && left <= 1e-8, "{want}: {right:e}, {left:e}");
        }
        assert_unit_and_finite(&r);
    }

    #[test]
    fn distinct_isolated_roots_have_exact_vectors() {
        // Every root simple: each of the back-substitutions (through T1, T2 and the LU of
        // B − λI, right and left) gives a true eigenvector; the larger block's pivoting is
        // more than a set of swaps, so a permutation applied the wrong way round would show.
        let small = dense_block(&[-3.0], &[(-0.2, 2.0), (-1.0, 7.0)]);
        let pairs: Vec<(f64, f64)> = (1..=6).map(|k| (-0.1 * k as f64, 1.5 * k as f64)).collect();
        let large = dense_block(&[-3.0, -4.5, 0.75], &pairs);
        for (b, block_roots) in [(small, 1 + 2), (large, 3 + 6)] {
            let a = hidden(&[0.5, -1.5, 2.5, -6.0], &b, &[-0.25, 1.25, -9.0]);
            let r = eigen_decomposition(&a).unwrap();
            assert_eq!(r.values.len(), 4 + 3 + block_roots);
            for k in 0..r.values.len() {
                let (right, left) = residuals(&a, &r, k);
                assert!(
                    right <= 1e-12 && left <= 1e-12,
                    "{}: {right:e}, {left:e}",
                    r.values[k]
                );
            }
            assert_unit_and_finite(&r);
        }
    }

    #[test]
    fn isolated_roots_equal_to_roots_of_the_block_stay_finite() {
        // B = [[2, 1], [1, 2]] has roots 1 and 3, and B − 3I an exactly zero LU pivot; the
        // isolated 3 (T2) and 1 (T1) make both LU solves singular.
        let b = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
        let a = hidden(&[1.0, 0.0], &b, &[3.0, 0.0, 3.0]);
        let r = eigen_decomposition(&a).unwrap();
        let mut values: Vec<f64> = r.values.iter().map(|l| l.re).collect();
        values.sort_by(f64::total_cmp);
        assert_eq!(values, [0.0, 0.0, 1.0, 1.0, 3.0, 3.0, 3.0]);
        assert_unit_and_finite(&r);
    }

    #[test]
    fn near_singular_pivots_cannot_overflow_a_vector() {
        // Upper triangular, everything isolates. The root 0 meets the pivots 1e-200, 2e-200,
        // 3e-200 on its way up: unguarded, its vector would reach 1e600.
        let mut a = DMatrix::from_fn(4, 4, |i, j| f64::from(u8::from(j > i)));
        for (i, d) in [3e-200, 2e-200, 1e-200, 0.0].into_iter().enumerate() {
            a[(i, i)] = d;
        }
        let r = eigen_decomposition(&a).unwrap();
        assert_unit_and_finite(&r);
        for k in 0..4 {
            let (right, left) = residuals(&a, &r, k);
            assert!(
                right <= 1e-12 && left <= 1e-12,
                "{}: {right:e}, {left:e}",
                r.values[k]
            );
        }
    }
}
