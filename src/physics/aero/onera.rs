//! ONERA stall aerodynamics of one strip (docs/model.md §5.3; paper Eqs. 4–6).
//!
//! Everything here is a pure function of one strip: the piecewise stall deviations `ΔC_X(α)`
//! with their slopes, the state derivatives of both forms with their partial derivatives (for the
//! analytic Jacobian of docs/model.md §6), the steady states, and the strip loads `f_u`, `m_φ` with
//! their partial derivatives. Spanwise sums and basis functions belong to the caller; the one
//! helper that touches them, [`add_generalized_force`], only weights a strip load by its
//! quadrature weight and the basis values at the station. [`OneraModel`] wraps these functions
//! as the system's [`StripModel`], including where the model is nonlinear
//! ([`NonlinearSupport`], for the time stepper of §7).
//!
//! State layout per station (docs/model.md §5.3):
//! - `rigid` (7): `[C1L, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`, driven by the rigid angle `α_r`;
//! - `coupled` (8): `[z1, z2, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`, the two R.T. Jones lags of §5.2 on
//!   the three-quarter-chord downwash `w`, and the stall states driven by `α = w/V0`.
//!
//! The pitching moment coefficient `C_M0` enters both forms (docs/model.md writes it only in the rigid
//! form; with its default 0 the coupled form still differs from `theodorsen` only by drag, and a
//! preset that sets `aero.onera.cm0` sees it in the default form too).

use super::{Kinematics, NonlinearSupport, SteadyStates, StripEval, StripModel, StripSection};
use crate::physics::inflow::Station;

/// The two ONERA forms (docs/model.md §5.3): `coupled`, the attached flow of §5.2 with stall
/// states driven by the blade's motion (stall flutter proper), or `rigid`, the paper's reduced
/// model, every state driven by the rigid angle of attack alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OneraForcing {
    Coupled,
    Rigid,
}

/// R.T. Jones' two-lag approximation `(A_i, ε_i)`, shared with the attached flow of §5.2.
pub use super::theodorsen::JONES;

/// Stall states per station: three second-order states, each a value and its rate.
pub const STALL_STATES: usize = 6;

/// The three aerodynamic coefficients that have a stall deviation and a second-order state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    Lift,
    Moment,
    Drag,
}

impl Channel {
    pub const ALL: [Channel; 3] = [Channel::Lift, Channel::Moment, Channel::Drag];

    /// Position in `[L, M, D]` arrays and, doubled, in the stall-state block.
    pub fn index(self) -> usize {
        match self {
            Channel::Lift => 0,
            Channel::Moment => 1,
            Channel::Drag => 2,
        }
    }
}

/// Which piece of the lift/moment deviation law an angle of attack lies on (docs/model.md §5.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Regime {
    /// `|α| ≤ α1`: no lift or moment deviation.
    Attached,
    /// `α1 < |α| ≤ α2`: slope `a_X1`.
    Stalling,
    /// `|α| > α2`: slope `a_X1 + a_X2`.
    Stalled,
}

/// The ONERA coefficients in SI (angles in rad), docs/model.md §5.3.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// `λ_L`, rate of the rigid form's first-order lift state.
    pub lambda_l: f64,
    /// `a_0L` (1/rad), attached-flow lift slope of both forms.
    pub a0l: f64,
    /// `a_X` for `[L, M, D]`: damping of the second-order stall states (per `ω_r`).
    pub damping: [f64; 3],
    /// `r_X` for `[L, M, D]`: stiffness of the second-order stall states (per `ω_r²`).
    pub stiffness: [f64; 3],
    /// `(a_L1, a_L2)`: lift-deviation slopes past `α1` and the extra slope past `α2`.
    pub lift_slopes: (f64, f64),
    /// `(a_M1, a_M2)`: the same for the moment.
    pub moment_slopes: (f64, f64),
    /// `(a_D1, a_D2, a_D3)`: drag deviation `−a_D1|α| − a_D2α² − a_D3|α|³`.
    pub drag_polynomial: (f64, f64, f64),
    /// `C_M0`, pitching moment at zero lift (nose-up).
    pub cm0: f64,
    /// `C_D0`, profile drag.
    pub cd0: f64,
    /// Stall onset `α1` (rad).
    pub alpha1: f64,
    /// Full-stall angle `α2` (rad).
    pub alpha2: f64,
}

