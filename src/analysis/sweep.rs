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
use crate::analysis::eigen::{analyse, Stability};
use crate::analysis::grid::{Grid, Shard};
use crate::analysis::mode::Mode;
use crate::analysis::tracking::{follow, match_modes, Matching, Point, REFINEMENT_DEPTH};
use crate::error::{Error, Result};
use crate::preset::ValidPreset;
use rayon::prelude::*;
use serde::Serialize;
use std::sync::{Arc, Mutex};

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
    Ok(tracked_with_gaps(key, grid, points, &resolve))
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
    let mut s = tracked_with_gaps(key, grid, points.to_vec(), &|_| None);
    // Unrefined, a switch would be a guess; the names need none.
    for m in &mut s.modes {
        m.switches.clear();
    }
    s
}

/// A solved point as tracking keeps it: its value along the line and its structural modes.
struct Held {
    value: f64,
    modes: Vec<Mode>,
}

impl Held {
    fn point(&self) -> Point<'_> {
        Point {
            value: self.value,
            modes: &self.modes,
        }
    }
}

/// What tracking says of one point of a line.
struct TrackedPoint {
    /// The point's structural modes (none if it could not be solved).
    held: Option<Arc<Held>>,
    /// For each name known so far along the line ([`LineTracker::names`]), its root's index in
    /// the point's modes, if it has one there.
    index: Vec<Option<usize>>,
    /// Names (by index) that moved to another root branch over the step into this point, with
    /// where (the step's midpoint); complete once the doubts are settled ([`settle`]).
    switches: Vec<(usize, f64)>,
    /// Names whose match over the step into this point is in doubt, to be followed through
    /// re-solved midpoints.
    doubts: Vec<Doubt>,
}

/// A name whose root at a point may not continue its root at the last point holding it.
struct Doubt {
    name: usize,
    before: Arc<Held>,
    /// The name's root at `before` and at the point in doubt.
    from: usize,
    to: usize,
}

/// Mode tracking along one line, fed its points in order.
///
/// A track is a mode *name* ([`crate::analysis::identify`]): at every point it is the root that
/// carries that name there, so a sweep names each root exactly as `eigen` does at that point.
/// Between consecutive points holding a name, the name's root is checked against its branch
/// ([`follow`]: eigenvector correlation and eigenvalue continuity); where the name has moved to
/// another branch (a veering that swaps the modes' content) the step is a switch. Only the last
/// point holding each name is kept, so memory does not grow with the line's length; a name
/// first appearing partway along the line is tracked from there on.
#[derive(Default)]
struct LineTracker {
    /// Names in order of first appearance along the line.
    names: Vec<String>,
    /// Per name: the last point holding it and the name's root there.
    last: Vec<Option<(Arc<Held>, usize)>>,
}

impl LineTracker {
    /// Track the next point of the line: its value and its structural modes, or none where it
    /// could not be solved (no name is held there; the tracks cross it).
    fn push(&mut self, value: f64, modes: Option<Vec<Mode>>) -> TrackedPoint {
        let Some(modes) = modes else {
            return TrackedPoint {
                held: None,
                index: vec![None; self.names.len()],
                switches: Vec::new(),
                doubts: Vec::new(),
            };
        };
        let here = Arc::new(Held { value, modes });
        let mut index = vec![None; self.names.len()];
        for (j, m) in here.modes.iter().enumerate() {
            match self.names.iter().position(|n| *n == m.label) {
                Some(k) => index[k] = Some(j),
                None => {
                    self.names.push(m.label.clone());
                    self.last.push(None);
                    index.push(Some(j));
                }
            }
        }
        let (switches, doubts) = self.switches(&here, &index);
        for (k, j) in index.iter().enumerate() {
            if let Some(j) = *j {
                self.last[k] = Some((Arc::clone(&here), j));
            }
        }
        TrackedPoint {
            held: Some(here),
            index,
            switches,
            doubts,
        }
    }

