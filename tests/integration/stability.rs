//! Aeroelastic stability: validation against docs/model.md §8 and closed forms, error paths, mode
//! tracking, the linear simulator, and the JSON of `eigen`, `flutter`, `simulate`.

use assert_cmd::Command;
use flutterscope::analysis::eigen::{analyse, analyse_system, linear_system};
use flutterscope::analysis::flutter::{flutter_boundary, BoundaryKind};
use flutterscope::analysis::response::{simulate, simulator};
use flutterscope::analysis::simulate::{RunStatus, Simulator};
use flutterscope::analysis::sweep::track;
use flutterscope::error::Error;
use flutterscope::model::assemble;
use flutterscope::numeric::eigen_decomposition;
use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;
use std::sync::mpsc;
use std::time::Duration;

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

/// Run `f` on a thread and fail if it does not finish in `secs` (guards against hangs).
pub(crate) fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .expect("computation did not finish in time")
}

#[test]
fn goland_flutter_speed_and_frequency() {
    // docs/model.md §8: 137 m/s ± 2 %, 70 rad/s ± 3 % (exact 137.2 m/s, 70.7 rad/s).
    let p = preset("goland", &[]);
    let b = flutter_boundary(&p, "operating.tunnel_speed", 110.0, 160.0, 6).unwrap();
    assert_eq!(b.kind, Some(BoundaryKind::Flutter));
    let v = b.critical.unwrap();
    let w = 2.0 * PI * b.frequency_hz.unwrap();
    assert!((v - 137.0).abs() <= 0.02 * 137.0, "flutter speed {v}");
    assert!(
        (w - 70.0).abs() <= 0.03 * 70.0,
        "flutter frequency {w} rad/s"
    );
    // Just below the boundary the wing is stable, just above it flutters.
    let below = analyse(&preset(
        "goland",
        &[&format!("operating.tunnel_speed={}", v * 0.99)],
    ))
    .unwrap();
    let above = analyse(&preset(
        "goland",
        &[&format!("operating.tunnel_speed={}", v * 1.01)],
    ))
    .unwrap();
    assert!(below.stable && !above.stable);
}

#[test]
fn torsional_divergence_matches_closed_form() {
    // Uniform cantilever, no bending–twist coupling, ψ = 0, α_r = 0: torsion diverges at
    // q_D = C22 (π/2L)² / (c a0 e_a) (e_a > 0: elastic axis aft of the AC). Quasi-steady strips have
    // no pitch damping, so structural damping is raised to keep flutter out of the range; it
    // does not move a static divergence point.
    let p = preset(
        "goland",
        &[
            "aero.model=quasi-steady",
            "section.cg_offset=0",
            "structure.loss_factor=0.3",
        ],
    );
    let s = &p.section;
    let q_d =
        s.c22 * (PI / (2.0 * p.blade.length)).powi(2) / (s.chord * p.aero.lift_slope * s.ea_offset);
    let v_d = (2.0 * q_d / p.operating.air_density).sqrt();
    let b = flutter_boundary(&p, "operating.tunnel_speed", 200.0, 300.0, 5).unwrap();
    assert_eq!(b.kind, Some(BoundaryKind::Divergence));
    let v = b.critical.unwrap();
    assert!(
        (v - v_d).abs() <= 2e-4 * v_d,
        "divergence at {v}, closed form {v_d}"
    );
    assert_eq!(b.frequency_hz, Some(0.0));
}

#[test]
fn no_crossing_is_reported_as_none() {
    let p = preset("goland", &[]);
    let b = flutter_boundary(&p, "operating.tunnel_speed", 50.0, 100.0, 3).unwrap();
    assert!(b.critical.is_none() && b.kind.is_none() && b.mode.is_none());
}