/// Stall deviations `ΔC_X(α)` for `[L, M, D]` and their slopes `dΔC_X/dα`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deviation {
    pub value: [f64; 3],
    pub slope: [f64; 3],
}

/// Sign with `sign(0) = 0`: the deviations are odd (or, for drag, contain `|α|`), and at α = 0
/// the mean of the one-sided slopes is the useful Jacobian entry.
fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

impl Coefficients {
    /// The piece of the lift/moment law that `α` lies on.
    pub fn regime(&self, alpha: f64) -> Regime {
        let m = alpha.abs();
        if m <= self.alpha1 {
            Regime::Attached
        } else if m <= self.alpha2 {
            Regime::Stalling
        } else {
            Regime::Stalled
        }
    }

    /// The odd piecewise-linear deviation of lift or moment with slopes `(a_X1, a_X2)`, and its
    /// (even) slope. Continuous at both breakpoints by construction.
    fn piecewise_deviation(&self, (a1, a2): (f64, f64), alpha: f64) -> (f64, f64) {
        let m = alpha.abs();
        match self.regime(alpha) {
            Regime::Attached => (0.0, 0.0),
            Regime::Stalling => (sign(alpha) * a1 * (m - self.alpha1), a1),
            Regime::Stalled => (
                sign(alpha) * ((a1 + a2) * m - a1 * self.alpha1 - a2 * self.alpha2),
                a1 + a2,
            ),
        }
    }

    /// The even drag deviation `−a_D1|α| − a_D2α² − a_D3|α|³` and its slope.
    fn drag_deviation(&self, alpha: f64) -> (f64, f64) {
        let (d1, d2, d3) = self.drag_polynomial;
        let m = alpha.abs();
        let value = -d1 * m - d2 * alpha * alpha - d3 * m * m * m;
        let slope = -d1 * sign(alpha) - 2.0 * d2 * alpha - 3.0 * d3 * alpha * m;
        (value, slope)
    }

    /// `ΔC_L, ΔC_M, ΔC_D` at `α` with their slopes (docs/model.md §5.3).
    pub fn deviation(&self, alpha: f64) -> Deviation {
        let (l, dl) = self.piecewise_deviation(self.lift_slopes, alpha);
        let (m, dm) = self.piecewise_deviation(self.moment_slopes, alpha);
        let (d, dd) = self.drag_deviation(alpha);
        Deviation {
            value: [l, m, d],
            slope: [dl, dm, dd],
        }
    }

    /// The static lift curve `C_L(α) = a_0L α − ΔC_L(α)`, the steady state of both forms.
    pub fn static_lift(&self, alpha: f64) -> f64 {
        self.a0l * alpha - self.deviation(alpha).value[0]
    }

    /// The static drag curve `C_D0 − ΔC_D(α)`.
    pub fn static_drag(&self, alpha: f64) -> f64 {
        self.cd0 - self.deviation(alpha).value[2]
    }

    /// The static moment curve `C_M0 − ΔC_M(α)` (nose-up, about the aerodynamic centre).
    pub fn static_moment(&self, alpha: f64) -> f64 {
        self.cm0 - self.deviation(alpha).value[1]
    }
}

/// The rigid flow and geometry of one strip, in SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strip {
    /// Air density `ρ_a` (kg/m³).
    pub air_density: f64,
    /// Relative speed `V0` (m/s).
    pub v0: f64,
    /// Inflow angle `ψ` (rad).
    pub psi: f64,
    /// Rigid angle of attack `α_r` (rad).
    pub alpha_r: f64,
    /// Chord `c` (m).
    pub chord: f64,
    /// `e_a = x_EA − x_AC` (m), positive when the elastic axis lies aft of the aerodynamic centre.
    pub ea_offset: f64,
}

