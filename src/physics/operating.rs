//! The steady aeroelastic operating point of a real blade and its linear system (docs/model.md
//! §12.6).
//!
//! Inputs ([`SteadyInputs`]): the rotor, its aerodynamic stations and strip model, the wind, the
//! rotor speed and pitch (or a control law that sets the pitch), and the structure at any pitch.
//! Steps: the BEM (§12.2) on the blade twisted and bent by its deflection (none at first); the
//! strips on that inflow, induction frozen (§12.5); the static equilibrium of the structure
//! under those strip loads, whose angles of attack see the elastic twist (§6); the BEM again
//! with the new twist and flap, until both settle at every station. Outputs ([`Operation`]): the
//! converged flow, the system about it and the equilibrium state.
//!
//! Why a fixed point rather than one Newton solve on everything: the BEM's induction is a
//! bracketed root per station (robust in stall and parked, §12.2), while the structure's
//! equilibrium is a Newton solve on a handful of modal coordinates; alternating them converges in
//! a few passes on any blade stiff enough to carry its load (the twist changes by the blade's
//! aeroelastic gain per pass, far below one).

use crate::error::{Error, Result};
use crate::physics::aero::blade_element::BladeElement;
use crate::physics::inflow::Station;
use crate::physics::rotor::bem::{self, Conditions, OperatingState, Rotor};
use crate::physics::rotor::schedule::{Law, PitchSearch};
use crate::physics::structure::Structure;
use crate::physics::system::System;
use nalgebra::{DMatrix, DVector};
use std::collections::VecDeque;
use std::sync::Arc;

/// Largest change of the elastic twist at any station (rad), or of its flap over the tip radius,
/// between two passes at which the operating point counts as converged: 1e-7 rad moves a power
/// or a damping by far less than the polar's own resolution.
const TWIST_TOLERANCE: f64 = 1e-7;
/// Passes allowed before the operating point is reported as not settling.
const MAX_PASSES: usize = 60;

/// The converged steady operating point.
pub struct Operation {
    /// The pitch (rad) the passes ended at.
    pub pitch: f64,
    /// The BEM on the deflected blade.
    pub flow: OperatingState,
    /// The structure and strips, inflow frozen at `flow`.
    pub system: System,
    /// The equilibrium state `x*` of `system`.
    pub equilibrium: DVector<f64>,
    /// BEM passes taken.
    pub passes: usize,
}

impl Operation {
    /// Tip deflection `[twist (rad, toward feather), flap (m, downwind), edge (m, toward the
    /// leading edge)]` at the reference axis.
    pub fn tip(&self) -> [f64; 3] {
        self.system.tip_motion(&self.equilibrium)
    }
}

/// What a steady aeroelastic operating point is found from.
pub struct SteadyInputs<'a> {
    pub rotor: Rotor,
    /// The aerodynamic stations, root to tip.
    pub strips: &'a [bem::AeroStation],
    /// The strip model on those stations.
    pub model: BladeElement,
    /// U (m/s), Ω (rad/s), ρ (kg/m³).
    pub wind_speed: f64,
    pub rotor_speed: f64,
    pub air_density: f64,
    /// The pitch (rad) where no law sets it.
    pub pitch: f64,
    /// The operating point as messages name it.
    pub context: &'a dyn Fn() -> String,
}

/// The structure built at one pitch, and what the caller built it from (`tag`), which the
/// operating point hands back with the build it ends on.
pub struct Built<T> {
    pub structure: Arc<dyn Structure>,
    /// The pitch (rad) as built.
    pub pitch: f64,
    pub tag: T,
}

/// Largest difference (rad) between the pitch a pass runs at and the pitch its structure was
/// built at: ten times the law's pitch tolerance, the noise of each pass's pitch search.
const STRUCTURE_PITCH_TOLERANCE: f64 = 1e-6;

