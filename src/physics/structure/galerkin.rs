//! The blade structure in Galerkin coordinates `q = [q_φ (N); q_u (N)]` (docs/model.md §3–§4): mass,
//! elastic and centrifugal stiffness, stiffness-proportional damping, natural modes.
//!
//! The section is uniform along the span, so every integral is a section constant times a pure
//! basis integral; the only span-varying coefficient is the centrifugal tension `F_c(x)`. All
//! integrals use one Gauss–Legendre rule sized for the basis ([`Basis::quadrature`]), on the unit
//! span, once per N: a blade's matrices are those integrals scaled by its length and section.

use crate::error::{Error, Result};
use crate::numeric::cholesky::cholesky_reduce;
use crate::numeric::faer_evd::real_evd;
use crate::physics::basis::{torsion_wavenumber, Basis, BendingMode};
use crate::physics::section::SectionProps;

use super::{MotionRows, NaturalMode, Shares, Structure};
use nalgebra::{Complex, DMatrix, DVector};
use std::sync::{Arc, OnceLock};

/// Structural matrices of one blade at one rotor speed (docs/model.md §3–§4).
#[derive(Debug, Clone)]
pub struct StructuralModel {
    pub n: usize,
    pub basis: Basis,
    pub section: SectionProps,
    /// M (2N×2N), symmetric.
    pub mass: DMatrix<f64>,
    /// K_e: symmetric in the weak form; the strong form adds the tip term `C23 U(L) Φ''(L)ᵀ` to
    /// the flap–twist block.
    pub elastic: DMatrix<f64>,
    /// K_c, symmetric.
    pub centrifugal: DMatrix<f64>,
    /// C_s = a_s K_e with a_s = η1/ω1 (docs/model.md §4, paper Eq. 9).
    pub damping: DMatrix<f64>,
    /// ω1 (rad/s), lowest natural frequency of (M, K_e + K_c).
    pub omega1: f64,
    /// r_hub (m).
    pub hub_radius: f64,
    /// The natural modes, found on first use: every analysis of the structure names its roots
    /// after them, and a sweep that keeps the structure asks for them at every point.
    natural: OnceLock<Vec<NaturalMode>>,
}

/// The form of the structural equations (docs/model.md §4): the weak (Galerkin, symmetric)
/// form, or the paper's strong form with its tip term.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Form {
    Weak,
    Strong,
}

/// Everything besides the section that fixes the structural matrices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BladeSpec {
    /// N, Galerkin functions per field.
    pub n: usize,
    /// L and r_hub (m).
    pub length: f64,
    pub hub_radius: f64,
    /// Ω (rad/s).
    pub omega: f64,
    pub form: Form,
    /// η1, the first mode's loss factor.
    pub loss_factor: f64,
}

impl BladeSpec {
    pub fn check(&self) -> Result<()> {
        if self.n == 0 {
            return Err(Error::numerical("structure.modes must be at least 1"));
        }
        let values = [
            ("blade.length", self.length),
            ("blade.hub_radius", self.hub_radius),
            ("rotor speed", self.omega),
            ("structure.loss_factor", self.loss_factor),
        ];
        if let Some((name, v)) = values.iter().find(|(_, v)| !v.is_finite()) {
            return Err(Error::numerical(format!("{name} = {v} is not finite")));
        }
        if self.length <= 0.0 {
            return Err(Error::numerical(format!(
                "blade.length = {} must be positive",
                self.length
            )));
        }
        Ok(())
    }
}

/// Pure basis integrals over [0, L] (section constants not applied), N×N each.
struct BasisIntegrals {
    /// ∫ΦΦᵀ
    phi_phi: DMatrix<f64>,
    /// ∫Φ'Φ'ᵀ
    dphi_dphi: DMatrix<f64>,
    /// ∫F_c Φ'Φ'ᵀ / (mΩ²)
    tension_dphi_dphi: DMatrix<f64>,
    /// ∫UUᵀ
    u_u: DMatrix<f64>,
    /// ∫U''U''ᵀ
    ddu_ddu: DMatrix<f64>,
    /// ∫F_c U'U'ᵀ / (mΩ²)
    tension_du_du: DMatrix<f64>,
    /// ∫ΦUᵀ
    phi_u: DMatrix<f64>,
    /// ∫Φ'U''ᵀ
    dphi_ddu: DMatrix<f64>,
}

