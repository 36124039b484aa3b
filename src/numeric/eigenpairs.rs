//! Every eigenvalue of an upper Hessenberg matrix with its vectors: the QR iteration
//! (`hessenberg.rs`) and inverse iteration (`inverse_iteration.rs`) scheduled on the cores
//! (docs/model.md §6.1).
//!
//! The QR iteration is sequential and the vectors wait for eigenvalues, but not for all of them:
//! the bottom of the matrix converges first, and a converged eigenvalue is final. So when the
//! caller is not itself one of the thread pool's workers (the explorer's solve, one command's
//! analysis: a sweep's points already fill the pool), a second thread starts on each root's
//! vectors as the iteration finds it, and once the iteration ends both threads share what is
//! left. Each vector comes out bit for bit as one sequential pass gives it: a root's vectors
//! depend only on its own shift and the earlier members of its cluster of (numerically)
//! repeated roots, so a root alone in its cluster is final as streamed, and every cluster with
//! more than one member is computed again afterwards, whole and in order.

use super::hessenberg::{hessenberg_eigenvalues, hessenberg_eigenvalues_as_found};
use super::inverse_iteration::{
    clusters, group_vectors, root_vectors, RootSolver, RootVectors, CLUSTER_RADIUS, PARALLEL_FROM,
};
use crossbeam_channel::Receiver;
use nalgebra::{Complex, DMatrix};

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
    let other = receiver.clone();
    let work = |found: &Receiver<Found>| -> Vec<(usize, Option<RootVectors>)> {
        let mut solver = RootSolver::new(h, hnorm);
        found
            .iter()
            .map(|(place, lambda)| (place, solver.vectors(lambda, want_left)))
            .collect()
    };
    let ((all, mine), theirs) = rayon::join(
        || {
            let all = hessenberg_eigenvalues_as_found(h.clone(), |place, lambda| {
                if lambda.im >= 0.0 {
                    // The receivers live until both threads return.
                    let _ = sender.send((place, lambda));
                }
            });
            // The iteration is over: once the queue is empty, both threads stop.
            drop(sender);
            (all, work(&receiver))
        },
        || work(&other),
    );
    let all = all?;
    let mut streamed: Vec<Option<Option<RootVectors>>> = vec![None; all.len()];
    for (place, vectors) in mine.into_iter().chain(theirs) {
        streamed[place] = Some(vectors);
    }
    let places: Vec<usize> = (0..all.len()).filter(|&p| all[p].im >= 0.0).collect();
    let values = one_per_pair(&all);
    let mut vectors: Vec<Option<RootVectors>> = places
        .iter()
        .map(|&p| streamed[p].take().flatten())
        .collect();
    let cluster = clusters(&values, CLUSTER_RADIUS * f64::EPSILON * hnorm);
    for label in 0..values.len() {
        let members: Vec<usize> = (0..values.len()).filter(|&k| cluster[k] == label).collect();
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::inverse_iteration::tests::clustered;

    #[test]
    fn overlapped_gives_the_vectors_of_one_pass_bit_for_bit() {
        // Clusters of repeated roots (streamed, then computed again) beside distinct ones.
        let (h, values) = clustered();
        let hnorm = h.norm();
        let all: Vec<usize> = (0..values.len()).collect();
        let sequential = group_vectors(&h, hnorm, &values, &all, true).unwrap();
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
        let right_only = group_vectors(&h, hnorm, &values, &all, false).unwrap();
        assert_eq!(pooled.1, right_only);
    }
}
