//! flutterscope: aeroelastic stability of rotating composite wind-turbine blades.
//!
//! Data flows one way: `physics` (section → structure → aero → system) → `analysis`
//! (eigen, tracking, flutter, sweep, simulate) → `explorer` (worker → state → ui). `numeric`
//! (eigendecomposition, balancing, assignment) holds the linear algebra both physics and
//! analysis use, with no physics in it. `formats` reads the blade definition files engineers
//! already have (OpenFAST, HAWC2) into plain tables in the files' own units, for physics to map.
//! The physics reference is `docs/model.md`; each module cites the section it implements.

/// Every program built on the library (the binary, its tests and benchmarks) allocates through
/// mimalloc: an analysis makes many small vectors per operating point (see Cargo.toml).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

pub mod analysis;
pub mod cli;
pub mod commands;
pub mod error;
pub mod explorer;
pub mod formats;
pub mod model;
pub mod numeric;
pub mod physics;
pub mod plot;
pub mod precision;
pub mod preset;
