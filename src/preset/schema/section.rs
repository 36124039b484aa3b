//! The `[section]` table: the cross-section's properties, given directly, from a table, or from
//! a laminate layup on a thin-walled contour.

use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SectionSource {
    Direct,
    Table,
    Layup,
}

impl SectionSource {
    /// As written in a preset.
    pub fn name(self) -> &'static str {
        match self {
            SectionSource::Direct => "direct",
            SectionSource::Table => "table",
            SectionSource::Layup => "layup",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Section {
    pub source: SectionSource,
    /// Ply angle θ (deg). The paper's blade: the CAS angle, `[θ]` upper wall, `[−θ]` lower wall
    /// (table and layup sources; unset: [`PAPER_PLY_ANGLE`]). A WindIO blade: the fibre angle
    /// given to the layers `rotate_layers` over `rotate_span` (unset: the ontology's own
    /// angles stand), docs/model.md §11.12.
    pub ply_angle: Option<f64>,
    /// The WindIO layers `ply_angle` turns, by name (empty: the spar caps, every shell layer
    /// whose name has "spar" and "cap").
    pub rotate_layers: Vec<String>,
    /// The span fractions `[from, to]` over which `ply_angle` turns them (inclusive).
    pub rotate_span: [f64; 2],
    /// A WindIO blade's trailing-edge fill: the material (a name in the file's `materials`;
    /// empty: none) that fills the cavity between the skins over the last
    /// `trailing_edge_fill_length` m of the chord, at the stations within
    /// `trailing_edge_fill_span` (docs/model.md §11.12).
    pub trailing_edge_fill: String,
    /// m, along the chord from the trailing edge.
    pub trailing_edge_fill_length: f64,
    /// Span fractions `[from, to]` (inclusive).
    pub trailing_edge_fill_span: [f64; 2],
    /// m (kg/m). Ignored by the layup source, which computes it from the contour.
    pub mass_per_length: f64,
    /// I (kg·m), polar mass moment about the elastic axis per length.
    pub polar_inertia: f64,
    /// K_A² (m²).
    pub ka2: f64,
    /// K_m1² (m²), thickness direction.
    pub km1_2: f64,
    /// K_m2² (m²), chordwise.
    pub km2_2: f64,
    /// Chord c (m).
    pub chord: f64,
    /// e_a = x_EA − x_AC (m), positive when the elastic axis is aft of the aerodynamic centre.
    pub ea_offset: f64,
    /// d = x_cg − x_EA (m), positive aft.
    pub cg_offset: f64,
    /// Torsion stiffness C22 (N·m²), direct source.
    pub c22: f64,
    /// Bending–twist coupling C23 (N·m²), direct source.
    pub c23: f64,
    /// Flap bending stiffness C33 (N·m²), direct source.
    pub c33: f64,
    pub layup: Layup,
    pub contour: Contour,
}

/// Ply material and lamination for `source = "layup"` (docs/model.md §2.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Layup {
    /// E11 (Pa), fibre direction.
    pub e11: f64,
    /// E22 (Pa), transverse.
    pub e22: f64,
    /// ν12.
    pub nu12: f64,
    /// G12 (Pa).
    pub g12: f64,
    /// Ply density ρ (kg/m³).
    pub density: f64,
    /// Ply thickness (m).
    pub ply_thickness: f64,
    /// Plies per wall.
    pub plies: usize,
    /// Non-structural mass per length (kg/m), e.g. leading-edge ballast.
    pub nonstructural_mass: f64,
    /// Its chordwise position relative to the elastic axis (m, positive aft).
    pub nonstructural_position: f64,
}

use crate::physics::laminate;
pub use crate::physics::laminate::ContourShape;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Contour {
    pub shape: ContourShape,
    /// Box mid-line width (m).
    pub width: f64,
    /// Box mid-line height (m).
    pub height: f64,
    /// Ellipse chordwise semi-axis (m).
    pub a: f64,
    /// Ellipse thickness semi-axis (m).
    pub b: f64,
}

/// The paper's blade's ply angle (deg) unless a preset sets one: the angle of the paper's
/// figures and of Table 1's middle column.
pub const PAPER_PLY_ANGLE: f64 = 45.0;

impl Section {
    /// The paper's blade's ply angle (deg): the preset's, else [`PAPER_PLY_ANGLE`].
    pub fn paper_ply_angle(&self) -> f64 {
        self.ply_angle.unwrap_or(PAPER_PLY_ANGLE)
    }
}

impl Default for Section {
    fn default() -> Self {
        Section {
            source: SectionSource::Table,
            ply_angle: None,
            rotate_layers: Vec::new(),
            rotate_span: [0.0, 1.0],
            trailing_edge_fill: String::new(),
            trailing_edge_fill_length: 0.2,
            trailing_edge_fill_span: [0.0, 1.0],
            mass_per_length: 0.06377,
            polar_inertia: 2.3e-6,
            ka2: 3.6e-5,
            km1_2: 1.4e-6,
            km2_2: 3.47e-5,
            chord: 0.01833,
            ea_offset: -0.01833 / 4.0,
            cg_offset: 0.0,
            // The paper's Table 1 at 45°, units corrected (docs/model.md §2).
            c22: 0.90509,
            c23: -0.15919,
            c33: 0.45931,
            layup: Layup::default(),
            contour: Contour::default(),
        }
    }
}

impl Layup {
    /// The paper's laminate (docs/model.md §2.1): its glass/epoxy ply and six 0.127 mm plies per wall.
    pub const PAPER: Layup = Layup {
        e11: laminate::PAPER_MATERIAL.e11,
        e22: laminate::PAPER_MATERIAL.e22,
        nu12: laminate::PAPER_MATERIAL.nu12,
        g12: laminate::PAPER_MATERIAL.g12,
        density: laminate::PAPER_DENSITY,
        ply_thickness: laminate::PAPER_PLY_THICKNESS,
        plies: laminate::PAPER_PLIES,
        nonstructural_mass: 0.0,
        nonstructural_position: 0.0,
    };
}

impl Default for Layup {
    fn default() -> Self {
        Layup::PAPER
    }
}

impl Contour {
    /// The flat box whose layup reproduces the paper's Table 1 (docs/model.md §2): mid-line
    /// 18.33 × 2.470 mm.
    pub const PAPER_BOX: Contour = Contour {
        shape: laminate::PAPER_BOX.shape,
        width: laminate::PAPER_BOX.width,
        height: laminate::PAPER_BOX.height,
        a: laminate::PAPER_BOX.a,
        b: laminate::PAPER_BOX.b,
    };
}

impl Default for Contour {
    fn default() -> Self {
        Contour::PAPER_BOX
    }
}
