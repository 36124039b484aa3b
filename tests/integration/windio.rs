//! The WindIO ontology reader on the project's copies of the IEA 15MW ontology, the current one
//! and that of 2019 (values read off the file text), and the placement of width-defined layers
//! and webs checked against the arc positions the design tool wrote into the same file.

use flutterscope::formats::windio::arc::{place_layers, place_web, Contour, Station};
use flutterscope::formats::windio::{self, Anchor, Elastic, Fixed, Placement, Side, WindIo};
use std::path::{Path, PathBuf};

const CURRENT: &str = "iea15mw-windio/IEA-15-240-RWT.yaml";
const OLD: &str = "iea15mw-windio-2019/IEA-15-240-RWT_2019.yaml";

fn blade_file(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades")
        .join(rel)
}

fn read(rel: &str) -> WindIo {
    windio::read(&blade_file(rel)).unwrap_or_else(|e| panic!("{e}"))
}

/// The 1-based line of the first line of the file's text that contains `needle`.
fn line_in(rel: &str, needle: &str) -> usize {
    let text = std::fs::read_to_string(blade_file(rel)).unwrap();
    text.lines().position(|l| l.contains(needle)).unwrap() + 1
}

#[test]
fn the_current_iea15_ontology_gives_its_layup() {
    let w = read(CURRENT);
    let s = &w.blade.structure;
    assert_eq!(s.layers.len(), 18);
    assert_eq!(s.webs.len(), 2);
    let names: Vec<&str> = s.webs.iter().map(|x| x.name.as_str()).collect();
    assert_eq!(names, ["web0", "web1"]);
    for (i, name, side) in [
        (2, "Spar_Cap_SS", Side::Suction),
        (3, "Spar_Cap_PS", Side::Pressure),
    ] {
        let cap = &s.layers[i];
        assert_eq!(cap.name, name);
        assert_eq!(cap.material, "CarbonUD");
        assert_eq!(cap.side, Some(side));
        assert_eq!(cap.thickness.grid.len(), 50);
        assert_eq!(cap.line, line_in(CURRENT, &format!("name: {name}")));
        // The design tool wrote the arcs next to the width-based definition; the arcs place it.
        assert!(matches!(cap.placement(), Some(Placement::Arcs { .. })));
        assert_eq!(cap.width.as_ref().unwrap().values[0], 0.9);
        assert!(cap.rotation.as_ref().unwrap().fixed_to_twist);
    }
    // "values: [0.0001, 0.0019253427544743858, …]" at grid point 10, 0.2040816326530612.
    let cap = &s.layers[2].thickness;
    assert_eq!(cap.grid[10], 0.2040816326530612);
    assert_eq!(cap.values[10], 0.07517917278251993);
    assert_eq!(cap.values[0], 0.0001);
    // Layers on webs, and one anchored at the trailing edge by its width.
    assert_eq!(s.layers.iter().filter(|l| l.web.is_some()).count(), 6);
    assert_eq!(s.layers[12].web.as_deref(), Some("web0"));
    let te = w.layer("TE_reinforcement_SS").unwrap();
    match te.placement() {
        Some(Placement::Width {
            width,
            anchor: Anchor::Start(start),
        }) => {
            assert_eq!(width.values, [0.0, 0.0, 0.75, 0.75, 0.0, 0.0]);
            assert_eq!(start.fixed, Some(Fixed::TrailingEdge));
        }
        other => panic!("{other:?}"),
    }
    let filler = w.layer("TE_SS_filler").unwrap();
    let start = filler.start_nd_arc.as_ref().unwrap();
    assert_eq!(
        start.fixed,
        Some(Fixed::Layer("TE_reinforcement_SS".into()))
    );
    assert_eq!(start.values.as_ref().unwrap().values.len(), 50);
    // Webs: both the offset about the pitch axis and the arcs.
    let web0 = &s.webs[0];
    assert_eq!(web0.offset.as_ref().unwrap().values, [-0.35, -0.35]);
    assert!(web0.start_nd_arc.is_some() && web0.end_nd_arc.is_some());
    assert_eq!(w.number_of_blades, 3);
}

