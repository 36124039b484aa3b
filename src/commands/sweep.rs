//! `flutterscope sweep`: tracked modes over a grid of one or more keys (CSV or JSON), on all
//! cores, optionally one shard of the grid.

use super::stdout_error;
use crate::analysis::grid::{Grid, Shard};
use crate::analysis::sweep::{grid_sweep, SweepRow, SweepSummary};
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
    let shard = shard.map(super::slurm::shard).transpose()?;
    let own = shard.map_or(grid.total(), |s| s.range(grid.total()).len());
    let bar = progress_bar(own as u64);
    let progress = |n: u64| bar.inc(n);
    let mut out = std::io::BufWriter::new(super::stdout()?);
    let mut keep = |batch: &[SweepRow]| {
        if plot.is_some() {
            plotted.extend_from_slice(batch);
        }
    };
    let result = if json {
        write_json(&mut out, p, &grid, shard, &progress, &mut keep)
    } else {
        write_csv(&mut out, p, &grid, shard, &progress, &mut keep)
    };
    bar.finish_and_clear();
    let summary = result?;
    drop(out);
    for line in warnings(&grid.keys, &summary) {
        eprintln!("{line}");
    }
    if let Some(e) = all_failed(&grid.keys, &summary) {
        return Err(e);
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

/// The sweep as CSV, a line per row as the points are solved.
fn write_csv(
    out: &mut impl Write,
    p: &ValidPreset,
    grid: &Grid,
    shard: Option<Shard>,
    progress: &(dyn Fn(u64) + Sync),
    keep: &mut dyn FnMut(&[SweepRow]),
) -> Result<SweepSummary> {
    writeln!(out, "{}", csv_header(&grid.keys)).map_err(stdout_error)?;
    let summary = grid_sweep(p, grid, shard, progress, &mut |batch| {
        for r in batch {
            writeln!(out, "{}", csv_row(r)).map_err(stdout_error)?;
        }
        keep(batch);
        out.flush().map_err(stdout_error)
    })?;
    Ok(summary)
}

/// The sweep as one JSON object, its rows written as the points are solved and the counts,
/// known only at the end, after them.
fn write_json(
    out: &mut impl Write,
    p: &ValidPreset,
    grid: &Grid,
    shard: Option<Shard>,
    progress: &(dyn Fn(u64) + Sync),
    keep: &mut dyn FnMut(&[SweepRow]),
) -> Result<SweepSummary> {
    let points = shard.map_or(grid.total(), |s| s.range(grid.total()).len());
    write!(
        out,
        "{{\n  \"parameters\": {},\n  \"points\": {points},\n  \"rows\": [",
        pretty(&grid.keys, 2)?
    )
    .map_err(stdout_error)?;
    let mut first = true;
    let summary = grid_sweep(p, grid, shard, progress, &mut |batch| {
        for r in batch {
            let sep = if std::mem::take(&mut first) { "" } else { "," };
            write!(out, "{sep}\n    {}", pretty(r, 4)?).map_err(stdout_error)?;
        }
        keep(batch);
        out.flush().map_err(stdout_error)
    })?;
    let close = if first { "]" } else { "\n  ]" };
    writeln!(
        out,
        "{close},\n  \"failed_points\": {},\n  \"no_root_rows\": {},\n  \"switches\": {}\n}}",
        summary.failed,
        summary.no_root,
        pretty(&summary.switches, 2)?
    )
    .and_then(|()| out.flush())
    .map_err(stdout_error)?;
    Ok(summary)
}

/// `value` as pretty JSON whose lines after the first are indented by `indent` spaces (its
/// place inside the sweep's object).
fn pretty(value: &impl serde::Serialize, indent: usize) -> Result<String> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::Io(format!("cannot encode JSON: {e}")))?;
    Ok(text.replace('\n', &format!("\n{}", " ".repeat(indent))))
}

/// A sweep none of whose points could be solved has no result to give: an error, after its
/// `failed` rows.
fn all_failed(keys: &[String], s: &SweepSummary) -> Option<Error> {
    let r = s.first_failed.as_ref().filter(|_| s.failed == s.points)?;
    Some(Error::numerical(format!(
        "none of the sweep's {} grid point(s) could be solved (every row has status `failed`); \
         the first, at {}: {}",
        s.points,
        at_values(keys, &r.values),
        r.error.as_deref().unwrap_or("unknown error")
    )))
}

/// `key = value` for each grid key, as the warnings name a point.
fn at_values(keys: &[String], values: &[f64]) -> String {
    keys.iter()
        .zip(values)
        .map(|(k, v)| format!("{k} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// What the rows without values mean, counted: failed points (a warning, with the first one's
/// values and error) and modes without a root at a solved point (a note: physics, not failure).
pub fn warnings(keys: &[String], s: &SweepSummary) -> Vec<String> {
    let at_values = |values: &[f64]| at_values(keys, values);
    let at = |r: &SweepRow| at_values(&r.values);
    let mut out = Vec::new();
    if let Some(r) = s.first_failed.as_ref().filter(|_| s.failed < s.points) {
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
    use std::fmt::Write;
    // Written in place: a sweep writes millions of these.
    let mut line = String::with_capacity(128);
    for v in &r.values {
        let _ = write!(line, "{v},");
    }
    line.push_str(r.mode.as_deref().unwrap_or_default());
    for v in [r.frequency_hz, r.damping_ratio, r.re, r.second_re] {
        line.push(',');
        if v.is_finite() {
            let _ = write!(line, "{v}");
        }
    }
    line.push(',');
    line.push_str(r.status.name());
    line
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
