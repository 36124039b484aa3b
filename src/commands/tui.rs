//! `flutterscope tui`: the interactive explorer (needs a terminal on stdin and stdout).

use crate::cli::TuiArgs;
use crate::error::{Error, Result};
use crate::explorer::headless::preset_entries;
use crate::explorer::state::{AppState, Options};
use crate::explorer::{terminal, Physics};
use std::io::IsTerminal;
use std::sync::Arc;

pub fn run(args: &TuiArgs) -> Result<()> {
    let (preset, display, fps) = (&args.preset, &args.display, args.fps);
    // A dumb terminal (Emacs shell buffers, some CI consoles) cannot move the cursor or switch
    // to the alternate screen: the full-screen explorer would scribble escape codes over it.
    if std::env::var_os("TERM").is_some_and(|t| t == "dumb") {
        return Err(Error::usage(format!(
            "TERM=dumb: this terminal cannot show the full-screen explorer (no cursor movement \
             or alternate screen). Use the headless commands: `flutterscope snapshot --preset \
             {p} --size 120x40` renders one explorer frame as text; `flutterscope eigen \
             --preset {p}`, `flutter`, `sweep`, `simulate` compute the same results (see \
             `flutterscope --help`); or run it in a terminal with a real TERM (e.g. xterm-256color)",
            p = preset.preset
        )));
    }
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
    let (entries, index) = preset_entries(&preset.preset, &first);
    let state = AppState::new(
        entries,
        index,
        first,
        Options {
            color: display.color,
            marker: display.marker,
        },
    );
    terminal::run(state, Arc::new(Physics), fps)
}
