//! The headless commands. Each file turns parsed arguments into a computation through the
//! library and prints text (default), JSON or CSV. No physics here.

use crate::cli::Command;
use crate::error::{Error, Result};
use std::io::Write;

pub mod eigen;
pub mod flutter;
pub mod modes;
pub mod operating;
pub mod presets;
pub mod reproduce;
pub mod section;
pub mod simulate;
pub mod slurm;
pub mod snapshot;
pub mod sweep;
pub mod tui;

pub fn run(command: Command) -> Result<()> {
    match command {
        Command::Tui(args) => tui::run(&args),
        Command::Modes {
            preset,
            json,
            shapes,
            plot,
        } => modes::run(&preset.load()?, json, shapes, plot.as_deref()),
        Command::Eigen { preset, json } => eigen::run(&preset.load()?, json),
        Command::Operating {
            preset,
            vary,
            json,
            csv,
            plot,
        } => operating::run(&preset.load()?, vary.as_deref(), json, csv, plot.as_deref()),
        Command::Flutter {
            preset,
            vary,
            from,
            to,
            points,
            json,
            plot,
        } => flutter::run(
            &preset.load()?,
            &vary,
            from,
            to,
            points as usize,
            json,
            plot.as_deref(),
        ),
        Command::Sweep {
            preset,
            vary,
            csv: _,
            json,
            shard,
            plot,
        } => sweep::run(
            &preset.load()?,
            &vary,
            json,
            shard.as_deref(),
            plot.as_deref(),
        ),
        Command::Simulate {
            preset,
            json,
            csv,
            plot,
        } => simulate::run(&preset.load()?, json, csv, plot.as_deref()),
        Command::Section {
            preset,
            at: Some(eta),
            json,
            plot,
            ..
        } => section::run_at(&preset.load_for_layup()?, eta, json, plot.as_deref()),
        Command::Section {
            preset,
            vary,
            json,
            plot,
            ..
        } => section::run(
            &preset.load_for_layup()?,
            vary.as_deref(),
            json,
            plot.as_deref(),
        ),
        Command::Reproduce { what, json, plot } => reproduce::run(what, json, plot.as_deref()),
        Command::Snapshot {
            preset,
            size,
            view,
            marker,
        } => snapshot::run(&preset, &size, view, marker),
        Command::Presets {
            json,
            preset,
            show,
            set,
        } => match show.or(preset) {
            Some(name) => presets::show(&name, &set),
            None => presets::run(json),
        },
    }
}

/// No subcommand in a terminal: the explorer on the default preset.
pub fn run_default_tui(args: &crate::cli::TuiArgs) -> Result<()> {
    tui::run(args)
}

/// Print a serialisable value as pretty JSON on stdout.
pub fn print_json<T: serde::Serialize>(value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::Io(format!("cannot encode JSON: {e}")))?;
    text.push('\n');
    print_text(&text)
}

/// Write a report to stdout ([`stdout`]).
pub fn print_text(text: &str) -> Result<()> {
    let mut out = stdout()?;
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(stdout_error)
}

/// Standard output for a command's report, or the error that it cannot take one. A full device
/// (`> /dev/full`) fails on the write itself ([`stdout_error`]); a descriptor closed when the
/// program started (`>&-`) does not: the Rust runtime reopens it on /dev/null, so everything
/// written would vanish and the command would succeed with nothing to show for it.
pub fn stdout() -> Result<std::io::StdoutLock<'static>> {
    if closed_at_start() {
        return Err(Error::Io(
            "cannot write to stdout: it was closed when flutterscope started (redirect it to a \
             file, a pipe or /dev/null instead)"
                .to_string(),
        ));
    }
    Ok(std::io::stdout().lock())
}

/// A failed write to stdout as the command's error (a reader that closed the pipe early,
/// `| head`, ends the process quietly by SIGPIPE before this is reached).
pub fn stdout_error(e: std::io::Error) -> Error {
    Error::Io(format!("cannot write to stdout: {e}"))
}

/// Whether descriptor 1 is the /dev/null the Rust runtime opened, read-write, in place of a
/// descriptor that was closed at start. A shell's `> /dev/null` opens it write-only.
#[cfg(unix)]
fn closed_at_start() -> bool {
    use std::os::unix::fs::MetadataExt;
    // SAFETY: F_GETFL and fstat only read descriptor 1's flags and status into owned memory.
    let (flags, stat) = unsafe {
        let mut stat: libc::stat = std::mem::zeroed();
        let flags = libc::fcntl(libc::STDOUT_FILENO, libc::F_GETFL);
        (
            flags,
            (libc::fstat(libc::STDOUT_FILENO, &mut stat) == 0).then_some(stat),
        )
    };
    let Some(stat) = stat else { return true };
    flags & libc::O_ACCMODE == libc::O_RDWR
        && stat.st_mode & libc::S_IFMT == libc::S_IFCHR
        && std::fs::metadata("/dev/null").is_ok_and(|null| null.rdev() == stat.st_rdev)
}

#[cfg(not(unix))]
fn closed_at_start() -> bool {
    false
}

