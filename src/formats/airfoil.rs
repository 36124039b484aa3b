//! AirfoilInfo polar files (OpenFAST AeroDyn 15): one or more tables of static lift, drag and
//! (optionally) pitching-moment coefficients against angle of attack.
//!
//! Lines starting with `!` are comments anywhere, as in AirfoilInfo. Of the unsteady-aerodynamics
//! block of a table (`InclUAdata` true) the constants the Hansen–Gaunaa–Madsen model reads are
//! kept ([`UaBlock`]); the rest is passed over by its key lines. Airfoil coordinates
//! (`NumCoords`, inline or an `@"file"` reference) are not read.

use super::text::{read_text, value, KeyLine, Row, Source, Table};
use crate::error::Result;
use std::path::Path;

/// Which 1-based column of a polar table holds what (0: the table has no such column).
///
/// OpenFAST takes these from the AeroDyn primary file (`InCol_Alfa` … `InCol_Cpmin`), so pass
/// them from there when they differ from the default Alpha Cl Cd Cm layout; `InCol_*` lines in
/// the polar file itself take precedence.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PolarColumns {
    pub alpha: usize,
    pub cl: usize,
    pub cd: usize,
    pub cm: usize,
    pub cpmin: usize,
}

impl Default for PolarColumns {
    /// Alpha Cl Cd Cm, no Cpmin: the layout of the NREL 5MW and IEA 15MW polars.
    fn default() -> Self {
        PolarColumns {
            alpha: 1,
            cl: 2,
            cd: 3,
            cm: 4,
            cpmin: 0,
        }
    }
}

impl PolarColumns {
    /// The table's column names by position (`-` for a column nothing is read from).
    fn names(&self) -> Vec<&'static str> {
        let named = [
            (self.alpha, "Alpha"),
            (self.cl, "Cl"),
            (self.cd, "Cd"),
            (self.cm, "Cm"),
            (self.cpmin, "Cpmin"),
        ];
        let width = named.iter().map(|&(col, _)| col).max().unwrap_or(0);
        (1..=width)
            .map(|i| {
                named
                    .iter()
                    .find(|&&(col, _)| col == i)
                    .map_or("-", |&(_, n)| n)
            })
            .collect()
    }
}

/// One table of an airfoil file.
#[derive(Debug, Clone, PartialEq)]
pub struct Polar {
    /// `Re`: Reynolds number in millions, as written.
    pub re: f64,
    /// `UserProp` (older files) or `Ctrl`: the control setting the table belongs to.
    pub user_prop: f64,
    /// Angle of attack, degrees, strictly increasing.
    pub alpha_deg: Vec<f64>,
    pub cl: Vec<f64>,
    pub cd: Vec<f64>,
    /// Pitching-moment coefficient (about the quarter chord), when the layout has the column.
    pub cm: Option<Vec<f64>>,
    /// Minimum pressure coefficient, when the layout has the column.
    pub cpmin: Option<Vec<f64>>,
    /// The table's unsteady-aerodynamics constants, when `InclUAdata` is true.
    pub ua: Option<UaBlock>,
}

/// The constants of a table's unsteady-aerodynamics block that the Hansen–Gaunaa–Madsen model
/// reads, as written: `None` for `Default` (AeroDyn's own default applies) or a missing line.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UaBlock {
    pub a1: Option<f64>,
    pub a2: Option<f64>,
    pub b1: Option<f64>,
    pub b2: Option<f64>,
    /// `T_f0`: the separation time constant (semichord travel times).
    pub t_f0: Option<f64>,
    /// `T_p`: the pressure time constant (semichord travel times).
    pub t_p: Option<f64>,
}

/// An AirfoilInfo file.
#[derive(Debug, Clone, PartialEq)]
pub struct AirfoilFile {
    /// `InterpOrd`: 1 linear, 3 cubic spline; `None` for DEFAULT (AirfoilInfo's own default).
    pub interp_ord: Option<usize>,
    /// `NonDimArea`: airfoil area / chord².
    pub non_dim_area: f64,
    /// `NumTabs` tables, in file order.
    pub tables: Vec<Polar>,
}

pub fn read_airfoil(path: &Path, columns: PolarColumns) -> Result<AirfoilFile> {
    parse_airfoil(&read_text(path)?, &path.display().to_string(), columns)
}

/// Parses the text of an AirfoilInfo file; `origin` names it in errors.
pub fn parse_airfoil(text: &str, origin: &str, columns: PolarColumns) -> Result<AirfoilFile> {
    let src = Source::new(origin, text).with_comments('!');
    let interp = src.key("InterpOrd", 0)?;
    let interp_ord = src.count_or_default(&interp, 1)?;
    let area = src.key("NonDimArea", interp.idx + 1)?;
    let non_dim_area = src.number(&area)?;
    let n_tabs_line = src.key("NumTabs", area.idx + 1)?;
    let n_tabs = src.count(&n_tabs_line, 1)?;
    let columns = file_columns(&src, n_tabs_line.idx, columns)?;

    let mut tables = Vec::new();
    let mut pos = n_tabs_line.idx + 1;
    for t in 1..=n_tabs {
        let (polar, next) = table(&src, pos, t, n_tabs, &columns)?;
        tables.push(polar);
        pos = next;
    }
    Ok(AirfoilFile {
        interp_ord,
        non_dim_area,
        tables,
    })
}

