//! Blade-element strip loads on a real blade in three directions (docs/model.md §12.5): each
//! station's own chord, aerodynamic centre and polar, the steady inflow with its induction frozen,
//! and the section's flap, edge and twist motion.
//!
//! Inputs per station: the frozen inflow (`V0`, `ψ0` and `α_r` of the [`Station`]: axial
//! `U_a = V0 sin ψ0`, tangential `U_t = V0 cos ψ0`, built-in angle `θ0 = ψ0 − α_r`, pitch plus
//! aerodynamic twist), the kinematics `φ, u̇, v̇, φ̇` and the section's airfoil states.
//! - relative flow `U_a − u̇`, `U_t + v̇`: speed `W`, inflow angle `ψ = atan2(U_a − u̇, U_t + v̇)`;
//! - geometric angle of attack `α_g = ψ − θ0 − φ`; three-quarter-chord angle
//!   `α_¾ = α_g − d_¾ φ̇ / W` with `d_¾ = c/2 − d_ac` the distance from the reference axis aft
//!   to the three-quarter chord (`d_ac`: aerodynamic centre ahead of the reference axis);
//! - the section's airfoil model ([`super::airfoil`], chosen by [`Unsteadiness`]) gives
//!   `C_l, C_d, C_m` from `α_¾` and its states;
//! - `L = ½ρW²c C_l`, `D = ½ρW²c C_d`, `M_ac = ½ρW²c² C_m`;
//! - `f_u = L cos ψ + D sin ψ` (downwind), `f_v = L sin ψ − D cos ψ` (toward the leading edge:
//!   the in-plane terms are the edgewise aerodynamic damping), and toward feather
//!   `m_φ = −(M_ac + d_ac (L cos α_g + D sin α_g))`;
//! - every model adds the non-circulatory loads of §5.2 on the plunge normal to the inflow,
//!   `h = −(u cos ψ0 + v sin ψ0)`, with `α_T = −φ`: the velocity terms in the loads, the
//!   acceleration terms in [`StripModel::apparent_mass`] (quasi-steady is Theodorsen with
//!   `C(k) = 1`, as in Hodges & Pierce; without the pitch-rate term of `M_nc` the ¾-chord term
//!   alone would make the torsion of a blade whose axis lies aft of the quarter chord
//!   aerodynamically undamped).
//!
//! Exact partial derivatives come from forward-mode dual numbers (`num-dual`) through the same
//! code that evaluates the loads, so the state matrix is the Jacobian of the nonlinear right-hand
//! side by construction (tested against central differences).

pub use super::airfoil::hgm::{Hgm, HgmOverrides};
pub use super::airfoil::onera::StallDynamics;

use super::airfoil::jones::JonesAirfoil;
use super::airfoil::quasi_steady::QuasiSteadyAirfoil;
use super::airfoil::{AirfoilDynamics, SectionFlow, SteadyFlow};
use super::polar::Polar;
use super::{
    Kinematics, NonlinearSupport, SteadyStates, StripEval, StripModel, KINEMATICS, LOADS, RATES,
};
use crate::physics::inflow::Station;
use nalgebra::{Const, U1};
use num_dual::{DualNum, DualSVec64};
use std::f64::consts::PI;
use std::sync::Arc;

/// One station's aerodynamic section.
#[derive(Debug, Clone)]
pub struct ElementSection {
    /// Chord c (m).
    pub chord: f64,
    /// `d_ac`: the aerodynamic centre's distance ahead of the reference axis along the chord (m).
    pub ac_ahead: f64,
    pub polar: Arc<Polar>,
}

impl ElementSection {
    fn semichord(&self) -> f64 {
        0.5 * self.chord
    }
    /// Distance from the reference axis aft to the three-quarter chord (m).
    fn three_quarter_arm(&self) -> f64 {
        0.5 * self.chord - self.ac_ahead
    }
    /// Theodorsen's `a`: the reference axis in semichords aft of mid-chord.
    fn theodorsen_a(&self) -> f64 {
        self.ac_ahead / self.semichord() - 0.5
    }
}

/// The section's airfoil model on top of the polar (`aero.model`), one [`AirfoilDynamics`] each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unsteadiness {
    QuasiSteady,
    Theodorsen,
    Onera(StallDynamics),
    Hgm(Hgm),
}

/// Work done with whichever airfoil model an [`Unsteadiness`] names.
trait WithAirfoil {
    type Output;
    fn run<D: AirfoilDynamics>(self, dynamics: &D) -> Self::Output;
}

