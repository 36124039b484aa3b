//! Time response of the blade tip (docs/model.md §7), every aerodynamic model.
//!
//! Input: a preset (its `simulation.*` settings: start, kicks, duration, sample rate).
//! Output: [`TipSample`]s, tip twist φ(L,t) and tip flap u(L,t), streamed by [`Simulator::advance`].
//!
//! **Model.** The right-hand side is split about a reference state `x_r` (the static
//! equilibrium; for a nonlinear model without one, the start state):
//! `ẋ = r0 + A y + B ũ(C y)`, `y = x − x_r` ([`Splitting`]). For the affine models (`none`,
//! `theodorsen`) and `quasi-steady` (whose only nonlinearity, the `cos α_g` arm, docs/model.md §7 keeps
//! linearised) `ũ` is empty and the run is the linear system `ẏ = A y`. For `onera` (§5.3) `ũ`
//! holds the stall deviations and the trigonometric load arms: a few scalars per station, read
//! from a few station inputs (`C`) and written into a few rates and loads (`B`).
//!
//! **Stepper: exponential trapezoidal rule.** Over a step `h`,
//! `y₊ = e^{hA} y + F1 r0 + (F1 − F2/h) B ũ₀ + (F2/h) B ũ₊`, with `F1 = hφ1(hA)`, `F2 = h²φ2(hA)`:
//! the linear part exactly (any stiffness, any `h`), the remainder with a linear interpolant in
//! time, implicit in its end value. `ũ₊ = ũ(C y₊)` is solved for by Newton on the `p` station
//! inputs alone (`p = 4` per station for ONERA: `dev = C y₊⁰ + K ũ(dev)`, `K = C F2 B/h`), with a
//! chord Jacobian kept while it converges. Why this and not an implicit Runge–Kutta or a
//! Rosenbrock method on the whole state: those resolve the 100 Hz torsion (10⁴× stiffer than the
//! first flap mode on the paper's blade) only with steps far below the 5 ms sample interval,
//! and they need an `n × n` factorisation per step; here the stiff linear part costs one
//! matrix–vector product per step, the Newton system is `p × p` (`p ≪ n`), and near the
//! reference, where the stall deviations sit on the reference's linear piece, the step is exact.
//! Linear models are therefore exact to rounding, and a linear response's growth rate is the
//! largest σ of `A`.
//!
//! **Accuracy control.** The interpolant's error is `≈ (h²/12) F1 B ũ''`; `ũ''` is estimated from
//! the last three remainder values and mapped to the tip. When it exceeds the tolerance the
//! sample interval is redone with 2, 4, … 2^[`MAX_LEVEL`] substeps (propagators for every level
//! come out of the same scaling-and-squaring), and the level relaxes again once the remainder is
//! smooth. The finest level is accepted whatever the estimate, so the cost per sample is bounded
//! and the step never collapses.
//!
//! A response whose tip twist exceeds [`TWIST_BOUND`] or tip flap the blade length (or turns
//! non-finite) ends the run with status `diverging` at that time, never with a NaN sample.

use crate::error::{Error, Result};
use crate::numeric::phi_functions::{propagators, Propagator};
use crate::physics::system::{check_finite, LinearSystem, RemainderScratch, Splitting, System};
use nalgebra::{DMatrix, DVector, Dyn, LU};
use serde::Serialize;
use std::sync::Arc;

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

/// A sample interval is split into at most `2^MAX_LEVEL` steps (78 µs at 200 samples/s).
pub const MAX_LEVEL: usize = 6;

/// Default bound on the estimated local error per step of the tip twist (rad); the tip flap's
/// is this times the blade length (m).
pub const DEFAULT_TOLERANCE: f64 = 1e-5;

/// Newton iterations per step on the station inputs before the step is refined.
const NEWTON_MAX_ITERATIONS: usize = 30;

/// Newton convergence: residual below this times (1 + largest input deviation).
const NEWTON_TOLERANCE: f64 = 1e-10;

// ---------------------------------------------------------------------------------------------
// The stepper
// ---------------------------------------------------------------------------------------------

/// One step size's precomputed operators (see the module documentation).
#[derive(Clone)]
struct Level {
    h: f64,
    /// `e^{hA}`.
    e: DMatrix<f64>,
    /// `F1 r0`: the constant part of the right-hand side (zero about an equilibrium).
    forcing: DVector<f64>,
    /// `(F1 − F2/h) B`: weight of the remainder at the step's start.
    start: DMatrix<f64>,
    /// `(F2/h) B`: weight of the remainder at the step's end.
    end: DMatrix<f64>,
    /// `C (F2/h) B`: how the end remainder moves the station inputs (the Newton system).
    inputs_from_end: DMatrix<f64>,
    /// `(h²/12) T F1 B`, `T` the tip rows: the interpolation error at the tip per unit `ũ''`.
    tip_error: DMatrix<f64>,
}

