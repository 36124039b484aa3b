//! Readers for the blade and turbine definition files engineers already have: OpenFAST BeamDyn,
//! ElastoDyn (blade, main and tower files), AeroDyn 15 and AirfoilInfo inputs, and the HAWC2 htc
//! (model), st, ae, pc and steady-operation files, and the WindIO ontology (YAML: the layup).
//!
//! Text in, plain tables out. A reader keeps the file's own units, axes and column meanings (each
//! field says which); mapping them into the model's frame is the physics layer's job, so nothing
//! here converts, interpolates or fills in a quantity the file does not state.
//!
//! Real files are hostile (truncated, hand-edited, the wrong file altogether), so every failure
//! is an [`Error::Format`](crate::error::Error::Format) naming the file, the 1-based line (0 for the file as a whole) and
//! what was expected there, and no input makes a reader panic or allocate beyond the file.
//! [`text::read_text`] is the one way a file reaches a reader: it refuses devices, pipes, directories
//! and oversized files before reading a byte of them.
//!
//! Values are separated by ASCII spaces and tabs, numbers may use Fortran exponents (`1.0D+00`)
//! and must be finite; each reader's `parse_*` takes the text and the name to put in errors,
//! its `read_*` a path.

pub mod aerodyn;
pub mod airfoil;
pub mod beamdyn;
pub mod elastodyn;
pub mod elastodyn_tower;
pub mod elastodyn_turbine;
pub mod hawc2_aero;
pub mod hawc2_st;
pub mod htc;
pub mod htc_turbine;
pub mod text;
pub mod text_file;
pub mod windio;
