//! What a user meets at the edges of the command line, through the real binary: a full or closed
//! stdout, a plot that cannot be written, a `--set` or `--vary` of a key that cannot act, a
//! schedule set aside by `--set`, damaged BeamDyn files, files with a byte-order mark, Slurm
//! array shards.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_flutterscope");

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A failure with a message: exit `code`, no panic, every `needles` in stderr.
fn assert_fails(out: &Output, code: i32, needles: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(code), "stderr: {err}");
    assert!(!err.contains("panicked"), "panic: {err}");
    for n in needles {
        assert!(err.contains(n), "stderr lacks {n:?}: {err}");
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "flutterscope-reliability-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn blades(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades")
        .join(rel)
}

/// One command of each kind, each quick, each writing its report to stdout.
const COMMANDS: &[&[&str]] = &[
    &["presets"],
    &["presets", "--json"],
    &["presets", "--show", "liu2017"],
    &["eigen", "--preset", "liu2017"],
    &["eigen", "--preset", "liu2017", "--json"],
    &["modes", "--preset", "liu2017"],
    &["section", "--preset", "liu2017"],
    &[
        "section",
        "--preset",
        "liu2017",
        "--vary",
        "section.ply_angle=0:90:45",
    ],
    &[
        "flutter",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed",
        "--from",
        "0",
        "--to",
        "60",
        "--points",
        "3",
    ],
    &[
        "simulate",
        "--preset",
        "liu2017",
        "--set",
        "simulation.duration=0.5",
    ],
    &[
        "simulate",
        "--preset",
        "liu2017",
        "--set",
        "simulation.duration=0.5",
        "--csv",
    ],
    &["snapshot", "--preset", "liu2017", "--size", "80x24"],
    &[
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:60:30",
    ],
    &["reproduce", "table1"],
    &["operating", "--preset", "nrel5mw"],
];

#[test]
fn a_full_stdout_is_an_error_for_every_command() {
    for args in COMMANDS {
        let out = Command::new(BIN)
            .args(*args)
            .stdout(Stdio::from(std::fs::File::create("/dev/full").unwrap()))
            .output()
            .unwrap();
        assert_fails(&out, 1, &["error: cannot write to stdout: "]);
        assert!(stderr(&out).contains("No space left"), "{args:?}");
    }
}

