//! HAWC2 blades from their htc model (docs/model.md §11.6, §12.1–§12.2): the IEA 15MW onshore
//! model in its own folders gives the same structure as its st file read directly, the twist
//! and prebend of its c2_def agree with the AeroDyn 15 file's, and a broken model is named by
//! file, line and block.

use flutterscope::formats::aerodyn;
use flutterscope::formats::text_file::{DiskFile, ModelRoot};
use flutterscope::model::blade::blade_structure;
use flutterscope::physics::blade::hawc2::ChordTwist;
use flutterscope::physics::blade::source::HtcFiles;
use flutterscope::physics::rotor::files::read_prebend;
use flutterscope::preset::{Preset, ValidPreset};
use std::path::{Path, PathBuf};

const MODEL: &str = "presets/blades/iea15mw-hawc2";
const HTC: &str = "IEA-15-240-RWT-Onshore/htc/IEA_15MW_RWT_Onshore.htc";
const BODIES: &str = "IEA-15-240-RWT/IEA_15MW_RWT_WTG_bodies_noFPM.htc";
const AERODYN: &str = "presets/blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat";

fn load(name: &str, overrides: &[&str]) -> flutterscope::error::Result<ValidPreset> {
    let overrides: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &overrides)
}

/// The AeroDyn 15 file's `(BlSpn, BlTwist in rad, BlCrvAC)`.
fn aerodyn_nodes() -> Vec<(f64, f64, f64)> {
    let text = std::fs::read_to_string(AERODYN).unwrap();
    aerodyn::parse_blade(&text, AERODYN)
        .unwrap()
        .nodes
        .iter()
        .map(|n| (n.bl_spn, n.bl_twist_deg.to_radians(), n.bl_crv_ac))
        .collect()
}

/// Linear interpolation in a table of increasing `x`, held beyond its ends.
fn interpolate(table: &[(f64, f64)], x: f64) -> f64 {
    let k = table.partition_point(|p| p.0 <= x);
    if k == 0 {
        return table[0].1;
    }
    if k == table.len() {
        return table[k - 1].1;
    }
    let ((xa, ya), (xb, yb)) = (table[k - 1], table[k]);
    ya + (yb - ya) * (x - xa) / (xb - xa)
}

/// The htc blade is the st file's blade: the same st file and set, station for station, the
/// same mass and stiffness; only the twist differs (c2_def's against BlTwist), and by at most
/// 0.011° (measured 0.0101°, at 10.5 m: BlTwist and c2_def are sampled at different stations
/// and each is read linearly between them). On the prebent axis the modes agree within 0.4 %
/// (measured 0.37 %, torsion 1): the htc's prebend is the half-chord line's, not the pitch
/// axis's. The htc's tuned damping_aniso gives the first flap
/// and edge modes 3 % logarithmic decrement (measured 2.9 % and 3.0 % at 7.56 rpm).
#[test]
fn the_htc_blade_is_the_st_file_blade_with_c2_def_twist() {
    let htc = load("iea15mw-htc", &[]).unwrap();
    let st = load("iea15mw", &[]).unwrap();
    let (a, b) = (
        htc.tabulated_blade().unwrap(),
        st.tabulated_blade().unwrap(),
    );
    assert_eq!(a.table.sections.len(), b.table.sections.len());
    let mut worst: f64 = 0.0;
    for (x, y) in a.table.sections.iter().zip(&b.table.sections) {
        let untwisted = |s: &flutterscope::physics::blade::BeamSection| {
            let mut s = *s;
            s.twist = 0.0;
            s
        };
        assert_eq!(untwisted(x), untwisted(y), "station at {} m", x.z);
        worst = worst.max((x.twist - y.twist).abs().to_degrees());
    }
    eprintln!("largest twist difference between c2_def and BlTwist: {worst:.5}°");
    assert!(worst < 0.011, "{worst}°");

    let omega = htc.omega();
    let modes = |p: &ValidPreset| blade_structure(p).unwrap().unwrap().modes(omega).unwrap();
    let straight = |p: &ValidPreset| p.edited(|e| e.structure.curved = false).unwrap();
    // Straight, only the twist differs; curved, the prebend too: c2_def's half-chord line sits
    // up to 0.20 m downwind of BlCrvAC's pitch axis inboard ([`prebend_from_c2_def_is_blcrvac`]),
    // which the edge modes, coupled to the twist by the curve, feel most.
    for (what, (ma, mb), bound) in [
        (
            "straight",
            (modes(&straight(&htc)), modes(&straight(&st))),
            2e-5,
        ),
        ("curved", (modes(&htc), modes(&st)), 5e-3),
    ] {
        for (k, (x, y)) in ma.iter().zip(&mb).enumerate() {
            let d = (x.frequency_hz - y.frequency_hz) / y.frequency_hz;
            eprintln!(
                "{what} mode {}: htc {:.6} Hz, st + BlTwist {:.6} Hz ({:+.2e})",
                k + 1,
                x.frequency_hz,
                y.frequency_hz,
                d
            );
            assert!(d.abs() < bound, "{what} mode {}: {d:e}", k + 1);
        }
    }
    let ma = modes(&htc);
    let log_decrement = |k: usize| {
        let z = ma[k].damping_ratio;
        std::f64::consts::TAU * z / (1.0 - z * z).sqrt()
    };
    eprintln!(
        "log decrements: flap 1 {:.4}, edge 1 {:.4}",
        log_decrement(0),
        log_decrement(1)
    );
    for k in [0, 1] {
        assert!((log_decrement(k) - 0.03).abs() < 0.002, "mode {}", k + 1);
    }
}

