//! Time-response and stall-model timings (README figures): 20 s at 200 samples/s with
//! N = 5 for every aerodynamic model, and the ONERA linearisation with eigen-analysis.
//! Run: `cargo bench --bench simulate`.

use flutterscope::analysis::eigen::{analyse_system, linear_system};
use flutterscope::analysis::response::simulate;
use flutterscope::preset::{Preset, ValidPreset};

fn main() {
    divan::main();
}

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

/// 20 s from rest, N = 5, each linear model on the paper's blade: target < 10 ms.
#[divan::bench(args = ["none", "quasi-steady", "theodorsen"], sample_count = 10)]
fn simulate_20s_linear(b: divan::Bencher, model: &str) {
    let p = preset(
        "liu2017",
        &["structure.modes=5", &format!("aero.model={model}")],
    );
    b.bench(|| simulate(divan::black_box(&p)).unwrap());
}

/// 20 s from rest, N = 5, ONERA coupled with 8 stations (84 states), the paper's stall case:
/// target < 100 ms.
#[divan::bench(sample_count = 10)]
fn simulate_20s_onera_coupled(b: divan::Bencher) {
    let p = preset(
        "liu2017-stall",
        &[
            "structure.modes=5",
            "aero.stations=8",
            "simulation.duration=20",
        ],
    );
    b.bench(|| simulate(divan::black_box(&p)).unwrap());
}

/// The same from equilibrium with a 1° tip twist kick.
#[divan::bench(sample_count = 10)]
fn simulate_20s_onera_coupled_kick(b: divan::Bencher) {
    let p = preset(
        "liu2017-stall",
        &[
            "structure.modes=5",
            "aero.stations=8",
            "simulation.duration=20",
            "simulation.start=equilibrium",
            "simulation.kick_twist=1",
        ],
    );
    b.bench(|| simulate(divan::black_box(&p)).unwrap());
}

/// Equilibrium (damped Newton), state matrix and eigen-analysis of ONERA coupled, 8 stations:
/// target < 15 ms.
#[divan::bench(sample_count = 20)]
fn linearise_and_eigen_onera_8_stations(b: divan::Bencher) {
    let p = preset("liu2017-stall", &["structure.modes=5", "aero.stations=8"]);
    b.bench(|| analyse_system(&linear_system(divan::black_box(&p)).unwrap()).unwrap());
}
