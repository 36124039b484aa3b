//! The rotating structural modes of a tabulated blade (docs/model.md §11.4), from a reduced
//! basis: the assembled `M`, `K₀`, `K_Ω` are projected once onto the lowest modes at the
//! reference rotor speeds, so the modes at any rotor speed are a small dense eigenproblem
//! (microseconds), not a re-assembly or a full-size solve. Each mode carries its family, its
//! modal damping ratio (docs/model.md §11.4) and its shape on the element dofs, which
//! [`BladeMatrices::reference_axis_at`] evaluates at any span position.

use super::fem::{scaled_stiffness, BladeGeometry, BladeMatrices, Mesh, NodeLayout};
use super::BladeTable;
use crate::error::{Error, Result};
use crate::numeric::banded::SymmetricBand;
use crate::numeric::cholesky::symmetrised;
use crate::numeric::lanczos::lowest_modes;
use crate::numeric::products::tr_mul;
use crate::physics::basis::gauss_rule;
use nalgebra::{DMatrix, DVector, SymmetricEigen};
use std::sync::Arc;

/// Iteration cap of the symmetric eigensolver (nalgebra's implicit QR): far beyond what these
/// sizes need, so reaching it means broken input, reported as an error.
const MAX_SWEEPS: usize = 10_000;

/// A basis vector whose M-norm falls below this fraction of its norm before
/// orthogonalisation repeats earlier ones and is dropped.
const DEPENDENT: f64 = 1e-8;

pub use crate::physics::structure::Family;

/// One natural mode of the rotating blade.
#[derive(Debug, Clone)]
pub struct BladeMode {
    pub frequency_hz: f64,
    /// Shares of the mode's kinetic energy in flap, edge and twist motion: the diagonal blocks
    /// `qᵤᵀMᵤᵤqᵤ`, `qᵥᵀMᵥᵥqᵥ`, `q_φᵀM_φφq_φ` over their sum (the cross terms, from the centre
    /// of mass offset, left out so that the shares add up to 1).
    pub shares: [f64; 3],
    /// Modal damping ratio ζ: `φᵀCφ / 2ω` of the structural damping matrix the basis carries
    /// (its projection on the pitch-range basis, [`super::pitch_range`]), 0 without one
    /// (docs/model.md §11.4).
    pub damping_ratio: f64,
    /// Free-dof vector (`[u, u', v, v', φ]` per node after the root), M-normalised.
    pub shape: DVector<f64>,
    /// The same in its blade's reduced coordinates, where the reduced mass is the identity
    /// (`shape = Φ·coordinates`, or `Φ·L⁻ᵀ·coordinates` on a pitch-range basis).
    pub coordinates: DVector<f64>,
}

impl BladeMode {
    /// The family with the largest share.
    pub fn family(&self) -> Family {
        Family::of(self.shares)
    }
}

/// Stiffness-proportional damping factors per strain of the section (s): the damping matrix is
/// the elastic stiffness `K₀` assembled with each term scaled by its factor (BeamDyn's `mu`,
/// docs/model.md §11.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessFactors {
    /// On the shear stiffnesses along ξ and η (BeamDyn `mu1`, `mu2`), for a shear-deformable
    /// blade.
    pub shear: [f64; 2],
    /// On the flap bending stiffness `EI_ξ` (BeamDyn `mu5`).
    pub flap: f64,
    /// On the edge bending stiffness `EI_η` (BeamDyn `mu4`).
    pub edge: f64,
    /// On the torsional stiffness `GJ` (BeamDyn `mu6`).
    pub torsion: f64,
}

/// The damping matrix `C` of stiffness-proportional damping: `K₀` of `table` on `mesh` at `pitch`
/// with every stiffness scaled by its factor, a coupling term by the mean of its two strains'
/// factors (the symmetric part of BeamDyn's `μK`, which is what a mode's `φᵀCφ` sees). The
/// centrifugal stiffness `K_Ω` is not damped: it is a load, not a material.
pub fn stiffness_damping(
    table: &BladeTable,
    mesh: &Mesh,
    pitch: f64,
    f: StiffnessFactors,
) -> Result<SymmetricBand> {
    let [shear_xi, shear_eta] = f.shear;
    scaled_stiffness(
        table,
        mesh,
        pitch,
        [shear_xi, shear_eta, f.flap, f.edge, f.torsion],
    )
}

