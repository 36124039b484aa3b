//! HAWC2 htc (model) files: the statements and `begin X; … end X;` blocks of a model, with the
//! files its `continue_in_file`s include, and the parts that describe one blade: the main body's
//! `c2_def` and `timoschenko_input`, its damping, and the `aero` block's files and set for it.
//!
//! The syntax as HAWC2 reads it (HAWC2 manual, "How 2 HAWC2", the htc input): a statement is a
//! keyword and its values ended by `;`; whatever follows the `;` on the line is a comment (a line
//! that starts with `;` is all comment); `begin X;` opens block `X` and `end X;` closes it, blocks
//! nest; `continue_in_file path;` reads `path` in its place, and `exit;` ends the file it is in
//! (an included file then continues the one that included it). Keywords are matched without
//! regard to case; values (file names) keep theirs.
//!
//! Paths inside an htc file are relative to the folder HAWC2 is run from (the model's root), not
//! to the file that names them; this reader leaves them as written and asks its caller for an
//! included file's text ([`parse_htc`]'s `include`).

use super::text::parse_number;
use crate::error::{Error, Result};

/// One statement: its keyword (lower case) and values, where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Statement {
    pub keyword: String,
    pub values: Vec<String>,
    pub file: String,
    /// 1-based.
    pub line: usize,
}

/// A `begin name …; … end name;` block (the root block has no name: the whole model).
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// The block's name (lower case), e.g. `main_body`.
    pub name: String,
    pub file: String,
    /// Line of its `begin` (0 for the root).
    pub line: usize,
    pub items: Vec<Item>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    Statement(Statement),
    Block(Block),
}

/// Deepest `continue_in_file` nesting: a file that includes itself stops here with an error
/// rather than recursing without end.
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// The model `text` (named `origin` in errors) as its tree of blocks. `include` returns the
/// name to put in errors and the text of the file a `continue_in_file` names, as written.
/// Errors name the file and line.
pub fn parse_htc(
    text: &str,
    origin: &str,
    include: &mut dyn FnMut(&str) -> Result<(String, String)>,
) -> Result<Block> {
    let mut stream = Vec::new();
    read_statements(text, origin, include, 0, &mut stream)?;
    into_blocks(stream, origin)
}

/// `text`'s statements in order, included files read in place, into `out`.
fn read_statements(
    text: &str,
    origin: &str,
    include: &mut dyn FnMut(&str) -> Result<(String, String)>,
    depth: usize,
    out: &mut Vec<Statement>,
) -> Result<()> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (idx, line) in text.lines().enumerate() {
        let at = |message: String| Error::format(origin, idx + 1, message);
        let Some((code, _comment)) = line.split_once(';') else {
            if line.trim().is_empty() {
                continue;
            }
            return Err(at(format!(
                "expected a statement ended by ';', found '{}'",
                line.trim()
            )));
        };
        let mut tokens = code.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        let statement = Statement {
            keyword: keyword.to_ascii_lowercase(),
            values: tokens.map(str::to_string).collect(),
            file: origin.to_string(),
            line: idx + 1,
        };
        match statement.keyword.as_str() {
            "exit" => return Ok(()),
            "continue_in_file" => {
                let [path] = statement.values.as_slice() else {
                    return Err(at("expected 'continue_in_file <path>;'".into()));
                };
                if depth + 1 >= MAX_INCLUDE_DEPTH {
                    return Err(at(format!(
                        "continue_in_file {path}: files included more than \
                         {MAX_INCLUDE_DEPTH} deep (does a file include itself?)"
                    )));
                }
                let (name, included) =
                    include(path).map_err(|e| at(format!("continue_in_file {path}: {e}")))?;
                read_statements(&included, &name, include, depth + 1, out)?;
            }
            _ => out.push(statement),
        }
    }
    Ok(())
}

