//! `flutterscope tui`: the interactive explorer (needs a terminal on stdin and stdout).

use crate::cli::{DisplayArgs, PresetArgs};
use crate::error::{Error, Result};
use crate::explorer::headless::preset_entries;
use crate::explorer::state::{AppState, Options};
use crate::explorer::{terminal, Physics};
use std::io::IsTerminal;
use std::sync::Arc;

pub fn run(preset: &PresetArgs, display: &DisplayArgs, fps: u32) -> Result<()> {
    if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(Error::usage(format!(
            "the explorer needs a terminal on stdin and stdout. Without one, use the headless \
             commands: `flutterscope snapshot --preset {p} --size 120x40` renders one explorer \
             frame as text; `flutterscope eigen --preset {p}`, `flutter`, `sweep`, `simulate` \
             compute the same results (see `flutterscope --help`)",
            p = preset.preset
        )));
    }
    let first = preset.load()?;
    let (entries, index) = preset_entries(&preset.preset, first);
    let state = AppState::new(
        entries,
        index,
        Options {
            color: display.color,
            marker: display.marker,
        },
    );
    terminal::run(state, Arc::new(Physics), fps)
}
