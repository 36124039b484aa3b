//! A blade's sections from its WindIO layup (docs/model.md §11.12): at a span station the
//! airfoil blended in relative thickness, scaled by the chord about the pitch axis, the layers
//! and webs placed on it as the ontology defines, meshed ([`mesh_layup`]) and analysed
//! ([`analyse_reusing`]) for the 6×6 stiffness and mass about the reference axis, in BeamDyn's
//! section axes (the frame turned by the twist), the form §11.5 reads from a BeamDyn blade file.
//! A station whose fibres turn keeps its mesh and the symbolic part of its factorisation: only
//! the plies' stiffness changes.

use super::beamdyn::from_beamdyn;
use super::BladeTable;
use crate::error::{Error, Result};
use crate::formats::beamdyn::{BeamDynBlade, BeamDynPrimary, BeamDynStation, KeyPoint};
use crate::formats::windio::arc::{place_layers, place_web, Contour, Station};
use crate::formats::windio::{Elastic, Material, WindIo};
use crate::physics::cross_section::layup::{
    mesh_layup, Layup, LayupMesh, Meshing, ShellLayer, WebLayer, WebLayup,
};
use crate::physics::cross_section::{
    analyse_reusing, BeamMatrices, Factorisation, Orthotropic, SectionProperties,
};
use rayon::prelude::*;
use std::sync::Arc;

/// Fibres turned from the ontology's own angles: `angle` (rad, toward the leading edge, as a
/// ply's own angle) given to the layers named in `layers` at the stations within `span`
/// (fractions of the span, inclusive).
#[derive(Debug, Clone, PartialEq)]
pub struct PlyTurn {
    pub angle: f64,
    pub layers: Vec<String>,
    pub span: [f64; 2],
}

impl PlyTurn {
    /// The layers a turn applies to unless a preset names them: the spar caps, every shell
    /// layer whose name has both "spar" and "cap" in it, in any case (`Spar_Cap_SS`,
    /// `Spar_cap_ps`, as the IEA ontologies name them).
    pub fn spar_caps(w: &WindIo) -> Vec<String> {
        w.blade
            .structure
            .layers
            .iter()
            .filter(|l| {
                let n = l.name.to_lowercase();
                l.web.is_none() && n.contains("spar") && n.contains("cap")
            })
            .map(|l| l.name.clone())
            .collect()
    }
}

/// A trailing-edge fill: at the stations within `span` (fractions of the span, inclusive) the
/// cavity between the skins' inner faces over the last `length` (m, along the chord from the
/// trailing edge) is filled with `material` (a name in the file's `materials`): the bond line
/// where the two shells are glued, which an ontology's layers do not describe, or the filler a
/// section code closes the trailing edge with (docs/model.md §11.12).
#[derive(Debug, Clone, PartialEq)]
pub struct TrailingEdgeFill {
    pub material: String,
    pub length: f64,
    pub span: [f64; 2],
}

impl TrailingEdgeFill {
    /// Whether the fill is laid at span fraction `eta`.
    pub fn acts_at(&self, eta: f64) -> bool {
        within(self.span, eta)
    }
}

/// Whether `[from, to]` are span fractions with 0 ≤ from ≤ to ≤ 1 (a ply turn's or a fill's).
pub fn is_span([from, to]: [f64; 2]) -> bool {
    (0.0..=1.0).contains(&from) && (0.0..=1.0).contains(&to) && from <= to
}

/// Whether span fraction `eta` lies within `span` (inclusive).
fn within([from, to]: [f64; 2], eta: f64) -> bool {
    (from..=to).contains(&eta)
}

/// One station's section from the layup.
#[derive(Debug, Clone, PartialEq)]
pub struct LayupSection {
    /// Span fraction.
    pub eta: f64,
    /// About the reference (pitch) axis, BeamDyn's section axes.
    pub matrices: BeamMatrices,
    /// Its stiffnesses, centres and mass, in the same axes.
    pub properties: SectionProperties,
    /// The layup as placed at this station, and its mesh.
    pub layup: Layup,
    pub mesh: LayupMesh,
    /// The symbolic factorisation of the mesh's warping matrix, for the same mesh turned.
    pub factorisation: Factorisation,
}

impl LayupSection {
    /// The coupling of flap bending (about x₂) and torsion over √(EI_flap·GJ), signed so that
    /// a positive ratio twists the blade toward feather when it bends downwind: in BeamDyn's
    /// section axes a positive K₅₆ of the bending–torsion stiffness (docs/model.md §11.12).
    pub fn flap_twist_ratio(&self) -> f64 {
        let c = self.properties.bending_torsion;
        c[1][2] / (c[1][1] * c[2][2]).sqrt()
    }
}

