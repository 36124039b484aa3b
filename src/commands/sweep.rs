//! `flutterscope sweep`: tracked modes over a grid of one or more keys (CSV or JSON), on all
//! cores, optionally one shard of the grid.

use crate::analysis::sweep::{grid_sweep, Grid, Shard, SweepRow};
use crate::error::{Error, Result};
use crate::preset::ValidPreset;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::Path;

pub fn run(
    p: &ValidPreset,
    vary: &[String],
    json: bool,
    shard: Option<&str>,
    plot: Option<&Path>,
) -> Result<()> {
    if let Some(path) = plot {
        crate::plot::format_for(path)?;
        if vary.len() != 1 {
            return Err(Error::usage(format!(
                "sweep --plot draws tracked modes along one key (a Campbell diagram along \
                 operating.rotor_speed); got {} --vary keys",
                vary.len()
            )));
        }
    }
    let grid = parse_grid(vary)?;
    // Rows kept for the plot (one key: the tracked modes along it).
    let mut plotted: Vec<SweepRow> = Vec::new();
    let keep = plot.is_some();
    let shard = shard.map(Shard::parse).transpose()?;
    let own = shard.map_or(grid.total(), |s| s.range(grid.total()).len());
    let bar = progress_bar(own as u64);
    let progress = |n: u64| bar.inc(n);
    let result = if json {
        let mut rows = Vec::new();
        grid_sweep(p, &grid, shard, &progress, &mut |batch| {
            rows.extend_from_slice(batch);
            if keep {
                plotted.extend_from_slice(batch);
            }
            Ok(())
        })
        .and_then(|failed| {
            super::print_json(&serde_json::json!({ "parameters": grid.keys, "rows": rows }))
                .map(|()| failed)
        })
    } else {
        let io = |e: std::io::Error| Error::Io(format!("cannot write CSV: {e}"));
        let mut out = std::io::BufWriter::new(std::io::stdout().lock());
        writeln!(out, "{}", csv_header(&grid.keys)).map_err(io)?;
        grid_sweep(p, &grid, shard, &progress, &mut |batch| {
            for r in batch {
                writeln!(out, "{}", csv_row(r)).map_err(io)?;
            }
            if keep {
                plotted.extend_from_slice(batch);
            }
            Ok(())
        })
        .and_then(|failed| out.flush().map_err(io).map(|()| failed))
    };
    bar.finish_and_clear();
    let failed = result?;
    if failed > 0 {
        eprintln!(
            "warning: {failed} grid point(s) could not be solved (e.g. no static equilibrium); \
             their rows have empty values"
        );
    }
    if let Some(path) = plot {
        let tracked = crate::plot::from_results::tracked_from_rows(&grid.keys[0], &plotted);
        let fig = crate::plot::from_results::sweep(p.display_name(), &tracked);
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}

/// The product grid of the `--vary KEY=A:B:STEP` arguments, in order (the last varies fastest
/// and is the tracking direction).
pub fn parse_grid(vary: &[String]) -> Result<Grid> {
    let mut keys = Vec::new();
    let mut axes = Vec::new();
    for spec in vary {
        let (key, axis) = super::parse_vary(spec)?;
        if keys.contains(&key) {
            return Err(Error::usage(format!("sweep: --vary {key} given twice")));
        }
        keys.push(key);
        axes.push(axis);
    }
    if keys.is_empty() {
        return Err(Error::usage("sweep: give at least one --vary KEY=A:B:STEP"));
    }
    let total = axes
        .iter()
        .try_fold(1usize, |acc, a| acc.checked_mul(a.len()));
    if total.is_none_or(|t| t > 100_000_000) {
        return Err(Error::usage("sweep: grid larger than 100 million points"));
    }
    Ok(Grid { keys, axes })
}

pub fn csv_header(keys: &[String]) -> String {
    let mut cols: Vec<&str> = keys.iter().map(String::as_str).collect();
    cols.extend(["mode", "frequency_hz", "damping_ratio", "re"]);
    cols.join(",")
}

/// One CSV line; a mode with no partner at this point leaves its numbers empty.
pub fn csv_row(r: &SweepRow) -> String {
    let num = |v: f64| {
        if v.is_finite() {
            format!("{v}")
        } else {
            String::new()
        }
    };
    let mut cols: Vec<String> = r.values.iter().map(|v| format!("{v}")).collect();
    cols.push(r.mode.clone());
    cols.extend([num(r.frequency_hz), num(r.damping_ratio), num(r.re)]);
    cols.join(",")
}

/// A bar on stderr when it is a terminal, nothing otherwise (logs and pipes stay clean).
fn progress_bar(total: u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} points, {per_sec}, eta {eta}")
    {
        bar.set_style(style);
    }
    bar
}