/// A blade's structure reduced onto a basis of its modes.
#[derive(Debug, Clone)]
pub struct ModalBlade {
    /// Table, mesh and pitch: what carries a shape to the reference axis.
    pub geometry: BladeGeometry,
    /// Basis Φ (dofs × b): M-orthonormal, or, from a pitch-range basis (docs/model.md §11.4),
    /// any basis with the Cholesky factor of its reduced mass in `mass_factor`.
    basis: Arc<DMatrix<f64>>,
    /// `L` of `ΦᵀMΦ = LLᵀ` when Φ is not M-orthonormal: every reduced matrix below is then
    /// `L⁻¹(Φᵀ·Φ)L⁻ᵀ`, and a mode's basis coordinates are `L⁻ᵀ y` (none: `L = I`).
    mass_factor: Option<DMatrix<f64>>,
    reduced_k0: DMatrix<f64>,
    reduced_k_omega: DMatrix<f64>,
    /// `ΦᵀCΦ` of the structural damping matrix, when there is one.
    reduced_damping: Option<DMatrix<f64>>,
    /// `Φᵀ M_b Φ` per family ([`reduced_family_mass`]).
    reduced_family: [DMatrix<f64>; 3],
    /// `Φᵀ f` of the centrifugal load per Ω² on a curved blade
    /// ([`BladeMatrices::centrifugal_load`]), in the coordinates where the reduced mass is the
    /// identity (`L⁻¹Φᵀ f`); zero for a straight blade.
    reduced_centrifugal_load: DVector<f64>,
    /// `Φᵀ M r` of the rigid motions ([`BladeMatrices::rigid_loads`]), in the same
    /// coordinates, and `rᵢᵀ M rⱼ`.
    reduced_rigid: DMatrix<f64>,
    rigid_mass: DMatrix<f64>,
}

/// The blade at rest under a torque spread evenly along its span (`K₀⁻¹ f`): the static
/// response the lowest modes represent worst, since a distributed torque excites every torsion
/// mode alike (docs/model.md §11.4, §12.6). With it in the basis, the static correction of the
/// left-out modes reaches the twist a converged basis gives.
fn static_twist(matrices: &BladeMatrices<SymmetricBand>) -> Result<DVector<f64>> {
    let n = matrices.mass.size();
    let mut twist = DVector::zeros(n);
    let rule = gauss_rule(2);
    for element in matrices.mesh.nodes.windows(2) {
        let h = element[1] - element[0];
        for (x, w) in rule.0.iter().zip(&rule.1) {
            matrices
                .reference_axis_at(element[0] + (1.0 + x) * h / 2.0)?
                .add_point_load(&mut twist, 0.0, 0.0, w * h / 2.0);
        }
    }
    let stiffness = matrices.k0.cholesky().ok_or_else(|| {
        Error::numerical(format!(
            "{}: the blade's stiffness at rest is not positive definite",
            matrices.table.origin
        ))
    })?;
    stiffness.solve_in_place(twist.as_mut_slice());
    Ok(twist)
}

/// `Φᵀ A Φ` of a banded matrix on the basis `Φ`, symmetrised against round-off.
pub fn projected(a: &SymmetricBand, basis: &DMatrix<f64>) -> DMatrix<f64> {
    symmetrised(tr_mul(basis, &a.mul(basis)))
}

/// The M-orthonormal basis of the lowest `per_speed` modes at each of `reference_speeds`
/// (rad/s), each speed's solve started from the one before's modes, and the blade's
/// [`static_twist`] (docs/model.md §11.4).
pub fn lowest_modes_basis(
    matrices: &BladeMatrices<SymmetricBand>,
    reference_speeds: &[f64],
    per_speed: usize,
) -> Result<DMatrix<f64>> {
    let n = matrices.mass.size();
    let per_speed = per_speed.min(n);
    let (mass, k0, k_omega) = (&matrices.mass, &matrices.k0, &matrices.k_omega);
    let mut columns: Vec<DVector<f64>> = Vec::new();
    let mut previous = DMatrix::zeros(n, 0);
    for &omega in reference_speeds {
        let k = k0.plus(omega * omega, k_omega);
        let modes = lowest_modes(&k, mass, per_speed, &previous).map_err(|e| {
            e.at(format!(
                "{}: blade modes at Ω = {omega} rad/s",
                matrices.table.origin
            ))
        })?;
        columns.extend(modes.vectors.column_iter().map(|c| c.into_owned()));
        previous = modes.vectors;
    }
    columns.push(static_twist(matrices)?);
    let basis = m_orthonormal(mass, columns);
    if basis.ncols() == 0 {
        return Err(Error::numerical(format!(
            "{}: blade modal basis is empty",
            matrices.table.origin
        )));
    }
    Ok(basis)
}

