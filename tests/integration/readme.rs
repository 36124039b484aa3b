//! The README and the reference pages in docs/ are the user's reference: keep them true to the
//! code, and their links whole.

use std::path::{Path, PathBuf};

use flutterscope::preset::{builtin_names, Preset, KEYS};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).unwrap()
}

/// A page under docs/, e.g. `doc("presets.md")`.
fn doc(name: &str) -> String {
    let path = root().join("docs").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// README.md and every docs/*.md, with their paths.
fn pages() -> Vec<(PathBuf, String)> {
    let mut paths = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "md"))
        .collect();
    docs.sort();
    paths.extend(docs);
    paths
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p, text)
        })
        .collect()
}

/// The targets of the inline markdown links `[text](target)` in `text`, outside code spans
/// and fenced code blocks.
fn link_targets(text: &str) -> Vec<String> {
    let mut targets = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop code spans: a `[x](y)` inside backticks is not a link.
        let mut plain = String::new();
        let mut in_code = false;
        for c in line.chars() {
            if c == '`' {
                in_code = !in_code;
            } else if !in_code {
                plain.push(c);
            }
        }
        let mut rest = plain.as_str();
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            match after.find(')') {
                Some(j) => {
                    targets.push(after[..j].trim().to_string());
                    rest = &after[j + 1..];
                }
                None => break,
            }
        }
    }
    targets
}

#[test]
fn every_numeric_key_is_documented_with_its_range_and_default() {
    let text = doc("presets.md");
    let defaults = Preset::default();
    for spec in KEYS {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| `{}` |", spec.key)))
            .unwrap_or_else(|| panic!("docs/presets.md lacks a row for {}", spec.key));
        assert!(
            row.contains(&format!("{}", spec.max)) || row.contains(&format!("{:e}", spec.max)),
            "docs/presets.md row for {} does not show its upper bound {}: {row}",
            spec.key,
            spec.max
        );
        let shown = row.trim_end_matches('|').rsplit('|').next().unwrap().trim();
        if shown == "unset" {
            assert!(
                (spec.unset)(&defaults),
                "docs/presets.md shows {} unset, the code sets it",
                spec.key
            );
            continue;
        }
        let shown = match shown {
            "2π" => std::f64::consts::TAU,
            v => v.parse::<f64>().unwrap_or_else(|_| {
                panic!(
                    "docs/presets.md default of {} is not a number: {row}",
                    spec.key
                )
            }),
        };
        let default = (spec.get)(&defaults);
        assert!(
            (shown - default).abs() <= 1e-12 * default.abs(),
            "docs/presets.md shows {shown} as the default of {}, the code has {default}",
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

#[test]
fn readme_is_under_400_lines() {
    let lines = readme().lines().count();
    assert!(
        lines < 400,
        "README.md has {lines} lines: keep it under 400, the full record belongs in docs/"
    );
}

#[test]
fn every_relative_link_points_at_a_file_that_exists() {
    let mut broken = Vec::new();
    let mut checked = 0;
    for (page, text) in pages() {
        let dir = page.parent().unwrap();
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with("mailto:") || target.starts_with('#') {
                continue;
            }
            let file = target.split('#').next().unwrap();
            checked += 1;
            if !dir.join(file).exists() {
                broken.push(format!("{}: ({target})", page.display()));
            }
        }
    }
    assert!(
        checked > 0,
        "no relative links found: is the link scanner broken?"
    );
    assert!(
        broken.is_empty(),
        "links to missing files:\n{}",
        broken.join("\n")
    );
}

#[test]
fn the_docs_describe_the_program_not_its_history() {
    for (page, text) in pages() {
        let lower = text.to_lowercase();
        let mut rest = lower.as_str();
        while let Some(i) = rest.find("issue ") {
            let after = &rest[i + "issue ".len()..];
            let next = after.trim_start_matches('#').chars().next();
            assert!(
                !next.is_some_and(|c| c.is_ascii_digit()),
                "{} refers to an issue by number (\"{}\"): say what the program does instead",
                page.display(),
                rest[i..].chars().take(12).collect::<String>()
            );
            rest = after;
        }
    }
}
