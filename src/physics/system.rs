//! The coupled aeroelastic system: structure + strip aerodynamics as one first-order ODE
//! (docs/model.md §6), its static equilibrium and its linearisation.
//!
//! State `x = [q, q̇, z]`: the structure's coordinates `q` (`n_q`: Galerkin coefficients of the
//! paper's blade, modal coordinates of a tabulated one; [`Structure`]), their rates and the
//! aerodynamic states `z` (station-major: `z[s·n_s + i]` is state `i` of station `s`).
//!
//! `(M − M_a) q̈ = Q(q, q̇, z) − K q − C q̇`, `ż = G(q, q̇, z)`, where `Q` is the projection
//! `Q = Σ_s w_s (m_φ e_φ(x_s) + f_u e_u(x_s) + f_v e_v(x_s))` of the strip loads on the
//! structure's motion rows (`φ = e_φ·q`, `u = e_u·q`, `v = e_v·q` at the station,
//! [`MotionRows`]; the paper's blade has `e_v = 0`) and `M_a = Σ_s w_s Pᵀ M_a,s P` the apparent
//! mass (P maps `q` to the strip's `[φ, u, v]`).
//!
//! The system is written for any [`StripModel`], linear or not: [`System::rhs`] gives `ẋ`,
//! [`System::jacobian`] its exact Jacobian (chain rule through the models' analytic partials),
//! [`System::equilibrium`] a damped Newton solve (one step for the affine models), and
//! [`System::linearise`] the state matrix `A = ∂ẋ/∂x` at equilibrium. A nonlinear model (ONERA,
//! §5.3) joins by implementing `StripModel`. For its time response (§7), [`System::splitting`]
//! separates the right-hand side about a reference state into the exact tangent and the few
//! scalar nonlinear strip outputs the model declares, and [`System::remainder`] evaluates those.

use crate::error::{Error, Result};
use crate::physics::aero::{
    Kinematics, NonlinearSupport, SteadyStates, StripEval, StripModel, LOADS, RATES,
};
use crate::physics::inflow::Station;
use crate::physics::structure::Structure;
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

/// Newton iterations allowed for the static equilibrium before reporting non-convergence.
const NEWTON_MAX_ITERATIONS: usize = 60;
/// Smallest load-factor step of the equilibrium's load continuation: below it the branch counts
/// as ended (1e-3 of the load locates a fold far more finely than any operating point needs).
const MIN_LOAD_STEP: f64 = 1e-3;
/// Where the equilibrium branch ends with the tangent stiffness's smallest eigenvalue below this
/// fraction of the blade's softest stiffness, the air has cancelled nearly all of it: a fold of
/// the branch, static divergence (a kink of a polar leaves the tangent far from singular).
const DIVERGENCE_MARGIN: f64 = 0.1;

pub struct System {
    structure: Arc<dyn Structure>,
    stations: Vec<Station>,
    model: Box<dyn StripModel>,
    /// The rows e_φ, e_u and e_v that map q to each strip's φ, u and v.
    rows: Arc<Vec<[DVector<f64>; RATES]>>,
    /// The same at the tip.
    tip_rows: [DVector<f64>; RATES],
    /// (M − M_a)⁻¹, factored once: every rhs and Jacobian needs it.
    mass_inv: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    /// States per station.
    ns: usize,
}

/// Which derivatives a [`System::project`] call assembles.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Derivatives {
    None,
    /// ∂Q/∂q and ∂Q/∂z only: all the static equilibrium's Newton step reads. Skipping the rest
    /// saves about half of each projection on a real blade (30 stations, 60 lag states), where
    /// the operating point takes two of them per Newton step on every BEM pass.
    Static,
    All,
}

/// Generalised loads and aero-state rates at one state, with their Jacobians when asked.
struct Projection {
    force: DVector<f64>,
    zdot: DVector<f64>,
    /// ∂Q/∂q, ∂Q/∂q̇, ∂Q/∂z.
    dq: DMatrix<f64>,
    dv: DMatrix<f64>,
    dz: DMatrix<f64>,
    /// ∂G/∂q, ∂G/∂q̇, ∂G/∂z.
    gq: DMatrix<f64>,
    gv: DMatrix<f64>,
    gz: DMatrix<f64>,
}

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
    pub structure: Arc<dyn Structure>,
}

