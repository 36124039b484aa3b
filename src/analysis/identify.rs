//! Mode identification: which roots of the aeroelastic system are the blade's structural modes,
//! and which structural mode each one is (docs/model.md §6.2). The one routine behind every name
//! a root carries: `eigen`, `flutter`, `sweep`, the explorer's panes and the plots all read the
//! labels [`identify`] gives, so the same root has the same name everywhere.
//!
//! Input: every root with its structural participation and the structural part of its right
//! eigenvector, and the structure's in-vacuo natural modes at the same rotor speed. Output: the
//! structural modes, named `flap k` / `edge k` / `torsion k` after the natural mode they were
//! assigned to (one-to-one), with the in-vacuo frequency of that mode; an overdamped mode's two
//! real roots as one mode with both decay rates; and the aerodynamic roots apart.
//!
//! Three rules, in order:
//! 1. **Which roots are structural.** The structure has `n_q` degrees of freedom, so `2 n_q`
//!    state dimensions. The roots that hold them are those with the largest structural
//!    participation (a complex pair fills two dimensions, a real root one); the rest are
//!    aerodynamic. Counting instead of a fixed threshold keeps the number of structural roots equal
//!    to what the structure can have, so none is left without a mode to be named after. A rotor
//!    in multi-blade coordinates, whose slots name its roots, decides by the assignment instead
//!    ([`candidates`]; docs/model.md §13.4).
//! 2. **Names.** A root's family is the family of the largest share of its motion's kinetic energy
//!    (flap, edge, twist; [`Structure::shares`], the measure that names the natural modes too).
//!    Roots are assigned to natural modes one-to-one (Kuhn–Munkres) maximising the summed modal
//!    energy share `|η_k|²/Σ|η|²`, `η = Φ̂ᵀMq` on the mass-normalised natural modes, with a
//!    penalty of one whole share for a natural mode of another family: a root takes a name of its
//!    own family whenever the family has one left, and among those the one whose in-vacuo mode
//!    it holds most of. The oscillating roots are named first; the natural modes left take the
//!    real roots, two each (two slots per mode, filled one-to-one by the same cost): a mode
//!    that aerodynamic damping has made non-oscillatory is one mode with two decay rates.

use crate::analysis::mode::Mode;
use crate::error::Result;
use crate::numeric::{hungarian, shares};
use crate::physics::structure::{NaturalMode, Structure};
use nalgebra::{Complex, DVector};

/// Cost of naming a root after a natural mode of another family, in units of modal energy share:
/// more than any difference of shares between two modes of the root's own family.
const FAMILY_PENALTY: f64 = 1.0;

/// Structural modes and aerodynamic roots of one operating point.
pub struct Identified {
    /// Named structural modes (an overdamped pair as one).
    pub structural: Vec<Mode>,
    /// Roots that are mostly aerodynamic state, unnamed.
    pub aero: Vec<Mode>,
}

/// Split `roots` (each with its structural share and shape) into named structural modes and
/// aerodynamic roots. `nq` is the number of structural coordinates.
pub fn identify(roots: Vec<Mode>, nq: usize, structure: &dyn Structure) -> Result<Identified> {
    let slots = |r: &Mode| structure.slot_content(&r.shape, Complex::new(r.re, r.im));
    let by_slots = roots.first().is_some_and(|r| slots(r).is_some());
    let (structural, mut aero) = if by_slots {
        candidates(roots)
    } else {
        split_structural(roots, nq)
    };
    if structural.is_empty() {
        return Ok(Identified { structural, aero });
    }
    let natural = structure.natural_modes()?;
    let content = structural
        .iter()
        .map(slots)
        .collect::<Option<Vec<_>>>()
        .unwrap_or_else(|| modal_content(&structural, &natural, structure));
    let (groups, left) = assign(&structural, &content, by_slots, &natural);
    let mut named: Vec<Mode> = Vec::new();
    for (k, group) in groups {
        let mut modes: Vec<Mode> = group.iter().map(|&i| structural[i].clone()).collect();
        let mut m = merged(&mut modes);
        let n = &natural[k];
        m.label = n.label.clone();
        m.family = Some(n.family);
        m.in_vacuo_hz = Some(n.frequency_hz);
        named.push(m);
    }
    // More structural roots than the natural modes can take: reported with the aerodynamic
    // roots rather than under a borrowed name.
    aero.extend(left.into_iter().map(|i| structural[i].clone()));
    Ok(Identified {
        structural: named,
        aero,
    })
}