#[test]
fn an_unstable_start_is_reported_and_not_searched() {
    // Goland flutters above 137 m/s: a search that starts at 150 m/s has no stable side.
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args([
            "flutter",
            "--preset",
            "goland",
            "--vary",
            "operating.tunnel_speed",
            "--from",
            "150",
            "--to",
            "100",
            "--points",
            "3",
        ])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(
        text.contains("already unstable at the start of the range")
            && text.contains("operating.tunnel_speed = 150 m/s")
            && text.contains("where the blade is stable"),
        "{text}"
    );
    let p = preset("goland", &[]);
    let b = flutter_boundary(&p, "operating.tunnel_speed", 150.0, 100.0, 3).unwrap();
    assert!(b.critical.is_none());
}

#[test]
fn eigen_solve_rejects_non_finite_input_without_hanging() {
    let mut a = DMatrix::<f64>::from_fn(6, 6, |i, j| (i as f64 - j as f64).sin());
    a[(3, 2)] = f64::NAN;
    let r = within(10, move || eigen_decomposition(&a).map(|_| ()));
    assert!(matches!(r, Err(Error::Numerical(_))));

    // The same through a full linear system and the simulator.
    let mut ls = linear_system(&preset("goland", &[])).unwrap();
    ls.a[(1, 1)] = f64::INFINITY;
    let ls2 = ls.clone();
    let r = within(10, move || analyse_system(&ls2).map(|_| ()));
    assert!(matches!(r, Err(Error::Numerical(_))));
    let r = within(10, move || {
        Simulator::from_linear(ls, 100.0, 6.0).map(|_| ())
    });
    assert!(matches!(r, Err(Error::Numerical(_))));
}

#[test]
fn structure_alone_reproduces_the_natural_frequencies() {
    // With no aerodynamics and no damping the roots are ±iω of (M, K).
    let p = preset("goland", &["aero.model=none", "structure.loss_factor=0"]);
    let natural = assemble(&p).unwrap().natural_modes().unwrap();
    let s = analyse(&p).unwrap();
    assert!(s.aero_lags.is_empty());
    let mut f: Vec<f64> = s.eigenvalues.iter().map(|m| m.frequency_hz).collect();
    f.sort_by(f64::total_cmp);
    assert_eq!(f.len(), natural.len());
    for (a, b) in f.iter().zip(&natural) {
        assert!(
            (a - b.frequency_hz).abs() <= 1e-8 * b.frequency_hz,
            "{a} vs {}",
            b.frequency_hz
        );
    }
    for m in &s.eigenvalues {
        assert!(m.re.abs() <= 1e-8 * m.im);
    }
}

#[test]
fn system_jacobian_matches_central_differences() {
    // Quasi-steady (nonlinear cos α_g moment) and theodorsen (lag states, apparent mass) on the
    // paper's and the demo blade.
    for (name, model) in [("liu2017", "quasi-steady"), ("demo-blade", "theodorsen")] {
        let p = preset(name, &[&format!("aero.model={model}")]);
        let sys = flutterscope::model::system(&p).unwrap();
        let x0 = sys.equilibrium().unwrap();
        // Move away from equilibrium so every term is exercised.
        let x = DVector::from_fn(sys.dim(), |i, _| x0[i] + 1e-3 * ((i as f64) * 0.7).sin());
        let jac = sys.jacobian(&x);
        let mut worst: f64 = 0.0;
        for j in 0..sys.dim() {
            let h = 1e-6 * (1.0 + x[j].abs());
            let mut xp = x.clone();
            let mut xm = x.clone();
            xp[j] += h;
            xm[j] -= h;
            let col = (sys.rhs(&xp) - sys.rhs(&xm)) / (2.0 * h);
            let scale = col.amax().max(jac.column(j).amax()).max(1e-8);
            worst = worst.max((col - jac.column(j)).amax() / scale);
        }
        assert!(worst < 1e-5, "{name}: Jacobian mismatch {worst}");
        // The equilibrium is a rest point of the full nonlinear right-hand side.
        assert!(
            sys.rhs(&x0).amax() < 1e-8 * (1.0 + x0.amax()),
            "{name}: rhs at equilibrium"
        );
    }
}

