//! Finite elements of a tabulated blade (docs/model.md §11.2–§11.3): a linear beam on the
//! straight pitch axis, clamped at the root, with flap `u` (along x) and edge `v` (along y) on
//! cubic Hermite elements and elastic twist `φ` on linear ones. Per node `[u, u', v, v', φ]`.
//!
//! Strain energy `½∫ EI_ξ κ_ξ² + EI_η κ_η² + 2 EI_ξη κ_ξ κ_η + GJ φ'² − 2 g_ξ κ_ξ φ' − 2 g_η κ_η φ'`
//! with the curvatures in the section frame `κ_ξ = u'' cos θ + v'' sin θ`,
//! `κ_η = −u'' sin θ + v'' cos θ` (θ = structural twist + pitch). Kinetic energy
//! `½∫ m(u̇² + v̇²) + I_p φ̇² − 2 m y_c u̇ φ̇ + 2 m x_c v̇ φ̇` (centre of mass at `(x_c, y_c)` in the
//! rotor frame, `I_p` about the pitch axis). Rotation at Ω about the shaft (along x) adds
//! `Ω² K_Ω`: the centrifugal tension `T(z) = Ω²∫_z^L m (r_hub + s) ds` on both bending slopes,
//! the in-plane spin softening `−mΩ²` on v and its coupling `−m x_c Ω²` with φ, and the
//! propeller moment `Ω²[(∫ρη² − ∫ρξ²) cos 2θ + 2∫ρξη sin 2θ]` on φ. So `K(Ω) = K₀ + Ω² K_Ω`
//! exactly: both are assembled once, and a rotor-speed change costs no re-assembly.

use super::BladeTable;
use crate::error::{Error, Result};
use crate::physics::basis::gauss_legendre;
use nalgebra::DMatrix;

/// Degrees of freedom per node: `u, u', v, v', φ`.
pub const NODE_DOFS: usize = 5;
/// Offsets of each quantity in a node's block.
pub const U: usize = 0;
pub const V: usize = 2;
pub const PHI: usize = 4;

/// Gauss points per element: exact for the mass (cubic × cubic × linear property, degree 7) and
/// for the tension term (cubic T(z) × quadratic slopes, degree 7).
const GAUSS_POINTS: usize = 4;

/// The element mesh: node positions along the span, root first.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub nodes: Vec<f64>,
}

impl Mesh {
    /// Nodes at every input station, elements halved (longest first) until there are at least
    /// `min_elements`: the mesh follows the table, where its properties change slope.
    pub fn following(table: &BladeTable, min_elements: usize) -> Mesh {
        let mut nodes: Vec<f64> = table.sections.iter().map(|s| s.z).collect();
        while nodes.len() - 1 < min_elements {
            let (k, _) = nodes
                .windows(2)
                .enumerate()
                .map(|(k, w)| (k, w[1] - w[0]))
                .fold(
                    (0, f64::NEG_INFINITY),
                    |best, e| if e.1 > best.1 { e } else { best },
                );
            nodes.insert(k + 1, 0.5 * (nodes[k] + nodes[k + 1]));
        }
        Mesh { nodes }
    }

    pub fn elements(&self) -> usize {
        self.nodes.len() - 1
    }

    /// Free degrees of freedom: every node but the clamped root.
    pub fn dofs(&self) -> usize {
        NODE_DOFS * self.elements()
    }
}

/// The assembled structure of one blade at one pitch: `M`, `K₀`, `K_Ω` (free dofs only).
#[derive(Debug, Clone)]
pub struct BladeMatrices {
    pub mesh: Mesh,
    /// Pitch the section frames were turned by (rad).
    pub pitch: f64,
    pub mass: DMatrix<f64>,
    pub k0: DMatrix<f64>,
    /// Per Ω² (rad/s)⁻²: `K(Ω) = K₀ + Ω² K_Ω`.
    pub k_omega: DMatrix<f64>,
}

/// Shape functions of one element at local `s ∈ [0, 1]` as rows over its 10 dofs
/// `[u, u', v, v', φ]_a ++ [u, u', v, v', φ]_b`: values, slopes and curvatures in z.
struct Shapes {
    u: [f64; 10],
    du: [f64; 10],
    ddu: [f64; 10],
    v: [f64; 10],
    dv: [f64; 10],
    ddv: [f64; 10],
    phi: [f64; 10],
    dphi: [f64; 10],
}