/// The same integrals on the unit span `s = x/L ∈ [0, 1]`, where the basis no longer depends on
/// L (`Φ_j(Ls)` and `U_j(Ls)` are functions of s alone). The tension weight
/// `F_c/(mΩ²) = ½((r_hub+L)² − r²) = L²·½(1−s²) + r_hub L·(1−s)` splits into two s-weights.
struct ReferenceIntegrals {
    phi_phi: DMatrix<f64>,
    dphi_dphi: DMatrix<f64>,
    u_u: DMatrix<f64>,
    ddu_ddu: DMatrix<f64>,
    phi_u: DMatrix<f64>,
    dphi_ddu: DMatrix<f64>,
    /// ∫½(1−s²)Φ̃'Φ̃'ᵀ ds and ∫(1−s)Φ̃'Φ̃'ᵀ ds
    tension_dphi_dphi: [DMatrix<f64>; 2],
    /// ∫½(1−s²)Ũ'Ũ'ᵀ ds and ∫(1−s)Ũ'Ũ'ᵀ ds
    tension_du_du: [DMatrix<f64>; 2],
}

/// Largest N whose reference integrals are cached (the preset allows 40).
const CACHED_BASES: usize = 64;

/// The unit-span integrals for N functions per field, computed once per N and shared: they are
/// the whole cost of assembly, and nothing in them depends on the blade.
fn reference_integrals(n: usize) -> Arc<ReferenceIntegrals> {
    static CACHE: [OnceLock<Arc<ReferenceIntegrals>>; CACHED_BASES + 1] =
        [const { OnceLock::new() }; CACHED_BASES + 1];
    match CACHE.get(n) {
        Some(cell) => cell
            .get_or_init(|| Arc::new(compute_reference_integrals(n)))
            .clone(),
        None => Arc::new(compute_reference_integrals(n)),
    }
}

/// Gauss quadrature of every basis product on the unit span (docs/model.md §4).
fn compute_reference_integrals(n: usize) -> ReferenceIntegrals {
    let unit = Basis::new(n, 1.0);
    let modes: Vec<BendingMode> = (1..=n).map(|j| BendingMode::new(j, 1.0)).collect();
    let wavenumbers: Vec<f64> = (1..=n).map(|j| torsion_wavenumber(j, 1.0)).collect();
    let (ss, ws) = unit.quadrature();
    let z = || DMatrix::<f64>::zeros(n, n);
    let mut r = ReferenceIntegrals {
        phi_phi: z(),
        dphi_dphi: z(),
        u_u: z(),
        ddu_ddu: z(),
        phi_u: z(),
        dphi_ddu: z(),
        tension_dphi_dphi: [z(), z()],
        tension_du_du: [z(), z()],
    };
    let (mut phi, mut dphi) = (vec![0.0; n], vec![0.0; n]);
    let (mut u, mut du, mut ddu) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for (&s, &w) in ss.iter().zip(&ws) {
        for j in 0..n {
            let (sin, cos) = (wavenumbers[j] * s).sin_cos();
            phi[j] = sin;
            dphi[j] = wavenumbers[j] * cos;
            [u[j], du[j], ddu[j]] = modes[j].eval012(s, 1.0);
        }
        let tension = [w * 0.5 * (1.0 - s * s), w * (1.0 - s)];
        add_outer_sym(&mut r.phi_phi, w, &phi);
        add_outer_sym(&mut r.dphi_dphi, w, &dphi);
        add_outer_sym(&mut r.u_u, w, &u);
        add_outer_sym(&mut r.ddu_ddu, w, &ddu);
        for ((tp, tu), wt) in r
            .tension_dphi_dphi
            .iter_mut()
            .zip(r.tension_du_du.iter_mut())
            .zip(tension)
        {
            add_outer_sym(tp, wt, &dphi);
            add_outer_sym(tu, wt, &du);
        }
        add_outer(&mut r.phi_u, w, &phi, &u);
        add_outer(&mut r.dphi_ddu, w, &dphi, &ddu);
    }
    let [t0, t1] = &mut r.tension_dphi_dphi;
    let [t2, t3] = &mut r.tension_du_du;
    for m in [
        &mut r.phi_phi,
        &mut r.dphi_dphi,
        &mut r.u_u,
        &mut r.ddu_ddu,
        t0,
        t1,
        t2,
        t3,
    ] {
        m.fill_lower_triangle_with_upper_triangle();
    }
    r
}

