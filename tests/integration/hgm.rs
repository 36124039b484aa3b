//! The Hansen–Gaunaa–Madsen dynamic-stall model (docs/model.md §12.8): the static polar at every
//! station of the real blades, Jones's indicial response in attached flow, the separation
//! point's lag, a dynamic-stall loop, a stall-induced edgewise vibration in time, its constants
//! from the files and the preset, and the model in every command.

use flutterscope::analysis::response::simulator;
use flutterscope::analysis::simulate::RunStatus;
use flutterscope::formats::airfoil::{parse_airfoil, read_airfoil, PolarColumns};
use flutterscope::model::aero::aero_stations_of;
use flutterscope::physics::aero::airfoil::hgm::{Hgm, HgmOverrides, PUBLISHED};
use flutterscope::physics::aero::airfoil::{AirfoilDynamics, SectionFlow, SteadyFlow};
use flutterscope::physics::aero::polar::{Polar, UnsteadyBlock, UnsteadyConstants};
use flutterscope::physics::rotor::files::{airfoil_polar, AERODYN_UA_DEFAULTS};
use flutterscope::preset::Preset;
use std::f64::consts::PI;
use std::path::Path;

/// A cambered thin airfoil: `2π(α + 0.03)` up to its stall at ±0.17 rad, then falling.
fn thin_airfoil() -> Polar {
    let alpha: Vec<f64> = (-40..=40).map(|d| (d as f64).to_radians()).collect();
    let cl = alpha
        .iter()
        .map(|&a| 2.0 * PI * (a.clamp(-0.17, 0.17) + 0.03) - 2.0 * (a.abs() - 0.17).max(0.0))
        .collect();
    let cd = alpha.iter().map(|a| 0.008 + 0.5 * a * a).collect();
    let cm = alpha.iter().map(|a| -0.08 - 0.05 * a).collect();
    Polar::new(alpha, cl, cd, cm, "thin").unwrap()
}

fn airfoil_file(name: &str) -> Polar {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades/nrel5mw/Airfoils")
        .join(name);
    let file = read_airfoil(&path, PolarColumns::default()).unwrap();
    airfoil_polar(&file, name).unwrap()
}

/// Still flow at angle `alpha` on a unit semichord at unit speed: reduced time is time.
fn flow(alpha: f64) -> SectionFlow<f64> {
    SectionFlow {
        alpha,
        alpha_geometric: alpha,
        twist_rate: 0.0,
        rate: 1.0,
    }
}

fn steady(hgm: &Hgm, polar: &Polar, alpha: f64) -> [f64; 4] {
    let mut z = [0.0; 4];
    let mut dz = [0.0; 4];
    let at = SteadyFlow {
        alpha,
        semichord: 1.0,
        speed: 1.0,
    };
    hgm.steady_states(polar, at, &mut z, &mut dz);
    z
}

