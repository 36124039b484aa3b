//! Steady blade-element momentum (BEM) theory for a rotor of B identical blades in uniform
//! wind along the shaft (docs/model.md §12.2): the axial and tangential induction at each
//! station, Prandtl's tip and hub losses, Buhl's or Madsen's high-thrust relation, solved as one
//! residual in the inflow angle bracketed as Ning (2014) shows, so that every station converges:
//! attached, stalled, near the hub, with the rotor parked. The blade may be coned, prebent and
//! bent by its elastic deflection, and the shaft tilted (§12.2, "Cone, prebend and tilt").
//!
//! Inputs: the stations (span, quadrature weight, section from [`AeroBlade::section_at`], the
//! prebend there), an optional deflection per station (elastic twist toward feather and flap
//! downwind, from a static equilibrium), the rotor (blade count, hub and tip radius, precone,
//! shaft tilt) and the operating conditions (wind, rotor speed, pitch, air density). Outputs:
//! per station the inflow angle, angle of attack, inductions, velocities and coefficients and
//! the loads per span; the rotor's power, thrust, torque and tip speed ratio.

use super::induction::HighThrust;
use super::{AeroBlade, AeroSection};
use crate::error::{Error, Result};
use crate::numeric::root::brent_with_values;
use crate::physics::basis::gauss_legendre;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The rotor around the blades: what the loss factors need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotor {
    /// Blade count B.
    pub blades: usize,
    /// Hub radius r_hub (m): a station's radius is `r_hub + span`.
    pub hub_radius: f64,
    /// Tip radius R (m), along the blade.
    pub tip_radius: f64,
    /// Precone β (rad): the blade's root axis inclined upwind out of the rotor plane (away from
    /// the tower of an upwind rotor; HAWC2's cone, AeroDyn's `−PreCone`).
    pub precone: f64,
    /// Shaft tilt τ (rad): the wind's component along the shaft is `U cos τ`; the in-plane
    /// component `U sin τ` changes sign around the revolution and averages out (its sign is
    /// immaterial here).
    pub shaft_tilt: f64,
    /// The thrust–induction relation of heavily loaded elements (`aero.high_thrust`).
    pub high_thrust: HighThrust,
}

/// The steady operating conditions (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conditions {
    /// Wind speed U (m/s), axial, uniform.
    pub wind_speed: f64,
    /// Rotor speed Ω (rad/s).
    pub rotor_speed: f64,
    /// Collective pitch θ_p (rad), toward feather.
    pub pitch: f64,
    /// Air density ρ (kg/m³).
    pub air_density: f64,
}

/// One blade element where the caller wants the flow: a span position with its quadrature weight.
#[derive(Debug, Clone)]
pub struct AeroStation {
    /// Span from the blade root (m).
    pub span: f64,
    /// Quadrature weight (m): the totals are `Σ weight · load`.
    pub weight: f64,
    pub section: AeroSection,
    /// Out-of-plane offset of the blade's axis from the coned root axis, downwind positive (m):
    /// the prebend (AeroDyn's `BlCrvAC` sign; the IEA 15MW tip sits 4 m upwind).
    pub prebend: f64,
}

/// The blade's static deflection at one station, from an aeroelastic equilibrium.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Deflection {
    /// Elastic twist toward feather (rad): adds to the station's twist.
    pub twist: f64,
    /// Flap deflection downwind (m): adds to the prebend, bending the blade's axis.
    pub flap: f64,
}

impl AeroStation {
    /// The station at `span` with its section and prebend from `blade`.
    pub fn on(blade: &AeroBlade, span: f64, weight: f64) -> Result<AeroStation> {
        Ok(AeroStation {
            span,
            weight,
            section: blade.section_at(span)?,
            prebend: blade.prebend_at(span),
        })
    }

    /// `count` stations at the Gauss–Legendre points of the blade's described span: the totals
    /// are then the Gauss quadrature of the load integrals, and no station sits on the hub or
    /// the tip, where the loss factors vanish.
    pub fn gauss(blade: &AeroBlade, count: usize) -> Result<Vec<AeroStation>> {
        let (first, last) = blade.span_range();
        let half = 0.5 * (last - first);
        let (nodes, weights) = gauss_legendre(count);
        nodes
            .iter()
            .zip(&weights)
            .map(|(&xi, &w)| AeroStation::on(blade, first + half * (xi + 1.0), half * w))
            .collect()
    }
}

