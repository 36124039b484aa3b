//! Numerical linear algebra with no physics in it, one algorithm per file (as faer lays itself
//! out). It exists so that the analyses read as physics and the solvers can be tested, measured
//! and reused on plain matrices: the dense non-symmetric eigendecomposition behind the stability
//! analysis ([`decompose`]) and its parts, isolation by permutation, balancing, the exponential
//! propagators of the time response ([`phi_functions`]), faer's general eigendecomposition (also
//! used for the strong-form natural modes), banded symmetric matrices and the lowest eigenpairs
//! of a banded pencil by shift-invert block Lanczos (the tabulated blade's modes), the
//! multi-blade coordinate transform of a rotor's states ([`mbc`]), LU factors that serve many
//! right-hand sides (`lu.rs`), and the optimal assignment
//! that mode labelling and tracking share ([`hungarian`]), and the running of a solve's two
//! independent pieces on two cores (`alongside.rs`). Nothing here depends on the rest of the
//! crate but its error type.

mod alongside;
mod assignment;
pub(crate) mod balance;
pub mod banded;
pub mod cholesky;
pub(crate) mod eigen;
mod eigenpairs;
pub(crate) mod faer_evd;
mod hessenberg;
mod hessenberg_reduction;
mod inverse_iteration;
mod isolate;
pub mod lanczos;
pub(crate) mod lu;
pub mod mbc;
pub mod phi_functions;
pub mod products;
pub mod root;
mod roots;

pub(crate) use alongside::alongside;
pub use assignment::hungarian;
pub use eigen::{decompose, eigen_decomposition};
pub use roots::{shares, Roots, Solver};
