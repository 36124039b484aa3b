//! The whole turbine in the ground frame (docs/model.md §13.6): the rotor on ElastoDyn's tower,
//! checked against OpenFAST's linearisation of the same turbine, the published full-system
//! frequencies, its own rotating-frame form (the azimuth drops out after the multi-blade
//! transform; the Floquet analysis of the periodic system agrees), and through the binary.

use super::{copy_tree, flutterscope_ok};
use flutterscope::analysis::eigen::analyse;
use flutterscope::analysis::mode::Mode;
use flutterscope::formats::elastodyn_tower::read_tower;
use flutterscope::formats::elastodyn_turbine::read_turbine;
use flutterscope::model::turbine::{rotor_inputs, support_of};
use flutterscope::numeric::decompose;
use flutterscope::physics::structure::Structure;
use flutterscope::physics::turbine::rotating_system;
use flutterscope::physics::turbine::rotor::Rotor;

use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::{Complex, DMatrix};
use std::f64::consts::TAU;
use std::path::Path;
use std::sync::Arc;

fn preset(overrides: &[&str]) -> ValidPreset {
    preset_of("nrel5mw", overrides)
}

fn preset_of(name: &str, overrides: &[&str]) -> ValidPreset {
    let mut o: Vec<String> = vec!["turbine.model=turbine".to_string()];
    o.extend(overrides.iter().map(|s| s.to_string()));
    Preset::load(name, &o).unwrap()
}

/// A turbine of each source: ElastoDyn's four-mode tower, HAWC2's beam tower with torsion.
const TURBINES: [&str; 2] = ["nrel5mw", "iea15mw-htc"];

fn hz(modes: &[Mode], label: &str) -> f64 {
    modes
        .iter()
        .find(|m| m.label == label)
        .unwrap_or_else(|| panic!("no {label}"))
        .frequency_hz
}

fn assert_within(label: &str, got: f64, published: f64, tol: f64) {
    assert!(
        (got / published - 1.0).abs() < tol,
        "{label}: {got:.4} Hz against {published} Hz"
    );
}

/// The NREL 5MW tower with the nacelle and the hub on top and no blades, from the onshore
/// ElastoDyn files, against ElastoDyn's own linearisation of it (the `ED.lin` case of
/// `../shared/blades/nrel5mw/reference/frequencies.txt`, whose blades are BeamDyn's and
/// not on ElastoDyn's tower): 0.3497, 0.3544, 2.8829, 2.9651 Hz within 1 %.
#[test]
fn the_nrel5mw_tower_has_elastodyns_own_frequencies() {
    let main = Path::new("presets/blades/nrel5mw-turbine/onshore/ElastoDyn.dat");
    let turbine = read_turbine(main).unwrap();
    let tower = read_tower(&turbine.tower_file_path(main)).unwrap();
    let tower = support_of(&turbine, &tower).unwrap().tower;
    let l = tower
        .mass
        .clone()
        .cholesky()
        .unwrap()
        .l()
        .try_inverse()
        .unwrap();
    let a = &l * &tower.stiffness * l.transpose();
    let mut f: Vec<f64> = a
        .symmetric_eigen()
        .eigenvalues
        .iter()
        .map(|w2| w2.sqrt() / TAU)
        .collect();
    f.sort_by(f64::total_cmp);
    for (got, published) in f.iter().zip([0.349716, 0.354365, 2.882901, 2.965065]) {
        assert_within("tower", *got, published, 0.01);
    }
}

