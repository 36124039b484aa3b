//! The preset schema: one struct per TOML table, every field with its unit and its default (the
//! paper's blade at its operating point), unknown fields rejected by serde. [`Preset`] holds the
//! tables (one file per table below it) and where it came from; what its files give is read when
//! it is checked and held beside it ([`crate::preset::ValidPreset`]).

pub mod aero;
pub mod blade;
pub mod operating;
pub mod section;
pub mod simulation;
pub mod structure;
pub mod turbine;
pub mod view;

pub use aero::*;
pub use blade::*;
pub use operating::*;
pub use section::*;
pub use simulation::*;
pub use structure::*;
pub use turbine::*;
pub use view::*;

use crate::preset::files::FileBase;
use serde::{Deserialize, Serialize};

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
    pub turbine: Turbine,
    pub simulation: Simulation,
    pub view: View,
    /// Where this preset came from (file path or `built-in NAME`), for error messages.
    #[serde(skip)]
    pub origin: String,
    /// Where a relative `blade.file` resolves: the preset file's directory, the blade files
    /// built into the binary, or the working directory.
    #[serde(skip)]
    pub base: FileBase,
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

impl Default for Preset {
    fn default() -> Self {
        Preset {
            meta: Meta::default(),
            blade: Blade::default(),
            section: Section::default(),
            operating: Operating::default(),
            structure: StructureSettings::default(),
            aero: Aero::default(),
            turbine: Turbine::default(),
            simulation: Simulation::default(),
            view: View::default(),
            origin: "defaults".into(),
            base: FileBase::default(),
            schedule_overrides: ScheduleOverrides::default(),
            notes: Vec::new(),
        }
    }
}
