//! Mode tracking along a swept parameter (docs/model.md §6.2): which root at the next parameter
//! value continues a root's branch.
//!
//! Consecutive points are matched by the assignment (Kuhn–Munkres, [`hungarian`]) minimising the
//! summed cost `1 − C + |λa − λb| / (|λa| + |λb|)`, where `C` is the correlation of the two roots'
//! eigenvectors: the Modal Assurance Criterion `MAC(a, b) = |aᴴb|² / (|a|²|b|²)` of the right
//! vectors, times that of the left vectors where both roots have them (the left vector is what
//! a root responds to, so two roots with alike shapes but different excitations are told apart),
//! and the second term the eigenvalue's continuity. Why not greedy best-MAC: at a crossing or
//! veering two candidates have similar costs, and a greedy pick for one root can steal the
//! partner the other needs; the optimal assignment looks at both together.
//!
//! A match is **ambiguous** when another partner would cost almost as much (within
//! [`AMBIGUITY_MARGIN`]) or when it swaps frequency order with another match (a crossing, or a
//! veering narrower than the step) and either root's shape has turned enough over the step
//! ([`kept_shape`]) for that veering to be one refinement could resolve; then [`follow`]
//! re-solves the midpoint and follows the branch over the two half steps, down to
//! [`REFINEMENT_DEPTH`] halvings, rather than guess. A rotor's roots of two whirls neither veer
//! nor compete for a partner.

use crate::analysis::mode::Mode;
use crate::numeric::hungarian;
use crate::physics::turbine::ground::Whirl;
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

/// Correlation of two roots (0…1): MAC of their right vectors, times MAC of their left vectors
/// when both have one.
pub fn correlation(a: &Mode, b: &Mode) -> f64 {
    let right = mac(&a.shape, &b.shape);
    if a.left_shape.is_empty() || b.left_shape.is_empty() {
        right
    } else {
        right * mac(&a.left_shape, &b.left_shape)
    }
}

/// Relative distance of two roots' eigenvalues (0…1).
fn distance(a: &Mode, b: &Mode) -> f64 {
    let la = Complex::new(a.re, a.im);
    let lb = Complex::new(b.re, b.im);
    (la - lb).norm() / (la.norm() + lb.norm()).max(f64::MIN_POSITIVE)
}

/// Cost of matching `a` with `b` (0 for the same root; at most 2).
pub fn cost(a: &Mode, b: &Mode) -> f64 {
    1.0 - correlation(a, b) + distance(a, b)
}

/// A match is ambiguous when its best alternative costs less than this much more.
pub const AMBIGUITY_MARGIN: f64 = 0.25;

/// Halvings of a step at most when following an ambiguous match (1/16 of the step).
pub const REFINEMENT_DEPTH: usize = 4;

/// The optimal matching of two points' roots.
#[derive(Debug, Clone, PartialEq)]
pub struct Matching {
    /// For each root of the first point, its partner in the second, if any.
    pub partner: Vec<Option<usize>>,
    /// Whether each root's match is ambiguous (another partner nearly as good).
    pub ambiguous: Vec<bool>,
}

/// For each root of `previous`, its partner in `next` (optimal total cost), or none, over a step
/// that refinement may halve [`REFINEMENT_DEPTH`] times.
pub fn match_modes(previous: &[Mode], next: &[Mode]) -> Matching {
    match_refinable(previous, next, REFINEMENT_DEPTH)
}

/// [`match_modes`] over a step that refinement may still halve `halvings` times (what decides
/// which frequency-order swaps are in doubt: [`kept_shape`]).
fn match_refinable(previous: &[Mode], next: &[Mode], halvings: usize) -> Matching {
    let (n, m) = (previous.len(), next.len());
    let size = n.max(m);
    // Padding (unmatched) costs more than any real pairing (real costs are ≤ 2).
    let mut c = vec![vec![3.0; size]; size];
    for (i, a) in previous.iter().enumerate() {
        for (j, b) in next.iter().enumerate() {
            c[i][j] = cost(a, b);
        }
    }
    let assigned = hungarian(&c);
    let partner: Vec<Option<usize>> = (0..n)
        .map(|i| Some(assigned[i]).filter(|&j| j < m))
        .collect();
    let ambiguous = partner
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let Some(j) = *p else { return false };
            let rival = rival(previous, i, next, j, |a, b| c[a][b]);
            rival - c[i][j] < AMBIGUITY_MARGIN || crosses(previous, next, &partner, i, halvings)
        })
        .collect();
    Matching { partner, ambiguous }
}

