//! Finite elements of a tabulated blade (docs/model.md §11.2–§11.3): a linear beam along the
//! pitch axis (curved by its prebend and sweep, §11.9), clamped at the root, with flap `u`
//! (along x) and edge `v` (along y) on cubic Hermite elements and elastic twist `φ` on linear
//! ones. Per node `[u, u', v, v', φ]`,
//! where `u`, `v` are the displacements of the shear centre (the elastic axis) and `φ` the
//! rotation of the section about it.
//!
//! Strain energy `½∫ EI_ξ κ_ξ² + EI_η κ_η² + 2 EI_ξη κ_ξ κ_η + GJ φ'² − 2 g_ξ κ_ξ φ' − 2 g_η κ_η φ'`
//! with the curvatures of the shear-centre line in the section frame
//! `κ_ξ = u'' cos θ + v'' sin θ`, `κ_η = −u'' sin θ + v'' cos θ` (θ = structural twist + pitch).
//! A point at `(x, y)` in the rotor frame moves by `(u − φ(y − y_s), v + φ(x − x_s))`, so the
//! kinetic energy is `½∫ m(u̇² + v̇²) + I_s φ̇² − 2 m (y_c − y_s) u̇ φ̇ + 2 m (x_c − x_s) v̇ φ̇`
//! (centre of mass `(x_c, y_c)`, shear centre `(x_s, y_s)`, `I_s` the polar mass moment about
//! the shear centre). Rotation at Ω about the shaft (along x) adds `Ω² K_Ω`: the centrifugal
//! tension `T(z) = Ω²∫_z^L m (r_hub + s) ds` on the slopes of the tension-centre line
//! `u_e = u − φ(y_e − y_s)`, `v_e = v + φ(x_e − x_s)`, the in-plane spin softening `−mΩ²` on v and
//! its coupling `−m (x_c − x_s) Ω²` with φ, and the propeller moment about the shear centre on φ.
//! So `K(Ω) = K₀ + Ω² K_Ω` exactly: both are assembled once, and a rotor-speed change costs no
//! re-assembly. With every offset zero the terms reduce exactly (bit for bit) to those of a blade
//! whose shear and tension centres lie on the pitch axis.

use super::axis::AxisPoint;
use super::hermite::hermite;
use super::{BeamSection, BladeTable};
use crate::error::{Error, Result};
use crate::numeric::banded::SymmetricBand;
use crate::physics::basis::gauss_legendre;
use nalgebra::{DMatrix, DVector};

/// Where each family's degrees of freedom sit among the free dofs: the element's own layout,
/// which what groups the dofs (the family shares of a mode) reads from the assembled matrices
/// ([`Beam::layout`] of [`BladeMatrices::beam`]) rather than assuming.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeLayout {
    /// The family (flap 0, edge 1, twist 2) of each dof of a node's block, in block order.
    pub family: &'static [usize],
    /// The families of the dofs the clamped root keeps, numbered before the nodes' blocks.
    pub root: &'static [usize],
}

impl NodeLayout {
    /// The family of free dof `i`.
    pub fn family_of(&self, i: usize) -> usize {
        match i.checked_sub(self.root.len()) {
            None => self.root[i],
            Some(k) => self.family[k % self.family.len()],
        }
    }

    /// Free dofs of a mesh of `elements` elements.
    pub fn dofs(&self, elements: usize) -> usize {
        self.root.len() + self.family.len() * elements
    }
}

/// The beam the elements model (docs/model.md §11.2–§11.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beam {
    /// Rigid in shear: `[u, u', v, v', φ]` per node, the root clamped.
    EulerBernoulli,
    /// Shear-deformable: `[u, u', γ_u, v, v', γ_v, φ]` per node, `γ` the transverse shear strain
    /// of the shear-centre line; the clamped root holds `u = v = φ = 0` and a zero section
    /// rotation `u' − γ_u = v' − γ_v = 0`, so it keeps one dof per direction, `γ_u = u'`.
    Timoshenko,
}

/// Local dofs of an element's node: both beams share this numbering, the Euler–Bernoulli beam
/// leaving the shear strains out.
pub const LOCAL: usize = 7;
const U: usize = 0;
const GU: usize = 2;
const V: usize = 3;
const GV: usize = 5;
const PHI: usize = 6;
/// An element's local dofs: two nodes.
const ELEMENT: usize = 2 * LOCAL;

/// A row of one quantity over an element's local dofs.
type Row = [f64; ELEMENT];

impl Beam {
    /// The beam a table's sections call for.
    pub fn of(table: &BladeTable) -> Beam {
        if table.is_shear_deformable() {
            Beam::Timoshenko
        } else {
            Beam::EulerBernoulli
        }
    }

