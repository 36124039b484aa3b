//! A tower given as a beam (docs/model.md §13.7): a HAWC2 tower body's sections on the blade's
//! finite elements ([`crate::physics::blade::fem`]), not rotating, clamped at its base, with
//! torsion. Its coordinates are its own lowest modes, computed with the rigid masses on its top
//! (yaw bearing, nacelle with its rotary inertia, hub) as a modes program computes ElastoDyn's
//! shapes: the first two fore–aft, the first two side–side and the first torsion. Plain inputs;
//! out: a [`Tower`] as the ElastoDyn tower's.
//!
//! Frame: the elements' flap direction ξ is the tower's fore–aft (x, downwind), their edge
//! direction η its side–side (y), their twist its torsion about z (up). The top moves by
//! `u_x = u`, `u_y = v` and turns with its section, `θ_y = u' − γ_u`, `θ_x = −(v' − γ_v)`,
//! `θ_z = φ` (`γ` the shear strains of a shear-deformable tower).

use super::tower::{leaning, Apex, Plane, Tower, TowerMode, TowerTop, APEX_MOTIONS};
use crate::error::{Error, Result};
use crate::physics::blade::fem::{assemble, Mesh};
use crate::physics::blade::modal::StiffnessFactors;
use crate::physics::blade::BladeTable;
use crate::physics::structure::{Family, MotionRows};
use nalgebra::{DMatrix, DVector};

/// The beam tower's plain inputs.
#[derive(Debug, Clone, PartialEq)]
pub struct BeamTowerInputs {
    /// Its sections from the base (`z = 0`, `hub_radius` 0) to the top, in the elements' frame
    /// (ξ fore–aft, η side–side).
    pub table: BladeTable,
    /// Stiffness-proportional damping (HAWC2's `damping_posdef` kx, ky, kz as a blade's).
    pub damping: StiffnessFactors,
    /// Elements along it at the least ([`TOWER_ELEMENTS`] in the model).
    pub elements: usize,
}

/// Elements along the tower at the least: on the IEA 15MW its modes within 1e-4 of 160
/// elements' (docs/model.md §13.7).
pub const TOWER_ELEMENTS: usize = 40;

/// Its modes kept per bending plane.
const BENDING_MODES: usize = 2;