impl Level {
    fn new(p: Propagator, split: &Splitting, tip: &DMatrix<f64>) -> Level {
        let end_weight = &p.f2 / p.h;
        let start = (&p.f1 - &end_weight) * &split.b;
        let end = &end_weight * &split.b;
        let tip_error = tip * (&p.f1 * &split.b) * (p.h * p.h / 12.0);
        Level {
            h: p.h,
            forcing: &p.f1 * &split.r0,
            inputs_from_end: &split.c * &end,
            e: p.e,
            start,
            end,
            tip_error,
        }
    }
}

/// The state of the nonlinear (ONERA) stepping: the remainder's history, the substep level,
/// the chord Newton matrix and reused buffers.
#[derive(Clone)]
struct Nonlinear {
    system: Arc<System>,
    split: Splitting,
    scratch: RemainderScratch,
    /// `ũ` at the current state, at the previous step, and that step's length (0: no history).
    u: DVector<f64>,
    u_prev: DVector<f64>,
    h_prev: f64,
    /// Current substep level: `2^level` steps per sample interval.
    level: usize,
    /// `I − K ∂ũ/∂dev` factored, and the level it belongs to.
    chord: Option<(LU<f64, Dyn, Dyn>, usize)>,
    /// Error bounds at the tip per step: twist (rad), flap (m).
    tolerance: [f64; 2],
    /// Counters for the benchmarks and tests.
    steps: u64,
    factorisations: u64,
    // Buffers.
    next: DVector<f64>,
    predicted: DVector<f64>,
    dev: DVector<f64>,
    u_trial: DVector<f64>,
    tangent: Vec<f64>,
    residual: DVector<f64>,
    delta: DVector<f64>,
}

/// Where a nonlinear step failed.
enum StepFailure {
    /// Newton on the station inputs did not converge; its last residual.
    Newton(f64),
}

impl Nonlinear {
    fn new(system: Arc<System>, split: Splitting, flap_scale: f64) -> Nonlinear {
        let (n, p, m) = (split.b.nrows(), split.c.nrows(), split.b.ncols());
        let scratch = system.remainder_scratch();
        Nonlinear {
            system,
            split,
            scratch,
            u: DVector::zeros(m),
            u_prev: DVector::zeros(m),
            h_prev: 0.0,
            level: 0,
            chord: None,
            tolerance: [DEFAULT_TOLERANCE, DEFAULT_TOLERANCE * flap_scale],
            steps: 0,
            factorisations: 0,
            next: DVector::zeros(n),
            predicted: DVector::zeros(p),
            dev: DVector::zeros(p),
            u_trial: DVector::zeros(m),
            tangent: vec![0.0; m * p],
            residual: DVector::zeros(p),
            delta: DVector::zeros(p),
        }
    }

    /// Restart the remainder's history at deviation `y` (after a kick or at the start).
    fn reset(&mut self, y: &DVector<f64>) {
        self.dev.gemv(1.0, &self.split.c, y, 0.0);
        self.system.remainder(
            &self.split,
            self.dev.as_slice(),
            self.u.as_mut_slice(),
            None,
            &mut self.scratch,
        );
        self.u_prev.copy_from(&self.u);
        self.h_prev = 0.0;
    }

    /// `ũ(dev)` into `u_trial`, its derivative into `tangent` when asked, and the Newton residual
    /// `dev − predicted − K ũ(dev)`.
    fn residual_at_dev(&mut self, k: &DMatrix<f64>, want_tangent: bool) -> f64 {
        let tangent = want_tangent.then_some(self.tangent.as_mut_slice());
        self.system.remainder(
            &self.split,
            self.dev.as_slice(),
            self.u_trial.as_mut_slice(),
            tangent,
            &mut self.scratch,
        );
        self.residual.copy_from(&self.dev);
        self.residual -= &self.predicted;
        self.residual.gemv(-1.0, k, &self.u_trial, 1.0);
        self.residual.amax()
    }

