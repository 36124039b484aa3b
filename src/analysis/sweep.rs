//! Parameter sweeps with tracked modes (a Campbell diagram when the key is rotor speed;
//! docs/model.md §6.4).
//!
//! One-dimensional: [`track`] solves every grid point on all cores, then tracks the structural
//! modes through the grid by MAC (sequential, cheap), from the first solved point, starting a
//! track wherever a root appears. A point that cannot be solved costs that point only.
//!
//! Multi-dimensional ([`grid_sweep`]): the grid is the product of the keys' axes, the last key
//! varying fastest. Modes are tracked along the last key, one *line* per combination of the other
//! keys. A shard `I/N` owns the contiguous slice `[⌊(I−1)T/N⌋, ⌊IT/N⌋)` of the T grid points;
//! a shard whose slice starts inside a line re-solves that line from its start (without printing
//! those points) so its tracked labels are exactly those of the whole run. Hence concatenating the
//! shards' rows in order reproduces the unsharded output exactly.

use crate::analysis::cancel::Cancel;
use crate::analysis::eigen::{analyse, Mode, Stability};
use crate::analysis::tracking::{follow, Point, REFINEMENT_DEPTH};
use crate::error::{Error, Result};
use crate::preset::{key_spec, ValidPreset};
use rayon::prelude::*;
use serde::Serialize;
use std::ops::Range;

/// One tracked mode along a one-dimensional sweep.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedMode {
    /// The mode's name: at every point, the root that `eigen` gives this name.
    pub label: String,
    /// NaN where the mode has no root: the point failed ([`TrackedSweep::failed`]), or the mode
    /// has not appeared yet or has merged with another there.
    pub frequency_hz: Vec<f64>,
    pub damping_ratio: Vec<f64>,
    /// σ where the mode is one root (or the less stable root of an overdamped pair).
    pub re: Vec<f64>,
    /// σ of the more stable root where the mode is overdamped (two real roots), NaN elsewhere.
    pub second_re: Vec<f64>,
    /// Parameter values (midpoints of grid steps) where the name moves to another root branch:
    /// a veering swapped the content of two modes, confirmed by re-solving within the step.
    pub switches: Vec<f64>,
}

/// A grid point that could not be solved (a numerical failure such as no static equilibrium).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FailedPoint {
    /// Its position in the grid.
    pub index: usize,
    /// The varied key's value there.
    pub value: f64,
    /// Why (the numerical error).
    pub error: String,
}

/// Tracked modes over a one-dimensional grid.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedSweep {
    pub parameter: String,
    pub values: Vec<f64>,
    pub modes: Vec<TrackedMode>,
    /// The points that could not be solved, in grid order: every mode is NaN there.
    pub failed: Vec<FailedPoint>,
}

impl TrackedSweep {
    /// Why point `k` could not be solved, if it could not.
    pub fn failure_at(&self, k: usize) -> Option<&FailedPoint> {
        self.failed.iter().find(|f| f.index == k)
    }
}

/// One grid point's result: its analysis, or the numerical error that stopped it.
pub type PointResult = std::result::Result<Stability, Error>;

/// Tracked structural modes of `p` along `key` over `grid`. A point that cannot be solved (a
/// numerical failure) costs that point only: it is listed in [`TrackedSweep::failed`] and the
/// tracks cross it; input errors still fail the whole sweep.
pub fn track(p: &ValidPreset, key: &str, grid: &[f64]) -> Result<TrackedSweep> {
    track_cancellable(p, key, grid, &Cancel::never())
}

/// [`track`], polling `cancel` before every point.
pub fn track_cancellable(
    p: &ValidPreset,
    key: &str,
    grid: &[f64],
    cancel: &Cancel,
) -> Result<TrackedSweep> {
    let points: Vec<PointResult> = grid
        .par_iter()
        .map(|&v| {
            cancel.check()?;
            point_result(p.with(key, v).and_then(|q| analyse(&q)))
        })
        .collect::<Result<_>>()?;
    let resolve = |v: f64| {
        p.with(key, v)
            .and_then(|q| analyse(&q))
            .ok()
            .map(|s| s.eigenvalues)
    };
    Ok(tracked_with_gaps(key, grid, &points, &resolve))
}

/// A point's result, keeping a numerical failure as that point's result; any other error (bad
/// input, cancellation) ends the whole computation.
pub fn point_result(r: Result<Stability>) -> Result<PointResult> {
    match r {
        Ok(s) => Ok(Ok(s)),
        Err(e @ Error::Numerical(_)) => Ok(Err(e)),
        Err(e) => Err(e),
    }
}