/// The cheapest pairing that competes with `i` ↔ `j`: `i` with another root of `next`, or `j`
/// with another root of `previous`, among the roots that could share a branch with them (a
/// rotor's roots of two whirls never do: [`may_veer`]).
fn rival(
    previous: &[Mode],
    i: usize,
    next: &[Mode],
    j: usize,
    cost: impl Fn(usize, usize) -> f64,
) -> f64 {
    let row = (0..next.len())
        .filter(|&k| k != j && may_veer(&previous[i], &next[k]))
        .map(|k| cost(i, k));
    let column = (0..previous.len())
        .filter(|&k| k != i && may_veer(&previous[k], &next[j]))
        .map(|k| cost(k, j));
    row.chain(column).fold(f64::INFINITY, f64::min)
}

/// Whether root `i`'s match swaps frequency order with another matched root: a crossing within
/// the step, which a veering narrower than the step looks like too (the shapes swap over the
/// veering, so a coarse step matches them across it); only a finer step tells the two apart,
/// unless both roots keep their shapes over the step so well ([`kept_shape`]) that any veering
/// would be narrower than the finest step too: then the match by shape is what refinement would
/// end on, and the step is a crossing.
///
/// A rotor's roots in the ground frame cross only where they can veer: two roots of different
/// whirls (backward, forward, collective: [`Whirl::of_name`]) are two blade roots 1P or 2P apart in the
/// blades' own frame, far from the near-resonance a veering needs, so their lines (which
/// cross everywhere on a Campbell diagram) are crossings, not refined.
fn crosses(
    previous: &[Mode],
    next: &[Mode],
    partner: &[Option<usize>],
    i: usize,
    halvings: usize,
) -> bool {
    let Some(j) = partner[i] else { return false };
    let kept = |a: &Mode, b: &Mode| kept_shape(a, b, halvings);
    partner.iter().enumerate().any(|(k, p)| {
        p.is_some_and(|l| {
            k != i
                && may_veer(&previous[i], &previous[k])
                && (previous[i].im - previous[k].im) * (next[j].im - next[l].im) < 0.0
                && !(kept(&previous[i], &next[j]) && kept(&previous[k], &next[l]))
        })
    })
}

/// Whether root `a`'s partner `b` over a step that refinement may still halve `halvings` times
/// has kept its shape too well to be passing through a veering that refinement could resolve.
/// Two modes veering over a width `w` turn each other's shapes: across a step `h` that holds the
/// veering, `1 − MAC ≥ (w/h)²` for the pair matched across it by shape (the two-mode model of
/// docs/model.md §6.2), so `1 − C ≤ 4^−halvings` means `w ≤ h/2^halvings`, the finest step
/// (`(1/16)²` on a sweep's step). On the finest step (no halving left) a swap stays in doubt:
/// there the finest step's own rule decides ([`clear`]).
fn kept_shape(a: &Mode, b: &Mode, halvings: usize) -> bool {
    halvings > 0 && 1.0 - correlation(a, b) <= 0.25f64.powi(halvings as i32)
}

/// Whether two roots could veer: not a rotor's roots of two different whirls.
fn may_veer(a: &Mode, b: &Mode) -> bool {
    match (Whirl::of_name(&a.label), Whirl::of_name(&b.label)) {
        (Some(x), Some(y)) => x == y,
        _ => true,
    }
}

/// The roots of one solved point along the parameter.
pub struct Point<'a> {
    pub value: f64,
    pub modes: &'a [Mode],
}

/// The root of `b` that root `index` of `a` reaches along its branch: the optimal match, and
/// where that is ambiguous, the branch followed through re-solved midpoints (`solve`, none if
/// the midpoint cannot be solved), at most `depth` halvings deep.
pub fn follow(
    a: &Point,
    index: usize,
    b: &Point,
    depth: usize,
    solve: &dyn Fn(f64) -> Option<Vec<Mode>>,
) -> Option<usize> {
    branch(a, index, b, depth, solve, Undecided::Guess)
}

/// [`follow`], or none where the tracking cannot decide: on the finest step the match is still
/// not clear (see [`clear`]), a midpoint it needs cannot be solved, or the root has no partner.
/// A rival within [`AMBIGUITY_MARGIN`] alone does not leave it undecided there: two flap roots
/// a tenth of a hertz apart stay that close however fine the step.
pub fn follow_decided(
    a: &Point,
    index: usize,
    b: &Point,
    depth: usize,
    solve: &dyn Fn(f64) -> Option<Vec<Mode>>,
) -> Option<usize> {
    branch(a, index, b, depth, solve, Undecided::Refuse)
}

/// What [`branch`] answers where refinement cannot settle a match: the optimal match (a
/// Campbell track must go on), or none (a name must not be guessed).
#[derive(Clone, Copy, PartialEq)]
enum Undecided {
    Guess,
    Refuse,
}