    /// Factor `I − K ∂ũ/∂dev` (`∂ũ/∂dev` block diagonal by station, in `tangent`).
    fn factor_chord(&mut self, k: &DMatrix<f64>, level: usize) {
        let p = self.dev.len();
        let (ps, ms) = (
            self.split.inputs_per_station(),
            self.split.outputs_per_station(),
        );
        let mut jac = DMatrix::<f64>::identity(p, p);
        for station in 0..p / ps {
            let block = &self.tangent[station * ms * ps..(station + 1) * ms * ps];
            for o in 0..ms {
                let kcol = k.column(station * ms + o);
                for i in 0..ps {
                    let d = block[o * ps + i];
                    if d != 0.0 {
                        jac.column_mut(station * ps + i).axpy(-d, &kcol, 1.0);
                    }
                }
            }
        }
        self.chord = Some((jac.lu(), level));
        self.factorisations += 1;
    }

    /// One exponential-trapezoidal step of `level` from deviation `y` (replaced by the new
    /// one); returns the tip error estimate `[twist, flap]`.
    fn step(
        &mut self,
        level: &Level,
        index: usize,
        y: &mut DVector<f64>,
    ) -> std::result::Result<[f64; 2], StepFailure> {
        self.steps += 1;
        // Everything known at the step's start: y₊⁰ = E y + F1 r0 + (F1 − F2/h) B ũ₀.
        self.next.gemv(1.0, &level.e, y, 0.0);
        self.next += &level.forcing;
        self.next.gemv(1.0, &level.start, &self.u, 1.0);
        self.predicted.gemv(1.0, &self.split.c, &self.next, 0.0);
        // Newton on dev = predicted + K ũ(dev), starting from the last remainder.
        let k = &level.inputs_from_end;
        self.dev.copy_from(&self.predicted);
        self.dev.gemv(1.0, k, &self.u, 1.0);
        let mut r = self.residual_at_dev(k, false);
        let mut converged = false;
        for _ in 0..NEWTON_MAX_ITERATIONS {
            if r <= NEWTON_TOLERANCE * (1.0 + self.dev.amax()) {
                converged = true;
                break;
            }
            // A chord matrix is kept across steps of one level while it contracts; the stall
            // deviations are piecewise linear, so it stays exact until a station changes piece.
            let fresh = !matches!(&self.chord, Some((_, l)) if *l == index);
            if fresh {
                self.residual_at_dev(k, true);
                self.factor_chord(k, index);
            }
            self.delta.copy_from(&self.residual);
            self.delta.neg_mut();
            let solved = match &self.chord {
                Some((lu, _)) => lu.solve_mut(&mut self.delta),
                None => false,
            };
            if !solved {
                return Err(StepFailure::Newton(r));
            }
            // Damped: halve a step that does not reduce the residual (a kink between two
            // pieces can make the full step cycle).
            let mut t = 1.0;
            let r_new = loop {
                self.dev.axpy(t, &self.delta, 1.0);
                let r_new = self.residual_at_dev(k, false);
                if r_new < r || t < 1.0 / 64.0 {
                    break r_new;
                }
                self.dev.axpy(-t, &self.delta, 1.0);
                if !fresh {
                    break f64::INFINITY;
                }
                t *= 0.5;
            };
            if r_new > 0.25 * r {
                // Slow or no contraction: refactor at the current point.
                self.chord = None;
            }
            if r_new.is_finite() {
                r = r_new;
            } else {
                r = self.residual_at_dev(k, false);
            }
        }
        if !converged {
            return Err(StepFailure::Newton(r));
        }
        // y₊ = y₊⁰ + (F2/h) B ũ₊.
        self.next.gemv(1.0, &level.end, &self.u_trial, 1.0);
        std::mem::swap(y, &mut self.next);
        let estimate = self.tip_error_estimate(level);
        std::mem::swap(&mut self.u_prev, &mut self.u);
        self.u.copy_from(&self.u_trial);
        self.h_prev = level.h;
        Ok(estimate)
    }

    /// `(h²/12) T F1 B ũ''` with `ũ''` the second divided difference over the last two steps
    /// (one-sided, `ũ' = 0` before it, on the first step after a reset).
    fn tip_error_estimate(&self, level: &Level) -> [f64; 2] {
        let h = level.h;
        let mut second = (&self.u_trial - &self.u) / h;
        if self.h_prev > 0.0 {
            second -= (&self.u - &self.u_prev) / self.h_prev;
            second *= 2.0 / (h + self.h_prev);
        } else {
            second *= 2.0 / h;
        }
        let e = &level.tip_error * second;
        [e[0].abs(), e[1].abs()]
    }
}

// ---------------------------------------------------------------------------------------------
// The simulator
// ---------------------------------------------------------------------------------------------