/// Rule 1: the roots filling the `2 nq` structural state dimensions, largest structural share
/// first; the rest are aerodynamic. Where the caller took out a rigid body's zero root
/// ([`Structure::rigid_body_roots`]) its dimension stays open: a free rotor's speed root,
/// coupled with an aerodynamic lag into a complex pair, takes it.
fn split_structural(roots: Vec<Mode>, nq: usize) -> (Vec<Mode>, Vec<Mode>) {
    let mut order: Vec<usize> = (0..roots.len()).collect();
    order.sort_by(|&a, &b| {
        roots[b]
            .structural_share
            .total_cmp(&roots[a].structural_share)
    });
    let mut room = 2 * nq;
    let mut is_structural = vec![false; roots.len()];
    for i in order {
        let dims = if roots[i].im > 0.0 { 2 } else { 1 };
        if dims <= room && roots[i].structural_share > 0.0 {
            is_structural[i] = true;
            room -= dims;
        }
    }
    let (mut structural, mut aero) = (Vec::new(), Vec::new());
    for (m, s) in roots.into_iter().zip(is_structural) {
        if s {
            structural.push(m)
        } else {
            aero.push(m)
        }
    }
    (structural, aero)
}

/// Below this structural share a root is an aerodynamic lag wherever the slots name the
/// roots: no structural name is worth its while.
const CANDIDATE_SHARE: f64 = 0.05;

/// Rule 1 where the structure names its roots by slots of its own (a rotor in multi-blade
/// coordinates, [`Structure::slot_content`]): every root holding some structural motion is a
/// candidate, and the assignment of rule 2, weighing each root's content in a slot by its
/// structural share, decides which are structural (those it names). Counting the largest
/// shares first, as for one blade, does not carry over: one blade root appears on a rotor as
/// its collective image and its two whirls, the collective coupled with the drivetrain, and a
/// heavily damped root's images then take dimensions the images of an overdamped mode need,
/// whose names pass down the line (the IEA 15MW above 13 m/s, where flap 1 is overdamped).
/// Each slot still takes one oscillating root or two real ones, so the named roots fill the
/// structural dimensions as rule 1's count does.
fn candidates(roots: Vec<Mode>) -> (Vec<Mode>, Vec<Mode>) {
    roots
        .into_iter()
        .partition(|r| r.structural_share >= CANDIDATE_SHARE)
}

/// Modal energy shares `|η_k|²/Σ|η|²` of each root on the natural modes, `η = Φ̂ᵀ M q` with `Φ̂`
/// mass-normalised (exact modal coordinates for the symmetric structures; an M-weighted
/// projection, all the assignment needs, for the strong form).
fn modal_content(
    roots: &[Mode],
    natural: &[NaturalMode],
    structure: &dyn Structure,
) -> Vec<Vec<f64>> {
    let mass = structure.mass();
    let weights: Vec<DVector<f64>> = natural
        .iter()
        .map(|m| {
            let mphi = mass * &m.shape;
            let modal_mass = m.shape.dot(&mphi);
            if modal_mass > 0.0 {
                mphi / modal_mass.sqrt()
            } else {
                mphi
            }
        })
        .collect();
    roots
        .iter()
        .map(|r| {
            shares(
                weights
                    .iter()
                    .map(|w| {
                        w.iter()
                            .zip(&r.shape)
                            .map(|(wi, qi)| qi * *wi)
                            .sum::<Complex<f64>>()
                            .norm_sqr()
                    })
                    .collect(),
            )
        })
        .collect()
}

/// Cost of leaving a structural root unnamed (more roots than the natural modes can take): worse
/// than any name, so an order that names more roots always wins.
const UNNAMED: f64 = FAMILY_PENALTY + 1.0;

