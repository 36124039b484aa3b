//! Stall flutter and time responses (docs/model.md §5.3, §6, §7): the ONERA model in the
//! system (equilibrium, Jacobian, eigenvalues, agreement with Theodorsen below stall), the
//! exponential stepper against exact and independent solutions, the rigid form's one-way
//! coupling, divergence handling, streaming, and the `simulate` command's JSON.

use assert_cmd::Command;
use flutterscope::analysis::eigen::{analyse, analyse_system, linear_system};
use flutterscope::analysis::flutter::{flutter_boundary, BoundaryKind};
use flutterscope::analysis::response::{simulate, simulator};
use flutterscope::analysis::simulate::RunStatus;
use flutterscope::analysis::sweep::track;
use flutterscope::numeric::phi_functions::propagators;
use flutterscope::physics::system::System;
use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::{DMatrix, DVector};

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

fn stall(overrides: &[&str]) -> ValidPreset {
    preset("liu2017-stall", overrides)
}

/// Largest relative difference between two matrices' entries, on the scale of the larger.
fn max_rel_diff(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    let scale = a.amax().max(b.amax());
    (a - b).amax() / scale
}

// ---------------------------------------------------------------------------------------------
// The ONERA model in the system (docs/model.md §5.3, §6)
// ---------------------------------------------------------------------------------------------

#[test]
fn paper_stall_case_reaches_equilibrium_and_is_stable_in_the_coupled_form() {
    let p = stall(&[]);
    let system = flutterscope::model::system(&p).unwrap();
    assert_static_equilibrium(&system);
    let lin = linear_system(&p).unwrap();
    let (twist, flap) = lin.tip_at(&lin.x_eq, 0.0);
    // The aerodynamic torsional stiffness dominates the soft blade: the tip twists toward
    // feather almost to zero angle of attack (α_r = 10.65°), below stall.
    let alpha_r = system.stations()[0].alpha_r;
    assert!(
        (alpha_r - twist).abs() < 0.02,
        "tip twist {twist}, α_r {alpha_r}"
    );
    assert!(flap > 0.0 && flap < p.blade.length, "tip flap {flap}");
    let s = analyse_system(&lin).unwrap();
    assert!(s.stable, "largest σ = {}", s.max_re());
    assert!(s.max_re() < -0.5);
}

/// The paper's reduced model has no aerodynamic torsional stiffness: Newton from the unloaded
/// blade stalls on the soft blade's lift at α_r, and the load continuation (docs/model.md §12.6)
/// follows the branch to the full load: the state it returns is a static equilibrium.
#[test]
fn load_continuation_reaches_the_soft_stall_blades_equilibrium() {
    let p = stall(&["aero.onera.forcing=rigid"]);
    let system = flutterscope::model::system(&p).unwrap();
    assert_static_equilibrium(&system);
}

/// The system's equilibrium is static: q̇ = 0 and every rate vanishes, on the scale of the
/// rigid load.
fn assert_static_equilibrium(system: &System) {
    let x = system.equilibrium().unwrap();
    let residual = system.rhs(&x).amax();
    let rigid_load = system.rhs(&DVector::zeros(system.dim())).amax();
    assert!(
        residual <= 1e-9 * rigid_load,
        "‖f(x*)‖ = {residual:e} vs {rigid_load:e}"
    );
}

/// A state away from equilibrium with stations on every piece of the deviation laws.
fn busy_state(system: &System, x_eq: &DVector<f64>) -> DVector<f64> {
    let n = system.dim();
    let nq = system.nq();
    DVector::from_fn(n, |i, _| {
        let wobble = ((i as f64) * 1.7).sin();
        x_eq[i]
            + match i {
                i if i < nq => 0.03 * wobble,    // deflections
                i if i < 2 * nq => 2.0 * wobble, // rates
                _ => 0.05 * wobble * (1.0 + x_eq[i].abs()),
            }
    })
}