impl Unsteadiness {
    /// `work` on the airfoil model: the one place the models are named.
    fn visit<W: WithAirfoil>(&self, work: W) -> W::Output {
        match self {
            Unsteadiness::QuasiSteady => work.run(&QuasiSteadyAirfoil),
            Unsteadiness::Theodorsen => work.run(&JonesAirfoil),
            Unsteadiness::Onera(stall) => work.run(stall),
            Unsteadiness::Hgm(hgm) => work.run(hgm),
        }
    }

    /// The preset name of the model.
    pub fn name(&self) -> &'static str {
        struct Name;
        impl WithAirfoil for Name {
            type Output = &'static str;
            fn run<D: AirfoilDynamics>(self, d: &D) -> &'static str {
                d.name()
            }
        }
        self.visit(Name)
    }

    /// Airfoil states per station.
    pub fn states(&self) -> usize {
        struct States;
        impl WithAirfoil for States {
            type Output = usize;
            fn run<D: AirfoilDynamics>(self, d: &D) -> usize {
                d.states()
            }
        }
        self.visit(States)
    }

    fn nonlinear_in_time(&self) -> bool {
        struct Nonlinear;
        impl WithAirfoil for Nonlinear {
            type Output = bool;
            fn run<D: AirfoilDynamics>(self, d: &D) -> bool {
                d.nonlinear_in_time()
            }
        }
        self.visit(Nonlinear)
    }
}

/// Most airfoil states of any model (ONERA's).
const MAX_STATES: usize = 8;

#[derive(Debug, Clone)]
pub struct BladeElement {
    /// One per station, in station order ([`Station::index`]).
    pub sections: Vec<ElementSection>,
    pub air_density: f64,
    pub unsteadiness: Unsteadiness,
}

/// Inputs of one evaluation: `[φ, u, v, φ̇, u̇, v̇, z…]`.
const MAX_INPUTS: usize = KINEMATICS + MAX_STATES;

impl BladeElement {
    fn lag_states(&self) -> usize {
        self.unsteadiness.states()
    }

    /// Loads `[m_φ, f_u, f_v]` and state rates at `inputs = [φ, u, v, φ̇, u̇, v̇, z…]`, in any
    /// dual-number type (plain `f64` for values, dual vectors for partial derivatives).
    fn strip<T: DualNum<Primitive = f64> + Copy, D: AirfoilDynamics>(
        &self,
        dynamics: &D,
        s: &Station,
        inputs: &[T],
        zdot: &mut [T],
    ) -> [T; LOADS] {
        let sec = &self.sections[s.index];
        let [phi, _, _, phi_dot, u_dot, v_dot] = std::array::from_fn(|i| inputs[i]);
        let (sin0, cos0) = s.psi.sin_cos();
        let axial = T::from(s.v0 * sin0) - u_dot;
        let tangential = T::from(s.v0 * cos0) + v_dot;
        let w2 = axial * axial + tangential * tangential;
        let zero = T::from(0.0);
        if w2.re() <= 0.0 {
            // No relative flow (a parked blade in still air): no load; the states stay where
            // they are, as every rate scales with the flow speed.
            zdot.fill(zero);
            return [zero; LOADS];
        }
        let w = w2.sqrt();
        let psi = axial.atan2(tangential);
        let theta0 = s.psi - s.alpha_r;
        let alpha_g = psi - theta0 - phi;
        let alpha_34 = alpha_g - phi_dot * sec.three_quarter_arm() / w;
        let flow = SectionFlow {
            alpha: alpha_34,
            alpha_geometric: alpha_g,
            twist_rate: phi_dot,
            rate: s.v0 / sec.semichord(),
        };
        let [cl, cd, cm] = dynamics.coefficients(&sec.polar, &flow, &inputs[KINEMATICS..], zdot);
        let q = w2 * (0.5 * self.air_density * sec.chord);
        let (lift, drag, moment_ac) = (q * cl, q * cd, q * cm * sec.chord);
        let (sin_psi, cos_psi) = (psi.sin(), psi.cos());
        let normal = lift * alpha_g.cos() + drag * alpha_g.sin();
        let mut loads = [
            -(moment_ac + normal * sec.ac_ahead),
            lift * cos_psi + drag * sin_psi,
            lift * sin_psi - drag * cos_psi,
        ];
        // Velocity parts of the non-circulatory loads (α̇_T = −φ̇), on the frozen inflow.
        let b = sec.semichord();
        let a = sec.theodorsen_a();
        let prb2 = PI * self.air_density * b * b;
        let lift_nc = phi_dot * (-prb2 * s.v0);
        let moment_nc = phi_dot * (prb2 * s.v0 * b * (0.5 - a));
        loads[0] -= moment_nc;
        loads[1] += lift_nc * cos0;
        loads[2] += lift_nc * sin0;
        loads
    }

