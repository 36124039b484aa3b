//! `flutterscope modes` on a real blade: the NREL 5MW preset from its
//! BeamDyn files, its families, numbers, shares and damping against OpenFAST's BeamDyn
//! linearisation, the mode shapes (text, JSON, plot), where blade files resolve from, and the
//! refusal of ElastoDyn blade files.

use assert_cmd::cargo::cargo_bin_cmd;
use flutterscope::model::blade::blade_structure;
use flutterscope::physics::structure::{numbers_within_families, Family};
use flutterscope::preset::Preset;
use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn run_in(dir: Option<&Path>, args: &[&str]) -> Run {
    let mut cmd = cargo_bin_cmd!("flutterscope");
    if let Some(dir) = dir {
        cmd.current_dir(dir);
    }
    let out = cmd.args(args).output().unwrap();
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

fn run(args: &[&str]) -> Run {
    run_in(None, args)
}

fn json(r: &Run) -> Value {
    assert_eq!(r.code, Some(0), "stderr: {}", r.stderr);
    serde_json::from_str(&r.stdout).unwrap()
}

fn fails_naming(r: &Run, needles: &[&str]) {
    assert_eq!(
        r.code,
        Some(1),
        "stdout: {}\nstderr: {}",
        r.stdout,
        r.stderr
    );
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    for n in needles {
        assert!(r.stderr.contains(n), "stderr lacks {n:?}: {}", r.stderr);
    }
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("flutterscope-modes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn shipped(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(path)
}

/// `modes --preset nrel5mw --json --shapes`, computed once for the tests that read it (each run
/// solves the 120-element blade at three reference speeds).
fn nrel5mw() -> &'static Value {
    static ONCE: OnceLock<Value> = OnceLock::new();
    ONCE.get_or_init(|| {
        json(&run(&[
            "modes", "--preset", "nrel5mw", "--json", "--shapes",
        ]))
    })
}

fn modes(v: &Value) -> &Vec<Value> {
    v["modes"].as_array().unwrap()
}

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is not a number in {v}"))
}

/// Validation through the command line: the first three modes at 12.1 rpm as the
/// library test measures them (tests/integration/timoshenko.rs: 0.7366, 1.0890, 2.0054 Hz on the
/// shear-deformable beam), flap, edge, flap, with their families, numbers and shares.
#[test]
fn nrel5mw_modes_have_families_numbers_shares_and_damping() {
    let v = nrel5mw();
    assert_eq!(v["source"], "beamdyn");
    assert_eq!(num(v, "rotor_speed_rpm"), 12.1);
    let modes = modes(v);
    assert_eq!(
        modes.len(),
        12,
        "structure.modes defaults to 12 for a tabulated blade"
    );
    for (m, (hz, family, label)) in modes.iter().zip([
        (0.7366, "flap", "flap 1"),
        (1.0890, "edge", "edge 1"),
        (2.0054, "flap", "flap 2"),
    ]) {
        let f = num(m, "frequency_hz");
        assert!((f / hz - 1.0).abs() < 0.005, "{label}: {f} Hz vs {hz}");
        assert_eq!(m["family"], family);
        assert_eq!(m["label"], label);
    }
    let mut f_prev = 0.0;
    for m in modes {
        let f = num(m, "frequency_hz");
        assert!(f >= f_prev, "modes ascend in frequency");
        f_prev = f;
        let s = &m["shares"];
        let (flap, edge, twist) = (num(s, "flap"), num(s, "edge"), num(s, "twist"));
        assert!((flap + edge + twist - 1.0).abs() < 1e-9, "{m}");
        let family = m["family"].as_str().unwrap();
        let own = match family {
            "flap" => flap,
            "edge" => edge,
            _ => twist,
        };
        assert!(
            own >= flap.max(edge).max(twist),
            "{family} is the largest share: {m}"
        );
        assert_eq!(num(m, "torsion_share"), twist);
        let zeta = num(m, "damping_ratio");
        assert!(zeta > 0.0 && zeta < 0.2, "{m}");
    }
    // Modes 4–12 (which families modes 4–5 are): edge 2, flap 3, then the first
    // torsion mode at 5.58 Hz.
    let families: Vec<&str> = modes
        .iter()
        .map(|m| m["family"].as_str().unwrap())
        .collect();
    assert_eq!(&families[3..6], ["edge", "flap", "torsion"]);
}