/// The integrals over `[0, L]` from the unit-span ones (`x = Ls`, `dx = L ds`, each derivative
/// brings `1/L`): e.g. `∫U''U''ᵀdx = L⁻³∫Ũ''Ũ''ᵀds`, and the tension integrals
/// `∫F_cU'U'ᵀ/(mΩ²) dx = L·T₁ + r_hub·T₂` (docs/model.md §3–§4).
fn basis_integrals(basis: &Basis, hub_radius: f64) -> BasisIntegrals {
    let r = reference_integrals(basis.n);
    let l = basis.length;
    let tension = |t: &[DMatrix<f64>; 2]| &t[0] * l + &t[1] * hub_radius;
    BasisIntegrals {
        phi_phi: &r.phi_phi * l,
        dphi_dphi: &r.dphi_dphi / l,
        tension_dphi_dphi: tension(&r.tension_dphi_dphi),
        u_u: &r.u_u * l,
        ddu_ddu: &r.ddu_ddu / (l * l * l),
        tension_du_du: tension(&r.tension_du_du),
        phi_u: &r.phi_u * l,
        dphi_ddu: &r.dphi_ddu / (l * l),
    }
}

/// `a += w · v vᵀ`, upper triangle only.
#[inline]
fn add_outer_sym(a: &mut DMatrix<f64>, w: f64, v: &[f64]) {
    for j in 0..v.len() {
        let wv = w * v[j];
        for i in 0..=j {
            a[(i, j)] += wv * v[i];
        }
    }
}

/// `a += w · x yᵀ`.
#[inline]
fn add_outer(a: &mut DMatrix<f64>, w: f64, x: &[f64], y: &[f64]) {
    for j in 0..y.len() {
        let wy = w * y[j];
        for i in 0..x.len() {
            a[(i, j)] += wy * x[i];
        }
    }
}

/// Place N×N blocks into a 2N×2N matrix `[φφ φu; uφ uu]`.
fn blocks(
    pp: &DMatrix<f64>,
    pu: &DMatrix<f64>,
    up: &DMatrix<f64>,
    uu: &DMatrix<f64>,
) -> DMatrix<f64> {
    let n = pp.nrows();
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, 0), (n, n)).copy_from(pp);
    a.view_mut((0, n), (n, n)).copy_from(pu);
    a.view_mut((n, 0), (n, n)).copy_from(up);
    a.view_mut((n, n), (n, n)).copy_from(uu);
    a
}

/// The strong form's extra flap–twist term `C23 U_i(L) Φ_j''(L)` (docs/model.md §4): what remains of
/// `∫U_i C23 Φ_j'''` after two integrations by parts, because the sines do not satisfy the coupled
/// tip shear condition. `Φ_j''(L) = −k_j² sin(k_j L) = −k_j² (−1)^{j−1}`.
fn strong_tip_term(basis: &Basis, c23: f64) -> DMatrix<f64> {
    let n = basis.n;
    let u_tip = basis.bending(basis.length, 0);
    DMatrix::from_fn(n, n, |i, j| {
        let k = torsion_wavenumber(j + 1, basis.length);
        let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
        c23 * u_tip[i] * (-k * k * sign)
    })
}

