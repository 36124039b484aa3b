//! The rotor's aerodynamic description and its steady operation (docs/model.md §12): the blade's
//! chord, aerodynamic twist, aerodynamic-centre position and airfoil polar along the span, read
//! from the turbine's own files.
//!
//! Positions along the blade are span positions from the blade root (m), the same coordinate as
//! the structure's; the radius is `hub_radius + span`.

pub mod bem;
pub mod files;
pub mod induction;
pub mod schedule;
pub mod steady;

use crate::physics::aero::polar::Polar;
use std::sync::Arc;

/// One aerodynamic node as the file gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroNode {
    /// Span position from the blade root (m).
    pub span: f64,
    /// Chord (m).
    pub chord: f64,
    /// Aerodynamic twist (rad), toward feather positive (AeroDyn's `BlTwist` sign).
    pub twist: f64,
    /// Distance from the structure's reference axis forward (toward the leading edge) to the
    /// aerodynamic centre, along the chord (m).
    pub ac_ahead: f64,
    pub polar: Arc<Polar>,
}

/// The aerodynamic description of one blade: nodes with strictly increasing span.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroBlade {
    pub nodes: Vec<AeroNode>,
    /// Prebend: `(span, offset)` of the blade's axis out of the coned root axis, downwind
    /// positive (m), spans increasing; empty for a straight blade (docs/model.md §12.2).
    pub prebend: Vec<(f64, f64)>,
    /// Where the description came from, for messages.
    pub origin: String,
}

/// Chord, twist, centre and polar at one span position, interpolated between nodes.
#[derive(Debug, Clone)]
pub struct AeroSection {
    pub chord: f64,
    pub twist: f64,
    pub ac_ahead: f64,
    pub polar: Arc<Polar>,
}

impl AeroBlade {
    /// Span of the first and last node (m).
    pub fn span_range(&self) -> (f64, f64) {
        (self.nodes[0].span, self.nodes[self.nodes.len() - 1].span)
    }

    /// The prebend at `span` (m, downwind), linear between the table's rows and held beyond
    /// them; 0 without a table.
    pub fn prebend_at(&self, span: f64) -> f64 {
        let table = &self.prebend;
        let i = table.partition_point(|&(s, _)| s <= span);
        match (i, table.len()) {
            (_, 0) => 0.0,
            (0, _) => table[0].1,
            (i, n) if i == n => table[n - 1].1,
            (i, _) => {
                let ((s0, w0), (s1, w1)) = (table[i - 1], table[i]);
                w0 + (span - s0) / (s1 - s0) * (w1 - w0)
            }
        }
    }

    /// The section at `span`: chord, twist and centre linear between the neighbouring nodes, the
    /// polar their blend by the same weight (one node's own polar where both share it); held at
    /// the end nodes beyond the described span.
    pub fn section_at(&self, span: f64) -> crate::error::Result<AeroSection> {
        let n = self.nodes.len();
        let i = self
            .nodes
            .partition_point(|node| node.span <= span)
            .clamp(1, n.max(2) - 1);
        if n == 1 {
            let a = &self.nodes[0];
            return Ok(AeroSection {
                chord: a.chord,
                twist: a.twist,
                ac_ahead: a.ac_ahead,
                polar: Arc::clone(&a.polar),
            });
        }
        let (a, b) = (&self.nodes[i - 1], &self.nodes[i]);
        let t = ((span - a.span) / (b.span - a.span)).clamp(0.0, 1.0);
        let lerp = |x: f64, y: f64| x + t * (y - x);
        let polar = if Arc::ptr_eq(&a.polar, &b.polar) || t == 0.0 {
            Arc::clone(&a.polar)
        } else if t == 1.0 {
            Arc::clone(&b.polar)
        } else {
            Arc::new(
                a.polar
                    .blend(&b.polar, t, &format!("{} at span {span:.3} m", self.origin))?,
            )
        };
        Ok(AeroSection {
            chord: lerp(a.chord, b.chord),
            twist: lerp(a.twist, b.twist),
            ac_ahead: lerp(a.ac_ahead, b.ac_ahead),
            polar,
        })
    }
}