/// The statements nested by their `begin`/`end` pairs.
fn into_blocks(stream: Vec<Statement>, origin: &str) -> Result<Block> {
    let mut open = vec![Block {
        name: String::new(),
        file: origin.to_string(),
        line: 0,
        items: Vec::new(),
    }];
    for s in stream {
        let at = |message: String| Error::format(&s.file, s.line, message);
        match s.keyword.as_str() {
            "begin" => {
                let name = s
                    .values
                    .first()
                    .ok_or_else(|| at("expected 'begin <block>;'".into()))?;
                open.push(Block {
                    name: name.to_ascii_lowercase(),
                    file: s.file.clone(),
                    line: s.line,
                    items: Vec::new(),
                });
            }
            "end" => {
                let name = s.values.first().map(|n| n.to_ascii_lowercase());
                let top = open.last().expect("the root block stays open");
                if open.len() == 1 {
                    return Err(at(format!(
                        "'end {}' closes no block: none is open",
                        name.unwrap_or_default()
                    )));
                }
                if name.as_deref() != Some(top.name.as_str()) {
                    return Err(at(format!(
                        "expected 'end {};' (the block begun at {}:{}), found 'end {}'",
                        top.name,
                        top.file,
                        top.line,
                        name.unwrap_or_default()
                    )));
                }
                let done = open.pop().expect("checked above");
                let parent = open.last_mut().expect("the root block stays open");
                parent.items.push(Item::Block(done));
            }
            _ => open
                .last_mut()
                .expect("the root block stays open")
                .items
                .push(Item::Statement(s)),
        }
    }
    if open.len() > 1 {
        let top = open.last().expect("checked");
        return Err(Error::format(
            &top.file,
            top.line,
            format!("block '{}' has no 'end {};'", top.name, top.name),
        ));
    }
    Ok(open.pop().expect("the root block"))
}

impl Item {
    /// This item if it is a block called `name`.
    fn block_named(&self, name: &str) -> Option<&Block> {
        match self {
            Item::Block(b) if b.name == name => Some(b),
            _ => None,
        }
    }

    /// This item if it is a statement with `keyword`.
    fn statement_with(&self, keyword: &str) -> Option<&Statement> {
        match self {
            Item::Statement(s) if s.keyword == keyword => Some(s),
            _ => None,
        }
    }
}

impl Block {
    /// The blocks called `name` directly inside this one.
    pub fn blocks<'a>(&'a self, name: &'a str) -> impl Iterator<Item = &'a Block> + 'a {
        self.items.iter().filter_map(move |i| i.block_named(name))
    }

    /// The first block called `name` directly inside this one.
    pub fn block(&self, name: &str) -> Option<&Block> {
        self.items.iter().find_map(|i| i.block_named(name))
    }

    /// The statements with `keyword` directly inside this block.
    pub fn statements<'a>(&'a self, keyword: &'a str) -> impl Iterator<Item = &'a Statement> + 'a {
        self.items
            .iter()
            .filter_map(move |i| i.statement_with(keyword))
    }

    /// The first statement with `keyword` directly inside this block.
    pub fn statement(&self, keyword: &str) -> Option<&Statement> {
        self.items.iter().find_map(|i| i.statement_with(keyword))
    }

    /// The block as errors name it: `main_body blade1` for a block with a `name` statement.
    pub fn title(&self) -> String {
        match self.statement("name").and_then(|s| s.values.first()) {
            Some(n) => format!("{} {n}", self.name),
            None => self.name.clone(),
        }
    }
}

/// Where in the model a block sits, for errors: `new_htc_structure › main_body blade1 › c2_def`.
#[derive(Debug, Clone)]
pub(super) struct Trail(pub(super) Vec<String>);

impl Trail {
    pub(super) fn within(&self, block: &Block) -> Trail {
        let mut t = self.0.clone();
        t.push(block.title());
        Trail(t)
    }

    pub(super) fn error(&self, file: &str, line: usize, message: impl std::fmt::Display) -> Error {
        Error::format(file, line, format!("in {}: {message}", self.0.join(" › ")))
    }