impl Strip {
    /// Semichord `b = c/2`.
    pub fn semichord(&self) -> f64 {
        0.5 * self.chord
    }

    /// Reduced-time rate `ω_r = V0/b` (1/s) of every ONERA state.
    pub fn omega_r(&self) -> f64 {
        self.v0 / self.semichord()
    }

    /// Dynamic pressure `½ρ_a V0²` (Pa).
    pub fn dynamic_pressure(&self) -> f64 {
        0.5 * self.air_density * self.v0 * self.v0
    }

    /// Theodorsen's elastic-axis position `a = e_a/b − ½` (semichords aft of mid-chord).
    pub fn theodorsen_a(&self) -> f64 {
        self.ea_offset / self.semichord() - 0.5
    }

    /// The angle of attack that drives the coupled form's stall states: `α = w/V0` (0 in still
    /// air, where every aerodynamic load vanishes anyway).
    pub fn downwash_angle(&self, w: f64) -> f64 {
        if self.v0 > 0.0 {
            w / self.v0
        } else {
            0.0
        }
    }

    /// `dα/dw = 1/V0` (0 in still air, consistent with [`Strip::downwash_angle`]).
    fn downwash_angle_slope(&self) -> f64 {
        if self.v0 > 0.0 {
            1.0 / self.v0
        } else {
            0.0
        }
    }
}

/// The structural motion at a station: twist `φ` (toward feather) and flap `u` (downwind) rates.
/// The flap displacement itself never enters the strip loads.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Motion {
    /// `φ` (rad).
    pub twist: f64,
    /// `φ̇` (rad/s).
    pub twist_rate: f64,
    /// `φ̈` (rad/s²).
    pub twist_accel: f64,
    /// `u̇` (m/s).
    pub flap_rate: f64,
    /// `ü` (m/s²).
    pub flap_accel: f64,
}

/// Strip loads per unit span: `f_u` along `+u` (N/m) and `m_φ` toward feather (N·m/m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    pub flap: f64,
    pub twist: f64,
}

impl Loads {
    fn scaled(self, k: f64) -> Loads {
        Loads {
            flap: k * self.flap,
            twist: k * self.twist,
        }
    }
}

/// Partial derivatives of [`Loads`] with respect to the motion and the `S` station states.
/// Entries that a form does not depend on are zero.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadPartials<const S: usize> {
    pub twist: Loads,
    pub twist_rate: Loads,
    pub twist_accel: Loads,
    pub flap_rate: Loads,
    pub flap_accel: Loads,
    pub states: [Loads; S],
}

impl<const S: usize> Default for LoadPartials<S> {
    fn default() -> Self {
        LoadPartials {
            twist: Loads::default(),
            twist_rate: Loads::default(),
            twist_accel: Loads::default(),
            flap_rate: Loads::default(),
            flap_accel: Loads::default(),
            states: [Loads::default(); S],
        }
    }
}

/// Aerodynamic states per station of a form: 7 (`rigid`) or 8 (`coupled`), docs/model.md §5.3.
pub fn states_per_station(forcing: OneraForcing) -> usize {
    match forcing {
        OneraForcing::Rigid => rigid::STATES,
        OneraForcing::Coupled => coupled::STATES,
    }
}

/// Add one strip's contribution to the generalised forces (docs/model.md §5): `Q_φ += w m_φ Φ(x_s)`,
/// `Q_u += w f_u U(x_s)`, with `w` the station's quadrature weight.
pub fn add_generalized_force(
    loads: Loads,
    weight: f64,
    twist_shape: &[f64],
    flap_shape: &[f64],
    q_twist: &mut [f64],
    q_flap: &mut [f64],
) {
    for (q, phi) in q_twist.iter_mut().zip(twist_shape) {
        *q += weight * loads.twist * phi;
    }
    for (q, u) in q_flap.iter_mut().zip(flap_shape) {
        *q += weight * loads.flap * u;
    }
}

