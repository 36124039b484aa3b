//! `aero.model = "onera"` as the system's strip model: either form of docs/model.md §5.3 on every
//! station.

use super::*;
use crate::physics::aero::{
    Kinematics, NonlinearSupport, SteadyStates, StripEval, StripModel, StripSection,
};
use crate::physics::inflow::Station;

/// `aero.model = "onera"` as a [`StripModel`]: either form of docs/model.md §5.3 on every station.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OneraModel {
    pub section: StripSection,
    pub coefficients: Coefficients,
    pub forcing: OneraForcing,
}

impl OneraModel {
    pub fn new(section: StripSection, coefficients: Coefficients, forcing: OneraForcing) -> Self {
        OneraModel {
            section,
            coefficients,
            forcing,
        }
    }

    /// One station's flow and geometry in this module's terms.
    pub fn strip(&self, s: &Station) -> Strip {
        Strip {
            air_density: self.section.air_density,
            v0: s.v0,
            psi: s.psi,
            alpha_r: s.alpha_r,
            chord: self.section.chord,
            ea_offset: self.section.ea_offset,
        }
    }

    /// The interface's kinematics as a strip motion, apparent mass excluded (the system keeps
    /// it in its mass matrix).
    fn motion(k: &Kinematics) -> Motion {
        Motion {
            twist: k.phi,
            twist_rate: k.phi_dot,
            flap_rate: k.u_dot,
            ..Motion::default()
        }
    }

    fn evaluate_rigid(
        &self,
        strip: &Strip,
        k: &Kinematics,
        z: &[f64],
        out: &mut StripEval,
        jac: bool,
    ) {
        let s: [f64; rigid::STATES] = state_array(z);
        let c = &self.coefficients;
        let loads = rigid::loads(c, strip, k.phi, &s);
        out.loads = [loads.twist, loads.flap, 0.0];
        out.zdot.copy_from_slice(&rigid::rates(c, strip, &s));
        if !jac {
            return;
        }
        let p = rigid::load_partials(c, strip, k.phi, &s);
        write_load_partials(&p, out);
        // The states never see the structure: ∂ż/∂[φ, u, v, φ̇, u̇, v̇] stays zero.
        write_rate_jacobian(&rigid::rate_jacobian(c, strip), out);
    }

    fn evaluate_coupled(
        &self,
        strip: &Strip,
        k: &Kinematics,
        z: &[f64],
        out: &mut StripEval,
        jac: bool,
    ) {
        let s: [f64; coupled::STATES] = state_array(z);
        let c = &self.coefficients;
        let motion = Self::motion(k);
        let w = coupled::downwash(strip, &motion);
        let loads = coupled::loads(c, strip, &motion, &s);
        out.loads = [loads.twist, loads.flap, 0.0];
        out.zdot.copy_from_slice(&coupled::rates(c, strip, w, &s));
        if !jac {
            return;
        }
        let p = coupled::load_partials(c, strip, &motion, &s);
        write_load_partials(&p, out);
        let dw = coupled::downwash_partials(strip);
        let dw_dk = [dw.twist, 0.0, 0.0, dw.twist_rate, dw.flap_rate, 0.0];
        let dzdot_dw = coupled::rate_downwash_partial(c, strip, w);
        for (row, d) in out.dzdot_dk.iter_mut().zip(dzdot_dw) {
            *row = dw_dk.map(|g| d * g);
        }
        write_rate_jacobian(&coupled::rate_jacobian(c, strip), out);
    }
}

/// The interface's state slice as this form's fixed-size array.
fn state_array<const S: usize>(z: &[f64]) -> [f64; S] {
    let mut s = [0.0; S];
    s.copy_from_slice(&z[..S]);
    s
}

/// Load partials into the interface's layout: loads `[m_φ, f_u, f_v]`, kinematics
/// `[φ, u, v, φ̇, u̇, v̇]` (the paper's blade has no edge motion: those entries stay zero).
fn write_load_partials<const S: usize>(p: &LoadPartials<S>, out: &mut StripEval) {
    let none = Loads::default();
    let by_kinematics = [p.twist, none, none, p.twist_rate, p.flap_rate, none];
    out.dloads_dk = [
        by_kinematics.map(|l| l.twist),
        by_kinematics.map(|l| l.flap),
        [0.0; 6],
    ];
    for (j, l) in p.states.iter().enumerate() {
        out.dloads_dz[0][j] = l.twist;
        out.dloads_dz[1][j] = l.flap;
    }
}

