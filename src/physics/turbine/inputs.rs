//! What a rotor is made of around its blade (docs/model.md §13.2, §13.6): the plain inputs of
//! [`super::rotor::Rotor`].

use super::drivetrain::Drivetrain;
use super::tower::Tower;

/// What a rotor adds to its blade: how many blades, the drivetrain, the speed.
#[derive(Debug, Clone, PartialEq)]
pub struct RotorInputs {
    pub blades: usize,
    /// None: the hub turns at a constant speed (an infinitely stiff drivetrain on an infinite
    /// inertia), the blades clamped to it.
    pub drivetrain: Option<Drivetrain>,
    /// None: the rotor on a rigid support (`turbine.model = "rotor"`).
    pub support: Option<Support>,
    /// Ω (rad/s), the speed the blade's modes are at.
    pub rotor_speed: f64,
}

/// What the rotor sits on (docs/model.md §13.6): the tower with its top masses, and what turns
/// with the nacelle as it rolls about the shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    pub tower: Tower,
    /// The hub's inertia about the shaft (kg·m²).
    pub hub_inertia: f64,
    /// The generator's inertia about the high-speed shaft (kg·m²) and the gear ratio: a roll
    /// `θ_x` of the nacelle turns the generator by `θ_x` on top of `N θ_g`.
    pub generator_inertia: f64,
    pub gear_ratio: f64,
}
