//! Presets: the TOML description of a blade, its section, its operating point and the analysis
//! settings. One schema, unknown fields rejected, every value range-checked through one key table
//! ([`KEYS`]) that also serves `--set key=value` overrides and the numeric parameters that sweeps,
//! flutter searches and the explorer vary.
//!
//! Units at this edge: degrees for angles, rpm for rotor speed, SI otherwise. The physics layers
//! receive SI through the accessors at the bottom of this file.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A complete, validated description of one case. Every section and field has a default (the
/// paper's blade at its operating point), so a preset lists only what differs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Preset {
    pub meta: Meta,
    pub blade: Blade,
    pub section: Section,
    pub operating: Operating,
    pub structure: Structure,
    pub aero: Aero,
    pub simulation: Simulation,
    pub view: View,
    /// Where this preset came from (file path or `built-in NAME`), for error messages.
    #[serde(skip)]
    pub origin: String,
}

#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Meta {
    pub name: String,
    pub description: String,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Blade {
    /// Span L (m).
    pub length: f64,
    /// Hub radius r_hub (m); r = r_hub + x.
    pub hub_radius: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SectionSource {
    Direct,
    Table,
    Layup,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Section {
    pub source: SectionSource,
    /// CAS ply angle θ (deg): `[θ]` upper wall, `[−θ]` lower wall (table and layup sources).
    pub ply_angle: f64,
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

/// Ply material and lamination for `source = "layup"` (MODEL.md §2.1).
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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContourShape {
    /// Rectangle of mid-line `width × height`.
    Box,
    /// Ellipse of mid-line semi-axes `a` (chordwise) and `b` (thickness).
    Ellipse,
    /// The paper's "integration line" Eq. (1), scaled by e = chord/4.
    Paper,
}

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

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Inflow {
    /// V0 and ψ evaluated at the tip for every station (the paper).
    Tip,
    /// Each station at its own radius.
    Local,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Operating {
    /// Wind speed U (m/s).
    pub wind_speed: f64,
    /// Rotor speed Ω (rpm).
    pub rotor_speed: f64,
    /// Collective pitch β (deg), toward feather.
    pub pitch: f64,
    /// In-plane "tunnel" speed V_t (m/s), for fixed-wing validation.
    pub tunnel_speed: f64,
    /// Air density ρ_a (kg/m³).
    pub air_density: f64,
    /// Axial induction a_ind.
    pub induction: f64,
    pub inflow: Inflow,
    /// Pretwist at the root (deg), toward feather.
    pub twist_root: f64,
    /// Pretwist at the tip (deg), toward feather.
    pub twist_tip: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Form {
    Weak,
    Strong,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Structure {
    /// N, Galerkin modes per field.
    pub modes: usize,
    pub form: Form,
    /// η1, first-mode loss factor (C_s = (η1/ω1) K_e).
    pub loss_factor: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AeroModel {
    None,
    QuasiSteady,
    Theodorsen,
    Onera,
}

impl AeroModel {
    pub const ALL: [AeroModel; 4] = [
        AeroModel::None,
        AeroModel::QuasiSteady,
        AeroModel::Theodorsen,
        AeroModel::Onera,
    ];
    pub fn name(self) -> &'static str {
        match self {
            AeroModel::None => "none",
            AeroModel::QuasiSteady => "quasi-steady",
            AeroModel::Theodorsen => "theodorsen",
            AeroModel::Onera => "onera",
        }
    }
    /// The next model in the cycle none → quasi-steady → theodorsen → onera → none.
    pub fn next(self) -> AeroModel {
        let i = Self::ALL.iter().position(|m| *m == self).unwrap_or(0);
        Self::ALL[(i + 1) % Self::ALL.len()]
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Aero {
    pub model: AeroModel,
    /// Lift-curve slope a0 (1/rad) for quasi-steady and theodorsen.
    pub lift_slope: f64,
    /// Strip-theory stations (Gauss points along the span).
    pub stations: usize,
    /// Profile drag C_D0 for quasi-steady (the paper: 0).
    pub drag_coefficient: f64,
    pub onera: Onera,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OneraForcing {
    Coupled,
    Rigid,
}

/// ONERA stall-model coefficients (MODEL.md §5.3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Onera {
    pub forcing: OneraForcing,
    pub lambda_l: f64,
    pub a0l: f64,
    pub a_l: f64,
    pub r_l: f64,
    pub a_m: f64,
    pub r_m: f64,
    pub a_d: f64,
    pub r_d: f64,
    pub a_l1: f64,
    pub a_l2: f64,
    pub a_m1: f64,
    pub a_m2: f64,
    pub a_d1: f64,
    pub a_d2: f64,
    pub a_d3: f64,
    pub cm0: f64,
    pub cd0: f64,
    /// Stall onset α1 (rad).
    pub alpha1: f64,
    /// Full-stall angle α2 (rad).
    pub alpha2: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Start {
    Rest,
    Equilibrium,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Simulation {
    pub start: Start,
    /// Tip twist kick Δφ_tip (deg) added to the start state.
    pub kick_twist: f64,
    /// Tip flap kick Δu_tip (m) added to the start state.
    pub kick_flap: f64,
    /// Duration (s).
    pub duration: f64,
    /// Output samples per second.
    pub sample_rate: f64,
}

/// Explorer settings: slider ranges and steps (they do not change the physics).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct View {
    /// Upper end of the rotor-speed slider and of the Campbell diagram (rpm).
    pub rotor_speed_max: f64,
    /// Upper end of the wind-speed slider (m/s).
    pub wind_speed_max: f64,
    /// Upper end of the tunnel-speed slider (m/s).
    pub tunnel_speed_max: f64,
    /// The parameter the explorer selects when it opens this preset, and so the one its first
    /// boundary search runs along.
    pub select: Selected,
}

/// An explorer parameter a preset can select at start (`view.select`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Selected {
    PlyAngle,
    WindSpeed,
    TunnelSpeed,
    RotorSpeed,
    Pitch,
}

impl Selected {
    /// The preset key the parameter varies.
    pub fn key(self) -> &'static str {
        match self {
            Selected::PlyAngle => "section.ply_angle",
            Selected::WindSpeed => "operating.wind_speed",
            Selected::TunnelSpeed => "operating.tunnel_speed",
            Selected::RotorSpeed => "operating.rotor_speed",
            Selected::Pitch => "operating.pitch",
        }
    }
}

impl Default for Preset {
    fn default() -> Self {
        Preset {
            meta: Meta::default(),
            blade: Blade::default(),
            section: Section::default(),
            operating: Operating::default(),
            structure: Structure::default(),
            aero: Aero::default(),
            simulation: Simulation::default(),
            view: View::default(),
            origin: "defaults".into(),
        }
    }
}

impl Default for Blade {
    fn default() -> Self {
        Blade {
            length: 8.4455,
            hub_radius: 0.0,
        }
    }
}

impl Default for Section {
    fn default() -> Self {
        Section {
            source: SectionSource::Table,
            ply_angle: 45.0,
            mass_per_length: 0.06377,
            polar_inertia: 2.3e-6,
            ka2: 3.6e-5,
            km1_2: 1.4e-6,
            km2_2: 3.47e-5,
            chord: 0.01833,
            ea_offset: -0.01833 / 4.0,
            cg_offset: 0.0,
            // The paper's Table 1 at 45°, units corrected (MODEL.md §2).
            c22: 0.90509,
            c23: -0.15919,
            c33: 0.45931,
            layup: Layup::default(),
            contour: Contour::default(),
        }
    }
}

impl Default for Layup {
    fn default() -> Self {
        Layup {
            e11: 25.8e9,
            e22: 8.7e9,
            nu12: 0.34,
            g12: 3.5e9,
            density: 1672.0,
            ply_thickness: 0.127e-3,
            plies: 6,
            nonstructural_mass: 0.0,
            nonstructural_position: 0.0,
        }
    }
}

impl Default for Contour {
    fn default() -> Self {
        Contour {
            shape: ContourShape::Box,
            width: 0.01833,
            height: 0.00247,
            a: 0.01833 / 2.0,
            b: 0.00247 / 2.0,
        }
    }
}

impl Default for Operating {
    fn default() -> Self {
        Operating {
            wind_speed: 20.0,
            rotor_speed: 60.0,
            pitch: 10.0,
            tunnel_speed: 0.0,
            air_density: 1.225,
            induction: 0.0,
            inflow: Inflow::Tip,
            twist_root: 0.0,
            twist_tip: 0.0,
        }
    }
}

impl Default for Structure {
    fn default() -> Self {
        Structure {
            modes: 5,
            form: Form::Weak,
            loss_factor: 0.02,
        }
    }
}

impl Default for Aero {
    fn default() -> Self {
        Aero {
            model: AeroModel::QuasiSteady,
            lift_slope: 2.0 * std::f64::consts::PI,
            stations: 8,
            drag_coefficient: 0.0,
            onera: Onera::default(),
        }
    }
}

impl Default for Onera {
    fn default() -> Self {
        Onera {
            forcing: OneraForcing::Coupled,
            lambda_l: 0.17,
            a0l: 2.0 * std::f64::consts::PI,
            a_l: 0.30,
            r_l: 0.0324,
            a_m: 0.25,
            r_m: 0.0484,
            a_d: 0.25,
            r_d: 0.0484,
            a_l1: 4.4,
            a_l2: 2.4,
            a_m1: 0.15,
            a_m2: 0.6,
            a_d1: 0.0,
            a_d2: 0.5,
            a_d3: 2.0,
            cm0: 0.0,
            cd0: 0.014,
            alpha1: 0.1396,
            alpha2: 0.3142,
        }
    }
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation {
            start: Start::Rest,
            kick_twist: 0.0,
            kick_flap: 0.0,
            duration: 20.0,
            sample_rate: 200.0,
        }
    }
}

impl Default for View {
    fn default() -> Self {
        View {
            rotor_speed_max: 200.0,
            wind_speed_max: 40.0,
            tunnel_speed_max: 200.0,
            select: Selected::RotorSpeed,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The key table
// ---------------------------------------------------------------------------------------------

/// One numeric preset key: its dotted name, unit, allowed range and accessors.
pub struct KeySpec {
    pub key: &'static str,
    pub unit: &'static str,
    pub min: f64,
    pub max: f64,
    /// When true the lower bound itself is not allowed (e.g. a length must be > 0).
    pub min_open: bool,
    /// Integer-valued key (modes, stations, plies).
    pub integer: bool,
    pub get: fn(&Preset) -> f64,
    pub set: fn(&mut Preset, f64),
}

impl KeySpec {
    pub fn allowed(&self) -> String {
        let lo = if self.min_open { "(" } else { "[" };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        if self.integer {
            format!("integer in {lo}{}, {}]{unit}", self.min, self.max)
        } else {
            format!("{lo}{}, {}]{unit}", fmt_num(self.min), fmt_num(self.max))
        }
    }

    pub fn contains(&self, v: f64) -> bool {
        v.is_finite()
            && (if self.min_open {
                v > self.min
            } else {
                v >= self.min
            })
            && v <= self.max
            && (!self.integer || v.fract() == 0.0)
    }
}

fn fmt_num(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

macro_rules! real {
    ($key:literal, $unit:literal, $min:expr, $max:expr, open=$open:expr, $($f:ident).+) => {
        KeySpec {
            key: $key,
            unit: $unit,
            min: $min,
            max: $max,
            min_open: $open,
            integer: false,
            get: |p| p.$($f).+,
            set: |p, v| p.$($f).+ = v,
        }
    };
}

macro_rules! int {
    ($key:literal, $min:expr, $max:expr, $($f:ident).+) => {
        KeySpec {
            key: $key,
            unit: "",
            min: $min as f64,
            max: $max as f64,
            min_open: false,
            integer: true,
            get: |p| p.$($f).+ as f64,
            set: |p, v| p.$($f).+ = v.round().max(0.0) as usize,
        }
    };
}

/// Every numeric key with its allowed range. Enumerated keys (`section.source`, `aero.model`, …)
/// are checked by serde against their variants.
pub static KEYS: &[KeySpec] = &[
    real!("blade.length", "m", 0.0, 500.0, open = true, blade.length),
    real!(
        "blade.hub_radius",
        "m",
        0.0,
        100.0,
        open = false,
        blade.hub_radius
    ),
    real!(
        "section.ply_angle",
        "deg",
        0.0,
        90.0,
        open = false,
        section.ply_angle
    ),
    real!(
        "section.mass_per_length",
        "kg/m",
        0.0,
        1e5,
        open = true,
        section.mass_per_length
    ),
    real!(
        "section.polar_inertia",
        "kg·m",
        0.0,
        1e5,
        open = true,
        section.polar_inertia
    ),
    real!("section.ka2", "m²", 0.0, 100.0, open = false, section.ka2),
    real!(
        "section.km1_2",
        "m²",
        0.0,
        100.0,
        open = false,
        section.km1_2
    ),
    real!(
        "section.km2_2",
        "m²",
        0.0,
        100.0,
        open = false,
        section.km2_2
    ),
    real!("section.chord", "m", 0.0, 50.0, open = true, section.chord),
    real!(
        "section.ea_offset",
        "m",
        -50.0,
        50.0,
        open = false,
        section.ea_offset
    ),
    real!(
        "section.cg_offset",
        "m",
        -50.0,
        50.0,
        open = false,
        section.cg_offset
    ),
    real!("section.c22", "N·m²", 0.0, 1e13, open = true, section.c22),
    real!(
        "section.c23",
        "N·m²",
        -1e13,
        1e13,
        open = false,
        section.c23
    ),
    real!("section.c33", "N·m²", 0.0, 1e13, open = true, section.c33),
    real!(
        "section.layup.e11",
        "Pa",
        0.0,
        1e13,
        open = true,
        section.layup.e11
    ),
    real!(
        "section.layup.e22",
        "Pa",
        0.0,
        1e13,
        open = true,
        section.layup.e22
    ),
    real!(
        "section.layup.nu12",
        "",
        -1.0,
        10.0,
        open = true,
        section.layup.nu12
    ),
    real!(
        "section.layup.g12",
        "Pa",
        0.0,
        1e13,
        open = true,
        section.layup.g12
    ),
    real!(
        "section.layup.density",
        "kg/m³",
        0.0,
        1e5,
        open = true,
        section.layup.density
    ),
    real!(
        "section.layup.ply_thickness",
        "m",
        0.0,
        0.1,
        open = true,
        section.layup.ply_thickness
    ),
    int!("section.layup.plies", 1, 200, section.layup.plies),
    real!(
        "section.layup.nonstructural_mass",
        "kg/m",
        0.0,
        1e5,
        open = false,
        section.layup.nonstructural_mass
    ),
    real!(
        "section.layup.nonstructural_position",
        "m",
        -50.0,
        50.0,
        open = false,
        section.layup.nonstructural_position
    ),
    real!(
        "section.contour.width",
        "m",
        0.0,
        50.0,
        open = true,
        section.contour.width
    ),
    real!(
        "section.contour.height",
        "m",
        0.0,
        50.0,
        open = true,
        section.contour.height
    ),
    real!(
        "section.contour.a",
        "m",
        0.0,
        50.0,
        open = true,
        section.contour.a
    ),
    real!(
        "section.contour.b",
        "m",
        0.0,
        50.0,
        open = true,
        section.contour.b
    ),
    real!(
        "operating.wind_speed",
        "m/s",
        0.0,
        200.0,
        open = false,
        operating.wind_speed
    ),
    real!(
        "operating.rotor_speed",
        "rpm",
        0.0,
        5000.0,
        open = false,
        operating.rotor_speed
    ),
    real!(
        "operating.pitch",
        "deg",
        -90.0,
        90.0,
        open = false,
        operating.pitch
    ),
    real!(
        "operating.tunnel_speed",
        "m/s",
        0.0,
        1000.0,
        open = false,
        operating.tunnel_speed
    ),
    real!(
        "operating.air_density",
        "kg/m³",
        0.0,
        100.0,
        open = false,
        operating.air_density
    ),
    real!(
        "operating.induction",
        "",
        0.0,
        0.5,
        open = false,
        operating.induction
    ),
    real!(
        "operating.twist_root",
        "deg",
        -90.0,
        90.0,
        open = false,
        operating.twist_root
    ),
    real!(
        "operating.twist_tip",
        "deg",
        -90.0,
        90.0,
        open = false,
        operating.twist_tip
    ),
    int!("structure.modes", 1, 40, structure.modes),
    real!(
        "structure.loss_factor",
        "",
        0.0,
        1.0,
        open = false,
        structure.loss_factor
    ),
    real!(
        "aero.lift_slope",
        "1/rad",
        0.0,
        20.0,
        open = false,
        aero.lift_slope
    ),
    int!("aero.stations", 1, 64, aero.stations),
    real!(
        "aero.drag_coefficient",
        "",
        0.0,
        2.0,
        open = false,
        aero.drag_coefficient
    ),
    real!(
        "aero.onera.lambda_l",
        "",
        0.0,
        10.0,
        open = true,
        aero.onera.lambda_l
    ),
    real!(
        "aero.onera.a0l",
        "1/rad",
        0.0,
        20.0,
        open = false,
        aero.onera.a0l
    ),
    real!("aero.onera.a_l", "", 0.0, 10.0, open = true, aero.onera.a_l),
    real!("aero.onera.r_l", "", 0.0, 10.0, open = true, aero.onera.r_l),
    real!("aero.onera.a_m", "", 0.0, 10.0, open = true, aero.onera.a_m),
    real!("aero.onera.r_m", "", 0.0, 10.0, open = true, aero.onera.r_m),
    real!("aero.onera.a_d", "", 0.0, 10.0, open = true, aero.onera.a_d),
    real!("aero.onera.r_d", "", 0.0, 10.0, open = true, aero.onera.r_d),
    real!(
        "aero.onera.a_l1",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_l1
    ),
    real!(
        "aero.onera.a_l2",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_l2
    ),
    real!(
        "aero.onera.a_m1",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_m1
    ),
    real!(
        "aero.onera.a_m2",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_m2
    ),
    real!(
        "aero.onera.a_d1",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_d1
    ),
    real!(
        "aero.onera.a_d2",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_d2
    ),
    real!(
        "aero.onera.a_d3",
        "",
        -100.0,
        100.0,
        open = false,
        aero.onera.a_d3
    ),
    real!(
        "aero.onera.cm0",
        "",
        -2.0,
        2.0,
        open = false,
        aero.onera.cm0
    ),
    real!("aero.onera.cd0", "", 0.0, 2.0, open = false, aero.onera.cd0),
    real!(
        "aero.onera.alpha1",
        "rad",
        0.0,
        1.5,
        open = false,
        aero.onera.alpha1
    ),
    real!(
        "aero.onera.alpha2",
        "rad",
        0.0,
        1.5,
        open = false,
        aero.onera.alpha2
    ),
    real!(
        "simulation.kick_twist",
        "deg",
        -90.0,
        90.0,
        open = false,
        simulation.kick_twist
    ),
    real!(
        "simulation.kick_flap",
        "m",
        -100.0,
        100.0,
        open = false,
        simulation.kick_flap
    ),
    real!(
        "simulation.duration",
        "s",
        0.0,
        1e4,
        open = true,
        simulation.duration
    ),
    real!(
        "simulation.sample_rate",
        "1/s",
        0.0,
        1e5,
        open = true,
        simulation.sample_rate
    ),
    real!(
        "view.rotor_speed_max",
        "rpm",
        0.0,
        5000.0,
        open = true,
        view.rotor_speed_max
    ),
    real!(
        "view.tunnel_speed_max",
        "m/s",
        0.0,
        1000.0,
        open = true,
        view.tunnel_speed_max
    ),
    real!(
        "view.wind_speed_max",
        "m/s",
        0.0,
        200.0,
        open = true,
        view.wind_speed_max
    ),
];

/// The spec of a numeric key, or a usage error listing what exists.
pub fn key_spec(key: &str) -> Result<&'static KeySpec> {
    KEYS.iter().find(|k| k.key == key).ok_or_else(|| {
        Error::usage(format!(
            "unknown numeric key '{key}'; numeric keys are: {}",
            KEYS.iter().map(|k| k.key).collect::<Vec<_>>().join(", ")
        ))
    })
}

// ---------------------------------------------------------------------------------------------
// Built-in presets
// ---------------------------------------------------------------------------------------------

/// Presets shipped in `presets/` and embedded so the binary runs from anywhere.
pub static BUILTIN: &[(&str, &str)] = &[
    ("liu2017", include_str!("../presets/liu2017.toml")),
    (
        "liu2017-stall",
        include_str!("../presets/liu2017-stall.toml"),
    ),
    ("goland", include_str!("../presets/goland.toml")),
    ("demo-blade", include_str!("../presets/demo-blade.toml")),
];

/// The preset the explorer opens with no arguments.
pub const DEFAULT_PRESET: &str = "liu2017";

/// Most samples one time response may hold (`simulation.duration × simulation.sample_rate`):
/// 2e6 samples is 10⁴ s at 200/s; time, tip twist and flap take 48 MB.
pub const MAX_SAMPLES: f64 = 2e6;

/// Names of the built-in presets, in display order.
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

impl Preset {
    /// Load a built-in preset by name, or a file by path (anything containing a path separator
    /// or ending in `.toml`), then apply `--set` overrides and validate.
    pub fn load(name_or_path: &str, overrides: &[String]) -> Result<Preset> {
        if let Some((name, text)) = BUILTIN.iter().find(|(n, _)| *n == name_or_path) {
            return Preset::from_toml(text, &format!("built-in preset '{name}'"), overrides);
        }
        let path = Path::new(name_or_path);
        let looks_like_path = name_or_path.ends_with(".toml")
            || name_or_path.contains(std::path::MAIN_SEPARATOR)
            || name_or_path.contains('/');
        if looks_like_path || path.exists() {
            let text = std::fs::read_to_string(path).map_err(|e| Error::Preset {
                origin: name_or_path.to_string(),
                message: format!("cannot read preset file: {e}"),
            })?;
            return Preset::from_toml(&text, name_or_path, overrides);
        }
        Err(Error::usage(format!(
            "no preset named '{name_or_path}'; built-in presets: {} (or give a path to a .toml file)",
            builtin_names().join(", ")
        )))
    }

    /// Parse TOML text, apply overrides (`key=value`, value in TOML syntax or a bare word) and
    /// validate. `origin` names the source in every error.
    pub fn from_toml(text: &str, origin: &str, overrides: &[String]) -> Result<Preset> {
        let preset_err = |message: String| Error::Preset {
            origin: origin.to_string(),
            message,
        };
        let file_err = |e: toml::de::Error| preset_err(e.to_string().trim_end().to_string());
        // The file alone, deserialized from its text so that every error in it (syntax, unknown
        // field, wrong type) carries the line and a caret.
        let mut preset: Preset = toml::from_str(text).map_err(file_err)?;
        if !overrides.is_empty() {
            // Overrides edit the parsed table; its errors have no spans and read "…\nin
            // `table`", kept on one line and blamed on the --set.
            let mut table: toml::Table = text.parse().map_err(file_err)?;
            for ov in overrides {
                apply_override(&mut table, ov)?;
            }
            preset = Preset::deserialize(table).map_err(|e| {
                let msg = e.to_string().trim_end().replace('\n', " ");
                preset_err(format!("{msg} (after --set {})", overrides.join(" --set ")))
            })?;
        }
        preset.origin = origin.to_string();
        preset.validate()?;
        Ok(preset)
    }

    /// Range-check every numeric key and the cross-field rules.
    pub fn validate(&self) -> Result<()> {
        for spec in KEYS {
            let v = (spec.get)(self);
            if !spec.contains(v) {
                return Err(Error::Range {
                    origin: self.origin.clone(),
                    key: spec.key.to_string(),
                    value: format!("{v}"),
                    allowed: spec.allowed(),
                });
            }
        }
        let invalid = |message: String| Error::Invalid {
            origin: self.origin.clone(),
            message,
        };
        let o = &self.aero.onera;
        if o.alpha2 <= o.alpha1 {
            return Err(invalid(format!(
                "aero.onera.alpha2 = {} must exceed aero.onera.alpha1 = {}",
                o.alpha2, o.alpha1
            )));
        }
        let sim = &self.simulation;
        let samples = sim.duration * sim.sample_rate;
        if !(1.0..=MAX_SAMPLES).contains(&samples) {
            return Err(invalid(format!(
                "simulation.duration × simulation.sample_rate = {} s × {} 1/s = {samples:.4e} \
                 samples; allowed: 1 … {MAX_SAMPLES:e} (the response is kept in memory)",
                sim.duration, sim.sample_rate
            )));
        }
        if self.section.ea_offset.abs() > self.section.chord {
            return Err(invalid(format!(
                "section.ea_offset = {} lies outside the chord (|e_a| must be ≤ section.chord = {})",
                self.section.ea_offset, self.section.chord
            )));
        }
        Ok(())
    }

    /// Value of a numeric key.
    pub fn get(&self, key: &str) -> Result<f64> {
        Ok((key_spec(key)?.get)(self))
    }

    /// Set a numeric key, checking its range (not the cross-field rules: call [`validate`]).
    pub fn set(&mut self, key: &str, value: f64) -> Result<()> {
        let spec = key_spec(key)?;
        if !spec.contains(value) {
            return Err(Error::Range {
                origin: self.origin.clone(),
                key: key.to_string(),
                value: format!("{value}"),
                allowed: spec.allowed(),
            });
        }
        (spec.set)(self, value);
        Ok(())
    }

    /// The preset as TOML text (round-trips through [`Preset::from_toml`]).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_default()
    }

    /// A display name: `meta.name`, else the origin.
    pub fn display_name(&self) -> &str {
        if self.meta.name.is_empty() {
            &self.origin
        } else {
            &self.meta.name
        }
    }

    // ---- SI accessors for the physics layers ----

    /// Rotor speed Ω (rad/s).
    pub fn omega(&self) -> f64 {
        self.operating.rotor_speed * std::f64::consts::PI / 30.0
    }
    /// Pitch β (rad).
    pub fn pitch_rad(&self) -> f64 {
        self.operating.pitch.to_radians()
    }
}

/// Apply one `key=value` override to the raw TOML table, creating intermediate tables. The value
/// is parsed as TOML (numbers, booleans, quoted strings); a bare word becomes a string, so
/// `--set aero.model=theodorsen` works without quotes.
fn apply_override(table: &mut toml::Table, ov: &str) -> Result<()> {
    let (key, raw) = ov.split_once('=').ok_or_else(|| {
        Error::usage(format!(
            "--set expects key=value (e.g. --set section.ply_angle=30), got '{ov}'"
        ))
    })?;
    let key = key.trim();
    let raw = raw.trim();
    if key.is_empty() || key.split('.').any(|p| p.is_empty()) {
        return Err(Error::usage(format!(
            "--set: malformed key '{key}' in '{ov}'"
        )));
    }
    let value: toml::Value = match format!("v = {raw}").parse::<toml::Table>() {
        Ok(mut t) => t
            .remove("v")
            .unwrap_or(toml::Value::String(raw.to_string())),
        Err(_) => toml::Value::String(raw.to_string()),
    };
    let parts: Vec<&str> = key.split('.').collect();
    let mut cur = table;
    for part in &parts[..parts.len() - 1] {
        let entry = cur
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        cur = entry.as_table_mut().ok_or_else(|| {
            Error::usage(format!("--set {key}: '{part}' is a value, not a section"))
        })?;
    }
    cur.insert(parts[parts.len() - 1].to_string(), value);
    Ok(())
}