/// Most points one `--vary KEY=FROM:TO:STEP` axis may have.
pub const MAX_AXIS_POINTS: usize = 10_000_000;

/// Parse `KEY=FROM:TO:STEP` into the key and its grid (FROM and TO included when STEP divides
/// the range; the last point never overshoots TO).
pub fn parse_vary(spec: &str) -> Result<(String, Vec<f64>)> {
    let bad = |why: &str| {
        Error::usage(format!(
            "--vary '{spec}': {why}; expected KEY=FROM:TO:STEP, e.g. operating.rotor_speed=0:200:5"
        ))
    };
    let (key, range) = spec.split_once('=').ok_or_else(|| bad("missing '='"))?;
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(bad("range needs three numbers"));
    }
    let num = |s: &str| -> Result<f64> {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(&format!("'{s}' is not a finite number")))
    };
    let (from, to, step) = (num(parts[0])?, num(parts[1])?, num(parts[2])?);
    if step <= 0.0 {
        return Err(bad("STEP must be positive"));
    }
    if to < from {
        return Err(bad("TO must not be below FROM"));
    }
    // Counted in floating point: a tiny STEP gives more points than any integer holds.
    let count = ((to - from) / step + 1e-9).floor() + 1.0;
    if count > MAX_AXIS_POINTS as f64 {
        let count = if count.is_finite() {
            format!(
                "{} (10 million) per --vary",
                crate::analysis::grid::beyond_limit(count, MAX_AXIS_POINTS)
            )
        } else {
            format!(
                "more points than a number holds; the limit is {MAX_AXIS_POINTS} (10 million) \
                 per --vary"
            )
        };
        return Err(bad(&format!(
            "the grid is too large: {count}, so STEP must be at least (TO − FROM)/{}",
            MAX_AXIS_POINTS - 1
        )));
    }
    crate::preset::key_spec(key.trim())?;
    let grid = axis(from, step, count as usize, decimals(&[parts[0], parts[2]]));
    if let Some(&last) = grid.last() {
        if to - last > 1e-9 * step {
            eprintln!(
                "note: --vary '{spec}': the grid stops at {last}, the last FROM + k·STEP not \
                 beyond TO = {to}"
            );
        }
    }
    Ok((key.trim().to_string(), grid))
}

/// `count` values from `from` by `step`, each the decimal the user's numbers carry (`decimals`
/// after the point: `0.1 · 3` is 0.3, not 0.30000000000000004), counted in integers of that
/// decimal where they fit a double exactly.
fn axis(from: f64, step: f64, count: usize, decimals: Option<i32>) -> Vec<f64> {
    let exact = decimals.and_then(|d| {
        let scale = 10f64.powi(d);
        let (a, s) = ((from * scale).round(), (step * scale).round());
        let limit = 2f64.powi(53);
        (s > 0.0 && a.abs() + s * count as f64 <= limit).then_some((a, s, scale))
    });
    (0..count)
        .map(|i| match exact {
            Some((a, s, scale)) => (a + s * i as f64) / scale,
            None => from + step * i as f64,
        })
        .collect()
}

/// The most digits after the decimal point among `numbers` as written (`2.5e-3` has 4), or
/// none beyond what a double's decimal holds exactly.
fn decimals(numbers: &[&str]) -> Option<i32> {
    numbers
        .iter()
        .map(|s| {
            let s = s.trim().to_ascii_lowercase();
            let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
            let exponent: i32 = exponent.parse().ok()?;
            let after = mantissa.split_once('.').map_or(0, |(_, f)| f.len() as i32);
            Some((after - exponent).max(0))
        })
        .try_fold(0, |d, n| n.map(|n| d.max(n)))
        .filter(|&d| d <= 15)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vary_grid_includes_both_ends() {
        let (k, g) = parse_vary("operating.rotor_speed=0:200:50").unwrap();
        assert_eq!(k, "operating.rotor_speed");
        assert_eq!(g, vec![0.0, 50.0, 100.0, 150.0, 200.0]);
    }

    #[test]
    fn vary_rejects_bad_specs() {
        for bad in [
            "operating.rotor_speed",
            "operating.rotor_speed=0:10",
            "operating.rotor_speed=0:10:0",
            "operating.rotor_speed=10:0:1",
            "operating.rotor_speed=a:10:1",
            "no.such_key=0:1:1",
        ] {
            assert!(parse_vary(bad).is_err(), "{bad} accepted");
        }
    }

    #[test]
    fn a_tiny_step_is_a_grid_too_large_with_its_count() {
        for spec in [
            "operating.rotor_speed=0:5000:1e-300",
            "operating.rotor_speed=0:5000:5e-324",
            "operating.rotor_speed=0:1:1e-7",
        ] {
            let e = parse_vary(spec).unwrap_err().to_string();
            assert!(
                e.contains("too large") && e.contains("10000000"),
                "{spec}: {e}"
            );
        }
        assert!(parse_vary("operating.rotor_speed=0:5000:1e-300")
            .unwrap_err()
            .to_string()
            .contains("5.0000e303 points"));
    }
}