/// Mass, elastic and centrifugal matrices, ω1 and damping for a uniform section (docs/model.md §3–§4).
pub fn assemble_section(section: SectionProps, spec: &BladeSpec) -> Result<StructuralModel> {
    let s = &section;
    definite_section(s)?;
    let basis = Basis::new(spec.n, spec.length);
    let g = basis_integrals(&basis, spec.hub_radius);
    let omega2 = spec.omega * spec.omega;

    // M: ∫IΦΦᵀ, ∫mUUᵀ, ∫m d ΦUᵀ.
    let m_pu = &g.phi_u * (s.m * s.cg_offset);
    let mass = blocks(
        &(&g.phi_phi * s.i),
        &m_pu,
        &m_pu.transpose(),
        &(&g.u_u * s.m),
    );

    // K_e: ∫C22Φ'Φ'ᵀ, ∫C23Φ'U''ᵀ, ∫C33U''U''ᵀ; the weak form is symmetric.
    let k_pu = &g.dphi_ddu * s.c23;
    let mut k_up = k_pu.transpose();
    if spec.form == Form::Strong {
        k_up += strong_tip_term(&basis, s.c23);
    }
    let elastic = blocks(&(&g.dphi_dphi * s.c22), &k_pu, &k_up, &(&g.ddu_ddu * s.c33));

    // K_c: ∫F_c K_A² Φ'Φ'ᵀ + ∫mΩ²(K_m2² − K_m1²)ΦΦᵀ (propeller moment), ∫F_c U'U'ᵀ.
    let m_omega2 = s.m * omega2;
    let kc_pp =
        &g.tension_dphi_dphi * (m_omega2 * s.ka2) + &g.phi_phi * (m_omega2 * (s.km2_2 - s.km1_2));
    let zero = DMatrix::zeros(spec.n, spec.n);
    let centrifugal = blocks(&kc_pp, &zero, &zero, &(&g.tension_du_du * m_omega2));

    for (name, a) in [
        ("mass", &mass),
        ("elastic stiffness", &elastic),
        ("centrifugal stiffness", &centrifugal),
    ] {
        if a.iter().any(|v| !v.is_finite()) {
            return Err(Error::numerical(format!(
                "{name} matrix has non-finite entries"
            )));
        }
    }

    let stiffness = &elastic + &centrifugal;
    let lambdas = eigenvalues(&mass, &stiffness)?;
    let omega1 = lowest_frequency(&lambdas).map_err(|e| match e {
        // A section whose thickness-direction inertia exceeds its chordwise one is turned
        // flat to the rotor plane by the propeller moment: name the cause, not just the symptom.
        Error::Numerical(symptom) if s.km1_2 > s.km2_2 && omega2 > 0.0 => {
            Error::numerical(format!(
                "{symptom}: the propeller moment m·Ω²·(K_m2² − K_m1²) = {:.4e} N·m/m per rad is \
                 negative (section.km1_2 = {} m² exceeds section.km2_2 = {} m²) and outweighs \
                 the torsional stiffness at Ω = {:.4} rad/s: the section turns flat to the \
                 rotor plane (propeller-moment divergence); lower the rotor speed or give the \
                 section more chordwise than thickness-direction inertia",
                s.m * omega2 * (s.km2_2 - s.km1_2),
                s.km1_2,
                s.km2_2,
                spec.omega
            ))
        }
        other => other,
    })?;
    let damping = &elastic * (spec.loss_factor / omega1);
    Ok(StructuralModel {
        n: spec.n,
        basis,
        section,
        mass,
        elastic,
        centrifugal,
        damping,
        omega1,
        hub_radius: spec.hub_radius,
        natural: OnceLock::new(),
    })
}

/// The section's energy densities must be positive definite, or no matrix built from them is:
/// the kinetic `I φ̇² + 2 m d φ̇ u̇ + m u̇²` needs `I − m d² > 0` (the inertia about the centre of
/// mass), the strain `C22 φ'² + 2 C23 φ' u'' + C33 u''²` needs `C22 C33 − C23² > 0`. Checked on
/// the section's own numbers (finite: [`section_properties`] checks), so a layup section (whose
/// m, I and d are computed) says which property is wrong instead of "matrix is not positive
/// definite".
fn definite_section(s: &SectionProps) -> Result<()> {
    let about_cg = s.i - s.m * s.cg_offset * s.cg_offset;
    if about_cg <= 0.0 {
        return Err(Error::numerical(format!(
            "the section's inertia about its centre of mass, I − m·d² = {about_cg:.4e} kg·m \
             (I = {:.4e} kg·m, m = {:.4e} kg/m, d = {:.4e} m), is not positive: the mass \
             matrix is not positive definite",
            s.i, s.m, s.cg_offset
        )));
    }
    let det = s.c22 * s.c33 - s.c23 * s.c23;
    if det <= 0.0 {
        return Err(Error::numerical(format!(
            "C22·C33 − C23² = {det:.4e} N²·m⁴ (C22 = {:.4e}, C23 = {:.4e}, C33 = {:.4e} N·m²) is \
             not positive: the bending–twist coupling exceeds what the torsion and flap \
             stiffnesses carry, and the section's stiffness is not positive definite",
            s.c22, s.c23, s.c33
        )));
    }
    Ok(())
}

