//! A preset's aeroelastic system (docs/model.md §6): its structure, stations along the
//! structure's span and strip model; a real blade in the wind on the inflow of its steady
//! operating point (§12.6).

use super::aero::{model_for, operating_point};
use super::operating::{in_the_wind, on_schedule, steady, unsteadiness};
use super::structure::for_preset;
use crate::error::Result;
use crate::physics::inflow::stations;
use crate::physics::system::{LinearSystem, System};
use crate::physics::turbine::rotor_system;
use crate::preset::{TurbineModel, ValidPreset};
use nalgebra::DVector;

/// The system of `p` at its scheduled rotor speed and pitch.
pub fn system(p: &ValidPreset) -> Result<System> {
    system_with_equilibrium(p).map(|(system, _)| system)
}

/// [`system`] with the static equilibrium when building the system already found it (a real
/// blade's steady operating point ends on it, §12.6): linearising about it
/// ([`System::linearise_at`]) then skips a second, identical Newton solve.
pub fn system_with_equilibrium(p: &ValidPreset) -> Result<(System, Option<DVector<f64>>)> {
    if in_the_wind(p) {
        return steady(p, unsteadiness(p)).map(|(_, op)| (op.system, Some(op.equilibrium)));
    }
    let scheduled = on_schedule(p)?;
    let p = &scheduled;
    let structure = for_preset(p)?;
    let model = model_for(p)?;
    let stations = stations(
        structure.length(),
        structure.hub_radius(),
        &operating_point(p),
        p.aero.stations,
    );
    Ok((System::from_parts(structure, stations, model)?, None))
}

/// The state matrix of `p` about its equilibrium, from its `system` and the `equilibrium`
/// building it found ([`system_with_equilibrium`]): the blade's, or for a rotor
/// (`turbine.model`, docs/model.md §13) the ground-frame rotor's made of that blade.
pub fn linearised(
    p: &ValidPreset,
    system: &System,
    equilibrium: Option<DVector<f64>>,
) -> Result<LinearSystem> {
    // The schedule's speed is read only for a rotor: a blade's linearisation, on every sweep
    // point and key press, needs none of it.
    let inputs = match p.turbine.model {
        TurbineModel::Blade => None,
        TurbineModel::Rotor | TurbineModel::Turbine => {
            let rpm = super::operating::scheduled_rotor_speed(p)?;
            super::turbine::rotor_inputs(p, rpm)?
        }
    };
    match inputs {
        None => system.linearise_at(equilibrium),
        Some(inputs) => {
            let x = match equilibrium {
                Some(x) => x,
                None => system.equilibrium()?,
            };
            rotor_system(system, &x, &inputs)
        }
    }
}
