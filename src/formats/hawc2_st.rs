//! HAWC2 structural (st) files: sets `#N` of subsets `$N <rows>` of sectional properties along
//! a main body, anything else being free text.
//!
//! A subset's column count decides its kind: 19 columns are the classic isotropic beam (E, G,
//! area moments, shear factors), 30 the fully populated 6×6 stiffness (FPM). Positions are in
//! HAWC2's cross-section frame, relative to the half-chord reference line (`c2_def`); `pitch`
//! is the angle of the principal bending axes from the chord (docs/model.md §11.6).
//!
//! The file's first line conventionally gives the number of sets, but HAWC2 finds sets by their
//! `#N` marks and so does this reader (the IEA 15MW noFPM file says 1 and holds 2).

use super::text::{array, numbers, read_text, Row, Source, Table};
use crate::error::{Error, Result};
use std::path::Path;

/// A classic (19-column) st row, in the file's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClassicRow {
    /// 1-based line of the row in the file, for errors about its values.
    pub line: usize,
    /// Curved length along the main body from its node 1, m.
    pub r: f64,
    /// Mass per unit length, kg/m.
    pub m: f64,
    /// Centre of gravity, m.
    pub x_cg: f64,
    pub y_cg: f64,
    /// Radii of gyration about the elastic centre, m.
    pub ri_x: f64,
    pub ri_y: f64,
    /// Shear centre, m.
    pub x_sh: f64,
    pub y_sh: f64,
    /// Young's modulus, N/m².
    pub e: f64,
    /// Shear modulus, N/m².
    pub g: f64,
    /// Area moments of inertia about the principal axes, m⁴.
    pub i_x: f64,
    pub i_y: f64,
    /// Torsional stiffness constant (HAWC2's `K`, written `I_p`), m⁴.
    pub i_p: f64,
    /// Shear factors, dimensionless.
    pub k_x: f64,
    pub k_y: f64,
    /// Cross-section area, m².
    pub a: f64,
    /// Structural pitch: the angle about `z_c2` from `x_c2` to the principal bending axis `x_e`,
    /// degrees.
    pub pitch_deg: f64,
    /// Elastic centre, m.
    pub x_e: f64,
    pub y_e: f64,
}

/// A fully populated (30-column) st row, in the file's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FpmRow {
    /// 1-based line of the row in the file, for errors about its values.
    pub line: usize,
    /// Curved length along the main body from its node 1, m.
    pub r: f64,
    /// Mass per unit length, kg/m.
    pub m: f64,
    /// Centre of gravity, m.
    pub x_cg: f64,
    pub y_cg: f64,
    /// Radii of gyration about the elastic centre, m.
    pub ri_x: f64,
    pub ri_y: f64,
    /// Structural pitch: the angle about `z_c2` from `x_c2` to the principal axis `x_e` along
    /// which the stiffness matrix is given, degrees.
    pub pitch_deg: f64,
    /// Elastic centre, m.
    pub x_e: f64,
    pub y_e: f64,
    /// Upper triangle of the symmetric sectional stiffness matrix at the elastic centre along the
    /// principal axes, row by row as in the file:
    /// K11 K12 K13 K14 K15 K16 K22 … K26 K33 … K66 (N, N·m, N·m² by block).
    pub k: [f64; 21],
}

impl FpmRow {
    /// The full symmetric 6×6 matrix the file's upper triangle stands for.
    pub fn stiffness(&self) -> [[f64; 6]; 6] {
        let mut out = [[0.0; 6]; 6];
        let upper = (0..6).flat_map(|i| (i..6).map(move |j| (i, j)));
        for ((i, j), &v) in upper.zip(&self.k) {
            out[i][j] = v;
            out[j][i] = v;
        }
        out
    }
}

/// The rows of a subset: all classic or all fully populated.
#[derive(Debug, Clone, PartialEq)]
pub enum StRows {
    Classic(Vec<ClassicRow>),
    FullyPopulated(Vec<FpmRow>),
}

