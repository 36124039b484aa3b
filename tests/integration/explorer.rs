//! The interactive explorer without a terminal: key sequences through `state::update`, the
//! worker's latest-wins and error handling with a counting test engine, and insta snapshots of
//! the real app (real engine) on a TestBackend.

use crossbeam_channel::{bounded, unbounded, Receiver, Sender};
use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use flutterscope::analysis::campbell::Campbell;
use flutterscope::analysis::cancel::Cancel;
use flutterscope::analysis::eigen::{Stability, Verdict};
use flutterscope::analysis::flutter::{Boundary, BoundaryKind, Search, SearchRange};
use flutterscope::analysis::mode::Mode;
use flutterscope::analysis::simulate::{RunStatus, TipSample};
use flutterscope::analysis::sweep::{TrackedMode, TrackedSweep};
use flutterscope::error::{Error, Result};
use flutterscope::explorer::display::{MarkerKind, ViewKind};
use flutterscope::explorer::headless::{
    self, parse_size, preset_entries, render_text, settle, settled_state,
};
use flutterscope::explorer::keys::{action_for, Action, BINDINGS};
use flutterscope::explorer::runner;
use flutterscope::explorer::state::jobs::CampbellAxis;
use flutterscope::explorer::state::params::PARAMS;
use flutterscope::explorer::state::update::update;
use flutterscope::explorer::state::{AppState, Check, Effect, Msg, Options, ViewMode};
use flutterscope::explorer::worker::Worker;
use flutterscope::explorer::{Engine, Physics, Solve, Solved, Stream};
use flutterscope::physics::section::SectionProps;
use flutterscope::preset::{AeroModel, Preset, ValidPreset, BUILTIN, DEFAULT_PRESET};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

// ---------------------------------------------------------------------------------------------
// A test engine: simple closed-form "results" that depend on the parameters, so tests can see
// which parameters were solved. It lives here only; the explorer never sees it outside tests.
// ---------------------------------------------------------------------------------------------

#[derive(Default)]
struct TestEngine {
    solves: AtomicUsize,
    /// Rotor speed of every preset solved, in order.
    solved_rpm: Mutex<Vec<f64>>,
    /// When set, the first solve waits for a message here before returning.
    gate: Mutex<Option<Receiver<()>>>,
    started: AtomicUsize,
    fail_solve: bool,
    panic_solve_at_rpm: Option<f64>,
    /// A solve at this rotor speed never ends on its own: only its cancellation flag stops it.
    endless_solve_at_rpm: Option<f64>,
    endless_started: AtomicUsize,
    boundaries: AtomicUsize,
    campbells: AtomicUsize,
}

fn mode(label: &str, re: f64, im: f64) -> Mode {
    Mode {
        label: label.into(),
        ..Mode::root(re, im)
    }
}

fn test_stability(p: &ValidPreset) -> Stability {
    let rpm = p.operating.rotor_speed;
    let flap_sigma = -0.05 + 0.01 * p.operating.wind_speed - 0.1;
    let eigenvalues = vec![
        mode(
            "flap 1",
            flap_sigma,
            2.0 * std::f64::consts::PI * (1.0 + rpm / 60.0),
        ),
        mode("torsion 1", -3.0, 2.0 * std::f64::consts::PI * 80.0),
    ];
    let stable = eigenvalues.iter().all(|m| m.re < 0.0);
    Stability {
        stable,
        verdict: if stable {
            Verdict::Stable
        } else {
            Verdict::Flutter
        },
        eigenvalues,
        aero_lags: Vec::new(),
    }
}

struct TestStream {
    t: f64,
    rate: f64,
}

impl Stream for TestStream {
    fn advance(&mut self, samples: usize) -> Result<Vec<TipSample>> {
        Ok((0..samples)
            .map(|_| {
                let s = TipSample {
                    t: self.t,
                    tip_twist: 0.01 * (3.0 * self.t).sin(),
                    tip_flap: 0.1 * (0.5 * self.t).cos(),
                };
                self.t += 1.0 / self.rate;
                s
            })
            .collect())
    }
    fn kick(&mut self, _twist_rad: f64, _flap_m: f64) {}
    fn status(&self) -> RunStatus {
        RunStatus::Ok
    }
}

impl TestEngine {
    fn solved(&self, p: &ValidPreset) -> Result<Solved> {
        self.started.fetch_add(1, Ordering::SeqCst);
        if let Some(gate) = self.gate.lock().unwrap().take() {
            gate.recv().ok();
        }
        if self.panic_solve_at_rpm == Some(p.operating.rotor_speed) {
            panic!(
                "test engine: deliberate panic at {} rpm",
                p.operating.rotor_speed
            );
        }
        self.solves.fetch_add(1, Ordering::SeqCst);
        self.solved_rpm
            .lock()
            .unwrap()
            .push(p.operating.rotor_speed);
        if self.fail_solve {
            return Err(Error::numerical(
                "test engine: eigenvalue solver did not converge",
            ));
        }
        Ok(Solved {
            setting: None,
            section: Some(SectionProps {
                m: 0.06,
                i: 2e-6,
                ka2: 3e-5,
                km1_2: 1e-6,
                km2_2: 3e-5,
                chord: 0.018,
                ea_offset: -0.0045,
                cg_offset: 0.0,
                c22: 0.9,
                c23: -0.16,
                c33: 0.46,
            }),
            stability: test_stability(p),
            shapes: Vec::new(),
        })
    }
}

impl Engine for TestEngine {
    fn solve(&self, p: &ValidPreset, cancel: &Cancel) -> Solve {
        if self.endless_solve_at_rpm == Some(p.operating.rotor_speed) {
            self.endless_started.fetch_add(1, Ordering::SeqCst);
            while !cancel.is_cancelled() {
                std::thread::sleep(Duration::from_millis(1));
            }
            return Solve {
                solved: Err(Error::Cancelled),
                stream: Err(Error::Cancelled),
            };
        }
        Solve {
            solved: self.solved(p),
            stream: Ok(Box::new(TestStream {
                t: 0.0,
                rate: p.simulation.sample_rate,
            })),
        }
    }

    fn boundary(&self, p: &ValidPreset, range: &SearchRange, cancel: &Cancel) -> Result<Search> {
        self.boundaries.fetch_add(1, Ordering::SeqCst);
        cancel.check()?;
        let (key, from, to) = (range.key.as_str(), range.from, range.to);
        // Flutter where the flap σ of `test_stability` crosses zero along the wind speed.
        let critical = if key == "operating.wind_speed" {
            Some(15.0).filter(|c| (from.min(to)..=from.max(to)).contains(c))
        } else {
            None
        };
        let _ = p;
        Ok(Search {
            boundary: Boundary {
                parameter: key.into(),
                critical,
                frequency_hz: critical.map(|_| 1.0),
                kind: critical.map(|_| BoundaryKind::Flutter),
                mode: critical.map(|_| "flap 1".into()),
                shares: None,
            },
            message: String::new(),
            max_re: 0.0,
            failed: Vec::new(),
            unstable_at_start: false,
            grid: Vec::new(),
            results: Vec::new(),
        })
    }

    fn campbell(
        &self,
        p: &ValidPreset,
        key: &str,
        grid: &[f64],
        cancel: &Cancel,
    ) -> Result<Campbell> {
        self.campbells.fetch_add(1, Ordering::SeqCst);
        cancel.check()?;
        let modes = ["flap 1", "torsion 1"]
            .iter()
            .enumerate()
            .map(|(k, label)| {
                let stab: Vec<Stability> = grid
                    .iter()
                    .map(|&r| test_stability(&p.with(key, r).unwrap()))
                    .collect();
                TrackedMode {
                    label: label.to_string(),
                    frequency_hz: stab.iter().map(|s| s.eigenvalues[k].frequency_hz).collect(),
                    damping_ratio: stab
                        .iter()
                        .map(|s| s.eigenvalues[k].damping_ratio)
                        .collect(),
                    re: stab.iter().map(|s| s.eigenvalues[k].re).collect(),
                    second_re: vec![f64::NAN; stab.len()],
                    switches: Vec::new(),
                }
            })
            .collect();
        Ok(Campbell {
            sweep: TrackedSweep {
                parameter: key.into(),
                values: grid.to_vec(),
                modes,
                failed: Vec::new(),
            },
            rotor_speed_rpm: vec![p.operating.rotor_speed; grid.len()],
        })
    }
}

fn default_preset() -> ValidPreset {
    Preset::load(DEFAULT_PRESET, &[]).expect("default preset loads")
}

fn fresh_state() -> (AppState, Vec<Effect>) {
    let p = default_preset();
    let (entries, index) = preset_entries(DEFAULT_PRESET, &p);
    let mut s = AppState::new(entries, index, p, Options::default());
    let effects = s.start();
    (s, effects)
}

fn settled(engine: &TestEngine) -> AppState {
    let (mut s, effects) = fresh_state();
    settle(&mut s, engine, effects);
    s
}

fn solve_gens(effects: &[Effect]) -> Vec<u64> {
    effects
        .iter()
        .filter_map(|e| match e {
            Effect::Solve { gen, .. } => Some(*gen),
            _ => None,
        })
        .collect()
}

fn key(code: KeyCode, mods: KeyModifiers) -> Msg {
    Msg::Action(action_for(&KeyEvent::new(code, mods)).expect("bound key"))
}

// ---------------------------------------------------------------------------------------------
// Key sequences (no terminal, no worker)
// ---------------------------------------------------------------------------------------------

