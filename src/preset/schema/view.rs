//! The `[view]` table: the explorer's axis limits and the parameter it opens on.

use serde::{Deserialize, Serialize};

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
    /// The span fraction whose layup section the parameters pane shows (WindIO blades): the
    /// station nearest it.
    pub section_at: f64,
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

impl Default for View {
    fn default() -> Self {
        View {
            rotor_speed_max: 200.0,
            wind_speed_max: 40.0,
            tunnel_speed_max: 200.0,
            select: Selected::RotorSpeed,
            section_at: 0.8,
        }
    }
}
