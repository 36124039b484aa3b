//! The hostile-input corpus: whatever a user, a script or a damaged file feeds the
//! program, it answers with finite numbers or an error that names what was wrong; never a panic,
//! never a NaN. Four parts:
//!
//! 1. the preset schema: every numeric key of [`KEYS`] at its bounds, just beyond, far beyond,
//!    NaN and ±∞, on every built-in preset (library), plus a handful through the binary for exit
//!    codes;
//! 2. random combinations of legal extremes (preset × aero model × N × stations × rotor, wind and
//!    tunnel speed, pitch, form, start) through eigen, modes, a short flutter search and a short
//!    simulation, plus the largest sizes (N = 40, 64 stations) a few times each;
//! 3. preset files truncated at every character boundary, and mutated at random: duplicated
//!    tables, wrong types, junk bytes, very long lines;
//! 4. sizes: each part counts its cases (`CASES_*` below); run time is bounded by counting, not
//!    by a clock, so a slow machine runs the same corpus.
//!
//! Generated cases use proptest with a fixed case count and seed and no failure files: every run
//! draws the same corpus and leaves nothing behind.

use assert_cmd::cargo::cargo_bin_cmd;
use flutterscope::analysis::eigen::{analyse, Stability};
use flutterscope::analysis::flutter::{flutter_search, Search};
use flutterscope::analysis::response::{simulate, Response};
use flutterscope::error::Error;
use flutterscope::model::for_preset;
use flutterscope::physics::structure::NaturalMode;
use flutterscope::preset::{builtin_names, AeroModel, KeySpec, Preset, ValidPreset, BUILTIN, KEYS};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed, TestCaseError};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Random combinations through the four analyses (part 2).
const CASES_COMBINATIONS: u32 = 400;
/// Random mutations of preset files (part 3).
const CASES_MUTATIONS: u32 = 2000;
/// The generators' seed: every run draws the same corpus, so CI cannot fail by chance. Set
/// `PROPTEST_RNG_SEED` to draw another.
const SEED: u64 = 15;

/// A fixed case count and seed, and no failure-persistence files (CI runs in a fresh clone; a
/// failure prints its minimal case instead).
fn config(cases: u32) -> ProptestConfig {
    let base = ProptestConfig::with_cases(cases);
    ProptestConfig {
        failure_persistence: None,
        rng_seed: match base.rng_seed {
            RngSeed::Random => RngSeed::Fixed(SEED),
            chosen => chosen,
        },
        ..base
    }
}

