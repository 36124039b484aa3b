//! Structure assembly plus natural frequencies (docs/model.md §3–§4) for N = 5, 10, 20 modes per field.
//! Target: N = 5 under 50 µs in release, so every explorer key press re-solves at once.
//!
//! Run: `cargo bench --bench structure`.

use flutterscope::model::assemble;
use flutterscope::preset::{Preset, ValidPreset};

fn main() {
    divan::main();
}

/// The paper's blade at its operating point (60 rpm: the centrifugal terms are live).
fn paper_blade(n: usize, form: &str) -> ValidPreset {
    Preset::load(
        "liu2017",
        &[
            format!("structure.modes={n}"),
            format!("structure.form={form}"),
        ],
    )
    .unwrap()
}

/// Weak form (default): Cholesky reduction + symmetric eigensolver, with mode shapes and labels.
#[divan::bench(args = [5, 10, 20])]
fn weak_assemble_and_modes(b: divan::Bencher, n: usize) {
    let p = paper_blade(n, "weak");
    b.bench(|| {
        let s = assemble(divan::black_box(&p)).unwrap();
        s.natural_modes().unwrap()
    });
}

/// Strong form (the paper's): non-symmetric, general real eigensolver with eigenvectors.
#[divan::bench(args = [5, 10, 20])]
fn strong_assemble_and_modes(b: divan::Bencher, n: usize) {
    let p = paper_blade(n, "strong");
    b.bench(|| {
        let s = assemble(divan::black_box(&p)).unwrap();
        s.natural_modes().unwrap()
    });
}

/// Assembly alone (matrices, ω1 and damping), weak form.
#[divan::bench(args = [5, 10, 20])]
fn weak_assemble_only(b: divan::Bencher, n: usize) {
    let p = paper_blade(n, "weak");
    b.bench(|| assemble(divan::black_box(&p)).unwrap());
}
