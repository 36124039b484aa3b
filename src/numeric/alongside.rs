//! Two independent pieces of one solve, the second on the other core when it is free
//! (docs/model.md §6.1): the caller runs the first at once and a job on rayon's pool takes the
//! second. The caller never waits for the job to start: if it has not started when the first
//! piece is done (every worker busy with a sweep's points, say), the caller runs the second piece
//! itself, and the job finds nothing to do. A job on the pool's existing threads, not a thread of
//! its own (whose start cost about 0.15 ms on the 2-core VM); the caller runs the first piece
//! itself, not `rayon::join` from outside the pool (which hands both to the workers and put two
//! wake-ups on the critical path: 1–5 ms more per turbine operating point, measured).

use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex, PoisonError};

/// `(here(), there())`, `there` on another core when one is free. A panic in either reaches the
/// caller as its own.
pub(crate) fn alongside<A, B, F>(here: impl FnOnce() -> A, there: F) -> (A, B)
where
    B: Send + 'static,
    F: FnOnce() -> B + Send + 'static,
{
    let slot = Arc::new(Mutex::new(Some(there)));
    let (send, result) = crossbeam_channel::bounded(1);
    let job = Arc::clone(&slot);
    rayon::spawn(move || {
        if let Some(there) = take(&job) {
            let _ = send.send(catch_unwind(AssertUnwindSafe(there)));
        }
    });
    let a = here();
    let b = match take(&slot) {
        Some(there) => there(),
        // The job took it, and sends what it gave or how it panicked.
        None => match result.recv() {
            Ok(Ok(b)) => b,
            Ok(Err(panic)) => resume_unwind(panic),
            Err(_) => resume_unwind(Box::new("the second piece's job ended without an answer")),
        },
    };
    (a, b)
}

/// The closure, for whichever side asks first.
fn take<F>(slot: &Mutex<Option<F>>) -> Option<F> {
    slot.lock().unwrap_or_else(PoisonError::into_inner).take()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    #[test]
    fn both_pieces_answer_in_their_places() {
        let (a, b) = alongside(|| 2 + 2, || "four".to_string());
        assert_eq!((a, b.as_str()), (4, "four"));
    }

    /// Holds every worker of rayon's pool until the returned sender is dropped (a Campbell
    /// diagram filling the pool), once each has started.
    pub(crate) fn every_worker_held() -> crossbeam_channel::Sender<()> {
        let (release, hold) = crossbeam_channel::unbounded::<()>();
        let (busy, all_busy) = crossbeam_channel::unbounded::<()>();
        for _ in 0..rayon::current_num_threads() {
            let (hold, busy) = (hold.clone(), busy.clone());
            rayon::spawn(move || {
                let _ = busy.send(());
                let _ = hold.recv();
            });
        }
        for _ in 0..rayon::current_num_threads() {
            all_busy.recv().unwrap();
        }
        release
    }

    /// With every worker held, the job cannot start: the caller runs the second piece itself
    /// instead of waiting (the explorer's key press while a Campbell diagram fills the pool).
    #[test]
    fn a_busy_pool_leaves_both_pieces_to_the_caller() {
        let release = every_worker_held();
        let caller = std::thread::current().id();
        let (done, answer) = crossbeam_channel::bounded(1);
        std::thread::spawn(move || {
            let _ = done.send(alongside(
                || std::thread::current().id(),
                || std::thread::current().id(),
            ));
        });
        let (here, there) = answer
            .recv_timeout(std::time::Duration::from_secs(20))
            .expect("the caller waited for a job that could not start");
        drop(release);
        assert_eq!(here, there, "the caller ran both pieces");
        assert_ne!(here, caller);
    }

    #[test]
    fn a_panic_in_the_second_piece_reaches_the_caller() {
        let caught = catch_unwind(|| alongside(|| 1, || -> i32 { panic!("second piece") }));
        let message = caught.expect_err("the panic was lost");
        assert_eq!(message.downcast_ref::<&str>(), Some(&"second piece"));
    }
}
