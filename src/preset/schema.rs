//! The preset schema: one struct per TOML table, every field with its unit and its default (the
//! paper's blade at its operating point), unknown fields rejected by serde.

use super::files::FileBase;
use crate::physics::blade::source::TabulatedBlade;
use crate::physics::rotor::induction::HighThrust;
use crate::physics::rotor::schedule::Table as ScheduleTable;
use crate::physics::rotor::stations::GaussStations;
use crate::physics::rotor::AeroBlade;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// A complete description of one case, as read (check it with [`Preset::validate`] before use). Every section and field has a default (the
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
    /// Where a relative `blade.file` resolves: the preset file's directory, the blade files
    /// built into the binary, or the working directory.
    #[serde(skip)]
    pub base: FileBase,
    /// The tabulated blade read from `blade.file` when the preset was checked (`None` for
    /// `blade.source = "uniform"`), so that the files are read once per preset, not per solve.
    #[serde(skip)]
    pub tabulated: Option<Tabulated>,
    /// The aerodynamic description and operating table read from the `aero.*` and
    /// `operating.schedule_file` keys when the preset was checked (`None` when it names none).
    #[serde(skip)]
    pub rotor_files: Option<RotorFiles>,
    /// Which of the schedule's outputs an edit (`--set`, `--vary`, the explorer) has set by
    /// hand: those hold, the schedule gives the rest (docs/model.md §12.3).
    #[serde(skip)]
    pub schedule_overrides: ScheduleOverrides,
    /// What loading the preset left unused at the user's request (a schedule file a `--set
    /// operating.schedule` set aside), for the command line to say.
    #[serde(skip)]
    pub notes: Vec<String>,
}

/// Rotor speed and pitch set by hand while `operating.schedule` runs: overspeed, idling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScheduleOverrides {
    pub rotor_speed: bool,
    pub pitch: bool,
}

#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Meta {
    pub name: String,
    pub description: String,
}

/// Where the blade's structure comes from (`blade.source`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BladeSource {
    /// The paper's uniform flap–torsion blade: `blade.length` and the `section.*` keys.
    Uniform,
    /// A BeamDyn primary file (key points, initial twist) and the blade file it names (6×6
    /// stiffness and mass per station), docs/model.md §11.5.
    Beamdyn,
    /// A HAWC2 st file, subset `blade.st_subset` of set `blade.st_set`.
    Hawc2,
}

impl BladeSource {
    pub fn name(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "beamdyn",
            BladeSource::Hawc2 => "hawc2",
        }
    }

    /// The name as the source's program spells it, for reports.
    pub fn title(self) -> &'static str {
        match self {
            BladeSource::Uniform => "uniform",
            BladeSource::Beamdyn => "BeamDyn",
            BladeSource::Hawc2 => "HAWC2",
        }
    }

    /// A blade described by tables of sections along the span (docs/model.md §11).
    pub fn is_tabulated(self) -> bool {
        self != BladeSource::Uniform
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Blade {
    pub source: BladeSource,
    /// The BeamDyn primary file or the HAWC2 st file, relative to the preset's directory (empty
    /// for the uniform blade).
    pub file: String,
    /// An AeroDyn 15 blade file whose `BlTwist` turns a HAWC2 blade's sections (the st file
    /// carries no twist; HAWC2 takes it from the htc's c2_def), relative to the preset's
    /// directory (hawc2 source only).
    pub twist_file: String,
    /// Span L (m). A tabulated blade's is its file's.
    pub length: f64,
    /// Hub radius r_hub (m); r = r_hub + x.
    pub hub_radius: f64,
    /// HAWC2 st set `#N` (hawc2 source).
    pub st_set: usize,
    /// HAWC2 st subset `$N` within the set (hawc2 source).
    pub st_subset: usize,
    /// α: adds `α·√(EI_flap·GJ)` to the flap–twist coupling of every station of a tabulated
    /// blade, on top of its files' (docs/model.md §11.7); α > 0 twists toward feather under
    /// downwind bending. Tabulated blades only.
    pub bend_twist_coupling: f64,
}

/// The tabulated blade a preset was checked with, and the keys it was read from: a change of
/// any of them (an edited preset) reads the files again.
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    pub source: BladeSource,
    pub file: String,
    pub twist_file: String,
    pub st_set: usize,
    pub st_subset: usize,
    pub blade: Arc<TabulatedBlade>,
}

impl Tabulated {
    /// Whether this was read from what `blade` now names.
    pub fn read_from(&self, blade: &Blade) -> bool {
        self.source == blade.source
            && self.file == blade.file
            && (self.source != BladeSource::Hawc2
                || (self.st_set, self.st_subset, &self.twist_file)
                    == (blade.st_set, blade.st_subset, &blade.twist_file))
    }
}

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