#[test]
fn the_current_iea15_ontology_gives_its_shape_airfoils_materials_and_hub() {
    let w = read(CURRENT);
    let shape = &w.blade.outer_shape;
    assert_eq!(shape.chord.values[0], 5.2);
    assert_eq!(shape.chord.grid.len(), 53);
    assert_eq!(*shape.reference_axis.z.values.last().unwrap(), 117.0);
    assert_eq!(shape.reference_axis.y.values, [0.0, 0.0]);
    assert_eq!(shape.twist.values[0], 0.27217629557079365);
    assert_eq!(shape.pitch_axis.values[0], 0.5045454545454545);
    // The structure's reference axis is an alias of the outer shape's.
    assert_eq!(w.blade.structure.reference_axis, shape.reference_axis);
    let labels = &shape.airfoil_position.labels;
    assert_eq!(labels.len(), 10);
    assert_eq!(labels[0], "circular");
    assert_eq!(labels[2], "SNL-FFA-W3-500");
    assert_eq!(labels[9], "FFA-W3-211");
    assert_eq!(w.airfoils.len(), 8);
    let af = w.airfoil("FFA-W3-211").unwrap();
    assert_eq!(af.relative_thickness, 0.211);
    assert_eq!(af.x.len(), 200);
    assert_eq!((af.x[0], af.y[0]), (1.0, 0.00094));
    let polar = &w.airfoil("SNL-FFA-W3-500").unwrap().polars[0];
    assert_eq!(polar.re, Some(8.1e6));
    assert_eq!(polar.c_l.grid.len(), polar.c_l.values.len());
    assert_eq!(w.materials.len(), 11);
    let carbon = w.material("CarbonUD").unwrap();
    assert_eq!(carbon.rho, 1220.0);
    assert_eq!(carbon.ply_t, Some(0.005158730158730159));
    assert_eq!(
        carbon.elastic,
        Elastic::Orthotropic {
            e: [114.5e9, 8.39e9, 8.39e9],
            g: [5.99e9, 5.99e9, 5.99e9],
            nu: [0.27, 0.27, 0.27],
        }
    );
    assert!(matches!(
        w.material("medium_density_foam").unwrap().elastic,
        Elastic::Isotropic { g: Some(_), .. }
    ));
    assert_eq!(w.hub.diameter, 7.94);
    assert_eq!(w.hub.cone_angle, 0.06981317007977318);
}

#[test]
fn the_2019_ontology_reads_with_its_older_names() {
    let w = read(OLD);
    let s = &w.blade.structure;
    assert_eq!(s.layers.len(), 20);
    let names: Vec<&str> = s.webs.iter().map(|x| x.name.as_str()).collect();
    assert_eq!(names, ["fore_web", "rear_web", "third_web"]);
    for (i, name) in [(9, "Spar_cap_ss"), (10, "Spar_cap_ps")] {
        assert_eq!(s.layers[i].name, name);
        assert_eq!(s.layers[i].material, "CarbonUD");
        // `offset_x_pa` in this ontology.
        assert!(s.layers[i].offset.is_some());
    }
    let cap = &s.layers[9].thickness;
    assert_eq!(cap.grid[12], 0.4391793464459161);
    assert_eq!(cap.values[12], 0.10433345664081885);
    assert_eq!(s.webs[0].offset.as_ref().unwrap().values[0], -0.35);
    // A midpoint locked to the trailing edge with no values beside it.
    let te = w.layer("TE_reinforcement").unwrap();
    let mid = te.midpoint_nd_arc.as_ref().unwrap();
    assert_eq!(
        (mid.fixed.clone(), mid.values.clone()),
        (Some(Fixed::TrailingEdge), None)
    );
    assert_eq!(w.blade.outer_shape.chord.values[0], 5.2);
    assert_eq!(
        *w.blade.outer_shape.chord.values.last().unwrap(),
        1.2851239626311368
    );
    assert_eq!(w.airfoils.len(), 12);
    assert_eq!(w.blade.outer_shape.airfoil_position.labels[7], "NACA64-618");
    assert_eq!(w.materials.len(), 6);
    assert_eq!(w.material("CarbonUD").unwrap().ply_t, None);
    // The hub from `assembly.global`: `hubD: 6.0`, `cone_angle: 4.0` (degrees).
    assert_eq!(w.hub.diameter, 6.0);
    assert!((w.hub.cone_angle - 4f64.to_radians()).abs() < 1e-15);
    assert_eq!(w.number_of_blades, 3);
}

