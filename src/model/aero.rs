//! A preset's aerodynamics as the physics takes it (docs/model.md §1, §5, §12.2–§12.3): the strip
//! section and model, the rigid operating point and its stations, and a real blade's rotor and
//! aerodynamic stations.

use crate::error::{Error, Result};
use crate::physics::aero::onera::{Coefficients, OneraModel};
use crate::physics::aero::quasi_steady::QuasiSteady;
use crate::physics::aero::theodorsen::Theodorsen;
use crate::physics::aero::{NoAero, StripModel, StripSection};
use crate::physics::inflow::{stations, OperatingPoint, Station};
use crate::physics::rotor::bem::{self, Rotor};
use crate::physics::rotor::AeroBlade;
use crate::preset::{AeroModel, Onera, ValidPreset};
use std::sync::Arc;

/// The per-length section and air the strip models of the paper's blade read.
pub fn strip_section(p: &ValidPreset) -> StripSection {
    StripSection {
        chord: p.section.chord,
        ea_offset: p.section.ea_offset,
        air_density: p.operating.air_density,
        lift_slope: p.aero.lift_slope,
        drag_coefficient: p.aero.drag_coefficient,
    }
}

/// The strip model `aero.model` selects (docs/model.md §5).
pub fn model_for(p: &ValidPreset) -> Result<Box<dyn StripModel>> {
    let section = strip_section(p);
    match p.aero.model {
        AeroModel::None => Ok(Box::new(NoAero)),
        AeroModel::QuasiSteady => Ok(Box::new(QuasiSteady::new(section))),
        AeroModel::Theodorsen => Ok(Box::new(Theodorsen::new(section))),
        AeroModel::Onera => Ok(Box::new(OneraModel::new(
            section,
            onera_coefficients(&p.aero.onera),
            p.aero.onera.forcing,
        ))),
        AeroModel::Hgm => Err(Error::Invalid {
            origin: p.origin.clone(),
            message: "aero.model = \"hgm\" reads each station's airfoil polar: it runs on a \
                      tabulated blade with its aerodynamic description, not on the uniform blade"
                .into(),
        }),
    }
}

/// The `aero.onera.*` coefficients; the preset's stall angles are in degrees.
pub fn onera_coefficients(o: &Onera) -> Coefficients {
    Coefficients {
        lambda_l: o.lambda_l,
        a0l: o.a0l,
        damping: [o.a_l, o.a_m, o.a_d],
        stiffness: [o.r_l, o.r_m, o.r_d],
        lift_slopes: (o.a_l1, o.a_l2),
        moment_slopes: (o.a_m1, o.a_m2),
        drag_polynomial: (o.a_d1, o.a_d2, o.a_d3),
        cm0: o.cm0,
        cd0: o.cd0,
        alpha1: o.alpha1.to_radians(),
        alpha2: o.alpha2.to_radians(),
    }
}

/// The preset's rigid operating point (docs/model.md §1).
pub fn operating_point(p: &ValidPreset) -> OperatingPoint {
    let o = &p.operating;
    OperatingPoint {
        wind: o.wind_speed,
        induction: o.induction,
        omega: p.omega(),
        tunnel: o.tunnel_speed,
        pitch: p.pitch_rad(),
        twist_root: o.twist_root.to_radians(),
        twist_tip: o.twist_tip.to_radians(),
        inflow: o.inflow,
    }
}

/// The stations of a preset (`aero.stations` of them) on its blade's span.
pub fn preset_stations(p: &ValidPreset) -> Vec<Station> {
    stations(
        p.blade.length,
        p.blade.hub_radius,
        &operating_point(p),
        p.aero.stations,
    )
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
/// blade and count and shared by the presets edited from it ([`super::files::ReadFiles`]).
pub fn aero_stations_of(p: &ValidPreset) -> Result<Arc<Vec<bem::AeroStation>>> {
    // The read files hold stations exactly when they hold a blade; without one, the blade's error.
    match p.aero_stations() {
        Some(stations) => stations,
        None => aero_blade_of(p)
            .and_then(|blade| bem::AeroStation::gauss(blade, p.aero.stations).map(Arc::new)),
    }
}