pub use crate::physics::inflow::Inflow;

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
    /// Precone (deg): the blades' root axis inclined upwind out of the rotor plane (HAWC2's
    /// cone; OpenFAST's `PreCone` with the opposite sign).
    pub precone: f64,
    /// Shaft tilt (deg): the wind's component along the shaft is `U cos(tilt)`.
    pub shaft_tilt: f64,
    /// Axial induction a_ind.
    pub induction: f64,
    pub inflow: Inflow,
    /// Pretwist at the root (deg), toward feather.
    pub twist_root: f64,
    /// Pretwist at the tip (deg), toward feather.
    pub twist_tip: f64,
    /// Blade count B of the rotor (steady BEM, docs/model.md §12.2).
    pub blades: usize,
    /// Where rotor speed and pitch come from when the wind changes (docs/model.md §12.3).
    pub schedule: Schedule,
    /// The operating table (`schedule = "table"`): a HAWC2 `.opt` file of wind speed, pitch and
    /// rotor speed, relative to the preset's directory.
    pub schedule_file: String,
    /// Rated aerodynamic power (W), `schedule = "law"`.
    pub rated_power: f64,
    /// Lowest rotor speed of the law (rpm).
    pub rotor_speed_min: f64,
    /// Highest rotor speed of the law (rpm).
    pub rotor_speed_max: f64,
    /// Optimal tip speed ratio of the law below rated.
    pub tip_speed_ratio: f64,
    /// The rotor speed margins are quoted against (rpm); 0: none stated.
    pub rated_rotor_speed: f64,
    /// Cut-in wind speed (m/s), where the schedule's Campbell diagram and wind-speed margin
    /// start; 0: not stated (the table's first row, or 0 for a law).
    pub cut_in: f64,
    /// Cut-out wind speed (m/s), where they end; 0: not stated (the table's last row, or
    /// `view.wind_speed_max` for a law).
    pub cut_out: f64,
}

/// `operating.schedule`: where rotor speed and pitch come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Schedule {
    /// Wind, rotor speed and pitch are set independently.
    None,
    /// From `operating.schedule_file`, linear in wind speed.
    Table,
    /// Optimal tip speed ratio within the rotor-speed limits, pitch to hold rated power above.
    Law,
}

impl Schedule {
    pub fn name(self) -> &'static str {
        match self {
            Schedule::None => "none",
            Schedule::Table => "table",
            Schedule::Law => "law",
        }
    }
}

pub use crate::physics::structure::galerkin::Form;

/// Default `structure.min_elements`: the first 12 modes of the NREL 5MW blade within 0.1 % of
/// their converged values. The twist is linear in each element, so the torsion modes converge
/// slowest (as h²): measured against 600 elements extrapolated in h², torsion 3 (14.69 Hz) is
/// 0.33 % high at 60 elements, 0.105 % at 100 and 0.063 % at 120; every flap and edge mode is
/// within 0.001 % from 60 elements on.
pub const MIN_ELEMENTS: usize = 120;