/// Labels never repeat and each family is numbered 1, 2, 3, … in frequency order.
#[test]
fn labels_are_unique_and_numbered_consecutively_per_family() {
    for v in [
        nrel5mw().clone(),
        json(&run(&["modes", "--json", "--set", "structure.modes=8"])),
    ] {
        let mut seen = HashMap::new();
        for m in modes(&v) {
            let family = m["family"].as_str().unwrap().to_string();
            let number = m["number"].as_u64().unwrap();
            let next = seen.entry(family.clone()).or_insert(0);
            *next += 1;
            assert_eq!(number, *next, "{family} numbered out of order: {m}");
            assert_eq!(m["label"], format!("{family} {number}"));
        }
    }
    // The same rule in the library, for any sequence of families.
    let numbers =
        numbers_within_families(&[Family::Edge, Family::Flap, Family::Edge, Family::Torsion]);
    assert_eq!(numbers, [1, 1, 2, 1]);
}

/// The uniform blade reports the same fields: flap or torsion by its torsion share, no edge
/// motion, and the damping of the paper's `C_s = (η1/ω1) K_e`: ζ₁ = η1/2 for the first mode
/// when the blade does not rotate (the whole stiffness is elastic).
#[test]
fn the_uniform_blade_reports_the_same_schema() {
    let v = json(&run(&[
        "modes",
        "--json",
        "--set",
        "operating.rotor_speed=0",
        "--set",
        "structure.loss_factor=0.04",
    ]));
    assert_eq!(v["source"], "uniform");
    let modes = modes(&v);
    assert_eq!(modes.len(), 10);
    for m in modes {
        let s = &m["shares"];
        assert_eq!(num(s, "edge"), 0.0);
        assert_eq!(num(s, "twist"), num(m, "torsion_share"));
        let family = if num(s, "twist") > 0.5 {
            "torsion"
        } else {
            "flap"
        };
        assert_eq!(m["family"], family);
        assert!(m.get("shape").is_none(), "shapes only with --shapes");
    }
    let zeta1 = num(&modes[0], "damping_ratio");
    assert!((zeta1 - 0.02).abs() < 1e-9, "ζ₁ = {zeta1}");
}

/// BeamDyn's stiffness-proportional damping (`mu`, damp_type 1) projected on each mode against
/// OpenFAST's BeamDyn linearisation (presets/blades/nrel5mw/reference/frequencies.txt, BD3: its
/// damping column is the ratio ζ, 0.004419, 0.004632, 0.013145 at 0.739, 1.110, 2.087 Hz).
/// Stiffness-proportional damping gives `ζ = ω·Σμᵢ Eᵢ/(2ΣEᵢ)`, so a mode's `ζ/f` is its
/// μ-weighted strain-energy mix, whatever its frequency; the reference's frequencies are those of
/// one stiff order-5 element (docs/model.md §11.5), ours converged. Measured `ζ/f`: −0.8 %,
/// +3.0 %, 0.0 % from BeamDyn's (ζ itself 0.00437, 0.00468, 0.01263: −1.1 %, +1.0 %, −3.9 %).
/// The edge mode's shear strain takes mu1 = mu2 = 1e-3 against mu4 = 1.4e-3 on edge bending.
#[test]
fn projected_damping_matches_the_beamdyn_linearisation() {
    let modes = modes(nrel5mw());
    for (m, (zeta_ref, f_ref, tolerance)) in modes.iter().zip([
        (0.004419, 0.739, 0.02),
        (0.004632, 1.110, 0.04),
        (0.013145, 2.087, 0.02),
    ]) {
        let (zeta, f) = (num(m, "damping_ratio"), num(m, "frequency_hz"));
        let (ours, reference) = (zeta / f, zeta_ref / f_ref);
        assert!(
            (ours / reference - 1.0).abs() < tolerance,
            "{}: ζ/f = {ours} vs BeamDyn {reference}",
            m["label"]
        );
    }
}

