//! One layup section evaluation (docs/model.md §2.1): CLT, contour moments, stiffness and mass.
//! Target: under 100 µs, so dragging the ply angle re-solves within one frame.

use flutterscope::model::section::layup_input;
use flutterscope::physics::laminate::layup_section_props;
use flutterscope::preset::{ContourShape, Preset, ValidPreset};

fn main() {
    divan::main();
}

fn preset(shape: ContourShape) -> ValidPreset {
    let mut p = Preset::default();
    p.section.contour.shape = shape;
    p.section.ply_angle = Some(30.0);
    p.validate().unwrap()
}

/// The paper's Table 1 box (exact with four corners): the default layup section.
#[divan::bench]
fn layup_box(b: divan::Bencher) {
    let layup = layup_input(&preset(ContourShape::Box));
    b.bench(|| layup_section_props(divan::black_box(&layup)).unwrap());
}

/// Smooth contours: two polylines (512 and 1024 segments) Richardson-combined.
#[divan::bench(args = [ContourShape::Ellipse, ContourShape::Paper])]
fn layup_smooth(b: divan::Bencher, shape: ContourShape) {
    let layup = layup_input(&preset(shape));
    b.bench(|| layup_section_props(divan::black_box(&layup)).unwrap());
}