    /// The names whose root at `here` is not the branch continuation of their root at the last
    /// point holding them, where the matching of the two points says so clearly, and the names
    /// whose match is in doubt ([`settle`] follows those). The matching of two points serves
    /// every name checked over that step.
    fn switches(&self, here: &Held, index: &[Option<usize>]) -> (Vec<(usize, f64)>, Vec<Doubt>) {
        let mut matchings: Vec<(*const Held, Matching)> = Vec::new();
        let mut doubts = Vec::new();
        let mut switches = Vec::new();
        for (k, j) in index.iter().enumerate() {
            let (Some(j), Some((before, i))) = (*j, &self.last[k]) else {
                continue;
            };
            // A rigid body's root (a free rotor's rotation, coupled with the air's lag or not)
            // is its one root at every point: no branch to follow.
            if here.modes[j].rigid_body() {
                continue;
            }
            let key = Arc::as_ptr(before);
            let m = match matchings.iter().position(|(p, _)| *p == key) {
                Some(at) => &matchings[at].1,
                None => {
                    matchings.push((key, match_modes(&before.modes, &here.modes)));
                    &matchings[matchings.len() - 1].1
                }
            };
            if m.ambiguous[*i] {
                doubts.push(Doubt {
                    name: k,
                    before: Arc::clone(before),
                    from: *i,
                    to: j,
                });
            } else if m.partner[*i] != Some(j) {
                switches.push((k, 0.5 * (before.value + here.value)));
            }
        }
        (switches, doubts)
    }
}

/// Follow every doubtful match of `points` through re-solved midpoints, all of them at once
/// on every core (the steps are independent), each midpoint solved once however many names
/// and steps need it (a real blade's re-solve rebuilds its operating point; a turbine's costs
/// tens of milliseconds), and add the switches found to their points.
fn settle(points: &mut [TrackedPoint], resolve: &Resolve) {
    type Solved = Arc<std::sync::OnceLock<Option<Vec<Mode>>>>;
    let solved: Mutex<std::collections::HashMap<u64, Solved>> = Mutex::default();
    let once = |value: f64| -> Option<Vec<Mode>> {
        let cell = match solved.lock() {
            Ok(mut s) => Arc::clone(s.entry(value.to_bits()).or_default()),
            Err(_) => return resolve(value),
        };
        cell.get_or_init(|| resolve(value)).clone()
    };
    let doubts: Vec<(usize, &Doubt, &Held)> = points
        .iter()
        .enumerate()
        .flat_map(|(p, t)| {
            t.held
                .iter()
                .flat_map(move |here| t.doubts.iter().map(move |d| (p, d, here.as_ref())))
        })
        .collect();
    let found: Vec<(usize, usize, f64)> = doubts
        .into_par_iter()
        .filter(|(_, d, here)| {
            follow(
                &d.before.point(),
                d.from,
                &here.point(),
                REFINEMENT_DEPTH,
                &once,
            ) != Some(d.to)
        })
        .map(|(p, d, here)| (p, d.name, 0.5 * (d.before.value + here.value)))
        .collect();
    for (p, name, at) in found {
        points[p].switches.push((name, at));
    }
    for t in points.iter_mut() {
        t.switches.sort_by_key(|&(k, _)| k);
        t.doubts.clear();
    }
}

