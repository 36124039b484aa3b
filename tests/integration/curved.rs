//! The blade on a curved reference axis (docs/model.md §11.9): a uniform arc twisted at its tip
//! against Castigliano's closed form (prebend and sweep, Euler–Bernoulli and shear-deformable),
//! the centrifugal pull on a prebent beam against the moment of its radial loads, the full
//! straightening at high speed, and what the IEA 15MW's 4 m of prebend does to its modes and
//! its operating point.

use flutterscope::model::blade::blade_structure;
use flutterscope::model::operating::deflected_point;
use flutterscope::physics::blade::axis::CurvedAxis;
use flutterscope::physics::blade::fem::{assemble, BladeMatrices, Mesh};
use flutterscope::physics::blade::modal::BladeMode;
use flutterscope::physics::blade::{BeamSection, BladeTable, ShearFlexibility};
use flutterscope::preset::{Preset, ValidPreset};
use nalgebra::DVector;

const LENGTH: f64 = 10.0;
const MASS: f64 = 50.0;
const EI_FLAP: f64 = 2.0e6;
const EI_EDGE: f64 = 6.0e6;
const GJ: f64 = 1.0e6;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// A uniform beam whose reference axis is `offset(z)` (`[prebend, sweep]`), sampled every
/// millimetre; shear-deformable with `ga` when given.
fn uniform_on(offset: impl Fn(f64) -> [f64; 2], ga: Option<f64>, hub: f64) -> BladeTable {
    let section = |z: f64| BeamSection {
        z,
        mass: MASS,
        cg: [0.0, 0.0],
        inertia: [0.5, 2.0, 0.0],
        ei_flap: EI_FLAP,
        ei_edge: EI_EDGE,
        ei_cross: 0.0,
        gj: GJ,
        flap_twist: 0.0,
        edge_twist: 0.0,
        twist: 0.0,
        shear_centre: [0.0, 0.0],
        tension_centre: [0.0, 0.0],
        shear: ga.map_or(ShearFlexibility::RIGID, |ga| ShearFlexibility {
            strain: [1.0 / ga, 1.0 / ga, 0.0],
            coupling: [0.0; 6],
        }),
    };
    let points: Vec<(f64, [f64; 2])> = (0..=10_000)
        .map(|k| {
            let z = LENGTH * k as f64 / 10_000.0;
            (z, offset(z))
        })
        .collect();
    BladeTable::new("uniform arc", hub, vec![section(0.0), section(LENGTH)])
        .unwrap()
        .with_axis(CurvedAxis::new("uniform arc", &points).unwrap())
}

/// The tip's twist under a torque `torque` about the tip's tangent, at rest.
fn tip_twist_under_torque(m: &BladeMatrices, torque: f64) -> f64 {
    let tip = m.shear_centre_at(LENGTH).unwrap();
    let f = tip.point_load(m.k0.nrows(), 0.0, 0.0, torque);
    let q = m.k0.clone().lu().solve(&f).unwrap();
    tip.motion(&q).twist
}

/// A cantilever arc of constant curvature `k` twisted by `T` at its tip: the moment is `T`
/// along the tip's tangent everywhere, so a section at angle `Δ = k (L − z)` from the tip
/// carries torsion `T cos Δ` and bending `T sin Δ`, and by Castigliano the tip turns by
/// `T ∫ cos²Δ / GJ + sin²Δ / EI`, EI the stiffness for bending out of the arc's plane.
fn castigliano_tip_twist(k: f64, torque: f64, ei: f64) -> f64 {
    let half = LENGTH / 2.0;
    let wave = (2.0 * k * LENGTH).sin() / (4.0 * k);
    torque * ((half + wave) / GJ + (half - wave) / ei)
}

#[test]
fn a_uniform_arc_twisted_at_its_tip_turns_as_castigliano_says() {
    // 0.8 rad between root and tip tangents: a strong curvature, so that the coupling carries a
    // third of the compliance and a wrong sign or factor shows at once.
    let k = 0.08;
    let torque = 1.0e3;
    for (plane, offset, ei) in [
        ("prebend", [1.0, 0.0], EI_EDGE),
        ("sweep", [0.0, 1.0], EI_FLAP),
    ] {
        for ga in [None, Some(5.0e7)] {
            let table = uniform_on(
                |z| [offset[0] * 0.5 * k * z * z, offset[1] * 0.5 * k * z * z],
                ga,
                0.0,
            );
            let m = assemble(&table, &Mesh::following(&table, 200), 0.0).unwrap();
            let got = tip_twist_under_torque(&m, torque);
            let want = castigliano_tip_twist(k, torque, ei);
            let straight = torque * LENGTH / GJ;
            assert!(
                rel(got, want) < 1e-4,
                "{plane}, shear {ga:?}: tip twist {got:e} rad, closed form {want:e} \
                 (straight beam {straight:e})"
            );
            assert!(
                rel(want, straight) > 0.05,
                "{plane}: the test must see the curve"
            );
        }
    }
}

/// The flap of the tip per Ω² under the centrifugal load of a prebent beam, at first order in
/// Ω² (the straight beam's stiffness).
fn first_order_straightening(m: &BladeMatrices) -> f64 {
    let q = m.k0.clone().lu().solve(&m.centrifugal_load()).unwrap();
    m.shear_centre_at(LENGTH).unwrap().motion(&q).flap
}

