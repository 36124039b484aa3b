//! `flutterscope sweep`: tracked modes over a grid of one or more keys (CSV or JSON), on all
//! cores, optionally one shard of the grid.

use crate::analysis::sweep::{grid_sweep, Grid, SweepRow, SweepSummary};
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
    // Every input error before the first line of output.
    grid.check(p)?;
    // Rows kept for the plot (one key: the tracked modes along it).
    let mut plotted: Vec<SweepRow> = Vec::new();
    let keep = plot.is_some();
    let shard = shard.map(super::slurm::shard).transpose()?;
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
        .and_then(|summary| {
            super::print_json(&serde_json::json!({
                "parameters": grid.keys,
                "points": summary.points,
                "failed_points": summary.failed,
                "no_root_rows": summary.no_root,
                "switches": summary.switches,
                "rows": rows,
            }))
            .map(|()| summary)
        })
    } else {
        let io = super::stdout_error;
        let mut out = std::io::BufWriter::new(super::stdout()?);
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
        .and_then(|summary| out.flush().map_err(io).map(|()| summary))
    };
    bar.finish_and_clear();
    let summary = result?;
    for line in warnings(&grid.keys, &summary) {
        eprintln!("{line}");
    }
    if let Some(path) = plot {
        let tracked = crate::plot::from_results::tracked_from_rows(&grid.keys[0], &plotted);
        let fig = match crate::analysis::campbell::along_schedule_rotor_speeds(
            p,
            &tracked.parameter,
            &tracked.values,
        )? {
            Some(rpm) => {
                crate::plot::from_results::campbell_along_schedule(p.display_name(), &tracked, &rpm)
            }
            None => crate::plot::from_results::sweep(p.display_name(), &tracked),
        };
        crate::plot::write(&fig, path)?;
        eprintln!("plot written to {}", path.display());
    }
    Ok(())
}

/// What the rows without values mean, counted: failed points (a warning, with the first one's
/// values and error) and modes without a root at a solved point (a note: physics, not failure).
pub fn warnings(keys: &[String], s: &SweepSummary) -> Vec<String> {
    let at_values = |values: &[f64]| {
        keys.iter()
            .zip(values)
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let at = |r: &SweepRow| at_values(&r.values);
    let mut out = Vec::new();
    if let Some(r) = &s.first_failed {
        out.push(format!(
            "warning: {} of {} grid point(s) could not be solved (rows with status `failed`, no \
             values); the first, at {}: {}",
            s.failed,
            s.points,
            at(r),
            r.error.as_deref().unwrap_or("unknown error")
        ));
    }
    if let Some(r) = &s.first_no_root {
        out.push(format!(
            "note: {} row(s) have no values because no root carries that mode's name at that \
             point (status `no-root`: the structure has more modes than structural roots there); \
             the first: {} at {}",
            s.no_root,
            r.mode.as_deref().unwrap_or(""),
            at(r)
        ));
    }
    if !s.switches.is_empty() {
        const SHOWN: usize = 5;
        let listed: Vec<String> = s
            .switches
            .iter()
            .take(SHOWN)
            .map(|w| format!("{} at {}", w.mode, at_values(&w.values)))
            .collect();
        let more = s.switches.len().saturating_sub(SHOWN);
        out.push(format!(
            "note: {} time(s) a mode's name moved to another root branch within a step (a \
             veering: the name follows the motion's content, and the rows follow the name): {}{}",
            s.switches.len(),
            listed.join("; "),
            if more > 0 {
                format!("; {more} more in --json")
            } else {
                String::new()
            }
        ));
    }
    out
}

/// The product grid of the `--vary KEY=A:B:STEP` arguments, in order (the last varies fastest
/// and is the tracking direction); [`Grid::check`] checks it against a preset.
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
    Ok(Grid { keys, axes })
}

pub fn csv_header(keys: &[String]) -> String {
    let mut cols: Vec<&str> = keys.iter().map(String::as_str).collect();
    cols.extend([
        "mode",
        "frequency_hz",
        "damping_ratio",
        "re",
        "second_re",
        "status",
    ]);
    cols.join(",")
}

/// One CSV line; a row whose status is not `ok` leaves its numbers empty (a failed point its
/// mode too).
pub fn csv_row(r: &SweepRow) -> String {
    let num = |v: f64| {
        if v.is_finite() {
            format!("{v}")
        } else {
            String::new()
        }
    };
    let mut cols: Vec<String> = r.values.iter().map(|v| format!("{v}")).collect();
    cols.push(r.mode.clone().unwrap_or_default());
    cols.extend([
        num(r.frequency_hz),
        num(r.damping_ratio),
        num(r.re),
        num(r.second_re),
    ]);
    cols.push(r.status.name().to_string());
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