/// A re-solve of one value of the tracked key (for refinement between grid points): the point's
/// structural modes, or none if it cannot be solved.
pub type Resolve<'a> = dyn Fn(f64) -> Option<Vec<Mode>> + Sync + 'a;

/// The modes of solved `points` by name, as [`tracked_with_gaps`] gives them but without the
/// branch checks (no switches, nothing re-solved): for a figure, which draws the names.
pub fn named_modes(key: &str, grid: &[f64], points: &[PointResult]) -> TrackedSweep {
    let mut s = tracked_with_gaps(key, grid, points, &|_| None);
    // Unrefined, a switch would be a guess; the names need none.
    for m in &mut s.modes {
        m.switches.clear();
    }
    s
}

/// Tracks through points some of which failed (no modes there; the tracks cross them).
///
/// A track is a mode *name* ([`crate::analysis::identify`]): at every point it is the root that
/// carries that name there, so a sweep names each root exactly as `eigen` does at that point.
/// Between consecutive points each track is checked against its branch ([`follow`]: eigenvector
/// correlation and eigenvalue continuity, re-solving midpoints through `resolve` where the match
/// is ambiguous); where the name has moved to another branch (a veering that swaps the modes'
/// content) the track records where, in [`TrackedMode::switches`].
pub fn tracked_with_gaps(
    key: &str,
    grid: &[f64],
    points: &[PointResult],
    resolve: &Resolve,
) -> TrackedSweep {
    let lists: Vec<&[Mode]> = points
        .iter()
        .map(|s| s.as_ref().map_or(&[][..], |s| s.eigenvalues.as_slice()))
        .collect();
    // Every name checks its branch over the same steps, so a midpoint one name re-solves the
    // next needs too: solve each once (a real blade's re-solve rebuilds its operating point).
    let solved: std::sync::Mutex<std::collections::HashMap<u64, Option<Vec<Mode>>>> =
        Default::default();
    let once = |value: f64| -> Option<Vec<Mode>> {
        let known = solved.lock().ok()?.get(&value.to_bits()).cloned();
        known.unwrap_or_else(|| {
            let modes = resolve(value);
            if let Ok(mut cache) = solved.lock() {
                cache.insert(value.to_bits(), modes.clone());
            }
            modes
        })
    };
    let resolve: &Resolve = &once;
    let mut names: Vec<&str> = Vec::new();
    for m in lists.iter().flat_map(|l| l.iter()) {
        if !names.contains(&m.label.as_str()) {
            names.push(&m.label);
        }
    }
    // Names in parallel: their branch checks re-solve midpoints independently.
    let modes = names
        .into_par_iter()
        .map(|name| {
            let index: Vec<Option<usize>> = lists
                .iter()
                .map(|l| l.iter().position(|m| m.label == name))
                .collect();
            let pick = |f: fn(&Mode) -> f64| -> Vec<f64> {
                index
                    .iter()
                    .zip(&lists)
                    .map(|(i, modes)| i.map_or(f64::NAN, |i| f(&modes[i])))
                    .collect()
            };
            TrackedMode {
                label: name.to_string(),
                frequency_hz: pick(|m| m.frequency_hz),
                damping_ratio: pick(|m| m.damping_ratio),
                re: pick(|m| m.re),
                second_re: pick(|m| m.second_re.unwrap_or(f64::NAN)),
                switches: branch_switches(grid, &lists, &index, resolve),
            }
        })
        .collect();
    TrackedSweep {
        parameter: key.to_string(),
        values: grid.to_vec(),
        modes,
        failed: failed_points(grid, points),
    }
}

/// Where a named track leaves its branch: between consecutive points holding the name, the
/// midpoint of each step over which the name's root is not the branch continuation of its root
/// before.
fn branch_switches(
    grid: &[f64],
    lists: &[&[Mode]],
    index: &[Option<usize>],
    resolve: &Resolve,
) -> Vec<f64> {
    let held: Vec<(usize, usize)> = index
        .iter()
        .enumerate()
        .filter_map(|(k, i)| i.map(|i| (k, i)))
        .collect();
    held.windows(2)
        .filter(|w| {
            let ((k, i), (l, j)) = (w[0], w[1]);
            let a = Point {
                value: grid[k],
                modes: lists[k],
            };
            let b = Point {
                value: grid[l],
                modes: lists[l],
            };
            follow(&a, i, &b, REFINEMENT_DEPTH, resolve) != Some(j)
        })
        .map(|w| 0.5 * (grid[w[0].0] + grid[w[1].0]))
        .collect()
}

