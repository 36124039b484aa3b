//! The static equilibrium of the system (docs/model.md §6): Newton's method on the structural
//! coordinates, with load continuation where it stalls.

use super::{Derivatives, System};
use crate::error::{Error, Result};
use crate::physics::aero::SteadyStates;
use nalgebra::{DMatrix, DVector};

/// Newton iterations allowed for the static equilibrium before reporting non-convergence.
const NEWTON_MAX_ITERATIONS: usize = 60;
/// Smallest load-factor step of the equilibrium's load continuation: below it the branch counts
/// as ended (1e-3 of the load locates a fold far more finely than any operating point needs).
const MIN_LOAD_STEP: f64 = 1e-3;
/// Where the equilibrium branch ends with the tangent stiffness's smallest eigenvalue below this
/// fraction of the blade's softest stiffness, the air has cancelled nearly all of it: a fold of
/// the branch, static divergence (a kink of a polar leaves the tangent far from singular).
const DIVERGENCE_MARGIN: f64 = 0.1;

impl System {
    /// The static equilibrium x* (q̇ = 0, aero states steady, `K q = Q(q)`), by Newton's method
    /// on q with a backtracking line search (docs/model.md §6). For the affine models (theodorsen,
    /// none) the first step is the exact linear solve; quasi-steady's `cos α_g` moment arm is
    /// mildly nonlinear in φ and takes a few steps more. Where Newton from the unloaded blade
    /// stalls (a heavily loaded, soft blade: the NREL 5MW in overspeed), the load is ramped up
    /// from zero along the equilibrium branch ([`System::load_continuation`]); if the branch ends
    /// before the full load, the error says where and why (static divergence).
    pub fn equilibrium(&self) -> Result<DVector<f64>> {
        let q0 = DVector::zeros(self.nq());
        let (rigid, jac) = self.static_residual(&q0, 1.0, true)?;
        let scale = self.load_scale(&rigid);
        match self.newton_from(q0, rigid, jac, 1.0, scale) {
            Ok(q) => Ok(self.steady_state_of(&q, 1.0)),
            Err(_) => self
                .load_continuation(scale)
                .map(|q| self.steady_state_of(&q, 1.0)),
        }
    }

    /// Load scale of the convergence test: the rigid (q = 0) load `rigid`, floored by the
    /// stiffness.
    fn load_scale(&self, rigid: &DVector<f64>) -> f64 {
        rigid
            .norm()
            .max(self.stiffness.amax() * 1e-12)
            .max(f64::MIN_POSITIVE)
    }

    /// Newton from `q` on `K q = s Q(q)` at load factor `s` (see [`System::newton_from`]).
    fn newton(&self, q: DVector<f64>, load: f64, scale: f64) -> Result<DVector<f64>> {
        let (res, jac) = self.static_residual(&q, load, true)?;
        self.newton_from(q, res, jac, load, scale)
    }

    /// Newton from `q`, whose residual `res` and tangent `jac` the caller has, with a
    /// backtracking line search (the full Newton step overshoots and cycles on soft blades).
    /// Later tangents are assembled only where a step is taken: the residual of an accepted
    /// trial is the next iterate's, and the affine models converge on their first step, so the
    /// usual solve assembles one tangent.
    fn newton_from(
        &self,
        mut q: DVector<f64>,
        mut res: DVector<f64>,
        jac: DMatrix<f64>,
        load: f64,
        scale: f64,
    ) -> Result<DVector<f64>> {
        let mut jac = Some(jac);
        for _ in 0..NEWTON_MAX_ITERATIONS {
            let rnorm = res.norm();
            if rnorm <= 1e-12 * scale {
                return Ok(q);
            }
            let tangent = match jac.take() {
                Some(j) => j,
                None => self.static_residual(&q, load, true)?.1,
            };
            let step = tangent
                .lu()
                .solve(&(-&res))
                .filter(|s| s.iter().all(|v| v.is_finite()))
                .ok_or_else(|| {
                    Error::numerical(
                        "static equilibrium: singular tangent stiffness (the operating point sits \
                         on a static-divergence boundary)",
                    )
                })?;
            if step.norm() <= 1e-14 * (1.0 + q.norm()) {
                // Round-off level: the residual cannot be reduced further.
                return Ok(q);
            }
            // Backtracking with an Armijo-type sufficient decrease.
            let mut t = 1.0;
            loop {
                let trial = &q + t * &step;
                let (r, _) = self.static_residual(&trial, load, false)?;
                if r.norm() <= (1.0 - 1e-4 * t) * rnorm {
                    (q, res) = (trial, r);
                    break;
                }
                t *= 0.5;
                if t < 1e-6 {
                    return Err(Error::numerical(format!(
                        "static equilibrium: Newton line search stalled (residual {rnorm:.3e} \
                         against load scale {scale:.3e})"
                    )));
                }
            }
        }
        Err(Error::numerical(format!(
            "static equilibrium did not converge in {NEWTON_MAX_ITERATIONS} Newton steps \
             (residual {:.3e} against load scale {scale:.3e})",
            res.norm()
        )))
    }