// ---------------------------------------------------------------------------------------------
// The second-order stall states, shared by both forms
// ---------------------------------------------------------------------------------------------

/// Derivatives of the stall block `[C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]` driven by `α`:
/// `C̈2X = −a_X ω_r Ċ2X − r_X ω_r² (C2X + ΔC_X(α))` (docs/model.md §5.3).
fn stall_rates(coef: &Coefficients, omega_r: f64, alpha: f64, stall: &[f64]) -> [f64; 6] {
    let dev = coef.deviation(alpha);
    let mut rates = [0.0; STALL_STATES];
    for ch in Channel::ALL {
        let i = ch.index();
        let (value, rate) = (stall[2 * i], stall[2 * i + 1]);
        rates[2 * i] = rate;
        rates[2 * i + 1] = -coef.damping[i] * omega_r * rate
            - coef.stiffness[i] * omega_r * omega_r * (value + dev.value[i]);
    }
    rates
}

/// Write `∂(stall rates)/∂(stall states)` into `jac` at `(offset, offset)`: three independent
/// damped oscillators, constant in the state.
fn stall_state_jacobian<const S: usize>(
    coef: &Coefficients,
    omega_r: f64,
    offset: usize,
    jac: &mut [[f64; S]; S],
) {
    for i in 0..3 {
        let (c, r) = (offset + 2 * i, offset + 2 * i + 1);
        jac[c][r] = 1.0;
        jac[r][c] = -coef.stiffness[i] * omega_r * omega_r;
        jac[r][r] = -coef.damping[i] * omega_r;
    }
}

/// `∂(stall rates)/∂α`: the deviation's slope through the oscillators' forcing.
fn stall_alpha_partial(coef: &Coefficients, omega_r: f64, alpha: f64) -> [f64; 6] {
    let dev = coef.deviation(alpha);
    let mut d = [0.0; STALL_STATES];
    for i in 0..3 {
        d[2 * i + 1] = -coef.stiffness[i] * omega_r * omega_r * dev.slope[i];
    }
    d
}

/// The steady stall block at `α`: `C2X = −ΔC_X(α)`, rates zero.
fn stall_steady(coef: &Coefficients, alpha: f64) -> [f64; 6] {
    let dev = coef.deviation(alpha);
    let mut s = [0.0; STALL_STATES];
    for i in 0..3 {
        s[2 * i] = -dev.value[i];
    }
    s
}

/// `d(steady stall block)/dα`.
fn stall_steady_alpha_partial(coef: &Coefficients, alpha: f64) -> [f64; 6] {
    let dev = coef.deviation(alpha);
    let mut s = [0.0; STALL_STATES];
    for i in 0..3 {
        s[2 * i] = -dev.slope[i];
    }
    s
}

/// The stall loads common to both forms, as dimensional lift `L2 = ½ρcV0² C2L`, nose-up moment
/// `M2 = ½ρc²V0² (C_M0 + C2M)` and drag `D = ½ρcV0² (C_D0 + C2D)`.
fn stall_forces(coef: &Coefficients, strip: &Strip, stall: &[f64]) -> (f64, f64, f64) {
    let qc = strip.dynamic_pressure() * strip.chord;
    (
        qc * stall[0],
        qc * strip.chord * (coef.cm0 + stall[2]),
        qc * (coef.cd0 + stall[4]),
    )
}

/// Loads per unit of the stall moment state `C2M` and of the stall drag state `C2D` (both forms
/// share them): the moment acts against feather with arm `c`, the drag downwind by `sin ψ` and
/// about the elastic axis with the arm `e_a sin α_g`.
fn stall_moment_and_drag_loads(strip: &Strip, sin_g: f64, sin_psi: f64) -> (Loads, Loads) {
    let qc = strip.dynamic_pressure() * strip.chord;
    (
        Loads {
            flap: 0.0,
            twist: -qc * strip.chord,
        },
        Loads {
            flap: qc * sin_psi,
            twist: -strip.ea_offset * qc * sin_g,
        },
    )
}