impl ModalBlade {
    /// Reduce onto the lowest `per_speed` modes at each of `reference_speeds` (rad/s), made
    /// M-orthonormal together: modes at rotor speeds between and near the references are then
    /// reproduced closely (docs/model.md §11.4 shows the convergence). The modes at each speed
    /// come from the banded pencil by shift-invert block Lanczos ([`lowest_modes`], residual
    /// checked), each speed started from the previous one's modes; an error names the blade.
    pub fn new(
        matrices: BladeMatrices,
        reference_speeds: &[f64],
        per_speed: usize,
    ) -> Result<ModalBlade> {
        Self::from_bands(matrices.banded(), reference_speeds, per_speed)
    }

    /// [`ModalBlade::new`] from the matrices' bands ([`super::fem::assemble_banded`]).
    pub fn from_bands(
        matrices: BladeMatrices<SymmetricBand>,
        reference_speeds: &[f64],
        per_speed: usize,
    ) -> Result<ModalBlade> {
        let basis = lowest_modes_basis(&matrices, reference_speeds, per_speed)?;
        let (mass, k0, k_omega) = (&matrices.mass, &matrices.k0, &matrices.k_omega);
        let reduced_k0 = projected(k0, &basis);
        let reduced_k_omega = projected(k_omega, &basis);
        let reduced_family = reduced_family_mass(mass, &basis, &matrices.beam.layout());
        let reduced_centrifugal_load = basis.tr_mul(&matrices.centrifugal_load());
        Ok(ModalBlade {
            reduced_centrifugal_load,
            reduced_rigid: basis.tr_mul(&matrices.rigid_loads),
            rigid_mass: matrices.rigid_mass.clone(),
            geometry: matrices.geometry(),
            basis: Arc::new(basis),
            mass_factor: None,
            reduced_k0,
            reduced_k_omega,
            reduced_damping: None,
            reduced_family,
        })
    }

    /// The blade on a basis `basis` that need not be M-orthonormal, from its projections
    /// `reduced` (docs/model.md §11.4, the pitch-range basis): the reduced mass is factored
    /// once, and every other projection turned into the coordinates where it is the identity.
    pub fn from_projections(
        geometry: BladeGeometry,
        basis: Arc<DMatrix<f64>>,
        reduced: &Projections,
    ) -> Result<ModalBlade> {
        let singular = || {
            Error::numerical(format!(
                "{}: the reduced blade mass is not positive definite",
                geometry.table.origin
            ))
        };
        let l = reduced
            .mass
            .clone()
            .cholesky()
            .ok_or_else(singular)?
            .unpack();
        // L⁻¹ once, then each projection turned by two matrix products.
        let n = l.nrows();
        let l_inv = l
            .solve_lower_triangular(&DMatrix::identity(n, n))
            .ok_or_else(singular)?;
        let reduce = |a: &DMatrix<f64>| symmetrised(&l_inv * a * l_inv.transpose());
        let reduced_k0 = reduce(&reduced.k0);
        let reduced_family = reduced.family.each_ref().map(reduce);
        Ok(ModalBlade {
            reduced_centrifugal_load: &l_inv * &reduced.centrifugal_load,
            reduced_rigid: &l_inv * &reduced.rigid,
            rigid_mass: reduced.rigid_mass.clone(),
            reduced_k_omega: reduce(&reduced.k_omega),
            reduced_damping: reduced.damping.as_ref().map(reduce),
            reduced_k0,
            reduced_family,
            geometry,
            basis,
            mass_factor: Some(l),
        })
    }

    /// The basis Φ (dofs × b).
    pub fn basis(&self) -> &DMatrix<f64> {
        &self.basis
    }

    /// Size of the reduced basis.
    pub fn basis_size(&self) -> usize {
        self.basis.ncols()
    }

