//! WindIO turbine ontology files (IEA Wind Task 37, YAML): the blade's outer shape and layup,
//! the airfoils with their polars, the materials, the hub and the number of blades, as plain
//! data in the file's own units (SI, angles in radians) and frame.
//!
//! The reader reads what the section analysis and the rotor need and checks it: every
//! distribution's grid increasing (within [0, 1] along the span and arc), its values as many and
//! finite and in range, and every name a layer or the airfoil positions refer to defined. What
//! the file leaves out is never filled in: a missing required field is an error naming its path,
//! an optional one is `None`. Errors name the file, the line and the YAML path
//! (`components.blade.internal_structure_2d_fem.layers[3].thickness`).
//!
//! Both the current ontology and the 2019 one read: the 2019 files name a layer's offset
//! `offset_x_pa` (now `offset_y_pa`) and give the hub and the number of blades under
//! `assembly.global` (`hubD` in metres, `cone_angle` in degrees) instead of `components.hub`.
//!
//! Arc positions given as a width, a side or an offset need the section's contour to become
//! `start_nd_arc`/`end_nd_arc`; [`arc`] places them on a contour.

pub mod airfoils;
pub mod arc;
pub mod blade;
pub mod distribution;
pub mod materials;
pub mod thickness;
mod yaml;

pub use airfoils::{Airfoil, Polar};
pub use blade::{
    AirfoilPosition, Anchor, ArcPosition, Axis, Blade, Fixed, InternalStructure, Layer, OuterShape,
    Placement, Rotation, Side, Web,
};
pub use distribution::Distribution;
pub use materials::{Elastic, Material};
pub use thickness::ThicknessBlend;

use super::text::read_text;
use crate::error::Result;
use distribution::{number_in, Range};
use std::collections::HashMap;
use std::path::Path;
use yaml::{Document, Node};

/// The hub, as far as the rotor's geometry needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hub {
    /// Diameter at the blade roots, m (> 0).
    pub diameter: f64,
    /// Precone, rad, positive for both upwind and downwind rotors (the 2019 ontology's degrees
    /// are converted).
    pub cone_angle: f64,
}

/// What a WindIO file says about the rotor and its blade.
#[derive(Debug, Clone, PartialEq)]
pub struct WindIo {
    /// The file's name as errors give it.
    pub path: String,
    /// The top-level `name`, when given.
    pub name: Option<String>,
    pub blade: Blade,
    pub airfoils: Vec<Airfoil>,
    pub materials: Vec<Material>,
    pub hub: Hub,
    pub number_of_blades: usize,
}

impl WindIo {
    pub fn airfoil(&self, name: &str) -> Option<&Airfoil> {
        self.airfoils.iter().find(|a| a.name == name)
    }

    pub fn material(&self, name: &str) -> Option<&Material> {
        self.materials.iter().find(|m| m.name == name)
    }

    pub fn layer(&self, name: &str) -> Option<&Layer> {
        self.blade.structure.layers.iter().find(|l| l.name == name)
    }

    pub fn web(&self, name: &str) -> Option<&Web> {
        self.blade.structure.webs.iter().find(|w| w.name == name)
    }
}

pub fn read(path: &Path) -> Result<WindIo> {
    parse(&read_text(path)?, &path.display().to_string())
}

/// Reads the ontology in `text`; `file` is the name errors give.
pub fn parse(text: &str, file: &str) -> Result<WindIo> {
    let doc = Document::parse(text, file)?;
    let root = doc.root(file);
    let components = root.req("components", "a mapping with the blade and the hub")?;
    let blade_node = components.req("blade", "the blade's outer shape and layup")?;
    let blade = blade::read_blade(&blade_node)?;

    let airfoils = named_list(
        &root,
        "airfoils",
        "a list of airfoils",
        "airfoil",
        airfoils::read_airfoil,
        |a| a.name.as_str(),
    )?;
    let materials = named_list(
        &root,
        "materials",
        "a list of materials",
        "material",
        materials::read_material,
        |m| m.name.as_str(),
    )?;

    let assembly = root.req("assembly", "a mapping with number_of_blades")?;
    let (hub, number_of_blades) = hub_and_blades(&components, &assembly)?;

    let out = WindIo {
        path: file.to_string(),
        name: root.get("name")?.map(|n| n.text()).transpose()?,
        blade,
        airfoils,
        materials,
        hub,
        number_of_blades,
    };
    check_references(&out, &blade_node)?;
    Ok(out)
}