#[test]
fn start_requests_one_solve_then_a_boundary_search() {
    let (mut s, effects) = fresh_state();
    assert_eq!(solve_gens(&effects), vec![1]);
    assert!(s.solving());
    let engine = TestEngine::default();
    let Effect::Solve { gen, preset } = &effects[0] else {
        panic!("first effect is a solve")
    };
    let follow = update(
        &mut s,
        Msg::Solved {
            gen: *gen,
            result: engine.solved(preset).map_err(|e| e.to_string()),
        },
    );
    assert!(!s.solving());
    assert!(
        matches!(
            follow.as_slice(),
            [Effect::Boundary { ranges, .. }] if ranges[0].key == "operating.rotor_speed"
        ),
        "{follow:?}"
    );
}

#[test]
fn arrows_adjust_the_focused_parameter_with_fine_and_coarse_steps() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    // Rotor speed is selected at start (its margin is the first question); ↑ reaches ply angle.
    assert_eq!(PARAMS[s.focus].label, "rotor speed");
    s.focus = 0;
    assert_eq!(PARAMS[s.focus].label, "ply angle");
    let ply0 = s.preset.section.paper_ply_angle();
    let e = update(&mut s, key(KeyCode::Right, KeyModifiers::NONE));
    assert_eq!(s.preset.section.ply_angle, Some(ply0 + 1.0));
    assert_eq!(solve_gens(&e), vec![s.gen]);
    let e = update(&mut s, key(KeyCode::Char('H'), KeyModifiers::SHIFT));
    // Coarse steps snap to the coarse grid: 46 → 45.
    assert_eq!(s.preset.section.ply_angle, Some(45.0));
    assert_eq!(solve_gens(&e).len(), 1);
    update(&mut s, key(KeyCode::Left, KeyModifiers::SHIFT));
    assert_eq!(s.preset.section.ply_angle, Some(40.0));
    // vi keys: j selects the next parameter, l increases it.
    update(&mut s, key(KeyCode::Char('j'), KeyModifiers::NONE));
    assert_eq!(PARAMS[s.focus].label, "wind speed");
    let w0 = s.preset.operating.wind_speed;
    update(&mut s, key(KeyCode::Char('l'), KeyModifiers::NONE));
    assert_eq!(s.preset.operating.wind_speed, w0 + 0.5);
    // The base preset is untouched (reset goes back to it).
    assert_eq!(s.opened.section.paper_ply_angle(), ply0);
}

#[test]
fn slider_limits_stop_without_a_solve() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    s.focus = 0;
    s.preset = s.preset.with("section.ply_angle", 0.0).unwrap();
    let e = update(&mut s, Msg::Action(Action::Decrease));
    assert!(e.is_empty());
    assert!(
        s.notice.as_deref().unwrap().contains("minimum"),
        "{:?}",
        s.notice
    );
    // Rotor speed stops at view.rotor_speed_max.
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    let max = s.preset.view.rotor_speed_max;
    s.preset = s.preset.with("operating.rotor_speed", max).unwrap();
    assert!(update(&mut s, Msg::Action(Action::IncreaseCoarse)).is_empty());
    assert_eq!(
        s.preset.operating.rotor_speed,
        s.preset.view.rotor_speed_max
    );
}

#[test]
fn stale_results_are_ignored() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    let gen_before = s.gen;
    let old = s.solved.clone().unwrap();
    update(&mut s, Msg::Action(Action::Increase));
    update(&mut s, Msg::Action(Action::Increase));
    assert_eq!(s.gen, gen_before + 2);
    // A result for the intermediate generation arrives late: dropped, still solving.
    let e = update(
        &mut s,
        Msg::Solved {
            gen: gen_before + 1,
            result: Ok(old.clone()),
        },
    );
    assert!(e.is_empty());
    assert!(s.solving());
    s.dirty = false;
    update(
        &mut s,
        Msg::Samples {
            gen: gen_before + 1,
            samples: vec![TipSample {
                t: 0.0,
                tip_twist: 1.0,
                tip_flap: 1.0,
            }],
            status: RunStatus::Diverging,
        },
    );
    assert!(!s.response.diverging);
    assert!(!s.dirty, "a stale message must not cause a redraw");
    update(
        &mut s,
        Msg::Solved {
            gen: gen_before + 2,
            result: Ok(old),
        },
    );
    assert!(!s.solving());
}

#[test]
fn aero_key_cycles_models_and_reset_restores_the_preset() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    let m0 = s.preset.aero.model;
    let e = update(&mut s, key(KeyCode::Char('a'), KeyModifiers::NONE));
    assert_eq!(s.preset.aero.model, m0.cycle(true));
    assert_eq!(solve_gens(&e).len(), 1);
    // The uniform blade takes every model but those that need polars.
    assert!(!s.preset.blade.source.is_tabulated());
    let taken = AeroModel::ALL.iter().filter(|m| !m.needs_polars()).count();
    assert!(taken < AeroModel::ALL.len());
    for _ in 0..taken - 1 {
        assert!(!s.preset.aero.model.needs_polars());
        update(&mut s, Msg::Action(Action::CycleAero));
    }
    assert_eq!(s.preset.aero.model, m0);
    update(&mut s, Msg::Action(Action::IncreaseCoarse));
    assert_ne!(s.preset, s.opened);
    let e = update(&mut s, key(KeyCode::Char('r'), KeyModifiers::NONE));
    assert_eq!(s.preset, s.opened);
    assert_eq!(solve_gens(&e), vec![s.gen]);
}

#[test]
fn pause_kick_help_campbell_marker_and_quit() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    let e = update(&mut s, key(KeyCode::Char(' '), KeyModifiers::NONE));
    assert!(s.paused);
    assert!(matches!(e.as_slice(), [Effect::Pause(true)]));
    // A kick resumes streaming and kicks the current simulation.
    let e = update(&mut s, key(KeyCode::Char('k'), KeyModifiers::NONE));
    assert!(!s.paused);
    let gen = s.gen;
    let (tw, fl) = s.kick_amounts();
    assert!(tw > 0.0 && fl > 0.0);
    assert!(
        matches!(e.as_slice(), [Effect::Pause(false), Effect::Kick { gen: g, .. }] if *g == gen),
        "{e:?}"
    );
    update(&mut s, key(KeyCode::Char('?'), KeyModifiers::SHIFT));
    assert!(s.help);
    update(&mut s, key(KeyCode::Esc, KeyModifiers::NONE));
    assert!(!s.help);
    let e = update(&mut s, key(KeyCode::Char('c'), KeyModifiers::NONE));
    assert_eq!(s.view, ViewMode::Campbell);
    assert!(matches!(e.as_slice(), [Effect::Campbell { .. }]), "{e:?}");
    update(&mut s, key(KeyCode::Esc, KeyModifiers::NONE));
    assert_eq!(s.view, ViewMode::Main);
    update(&mut s, key(KeyCode::Char('m'), KeyModifiers::NONE));
    assert_eq!(s.opts.marker, MarkerKind::Halfblock);
    let e = update(&mut s, key(KeyCode::Char('c'), KeyModifiers::CONTROL));
    assert!(s.quit);
    assert!(matches!(e.as_slice(), [Effect::Quit]));
}

#[test]
fn campbell_is_recomputed_for_new_parameters_but_not_for_rotor_speed() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    headless::press(&mut s, &engine, &[Action::ToggleCampbell]);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 1);
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    headless::press(&mut s, &engine, &[Action::Increase, Action::Increase]);
    assert_eq!(
        engine.campbells.load(Ordering::SeqCst),
        1,
        "rotor speed is the axis"
    );
    s.focus = PARAMS.iter().position(|p| p.label == "wind speed").unwrap();
    headless::press(&mut s, &engine, &[Action::Increase]);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 2);
    // Back in the main view, changes do not sweep.
    headless::press(&mut s, &engine, &[Action::Back, Action::Increase]);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 2);
}

#[test]
fn boundary_follows_the_selected_parameter() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    assert_eq!(s.boundary_key, "operating.rotor_speed");
    // Select wind speed: a new search along it.
    s.focus = 0;
    let e = update(&mut s, Msg::Action(Action::FocusNext));
    let Some(Effect::Boundary { ranges, .. }) = e.first() else {
        panic!("{e:?}")
    };
    // Both ways from the current 20 m/s, to the slider's ends (0 and view.wind_speed_max), each
    // on its share of the points; from the unstable point each looks for stability regained.
    let ends: Vec<(&str, f64, f64, usize, bool)> = ranges
        .iter()
        .map(|r| (r.key.as_str(), r.from, r.to, r.points, r.regain))
        .collect();
    assert_eq!(
        ends,
        [
            ("operating.wind_speed", 20.0, 0.0, 21, true),
            ("operating.wind_speed", 20.0, 40.0, 21, true)
        ]
    );
    settle(&mut s, &engine, e);
    let text = flutterscope::explorer::ui::status::margin_text(&s).unwrap();
    // The test engine's flap mode is unstable at the preset's 20 m/s: the stretch it lies in
    // begins at 15 m/s (and the search above finds no end before 40 m/s).
    assert_eq!(text, "wind speed: unstable from 15.0 m/s, -25 %");
    // The aero-model row keeps the last numeric key.
    let n = engine.boundaries.load(Ordering::SeqCst);
    headless::press(
        &mut s,
        &engine,
        &[
            Action::FocusNext,
            Action::FocusNext,
            Action::FocusNext,
            Action::FocusNext,
        ],
    );
    assert_eq!(PARAMS[s.focus].label, "aero model");
    assert_eq!(s.boundary_key, "operating.pitch");
    headless::press(&mut s, &engine, &[Action::FocusNext]);
    assert_eq!(s.boundary_key, "operating.pitch");
    // Tunnel speed, rotor speed and pitch are searched on the way: both sides of rotor speed
    // and pitch, only above the tunnel speed's 0 m/s (nothing below it to search).
    assert_eq!(engine.boundaries.load(Ordering::SeqCst), n + 5);
    // f recomputes.
    headless::press(&mut s, &engine, &[Action::Boundary]);
    assert_eq!(engine.boundaries.load(Ordering::SeqCst), n + 7);
}

