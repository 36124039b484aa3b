//! One root of the linearised aeroelastic system as the analyses report it: λ = σ + iω with its
//! frequency, damping ratio, name, family, motion shares and structural eigenvector coordinates
//! ([`crate::analysis::eigen`] computes the roots, [`crate::analysis::identify`] names them).

use crate::physics::structure::{Components, Family, Shares};
use nalgebra::Complex;
use serde::Serialize;

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
    /// `flap k` / `edge k` / `torsion k`: the in-vacuo natural mode the root is named after
    /// ([`crate::analysis::identify`]); `aero lag k` for aerodynamic-state roots.
    pub label: String,
    /// The family of that natural mode (none for an aerodynamic root).
    pub family: Option<Family>,
    /// Kinetic-energy shares of flap, edge and twist in the root's motion (docs/model.md §6.2).
    pub shares: Shares,
    /// A rotor's or a turbine's root by component: blades (flap, edge, twist), drivetrain,
    /// tower (none for one blade).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub components: Option<Components>,
    /// A rotor's blade-mode root in its blades' rotating frame (Hz): `f + 1P` for a backward
    /// whirl, `f − 1P` forward, `f` collective (none for one blade, the drivetrain, the tower).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotating_hz: Option<f64>,
    /// Frequency (Hz) of the in-vacuo natural mode the root is named after.
    pub in_vacuo_hz: Option<f64>,
    /// An overdamped mode (two real roots): σ of its more stable root; `re` is the other.
    pub second_re: Option<f64>,
    /// Share of the eigenvector's energy in the structural coordinates (0…1).
    pub structural_share: f64,
    /// Structural coordinates q of the right eigenvector, unit norm; used for tracking and mode
    /// shapes.
    #[serde(skip)]
    pub shape: Vec<Complex<f64>>,
    /// Structural coordinates of the left eigenvector, unit norm (empty without aerodynamic
    /// states, where only right vectors are computed); used for tracking.
    #[serde(skip)]
    pub left_shape: Vec<Complex<f64>>,
}

impl Mode {
    /// A bare root `λ = re + i·im` (im ≥ 0) with its frequency and damping ratio, not yet named.
    pub fn root(re: f64, im: f64) -> Mode {
        let magnitude = re.hypot(im);
        Mode {
            re,
            im,
            frequency_hz: im / std::f64::consts::TAU,
            damping_ratio: if magnitude > 0.0 {
                -re / magnitude
            } else {
                0.0
            },
            label: String::new(),
            family: None,
            shares: Shares::from_energies(0.0, 0.0, 0.0),
            components: None,
            rotating_hz: None,
            in_vacuo_hz: None,
            second_re: None,
            structural_share: 1.0,
            shape: Vec::new(),
            left_shape: Vec::new(),
        }
    }

    /// The name with the shares of its motion, as every command and pane reports a mode:
    /// `torsion 1 (flap 38 %, twist 60 %)`; families below 0.5 % are left out.
    pub fn described(&self) -> String {
        match self.content() {
            Some(content) => format!("{} ({content})", self.label),
            None => self.label.clone(),
        }
    }

    /// The shares of its motion, `flap 38 %, twist 60 %` (families below 0.5 % left out), a
    /// rotor's or turbine's by component (`tower 91 %, blade edge 8 %`); none for an
    /// aerodynamic root.
    pub fn content(&self) -> Option<String> {
        let shares: Vec<(&str, f64)> = match &self.components {
            Some(c) => vec![
                ("blade flap", c.blade_flap),
                ("blade edge", c.blade_edge),
                ("blade twist", c.blade_twist),
                ("drivetrain", c.drivetrain),
                ("tower", c.tower),
            ],
            None => vec![
                ("flap", self.shares.flap),
                ("edge", self.shares.edge),
                ("twist", self.shares.twist),
            ],
        };
        let parts: Vec<String> = shares
            .iter()
            .filter(|(_, s)| *s >= 0.005)
            .map(|(name, s)| format!("{name} {:.0} %", 100.0 * s))
            .collect();
        (!parts.is_empty() && self.family.is_some()).then(|| parts.join(", "))
    }

    /// Whether the root is a rigid body's: a free rotor's turning (its in-vacuo frequency zero),
    /// whose σ is the rotor speed's own stability under the generator's torque, not the
    /// structure's (docs/model.md §13.1).
    pub fn rigid_body(&self) -> bool {
        self.in_vacuo_hz == Some(0.0) && self.im == 0.0
    }

    /// Whether the mode is an overdamped pair of real roots.
    pub fn overdamped(&self) -> bool {
        self.second_re.is_some()
    }
}
