//! docs/model.md §8 validation targets, rows 1–5: the paper's Table 2 (AC and Present), the
//! effective-stiffness cantilever, uncoupled torsion and the rotating uniform cantilever.

use flutterscope::commands::reproduce::{TABLE2_AC, TABLE2_PRESENT};
use flutterscope::model::assemble;
use flutterscope::model::section_properties;
use flutterscope::physics::basis::bending_root;
use flutterscope::physics::section::TABLE1_ANGLES;
use flutterscope::physics::structure::{ac_frequency_hz, NaturalMode};
use flutterscope::preset::{Preset, ValidPreset};
use std::f64::consts::PI;

/// The paper's blade for its §4.1 free-vibration check: Ω = 0, a_s = 0, I = 2.3e-6 ≤ 1e-4.
fn paper_blade(angle: f64, form: &str, n: usize) -> ValidPreset {
    let p = Preset::load(
        "liu2017",
        &[
            "operating.rotor_speed=0".into(),
            "structure.loss_factor=0".into(),
            "section.source=table".into(),
            format!("section.ply_angle={angle}"),
            format!("structure.form={form}"),
            format!("structure.modes={n}"),
        ],
    )
    .unwrap();
    assert!(p.section.polar_inertia <= 1e-4);
    p
}

fn flap_modes(p: &ValidPreset) -> Vec<NaturalMode> {
    assemble(p)
        .unwrap()
        .natural_modes()
        .unwrap()
        .into_iter()
        .filter(|m| m.label.starts_with("flap"))
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// §8 row 1: Eq. 13 at λ = i k₁, lower root, corrected units, m = 0.06377: every entry ±0.0001 Hz.
#[test]
fn table2_ac_rows_to_a_tenth_of_a_millihertz() {
    for (k, &angle) in TABLE1_ANGLES.iter().enumerate() {
        let p = paper_blade(angle, "weak", 5);
        assert_eq!(p.section.mass_per_length, 0.06377);
        let s = section_properties(&p).unwrap();
        for n in 1..=5 {
            let ours = ac_frequency_hz(&s, p.blade.length, n);
            let paper = TABLE2_AC[n - 1][k];
            assert!(
                (ours - paper).abs() <= 1e-4,
                "AC mode {n} at {angle}°: ours {ours:.6} vs paper {paper}"
            );
        }
    }
}

/// §8 row 2: the strong form with N = 5 reproduces Table 2 "Present" within 1 %.
#[test]
fn table2_present_rows_by_strong_form_within_one_percent() {
    let mut worst: f64 = 0.0;
    for (k, &angle) in TABLE1_ANGLES.iter().enumerate() {
        let flaps = flap_modes(&paper_blade(angle, "strong", 5));
        for n in 1..=5 {
            let (ours, paper) = (flaps[n - 1].frequency_hz, TABLE2_PRESENT[n - 1][k]);
            worst = worst.max(rel(ours, paper));
            assert!(
                rel(ours, paper) <= 0.01,
                "mode {n} at {angle}°: strong {ours:.5} vs paper {paper}"
            );
        }
    }
    // The strong form is what the paper computed: it must not be a loose match everywhere.
    assert!(worst > 1e-4, "suspiciously exact: {worst}");
}

/// `ω_n = (β_nL)² √((C33 − C23²/C22)/(mL⁴))`, the cantilever with twist condensed out (I → 0).
fn effective_stiffness_hz(p: &ValidPreset, n: usize) -> f64 {
    let s = section_properties(p).unwrap();
    let l = p.blade.length;
    let ei = s.c33 - s.c23 * s.c23 / s.c22;
    bending_root(n).powi(2) * (ei / (s.m * l.powi(4))).sqrt() / (2.0 * PI)
}

/// §8 row 3: weak form, N ≥ 8, Ω = 0: the effective-stiffness cantilever within 0.5 %.
#[test]
fn weak_form_converges_to_effective_stiffness_cantilever() {
    for n_modes in [8, 12] {
        for &angle in &TABLE1_ANGLES {
            let p = paper_blade(angle, "weak", n_modes);
            let flaps = flap_modes(&p);
            for n in 1..=5 {
                let (ours, exact) = (flaps[n - 1].frequency_hz, effective_stiffness_hz(&p, n));
                assert!(
                    rel(ours, exact) <= 0.005,
                    "N={n_modes} mode {n} at {angle}°: weak {ours:.6} vs {exact:.6}"
                );
            }
        }
    }
}

/// The weak form is variational: its frequencies decrease monotonically with N toward the
/// effective-stiffness values (a check that the 0.5 % above is convergence, not luck).
#[test]
fn weak_form_frequencies_decrease_with_n() {
    let f = |n| flap_modes(&paper_blade(30.0, "weak", n))[0].frequency_hz;
    let seq: Vec<f64> = [4, 6, 8, 12, 16].iter().map(|&n| f(n)).collect();
    assert!(
        seq.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-12)),
        "{seq:?}"
    );
    let exact = effective_stiffness_hz(&paper_blade(30.0, "weak", 16), 1);
    assert!(rel(seq[4], exact) < rel(seq[0], exact));
}

