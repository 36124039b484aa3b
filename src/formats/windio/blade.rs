//! `components.blade`: the outer shape (`outer_shape_bem`) and the layup
//! (`internal_structure_2d_fem`: shear webs and layers), kept as the file defines them.

use super::distribution::{distribution, grid, Distribution, Grid, Range};
use super::yaml::Node;
use crate::error::Result;

/// A curve in the blade root frame, each coordinate tabulated along the span (metres). The
/// frame is BeamDyn's: z along the pitch axis toward the tip, x toward the suction side (a
/// standard prebend is negative), y toward the trailing edge (a standard sweep is positive).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub x: Distribution,
    pub y: Distribution,
    pub z: Distribution,
}

/// Which airfoil sits where along the span.
#[derive(Debug, Clone, PartialEq)]
pub struct AirfoilPosition {
    /// Non-dimensional span positions, increasing; an airfoil held over a stretch is listed at
    /// both of its ends.
    pub grid: Vec<f64>,
    /// The airfoil at each grid point, by the name it has in `airfoils` (checked on reading).
    pub labels: Vec<String>,
}

/// `outer_shape_bem`: what the aerodynamics and the section geometry start from.
#[derive(Debug, Clone, PartialEq)]
pub struct OuterShape {
    pub airfoil_position: AirfoilPosition,
    /// Chord, m (> 0).
    pub chord: Distribution,
    /// Aerodynamic twist, rad, positive toward feather as the ontology's root frame has it
    /// (standard blades: positive inboard, near zero at the tip).
    pub twist: Distribution,
    /// Where the reference axis crosses the chord, as a fraction of the chord from the leading
    /// edge (0) to the trailing edge (1).
    pub pitch_axis: Distribution,
    pub reference_axis: Axis,
    /// `rthick`: relative thickness along the span, where the file gives it (otherwise it
    /// follows from the airfoils placed along the span).
    pub relative_thickness: Option<Distribution>,
}

/// Where a layer's or web's edge is, along the section contour: `start_nd_arc`, `end_nd_arc` or
/// `midpoint_nd_arc`. The non-dimensional arc runs from 0 at the trailing edge on the suction
/// side, round the leading edge, to 1 at the trailing edge on the pressure side (for a flatback,
/// from and to the middle of the trailing edge).
#[derive(Debug, Clone, PartialEq)]
pub struct ArcPosition {
    /// What the edge is locked to, when the file says (`fixed`).
    pub fixed: Option<Fixed>,
    /// The non-dimensional arc position along the span (values in [0, 1]), when given. A
    /// design tool writes them next to `fixed` once it has placed the edge.
    pub values: Option<Distribution>,
    pub line: usize,
}

/// What an edge is locked to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Fixed {
    /// `LE`: the leading edge.
    LeadingEdge,
    /// `TE`: the trailing edge (arc 0 for a start, 1 for an end).
    TrailingEdge,
    /// Another layer, by name (checked on reading): a start locked to a layer sits at that
    /// layer's end, an end at its start.
    Layer(String),
}

/// The side of the section a layer placed about the pitch axis is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Suction,
    Pressure,
}

/// `rotation`: the angle (rad) from the chord line to the axis along which an offset is
/// measured; the ontology gives it the opposite sign of the twist.
#[derive(Debug, Clone, PartialEq)]
pub struct Rotation {
    /// `fixed: twist`: the axis is the root frame's y axis in every section, so the rotation
    /// is the twist with its sign changed.
    pub fixed_to_twist: bool,
    /// The rotation along the span, rad, when given.
    pub values: Option<Distribution>,
    pub line: usize,
}

/// How a shear web is placed, as written.
#[derive(Debug, Clone, PartialEq)]
pub struct Web {
    pub name: String,
    pub start_nd_arc: Option<ArcPosition>,
    pub end_nd_arc: Option<ArcPosition>,
    pub rotation: Option<Rotation>,
    /// `offset_y_pa` (`offset_x_pa` in the 2019 ontology): distance, m, from the pitch axis
    /// along the rotated axis to the web's plane; negative toward the leading edge.
    pub offset: Option<Distribution>,
    pub line: usize,
}

