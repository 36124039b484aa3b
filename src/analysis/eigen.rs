//! Eigen-analysis of the linearised aeroelastic system (MODEL.md §6).

use crate::error::Result;
use crate::preset::Preset;
use nalgebra::Complex;
use serde::Serialize;

/// The stability verdict of one operating point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Stable,
    /// An oscillatory mode (ω > 0) has σ ≥ 0.
    Flutter,
    /// A non-oscillatory mode (ω = 0) has σ ≥ 0.
    Divergence,
}

/// One eigenvalue λ = σ + iω with its identification.
#[derive(Debug, Clone, Serialize)]
pub struct Mode {
    /// σ (1/s).
    pub re: f64,
    /// ω (rad/s), ≥ 0 (one entry per conjugate pair).
    pub im: f64,
    /// ω / 2π.
    pub frequency_hz: f64,
    /// ζ = −σ/|λ|.
    pub damping_ratio: f64,
    /// `flap k` / `torsion k` from the eigenvector's Galerkin coefficients; `aero lag k` for
    /// aerodynamic-state roots.
    pub label: String,
    /// Share of the eigenvector's energy in the structural coordinates (0…1).
    pub structural_share: f64,
    /// Galerkin coefficients q = [q_φ; q_u] (2N) of the eigenvector, unit norm; used for MAC
    /// tracking and mode shapes.
    #[serde(skip)]
    pub shape: Vec<Complex<f64>>,
}

/// All eigenvalues of one operating point.
#[derive(Debug, Clone, Serialize)]
pub struct Stability {
    pub stable: bool,
    pub verdict: Verdict,
    /// Structural (aeroelastic) modes, sorted by σ descending.
    pub eigenvalues: Vec<Mode>,
    /// Roots dominated by aerodynamic lag states, reported apart, sorted by σ descending.
    pub aero_lags: Vec<Mode>,
}
