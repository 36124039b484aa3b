//! A blade built from its WindIO layup (docs/model.md §11.12): the IEA 15MW's sections against
//! its BeamDyn file (current ontology) and its HAWC2 st files (2019 ontology, baseline and 8°
//! bend–twist coupled), its modes against the tabulated blade's, the ply angle's sign and what a
//! new ply angle analyses again.

use flutterscope::formats::text_file::DiskFile;
use flutterscope::physics::blade::source::{read_beamdyn, read_hawc2, read_twist, TabulatedBlade};
use flutterscope::physics::blade::windio::LayupBlade;
use flutterscope::physics::blade::BladeTable;
use flutterscope::preset::{Preset, ValidPreset};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn presets_file(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets")
        .join(rel)
}

const OLD_YAML: &str = "presets/blades/iea15mw-windio-2019/IEA-15-240-RWT_2019.yaml";

fn preset(name: &str, set: &[&str]) -> ValidPreset {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    Preset::load(name, &set).unwrap_or_else(|e| panic!("{e}"))
}

fn layup_table(p: &ValidPreset) -> BladeTable {
    p.tabulated_blade().unwrap().table.clone()
}

fn hawc2_st(rel: &str) -> TabulatedBlade {
    let twist = read_twist(&DiskFile(presets_file(
        "blades/iea15mw/IEA-15-240-RWT_AeroDyn15_blade.dat",
    )))
    .unwrap();
    read_hawc2(&DiskFile(presets_file(rel)), &twist, 1, 1).unwrap()
}

/// The IEA 15MW BeamDyn-file blade.
fn beamdyn_blade() -> TabulatedBlade {
    read_beamdyn(&DiskFile(presets_file(
        "blades/iea15mw/IEA-15-240-RWT_BeamDyn.dat",
    )))
    .unwrap()
}

/// Per property, the worst `ours/reference − 1` over the reference's stations within `span`
/// (fractions), compared at the same fraction of each blade's length.
fn worst(ours: &BladeTable, reference: &BladeTable, span: (f64, f64)) -> [f64; 5] {
    let (lo, lr) = (ours.length(), reference.length());
    let mut w = [0.0f64; 5];
    for r in &reference.sections {
        let eta = r.z / lr;
        if eta < span.0 - 1e-9 || eta > span.1 + 1e-9 {
            continue;
        }
        let o = ours.at(eta * lo);
        let d = [
            o.mass / r.mass - 1.0,
            o.ei_flap / r.ei_flap - 1.0,
            o.ei_edge / r.ei_edge - 1.0,
            o.gj / r.gj - 1.0,
            0.0,
        ];
        eprintln!(
            "  η {eta:.3}: mass {:+.3} EI_flap {:+.3} EI_edge {:+.3} GJ {:+.3}",
            d[0], d[1], d[2], d[3]
        );
        for k in 0..4 {
            if d[k].abs() > w[k].abs() {
                w[k] = d[k];
            }
        }
    }
    w
}

/// The 2019 ontology against the baseline HAWC2 st file of the same commit, where the design is
/// the same (docs/model.md §11.12 tabulates every station): mass, bending and, to 80 % span,
/// torsion within the tolerances; outboard of it the file's torsion is 16–26 % below
/// the layup's, a difference no meshing choice explains (measured).
#[test]
fn the_2019_layup_gives_the_baseline_st_files_sections() {
    let ours = layup_table(&preset(
        "iea15mw-windio",
        &[&format!("blade.file={OLD_YAML}")],
    ));
    let st = hawc2_st("blades/iea15mw-windio-2019/IEA_15MW_RWT_Blade_st_2019.dat");
    let w = worst(&ours, &st.table, (0.1, 0.95));
    eprintln!("2019 worst over 0.1–0.95: {w:+.3?}");
    assert!(w[0].abs() < 0.03, "mass {w:?}");
    assert!(w[1].abs() < 0.05 && w[2].abs() < 0.08, "bending {w:?}");
    let inboard = worst(&ours, &st.table, (0.1, 0.8));
    assert!(inboard[3].abs() < 0.10, "torsion to 80 % {inboard:?}");
}