/// A WindIO material as the section analysis takes it. An isotropic material given with its own
/// shear modulus keeps it.
pub fn orthotropic(m: &Material) -> Orthotropic {
    match m.elastic {
        Elastic::Isotropic { e, g, nu } => {
            let base = Orthotropic::isotropic(e, nu, m.rho);
            match g {
                Some(g) => Orthotropic {
                    g12: g,
                    g13: g,
                    g23: g,
                    ..base
                },
                None => base,
            }
        }
        Elastic::Orthotropic { e, g, nu } => Orthotropic {
            e1: e[0],
            e2: e[1],
            e3: e[2],
            g12: g[0],
            g13: g[1],
            g23: g[2],
            nu12: nu[0],
            nu13: nu[1],
            nu23: nu[2],
            rho: m.rho,
        },
    }
}

/// The station's layup at span fraction `eta`: its contour in the chord frame about the pitch
/// axis, the shell's layers with their arcs (and `fill`'s, innermost, where it is laid), the
/// webs present there (a web whose layers all have zero thickness is absent) and the materials
/// in the file's order.
pub fn station_layup(
    w: &WindIo,
    eta: f64,
    turn: Option<&PlyTurn>,
    fill: Option<&TrailingEdgeFill>,
) -> Result<Layup> {
    let file = w.path.as_str();
    let shape = &w.blade.outer_shape;
    let (x, y) = w.station_shape(eta, file)?;
    let contour = Contour::new(
        &x,
        &y,
        shape.chord.linear(eta),
        shape.pitch_axis.linear(eta),
    )
    .map_err(|e| Error::format(file, shape.chord.line, format!("at span {eta}: {e}")))?;
    let at = Station {
        eta,
        twist: shape.twist.linear(eta),
        contour: &contour,
    };
    let structure = &w.blade.structure;
    let material_index = |name: &str| {
        w.materials
            .iter()
            .position(|m| m.name == name)
            .expect("the reader checks every layer's material")
    };
    let fibre = |l: &crate::formats::windio::Layer| -> f64 {
        match turn {
            Some(t) if t.layers.contains(&l.name) && t.acts_at(eta) => t.angle,
            _ => l.fiber_orientation.as_ref().map_or(0.0, |d| d.linear(eta)),
        }
    };
    let arcs = place_layers(&structure.layers, &at, file)?;
    let mut shell: Vec<ShellLayer> = structure
        .layers
        .iter()
        .zip(&arcs)
        .filter_map(|(l, arc)| {
            arc.map(|(start, end)| ShellLayer {
                material: material_index(&l.material),
                thickness: l.thickness.linear(eta),
                fibre_angle: fibre(l),
                start,
                end,
                fill_to: None,
            })
        })
        .collect();
    if let Some(f) = fill.filter(|f| f.acts_at(eta)) {
        let edge = contour.points()[0][0];
        let (suction, pressure) = contour.across_chord(edge - f.length).ok_or_else(|| {
            station_error(
                w,
                eta,
                format!(
                    "section.trailing_edge_fill_length = {} m: the fill would reach past the \
                     leading edge of a {:.3} m chord",
                    f.length,
                    shape.chord.linear(eta)
                ),
            )
        })?;
        shell.push(ShellLayer {
            material: material_index(&f.material),
            thickness: 0.0,
            fibre_angle: 0.0,
            start: pressure,
            end: suction,
            fill_to: Some(edge - f.length),
        });
    }
    let mut webs = Vec::new();
    for web in &structure.webs {
        let layers: Vec<WebLayer> = structure
            .layers
            .iter()
            .filter(|l| l.web.as_deref() == Some(web.name.as_str()))
            .map(|l| WebLayer {
                material: material_index(&l.material),
                thickness: l.thickness.linear(eta),
                fibre_angle: fibre(l),
            })
            .collect();
        if layers.iter().all(|l| l.thickness <= 0.0) {
            continue;
        }
        let (start, end) = place_web(web, &at, file)?;
        webs.push(WebLayup { start, end, layers });
    }
    Ok(Layup {
        contour: contour.points().to_vec(),
        leading_edge: contour.leading_edge(),
        shell,
        webs,
        materials: w.materials.iter().map(orthotropic).collect(),
    })
}

