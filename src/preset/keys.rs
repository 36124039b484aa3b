//! The key table: every numeric preset key with its unit, allowed range and accessors. It checks
//! presets and `--set` overrides, and names the numeric parameters that sweeps, flutter searches
//! and the explorer vary; every out-of-range message is built here ([`KeySpec::check`]).

use super::schema::section::PAPER_PLY_ANGLE;
use super::schema::Preset;
use crate::error::{Error, Result};

/// Most finite elements `structure.min_elements` may ask for: the modes come from a dense
/// eigensolution of 5 dofs per element, about a second at 400 elements.
pub const MAX_ELEMENTS: usize = 400;

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
    /// True while an optional key is unset: there is no value to check.
    pub unset: fn(&Preset) -> bool,
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

    /// `Ok` when `v` is allowed, else the one out-of-range error, naming where the value came
    /// from (`origin`: a file, a built-in preset, a command-line flag).
    pub fn check(&self, origin: &str, v: f64) -> Result<()> {
        if self.contains(v) {
            return Ok(());
        }
        Err(Error::Range {
            origin: origin.to_string(),
            key: self.key.to_string(),
            value: format!("{v}"),
            allowed: self.allowed(),
        })
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
            unset: |_| false,
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
            unset: |_| false,
        }
    };
}

/// A key that may be left unset (`Option<f64>`: unset, a value from elsewhere applies, e.g. the
/// blade file's damping). It reads 0 while unset, and setting it sets it.
macro_rules! optional {
    ($key:literal, $unit:literal, $min:expr, $max:expr, $($f:ident).+) => {
        optional!($key, $unit, $min, $max, open = false, $($f).+)
    };
    ($key:literal, $unit:literal, $min:expr, $max:expr, open=$open:expr, $($f:ident).+) => {
        KeySpec {
            key: $key,
            unit: $unit,
            min: $min,
            max: $max,
            min_open: $open,
            integer: false,
            get: |p| p.$($f).+.unwrap_or(0.0),
            set: |p, v| p.$($f).+ = Some(v),
            unset: |p| p.$($f).+.is_none(),
        }
    };
}

