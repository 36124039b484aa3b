//! A tabulated blade (docs/model.md §11): section properties that vary along the span, read from
//! a real blade's files and interpolated linearly between the input stations, in the frame the
//! finite elements use.
//!
//! Frame (docs/model.md §11.1): `z` along the straight pitch axis from the blade root (radius
//! `r = r_hub + z`), `x` out of the rotor plane (downwind), `y` in the rotor plane toward the
//! leading edge at zero pitch and twist, so that a positive rotation about `z` (x toward y) turns
//! the leading edge upwind: toward feather. Each section has its own frame, turned from `(x, y)`
//! by its structural twist plus the pitch: `ξ` normal to the chord (flap direction) and `η` along
//! the chord toward the leading edge.

pub mod axis;
pub mod beamdyn;
pub mod classical;
pub mod coupling;
pub mod fem;
pub mod hawc2;
pub mod hermite;
pub mod modal;
pub mod pitch_range;
pub mod source;
pub mod windio;

use crate::error::{Error, Result};
use axis::CurvedAxis;
use nalgebra::{Matrix2, Matrix2x3, Matrix3, Matrix5};

/// One input station, in its section frame `(ξ, η)` about the reference (pitch) axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamSection {
    /// Span position from the root (m).
    pub z: f64,
    /// Mass per length (kg/m).
    pub mass: f64,
    /// Centre of mass from the reference axis (m): `[ξ, η]`.
    pub cg: [f64; 2],
    /// Mass moments per length about the reference axis (kg·m): `[∫ρξ², ∫ρη², ∫ρξη]`.
    pub inertia: [f64; 3],
    /// Flap bending stiffness, for curvature along ξ (N·m²).
    pub ei_flap: f64,
    /// Edge bending stiffness, for curvature along η (N·m²).
    pub ei_edge: f64,
    /// Cross term of the two curvatures when ξ, η are not principal (N·m²).
    pub ei_cross: f64,
    /// Torsional stiffness (N·m²).
    pub gj: f64,
    /// Flap–twist coupling (N·m²): positive twists the section toward feather when the blade
    /// bends downwind (strain energy `−g κ_ξ φ'`).
    pub flap_twist: f64,
    /// Edge–twist coupling (N·m²): positive twists toward feather when the blade bends toward
    /// the leading edge.
    pub edge_twist: f64,
    /// Structural twist of the section frame from the rotor plane (rad), toward feather.
    pub twist: f64,
    /// Shear centre from the reference axis (m): `[ξ, η]`. The bending–torsion elastic axis: a
    /// lateral force through it bends the section without twisting it (docs/model.md §11.2).
    pub shear_centre: [f64; 2],
    /// Elastic (tension) centre from the reference axis (m): `[ξ, η]`. The centrifugal tension
    /// acts along it (docs/model.md §11.2).
    pub tension_centre: [f64; 2],
    /// What the section's transverse shear adds to its flexibility (docs/model.md §11.2); zero
    /// for a section rigid in shear (the Euler–Bernoulli beam).
    pub shear: ShearFlexibility,
}

/// A section's transverse-shear flexibility about its shear centre, in the section frame: with
/// the bending–torsion stiffness `C` of [`BeamSection`] (whose inverse is the flexibility of the
/// curvatures `κ_ξ, κ_η, φ'` under moments), the whole flexibility of the strains
/// `(γ_ξ, γ_η, κ_ξ, κ_η, φ')` under `(V_ξ, V_η, M_ξ, M_η, M_φ)` is `[[S_γγ, S_γκ], [S_γκᵀ, C⁻¹]]`
/// (docs/model.md §11.2). The axial force is taken zero (no axial degree of freedom).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShearFlexibility {
    /// `S_γγ`: `[S_ξξ, S_ηη, S_ξη]` (1/N), shear strain per shear force.
    pub strain: [f64; 3],
    /// `S_γκ` row by row: `γ_ξ` then `γ_η` per unit moment about `(κ_ξ, κ_η, φ')` (1/(N·m)),
    /// the shear–bending and shear–twist couplings left at the shear centre.
    pub coupling: [f64; 6],
}

impl ShearFlexibility {
    /// A section rigid in shear.
    pub const RIGID: ShearFlexibility = ShearFlexibility {
        strain: [0.0; 3],
        coupling: [0.0; 6],
    };