/// The passes of the static aeroelastic equilibrium (docs/model.md §12.6) at the inputs' rotor
/// speed; at their pitch, or with `law`, at the pitch each pass's blade needs for rated power.
/// The structure depends on the pitch (§11.8): it follows the passes' pitch, built by `build`
/// (`context` names a build's operating point in messages). Returns the point and the build it
/// ends on.
pub fn settle<T>(
    inputs: &SteadyInputs,
    law: Option<&Law>,
    build: &dyn Fn(f64) -> Result<Built<T>>,
    context: &dyn Fn(&T) -> String,
) -> Result<(Operation, T)> {
    let (rotor, strips, model) = (&inputs.rotor, inputs.strips, &inputs.model);
    let conditions = |pitch: f64| Conditions {
        wind_speed: inputs.wind_speed,
        rotor_speed: inputs.rotor_speed,
        pitch,
        air_density: inputs.air_density,
    };
    // The deflection the BEM sees, `[twist…, flap/R…]`: the flap scaled by the tip radius so
    // that one tolerance (rad) serves both; then, where the structure truncates its basis, the
    // left-out modes' static coordinates, each scaled by the largest twist or flap/R it gives
    // (docs/model.md §12.6).
    let n = strips.len();
    let mut shape = vec![0.0; 2 * n];
    let mut change = f64::INFINITY;
    let mut search = PitchSearch::default();
    // The structure the passes run on, and the build it came from.
    let mut built: Option<Built<T>> = None;
    let mut acceleration = Anderson::default();
    let mut last: Option<System> = None;
    for pass in 1..=MAX_PASSES {
        let deflection: Vec<bem::Deflection> = (0..n)
            .map(|i| bem::Deflection {
                twist: shape[i],
                flap: shape[n + i] * rotor.tip_radius,
            })
            .collect();
        let solve = |pitch: f64| bem::solve(rotor, strips, &deflection, &conditions(pitch));
        let (pitch, flow) = match law {
            None => (inputs.pitch, solve(inputs.pitch)?),
            Some(law) => law_pitch(law, inputs, &mut search, solve)?,
        };
        // The structure turns with the pitch (§11.8): built again where the pass's pitch has
        // moved from the one it was built at. Its pitch moves the equilibrium little (on the
        // NREL 5MW at 25 m/s a structure 1.3° off moves the law's pitch by 1e-4°), so the passes
        // keep their acceleration across the rebuild.
        let b = match built.take() {
            Some(b) if (pitch - b.pitch).abs() <= STRUCTURE_PITCH_TOLERANCE => b,
            _ => {
                last = None;
                build(pitch)?
            }
        };
        let stations = frozen_inflow(strips, &flow, pitch);
        let system = match &last {
            None => System::from_parts(Arc::clone(&b.structure), stations, Box::new(model.clone())),
            Some(earlier) => earlier.on_inflow(stations, Box::new(model.clone())),
        }?;
        let left_out = system.left_out_count();
        shape.resize(2 * n + left_out, 0.0);
        let held = system.left_out_unscaled(&shape[2 * n..]);
        let system = system.with_left_out_at(&held);
        let equilibrium = system.equilibrium().map_err(|e| e.at(context(&b.tag)))?;
        let (system, left_out_scaled) = match system.left_out_response(&equilibrium) {
            Some(p) => {
                let scaled = system.left_out_scaled(&p);
                (system.with_left_out_at(&p), scaled)
            }
            None => (system, Vec::new()),
        };
        let motion = system.station_motion(&equilibrium);
        let settled: Vec<f64> = (motion.iter().map(|[phi, _, _]| *phi))
            .chain(motion.iter().map(|[_, u, _]| u / rotor.tip_radius))
            .chain(left_out_scaled)
            .collect();
        change = settled
            .iter()
            .zip(&shape)
            .fold(0.0, |m, (a, b)| f64::max(m, (a - b).abs()));
        if change <= TWIST_TOLERANCE {
            return Ok((
                Operation {
                    pitch,
                    flow,
                    system,
                    equilibrium,
                    passes: pass,
                },
                b.tag,
            ));
        }
        shape = acceleration.step(&shape, &settled);
        last = Some(system);
        built = Some(b);
    }
    Err(Error::numerical(format!(
        "static aeroelastic equilibrium: the elastic twist had not settled after {MAX_PASSES} \
         BEM passes (last change {:.2e} rad at {}); the blade may be near static divergence",
        change,
        (inputs.context)()
    )))
}

/// The law's pitch for the blade one pass deflects and the BEM there (`solve` at a pitch).
fn law_pitch(
    law: &Law,
    inputs: &SteadyInputs,
    search: &mut PitchSearch,
    solve: impl Fn(f64) -> Result<OperatingState>,
) -> Result<(f64, OperatingState)> {
    let mut tried: Vec<(f64, OperatingState)> = Vec::new();
    let pitch = law
        .pitch(inputs.wind_speed, search, |pitch| {
            let flow = solve(pitch)?;
            let power = flow.power;
            tried.push((pitch, flow));
            Ok(power)
        })
        .map_err(|e| e.at((inputs.context)()))?;
    let flow = match tried.into_iter().rev().find(|(x, _)| *x == pitch) {
        Some((_, flow)) => flow,
        None => solve(pitch)?,
    };
    Ok((pitch, flow))
}

/// Anderson's acceleration of the deflection fixed point (Anderson 1965; Walker & Ni, SIAM J.
/// Numer. Anal. 49:1715–1735, 2011, "type II" with depth [`ANDERSON_DEPTH`]): the next
/// deflection is the combination of the last few passes' outputs whose residuals (output −
/// input) cancel best in the least-squares sense. It uses the history the passes already
/// computed, so it costs no pass of its own; where the map is nearly linear (the affine strip
/// models below stall) it extrapolates to the fixed point in a few passes. Measured on the
/// presets (3–25 m/s, the NREL 5MW to 34 rpm, the IEA 15MW to 13 rpm): 187 passes in all against
/// 227 with Aitken's scalar relaxation, which it replaced; the NREL 5MW at 26 rpm (2.15× rated,
/// near static divergence) in 11 passes instead of 37.
#[derive(Default)]
struct Anderson {
    /// The outputs and residuals (output − input) of the last passes, oldest first.
    outputs: VecDeque<DVector<f64>>,
    residuals: VecDeque<DVector<f64>>,
}