/// OpenFAST's linearisation of the whole NREL 5MW at 12.1 rpm, no air, generator free (case
/// `1.lin`): the two first tower modes 0.3221 / 0.3272 Hz and the collective edge mode the
/// drivetrain lifts, 1.6916 Hz, within 3 %. The blades' first flap and edge modes, which the
/// case lists in the blades' rotating frame (0.7295, 0.7410, 0.7630 and 1.1099, 1.1267 Hz),
/// are ours shifted back by the rotor speed (BW + Ω, FW − Ω), within 3 %, and its 2.0181 Hz a
/// second flap mode of ours within 3 %. (Its lowest, 0.1885 Hz, no mode of ours matches.)
#[test]
fn the_whole_nrel5mw_at_rated_speed_has_openfasts_frequencies() {
    let p = preset(&["aero.model=none"]);
    let modes = analyse(&p).unwrap().eigenvalues;
    let f = |label: &str| hz(&modes, label);
    let mut tower = [f("tower FA 1"), f("tower SS 1")];
    tower.sort_by(f64::total_cmp);
    assert_within("tower 1", tower[0], 0.322053, 0.03);
    assert_within("tower 2", tower[1], 0.327190, 0.03);
    assert_within("collective edge 1", f("collective edge 1"), 1.691631, 0.03);
    let omega = 12.1 / 60.0;
    let mut flap = [
        f("BW flap 1") + omega,
        f("collective flap 1"),
        f("FW flap 1") - omega,
    ];
    flap.sort_by(f64::total_cmp);
    for (got, published) in flap.iter().zip([0.729459, 0.741033, 0.763015]) {
        assert_within("flap 1 (rotating)", *got, published, 0.03);
    }
    // 2.0181 Hz: a second flap mode, nearest of ours in the blades' frame.
    let flap_2 = [
        f("BW flap 2") + omega,
        f("collective flap 2"),
        f("FW flap 2") - omega,
    ];
    let nearest = flap_2
        .iter()
        .copied()
        .min_by(|a, b| (a - 2.018051).abs().total_cmp(&(b - 2.018051).abs()))
        .unwrap();
    assert_within("flap 2 (rotating)", nearest, 2.018051, 0.03);
    let mut edge = [f("BW edge 1") + omega, f("FW edge 1") - omega];
    edge.sort_by(f64::total_cmp);
    for (got, published) in edge.iter().zip([1.109901, 1.126696]) {
        assert_within("edge 1 (rotating)", *got, published, 0.03);
    }
}

/// Jonkman et al. (2009), NREL/TP-500-38060, table 9-1: the land-based turbine at rest, brake
/// engaged, no air (FAST): tower fore–aft 0.3240 and 2.9003 Hz, side–side 0.3120 and 2.9361 Hz,
/// drivetrain 0.6205 Hz, within 3 %, on the blade degrees of freedom FAST gives a blade
/// (ElastoDyn's flap 1, flap 2 and edge 1: `structure.modes = 3`). On the whole basis the tower's
/// first modes and the drivetrain stay within 3 %; the second side–side mode rises 5.6 % above
/// FAST's (docs/model.md §13.6): the hub turning against the blades' edgewise bending
/// (`collective edge 1`), which one edge mode a blade puts above that tower mode, falls below it
/// on the whole basis and pushes it up.
#[test]
fn the_nrel5mw_turbine_at_rest_has_the_published_tower_frequencies() {
    let at_rest = |modes: &str| {
        let p = preset(&[
            "aero.model=none",
            "operating.schedule=none",
            "operating.rotor_speed=0",
            "turbine.drivetrain=locked",
            modes,
        ]);
        analyse(&p).unwrap().eigenvalues
    };
    let published = [
        ("tower FA 1", 0.3240),
        ("tower SS 1", 0.3120),
        ("tower FA 2", 2.9003),
        ("tower SS 2", 2.9361),
        ("drivetrain 1", 0.6205),
    ];
    let fast = at_rest("structure.modes=3");
    for (label, published) in published {
        assert_within(label, hz(&fast, label), published, 0.03);
    }
    assert!(hz(&fast, "collective edge 1") > hz(&fast, "tower SS 2"));
    let whole = at_rest("structure.modes=12");
    for (label, published) in published.into_iter().filter(|(l, _)| *l != "tower SS 2") {
        assert_within(label, hz(&whole, label), published, 0.03);
    }
    assert!(hz(&whole, "collective edge 1") < hz(&whole, "tower SS 2"));
}