    /// Value and exact partials at `inputs`, through dual vectors of `N` = inputs.
    fn strip_with_partials<const N: usize, D: AirfoilDynamics>(
        &self,
        dynamics: &D,
        s: &Station,
        inputs: &[f64],
        out: &mut StripEval,
    ) {
        let duals: Vec<DualSVec64<N>> = inputs
            .iter()
            .enumerate()
            .map(|(i, &x)| DualSVec64::from_re(x).derivative(i))
            .collect();
        let mut zdot = [DualSVec64::<N>::from_re(0.0); MAX_STATES];
        let ns = self.lag_states();
        let loads = self.strip(dynamics, s, &duals, &mut zdot[..ns]);
        let gradient = |d: &DualSVec64<N>| d.eps.unwrap_generic(Const::<N>, U1);
        for (l, load) in loads.iter().enumerate() {
            out.loads[l] = load.re;
            let g = gradient(load);
            for j in 0..KINEMATICS {
                out.dloads_dk[l][j] = g[j];
            }
            for i in 0..ns {
                out.dloads_dz[l][i] = g[KINEMATICS + i];
            }
        }
        for (i, rate) in zdot.iter().take(ns).enumerate() {
            out.zdot[i] = rate.re;
            let g = gradient(rate);
            for j in 0..KINEMATICS {
                out.dzdot_dk[i][j] = g[j];
            }
            for k in 0..ns {
                out.dzdot_dz[i * ns + k] = g[KINEMATICS + k];
            }
        }
    }
}

/// [`StripModel::evaluate`] on the airfoil model.
struct Evaluate<'a> {
    model: &'a BladeElement,
    s: &'a Station,
    k: &'a Kinematics,
    z: &'a [f64],
    out: &'a mut StripEval,
    jacobian: bool,
}

impl WithAirfoil for Evaluate<'_> {
    type Output = ();
    fn run<D: AirfoilDynamics>(self, d: &D) {
        let Evaluate {
            model,
            s,
            k,
            z,
            out,
            jacobian,
        } = self;
        let ns = d.states();
        let mut inputs = [0.0; MAX_INPUTS];
        inputs[..KINEMATICS].copy_from_slice(&k.to_array());
        inputs[KINEMATICS..KINEMATICS + ns].copy_from_slice(&z[..ns]);
        if jacobian {
            let at = &inputs[..KINEMATICS + ns];
            match ns {
                0 => model.strip_with_partials::<KINEMATICS, D>(d, s, at, out),
                2 => model.strip_with_partials::<{ KINEMATICS + 2 }, D>(d, s, at, out),
                4 => model.strip_with_partials::<{ KINEMATICS + 4 }, D>(d, s, at, out),
                _ => model.strip_with_partials::<MAX_INPUTS, D>(d, s, &inputs, out),
            }
        } else {
            let mut zdot = [0.0; MAX_STATES];
            out.loads = model.strip(d, s, &inputs[..KINEMATICS + ns], &mut zdot[..ns]);
            out.zdot.copy_from_slice(&zdot[..ns]);
        }
    }
}

/// [`StripModel::steady_states`] on the airfoil model.
struct Steady<'a> {
    polar: &'a Polar,
    flow: SteadyFlow,
    out: &'a mut SteadyStates,
}

impl WithAirfoil for Steady<'_> {
    type Output = ();
    fn run<D: AirfoilDynamics>(self, d: &D) {
        let ns = d.states();
        let mut dz_dalpha = [0.0; MAX_STATES];
        d.steady_states(self.polar, self.flow, &mut self.out.z, &mut dz_dalpha[..ns]);
        // dα/dφ = −1.
        for (row, slope) in self.out.dz_dk.iter_mut().zip(&dz_dalpha[..ns]) {
            row[0] = 0.0 - slope;
        }
    }
}

