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

/// The preset of the README's ```toml block that names itself `name`.
fn readme_preset(text: &str, name: &str) -> String {
    let mut block: Option<String> = None;
    for line in text.lines() {
        match &mut block {
            None if line == "```toml" => block = Some(String::new()),
            Some(b) if line == "```" => {
                if b.contains(&format!("name = \"{name}\"")) {
                    return b.clone();
                }
                block = None;
            }
            Some(b) => {
                b.push_str(line);
                b.push('\n');
            }
            None => {}
        }
    }
    panic!("README.md has no ```toml block named {name}")
}

/// One command of a page's shell transcripts (a fenced line `$ …`) and the lines shown after it.
#[derive(Debug)]
struct Transcript {
    command: String,
    shown: Vec<String>,
}

/// Every `$ …` line of `text`'s fenced blocks with the lines shown under it (up to the next
/// prompt or fence); a trailing `# comment` is the page's, not the shell's.
fn transcripts(text: &str) -> Vec<Transcript> {
    let mut out: Vec<Transcript> = Vec::new();
    let mut fenced = false;
    // Whether the lines read belong to the last command's output.
    let mut output = false;
    for line in text.lines() {
        if line.starts_with("```") {
            fenced = !fenced;
            output = false;
        } else if let Some(command) = line.strip_prefix("$ ").filter(|_| fenced) {
            let command = match command.find("  #") {
                Some(at) => &command[..at],
                None => command,
            };
            out.push(Transcript {
                command: command.trim().to_string(),
                shown: Vec::new(),
            });
            output = true;
        } else if output {
            if let Some(last) = out.last_mut() {
                last.shown.push(line.to_string());
            }
        }
    }
    out
}

/// Whether `printed` is what a page shows as `shown`: a shown line `…` stands for any lines
/// (none included), and a shown line ending in `…` or `…)` for the rest of a printed line from
/// there. Numbers match to 1e-9 relative, so a full-precision float's last digit may differ.
fn shows(shown: &[String], printed: &[&str]) -> bool {
    match shown.split_first() {
        None => printed.is_empty(),
        Some((first, rest)) if first.trim() == "…" => {
            (0..=printed.len()).any(|skip| shows(rest, &printed[skip..]))
        }
        Some((first, rest)) => {
            let Some((line, others)) = printed.split_first() else {
                return false;
            };
            let elided = first.ends_with('…') || first.ends_with("…)");
            let same = match first.rfind('…').filter(|_| elided) {
                Some(at) => line.starts_with(&first[..at]),
                None => same_line(line, first),
            };
            same && shows(rest, others)
        }
    }
}

/// A line's text with every number replaced by `#`, and its numbers.
fn numbers_of(line: &str) -> (String, Vec<f64>) {
    let chars: Vec<char> = line.chars().collect();
    let (mut text, mut numbers) = (String::new(), Vec::new());
    let mut k = 0;
    while k < chars.len() {
        let starts = chars[k].is_ascii_digit()
            || (chars[k] == '-' && chars.get(k + 1).is_some_and(|c| c.is_ascii_digit()));
        if !starts {
            text.push(chars[k]);
            k += 1;
            continue;
        }
        let begin = k;
        k += 1;
        while k < chars.len() {
            let c = chars[k];
            let exponent_sign = (c == '-' || c == '+') && chars[k - 1] == 'e';
            if c.is_ascii_digit() || c == '.' || c == 'e' || exponent_sign {
                k += 1;
            } else {
                break;
            }
        }
        let token: String = chars[begin..k].iter().collect();
        match token.parse::<f64>() {
            Ok(x) => {
                text.push('#');
                numbers.push(x);
            }
            Err(_) => text.push_str(&token),
        }
    }
    (text, numbers)
}

fn same_line(printed: &str, shown: &str) -> bool {
    if printed == shown {
        return true;
    }
    let (a, x) = numbers_of(printed);
    let (b, y) = numbers_of(shown);
    a == b
        && x.len() == y.len()
        && x.iter()
            .zip(&y)
            .all(|(p, q)| (p - q).abs() <= 1e-9 * p.abs().max(q.abs()))
}

/// The pages' command transcripts print what they show, run as a user would in a fresh folder:
/// README's "your own blade in five minutes" presets saved beside copies of the files they name
/// (`nrel/`, `iea/`), every shell line of the pages run in order (`printf … > my.toml` makes a
/// page's example file), and every command shown with its output (stdout, then stderr) printing
/// that output now; one shown without output must succeed. Only the explorer (no subcommand) is
/// not run.
#[test]
fn the_pages_commands_print_what_the_pages_show() {
    let dir = std::env::temp_dir().join(format!("flutterscope-pages-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let blades = root().join("presets").join("blades");
    crate::copy_tree(&blades.join("nrel5mw"), &dir.join("nrel"));
    crate::copy_tree(&blades.join("iea15mw"), &dir.join("iea"));
    let text = readme();
    for name in ["my-openfast", "my-hawc2"] {
        std::fs::write(dir.join(format!("{name}.toml")), readme_preset(&text, name)).unwrap();
    }
    let binary = assert_cmd::cargo::cargo_bin("flutterscope");
    let mut checked = 0;
    for page in ["README.md", "docs/commands.md", "docs/presets.md"] {
        let text = std::fs::read_to_string(root().join(page)).unwrap();
        for t in transcripts(&text) {
            let ours = t.command.starts_with("flutterscope");
            let explorer = t
                .command
                .split_whitespace()
                .nth(1)
                .is_some_and(|a| a.starts_with('-'));
            if ours && explorer {
                continue;
            }
            let command = match t.command.strip_prefix("flutterscope") {
                Some(rest) => format!("'{}'{rest}", binary.display()),
                None => t.command.clone(),
            };
            let out = std::process::Command::new("sh")
                .arg("-c")
                .arg(&command)
                .current_dir(&dir)
                .output()
                .unwrap();
            let printed = format!(
                "{}{}",
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            if t.shown.is_empty() {
                assert!(
                    out.status.success(),
                    "{page}: `{}` fails:\n{printed}",
                    t.command
                );
                continue;
            }
            let lines: Vec<&str> = printed.lines().collect();
            assert!(
                shows(&t.shown, &lines),
                "{page}: `{}` prints\n{printed}\nwhere the page shows\n{}",
                t.command,
                t.shown.join("\n")
            );
            checked += usize::from(ours);
        }
    }
    assert!(checked >= 20, "only {checked} commands checked");
    let _ = std::fs::remove_dir_all(&dir);
}
