//! The right-hand side split about a reference state for the time stepper (docs/model.md §7).

use super::System;
use crate::physics::aero::{Kinematics, NonlinearSupport, StripEval, RATES};
use nalgebra::{DMatrix, DVector};

// ---- the split about a reference state, for the time stepper (docs/model.md §7) ----

/// The right-hand side split about a reference state `x_r` for the time stepper (docs/model.md §7):
///
/// `ẋ = r0 + A (x − x_r) + B ũ(C (x − x_r))`
///
/// with `A = ∂f/∂x(x_r)` and `r0 = f(x_r)`. The strip models' nonlinear parts read a few local
/// inputs ([`NonlinearSupport`]); `C` picks those inputs at every station out of the state, `B`
/// takes the outputs they write into `ẋ` (a load through `(M − M_a)⁻¹` and the Galerkin
/// projection, a state rate directly), and `ũ` is what those outputs add beyond their tangent at
/// `x_r`. The split is exact, not an approximation: every other output is affine with constant
/// coefficients, so it is all in `A`. For the affine models `ũ` is empty.
#[derive(Clone)]
pub struct Splitting {
    pub x_ref: DVector<f64>,
    pub a: DMatrix<f64>,
    pub r0: DVector<f64>,
    /// `n × m`: where each station's nonlinear outputs enter `ẋ`.
    pub b: DMatrix<f64>,
    /// `p × n`: the station inputs the nonlinear parts read.
    pub c: DMatrix<f64>,
    support: NonlinearSupport,
    /// Per station: local inputs and nonlinear outputs at `x_r`, and their tangent
    /// (outputs × inputs, row-major).
    reference: Vec<StripReference>,
}

#[derive(Clone)]
struct StripReference {
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    tangent: Vec<f64>,
}

/// Reused buffers for [`System::remainder`] (the stepper's inner loop does not allocate).
#[derive(Clone)]
pub struct RemainderScratch {
    eval: StripEval,
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    tangent: Vec<f64>,
}

impl Splitting {
    /// Nonlinear inputs per station (`p / stations`).
    pub fn inputs_per_station(&self) -> usize {
        self.support.inputs.len()
    }
    /// Nonlinear outputs per station (`m / stations`).
    pub fn outputs_per_station(&self) -> usize {
        self.support.outputs.len()
    }
    /// True when the model is affine: the split is `ẋ = r0 + A (x − x_r)` exactly.
    pub fn is_affine(&self) -> bool {
        self.support.outputs.is_empty()
    }
}

impl System {
    /// The split of the right-hand side about `x_ref` ([`Splitting`]).
    pub fn splitting(&self, x_ref: &DVector<f64>) -> Splitting {
        self.splitting_with(x_ref, self.jacobian(x_ref))
    }

    /// [`System::splitting`] with the Jacobian at `x_ref` already known (`a`), as the
    /// linearisation that found the equilibrium has it.
    pub fn splitting_with(&self, x_ref: &DVector<f64>, a: DMatrix<f64>) -> Splitting {
        let (nq, ns) = (self.nq(), self.ns);
        let dim = self.dim();
        let support = self.model.nonlinear_support();
        let (p, m) = (support.inputs.len(), support.outputs.len());
        let stations = self.stations.len();
        let mut b = DMatrix::zeros(dim, m * stations);
        let mut c = DMatrix::zeros(p * stations, dim);
        let mut scratch = self.remainder_scratch();
        let mut reference = Vec::with_capacity(stations);
        for (si, s) in self.stations.iter().enumerate() {
            for (r, &input) in support.inputs.iter().enumerate() {
                let mut row = c.row_mut(si * p + r);
                if input < NonlinearSupport::FIRST_STATE {
                    // A deflection reads q, a rate q̇, through the same motion row.
                    let offset = if input < RATES { 0 } else { nq };
                    let motion = &self.rows[si][input % RATES];
                    row.columns_mut(offset, nq).copy_from(&motion.transpose());
                } else {
                    row[2 * nq + si * ns + input - NonlinearSupport::FIRST_STATE] = 1.0;
                }
            }
            for (k, &output) in support.outputs.iter().enumerate() {
                let col = si * m + k;
                if output < NonlinearSupport::FIRST_RATE {
                    // A load per span: Galerkin projection, then the mass matrix.
                    let projected = &self.mass_inv * (s.weight * &self.rows[si][output]);
                    b.view_mut((nq, col), (nq, 1)).copy_from(&projected);
                } else {
                    b[(
                        2 * nq + si * ns + output - NonlinearSupport::FIRST_RATE,
                        col,
                    )] = 1.0;
                }
            }
            self.local_inputs(si, x_ref, &mut scratch.inputs);
            self.evaluate_nonlinear(si, &support, &mut scratch, true);
            reference.push(StripReference {
                inputs: scratch.inputs.clone(),
                outputs: scratch.outputs.clone(),
                tangent: scratch.tangent.clone(),
            });
        }
        Splitting {
            x_ref: x_ref.clone(),
            a,
            r0: self.rhs(x_ref),
            b,
            c,
            support,
            reference,
        }
    }