/// The flow and loads at one station.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StationFlow {
    /// Span from the blade root (m).
    pub span: f64,
    /// Distance from the shaft axis (m): `r cos β` on a straight blade, less (or more) where
    /// the axis is bent (§12.2).
    pub radius: f64,
    /// Inflow angle φ between the relative wind and the rotor plane (rad).
    pub inflow_angle: f64,
    /// Angle of attack α = φ − (θ_twist + θ_p + extra twist) (rad).
    pub angle_of_attack: f64,
    /// Axial induction a.
    pub axial_induction: f64,
    /// Tangential induction a'.
    pub tangential_induction: f64,
    /// Combined Prandtl loss factor F = F_tip F_hub.
    pub loss_factor: f64,
    /// Axial velocity through the rotor after induction, U (1 − a) (m/s).
    pub axial_velocity: f64,
    /// In-plane velocity after induction, Ω r (1 + a') (m/s).
    pub tangential_velocity: f64,
    /// Relative speed W (m/s).
    pub relative_speed: f64,
    pub cl: f64,
    pub cd: f64,
    /// About the quarter chord, nose-up positive.
    pub cm: f64,
    /// Out-of-plane (downwind) load per span (N/m): ½ρW²c (C_l cos φ + C_d sin φ).
    pub out_of_plane_load: f64,
    /// In-plane load per span, in the direction of rotation (N/m): ½ρW²c (C_l sin φ − C_d cos φ).
    pub in_plane_load: f64,
}

/// The steady operating point of the rotor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OperatingState {
    /// Aerodynamic power Ω Q (W).
    pub power: f64,
    /// Thrust along the shaft, all blades (N).
    pub thrust: f64,
    /// Aerodynamic torque, all blades (N·m).
    pub torque: f64,
    /// Ω R / U (0 without wind).
    pub tip_speed_ratio: f64,
    pub stations: Vec<StationFlow>,
}

/// Angle kept from the bracket ends 0 and π, where the residual's momentum terms divide by
/// sin φ (rad).
const EPSILON: f64 = 1e-6;
/// Tolerance on the inflow angle (rad): far below any polar's resolution.
const TOLERANCE: f64 = 1e-10;
/// Smallest loss factor used: at the hub or tip themselves F = 0 and the momentum balance
/// divides by it; 1e-4 leaves F's effect (the load vanishing there) and keeps the residual finite.
const MIN_LOSS: f64 = 1e-4;