/// ω1 = √λ_min; a non-positive λ means the blade has no stiffness against some shape.
fn lowest_frequency(lambdas: &[f64]) -> Result<f64> {
    let lmin = lambdas.iter().copied().fold(f64::INFINITY, f64::min);
    if lmin > 0.0 && lmin.is_finite() {
        Ok(lmin.sqrt())
    } else {
        Err(Error::numerical(format!(
            "structure is not positive definite: lowest eigenvalue ω² = {lmin:e} (rad/s)²"
        )))
    }
}

/// Iteration cap for the eigensolvers: far beyond what a 2N ≤ 80 problem needs, so a
/// failure means broken input, reported rather than looped on.
const MAX_SWEEPS: usize = 10_000;

/// Eigenvalues ω² of `K q = ω² M q`, ascending. Symmetric K (weak form, or no coupling):
/// Cholesky reduction and the symmetric solver. Non-symmetric K (strong form): the real Schur
/// form of `M⁻¹K` (Francis QR with an iteration cap); complex pairs, which a nearly symmetric
/// positive K does not produce, keep their real part.
fn eigenvalues(mass: &DMatrix<f64>, k: &DMatrix<f64>) -> Result<Vec<f64>> {
    let mut lambdas = match is_symmetric(k) {
        true => {
            let (a, _) = cholesky_reduce(mass, k)?;
            nalgebra::SymmetricEigen::try_new(a, f64::EPSILON, MAX_SWEEPS)
                .ok_or_else(|| Error::numerical("symmetric eigensolver did not converge"))?
                .eigenvalues
                .iter()
                .copied()
                .collect::<Vec<_>>()
        }
        false => {
            // Eigenvalues only: nalgebra's real Schur form with an iteration cap is several
            // times faster than a full decomposition on these small matrices.
            let a = mass_inverse_times(mass, k)?;
            nalgebra::Schur::try_new(a, f64::EPSILON, MAX_SWEEPS)
                .ok_or_else(|| Error::numerical("general eigensolver did not converge"))?
                .complex_eigenvalues()
                .iter()
                .map(|z| z.re)
                .collect()
        }
    };
    if lambdas.iter().any(|v| !v.is_finite()) {
        return Err(Error::numerical("non-finite structural eigenvalue"));
    }
    lambdas.sort_by(f64::total_cmp);
    Ok(lambdas)
}

/// `M⁻¹ K` through the Cholesky factor of M.
fn mass_inverse_times(mass: &DMatrix<f64>, k: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let chol = mass
        .clone()
        .cholesky()
        .ok_or_else(|| Error::numerical("mass matrix is not positive definite"))?;
    Ok(chol.solve(k))
}

impl StructuralModel {
    /// K_e + K_c.
    pub fn stiffness(&self) -> DMatrix<f64> {
        &self.elastic + &self.centrifugal
    }

