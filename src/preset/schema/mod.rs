//! The preset schema: one struct per TOML table, every field with its unit and its default (the
//! paper's blade at its operating point), unknown fields rejected by serde. [`Preset`] holds the
//! tables (one file per table below it) and what its files gave when read ([`RotorFiles`]).

pub mod aero;
pub mod blade;
pub mod operating;
pub mod section;
pub mod simulation;
pub mod structure;
pub mod view;

pub use aero::*;
pub use blade::*;
pub use operating::*;
pub use section::*;
pub use simulation::*;
pub use structure::*;
pub use view::*;

use crate::physics::rotor::schedule::Table as ScheduleTable;
use crate::physics::rotor::stations::GaussStations;
use crate::physics::rotor::AeroBlade;
use crate::preset::files::FileBase;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A complete description of one case, as read (check it with [`Preset::validate`] before use). Every section and field has a default (the
/// paper's blade at its operating point), so a preset lists only what differs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Preset {
    pub meta: Meta,
    pub blade: Blade,
    pub section: Section,
    pub operating: Operating,
    pub structure: StructureSettings,
    pub aero: Aero,
    pub simulation: Simulation,
    pub view: View,
    /// Where this preset came from (file path or `built-in NAME`), for error messages.
    #[serde(skip)]
    pub origin: String,
    /// Where a relative `blade.file` resolves: the preset file's directory, the blade files
    /// built into the binary, or the working directory.
    #[serde(skip)]
    pub base: FileBase,
    /// The tabulated blade read from `blade.file` when the preset was checked (`None` for
    /// `blade.source = "uniform"`), so that the files are read once per preset, not per solve.
    #[serde(skip)]
    pub tabulated: Option<Tabulated>,
    /// The aerodynamic description and operating table read from the `aero.*` and
    /// `operating.schedule_file` keys when the preset was checked (`None` when it names none).
    #[serde(skip)]
    pub rotor_files: Option<RotorFiles>,
    /// Which of the schedule's outputs an edit (`--set`, `--vary`, the explorer) has set by
    /// hand: those hold, the schedule gives the rest (docs/model.md §12.3).
    #[serde(skip)]
    pub schedule_overrides: ScheduleOverrides,
    /// What loading the preset left unused at the user's request (a schedule file a `--set
    /// operating.schedule` set aside), for the command line to say.
    #[serde(skip)]
    pub notes: Vec<String>,
}

#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Meta {
    pub name: String,
    pub description: String,
}

/// The rotor's files as read when the preset was checked, with the keys they were read from:
/// an edit of any of them reads the files again.
#[derive(Debug, Clone, PartialEq)]
pub struct RotorFiles {
    /// What was read: (aero keys, `blade.twist_file`, `operating.schedule_file`).
    pub keys: (Vec<String>, String, String),
    /// The aerodynamic description (`None` when the preset names no aerodynamic files).
    pub blade: Option<Arc<AeroBlade>>,
    /// The operating table (`None` unless `operating.schedule = "table"`).
    pub table: Option<Arc<ScheduleTable>>,
    /// The Gauss stations built on `blade`, by count (new whenever the blade is read again).
    pub stations: GaussStations,
}

impl RotorFiles {
    /// The keys that decide what [`RotorFiles`] holds, in the form it stores them.
    pub fn keys_of(p: &Preset) -> (Vec<String>, String, String) {
        let a = &p.aero;
        let mut aero = vec![
            a.blade_file.clone(),
            a.pitch_axis_file.clone(),
            a.ae_file.clone(),
            a.ae_set.to_string(),
            a.pc_file.clone(),
            a.prebend_file.clone(),
        ];
        aero.extend(a.airfoils.iter().cloned());
        aero.extend(p.blade.htc_keys());
        let table = match p.operating.schedule {
            Schedule::Table => p.operating.schedule_file.clone(),
            _ => String::new(),
        };
        (aero, p.blade.twist_file.clone(), table)
    }
}

impl Default for Preset {
    fn default() -> Self {
        Preset {
            meta: Meta::default(),
            blade: Blade::default(),
            section: Section::default(),
            operating: Operating::default(),
            structure: StructureSettings::default(),
            aero: Aero::default(),
            simulation: Simulation::default(),
            view: View::default(),
            origin: "defaults".into(),
            base: FileBase::default(),
            tabulated: None,
            rotor_files: None,
            schedule_overrides: ScheduleOverrides::default(),
            notes: Vec::new(),
        }
    }
}
