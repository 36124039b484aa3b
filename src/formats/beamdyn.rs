//! BeamDyn input files (OpenFAST): the primary file's key points (the blade's reference axis
//! and its initial twist) and name of the blade file, and the blade file's damping and
//! sectional 6×6 stiffness and mass matrices along the span.
//!
//! Everything stays in BeamDyn's own blade frame and units: z_r along the blade, matrices in
//! the order (shear 1, shear 2, extension, bending 1, bending 2, torsion) — K44/K55 the two
//! bending stiffnesses, K66 torsion — as printed, row by row.

use super::text::{array, read_text, value, Source, Table};
use crate::error::Result;
use std::path::{Path, PathBuf};

/// One key point of the blade reference axis (BeamDyn blade frame, metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeyPoint {
    pub kp_xr: f64,
    pub kp_yr: f64,
    pub kp_zr: f64,
    /// Twist of the sectional frame about the reference axis, degrees, as BeamDyn's
    /// `initial_twist` (the sign convention is BeamDyn's).
    pub initial_twist_deg: f64,
}

/// What the primary file says about the blade geometry and where its properties are.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamDynPrimary {
    /// Key points of each member in file order. Adjacent members share their end point, so
    /// the last key point of a member repeats as the first of the next.
    pub members: Vec<Vec<KeyPoint>>,
    /// `kp_total` as written; checked against the members (Σ per member − shared points).
    pub kp_total: usize,
    /// `BldFile` exactly as written (usually relative to the primary file; see
    /// [`BeamDynPrimary::blade_file_path`]).
    pub blade_file: String,
}

impl BeamDynPrimary {
    /// The blade file's path: BeamDyn resolves a relative `BldFile` against the directory of
    /// the primary file, not the working directory.
    pub fn blade_file_path(&self, primary: &Path) -> PathBuf {
        primary
            .parent()
            .unwrap_or_else(|| Path::new(""))
            .join(&self.blade_file)
    }
}

/// One station of the blade file.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamDynStation {
    /// The line of its eta (1-based), where errors about the station point.
    pub line: usize,
    /// Non-dimensional position along the reference axis, 0 at the root to 1 at the tip.
    pub eta: f64,
    /// Sectional stiffness matrix as printed (N, N·m, N·m² by block).
    pub stiffness: [[f64; 6]; 6],
    /// Sectional mass matrix as printed (kg/m, kg, kg·m by block).
    pub mass: [[f64; 6]; 6],
}

/// The BeamDyn blade file.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamDynBlade {
    /// The file's name as errors give it.
    pub path: String,
    /// 0: no damping; 1: damping proportional to stiffness with the factors `mu`.
    pub damp_type: u32,
    /// Stiffness-proportional damping factors, one per sectional degree of freedom in the matrix
    /// order, as written (the file labels them `(-)`); BeamDyn applies them only when
    /// `damp_type` is 1.
    pub mu: [f64; 6],
    /// `station_total` stations, eta strictly increasing.
    pub stations: Vec<BeamDynStation>,
}

const KP_COLUMNS: [&str; 4] = ["kp_xr", "kp_yr", "kp_zr", "initial_twist"];