/// Rules 2 and 3: the natural mode each structural root is named after. First the oscillating
/// roots, one-to-one; then the real roots, two to each natural mode left (its overdamped pair),
/// each mode's two slots filled one-to-one by the same cost. When the families do not add up
/// (six roots that are mostly flap for five flap modes, say) the order matters: so the pairs so
/// formed are also named first, as units, and the oscillating roots after them; the order with
/// the smaller total cost is kept (ties: oscillating roots first). The root that fits worst then
/// takes the other family's name, not whichever came second (the IEA 15MW in quasi-steady air:
/// its overdamped flap 1, 97 % flap, was called torsion 1 while a 3.6 Hz root with 37 % twist
/// took flap 1). Returns the roots of each named mode with the mode's index; roots left without
/// a mode are returned apart.
fn assign(
    roots: &[Mode],
    content: &[Vec<f64>],
    by_slots: bool,
    natural: &[NaturalMode],
) -> (Vec<(usize, Vec<usize>)>, Vec<usize>) {
    // Where the slots name the roots, a root's claim on a slot is its content there weighted
    // by how structural it is (rule 1 by assignment, [`candidates`]); the candidates outnumber
    // the names, and one left unnamed is an aerodynamic lag, a loss of its structural share.
    // For one blade every structural root is owed a name.
    let weight = |i: usize| {
        if by_slots {
            roots[i].structural_share
        } else {
            1.0
        }
    };
    let leave: Option<&dyn Fn(usize) -> f64> = if by_slots { Some(&weight) } else { None };
    let unnamed = |i: usize| leave.map_or(UNNAMED, |l| l(i));
    let rigid = |k: usize| natural[k].frequency_hz == 0.0;
    let cost = |i: usize, k: usize| -> f64 {
        // A rigid body (a free rotor's speed) takes only a root that is mostly its motion:
        // any other mode's root holds a little of it, none of its own name.
        if rigid(k) && content[i][k] < 0.5 {
            return MISFIT;
        }
        // A rotor's root takes no slot it holds next to nothing of: left over, it would be
        // named after whatever slot the others left (the IEA 15MW's yaw-and-flap root at
        // 2.2 Hz, no twist, called `collective torsion 1` at 11 m/s).
        if by_slots && content[i][k] < SLOT_FLOOR {
            return MISFIT;
        }
        penalty(&roots[i], &natural[k], by_slots) - weight(i) * content[i][k]
    };
    let oscillating: Vec<usize> = (0..roots.len()).filter(|&i| roots[i].im > 0.0).collect();
    let real: Vec<usize> = (0..roots.len()).filter(|&i| roots[i].im == 0.0).collect();
    let modes: Vec<usize> = (0..natural.len()).collect();
    let total = |(named, left): &(Vec<(usize, Vec<usize>)>, Vec<usize>)| -> f64 {
        let named: f64 = named
            .iter()
            .flat_map(|(k, group)| group.iter().map(move |&i| cost(i, *k)))
            .sum();
        named + left.iter().map(|&i| unnamed(i)).sum::<f64>()
    };
    let (mut named, mut left, free) = name_oscillating(&oscillating, &modes, &cost, leave);
    let (pairs, unpaired) = name_real(&real, &free, &cost, &rigid, leave);
    named.extend(pairs.iter().cloned());
    left.extend(unpaired.iter().copied());
    let oscillating_first = (named, left);
    let units: Vec<Vec<usize>> = pairs.into_iter().map(|(_, group)| group).collect();
    // A rigid mode takes one real root, never a pair.
    let pair_cost = |i: usize, k: usize| {
        let pair = units.iter().any(|u| u.len() > 1 && u.contains(&i));
        if pair && rigid(k) {
            MISFIT
        } else {
            cost(i, k)
        }
    };
    let (mut named, mut left, free) = name_units(&units, &modes, &pair_cost, leave);
    let (single, unnamed_roots, _) = name_oscillating(&oscillating, &free, &cost, leave);
    named.extend(single);
    left.extend(unnamed_roots);
    left.extend(unpaired);
    let pairs_first = (named, left);
    if total(&pairs_first) < total(&oscillating_first) - 1e-9 {
        pairs_first
    } else {
        oscillating_first
    }
}

/// What naming `root` after natural mode `n` of another family costs: [`FAMILY_PENALTY`] if
/// the root's family is neither the one the name says nor the one the mode's motion in vacuo
/// has (a rotor's `collective flap 6`, its blades' flap 6 swinging the hub, can be mostly
/// edge). `graded` (a rotor's slots): the penalty times how much more of the root's energy
/// lies in its own family than in the name's, so that a root split evenly between flap and
/// edge (a large blade's edge 2 in the wind) fits either family's name as well.
fn penalty(root: &Mode, n: &NaturalMode, graded: bool) -> f64 {
    let family = root.shares.family();
    if family == n.family || family == n.shares.family() {
        return 0.0;
    }
    if !graded {
        return FAMILY_PENALTY;
    }
    let s = root.shares.array();
    let own = s[family.index()];
    let named = s[n.family.index()].max(s[n.shares.family().index()]);
    FAMILY_PENALTY * (own - named).max(0.0)
}

/// The least content a rotor's root must hold in a slot to be named after it (its share of the
/// root's kinetic energy there, [`Structure::slot_content`]).
const SLOT_FLOOR: f64 = 0.05;

/// Cost of a name a root cannot take (an overdamped pair for a rigid mode's one real root):
/// far above any other, so it is taken only when nothing else is left.
const MISFIT: f64 = 1e3;

/// Named groups, roots left unnamed, and the natural modes still free.
type Naming = (Vec<(usize, Vec<usize>)>, Vec<usize>, Vec<usize>);

/// Oscillating roots, one natural mode each, among `modes` ([`one_to_one`]'s `leave`).
fn name_oscillating(
    roots: &[usize],
    modes: &[usize],
    cost: &dyn Fn(usize, usize) -> f64,
    leave: Option<&dyn Fn(usize) -> f64>,
) -> Naming {
    let units: Vec<Vec<usize>> = roots.iter().map(|&i| vec![i]).collect();
    name_units(&units, modes, cost, leave)
}

