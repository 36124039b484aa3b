//! Eigenvectors of an upper Hessenberg matrix for eigenvalues already known, by inverse
//! iteration (LAPACK `dhsein`/`dlaein`): one O(n²) LU factorisation of H − λI with
//! adjacent-row pivoting per root, a few solves, and a residual check. The vector half of the fast
//! eigendecomposition in [`super::eigen`]: far cheaper than a Schur form with its vectors, and
//! (numerically) repeated roots still get a basis of their eigenspace.

use nalgebra::{Complex, ComplexField, DMatrix};

/// Iteration cap: solves per vector. With a converged eigenvalue as shift one or two solves
/// usually suffice; a root that needs more is defective or extremely ill-conditioned, and goes to
/// faer's fallback instead.
const MAX_SOLVES: usize = 4;

/// Residual tolerance in units of nε‖H‖: an iterate is accepted when ‖Hx − λx‖ ≤ 64nε‖H‖.
const RESIDUAL_TOLERANCE: f64 = 64.0;

/// Earlier roots within this many ε‖H‖ of a shift share (numerically) its eigenspace.
pub(super) const CLUSTER_RADIUS: f64 = 1e3;

/// A right eigenvector and, when asked, the w with wᵀH = λwᵀ (unit 2-norm), of one root.
pub(super) type RootVectors = (Vec<Complex<f64>>, Option<Vec<Complex<f64>>>);

/// Below this many rows the vectors of all roots are computed on the calling thread: handing half
/// of them to a second thread costs more than it saves (tens of µs against O(n³) flops).
pub(super) const PARALLEL_FROM: usize = 40;

/// The vectors of every root in `values` (real roots in real arithmetic, pairs in complex), or
/// `None` if any fails its residual check.
///
/// Why two groups: each root's vectors depend only on its own shift and on the earlier roots of
/// its cluster (same kind, within [`CLUSTER_RADIUS`]·ε‖H‖; see [`InverseIteration::vectors`]).
/// So the roots split into whole clusters on two threads (rayon, so a sweep that already runs
/// its points in parallel does not oversubscribe the cores) and every vector comes out bit for
/// bit as it would in one sequential pass (docs/model.md §6.1).
pub(super) fn root_vectors(
    h: &DMatrix<f64>,
    hnorm: f64,
    values: &[Complex<f64>],
    want_left: bool,
) -> Option<Vec<RootVectors>> {
    let (first, second) = if h.nrows() >= PARALLEL_FROM {
        balanced_halves(values, CLUSTER_RADIUS * f64::EPSILON * hnorm)
    } else {
        ((0..values.len()).collect(), Vec::new())
    };
    let run = |group: &[usize]| group_vectors(h, hnorm, values, group, want_left);
    let (a, b) = if second.is_empty() {
        (run(&first), Some(Vec::new()))
    } else {
        rayon::join(|| run(&first), || run(&second))
    };
    let mut out: Vec<Option<RootVectors>> = vec![None; values.len()];
    for (k, v) in first.iter().zip(a?).chain(second.iter().zip(b?)) {
        out[*k] = Some(v);
    }
    out.into_iter().collect()
}

/// The vectors of the roots `group` (indices into `values`, in order), one sequential pass.
pub(super) fn group_vectors(
    h: &DMatrix<f64>,
    hnorm: f64,
    values: &[Complex<f64>],
    group: &[usize],
    want_left: bool,
) -> Option<Vec<RootVectors>> {
    let mut solver = RootSolver::new(h, hnorm);
    group
        .iter()
        .map(|&k| solver.vectors(values[k], want_left))
        .collect()
}

/// Inverse iteration for roots of either kind on one matrix: real roots in real arithmetic (a
/// quarter of the work), pairs in complex.
pub(super) struct RootSolver<'a> {
    real: InverseIteration<'a, f64>,
    complex: InverseIteration<'a, Complex<f64>>,
}

impl<'a> RootSolver<'a> {
    pub(super) fn new(h: &'a DMatrix<f64>, hnorm: f64) -> Self {
        RootSolver {
            real: InverseIteration::new(h, hnorm),
            complex: InverseIteration::new(h, hnorm),
        }
    }