    /// Whether the section deforms in shear at all.
    pub fn is_rigid(&self) -> bool {
        self.strain.iter().chain(&self.coupling).all(|v| *v == 0.0)
    }
}

impl BeamSection {
    /// Linear interpolation between two stations (at fraction `t` from `a` to `b`).
    fn lerp(a: &BeamSection, b: &BeamSection, t: f64) -> BeamSection {
        BeamSection::zip_with(a, b, |x, y| x + (y - x) * t)
    }

    /// The per-metre rate of every property from `a` to `b` (the slope of the linear
    /// interpolation; `z` is then 1).
    fn rate(a: &BeamSection, b: &BeamSection) -> BeamSection {
        let h = b.z - a.z;
        BeamSection {
            z: 1.0,
            ..BeamSection::zip_with(a, b, |x, y| (y - x) / h)
        }
    }

    /// Every property of `a` and `b` combined by `f`, field by field.
    fn zip_with(a: &BeamSection, b: &BeamSection, f: impl Fn(f64, f64) -> f64) -> BeamSection {
        let pair = |x: [f64; 2], y: [f64; 2]| [f(x[0], y[0]), f(x[1], y[1])];
        BeamSection {
            z: f(a.z, b.z),
            mass: f(a.mass, b.mass),
            cg: pair(a.cg, b.cg),
            inertia: [
                f(a.inertia[0], b.inertia[0]),
                f(a.inertia[1], b.inertia[1]),
                f(a.inertia[2], b.inertia[2]),
            ],
            ei_flap: f(a.ei_flap, b.ei_flap),
            ei_edge: f(a.ei_edge, b.ei_edge),
            ei_cross: f(a.ei_cross, b.ei_cross),
            gj: f(a.gj, b.gj),
            flap_twist: f(a.flap_twist, b.flap_twist),
            edge_twist: f(a.edge_twist, b.edge_twist),
            twist: f(a.twist, b.twist),
            shear_centre: pair(a.shear_centre, b.shear_centre),
            tension_centre: pair(a.tension_centre, b.tension_centre),
            shear: ShearFlexibility {
                strain: std::array::from_fn(|k| f(a.shear.strain[k], b.shear.strain[k])),
                coupling: std::array::from_fn(|k| f(a.shear.coupling[k], b.shear.coupling[k])),
            },
        }
    }

    /// The named quantities that must be finite and, for masses and stiffnesses, positive.
    fn check(&self, origin: &str, index: usize) -> Result<()> {
        match self.fault() {
            None => Ok(()),
            Some(message) => Err(Error::Invalid {
                origin: origin.to_string(),
                message: format!("station {} (z = {} m): {message}", index + 1, self.z),
            }),
        }
    }

    /// What [`BeamSection::check`] finds wrong with this section, without where it is.
    fn fault(&self) -> Option<String> {
        let positive = [
            ("mass per length", self.mass),
            ("flap stiffness", self.ei_flap),
            ("edge stiffness", self.ei_edge),
            ("torsional stiffness", self.gj),
        ];
        let finite = [
            ("centre of mass ξ", self.cg[0]),
            ("centre of mass η", self.cg[1]),
            ("mass moment ∫ρξ²", self.inertia[0]),
            ("mass moment ∫ρη²", self.inertia[1]),
            ("mass moment ∫ρξη", self.inertia[2]),
            ("bending cross stiffness", self.ei_cross),
            ("flap–twist coupling", self.flap_twist),
            ("edge–twist coupling", self.edge_twist),
            ("structural twist", self.twist),
            ("shear centre ξ", self.shear_centre[0]),
            ("shear centre η", self.shear_centre[1]),
            ("tension centre ξ", self.tension_centre[0]),
            ("tension centre η", self.tension_centre[1]),
        ];
        if let Some((name, v)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Some(format!("{name} = {v} must be positive"));
        }
        if let Some((name, v)) = finite.iter().find(|(_, v)| !v.is_finite()) {
            return Some(format!("{name} = {v} is not finite"));
        }
        if let Some(v) = self
            .shear
            .strain
            .iter()
            .chain(&self.shear.coupling)
            .find(|v| !v.is_finite())
        {
            return Some(format!("shear flexibility {v} is not finite"));
        }
        if !self.shear.is_rigid() && self.timoshenko_stiffness().is_none() {
            return Some(format!(
                "the shear flexibility {:?} (coupling {:?}) with the bending–torsion stiffness is not positive definite",
                self.shear.strain, self.shear.coupling
            ));
        }
        if self.inertia[0] < 0.0 || self.inertia[1] < 0.0 {
            return Some(format!(
                "mass moments ∫ρξ² = {}, ∫ρη² = {} must not be negative",
                self.inertia[0], self.inertia[1]
            ));
        }
        None
    }
}