/// The points of `grid` whose result is an error, with the error.
pub fn failed_points(grid: &[f64], points: &[PointResult]) -> Vec<FailedPoint> {
    points
        .iter()
        .zip(grid)
        .enumerate()
        .filter_map(|(index, (r, &value))| {
            r.as_ref().err().map(|e| FailedPoint {
                index,
                value,
                error: e.to_string(),
            })
        })
        .collect()
}

/// Slice `index` (1-based) of `count` of a grid sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Parse `I/N` with 1 ≤ I ≤ N.
    pub fn parse(text: &str) -> Result<Shard> {
        let bad = || {
            Error::usage(format!(
                "--shard '{text}': expected I/N with 1 ≤ I ≤ N, e.g. --shard 2/8"
            ))
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The grid indices this shard owns out of `total`.
    pub fn range(&self, total: usize) -> Range<usize> {
        let edge = |k: usize| ((k as u128 * total as u128) / self.count as u128) as usize;
        edge(self.index - 1)..edge(self.index)
    }
}

/// Most points a grid sweep takes (the product of its axes).
pub const MAX_GRID_POINTS: usize = 100_000_000;

/// A product grid: `keys[k]` takes the values `axes[k]`; the last key varies fastest.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub keys: Vec<String>,
    pub axes: Vec<Vec<f64>>,
}

impl Grid {
    pub fn total(&self) -> usize {
        self.axes.iter().map(Vec::len).product()
    }
    /// Points per tracking line (the last axis).
    pub fn line_length(&self) -> usize {
        self.axes.last().map_or(1, Vec::len)
    }
    /// The key values at flat index `i`.
    pub fn values(&self, mut i: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.axes.len()];
        for (k, axis) in self.axes.iter().enumerate().rev() {
            out[k] = axis[i % axis.len()];
            i /= axis.len();
        }
        out
    }

    /// The grid's input errors, found before any point is solved (so a command prints nothing
    /// before them): its size, every value of every axis against its key's range, and the rules
    /// across keys at every corner of the grid (each key at the first or the last value of its
    /// axis). Each rule is monotone or convex in every key separately, so its worst case over
    /// the grid lies at a corner; there are never more corners than grid points.
    pub fn check(&self, p: &ValidPreset) -> Result<()> {
        if self.keys.is_empty()
            || self.keys.len() != self.axes.len()
            || self.axes.iter().any(Vec::is_empty)
        {
            return Err(Error::usage(
                "sweep: every --vary needs at least one grid point",
            ));
        }
        let total = self
            .axes
            .iter()
            .try_fold(1usize, |acc, a| acc.checked_mul(a.len()));
        if total.is_none_or(|t| t > MAX_GRID_POINTS) {
            let sizes: Vec<String> = self.axes.iter().map(|a| a.len().to_string()).collect();
            return Err(Error::usage(format!(
                "sweep: the grid is too large: {} points; the limit is {MAX_GRID_POINTS} \
                 (100 million)",
                sizes.join(" × ")
            )));
        }
        for (key, axis) in self.keys.iter().zip(&self.axes) {
            let spec = key_spec(key)?;
            for &v in axis {
                spec.check(&p.origin, v)?;
            }
        }
        let spread: Vec<usize> = (0..self.axes.len())
            .filter(|&k| self.axes[k].len() > 1)
            .collect();
        for corner in 0..1usize << spread.len() {
            let values: Vec<(&str, f64)> = self
                .keys
                .iter()
                .zip(&self.axes)
                .enumerate()
                .map(|(k, (key, axis))| {
                    let last = spread
                        .iter()
                        .position(|&s| s == k)
                        .is_some_and(|bit| corner >> bit & 1 == 1);
                    (
                        key.as_str(),
                        if last { axis[axis.len() - 1] } else { axis[0] },
                    )
                })
                .collect();
            p.with_all(&values).map_err(|e| match e {
                Error::Invalid { origin, message } => Error::Invalid {
                    origin,
                    message: format!(
                        "at the sweep's grid point {}: {message}",
                        values
                            .iter()
                            .map(|(k, v)| format!("{k} = {v}"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                },
                e => e,
            })?;
        }
        Ok(())
    }
}

/// What a sweep row holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RowStatus {
    /// The mode's frequency, damping ratio and σ at this point.
    Ok,
    /// The point was solved but no root carries this mode's name there (it is named elsewhere
    /// along the line).
    NoRoot,
    /// The mode is overdamped here: two real roots; `re` is the less stable one's σ.
    Overdamped,
    /// The point could not be solved ([`SweepRow::error`] says why): one row, no mode.
    Failed,
}

impl RowStatus {
    /// The word in CSV and JSON.
    pub fn name(self) -> &'static str {
        match self {
            RowStatus::Ok => "ok",
            RowStatus::NoRoot => "no-root",
            RowStatus::Overdamped => "overdamped",
            RowStatus::Failed => "failed",
        }
    }
}

