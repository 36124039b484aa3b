//! Every eigenvalue of an upper Hessenberg matrix with its vectors: the QR iteration
//! (`hessenberg.rs`) and inverse iteration (`inverse_iteration.rs`) scheduled on the cores
//! (docs/model.md §6.1).
//!
//! The QR iteration is sequential and the vectors wait for eigenvalues, but not for all of them:
//! the bottom of the matrix converges first, and a converged eigenvalue is final. So when the
//! caller is not itself one of the thread pool's workers (the explorer's solve, one command's
//! analysis: a sweep's points already fill the pool), a second thread starts on each root's
//! vectors as the iteration finds it, and once the iteration ends both threads share what is
//! left. The iteration stays on the caller's thread and starts at once; the second thread is a
//! job on rayon's pool ([`alongside`]). Handing both halves to the pool with `rayon::join`
//! instead put the wake-up of a sleeping worker, and of the caller at the end, on the critical
//! path (on the 2-core VM that made the key-press bench bimodal, 2.7 ms or 4 ms).
//!
//! Each vector comes out bit for bit as one sequential pass gives it: a root's vectors depend
//! only on its own shift and the earlier members of its cluster of (numerically) repeated roots,
//! so a root alone in its cluster is final as streamed, and every cluster with more than one
//! member is computed again afterwards, whole and in order.

use super::alongside;
use super::hessenberg::{hessenberg_eigenvalues, hessenberg_eigenvalues_as_found};
use super::inverse_iteration::{
    clusters, group_vectors, root_vectors, RootSolver, RootVectors, CLUSTER_RADIUS, PARALLEL_FROM,
};
use crossbeam_channel::Receiver;
use nalgebra::{Complex, DMatrix};
use std::sync::Arc;

/// The eigenvalues of `h` (one per real root and per conjugate pair, the member with ω ≥ 0, in
/// the order of the diagonal) and each one's right and, when `want_left`, left vectors; `None`
/// when the QR iteration does not converge or a vector fails its residual check.
pub(super) fn eigenpairs(
    h: &DMatrix<f64>,
    hnorm: f64,
    want_left: bool,
) -> Option<(Vec<Complex<f64>>, Vec<RootVectors>)> {
    if h.nrows() >= PARALLEL_FROM && rayon::current_thread_index().is_none() {
        overlapped(h, hnorm, want_left)
    } else {
        let values = one_per_pair(&hessenberg_eigenvalues(h.clone())?);
        let vectors = root_vectors(h, hnorm, &values, want_left)?;
        Some((values, vectors))
    }
}

/// The members with ω ≥ 0 of every root, in order.
fn one_per_pair(all: &[Complex<f64>]) -> Vec<Complex<f64>> {
    all.iter().copied().filter(|l| l.im >= 0.0).collect()
}

/// A root found by the QR iteration: its place on the diagonal and its value.
type Found = (usize, Complex<f64>);

/// The QR iteration on this thread, feeding its roots to inverse iteration on another as they
/// converge (see the module's comment).
fn overlapped(
    h: &DMatrix<f64>,
    hnorm: f64,
    want_left: bool,
) -> Option<(Vec<Complex<f64>>, Vec<RootVectors>)> {
    let (sender, receiver) = crossbeam_channel::unbounded::<Found>();
    let (shared, queue) = (Arc::new(h.clone()), receiver.clone());
    // If the second thread never started, the caller has drained the queue by the time it runs
    // that piece itself, and the piece finds nothing to do.
    let ((all, mine), theirs) = alongside(
        || {
            let all = hessenberg_eigenvalues_as_found(h.clone(), |place, lambda| {
                if lambda.im >= 0.0 {
                    // The receivers live until both pieces are done with them.
                    let _ = sender.send((place, lambda));
                }
            });
            // The iteration is over: once the queue is empty, both pieces stop.
            drop(sender);
            (all, vectors_of_found(h, hnorm, want_left, &receiver))
        },
        move || vectors_of_found(&shared, hnorm, want_left, &queue),
    );
    let all = all?;
    // By place on the diagonal; a root whose vectors failed stays `None` like one never computed.
    let mut streamed: Vec<Option<RootVectors>> = vec![None; all.len()];
    for (place, vectors) in mine.into_iter().chain(theirs) {
        streamed[place] = vectors;
    }
    let values = one_per_pair(&all);
    let mut vectors: Vec<Option<RootVectors>> = (0..all.len())
        .filter(|&p| all[p].im >= 0.0)
        .map(|p| streamed[p].take())
        .collect();
    for members in clusters(&values, CLUSTER_RADIUS * f64::EPSILON * hnorm) {
        if members.len() > 1 {
            let again = group_vectors(h, hnorm, &values, &members, want_left)?;
            for (k, v) in members.into_iter().zip(again) {
                vectors[k] = Some(v);
            }
        }
    }
    let vectors = vectors.into_iter().collect::<Option<Vec<_>>>()?;
    Some((values, vectors))
}