impl Tower {
    /// The tower `inputs` describes carrying `top`.
    pub fn from_beam(inputs: &BeamTowerInputs, top: &TowerTop) -> Result<Tower> {
        super::tower::check_top(top)?;
        let table = &inputs.table;
        let mesh = tower_mesh(table, inputs.elements.max(1));
        let fe = assemble(table, &mesh, 0.0)?;
        let n = fe.mass.nrows();
        let length = mesh.nodes[mesh.elements()];
        // The top's motion per free dof, in [`Apex`] rows: the nacelle turns with the top
        // section (`u' − γ_u`, `v' − γ_v`), not with the centreline's slope.
        let [u, du, gu, v, dv, gv, phi_top] = fe.beam.node_dofs(mesh.elements());
        let mut top_motion = DMatrix::zeros(APEX_MOTIONS, n);
        let mut put = |row: Apex, dof: Option<usize>, value: f64| {
            if let Some(i) = dof {
                top_motion[(row as usize, i)] += value;
            }
        };
        put(Apex::X, u, 1.0);
        put(Apex::Y, v, 1.0);
        put(Apex::Tilt, du, 1.0);
        put(Apex::Tilt, gu, -1.0);
        put(Apex::Roll, dv, -1.0);
        put(Apex::Roll, gv, 1.0);
        put(Apex::Yaw, phi_top, 1.0);
        let loaded = &fe.mass + Tower::top_inertia(&top_motion, top);
        let (omega2, shapes) = lowest_modes(&loaded, &fe.k0)?;
        let layout = fe.beam.layout();
        let picked = pick_modes(&shapes, &loaded, |i| layout.family_of(i), &omega2, table)?;
        let modes: Vec<TowerMode> = picked.iter().map(|p| p.1).collect();
        let phi = DMatrix::from_columns(
            &picked
                .iter()
                .map(|p| shapes.column(p.0).into_owned())
                .collect::<Vec<_>>(),
        );
        // `Φᵀ K Φ` is `ω²` on the loaded tower's mass-normalised modes; formed from `K₀` it
        // would lose every digit to the shear stiffness (10²³ against 10¹ here). So is the
        // stiffness-proportional damping `β ω²`, `β` the factor of the mode's plane (each mode
        // lies in one plane of a straight tower).
        let factors = inputs.damping;
        let stiffness = DMatrix::from_diagonal(&DVector::from_iterator(
            picked.len(),
            picked.iter().map(|p| omega2[p.0]),
        ));
        let damping = DMatrix::from_diagonal(&DVector::from_iterator(
            picked.len(),
            picked.iter().map(|p| {
                let beta = match p.1.plane() {
                    Plane::ForeAft => factors.flap,
                    Plane::SideSide => factors.edge,
                    Plane::Torsion => factors.torsion,
                };
                beta * omega2[p.0]
            }),
        ));
        let own_mass = phi.transpose() * &fe.mass * &phi;
        let density: Vec<(f64, f64)> = table.sections.iter().map(|s| (s.z, s.mass)).collect();
        let columns = phi.ncols();
        let slopes = |z: f64| {
            let mut d = DMatrix::zeros(2, columns);
            if let Ok(map) = fe.reference_axis_at(z.min(length)) {
                for j in 0..columns {
                    let m = map.motion(&phi.column(j).into_owned());
                    d[(0, j)] = m.flap_slope;
                    d[(1, j)] = m.edge_slope;
                }
            }
            d
        };
        let (sag, own_weight) = leaning(&density, &mesh.nodes, columns, &slopes);
        let profile = mesh
            .nodes
            .iter()
            .map(|&z| {
                let mut rows = MotionRows::zeros(columns);
                let map = fe.reference_axis_at(z)?;
                for j in 0..columns {
                    let m = map.motion(&phi.column(j).into_owned());
                    rows.flap[j] = m.flap;
                    rows.edge[j] = m.edge;
                    rows.twist[j] = m.twist;
                }
                Ok((z, rows))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Tower::on_top(
            modes,
            own_mass,
            stiffness,
            damping,
            own_weight,
            sag,
            &(top_motion * &phi),
            profile,
            top,
        ))
    }
}

/// Nodes at the table's stations but where two lie within a thousandth of the tower's length
/// (a step in wall thickness written as two stations a millimetre apart: an element that short
/// would make the stiffness 10¹⁰ times stiffer than the modes it carries), elements halved
/// (longest first) up to `elements`.
fn tower_mesh(table: &BladeTable, elements: usize) -> Mesh {
    let length = table.sections.last().map_or(0.0, |s| s.z);
    let mut nodes: Vec<f64> = Vec::new();
    for s in &table.sections {
        match nodes.last() {
            Some(&last) if s.z - last < 1e-3 * length => {}
            _ => nodes.push(s.z),
        }
    }
    if let Some(last) = nodes.last_mut() {
        *last = length;
    }
    while nodes.len() - 1 < elements {
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

/// From the loaded tower's modes (columns of `shapes`, ascending, `ω²` in `omega2`), the
/// first [`BENDING_MODES`] of each bending plane and the first torsion mode, in the order
/// fore–aft, side–side, torsion: each mode's plane is the family (`family_of` a free dof) that
/// holds most of its kinetic energy.
fn pick_modes(
    shapes: &DMatrix<f64>,
    mass: &DMatrix<f64>,
    family_of: impl Fn(usize) -> usize,
    omega2: &DVector<f64>,
    table: &BladeTable,
) -> Result<Vec<(usize, TowerMode)>> {
    let mut found: [Vec<usize>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    let wanted = [BENDING_MODES, BENDING_MODES, 1];
    for j in 0..shapes.ncols() {
        let phi = shapes.column(j);
        let m_phi = mass * phi;
        let mut energy = [0.0; 3];
        for i in 0..phi.len() {
            energy[family_of(i)] += phi[i] * m_phi[i];
        }
        let family = (0..3)
            .max_by(|&a, &b| energy[a].total_cmp(&energy[b]))
            .unwrap_or(0);
        if found[family].len() < wanted[family] && omega2[j] > 0.0 {
            found[family].push(j);
        }
    }
    let planes = [Plane::ForeAft, Plane::SideSide, Plane::Torsion];
    let families = [Family::Flap, Family::Edge, Family::Torsion];
    let mut picked = Vec::new();
    for ((plane, family), (columns, count)) in planes
        .into_iter()
        .zip(families)
        .zip(found.iter().zip(wanted))
    {
        if columns.len() < count {
            return Err(Error::Invalid {
                origin: table.origin.clone(),
                message: format!(
                    "the tower has {} {} modes, the model needs {count}",
                    columns.len(),
                    family.name()
                ),
            });
        }
        picked.extend(
            columns
                .iter()
                .enumerate()
                .map(|(k, &j)| (j, TowerMode::named(plane, k + 1))),
        );
    }
    Ok(picked)
}

/// The undamped modes of mass `m` and stiffness `k`, ascending: `ω²` and the mass-normalised
/// shapes. Solved in the flexibility form (`L⁻¹ M L⁻ᵀ`, `K = L Lᵀ`), whose largest
/// eigenvalues are the lowest modes, accurate relative to themselves however stiff the beam is
/// in shear.
fn lowest_modes(m: &DMatrix<f64>, k: &DMatrix<f64>) -> Result<(DVector<f64>, DMatrix<f64>)> {
    let l = k
        .clone()
        .cholesky()
        .ok_or_else(|| Error::numerical("the tower's stiffness is not positive definite"))?
        .l();
    let l_inv = l
        .solve_lower_triangular(&DMatrix::identity(k.nrows(), k.ncols()))
        .ok_or_else(|| Error::numerical("the tower's stiffness is singular"))?;
    let b = &l_inv * m * l_inv.transpose();
    let eig = ((&b + b.transpose()) * 0.5).symmetric_eigen();
    let mut order: Vec<usize> = (0..b.nrows())
        .filter(|&i| eig.eigenvalues[i] > 0.0)
        .collect();
    order.sort_by(|&i, &j| eig.eigenvalues[j].total_cmp(&eig.eigenvalues[i]));
    let omega2 =
        DVector::from_iterator(order.len(), order.iter().map(|&i| 1.0 / eig.eigenvalues[i]));
    let mut shapes = l_inv.transpose() * eig.eigenvectors.select_columns(&order);
    for mut col in shapes.column_iter_mut() {
        let modal_mass = (col.transpose() * m * &col)[(0, 0)];
        col /= modal_mass.sqrt();
    }
    Ok((omega2, shapes))
}