/// An incremental time stepper (the explorer streams from it): every aerodynamic model, one
/// sample interval per [`Simulator::advance`] sample, substeps inside when the nonlinear
/// remainder asks for them.
#[derive(Clone)]
pub struct Simulator {
    /// The tangent system about the reference state (`x_eq` is the reference: the equilibrium,
    /// or for a nonlinear model without one, the rest state).
    linear: LinearSystem,
    /// Operators for `h, h/2, …` (one level for the linear models).
    levels: Vec<Level>,
    /// Deviation from the reference, `x − x_r`, at the next sample time.
    y: DVector<f64>,
    nonlinear: Option<Box<Nonlinear>>,
    /// Sample interval h (s).
    interval: f64,
    /// Index of the next sample to emit.
    next: u64,
    status: RunStatus,
    /// Bound on |u_tip| (m): the blade length.
    flap_bound: f64,
}

impl Simulator {
    /// Start from rest instead of the reference state: `q = 0, q̇ = 0`, aerodynamic states 0 (the
    /// load switched on at t = 0).
    pub fn start_from_rest(&mut self) {
        self.y = -self.linear.x_eq.clone();
        self.restart_history();
    }

    /// A stepper on an already linearised system, starting at its equilibrium: exact stepping
    /// `y₊ = e^{hA} y`.
    pub fn from_linear(
        linear: LinearSystem,
        sample_rate: f64,
        flap_bound: f64,
    ) -> Result<Simulator> {
        let interval = sample_interval(sample_rate)?;
        let step = propagators(&linear.a, interval, 0)?.remove(0);
        let n = linear.dim();
        let level = Level {
            h: interval,
            e: step.e,
            forcing: DVector::zeros(n),
            start: DMatrix::zeros(n, 0),
            end: DMatrix::zeros(n, 0),
            inputs_from_end: DMatrix::zeros(0, 0),
            tip_error: DMatrix::zeros(2, 0),
        };
        Ok(Simulator {
            y: DVector::zeros(n),
            linear,
            levels: vec![level],
            nonlinear: None,
            interval,
            next: 0,
            status: RunStatus::Ok,
            flap_bound,
        })
    }