#[test]
fn state_jacobian_matches_central_differences() {
    for forcing in ["coupled", "rigid"] {
        let p = stall(&[
            &format!("aero.onera.forcing={forcing}"),
            "operating.pitch=2",
        ]);
        let system = flutterscope::model::system(&p).unwrap();
        let x_eq = system
            .equilibrium()
            .unwrap_or_else(|_| DVector::zeros(system.dim()));
        let x = busy_state(&system, &x_eq);
        let exact = system.jacobian(&x);
        let n = system.dim();
        let mut numeric = DMatrix::zeros(n, n);
        for j in 0..n {
            let h = 1e-7 * (1.0 + x[j].abs());
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[j] += h;
            xm[j] -= h;
            numeric.set_column(j, &((system.rhs(&xp) - system.rhs(&xm)) / (2.0 * h)));
        }
        let d = max_rel_diff(&exact, &numeric);
        assert!(d < 1e-6, "{forcing}: Jacobian mismatch {d:e}");
    }
}

#[test]
fn coupled_form_below_stall_has_theodorsens_eigenvalues() {
    // No drag, so the stall states carry nothing at an attached equilibrium: the structural
    // roots must be Theodorsen's exactly (docs/model.md §5.3).
    let no_drag = [
        "aero.onera.cd0=0",
        "aero.onera.a_d1=0",
        "aero.onera.a_d2=0",
        "aero.onera.a_d3=0",
    ];
    // Pitch 15°: α_r = 5.6°, every station attached (at 10° the inboard stations, which twist
    // little, sit past α1 at equilibrium).
    let attached = "operating.pitch=15";
    let mut o = no_drag.to_vec();
    o.push(attached);
    let onera = analyse(&stall(&o)).unwrap();
    let theodorsen = analyse(&stall(&["aero.model=theodorsen", attached])).unwrap();
    assert_eq!(onera.eigenvalues.len(), theodorsen.eigenvalues.len());
    for (a, b) in onera.eigenvalues.iter().zip(&theodorsen.eigenvalues) {
        let scale = a.re.hypot(a.im);
        assert!(
            (a.re - b.re).abs() <= 1e-7 * scale && (a.im - b.im).abs() <= 1e-7 * scale,
            "{} {}+{}i vs {} {}+{}i",
            a.label,
            a.re,
            a.im,
            b.label,
            b.re,
            b.im
        );
    }
    // With the default drag they differ, but only slightly.
    let with_drag = analyse(&stall(&[attached])).unwrap();
    let (a, b) = (&with_drag.eigenvalues[0], &theodorsen.eigenvalues[0]);
    assert!(a.re != b.re && (a.re - b.re).abs() < 0.1 * b.re.abs());
}

// ---------------------------------------------------------------------------------------------
// The stepper (docs/model.md §7)
// ---------------------------------------------------------------------------------------------

#[test]
fn propagators_match_the_matrix_exponential_and_phi_functions() {
    let p = stall(&[]);
    let a = linear_system(&p).unwrap().a;
    let h = 0.005;
    let props = propagators(&a, h, 3).unwrap();
    let n = a.nrows();
    let id = DMatrix::<f64>::identity(n, n);
    for (j, prop) in props.iter().enumerate() {
        let hj = h / f64::powi(2.0, j as i32);
        assert!((prop.h - hj).abs() < 1e-18);
        let exact = (&a * hj).exp();
        assert!(max_rel_diff(&prop.e, &exact) < 1e-10, "level {j}: e^(hA)");
        // A F1 = E − I and A F2 = F1 − h I define φ1, φ2.
        assert!(max_rel_diff(&(&a * &prop.f1), &(&prop.e - &id)) < 1e-10);
        assert!(max_rel_diff(&(&a * &prop.f2), &(&prop.f1 - &id * hj)) < 1e-10);
    }
}

#[test]
fn linear_response_matches_the_exact_exponential_solution() {
    let p = preset(
        "goland",
        &[
            "simulation.start=equilibrium",
            "simulation.kick_twist=1",
            "simulation.kick_flap=0.05",
        ],
    );
    let mut sim = simulator(&p).unwrap();
    let lin = sim.linear().clone();
    let y0 = sim.state() - &lin.x_eq;
    let samples = sim.advance(2001).unwrap();
    for k in [1usize, 7, 100, 1000, 2000] {
        let t = k as f64 / p.simulation.sample_rate;
        let x = &lin.x_eq + (&lin.a * t).exp() * &y0;
        let (twist, flap) = lin.tip_at(&x, 0.0);
        let s = samples[k];
        assert!((s.t - t).abs() < 1e-12);
        assert!(
            (s.tip_twist - twist).abs() <= 1e-9 * (1.0 + twist.abs()),
            "t = {t}: {} vs {twist}",
            s.tip_twist
        );
        assert!(
            (s.tip_flap - flap).abs() <= 1e-9 * (1.0 + flap.abs()),
            "t = {t}: {} vs {flap}",
            s.tip_flap
        );
    }
}