/// The rotating-frame state matrix of `p`'s turbine with blade 0 at `azimuth`, and its
/// multi-blade transform there.
fn at_azimuth(p: &ValidPreset, azimuth: f64) -> (DMatrix<f64>, DMatrix<f64>) {
    let (system, eq) = flutterscope::model::system::system_with_equilibrium(p).unwrap();
    let x = eq.unwrap_or_else(|| system.equilibrium().unwrap());
    let rpm = flutterscope::model::operating::scheduled_rotor_speed(p).unwrap();
    let inputs = rotor_inputs(p, rpm).unwrap().unwrap();
    let r = rotating_system(&system, &x, &inputs, azimuth).unwrap();
    let ground = r
        .layout
        .transform(&r.system.a, azimuth, inputs.rotor_speed)
        .unwrap();
    (r.system.a, ground)
}

fn max_abs(a: &DMatrix<f64>) -> f64 {
    a.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// On its tower the rotor's state matrix turns with the blades; after the multi-blade
/// transform it is the same at every azimuth (an isotropic rotor in uniform inflow), in the
/// wind as in vacuo, to 1e-9 of its largest entry.
#[test]
fn the_turbine_in_the_ground_frame_is_the_same_at_every_azimuth() {
    for (name, air) in TURBINES
        .into_iter()
        .flat_map(|n| ["aero.model=theodorsen", "aero.model=none"].map(|a| (n, a)))
    {
        let p = preset_of(name, &[air]);
        let (rotating, ground) = at_azimuth(&p, 0.0);
        for psi in [0.3, 1.7, 4.0] {
            let (turned, turned_ground) = at_azimuth(&p, psi);
            assert!(
                max_abs(&(&turned - &rotating)) > 1e-5 * max_abs(&rotating),
                "{name}, {air}: the rotating-frame matrix does not turn with the rotor ({:e})",
                max_abs(&(&turned - &rotating)) / max_abs(&rotating)
            );
            let d = max_abs(&(&turned_ground - &ground)) / max_abs(&ground);
            assert!(
                d < 1e-9,
                "{name}, {air}, ψ = {psi}: the ground-frame matrix moves by {d:e}"
            );
        }
    }
}

/// The periodic three-blade system in the blades' rotating frames, integrated over one turn
/// (RK4, the rotor rebuilt at every stage's azimuth), has the Floquet multipliers `exp(λT)` of
/// the ground-frame roots λ, to 3e-8 (a heavily damped root's multiplier, 1e-3 in size, is
/// the least well conditioned eigenvalue of the monodromy matrix: round-off in the system moves
/// it by 1e-8). In vacuo, generator locked (a free one's rigid rotation
/// is a double root at zero, which no integration splits cleanly), four modes per blade, at
/// 30 rpm so that one turn is short.
#[test]
fn the_turbine_in_the_ground_frame_is_its_floquet_analysis() {
    for name in TURBINES {
        floquet_matches_the_ground_frame(name);
    }
}

fn floquet_matches_the_ground_frame(name: &str) {
    let p = preset_of(
        name,
        &[
            "aero.model=none",
            "structure.modes=4",
            "operating.schedule=none",
            "operating.rotor_speed=30",
            "turbine.drivetrain=locked",
        ],
    );
    let blade = flutterscope::model::structure::for_preset(&p).unwrap();
    let q_eq = blade.stiffness().lu().solve(&blade.static_load()).unwrap();
    let inputs = rotor_inputs(&p, 30.0).unwrap().unwrap();
    let omega = inputs.rotor_speed;
    let state_matrix = |psi: f64| {
        let rotor = Rotor::new(Arc::clone(&blade), &inputs, &q_eq, psi).unwrap();
        let n = rotor.coordinates();
        let m_inv = rotor.mass().clone().try_inverse().unwrap();
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        a.view_mut((0, n), (n, n)).fill_with_identity();
        a.view_mut((n, 0), (n, n))
            .copy_from(&(-&m_inv * rotor.stiffness()));
        a.view_mut((n, n), (n, n))
            .copy_from(&(-&m_inv * rotor.damping()));
        (a, rotor)
    };
    let (a0, rotor) = state_matrix(0.0);
    let dim = a0.nrows();
    let tower = inputs.support.as_ref().unwrap().tower.coordinates();
    assert_eq!(dim, 2 * (3 * 4 + 1 + tower));
    let period = TAU / omega;
    let steps = 8000;
    let h = period / steps as f64;
    let mut phi = DMatrix::<f64>::identity(dim, dim);
    let mut a_start = a0.clone();
    for i in 0..steps {
        let t = i as f64 * h;
        let a_mid = state_matrix(omega * (t + 0.5 * h)).0;
        let a_end = state_matrix(omega * (t + h)).0;
        let k1 = &a_start * &phi;
        let k2 = &a_mid * (&phi + &k1 * (0.5 * h));
        let k3 = &a_mid * (&phi + &k2 * (0.5 * h));
        let k4 = &a_end * (&phi + &k3 * h);
        phi += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
        a_start = a_end;
    }
    let multipliers = phi.complex_eigenvalues();
    let layout = flutterscope::physics::turbine::ground::layout(&rotor, dim).unwrap();
    let ground = layout.transform(&a0, 0.0, omega).unwrap();
    let roots = decompose(&ground, false).unwrap().values;
    let roots: Vec<Complex<f64>> = roots
        .iter()
        .copied()
        .chain(roots.iter().filter(|l| l.im != 0.0).map(|l| l.conj()))
        .collect();
    assert_eq!(roots.len(), dim);
    // A blade mode's BW, FW and collective roots differ by ±iΩ: one multiplier, three times,
    // split by the integration's error. So each root is matched to its nearest multiplier and
    // each multiplier to its nearest root, not one to one.
    let multipliers: Vec<Complex<f64>> = multipliers.iter().copied().collect();
    let wanted: Vec<Complex<f64>> = roots.iter().map(|l| (l * period).exp()).collect();
    let nearest = |z: Complex<f64>, among: &[Complex<f64>]| {
        among
            .iter()
            .map(|m| (m - z).norm())
            .fold(f64::INFINITY, f64::min)
    };
    for (l, want) in roots.iter().zip(&wanted) {
        let d = nearest(*want, &multipliers);
        assert!(
            d < 3e-8,
            "{name}, root {l}: exp(λT) = {want}, nearest multiplier off by {d:e}"
        );
    }
    for m in &multipliers {
        let d = nearest(*m, &wanted);
        assert!(
            d < 3e-8,
            "{name}: multiplier {m} is no root's, off by {d:e}"
        );
    }
}

/// With no structural damping the turbine in vacuo is conservative: the rotation's Coriolis and
/// centrifugal terms between the blades and the tower move energy about and never add or
/// take any, so every ground-frame root lies on the imaginary axis (to 1e-9 of the largest).
/// A sign slip in any of them would not survive: the transform is exact either way (the
/// tests above), the energy is not.
#[test]
fn the_undamped_turbine_in_vacuo_neither_gains_nor_loses_energy() {
    for name in TURBINES {
        conserves_energy(name);
    }
}

fn conserves_energy(name: &str) {
    let p = preset_of(name, &["aero.model=none", "turbine.drivetrain=locked"]);
    let blade = flutterscope::model::structure::for_preset(&p).unwrap();
    let q_eq = blade.stiffness().lu().solve(&blade.static_load()).unwrap();
    let rpm = flutterscope::model::operating::scheduled_rotor_speed(&p).unwrap();
    let inputs = rotor_inputs(&p, rpm).unwrap().unwrap();
    let rotor = Rotor::new(Arc::clone(&blade), &inputs, &q_eq, 0.0).unwrap();
    let n = rotor.coordinates();
    let m_inv = rotor.mass().clone().try_inverse().unwrap();
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, n), (n, n)).fill_with_identity();
    a.view_mut((n, 0), (n, n))
        .copy_from(&(-&m_inv * rotor.stiffness()));
    a.view_mut((n, n), (n, n))
        .copy_from(&(-&m_inv * rotor.gyroscopic()));
    let layout = flutterscope::physics::turbine::ground::layout(&rotor, 2 * n).unwrap();
    let ground = layout.transform(&a, 0.0, inputs.rotor_speed).unwrap();
    let roots = decompose(&ground, false).unwrap().values;
    let scale = roots.iter().map(|l| l.norm()).fold(0.0, f64::max);
    let worst = roots.iter().map(|l| l.re.abs()).fold(0.0, f64::max);
    assert!(
        worst < 1e-9 * scale,
        "{name}: a root off the imaginary axis by {worst:e} (largest root {scale})"
    );
}

