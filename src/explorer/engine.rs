//! The explorer's view of the analysis layer: a small trait the worker calls, so the whole explorer
//! (state, worker, rendering) can be driven and tested with any engine. [`Physics`] is the real
//! one; it only forwards to `physics::section`, `analysis::eigen`, `analysis::flutter`,
//! `analysis::sweep` and `analysis::simulate`.

use crate::analysis::eigen::Stability;
use crate::analysis::flutter::Boundary;
use crate::analysis::simulate::{RunStatus, TipSample};
use crate::analysis::sweep::TrackedSweep;
use crate::error::Result;
use crate::physics::section::SectionProps;
use crate::preset::Preset;

/// One operating point, solved: the live section stiffnesses and the eigen-analysis.
#[derive(Debug, Clone)]
pub struct Solved {
    pub section: SectionProps,
    pub stability: Stability,
}

/// A running time simulation of the blade tip.
pub trait Stream: Send {
    /// The next `samples` output samples at the preset's sample rate (fewer when the run stops).
    fn advance(&mut self, samples: usize) -> Result<Vec<TipSample>>;
    /// Add a tip kick (twist in rad, flap in m) to the current state.
    fn kick(&mut self, twist_rad: f64, flap_m: f64);
    fn status(&self) -> RunStatus;
}

/// Everything the explorer asks of the analysis layer.
pub trait Engine: Send + Sync {
    fn solve(&self, p: &Preset) -> Result<Solved>;
    /// First stability crossing along `key` in `[from, to]`.
    fn boundary(
        &self,
        p: &Preset,
        key: &str,
        from: f64,
        to: f64,
        points: usize,
    ) -> Result<Boundary>;
    /// Tracked modes over rotor speeds `grid` (rpm).
    fn campbell(&self, p: &Preset, grid: &[f64]) -> Result<TrackedSweep>;
    /// A new tip simulation of `p` from its start state.
    fn stream(&self, p: &Preset) -> Result<Box<dyn Stream>>;
}

/// The real engine: the analysis layer, unchanged.
#[derive(Debug, Clone, Copy, Default)]
pub struct Physics;

impl Stream for crate::analysis::simulate::Simulator {
    fn advance(&mut self, samples: usize) -> Result<Vec<TipSample>> {
        crate::analysis::simulate::Simulator::advance(self, samples)
    }
    fn kick(&mut self, twist_rad: f64, flap_m: f64) {
        crate::analysis::simulate::Simulator::kick(self, twist_rad, flap_m)
    }
    fn status(&self) -> RunStatus {
        crate::analysis::simulate::Simulator::status(self)
    }
}

impl Engine for Physics {
    fn solve(&self, p: &Preset) -> Result<Solved> {
        Ok(Solved {
            section: crate::physics::section::section_properties(p)?,
            stability: crate::analysis::eigen::analyse(p)?,
        })
    }

    fn boundary(
        &self,
        p: &Preset,
        key: &str,
        from: f64,
        to: f64,
        points: usize,
    ) -> Result<Boundary> {
        crate::analysis::flutter::flutter_boundary(p, key, from, to, points)
    }

    fn campbell(&self, p: &Preset, grid: &[f64]) -> Result<TrackedSweep> {
        crate::analysis::sweep::track(p, "operating.rotor_speed", grid)
    }

    fn stream(&self, p: &Preset) -> Result<Box<dyn Stream>> {
        Ok(Box::new(crate::analysis::simulate::Simulator::new(p)?))
    }
}
