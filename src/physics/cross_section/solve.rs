//! The section's 6×6 stiffness and mass from its mesh (docs/model.md §11.11): Giavotto's
//! anisotropic beam theory discretised as in BECAS, solved for the warping.
//!
//! A point of the section at `(x, y)` moves by the section's rigid motion plus the warping:
//! `u = Z(x, y) r(z) + N(x, y) w(z)`, `r = (u_x, u_y, u_z, θ_x, θ_y, θ_z)` with right-hand
//! rotations, `N` the elements' bilinear shape functions and `w` the nodal warping. The strains
//! are `ε = S_z Z ψ + B w + S w'`, with the section's strains `ψ = (γ_x, γ_y, ε, κ_x, κ_y, κ_z)`,
//! `B` the in-plane derivatives and `S` the `∂/∂z` part. Far from the beam's ends (the "central
//! solution") the forces `T = (F_x, F_y, F_z, M_x, M_y, M_z)` vary only as equilibrium demands,
//! `T' = Aᵀ T`, and the warping and section strains are linear in them, `w = X T`, `ψ = Y T`; the
//! warping equations and the definition `T = ∂U/∂ψ` give
//!
//! ```text
//!   E X + R Y = −(C − Cᵀ) X Aᵀ + M Y Aᵀ,      Rᵀ X + 𝒜 Y = I − Mᵀ X Aᵀ,
//! ```
//!
//! with `E = ∫BᵀQB`, `C = ∫BᵀQS`, `R = ∫BᵀQ S_zZ`, `M = ∫SᵀQ S_zZ`, `𝒜 = ∫(S_zZ)ᵀQ S_zZ`. `Aᵀ`
//! only carries the shear forces into the moments' slopes (`M_x' = F_y`, `M_y' = −F_x`), so the
//! columns for `F_z, M_x, M_y, M_z` have a plain right-hand side and the two shear columns take
//! theirs from the bending columns. The compliance is the strain energy of that solution,
//! `½ Tᵀ F T = ½ ∫εᵀQε dA`; the stiffness is `F⁻¹`.
//!
//! The warping is defined up to the six rigid motions (they move the section, and `r` already
//! does). Rather than constraining them with Lagrange multipliers, six warping components at three
//! nodes are held at zero: the system stays symmetric positive definite (one sparse Cholesky) and,
//! since the strain field and so the energy does not depend on how the rigid motion is split
//! between `r` and `w`, the compliance does not either (tested against another choice of nodes).

use super::material::section_stiffness;
use super::mesh::Mesh;
use crate::error::{Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, Mat, Par, Side};
use nalgebra::{Matrix6, SMatrix, Vector6};
use std::sync::Arc;

/// The section's matrices about `reference` (m, `[x, y]` in the mesh's plane), BeamDyn's
/// order: strains `(γ_x, γ_y, ε, κ_x, κ_y, κ_z)` (shear along x, along y, extension, bending
/// about x, about y, twist; `κ` the rates of the right-hand rotations about the axes) against
/// `(F_x, F_y, F_z, M_x, M_y, M_z)`, z along the beam and `x × y = z`.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamMatrices {
    /// Stiffness (N, N·m, N·m²).
    pub stiffness: [[f64; 6]; 6],
    /// Mass per length `∫ρ ZᵀZ dA`: `[[m I, −m c̃], [m c̃, J]]` (kg/m, kg, kg·m).
    pub mass: [[f64; 6]; 6],
    /// The point the matrices are about (m).
    pub reference: [f64; 2],
}

type Vec12 = SMatrix<f64, 12, 1>;

const GAUSS: f64 = 0.577_350_269_189_625_8;
const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// One Gauss point: shape functions, their x and y derivatives, position from the reference
/// and weight times the Jacobian determinant.
#[derive(Clone, Copy)]
struct Point {
    n: [f64; 4],
    dx: [f64; 4],
    dy: [f64; 4],
    x: f64,
    y: f64,
    w: f64,
}

/// An element's Gauss points, its material stiffness in section axes, density and nodes.
struct Quad {
    points: [Point; 4],
    q: Matrix6<f64>,
    rho: f64,
    nodes: [usize; 4],
}

