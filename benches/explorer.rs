//! Explorer speed: one 160×48 frame rendered into a TestBackend buffer (target < 2 ms),
//! and a key press → re-solve → rendered frame for the quasi-steady, theodorsen and onera models
//! at N = 5 (target < 30 ms). The re-solve is what the worker's solver thread runs for a key: one
//! build of the system, its eigen-analysis and the start of the tip simulation from the same
//! linearisation. The boundary search and the streamed samples that follow run in the
//! background and are not part of the latency.

use flutterscope::analysis::cancel::Cancel;
use flutterscope::explorer::display::{MarkerKind, ViewKind};
use flutterscope::explorer::headless::settled_state;
use flutterscope::explorer::keys::Action;
use flutterscope::explorer::runner;
use flutterscope::explorer::state::params::PARAMS;
use flutterscope::explorer::state::update::update;
use flutterscope::explorer::state::{AppState, Effect, Msg};
use flutterscope::explorer::{ui, Engine, Physics};
use flutterscope::preset::{Preset, ValidPreset, DEFAULT_PRESET};
use ratatui::backend::TestBackend;
use ratatui::Terminal;

fn main() {
    divan::main();
}

fn preset(model: &str) -> ValidPreset {
    Preset::load(
        DEFAULT_PRESET,
        &[format!("aero.model={model}"), "structure.modes=5".into()],
    )
    .expect("default preset loads")
}

#[divan::bench]
fn render_160x48(bencher: divan::Bencher) {
    let state = settled_state(
        DEFAULT_PRESET,
        preset("quasi-steady"),
        &Physics,
        ViewKind::Main,
        MarkerKind::Braille,
    );
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    bencher.bench_local(|| {
        terminal.draw(|f| ui::render(&state, f)).unwrap();
    });
}

#[divan::bench(args = ["quasi-steady", "theodorsen", "onera"])]
fn key_to_solved_frame_160x48(bencher: divan::Bencher, model: &str) {
    let state = settled_state(
        DEFAULT_PRESET,
        preset(model),
        &Physics,
        ViewKind::Main,
        MarkerKind::Braille,
    );
    key_to_frame(bencher, state, "rotor speed");
}

/// The IEA 15MW in the wind (12 modes, 30 stations) at its rated point; a key on the
/// rotor speed (an overspeed step, the structure's build kept) and on the wind speed (a step
/// along the schedule: new pitch and rotor speed, its own deflected operating point). Targets:
/// < 30 ms with theodorsen, < 150 ms with onera.
#[divan::bench(
    args = ["theodorsen/rotor speed", "theodorsen/wind speed", "onera/rotor speed", "onera/wind speed"],
    sample_count = 20
)]
fn key_to_solved_frame_160x48_iea15mw(bencher: divan::Bencher, case: &str) {
    let (model, row) = case.split_once('/').unwrap();
    let p = Preset::load("iea15mw", &[format!("aero.model={model}")]).expect("iea15mw loads");
    let state = settled_state("iea15mw", p, &Physics, ViewKind::Main, MarkerKind::Braille);
    key_to_frame(bencher, state, row);
}

/// The same on the whole IEA 15MW turbine (`turbine.model = "turbine"`: 3 blades × 12 modes,
/// the drivetrain and the tower in the ground frame), theodorsen (target < 100 ms).
#[divan::bench(args = ["rotor speed", "wind speed"], sample_count = 10)]
fn key_to_solved_frame_160x48_iea15mw_turbine(bencher: divan::Bencher, row: &str) {
    let p = Preset::load("iea15mw", &["turbine.model=turbine".to_string()]).expect("iea15mw loads");
    let state = settled_state("iea15mw", p, &Physics, ViewKind::Main, MarkerKind::Braille);
    key_to_frame(bencher, state, row);
}

/// One key press on parameter row `row`, its solve (what the worker's solver thread runs) and the
/// 160×48 frame drawn from the result.
fn key_to_frame(bencher: divan::Bencher, state: AppState, row: &str) {
    // Alternate up and down so the operating point stays put over the run.
    let mut up = false;
    keys_to_frames(bencher, state, row, move || {
        up = !up;
        if up {
            Action::Increase
        } else {
            Action::Decrease
        }
    });
}

/// Key presses on parameter row `row`, each `next()`, with their solves and frames.
fn keys_to_frames(
    bencher: divan::Bencher,
    mut state: AppState,
    row: &str,
    mut next: impl FnMut() -> Action,
) {
    state.focus = PARAMS.iter().position(|p| p.label == row).unwrap();
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    bencher.bench_local(|| {
        // The key, the check it may ask for (a blade analysed again) and the solve; the
        // background jobs are left out.
        let mut effects = update(&mut state, Msg::Action(next()));
        while let Some(effect) = effects.pop() {
            match effect {
                Effect::Check { id, check } => {
                    effects.extend(update(&mut state, runner::check(id, &check)));
                }
                Effect::Solve { gen, preset } => {
                    let (solved, stream) = runner::solve(&Physics, gen, &preset, &Cancel::never());
                    update(&mut state, solved);
                    divan::black_box(stream.is_ok());
                }
                _ => {}
            }
        }
        assert!(!state.solving() && state.checking.is_none());
        terminal.draw(|f| ui::render(&state, f)).unwrap();
    });
}

/// The worker's work for one key without the frame: one build, its eigen-analysis and the start
/// of the tip simulation from the same linearisation.
#[divan::bench(args = ["quasi-steady", "theodorsen", "onera"])]
fn solve_and_start_stream(bencher: divan::Bencher, model: &str) {
    let p = preset(model);
    bencher.bench_local(|| {
        let s = Physics.solve(divan::black_box(&p), &Cancel::never());
        (s.solved.is_ok(), s.stream.is_ok())
    });
}

/// The bend–twist-coupled IEA 15MW from its WindIO layup (`iea15mw-btc`): a key that turns the
/// spar caps a degree further (a ply angle never analysed before, as a drag gives) → the turned
/// stations' sections (21 of 50, r/R 0.6–1.0) → beam → modal basis → operating point →
/// eigen-analysis → 160×48 frame. Target < 150 ms.
#[divan::bench(sample_count = 10, sample_size = 1)]
fn ply_angle_to_solved_frame_160x48_iea15mw_btc(bencher: divan::Bencher) {
    let p = Preset::load("iea15mw-btc", &[]).expect("iea15mw-btc loads");
    let state = settled_state(
        "iea15mw-btc",
        p,
        &Physics,
        ViewKind::Main,
        MarkerKind::Braille,
    );
    keys_to_frames(bencher, state, "ply angle", || Action::Increase);
}