/// Inverse iteration on every root that comes down `found`, until it is closed and empty.
fn vectors_of_found(
    h: &DMatrix<f64>,
    hnorm: f64,
    want_left: bool,
    found: &Receiver<Found>,
) -> Vec<(usize, Option<RootVectors>)> {
    let mut solver = RootSolver::new(h, hnorm);
    found
        .iter()
        .map(|(place, lambda)| (place, solver.vectors(lambda, want_left)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::alongside::tests::every_worker_held;
    use crate::numeric::inverse_iteration::tests::clustered;

    /// Clusters of repeated roots (streamed, then computed again) beside distinct ones: the
    /// matrix, its norm, its roots and their vectors (right and left) from one sequential pass.
    fn clustered_with_one_pass() -> (DMatrix<f64>, f64, Vec<Complex<f64>>, Vec<RootVectors>) {
        let (h, values) = clustered();
        let hnorm = h.norm();
        let all: Vec<usize> = (0..values.len()).collect();
        let sequential = group_vectors(&h, hnorm, &values, &all, true).unwrap();
        (h, hnorm, values, sequential)
    }

    #[test]
    fn overlapped_gives_the_vectors_of_one_pass_bit_for_bit() {
        let (h, hnorm, values, sequential) = clustered_with_one_pass();
        let (found, vectors) = overlapped(&h, hnorm, true).unwrap();
        assert_eq!(found, values);
        assert_eq!(vectors, sequential);
        // From a test thread (outside the pool) the dispatcher takes the overlapped path.
        assert!(rayon::current_thread_index().is_none());
        assert_eq!(eigenpairs(&h, hnorm, true).unwrap().1, sequential);
        // From inside a pool (a sweep's points), the sequential iteration and two halves.
        let pooled = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap()
            .install(|| eigenpairs(&h, hnorm, false).unwrap());
        let all: Vec<usize> = (0..values.len()).collect();
        let right_only = group_vectors(&h, hnorm, &values, &all, false).unwrap();
        assert_eq!(pooled.1, right_only);
    }

    /// With every thread of the pool busy, the helper cannot start: the caller does every root
    /// itself and then runs the helper's piece on an empty queue instead of waiting for it (the
    /// explorer's key press while a Campbell diagram fills the pool).
    #[test]
    fn a_busy_pool_costs_the_overlap_not_the_answer() {
        let (h, hnorm, values, sequential) = clustered_with_one_pass();
        let release = every_worker_held();
        let (done, result) = crossbeam_channel::bounded(1);
        let h_owned = h.clone();
        std::thread::spawn(move || {
            let _ = done.send(overlapped(&h_owned, hnorm, true));
        });
        let answer = result.recv_timeout(std::time::Duration::from_secs(20));
        drop(release);
        let (found, vectors) = answer
            .expect("the caller waited for a helper that could not start")
            .unwrap();
        assert_eq!(found, values);
        assert_eq!(vectors, sequential);
    }
}
