//! Time response of the blade tip (MODEL.md §7).

use serde::Serialize;

/// One output sample: tip twist φ(L,t) (rad, toward feather) and tip flap u(L,t) (m, downwind).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TipSample {
    pub t: f64,
    pub tip_twist: f64,
    pub tip_flap: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RunStatus {
    Ok,
    /// The response grew past the divergence bound; the run stopped there.
    Diverging,
}