impl System {
    /// Build from an assembled structure, stations (along the structure's span) and a strip
    /// model.
    pub fn from_parts(
        structure: Arc<dyn Structure>,
        stations: Vec<Station>,
        model: Box<dyn StripModel>,
    ) -> Result<System> {
        let motion = |x: f64| {
            let r = structure.motion_rows(x);
            [r.twist, r.flap, r.edge]
        };
        let rows: Arc<Vec<_>> = Arc::new(stations.iter().map(|s| motion(s.x)).collect());
        let tip_rows = motion(structure.length());
        let stiffness = structure.stiffness();
        check_finite("stiffness matrix", &stiffness)?;
        let damping = structure.damping().clone();
        check_finite("damping matrix", &damping)?;
        let mass_inv = mass_inverse(structure.as_ref(), &stations, &rows, model.as_ref())?;
        let ns = model.states_per_station();
        Ok(System {
            structure,
            stations,
            model,
            rows,
            tip_rows,
            mass_inv,
            stiffness,
            damping,
            ns,
        })
    }

    /// This system on another inflow: `stations` at the same span positions with their own speed
    /// and angles, and `model` the same strip model (a steady operating point's next BEM pass,
    /// docs/model.md §12.6). The structure's rows at the stations and its matrices are shared,
    /// not rebuilt; only the apparent mass, which turns with the inflow angle, is assembled
    /// again.
    pub fn on_inflow(&self, stations: Vec<Station>, model: Box<dyn StripModel>) -> Result<System> {
        debug_assert!(self
            .stations
            .iter()
            .zip(&stations)
            .all(|(a, b)| a.x == b.x && a.weight == b.weight));
        let mass_inv = mass_inverse(
            self.structure.as_ref(),
            &stations,
            &self.rows,
            model.as_ref(),
        )?;
        Ok(System {
            structure: Arc::clone(&self.structure),
            stations,
            model,
            rows: Arc::clone(&self.rows),
            tip_rows: self.tip_rows.clone(),
            mass_inv,
            stiffness: self.stiffness.clone(),
            damping: self.damping.clone(),
            ns: self.ns,
        })
    }

    /// Length of the state vector: 2 n_q + aero states.
    pub fn dim(&self) -> usize {
        2 * self.nq() + self.n_aero()
    }
    /// Structural coordinates n_q.
    pub fn nq(&self) -> usize {
        self.structure.coordinates()
    }
    pub fn n_aero(&self) -> usize {
        self.ns * self.stations.len()
    }
    pub fn structure(&self) -> &dyn Structure {
        self.structure.as_ref()
    }
    pub fn stations(&self) -> &[Station] {
        &self.stations
    }
    pub fn model(&self) -> &dyn StripModel {
        self.model.as_ref()
    }

    /// Tip twist φ(L) (rad) and tip flap u(L) (m) of a state.
    pub fn tip(&self, x: &DVector<f64>) -> (f64, f64) {
        let q = x.rows(0, self.nq());
        (self.tip_rows[0].dot(&q), self.tip_rows[1].dot(&q))
    }

    /// `[φ, u, v]` (twist toward feather, flap downwind, edge toward the leading edge) at the
    /// tip's reference axis in state `x`.
    pub fn tip_motion(&self, x: &DVector<f64>) -> [f64; RATES] {
        let q = x.rows(0, self.nq());
        self.tip_rows.each_ref().map(|row| row.dot(&q))
    }

    /// `[φ, u, v]` at every station in state `x`.
    pub fn station_motion(&self, x: &DVector<f64>) -> Vec<[f64; RATES]> {
        let q = x.rows(0, self.nq());
        (0..self.stations.len())
            .map(|si| self.deflection_at(si, q))
            .collect()
    }

    /// ẋ = f(x).
    pub fn rhs(&self, x: &DVector<f64>) -> DVector<f64> {
        let nq = self.nq();
        let (q, v, z) = self.split(x);
        let pr = self.project(q, v, z, Derivatives::None);
        let mut out = DVector::zeros(self.dim());
        out.rows_mut(0, nq).copy_from(&v);
        let net = &pr.force - &self.stiffness * q - &self.damping * v;
        out.rows_mut(nq, nq).copy_from(&(&self.mass_inv * net));
        out.rows_mut(2 * nq, self.n_aero()).copy_from(&pr.zdot);
        out
    }

