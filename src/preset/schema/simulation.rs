//! The `[simulation]` table: the tip response's start state, kicks, duration and sample rate.

use serde::{Deserialize, Serialize};

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
