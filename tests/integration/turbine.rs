//! The rotor in the ground frame (docs/model.md §13): three blades on the drivetrain, carried
//! by the multi-blade transform; checked against the one blade it is made of, against the
//! NREL 5MW's published full-system frequencies, and through the real binary.

use super::flutterscope_ok;
use flutterscope::analysis::eigen::{analyse, linear_system, Verdict};
use flutterscope::analysis::flutter::{flutter_search, BoundaryKind};
use flutterscope::analysis::mode::Mode;
use flutterscope::analysis::mode_shape::ModeShapes;
use flutterscope::analysis::response::{simulate, simulator};
use flutterscope::analysis::simulate::Simulator;
use flutterscope::numeric::decompose;
use flutterscope::physics::structure::{Family, PartKind};
use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::{Complex, DVector};
use std::f64::consts::TAU;

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

/// The mode named `label` among `modes`.
fn mode<'a>(modes: &'a [Mode], label: &str) -> &'a Mode {
    modes
        .iter()
        .find(|m| m.label == label)
        .unwrap_or_else(|| panic!("no {label}"))
}

/// Every root of the state matrix of `p`, each complex pair's both roots.
fn roots(p: &ValidPreset) -> Vec<Complex<f64>> {
    let values = decompose(&linear_system(p).unwrap().a, false)
        .unwrap()
        .values;
    let conjugates: Vec<Complex<f64>> = values
        .iter()
        .filter(|l| l.im != 0.0)
        .map(|l| l.conj())
        .collect();
    values.into_iter().chain(conjugates).collect()
}

/// The rotor speed (rad/s) `p` runs at.
fn omega(p: &ValidPreset) -> f64 {
    flutterscope::model::operating::scheduled_rotor_speed(p).unwrap() * TAU / 60.0
}

/// Every blade root `λ` is the rotor's three times, as `λ` (collective) and `λ ∓ iΩ` (the
/// cyclic pair), to `tol` of the spectral scale; and the rotor has no other root.
fn assert_blade_roots_shifted(blade: &[Complex<f64>], rotor: &[Complex<f64>], w: f64, tol: f64) {
    assert_eq!(rotor.len(), 3 * blade.len());
    let scale = rotor.iter().map(|l| l.norm()).fold(1.0, f64::max);
    let mut left: Vec<Complex<f64>> = rotor.to_vec();
    for l in blade {
        for shift in [0.0, w, -w] {
            let want = l + Complex::new(0.0, shift);
            let (k, d) = left
                .iter()
                .enumerate()
                .map(|(k, r)| (k, (r - want).norm()))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            assert!(
                d <= tol * scale,
                "blade root {l} shifted by {shift} i: nearest rotor root {} off by {d:e}",
                left[k]
            );
            left.swap_remove(k);
        }
    }
}

#[test]
fn a_rotor_on_a_rigid_drivetrain_in_vacuo_is_its_blade_at_and_either_side_of_1p() {
    let o = ["aero.model=none"];
    let blade = preset("nrel5mw", &o);
    let rotor = preset(
        "nrel5mw",
        &[
            "aero.model=none",
            "turbine.model=rotor",
            "turbine.drivetrain=rigid",
        ],
    );
    assert_blade_roots_shifted(&roots(&blade), &roots(&rotor), omega(&blade), 1e-9);
    // Named: collective at the blade's frequency, BW at f − 1P, FW at f + 1P.
    let named = analyse(&rotor).unwrap().eigenvalues;
    let find = |label: &str| -> &Mode { mode(&named, label) };
    let one_p = omega(&blade) / TAU;
    for m in analyse(&blade).unwrap().eigenvalues.iter().take(6) {
        let f = m.frequency_hz;
        for (whirl, want) in [
            ("collective", f),
            ("BW", (f - one_p).abs()),
            ("FW", f + one_p),
        ] {
            let got = find(&format!("{whirl} {}", m.label)).frequency_hz;
            assert!(
                (got - want).abs() <= 1e-9 * want,
                "{whirl} {}: {got} Hz, want {want}",
                m.label
            );
        }
    }
}