/// One output row: a tracked mode at one grid point, or a point that failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// Values of the grid keys, in key order.
    pub values: Vec<f64>,
    /// The tracked mode; `None` on a failed point's row.
    pub mode: Option<String>,
    /// NaN (null in JSON, empty in CSV) unless the status is ok.
    pub frequency_hz: f64,
    pub damping_ratio: f64,
    pub re: f64,
    /// σ of the more stable root of an overdamped pair (status overdamped only; NaN, empty in
    /// CSV and null in JSON, otherwise).
    pub second_re: f64,
    pub status: RowStatus,
    /// Why the point could not be solved (failed rows only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// What a grid sweep could not compute, counted over the shard's own points, with the first
/// row of each kind, for the command's warning.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepSummary {
    /// The shard's grid points.
    pub points: usize,
    /// Points that could not be solved (status failed).
    pub failed: usize,
    pub first_failed: Option<SweepRow>,
    /// Rows of solved points where a mode has no root (status no-root).
    pub no_root: usize,
    pub first_no_root: Option<SweepRow>,
    /// Where a tracked name moved to another root branch within a step (a veering,
    /// [`TrackedMode::switches`]), in grid order.
    pub switches: Vec<NameSwitch>,
}

/// A mode's name moving to another root branch between two grid points of a line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NameSwitch {
    /// Values of the grid keys there, in key order (the last is where, within the step).
    pub values: Vec<f64>,
    pub mode: String,
}

impl SweepSummary {
    fn count(&mut self, r: &SweepRow) {
        let (n, first) = match r.status {
            RowStatus::Ok | RowStatus::Overdamped => return,
            RowStatus::Failed => (&mut self.failed, &mut self.first_failed),
            RowStatus::NoRoot => (&mut self.no_root, &mut self.first_no_root),
        };
        *n += 1;
        first.get_or_insert_with(|| r.clone());
    }
}

/// Points solved per parallel batch: bounds memory on huge grids while keeping cores busy.
const BATCH_POINTS: usize = 4096;