#[test]
fn tracking_keeps_torsion_through_a_crossing() {
    // Goland structure alone with its inertial coupling removed: the first torsion frequency
    // (π/2L)√(C22/I) rises through the fixed second flap frequency as C22 grows. The tracked
    // "torsion 1" must follow the exact torsion frequency on both sides of the crossing, and
    // "flap 2" must stay put.
    let p = preset(
        "goland",
        &[
            "aero.model=none",
            "structure.loss_factor=0",
            "section.cg_offset=0",
        ],
    );
    let grid: Vec<f64> = (0..12).map(|k| 0.6e7 + 0.17e7 * k as f64).collect();
    let sweep = track(&p, "section.c22", &grid).unwrap();
    let torsion = sweep.modes.iter().find(|m| m.label == "torsion 1").unwrap();
    let flap2 = sweep.modes.iter().find(|m| m.label == "flap 2").unwrap();
    let l = p.blade.length;
    let i = p.section.polar_inertia;
    let mut crossed = false;
    for (k, c22) in grid.iter().enumerate() {
        let exact = PI / (2.0 * l) * (c22 / i).sqrt() / (2.0 * PI);
        assert!(
            (torsion.frequency_hz[k] - exact).abs() <= 1e-6 * exact,
            "point {k}: tracked torsion at {} Hz, exact {exact}",
            torsion.frequency_hz[k]
        );
        assert!(
            (flap2.frequency_hz[k] - flap2.frequency_hz[0]).abs() <= 1e-9 * flap2.frequency_hz[0]
        );
        crossed |= torsion.frequency_hz[k] > flap2.frequency_hz[k];
    }
    assert!(torsion.frequency_hz[0] < flap2.frequency_hz[0] && crossed);
}

#[test]
fn simulated_decay_rate_equals_the_largest_sigma() {
    // Structure with stiffness-proportional damping, flap kick from equilibrium: the slowest
    // root (flap 1) dominates late in the run; its envelope decays at the largest σ.
    let p = preset(
        "goland",
        &[
            "aero.model=none",
            "structure.loss_factor=0.02",
            "simulation.start=equilibrium",
            "simulation.kick_flap=0.1",
            "simulation.kick_twist=0",
            "simulation.duration=12",
            "simulation.sample_rate=400",
        ],
    );
    let sigma = analyse(&p).unwrap().max_re();
    assert!(sigma < 0.0);
    let r = simulate(&p).unwrap();
    assert_eq!(r.status, RunStatus::Ok);
    let peak = |t0: f64, t1: f64| {
        r.t.iter()
            .zip(&r.tip_flap)
            .filter(|(t, _)| **t >= t0 && **t < t1)
            .map(|(_, u)| u.abs())
            .fold(0.0, f64::max)
    };
    let (a1, a2) = (peak(4.0, 5.0), peak(10.0, 11.0));
    let rate = (a2 / a1).ln() / 6.0;
    assert!(
        (rate - sigma).abs() <= 0.02 * sigma.abs(),
        "measured {rate}, largest σ {sigma}"
    );
}

#[test]
fn rest_start_settles_to_equilibrium_and_flutter_diverges_cleanly() {
    // Stable: the load switched on at t = 0 settles on the static deflection.
    let p = preset(
        "goland",
        &[
            "operating.tunnel_speed=100",
            "operating.pitch=-2",
            "simulation.start=rest",
            "simulation.kick_twist=0",
            "simulation.sample_rate=200",
            "simulation.duration=30",
        ],
    );
    let lin = linear_system(&p).unwrap();
    let (twist_eq, flap_eq) = lin.tip_at(&lin.x_eq, 0.0);
    assert!(twist_eq.abs() > 0.0 && flap_eq.abs() > 0.0);
    let r = simulate(&p).unwrap();
    assert_eq!(r.status, RunStatus::Ok);
    assert_eq!(r.t.len(), 30 * 200 + 1);
    assert_eq!((r.tip_twist[0], r.tip_flap[0]), (0.0, 0.0));
    let last = r.t.len() - 1;
    assert!((r.tip_twist[last] - twist_eq).abs() < 1e-3 * twist_eq.abs());
    assert!((r.tip_flap[last] - flap_eq).abs() < 1e-3 * flap_eq.abs());

    // Past the flutter speed: stops at the bound with status diverging, no NaN.
    let p = preset(
        "goland",
        &[
            "operating.tunnel_speed=160",
            "simulation.kick_twist=0.5",
            "simulation.duration=1000",
        ],
    );
    let r = within(60, move || simulate(&p).unwrap());
    assert_eq!(r.status, RunStatus::Diverging);
    let t_end = r.diverged_at.unwrap();
    assert!(t_end < 1000.0 && *r.t.last().unwrap() == t_end);
    assert!(r.tip_twist.iter().chain(&r.tip_flap).all(|v| v.is_finite()));
}

