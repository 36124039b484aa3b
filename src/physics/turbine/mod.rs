//! The rotor as one aeroelastic system in the ground frame (docs/model.md §13): three identical
//! blades in their rotating frames ([`rotor::Rotor`]) on the drivetrain
//! ([`drivetrain::Drivetrain`]), their strips as one blade's, linearised about the blade's
//! equilibrium and carried into the ground frame by the multi-blade transform
//! ([`crate::numeric::mbc`]), where [`ground::GroundRotor`] names the roots.
//!
//! An isotropic rotor in uniform axial inflow, on a support that does not move: the
//! rotating-frame state matrix does not depend on the azimuth, and the transform gives the
//! ground-frame matrix exactly at any one azimuth.

pub mod drivetrain;
pub mod ground;
pub mod inputs;
pub mod rotor;
pub mod tower;
pub mod tower_beam;

use crate::error::{Error, Result};
use crate::numeric::alongside;
use crate::numeric::mbc::MultiBlade;
use crate::physics::structure::Structure;
use crate::physics::system::{LinearSystem, System};
use ground::GroundRotor;
pub use inputs::{RotorInputs, Support};
use nalgebra::DVector;
use rotor::Rotor;
use std::sync::Arc;

/// The rotor of `inputs` made of `blade`'s structure and strips, linearised about the blade's
/// equilibrium state `x_eq` (every blade at it, the drivetrain and the tower at rest): the
/// ground-frame state matrix, its states `[a, ȧ, z̄]` in multi-blade coordinates.
pub fn rotor_system(
    blade: &System,
    x_eq: &DVector<f64>,
    inputs: &RotorInputs,
) -> Result<LinearSystem> {
    let rotor = rotor_of(blade, x_eq, inputs, 0.0)?;
    // The names' reference (the rotor in vacuo) needs the rotor alone: it is built while the
    // strips are linearised.
    let in_vacuo = Arc::clone(&rotor);
    let omega = inputs.rotor_speed;
    let (at, ground) = alongside(
        || linearised_on(blade, x_eq, inputs, rotor),
        move || GroundRotor::new(&in_vacuo, omega),
    );
    let (at, ground) = (at?, ground?);
    let a = at.layout.transform(&at.system.a, 0.0, inputs.rotor_speed)?;
    let x_eq = at.layout.to_ground(0.0, inputs.rotor_speed) * &at.system.x_eq;
    let view = ground.blade_view();
    let [tip_twist, tip_flap] = view.tip.at(0.0);
    Ok(LinearSystem {
        a,
        x_eq,
        nq: at.rotor.coordinates(),
        n_aero: at.system.n_aero,
        tip_twist,
        tip_flap,
        tip_offset: at.system.tip_offset,
        turning: Some(Arc::new(view)),
        structure: Arc::new(ground),
    })
}

/// The rotor linearised in the blades' rotating frames with blade 0 at one azimuth.
pub struct RotatingSystem {
    /// Its state matrix, states `[q, q̇, z]` blade by blade.
    pub system: LinearSystem,
    /// The multi-blade layout of those states.
    pub layout: MultiBlade,
    pub rotor: Arc<Rotor>,
}

/// [`rotor_system`] before the multi-blade transform, blade 0 at `azimuth` (rad): on a tower
/// the state matrix turns with the rotor (docs/model.md §13.6); after the transform it does
/// not.
pub fn rotating_system(
    blade: &System,
    x_eq: &DVector<f64>,
    inputs: &RotorInputs,
    azimuth: f64,
) -> Result<RotatingSystem> {
    let rotor = rotor_of(blade, x_eq, inputs, azimuth)?;
    linearised_on(blade, x_eq, inputs, rotor)
}

/// The rotor of `inputs` made of `blade`'s structure, its blades at the equilibrium `x_eq`,
/// blade 0 at `azimuth` (rad).
fn rotor_of(
    blade: &System,
    x_eq: &DVector<f64>,
    inputs: &RotorInputs,
    azimuth: f64,
) -> Result<Arc<Rotor>> {
    if x_eq.len() != blade.dim() {
        return Err(Error::numerical(format!(
            "rotor: the blade's equilibrium has {} states, the blade {}",
            x_eq.len(),
            blade.dim()
        )));
    }
    let q_eq = x_eq.rows(0, blade.nq()).into_owned();
    Ok(Arc::new(Rotor::new(
        blade.structure_arc(),
        inputs,
        &q_eq,
        azimuth,
    )?))
}

/// [`rotating_system`] on the `rotor` built for it ([`rotor_of`]).
fn linearised_on(
    blade: &System,
    x_eq: &DVector<f64>,
    inputs: &RotorInputs,
    rotor: Arc<Rotor>,
) -> Result<RotatingSystem> {
    let k = blade.nq();
    let n_blades = inputs.blades;
    let left_out = blade.left_out_response(x_eq);
    let q_eq = x_eq.rows(0, k).into_owned();
    let z_eq = x_eq.rows(2 * k, blade.n_aero()).into_owned();
    let mut system = blade.on_rotor(Arc::clone(&rotor) as _, n_blades)?;
    if let Some(p) = left_out {
        system = system.with_left_out_at(&repeated(&p, n_blades));
    }
    let n = rotor.coordinates();
    let mut x = DVector::zeros(system.dim());
    x.rows_mut(0, n_blades * k)
        .copy_from(&repeated(&q_eq, n_blades));
    x.rows_mut(2 * n, system.n_aero())
        .copy_from(&repeated(&z_eq, n_blades));
    let system = system.linearise_at(Some(x))?;
    let layout = ground::layout(&rotor, system.dim())?;
    Ok(RotatingSystem {
        system,
        layout,
        rotor,
    })
}

/// `v` once per blade.
fn repeated(v: &DVector<f64>, blades: usize) -> DVector<f64> {
    DVector::from_iterator(
        v.len() * blades,
        (0..blades).flat_map(|_| v.iter().copied()),
    )
}
