//! Cross-section analysis by two-dimensional finite elements (docs/model.md §11.11): the
//! anisotropic beam theory of Giavotto et al. (1983) as BECAS discretises it (Blasques 2012),
//! from a meshed section to its 6×6 stiffness and mass matrices and the engineering properties
//! read from them.
//!
//! The chain is [`material`] (each ply's 3-D stiffness in the section's axes) → [`mesh`] (4-node
//! quadrilaterals with their plies; [`layup`] meshes a section from its layers and webs) → [`solve`] (the warping and the 6×6 matrices about a chosen
//! point) → [`properties`] (centres, principal axes, stiffnesses, mass). Inputs and outputs are
//! plain numbers: the section's own plane `(x, y)` with `z` along the beam, right-handed; the
//! matrices are in BeamDyn's order (shear x, shear y, extension, bending about x, about y,
//! torsion), so a mesh drawn in BeamDyn's section axes (x₁ toward the suction side, x₂ toward the
//! trailing edge) gives a blade file's matrices directly.

pub mod layup;
pub mod material;
pub mod mesh;
pub mod properties;
pub mod solve;

pub use material::Orthotropic;
pub use mesh::{Element, Mesh, Ply};
pub use properties::SectionProperties;
pub use solve::{analyse, analyse_reusing, BeamMatrices, Factorisation};