/// The current ontology as it stands against the IEA 15MW BeamDyn file: within these bounds,
/// measured. Outboard the file's section code filled the trailing edge with glass the ontology
/// does not describe (docs/model.md §11.12; with that fill, the test below).
#[test]
fn the_current_layup_is_close_to_the_beamdyn_file() {
    let ours = layup_table(&preset("iea15mw-windio", &[]));
    let bd = beamdyn_blade();
    let w = worst(&ours, &bd.table, (0.1, 0.95));
    eprintln!("current worst over 0.1–0.95: {w:+.3?}");
    assert!(w[0].abs() < 0.12 && w[1].abs() < 0.10, "{w:?}");
    assert!(w[2].abs() < 0.45 && w[3].abs() < 0.20, "{w:?}");
    let inboard = worst(&ours, &bd.table, (0.1, 0.6));
    assert!(
        inboard[0].abs() < 0.05 && inboard[3].abs() < 0.10,
        "{inboard:?}"
    );
}

/// The 8° turn on the 2019 ontology against the BTC8deg st file: the bend–twist coupling over
/// √(EI_flap·GJ) along r/R 0.6–0.95, same sign and within 20 % where it exceeds 0.05.
#[test]
fn the_8_degree_turn_gives_the_btc_files_coupling() {
    let ours = layup_table(&preset("iea15mw-btc", &[&format!("blade.file={OLD_YAML}")]));
    let btc = hawc2_st("blades/iea15mw-windio-2019/IEA_15MW_RWT_BTC8deg_Blade_st_2019.dat");
    let (lo, lr) = (ours.length(), btc.table.length());
    let mut compared = 0;
    for r in &btc.table.sections {
        let eta = r.z / lr;
        if !(0.6..=0.95).contains(&eta) {
            continue;
        }
        let o = ours.at(eta * lo);
        let ratio = |s: &flutterscope::physics::blade::BeamSection| {
            s.flap_twist / (s.ei_flap * s.gj).sqrt()
        };
        let (a, b) = (ratio(&o), ratio(r));
        eprintln!("η {eta:.3}: coupling ratio layup {a:+.4}, BTC8deg {b:+.4}");
        if b.abs() > 0.05 {
            assert!(
                a.signum() == b.signum() && (a / b - 1.0).abs() < 0.2,
                "η {eta}: {a} vs {b}"
            );
            compared += 1;
        }
    }
    assert!(compared >= 4, "{compared} stations compared");
}

/// The modes of preset `name` with `set`, as `modes --json --shapes` reports them.
fn modes_json(name: &str, set: &[&str]) -> Vec<serde_json::Value> {
    let mut args = vec!["modes", "--preset", name, "--json", "--shapes"];
    for s in set {
        args.extend(["--set", s]);
    }
    let out = crate::flutterscope_ok(&args);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["modes"].as_array().unwrap().clone()
}

