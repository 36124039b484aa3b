//! `onera` on a real blade's section (docs/model.md §12.5): the coupled form of §5.3 on the
//! section's own polar. The polar splits into its attached line and the static deviations from
//! it, `ΔC_L = a0(α − α0) − C_l(α)`, `ΔC_M = C_m(α0) − C_m(α)`, `ΔC_D = C_d(α0) − C_d(α)`; the
//! attached lift runs through Jones's lags as `theodorsen`'s, and each deviation through its
//! second-order stall state `C̈2X + a_X ω_r Ċ2X + r_X ω_r² C2X = −r_X ω_r² ΔC_X(α_¾)`,
//! `ω_r = V0/b`. `C_l = a0(α_e − α0) + C2L`, `C_m = C_m(α0) + C2M`, `C_d = C_d(α0) + C2D`.
//!
//! States: the two lags, then `[C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`. Its steady state is the polar
//! exactly.

use super::jones::JonesAirfoil;
use super::{polar_coefficients, AirfoilDynamics, SectionFlow, SteadyFlow};
use crate::physics::aero::polar::Polar;
use crate::physics::aero::theodorsen::JONES;
use nalgebra::{Const, U1};
use num_dual::{DualNum, DualSVec64};

/// ONERA's stall-state coefficients (`aero.onera.a_l`, `r_l`, `a_m`, `r_m`, `a_d`, `r_d`), in the
/// order lift, moment, drag.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StallDynamics {
    pub a: [f64; 3],
    pub r: [f64; 3],
}

/// Index of the first stall state (`C2L`), after the two Jones lags; each deviation has a
/// value and a rate state.
const STALL: usize = JONES.len();

/// The static deviations `[ΔC_L, ΔC_M, ΔC_D]` of `polar` from its attached flow at `alpha`.
fn deviations<T: DualNum<Primitive = f64> + Copy>(polar: &Polar, alpha: T) -> [T; 3] {
    let line = polar.attached();
    let at_zero_lift = polar.at(line.zero_lift);
    let [cl, cd, cm] = polar_coefficients(polar, alpha);
    [
        (alpha - line.zero_lift) * line.slope - cl,
        -cm + at_zero_lift.cm,
        -cd + at_zero_lift.cd,
    ]
}

impl AirfoilDynamics for StallDynamics {
    fn name(&self) -> &'static str {
        "onera"
    }

    fn states(&self) -> usize {
        STALL + 6
    }

    fn coefficients<T: DualNum<Primitive = f64> + Copy>(
        &self,
        polar: &Polar,
        flow: &SectionFlow<T>,
        z: &[T],
        zdot: &mut [T],
    ) -> [T; 3] {
        let alpha_e = JonesAirfoil::effective_angle(flow, z, zdot);
        let rate = flow.rate;
        let deviation = deviations(polar, flow.alpha);
        let line = polar.attached();
        let at_zero_lift = polar.at(line.zero_lift);
        let stall = |k: usize| z[STALL + k];
        for x in 0..3 {
            let (a, r) = (self.a[x], self.r[x]);
            let (value, slope) = (stall(2 * x), stall(2 * x + 1));
            zdot[STALL + 2 * x] = slope;
            zdot[STALL + 2 * x + 1] =
                -(slope * (a * rate)) - (value + deviation[x]) * (r * rate * rate);
        }
        [
            (alpha_e - line.zero_lift) * line.slope + stall(0),
            stall(4) + at_zero_lift.cd,
            stall(2) + at_zero_lift.cm,
        ]
    }

    /// The lags as `theodorsen`'s; the stall states at `C2X = −ΔC_X(α)`, `Ċ2X = 0`.
    fn steady_states(&self, polar: &Polar, flow: SteadyFlow, z: &mut [f64], dz_dalpha: &mut [f64]) {
        JonesAirfoil::steady_lags(flow, z, dz_dalpha);
        let alpha = DualSVec64::<1>::from_re(flow.alpha).derivative(0);
        for (x, d) in deviations(polar, alpha).iter().enumerate() {
            z[STALL + 2 * x] = -d.re;
            dz_dalpha[STALL + 2 * x] = -d.eps.unwrap_generic(Const::<1>, U1)[0];
        }
    }
}
