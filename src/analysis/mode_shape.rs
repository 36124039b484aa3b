//! The shape of one aeroelastic mode along the span (docs/model.md §6.5): the structural part of
//! its eigenvector `q` mapped through the structure's motion rows at its span points into the
//! flap, edge and twist of the reference axis, then made real and normalised for display.
//!
//! An aeroelastic eigenvector is complex: flap and twist need not move in phase (in flutter they
//! do not). The shape is turned by one complex factor so that its dominant component (the family
//! with the largest kinetic-energy share) is real and +1 at its largest value; what is drawn is
//! the real part, each component scaled to its own peak (the three have different units), and
//! each component's peak amplitude and phase there, relative to that reference, say how large and
//! how late it is.

use crate::physics::structure::{Family, MotionRows, Structure};
use nalgebra::Complex;

/// A component with less of the mode's kinetic energy than this is absent (round-off of an
/// exactly uncoupled motion, e.g. the twist of an NREL 5MW flap mode, whose file has no coupling
/// or offsets); the real couplings of the reference blades give shares of 1e-5 and more.
const NEGLIGIBLE_SHARE: f64 = 1e-12;

/// One mode along the span, ready to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShape {
    /// Span positions (m from the root).
    pub span: Vec<f64>,
    /// Flap, edge and twist along the span (in [`Family::ALL`] order): the real part of the
    /// normalised shape, each divided by its own peak magnitude (all zero where the component
    /// is absent, as the edge of the paper's flap–torsion blade).
    pub components: [Vec<f64>; 3],
    /// Each component's peak magnitude per unit of the reference component (flap and edge in m,
    /// twist in rad, per m or rad of the reference).
    pub peaks: [f64; 3],
    /// Each component's phase at its peak, relative to the reference (deg, in (−180, 180]).
    pub phases: [f64; 3],
    /// The dominant family: the reference component, +1 at its peak.
    pub reference: Family,
}

/// The structure's motion rows at its span points, evaluated once for all the modes of a solve.
pub struct SpanRows {
    span: Vec<f64>,
    rows: Vec<MotionRows>,
}

impl SpanRows {
    pub fn of(structure: &dyn Structure) -> SpanRows {
        let span = structure.span_points();
        let rows = span.iter().map(|&x| structure.motion_rows(x)).collect();
        SpanRows { span, rows }
    }
}

/// The shape of the structural coordinates `q` (an eigenvector's first `n_q` entries) along
/// `structure`'s span points, whose motion rows `at` holds.
pub fn mode_shape(structure: &dyn Structure, at: &SpanRows, q: &[Complex<f64>]) -> ModeShape {
    let span = at.span.clone();
    let mut raw: [Vec<Complex<f64>>; 3] = Default::default();
    for rows in &at.rows {
        for (values, row) in raw.iter_mut().zip([&rows.flap, &rows.edge, &rows.twist]) {
            values.push(
                row.iter()
                    .zip(q)
                    .map(|(r, qi)| qi * *r)
                    .sum::<Complex<f64>>(),
            );
        }
    }
    let shares = structure.shares(q);
    let reference = shares.family();
    let peak_of = |values: &[Complex<f64>]| {
        values
            .iter()
            .copied()
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
            .unwrap_or_default()
    };
    let anchor = peak_of(&raw[reference.index()]);
    // Divide by the reference's peak value: it becomes +1, every other value relative to it.
    let turn = if anchor.norm() > 0.0 {
        anchor.inv()
    } else {
        Complex::new(1.0, 0.0)
    };
    let mut components: [Vec<f64>; 3] = Default::default();
    let mut peaks = [0.0; 3];
    let mut phases = [0.0; 3];
    for k in 0..3 {
        if shares.array()[k] < NEGLIGIBLE_SHARE {
            // Round-off where the model has no such motion: nothing to draw, not noise blown up.
            components[k] = vec![0.0; span.len()];
            continue;
        }
        let values: Vec<Complex<f64>> = raw[k].iter().map(|v| v * turn).collect();
        let peak = peak_of(&values);
        peaks[k] = peak.norm();
        phases[k] = if peaks[k] > 0.0 {
            peak.arg().to_degrees()
        } else {
            0.0
        };
        components[k] = if peaks[k] > 0.0 {
            // `+ 0.0` turns −0 (the clamped root) into 0.
            values.iter().map(|v| v.re / peaks[k] + 0.0).collect()
        } else {
            vec![0.0; values.len()]
        };
    }
    ModeShape {
        span,
        components,
        peaks,
        phases,
        reference,
    }
}
