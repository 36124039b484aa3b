//! The section's unsteady airfoil model behind the blade-element strip loads (docs/model.md
//! §12.5, §12.8): one trait, [`AirfoilDynamics`], one implementation per file.
//!
//! A model sees the section's polar and its flow — the three-quarter-chord angle of attack
//! `α_¾`, the geometric angle `α_g` the loads are resolved in, the twist rate and the reduced-time
//! rate `V0/b` — and its own states; it returns the coefficients `[C_l, C_d, C_m]` (the moment
//! about the aerodynamic centre) and the state rates. The strip around it (the relative flow, the
//! rotation of the loads into the rotor frame, the non-circulatory loads) is the same for every
//! model and lives in `blade_element.rs`.
//!
//! Every model is written once, generic over forward-mode dual numbers (`num-dual`): evaluated on
//! plain `f64` it gives values, on a dual vector seeded with the strip's inputs it gives their
//! exact partial derivatives, so a model's linearisation is the Jacobian of its nonlinear
//! right-hand side by construction.
//!
//! Adding a model: a file implementing [`AirfoilDynamics`] (its coefficients and rates, and the
//! states that hold still at a constant angle of attack), a variant of
//! `blade_element::Unsteadiness` and its arm in `Unsteadiness::visit`, the one place the strip
//! names a model; the preset names it in `AeroModel` and `crate::model::operating::unsteadiness`
//! maps the one onto the other.

pub mod hgm;
pub mod jones;
pub mod onera;
pub mod quasi_steady;

use super::polar::Polar;
use num_dual::DualNum;

/// The flow a section's airfoil model reads, in any dual-number type `T`.
#[derive(Debug, Clone, Copy)]
pub struct SectionFlow<T> {
    /// `α_¾`: the angle of attack at the three-quarter chord (rad).
    pub alpha: T,
    /// `α_g`: the geometric angle of attack at the reference axis (rad), the angle between the
    /// chord and the inflow the lift and drag are resolved on.
    pub alpha_geometric: T,
    /// `φ̇`: the elastic twist rate toward feather (rad/s); the nose-up pitch rate is `−φ̇`.
    pub twist_rate: T,
    /// `V0/b`: the rate of reduced time (1/s), on the frozen inflow's speed.
    pub rate: f64,
}

/// A section held still at a constant angle of attack, for [`AirfoilDynamics::steady_states`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyFlow {
    /// `α` (rad), at every chordwise point alike.
    pub alpha: f64,
    /// Semichord `b` (m).
    pub semichord: f64,
    /// Flow speed `V0` (m/s), positive.
    pub speed: f64,
}

/// A section's unsteady airfoil model (docs/model.md §12.5).
pub trait AirfoilDynamics: Copy + std::fmt::Debug + PartialEq + Send + Sync {
    /// The preset name of the model (`aero.model`).
    fn name(&self) -> &'static str;

    /// States per section.
    fn states(&self) -> usize;

    /// `[C_l, C_d, C_m]` at the flow and states `z`, the state rates into `zdot` (`states()` of
    /// each). The moment is about the aerodynamic centre, nose-up positive.
    fn coefficients<T: DualNum<Primitive = f64> + Copy>(
        &self,
        polar: &Polar,
        flow: &SectionFlow<T>,
        z: &[T],
        zdot: &mut [T],
    ) -> [T; 3];

    /// The states for which the rates vanish at the constant angle of attack of `flow`, into `z`,
    /// and their derivative with respect to that angle into `dz_dalpha`. With them the model
    /// returns the polar's coefficients exactly.
    fn steady_states(&self, polar: &Polar, flow: SteadyFlow, z: &mut [f64], dz_dalpha: &mut [f64]);

    /// True when the model is to be simulated as the nonlinear model it is (docs/model.md §7);
    /// false: linearised about the equilibrium.
    fn nonlinear_in_time(&self) -> bool {
        false
    }
}

/// `C_l, C_d, C_m` of `polar` at `alpha`: the table's value and slope at α's value, carried to
/// every input through α's derivative.
pub fn polar_coefficients<T: DualNum<Primitive = f64> + Copy>(polar: &Polar, alpha: T) -> [T; 3] {
    let c = polar.at(alpha.re());
    [
        carried(alpha, c.cl, c.dcl),
        carried(alpha, c.cd, c.dcd),
        carried(alpha, c.cm, c.dcm),
    ]
}

/// A table's `value` and `slope` at α's value, as a function of α: the value, carried to every
/// input α depends on through its derivative.
pub fn carried<T: DualNum<Primitive = f64> + Copy>(alpha: T, value: f64, slope: f64) -> T {
    (alpha - alpha.re()) * slope + value
}
