//! One cross-section analysis by 2-D finite elements (docs/model.md §11.11): a composite box of a
//! blade spar's proportions, meshed four elements through its walls, about as many elements as
//! a blade section's layup mesh.

use flutterscope::physics::blade::windio::LayupBlade;
use flutterscope::physics::cross_section::mesh::graded;
use flutterscope::physics::cross_section::{analyse, Mesh, Orthotropic, Ply};
use std::f64::consts::{FRAC_PI_2, PI};

fn main() {
    divan::main();
}

/// A glass-fibre box of outer `0.5 × 0.2` m with 10 mm walls, `[θ]` above the mid-plane and
/// `[−θ]` below; `along` elements per metre of wall.
fn spar_box(along: f64) -> Mesh {
    let (b, h, t, through) = (0.5, 0.2, 0.01, 4);
    let n = |len: f64| (len * along).round() as usize;
    let xs = graded(
        &[-b / 2.0, -b / 2.0 + t, b / 2.0 - t, b / 2.0],
        &[through, n(b - 2.0 * t), through],
    );
    let ys = graded(
        &[-h / 2.0, -h / 2.0 + t, 0.0, h / 2.0 - t, h / 2.0],
        &[through, n(h / 2.0 - t), n(h / 2.0 - t), through],
    );
    let glass = Orthotropic {
        e1: 41e9,
        e2: 14e9,
        e3: 14e9,
        g12: 5e9,
        g13: 5e9,
        g23: 5e9,
        nu12: 0.28,
        nu13: 0.28,
        nu23: 0.4,
        rho: 1900.0,
    };
    let theta = 20f64.to_radians();
    Mesh::grid(&xs, &ys, vec![glass], |c| {
        let wall = c[0].abs() > b / 2.0 - t || c[1].abs() > h / 2.0 - t;
        let orientation = if c[1] > h / 2.0 - t {
            PI
        } else if c[1] < -h / 2.0 + t {
            0.0
        } else {
            FRAC_PI_2 * c[0].signum()
        };
        wall.then_some(Ply {
            material: 0,
            fibre_angle: theta * c[1].signum(),
            orientation,
        })
    })
    .unwrap()
}

/// Elements per metre of wall: 330 gives 1 808 elements (2 260 nodes, 6 780 warping unknowns),
/// 660 gives 3 544 elements (4 430 nodes, 13 290 unknowns).
#[divan::bench(args = [330.0, 660.0])]
fn composite_box(b: divan::Bencher, along: f64) {
    let mesh = spar_box(along);
    b.bench(|| analyse(divan::black_box(&mesh), [0.0, 0.0]).unwrap());
}

/// Every station of the IEA 15MW from its WindIO layup (50 sections, about 1 000–1 700
/// elements each), meshed and analysed in parallel on all cores. Target < 50 ms on two cores.
#[divan::bench(sample_count = 10)]
fn iea15mw_blade_from_its_layup(b: divan::Bencher) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades/iea15mw-windio/IEA-15-240-RWT.yaml");
    let w = std::sync::Arc::new(flutterscope::formats::windio::read(&path).unwrap());
    b.bench(|| LayupBlade::new(w.clone(), None, None, None).unwrap());
}

/// The spar caps of the IEA 15MW turned a degree further over r/R 0.6–1.0, from the blade
/// analysed at the angle before (a ply-angle key's sections): the 21 turned stations on their
/// held meshes and factorisation patterns, in parallel on all cores.
#[divan::bench(sample_count = 20)]
fn iea15mw_spar_caps_turned_a_degree(b: divan::Bencher) {
    use flutterscope::physics::blade::windio::PlyTurn;
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades/iea15mw-windio/IEA-15-240-RWT.yaml");
    let w = std::sync::Arc::new(flutterscope::formats::windio::read(&path).unwrap());
    let turn = |angle: f64| PlyTurn {
        angle,
        layers: PlyTurn::spar_caps(&w),
        span: [0.6, 1.0],
    };
    let held = LayupBlade::new(w.clone(), Some(turn(8.0)), None, None).unwrap();
    let mut angle = 8.0;
    b.bench_local(|| {
        angle += 1.0;
        LayupBlade::new(w.clone(), Some(turn(angle)), None, Some(&held)).unwrap()
    });
}
