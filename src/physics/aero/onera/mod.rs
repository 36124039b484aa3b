//! ONERA stall aerodynamics of one strip (docs/model.md §5.3; paper Eqs. 4–6).
//!
//! Everything here is a pure function of one strip: the piecewise stall deviations `ΔC_X(α)`
//! with their slopes, the state derivatives of both forms with their partial derivatives (for the
//! analytic Jacobian of docs/model.md §6), the steady states, and the strip loads `f_u`, `m_φ` with
//! their partial derivatives. Spanwise sums and basis functions belong to the caller (the
//! system's projection, §6). [`OneraModel`] wraps these functions as the system's
//! [`StripModel`](crate::physics::aero::StripModel), including where the model is nonlinear
//! ([`NonlinearSupport`](crate::physics::aero::NonlinearSupport), for the time stepper of §7).
//!
//! Files: this one holds what both forms share (coefficients, stall deviations, the strip, the
//! second-order stall states); [`rigid`] and [`coupled`] are the two forms, `model.rs` the strip
//! model.
//!
//! State layout per station (docs/model.md §5.3):
//! - `rigid` (7): `[C1L, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`, driven by the rigid angle `α_r`;
//! - `coupled` (8): `[z1, z2, C2L, Ċ2L, C2M, Ċ2M, C2D, Ċ2D]`, the two R.T. Jones lags of §5.2 on
//!   the three-quarter-chord downwash `w`, and the stall states driven by `α = w/V0`.
//!
//! The pitching moment coefficient `C_M0` enters both forms (docs/model.md writes it only in the rigid
//! form; with its default 0 the coupled form still differs from `theodorsen` only by drag, and a
//! preset that sets `aero.onera.cm0` sees it in the default form too).

pub mod coupled;
mod model;
pub mod rigid;

pub use model::OneraModel;

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
