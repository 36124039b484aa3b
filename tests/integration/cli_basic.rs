//! The headless binary end to end: `modes`, `reproduce table1|table2`, and bad input: every
//! failure exits non-zero with a message naming file, key, value and range, and never panics.

use assert_cmd::cargo::cargo_bin_cmd;
use std::path::PathBuf;

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn run(args: &[&str]) -> Run {
    let out = cargo_bin_cmd!("flutterscope").args(args).output().unwrap();
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// A failure with a clear message: non-zero exit, no panic, every `needles` in stderr.
fn assert_fails_naming(r: &Run, needles: &[&str]) {
    assert!(
        r.code.is_some_and(|c| c != 0),
        "exit {:?}; stderr: {}",
        r.code,
        r.stderr
    );
    assert!(!r.stderr.contains("panicked"), "panic: {}", r.stderr);
    for n in needles {
        assert!(r.stderr.contains(n), "stderr lacks {n:?}: {}", r.stderr);
    }
}

/// A scratch preset file unique to this test.
fn preset_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flutterscope-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn json(r: &Run) -> serde_json::Value {
    assert_eq!(r.code, Some(0), "stderr: {}", r.stderr);
    serde_json::from_str(&r.stdout).unwrap()
}

#[test]
fn modes_json_is_sorted_and_labelled() {
    let v = json(&run(&["modes", "--preset", "liu2017", "--json"]));
    let modes = v["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 10);
    let f: Vec<f64> = modes
        .iter()
        .map(|m| m["frequency_hz"].as_f64().unwrap())
        .collect();
    assert!(f.windows(2).all(|w| w[0] <= w[1]), "{f:?}");
    assert!(f[0] > 0.0);
    assert_eq!(modes[0]["label"], "flap 1");
    let torsion = modes
        .iter()
        .filter(|m| m["label"].as_str().unwrap().starts_with("torsion"));
    assert_eq!(torsion.count(), 5);
    for m in modes {
        let share = m["torsion_share"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&share));
        assert_eq!(
            m["label"].as_str().unwrap().starts_with("torsion"),
            share > 0.5
        );
    }
}

#[test]
fn modes_follow_set_overrides() {
    let still = json(&run(&[
        "modes",
        "--json",
        "--set",
        "operating.rotor_speed=0",
    ]));
    let spinning = json(&run(&[
        "modes",
        "--json",
        "--set",
        "operating.rotor_speed=120",
    ]));
    let f = |v: &serde_json::Value| v["modes"][0]["frequency_hz"].as_f64().unwrap();
    assert!(f(&spinning) > 2.0 * f(&still));
    let n8 = json(&run(&["modes", "--json", "--set", "structure.modes=8"]));
    assert_eq!(n8["modes"].as_array().unwrap().len(), 16);
}

#[test]
fn modes_text_lists_every_mode() {
    let r = run(&["modes", "--set", "structure.form=strong"]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(r.stdout.contains("strong form"));
    for k in 1..=5 {
        assert!(r.stdout.contains(&format!("flap {k}")));
        assert!(r.stdout.contains(&format!("torsion {k}")));
    }
}

#[test]
fn reproduce_table1_carries_paper_and_ours() {
    let v = json(&run(&["reproduce", "table1", "--json"]));
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 7);
    let at45 = &rows[3];
    assert_eq!(at45["ply_angle_deg"], 45.0);
    assert_eq!(at45["paper_printed"]["c22"], 9.0509e5);
    let si = at45["paper_si"]["c22"].as_f64().unwrap();
    assert!((si - 0.90509).abs() < 1e-12);
    // The table source is exact at the nodes.
    assert!((at45["ours_table"]["c23"].as_f64().unwrap() + 0.15919).abs() < 1e-12);
    let text = run(&["reproduce", "table1"]);
    assert!(text.stdout.contains("C22") && text.stdout.contains("ours: layup"));
}

#[test]
fn reproduce_table2_meets_model_targets() {
    let v = json(&run(&["reproduce", "table2", "--json"]));
    let entries = v["entries"].as_array().unwrap();
    assert_eq!(entries.len(), 35);
    for e in entries {
        let g = |k: &str| e[k].as_f64().unwrap();
        assert!(g("ac_abs_diff").abs() <= 1e-4, "{e}");
        assert!(g("strong_rel_diff").abs() <= 0.01, "{e}");
        assert!((g("ours_ac") - g("paper_ac") - g("ac_abs_diff")).abs() < 1e-12);
    }
    let text = run(&["reproduce", "table2"]);
    assert!(text.stdout.contains("paper Present") && text.stdout.contains("ours AC (Eq. 13)"));
}

// ---- bad input ----

#[test]
fn malformed_toml_names_the_file() {
    let path = preset_file("malformed.toml", "[blade]\nlength = = 3\n");
    let p = path.to_str().unwrap();
    assert_fails_naming(&run(&["modes", "--preset", p]), &[p, "line 2"]);
}

#[test]
fn unknown_field_names_file_and_field() {
    let path = preset_file("unknown.toml", "[blade]\nlength = 3.0\nwingspan = 4.0\n");
    let p = path.to_str().unwrap();
    // The file's own schema errors point at the line.
    assert_fails_naming(&run(&["modes", "--preset", p]), &[p, "wingspan", "line 3"]);
    // An override's error names the override, on one line.
    let out = run(&["modes", "--set", "blade.wingspan=4"]);
    assert_fails_naming(
        &out,
        &[
            "unknown field `wingspan`",
            "in `blade`",
            "--set blade.wingspan=4",
        ],
    );
    assert_eq!(out.stderr.trim_end().lines().count(), 1, "{}", out.stderr);
}

#[test]
fn a_response_too_long_to_hold_is_refused_before_it_runs() {
    // 10⁴ s at 10⁵ samples/s would be 10⁹ samples (24 GB): refused, naming both keys.
    assert_fails_naming(
        &run(&[
            "simulate",
            "--set",
            "simulation.duration=1e4",
            "--set",
            "simulation.sample_rate=1e5",
        ]),
        &["simulation.duration", "simulation.sample_rate", "2e6"],
    );
}

#[test]
fn a_flutter_grid_too_large_to_hold_is_a_usage_error() {
    let r = run(&[
        "flutter",
        "--vary",
        "operating.rotor_speed",
        "--from",
        "1",
        "--to",
        "100",
        "--points",
        "100000000",
    ]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains("--points") && r.stderr.contains("2..=10000"),
        "{}",
        r.stderr
    );
}

#[test]
fn negative_length_names_key_value_and_range() {
    let path = preset_file("negative.toml", "[blade]\nlength = -2.5\n");
    let p = path.to_str().unwrap();
    assert_fails_naming(
        &run(&["modes", "--preset", p]),
        &[p, "blade.length", "-2.5", "(0, 500] m"],
    );
}

#[test]
fn nan_is_rejected_with_its_key() {
    assert_fails_naming(
        &run(&["modes", "--set", "section.c33=nan"]),
        &["section.c33", "NaN", "allowed"],
    );
    assert_fails_naming(
        &run(&["modes", "--set", "operating.rotor_speed=inf"]),
        &["operating.rotor_speed", "inf"],
    );
}

#[test]
fn set_without_equals_is_a_usage_error() {
    let r = run(&["modes", "--set", "section.ply_angle"]);
    assert_fails_naming(&r, &["key=value", "section.ply_angle"]);
    assert_eq!(r.code, Some(2));
}

#[test]
fn out_of_range_ply_angle_names_range() {
    assert_fails_naming(
        &run(&["modes", "--set", "section.ply_angle=120"]),
        &["section.ply_angle", "120", "[-90, 90] deg", "liu2017"],
    );
}

#[test]
fn missing_file_names_the_path() {
    let p = "/nonexistent/dir/blade.toml";
    assert_fails_naming(&run(&["modes", "--preset", p]), &[p, "cannot read"]);
}

#[test]
fn unknown_preset_name_lists_the_builtins() {
    assert_fails_naming(
        &run(&["modes", "--preset", "no-such-blade"]),
        &["no-such-blade", "liu2017"],
    );
}

#[test]
fn wrong_type_names_the_key() {
    assert_fails_naming(
        &run(&["modes", "--set", "structure.modes=many"]),
        &["modes", "many"],
    );
}

/// `presets --show` prints what the engine uses: the keys a preset leaves out at their defaults
/// (the stall preset does not restate the ONERA coefficients), overrides applied, and the text
/// loads back as the same preset.
#[test]
fn presets_show_prints_every_key_with_defaults_and_overrides() {
    let r = run(&[
        "presets",
        "--show",
        "liu2017-stall",
        "--set",
        "aero.onera.alpha1=10",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let body: String = r
        .stdout
        .lines()
        .filter(|l| !l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n");
    let shown: toml::Table = body.parse().expect("presets --show prints TOML");
    let onera = &shown["aero"]["onera"];
    assert_eq!(onera["alpha1"].as_float(), Some(10.0), "override applied");
    assert_eq!(onera["alpha2"].as_float(), Some(18.0), "default filled in");
    assert_eq!(onera["a_l1"].as_float(), Some(4.4));
    let again = flutterscope::preset::Preset::from_toml(&body, "shown", &[]).unwrap();
    let direct =
        flutterscope::preset::Preset::load("liu2017-stall", &["aero.onera.alpha1=10".to_string()])
            .unwrap();
    assert_eq!(
        again.into_preset().to_toml(),
        direct.into_preset().to_toml()
    );
    // A table of keys that are all unset (the HGM constants a blade's airfoil files give) is
    // left out rather than printed empty; set, it appears and loads back.
    assert!(!shown["aero"].as_table().unwrap().contains_key("hgm"));
    let r = run(&["presets", "--show", "iea15mw", "--set", "aero.hgm.tau_f=4"]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(r.stdout.contains("[aero.hgm]\ntau_f = 4.0"), "{}", r.stdout);
    assert_fails_naming(
        &run(&["presets", "--show", "no-such-blade"]),
        &["no-such-blade"],
    );
    // The name alone, as a first try would type it, shows the same preset.
    let named = run(&["presets", "goland", "--set", "operating.tunnel_speed=100"]);
    let shown = run(&[
        "presets",
        "--show",
        "goland",
        "--set",
        "operating.tunnel_speed=100",
    ]);
    assert_eq!(named.code, Some(0), "{}", named.stderr);
    assert_eq!(named.stdout, shown.stdout);
    assert!(
        named.stdout.contains("tunnel_speed = 100.0"),
        "{}",
        named.stdout
    );
    assert_ne!(
        run(&["presets", "goland", "--show", "liu2017"]).code,
        Some(0)
    );
}

// ---- hostile input: errors that name what is wrong and where ----

/// A centre of mass so far from the elastic axis that the inertia about it would be negative
/// used to surface as "mass matrix is not positive definite"; the rule names keys and values.
#[test]
fn an_offset_mass_beyond_the_inertia_names_keys_and_values() {
    let r = run(&[
        "modes",
        "--preset",
        "goland",
        "--set",
        "section.cg_offset=1",
    ]);
    assert_fails_naming(
        &r,
        &[
            "goland",
            "section.polar_inertia = 8.64",
            "section.mass_per_length × section.cg_offset² = 35.71 kg/m × (1 m)²",
            "I − m·d²",
        ],
    );
    assert_eq!(r.code, Some(1));
    assert!(!r.stderr.contains("positive definite"), "{}", r.stderr);
    // Within the rule (I = 8.64 > 35.71 × 0.45² = 7.23) the modes are computed.
    let ok = run(&[
        "modes",
        "--preset",
        "goland",
        "--set",
        "section.cg_offset=0.45",
    ]);
    assert_eq!(ok.code, Some(0), "{}", ok.stderr);
    // A layup section computes m, I and d itself: the structure says which is wrong, and where.
    let layup = run(&[
        "modes",
        "--preset",
        "demo-blade",
        "--set",
        "section.cg_offset=50",
    ]);
    assert_fails_naming(
        &layup,
        &[
            "demo-blade at operating.rotor_speed = 75 rpm",
            "inertia about its centre of mass, I − m·d²",
        ],
    );
    // A coupling stiffer than torsion and flap together carry, likewise named up front.
    let coupled = run(&["modes", "--preset", "goland", "--set", "section.c23=1e7"]);
    assert_fails_naming(
        &coupled,
        &[
            "section.c23 = 10000000",
            "section.c22 = 987000",
            "C22·C33 − C23²",
        ],
    );
}

/// A single solve that fails numerically names the preset and its operating point.
#[test]
fn numerical_errors_name_the_operating_point() {
    let point = [
        "liu2017-stall (onera aerodynamics) at operating.rotor_speed = 0 rpm",
        "operating.wind_speed = 20 m/s",
        "operating.pitch = 10 deg",
        "static equilibrium",
    ];
    for args in [
        &["eigen", "--set", "operating.rotor_speed=0"][..],
        &[
            "simulate",
            "--set",
            "operating.rotor_speed=0",
            "--set",
            "simulation.start=equilibrium",
        ][..],
    ] {
        let r = run(&[args, &["--preset", "liu2017-stall"]].concat());
        assert_fails_naming(&r, &point);
        assert_eq!(r.code, Some(1));
    }
}

/// One unconvergent grid point (0 rpm) used to abort the whole search without saying which
/// rpm; now it is skipped, and the result names it, in text and JSON.
#[test]
fn a_flutter_search_skips_a_failed_point_and_names_it() {
    let args = [
        "flutter",
        "--preset",
        "liu2017-stall",
        "--vary",
        "operating.rotor_speed",
        "--from",
        "0",
        "--to",
        "5000",
        "--points",
        "11",
    ];
    let text = run(&args);
    assert_eq!(text.code, Some(0), "{}", text.stderr);
    assert!(
        text.stdout
            .contains("1 of 11 grid points could not be solved and were skipped")
            && text
                .stdout
                .contains("operating.rotor_speed = 0 rpm: numerical: static equilibrium"),
        "{}",
        text.stdout
    );
    let v = json(&run(&[&args[..], &["--json"]].concat()));
    assert_eq!(v["failed"].as_array().unwrap().len(), 1);
    assert_eq!(v["failed"][0]["value"], 0.0);
    assert!(v["failed"][0]["error"]
        .as_str()
        .unwrap()
        .contains("static equilibrium"));
    assert!(v["message"].as_str().unwrap().contains("skipped"));
    assert!(v["max_re"].as_f64().unwrap().is_finite());
}

/// With no crossing, the JSON used to carry only nulls while the text said why.
#[test]
fn flutter_json_without_a_crossing_says_why_and_gives_the_largest_sigma() {
    let v = json(&run(&[
        "flutter",
        "--vary",
        "operating.rotor_speed",
        "--from",
        "100",
        "--to",
        "200",
        "--points",
        "5",
        "--json",
    ]));
    assert!(v["critical"].is_null());
    let message = v["message"].as_str().unwrap();
    assert!(message.contains("stable throughout"), "{message}");
    let max_re = v["max_re"].as_f64().unwrap();
    assert!(max_re < 0.0);
    assert!(
        message.contains(&format!("largest σ = {max_re:.4}")),
        "{message}"
    );
    assert_eq!(v["failed"], serde_json::json!([]));
}

/// Without `--from` the search starts at the preset's value; without `--to` it runs to the top
/// of the key's range, as the explorer's slider has it (`view.rotor_speed_max`), and says so.
#[test]
fn flutter_without_a_range_searches_from_the_preset_to_the_top_of_the_key() {
    let message = |args: &[&str]| {
        let mut all = vec![
            "flutter",
            "--vary",
            "operating.rotor_speed",
            "--points",
            "5",
            "--json",
        ];
        all.extend_from_slice(args);
        json(&run(&all))["message"].as_str().unwrap().to_string()
    };
    assert!(message(&[]).contains("in 60 … 200 rpm"), "{}", message(&[]));
    assert!(message(&["--to", "100"]).contains("in 60 … 100 rpm"));
    assert!(message(&["--from", "80"]).contains("in 80 … 200 rpm"));
    let said = run(&[
        "flutter",
        "--vary",
        "operating.rotor_speed",
        "--points",
        "5",
    ]);
    assert_eq!(said.code, Some(0), "{}", said.stderr);
    assert!(
        said.stderr
            .contains("searching operating.rotor_speed from 60 to 200"),
        "{}",
        said.stderr
    );
}

/// `--set` sets one key: a line break or a table would smuggle in more (and used to be
/// ignored silently).
#[test]
fn set_refuses_more_than_one_assignment() {
    for (value, needle) in [
        ("blade.length=5\nstructure.modes=3", "spans several lines"),
        ("blade.length=5\r\nstructure.modes=3", "spans several lines"),
        ("blade={length=5}", "table or array"),
        ("section.ply_angle=[30, 45]", "table or array"),
        ("blade.len\ngth=5", "malformed key"),
    ] {
        let r = run(&["modes", "--set", value]);
        assert_fails_naming(&r, &[needle]);
        assert_eq!(r.code, Some(2), "{value:?}: {}", r.stderr);
    }
}

/// A dumb terminal cannot hold the full-screen explorer: refused before anything is drawn,
/// pointing to the headless commands.
#[test]
fn the_explorer_refuses_a_dumb_terminal() {
    let out = cargo_bin_cmd!("flutterscope")
        .args(["tui", "--preset", "goland"])
        .env("TERM", "dumb")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("TERM=dumb") && stderr.contains("snapshot --preset goland"),
        "{stderr}"
    );
    assert!(out.stdout.is_empty());
}

/// `snapshot --size` with digits beyond any integer: too large, not "not a whole number".
#[test]
fn a_huge_snapshot_size_is_too_large() {
    let r = run(&["snapshot", "--size", "99999x99999"]);
    assert_fails_naming(&r, &["99999x99999 is too large", "1000 columns"]);
    assert_eq!(r.code, Some(2));
}

/// Still air with the stall model: the frozen aerodynamic states are neutral roots (σ = 0), and the
/// verdict says so rather than claiming every root decays.
#[test]
fn still_air_verdict_names_the_neutral_roots() {
    let r = run(&[
        "eigen",
        "--set",
        "aero.model=onera",
        "--set",
        "structure.modes=1",
        "--set",
        "aero.stations=25",
        "--set",
        "operating.rotor_speed=0",
        "--set",
        "operating.wind_speed=0",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(
        r.stdout
            .contains("STABLE: no root grows; the least damped is neutral"),
        "{}",
        r.stdout
    );
}

/// With no subcommand the explorer's options apply (`flutterscope --preset goland --set …` opens
/// the explorer on that preset, as `tui` does); after a subcommand they are the subcommand's.
#[test]
fn explorer_options_work_without_the_tui_subcommand() {
    use clap::Parser;
    use flutterscope::cli::{Cli, Command};
    let cli = Cli::try_parse_from([
        "flutterscope",
        "--preset",
        "goland",
        "--set",
        "operating.tunnel_speed=120",
        "--marker",
        "dot",
    ])
    .unwrap();
    assert!(cli.command.is_none());
    assert_eq!(cli.explorer.preset.preset, "goland");
    assert_eq!(cli.explorer.preset.set, ["operating.tunnel_speed=120"]);
    let cli = Cli::try_parse_from(["flutterscope", "eigen", "--preset", "goland"]).unwrap();
    assert!(
        matches!(cli.command, Some(Command::Eigen { ref preset, .. }) if preset.preset == "goland")
    );
    let cli = Cli::try_parse_from(["flutterscope", "tui", "--preset", "demo-blade"]).unwrap();
    assert!(matches!(cli.command, Some(Command::Tui(ref a)) if a.preset.preset == "demo-blade"));
}

/// A section turned flat by the propeller moment (thickness-direction inertia above the
/// chordwise one, rotating) is named by its cause and keys, not only "not positive definite".
#[test]
fn propeller_moment_divergence_names_its_keys() {
    assert_fails_naming(
        &run(&["modes", "--set", "section.km1_2=50"]),
        &[
            "propeller moment",
            "section.km1_2 = 50",
            "section.km2_2",
            "60 rpm",
        ],
    );
}

/// The blade keys through the binary: ranges and the rules across them name the keys,
/// exit 1, and never panic.
#[test]
fn blade_keys_name_themselves_in_errors() {
    for (sets, needles) in [
        (
            &["structure.min_elements=0"][..],
            &["structure.min_elements = 0", "integer in [1, 400]"][..],
        ),
        (
            &["structure.damping_flap=2"],
            &["structure.damping_flap = 2", "[0, 1]"],
        ),
        (
            &["blade.st_subset=0"],
            &["blade.st_subset = 0", "[1, 1000]"],
        ),
        (
            &["blade.length=60"],
            &[
                "blade.length = 60 m does not apply",
                "blade.source",
                "blade.file",
            ],
        ),
        (&["blade.file="], &["needs blade.file"]),
        (
            &["blade.source=uniform"],
            &["does not apply to blade.source = \"uniform\""],
        ),
    ] {
        let mut args = vec!["modes", "--preset", "nrel5mw"];
        for s in sets {
            args.extend(["--set", s]);
        }
        let r = run(&args);
        assert_fails_naming(&r, &[&["built-in preset 'nrel5mw'"], needles].concat());
        assert_eq!(r.code, Some(1), "{}", r.stderr);
    }
}
