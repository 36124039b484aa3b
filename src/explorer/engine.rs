//! The explorer's view of the analysis layer: a small trait the worker calls, so the whole explorer
//! (state, worker, rendering) can be driven and tested with any engine. [`Physics`] is the real
//! one; it only forwards to `analysis` (`solve`, `flutter`, `sweep`, `simulate`).

use crate::analysis::campbell::Campbell;
use crate::analysis::cancel::Cancel;
use crate::analysis::eigen::Stability;
use crate::analysis::flutter::{Search, SearchRange};
use crate::analysis::mode_shape::ModeShapes;
use crate::analysis::simulate::{RunStatus, Simulator, TipSample};
use crate::analysis::solve::SectionProps;
use crate::error::Result;
use crate::preset::ValidPreset;

/// One operating point, solved: the live section stiffnesses (a uniform blade's), the
/// eigen-analysis and the shape of each of its structural roots.
#[derive(Debug, Clone)]
pub struct Solved {
    pub section: Option<SectionProps>,
    pub stability: Stability,
    /// `shapes[i]` is the shape of `stability.eigenvalues[i]` on each part (empty when the
    /// engine computes none).
    pub shapes: Vec<ModeShapes>,
    /// The rotor speed (rpm) and pitch (deg) the solve ran at when the preset's schedule set
    /// either (`None` without a schedule): the parameters pane shows them as following it.
    pub setting: Option<(f64, f64)>,
}

/// What one solve gives the explorer: the analysis and the tip simulation started from the same
/// build. Either can fail alone (a nonlinear model with no equilibrium still runs from rest).
pub struct Solve {
    pub solved: Result<Solved>,
    pub stream: Result<Box<dyn Stream>>,
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
    /// Solve `p` and start its tip simulation (`simulation.*`); stop early once `cancel` is raised.
    fn solve(&self, p: &ValidPreset, cancel: &Cancel) -> Solve;
    /// First stability crossing in `range`.
    fn boundary(&self, p: &ValidPreset, range: &SearchRange, cancel: &Cancel) -> Result<Search>;
    /// Tracked modes along `key` (rotor speed, or wind speed along the schedule) over `grid`,
    /// with the rotor speed at each point.
    fn campbell(
        &self,
        p: &ValidPreset,
        key: &str,
        grid: &[f64],
        cancel: &Cancel,
    ) -> Result<Campbell>;
}

/// The real engine: the analysis layer, unchanged.
#[derive(Debug, Clone, Copy, Default)]
pub struct Physics;

impl Stream for Simulator {
    fn advance(&mut self, samples: usize) -> Result<Vec<TipSample>> {
        Simulator::advance(self, samples)
    }
    fn kick(&mut self, twist_rad: f64, flap_m: f64) {
        Simulator::kick(self, twist_rad, flap_m)
    }
    fn status(&self) -> RunStatus {
        Simulator::status(self)
    }
}

impl Engine for Physics {
    fn solve(&self, p: &ValidPreset, cancel: &Cancel) -> Solve {
        // The schedule once, here: the solve and the simulation run at its setting.
        let scheduled = match crate::model::operating::on_schedule(p) {
            Ok(q) => q,
            Err(e) => {
                return Solve {
                    solved: Err(e.clone()),
                    stream: Err(e),
                }
            }
        };
        let setting = (p.operating.schedule != crate::preset::Schedule::None)
            .then(|| (scheduled.operating.rotor_speed, scheduled.operating.pitch));
        let p = &scheduled;
        let solution = cancel
            .check()
            .and_then(|_| crate::analysis::solve::solve(p));
        match solution {
            Ok(solution) => {
                let solved = cancel.check().and_then(|_| {
                    let stability = solution.stability()?;
                    Ok(Solved {
                        section: solution.section().copied(),
                        shapes: solution.mode_shapes(&stability),
                        stability,
                        setting,
                    })
                });
                let stream = cancel
                    .check()
                    .and_then(|_| Ok(Box::new(solution.simulator(p)?) as Box<dyn Stream>));
                Solve { solved, stream }
            }
            Err(e) => Solve {
                solved: Err(e.clone()),
                stream: Err(e),
            },
        }
    }

    fn boundary(&self, p: &ValidPreset, range: &SearchRange, cancel: &Cancel) -> Result<Search> {
        crate::analysis::flutter::search(p, range, cancel)
    }

    fn campbell(
        &self,
        p: &ValidPreset,
        key: &str,
        grid: &[f64],
        cancel: &Cancel,
    ) -> Result<Campbell> {
        crate::analysis::campbell::campbell(p, key, grid, cancel)
    }
}
