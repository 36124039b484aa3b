//! A preset's turbine (docs/model.md §13): `turbine.model` and the values `turbine.file` gives,
//! as the plain inputs of [`crate::physics::turbine`].

use crate::error::{Error, Result};
use crate::formats::elastodyn_turbine::ElastoDynTurbine;
use crate::physics::structure::Structure;
use crate::physics::turbine::drivetrain::{Drivetrain, Generator};
use crate::physics::turbine::ground::GroundRotor;
use crate::physics::turbine::rotor::Rotor;
use crate::physics::turbine::RotorInputs;
use crate::preset::{DrivetrainModel, TurbineModel, ValidPreset};
use std::f64::consts::PI;
use std::sync::Arc;

/// The rotor `p` describes around its blade, at rotor speed `rpm`; none for the blade alone.
pub fn rotor_inputs(p: &ValidPreset, rpm: f64) -> Result<Option<RotorInputs>> {
    if p.turbine.model == TurbineModel::Blade {
        return Ok(None);
    }
    let generator = match p.turbine.drivetrain {
        DrivetrainModel::Rigid => None,
        DrivetrainModel::Free => Some(Generator::Free),
        DrivetrainModel::Locked => Some(Generator::Locked),
    };
    let drivetrain = match generator {
        None => None,
        Some(generator) => {
            let (file, name) = p.files().turbine().ok_or_else(|| Error::Invalid {
                origin: p.origin.clone(),
                message: "turbine.drivetrain needs turbine.file".to_string(),
            })?;
            Some(drivetrain_of(file, generator).map_err(|e| e.at(name.clone()))?)
        }
    };
    Ok(Some(RotorInputs {
        blades: p.operating.blades,
        drivetrain,
        rotor_speed: rpm * PI / 30.0,
    }))
}

/// The drivetrain an ElastoDyn main file gives: `HubIner`, `GenIner · GBRatio²`, `DTTorSpr`,
/// `DTTorDmp` (the file's `GenDOF` and `DrTrDOF` switches are not read: `turbine.drivetrain`
/// says what turns).
fn drivetrain_of(t: &ElastoDynTurbine, generator: Generator) -> Result<Drivetrain> {
    Drivetrain {
        hub_inertia: t.hub_inertia,
        generator_inertia: t.generator_inertia * t.gearbox_ratio * t.gearbox_ratio,
        stiffness: t.drivetrain_stiffness,
        damping: t.drivetrain_damping,
        generator,
    }
    .checked()
}

/// The structure whose natural modes `modes` lists for `p` (on its schedule): the blade's, or
/// for a rotor the ground-frame rotor of that blade in vacuo, each blade at its static
/// deflection under its own centrifugal load.
pub fn structure_in_vacuo(p: &ValidPreset) -> Result<Arc<dyn Structure>> {
    let blade = super::structure::for_preset(p)?;
    let Some(inputs) = rotor_inputs(p, p.operating.rotor_speed)? else {
        return Ok(blade);
    };
    let q_eq = blade
        .stiffness()
        .lu()
        .solve(&blade.static_load())
        .ok_or_else(|| Error::numerical("the blade's stiffness is singular"))?;
    let rotor = Rotor::new(
        Arc::clone(&blade),
        inputs.blades,
        inputs.drivetrain,
        inputs.rotor_speed,
        &q_eq,
    )?;
    Ok(Arc::new(GroundRotor::new(&rotor, inputs.rotor_speed)?))
}
