//! Unsteady attached-flow strip aerodynamics: Theodorsen's theory with R. T. Jones's two-lag
//! approximation of the lift-deficiency function (docs/model.md §5.2).
//!
//! Inputs: the strip's rigid flow (`V = V0`, `ψ`, `α_r`) and kinematics `φ, φ̇, u̇`; two states
//! `z1, z2` per strip. Parameters: chord, `e_a`, air density, lift slope `a0`.
//! In Theodorsen's variables `h = −u cos ψ` (down), `α_T = −φ` (nose-up), elastic axis `a = e_a/b − ½`
//! semichords aft of mid-chord:
//! - downwash at three-quarter chord `w = V(α_r − φ) − u̇ cos ψ − b(½ − a) φ̇`;
//! - lags `ż_i = −ε_i (V/b) z_i + w`, `w_eff = (1 − A1 − A2) w + (V/b)(A1 ε1 z1 + A2 ε2 z2)`;
//! - circulatory lift `L_c = ½ρ V c a0 w_eff`;
//! - non-circulatory `L_nc = πρb²(ḧ + V α̇_T − b a α̈_T)`,
//!   `M_T = πρb²(b a ḧ − V b(½ − a) α̇_T − b²(⅛ + a²) α̈_T) + b(a + ½) L_c`;
//! - outputs `f_u = (L_c + L_nc) cos ψ`, `m_φ = −M_T`.
//!
//! The `ḧ`, `α̈_T` (apparent-mass) terms are returned by [`StripModel::apparent_mass`]; the
//! velocity terms stay in the loads, so the linearisation puts them in the damping.

use super::{Kinematics, SteadyStates, StripEval, StripModel, StripSection};
use crate::physics::inflow::Station;
use std::f64::consts::PI;

/// Jones's indicial-lift coefficients `(A_i, ε_i)`.
pub const JONES: [(f64, f64); 2] = [(0.165, 0.0455), (0.335, 0.3)];

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Theodorsen {
    pub section: StripSection,
}

impl Theodorsen {
    pub fn new(section: StripSection) -> Theodorsen {
        Theodorsen { section }
    }

    /// Elastic-axis position `a` in semichords aft of mid-chord (the aerodynamic centre sits at
    /// the quarter chord, `a = −½`).
    pub fn elastic_axis(&self) -> f64 {
        self.section.ea_offset / self.section.semichord() - 0.5
    }

    /// Downwash at three-quarter chord and its slopes `∂w/∂[φ, u, v, φ̇, u̇, v̇]`.
    fn downwash(&self, s: &Station, k: &Kinematics) -> (f64, [f64; 6]) {
        let b = self.section.semichord();
        let arm = b * (0.5 - self.elastic_axis());
        let cos_psi = s.psi.cos();
        let w = s.v0 * (s.alpha_r - k.phi) - k.u_dot * cos_psi - arm * k.phi_dot;
        (w, [-s.v0, 0.0, 0.0, -arm, -cos_psi, 0.0])
    }
}

