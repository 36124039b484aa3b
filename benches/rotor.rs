//! A real blade in the wind (docs/model.md §12): the IEA 15MW preset (12 modes, 30 stations,
//! Theodorsen) at 10.7 m/s along its operating table. One operating point is the steady
//! aeroelastic equilibrium (schedule, BEM passes, structure, strips; target with the eigen-solve
//! < 3 ms) and the whole stability analysis of it; the Campbell is the 23-point sweep along the
//! schedule from 3 to 25 m/s (target < 0.2 s on two cores); ONERA at 30 stations (target
//! < 50 ms a point); the Hansen–Gaunaa–Madsen model at 30 stations (targets < 20 ms a point,
//! < 0.5 s the Campbell).
//!
//! Run: `cargo bench --bench rotor`.

use flutterscope::analysis::eigen::{analyse, analyse_system, linear_system};
use flutterscope::analysis::sweep::track;
use flutterscope::model::operating::steady;
use flutterscope::physics::aero::blade_element::Unsteadiness;
use flutterscope::preset::{Preset, ValidPreset};

fn main() {
    divan::main();
}

fn preset() -> ValidPreset {
    Preset::load("iea15mw", &[]).unwrap()
}

/// The steady aeroelastic operating point alone.
#[divan::bench]
fn operating_point(bencher: divan::Bencher) {
    let p = preset();
    bencher.bench(|| steady(divan::black_box(&p), Unsteadiness::Theodorsen).unwrap());
}

/// The NREL 5MW above rated on its control law (13 m/s, quasi-steady): the pitch that holds
/// rated power found pass by pass on the deflected blade, the structure following it.
#[divan::bench]
fn law_operating_point_above_rated(bencher: divan::Bencher) {
    let p = Preset::load("nrel5mw", &["operating.wind_speed=13".into()]).unwrap();
    bencher.bench(|| steady(divan::black_box(&p), Unsteadiness::QuasiSteady).unwrap());
}

/// The same at the pitch the law found, held by hand: the operating point without the search.
#[divan::bench]
fn operating_point_at_the_law_pitch(bencher: divan::Bencher) {
    let law = Preset::load("nrel5mw", &["operating.wind_speed=13".into()]).unwrap();
    let pitch = steady(&law, Unsteadiness::QuasiSteady)
        .unwrap()
        .0
        .operating
        .pitch;
    let p = law.with("operating.pitch", pitch).unwrap();
    bencher.bench(|| steady(divan::black_box(&p), Unsteadiness::QuasiSteady).unwrap());
}

/// Operating point, linearisation and eigen-analysis with mode names: what a key press costs.
#[divan::bench]
fn stability_at_an_operating_point(bencher: divan::Bencher) {
    let p = preset();
    bencher.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// Its eigen-analysis alone (84 states, left and right vectors, names), on the system built
/// once: what the operating point leaves of the budget.
#[divan::bench]
fn eigen_analysis_of_the_operating_point(bencher: divan::Bencher) {
    let ls = linear_system(&preset()).unwrap();
    bencher.bench(|| analyse_system(divan::black_box(&ls)).unwrap());
}

/// The same for ONERA's system.
#[divan::bench]
fn eigen_analysis_of_the_operating_point_onera(bencher: divan::Bencher) {
    let p = Preset::load("iea15mw", &["aero.model=onera".to_string()]).unwrap();
    let ls = linear_system(&p).unwrap();
    bencher.bench(|| analyse_system(divan::black_box(&ls)).unwrap());
}

/// The same with ONERA's stall states on every station's own polar (target < 50 ms a point).
#[divan::bench]
fn stability_at_an_operating_point_onera(bencher: divan::Bencher) {
    let p = Preset::load("iea15mw", &["aero.model=onera".to_string()]).unwrap();
    bencher.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// The aeroelastic Campbell diagram along the schedule, 3–25 m/s in 1 m/s steps, tracked.
#[divan::bench(sample_count = 5)]
fn campbell_along_the_schedule(bencher: divan::Bencher) {
    let p = preset();
    let grid: Vec<f64> = (3..=25).map(f64::from).collect();
    bencher.bench(|| track(divan::black_box(&p), "operating.wind_speed", &grid).unwrap());
}

fn hgm() -> ValidPreset {
    Preset::load("iea15mw", &["aero.model=hgm".to_string()]).unwrap()
}

/// The whole stability analysis with the Hansen–Gaunaa–Madsen model at every station (target
/// with the eigen-solve < 20 ms a point).
#[divan::bench]
fn stability_at_an_operating_point_hgm(bencher: divan::Bencher) {
    let p = hgm();
    bencher.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// Its eigen-analysis alone (144 states), on the system built once.
#[divan::bench]
fn eigen_analysis_of_the_operating_point_hgm(bencher: divan::Bencher) {
    let ls = linear_system(&hgm()).unwrap();
    bencher.bench(|| analyse_system(divan::black_box(&ls)).unwrap());
}

/// The Campbell diagram along the schedule with it (target < 0.5 s).
#[divan::bench(sample_count = 5)]
fn campbell_along_the_schedule_hgm(bencher: divan::Bencher) {
    let p = hgm();
    let grid: Vec<f64> = (3..=25).map(f64::from).collect();
    bencher.bench(|| track(divan::black_box(&p), "operating.wind_speed", &grid).unwrap());
}

fn turbine() -> ValidPreset {
    Preset::load("iea15mw", &["turbine.model=turbine".to_string()]).unwrap()
}

/// The whole turbine (3 blades × 12 modes, the free drivetrain, four tower modes, Theodorsen at
/// 30 stations per blade) at one operating point: equilibrium, linearisation, multi-blade
/// transform, eigen-analysis and names (target < 30 ms).
#[divan::bench]
fn stability_at_an_operating_point_turbine(bencher: divan::Bencher) {
    let p = turbine();
    bencher.bench(|| analyse(divan::black_box(&p)).unwrap());
}

/// Its ground-frame state matrix alone: the operating point, the rotor and tower built, the
/// rotating-frame linearisation and the transform.
#[divan::bench]
fn ground_frame_system_turbine(bencher: divan::Bencher) {
    let p = turbine();
    bencher.bench(|| linear_system(divan::black_box(&p)).unwrap());
}

/// Its eigen-analysis alone, on the system built once.
#[divan::bench]
fn eigen_analysis_of_the_operating_point_turbine(bencher: divan::Bencher) {
    let ls = linear_system(&turbine()).unwrap();
    bencher.bench(|| analyse_system(divan::black_box(&ls)).unwrap());
}

/// The ground-frame Campbell diagram of the whole turbine along the schedule, 3–25 m/s
/// (target < 1 s on two cores).
#[divan::bench(sample_count = 3)]
fn campbell_along_the_schedule_turbine(bencher: divan::Bencher) {
    let p = turbine();
    let grid: Vec<f64> = (3..=25).map(f64::from).collect();
    bencher.bench(|| track(divan::black_box(&p), "operating.wind_speed", &grid).unwrap());
}
