//! One operating point, built once (docs/model.md §6–§7): section, structure, stations, aerodynamic
//! model, static equilibrium and the linearisation about it. The eigen-analysis and the time
//! response both start from this build, so a re-solve (an explorer key press, `reproduce fig2`)
//! never assembles or linearises anything twice.

use crate::analysis::eigen::{analyse_system, Stability};
use crate::analysis::mode_shape::{mode_shape, ModeShapes, PartRows};
use crate::analysis::simulate::Simulator;
use crate::error::Result;
use crate::physics::system::{LinearSystem, System};
use crate::preset::{Start, TurbineModel, ValidPreset};
use nalgebra::DVector;
use std::sync::Arc;

pub use crate::physics::section::SectionProps;

/// The coupled system of one preset and its linearisation.
pub struct Solution {
    system: Arc<System>,
    /// About the static equilibrium; an error when there is none (a nonlinear model loaded past
    /// what the blade carries). A time response from rest still runs without it.
    linear: Result<LinearSystem>,
}

/// Build the preset's system once and linearise it about its static equilibrium.
pub fn solve(p: &ValidPreset) -> Result<Solution> {
    let (system, equilibrium) = crate::model::system_with_equilibrium(p)?;
    let linear = crate::model::linearised(p, &system, equilibrium);
    let system = Arc::new(system);
    Ok(Solution { system, linear })
}

impl Solution {
    /// The uniform section the structure was assembled from (none for a tabulated blade).
    pub fn section(&self) -> Option<&SectionProps> {
        self.system.structure().uniform_section()
    }

    /// The linearisation about the equilibrium, or why there is none.
    pub fn linear(&self) -> Result<&LinearSystem> {
        self.linear.as_ref().map_err(Clone::clone)
    }

    /// Eigenvalues, labels and verdict (docs/model.md §6).
    pub fn stability(&self) -> Result<Stability> {
        analyse_system(self.linear()?)
    }

    /// The shape of each structural root of `stability` (in its order) on each part of this
    /// build's structure: the blade, or a rotor's blades and tower (docs/model.md §6.5).
    pub fn mode_shapes(&self, stability: &Stability) -> Vec<ModeShapes> {
        // The linearisation's coordinates: a rotor's are its ground frame's, not the blade's.
        let structure = match &self.linear {
            Ok(l) => l.structure.as_ref(),
            Err(_) => self.system.structure(),
        };
        let at = PartRows::of(structure);
        stability
            .eigenvalues
            .iter()
            .map(|m| mode_shape(structure, &at, m))
            .collect()
    }

    /// The tip response of `simulation.*` (docs/model.md §7), stepping the linearisation of this
    /// build: exactly for the affine models, split about it for the nonlinear ones. A run from
    /// rest of a nonlinear model without an equilibrium is split about the rest state instead.
    /// A rotor or turbine steps its ground-frame linearisation, time-invariant for the
    /// isotropic rotor, and reads blade 1's tip as it turns (docs/model.md §13.8): a nonlinear
    /// model's stall is then linearised about the equilibrium
    /// ([`ValidPreset::stall_linearised_in_time`]).
    pub fn simulator(self, p: &ValidPreset) -> Result<Simulator> {
        let sim = &p.simulation;
        let length = self.system.structure().length();
        // A rotor's stall is stepped as its linearisation: its stepper is the affine models'.
        let affine = p.turbine.model != TurbineModel::Blade
            || self.system.model().nonlinear_support().is_affine();
        let mut s = match (self.linear, affine, sim.start) {
            (Ok(linear), true, _) => Simulator::from_linear(linear, sim.sample_rate, length)?,
            (Ok(tangent), false, _) => {
                Simulator::from_system(self.system, tangent, sim.sample_rate, length)?
            }
            (Err(_), false, Start::Rest) => {
                let rest = DVector::zeros(self.system.dim());
                let tangent = self
                    .system
                    .tangent(rest.clone(), self.system.jacobian(&rest));
                Simulator::from_system(self.system, tangent, sim.sample_rate, length)?
            }
            (Err(e), _, _) => return Err(e),
        };
        if sim.start == Start::Rest {
            s.start_from_rest();
        }
        s.kick(sim.kick_twist.to_radians(), sim.kick_flap);
        Ok(s)
    }
}