/// Largest column index accepted: a hostile `InCol_*` must not size the row layout.
const MAX_COLUMN: usize = 100;

/// The column layout: `InCol_*` lines before `NumTabs` override `given`.
fn file_columns(src: &Source, before: usize, given: PolarColumns) -> Result<PolarColumns> {
    let mut c = given;
    for (key, slot) in [
        ("InCol_Alfa", &mut c.alpha),
        ("InCol_Cl", &mut c.cl),
        ("InCol_Cd", &mut c.cd),
        ("InCol_Cm", &mut c.cm),
        ("InCol_Cpmin", &mut c.cpmin),
    ] {
        if let Some(k) = src.find_key(&[key], 0).filter(|k| k.idx < before) {
            *slot = src.count(&k, 0)?;
        }
    }
    if c.alpha == 0 || c.cl == 0 || c.cd == 0 {
        return Err(src.err_file(format!(
            "the polar columns must include Alpha, Cl and Cd, found InCol_Alfa {}, InCol_Cl {}, InCol_Cd {}",
            c.alpha, c.cl, c.cd
        )));
    }
    let widest = c.alpha.max(c.cl).max(c.cd).max(c.cm).max(c.cpmin);
    if widest > MAX_COLUMN {
        return Err(src.err_file(format!(
            "a polar column index of {widest} is beyond any polar table (at most {MAX_COLUMN})"
        )));
    }
    Ok(c)
}

/// Table `t` of `n_tabs`, whose `Re` line is the first at or after `from`.
fn table(
    src: &Source,
    from: usize,
    t: usize,
    n_tabs: usize,
    c: &PolarColumns,
) -> Result<(Polar, usize)> {
    let re_line = src.key("Re", from).map_err(|_| {
        src.missing(
            &format!(
                "expected table {t} of {n_tabs} (NumTabs), starting with its line '<value>  Re'"
            ),
            from,
        )
    })?;
    let re = src.number(&re_line)?;
    let prop_line = src.key_next(&["UserProp", "Ctrl"], re_line.idx + 1)?;
    let user_prop = src.number(&prop_line)?;
    let ua_line = src.key_next(&["InclUAdata"], prop_line.idx + 1)?;
    let (n_line, ua) = if src.flag(&ua_line)? {
        let (n_line, ua) = ua_block(src, ua_line.idx + 1, t)?;
        (n_line, Some(ua))
    } else {
        (src.key_next(&["NumAlf"], ua_line.idx + 1)?, None)
    };
    let n = src.count(&n_line, 1)?;

    let names = c.names();
    let spec = Table::new(n, "rows (NumAlf)", &names)
        .at(format!("in table {t}"))
        .at_least();
    let (rows, next) = src.rows(n_line.idx + 1, &spec)?;
    let alpha_col = c.alpha - 1;
    src.increasing(&rows, alpha_col, "Alpha")?;
    let column = |col: usize| -> Option<Vec<f64>> {
        let i = col.checked_sub(1)?;
        Some(rows.iter().map(|r: &Row| value(r, i)).collect())
    };
    let polar = Polar {
        re,
        user_prop,
        alpha_deg: column(c.alpha).unwrap_or_default(),
        cl: column(c.cl).unwrap_or_default(),
        cd: column(c.cd).unwrap_or_default(),
        cm: column(c.cm),
        cpmin: column(c.cpmin),
        ua,
    };
    Ok((polar, next))
}

/// A table's unsteady-aerodynamics block up to the `NumAlf` line after it, with the constants
/// [`UaBlock`] keeps: every line up to `NumAlf` must be a `value  Key` line, so a missing
/// `NumAlf` is not found in the next table instead.
fn ua_block<'a>(src: &Source<'a>, from: usize, t: usize) -> Result<(KeyLine<'a>, UaBlock)> {
    let expected = format!("expected the line '<value>  NumAlf' of table {t} after its UA block");
    let mut ua = UaBlock::default();
    let mut pos = from;
    loop {
        let idx = src.expect_content(pos, &expected)?;
        match src.key_line(idx) {
            Some(k) if k.key.eq_ignore_ascii_case("NumAlf") => return Ok((k, ua)),
            Some(k)
                if !k.key.eq_ignore_ascii_case("Re")
                    && super::text::parse_number(k.key).is_none() =>
            {
                let slot = match k.key.to_ascii_lowercase().as_str() {
                    "a1" => Some(&mut ua.a1),
                    "a2" => Some(&mut ua.a2),
                    "b1" => Some(&mut ua.b1),
                    "b2" => Some(&mut ua.b2),
                    "t_f0" => Some(&mut ua.t_f0),
                    "t_p" => Some(&mut ua.t_p),
                    _ => None,
                };
                if let Some(slot) = slot {
                    *slot = if k.value.eq_ignore_ascii_case("default") {
                        None
                    } else {
                        Some(src.number(&k).map_err(|_| {
                            src.err(
                                idx,
                                format!(
                                    "expected Default or a number for {} in the UA block of \
                                     table {t}, found '{}'",
                                    k.key, k.value
                                ),
                            )
                        })?)
                    };
                }
                pos = idx + 1
            }
            _ => return Err(src.err(idx, format!("{expected}, found '{}'", src.excerpt(idx)))),
        }
    }
}
