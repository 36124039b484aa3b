//! Stall flutter proper (docs/model.md §5.3, `forcing = "coupled"`): the attached flow of §5.2
//! exactly (two Jones lags on the three-quarter-chord downwash, apparent mass, pitch-rate terms)
//! plus the second-order stall states driven by `α = w/V0`.

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