/// Each natural mode's name and frequency (Hz) of preset `name`, without aerodynamics.
fn frequencies(name: &str) -> Vec<(String, f64)> {
    modes_json(name, &["aero.model=none"])
        .iter()
        .map(|m| {
            (
                m["label"].as_str().unwrap().to_string(),
                m["frequency_hz"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// The first flap mode's tip twist per metre of tip flap (toward feather), curvature left out
/// so that only the sections' coupling twists it.
fn tip_twist(name: &str, set: &[&str]) -> f64 {
    let mut set = set.to_vec();
    set.push("structure.curved=false");
    let m = modes_json(name, &set);
    m[0]["shape"]["twist"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .as_f64()
        .unwrap()
}

/// A positive ply angle turns the spar caps' fibres toward the leading edge: downwind bending
/// then twists the blade toward feather, and 8° over r/R 0.6–1.0 gives the BTC8deg blade's twist
/// within 20 %.
#[test]
fn a_positive_ply_angle_twists_toward_feather_as_the_btc_blade() {
    let base = tip_twist("iea15mw-windio", &[]);
    let plus = tip_twist("iea15mw-windio", &["section.ply_angle=8"]);
    let minus = tip_twist("iea15mw-windio", &["section.ply_angle=-8"]);
    let st = tip_twist("iea15mw-btc-st2019", &[]);
    eprintln!("tip twist per m of flap: −8° {minus:.5}, ontology {base:.5}, +8° {plus:.5}, BTC8deg st {st:.5}");
    assert!(plus > base && base > minus, "{minus} {base} {plus}");
    assert!((plus / st - 1.0).abs() < 0.2, "{plus} vs {st}");
}

/// A new ply angle analyses only the stations it turns: the others are the held blade's.
#[test]
fn a_new_ply_angle_analyses_only_the_turned_stations() {
    let p = preset("iea15mw-btc", &[]);
    let q = p.with("section.ply_angle", 4.0).unwrap();
    let layup = |p: &ValidPreset| -> Arc<LayupBlade> {
        p.tabulated_blade().unwrap().layup.clone().unwrap()
    };
    let (a, b) = (layup(&p), layup(&q));
    assert!(Arc::ptr_eq(&a.windio, &b.windio));
    for (x, y) in a.sections.iter().zip(&b.sections) {
        let turned = (0.6..=1.0).contains(&x.eta);
        assert_eq!(Arc::ptr_eq(x, y), !turned, "η {}", x.eta);
        assert_eq!(x.matrices == y.matrices, !turned, "η {}", x.eta);
    }
}

/// A turned station keeps its mesh and its factorisation's pattern: its section is the one a
/// new mesh of the turned layup gives, to round-off.
#[test]
fn a_turned_station_is_the_section_of_its_turned_layup_meshed_anew() {
    use flutterscope::physics::blade::windio::{layup_section, PlyTurn};
    let p = preset("iea15mw-btc", &[]);
    let q = p.with("section.ply_angle", -5.0).unwrap();
    let turned = q.tabulated_blade().unwrap().layup.clone().unwrap();
    let turn = turned.turn.clone().unwrap();
    assert_eq!(
        turn,
        PlyTurn {
            angle: (-5.0f64).to_radians(),
            ..turn.clone()
        }
    );
    let mut compared = 0;
    for s in turned.sections.iter().filter(|s| turn.acts_at(s.eta)) {
        let fresh = layup_section(&turned.windio, s.eta, Some(&turn), None, None).unwrap();
        assert_eq!(fresh.mesh.mesh, s.mesh.mesh, "η {}", s.eta);
        let scale = fresh.matrices.stiffness[2][2];
        for (a, b) in fresh
            .matrices
            .stiffness
            .iter()
            .flatten()
            .zip(s.matrices.stiffness.iter().flatten())
        {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "η {}: {a} against {b}",
                s.eta
            );
        }
        compared += 1;
    }
    assert!(compared > 10, "{compared} turned stations");
}

/// The first 8 modes of the layup blade against the IEA 15MW st-file blade (the BeamDyn file's
/// data): bending within 3 %; the first torsion mode 5.3 % low, as the layup's outboard GJ is.
#[test]
fn the_layup_blades_modes_are_the_tabulated_blades() {
    let (ours, file) = (frequencies("iea15mw-windio"), frequencies("iea15mw"));
    for ((name, f), (file_name, g)) in ours.iter().zip(&file).take(8) {
        eprintln!(
            "{name:<10} {f:.4} Hz, file {file_name:<10} {g:.4} Hz, {:+.2} %",
            100.0 * (f / g - 1.0)
        );
        assert_eq!(name, file_name);
        let tolerance = if name.starts_with("torsion") {
            0.06
        } else {
            0.03
        };
        assert!((f / g - 1.0).abs() < tolerance, "{name}: {f} vs {g}");
    }
}

/// A user's preset on the shipped WindIO file (`{yaml}`, as [`own_preset_error`] fills it in), in
/// still air, up to its `[section]` table.
const WINDIO_SECTION: &str =
    "[blade]\nsource = \"windio\"\nfile = \"{yaml}\"\n[aero]\nmodel = \"none\"\n[section]\n";

/// The error of the user's own preset file `text` (its WindIO file given by `{yaml}`).
fn own_preset_error(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("flutterscope-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.toml"));
    let yaml = presets_file("blades/iea15mw-windio/IEA-15-240-RWT.yaml");
    std::fs::write(&file, text.replace("{yaml}", &yaml.display().to_string())).unwrap();
    let e = Preset::load(file.to_str().unwrap(), &[])
        .unwrap_err()
        .to_string();
    std::fs::remove_dir_all(&dir).unwrap();
    e
}

/// What a user can get wrong about the turn is an error that names the key.
#[test]
fn bad_turns_are_errors_naming_the_key() {
    let e = own_preset_error(
        "layers",
        &format!("{WINDIO_SECTION}ply_angle = 5.0\nrotate_layers = [\"Spar_Cap\"]\n"),
    );
    assert!(
        e.contains("section.rotate_layers") && e.contains("Spar_Cap_SS"),
        "{e}"
    );
    let e = own_preset_error(
        "span",
        &format!("{WINDIO_SECTION}rotate_span = [0.8, 0.2]\n"),
    );
    assert!(
        e.contains("section.rotate_span") && e.contains("0 ≤ from ≤ to ≤ 1"),
        "{e}"
    );
    let e = own_preset_error(
        "beamdyn",
        "[blade]\nsource = \"beamdyn\"\nfile = \"{yaml}\"\n[section]\nrotate_span = [0.6, 1.0]\n",
    );
    assert!(e.contains("WindIO") && e.contains("beamdyn"), "{e}");
    let set = vec!["section.ply_angle=-10".to_string()];
    let e = Preset::load("liu2017", &set).unwrap_err().to_string();
    assert!(
        e.contains("section.ply_angle") && e.contains("[0, 90]"),
        "{e}"
    );
}

/// EA (the 6×6's `K₃₃`) of the layup's sections at each reference station within r/R 0.1–0.95,
/// against the reference's own: the worst `ours/reference − 1`.
fn worst_axial(yaml: &str, reference: &[(f64, f64)]) -> f64 {
    use flutterscope::physics::blade::windio::layup_section;
    let w = flutterscope::formats::windio::read(&presets_file(yaml)).unwrap();
    reference
        .iter()
        .filter(|(eta, _)| (0.1 - 1e-9..=0.95 + 1e-9).contains(eta))
        .map(|&(eta, ea)| {
            let ours = layup_section(&w, eta, None, None, None).unwrap();
            let d = ours.matrices.stiffness[2][2] / ea - 1.0;
            eprintln!("  η {eta:.3}: EA {d:+.4}");
            d
        })
        .fold(0.0, |w: f64, d| if d.abs() > w.abs() { d } else { w })
}

/// The axial stiffness: on the 2019 ontology within 0.6 % of its st file at every station (the
/// same design, and the closest check of the section analysis against the file's section code);
/// on the current one, as it stands, within 8.4 % of the BeamDyn file's.
#[test]
fn the_layups_axial_stiffness_is_the_files() {
    use flutterscope::formats::beamdyn::read_blade;
    use flutterscope::formats::hawc2_st::{read_st, StRows};
    let st = read_st(&presets_file(
        "blades/iea15mw-windio-2019/IEA_15MW_RWT_Blade_st_2019.dat",
    ))
    .unwrap();
    let rows: Vec<(f64, f64)> = match &st.subset(1, 1).unwrap().rows {
        StRows::Classic(rows) => rows.iter().map(|r| (r.r, r.e * r.a)).collect(),
        StRows::FullyPopulated(rows) => rows.iter().map(|r| (r.r, r.stiffness()[2][2])).collect(),
    };
    let length = rows.last().unwrap().0;
    let by_eta: Vec<(f64, f64)> = rows.iter().map(|&(r, ea)| (r / length, ea)).collect();
    let old = worst_axial(OLD_YAML.trim_start_matches("presets/"), &by_eta);
    assert!(old.abs() < 0.006, "2019: {old:+.4}");
    let bd = read_blade(&presets_file(
        "blades/iea15mw/IEA-15-240-RWT_BeamDyn_blade.dat",
    ))
    .unwrap();
    let by_eta: Vec<(f64, f64)> = bd
        .stations
        .iter()
        .map(|s| (s.eta, s.stiffness[2][2]))
        .collect();
    let current = worst_axial("blades/iea15mw-windio/IEA-15-240-RWT.yaml", &by_eta);
    assert!(current.abs() < 0.09, "current: {current:+.4}");
}

/// A preset file in a scratch folder: the built-in `name` with its files named by absolute path,
/// the lines starting with any of `drop` left out and each `(from, to)` of `replace` made once.
fn edited_preset(name: &str, drop: &[&str], replace: &[(&str, &str)]) -> String {
    let text = std::fs::read_to_string(presets_file(&format!("{name}.toml"))).unwrap();
    let blades = presets_file("blades");
    let mut out = String::new();
    for line in text.lines() {
        if drop.iter().any(|d| line.starts_with(d)) {
            continue;
        }
        out += &line.replace("\"blades/", &format!("\"{}/", blades.display()));
        out += "\n";
    }
    for (from, to) in replace {
        assert!(out.contains(from), "{name}.toml has no {from:?}");
        out = out.replacen(from, to, 1);
    }
    let dir = std::env::temp_dir().join(format!("flutterscope-layup-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}-{}.toml", out.len()));
    std::fs::write(&file, out).unwrap();
    file.display().to_string()
}

/// The IEA 15MW WindIO blade with the trailing edge its BeamDyn file's section code closed:
/// glass_uni over the last 0.207 m of the chord from r/R 0.5 to where the webs end (docs/model.md
/// §11.12, measured from that code's section drawings).
fn with_the_beamdyn_files_trailing_edge() -> String {
    edited_preset(
        "iea15mw-windio",
        &[],
        &[(
            "[section]\n",
            "[section]\ntrailing_edge_fill = \"glass_uni\"\ntrailing_edge_fill_length = 0.207\n\
             trailing_edge_fill_span = [0.5, 0.975]\n",
        )],
    )
}

/// With the trailing edge filled as the BeamDyn file's section code filled it, the current
/// ontology gives the file's sections: from r/R 0.8 mass within 1.4 %, edge stiffness within
/// 5.3 %, torsion within 1.0 % (without the fill: −10.5 %, −41 %, −20 %); over r/R 0.1–0.95
/// torsion within 7.9 % and mass within 4.3 %.
#[test]
fn the_layup_with_the_section_codes_trailing_edge_gives_the_beamdyn_file() {
    let ours = layup_table(&preset(&with_the_beamdyn_files_trailing_edge(), &[]));
    let bd = beamdyn_blade();
    let w = worst(&ours, &bd.table, (0.1, 0.95));
    eprintln!("with the fill, worst over 0.1–0.95: {w:+.3?}");
    assert!(w[0].abs() < 0.05 && w[3].abs() < 0.10, "{w:?}");
    assert!(w[1].abs() < 0.10 && w[2].abs() < 0.11, "{w:?}");
    let outboard = worst(&ours, &bd.table, (0.8, 0.95));
    eprintln!("with the fill, worst over 0.8–0.95: {outboard:+.3?}");
    assert!(
        outboard[0].abs() < 0.02 && outboard[2].abs() < 0.07 && outboard[3].abs() < 0.02,
        "{outboard:?}"
    );
}

/// With the same trailing edge the first 8 modes are the BeamDyn-file blade's within 3.2 %
/// (edge 1 −3.1 %, the rest within 2.9 %).
#[test]
fn with_the_section_codes_trailing_edge_the_modes_are_the_beamdyn_blades() {
    // The st-file preset on the BeamDyn file instead: no twist file, no HAWC2 aerodynamics.
    let bd = edited_preset(
        "iea15mw",
        &["twist_file", "ae_file", "ae_set", "pc_file"],
        &[
            ("source = \"hawc2\"", "source = \"beamdyn\""),
            (
                "IEA_15MW_RWT_Blade_st_noFPM.st",
                "IEA-15-240-RWT_BeamDyn.dat",
            ),
        ],
    );
    let ours = frequencies(&with_the_beamdyn_files_trailing_edge());
    let file = frequencies(&bd);
    let mut beyond = 0;
    for ((name, f), (file_name, g)) in ours.iter().zip(&file).take(8) {
        let d = f / g - 1.0;
        eprintln!(
            "{name:<10} {f:.4} Hz, BeamDyn file {file_name:<10} {g:.4} Hz, {:+.2} %",
            100.0 * d
        );
        assert_eq!(name, file_name);
        assert!(d.abs() < 0.032, "{name}: {f} vs {g}");
        beyond += usize::from(d.abs() >= 0.03);
    }
    assert!(beyond <= 1, "{beyond} modes beyond 3 %");
}

/// What a user can get wrong about the trailing-edge fill is an error that names the key.
#[test]
fn bad_fills_are_errors_naming_the_key() {
    let e = own_preset_error(
        "fill-material",
        &format!("{WINDIO_SECTION}trailing_edge_fill = \"glue\"\n"),
    );
    assert!(
        e.contains("section.trailing_edge_fill") && e.contains("glass_uni"),
        "{e}"
    );
    let e = own_preset_error(
        "fill-length",
        &format!(
            "{WINDIO_SECTION}trailing_edge_fill = \"adhesive\"\n\
             trailing_edge_fill_length = 30.0\n"
        ),
    );
    assert!(
        e.contains("section.trailing_edge_fill_length") && e.contains("leading edge"),
        "{e}"
    );
    let e = own_preset_error(
        "fill-negative",
        &format!("{WINDIO_SECTION}trailing_edge_fill_length = -1.0\n"),
    );
    assert!(
        e.contains("section.trailing_edge_fill_length") && e.contains("allowed"),
        "{e}"
    );
    let e = own_preset_error(
        "fill-beamdyn",
        "[blade]\nsource = \"beamdyn\"\nfile = \"{yaml}\"\n[section]\ntrailing_edge_fill = \"adhesive\"\n",
    );
    assert!(e.contains("WindIO") && e.contains("beamdyn"), "{e}");
}

/// A fill over the whole span: every station meshes (round roots, open flatback edges and
/// sharp tips alike) and gains mass, but where the fill's stacks pair the skins farther
/// forward than the skins alone do, whose layers then run across the gap (two stations, 0.26 %
/// and 0.09 % lighter).
#[test]
fn a_fill_over_the_whole_blade_meshes_every_station() {
    let plain = layup_table(&preset("iea15mw-windio", &[]));
    let filled = layup_table(&preset(
        "iea15mw-windio",
        &["section.trailing_edge_fill=adhesive"],
    ));
    let mut heavier = 0;
    for (a, b) in plain.sections.iter().zip(&filled.sections) {
        let gain = b.mass / a.mass - 1.0;
        eprintln!("z {:.2}: mass {gain:+.5}", a.z);
        assert!(gain > -0.003, "z {}: {} against {}", a.z, b.mass, a.mass);
        heavier += usize::from(gain > 1e-6);
    }
    assert!(heavier >= 40, "{heavier} of {}", plain.sections.len());
}