    /// The lowest `count` modes at rotor speed `omega` (rad/s), ascending in frequency.
    pub fn modes(&self, omega: f64, count: usize) -> Result<Vec<BladeMode>> {
        let k = &self.reduced_k0 + &self.reduced_k_omega * (omega * omega);
        let eig = SymmetricEigen::try_new(k, f64::EPSILON, MAX_SWEEPS).ok_or_else(|| {
            Error::numerical("blade modes: symmetric eigensolver did not converge")
        })?;
        let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        order.truncate(count);
        if let Some(&j) = order
            .iter()
            .find(|&&j| !(eig.eigenvalues[j].is_finite() && eig.eigenvalues[j] > 0.0))
        {
            return Err(Error::numerical(format!(
                "blade modes: ω² = {:e} (rad/s)² at Ω = {omega} rad/s; the rotating blade has \
                 no stiffness against this shape (rotor speed too high?)",
                eig.eigenvalues[j]
            )));
        }
        // All shapes in one product (Φ·Y): a matrix product, far quicker than one per mode.
        let y = eig.eigenvectors.select_columns(&order);
        let in_basis = match &self.mass_factor {
            None => y.clone(),
            Some(l) => l
                .tr_solve_lower_triangular(&y)
                .ok_or_else(|| Error::numerical("blade modes: singular reduced mass factor"))?,
        };
        let shapes = &*self.basis * in_basis;
        Ok(order
            .iter()
            .enumerate()
            .map(|(c, &j)| {
                let omega_k = eig.eigenvalues[j].sqrt();
                let coordinates = y.column(c).into_owned();
                // ζ = φᵀCφ / 2ω for an M-normalised φ = Φy (Φ M-orthonormal, |y| = 1).
                let damping_ratio = self.reduced_damping.as_ref().map_or(0.0, |d| {
                    coordinates.dot(&(d * &coordinates)) / (2.0 * omega_k)
                });
                BladeMode {
                    frequency_hz: omega_k / std::f64::consts::TAU,
                    shares: shares_of(&coordinates, &self.reduced_family),
                    damping_ratio,
                    shape: shapes.column(c).into_owned(),
                    coordinates,
                }
            })
            .collect())
    }

    /// The kinetic energies of the flap, edge and twist blocks of `M` between any two modes,
    /// `[Yᵀ Φᵀ M_b Φ Y]` for `b` = flap, edge, twist, from the modes' basis coordinates: the
    /// shares of any combination of `modes` (docs/model.md §11.4), with no product over the dofs.
    pub fn family_energy(&self, modes: &[BladeMode]) -> [DMatrix<f64>; 3] {
        let y = basis_coordinates(modes);
        self.reduced_family.clone().map(|e| y.tr_mul(&(e * &y)))
    }

    /// The centrifugal load per Ω² on `modes` (docs/model.md §11.9): each mode's generalised
    /// force `φᵀ f` from the pull on the curved axis, zero for a straight blade.
    pub fn centrifugal_load(&self, modes: &[BladeMode]) -> DVector<f64> {
        DVector::from_iterator(
            modes.len(),
            modes
                .iter()
                .map(|m| m.coordinates.dot(&self.reduced_centrifugal_load)),
        )
    }
}

impl ModalBlade {
    /// Each mode's share of the blade's rigid motions with the hub, `φᵀ M r` (modes × 4, the
    /// columns [`Rigid`](super::fem::Rigid)'s; docs/model.md §13.2, §13.6): the coupling of
    /// its coordinate with the hub's motion through the mass.
    pub fn rigid_participation(&self, modes: &[BladeMode]) -> DMatrix<f64> {
        basis_coordinates(modes).tr_mul(&self.reduced_rigid)
    }

    /// `rᵢᵀ M rⱼ` of the blade's rigid motions (4 × 4).
    pub fn rigid_mass(&self) -> &DMatrix<f64> {
        &self.rigid_mass
    }

    /// `K_Ω` (per Ω²) between `modes`: how their stiffness changes with the rotor speed.
    pub fn centrifugal_stiffness(&self, modes: &[BladeMode]) -> DMatrix<f64> {
        let y = basis_coordinates(modes);
        y.tr_mul(&(&self.reduced_k_omega * &y))
    }
}

