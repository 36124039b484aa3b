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
//!
//! Files: this one builds the system and evaluates it (state layout, right-hand side, Jacobian,
//! the strip projection); [`equilibrium`] solves the static equilibrium, [`linear`] linearises
//! about it, [`splitting`] separates the right-hand side for the time stepper; [`left_out`] holds
//! the modes a truncated basis leaves out, whose static response corrects the equilibrium.

mod equilibrium;
mod left_out;
mod linear;
mod splitting;

pub use linear::{Azimuthal, LinearSystem, TurningBlade};
pub use splitting::{RemainderScratch, Splitting};

use crate::error::{Error, Result};
use crate::physics::aero::{Kinematics, StripEval, StripModel, LOADS, RATES};
use crate::physics::inflow::Station;
use crate::physics::structure::Structure;
use left_out::{LeftOut, Offsets};
use nalgebra::{DMatrix, DVector};
use std::sync::Arc;

pub struct System {
    structure: Arc<dyn Structure>,
    stations: Vec<Station>,
    model: Arc<dyn StripModel>,
    /// The rows e_φ, e_u and e_v that map q to each strip's φ, u and v.
    rows: Arc<Vec<[DVector<f64>; RATES]>>,
    /// The same at the tip.
    tip_rows: [DVector<f64>; RATES],
    /// (M − M_a)⁻¹, factored once: every rhs and Jacobian needs it.
    mass_inv: DMatrix<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    /// [`Structure::static_load`], the centrifugal pull on a curved blade; `None` where it is
    /// zero (a straight blade), so such a blade's loads are not touched at all.
    static_load: Option<DVector<f64>>,
    /// States per station.
    ns: usize,
    /// The modes the structure's coordinates leave out, at the stations (docs/model.md §12.6).
    left_out: Option<Arc<LeftOut>>,
    /// Their static coordinates and motion, added to every position the strips and the
    /// outputs read; none until set ([`System::with_left_out_at`]).
    offsets: Option<Offsets>,
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

impl System {
    /// Build from an assembled structure, stations (along the structure's span) and a strip
    /// model.
    pub fn from_parts(
        structure: Arc<dyn Structure>,
        stations: Vec<Station>,
        model: Box<dyn StripModel>,
    ) -> Result<System> {
        System::with_model(structure, stations, Arc::from(model))
    }

    /// [`System::from_parts`] with a strip model shared with other systems.
    fn with_model(
        structure: Arc<dyn Structure>,
        stations: Vec<Station>,
        model: Arc<dyn StripModel>,
    ) -> Result<System> {
        let xs: Vec<f64> = stations.iter().map(|s| s.x).collect();
        let rows: Arc<Vec<_>> = Arc::new(
            structure
                .station_rows(&xs)
                .into_iter()
                .map(|r| [r.twist, r.flap, r.edge])
                .collect(),
        );
        let tip = structure.motion_rows(structure.length());
        let tip_rows = [tip.twist, tip.flap, tip.edge];
        let stiffness = structure.stiffness();
        check_finite("stiffness matrix", &stiffness)?;
        let damping = structure.damping().clone();
        check_finite("damping matrix", &damping)?;
        let static_load = structure.static_load();
        if !static_load.iter().all(|v| v.is_finite()) {
            return Err(Error::numerical(
                "non-finite centrifugal load on the curved blade",
            ));
        }
        let static_load = static_load.iter().any(|v| *v != 0.0).then_some(static_load);
        let mass_inv = mass_inverse(structure.as_ref(), &stations, &rows, model.as_ref())?;
        let ns = model.states_per_station();
        let left_out = LeftOut::of(structure.as_ref(), &stations)?.map(Arc::new);
        Ok(System {
            structure,
            stations,
            model,
            rows,
            tip_rows,
            mass_inv,
            stiffness,
            damping,
            static_load,
            ns,
            left_out,
            offsets: None,
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
            model: Arc::from(model),
            rows: Arc::clone(&self.rows),
            tip_rows: self.tip_rows.clone(),
            mass_inv,
            stiffness: self.stiffness.clone(),
            damping: self.damping.clone(),
            static_load: self.static_load.clone(),
            ns: self.ns,
            left_out: self.left_out.clone(),
            offsets: self.offsets.clone(),
        })
    }

