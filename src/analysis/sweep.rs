//! Parameter sweeps with tracked modes (a Campbell diagram when the key is rotor speed;
//! docs/model.md §6.4).
//!
//! One-dimensional: [`track`] solves every grid point on all cores, then tracks the structural
//! modes of the first point through the grid by MAC (sequential, cheap).
//!
//! Multi-dimensional ([`grid_sweep`]): the grid is the product of the keys' axes, the last key
//! varying fastest. Modes are tracked along the last key, one *line* per combination of the other
//! keys. A shard `I/N` owns the contiguous slice `[⌊(I−1)T/N⌋, ⌊IT/N⌋)` of the T grid points;
//! a shard whose slice starts inside a line re-solves that line from its start (without printing
//! those points) so its tracked labels are exactly those of the whole run. Hence concatenating the
//! shards' rows in order reproduces the unsharded output exactly.

use crate::analysis::cancel::Cancel;
use crate::analysis::eigen::{analyse, Mode, Stability};
use crate::analysis::tracking::track_modes;
use crate::error::{Error, Result};
use crate::preset::ValidPreset;
use rayon::prelude::*;
use serde::Serialize;
use std::ops::Range;

/// One tracked mode along a one-dimensional sweep.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedMode {
    /// Label at the first grid point; kept through crossings by MAC tracking.
    pub label: String,
    pub frequency_hz: Vec<f64>,
    pub damping_ratio: Vec<f64>,
    pub re: Vec<f64>,
}

/// Tracked modes over a one-dimensional grid.
#[derive(Debug, Clone, Serialize)]
pub struct TrackedSweep {
    pub parameter: String,
    pub values: Vec<f64>,
    pub modes: Vec<TrackedMode>,
}

/// Tracked structural modes of `p` along `key` over `grid`. Values where a mode has no partner
/// (e.g. a pair that split into real roots) or where the point could not be solved (a numerical
/// failure such as no static equilibrium) are NaN (null in JSON); input errors still fail.
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
    let points: Vec<Option<Stability>> = grid
        .par_iter()
        .map(|&v| {
            cancel.check()?;
            solved_or_gap(p.with(key, v).and_then(|q| analyse(&q)))
        })
        .collect::<Result<_>>()?;
    Ok(tracked_with_gaps(key, grid, &points))
}

/// Track already-solved points (the explorer can solve incrementally and call this).
pub fn tracked_from(key: &str, grid: &[f64], points: &[Stability]) -> TrackedSweep {
    let points: Vec<Option<Stability>> = points.iter().cloned().map(Some).collect();
    tracked_with_gaps(key, grid, &points)
}

/// A point's result, with numerical failures turned into a gap (None).
fn solved_or_gap(r: Result<Stability>) -> Result<Option<Stability>> {
    match r {
        Ok(s) => Ok(Some(s)),
        Err(Error::Numerical(_)) => Ok(None),
        Err(e) => Err(e),
    }
}

/// Track through points some of which are gaps (no modes there; tracks resume after).
pub fn tracked_with_gaps(key: &str, grid: &[f64], points: &[Option<Stability>]) -> TrackedSweep {
    let lists: Vec<Vec<Mode>> = points
        .iter()
        .map(|s| s.as_ref().map_or_else(Vec::new, |s| s.eigenvalues.clone()))
        .collect();
    let tracks = track_modes(&lists);
    let modes = tracks
        .into_iter()
        .map(|t| {
            let pick = |f: fn(&Mode) -> f64| -> Vec<f64> {
                t.index
                    .iter()
                    .zip(&lists)
                    .map(|(i, modes)| i.map_or(f64::NAN, |i| f(&modes[i])))
                    .collect()
            };
            TrackedMode {
                label: t.label.clone(),
                frequency_hz: pick(|m| m.frequency_hz),
                damping_ratio: pick(|m| m.damping_ratio),
                re: pick(|m| m.re),
            }
        })
        .collect();
    TrackedSweep {
        parameter: key.to_string(),
        values: grid.to_vec(),
        modes,
    }
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
}

/// One output row: a tracked mode at one grid point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// Values of the grid keys, in key order.
    pub values: Vec<f64>,
    pub mode: String,
    pub frequency_hz: f64,
    pub damping_ratio: f64,
    pub re: f64,
}

/// Points solved per parallel batch: bounds memory on huge grids while keeping cores busy.
const BATCH_POINTS: usize = 4096;

/// Solve the shard's slice of `grid`, handing rows to `sink` batch by batch in grid order.
/// `progress` is called with the number of points just solved (warm-up included). Returns how
/// many of the shard's points could not be solved (numerical failure: their rows are NaN).
pub fn grid_sweep(
    p: &ValidPreset,
    grid: &Grid,
    shard: Option<Shard>,
    progress: &(dyn Fn(u64) + Sync),
    sink: &mut dyn FnMut(&[SweepRow]) -> Result<()>,
) -> Result<usize> {
    if grid.keys.is_empty()
        || grid.keys.len() != grid.axes.len()
        || grid.axes.iter().any(Vec::is_empty)
    {
        return Err(Error::usage(
            "sweep: every --vary needs at least one grid point",
        ));
    }
    let total = grid.total();
    let own = shard.map_or(0..total, |s| s.range(total));
    if own.is_empty() {
        return Ok(0);
    }
    let mut failed = 0;
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
        let solved: Vec<Option<Stability>> = flat
            .par_iter()
            .map(|&i| {
                let s = solved_or_gap(solve_point(p, grid, i));
                progress(1);
                s
            })
            .collect::<Result<_>>()?;
        failed += flat
            .iter()
            .zip(&solved)
            .filter(|(i, s)| own.contains(i) && s.is_none())
            .count();
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
            let tracked = tracked_with_gaps(&grid.keys[grid.keys.len() - 1], &axis, pts);
            for (k, i) in r.clone().enumerate() {
                if !own.contains(&i) {
                    continue;
                }
                let values = grid.values(i);
                for m in &tracked.modes {
                    rows.push(SweepRow {
                        values: values.clone(),
                        mode: m.label.clone(),
                        frequency_hz: m.frequency_hz[k],
                        damping_ratio: m.damping_ratio[k],
                        re: m.re[k],
                    });
                }
            }
        }
        sink(&rows)?;
    }
    Ok(failed)
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