/// The two nonzero rows of `B`'s column for warping component `c` (x, y, z) of a node with
/// derivatives `(dx, dy)`, Voigt (xx, yy, zz, yz, xz, xy): `B` is sparse, and the element
/// matrices are built from these pairs rather than from dense products.
#[inline]
fn b_rows(c: usize, dx: f64, dy: f64) -> [(usize, f64); 2] {
    match c {
        0 => [(0, dx), (5, dy)],
        1 => [(1, dy), (5, dx)],
        _ => [(3, dy), (4, dx)],
    }
}

impl Point {
    /// `B X`: the in-plane derivatives' strains of an element's warping, `x[i][j]` component
    /// `i` of column `j`, by rows (`[r][j]`, strain `r` of column `j`).
    #[inline]
    fn b<const N: usize>(&self, x: &[[f64; N]; 12]) -> [[f64; N]; 6] {
        let mut e = [[0.0; N]; 6];
        for a in 0..4 {
            let (dx, dy) = (self.dx[a], self.dy[a]);
            let (u, w, z) = (&x[3 * a], &x[3 * a + 1], &x[3 * a + 2]);
            for j in 0..N {
                e[0][j] += dx * u[j];
                e[1][j] += dy * w[j];
                e[3][j] += dy * z[j];
                e[4][j] += dx * z[j];
                e[5][j] += dy * u[j] + dx * w[j];
            }
        }
        e
    }

    /// `S X`: the strains of the warping's slope along the beam, by rows as [`Self::b`].
    #[inline]
    fn s<const N: usize>(&self, x: &[[f64; N]; 12]) -> [[f64; N]; 6] {
        let mut e = [[0.0; N]; 6];
        for a in 0..4 {
            let n = self.n[a];
            for j in 0..N {
                e[2][j] += n * x[3 * a + 2][j];
                e[3][j] += n * x[3 * a + 1][j];
                e[4][j] += n * x[3 * a][j];
            }
        }
        e
    }

    /// `(S_z Z) ψ`: the strains of the section's strains `ψ` at this point.
    #[inline]
    fn z(&self, psi: &Vector6<f64>) -> Vector6<f64> {
        Vector6::new(
            0.0,
            0.0,
            psi[2] + self.y * psi[3] - self.x * psi[4],
            psi[1] + self.x * psi[5],
            psi[0] - self.y * psi[5],
            0.0,
        )
    }

    /// `Bᵀ σ`.
    #[inline]
    fn bt(&self, s: &Vector6<f64>) -> Vec12 {
        let mut f = Vec12::zeros();
        for a in 0..4 {
            let (dx, dy) = (self.dx[a], self.dy[a]);
            f[3 * a] = dx * s[0] + dy * s[5];
            f[3 * a + 1] = dy * s[1] + dx * s[5];
            f[3 * a + 2] = dy * s[3] + dx * s[4];
        }
        f
    }

    /// `Sᵀ σ`.
    #[inline]
    fn st(&self, s: &Vector6<f64>) -> Vec12 {
        let mut f = Vec12::zeros();
        for a in 0..4 {
            let n = self.n[a];
            f[3 * a] = n * s[4];
            f[3 * a + 1] = n * s[3];
            f[3 * a + 2] = n * s[2];
        }
        f
    }

    /// `(S_z Z)ᵀ σ`.
    #[inline]
    fn zt(&self, s: &Vector6<f64>) -> Vector6<f64> {
        Vector6::new(
            s[4],
            s[3],
            s[2],
            self.y * s[2],
            -self.x * s[2],
            self.x * s[3] - self.y * s[4],
        )
    }
}