#[test]
fn a_rotor_on_a_rigid_drivetrain_in_the_wind_is_its_blade_shifted_by_1p() {
    // Theodorsen's lags, and the dynamic-stall model's four states a station (a 432-state
    // rotor on faer's decomposition).
    for aero in ["aero.model=theodorsen", "aero.model=hgm"] {
        let blade = preset("nrel5mw", &[aero]);
        let rotor = preset(
            "nrel5mw",
            &[aero, "turbine.model=rotor", "turbine.drivetrain=rigid"],
        );
        assert_blade_roots_shifted(&roots(&blade), &roots(&rotor), omega(&blade), 1e-9);
    }
}

/// Jonkman et al. (2009), NREL/TP-500-38060, table 9-1: the full-system natural frequencies
/// (FAST) of the land-based turbine at rest, generator brake engaged, no aerodynamic damping.
/// The rotor on a rigid support holds the drivetrain and the modes the tower barely moves.
#[test]
fn the_nrel5mw_rotor_at_rest_with_its_brake_on_has_the_published_frequencies() {
    let p = preset(
        "nrel5mw",
        &[
            "aero.model=none",
            "operating.schedule=none",
            "operating.rotor_speed=0",
            "turbine.model=rotor",
            "turbine.drivetrain=locked",
        ],
    );
    let named = analyse(&p).unwrap().eigenvalues;
    let hz = |label: &str| mode(&named, label).frequency_hz;
    for (label, published) in [
        ("drivetrain 1", 0.6205),
        ("collective flap 1", 0.6993),
        ("BW edge 1", 1.0793),
        ("FW edge 1", 1.0898),
        ("BW flap 2", 1.9223),
        ("FW flap 2", 1.9337),
    ] {
        let got = hz(label);
        assert!(
            (got / published - 1.0).abs() < 0.03,
            "{label}: {got:.4} Hz against {published} Hz"
        );
    }
    // The drivetrain carries the collective edge mode far above the blade's.
    assert!(hz("collective edge 1") > 2.0 * hz("BW edge 1"));
}

/// The blade's mass and inertia about the shaft, from the mass matrix of its elements, are the
/// published ones (Jonkman et al. 2009, table 2-1: 17 740 kg and 11 776 047 kg·m², which
/// include ElastoDyn's mass factor AdjBlMs = 1.04536 of the blade file the BeamDyn blade does
/// not carry) within 1 %; a rigid tilt about the root carries the same second moment (the
/// sections' rotary inertia apart) and a translation moves the whole mass either way.
#[test]
fn the_blades_mass_and_inertia_about_the_root_are_the_published_ones() {
    use flutterscope::physics::blade::fem::Rigid;
    let p = preset("nrel5mw", &["aero.model=none", "blade.hub_radius=1e-9"]);
    let coupling = flutterscope::model::for_preset(&p)
        .unwrap()
        .rotor_coupling()
        .unwrap();
    let m = |a: Rigid, b: Rigid| coupling.rigid_mass[(a as usize, b as usize)];
    let (inertia, mass) = (
        m(Rigid::Rotation, Rigid::Rotation),
        m(Rigid::Flap, Rigid::Flap),
    );
    let published = 11_776_047.0 / 1.04536;
    assert!(
        (inertia / published - 1.0).abs() < 0.01,
        "{inertia} kg·m² against {published}"
    );
    let published_mass = 17_740.0 / 1.04536;
    assert!(
        (mass / published_mass - 1.0).abs() < 0.01,
        "{mass} kg against {published_mass}"
    );
    assert!((m(Rigid::Edge, Rigid::Edge) / mass - 1.0).abs() < 1e-12);
    assert!((m(Rigid::Tilt, Rigid::Tilt) / inertia - 1.0).abs() < 1e-3);
    // The first moment: the same for a rotation about the shaft and across it.
    assert!((m(Rigid::Flap, Rigid::Tilt) / m(Rigid::Edge, Rigid::Rotation) - 1.0).abs() < 1e-12);
    assert!(m(Rigid::Flap, Rigid::Edge).abs() < 1e-9 * mass);
}

#[test]
fn a_free_drivetrain_turns_as_a_whole_and_twists() {
    let p = preset(
        "nrel5mw",
        &[
            "aero.model=none",
            "turbine.model=rotor",
            "turbine.drivetrain=free",
        ],
    );
    let s = analyse(&p).unwrap();
    let rotation = mode(&s.eigenvalues, "rotor rotation");
    assert_eq!(rotation.frequency_hz, 0.0);
    assert_eq!(rotation.damping_ratio, 0.0);
    assert!(s.eigenvalues.iter().any(|m| m.label == "drivetrain 1"));
    // In the wind the rotor's speed decays by the aerodynamic torque's slope.
    let windy = analyse(&preset("nrel5mw", &["turbine.model=rotor"])).unwrap();
    let rotation = mode(&windy.eigenvalues, "rotor rotation");
    assert!(rotation.re < 0.0 && rotation.im == 0.0 && rotation.second_re.is_none());
    assert!(windy.stable);
}