// ---------------------------------------------------------------------------------------------
// The rigid form: the paper's reduced model
// ---------------------------------------------------------------------------------------------

/// The paper's reduced ONERA model ("suitable for constant pitch motion", docs/model.md §5.3): every
/// state is driven by the rigid angle `α_r`, so the structure never feeds back into them; it
/// only enters the loads through `α_g = α_r − φ` in the moment arm.
pub mod rigid {
    use super::*;

    /// `[C1L, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`.
    pub const STATES: usize = 7;
    /// Index of the first-order lift state `C1L`.
    pub const C1L: usize = 0;
    /// Index of the first stall state (`C2L`).
    pub const STALL: usize = 1;

    /// State derivatives: `Ċ1L = λ_L ω_r (a_0L α_r − C1L)` and the stall block driven by `α_r`.
    pub fn rates(coef: &Coefficients, strip: &Strip, s: &[f64; STATES]) -> [f64; STATES] {
        let w = strip.omega_r();
        let mut out = [0.0; STATES];
        out[C1L] = coef.lambda_l * w * (coef.a0l * strip.alpha_r - s[C1L]);
        out[STALL..].copy_from_slice(&stall_rates(coef, w, strip.alpha_r, &s[STALL..]));
        out
    }

    /// `∂rates/∂states` (`jac[i][j] = ∂ṡ_i/∂s_j`): constant, and the rates depend on nothing else
    /// that moves.
    pub fn rate_jacobian(coef: &Coefficients, strip: &Strip) -> [[f64; STATES]; STATES] {
        let w = strip.omega_r();
        let mut jac = [[0.0; STATES]; STATES];
        jac[C1L][C1L] = -coef.lambda_l * w;
        stall_state_jacobian(coef, w, STALL, &mut jac);
        jac
    }

    /// The steady state: `C1L = a_0L α_r`, `C2X = −ΔC_X(α_r)`, rates zero.
    pub fn steady(coef: &Coefficients, strip: &Strip) -> [f64; STATES] {
        let mut s = [0.0; STATES];
        s[C1L] = coef.a0l * strip.alpha_r;
        s[STALL..].copy_from_slice(&stall_steady(coef, strip.alpha_r));
        s
    }

    /// Strip loads: `L = ½ρcV0²(C1L + C2L)`, `f_u = L cos ψ + D sin ψ`,
    /// `m_φ = −[M_c + e_a (L cos α_g + D sin α_g)]`, `α_g = α_r − φ`.
    pub fn loads(coef: &Coefficients, strip: &Strip, twist: f64, s: &[f64; STATES]) -> Loads {
        let qc = strip.dynamic_pressure() * strip.chord;
        let (l2, moment, drag) = stall_forces(coef, strip, &s[STALL..]);
        let lift = qc * s[C1L] + l2;
        let alpha_g = strip.alpha_r - twist;
        Loads {
            flap: lift * strip.psi.cos() + drag * strip.psi.sin(),
            twist: -(moment + strip.ea_offset * (lift * alpha_g.cos() + drag * alpha_g.sin())),
        }
    }

