//! Flutter-boundary search along one numeric preset key (docs/model.md §6).
//!
//! Input: a preset, a key, a range and a grid size. The stability margin along the key is the
//! largest real part `σ_max` over every root. The grid (evaluated on all cores) brackets the first
//! point where `σ_max` turns positive; bisection then narrows the bracket to 1e-4 of the value,
//! and the crossing is placed by linear interpolation of `σ_max` inside the final bracket.
//! Bisection rather than Brent: `σ_max` is the upper envelope of several roots, so it has kinks
//! where the critical mode changes, and a guaranteed halving per step is worth the few extra
//! solves (≈ 10 for a 40-point grid). The kind (flutter or divergence), frequency and content
//! (the shares of its motion) come from the critical root just past the crossing. Its name is
//! the one its branch has at the start value: the root is followed back along the search path
//! (the solved grid points from the start, the bisection's stable ends, the crossing) with the
//! tracking a Campbell diagram uses ([`follow_decided`]). The name the identification
//! ([`crate::analysis::identify`]) gives the root at the crossing goes by its content alone, and
//! a root that aerodynamic coupling has reshaped (the IEA 15MW's flap 3 branch with bend–twist
//! coupling, 91 % flap at 3.09 Hz) takes whichever name is left there, flap 1 that time. Where
//! the tracking cannot decide, the result says so and names no mode.
//!
//! A search may start where the blade is already unstable only if it says so
//! ([`SearchRange::regain`], the explorer's margin): it then finds where stability returns, the
//! end of the unstable stretch the start lies in. `flutterscope flutter` asks for a stable start.
//!
//! A grid point that cannot be solved (a numerical failure, e.g. no static equilibrium) is
//! skipped, counted and named in the result's message: one unconvergent point says nothing
//! about the stability of its neighbours, and aborting would hide a boundary the rest of the
//! grid brackets. A refinement point inside the final bracket that cannot be solved ends the
//! search with an error naming the bracket and the value.

use crate::analysis::campbell::{schedule_wind_range, WIND_SPEED_KEY};
use crate::analysis::cancel::Cancel;
use crate::analysis::eigen::{analyse, Stability, NEUTRAL_TOLERANCE};
use crate::analysis::mode::Mode;
use crate::analysis::sweep::{failed_points, point_result, FailedPoint, PointResult};
use crate::analysis::tracking::{follow_decided, Point, REFINEMENT_DEPTH};
use crate::error::{Error, Result};
use crate::physics::structure::Shares;
use crate::precision;
use crate::preset::{key_spec, ValidPreset};
use rayon::prelude::*;
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryKind {
    /// The crossing mode oscillates (ω > 0).
    Flutter,
    /// The crossing root is real (ω = 0).
    Divergence,
    /// The crossing root is a free rotor's turning ([`Mode::rigid_body`]).
    Runaway,
}

impl BoundaryKind {
    /// The boundary's name in messages: `flutter`, `divergence`, `runaway`.
    pub fn word(self) -> &'static str {
        match self {
            BoundaryKind::Flutter => "flutter",
            BoundaryKind::Divergence => "divergence",
            BoundaryKind::Runaway => "runaway",
        }
    }
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
    /// Name of the crossing mode: the name its branch has at the start of the search, followed
    /// along the search path (the aerodynamic root's own name for an aero lag); none when the
    /// tracking cannot decide.
    pub mode: Option<String>,
    /// Kinetic-energy shares of flap, edge and twist in the crossing mode's motion (none for an
    /// aerodynamic root).
    pub shares: Option<Shares>,
}

/// A boundary with the result in plain words (also when there is no crossing: stable throughout,
/// or already unstable at the start of the range), the largest σ the grid met, and the grid
/// points that could not be solved.
#[derive(Debug, Clone, Serialize)]
pub struct Search {
    #[serde(flatten)]
    pub boundary: Boundary,
    pub message: String,
    /// The largest σ (1/s) over the solved grid points: the margin when stable throughout.
    pub max_re: f64,
    /// Grid points that could not be solved (numerical failures), skipped by the search.
    pub failed: Vec<FailedPoint>,
    /// The first solved point is already unstable. Without [`SearchRange::regain`] the search
    /// stops there, with no crossing (the message says so; a caller quoting a margin says it in
    /// its own words); with it, the crossing is where the blade is stable again.
    #[serde(skip)]
    pub unstable_at_start: bool,
    /// The bracketing grid and each point's result, for a figure of the search.
    #[serde(skip)]
    pub grid: Vec<f64>,
    #[serde(skip)]
    pub results: Vec<PointResult>,
}