/// OpenFAST's linearisation of the whole NREL 5MW at 12.1 rpm without air, generator free
/// (`../shared/blades/nrel5mw/reference/frequencies.txt`, case 1.lin): the collective edge mode
/// the drivetrain lifts, 1.6916 Hz, within 3 % (its tower, which the rotor model does not
/// hold, barely moves in it).
#[test]
fn the_drivetrain_lifts_the_collective_edge_mode_as_openfast_has_it() {
    let p = preset("nrel5mw", &["aero.model=none", "turbine.model=rotor"]);
    let s = analyse(&p).unwrap();
    let edge = mode(&s.eigenvalues, "collective edge 1");
    assert!(
        (edge.frequency_hz / 1.6916 - 1.0).abs() < 0.03,
        "{} Hz",
        edge.frequency_hz
    );
}

#[test]
fn the_commands_name_the_rotors_modes() {
    let out = flutterscope_ok(&[
        "eigen",
        "--preset",
        "nrel5mw",
        "--set",
        "turbine.model=rotor",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    for name in [
        "BW edge 1",
        "FW edge 1",
        "collective edge 1",
        "drivetrain 1",
        "rotor rotation",
    ] {
        assert!(text.contains(name), "eigen lacks {name}:\n{text}");
    }
    let out = flutterscope_ok(&[
        "modes",
        "--preset",
        "nrel5mw",
        "--json",
        "--set",
        "turbine.model=rotor",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let labels: Vec<&str> = json["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels.len(), 3 * 12 + 2);
    for name in [
        "collective flap 1",
        "BW flap 1",
        "FW flap 1",
        "drivetrain 1",
    ] {
        assert!(labels.contains(&name), "modes lacks {name}: {labels:?}");
    }
}

#[test]
fn a_rotor_the_preset_cannot_hold_is_refused_with_the_reason() {
    let err = |overrides: &[&str]| {
        let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        Preset::load("nrel5mw", &o).unwrap_err().to_string()
    };
    let e = err(&[
        "turbine.model=rotor",
        "turbine.source=none",
        "turbine.file=",
    ]);
    assert!(
        e.contains("turbine.drivetrain = \"free\"") && e.contains("turbine.file"),
        "{e}"
    );
    let e = err(&["operating.blades=2"]);
    assert!(e.contains("NumBl = 3"), "{e}");
    let e = Preset::load("liu2017", &["turbine.model=rotor".to_string()])
        .unwrap_err()
        .to_string();
    assert!(e.contains("tabulated blade"), "{e}");
    let e = err(&["turbine.file=blades/missing.dat"]);
    assert!(e.contains("turbine.file = \"blades/missing.dat\""), "{e}");
}

/// Above rated the IEA 15MW blade's flap modes mix strongly with the air (flap 1 turns
/// overdamped from 13 m/s, its decays seen in the ground frame as collective real roots and
/// roots at exactly 1P; a flap root with ζ ≈ 0.6 sits at 3.4 Hz), and its edge 2 is half flap.
/// The edge whirls, the collective edge and flap modes around them and the drivetrain's twist
/// keep their roots from 12 to 21 m/s (the rotor at 7.56 rpm throughout): once, the 1P images
/// took flap names and the rest passed down the line, and `BW edge 2`, more flap than edge in
/// the wind, went to a 6.8 Hz root while its own took `BW flap 2`.
#[test]
fn a_rotors_edge_names_stay_on_their_roots_while_its_flap_modes_mix_in_the_wind() {
    let names = [
        "BW edge 1",
        "FW edge 1",
        "collective edge 1",
        "BW edge 2",
        "FW edge 2",
        "collective edge 2",
        "collective flap 6",
        "drivetrain 1",
    ];
    let points: Vec<Vec<Mode>> = (12..=21)
        .map(|u| {
            let p = preset(
                "iea15mw",
                &["turbine.model=rotor", &format!("operating.wind_speed={u}")],
            );
            analyse(&p).unwrap().eigenvalues
        })
        .collect();
    for name in names {
        let hz: Vec<f64> = points.iter().map(|m| mode(m, name).frequency_hz).collect();
        for (u, w) in (12..).zip(hz.windows(2)) {
            let step = (w[1] - w[0]).abs() / w[0];
            assert!(
                step < 0.05,
                "{name}: {:.4} Hz at {u} m/s, {:.4} Hz at {} m/s",
                w[0],
                w[1],
                u + 1
            );
        }
    }
}

/// With its torque held constant (open loop) the IEA 15MW's free generator lets the rotor run
/// away slowly at 7 m/s (the rotor's aerodynamic torque rises with its speed there); a
/// generator torque that rises with speed, region 2's `Q = k Ω²` through the operating point
/// (slope `2 Q / Ω`, Q = 8.905 MN·m at 5 rpm), holds it: the rotation's root moves left by about
/// the slope over the drivetrain's whole inertia, and every root decays.
#[test]
fn a_generator_torque_that_rises_with_speed_holds_the_free_rotor() {
    let rotation = |slope: f64| {
        let p = Preset::load(
            "iea15mw",
            &[
                "turbine.model=rotor".to_string(),
                "operating.wind_speed=7".to_string(),
                format!("turbine.torque_slope={slope}"),
            ],
        )
        .unwrap();
        let stability = analyse(&p).unwrap();
        let root = stability
            .eigenvalues
            .iter()
            .find(|m| m.label == "rotor rotation")
            .unwrap()
            .re;
        let worst = stability
            .eigenvalues
            .iter()
            .map(|m| m.re)
            .fold(f64::NEG_INFINITY, f64::max);
        (root, worst, stability.verdict)
    };
    let slope = 2.0 * 8.9046e6 / (5.0 * std::f64::consts::PI / 30.0);
    let (open, _, open_verdict) = rotation(0.0);
    let (held, worst, held_verdict) = rotation(slope);
    assert!(open > 0.0, "open loop: the rotation's σ = {open}");
    assert_eq!(open_verdict, Verdict::Runaway);
    assert!(
        held < 0.0 && worst < 0.0 && held_verdict == Verdict::Stable,
        "held: σ = {held}, largest {worst}, {held_verdict:?}"
    );
    // The drivetrain's inertia about the shaft: the hub's, the generator's and three blades'.
    let shift = open - held;
    assert!(
        (0.07..0.12).contains(&shift),
        "the slope moved the rotation's root by {shift} 1/s"
    );
    let locked = Preset::load(
        "iea15mw",
        &[
            "turbine.drivetrain=locked".to_string(),
            format!("turbine.torque_slope={slope}"),
        ],
    )
    .unwrap_err()
    .to_string();
    assert!(
        locked.contains("only a free generator turns against its torque's slope"),
        "{locked}"
    );
}

/// A free rotor's turning that grows below rated (the NREL 5MW at 11 m/s: its aerodynamic
/// torque rises with speed under 11.6 rpm) is the rotor speed's runaway, named so by the
/// search and not an overspeed margin or a structural divergence.
#[test]
fn a_free_rotors_runaway_is_named_as_such() {
    let p = Preset::load("nrel5mw", &["turbine.model=rotor".to_string()]).unwrap();
    let search = flutter_search(&p, "operating.rotor_speed", 12.1, 5.0, 8).unwrap();
    let b = &search.boundary;
    let at = b.critical.unwrap();
    assert_eq!(b.kind, Some(BoundaryKind::Runaway));
    assert_eq!(b.mode.as_deref(), Some("rotor rotation"));
    assert!((11.0..12.1).contains(&at), "{at} rpm");
    assert!(
        search.message.starts_with("rotor speed runaway at")
            && search.message.contains("turbine.torque_slope"),
        "{}",
        search.message
    );
}

/// Blade `k`'s tip (twist, flap) in the state `x` of a rotor's stepper at time `t`: blade 1's
/// rows turned on by `k` thirds of a turn.
fn blade_tip(sim: &Simulator, x: &DVector<f64>, t: f64, k: usize) -> (f64, f64) {
    let l = sim.linear();
    let turning = l.turning.as_ref().expect("a rotor's blade turns");
    let psi = turning.rotor_speed * t + k as f64 * TAU / 3.0;
    let [twist, flap] = turning.tip.at(psi);
    let q = x.rows(0, l.nq);
    (
        twist.dot(&q) + l.tip_offset[0],
        flap.dot(&q) + l.tip_offset[1],
    )
}

/// Blade 1 of a rotor on a rigid drivetrain is the clamped blade: kicked alone at zero azimuth,
/// its tip as it turns (read from the ground frame's states at azimuth Ωt) follows the clamped
/// blade's response, and blades 2 and 3 stay where the equilibrium holds them, through a second
/// kick at another azimuth too.
#[test]
fn blade_1_of_a_rotor_on_a_rigid_drivetrain_moves_as_the_clamped_blade_and_alone() {
    let o = [
        "simulation.duration=3",
        "simulation.kick_twist=0.5",
        "simulation.kick_flap=0.5",
    ];
    let blade = simulate(&preset("nrel5mw", &o)).unwrap();
    let rotor_preset = preset(
        "nrel5mw",
        &[&o[..], &["turbine.model=rotor", "turbine.drivetrain=rigid"]].concat(),
    );
    let rotor = simulate(&rotor_preset).unwrap();
    assert_eq!(rotor.rotor_blade, Some(1));
    assert_eq!(rotor.t.len(), blade.t.len());
    let (flap0, twist0) = (blade.tip_flap[0], blade.tip_twist[0]);
    let mut worst: f64 = 0.0;
    for i in 0..blade.t.len() {
        worst = worst
            .max((rotor.tip_flap[i] - blade.tip_flap[i]).abs() / 0.5)
            .max((rotor.tip_twist[i] - blade.tip_twist[i]).abs() / 0.5f64.to_radians());
    }
    assert!(
        worst < 1e-8,
        "blade 1 off the clamped blade by {worst:e} of the kick"
    );
    // The response moved: the comparison is not of two resting blades.
    let swing = blade
        .tip_flap
        .iter()
        .map(|u| (u - flap0).abs())
        .fold(0.0, f64::max);
    assert!(
        swing > 0.1 && twist0.is_finite(),
        "tip flap swing {swing} m"
    );

    let mut sim = simulator(&rotor_preset).unwrap();
    let interval = 1.0 / rotor_preset.simulation.sample_rate;
    let rest: Vec<(f64, f64)> = (1..3)
        .map(|k| blade_tip(&sim, &sim.linear().x_eq, 0.0, k))
        .collect();
    for n in 1..=600 {
        if n == 237 {
            // A second kick, blade 1 a quarter turn round (12.1 rpm): still its alone.
            sim.kick(0.2f64.to_radians(), -0.3);
        }
        sim.advance(1).unwrap();
        let (x, t) = (sim.state(), n as f64 * interval);
        for (k, (twist, flap)) in (1..3).zip(&rest) {
            let (a, u) = blade_tip(&sim, &x, t, k);
            assert!(
                (a - twist).abs() < 1e-10 && (u - flap).abs() < 1e-9,
                "blade {} moved at t = {t}: twist {a} (rest {twist}), flap {u} (rest {flap})",
                k + 1
            );
        }
    }
}

/// On the whole turbine the blades share the hub: a kick of blade 1 sets its tip by exactly the
/// kick and leaves blades 2 and 3 still at that instant, at whatever azimuth it comes; then the
/// hub carries the motion to them.
#[test]
fn a_kick_on_the_turbine_moves_blade_1_alone_and_the_hub_passes_it_on() {
    let p = preset(
        "nrel5mw",
        &[
            "turbine.model=turbine",
            "simulation.kick_twist=0",
            "simulation.kick_flap=0",
        ],
    );
    let mut sim = simulator(&p).unwrap();
    let interval = 1.0 / p.simulation.sample_rate;
    sim.advance(37).unwrap();
    let t = 37.0 * interval;
    let before: Vec<(f64, f64)> = (0..3)
        .map(|k| blade_tip(&sim, &sim.state(), t, k))
        .collect();
    sim.kick(0.3f64.to_radians(), 0.4);
    let after: Vec<(f64, f64)> = (0..3)
        .map(|k| blade_tip(&sim, &sim.state(), t, k))
        .collect();
    assert!((after[0].0 - before[0].0 - 0.3f64.to_radians()).abs() < 1e-12);
    assert!((after[0].1 - before[0].1 - 0.4).abs() < 1e-12);
    for k in 1..3 {
        assert!(
            (after[k].0 - before[k].0).abs() < 1e-12 && (after[k].1 - before[k].1).abs() < 1e-12,
            "blade {} moved with the kick: {:?} → {:?}",
            k + 1,
            before[k],
            after[k]
        );
    }
    let samples = sim.advance(200).unwrap();
    assert_eq!(samples[0].tip_flap, after[0].1);
    let x = sim.state();
    let t_end = (37 + 200) as f64 * interval;
    let moved = (1..3)
        .map(|k| (blade_tip(&sim, &x, t_end, k).1 - before[k].1).abs())
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "blades 2 and 3 moved {moved} m in a second");
}

/// `simulate` on a rotor or turbine through the binary: blade 1's tip, named so; a stall model
/// stepped as its linearisation says so, in the text and the JSON; the clamped blade's JSON keeps
/// its keys.
#[test]
fn simulate_follows_blade_1_of_a_turbine_and_says_so() {
    let run = |extra: &[&str]| -> String {
        let mut args = vec![
            "simulate",
            "--preset",
            "nrel5mw",
            "--set",
            "simulation.duration=0.5",
        ];
        for e in extra {
            args.extend(["--set", e]);
        }
        String::from_utf8(flutterscope_ok(&args).stdout).unwrap()
    };
    let text = run(&["turbine.model=turbine", "aero.model=onera"]);
    assert!(
        text.contains("blade 1's tip on the turbine, onera aerodynamics (stall linearised"),
        "{text}"
    );
    assert!(text.contains("status: ok"), "{text}");
    let json = |extra: &[&str]| -> serde_json::Value {
        let mut e = extra.to_vec();
        e.push("simulation.sample_rate=100");
        let mut args = vec!["simulate", "--preset", "nrel5mw", "--json"];
        for x in &e {
            args.extend(["--set", x]);
        }
        serde_json::from_slice(&flutterscope_ok(&args).stdout).unwrap()
    };
    let v = json(&[
        "turbine.model=rotor",
        "aero.model=theodorsen",
        "simulation.duration=0.5",
    ]);
    assert_eq!(v["rotor_blade"], 1);
    assert!(v.get("stall_linearised").is_none());
    assert_eq!(v["t"].as_array().unwrap().len(), 51);
    let v = json(&["aero.model=onera", "simulation.duration=0.5"]);
    assert!(v.get("rotor_blade").is_none() && v.get("stall_linearised").is_none());
}

/// The shapes the explorer draws of `p`'s roots, with their roots.
fn shapes_of(p: &ValidPreset) -> Vec<(Mode, ModeShapes)> {
    let solution = flutterscope::analysis::solve::solve(p).unwrap();
    let stability = solution.stability().unwrap();
    let shapes = solution.mode_shapes(&stability);
    stability.eigenvalues.into_iter().zip(shapes).collect()
}

/// A rotor's mode is drawn on each blade at its azimuth, all relative to blade 1. In vacuo on
/// a rigid support the isotropic rotor's whirls are circular, so blade 2 (a third of a turn
/// ahead) moves as far as blade 1, 120° ahead in a backward whirl and 120° behind in a forward
/// one (blade 3 the other way); a collective mode moves the three alike.
#[test]
fn a_rotors_mode_shapes_show_its_whirl_in_the_blades_phases() {
    let p = preset("nrel5mw", &["turbine.model=rotor", "aero.model=none"]);
    let shapes = shapes_of(&p);
    for (label, lead) in [
        ("BW edge 1", 120.0),
        ("FW edge 1", -120.0),
        ("BW flap 2", 120.0),
        ("FW flap 2", -120.0),
        ("collective flap 1", 0.0),
        ("collective edge 1", 0.0),
    ] {
        let (_, s) = shapes.iter().find(|(m, _)| m.label == label).unwrap();
        let names: Vec<&str> = s.parts.iter().map(|p| p.part.as_str()).collect();
        assert_eq!(names, ["blade 1", "blade 2", "blade 3"], "{label}");
        assert_eq!(s.main, 0, "{label}");
        let k = s.reference.index();
        let own = &s.parts[0];
        assert!(
            (own.peaks[k] - 1.0).abs() < 1e-12 && own.phases[k].abs() < 1e-9,
            "{label}: blade 1 {} ∠{}°",
            own.peaks[k],
            own.phases[k]
        );
        for (blade, expected) in [(1, lead), (2, -lead)] {
            let part = &s.parts[blade];
            assert!(
                (part.peaks[k] - 1.0).abs() < 1e-8 && (part.phases[k] - expected).abs() < 1e-6,
                "{label} blade {}: {} ∠{}° against 1 ∠{expected}°",
                blade + 1,
                part.peaks[k],
                part.phases[k]
            );
        }
    }
}

/// A turbine's tower mode is drawn on the tower (its main part): the bending or torsion it is
/// named after, zero at the base and rising to +1 at the top, its content given by component (in
/// the wind too, where the blades hold more of the tower top's yaw); a blade mode stays on blade 1.
/// Both towers: ElastoDyn's assumed modes (no torsion) and the HAWC2 beam.
#[test]
fn a_turbines_tower_modes_are_drawn_on_its_tower() {
    for (name, towers) in [
        (
            "nrel5mw",
            vec![("tower FA 1", Family::Flap), ("tower SS 1", Family::Edge)],
        ),
        (
            "iea15mw-htc",
            vec![
                ("tower FA 1", Family::Flap),
                ("tower SS 1", Family::Edge),
                ("tower torsion 1", Family::Torsion),
            ],
        ),
    ] {
        let p = preset(name, &["turbine.model=turbine", "aero.model=none"]);
        let shapes = shapes_of(&p);
        for (label, family) in towers {
            let (m, s) = shapes.iter().find(|(m, _)| m.label == label).unwrap();
            // Its content by component, as the status line and `flutter` word it.
            assert!(
                m.described().starts_with(&format!("{label} (")) && m.described().contains("tower"),
                "{}",
                m.described()
            );
            let tower = &s.parts[s.main];
            assert_eq!(
                (tower.part.as_str(), tower.kind, s.reference),
                ("tower", PartKind::Tower, family),
                "{name} {label}"
            );
            let along = &tower.components[family.index()];
            assert!(along[0].abs() < 1e-12, "{name} {label}: base {}", along[0]);
            assert!(
                (along.last().unwrap() - 1.0).abs() < 1e-12
                    && along.windows(2).all(|w| w[1] >= w[0] - 1e-12),
                "{name} {label}: {along:?}"
            );
        }
        let (_, flap) = shapes
            .iter()
            .find(|(m, _)| m.label == "collective flap 1")
            .unwrap();
        assert_eq!(flap.parts[flap.main].part, "blade 1", "{name}");
        assert_eq!(flap.parts.len(), 4, "{name}");
    }
    // In the wind the tower top's yaw swings the blades' flap more than it twists the tower;
    // named after the tower, the root is still drawn on it, its torsion the reference.
    let p = preset(
        "iea15mw-htc",
        &["turbine.model=turbine", "operating.wind_speed=11"],
    );
    let shapes = shapes_of(&p);
    let (m, s) = shapes
        .iter()
        .find(|(m, _)| m.label == "tower torsion 1")
        .unwrap();
    let c = m.components.unwrap();
    assert!(c.tower < c.blade_flap, "{c:?}");
    assert_eq!(
        (s.parts[s.main].part.as_str(), s.reference),
        ("tower", Family::Torsion)
    );
}

/// A rotor's root is named only after a slot it holds some of: on the IEA 15MW's HAWC2 turbine
/// at rated the yaw of the tower top, swinging the blades' flap, has no twist, and once took
/// `collective torsion 1` (left over when a heavily damped flap whirl fell to the aerodynamic
/// roots) while the blades' real collective torsion was called `collective flap 3`.
#[test]
fn every_blade_torsion_name_on_the_htc_turbine_is_on_a_twisting_root() {
    for wind in ["10", "11"] {
        let p = preset(
            "iea15mw-htc",
            &[
                "turbine.model=turbine",
                &format!("operating.wind_speed={wind}"),
            ],
        );
        let modes = analyse(&p).unwrap().eigenvalues;
        let torsion: Vec<&Mode> = modes
            .iter()
            .filter(|m| m.label.contains("torsion") && !m.label.starts_with("tower"))
            .collect();
        assert!(
            torsion.len() >= 6,
            "{wind} m/s: {} torsion roots",
            torsion.len()
        );
        for m in torsion {
            let twist = m.components.unwrap().blade_twist;
            assert!(
                twist > 0.1,
                "{wind} m/s: {} at {:.3} Hz has blade twist {twist:.3}",
                m.label,
                m.frequency_hz
            );
        }
    }
}
