//! `airfoils`: each profile's contour, relative thickness and polars.

use super::distribution::{distribution, number_in, Distribution, Grid, Range};
use super::yaml::Node;
use crate::error::Result;

/// One set of aerodynamic coefficients of an airfoil.
#[derive(Debug, Clone, PartialEq)]
pub struct Polar {
    /// `configuration`, when named (e.g. `Default`).
    pub configuration: Option<String>,
    /// Reynolds number, when given.
    pub re: Option<f64>,
    /// Lift, drag and moment coefficients against the angle of attack (grid in rad, usually
    /// −π to π).
    pub c_l: Distribution,
    pub c_d: Distribution,
    pub c_m: Distribution,
}

/// An airfoil of the top-level `airfoils` list.
#[derive(Debug, Clone, PartialEq)]
pub struct Airfoil {
    pub name: String,
    /// Contour in chord units, leading edge at x = 0 and trailing edge at x = 1, as listed:
    /// WindIO runs from the trailing edge over the suction side (y > 0) round the leading edge
    /// and back along the pressure side. At least three points; x and y the same length.
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Thickness over chord (> 0).
    pub relative_thickness: f64,
    /// Aerodynamic centre as a fraction of the chord from the leading edge, when given.
    pub aerodynamic_center: Option<f64>,
    /// At least one.
    pub polars: Vec<Polar>,
    pub line: usize,
}

fn coefficient(node: &Node, key: &str) -> Result<Distribution> {
    distribution(
        &node.req(key, "a mapping with grid (angle of attack, rad) and values")?,
        Grid::Any,
        Range::Any,
    )
}

fn read_polar(node: &Node) -> Result<Polar> {
    Ok(Polar {
        configuration: node.get("configuration")?.map(|n| n.text()).transpose()?,
        re: node
            .get("re")?
            .map(|n| number_in(&n, Range::Positive))
            .transpose()?,
        c_l: coefficient(node, "c_l")?,
        c_d: coefficient(node, "c_d")?,
        c_m: coefficient(node, "c_m")?,
    })
}

pub(super) fn read_airfoil(node: &Node) -> Result<Airfoil> {
    let name = node.req("name", "the airfoil's name")?.text()?;
    let coordinates = node.req("coordinates", "a mapping with x and y (chord units)")?;
    let x_node = coordinates.req("x", "a list of x coordinates")?;
    let x = x_node.numbers()?;
    if x.len() < 3 {
        return Err(x_node.error(format!(
            "expected a contour of at least three points, found {}",
            x.len()
        )));
    }
    let y_node = coordinates.req("y", "a list of y coordinates")?;
    let y = y_node.numbers()?;
    if y.len() != x.len() {
        return Err(y_node.error(format!(
            "expected as many y as x coordinates ({}), found {}",
            x.len(),
            y.len()
        )));
    }
    let polars_node = node.req("polars", "a list of polars")?;
    let polars = polars_node
        .items()?
        .iter()
        .map(read_polar)
        .collect::<Result<Vec<_>>>()?;
    if polars.is_empty() {
        return Err(polars_node.error("expected at least one polar, found an empty list"));
    }
    Ok(Airfoil {
        name,
        x,
        y,
        relative_thickness: number_in(
            &node.req("relative_thickness", "thickness over chord")?,
            Range::Positive,
        )?,
        aerodynamic_center: node
            .get("aerodynamic_center")?
            .map(|n| number_in(&n, Range::Any))
            .transpose()?,
        polars,
        line: node.line(),
    })
}
