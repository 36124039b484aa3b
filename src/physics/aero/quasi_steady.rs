//! Quasi-steady strip aerodynamics: the paper's classical-flutter model (docs/model.md §5.1, Eq. 2).
//!
//! Inputs: the strip's rigid flow (`V0`, `ψ`, `α_r`), its twist `φ` and flap rate `u̇`.
//! Parameters: chord `c`, offset `e_a`, air density, lift slope `a0`, profile drag `C_D0`.
//! No states. Outputs:
//! `L = ½ρ V0² c a0 α_qs` with `α_qs = α_r − φ − u̇ cos ψ / V0`, `D = ½ρ V0² c C_D0`,
//! `f_u = L cos ψ + D sin ψ`, `m_φ = −e_a (L cos α_g + D sin α_g)`, `α_g = α_r − φ`.
//!
//! The lift is written as `½ρ c a0 (V0²(α_r − φ) − V0 u̇ cos ψ)` so that `V0 = 0` needs no
//! special case. The `cos α_g`, `sin α_g` projection makes the moment mildly nonlinear in `φ`;
//! the equilibrium solve handles that by Newton and the linearisation keeps its exact slope.

use super::{Kinematics, SteadyStates, StripEval, StripModel, StripSection};
use crate::physics::inflow::Station;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuasiSteady {
    pub section: StripSection,
}

impl QuasiSteady {
    pub fn new(section: StripSection) -> QuasiSteady {
        QuasiSteady { section }
    }

    /// Lift per span and its slopes with respect to φ and u̇.
    fn lift(&self, s: &Station, k: &Kinematics) -> (f64, f64, f64) {
        let sec = &self.section;
        let half_rho_c_a0 = 0.5 * sec.air_density * sec.chord * sec.lift_slope;
        let v2 = s.v0 * s.v0;
        let cos_psi = s.psi.cos();
        let lift = half_rho_c_a0 * (v2 * (s.alpha_r - k.phi) - s.v0 * k.u_dot * cos_psi);
        (lift, -half_rho_c_a0 * v2, -half_rho_c_a0 * s.v0 * cos_psi)
    }

    fn drag(&self, s: &Station) -> f64 {
        let sec = &self.section;
        0.5 * sec.air_density * s.v0 * s.v0 * sec.chord * sec.drag_coefficient
    }
}

impl StripModel for QuasiSteady {
    fn name(&self) -> &'static str {
        "quasi-steady"
    }

    fn states_per_station(&self) -> usize {
        0
    }

    fn evaluate(
        &self,
        s: &Station,
        k: &Kinematics,
        _z: &[f64],
        out: &mut StripEval,
        jacobian: bool,
    ) {
        let (lift, lift_phi, lift_udot) = self.lift(s, k);
        let drag = self.drag(s);
        let (sin_psi, cos_psi) = s.psi.sin_cos();
        let alpha_g = s.alpha_r - k.phi;
        let (sin_g, cos_g) = alpha_g.sin_cos();
        let ea = self.section.ea_offset;
        // The paper's blade has no edge motion: f_v and every edge slope stay zero.
        out.loads = [
            -ea * (lift * cos_g + drag * sin_g),
            lift * cos_psi + drag * sin_psi,
            0.0,
        ];
        if jacobian {
            // dα_g/dφ = −1, so d(cos α_g)/dφ = sin α_g and d(sin α_g)/dφ = −cos α_g.
            out.dloads_dk = [
                [
                    -ea * (lift_phi * cos_g + lift * sin_g - drag * cos_g),
                    0.0,
                    0.0,
                    0.0,
                    -ea * lift_udot * cos_g,
                    0.0,
                ],
                [lift_phi * cos_psi, 0.0, 0.0, 0.0, lift_udot * cos_psi, 0.0],
                [0.0; 6],
            ];
        }
    }

    fn steady_states(&self, _: &Station, _: [f64; 3], _: &mut SteadyStates) {}
}

#[cfg(test)]
mod tests {
    use super::super::test_support::{jacobian_mismatch, section, station};
    use super::*;

    #[test]
    fn jacobian_matches_central_differences() {
        let m = QuasiSteady::new(section());
        let k = Kinematics {
            phi: 0.03,
            u: 0.2,
            phi_dot: 0.4,
            u_dot: -0.7,
            ..Kinematics::default()
        };
        assert!(jacobian_mismatch(&m, &station(), k, &[]) < 1e-6);
    }

    #[test]
    fn lift_lowers_with_twist_toward_feather_and_downwind_flap_rate() {
        let m = QuasiSteady::new(section());
        let s = station();
        let mut e = StripEval::new(0);
        m.evaluate(&s, &Kinematics::default(), &[], &mut e, true);
        let f0 = e.loads[1];
        assert!(f0 > 0.0, "positive α_r pushes the blade downwind");
        assert!(e.dloads_dk[1][0] < 0.0 && e.dloads_dk[1][4] < 0.0);
        // e_a > 0: the lift's moment is nose-up (negative toward feather), destabilising.
        assert!(e.loads[0] < 0.0 && e.dloads_dk[0][0] > 0.0);
    }
}
