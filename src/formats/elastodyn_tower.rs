//! ElastoDyn tower files (OpenFAST): the tower's distributed mass and bending stiffness, the
//! factors ElastoDyn scales them by, the modal damping and the assumed mode shapes.
//!
//! An ElastoDyn tower bends fore–aft and side–side only: the file has no torsional stiffness,
//! and nothing here offers one. Its mode shapes are polynomials in the height fraction `h`,
//! `φ(h) = Σ_{i=2}^{6} c_i h^i`, normalised to 1 at the tower top, so the coefficients of each
//! shape must sum to 1; a shape that does not is an error, not rescaled.

use super::text::{read_text, Bound, Row, Source, Table};
use crate::error::Result;
use std::path::Path;

/// One row of the DISTRIBUTED TOWER PROPERTIES table, in the file's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TowerStation {
    /// `HtFract`: fraction of the tower's length from its base (0) to its top (1).
    pub height_fraction: f64,
    /// `TMassDen` (kg/m).
    pub mass_density: f64,
    /// `TwFAStif`, `TwSSStif` (N·m²).
    pub fore_aft_stiffness: f64,
    pub side_side_stiffness: f64,
}

/// The coefficients of `h², …, h⁶` of one assumed mode shape.
pub type ModeShape = [f64; 5];

/// Largest |Σ c_i − 1| accepted: the published files round their coefficients to four or five
/// digits (the NREL 5MW's second side–side shape sums to 0.999, its second fore–aft one to
/// 1.0004), while a mistyped coefficient moves the sum by far more.
const SHAPE_SUM_TOLERANCE: f64 = 2e-3;

/// The ElastoDyn tower file.
#[derive(Debug, Clone, PartialEq)]
pub struct ElastoDynTower {
    /// `TwrFADmp(1..2)`, `TwrSSDmp(1..2)`: structural damping of the first two modes each way,
    /// percent of critical.
    pub fore_aft_damping_pct: [f64; 2],
    pub side_side_damping_pct: [f64; 2],
    /// `FAStTunr(1..2)`, `SSStTunr(1..2)`: the modal stiffness tuners.
    pub fore_aft_tuners: [f64; 2],
    pub side_side_tuners: [f64; 2],
    /// `AdjTwMa`, `AdjFASt`, `AdjSSSt`: factors on the mass density and the two stiffnesses,
    /// kept beside the table rather than applied (they change what the table means).
    pub mass_factor: f64,
    pub fore_aft_factor: f64,
    pub side_side_factor: f64,
    /// `NTwInpSt` stations as written, unadjusted, from `HtFract` 0 to 1.
    pub stations: Vec<TowerStation>,
    /// `TwFAM1Sh`, `TwFAM2Sh` and `TwSSM1Sh`, `TwSSM2Sh`.
    pub fore_aft_shapes: [ModeShape; 2],
    pub side_side_shapes: [ModeShape; 2],
}

pub fn read_tower(path: &Path) -> Result<ElastoDynTower> {
    parse_tower(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an ElastoDyn tower file; `origin` names it in errors.
pub fn parse_tower(text: &str, origin: &str) -> Result<ElastoDynTower> {
    let src = Source::new(origin, text);
    let n_line = src.key("NTwInpSt", 0)?;
    let n = src.count(&n_line, 2)?;
    let non_negative = |key: &str| src.bounded(key, 0, Bound::NonNegative);
    let positive = |key: &str| src.bounded(key, 0, Bound::Positive);
    let pair = |key: &str, read: &dyn Fn(&str) -> Result<f64>| -> Result<[f64; 2]> {
        Ok([read(&format!("{key}(1)"))?, read(&format!("{key}(2)"))?])
    };

    let header = src.line_starting(
        "HtFract",
        n_line.idx + 1,
        "expected the distributed-properties header 'HtFract TMassDen TwFAStif TwSSStif'",
    )?;
    let names = src.tokens(header);
    let col = |name| super::text::column(&src, &names, header, name);
    let (c_h, c_m) = (col("HtFract")?, col("TMassDen")?);
    let (c_fa, c_ss) = (col("TwFAStif")?, col("TwSSStif")?);
    let units = src.expect_text(
        header + 1,
        "expected the units line of the distributed properties",
    )?;
    let table = Table::new(n, "distributed-property rows", &names);
    let (rows, after) = src.rows(units + 1, &table)?;
    src.increasing(&rows, c_h, "HtFract")?;
    let at = |r: &Row, c| super::text::value(r, c);
    for (r, end, want) in [(&rows[0], "first", 0.0), (&rows[n - 1], "last", 1.0)] {
        if at(r, c_h) != want {
            return Err(src.err(
                r.idx,
                format!(
                    "HtFract of the {end} station is {}: the table runs from the tower base \
                     (0) to its top (1)",
                    at(r, c_h)
                ),
            ));
        }
    }
    for r in &rows {
        for (c, name) in [(c_m, "TMassDen"), (c_fa, "TwFAStif"), (c_ss, "TwSSStif")] {
            if at(r, c) <= 0.0 {
                return Err(src.err(
                    r.idx,
                    format!("{name} is {}: it must be greater than 0", at(r, c)),
                ));
            }
        }
    }
    let shapes = |name: &str| -> Result<[ModeShape; 2]> {
        Ok([
            shape(&src, &format!("{name}1Sh"), after)?,
            shape(&src, &format!("{name}2Sh"), after)?,
        ])
    };
    Ok(ElastoDynTower {
        fore_aft_damping_pct: pair("TwrFADmp", &non_negative)?,
        side_side_damping_pct: pair("TwrSSDmp", &non_negative)?,
        fore_aft_tuners: pair("FAStTunr", &positive)?,
        side_side_tuners: pair("SSStTunr", &positive)?,
        mass_factor: positive("AdjTwMa")?,
        fore_aft_factor: positive("AdjFASt")?,
        side_side_factor: positive("AdjSSSt")?,
        stations: rows
            .iter()
            .map(|r| TowerStation {
                height_fraction: at(r, c_h),
                mass_density: at(r, c_m),
                fore_aft_stiffness: at(r, c_fa),
                side_side_stiffness: at(r, c_ss),
            })
            .collect(),
        fore_aft_shapes: shapes("TwFAM")?,
        side_side_shapes: shapes("TwSSM")?,
    })
}

/// The five coefficients `key(2)` … `key(6)` of one mode shape, which must sum to 1.
fn shape(src: &Source, key: &str, from: usize) -> Result<ModeShape> {
    let mut c = [0.0; 5];
    let mut last = from;
    for (i, out) in c.iter_mut().enumerate() {
        let k = src.key(&format!("{key}({})", i + 2), from)?;
        *out = src.number(&k)?;
        last = k.idx;
    }
    let sum: f64 = c.iter().sum();
    if (sum - 1.0).abs() > SHAPE_SUM_TOLERANCE {
        return Err(src.err(
            last,
            format!(
                "the coefficients {key}(2) … {key}(6) sum to {sum}: a mode shape is 1 at the \
                 tower top, so they must sum to 1 (within {SHAPE_SUM_TOLERANCE})"
            ),
        ));
    }
    Ok(c)
}