/// Exponential rate of a sampled oscillation of period `period`: least-squares slope of the log
/// of its largest magnitude in consecutive periods within `[t0, t1]` (robust to small
/// contributions of other roots and to the sampling phase).
fn envelope_rate(t: &[f64], v: &[f64], period: f64, t0: f64, t1: f64) -> f64 {
    let mut points = vec![];
    let mut start = t0;
    while start + period <= t1 {
        let peak = t
            .iter()
            .zip(v)
            .filter(|(t, _)| **t >= start && **t < start + period)
            .map(|(_, v)| v.abs())
            .fold(0.0, f64::max);
        points.push((start, peak.ln()));
        start += period;
    }
    assert!(points.len() >= 4, "too few periods: {}", points.len());
    let n = points.len() as f64;
    let (mt, ml) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, l)| (a + t / n, b + l / n));
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), (t, l)| {
        (a + (t - mt) * (l - ml), b + (t - mt) * (t - mt))
    });
    num / den
}

#[test]
fn linear_growth_rate_equals_the_largest_sigma() {
    // Goland above its flutter speed: the flutter root grows at the largest σ.
    let p = preset(
        "goland",
        &[
            "operating.tunnel_speed=139",
            "simulation.start=equilibrium",
            "simulation.kick_twist=1e-4",
            "simulation.duration=8",
            "simulation.sample_rate=2000",
        ],
    );
    let critical = analyse(&p).unwrap();
    let mode = critical.critical().unwrap();
    let (sigma, period) = (mode.re, 2.0 * std::f64::consts::PI / mode.im);
    assert!(sigma > 0.0);
    let r = simulate(&p).unwrap();
    assert_eq!(r.status, RunStatus::Ok);
    let lin = linear_system(&p).unwrap();
    let (twist_eq, _) = lin.tip_at(&lin.x_eq, 0.0);
    let dev: Vec<f64> = r.tip_twist.iter().map(|v| v - twist_eq).collect();
    let rate = envelope_rate(&r.t, &dev, period, 3.0, 8.0);
    assert!(
        (rate - sigma).abs() <= 0.02 * sigma,
        "measured {rate}, largest σ {sigma}"
    );
}

#[test]
fn stall_response_from_a_kick_decays_at_the_largest_sigma() {
    // Near the equilibrium every station stays on its linear piece, so the nonlinear stepper
    // must reproduce the linearisation's slowest root.
    let p = stall(&[
        "simulation.start=equilibrium",
        "simulation.kick_flap=0.01",
        "simulation.duration=6",
    ]);
    let stability = analyse(&p).unwrap();
    let mode = stability.critical().unwrap();
    let (sigma, period) = (mode.re, 2.0 * std::f64::consts::PI / mode.im);
    let r = simulate(&p).unwrap();
    let lin = linear_system(&p).unwrap();
    let (_, flap_eq) = lin.tip_at(&lin.x_eq, 0.0);
    let dev: Vec<f64> = r.tip_flap.iter().map(|v| v - flap_eq).collect();
    let rate = envelope_rate(&r.t, &dev, period, 1.0, 6.0);
    assert!(
        (rate - sigma).abs() <= 0.02 * sigma.abs(),
        "measured {rate}, largest σ {sigma}"
    );
}

