//! The `[operating]` table: wind and rotor speed, pitch, inflow, and the operating schedule
//! that sets rotor speed and pitch from the wind speed.

use serde::{Deserialize, Serialize};

/// Rotor speed and pitch set by hand while `operating.schedule` runs: overspeed, idling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ScheduleOverrides {
    pub rotor_speed: bool,
    pub pitch: bool,
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
