//! `flutterscope snapshot`: one explorer frame as plain text, after every solve has finished
//! (deterministic: the tip simulation runs a fixed number of samples, no threads, no timing).

use crate::cli::PresetArgs;
use crate::error::Result;
use crate::explorer::display::{MarkerKind, ViewKind};
use crate::explorer::headless::{parse_size, render_text, settled_state};
use crate::explorer::Physics;

pub fn run(preset: &PresetArgs, size: &str, view: ViewKind, marker: MarkerKind) -> Result<()> {
    let (cols, rows) = parse_size(size)?;
    let p = preset.load()?;
    let state = settled_state(&preset.preset, p, &Physics, view, marker);
    super::print_text(&render_text(&state, cols, rows))
}