/// The projection itself: without rotation every strain energy is elastic, so for each mode
/// `2ζ/ω = Σ μᵢ Eᵢ / Σ Eᵢ` (Eᵢ the mode's strain energy in shear, bending or twist, μᵢ its
/// factor) lies between the smallest and largest factor (mu1 = mu2 = 0.001 on shear, mu4 =
/// 0.0014 on edge bending, mu5 = mu6 = 0.0022 on flap bending and twist), nearer its own
/// family's: measured 1.90e-3…2.17e-3 for the flap modes, 1.23e-3…1.39e-3 for the edge modes
/// (the higher, the more shear), 2.2e-3 exactly for the torsion modes (pure twist in this file).
/// Rotating, the centrifugal stiffness adds undamped strain energy: flap 1 falls below.
#[test]
fn projected_damping_is_the_mu_weighted_strain_energy() {
    let at = |rpm: &str| {
        let p = Preset::load("nrel5mw", &[format!("operating.rotor_speed={rpm}")]).unwrap();
        blade_structure(&p)
            .unwrap()
            .unwrap()
            .modes(p.omega())
            .unwrap()
    };
    let between = 0.5 * (0.0014 + 0.0022);
    for m in at("0") {
        let ratio = 2.0 * m.damping_ratio / (m.frequency_hz * std::f64::consts::TAU);
        assert!(
            (0.001 * (1.0 - 1e-9)..=0.0022 * (1.0 + 1e-9)).contains(&ratio),
            "{:?} at {} Hz: 2ζ/ω = {ratio}",
            m.family(),
            m.frequency_hz
        );
        match m.family() {
            Family::Flap => assert!(ratio > between, "flap: {ratio}"),
            Family::Edge => assert!(ratio < between, "edge: {ratio}"),
            Family::Torsion => assert!((ratio / 0.0022 - 1.0).abs() < 1e-6, "torsion: {ratio}"),
        }
    }
    let spinning = at("12.1");
    let flap1 = &spinning[0];
    assert_eq!(flap1.family(), Family::Flap);
    let ratio = 2.0 * flap1.damping_ratio / (flap1.frequency_hz * std::f64::consts::TAU);
    assert!(ratio < 0.0022 * 0.95, "flap 1 rotating: 2ζ/ω = {ratio}");
}

/// An explicit `structure.damping_*` replaces the file's damping for every mode of its family
/// and leaves the other families alone.
#[test]
fn a_family_damping_key_overrides_the_files_for_that_family() {
    let v = json(&run(&[
        "modes",
        "--preset",
        "nrel5mw",
        "--json",
        "--set",
        "structure.damping_edge=0.01",
        "--set",
        "structure.damping_torsion=0",
        "--set",
        "structure.min_elements=1",
    ]));
    let mut flap_zetas = Vec::new();
    for m in modes(&v) {
        let zeta = num(m, "damping_ratio");
        match m["family"].as_str().unwrap() {
            // Through the modal damping matrix `2ζω` and back: exact up to the last bit.
            "edge" => assert!((zeta - 0.01).abs() <= 1e-15, "{zeta}"),
            "torsion" => assert_eq!(zeta, 0.0),
            _ => flap_zetas.push(zeta),
        }
    }
    // Flap keeps the projected mu damping: different for each mode, growing with frequency.
    assert!(flap_zetas.len() >= 3 && flap_zetas.windows(2).all(|w| w[1] > w[0]));
}