/// Passes an Anderson step combines beyond the last.
const ANDERSON_DEPTH: usize = 3;

impl Anderson {
    /// The next input after a pass took `input` to `output`.
    fn step(&mut self, input: &[f64], output: &[f64]) -> Vec<f64> {
        let plain = DVector::from_column_slice(output);
        self.residuals.push_back(DVector::from_iterator(
            input.len(),
            output.iter().zip(input).map(|(g, x)| g - x),
        ));
        self.outputs.push_back(plain.clone());
        if self.outputs.len() > ANDERSON_DEPTH + 1 {
            self.outputs.pop_front();
            self.residuals.pop_front();
        }
        let passes = self.outputs.len();
        if passes == 1 {
            return output.to_vec();
        }
        // Differences of consecutive residuals and outputs, one column per pair of passes.
        let (f, g) = (&self.residuals, &self.outputs);
        let df = DMatrix::from_fn(input.len(), passes - 1, |r, c| f[c + 1][r] - f[c][r]);
        let dg = DMatrix::from_fn(input.len(), passes - 1, |r, c| g[c + 1][r] - g[c][r]);
        let svd = df.svd(true, true);
        // Columns that are (nearly) dependent are dropped by the tolerance.
        let tolerance = 1e-10 * svd.singular_values.max();
        match svd.solve(&f[passes - 1], tolerance) {
            Ok(gamma) if gamma.iter().all(|v| v.is_finite()) => {
                (plain - dg * gamma).iter().copied().collect()
            }
            _ => output.to_vec(),
        }
    }
}

/// The system's stations on the BEM's inflow: speed and inflow angle after induction, rigid
/// angle of attack without the elastic twist (the system adds it).
fn frozen_inflow(strips: &[bem::AeroStation], flow: &OperatingState, pitch: f64) -> Vec<Station> {
    strips
        .iter()
        .zip(&flow.stations)
        .enumerate()
        .map(|(index, (s, f))| Station {
            index,
            x: s.span,
            weight: s.weight,
            radius: f.radius,
            v0: f.relative_speed,
            psi: f.inflow_angle,
            alpha_r: f.inflow_angle - pitch - s.section.twist,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Passes to within 1e-8 of the fixed point of `x → Gx + c` from zero: with Anderson's
    /// acceleration, and plain.
    fn passes_to_the_fixed_point(g: &DMatrix<f64>, c: &DVector<f64>) -> (usize, usize) {
        let n = c.len();
        let fixed = (DMatrix::identity(n, n) - g).lu().solve(c).unwrap();
        let map = |x: &[f64]| -> Vec<f64> {
            (g * DVector::from_column_slice(x) + c)
                .iter()
                .copied()
                .collect()
        };
        let distance = |x: &[f64]| (DVector::from_column_slice(x) - &fixed).amax();
        let mut acceleration = Anderson::default();
        let (mut x, mut accelerated) = (vec![0.0; n], 0);
        while distance(&x) > 1e-8 && accelerated < 1000 {
            let out = map(&x);
            x = acceleration.step(&x, &out);
            accelerated += 1;
        }
        let (mut y, mut plain) = (vec![0.0; n], 0);
        while distance(&y) > 1e-8 && plain < 1000 {
            y = map(&y);
            plain += 1;
        }
        (accelerated, plain)
    }

    /// A slowly converging and an oscillating direction (spectral radius 0.9): plain passes need
    /// about 200 steps for 1e-8. Anderson's acceleration of depth 3 is a Krylov method on a
    /// linear map: with no more directions than its depth it lands on the fixed point within a
    /// few passes, and with one more it still needs a tenth of the plain passes.
    #[test]
    fn anderson_finds_the_fixed_point_of_a_linear_map_in_a_few_passes() {
        let g = DMatrix::from_row_slice(
            4,
            4,
            &[
                0.9, 0.05, 0.0, 0.0, //
                0.0, -0.8, 0.1, 0.0, //
                0.0, 0.0, 0.5, 0.2, //
                0.0, 0.0, 0.0, 0.1,
            ],
        );
        let c = DVector::from_vec(vec![1.0, -2.0, 0.5, 3.0]);
        let three = g.view((0, 0), (3, 3)).into_owned();
        let (accelerated, plain) = passes_to_the_fixed_point(&three, &c.rows(0, 3).into_owned());
        assert!(accelerated <= 5 && plain > 150, "{accelerated} / {plain}");
        let (accelerated, plain) = passes_to_the_fixed_point(&g, &c);
        assert!(accelerated <= 20 && plain > 150, "{accelerated} / {plain}");
    }
}