#[test]
fn a_broken_real_file_names_the_path_and_line() {
    let path = blade_file(CURRENT);
    let text = std::fs::read_to_string(&path).unwrap();
    let line = line_in(CURRENT, "material: CarbonUD");
    let broken = text.replacen("material: CarbonUD", "material: CarbonXD", 1);
    let e = windio::parse(&broken, "iea.yaml").unwrap_err().to_string();
    assert!(
        e.starts_with(&format!(
            "iea.yaml:{line}: components.blade.internal_structure_2d_fem.layers[2].material: no material named `CarbonXD`"
        )),
        "{e}"
    );
}

/// The section of the current IEA 15MW blade at grid point `eta` of the layup, where the
/// airfoil is the named one unblended (at an airfoil position, or beyond the last change).
fn section(w: &WindIo, eta: f64, airfoil: &str) -> (Contour, f64) {
    let shape = &w.blade.outer_shape;
    let af = w.airfoil(airfoil).unwrap();
    let contour = Contour::new(
        &af.x,
        &af.y,
        shape.chord.linear(eta),
        shape.pitch_axis.linear(eta),
    )
    .unwrap();
    (contour, shape.twist.linear(eta))
}

/// The layup with the arcs the design tool wrote removed wherever a width or a lock defines
/// them, so that the placement has to derive them.
fn without_written_arcs(w: &WindIo) -> Vec<windio::Layer> {
    let mut layers = w.blade.structure.layers.clone();
    for l in &mut layers {
        let by_width = l.width.is_some();
        for arc in [&mut l.start_nd_arc, &mut l.end_nd_arc]
            .into_iter()
            .flatten()
        {
            if arc.fixed.is_some() {
                arc.values = None;
            }
        }
        if by_width {
            for arc in [&mut l.start_nd_arc, &mut l.end_nd_arc] {
                if arc.as_ref().is_some_and(|a| a.fixed.is_none()) {
                    *arc = None;
                }
            }
        }
    }
    layers
}

const STATIONS: [(f64, &str); 3] = [
    (0.15, "SNL-FFA-W3-500"),
    (0.24517031675566095, "FFA-W3-360"),
    (0.7755102040816326, "FFA-W3-211"),
];

#[test]
fn width_defined_layers_land_where_the_design_tool_placed_them() {
    let w = read(CURRENT);
    let derived_layers = without_written_arcs(&w);
    for (eta, airfoil) in STATIONS {
        let (contour, twist) = section(&w, eta, airfoil);
        let at = Station {
            eta,
            twist,
            contour: &contour,
        };
        let written = place_layers(&w.blade.structure.layers, &at, "iea").unwrap();
        let derived = place_layers(&derived_layers, &at, "iea").unwrap();
        for (layer, (given, ours)) in derived_layers.iter().zip(written.iter().zip(&derived)) {
            let (Some((s0, e0)), Some((s1, e1))) = (given, ours) else {
                assert!(layer.web.is_some(), "{} was not placed", layer.name);
                assert_eq!((given, ours), (&None, &None));
                continue;
            };
            if layer.width.is_some() {
                let width_given = e0 - s0;
                let width_ours = e1 - s1;
                assert!(
                    (width_ours - width_given).abs() <= 0.01 * width_given,
                    "{} at {eta}: width {width_ours} against {width_given}",
                    layer.name
                );
            }
            // The tool put the leading edge a few thousandths of the perimeter from the contour's
            // foremost point; everything else lands within that.
            let tol = if layer.name.starts_with("LE_") {
                0.007
            } else {
                0.005
            };
            assert!(
                (s1 - s0).abs() < tol && (e1 - e0).abs() < tol,
                "{} at {eta}: ({s1}, {e1}) against ({s0}, {e0})",
                layer.name
            );
        }
        let nose = derived_layers
            .iter()
            .position(|l| l.name == "LE_reinforcement")
            .unwrap();
        let (s, e) = derived[nose].unwrap();
        assert!(((s + e) / 2.0 - contour.leading_edge()).abs() < 1e-12);
    }
}

