//! Strip-theory stations and the rigid inflow at each of them (docs/model.md §1).
//!
//! Inputs: blade length and hub radius, the operating point (wind `U`, induction `a_ind`, rotor
//! speed `Ω`, tunnel speed `V_t`, pitch `β`, pretwist, inflow mode), the station count.
//! Outputs: one [`Station`] per Gauss–Legendre point on `[0, L]` with its quadrature weight,
//! radius, relative speed `V0`, inflow angle `ψ` and rigid angle of attack `α_r = ψ − β − θ_tw`.
//!
//! Gauss points are used as stations so that the strip sums `Σ w_s f(x_s)` are the Gauss
//! quadrature of the spanwise load integrals `∫ f dx` of §5 (exact for smooth loads as the count
//! grows, and never evaluating at the root or tip where the Galerkin functions vanish or peak).

use crate::physics::basis::gauss_legendre;

/// Where each strip's relative speed and inflow angle are evaluated (docs/model.md §1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Inflow {
    /// V0 and ψ evaluated at the tip for every station (the paper).
    Tip,
    /// Each station at its own radius.
    Local,
}

/// The rigid (structure-independent) flow seen by one strip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Position of the station in its list: a model with a section per station (a real blade,
    /// §12) keeps them in the same order.
    pub index: usize,
    /// Span position x from the root (m).
    pub x: f64,
    /// Quadrature weight (m): `Σ w_s = L`.
    pub weight: f64,
    /// Radius r = r_hub + x (m).
    pub radius: f64,
    /// Relative speed V0 = √(U_a² + U_t²) (m/s), at the tip or the local radius per the inflow mode.
    pub v0: f64,
    /// Inflow angle ψ = atan2(U_a, U_t) (rad).
    pub psi: f64,
    /// Rigid angle of attack α_r = ψ − β − θ_tw(x) (rad).
    pub alpha_r: f64,
}

/// The operating point in SI, as the inflow needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatingPoint {
    /// Wind speed U (m/s).
    pub wind: f64,
    /// Axial induction a_ind.
    pub induction: f64,
    /// Rotor speed Ω (rad/s).
    pub omega: f64,
    /// In-plane tunnel speed V_t (m/s).
    pub tunnel: f64,
    /// Collective pitch β (rad), toward feather.
    pub pitch: f64,
    /// Pretwist at root and tip (rad), toward feather, linear in between.
    pub twist_root: f64,
    pub twist_tip: f64,
    pub inflow: Inflow,
}

impl OperatingPoint {
    /// Relative speed V0 and inflow angle ψ at radius `r` (docs/model.md §1).
    pub fn velocity_triangle(&self, r: f64) -> (f64, f64) {
        let axial = self.wind * (1.0 - self.induction);
        let in_plane = self.omega * r + self.tunnel;
        (axial.hypot(in_plane), axial.atan2(in_plane))
    }

    /// Pretwist θ_tw at span position `x` of a blade of length `length` (rad).
    pub fn pretwist(&self, x: f64, length: f64) -> f64 {
        self.twist_root + (self.twist_tip - self.twist_root) * x / length
    }
}

/// Stations at the `count` Gauss–Legendre points of `[0, length]`.
pub fn stations(length: f64, hub_radius: f64, op: &OperatingPoint, count: usize) -> Vec<Station> {
    let (nodes, weights) = gauss_legendre(count);
    let half = 0.5 * length;
    let tip_flow = op.velocity_triangle(hub_radius + length);
    nodes
        .iter()
        .zip(&weights)
        .enumerate()
        .map(|(index, (&xi, &w))| {
            let x = half * (xi + 1.0);
            let radius = hub_radius + x;
            let (v0, psi) = match op.inflow {
                Inflow::Tip => tip_flow,
                Inflow::Local => op.velocity_triangle(radius),
            };
            Station {
                index,
                x,
                weight: half * w,
                radius,
                v0,
                psi,
                alpha_r: psi - op.pitch - op.pretwist(x, length),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(inflow: Inflow) -> OperatingPoint {
        OperatingPoint {
            wind: 20.0,
            induction: 0.25,
            omega: 6.0,
            tunnel: 0.0,
            pitch: 0.1,
            twist_root: 0.2,
            twist_tip: 0.0,
            inflow,
        }
    }

    #[test]
    fn weights_integrate_the_span() {
        let s = stations(8.0, 0.5, &op(Inflow::Local), 7);
        let total: f64 = s.iter().map(|s| s.weight).sum();
        assert!((total - 8.0).abs() < 1e-12);
        // ∫ x² dx over [0, 8] = 512/3, exact for Gauss with 7 points.
        let m2: f64 = s.iter().map(|s| s.weight * s.x * s.x).sum();
        assert!((m2 - 512.0 / 3.0).abs() < 1e-9);
    }

    #[test]
    fn tip_inflow_is_uniform_local_is_not() {
        let tip = stations(8.0, 0.5, &op(Inflow::Tip), 5);
        let local = stations(8.0, 0.5, &op(Inflow::Local), 5);
        let psi_tip = (15.0f64).atan2(6.0 * 8.5);
        for s in &tip {
            assert!((s.psi - psi_tip).abs() < 1e-14);
            assert!((s.v0 - 15.0f64.hypot(51.0)).abs() < 1e-12);
        }
        // Inboard the in-plane speed is lower, so the inflow angle is larger.
        assert!(local[0].psi > local[4].psi);
        // Pretwist (toward feather) lowers α_r inboard.
        let s = &local[0];
        let expected = s.psi - 0.1 - (0.2 - 0.2 * s.x / 8.0);
        assert!((s.alpha_r - expected).abs() < 1e-14);
    }
}