/// Hermite cubics (values, first and second z-derivatives) for `[w_a, w'_a, w_b, w'_b]`.
pub(crate) fn hermite(s: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (s2, s3) = (s * s, s * s * s);
    (
        [
            1.0 - 3.0 * s2 + 2.0 * s3,
            h * (s - 2.0 * s2 + s3),
            3.0 * s2 - 2.0 * s3,
            h * (s3 - s2),
        ],
        [
            (-6.0 * s + 6.0 * s2) / h,
            1.0 - 4.0 * s + 3.0 * s2,
            (6.0 * s - 6.0 * s2) / h,
            3.0 * s2 - 2.0 * s,
        ],
        [
            (-6.0 + 12.0 * s) / (h * h),
            (-4.0 + 6.0 * s) / h,
            (6.0 - 12.0 * s) / (h * h),
            (6.0 * s - 2.0) / h,
        ],
    )
}

impl Shapes {
    fn at(s: f64, h: f64) -> Shapes {
        let (n, dn, ddn) = hermite(s, h);
        let place = |w: [f64; 4], offset: usize| {
            let mut row = [0.0; 10];
            row[offset] = w[0];
            row[offset + 1] = w[1];
            row[NODE_DOFS + offset] = w[2];
            row[NODE_DOFS + offset + 1] = w[3];
            row
        };
        let mut phi = [0.0; 10];
        let mut dphi = [0.0; 10];
        phi[PHI] = 1.0 - s;
        phi[NODE_DOFS + PHI] = s;
        dphi[PHI] = -1.0 / h;
        dphi[NODE_DOFS + PHI] = 1.0 / h;
        Shapes {
            u: place(n, U),
            du: place(dn, U),
            ddu: place(ddn, U),
            v: place(n, V),
            dv: place(dn, V),
            ddv: place(ddn, V),
            phi,
            dphi,
        }
    }
}

/// Adds `w (aᵀb + bᵀa)` to a 10×10 element matrix: the symmetric part of a coupling term.
fn add_sym(k: &mut [[f64; 10]; 10], w: f64, a: &[f64; 10], b: &[f64; 10]) {
    if w == 0.0 {
        return;
    }
    for i in 0..10 {
        for j in 0..10 {
            k[i][j] += w * (a[i] * b[j] + b[i] * a[j]);
        }
    }
}

/// Adds `w aᵀa` to a 10×10 element matrix.
fn add_outer(k: &mut [[f64; 10]; 10], w: f64, a: &[f64; 10]) {
    if w == 0.0 {
        return;
    }
    for i in 0..10 {
        for j in 0..10 {
            k[i][j] += w * a[i] * a[j];
        }
    }
}

/// `∫_a^b m(z)(r_hub + z) dz` by Simpson's rule: exact when `[a, b]` lies within one table
/// interval, where the mass is linear and the integrand quadratic.
fn tension_integral(table: &BladeTable, a: f64, b: f64) -> f64 {
    let f = |z: f64| table.at(z).mass * (table.hub_radius + z);
    (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b))
}

/// `T(z)/Ω² = ∫_z^L m (r_hub + s) ds` at every node, summed over pieces split at the nodes and
/// the table stations (exact for the piecewise linear mass).
fn tension_at_nodes(table: &BladeTable, nodes: &[f64]) -> Vec<f64> {
    let mut points: Vec<f64> = table
        .sections
        .iter()
        .map(|s| s.z)
        .chain(nodes.iter().copied())
        .collect();
    points.sort_by(f64::total_cmp);
    points.dedup();
    let mut tail = vec![0.0; points.len()];
    for k in (0..points.len() - 1).rev() {
        tail[k] = tail[k + 1] + tension_integral(table, points[k], points[k + 1]);
    }
    nodes
        .iter()
        .map(|z| tail[points.partition_point(|p| p < z)])
        .collect()
}

