//! Mode tracking along a swept parameter by eigenvector correlation (MAC; docs/model.md §6.2).
//!
//! Input: the structural modes at consecutive parameter values (each with its Galerkin shape); a
//! point that could not be solved has none. Output: tracks — for each mode, the index of the same
//! physical mode at every point, or none where it has no root: before it appears, at a point that
//! could not be solved, or where its root merged with another (two real roots of an overdamped
//! mode becoming one oscillating pair). A track starts wherever a root is left unclaimed by the
//! tracks so far: the modes of the first solved point, and any root that appears later (a pair
//! splitting into two real roots), so a failed first point or a growing root count drops nothing.
//!
//! Consecutive points are matched by the assignment that maximises the total Modal Assurance
//! Criterion `MAC(a, b) = |aᴴb|² / (|a|²|b|²)`, solved exactly by the Hungarian algorithm
//! ([`hungarian`]). Why not greedy best-MAC: at a crossing or veering two candidates have similar
//! MACs, and a greedy pick for one mode can steal the partner the other mode needs, swapping
//! identities; the optimal assignment looks at both together. With at most a few dozen modes the
//! O(n³) cost is negligible next to the eigen-solve. Each track compares with the last shape it
//! was matched to, so a mode that rotates slowly through a veering keeps its identity.

use crate::analysis::eigen::Mode;
use crate::numeric::hungarian;
use nalgebra::Complex;

/// Modal Assurance Criterion of two complex shapes (0…1; 0 if either is zero).
pub fn mac(a: &[Complex<f64>], b: &[Complex<f64>]) -> f64 {
    let dot: Complex<f64> = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let na: f64 = a.iter().map(|c| c.norm_sqr()).sum();
    let nb: f64 = b.iter().map(|c| c.norm_sqr()).sum();
    if na == 0.0 || nb == 0.0 {
        0.0
    } else {
        dot.norm_sqr() / (na * nb)
    }
}

/// One tracked mode: its label where it starts and its index in each point's mode list.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub label: String,
    /// The point where the track starts (its first root).
    pub start: usize,
    pub index: Vec<Option<usize>>,
}

/// Weight of the eigenvalue distance in the matching cost. It only breaks ties between shapes
/// that MAC cannot tell apart (e.g. exactly repeated roots); shape similarity decides everything
/// else.
const EIGENVALUE_TIE_BREAK: f64 = 1e-3;

/// Track the modes through `points`, starting a track at every root no earlier track claims.
pub fn track_modes(points: &[Vec<Mode>]) -> Vec<Track> {
    let mut tracks: Vec<Track> = Vec::new();
    // Reference (last matched) mode of each track.
    let mut reference: Vec<Mode> = Vec::new();
    for (k, modes) in points.iter().enumerate() {
        let assignment = match_modes(&reference, modes);
        let mut claimed = vec![false; modes.len()];
        for ((t, r), a) in tracks.iter_mut().zip(&mut reference).zip(&assignment) {
            t.index.push(*a);
            if let Some(j) = *a {
                claimed[j] = true;
                *r = modes[j].clone();
            }
        }
        for (j, m) in modes.iter().enumerate().filter(|(j, _)| !claimed[*j]) {
            let mut index = vec![None; k];
            index.push(Some(j));
            tracks.push(Track {
                label: m.label.clone(),
                start: k,
                index,
            });
            reference.push(m.clone());
        }
    }
    tracks
}

/// For each mode of `previous`, its partner in `next` (optimal total MAC), or none.
pub fn match_modes(previous: &[Mode], next: &[Mode]) -> Vec<Option<usize>> {
    let (n, m) = (previous.len(), next.len());
    let size = n.max(m);
    // Padding (unmatched) costs more than any real pairing: real costs are ≤ 1 + tie-break.
    let mut cost = vec![vec![2.0; size]; size];
    for (i, a) in previous.iter().enumerate() {
        for (j, b) in next.iter().enumerate() {
            let la = Complex::new(a.re, a.im);
            let lb = Complex::new(b.re, b.im);
            let distance = (la - lb).norm() / (la.norm() + lb.norm()).max(f64::MIN_POSITIVE);
            cost[i][j] = 1.0 - mac(&a.shape, &b.shape) + EIGENVALUE_TIE_BREAK * distance;
        }
    }
    let assigned = hungarian(&cost);
    (0..n)
        .map(|i| Some(assigned[i]).filter(|&j| j < m))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(label: &str, freq: f64, shape: &[f64]) -> Mode {
        Mode {
            re: -0.1,
            im: freq,
            frequency_hz: freq / std::f64::consts::TAU,
            damping_ratio: 0.0,
            label: label.into(),
            structural_share: 1.0,
            shape: shape.iter().map(|&x| Complex::new(x, 0.0)).collect(),
        }
    }

    #[test]
    fn mac_is_scale_and_phase_invariant() {
        let a = [Complex::new(1.0, 0.0), Complex::new(0.5, 0.0)];
        let b: Vec<_> = a.iter().map(|c| c * Complex::new(0.0, -3.0)).collect();
        assert!((mac(&a, &b) - 1.0).abs() < 1e-14);
        let c = [Complex::new(-0.5, 0.0), Complex::new(1.0, 0.0)];
        assert!(mac(&a, &c).abs() < 1e-14);
    }

    #[test]
    fn identities_survive_a_frequency_crossing() {
        // Two modes whose frequencies cross between the second and third points; the
        // frequency-sorted lists swap order, the shapes do not.
        let points = vec![
            vec![
                mode("flap 1", 1.0, &[1.0, 0.05]),
                mode("torsion 1", 3.0, &[0.05, 1.0]),
            ],
            vec![
                mode("flap 1", 1.5, &[1.0, 0.04]),
                mode("torsion 1", 2.0, &[0.06, 1.0]),
            ],
            vec![
                mode("flap 1", 1.2, &[0.07, 1.0]),
                mode("torsion 1", 1.9, &[1.0, 0.03]),
            ],
        ];
        let tracks = track_modes(&points);
        assert_eq!(tracks[0].label, "flap 1");
        assert_eq!(tracks[0].index, vec![Some(0), Some(0), Some(1)]);
        assert_eq!(tracks[1].index, vec![Some(1), Some(1), Some(0)]);
    }

    #[test]
    fn a_vanished_mode_is_unmatched() {
        let points = vec![
            vec![mode("a", 1.0, &[1.0, 0.0]), mode("b", 2.0, &[0.0, 1.0])],
            vec![mode("b", 2.0, &[0.0, 1.0])],
        ];
        let tracks = track_modes(&points);
        assert_eq!(tracks[0].index, vec![Some(0), None]);
        assert_eq!(tracks[1].index, vec![Some(1), Some(0)]);
    }

    #[test]
    fn tracks_start_after_a_failed_point_and_where_a_root_appears() {
        // The first point could not be solved (no modes); the second has one root, the third
        // two: tracks start at the first solved point, and the new root starts its own.
        let points = vec![
            vec![],
            vec![mode("a", 1.0, &[1.0, 0.0])],
            vec![mode("a", 1.1, &[1.0, 0.1]), mode("b", 2.0, &[0.0, 1.0])],
        ];
        let tracks = track_modes(&points);
        assert_eq!(tracks.len(), 2);
        assert_eq!((tracks[0].label.as_str(), tracks[0].start), ("a", 1));
        assert_eq!(tracks[0].index, vec![None, Some(0), Some(0)]);
        assert_eq!((tracks[1].label.as_str(), tracks[1].start), ("b", 2));
        assert_eq!(tracks[1].index, vec![None, None, Some(1)]);
    }
}
