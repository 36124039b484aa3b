//! Analyses on top of the physics: eigen-analysis with labelled modes, mode tracking (MAC),
//! flutter-boundary search, parameter sweeps and time simulation (docs/model.md §6–§7).

pub mod campbell;
pub mod cancel;
pub mod eigen;
pub mod flutter;
pub mod grid;
pub mod identify;
pub mod mode;
pub mod mode_shape;
pub mod response;
pub mod simulate;
pub mod solve;
pub mod sweep;
pub mod tracking;
