//! `hgm`: the Hansen–Gaunaa–Madsen dynamic-stall model on a real blade's section (docs/model.md
//! §12.8; M. H. Hansen, M. Gaunaa, H. Aa. Madsen, Risø-R-1354, 2004; OpenFAST AeroDyn's
//! `UA_Mod = 4`).
//!
//! States `[x1, x2, x3, x4]`, all on the reduced-time rate `1/T_u = V0/b`:
//! - attached-flow lags (Jones's indicial form): `ẋ_i = b_i (V0/b)(A_i α_¾ − x_i)`, effective
//!   angle `α_E = (1 − A1 − A2) α_¾ + x1 + x2`;
//! - the lagged pressure lift: `ẋ3 = (C_l,p − x3)/T_p` with `C_l,p = a0 (α_E − α0) + π T_u ω`
//!   (`ω = −φ̇`, nose-up), `T_p = τ_p T_u`; its angle `α_F = x3/a0 + α0`;
//! - the lagged separation point: `ẋ4 = (f_st(α_F) − x4)/T_f`, `T_f = τ_f T_u`, with `f_st` the
//!   polar's own Kirchhoff separation point ([`Polar::separation`]).
//!
//! Coefficients, in the rearranged form that returns the polar exactly wherever `x4 = f_st(α_E)`
//! (also where `f_st` is held at 1 above the attached line):
//! - `C_l = C_l,st(α_E) + (a0 (α_E − α0) − C_l,fs(α_E)) (x4 − f_st(α_E))`, which is the
//!   published `x4 a0 (α_E − α0) + (1 − x4) C_l,fs(α_E)` wherever Kirchhoff's relation holds;
//! - `C_d = C_d,st(α_E) + (α_g − α_E) C_l + (C_d,st(α_E) − C_d,st(α0)) ΔC_d''`,
//!   `ΔC_d'' = (√f_st(α_E) − √x4)/2 − (f_st(α_E) − x4)/4`: the lift tilted by the lag, and the
//!   separation drag;
//! - `C_m = C_m,st(α_E)` about the aerodynamic centre.
//!
//! The non-circulatory terms of the model's lift and moment (`π T_u ω`, `−π T_u ω/2`) are §5.2's
//! velocity terms, which the strip adds for every model; the pressure lag reads its own.
//! The square roots of `ΔC_d''` continue as their tangent below `f = 0.01`, so that deep stall
//! (`x4 → 0`, where `√x4` has no derivative) can be linearised; at the steady state both roots
//! are equal and the drag is the polar's.

use super::{carried, polar_coefficients, AirfoilDynamics, SectionFlow, SteadyFlow};
use crate::physics::aero::polar::{Polar, UnsteadyConstants};
use nalgebra::{Const, U1};
use num_dual::{DualNum, DualSVec64};
use std::f64::consts::PI;

/// The published constants (Hansen et al. 2004; HAWC2's): Jones's flat-plate indicial
/// response, `τ_p = 1.5`, `τ_f = 6`. A polar whose file gives none (a HAWC2 pc file) runs on
/// these.
pub const PUBLISHED: UnsteadyConstants = UnsteadyConstants {
    a1: 0.165,
    a2: 0.335,
    b1: 0.0455,
    b2: 0.3,
    tau_p: 1.5,
    tau_f: 6.0,
};

/// `aero.hgm.*`: constants set for every section, `None` where each polar's own (its file's,
/// else [`PUBLISHED`]) hold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HgmOverrides {
    pub a1: Option<f64>,
    pub a2: Option<f64>,
    pub b1: Option<f64>,
    pub b2: Option<f64>,
    pub tau_p: Option<f64>,
    pub tau_f: Option<f64>,
}

/// The model, with the constants set for every section.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Hgm {
    pub overrides: HgmOverrides,
}

/// Below this the square roots of `ΔC_d''` continue as their tangent.
const ROOT_FLOOR: f64 = 0.01;

fn root<T: DualNum<Primitive = f64> + Copy>(x: T) -> T {
    if x.re() >= ROOT_FLOOR {
        x.sqrt()
    } else {
        let r = ROOT_FLOOR.sqrt();
        (x - ROOT_FLOOR) * (0.5 / r) + r
    }
}

/// `[f_st, C_l,fs]` of `polar` at `alpha`, carried to every input through α's derivative.
fn separation<T: DualNum<Primitive = f64> + Copy>(polar: &Polar, alpha: T) -> [T; 2] {
    let s = polar.separation(alpha.re());
    [carried(alpha, s.f, s.df), carried(alpha, s.cl_fs, s.dcl_fs)]
}

