//! The `[blade]` table: the blade's length, mass and stiffness source (the paper's uniform blade
//! or a real blade's tabulated files) and the files' damping and coupling settings.

use crate::physics::blade::source::TabulatedBlade;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Where the blade's structure comes from (`blade.source`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BladeSource {
    /// The paper's uniform flap–torsion blade: `blade.length` and the `section.*` keys.
    Uniform,
    /// A BeamDyn primary file (key points, initial twist) and the blade file it names (6×6
    /// stiffness and mass per station), docs/model.md §11.5.
    Beamdyn,
    /// A HAWC2 st file, subset `blade.st_subset` of set `blade.st_set`.
    Hawc2,
}

impl BladeSource {
    pub fn name(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "beamdyn",
            BladeSource::Hawc2 => "hawc2",
        }
    }

    /// The name as the source's program spells it, for reports.
    pub fn title(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "BeamDyn",
            BladeSource::Hawc2 => "HAWC2",
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

/// The tabulated blade a preset was checked with, and the keys it was read from: a change of
/// any of them (an edited preset) reads the files again.
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    pub source: BladeSource,
    pub file: String,
    pub twist_file: String,
    pub st_set: usize,
    pub st_subset: usize,
    pub blade: Arc<TabulatedBlade>,
}

impl Tabulated {
    /// Whether this was read from what `blade` now names.
    pub fn read_from(&self, blade: &Blade) -> bool {
        self.source == blade.source
            && self.file == blade.file
            && (self.source != BladeSource::Hawc2
                || (self.st_set, self.st_subset, &self.twist_file)
                    == (blade.st_set, blade.st_subset, &blade.twist_file))
    }
}

impl Default for Blade {
    fn default() -> Self {
        Blade {
            source: BladeSource::Uniform,
            file: String::new(),
            twist_file: String::new(),
            length: 8.4455,
            hub_radius: 0.0,
            st_set: 1,
            st_subset: 1,
            bend_twist_coupling: 0.0,
        }
    }
}
