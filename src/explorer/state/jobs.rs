//! The background jobs the explorer runs beside the solve: the boundary search along one key
//! either way from the current value ([`BoundaryJob`]) and the Campbell diagram along rotor or
//! wind speed ([`CampbellJob`]), with their grid sizes.

use crate::analysis::campbell::{Campbell, ROTOR_SPEED_KEY, WIND_SPEED_KEY};
use crate::analysis::flutter::Search;
use crate::explorer::state::params::{offered, ParamKind, PARAMS};
use crate::preset::{Preset, ValidPreset};

/// Grid points the background boundary search brackets on (as `flutterscope flutter`).
pub const BOUNDARY_POINTS: usize = 41;

/// Rotor speeds in the Campbell diagram, 0 to `view.rotor_speed_max`.
pub const CAMPBELL_POINTS: usize = 41;

/// Wind speeds in the Campbell diagram along the schedule: 1 m/s steps from cut-in 3 to
/// cut-out 25 m/s on the real-blade presets, as HAWCStab2's operating-point files have them.
pub const CAMPBELL_WIND_POINTS: usize = 23;

/// The Campbell view's axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CampbellAxis {
    /// 0 to `view.rotor_speed_max`, everything else as set.
    RotorSpeed,
    /// Cut-in to cut-out along the operating schedule (rotor speed and pitch the schedule's).
    WindSpeed,
}

impl CampbellAxis {
    pub fn key(self) -> &'static str {
        match self {
            CampbellAxis::RotorSpeed => ROTOR_SPEED_KEY,
            CampbellAxis::WindSpeed => WIND_SPEED_KEY,
        }
    }
}

/// Which way from the current value one search of a margin runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Down to the slider's low end.
    Below,
    /// Up to the slider's high end.
    Above,
}

/// The background boundary search along one key: from the current value both ways to the
/// slider's ends. From a stable point each side's search finds the nearest boundary on that side;
/// from an unstable one, where the blade is stable again, so the two bound the unstable stretch
/// the current value lies in.
#[derive(Debug, Clone)]
pub struct BoundaryJob {
    pub gen: u64,
    pub key: &'static str,
    /// The slider's range and the value the searches start from.
    pub from: f64,
    pub to: f64,
    pub current: f64,
    /// Whether the operating point was unstable.
    pub unstable: bool,
    /// The sides searched, in the order of the results (a side with nothing between the current
    /// value and the slider's end is not searched).
    pub sides: Vec<Side>,
    /// One search per side; `None` while running (or when no side has a range).
    pub result: Option<Result<Vec<Search>, String>>,
}

/// The Campbell diagram, valid for every preset equal to `for_preset` up to the axis's key.
#[derive(Debug, Clone)]
pub struct CampbellJob {
    pub gen: u64,
    pub axis: CampbellAxis,
    /// The axis's range.
    pub from: f64,
    pub to: f64,
    pub points: usize,
    pub for_preset: Preset,
    pub result: Option<Result<Campbell, String>>,
}

/// The parameter a preset's first boundary search runs along: the focused row's key when it
/// searches one, else rotor speed.
pub(super) fn opening_key(p: &ValidPreset, focus: usize) -> &'static str {
    match PARAMS[focus].kind {
        ParamKind::Number {
            key,
            boundary: true,
            ..
        } if offered(p, &PARAMS[focus]) => key,
        _ => "operating.rotor_speed",
    }
}