    /// The same strips on `blades` blades of `rotor`, a structure whose coordinates hold this
    /// system's blade once per blade (docs/model.md §13.3): the stations repeated blade after
    /// blade, the strip model shared (it reads each station's section by its index, the same
    /// on every blade).
    pub fn on_rotor(&self, rotor: Arc<dyn Structure>, blades: usize) -> Result<System> {
        let stations: Vec<Station> = (0..blades)
            .flat_map(|_| self.stations.iter().cloned())
            .collect();
        System::with_model(rotor, stations, Arc::clone(&self.model))
    }

    /// The blade structure, shared.
    pub fn structure_arc(&self) -> Arc<dyn Structure> {
        Arc::clone(&self.structure)
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
        let [phi, u, _] = self.tip_motion(x);
        (phi, u)
    }

    /// `[φ, u, v]` (twist toward feather, flap downwind, edge toward the leading edge) at the
    /// tip's reference axis in state `x`, the left-out modes' static motion included.
    pub fn tip_motion(&self, x: &DVector<f64>) -> [f64; RATES] {
        let q = x.rows(0, self.nq());
        let offset = self.tip_offset();
        let mut motion = self.tip_rows.each_ref().map(|row| row.dot(&q));
        for (m, o) in motion.iter_mut().zip(offset) {
            *m += o;
        }
        motion
    }

    /// The left-out modes' static `[φ, u, v]` at the tip (zero without them).
    fn tip_offset(&self) -> [f64; RATES] {
        self.offsets.as_ref().map_or([0.0; RATES], |o| o.tip)
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
        let pr = self.project(q, v, z, Derivatives::None, 1.0);
        let mut out = DVector::zeros(self.dim());
        out.rows_mut(0, nq).copy_from(&v);
        let mut net = &pr.force - &self.stiffness * q - &self.damping * v;
        self.add_static_load(&mut net);
        out.rows_mut(nq, nq).copy_from(&(&self.mass_inv * net));
        out.rows_mut(2 * nq, self.n_aero()).copy_from(&pr.zdot);
        out
    }

    /// Adds the structure's own static load (the centrifugal pull on a curved blade) to a
    /// generalised force.
    fn add_static_load(&self, force: &mut DVector<f64>) {
        if let Some(f) = &self.static_load {
            *force += f;
        }
    }

    /// ∂ẋ/∂x at `x`, exact.
    pub fn jacobian(&self, x: &DVector<f64>) -> DMatrix<f64> {
        let (nq, na) = (self.nq(), self.n_aero());
        let (q, v, z) = self.split(x);
        let pr = self.project(q, v, z, Derivatives::All, 1.0);
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

    // ---- internals ----

    fn split<'a>(&self, x: &'a DVector<f64>) -> StateViews<'a> {
        let nq = self.nq();
        (x.rows(0, nq), x.rows(nq, nq), x.rows(2 * nq, self.n_aero()))
    }

    /// `[φ, u, v]` at station `si` for coordinates `q`, with the left-out modes' static motion.
    fn deflection_at(&self, si: usize, q: nalgebra::DVectorView<f64>) -> [f64; RATES] {
        self.position_at(si, q, 1.0)
    }

    /// [`System::deflection_at`] with the left-out modes' response to the strip loads scaled by
    /// `ramp`: the equilibrium's load continuation ramps it with the load.
    fn position_at(&self, si: usize, q: nalgebra::DVectorView<f64>, ramp: f64) -> [f64; RATES] {
        let mut d = self.rate_at(si, q);
        if let Some(o) = &self.offsets {
            for ((d, fixed), loaded) in d.iter_mut().zip(o.fixed[si]).zip(o.loaded[si]) {
                *d += fixed + ramp * loaded;
            }
        }
        d
    }

    /// `[φ̇, u̇, v̇]` at station `si` for coordinate rates `v` (the left-out modes are static).
    fn rate_at(&self, si: usize, v: nalgebra::DVectorView<f64>) -> [f64; RATES] {
        self.rows[si].each_ref().map(|row| row.dot(&v))
    }