#[test]
fn incremental_stepping_equals_one_run_and_kicks_move_the_tip() {
    let p = preset("demo-blade", &[]);
    let mut a = simulator(&p).unwrap();
    let whole = a.advance(100).unwrap();
    let mut b = simulator(&p).unwrap();
    let mut parts = b.advance(37).unwrap();
    parts.extend(b.advance(63).unwrap());
    assert_eq!(whole, parts);
    assert!((b.time() - 99.0 / p.simulation.sample_rate).abs() < 1e-12);
    let before = b.state();
    b.kick(0.01, 0.02);
    let lin = b.linear();
    let (dt, du) = lin.tip_at(&(b.state() - before), 0.0);
    assert!((dt - 0.01).abs() < 1e-12 && (du - 0.02).abs() < 1e-12);
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args(args)
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).unwrap()
}

#[test]
fn eigen_json_shape() {
    let v = json(&["eigen", "--preset", "goland", "--json"]);
    assert_eq!(v["stable"], true);
    assert_eq!(v["verdict"], "stable");
    let eig = v["eigenvalues"].as_array().unwrap();
    assert!(!eig.is_empty() && !v["aero_lags"].as_array().unwrap().is_empty());
    for key in [
        "re",
        "im",
        "frequency_hz",
        "damping_ratio",
        "label",
        "structural_share",
    ] {
        assert!(eig.iter().all(|m| !m[key].is_null()), "{key}");
    }
    let re: Vec<f64> = eig.iter().map(|m| m["re"].as_f64().unwrap()).collect();
    assert!(
        re.windows(2).all(|w| w[0] >= w[1]),
        "sorted by re descending"
    );
}

#[test]
fn flutter_json_shape() {
    let args = [
        "flutter",
        "--preset",
        "goland",
        "--vary",
        "operating.tunnel_speed",
    ];
    let v = json(
        &[
            &args[..],
            &["--from", "120", "--to", "150", "--points", "4", "--json"],
        ]
        .concat(),
    );
    assert_eq!(v["parameter"], "operating.tunnel_speed");
    assert!(v["critical"].as_f64().is_some() && v["frequency_hz"].as_f64().is_some());
    assert_eq!(v["kind"], "flutter");
    assert!(v["mode"].is_string());
    let v = json(
        &[
            &args[..],
            &["--from", "50", "--to", "90", "--points", "3", "--json"],
        ]
        .concat(),
    );
    assert!(v["critical"].is_null());
    // Text says so plainly.
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args([&args[..], &["--from", "50", "--to", "90", "--points", "3"]].concat())
        .assert()
        .success();
    assert!(String::from_utf8_lossy(&out.get_output().stdout).contains("no stability boundary"));
}

#[test]
fn simulate_json_shape_and_bad_plot_extension() {
    let v = json(&[
        "simulate",
        "--preset",
        "goland",
        "--set",
        "simulation.duration=0.5",
        "--set",
        "simulation.sample_rate=200",
        "--json",
    ]);
    assert_eq!(v["status"], "ok");
    let n = v["t"].as_array().unwrap().len();
    assert_eq!(n, 101);
    assert_eq!(v["tip_twist"].as_array().unwrap().len(), n);
    assert_eq!(v["tip_flap"].as_array().unwrap().len(), n);
    Command::cargo_bin("flutterscope")
        .unwrap()
        .args(["simulate", "--preset", "goland", "--plot", "response.txt"])
        .assert()
        .code(2);
    assert!(!std::path::Path::new("response.txt").exists());
}
