//! ElastoDyn blade files (OpenFAST): the distributed blade properties, the factors ElastoDyn
//! scales them by and the modal structural damping.
//!
//! ElastoDyn models a blade by flap and edge bending alone, so its file has no torsional
//! stiffness (and no shear-centre or elastic-axis offsets): nothing here offers one. A
//! structural model that needs torsion must take it from elsewhere (BeamDyn, HAWC2 st).

use super::text::{read_text, Row, Source, Table};
use crate::error::Result;
use std::path::Path;

/// One row of the DISTRIBUTED BLADE PROPERTIES table, in the file's units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElastoDynStation {
    /// `BlFract`: fraction of the blade length from the root (0) to the tip (1).
    pub bl_fract: f64,
    /// `PitchAxis`: pitch axis position as a fraction of chord from the leading edge.
    pub pitch_axis: f64,
    /// `StrcTwst`: structural twist, degrees.
    pub strc_twst_deg: f64,
    /// `BMassDen`: mass per unit length, kg/m.
    pub b_mass_den: f64,
    /// `FlpStff`: flapwise bending stiffness, N·m².
    pub flp_stff: f64,
    /// `EdgStff`: edgewise bending stiffness, N·m².
    pub edg_stff: f64,
}

/// Structural damping of the blade modes, percent of critical (`BldFlDmp(1)`, `BldFlDmp(2)`,
/// `BldEdDmp(1)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalDamping {
    pub flap_1_pct: f64,
    pub flap_2_pct: f64,
    pub edge_1_pct: f64,
}

/// `AdjBlMs`, `AdjFlSt`, `AdjEdSt`: the factors ElastoDyn multiplies `BMassDen`, `FlpStff`
/// and `EdgStff` by. They change what the table means (the NREL 5MW file adds 4.5 % mass this
/// way), so they travel with it rather than being applied here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Adjustment {
    pub mass: f64,
    pub flap_stiffness: f64,
    pub edge_stiffness: f64,
}

/// The ElastoDyn blade file.
#[derive(Debug, Clone, PartialEq)]
pub struct ElastoDynBlade {
    /// `None` when the file has none of the three damping lines.
    pub damping: Option<ModalDamping>,
    pub adjustment: Adjustment,
    /// `NBlInpSt` stations as written, unadjusted, `bl_fract` strictly increasing.
    pub stations: Vec<ElastoDynStation>,
}

pub fn read_blade(path: &Path) -> Result<ElastoDynBlade> {
    parse_blade(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an ElastoDyn blade file; `origin` names it in errors.
pub fn parse_blade(text: &str, origin: &str) -> Result<ElastoDynBlade> {
    let src = Source::new(origin, text);
    let n_line = src.key("NBlInpSt", 0)?;
    let n = src.count(&n_line, 1)?;
    let damping = damping(&src)?;
    let factor = |key| src.key(key, 0).and_then(|k| src.number(&k));
    let adjustment = Adjustment {
        mass: factor("AdjBlMs")?,
        flap_stiffness: factor("AdjFlSt")?,
        edge_stiffness: factor("AdjEdSt")?,
    };

    let header = src.line_starting(
        "BlFract",
        n_line.idx + 1,
        "expected the distributed-properties header 'BlFract PitchAxis …'",
    )?;
    let names = src.tokens(header);
    let col = |name| super::text::column(&src, &names, header, name);
    let (c_fract, c_pitch, c_twist) = (col("BlFract")?, col("PitchAxis")?, col("StrcTwst")?);
    let (c_mass, c_flap, c_edge) = (col("BMassDen")?, col("FlpStff")?, col("EdgStff")?);
    let units = src.expect_text(
        header + 1,
        "expected the units line of the distributed properties",
    )?;
    let table = Table::new(n, "distributed-property rows", &names);
    let (rows, _) = src.rows(units + 1, &table)?;
    src.increasing(&rows, c_fract, "BlFract")?;
    let at = |r: &Row, c| super::text::value(r, c);
    Ok(ElastoDynBlade {
        damping,
        adjustment,
        stations: rows
            .iter()
            .map(|r| ElastoDynStation {
                bl_fract: at(r, c_fract),
                pitch_axis: at(r, c_pitch),
                strc_twst_deg: at(r, c_twist),
                b_mass_den: at(r, c_mass),
                flp_stff: at(r, c_flap),
                edg_stff: at(r, c_edge),
            })
            .collect(),
    })
}

/// The three damping values, all or none (a partial set would leave a mode's damping to guess).
fn damping(src: &Source) -> Result<Option<ModalDamping>> {
    let keys = ["BldFlDmp(1)", "BldFlDmp(2)", "BldEdDmp(1)"];
    let found = keys.map(|k| src.find_key(&[k], 0));
    if found.iter().all(Option::is_none) {
        return Ok(None);
    }
    let mut pct = [0.0; 3];
    for ((out, line), key) in pct.iter_mut().zip(&found).zip(keys) {
        let line = line.as_ref().ok_or_else(|| {
            src.missing(
                &format!("expected a line '<value>  {key}' beside the other blade damping values"),
                0,
            )
        })?;
        *out = src.number(line)?;
    }
    let [flap_1_pct, flap_2_pct, edge_1_pct] = pct;
    Ok(Some(ModalDamping {
        flap_1_pct,
        flap_2_pct,
        edge_1_pct,
    }))
}
