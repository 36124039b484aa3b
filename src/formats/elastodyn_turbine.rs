//! ElastoDyn main files (OpenFAST): the turbine around the blades — rotor geometry, hub,
//! nacelle, drivetrain and where the tower file is.
//!
//! Only what a stability model of the whole turbine needs is read; the blade files the main
//! file names (`BldFile`) are not, since an ElastoDyn blade has no torsion and the blades come
//! from the preset's own blade files. Every value keeps the file's units and signs (OpenFAST's:
//! `OverHang` negative for an upwind rotor, `ShftTilt` negative when the shaft tilts the rotor
//! up, `PreCone` negative toward the wind). A value no turbine can have (a negative mass or
//! stiffness, a tower top below its base) is an error naming the file and line here, so that
//! nothing downstream needs to know where a number came from.

use super::text::{read_text, Bound, Source};
use crate::error::Result;
use std::path::{Path, PathBuf};

/// What an ElastoDyn main file says about the turbine, in its own units.
#[derive(Debug, Clone, PartialEq)]
pub struct ElastoDynTurbine {
    /// `NumBl`.
    pub blades: usize,
    /// `TipRad`, `HubRad` (m): rotor apex to the blade tip and to the blade root.
    pub tip_radius: f64,
    pub hub_radius: f64,
    /// `PreCone(k)` (deg), one per blade.
    pub precone_deg: Vec<f64>,
    /// `HubCM` (m): rotor apex to the hub's centre of mass, positive downwind.
    pub hub_cm: f64,
    /// `OverHang` (m): yaw axis to the rotor apex along the shaft, negative upwind.
    pub overhang: f64,
    /// `ShftTilt` (deg).
    pub shaft_tilt_deg: f64,
    /// `Twr2Shft` (m): tower top up to the shaft.
    pub tower_to_shaft: f64,
    /// `NacCMxn`, `NacCMyn`, `NacCMzn` (m): the nacelle's centre of mass from the tower top
    /// (downwind, lateral, up).
    pub nacelle_cm: [f64; 3],
    /// `TowerHt`, `TowerBsHt` (m): the tower top and its base above the ground (or sea level).
    pub tower_height: f64,
    pub tower_base_height: f64,
    /// `HubMass` (kg), `HubIner` (kg·m², about the rotor axis).
    pub hub_mass: f64,
    pub hub_inertia: f64,
    /// `GenIner` (kg·m², about the high-speed shaft).
    pub generator_inertia: f64,
    /// `NacMass` (kg), `NacYIner` (kg·m², about the yaw axis), `YawBrMass` (kg).
    pub nacelle_mass: f64,
    pub nacelle_yaw_inertia: f64,
    pub yaw_bearing_mass: f64,
    /// `GBoxEff` (%), `GBRatio` (-).
    pub gearbox_efficiency_pct: f64,
    pub gearbox_ratio: f64,
    /// `DTTorSpr` (N·m/rad), `DTTorDmp` (N·m·s/rad): the drivetrain's torsion, on the
    /// low-speed shaft.
    pub drivetrain_stiffness: f64,
    pub drivetrain_damping: f64,
    /// `DrTrDOF`, `GenDOF`: whether the drivetrain twists and the generator turns.
    pub drivetrain_dof: bool,
    pub generator_dof: bool,
    /// `TwrFile` exactly as written (see [`ElastoDynTurbine::tower_file_path`]).
    pub tower_file: String,
}

impl ElastoDynTurbine {
    /// The tower file's path: OpenFAST resolves a relative `TwrFile` against the directory of
    /// the main file, not the working directory.
    pub fn tower_file_path(&self, main: &Path) -> PathBuf {
        main.parent()
            .unwrap_or_else(|| Path::new(""))
            .join(&self.tower_file)
    }
}

