//! The interactive explorer: live root locus, streaming tip response, modes, stability margin and
//! a Campbell diagram, in any terminal (including over SSH), and headless for snapshots.
//!
//! One way through: `terminal` reads a key → `keys` maps it to an [`keys::Action`] →
//! [`state::update::update`] changes the parameters and returns [`state::Effect`]s → the
//! `worker` re-solves through the [`engine::Engine`] (the analysis layer) → its results come back
//! as [`state::Msg`]s → `update` stores them → [`ui::render`] draws the next frame. `update` and
//! `render` do no I/O; only `terminal` touches the terminal.

pub mod display;
pub mod engine;
pub mod headless;
pub mod keys;
pub mod runner;
pub mod state;
pub mod terminal;
pub mod ui;
pub mod worker;

pub use engine::{Engine, Physics, Solve, Solved, Stream};
pub use state::{AppState, Effect, Msg, Options};