/// Two entries of one name would make every reference to it ambiguous.
/// The list at `key` of `root`, each item read by `read` and named by `name`, no name twice.
fn named_list<T>(
    root: &Node,
    key: &str,
    expected: &str,
    what: &str,
    read: impl Fn(&Node) -> Result<T>,
    name: impl Fn(&T) -> &str,
) -> Result<Vec<T>> {
    let nodes = root.req(key, expected)?.items()?;
    let items = nodes.iter().map(read).collect::<Result<Vec<_>>>()?;
    unique(&nodes, items.iter().map(name), what)?;
    Ok(items)
}

fn unique<'n>(nodes: &[Node], names: impl Iterator<Item = &'n str>, what: &str) -> Result<()> {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, name) in names.enumerate() {
        if let Some(first) = seen.insert(name, i) {
            return Err(nodes[i].error(format!(
                "a second {what} named `{name}` (the first is at line {}); names must be unique",
                nodes[first].line()
            )));
        }
    }
    Ok(())
}

fn hub_and_blades(components: &Node, assembly: &Node) -> Result<(Hub, usize)> {
    let global = assembly.get("global")?;
    let blades_node = match (assembly.get("number_of_blades")?, &global) {
        (Some(n), _) => n,
        (None, Some(g)) if g.get("number_of_blades")?.is_some() => {
            g.req("number_of_blades", "an integer ≥ 1")?
        }
        (None, _) => assembly.req("number_of_blades", "an integer ≥ 1")?,
    };
    let blades = blades_node.number()?;
    if blades < 1.0 || blades.fract() != 0.0 || blades > 1000.0 {
        return Err(blades_node.error(format!("expected an integer ≥ 1, found {blades}")));
    }
    let hub = match components.get("hub")? {
        Some(h) => {
            // The ontology of 2020 nested the hub's geometry under `outer_shape_bem`.
            let h = match h.get("outer_shape_bem")? {
                Some(inner) if h.get("diameter")?.is_none() => inner,
                _ => h,
            };
            Hub {
                diameter: number_in(&h.req("diameter", "the hub diameter, m")?, Range::Positive)?,
                cone_angle: number_in(&h.req("cone_angle", "the precone, rad")?, Range::Any)?,
            }
        }
        None => match &global {
            Some(g) if g.get("hubD")?.is_some() => Hub {
                diameter: number_in(&g.req("hubD", "the hub diameter, m")?, Range::Positive)?,
                cone_angle: number_in(&g.req("cone_angle", "the precone, deg")?, Range::Any)?
                    .to_radians(),
            },
            _ => return Err(components.missing("hub", "the hub's diameter and cone_angle")),
        },
    };
    Ok((hub, blades as usize))
}

