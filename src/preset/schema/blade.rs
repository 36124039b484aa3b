//! The `[blade]` table: the blade's length, mass and stiffness source (the paper's uniform blade
//! or a real blade's tabulated files) and the files' damping and coupling settings.

use serde::{Deserialize, Serialize};

/// Where the blade's structure comes from (`blade.source`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BladeSource {
    /// The paper's uniform flap–torsion blade: `blade.length` and the `section.*` keys.
    Uniform,
    /// A BeamDyn primary file (key points, initial twist) and the blade file it names (6×6
    /// stiffness and mass per station), docs/model.md §11.5.
    Beamdyn,
    /// A HAWC2 blade: a model's htc file (`blade.htc_file`, body `blade.htc_body`), or an st
    /// file, subset `blade.st_subset` of set `blade.st_set`, twisted by `blade.twist_file`.
    Hawc2,
    /// A WindIO ontology file: the sections from its layup (docs/model.md §11.12), the ply
    /// angle turning the layers `section.rotate_layers` names.
    Windio,
}

impl BladeSource {
    pub fn name(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "beamdyn",
            BladeSource::Hawc2 => "hawc2",
            BladeSource::Windio => "windio",
        }
    }

    /// The name as the source's program spells it, for reports.
    pub fn title(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "BeamDyn",
            BladeSource::Hawc2 => "HAWC2",
            BladeSource::Windio => "WindIO",
        }
    }

    /// A blade described by tables of sections along the span (docs/model.md §11).
    pub fn is_tabulated(self) -> bool {
        self != BladeSource::Uniform
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Blade {
    pub source: BladeSource,
    /// The BeamDyn primary file or the HAWC2 st file, relative to the preset's directory (empty
    /// for the uniform blade).
    pub file: String,
    /// An AeroDyn 15 blade file whose `BlTwist` turns a HAWC2 blade's sections (the st file
    /// carries no twist; HAWC2 takes it from the htc's c2_def), relative to the preset's
    /// directory (hawc2 source only).
    pub twist_file: String,
    /// A HAWC2 model's htc file, relative to the preset's directory: its main body
    /// `blade.htc_body` gives the st file, set and subset, the twist, the prebend and the
    /// damping, its `aero` block the ae and pc files (hawc2 source only; instead of `file`,
    /// `twist_file`, `st_set`, `st_subset` and `aero.prebend_file`).
    pub htc_file: String,
    /// The main body of `htc_file` that is the blade.
    pub htc_body: String,
    /// The model's root folder, against which the htc's own paths resolve (HAWC2 resolves them
    /// against the folder it is run from), relative to the preset's directory; empty: the
    /// folder above the one `htc_file` is in (a model's `htc/` folder).
    pub htc_root: String,
    /// Span L (m). A tabulated blade's is its file's.
    pub length: f64,
    /// Hub radius r_hub (m); r = r_hub + x.
    pub hub_radius: f64,
    /// HAWC2 st set `#N` (hawc2 source).
    pub st_set: usize,
    /// HAWC2 st subset `$N` within the set (hawc2 source).
    pub st_subset: usize,
    /// α: adds `α·√(EI_flap·GJ)` to the flap–twist coupling of every station of a tabulated
    /// blade, on top of its files' (docs/model.md §11.7); α > 0 twists toward feather under
    /// downwind bending. Tabulated blades only.
    pub bend_twist_coupling: f64,
}

impl Blade {
    /// `htc_file`, `htc_body`, `htc_root`: what an htc blade is read from.
    pub fn htc_keys(&self) -> [String; 3] {
        [
            self.htc_file.clone(),
            self.htc_body.clone(),
            self.htc_root.clone(),
        ]
    }

    /// Whether the blade is read from a HAWC2 model's htc file.
    pub fn from_htc(&self) -> bool {
        !self.htc_file.trim().is_empty()
    }
}

impl Default for Blade {
    fn default() -> Self {
        Blade {
            source: BladeSource::Uniform,
            file: String::new(),
            twist_file: String::new(),
            htc_file: String::new(),
            htc_body: "blade1".into(),
            htc_root: String::new(),
            length: 8.4455,
            hub_radius: 0.0,
            st_set: 1,
            st_subset: 1,
            bend_twist_coupling: 0.0,
        }
    }
}