    /// Undamped natural modes of (M, K_e + K_c), sorted by frequency, labelled by their kinetic
    /// energy share (docs/model.md §4, §6).
    pub fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        if let Some(known) = self.natural.get() {
            return Ok(known.clone());
        }
        let modes = self.find_natural_modes()?;
        Ok(self.natural.get_or_init(|| modes).clone())
    }

    fn find_natural_modes(&self) -> Result<Vec<NaturalMode>> {
        let k = self.stiffness();
        let pairs = match is_symmetric(&k) {
            true => self.symmetric_pairs(&k)?,
            false => self.general_pairs(&k)?,
        };
        let named = pairs
            .into_iter()
            .map(|(lambda, shape)| {
                let qc: Vec<Complex<f64>> = shape.iter().map(|&v| Complex::new(v, 0.0)).collect();
                let frequency_hz = lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI);
                (frequency_hz, self.kinetic_shares(&qc), shape)
            })
            .collect();
        Ok(NaturalMode::named(named))
    }

    /// (ω², q) pairs, ascending, of the symmetric problem.
    fn symmetric_pairs(&self, k: &DMatrix<f64>) -> Result<Vec<(f64, DVector<f64>)>> {
        let (a, l) = cholesky_reduce(&self.mass, k)?;
        let eig = nalgebra::SymmetricEigen::try_new(a, f64::EPSILON, MAX_SWEEPS)
            .ok_or_else(|| Error::numerical("symmetric eigensolver did not converge"))?;
        let q = l
            .tr_solve_lower_triangular(&eig.eigenvectors)
            .ok_or_else(|| Error::numerical("singular mass factor"))?;
        let mut pairs: Vec<(f64, DVector<f64>)> = eig
            .eigenvalues
            .iter()
            .zip(q.column_iter())
            .map(|(&lambda, col)| (lambda, normalise(col.into_owned())))
            .collect();
        check_pairs(&mut pairs)?;
        Ok(pairs)
    }

    /// (ω², q) pairs, ascending, of the non-symmetric (strong-form) problem: faer's real
    /// eigendecomposition ([`real_evd`]: Hessenberg, Francis QR with an iteration cap,
    /// back-substitution). Real eigenvalues have real eigenvectors (a column of the real form); a
    /// complex pair, which a nearly symmetric positive K does not produce, keeps the real part of
    /// its first column.
    fn general_pairs(&self, k: &DMatrix<f64>) -> Result<Vec<(f64, DVector<f64>)>> {
        let a = mass_inverse_times(&self.mass, k)?;
        let dim = a.nrows();
        let evd = real_evd(&a, false)
            .map_err(|e| Error::numerical(format!("general eigensolver failed: {e:?}")))?;
        let mut pairs: Vec<(f64, DVector<f64>)> = (0..dim)
            .map(|c| {
                let q = DVector::from_fn(dim, |r, _| evd.right[(r, c)]);
                (evd.re[c], normalise(q))
            })
            .collect();
        check_pairs(&mut pairs)?;
        Ok(pairs)
    }

    /// Φ(L): the tip twist is `row · q_φ`.
    pub fn tip_twist_row(&self) -> DVector<f64> {
        self.basis.torsion(self.basis.length, 0)
    }

    /// U(L): the tip flap is `row · q_u`.
    pub fn tip_flap_row(&self) -> DVector<f64> {
        self.basis.bending(self.basis.length, 0)
    }

    /// Share of the kinetic energy in the twist coordinates,
    /// `q_φᴴM_φφq_φ / (q_φᴴM_φφq_φ + q_uᴴM_uuq_u)`: in [0, 1] for any complex eigenvector (the
    /// cg-offset coupling block is left out, as it carries no sign). Uses the first 2N entries.
    pub fn torsion_share(&self, q: &[Complex<f64>]) -> f64 {
        self.kinetic_shares(q).twist
    }

    /// Flap and twist kinetic energies from the diagonal blocks of M (no edge motion).
    fn kinetic_shares(&self, q: &[Complex<f64>]) -> Shares {
        let n = self.n;
        let quad = |offset: usize| -> f64 {
            let mut e = 0.0;
            for j in 0..n {
                for i in 0..n {
                    let mij = self.mass[(offset + i, offset + j)];
                    e += mij * (q[offset + i].conj() * q[offset + j]).re;
                }
            }
            e.max(0.0)
        };
        Shares::from_energies(quad(n), 0.0, quad(0))
    }
}