/// `f()`, or a test failure naming `what` if it panicked.
fn no_panic<T>(what: &str, f: impl FnOnce() -> T) -> T {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(v) => v,
        Err(payload) => {
            let text = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            panic!("{what} panicked: {text}")
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 1. The schema: every numeric key at and beyond its bounds
// ---------------------------------------------------------------------------------------------

/// A float as TOML text (TOML spells NaN and infinities `nan`, `inf`).
fn toml_float(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{v:?}")
    }
}

/// The values tried for one key, as TOML text: its bounds, the middle, just beyond each bound,
/// far beyond, the extremes of f64, NaN and ±∞; for integer keys also a fraction and a float.
fn hostile_values(spec: &KeySpec) -> Vec<String> {
    let (lo, hi) = (spec.min, spec.max);
    let span = hi - lo;
    let floats = [
        lo,
        hi,
        0.5 * (lo + hi),
        lo - 1e-9 * span,
        hi + 1e-9 * span,
        lo + 1e-9 * span,
        lo - 1e6 * span,
        hi + 1e6 * span,
        f64::MAX,
        f64::MIN,
        f64::MIN_POSITIVE,
        5e-324,
        -0.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    if spec.integer {
        let (lo, hi) = (lo as i64, hi as i64);
        [
            lo,
            hi,
            (lo + hi) / 2,
            lo - 1,
            hi + 1,
            -1_000_000,
            i64::MAX,
            0,
        ]
        .iter()
        .map(i64::to_string)
        .chain(["1.5", "2.0", "1e300", "nan", "inf"].map(String::from))
        .collect()
    } else {
        floats.iter().map(|&v| toml_float(v)).collect()
    }
}

/// Loading `--set key=literal` either succeeds with a value in range, or fails with an error
/// that names the preset and the key, and for a range error the value and the allowed range.
fn check_set(name: &str, spec: &KeySpec, literal: &str) {
    let set = format!("{}={literal}", spec.key);
    let loaded = no_panic(&format!("{name} --set {set}"), || {
        Preset::load(name, std::slice::from_ref(&set))
    });
    let origin = format!("built-in preset '{name}'");
    match loaded {
        Ok(p) => {
            let v = (spec.get)(&p);
            assert!(spec.contains(v), "{name} --set {set} accepted {v}");
            let given: f64 = literal.parse().unwrap_or(f64::NAN);
            assert!(v == given, "{name} --set {set} gave {v}");
            // What loads, the structure takes: natural modes, finite, or a numerical error.
            match no_panic(&format!("modes of {name} --set {set}"), || {
                for_preset(&p).and_then(|m| m.natural_modes())
            }) {
                Ok(modes) => assert!(
                    mode_numbers(&modes).iter().all(|x| x.is_finite()),
                    "{name} --set {set}: non-finite modes"
                ),
                Err(e) => assert!(
                    matches!(&e, Error::Numerical(m) if !m.is_empty()),
                    "{name} --set {set}: {e:?}"
                ),
            }
        }
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with(&origin), "{set}: no origin in {msg}");
            match &e {
                Error::Range {
                    key,
                    value,
                    allowed,
                    ..
                } => {
                    assert_eq!(key, spec.key, "{set}: {msg}");
                    assert_eq!(allowed, &spec.allowed(), "{set}: {msg}");
                    let shown: f64 = value.parse().unwrap_or_else(|_| panic!("{set}: {msg}"));
                    let given: f64 = literal.parse().unwrap_or(f64::NAN);
                    assert!(
                        shown == given || (shown.is_nan() && given.is_nan()),
                        "{set}: value {value} in {msg}"
                    );
                    assert!(!spec.contains(shown), "{set}: in range yet refused: {msg}");
                }
                // A type the key cannot hold (a fraction for an integer key): the override is
                // quoted whole.
                Error::Preset { .. } => {
                    assert!(msg.contains(&format!("--set {set}")), "{set}: {msg}")
                }
                // In range, but against a rule across keys: the rule names the key.
                Error::Invalid { .. } => assert!(msg.contains(spec.key), "{set}: {msg}"),
                other => panic!("{set}: unexpected error kind {other:?}"),
            }
        }
    }
}

#[test]
fn every_key_at_and_beyond_its_bounds_loads_or_names_key_value_and_range() {
    let mut cases = 0;
    for name in builtin_names() {
        let base = Preset::load(name, &[]).unwrap();
        for spec in KEYS {
            for literal in hostile_values(spec) {
                check_set(name, spec, &literal);
                // The explorer and the sweeps change keys through `with`: same contract.
                let v: f64 = literal.parse().unwrap_or(f64::NAN);
                match no_panic(&format!("{name}.with({}, {v})", spec.key), || {
                    base.with(spec.key, v)
                }) {
                    Ok(p) => assert!(spec.contains((spec.get)(&p))),
                    Err(e) => assert!(e.to_string().contains(spec.key), "{}: {e}", spec.key),
                }
                cases += 2;
            }
        }
    }
    eprintln!("schema corpus: {cases} loads");
    assert!(cases > 3000, "{cases}");
}