impl Hgm {
    /// The constants a section with `polar` runs on: the preset's where set, else the polar's
    /// file's, else [`PUBLISHED`].
    pub fn constants(&self, polar: &Polar) -> UnsteadyConstants {
        let own = polar.unsteady().map_or(PUBLISHED, |b| b.constants);
        let o = &self.overrides;
        UnsteadyConstants {
            a1: o.a1.unwrap_or(own.a1),
            a2: o.a2.unwrap_or(own.a2),
            b1: o.b1.unwrap_or(own.b1),
            b2: o.b2.unwrap_or(own.b2),
            tau_p: o.tau_p.unwrap_or(own.tau_p),
            tau_f: o.tau_f.unwrap_or(own.tau_f),
        }
    }

    /// `Ok` when the constants a section with `polar` runs on are in range, else what is wrong
    /// and where the constants came from.
    pub fn check(&self, polar: &Polar) -> std::result::Result<(), String> {
        self.constants(polar).check().map_err(|e| {
            let from = polar.unsteady().map_or_else(
                || "the published defaults".to_string(),
                |b| format!("the dynamic-stall block of {}", b.origin),
            );
            format!("{e} (aero.hgm.* where set, else {from})")
        })
    }

    /// `α_F = x3/a0 + α0`; α0 itself on a section that lifts nowhere.
    fn separation_angle<T: DualNum<Primitive = f64> + Copy>(polar: &Polar, x3: T) -> T {
        let line = polar.attached();
        if line.slope > 0.0 {
            x3 / line.slope + line.zero_lift
        } else {
            T::from(line.zero_lift)
        }
    }
}

impl AirfoilDynamics for Hgm {
    fn name(&self) -> &'static str {
        "hgm"
    }

    fn states(&self) -> usize {
        4
    }

    fn coefficients<T: DualNum<Primitive = f64> + Copy>(
        &self,
        polar: &Polar,
        flow: &SectionFlow<T>,
        z: &[T],
        zdot: &mut [T],
    ) -> [T; 3] {
        let k = self.constants(polar);
        let line = polar.attached();
        let rate = flow.rate;
        let [x1, x2, x3, x4] = [z[0], z[1], z[2], z[3]];
        zdot[0] = (flow.alpha * k.a1 - x1) * (k.b1 * rate);
        zdot[1] = (flow.alpha * k.a2 - x2) * (k.b2 * rate);
        let alpha_e = flow.alpha * (1.0 - k.a1 - k.a2) + x1 + x2;
        let cl_inv = (alpha_e - line.zero_lift) * line.slope;
        // π T_u ω, with T_u = b/V0 and ω = −φ̇; no flow, no reduced time.
        let pressure = if rate > 0.0 {
            cl_inv - flow.twist_rate * (PI / rate)
        } else {
            cl_inv
        };
        zdot[2] = (pressure - x3) * (rate / k.tau_p);
        let [f_lagged, _] = separation(polar, Self::separation_angle(polar, x3));
        zdot[3] = (f_lagged - x4) * (rate / k.tau_f);

        let [cl_st, cd_st, cm_st] = polar_coefficients(polar, alpha_e);
        let [f_e, cl_fs] = separation(polar, alpha_e);
        let cl = cl_st + (cl_inv - cl_fs) * (x4 - f_e);
        let cd0 = polar.at(line.zero_lift).cd;
        let separation_drag = (root(f_e) - root(x4)) * 0.5 - (f_e - x4) * 0.25;
        let cd = cd_st + (flow.alpha_geometric - alpha_e) * cl + (cd_st - cd0) * separation_drag;
        [cl, cd, cm_st]
    }

    /// `x_i = A_i α`, `x3 = a0 (α − α0)`, `x4 = f_st(α_F)` with `α_F` from that `x3`.
    fn steady_states(&self, polar: &Polar, flow: SteadyFlow, z: &mut [f64], dz_dalpha: &mut [f64]) {
        let k = self.constants(polar);
        let line = polar.attached();
        let alpha = DualSVec64::<1>::from_re(flow.alpha).derivative(0);
        let x3 = (alpha - line.zero_lift) * line.slope;
        let [x4, _] = separation(polar, Self::separation_angle(polar, x3));
        let slope = |d: &DualSVec64<1>| d.eps.unwrap_generic(Const::<1>, U1)[0];
        z[..4].copy_from_slice(&[k.a1 * flow.alpha, k.a2 * flow.alpha, x3.re, x4.re]);
        dz_dalpha[..4].copy_from_slice(&[k.a1, k.a2, slope(&x3), slope(&x4)]);
    }

    fn nonlinear_in_time(&self) -> bool {
        true
    }
}