impl StRows {
    pub fn len(&self) -> usize {
        match self {
            StRows::Classic(rows) => rows.len(),
            StRows::FullyPopulated(rows) => rows.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct StSubset {
    /// The `N` of `$N`.
    pub number: usize,
    /// The declared number of rows, `r` strictly increasing.
    pub rows: StRows,
}

#[derive(Debug, Clone, PartialEq)]
pub struct StSet {
    /// The `N` of `#N`.
    pub number: usize,
    pub subsets: Vec<StSubset>,
}

/// An st file: its sets in file order, and its name for [`StFile::subset`]'s errors.
#[derive(Debug, Clone, PartialEq)]
pub struct StFile {
    pub path: String,
    pub sets: Vec<StSet>,
}

impl StFile {
    /// Subset `$subset` of set `#set`, as an htc `st_file … set <set> <subset>` line asks for.
    pub fn subset(&self, set: usize, subset: usize) -> Result<&StSubset> {
        self.sets
            .iter()
            .find(|s| s.number == set)
            .and_then(|s| s.subsets.iter().find(|u| u.number == subset))
            .ok_or_else(|| {
                let available: Vec<String> = self
                    .sets
                    .iter()
                    .map(|s| {
                        let subs: Vec<String> =
                            s.subsets.iter().map(|u| format!("${}", u.number)).collect();
                        format!("#{} ({})", s.number, subs.join(" "))
                    })
                    .collect();
                Error::format(
                    self.path.clone(),
                    0,
                    format!(
                        "no subset ${subset} in set #{set}; the file has sets {}",
                        available.join(", ")
                    ),
                )
            })
    }
}

const CLASSIC: [&str; 19] = [
    "r", "m", "x_cg", "y_cg", "ri_x", "ri_y", "x_sh", "y_sh", "E", "G", "I_x", "I_y", "I_p", "k_x",
    "k_y", "A", "pitch", "x_e", "y_e",
];
const FPM: [&str; 30] = [
    "r", "m", "x_cg", "y_cg", "ri_x", "ri_y", "pitch", "x_e", "y_e", "K11", "K12", "K13", "K14",
    "K15", "K16", "K22", "K23", "K24", "K25", "K26", "K33", "K34", "K35", "K36", "K44", "K45",
    "K46", "K55", "K56", "K66",
];

pub fn read_st(path: &Path) -> Result<StFile> {
    parse_st(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an st file; `origin` names it in errors.
pub fn parse_st(text: &str, origin: &str) -> Result<StFile> {
    let src = Source::new(origin, text);
    let mut sets: Vec<(usize, StSet)> = Vec::new();
    let mut idx = 0;
    while idx < src.lines.len() {
        let line = src.line(idx).trim_ascii_start();
        if let Some(rest) = line.strip_prefix('#') {
            let number = mark_number(&src, idx, rest, "set", '#')?;
            if sets.iter().any(|(_, s)| s.number == number) {
                return Err(src.err(idx, format!("set #{number} appears twice")));
            }
            sets.push((
                idx,
                StSet {
                    number,
                    subsets: Vec::new(),
                },
            ));
            idx += 1;
        } else if let Some(rest) = line.strip_prefix('$') {
            let Some((_, set)) = sets.last_mut() else {
                return Err(src.err(idx, "expected a set '#N' before the subset '$N <rows>'"));
            };
            let (subset, next) = subset(&src, idx, rest, set.number)?;
            if set.subsets.iter().any(|s| s.number == subset.number) {
                return Err(src.err(
                    idx,
                    format!(
                        "subset ${} appears twice in set #{}",
                        subset.number, set.number
                    ),
                ));
            }
            set.subsets.push(subset);
            idx = next;
        } else {
            idx += 1;
        }
    }
    if sets.is_empty() {
        return Err(src.missing(
            "expected sets '#N' of subsets '$N <rows>' (a HAWC2 st file)",
            0,
        ));
    }
    if let Some((line, set)) = sets.iter().find(|(_, s)| s.subsets.is_empty()) {
        return Err(src.err(
            *line,
            format!(
                "expected a subset '$N <rows>' in set #{}, found none",
                set.number
            ),
        ));
    }
    Ok(StFile {
        path: origin.to_string(),
        sets: sets.into_iter().map(|(_, s)| s).collect(),
    })
}

/// The number right after a `#` or `$` mark.
fn mark_number(src: &Source, idx: usize, rest: &str, what: &str, mark: char) -> Result<usize> {
    rest.split_ascii_whitespace()
        .next()
        .and_then(|t| t.parse::<usize>().ok())
        .ok_or_else(|| {
            src.err(
                idx,
                format!(
                    "expected a {what} number right after '{mark}' (e.g. '{mark}1'), found '{}'",
                    src.excerpt(idx)
                ),
            )
        })
}

/// The subset whose `$N <rows>` line is `idx`; returns it and the index after its rows.
fn subset(src: &Source, idx: usize, rest: &str, set: usize) -> Result<(StSubset, usize)> {
    let number = mark_number(src, idx, rest, "subset", '$')?;
    let n_rows = rest
        .split_ascii_whitespace()
        .nth(1)
        .and_then(|t| t.parse::<usize>().ok())
        .filter(|&n| n >= 1)
        .ok_or_else(|| {
            src.err(
                idx,
                format!(
                    "expected '${number} <number of rows>' for subset ${number} of set #{set}, found '{}'",
                    src.excerpt(idx)
                ),
            )
        })?;
    let place = format!("in subset ${number} of set #{set}");
    let first = src.next_content(idx + 1).ok_or_else(|| {
        src.eof(&format!(
            "expected {n_rows} rows of 19 (classic) or 30 (fully populated) numbers {place}"
        ))
    })?;
    let width = src.tokens(first).len();
    let columns: &[&str] = match width {
        19 => &CLASSIC,
        30 => &FPM,
        _ => {
            return Err(src.err(
                first,
                format!(
                    "expected {n_rows} rows of 19 numbers (classic: {}) or 30 (fully populated: {}) {place}, found {width} value(s)",
                    CLASSIC.join(" "),
                    FPM.join(" ")
                ),
            ))
        }
    };
    let table = Table::new(n_rows, "rows", columns).at(place);
    let (rows, next) = src.rows(first, &table)?;
    src.increasing(&rows, 0, "r")?;
    // One row too many means the count and the table disagree; HAWC2 would drop it silently.
    if let Some(extra) = src.next_content(next) {
        if numbers(&src.tokens(extra)).is_some_and(|v| v.len() == width) {
            return Err(src.err(
                extra,
                format!(
                    "subset ${number} of set #{set} declares {n_rows} rows, but this line holds another"
                ),
            ));
        }
    }
    let rows = match width {
        19 => StRows::Classic(rows.iter().map(classic).collect()),
        _ => StRows::FullyPopulated(rows.iter().map(fpm).collect()),
    };
    Ok((StSubset { number, rows }, next))
}

fn classic(row: &Row) -> ClassicRow {
    let [r, m, x_cg, y_cg, ri_x, ri_y, x_sh, y_sh, e, g, i_x, i_y, i_p, k_x, k_y, a, pitch_deg, x_e, y_e] =
        array(&row.values);
    ClassicRow {
        line: row.idx + 1,
        r,
        m,
        x_cg,
        y_cg,
        ri_x,
        ri_y,
        x_sh,
        y_sh,
        e,
        g,
        i_x,
        i_y,
        i_p,
        k_x,
        k_y,
        a,
        pitch_deg,
        x_e,
        y_e,
    }
}

fn fpm(row: &Row) -> FpmRow {
    let [r, m, x_cg, y_cg, ri_x, ri_y, pitch_deg, x_e, y_e] = array(&row.values);
    FpmRow {
        line: row.idx + 1,
        r,
        m,
        x_cg,
        y_cg,
        ri_x,
        ri_y,
        pitch_deg,
        x_e,
        y_e,
        k: array(row.values.get(9..).unwrap_or(&[])),
    }
}
