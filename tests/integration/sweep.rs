//! Sweeps: shards merge into the whole, CSV and JSON through the real binary.

use assert_cmd::Command;
use flutterscope::analysis::grid::{Grid, Shard};
use flutterscope::analysis::sweep::{grid_sweep, SweepRow};
use flutterscope::preset::{Preset, ValidPreset};

fn rows(p: &ValidPreset, grid: &Grid, shard: Option<Shard>) -> Vec<SweepRow> {
    let mut out = Vec::new();
    grid_sweep(p, grid, shard, &|_| {}, &mut |batch| {
        out.extend_from_slice(batch);
        Ok(())
    })
    .unwrap();
    out
}

#[test]
fn shards_concatenate_to_the_whole_grid() {
    let p = Preset::load("liu2017", &[]).unwrap();
    let grid = Grid {
        keys: vec!["operating.pitch".into(), "operating.rotor_speed".into()],
        axes: vec![vec![0.0, 10.0], (0..7).map(|k| 20.0 * k as f64).collect()],
    };
    let whole = rows(&p, &grid, None);
    assert!(!whole.is_empty() && whole.len() % grid.total() == 0);
    // 3 shards cut the 14 points at 4 and 9: both cuts fall inside a tracking line.
    let mut merged = Vec::new();
    for index in 1..=3 {
        merged.extend(rows(&p, &grid, Some(Shard { index, count: 3 })));
    }
    // Debug text compares NaN (a mode without a partner at a point) equal to itself.
    assert_eq!(format!("{merged:?}"), format!("{whole:?}"));
}

fn stdout(args: &[&str]) -> String {
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args(args)
        .assert()
        .success();
    String::from_utf8(out.get_output().stdout.clone()).unwrap()
}

#[test]
fn csv_shards_merge_like_the_readme_says() {
    let base = [
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:100:20",
    ];
    let whole = stdout(&base);
    let mut lines = whole.lines();
    assert_eq!(
        lines.next().unwrap(),
        "operating.rotor_speed,mode,frequency_hz,damping_ratio,re,second_re,status"
    );
    let first = lines.next().unwrap();
    assert!(
        first.starts_with("0,") && first.split(',').count() == 7,
        "{first}"
    );
    // Header from the first shard, body of every shard.
    let mut merged = String::new();
    for i in 1..=4 {
        let part = stdout(&[&base[..], &["--shard", &format!("{i}/4")]].concat());
        let mut it = part.lines();
        let header = it.next().unwrap();
        if i == 1 {
            merged += header;
            merged += "\n";
        }
        for l in it {
            merged += l;
            merged += "\n";
        }
    }
    // Debug text compares NaN (a mode without a partner at a point) equal to itself.
    assert_eq!(format!("{merged:?}"), format!("{whole:?}"));
}

