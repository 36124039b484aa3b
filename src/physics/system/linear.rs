//! The system linearised about its equilibrium (docs/model.md §6): the state matrix.

use super::{check_finite, System};
use crate::error::Result;
use crate::physics::structure::Structure;
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// The linearised system about its equilibrium: `ẋ = A (x − x*)`.
#[derive(Clone)]
pub struct LinearSystem {
    pub a: DMatrix<f64>,
    /// Equilibrium state x*.
    pub x_eq: DVector<f64>,
    /// Structural coordinates 2N (q); the state is `[q (2N), q̇ (2N), z (n_aero)]`.
    pub nq: usize,
    pub n_aero: usize,
    /// Tip twist φ(L) = `tip_twist · q` and tip flap u(L) = `tip_flap · q` (`n_q` each).
    pub tip_twist: DVector<f64>,
    pub tip_flap: DVector<f64>,
    /// The left-out modes' static tip twist and flap (docs/model.md §12.6), added to every state's.
    pub tip_offset: [f64; 2],
    pub structure: Arc<dyn Structure>,
}

impl System {
    /// Equilibrium and the state matrix there.
    pub fn linearise(&self) -> Result<LinearSystem> {
        self.linearise_at(None)
    }

    /// The state matrix at `known`, an equilibrium of this system found while building it
    /// (`crate::model::system_with_equilibrium`), or at the one solved here when there is none.
    pub fn linearise_at(&self, known: Option<DVector<f64>>) -> Result<LinearSystem> {
        let x_eq = match known {
            Some(x) => x,
            None => self.equilibrium()?,
        };
        let a = self.jacobian(&x_eq);
        check_finite("state matrix", &a)?;
        Ok(self.tangent(x_eq, a))
    }

    /// The tangent system `ẋ ≈ A (x − x_r)` about a state `x_r` with its Jacobian `a` (the
    /// equilibrium for [`System::linearise`]; any reference state for the time stepper).
    pub fn tangent(&self, x_ref: DVector<f64>, a: DMatrix<f64>) -> LinearSystem {
        LinearSystem {
            a,
            x_eq: x_ref,
            nq: self.nq(),
            n_aero: self.n_aero(),
            tip_twist: self.tip_rows[0].clone(),
            tip_flap: self.tip_rows[1].clone(),
            tip_offset: {
                let [phi, u, _] = self.tip_offset();
                [phi, u]
            },
            structure: Arc::clone(&self.structure),
        }
    }
}

impl LinearSystem {
    /// Length of the state vector.
    pub fn dim(&self) -> usize {
        self.a.nrows()
    }
    /// Tip twist and flap of a state.
    pub fn tip(&self, x: &DVector<f64>) -> (f64, f64) {
        let q = x.rows(0, self.nq);
        let [phi, u] = self.tip_offset;
        (self.tip_twist.dot(&q) + phi, self.tip_flap.dot(&q) + u)
    }
}
