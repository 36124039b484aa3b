//! Stability engine timings (README figures): re-solve = assemble + equilibrium + eigen with
//! vectors; a 10,000-point quasi-steady sweep on all cores; flutter search; linear simulation.
//! Run: `cargo bench --bench stability`.

use flutterscope::analysis::eigen::analyse;
use flutterscope::analysis::flutter::{flutter_boundary, flutter_search};
use flutterscope::analysis::grid::Grid;
use flutterscope::analysis::response::simulate;
use flutterscope::analysis::sweep::{grid_sweep, named_modes};
use flutterscope::preset::{Preset, ValidPreset};

fn main() {
    divan::main();
}

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

/// The paper's blade, N = 5, quasi-steady (8 stations): target < 150 µs.
#[divan::bench]
fn resolve_quasi_steady_n5(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    b.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// The demo blade, N = 5, theodorsen with 16 stations (52 states): target < 2 ms.
#[divan::bench]
fn resolve_theodorsen_n5_16_stations(b: divan::Bencher) {
    let p = preset("demo-blade", &["structure.modes=5", "aero.stations=16"]);
    b.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// 100 × 100 grid (pitch × rotor speed) of the paper's blade, tracked: target < 5 s.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn sweep_10k_quasi_steady(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    let grid = Grid {
        keys: vec!["operating.pitch".into(), "operating.rotor_speed".into()],
        axes: vec![
            (0..100).map(|k| 0.2 * k as f64).collect(),
            (0..100).map(|k| 2.0 * k as f64).collect(),
        ],
    };
    b.bench(|| rows_of(&p, &grid));
}

/// The rows of a whole grid sweep, streamed and counted as an output would take them.
fn rows_of(p: &ValidPreset, grid: &Grid) -> usize {
    let mut rows = 0usize;
    grid_sweep(p, grid, None, &|_| {}, &mut |batch| {
        rows += batch.len();
        Ok(())
    })
    .unwrap();
    rows
}

/// The paper's blade as the README sweeps it: 2,001 wind speeds, 5 to 30 m/s, tracked
/// (`sweep --preset liu2017 --vary operating.wind_speed=5:30:0.0125` in process).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn sweep_2001_wind_speeds_liu2017(b: divan::Bencher) {
    let p = preset("liu2017", &[]);
    let grid = Grid {
        keys: vec!["operating.wind_speed".into()],
        axes: vec![(0..=2000).map(|k| 5.0 + 0.0125 * k as f64).collect()],
    };
    b.bench(|| rows_of(&p, &grid));
}

/// Goland flutter speed, 41-point bracket + bisection.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn flutter_search_goland(b: divan::Bencher) {
    let p = preset("goland", &[]);
    b.bench(|| flutter_boundary(&p, "operating.tunnel_speed", 50.0, 250.0, 41).unwrap());
}

/// 20 s at 200 samples/s, N = 5, quasi-steady: target < 10 ms.
#[divan::bench(sample_count = 10)]
fn simulate_20s_quasi_steady(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    b.bench(|| simulate(divan::black_box(&p)).unwrap());
}

/// Breakdown of the quasi-steady re-solve: structure assembly alone.
#[divan::bench]
fn part_assemble_n5(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    b.bench(|| flutterscope::model::assemble(divan::black_box(&p)).unwrap());
}

/// Breakdown: system set-up, equilibrium and state matrix (quasi-steady, N = 5).
#[divan::bench]
fn part_linearise_n5(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    b.bench(|| flutterscope::analysis::eigen::linear_system(divan::black_box(&p)).unwrap());
}

/// Breakdown: eigen-analysis with vectors of the 20-state quasi-steady system.
#[divan::bench]
fn part_eigen_n5(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    let ls = flutterscope::analysis::eigen::linear_system(&p).unwrap();
    b.bench(|| flutterscope::analysis::eigen::analyse_system(divan::black_box(&ls)).unwrap());
}

/// Breakdown: the dense eigendecomposition (left and right vectors) of a 20 × 20 state matrix
/// (`analyse` skips the left vectors when there are no aero states).
#[divan::bench]
fn part_eigen_decomposition_20(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    let ls = flutterscope::analysis::eigen::linear_system(&p).unwrap();
    b.bench(|| flutterscope::numeric::eigen_decomposition(divan::black_box(&ls.a)).unwrap());
}

/// Reference: the same decomposition of a well-scaled random 20 × 20 matrix.
#[divan::bench]
fn part_eigen_decomposition_random_20(b: divan::Bencher) {
    let a = nalgebra::DMatrix::<f64>::from_fn(20, 20, |i, j| ((i * 31 + j * 17) as f64).sin());
    b.bench(|| flutterscope::numeric::eigen_decomposition(divan::black_box(&a)).unwrap());
}

/// Breakdown: eigen-analysis with vectors of the 52-state theodorsen system (16 stations).
#[divan::bench]
fn part_eigen_theodorsen_n5_16_stations(b: divan::Bencher) {
    let p = preset("demo-blade", &["structure.modes=5", "aero.stations=16"]);
    let ls = flutterscope::analysis::eigen::linear_system(&p).unwrap();
    b.bench(|| flutterscope::analysis::eigen::analyse_system(divan::black_box(&ls)).unwrap());
}

/// Breakdown: the in-vacuo natural modes that label the structural roots (N = 5), found on a
/// structure that has not been asked for them yet (it keeps them once found).
#[divan::bench]
fn part_natural_modes_n5(b: divan::Bencher) {
    let p = preset("liu2017", &["structure.modes=5"]);
    b.with_inputs(|| flutterscope::model::assemble(&p).unwrap())
        .bench_local_refs(|s| divan::black_box(&*s).natural_modes().unwrap());
}

/// Breakdown: the eigendecomposition alone (right and left vectors) of the 52-state theodorsen
/// system, without identification: `part_eigen_theodorsen_n5_16_stations` minus this is what
/// naming the roots costs (docs/model.md §6.2).
#[divan::bench]
fn part_decompose_theodorsen_n5_16_stations(b: divan::Bencher) {
    let p = preset("demo-blade", &["structure.modes=5", "aero.stations=16"]);
    let ls = flutterscope::analysis::eigen::linear_system(&p).unwrap();
    b.bench(|| flutterscope::numeric::decompose(divan::black_box(&ls.a), true).unwrap());
}

/// `flutter --plot` on the IEA 15MW along rotor speed 0–30 rpm, 41 points: the search (its
/// crossing named along the search path) and the figure's modes from the search's own grid.
#[divan::bench(sample_count = 3, sample_size = 1)]
fn flutter_search_and_figure_iea15mw(b: divan::Bencher) {
    let p = preset("iea15mw", &[]);
    b.bench(|| {
        let s = flutter_search(&p, "operating.rotor_speed", 0.0, 30.0, 41).unwrap();
        let tracked = named_modes(&s.boundary.parameter, &s.grid, &s.results);
        flutterscope::plot::from_results::flutter("iea15mw", &tracked, &s)
    });
}