/// Why a free rotor's turning can grow, and what holds it (docs/model.md §13.1).
pub const RUNAWAY: &str = "open loop, the generator holds its steady torque while the \
    aerodynamic torque rises with rotor speed (turbine.torque_slope gives the generator a \
    slope; a speed controller's region 2 has 2Q/Ω)";

/// Relative accuracy of the critical value (docs/model.md §6).
pub const RELATIVE_TOLERANCE: f64 = 1e-4;

/// Bisection steps at most: each halves the bracket, so reaching 1e-4 of a value from a grid
/// spacing takes about 24 of the 41-point grid's steps; the cap only guarantees the end (at
/// the cap the bracket is as narrow as doubles allow, and the crossing is placed in it).
pub const MAX_BISECTIONS: usize = 64;

/// Stability with `key` set to `value`.
pub fn stability_at(p: &ValidPreset, key: &str, value: f64) -> Result<Stability> {
    analyse(&p.with(key, value)?)
}

/// Where a boundary search looks: along `key` from `from` toward `to`, bracketing the crossing
/// on `points` grid points first.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchRange {
    pub key: String,
    pub from: f64,
    pub to: f64,
    pub points: usize,
    /// From an unstable start, look for where the blade is stable again instead of stopping.
    pub regain: bool,
}

/// Whether a stability result counts as unstable: its critical root has σ above the neutral
/// tolerance of its own spectral scale.
fn unstable(s: &Stability) -> bool {
    !s.stable
}

/// The first stability boundary along `key` from `from` toward `to`.
pub fn flutter_boundary(
    p: &ValidPreset,
    key: &str,
    from: f64,
    to: f64,
    points: usize,
) -> Result<Boundary> {
    Ok(flutter_search(p, key, from, to, points)?.boundary)
}

/// [`flutter_boundary`] with a plain-words account of the result.
pub fn flutter_search(
    p: &ValidPreset,
    key: &str,
    from: f64,
    to: f64,
    points: usize,
) -> Result<Search> {
    let range = SearchRange {
        key: key.to_string(),
        from,
        to,
        points,
        regain: false,
    };
    search(p, &range, &Cancel::never())
}