/// c2_def's twist is BlTwist with HAWC2's sign (negative toward feather): read at the same
/// span along the pitch axis (c2_def's z, AeroDyn's BlSpn) the two agree within 0.011°.
#[test]
fn c2_def_twist_is_bltwist_turned_to_our_sign() {
    let htc = DiskFile(Path::new(MODEL).join(HTC));
    let files = HtcFiles {
        root: ModelRoot::above_folder_of(&htc),
        htc,
        body: "blade1".into(),
    };
    let blade = files.model().unwrap();
    let twist: Vec<(f64, f64)> = aerodyn_nodes().iter().map(|n| (n.0, n.1)).collect();
    let mut worst: f64 = 0.0;
    for s in &blade.body.c2_def {
        let d = -s.twist_deg.to_radians() - interpolate(&twist, s.z);
        worst = worst.max(d.abs().to_degrees());
    }
    eprintln!("c2_def twist against BlTwist at c2_def's z: within {worst:.5}°");
    assert!(worst < 0.011, "{worst}°");
    assert_eq!(blade.body.c2_def[0].twist_deg, -15.5946);
    let line = flutterscope::physics::blade::source::c2_line(&blade).unwrap();
    let tip = line.points.last().unwrap().0;
    eprintln!("c2_def curved length {tip:.4} m (z to 117.0 m)");
    assert!((tip - 117.18).abs() < 0.01, "{tip}");
    let ours = ChordTwist::from_c2_def(&line);
    assert!((ours.at(0.0) - 15.5946_f64.to_radians()).abs() < 1e-12);
}

/// The prebend from c2_def is AeroDyn's BlCrvAC in sign and axis: the tip 4.0 m upwind
/// (−4.0014 against −3.9987 m). Along the span the half-chord line c2_def follows sits
/// `(½ − a)c sin θ` downwind of the pitch axis BlCrvAC follows (`a` the pitch axis' chord
/// fraction), up to 0.21 m at 23 m (measured 0.2018 m).
#[test]
fn prebend_from_c2_def_is_blcrvac() {
    let p = load("iea15mw-htc", &[]).unwrap();
    let blade = p.aero_blade().unwrap();
    let blcrvac = read_prebend(&DiskFile(PathBuf::from(AERODYN))).unwrap();
    let tip = blade.prebend.last().unwrap();
    let aerodyn_tip = blcrvac.last().unwrap();
    eprintln!(
        "tip prebend: c2_def {:.4} m, BlCrvAC {:.4} m",
        tip.1, aerodyn_tip.1
    );
    assert!(tip.1 < -3.99 && (tip.1 - aerodyn_tip.1).abs() < 0.005);
    let mut worst = (0.0, 0.0);
    for &(s, y) in &blade.prebend {
        let d = y - interpolate(&blcrvac, s);
        if d.abs() > worst.1 {
            worst = (s, d.abs());
        }
    }
    eprintln!(
        "largest c2_def − BlCrvAC: {:.4} m at {:.1} m",
        worst.1, worst.0
    );
    assert!(worst.1 < 0.21, "{worst:?}");
    // The aerodynamic nodes' twist is c2_def's: within 0.07° of the st-file preset's BlTwist
    // at the same ae rows (measured 0.060°), which reads BlTwist at the ae rows' curved length
    // as if it were BlSpn.
    let st = load("iea15mw", &[]).unwrap();
    let worst = blade
        .nodes
        .iter()
        .zip(&st.aero_blade().unwrap().nodes)
        .map(|(a, b)| (a.twist - b.twist).abs().to_degrees())
        .fold(0.0, f64::max);
    eprintln!("aerodynamic nodes' twist: c2_def against BlTwist within {worst:.4}°");
    assert!(worst < 0.07, "{worst}°");
}