/// How a layer is laid, as written: its material and thickness and every positioning field the
/// file gives (a design tool often writes both the width-based definition and the arc positions
/// it computed from it). [`Layer::placement`] says which definition places it.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    pub name: String,
    /// The material's name in `materials` (checked on reading).
    pub material: String,
    /// The shear web it belongs to (checked on reading); `None` for a layer on the outer shell.
    pub web: Option<String>,
    /// Laminate thickness, m (≥ 0; 0 where the layer is absent).
    pub thickness: Distribution,
    /// Number of plies (≥ 0), when given.
    pub n_plies: Option<Distribution>,
    /// Fibre angle, rad, in the section's local frame; positive turns the fibres toward the
    /// leading edge, looking from the root. `None` when the file gives none (an isotropic
    /// layer needs none).
    pub fiber_orientation: Option<Distribution>,
    pub start_nd_arc: Option<ArcPosition>,
    pub end_nd_arc: Option<ArcPosition>,
    pub midpoint_nd_arc: Option<ArcPosition>,
    /// Width along the arc, m (≥ 0).
    pub width: Option<Distribution>,
    pub side: Option<Side>,
    /// As for a web: distance, m, from the pitch axis along the rotated axis to the layer's
    /// middle.
    pub offset: Option<Distribution>,
    pub rotation: Option<Rotation>,
    pub line: usize,
}

/// The definition that places a layer, in the ontology's order of precedence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Placement<'a> {
    /// On a shear web, through its whole height.
    Web(&'a str),
    /// On the shell between two arc positions (each given as values, or locked to an edge
    /// or another layer).
    Arcs {
        start: &'a ArcPosition,
        end: &'a ArcPosition,
    },
    /// A width (m) along the arc from an anchor.
    Width {
        width: &'a Distribution,
        anchor: Anchor<'a>,
    },
    /// Nothing positions it: the ontology's default, the whole section (arc 0 to 1).
    WholeSection,
}