    /// The vectors of root `lambda` (see [`InverseIteration::vectors`]).
    pub(super) fn vectors(&mut self, lambda: Complex<f64>, want_left: bool) -> Option<RootVectors> {
        if lambda.im == 0.0 {
            let (x, w) = self.real.vectors(lambda.re, want_left)?;
            let up = |v: Vec<f64>| v.into_iter().map(|r| Complex::new(r, 0.0)).collect();
            Some((up(x), w.map(up)))
        } else {
            self.complex.vectors(lambda, want_left)
        }
    }
}

/// The clusters of `values`, each a list of root indices in ascending order: roots of one kind
/// (real or complex) within `radius` of each other, transitively. The roots whose vectors depend
/// on each other ([`InverseIteration::vectors`]).
pub(super) fn clusters(values: &[Complex<f64>], radius: f64) -> Vec<Vec<usize>> {
    let n = values.len();
    let mut label: Vec<usize> = (0..n).collect();
    for k in 0..n {
        for j in 0..k {
            let same_kind = (values[j].im == 0.0) == (values[k].im == 0.0);
            if same_kind && (values[j] - values[k]).norm() <= radius {
                // Relabel k's cluster as j's (n is a few hundred at most).
                let (from, to) = (label[k], label[j]);
                label
                    .iter_mut()
                    .filter(|c| **c == from)
                    .for_each(|c| *c = to);
            }
        }
    }
    (0..n)
        .map(|c| (0..n).filter(|&k| label[k] == c).collect::<Vec<_>>())
        .filter(|members| !members.is_empty())
        .collect()
}

/// Two lists of root indices, each in ascending order, that never separate two roots of one
/// cluster (same kind, real or complex, and within `radius` of each other, transitively), with
/// about equal work: a complex root costs about four real ones (complex arithmetic).
fn balanced_halves(values: &[Complex<f64>], radius: f64) -> (Vec<usize>, Vec<usize>) {
    let cost = |k: usize| if values[k].im == 0.0 { 1 } else { 4 };
    let mut load = [0usize; 2];
    let mut side = vec![0usize; values.len()];
    for members in clusters(values, radius) {
        let lighter = usize::from(load[1] < load[0]);
        load[lighter] += members.iter().map(|&k| cost(k)).sum::<usize>();
        members.iter().for_each(|&k| side[k] = lighter);
    }
    (0..values.len()).partition(|&k| side[k] == 0)
}

/// Inverse iteration on one upper Hessenberg matrix for a sequence of shifts (real `f64` or
/// complex), remembering earlier roots' vectors to separate (numerically) repeated roots.
pub(super) struct InverseIteration<'a, T> {
    h: &'a DMatrix<f64>,
    /// H row by row, so that each factorisation reads its rows contiguously.
    h_rows: Vec<f64>,
    hnorm: f64,
    lu: HessenbergLu<T>,
    right: Vec<(T, Vec<T>)>,
    left: Vec<(T, Vec<T>)>,
}

impl<'a, T: ComplexField<RealField = f64> + Copy> InverseIteration<'a, T> {
    pub(super) fn new(h: &'a DMatrix<f64>, hnorm: f64) -> Self {
        InverseIteration {
            h,
            h_rows: h.transpose().as_slice().to_vec(),
            hnorm,
            lu: HessenbergLu {
                n: 0,
                u: Vec::new(),
                mult: Vec::new(),
                swapped: Vec::new(),
                carry: Vec::new(),
                next: Vec::new(),
            },
            right: Vec::new(),
            left: Vec::new(),
        }
    }

    /// Right eigenvector x (Hx = λx) and, if asked, w with wᵀH = λwᵀ; unit 2-norm.
    pub(super) fn vectors(
        &mut self,
        lambda: T,
        want_left: bool,
    ) -> Option<(Vec<T>, Option<Vec<T>>)> {
        let eps3 = f64::EPSILON * self.hnorm;
        self.lu.factor(&self.h_rows, self.h.nrows(), lambda, eps3);
        // Earlier roots this close share (numerically) an eigenspace with this one.
        let near = |done: &[(T, Vec<T>)]| -> Vec<Vec<T>> {
            done.iter()
                .filter(|(l, _)| (*l - lambda).modulus() <= CLUSTER_RADIUS * eps3)
                .map(|(_, v)| v.clone())
                .collect()
        };
        let cluster = near(&self.right);
        let x = self.iterate(lambda, &cluster, false)?;
        self.right.push((lambda, x.clone()));
        let w = if want_left {
            let cluster = near(&self.left);
            let w = self.iterate(lambda, &cluster, true)?;
            self.left.push((lambda, w.clone()));
            Some(w)
        } else {
            None
        };
        Some((x, w))
    }