#[test]
fn margin_reads_like_a_sentence() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    s.focus = PARAMS.iter().position(|p| p.label == "wind speed").unwrap();
    s.boundary_key = "operating.wind_speed";
    // The test engine's flap σ < 0 below 15 m/s.
    s.preset = s.preset.with("operating.wind_speed", 10.0).unwrap();
    let e = update(&mut s, Msg::Action(Action::Decrease));
    settle(&mut s, &engine, e);
    assert_eq!(s.preset.operating.wind_speed, 9.5);
    let text = flutterscope::explorer::ui::status::margin_text(&s).unwrap();
    assert_eq!(
        text,
        "wind speed: flutter at 15.0 m/s (+58 %, flap 1), none below"
    );
}

#[test]
fn engine_errors_show_in_the_status_and_the_explorer_keeps_going() {
    let engine = TestEngine {
        fail_solve: true,
        ..TestEngine::default()
    };
    let mut s = settled(&engine);
    assert!(s.solved.is_none());
    assert!(s
        .solve_error
        .as_deref()
        .unwrap()
        .contains("did not converge"));
    let text = render_text(&s, 100, 30);
    assert!(text.contains("ERROR"), "{text}");
    assert!(text.contains("did not converge"), "{text}");
    // Keys still work.
    headless::press(&mut s, &engine, &[Action::Increase]);
    assert_eq!(engine.solves.load(Ordering::SeqCst), 2);
}

#[test]
fn preset_keys_cycle_through_the_builtins() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    assert_eq!(s.presets.len(), BUILTIN.len());
    headless::press(&mut s, &engine, &[Action::NextPreset]);
    if BUILTIN.len() > 1 {
        assert_eq!(s.preset_index, 1 % BUILTIN.len());
        assert_eq!(s.preset, s.opened);
        assert_eq!(s.presets[s.preset_index].preset.as_ref(), Some(&s.opened));
        headless::press(&mut s, &engine, &[Action::PrevPreset]);
        assert_eq!(s.preset_index, 0);
    } else {
        assert!(s.notice.is_some());
    }
}

#[test]
fn trails_and_trends_start_afresh_on_a_new_preset() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    headless::press(&mut s, &engine, &[Action::Increase, Action::Increase]);
    assert_eq!(s.trails.len(), 2);
    assert!(!s.prev_modes.is_empty());
    // Reset (or another preset): no trails or trend arrows across the jump.
    headless::press(&mut s, &engine, &[Action::Reset]);
    assert!(s.trails.is_empty());
    assert!(s.prev_modes.is_empty());
    headless::press(&mut s, &engine, &[Action::Increase]);
    assert_eq!(s.trails.len(), 1);
}

#[test]
fn a_preset_file_joins_the_cycle_in_front() {
    let p = default_preset()
        .edited(|p| p.meta.name = "my blade".into())
        .unwrap();
    let (entries, index) = preset_entries("blades/mine.toml", &p);
    assert_eq!(index, 0);
    assert_eq!(entries[0].name, "my blade");
    assert_eq!(entries.len(), BUILTIN.len() + 1);
}

#[test]
fn help_lists_every_binding() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    headless::press(&mut s, &engine, &[Action::ToggleHelp]);
    let text = render_text(&s, 120, 40);
    for b in BINDINGS {
        let help = b.help_text();
        assert!(text.contains(&help), "help misses '{help}'\n{text}");
    }
}

#[test]
fn tiny_windows_say_so_and_never_panic() {
    let engine = TestEngine::default();
    let s = settled(&engine);
    let text = render_text(&s, 79, 24);
    assert!(text.contains("window too small"), "{text}");
    for (w, h) in [(1, 1), (10, 3), (80, 23), (200, 5)] {
        render_text(&s, w, h);
    }
    let text = render_text(&s, 80, 24);
    assert!(!text.contains("window too small"));
}

