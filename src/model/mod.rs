//! The model builder: the one place where a checked preset becomes the plain inputs of the
//! physics (docs/model.md). Each file turns one part of the preset into what one part of the
//! physics takes: the section ([`section`]), the structure ([`structure`], a tabulated blade's
//! build in [`blade`], a HAWC2 model's files in [`htc`]), the aerodynamics ([`aero`]), the
//! operating point and its schedule ([`operating`]), and the coupled system ([`system`]). It
//! reads the files a preset names when the preset is checked and holds what they gave
//! ([`files`], carried by the checked preset), and keeps the builds a sweep or the explorer asks
//! for again ([`kept`]).
//!
//! A turbine's several bodies (blades, drivetrain, tower; docs/architecture.md) are assembled
//! here too: each body's physics takes its own inputs, and this layer reads them from the preset
//! and the files it names.

pub mod aero;
pub mod blade;
pub mod files;
pub mod htc;
pub mod kept;
pub mod operating;
pub mod section;
pub mod structure;
pub mod system;
pub mod turbine;
pub mod turbine_htc;

pub use section::section_properties;
pub use structure::{assemble, for_preset};
pub use system::{linearised, system, system_with_equilibrium};