/// The section at span fraction `eta` from the layup, meshed as `meshing` says (by default
/// [`Meshing::for_perimeter`]).
pub fn layup_section(
    w: &WindIo,
    eta: f64,
    turn: Option<&PlyTurn>,
    fill: Option<&TrailingEdgeFill>,
    meshing: Option<Meshing>,
) -> Result<LayupSection> {
    meshed_section(w, eta, station_layup(w, eta, turn, fill)?, meshing)
}

/// The section of `layup`, the layup at `eta`, meshed and analysed.
fn meshed_section(
    w: &WindIo,
    eta: f64,
    layup: Layup,
    meshing: Option<Meshing>,
) -> Result<LayupSection> {
    let perimeter: f64 = layup
        .contour
        .windows(2)
        .map(|p| (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]))
        .sum();
    let meshing = meshing.unwrap_or_else(|| Meshing::for_perimeter(perimeter));
    let mesh = mesh_layup(&layup, meshing).map_err(|e| at_station(w, eta, e))?;
    analysed(w, eta, layup, mesh, None)
}

/// The section at `held`'s station with its fibres turned by `turn`: `held`'s mesh with the new
/// fibre angles, analysed on its factorisation's pattern (the same as a new mesh would give,
/// at the cost of the analysis alone). Meshed anew if the layup differs in more than angles.
fn turned_section(
    w: &WindIo,
    held: &LayupSection,
    turn: Option<&PlyTurn>,
    fill: Option<&TrailingEdgeFill>,
) -> Result<LayupSection> {
    let eta = held.eta;
    let layup = station_layup(w, eta, turn, fill)?;
    match held.mesh.turned(&held.layup, &layup) {
        Some(mesh) => analysed(w, eta, layup, mesh, Some(&held.factorisation)),
        None => meshed_section(w, eta, layup, None),
    }
}

fn analysed(
    w: &WindIo,
    eta: f64,
    layup: Layup,
    mesh: LayupMesh,
    reuse: Option<&Factorisation>,
) -> Result<LayupSection> {
    let (matrices, factorisation) =
        analyse_reusing(&mesh.mesh, [0.0, 0.0], reuse).map_err(|e| at_station(w, eta, e))?;
    let properties = matrices.properties().map_err(|e| at_station(w, eta, e))?;
    Ok(LayupSection {
        eta,
        matrices,
        properties,
        layup,
        mesh,
        factorisation,
    })
}

fn at_station(w: &WindIo, eta: f64, e: Error) -> Error {
    station_error(w, eta, e.to_string())
}

/// What went wrong at the station at span fraction `eta`.
fn station_error(w: &WindIo, eta: f64, message: String) -> Error {
    Error::Invalid {
        origin: format!("{}: the section at span {eta}", w.path),
        message,
    }
}

/// A WindIO blade's layup as analysed: the file, the ply turn, the trailing-edge fill and each
/// station's section, at the stations of the structure's reference axis.
#[derive(Debug, Clone, PartialEq)]
pub struct LayupBlade {
    pub windio: Arc<WindIo>,
    pub turn: Option<PlyTurn>,
    pub fill: Option<TrailingEdgeFill>,
    pub sections: Vec<Arc<LayupSection>>,
}

impl PlyTurn {
    /// Whether the turn changes anything at span fraction `eta`.
    pub fn acts_at(&self, eta: f64) -> bool {
        within(self.span, eta)
    }
}

/// What a station's fibres are given by a turn: nothing outside its span.
fn turn_at(turn: Option<&PlyTurn>, eta: f64) -> Option<&PlyTurn> {
    turn.filter(|t| t.acts_at(eta))
}

