//! What the steady operating point of a checked preset is built from (docs/model.md
//! §12.2–§12.3): the rotor from `operating.blades`, `blade.hub_radius` and the aerodynamic
//! description, and the stations at `aero.stations` Gauss points. The operating point itself is
//! the static aeroelastic equilibrium's ([`crate::physics::operating`]), which runs
//! [`super::bem::solve`] on the deflected blade at the schedule's setting.

use super::bem::{OperatingState, Rotor, Station};
use super::AeroBlade;
use crate::error::{Error, Result};
use crate::preset::ValidPreset;
use serde::Serialize;
use std::sync::Arc;

/// One steady operating point with the setting it ran at.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteadyPoint {
    /// U (m/s).
    pub wind_speed: f64,
    /// Ω (rpm), from the schedule or `operating.rotor_speed`.
    pub rotor_speed_rpm: f64,
    /// θ_p (deg), from the schedule or `operating.pitch`.
    pub pitch_deg: f64,
    pub state: OperatingState,
}

/// The rotor a preset describes.
pub fn rotor_of(p: &ValidPreset, blade: &AeroBlade) -> Rotor {
    Rotor {
        blades: p.operating.blades,
        hub_radius: p.blade.hub_radius,
        tip_radius: p.blade.hub_radius + blade.span_range().1,
        precone: p.operating.precone.to_radians(),
        shaft_tilt: p.operating.shaft_tilt.to_radians(),
        high_thrust: p.aero.high_thrust,
    }
}

/// The preset's aerodynamic description, or an error saying which keys give one.
pub fn aero_blade_of(p: &ValidPreset) -> Result<&AeroBlade> {
    p.aero_blade()
        .map(|b| b.as_ref())
        .ok_or_else(|| Error::Invalid {
            origin: p.origin.clone(),
            message: "the steady operating point needs the rotor's aerodynamic description: \
                  aero.blade_file, aero.airfoils and aero.pitch_axis_file (AeroDyn 15 with a \
                  BeamDyn blade) or aero.ae_file and aero.pc_file (HAWC2 with a HAWC2 blade)"
                .into(),
        })
}

/// The preset's `aero.stations` Gauss stations on its aerodynamic description, built once per
/// blade and count and shared by the presets edited from it ([`crate::physics::rotor::stations`]).
pub fn aero_stations_of(p: &ValidPreset) -> Result<Arc<Vec<Station>>> {
    // The preset holds stations exactly when it holds a blade; without one, the blade's error.
    match p.aero_stations() {
        Some(stations) => stations,
        None => {
            aero_blade_of(p).and_then(|blade| Station::gauss(blade, p.aero.stations).map(Arc::new))
        }
    }
}
