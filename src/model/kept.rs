//! The builds the model keeps for the next call: a structure, a blade's basis, the stations on an
//! aerodynamic description. An explorer that drags one knob, and the points of a sweep, ask for
//! the same build again and again. Keys are compared by value.

use crate::error::Result;
use std::sync::{Arc, Mutex};

/// The last few builds, newest last, found by their key.
pub struct Kept<K, V>(Mutex<Vec<(K, Arc<V>)>>);

impl<K: PartialEq, V> Default for Kept<K, V> {
    fn default() -> Kept<K, V> {
        Kept::new()
    }
}

impl<K: PartialEq, V> Kept<K, V> {
    pub const fn new() -> Kept<K, V> {
        Kept(Mutex::new(Vec::new()))
    }

    /// The newest build whose key satisfies `like`, if one is kept.
    pub fn newest(&self, like: impl Fn(&K) -> bool) -> Option<Arc<V>> {
        let kept = self.0.lock().unwrap_or_else(|e| e.into_inner());
        kept.iter()
            .rev()
            .find(|(k, _)| like(k))
            .map(|(_, v)| v.clone())
    }

    /// The build kept under `key`, or a new one from `build`, kept in place of the oldest
    /// when `capacity` are. A poisoned lock only means another thread panicked mid-push: the
    /// list is still whole.
    pub fn get_or_build(
        &self,
        key: K,
        capacity: usize,
        build: impl FnOnce() -> Result<V>,
    ) -> Result<Arc<V>> {
        let lock = || self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(hit) = lock().iter().find(|(k, _)| *k == key) {
            return Ok(hit.1.clone());
        }
        let built = Arc::new(build()?);
        let mut kept = lock();
        if kept.len() >= capacity {
            kept.remove(0);
        }
        kept.push((key, built.clone()));
        Ok(built)
    }
}
