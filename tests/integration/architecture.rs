//! The crate's file-level import graph: every `.rs` file under `src/` is a node, and a file has
//! an edge to each module file whose items it names through `crate::`, `super::` or `self::`
//! paths (in `use` statements, grouped or not, and inline) and, in `use` statements, paths into
//! its own child modules (`use eigen::decompose` in a `mod.rs`). A path resolves to the deepest
//! module file that exists for it (`src/a/b.rs` or `src/a/b/mod.rs`), so a parent `mod.rs` is
//! a target only when the path stops at the parent. Comments, string literals and a trailing
//! `#[cfg(test)] mod tests` block are not read. Cycles are the graph's strongly connected
//! components with more than one file (Tarjan).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A file-level graph: node names (paths relative to the crate root, `/`-separated) and, for
/// each node, the indices of the nodes it uses.
struct Graph {
    names: Vec<String>,
    edges: Vec<BTreeSet<usize>>,
}

/// The strongly connected components of more than one node (and single nodes with an edge to
/// themselves), each as sorted node indices, in Tarjan's order of completion.
fn cycles(edges: &[BTreeSet<usize>]) -> Vec<Vec<usize>> {
    struct Tarjan<'a> {
        edges: &'a [BTreeSet<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            self.index[v] = Some(self.next);
            self.low[v] = self.next;
            self.next += 1;
            self.stack.push(v);
            self.on_stack[v] = true;
            for &w in self.edges[v].iter() {
                match self.index[w] {
                    None => {
                        self.visit(w);
                        self.low[v] = self.low[v].min(self.low[w]);
                    }
                    Some(iw) if self.on_stack[w] => self.low[v] = self.low[v].min(iw),
                    Some(_) => {}
                }
            }
            if Some(self.low[v]) == self.index[v] {
                let mut component = Vec::new();
                loop {
                    let w = self.stack.pop().expect("v is on the stack");
                    self.on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                if component.len() > 1 || self.edges[v].contains(&v) {
                    component.sort_unstable();
                    self.out.push(component);
                }
            }
        }
    }
    let n = edges.len();
    let mut t = Tarjan {
        edges,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            t.visit(v);
        }
    }
    t.out
}