/// Every name a layer, a web or the airfoil positions use is defined.
fn check_references(w: &WindIo, blade_node: &Node) -> Result<()> {
    let shape = blade_node.req("outer_shape_bem", "")?;
    let labels = shape
        .req("airfoil_position", "")?
        .req("labels", "")?
        .items()?;
    for (label, node) in w
        .blade
        .outer_shape
        .airfoil_position
        .labels
        .iter()
        .zip(&labels)
    {
        if w.airfoil(label).is_none() {
            return Err(node.error(format!(
                "no airfoil named `{label}` in airfoils (it has: {})",
                names(w.airfoils.iter().map(|a| a.name.as_str()))
            )));
        }
    }
    let structure = blade_node.req("internal_structure_2d_fem", "")?;
    let layer_nodes = structure.req("layers", "")?.items()?;
    unique(
        &layer_nodes,
        w.blade.structure.layers.iter().map(|l| l.name.as_str()),
        "layer",
    )?;
    if let Some(webs) = structure.get("webs")? {
        unique(
            &webs.items()?,
            w.blade.structure.webs.iter().map(|x| x.name.as_str()),
            "web",
        )?;
    }
    for (layer, node) in w.blade.structure.layers.iter().zip(&layer_nodes) {
        if w.material(&layer.material).is_none() {
            return Err(node.req("material", "")?.error(format!(
                "no material named `{}` in materials (it has: {})",
                layer.material,
                names(w.materials.iter().map(|m| m.name.as_str()))
            )));
        }
        if let Some(web) = &layer.web {
            if w.web(web).is_none() {
                return Err(node.req("web", "")?.error(format!(
                    "no web named `{web}` in internal_structure_2d_fem.webs (it has: {})",
                    names(w.blade.structure.webs.iter().map(|x| x.name.as_str()))
                )));
            }
        }
        for (key, arc) in [
            ("start_nd_arc", &layer.start_nd_arc),
            ("end_nd_arc", &layer.end_nd_arc),
            ("midpoint_nd_arc", &layer.midpoint_nd_arc),
        ] {
            if let Some(ArcPosition {
                fixed: Some(Fixed::Layer(other)),
                ..
            }) = arc
            {
                if other == &layer.name || w.layer(other).is_none() {
                    let what = if other == &layer.name {
                        "the layer itself"
                    } else {
                        "no layer of that name"
                    };
                    return Err(node.req(key, "")?.req("fixed", "")?.error(format!(
                        "expected LE, TE or another layer's name, found `{other}` ({what})"
                    )));
                }
            }
        }
    }
    Ok(())
}