/// The steady flow at every station and the rotor's totals. `deflection` (one per station, or
/// empty for none) twists each station toward feather and bends the blade's axis downwind, e.g.
/// the elastic deflection of a static equilibrium.
pub fn solve(
    rotor: &Rotor,
    stations: &[AeroStation],
    deflection: &[Deflection],
    at: &Conditions,
) -> Result<OperatingState> {
    if !deflection.is_empty() && deflection.len() != stations.len() {
        return Err(Error::numerical(format!(
            "BEM: {} deflections given for {} stations",
            deflection.len(),
            stations.len()
        )));
    }
    let deflected = |i: usize| deflection.get(i).copied().unwrap_or_default();
    let places = placements(rotor, stations, deflected);
    let flows = stations
        .iter()
        .zip(&places)
        .enumerate()
        .map(|(i, (s, place))| {
            let twist = s.section.twist + at.pitch + deflected(i).twist;
            station_flow(rotor, s, place, twist, at)
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(totals(rotor, stations, &places, flows, at))
}

/// Where a station sits on the coned, bent blade.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Placement {
    /// Distance from the shaft axis (m).
    radius: f64,
    /// Local cone angle κ (rad), upwind positive: the precone plus the slope of the bent axis.
    cone: f64,
}

/// Each station's distance from the shaft and local cone angle. A point at `s = r_hub + span`
/// along the coned root axis, offset `w` (prebend + flap) downwind normal to it, sits
/// `x = −s sin β + w cos β` downwind of the rotor plane and `z = s cos β + w sin β` from the
/// shaft; the local cone is the inclination `atan2(−Δx, Δz)` of the axis, from the neighbouring
/// stations (the mean of the two segments inside, the one segment at the ends), as CCBlade
/// takes it (Ning 2014's code, `defineCurvature`).
fn placements(
    rotor: &Rotor,
    stations: &[AeroStation],
    deflected: impl Fn(usize) -> Deflection,
) -> Vec<Placement> {
    let (sb, cb) = rotor.precone.sin_cos();
    let points: Vec<(f64, f64)> = stations
        .iter()
        .enumerate()
        .map(|(i, st)| {
            let s = rotor.hub_radius + st.span;
            let w = st.prebend + deflected(i).flap;
            (-s * sb + w * cb, s * cb + w * sb)
        })
        .collect();
    let segment = |i: usize| {
        let ((x0, z0), (x1, z1)) = (points[i], points[i + 1]);
        (x0 - x1).atan2(z1 - z0)
    };
    let n = points.len();
    (0..n)
        .map(|i| Placement {
            radius: points[i].1,
            cone: match (i, n) {
                (_, 1) => rotor.precone,
                (0, _) => segment(0),
                (i, n) if i == n - 1 => segment(n - 2),
                (i, _) => 0.5 * (segment(i - 1) + segment(i)),
            },
        })
        .collect()
}

/// Power, thrust and torque from the station loads by the stations' quadrature: the thrust is
/// the loads normal to the coned blade turned onto the shaft (`cos κ`), the torque their
/// in-plane part times the distance from the shaft.
fn totals(
    rotor: &Rotor,
    stations: &[AeroStation],
    places: &[Placement],
    flows: Vec<StationFlow>,
    at: &Conditions,
) -> OperatingState {
    let b = rotor.blades as f64;
    let (thrust, torque) =
        stations
            .iter()
            .zip(places)
            .zip(&flows)
            .fold((0.0, 0.0), |(t, q), ((s, place), f)| {
                (
                    t + b * s.weight * f.out_of_plane_load * place.cone.cos(),
                    q + b * s.weight * f.in_plane_load * place.radius,
                )
            });
    OperatingState {
        power: at.rotor_speed * torque,
        thrust,
        torque,
        tip_speed_ratio: if at.wind_speed > 0.0 {
            at.rotor_speed * rotor.tip_radius / at.wind_speed
        } else {
            0.0
        },
        stations: flows,
    }
}

/// What one station's blade element gives at inflow angle φ: the inductions the momentum
/// balance asks for and the residual whose root is the steady flow.
#[derive(Debug, Clone, Copy)]
struct Element {
    axial: f64,
    tangential: f64,
    loss: f64,
    residual: f64,
}

/// The blade element at one station: its solidity, radius, twist and polar.
struct Blade<'a> {
    rotor: &'a Rotor,
    section: &'a AeroSection,
    /// Radius along the blade, `r_hub + span` (m): the solidity and the loss factors use it,
    /// as CCBlade does.
    radius: f64,
    /// Distance from the shaft axis (m).
    arm: f64,
    /// Wind speed normal to the coned blade, `U cos τ cos κ` (m/s).
    axial: f64,
    /// Local solidity σ' = B c / (2π r).
    solidity: f64,
    /// θ_twist + θ_p + extra twist (rad).
    twist: f64,
    /// Local speed ratio λ_r = Ω r / U.
    speed_ratio: f64,
}

fn station_flow(
    rotor: &Rotor,
    station: &AeroStation,
    place: &Placement,
    twist: f64,
    at: &Conditions,
) -> Result<StationFlow> {
    let radius = rotor.hub_radius + station.span;
    // Azimuth-averaged components in the coned blade's frame (CCBlade's `windComponents` at
    // zero yaw, the tilt's in-plane part averaged out): normal to the blade the shaft-wise wind
    // turned by the local cone, in plane the rotation about the shaft.
    let axial = at.wind_speed * rotor.shaft_tilt.cos() * place.cone.cos();
    let in_plane = at.rotor_speed * place.radius;
    let blade = Blade {
        rotor,
        section: &station.section,
        radius,
        arm: place.radius,
        axial,
        solidity: rotor.blades as f64 * station.section.chord / (2.0 * PI * radius),
        twist,
        speed_ratio: if axial > 0.0 { in_plane / axial } else { 0.0 },
    };
    // No momentum balance without both velocities (parked rotor, or no wind): the element sees
    // the undisturbed flow, as AeroDyn's BEMT does when either velocity vanishes.
    if axial <= 0.0 || in_plane <= 0.0 {
        let phi = axial.atan2(in_plane);
        return Ok(blade.flow(phi, 0.0, 0.0, blade.loss(phi), at));
    }
    let phi = blade.inflow_angle().ok_or_else(|| {
        Error::numerical(format!(
            "BEM: no inflow angle balances momentum at span {:.3} m (radius {radius:.3} m) at \
             wind {axial} m/s, rotor speed {} rad/s, pitch {:.3}°: no sign change of the residual \
             on (0, π/2], [−π/4, 0) or (π/2, π)",
            station.span,
            at.rotor_speed,
            at.pitch.to_degrees()
        ))
    })?;
    let e = blade.element(phi);
    Ok(blade.flow(phi, e.axial, e.tangential, e.loss, at))
}

