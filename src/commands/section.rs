//! `flutterscope section`: the layup section (docs/model.md §2.1) of a preset, whatever its
//! `section.source` says — laminate A matrices, reduced wall stiffnesses, C22/C23/C33 and the mass
//! properties; with `--vary KEY=A:B:STEP`, C22/C23/C33 over a grid like the paper's Table 1.

use crate::commands::{parse_vary, print_json, print_text};
use crate::error::{Error, Result};
use crate::model::section::layup_input;
use crate::physics::blade::windio::layup_section as layup_station;
use crate::physics::cross_section::SectionProperties;
use crate::physics::laminate::{layup_section, LayupSection, Stiffness3, WallLaminate};
use crate::physics::section::SectionProps;
use crate::preset::{key_spec, ContourShape, SectionSource, ValidPreset};
use serde::Serialize;
use std::path::Path;

/// The header line's note: this command evaluates the layup even when the model does not.
fn source_note(p: &ValidPreset) -> String {
    let source = p.section.source.name();
    if p.tabulated_blade().is_some() {
        format!(
            "always evaluated from the layup; the model uses the {} blade of blade.file = \"{}\", \
             not these",
            p.blade.source.name(),
            p.blade.file
        )
    } else if p.section.source == SectionSource::Layup {
        "section.source = \"layup\": these are the properties the model uses".into()
    } else {
        format!(
            "always evaluated from the layup; the model uses section.source = \"{source}\", not these"
        )
    }
}

#[derive(Serialize)]
struct SectionReport<'a> {
    preset: &'a str,
    evaluated: &'static str,
    preset_section_source: &'static str,
    section: LayupSection,
}

#[derive(Serialize)]
struct VaryReport<'a> {
    preset: &'a str,
    evaluated: &'static str,
    preset_section_source: &'static str,
    key: String,
    values: Vec<f64>,
    sections: Vec<LayupSection>,
}

pub fn run(p: &ValidPreset, vary: Option<&str>, json: bool, plot: Option<&Path>) -> Result<()> {
    if plot.is_some() && vary.is_none() {
        return Err(Error::usage(
            "section --plot draws C22/C23/C33 over a grid: add --vary KEY=A:B:STEP, e.g. section.ply_angle=0:90:15",
        ));
    }
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    match vary {
        None => {
            let s = layup_section(&layup_input(p))?;
            if json {
                print_json(&SectionReport {
                    preset: p.display_name(),
                    evaluated: "layup",
                    preset_section_source: p.section.source.name(),
                    section: s,
                })
            } else {
                print_text(&section_text(p, &s))
            }
        }
        Some(spec) => {
            let (key, values) = parse_vary(spec)?;
            let sections = vary_sections(p, &key, &values)?;
            if let Some(path) = plot {
                let fig = crate::plot::from_results::section_grid(
                    p.display_name(),
                    &key,
                    &values,
                    &sections,
                );
                crate::plot::write(&fig, path)?;
                eprintln!("plot written to {}", path.display());
            }
            if json {
                print_json(&VaryReport {
                    preset: p.display_name(),
                    evaluated: "layup",
                    preset_section_source: p.section.source.name(),
                    key,
                    values,
                    sections,
                })
            } else {
                print_text(&vary_text(p, &key, &values, &sections))
            }
        }
    }
}

/// The layup section at every grid value of `key` (range- and cross-checked like `--set`). A
/// key the model does not use for this blade (the ply angle of a tabulated blade) is varied
/// all the same: the layup is evaluated whatever the blade uses.
pub fn vary_sections(p: &ValidPreset, key: &str, values: &[f64]) -> Result<Vec<LayupSection>> {
    let spec = key_spec(key)?;
    values
        .iter()
        .map(|&v| {
            spec.check(&p.origin, v)?;
            layup_section(&layup_input(&p.edited(|q| (spec.set)(q, v))?))
        })
        .collect()
}

fn matrix_lines(out: &mut String, title: &str, a: &Stiffness3) {
    out.push_str(&format!("  {title}\n"));
    for row in a {
        out.push_str(&format!(
            "    {:>13.5e} {:>13.5e} {:>13.5e}\n",
            row[0], row[1], row[2]
        ));
    }
}