    /// At most [`MAX_SOLVES`] solves from the current factors, until the residual is at
    /// round-off level, ‖Hx − λx‖ ≤ 64nε‖H‖ ([`RESIDUAL_TOLERANCE`]; LAPACK `dlaein`); inside a
    /// cluster that never gets there, the best iterate is accepted at √ε‖H‖. Without a cluster the residual of the normalised iterate is known
    /// without a product: (H − λI)(x/‖x‖) = v/‖x‖ for the unit right-hand side v, up to the ε‖H‖
    /// pivot perturbation, so the growth ‖x‖ decides; inside a cluster the orthogonalisation
    /// changes the iterate and the residual is computed.
    fn iterate(&self, lambda: T, cluster: &[Vec<T>], transposed: bool) -> Option<Vec<T>> {
        let n = self.h.nrows();
        let tolerance = RESIDUAL_TOLERANCE * (n as f64) * f64::EPSILON * self.hnorm;
        // Start: all ones (LAPACK), or, inside a cluster, a vector that differs from the ones
        // used before so repeated roots get independent iterates.
        let mut x: Vec<T> = (0..n)
            .map(|i| {
                let t = if cluster.is_empty() {
                    1.0
                } else {
                    1.0 + ((i * (cluster.len() + 1) * 7919) % 101) as f64 / 101.0
                };
                T::from_real(t)
            })
            .collect();
        // The first right solve skips G: its right-hand side is G⁻¹·start, whose norm the
        // growth test needs (O(n)).
        let mut rhs_norm = if transposed || !cluster.is_empty() {
            (n as f64).sqrt()
        } else {
            self.lu.start_norm(&x)
        };
        let mut best = (f64::INFINITY, Vec::new());
        for iteration in 0..MAX_SOLVES {
            if transposed {
                self.lu.solve_transposed(&mut x);
            } else {
                self.lu.solve(&mut x, iteration > 0);
            }
            for c in cluster {
                let dot = c
                    .iter()
                    .zip(&x)
                    .fold(T::zero(), |s, (a, b)| s + a.conjugate() * *b);
                for (xi, ci) in x.iter_mut().zip(c) {
                    *xi -= dot * *ci;
                }
            }
            let norm = x.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                return None;
            }
            for c in x.iter_mut() {
                *c = c.unscale(norm);
            }
            let res = if cluster.is_empty() {
                rhs_norm / norm + 2.0 * eps_pivot(self.hnorm)
            } else {
                residual(self.h, &x, lambda, transposed)
            };
            if res <= tolerance {
                return Some(x);
            }
            if !cluster.is_empty() && res < best.0 {
                best = (res, x.clone());
            }
            rhs_norm = 1.0;
        }
        // Inside a large cluster of repeated roots (the identical lag and stall roots of many
        // ONERA stations at one inflow speed) each earlier member is exact only to round-off,
        // and orthogonalising against dozens of them leaves a residual floor a few times the
        // tolerance, growing with their number. An iterate at √(1 + m)·√ε‖H‖ (m earlier
        // members) is still an eigenvector to seven or eight digits: ample for labels,
        // participation and tracking. (Measured: the 29th member of a cluster of 32 ONERA
        // stations stopped at 1.6·√ε‖H‖.)
        let floor = ((1 + cluster.len()) as f64).sqrt() * f64::EPSILON.sqrt() * self.hnorm;
        (best.0 <= floor).then_some(best.1)
    }
}

/// The pivot perturbation ε‖H‖ of [`HessenbergLu::factor`].
fn eps_pivot(hnorm: f64) -> f64 {
    f64::EPSILON * hnorm
}

/// LU factors of the Hessenberg matrix H − λI with adjacent-row partial pivoting:
/// G (H − λI) = U, G = M_{n−2}P_{n−2}⋯M_0P_0, each M_k one multiplier below the diagonal.
///
/// U is stored row by row. Why: step k of the elimination touches only rows k and k+1, and
/// row-wise every step, every solve and the transposed solve run along contiguous memory; held
/// column by column (as H is), the factorisation strode across the whole matrix at every entry,
/// which on the 200-odd states of ONERA at 30 stations missed the cache at nearly every access.
/// The back-substitution's dot products run in four partial sums ([`dot`]).
struct HessenbergLu<T> {
    n: usize,
    /// U, row-major n × n (upper triangle used).
    u: Vec<T>,
    mult: Vec<T>,
    swapped: Vec<bool>,
    /// Row k of the elimination as it stands at step k, and row k + 1 of H − λI.
    carry: Vec<T>,
    next: Vec<T>,
}

