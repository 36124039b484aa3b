//! AeroDyn 15 blade files (OpenFAST): the aerodynamic nodes along the span — position of the
//! aerodynamic centre, twist, chord and which airfoil file applies.
//!
//! Columns are found by their header names, since newer files add columns (`BlCb`, `BlCenBn`,
//! `BlCenBt`, …) that this reader does not need.

use super::text::{column, read_text, value, whole, Source, Table};
use crate::error::Result;
use std::path::Path;

/// One blade node, in the file's units (AeroDyn blade frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AeroDynNode {
    /// `BlSpn`: span position along the blade pitch axis from the root, m.
    pub bl_spn: f64,
    /// `BlCrvAC`: out-of-plane offset of the aerodynamic centre (curvature, prebend), m.
    pub bl_crv_ac: f64,
    /// `BlSwpAC`: in-plane offset of the aerodynamic centre (sweep), m.
    pub bl_swp_ac: f64,
    /// `BlCrvAng`: local angle of the curved blade, degrees.
    pub bl_crv_ang_deg: f64,
    /// `BlTwist`: aerodynamic twist, degrees.
    pub bl_twist_deg: f64,
    /// `BlChord`: chord, m.
    pub bl_chord: f64,
    /// `BlAFID`: 1-based index of the airfoil file in the AeroDyn primary file's list.
    pub bl_af_id: usize,
}

/// The AeroDyn blade file: `NumBlNds` nodes, `bl_spn` strictly increasing.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroDynBlade {
    pub nodes: Vec<AeroDynNode>,
}

pub fn read_blade(path: &Path) -> Result<AeroDynBlade> {
    parse_blade(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of an AeroDyn blade file; `origin` names it in errors.
pub fn parse_blade(text: &str, origin: &str) -> Result<AeroDynBlade> {
    let src = Source::new(origin, text);
    let n_line = src.key("NumBlNds", 0)?;
    let n = src.count(&n_line, 2)?;
    // The header follows NumBlNds directly; OpenFAST reads the file line by line.
    let header = src.expect_text(
        n_line.idx + 1,
        "expected the node table header 'BlSpn BlCrvAC …'",
    )?;
    let names = src.tokens(header);
    let col = |name| column(&src, &names, header, name);
    let (c_spn, c_crv, c_swp, c_ang) = (
        col("BlSpn")?,
        col("BlCrvAC")?,
        col("BlSwpAC")?,
        col("BlCrvAng")?,
    );
    let (c_twist, c_chord, c_af) = (col("BlTwist")?, col("BlChord")?, col("BlAFID")?);
    let units = src.expect_text(header + 1, "expected the units line of the node table")?;
    let (rows, _) = src.rows(units + 1, &Table::new(n, "blade-node rows", &names))?;
    src.increasing(&rows, c_spn, "BlSpn")?;
    let nodes = rows
        .iter()
        .map(|r| {
            Ok(AeroDynNode {
                bl_spn: value(r, c_spn),
                bl_crv_ac: value(r, c_crv),
                bl_swp_ac: value(r, c_swp),
                bl_crv_ang_deg: value(r, c_ang),
                bl_twist_deg: value(r, c_twist),
                bl_chord: value(r, c_chord),
                bl_af_id: whole(&src, r, c_af, "BlAFID", 1)?,
            })
        })
        .collect::<Result<_>>()?;
    Ok(AeroDynBlade { nodes })
}
