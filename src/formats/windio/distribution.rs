//! The ontology's one way of giving a quantity along a coordinate: a `grid` and the `values` at
//! its points, checked on reading (at least two points, the grid increasing, as many values as
//! grid points, every number finite and in the quantity's range).

use super::yaml::Node;
use crate::error::Result;

/// A quantity tabulated on a grid, as the file gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution {
    /// Strictly increasing. Along the blade: the non-dimensional position along the reference
    /// axis, 0 at the root to 1 at the tip; for a polar: the angle of attack, rad.
    pub grid: Vec<f64>,
    /// One value per grid point, in the quantity's unit (each field says which).
    pub values: Vec<f64>,
    /// The 1-based line of the mapping that holds `grid` and `values`.
    pub line: usize,
}

/// What a grid spans.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Grid {
    /// The non-dimensional span or arc, in [0, 1].
    Unit,
    /// Any increasing numbers (angles of attack).
    Any,
}

/// What the values must be.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Range {
    Any,
    NonNegative,
    Positive,
    Unit,
}

impl Range {
    fn admits(self, v: f64) -> bool {
        match self {
            Range::Any => true,
            Range::NonNegative => v >= 0.0,
            Range::Positive => v > 0.0,
            Range::Unit => (0.0..=1.0).contains(&v),
        }
    }

    pub(super) fn wording(self) -> &'static str {
        match self {
            Range::Any => "a finite number",
            Range::NonNegative => "a number ≥ 0",
            Range::Positive => "a number > 0",
            Range::Unit => "a number in [0, 1]",
        }
    }
}

/// A number of a range at `node`.
pub(super) fn number_in(node: &Node, range: Range) -> Result<f64> {
    let v = node.number()?;
    if range.admits(v) {
        Ok(v)
    } else {
        Err(node.error(format!("expected {}, found {v}", range.wording())))
    }
}

/// An increasing grid of at least two points at `node`.
pub(super) fn grid(node: &Node, kind: Grid) -> Result<Vec<f64>> {
    let items = node.items()?;
    let wording = match kind {
        Grid::Unit => "a grid of at least two increasing numbers in [0, 1]",
        Grid::Any => "a grid of at least two increasing numbers",
    };
    if items.len() < 2 {
        return Err(node.error(format!("expected {wording}, found {} values", items.len())));
    }
    let mut out = Vec::with_capacity(items.len());
    for item in &items {
        let v = item.number()?;
        if kind == Grid::Unit && !(0.0..=1.0).contains(&v) {
            return Err(item.error(format!("expected {wording}, found {v} outside [0, 1]")));
        }
        if let Some(&last) = out.last() {
            if v <= last {
                return Err(item.error(format!("expected {wording}, found {v} after {last}")));
            }
        }
        out.push(v);
    }
    Ok(out)
}

/// The `grid` and `values` of the mapping at `node`.
pub(super) fn distribution(node: &Node, kind: Grid, range: Range) -> Result<Distribution> {
    let grid = grid(&node.req("grid", "a list of grid points")?, kind)?;
    let values = values(
        &node.req("values", "a list of values, one per grid point")?,
        grid.len(),
        range,
    )?;
    Ok(Distribution {
        grid,
        values,
        line: node.line(),
    })
}

/// A list of `n` numbers of a range at `node`.
pub(super) fn values(node: &Node, n: usize, range: Range) -> Result<Vec<f64>> {
    let items = node.items()?;
    if items.len() != n {
        return Err(node.error(format!(
            "expected values the same length as grid ({n}), found {}",
            items.len()
        )));
    }
    items.iter().map(|item| number_in(item, range)).collect()
}