impl BeamSection {
    /// The bending–torsion stiffness `C` over `(κ_ξ, κ_η, φ')` (docs/model.md §11.2).
    pub fn bending_torsion(&self) -> Matrix3<f64> {
        Matrix3::new(
            self.ei_flap,
            self.ei_cross,
            -self.flap_twist,
            self.ei_cross,
            self.ei_edge,
            -self.edge_twist,
            -self.flap_twist,
            -self.edge_twist,
            self.gj,
        )
    }

    /// The shear-deformable section's stiffness over `(γ_ξ, γ_η, κ_ξ, κ_η, φ')` about the shear
    /// centre (docs/model.md §11.2): the inverse of `[[S_γγ, S_γκ], [S_γκᵀ, C⁻¹]]`, formed without
    /// inverting `C` as `[[P, −P S_γκ C], [·, C + C S_γκᵀ P S_γκ C]]` with
    /// `P = (S_γγ − S_γκ C S_γκᵀ)⁻¹`. `None` when that is not positive definite (or the section is
    /// rigid in shear, where `P` is infinite).
    pub fn timoshenko_stiffness(&self) -> Option<Matrix5<f64>> {
        let [sxx, syy, sxy] = self.shear.strain;
        let a = Matrix2::new(sxx, sxy, sxy, syy);
        let b = Matrix2x3::from_row_slice(&self.shear.coupling);
        let c = self.bending_torsion();
        let schur = a - b * c * b.transpose();
        let det = schur.determinant();
        if !(schur[(0, 0)] > 0.0 && det > 0.0 && det.is_finite()) {
            return None;
        }
        let p = schur.try_inverse()?;
        let pbc = p * b * c;
        let mut k = Matrix5::zeros();
        k.fixed_view_mut::<2, 2>(0, 0).copy_from(&p);
        k.fixed_view_mut::<2, 3>(0, 2).copy_from(&(-pbc));
        k.fixed_view_mut::<3, 2>(2, 0)
            .copy_from(&(-pbc.transpose()));
        k.fixed_view_mut::<3, 3>(2, 2)
            .copy_from(&(c + c * b.transpose() * p * b * c));
        Some(k)
    }
}

/// A section's 6×6 matrices as its file gives them (docs/model.md §11.2, §11.5–§11.6): what a
/// [`BeamSection`] is reduced from ([`classical::reduce`]), kept whole for a beam that carries
/// shear and extension.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionMatrices {
    /// The stiffness relating `(F₁, F₂, F₃, M₁, M₂, M₃)` to `(γ₁, γ₂, ε₃, κ₁, κ₂, κ₃)` in the
    /// file's section axes (3 along the blade) about [`SectionMatrices::origin`].
    pub stiffness: [[f64; 6]; 6],
    /// The mass per length in the same axes and about the same point, where the file gives one
    /// (BeamDyn).
    pub mass: Option<[[f64; 6]; 6]>,
    /// How the file's section axes lie in ours.
    pub frame: classical::FileFrame,
    /// The matrices' origin from the reference axis (m, `[ξ, η]`).
    pub origin: [f64; 2],
}

/// A blade as a table of sections along its span.
#[derive(Debug, Clone, PartialEq)]
pub struct BladeTable {
    /// Where the table came from, for messages.
    pub origin: String,
    /// Hub radius (m): the root is at `r = hub_radius`.
    pub hub_radius: f64,
    /// Stations sorted by `z`, the first at the root (`z = 0`), the last at the tip.
    pub sections: Vec<BeamSection>,
    /// Each station's matrices, in station order, where the file gives its sections as 6×6
    /// matrices (BeamDyn, a HAWC2 fully populated st file); empty for a HAWC2 classic st file,
    /// whose columns the sections hold. The file's, before any coupling a preset adds
    /// ([`coupling::with_bend_twist_coupling`]).
    pub matrices: Vec<SectionMatrices>,
    /// The reference axis's prebend and sweep (docs/model.md §11.9); straight unless a blade's
    /// files give a curve and the preset keeps it.
    pub axis: CurvedAxis,
}