/// The boundary search over `range`, polling `cancel` before every solve.
pub fn search(p: &ValidPreset, range: &SearchRange, cancel: &Cancel) -> Result<Search> {
    let (key, from, to, points) = (range.key.as_str(), range.from, range.to, range.points);
    let spec = key_spec(key)?;
    p.acts(key)?;
    if spec.integer {
        return Err(Error::usage(format!(
            "flutter: {key} is an integer setting; vary a continuous key (e.g. operating.wind_speed)"
        )));
    }
    if points < 2 {
        return Err(Error::usage("flutter: --points must be at least 2"));
    }
    if !(from.is_finite() && to.is_finite()) || from == to {
        return Err(Error::usage(format!(
            "flutter: the range {from} … {to} is empty; give two different finite values"
        )));
    }
    for v in [from, to] {
        spec.check("flutter --from/--to", v)
            .map_err(|e| Error::usage(e.to_string()))?;
    }
    let grid = precision::grid(from, to, points);
    let results: Vec<PointResult> = grid
        .par_iter()
        .map(|&v| {
            cancel.check()?;
            point_result(stability_at(p, key, v))
        })
        .collect::<Result<_>>()?;
    let unit = if spec.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", spec.unit)
    };
    let failed = failed_points(&grid, &results);
    // The search runs over the solved points; a failed one is skipped, and said.
    let solved: Vec<(f64, &Stability)> = grid
        .iter()
        .zip(&results)
        .filter_map(|(&v, r)| r.as_ref().ok().map(|s| (v, s)))
        .collect();
    let skipped = match failed.first() {
        Some(f) => format!(
            "; {} of {points} grid points could not be solved and were skipped (the first at \
             {key} = {}{unit}: {})",
            failed.len(),
            f.value,
            f.error
        ),
        None => String::new(),
    };
    let Some(&(start, first_solved)) = solved.first() else {
        let f = &failed[0];
        return Err(Error::numerical(format!(
            "flutter: none of the {points} grid points of {key} in {from} … {to}{unit} could be \
             solved; at {key} = {}{unit}: {}",
            f.value, f.error
        )));
    };
    let max_re = solved
        .iter()
        .map(|(_, s)| s.max_re())
        .fold(f64::NEG_INFINITY, f64::max);
    let none = |message: String| Search {
        boundary: Boundary {
            parameter: key.to_string(),
            critical: None,
            frequency_hz: None,
            kind: None,
            mode: None,
            shares: None,
        },
        message: message + &skipped,
        max_re,
        failed: failed.clone(),
        unstable_at_start: false,
        grid: grid.clone(),
        results: results.clone(),
    };
    let start_unstable = unstable(first_solved);
    if start_unstable && !range.regain {
        let m = first_solved.critical().map(describe).unwrap_or_default();
        return Ok(Search {
            unstable_at_start: true,
            ..none(format!(
                "already unstable at the start of the range, {key} = {start}{unit} ({m}); \
                 start the search from a value where the blade is stable (--from is where it \
                 starts; the range may run downward)"
            ))
        });
    }
    // The first grid point whose stability differs from the start's: past a stable start the
    // first unstable one, past an unstable start (regain) the first stable one.
    let Some(first) = solved
        .iter()
        .position(|(_, s)| unstable(s) != start_unstable)
    else {
        if start_unstable {
            return Ok(Search {
                unstable_at_start: true,
                ..none(format!(
                    "unstable throughout {key} in {from} … {to}{unit} (largest σ = {max_re:.4} \
                     1/s)"
                ))
            });
        }
        return Ok(none(format!(
            "no stability boundary for {key} in {from} … {to}{unit}: stable throughout \
             (largest σ = {max_re:.4} 1/s)"
        )));
    };
    // `lo` keeps the start's stability and `hi` the other, whichever way the range runs.
    let (mut lo, mut hi) = (solved[first - 1].0, solved[first].0);
    let mut s_hi = solved[first].1.clone();
    // The stable points from the start to the bracket's stable end, in search order.
    let mut path: Vec<(f64, Stability)> = solved[..first]
        .iter()
        .map(|&(v, s)| (v, s.clone()))
        .collect();
    let scale = (to - from).abs();
    for _ in 0..MAX_BISECTIONS {
        if (hi - lo).abs() <= RELATIVE_TOLERANCE * lo.abs().max(hi.abs()).max(1e-3 * scale) {
            break;
        }
        let mid = precision::carried(0.5 * (lo + hi));
        if mid == lo || mid == hi {
            break;
        }
        cancel.check()?;
        let s = stability_at(p, key, mid).map_err(|e| {
            e.at(format!(
                "flutter: the boundary lies between {key} = {lo} and {hi}{unit}, but {key} = \
                 {mid}{unit} could not be solved"
            ))
        })?;
        if unstable(&s) != start_unstable {
            hi = mid;
            s_hi = s;
        } else {
            lo = mid;
            path.push((mid, s));
        }
    }
    // The path ends at the bracket's end that keeps the start's stability.
    let s_lo = path[path.len() - 1].1.clone();
    let ((x_s, s_s), (x_u, s_u)) = if start_unstable {
        ((hi, &s_hi), (lo, &s_lo))
    } else {
        ((lo, &s_lo), (hi, &s_hi))
    };
    let (g_s, g_u) = (s_s.max_re(), s_u.max_re());
    // Inside the final bracket σ_max is close to linear; place its zero there.
    let critical = if g_u > g_s && g_s <= 0.0 {
        x_s + (x_u - x_s) * (-g_s) / (g_u - g_s)
    } else {
        x_u
    };
    let crossing = s_u
        .critical()
        .cloned()
        .ok_or_else(|| Error::numerical(format!("flutter: no roots at {key} = {x_u}{unit}")))?;
    let kind = if crossing.im > 0.0 {
        BoundaryKind::Flutter
    } else if crossing.rigid_body() {
        BoundaryKind::Runaway
    } else {
        BoundaryKind::Divergence
    };
    let structural = s_u
        .eigenvalues
        .iter()
        .position(|m| m.re == crossing.re && m.im == crossing.im && m.label == crossing.label);
    let name = match structural {
        Some(index) => {
            // Past a stable start the unstable root lies one step beyond the path.
            if !start_unstable {
                path.push((hi, s_hi.clone()));
            }
            let named = branch_name(p, key, &path, index, cancel);
            cancel.check()?;
            named
        }
        None => Ok(crossing.label.clone()),
    };
    let root = match (&name, crossing.content()) {
        // The branch's name and the one its content gives at the crossing can differ where the
        // air has reshaped the root; say both, so that `eigen` there is not read as another mode.
        (Ok(name), Some(content)) if *name != crossing.label => format!(
            "{name} ({content}; tracked from {start}{unit}; {} by its content there)",
            crossing.label
        ),
        (Ok(name), Some(content)) => {
            format!("{name} ({content}; tracked from {start}{unit})")
        }
        (Ok(name), None) => name.clone(),
        (Err((a, b)), content) => format!(
            "a root ({}) whose mode the tracking cannot tell: following it back toward \
             {key} = {start}{unit}, its match stays ambiguous between {key} = {a} and {b}{unit}",
            content.unwrap_or_default()
        ),
    };
    let what = match kind {
        _ if start_unstable => format!(
            "stable again at {key} = {critical:.6}{unit}: the {} of {root} ends there",
            kind.word()
        ),
        BoundaryKind::Flutter => format!(
            "flutter at {key} = {critical:.6}{unit}: {root} at {:.4} Hz",
            crossing.frequency_hz
        ),
        BoundaryKind::Divergence => {
            format!("static divergence at {key} = {critical:.6}{unit}: {root}")
        }
        BoundaryKind::Runaway => {
            format!("rotor speed runaway at {key} = {critical:.6}{unit}: {root}; {RUNAWAY}")
        }
    };
    Ok(Search {
        boundary: Boundary {
            parameter: key.to_string(),
            critical: Some(critical),
            frequency_hz: Some(crossing.frequency_hz),
            kind: Some(kind),
            shares: crossing.family.map(|_| crossing.shares),
            mode: name.ok(),
        },
        message: what + &skipped,
        max_re,
        failed,
        unstable_at_start: start_unstable,
        grid,
        results,
    })
}

