//! HAWC2 aerodynamic inputs — the ae file (chord, relative thickness and profile set along the
//! blade), the pc file (profile coefficients by relative thickness) — and the steady operation
//! (`.opt`) table of pitch and rotor speed against wind speed.
//!
//! These files count their blocks and rows in header lines and leave the rest of a header line
//! as free text; data rows are read like Fortran list-directed reads, so text after the needed
//! numbers of a row is ignored.

use super::text::{read_text, value, whole, Row, Source, Table};
use crate::error::Result;
use std::path::Path;

/// One ae row, in the file's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AeRow {
    /// Curved length along the blade from the root, m.
    pub r: f64,
    /// Chord, m.
    pub chord: f64,
    /// Relative thickness (thickness / chord), percent.
    pub thickness_pct: f64,
    /// Number of the pc set the profiles are taken from.
    pub pc_set: usize,
}

#[derive(Debug, Clone, PartialEq)]
pub struct AeSet {
    /// The set number as written (sets are numbered 1, 2, … in file order).
    pub number: usize,
    /// `r` strictly increasing.
    pub rows: Vec<AeRow>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct AeFile {
    pub sets: Vec<AeSet>,
}

/// One profile of a pc set: static coefficients against angle of attack.
#[derive(Debug, Clone, PartialEq)]
pub struct PcProfile {
    /// The profile number as written (1, 2, … within its set).
    pub number: usize,
    /// Relative thickness the profile stands for, percent.
    pub thickness_pct: f64,
    /// Angle of attack, degrees, strictly increasing.
    pub alpha_deg: Vec<f64>,
    pub cl: Vec<f64>,
    pub cd: Vec<f64>,
    pub cm: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct PcSet {
    pub profiles: Vec<PcProfile>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct PcFile {
    pub sets: Vec<PcSet>,
}

/// The steady operation table, one entry per row, in the units HAWC2 defines for it.
#[derive(Debug, Clone, PartialEq)]
pub struct OperationTable {
    /// Wind speed, m/s, strictly increasing.
    pub wind_speed: Vec<f64>,
    /// Blade pitch, degrees.
    pub pitch_deg: Vec<f64>,
    /// Rotor speed, rpm.
    pub rotor_speed_rpm: Vec<f64>,
    /// Aerodynamic power, kW, when the header names the column.
    pub aero_power_kw: Option<Vec<f64>>,
    /// Aerodynamic thrust, kN, when the header names the column.
    pub aero_thrust_kn: Option<Vec<f64>>,
}

pub fn read_ae(path: &Path) -> Result<AeFile> {
    parse_ae(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an ae file: a line with the number of sets, then per set a line
/// `<set number> <rows>` and its rows `r chord thickness pc_set`. `origin` names it in errors.
pub fn parse_ae(text: &str, origin: &str) -> Result<AeFile> {
    let src = Source::new(origin, text);
    let (n_sets, mut pos) = counts(&src, 0, "the number of ae sets", 1)?;
    let mut sets = Vec::new();
    for s in 1..=n_sets {
        let (n_rows, next) = numbered(&src, pos, s, &format!("ae set {s} of {n_sets}"))?;
        let table = Table::new(n_rows, "rows", &["r", "chord", "thickness", "pc_set"])
            .at(format!("in ae set {s}"))
            .at_least();
        let (rows, next) = src.rows(next, &table)?;
        src.increasing(&rows, 0, "r")?;
        let rows = rows
            .iter()
            .map(|r| {
                Ok(AeRow {
                    r: value(r, 0),
                    chord: value(r, 1),
                    thickness_pct: value(r, 2),
                    pc_set: whole(&src, r, 3, "the pc set number", 1)?,
                })
            })
            .collect::<Result<_>>()?;
        sets.push(AeSet { number: s, rows });
        pos = next;
    }
    Ok(AeFile { sets })
}

pub fn read_pc(path: &Path) -> Result<PcFile> {
    parse_pc(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of a pc file: a line with the number of sets, then per set a line with its
/// number of profiles, and per profile a line `<profile number> <rows> <thickness %>` and its
/// rows `alpha cl cd cm`. `origin` names it in errors.
pub fn parse_pc(text: &str, origin: &str) -> Result<PcFile> {
    let src = Source::new(origin, text);
    let (n_sets, mut pos) = counts(&src, 0, "the number of pc sets", 1)?;
    let mut sets = Vec::new();
    for s in 1..=n_sets {
        let (n_profiles, next) = counts(
            &src,
            pos,
            &format!("the number of profiles in pc set {s}"),
            1,
        )?;
        pos = next;
        let mut profiles = Vec::new();
        for p in 1..=n_profiles {
            let what = format!("profile {p} of {n_profiles} in pc set {s}");
            let (n_rows, next) = numbered(&src, pos, p, &what)?;
            let header = next - 1;
            let thickness_pct = src
                .tokens(header)
                .get(2)
                .and_then(|t| super::text::parse_number(t))
                .ok_or_else(|| {
                    src.err(
                        header,
                        format!(
                            "expected '{p} <rows> <thickness %>' for {what}, found '{}'",
                            src.excerpt(header)
                        ),
                    )
                })?;
            let table = Table::new(n_rows, "rows", &["alpha", "cl", "cd", "cm"])
                .at(format!("in {what}"))
                .at_least();
            let (rows, next) = src.rows(next, &table)?;
            src.increasing(&rows, 0, "alpha")?;
            let col = |c: usize| rows.iter().map(|r: &Row| value(r, c)).collect();
            profiles.push(PcProfile {
                number: p,
                thickness_pct,
                alpha_deg: col(0),
                cl: col(1),
                cd: col(2),
                cm: col(3),
            });
            pos = next;
        }
        sets.push(PcSet { profiles });
    }
    Ok(PcFile { sets })
}

pub fn read_opt(path: &Path) -> Result<OperationTable> {
    parse_opt(&read_text(path)?, &path.display().to_string())
}

/// What an `.opt` column holds, recognised by its header name.
#[derive(Debug, Clone, Copy, PartialEq)]
enum OptColumn {
    Wind,
    Pitch,
    Rotor,
    Power,
    Thrust,
}

impl OptColumn {
    /// (column, its name in errors, words that name it in a header, the unit HAWC2 defines).
    const ALL: [(
        OptColumn,
        &'static str,
        &'static [&'static str],
        &'static str,
    ); 5] = [
        (OptColumn::Wind, "wind_speed", &["wind", "wsp"], "m/s"),
        (OptColumn::Pitch, "pitch", &["pitch"], "deg"),
        (
            OptColumn::Rotor,
            "rotor_speed",
            &["rot", "rpm", "omega"],
            "rpm",
        ),
        (OptColumn::Power, "aero_power", &["power"], "kw"),
        (OptColumn::Thrust, "aero_thrust", &["thrust"], "kn"),
    ];

    fn name(self) -> &'static str {
        OptColumn::ALL
            .iter()
            .find(|(k, ..)| *k == self)
            .map_or("", |(_, name, ..)| name)
    }
}

/// Parses the text of an `.opt` file: a line with the number of rows (optionally followed by
/// column names with units in brackets, `wind speed [m/s] pitch [deg] …`), then the rows. With
/// named columns the header decides the order and the units must be HAWC2's (m/s, deg, rpm, kW,
/// kN); without, the first three columns are HAWC2's wind speed, pitch and rotor speed and
/// nothing else is read. `origin` names it in errors.
pub fn parse_opt(text: &str, origin: &str) -> Result<OperationTable> {
    let src = Source::new(origin, text);
    let (n_rows, next) = counts(&src, 0, "the number of operating points", 1)?;
    let header = next - 1;
    let columns = opt_columns(&src, header)?;
    let names: Vec<&str> = columns.iter().map(|c| c.name()).collect();
    let table = Table::new(n_rows, "operating-point rows", &names).at_least();
    let (rows, _) = src.rows(next, &table)?;
    let col = |which: OptColumn| -> Option<Vec<f64>> {
        let c = columns.iter().position(|&k| k == which)?;
        Some(rows.iter().map(|r| value(r, c)).collect())
    };
    let wind = columns
        .iter()
        .position(|&k| k == OptColumn::Wind)
        .unwrap_or(0);
    src.increasing(&rows, wind, "wind speed")?;
    Ok(OperationTable {
        wind_speed: col(OptColumn::Wind).unwrap_or_default(),
        pitch_deg: col(OptColumn::Pitch).unwrap_or_default(),
        rotor_speed_rpm: col(OptColumn::Rotor).unwrap_or_default(),
        aero_power_kw: col(OptColumn::Power),
        aero_thrust_kn: col(OptColumn::Thrust),
    })
}

/// The columns an `.opt` header names (`name [unit]` after the row count), or HAWC2's first
/// three when it names none.
fn opt_columns(src: &Source, header: usize) -> Result<Vec<OptColumn>> {
    let line = src.line(header).trim_ascii_start();
    let rest = line
        .find(|c: char| c.is_ascii_whitespace())
        .map_or("", |i| &line[i..]);
    if !rest.contains('[') {
        return Ok(vec![OptColumn::Wind, OptColumn::Pitch, OptColumn::Rotor]);
    }
    let mut columns = Vec::new();
    let mut text = rest;
    while let Some(open) = text.find('[') {
        let name = text[..open].trim();
        let close = text[open..].find(']').map(|c| open + c).ok_or_else(|| {
            src.err(
                header,
                format!("expected ']' closing the unit of column '{name}'"),
            )
        })?;
        let unit = text[open + 1..close].trim();
        let lower = name.to_ascii_lowercase();
        let (kind, _, _, want) = OptColumn::ALL
            .iter()
            .find(|(_, _, words, _)| words.iter().any(|w| lower.contains(w)))
            .ok_or_else(|| {
                src.err(
                    header,
                    format!("expected columns wind speed, pitch, rotor speed (and aero power, aero thrust), found '{name}'"),
                )
            })?;
        if !unit.eq_ignore_ascii_case(want) {
            return Err(src.err(
                header,
                format!("column '{name}' is in [{unit}]; expected HAWC2's [{want}]"),
            ));
        }
        if columns.contains(kind) {
            return Err(src.err(header, format!("column '{name}' appears twice")));
        }
        columns.push(*kind);
        text = &text[close + 1..];
    }
    if !text.trim().is_empty() {
        return Err(src.err(
            header,
            format!("expected a unit in brackets after column '{}'", text.trim()),
        ));
    }
    for kind in [OptColumn::Wind, OptColumn::Pitch, OptColumn::Rotor] {
        if !columns.contains(&kind) {
            return Err(src.err(
                header,
                format!(
                    "expected a column {} in the header, found none",
                    kind.name()
                ),
            ));
        }
    }
    Ok(columns)
}

/// A header line whose first word is a count of at least `at_least` (the rest is free text):
/// the count and the index after the line.
fn counts(src: &Source, from: usize, what: &str, at_least: usize) -> Result<(usize, usize)> {
    let expected = format!("expected a line starting with {what}");
    let idx = src.expect_content(from, &expected)?;
    src.tokens(idx)
        .first()
        .and_then(|t| t.parse::<usize>().ok())
        .filter(|&n| n >= at_least)
        .map(|n| (n, idx + 1))
        .ok_or_else(|| {
            src.err(
                idx,
                format!(
                    "{expected} (at least {at_least}), found '{}'",
                    src.excerpt(idx)
                ),
            )
        })
}

/// A block header `<number> <rows> …` whose number must be `number`: the row count and the
/// index after the line.
fn numbered(src: &Source, from: usize, number: usize, what: &str) -> Result<(usize, usize)> {
    let expected = format!("expected the header '{number} <rows> …' of {what}");
    let idx = src.expect_content(from, &expected)?;
    match src.tokens(idx).as_slice() {
        [no, n, ..] if no.parse::<usize>() == Ok(number) => {
            n.parse::<usize>().ok().filter(|&n| n >= 1)
        }
        _ => None,
    }
    .map(|n| (n, idx + 1))
    .ok_or_else(|| src.err(idx, format!("{expected}, found '{}'", src.excerpt(idx))))
}
