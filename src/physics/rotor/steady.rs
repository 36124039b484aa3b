//! A steady operating point as reported (docs/model.md §12.2–§12.6): the BEM's flow with the
//! setting it ran at. The point itself is the static aeroelastic equilibrium's
//! ([`crate::physics::operating`]), which runs [`super::bem::solve`] on the deflected blade.

use super::bem::OperatingState;
use serde::Serialize;

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