/// Every numeric key with its allowed range, one per line. Enumerated keys (`section.source`,
/// `aero.model`, …) are checked by serde against their variants.
#[rustfmt::skip]
pub static KEYS: &[KeySpec] = &[
    real!("blade.length", "m", 0.0, 500.0, open = true, blade.length),
    real!("blade.hub_radius", "m", 0.0, 100.0, open = false, blade.hub_radius),
    int!("blade.st_set", 1, 1000, blade.st_set),
    int!("blade.st_subset", 1, 1000, blade.st_subset),
    real!("blade.bend_twist_coupling", "", -0.3, 0.3, open = false, blade.bend_twist_coupling),
    KeySpec {
        key: "section.ply_angle",
        unit: "deg",
        min: -90.0,
        max: 90.0,
        min_open: false,
        integer: false,
        // Unset, the paper's blade reads its default angle and a WindIO blade 0 (the angle a
        // knob starts turning from; the ontology's own angles stand until it does).
        get: |p| p.section.ply_angle.unwrap_or(if p.blade.source.is_tabulated() { 0.0 } else { PAPER_PLY_ANGLE }),
        set: |p, v| p.section.ply_angle = Some(v),
        unset: |p| p.section.ply_angle.is_none(),
    },
    real!("section.trailing_edge_fill_length", "m", 0.0, 50.0, open = true, section.trailing_edge_fill_length),
    real!("section.mass_per_length", "kg/m", 0.0, 1e5, open = true, section.mass_per_length),
    real!("section.polar_inertia", "kg·m", 0.0, 1e5, open = true, section.polar_inertia),
    real!("section.ka2", "m²", 0.0, 100.0, open = false, section.ka2),
    real!("section.km1_2", "m²", 0.0, 100.0, open = false, section.km1_2),
    real!("section.km2_2", "m²", 0.0, 100.0, open = false, section.km2_2),
    real!("section.chord", "m", 0.0, 50.0, open = true, section.chord),
    real!("section.ea_offset", "m", -50.0, 50.0, open = false, section.ea_offset),
    real!("section.cg_offset", "m", -50.0, 50.0, open = false, section.cg_offset),
    real!("section.c22", "N·m²", 0.0, 1e13, open = true, section.c22),
    real!("section.c23", "N·m²", -1e13, 1e13, open = false, section.c23),
    real!("section.c33", "N·m²", 0.0, 1e13, open = true, section.c33),
    real!("section.layup.e11", "Pa", 0.0, 1e13, open = true, section.layup.e11),
    real!("section.layup.e22", "Pa", 0.0, 1e13, open = true, section.layup.e22),
    real!("section.layup.nu12", "", -1.0, 10.0, open = true, section.layup.nu12),
    real!("section.layup.g12", "Pa", 0.0, 1e13, open = true, section.layup.g12),
    real!("section.layup.density", "kg/m³", 0.0, 1e5, open = true, section.layup.density),
    real!("section.layup.ply_thickness", "m", 0.0, 0.1, open = true, section.layup.ply_thickness),
    int!("section.layup.plies", 1, 200, section.layup.plies),
    real!("section.layup.nonstructural_mass", "kg/m", 0.0, 1e5, open = false, section.layup.nonstructural_mass),
    real!("section.layup.nonstructural_position", "m", -50.0, 50.0, open = false, section.layup.nonstructural_position),
    real!("section.contour.width", "m", 0.0, 50.0, open = true, section.contour.width),
    real!("section.contour.height", "m", 0.0, 50.0, open = true, section.contour.height),
    real!("section.contour.a", "m", 0.0, 50.0, open = true, section.contour.a),
    real!("section.contour.b", "m", 0.0, 50.0, open = true, section.contour.b),
    real!("operating.wind_speed", "m/s", 0.0, 200.0, open = false, operating.wind_speed),
    real!("operating.rotor_speed", "rpm", 0.0, 5000.0, open = false, operating.rotor_speed),
    real!("operating.pitch", "deg", -90.0, 90.0, open = false, operating.pitch),
    real!("operating.tunnel_speed", "m/s", 0.0, 1000.0, open = false, operating.tunnel_speed),
    real!("operating.air_density", "kg/m³", 0.0, 100.0, open = false, operating.air_density),
    real!("operating.precone", "deg", -30.0, 30.0, open = false, operating.precone),
    real!("operating.shaft_tilt", "deg", -30.0, 30.0, open = false, operating.shaft_tilt),
    real!("operating.induction", "", 0.0, 0.5, open = false, operating.induction),
    real!("operating.twist_root", "deg", -90.0, 90.0, open = false, operating.twist_root),
    real!("operating.twist_tip", "deg", -90.0, 90.0, open = false, operating.twist_tip),
    int!("operating.blades", 1, 20, operating.blades),
    real!("operating.rated_power", "W", 0.0, 1e10, open = false, operating.rated_power),
    real!("operating.rotor_speed_min", "rpm", 0.0, 5000.0, open = false, operating.rotor_speed_min),
    real!("operating.rotor_speed_max", "rpm", 0.0, 5000.0, open = false, operating.rotor_speed_max),
    real!("operating.tip_speed_ratio", "", 0.0, 50.0, open = false, operating.tip_speed_ratio),
    real!("operating.rated_rotor_speed", "rpm", 0.0, 5000.0, open = false, operating.rated_rotor_speed),
    real!("operating.cut_in", "m/s", 0.0, 200.0, open = false, operating.cut_in),
    real!("operating.cut_out", "m/s", 0.0, 200.0, open = false, operating.cut_out),
    int!("structure.modes", 1, 40, structure.modes),
    real!("structure.loss_factor", "", 0.0, 1.0, open = false, structure.loss_factor),
    int!("structure.min_elements", 1, MAX_ELEMENTS, structure.min_elements),
    optional!("structure.damping_flap", "", 0.0, 1.0, structure.damping_flap),
    optional!("structure.damping_edge", "", 0.0, 1.0, structure.damping_edge),
    optional!("structure.damping_torsion", "", 0.0, 1.0, structure.damping_torsion),
    real!("aero.lift_slope", "1/rad", 0.0, 20.0, open = false, aero.lift_slope),
    int!("aero.stations", 1, 64, aero.stations),
    real!("aero.drag_coefficient", "", 0.0, 2.0, open = false, aero.drag_coefficient),
    int!("aero.ae_set", 1, 1000, aero.ae_set),
    real!("aero.onera.lambda_l", "", 0.0, 10.0, open = true, aero.onera.lambda_l),
    real!("aero.onera.a0l", "1/rad", 0.0, 20.0, open = false, aero.onera.a0l),
    real!("aero.onera.a_l", "", 0.0, 10.0, open = true, aero.onera.a_l),
    real!("aero.onera.r_l", "", 0.0, 10.0, open = true, aero.onera.r_l),
    real!("aero.onera.a_m", "", 0.0, 10.0, open = true, aero.onera.a_m),
    real!("aero.onera.r_m", "", 0.0, 10.0, open = true, aero.onera.r_m),
    real!("aero.onera.a_d", "", 0.0, 10.0, open = true, aero.onera.a_d),
    real!("aero.onera.r_d", "", 0.0, 10.0, open = true, aero.onera.r_d),
    real!("aero.onera.a_l1", "", -100.0, 100.0, open = false, aero.onera.a_l1),
    real!("aero.onera.a_l2", "", -100.0, 100.0, open = false, aero.onera.a_l2),
    real!("aero.onera.a_m1", "", -100.0, 100.0, open = false, aero.onera.a_m1),
    real!("aero.onera.a_m2", "", -100.0, 100.0, open = false, aero.onera.a_m2),
    real!("aero.onera.a_d1", "", -100.0, 100.0, open = false, aero.onera.a_d1),
    real!("aero.onera.a_d2", "", -100.0, 100.0, open = false, aero.onera.a_d2),
    real!("aero.onera.a_d3", "", -100.0, 100.0, open = false, aero.onera.a_d3),
    real!("aero.onera.cm0", "", -2.0, 2.0, open = false, aero.onera.cm0),
    real!("aero.onera.cd0", "", 0.0, 2.0, open = false, aero.onera.cd0),
    real!("aero.onera.alpha1", "deg", 0.0, 85.0, open = false, aero.onera.alpha1),
    real!("aero.onera.alpha2", "deg", 0.0, 85.0, open = false, aero.onera.alpha2),
    optional!("aero.hgm.a1", "", 0.0, 1.0, aero.hgm.a1),
    optional!("aero.hgm.a2", "", 0.0, 1.0, aero.hgm.a2),
    optional!("aero.hgm.b1", "", 0.0, 10.0, open = true, aero.hgm.b1),
    optional!("aero.hgm.b2", "", 0.0, 10.0, open = true, aero.hgm.b2),
    optional!("aero.hgm.tau_p", "", 0.0, 100.0, open = true, aero.hgm.tau_p),
    optional!("aero.hgm.tau_f", "", 0.0, 100.0, open = true, aero.hgm.tau_f),
    real!("turbine.torque_slope", "N·m·s/rad", 0.0, 1e12, open = false, turbine.torque_slope),
    real!("simulation.kick_twist", "deg", -90.0, 90.0, open = false, simulation.kick_twist),
    real!("simulation.kick_flap", "m", -100.0, 100.0, open = false, simulation.kick_flap),
    real!("simulation.duration", "s", 0.0, 1e4, open = true, simulation.duration),
    real!("simulation.sample_rate", "1/s", 0.0, 1e5, open = true, simulation.sample_rate),
    real!("view.rotor_speed_max", "rpm", 0.0, 5000.0, open = true, view.rotor_speed_max),
    real!("view.tunnel_speed_max", "m/s", 0.0, 1000.0, open = true, view.tunnel_speed_max),
    real!("view.wind_speed_max", "m/s", 0.0, 200.0, open = true, view.wind_speed_max),
    real!("view.section_at", "", 0.0, 1.0, open = false, view.section_at),
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
