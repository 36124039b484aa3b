//! Real-blade aerodynamics in the system (docs/model.md §12.5): the blade-element strip loads
//! in flap, edge and twist on a tabulated structure.

use flutterscope::formats::airfoil::{read_airfoil, PolarColumns};
use flutterscope::physics::aero::blade_element::{
    BladeElement, ElementSection, StallDynamics, Unsteadiness,
};
use flutterscope::physics::aero::polar::Polar;
use flutterscope::physics::inflow::{stations, OperatingPoint};
use flutterscope::physics::structure::for_preset;
use flutterscope::physics::system::System;
use flutterscope::preset::{Inflow, Preset};
use nalgebra::DVector;
use std::path::Path;
use std::sync::Arc;

/// The NREL 5MW DU21 polar, as its file gives it.
fn du21() -> Arc<Polar> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/blades/nrel5mw/Airfoils/DU21_A17.dat");
    let file = read_airfoil(&path, PolarColumns::default()).unwrap();
    let t = &file.tables[0];
    let rad: Vec<f64> = t.alpha_deg.iter().map(|a| a.to_radians()).collect();
    Arc::new(
        Polar::new(
            rad,
            t.cl.clone(),
            t.cd.clone(),
            t.cm.clone().unwrap(),
            "DU21",
        )
        .unwrap(),
    )
}

/// The NREL 5MW structure (12 modes at 12.1 rpm) with DU21 strips at 11.4 m/s, a uniform
/// induction of 0.3 and a twist that puts the outboard stations near 6° and the root in stall.
fn nrel_system(unsteadiness: Unsteadiness) -> System {
    let p = Preset::load("nrel5mw", &[]).unwrap();
    let structure = for_preset(&p).unwrap();
    let op = OperatingPoint {
        wind: 11.4,
        induction: 0.3,
        omega: p.omega(),
        tunnel: 0.0,
        pitch: 0.0,
        twist_root: 13f64.to_radians(),
        twist_tip: 0.0,
        inflow: Inflow::Local,
    };
    let at = stations(structure.length(), structure.hub_radius(), &op, 12);
    let polar = du21();
    let sections = at
        .iter()
        .map(|s| ElementSection {
            chord: 4.6 - 3.0 * s.x / structure.length(),
            ac_ahead: 0.1,
            polar: Arc::clone(&polar),
        })
        .collect();
    let model = BladeElement {
        sections,
        air_density: 1.225,
        unsteadiness,
    };
    System::from_parts(structure, at, Box::new(model)).unwrap()
}

/// Largest relative column mismatch between the analytic Jacobian at `x` and central
/// differences of the right-hand side.
fn jacobian_mismatch(system: &System, x: &DVector<f64>) -> f64 {
    let a = system.jacobian(x);
    let mut worst: f64 = 0.0;
    for j in 0..system.dim() {
        // Modal coordinates of a mass-normalised basis are O(1) and larger: a step of 1e-5 keeps
        // the round-off of rhs/h well below the truncation error.
        let h = 1e-5 * x[j].abs().max(1.0);
        let mut xp = x.clone();
        let mut xm = x.clone();
        xp[j] += h;
        xm[j] -= h;
        let numeric = (system.rhs(&xp) - system.rhs(&xm)) / (2.0 * h);
        let analytic = a.column(j);
        let scale = numeric.norm().max(analytic.norm()).max(1e-9);
        worst = worst.max((analytic - &numeric).norm() / scale);
    }
    worst
}

#[test]
fn the_state_matrix_is_the_jacobian_of_the_nonlinear_right_hand_side() {
    let onera = Unsteadiness::Onera(StallDynamics {
        a: [0.3, 0.25, 0.25],
        r: [0.0324, 0.0484, 0.0484],
    });
    for unsteadiness in [Unsteadiness::QuasiSteady, Unsteadiness::Theodorsen, onera] {
        let system = nrel_system(unsteadiness);
        let x_eq = system.equilibrium().unwrap();
        // Away from equilibrium too: every coordinate, rate and state moved.
        let wobble = DVector::from_fn(system.dim(), |i, _| 1e-3 * ((i as f64) * 0.7).sin());
        for x in [x_eq.clone(), &x_eq + wobble] {
            let worst = jacobian_mismatch(&system, &x);
            assert!(worst < 1e-6, "{unsteadiness:?}: {worst:e}");
        }
    }
}

#[test]
fn every_mode_is_damped_by_the_air_flap_far_more_than_edge() {
    let system = nrel_system(Unsteadiness::QuasiSteady);
    let nq = system.nq();
    let x_eq = system.equilibrium().unwrap();
    let a = system.jacobian(&x_eq);
    // Aerodynamic damping on each mode: the diagonal of ∂q̈/∂q̇ less the structural part. Every
    // mode with edge motion gets some, and the flap modes much more than the edge modes.
    let structural = system.structure().damping();
    let natural = system.structure().natural_modes().unwrap();
    let mut by_label = std::collections::HashMap::new();
    for (k, mode) in natural.iter().enumerate() {
        let aero = -(a[(nq + k, nq + k)] + structural[(k, k)]);
        assert!(aero > 0.0, "{}: aerodynamic damping {aero}", mode.label);
        by_label.insert(mode.label.clone(), aero);
    }
    assert!(by_label["flap 1"] > 5.0 * by_label["edge 1"]);
}
