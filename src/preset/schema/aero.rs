//! The `[aero]` table: the aerodynamic model, its stations, the rotor's aerodynamic files and
//! the ONERA and Hansen–Gaunaa–Madsen dynamic-stall parameters.

use crate::physics::rotor::induction::HighThrust;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AeroModel {
    None,
    QuasiSteady,
    Theodorsen,
    Onera,
    Hgm,
}

impl AeroModel {
    pub const ALL: [AeroModel; 5] = [
        AeroModel::None,
        AeroModel::QuasiSteady,
        AeroModel::Theodorsen,
        AeroModel::Onera,
        AeroModel::Hgm,
    ];
    pub fn name(self) -> &'static str {
        match self {
            AeroModel::None => "none",
            AeroModel::QuasiSteady => "quasi-steady",
            AeroModel::Theodorsen => "theodorsen",
            AeroModel::Onera => "onera",
            AeroModel::Hgm => "hgm",
        }
    }

    /// True when the model's stall is nonlinear in time (ONERA's, HGM's separation).
    pub fn stalls(self) -> bool {
        matches!(self, AeroModel::Onera | AeroModel::Hgm)
    }

    /// True when the model needs each station's own polar (a tabulated blade's aerodynamic
    /// description): the uniform blade has none.
    pub fn needs_polars(self) -> bool {
        self == AeroModel::Hgm
    }

    /// [`AeroModel::cycle`] over the models a blade takes: without polars (`polars` false),
    /// past those that need them.
    pub fn cycle_for(self, forward: bool, polars: bool) -> AeroModel {
        let mut m = self.cycle(forward);
        while m.needs_polars() && !polars {
            m = m.cycle(forward);
        }
        m
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
    #[serde(skip_serializing_if = "HgmKeys::is_unset")]
    pub hgm: HgmKeys,
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

/// Hansen–Gaunaa–Madsen constants set for every station (docs/model.md §12.8); unset, each
/// station's airfoil file gives them (its AirfoilInfo UA block), else the published values.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HgmKeys {
    pub a1: Option<f64>,
    pub a2: Option<f64>,
    pub b1: Option<f64>,
    pub b2: Option<f64>,
    /// τ_p: the pressure lag's time constant in semichord travel times.
    pub tau_p: Option<f64>,
    /// τ_f: the separation point's time constant in semichord travel times.
    pub tau_f: Option<f64>,
}

impl HgmKeys {
    /// Whether no constant is set, so that a preset written back leaves the table out.
    pub fn is_unset(&self) -> bool {
        *self == HgmKeys::default()
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
            hgm: HgmKeys::default(),
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