/// Classical RK4 on the full right-hand side with a step far below every time scale: an
/// independent reference for the nonlinear stepper.
pub(crate) fn rk4_tip(
    system: &System,
    x0: &DVector<f64>,
    h: f64,
    every: usize,
    samples: usize,
) -> Vec<(f64, f64)> {
    let mut x = x0.clone();
    let mut out = vec![system.tip(&x)];
    for _ in 1..samples {
        for _ in 0..every {
            let k1 = system.rhs(&x);
            let k2 = system.rhs(&(&x + &k1 * (h / 2.0)));
            let k3 = system.rhs(&(&x + &k2 * (h / 2.0)));
            let k4 = system.rhs(&(&x + &k3 * h));
            x += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
        }
        out.push(system.tip(&x));
    }
    out
}

#[test]
fn stall_transient_from_rest_matches_a_fine_runge_kutta_reference() {
    // The load switched on at t = 0: the tip swings through stall at the torsion frequency
    // (~100 Hz) while sampled at 200 Hz.
    let p = stall(&["simulation.duration=0.1"]);
    let system = flutterscope::model::system(&p).unwrap();
    let reference = rk4_tip(&system, &DVector::zeros(system.dim()), 1e-5, 500, 21);
    let run = |tolerance: Option<f64>| {
        let mut sim = simulator(&p).unwrap();
        if let Some(tol) = tolerance {
            sim.set_tolerance(tol, tol * p.blade.length);
        }
        let samples = sim.advance(21).unwrap();
        let mut worst: (f64, f64) = (0.0, 0.0);
        for (s, (twist, flap)) in samples.iter().zip(&reference) {
            worst.0 = worst.0.max((s.tip_twist - twist).abs());
            worst.1 = worst.1.max((s.tip_flap - flap).abs());
        }
        (worst, sim.work().0)
    };
    // The twist swings by 0.3 rad here; the default tolerance keeps it within 1e-3 rad.
    let (default, steps) = run(None);
    assert!(
        default.0 < 1e-3 && default.1 < 1e-4,
        "largest difference: twist {:e} rad, flap {:e} m",
        default.0,
        default.1
    );
    // Substeps were used where the stall remainder is rough, but no collapse: at most
    // 2^6 steps per sample interval.
    assert!(steps > 20 && steps <= 20 * 64, "{steps} steps");
    // A tighter tolerance converges on the reference.
    let (tight, tight_steps) = run(Some(1e-7));
    assert!(
        tight.0 < 0.2 * default.0 && tight.0 < 5e-5,
        "tight: {tight:?}"
    );
    assert!(tight_steps > steps);
}

#[test]
fn rigid_forcing_leaves_the_aero_states_independent_of_the_structure() {
    // Pitch 20.5°: α_r = 0.15°, a small lift, so the rigid form's twist stays moderate (at the
    // paper's 10° it runs away, see below). Two different kicks give different structural
    // responses but identical aerodynamic states.
    let base = [
        "aero.onera.forcing=rigid",
        "operating.pitch=20.5",
        "simulation.duration=1",
    ];
    let run = |kick: &str| {
        let mut o: Vec<&str> = base.to_vec();
        o.push(kick);
        let mut sim = simulator(&stall(&o)).unwrap();
        let mut states = vec![];
        for _ in 0..100 {
            sim.advance(1).unwrap();
            assert_eq!(sim.status(), RunStatus::Ok);
            states.push(sim.state());
        }
        states
    };
    let (a, b) = (
        run("simulation.kick_twist=0"),
        run("simulation.kick_twist=5"),
    );
    let system = flutterscope::model::system(&stall(&base)).unwrap();
    let nq = system.nq();
    let mut structural_differs = false;
    for (xa, xb) in a.iter().zip(&b) {
        let za = xa.rows(2 * nq, system.n_aero());
        let zb = xb.rows(2 * nq, system.n_aero());
        assert!((za - zb).amax() <= 1e-12 * za.amax(), "aero states differ");
        structural_differs |= (xa.rows(0, nq) - xb.rows(0, nq)).amax() > 1e-6;
    }
    assert!(structural_differs);
    // The same in the Jacobian: the aero-state rows have no structural columns.
    let j = system.jacobian(&a[50]);
    assert_eq!(j.view((2 * nq, 0), (system.n_aero(), 2 * nq)).amax(), 0.0);
}