/// Where a width-defined layer is anchored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anchor<'a> {
    /// Centred on `midpoint_nd_arc`.
    Midpoint(&'a ArcPosition),
    /// From `start_nd_arc` toward the pressure-side trailing edge.
    Start(&'a ArcPosition),
    /// Up to `end_nd_arc`.
    End(&'a ArcPosition),
    /// Centred where the line through the offset point, perpendicular to the rotated axis,
    /// meets the contour on `side`.
    PitchAxis {
        side: Side,
        offset: &'a Distribution,
        rotation: Option<&'a Rotation>,
    },
}

impl Layer {
    /// The definition that places the layer. Arc positions given at both edges come first
    /// (they are what the width-based fields resolve to); a width needs an anchor.
    pub fn placement(&self) -> Option<Placement<'_>> {
        if let Some(web) = &self.web {
            return Some(Placement::Web(web));
        }
        if let (Some(start), Some(end)) = (&self.start_nd_arc, &self.end_nd_arc) {
            return Some(Placement::Arcs { start, end });
        }
        if let Some(width) = &self.width {
            let anchor = if let Some(m) = &self.midpoint_nd_arc {
                Anchor::Midpoint(m)
            } else if let Some(s) = &self.start_nd_arc {
                Anchor::Start(s)
            } else if let Some(e) = &self.end_nd_arc {
                Anchor::End(e)
            } else if let (Some(side), Some(offset)) = (self.side, &self.offset) {
                Anchor::PitchAxis {
                    side,
                    offset,
                    rotation: self.rotation.as_ref(),
                }
            } else {
                return None;
            };
            return Some(Placement::Width { width, anchor });
        }
        if self.start_nd_arc.is_none()
            && self.end_nd_arc.is_none()
            && self.midpoint_nd_arc.is_none()
        {
            return Some(Placement::WholeSection);
        }
        None
    }
}

/// `internal_structure_2d_fem`.
#[derive(Debug, Clone, PartialEq)]
pub struct InternalStructure {
    pub reference_axis: Axis,
    /// In file order (a section's webs from leading to trailing edge, usually).
    pub webs: Vec<Web>,
    /// In file order, which is the stacking order from the outer surface inward.
    pub layers: Vec<Layer>,
}

/// `components.blade`.
#[derive(Debug, Clone, PartialEq)]
pub struct Blade {
    pub outer_shape: OuterShape,
    pub structure: InternalStructure,
}

fn span(node: &Node, range: Range) -> Result<Distribution> {
    distribution(node, Grid::Unit, range)
}

fn axis(node: &Node) -> Result<Axis> {
    let d = |k: &str| {
        span(
            &node.req(k, "a mapping with grid and values (m)")?,
            Range::Any,
        )
    };
    Ok(Axis {
        x: d("x")?,
        y: d("y")?,
        z: d("z")?,
    })
}

pub(super) fn read_blade(node: &Node) -> Result<Blade> {
    let shape = node.req("outer_shape_bem", "the blade's outer shape")?;
    let structure = node.req(
        "internal_structure_2d_fem",
        "the blade's layup (reference_axis, webs, layers)",
    )?;
    Ok(Blade {
        outer_shape: read_outer_shape(&shape)?,
        structure: read_structure(&structure)?,
    })
}

fn read_outer_shape(node: &Node) -> Result<OuterShape> {
    let dist = "a mapping with grid and values";
    let positions = node.req("airfoil_position", "a mapping with grid and labels")?;
    let grid_node = positions.req("grid", "the span positions of the airfoils")?;
    let position_grid = grid(&grid_node, Grid::Unit)?;
    let labels_node = positions.req("labels", "the airfoil names, one per grid point")?;
    let labels = labels_node.texts()?;
    if labels.len() != position_grid.len() {
        return Err(labels_node.error(format!(
            "expected labels the same length as grid ({}), found {}",
            position_grid.len(),
            labels.len()
        )));
    }
    Ok(OuterShape {
        airfoil_position: AirfoilPosition {
            grid: position_grid,
            labels,
        },
        chord: span(&node.req("chord", dist)?, Range::Positive)?,
        twist: span(&node.req("twist", dist)?, Range::Any)?,
        pitch_axis: span(&node.req("pitch_axis", dist)?, Range::Any)?,
        reference_axis: axis(&node.req("reference_axis", "a mapping with x, y and z")?)?,
        relative_thickness: node
            .get("rthick")?
            .map(|n| span(&n, Range::Positive))
            .transpose()?,
    })
}

fn read_structure(node: &Node) -> Result<InternalStructure> {
    let reference_axis = axis(&node.req("reference_axis", "a mapping with x, y and z")?)?;
    let webs = match node.get("webs")? {
        Some(list) => list.items()?.iter().map(read_web).collect::<Result<_>>()?,
        None => Vec::new(),
    };
    let layers_node = node.req("layers", "a list of layers")?;
    let layers = layers_node
        .items()?
        .iter()
        .map(read_layer)
        .collect::<Result<Vec<_>>>()?;
    if layers.is_empty() {
        return Err(layers_node.error("expected at least one layer, found an empty list"));
    }
    Ok(InternalStructure {
        reference_axis,
        webs,
        layers,
    })
}

fn arc_position(node: &Node) -> Result<ArcPosition> {
    let fixed = node
        .get("fixed")?
        .map(|f| {
            f.text().map(|t| match t.as_str() {
                "LE" => Fixed::LeadingEdge,
                "TE" => Fixed::TrailingEdge,
                _ => Fixed::Layer(t),
            })
        })
        .transpose()?;
    let values = if node.get("grid")?.is_some() || node.get("values")?.is_some() {
        Some(span(node, Range::Unit)?)
    } else {
        None
    };
    if fixed.is_none() && values.is_none() {
        return Err(node.error("expected grid and values (an arc position in [0, 1]) or fixed"));
    }
    Ok(ArcPosition {
        fixed,
        values,
        line: node.line(),
    })
}

fn rotation(node: &Node) -> Result<Rotation> {
    let fixed_to_twist = match node.get("fixed")? {
        Some(f) => {
            let t = f.text()?;
            if t != "twist" {
                return Err(f.error(format!(
                    "expected `twist` (the only rotation a section can be locked to), found `{t}`"
                )));
            }
            true
        }
        None => false,
    };
    let values = if node.get("grid")?.is_some() || node.get("values")?.is_some() {
        Some(span(node, Range::Any)?)
    } else {
        None
    };
    if !fixed_to_twist && values.is_none() {
        return Err(node.error("expected grid and values (rad) or fixed: twist"));
    }
    Ok(Rotation {
        fixed_to_twist,
        values,
        line: node.line(),
    })
}

/// `offset_y_pa`, or `offset_x_pa` as the 2019 ontology named it; both at once are ambiguous.
fn offset(node: &Node) -> Result<Option<Distribution>> {
    match (node.get("offset_y_pa")?, node.get("offset_x_pa")?) {
        (Some(_), Some(x)) => Err(x.error(
            "expected one offset, found both offset_y_pa and offset_x_pa (the older name of the same field)",
        )),
        (Some(n), None) | (None, Some(n)) => Ok(Some(span(&n, Range::Any)?)),
        (None, None) => Ok(None),
    }
}

fn optional<T>(node: &Node, key: &str, read: impl Fn(&Node) -> Result<T>) -> Result<Option<T>> {
    node.get(key)?.map(|n| read(&n)).transpose()
}

fn read_web(node: &Node) -> Result<Web> {
    let web = Web {
        name: node.req("name", "the web's name")?.text()?,
        start_nd_arc: optional(node, "start_nd_arc", arc_position)?,
        end_nd_arc: optional(node, "end_nd_arc", arc_position)?,
        rotation: optional(node, "rotation", rotation)?,
        offset: offset(node)?,
        line: node.line(),
    };
    let by_arcs = web.start_nd_arc.is_some() && web.end_nd_arc.is_some();
    if !by_arcs && web.offset.is_none() {
        return Err(node.error(
            "expected the web's position: start_nd_arc and end_nd_arc, or offset_y_pa (with rotation)",
        ));
    }
    Ok(web)
}

fn read_layer(node: &Node) -> Result<Layer> {
    let side = node
        .get("side")?
        .map(|s| {
            let t = s.text()?;
            match t.as_str() {
                "suction" => Ok(Side::Suction),
                "pressure" => Ok(Side::Pressure),
                _ => Err(s.error(format!("expected `suction` or `pressure`, found `{t}`"))),
            }
        })
        .transpose()?;
    let layer = Layer {
        name: node.req("name", "the layer's name")?.text()?,
        material: node
            .req("material", "the name of a material in materials")?
            .text()?,
        web: optional(node, "web", |n| n.text())?,
        thickness: span(
            &node.req("thickness", "a mapping with grid and values (m)")?,
            Range::NonNegative,
        )?,
        n_plies: optional(node, "n_plies", |n| span(n, Range::NonNegative))?,
        fiber_orientation: optional(node, "fiber_orientation", |n| span(n, Range::Any))?,
        start_nd_arc: optional(node, "start_nd_arc", arc_position)?,
        end_nd_arc: optional(node, "end_nd_arc", arc_position)?,
        midpoint_nd_arc: optional(node, "midpoint_nd_arc", arc_position)?,
        width: optional(node, "width", |n| span(n, Range::NonNegative))?,
        side,
        offset: offset(node)?,
        rotation: optional(node, "rotation", rotation)?,
        line: node.line(),
    };
    if layer.placement().is_none() {
        return Err(node.error(
            "expected the layer's position: web, or start_nd_arc and end_nd_arc, or width with \
             midpoint_nd_arc, start_nd_arc, end_nd_arc or side and offset_y_pa, or none of \
             these (the whole section)",
        ));
    }
    Ok(layer)
}