/// `modes --shapes --json`: every mode's flap, edge and twist at the mesh nodes from root to
/// tip, zero at the clamped root, scaled so that its own family's component peaks at +1.
#[test]
fn shapes_json_gives_each_mode_along_the_span_scaled_by_its_family() {
    for m in modes(nrel5mw()) {
        let s = &m["shape"];
        let get = |k: &str| -> Vec<f64> {
            s[k].as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let (z, r) = (get("z"), get("r"));
        let fields = [get("flap"), get("edge"), get("twist")];
        assert_eq!(z.len(), 121, "120 elements: 121 nodes");
        assert!(fields.iter().all(|f| f.len() == z.len()));
        assert_eq!(z[0], 0.0);
        assert!((z[z.len() - 1] - 61.5).abs() < 1e-9);
        assert!(z.iter().zip(&r).all(|(z, r)| (r - z - 1.5).abs() < 1e-12));
        assert!(fields.iter().all(|f| f[0] == 0.0), "clamped root");
        let (key, own) = match m["family"].as_str().unwrap() {
            "flap" => ("flap", &fields[0]),
            "edge" => ("edge", &fields[1]),
            _ => ("twist", &fields[2]),
        };
        assert_eq!(s["scaled_by"], key);
        let peak = own
            .iter()
            .fold(0.0f64, |a, &x| if x.abs() > a.abs() { x } else { a });
        assert!((peak - 1.0).abs() < 1e-12, "{}: peak {peak}", m["label"]);
    }
    // The first flap mode bends the whole blade one way, its tip furthest out.
    let flap1 = &modes(nrel5mw())[0]["shape"]["flap"];
    let u: Vec<f64> = flap1
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(
        u.windows(2).all(|w| w[1] >= w[0]),
        "flap 1 grows toward the tip"
    );
    assert_eq!(u[u.len() - 1], 1.0);
}

/// `modes --shapes` as text: the summary, then one table per mode (z, r, flap, edge, twist at
/// the nodes) with its scaling stated.
#[test]
fn shapes_text_has_a_table_per_mode() {
    let r = run(&[
        "modes",
        "--preset",
        "nrel5mw",
        "--shapes",
        "--set",
        "structure.min_elements=1",
        "--set",
        "structure.modes=4",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(
        r.stdout.contains("4 blade modes at 12.1 rpm"),
        "{}",
        r.stdout
    );
    assert!(
        r.stdout.contains("48 shear-deformable elements"),
        "the 49 stations alone"
    );
    for label in ["flap 1", "edge 1", "flap 2", "edge 2"] {
        assert!(
            r.stdout.contains(&format!("\n{label} at ")),
            "no shape table for {label}"
        );
    }
    assert!(r
        .stdout
        .contains("flap u peaks at +1 m; v in m per m, φ in rad per m"));
    assert!(r.stdout.contains("edge v peaks at +1 m"));
    let header_rows = r.stdout.matches("z (m)").count();
    assert_eq!(header_rows, 4);
    // 49 node rows under each header.
    let rows = r
        .stdout
        .lines()
        .filter(|l| {
            l.split_whitespace().count() == 5 && l.trim_start().starts_with(char::is_numeric)
        })
        .count();
    assert_eq!(rows, 4 * 49, "{}", r.stdout);
    let plain = run(&[
        "modes",
        "--preset",
        "nrel5mw",
        "--set",
        "structure.min_elements=1",
    ]);
    assert!(!plain.stdout.contains("z (m)"), "shapes only with --shapes");
}

/// `modes --plot FILE`: the shapes as SVG (flap, edge and twist panels, a line per mode) or PNG.
#[test]
fn shapes_plot_as_svg_and_png() {
    let dir = scratch("plot");
    let svg = dir.join("shapes.svg");
    let png = dir.join("shapes.png");
    for path in [&svg, &png] {
        let r = run(&[
            "modes",
            "--preset",
            "nrel5mw",
            "--set",
            "structure.min_elements=1",
            "--set",
            "structure.modes=5",
            "--plot",
            path.to_str().unwrap(),
        ]);
        assert_eq!(r.code, Some(0), "{}", r.stderr);
        assert!(r.stderr.contains("plot written to"), "{}", r.stderr);
    }
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("SVG parses");
    let polylines = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .count();
    assert!(polylines >= 15, "5 modes × 3 panels: {polylines} polylines");
    for needle in ["flap 1", "edge 1", "twist", "Mode shapes", "nrel5mw"] {
        assert!(text.contains(needle), "SVG lacks {needle}");
    }
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let bad = run(&["modes", "--plot", dir.join("shapes.pdf").to_str().unwrap()]);
    assert_eq!(bad.code, Some(2), "{}", bad.stderr);
    assert!(bad.stderr.contains(".pdf"));
}

/// The built-in preset carries its blade files in the binary: it runs from any directory.
#[test]
fn the_builtin_preset_runs_from_another_directory() {
    let dir = scratch("elsewhere");
    let v = json(&run_in(
        Some(&dir),
        &[
            "modes",
            "--preset",
            "nrel5mw",
            "--json",
            "--set",
            "structure.modes=3",
            "--set",
            "structure.min_elements=1",
        ],
    ));
    let f = num(&modes(&v)[0], "frequency_hz");
    assert!((f / 0.7366 - 1.0).abs() < 0.005, "{f}");
}

/// A user's preset resolves `blade.file` against its own directory, and BeamDyn's `BldFile`
/// against the primary file's: a copy of the NREL 5MW files beside a preset in a temporary
/// directory gives the built-in preset's modes, run from anywhere.
#[test]
fn a_user_preset_reads_its_own_blade_files_relative_to_itself() {
    let dir = scratch("user");
    std::fs::create_dir_all(dir.join("blade")).unwrap();
    for name in [
        "NRELOffshrBsline5MW_BeamDyn.dat",
        "NRELOffshrBsline5MW_BeamDyn_Blade.dat",
    ] {
        std::fs::copy(
            shipped(&format!("blades/nrel5mw/{name}")),
            dir.join("blade").join(name),
        )
        .unwrap();
    }
    let text = "[blade]\nsource = \"beamdyn\"\nfile = \"blade/NRELOffshrBsline5MW_BeamDyn.dat\"\n\
                hub_radius = 1.5\n[operating]\nrotor_speed = 12.1\npitch = 0.0\n\
                [structure]\nmodes = 3\nmin_elements = 1\n[aero]\nmodel = \"none\"\n\
                [view]\nrotor_speed_max = 20.0\n";
    let preset = dir.join("mine.toml");
    std::fs::write(&preset, text).unwrap();
    let elsewhere = scratch("user-cwd");
    let mine = json(&run_in(
        Some(&elsewhere),
        &["modes", "--preset", preset.to_str().unwrap(), "--json"],
    ));
    let builtin = json(&run(&[
        "modes",
        "--preset",
        "nrel5mw",
        "--json",
        "--set",
        "structure.modes=3",
        "--set",
        "structure.min_elements=1",
    ]));
    // The same blade, mesh and basis range (the built-in's Campbell range is 20 rpm, as this
    // preset's): the same frequencies.
    for (a, b) in modes(&mine).iter().zip(modes(&builtin)) {
        let (fa, fb) = (num(a, "frequency_hz"), num(b, "frequency_hz"));
        assert!((fa / fb - 1.0).abs() < 1e-12, "{fa} vs {fb}");
        assert_eq!(a["label"], b["label"]);
    }
    // Relative to the preset, not to the working directory: run from the preset's parent with
    // a relative preset path, the same file is found.
    let parent = dir.parent().unwrap();
    let relative = format!("{}/mine.toml", dir.file_name().unwrap().to_str().unwrap());
    assert_eq!(
        json(&run_in(
            Some(parent),
            &["modes", "--preset", &relative, "--json"]
        ))["modes"],
        mine["modes"]
    );

    // A preset whose file is missing: the message names the preset, the key and the path it
    // resolved to.
    std::fs::write(
        dir.join("missing.toml"),
        text.replace("blade/NREL", "nowhere/NREL"),
    )
    .unwrap();
    let missing = dir.join("missing.toml");
    let resolved = dir.join("nowhere/NRELOffshrBsline5MW_BeamDyn.dat");
    fails_naming(
        &run(&["modes", "--preset", missing.to_str().unwrap()]),
        &[
            missing.to_str().unwrap(),
            "blade.file = \"nowhere/NRELOffshrBsline5MW_BeamDyn.dat\"",
            resolved.to_str().unwrap(),
            "cannot read",
        ],
    );
    // A primary file whose BldFile is missing: the blade file's resolved path.
    std::fs::remove_file(dir.join("blade/NRELOffshrBsline5MW_BeamDyn_Blade.dat")).unwrap();
    fails_naming(
        &run(&["modes", "--preset", preset.to_str().unwrap()]),
        &[dir
            .join("blade/NRELOffshrBsline5MW_BeamDyn_Blade.dat")
            .to_str()
            .unwrap()],
    );
}

/// An ElastoDyn blade file has no torsional stiffness: pointing `blade.file` at the shipped one
/// ends in a message that says so and names the file, not in a parse error at some line.
#[test]
fn an_elastodyn_blade_file_is_refused_for_its_missing_torsion() {
    let elastodyn = shipped("blades/nrel5mw/NRELOffshrBsline5MW_Blade.dat");
    let path = elastodyn.to_str().unwrap();
    for (preset, source) in [("nrel5mw", "beamdyn"), ("iea15mw", "hawc2")] {
        let r = run(&[
            "modes",
            "--preset",
            preset,
            "--set",
            &format!("blade.source={source}"),
            "--set",
            &format!("blade.file={path}"),
        ]);
        fails_naming(
            &r,
            &[
                &format!("{path}: this is an ElastoDyn blade file"),
                "carry no torsional stiffness",
                "BeamDyn",
                "HAWC2 st",
            ],
        );
        assert!(
            !r.stderr.contains(&format!("{path}:1")),
            "not a line error: {}",
            r.stderr
        );
    }
}

/// The IEA 15MW presets from their HAWC2 st files (docs/model.md §11.6): the baseline's lowest
/// modes are flap, edge, flap, edge, flap with the frequencies of its shear-deformable beam on
/// the prebent axis (0.5307 Hz flap 1, 0.6979 Hz edge 1, 1.5073 Hz flap 2 at rated), damped as
/// the preset states (3 % log decrement); the bend–twist-coupled blade twists more toward
/// feather per metre of flap in its first mode, on the straight beam (on the prebent one the
/// BTC blade's first mode is 45 % edge, whose bending the curve turns into twist of its own).
#[test]
fn iea15mw_presets_read_their_hawc2_files() {
    let base = json(&run(&["modes", "--preset", "iea15mw", "--json"]));
    let m = modes(&base);
    let families: Vec<&str> = m[..5]
        .iter()
        .map(|m| m["family"].as_str().unwrap())
        .collect();
    assert_eq!(families, ["flap", "edge", "flap", "edge", "flap"]);
    for (mode, want) in m.iter().zip([0.5307, 0.6979, 1.5073]) {
        let f = num(mode, "frequency_hz");
        assert!((f / want - 1.0).abs() < 2e-3, "{f} vs {want}");
        assert!((num(mode, "damping_ratio") - 0.00477).abs() < 1e-12);
    }
    // The first mode scaled to 1 m of peak flap: its tip twist (rad per m), toward feather.
    let tip_twist = |preset: &str| {
        let v = json(&run(&[
            "modes",
            "--preset",
            preset,
            "--json",
            "--shapes",
            "--set",
            "structure.curved=false",
        ]));
        let twist = modes(&v)[0]["shape"]["twist"].as_array().unwrap().clone();
        twist.last().unwrap().as_f64().unwrap()
    };
    let (btc, baseline) = (tip_twist("iea15mw-btc-st2019"), tip_twist("iea15mw"));
    assert!(
        btc > 1.3 * baseline && baseline > 0.0,
        "{btc} vs {baseline}"
    );
}

/// A HAWC2 blade needs the file its twist comes from, and only a HAWC2 blade takes one.
#[test]
fn the_twist_file_belongs_to_hawc2_blades_only() {
    fails_naming(
        &run(&["modes", "--preset", "iea15mw", "--set", "blade.twist_file="]),
        &["blade.twist_file", "AeroDyn 15", "no twist"],
    );
    fails_naming(
        &run(&[
            "modes",
            "--preset",
            "nrel5mw",
            "--set",
            "blade.twist_file=blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
        ]),
        &["blade.twist_file", "does not apply", "beamdyn"],
    );
    fails_naming(
        &run(&[
            "modes",
            "--preset",
            "iea15mw",
            "--set",
            "blade.twist_file=nowhere.dat",
        ]),
        &["blade.twist_file = \"nowhere.dat\"", "nowhere.dat"],
    );
}
