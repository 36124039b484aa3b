//! The pitch-range basis of a tabulated blade (docs/model.md §11.8): its Fourier terms rebuild
//! the assembled matrices at any pitch, and its Ritz modes at pitches across 0…90° and rotor
//! speeds from rest to the top of the range agree with a full rebuild at that pitch.

use flutterscope::model::blade::blade_structure;
use flutterscope::physics::blade::fem::assemble;
use flutterscope::physics::blade::modal::ModalBlade;
use flutterscope::preset::Preset;

/// Relative frequency error allowed between the pitch-range basis and a full rebuild. The Ritz
/// error of an eigenvalue is the square of its vector's distance from the basis; 1e-5 in
/// frequency is far below what a damping ratio or a tracked name can see (the sweep's CSV moves
/// in the sixth digit at most) and a hundredth of the FE mesh's own discretisation error
/// (docs/model.md §11.4).
const FREQUENCY_TOLERANCE: f64 = 1e-5;
/// `1 − MAC` allowed between a mode shape on the basis and the rebuild's.
const SHAPE_TOLERANCE: f64 = 1e-5;

/// Every pitch from 0 to 90° in 7.5° steps (the snapshots at 0, 30, 60, 90°, and the points
/// between) at rest, half and full speed of the basis' range.
#[test]
fn ritz_modes_across_the_pitch_range_match_a_full_rebuild() {
    for name in ["iea15mw", "nrel5mw"] {
        let base = Preset::load(name, &[]).unwrap();
        let top = base.view.rotor_speed_max;
        let (mut worst_f, mut worst_mac) = (0.0f64, 0.0f64);
        for step in 0..=12 {
            let pitch = 7.5 * step as f64;
            let p = base
                .with("operating.pitch", pitch)
                .unwrap()
                .with("operating.rotor_speed", top)
                .unwrap();
            let built = blade_structure(&p).unwrap().unwrap();
            let g = &built.modal.geometry;
            let matrices = assemble(&g.table, &g.mesh, pitch.to_radians()).unwrap();
            let omega_top = top * std::f64::consts::PI / 30.0;
            let full =
                ModalBlade::new(matrices.clone(), &[0.0, omega_top], built.count + 8).unwrap();
            for omega in [0.0, 0.5 * omega_top, omega_top] {
                let ritz = built.modal.modes(omega, built.count).unwrap();
                let exact = full.modes(omega, built.count).unwrap();
                for (r, e) in ritz.iter().zip(&exact) {
                    let df = (r.frequency_hz - e.frequency_hz).abs() / e.frequency_hz;
                    let m_e = &matrices.mass * &e.shape;
                    let dot = r.shape.dot(&m_e);
                    let mac =
                        dot * dot / (r.shape.dot(&(&matrices.mass * &r.shape)) * e.shape.dot(&m_e));
                    worst_f = worst_f.max(df);
                    worst_mac = worst_mac.max(1.0 - mac);
                    assert!(
                        df <= FREQUENCY_TOLERANCE && 1.0 - mac <= SHAPE_TOLERANCE,
                        "{name} at pitch {pitch}°, Ω = {omega} rad/s: {} Hz vs {} Hz, 1 − MAC {:e}",
                        r.frequency_hz,
                        e.frequency_hz,
                        1.0 - mac
                    );
                }
            }
        }
        let size = blade_structure(&base).unwrap().unwrap().modal.basis_size();
        eprintln!(
            "{name} (basis {size}): largest relative frequency error {worst_f:.2e}, largest 1 − MAC {worst_mac:.2e}"
        );
    }
}
