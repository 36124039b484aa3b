//! Pure physics: functions of parameters, no threads, no terminal (docs/model.md §2–§5).
//! Flow: `section` → `structure` (on `basis`) → `inflow` → `aero` → `system`.

pub mod aero;
pub mod basis;
pub mod blade;
pub mod cross_section;
pub mod inflow;
pub mod laminate;
pub mod operating;
pub mod rotor;
pub mod section;
pub mod structure;
pub mod system;
pub mod turbine;