#[test]
fn sweep_json_shape_and_errors() {
    let text = stdout(&[
        "sweep",
        "--preset",
        "goland",
        "--vary",
        "operating.tunnel_speed=100:140:20",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["parameters"][0], "operating.tunnel_speed");
    let rows = v["rows"].as_array().unwrap();
    assert!(rows.len() >= 3);
    for key in [
        "values",
        "mode",
        "frequency_hz",
        "damping_ratio",
        "re",
        "status",
    ] {
        assert!(rows.iter().all(|r| r.get(key).is_some()), "{key}");
    }
    // The goland wing flutters between 120 and 140 m/s: one named track turns unstable, and
    // it carries the name `eigen` gives the growing root at 140 m/s.
    let unstable: Vec<&str> = rows
        .iter()
        .filter(|r| r["values"][0] == 140.0 && r["re"].as_f64().is_some_and(|re| re > 0.0))
        .map(|r| r["mode"].as_str().unwrap())
        .collect();
    let p = flutterscope::preset::Preset::load("goland", &["operating.tunnel_speed=140".into()])
        .unwrap();
    let eigen = flutterscope::analysis::eigen::analyse(&p).unwrap();
    assert_eq!(unstable, [eigen.critical().unwrap().label.as_str()]);
    let track: Vec<f64> = rows
        .iter()
        .filter(|r| r["mode"] == unstable[0])
        .map(|r| r["re"].as_f64().unwrap())
        .collect();
    assert_eq!(track.len(), 3);
    assert!(track[0] < 0.0 && track[2] > 0.0);
    for bad in [&["--shard", "5/4"][..], &["--plot", "sweep.txt"][..]] {
        Command::cargo_bin("flutterscope")
            .unwrap()
            .args(
                [
                    &["sweep", "--vary", "operating.rotor_speed=0:10:5"][..],
                    bad,
                ]
                .concat(),
            )
            .assert()
            .code(2);
    }
}

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn run(args: &[&str]) -> Run {
    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args(args)
        .output()
        .unwrap();
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// The stall preset has no static equilibrium at 0 rpm (20 m/s of wind straight into a blade
/// that does not turn): that point fails, and it used to take every row with it, because
/// tracking started from the first point. Now it costs that point only, is counted and named.
#[test]
fn a_failed_first_point_costs_that_point_only_json() {
    let r = run(&[
        "sweep",
        "--preset",
        "liu2017-stall",
        "--vary",
        "operating.rotor_speed=0:5000:500",
        "--json",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(v["points"], 11);
    assert_eq!(v["failed_points"], 1);
    let rows = v["rows"].as_array().unwrap();
    let failed = &rows[0];
    assert_eq!(failed["status"], "failed");
    assert_eq!(failed["values"][0], 0.0);
    assert!(failed["mode"].is_null() && failed["re"].is_null());
    assert!(
        failed["error"]
            .as_str()
            .unwrap()
            .contains("static equilibrium"),
        "{failed}"
    );
    // Every other speed has its modes; values exactly where the status is ok.
    for rpm in (1..=10).map(|k| 500.0 * k as f64) {
        let at: Vec<&serde_json::Value> = rows.iter().filter(|r| r["values"][0] == rpm).collect();
        assert!(
            at.iter()
                .any(|r| r["mode"] == "flap 1" && r["status"] == "ok"),
            "{rpm}"
        );
    }
    let mut no_root = 0;
    for row in rows {
        let ok = row["status"] == "ok";
        no_root += usize::from(row["status"] == "no-root");
        for key in ["frequency_hz", "damping_ratio", "re"] {
            assert_eq!(row[key].is_f64(), ok, "{row}");
        }
    }
    assert_eq!(v["no_root_rows"], no_root);
    assert!(
        r.stderr
            .contains("warning: 1 of 11 grid point(s) could not be solved")
            && r.stderr
                .contains("at operating.rotor_speed = 0: numerical: static equilibrium"),
        "{}",
        r.stderr
    );
}

/// Two keys: the failed point (20 m/s, 0 rpm) used to take its whole `wind = 20` line.
#[test]
fn a_failed_point_keeps_the_rest_of_its_line_csv() {
    let r = run(&[
        "sweep",
        "--preset",
        "liu2017-stall",
        "--vary",
        "operating.wind_speed=10:20:10",
        "--vary",
        "operating.rotor_speed=0:100:50",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let lines: Vec<&str> = r.stdout.lines().collect();
    assert_eq!(
        lines[0],
        "operating.wind_speed,operating.rotor_speed,mode,frequency_hz,damping_ratio,re,second_re,status"
    );
    assert!(lines.contains(&"20,0,,,,,,failed"), "{}", r.stdout);
    for rpm in ["50", "100"] {
        assert!(
            lines
                .iter()
                .any(|l| l.starts_with(&format!("20,{rpm},flap 1,")) && l.ends_with(",ok")),
            "no wind = 20, {rpm} rpm rows:\n{}",
            r.stdout
        );
    }
    for l in &lines[1..] {
        let cols: Vec<&str> = l.split(',').collect();
        assert_eq!(cols.len(), 8, "{l}");
        let empty = cols[3..6].iter().all(|c| c.is_empty());
        assert_eq!(empty, !["ok", "overdamped"].contains(&cols[7]), "{l}");
        // The second decay rate is there exactly on overdamped rows.
        assert_eq!(cols[6].is_empty(), cols[7] != "overdamped", "{l}");
    }
    assert!(
        r.stderr.contains("1 of 6 grid point(s)")
            && r.stderr
                .contains("operating.wind_speed = 20, operating.rotor_speed = 0"),
        "{}",
        r.stderr
    );
}

/// An overdamped mode keeps its name and its row: liu2017's torsion modes are two real roots
/// each at rest (one mode, status `overdamped`, with values) and oscillate further on under the
/// same names. No row goes empty and nothing is called a failure (before identification merged
/// the pair, `torsion 1` had no root of its own at 50 rpm and its rows said `no-root`).
#[test]
fn overdamped_modes_keep_their_rows() {
    let r = run(&[
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:100:50",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(!r.stdout.lines().any(|l| l.contains(",,,")), "{}", r.stdout);
    assert!(r.stdout.contains("0,torsion 1,0,"), "{}", r.stdout);
    let at_rest = r
        .stdout
        .lines()
        .find(|l| l.starts_with("0,torsion 1,"))
        .unwrap_or_else(|| panic!("no torsion 1 row at rest:\n{}", r.stdout));
    let cols: Vec<&str> = at_rest.split(',').collect();
    assert_eq!(cols.last(), Some(&"overdamped"), "{at_rest}");
    // Both real roots are in the row: `re` the less stable, `second_re` the other.
    let re: f64 = cols[4].parse().unwrap();
    let second: f64 = cols[5].parse().unwrap();
    assert!(second < re, "{at_rest}");
    assert!(
        r.stdout
            .lines()
            .any(|l| l.starts_with("100,torsion 1,") && l.ends_with(",ok")),
        "{}",
        r.stdout
    );
    assert!(!r.stderr.contains("warning"), "{}", r.stderr);
    assert!(!r.stderr.contains("no values"), "{}", r.stderr);
}

/// Bad input is found before the first line of output: no CSV header above the error.
#[test]
fn input_errors_come_before_any_output() {
    for (vary, needle) in [
        (
            &["operating.rotor_speed=0:6000:1000"][..],
            "operating.rotor_speed = 6000 is out of range",
        ),
        // alpha2 (18) must exceed alpha1: broken at the grid's corner alpha1 = 20.
        (
            &["aero.onera.alpha1=0:20:10", "operating.rotor_speed=0:10:10"][..],
            "at the sweep's grid point aero.onera.alpha1 = 20",
        ),
        (&["structure.modes=1:3:0.5"][..], "structure.modes = 1.5"),
    ] {
        let mut args = vec!["sweep"];
        for v in vary {
            args.extend(["--vary", v]);
        }
        for json in [false, true] {
            let mut args = args.clone();
            if json {
                args.push("--json");
            }
            let r = run(&args);
            assert_eq!(r.code, Some(1), "{args:?}: {}", r.stderr);
            assert_eq!(r.stdout, "", "{args:?} printed before failing");
            assert!(r.stderr.contains(needle), "{args:?}: {}", r.stderr);
        }
    }
    // An enormous grid is too large, with its count and the limit.
    let r = run(&["sweep", "--vary", "operating.rotor_speed=0:5000:1e-300"]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains("too large: 5.0000e303 points") && r.stderr.contains("10000000"),
        "{}",
        r.stderr
    );
    assert_eq!(r.stdout, "");
}

/// A veering that moves a name to the other branch is reported, not hidden: demo-blade's flap 1
/// and flap 2 swap content between 170 and 180 rpm. stderr names both, JSON lists them with
/// where (inside the step), and every listed name is a tracked mode of the rows.
#[test]
fn name_switches_are_reported() {
    let args = [
        "sweep",
        "--preset",
        "demo-blade",
        "--vary",
        "operating.rotor_speed=0:200:10",
    ];
    let r = run(&args);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let note = r
        .stderr
        .lines()
        .find(|l| l.contains("moved to another root branch"))
        .unwrap_or_else(|| panic!("no switch note:\n{}", r.stderr));
    let v: serde_json::Value =
        serde_json::from_str(&stdout(&[&args[..], &["--json"]].concat())).unwrap();
    let switches = v["switches"].as_array().unwrap();
    assert!(!switches.is_empty());
    assert!(
        note.starts_with(&format!("note: {} time(s)", switches.len())),
        "{note}"
    );
    let modes: Vec<&str> = v["rows"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|row| row["mode"].as_str())
        .collect();
    for s in switches {
        let mode = s["mode"].as_str().unwrap();
        let at = s["values"][0].as_f64().unwrap();
        assert!(modes.contains(&mode), "{s}");
        assert!(
            note.contains(&format!("{mode} at operating.rotor_speed = {at}")),
            "{note}"
        );
        // Strictly inside a step: a switch is found between two grid points, never on one.
        assert!(at > 0.0 && at < 200.0 && at % 10.0 != 0.0, "{s}");
    }
}

/// The stall preset has no static equilibrium at 0 rpm: a sweep of that point alone has no
/// result at all, and says so by its exit status, after the `failed` row.
#[test]
fn a_sweep_whose_every_point_failed_exits_non_zero() {
    for json in [false, true] {
        let mut args = vec![
            "sweep",
            "--preset",
            "liu2017-stall",
            "--vary",
            "operating.rotor_speed=0:0:1",
        ];
        if json {
            args.push("--json");
        }
        let r = run(&args);
        assert_eq!(r.code, Some(1), "{args:?}: {}", r.stderr);
        assert!(
            r.stderr
                .contains("error: numerical: none of the sweep's 1 grid point(s) could be solved")
                && r.stderr
                    .contains("at operating.rotor_speed = 0: numerical: static equilibrium"),
            "{args:?}: {}",
            r.stderr
        );
        if json {
            let v: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
            assert_eq!(
                (v["points"].clone(), v["failed_points"].clone()),
                (1.into(), 1.into())
            );
            assert_eq!(v["rows"][0]["status"], "failed");
        } else {
            assert!(r.stdout.ends_with("\n0,,,,,,failed\n"), "{}", r.stdout);
        }
    }
}

/// Rows come out as the points are solved, in grid order: a sweep far too long to wait for has
/// printed its first points while it runs (CSV and JSON), so a sweep that is stopped keeps what
/// it finished.
#[test]
fn a_long_sweep_prints_its_first_points_while_it_runs() {
    use std::io::BufRead;
    for json in [false, true] {
        let mut args = vec![
            "sweep",
            "--preset",
            "liu2017",
            "--vary",
            "operating.wind_speed=5:30:0.0001",
        ];
        if json {
            args.push("--json");
        }
        let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("flutterscope"))
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        let out = std::io::BufReader::new(child.stdout.take().unwrap());
        let (lines, received) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            for line in out.lines().map_while(std::result::Result::ok) {
                if lines.send(line).is_err() {
                    break;
                }
            }
        });
        // The first points' wind speeds, in grid order: CSV rows start with it; JSON rows hold
        // it as the line after `"values": [`.
        let mut seen: Vec<String> = Vec::new();
        let mut after_values = false;
        while seen.len() < 2 {
            let line = received
                .recv_timeout(std::time::Duration::from_secs(120))
                .unwrap_or_else(|e| panic!("{args:?}: no rows while the sweep runs ({e})"));
            let value = if json {
                let v = std::mem::replace(&mut after_values, line.ends_with("\"values\": ["));
                v.then(|| line.trim().to_string())
            } else {
                line.split(',')
                    .next()
                    .filter(|v| v.starts_with('5'))
                    .map(str::to_string)
            };
            if let Some(v) = value.filter(|v| seen.last() != Some(v)) {
                seen.push(v);
            }
        }
        let running = child.try_wait().unwrap().is_none();
        child.kill().unwrap();
        child.wait().unwrap();
        assert!(running, "{args:?}: the sweep had finished");
        let first = if json { "5.0" } else { "5" };
        assert_eq!(seen, [first, "5.0001"], "{args:?}");
    }
}

/// Swept values are the decimals the grid is written in (0.1 · 3 is 0.3, not
/// 0.30000000000000004), and a grid whose STEP does not divide the range says where it stops.
#[test]
fn swept_values_are_the_grids_decimals_and_its_end_is_told() {
    let r = run(&[
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.pitch=0:0.3:0.1",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let mut values: Vec<&str> = r
        .stdout
        .lines()
        .skip(1)
        .map(|l| &l[..l.find(',').unwrap()])
        .collect();
    values.dedup();
    assert_eq!(values, ["0", "0.1", "0.2", "0.3"], "{}", r.stdout);
    assert!(!r.stderr.contains("grid stops"), "{}", r.stderr);
    let r = run(&[
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:100:33",
    ]);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(
        r.stderr.contains(
            "note: --vary 'operating.rotor_speed=0:100:33': the grid stops at 99, the last \
             FROM + k·STEP not beyond TO = 100"
        ),
        "{}",
        r.stderr
    );
}

/// A grid beyond the point-count limits says the limit and how far beyond it the request is.
#[test]
fn a_grid_too_large_says_by_how_much() {
    let r = run(&["sweep", "--vary", "operating.rotor_speed=0:100:0.000001"]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains(
            "too large: 1.0000e8 points, 10.0 times the limit of 10000000 (10 million) per --vary"
        ),
        "{}",
        r.stderr
    );
    let r = run(&[
        "sweep",
        "--vary",
        "operating.pitch=0:20:0.001",
        "--vary",
        "operating.rotor_speed=0:100:0.001",
    ]);
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains(
            "too large: 20001 × 100001 = 2.0001e9 points, 20.0 times the limit of 100000000 \
             (100 million)"
        ),
        "{}",
        r.stderr
    );
    assert_eq!(r.stdout, "");
}