    /// Partial derivatives of [`loads`] with respect to the twist and the states.
    pub fn load_partials(
        coef: &Coefficients,
        strip: &Strip,
        twist: f64,
        s: &[f64; STATES],
    ) -> LoadPartials<STATES> {
        let qc = strip.dynamic_pressure() * strip.chord;
        let (l2, _, drag) = stall_forces(coef, strip, &s[STALL..]);
        let lift = qc * s[C1L] + l2;
        let (sin_g, cos_g) = (strip.alpha_r - twist).sin_cos();
        let (sin_psi, cos_psi) = strip.psi.sin_cos();
        let e = strip.ea_offset;
        let lift_load = Loads {
            flap: qc * cos_psi,
            twist: -e * qc * cos_g,
        };
        let mut states = [Loads::default(); STATES];
        states[C1L] = lift_load;
        states[STALL] = lift_load;
        (states[STALL + 2], states[STALL + 4]) = stall_moment_and_drag_loads(strip, sin_g, sin_psi);
        LoadPartials {
            // dα_g/dφ = −1: d(cos α_g)/dφ = sin α_g, d(sin α_g)/dφ = −cos α_g.
            twist: Loads {
                flap: 0.0,
                twist: -e * (lift * sin_g - drag * cos_g),
            },
            states,
            ..LoadPartials::default()
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The coupled form: §5.2 attached flow plus stall states on the downwash angle
// ---------------------------------------------------------------------------------------------

/// Stall flutter proper (docs/model.md §5.3, `forcing = "coupled"`): the attached flow of §5.2
/// exactly (two Jones lags on the three-quarter-chord downwash, apparent mass, pitch-rate terms)
/// plus the second-order stall states driven by `α = w/V0`.
pub mod coupled {
    use super::*;
    use std::f64::consts::PI;

    /// `[z1, z2, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`.
    pub const STATES: usize = 8;
    /// Index of the first Jones lag state `z1` (`z2` follows).
    pub const LAG: usize = 0;
    /// Index of the first stall state (`C2L`).
    pub const STALL: usize = 2;

    /// Three-quarter-chord downwash `w = V0(α_r − φ) − u̇ cos ψ − b(½ − a) φ̇` (docs/model.md §5.2).
    pub fn downwash(strip: &Strip, motion: &Motion) -> f64 {
        let g = downwash_partials(strip);
        strip.v0 * strip.alpha_r
            + g.twist * motion.twist
            + g.twist_rate * motion.twist_rate
            + g.flap_rate * motion.flap_rate
    }

    /// `∂w/∂(motion)`, constant: `∂w/∂φ = −V0`, `∂w/∂φ̇ = −b(½ − a) = −(b − e_a)`,
    /// `∂w/∂u̇ = −cos ψ`; the accelerations do not enter.
    pub fn downwash_partials(strip: &Strip) -> Motion {
        Motion {
            twist: -strip.v0,
            twist_rate: -strip.semichord() * (0.5 - strip.theodorsen_a()),
            twist_accel: 0.0,
            flap_rate: -strip.psi.cos(),
            flap_accel: 0.0,
        }
    }

    /// State derivatives for downwash `w`: `ż_i = −ε_i (V0/b) z_i + w`, stall block on `w/V0`.
    pub fn rates(coef: &Coefficients, strip: &Strip, w: f64, s: &[f64; STATES]) -> [f64; STATES] {
        let omega_r = strip.omega_r();
        let mut out = [0.0; STATES];
        for (i, (_, eps)) in JONES.iter().enumerate() {
            out[LAG + i] = -eps * omega_r * s[LAG + i] + w;
        }
        let alpha = strip.downwash_angle(w);
        out[STALL..].copy_from_slice(&stall_rates(coef, omega_r, alpha, &s[STALL..]));
        out
    }

    /// `∂rates/∂states` (`jac[i][j] = ∂ṡ_i/∂s_j`), constant in the state.
    pub fn rate_jacobian(coef: &Coefficients, strip: &Strip) -> [[f64; STATES]; STATES] {
        let omega_r = strip.omega_r();
        let mut jac = [[0.0; STATES]; STATES];
        for (i, (_, eps)) in JONES.iter().enumerate() {
            jac[LAG + i][LAG + i] = -eps * omega_r;
        }
        stall_state_jacobian(coef, omega_r, STALL, &mut jac);
        jac
    }

    /// `∂rates/∂w`: 1 into each lag, and the deviation slopes over `V0` into the stall rates.
    pub fn rate_downwash_partial(coef: &Coefficients, strip: &Strip, w: f64) -> [f64; STATES] {
        let mut d = [0.0; STATES];
        d[LAG] = 1.0;
        d[LAG + 1] = 1.0;
        let da = stall_alpha_partial(coef, strip.omega_r(), strip.downwash_angle(w));
        let k = strip.downwash_angle_slope();
        for (out, v) in d[STALL..].iter_mut().zip(da) {
            *out = k * v;
        }
        d
    }

    /// The steady state under a constant downwash `w`: `z_i = w b/(ε_i V0)` (so `w_eff = w`),
    /// `C2X = −ΔC_X(w/V0)`, rates zero. In still air the lags have no steady state and are 0.
    pub fn steady(coef: &Coefficients, strip: &Strip, w: f64) -> [f64; STATES] {
        let mut s = [0.0; STATES];
        let lag = lag_steady_per_downwash(strip);
        s[LAG] = lag[0] * w;
        s[LAG + 1] = lag[1] * w;
        s[STALL..].copy_from_slice(&stall_steady(coef, strip.downwash_angle(w)));
        s
    }

    /// `d(steady state)/dw`, for the equilibrium Newton's reduced Jacobian (docs/model.md §6).
    pub fn steady_downwash_partial(coef: &Coefficients, strip: &Strip, w: f64) -> [f64; STATES] {
        let mut d = [0.0; STATES];
        let lag = lag_steady_per_downwash(strip);
        d[LAG] = lag[0];
        d[LAG + 1] = lag[1];
        let ds = stall_steady_alpha_partial(coef, strip.downwash_angle(w));
        let k = strip.downwash_angle_slope();
        for (out, v) in d[STALL..].iter_mut().zip(ds) {
            *out = k * v;
        }
        d
    }

    /// `z_i / w` in steady flow: `b/(ε_i V0)` (0 in still air).
    fn lag_steady_per_downwash(strip: &Strip) -> [f64; 2] {
        let omega_r = strip.omega_r();
        JONES.map(|(_, eps)| {
            if omega_r > 0.0 {
                1.0 / (eps * omega_r)
            } else {
                0.0
            }
        })
    }

    /// Coefficients of the circulatory lift `L_c = ½ρ_a V0 c a_0L w_eff` on its inputs:
    /// `(∂L_c/∂w, [∂L_c/∂z1, ∂L_c/∂z2])`, with
    /// `w_eff = (1 − A1 − A2) w + (V0/b)(A1 ε1 z1 + A2 ε2 z2)`.
    fn circulatory_gains(coef: &Coefficients, strip: &Strip) -> (f64, [f64; 2]) {
        let k = 0.5 * strip.air_density * strip.v0 * strip.chord * coef.a0l;
        let a_sum: f64 = JONES.iter().map(|(a, _)| a).sum();
        let omega_r = strip.omega_r();
        (
            k * (1.0 - a_sum),
            JONES.map(|(a, eps)| k * omega_r * a * eps),
        )
    }

    /// Non-circulatory lift and moment coefficients on `(φ̇, φ̈, ü)` (docs/model.md §5.2, with
    /// `h = −u cos ψ`, `α_T = −φ`): `L_nc = πρb²(−ü cos ψ − V0 φ̇ + b a φ̈)` and the apparent-mass
    /// part of `M_T = πρb²(−b a ü cos ψ + V0 b(½ − a) φ̇ + b²(⅛ + a²) φ̈)`. Returned as
    /// `[(∂L_nc, ∂M_nc)/∂φ̇, /∂φ̈, /∂ü]`.
    fn apparent_mass_gains(strip: &Strip) -> [(f64, f64); 3] {
        let b = strip.semichord();
        let a = strip.theodorsen_a();
        let k = PI * strip.air_density * b * b;
        let cos_psi = strip.psi.cos();
        [
            (-k * strip.v0, k * strip.v0 * b * (0.5 - a)),
            (k * b * a, k * b * b * (0.125 + a * a)),
            (-k * cos_psi, -k * b * a * cos_psi),
        ]
    }

    /// Strip loads (docs/model.md §5.3 coupled): `f_u = (L_c + L_nc + L2) cos ψ + D sin ψ`,
    /// `m_φ = −[M_T + e_a L2 + M2 + e_a D sin α_g]` with `M_T = M_nc + e_a L_c`
    /// (`b(a + ½) = e_a`).
    pub fn loads(coef: &Coefficients, strip: &Strip, motion: &Motion, s: &[f64; STATES]) -> Loads {
        let (gw, gz) = circulatory_gains(coef, strip);
        let lift_c = gw * downwash(strip, motion) + gz[0] * s[LAG] + gz[1] * s[LAG + 1];
        let [rate, accel, flap_accel] = apparent_mass_gains(strip);
        let lift_nc = rate.0 * motion.twist_rate
            + accel.0 * motion.twist_accel
            + flap_accel.0 * motion.flap_accel;
        let moment_nc = rate.1 * motion.twist_rate
            + accel.1 * motion.twist_accel
            + flap_accel.1 * motion.flap_accel;
        let (l2, m2, drag) = stall_forces(coef, strip, &s[STALL..]);
        let e = strip.ea_offset;
        let alpha_g = strip.alpha_r - motion.twist;
        Loads {
            flap: (lift_c + lift_nc + l2) * strip.psi.cos() + drag * strip.psi.sin(),
            twist: -(moment_nc + e * (lift_c + l2) + m2 + e * drag * alpha_g.sin()),
        }
    }

    /// Partial derivatives of [`loads`] with respect to the motion and the states. Those on
    /// `φ̈, ü` are the apparent mass (constant), those on `φ̇, u̇` aerodynamic damping.
    pub fn load_partials(
        coef: &Coefficients,
        strip: &Strip,
        motion: &Motion,
        s: &[f64; STATES],
    ) -> LoadPartials<STATES> {
        let (gw, gz) = circulatory_gains(coef, strip);
        let [rate, accel, flap_accel] = apparent_mass_gains(strip);
        let (sin_psi, cos_psi) = strip.psi.sin_cos();
        let (sin_g, cos_g) = (strip.alpha_r - motion.twist).sin_cos();
        let (_, _, drag) = stall_forces(coef, strip, &s[STALL..]);
        let e = strip.ea_offset;
        let qc = strip.dynamic_pressure() * strip.chord;
        // A unit of circulatory (or stall) lift: cos ψ downwind, arm e_a against feather.
        let lift_unit = Loads {
            flap: cos_psi,
            twist: -e,
        };
        let apparent = |(l, m): (f64, f64)| Loads {
            flap: l * cos_psi,
            twist: -m,
        };
        let dw = downwash_partials(strip);
        let through_downwash = |dw_dx: f64| lift_unit.scaled(gw * dw_dx);
        let twist_c = through_downwash(dw.twist);
        let rate_c = through_downwash(dw.twist_rate);
        let rate_nc = apparent(rate);
        let mut states = [Loads::default(); STATES];
        states[LAG] = lift_unit.scaled(gz[0]);
        states[LAG + 1] = lift_unit.scaled(gz[1]);
        states[STALL] = lift_unit.scaled(qc);
        (states[STALL + 2], states[STALL + 4]) = stall_moment_and_drag_loads(strip, sin_g, sin_psi);
        LoadPartials {
            // dα_g/dφ = −1 in the drag's arm: d(sin α_g)/dφ = −cos α_g.
            twist: Loads {
                flap: twist_c.flap,
                twist: twist_c.twist + e * drag * cos_g,
            },
            twist_rate: Loads {
                flap: rate_c.flap + rate_nc.flap,
                twist: rate_c.twist + rate_nc.twist,
            },
            twist_accel: apparent(accel),
            flap_rate: through_downwash(dw.flap_rate),
            flap_accel: apparent(flap_accel),
            states,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The strip model the system assembles (`aero.model = "onera"`)
// ---------------------------------------------------------------------------------------------

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
