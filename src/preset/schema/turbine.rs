//! The `[turbine]` table: what around the blade the model holds (docs/model.md §13): the blade
//! alone, clamped (the default), or the rotor of identical blades on its drivetrain, analysed in
//! the ground frame; and the file the drivetrain's values come from.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Turbine {
    pub model: TurbineModel,
    /// What gives the hub's and the drivetrain's values: `elastodyn` (an ElastoDyn main file)
    /// or `hawc2` (a HAWC2 model's htc file).
    pub source: TurbineSource,
    /// The turbine file (relative to the preset's directory).
    pub file: String,
    /// A HAWC2 model's htc file (relative to the preset's directory) for `source = "hawc2"`:
    /// its paths resolve from the folder above the htc file's, as HAWC2 runs.
    pub htc_file: String,
    /// The drivetrain of a `rotor`: the generator `free` (open loop, held by its constant
    /// torque), `locked` (a held brake), or `rigid`: no drivetrain, the hub turning at exactly
    /// the rotor speed (no file needed).
    pub drivetrain: DrivetrainModel,
    /// The generator torque's rise per unit of its speed (N·m·s/rad, on the low-speed shaft)
    /// with the generator free: 0 holds its torque constant (open loop); a speed controller's
    /// slope damps the drivetrain (region 2's `Q = k Ω²`: `2 Q / Ω`).
    pub torque_slope: f64,
}

/// `turbine.model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TurbineModel {
    /// One blade clamped at its root, in its rotating frame.
    Blade,
    /// Three identical blades on the drivetrain, the support rigid, in the ground frame.
    Rotor,
    /// The rotor on the tower (two fore–aft and two side–side bending modes) with the
    /// nacelle's and the hub's masses on its top, in the ground frame.
    Turbine,
}

/// `turbine.source`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TurbineSource {
    /// No turbine file.
    None,
    /// An OpenFAST ElastoDyn main file.
    Elastodyn,
    /// A HAWC2 model's htc file.
    Hawc2,
}

/// `turbine.drivetrain`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DrivetrainModel {
    Free,
    Locked,
    Rigid,
}

impl TurbineModel {
    pub fn name(self) -> &'static str {
        match self {
            TurbineModel::Blade => "blade",
            TurbineModel::Rotor => "rotor",
            TurbineModel::Turbine => "turbine",
        }
    }
}

impl DrivetrainModel {
    pub fn name(self) -> &'static str {
        match self {
            DrivetrainModel::Free => "free",
            DrivetrainModel::Locked => "locked",
            DrivetrainModel::Rigid => "rigid",
        }
    }
}

impl Default for Turbine {
    fn default() -> Self {
        Turbine {
            model: TurbineModel::Blade,
            source: TurbineSource::None,
            file: String::new(),
            htc_file: String::new(),
            drivetrain: DrivetrainModel::Free,
            torque_slope: 0.0,
        }
    }
}
