//! Mode labels from the in-vacuo natural modes (docs/model.md §6).

use flutterscope::analysis::eigen::{analyse, SECOND_ROOT_SUFFIX};
use flutterscope::physics::structure::assemble;
use flutterscope::preset::{Preset, ValidPreset};
use std::collections::HashSet;

fn preset(name: &str, overrides: &[&str]) -> ValidPreset {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &o).unwrap()
}

#[test]
fn paper_blade_labels_name_existing_modes_once() {
    // liu2017: quasi-steady, 60 rpm, N = 5. The torsion roots sit far from the in-vacuo torsion
    // modes (aerodynamic torsional stiffness ≈ 30× structural); a torsion-share count used to
    // call them `flap 6`, `flap 7`.
    let p = preset("liu2017", &[]);
    assert_eq!(p.structure.modes, 5);
    let s = analyse(&p).unwrap();
    let allowed: HashSet<String> = (1..=5)
        .flat_map(|k| [format!("flap {k}"), format!("torsion {k}")])
        .collect();
    let mut plain = HashSet::new();
    for m in &s.eigenvalues {
        match m.label.strip_suffix(SECOND_ROOT_SUFFIX) {
            // The second real root of an overdamped mode: only next to its real partner.
            Some(base) => {
                assert!(allowed.contains(base) && m.im == 0.0, "{}", m.label);
                assert!(s
                    .eigenvalues
                    .iter()
                    .any(|o| o.label == base && o.im == 0.0 && o.re >= m.re));
            }
            None => {
                assert!(allowed.contains(&m.label), "label {}", m.label);
                assert!(plain.insert(m.label.clone()), "duplicate {}", m.label);
            }
        }
    }
    // Every natural mode is accounted for.
    assert_eq!(plain, allowed);
    // The five lowest roots are the flap modes in order.
    let mut by_freq: Vec<_> = s.eigenvalues.iter().filter(|m| m.im > 0.0).collect();
    by_freq.sort_by(|a, b| a.im.total_cmp(&b.im));
    let first: Vec<&str> = by_freq[..5].iter().map(|m| m.label.as_str()).collect();
    assert_eq!(first, ["flap 1", "flap 2", "flap 3", "flap 4", "flap 5"]);
}

#[test]
fn structure_alone_takes_the_natural_labels_in_frequency_order() {
    for (name, extra) in [
        ("liu2017", "structure.loss_factor=0"),
        ("goland", "structure.loss_factor=0.02"),
    ] {
        let p = preset(name, &["aero.model=none", extra]);
        let natural = assemble(&p).unwrap().natural_modes().unwrap();
        let s = analyse(&p).unwrap();
        let mut roots = s.eigenvalues.clone();
        roots.sort_by(|a, b| a.re.hypot(a.im).total_cmp(&b.re.hypot(b.im)));
        let labels: Vec<&str> = roots.iter().map(|m| m.label.as_str()).collect();
        let expected: Vec<&str> = natural.iter().map(|m| m.label.as_str()).collect();
        assert_eq!(labels, expected, "{name}");
    }
}

#[test]
fn goland_flutter_mode_is_a_natural_mode() {
    // Bending–torsion flutter: the root going unstable is one of the two coalescing modes,
    // flap 1 and torsion 1, and keeps a plain natural-mode label.
    let p = preset("goland", &["operating.tunnel_speed=145"]);
    let s = analyse(&p).unwrap();
    assert!(!s.stable);
    let c = s.critical().unwrap();
    assert!(c.im > 0.0 && c.structural_share > 0.5);
    assert!(c.label == "flap 1" || c.label == "torsion 1", "{}", c.label);
    let b = flutterscope::analysis::flutter::flutter_boundary(
        &preset("goland", &[]),
        "operating.tunnel_speed",
        110.0,
        160.0,
        6,
    )
    .unwrap();
    let mode = b.mode.unwrap();
    assert!(mode == "flap 1" || mode == "torsion 1", "{mode}");
}

#[test]
fn many_identical_stations_still_give_eigenvectors() {
    // With tip inflow every ONERA station sees the same speed, so 32 stations repeat each lag and
    // stall root 32 times; inverse iteration inside such clusters used to stall just above its
    // tolerance and the solve failed ("non-finite eigenvectors"). Every right and left vector
    // must now satisfy its eigen-equation, and the structural roots must not depend on the
    // station count beyond the quadrature's own convergence.
    use flutterscope::analysis::eigen::linear_system;
    use flutterscope::numeric::eigen_decomposition;
    let p = preset("liu2017", &["aero.model=onera", "aero.stations=32"]);
    let ls = linear_system(&p).unwrap();
    let a = ls.a.map(|v| nalgebra::Complex::new(v, 0.0));
    let roots = eigen_decomposition(&ls.a).unwrap();
    let scale = ls.a.norm();
    for (k, lambda) in roots.values.iter().enumerate() {
        let x = roots.vectors.column(k);
        let l = roots.left.column(k);
        let right = (&a * x - x * *lambda).norm() / x.norm();
        let left = (l.adjoint() * &a - l.adjoint() * *lambda).norm() / l.norm();
        assert!(
            right <= 1e-7 * scale,
            "right residual {right:e} at {lambda}"
        );
        assert!(left <= 1e-7 * scale, "left residual {left:e} at {lambda}");
    }
    let s32 = analyse(&p).unwrap();
    let s24 = analyse(&preset(
        "liu2017",
        &["aero.model=onera", "aero.stations=24"],
    ))
    .unwrap();
    let flap1 = |s: &flutterscope::analysis::eigen::Stability| {
        s.eigenvalues
            .iter()
            .find(|m| m.label == "flap 1")
            .unwrap()
            .re
    };
    assert!((flap1(&s32) / flap1(&s24) - 1.0).abs() < 1e-3);
}