/// `structure.modes` of a tabulated blade whose preset does not set it: the first 12 modes
/// reach past the third flap and second torsion modes of a multi-megawatt blade.
pub const TABULATED_MODES: usize = 12;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Structure {
    /// Uniform blade: N, Galerkin functions per field. Tabulated blade: K, the blade modes
    /// retained (listed by `modes`, the basis of the aeroelastic model).
    pub modes: usize,
    pub form: Form,
    /// η1, first-mode loss factor (C_s = (η1/ω1) K_e), uniform blade.
    pub loss_factor: f64,
    /// Tabulated blade: fewest finite elements; the mesh follows the input stations, then the
    /// longest elements are halved until there are this many (docs/model.md §11.3).
    pub min_elements: usize,
    /// Tabulated blade: modal damping ratio of every flap mode; `None`: the blade file's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_flap: Option<f64>,
    /// … of every edge mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_edge: Option<f64>,
    /// … of every torsion mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_torsion: Option<f64>,
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
    /// The next model in [`AeroModel::ALL`] order (the previous one when `forward` is false),
    /// wrapping around.
    pub fn cycle(self, forward: bool) -> AeroModel {
        let n = Self::ALL.len();
        let i = Self::ALL.iter().position(|m| *m == self).unwrap_or(0);
        Self::ALL[if forward {
            (i + 1) % n
        } else {
            (i + n - 1) % n
        }]
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
    /// An AeroDyn 15 blade file (chord, twist, airfoil id per node), relative to the preset's
    /// directory; with `airfoils` and `pitch_axis_file` (docs/model.md §12.1).
    pub blade_file: String,
    /// AirfoilInfo polar files in airfoil-id (`BlAFID`) order.
    pub airfoils: Vec<String>,
    /// An ElastoDyn blade file whose `PitchAxis` places the pitch axis on the chord.
    pub pitch_axis_file: String,
    /// A HAWC2 ae file (chord, relative thickness, pc set along the blade); with `pc_file`.
    pub ae_file: String,
    /// The ae set used (1-based).
    pub ae_set: usize,
    /// The HAWC2 pc file (profile coefficients by relative thickness).
    pub pc_file: String,
    /// An AeroDyn 15 blade file whose `BlCrvAC` column is the blade's prebend (out-of-plane
    /// offset of its axis, downwind positive); empty for a straight blade (docs/model.md §12.2).
    pub prebend_file: String,
    /// The steady BEM's thrust–induction relation where an element is heavily loaded: `buhl`
    /// (momentum theory, Buhl beyond a = 0.4) or `madsen` (HAWC2's cubic a(C_T), §12.2).
    pub high_thrust: HighThrust,
}

/// The rotor's files as read when the preset was checked, with the keys they were read from:
/// an edit of any of them reads the files again.
#[derive(Debug, Clone, PartialEq)]
pub struct RotorFiles {
    /// What was read: (aero keys, `blade.twist_file`, `operating.schedule_file`).
    pub keys: (Vec<String>, String, String),
    /// The aerodynamic description (`None` when the preset names no aerodynamic files).
    pub blade: Option<Arc<AeroBlade>>,
    /// The operating table (`None` unless `operating.schedule = "table"`).
    pub table: Option<Arc<ScheduleTable>>,
    /// The Gauss stations built on `blade`, by count (new whenever the blade is read again).
    pub stations: GaussStations,
}

impl RotorFiles {
    /// The keys that decide what [`RotorFiles`] holds, in the form it stores them.
    pub fn keys_of(p: &Preset) -> (Vec<String>, String, String) {
        let a = &p.aero;
        let mut aero = vec![
            a.blade_file.clone(),
            a.pitch_axis_file.clone(),
            a.ae_file.clone(),
            a.ae_set.to_string(),
            a.pc_file.clone(),
            a.prebend_file.clone(),
        ];
        aero.extend(a.airfoils.iter().cloned());
        let table = match p.operating.schedule {
            Schedule::Table => p.operating.schedule_file.clone(),
            _ => String::new(),
        };
        (aero, p.blade.twist_file.clone(), table)
    }
}

pub use crate::physics::aero::onera::OneraForcing;

/// ONERA stall-model coefficients (docs/model.md §5.3).
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
    /// Stall onset α1 (deg).
    pub alpha1: f64,
    /// Full-stall angle α2 (deg).
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
    /// `blade.bend_twist_coupling` (tabulated blades).
    BendTwistCoupling,
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
            Selected::BendTwistCoupling => "blade.bend_twist_coupling",
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
            base: FileBase::default(),
            tabulated: None,
            rotor_files: None,
            schedule_overrides: ScheduleOverrides::default(),
            notes: Vec::new(),
        }
    }
}

impl Default for Blade {
    fn default() -> Self {
        Blade {
            source: BladeSource::Uniform,
            file: String::new(),
            twist_file: String::new(),
            length: 8.4455,
            hub_radius: 0.0,
            st_set: 1,
            st_subset: 1,
            bend_twist_coupling: 0.0,
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
        e11: 25.8e9,
        e22: 8.7e9,
        nu12: 0.34,
        g12: 3.5e9,
        density: 1672.0,
        ply_thickness: 0.127e-3,
        plies: 6,
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
        shape: ContourShape::Box,
        width: 0.01833,
        height: 0.00247,
        a: 0.01833 / 2.0,
        b: 0.00247 / 2.0,
    };
}

impl Default for Contour {
    fn default() -> Self {
        Contour::PAPER_BOX
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
            precone: 0.0,
            shaft_tilt: 0.0,
            induction: 0.0,
            inflow: Inflow::Tip,
            twist_root: 0.0,
            twist_tip: 0.0,
            blades: 3,
            schedule: Schedule::None,
            schedule_file: String::new(),
            rated_power: 0.0,
            rotor_speed_min: 0.0,
            rotor_speed_max: 0.0,
            tip_speed_ratio: 0.0,
            rated_rotor_speed: 0.0,
            cut_in: 0.0,
            cut_out: 0.0,
        }
    }
}

impl Default for Structure {
    fn default() -> Self {
        Structure {
            modes: 5,
            form: Form::Weak,
            loss_factor: 0.02,
            min_elements: MIN_ELEMENTS,
            damping_flap: None,
            damping_edge: None,
            damping_torsion: None,
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
            blade_file: String::new(),
            airfoils: Vec::new(),
            pitch_axis_file: String::new(),
            ae_file: String::new(),
            ae_set: 1,
            pc_file: String::new(),
            prebend_file: String::new(),
            high_thrust: HighThrust::Buhl,
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
            // The paper's Eq. 5 gives 0.1396 and 0.3142 rad: 8° and 18° to its four digits.
            alpha1: 8.0,
            alpha2: 18.0,
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