/// Groups of roots (an oscillating root, an overdamped pair), one natural mode each, among
/// `modes`, at the summed cost of their roots.
fn name_units(
    units: &[Vec<usize>],
    modes: &[usize],
    cost: &dyn Fn(usize, usize) -> f64,
    leave: Option<&dyn Fn(usize) -> f64>,
) -> Naming {
    let rows: Vec<usize> = (0..units.len()).collect();
    let unit_cost = |u: usize, k: usize| units[u].iter().map(|&i| cost(i, k)).sum::<f64>();
    let unit_leave = |u: usize| leave.map_or(0.0, |l| units[u].iter().map(|&i| l(i)).sum());
    let leave: Option<&dyn Fn(usize) -> f64> = leave.map(|_| &unit_leave as &dyn Fn(usize) -> f64);
    let mut named = Vec::new();
    let mut left = Vec::new();
    let mut free = modes.to_vec();
    for (&u, k) in rows.iter().zip(one_to_one(&rows, modes, &unit_cost, leave)) {
        match k {
            Some(k) => {
                named.push((k, units[u].clone()));
                free.retain(|&f| f != k);
            }
            None => left.extend(units[u].iter().copied()),
        }
    }
    (named, left, free)
}

/// The real roots, two to each of `modes` (an overdamped pair's two decay rates) and one to a
/// `rigid` one (a natural mode at zero frequency: a free rotor's speed, whose azimuth the
/// caller took out), the slots filled one-to-one: the groups formed and the roots left over.
fn name_real(
    roots: &[usize],
    modes: &[usize],
    cost: &dyn Fn(usize, usize) -> f64,
    rigid: &dyn Fn(usize) -> bool,
    leave: Option<&dyn Fn(usize) -> f64>,
) -> (Vec<(usize, Vec<usize>)>, Vec<usize>) {
    let slots: Vec<usize> = modes
        .iter()
        .flat_map(|&k| if rigid(k) { vec![k] } else { vec![k, k] })
        .collect();
    let mut groups: Vec<(usize, Vec<usize>)> = Vec::new();
    let mut left = Vec::new();
    for (&i, k) in roots.iter().zip(one_to_one(roots, &slots, cost, leave)) {
        match k {
            Some(k) => match groups.iter_mut().find(|(m, _)| *m == k) {
                Some((_, r)) => r.push(i),
                None => groups.push((k, vec![i])),
            },
            None => left.push(i),
        }
    }
    (groups, left)
}

/// For each row, the column it is assigned to (minimum total `cost`), or none. Without `leave`
/// as many rows as there are columns are assigned, whatever it costs; with it, row `i` may
/// stay unassigned at cost `leave(i)` and a column empty at none (a name no candidate fits
/// stays free).
fn one_to_one(
    rows: &[usize],
    columns: &[usize],
    cost: &dyn Fn(usize, usize) -> f64,
    leave: Option<&dyn Fn(usize) -> f64>,
) -> Vec<Option<usize>> {
    let (n, m) = (rows.len(), columns.len());
    if n == 0 {
        return Vec::new();
    }
    // Without `leave` a row beyond the columns gets none (zero-cost padding); with it, each row
    // may take one of n further columns at the cost of being left.
    let width = match leave {
        None => m,
        Some(_) => m + n,
    };
    let matrix: Vec<Vec<f64>> = rows
        .iter()
        .map(|&i| {
            (0..width)
                .map(|b| match columns.get(b) {
                    Some(&k) => cost(i, k),
                    None => leave.map_or(0.0, |l| l(i)),
                })
                .collect()
        })
        .collect();
    let assigned = hungarian(&matrix);
    (0..n).map(|a| columns.get(assigned[a]).copied()).collect()
}

/// One mode from a candidate's roots: the root itself, or for an overdamped pair the less stable
/// root (it decides stability) carrying the other's decay rate and the pair's damping ratio
/// `ζ = −(σ₁ + σ₂) / (2√(σ₁σ₂))` (the roots of `s² + 2ζω s + ω²`; −sign σ when one grows).
fn merged(modes: &mut [Mode]) -> Mode {
    modes.sort_by(|a, b| b.re.total_cmp(&a.re));
    let mut m = modes[0].clone();
    if let Some(other) = modes.get(1) {
        let (s1, s2) = (m.re, other.re);
        m.second_re = Some(s2);
        m.damping_ratio = if s1 * s2 > 0.0 {
            -(s1 + s2) / (2.0 * (s1 * s2).sqrt())
        } else {
            -s1.signum()
        };
        m.structural_share = 0.5 * (m.structural_share + other.structural_share);
    }
    m
}
