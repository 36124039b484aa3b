//! Blade definition file readers (`formats`): each reader on the project's copies of the real
//! NREL 5MW and IEA 15MW files (values read off the files by eye), then on hostile input made
//! from them — empty, truncated at every line, a number replaced by text, a row missing, binary
//! junk — and `read_text` on devices, FIFOs, directories and oversized files.

use flutterscope::error::{Error, Result};
use flutterscope::formats::airfoil::{AirfoilFile, PolarColumns};
use flutterscope::formats::hawc2_st::{StFile, StRows};
use flutterscope::formats::text::{read_text, MAX_FILE_BYTES};
use flutterscope::formats::{
    aerodyn, airfoil, beamdyn, elastodyn, elastodyn_tower, elastodyn_turbine, hawc2_aero, hawc2_st,
};
use flutterscope::preset::Preset;
use std::path::{Path, PathBuf};

const BD_PRIMARY: &str = "nrel5mw/NRELOffshrBsline5MW_BeamDyn.dat";
const BD_BLADE: &str = "nrel5mw/NRELOffshrBsline5MW_BeamDyn_Blade.dat";
const ED_BLADE: &str = "nrel5mw/NRELOffshrBsline5MW_Blade.dat";
const AD_BLADE: &str = "nrel5mw/NRELOffshrBsline5MW_AeroDyn_blade.dat";
const DU21: &str = "nrel5mw/Airfoils/DU21_A17.dat";
const ST_CLASSIC: &str = "iea15mw/IEA_15MW_RWT_Blade_st_noFPM.st";
const ST_FPM: &str = "iea15mw/IEA_15MW_RWT_Blade_st_FPM.st";
const ST_BTC: &str = "iea15mw/IEA_15MW_RWT_BTC8deg_Blade_st.dat";
const AE: &str = "iea15mw/IEA_15MW_RWT_ae.dat";
const PC: &str = "iea15mw/IEA_15MW_RWT_pc.dat";
const OPT: &str = "iea15mw/IEA_15MW_RWT_Onshore.opt";
const ED_MAIN: &str = "nrel5mw-turbine/onshore/ElastoDyn.dat";
const ED_TOWER: &str =
    "nrel5mw-turbine/5MW_Baseline/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat";
const IEA_ED_MAIN: &str =
    "iea15mw-monopile/IEA-15-240-RWT-Monopile/IEA-15-240-RWT-Monopile_ElastoDyn.dat";

fn blades(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("presets/blades")
        .join(rel)
}

