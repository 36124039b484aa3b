//! The explorer without a terminal or threads: effects are carried out synchronously, in order,
//! so a frame is a pure function of the preset and the keys pressed (snapshots, tests,
//! benchmarks). The tip simulation runs for a fixed number of samples instead of real time.

use crate::analysis::cancel::Cancel;
use crate::error::{Error, Result};
use crate::explorer::display::{ColorMode, MarkerKind, ViewKind};
use crate::explorer::engine::Engine;
use crate::explorer::keys::Action;
use crate::explorer::runner;
use crate::explorer::state::update::update;
use crate::explorer::state::{AppState, Effect, Msg, Options, PresetEntry};
use crate::preset::{builtin_names, ValidPreset};
use ratatui::backend::TestBackend;
use ratatui::buffer::CellWidth;
use ratatui::Terminal;

/// Samples a headless run simulates: one `simulation.duration` at `simulation.sample_rate`
/// (what the response pane holds), capped so a long preset cannot stall a snapshot.
pub fn fixed_samples(p: &ValidPreset) -> usize {
    const CAP: f64 = 20_000.0;
    (p.simulation.duration * p.simulation.sample_rate)
        .round()
        .clamp(1.0, CAP) as usize
}

/// Carry out `effects` and every effect they lead to, synchronously, through the same
/// [`runner`] as the worker threads.
pub fn settle(state: &mut AppState, engine: &dyn Engine, effects: Vec<Effect>) {
    let mut queue: std::collections::VecDeque<Effect> = effects.into();
    while let Some(effect) = queue.pop_front() {
        let msgs: Vec<Msg> = match &effect {
            Effect::Solve { gen, preset } => {
                let (solved, stream) = runner::solve(engine, *gen, preset, &Cancel::never());
                let samples = match stream {
                    Ok(mut stream) => runner::advance(&mut *stream, *gen, fixed_samples(preset)),
                    Err(failed) => failed,
                };
                vec![solved, samples]
            }
            Effect::Check { id, check } => vec![runner::check(*id, check)],
            // No running simulation to kick or pause between headless frames.
            Effect::Kick { .. } | Effect::Pause(_) | Effect::Quit => Vec::new(),
            job => runner::job(engine, job, &Cancel::never())
                .into_iter()
                .collect(),
        };
        for m in msgs {
            queue.extend(update(state, m));
        }
    }
}

/// Press `actions` in order, settling after each.
pub fn press(state: &mut AppState, engine: &dyn Engine, actions: &[Action]) {
    for a in actions {
        let effects = update(state, Msg::Action(*a));
        settle(state, engine, effects);
    }
}

/// The presets `[`/`]` cycle through: the built-ins (checked when first opened), with `first` (a
/// loaded file or a built-in with `--set` overrides) in its built-in's place or in front. Returns
/// the entries and the index of `first`, for [`AppState::new`].
pub fn preset_entries(first_name: &str, first: &ValidPreset) -> (Vec<PresetEntry>, usize) {
    let mut entries: Vec<PresetEntry> = builtin_names()
        .iter()
        .map(|name| PresetEntry {
            name: name.to_string(),
            preset: None,
        })
        .collect();
    match entries.iter().position(|e| e.name == first_name) {
        Some(i) => (entries, i),
        None => {
            entries.insert(
                0,
                PresetEntry {
                    name: first.display_name().to_string(),
                    preset: None,
                },
            );
            (entries, 0)
        }
    }
}

/// A settled explorer on `preset` in `view`, as the snapshot command and the tests see it.
pub fn settled_state(
    name: &str,
    preset: ValidPreset,
    engine: &dyn Engine,
    view: ViewKind,
    marker: MarkerKind,
) -> AppState {
    let (entries, index) = preset_entries(name, &preset);
    let opts = Options {
        color: ColorMode::None,
        marker,
    };
    let mut state = AppState::new(entries, index, preset, opts);
    let effects = state.start();
    settle(&mut state, engine, effects);
    match view {
        ViewKind::Main => {}
        ViewKind::Campbell => press(&mut state, engine, &[Action::ToggleCampbell]),
        // On a preset without a schedule the key says so and the view is against rotor speed.
        ViewKind::CampbellWind => press(&mut state, engine, &[Action::ToggleCampbellAxis]),
        ViewKind::Help => press(&mut state, engine, &[Action::ToggleHelp]),
        ViewKind::Shape => press(&mut state, engine, &[Action::ToggleShape]),
    }
    state
}

/// Parse `COLSxROWS`; at least 80×24 (the smallest layout), at most 1000×500.
pub fn parse_size(text: &str) -> Result<(u16, u16)> {
    let bad = |why: &str| {
        Error::usage(format!(
            "--size '{text}': {why}; expected COLSxROWS between 80x24 and 1000x500, e.g. 120x40"
        ))
    };
    let (w, h) = text
        .trim()
        .split_once(['x', 'X'])
        .ok_or_else(|| bad("missing 'x'"))?;
    // Digits that overflow an integer are a size too large, not "not a number".
    let num = |s: &str| -> Result<u64> {
        let s = s.trim();
        if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad(&format!("'{s}' is not a whole number")));
        }
        Ok(s.parse::<u64>().unwrap_or(u64::MAX))
    };
    let (w, h) = (num(w)?, num(h)?);
    if w < 80 || h < 24 {
        return Err(bad("smaller than 80x24, the smallest explorer layout"));
    }
    if w > 1000 || h > 500 {
        return Err(bad(&format!(
            "{} is too large: at most 1000 columns and 500 rows",
            text.trim()
        )));
    }
    Ok((w as u16, h as u16))
}

/// Render `state` into a `cols × rows` buffer and return it as text, one line per row, trailing
/// spaces trimmed.
pub fn render_text(state: &AppState, cols: u16, rows: u16) -> String {
    let mut terminal = match Terminal::new(TestBackend::new(cols, rows)) {
        Ok(t) => t,
        Err(never) => match never {},
    };
    let frame = match terminal.draw(|f| crate::explorer::ui::render(state, f)) {
        Ok(f) => f,
        Err(never) => match never {},
    };
    buffer_text(frame.buffer)
}

/// A buffer as plain text (symbols only), trailing spaces trimmed.
pub fn buffer_text(buf: &ratatui::buffer::Buffer) -> String {
    let width = buf.area.width as usize;
    let mut out = String::with_capacity(buf.content.len() + buf.area.height as usize);
    for row in buf.content.chunks(width.max(1)) {
        let mut line = String::with_capacity(width);
        let mut skip = 0u16;
        for cell in row {
            if skip == 0 {
                line.push_str(cell.symbol());
            }
            skip = skip.max(cell.cell_width()).saturating_sub(1);
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}