impl<T: ComplexField<RealField = f64> + Copy> HessenbergLu<T> {
    /// Factors H − λI, `h_rows` being H row-major (n × n). Row k + 1 of an upper Hessenberg
    /// matrix is zero left of column k and untouched until step k, so each step pivots between
    /// the carried row k and row k + 1 read fresh from H, and writes row k of U once.
    fn factor(&mut self, h_rows: &[f64], n: usize, lambda: T, eps3: f64) {
        self.n = n;
        // Every entry on and above the diagonal is written below; the rest is never read.
        if self.u.len() != n * n {
            self.u.clear();
            self.u.resize(n * n, T::zero());
        }
        self.mult.clear();
        self.mult.resize(n.saturating_sub(1), T::zero());
        self.swapped.clear();
        self.swapped.resize(n.saturating_sub(1), false);
        if n == 0 {
            return;
        }
        let shifted_row = |row: &mut Vec<T>, i: usize| {
            row.clear();
            row.extend(h_rows[i * n..(i + 1) * n].iter().map(|&v| T::from_real(v)));
            row[i] -= lambda;
        };
        shifted_row(&mut self.carry, 0);
        let tiny = T::from_real(eps3);
        for k in 0..n - 1 {
            shifted_row(&mut self.next, k + 1);
            if self.next[k].modulus_squared() > self.carry[k].modulus_squared() {
                std::mem::swap(&mut self.carry, &mut self.next);
                self.swapped[k] = true;
            }
            if self.carry[k].modulus_squared() < eps3 * eps3 {
                // A (numerically) exact shift: the standard perturbation of inverse iteration.
                self.carry[k] = tiny;
            }
            let m = self.next[k] / self.carry[k];
            self.mult[k] = m;
            for (nj, cj) in self.next[k + 1..].iter_mut().zip(&self.carry[k + 1..]) {
                *nj -= m * *cj;
            }
            self.u[k * n + k..(k + 1) * n].copy_from_slice(&self.carry[k..]);
            std::mem::swap(&mut self.carry, &mut self.next);
        }
        if self.carry[n - 1].modulus_squared() < eps3 * eps3 {
            self.carry[n - 1] = tiny;
        }
        self.u[n * n - 1] = self.carry[n - 1];
    }

    /// ‖G⁻¹v‖₂: the right-hand side that a solve with `apply_g = false` actually solves for.
    fn start_norm(&self, v: &[T]) -> f64 {
        let mut w = v.to_vec();
        for k in (0..self.n.saturating_sub(1)).rev() {
            let wk = w[k];
            w[k + 1] += self.mult[k] * wk;
            if self.swapped[k] {
                w.swap(k, k + 1);
            }
        }
        w.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt()
    }

    /// Solves (H − λI) x = v in place; with `apply_g = false` solves U x = v (the first step of
    /// LAPACK's inverse iteration, whose start vector is then G⁻¹v).
    fn solve(&self, v: &mut [T], apply_g: bool) {
        let n = self.n;
        if apply_g {
            for k in 0..n.saturating_sub(1) {
                if self.swapped[k] {
                    v.swap(k, k + 1);
                }
                let vk = v[k];
                v[k + 1] -= self.mult[k] * vk;
            }
        }
        for i in (0..n).rev() {
            // Row i of U against the entries already solved.
            let row = &self.u[i * n..(i + 1) * n];
            v[i] = (v[i] - dot(&row[i + 1..], &v[i + 1..])) / row[i];
        }
    }

    /// Solves (H − λI)ᵀ w = v in place: Uᵀz = v, then w = Gᵀz. (Gᵀ comes after the triangular
    /// solve here, so unlike [`Self::solve`] it cannot be folded into the start vector.)
    fn solve_transposed(&self, v: &mut [T]) {
        let n = self.n;
        for i in 0..n {
            // Uᵀz = v by rows of U: once z_i is known it leaves every later equation, first
            // row first (the order of the column-wise dot products).
            let row = &self.u[i * n..(i + 1) * n];
            v[i] /= row[i];
            let vi = v[i];
            for (vj, uij) in v[i + 1..].iter_mut().zip(&row[i + 1..]) {
                *vj -= *uij * vi;
            }
        }
        for k in (0..n.saturating_sub(1)).rev() {
            let vk1 = v[k + 1];
            v[k] -= self.mult[k] * vk1;
            if self.swapped[k] {
                v.swap(k, k + 1);
            }
        }
    }
}