fn wall_line(name: &str, w: &WallLaminate) -> String {
    format!(
        "  {name:<22} K11 = {:>12.5e}  K12 = {:>12.5e}  K22 = {:>12.5e}\n",
        w.k.k11, w.k.k12, w.k.k22
    )
}

fn contour_description(p: &ValidPreset) -> String {
    let c = &p.section.contour;
    match c.shape {
        ContourShape::Box => format!(
            "box {:.4} × {:.4} mm (mid-line)",
            c.width * 1e3,
            c.height * 1e3
        ),
        ContourShape::Ellipse => format!(
            "ellipse a = {:.4} mm, b = {:.4} mm (mid-line)",
            c.a * 1e3,
            c.b * 1e3
        ),
        ContourShape::Paper => format!(
            "paper Eq. (1) mid-line, e = chord/4 = {:.4} mm",
            p.section.chord / 4.0 * 1e3
        ),
    }
}

/// The single-section report.
pub fn section_text(p: &ValidPreset, s: &LayupSection) -> String {
    let mut o = String::new();
    let m = &s.material;
    let sp = &s.props;
    o.push_str(&format!(
        "section of {} — layup (CLT + thin-walled closed contour, docs/model.md §2.1)\n  {}\n\n",
        p.display_name(),
        source_note(p)
    ));
    o.push_str(&format!(
        "ply        E11 = {:.4} GPa  E22 = {:.4} GPa  ν12 = {}  G12 = {:.4} GPa  ρ = {} kg/m³\n",
        m.e11 * 1e-9,
        m.e22 * 1e-9,
        m.nu12,
        m.g12 * 1e-9,
        s.density
    ));
    o.push_str(&format!(
        "laminate   {} × {:.4} mm plies, wall t = {:.4} mm; CAS [{:+}]{} upper (z ≥ 0), [{:+}]{} lower (z < 0);\n           side walls split at z = 0, each half with its side's angle\n",
        s.plies,
        s.ply_thickness * 1e3,
        s.wall_thickness * 1e3,
        s.upper.angle_deg,
        s.plies,
        s.lower.angle_deg,
        s.plies
    ));
    o.push_str(&format!(
        "Q (Pa)     Q11 = {:.5e}  Q22 = {:.5e}  Q12 = {:.5e}  Q66 = {:.5e}\n\n",
        s.q.q11, s.q.q22, s.q.q12, s.q.q66
    ));
    o.push_str("membrane stiffness A (N/m), order (x, s, xs)\n");
    matrix_lines(
        &mut o,
        &format!("upper wall [{:+}]", s.upper.angle_deg),
        &s.upper.a,
    );
    matrix_lines(
        &mut o,
        &format!("lower wall [{:+}]", s.lower.angle_deg),
        &s.lower.a,
    );
    o.push_str("reduced wall stiffness, hoop resultant free (N/m)\n");
    o.push_str(&wall_line(
        &format!("upper [{:+}]", s.upper.angle_deg),
        &s.upper,
    ));
    o.push_str(&wall_line(
        &format!("lower [{:+}]", s.lower.angle_deg),
        &s.lower,
    ));
    o.push('\n');
    o.push_str(&format!(
        "contour    {}\n           perimeter ∮ds = {:.6e} m, enclosed area A_e = {:.6e} m², {} polyline segments\n\n",
        contour_description(p),
        s.contour.perimeter,
        s.contour.enclosed_area,
        s.contour.segments
    ));
    o.push_str(&format!(
        "stiffness  C22 = {:>12.5e} N·m²  (torsion)\n           C23 = {:>12.5e} N·m²  (bending–twist; paper's sign)\n           C33 = {:>12.5e} N·m²  (flap bending)\n\n",
        sp.c22,
        shown_c23(sp),
        sp.c33
    ));
    o.push_str(&format!(
        "mass       m = {:.5e} kg/m (walls {:.5e}, non-structural {:.5e}), wall area A0 = {:.5e} m²\n",
        sp.m,
        s.structural_mass,
        sp.m - s.structural_mass,
        s.wall_area
    ));
    o.push_str(&format!(
        "           I = {:.5e} kg·m about the elastic axis (= contour centroid)\n           K_A² = {:.5e} m²  K_m1² = {:.5e} m²  K_m2² = {:.5e} m²\n",
        sp.i, sp.ka2, sp.km1_2, sp.km2_2
    ));
    o.push_str(&format!(
        "           chord = {} m  e_a = {} m  d = {:.5e} m\n",
        sp.chord, sp.ea_offset, sp.cg_offset
    ));
    o
}

