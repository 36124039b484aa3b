//! The Gauss stations of one aerodynamic description, built once per station count and shared by
//! every operating point of the preset that holds it (docs/model.md §12.6).
//!
//! Why: a station's section is a blend of the neighbouring airfoils' polars (§12.1), and
//! building the 30 stations of the IEA 15MW is about 0.5 ms, more than a third of its steady
//! operating point once they are kept; the stations depend only on the blade and the count, so a
//! sweep along the schedule or a key press that moves the wind speed reuses them.

use crate::error::Result;
use crate::physics::rotor::bem::Station;
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
type Built = (usize, Arc<Vec<Station>>);

impl GaussStations {
    /// The `count` Gauss stations of `blade` ([`Station::gauss`]), built on first use.
    pub fn of(&self, blade: &AeroBlade, count: usize) -> Result<Arc<Vec<Station>>> {
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
        let stations = Arc::new(Station::gauss(blade, count)?);
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

#[cfg(test)]
mod tests {
    use crate::physics::operating::on_schedule;
    use crate::preset::Preset;
    use std::sync::Arc;

    /// What a sweep along the schedule relies on: moving the wind speed, and then to the
    /// schedule's setting, keeps the aerodynamic description as read and the stations as built;
    /// a new station count builds new ones, and the old count's are still there.
    #[test]
    fn operating_points_share_the_blade_and_its_stations() {
        let p = Preset::load("iea15mw", &[]).unwrap();
        let stations = p.aero_stations().unwrap().unwrap();
        let q = on_schedule(&p.with("operating.wind_speed", 14.0).unwrap()).unwrap();
        assert!(Arc::ptr_eq(
            p.aero_blade().unwrap(),
            q.aero_blade().unwrap()
        ));
        assert!(Arc::ptr_eq(&stations, &q.aero_stations().unwrap().unwrap()));
        let fewer = q.with("aero.stations", 12.0).unwrap();
        let twelve = fewer.aero_stations().unwrap().unwrap();
        assert_eq!((stations.len(), twelve.len()), (30, 12));
        assert!(Arc::ptr_eq(&stations, &p.aero_stations().unwrap().unwrap()));
        // Only the last few counts stay: after four more, 30 is built again.
        for count in 8..12 {
            let other = p.with("aero.stations", f64::from(count)).unwrap();
            assert_eq!(
                other.aero_stations().unwrap().unwrap().len(),
                count as usize
            );
        }
        let again = p.aero_stations().unwrap().unwrap();
        assert!(!Arc::ptr_eq(&stations, &again) && again.len() == 30);
        // A blade read again (another aerodynamic file key) gets stations of its own.
        let straight = p.edited(|e| e.aero.prebend_file.clear()).unwrap();
        assert!(!Arc::ptr_eq(
            p.aero_blade().unwrap(),
            straight.aero_blade().unwrap()
        ));
        let own = straight.aero_stations().unwrap().unwrap();
        assert!(!Arc::ptr_eq(&stations, &own));
    }
}