impl StripModel for Theodorsen {
    fn name(&self) -> &'static str {
        "theodorsen"
    }

    fn states_per_station(&self) -> usize {
        JONES.len()
    }

    fn apparent_mass(&self, s: &Station) -> [[f64; 3]; 3] {
        let sec = &self.section;
        let b = sec.semichord();
        let a = self.elastic_axis();
        let prb2 = PI * sec.air_density * b * b;
        let cos_psi = s.psi.cos();
        // ḧ = −ü cos ψ, α̈_T = −φ̈ substituted into L_nc and M_T, then f_u = L cos ψ, m_φ = −M_T.
        [
            [-prb2 * b * b * (0.125 + a * a), prb2 * b * a * cos_psi, 0.0],
            [prb2 * b * a * cos_psi, -prb2 * cos_psi * cos_psi, 0.0],
            [0.0; 3],
        ]
    }

    fn evaluate(
        &self,
        s: &Station,
        k: &Kinematics,
        z: &[f64],
        out: &mut StripEval,
        jacobian: bool,
    ) {
        let sec = &self.section;
        let b = sec.semichord();
        let a = self.elastic_axis();
        let v = s.v0;
        let rate = v / b;
        let cos_psi = s.psi.cos();
        let (w, dw) = self.downwash(s, k);
        let direct = 1.0 - JONES.iter().map(|(amp, _)| amp).sum::<f64>();
        let lagged: f64 = JONES
            .iter()
            .zip(z)
            .map(|((amp, eps), zi)| amp * eps * zi)
            .sum();
        let w_eff = direct * w + rate * lagged;
        let circ = 0.5 * sec.air_density * v * sec.chord * sec.lift_slope;
        let lift_c = circ * w_eff;
        let prb2 = PI * sec.air_density * b * b;
        // Velocity parts of the non-circulatory terms (α̇_T = −φ̇).
        let lift_nc = -prb2 * v * k.phi_dot;
        let moment_nc = prb2 * v * b * (0.5 - a) * k.phi_dot;
        let ea = sec.ea_offset; // = b(a + ½)
        out.loads = [
            -(moment_nc + ea * lift_c),
            (lift_c + lift_nc) * cos_psi,
            0.0,
        ];
        for (i, (_, eps)) in JONES.iter().enumerate() {
            out.zdot[i] = -eps * rate * z[i] + w;
        }
        if jacobian {
            let dlc_dk: [f64; 6] = std::array::from_fn(|j| circ * direct * dw[j]);
            let dlnc = [0.0, 0.0, 0.0, -prb2 * v, 0.0, 0.0];
            let dmnc = [0.0, 0.0, 0.0, prb2 * v * b * (0.5 - a), 0.0, 0.0];
            out.dloads_dk = [
                std::array::from_fn(|j| -(dmnc[j] + ea * dlc_dk[j])),
                std::array::from_fn(|j| (dlc_dk[j] + dlnc[j]) * cos_psi),
                [0.0; 6],
            ];
            for (i, (amp, eps)) in JONES.iter().enumerate() {
                let dlc_dz = circ * rate * amp * eps;
                out.dloads_dz[0][i] = -ea * dlc_dz;
                out.dloads_dz[1][i] = dlc_dz * cos_psi;
                out.dzdot_dk[i] = dw;
                for j in 0..JONES.len() {
                    out.dzdot_dz[i * JONES.len() + j] = if i == j { -eps * rate } else { 0.0 };
                }
            }
        }
    }

    /// `ż_i = 0` with no motion: `z_i = w b/(ε_i V) = b(α_r − φ)/ε_i`. Written without the
    /// division by V, so it is also the (irrelevant but finite) choice when V = 0.
    fn steady_states(&self, s: &Station, [phi, _, _]: [f64; 3], out: &mut SteadyStates) {
        let b = self.section.semichord();
        for (i, (_, eps)) in JONES.iter().enumerate() {
            out.z[i] = b * (s.alpha_r - phi) / eps;
            out.dz_dk[i] = [-b / eps, 0.0, 0.0];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{jacobian_mismatch, section, station};
    use super::super::SteadyStates;
    use super::*;

    #[test]
    fn jacobian_matches_central_differences() {
        let m = Theodorsen::new(section());
        let k = Kinematics {
            phi: 0.03,
            u: 0.2,
            phi_dot: 0.4,
            u_dot: -0.7,
            ..Kinematics::default()
        };
        assert!(jacobian_mismatch(&m, &station(), k, &[0.3, -0.1]) < 1e-6);
    }

    #[test]
    fn steady_states_recover_quasi_steady_lift() {
        // In steady flow C(k→0) = 1: w_eff = w and the circulatory lift is ½ρV²c a0 (α_r − φ).
        let sec = section();
        let m = Theodorsen::new(sec);
        let s = station();
        let phi = 0.02;
        let mut st = SteadyStates::new(2);
        m.steady_states(&s, [phi, 0.0, 0.0], &mut st);
        let mut e = StripEval::new(2);
        let k = Kinematics {
            phi,
            ..Kinematics::default()
        };
        m.evaluate(&s, &k, &st.z, &mut e, false);
        assert!(e.zdot.iter().all(|zd| zd.abs() < 1e-12));
        let lift =
            0.5 * sec.air_density * s.v0 * s.v0 * sec.chord * sec.lift_slope * (s.alpha_r - phi);
        assert!((e.loads[1] - lift * s.psi.cos()).abs() < 1e-9 * lift.abs());
        assert!((e.loads[0] + sec.ea_offset * lift).abs() < 1e-9 * lift.abs());
    }

    #[test]
    fn apparent_mass_is_symmetric_and_adds_inertia() {
        let m = Theodorsen::new(section());
        let ma = m.apparent_mass(&station());
        assert!(ma[2]
            .iter()
            .chain(ma.iter().map(|r| &r[2]))
            .all(|&v| v == 0.0));
        assert_eq!(ma[0][1], ma[1][0]);
        // Loads oppose accelerations: negative definite.
        assert!(ma[0][0] < 0.0 && ma[1][1] < 0.0);
        assert!(ma[0][0] * ma[1][1] - ma[0][1] * ma[1][0] > 0.0);
    }
}