#[test]
fn webs_placed_about_the_pitch_axis_meet_the_shell_where_the_file_says() {
    let w = read(CURRENT);
    for (eta, airfoil) in STATIONS {
        let (contour, twist) = section(&w, eta, airfoil);
        let at = Station {
            eta,
            twist,
            contour: &contour,
        };
        for web in &w.blade.structure.webs {
            let (s0, e0) = place_web(web, &at, "iea").unwrap();
            let mut by_offset = web.clone();
            by_offset.start_nd_arc = None;
            by_offset.end_nd_arc = None;
            let (s1, e1) = place_web(&by_offset, &at, "iea").unwrap();
            assert!(
                (s1 - s0).abs() < 0.005 && (e1 - e0).abs() < 0.005,
                "{} at {eta}: ({s1}, {e1}) against ({s0}, {e0})",
                web.name
            );
            // Turning the web the other way moves both ends by far more than that.
            let mut turned = by_offset.clone();
            let rotation = turned.rotation.as_mut().unwrap();
            for v in &mut rotation.values.as_mut().unwrap().values {
                *v = -*v;
            }
            let (s2, e2) = place_web(&turned, &at, "iea").unwrap();
            if twist.abs() > 0.1 {
                assert!(
                    (s2 - s0).abs() > 0.01 && (e2 - e0).abs() > 0.01,
                    "{s2} {e2}"
                );
            }
        }
    }
}

#[test]
fn a_reinforcement_centred_on_the_trailing_edge_runs_across_it() {
    let w = read(OLD);
    // The last airfoil position before the tip: FFA-W3-211 unblended.
    let eta = 0.7717438522715817;
    let (contour, twist) = section(&w, eta, "FFA-W3-211");
    let at = Station {
        eta,
        twist,
        contour: &contour,
    };
    let mut layers = w.blade.structure.layers.clone();
    let i = layers
        .iter()
        .position(|l| l.name == "TE_reinforcement")
        .unwrap();
    let (start, end) = (
        layers[i].start_nd_arc.take().unwrap(),
        layers[i].end_nd_arc.take().unwrap(),
    );
    let (s, e) = place_layers(&layers, &at, "iea").unwrap()[i].unwrap();
    assert!(s > 0.9 && e < 0.1, "({s}, {e})");
    assert!(
        (s + e - 1.0).abs() < 1e-12,
        "centred on the trailing edge: ({s}, {e})"
    );
    let (s0, e0) = (
        start.values.unwrap().linear(eta),
        end.values.unwrap().linear(eta),
    );
    assert!(
        (s - s0).abs() < 0.002 && (e - e0).abs() < 0.002,
        "({s}, {e}) against ({s0}, {e0})"
    );
}

#[test]
fn the_current_iea15_ontology_reads_in_milliseconds() {
    let path = blade_file(CURRENT);
    let text = std::fs::read_to_string(&path).unwrap();
    let t = std::time::Instant::now();
    let runs = 5;
    for _ in 0..runs {
        windio::parse(&text, "iea.yaml").unwrap();
    }
    let each = t.elapsed().as_secs_f64() / runs as f64;
    eprintln!("IEA 15MW ontology: {:.1} ms per read", each * 1e3);
    assert!(each < 0.5, "{each} s per read");
}

/// The largest distance across the contour between the two surfaces' points of the same
/// parameter (suction point j against pressure point j), in chord units.
fn shape_thickness(x: &[f64], y: &[f64]) -> f64 {
    let n = (x.len() - 1) / 2;
    (0..=n)
        .map(|j| (y[n - j] - y[n + j]).abs())
        .fold(0.0, f64::max)
}

