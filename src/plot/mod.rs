//! Publication-quality plots: a small declarative figure model and one writer.
//!
//! The commands build a [`Figure`] from their results (this module computes no physics, it only
//! draws the numbers it is given) and call [`write()`], which picks SVG or PNG from the
//! file's extension. A figure is a grid of [`Panel`]s (one column by default: stacked panels,
//! e.g. a Campbell diagram with frequency above damping); each panel has axes with units, data
//! [`Series`], reference [`Guide`] lines (1P/3P, a flutter boundary, zero damping), labelled
//! [`Marker`]s and free-text notes.
//!
//! Rendering never needs a system font: DejaVu Sans is registered from bytes embedded in the
//! binary (the `dejavu` crate) for plotters' `ab_glyph` text path. Figures are drawn in memory
//! and written in one `std::fs::write`, so a bad path gives an
//! [`Error::Io`](crate::error::Error::Io) naming it and never leaves a half-written file from a
//! drawing failure.
//!
//! [`from_results`] turns the engine's results (sweeps, flutter searches, time responses, section
//! grids) into figures; the commands call it for `--plot FILE`.
//!
//! SVG structure (the tests rely on it): every maximal run of finite, in-range points of a line
//! series (`Mark::Line` or `Mark::LinePoints`) is exactly one `<polyline>`; legend swatches,
//! frames and the grid are `<rect>`/`<line>`; guides are drawn as dashes (several short
//! `<polyline>`s) and points as `<circle>`s.
//!
//! Inside: `figure` holds the model, `output` the files, formats and font, `layout` the geometry
//! (ranges, ticks, clipping, legend and notes placement) that both the plotters backend `draw`
//! and the terminal renderer [`text`] follow.

mod draw;
mod figure;
pub mod from_results;
mod layout;
mod output;
pub mod text;

pub use figure::{
    Dash, Figure, Guide, GuideKind, Mark, Marker, Panel, Rgb, Series, Style, DEFAULT_SIZE, PALETTE,
};
pub use layout::visible_runs;
pub use output::{format_for, render_png, render_svg, write, Format};