    /// The error for a statement `block` lacks.
    pub(super) fn missing(&self, block: &Block, expected: &str) -> Error {
        self.error(
            &block.file,
            block.line,
            format!("expected {expected}, found none"),
        )
    }
}

/// A `sec` of a `c2_def`: a point of the half-chord line in the body's frame and the twist
/// there, as written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct C2Section {
    /// m, in the body's frame (for a blade: `z` along the pitch axis from the root, `y` out of
    /// the rotor plane, `x` in it).
    pub x: f64,
    pub y: f64,
    pub z: f64,
    /// Degrees about `z`, in HAWC2's sense (docs/model.md §11.6).
    pub twist_deg: f64,
    pub line: usize,
}

/// A body's `timoschenko_input`: which st file, set and subset, and whether it is fully populated.
#[derive(Debug, Clone, PartialEq)]
pub struct TimoshenkoInput {
    /// As written (relative to the model's root).
    pub filename: String,
    /// `FPM 1`: the st file holds fully populated matrices (HAWC2's default is 0, the classic
    /// columns).
    pub fpm: bool,
    pub set: usize,
    pub subset: usize,
    pub file: String,
    pub line: usize,
}

/// A body's damping statement (`damping_posdef` or `damping_aniso`): mass- and
/// stiffness-proportional factors about the body's x, y, z, as written.
#[derive(Debug, Clone, PartialEq)]
pub struct HtcDamping {
    pub keyword: String,
    pub mass: [f64; 3],
    pub stiffness: [f64; 3],
    pub file: String,
    pub line: usize,
}

/// The main body of a blade.
#[derive(Debug, Clone, PartialEq)]
pub struct HtcBody {
    /// The name asked for; `source` the body whose statements it copies (`copy_main_body`).
    pub name: String,
    pub source: String,
    /// Sections in `sec` order.
    pub c2_def: Vec<C2Section>,
    pub timoshenko: TimoshenkoInput,
    pub damping: Option<HtcDamping>,
    /// Where the `c2_def` block begins, for errors about its sections.
    pub c2_file: String,
    pub c2_line: usize,
}

/// A value of the `aero` block that names a file, with where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Named {
    pub value: String,
    pub file: String,
    pub line: usize,
}

/// What the `aero` block says about one blade.
#[derive(Debug, Clone, PartialEq)]
pub struct HtcAero {
    pub ae_filename: Named,
    pub pc_filename: Named,
    /// The ae set of the blade (`ae_sets`, at the blade's `link` number).
    pub ae_set: usize,
    /// The `link` number the body is attached as.
    pub blade: usize,
}

/// A blade as an htc model describes it: its main body and, if the model has an `aero` block,
/// its aerodynamic files.
#[derive(Debug, Clone, PartialEq)]
pub struct HtcBlade {
    pub body: HtcBody,
    pub aero: Option<HtcAero>,
}

/// The main body `name` of `model` (in `new_htc_structure`) and what the `aero` block says of
/// it. A body not found lists the bodies there; a missing `c2_def` or `timoschenko_input` is an
/// error, never a default.
pub fn blade(model: &Block, name: &str) -> Result<HtcBlade> {
    let top = Trail(Vec::new());
    let structure = model.block("new_htc_structure").ok_or_else(|| {
        Error::format(
            &model.file,
            0,
            "expected a 'begin new_htc_structure;' block, found none",
        )
    })?;
    let trail = top.within(structure);
    let (block, source) = main_body(structure, name, &trail)?;
    let trail = trail.within(block);
    let c2 = block
        .block("c2_def")
        .ok_or_else(|| trail.missing(block, "a 'begin c2_def;' block"))?;
    let body = HtcBody {
        name: name.to_string(),
        source: source.to_string(),
        c2_def: c2_def(c2, &trail.within(c2))?,
        timoshenko: timoshenko_input(block, &trail)?,
        damping: damping(block, &trail)?,
        c2_file: c2.file.clone(),
        c2_line: c2.line,
    };
    let aero = match model.block("aero") {
        Some(a) => Some(aero(a, name, &top.within(a))?),
        None => None,
    };
    Ok(HtcBlade { body, aero })
}

