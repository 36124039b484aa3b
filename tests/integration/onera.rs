//! ONERA stall aerodynamics of one strip (docs/model.md §5.3): the static curves, the steady states,
//! both forms' state derivatives and loads, and every analytic partial derivative against central
//! differences.

use flutterscope::model::aero::onera_coefficients;
use flutterscope::physics::aero::onera::{
    self, coupled, rigid, Coefficients, Motion, Regime, Strip,
};
use flutterscope::preset::{Onera, OneraForcing};

/// docs/model.md §5.3 defaults, through the preset so the conversion is covered too.
fn defaults() -> Coefficients {
    onera_coefficients(&Onera::default())
}

/// The paper's section at its operating point: tip V0 and ψ at U = 20 m/s, 60 rpm, L = 8.4455 m.
fn paper_strip(alpha_r: f64) -> Strip {
    let omega_r = 2.0 * std::f64::consts::PI * 8.4455;
    Strip {
        air_density: 1.225,
        v0: 20.0f64.hypot(omega_r),
        psi: 20.0f64.atan2(omega_r),
        alpha_r,
        chord: 0.01833,
        ea_offset: -0.01833 / 4.0,
    }
}

/// The default stall onset α1 = 8° and full-stall angle α2 = 18° (docs/model.md §5.3; the paper's
/// 0.1396 and 0.3142 rad), in radians as the library converts them.
const A1: f64 = 8.0 * (std::f64::consts::PI / 180.0);
const A2: f64 = 18.0 * (std::f64::consts::PI / 180.0);

/// The static lift curve written out from docs/model.md §5.3 with the default numbers,
/// independently of the library: 2π α, minus 4.4 (|α| − α1) past stall onset, minus a further
/// 2.4 (|α| − α2) past full stall, odd in α.
fn static_lift_by_hand(alpha: f64) -> f64 {
    let m = alpha.abs();
    let deviation = 4.4 * (m - A1).max(0.0) + 2.4 * (m - A2).max(0.0);
    2.0 * std::f64::consts::PI * alpha - alpha.signum() * deviation
}

/// Angles across both breakpoints, both signs, including the breakpoints themselves.
const ANGLES: [f64; 13] = [
    0.0, 0.05, -0.05, A1, -A1, 0.2, -0.2, A2, -A2, 0.4, -0.4, 0.7, -0.7,
];

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn static_lift_curve_matches_model() {
    let coef = defaults();
    for alpha in ANGLES {
        let expected = static_lift_by_hand(alpha);
        assert!(
            close(coef.static_lift(alpha), expected, 1e-12),
            "α = {alpha}: {} vs {expected}",
            coef.static_lift(alpha)
        );
    }
    // Spot values: the curve's peak at α2 and its negative slope beyond.
    assert!(close(
        coef.static_lift(A2),
        2.0 * std::f64::consts::PI * A2 - 4.4 * (A2 - A1),
        1e-12
    ));
    assert!(coef.static_lift(0.5) < coef.static_lift(0.4));
}

/// With ψ = 0 the flap load is the lift itself, so `f_u / (½ρcV0²)` is the lift coefficient.
fn lift_coefficient_from_flap_load(strip: &Strip, flap: f64) -> f64 {
    flap / (strip.dynamic_pressure() * strip.chord)
}

#[test]
fn steady_lift_of_both_forms_is_the_static_curve() {
    let coef = defaults();
    for alpha in ANGLES {
        let strip = Strip {
            psi: 0.0,
            ..paper_strip(alpha)
        };
        // Rigid: the states settle on α_r, the twist does not change the lift.
        let s = rigid::steady(&coef, &strip);
        let loads = rigid::loads(&coef, &strip, 0.0, &s);
        let cl = lift_coefficient_from_flap_load(&strip, loads.flap);
        assert!(
            close(cl, static_lift_by_hand(alpha), 1e-12),
            "rigid α = {alpha}: C_L = {cl}"
        );

        // Coupled: at rest the downwash angle is α_r − φ; put the whole angle in α_r − φ with a
        // nonzero twist to check that the twist enters the angle, not only the arm.
        let twist = 0.03;
        let strip_c = Strip {
            alpha_r: alpha + twist,
            ..strip
        };
        let motion = Motion {
            twist,
            ..Motion::default()
        };
        let w = coupled::downwash(&strip_c, &motion);
        assert!(close(w / strip_c.v0, alpha, 1e-14));
        let s = coupled::steady(&coef, &strip_c, w);
        let loads = coupled::loads(&coef, &strip_c, &motion, &s);
        let cl = lift_coefficient_from_flap_load(&strip_c, loads.flap);
        assert!(
            close(cl, static_lift_by_hand(alpha), 1e-12),
            "coupled α = {alpha}: C_L = {cl}"
        );
    }
}

