//! A section's mesh from its layup (docs/model.md §11.12): the outer contour, the layers laid
//! inward from it between their arc positions, and the shear webs between the shell's inner
//! faces, meshed with 4-node quadrilaterals for the section analysis of [`super::solve`].
//!
//! - **Columns** along the arc: at every layer edge, at every web face, at the contour's own
//!   points, and in between at most `element_length` apart. Between two neighbouring columns the
//!   set of layers is the same, so each layer is one row of elements (or `rows_per_layer`) from
//!   column to column.
//! - **Stacking.** At a column the layers present are stacked inward along the contour's inward
//!   normal in the given order (the ontology's: outer surface first). Where a layer ends, the
//!   edge column carries the fraction `δ_in/(δ_in + δ_out)` of its thickness (`δ` the lengths of
//!   the segments on its two sides), which keeps the layer's area exactly; the element beyond
//!   the edge is a collapsed quadrilateral (a triangle).
//! - **Where the walls meet.** A stack deeper than half the distance to the opposite wall
//!   (near a sharp trailing edge, where the two skins close in on each other; see
//!   `Outline::room`) is scaled down to it: the mass cut away is reported
//!   ([`LayupMesh::clipped_mass`]). The stack's normal is averaged along the arc over three
//!   times its depth, so that round a corner (a flatback's) the rows fan out without folding.
//! - **Webs**: the web's layers side by side across its thickness, centred on the line between
//!   its two footprints (its plane), each face where it meets the shell a column of the shell, so
//!   the web's ends are the shell's innermost nodes there and the mesh is conforming.
//!
//! The layup is given in the chord frame (`X` along the chord toward the trailing edge, `Y`
//! toward the suction side, about the section's reference point); the mesh comes out in
//! BeamDyn's section axes (`x₁ = Y` toward the suction side, `x₂ = X` toward the trailing edge,
//! `z = x₁ × x₂` toward the tip), so the analysis gives a blade file's matrices directly.
//!
//! Fibre angles: a shell ply's fibre is turned by its angle θ from the beam axis toward the
//! leading edge along the contour (`e₁ = cos θ e_z + sin θ t`, `t` the contour's tangent
//! pointing to the leading edge: toward growing arc on the suction side, falling arc on the
//! pressure side), so equal angles on the two skins lay the fibres parallel in space; a web
//! ply's from the beam axis toward the pressure side along the web.

use super::material::Orthotropic;
use super::mesh::{Element, Mesh, Ply};
use crate::error::{Error, Result};

/// A layer on the outer shell, between two non-dimensional arc positions (`start > end` runs
/// across the trailing edge, arc 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellLayer {
    pub material: usize,
    /// m (≥ 0; a layer of zero thickness is left out).
    pub thickness: f64,
    /// rad, toward the leading edge (module documentation).
    pub fibre_angle: f64,
    pub start: f64,
    pub end: f64,
    /// A fill up to the line across the chord at this `X` (chord frame, m): the layer takes
    /// whatever depth the other layers leave, to that line or to the opposite wall, whichever
    /// is nearer (`thickness` is then unused), as a trailing edge's bond or filler closes the
    /// cavity between the skins behind a line.
    pub fill_to: Option<f64>,
}

/// One layer of a shear web.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WebLayer {
    pub material: usize,
    /// m (≥ 0).
    pub thickness: f64,
    /// rad, toward the pressure side along the web.
    pub fibre_angle: f64,
}

/// A shear web: where its plane meets the outer contour (non-dimensional arc on the suction
/// side, then on the pressure side) and its layers from its leading-edge face to its
/// trailing-edge face.
#[derive(Debug, Clone, PartialEq)]
pub struct WebLayup {
    pub start: f64,
    pub end: f64,
    pub layers: Vec<WebLayer>,
}

/// A section as its layup describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Layup {
    /// The outer contour from arc 0 (the trailing edge, suction side) over the suction side,
    /// round the leading edge and back (arc 1): a closed loop (the last point equals the first)
    /// turning counterclockwise, m, chord frame.
    pub contour: Vec<[f64; 2]>,
    /// Non-dimensional arc of the leading edge.
    pub leading_edge: f64,
    /// The shell's layers, outer surface first.
    pub shell: Vec<ShellLayer>,
    pub webs: Vec<WebLayup>,
    pub materials: Vec<Orthotropic>,
}

/// How fine the mesh is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meshing {
    /// Largest element length along the contour and along the webs, m.
    pub element_length: f64,
    /// Element rows through each layer's thickness (≥ 1).
    pub rows_per_layer: usize,
}

impl Meshing {
    /// The default for a blade section of perimeter `perimeter` (m): 240 elements round it,
    /// one row per layer. The stiffnesses are within 0.5 % of a twice finer mesh on the
    /// IEA 15MW (docs/model.md §11.12).
    pub fn for_perimeter(perimeter: f64) -> Meshing {
        Meshing {
            element_length: perimeter / 240.0,
            rows_per_layer: 1,
        }
    }
}

/// Which layer of the [`Layup`] an element lies in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LayerOf {
    /// `layup.shell[i]`.
    Shell(usize),
    /// `layup.webs[web].layers[layer]`.
    Web { web: usize, layer: usize },
}

/// The mesh and what the meshing had to leave out.
#[derive(Debug, Clone, PartialEq)]
pub struct LayupMesh {
    /// In BeamDyn's section axes, about the reference point.
    pub mesh: Mesh,
    /// The layer of each element of `mesh`.
    pub layers: Vec<LayerOf>,
    /// Mass per length of the layers cut away where the walls meet (kg/m).
    pub clipped_mass: f64,
    /// Mass per length the layup asks for on the shell (kg/m), for scale.
    pub shell_mass: f64,
}

fn invalid(message: String) -> Error {
    Error::Invalid {
        origin: "section layup".into(),
        message,
    }
}

/// Nodes of one column closer than this (m) are one node.
const SAME_DEPTH: f64 = 1e-9;
/// A layer thinner than this (m) at a station is absent there.
const THINNEST: f64 = 1e-6;
/// Columns closer than this (m of arc) are one column.
const SAME_COLUMN: f64 = 1e-5;