fn names<'n>(it: impl Iterator<Item = &'n str>) -> String {
    let all: Vec<&str> = it.collect();
    if all.is_empty() {
        "none".to_string()
    } else {
        all.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small but complete ontology: a two-station blade with one web, a spar cap placed about
    /// the pitch axis, a reinforcement about the leading edge and a filler locked between them.
    /// The reference axis and a polar grid are shared through anchors, as the IEA files do.
    pub(super) const GOOD: &str = "\
name: test turbine
assembly:
    number_of_blades: 3
components:
    blade:
        outer_shape_bem:
            airfoil_position:
                grid: [0.0, 1.0]
                labels: [round, round]
            chord:
                grid: [0.0, 1.0]
                values: [2.0, 1.0]
            twist: &twist
                grid: [0.0, 1.0]
                values: [0.1, 0.0]
            pitch_axis:
                grid: [0.0, 1.0]
                values: [0.5, 0.5]
            reference_axis: &axis
                x: {grid: [0.0, 1.0], values: [0.0, 0.0]}
                y: {grid: [0.0, 1.0], values: [0.0, 0.0]}
                z: {grid: [0.0, 1.0], values: [0.0, 50.0]}
        internal_structure_2d_fem:
            reference_axis: *axis
            webs:
              - name: spar
                rotation: {fixed: twist}
                offset_y_pa: {grid: [0.0, 1.0], values: [0.0, 0.0]}
            layers:
              - name: skin
                material: glass
                thickness: {grid: [0.0, 1.0], values: [0.01, 0.005]}
                fiber_orientation: {grid: [0.0, 1.0], values: [0.0, 0.0]}
              - name: cap
                material: carbon
                thickness: {grid: [0.0, 0.5, 1.0], values: [0.02, 0.03, 0.0]}
                width: {grid: [0.0, 1.0], values: [0.5, 0.5]}
                side: suction
                offset_y_pa: {grid: [0.0, 1.0], values: [0.0, 0.0]}
                rotation: {fixed: twist}
              - name: nose
                material: glass
                thickness: {grid: [0.0, 1.0], values: [0.01, 0.01]}
                width: {grid: [0.0, 1.0], values: [0.4, 0.4]}
                midpoint_nd_arc: {fixed: LE}
              - name: filler
                material: foam
                thickness: {grid: [0.0, 1.0], values: [0.05, 0.05]}
                start_nd_arc: {fixed: cap}
                end_nd_arc: {fixed: nose}
              - name: web_skin
                material: glass
                web: spar
                thickness: {grid: [0.0, 1.0], values: [0.004, 0.004]}
    hub:
        diameter: 4.0
        cone_angle: 0.05
airfoils:
  - name: round
    coordinates:
        x: [1.0, 0.5, 0.0, 0.5, 1.0]
        y: [0.0, 0.5, 0.0, -0.5, 0.0]
    relative_thickness: 1.0
    aerodynamic_center: 0.25
    polars:
      - configuration: Default
        re: 1.0e+6
        c_l: {grid: &alpha [-3.0, 3.0], values: [0.0, 0.0]}
        c_d: {grid: *alpha, values: [0.5, 0.5]}
        c_m: {grid: *alpha, values: [0.0, 0.0]}
materials:
  - name: glass
    orth: 1
    E: [4.0e+10, 1.0e+10, 1.0e+10]
    G: [4.0e+9, 4.0e+9, 3.0e+9]
    nu: [0.3, 0.3, 0.3]
    rho: 1900.0
    ply_t: 0.001
    unit_cost: 3.0
  - name: carbon
    orth: 1.0
    E: [1.2e+11, 9.0e+9, 9.0e+9]
    G: [5.0e+9, 5.0e+9, 5.0e+9]
    nu: [0.27, 0.27, 0.27]
    rho: 1600.0
  - name: foam
    orth: 0
    E: 1.2e+8
    nu: 0.3
    rho: 130.
";

    fn parse_err(text: &str) -> String {
        match parse(text, "t.yaml") {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.to_string(),
        }
    }

    /// The 1-based line of the first line of `text` containing `needle`.
    fn line_of(text: &str, needle: &str) -> usize {
        text.lines()
            .position(|l| l.contains(needle))
            .unwrap_or_else(|| panic!("`{needle}` not in the text"))
            + 1
    }

    /// `GOOD` with the first occurrence of `from` replaced by `to` (which must be there).
    fn with(from: &str, to: &str) -> String {
        assert!(GOOD.contains(from), "`{from}` not in the text");
        GOOD.replacen(from, to, 1)
    }

    fn assert_names(message: &str, path: &str, line: usize) {
        assert!(message.contains(path), "no `{path}` in: {message}");
        assert!(
            message.starts_with(&format!("t.yaml:{line}: ")),
            "not at line {line}: {message}"
        );
    }

    #[test]
    fn a_complete_ontology_reads_with_its_anchors_resolved() {
        let w = parse(GOOD, "t.yaml").unwrap();
        assert_eq!(w.name.as_deref(), Some("test turbine"));
        assert_eq!(w.number_of_blades, 3);
        assert_eq!(
            w.hub,
            Hub {
                diameter: 4.0,
                cone_angle: 0.05
            }
        );
        let b = &w.blade;
        assert_eq!(b.structure.reference_axis, b.outer_shape.reference_axis);
        assert_eq!(b.structure.reference_axis.z.values, vec![0.0, 50.0]);
        let polar = &w.airfoils[0].polars[0];
        assert_eq!(polar.c_d.grid, vec![-3.0, 3.0]);
        assert_eq!(polar.c_d.values, vec![0.5, 0.5]);
        assert_eq!(polar.re, Some(1.0e6));
        let cap = w.layer("cap").unwrap();
        assert_eq!(cap.thickness.values, vec![0.02, 0.03, 0.0]);
        assert_eq!(cap.line, line_of(GOOD, "name: cap"));
        assert!(matches!(
            w.material("foam").unwrap().elastic,
            Elastic::Isotropic { e, g: None, nu } if e == 1.2e8 && nu == 0.3
        ));
        assert_eq!(w.material("glass").unwrap().ply_t, Some(0.001));
        assert_eq!(w.material("carbon").unwrap().ply_t, None);
    }

    #[test]
    fn each_layer_is_placed_by_the_definition_it_gives() {
        let w = parse(GOOD, "t.yaml").unwrap();
        let kind = |name: &str| w.layer(name).unwrap().placement().unwrap();
        assert_eq!(kind("skin"), Placement::WholeSection);
        assert!(matches!(
            kind("cap"),
            Placement::Width {
                anchor: Anchor::PitchAxis { side: Side::Suction, rotation: Some(r), .. },
                ..
            } if r.fixed_to_twist && r.values.is_none()
        ));
        assert!(matches!(
            kind("nose"),
            Placement::Width {
                anchor: Anchor::Midpoint(ArcPosition {
                    fixed: Some(Fixed::LeadingEdge),
                    values: None,
                    ..
                }),
                ..
            }
        ));
        assert!(matches!(kind("filler"), Placement::Arcs { .. }));
        assert_eq!(kind("web_skin"), Placement::Web("spar"));
    }

    #[test]
    fn the_2019_ontology_gives_the_hub_under_assembly_in_degrees() {
        let text = with(
            "    hub:\n        diameter: 4.0\n        cone_angle: 0.05\n",
            "",
        )
        .replace(
            "assembly:\n    number_of_blades: 3\n",
            "assembly:\n    global:\n        number_of_blades: 2\n        cone_angle: 4.0\n        hubD: 6.0\n",
        )
        .replace("offset_y_pa", "offset_x_pa");
        let w = parse(&text, "t.yaml").unwrap();
        assert_eq!(w.number_of_blades, 2);
        assert_eq!(w.hub.diameter, 6.0);
        assert!((w.hub.cone_angle - 4f64.to_radians()).abs() < 1e-15);
        assert_eq!(
            w.web("spar").unwrap().offset.as_ref().unwrap().values,
            vec![0.0, 0.0]
        );
    }

    #[test]
    fn a_missing_field_is_named_with_its_path_and_the_line_of_its_parent() {
        let text = with(
            "            chord:\n                grid: [0.0, 1.0]\n                values: [2.0, 1.0]\n",
            "",
        );
        let m = parse_err(&text);
        assert_names(
            &m,
            "components.blade.outer_shape_bem.chord: missing",
            line_of(&text, "airfoil_position:"),
        );
    }

    #[test]
    fn a_grid_that_does_not_increase_is_named_at_its_point() {
        let text = with(
            "thickness: {grid: [0.0, 0.5, 1.0]",
            "thickness: {grid: [0.0, 0.5, 0.5]",
        );
        let m = parse_err(&text);
        assert_names(
            &m,
            "components.blade.internal_structure_2d_fem.layers[1].thickness.grid[2]",
            line_of(&text, "[0.0, 0.5, 0.5]"),
        );
        assert!(m.contains("increasing numbers in [0, 1]"), "{m}");
        let text = with(
            "grid: [0.0, 1.0]\n                labels",
            "grid: [0.0, 1.5]\n                labels",
        );
        let m = parse_err(&text);
        assert_names(
            &m,
            "outer_shape_bem.airfoil_position.grid[1]",
            line_of(&text, "[0.0, 1.5]"),
        );
    }

    #[test]
    fn values_of_another_length_than_the_grid_are_refused() {
        let text = with("values: [0.02, 0.03, 0.0]", "values: [0.02, 0.03]");
        let m = parse_err(&text);
        assert_names(
            &m,
            "components.blade.internal_structure_2d_fem.layers[1].thickness.values",
            line_of(&text, "values: [0.02, 0.03]}"),
        );
        assert!(
            m.contains("values the same length as grid (3), found 2"),
            "{m}"
        );
        let text = with("labels: [round, round]", "labels: [round]");
        let m = parse_err(&text);
        assert_names(
            &m,
            "airfoil_position.labels",
            line_of(&text, "labels: [round]"),
        );
    }

    #[test]
    fn numbers_must_be_finite_numbers_in_their_range() {
        for (from, to, path) in [
            (
                "values: [2.0, 1.0]",
                "values: [2.0, .nan]",
                "outer_shape_bem.chord.values[1]",
            ),
            (
                "values: [2.0, 1.0]",
                "values: [2.0, -1.0]",
                "outer_shape_bem.chord.values[1]",
            ),
            (
                "values: [2.0, 1.0]",
                "values: [2.0, one]",
                "outer_shape_bem.chord.values[1]",
            ),
            (
                "values: [0.01, 0.005]",
                "values: [0.01, -0.005]",
                "layers[0].thickness.values[1]",
            ),
            ("rho: 130.", "rho: 0", "materials[2].rho"),
            ("E: 1.2e+8", "E: -1.2e+8", "materials[2].E"),
            ("diameter: 4.0", "diameter: .inf", "components.hub.diameter"),
        ] {
            let text = with(from, to);
            let m = parse_err(&text);
            assert_names(&m, path, line_of(&text, to));
        }
    }

    #[test]
    fn names_that_refer_to_nothing_are_refused() {
        for (from, to, path, says) in [
            (
                "material: foam",
                "material: cork",
                "layers[3].material",
                "no material named `cork`",
            ),
            (
                "web: spar",
                "web: aft",
                "layers[4].web",
                "no web named `aft`",
            ),
            (
                "labels: [round, round]",
                "labels: [round, square]",
                "airfoil_position.labels[1]",
                "no airfoil named `square`",
            ),
            (
                "start_nd_arc: {fixed: cap}",
                "start_nd_arc: {fixed: cup}",
                "layers[3].start_nd_arc.fixed",
                "found `cup`",
            ),
            (
                "end_nd_arc: {fixed: nose}",
                "end_nd_arc: {fixed: filler}",
                "layers[3].end_nd_arc.fixed",
                "the layer itself",
            ),
        ] {
            let text = with(from, to);
            let m = parse_err(&text);
            assert_names(&m, path, line_of(&text, to));
            assert!(m.contains(says), "{m}");
        }
    }

    #[test]
    fn a_name_given_twice_is_ambiguous() {
        let text = with("  - name: carbon", "  - name: glass");
        let m = parse_err(&text);
        assert_names(&m, "materials[1]", line_of(GOOD, "  - name: carbon"));
        assert!(m.contains("a second material named `glass`"), "{m}");
    }

    #[test]
    fn a_material_must_match_its_kind() {
        let text = with("orth: 1.0", "orth: 0");
        let m = parse_err(&text);
        assert_names(&m, "materials[1].E", line_of(&text, "E: [1.2e+11"));
        let text = with("E: 1.2e+8", "E: [1.2e+8, 1.0e+8]");
        let m = parse_err(&text.replacen("orth: 0", "orth: 1", 1));
        assert!(m.contains("materials[2].E: expected three numbers"), "{m}");
        let text = with("orth: 0", "orth: 2");
        assert!(parse_err(&text).contains("materials[2].orth: expected 0 (isotropic) or 1"));
    }

    #[test]
    fn a_layer_with_a_width_and_nothing_to_anchor_it_is_refused() {
        let text = with("                midpoint_nd_arc: {fixed: LE}\n", "");
        let m = parse_err(&text);
        assert_names(
            &m,
            "internal_structure_2d_fem.layers[2]",
            line_of(&text, "name: nose"),
        );
        assert!(m.contains("expected the layer's position"), "{m}");
    }

    #[test]
    fn a_missing_rotor_quantity_is_named() {
        let m = parse_err(&with("    number_of_blades: 3\n", "    rated_power: 1.0\n"));
        assert!(m.contains("assembly.number_of_blades: missing"), "{m}");
        let m = parse_err(&with(
            "    number_of_blades: 3",
            "    number_of_blades: 2.5",
        ));
        assert!(
            m.contains("assembly.number_of_blades: expected an integer"),
            "{m}"
        );
        let m = parse_err(&with(
            "    hub:\n        diameter: 4.0\n        cone_angle: 0.05\n",
            "",
        ));
        assert!(m.contains("components.hub: missing"), "{m}");
    }

    #[test]
    fn broken_yaml_names_its_line_and_nothing_panics() {
        let text = with("rho: 1600.0", "rho: [1600.0");
        let m = parse_err(&text);
        assert!(m.starts_with("t.yaml:"), "{m}");
        assert!(m.contains("not valid YAML"), "{m}");
        assert!(parse_err("").contains("empty"));
        assert!(parse_err("just text").contains("the document: expected a mapping"));
        assert!(parse_err("components: 3\n").contains("components: expected a mapping"));
        // Every prefix of a good file fails cleanly or reads.
        for end in (0..GOOD.len())
            .filter(|&i| GOOD.is_char_boundary(i))
            .step_by(7)
        {
            let _ = parse(&GOOD[..end], "t.yaml");
        }
    }

    #[test]
    fn aliases_that_expand_without_bound_are_refused() {
        let mut text = String::from("a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n");
        for i in 1..12 {
            let p = i - 1;
            text.push_str(&format!(
                "a{i}: &a{i} [*a{p}, *a{p}, *a{p}, *a{p}, *a{p}, *a{p}, *a{p}, *a{p}, *a{p}, *a{p}]\n"
            ));
        }
        let m = parse_err(&text);
        assert!(m.contains("not valid YAML"), "{m}");
    }
}