fn branch(
    a: &Point,
    index: usize,
    b: &Point,
    depth: usize,
    solve: &dyn Fn(f64) -> Option<Vec<Mode>>,
    undecided: Undecided,
) -> Option<usize> {
    let m = match_refinable(a.modes, b.modes, depth);
    if !m.ambiguous[index] {
        return m.partner[index];
    }
    let guess = undecided == Undecided::Guess;
    if depth == 0 {
        let j = m.partner[index]?;
        return (guess || clear(a.modes, index, b.modes, j)).then_some(j);
    }
    let value = 0.5 * (a.value + b.value);
    let Some(modes) = solve(value) else {
        return m.partner[index].filter(|_| guess);
    };
    let mid = Point {
        value,
        modes: &modes,
    };
    let at_mid = branch(a, index, &mid, depth - 1, solve, undecided)?;
    branch(&mid, at_mid, b, depth - 1, solve, undecided)
}

/// Whether root `i` of `previous` matching root `j` of `next` is clear on a step too fine to
/// refine: it costs less than half of the best rival pairing of either, or `j` is also the root
/// nearest in eigenvalue (a root's eigenvector can turn within a step where its eigenvalue moves
/// on smoothly, as the IEA 15MW's 3.1 Hz flap root does near 10.345 rpm with bend–twist coupling).
fn clear(previous: &[Mode], i: usize, next: &[Mode], j: usize) -> bool {
    let rival = rival(previous, i, next, j, |a, b| cost(&previous[a], &next[b]));
    let nearest = (0..next.len()).min_by(|&a, &b| {
        distance(&previous[i], &next[a]).total_cmp(&distance(&previous[i], &next[b]))
    });
    cost(&previous[i], &next[j]) < 0.5 * rival || nearest == Some(j)
}

/// One tracked branch: its label where it starts and its index in each point's mode list.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    pub label: String,
    /// The point where the track starts (its first root).
    pub start: usize,
    pub index: Vec<Option<usize>>,
}