    /// A stepper on the full (nonlinear) system split about the reference state of `tangent`
    /// (its tangent system there), starting at that state.
    pub fn from_system(
        system: Arc<System>,
        linear: LinearSystem,
        sample_rate: f64,
        flap_bound: f64,
    ) -> Result<Simulator> {
        let interval = sample_interval(sample_rate)?;
        check_finite("state matrix", &linear.a)?;
        // The exact tangent of the right-hand side the remainder is measured against: the
        // linearisation may also hold the left-out modes' quasi-static response (docs/model.md
        // §12.6), which the nonlinear right-hand side does not.
        let split = system.splitting_with(&linear.x_eq, system.jacobian(&linear.x_eq));
        if !split.r0.iter().all(|v| v.is_finite()) {
            return Err(Error::numerical(
                "non-finite right-hand side at the reference state",
            ));
        }
        let tip = DMatrix::from_fn(2, split.a.nrows(), |r, c| {
            let row = if r == 0 {
                &linear.tip_twist
            } else {
                &linear.tip_flap
            };
            if c < linear.nq {
                row[c]
            } else {
                0.0
            }
        });
        let levels = propagators(&split.a, interval, MAX_LEVEL)?
            .into_iter()
            .map(|p| Level::new(p, &split, &tip))
            .collect();
        let n = split.a.nrows();
        let mut nonlinear = Nonlinear::new(system, split, flap_bound);
        nonlinear.reset(&DVector::zeros(n));
        Ok(Simulator {
            y: DVector::zeros(n),
            linear,
            levels,
            nonlinear: Some(Box::new(nonlinear)),
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
            self.step_interval(t)?;
        }
        Ok(out)
    }

    /// Add a tip twist (rad) and tip flap (m) to the current state, along the structure's first
    /// torsion and first flap shapes
    /// ([`crate::physics::structure::Structure::kick_shapes`]): the mix of the two that gives
    /// exactly this tip twist and tip flap (the shapes may each move both).
    pub fn kick(&mut self, twist_rad: f64, flap_m: f64) {
        if twist_rad == 0.0 && flap_m == 0.0 {
            return;
        }
        let l = &self.linear;
        let now = self.next as f64 * self.interval;
        let shapes = l.kick_shapes_at(now);
        let [twist_row, flap_row] = l.tip_rows_at(now);
        let nq = l.nq;
        let tip = |s: &DVector<f64>| {
            let q = s.rows(0, nq);
            (twist_row.dot(&q), flap_row.dot(&q))
        };
        let ((t0, f0), (t1, f1)) = (tip(&shapes[0]), tip(&shapes[1]));
        let det = t0 * f1 - t1 * f0;
        if det == 0.0 || !det.is_finite() {
            return;
        }
        let a = (twist_rad * f1 - flap_m * t1) / det;
        let b = (flap_m * t0 - twist_rad * f0) / det;
        let mut q = self.y.rows_mut(0, 2 * nq);
        q.axpy(a, &shapes[0], 1.0);
        q.axpy(b, &shapes[1], 1.0);
        self.restart_history();
    }

    pub fn status(&self) -> RunStatus {
        self.status
    }

    /// Time of the last emitted sample (s); 0 before the first.
    pub fn time(&self) -> f64 {
        self.next.saturating_sub(1) as f64 * self.interval
    }

    /// The current state x (= x_r + y).
    pub fn state(&self) -> DVector<f64> {
        &self.linear.x_eq + &self.y
    }

    /// The tangent system about the reference state (the equilibrium when there is one).
    pub fn linear(&self) -> &LinearSystem {
        &self.linear
    }

    /// Set the local-error bounds per step at the tip (twist in rad, flap in m) of the
    /// nonlinear stepping; no effect on the (exact) linear models.
    pub fn set_tolerance(&mut self, twist_rad: f64, flap_m: f64) {
        if let Some(nl) = &mut self.nonlinear {
            nl.tolerance = [twist_rad, flap_m];
        }
    }

    /// Steps taken and chord matrices factored so far (nonlinear models; 0 for linear ones).
    pub fn work(&self) -> (u64, u64) {
        self.nonlinear
            .as_ref()
            .map_or((0, 0), |nl| (nl.steps, nl.factorisations))
    }

    fn tip(&self) -> (f64, f64) {
        self.linear
            .tip_at(&self.state(), self.next as f64 * self.interval)
    }

    /// A kick or a new start invalidates the remainder's history.
    fn restart_history(&mut self) {
        if let Some(nl) = &mut self.nonlinear {
            nl.reset(&self.y);
        }
    }

    /// Advance `y` by one sample interval from time `t`.
    fn step_interval(&mut self, t: f64) -> Result<()> {
        let Some(nl) = self.nonlinear.as_deref_mut() else {
            let l = &self.levels[0];
            self.y = &l.e * &self.y + &l.forcing;
            return Ok(());
        };
        let saved = (self.y.clone(), nl.u.clone(), nl.u_prev.clone(), nl.h_prev);
        loop {
            let index = nl.level;
            let level = &self.levels[index];
            let finest = index == MAX_LEVEL;
            let mut worst: f64 = 0.0;
            let mut failure = None;
            for _ in 0..1usize << index {
                match nl.step(level, index, &mut self.y) {
                    Ok([twist, flap]) => {
                        worst = worst
                            .max(twist / nl.tolerance[0])
                            .max(flap / nl.tolerance[1]);
                    }
                    Err(StepFailure::Newton(r)) => {
                        failure = Some(r);
                        break;
                    }
                }
            }
            match failure {
                None if worst <= 1.0 || finest => {
                    // Smooth again: try the coarser level next interval (error ∝ h³ per step).
                    if worst < 0.05 && index > 0 {
                        nl.level -= 1;
                    }
                    return Ok(());
                }
                Some(r) if finest => {
                    if !r.is_finite() || !self.y.iter().all(|v| v.is_finite()) {
                        // The response blew up inside the interval: stop here, as at the
                        // bound, rather than emit a NaN.
                        self.status = RunStatus::Diverging;
                        return Ok(());
                    }
                    return Err(Error::numerical(format!(
                        "time step at t = {t:.6} s: Newton on the stall inputs did not converge \
                         with {} substeps (residual {r:.3e})",
                        1usize << MAX_LEVEL
                    )));
                }
                _ => {}
            }
            // Redo the interval with twice as many steps.
            nl.level += 1;
            self.y.copy_from(&saved.0);
            nl.u.copy_from(&saved.1);
            nl.u_prev.copy_from(&saved.2);
            nl.h_prev = saved.3;
        }
    }
}

/// `1 / sample_rate`, or a usage error.
fn sample_interval(sample_rate: f64) -> Result<f64> {
    if !(sample_rate.is_finite() && sample_rate > 0.0) {
        return Err(Error::usage(format!(
            "simulation.sample_rate = {sample_rate} must be positive"
        )));
    }
    Ok(1.0 / sample_rate)
}