#[test]
fn diverging_stall_run_ends_cleanly() {
    // The paper's reduced model on the corrected (soft) blade: the twist runs away.
    let p = stall(&["aero.onera.forcing=rigid", "simulation.duration=20"]);
    let r = simulate(&p).unwrap();
    assert_eq!(r.status, RunStatus::Diverging);
    let t_end = r.diverged_at.unwrap();
    assert!(t_end < 1.0 && *r.t.last().unwrap() == t_end);
    assert!(r.tip_twist.iter().chain(&r.tip_flap).all(|v| v.is_finite()));
    assert!(
        r.tip_twist.last().unwrap().abs() > 1.0
            || r.tip_flap.last().unwrap().abs() > p.blade.length
    );
}

#[test]
fn streaming_equals_one_run_and_kicks_move_the_tip() {
    let p = stall(&[]);
    let mut a = simulator(&p).unwrap();
    let whole = a.advance(100).unwrap();
    let mut b = simulator(&p).unwrap();
    let mut parts = b.advance(37).unwrap();
    parts.extend(b.advance(63).unwrap());
    assert_eq!(whole, parts);
    let before = b.state();
    b.kick(0.01, 0.02);
    let (dt, du) = b.linear().tip_at(&(b.state() - before), 0.0);
    assert!((dt - 0.01).abs() < 1e-12 && (du - 0.02).abs() < 1e-12);
    // The kicked run goes on, and differs from the unkicked one.
    let next = b.advance(5).unwrap();
    let plain = a.advance(5).unwrap();
    assert_eq!(next.len(), 5);
    assert!(next
        .iter()
        .zip(&plain)
        .any(|(x, y)| x.tip_twist != y.tip_twist));
}

#[test]
fn every_model_simulates_and_the_json_has_the_documented_shape() {
    for model in ["none", "quasi-steady", "theodorsen", "onera"] {
        let out = Command::cargo_bin("flutterscope")
            .unwrap()
            .args([
                "simulate",
                "--preset",
                "liu2017-stall",
                "--set",
                &format!("aero.model={model}"),
                "--set",
                "simulation.duration=0.5",
                "--json",
            ])
            .assert()
            .success();
        let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
        assert_eq!(v["status"], "ok", "{model}");
        let len = v["t"].as_array().unwrap().len();
        assert_eq!(len, 101);
        for key in ["tip_twist", "tip_flap"] {
            let a = v[key].as_array().unwrap();
            assert_eq!(a.len(), len);
            assert!(a.iter().all(|x| x.as_f64().unwrap().is_finite()));
        }
    }
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args([
            "simulate",
            "--preset",
            "liu2017-stall",
            "--set",
            "aero.onera.forcing=rigid",
            "--json",
        ])
        .assert()
        .success();
    let v: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(v["status"], "diverging");
}

#[test]
fn flutter_search_and_tracking_work_unchanged_on_the_stall_model() {
    // Goland's wing at zero incidence stays attached: the coupled ONERA form (drag aside, and
    // drag has no arm at ψ = 0) must find Theodorsen's flutter speed.
    let theodorsen = flutter_boundary(
        &preset("goland", &[]),
        "operating.tunnel_speed",
        110.0,
        160.0,
        6,
    )
    .unwrap();
    let onera = flutter_boundary(
        &preset("goland", &["aero.model=onera"]),
        "operating.tunnel_speed",
        110.0,
        160.0,
        6,
    )
    .unwrap();
    let (vt, vo) = (theodorsen.critical.unwrap(), onera.critical.unwrap());
    assert_eq!(onera.kind, Some(BoundaryKind::Flutter));
    assert!(
        (vo - vt).abs() <= 2e-3 * vt,
        "onera {vo} m/s vs theodorsen {vt} m/s"
    );
    // The paper's stall case is stable over the wind speeds of the explorer's slider.
    let b = flutter_boundary(&stall(&[]), "operating.wind_speed", 5.0, 40.0, 8).unwrap();
    assert_eq!(b.critical, None);
    // Tracked over the paper's ply angles: every point solved, flap 1 damped throughout.
    let sweep = track(
        &stall(&[]),
        "section.ply_angle",
        &[15.0, 30.0, 45.0, 60.0, 75.0],
    )
    .unwrap();
    let flap1 = sweep.modes.iter().find(|m| m.label == "flap 1").unwrap();
    assert!(
        flap1.re.iter().all(|s| s.is_finite() && *s < 0.0),
        "{:?}",
        flap1.re
    );
}