/// One classical Runge–Kutta step of the states at the flow `at(t)` over `h`.
fn rk4(
    hgm: &Hgm,
    polar: &Polar,
    at: &dyn Fn(f64) -> SectionFlow<f64>,
    t: f64,
    h: f64,
    z: &mut [f64; 4],
) {
    let rate = |t: f64, z: &[f64; 4]| {
        let mut d = [0.0; 4];
        hgm.coefficients(polar, &at(t), z, &mut d);
        d
    };
    let shift = |z: &[f64; 4], d: &[f64; 4], s: f64| std::array::from_fn(|i| z[i] + s * d[i]);
    let k1 = rate(t, z);
    let k2 = rate(t + h / 2.0, &shift(z, &k1, h / 2.0));
    let k3 = rate(t + h / 2.0, &shift(z, &k2, h / 2.0));
    let k4 = rate(t + h, &shift(z, &k3, h));
    for i in 0..4 {
        z[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

#[test]
fn steady_states_return_the_polar_at_every_station_in_and_beyond_stall() {
    let hgm = Hgm::default();
    let mut worst: f64 = 0.0;
    let mut count = 0;
    for name in ["nrel5mw", "iea15mw"] {
        let p = Preset::load(name, &[]).unwrap();
        let stations = aero_stations_of(&p).unwrap();
        for st in stations.iter() {
            let polar = &st.section.polar;
            // −30° to 90° in steps off the tables' rows: attached, stall, deep stall.
            for k in 0..=150 {
                let alpha = (-30.0 + 0.8 * k as f64 + 0.13).to_radians();
                let z = steady(&hgm, polar, alpha);
                let mut zdot = [0.0; 4];
                let c = hgm.coefficients(polar, &flow(alpha), &z, &mut zdot);
                let s = polar.at(alpha);
                for (got, want) in c.iter().zip([s.cl, s.cd, s.cm]) {
                    worst = worst.max((got - want).abs() / want.abs().max(1.0));
                }
                assert!(
                    zdot.iter().all(|r| r.abs() < 1e-12),
                    "{name} {alpha}: {zdot:?}"
                );
                count += 1;
            }
        }
    }
    eprintln!("steady HGM against the polar: {count} points, worst {worst:e}");
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn step_in_attached_flow_follows_jones_wagner_function() {
    let (hgm, polar) = (Hgm::default(), thin_airfoil());
    let line = polar.attached();
    let (from, step) = (line.zero_lift, 0.05);
    let mut z = steady(&hgm, &polar, from);
    let at = |_: f64| flow(from + step);
    let h = 0.01;
    let mut worst: f64 = 0.0;
    for n in 0..=4000 {
        let t = n as f64 * h;
        let mut zdot = [0.0; 4];
        let cl = hgm.coefficients(&polar, &at(t), &z, &mut zdot)[0];
        let k = PUBLISHED;
        let wagner = 1.0 - k.a1 * (-k.b1 * t).exp() - k.a2 * (-k.b2 * t).exp();
        worst = worst.max((cl / (line.slope * step) - wagner).abs());
        rk4(&hgm, &polar, &at, t, h, &mut z);
    }
    eprintln!("indicial lift against Jones's Wagner function: worst {worst:e}");
    assert!(worst < 1e-6, "{worst:e}");
    // The separation point stayed attached.
    assert!((z[3] - 1.0).abs() < 1e-12, "{}", z[3]);
}

#[test]
fn separation_point_relaxes_on_tau_f() {
    let hgm = Hgm {
        overrides: HgmOverrides {
            tau_f: Some(4.0),
            ..HgmOverrides::default()
        },
    };
    let polar = thin_airfoil();
    let (attached, stalled) = (0.12, 0.25);
    let f_attached = polar.separation(attached).f;
    let f_stalled = polar.separation(stalled).f;
    assert!(
        f_attached == 1.0 && f_stalled < 0.5,
        "{f_attached} {f_stalled}"
    );
    // Every other state already at the stalled angle: x4 alone relaxes, e^(−s/τ_f).
    let mut z = steady(&hgm, &polar, stalled);
    z[3] = f_attached;
    let at = |_: f64| flow(stalled);
    let h = 0.01;
    let mut worst: f64 = 0.0;
    for n in 0..=2000 {
        let t = n as f64 * h;
        let exact = f_stalled + (f_attached - f_stalled) * (-t / 4.0).exp();
        worst = worst.max((z[3] - exact).abs());
        rk4(&hgm, &polar, &at, t, h, &mut z);
    }
    eprintln!("separation point against e^(−s/τ_f): worst {worst:e}");
    assert!(worst < 1e-9, "{worst:e}");
    // The lift follows it from the attached line's toward the polar's.
    let mut zdot = [0.0; 4];
    let mut lagging = steady(&hgm, &polar, stalled);
    lagging[3] = 0.9;
    let cl = hgm.coefficients(&polar, &flow(stalled), &lagging, &mut zdot)[0];
    assert!(cl > polar.at(stalled).cl && cl < polar.attached().lift(stalled));
}

/// `C_l` along one period of `α = 10° + 8° sin ωt` (after settling), with `α` and `α̇`.
fn loop_on(polar: &Polar, k: f64) -> Vec<(f64, f64, f64)> {
    let hgm = Hgm::default();
    let (mean, amp) = (10f64.to_radians(), 8f64.to_radians());
    // Reduced frequency k = ωb/V with b = V = 1; the pitch about the three-quarter chord.
    let at = |t: f64| SectionFlow {
        alpha: mean + amp * (k * t).sin(),
        alpha_geometric: mean + amp * (k * t).sin(),
        twist_rate: -amp * k * (k * t).cos(),
        rate: 1.0,
    };
    let period = 2.0 * PI / k;
    let steps = 4000;
    let h = period / steps as f64;
    let mut z = steady(&hgm, polar, mean);
    let mut out = Vec::new();
    for n in 0..4 * steps {
        let t = n as f64 * h;
        if n >= 3 * steps {
            let mut zdot = [0.0; 4];
            let f = at(t);
            let cl = hgm.coefficients(polar, &f, &z, &mut zdot)[0];
            out.push((f.alpha, -f.twist_rate, cl));
        }
        rk4(&hgm, polar, &at, t, h, &mut z);
    }
    out
}

#[test]
fn dynamic_stall_loop_overshoots_on_the_upstroke_and_runs_clockwise() {
    // DU21 (the NREL 5MW's outboard thick airfoil) stalls near 10°: the loop spans 2°–18°.
    let polar = airfoil_file("DU21_A17.dat");
    for k in [0.05, 0.1] {
        let cycle = loop_on(&polar, k);
        let static_max = cycle
            .iter()
            .map(|&(a, _, _)| polar.at(a).cl)
            .fold(f64::MIN, f64::max);
        let dynamic_max = cycle.iter().map(|c| c.2).fold(f64::MIN, f64::max);
        // ∮ C_l dα over the cycle: positive when the upstroke runs above the downstroke.
        let area: f64 = cycle
            .windows(2)
            .map(|w| 0.5 * (w[0].2 + w[1].2) * (w[1].0 - w[0].0))
            .sum();
        // At 15°, up against down.
        let near = |up: bool| {
            cycle
                .iter()
                .filter(|c| (c.1 > 0.0) == up)
                .min_by(|x, y| {
                    (x.0 - 15f64.to_radians())
                        .abs()
                        .total_cmp(&(y.0 - 15f64.to_radians()).abs())
                })
                .unwrap()
                .2
        };
        let (up, down) = (near(true), near(false));
        eprintln!(
            "k = {k}: C_l max {dynamic_max:.4} (static {static_max:.4}), ∮C_l dα = {area:.5}, \
             C_l at 15° up {up:.4} down {down:.4}"
        );
        assert!(dynamic_max > static_max + 0.05, "no stall delay at k = {k}");
        assert!(up > down + 0.05, "k = {k}: {up} against {down}");
        assert!(area > 0.0, "k = {k}: ∮C_l dα = {area}");
    }
}

#[test]
fn constants_come_from_the_ua_block_the_published_values_or_the_preset() {
    // NREL 5MW: every UA block gives or defaults to AeroDyn's constants.
    let du21 = airfoil_file("DU21_A17.dat");
    let block = du21.unsteady().expect("DU21 has a UA block");
    assert_eq!(block.constants, AERODYN_UA_DEFAULTS);
    assert_eq!(Hgm::default().constants(&du21), AERODYN_UA_DEFAULTS);
    // NACA64 writes "Default" where DU21 writes the numbers.
    let naca = airfoil_file("NACA64_A17.dat");
    assert_eq!(naca.unsteady().unwrap().constants, AERODYN_UA_DEFAULTS);
    // No block (a HAWC2 pc file's polar): the published constants.
    assert_eq!(Hgm::default().constants(&thin_airfoil()), PUBLISHED);
    // The preset's keys win over the file's, one by one.
    let set = Hgm {
        overrides: HgmOverrides {
            a1: Some(0.2),
            tau_p: Some(2.5),
            ..HgmOverrides::default()
        },
    };
    let k = set.constants(&du21);
    assert_eq!((k.a1, k.a2, k.tau_p, k.tau_f), (0.2, 0.7, 2.5, 3.0));
    // A file's constant out of range names the file and the range.
    let bad = thin_airfoil().with_unsteady(UnsteadyBlock {
        constants: UnsteadyConstants {
            b2: -0.5,
            ..PUBLISHED
        },
        origin: "odd.dat, table 1".into(),
    });
    let e = Hgm::default().check(&bad).unwrap_err();
    assert!(
        e.contains("b2 = -0.5") && e.contains("(0, 10]") && e.contains("odd.dat"),
        "{e}"
    );
    assert!(Hgm::default().check(&du21).is_ok());
}

#[test]
fn ua_block_reads_numbers_and_defaults_and_refuses_words() {
    let text = |a1: &str| {
        format!(
            "! AirfoilInfo\n\"DEFAULT\" InterpOrd\n1 NonDimArea\n0 NumCoords\n1 NumTabs\n\
             0.75 Re\n0 UserProp\nTrue InclUAdata\n-4 alpha0\n{a1} A1\n\"Default\" A2\n\
             0.2 b1\n4.5 T_f0\n\"Default\" T_p\n3 NumAlf\n-10 -0.6 0.02 0\n0 0.4 0.01 -0.05\n\
             10 1.2 0.03 -0.06\n"
        )
    };
    let f = parse_airfoil(&text("0.25"), "ua.dat", PolarColumns::default()).unwrap();
    let ua = f.tables[0].ua.unwrap();
    assert_eq!(
        (ua.a1, ua.a2, ua.b1, ua.b2),
        (Some(0.25), None, Some(0.2), None)
    );
    assert_eq!((ua.t_f0, ua.t_p), (Some(4.5), None));
    let e = parse_airfoil(&text("soon"), "ua.dat", PolarColumns::default()).unwrap_err();
    let e = e.to_string();
    assert!(
        e.contains("A1") && e.contains("soon") && e.contains("ua.dat"),
        "{e}"
    );
}

#[test]
fn bad_hgm_input_is_an_error_not_a_panic() {
    let load = |name: &str, sets: &[&str]| {
        let o: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        Preset::load(name, &o).map(|_| ()).unwrap_err().to_string()
    };
    let e = load("liu2017", &["aero.model=hgm"]);
    assert!(e.contains("hgm") && e.contains("uniform"), "{e}");
    let e = load("nrel5mw", &["aero.model=hgm", "aero.hgm.b1=0"]);
    assert!(e.contains("aero.hgm.b1") && e.contains("(0, 10]"), "{e}");
    let e = load(
        "nrel5mw",
        &["aero.model=hgm", "aero.hgm.a1=0.6", "aero.hgm.a2=0.5"],
    );
    assert!(
        e.contains("aero.hgm.a1 + aero.hgm.a2") && e.contains("at most 1"),
        "{e}"
    );
    // A constant the preset sets alone can still break a station's sum with the file's other.
    let p = Preset::load(
        "nrel5mw",
        &["aero.model=hgm".into(), "aero.hgm.a1=0.5".into()],
    );
    let e = flutterscope::model::system(&p.unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("A1 + A2 = 0.5 + 0.7") && e.contains("station 1 of"),
        "{e}"
    );
    assert!(e.contains("Cylinder1.dat"), "{e}");
}

#[test]
fn hgm_runs_in_eigen_sweep_flutter_and_simulate() {
    let eigen = super::flutterscope_ok(&["eigen", "-p", "nrel5mw", "--set", "aero.model=hgm"]);
    let text = String::from_utf8_lossy(&eigen.stdout);
    assert!(
        text.contains("aero model hgm") && text.contains("edge 1"),
        "{text}"
    );
    // The whole turbine, each blade's stations with their four states, in the ground frame.
    let turbine = super::flutterscope_ok(&[
        "eigen",
        "-p",
        "iea15mw",
        "--set",
        "aero.model=hgm",
        "--set",
        "turbine.model=turbine",
    ]);
    let text = String::from_utf8_lossy(&turbine.stdout);
    for name in [
        "aero model hgm",
        "BW edge 1",
        "FW edge 1",
        "tower FA 1",
        "\nSTABLE: every root",
    ] {
        assert!(text.contains(name), "{name}: {text}");
    }
    super::flutterscope_ok(&[
        "sweep",
        "-p",
        "iea15mw",
        "--set",
        "aero.model=hgm",
        "--vary",
        "operating.wind_speed=8:12:2",
    ]);
    super::flutterscope_ok(&[
        "flutter",
        "-p",
        "iea15mw",
        "--set",
        "aero.model=hgm",
        "--vary",
        "operating.wind_speed",
        "--from",
        "5",
        "--to",
        "15",
        "--points",
        "5",
    ]);
    // In time the model runs as the nonlinear model it is: against classical Runge–Kutta on
    // the full right-hand side from the same kicked start.
    let p = Preset::load(
        "nrel5mw",
        &[
            "aero.model=hgm".into(),
            "simulation.duration=0.5".into(),
            "simulation.kick_twist=2".into(),
            "simulation.kick_flap=2".into(),
        ],
    )
    .unwrap();
    let mut sim = simulator(&p).unwrap();
    assert!(!sim.linear().x_eq.is_empty());
    let system = flutterscope::model::system(&p).unwrap();
    assert!(!system.model().nonlinear_support().is_affine());
    let x0 = sim.state();
    let samples = sim.advance(101).unwrap();
    assert_eq!(sim.status(), RunStatus::Ok);
    let reference = crate::simulate::rk4_tip(&system, &x0, 2e-5, 250, samples.len());
    let (mut worst_twist, mut worst_flap, mut swing): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for (sample, &(twist, flap)) in samples.iter().zip(&reference) {
        worst_twist = worst_twist.max((sample.tip_twist - twist).abs());
        worst_flap = worst_flap.max((sample.tip_flap - flap).abs());
        swing = swing.max((flap - samples[0].tip_flap).abs());
    }
    eprintln!(
        "hgm in time against RK4: twist {worst_twist:.2e} rad, flap {worst_flap:.2e} m \
         (flap swing {swing:.3} m)"
    );
    assert!(swing > 0.5, "{swing}");
    assert!(
        worst_twist < 1e-4 && worst_flap < 1e-3,
        "{worst_twist:e} {worst_flap:e}"
    );
}

#[test]
fn the_aero_key_reaches_hgm_on_a_real_blade_only() {
    use flutterscope::preset::AeroModel;
    assert_eq!(AeroModel::Onera.cycle_for(true, true), AeroModel::Hgm);
    assert_eq!(AeroModel::Hgm.cycle_for(true, true), AeroModel::None);
    assert_eq!(AeroModel::Onera.cycle_for(true, false), AeroModel::None);
    assert_eq!(AeroModel::None.cycle_for(false, false), AeroModel::Onera);
    // Shown and read back, a set constant stays set and the others unset.
    let p = Preset::load("nrel5mw", &["aero.hgm.tau_f=4.5".into()]).unwrap();
    assert_eq!((p.aero.hgm.tau_f, p.aero.hgm.a1), (Some(4.5), None));
}

/// A stall-induced edgewise vibration in time (docs/model.md §12.8): the NREL 5MW held at 0°
/// pitch in 20 m/s at 12.1 rpm stalls over much of its span, and without structural damping its
/// 4th edge mode (12.8 Hz) takes energy from the falling lift slope: the linear model has it
/// growing. The nonlinear model in time, kicked from its equilibrium, grows at the same rate once
/// the other modes have died out: the tip twist's component at the mode's frequency, averaged over
/// 10 s, 20 s apart.
#[test]
fn a_stall_induced_edgewise_vibration_grows_in_time_as_the_linear_model_predicts() {
    let p = Preset::load(
        "nrel5mw",
        &[
            "aero.model=hgm".into(),
            "operating.schedule=none".into(),
            "operating.wind_speed=20".into(),
            "operating.rotor_speed=12.1".into(),
            "operating.pitch=0".into(),
            "structure.damping_edge=0".into(),
            "structure.damping_flap=0".into(),
            "simulation.duration=60".into(),
            "simulation.sample_rate=200".into(),
        ],
    )
    .unwrap();
    let stability = flutterscope::analysis::eigen::analyse(&p).unwrap();
    let growing = stability.critical().unwrap();
    assert!(
        growing.label.starts_with("edge") && growing.re > 0.05,
        "{growing:?}"
    );
    let mut sim = simulator(&p).unwrap();
    let samples = sim.advance(12_001).unwrap();
    assert_eq!(sim.status(), RunStatus::Ok);
    let mean = samples.iter().map(|s| s.tip_twist).sum::<f64>() / samples.len() as f64;
    // |mean over [from, from + 10 s) of (twist − mean) e^{−iωt}|: the mode's amplitude there.
    let amplitude = |from: f64| {
        let window = samples.iter().filter(|s| s.t >= from && s.t < from + 10.0);
        let (mut re, mut im, mut n) = (0.0, 0.0, 0.0);
        for s in window {
            let (sin, cos) = (growing.im * s.t).sin_cos();
            re += (s.tip_twist - mean) * cos;
            im -= (s.tip_twist - mean) * sin;
            n += 1.0;
        }
        (re * re + im * im).sqrt() / n
    };
    let rate = (amplitude(50.0) / amplitude(30.0)).ln() / 20.0;
    eprintln!(
        "edge vibration in time grows at {rate:.4} 1/s, linear σ {:.4} 1/s",
        growing.re
    );
    assert!(
        (rate / growing.re - 1.0).abs() < 0.05,
        "in time {rate} 1/s against the linear model's {} 1/s",
        growing.re
    );
}
