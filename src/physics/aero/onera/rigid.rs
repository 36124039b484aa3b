//! The paper's reduced ONERA model ("suitable for constant pitch motion", docs/model.md §5.3): every
//! state is driven by the rigid angle `α_r`, so the structure never feeds back into them; it
//! only enters the loads through `α_g = α_r − φ` in the moment arm.

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
