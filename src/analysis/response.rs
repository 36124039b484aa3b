//! A preset's tip response as a whole (docs/model.md §7): the stepper of its `simulation.*`
//! settings, set up from one build of the operating point ([`crate::analysis::solve`]), and the
//! run over `simulation.duration` collected into a [`Response`].

use crate::analysis::simulate::{RunStatus, Simulator};
use crate::analysis::solve::solve;
use crate::error::Result;
use crate::preset::{TurbineModel, ValidPreset};
use serde::Serialize;

/// The preset's model and the start state of `simulation.*` as a stepper (one build, see
/// [`crate::analysis::solve`]).
pub fn simulator(p: &ValidPreset) -> Result<Simulator> {
    solve(p)?.simulator(p)
}

/// A whole run.
#[derive(Debug, Clone, Serialize)]
pub struct Response {
    pub status: RunStatus,
    pub t: Vec<f64>,
    pub tip_twist: Vec<f64>,
    pub tip_flap: Vec<f64>,
    /// The blade whose tip the run follows on a rotor or turbine (blade 1, turning from zero
    /// azimuth); none for the clamped blade.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotor_blade: Option<u32>,
    /// The model's stall stepped as its linearisation about the equilibrium (a rotor or
    /// turbine with `onera` or `hgm`, docs/model.md §13.8).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub stall_linearised: bool,
    /// Time the run stopped at the divergence bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diverged_at: Option<f64>,
}

/// Samples in `[0, duration]` at the preset's sample rate, both ends included.
pub fn sample_count(p: &ValidPreset) -> usize {
    (p.simulation.duration * p.simulation.sample_rate + 1e-9).floor() as usize + 1
}

/// Simulate the preset for `simulation.duration`.
pub fn simulate(p: &ValidPreset) -> Result<Response> {
    let mut sim = simulator(p)?;
    let samples = sim.advance(sample_count(p))?;
    let status = sim.status();
    Ok(Response {
        status,
        rotor_blade: (p.turbine.model != TurbineModel::Blade).then_some(1),
        stall_linearised: p.stall_linearised_in_time(),
        diverged_at: (status == RunStatus::Diverging).then(|| sim.time()),
        t: samples.iter().map(|s| s.t).collect(),
        tip_twist: samples.iter().map(|s| s.tip_twist).collect(),
        tip_flap: samples.iter().map(|s| s.tip_flap).collect(),
    })
}