fn quads(mesh: &Mesh, reference: [f64; 2]) -> Result<Vec<Quad>> {
    let stiffness = mesh
        .materials
        .iter()
        .map(|m| m.stiffness())
        .collect::<Result<Vec<_>>>()?;
    mesh.elements
        .iter()
        .enumerate()
        .map(|(k, e)| {
            let p = mesh.corners(e);
            let mut points = [Point {
                n: [0.0; 4],
                dx: [0.0; 4],
                dy: [0.0; 4],
                x: 0.0,
                y: 0.0,
                w: 0.0,
            }; 4];
            for (g, point) in points.iter_mut().enumerate() {
                let (xi, eta) = (CORNERS[g][0] * GAUSS, CORNERS[g][1] * GAUSS);
                let mut n = [0.0; 4];
                let (mut dxi, mut deta) = ([0.0; 4], [0.0; 4]);
                for a in 0..4 {
                    let (xa, ea) = (CORNERS[a][0], CORNERS[a][1]);
                    n[a] = 0.25 * (1.0 + xa * xi) * (1.0 + ea * eta);
                    dxi[a] = 0.25 * xa * (1.0 + ea * eta);
                    deta[a] = 0.25 * ea * (1.0 + xa * xi);
                }
                let mut j = [[0.0; 2]; 2];
                let (mut x, mut y) = (0.0, 0.0);
                for a in 0..4 {
                    j[0][0] += dxi[a] * p[a][0];
                    j[0][1] += dxi[a] * p[a][1];
                    j[1][0] += deta[a] * p[a][0];
                    j[1][1] += deta[a] * p[a][1];
                    x += n[a] * p[a][0];
                    y += n[a] * p[a][1];
                }
                let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                if !(det > 0.0 && det.is_finite()) {
                    return Err(Error::Invalid {
                        origin: "cross-section mesh".into(),
                        message: format!("element {k} has Jacobian {det} at a Gauss point"),
                    });
                }
                let mut dx = [0.0; 4];
                let mut dy = [0.0; 4];
                for a in 0..4 {
                    dx[a] = (j[1][1] * dxi[a] - j[0][1] * deta[a]) / det;
                    dy[a] = (-j[1][0] * dxi[a] + j[0][0] * deta[a]) / det;
                }
                *point = Point {
                    n,
                    dx,
                    dy,
                    x: x - reference[0],
                    y: y - reference[1],
                    w: det,
                };
            }
            let material = e.ply.material;
            Ok(Quad {
                points,
                q: section_stiffness(&stiffness[material], e.ply.fibre_angle, e.ply.orientation),
                rho: mesh.materials[material].rho,
                nodes: e.nodes,
            })
        })
        .collect()
}

/// The free components' rows of a nodal field given row by row, as columns (held ones left out).
fn free_columns<const N: usize>(rows: &[[f64; N]], free: &[usize], nfree: usize) -> Mat<f64> {
    let mut m = Mat::<f64>::zeros(nfree, N);
    for (row, &f) in rows.iter().zip(free) {
        if f != usize::MAX {
            for (c, v) in row.iter().enumerate() {
                m[(f, c)] = *v;
            }
        }
    }
    m
}

/// The sparsity of the warping matrix `E` on the free components (lower triangle, by columns):
/// built from which nodes share an element, so the matrix is assembled in place rather than
/// from sorted triplets.
#[derive(Debug)]
struct Pattern {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Each warping component's free index (`usize::MAX` where held).
    free: Vec<usize>,
}