/// Tracks through points some of which failed (no modes there; the tracks cross them), kept
/// whole: every name's values at every point, NaN where it has no root (before its first
/// appearance too), and where it switched branch ([`LineTracker`]).
fn tracked_with_gaps(
    key: &str,
    grid: &[f64],
    points: Vec<PointResult>,
    resolve: &Resolve,
) -> TrackedSweep {
    let failed = failed_points(grid, &points);
    let mut tracker = LineTracker::default();
    let mut tracked: Vec<TrackedPoint> = points
        .into_iter()
        .zip(grid)
        .map(|(r, &value)| tracker.push(value, r.ok().map(|s| s.eigenvalues)))
        .collect();
    settle(&mut tracked, resolve);
    let mut modes: Vec<TrackedMode> = Vec::new();
    for (k, t) in tracked.into_iter().enumerate() {
        for (n, i) in t.index.iter().enumerate() {
            if n == modes.len() {
                modes.push(TrackedMode {
                    label: tracker.names[n].clone(),
                    frequency_hz: vec![f64::NAN; k],
                    damping_ratio: vec![f64::NAN; k],
                    re: vec![f64::NAN; k],
                    second_re: vec![f64::NAN; k],
                    switches: Vec::new(),
                });
            }
            let root = i.zip(t.held.as_ref()).map(|(i, h)| &h.modes[i]);
            let value = |f: fn(&Mode) -> f64| root.map_or(f64::NAN, f);
            let m = &mut modes[n];
            m.frequency_hz.push(value(|m| m.frequency_hz));
            m.damping_ratio.push(value(|m| m.damping_ratio));
            m.re.push(value(|m| m.re));
            m.second_re.push(value(|m| m.second_re.unwrap_or(f64::NAN)));
        }
        for (n, at) in t.switches {
            modes[n].switches.push(at);
        }
    }
    TrackedSweep {
        parameter: key.to_string(),
        values: grid.to_vec(),
        modes,
        failed,
    }
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

impl SweepRow {
    /// The one row of a point that could not be solved, with why (if known).
    pub fn failed(values: Vec<f64>, error: Option<String>) -> SweepRow {
        SweepRow {
            values,
            mode: None,
            frequency_hz: f64::NAN,
            damping_ratio: f64::NAN,
            re: f64::NAN,
            second_re: f64::NAN,
            status: RowStatus::Failed,
            error,
        }
    }
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

/// Points solved per parallel chunk, per thread: enough to keep every core busy between the
/// chunks, few enough that the points waiting to be tracked and written stay a few megabytes.
const CHUNK_POINTS_PER_THREAD: usize = 32;

/// Chunks solved ahead of the one being tracked and written.
const CHUNKS_AHEAD: usize = 1;

/// Consecutive solved points of the grid, from flat index `first`.
type Chunk = (usize, Vec<PointResult>);

/// Solve the shard's slice of `grid`, handing rows to `sink` in grid order as the points are
/// solved, chunk by chunk: the points are solved on all cores a chunk ahead of their tracking,
/// and only the chunks in flight and, per mode, the last point holding it are kept, so memory
/// does not grow with the number of points. `progress` is called with the number of points just
/// solved (warm-up included). Every point of the grid is in the output: a solved point as one
/// row per mode named so far along its line, a point that could not be solved (a numerical
/// failure) as one `failed` row. Input errors fail before any point is solved ([`Grid::check`]).
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
    // A shard starting inside a line tracks it from its start, so its names are the whole run's.
    let first = own.start / line * line;
    let chunk = CHUNK_POINTS_PER_THREAD * rayon::current_num_threads().max(1);
    std::thread::scope(|scope| {
        let (solved, chunks) = std::sync::mpsc::sync_channel::<Result<Chunk>>(CHUNKS_AHEAD);
        let end = own.end;
        scope.spawn(move || {
            for at in (first..end).step_by(chunk) {
                let points: Result<Vec<PointResult>> = (at..(at + chunk).min(end))
                    .into_par_iter()
                    .map(|i| {
                        let s = point_result(solve_point(p, grid, i));
                        progress(1);
                        s
                    })
                    .collect();
                let stop = points.is_err();
                // A closed channel: the writer stopped (an output error); so does the solving.
                if solved.send(points.map(|s| (at, s))).is_err() || stop {
                    return;
                }
            }
        });
        let mut tracker = LineTracker::default();
        for received in chunks {
            let (at, points) = received?;
            let mut rows = Vec::new();
            // The chunk's points by line (a line's doubts re-solve along its own key values),
            // each point with its flat index and failure, and the names known at the line's
            // last point in the chunk (names are only added along a line: a point's are a
            // prefix of them).
            type Line = (Vec<(usize, TrackedPoint, Option<String>)>, Vec<String>);
            let mut lines: Vec<Line> = Vec::new();
            for (i, point) in (at..).zip(points) {
                if i % line == 0 {
                    if let Some(l) = lines.last_mut() {
                        l.1 = tracker.names.clone();
                    }
                    tracker = LineTracker::default();
                }
                if i % line == 0 || lines.is_empty() {
                    lines.push((Vec::new(), Vec::new()));
                }
                let values = grid.values(i);
                let (modes, failure) = match point {
                    Ok(s) => (Some(s.eigenvalues), None),
                    Err(e) => (None, Some(e.to_string())),
                };
                let tracked = tracker.push(values[values.len() - 1], modes);
                if let Some(l) = lines.last_mut() {
                    l.0.push((i, tracked, failure));
                }
            }
            if let Some(l) = lines.last_mut() {
                l.1 = tracker.names.clone();
            }
            for (points, names) in lines {
                let Some(&(first, ..)) = points.first() else {
                    continue;
                };
                let values = grid.values(first);
                let resolve = |v: f64| {
                    let keyed: Vec<(&str, f64)> = grid
                        .keys
                        .iter()
                        .map(String::as_str)
                        .zip(with_last(&values, v))
                        .collect();
                    p.with_all(&keyed)
                        .and_then(|q| analyse(&q))
                        .ok()
                        .map(|s| s.eigenvalues)
                };
                let (meta, mut tracked): (Vec<_>, Vec<TrackedPoint>) = points
                    .into_iter()
                    .map(|(i, t, failure)| ((i, failure), t))
                    .unzip();
                settle(&mut tracked, &resolve);
                for ((i, failure), t) in meta.into_iter().zip(tracked) {
                    if !own.contains(&i) {
                        continue;
                    }
                    let values = grid.values(i);
                    summary
                        .switches
                        .extend(t.switches.iter().map(|&(n, at)| NameSwitch {
                            values: with_last(&values, at),
                            mode: names[n].clone(),
                        }));
                    point_rows(&mut rows, values, &t, &names, failure);
                }
            }
            rows.iter().for_each(|r| summary.count(r));
            sink(&rows)?;
        }
        Ok(summary)
    })
}

/// `values` with its last (the tracked key's) replaced by `last`.
fn with_last(values: &[f64], last: f64) -> Vec<f64> {
    let mut out = values.to_vec();
    if let Some(l) = out.last_mut() {
        *l = last;
    }
    out
}

/// The rows of one grid point: one `failed` row where it could not be solved (`failure` says
/// why), else one row per name known along its line.
fn point_rows(
    rows: &mut Vec<SweepRow>,
    values: Vec<f64>,
    tracked: &TrackedPoint,
    names: &[String],
    failure: Option<String>,
) {
    let Some(held) = tracked.held.as_ref().filter(|_| failure.is_none()) else {
        rows.push(SweepRow::failed(values, failure));
        return;
    };
    for (name, i) in names.iter().zip(&tracked.index) {
        let root = i.map(|i| &held.modes[i]);
        let status = match root {
            None => RowStatus::NoRoot,
            Some(m) if m.second_re.is_some() => RowStatus::Overdamped,
            Some(_) => RowStatus::Ok,
        };
        let value = |f: fn(&Mode) -> f64| root.map_or(f64::NAN, f);
        rows.push(SweepRow {
            values: values.clone(),
            mode: Some(name.clone()),
            frequency_hz: value(|m| m.frequency_hz),
            damping_ratio: value(|m| m.damping_ratio),
            re: value(|m| m.re),
            second_re: value(|m| m.second_re.unwrap_or(f64::NAN)),
            status,
            error: None,
        });
    }
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
