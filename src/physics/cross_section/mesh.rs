//! The section mesh (docs/model.md §11.11): nodes in the section plane, 4-node bilinear
//! quadrilaterals, each with its material, fibre angle and layer orientation.
//!
//! Coordinates `(x, y)` are in the section plane, `z` along the beam, `x × y = z`. Element nodes
//! run counterclockwise in `(x, y)`; an element whose mapping folds or collapses anywhere (a
//! non-positive Jacobian at a corner) is an error, not silently reordered, because a clockwise
//! element usually means the mesh generator got the geometry wrong.

use super::material::Orthotropic;
use crate::error::{Error, Result};

/// How the material lies in one element: which material, the fibre angle and the direction of
/// the layer in the section plane (both rad; see [`super::material`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ply {
    pub material: usize,
    pub fibre_angle: f64,
    pub orientation: f64,
}

/// A 4-node quadrilateral: node indices counterclockwise and its ply.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    pub nodes: [usize; 4],
    pub ply: Ply,
}

/// A section mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Node coordinates `[x, y]` (m).
    pub nodes: Vec<[f64; 2]>,
    pub elements: Vec<Element>,
    pub materials: Vec<Orthotropic>,
}

fn invalid(message: String) -> Error {
    Error::Invalid {
        origin: "cross-section mesh".into(),
        message,
    }
}

/// The Jacobian determinant of a bilinear quadrilateral at its corner `k`: the cross product of
/// the two edges leaving it (positive when the corners run counterclockwise).
fn corner_jacobian(p: &[[f64; 2]; 4], k: usize) -> f64 {
    let (a, b, c) = (p[(k + 3) % 4], p[k], p[(k + 1) % 4]);
    let (u, v) = ([c[0] - b[0], c[1] - b[1]], [a[0] - b[0], a[1] - b[1]]);
    u[0] * v[1] - u[1] * v[0]
}

impl Mesh {
    /// The corner coordinates of element `e`.
    pub fn corners(&self, e: &Element) -> [[f64; 2]; 4] {
        e.nodes.map(|n| self.nodes[n])
    }

    /// Checks what the solver relies on: finite coordinates, elements that reference existing
    /// nodes and materials, finite angles, and every element convex and counterclockwise (the
    /// bilinear map's Jacobian is bilinear, so positive corners make it positive throughout).
    pub fn validate(&self) -> Result<()> {
        if self.elements.is_empty() {
            return Err(invalid("the mesh has no elements".into()));
        }
        if let Some((k, p)) = self
            .nodes
            .iter()
            .enumerate()
            .find(|(_, p)| !(p[0].is_finite() && p[1].is_finite()))
        {
            return Err(invalid(format!("node {k} at {p:?} is not finite")));
        }
        for (k, m) in self.materials.iter().enumerate() {
            m.stiffness()
                .map_err(|e| invalid(format!("material {k}: {e}")))?;
        }
        let scale = self.size();
        for (k, e) in self.elements.iter().enumerate() {
            if let Some(n) = e.nodes.iter().find(|n| **n >= self.nodes.len()) {
                return Err(invalid(format!(
                    "element {k} names node {n}, but the mesh has {} nodes",
                    self.nodes.len()
                )));
            }
            if e.ply.material >= self.materials.len() {
                return Err(invalid(format!(
                    "element {k} names material {}, but the mesh has {}",
                    e.ply.material,
                    self.materials.len()
                )));
            }
            if !(e.ply.fibre_angle.is_finite() && e.ply.orientation.is_finite()) {
                return Err(invalid(format!(
                    "element {k}: fibre angle {} and orientation {} must be finite",
                    e.ply.fibre_angle, e.ply.orientation
                )));
            }
            let p = self.corners(e);
            // A quadrilateral with one edge collapsed (two neighbouring corners the same node)
            // is a triangle: the bilinear map stays positive inside, zero only at that edge.
            let collapsed: Vec<usize> = (0..4)
                .filter(|&c| e.nodes[c] == e.nodes[(c + 1) % 4])
                .collect();
            if collapsed.len() > 1 {
                return Err(invalid(format!(
                    "element {k} (nodes {:?}) has more than one collapsed edge",
                    e.nodes
                )));
            }
            for c in 0..4 {
                if collapsed.iter().any(|&d| c == d || c == (d + 1) % 4) {
                    continue;
                }
                let j = corner_jacobian(&p, c);
                if j.is_nan() || j <= 1e-14 * scale * scale {
                    return Err(invalid(format!(
                        "element {k} (nodes {:?}) is degenerate, folded or clockwise at its corner {c} \
                         (edge cross product {j:e} m²)",
                        e.nodes
                    )));
                }
            }
        }
        self.check_connected()
    }