impl Structure for StructuralModel {
    fn coordinates(&self) -> usize {
        2 * self.n
    }
    fn length(&self) -> f64 {
        self.basis.length
    }
    fn hub_radius(&self) -> f64 {
        self.hub_radius
    }
    fn mass(&self) -> &DMatrix<f64> {
        &self.mass
    }
    fn stiffness(&self) -> DMatrix<f64> {
        StructuralModel::stiffness(self)
    }
    fn damping(&self) -> &DMatrix<f64> {
        &self.damping
    }
    /// `q = [q_φ; q_u]`: twist from the torsion functions, flap from the bending functions, no
    /// edge motion (docs/model.md §4).
    fn motion_rows(&self, x: f64) -> MotionRows {
        let n = self.n;
        let mut twist = DVector::zeros(2 * n);
        let mut flap = DVector::zeros(2 * n);
        twist.rows_mut(0, n).copy_from(&self.basis.torsion(x, 0));
        flap.rows_mut(n, n).copy_from(&self.basis.bending(x, 0));
        MotionRows {
            twist,
            flap,
            edge: DVector::zeros(2 * n),
        }
    }
    fn natural_modes(&self) -> Result<Vec<NaturalMode>> {
        StructuralModel::natural_modes(self)
    }
    fn shares(&self, q: &[Complex<f64>]) -> Shares {
        self.kinetic_shares(q)
    }
    /// The first torsion and the first bending function.
    fn kick_shapes(&self) -> [DVector<f64>; 2] {
        let n = self.n;
        let unit = |k: usize| DVector::from_fn(2 * n, |i, _| if i == k { 1.0 } else { 0.0 });
        [unit(0), unit(n)]
    }
    fn uniform_section(&self) -> Option<&SectionProps> {
        Some(&self.section)
    }
    /// 41 evenly spaced points: the Galerkin functions are smooth.
    fn span_points(&self) -> Vec<f64> {
        const POINTS: usize = 41;
        let length = self.basis.length;
        (0..POINTS)
            .map(|i| length * i as f64 / (POINTS - 1) as f64)
            .collect()
    }
}

/// Whether K is symmetric to round-off. Only the strong form's tip term breaks symmetry, and it
/// does so at the size of the coupling blocks, far above this tolerance; a symmetric K gets the
/// faster and more accurate symmetric solver whatever form built it.
fn is_symmetric(k: &DMatrix<f64>) -> bool {
    let scale = k.amax();
    let n = k.nrows();
    (0..n).all(|i| (0..i).all(|j| (k[(i, j)] - k[(j, i)]).abs() <= 1e-13 * scale))
}

/// Sort ascending and reject non-finite results.
fn check_pairs(pairs: &mut [(f64, DVector<f64>)]) -> Result<()> {
    if pairs
        .iter()
        .any(|(l, v)| !l.is_finite() || v.iter().any(|x| !x.is_finite()))
    {
        return Err(Error::numerical("non-finite natural mode"));
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(())
}

/// Unit Euclidean norm, largest-magnitude entry positive (a deterministic sign).
fn normalise(mut v: DVector<f64>) -> DVector<f64> {
    let imax = v.iamax();
    let norm = v.norm();
    if norm > 0.0 {
        v *= v[imax].signum() / norm;
    }
    v
}

/// The paper's "approximate calculation" (AC, Eq. 13) for the n-th row of Table 2 (Hz), as docs/model.md
/// §8 and §9.7 read it: λ = i k₁ with `k₁ = (2n−1)π/2L`, the lower root. With `λ² = −k²` Eq. 13
/// becomes `ω² = [S ∓ √(S² − 4mIΔk⁶)]/(2mI)`, `S = C22 m k² + C33 I k⁴`, `Δ = C22C33 − C23²`; the
/// lower root is evaluated as `2Δk⁶/(S + √(S² − 4mIΔk⁶))`, which does not cancel when I is small
/// (the paper's blade has `mI·k⁴` some 1e-9 of `S²`).
pub fn ac_frequency_hz(section: &SectionProps, length: f64, n: usize) -> f64 {
    let s = section;
    let k = torsion_wavenumber(n.max(1), length);
    let k2 = k * k;
    let delta = s.c22 * s.c33 - s.c23 * s.c23;
    let sum = s.c22 * s.m * k2 + s.c33 * s.i * k2 * k2;
    let disc = (sum * sum - 4.0 * s.m * s.i * delta * k2 * k2 * k2).max(0.0);
    let omega2 = 2.0 * delta * k2 * k2 * k2 / (sum + disc.sqrt());
    omega2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}