#[test]
fn steady_states_are_fixed_points() {
    let coef = defaults();
    for alpha in ANGLES {
        let strip = paper_strip(alpha);
        let s = rigid::steady(&coef, &strip);
        for (i, r) in rigid::rates(&coef, &strip, &s).iter().enumerate() {
            assert!(r.abs() < 1e-9, "rigid α = {alpha}: rate {i} = {r}");
        }
        let w = strip.v0 * alpha;
        let s = coupled::steady(&coef, &strip, w);
        for (i, r) in coupled::rates(&coef, &strip, w, &s).iter().enumerate() {
            assert!(r.abs() < 1e-9, "coupled α = {alpha}: rate {i} = {r}");
        }
        // The lags settle so that the effective downwash is the downwash itself.
        let z = &s[coupled::LAG..coupled::LAG + 2];
        let w_eff = (1.0 - 0.165 - 0.335) * w
            + strip.omega_r() * (0.165 * 0.0455 * z[0] + 0.335 * 0.3 * z[1]);
        assert!(close(w_eff, w, 1e-12));
    }
}

#[test]
fn deviations_are_odd_even_and_continuous() {
    let coef = defaults();
    for alpha in [0.05, A1, 0.2, A2, 0.5] {
        let p = coef.deviation(alpha);
        let n = coef.deviation(-alpha);
        assert_eq!(p.value[0], -n.value[0]);
        assert_eq!(p.value[1], -n.value[1]);
        assert_eq!(p.value[2], n.value[2]);
        assert_eq!(p.slope[0], n.slope[0]);
        assert_eq!(p.slope[2], -n.slope[2]);
    }
    for brk in [A1, A2] {
        let below = coef.deviation(brk - 1e-12);
        let above = coef.deviation(brk + 1e-12);
        for i in 0..3 {
            assert!((below.value[i] - above.value[i]).abs() < 1e-10);
        }
    }
    assert_eq!(coef.regime(0.1), Regime::Attached);
    assert_eq!(coef.regime(-0.2), Regime::Stalling);
    assert_eq!(coef.regime(0.35), Regime::Stalled);
    // Drag only grows: ΔC_D ≤ 0, the steady C2D = −ΔC_D ≥ 0.
    assert!(coef.deviation(0.3).value[2] < 0.0);
    assert!(close(
        coef.static_drag(0.3),
        0.014 + 0.5 * 0.09 + 2.0 * 0.027,
        1e-12
    ));
    assert!(close(coef.static_moment(0.2), -0.15 * (0.2 - A1), 1e-12));
}

#[test]
fn deviation_slopes_match_central_differences() {
    let coef = Coefficients {
        drag_polynomial: (0.3, 0.5, 2.0),
        ..defaults()
    };
    let h = 1e-7;
    // Away from the breakpoints (and from the |α| kink of the drag at 0).
    for alpha in [0.02, -0.07, 0.2, -0.25, 0.45, -0.9] {
        let d = coef.deviation(alpha);
        for i in 0..3 {
            let fd = (coef.deviation(alpha + h).value[i] - coef.deviation(alpha - h).value[i])
                / (2.0 * h);
            assert!(
                close(d.slope[i], fd, 1e-6),
                "α = {alpha}, channel {i}: {} vs {fd}",
                d.slope[i]
            );
        }
    }
}