    /// Every node in an element and every element joined to the others through shared nodes: a
    /// node in no element, or a piece on its own, has rigid motions nothing holds, and the warping
    /// equations would be singular.
    fn check_connected(&self) -> Result<()> {
        let mut parent: Vec<usize> = (0..self.nodes.len()).collect();
        fn root(parent: &mut [usize], mut k: usize) -> usize {
            while parent[k] != k {
                parent[k] = parent[parent[k]];
                k = parent[k];
            }
            k
        }
        let mut used = vec![false; self.nodes.len()];
        for e in &self.elements {
            let first = root(&mut parent, e.nodes[0]);
            for &n in &e.nodes {
                used[n] = true;
                let r = root(&mut parent, n);
                parent[r] = first;
            }
        }
        if let Some(k) = used.iter().position(|u| !u) {
            return Err(invalid(format!("node {k} belongs to no element")));
        }
        let base = root(&mut parent, 0);
        if let Some(k) = (0..self.nodes.len()).find(|&k| root(&mut parent, k) != base) {
            return Err(invalid(format!(
                "the mesh is in more than one piece (node {k} is not joined to node 0)"
            )));
        }
        Ok(())
    }

    /// The largest extent of the nodes (m), for relative tolerances.
    pub fn size(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &self.nodes {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (hi[0] - lo[0]).max(hi[1] - lo[1])
    }

    /// A mesh on the rectilinear grid `xs × ys` (both increasing): the cell between
    /// `xs[i], xs[i+1]` and `ys[j], ys[j+1]` becomes an element with the ply `ply(centre)` returns,
    /// or is left out where it returns `None`. Nodes no element uses are dropped. Rectangles,
    /// boxes, channels and other rectilinear sections are grids with cells left out.
    pub fn grid(
        xs: &[f64],
        ys: &[f64],
        materials: Vec<Orthotropic>,
        ply: impl Fn([f64; 2]) -> Option<Ply>,
    ) -> Result<Mesh> {
        let increasing = |v: &[f64]| v.len() >= 2 && v.windows(2).all(|w| w[1] > w[0]);
        if !(increasing(xs) && increasing(ys)) {
            return Err(invalid(
                "grid lines must be at least two per direction and strictly increasing".into(),
            ));
        }
        let (nx, ny) = (xs.len(), ys.len());
        let mut index = vec![usize::MAX; nx * ny];
        let mut nodes = Vec::new();
        let mut elements = Vec::new();
        let mut node = |i: usize, j: usize, nodes: &mut Vec<[f64; 2]>| {
            let slot = &mut index[j * nx + i];
            if *slot == usize::MAX {
                *slot = nodes.len();
                nodes.push([xs[i], ys[j]]);
            }
            *slot
        };
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let centre = [0.5 * (xs[i] + xs[i + 1]), 0.5 * (ys[j] + ys[j + 1])];
                if let Some(p) = ply(centre) {
                    let n = [
                        node(i, j, &mut nodes),
                        node(i + 1, j, &mut nodes),
                        node(i + 1, j + 1, &mut nodes),
                        node(i, j + 1, &mut nodes),
                    ];
                    elements.push(Element { nodes: n, ply: p });
                }
            }
        }
        let mesh = Mesh {
            nodes,
            elements,
            materials,
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// A ring between radii `inner` and `outer` about `centre`: `around` elements round it and
    /// `through` across the wall, the layer running counterclockwise round the ring (orientation
    /// along the tangent), all of `material` at `fibre_angle` (rad). The boundaries are regular
    /// polygons through the nodes.
    pub fn ring(
        centre: [f64; 2],
        inner: f64,
        outer: f64,
        around: usize,
        through: usize,
        material: Orthotropic,
        fibre_angle: f64,
    ) -> Result<Mesh> {
        if !(inner.is_finite() && outer.is_finite() && inner > 0.0 && outer > inner) {
            return Err(invalid(format!(
                "a ring needs 0 < inner radius < outer radius, got {inner} and {outer}"
            )));
        }
        if around < 3 || through < 1 {
            return Err(invalid(format!(
                "a ring needs at least 3 elements round it and 1 through its wall, got {around} and {through}"
            )));
        }
        let step = 2.0 * std::f64::consts::PI / around as f64;
        let mut nodes = Vec::with_capacity(around * (through + 1));
        for k in 0..around {
            let (s, c) = (k as f64 * step).sin_cos();
            for j in 0..=through {
                let r = inner + (outer - inner) * j as f64 / through as f64;
                nodes.push([centre[0] + r * c, centre[1] + r * s]);
            }
        }
        let at = |k: usize, j: usize| (k % around) * (through + 1) + j;
        let mut elements = Vec::with_capacity(around * through);
        for k in 0..around {
            // The tangent at the element's middle angle.
            let orientation = (k as f64 + 0.5) * step + std::f64::consts::FRAC_PI_2;
            for j in 0..through {
                elements.push(Element {
                    nodes: [at(k, j), at(k, j + 1), at(k + 1, j + 1), at(k + 1, j)],
                    ply: Ply {
                        material: 0,
                        fibre_angle,
                        orientation,
                    },
                });
            }
        }
        let mesh = Mesh {
            nodes,
            elements,
            materials: vec![material],
        };
        mesh.validate()?;
        Ok(mesh)
    }
}

/// `n` equal intervals from `a` to `b`: `n + 1` grid lines.
pub fn spaced(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect()
}

/// Grid lines through each of `breaks` (increasing), with `per[k]` equal intervals between
/// `breaks[k]` and `breaks[k + 1]`: a grid that follows walls of different thicknesses.
pub fn graded(breaks: &[f64], per: &[usize]) -> Vec<f64> {
    let mut out = vec![breaks[0]];
    for (w, n) in breaks.windows(2).zip(per) {
        out.extend(spaced(w[0], w[1], (*n).max(1)).into_iter().skip(1));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Orthotropic {
        Orthotropic::isotropic(200e9, 0.3, 7850.0)
    }

    fn solid() -> Option<Ply> {
        Some(Ply {
            material: 0,
            fibre_angle: 0.0,
            orientation: 0.0,
        })
    }

    #[test]
    fn a_grid_with_a_hole_keeps_only_the_walls() {
        let xs = graded(&[0.0, 1.0, 3.0, 4.0], &[1, 2, 1]);
        let ys = graded(&[0.0, 1.0, 2.0], &[1, 1]);
        let m = Mesh::grid(&xs, &ys, vec![steel()], |c| {
            if c[0] > 1.0 && c[0] < 3.0 && c[1] > 1.0 {
                None
            } else {
                solid()
            }
        })
        .unwrap();
        assert_eq!(m.elements.len(), 6);
        // The one node only the notch's cells touch (its top middle) is dropped.
        assert_eq!(m.nodes.len(), 14);
    }

    #[test]
    fn a_ring_has_its_elements_counterclockwise() {
        let m = Mesh::ring([0.1, -0.2], 0.9, 1.0, 24, 2, steel(), 0.0).unwrap();
        assert_eq!(m.elements.len(), 48);
        assert_eq!(m.nodes.len(), 72);
    }

    #[test]
    fn bad_meshes_are_errors() {
        let good = Mesh::ring([0.0, 0.0], 0.5, 1.0, 8, 1, steel(), 0.0).unwrap();
        let mut m = good.clone();
        m.elements[3].nodes.reverse();
        assert!(m.validate().is_err(), "clockwise element accepted");
        let mut m = good.clone();
        let n = m.elements[0].nodes;
        m.elements[0].nodes = [n[0], n[1], n[1], n[0]];
        assert!(
            m.validate().is_err(),
            "element collapsed to a line accepted"
        );
        let mut m = good.clone();
        m.elements[0].nodes = [n[0], n[0], n[2], n[3]];
        assert!(
            m.validate().is_ok(),
            "a triangle (one collapsed edge) refused"
        );
        m.elements[0].nodes = [n[0], n[0], n[3], n[2]];
        assert!(m.validate().is_err(), "a clockwise triangle accepted");
        let mut m = good.clone();
        m.nodes[2][0] = f64::NAN;
        assert!(m.validate().is_err(), "NaN node accepted");
        let mut m = good.clone();
        m.elements[1].ply.material = 4;
        assert!(m.validate().is_err(), "missing material accepted");
        let mut m = good.clone();
        m.materials[0].e1 = 0.0;
        assert!(m.validate().is_err(), "zero stiffness accepted");
        let mut m = good;
        m.elements[0].ply.fibre_angle = f64::INFINITY;
        assert!(m.validate().is_err(), "infinite angle accepted");
        assert!(Mesh::ring([0.0, 0.0], 1.0, 0.5, 8, 1, steel(), 0.0).is_err());
        // Two squares that do not touch, and a node no element uses.
        let apart = Mesh::grid(&[0.0, 1.0, 2.0, 3.0], &[0.0, 1.0], vec![steel()], |c| {
            if c[0] > 1.0 && c[0] < 2.0 {
                None
            } else {
                solid()
            }
        });
        assert!(apart.is_err(), "a mesh in two pieces accepted");
        let mut m = Mesh::ring([0.0, 0.0], 0.5, 1.0, 8, 1, steel(), 0.0).unwrap();
        m.nodes.push([3.0, 3.0]);
        assert!(m.validate().is_err(), "a loose node accepted");
        assert!(Mesh::grid(&[0.0, 0.0], &[0.0, 1.0], vec![steel()], |_| solid()).is_err());
    }
}