#[test]
fn size_argument_is_checked() {
    assert_eq!(parse_size("120x40").unwrap(), (120, 40));
    assert_eq!(parse_size("80X24").unwrap(), (80, 24));
    for bad in [
        "10x5", "abc", "120", "120x", "x40", "-1x30", "2000x40", "79x24",
    ] {
        let e = parse_size(bad).unwrap_err().to_string();
        assert!(e.contains("COLSxROWS"), "{bad}: {e}");
    }
    // Digits too many for any integer are a size too large, not "not a whole number".
    for huge in ["99999x99999", "120x99999999999999999999999"] {
        let e = parse_size(huge).unwrap_err().to_string();
        assert!(
            e.contains("too large") && !e.contains("not a whole number"),
            "{huge}: {e}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The worker
// ---------------------------------------------------------------------------------------------

fn solve_effect(gen: u64, rpm: f64) -> Effect {
    let p = default_preset().with("operating.rotor_speed", rpm).unwrap();
    Effect::Solve {
        gen,
        preset: Arc::new(p),
    }
}

/// Receive until `done` says stop, or fail after a generous timeout.
fn collect_until(rx: &Receiver<Msg>, mut done: impl FnMut(&Msg) -> bool) -> Vec<Msg> {
    let deadline = Instant::now() + Duration::from_secs(10);
    let mut out = Vec::new();
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let m = rx.recv_timeout(left).expect("worker answered in time");
        let stop = done(&m);
        out.push(m);
        if stop {
            return out;
        }
    }
}

fn wait_for(cond: impl Fn() -> bool) {
    let deadline = Instant::now() + Duration::from_secs(10);
    while !cond() {
        assert!(Instant::now() < deadline, "condition not reached in time");
        std::thread::sleep(Duration::from_millis(1));
    }
}

#[test]
fn worker_solves_only_the_latest_of_a_flood() {
    let (gate_tx, gate_rx): (Sender<()>, Receiver<()>) = bounded(0);
    let engine = Arc::new(TestEngine {
        gate: Mutex::new(Some(gate_rx)),
        ..TestEngine::default()
    });
    let (tx, rx) = unbounded();
    let mut worker = Worker::spawn(engine.clone(), tx, Duration::from_millis(20));
    worker.send(solve_effect(1, 1.0));
    // The first solve is now blocked inside the engine; flood while it is busy.
    wait_for(|| engine.started.load(Ordering::SeqCst) == 1);
    for g in 2..=200u64 {
        worker.send(solve_effect(g, g as f64));
    }
    gate_tx.send(()).unwrap();
    let msgs = collect_until(&rx, |m| matches!(m, Msg::Solved { gen: 200, .. }));
    let solved: Vec<u64> = msgs
        .iter()
        .filter_map(|m| match m {
            Msg::Solved { gen, .. } => Some(*gen),
            _ => None,
        })
        .collect();
    // The first solve was replaced while it ran: its result is dropped, not shown (this engine
    // ignores the cancellation flag, so it finished; the real one stops at its next check).
    assert_eq!(solved, vec![200]);
    assert_eq!(engine.solves.load(Ordering::SeqCst), 2);
    assert_eq!(*engine.solved_rpm.lock().unwrap(), vec![1.0, 200.0]);
    worker.send(Effect::Quit);
}

#[test]
fn worker_streams_samples_and_stops_when_paused() {
    let engine = Arc::new(TestEngine::default());
    let (tx, rx) = unbounded();
    let mut worker = Worker::spawn(engine, tx, Duration::from_millis(10));
    worker.send(solve_effect(1, 60.0));
    let mut samples = 0;
    collect_until(&rx, |m| {
        if let Msg::Samples {
            gen: 1, samples: s, ..
        } = m
        {
            samples += s.len();
        }
        samples >= 4
    });
    worker.send(Effect::Pause(true));
    // Let batches already on their way arrive, then nothing more may come.
    std::thread::sleep(Duration::from_millis(60));
    while rx.try_recv().is_ok() {}
    assert!(
        rx.recv_timeout(Duration::from_millis(150)).is_err(),
        "paused worker kept sending"
    );
    worker.send(Effect::Pause(false));
    collect_until(&rx, |m| matches!(m, Msg::Samples { gen: 1, .. }));
    worker.send(Effect::Quit);
}

/// A solve that would never end is abandoned as soon as a newer request arrives: the worker
/// answers the newest position and never reports the old one.
#[test]
fn worker_abandons_a_solve_in_flight_for_a_newer_one() {
    let engine = Arc::new(TestEngine {
        endless_solve_at_rpm: Some(13.0),
        ..TestEngine::default()
    });
    let (tx, rx) = unbounded();
    let mut worker = Worker::spawn(engine.clone(), tx, Duration::from_millis(20));
    worker.send(solve_effect(1, 13.0));
    // The endless solve is running when the newer request replaces it.
    wait_for(|| engine.endless_started.load(Ordering::SeqCst) == 1);
    worker.send(solve_effect(2, 20.0));
    let msgs = collect_until(&rx, |m| matches!(m, Msg::Solved { gen: 2, .. }));
    assert!(matches!(
        msgs.last(),
        Some(Msg::Solved { result: Ok(_), .. })
    ));
    assert!(
        !msgs.iter().any(|m| matches!(m, Msg::Solved { gen: 1, .. })),
        "the abandoned solve reported a result"
    );
    worker.send(Effect::Quit);
}

#[test]
fn worker_survives_an_engine_panic() {
    let engine = Arc::new(TestEngine {
        panic_solve_at_rpm: Some(13.0),
        ..TestEngine::default()
    });
    let (tx, rx) = unbounded();
    let mut worker = Worker::spawn(engine.clone(), tx, Duration::from_millis(20));
    worker.send(solve_effect(1, 13.0));
    let msgs = collect_until(&rx, |m| matches!(m, Msg::Solved { gen: 1, .. }));
    let Some(Msg::Solved { result: Err(e), .. }) = msgs.last() else {
        panic!("expected an error result")
    };
    assert!(
        e.contains("panicked") && e.contains("deliberate panic"),
        "{e}"
    );
    // The same worker keeps serving.
    worker.send(solve_effect(2, 20.0));
    let msgs = collect_until(&rx, |m| matches!(m, Msg::Solved { gen: 2, .. }));
    assert!(matches!(
        msgs.last(),
        Some(Msg::Solved { result: Ok(_), .. })
    ));
    // And the state shows the panic in the status line.
    let (mut s, _) = fresh_state();
    update(
        &mut s,
        Msg::Solved {
            gen: 1,
            result: Err(e.clone()),
        },
    );
    let text = render_text(&s, 120, 40);
    assert!(text.contains("deliberate panic"), "{text}");
    worker.send(Effect::Quit);
}

#[test]
fn worker_jobs_run_the_latest_request() {
    let engine = Arc::new(TestEngine::default());
    let (tx, rx) = unbounded();
    let mut worker = Worker::spawn(engine.clone(), tx, Duration::from_millis(20));
    let p = Arc::new(default_preset());
    for g in 1..=50u64 {
        worker.send(Effect::Boundary {
            gen: g,
            key: "operating.wind_speed",
            preset: p.clone(),
            ranges: vec![SearchRange {
                key: "operating.wind_speed".into(),
                from: 0.0,
                to: 40.0,
                points: 41,
                regain: false,
            }],
        });
    }
    let msgs = collect_until(&rx, |m| matches!(m, Msg::Boundary { gen: 50, .. }));
    // At most the first one (if it started before the flood) and the last one ran.
    let gens: Vec<u64> = msgs
        .iter()
        .filter_map(|m| match m {
            Msg::Boundary { gen, .. } => Some(*gen),
            _ => None,
        })
        .collect();
    assert!(gens == [50] || gens == [1, 50], "{gens:?}");
    assert_eq!(engine.boundaries.load(Ordering::SeqCst), gens.len());
    worker.send(Effect::Quit);
}

// ---------------------------------------------------------------------------------------------
// Snapshots of the real app (real engine), deterministic: headless, fixed simulation length.
// ---------------------------------------------------------------------------------------------

fn snapshot_of(name: &str, view: ViewKind, cols: u16, rows: u16) -> String {
    let p = Preset::load(name, &[]).expect("preset loads");
    let s = settled_state(name, p, &Physics, view, MarkerKind::Braille);
    render_text(&s, cols, rows)
}

/// The stall preset has no equilibrium at 0 rpm: its Campbell diagram used to be empty without
/// a word (tracking started from that point). Now it draws every speed that solves and its title
/// says which failed.
#[test]
fn campbell_view_draws_past_a_failed_speed_and_says_so() {
    let text = snapshot_of("liu2017-stall", ViewKind::Campbell, 120, 40);
    assert!(
        text.contains("Campbell · 1/41 speeds not solved, first 0 rpm"),
        "{text}"
    );
    assert!(
        text.contains("flap 1") && text.contains("28.6 Hz"),
        "{text}"
    );
}

#[test]
fn snapshot_every_builtin_preset() {
    for (name, _) in BUILTIN {
        let text = snapshot_of(name, ViewKind::Main, 120, 40);
        assert!(!text.contains("ERROR"), "{name}:\n{text}");
        insta::assert_snapshot!(format!("main_{name}"), text);
    }
}

#[test]
fn snapshot_help_overlay() {
    insta::assert_snapshot!("help", snapshot_of(DEFAULT_PRESET, ViewKind::Help, 120, 40));
}

#[test]
fn snapshot_campbell_view() {
    insta::assert_snapshot!(
        "campbell",
        snapshot_of(DEFAULT_PRESET, ViewKind::Campbell, 120, 40)
    );
}

#[test]
fn snapshot_small_window() {
    insta::assert_snapshot!(
        "small_80x24",
        snapshot_of(DEFAULT_PRESET, ViewKind::Main, 80, 24)
    );
}

#[test]
fn snapshot_large_window() {
    insta::assert_snapshot!(
        "large_160x48",
        snapshot_of(DEFAULT_PRESET, ViewKind::Main, 160, 48)
    );
}

/// The real engine, except that solving fails: what a user sees when the solver gives up.
struct FailingSolve;

impl Engine for FailingSolve {
    fn solve(&self, p: &ValidPreset, _cancel: &Cancel) -> Solve {
        Solve {
            solved: Err(Error::numerical(
                "eigenvalues of the state matrix did not converge (test)",
            )),
            ..Physics.solve(p, &Cancel::never())
        }
    }
    fn boundary(&self, p: &ValidPreset, range: &SearchRange, cancel: &Cancel) -> Result<Search> {
        Physics.boundary(p, range, cancel)
    }
    fn campbell(
        &self,
        p: &ValidPreset,
        key: &str,
        grid: &[f64],
        cancel: &Cancel,
    ) -> Result<Campbell> {
        Physics.campbell(p, key, grid, cancel)
    }
}

#[test]
fn snapshot_error_state() {
    let p = default_preset();
    let s = settled_state(
        DEFAULT_PRESET,
        p,
        &FailingSolve,
        ViewKind::Main,
        MarkerKind::Braille,
    );
    let text = render_text(&s, 120, 40);
    assert!(text.contains("did not converge"), "{text}");
    insta::assert_snapshot!("error_state", text);
}

#[test]
fn snapshots_are_deterministic() {
    let a = snapshot_of(DEFAULT_PRESET, ViewKind::Main, 120, 40);
    let b = snapshot_of(DEFAULT_PRESET, ViewKind::Main, 120, 40);
    assert_eq!(a, b);
}

#[test]
fn every_marker_renders() {
    let p = default_preset();
    for m in [
        MarkerKind::Braille,
        MarkerKind::Halfblock,
        MarkerKind::Block,
        MarkerKind::Dot,
    ] {
        let s = settled_state(
            DEFAULT_PRESET,
            p.clone(),
            &TestEngine::default(),
            ViewKind::Main,
            m,
        );
        let text = render_text(&s, 120, 40);
        assert!(text.contains("Root locus"), "{m:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// The binary
// ---------------------------------------------------------------------------------------------

#[test]
fn tui_without_a_terminal_points_to_the_headless_commands() {
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .arg("tui")
        .write_stdin("")
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("needs a terminal") && err.contains("snapshot"),
        "{err}"
    );
}

#[test]
fn snapshot_command_checks_its_size() {
    for bad in ["10x5", "abc"] {
        let out = assert_cmd::Command::cargo_bin("flutterscope")
            .unwrap()
            .args(["snapshot", "--size", bad])
            .output()
            .unwrap();
        assert!(!out.status.success(), "{bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--size") && err.contains("COLSxROWS"), "{err}");
    }
}

#[test]
fn snapshot_command_prints_a_frame() {
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .args(["snapshot", "--preset", DEFAULT_PRESET, "--size", "100x30"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 30);
    assert!(text
        .lines()
        .all(|l| l.chars().count() <= 100 && !l.ends_with(' ')));
    assert!(text.contains("Root locus") && text.contains("Tip response"));
}

#[test]
fn each_preset_opens_on_the_parameter_it_selects() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    // liu2017 selects nothing: rotor speed by default.
    assert_eq!(PARAMS[s.focus].label, "rotor speed");
    assert_eq!(s.boundary_key, "operating.rotor_speed");
    s.focus = 0;
    // Cycle to goland (view.select = "tunnel-speed"): tunnel speed is selected and searched.
    let goland = s.presets.iter().position(|e| e.name == "goland").unwrap();
    while s.preset_index != goland {
        let e = update(&mut s, Msg::Action(Action::NextPreset));
        settle(&mut s, &engine, e);
    }
    assert_eq!(PARAMS[s.focus].label, "tunnel speed");
    assert_eq!(s.boundary_key, "operating.tunnel_speed");
    assert_eq!(
        s.boundary.as_ref().map(|b| b.key),
        Some("operating.tunnel_speed")
    );
}

/// A solve over its time budget is reported with its running time in the status line; the last
/// result stays on screen and keys keep working. Time for stale or fast solves changes nothing.
#[test]
fn a_slow_solve_shows_its_running_time() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    let e = update(&mut s, Msg::Action(Action::Increase));
    assert!(s.solving());
    let gen = s.gen;
    // Fast so far, or from an older generation: nothing to redraw.
    s.dirty = false;
    update(&mut s, Msg::SolveTime { gen, seconds: 0.1 });
    update(
        &mut s,
        Msg::SolveTime {
            gen: gen - 1,
            seconds: 9.0,
        },
    );
    assert!(!s.dirty);
    update(&mut s, Msg::SolveTime { gen, seconds: 2.26 });
    assert!(s.dirty);
    let text = render_text(&s, 160, 48);
    assert!(text.contains("solving… 2.3 s"), "{text}");
    // The previous result is still drawn, and a key still moves the parameters on.
    assert!(text.contains("flap 1"), "{text}");
    let next = update(&mut s, Msg::Action(Action::Increase));
    assert_eq!(solve_gens(&next), vec![gen + 1]);
    settle(&mut s, &engine, [e, next].concat());
    let text = render_text(&s, 160, 48);
    assert!(!text.contains("solving…"), "{text}");
}

/// The parameters pane offers only the knobs that can change something for the preset's blade
/// and dims those waiting for another setting: on a tabulated blade without aerodynamics the
/// bend–twist coupling is offered, the ply angle and the loss factor are not, wind and tunnel
/// speed are dimmed; on the paper's blade (table section, quasi-steady aerodynamics) the ply
/// angle is offered and nothing dimmed; the Goland wing's direct stiffnesses have no ply angle.
#[test]
fn the_parameters_pane_offers_what_applies_and_dims_what_waits() {
    use ratatui::backend::TestBackend;
    use ratatui::style::Modifier;
    use ratatui::Terminal;
    // (shown, dimmed) labels of the parameters pane.
    let rows = |name: &str| -> (Vec<String>, Vec<String>) {
        let p = Preset::load(name, &[]).unwrap();
        let s = settled_state(name, p, &Physics, ViewKind::Main, MarkerKind::Braille);
        let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
        let frame = terminal
            .draw(|f| flutterscope::explorer::ui::render(&s, f))
            .unwrap();
        let buf = frame.buffer;
        let mut shown = Vec::new();
        let mut dimmed = Vec::new();
        for param in PARAMS {
            let found = (0..buf.area.height).find_map(|y| {
                let row: String = (0..36).map(|x| buf[(x, y)].symbol()).collect();
                let x = row.find(param.label)?;
                let cell = &buf[(row[..x].chars().count() as u16, y)];
                Some(cell.modifier.contains(Modifier::DIM))
            });
            if let Some(dim) = found {
                shown.push(param.label.to_string());
                if dim {
                    dimmed.push(param.label.to_string());
                }
            }
        }
        (shown, dimmed)
    };
    // A real blade in the wind: no tunnel (its inflow is the BEM's), nothing waiting.
    let (shown, dimmed) = rows("nrel5mw");
    assert_eq!(
        shown,
        [
            "bend–twist α",
            "wind speed",
            "rotor speed",
            "pitch",
            "aero model",
            "modes N"
        ]
    );
    assert!(dimmed.is_empty(), "{dimmed:?}");
    let (shown, dimmed) = rows("liu2017");
    assert!(shown.contains(&"ply angle".to_string()), "{shown:?}");
    assert!(shown.contains(&"loss factor".to_string()), "{shown:?}");
    assert!(!shown.contains(&"bend–twist α".to_string()), "{shown:?}");
    assert!(dimmed.is_empty(), "{dimmed:?}");
    let (shown, _) = rows("goland");
    assert!(!shown.contains(&"ply angle".to_string()), "{shown:?}");
}

/// ↑/↓ walk the offered rows only; on a tabulated blade the coupling knob is one of them and
/// drags like the others: fine and coarse steps, a re-solve each, the margin searched along it,
/// and its ends stop without a solve.
#[test]
fn the_coupling_knob_is_selected_and_dragged_on_a_real_blade() {
    let engine = TestEngine::default();
    let p = Preset::load("nrel5mw", &[]).unwrap();
    let (entries, index) = preset_entries("nrel5mw", &p);
    let mut s = AppState::new(entries, index, p, Options::default());
    let e = s.start();
    settle(&mut s, &engine, e);
    assert_eq!(PARAMS[s.focus].label, "rotor speed");
    // Up past wind speed to the top row: the coupling (neither the ply angle nor the tunnel
    // speed is offered on a real blade).
    for _ in 0..2 {
        update(&mut s, Msg::Action(Action::FocusPrev));
    }
    assert_eq!(PARAMS[s.focus].label, "bend–twist α");
    // One more wraps to the last offered row, modes N (no loss factor on a tabulated blade).
    update(&mut s, Msg::Action(Action::FocusPrev));
    assert_eq!(PARAMS[s.focus].label, "modes N");
    update(&mut s, Msg::Action(Action::FocusNext));
    assert_eq!(s.boundary_key, "blade.bend_twist_coupling");
    let e = update(&mut s, Msg::Action(Action::Increase));
    assert_eq!(solve_gens(&e), vec![s.gen]);
    settle(&mut s, &engine, e);
    assert_eq!(s.preset.blade.bend_twist_coupling, 0.01);
    // Coarse steps snap to their grid: 0.01 → 0 → −0.05.
    let e = update(&mut s, Msg::Action(Action::DecreaseCoarse));
    settle(&mut s, &engine, e);
    assert_eq!(s.preset.blade.bend_twist_coupling, 0.0);
    let e = update(&mut s, Msg::Action(Action::DecreaseCoarse));
    settle(&mut s, &engine, e);
    assert_eq!(s.preset.blade.bend_twist_coupling, -0.05);
    for _ in 0..10 {
        let e = update(&mut s, Msg::Action(Action::DecreaseCoarse));
        settle(&mut s, &engine, e);
    }
    assert_eq!(s.preset.blade.bend_twist_coupling, -0.3);
    let e = update(&mut s, Msg::Action(Action::Decrease));
    assert!(solve_gens(&e).is_empty());
    assert!(s.notice.as_deref().unwrap_or("").contains("minimum"));
    assert!(render_text(&s, 120, 40).contains("-0.30"));
}

/// A preset can open on the coupling (`view.select = "bend-twist-coupling"`); on the uniform
/// blade, which does not offer it, the explorer falls back to the first offered row and searches
/// rotor speed.
#[test]
fn view_select_can_open_on_the_coupling() {
    let open = |name: &str| {
        let p = Preset::load(name, &["view.select=bend-twist-coupling".into()]).unwrap();
        let (entries, index) = preset_entries(name, &p);
        let s = AppState::new(entries, index, p, Options::default());
        (PARAMS[s.focus].label, s.boundary_key)
    };
    assert_eq!(
        open("iea15mw-btc-st2019"),
        ("bend–twist α", "blade.bend_twist_coupling")
    );
    assert_eq!(open("liu2017"), ("ply angle", "section.ply_angle"));
}

/// The mode-shape pane follows the least-damped mode until a mode is picked; `.` and `,` step
/// through the modes by frequency (opening the pane), the pick survives a parameter change, and
/// `s` (re)opens the pane on the least-damped mode.
#[test]
fn the_shape_pane_starts_on_the_least_damped_mode_and_steps_by_frequency() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    // The test engine's flap 1 has σ = −0.05 + 0.01·20 − 0.1 = 0.05 > 0: the least damped.
    update(&mut s, Msg::Action(Action::ToggleShape));
    assert_eq!(s.view, ViewMode::Shape);
    let label = |s: &AppState| {
        s.shape_index().map(|i| {
            s.solved.as_ref().unwrap().stability.eigenvalues[i]
                .label
                .clone()
        })
    };
    assert_eq!(label(&s).as_deref(), Some("flap 1"));
    update(&mut s, Msg::Action(Action::NextMode));
    assert_eq!(label(&s).as_deref(), Some("torsion 1"));
    update(&mut s, Msg::Action(Action::NextMode));
    assert_eq!(label(&s).as_deref(), Some("flap 1"));
    update(&mut s, Msg::Action(Action::PrevMode));
    assert_eq!(label(&s).as_deref(), Some("torsion 1"));
    let e = update(&mut s, Msg::Action(Action::Increase));
    settle(&mut s, &engine, e);
    assert_eq!(label(&s).as_deref(), Some("torsion 1"));
    // The test engine has no shapes: the pane says so instead of drawing.
    assert!(render_text(&s, 120, 40).contains("no mode shapes from this solve"));
    update(&mut s, Msg::Action(Action::ToggleShape));
    assert_eq!(s.view, ViewMode::Main);
    update(&mut s, Msg::Action(Action::ToggleShape));
    assert_eq!(label(&s).as_deref(), Some("flap 1"));
    update(&mut s, Msg::Action(Action::Back));
    assert_eq!(s.view, ViewMode::Main);
    // Stepping from the main view opens the pane.
    update(&mut s, Msg::Action(Action::NextMode));
    assert_eq!(s.view, ViewMode::Shape);
}

/// The pane draws the real engine's shapes: the mode's name, frequency and damping ratio, the
/// legend of the components the blade has (no edge on the paper's flap–torsion blade), the span.
#[test]
fn the_shape_pane_draws_the_solved_shape() {
    let text = snapshot_of("liu2017", ViewKind::Shape, 120, 40);
    assert!(text.contains("Mode shape · flap 1"), "{text}");
    assert!(
        text.contains("1.044 Hz  ζ = 0.132") && text.contains("least damped"),
        "{text}"
    );
    assert!(
        text.contains("F flap 1.0 m") && text.contains("T twist"),
        "{text}"
    );
    assert!(!text.contains("E edge"), "{text}");
    assert!(text.contains("tip 8.45 m"), "{text}");
    // In the wind the flap modes are heavily damped: the least damped is edge 1.
    let text = snapshot_of("nrel5mw", ViewKind::Shape, 120, 40);
    assert!(
        text.contains("Mode shape · edge 1") && text.contains("E edge"),
        "{text}"
    );
}

#[test]
fn snapshot_the_shape_pane_of_every_builtin_preset() {
    for (name, _) in BUILTIN {
        for (cols, rows) in [(80, 24), (160, 48)] {
            let text = snapshot_of(name, ViewKind::Shape, cols, rows);
            assert!(text.contains("Mode shape · "), "{name}:\n{text}");
            insta::assert_snapshot!(format!("shape_{name}_{cols}x{rows}"), text);
        }
    }
}

/// On a turbine the pane draws one part of a mode at a time: a tower mode on the tower (its
/// fore–aft, side–side and torsion along the height), `p` stepping through blade 1, 2 and 3
/// (each relative to the tower's motion) and back. On one blade `p` says why it has no parts.
#[test]
fn the_shape_pane_steps_through_a_turbines_blades_and_tower() {
    let p = Preset::load(
        "nrel5mw",
        &["turbine.model=turbine".into(), "aero.model=none".into()],
    )
    .unwrap();
    let mut s = settled_state("nrel5mw", p, &Physics, ViewKind::Shape, MarkerKind::Braille);
    s.shape_pick = Some("tower FA 1".into());
    let text = render_text(&s, 120, 40);
    for expected in [
        "Mode shape · tower FA 1 · tower",
        "A fore–aft 1.0 m",
        "base 0 m · height (m) · top 87.6 m",
        "p: next part",
    ] {
        assert!(text.contains(expected), "{expected}:\n{text}");
    }
    insta::assert_snapshot!("shape_nrel5mw_turbine_tower_120x40", text);
    for part in ["blade 1", "blade 2", "blade 3", "tower"] {
        headless::press(&mut s, &Physics, &[Action::CyclePart]);
        let text = render_text(&s, 120, 40);
        assert!(
            text.contains(&format!("Mode shape · tower FA 1 · {part}")),
            "{part}:\n{text}"
        );
        assert_eq!(
            text.contains("per m of tower's fore–aft"),
            part != "tower",
            "{part}:\n{text}"
        );
    }
    let mut one = settled_state(
        "nrel5mw",
        Preset::load("nrel5mw", &[]).unwrap(),
        &Physics,
        ViewKind::Shape,
        MarkerKind::Braille,
    );
    headless::press(&mut one, &Physics, &[Action::CyclePart]);
    assert!(
        one.notice
            .as_deref()
            .is_some_and(|n| n.contains("turbine.model")),
        "{:?}",
        one.notice
    );
}

/// Without aerodynamics a tabulated blade's roots are its damped natural modes, so the shape the
/// solve gives the pane must be the one `modes --shapes` prints (scaled the same way: the
/// dominant component +1 at its peak), through an independent path (the command's JSON).
#[test]
fn the_solved_shape_of_a_structural_root_is_the_natural_mode_shape() {
    let p = Preset::load("nrel5mw", &["aero.model=none".to_string()]).unwrap();
    let solution = flutterscope::analysis::solve::solve(&p).unwrap();
    let stability = solution.stability().unwrap();
    let shapes = solution.mode_shapes(&stability);
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .args(["modes", "--preset", "nrel5mw", "--shapes", "--json"])
        .output()
        .unwrap();
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for label in ["flap 1", "edge 1", "flap 2"] {
        let i = stability
            .eigenvalues
            .iter()
            .position(|m| m.label == label)
            .unwrap();
        // One blade: one part, the blade.
        assert_eq!(shapes[i].parts.len(), 1, "{label}");
        let shape = &shapes[i].parts[0];
        let printed = json["modes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|m| m["label"] == label)
            .unwrap();
        let along = |c: &str| -> Vec<f64> {
            printed["shape"][c]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        };
        let z = along("z");
        assert_eq!(z.len(), shape.span.len(), "{label}");
        for (k, c) in ["flap", "edge"].iter().enumerate() {
            let printed = along(c);
            let peak = printed.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!(
                (shape.peaks[k] - peak).abs() < 1e-6 * peak.max(1e-3),
                "{label} {c}: peak {} against {peak}",
                shape.peaks[k]
            );
            for (drawn, value) in shape.components[k].iter().zip(&printed) {
                assert!(
                    (drawn * peak - value).abs() < 1e-6,
                    "{label} {c}: {drawn} × {peak} against {value}"
                );
            }
        }
        // No coupling in the NREL 5MW file: no twist to draw.
        assert_eq!(shape.peaks[2], 0.0, "{label}");
    }
}

/// Along the turbine's schedule: a real blade's rotor speed and pitch are the
/// schedule's at the wind speed and shown as following it (↻); dragging the rotor speed
/// overrides it (overspeed) while the pitch still follows; `o` puts both back on the schedule.
#[test]
fn rotor_speed_and_pitch_follow_the_schedule_until_overridden() {
    let p = Preset::load("iea15mw", &[]).unwrap();
    let mut s = settled_state("iea15mw", p, &Physics, ViewKind::Main, MarkerKind::Braille);
    let row = |s: &AppState, label: &str| {
        let i = PARAMS.iter().position(|p| p.label == label).unwrap();
        s.param_text(&PARAMS[i])
    };
    // 10.7 m/s on the IEA 15MW table: 7.56 rpm.
    assert_eq!(row(&s, "rotor speed"), "↻ 7.56 rpm");
    assert!(row(&s, "pitch").starts_with("↻ "), "{}", row(&s, "pitch"));
    assert_eq!(PARAMS[s.focus].label, "rotor speed");
    // A coarse step is 10 % of the rated 7.56 rpm.
    headless::press(&mut s, &Physics, &[Action::IncreaseCoarse]);
    assert_eq!(row(&s, "rotor speed"), "8.32 rpm");
    assert!(row(&s, "pitch").starts_with("↻ "), "{}", row(&s, "pitch"));
    let solved = s.solved.as_ref().unwrap();
    assert_eq!(solved.setting.map(|(rpm, _)| rpm), Some(8.316));
    headless::press(&mut s, &Physics, &[Action::FollowSchedule]);
    assert_eq!(row(&s, "rotor speed"), "↻ 7.56 rpm");
    // Nothing reads as changed by hand any more (no `*`).
    let start = &s.opened;
    assert_eq!(s.preset.operating.rotor_speed, start.operating.rotor_speed);
    let solved = s.solved.as_ref().unwrap();
    assert!((solved.setting.unwrap().0 - 7.56).abs() < 1e-3);
    // Nothing left to return to: said so.
    headless::press(&mut s, &Physics, &[Action::FollowSchedule]);
    assert!(s.notice.as_deref().unwrap_or("").contains("already follow"));
}

// ---------------------------------------------------------------------------------------------
// The Campbell view against wind speed along the schedule, and margins along the
// schedule and the coupling.
// ---------------------------------------------------------------------------------------------

fn state_on(name: &str, overrides: &[&str], engine: &dyn Engine) -> AppState {
    let ov: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let p = Preset::load(name, &ov).unwrap();
    let (entries, index) = preset_entries(name, &p);
    let mut s = AppState::new(entries, index, p, Options::default());
    let e = s.start();
    settle(&mut s, engine, e);
    s
}

/// `w` opens the Campbell view against wind speed on a scheduled preset and toggles the axis in
/// it; the sweep runs from cut-in to cut-out, keeps while the wind moves (the diagram does not
/// depend on it) and while a rotor-speed override comes and goes, and the axis key on a preset
/// without a schedule says why nothing changes.
#[test]
fn the_campbell_axis_toggles_between_rotor_speed_and_wind_speed_along_the_schedule() {
    let engine = TestEngine::default();
    let mut s = state_on("iea15mw", &[], &engine);
    let e = update(&mut s, key(KeyCode::Char('w'), KeyModifiers::NONE));
    assert_eq!(s.view, ViewMode::Campbell);
    assert_eq!(s.campbell_axis, CampbellAxis::WindSpeed);
    let Some(Effect::Campbell { key: k, grid, .. }) = e.first() else {
        panic!("{e:?}")
    };
    assert_eq!(*k, "operating.wind_speed");
    assert_eq!(grid.len(), 23);
    assert_eq!((grid[0], grid[22]), (3.0, 25.0));
    assert!((grid[1] - 4.0).abs() < 1e-12);
    settle(&mut s, &engine, e);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 1);
    // While computing the pane said so; now the diagram is drawn with the schedule's harmonics.
    let text = render_text(&s, 160, 48);
    assert!(text.contains("Campbell along the schedule"), "{text}");
    assert!(text.contains("1P, 3P, 6P, now"), "{text}");
    assert!(text.contains("· now 10.7 m/s"), "{text}");
    // The wind moves: the same diagram, the marker moves.
    s.focus = PARAMS.iter().position(|p| p.label == "wind speed").unwrap();
    headless::press(&mut s, &engine, &[Action::Increase, Action::IncreaseCoarse]);
    assert_eq!(s.preset.operating.wind_speed, 15.0);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 1);
    assert!(render_text(&s, 160, 48).contains("· now 15.0 m/s"));
    // The wind slider stops at cut-out.
    headless::press(
        &mut s,
        &engine,
        &[Action::IncreaseCoarse, Action::IncreaseCoarse],
    );
    assert_eq!(s.preset.operating.wind_speed, 25.0);
    headless::press(&mut s, &engine, &[Action::Increase]);
    assert!(s.notice.as_deref().unwrap_or("").contains("maximum"));
    // Overspeed by hand: the diagram along the schedule stays the schedule's.
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    headless::press(&mut s, &engine, &[Action::IncreaseCoarse]);
    assert!(s.preset.schedule_overrides.rotor_speed);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 1);
    // Another knob changes it.
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "bend–twist α")
        .unwrap();
    headless::press(&mut s, &engine, &[Action::Increase]);
    assert_eq!(engine.campbells.load(Ordering::SeqCst), 2);
    // w again: against rotor speed, 0 to view.rotor_speed_max.
    let e = update(&mut s, Msg::Action(Action::ToggleCampbellAxis));
    assert_eq!(s.campbell_axis, CampbellAxis::RotorSpeed);
    let Some(Effect::Campbell { key: k, grid, .. }) = e.first() else {
        panic!("{e:?}")
    };
    assert_eq!(*k, "operating.rotor_speed");
    assert_eq!((grid[0], *grid.last().unwrap()), (0.0, 15.0));
    // A preset without a schedule: the key says so, and the view is against rotor speed.
    let mut s = settled(&engine);
    headless::press(&mut s, &engine, &[Action::ToggleCampbellAxis]);
    assert_eq!(s.view, ViewMode::Campbell);
    assert_eq!(s.campbell_axis, CampbellAxis::RotorSpeed);
    assert!(
        s.notice
            .as_deref()
            .unwrap_or("")
            .contains("no operating schedule"),
        "{:?}",
        s.notice
    );
    assert!(render_text(&s, 120, 40).contains("no operating schedule"));
}