impl LayupBlade {
    /// The blade of `windio` with its layers turned by `turn`, each station's section analysed
    /// (in parallel), or taken from `held` where its fibres are the same there: a new ply angle
    /// analyses only the stations it turns, on `held`'s meshes and factorisation patterns.
    pub fn new(
        windio: Arc<WindIo>,
        turn: Option<PlyTurn>,
        fill: Option<TrailingEdgeFill>,
        held: Option<&LayupBlade>,
    ) -> Result<LayupBlade> {
        if let Some(t) = &turn {
            check_turn(&windio, t)?;
        }
        if let Some(f) = &fill {
            check_fill(&windio, f)?;
        }
        let etas = &windio.blade.structure.reference_axis.z.grid;
        let held = held.filter(|h| {
            Arc::ptr_eq(&h.windio, &windio) && h.fill == fill && h.sections.len() == etas.len()
        });
        let sections = etas
            .par_iter()
            .enumerate()
            .map(|(k, &eta)| {
                let here = turn_at(turn.as_ref(), eta);
                match held {
                    Some(h) if turn_at(h.turn.as_ref(), eta) == here => Ok(h.sections[k].clone()),
                    Some(h) => {
                        turned_section(&windio, &h.sections[k], here, fill.as_ref()).map(Arc::new)
                    }
                    None => layup_section(&windio, eta, here, fill.as_ref(), None).map(Arc::new),
                }
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(LayupBlade {
            windio,
            turn,
            fill,
            sections,
        })
    }

    /// The blade as the beam takes it: BeamDyn's form (docs/model.md §11.5), each station's
    /// 6×6 about the reference axis in the section axes turned by the twist, the span the
    /// reference axis's `z`.
    pub fn table(&self) -> Result<BladeTable> {
        let w = &self.windio;
        let z = &w.blade.structure.reference_axis.z;
        let twist = &w.blade.outer_shape.twist;
        let key_points = self
            .sections
            .iter()
            .map(|s| KeyPoint {
                kp_xr: 0.0,
                kp_yr: 0.0,
                kp_zr: z.linear(s.eta),
                initial_twist_deg: twist.linear(s.eta).to_degrees(),
            })
            .collect::<Vec<_>>();
        let primary = BeamDynPrimary {
            kp_total: key_points.len(),
            members: vec![key_points],
            blade_file: w.path.clone(),
        };
        let blade = BeamDynBlade {
            path: w.path.clone(),
            damp_type: 0,
            mu: [0.0; 6],
            stations: self
                .sections
                .iter()
                .map(|s| BeamDynStation {
                    line: z.line,
                    eta: s.eta,
                    stiffness: s.matrices.stiffness,
                    mass: s.matrices.mass,
                })
                .collect(),
        };
        from_beamdyn(&primary, &blade, &w.path, 0.0)
    }

    /// The station nearest span fraction `eta`.
    pub fn nearest(&self, eta: f64) -> &LayupSection {
        self.sections
            .iter()
            .min_by(|a, b| (a.eta - eta).abs().total_cmp(&(b.eta - eta).abs()))
            .expect("a blade has stations")
    }
}

/// An error about the file `w` as the preset's keys read it.
fn file_error(w: &WindIo, message: String) -> Result<()> {
    Err(Error::Invalid {
        origin: w.path.clone(),
        message,
    })
}

/// `span`, the preset's `key`, is span fractions `[from, to]` within the blade.
fn check_span(w: &WindIo, key: &str, [from, to]: [f64; 2]) -> Result<()> {
    if !is_span([from, to]) {
        return file_error(
            w,
            format!("{key} = [{from}, {to}]: expected span fractions 0 ≤ from ≤ to ≤ 1"),
        );
    }
    Ok(())
}

/// A fill names a material the file has, a length > 0 and a span within the blade.
fn check_fill(w: &WindIo, f: &TrailingEdgeFill) -> Result<()> {
    let fail = |message: String| file_error(w, message);
    check_span(w, "section.trailing_edge_fill_span", f.span)?;
    if !(f.length.is_finite() && f.length > 0.0) {
        return fail(format!(
            "section.trailing_edge_fill_length = {}: expected a length > 0 (m, along the chord \
             from the trailing edge)",
            f.length
        ));
    }
    if !w.materials.iter().any(|m| m.name == f.material) {
        let names: Vec<&str> = w.materials.iter().map(|m| m.name.as_str()).collect();
        return fail(format!(
            "section.trailing_edge_fill = \"{}\" is no material of the file's materials; they \
             are: {}",
            f.material,
            names.join(", ")
        ));
    }
    Ok(())
}

/// A turn names layers the file has, on the shell, and a span within the blade.
fn check_turn(w: &WindIo, t: &PlyTurn) -> Result<()> {
    check_span(w, "section.rotate_span", t.span)?;
    if !t.angle.is_finite() {
        return file_error(
            w,
            format!("section.ply_angle = {}: expected a finite angle", t.angle),
        );
    }
    if t.layers.is_empty() {
        return file_error(
            w,
            "section.ply_angle turns no layer: the file has no spar caps (no shell layer named \
             with \"spar\" and \"cap\"); name the layers in section.rotate_layers"
                .into(),
        );
    }
    for name in &t.layers {
        if w.layer(name).is_none() {
            let names: Vec<&str> = w
                .blade
                .structure
                .layers
                .iter()
                .map(|l| l.name.as_str())
                .collect();
            return file_error(
                w,
                format!(
                    "section.rotate_layers names \"{name}\", which is no layer of \
                     components.blade.internal_structure_2d_fem.layers; the layers are: {}",
                    names.join(", ")
                ),
            );
        }
    }
    Ok(())
}
