//! The bend–twist coupling knob of a tabulated blade (docs/model.md §11.7): α = 0 is the files'
//! blade, α > 0 twists toward feather under downwind bending (the sense of the IEA 15MW BTC
//! blade's own coupling), the build cache tells α apart, the uniform blade refuses the key, and
//! sweeps vary it.

use flutterscope::model::blade::blade_structure;
use flutterscope::physics::blade::coupling::coupling_ratio;
use flutterscope::physics::blade::fem::assemble;
use flutterscope::preset::{Preset, ValidPreset};
use std::sync::Arc;

fn with_alpha(name: &str, alpha: f64) -> ValidPreset {
    Preset::load(name, &[format!("blade.bend_twist_coupling={alpha}")]).unwrap()
}

/// Tip flap (m) and twist (rad, toward feather) under a 100 kN downwind force through the tip's
/// shear centre, at rest, on the blade as the preset builds it.
fn tip_under_load(p: &ValidPreset) -> (f64, f64) {
    let built = blade_structure(p).unwrap().unwrap();
    let g = &built.modal.geometry;
    let m = assemble(&g.table, &g.mesh, g.pitch).unwrap();
    let centre = m.shear_centre_at(built.table.length()).unwrap();
    let f = centre.point_load(m.k0.nrows(), 1.0e5, 0.0, 0.0);
    let motion = centre.motion(&m.k0.clone().lu().solve(&f).unwrap());
    (motion.flap, motion.twist)
}

#[test]
fn zero_coupling_is_the_files_blade() {
    for name in ["nrel5mw", "iea15mw-btc-st2019"] {
        let p = with_alpha(name, 0.0);
        let built = blade_structure(&p).unwrap().unwrap();
        let file = &p.tabulated_blade().unwrap().table;
        assert_eq!(built.table.sections.len(), file.sections.len());
        for (a, b) in built.table.sections.iter().zip(&file.sections) {
            assert_eq!(a.flap_twist, b.flap_twist, "{name}");
            assert_eq!(a.gj, b.gj, "{name}");
        }
    }
}

/// α adds `α√(EI_flap·GJ)` at every station, on top of the file's coupling.
#[test]
fn alpha_adds_to_every_station() {
    let p = with_alpha("iea15mw-btc-st2019", 0.2);
    let built = blade_structure(&p).unwrap().unwrap();
    let file = &p.tabulated_blade().unwrap().table;
    let ratios: Vec<f64> = file.sections.iter().map(coupling_ratio).collect();
    eprintln!("iea15mw-btc-st2019 g/√(EI_flap·GJ) by station: {ratios:.3?}");
    for (a, b) in built.table.sections.iter().zip(&file.sections) {
        let added = a.flap_twist - b.flap_twist;
        let expected = 0.2 * (b.ei_flap * b.gj).sqrt();
        assert!((added - expected).abs() <= 1e-9 * expected, "z = {}", b.z);
        assert!((coupling_ratio(a) - coupling_ratio(b) - 0.2).abs() < 1e-12);
    }
}

/// docs/model.md §11.7: α > 0 twists the tip toward feather (φ > 0) under a downwind tip force,
/// α < 0 away from it; the NREL 5MW file has no coupling, so α = 0 does not twist it at all. The
/// IEA 15MW BTC blade's own coupling twists toward feather: α > 0 adds to it, α < 0 takes away.
#[test]
fn positive_coupling_twists_toward_feather_as_the_btc_blade_does() {
    let nrel: Vec<(f64, f64)> = [-0.1, 0.0, 0.1]
        .iter()
        .map(|&a| tip_under_load(&with_alpha("nrel5mw", a)))
        .collect();
    let btc: Vec<(f64, f64)> = [-0.1, 0.0, 0.1]
        .iter()
        .map(|&a| tip_under_load(&with_alpha("iea15mw-btc-st2019", a)))
        .collect();
    eprintln!(
        "tip (flap m, twist rad) at α = -0.1, 0, 0.1: nrel5mw {nrel:?}; iea15mw-btc-st2019 {btc:?}"
    );
    assert!(nrel.iter().all(|(flap, _)| *flap > 0.0));
    assert!(nrel[1].1.abs() < 1e-12, "{nrel:?}");
    assert!(nrel[2].1 > 1e-4 && nrel[0].1 < -1e-4, "{nrel:?}");
    assert!(
        btc[1].1 > 0.01,
        "the BTC blade twists toward feather: {btc:?}"
    );
    assert!(btc[2].1 > btc[1].1 && btc[1].1 > btc[0].1, "{btc:?}");
}

/// The build kept for one α is not the one for another: the cache key holds α (were it not,
/// the second call would return the first build, with the first α's coupling).
#[test]
fn the_build_cache_tells_couplings_apart() {
    let a = blade_structure(&with_alpha("nrel5mw", 0.1))
        .unwrap()
        .unwrap();
    let b = blade_structure(&with_alpha("nrel5mw", -0.1))
        .unwrap()
        .unwrap();
    assert!(!Arc::ptr_eq(&a, &b));
    let outboard = a.table.sections.len() / 2;
    let (ga, gb) = (
        a.table.sections[outboard].flap_twist,
        b.table.sections[outboard].flap_twist,
    );
    assert!(ga > 0.0 && gb == -ga, "{ga} {gb}");
    let fa = a.modes(0.0).unwrap()[0].frequency_hz;
    let fb = b.modes(0.0).unwrap()[0].frequency_hz;
    // ±α couple the same amount in opposite senses: the same frequencies.
    assert!((fa - fb).abs() < 1e-9 * fa, "{fa} {fb}");
}

#[test]
fn the_uniform_blade_refuses_the_key_and_the_range_is_checked() {
    let err = Preset::load("liu2017", &["blade.bend_twist_coupling=0.1".into()])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("blade.bend_twist_coupling = 0.1")
            && err.contains("uniform")
            && err.contains("section.c23"),
        "{err}"
    );
    // 0 is every preset's default: allowed everywhere.
    Preset::load("liu2017", &["blade.bend_twist_coupling=0".into()]).unwrap();
    let err = Preset::load("nrel5mw", &["blade.bend_twist_coupling=0.4".into()])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("blade.bend_twist_coupling = 0.4") && err.contains("[-0.3, 0.3]"),
        "{err}"
    );
}

/// Sweeps and flutter searches vary it as any numeric key.
#[test]
fn a_sweep_varies_the_coupling() {
    let out = assert_cmd::Command::cargo_bin("flutterscope")
        .unwrap()
        .args([
            "sweep",
            "--preset",
            "iea15mw-btc-st2019",
            "--vary",
            "blade.bend_twist_coupling=-0.3:0.3:0.3",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("blade.bend_twist_coupling"), "{text}");
}
