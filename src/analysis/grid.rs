//! The grids of a parameter sweep: a product [`Grid`] of the keys' axes (the last key varying
//! fastest) with its input checks and size limit ([`MAX_GRID_POINTS`]), and the [`Shard`]s a
//! sweep is split into for a cluster, each a contiguous slice of the grid's points.

use crate::error::{Error, Result};
use crate::preset::{key_spec, ValidPreset};
use std::ops::Range;

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

/// Most points a grid sweep takes (the product of its axes). Not for memory, which does not
/// grow with the points ([`crate::analysis::sweep::grid_sweep`]), but time: a mistyped STEP asking for more would run
/// for days (10⁸ points of the paper's blade take about three hours on one core).
pub const MAX_GRID_POINTS: usize = 100_000_000;

/// `count` points said against `limit`: how many, and how many times the limit that is.
pub fn beyond_limit(count: f64, limit: usize) -> String {
    let times = count / limit as f64;
    let times = if times < 1e4 {
        format!("{times:.1}")
    } else {
        format!("{times:.1e}")
    };
    format!("{count:.4e} points, {times} times the limit of {limit}")
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
            let size = self.axes.iter().map(|a| a.len() as f64).product::<f64>();
            return Err(Error::usage(format!(
                "sweep: the grid is too large: {} = {} (100 million)",
                sizes.join(" × "),
                beyond_limit(size, MAX_GRID_POINTS)
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
        assert!(
            e.contains("100000 × 100000 = 1.0000e10 points, 100.0 times the limit of 100000000 (100 million)"),
            "{e}"
        );
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
