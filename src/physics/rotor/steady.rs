//! The steady operating point of a checked preset (docs/model.md §12.2–§12.3): the rotor from
//! `operating.blades`, `blade.hub_radius` and the aerodynamic description, the stations at
//! `aero.stations` Gauss points, rotor speed and pitch from `operating.schedule`, then the BEM.
//! The blade is rigid here: the static aeroelastic equilibrium re-runs [`bem::solve`] with the
//! elastic twist and flap as the blade's deflection.

use super::bem::{self, Conditions, OperatingState, Rotor, Station};
use super::schedule::{Law, Setting};
use super::AeroBlade;
use crate::error::{Error, Result};
use crate::preset::{Schedule, ValidPreset};
use serde::Serialize;
use std::f64::consts::PI;
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

/// The steady operating point at the preset's wind speed, rigid blade.
pub fn for_preset(p: &ValidPreset) -> Result<SteadyPoint> {
    let blade = aero_blade_of(p)?;
    let rotor = rotor_of(p, blade);
    let stations = aero_stations_of(p)?;
    let wind = p.operating.wind_speed;
    let air_density = p.operating.air_density;
    let solve_at = |s: Setting| {
        bem::solve(
            &rotor,
            &stations,
            &[],
            &Conditions {
                wind_speed: wind,
                rotor_speed: s.rotor_speed,
                pitch: s.pitch,
                air_density,
            },
        )
    };
    let setting = setting(p, &rotor, |s| solve_at(s).map(|st| st.power))
        .map_err(|e| e.at(p.operating_point()))?;
    let state = solve_at(setting).map_err(|e| e.at(p.operating_point()))?;
    Ok(SteadyPoint {
        wind_speed: wind,
        rotor_speed_rpm: setting.rotor_speed * 30.0 / PI,
        pitch_deg: setting.pitch.to_degrees(),
        state,
    })
}

/// Rotor speed and pitch at the preset's wind speed, as `operating.schedule` says; `power` is
/// the rotor's aerodynamic power at a setting (the law's pitch search).
pub fn setting(
    p: &ValidPreset,
    rotor: &Rotor,
    mut power: impl FnMut(Setting) -> Result<f64>,
) -> Result<Setting> {
    let o = &p.operating;
    match o.schedule {
        Schedule::None => Ok(Setting {
            rotor_speed: p.omega(),
            pitch: p.pitch_rad(),
        }),
        Schedule::Table => p
            .schedule_table()
            .ok_or_else(|| Error::numerical("operating.schedule = \"table\" without its table"))?
            .at(o.wind_speed),
        Schedule::Law => Law {
            rated_power: o.rated_power,
            rotor_speed_min: o.rotor_speed_min * PI / 30.0,
            rotor_speed_max: o.rotor_speed_max * PI / 30.0,
            tip_speed_ratio: o.tip_speed_ratio,
            tip_radius: rotor.tip_radius,
        }
        .at(o.wind_speed, |rotor_speed, pitch| {
            power(Setting { rotor_speed, pitch })
        }),
    }
}
