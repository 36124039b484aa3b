//! Mode identification (docs/model.md §6.2): one name per mode, the same in every command.

use assert_cmd::Command;
use flutterscope::analysis::eigen::{analyse, linear_system};
use flutterscope::analysis::flutter::flutter_search;
use flutterscope::analysis::sweep::track;
use flutterscope::physics::structure::Family;
use flutterscope::preset::{builtin_names, Preset};
use std::collections::HashSet;

/// No name twice at one operating point, and no number beyond the natural modes of its family,
/// across every built-in preset × aerodynamic model × N.
#[test]
fn names_are_unique_and_within_their_family_everywhere() {
    let mut checked = 0;
    for name in builtin_names() {
        for model in ["none", "quasi-steady", "theodorsen", "onera"] {
            for n in [1, 5, 8, 20] {
                let o = vec![
                    format!("aero.model={model}"),
                    format!("structure.modes={n}"),
                ];
                // Not every preset takes every model or N (tabulated blades: aero none for now).
                let Ok(p) = Preset::load(name, &o) else {
                    continue;
                };
                let Ok(s) = analyse(&p) else { continue };
                let natural = linear_system(&p)
                    .unwrap()
                    .structure
                    .natural_modes()
                    .unwrap();
                let count = |f: Family| natural.iter().filter(|m| m.family == f).count();
                let what = format!("{name}, {model}, N = {n}");
                let mut seen = HashSet::new();
                for m in &s.eigenvalues {
                    assert!(seen.insert(m.label.clone()), "{what}: {} twice", m.label);
                    let family = m.family.unwrap_or_else(|| panic!("{what}: {}", m.label));
                    let number: usize = m
                        .label
                        .strip_prefix(family.name())
                        .and_then(|k| k.trim().parse().ok())
                        .unwrap_or_else(|| panic!("{what}: {}", m.label));
                    assert!(
                        (1..=count(family)).contains(&number),
                        "{what}: {} of {} {} modes",
                        m.label,
                        count(family),
                        family.name()
                    );
                    assert!(!m.label.contains('\''), "{what}: {}", m.label);
                }
                checked += 1;
            }
        }
    }
    assert!(checked >= 30, "only {checked} combinations solved");
}