/// The `main_body` block called `name`, or the one it copies (`copy_main_body`), with the name
/// of the block whose statements it has.
pub(super) fn main_body<'a>(
    structure: &'a Block,
    name: &str,
    trail: &Trail,
) -> Result<(&'a Block, String)> {
    let name_of = |b: &Block| {
        b.statement("name")
            .and_then(|s| s.values.first())
            .cloned()
            .unwrap_or_default()
    };
    let find = |wanted: &str| structure.blocks("main_body").find(|b| name_of(b) == wanted);
    let mut wanted = name.to_string();
    for _ in 0..MAX_INCLUDE_DEPTH {
        let Some(block) = find(&wanted) else {
            let names: Vec<String> = structure.blocks("main_body").map(name_of).collect();
            return Err(trail.error(
                &structure.file,
                structure.line,
                format!(
                    "no main_body named '{wanted}'; the bodies there: {}",
                    names.join(", ")
                ),
            ));
        };
        match block.statement("copy_main_body") {
            Some(copy) => {
                wanted = copy.values.first().cloned().ok_or_else(|| {
                    trail.error(&copy.file, copy.line, "expected 'copy_main_body <body>;'")
                })?
            }
            None => return Ok((block, wanted)),
        }
    }
    Err(trail.error(
        &structure.file,
        structure.line,
        format!("main_body '{name}': copy_main_body goes round in a circle"),
    ))
}

/// The numbers of `s`, exactly `n` of them, or the error saying `expected`.
pub(super) fn numbers(s: &Statement, n: usize, trail: &Trail, expected: &str) -> Result<Vec<f64>> {
    let values: Option<Vec<f64>> = s.values.iter().map(|v| parse_number(v)).collect();
    match values {
        Some(v) if v.len() == n => Ok(v),
        _ => Err(trail.error(
            &s.file,
            s.line,
            format!(
                "expected '{expected}', found '{} {}'",
                s.keyword,
                s.values.join(" ")
            ),
        )),
    }
}

/// A whole number ≥ 1 written as a number.
pub(super) fn count(v: f64) -> Option<usize> {
    (v.fract() == 0.0 && (1.0..=1e6).contains(&v)).then_some(v as usize)
}

const SEC: &str = "sec <i> <x> <y> <z> <twist>;";

/// `nsec n;` and its `n` sections, numbered 1…n, in number order.
pub(super) fn c2_def(c2: &Block, trail: &Trail) -> Result<Vec<C2Section>> {
    let nsec = c2
        .statement("nsec")
        .ok_or_else(|| trail.missing(c2, "'nsec <count>;'"))?;
    let n = numbers(nsec, 1, trail, "nsec <count>;")
        .ok()
        .and_then(|v| count(v[0]))
        .filter(|&n| n >= 2)
        .ok_or_else(|| {
            trail.error(
                &nsec.file,
                nsec.line,
                format!(
                    "expected 'nsec <count>;' with a count of at least 2, found 'nsec {}'",
                    nsec.values.join(" ")
                ),
            )
        })?;
    // Counted before anything is allocated: a mistyped nsec must not size the table.
    let written = c2.statements("sec").count();
    if written != n {
        return Err(trail.error(
            &nsec.file,
            nsec.line,
            format!("nsec = {n}, but {written} '{SEC}' statements follow"),
        ));
    }
    let mut sections: Vec<Option<C2Section>> = vec![None; n];
    for s in c2.statements("sec") {
        let v = numbers(s, 5, trail, SEC)?;
        let slot = count(v[0]).filter(|&i| i <= n).ok_or_else(|| {
            trail.error(
                &s.file,
                s.line,
                format!(
                    "expected a section number from 1 to nsec = {n}, found {}",
                    v[0]
                ),
            )
        })?;
        if sections[slot - 1].is_some() {
            return Err(trail.error(&s.file, s.line, format!("section {slot} given twice")));
        }
        sections[slot - 1] = Some(C2Section {
            x: v[1],
            y: v[2],
            z: v[3],
            twist_deg: v[4],
            line: s.line,
        });
    }
    Ok(sections
        .into_iter()
        .map(|s| s.expect("all counted"))
        .collect())
}

