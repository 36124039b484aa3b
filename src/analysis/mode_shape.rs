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
//!
//! A rotor's or turbine's mode is drawn on each of its parts: every blade at its azimuth and the
//! tower along its height. All parts are turned by the same factor, that of the mode's main part
//! (the tower where it holds most of the mode's energy, else blade 1), so the sizes and phases of
//! the other parts are relative to the same reference: a whirl shows as the blades' phases.

use crate::analysis::mode::Mode;
use crate::physics::structure::{Family, PartKind, ShapePart, Structure};
use crate::physics::turbine::tower::TowerMode;
use nalgebra::{Complex, DVector};

/// A component with less of the mode's kinetic energy than this is absent (round-off of an
/// exactly uncoupled motion, e.g. the twist of an NREL 5MW flap mode, whose file has no coupling
/// or offsets); the real couplings of the reference blades give shares of 1e-5 and more.
const NEGLIGIBLE_SHARE: f64 = 1e-12;

/// One mode on one part, ready to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShape {
    /// `blade` (the one blade), `blade 2`, `tower`.
    pub part: String,
    pub kind: PartKind,
    /// Positions along the part (m from its root or base).
    pub span: Vec<f64>,
    /// Flap, edge and twist along it (in [`Family::ALL`] order; a tower's fore–aft, side–side
    /// and torsion): the real part of the normalised shape, each divided by its own peak
    /// magnitude (all zero where the component is absent, as the edge of the paper's
    /// flap–torsion blade).
    pub components: [Vec<f64>; 3],
    /// Each component's peak magnitude per unit of the reference (m or rad, per m or rad).
    pub peaks: [f64; 3],
    /// Each component's phase at its peak, relative to the reference (deg, in (−180, 180]).
    pub phases: [f64; 3],
}

/// One mode on every part of its structure.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShapes {
    pub parts: Vec<ModeShape>,
    /// The part holding the reference: +1 at its peak there.
    pub main: usize,
    /// The reference component: the dominant family of the mode's motion.
    pub reference: Family,
}

/// The structure's parts with their motion rows, evaluated once for all the modes of a solve.
pub struct PartRows {
    parts: Vec<ShapePart>,
}

impl PartRows {
    pub fn of(structure: &dyn Structure) -> PartRows {
        PartRows {
            parts: structure.shape_parts(),
        }
    }
}

/// The shape of a structural root (its eigenvector's first `n_q` entries, `mode.shape`) on each
/// of `structure`'s parts, whose motion rows `at` holds. A root named after the tower, or whose
/// largest energy component is the tower's, has the tower for its main part, and the plane it is
/// named after for reference.
pub fn mode_shape(structure: &dyn Structure, at: &PartRows, mode: &Mode) -> ModeShapes {
    let q = &mode.shape;
    let raw: Vec<[Vec<Complex<f64>>; 3]> = at.parts.iter().map(|p| along(p, q)).collect();
    let shares = structure.shares(q);
    // The plane a root named after the tower moves in, as a family ([`TowerMode`]).
    let named_plane = TowerMode::of_name(&mode.label).map(|t| t.family_and_number().0);
    let tower_dominates = structure.components(q).is_some_and(|c| {
        c.tower
            > c.blade_flap
                .max(c.blade_edge)
                .max(c.blade_twist)
                .max(c.drivetrain)
    });
    let tower = at
        .parts
        .iter()
        .position(|p| p.kind == PartKind::Tower)
        .filter(|_| named_plane.is_some() || tower_dominates);
    let main = tower.unwrap_or(0);
    // The dominant family (on the tower, the plane the root is named after), or the next where
    // the main part does not move in it (a blade mode's edge, say, that the tower holds none of).
    let mut families = Family::ALL;
    families.sort_by(|a, b| shares.array()[b.index()].total_cmp(&shares.array()[a.index()]));
    if let (Some(_), Some(named)) = (tower, named_plane) {
        families.sort_by_key(|f| *f != named);
    }
    let (reference, anchor) = families
        .iter()
        .map(|&f| (f, peak_of(&raw[main][f.index()])))
        .find(|(_, anchor)| anchor.norm() > 0.0)
        .unwrap_or((shares.family(), Complex::new(1.0, 0.0)));
    // Divide by the reference's peak value: it becomes +1, every other value relative to it.
    let turn = anchor.inv();
    let parts = at
        .parts
        .iter()
        .zip(&raw)
        .map(|(part, raw)| {
            let mut components: [Vec<f64>; 3] = Default::default();
            let mut peaks = [0.0; 3];
            let mut phases = [0.0; 3];
            for k in 0..3 {
                let values: Vec<Complex<f64>> = raw[k].iter().map(|v| v * turn).collect();
                let peak = peak_of(&values);
                // Round-off where the model has no such motion: nothing to draw, not noise
                // blown up.
                if shares.array()[k] < NEGLIGIBLE_SHARE || peak.norm() == 0.0 {
                    components[k] = vec![0.0; values.len()];
                    continue;
                }
                peaks[k] = peak.norm();
                phases[k] = peak.arg().to_degrees();
                // `+ 0.0` turns −0 (the clamped root) into 0.
                components[k] = values.iter().map(|v| v.re / peaks[k] + 0.0).collect();
            }
            ModeShape {
                part: part.name.clone(),
                kind: part.kind,
                span: part.points.clone(),
                components,
                peaks,
                phases,
            }
        })
        .collect();
    ModeShapes {
        parts,
        main,
        reference,
    }
}

/// Flap, edge and twist of `q` at each of the part's points.
fn along(part: &ShapePart, q: &[Complex<f64>]) -> [Vec<Complex<f64>>; 3] {
    // The part's own coordinates, real and imaginary parts apart (the rows are real).
    let re = &part.map * DVector::from_iterator(q.len(), q.iter().map(|c| c.re));
    let im = &part.map * DVector::from_iterator(q.len(), q.iter().map(|c| c.im));
    part.rows.each_ref().map(|rows| {
        let (re, im) = (rows * &re, rows * &im);
        re.iter()
            .zip(im.iter())
            .map(|(&r, &i)| Complex::new(r, i))
            .collect()
    })
}

/// The value of largest magnitude (zero for none).
fn peak_of(values: &[Complex<f64>]) -> Complex<f64> {
    values
        .iter()
        .copied()
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))
        .unwrap_or_default()
}