#[test]
fn rotation_pulls_a_prebent_beam_toward_the_rotor_plane_by_its_radial_loads_moment() {
    // Prebend c z²: each element's pull m Ω² r, radial, acts off the axis of the sections
    // inboard of it, bending them by M(z) = m Ω² ∫_z^L r(s) (x₀(s) − x₀(z)) ds toward the rotor
    // plane; the tip moves by −∫ (L − z) M(z) / EI dz.
    let (c, hub) = (0.02, 3.0);
    let table = uniform_on(|z| [c * z * z, 0.0], None, hub);
    let m = assemble(&table, &Mesh::following(&table, 100), 0.0).unwrap();
    let moment = |z: f64| {
        let cubes = (LENGTH.powi(3) - z.powi(3)) / 3.0 - z * z * (LENGTH - z);
        let fourths = (LENGTH.powi(4) - z.powi(4)) / 4.0 - z * z * (LENGTH * LENGTH - z * z) / 2.0;
        MASS * c * (hub * cubes + fourths)
    };
    // Simpson on 2000 intervals: the integrand is a polynomial of degree 5.
    let n = 2000;
    let h = LENGTH / n as f64;
    let want = -(0..=n)
        .map(|i| {
            let z = i as f64 * h;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            w * (LENGTH - z) * moment(z) / EI_FLAP
        })
        .sum::<f64>()
        * h
        / 3.0;
    let got = first_order_straightening(&m);
    assert!(
        rel(got, want) < 1e-6,
        "tip per Ω²: {got:e} m, moments {want:e} m"
    );

    // At a speed where the tension dwarfs the bending stiffness, the beam straightens fully:
    // the tip comes back to the pitch axis.
    let prebend = c * LENGTH * LENGTH;
    let mut left = prebend;
    for omega in [1.0, 10.0, 100.0, 1000.0] {
        let k = &m.k0 + &m.k_omega * (omega * omega);
        let q = k
            .lu()
            .solve(&(m.centrifugal_load() * (omega * omega)))
            .unwrap();
        let tip = prebend + m.shear_centre_at(LENGTH).unwrap().motion(&q).flap;
        assert!(
            tip < left && tip > 0.0,
            "Ω = {omega}: tip {tip} m after {left} m"
        );
        left = tip;
    }
    assert!(left < 1e-3 * prebend, "tip at Ω = 1000 rad/s: {left} m");
}

#[test]
fn a_straight_axis_loads_and_bends_nothing() {
    let table = uniform_on(|_| [0.0, 0.0], Some(5.0e7), 3.0);
    assert!(table.axis.is_straight());
    let m = assemble(&table, &Mesh::following(&table, 40), 0.3).unwrap();
    assert_eq!(m.centrifugal_load(), DVector::zeros(m.k0.nrows()));
    let plain = assemble(
        &table.clone().with_axis(CurvedAxis::straight()),
        &Mesh::following(&table, 40),
        0.3,
    )
    .unwrap();
    assert_eq!(m.k0, plain.k0);
}

fn modes_of(p: &ValidPreset) -> Vec<BladeMode> {
    blade_structure(p)
        .unwrap()
        .unwrap()
        .modes(p.omega())
        .unwrap()
}

fn frequency(modes: &[BladeMode], family: usize, number: usize) -> f64 {
    modes
        .iter()
        .filter(|m| m.family().index() == family)
        .nth(number - 1)
        .unwrap()
        .frequency_hz
}

/// The IEA 15MW's 4 m of prebend (its AeroDyn `BlCrvAC`) in the structure, measured against
/// the same blade straight (docs/model.md §11.9): the curve couples edge bending with torsion,
/// which pushes the second edge mode down and the first torsion mode up, and rotation pulls the
/// blade 0.94 m toward the rotor plane at rated, where its twist eases by 0.42°.
#[test]
fn the_iea15mw_prebend_moves_its_edge_and_torsion_modes_and_its_tip() {
    let curved = Preset::load("iea15mw", &[]).unwrap();
    let straight = Preset::load("iea15mw", &["structure.curved=false".into()]).unwrap();
    let (c, s) = (modes_of(&curved), modes_of(&straight));
    let [flap, edge, torsion] = [0, 1, 2];
    for (name, family, number, curved_hz, straight_hz) in [
        ("flap 1", flap, 1, 0.53067, 0.53028),
        ("edge 1", edge, 1, 0.69786, 0.70525),
        ("edge 2", edge, 2, 2.1490, 2.2040),
        ("torsion 1", torsion, 1, 4.2829, 4.1467),
    ] {
        let (got_c, got_s) = (frequency(&c, family, number), frequency(&s, family, number));
        assert!(rel(got_c, curved_hz) < 1e-4, "{name} curved: {got_c} Hz");
        assert!(
            rel(got_s, straight_hz) < 1e-4,
            "{name} straight: {got_s} Hz"
        );
    }
    let tip = |p: &ValidPreset| deflected_point(p).unwrap().1;
    let ([twist_c, flap_c, _], [twist_s, flap_s, _]) = (tip(&curved), tip(&straight));
    let pulled = flap_c - flap_s;
    assert!(
        (pulled - 0.935).abs() < 0.01,
        "tip pulled downwind by {pulled} m"
    );
    let eased = (twist_s - twist_c).to_degrees();
    assert!((eased - 0.434).abs() < 0.01, "tip twist eased by {eased}°");
}