/// The contour as a polygon with its arc length.
struct Outline {
    points: Vec<[f64; 2]>,
    /// Non-dimensional arc at each point (0 … 1).
    arc: Vec<f64>,
    length: f64,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = v[0].hypot(v[1]);
    [v[0] / n, v[1] / n]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl Outline {
    fn new(points: &[[f64; 2]]) -> Result<Outline> {
        let n = points.len();
        if n < 4 || points[0] != points[n - 1] {
            return Err(invalid(format!(
                "expected a closed contour (last point equal to the first) of at least three \
                 distinct points, found {n} points"
            )));
        }
        if points
            .iter()
            .any(|p| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(invalid("expected finite contour points".into()));
        }
        let mut arc = vec![0.0];
        let mut total = 0.0;
        for w in points.windows(2) {
            let d = sub(w[1], w[0]);
            if d[0].hypot(d[1]) == 0.0 {
                return Err(invalid("the contour repeats a point".into()));
            }
            total += d[0].hypot(d[1]);
            arc.push(total);
        }
        let twice_area: f64 = points.windows(2).map(|w| cross(w[0], w[1])).sum();
        if twice_area <= 0.0 {
            return Err(invalid(
                "expected the contour to turn counterclockwise (suction side first)".into(),
            ));
        }
        arc.iter_mut().for_each(|a| *a /= total);
        Ok(Outline {
            points: points.to_vec(),
            arc,
            length: total,
        })
    }

    /// The greatest X, where the trailing edge is.
    fn trailing_edge_x(&self) -> f64 {
        self.points
            .iter()
            .map(|p| p[0])
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The trailing edge's corners: the last suction-side and the first pressure-side point of
    /// greatest X (arcs 0 and 1, one point, for a sharp edge; the ends of the face of an open
    /// one).
    fn trailing_edge_corners(&self, le: f64) -> (f64, f64) {
        let x_max = self.trailing_edge_x();
        let on_edge: Vec<f64> = (0..self.points.len())
            .filter(|&i| self.points[i][0] == x_max)
            .map(|i| self.arc[i])
            .collect();
        (
            on_edge
                .iter()
                .copied()
                .filter(|&a| a < le)
                .fold(0.0, f64::max),
            on_edge
                .iter()
                .copied()
                .filter(|&a| a > le)
                .fold(1.0, f64::min),
        )
    }

    /// The segment holding arc `s` (the last segment for s = 1).
    fn segment(&self, s: f64) -> usize {
        self.arc
            .partition_point(|&a| a <= s)
            .clamp(1, self.points.len() - 1)
            - 1
    }

    fn point(&self, s: f64) -> [f64; 2] {
        let i = self.segment(s);
        let t = (s - self.arc[i]) / (self.arc[i + 1] - self.arc[i]);
        let (a, b) = (self.points[i], self.points[i + 1]);
        [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    }

    /// The unit tangent of segment `i` (cyclic), along growing arc.
    fn tangent(&self, i: usize) -> [f64; 2] {
        let m = self.points.len() - 1;
        let i = i % m;
        unit(sub(self.points[i + 1], self.points[i]))
    }

    /// The vertex at arc `s`, if `s` is one.
    fn vertex(&self, s: f64) -> Option<usize> {
        let i = self.segment(s);
        if s == self.arc[i] {
            Some(i)
        } else if s == self.arc[i + 1] {
            Some(i + 1)
        } else {
            None
        }
    }

    /// The inward unit normal at arc `s` (at a vertex, the mean of its two segments').
    fn inward_normal(&self, s: f64) -> [f64; 2] {
        let m = self.points.len() - 1;
        let left = |t: [f64; 2]| [-t[1], t[0]];
        match self.vertex(s) {
            Some(v) => {
                let (before, after) = (
                    left(self.tangent((v + m - 1) % m)),
                    left(self.tangent(v % m)),
                );
                unit([before[0] + after[0], before[1] + after[1]])
            }
            None => left(self.tangent(self.segment(s))),
        }
    }

    /// How deep a stack may reach at `p` with inward normal `n`: half the distance to the
    /// nearest contour point seen within 40° of the normal (the opposite skin across a thin
    /// trailing edge, the far side of a tight nose), so that the two skins' stacks never cross
    /// and a stack never reaches past the centre of the curvature it lies on. A flat neighbour
    /// on the same skin lies at 90° and a flatback's other face at 45°: neither limits it.
    fn room(&self, p: [f64; 2], n: [f64; 2]) -> f64 {
        let cone = 40f64.to_radians().cos();
        let skip = 1e-9 * self.length;
        self.points
            .iter()
            .filter_map(|&q| {
                let d = sub(q, p);
                let r = d[0].hypot(d[1]);
                (r > skip && d[0] * n[0] + d[1] * n[1] >= cone * r).then_some(r)
            })
            .fold(f64::INFINITY, f64::min)
            / 2.0
    }

    /// The inward normal at arc `s` averaged over the arc within `window` m of it (each
    /// segment's normal weighted by its length inside): turning gradually round a corner, the
    /// normals of a stack of depth under about `window`/1.6 do not cross.
    fn smoothed_normal(&self, s: f64, window: f64) -> [f64; 2] {
        let half = window / 2.0 / self.length;
        if half <= 0.0 {
            return self.inward_normal(s);
        }
        let mut sum = [0.0, 0.0];
        // The window may run across s = 0: look at the contour shifted by a whole turn too.
        for shift in [-1.0, 0.0, 1.0] {
            let (lo, hi) = (s - half - shift, s + half - shift);
            // Only the segments that reach into the window add to the sum.
            let first = self.arc.partition_point(|&a| a <= lo).saturating_sub(1);
            let last = self
                .arc
                .partition_point(|&a| a < hi)
                .min(self.points.len() - 1);
            for i in first..last {
                let overlap = self.arc[i + 1].min(hi) - self.arc[i].max(lo);
                if overlap > 0.0 {
                    let t = self.tangent(i);
                    sum[0] -= overlap * t[1];
                    sum[1] += overlap * t[0];
                }
            }
        }
        unit(sum)
    }

    /// The step inward per metre of stack at arc `s`: along the normal averaged over `window`
    /// ([`Self::smoothed_normal`]), lengthened so that the stack's depth is its thickness
    /// measured square to the wall it lies on (at a vertex, to both walls: a corner's stack ends
    /// where the offset walls meet, as a mitre does). At most twice the normal.
    fn offset_direction(&self, s: f64, window: f64) -> [f64; 2] {
        let n = self.smoothed_normal(s, window);
        let m = self.points.len() - 1;
        let left = |t: [f64; 2]| [-t[1], t[0]];
        let walls = match self.vertex(s) {
            Some(v) => [
                left(self.tangent((v + m - 1) % m)),
                left(self.tangent(v % m)),
            ],
            None => [left(self.tangent(self.segment(s))); 2],
        };
        let square = walls
            .iter()
            .map(|w| w[0] * n[0] + w[1] * n[1])
            .fold(f64::INFINITY, f64::min)
            .max(0.5);
        [n[0] / square, n[1] / square]
    }

    /// The arc between `from` and `to` (in [0, 1]) where the line `{q : (q − point)·normal = 0}`
    /// crosses the contour nearest to `near`.
    fn crossing(
        &self,
        point: [f64; 2],
        normal: [f64; 2],
        from: f64,
        to: f64,
        near: f64,
    ) -> Option<f64> {
        let f = |q: [f64; 2]| (q[0] - point[0]) * normal[0] + (q[1] - point[1]) * normal[1];
        let mut best: Option<f64> = None;
        for i in 0..self.points.len() - 1 {
            let (s0, s1) = (self.arc[i], self.arc[i + 1]);
            if s1 < from || s0 > to {
                continue;
            }
            let (f0, f1) = (f(self.points[i]), f(self.points[i + 1]));
            let s = if f0 == 0.0 {
                s0
            } else if f0 * f1 < 0.0 {
                s0 + f0 / (f0 - f1) * (s1 - s0)
            } else {
                continue;
            };
            if (from..=to).contains(&s) && best.is_none_or(|b| (s - near).abs() < (b - near).abs())
            {
                best = Some(s);
            }
        }
        best
    }
}

/// A column's stack depth in its layers outside any fill, and in its fills.
fn depths(stack: &[f64], fills: &[bool]) -> (f64, f64) {
    stack
        .iter()
        .zip(fills)
        .fold((0.0, 0.0), |(laid, filled), (&t, &fill)| {
            if fill {
                (laid, filled + t)
            } else {
                (laid + t, filled)
            }
        })
}

/// Whether a layer from `start` to `end` covers arc `s`.
fn covers(start: f64, end: f64, s: f64) -> bool {
    if start <= end {
        start <= s && s <= end
    } else {
        s >= start || s <= end
    }
}

/// A web's face lines: the arcs where each line across its thickness (its faces and the
/// boundaries between its layers, with the rows between) meets the suction and the pressure
/// side, and each row's ply.
struct WebLines {
    suction: Vec<f64>,
    pressure: Vec<f64>,
    plies: Vec<Ply>,
    /// The web's layer (index in the layup) of each row.
    ply_layers: Vec<usize>,
    /// Unit vector along the web from the suction to the pressure side (chord frame).
    along: [f64; 2],
}

fn web_lines(outline: &Outline, le: f64, web: &WebLayup, rows: usize) -> Result<Option<WebLines>> {
    let layers: Vec<(usize, &WebLayer)> = web
        .layers
        .iter()
        .enumerate()
        .filter(|(_, l)| l.thickness >= THINNEST)
        .collect();
    let total: f64 = layers.iter().map(|(_, l)| l.thickness).sum();
    if layers.is_empty() {
        return Ok(None);
    }
    let (a, b) = (outline.point(web.start), outline.point(web.end));
    let along = unit(sub(b, a));
    // Across the web toward the trailing edge (+X in the chord frame).
    let mut across = [along[1], -along[0]];
    if across[0] < 0.0 {
        across = [-across[0], -across[1]];
    }
    let mut offsets = vec![-total / 2.0];
    let mut plies = Vec::new();
    let mut ply_layers = Vec::new();
    for &(index, l) in &layers {
        let o = *offsets.last().expect("starts with one offset");
        for k in 1..=rows {
            offsets.push(o + l.thickness * k as f64 / rows as f64);
            plies.push(Ply {
                material: l.material,
                fibre_angle: l.fibre_angle,
                orientation: 0.0,
            });
            ply_layers.push(index);
        }
    }
    let meet = |o: f64, from: f64, to: f64, near: f64| {
        let p = [a[0] + o * across[0], a[1] + o * across[1]];
        outline.crossing(p, across, from, to, near).ok_or_else(|| {
            invalid(format!(
                "the web between arcs {} and {} with faces {total} m apart does not meet the \
                 contour on both sides",
                web.start, web.end
            ))
        })
    };
    let suction = offsets
        .iter()
        .map(|&o| meet(o, 0.0, le, web.start))
        .collect::<Result<Vec<_>>>()?;
    let pressure = offsets
        .iter()
        .map(|&o| meet(o, le, 1.0, web.end))
        .collect::<Result<Vec<_>>>()?;
    Ok(Some(WebLines {
        suction,
        pressure,
        plies,
        ply_layers,
        along,
    }))
}

/// The trailing edge's closing zone: where the two skins' stacks, laid toward each other, fill
/// the section's whole depth. There the columns come in pairs at equal `X` (one on each skin)
/// and each pair's stacks run along the line between them and meet: their innermost node is
/// one, so the skins are joined and the trailing-edge cell stays closed. Returns the pairs
/// (suction-side arc, pressure-side arc), from the trailing edge forward; none where the stacks
/// never fill the depth (a thick flatback).
fn trailing_edge_pairs(
    outline: &Outline,
    le: f64,
    shell: &[&ShellLayer],
    h: f64,
) -> Vec<(f64, f64)> {
    let stack = |s: f64| -> f64 {
        shell
            .iter()
            .filter(|l| covers(l.start, l.end, s))
            .map(|l| l.thickness)
            .sum()
    };
    let x_max = outline.trailing_edge_x();
    let (corner_ss, corner_ps) = outline.trailing_edge_corners(le);
    let at_x = |x: f64| -> Option<(f64, f64)> {
        let ss = outline.crossing([x, 0.0], [1.0, 0.0], corner_ss, le, corner_ss)?;
        let ps = outline.crossing([x, 0.0], [1.0, 0.0], le, corner_ps, corner_ps)?;
        Some((ss, ps))
    };
    // The stacks reach across the gap as far as their normals point into it: a round edge's
    // normals point forward, not across, so its skins' stacks never meet.
    let fills = |(ss, ps): (f64, f64)| {
        let g = sub(outline.point(ps), outline.point(ss));
        let gap = g[0].hypot(g[1]);
        if gap == 0.0 {
            return false;
        }
        let u = [g[0] / gap, g[1] / gap];
        let (n_ss, n_ps) = (outline.inward_normal(ss), outline.inward_normal(ps));
        let across = |n: [f64; 2], sign: f64| (sign * (n[0] * u[0] + n[1] * u[1])).max(0.0);
        stack(ss) * across(n_ss, 1.0) + stack(ps) * across(n_ps, -1.0) >= gap
    };
    // A sharp edge (its skins meeting at under a right angle) is closed by its stacks; a
    // smooth one (a round tube's) is not an edge at all.
    let sharp = || {
        let m = outline.points.len() - 1;
        let (out, back) = (outline.tangent(0), outline.tangent(m - 1));
        out[0] * back[0] + out[1] * back[1] < 0.0
    };
    let closes = if corner_ss == 0.0 && corner_ps == 1.0 {
        sharp()
    } else {
        fills((corner_ss, corner_ps))
    };
    if !closes {
        return Vec::new();
    }
    // Forward in steps of a quarter element until the stacks no longer meet.
    let chord = x_max
        - outline
            .points
            .iter()
            .map(|p| p[0])
            .fold(f64::INFINITY, f64::min);
    let step = h / 4.0;
    let mut x_end = x_max;
    while x_end > x_max - 0.5 * chord {
        match at_x(x_end - step) {
            Some(pair) if fills(pair) => x_end -= step,
            _ => break,
        }
    }
    if x_end == x_max {
        return vec![(corner_ss, corner_ps)];
    }
    // Every layer edge inside the zone, on either skin, gets its pair; then at most h apart.
    let mut xs: Vec<f64> = vec![x_max, x_end];
    for l in shell {
        for e in [l.start, l.end] {
            let p = outline.point(e);
            if p[0] > x_end && p[0] < x_max {
                xs.push(p[0]);
            }
        }
    }
    xs.sort_by(|a, b| b.total_cmp(a));
    xs.dedup_by(|b, a| (*a - *b) < SAME_COLUMN);
    let mut filled = vec![xs[0]];
    for w in xs.windows(2) {
        let m = ((w[0] - w[1]) / h).ceil().max(1.0) as usize;
        for i in 1..=m {
            filled.push(w[0] + (w[1] - w[0]) * i as f64 / m as f64);
        }
    }
    let mut pairs = vec![(corner_ss, corner_ps)];
    pairs.extend(filled[1..].iter().filter_map(|&x| at_x(x)));
    pairs
}

/// The columns: every breakpoint, the contour's points not too close to them, and fill-ins at
/// most `h` m apart; in the trailing edge's zone (arc below `frozen[0]` or above `frozen[1]`)
/// only the breakpoints, which come in pairs there. Sorted, in [0, 1), the first at 0.
fn columns(outline: &Outline, breaks: &[f64], h: f64, frozen: [f64; 2]) -> Vec<f64> {
    let l = outline.length;
    let mut must: Vec<f64> = breaks
        .iter()
        .map(|&s| if s >= 1.0 { 0.0 } else { s })
        .collect();
    must.push(0.0);
    must.sort_by(f64::total_cmp);
    must.dedup_by(|b, a| (*b - *a) * l < SAME_COLUMN);
    if (1.0 - must[must.len() - 1]) * l < SAME_COLUMN && must.len() > 1 {
        must.pop();
    }
    let mut out = Vec::new();
    for (k, &s0) in must.iter().enumerate() {
        let s1 = must.get(k + 1).copied().unwrap_or(1.0);
        if s1 <= frozen[0] + SAME_COLUMN / l || s0 >= frozen[1] - SAME_COLUMN / l {
            out.push(s0);
            continue;
        }
        let mut kept = vec![s0];
        let gap = 0.3 * h / l;
        for &v in &outline.arc {
            if v > s0 + gap && v < s1 - gap && v > kept[kept.len() - 1] + gap {
                kept.push(v);
            }
        }
        kept.push(s1);
        for w in kept.windows(2) {
            let n = ((w[1] - w[0]) * l / h).ceil().max(1.0) as usize;
            for i in 0..n {
                out.push(w[0] + (w[1] - w[0]) * i as f64 / n as f64);
            }
        }
    }
    out
}

/// The mesh of `layup` (module documentation).
pub fn mesh_layup(layup: &Layup, meshing: Meshing) -> Result<LayupMesh> {
    check(layup, meshing)?;
    let outline = Outline::new(&layup.contour)?;
    let (h, rows) = (meshing.element_length, meshing.rows_per_layer);
    let le = layup.leading_edge;
    let scale = layup
        .contour
        .iter()
        .map(|p| p[0].abs().max(p[1].abs()))
        .fold(0.0, f64::max);
    // A fill is laid as deep as the section is wide, then cut back to its line and to what the
    // other layers and the walls' clipping leave it.
    let laid: Vec<ShellLayer> = layup
        .shell
        .iter()
        .map(|l| ShellLayer {
            thickness: if l.fill_to.is_some() {
                2.0 * scale
            } else {
                l.thickness
            },
            ..*l
        })
        .collect();
    let shell: Vec<&ShellLayer> = laid.iter().filter(|l| l.thickness >= THINNEST).collect();
    let shell_index: Vec<usize> = (0..laid.len())
        .filter(|&i| laid[i].thickness >= THINNEST)
        .collect();
    let fills: Vec<bool> = shell.iter().map(|l| l.fill_to.is_some()).collect();

    let webs = layup
        .webs
        .iter()
        .map(|w| web_lines(&outline, le, w, rows))
        .collect::<Result<Vec<_>>>()?;
    let mut breaks: Vec<f64> = shell.iter().flat_map(|l| [l.start, l.end]).collect();
    for w in webs.iter().flatten() {
        breaks.extend(&w.suction);
        breaks.extend(&w.pressure);
    }
    // An open trailing edge's corners are columns, so the face between them keeps its shape.
    let (corner_ss, corner_ps) = outline.trailing_edge_corners(le);
    breaks.extend([corner_ss, corner_ps]);
    let pairs = trailing_edge_pairs(&outline, le, &shell, h);
    for &(ss, ps) in &pairs {
        breaks.extend([ss, ps]);
    }
    let frozen = match pairs.last() {
        Some(&(ss, ps)) => [ss, ps],
        None => [0.0, 1.0],
    };
    if !pairs.is_empty() {
        // The corners' stacks meet at the open face's middle and lie along it: a column
        // between them (a layer's edge on the face) would carry nothing.
        breaks.retain(|&b| !((0.0 < b && b < corner_ss) || (corner_ps < b && b < 1.0)));
    }
    let cols = columns(&outline, &breaks, h, frozen);
    let n = cols.len();
    let at = |k: usize| if k == n { 1.0 } else { cols[k] };
    let seg_len = |k: usize| (at(k + 1) - cols[k]) * outline.length;

    // Each layer's thickness at each column, before and after clipping.
    let mut thick = vec![vec![0.0; shell.len()]; n];
    let mut points = Vec::with_capacity(n);
    let mut clipped_mass = 0.0;
    let mut cut = vec![vec![0.0; shell.len()]; n];
    for k in 0..n {
        let (before, after) = ((k + n - 1) % n, k);
        let (d_in_left, d_in_right) = (seg_len(before), seg_len(after));
        let mid = |j: usize| (cols[j] + at(j + 1)) / 2.0;
        for (i, l) in shell.iter().enumerate() {
            let left = covers(l.start, l.end, mid(before));
            let right = covers(l.start, l.end, mid(after));
            let f = match (left, right) {
                (true, true) => 1.0,
                (true, false) => d_in_left / (d_in_left + d_in_right),
                (false, true) => d_in_right / (d_in_left + d_in_right),
                (false, false) => 0.0,
            };
            thick[k][i] = f * l.thickness;
        }
        let point = outline.point(cols[k]);
        let (outside, _) = depths(&thick[k], &fills);
        for (i, l) in shell.iter().enumerate() {
            if let (Some(x), true) = (l.fill_to, thick[k][i] > 0.0) {
                // Along the inward normal to the fill's line, less the layers outside it.
                let n = outline.inward_normal(cols[k]);
                let to_line = if n[0] < 0.0 {
                    ((x - point[0]) / n[0]).max(0.0)
                } else {
                    thick[k][i]
                };
                thick[k][i] = (to_line.min(thick[k][i]) - outside).max(0.0);
            }
        }
        points.push(point);
    }
    // A stack deeper than `depth` is scaled down to it, a fill first: what it gives up is not
    // cut (it only ever takes the room left), what the other layers give up is.
    let clip = |thick: &mut Vec<Vec<f64>>, cut: &mut Vec<Vec<f64>>, k: usize, depth: f64| {
        let (laid, filled) = depths(&thick[k], &fills);
        if filled + laid <= depth {
            return;
        }
        let room = (depth - laid).max(0.0);
        let c = if laid > depth { depth / laid } else { 1.0 };
        for i in 0..thick[k].len() {
            if fills[i] {
                thick[k][i] = if filled > 0.0 {
                    thick[k][i] * room / filled
                } else {
                    0.0
                };
            } else {
                cut[k][i] += thick[k][i] * (1.0 - c);
                thick[k][i] *= c;
            }
        }
    };
    // The trailing edge's pairs: each stack runs toward the other skin and the two meet
    // (`trailing_edge_pairs`); at an open edge the corners' stacks meet at its middle, the
    // column at arc 0, whose own stack is empty, as at a sharp edge.
    let column_of = |s: f64| -> usize {
        let s = if s >= 1.0 { 0.0 } else { s };
        (0..n)
            .min_by(|&a, &b| (cols[a] - s).abs().total_cmp(&(cols[b] - s).abs()))
            .expect("at least one column")
    };
    let mut direction: Vec<Option<[f64; 2]>> = vec![None; n];
    let mut weld: Vec<Option<usize>> = vec![None; n];
    if !pairs.is_empty() {
        clip(&mut thick, &mut cut, 0, 0.0);
    }
    for (j, &(ss, ps)) in pairs.iter().enumerate() {
        let (a, b) = (column_of(ss), column_of(ps));
        if a == b || a == 0 || b == 0 {
            continue;
        }
        let g = sub(points[b], points[a]);
        let gap = g[0].hypot(g[1]);
        let u = [g[0] / gap, g[1] / gap];
        let (da, db): (f64, f64) = (thick[a].iter().sum(), thick[b].iter().sum());
        if j == 0 {
            // The open edge's corners: each stack reaches the middle, where column 0 is.
            clip(&mut thick, &mut cut, a, gap / 2.0);
            clip(&mut thick, &mut cut, b, gap / 2.0);
            weld[a] = Some(0);
            weld[b] = Some(0);
        } else if da + db >= gap {
            // The gap is shared by the layers' depths, a fill giving way first.
            let ((fa, ga), (fb, gb)) = (depths(&thick[a], &fills), depths(&thick[b], &fills));
            let (ta, tb) = if fa + fb >= gap {
                (gap * fa / (fa + fb), gap * fb / (fa + fb))
            } else {
                let room = gap - fa - fb;
                (fa + room * ga / (ga + gb), fb + room * gb / (ga + gb))
            };
            clip(&mut thick, &mut cut, a, ta);
            clip(&mut thick, &mut cut, b, tb);
            weld[b] = Some(a);
        } else {
            continue;
        }
        direction[a] = Some(u);
        direction[b] = Some([-u[0], -u[1]]);
    }
    for k in 0..n {
        if direction[k].is_none() && k != 0 || pairs.is_empty() {
            let room = outline.room(points[k], outline.inward_normal(cols[k]));
            clip(&mut thick, &mut cut, k, room);
        }
    }
    // The stack's normals turn over three times the deepest stack nearby, so that round a
    // flatback's corners the rows fan out instead of folding. Where a row still folds (a stack
    // in the last millimetres of a sharp trailing edge), both its columns' stacks are thinned
    // until none does; what that takes away is clipped mass like the rest.
    let mut normals = Vec::new();
    for _ in 0..60 {
        // A fill's depth is the cavity's, not a wall's: it does not widen the window.
        let depth: Vec<f64> = thick.iter().map(|t| depths(t, &fills).0).collect();
        normals = (0..n)
            .map(|k| {
                direction[k].unwrap_or_else(|| {
                    let near = depth[(k + n - 1) % n].max(depth[k]).max(depth[(k + 1) % n]);
                    outline.offset_direction(cols[k], 3.0 * near)
                })
            })
            .collect();
        let folded: Vec<usize> = (0..n)
            .filter(|&k| {
                folds(
                    &points,
                    &normals,
                    &thick,
                    k,
                    (k + 1) % n,
                    1e-12 * scale * scale,
                )
            })
            .collect();
        if folded.is_empty() {
            break;
        }
        for k in folded {
            for c in [k, (k + 1) % n]
                .into_iter()
                .filter(|&c| weld[c].is_none() && direction[c].is_none())
            {
                for i in 0..shell.len() {
                    if !fills[i] {
                        cut[c][i] += 0.3 * thick[c][i];
                    }
                    thick[c][i] *= 0.7;
                }
            }
        }
    }
    let mut shell_mass = 0.0;
    for k in 0..n {
        let k1 = (k + 1) % n;
        for (i, l) in shell.iter().enumerate() {
            let rho = layup.materials[l.material].rho;
            clipped_mass += rho * 0.5 * (cut[k][i] + cut[k1][i]) * seg_len(k);
            shell_mass +=
                rho * 0.5 * (cut[k][i] + cut[k1][i] + thick[k][i] + thick[k1][i]) * seg_len(k);
        }
    }

    // Nodes, column by column: level j lies `rows` levels per layer deep.
    let levels = shell.len() * rows + 1;
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut level_node = vec![vec![0usize; levels]; n];
    for k in 0..n {
        let total: f64 = thick[k].iter().filter(|&&t| t >= THINNEST).sum();
        let mut depth = 0.0;
        let mut last = nodes.len();
        nodes.push(points[k]);
        level_node[k][0] = last;
        for (i, &t) in thick[k].iter().enumerate() {
            for r in 1..=rows {
                let j = i * rows + r;
                let d = depth + t * r as f64 / rows as f64;
                if t >= THINNEST && d > depth + SAME_DEPTH {
                    last = match weld[k] {
                        // The innermost node is the partner's (they are at one point).
                        Some(w) if r == rows && (total - (depth + t)).abs() <= SAME_DEPTH => {
                            level_node[w][levels - 1]
                        }
                        _ => {
                            let p = points[k];
                            nodes.push([p[0] + d * normals[k][0], p[1] + d * normals[k][1]]);
                            nodes.len() - 1
                        }
                    };
                }
                level_node[k][j] = last;
            }
            if t >= THINNEST {
                depth += t;
            }
        }
    }

    // Shell elements: counterclockwise in the chord frame as (outer k, outer k+1, inner k+1,
    // inner k).
    let mut elements: Vec<Element> = Vec::new();
    let mut layers: Vec<LayerOf> = Vec::new();
    for k in 0..n {
        let k1 = (k + 1) % n;
        let mid = (cols[k] + at(k + 1)) / 2.0;
        let mut t = unit(sub(points[k1], points[k]));
        if mid > le {
            t = [-t[0], -t[1]];
        }
        for (i, l) in shell.iter().enumerate() {
            if !covers(l.start, l.end, mid) && thick[k][i] == 0.0 && thick[k1][i] == 0.0 {
                continue;
            }
            for r in 0..rows {
                let j = i * rows + r;
                let q = [
                    level_node[k][j],
                    level_node[k1][j],
                    level_node[k1][j + 1],
                    level_node[k][j + 1],
                ];
                let p = q.map(|v| nodes[v]);
                if cross(sub(p[2], p[0]), sub(p[3], p[1])).abs() <= 1e-12 * scale * scale {
                    // Nothing between the columns (an empty layer, or the open trailing
                    // edge's corner stacks lying along its face).
                    continue;
                }
                elements.push(Element {
                    nodes: q,
                    ply: Ply {
                        material: l.material,
                        fibre_angle: l.fibre_angle,
                        orientation: orientation_in_section_axes(t),
                    },
                });
                layers.push(LayerOf::Shell(shell_index[i]));
            }
        }
    }

    // Webs between the shell's innermost nodes at their face columns.
    for (web, w) in webs
        .iter()
        .enumerate()
        .filter_map(|(k, w)| w.as_ref().map(|w| (k, w)))
    {
        let ends: Vec<(usize, usize)> = w
            .suction
            .iter()
            .zip(&w.pressure)
            .map(|(&a, &b)| {
                (
                    level_node[column_of(a)][levels - 1],
                    level_node[column_of(b)][levels - 1],
                )
            })
            .collect();
        let height = ends
            .iter()
            .map(|&(a, b)| {
                let d = sub(nodes[b], nodes[a]);
                d[0].hypot(d[1])
            })
            .fold(0.0, f64::max);
        let m = (height / h).ceil().max(1.0) as usize;
        let lines: Vec<Vec<usize>> = ends
            .iter()
            .map(|&(a, b)| {
                let (pa, pb) = (nodes[a], nodes[b]);
                let mut line = vec![a];
                for i in 1..m {
                    let f = i as f64 / m as f64;
                    nodes.push([pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])]);
                    line.push(nodes.len() - 1);
                }
                line.push(b);
                line
            })
            .collect();
        for (j, ply) in w.plies.iter().enumerate() {
            for i in 0..m {
                let mut q = [
                    lines[j][i],
                    lines[j + 1][i],
                    lines[j + 1][i + 1],
                    lines[j][i + 1],
                ];
                let p = q.map(|v| nodes[v]);
                let twice_area = cross(sub(p[2], p[0]), sub(p[3], p[1]));
                if twice_area < 0.0 {
                    q.reverse();
                }
                elements.push(Element {
                    nodes: q,
                    ply: Ply {
                        orientation: orientation_in_section_axes(w.along),
                        ..*ply
                    },
                });
                layers.push(LayerOf::Web {
                    web,
                    layer: w.ply_layers[j],
                });
            }
        }
    }

    // Into BeamDyn's section axes: (x₁, x₂) = (Y, X), a reflection, so each element's corners
    // are listed the other way round to stay counterclockwise.
    let nodes = nodes.into_iter().map(|p| [p[1], p[0]]).collect();
    for e in &mut elements {
        let q = e.nodes;
        e.nodes = [q[0], q[3], q[2], q[1]];
    }
    let mesh = Mesh {
        nodes,
        elements,
        materials: layup.materials.clone(),
    };
    mesh.validate()?;
    Ok(LayupMesh {
        mesh,
        layers,
        clipped_mass,
        shell_mass,
    })
}

impl LayupMesh {
    /// This mesh with each element's fibre angle from `layup`, a layup that differs from the
    /// one meshed (`meshed`) in its fibre angles only (a ply turn): the same elements, so the
    /// same factorisation pattern. `None` when `layup` differs in anything else.
    pub fn turned(&self, meshed: &Layup, layup: &Layup) -> Option<LayupMesh> {
        if !same_but_angles(meshed, layup) {
            return None;
        }
        let mut turned = self.clone();
        for (e, layer) in turned.mesh.elements.iter_mut().zip(&self.layers) {
            e.ply.fibre_angle = match *layer {
                LayerOf::Shell(i) => layup.shell[i].fibre_angle,
                LayerOf::Web { web, layer } => layup.webs[web].layers[layer].fibre_angle,
            };
        }
        Some(turned)
    }
}

/// Whether two layups are the same but for their layers' fibre angles.
fn same_but_angles(a: &Layup, b: &Layup) -> bool {
    let shell = |l: &ShellLayer| (l.material, l.thickness, l.start, l.end, l.fill_to);
    let web = |l: &WebLayer| (l.material, l.thickness);
    a.contour == b.contour
        && a.leading_edge == b.leading_edge
        && a.materials == b.materials
        && a.shell.iter().map(shell).eq(b.shell.iter().map(shell))
        && a.webs.len() == b.webs.len()
        && a.webs.iter().zip(&b.webs).all(|(x, y)| {
            (x.start, x.end) == (y.start, y.end)
                && x.layers.iter().map(web).eq(y.layers.iter().map(web))
        })
}

/// Whether a row of the stacks between columns `k` and `k1` folds: a corner of its quadrilateral
/// (corners on a collapsed edge aside) turning the wrong way, or by less than `tiny` m².
fn folds(
    points: &[[f64; 2]],
    normals: &[[f64; 2]],
    thick: &[Vec<f64>],
    k: usize,
    k1: usize,
    tiny: f64,
) -> bool {
    let at = |c: usize, d: f64| {
        [
            points[c][0] + d * normals[c][0],
            points[c][1] + d * normals[c][1],
        ]
    };
    let (mut dk, mut dk1) = (0.0, 0.0);
    for (&tk, &tk1) in thick[k].iter().zip(&thick[k1]) {
        let (k_thin, k1_thin) = (tk < THINNEST, tk1 < THINNEST);
        if !(k_thin && k1_thin) {
            let p = [at(k, dk), at(k1, dk1), at(k1, dk1 + tk1), at(k, dk + tk)];
            for corner in 0..4 {
                let on_collapsed = match corner {
                    0 | 3 => k_thin,
                    _ => k1_thin,
                };
                if on_collapsed {
                    continue;
                }
                let (a, b, c) = (p[(corner + 3) % 4], p[corner], p[(corner + 1) % 4]);
                if cross(sub(c, b), sub(a, b)) <= tiny {
                    return true;
                }
            }
        }
        if !k_thin {
            dk += tk;
        }
        if !k1_thin {
            dk1 += tk1;
        }
    }
    false
}

/// The orientation angle in BeamDyn's section axes of a direction `t` in the chord frame.
fn orientation_in_section_axes(t: [f64; 2]) -> f64 {
    t[0].atan2(t[1])
}

fn check(layup: &Layup, meshing: Meshing) -> Result<()> {
    if !(meshing.element_length.is_finite() && meshing.element_length > 0.0) {
        return Err(invalid(format!(
            "expected an element length > 0, found {}",
            meshing.element_length
        )));
    }
    if meshing.rows_per_layer == 0 {
        return Err(invalid(
            "expected at least one element row per layer".into(),
        ));
    }
    let arc = |what: &str, s: f64| {
        if (0.0..=1.0).contains(&s) {
            Ok(())
        } else {
            Err(invalid(format!(
                "{what}: expected an arc position in [0, 1], found {s}"
            )))
        }
    };
    arc("leading edge", layup.leading_edge)?;
    let material = |what: &str, m: usize, t: f64, angle: f64| {
        if m >= layup.materials.len() {
            return Err(invalid(format!(
                "{what}: material {m}, but the layup has {}",
                layup.materials.len()
            )));
        }
        if !(t.is_finite() && t >= 0.0 && angle.is_finite()) {
            return Err(invalid(format!(
                "{what}: expected a thickness ≥ 0 and a finite fibre angle, found {t} and {angle}"
            )));
        }
        Ok(())
    };
    for (i, l) in layup.shell.iter().enumerate() {
        let what = format!("shell layer {i}");
        material(&what, l.material, l.thickness, l.fibre_angle)?;
        arc(&what, l.start)?;
        arc(&what, l.end)?;
    }
    for (i, w) in layup.webs.iter().enumerate() {
        let what = format!("web {i}");
        arc(&what, w.start)?;
        arc(&what, w.end)?;
        if !(w.start < layup.leading_edge && w.end > layup.leading_edge) {
            return Err(invalid(format!(
                "{what}: expected its start on the suction side and its end on the pressure \
                 side (arcs either side of the leading edge {}), found {} and {}",
                layup.leading_edge, w.start, w.end
            )));
        }
        for (j, l) in w.layers.iter().enumerate() {
            material(
                &format!("{what} layer {j}"),
                l.material,
                l.thickness,
                l.fibre_angle,
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square_layup() -> Layup {
        Layup {
            contour: vec![
                [0.5, 0.0],
                [0.5, 0.5],
                [-0.5, 0.5],
                [-0.5, -0.5],
                [0.5, -0.5],
                [0.5, 0.0],
            ],
            leading_edge: 0.5,
            shell: vec![ShellLayer {
                material: 0,
                thickness: 0.01,
                fibre_angle: 0.0,
                start: 0.0,
                end: 1.0,
                fill_to: None,
            }],
            webs: vec![WebLayup {
                start: 0.3,
                end: 0.7,
                layers: vec![WebLayer {
                    material: 0,
                    thickness: 0.02,
                    fibre_angle: 0.0,
                }],
            }],
            materials: vec![Orthotropic::isotropic(70e9, 0.3, 2700.0)],
        }
    }

    const MESHING: Meshing = Meshing {
        element_length: 0.05,
        rows_per_layer: 1,
    };

    /// A web across the square's middle: the shell's and the web's areas, the mesh conforming.
    #[test]
    fn a_square_with_a_web_keeps_every_layers_area() {
        let m = mesh_layup(&square_layup(), MESHING).unwrap();
        m.mesh.validate().unwrap();
        let area: f64 = m
            .mesh
            .elements
            .iter()
            .map(|e| {
                let c = m.mesh.corners(e);
                (0..4).map(|i| cross(c[i], c[(i + 1) % 4])).sum::<f64>() / 2.0
            })
            .sum();
        let shell = 1.0 - 0.98 * 0.98;
        let web = 0.02 * 0.98;
        assert!(
            (area - shell - web).abs() < 1e-12,
            "{area} against {}",
            shell + web
        );
        assert_eq!(m.clipped_mass, 0.0);
    }

    /// A fill takes the depth the skin leaves to the middle of the section and no more; the
    /// skin keeps its thickness and nothing counts as cut.
    #[test]
    fn a_fill_takes_the_room_the_other_layers_leave() {
        let area_of = |m: &LayupMesh, which: usize| -> f64 {
            m.mesh
                .elements
                .iter()
                .zip(&m.layers)
                .filter(|(_, l)| **l == LayerOf::Shell(which))
                .map(|(e, _)| {
                    let c = m.mesh.corners(e);
                    (0..4).map(|i| cross(c[i], c[(i + 1) % 4])).sum::<f64>() / 2.0
                })
                .sum()
        };
        let plain = mesh_layup(&square_layup(), MESHING).unwrap();
        let mut filled = square_layup();
        // Across the right-hand wall from y = −0.2 to 0.2 (the contour starts at its middle).
        filled.shell.push(ShellLayer {
            material: 0,
            thickness: 0.0,
            fibre_angle: 0.0,
            start: 0.95,
            end: 0.05,
            fill_to: Some(-1.0),
        });
        let m = mesh_layup(&filled, MESHING).unwrap();
        m.mesh.validate().unwrap();
        assert_eq!(m.clipped_mass, 0.0);
        assert!((area_of(&m, 0) - area_of(&plain, 0)).abs() < 1e-12);
        // Half the width less the skin, over the 0.4 m it covers and the triangles at its ends.
        let depth = 0.5 - 0.01;
        let fill = area_of(&m, 1);
        assert!(
            fill > 0.4 * depth && fill < (0.4 + 2.0 * MESHING.element_length) * depth,
            "{fill}"
        );
        // Up to a line across the chord 0.2 m in from the wall, it stops there.
        filled.shell[1].fill_to = Some(0.3);
        let m = mesh_layup(&filled, MESHING).unwrap();
        m.mesh.validate().unwrap();
        let depth = 0.2 - 0.01;
        let fill = area_of(&m, 1);
        assert!(
            fill > 0.4 * depth && fill < (0.4 + 2.0 * MESHING.element_length) * depth,
            "{fill}"
        );
    }

    /// Bad layups are errors that say what is wrong, never a panic or a broken mesh.
    #[test]
    fn bad_layups_are_errors() {
        let expect = |l: Layup, meshing: Meshing, says: &str| {
            let e = mesh_layup(&l, meshing).unwrap_err().to_string();
            assert!(e.contains(says), "{e}");
        };
        let mut open = square_layup();
        open.contour.pop();
        expect(open, MESHING, "closed contour");
        let mut clockwise = square_layup();
        clockwise.contour.reverse();
        expect(clockwise, MESHING, "counterclockwise");
        let mut thick = square_layup();
        thick.shell[0].thickness = f64::NAN;
        expect(thick, MESHING, "thickness ≥ 0");
        let mut arc = square_layup();
        arc.shell[0].end = 1.5;
        expect(arc, MESHING, "arc position in [0, 1]");
        let mut material = square_layup();
        material.webs[0].layers[0].material = 3;
        expect(material, MESHING, "material 3");
        let mut web = square_layup();
        web.webs[0].start = 0.6;
        expect(web, MESHING, "suction side");
        let coarse = Meshing {
            element_length: 0.0,
            rows_per_layer: 1,
        };
        expect(square_layup(), coarse, "element length > 0");
    }
}