/// The explorer's wind-speed margin along the schedule is the unstable stretch the current wind
/// lies in (IEA 15MW, coupling −0.12: flap 1–4 flutter in a stretch of winds around the rated
/// 10.7 m/s): it begins where `flutterscope flutter --vary operating.wind_speed` up from cut-in
/// finds the onset and ends where the blade is stable again, though another stretch (flap 1's
/// static divergence near 17–19 m/s) lies beyond it.
#[test]
fn the_wind_speed_margin_is_the_unstable_stretch_along_the_schedule() {
    let coupled = ["blade.bend_twist_coupling=-0.12"];
    let mut s = state_on("iea15mw", &coupled, &Physics);
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    headless::press(&mut s, &Physics, &[Action::FocusPrev]);
    assert_eq!(s.boundary_key, "operating.wind_speed");
    let job = s.boundary.as_ref().unwrap();
    assert_eq!((job.from, job.to), (3.0, 25.0));
    assert!(job.unstable);
    let text = flutterscope::explorer::ui::status::margin_text(&s).unwrap();
    let onset = |from: &str, to: &str| {
        let out = assert_cmd::Command::cargo_bin("flutterscope")
            .unwrap()
            .args(["flutter", "--preset", "iea15mw", "--set", coupled[0]])
            .args(["--vary", "operating.wind_speed", "--from", from, "--to", to])
            .arg("--json")
            .output()
            .unwrap();
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        json["critical"]
            .as_f64()
            .expect("a crossing between 3 and 25 m/s")
    };
    let begin = onset("3", "25");
    let below = 100.0 * (begin - 10.7) / 10.7;
    let prefix = format!("wind speed: unstable from {begin:.1} m/s, {below:+.0} %, to ");
    assert!(text.starts_with(&prefix), "{text}");
    let end: f64 = text[prefix.len()..]
        .trim_end_matches(" m/s")
        .parse()
        .unwrap();
    let unstable_at = |wind: f64| {
        let p = Preset::load(
            "iea15mw",
            &[
                coupled[0].to_string(),
                format!("operating.wind_speed={wind}"),
            ],
        )
        .unwrap();
        flutterscope::analysis::eigen::analyse(&p)
            .unwrap()
            .eigenvalues
            .iter()
            .any(|e| e.re > 0.0)
    };
    assert!(unstable_at(end - 0.1) && !unstable_at(end + 0.1), "{text}");
    assert!(
        onset("25", "3") > end + 1.0,
        "a second stretch beyond {end} m/s"
    );
}