/// A copy of the model's folders under a fresh temporary directory.
fn copy_model(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flutterscope-htc-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for folder in ["IEA-15-240-RWT-Onshore/htc", "IEA-15-240-RWT"] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
        for entry in std::fs::read_dir(Path::new(MODEL).join(folder)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(&path, dir.join(folder).join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    dir
}

/// A preset in `dir` naming the htc at `htc` (relative to `dir`) and `extra` blade keys.
fn preset_in(dir: &Path, htc: &str, extra: &str) -> flutterscope::error::Result<ValidPreset> {
    let text =
        format!("[blade]\nsource = \"hawc2\"\nhtc_file = \"{htc}\"\nhub_radius = 3.97\n{extra}\n");
    let path = dir.join("preset.toml");
    std::fs::write(&path, text).unwrap();
    Preset::load(path.to_str().unwrap(), &[])
}

/// A mangled model is refused with the htc file, the line and the block.
#[test]
fn errors_name_the_htc_file_line_and_block() {
    let dir = copy_model("errors");
    let bodies = dir.join(BODIES);
    let text = std::fs::read_to_string(&bodies).unwrap();
    let line = text
        .lines()
        .position(|l| l.trim_start().starts_with("sec    5 "))
        .unwrap()
        + 1;
    let broken = |from: &str, to: &str| {
        std::fs::write(&bodies, text.replacen(from, to, 1)).unwrap();
        let e = preset_in(&dir, HTC, "").unwrap_err().to_string();
        std::fs::write(&bodies, &text).unwrap();
        e
    };
    let e = broken("sec    5    -1.344445e-01", "sec    5    -1.344445e-01x");
    let at = format!(
        "IEA_15MW_RWT_WTG_bodies_noFPM.htc:{line}: in new_htc_structure › main_body blade1 › \
         c2_def: expected 'sec <i> <x> <y> <z> <twist>;'"
    );
    assert!(e.contains(&at), "{e}\n  expected: {at}");
    assert!(e.contains("blade.htc_file"), "{e}");
    let begin = text.find("begin timoschenko_input ;").unwrap();
    let end = begin + text[begin..].find("end timoschenko_input;").unwrap();
    let e = broken(&text[begin..end + "end timoschenko_input;".len()], "");
    assert!(
        e.contains("in new_htc_structure › main_body blade1: expected a 'begin timoschenko_input;' block, found none"),
        "{e}"
    );
    let e = preset_in(&dir, HTC, "htc_body = \"blade9\"")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no main_body named 'blade9'; the bodies there: tower, towertop, connector, shaft, hub1, hub2, hub3, blade1, blade2, blade3"),
        "{e}"
    );
    // blade2 copies blade1 and is the same blade.
    let b2 = preset_in(&dir, HTC, "htc_body = \"blade2\"").unwrap();
    let b1 = preset_in(&dir, HTC, "").unwrap();
    assert_eq!(
        b2.tabulated_blade().unwrap().table,
        b1.tabulated_blade().unwrap().table
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `blade.htc_root` moves the folder the htc's paths resolve against: an htc file kept outside
/// its model reads the model's files through it, and the blade is the one the model's own
/// layout gives; without it the paths resolve above the htc's folder, where nothing is.
#[test]
fn htc_root_overrides_where_the_htc_paths_resolve() {
    let dir = copy_model("root");
    let elsewhere = dir.join("runs/a/case");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::copy(dir.join(HTC), elsewhere.join("main.htc")).unwrap();
    let e = preset_in(&dir, "runs/a/case/main.htc", "")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "main.htc:51: continue_in_file ../IEA-15-240-RWT/IEA_15MW_RWT_WTG_bodies_noFPM.htc"
        ),
        "{e}"
    );
    let moved = preset_in(
        &dir,
        "runs/a/case/main.htc",
        "htc_root = \"IEA-15-240-RWT-Onshore\"",
    )
    .unwrap();
    let own = load("iea15mw-htc", &[]).unwrap();
    assert_eq!(
        moved.tabulated_blade().unwrap().table.sections,
        own.tabulated_blade().unwrap().table.sections
    );
    assert_eq!(
        moved.aero_blade().unwrap().prebend,
        own.aero_blade().unwrap().prebend
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// What the htc gives may not be given again by the keys of an st-file blade: the error names
/// both keys. The ae and pc files the preset names replace the htc's.
#[test]
fn keys_given_both_ways_name_both_keys() {
    for (set, keys) in [
        (
            "blade.file=blades/iea15mw/IEA_15MW_RWT_Blade_st_noFPM.st",
            "blade.file and blade.htc_file",
        ),
        (
            "blade.twist_file=blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
            "blade.twist_file and blade.htc_file",
        ),
        (
            "blade.st_set=2",
            "blade.st_set/blade.st_subset and blade.htc_file",
        ),
        (
            "aero.prebend_file=blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
            "aero.prebend_file and blade.htc_file",
        ),
        ("blade.source=beamdyn", "it needs blade.source = \"hawc2\""),
    ] {
        let e = load("iea15mw-htc", &[set]).unwrap_err().to_string();
        assert!(e.contains(keys), "--set {set}: {e}");
    }
    let e = load("iea15mw", &["blade.htc_body=blade2"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("apply only with blade.htc_file"), "{e}");
    let own = load("iea15mw-htc", &[]).unwrap();
    let given = load(
        "iea15mw-htc",
        &[
            "aero.ae_file=blades/iea15mw/IEA_15MW_RWT_ae.dat",
            "aero.pc_file=blades/iea15mw/IEA_15MW_RWT_pc.dat",
        ],
    )
    .unwrap();
    let (a, b) = (own.aero_blade().unwrap(), given.aero_blade().unwrap());
    assert_eq!(a.prebend, b.prebend);
    assert_eq!(a.nodes.len(), b.nodes.len());
    // Same ae rows and c2_def twist; the 8-profile pc file is another set of polars.
    assert!(a
        .nodes
        .iter()
        .zip(&b.nodes)
        .all(|(x, y)| x.span == y.span && x.twist == y.twist));
    assert!(a
        .nodes
        .iter()
        .zip(&b.nodes)
        .any(|(x, y)| x.polar != y.polar));
}

/// A preset may replace one of the htc's aerodynamic files and keep the other: the 8-profile pc
/// file alone gives the same operating point as naming it with the aero block's own ae file
/// (15824.2 kW against the 3-D corrected polars' 15901.2 kW), and a missing replacement is
/// named by its key, not as the aero block's file.
#[test]
fn one_aerodynamic_file_of_the_htc_can_be_replaced() {
    use flutterscope::model::operating::{steady, unsteadiness};
    let power = |overrides: &[&str]| {
        let p = load("iea15mw-htc", overrides).unwrap();
        steady(&p, unsteadiness(&p)).unwrap().1.flow.power
    };
    let pc = "aero.pc_file=blades/iea15mw/IEA_15MW_RWT_pc.dat";
    let ae = "aero.ae_file=blades/iea15mw-hawc2/IEA-15-240-RWT/IEA_15MW_RWT_ae.dat";
    let (alone, both, own) = (power(&[pc]), power(&[pc, ae]), power(&[]));
    assert_eq!(alone, both);
    assert!((own / alone - 1.0).abs() > 1e-3, "{own} against {alone}");
    let e = load("iea15mw-htc", &["aero.pc_file=no-such.pc"])
        .and_then(|p| steady(&p, unsteadiness(&p)).map(|_| ()))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("aero.pc_file = \"no-such.pc\"") && e.contains("no-such.pc: cannot read"),
        "{e}"
    );
    assert!(!e.contains("in aero: ae_filename"), "{e}");
}