/// Follow every branch through `points` (no refinement), starting a track at every root no
/// earlier track claims: the roots of the first solved point, and any root that appears later.
pub fn track_modes(points: &[Vec<Mode>]) -> Vec<Track> {
    let mut tracks: Vec<Track> = Vec::new();
    // Reference (last matched) root of each track.
    let mut reference: Vec<Mode> = Vec::new();
    for (k, modes) in points.iter().enumerate() {
        let assignment = match_modes(&reference, modes).partner;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn mode(label: &str, freq: f64, shape: &[f64]) -> Mode {
        Mode {
            label: label.into(),
            shape: shape.iter().map(|&x| Complex::new(x, 0.0)).collect(),
            ..Mode::root(-0.1, freq)
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

    /// Two lines of a rotor's Campbell diagram crossing: of different whirls they are a
    /// crossing, matched without refinement; of one whirl (or one blade's) they could be a
    /// veering narrower than the step, and the match is left to refinement.
    #[test]
    fn only_roots_of_one_whirl_can_veer() {
        let cross = |a: &str, b: &str| {
            let before = [mode(a, 1.0, &[1.0, 0.0]), mode(b, 2.0, &[0.0, 1.0])];
            // Shapes turned as a veering's are, by more than kept_shape allows.
            let after = [mode(a, 2.0, &[1.0, 0.2]), mode(b, 1.0, &[-0.2, 1.0])];
            match_modes(&before, &after)
        };
        let m = cross("BW edge 2", "FW flap 3");
        assert_eq!(m.partner, [Some(0), Some(1)]);
        assert_eq!(m.ambiguous, [false, false]);
        for (a, b) in [
            ("BW edge 2", "BW flap 3"),
            ("edge 2", "flap 3"),
            ("tower FA 2", "FW flap 1"),
        ] {
            assert_eq!(cross(a, b).ambiguous, [true, true], "{a} and {b}");
        }
    }

    /// Two roots of nearly one shape compete for a partner only where they could share a
    /// branch: of one whirl, the match is in doubt; of two whirls (a rotor's FW and collective
    /// flap 5, 12 mHz apart), it is not.
    #[test]
    fn only_roots_of_one_whirl_compete_for_a_partner() {
        let doubt = |a: &str, b: &str| {
            let before = [mode(a, 6.80, &[1.0, 0.10]), mode(b, 6.82, &[1.0, 0.12])];
            let after = [mode(a, 6.81, &[1.0, 0.10]), mode(b, 6.83, &[1.0, 0.12])];
            let m = match_modes(&before, &after);
            assert_eq!(m.partner, [Some(0), Some(1)]);
            m.ambiguous
        };
        assert_eq!(doubt("FW flap 5", "collective flap 5"), [false, false]);
        assert_eq!(doubt("FW flap 5", "FW flap 6"), [true, true]);
        assert_eq!(doubt("flap 5", "tower FA 2"), [true, true]);
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

    /// The two modes of `M = I`, `K = [[1 + p, c], [c, 2 − p]]` at `p`, lightly damped: their
    /// uncoupled frequencies cross at p = ½; coupling `c` turns the crossing into a veering.
    fn two_modes(p: f64, c: f64) -> Vec<Mode> {
        let k = nalgebra::Matrix2::new(1.0 + p, c, c, 2.0 - p);
        let eig = k.symmetric_eigen();
        (0..2)
            .map(|j| {
                let omega = eig.eigenvalues[j].sqrt();
                let v = eig.eigenvectors.column(j);
                let shape: Vec<Complex<f64>> = v.iter().map(|&x| Complex::new(x, 0.0)).collect();
                Mode {
                    label: format!("mode {j}"),
                    left_shape: shape.clone(),
                    shape,
                    ..Mode::root(-0.01 * omega, omega)
                }
            })
            .collect()
    }

    /// A veering far narrower than the finest refinement (coupling 10⁻³: width 0.002 against
    /// a finest step of 0.025) turns neither shape measurably over the step, so the swap is taken
    /// for the crossing it looks like without re-solving a midpoint; one as wide as 1.6 finest
    /// steps (coupling 0.02) turns them, and is followed through midpoints onto its branch, as
    /// a sweep fine enough to resolve it agrees.
    #[test]
    fn only_a_veering_refinement_could_resolve_is_refined() {
        for (c, resolved) in [(1e-3, false), (0.02, true)] {
            let followed = follow_lower(0.31, 0.71, c);
            assert_eq!(followed.solves > 0, resolved, "c = {c}: midpoints solved");
            // Resolved, the lower branch stays lower; unresolved, the shape crosses over.
            assert_eq!(followed.to == followed.lower_at_b, resolved, "c = {c}");
            if resolved {
                assert_eq!(
                    sweep_lower(0.31, 0.001, 400, c),
                    followed.to,
                    "c = {c}: refinement disagrees with a fine sweep"
                );
            }
        }
    }

    /// Where the lower root of [`two_modes`] at `a` lands at `b` by [`follow`].
    struct Followed {
        to: usize,
        lower_at_b: usize,
        /// Midpoints solved on the way.
        solves: usize,
    }

    fn follow_lower(a: f64, b: f64, c: f64) -> Followed {
        let solves = std::cell::Cell::new(0);
        let solve = |p: f64| {
            solves.set(solves.get() + 1);
            Some(two_modes(p, c))
        };
        let (a_modes, b_modes) = (two_modes(a, c), two_modes(b, c));
        let to = follow(
            &Point {
                value: a,
                modes: &a_modes,
            },
            lower(&a_modes),
            &Point {
                value: b,
                modes: &b_modes,
            },
            REFINEMENT_DEPTH,
            &solve,
        )
        .unwrap();
        Followed {
            to,
            lower_at_b: lower(&b_modes),
            solves: solves.get(),
        }
    }

    /// Where the lower root of [`two_modes`] at `a` lands after `steps` steps of `step`, each
    /// matched without refinement.
    fn sweep_lower(a: f64, step: f64, steps: usize, c: f64) -> usize {
        let first = two_modes(a, c);
        let mut here = (lower(&first), first);
        for k in 1..=steps {
            let next = two_modes(a + step * k as f64, c);
            here = (match_modes(&here.1, &next).partner[here.0].unwrap(), next);
        }
        here.0
    }

    fn lower(modes: &[Mode]) -> usize {
        if modes[0].im < modes[1].im {
            0
        } else {
            1
        }
    }

    #[test]
    fn a_crossing_keeps_each_shape_and_a_veering_keeps_each_branch() {
        // Coarse steps straddling p = ½, where the matching is ambiguous: the branch is
        // followed through re-solved midpoints.
        for (c, crosses) in [(0.0, true), (0.1, false)] {
            let followed = follow_lower(0.3, 0.7, c);
            // Uncoupled: the lower mode's shape crosses to the upper frequency. Coupled: the
            // lower branch stays lower, its shape turning through the veering.
            assert_eq!(followed.to != followed.lower_at_b, crosses, "c = {c}");
            // And the frequency it lands on is continuous with a fine sweep's.
            assert_eq!(
                sweep_lower(0.3, 0.01, 40, c),
                followed.to,
                "c = {c}: refinement disagrees with a fine sweep"
            );
        }
    }
}