/// `Σ aᵢbᵢ` in four interleaved partial sums. One running sum makes every term wait for the
/// last addition (the back-substitution's n²/2 terms per solve ran at the adder's latency, not
/// its throughput); four independent ones keep it busy. A fixed order, so every run and thread
/// gives the same bits.
fn dot<T: ComplexField<RealField = f64> + Copy>(a: &[T], b: &[T]) -> T {
    let mut lanes = [T::zero(); 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let (a_rest, b_rest) = (a4.remainder(), b4.remainder());
    for (x, y) in a4.zip(b4) {
        for l in 0..4 {
            lanes[l] += x[l] * y[l];
        }
    }
    let mut tail = T::zero();
    for (x, y) in a_rest.iter().zip(b_rest) {
        tail += *x * *y;
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
}

/// ‖Hx − λx‖₂ (or ‖Hᵀx − λx‖₂) for upper Hessenberg H.
fn residual<T: ComplexField<RealField = f64> + Copy>(
    h: &DMatrix<f64>,
    x: &[T],
    lambda: T,
    transposed: bool,
) -> f64 {
    let n = h.nrows();
    let mut r: Vec<T> = x.iter().map(|&v| -(lambda * v)).collect();
    for j in 0..n {
        let col = &h.as_slice()[j * n..j * n + (j + 2).min(n)];
        if transposed {
            // (Hᵀx)_j = Σ_i H_ij x_i.
            r[j] += col
                .iter()
                .zip(x)
                .fold(T::zero(), |s, (hij, xi)| s + xi.scale(*hij));
        } else {
            let xj = x[j];
            for (ri, hij) in r.iter_mut().zip(col) {
                *ri += xj.scale(*hij);
            }
        }
    }
    r.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt()
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::numeric::eigen::tests::repeated_roots;
    use crate::numeric::hessenberg::hessenberg_eigenvalues;

    /// A 64-state matrix (above [`PARALLEL_FROM`]) with a cluster of four identical
    /// oscillators, a cluster of six identical real roots, and distinct roots coupled to
    /// them, in Hessenberg form, with its roots one per pair.
    pub(crate) fn clustered() -> (DMatrix<f64>, Vec<Complex<f64>>) {
        let n = 64;
        let mut a = repeated_roots(n, 4, [-9.0, -0.3], 6, -2.0);
        // The rest: distinct roots, coupled one way into the clusters so that these stay exact.
        for i in 14..n {
            for j in 0..n {
                a[(i, j)] = ((i * 31 + j * 17) as f64).sin() * if j >= 14 { 1.0 } else { 0.1 };
            }
        }
        let (_, h) = nalgebra::linalg::Hessenberg::new(a).unpack();
        let values = hessenberg_eigenvalues(h.clone())
            .unwrap()
            .into_iter()
            .filter(|l| l.im >= 0.0)
            .collect();
        (h, values)
    }

    #[test]
    fn two_threads_give_the_vectors_of_one_pass_bit_for_bit() {
        let (h, values) = clustered();
        let hnorm = h.norm();
        let radius = CLUSTER_RADIUS * f64::EPSILON * hnorm;
        let (first, second) = balanced_halves(&values, radius);
        assert!(!first.is_empty() && !second.is_empty());
        // No cluster is split: every near pair of one kind is on one side.
        let side = |k: usize| first.contains(&k);
        let mut near_pairs = 0;
        for k in 0..values.len() {
            for j in 0..k {
                let same_kind = (values[j].im == 0.0) == (values[k].im == 0.0);
                if same_kind && (values[j] - values[k]).norm() <= radius {
                    near_pairs += 1;
                    assert_eq!(side(j), side(k), "roots {j} and {k} split");
                }
            }
        }
        // The clusters are there to be kept together (3 + 15 pairs at least, one per root).
        assert!(near_pairs >= 3 + 15, "{near_pairs} near pairs");
        let all: Vec<usize> = (0..values.len()).collect();
        let sequential = group_vectors(&h, hnorm, &values, &all, true).unwrap();
        let parallel = root_vectors(&h, hnorm, &values, true).unwrap();
        assert_eq!(sequential, parallel);
    }
}