/// Assemble `M`, `K₀` and `K_Ω` of `table` on `mesh` at `pitch` (rad), clamped at the root.
pub fn assemble(table: &BladeTable, mesh: &Mesh, pitch: f64) -> Result<BladeMatrices> {
    if mesh.nodes.len() < 2 {
        return Err(Error::numerical("blade mesh needs at least one element"));
    }
    let n = mesh.dofs();
    let mut mass = DMatrix::zeros(n, n);
    let mut k0 = DMatrix::zeros(n, n);
    let mut k_omega = DMatrix::zeros(n, n);
    let (gauss_s, gauss_w) = gauss_legendre(GAUSS_POINTS);
    let tension = tension_at_nodes(table, &mesh.nodes);
    for e in 0..mesh.elements() {
        let (za, zb) = (mesh.nodes[e], mesh.nodes[e + 1]);
        let h = zb - za;
        let (mut me, mut ke, mut kw) = ([[0.0; 10]; 10], [[0.0; 10]; 10], [[0.0; 10]; 10]);
        for (&xi, &wq) in gauss_s.iter().zip(&gauss_w) {
            let s = 0.5 * (xi + 1.0);
            let w = 0.5 * wq * h;
            let z = za + s * h;
            let sec = table.at(z);
            let sh = Shapes::at(s, h);
            let theta = sec.twist + pitch;
            let (sn, cs) = theta.sin_cos();
            let row = |a: &[f64; 10], ca: f64, b: &[f64; 10], cb: f64| {
                let mut r = [0.0; 10];
                for i in 0..10 {
                    r[i] = ca * a[i] + cb * b[i];
                }
                r
            };
            let k_xi = row(&sh.ddu, cs, &sh.ddv, sn);
            let k_eta = row(&sh.ddu, -sn, &sh.ddv, cs);
            add_outer(&mut ke, w * sec.ei_flap, &k_xi);
            add_outer(&mut ke, w * sec.ei_edge, &k_eta);
            add_sym(&mut ke, w * sec.ei_cross, &k_xi, &k_eta);
            add_outer(&mut ke, w * sec.gj, &sh.dphi);
            add_sym(&mut ke, -w * sec.flap_twist, &k_xi, &sh.dphi);
            add_sym(&mut ke, -w * sec.edge_twist, &k_eta, &sh.dphi);

            // Centre of mass in the rotor frame.
            let (c_xi, c_eta) = (sec.cg[0], sec.cg[1]);
            let x_c = c_xi * cs - c_eta * sn;
            let y_c = c_xi * sn + c_eta * cs;
            let [i_xi, i_eta, i_xe] = sec.inertia;
            let m = sec.mass;
            add_outer(&mut me, w * m, &sh.u);
            add_outer(&mut me, w * m, &sh.v);
            add_outer(&mut me, w * (i_xi + i_eta), &sh.phi);
            add_sym(&mut me, -w * m * y_c, &sh.u, &sh.phi);
            add_sym(&mut me, w * m * x_c, &sh.v, &sh.phi);

            // Per Ω²: the tension at the Gauss point, from the next node outboard (the mesh
            // follows the stations, so [z, z_b] lies in one table interval).
            let t = tension[e + 1] + tension_integral(table, z, zb);
            add_outer(&mut kw, w * t, &sh.du);
            add_outer(&mut kw, w * t, &sh.dv);
            add_outer(&mut kw, -w * m, &sh.v);
            add_sym(&mut kw, -w * m * x_c, &sh.v, &sh.phi);
            let propeller = (i_eta - i_xi) * (2.0 * theta).cos() + 2.0 * i_xe * (2.0 * theta).sin();
            add_outer(&mut kw, w * propeller, &sh.phi);
        }
        scatter(&mut mass, &me, e);
        scatter(&mut k0, &ke, e);
        scatter(&mut k_omega, &kw, e);
    }
    for (name, a) in [
        ("mass", &mass),
        ("stiffness", &k0),
        ("rotational stiffness", &k_omega),
    ] {
        if a.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(format!(
                "{}: blade {name} matrix has non-finite entries",
                table.origin
            )));
        }
    }
    Ok(BladeMatrices {
        mesh: mesh.clone(),
        pitch,
        mass,
        k0,
        k_omega,
    })
}

/// Add an element matrix into the global one (the root node's dofs are clamped away).
fn scatter(global: &mut DMatrix<f64>, local: &[[f64; 10]; 10], element: usize) {
    let index = |i: usize| -> Option<usize> {
        let node = element + i / NODE_DOFS;
        (node > 0).then(|| (node - 1) * NODE_DOFS + i % NODE_DOFS)
    };
    for (i, row) in local.iter().enumerate() {
        let Some(gi) = index(i) else { continue };
        for (j, value) in row.iter().enumerate() {
            let Some(gj) = index(j) else { continue };
            global[(gi, gj)] += value;
        }
    }
}