/// Solve the shard's slice of `grid`, handing rows to `sink` batch by batch in grid order.
/// `progress` is called with the number of points just solved (warm-up included). Every point
/// of the grid is in the output: a solved point as one row per tracked mode of its line, a point
/// that could not be solved (a numerical failure) as one `failed` row. Input errors fail before
/// any point is solved ([`Grid::check`]).
pub fn grid_sweep(
    p: &ValidPreset,
    grid: &Grid,
    shard: Option<Shard>,
    progress: &(dyn Fn(u64) + Sync),
    sink: &mut dyn FnMut(&[SweepRow]) -> Result<()>,
) -> Result<SweepSummary> {
    grid.check(p)?;
    let total = grid.total();
    let own = shard.map_or(0..total, |s| s.range(total));
    let mut summary = SweepSummary {
        points: own.len(),
        ..SweepSummary::default()
    };
    if own.is_empty() {
        return Ok(summary);
    }
    let line = grid.line_length();
    let first_line = own.start / line;
    let last_line = (own.end - 1) / line;
    let mut next_line = first_line;
    while next_line <= last_line {
        // A batch of whole lines, clipped to the shard's end.
        let mut lines = Vec::new();
        let mut points = 0;
        while next_line <= last_line && (lines.is_empty() || points + line <= BATCH_POINTS) {
            let start = next_line * line;
            let end = ((next_line + 1) * line).min(own.end);
            points += end - start;
            lines.push(start..end);
            next_line += 1;
        }
        let flat: Vec<usize> = lines.iter().flat_map(|r| r.clone()).collect();
        let solved: Vec<PointResult> = flat
            .par_iter()
            .map(|&i| {
                let s = point_result(solve_point(p, grid, i));
                progress(1);
                s
            })
            .collect::<Result<_>>()?;
        let mut rows = Vec::new();
        let mut offset = 0;
        for r in &lines {
            let n = r.len();
            let pts = &solved[offset..offset + n];
            offset += n;
            let axis: Vec<f64> = r
                .clone()
                .map(|i| grid.values(i)[grid.keys.len() - 1])
                .collect();
            let line_start = grid.values(r.start);
            let resolve = |v: f64| {
                let mut values = line_start.clone();
                if let Some(last) = values.last_mut() {
                    *last = v;
                }
                let keyed: Vec<(&str, f64)> =
                    grid.keys.iter().map(String::as_str).zip(values).collect();
                p.with_all(&keyed)
                    .and_then(|q| analyse(&q))
                    .ok()
                    .map(|s| s.eigenvalues)
            };
            let tracked = tracked_with_gaps(&grid.keys[grid.keys.len() - 1], &axis, pts, &resolve);
            for m in &tracked.modes {
                summary.switches.extend(m.switches.iter().map(|&at| {
                    let mut values = line_start.clone();
                    if let Some(last) = values.last_mut() {
                        *last = at;
                    }
                    NameSwitch {
                        values,
                        mode: m.label.clone(),
                    }
                }));
            }
            for (k, i) in r.clone().enumerate() {
                if !own.contains(&i) {
                    continue;
                }
                let values = grid.values(i);
                if let Some(f) = tracked.failure_at(k) {
                    rows.push(SweepRow {
                        values,
                        mode: None,
                        frequency_hz: f64::NAN,
                        damping_ratio: f64::NAN,
                        re: f64::NAN,
                        second_re: f64::NAN,
                        status: RowStatus::Failed,
                        error: Some(f.error.clone()),
                    });
                    continue;
                }
                for m in &tracked.modes {
                    let status = if m.re[k].is_nan() {
                        RowStatus::NoRoot
                    } else if !m.second_re[k].is_nan() {
                        RowStatus::Overdamped
                    } else {
                        RowStatus::Ok
                    };
                    rows.push(SweepRow {
                        values: values.clone(),
                        mode: Some(m.label.clone()),
                        frequency_hz: m.frequency_hz[k],
                        damping_ratio: m.damping_ratio[k],
                        re: m.re[k],
                        second_re: m.second_re[k],
                        status,
                        error: None,
                    });
                }
            }
        }
        rows.iter().for_each(|r| summary.count(r));
        sink(&rows)?;
    }
    Ok(summary)
}

fn solve_point(p: &ValidPreset, grid: &Grid, i: usize) -> Result<Stability> {
    let values: Vec<(&str, f64)> = grid
        .keys
        .iter()
        .map(String::as_str)
        .zip(grid.values(i))
        .collect();
    analyse(&p.with_all(&values)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_grid() {
        for total in [0usize, 1, 7, 10, 101] {
            for count in 1..=5 {
                let mut covered = Vec::new();
                for index in 1..=count {
                    covered.extend(Shard { index, count }.range(total));
                }
                assert_eq!(covered, (0..total).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn shard_parsing() {
        assert_eq!(Shard::parse("2/8").unwrap(), Shard { index: 2, count: 8 });
        for bad in ["0/3", "4/3", "1/0", "x/2", "3"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn grid_check_finds_range_rule_and_size_errors_up_front() {
        let p = crate::preset::Preset::load("liu2017", &[]).unwrap();
        let grid = |keys: &[&str], axes: Vec<Vec<f64>>| Grid {
            keys: keys.iter().map(|k| k.to_string()).collect(),
            axes,
        };
        let ok = grid(
            &["aero.onera.alpha1", "operating.rotor_speed"],
            vec![vec![0.0, 10.0], vec![0.0, 100.0]],
        );
        assert!(ok.check(&p).is_ok());
        // alpha2 = 18 must exceed alpha1: fine at 0 and 10, broken at the corner alpha1 = 20.
        let e = grid(&["aero.onera.alpha1"], vec![vec![0.0, 10.0, 20.0]])
            .check(&p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("grid point aero.onera.alpha1 = 20"), "{e}");
        let e = grid(&["operating.rotor_speed"], vec![vec![0.0, 6000.0]])
            .check(&p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("6000 is out of range"), "{e}");
        let big = vec![vec![0.0; 100_000]; 2];
        let e = grid(&["operating.pitch", "operating.wind_speed"], big)
            .check(&p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("100000 × 100000 points"), "{e}");
    }

    #[test]
    fn grid_values_last_key_fastest() {
        let g = Grid {
            keys: vec!["a".into(), "b".into()],
            axes: vec![vec![1.0, 2.0], vec![10.0, 20.0, 30.0]],
        };
        assert_eq!(g.total(), 6);
        assert_eq!(g.values(0), vec![1.0, 10.0]);
        assert_eq!(g.values(4), vec![2.0, 20.0]);
    }
}