pub fn read_primary(path: &Path) -> Result<BeamDynPrimary> {
    parse_primary(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of a primary file; `origin` names it in errors.
pub fn parse_primary(text: &str, origin: &str) -> Result<BeamDynPrimary> {
    let src = Source::new(origin, text);
    let members_line = src.key("member_total", 0)?;
    let member_total = src.count(&members_line, 1)?;
    let kp_line = src.key("kp_total", members_line.idx + 1)?;
    let kp_total = src.count(&kp_line, 3)?;

    let mut members = Vec::new();
    let mut pos = kp_line.idx + 1;
    for m in 1..=member_total {
        let expected = format!("expected the line '{m} <key points>' of member {m}");
        let idx = src.expect_content(pos, &expected)?;
        let kp_member = match src.tokens(idx).as_slice() {
            [no, n, ..] if no.parse::<usize>() == Ok(m) => n.parse::<usize>().ok(),
            _ => None,
        }
        .filter(|&n| n >= 2)
        .ok_or_else(|| {
            src.err(
                idx,
                format!("{expected} (at least 2), found '{}'", src.excerpt(idx)),
            )
        })?;
        let header = format!(
            "expected the key-point header of member {m} (kp_xr kp_yr kp_zr initial_twist)"
        );
        let names = src.expect_text(idx + 1, &header)?;
        let units = src.expect_text(names + 1, &format!("{header} and its units line"))?;
        let table =
            Table::new(kp_member, "key-point rows", &KP_COLUMNS).at(format!("in member {m}"));
        let (rows, next) = src.rows(units + 1, &table)?;
        // A repeated or reversed key point is a hand edit gone wrong (the member's count then
        // leaves its last point, the tip, unread), not a blade.
        src.increasing(&rows, 2, "kp_zr")?;
        members.push(
            rows.iter()
                .map(|r| {
                    let [kp_xr, kp_yr, kp_zr, initial_twist_deg] = array(&r.values);
                    KeyPoint {
                        kp_xr,
                        kp_yr,
                        kp_zr,
                        initial_twist_deg,
                    }
                })
                .collect::<Vec<_>>(),
        );
        pos = next;
    }

    let listed: usize = members.iter().map(Vec::len).sum::<usize>() + 1 - member_total;
    if listed != kp_total {
        return Err(src.err(
            kp_line.idx,
            format!(
                "kp_total is {kp_total} but the members list {listed} distinct key points \
                 (adjacent members share their end point)"
            ),
        ));
    }

    let blade = src.key("BldFile", pos)?;
    if blade.value.trim().is_empty() {
        return Err(src.err(blade.idx, "expected a file name for BldFile, found none"));
    }
    Ok(BeamDynPrimary {
        members,
        kp_total,
        blade_file: blade.value.to_string(),
    })
}

pub fn read_blade(path: &Path) -> Result<BeamDynBlade> {
    parse_blade(&read_text(path)?, &path.display().to_string())
}

/// Parses the text of a blade file; `origin` names it in errors.
pub fn parse_blade(text: &str, origin: &str) -> Result<BeamDynBlade> {
    let src = Source::new(origin, text);
    let stations_line = src.key("station_total", 0)?;
    let station_total = src.count(&stations_line, 1)?;
    let damp_line = src.key("damp_type", stations_line.idx + 1)?;
    let damp_type = match src.count(&damp_line, 0)? {
        d @ (0 | 1) => d as u32,
        d => {
            return Err(src.err(
                damp_line.idx,
                format!("damp_type {d} is not supported: expected 0 (none) or 1 (mu factors)"),
            ))
        }
    };

    let mu_header = src.line_starting(
        "mu1",
        damp_line.idx + 1,
        "expected the damping header 'mu1 … mu6'",
    )?;
    let units = src.expect_text(mu_header + 1, "expected the units line of mu1 … mu6")?;
    let mu_table = Table::new(
        1,
        "the damping row",
        &["mu1", "mu2", "mu3", "mu4", "mu5", "mu6"],
    );
    let (mu_row, next) = src.row_after(units + 1, &mu_table, 0)?;
    let mu = array(&mu_row.values);
    let mut pos = src.expect_text(next, "expected the DISTRIBUTED PROPERTIES section line")? + 1;

    let mut stations = Vec::new();
    let mut etas = Vec::new();
    for s in 1..=station_total {
        let eta_table = Table::new(1, "the eta line", &["eta"])
            .at(format!("of station {s} of {station_total}"));
        let (eta_row, next) = src.row_after(pos, &eta_table, 0)?;
        let eta = value(&eta_row, 0);
        if !(0.0..=1.0).contains(&eta) {
            return Err(src.err(
                eta_row.idx,
                format!("expected eta of station {s} between 0 and 1, found {eta}"),
            ));
        }
        let matrix = |what: &str, from: usize| -> Result<([[f64; 6]; 6], usize)> {
            let cols = ["c1", "c2", "c3", "c4", "c5", "c6"];
            let table = Table::new(6, format!("{what} rows"), &cols)
                .at(format!("at station {s} (eta {eta})"));
            let (rows, next) = src.rows(from, &table)?;
            let mut m = [[0.0; 6]; 6];
            for (out, row) in m.iter_mut().zip(&rows) {
                *out = array(&row.values);
            }
            Ok((m, next))
        };
        let (stiffness, next) = matrix("stiffness", next)?;
        let (mass, next) = matrix("mass", next)?;
        stations.push(BeamDynStation {
            line: eta_row.idx + 1,
            eta,
            stiffness,
            mass,
        });
        etas.push(eta_row);
        pos = next;
    }
    src.increasing(&etas, 0, "eta")?;
    Ok(BeamDynBlade {
        path: origin.to_string(),
        damp_type,
        mu,
        stations,
    })
}