impl BladeTable {
    /// A table checked for what the elements need: at least two stations, strictly increasing
    /// span from 0, every property finite and every mass and stiffness positive.
    pub fn new(origin: &str, hub_radius: f64, sections: Vec<BeamSection>) -> Result<BladeTable> {
        let invalid = |message: String| Error::Invalid {
            origin: origin.to_string(),
            message,
        };
        if sections.len() < 2 {
            return Err(invalid(format!(
                "a blade needs at least two stations, got {}",
                sections.len()
            )));
        }
        if !(hub_radius.is_finite() && hub_radius >= 0.0) {
            return Err(invalid(format!(
                "hub radius {hub_radius} m must be finite and not negative"
            )));
        }
        if sections[0].z != 0.0 {
            return Err(invalid(format!(
                "the first station must be at the root (z = 0), not z = {} m",
                sections[0].z
            )));
        }
        for (k, w) in sections.windows(2).enumerate() {
            if w[1].z.partial_cmp(&w[0].z) != Some(std::cmp::Ordering::Greater) {
                return Err(invalid(format!(
                    "stations {} and {} are not in increasing span order (z = {} m, then {} m)",
                    k + 1,
                    k + 2,
                    w[0].z,
                    w[1].z
                )));
            }
        }
        for (k, s) in sections.iter().enumerate() {
            s.check(origin, k)?;
        }
        let shear_rigid = sections.iter().position(|s| s.shear.is_rigid());
        if let (Some(k), true) = (shear_rigid, sections.iter().any(|s| !s.shear.is_rigid())) {
            return Err(invalid(format!(
                "station {} (z = {} m) has no shear flexibility where others have: a blade is \
                 shear-deformable at every station or at none",
                k + 1,
                sections[k].z
            )));
        }
        Ok(BladeTable {
            origin: origin.to_string(),
            hub_radius,
            sections,
            matrices: Vec::new(),
            axis: CurvedAxis::straight(),
        })
    }

    /// The table on the curved reference axis `axis`.
    pub fn with_axis(mut self, axis: CurvedAxis) -> BladeTable {
        self.axis = axis;
        self
    }

    /// The table with the matrices its sections were reduced from, one per station.
    pub fn with_matrices(mut self, matrices: Vec<SectionMatrices>) -> Result<BladeTable> {
        if !matrices.is_empty() && matrices.len() != self.sections.len() {
            return Err(Error::Invalid {
                origin: self.origin.clone(),
                message: format!(
                    "{} section matrices for {} stations",
                    matrices.len(),
                    self.sections.len()
                ),
            });
        }
        self.matrices = matrices;
        Ok(self)
    }

    /// Whether the sections deform in shear (docs/model.md §11.2): then the elements are
    /// Timoshenko beams, else Euler–Bernoulli ones.
    pub fn is_shear_deformable(&self) -> bool {
        self.sections.iter().any(|s| !s.shear.is_rigid())
    }

    /// The same blade rigid in shear: the Euler–Bernoulli limit (`structure.shear = false`).
    pub fn rigid_in_shear(&self) -> BladeTable {
        let mut out = self.clone();
        for s in &mut out.sections {
            s.shear = ShearFlexibility::RIGID;
        }
        out
    }

    /// Blade length (m): the span of the last station.
    pub fn length(&self) -> f64 {
        self.sections[self.sections.len() - 1].z
    }

    /// The section at span `z`, linear between the stations (clamped to the ends).
    pub fn at(&self, z: f64) -> BeamSection {
        let (a, b) = self.interval(z);
        let t = ((z - a.z) / (b.z - a.z)).clamp(0.0, 1.0);
        BeamSection::lerp(a, b, t)
    }

    /// The rate of change along the span of every property at `z` (per metre): the slope of the
    /// table interval holding `z` (at a station, the interval outboard of it), as the offsets'
    /// rates in the tension-centre slopes need (docs/model.md §11.2).
    pub fn rate_at(&self, z: f64) -> BeamSection {
        let (a, b) = self.interval(z);
        BeamSection::rate(a, b)
    }

    /// The two stations around `z` (the first or last interval beyond the ends).
    fn interval(&self, z: f64) -> (&BeamSection, &BeamSection) {
        let s = &self.sections;
        let k = s.partition_point(|x| x.z <= z).clamp(1, s.len() - 1);
        (&s[k - 1], &s[k])
    }
}