    /// The beam as reports name it.
    pub fn title(self) -> &'static str {
        match self {
            Beam::EulerBernoulli => "Euler–Bernoulli",
            Beam::Timoshenko => "shear-deformable",
        }
    }

    /// Where each family's dofs sit.
    pub fn layout(self) -> NodeLayout {
        match self {
            Beam::EulerBernoulli => NodeLayout {
                family: &[0, 0, 1, 1, 2],
                root: &[],
            },
            Beam::Timoshenko => NodeLayout {
                family: &[0, 0, 0, 1, 1, 1, 2],
                root: &[0, 1],
            },
        }
    }

    /// The free dof local dof `k` of node `node` is (`None`: held at zero by the clamp or not
    /// modelled). Two local dofs may be one free dof: the root's slope and shear strain.
    fn global(self, node: usize, k: usize) -> Option<usize> {
        match self {
            Beam::EulerBernoulli => {
                const SLOT: [Option<usize>; LOCAL] =
                    [Some(0), Some(1), None, Some(2), Some(3), None, Some(4)];
                SLOT[k].filter(|_| node > 0).map(|j| (node - 1) * 5 + j)
            }
            Beam::Timoshenko if node == 0 => match k {
                1 | GU => Some(0),
                4 | GV => Some(1),
                _ => None,
            },
            Beam::Timoshenko => Some(2 + (node - 1) * LOCAL + k),
        }
    }

    /// The free dofs of node `node` (0 the root) in the order `[u, u', γ_u, v, v', γ_v, φ]`
    /// (`None`: held by the clamp, or a shear strain the Euler–Bernoulli beam has not). Its
    /// section turns by `u' − γ_u` and `v' − γ_v`.
    pub fn node_dofs(self, node: usize) -> [Option<usize>; LOCAL] {
        std::array::from_fn(|k| self.global(node, k))
    }

    /// The free dof of each of element `element`'s local dofs.
    fn element_dofs(self, element: usize) -> [Option<usize>; ELEMENT] {
        std::array::from_fn(|i| self.global(element + i / LOCAL, i % LOCAL))
    }
}

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
}

/// The assembled structure of one blade at one pitch: `M`, `K₀`, `K_Ω` (free dofs only), dense
/// ([`assemble`]) or as their bands ([`assemble_banded`], what the modal bases are built from).
#[derive(Debug, Clone)]
pub struct BladeMatrices<M = DMatrix<f64>> {
    /// The table the matrices came from: the offsets that carry a mode shape from the shear
    /// centre to the reference axis ([`BladeMatrices::reference_axis_at`]).
    pub table: BladeTable,
    pub mesh: Mesh,
    /// Pitch the section frames were turned by (rad).
    pub pitch: f64,
    pub mass: M,
    pub k0: M,
    /// Per Ω² (rad/s)⁻²: `K(Ω) = K₀ + Ω² K_Ω`.
    pub k_omega: M,
    /// The beam the elements model; where each family's dofs sit is its
    /// [`layout`](Beam::layout).
    pub beam: Beam,
    /// Per Ω², the load rotation puts on the curved blade with its curve turned by 0 and by 90°
    /// instead of by the pitch (zero for a straight blade): the load at any pitch of the curve
    /// is `cos p · [0] + sin p · [1]` ([`BladeMatrices::centrifugal_load`]).
    pub curve_loads: [DVector<f64>; 2],
    /// The blade moving rigidly with the hub (docs/model.md §13.2, §13.6), one column per
    /// [`Rigid`] motion: `M r` on the free dofs, the inertial load the hub's acceleration in
    /// that motion puts on the blade (n × 4).
    pub rigid_loads: DMatrix<f64>,
    /// `rᵢᵀ M rⱼ` of the rigid motions (4 × 4), root element included (the clamp holds the
    /// root's dofs at zero relative to the hub, not in space): the blade's moment of inertia
    /// about the shaft, its mass, its moment of inertia about an axis across the shaft.
    pub rigid_mass: DMatrix<f64>,
}

/// The blade's rigid motions with the hub, per unit: the columns of
/// [`BladeMatrices::rigid_loads`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rigid {
    /// About the shaft, one radian: every point moves in the edge direction by its radius.
    Rotation = 0,
    /// One metre downwind.
    Flap = 1,
    /// One metre in the edge direction.
    Edge = 2,
    /// About the axis across the shaft perpendicular to the blade, one radian: every point
    /// moves downwind by its radius.
    Tilt = 3,
}

/// How many [`Rigid`] motions there are.
pub const RIGID_MOTIONS: usize = 4;

impl Rigid {
    pub const ALL: [Rigid; RIGID_MOTIONS] =
        [Rigid::Rotation, Rigid::Flap, Rigid::Edge, Rigid::Tilt];

    /// An element's local dofs in this motion, its nodes at radii `ra`, `rb`: a translation
    /// moves every node alike, a rotation by its radius with the slope 1 (the section turns
    /// with the slope, no shear strain, no twist).
    fn element_dofs(self, ra: f64, rb: f64) -> Row {
        let mut r = [0.0; ELEMENT];
        for (node, radius) in [(0, ra), (1, rb)] {
            let at = node * LOCAL;
            match self {
                Rigid::Rotation => {
                    r[at + V] = radius;
                    r[at + V + 1] = 1.0;
                }
                Rigid::Flap => r[at + U] = 1.0,
                Rigid::Edge => r[at + V] = 1.0,
                Rigid::Tilt => {
                    r[at + U] = radius;
                    r[at + U + 1] = 1.0;
                }
            }
        }
        r
    }
}