/// The body's `timoschenko_input` block (HAWC2's spelling; `timoshenko_input` is taken too):
/// `filename`, `set`, and `FPM` (0 unless given).
pub(super) fn timoshenko_input(body: &Block, trail: &Trail) -> Result<TimoshenkoInput> {
    let t = body
        .block("timoschenko_input")
        .or_else(|| body.block("timoshenko_input"))
        .ok_or_else(|| trail.missing(body, "a 'begin timoschenko_input;' block"))?;
    let trail = trail.within(t);
    let filename = t
        .statement("filename")
        .ok_or_else(|| trail.missing(t, "'filename <st file>;'"))?;
    let [name] = filename.values.as_slice() else {
        return Err(trail.error(
            &filename.file,
            filename.line,
            "expected 'filename <st file>;'",
        ));
    };
    let set = t
        .statement("set")
        .ok_or_else(|| trail.missing(t, "'set <set> <subset>;'"))?;
    let bad_set = || {
        trail.error(
            &set.file,
            set.line,
            "expected 'set <set> <subset>;' of whole numbers ≥ 1",
        )
    };
    let v = numbers(set, 2, &trail, "set <set> <subset>;")?;
    let (Some(set_no), Some(subset)) = (count(v[0]), count(v[1])) else {
        return Err(bad_set());
    };
    let fpm = match t.statement("fpm") {
        None => false,
        Some(s) => match numbers(s, 1, &trail, "FPM 0;' or 'FPM 1;")?[0] {
            0.0 => false,
            1.0 => true,
            other => {
                return Err(trail.error(
                    &s.file,
                    s.line,
                    format!("expected 'FPM 0;' or 'FPM 1;', found 'FPM {other}'"),
                ))
            }
        },
    };
    Ok(TimoshenkoInput {
        filename: name.clone(),
        fpm,
        set: set_no,
        subset,
        file: filename.file.clone(),
        line: filename.line,
    })
}

/// The body's `damping_posdef` or `damping_aniso` statement, if it has one.
pub(super) fn damping(body: &Block, trail: &Trail) -> Result<Option<HtcDamping>> {
    let found = body.items.iter().find_map(|i| match i {
        Item::Statement(s) if matches!(s.keyword.as_str(), "damping_posdef" | "damping_aniso") => {
            Some(s)
        }
        _ => None,
    });
    let Some(s) = found else { return Ok(None) };
    let v = numbers(
        s,
        6,
        trail,
        &format!("{} <mx> <my> <mz> <kx> <ky> <kz>;", s.keyword),
    )?;
    Ok(Some(HtcDamping {
        keyword: s.keyword.clone(),
        mass: [v[0], v[1], v[2]],
        stiffness: [v[3], v[4], v[5]],
        file: s.file.clone(),
        line: s.line,
    }))
}

/// A statement of one file name in the `aero` block.
fn named(aero: &Block, keyword: &str, trail: &Trail) -> Result<Named> {
    let s = aero
        .statement(keyword)
        .ok_or_else(|| trail.missing(aero, &format!("'{keyword} <file>;'")))?;
    match s.values.as_slice() {
        [value] => Ok(Named {
            value: value.clone(),
            file: s.file.clone(),
            line: s.line,
        }),
        _ => Err(trail.error(&s.file, s.line, format!("expected '{keyword} <file>;'"))),
    }
}

