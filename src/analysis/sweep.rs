//! Parameter sweeps with tracked modes (a Campbell diagram when the key is rotor speed).

use serde::Serialize;

/// One tracked mode along a one-dimensional sweep.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedMode {
    /// Label at the first grid point; kept through crossings by MAC tracking.
    pub label: String,
    pub frequency_hz: Vec<f64>,
    pub damping_ratio: Vec<f64>,
    pub re: Vec<f64>,
}

/// Tracked modes over a one-dimensional grid.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedSweep {
    pub parameter: String,
    pub values: Vec<f64>,
    pub modes: Vec<TrackedMode>,
}