/// The name root `index` of the path's last point has at its first: the root followed back step
/// by step, re-solving midpoints where a match is ambiguous, as a Campbell diagram's tracks are
/// checked. Where the tracking cannot decide, the step (its two values) where it could not.
fn branch_name(
    p: &ValidPreset,
    key: &str,
    path: &[(f64, Stability)],
    index: usize,
    cancel: &Cancel,
) -> std::result::Result<String, (f64, f64)> {
    let solve = |v: f64| {
        cancel.check().ok()?;
        stability_at(p, key, v).ok().map(|s| s.eigenvalues)
    };
    let mut index = index;
    for w in path.windows(2).rev() {
        let (a, b) = (&w[1], &w[0]);
        let here = Point {
            value: a.0,
            modes: &a.1.eigenvalues,
        };
        let before = Point {
            value: b.0,
            modes: &b.1.eigenvalues,
        };
        index =
            follow_decided(&here, index, &before, REFINEMENT_DEPTH, &solve).ok_or((b.0, a.0))?;
    }
    Ok(path[0].1.eigenvalues[index].label.clone())
}

fn describe(m: &Mode) -> String {
    format!(
        "{}: σ = {:.4} 1/s at {:.4} Hz (neutral tolerance {NEUTRAL_TOLERANCE:e} of |λ|)",
        m.described(),
        m.re,
        m.frequency_hz
    )
}

/// The range a key is explored over, by the explorer's slider and by a search given no range:
/// the key table's, with wind, tunnel and rotor speed capped by the preset's `view` maxima (but
/// never below the current value), the wind along a schedule from cut-in to cut-out, and the
/// paper's blade's ply angle over Table 1's [0°, 90°] (a WindIO blade's fibres turn either way).
pub fn key_range(p: &ValidPreset, key: &str) -> (f64, f64) {
    let Ok(spec) = key_spec(key) else {
        return (f64::NEG_INFINITY, f64::INFINITY);
    };
    let (mut lo, mut hi) = (spec.min, spec.max);
    let cur = (spec.get)(p);
    if key == WIND_SPEED_KEY {
        if let Some((a, b)) = schedule_wind_range(p) {
            return (a.min(cur), b.max(cur));
        }
    }
    match key {
        "operating.rotor_speed" => hi = p.view.rotor_speed_max.max(cur),
        "operating.wind_speed" => hi = p.view.wind_speed_max.max(cur),
        "operating.tunnel_speed" => hi = p.view.tunnel_speed_max.max(cur),
        "section.ply_angle" if !p.blade.source.is_tabulated() => lo = 0.0,
        _ => {}
    }
    (lo, hi)
}
