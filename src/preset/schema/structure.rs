//! The `[structure]` table: the structural model's form (Galerkin modes of the paper's blade or
//! finite elements of a tabulated one) and its sizes.

use serde::{Deserialize, Serialize};

pub use crate::physics::structure::galerkin::Form;

/// Default `structure.min_elements`: the first 12 modes of the NREL 5MW blade within 0.1 % of
/// their converged values. The twist is linear in each element, so the torsion modes converge
/// slowest (as h²): measured against 600 elements extrapolated in h², torsion 3 (14.69 Hz) is
/// 0.33 % high at 60 elements, 0.105 % at 100 and 0.063 % at 120; every flap and edge mode is
/// within 0.001 % from 60 elements on.
pub const MIN_ELEMENTS: usize = 120;

/// `structure.modes` of a tabulated blade whose preset does not set it: the first 12 modes
/// reach past the third flap and second torsion modes of a multi-megawatt blade.
pub const TABULATED_MODES: usize = 12;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct StructureSettings {
    /// Uniform blade: N, Galerkin functions per field. Tabulated blade: K, the blade modes
    /// retained (listed by `modes`, the basis of the aeroelastic model).
    pub modes: usize,
    pub form: Form,
    /// η1, first-mode loss factor (C_s = (η1/ω1) K_e), uniform blade.
    pub loss_factor: f64,
    /// Tabulated blade: fewest finite elements; the mesh follows the input stations, then the
    /// longest elements are halved until there are this many (docs/model.md §11.3).
    pub min_elements: usize,
    /// Tabulated blade: shear-deformable (Timoshenko) elements with the files' shear stiffness;
    /// `false`: rigid in shear, the Euler–Bernoulli beam (docs/model.md §11.2–§11.3).
    pub shear: bool,
    /// Tabulated blade: the reference axis's prebend (`aero.prebend_file`'s `BlCrvAC`, or the
    /// htc's `c2_def`) in the structure as well as in the aerodynamics, a beam about the curved
    /// axis; `false`: the beam straight along the pitch axis, the prebend in the aerodynamics
    /// only (docs/model.md §11.9).
    pub curved: bool,
    /// Tabulated blade: the static response of the reduced basis's modes beyond the first K
    /// added to the operating point's equilibrium (the truncated basis's correction,
    /// docs/model.md §12.6); `false`: the equilibrium on the K modes alone.
    pub static_correction: bool,
    /// Tabulated blade: modal damping ratio of every flap mode; `None`: the blade file's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_flap: Option<f64>,
    /// … of every edge mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_edge: Option<f64>,
    /// … of every torsion mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_torsion: Option<f64>,
}

impl Default for StructureSettings {
    fn default() -> Self {
        StructureSettings {
            modes: 5,
            form: Form::Weak,
            loss_factor: 0.02,
            min_elements: MIN_ELEMENTS,
            shear: true,
            curved: true,
            static_correction: true,
            damping_flap: None,
            damping_edge: None,
            damping_torsion: None,
        }
    }
}