/// Distance from `p` to the polyline `(x, y)`.
fn off_line(x: &[f64], y: &[f64], p: [f64; 2]) -> f64 {
    (0..x.len() - 1)
        .map(|i| {
            let (a, b) = ([x[i], y[i]], [x[i + 1], y[i + 1]]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            let t = if len2 > 0.0 {
                (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p[0] - a[0] - t * d[0]).hypot(p[1] - a[1] - t * d[1])
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn a_station_at_a_listed_airfoil_has_that_airfoils_shape() {
    let w = read(CURRENT);
    for (eta, name) in STATIONS {
        let b = w.thickness_blend(eta);
        let af = w.airfoil(name).unwrap();
        assert!(
            (b.thickness - af.relative_thickness).abs() < 1e-12,
            "{eta}: {}",
            b.thickness
        );
        let listed = if b.weight == 0.0 {
            b.thinner
        } else {
            b.thicker
        };
        assert!(b.weight == 0.0 || b.weight == 1.0, "{eta}: {}", b.weight);
        assert_eq!(listed.name, name);
        let (x, y) = w.station_shape(eta, CURRENT).unwrap();
        assert_eq!(x.len(), 2 * windio::thickness::SURFACE_POINTS + 1);
        let worst = x
            .iter()
            .zip(&y)
            .map(|(&px, &py)| off_line(&af.x, &af.y, [px, py]))
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-12,
            "{eta} {name}: a point {worst:e} off the contour"
        );
        // The leading edge is the sample in the middle, the ends the trailing edge's.
        let least = af.x.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((x[x.len() / 2] - least).abs() < 1e-12);
        assert_eq!((x[0], y[0]), (af.x[0], af.y[0]));
        let last = af.x.len() - 1;
        assert_eq!((x[x.len() - 1], y[y.len() - 1]), (af.x[last], af.y[last]));
    }
}

#[test]
fn stations_between_listed_airfoils_blend_them_in_relative_thickness() {
    for (file, thinnest) in [(CURRENT, 0.211), (OLD, 0.18)] {
        let w = read(file);
        let mut previous = f64::INFINITY;
        let mut worst: f64 = 0.0;
        for i in 0..=200 {
            let eta = i as f64 / 200.0;
            let b = w.thickness_blend(eta);
            // The IEA 15MW thins monotonically from its cylinder to the tip airfoil.
            assert!(b.thickness <= previous + 1e-15, "{file} {eta}");
            assert!((thinnest - 1e-12..=1.0 + 1e-12).contains(&b.thickness));
            previous = b.thickness;
            let (lo, hi) = (b.thinner.relative_thickness, b.thicker.relative_thickness);
            assert!(lo <= b.thickness + 1e-12 && b.thickness <= hi + 1e-12);
            if hi > lo {
                assert!((lo + b.weight * (hi - lo) - b.thickness).abs() < 1e-12);
            }
            // The blended shape is as thick as the station is said to be, and its contour
            // places every layer and web of the layup.
            let (x, y) = w.station_shape(eta, file).unwrap();
            let t = shape_thickness(&x, &y);
            worst = worst.max((t / b.thickness - 1.0).abs());
            let shape = &w.blade.outer_shape;
            let contour = Contour::new(
                &x,
                &y,
                shape.chord.linear(eta),
                shape.pitch_axis.linear(eta),
            )
            .unwrap_or_else(|e| panic!("{file} {eta}: {e}"));
            let at = Station {
                eta,
                twist: shape.twist.linear(eta),
                contour: &contour,
            };
            place_layers(&w.blade.structure.layers, &at, file)
                .unwrap_or_else(|e| panic!("{file} {eta}: {e}"));
            for web in &w.blade.structure.webs {
                place_web(web, &at, file).unwrap_or_else(|e| panic!("{file} {eta}: {e}"));
            }
        }
        eprintln!("{file}: thickness within {worst:.4}");
        assert!(worst < 0.03, "{file}: shape thickness off by {worst}");
    }
}
