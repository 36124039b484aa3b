//! Sweeps: shards merge into the whole, CSV and JSON through the real binary.

use assert_cmd::Command;
use flutterscope::analysis::sweep::{grid_sweep, Grid, Shard, SweepRow};
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
        "operating.rotor_speed,mode,frequency_hz,damping_ratio,re"
    );
    let first = lines.next().unwrap();
    assert!(
        first.starts_with("0,") && first.split(',').count() == 5,
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
    for key in ["values", "mode", "frequency_hz", "damping_ratio", "re"] {
        assert!(rows.iter().all(|r| r.get(key).is_some()), "{key}");
    }
    // The goland wing flutters between 120 and 140 m/s: its torsion-1 track turns unstable.
    let torsion: Vec<f64> = rows
        .iter()
        .filter(|r| r["mode"] == "torsion 1")
        .map(|r| r["re"].as_f64().unwrap())
        .collect();
    assert_eq!(torsion.len(), 3);
    assert!(torsion[0] < 0.0 && torsion[2] > 0.0);
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