    /// The strip kinematics at station `si` for coordinates `q` and their rates `v` (`ramp`:
    /// [`System::position_at`]).
    fn kinematics(
        &self,
        si: usize,
        q: nalgebra::DVectorView<f64>,
        v: nalgebra::DVectorView<f64>,
        ramp: f64,
    ) -> Kinematics {
        let [phi, u, edge] = self.position_at(si, q, ramp);
        let [phi_dot, u_dot, v_dot] = self.rate_at(si, v);
        Kinematics {
            phi,
            u,
            v: edge,
            phi_dot,
            u_dot,
            v_dot,
        }
    }

    /// Station `si`'s strip at coordinates, rates and aerodynamic states `(q, v, z)` (`ramp`:
    /// [`System::position_at`]), with its derivatives when `want_jac`.
    fn evaluate_station<'s>(
        &self,
        si: usize,
        (q, v, z): StateViews,
        ramp: f64,
        want_jac: bool,
        scratch: &'s mut StripScratch,
    ) -> &'s StripEval {
        let k = self.kinematics(si, q, v, ramp);
        scratch.z.clear();
        scratch.z.extend(z.rows(si * self.ns, self.ns).iter());
        scratch.eval.clear();
        let s = &self.stations[si];
        self.model
            .evaluate(s, &k, &scratch.z, &mut scratch.eval, want_jac);
        &scratch.eval
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
        ramp: f64,
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
        let mut scratch = StripScratch::new(ns);
        for (si, s) in self.stations.iter().enumerate() {
            let eval = self.evaluate_station(si, (q, v, z), ramp, want_jac, &mut scratch);
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

impl System {
    // ---- the truncated basis's static correction (docs/model.md §12.6) ----

    /// The left-out modes' static coordinates under the strip loads of state `x` and the
    /// structure's own static load, where the structure leaves modes out (docs/model.md §12.6).
    pub fn left_out_response(&self, x: &DVector<f64>) -> Option<DVector<f64>> {
        let left_out = self.left_out.as_deref()?;
        let (q, v, z) = self.split(x);
        let mut force = left_out.own_load();
        let mut scratch = StripScratch::new(self.ns);
        for (si, s) in self.stations.iter().enumerate() {
            let eval = self.evaluate_station(si, (q, v, z), 1.0, false, &mut scratch);
            left_out.add_strip(&mut force, si, s.weight, &eval.loads);
        }
        Some(left_out.coordinates(force))
    }

    /// This system with the left-out modes held at static coordinates `p` (from
    /// [`System::left_out_response`]); unchanged where the structure leaves none out.
    pub fn with_left_out_at(mut self, p: &DVector<f64>) -> System {
        if let Some(left_out) = self.left_out.as_deref() {
            debug_assert_eq!(p.len(), left_out.len());
            self.offsets = Some(left_out.offsets(p));
        }
        self
    }

    /// How many modes the structure leaves out (0 for a complete basis).
    pub fn left_out_count(&self) -> usize {
        self.left_out.as_deref().map_or(0, LeftOut::len)
    }

    /// `p` on the scale the operating point's passes compare (rad of twist or flap over the
    /// tip radius it gives at a station), and back.
    pub fn left_out_scaled(&self, p: &DVector<f64>) -> Vec<f64> {
        self.left_out
            .as_deref()
            .map_or_else(Vec::new, |l| l.scaled(p).iter().copied().collect())
    }
    pub fn left_out_unscaled(&self, scaled: &[f64]) -> DVector<f64> {
        self.left_out
            .as_deref()
            .map_or_else(|| DVector::zeros(0), |l| l.unscaled(scaled))
    }
}

/// The coordinates, their rates and the aerodynamic states of one state vector.
type StateViews<'a> = (
    nalgebra::DVectorView<'a, f64>,
    nalgebra::DVectorView<'a, f64>,
    nalgebra::DVectorView<'a, f64>,
);

/// What evaluating one station's strip at a time reuses.
struct StripScratch {
    eval: StripEval,
    z: Vec<f64>,
}

impl StripScratch {
    fn new(states: usize) -> StripScratch {
        StripScratch {
            eval: StripEval::new(states),
            z: Vec::with_capacity(states),
        }
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