    /// ∂ẋ/∂x at `x`, exact.
    pub fn jacobian(&self, x: &DVector<f64>) -> DMatrix<f64> {
        let (nq, na) = (self.nq(), self.n_aero());
        let (q, v, z) = self.split(x);
        let pr = self.project(q, v, z, Derivatives::All);
        let mut a = DMatrix::zeros(self.dim(), self.dim());
        a.view_mut((0, nq), (nq, nq)).fill_with_identity();
        a.view_mut((nq, 0), (nq, nq))
            .copy_from(&(&self.mass_inv * (&pr.dq - &self.stiffness)));
        a.view_mut((nq, nq), (nq, nq))
            .copy_from(&(&self.mass_inv * (&pr.dv - &self.damping)));
        if na > 0 {
            a.view_mut((nq, 2 * nq), (nq, na))
                .copy_from(&(&self.mass_inv * &pr.dz));
            a.view_mut((2 * nq, 0), (na, nq)).copy_from(&pr.gq);
            a.view_mut((2 * nq, nq), (na, nq)).copy_from(&pr.gv);
            a.view_mut((2 * nq, 2 * nq), (na, na)).copy_from(&pr.gz);
        }
        a
    }

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
            Ok(q) => Ok(self.steady_state_of(&q)),
            Err(_) => self
                .load_continuation(scale)
                .map(|q| self.steady_state_of(&q)),
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

    /// Equilibrium and the state matrix there.
    pub fn linearise(&self) -> Result<LinearSystem> {
        self.linearise_at(None)
    }

    /// The state matrix at `known`, an equilibrium of this system found while building it
    /// ([`System::with_equilibrium`]), or at the one solved here when there is none.
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
            structure: Arc::clone(&self.structure),
        }
    }

    // ---- internals ----

    fn split<'a>(
        &self,
        x: &'a DVector<f64>,
    ) -> (
        nalgebra::DVectorView<'a, f64>,
        nalgebra::DVectorView<'a, f64>,
        nalgebra::DVectorView<'a, f64>,
    ) {
        let nq = self.nq();
        (x.rows(0, nq), x.rows(nq, nq), x.rows(2 * nq, self.n_aero()))
    }

    /// The full state at static deflection q: q̇ = 0, aero states steady.
    fn steady_state_of(&self, q: &DVector<f64>) -> DVector<f64> {
        let nq = self.nq();
        let mut x = DVector::zeros(self.dim());
        x.rows_mut(0, nq).copy_from(q);
        let mut st = SteadyStates::new(self.ns);
        for (si, s) in self.stations.iter().enumerate() {
            let deflection = self.deflection_at(si, q.as_view());
            self.model.steady_states(s, deflection, &mut st);
            x.rows_mut(2 * nq + si * self.ns, self.ns)
                .copy_from_slice(&st.z);
        }
        x
    }

    /// `R(q) = s Q(q, 0, z*(q)) − K q` at load factor `s` (1: the full load) and, when asked,
    /// `dR/dq` (aero states held steady).
    fn static_residual(
        &self,
        q: &DVector<f64>,
        load: f64,
        want_jac: bool,
    ) -> Result<(DVector<f64>, DMatrix<f64>)> {
        let nq = self.nq();
        let x = self.steady_state_of(q);
        let (qv, v, z) = self.split(&x);
        let wanted = if want_jac {
            Derivatives::Static
        } else {
            Derivatives::None
        };
        let pr = self.project(qv, v, z, wanted);
        let res = load * &pr.force - &self.stiffness * q;
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
                let deflection = self.deflection_at(si, q.as_view());
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

    /// `[φ, u, v]` at station `si` for coordinates `q`.
    fn deflection_at(&self, si: usize, q: nalgebra::DVectorView<f64>) -> [f64; RATES] {
        self.rows[si].each_ref().map(|row| row.dot(&q))
    }

    fn kinematic_rows(&self, si: usize) -> &[DVector<f64>; RATES] {
        &self.rows[si]
    }

    fn project(
        &self,
        q: nalgebra::DVectorView<f64>,
        v: nalgebra::DVectorView<f64>,
        z: nalgebra::DVectorView<f64>,
        wanted: Derivatives,
    ) -> Projection {
        let (nq, na, ns) = (self.nq(), self.n_aero(), self.ns);
        let want_jac = wanted != Derivatives::None;
        let want_all = wanted == Derivatives::All;
        let sized = |on: bool, r: usize, c: usize| {
            if on {
                DMatrix::zeros(r, c)
            } else {
                DMatrix::zeros(0, 0)
            }
        };
        let mut pr = Projection {
            force: DVector::zeros(nq),
            zdot: DVector::zeros(na),
            dq: sized(want_jac, nq, nq),
            dv: sized(want_all, nq, nq),
            dz: sized(want_jac, nq, na),
            gq: sized(want_all, na, nq),
            gv: sized(want_all, na, nq),
            gz: sized(want_all, na, na),
        };
        let mut eval = StripEval::new(ns);
        let mut zs = Vec::with_capacity(ns);
        for (si, s) in self.stations.iter().enumerate() {
            let [phi, u, edge] = self.deflection_at(si, q);
            let [phi_dot, u_dot, v_dot] = self.deflection_at(si, v);
            let k = Kinematics {
                phi,
                u,
                v: edge,
                phi_dot,
                u_dot,
                v_dot,
            };
            zs.clear();
            zs.extend(z.rows(si * ns, ns).iter());
            eval.clear();
            self.model.evaluate(s, &k, &zs, &mut eval, want_jac);
            let rows = self.kinematic_rows(si);
            let w = s.weight;
            for (load, row) in eval.loads.iter().zip(rows) {
                pr.force.axpy(w * load, row, 1.0);
            }
            pr.zdot.rows_mut(si * ns, ns).copy_from_slice(&eval.zdot);
            if !want_jac {
                continue;
            }
            for l in 0..LOADS {
                for j in 0..RATES {
                    let dpos = eval.dloads_dk[l][j];
                    if dpos != 0.0 {
                        pr.dq.ger(w * dpos, &rows[l], &rows[j], 1.0);
                    }
                    let drate = eval.dloads_dk[l][j + RATES];
                    if want_all && drate != 0.0 {
                        pr.dv.ger(w * drate, &rows[l], &rows[j], 1.0);
                    }
                }
                for i in 0..ns {
                    let mut col = pr.dz.column_mut(si * ns + i);
                    col.axpy(w * eval.dloads_dz[l][i], &rows[l], 1.0);
                }
            }
            if !want_all {
                continue;
            }
            for i in 0..ns {
                let r = si * ns + i;
                let d = eval.dzdot_dk[i];
                for (j, row) in rows.iter().enumerate() {
                    if d[j] != 0.0 {
                        let mut gq = pr.gq.row_mut(r);
                        gq += d[j] * row.transpose();
                    }
                    if d[j + RATES] != 0.0 {
                        let mut gv = pr.gv.row_mut(r);
                        gv += d[j + RATES] * row.transpose();
                    }
                }
                for j in 0..ns {
                    pr.gz[(r, si * ns + j)] = eval.dzdot_dz[i * ns + j];
                }
            }
        }
        pr
    }
}

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
        out.extend_from_slice(&self.deflection_at(si, x.rows(nq, nq)));
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

