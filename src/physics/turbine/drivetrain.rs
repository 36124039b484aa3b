//! The drivetrain (docs/model.md §13.2): the rotor's azimuth `θ_r` and the generator's angle
//! `θ_g` (on the low-speed side, the gear ratio folded in), joined by the shaft's torsional
//! spring and damper. Plain inputs, two coordinates (one with the generator locked) with their
//! mass, stiffness and damping.
//!
//! With the generator free the coordinates are `θ_r` and the shaft's twist `δ = θ_r − θ_g`:
//! nothing depends on where the drivetrain has turned to, only on its twist and its rates, so
//! the azimuth's column of the state matrix is zero and its root an exact, isolated zero
//! (in `θ_r, θ_g` it would be a double root of a Jordan block, split by round-off into a pair
//! `±√ε`, one of them growing).

use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// Whether the generator turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Generator {
    /// Free, held by its constant torque (open loop): the drivetrain turns as a whole, a zero
    /// root, and twists against the generator's inertia.
    Free,
    /// Held in place (a locked brake): the rotor twists the shaft against the ground.
    Locked,
}

/// The drivetrain's inputs, on the low-speed shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Drivetrain {
    /// The hub's moment of inertia about the shaft (kg·m²); the blades bring their own.
    pub hub_inertia: f64,
    /// The generator's inertia seen from the low-speed shaft, `J_gen N²` (kg·m²).
    pub generator_inertia: f64,
    /// Torsional stiffness (N·m/rad) and damping (N·m·s/rad) of the shaft.
    pub stiffness: f64,
    pub damping: f64,
    pub generator: Generator,
    /// The generator torque's rise per unit of the generator's speed (N·m·s/rad, low-speed
    /// side): a damper on the generator's turning while it is free; 0 holds its torque.
    pub torque_slope: f64,
}

impl Drivetrain {
    /// Every value finite, the inertias and the stiffness positive, the damping not negative;
    /// else an error naming the value.
    pub fn checked(self) -> Result<Drivetrain> {
        let positive = [
            ("hub inertia", self.hub_inertia),
            ("generator inertia", self.generator_inertia),
            ("shaft torsional stiffness", self.stiffness),
        ];
        for (what, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::numerical(format!(
                    "drivetrain: {what} is {v}; it must be finite and positive"
                )));
            }
        }
        if !(self.torque_slope.is_finite() && self.torque_slope >= 0.0) {
            return Err(Error::numerical(format!(
                "drivetrain: the generator torque slope is {}; it must be finite and ≥ 0",
                self.torque_slope
            )));
        }
        if !(self.damping.is_finite() && self.damping >= 0.0) {
            return Err(Error::numerical(format!(
                "drivetrain: shaft torsional damping is {}; it must be finite and ≥ 0",
                self.damping
            )));
        }
        Ok(self)
    }

    /// Its coordinates: `θ_r`, and `θ_g` while the generator is free.
    pub fn coordinates(&self) -> usize {
        match self.generator {
            Generator::Free => 2,
            Generator::Locked => 1,
        }
    }

    /// Mass (the hub's and the generator's inertia; the blades add theirs to `θ_r`), stiffness
    /// and damping over [`Drivetrain::coordinates`]: `θ_r` (and `δ`). The generator turns by
    /// `θ_r − δ`, so its kinetic energy `½ J_g (θ̇_r − δ̇)²` couples the two, and so does its
    /// torque's slope `c_g`: `−c_g (θ̇_r − δ̇)` on it.
    pub fn matrices(&self) -> [DMatrix<f64>; 3] {
        let (jh, jg) = (self.hub_inertia, self.generator_inertia);
        match self.generator {
            Generator::Free => {
                let shaft = |k: f64| DMatrix::from_row_slice(2, 2, &[0.0, 0.0, 0.0, k]);
                let c = self.torque_slope;
                let generator = DMatrix::from_row_slice(2, 2, &[c, -c, -c, c]);
                [
                    DMatrix::from_row_slice(2, 2, &[jh + jg, -jg, -jg, jg]),
                    shaft(self.stiffness),
                    shaft(self.damping) + generator,
                ]
            }
            Generator::Locked => [
                DMatrix::from_element(1, 1, jh),
                DMatrix::from_element(1, 1, self.stiffness),
                DMatrix::from_element(1, 1, self.damping),
            ],
        }
    }
}