    /// Natural-parameter continuation in the load factor `s` from 0 (the unloaded blade, q = 0)
    /// to 1: each step's Newton starts from the last equilibrium, the step grows after a success
    /// and halves after a failure. When the step falls below [`MIN_LOAD_STEP`] the branch ends
    /// short of the full load: the error gives the load reached and the smallest eigenvalue of
    /// the tangent stiffness `K − ∂(sQ)/∂q` relative to the blade's softest stiffness, which is
    /// near zero (or negative) at a fold of the branch: static divergence, no equilibrium at the
    /// full load.
    fn load_continuation(&self, scale: f64) -> Result<DVector<f64>> {
        let mut q = DVector::zeros(self.nq());
        let (mut load, mut step) = (0.0, 0.25);
        while load < 1.0 {
            let next = f64::min(load + step, 1.0);
            match self.newton(q.clone(), next, scale * next) {
                Ok(reached) => {
                    (q, load) = (reached, next);
                    step = f64::min(2.0 * step, 0.5);
                }
                Err(_) if step > MIN_LOAD_STEP => step *= 0.5,
                Err(e) => return Err(self.branch_end(&q, load, e)),
            }
        }
        Ok(q)
    }

    /// Why the equilibrium branch ends at load factor `load` with deflection `q`: the tangent
    /// stiffness there (docs/model.md §6).
    fn branch_end(&self, q: &DVector<f64>, load: f64, last: Error) -> Error {
        let tangent = match self.static_residual(q, load, true) {
            Ok((_, jac)) => -jac,
            Err(e) => return e,
        };
        let softest = tangent
            .complex_eigenvalues()
            .iter()
            .map(|l| l.re)
            .fold(f64::INFINITY, f64::min);
        // Against the blade's own softest stiffness: how much of it the aerodynamic stiffness
        // has cancelled.
        let structural = self
            .stiffness
            .clone()
            .symmetric_eigenvalues()
            .min()
            .max(f64::MIN_POSITIVE);
        let relative = softest / structural;
        let why = if relative < DIVERGENCE_MARGIN {
            "the tangent stiffness is (nearly) singular there: the aerodynamic stiffness cancels \
             the blade's (static divergence), so no static equilibrium carries the full load"
        } else {
            "the tangent stiffness is still regular there: the load path crosses a kink of the \
             linearly interpolated polars that Newton cannot step over"
        };
        Error::numerical(format!(
            "static equilibrium: ramping the aerodynamic load up from the unloaded blade, the \
             equilibrium branch ends at {:.1} % of the load (the tangent stiffness's smallest \
             eigenvalue is {:.1} % of the blade's softest); {why} ({last})",
            100.0 * load,
            100.0 * relative
        ))
    }

    /// The full state at static deflection q: q̇ = 0, aero states steady (`ramp`: the share of
    /// the left-out modes' response to the strip loads, [`System::position_at`]).
    fn steady_state_of(&self, q: &DVector<f64>, ramp: f64) -> DVector<f64> {
        let nq = self.nq();
        let mut x = DVector::zeros(self.dim());
        x.rows_mut(0, nq).copy_from(q);
        let mut st = SteadyStates::new(self.ns);
        for (si, s) in self.stations.iter().enumerate() {
            let deflection = self.position_at(si, q.as_view(), ramp);
            self.model.steady_states(s, deflection, &mut st);
            x.rows_mut(2 * nq + si * self.ns, self.ns)
                .copy_from_slice(&st.z);
        }
        x
    }

    /// `R(q) = s Q(q, 0, z*(q)) + f − K q` at load factor `s` (1: the full aerodynamic load; the
    /// structure's own static load `f`, the centrifugal pull on a curved blade, is never ramped:
    /// it is linear; the left-out modes' response to the strip loads is ramped with them, their
    /// response to `f` is not) and, when asked,
    /// `dR/dq` (aero states held steady).
    fn static_residual(
        &self,
        q: &DVector<f64>,
        load: f64,
        want_jac: bool,
    ) -> Result<(DVector<f64>, DMatrix<f64>)> {
        let nq = self.nq();
        let x = self.steady_state_of(q, load);
        let (qv, v, z) = self.split(&x);
        let wanted = if want_jac {
            Derivatives::Static
        } else {
            Derivatives::None
        };
        let pr = self.project(qv, v, z, wanted, load);
        let mut res = load * &pr.force - &self.stiffness * q;
        self.add_static_load(&mut res);
        if !res.iter().all(|v| v.is_finite()) {
            return Err(Error::numerical(
                "static equilibrium: non-finite aerodynamic load (check the operating point)",
            ));
        }
        if !want_jac {
            return Ok((res, DMatrix::zeros(0, 0)));
        }
        let mut jac = &pr.dq * load - &self.stiffness;
        if self.ns > 0 {
            // Chain rule through the steady states: dz*/dq.
            let mut zq = DMatrix::zeros(self.n_aero(), nq);
            let mut st = SteadyStates::new(self.ns);
            for (si, s) in self.stations.iter().enumerate() {
                let deflection = self.position_at(si, q.as_view(), load);
                self.model.steady_states(s, deflection, &mut st);
                let rows = self.kinematic_rows(si);
                for i in 0..self.ns {
                    let mut row = zq.row_mut(si * self.ns + i);
                    for (d, r) in st.dz_dk[i].iter().zip(rows) {
                        if *d != 0.0 {
                            row += *d * r.transpose();
                        }
                    }
                }
            }
            jac += (&pr.dz * zq) * load;
        }
        Ok((res, jac))
    }
}