/// The unstable demo-blade mode, just past its flutter boundary, has one name in `eigen`,
/// `flutter`, `sweep` and the explorer's status line, and every named track of the 0–200 rpm
/// sweep either moves continuously or leaves its branch only where re-solving inside the step
/// confirms it.
#[test]
fn demo_blade_names_agree_and_tracks_are_continuous() {
    let base = Preset::load("demo-blade", &[]).unwrap();
    let search = flutter_search(&base, "operating.rotor_speed", 0.0, 200.0, 41).unwrap();
    let critical = search
        .boundary
        .critical
        .expect("demo-blade flutters below 200 rpm");
    // The first sweep grid point past the boundary.
    let grid: Vec<f64> = (0..=20).map(|k| 10.0 * k as f64).collect();
    let at = grid.iter().position(|&v| v > critical).unwrap();
    let rpm = grid[at];
    let p = base.with("operating.rotor_speed", rpm).unwrap();
    let eigen = analyse(&p).unwrap();
    let unstable = eigen.critical().unwrap();
    assert!(unstable.re > 0.0 && unstable.family.is_some());
    let name = unstable.label.clone();

    assert_eq!(search.boundary.mode.as_deref(), Some(name.as_str()));
    assert!(
        search.message.contains(&format!("{name} (flap ")),
        "{}",
        search.message
    );

    let sweep = track(&p, "operating.rotor_speed", &grid).unwrap();
    let growing: Vec<&str> = sweep
        .modes
        .iter()
        .filter(|m| m.re[at] > 0.0)
        .map(|m| m.label.as_str())
        .collect();
    assert_eq!(growing, [name.as_str()]);

    let out = Command::cargo_bin("flutterscope")
        .unwrap()
        .args(["snapshot", "--preset", "demo-blade", "--set"])
        .args([
            format!("operating.rotor_speed={rpm}").as_str(),
            "--size",
            "160x48",
        ])
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let status = text.lines().rev().nth(1).unwrap();
    assert!(
        status.contains(&format!("least damped: {}", unstable.described())),
        "{status}"
    );

    // Continuity: a step whose frequency jump exceeds 25 % (and 1 Hz) either ends at an
    // overdamped point (0 Hz), or is a branch switch confirmed and recorded in that step, or is
    // confirmed by a refinement step: re-solved at the step's midpoint, the mode's frequency lies
    // between its two ends (a fast but continuous change, not a jump).
    for m in &sweep.modes {
        for k in 1..grid.len() {
            let (a, b) = (m.frequency_hz[k - 1], m.frequency_hz[k]);
            if !(a.is_finite() && b.is_finite()) || a == 0.0 || b == 0.0 {
                continue;
            }
            let jump = (b - a).abs();
            let mid = 0.5 * (grid[k - 1] + grid[k]);
            if jump <= f64::max(1.0, 0.25 * a.max(b)) || m.switches.contains(&mid) {
                continue;
            }
            let s = analyse(&p.with("operating.rotor_speed", mid).unwrap()).unwrap();
            let f = s
                .eigenvalues
                .iter()
                .find(|r| r.label == m.label)
                .map(|r| r.frequency_hz)
                .unwrap_or(f64::NAN);
            let slack = 0.05 * jump;
            assert!(
                (a.min(b) - slack..=a.max(b) + slack).contains(&f),
                "{}: {a} → {b} Hz between {} and {} rpm, {f} Hz at {mid} rpm",
                m.label,
                grid[k - 1],
                grid[k]
            );
        }
    }
}

/// When the families do not add up, the root that fits worst takes the other family's name
/// (docs/model.md §6.2, which kind names first). The IEA 15MW at 12.4 rpm, past its overspeed
/// flutter point (12.08 rpm): flap 1 is an
/// overdamped pair, almost pure flap, and must be called flap 1; the growing 3.0 Hz root, the
/// torsion-1 branch coalescing with flap 3, is then 94 % flap and takes torsion 1 (named first,
/// the oscillating roots used to take flap 1 and leave the pair `torsion 1`, two roots of the
/// wrong family). The same in quasi-steady air at rated, where that pair is the overdamped
/// flap 1 and the 3.6 Hz flutter root torsion 1.
#[test]
fn an_overdamped_flap_mode_keeps_its_family() {
    for set in [
        vec!["operating.rotor_speed=12.4".to_string()],
        vec!["aero.model=quasi-steady".to_string()],
    ] {
        let p = Preset::load("iea15mw", &set).unwrap();
        let s = analyse(&p).unwrap();
        let pair = s
            .eigenvalues
            .iter()
            .find(|m| m.second_re.is_some() && m.shares.flap > 0.9)
            .unwrap_or_else(|| panic!("{set:?}: no overdamped flap pair"));
        assert_eq!(pair.label, "flap 1", "{set:?}");
        let growing = s.critical().unwrap();
        assert!(growing.re > 0.0 && growing.im > 0.0, "{set:?}");
        assert_eq!(growing.label, "torsion 1", "{set:?}");
        // No more roots named across families than the families' counts force: the roots of
        // a family beyond its natural modes (`eigen` lists an overdamped pair once).
        let foreign = s
            .eigenvalues
            .iter()
            .filter(|m| m.family != Some(m.shares.family()))
            .count();
        let forced: usize = Family::ALL
            .iter()
            .map(|&f| {
                let roots = s
                    .eigenvalues
                    .iter()
                    .filter(|m| m.shares.family() == f)
                    .count();
                let names = s.eigenvalues.iter().filter(|m| m.family == Some(f)).count();
                roots.saturating_sub(names)
            })
            .sum();
        assert_eq!(foreign, forced, "{set:?}");
    }
}