/// The coupling margin looks both ways from α = 0: on the IEA 15MW at rated the blade flutters
/// below (flap 1) and, nearer, above (edge 2, whose twist the prebent axis couples in), at the α
/// the boundary search finds each way.
#[test]
fn the_coupling_margin_is_the_nearest_crossing_either_way() {
    let mut s = state_on("iea15mw", &[], &Physics);
    s.focus = PARAMS
        .iter()
        .position(|p| p.label == "bend–twist α")
        .unwrap();
    s.boundary_key = "blade.bend_twist_coupling";
    let e = update(&mut s, Msg::Action(Action::Boundary));
    let Some(Effect::Boundary { ranges, .. }) = e.first() else {
        panic!("{e:?}")
    };
    let ends: Vec<(f64, f64)> = ranges.iter().map(|r| (r.from, r.to)).collect();
    assert_eq!(ends, [(0.0, -0.3), (0.0, 0.3)]);
    settle(&mut s, &Physics, e);
    let text = flutterscope::explorer::ui::status::margin_text(&s).unwrap();
    let down = flutterscope::analysis::flutter::flutter_search(
        &s.preset,
        "blade.bend_twist_coupling",
        0.0,
        -0.3,
        21,
    )
    .unwrap();
    let c = down.boundary.critical.expect("flutter below α = 0");
    let up = flutterscope::analysis::flutter::flutter_search(
        &s.preset,
        "blade.bend_twist_coupling",
        0.0,
        0.3,
        21,
    )
    .unwrap();
    let u = up.boundary.critical.expect("flutter above α = 0");
    let (down_mode, up_mode) = (down.boundary.mode.unwrap(), up.boundary.mode.unwrap());
    assert!(c < 0.0 && u > 0.0 && u < -c, "{c} {u}");
    assert_eq!(
        text,
        format!("bend–twist α: flutter at α {c:.2} ({down_mode}) and α {u:.2} ({up_mode})")
    );
}