#[test]
fn a_closed_stdout_is_an_error_for_every_command() {
    for args in COMMANDS {
        let out = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" >&-"#)
            .arg(BIN)
            .args(*args)
            .output()
            .unwrap();
        assert_fails(&out, 1, &["error: cannot write to stdout: ", "closed"]);
    }
    // /dev/null is a place to write to, not a closed stdout.
    let out = Command::new(BIN)
        .args(["eigen", "--preset", "liu2017"])
        .stdout(Stdio::null())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn a_plot_that_cannot_be_written_leaves_the_file_that_was_there() {
    let dir = scratch("plot");
    let target = dir.join("grid.svg");
    std::fs::write(&target, "the user's own file").unwrap();
    // A file-size limit of one block fails the plot's write part-way (SIGXFSZ ignored, so the
    // write returns EFBIG instead of killing the process).
    let out = Command::new("sh")
        .arg("-c")
        .arg(r#"trap '' XFSZ; ulimit -f 1; exec "$0" "$@""#)
        .arg(BIN)
        .args(["section", "--preset", "liu2017", "--vary"])
        .arg("section.ply_angle=0:90:5")
        .arg("--plot")
        .arg(&target)
        .output()
        .unwrap();
    assert_fails(&out, 1, &["cannot write plot", "grid.svg"]);
    assert_eq!(
        std::fs::read_to_string(&target).unwrap(),
        "the user's own file"
    );
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, vec![std::ffi::OsString::from("grid.svg")]);
    // A plot that can be written replaces the file whole.
    let out = run(&[
        "section",
        "--preset",
        "liu2017",
        "--vary",
        "section.ply_angle=0:90:45",
        "--plot",
        target.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::read_to_string(&target)
        .unwrap()
        .trim_end()
        .ends_with("</svg>"));
}

#[test]
fn a_key_that_cannot_act_for_the_blade_is_refused_naming_what_acts() {
    let cases: &[(&[&str], &[&str])] = &[
        (
            &[
                "sweep",
                "--preset",
                "iea15mw",
                "--vary",
                "section.ply_angle=0:90:45",
            ],
            &[
                "section.ply_angle",
                "blade.file",
                "blade.bend_twist_coupling",
            ],
        ),
        (
            &[
                "eigen",
                "--preset",
                "nrel5mw",
                "--set",
                "structure.loss_factor=0.02",
            ],
            &["structure.loss_factor", "structure.damping_flap"],
        ),
        (
            &[
                "modes",
                "--preset",
                "goland",
                "--set",
                "section.ply_angle=30",
            ],
            &["section.ply_angle", "section.c23"],
        ),
        (
            &[
                "flutter",
                "--preset",
                "iea15mw",
                "--vary",
                "operating.tunnel_speed",
                "--from",
                "0",
                "--to",
                "10",
            ],
            &["operating.tunnel_speed", "operating.wind_speed"],
        ),
        (
            &[
                "operating",
                "--preset",
                "nrel5mw",
                "--vary",
                "operating.tunnel_speed=0:10:5",
            ],
            &["operating.tunnel_speed", "operating.wind_speed"],
        ),
        (
            &[
                "eigen",
                "--preset",
                "liu2017",
                "--set",
                "blade.bend_twist_coupling=0",
            ],
            &["blade.bend_twist_coupling", "section.c23"],
        ),
        (
            &["eigen", "--preset", "iea15mw", "--set", "section.chord=2"],
            &["section.chord", "blade.file"],
        ),
        (
            &[
                "sweep",
                "--preset",
                "nrel5mw",
                "--vary",
                "aero.lift_slope=5:6:1",
            ],
            &["aero.lift_slope", "polar"],
        ),
        (
            &[
                "eigen",
                "--preset",
                "liu2017",
                "--set",
                "operating.precone=2",
            ],
            &["operating.precone", "BEM", "operating.induction"],
        ),
        (
            &[
                "eigen",
                "--preset",
                "demo-blade",
                "--set",
                "structure.damping_flap=0.01",
            ],
            &["structure.damping_flap", "structure.loss_factor"],
        ),
        (
            &[
                "sweep",
                "--preset",
                "iea15mw",
                "--vary",
                "operating.rated_power=1e6:2e6:1e6",
            ],
            &[
                "operating.rated_power",
                "operating.schedule = \"table\"",
                "law",
            ],
        ),
        (
            &["eigen", "--preset", "nrel5mw", "--set", "blade.st_set=2"],
            &["blade.st_set", "HAWC2 st file"],
        ),
        (
            &["eigen", "--preset", "liu2017", "--set", "section.c22=1"],
            &["section.c22", "section.source = \"table\"", "Table 1"],
        ),
        (
            &[
                "eigen",
                "--preset",
                "demo-blade",
                "--set",
                "section.mass_per_length=10",
            ],
            &["section.mass_per_length", "laminate"],
        ),
    ];
    for (args, needles) in cases {
        let out = run(args);
        assert_fails(&out, 2, needles);
        assert!(out.stdout.is_empty(), "{args:?} printed rows");
    }
    // The section command evaluates the layup whatever the blade uses.
    let out = run(&[
        "section",
        "--preset",
        "iea15mw",
        "--vary",
        "section.ply_angle=0:90:45",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn setting_the_schedule_aside_leaves_its_file_unused_with_a_note() {
    let out = run(&[
        "modes",
        "--preset",
        "iea15mw",
        "--set",
        "operating.schedule=none",
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("note: ")
            && err
                .contains("operating.schedule_file = \"blades/iea15mw/IEA_15MW_RWT_Onshore.opt\"")
            && err.contains("not used"),
        "{err}"
    );
    // A preset file that says so itself is still refused: its file would be ignored silently.
    let dir = scratch("schedule");
    let preset = dir.join("p.toml");
    std::fs::write(
        &preset,
        "[operating]\nschedule = \"none\"\nschedule_file = \"x.opt\"\n",
    )
    .unwrap();
    assert_fails(
        &run(&["eigen", "--preset", preset.to_str().unwrap()]),
        1,
        &["operating.schedule_file = \"x.opt\" does not apply"],
    );
}

/// The NREL 5MW BeamDyn files copied into `dir`, each line passed through `edit_primary` and
/// `edit_blade` (1-based line number, line), and a preset naming the copy.
fn beamdyn_copy(
    dir: &Path,
    edit_primary: impl Fn(usize, &str) -> Vec<String>,
    edit_blade: impl Fn(usize, &str) -> String,
) -> PathBuf {
    let copy = |name: &str, edit: &dyn Fn(usize, &str) -> Vec<String>| {
        let text = std::fs::read_to_string(blades(&format!("nrel5mw/{name}"))).unwrap();
        let lines: Vec<String> = text
            .lines()
            .enumerate()
            .flat_map(|(i, l)| edit(i + 1, l))
            .collect();
        std::fs::write(dir.join(name), lines.join("\n") + "\n").unwrap();
    };
    copy("NRELOffshrBsline5MW_BeamDyn.dat", &edit_primary);
    copy("NRELOffshrBsline5MW_BeamDyn_Blade.dat", &|i, l| {
        vec![edit_blade(i, l)]
    });
    let preset = dir.join("blade.toml");
    std::fs::write(
        &preset,
        "[blade]\nsource = \"beamdyn\"\nfile = \"NRELOffshrBsline5MW_BeamDyn.dat\"\nhub_radius = 1.5\n",
    )
    .unwrap();
    preset
}

#[test]
fn a_repeated_beamdyn_key_point_is_refused_at_its_line() {
    let dir = scratch("kp");
    // Line 30 is a key point (kp_zr = 4.19985 m) of the 49 in member 1: written twice, the
    // member's count leaves the tip's line unread.
    let preset = beamdyn_copy(
        &dir,
        |i, l| match i {
            30 => vec![l.to_string(), l.to_string()],
            _ => vec![l.to_string()],
        },
        |_, l| l.to_string(),
    );
    let out = run(&["modes", "--preset", preset.to_str().unwrap()]);
    assert_fails(
        &out,
        1,
        &["NRELOffshrBsline5MW_BeamDyn.dat:31:", "kp_zr", "line 30"],
    );
}

#[test]
fn a_fault_in_a_beamdyn_blade_file_names_that_file_and_line() {
    let dir = scratch("station");
    // Station 1's eta is line 11, its mass matrix lines 19–24: no mass per length.
    let preset = beamdyn_copy(
        &dir,
        |_, l| vec![l.to_string()],
        |i, l| match i {
            19 => l.replacen("6.789350E+02", "0.000000E+00", 1),
            _ => l.to_string(),
        },
    );
    let out = run(&["modes", "--preset", preset.to_str().unwrap()]);
    assert_fails(
        &out,
        1,
        &[
            "NRELOffshrBsline5MW_BeamDyn_Blade.dat:11:",
            "station 1",
            "mass per length = 0 must be positive",
        ],
    );
}

#[test]
fn hawc2_ae_pc_and_opt_files_may_start_with_a_byte_order_mark() {
    let dir = scratch("bom");
    for name in [
        "IEA_15MW_RWT_ae.dat",
        "IEA_15MW_RWT_pc.dat",
        "IEA_15MW_RWT_Onshore.opt",
    ] {
        let text = std::fs::read_to_string(blades(&format!("iea15mw/{name}"))).unwrap();
        std::fs::write(dir.join(name), format!("\u{feff}{text}")).unwrap();
    }
    let builtin = |name: &str| blades(&format!("iea15mw/{name}")).display().to_string();
    let preset = dir.join("iea15mw-bom.toml");
    std::fs::write(
        &preset,
        format!(
            "[blade]\nsource = \"hawc2\"\nfile = \"{}\"\ntwist_file = \"{}\"\nhub_radius = 3.97\n\n\
             [operating]\nschedule = \"table\"\nschedule_file = \"IEA_15MW_RWT_Onshore.opt\"\n\n\
             [aero]\nmodel = \"theodorsen\"\nae_file = \"IEA_15MW_RWT_ae.dat\"\n\
             pc_file = \"IEA_15MW_RWT_pc.dat\"\n",
            builtin("IEA_15MW_RWT_Blade_st_noFPM.st"),
            builtin("IEA-15-240-RWT_AeroDyn15_blade.dat"),
        ),
    )
    .unwrap();
    let out = run(&["presets", "--show", preset.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
}

fn sweep_shard(env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(BIN);
    cmd.args([
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:50:10",
        "--shard",
        "auto",
    ]);
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().unwrap()
}

#[test]
fn slurm_array_tasks_from_any_first_index_and_step_cover_the_sweep_once() {
    let whole = run(&[
        "sweep",
        "--preset",
        "liu2017",
        "--vary",
        "operating.rotor_speed=0:50:10",
    ]);
    assert!(whole.status.success());
    let whole = String::from_utf8(whole.stdout).unwrap();
    // `sbatch --array=1-3` and `--array=4-8:2`.
    for (ids, min, step) in [(["1", "2", "3"], "1", "1"), (["4", "6", "8"], "4", "2")] {
        let mut rows = String::new();
        for (k, id) in ids.iter().enumerate() {
            let out = sweep_shard(&[
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
                ("SLURM_ARRAY_TASK_MIN", min),
                ("SLURM_ARRAY_TASK_STEP", step),
            ]);
            assert!(out.status.success(), "task {id}: {}", stderr(&out));
            let text = String::from_utf8(out.stdout).unwrap();
            // Each shard repeats the header; keep it once.
            let body = text.split_once('\n').unwrap().1;
            if k == 0 {
                rows += text.split_once('\n').unwrap().0;
                rows += "\n";
            }
            rows += body;
        }
        assert_eq!(rows, whole, "array from {min} in steps of {step}");
    }
    let out = sweep_shard(&[
        ("SLURM_ARRAY_TASK_ID", "1"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_STEP", "0"),
    ]);
    assert_fails(&out, 2, &["SLURM_ARRAY_TASK_STEP = 0"]);
    let help = run(&["sweep", "--help"]);
    let help = String::from_utf8(help.stdout).unwrap();
    assert!(
        help.contains("SLURM_ARRAY_TASK_MIN") && help.contains("SLURM_ARRAY_TASK_STEP"),
        "{help}"
    );
}
