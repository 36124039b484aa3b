//! `theodorsen` on a real blade's section (docs/model.md §12.5): R. T. Jones's two lags on the
//! three-quarter-chord angle, `ż_i = −ε_i (V0/b) z_i + α_¾`,
//! `α_e = (1 − A1 − A2) α_¾ + (V0/b) Σ A_i ε_i z_i`, and the polar at `α_e`.
//!
//! The lags on the angle rather than on §5.2's downwash keep the polar's own lift slope; their
//! constants are §5.2's ([`JONES`]).

use super::{polar_coefficients, AirfoilDynamics, SectionFlow, SteadyFlow};
use crate::physics::aero::polar::Polar;
use crate::physics::aero::theodorsen::JONES;
use num_dual::DualNum;

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JonesAirfoil;

impl JonesAirfoil {
    /// `α_e` at the flow and lag states `z` (the first two), their rates into `zdot`.
    pub fn effective_angle<T: DualNum<Primitive = f64> + Copy>(
        flow: &SectionFlow<T>,
        z: &[T],
        zdot: &mut [T],
    ) -> T {
        let direct = 1.0 - JONES.iter().map(|(a, _)| a).sum::<f64>();
        let mut alpha_e = flow.alpha * direct;
        for (i, (amp, eps)) in JONES.iter().enumerate() {
            alpha_e += z[i] * (flow.rate * amp * eps);
            zdot[i] = flow.alpha - z[i] * (eps * flow.rate);
        }
        alpha_e
    }

    /// The lags' steady states `z_i = b α / (ε_i V0)` and their slope in α.
    pub fn steady_lags(flow: SteadyFlow, z: &mut [f64], dz_dalpha: &mut [f64]) {
        for (i, (_, eps)) in JONES.iter().enumerate() {
            let gain = flow.semichord / (eps * flow.speed);
            z[i] = gain * flow.alpha;
            dz_dalpha[i] = gain;
        }
    }
}

impl AirfoilDynamics for JonesAirfoil {
    fn name(&self) -> &'static str {
        "theodorsen"
    }

    fn states(&self) -> usize {
        JONES.len()
    }

    fn coefficients<T: DualNum<Primitive = f64> + Copy>(
        &self,
        polar: &Polar,
        flow: &SectionFlow<T>,
        z: &[T],
        zdot: &mut [T],
    ) -> [T; 3] {
        let alpha_e = Self::effective_angle(flow, z, zdot);
        polar_coefficients(polar, alpha_e)
    }

    fn steady_states(&self, _: &Polar, flow: SteadyFlow, z: &mut [f64], dz_dalpha: &mut [f64]) {
        Self::steady_lags(flow, z, dz_dalpha);
    }
}