/// A generic central-difference check: `f(x)` vs the analytic partial `d` along coordinate `k`.
fn check_partial(what: &str, analytic: f64, f: impl Fn(f64) -> f64, x0: f64, scale: f64) {
    let h = 1e-6 * x0.abs().max(scale);
    let fd = (f(x0 + h) - f(x0 - h)) / (2.0 * h);
    assert!(
        (analytic - fd).abs() <= 1e-6 * analytic.abs().max(fd.abs()).max(1e-3),
        "{what}: analytic {analytic:e} vs central difference {fd:e}"
    );
}

/// A stalled, moving state with every coefficient active.
fn busy_coefficients() -> Coefficients {
    Coefficients {
        cm0: -0.02,
        drag_polynomial: (0.1, 0.5, 2.0),
        ..defaults()
    }
}

#[test]
fn coupled_rate_jacobian_matches_central_differences() {
    let coef = busy_coefficients();
    let strip = paper_strip(0.3);
    let s0 = [1e-4, -2e-5, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    for w in [0.05 * strip.v0, 0.25 * strip.v0, -0.4 * strip.v0] {
        let jac = coupled::rate_jacobian(&coef, &strip);
        for (i, row) in jac.iter().enumerate() {
            for (j, d) in row.iter().enumerate() {
                check_partial(
                    &format!("coupled ∂ṡ{i}/∂s{j} at w = {w}"),
                    *d,
                    |x| {
                        let mut s = s0;
                        s[j] = x;
                        coupled::rates(&coef, &strip, w, &s)[i]
                    },
                    s0[j],
                    1e-3,
                );
            }
        }
        let dw = coupled::rate_downwash_partial(&coef, &strip, w);
        for (i, d) in dw.iter().enumerate() {
            check_partial(
                &format!("coupled ∂ṡ{i}/∂w at w = {w}"),
                *d,
                |x| coupled::rates(&coef, &strip, x, &s0)[i],
                w,
                1.0,
            );
        }
        let ds = coupled::steady_downwash_partial(&coef, &strip, w);
        for (i, d) in ds.iter().enumerate() {
            check_partial(
                &format!("coupled d(steady s{i})/dw at w = {w}"),
                *d,
                |x| coupled::steady(&coef, &strip, x)[i],
                w,
                1.0,
            );
        }
    }
}

#[test]
fn rigid_rate_jacobian_matches_central_differences() {
    let coef = busy_coefficients();
    let strip = paper_strip(0.25);
    let s0 = [0.9, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    let jac = rigid::rate_jacobian(&coef, &strip);
    for (i, row) in jac.iter().enumerate() {
        for (j, d) in row.iter().enumerate() {
            check_partial(
                &format!("rigid ∂ṡ{i}/∂s{j}"),
                *d,
                |x| {
                    let mut s = s0;
                    s[j] = x;
                    rigid::rates(&coef, &strip, &s)[i]
                },
                s0[j],
                1e-3,
            );
        }
    }
}

#[test]
fn coupled_load_partials_match_central_differences() {
    let coef = busy_coefficients();
    let strip = paper_strip(0.3);
    let s0 = [1e-4, -2e-5, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    let m0 = Motion {
        twist: 0.04,
        twist_rate: 2.0,
        twist_accel: -300.0,
        flap_rate: 0.3,
        flap_accel: 5.0,
    };
    let p = coupled::load_partials(&coef, &strip, &m0, &s0);
    type Setter = fn(&mut Motion, f64);
    let motion_axes: [(&str, onera::Loads, f64, Setter); 5] = [
        ("φ", p.twist, m0.twist, |m, v| m.twist = v),
        ("φ̇", p.twist_rate, m0.twist_rate, |m, v| m.twist_rate = v),
        ("φ̈", p.twist_accel, m0.twist_accel, |m, v| {
            m.twist_accel = v
        }),
        ("u̇", p.flap_rate, m0.flap_rate, |m, v| m.flap_rate = v),
        ("ü", p.flap_accel, m0.flap_accel, |m, v| m.flap_accel = v),
    ];
    for (name, d, x0, set) in motion_axes {
        let eval = |x: f64| {
            let mut m = m0;
            set(&mut m, x);
            coupled::loads(&coef, &strip, &m, &s0)
        };
        check_partial(&format!("∂f_u/∂{name}"), d.flap, |x| eval(x).flap, x0, 1e-2);
        check_partial(
            &format!("∂m_φ/∂{name}"),
            d.twist,
            |x| eval(x).twist,
            x0,
            1e-2,
        );
    }
    for j in 0..coupled::STATES {
        let eval = |x: f64| {
            let mut s = s0;
            s[j] = x;
            coupled::loads(&coef, &strip, &m0, &s)
        };
        check_partial(
            &format!("∂f_u/∂s{j}"),
            p.states[j].flap,
            |x| eval(x).flap,
            s0[j],
            1e-3,
        );
        check_partial(
            &format!("∂m_φ/∂s{j}"),
            p.states[j].twist,
            |x| eval(x).twist,
            s0[j],
            1e-3,
        );
    }
}

#[test]
fn rigid_load_partials_match_central_differences() {
    let coef = busy_coefficients();
    let strip = paper_strip(0.25);
    let s0 = [0.9, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    let twist = 0.1;
    let p = rigid::load_partials(&coef, &strip, twist, &s0);
    check_partial(
        "rigid ∂f_u/∂φ",
        p.twist.flap,
        |x| rigid::loads(&coef, &strip, x, &s0).flap,
        twist,
        1e-2,
    );
    check_partial(
        "rigid ∂m_φ/∂φ",
        p.twist.twist,
        |x| rigid::loads(&coef, &strip, x, &s0).twist,
        twist,
        1e-2,
    );
    for j in 0..rigid::STATES {
        let eval = |x: f64| {
            let mut s = s0;
            s[j] = x;
            rigid::loads(&coef, &strip, twist, &s)
        };
        check_partial(
            &format!("rigid ∂f_u/∂s{j}"),
            p.states[j].flap,
            |x| eval(x).flap,
            s0[j],
            1e-3,
        );
        check_partial(
            &format!("rigid ∂m_φ/∂s{j}"),
            p.states[j].twist,
            |x| eval(x).twist,
            s0[j],
            1e-3,
        );
    }
    // The rigid form has no aerodynamic damping or apparent mass.
    assert_eq!(p.twist_rate, onera::Loads::default());
    assert_eq!(p.flap_accel, onera::Loads::default());
}

/// Theodorsen's loads (docs/model.md §5.2) transcribed in its own variables `h = −u cos ψ`, `α_T = −φ`,
/// independently of the library's rearrangement.
fn theodorsen_by_hand(strip: &Strip, m: &Motion, z: [f64; 2], a0: f64) -> (f64, f64) {
    let pi = std::f64::consts::PI;
    let rho = strip.air_density;
    let v = strip.v0;
    let b = strip.chord / 2.0;
    let a = strip.ea_offset / b - 0.5;
    let h_dd = -m.flap_accel * strip.psi.cos();
    let (at_d, at_dd) = (-m.twist_rate, -m.twist_accel);
    let w = v * (strip.alpha_r - m.twist)
        - m.flap_rate * strip.psi.cos()
        - b * (0.5 - a) * m.twist_rate;
    let w_eff = (1.0 - 0.165 - 0.335) * w + (v / b) * (0.165 * 0.0455 * z[0] + 0.335 * 0.3 * z[1]);
    let lc = 0.5 * rho * v * strip.chord * a0 * w_eff;
    let lnc = pi * rho * b * b * (h_dd + v * at_d - b * a * at_dd);
    let mt = pi
        * rho
        * b
        * b
        * (b * a * h_dd - v * b * (0.5 - a) * at_d - b * b * (0.125 + a * a) * at_dd)
        + b * (a + 0.5) * lc;
    ((lc + lnc) * strip.psi.cos(), -mt)
}

#[test]
fn coupled_below_stall_without_drag_is_theodorsen() {
    let coef = Coefficients {
        cd0: 0.0,
        drag_polynomial: (0.0, 0.0, 0.0),
        ..defaults()
    };
    let strip = paper_strip(0.12);
    let motion = Motion {
        twist: 0.02,
        twist_rate: 1.5,
        twist_accel: -200.0,
        flap_rate: -0.4,
        flap_accel: 3.0,
    };
    let w = coupled::downwash(&strip, &motion);
    assert_eq!(coef.regime(strip.downwash_angle(w)), Regime::Attached);
    // Lags away from steady, stall states at their (zero) steady values below stall.
    let s = [3e-4, -1e-4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let loads = coupled::loads(&coef, &strip, &motion, &s);
    let (f, m) = theodorsen_by_hand(&strip, &motion, [s[0], s[1]], coef.a0l);
    assert!(close(loads.flap, f, 1e-12), "f_u {} vs {f}", loads.flap);
    assert!(close(loads.twist, m, 1e-12), "m_φ {} vs {m}", loads.twist);
    // And the stall states stay at rest there.
    let r = coupled::rates(&coef, &strip, w, &s);
    assert!(r[coupled::STALL..].iter().all(|v| *v == 0.0));
}

#[test]
fn rigid_states_ignore_the_structure_and_loads_use_the_geometric_arm() {
    let coef = busy_coefficients();
    let strip = paper_strip(0.25);
    let s = [0.9, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    // The rates take no motion at all: only α_r drives them, so they equal the steady-state
    // relaxation whatever the blade does. Check the forcing uses α_r.
    let r = rigid::rates(&coef, &strip, &s);
    let w = strip.omega_r();
    assert!(close(
        r[rigid::C1L],
        0.17 * w * (coef.a0l * 0.25 - 0.9),
        1e-12
    ));
    let dl = 4.4 * (0.25 - A1);
    assert!(close(
        r[rigid::STALL + 1],
        -0.30 * w * 40.0 - 0.0324 * w * w * (-0.3 + dl),
        1e-12
    ));
    // Loads written out: L = qc(C1L + C2L), D = qc(C_D0 + C2D), M = qc²(C_M0 + C2M).
    let twist = 0.1;
    let qc = strip.dynamic_pressure() * strip.chord;
    let (lift, drag, moment) = (
        qc * (0.9 - 0.3),
        qc * (0.014 + 0.06),
        qc * strip.chord * (-0.02 - 0.05),
    );
    let ag: f64 = 0.25 - twist;
    let loads = rigid::loads(&coef, &strip, twist, &s);
    assert!(close(
        loads.flap,
        lift * strip.psi.cos() + drag * strip.psi.sin(),
        1e-12
    ));
    let m = -(moment + strip.ea_offset * (lift * ag.cos() + drag * ag.sin()));
    assert!(close(loads.twist, m, 1e-12));
}

#[test]
fn state_counts() {
    assert_eq!(onera::states_per_station(OneraForcing::Rigid), 7);
    assert_eq!(onera::states_per_station(OneraForcing::Coupled), 8);
}

// ---------------------------------------------------------------------------------------------
// The model as the system sees it (`StripModel`)
// ---------------------------------------------------------------------------------------------

use flutterscope::physics::aero::onera::OneraModel;
use flutterscope::physics::aero::theodorsen::Theodorsen;
use flutterscope::physics::aero::{Kinematics, SteadyStates, StripEval, StripModel, StripSection};
use flutterscope::physics::inflow::Station;

fn paper_station(alpha_r: f64) -> Station {
    let s = paper_strip(alpha_r);
    Station {
        index: 0,
        x: 6.0,
        weight: 0.7,
        radius: 6.0,
        v0: s.v0,
        psi: s.psi,
        alpha_r,
    }
}

fn paper_section() -> StripSection {
    StripSection {
        chord: 0.01833,
        ea_offset: -0.01833 / 4.0,
        air_density: 1.225,
        lift_slope: 2.0 * std::f64::consts::PI,
        drag_coefficient: 0.0,
    }
}

fn model(forcing: OneraForcing, coef: Coefficients) -> OneraModel {
    OneraModel::new(paper_section(), coef, forcing)
}

/// Every partial the model reports (loads and rates on kinematics and states) against central
/// differences of its own values.
fn check_model_jacobian(m: &OneraModel, st: &Station, k: Kinematics, z: &[f64]) {
    let ns = m.states_per_station();
    let mut exact = StripEval::new(ns);
    m.evaluate(st, &k, z, &mut exact, true);
    let eval = |k: Kinematics, z: &[f64]| {
        let mut e = StripEval::new(ns);
        m.evaluate(st, &k, z, &mut e, false);
        e
    };
    type KSet = fn(&mut Kinematics, f64);
    // (setter, value, index in the interface's [φ, u, v, φ̇, u̇, v̇]); the paper's blade has no edge.
    let axes: [(KSet, f64, usize); 4] = [
        (|k, v| k.phi = v, k.phi, 0),
        (|k, v| k.u = v, k.u, 1),
        (|k, v| k.phi_dot = v, k.phi_dot, 3),
        (|k, v| k.u_dot = v, k.u_dot, 4),
    ];
    for (set, x0, j) in axes {
        let at = |x: f64| {
            let mut kk = k;
            set(&mut kk, x);
            eval(kk, z)
        };
        for l in 0..3 {
            check_partial(
                &format!("{} ∂load{l}/∂k{j}", m.name()),
                exact.dloads_dk[l][j],
                |x| at(x).loads[l],
                x0,
                1e-2,
            );
        }
        for i in 0..ns {
            check_partial(
                &format!("∂ż{i}/∂k{j}"),
                exact.dzdot_dk[i][j],
                |x| at(x).zdot[i],
                x0,
                1e-2,
            );
        }
    }
    for j in 0..ns {
        let at = |x: f64| {
            let mut zz = z.to_vec();
            zz[j] = x;
            eval(k, &zz)
        };
        for l in 0..2 {
            check_partial(
                &format!("∂load{l}/∂z{j}"),
                exact.dloads_dz[l][j],
                |x| at(x).loads[l],
                z[j],
                1e-3,
            );
        }
        for i in 0..ns {
            check_partial(
                &format!("∂ż{i}/∂z{j}"),
                exact.dzdot_dz[i * ns + j],
                |x| at(x).zdot[i],
                z[j],
                1e-3,
            );
        }
    }
}

#[test]
fn strip_model_jacobians_match_central_differences() {
    let k = Kinematics {
        phi: 0.04,
        u: 0.3,
        phi_dot: 2.0,
        u_dot: 0.3,
        ..Kinematics::default()
    };
    let st = paper_station(0.3);
    let coupled_z = [1e-4, -2e-5, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    check_model_jacobian(
        &model(OneraForcing::Coupled, busy_coefficients()),
        &st,
        k,
        &coupled_z,
    );
    let rigid_z = [0.9, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    check_model_jacobian(
        &model(OneraForcing::Rigid, busy_coefficients()),
        &st,
        k,
        &rigid_z,
    );
}

#[test]
fn strip_model_steady_states_are_fixed_points_with_exact_slopes() {
    for forcing in [OneraForcing::Coupled, OneraForcing::Rigid] {
        let m = model(forcing, busy_coefficients());
        let ns = m.states_per_station();
        let st = paper_station(0.3);
        for phi in [-0.2, 0.0, 0.1, 0.2, 0.4] {
            let mut steady = SteadyStates::new(ns);
            m.steady_states(&st, [phi, 0.1, 0.0], &mut steady);
            let mut e = StripEval::new(ns);
            let k = Kinematics {
                phi,
                u: 0.1,
                ..Kinematics::default()
            };
            m.evaluate(&st, &k, &steady.z, &mut e, false);
            assert!(
                e.zdot.iter().all(|r| r.abs() < 1e-9),
                "{forcing:?} φ = {phi}: ż = {:?}",
                e.zdot
            );
            for i in 0..ns {
                check_partial(
                    &format!("{forcing:?} dz{i}/dφ at φ = {phi}"),
                    steady.dz_dk[i][0],
                    |x| {
                        let mut s = SteadyStates::new(ns);
                        m.steady_states(&st, [x, 0.1, 0.0], &mut s);
                        s.z[i]
                    },
                    phi,
                    1e-2,
                );
                assert_eq!(steady.dz_dk[i][1..], [0.0, 0.0]);
            }
        }
    }
}

#[test]
fn coupled_model_below_stall_without_drag_equals_theodorsen_model() {
    let coef = Coefficients {
        cd0: 0.0,
        drag_polynomial: (0.0, 0.0, 0.0),
        ..defaults()
    };
    let m = model(OneraForcing::Coupled, coef);
    let t = Theodorsen::new(paper_section());
    let st = paper_station(0.1);
    assert_eq!(m.apparent_mass(&st), t.apparent_mass(&st));
    let k = Kinematics {
        phi: 0.02,
        u: 0.5,
        phi_dot: 1.0,
        u_dot: -0.3,
        ..Kinematics::default()
    };
    let z = [2e-4, -1e-4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let (mut eo, mut et) = (StripEval::new(8), StripEval::new(2));
    m.evaluate(&st, &k, &z, &mut eo, true);
    t.evaluate(&st, &k, &z[..2], &mut et, true);
    for l in 0..2 {
        assert!(close(eo.loads[l], et.loads[l], 1e-12), "load {l}");
        for j in 0..4 {
            assert!(
                close(eo.dloads_dk[l][j], et.dloads_dk[l][j], 1e-12),
                "∂load{l}/∂k{j}"
            );
        }
    }
    assert!(close(eo.zdot[0], et.zdot[0], 1e-12) && close(eo.zdot[1], et.zdot[1], 1e-12));
    // The rigid form has no apparent mass.
    assert_eq!(
        model(OneraForcing::Rigid, defaults()).apparent_mass(&st),
        [[0.0; 3]; 3]
    );
}

#[test]
fn rigid_model_rates_do_not_depend_on_the_structure() {
    let m = model(OneraForcing::Rigid, busy_coefficients());
    let st = paper_station(0.25);
    let z = [0.9, -0.3, 40.0, -0.05, 3.0, 0.06, -7.0];
    let mut a = StripEval::new(7);
    m.evaluate(&st, &Kinematics::default(), &z, &mut a, true);
    let mut b = StripEval::new(7);
    let k = Kinematics {
        phi: 0.3,
        u: 1.0,
        phi_dot: -5.0,
        u_dot: 2.0,
        ..Kinematics::default()
    };
    m.evaluate(&st, &k, &z, &mut b, true);
    assert_eq!(a.zdot, b.zdot);
    assert!(b.dzdot_dk.iter().all(|row| row.iter().all(|v| *v == 0.0)));
}

#[test]
fn steady_moment_of_both_forms_follows_the_static_curves() {
    let coef = busy_coefficients();
    for alpha in ANGLES {
        let strip = paper_strip(alpha);
        let qc = strip.dynamic_pressure() * strip.chord;
        let e = strip.ea_offset;
        // Written out from docs/model.md §5.3: C_L, C_M = C_M0 − ΔC_M, C_D = C_D0 − ΔC_D on the
        // static curves; the lift acts at the aerodynamic centre, so its arm is e_a.
        let dev = |a: f64| {
            let m = a.abs();
            let lm = 0.15 * (m - A1).max(0.0) + 0.6 * (m - A2).max(0.0);
            let d = -0.1 * m - 0.5 * a * a - 2.0 * m * m * m;
            (a.signum() * lm, d)
        };
        let (dm, dd) = dev(alpha);
        let (cl, cm, cd) = (static_lift_by_hand(alpha), -0.02 - dm, 0.014 - dd);
        // Rigid at zero twist: α_g = α_r.
        let s = rigid::steady(&coef, &strip);
        let m_rigid = rigid::loads(&coef, &strip, 0.0, &s).twist;
        let expect = -qc * (strip.chord * cm + e * (cl * alpha.cos() + cd * alpha.sin()));
        assert!(
            close(m_rigid, expect, 1e-12),
            "rigid α = {alpha}: {m_rigid} vs {expect}"
        );
        // Coupled at rest: the attached lift enters linearly (no cos α_g), drag through sin α_g.
        let w = strip.v0 * alpha;
        let s = coupled::steady(&coef, &strip, w);
        let m_coupled = coupled::loads(&coef, &strip, &Motion::default(), &s).twist;
        let expect = -qc * (strip.chord * cm + e * (cl + cd * alpha.sin()));
        assert!(
            close(m_coupled, expect, 1e-12),
            "coupled α = {alpha}: {m_coupled} vs {expect}"
        );
    }
}
