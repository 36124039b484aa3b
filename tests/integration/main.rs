//! The integration tests, one binary (one link on the 2-core CI machine): each module is an
//! area of the program, driven through the library or the real `flutterscope` binary.

mod architecture;
mod bem;
mod blade;
mod cli_basic;
mod cli_reliability;
mod coupling;
mod cross_section;
mod curved;
mod eigen;
mod explorer;
mod formats;
mod hgm;
mod hostile;
mod htc;
mod identify;
mod laminate;
mod layup_blade;
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
mod timoshenko;
mod tower;
mod tui_tmux;
mod turbine;
mod validation;
mod windio;

/// The real binary run with `args`, as a user would; a failure fails the test with its stderr.
fn flutterscope_ok(args: &[&str]) -> std::process::Output {
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// A copy of the folder `from` and everything in it at `to`, as a user copies a model.
fn copy_tree(from: &std::path::Path, to: &std::path::Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}
