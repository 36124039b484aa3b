//! Cooperative cancellation. The explorer's worker raises the flag of a request in flight when a
//! newer one replaces it; the long analyses (boundary search, sweeps, a re-solve) poll it between
//! their solves and stop with [`Error::Cancelled`], so the newest position is answered within its
//! latency budget even after a slow one. Commands that run once use [`Cancel::never`].

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A cancellation flag shared between the requester and the computation.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Option<Arc<AtomicBool>>);

impl Cancel {
    /// A flag that can be raised with [`Cancel::cancel`].
    pub fn new() -> Cancel {
        Cancel(Some(Arc::new(AtomicBool::new(false))))
    }

    /// A flag that is never raised (one-shot commands, tests).
    pub fn never() -> Cancel {
        Cancel(None)
    }

    /// Ask the computation to stop at its next check.
    pub fn cancel(&self) {
        if let Some(flag) = &self.0 {
            flag.store(true, Ordering::Relaxed);
        }
    }

    pub fn is_cancelled(&self) -> bool {
        self.0.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
    }

    /// `Err(Error::Cancelled)` once the flag is raised.
    pub fn check(&self) -> Result<()> {
        if self.is_cancelled() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }
}