/// The Table-1-like grid: one column per value, rows C22, C23, C33.
pub fn vary_text(p: &ValidPreset, key: &str, values: &[f64], sections: &[LayupSection]) -> String {
    let mut o = format!(
        "section of {} over {key} — layup (docs/model.md §2.1)\n  {}\n\n",
        p.display_name(),
        source_note(p)
    );
    let unit = crate::preset::key_spec(key).map(|k| k.unit).unwrap_or("");
    let head = if unit.is_empty() {
        key.to_string()
    } else {
        format!("{key} ({unit})")
    };
    o.push_str(&format!("{head:<26}"));
    for v in values {
        o.push_str(&format!("{:>13}", format!("{v}")));
    }
    o.push('\n');
    type Pick = fn(&LayupSection) -> f64;
    let rows: [(&str, Pick); 3] = [
        ("C22 (N·m²)", |s| s.props.c22),
        ("C23 (N·m²)", |s| shown_c23(&s.props)),
        ("C33 (N·m²)", |s| s.props.c33),
    ];
    for (name, pick) in rows {
        o.push_str(&format!("{name:<26}"));
        for s in sections {
            o.push_str(&format!("{:>13.5e}", pick(s)));
        }
        o.push('\n');
    }
    o
}

/// C23 as reported: it vanishes at 0° and 90° by symmetry, where the trigonometry leaves
/// round-off (≈1e-17 of C22, C33); print that as the zero it is. JSON keeps the raw value.
fn shown_c23(p: &SectionProps) -> f64 {
    if p.c23.abs() < 1e-12 * p.c22.abs().max(p.c33.abs()) {
        0.0
    } else {
        p.c23
    }
}

/// A WindIO blade's section at a span fraction, as its layup gives it (docs/model.md §11.12).
#[derive(Serialize)]
struct LayupStationReport<'a> {
    preset: &'a str,
    file: &'a str,
    /// Span fraction.
    eta: f64,
    /// The fibre angle the preset's ply turn gives here (deg), `None`: the ontology's own.
    ply_angle_deg: Option<f64>,
    turned_layers: Vec<String>,
    /// The trailing-edge fill laid here: its material and its length along the chord (m).
    trailing_edge_fill: Option<(String, f64)>,
    /// Elements of the section mesh and the mass the mesher cut where the walls meet (kg/m).
    elements: usize,
    clipped_mass: f64,
    /// About the reference (pitch) axis, BeamDyn's section axes (x₁ toward the suction side,
    /// x₂ toward the trailing edge).
    stiffness: [[f64; 6]; 6],
    mass_matrix: [[f64; 6]; 6],
    properties: SectionProperties,
    /// The bend–twist coupling over √(EI_flap·GJ) (positive: downwind bending twists toward
    /// feather).
    coupling_ratio: f64,
}

