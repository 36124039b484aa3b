//! The integration tests, one binary (one link on the 2-core CI machine): each module is an
//! area of the program, driven through the library or the real `flutterscope` binary.

mod bem;
mod blade;
mod cli_basic;
mod cli_reliability;
mod coupling;
mod eigen;
mod explorer;
mod formats;
mod hostile;
mod identify;
mod laminate;
mod modes;
mod onera;
mod paper_figures;
mod pitch_range;
mod plot;
mod presets;
mod readme;
mod rotor_aero;
mod simulate;
mod stability;
mod structure;
mod sweep;
mod tabulated;
mod tui_tmux;
mod validation;
