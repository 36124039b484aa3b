//! The bend–twist coupling design knob of a tabulated blade (docs/model.md §11.7): a coefficient
//! α that adds `α·√(EI_ξ·GJ)` to the flap–twist coupling `g_ξ` of every station, on top of what
//! the blade's files give (α = 0 is the files' blade). The sign follows `g_ξ` (§11.1): α > 0
//! twists the blade toward feather when it bends downwind.
//!
//! The added coupling must leave each station's bending–torsion stiffness positive definite, or
//! the strain energy is not; [`indefinite_station`] finds the first station where it does not.

use super::{BeamSection, BladeTable};

/// The flap–twist coupling α adds to one station (N·m²).
pub fn added_coupling(s: &BeamSection, alpha: f64) -> f64 {
    alpha * (s.ei_flap * s.gj).sqrt()
}

/// The table with `alpha` added to every station's flap–twist coupling; α = 0 returns the
/// table unchanged, bit for bit.
pub fn with_bend_twist_coupling(table: &BladeTable, alpha: f64) -> BladeTable {
    if alpha == 0.0 {
        return table.clone();
    }
    let mut out = table.clone();
    for s in &mut out.sections {
        s.flap_twist += added_coupling(s, alpha);
    }
    out
}

/// The normalised flap–twist coupling of a station, `g_ξ/√(EI_ξ·GJ)`: what α adds to.
pub fn coupling_ratio(s: &BeamSection) -> f64 {
    s.flap_twist / (s.ei_flap * s.gj).sqrt()
}

/// The first station (index and section) whose stiffness in the curvatures
/// `(κ_ξ, κ_η, φ')` is not positive definite once `alpha` is added (§11.2: the matrix
/// `[[EI_ξ, EI_ξη, −g_ξ], [EI_ξη, EI_η, −g_η], [−g_ξ, −g_η, GJ]]`), if any.
pub fn indefinite_station(table: &BladeTable, alpha: f64) -> Option<(usize, BeamSection)> {
    table.sections.iter().enumerate().find_map(|(k, s)| {
        let g = s.flap_twist + added_coupling(s, alpha);
        (!stiffness_is_definite(s, g)).then_some((k, *s))
    })
}

/// Sylvester's criterion on the section stiffness with flap–twist coupling `g` (scaled by the
/// diagonal, so the test does not depend on the magnitudes, which span decades).
fn stiffness_is_definite(s: &BeamSection, g: f64) -> bool {
    let d = [s.ei_flap.sqrt(), s.ei_edge.sqrt(), s.gj.sqrt()];
    // Correlation form: unit diagonal, off-diagonals scaled by the diagonal roots.
    let a = s.ei_cross / (d[0] * d[1]);
    let b = -g / (d[0] * d[2]);
    let c = -s.edge_twist / (d[1] * d[2]);
    let minor2 = 1.0 - a * a;
    let det = 1.0 + 2.0 * a * b * c - a * a - b * b - c * c;
    minor2 > 0.0 && det > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::blade::ShearFlexibility;

    fn station(g: f64) -> BeamSection {
        BeamSection {
            z: 0.0,
            mass: 100.0,
            cg: [0.0, 0.0],
            inertia: [1.0, 5.0, 0.0],
            ei_flap: 4.0e8,
            ei_edge: 9.0e9,
            ei_cross: 0.0,
            gj: 1.0e8,
            flap_twist: g,
            edge_twist: 0.0,
            twist: 0.0,
            shear_centre: [0.0, 0.0],
            tension_centre: [0.0, 0.0],
            shear: ShearFlexibility::RIGID,
        }
    }

    fn table(g: f64) -> BladeTable {
        let mut tip = station(g);
        tip.z = 10.0;
        BladeTable::new("test", 0.0, vec![station(g), tip]).unwrap()
    }

    #[test]
    fn alpha_adds_its_share_of_the_geometric_mean_stiffness() {
        let t = with_bend_twist_coupling(&table(1.0e8), 0.25);
        // √(4e8 · 1e8) = 2e8.
        assert_eq!(t.sections[0].flap_twist, 1.0e8 + 0.25 * 2.0e8);
        assert_eq!(coupling_ratio(&t.sections[1]), 0.75);
        assert_eq!(with_bend_twist_coupling(&table(1.0e8), 0.0), table(1.0e8));
    }

    #[test]
    fn a_coupling_as_large_as_the_stiffnesses_is_indefinite() {
        // Without edge coupling the criterion is |g| < √(EI_ξ GJ): ratio 1 is the limit.
        assert_eq!(indefinite_station(&table(0.0), 0.3), None);
        assert_eq!(indefinite_station(&table(1.5e8), 0.24), None);
        assert_eq!(
            indefinite_station(&table(1.5e8), 0.26).map(|s| s.0),
            Some(0)
        );
        assert_eq!(
            indefinite_station(&table(-1.5e8), -0.26).map(|s| s.0),
            Some(0)
        );
    }
}