impl Pattern {
    fn new(near: &[Vec<usize>], pinned: &[usize; 6]) -> Pattern {
        let nodes = near.len();
        let mut free = vec![0usize; 3 * nodes];
        let mut nfree = 0;
        for (k, f) in free.iter_mut().enumerate() {
            if pinned.contains(&k) {
                *f = usize::MAX;
            } else {
                *f = nfree;
                nfree += 1;
            }
        }
        // Column f (a free component of node a) holds the free components of a's neighbours
        // at or below it; free indices grow with the component index, so they come sorted.
        let mut col_ptr = Vec::with_capacity(nfree + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for (g, &f) in free.iter().enumerate() {
            if f == usize::MAX {
                continue;
            }
            for &b in &near[g / 3] {
                for c in 0..3 {
                    let r = free[3 * b + c];
                    if r != usize::MAX && r >= f {
                        row_idx.push(r);
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
        Pattern {
            col_ptr,
            row_idx,
            free,
        }
    }

    fn len(&self) -> usize {
        self.col_ptr.len() - 1
    }

    fn structure(&self) -> SymbolicSparseColMatRef<'_, usize> {
        let n = self.len();
        SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx)
    }

    /// Where an element's entries go: `slots[i * 12 + j]` is the value index of the entry that
    /// its components `i` and `j` make, when `i`'s free index is at or below `j`'s in the
    /// matrix (else, or for a held component, `usize::MAX`). In a column a node's rows are
    /// contiguous, so one search finds each node's block.
    fn slots(&self, nodes: &[usize; 4]) -> [usize; 144] {
        let mut s = [usize::MAX; 144];
        for j in 0..12 {
            let f = self.free[3 * nodes[j / 3] + j % 3];
            if f == usize::MAX {
                continue;
            }
            let start = self.col_ptr[f];
            let rows = &self.row_idx[start..self.col_ptr[f + 1]];
            for (ai, &a) in nodes.iter().enumerate() {
                // The node's first row found by search, the next ones following it.
                let mut at = None;
                for c in 0..3 {
                    let r = self.free[3 * a + c];
                    if r == usize::MAX || r < f {
                        continue;
                    }
                    let here = at.unwrap_or_else(|| start + rows.partition_point(|&row| row < r));
                    s[(3 * ai + c) * 12 + j] = here;
                    at = Some(here + 1);
                }
            }
        }
        s
    }
}

/// Each node's neighbours (itself included), sorted: the nodes it shares an element with.
fn node_graph(elements: &[[usize; 4]], nodes: usize) -> Vec<Vec<usize>> {
    let mut near: Vec<Vec<usize>> = vec![Vec::with_capacity(9); nodes];
    for e in elements {
        for &a in e {
            near[a].extend_from_slice(e);
        }
    }
    for list in &mut near {
        list.sort_unstable();
        list.dedup();
    }
    near
}

/// The fill-reducing order of the free warping components (forward and inverse): the
/// approximate minimum degree order of the nodes, each node's components kept together. A
/// node's three components couple to the same neighbours, so ordering the node graph gives
/// the order of the component graph at a third of its size (and keeps each node's components
/// in one supernode).
fn fill_reducing_order(near: &[Vec<usize>], pattern: &Pattern) -> Result<(Vec<usize>, Vec<usize>)> {
    let n = near.len();
    let mut col_ptr = Vec::with_capacity(n + 1);
    col_ptr.push(0);
    for list in near {
        col_ptr.push(col_ptr.last().unwrap_or(&0) + list.len());
    }
    let row_idx: Vec<usize> = near.iter().flatten().copied().collect();
    let graph = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
    let (mut order, mut inverse) = (vec![0usize; n], vec![0usize; n]);
    amd::order(
        &mut order,
        &mut inverse,
        graph,
        amd::Control::default(),
        MemStack::new(&mut MemBuffer::new(amd::order_scratch::<usize>(
            n,
            row_idx.len(),
        ))),
    )
    .map_err(|err| Error::numerical(format!("cross-section: no node order ({err:?})")))?;
    let forward: Vec<usize> = order
        .iter()
        .flat_map(|&a| (0..3).map(move |c| pattern.free[3 * a + c]))
        .filter(|&f| f != usize::MAX)
        .collect();
    let mut inverse = vec![0usize; forward.len()];
    for (k, &f) in forward.iter().enumerate() {
        inverse[f] = k;
    }
    Ok((forward, inverse))
}

/// Six warping components held at zero to take out the rigid motions: both in-plane components
/// at `first`, the one across the line to the node farthest from it, and the axial component at
/// those two and at the node farthest from their line (a plane through three points that are not
/// on a line is fixed by them).
fn pins(nodes: &[[f64; 2]], first: usize) -> Result<[usize; 6]> {
    let a = nodes[first];
    let dist2 = |p: &[f64; 2]| (p[0] - a[0]).powi(2) + (p[1] - a[1]).powi(2);
    let (b, far) = nodes
        .iter()
        .enumerate()
        .map(|(k, p)| (k, dist2(p)))
        .fold((first, 0.0), |m, c| if c.1 > m.1 { c } else { m });
    let d = [nodes[b][0] - a[0], nodes[b][1] - a[1]];
    let off_line = |p: &[f64; 2]| ((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]).abs();
    let (c, area) = nodes
        .iter()
        .enumerate()
        .map(|(k, p)| (k, off_line(p)))
        .fold((first, 0.0), |m, c| if c.1 > m.1 { c } else { m });
    if !(far > 0.0 && area > 1e-9 * far) {
        return Err(Error::Invalid {
            origin: "cross-section mesh".into(),
            message: "the nodes lie on a line: a section needs an area".into(),
        });
    }
    // Across the a–b line: the component of b's motion that a rotation about a would give.
    let across = if d[0].abs() >= d[1].abs() { 1 } else { 0 };
    Ok([
        3 * first,
        3 * first + 1,
        3 * b + across,
        3 * first + 2,
        3 * b + 2,
        3 * c + 2,
    ])
}

/// The symbolic part of a mesh's warping factorisation (its fill-reducing ordering and the
/// factor's pattern): it depends only on which nodes share an element, so a mesh of the same
/// nodes and elements with other plies (the fibres turned) reuses it ([`analyse_reusing`]).
#[derive(Debug, Clone)]
pub struct Factorisation {
    pattern: Arc<Pattern>,
    symbolic: Arc<SymbolicCholesky<usize>>,
    /// What it was made for: the node count, each element's nodes and the held warping
    /// components (which follow from the nodes' positions).
    nodes: usize,
    elements: Arc<Vec<[usize; 4]>>,
    pinned: [usize; 6],
}

impl PartialEq for Factorisation {
    fn eq(&self, other: &Factorisation) -> bool {
        self.nodes == other.nodes && self.elements == other.elements && self.pinned == other.pinned
    }
}

impl Factorisation {
    /// The pattern and symbolic factorisation of `mesh`'s warping matrix with `pinned` held.
    fn new(mesh: &Mesh, pinned: [usize; 6]) -> Result<Factorisation> {
        let elements: Vec<[usize; 4]> = mesh.elements.iter().map(|e| e.nodes).collect();
        let near = node_graph(&elements, mesh.nodes.len());
        let pattern = Pattern::new(&near, &pinned);
        let (forward, inverse) = fill_reducing_order(&near, &pattern)?;
        let n = pattern.len();
        let symbolic = factorize_symbolic_cholesky(
            pattern.structure(),
            Side::Lower,
            SymmetricOrdering::Custom(PermRef::new_checked(&forward, &inverse, n)),
            CholeskySymbolicParams {
                // Supernodal: on these meshes faster than the simplicial factor faer picks.
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|err| {
            Error::numerical(format!("cross-section: no factorisation pattern ({err:?})"))
        })?;
        Ok(Factorisation {
            pattern: Arc::new(pattern),
            symbolic: Arc::new(symbolic),
            nodes: mesh.nodes.len(),
            elements: Arc::new(elements),
            pinned,
        })
    }

    /// Whether it was made for `mesh`'s nodes and elements, with these warping components held.
    fn fits(&self, mesh: &Mesh, pinned: &[usize; 6]) -> bool {
        self.pinned == *pinned
            && self.nodes == mesh.nodes.len()
            && self.elements.len() == mesh.elements.len()
            && self
                .elements
                .iter()
                .zip(&mesh.elements)
                .all(|(a, b)| *a == b.nodes)
    }
}

/// The section's stiffness and mass matrices about `reference` (see [`BeamMatrices`]).
pub fn analyse(mesh: &Mesh, reference: [f64; 2]) -> Result<BeamMatrices> {
    analyse_pinned(mesh, reference, 0, None).map(|(m, _)| m)
}

/// [`analyse`], reusing `reuse` when it was made for this mesh's nodes and elements; with the
/// factorisation made, for the next mesh of the same topology.
pub fn analyse_reusing(
    mesh: &Mesh,
    reference: [f64; 2],
    reuse: Option<&Factorisation>,
) -> Result<(BeamMatrices, Factorisation)> {
    analyse_pinned(mesh, reference, 0, reuse)
}

/// [`analyse`] with the warping's rigid motions held at the nodes chosen from `first`.
pub(crate) fn analyse_pinned(
    mesh: &Mesh,
    reference: [f64; 2],
    first: usize,
    reuse: Option<&Factorisation>,
) -> Result<(BeamMatrices, Factorisation)> {
    mesh.validate()?;
    if !(reference[0].is_finite() && reference[1].is_finite()) {
        return Err(Error::Invalid {
            origin: "cross-section".into(),
            message: format!("the reference point {reference:?} is not finite"),
        });
    }
    let quads = quads(mesh, reference)?;
    let ndof = 3 * mesh.nodes.len();
    let pinned = pins(&mesh.nodes, first.min(mesh.nodes.len() - 1))?;
    let factorisation = match reuse.filter(|f| f.fits(mesh, &pinned)) {
        Some(f) => f.clone(),
        None => Factorisation::new(mesh, pinned)?,
    };
    let pattern = &*factorisation.pattern;
    let (free, nfree) = (&pattern.free, pattern.len());

    // E (sparse, free components, lower triangle), R (dense columns), 𝒜 and the mass, each
    // element's part summed over its Gauss points before it goes to its slots.
    let mut values = vec![0.0; pattern.row_idx.len()];
    let mut r = vec![[0.0; 6]; ndof];
    let mut a6 = Matrix6::zeros();
    let mut mass = Matrix6::zeros();
    for quad in &quads {
        let q = &quad.q;
        let mut ke = [[0.0; 12]; 12];
        let mut re = [[0.0; 6]; 12];
        for p in &quad.points {
            // Q B and Q S_zZ by rows, weighted: B's column for a node's component has two
            // nonzero rows, so each is a sum of two of Q's columns; by rows, the products with
            // Bᵀ below run along contiguous memory.
            let mut qb = [[0.0; 12]; 6];
            for a in 0..4 {
                let (dx, dy) = (p.dx[a] * p.w, p.dy[a] * p.w);
                for (r, row) in qb.iter_mut().enumerate() {
                    row[3 * a] = q[(r, 0)] * dx + q[(r, 5)] * dy;
                    row[3 * a + 1] = q[(r, 1)] * dy + q[(r, 5)] * dx;
                    row[3 * a + 2] = q[(r, 3)] * dy + q[(r, 4)] * dx;
                }
            }
            let (x, y) = (p.x, p.y);
            let qz: [[f64; 6]; 6] = std::array::from_fn(|r| {
                let (q2, q3, q4) = (q[(r, 2)] * p.w, q[(r, 3)] * p.w, q[(r, 4)] * p.w);
                [q4, q3, q2, q2 * y, -q2 * x, q3 * x - q4 * y]
            });
            for i in 0..12 {
                let [(r1, v1), (r2, v2)] = b_rows(i % 3, p.dx[i / 3], p.dy[i / 3]);
                for j in 0..12 {
                    ke[i][j] += v1 * qb[r1][j] + v2 * qb[r2][j];
                }
                for c in 0..6 {
                    re[i][c] += v1 * qz[r1][c] + v2 * qz[r2][c];
                }
            }
            for c in 0..6 {
                let col = p.zt(&Vector6::from_fn(|r, _| qz[r][c]));
                for k in 0..6 {
                    a6[(k, c)] += col[k];
                }
            }
            let m = quad.rho * p.w;
            mass[(0, 0)] += m;
            mass[(0, 5)] -= m * y;
            mass[(1, 5)] += m * x;
            mass[(2, 3)] += m * y;
            mass[(2, 4)] -= m * x;
            mass[(3, 3)] += m * y * y;
            mass[(4, 4)] += m * x * x;
            mass[(3, 4)] -= m * x * y;
            mass[(5, 5)] += m * (x * x + y * y);
        }
        let slots = pattern.slots(&quad.nodes);
        for i in 0..12 {
            for j in 0..=i {
                // The pair lands below the diagonal in one order; in both when the two are one
                // component (a triangle's repeated node).
                let (below, above) = (slots[i * 12 + j], slots[j * 12 + i]);
                if below != usize::MAX {
                    values[below] += ke[i][j];
                }
                if i != j && above != usize::MAX {
                    values[above] += ke[i][j];
                }
            }
            let g = 3 * quad.nodes[i / 3] + i % 3;
            for c in 0..6 {
                r[g][c] += re[i][c];
            }
        }
    }
    mass[(1, 1)] = mass[(0, 0)];
    mass[(2, 2)] = mass[(0, 0)];
    for i in 0..6 {
        for j in 0..i {
            mass[(i, j)] = mass[(j, i)];
        }
    }

    let e = SparseColMatRef::new(pattern.structure(), &values);
    let not_definite = |err: String| {
        Error::numerical(format!(
            "cross-section: the warping stiffness is not positive definite ({err}): a material \
             without stiffness, or elements not connected to the rest of the section"
        ))
    };
    let symbolic = &*factorisation.symbolic;
    let mut factor = vec![0.0; symbolic.len_val()];
    let par = Par::Seq;
    let llt = symbolic
        .factorize_numeric_llt(
            &mut factor,
            e,
            Side::Lower,
            Default::default(),
            par,
            MemStack::new(&mut MemBuffer::new(
                symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
            )),
            Default::default(),
        )
        .map_err(|err| not_definite(format!("{err:?}")))?;
    // Solves E w = f in place on the free components' columns.
    let solve = |rhs: &mut Mat<f64>| {
        let k = rhs.ncols();
        llt.solve_in_place_with_conj(
            Conj::No,
            rhs.as_mut(),
            par,
            MemStack::new(&mut MemBuffer::new(
                llt.solve_in_place_scratch::<f64>(k, par),
            )),
        );
    };
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
    let rf = free_columns(&r, free, nfree);
    let mut xr = rf.clone();
    solve(&mut xr);
    let rt = |m: &Mat<f64>, c: usize| {
        Vector6::from_fn(|i, _| dot(rf.col_as_slice(i), m.col_as_slice(c)))
    };
    let mut schur = a6;
    for j in 0..6 {
        schur.set_column(j, &(schur.column(j) - rt(&xr, j)));
    }
    let schur = ((schur + schur.transpose()) * 0.5).cholesky().ok_or_else(|| {
        Error::numerical("cross-section: the section has no positive stiffness (is a material's stiffness zero?)")
    })?;
    // The warping by rows, `x[k][j]` for component k and unit force j, and the section strains
    // `ys[j]`: X = x_f − Xr Y with Y = S⁻¹(g − Rᵀ x_f), x_f the column of `xf` (zero if none).
    let mut x = vec![[0.0; 6]; ndof];
    let mut ys = [Vector6::zeros(); 6];
    let column = |x: &mut [[f64; 6]], j: usize, xf: Option<(&Mat<f64>, usize)>, g: Vector6<f64>| {
        let y = schur.solve(&(g - xf.map_or(Vector6::zeros(), |(m, c)| rt(m, c))));
        for (k, &f) in free.iter().enumerate() {
            if f != usize::MAX {
                let mut v = xf.map_or(0.0, |(m, c)| m[(f, c)]);
                for c in 0..6 {
                    v -= xr[(f, c)] * y[c];
                }
                x[k][j] = v;
            }
        }
        y
    };
    for (j, y) in ys.iter_mut().enumerate().skip(2) {
        *y = column(&mut x, j, None, Vector6::ith(j, 1.0));
    }
    // The shear columns: their warping's slope is the bending columns' (w' = X Aᵀ T):
    // X'₁ = −X₅, X'₂ = X₄ (0-based 4 and 3).
    let slope = |v: &[f64; 6]| [-v[4], v[3]];
    let y_slope = [-ys[4], ys[3]];
    // f = −(C − Cᵀ) X' + M Y',  g = e_j − Mᵀ X', both columns at once.
    let mut f = vec![[0.0; 2]; ndof];
    let mut g = [Vector6::ith(0, 1.0), Vector6::ith(1, 1.0)];
    for quad in &quads {
        let ve: [[f64; 2]; 12] = std::array::from_fn(|i| slope(&x[3 * quad.nodes[i / 3] + i % 3]));
        let mut fe = [Vec12::zeros(); 2];
        for p in &quad.points {
            let (bv, sv) = (p.b(&ve), p.s(&ve));
            for j in 0..2 {
                let column = |rows: &[[f64; 2]; 6]| Vector6::from_fn(|r, _| rows[r][j]);
                let qs = quad.q * column(&sv);
                let qbz = quad.q * (column(&bv) + p.z(&y_slope[j]));
                fe[j] += (p.st(&qbz) - p.bt(&qs)) * p.w;
                g[j] -= p.zt(&qs) * p.w;
            }
        }
        for (i, (a, b)) in fe[0].iter().zip(fe[1].iter()).enumerate() {
            let k = 3 * quad.nodes[i / 3] + i % 3;
            f[k][0] += a;
            f[k][1] += b;
        }
    }
    let mut xf = free_columns(&f, free, nfree);
    solve(&mut xf);
    for (j, g) in g.into_iter().enumerate() {
        ys[j] = column(&mut x, j, Some((&xf, j)), g);
    }

    // F = ∫εᵀQε over the six unit forces, ε = S_zZ Y + B X + S X'.
    let mut flex = Matrix6::zeros();
    for quad in &quads {
        let xe: [[f64; 6]; 12] = std::array::from_fn(|i| x[3 * quad.nodes[i / 3] + i % 3]);
        for p in &quad.points {
            // B X over the six columns, and S X' for the two shear columns.
            let mut e = p.b(&xe);
            let de: [[f64; 2]; 12] = std::array::from_fn(|i| slope(&xe[i]));
            for (row, sd) in e.iter_mut().zip(p.s(&de)) {
                row[0] += sd[0];
                row[1] += sd[1];
            }
            let mut eps = Matrix6::from_fn(|r, j| e[r][j]);
            for j in 0..6 {
                let zc = p.z(&ys[j]);
                for r in 0..6 {
                    eps[(r, j)] += zc[r];
                }
            }
            flex += eps.transpose() * (quad.q * eps) * p.w;
        }
    }
    let flex = (flex + flex.transpose()) * 0.5;
    let stiffness = flex.cholesky().map(|c| c.inverse()).ok_or_else(|| {
        Error::numerical("cross-section: the compliance is not positive definite")
    })?;
    let stiffness = (stiffness + stiffness.transpose()) * 0.5;
    let out = BeamMatrices {
        stiffness: to_array(&stiffness),
        mass: to_array(&mass),
        reference,
    };
    if out
        .stiffness
        .iter()
        .flatten()
        .chain(out.mass.iter().flatten())
        .any(|v| !v.is_finite())
    {
        return Err(Error::numerical(
            "cross-section: non-finite section matrices",
        ));
    }
    Ok((out, factorisation))
}

fn to_array(m: &Matrix6<f64>) -> [[f64; 6]; 6] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

#[cfg(test)]
mod tests {
    use super::super::material::Orthotropic;
    use super::super::mesh::{graded, Mesh, Ply};
    use super::*;

    fn channel() -> Mesh {
        // An unsymmetric section: every coupling of an isotropic beam shows.
        let xs = graded(&[0.0, 0.01, 0.06], &[2, 6]);
        let ys = graded(&[0.0, 0.01, 0.07, 0.08], &[2, 6, 2]);
        Mesh::grid(
            &xs,
            &ys,
            vec![Orthotropic::isotropic(70e9, 0.3, 2700.0)],
            |c| {
                (c[0] < 0.01 || c[1] < 0.01 || c[1] > 0.07).then_some(Ply {
                    material: 0,
                    fibre_angle: 0.0,
                    orientation: 0.0,
                })
            },
        )
        .unwrap()
    }

    fn max_rel(a: &[[f64; 6]; 6], b: &[[f64; 6]; 6]) -> f64 {
        let scale = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .fold(0.0, |m, (x, y)| m.max((x - y).abs() / scale))
    }

    #[test]
    fn the_matrices_do_not_depend_on_which_warping_nodes_are_held() {
        let mesh = channel();
        let (a, _) = analyse_pinned(&mesh, [0.02, 0.03], 0, None).unwrap();
        let (b, _) = analyse_pinned(&mesh, [0.02, 0.03], mesh.nodes.len() / 2, None).unwrap();
        let d = max_rel(&a.stiffness, &b.stiffness);
        assert!(d < 1e-9, "stiffness changed by {d:e} with the held nodes");
    }

    #[test]
    fn moving_the_reference_point_is_the_rigid_transform() {
        let mesh = channel();
        let a = analyse(&mesh, [0.0, 0.0]).unwrap();
        let b = analyse(&mesh, [0.03, -0.01]).unwrap();
        let moved = a.about([0.03, -0.01]);
        assert!(max_rel(&moved.stiffness, &b.stiffness) < 1e-9);
        assert!(max_rel(&moved.mass, &b.mass) < 1e-12);
    }

    #[test]
    fn the_stiffness_is_symmetric_positive_definite() {
        let k = analyse(&channel(), [0.0, 0.0]).unwrap().stiffness;
        let m = Matrix6::from_fn(|i, j| k[i][j]);
        assert!((m - m.transpose()).abs().max() <= 1e-12 * m.abs().max());
        assert!(m.cholesky().is_some());
    }

    #[test]
    fn a_material_without_stiffness_or_a_bad_point_is_an_error() {
        let mut mesh = channel();
        mesh.materials[0].g12 = 0.0;
        assert!(analyse(&mesh, [0.0, 0.0]).is_err());
        assert!(analyse(&channel(), [f64::NAN, 0.0]).is_err());
    }
}