impl StripModel for BladeElement {
    fn name(&self) -> &'static str {
        self.unsteadiness.name()
    }

    fn states_per_station(&self) -> usize {
        self.lag_states()
    }

    /// Theodorsen's apparent mass on the plunge normal to the frozen inflow and the twist.
    fn apparent_mass(&self, s: &Station) -> [[f64; RATES]; LOADS] {
        let sec = &self.sections[s.index];
        let b = sec.semichord();
        let a = sec.theodorsen_a();
        let prb2 = PI * self.air_density * b * b;
        let (sin0, cos0) = s.psi.sin_cos();
        // ḧ = −(ü cos ψ0 + v̈ sin ψ0), α̈_T = −φ̈ in L_nc and M_T; f = L_nc (cos ψ0, sin ψ0),
        // m_φ = −M_T.
        let plunge = [cos0, sin0];
        let mut ma = [[0.0; RATES]; LOADS];
        ma[0][0] = -prb2 * b * b * (0.125 + a * a);
        for (i, p) in plunge.iter().enumerate() {
            ma[0][1 + i] = prb2 * b * a * p;
            ma[1 + i][0] = prb2 * b * a * p;
            for (j, q) in plunge.iter().enumerate() {
                ma[1 + i][1 + j] = -prb2 * p * q;
            }
        }
        ma
    }

    fn evaluate(&self, s: &Station, k: &Kinematics, z: &[f64], out: &mut StripEval, jac: bool) {
        self.unsteadiness.visit(Evaluate {
            model: self,
            s,
            k,
            z,
            out,
            jacobian: jac,
        });
    }

    /// `ż = 0` with no motion at `α = α_r − φ`, as the airfoil model holds still there.
    fn steady_states(&self, s: &Station, [phi, _, _]: [f64; RATES], out: &mut SteadyStates) {
        out.z.fill(0.0);
        out.dz_dk.fill([0.0; RATES]);
        if s.v0 <= 0.0 {
            return;
        }
        let sec = &self.sections[s.index];
        let flow = SteadyFlow {
            alpha: s.alpha_r - phi,
            semichord: sec.semichord(),
            speed: s.v0,
        };
        self.unsteadiness.visit(Steady {
            polar: &sec.polar,
            flow,
            out,
        });
    }

    /// A model simulated as what it is reads the twist and the rates of every station and all
    /// its states, and writes every load and rate: the relative flow's speed and angle make
    /// nothing of the strip affine.
    fn nonlinear_support(&self) -> NonlinearSupport {
        if !self.unsteadiness.nonlinear_in_time() {
            return NonlinearSupport::default();
        }
        let ns = self.lag_states();
        let mut inputs = vec![
            NonlinearSupport::TWIST,
            NonlinearSupport::TWIST_RATE,
            NonlinearSupport::FLAP_RATE,
            NonlinearSupport::EDGE_RATE,
        ];
        inputs.extend((0..ns).map(|i| NonlinearSupport::FIRST_STATE + i));
        let outputs = (0..LOADS + ns).collect();
        NonlinearSupport { inputs, outputs }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{jacobian_mismatch, station};
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use std::ops::SubAssign;

    fn model(unsteadiness: Unsteadiness) -> BladeElement {
        // A cambered thin airfoil that stalls at 10°, with a nose-down moment.
        let alpha: Vec<f64> = (-30..=30).map(|d| (d as f64).to_radians()).collect();
        let cl = alpha
            .iter()
            .map(|&a| 2.0 * PI * (a.clamp(-0.17, 0.17) + 0.03) - 2.0 * (a.abs() - 0.17).max(0.0))
            .collect();
        let cd = alpha.iter().map(|a| 0.008 + 0.5 * a * a).collect();
        let cm = alpha.iter().map(|a| -0.08 - 0.05 * a).collect();
        let polar = Arc::new(Polar::new(alpha, cl, cd, cm, "test").unwrap());
        BladeElement {
            sections: vec![ElementSection {
                chord: 0.5,
                ac_ahead: 0.06,
                polar,
            }],
            air_density: 1.225,
            unsteadiness,
        }
    }

    fn moving() -> Kinematics {
        Kinematics {
            phi: 0.03,
            u: 0.2,
            v: -0.1,
            phi_dot: 0.4,
            u_dot: -0.7,
            v_dot: 1.3,
        }
    }

    #[test]
    fn partials_match_central_differences() {
        let qs = model(Unsteadiness::QuasiSteady);
        assert!(jacobian_mismatch(&qs, &station(), moving(), &[]) < 1e-6);
        let th = model(Unsteadiness::Theodorsen);
        assert!(jacobian_mismatch(&th, &station(), moving(), &[0.01, -0.02]) < 1e-6);
    }

    fn onera() -> Unsteadiness {
        Unsteadiness::Onera(StallDynamics {
            a: [0.3, 0.25, 0.25],
            r: [0.0324, 0.0484, 0.0484],
        })
    }

    #[test]
    fn onera_partials_match_central_differences_in_stall() {
        let m = model(onera());
        let mut s = station();
        for alpha_r in [0.05, 0.25] {
            s.alpha_r = alpha_r;
            let z = [0.01, -0.02, -0.3, 0.5, 0.01, -0.2, 0.04, 0.3];
            let worst = jacobian_mismatch(&m, &s, moving(), &z);
            assert!(worst < 1e-6, "α_r {alpha_r}: {worst:e}");
        }
    }

    #[test]
    fn steady_states_recover_quasi_steady_loads_attached_and_stalled() {
        let qs = model(Unsteadiness::QuasiSteady);
        let mut s = station();
        for alpha_r in [0.05, 0.25] {
            s.alpha_r = alpha_r;
            for unsteady in [
                Unsteadiness::Theodorsen,
                onera(),
                Unsteadiness::Hgm(Hgm::default()),
            ] {
                let m = model(unsteady);
                let ns = m.states_per_station();
                let k = Kinematics {
                    phi: 0.02,
                    ..Kinematics::default()
                };
                let mut st = SteadyStates::new(ns);
                m.steady_states(&s, [k.phi, 0.0, 0.0], &mut st);
                let (mut a, mut b) = (StripEval::new(0), StripEval::new(ns));
                qs.evaluate(&s, &k, &[], &mut a, false);
                m.evaluate(&s, &k, &st.z, &mut b, false);
                assert!(
                    b.zdot.iter().all(|r| r.abs() < 1e-9),
                    "{unsteady:?}: {:?}",
                    b.zdot
                );
                for l in 0..LOADS {
                    let scale = a.loads[l].abs().max(1.0);
                    assert!(
                        (a.loads[l] - b.loads[l]).abs() <= 1e-12 * scale,
                        "{unsteady:?}"
                    );
                }
                // The steady states' slope in φ, against central differences.
                let h = 1e-6;
                let at = |phi: f64| {
                    let mut o = SteadyStates::new(ns);
                    m.steady_states(&s, [phi, 0.0, 0.0], &mut o);
                    o.z
                };
                let (p, q) = (at(k.phi + h), at(k.phi - h));
                for i in 0..ns {
                    let numeric = (p[i] - q[i]) / (2.0 * h);
                    assert!((st.dz_dk[i][0] - numeric).abs() <= 1e-6 * numeric.abs().max(1.0));
                }
            }
        }
    }

    #[test]
    fn hgm_partials_match_central_differences_attached_around_stall_and_deep() {
        let m = model(Unsteadiness::Hgm(Hgm::default()));
        let polar = Arc::clone(&m.sections[0].polar);
        let mut s = station();
        // The test polar stalls at 0.17 rad; at 0.4 its separation point is below 1 %, where the
        // separation drag's roots continue as tangents.
        for alpha_r in [0.05, 0.21, 0.4] {
            s.alpha_r = alpha_r;
            let f = polar.separation(alpha_r).f;
            let x3 = polar.attached().lift(alpha_r) + 0.05;
            let z = [
                0.165 * alpha_r + 0.004,
                0.335 * alpha_r - 0.003,
                x3,
                0.9 * f + 0.003,
            ];
            let worst = jacobian_mismatch(&m, &s, moving(), &z);
            eprintln!("hgm partials at α_r {alpha_r} (f_st {f:.4}): {worst:e}");
            assert!(worst < 1e-6, "α_r {alpha_r} (f_st {f}): {worst:e}");
        }
    }

    /// A section on pitch, flap and edge springs: its state matrix about zero deflection with the
    /// first `keep` airfoil states (the others held at `z0`).
    fn section_matrix(m: &BladeElement, s: &Station, z0: &[f64], keep: usize) -> DMatrix<f64> {
        let ns = m.states_per_station();
        let mut e = StripEval::new(ns);
        m.evaluate(s, &Kinematics::default(), z0, &mut e, true);
        let mass = DMatrix::from_diagonal(&DVector::from_vec(vec![0.3, 20.0, 20.0]));
        let stiffness = DMatrix::from_diagonal(&DVector::from_vec(vec![3000.0, 2000.0, 8000.0]));
        let ma = m.apparent_mass(s);
        let effective = mass - DMatrix::from_fn(3, 3, |i, j| ma[i][j]);
        let inv = effective.try_inverse().unwrap();
        let n = 6 + keep;
        let mut forces = DMatrix::zeros(3, n);
        for l in 0..LOADS {
            for j in 0..KINEMATICS {
                forces[(l, j)] = e.dloads_dk[l][j];
            }
            for j in 0..keep {
                forces[(l, 6 + j)] = e.dloads_dz[l][j];
            }
        }
        forces.view_mut((0, 0), (3, 3)).sub_assign(&stiffness);
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 3), (3, 3)).fill_with_identity();
        a.view_mut((3, 0), (3, n)).copy_from(&(inv * forces));
        for i in 0..keep {
            for j in 0..KINEMATICS {
                a[(6 + i, j)] = e.dzdot_dk[i][j];
            }
            for j in 0..keep {
                a[(6 + i, 6 + j)] = e.dzdot_dz[i * ns + j];
            }
        }
        a
    }

    fn sorted_eigenvalues(a: DMatrix<f64>) -> Vec<nalgebra::Complex<f64>> {
        let mut v: Vec<_> = a.complex_eigenvalues().iter().copied().collect();
        v.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        v
    }

    #[test]
    fn hgm_attached_with_its_separation_frozen_is_theodorsen() {
        // Jones's constants (HGM's published ones), attached flow at zero mean lift, where the
        // lag's tilt of the lift into drag has no first-order part; the separation point held
        // at attached flow and the pressure lag (which only drives it) left out.
        let hgm = model(Unsteadiness::Hgm(Hgm::default()));
        let jones = model(Unsteadiness::Theodorsen);
        let mut s = station();
        s.alpha_r = hgm.sections[0].polar.attached().zero_lift;
        let steady = |m: &BladeElement| {
            let mut st = SteadyStates::new(m.states_per_station());
            m.steady_states(&s, [0.0; 3], &mut st);
            st.z
        };
        let z_hgm = steady(&hgm);
        assert!((z_hgm[3] - 1.0).abs() < 1e-12, "attached: f = {}", z_hgm[3]);
        let a = sorted_eigenvalues(section_matrix(&hgm, &s, &z_hgm, 2));
        let b = sorted_eigenvalues(section_matrix(&jones, &s, &steady(&jones), 2));
        assert_eq!(a.len(), b.len());
        let mut worst: f64 = 0.0;
        for (x, y) in a.iter().zip(&b) {
            worst = worst.max((x - y).norm() / y.norm());
        }
        eprintln!("hgm attached, frozen separation, against theodorsen: {worst:e}");
        assert!(worst < 1e-7, "{worst:e}: {a:?} against {b:?}");
        // Not by accident: the separated lift changes them.
        let separated = [z_hgm[0], z_hgm[1], z_hgm[2], 0.5];
        let c = sorted_eigenvalues(section_matrix(&hgm, &s, &separated, 2));
        assert!(c
            .iter()
            .zip(&b)
            .any(|(x, y)| (x - y).norm() > 1e-3 * y.norm()));
    }

    #[test]
    fn in_plane_motion_is_damped_and_lift_drives_the_rotor() {
        let m = model(Unsteadiness::QuasiSteady);
        let s = station();
        let mut e = StripEval::new(0);
        m.evaluate(&s, &Kinematics::default(), &[], &mut e, true);
        // Positive α_r: lift downwind and forward (the torque that turns the rotor).
        assert!(e.loads[1] > 0.0 && e.loads[2] > 0.0);
        // Downwind motion lowers the angle of attack (flap damping); edge damping from the
        // in-plane force growing against in-plane motion.
        assert!(e.dloads_dk[1][4] < 0.0);
        assert!(e.dloads_dk[2][5] < 0.0);
    }

    #[test]
    fn apparent_mass_is_symmetric_and_negative_definite() {
        let m = model(Unsteadiness::QuasiSteady);
        let ma = nalgebra::Matrix3::from_fn(|i, j| m.apparent_mass(&station())[i][j]);
        assert_eq!(ma, ma.transpose());
        // Rank two: plunge normal to the inflow and twist; in-flow motion adds no mass.
        let eig = ma.symmetric_eigenvalues();
        assert_eq!(eig.iter().filter(|&&v| v < -1e-12).count(), 2);
        assert!(eig.iter().all(|&v| v < 1e-12));
    }
}
