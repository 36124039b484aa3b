//! The Gauss stations of one aerodynamic description, built once per station count and shared by
//! every operating point of the preset that holds it (docs/model.md §12.6).
//!
//! Why: a station's section is a blend of the neighbouring airfoils' polars (§12.1), and
//! building the 30 stations of the IEA 15MW is about 0.5 ms, more than a third of its steady
//! operating point once they are kept; the stations depend only on the blade and the count, so a
//! sweep along the schedule or a key press that moves the wind speed reuses them.

use crate::error::Result;
use crate::physics::rotor::bem::AeroStation;
use crate::physics::rotor::AeroBlade;
use std::sync::{Arc, Mutex};

/// How many station counts are kept (the most recently built): an operating point and a
/// convergence study's neighbours.
const KEPT_COUNTS: usize = 4;

/// Stations of one blade by count. Clones share the built stations (a preset edited in keys
/// other than its aerodynamic files keeps them); the holder builds a new one whenever the blade is
/// read again, so stations never outlive the blade they were built on.
#[derive(Clone, Default)]
pub struct GaussStations(Arc<Mutex<Vec<Built>>>);

/// Stations built for one count.
type Built = (usize, Arc<Vec<AeroStation>>);

impl GaussStations {
    /// The `count` Gauss stations of `blade` ([`AeroStation::gauss`]), built on first use.
    pub fn of(&self, blade: &AeroBlade, count: usize) -> Result<Arc<Vec<AeroStation>>> {
        let built = |cache: &[Built]| {
            cache
                .iter()
                .find(|(n, _)| *n == count)
                .map(|(_, s)| Arc::clone(s))
        };
        // A poisoned lock (a panic elsewhere while it was held) only loses the cache.
        if let Some(s) = self.0.lock().ok().and_then(|c| built(&c)) {
            return Ok(s);
        }
        let stations = Arc::new(AeroStation::gauss(blade, count)?);
        if let Ok(mut cache) = self.0.lock() {
            if built(&cache).is_none() {
                // A sweep over `aero.stations` would otherwise keep every count it visited.
                if cache.len() == KEPT_COUNTS {
                    cache.remove(0);
                }
                cache.push((count, Arc::clone(&stations)));
            }
        }
        Ok(stations)
    }
}

/// The cache is no part of what a preset says: two holders compare equal whatever they built.
impl PartialEq for GaussStations {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for GaussStations {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("GaussStations")
    }
}
