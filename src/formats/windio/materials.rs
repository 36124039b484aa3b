//! `materials`: the elastic constants, density and ply thickness of each material. Strengths,
//! costs and manufacturing data are not read.

use super::distribution::{number_in, Range};
use super::yaml::Node;
use crate::error::Result;

/// Elastic constants, Pa. Directions of an orthotropic material: 1 along the fibres, 2 across
/// them in the ply, 3 through the thickness.
#[derive(Debug, Clone, PartialEq)]
pub enum Elastic {
    /// `orth: 0`: one Young's modulus and Poisson ratio; the shear modulus when given.
    Isotropic { e: f64, g: Option<f64>, nu: f64 },
    /// `orth: 1`: E = [E1, E2, E3], G = [G12, G13, G23], ν = [ν12, ν13, ν23], as the ontology
    /// lists them.
    Orthotropic {
        e: [f64; 3],
        g: [f64; 3],
        nu: [f64; 3],
    },
}

/// A material of the top-level `materials` list.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    pub elastic: Elastic,
    /// Density, kg/m³ (> 0).
    pub rho: f64,
    /// Thickness of one ply, m (> 0), when given; layers given as `n_plies` need it.
    pub ply_t: Option<f64>,
    pub line: usize,
}

fn triple(node: &Node, range: Range) -> Result<[f64; 3]> {
    let items = node.items().map_err(|_| {
        node.error("expected a list of three numbers, as an orthotropic material (orth: 1) has")
    })?;
    if items.len() != 3 {
        return Err(node.error(format!(
            "expected three numbers (orth: 1), found {}",
            items.len()
        )));
    }
    Ok([
        number_in(&items[0], range)?,
        number_in(&items[1], range)?,
        number_in(&items[2], range)?,
    ])
}

fn scalar(node: &Node, range: Range) -> Result<f64> {
    if node.items().is_ok() {
        return Err(
            node.error("expected one number, as an isotropic material (orth: 0) has, found a list")
        );
    }
    number_in(node, range)
}

pub(super) fn read_material(node: &Node) -> Result<Material> {
    let name = node.req("name", "the material's name")?.text()?;
    let orth_node = node.req("orth", "0 (isotropic) or 1 (orthotropic)")?;
    let orthotropic = match orth_node.number() {
        Ok(0.0) => false,
        Ok(1.0) => true,
        _ => return Err(orth_node.error("expected 0 (isotropic) or 1 (orthotropic)")),
    };
    let e = node.req("E", "Young's modulus, Pa")?;
    let nu = node.req("nu", "Poisson's ratio")?;
    let elastic = if orthotropic {
        Elastic::Orthotropic {
            e: triple(&e, Range::Positive)?,
            g: triple(&node.req("G", "shear moduli, Pa")?, Range::Positive)?,
            nu: triple(&nu, Range::Any)?,
        }
    } else {
        Elastic::Isotropic {
            e: scalar(&e, Range::Positive)?,
            g: node
                .get("G")?
                .map(|g| scalar(&g, Range::Positive))
                .transpose()?,
            nu: scalar(&nu, Range::Any)?,
        }
    };
    Ok(Material {
        name,
        elastic,
        rho: number_in(&node.req("rho", "density, kg/m³")?, Range::Positive)?,
        ply_t: node
            .get("ply_t")?
            .map(|n| number_in(&n, Range::Positive))
            .transpose()?,
        line: node.line(),
    })
}
