//! A preset's turbine (docs/model.md §13): `turbine.model` and the values `turbine.file` gives,
//! as the plain inputs of [`crate::physics::turbine`].

use crate::error::{Error, Result};
use crate::formats::elastodyn_tower::ElastoDynTower;
use crate::formats::elastodyn_turbine::ElastoDynTurbine;
use crate::physics::structure::Structure;
use crate::physics::turbine::drivetrain::{Drivetrain, Generator};
use crate::physics::turbine::ground::GroundRotor;
use crate::physics::turbine::rotor::Rotor;
use crate::physics::turbine::tower::{Tower, TowerInputs, TowerSection, TowerTop};
use crate::physics::turbine::{RotorInputs, Support};
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
    if let Some((hawc2, name)) = p.files().hawc2_turbine() {
        let drivetrain = generator.map(|generator| Drivetrain {
            generator,
            torque_slope: p.turbine.torque_slope,
            ..hawc2.drivetrain.clone()
        });
        let support = match p.turbine.model {
            TurbineModel::Turbine => Some(hawc2.support.clone().ok_or_else(|| Error::Invalid {
                origin: p.origin.clone(),
                message: format!("{name}: its tower was not read"),
            })?),
            _ => None,
        };
        return Ok(Some(RotorInputs {
            blades: p.operating.blades,
            drivetrain,
            support,
            rotor_speed: rpm * PI / 30.0,
        }));
    }
    let turbine_file = || {
        p.files().turbine().ok_or_else(|| Error::Invalid {
            origin: p.origin.clone(),
            message: format!(
                "turbine.model = \"{}\" with turbine.drivetrain = \"{}\" needs turbine.file",
                p.turbine.model.name(),
                p.turbine.drivetrain.name()
            ),
        })
    };
    let drivetrain = match generator {
        None => None,
        Some(generator) => {
            let (file, name) = turbine_file()?;
            Some(
                drivetrain_of(file, generator, p.turbine.torque_slope)
                    .map_err(|e| e.at(name.clone()))?,
            )
        }
    };
    let support = match p.turbine.model {
        TurbineModel::Turbine => {
            let (file, name) = turbine_file()?;
            let (tower, tower_name) = p.files().tower().ok_or_else(|| Error::Invalid {
                origin: p.origin.clone(),
                message: format!("{name}: its tower file was not read"),
            })?;
            Some(support_of(file, tower).map_err(|e| e.at(tower_name.clone()))?)
        }
        _ => None,
    };
    Ok(Some(RotorInputs {
        blades: p.operating.blades,
        drivetrain,
        support,
        rotor_speed: rpm * PI / 30.0,
    }))
}

/// The tower an ElastoDyn main file and its tower file give (docs/model.md §13.6): the
/// tower's length `TowerHt − TowerBsHt`, its distributed properties with `AdjTwMa`,
/// `AdjFASt`, `AdjSSSt` applied, the mode shapes, tuners and damping of the tower file; on
/// top `YawBrMass`, `NacMass` at `NacCMxn/yn/zn`, `HubMass` at `HubCM` along the shaft from
/// the apex at `OverHang`, `Twr2Shft`; `HubIner`, `GenIner` and `GBRatio` for what rolls with
/// the nacelle. `ShftTilt` and `PreCone` are read but not modelled (§13.6 says why).
pub fn support_of(t: &ElastoDynTurbine, tower: &ElastoDynTower) -> Result<Support> {
    let [fa, ss] = [tower.fore_aft_shapes, tower.side_side_shapes];
    let inputs = TowerInputs {
        length: t.tower_height - t.tower_base_height,
        sections: tower
            .stations
            .iter()
            .map(|s| TowerSection {
                height_fraction: s.height_fraction,
                mass_density: s.mass_density * tower.mass_factor,
                fore_aft_stiffness: s.fore_aft_stiffness * tower.fore_aft_factor,
                side_side_stiffness: s.side_side_stiffness * tower.side_side_factor,
            })
            .collect(),
        shapes: [fa[0], fa[1], ss[0], ss[1]],
        tuners: [
            tower.fore_aft_tuners[0],
            tower.fore_aft_tuners[1],
            tower.side_side_tuners[0],
            tower.side_side_tuners[1],
        ],
        damping: [
            tower.fore_aft_damping_pct[0],
            tower.fore_aft_damping_pct[1],
            tower.side_side_damping_pct[0],
            tower.side_side_damping_pct[1],
        ]
        .map(|pct| pct / 100.0),
    };
    let top = TowerTop {
        yaw_bearing_mass: t.yaw_bearing_mass,
        nacelle_mass: t.nacelle_mass,
        nacelle_cm: t.nacelle_cm,
        // ElastoDyn's nacelle turns only in yaw (`NacYIner`), which its tower cannot do.
        nacelle_inertia: [[0.0; 3]; 3],
        hub_mass: t.hub_mass,
        hub_cm: t.hub_cm,
        overhang: t.overhang,
        shaft_height: t.tower_to_shaft,
    };
    Ok(Support {
        tower: Tower::new(&inputs, &top)?,
        hub_inertia: t.hub_inertia,
        generator_inertia: t.generator_inertia,
        gear_ratio: t.gearbox_ratio,
    })
}

/// The drivetrain an ElastoDyn main file gives: `HubIner`, `GenIner · GBRatio²`, `DTTorSpr`,
/// `DTTorDmp` (the file's `GenDOF` and `DrTrDOF` switches are not read: `turbine.drivetrain`
/// says what turns).
fn drivetrain_of(
    t: &ElastoDynTurbine,
    generator: Generator,
    torque_slope: f64,
) -> Result<Drivetrain> {
    Drivetrain {
        hub_inertia: t.hub_inertia,
        generator_inertia: t.generator_inertia * t.gearbox_ratio * t.gearbox_ratio,
        stiffness: t.drivetrain_stiffness,
        damping: t.drivetrain_damping,
        generator,
        torque_slope,
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
    let rotor = Rotor::new(Arc::clone(&blade), &inputs, &q_eq, 0.0)?;
    Ok(Arc::new(GroundRotor::new(&rotor, inputs.rotor_speed)?))
}