fn text(rel: &str) -> String {
    std::fs::read_to_string(blades(rel)).unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flutterscope-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

// ---- the real files ----

#[test]
fn beamdyn_primary_nrel5mw() {
    let path = blades(BD_PRIMARY);
    let p = beamdyn::read_primary(&path).unwrap();
    assert_eq!(p.kp_total, 49);
    assert_eq!(p.members.len(), 1);
    let kps = &p.members[0];
    assert_eq!(kps.len(), 49);
    assert_eq!((kps[0].kp_zr, kps[0].initial_twist_deg), (0.0, 13.308));
    assert_eq!((kps[2].kp_zr, kps[2].initial_twist_deg), (1.199865, 13.308));
    assert_eq!((kps[48].kp_zr, kps[48].initial_twist_deg), (61.5, 0.0));
    assert_eq!(p.blade_file, "NRELOffshrBsline5MW_BeamDyn_Blade.dat");
    // The copy keeps the primary file's relative name working.
    assert_eq!(p.blade_file_path(&path), blades(BD_BLADE));
    assert!(p.blade_file_path(&path).is_file());
}

#[test]
fn beamdyn_blade_nrel5mw() {
    let b = beamdyn::read_blade(&blades(BD_BLADE)).unwrap();
    assert_eq!(b.stations.len(), 49);
    assert_eq!(b.damp_type, 1);
    assert_eq!(b.mu, [1e-3, 1e-3, 1e-3, 0.0014, 0.0022, 0.0022]);
    let (root, tip) = (&b.stations[0], &b.stations[48]);
    assert_eq!((root.eta, b.stations[1].eta, tip.eta), (0.0, 0.00325, 1.0));
    assert_eq!(root.stiffness[0][0], 9.729480e8);
    assert_eq!(root.stiffness[3][3], 1.811360e10);
    assert_eq!(root.stiffness[5][5], 5.564400e9);
    assert_eq!(root.mass[3][3], 9.730400e2);
    assert_eq!(tip.stiffness[3][3], 5.01e6);
    assert_eq!(tip.stiffness[4][4], 1.7e5);
    assert_eq!(tip.mass[5][5], 0.7);
}

#[test]
fn elastodyn_blade_nrel5mw() {
    let b = elastodyn::read_blade(&blades(ED_BLADE)).unwrap();
    assert_eq!(b.stations.len(), 49);
    let a = b.adjustment;
    assert_eq!(
        (a.mass, a.flap_stiffness, a.edge_stiffness),
        (1.04536, 1.0, 1.0)
    );
    let d = b.damping.unwrap();
    assert_eq!(
        (d.flap_1_pct, d.flap_2_pct, d.edge_1_pct),
        (0.477465, 0.477465, 0.477465)
    );
    let (root, tip) = (&b.stations[0], &b.stations[48]);
    assert_eq!(
        (root.bl_fract, root.pitch_axis, root.strc_twst_deg),
        (0.0, 0.25, 13.308)
    );
    assert_eq!(
        (root.b_mass_den, root.flp_stff, root.edg_stff),
        (678.935, 1.811e10, 1.81136e10)
    );
    assert_eq!(
        (tip.bl_fract, tip.b_mass_den, tip.flp_stff, tip.edg_stff),
        (1.0, 10.319, 1.7e5, 5.01e6)
    );
}

/// The NREL 5MW onshore ElastoDyn main file, and the tower file its `TwrFile` names relative
/// to itself (`../5MW_Baseline/…`), read from the main file's folder.
#[test]
fn elastodyn_turbine_and_tower_nrel5mw() {
    let t = elastodyn_turbine::read_turbine(&blades(ED_MAIN)).unwrap();
    assert_eq!((t.blades, t.tip_radius, t.hub_radius), (3, 63.0, 1.5));
    assert_eq!(t.precone_deg, vec![-2.5; 3]);
    assert_eq!(
        (t.hub_cm, t.overhang, t.shaft_tilt_deg, t.tower_to_shaft),
        (0.0, -5.0191, -5.0, 1.96256)
    );
    assert_eq!(t.nacelle_cm, [1.9, 0.0, 1.75]);
    assert_eq!((t.tower_height, t.tower_base_height), (87.6, 0.0));
    assert_eq!(
        (t.hub_mass, t.hub_inertia, t.generator_inertia),
        (56780.0, 115926.0, 534.116)
    );
    assert_eq!(
        (t.nacelle_mass, t.nacelle_yaw_inertia, t.yaw_bearing_mass),
        (240000.0, 2.60789e6, 0.0)
    );
    assert_eq!((t.gearbox_efficiency_pct, t.gearbox_ratio), (100.0, 97.0));
    assert_eq!(
        (t.drivetrain_stiffness, t.drivetrain_damping),
        (8.67637e8, 6.215e6)
    );
    assert!(t.drivetrain_dof && t.generator_dof);

    let tower_path = t.tower_file_path(&blades(ED_MAIN));
    assert_eq!(
        tower_path,
        blades("nrel5mw-turbine/onshore")
            .join("../5MW_Baseline/NRELOffshrBsline5MW_Onshore_ElastoDyn_Tower.dat")
    );
    let w = elastodyn_tower::read_tower(&tower_path).unwrap();
    assert_eq!(w, elastodyn_tower::read_tower(&blades(ED_TOWER)).unwrap());
    assert_eq!(w.stations.len(), 11);
    assert_eq!(
        (w.fore_aft_damping_pct, w.side_side_damping_pct),
        ([1.0; 2], [1.0; 2])
    );
    assert_eq!(
        (w.fore_aft_tuners, w.side_side_tuners),
        ([1.0; 2], [1.0; 2])
    );
    assert_eq!(
        (w.mass_factor, w.fore_aft_factor, w.side_side_factor),
        (1.0, 1.0, 1.0)
    );
    let (base, top) = (&w.stations[0], &w.stations[10]);
    assert_eq!(
        (
            base.height_fraction,
            base.mass_density,
            base.fore_aft_stiffness,
            base.side_side_stiffness
        ),
        (0.0, 5590.87, 6.14343e11, 6.14343e11)
    );
    assert_eq!(
        (
            top.height_fraction,
            top.mass_density,
            top.fore_aft_stiffness
        ),
        (1.0, 2536.27, 1.1582e11)
    );
    assert_eq!(
        w.fore_aft_shapes[0],
        [0.7004, 2.1963, -5.6202, 6.2275, -2.504]
    );
    assert_eq!(
        w.side_side_shapes[1],
        [-121.21, 184.415, -224.904, 298.536, -135.838]
    );
}

/// The IEA 15MW monopile's main file: a direct drive (gearbox ratio 1) whose tower starts at
/// the transition piece, 15 m up; its `TwrFile` names its own folder by `../`.
#[test]
fn elastodyn_turbine_and_tower_iea15mw_monopile() {
    let t = elastodyn_turbine::read_turbine(&blades(IEA_ED_MAIN)).unwrap();
    assert_eq!((t.blades, t.tip_radius, t.hub_radius), (3, 120.97, 3.97));
    assert_eq!(t.precone_deg, vec![-4.0; 3]);
    assert_eq!((t.tower_height, t.tower_base_height), (144.386, 15.0));
    assert_eq!((t.gearbox_ratio, t.generator_inertia), (1.0, 1836784.0));
    assert_eq!(
        (t.hub_mass, t.nacelle_mass, t.yaw_bearing_mass),
        (69131.0, 644857.0, 28249.0)
    );
    assert_eq!(
        (t.drivetrain_stiffness, t.drivetrain_damping),
        (69737644900.0, 49418406.0)
    );
    let w = elastodyn_tower::read_tower(&t.tower_file_path(&blades(IEA_ED_MAIN))).unwrap();
    assert_eq!(w.stations.len(), 20);
    assert_eq!(w.stations[0].mass_density, 1.031_484_441_173_36e4);
}

/// The main file's errors name the file, the line and the key: a missing quantity is an error
/// (never a default), as is a value no turbine can have.
#[test]
fn elastodyn_turbine_errors_name_the_line_and_key() {
    let main = text(ED_MAIN);
    let line_of = |key: &str| {
        main.lines()
            .position(|l| l.split_whitespace().nth(1) == Some(key))
            .unwrap()
            + 1
    };
    let with = |key: &str, value: &str| {
        main.lines()
            .map(|l| {
                if l.split_whitespace().nth(1) == Some(key) {
                    format!("{value}   {key}   - edited")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let parse = |t: &str| elastodyn_turbine::parse_turbine(t, "ed.dat").unwrap_err();
    let without: String = main
        .lines()
        .filter(|l| l.split_whitespace().nth(1) != Some("HubIner"))
        .collect::<Vec<_>>()
        .join("\n");
    assert_format(
        &parse(&without),
        "ed.dat",
        0,
        "expected a line '<value>  HubIner'",
    );
    for (key, value, says) in [
        (
            "NacMass",
            "-240000",
            "NacMass is -240000: it must be at least 0",
        ),
        ("DTTorSpr", "0", "DTTorSpr is 0: it must be greater than 0"),
        (
            "GBRatio",
            "abc",
            "expected a number for GBRatio, found 'abc'",
        ),
        ("NumBl", "4", "NumBl is 4: ElastoDyn models 1 to 3 blades"),
        (
            "ShftTilt",
            "95",
            "ShftTilt is 95°: it must lie strictly between -90° and 90°",
        ),
        (
            "TowerBsHt",
            "90",
            "TowerBsHt (90 m) must be below TowerHt (87.6 m)",
        ),
        (
            "HubRad",
            "70",
            "HubRad (70 m) must be less than TipRad (63 m)",
        ),
        ("GBoxEff", "0", "GBoxEff is 0 %: it must lie in (0, 100] %"),
        (
            "GenDOF",
            "maybe",
            "expected True or False for GenDOF, found 'maybe'",
        ),
    ] {
        assert_format(&parse(&with(key, value)), "ed.dat", line_of(key), says);
    }
    // Every whole-line prefix fails where the file is cut, or reads the whole file's values.
    let full = elastodyn_turbine::parse_turbine(&main, "ed.dat").unwrap();
    for k in 0..main.lines().count() {
        let prefix = main.lines().take(k).collect::<Vec<_>>().join("\n");
        match elastodyn_turbine::parse_turbine(&prefix, "ed.dat") {
            Ok(t) => assert_eq!(t, full, "{k} lines"),
            Err(e) => assert_located(&e, "ed.dat", &prefix),
        }
    }
}

/// The tower file's errors: a mode shape that is not 1 at the tower top, a table that does not
/// run from the base to the top, a stiffness of zero.
#[test]
fn elastodyn_tower_errors_name_the_line() {
    let tower = text(ED_TOWER);
    let parse = |t: String| elastodyn_tower::parse_tower(&t, "tower.dat").unwrap_err();
    let e = parse(tower.replace("     2.1963   TwFAM1Sh(3)", "     2.2963   TwFAM1Sh(3)"));
    assert_format(&e, "tower.dat", 36, "TwFAM1Sh(2) … TwFAM1Sh(6) sum to 1.1");
    let e = parse(tower.replace(
        "1.0000000E+00  2.5362700E+03",
        "9.5000000E-01  2.5362700E+03",
    ));
    assert_format(&e, "tower.dat", 30, "HtFract of the last station is 0.95");
    let e = parse(tower.replace(
        "5.0000000E-01  3.9164100E+03  2.9101100E+11",
        "5.0000000E-01  3.9164100E+03  0.0",
    ));
    assert_format(
        &e,
        "tower.dat",
        25,
        "TwFAStif is 0: it must be greater than 0",
    );
    let e = parse(tower.replace("          1   AdjFASt", "         -1   AdjFASt"));
    assert_format(
        &e,
        "tower.dat",
        15,
        "AdjFASt is -1: it must be greater than 0",
    );
}

#[test]
fn aerodyn_blade_nrel5mw() {
    let b = aerodyn::read_blade(&blades(AD_BLADE)).unwrap();
    // NumBlNds 19: the 20th row after the "!bjj" comment is not part of the table.
    assert_eq!(b.nodes.len(), 19);
    let n = &b.nodes[1];
    assert_eq!(
        (n.bl_spn, n.bl_crv_ac, n.bl_swp_ac),
        (1.3667, -8.1531745e-4, -3.4468858e-3)
    );
    assert_eq!((n.bl_twist_deg, n.bl_chord, n.bl_af_id), (13.308, 3.542, 1));
    let tip = &b.nodes[18];
    assert_eq!(
        (tip.bl_spn, tip.bl_chord, tip.bl_af_id),
        (61.4999, 1.419, 8)
    );
}

#[test]
fn aerodyn_columns_are_found_by_name() {
    let text = "AERODYN BLADE\ntitle\n=== Blade Properties ===\n\
        2   NumBlNds  - nodes\n\
        BlSpn BlChord BlCrvAC BlSwpAC BlCrvAng BlTwist BlAFID BlCb BlCenBn BlCenBt\n\
        (m) (m) (m) (m) (deg) (deg) (-) (-) (m) (m)\n\
        0.0 5.2 0.1 0.2 0.3 15.6 1 0.0 0.0 0.0\n\
        117.0 0.5 -4.0 0.0 0.0 -1.2 50 0.0 0.0 0.0\n";
    let b = aerodyn::parse_blade(text, "new.dat").unwrap();
    let (root, tip) = (&b.nodes[0], &b.nodes[1]);
    assert_eq!(
        (root.bl_chord, root.bl_crv_ac, root.bl_twist_deg),
        (5.2, 0.1, 15.6)
    );
    assert_eq!((tip.bl_spn, tip.bl_crv_ac, tip.bl_af_id), (117.0, -4.0, 50));
}

#[test]
fn airfoil_polars_nrel5mw() {
    let du21 = airfoil::read_airfoil(&blades(DU21), PolarColumns::default()).unwrap();
    assert_eq!((du21.interp_ord, du21.non_dim_area), (None, 1.0));
    assert_eq!(du21.tables.len(), 1);
    let t = &du21.tables[0];
    assert_eq!((t.re, t.user_prop, t.alpha_deg.len()), (0.75, 0.0, 142));
    let cm = t.cm.as_ref().unwrap();
    assert_eq!(
        (t.alpha_deg[1], t.cl[1], t.cd[1], cm[1]),
        (-175.0, 0.394, 0.0332, 0.1978)
    );
    assert_eq!((t.alpha_deg[141], t.cd[141]), (180.0, 0.0185));
    assert!(t.cpmin.is_none());
    // Every airfoil the AeroDyn file refers to (BlAFID 1..8, in SOURCES.md's order).
    let expected = [
        ("Cylinder1", 3),
        ("Cylinder2", 3),
        ("DU40_A17", 136),
        ("DU35_A17", 135),
        ("DU30_A17", 143),
        ("DU25_A17", 140),
        ("DU21_A17", 142),
        ("NACA64_A17", 127),
    ];
    for (name, n_alf) in expected {
        let path = blades(&format!("nrel5mw/Airfoils/{name}.dat"));
        let a = airfoil::read_airfoil(&path, PolarColumns::default()).unwrap();
        assert_eq!(a.tables[0].alpha_deg.len(), n_alf, "{name}");
    }
}

#[test]
fn airfoil_tables_and_column_layout() {
    let header = "! AirfoilInfo\nDEFAULT  InterpOrd\n1  NonDimArea\n0  NumCoords\n";
    let tables = "2  NumTabs\n\
        ! table 1\n0.5  Re\n0  Ctrl\nTrue  InclUAdata\n-2.0  alpha0\nDefault  T_f0\n\
        3  NumAlf\n-10 -0.8 0.02\n0 0.2 0.01\n10 1.1 0.03\n\
        ! table 2\n1.5  Re\n0  Ctrl\nFalse  InclUAdata\n2  NumAlf\n-5 -0.3 0.01\n5 0.8 0.02\n";
    let three = PolarColumns {
        cm: 0,
        ..PolarColumns::default()
    };
    let a = airfoil::parse_airfoil(&format!("{header}{tables}"), "two.dat", three).unwrap();
    assert_eq!(a.tables.len(), 2);
    assert_eq!((a.tables[0].re, a.tables[0].cl[2]), (0.5, 1.1));
    assert_eq!(
        (a.tables[1].re, a.tables[1].alpha_deg.clone()),
        (1.5, vec![-5.0, 5.0])
    );
    assert!(a.tables[1].cm.is_none());
    // InCol_* lines in the file override the layout passed in.
    let in_file = format!("{header}1 InCol_Alfa\n2 InCol_Cl\n3 InCol_Cd\n0 InCol_Cm\n{tables}");
    let b = airfoil::parse_airfoil(&in_file, "two.dat", PolarColumns::default()).unwrap();
    assert_eq!(a, b);
    // With the default Alpha Cl Cd Cm layout the three-column rows are short.
    let e = airfoil::parse_airfoil(
        &format!("{header}{tables}"),
        "two.dat",
        PolarColumns::default(),
    )
    .unwrap_err();
    assert_format(&e, "two.dat", 13, "found 3 value(s)");
}

#[test]
fn airfoil_alpha_must_increase() {
    let mut lines: Vec<String> = text(DU21).lines().map(String::from).collect();
    lines.swap(55, 56); // the rows at -175 and -170 degrees
    let e =
        airfoil::parse_airfoil(&lines.join("\n"), "du21.dat", PolarColumns::default()).unwrap_err();
    assert_format(&e, "du21.dat", 57, "Alpha must increase strictly");
}

#[test]
fn hawc2_st_classic_and_fully_populated() {
    let classic = hawc2_st::read_st(&blades(ST_CLASSIC)).unwrap();
    assert_eq!(classic.sets.len(), 2);
    let StRows::Classic(rows) = &classic.subset(1, 1).unwrap().rows else {
        panic!("19 columns are the classic layout")
    };
    assert_eq!(rows.len(), 26);
    let r = &rows[0];
    assert_eq!(
        (r.r, r.m, r.e, r.g),
        (
            0.0,
            3.1265243837780e3,
            1.8877163007300e10,
            3.9142657899700e9
        )
    );
    assert_eq!(
        (r.pitch_deg, r.x_e, r.y_e),
        (-6.0000870619165, 1.9957381077269e-4, -4.7667659657248e-4)
    );
    assert_eq!(rows[25].r, 1.1717944874363e2);
    let StRows::Classic(stiff) = &classic.subset(2, 1).unwrap().rows else {
        panic!("set 2 is classic too")
    };
    assert_eq!(stiff[0].e, 1.8877163007300e18);

    let fpm = hawc2_st::read_st(&blades(ST_FPM)).unwrap();
    assert_eq!(fpm.sets.len(), 1);
    let StRows::FullyPopulated(rows) = &fpm.subset(1, 1).unwrap().rows else {
        panic!("30 columns are the fully populated layout")
    };
    assert_eq!(rows.len(), 26);
    let k = rows[0].stiffness();
    assert_eq!(
        (k[0][0], k[0][1], k[1][0]),
        (6.7269806300528e9, -2.2070863839243e6, -2.2070863839243e6)
    );
    assert_eq!(
        (k[0][5], k[5][0], k[5][5]),
        (-4.0229939372056e7, -4.0229939372056e7, 8.7412309114908e10)
    );
    assert_eq!(rows[0].pitch_deg, -6.0000870286029);

    let btc = hawc2_st::read_st(&blades(ST_BTC)).unwrap();
    assert_eq!(btc.subset(1, 1).unwrap().rows.len(), 20);
}

#[test]
fn hawc2_st_subset_names_what_the_file_has() {
    let st = hawc2_st::read_st(&blades(ST_CLASSIC)).unwrap();
    let e = st.subset(1, 2).unwrap_err().to_string();
    assert!(e.contains("IEA_15MW_RWT_Blade_st_noFPM.st"), "{e}");
    assert!(
        e.contains("no subset $2 in set #1") && e.contains("#1 ($1), #2 ($1)"),
        "{e}"
    );
}

#[test]
fn hawc2_ae_pc_and_operation() {
    let ae = hawc2_aero::read_ae(&blades(AE)).unwrap();
    assert_eq!(ae.sets.len(), 1);
    let rows = &ae.sets[0].rows;
    assert_eq!(rows.len(), 30);
    assert_eq!(
        (
            rows[0].r,
            rows[0].chord,
            rows[0].thickness_pct,
            rows[0].pc_set
        ),
        (0.0, 5.2, 100.0, 1)
    );
    assert_eq!(
        (rows[29].r, rows[29].thickness_pct),
        (1.171835883386072e2, 21.1)
    );

    let pc = hawc2_aero::read_pc(&blades(PC)).unwrap();
    let profiles = &pc.sets[0].profiles;
    let thickness: Vec<f64> = profiles.iter().map(|p| p.thickness_pct).collect();
    assert_eq!(thickness, [21.1, 24.1, 27.0, 30.1, 33.0, 36.0, 50.0, 100.0]);
    let rows: Vec<usize> = profiles.iter().map(|p| p.alpha_deg.len()).collect();
    assert_eq!(rows, [120, 120, 120, 120, 120, 120, 199, 2]);
    let p = &profiles[0];
    assert_eq!(
        (p.alpha_deg[0], p.cl[0], p.cd[0], p.cm[0]),
        (-180.0, 0.0, 2.464146255885971e-2, 0.0)
    );

    let opt = hawc2_aero::read_opt(&blades(OPT)).unwrap();
    assert_eq!(opt.wind_speed.len(), 17);
    let (power, thrust) = (opt.aero_power_kw.unwrap(), opt.aero_thrust_kn.unwrap());
    assert_eq!(
        (
            opt.wind_speed[6],
            opt.pitch_deg[6],
            opt.rotor_speed_rpm[6],
            power[6],
            thrust[6]
        ),
        (10.0, 0.000535, 7.101976, 12880.953731, 1898.680029)
    );
    assert_eq!((opt.wind_speed[0], power[0]), (0.5, -331.16584));
}

#[test]
fn hawc2_opt_header_decides_columns_and_units() {
    let rows = "3.0 1.0 5.0\n4.0 2.0 6.0\n";
    let bare = hawc2_aero::parse_opt(&format!("2\n{rows}"), "bare.opt").unwrap();
    assert_eq!(
        (bare.wind_speed.clone(), bare.aero_power_kw.clone()),
        (vec![3.0, 4.0], None)
    );
    let named = "2 pitch [deg] wind speed [m/s] rot. speed [rpm]\n";
    let moved = hawc2_aero::parse_opt(&format!("{named}{rows}"), "named.opt").unwrap();
    assert_eq!(
        (moved.pitch_deg, moved.wind_speed),
        (vec![3.0, 4.0], vec![1.0, 2.0])
    );
    let e = hawc2_aero::parse_opt(
        &format!("2 wind [m/s] pitch [rad] rpm [rpm]\n{rows}"),
        "rad.opt",
    )
    .unwrap_err();
    assert_format(&e, "rad.opt", 1, "expected HAWC2's [deg]");
}

// ---- hostile input ----

/// `e` is a format error about `path` at `line` whose message contains `needle`.
fn assert_format(e: &Error, path: &str, line: usize, needle: &str) {
    match e {
        Error::Format {
            path: p,
            line: l,
            message,
        } => {
            assert_eq!((p.as_str(), *l), (path, line), "{e}");
            assert!(message.contains(needle), "{e}");
        }
        other => panic!("expected a format error, got {other:?}"),
    }
}

/// `e` names `path` and locates itself: a line, or a line number in the message (the end of
/// the file, a search that found nothing) unless the input was empty.
fn assert_located(e: &Error, path: &str, input: &str) {
    let Error::Format {
        path: p,
        line,
        message,
    } = e
    else {
        panic!("expected a format error, got {e:?}")
    };
    assert_eq!(p, path, "{e}");
    assert!(!message.is_empty());
    if !input.trim().is_empty() {
        assert!(*line > 0 || message.contains("line"), "not located: {e}");
    }
}

/// Bytes from a fixed-seed generator, as text (invalid UTF-8 replaced): junk that still reaches
/// the parser.
fn junk(len: usize) -> String {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let bytes: Vec<u8> = (0..len)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Drives one reader through the hostile cases built from the real file `rel`:
/// - empty input and binary junk fail, naming the file;
/// - every whole-line prefix either fails (named, located) or, once it holds all the reader
///   needs, reads what the full file reads (`same`: equal, or a prefix for files of sets);
/// - a prefix cut inside a line (every 8th line, to stay fast) fails cleanly or reads;
/// - a number replaced by text fails at that line, naming the column;
/// - removing one table row fails, naming the file.
struct Hostile<T> {
    rel: &'static str,
    parse: fn(&str, &str) -> Result<T>,
    same: fn(&T, &T) -> bool,
    /// (1-based line, 1-based column) of a table value to replace by text.
    number: (usize, usize),
    /// 1-based line of a table row to remove.
    row: usize,
}

impl<T: std::fmt::Debug> Hostile<T> {
    fn run(&self) {
        let origin = format!("hostile/{}", self.rel);
        let full_text = text(self.rel);
        let full = (self.parse)(&full_text, &origin).unwrap();
        let lines: Vec<&str> = full_text.lines().collect();

        for input in ["", "\n\n", &junk(4096)] {
            let e = (self.parse)(input, &origin).unwrap_err();
            assert_located(&e, &origin, input);
        }
        // Byte offsets where each line starts: prefixes are slices, not copies.
        let starts: Vec<usize> = full_text
            .char_indices()
            .filter(|&(_, c)| c == '\n')
            .map(|(i, _)| i + 1)
            .collect();
        for (k, &end) in std::iter::once(&0).chain(&starts).enumerate() {
            let prefix = &full_text[..end];
            match (self.parse)(prefix, &origin) {
                Ok(v) => assert!((self.same)(&v, &full), "{k} lines read as {v:?}"),
                Err(e) => assert_located(&e, &origin, prefix),
            }
            // A number cut short may still read as a number: only a clean failure is required.
            let next = starts.get(k).copied().unwrap_or(full_text.len());
            let cut = (end + next) / 2;
            if k % 8 == 0 && full_text.is_char_boundary(cut) {
                if let Err(e) = (self.parse)(&full_text[..cut], &origin) {
                    assert_located(&e, &origin, &full_text[..cut]);
                }
            }
        }

        let (at, col) = self.number;
        let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        let mut tokens: Vec<&str> = lines[at - 1].split_whitespace().collect();
        tokens[col - 1] = "abc";
        edited[at - 1] = tokens.join(" ");
        let e = (self.parse)(&edited.join("\n"), &origin).unwrap_err();
        assert_format(&e, &origin, at, &format!("found 'abc' in column {col}"));

        let mut shorter = lines.clone();
        shorter.remove(self.row - 1);
        let input = shorter.join("\n");
        let e = (self.parse)(&input, &origin).unwrap_err();
        assert_located(&e, &origin, &input);
    }
}

fn equal<T: PartialEq>(a: &T, b: &T) -> bool {
    a == b
}

/// A prefix of an st file may end on a set boundary: it then reads the sets so far.
fn st_prefix(part: &StFile, full: &StFile) -> bool {
    full.sets.starts_with(&part.sets)
}

fn polar(text: &str, origin: &str) -> Result<AirfoilFile> {
    airfoil::parse_airfoil(text, origin, PolarColumns::default())
}

#[test]
fn hostile_beamdyn_primary() {
    Hostile {
        rel: BD_PRIMARY,
        parse: beamdyn::parse_primary,
        same: equal,
        number: (27, 3),
        row: 30,
    }
    .run();
}

#[test]
fn hostile_beamdyn_blade() {
    Hostile {
        rel: BD_BLADE,
        parse: beamdyn::parse_blade,
        same: equal,
        number: (12, 2),
        row: 13,
    }
    .run();
}

#[test]
fn hostile_elastodyn_blade() {
    Hostile {
        rel: ED_BLADE,
        parse: elastodyn::parse_blade,
        same: equal,
        number: (17, 5),
        row: 20,
    }
    .run();
}

#[test]
fn hostile_elastodyn_tower() {
    Hostile {
        rel: ED_TOWER,
        parse: elastodyn_tower::parse_tower,
        same: equal,
        number: (22, 2),
        row: 25,
    }
    .run();
}

#[test]
fn hostile_aerodyn_blade() {
    Hostile {
        rel: AD_BLADE,
        parse: aerodyn::parse_blade,
        same: equal,
        number: (8, 7),
        row: 10,
    }
    .run();
}

#[test]
fn hostile_airfoil() {
    Hostile {
        rel: DU21,
        parse: polar,
        same: equal,
        number: (55, 2),
        row: 60,
    }
    .run();
}

#[test]
fn hostile_hawc2_st() {
    for (rel, number) in [(ST_CLASSIC, (6, 9)), (ST_FPM, (6, 12))] {
        Hostile {
            rel,
            parse: hawc2_st::parse_st,
            same: st_prefix,
            number,
            row: 10,
        }
        .run();
    }
}

#[test]
fn hostile_hawc2_ae_pc_opt() {
    Hostile {
        rel: AE,
        parse: hawc2_aero::parse_ae,
        same: equal,
        number: (3, 2),
        row: 5,
    }
    .run();
    Hostile {
        rel: PC,
        parse: hawc2_aero::parse_pc,
        same: equal,
        number: (4, 3),
        row: 10,
    }
    .run();
    Hostile {
        rel: OPT,
        parse: hawc2_aero::parse_opt,
        same: equal,
        number: (2, 3),
        row: 5,
    }
    .run();
}

#[test]
fn a_missing_row_is_reported_where_the_table_breaks() {
    // NumBlNds 19 with a row removed: the 19th row read is the "!bjj" comment after the table.
    let ad = text(AD_BLADE);
    let lines: Vec<&str> = ad
        .lines()
        .filter(|l| !l.starts_with("1.0250000E+01"))
        .collect();
    let e = aerodyn::parse_blade(&lines.join("\n"), "ad.dat").unwrap_err();
    assert_format(&e, "ad.dat", 26, "expected 19 blade-node rows of 7 numbers");
    // A subset one row longer than it says.
    let st = text(ST_FPM).replace("$1 26", "$1 25");
    let e = hawc2_st::parse_st(&st, "st.st").unwrap_err();
    assert_format(&e, "st.st", 31, "declares 25 rows");
}

// ---- read_text on what is not a definition file ----

#[test]
fn read_text_refuses_devices_directories_fifos_and_huge_files() {
    let e = read_text(Path::new("/dev/zero")).unwrap_err();
    assert_format(&e, "/dev/zero", 0, "not a regular text file");
    let dir = scratch("a-directory");
    std::fs::create_dir_all(&dir).unwrap();
    let e = read_text(&dir).unwrap_err();
    assert_format(&e, &dir.display().to_string(), 0, "a directory");

    let fifo = scratch("a-fifo");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        // Opening a FIFO with no writer would block; the metadata check refuses it first.
        let e = read_text(&fifo).unwrap_err();
        assert_format(&e, &fifo.display().to_string(), 0, "pipe");
    }

    let huge = scratch("huge.dat");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(MAX_FILE_BYTES + 1).unwrap(); // sparse: no 64 MiB written
    let e = read_text(&huge).unwrap_err();
    assert_format(&e, &huge.display().to_string(), 0, "more than the 64 MiB");
    let e = beamdyn::read_blade(&huge).unwrap_err();
    assert_format(&e, &huge.display().to_string(), 0, "more than the 64 MiB");

    let binary = scratch("binary.dat");
    std::fs::write(&binary, [0x42, 0x44, 0xff, 0xfe, 0x00, 0x9f]).unwrap();
    let e = hawc2_st::read_st(&binary).unwrap_err();
    assert_format(&e, &binary.display().to_string(), 0, "not UTF-8");

    let missing = scratch("no-such-file.dat");
    let e = airfoil::read_airfoil(&missing, PolarColumns::default()).unwrap_err();
    assert_format(&e, &missing.display().to_string(), 0, "cannot read");
}

#[test]
fn presets_are_read_through_the_capped_reader() {
    let e = Preset::load("/dev/urandom", &[]).unwrap_err().to_string();
    assert!(
        e.contains("/dev/urandom") && e.contains("cannot read"),
        "{e}"
    );
    let huge = scratch("huge.toml");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(MAX_FILE_BYTES + 1)
        .unwrap();
    let name = huge.display().to_string();
    let e = Preset::load(&name, &[]).unwrap_err().to_string();
    assert!(
        e.contains(&name) && e.contains("cannot read preset file"),
        "{e}"
    );
}