/// A direct-stiffness blade from TOML text.
fn direct_blade(extra: &str) -> ValidPreset {
    let text = format!(
        "[section]\nsource = \"direct\"\nka2 = 0.0\nkm1_2 = 0.0\nkm2_2 = 0.0\ncg_offset = 0.0\n{extra}"
    );
    Preset::from_toml(&text, "test blade", &[]).unwrap()
}

/// §8 row 4: with C23 = 0 the sines are the exact torsion modes: `ω_j = (2j−1)π/(2L) √(C22/I)`.
#[test]
fn uncoupled_torsion_is_exact() {
    for form in ["weak", "strong"] {
        let p = direct_blade(&format!(
            "c22 = 3.0\nc23 = 0.0\nc33 = 2.0\npolar_inertia = 0.01\nmass_per_length = 1.5\n\
             [blade]\nlength = 2.0\n[operating]\nrotor_speed = 0.0\n\
             [structure]\nmodes = 6\nform = \"{form}\"\nloss_factor = 0.0\n"
        ));
        let modes = assemble(&p).unwrap().natural_modes().unwrap();
        let torsion: Vec<&NaturalMode> = modes
            .iter()
            .filter(|m| m.label.starts_with("torsion"))
            .collect();
        assert_eq!(torsion.len(), 6);
        for (j, m) in torsion.iter().enumerate() {
            let exact = (2 * j + 1) as f64 * PI / (2.0 * 2.0) * (3.0f64 / 0.01).sqrt() / (2.0 * PI);
            assert!(
                rel(m.frequency_hz, exact) <= 1e-6,
                "{form} torsion {}: {} vs {exact}",
                j + 1,
                m.frequency_hz
            );
            assert!(m.torsion_share > 1.0 - 1e-12);
        }
    }
}

/// §8 row 5: the rotating uniform cantilever (no hub), `ω̄ = ω√(mL⁴/EI)` against `Ω̄`.
#[test]
fn rotating_uniform_cantilever_table() {
    const TABLE: [(f64, [f64; 3]); 7] = [
        (0.0, [3.5160, 22.0345, 61.6972]),
        (2.0, [4.1373, 22.6149, 62.2732]),
        (4.0, [5.5850, 24.2733, 63.9668]),
        (6.0, [7.3604, 26.8091, 66.6839]),
        (8.0, [9.2568, 29.9954, 70.2930]),
        (10.0, [11.2023, 33.6404, 74.6493]),
        (12.0, [13.1702, 37.6031, 79.6145]),
    ];
    // m = EI = L = 1, so ω̄ = ω and Ω̄ = Ω (rad/s). Torsion is decoupled (C23 = 0) and stiff.
    for n_modes in [8, 10] {
        for (omega_bar, expected) in TABLE {
            let rpm = omega_bar * 30.0 / PI;
            let p = direct_blade(&format!(
                "c22 = 1.0e4\nc23 = 0.0\nc33 = 1.0\npolar_inertia = 0.01\nmass_per_length = 1.0\n\
                 [blade]\nlength = 1.0\nhub_radius = 0.0\n[operating]\nrotor_speed = {rpm}\n\
                 [structure]\nmodes = {n_modes}\nloss_factor = 0.0\n"
            ));
            let flaps = flap_modes(&p);
            for (k, &e) in expected.iter().enumerate() {
                let ours = 2.0 * PI * flaps[k].frequency_hz;
                assert!(
                    rel(ours, e) <= 5e-4,
                    "N={n_modes} Ω̄={omega_bar} mode {}: {ours:.5} vs {e}",
                    k + 1
                );
            }
        }
    }
}