/// The same contract through the real binary: exit 1 for input errors, 2 for usage errors, a
/// message naming the key, and never a panic.
#[test]
fn hostile_arguments_through_the_binary_exit_1_or_2_without_panicking() {
    let cases: &[(&[&str], i32, &[&str])] = &[
        (
            &["modes", "--set", "structure.modes=41"],
            1,
            &["structure.modes = 41", "integer in [1, 40]"],
        ),
        (
            &["modes", "--set", "structure.modes=1.5"],
            1,
            &["--set structure.modes=1.5"],
        ),
        (
            &["eigen", "--set", "operating.wind_speed=-inf"],
            1,
            &["operating.wind_speed = -inf", "[0, 200] m/s"],
        ),
        (
            &["simulate", "--set", "simulation.sample_rate=nan"],
            1,
            &["simulation.sample_rate = NaN"],
        ),
        (
            &[
                "eigen",
                "--preset",
                "goland",
                "--set",
                "section.cg_offset=50",
            ],
            1,
            &["section.cg_offset", "I − m·d²"],
        ),
        (
            &[
                "presets",
                "--show",
                "demo-blade",
                "--set",
                "blade.length=1e308",
            ],
            1,
            &["blade.length", "(0, 500] m"],
        ),
        (
            &["sweep", "--vary", "operating.rotor_speed=0:inf:1"],
            2,
            &["'inf' is not a finite number"],
        ),
        (
            &[
                "flutter",
                "--vary",
                "operating.pitch",
                "--from",
                "nan",
                "--to",
                "1",
            ],
            2,
            &["give two different finite values"],
        ),
        (
            &[
                "flutter",
                "--vary",
                "structure.modes",
                "--from",
                "1",
                "--to",
                "5",
            ],
            2,
            &["integer setting"],
        ),
        (&["modes", "--set", "section.ply_angle"], 2, &["key=value"]),
        (&["snapshot", "--size", "0x0"], 2, &["smaller than 80x24"]),
    ];
    for (args, code, needles) in cases {
        let out = cargo_bin_cmd!("flutterscope").args(*args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(*code), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        for n in *needles {
            assert!(stderr.contains(n), "{args:?}: stderr lacks {n:?}: {stderr}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2. Random combinations of legal extremes through the analyses
// ---------------------------------------------------------------------------------------------

/// One operating point and model, each value legal on its own.
#[derive(Debug, Clone)]
struct Case {
    preset: &'static str,
    model: AeroModel,
    modes: usize,
    stations: usize,
    rotor_speed: f64,
    wind_speed: f64,
    tunnel_speed: f64,
    pitch: f64,
    strong: bool,
    from_rest: bool,
}

impl Case {
    /// The preset, validated; a short simulation (0.05 s, 11 samples) keeps each case cheap.
    fn preset(&self) -> Result<ValidPreset, Error> {
        let set = [
            format!("aero.model={}", self.model.name()),
            format!("structure.modes={}", self.modes),
            format!("aero.stations={}", self.stations),
            format!("operating.rotor_speed={:?}", self.rotor_speed),
            format!("operating.wind_speed={:?}", self.wind_speed),
            format!("operating.tunnel_speed={:?}", self.tunnel_speed),
            format!("operating.pitch={:?}", self.pitch),
            format!(
                "structure.form={}",
                if self.strong { "strong" } else { "weak" }
            ),
            format!(
                "simulation.start={}",
                if self.from_rest {
                    "rest"
                } else {
                    "equilibrium"
                }
            ),
            "simulation.duration=0.05".into(),
            "simulation.sample_rate=200.0".into(),
        ];
        Preset::load(self.preset, &set)
    }
}

/// A speed: zero, the top of its range, or anywhere between.
fn speed(max: f64) -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(max), 0.0..=max]
}

fn case() -> impl Strategy<Value = Case> {
    let names: Vec<&'static str> = BUILTIN.iter().map(|(n, _)| *n).collect();
    (
        (
            proptest::sample::select(names),
            proptest::sample::select(AeroModel::ALL.to_vec()),
            1usize..=12,
            1usize..=24,
        ),
        (
            speed(5000.0),
            speed(200.0),
            prop_oneof![3 => Just(0.0), 1 => speed(1000.0)],
            prop_oneof![Just(-90.0), Just(90.0), -90.0..=90.0f64],
            any::<bool>(),
            any::<bool>(),
        ),
    )
        .prop_map(
            |((preset, model, modes, stations), (rotor, wind, tunnel, pitch, strong, rest))| Case {
                preset,
                model,
                modes,
                stations,
                rotor_speed: rotor,
                wind_speed: wind,
                tunnel_speed: tunnel,
                pitch,
                strong,
                from_rest: rest,
            },
        )
}

/// Every number of an eigen-analysis.
fn stability_numbers(s: &Stability) -> Vec<f64> {
    s.eigenvalues
        .iter()
        .chain(&s.aero_lags)
        .flat_map(|m| {
            [
                m.re,
                m.im,
                m.frequency_hz,
                m.damping_ratio,
                m.structural_share,
            ]
        })
        .collect()
}

fn mode_numbers(modes: &[NaturalMode]) -> Vec<f64> {
    modes
        .iter()
        .flat_map(|m| [m.frequency_hz, m.torsion_share])
        .collect()
}

fn search_numbers(s: &Search) -> Vec<f64> {
    let b = &s.boundary;
    [Some(s.max_re), b.critical, b.frequency_hz]
        .into_iter()
        .flatten()
        .chain(s.failed.iter().map(|f| f.value))
        .collect()
}

fn response_numbers(r: &Response) -> Vec<f64> {
    r.t.iter()
        .chain(&r.tip_twist)
        .chain(&r.tip_flap)
        .chain(&r.diverged_at)
        .copied()
        .collect()
}

const ANALYSES: [&str; 4] = ["eigen", "modes", "flutter", "simulate"];

/// How the analyses ended, [results, numerical errors] per analysis of [`ANALYSES`]: printed, so
/// a run shows what the corpus covered.
#[derive(Default)]
struct Tally([[AtomicUsize; 2]; 4]);

impl Tally {
    fn count(&self, what: &str, failed: bool) {
        if let Some(k) = ANALYSES.iter().position(|a| *a == what) {
            self.0[k][usize::from(failed)].fetch_add(1, Ordering::Relaxed);
        }
    }

    fn summary(&self) -> String {
        ANALYSES
            .iter()
            .zip(&self.0)
            .map(|(a, [ok, err])| {
                let (ok, err) = (ok.load(Ordering::Relaxed), err.load(Ordering::Relaxed));
                format!("{a} {ok} results / {err} numerical errors")
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// One analysis of a case: no panic, and either finite numbers that serialize to JSON, or a
/// numerical error with a message (the preset is valid, so nothing else may fail).
fn analysis<T: serde::Serialize>(
    tally: &Tally,
    case: &Case,
    what: &str,
    run: impl FnOnce() -> Result<T, Error>,
    numbers: impl FnOnce(&T) -> Vec<f64>,
) -> Result<(), TestCaseError> {
    let outcome = no_panic(&format!("{what} of {case:?}"), run);
    tally.count(what, outcome.is_err());
    match outcome {
        Ok(v) => {
            let bad: Vec<f64> = numbers(&v).into_iter().filter(|x| !x.is_finite()).collect();
            prop_assert!(bad.is_empty(), "{what}: non-finite {bad:?} for {case:?}");
            prop_assert!(serde_json::to_string(&v).is_ok(), "{what}: JSON");
        }
        Err(e) => {
            prop_assert!(
                matches!(&e, Error::Numerical(m) if !m.trim().is_empty()),
                "{what} of {case:?}: {e:?}"
            );
        }
    }
    Ok(())
}

/// Eigen, modes, a flutter search along pitch (2 grid points and a bisection if it crosses) and
/// a 0.05 s simulation. Still air with the stall model is included (its aerodynamic states are
/// frozen: the eigen-solver isolates them, tests/integration/eigen.rs).
fn analyse_case(tally: &Tally, case: &Case) -> Result<(), TestCaseError> {
    let p = match no_panic(&format!("loading {case:?}"), || case.preset()) {
        Ok(p) => p,
        // Legal values that break a rule across keys together: named, and nothing to analyse.
        Err(e @ Error::Invalid { .. }) => {
            prop_assert!(e.to_string().contains(case.preset));
            return Ok(());
        }
        Err(e) => return Err(TestCaseError::fail(format!("{case:?}: {e}"))),
    };
    analysis(tally, case, "eigen", || analyse(&p), stability_numbers)?;
    analysis(
        tally,
        case,
        "modes",
        || for_preset(&p).and_then(|m| m.natural_modes()),
        |m| mode_numbers(m),
    )?;
    let (from, to) = if case.pitch <= 88.0 {
        (case.pitch, case.pitch + 2.0)
    } else {
        (case.pitch, case.pitch - 2.0)
    };
    analysis(
        tally,
        case,
        "flutter",
        || flutter_search(&p, "operating.pitch", from, to, 2),
        search_numbers,
    )?;
    analysis(tally, case, "simulate", || simulate(&p), response_numbers)
}

#[test]
fn legal_extremes_give_finite_numbers_or_a_numerical_error() {
    let tally = Tally::default();
    proptest::proptest!(config(CASES_COMBINATIONS), |(case in case())| {
        analyse_case(&tally, &case)?;
    });
    eprintln!("combination corpus: {}", tally.summary());
}

/// The largest sizes the schema allows, a few times each: N = 40 Galerkin functions per field,
/// 64 aerodynamic stations.
#[test]
fn the_largest_sizes_give_finite_numbers_or_a_numerical_error() {
    let big = |preset, model, modes, stations, rotor_speed, wind_speed| Case {
        preset,
        model,
        modes,
        stations,
        rotor_speed,
        wind_speed,
        tunnel_speed: 0.0,
        pitch: 10.0,
        strong: false,
        from_rest: true,
    };
    let cases = [
        big("liu2017", AeroModel::QuasiSteady, 40, 8, 60.0, 20.0),
        big("goland", AeroModel::Theodorsen, 40, 16, 0.0, 0.0),
        big("demo-blade", AeroModel::None, 40, 8, 5000.0, 0.0),
        big("liu2017-stall", AeroModel::Onera, 5, 64, 60.0, 20.0),
        big("demo-blade", AeroModel::Theodorsen, 6, 64, 200.0, 40.0),
        big("liu2017", AeroModel::Onera, 12, 64, 0.0, 200.0),
    ];
    let tally = Tally::default();
    for case in &cases {
        analyse_case(&tally, case).unwrap_or_else(|e| panic!("{e}"));
    }
    eprintln!("largest sizes: {}", tally.summary());
}

// ---------------------------------------------------------------------------------------------
// 3. Damaged preset files
// ---------------------------------------------------------------------------------------------

/// Parsing `text` never panics; an error names `origin` first.
fn check_file(text: &str, origin: &str) -> Result<(), TestCaseError> {
    let r = no_panic(&format!("from_toml of {} bytes", text.len()), || {
        Preset::from_toml(text, origin, &[])
    });
    if let Err(e) = r {
        let msg = e.to_string();
        prop_assert!(msg.starts_with(&format!("{origin}: ")), "{msg}");
    }
    Ok(())
}

#[test]
fn a_preset_truncated_anywhere_loads_or_names_its_origin() {
    let mut cases = 0;
    for (name, text) in BUILTIN {
        let origin = format!("{name}.toml");
        for cut in (0..=text.len()).filter(|&i| text.is_char_boundary(i)) {
            check_file(&text[..cut], &origin).unwrap_or_else(|e| panic!("cut at {cut}: {e}"));
            cases += 1;
        }
    }
    eprintln!("truncation corpus: {cases} files");
}

#[test]
fn hand_made_damage_loads_or_names_its_origin() {
    let liu = BUILTIN[0].1;
    let long_number = format!("[blade]\nlength = 1{}\n", "0".repeat(100_000));
    let long_string = format!("[meta]\nname = \"{}\"\n", "x".repeat(1_000_000));
    let long_key = format!("[blade]\n{} = 1.0\n", "k".repeat(100_000));
    let deep = format!(
        "[meta]\nname = {}{}\n",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    let deep_tables = format!(
        "[meta]\nname = {}1{}\n",
        "{a = ".repeat(100_000),
        "}".repeat(100_000)
    );
    let many_tables = "[blade]\n".repeat(10_000);
    let files: Vec<String> = vec![
        String::new(),
        " \n\t\n".into(),
        "\0\0\0\u{1}\u{7f}".into(),
        format!("\u{feff}{liu}"),
        format!("{liu}\n{liu}"),
        format!("{liu}\n[blade]\nlength = 3.0\n"),
        "[blade]\nlength = 3.0\nlength = 4.0\n".into(),
        "[blade]\nlength = \"long\"\n".into(),
        "[blade]\nlength = [1.0, 2.0]\n".into(),
        "[blade]\nlength = { value = 1.0 }\n".into(),
        "blade = 3\n".into(),
        "[structure]\nmodes = -3\n".into(),
        "[structure]\nmodes = 99999999999999999999999\n".into(),
        "[structure]\nmodes = 2.5\n".into(),
        "[aero]\nmodel = \"vortex\"\n".into(),
        "[[blade]]\nlength = 3.0\n".into(),
        "[operating]\nrotor_speed = nan\n".into(),
        "[operating]\nrotor_speed = 1979-05-27\n".into(),
        long_number,
        long_string,
        long_key,
        deep,
        deep_tables,
        many_tables,
        "\u{fffd}".repeat(10_000),
    ];
    for (k, text) in files.iter().enumerate() {
        check_file(text, "damaged.toml").unwrap_or_else(|e| panic!("file {k}: {e}"));
    }
}

/// One random change to a preset's text (one that still has a `key = value` line; otherwise
/// the text is left as it is).
#[derive(Debug, Clone)]
enum Mutation {
    /// Junk bytes (made valid UTF-8, as a file read as text would be) inserted at a position.
    Insert(usize, Vec<u8>),
    /// A range of bytes removed.
    Delete(usize, usize),
    /// A line repeated (a duplicated key or table header).
    DuplicateLine(usize),
    /// A number replaced by a hostile one.
    Number(usize, String),
    /// A line made very long.
    LongLine(usize, usize),
}

fn hostile_number() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("1e309".to_string()),
        Just("-0.0".to_string()),
        Just("\"12\"".to_string()),
        Just("true".to_string()),
        Just("[]".to_string()),
        Just("{}".to_string()),
        Just("0x7fffffffffffffff".to_string()),
        any::<f64>().prop_map(toml_float),
        any::<i64>().prop_map(|v| v.to_string()),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (
            any::<usize>(),
            proptest::collection::vec(any::<u8>(), 1..16)
        )
            .prop_map(|(at, bytes)| Mutation::Insert(at, bytes)),
        (any::<usize>(), 1usize..64).prop_map(|(at, n)| Mutation::Delete(at, n)),
        any::<usize>().prop_map(Mutation::DuplicateLine),
        (any::<usize>(), hostile_number()).prop_map(|(k, v)| Mutation::Number(k, v)),
        (any::<usize>(), 1000usize..100_000).prop_map(|(k, n)| Mutation::LongLine(k, n)),
    ]
}

/// The nearest character boundary at or below `at % (len + 1)`.
fn boundary(text: &str, at: usize) -> usize {
    let mut i = at % (text.len() + 1);
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn mutate(text: &str, m: &Mutation) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let assignments: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].contains(" = "))
        .collect();
    if assignments.is_empty() {
        return text.to_string();
    }
    match m {
        Mutation::Insert(at, bytes) => {
            let i = boundary(text, *at);
            format!(
                "{}{}{}",
                &text[..i],
                String::from_utf8_lossy(bytes),
                &text[i..]
            )
        }
        Mutation::Delete(at, n) => {
            let i = boundary(text, *at);
            let j = boundary(text, (i + n).min(text.len()));
            format!("{}{}", &text[..i], &text[j.max(i)..])
        }
        Mutation::DuplicateLine(k) => {
            let k = k % lines.len();
            let mut out: Vec<&str> = lines.clone();
            out.insert(k, lines[k]);
            out.join("\n")
        }
        Mutation::Number(k, v) => {
            // The k-th `key = value` line (mod their count) gets the hostile value.
            let target = assignments[k % assignments.len()];
            let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            let key = out[target].split(" = ").next().unwrap_or("").to_string();
            out[target] = format!("{key} = {v}");
            out.join("\n")
        }
        Mutation::LongLine(k, n) => {
            let k = k % lines.len();
            let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            out[k] = format!("{}{}", out[k], "9".repeat(*n));
            out.join("\n")
        }
    }
}

proptest! {
    #![proptest_config(config(CASES_MUTATIONS))]

    #[test]
    fn a_mutated_preset_loads_or_names_its_origin(
        which in 0..BUILTIN.len(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let (name, text) = BUILTIN[which];
        let damaged = mutations.iter().fold(text.to_string(), |t, m| mutate(&t, m));
        check_file(&damaged, &format!("{name}.toml"))?;
    }
}