/// Shape functions of one element at local `s ∈ [0, 1]` as rows over its local dofs
/// `[u, u', γ_u, v, v', γ_v, φ]_a ++ […]_b`: values, slopes and curvatures in z of the
/// displacements, the shear strains (linear) and their slopes, and the twist.
struct Shapes {
    u: Row,
    du: Row,
    ddu: Row,
    gu: Row,
    dgu: Row,
    v: Row,
    dv: Row,
    ddv: Row,
    gv: Row,
    dgv: Row,
    phi: Row,
    dphi: Row,
}

impl Shapes {
    fn at(s: f64, h: f64) -> Shapes {
        let (n, dn, ddn) = hermite(s, h);
        let place = |w: [f64; 4], offset: usize| {
            let mut row = [0.0; ELEMENT];
            row[offset] = w[0];
            row[offset + 1] = w[1];
            row[LOCAL + offset] = w[2];
            row[LOCAL + offset + 1] = w[3];
            row
        };
        let linear = |offset: usize| {
            let (mut value, mut slope) = ([0.0; ELEMENT], [0.0; ELEMENT]);
            value[offset] = 1.0 - s;
            value[LOCAL + offset] = s;
            slope[offset] = -1.0 / h;
            slope[LOCAL + offset] = 1.0 / h;
            (value, slope)
        };
        let (gu, dgu) = linear(GU);
        let (gv, dgv) = linear(GV);
        let (phi, dphi) = linear(PHI);
        Shapes {
            u: place(n, U),
            du: place(dn, U),
            ddu: place(ddn, U),
            gu,
            dgu,
            v: place(n, V),
            dv: place(dn, V),
            ddv: place(ddn, V),
            gv,
            dgv,
            phi,
            dphi,
        }
    }
}

/// An element matrix over its local dofs.
type ElementMatrix = [[f64; ELEMENT]; ELEMENT];

/// Adds `w (aᵀb + bᵀa)` to an element matrix: the symmetric part of a coupling term.
fn add_sym(k: &mut ElementMatrix, w: f64, a: &Row, b: &Row) {
    if w == 0.0 {
        return;
    }
    for i in 0..ELEMENT {
        for j in 0..ELEMENT {
            k[i][j] += w * (a[i] * b[j] + b[i] * a[j]);
        }
    }
}