impl Blade<'_> {
    /// The root of the residual, from the first of Ning's three brackets with a sign change:
    /// the windmill region (0, π/2], the propeller brake region [−π/4, 0), and (π/2, π).
    fn inflow_angle(&self) -> Option<f64> {
        let brackets = [
            (EPSILON, FRAC_PI_2),
            (-FRAC_PI_4, -EPSILON),
            (FRAC_PI_2, PI - EPSILON),
        ];
        let mut residual = |phi: f64| self.element(phi).residual;
        brackets.iter().find_map(|&(a, b)| {
            let (fa, fb) = (residual(a), residual(b));
            (fa.is_finite() && fb.is_finite() && fa * fb <= 0.0)
                .then(|| brent_with_values(&mut residual, a, fa, b, fb, TOLERANCE))
                .flatten()
        })
    }

    /// Prandtl's tip and hub loss factors at inflow angle φ:
    /// `F = (2/π) acos(exp(−B(R − r)/(2 r |sin φ|))) · (2/π) acos(exp(−B(r − r_hub)/(2 r_hub |sin φ|)))`.
    fn loss(&self, phi: f64) -> f64 {
        let b = self.rotor.blades as f64;
        let s = phi.sin().abs().max(1e-12);
        let prandtl = |f: f64| 2.0 / PI * (-f.max(0.0)).exp().acos();
        let tip = prandtl(0.5 * b * (self.rotor.tip_radius - self.radius) / (self.radius * s));
        let hub = if self.rotor.hub_radius > 0.0 {
            prandtl(0.5 * b * (self.radius - self.rotor.hub_radius) / (self.rotor.hub_radius * s))
        } else {
            1.0
        };
        tip * hub
    }

    /// The element at inflow angle φ: normal and tangential force coefficients from the polar,
    /// the inductions momentum theory gives for them (the rotor's high-thrust relation where
    /// heavily loaded, [`HighThrust`]), and Ning's residual (docs/model.md §12.2).
    fn element(&self, phi: f64) -> Element {
        let (s, c) = phi.sin_cos();
        let coeff = self.section.polar.at(phi - self.twist);
        let cn = coeff.cl * c + coeff.cd * s;
        let ct = coeff.cl * s - coeff.cd * c;
        let loss = self.loss(phi).max(MIN_LOSS);
        let k = self.solidity * cn / (4.0 * loss * s * s);
        let kp = self.solidity * ct / (4.0 * loss * s * c);
        let tangential = kp / (1.0 - kp);
        let (axial, residual) = if phi > 0.0 {
            let a = self.rotor.high_thrust.axial_induction(k, loss);
            (a, s / (1.0 - a) - c / self.speed_ratio * (1.0 - kp))
        } else {
            // Propeller brake: the residual in the form that stays finite there.
            let a = if k > 1.0 { k / (k - 1.0) } else { 0.0 };
            (a, s * (1.0 - k) - c / self.speed_ratio * (1.0 - kp))
        };
        Element {
            axial,
            tangential,
            loss,
            residual,
        }
    }

    /// The reported flow at inflow angle φ with inductions `a`, `a'`.
    fn flow(
        &self,
        phi: f64,
        axial_induction: f64,
        tangential_induction: f64,
        loss: f64,
        at: &Conditions,
    ) -> StationFlow {
        let u = self.axial * (1.0 - axial_induction);
        let v = at.rotor_speed * self.arm * (1.0 + tangential_induction);
        let w = u.hypot(v);
        let alpha = phi - self.twist;
        let coeff = self.section.polar.at(alpha);
        let (s, c) = phi.sin_cos();
        let q = 0.5 * at.air_density * w * w * self.section.chord;
        StationFlow {
            span: self.radius - self.rotor.hub_radius,
            radius: self.arm,
            inflow_angle: phi,
            angle_of_attack: alpha,
            axial_induction,
            tangential_induction,
            loss_factor: loss,
            axial_velocity: u,
            tangential_velocity: v,
            relative_speed: w,
            cl: coeff.cl,
            cd: coeff.cd,
            cm: coeff.cm,
            out_of_plane_load: q * (coeff.cl * c + coeff.cd * s),
            in_plane_load: q * (coeff.cl * s - coeff.cd * c),
        }
    }
}