impl LinearSystem {
    /// Length of the state vector.
    pub fn dim(&self) -> usize {
        self.a.nrows()
    }
    /// Tip twist and flap of a state.
    pub fn tip(&self, x: &DVector<f64>) -> (f64, f64) {
        let q = x.rows(0, self.nq);
        (self.tip_twist.dot(&q), self.tip_flap.dot(&q))
    }
}

/// `(M − M_a)⁻¹`: the structure's mass with the strips' apparent mass `M_a` moved to the
/// left-hand side (docs/model.md §5, §12.5).
fn mass_inverse(
    structure: &dyn Structure,
    stations: &[Station],
    rows: &[[DVector<f64>; RATES]],
    model: &dyn StripModel,
) -> Result<DMatrix<f64>> {
    let mut mass = structure.mass().clone();
    for (s, rows) in stations.iter().zip(rows) {
        let ma = model.apparent_mass(s);
        for l in 0..LOADS {
            for j in 0..RATES {
                if ma[l][j] != 0.0 {
                    // Loads M_a q̈ move to the left-hand side: M − M_a.
                    mass.ger(-s.weight * ma[l][j], &rows[l], &rows[j], 1.0);
                }
            }
        }
    }
    check_finite("mass matrix", &mass)?;
    let mass_inv = mass.lu().try_inverse().ok_or_else(|| {
        Error::numerical("the mass matrix (structure plus apparent mass) is singular")
    })?;
    check_finite("inverse mass matrix", &mass_inv)?;
    Ok(mass_inv)
}

/// Every entry finite, or a numerical error naming the matrix.
pub fn check_finite(what: &str, m: &DMatrix<f64>) -> Result<()> {
    if m.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(Error::numerical(format!("{what} has non-finite entries")))
    }
}