/// Every real-blade preset's main view and its Campbell view along the schedule, at the smallest
/// and a large window (the mode-shape pane's are `shape_*` above). The diagram runs on 12 winds
/// (2 m/s steps) rather than the explorer's 23 to keep the suite fast; it is the same code.
#[test]
fn snapshot_the_real_blades_main_and_wind_campbell_views() {
    for name in ["nrel5mw", "iea15mw", "iea15mw-btc-st2019"] {
        let p = Preset::load(name, &[]).unwrap();
        let mut s = settled_state(name, p, &Physics, ViewKind::Main, MarkerKind::Braille);
        for (cols, rows) in [(80, 24), (160, 48)] {
            let text = render_text(&s, cols, rows);
            assert!(!text.contains("ERROR"), "{name}:\n{text}");
            insta::assert_snapshot!(format!("main_{name}_{cols}x{rows}"), text);
        }
        s.campbell_wind_points = 12;
        headless::press(&mut s, &Physics, &[Action::ToggleCampbellAxis]);
        let job = s.campbell.as_ref().unwrap();
        assert_eq!((job.from, job.to, job.points), (3.0, 25.0, 12));
        let diagram = job.result.as_ref().unwrap().as_ref().unwrap();
        assert!(
            diagram.sweep.failed.is_empty(),
            "{name}: {:?}",
            diagram.sweep.failed
        );
        for (cols, rows) in [(80, 24), (160, 48)] {
            let text = render_text(&s, cols, rows);
            assert!(
                text.contains("Campbell along the schedule"),
                "{name}:\n{text}"
            );
            assert!(text.contains("· now 10.7 m/s") || text.contains("· now 11.0 m/s"));
            insta::assert_snapshot!(format!("campbell_wind_{name}_{cols}x{rows}"), text);
        }
    }
}