fn write_rate_jacobian<const S: usize>(jac: &[[f64; S]; S], out: &mut StripEval) {
    for (i, row) in jac.iter().enumerate() {
        out.dzdot_dz[i * S..(i + 1) * S].copy_from_slice(row);
    }
}

impl StripModel for OneraModel {
    fn name(&self) -> &'static str {
        "onera"
    }

    fn states_per_station(&self) -> usize {
        states_per_station(self.forcing)
    }

    /// The coupled form carries Theodorsen's apparent mass (§5.2); the rigid form has none.
    fn apparent_mass(&self, s: &Station) -> [[f64; 3]; 3] {
        match self.forcing {
            OneraForcing::Rigid => [[0.0; 3]; 3],
            OneraForcing::Coupled => {
                let strip = self.strip(s);
                let z = [0.0; coupled::STATES];
                let p = coupled::load_partials(&self.coefficients, &strip, &Motion::default(), &z);
                [
                    [p.twist_accel.twist, p.flap_accel.twist, 0.0],
                    [p.twist_accel.flap, p.flap_accel.flap, 0.0],
                    [0.0; 3],
                ]
            }
        }
    }

    fn evaluate(
        &self,
        s: &Station,
        k: &Kinematics,
        z: &[f64],
        out: &mut StripEval,
        jacobian: bool,
    ) {
        let strip = self.strip(s);
        match self.forcing {
            OneraForcing::Rigid => self.evaluate_rigid(&strip, k, z, out, jacobian),
            OneraForcing::Coupled => self.evaluate_coupled(&strip, k, z, out, jacobian),
        }
    }

    /// Coupled: the stall deviations read `α = w/V0` (`φ, φ̇, u̇`) and drive the three stall
    /// rates; the drag's arm `e_a D sin α_g` makes `m_φ` bilinear in `C2D` and `sin(α_r − φ)`.
    /// Rigid: the stall forcing is constant (`α_r`); only `m_φ` is nonlinear, through
    /// `e_a (L cos α_g + D sin α_g)` with `L` from `C1L + C2L` and `D` from `C2D`. Everything
    /// else (the attached flow, `f_u`, the lags) is affine with constant coefficients.
    fn nonlinear_support(&self) -> NonlinearSupport {
        let state = |i: usize| NonlinearSupport::FIRST_STATE + i;
        let rate = |i: usize| NonlinearSupport::FIRST_RATE + i;
        match self.forcing {
            OneraForcing::Coupled => NonlinearSupport {
                inputs: vec![
                    NonlinearSupport::TWIST,
                    NonlinearSupport::TWIST_RATE,
                    NonlinearSupport::FLAP_RATE,
                    state(coupled::STALL + 4),
                ],
                outputs: vec![
                    NonlinearSupport::TWIST_LOAD,
                    rate(coupled::STALL + 1),
                    rate(coupled::STALL + 3),
                    rate(coupled::STALL + 5),
                ],
            },
            OneraForcing::Rigid => NonlinearSupport {
                inputs: vec![
                    NonlinearSupport::TWIST,
                    state(rigid::C1L),
                    state(rigid::STALL),
                    state(rigid::STALL + 4),
                ],
                outputs: vec![NonlinearSupport::TWIST_LOAD],
            },
        }
    }

    /// Rigid: the states settle on `α_r` whatever the deflection. Coupled: on the static
    /// downwash `w = V0(α_r − φ)`, so they move with the twist.
    fn steady_states(&self, s: &Station, [phi, _, _]: [f64; 3], out: &mut SteadyStates) {
        let strip = self.strip(s);
        let c = &self.coefficients;
        match self.forcing {
            OneraForcing::Rigid => {
                out.z.copy_from_slice(&rigid::steady(c, &strip));
                out.dz_dk.fill([0.0; 3]);
            }
            OneraForcing::Coupled => {
                let w = coupled::downwash(
                    &strip,
                    &Motion {
                        twist: phi,
                        ..Motion::default()
                    },
                );
                out.z.copy_from_slice(&coupled::steady(c, &strip, w));
                let dw_dphi = -strip.v0;
                for (row, d) in out
                    .dz_dk
                    .iter_mut()
                    .zip(coupled::steady_downwash_partial(c, &strip, w))
                {
                    *row = [d * dw_dphi, 0.0, 0.0];
                }
            }
        }
    }
}
