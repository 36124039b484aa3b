//! Time response of the blade tip (MODEL.md §7), linear aerodynamic models.
//!
//! Input: a preset (its `simulation.*` settings: start, kicks, duration, sample rate).
//! Model: the linearised system `ẋ = A (x − x*)` about the static equilibrium `x*` — exact for
//! `none` and `theodorsen` (affine), the tangent model for `quasi-steady` (whose only
//! nonlinearity is the `cos α_g` projection of the lift's moment arm). A `rest` start (`x = 0`)
//! is the load switched on at `t = 0`, as in the paper's figures; `equilibrium` starts at `x*`.
//! Kicks displace the first torsion and first flap Galerkin functions so that the tip moves by
//! the kick.
//!
//! Stepping is exact: `y_{k+1} = E y_k`, `y = x − x*`, `E = e^{A h}`, `h` the sample interval.
//! No step-size control is needed however stiff the blade (torsion 10⁴× faster than flap on the
//! paper's blade): `E` is computed once by scaling and squaring. A response whose tip twist
//! exceeds 1 rad or tip flap the blade length (or turns non-finite) ends the run with status
//! `diverging` at that time, never with a NaN sample.
//!
//! Output: [`TipSample`]s: tip twist φ(L,t) and tip flap u(L,t).

use crate::analysis::eigen::linear_system;
use crate::error::{Error, Result};
use crate::physics::system::{check_finite, LinearSystem};
use crate::preset::{Preset, Start};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// One output sample: tip twist φ(L,t) (rad, toward feather) and tip flap u(L,t) (m, downwind).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TipSample {
    pub t: f64,
    pub tip_twist: f64,
    pub tip_flap: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RunStatus {
    Ok,
    /// The response grew past the divergence bound; the run stopped there.
    Diverging,
}

/// Tip twist beyond which a response counts as diverging (rad): far outside any linear model.
pub const TWIST_BOUND: f64 = 1.0;

/// An incremental exact-exponential stepper (the explorer streams from it).
#[derive(Clone)]
pub struct Simulator {
    linear: LinearSystem,
    /// e^{A h}.
    step: DMatrix<f64>,
    /// Deviation from equilibrium, x − x*, at the next sample time.
    y: DVector<f64>,
    /// Sample interval h (s).
    interval: f64,
    /// Index of the next sample to emit.
    next: u64,
    status: RunStatus,
    /// Bound on |u_tip| (m): the blade length.
    flap_bound: f64,
}

impl Simulator {
    /// Linearise the preset and set up the start state of `simulation.*`.
    pub fn new(p: &Preset) -> Result<Simulator> {
        let linear = linear_system(p)?;
        let sim = &p.simulation;
        let mut s = Simulator::from_linear(linear, sim.sample_rate, p.blade.length)?;
        if sim.start == Start::Rest {
            s.y = -s.linear.x_eq.clone();
        }
        s.kick(sim.kick_twist.to_radians(), sim.kick_flap);
        Ok(s)
    }

    /// A stepper on an already linearised system, starting at equilibrium.
    pub fn from_linear(
        linear: LinearSystem,
        sample_rate: f64,
        flap_bound: f64,
    ) -> Result<Simulator> {
        if !(sample_rate.is_finite() && sample_rate > 0.0) {
            return Err(Error::usage(format!(
                "simulation.sample_rate = {sample_rate} must be positive"
            )));
        }
        let interval = 1.0 / sample_rate;
        check_finite("state matrix", &linear.a)?;
        let step = (&linear.a * interval).exp();
        check_finite("step matrix e^(A h)", &step)?;
        let y = DVector::zeros(linear.dim());
        Ok(Simulator {
            linear,
            step,
            y,
            interval,
            next: 0,
            status: RunStatus::Ok,
            flap_bound,
        })
    }

    /// The next `samples` samples (fewer if the run diverges; none once it has).
    pub fn advance(&mut self, samples: usize) -> Result<Vec<TipSample>> {
        let mut out = Vec::with_capacity(samples);
        for _ in 0..samples {
            if self.status == RunStatus::Diverging {
                break;
            }
            let t = self.next as f64 * self.interval;
            let (tip_twist, tip_flap) = self.tip();
            let finite = tip_twist.is_finite() && tip_flap.is_finite();
            if finite {
                out.push(TipSample {
                    t,
                    tip_twist,
                    tip_flap,
                });
            }
            self.next += 1;
            if !finite || tip_twist.abs() > TWIST_BOUND || tip_flap.abs() > self.flap_bound {
                self.status = RunStatus::Diverging;
                break;
            }
            self.y = &self.step * &self.y;
        }
        Ok(out)
    }

    /// Add a tip twist (rad) and tip flap (m) to the current state, along the first torsion and
    /// first flap Galerkin functions.
    pub fn kick(&mut self, twist_rad: f64, flap_m: f64) {
        let n = self.linear.nq / 2;
        if n == 0 {
            return;
        }
        let twist_at_tip = self.linear.tip_twist[0];
        let flap_at_tip = self.linear.tip_flap[n];
        if twist_rad != 0.0 && twist_at_tip != 0.0 {
            self.y[0] += twist_rad / twist_at_tip;
        }
        if flap_m != 0.0 && flap_at_tip != 0.0 {
            self.y[n] += flap_m / flap_at_tip;
        }
    }

    pub fn status(&self) -> RunStatus {
        self.status
    }

    /// Time of the last emitted sample (s); 0 before the first.
    pub fn time(&self) -> f64 {
        self.next.saturating_sub(1) as f64 * self.interval
    }

    /// The current state x (= x* + y).
    pub fn state(&self) -> DVector<f64> {
        &self.linear.x_eq + &self.y
    }

    pub fn linear(&self) -> &LinearSystem {
        &self.linear
    }

    fn tip(&self) -> (f64, f64) {
        self.linear.tip(&self.state())
    }
}

/// A whole run.
#[derive(Debug, Clone, Serialize)]
pub struct Response {
    pub status: RunStatus,
    pub t: Vec<f64>,
    pub tip_twist: Vec<f64>,
    pub tip_flap: Vec<f64>,
    /// Time the run stopped at the divergence bound.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub diverged_at: Option<f64>,
}

/// Samples in `[0, duration]` at the preset's sample rate, both ends included.
pub fn sample_count(p: &Preset) -> usize {
    (p.simulation.duration * p.simulation.sample_rate + 1e-9).floor() as usize + 1
}

/// Simulate the preset for `simulation.duration`.
pub fn simulate(p: &Preset) -> Result<Response> {
    let mut sim = Simulator::new(p)?;
    let samples = sim.advance(sample_count(p))?;
    let status = sim.status();
    Ok(Response {
        status,
        diverged_at: (status == RunStatus::Diverging).then(|| sim.time()),
        t: samples.iter().map(|s| s.t).collect(),
        tip_twist: samples.iter().map(|s| s.tip_twist).collect(),
        tip_flap: samples.iter().map(|s| s.tip_flap).collect(),
    })
}