/// The frame `flutterscope snapshot` prints for a preset with `--set` overrides.
fn snapshot_command(preset: &str, sets: &[&str], size: &str) -> String {
    let mut cmd = assert_cmd::Command::cargo_bin("flutterscope").unwrap();
    cmd.args(["snapshot", "--preset", preset, "--size", size]);
    for s in sets {
        cmd.args(["--set", s]);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The rotor speed at which `flutterscope flutter` finds the first boundary from `from` toward
/// `to` on the IEA 15MW, and the mode it names there (none where its tracking cannot tell).
fn iea15mw_rotor_speed_boundary(from: &str, to: &str) -> (f64, Option<String>) {
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .args(["flutter", "--preset", "iea15mw", "--json"])
        .args([
            "--vary",
            "operating.rotor_speed",
            "--from",
            from,
            "--to",
            to,
        ])
        .output()
        .unwrap();
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    (
        json["critical"].as_f64().expect("a boundary in the range"),
        json["mode"].as_str().map(str::to_string),
    )
}

/// The IEA 15MW is stable at its rated 7.56 rpm between a stall instability at 3.6 rpm and the
/// flutter at 12.1 rpm. Stable, the margin names the nearest boundary on each side, with the
/// mode `flutterscope flutter` names there (where the tracking cannot tell the branch, none);
/// 0.3 rpm above the flutter, unstable, it names the unstable stretch the rotor speed lies in
/// and where it begins (it used to say `flutter from 2 rpm, -85 %`: the stall region's onset).
/// Both as `flutterscope flutter` finds them from the rated speed.
#[test]
fn the_rotor_speed_margin_names_the_stretch_the_current_speed_lies_in() {
    let rated = 7.56;
    let ((down, down_mode), (up, up_mode)) = (
        iea15mw_rotor_speed_boundary("7.56", "0"),
        iea15mw_rotor_speed_boundary("7.56", "15"),
    );
    let named = |mode: Option<String>| mode.map(|m| format!(", {m}")).unwrap_or_default();
    let status = |frame: &str| frame.lines().rev().nth(1).unwrap().to_string();
    let stable = status(&snapshot_command("iea15mw", &[], "160x48"));
    let expected = format!(
        "margin along rotor speed: flutter at {down:.2} rpm ({:.2}× rated{}) and \
         {up:.2} rpm ({:.2}× rated{})",
        down / rated,
        named(down_mode),
        up / rated,
        named(up_mode)
    );
    assert!(stable.contains(&expected), "{stable}\nexpected {expected}");
    let unstable = status(&snapshot_command(
        "iea15mw",
        &[format!("operating.rotor_speed={:.2}", up + 0.3).as_str()],
        "160x48",
    ));
    let expected = format!(
        "margin along rotor speed: unstable from {up:.2} rpm, {:.2}× rated",
        up / rated
    );
    assert!(
        unstable.contains("FLUTTER") && unstable.ends_with(&expected),
        "{unstable}\nexpected {expected}"
    );
    // At 80 columns the margin keeps its values.
    let small = status(&snapshot_command("iea15mw", &[], "80x24"));
    assert!(
        small.contains(&format!("flutter at {down:.2} rpm and {up:.2} rpm")),
        "{small}"
    );
}

/// A turbine's rotor speed shows to 0.01 rpm (the IEA 15MW's rated 7.56 rpm used to read
/// `↻ 8 rpm`); the paper's blades at 60 rpm keep their whole rpm.
#[test]
fn rotor_speeds_below_30_rpm_show_to_a_hundredth() {
    let frame = snapshot_command("iea15mw", &[], "80x24");
    assert!(frame.contains("rotor speed         ↻ 7.56 rpm"), "{frame}");
    let frame = snapshot_command("nrel5mw", &["operating.wind_speed=6"], "80x24");
    let row = frame.lines().find(|l| l.contains("rotor speed")).unwrap();
    assert!(row.contains("↻ ") && row.contains('.'), "{row}");
    let frame = snapshot_command("liu2017", &[], "80x24");
    let row = frame.lines().find(|l| l.contains("rotor speed")).unwrap();
    assert!(row.contains(" 60 rpm│"), "{row}");
}

/// An error line wraps over as many rows as it needs (a third of the window at most) instead of
/// being cut at the window's edge: the whole account of liu2017-stall's failed equilibrium at
/// 0 rpm is on screen at 80×24.
#[test]
fn an_error_line_wraps_instead_of_being_cut() {
    let wide = snapshot_command("liu2017-stall", &["operating.rotor_speed=0"], "1000x24");
    let error = wide
        .lines()
        .find(|l| l.starts_with("error: "))
        .expect("an error line")
        .to_string();
    assert!(error.chars().count() > 3 * 80, "{error}");
    let frame = snapshot_command("liu2017-stall", &["operating.rotor_speed=0"], "80x24");
    let lines: Vec<&str> = frame.lines().collect();
    let first = lines.iter().position(|l| l.starts_with("error: ")).unwrap();
    let shown = lines[first..].join(" ");
    assert_eq!(shown, error, "{frame}");
    assert_eq!(lines.len(), 24);
    assert!(lines.iter().all(|l| l.chars().count() <= 80));
}

/// Numbers in the explorer carry the precision of what they stand for: on iea15mw-btc-st2019 at a
/// coupling of −0.1 the margin's search upward used to end at α = 0.30000000000000004, out of
/// the key's range, and the status line said so (`error: boundary search: … = 0.30000000000000004
/// is out of range`); the search now ends at 0.3 and finds its margin.
#[test]
fn a_margin_search_ends_at_the_slider_end_and_prints_no_float_noise() {
    let frame = snapshot_command(
        "iea15mw-btc-st2019",
        &[
            "view.select=\"bend-twist-coupling\"",
            "blade.bend_twist_coupling=-0.1",
        ],
        "200x48",
    );
    assert!(!frame.contains("error"), "{frame}");
    assert!(
        frame.contains("margin along bend–twist α: flutter at α -0.20"),
        "{frame}"
    );
    let noisy = frame
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .any(|w| {
            w.split_once('.')
                .is_some_and(|(_, decimals)| decimals.len() >= 10)
        });
    assert!(!noisy, "{frame}");
}

// ---------------------------------------------------------------------------------------------
// Checks off the event loop: a WindIO blade's ply angle, presets opened on first use.
// ---------------------------------------------------------------------------------------------

/// The checks among `effects`, as (id, what they check).
fn checks(effects: &[Effect]) -> Vec<(u64, Check)> {
    effects
        .iter()
        .filter_map(|e| match e {
            Effect::Check { id, check } => Some((*id, check.clone())),
            _ => None,
        })
        .collect()
}

/// On a WindIO blade the ply angle analyses the blade's sections again: the key asks for a check
/// (run off the event loop) instead of analysing in the key handler. The row shows the new angle
/// at once and the status line says what runs; a second key steps on from it and replaces the
/// check; the answer of an older check is ignored, the newest one's is solved.
#[test]
fn a_ply_angle_key_on_a_windio_blade_is_checked_off_the_event_loop() {
    let engine = TestEngine::default();
    let mut s = state_on("iea15mw-btc", &["view.select=ply-angle"], &engine);
    assert_eq!(PARAMS[s.focus].label, "ply angle");
    assert_eq!(s.preset.section.ply_angle, Some(8.0));
    let gen0 = s.gen;
    let e1 = update(&mut s, Msg::Action(Action::Increase));
    assert!(solve_gens(&e1).is_empty(), "no solve before the check");
    let c1 = checks(&e1);
    assert_eq!(c1.len(), 1);
    assert_eq!(s.gen, gen0, "the parameters have not changed yet");
    assert_eq!(s.preset.section.ply_angle, Some(8.0));
    assert_eq!(s.param_text(&PARAMS[s.focus]), "9.0 deg");
    let text = render_text(&s, 160, 48);
    assert!(
        text.contains("analysing the blade at ply angle 9.0 deg…"),
        "{text}"
    );
    // Marked as changed from the preset at once, as the value shows.
    let row = text.lines().find(|l| l.contains("ply angle")).unwrap();
    assert!(row.contains("ply angle   *"), "{row}");
    // A second key steps from the angle asked for.
    let e2 = update(&mut s, Msg::Action(Action::Increase));
    let c2 = checks(&e2);
    assert_eq!(s.param_text(&PARAMS[s.focus]), "10.0 deg");
    let Check::Edit { value, .. } = &c2[0].1 else {
        panic!("an edit check: {:?}", c2[0].1)
    };
    assert_eq!(*value, 10.0);
    // The first check's answer comes late: ignored.
    let late = runner::check(c1[0].0, &c1[0].1);
    assert!(update(&mut s, late).is_empty());
    assert_eq!(s.preset.section.ply_angle, Some(8.0));
    // The second's is applied and solved.
    let answer = runner::check(c2[0].0, &c2[0].1);
    let e3 = update(&mut s, answer);
    assert_eq!(solve_gens(&e3), vec![gen0 + 1]);
    assert_eq!(s.preset.section.ply_angle, Some(10.0));
    assert!(s.checking.is_none());
    assert_eq!(s.param_text(&PARAMS[s.focus]), "10.0 deg");
    assert!(!render_text(&s, 160, 48).contains("analysing the blade"));
}

/// Another parameter moved while the blade was analysed: the ply angle lands on the parameters
/// as they are now, and neither edit is lost. Other keys never wait for a check.
#[test]
fn an_edit_made_while_the_blade_is_analysed_is_kept() {
    let engine = TestEngine::default();
    let mut s = state_on("iea15mw-btc", &["view.select=ply-angle"], &engine);
    let asked = checks(&update(&mut s, Msg::Action(Action::Decrease)));
    update(&mut s, Msg::Action(Action::FocusNext));
    let focused = PARAMS[s.focus].label;
    let key = match PARAMS[s.focus].kind {
        flutterscope::explorer::state::params::ParamKind::Number { key, .. } => key,
        _ => panic!("a number row after the ply angle, not {focused}"),
    };
    let before = s.preset.get(key).unwrap();
    let e = update(&mut s, Msg::Action(Action::IncreaseCoarse));
    assert_eq!(solve_gens(&e), vec![s.gen], "{focused} is solved at once");
    let moved = s.preset.get(key).unwrap();
    assert_ne!(moved, before);
    let answer = runner::check(asked[0].0, &asked[0].1);
    let e = update(&mut s, answer);
    assert_eq!(solve_gens(&e), vec![s.gen]);
    assert_eq!(s.preset.section.ply_angle, Some(7.0));
    assert_eq!(s.preset.get(key).unwrap(), moved);
}

/// Reset (`r`) while the blade is analysed for a new angle drops that edit: the answer that
/// comes later changes nothing.
#[test]
fn reset_drops_an_edit_still_being_checked() {
    let engine = TestEngine::default();
    let mut s = state_on("iea15mw-btc", &["view.select=ply-angle"], &engine);
    let asked = checks(&update(&mut s, Msg::Action(Action::Increase)));
    let e = update(&mut s, key(KeyCode::Char('r'), KeyModifiers::NONE));
    assert_eq!(solve_gens(&e), vec![s.gen]);
    assert!(s.checking.is_none());
    assert_eq!(s.param_text(&PARAMS[s.focus]), "8.0 deg");
    let late = runner::check(asked[0].0, &asked[0].1);
    assert!(update(&mut s, late).is_empty());
    assert_eq!(s.preset.section.ply_angle, Some(8.0));
}

/// A check that fails (its answer an error, as a layup that cannot be meshed gives) leaves the
/// explorer where it was, with the reason in the status line.
#[test]
fn a_check_that_fails_is_shown_and_changes_nothing() {
    let engine = TestEngine::default();
    let mut s = state_on("iea15mw-btc", &["view.select=ply-angle"], &engine);
    let before = s.preset.clone();
    let asked = checks(&update(&mut s, Msg::Action(Action::Increase)));
    let e = update(
        &mut s,
        Msg::Checked {
            id: asked[0].0,
            result: Err("section.ply_angle = 9: the layup failed".into()),
        },
    );
    assert!(e.is_empty());
    assert_eq!(s.preset, before);
    assert!(s.checking.is_none());
    let text = render_text(&s, 160, 48);
    assert!(text.contains("the layup failed"), "{text}");
}

/// The explorer starts on its preset alone: the other built-ins are checked when first opened
/// (off the event loop), then kept; opening one shows it from a fresh start.
#[test]
fn presets_are_checked_when_first_opened() {
    let engine = TestEngine::default();
    let mut s = settled(&engine);
    let loaded: Vec<&str> = s
        .presets
        .iter()
        .filter(|e| e.preset.is_some())
        .map(|e| e.name.as_str())
        .collect();
    assert_eq!(loaded, vec![DEFAULT_PRESET]);
    let e = update(&mut s, Msg::Action(Action::NextPreset));
    let asked = checks(&e);
    assert!(matches!(&asked[..], [(_, Check::Open { name, .. })] if *name == s.presets[1].name));
    assert_eq!(
        s.preset_index, 0,
        "still on the first until the check answers"
    );
    let text = render_text(&s, 160, 48);
    assert!(
        text.contains(&format!("opening {}…", s.presets[1].name)),
        "{text}"
    );
    let e = update(&mut s, runner::check(asked[0].0, &asked[0].1));
    assert_eq!(solve_gens(&e), vec![s.gen]);
    assert_eq!(s.preset_index, 1);
    assert!(s.presets[1].preset.is_some());
    // Back and forth again: both are kept, nothing to check.
    for a in [Action::PrevPreset, Action::NextPreset] {
        let e = update(&mut s, Msg::Action(a));
        assert!(checks(&e).is_empty());
        assert_eq!(solve_gens(&e), vec![s.gen]);
    }
}