/// `section --at ETA` on a WindIO blade: the section at span fraction `eta` from the layup, with
/// the preset's ply turn; `--plot` draws its mesh coloured by material.
pub fn run_at(p: &ValidPreset, eta: f64, json: bool, plot: Option<&Path>) -> Result<()> {
    let layup = p
        .tabulated_blade()
        .and_then(|b| b.layup.clone())
        .ok_or_else(|| {
            Error::usage(format!(
                "section --at draws a WindIO blade's section from its layup; {} has blade.source \
                 = \"{}\" (without --at, section evaluates the paper's layup keys)",
                p.display_name(),
                p.blade.source.name()
            ))
        })?;
    if !(0.0..=1.0).contains(&eta) {
        return Err(Error::usage(format!(
            "section --at {eta}: expected a span fraction in [0, 1]"
        )));
    }
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
    }
    let turn = layup.turn.as_ref().filter(|t| t.acts_at(eta));
    let fill = layup.fill.as_ref().filter(|f| f.acts_at(eta));
    let s = layup_station(&layup.windio, eta, turn, fill, None)?;
    let props = s.properties;
    let report = LayupStationReport {
        preset: p.display_name(),
        file: &layup.windio.path,
        eta,
        ply_angle_deg: turn.map(|t| t.angle.to_degrees()),
        turned_layers: turn.map(|t| t.layers.clone()).unwrap_or_default(),
        trailing_edge_fill: fill.map(|f| (f.material.clone(), f.length)),
        elements: s.mesh.mesh.elements.len(),
        clipped_mass: s.mesh.clipped_mass,
        stiffness: s.matrices.stiffness,
        mass_matrix: s.matrices.mass,
        coupling_ratio: s.flap_twist_ratio(),
        properties: props,
    };
    if let Some(path) = plot {
        let names: Vec<&str> = layup
            .windio
            .materials
            .iter()
            .map(|m| m.name.as_str())
            .collect();
        let fig =
            crate::plot::from_results::layup_section(p.display_name(), eta, &s.mesh.mesh, &names);
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    if json {
        print_json(&report)
    } else {
        print_text(&station_text(&report))
    }
}

fn station_text(r: &LayupStationReport) -> String {
    let p = &r.properties;
    let c = p.bending_torsion;
    let mut out = format!(
        "{} — section at {:.1} % span from the layup of {}\n",
        r.preset,
        100.0 * r.eta,
        r.file
    );
    match r.ply_angle_deg {
        Some(a) => {
            out += &format!(
                "  fibres of {} turned to {a:+.2}°\n",
                r.turned_layers.join(", ")
            )
        }
        None => out += "  the ontology's own fibre angles\n",
    }
    if let Some((material, length)) = &r.trailing_edge_fill {
        out += &format!("  trailing edge filled with {material} over its last {length} m\n");
    }
    out += &format!(
        "  mesh: {} elements; mass cut where the walls meet {:.3} kg/m\n\n",
        r.elements, r.clipped_mass
    );
    out += &format!("  mass per length     {:>12.4} kg/m\n", p.mass);
    out += &format!("  EA                  {:>12.5e} N\n", p.ea);
    out += &format!("  EI flap (about x₂)  {:>12.5e} N·m²\n", c[1][1]);
    out += &format!("  EI edge (about x₁)  {:>12.5e} N·m²\n", c[0][0]);
    out += &format!("  GJ                  {:>12.5e} N·m²\n", p.gj);
    out += &format!(
        "  flap–twist coupling {:>12.5e} N·m²   g/√(EI_flap·GJ) = {:+.4} (+: feather under downwind bending)\n",
        c[1][2], r.coupling_ratio
    );
    out += &format!(
        "  principal EI        {:>12.5e} {:.5e} N·m², first axis at {:+.2}° from x₁\n",
        p.ei_principal[0],
        p.ei_principal[1],
        p.principal_angle.to_degrees()
    );
    let at =
        |name: &str, v: [f64; 2]| format!("  {name:<19} x₁ {:+.4} m  x₂ {:+.4} m\n", v[0], v[1]);
    out += "\n  centres from the pitch axis (x₁ toward the suction side, x₂ toward the trailing edge):\n";
    out += &at("elastic centre", p.elastic_centre);
    out += &at("shear centre", p.shear_centre);
    out += &at("centre of mass", p.centre_of_mass);
    out += "\n  6×6 stiffness about the pitch axis (BeamDyn order: shear x₁, x₂, extension, bending x₁, x₂, torsion):\n";
    for row in &r.stiffness {
        out += "   ";
        for v in row {
            out += &format!(" {v:>12.4e}");
        }
        out += "\n";
    }
    out
}