/// `text` with comments, string and character literals blanked out and everything from a
/// `#[cfg(test)]` line followed by a `mod tests` line onwards dropped.
fn code_only(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let end = lines
        .windows(2)
        .position(|w| w[0].trim() == "#[cfg(test)]" && w[1].contains("mod tests"))
        .unwrap_or(lines.len());
    let text = lines[..end].join("\n");
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !chars[..i]
                .last()
                .is_some_and(|p| p.is_alphanumeric() || *p == '_')
        {
            // A raw string r"…" or r#"…"#: skip to the quote followed by as many hashes.
            let mut j = i + 1;
            let mut hashes = 0;
            while chars.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if chars.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= chars.len() {
                    break;
                }
                if chars[j] == '"' && (1..=hashes).all(|k| chars.get(j + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}'); otherwise a lifetime, kept.
            if next == Some('\\') {
                i += 2;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
                out.push_str("' '");
            } else if chars.get(i + 2) == Some(&'\'') {
                i += 3;
                out.push_str("' '");
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Every path a `use` tree names, expanded: `a::{b, c::{d, self}}` gives `a::b`, `a::c::d` and
/// `a::c`. Renames (`as x`) and globs are dropped; the glob's module is kept.
fn expand_use_tree(tree: &str) -> Vec<String> {
    fn split_top(s: &str) -> Vec<&str> {
        let mut parts = Vec::new();
        let (mut depth, mut start) = (0, 0);
        for (i, c) in s.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&s[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(&s[start..]);
        parts
    }
    fn walk(prefix: &str, tree: &str, out: &mut Vec<String>) {
        let tree = tree.trim();
        if tree.is_empty() {
            return;
        }
        if let Some(open) = tree.find('{') {
            let head = tree[..open].trim().trim_end_matches("::");
            let close = tree.rfind('}').unwrap_or(tree.len());
            let inner = &tree[open + 1..close];
            let prefix = join(prefix, head);
            for part in split_top(inner) {
                walk(&prefix, part, out);
            }
        } else {
            let path = tree.split(" as ").next().unwrap_or(tree).trim();
            let path = path.trim_end_matches('*').trim_end_matches("::");
            let path = if path == "self" {
                prefix.to_string()
            } else {
                join(prefix, path)
            };
            out.push(path);
        }
    }
    fn join(prefix: &str, tail: &str) -> String {
        match (prefix.is_empty(), tail.is_empty()) {
            (true, _) => tail.to_string(),
            (_, true) => prefix.to_string(),
            _ => format!("{prefix}::{tail}"),
        }
    }
    let compact: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = Vec::new();
    walk("", &compact, &mut out);
    out
}

/// The paths in `code` (already through [`code_only`]) as segment lists: every path of its `use`
/// statements, and the inline paths that start with `crate`, `super` or `self`; each with whether
/// it is a re-export (`pub use`, `pub(crate) use`).
fn paths_with_kind(code: &str) -> Vec<(Vec<String>, bool)> {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    let mut paths = Vec::new();
    let mut rest = String::new();
    // `use` statements, each up to its semicolon.
    let mut i = 0;
    while i < code.len() {
        let starts_use = code[i..].starts_with("use ")
            && (i == 0 || !is_ident(code[..i].chars().next_back().unwrap_or(' ')));
        if starts_use {
            let end = code[i..].find(';').map_or(code.len(), |e| i + e);
            let before = code[..i].trim_end();
            let reexport = before.ends_with("pub")
                || before.ends_with(')') && {
                    let open = before.rfind('(').unwrap_or(0);
                    before[..open].trim_end().ends_with("pub")
                };
            for path in expand_use_tree(&code[i + 4..end]) {
                let segs: Vec<String> = path.split("::").map(|s| s.trim().to_string()).collect();
                // A path with another first segment is an external crate's or, in a file with
                // that child module, the child's (told apart in `graph_of`).
                if !segs[0].is_empty() && segs[0] != "std" {
                    paths.push((segs, reexport));
                }
            }
            rest.push(' ');
            i = end;
        } else {
            let c = code[i..].chars().next().unwrap();
            rest.push(c);
            i += c.len_utf8();
        }
    }
    // Inline paths outside `use` statements.
    let chars: Vec<char> = rest.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let at_word = i == 0 || !(is_ident(chars[i - 1]));
        let word: String = chars[i..].iter().take_while(|c| is_ident(**c)).collect();
        if at_word && matches!(word.as_str(), "crate" | "super" | "self") {
            let mut segs = vec![word.clone()];
            let mut j = i + word.len();
            while chars.get(j) == Some(&':') && chars.get(j + 1) == Some(&':') {
                let seg: String = chars[j + 2..]
                    .iter()
                    .take_while(|c| is_ident(**c))
                    .collect();
                if seg.is_empty() {
                    break;
                }
                j += 2 + seg.len();
                segs.push(seg);
            }
            if segs.len() > 1 {
                paths.push((segs, false));
            }
            i = j;
        } else if word.is_empty() {
            i += 1;
        } else {
            i += word.len();
        }
    }
    paths
}

/// The module path of a file relative to `src/` (`analysis/eigen.rs` → `[analysis, eigen]`,
/// `numeric/mod.rs` → `[numeric]`, `lib.rs` → `[]`).
fn module_of(rel: &str) -> Vec<String> {
    let rel = rel.trim_end_matches(".rs");
    let mut segs: Vec<String> = rel.split('/').map(str::to_string).collect();
    if matches!(
        segs.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        segs.pop();
    }
    segs
}

/// The file of module `segs` among `files` (relative to `src/`), if it has one.
fn file_of(segs: &[String], files: &BTreeMap<String, usize>) -> Option<usize> {
    if segs.is_empty() {
        return files.get("lib.rs").copied();
    }
    let base = segs.join("/");
    files
        .get(&format!("{base}.rs"))
        .or_else(|| files.get(&format!("{base}/mod.rs")))
        .copied()
}

/// The graph of `sources` (paths relative to `src/` and their text).
fn graph_of(sources: &[(String, String)]) -> Graph {
    let files: BTreeMap<String, usize> = sources
        .iter()
        .enumerate()
        .map(|(i, (rel, _))| (rel.clone(), i))
        .collect();
    let mut edges = vec![BTreeSet::new(); sources.len()];
    for (from, (rel, text)) in sources.iter().enumerate() {
        let here = module_of(rel);
        for (path, reexport) in paths_with_kind(&code_only(text)) {
            let mut module = here.clone();
            let mut rest = &path[..];
            match rest[0].as_str() {
                "crate" => {
                    module.clear();
                    rest = &rest[1..];
                }
                "self" | "super" => {
                    while let Some(first) = rest.first() {
                        match first.as_str() {
                            "self" => rest = &rest[1..],
                            "super" => {
                                module.pop();
                                rest = &rest[1..];
                            }
                            _ => break,
                        }
                    }
                }
                child => {
                    let mut module = here.clone();
                    module.push(child.to_string());
                    if file_of(&module, &files).is_none() {
                        continue;
                    }
                }
            }
            module.extend(rest.iter().cloned());
            // A module re-exporting its own submodules' items states its interface; it does
            // not depend on them (they may use the module's own types without a cycle).
            if reexport && module.len() > here.len() && module.starts_with(&here) {
                continue;
            }
            let target = (0..=module.len())
                .rev()
                .find_map(|k| file_of(&module[..k], &files));
            if let Some(to) = target {
                if to != from {
                    edges[from].insert(to);
                }
            }
        }
    }
    Graph {
        names: sources
            .iter()
            .map(|(rel, _)| format!("src/{rel}"))
            .collect(),
        edges,
    }
}

/// Every `.rs` file under `dir`, with its path relative to `root`.
fn sources_under(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            sources_under(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let rel = path
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push((rel, std::fs::read_to_string(&path).unwrap()));
        }
    }
}

/// The file-level import graph of the crate's `src/`.
fn crate_graph() -> Graph {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut sources = Vec::new();
    sources_under(&src, &src, &mut sources);
    graph_of(&sources)
}

/// Every import of the crate's `src/` as (the file that imports, the file it imports).
fn import_edges() -> Vec<(String, String)> {
    let graph = crate_graph();
    graph
        .edges
        .iter()
        .enumerate()
        .flat_map(|(from, to)| {
            let names = &graph.names;
            to.iter()
                .map(move |&to| (names[from].clone(), names[to].clone()))
        })
        .collect()
}

/// The import cycles of the crate's `src/`, each as its files' names.
fn crate_cycles() -> Vec<Vec<String>> {
    let graph = crate_graph();
    cycles(&graph.edges)
        .into_iter()
        .map(|c| c.into_iter().map(|i| graph.names[i].clone()).collect())
        .collect()
}

#[test]
fn no_import_cycles() {
    let all = crate_cycles();
    assert!(
        all.is_empty(),
        "import cycles among the files of src/:\n{}",
        all.iter()
            .map(|c| format!("  {}", c.join(" ↔ ")))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The data flows one way (README, docs/architecture.md): the physics never reads the preset,
/// the model builder or the analyses, and the linear algebra and file readers read no layer
/// above them.
#[test]
fn lower_layers_import_nothing_above_them() {
    let above = |file: &str| -> &'static [&'static str] {
        if file.starts_with("src/physics/") {
            &[
                "src/preset/",
                "src/model/",
                "src/analysis/",
                "src/explorer/",
                "src/commands/",
            ]
        } else if file.starts_with("src/numeric/") || file.starts_with("src/formats/") {
            &[
                "src/preset/",
                "src/model/",
                "src/physics/",
                "src/analysis/",
                "src/explorer/",
            ]
        } else if file.starts_with("src/model/") {
            &["src/analysis/", "src/explorer/", "src/commands/"]
        } else {
            &[]
        }
    };
    let wrong: Vec<String> = import_edges()
        .into_iter()
        .filter(|(from, to)| above(from).iter().any(|layer| to.starts_with(layer)))
        .map(|(from, to)| format!("  {from} → {to}"))
        .collect();
    assert!(
        wrong.is_empty(),
        "imports that run up the layers:\n{}",
        wrong.join("\n")
    );
}

/// A preset is checked with the files it names: `preset/` calls into the model only to read them
/// (`model/files.rs`, and a HAWC2 model's files, `model/htc.rs`), and those read nothing of
/// `preset/` but its schema and file bases, so the model stays above the preset.
#[test]
fn the_preset_calls_the_model_only_to_read_its_files() {
    let readers = ["src/model/files.rs", "src/model/htc.rs"];
    let reader = |file: &str| readers.contains(&file);
    let wrong: Vec<String> = import_edges()
        .into_iter()
        .filter(|(from, to)| {
            let into_model = from.starts_with("src/preset/") && to.starts_with("src/model/");
            let into_preset = reader(from) && to.starts_with("src/preset/");
            (into_model && !reader(to))
                || (into_preset
                    && !(to.starts_with("src/preset/schema/") || to == "src/preset/files.rs"))
        })
        .map(|(from, to)| format!("  {from} → {to}"))
        .collect();
    assert!(
        wrong.is_empty(),
        "imports between the preset and the model other than the file readers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn cycle_finder_finds_a_known_cycle() {
    let file = |rel: &str, text: &str| (rel.to_string(), text.to_string());
    let sources = vec![
        file("lib.rs", "pub mod a;\npub mod b;\npub mod c;\npub mod d;\n"),
        file(
            "a/mod.rs",
            "pub mod x;\npub mod y;\nuse nalgebra::DMatrix;\nfn h() { self::y::f(); }\n",
        ),
        // a::x → a::y and a through a grouped use, a → a::y through an inline path, a::y → b
        // through an inline path, b → a::x through `super`: a cycle of four files.
        file("a/x.rs", "use crate::{a::{y::Thing, self}, c};\n"),
        file(
            "a/y.rs",
            "pub struct Thing;\nfn f() { crate::b::g(); }\n// crate::c::Never\n",
        ),
        file(
            "b.rs",
            "use super::a::x as other;\npub fn g() {}\n#[cfg(test)]\nmod tests {\n    use crate::c::T;\n}\n",
        ),
        // d re-exports its child's items, which use d's own type: the re-export is d's
        // interface, not a use, so d is on no cycle.
        file(
            "d/mod.rs",
            "pub mod e;\npub use e::E;\npub(crate) use e::F;\npub struct D;\n",
        ),
        file("d/e.rs", "use super::D;\npub struct E;\npub struct F;\n"),
        // c → b only inside a string and a test block: no edge, so c is on no cycle.
        file(
            "c.rs",
            "const S: &str = \"crate::b::g\";\n#[cfg(test)]\nmod tests {\n    use crate::b::g;\n}\n",
        ),
    ];
    let graph = graph_of(&sources);
    let named: Vec<Vec<&str>> = cycles(&graph.edges)
        .iter()
        .map(|c| c.iter().map(|&i| graph.names[i].as_str()).collect())
        .collect();
    assert_eq!(
        named,
        vec![vec!["src/a/mod.rs", "src/a/x.rs", "src/a/y.rs", "src/b.rs"]]
    );
    let id = |name: &str| graph.names.iter().position(|n| n == name).unwrap();
    // `a::{self}` stops at a/mod.rs; `crate::c` is the file c.rs.
    assert!(graph.edges[id("src/a/x.rs")].contains(&id("src/a/mod.rs")));
    assert!(graph.edges[id("src/a/x.rs")].contains(&id("src/c.rs")));
    assert!(graph.edges[id("src/c.rs")].is_empty());
    assert!(graph.edges[id("src/d/mod.rs")].is_empty());
    assert!(graph.edges[id("src/d/e.rs")].contains(&id("src/d/mod.rs")));
    // A `mod.rs` re-exporting from its child uses the child; an external crate is no file.
    assert_eq!(
        graph.edges[id("src/a/mod.rs")],
        [id("src/a/y.rs")].into_iter().collect()
    );
    assert!(!graph.edges[id("src/a/y.rs")].contains(&id("src/c.rs")));
}
