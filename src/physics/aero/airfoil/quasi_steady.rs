//! `quasi-steady` on a real blade's section (docs/model.md §12.5): the polar at the
//! three-quarter-chord angle of attack, no states.

use super::{polar_coefficients, AirfoilDynamics, SectionFlow, SteadyFlow};
use crate::physics::aero::polar::Polar;
use num_dual::DualNum;

#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct QuasiSteadyAirfoil;

impl AirfoilDynamics for QuasiSteadyAirfoil {
    fn name(&self) -> &'static str {
        "quasi-steady"
    }

    fn states(&self) -> usize {
        0
    }

    fn coefficients<T: DualNum<Primitive = f64> + Copy>(
        &self,
        polar: &Polar,
        flow: &SectionFlow<T>,
        _: &[T],
        _: &mut [T],
    ) -> [T; 3] {
        polar_coefficients(polar, flow.alpha)
    }

    fn steady_states(&self, _: &Polar, _: SteadyFlow, _: &mut [f64], _: &mut [f64]) {}
}
