//! Explorer speed (issue 4): one 160×48 frame rendered into a TestBackend buffer (target < 2 ms),
//! and a key press → re-solve → rendered frame for the quasi-steady and theodorsen models at
//! N = 5 (target < 30 ms). The solve is what the worker thread runs; the boundary search and the
//! tip simulation that follow it run in the background and are not part of the latency.

use flutterscope::cli::{MarkerKind, ViewKind};
use flutterscope::explorer::headless::settled_state;
use flutterscope::explorer::keys::Action;
use flutterscope::explorer::state::{update, Effect, Msg, PARAMS};
use flutterscope::explorer::{ui, Engine, Physics};
use flutterscope::preset::{Preset, DEFAULT_PRESET};
use ratatui::backend::TestBackend;
use ratatui::Terminal;

fn main() {
    divan::main();
}

fn preset(model: &str) -> Preset {
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

#[divan::bench(args = ["quasi-steady", "theodorsen"])]
fn key_to_solved_frame_160x48(bencher: divan::Bencher, model: &str) {
    let mut state = settled_state(
        DEFAULT_PRESET,
        preset(model),
        &Physics,
        ViewKind::Main,
        MarkerKind::Braille,
    );
    state.focus = PARAMS
        .iter()
        .position(|p| p.label == "rotor speed")
        .unwrap();
    let mut terminal = Terminal::new(TestBackend::new(160, 48)).unwrap();
    let mut up = true;
    bencher.bench_local(|| {
        // Alternate up and down so the operating point stays put over the run.
        let action = if up {
            Action::Increase
        } else {
            Action::Decrease
        };
        up = !up;
        for effect in update(&mut state, Msg::Action(action)) {
            if let Effect::Solve { gen, preset } = effect {
                let result = Physics.solve(&preset).map_err(|e| e.to_string());
                update(&mut state, Msg::Solved { gen, result });
            }
        }
        assert!(!state.solving());
        terminal.draw(|f| ui::render(&state, f)).unwrap();
    });
}