/// The `aero` block's files and the ae set of the blade `link`ed to body `name`.
fn aero(a: &Block, name: &str, trail: &Trail) -> Result<HtcAero> {
    let mut links = Vec::new();
    for s in a.statements("link") {
        match s.values.as_slice() {
            [i, kind, body] if kind.eq_ignore_ascii_case("mbdy_c2_def") => {
                let i = parse_number(i).and_then(count).ok_or_else(|| {
                    trail.error(
                        &s.file,
                        s.line,
                        "expected 'link <blade> mbdy_c2_def <body>;'",
                    )
                })?;
                links.push((i, body.clone()));
            }
            _ => {
                return Err(trail.error(
                    &s.file,
                    s.line,
                    "expected 'link <blade> mbdy_c2_def <body>;'",
                ))
            }
        }
    }
    let blade = links
        .iter()
        .find(|(_, body)| body == name)
        .map(|(i, _)| *i)
        .ok_or_else(|| {
            trail.error(
                &a.file,
                a.line,
                format!(
                    "no 'link <blade> mbdy_c2_def {name};'; the bodies linked: {}",
                    links
                        .iter()
                        .map(|(_, b)| b.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
    let sets = a
        .statement("ae_sets")
        .ok_or_else(|| trail.missing(a, "'ae_sets <set of blade 1> …;'"))?;
    let ae_set = sets
        .values
        .get(blade - 1)
        .and_then(|v| parse_number(v))
        .and_then(count)
        .ok_or_else(|| {
            trail.error(
                &sets.file,
                sets.line,
                format!(
                    "expected an ae set (a whole number ≥ 1) for blade {blade} (linked to \
                     {name}), found 'ae_sets {}'",
                    sets.values.join(" ")
                ),
            )
        })?;
    Ok(HtcAero {
        ae_filename: named(a, "ae_filename", trail)?,
        pc_filename: named(a, "pc_filename", trail)?,
        ae_set,
        blade,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_includes(path: &str) -> Result<(String, String)> {
        Err(Error::format(path, 0, "no such file"))
    }

    fn parse(text: &str) -> Result<Block> {
        parse_htc(text, "m.htc", &mut no_includes)
    }

    const BLADE: &str = "\
begin new_htc_structure;   comment after the statement
  begin main_body;  blade
    name   blade1 ;
    damping_aniso  0.0 0.0 0.0 3.0e-3 2.0e-3 1.0e-8 ; tuned
    begin timoschenko_input ;
      filename ./data/st.dat;  the st file
      FPM 1;
      set 1 2 ;
    end timoschenko_input;
    begin c2_def;
      nsec 3 ;
      sec 1 0.0 0.0  0.0 -15.0;
      sec 3 0.1 -4.0 100.0 1.0;
      sec 2 0.0 0.5 50.0 -5.0;
    end c2_def ;
  end main_body;
  begin main_body;
    name blade2;
    copy_main_body blade1;
  end main_body;
end new_htc_structure;
begin aero;
  link 1 mbdy_c2_def blade1;
  link 2 mbdy_c2_def blade2;
  ae_filename ./data/ae.dat ;
  pc_filename ./data/pc.dat ;
  ae_sets 1 3;
end aero;
exit;
this line is after exit and never read
";

    /// Blocks nest, `;` ends a statement and what follows it is a comment, sections are put
    /// in their number order, a copied body has the statements of the one it copies, and
    /// nothing after `exit;` is read.
    #[test]
    fn blocks_nest_and_comments_are_skipped() {
        let model = parse(BLADE).unwrap();
        let b = blade(&model, "blade1").unwrap();
        let z: Vec<f64> = b.body.c2_def.iter().map(|s| s.z).collect();
        assert_eq!(z, [0.0, 50.0, 100.0]);
        assert_eq!(b.body.c2_def[2].twist_deg, 1.0);
        assert_eq!(b.body.c2_def[2].line, 13);
        let t = &b.body.timoshenko;
        assert_eq!(
            (t.filename.as_str(), t.fpm, t.set, t.subset),
            ("./data/st.dat", true, 1, 2)
        );
        let d = b.body.damping.as_ref().unwrap();
        assert_eq!(
            (d.keyword.as_str(), d.stiffness),
            ("damping_aniso", [3.0e-3, 2.0e-3, 1.0e-8])
        );
        let aero = b.aero.unwrap();
        assert_eq!(
            (aero.ae_filename.value.as_str(), aero.ae_set),
            ("./data/ae.dat", 1)
        );
        let copy = blade(&model, "blade2").unwrap();
        assert_eq!(
            (copy.body.source.as_str(), copy.aero.unwrap().ae_set),
            ("blade1", 3)
        );
        assert_eq!(copy.body.c2_def, b.body.c2_def);
    }

    /// `continue_in_file` reads the named file in its place (blocks may continue across it),
    /// and `exit;` in an included file returns to the one that included it.
    #[test]
    fn continue_in_file_reads_the_file_in_place() {
        let main = "begin new_htc_structure;\n  continue_in_file ../shared/bodies.htc;\nend new_htc_structure;\n";
        let bodies =
            "begin main_body;\n name tower;\n end main_body;\nexit;\nbegin main_body; never read\n";
        let mut asked = Vec::new();
        let mut include = |path: &str| {
            asked.push(path.to_string());
            Ok(("bodies.htc".to_string(), bodies.to_string()))
        };
        let model = parse_htc(main, "main.htc", &mut include).unwrap();
        assert_eq!(asked, ["../shared/bodies.htc"]);
        let s = model.block("new_htc_structure").unwrap();
        let bodies: Vec<&Block> = s.blocks("main_body").collect();
        assert_eq!(bodies.len(), 1);
        assert_eq!((bodies[0].file.as_str(), bodies[0].line), ("bodies.htc", 1));
        let e = blade(&model, "blade1").unwrap_err().to_string();
        assert!(
            e.contains(
                "in new_htc_structure: no main_body named 'blade1'; the bodies there: tower"
            ),
            "{e}"
        );
    }

    #[test]
    fn a_file_that_includes_itself_is_an_error() {
        let main = "continue_in_file ./self.htc;\n";
        let mut include = |_: &str| Ok(("self.htc".to_string(), main.to_string()));
        let e = parse_htc(main, "self.htc", &mut include)
            .unwrap_err()
            .to_string();
        assert!(e.contains("included more than 16 deep"), "{e}");
    }

    /// Errors name the file, the line and the block.
    #[test]
    fn errors_name_file_line_and_block() {
        let check = |text: &str, expected: &str| {
            let e = parse(text)
                .and_then(|m| blade(&m, "blade1"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(expected), "{e}\n  expected: {expected}");
        };
        check(
            &BLADE.replace("sec 3 0.1 -4.0 100.0 1.0;", "sec 3 0.1 -4.0 1.0;"),
            "m.htc:13: in new_htc_structure › main_body blade1 › c2_def: expected 'sec <i> <x> <y> <z> <twist>;', found 'sec 3 0.1 -4.0 1.0'",
        );
        check(
            &BLADE.replace("nsec 3", "nsec 4"),
            "m.htc:11: in new_htc_structure › main_body blade1 › c2_def: nsec = 4, but 3",
        );
        check(
            &BLADE.replace("      set 1 2 ;\n", ""),
            "m.htc:5: in new_htc_structure › main_body blade1 › timoschenko_input: expected 'set <set> <subset>;', found none",
        );
        check(
            &BLADE
                .replace("begin c2_def;", "begin c2_defs;")
                .replace("end c2_def ;", "end c2_defs;"),
            "m.htc:2: in new_htc_structure › main_body blade1: expected a 'begin c2_def;' block",
        );
        check(
            &BLADE.replace("end c2_def ;", ""),
            "m.htc:16: expected 'end c2_def;' (the block begun at m.htc:10), found 'end main_body'",
        );
        check(
            &BLADE.replace("ae_sets 1 3;", "ae_sets x;"),
            "m.htc:27: in aero: expected an ae set",
        );
        check("begin aero;\n", "m.htc:1: block 'aero' has no 'end aero;'");
        check("end aero;\n", "m.htc:1: 'end aero' closes no block");
        check(
            "nsec 3\n",
            "m.htc:1: expected a statement ended by ';', found 'nsec 3'",
        );
    }
}