#[test]
fn splitting_reproduces_the_right_hand_side_exactly() {
    // ẋ = r0 + A y + B ũ(C y) must hold at any state, not only near the reference, and the
    // remainder's tangent must be its derivative.
    for forcing in ["coupled", "rigid"] {
        let p = stall(&[
            &format!("aero.onera.forcing={forcing}"),
            "operating.pitch=2",
        ]);
        let system = flutterscope::model::system(&p).unwrap();
        let x_ref = system
            .equilibrium()
            .unwrap_or_else(|_| DVector::zeros(system.dim()));
        let split = system.splitting(&x_ref);
        let mut scratch = system.remainder_scratch();
        let (m, pdim) = (split.b.ncols(), split.c.nrows());
        assert_eq!(m, 8 * split.outputs_per_station());
        assert_eq!(pdim, 8 * split.inputs_per_station());
        let x = busy_state(&system, &x_ref);
        let y = &x - &x_ref;
        let dev = &split.c * &y;
        let mut u = DVector::zeros(m);
        let mut tangent = vec![0.0; m * split.inputs_per_station()];
        system.remainder(
            &split,
            dev.as_slice(),
            u.as_mut_slice(),
            Some(&mut tangent),
            &mut scratch,
        );
        assert!(
            u.amax() > 0.0,
            "{forcing}: the busy state must leave the tangent"
        );
        let rebuilt = &split.r0 + &split.a * &y + &split.b * &u;
        let exact = system.rhs(&x);
        let d = (&rebuilt - &exact).amax() / exact.amax();
        assert!(d < 1e-12, "{forcing}: split differs from f(x) by {d:e}");
        // Tangent blocks against central differences of the remainder, on the scale of the
        // largest entry (the rates are ~ω_r² ≈ 4e7 per unit deviation).
        let (ps, ms) = (split.inputs_per_station(), split.outputs_per_station());
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        for j in 0..pdim {
            let h = 1e-6 * (1.0 + dev[j].abs());
            let mut at = |shift: f64| {
                let mut d = dev.clone();
                d[j] += shift;
                let mut v = DVector::zeros(m);
                system.remainder(&split, d.as_slice(), v.as_mut_slice(), None, &mut scratch);
                v
            };
            let numeric = (at(h) - at(-h)) / (2.0 * h);
            let station = j / ps;
            for (i, fd) in numeric.iter().enumerate() {
                if i / ms == station {
                    let analytic = tangent[station * ms * ps + (i % ms) * ps + j % ps];
                    worst = worst.max((analytic - fd).abs());
                    scale = scale.max(analytic.abs()).max(fd.abs());
                } else {
                    // A station's outputs read only its own inputs.
                    assert_eq!(*fd, 0.0);
                }
            }
        }
        assert!(
            scale > 0.0 && worst <= 1e-6 * scale,
            "{forcing}: tangent mismatch {worst:e} of {scale:e}"
        );
    }
}

#[test]
fn rigid_transient_matches_a_fine_runge_kutta_reference() {
    let p = stall(&[
        "aero.onera.forcing=rigid",
        "operating.pitch=20.5",
        "simulation.duration=0.1",
    ]);
    let system = flutterscope::model::system(&p).unwrap();
    let reference = rk4_tip(&system, &DVector::zeros(system.dim()), 1e-5, 500, 21);
    let mut sim = simulator(&p).unwrap();
    let samples = sim.advance(21).unwrap();
    for (s, (twist, flap)) in samples.iter().zip(&reference) {
        assert!(
            (s.tip_twist - twist).abs() < 1e-4 * (1.0 + twist.abs()),
            "t = {}: {} vs {twist}",
            s.t,
            s.tip_twist
        );
        assert!(
            (s.tip_flap - flap).abs() < 1e-4 * (1.0 + flap.abs()),
            "t = {}: {} vs {flap}",
            s.t,
            s.tip_flap
        );
    }
    assert!(reference.iter().any(|(t, _)| t.abs() > 0.01));
}
