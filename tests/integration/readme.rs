//! The README is the user's reference: keep it true to the code.

use flutterscope::preset::{builtin_names, Preset, KEYS};

fn readme() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap()
}

#[test]
fn every_numeric_key_is_documented_with_its_range_and_default() {
    let text = readme();
    let defaults = Preset::default();
    for spec in KEYS {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| `{}` |", spec.key)))
            .unwrap_or_else(|| panic!("README.md lacks a row for {}", spec.key));
        assert!(
            row.contains(&format!("{}", spec.max)) || row.contains(&format!("{:e}", spec.max)),
            "README row for {} does not show its upper bound {}: {row}",
            spec.key,
            spec.max
        );
        let shown = row.trim_end_matches('|').rsplit('|').next().unwrap().trim();
        let shown = match shown {
            "2π" => std::f64::consts::TAU,
            v => v.parse::<f64>().unwrap_or_else(|_| {
                panic!("README default of {} is not a number: {row}", spec.key)
            }),
        };
        let default = (spec.get)(&defaults);
        assert!(
            (shown - default).abs() <= 1e-12 * default.abs(),
            "README shows {shown} as the default of {}, the code has {default}",
            spec.key
        );
    }
}

#[test]
fn every_builtin_preset_is_documented() {
    let text = readme();
    for name in builtin_names() {
        assert!(
            text.contains(&format!("`{name}`")),
            "README.md does not mention preset {name}"
        );
    }
}

#[test]
fn readme_shows_the_two_commands() {
    let text = readme();
    assert!(text.contains("cargo run --release"));
    assert!(text.contains("cargo test"));
}

#[test]
fn every_explorer_key_is_documented() {
    let text = readme();
    for b in flutterscope::explorer::keys::BINDINGS {
        let row = format!("| `{}` | {} |", b.shown, b.help_text());
        assert!(text.contains(&row), "README.md lacks the key row {row}");
    }
}

/// The README's capture of the explorer is what `flutterscope snapshot --size 120x40` draws now.
#[test]
fn readme_screenshot_is_the_current_default_frame() {
    let out = assert_cmd::cargo::cargo_bin_cmd!("flutterscope")
        .args(["snapshot", "--size", "120x40"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let frame = String::from_utf8(out.stdout).unwrap();
    let text = readme();
    let start = text
        .find("```text\n┌ Parameters")
        .expect("README.md lacks the explorer capture")
        + "```text\n".len();
    let end = start + text[start..].find("```").unwrap();
    assert_eq!(
        text[start..end].trim_end(),
        frame.trim_end(),
        "README.md's capture is stale: paste `flutterscope snapshot --size 120x40`"
    );
}
