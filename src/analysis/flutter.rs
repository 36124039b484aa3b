//! Flutter-boundary search along one numeric preset key (MODEL.md §6).

use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryKind {
    /// The crossing mode oscillates (ω > 0).
    Flutter,
    /// The crossing root is real (ω = 0).
    Divergence,
}

/// The first crossing of the largest σ through zero along a parameter, if any.
#[derive(Debug, Clone, Serialize)]
pub struct Boundary {
    /// The varied key.
    pub parameter: String,
    /// Critical value in the key's unit, `None` when no crossing lies in the range.
    pub critical: Option<f64>,
    pub frequency_hz: Option<f64>,
    pub kind: Option<BoundaryKind>,
    /// Label of the crossing mode.
    pub mode: Option<String>,
}
