//! Tabulated-blade structure timings (docs/model.md §11.3–§11.4, README figures): the IEA 15MW
//! blade from its HAWC2 st file at the preset's 120 elements (600 dofs). Assembly (target < 20 ms),
//! the modal basis at the preset's reference speeds, a rotor-speed change on the built basis
//! (target < 200 µs), and `model::for_preset` at a new pitch (a rebuild) and at a new rotor
//! speed (the kept build).
//!
//! Run: `cargo bench --bench blade`.

use flutterscope::model::for_preset;
use flutterscope::physics::blade::fem::{assemble, BladeMatrices, Mesh};
use flutterscope::physics::blade::modal::ModalBlade;
use flutterscope::physics::blade::BladeTable;
use flutterscope::preset::{Preset, ValidPreset};
use std::sync::atomic::{AtomicUsize, Ordering};

fn main() {
    divan::main();
}

/// Reduced-basis modes per reference speed beyond K, as `blade::source` builds it.
const BASIS_MARGIN: usize = 8;

fn preset() -> ValidPreset {
    Preset::load("iea15mw", &[]).unwrap()
}

/// The table as `blade::source` builds it: the file's sections at the preset's hub radius.
fn table(p: &ValidPreset) -> BladeTable {
    let blade = p.tabulated_blade().unwrap();
    BladeTable::new(
        &blade.table.origin,
        p.blade.hub_radius,
        blade.table.sections.clone(),
    )
    .unwrap()
}

fn matrices(p: &ValidPreset) -> BladeMatrices {
    let t = table(p);
    assemble(
        &t,
        &Mesh::following(&t, p.structure.min_elements),
        p.pitch_rad(),
    )
    .unwrap()
}

/// The preset's reference speeds: rest and the top of the range (or the operating speed).
fn reference_speeds(p: &ValidPreset) -> Vec<f64> {
    let top = p.view.rotor_speed_max * std::f64::consts::PI / 30.0;
    vec![0.0, top.max(p.omega())]
}

/// `M`, `K₀`, `K_Ω` of the IEA 15MW blade at 120 elements: target < 20 ms.
#[divan::bench]
fn assemble_iea15mw_120_elements(b: divan::Bencher) {
    let p = preset();
    let t = table(&p);
    let mesh = Mesh::following(&t, p.structure.min_elements);
    b.bench(|| assemble(divan::black_box(&t), &mesh, 0.0).unwrap());
}

/// The modal basis: K + 8 lowest modes at rest and at the top of the range, M-orthonormal.
#[divan::bench(sample_count = 20)]
fn modal_basis_iea15mw(b: divan::Bencher) {
    let p = preset();
    let m = matrices(&p);
    let speeds = reference_speeds(&p);
    let per_speed = p.structure.modes + BASIS_MARGIN;
    b.bench(|| ModalBlade::new(divan::black_box(m.clone()), &speeds, per_speed).unwrap());
}

/// A rotor-speed change: the 12 modes on the built basis (target < 200 µs).
#[divan::bench]
fn modes_at_new_rotor_speed(b: divan::Bencher) {
    let p = preset();
    let modal = ModalBlade::new(
        matrices(&p),
        &reference_speeds(&p),
        p.structure.modes + BASIS_MARGIN,
    )
    .unwrap();
    let omega = 9.1 * std::f64::consts::PI / 30.0;
    b.bench(|| modal.modes(divan::black_box(omega), 12).unwrap());
}

/// `model::for_preset` at a pitch not seen before: assembly + basis + modes (a cache miss).
#[divan::bench(sample_count = 20)]
fn for_preset_new_pitch(b: divan::Bencher) {
    let p = preset();
    let next = AtomicUsize::new(0);
    b.with_inputs(|| {
        let k = next.fetch_add(1, Ordering::Relaxed);
        p.with("operating.pitch", 0.5 + 1e-3 * k as f64).unwrap()
    })
    .bench_refs(|p| for_preset(p).unwrap());
}

/// `model::for_preset` at another rotor speed in the range: the kept build's modes only.
#[divan::bench]
fn for_preset_new_rotor_speed(b: divan::Bencher) {
    let p = preset();
    for_preset(&p).unwrap();
    let next = AtomicUsize::new(0);
    b.with_inputs(|| {
        let k = next.fetch_add(1, Ordering::Relaxed);
        p.with("operating.rotor_speed", 5.0 + 1e-3 * (k % 5000) as f64)
            .unwrap()
    })
    .bench_refs(|p| for_preset(p).unwrap());
}