/// Adds `w aᵀa` to an element matrix.
fn add_outer(k: &mut ElementMatrix, w: f64, a: &Row) {
    if w == 0.0 {
        return;
    }
    for i in 0..ELEMENT {
        for j in 0..ELEMENT {
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

/// The offsets of one section in the rotor frame (docs/model.md §11.2), turned from its section
/// frame by `θ = twist + pitch`: centre of mass and shear centre from the reference axis, and
/// the tension centre from the shear centre with its rate along the span.
struct RotorOffsets {
    cg: [f64; 2],
    shear: [f64; 2],
    /// Tension centre minus shear centre.
    tension: [f64; 2],
    /// Its derivative along the span: the section-frame offsets change and the frame turns.
    tension_rate: [f64; 2],
}

/// `(ξ, η)` of a section frame turned by `theta` toward feather, in the rotor frame `(x, y)`
/// (docs/model.md §11.1).
fn to_rotor(v: [f64; 2], theta: f64) -> [f64; 2] {
    let (sn, cs) = theta.sin_cos();
    [v[0] * cs - v[1] * sn, v[0] * sn + v[1] * cs]
}

/// The span derivative of `to_rotor(v(z), θ(z))`: `R v' + θ' J R v` (J turns a vector by +90°;
/// docs/model.md §11.2).
fn to_rotor_rate(v: [f64; 2], v_rate: [f64; 2], theta: f64, theta_rate: f64) -> [f64; 2] {
    let turned = to_rotor(v, theta);
    let moved = to_rotor(v_rate, theta);
    [
        moved[0] - theta_rate * turned[1],
        moved[1] + theta_rate * turned[0],
    ]
}

impl RotorOffsets {
    /// docs/model.md §11.2: the offsets of `sec` (with `rate` its span derivative) at `theta`.
    fn of(sec: &BeamSection, rate: &BeamSection, theta: f64) -> RotorOffsets {
        let relative = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        let tension = relative(sec.tension_centre, sec.shear_centre);
        let tension_rate = relative(rate.tension_centre, rate.shear_centre);
        RotorOffsets {
            cg: to_rotor(sec.cg, theta),
            shear: to_rotor(sec.shear_centre, theta),
            tension: to_rotor(tension, theta),
            tension_rate: to_rotor_rate(tension, tension_rate, theta, rate.twist),
        }
    }
}

/// `ca a + cb b`, entry by entry: a row of one quantity over an element's dofs.
fn mix(a: &Row, ca: f64, b: &Row, cb: f64) -> Row {
    let mut r = [0.0; ELEMENT];
    for i in 0..ELEMENT {
        r[i] = ca * a[i] + cb * b[i];
    }
    r
}

/// Assemble `M`, `K₀` and `K_Ω` of `table` on `mesh` at `pitch` (rad), clamped at the root
/// (docs/model.md §11.2–§11.3), as the beam its sections call for ([`Beam::of`]).
pub fn assemble(table: &BladeTable, mesh: &Mesh, pitch: f64) -> Result<BladeMatrices> {
    assemble_with(table, mesh, pitch, None)
}

/// [`assemble`] into the matrices' bands: what the modal bases take, without the dense
/// matrices (on a 120-element blade three of 5.7 MB each, zeroed and scanned for nothing).
pub fn assemble_banded(
    table: &BladeTable,
    mesh: &Mesh,
    pitch: f64,
) -> Result<BladeMatrices<SymmetricBand>> {
    assemble_with(table, mesh, pitch, None)
}

/// Where the assembly adds the element matrices: a dense matrix, or the lower band of a
/// symmetric one (the element matrices are symmetric).
pub trait Storage: Sized {
    fn zeros(n: usize, band: usize) -> Self;
    fn add(&mut self, i: usize, j: usize, v: f64);
}

impl Storage for DMatrix<f64> {
    fn zeros(n: usize, _band: usize) -> Self {
        DMatrix::zeros(n, n)
    }
    fn add(&mut self, i: usize, j: usize, v: f64) {
        self[(i, j)] += v;
    }
}

impl Storage for SymmetricBand {
    fn zeros(n: usize, band: usize) -> Self {
        SymmetricBand::zeros(n, band)
    }
    fn add(&mut self, i: usize, j: usize, v: f64) {
        // Each off-diagonal pair comes twice, once from each side; the lower one is kept.
        if i >= j {
            self.add_lower(i, j, v);
        }
    }
}

/// Factors on the section stiffness per strain `(γ_ξ, γ_η, κ_ξ, κ_η, φ')`: a coupling term
/// between two strains takes the mean of theirs (docs/model.md §11.4, stiffness-proportional
/// damping).
pub type StrainFactors = [f64; 5];

/// `K₀` with every stiffness term scaled by [`StrainFactors`]: the damping matrix of
/// stiffness-proportional damping, term by term the elastic stiffness of [`assemble`].
pub fn scaled_stiffness(
    table: &BladeTable,
    mesh: &Mesh,
    pitch: f64,
    factors: StrainFactors,
) -> Result<SymmetricBand> {
    Ok(assemble_with(table, mesh, pitch, Some(factors))?.k0)
}

fn assemble_with<M: Storage>(
    table: &BladeTable,
    mesh: &Mesh,
    pitch: f64,
    factors: Option<StrainFactors>,
) -> Result<BladeMatrices<M>> {
    if mesh.nodes.len() < 2 {
        return Err(Error::numerical("blade mesh needs at least one element"));
    }
    let beam = Beam::of(table);
    let n = beam.layout().dofs(mesh.elements());
    let band = element_band(beam, mesh.elements());
    let mut mass = M::zeros(n, band);
    let mut k0 = M::zeros(n, band);
    let mut k_omega = M::zeros(n, band);
    let mut curve_loads = [DVector::zeros(n), DVector::zeros(n)];
    let mut rigid_loads = DMatrix::zeros(n, RIGID_MOTIONS);
    let mut rigid_mass = DMatrix::zeros(RIGID_MOTIONS, RIGID_MOTIONS);
    let curved = !table.axis.is_straight();
    let (gauss_s, gauss_w) = gauss_legendre(GAUSS_POINTS);
    let tension = tension_at_nodes(table, &mesh.nodes);
    let scale = |i: usize, j: usize| factors.map_or(1.0, |f| 0.5 * (f[i] + f[j]));
    for e in 0..mesh.elements() {
        let (za, zb) = (mesh.nodes[e], mesh.nodes[e + 1]);
        let h = zb - za;
        let zero = [[0.0; ELEMENT]; ELEMENT];
        let (mut me, mut ke, mut kw) = (zero, zero, zero);
        let mut le = [[0.0; ELEMENT]; 2];
        let axis = [za, zb].map(|z| table.axis.at(z));
        for (&xi, &wq) in gauss_s.iter().zip(&gauss_w) {
            let s = 0.5 * (xi + 1.0);
            let w = 0.5 * wq * h;
            let z = za + s * h;
            let sec = table.at(z);
            let sh = Shapes::at(s, h);
            let along = axis_along(&axis, s, h);
            let curvature = to_rotor(along.curvature, pitch);
            let theta = sec.twist + pitch;
            let (sn, cs) = theta.sin_cos();
            let to_section = |x: &Row, y: &Row| (mix(x, cs, y, sn), mix(x, -sn, y, cs));
            match beam {
                Beam::EulerBernoulli => {
                    // Curvatures of the shear-centre line in the section frame.
                    let (k_xi, k_eta) = to_section(
                        &mix(&sh.ddu, 1.0, &sh.phi, curvature[1]),
                        &mix(&sh.ddv, 1.0, &sh.phi, -curvature[0]),
                    );
                    let twist_rate = curved_twist_rate(&sh.dphi, &sh.du, &sh.dv, curvature);
                    let c = sec.bending_torsion();
                    let strains = [&k_xi, &k_eta, &twist_rate];
                    // Diagonal terms first, then the couplings (flap–edge, then with the twist).
                    for (i, j) in [(0, 0), (1, 1), (0, 1), (2, 2), (0, 2), (1, 2)] {
                        let k = w * (scale(i + 2, j + 2) * c[(i, j)]);
                        if i == j {
                            add_outer(&mut ke, k, strains[i]);
                        } else {
                            add_sym(&mut ke, k, strains[i], strains[j]);
                        }
                    }
                }
                Beam::Timoshenko => {
                    let k5 = sec.timoshenko_stiffness().ok_or_else(|| Error::Invalid {
                        origin: table.origin.clone(),
                        message: format!(
                            "at z = {z} m the section's shear flexibility and bending–torsion \
                             stiffness are not positive definite together"
                        ),
                    })?;
                    // Section rotations `u' − γ`: their rates are the curvatures.
                    let (k_xi, k_eta) = to_section(
                        &mix(
                            &mix(&sh.ddu, 1.0, &sh.dgu, -1.0),
                            1.0,
                            &sh.phi,
                            curvature[1],
                        ),
                        &mix(
                            &mix(&sh.ddv, 1.0, &sh.dgv, -1.0),
                            1.0,
                            &sh.phi,
                            -curvature[0],
                        ),
                    );
                    let twist_rate = curved_twist_rate(
                        &sh.dphi,
                        &mix(&sh.du, 1.0, &sh.gu, -1.0),
                        &mix(&sh.dv, 1.0, &sh.gv, -1.0),
                        curvature,
                    );
                    let (g_xi, g_eta) = to_section(&sh.gu, &sh.gv);
                    let strains = [&g_xi, &g_eta, &k_xi, &k_eta, &twist_rate];
                    for i in 0..5 {
                        add_outer(&mut ke, w * (scale(i, i) * k5[(i, i)]), strains[i]);
                        for j in i + 1..5 {
                            let k = w * (scale(i, j) * k5[(i, j)]);
                            add_sym(&mut ke, k, strains[i], strains[j]);
                        }
                    }
                }
            }

            // Mass about the shear centre, the axis the section turns about.
            let at = RotorOffsets::of(&sec, &table.rate_at(z), theta);
            let ([x_c, y_c], [x_s, y_s]) = (at.cg, at.shear);
            let [i_xi, i_eta, _] = sec.inertia;
            let m = sec.mass;
            let polar =
                i_xi + i_eta - 2.0 * m * (x_c * x_s + y_c * y_s) + m * (x_s * x_s + y_s * y_s);
            add_outer(&mut me, w * m, &sh.u);
            add_outer(&mut me, w * m, &sh.v);
            add_outer(&mut me, w * polar, &sh.phi);
            add_sym(&mut me, -w * m * (y_c - y_s), &sh.u, &sh.phi);
            add_sym(&mut me, w * m * (x_c - x_s), &sh.v, &sh.phi);
            if beam == Beam::Timoshenko {
                // Rotary inertia of the section turning with the bending rotation.
                let [j_xx, j_yy, j_xy] = rotary_inertia(&sec, theta);
                let rot_u = mix(&sh.du, 1.0, &sh.gu, -1.0);
                let rot_v = mix(&sh.dv, 1.0, &sh.gv, -1.0);
                add_outer(&mut me, w * j_xx, &rot_u);
                add_outer(&mut me, w * j_yy, &rot_v);
                add_sym(&mut me, w * j_xy, &rot_u, &rot_v);
            }

            // Per Ω²: the tension at the Gauss point, from the next node outboard (the mesh
            // follows the stations, so [z, z_b] lies in one table interval), on the slopes of the
            // tension-centre line, where it acts.
            let t = tension[e + 1] + tension_integral(table, z, zb);
            let [dx, dy] = at.tension;
            let [dx_rate, dy_rate] = at.tension_rate;
            let slope_u = mix(&mix(&sh.du, 1.0, &sh.dphi, -dy), 1.0, &sh.phi, -dy_rate);
            let slope_v = mix(&mix(&sh.dv, 1.0, &sh.dphi, dx), 1.0, &sh.phi, dx_rate);
            add_outer(&mut kw, w * t, &slope_u);
            add_outer(&mut kw, w * t, &slope_v);
            add_outer(&mut kw, -w * m, &sh.v);
            add_sym(&mut kw, -w * m * (x_c - x_s), &sh.v, &sh.phi);
            add_outer(
                &mut kw,
                w * propeller(sec.inertia, m, at.cg, at.shear, theta),
                &sh.phi,
            );
            if curved {
                // The centrifugal pull on the curve (the curve turned by 0 and by 90°): the
                // tension on the curve's slopes against the radial pitch axis, and the in-plane
                // pull on its offset in the rotor plane, at the mass and its arm about the shear
                // centre (the terms of K_Ω with the curve in place of the motion).
                let ([x, y], [dx0, dy0]) = (along.offset, along.slope);
                for (turn, (y0, slopes)) in [(y, [dx0, dy0]), (x, [-dy0, dx0])].iter().enumerate() {
                    let load = mix(
                        &mix(&slope_u, -w * t * slopes[0], &slope_v, -w * t * slopes[1]),
                        1.0,
                        &mix(&sh.v, w * m * y0, &sh.phi, w * m * (x_c - x_s) * y0),
                        1.0,
                    );
                    for (acc, v) in le[turn].iter_mut().zip(load) {
                        *acc += v;
                    }
                }
            }
        }
        // Checked element by element: a scan of the assembled matrices costs more than the
        // assembly on a long blade.
        for (name, a) in [
            ("mass", &me),
            ("stiffness", &ke),
            ("rotational stiffness", &kw),
        ] {
            if a.iter().flatten().any(|v| !v.is_finite()) {
                return Err(Error::numerical(format!(
                    "{}: blade {name} matrix has non-finite entries (element {e}, z = {za}–{zb} m)",
                    table.origin
                )));
            }
        }
        let dofs = beam.element_dofs(e);
        let (ra, rb) = (table.hub_radius + za, table.hub_radius + zb);
        let motions = Rigid::ALL.map(|m| m.element_dofs(ra, rb));
        for (i, r) in motions.iter().enumerate() {
            let load = element_times(&me, r);
            for (j, s) in motions.iter().enumerate() {
                rigid_mass[(i, j)] += load.iter().zip(s).map(|(a, b)| a * b).sum::<f64>();
            }
            for (value, d) in load.iter().zip(&dofs) {
                if let Some(d) = d {
                    rigid_loads[(*d, i)] += value;
                }
            }
        }
        scatter(&mut mass, &me, &dofs);
        scatter(&mut k0, &ke, &dofs);
        scatter(&mut k_omega, &kw, &dofs);
        for (global, local) in curve_loads.iter_mut().zip(&le) {
            scatter_load(global, local, &dofs);
        }
    }
    Ok(BladeMatrices {
        curve_loads,
        rigid_loads,
        rigid_mass,
        table: table.clone(),
        mesh: mesh.clone(),
        pitch,
        mass,
        k0,
        k_omega,
        beam,
    })
}

/// The reference axis at local `s` of an element of length `h` whose nodes hold `axis`, in the
/// blade's frame: the Hermite cubic through the nodes' offsets and slopes, the interpolation the
/// displacements use, and its curvature.
struct AxisAlong {
    offset: [f64; 2],
    slope: [f64; 2],
    curvature: [f64; 2],
}

fn axis_along(axis: &[AxisPoint; 2], s: f64, h: f64) -> AxisAlong {
    let (n, dn, ddn) = hermite(s, h);
    let [a, b] = axis;
    let at = |w: &[f64; 4], c: usize| {
        w[0] * a.offset[c] + w[1] * a.slope[c] + w[2] * b.offset[c] + w[3] * b.slope[c]
    };
    AxisAlong {
        offset: [at(&n, 0), at(&n, 1)],
        slope: [at(&dn, 0), at(&dn, 1)],
        curvature: [at(&ddn, 0), at(&ddn, 1)],
    }
}

/// The rate of twist of a curved beam (docs/model.md §11.9): `φ' − y₀'' θ_u + x₀'' θ_v`, with
/// `θ_u`, `θ_v` the section rotations (the slopes, less the shear strains) and `[x₀'', y₀'']`
/// the axis's curvature in the rotor frame: bending a curved axis about one direction turns its
/// sections about the tangent.
fn curved_twist_rate(dphi: &Row, rot_u: &Row, rot_v: &Row, curvature: [f64; 2]) -> Row {
    mix(
        &mix(dphi, 1.0, rot_u, -curvature[1]),
        1.0,
        rot_v,
        curvature[0],
    )
}

/// The section's second moments of mass about its tension centre in the rotor frame,
/// `[∫ρ(x − x_e)², ∫ρ(y − y_e)², ∫ρ(x − x_e)(y − y_e)]`: the rotary inertia of a section turning
/// in bending about the line that does not stretch (docs/model.md §11.2).
fn rotary_inertia(sec: &BeamSection, theta: f64) -> [f64; 3] {
    let [i_xi, i_eta, i_xe] = sec.inertia;
    let ([c_xi, c_eta], [e_xi, e_eta], m) = (sec.cg, sec.tension_centre, sec.mass);
    let j_xi = i_xi - 2.0 * m * c_xi * e_xi + m * e_xi * e_xi;
    let j_eta = i_eta - 2.0 * m * c_eta * e_eta + m * e_eta * e_eta;
    let j_xe = i_xe - m * (c_xi * e_eta + c_eta * e_xi) + m * e_xi * e_eta;
    let (sn, cs) = theta.sin_cos();
    [
        cs * cs * j_xi - 2.0 * cs * sn * j_xe + sn * sn * j_eta,
        sn * sn * j_xi + 2.0 * cs * sn * j_xe + cs * cs * j_eta,
        cs * sn * (j_xi - j_eta) + (cs * cs - sn * sn) * j_xe,
    ]
}

/// The propeller (tennis-racket) stiffness per Ω² on the twist (docs/model.md §11.2): the
/// quadratic part of `−½Ω²∫ρ y²` when the section turns by φ about the shear centre `(x_s, y_s)`,
/// `∫ρ y(y − y_s) − ∫ρ(x − x_s)²`. About the pitch axis (`x_s = y_s = 0`) it is
/// `(∫ρη² − ∫ρξ²) cos 2θ + 2∫ρξη sin 2θ`, which turns the chord toward the rotor plane.
fn propeller(inertia: [f64; 3], m: f64, cg: [f64; 2], shear: [f64; 2], theta: f64) -> f64 {
    let [i_xi, i_eta, i_xe] = inertia;
    let ([x_c, y_c], [x_s, y_s]) = (cg, shear);
    let about_pitch_axis = (i_eta - i_xi) * (2.0 * theta).cos() + 2.0 * i_xe * (2.0 * theta).sin();
    about_pitch_axis + m * (2.0 * x_c * x_s - x_s * x_s - y_c * y_s)
}

/// Add an element matrix into the global one at the element's free dofs (a clamped dof has
/// none; two local dofs may share one).
fn scatter<M: Storage>(global: &mut M, local: &ElementMatrix, dofs: &[Option<usize>; ELEMENT]) {
    for (row, gi) in local.iter().zip(dofs) {
        let Some(gi) = *gi else { continue };
        for (value, gj) in row.iter().zip(dofs) {
            let Some(gj) = *gj else { continue };
            global.add(gi, gj, *value);
        }
    }
}

/// The widest distance between two free dofs of one element: no entry of the matrices lies
/// further from the diagonal.
fn element_band(beam: Beam, elements: usize) -> usize {
    (0..elements)
        .map(|e| {
            let dofs = beam.element_dofs(e).into_iter().flatten();
            let (lo, hi) = dofs.fold((usize::MAX, 0), |(lo, hi), d| (lo.min(d), hi.max(d)));
            hi.saturating_sub(lo)
        })
        .max()
        .unwrap_or(0)
}

/// `a x` for an element matrix.
fn element_times(a: &ElementMatrix, x: &Row) -> Row {
    std::array::from_fn(|i| a[i].iter().zip(x).map(|(a, b)| a * b).sum())
}

/// Add an element load vector into the global one at the element's free dofs.
fn scatter_load(global: &mut DVector<f64>, local: &Row, dofs: &[Option<usize>; ELEMENT]) {
    for (value, d) in local.iter().zip(dofs) {
        if let Some(i) = d {
            global[*i] += value;
        }
    }
}

/// The motion of one point of a section: displacements along x (flap) and y (edge), their span
/// slopes, and the twist (docs/model.md §11.1 signs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationMotion {
    pub flap: f64,
    pub flap_slope: f64,
    pub edge: f64,
    pub edge_slope: f64,
    pub twist: f64,
}

/// How the motion of one point of the section at one span follows from the free dofs: rows
/// over the local dofs of the element holding it, for `[u, u', v, v', φ]` of that point.
#[derive(Debug, Clone, PartialEq)]
pub struct StationMap {
    /// Global free-dof index of each element dof (`None`: clamped at the root).
    dofs: [Option<usize>; ELEMENT],
    rows: [Row; 5],
}

impl StationMap {
    /// The point's motion for the free-dof vector `q` (a mode shape, a static solution).
    pub fn motion(&self, q: &DVector<f64>) -> StationMotion {
        let value = |row: &Row| -> f64 {
            self.dofs
                .iter()
                .zip(row)
                .filter_map(|(d, c)| d.map(|i| c * q[i]))
                .sum()
        };
        StationMotion {
            flap: value(&self.rows[0]),
            flap_slope: value(&self.rows[1]),
            edge: value(&self.rows[2]),
            edge_slope: value(&self.rows[3]),
            twist: value(&self.rows[4]),
        }
    }

    /// The generalised forces (length `dofs`) of a flap force, an edge force (N) and a twisting
    /// moment (N·m, toward feather) applied at the point: by virtual work, the transposed rows.
    /// A force at a point off the shear centre twists the section by the force times the offset.
    pub fn point_load(
        &self,
        dofs: usize,
        flap_force: f64,
        edge_force: f64,
        twist_moment: f64,
    ) -> DVector<f64> {
        let mut f = DVector::zeros(dofs);
        self.add_point_load(&mut f, flap_force, edge_force, twist_moment);
        f
    }

    /// [`StationMap::point_load`] added into `f`: a distributed load summed point by point.
    pub fn add_point_load(
        &self,
        f: &mut DVector<f64>,
        flap_force: f64,
        edge_force: f64,
        twist_moment: f64,
    ) {
        for (k, d) in self.dofs.iter().enumerate() {
            if let Some(i) = d {
                f[*i] += flap_force * self.rows[0][k]
                    + edge_force * self.rows[2][k]
                    + twist_moment * self.rows[4][k];
            }
        }
    }
}

/// Where a blade's elements lie and how its sections are turned, without the matrices: what
/// carries a mode shape from the shear centre to any span position (docs/model.md §11.2), kept
/// by a reduced basis that no longer holds the full matrices (§11.4).
#[derive(Debug, Clone, PartialEq)]
pub struct BladeGeometry {
    pub table: BladeTable,
    pub mesh: Mesh,
    /// Pitch the section frames are turned by (rad).
    pub pitch: f64,
    /// The beam the elements model: how the element's dofs number among the free ones.
    pub beam: Beam,
}

impl BladeMatrices {
    /// The same matrices as their bands.
    pub fn banded(self) -> BladeMatrices<SymmetricBand> {
        let band = self.band();
        BladeMatrices {
            mass: SymmetricBand::from_dense(&self.mass, band),
            k0: SymmetricBand::from_dense(&self.k0, band),
            k_omega: SymmetricBand::from_dense(&self.k_omega, band),
            table: self.table,
            mesh: self.mesh,
            pitch: self.pitch,
            beam: self.beam,
            curve_loads: self.curve_loads,
            rigid_loads: self.rigid_loads,
            rigid_mass: self.rigid_mass,
        }
    }
}

impl<M> BladeMatrices<M> {
    /// The half-bandwidth of the matrices: the widest distance between two dofs of one element,
    /// which no entry lies beyond (from the mesh, without a scan of the dense matrices).
    pub fn band(&self) -> usize {
        element_band(self.beam, self.mesh.elements())
    }

    /// The load per Ω² that rotation puts on the curved blade (docs/model.md §11.9): the
    /// centrifugal tension on the slopes of the curve (pulling a prebent blade toward the rotor
    /// plane) and the in-plane pull on a swept one, as a generalised force.
    pub fn centrifugal_load(&self) -> DVector<f64> {
        let [a, b] = &self.curve_loads;
        a * self.pitch.cos() + b * self.pitch.sin()
    }

    /// The table, mesh and pitch of these matrices.
    pub fn geometry(&self) -> BladeGeometry {
        BladeGeometry {
            table: self.table.clone(),
            mesh: self.mesh.clone(),
            pitch: self.pitch,
            beam: self.beam,
        }
    }

    /// [`BladeGeometry::reference_axis_at`] of these matrices' blade.
    pub fn reference_axis_at(&self, z: f64) -> Result<StationMap> {
        self.geometry().reference_axis_at(z)
    }

    /// [`BladeGeometry::shear_centre_at`] of these matrices' blade.
    pub fn shear_centre_at(&self, z: f64) -> Result<StationMap> {
        self.geometry().shear_centre_at(z)
    }
}

impl BladeGeometry {
    /// The motion of the reference (pitch) axis at span `z`, where the aerodynamic loads attach
    /// (docs/model.md §11.2): the section turns about the shear centre `(x_s, y_s)`, so the
    /// reference axis moves by `u + y_s φ`, `v − x_s φ` (slopes by differentiation, the offsets
    /// changing along the span too).
    pub fn reference_axis_at(&self, z: f64) -> Result<StationMap> {
        let (element, s, h) = self.locate(z)?;
        let sec = self.table.at(z);
        let theta = sec.twist + self.pitch;
        let [x_s, y_s] = to_rotor(sec.shear_centre, theta);
        let rate = self.table.rate_at(z);
        let [x_s_rate, y_s_rate] =
            to_rotor_rate(sec.shear_centre, rate.shear_centre, theta, rate.twist);
        let sh = Shapes::at(s, h);
        let rows = [
            mix(&sh.u, 1.0, &sh.phi, y_s),
            mix(&mix(&sh.du, 1.0, &sh.dphi, y_s), 1.0, &sh.phi, y_s_rate),
            mix(&sh.v, 1.0, &sh.phi, -x_s),
            mix(&mix(&sh.dv, 1.0, &sh.dphi, -x_s), 1.0, &sh.phi, -x_s_rate),
            sh.phi,
        ];
        Ok(self.station_map(element, rows))
    }

    /// The motion of the shear centre at span `z`: the dofs themselves, interpolated by the shape
    /// functions (docs/model.md §11.3).
    pub fn shear_centre_at(&self, z: f64) -> Result<StationMap> {
        let (element, s, h) = self.locate(z)?;
        let sh = Shapes::at(s, h);
        Ok(self.station_map(element, [sh.u, sh.du, sh.v, sh.dv, sh.phi]))
    }

    /// The element holding span `z`, the local coordinate in it and its length.
    fn locate(&self, z: f64) -> Result<(usize, f64, f64)> {
        let nodes = &self.mesh.nodes;
        let (root, tip) = (nodes[0], nodes[nodes.len() - 1]);
        if !(z >= root && z <= tip) {
            return Err(Error::Invalid {
                origin: self.table.origin.clone(),
                message: format!("span {z} m is not on the blade ({root} m to {tip} m)"),
            });
        }
        let e = nodes.partition_point(|&x| x <= z).clamp(1, nodes.len() - 1) - 1;
        let h = nodes[e + 1] - nodes[e];
        Ok((e, (z - nodes[e]) / h, h))
    }

    fn station_map(&self, element: usize, rows: [Row; 5]) -> StationMap {
        StationMap {
            dofs: self.beam.element_dofs(element),
            rows,
        }
    }
}