pub fn read_turbine(path: &Path) -> Result<ElastoDynTurbine> {
    parse_turbine(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an ElastoDyn main file; `origin` names it in errors.
pub fn parse_turbine(text: &str, origin: &str) -> Result<ElastoDynTurbine> {
    let src = Source::new(origin, text);
    let line = |key: &str| src.key(key, 0);
    let value = |key: &str, bound: Bound| src.bounded(key, 0, bound);
    let blades_line = line("NumBl")?;
    let blades = src.count(&blades_line, 1)?;
    if blades > 3 {
        return Err(src.err(
            blades_line.idx,
            format!("NumBl is {blades}: ElastoDyn models 1 to 3 blades"),
        ));
    }
    let precone_deg = (1..=blades)
        .map(|k| value(&format!("PreCone({k})"), Bound::Any))
        .collect::<Result<Vec<_>>>()?;
    let tip_radius = value("TipRad", Bound::Positive)?;
    let hub_line = line("HubRad")?;
    let hub_radius = value("HubRad", Bound::NonNegative)?;
    if hub_radius >= tip_radius {
        return Err(src.err(
            hub_line.idx,
            format!("HubRad ({hub_radius} m) must be less than TipRad ({tip_radius} m)"),
        ));
    }
    let tower_height = value("TowerHt", Bound::Any)?;
    let base_line = line("TowerBsHt")?;
    let tower_base_height = src.number(&base_line)?;
    if tower_base_height >= tower_height {
        return Err(src.err(
            base_line.idx,
            format!(
                "TowerBsHt ({tower_base_height} m) must be below TowerHt ({tower_height} m): \
                 the tower needs a length"
            ),
        ));
    }
    let tower = line("TwrFile")?;
    if tower.value.trim().is_empty() {
        return Err(src.err(tower.idx, "expected a file name for TwrFile, found none"));
    }
    let flag = |key: &str| line(key).and_then(|k| src.flag(&k));
    Ok(ElastoDynTurbine {
        blades,
        tip_radius,
        hub_radius,
        precone_deg,
        hub_cm: value("HubCM", Bound::Any)?,
        overhang: value("OverHang", Bound::Any)?,
        shaft_tilt_deg: angle(&src, "ShftTilt")?,
        tower_to_shaft: value("Twr2Shft", Bound::Any)?,
        nacelle_cm: [
            value("NacCMxn", Bound::Any)?,
            value("NacCMyn", Bound::Any)?,
            value("NacCMzn", Bound::Any)?,
        ],
        tower_height,
        tower_base_height,
        hub_mass: value("HubMass", Bound::NonNegative)?,
        hub_inertia: value("HubIner", Bound::NonNegative)?,
        generator_inertia: value("GenIner", Bound::NonNegative)?,
        nacelle_mass: value("NacMass", Bound::NonNegative)?,
        nacelle_yaw_inertia: value("NacYIner", Bound::NonNegative)?,
        yaw_bearing_mass: value("YawBrMass", Bound::NonNegative)?,
        gearbox_efficiency_pct: efficiency(&src)?,
        gearbox_ratio: value("GBRatio", Bound::Positive)?,
        drivetrain_stiffness: value("DTTorSpr", Bound::Positive)?,
        drivetrain_damping: value("DTTorDmp", Bound::NonNegative)?,
        drivetrain_dof: flag("DrTrDOF")?,
        generator_dof: flag("GenDOF")?,
        tower_file: tower.value.to_string(),
    })
}

/// `ShftTilt` within ±90°: beyond that the shaft would point the rotor backward.
fn angle(src: &Source, key: &str) -> Result<f64> {
    let k = src.key(key, 0)?;
    let v = src.number(&k)?;
    if v.abs() >= 90.0 {
        return Err(src.err(
            k.idx,
            format!("{key} is {v}°: it must lie strictly between -90° and 90°"),
        ));
    }
    Ok(v)
}

/// `GBoxEff` in (0, 100] %.
fn efficiency(src: &Source) -> Result<f64> {
    let k = src.key("GBoxEff", 0)?;
    let v = src.number(&k)?;
    if !(v > 0.0 && v <= 100.0) {
        return Err(src.err(
            k.idx,
            format!("GBoxEff is {v} %: it must lie in (0, 100] %"),
        ));
    }
    Ok(v)
}