/// The modes' basis coordinates as the columns of one matrix `Y`.
fn basis_coordinates(modes: &[BladeMode]) -> DMatrix<f64> {
    DMatrix::from_columns(
        &modes
            .iter()
            .map(|m| m.coordinates.clone())
            .collect::<Vec<_>>(),
    )
}

/// The projections `ΦᵀAΦ` of a blade's matrices on a basis Φ (b × b each).
#[derive(Debug, Clone)]
pub struct Projections {
    pub mass: DMatrix<f64>,
    pub k0: DMatrix<f64>,
    pub k_omega: DMatrix<f64>,
    pub damping: Option<DMatrix<f64>>,
    /// [`reduced_family_mass`]: flap, edge, twist.
    pub family: [DMatrix<f64>; 3],
    /// `Φᵀ f` of [`BladeMatrices::centrifugal_load`] (b).
    pub centrifugal_load: DVector<f64>,
    /// `Φᵀ M r` and `rᵢᵀ M rⱼ` of [`BladeMatrices::rigid_loads`].
    pub rigid: DMatrix<f64>,
    pub rigid_mass: DMatrix<f64>,
}

/// `Φᵀ M_b Φ` for the flap, edge and twist blocks `b` of the mass matrix (the diagonal blocks of
/// each group of dofs, the cross terms from the centre of mass offset left out): O(n·band·b),
/// once per basis.
pub fn reduced_family_mass(
    mass: &SymmetricBand,
    basis: &DMatrix<f64>,
    layout: &NodeLayout,
) -> [DMatrix<f64>; 3] {
    let group = |i: usize| layout.family_of(i);
    let (n, b) = (basis.nrows(), basis.ncols());
    // `M_b Φ` row by row: each band entry within a family adds a row of Φ to a row of the
    // product, rows made contiguous by transposing.
    let phi_t = basis.transpose();
    let rows = phi_t.as_slice();
    let mut products_t = [(); 3].map(|_| DMatrix::zeros(b, n));
    for i in 0..n {
        let g = group(i);
        let lo = i.saturating_sub(mass.band());
        let hi = (i + mass.band() + 1).min(n);
        let out = &mut products_t[g].as_mut_slice()[i * b..(i + 1) * b];
        for j in (lo..hi).filter(|&j| group(j) == g) {
            let mij = mass.get(i, j);
            for (p, x) in out.iter_mut().zip(&rows[j * b..(j + 1) * b]) {
                *p += mij * x;
            }
        }
    }
    let products = products_t.map(|p| p.transpose());
    products.map(|mb| symmetrised(tr_mul(basis, &mb)))
}

/// Shares of `[flap, edge, twist]` from basis coordinates `y` and [`reduced_family_mass`].
fn shares_of(y: &DVector<f64>, family: &[DMatrix<f64>; 3]) -> [f64; 3] {
    let e = family.clone().map(|f| y.dot(&(f * y)).max(0.0));
    let total: f64 = e.iter().sum();
    if total > 0.0 {
        e.map(|x| x / total)
    } else {
        e
    }
}

/// Modified Gram–Schmidt in the M inner product, twice for round-off; dependent vectors dropped.
/// Each kept vector's `M k` is stored, so a projection is a dot product, not a product with M.
pub fn m_orthonormal(mass: &SymmetricBand, columns: Vec<DVector<f64>>) -> DMatrix<f64> {
    let n = mass.size();
    let mut kept: Vec<(DVector<f64>, DVector<f64>)> = Vec::new();
    let mut mc = DVector::zeros(n);
    for mut c in columns {
        mass.mul_into(c.as_slice(), mc.as_mut_slice());
        let start = c.dot(&mc).sqrt();
        for _ in 0..2 {
            for (k, mk) in &kept {
                let proj = mk.dot(&c);
                c.axpy(-proj, k, 1.0);
            }
        }
        mass.mul_into(c.as_slice(), mc.as_mut_slice());
        let norm = c.dot(&mc).sqrt();
        if norm > DEPENDENT * start && norm.is_finite() {
            kept.push((c / norm, &mc / norm));
        }
    }
    if kept.is_empty() {
        return DMatrix::zeros(n, 0);
    }
    DMatrix::from_columns(&kept.into_iter().map(|(k, _)| k).collect::<Vec<_>>())
}