    pub fn remainder_scratch(&self) -> RemainderScratch {
        RemainderScratch {
            eval: StripEval::new(self.ns),
            inputs: Vec::with_capacity(NonlinearSupport::FIRST_STATE + self.ns),
            outputs: Vec::new(),
            tangent: Vec::new(),
        }
    }

    /// `ũ` at input deviations `dev = C (x − x_r)` into `u` (`m`), and when asked its derivative
    /// `∂ũ/∂dev` into `tangent`: one `m_s × p_s` row-major block per station (the derivative is
    /// block diagonal, a station's outputs read only its own inputs).
    pub fn remainder(
        &self,
        split: &Splitting,
        dev: &[f64],
        u: &mut [f64],
        mut tangent: Option<&mut [f64]>,
        scratch: &mut RemainderScratch,
    ) {
        let support = &split.support;
        let (p, m) = (support.inputs.len(), support.outputs.len());
        for (si, reference) in split.reference.iter().enumerate() {
            let dev = &dev[si * p..(si + 1) * p];
            scratch.inputs.clear();
            scratch.inputs.extend_from_slice(&reference.inputs);
            for (&input, d) in support.inputs.iter().zip(dev) {
                scratch.inputs[input] += d;
            }
            self.evaluate_nonlinear(si, support, scratch, tangent.is_some());
            for k in 0..m {
                let row = &reference.tangent[k * p..(k + 1) * p];
                let linear: f64 = row.iter().zip(dev).map(|(t, d)| t * d).sum();
                u[si * m + k] = scratch.outputs[k] - reference.outputs[k] - linear;
            }
            if let Some(t) = tangent.as_deref_mut() {
                let block = &mut t[si * m * p..(si + 1) * m * p];
                for ((out, now), then) in block
                    .iter_mut()
                    .zip(&scratch.tangent)
                    .zip(&reference.tangent)
                {
                    *out = now - then;
                }
            }
        }
    }

    /// Station `si`'s local inputs `[φ, u, v, φ̇, u̇, v̇, z…]` in state `x`.
    fn local_inputs(&self, si: usize, x: &DVector<f64>, out: &mut Vec<f64>) {
        let (nq, ns) = (self.nq(), self.ns);
        out.clear();
        out.extend_from_slice(&self.deflection_at(si, x.rows(0, nq)));
        out.extend_from_slice(&self.rate_at(si, x.rows(nq, nq)));
        out.extend(x.rows(2 * nq + si * ns, ns).iter());
    }

    /// Evaluate station `si` at `scratch.inputs`; keep the supported outputs and, when asked,
    /// their derivatives with respect to the supported inputs.
    fn evaluate_nonlinear(
        &self,
        si: usize,
        support: &NonlinearSupport,
        scratch: &mut RemainderScratch,
        want: bool,
    ) {
        let inp = &scratch.inputs;
        let mut kinematics = [0.0; NonlinearSupport::FIRST_STATE];
        kinematics.copy_from_slice(&inp[..NonlinearSupport::FIRST_STATE]);
        let k = Kinematics::from_array(kinematics);
        let e = &mut scratch.eval;
        self.model.evaluate(
            &self.stations[si],
            &k,
            &inp[NonlinearSupport::FIRST_STATE..],
            e,
            want,
        );
        let ns = self.ns;
        let value = |o: usize| {
            if o < NonlinearSupport::FIRST_RATE {
                e.loads[o]
            } else {
                e.zdot[o - NonlinearSupport::FIRST_RATE]
            }
        };
        scratch.outputs.clear();
        scratch
            .outputs
            .extend(support.outputs.iter().map(|&o| value(o)));
        if !want {
            return;
        }
        let slope = |o: usize, i: usize| match (
            o < NonlinearSupport::FIRST_RATE,
            i < NonlinearSupport::FIRST_STATE,
        ) {
            (true, true) => e.dloads_dk[o][i],
            (true, false) => e.dloads_dz[o][i - NonlinearSupport::FIRST_STATE],
            (false, true) => e.dzdot_dk[o - NonlinearSupport::FIRST_RATE][i],
            (false, false) => {
                e.dzdot_dz
                    [(o - NonlinearSupport::FIRST_RATE) * ns + i - NonlinearSupport::FIRST_STATE]
            }
        };
        scratch.tangent.clear();
        for &o in &support.outputs {
            scratch
                .tangent
                .extend(support.inputs.iter().map(|&i| slope(o, i)));
        }
    }
}
