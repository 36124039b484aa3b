//! Steady BEM timings (docs/model.md §12.2, README figures): one solve of the IEA 15MW rotor at
//! 30 stations (its preset's Gauss stations, sections from the HAWC2 ae and pc files) at rated
//! (10.7 m/s, 7.56 rpm), with the preset's thrust–induction relation (Madsen's) and with Buhl's,
//! and the same with the sections looked up afresh (what a caller pays when
//! the stations change). The control law's operating point is the deflected blade's
//! (`benches/rotor.rs`).
//!
//! Run: `cargo bench --bench bem`.

use flutterscope::model::aero::rotor_of;
use flutterscope::physics::rotor::bem::{solve, AeroStation, Conditions, Rotor};
use flutterscope::physics::rotor::induction::HighThrust;
use flutterscope::preset::Preset;

fn main() {
    divan::main();
}

fn iea15mw() -> (Rotor, Vec<AeroStation>, Conditions) {
    let p = Preset::load("iea15mw", &[]).unwrap();
    let blade = p.aero_blade().unwrap();
    let rotor = rotor_of(&p, blade);
    let stations = AeroStation::gauss(blade, 30).unwrap();
    let at = Conditions {
        wind_speed: 10.7,
        rotor_speed: 7.56 * std::f64::consts::PI / 30.0,
        pitch: 0.0,
        air_density: 1.225,
    };
    (rotor, stations, at)
}

#[divan::bench]
fn solve_30_stations(bencher: divan::Bencher) {
    let (rotor, stations, at) = iea15mw();
    bencher.bench(|| solve(&rotor, &stations, &[], &at).unwrap());
}

#[divan::bench]
fn solve_30_stations_buhl(bencher: divan::Bencher) {
    let (rotor, stations, at) = iea15mw();
    let rotor = Rotor {
        high_thrust: HighThrust::Buhl,
        ..rotor
    };
    bencher.bench(|| solve(&rotor, &stations, &[], &at).unwrap());
}

#[divan::bench]
fn stations_and_solve_30(bencher: divan::Bencher) {
    let p = Preset::load("iea15mw", &[]).unwrap();
    let blade = p.aero_blade().unwrap().clone();
    let (rotor, _, at) = iea15mw();
    bencher.bench(|| {
        let stations = AeroStation::gauss(&blade, 30).unwrap();
        solve(&rotor, &stations, &[], &at).unwrap()
    });
}
