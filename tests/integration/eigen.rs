//! Mode labels from the in-vacuo natural modes (docs/model.md §6), and still air, where the
//! aerodynamic states have no dynamics (§6.1).

use crate::stability::within;
use flutterscope::analysis::eigen::{analyse, analyse_system, linear_system, Stability};
use flutterscope::model::aero::{model_for, preset_stations};
use flutterscope::model::assemble;
use flutterscope::numeric::{decompose, Solver};
use flutterscope::physics::aero::{Kinematics, SteadyStates, StripEval, StripModel};
use flutterscope::physics::inflow::Station;
use flutterscope::physics::system::System;
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
        // An overdamped mode is one entry with both decay rates, never a second label.
        assert!(allowed.contains(&m.label), "label {}", m.label);
        assert!(plain.insert(m.label.clone()), "duplicate {}", m.label);
        if let Some(s2) = m.second_re {
            assert!(m.im == 0.0 && s2 <= m.re, "{}", m.label);
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

/// The still-air cases that used to hang (faer's deflation spinning on the defective cluster of
/// exactly zero aero roots), as `(preset, overrides)`.
fn still_air_cases() -> Vec<(&'static str, Vec<String>)> {
    let set = |o: &[&str]| o.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let rotor = ["operating.rotor_speed=0", "operating.wind_speed=0"];
    let mut cases = Vec::new();
    for (modes, stations) in [
        (1, &[25, 23, 27, 45, 52, 55, 63][..]),
        (5, &[28, 31, 44, 49, 50][..]),
    ] {
        for s in stations {
            let mut o = set(&rotor);
            o.extend(set(&["aero.model=onera"]));
            o.push(format!("structure.modes={modes}"));
            o.push(format!("aero.stations={s}"));
            cases.push(("liu2017", o));
        }
    }
    for s in 20..=61 {
        let mut o = set(&rotor);
        o.extend(set(&["aero.model=onera"]));
        o.push(format!("aero.stations={s}"));
        cases.push(("demo-blade", o));
    }
    for modes in [21, 29, 38] {
        let mut o = set(&["aero.model=onera", "operating.tunnel_speed=0"]);
        o.push(format!("structure.modes={modes}"));
        cases.push(("goland", o));
    }
    cases
}

/// Every still-air case answers on the solver its active block's size chooses, without a
/// fallback (a count, not a clock: the aerodynamic states were isolated, so the active block is
/// the structure alone), with finite results in which every aerodynamic state is an exactly zero
/// root reported apart with structural share 0, and the 4N structural states are the structural
/// roots.
fn check_still_air(name: &str, overrides: &[String]) -> Stability {
    let what = format!("{name} {overrides:?}");
    let p = Preset::load(name, overrides).unwrap();
    let ls = linear_system(&p).unwrap();
    let roots = decompose(&ls.a, true).unwrap();
    assert_ne!(roots.solver, Solver::Fallback, "{what}");
    let s = analyse_system(&ls).unwrap();
    for m in s.eigenvalues.iter().chain(&s.aero_lags) {
        let numbers = [
            m.re,
            m.im,
            m.frequency_hz,
            m.damping_ratio,
            m.structural_share,
        ];
        assert!(numbers.iter().all(|v| v.is_finite()), "{what}: {m:?}");
    }
    assert_eq!(s.aero_lags.len(), ls.n_aero, "{what}");
    for m in &s.aero_lags {
        assert!(
            m.re == 0.0 && m.im == 0.0,
            "{what}: {} at {}",
            m.label,
            m.re
        );
        assert_eq!(m.structural_share, 0.0, "{what}: {}", m.label);
    }
    let structural: usize = s
        .eigenvalues
        .iter()
        // An oscillating mode and an overdamped mode (two real roots) fill two dimensions each.
        .map(|m| {
            if m.im > 0.0 || m.second_re.is_some() {
                2
            } else {
                1
            }
        })
        .sum();
    assert_eq!(structural, 2 * ls.nq, "{what}");
    assert!(s.stable, "{what}");
    s
}

#[test]
fn still_air_onera_cases_answer_without_a_fallback() {
    // One guard against a hang for all of them (the bound that matters is the path above).
    within(600, || {
        for (name, overrides) in still_air_cases() {
            check_still_air(name, &overrides);
        }
    });
}

/// `name`'s aerodynamic model reduced to its apparent mass: no loads, no states.
#[derive(Debug)]
struct ApparentMassOnly(Box<dyn StripModel>);

impl StripModel for ApparentMassOnly {
    fn name(&self) -> &'static str {
        "apparent mass only"
    }
    fn states_per_station(&self) -> usize {
        0
    }
    fn apparent_mass(&self, s: &Station) -> [[f64; 3]; 3] {
        self.0.apparent_mass(s)
    }
    fn evaluate(&self, _: &Station, _: &Kinematics, _: &[f64], out: &mut StripEval, _: bool) {
        out.clear();
    }
    fn steady_states(&self, _: &Station, _: [f64; 3], _: &mut SteadyStates) {}
}

#[test]
fn still_air_structural_roots_are_the_structure_with_apparent_mass() {
    // At V0 = 0 every ONERA load vanishes (circulatory and stall loads ∝ V0 or V0², the lag
    // states' effect ∝ V0) except the apparent mass, which stays in the mass matrix. So the
    // structural roots are those of (M − M_a, C_s, K) at Ω = 0, not the bare in-vacuo (M, K):
    // the added air inertia lowers every natural frequency.
    for (name, overrides) in [
        (
            "goland",
            vec![
                "aero.model=onera",
                "operating.tunnel_speed=0",
                "structure.modes=21",
            ],
        ),
        (
            "liu2017",
            vec![
                "aero.model=onera",
                "operating.rotor_speed=0",
                "operating.wind_speed=0",
                "aero.stations=28",
                "structure.loss_factor=0",
            ],
        ),
    ] {
        let p = preset(name, &overrides);
        let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
        let still = check_still_air(name, &o);
        let model = Box::new(ApparentMassOnly(model_for(&p).unwrap()));
        let loaded = System::from_parts(
            std::sync::Arc::new(assemble(&p).unwrap()),
            preset_stations(&p),
            model,
        )
        .unwrap()
        .linearise()
        .unwrap();
        let loaded = analyse_system(&loaded).unwrap();
        let sorted = |s: &Stability| {
            let mut l: Vec<(f64, f64)> = s.eigenvalues.iter().map(|m| (m.im, m.re)).collect();
            l.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
            l
        };
        let (a, b) = (sorted(&still), sorted(&loaded));
        assert_eq!(a.len(), b.len(), "{name}");
        for (x, y) in a.iter().zip(&b) {
            let scale = x.0.hypot(x.1);
            assert!(
                (x.0 - y.0).abs() <= 1e-10 * scale && (x.1 - y.1).abs() <= 1e-10 * scale,
                "{name}: {x:?} vs {y:?}"
            );
        }
        // Undamped here, so the roots are ±iω: each frequency sits below its in-vacuo one.
        let natural = assemble(&p).unwrap().natural_modes().unwrap();
        let mut f: Vec<f64> = still.eigenvalues.iter().map(|m| m.frequency_hz).collect();
        f.sort_by(f64::total_cmp);
        assert_eq!(f.len(), natural.len(), "{name}");
        for (f, m) in f.iter().zip(&natural) {
            assert!(*f < m.frequency_hz, "{name} {}: {f} Hz", m.label);
        }
    }
}