#[test]
fn the_commands_name_the_turbines_modes() {
    let run = |command: &str| {
        let out = flutterscope_ok(&[
            command,
            "--preset",
            "nrel5mw",
            "--set",
            "turbine.model=turbine",
        ]);
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    let out = run("modes");
    assert!(
        out.contains("modes of the turbine (3 blades on a free drivetrain, on its tower)"),
        "{out}"
    );
    for label in [
        "tower FA 1",
        "tower SS 1",
        "tower FA 2",
        "tower SS 2",
        "BW edge 1",
    ] {
        assert!(out.contains(label), "no {label} in\n{out}");
    }
    let out = run("eigen");
    assert!(
        out.contains("tower SS 1") && out.contains("STABLE"),
        "{out}"
    );
}

/// `eigen --json` gives each root of the turbine its kinetic energy by component, summing to 1;
/// the tower's modes are mostly the tower's, the whirling edge modes the blades' edge; one
/// blade has no components.
#[test]
fn the_json_gives_each_root_its_share_by_component() {
    let json = |model: &str| {
        let out = flutterscope_ok(&[
            "eigen",
            "--preset",
            "nrel5mw",
            "--set",
            &format!("turbine.model={model}"),
            "--json",
        ]);
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let turbine = json("turbine");
    let roots = turbine["eigenvalues"].as_array().unwrap();
    let part = |label: &str, component: &str| {
        let root = roots.iter().find(|r| r["label"] == label).unwrap();
        let c = &root["components"];
        let total: f64 = [
            "blade_flap",
            "blade_edge",
            "blade_twist",
            "drivetrain",
            "tower",
        ]
        .iter()
        .map(|k| c[k].as_f64().unwrap())
        .sum();
        assert!((total - 1.0).abs() < 1e-12, "{label}: {c}");
        c[component].as_f64().unwrap()
    };
    for label in ["tower FA 1", "tower SS 1"] {
        assert!(part(label, "tower") > 0.9, "{label}");
    }
    for label in ["BW edge 1", "FW edge 1"] {
        assert!(part(label, "blade_edge") > 0.9, "{label}");
    }
    assert!(part("BW flap 1", "blade_flap") > 0.5);
    // Each blade-mode root's frequency in the blades' frame: ground ± 1P.
    let hz = |label: &str, key: &str| {
        roots.iter().find(|r| r["label"] == label).unwrap()[key]
            .as_f64()
            .unwrap_or(f64::NAN)
    };
    let one_p = 12.1 / 60.0;
    assert!(
        (hz("BW edge 1", "rotating_hz") - hz("BW edge 1", "frequency_hz") - one_p).abs() < 1e-12
    );
    assert!(
        (hz("FW edge 1", "frequency_hz") - hz("FW edge 1", "rotating_hz") - one_p).abs() < 1e-12
    );
    assert_eq!(
        hz("collective flap 1", "rotating_hz"),
        hz("collective flap 1", "frequency_hz")
    );
    assert!(hz("tower FA 1", "rotating_hz").is_nan());
    let blade = json("blade");
    assert!(blade["eigenvalues"][0].get("components").is_none());
}

#[test]
fn a_turbine_without_its_files_is_refused_with_the_reason() {
    let err = |overrides: &[String]| Preset::load("nrel5mw", overrides).unwrap_err().to_string();
    let e = err(&[
        "turbine.model=turbine".to_string(),
        "turbine.source=none".to_string(),
        "turbine.file=".to_string(),
        "turbine.drivetrain=rigid".to_string(),
    ]);
    assert!(
        e.contains("turbine.model = \"turbine\" reads the tower"),
        "{e}"
    );
    // The main file alone, away from the tower file its TwrFile names.
    let dir = std::env::temp_dir().join(format!("flutterscope-tower-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let main = dir.join("ElastoDyn.dat");
    std::fs::copy(
        "presets/blades/nrel5mw-turbine/onshore/ElastoDyn.dat",
        &main,
    )
    .unwrap();
    let e = err(&[
        "turbine.model=turbine".to_string(),
        format!("turbine.file={}", main.display()),
    ]);
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(
        e.contains("NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat") && e.contains("TwrFile"),
        "{e}"
    );
    // A HAWC2 turbine's key without its source, the source without its key, the ElastoDyn key
    // beside it.
    let htc =
        "turbine.htc_file=blades/iea15mw-hawc2/IEA-15-240-RWT-Onshore/htc/IEA_15MW_RWT_Onshore.htc";
    for (overrides, says) in [
        (
            vec![htc.to_string()],
            "is a HAWC2 model's: set turbine.source = \"hawc2\"",
        ),
        (
            vec![
                "turbine.source=hawc2".to_string(),
                "turbine.file=".to_string(),
            ],
            "turbine.source = \"hawc2\" needs turbine.htc_file",
        ),
        (
            vec!["turbine.source=hawc2".to_string(), htc.to_string()],
            "is an ElastoDyn main file's key",
        ),
    ] {
        let e = err(&overrides);
        assert!(e.contains(says), "{overrides:?}: {e}");
    }
}

/// The lowest root of `f` in `(a, b)` (where it changes sign), by bisection.
fn root_between(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if f(a) * f(m) <= 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
    0.5 * (a + b)
}

/// A uniform beam tower from a HAWC2 st table carrying a point mass and a yaw inertia on its
/// top has the cantilever's exact frequencies: bending with a tip mass (`1 + cos x cosh x +
/// μ x (cos x sinh x − sin x cosh x) = 0`, `μ` the tip's share of the tower's mass) and torsion
/// with a tip inertia (`x tan x = j L / J`), to 1e-3 (the tower's weight, its shear and its
/// rotary inertia take under 5e-4).
#[test]
fn a_uniform_beam_tower_has_the_cantilevers_exact_frequencies() {
    use flutterscope::formats::hawc2_st::parse_st;
    use flutterscope::physics::blade::hawc2::{from_hawc2_st, ChordTwist};
    use flutterscope::physics::blade::modal::StiffnessFactors;
    use flutterscope::physics::turbine::tower::{Tower, TowerMode, TowerTop};
    use flutterscope::physics::turbine::tower_beam::BeamTowerInputs;
    let (length, m, ei, gj, ri) = (50.0, 100.0, 2e11, 1.6e11, 0.5_f64);
    let row = |r: f64| format!("{r} {m} 0 0 {ri} {ri} 0 0 2e11 8e10 1 1 2 1 1 10 0 0 0\n");
    let text = format!("1\n#1 tower\n$1 2\n{}{}", row(0.0), row(length));
    let st = parse_st(&text, "tower_st.dat").unwrap();
    let table = from_hawc2_st(&st, 1, 1, &ChordTwist::untwisted(), 0.0).unwrap();
    let j = m * 2.0 * ri * ri;
    let (tip_mass, tip_inertia) = (0.5 * m * length, j * length);
    let top = TowerTop {
        yaw_bearing_mass: 0.0,
        nacelle_mass: tip_mass,
        nacelle_cm: [0.0; 3],
        nacelle_inertia: [[0.0; 3], [0.0; 3], [0.0, 0.0, tip_inertia]],
        hub_mass: 0.0,
        hub_cm: 0.0,
        overhang: 0.0,
        shaft_height: 0.0,
    };
    let no_damping = StiffnessFactors {
        shear: [0.0; 2],
        flap: 0.0,
        edge: 0.0,
        torsion: 0.0,
    };
    let tower = Tower::from_beam(
        &BeamTowerInputs {
            table,
            damping: no_damping,
            elements: 40,
        },
        &top,
    )
    .unwrap();
    let mu = tip_mass / (m * length);
    let bending = root_between(
        |x: f64| 1.0 + x.cos() * x.cosh() + mu * x * (x.cos() * x.sinh() - x.sin() * x.cosh()),
        0.5,
        1.875,
    );
    let bending_hz = bending * bending * (ei / (m * length.powi(4))).sqrt() / TAU;
    let torsion = root_between(|x: f64| x * x.tan() - j * length / tip_inertia, 0.1, 1.5);
    let torsion_hz = torsion / length * (gj / j).sqrt() / TAU;
    let a = tower.mass.clone().try_inverse().unwrap() * &tower.stiffness;
    let mut found: Vec<f64> = a
        .complex_eigenvalues()
        .iter()
        .map(|l| l.re.sqrt() / TAU)
        .collect();
    found.sort_by(f64::total_cmp);
    assert_eq!(
        tower.modes,
        [
            TowerMode::ForeAft1,
            TowerMode::ForeAft2,
            TowerMode::SideSide1,
            TowerMode::SideSide2,
            TowerMode::Torsion1
        ]
    );
    for (what, got, exact) in [
        ("fore–aft 1", found[0], bending_hz),
        ("side–side 1", found[1], bending_hz),
        ("torsion 1", found[4], torsion_hz),
    ] {
        assert!(
            ((got - exact) / exact).abs() < 1e-3,
            "{what}: {got} Hz, exact {exact} Hz"
        );
    }
}

/// A beam tower carrying a nacelle that tilts with its top section: soft in shear, its top's
/// rotary inertia acts on the section's turn (`u' − γ`), so its modes do not move as the
/// elements shrink (40 against 160, to 1e-4; on the centreline's slope instead, the shear
/// strain of an ever shorter top element lets the nacelle's inertia go, and the second
/// fore–aft mode moved by 20 %).
#[test]
fn a_beam_towers_modes_with_a_tilting_nacelle_do_not_move_with_its_mesh() {
    use flutterscope::formats::hawc2_st::parse_st;
    use flutterscope::physics::blade::hawc2::{from_hawc2_st, ChordTwist};
    use flutterscope::physics::blade::modal::StiffnessFactors;
    use flutterscope::physics::turbine::tower::{Tower, TowerTop};
    use flutterscope::physics::turbine::tower_beam::BeamTowerInputs;
    let row = |r: f64| format!("{r} 5000 0 0 2 2 0 0 2e11 8e10 5 5 10 0.5 0.5 0.2 0 0 0\n");
    let text = format!("1\n#1 tower\n$1 2\n{}{}", row(0.0), row(100.0));
    let st = parse_st(&text, "tower_st.dat").unwrap();
    let table = from_hawc2_st(&st, 1, 1, &ChordTwist::untwisted(), 0.0).unwrap();
    let top = TowerTop {
        yaw_bearing_mass: 0.0,
        nacelle_mass: 4e5,
        nacelle_cm: [-5.0, 0.0, 4.0],
        nacelle_inertia: [[2e7, 0.0, 0.0], [0.0, 3e7, 0.0], [0.0, 0.0, 2e7]],
        hub_mass: 0.0,
        hub_cm: 0.0,
        overhang: -10.0,
        shaft_height: 5.0,
    };
    let frequencies = |elements: usize| {
        let inputs = BeamTowerInputs {
            table: table.clone(),
            damping: StiffnessFactors {
                shear: [0.0; 2],
                flap: 0.0,
                edge: 0.0,
                torsion: 0.0,
            },
            elements,
        };
        let tower = Tower::from_beam(&inputs, &top).unwrap();
        let a = tower.mass.clone().try_inverse().unwrap() * &tower.stiffness;
        let mut f: Vec<f64> = a
            .complex_eigenvalues()
            .iter()
            .map(|l| l.re.sqrt() / TAU)
            .collect();
        f.sort_by(f64::total_cmp);
        f
    };
    let (coarse, fine) = (frequencies(40), frequencies(160));
    for (a, b) in coarse.iter().zip(&fine) {
        assert!(
            ((a - b) / b).abs() < 1e-4,
            "40 elements: {coarse:?}, 160: {fine:?}"
        );
    }
}

/// The IEA 15MW's HAWC2 model and its ElastoDyn files describe one tower (from the transition
/// piece, 15 m up): the whole turbine read from either has its first tower modes within 5 %
/// (HAWC2's beam 0.224 / 0.231 Hz, ElastoDyn's polynomial shapes 0.233 / 0.242 Hz), and only
/// the HAWC2 tower twists.
#[test]
fn the_iea15mw_tower_from_its_htc_model_and_from_its_elastodyn_files_agree() {
    let modes_of = |name: &str| {
        let p = preset_of(name, &["aero.model=none"]);
        flutterscope::model::turbine::structure_in_vacuo(&p)
            .unwrap()
            .natural_modes()
            .unwrap()
    };
    let (htc, elastodyn) = (modes_of("iea15mw-htc"), modes_of("iea15mw"));
    let freq = |modes: &[flutterscope::physics::structure::NaturalMode], label: &str| {
        modes
            .iter()
            .find(|m| m.label == label)
            .unwrap_or_else(|| panic!("no {label}"))
            .frequency_hz
    };
    for label in ["tower FA 1", "tower SS 1"] {
        let (a, b) = (freq(&htc, label), freq(&elastodyn, label));
        assert!(
            ((a - b) / b).abs() < 0.05,
            "{label}: HAWC2 {a} Hz, ElastoDyn {b} Hz"
        );
    }
    let torsion = freq(&htc, "tower torsion 1");
    assert!(
        (1.0..5.0).contains(&torsion),
        "tower torsion 1 at {torsion} Hz"
    );
    assert!(elastodyn.iter().all(|m| m.label != "tower torsion 1"));
}

/// A HAWC2 turbine the program cannot read says which file, line and block, and why.
#[test]
fn a_broken_htc_turbine_names_its_file_line_and_the_problem() {
    let dir = std::env::temp_dir().join(format!("flutterscope-htc-turbine-{}", std::process::id()));
    let model = dir.join("model");
    let shared = Path::new("presets/blades/iea15mw-hawc2");
    copy_tree(shared, &model);
    let constraint = model.join("IEA-15-240-RWT/IEA_15MW_RWT_WTG_constraint.htc");
    let text = std::fs::read_to_string(&constraint).unwrap();
    std::fs::write(
        &constraint,
        text.replace("begin bearing1;", "begin fix1;")
            .replace("end bearing1;", "end fix1;"),
    )
    .unwrap();
    let preset = std::fs::read_to_string("presets/iea15mw-htc.toml")
        .unwrap()
        .replace(
            "blades/iea15mw/",
            &format!(
                "{}/",
                Path::new("presets/blades/iea15mw")
                    .canonicalize()
                    .unwrap()
                    .display()
            ),
        )
        .replace("blades/iea15mw-hawc2/", "model/");
    let file = dir.join("broken.toml");
    std::fs::write(&file, preset).unwrap();
    let e = Preset::load(
        file.to_str().unwrap(),
        &["turbine.model=turbine".to_string()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("turbine.htc_file")
            && e.contains("exactly one shaft bearing")
            && e.contains("fix1 shaft_rot"),
        "{e}"
    );
    let bodies = model.join("IEA-15-240-RWT/IEA_15MW_RWT_WTG_bodies_noFPM.htc");
    let text = std::fs::read_to_string(&bodies).unwrap();
    std::fs::write(&bodies, text.replace("concentrated_mass  1  0.00   0.00    0.00    28249   0.00          0.00           0.00    ;", "concentrated_mass  1  0.00 0.00 28249 ;")).unwrap();
    std::fs::write(
        &constraint,
        text_of_original(&shared.join("IEA-15-240-RWT/IEA_15MW_RWT_WTG_constraint.htc")),
    )
    .unwrap();
    let e = Preset::load(
        file.to_str().unwrap(),
        &["turbine.model=turbine".to_string()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("IEA_15MW_RWT_WTG_bodies_noFPM.htc:")
            && e.contains("main_body towertop")
            && e.contains("concentrated_mass"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

fn text_of_original(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap()
}
