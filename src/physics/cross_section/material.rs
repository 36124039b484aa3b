//! The 3-D stiffness of an orthotropic ply, turned into the section's axes (docs/model.md §11.11).
//!
//! Material axes: 1 along the fibre, 2 across it in the ply's plane, 3 normal to the ply. A ply
//! lies in its layer with the fibre turned by the fibre angle θ about the layer normal, from the
//! beam axis toward the layer's in-plane direction `t` (the direction the layer runs in the section
//! plane, at the orientation angle α from the section's x axis): `e₁ = cos θ e_z + sin θ t`,
//! `e₂ = −sin θ e_z + cos θ t`, `e₃ = e_z × t`. On a closed contour run counterclockwise this is
//! the thin-walled laminate's convention (docs/model.md §2.1: θ from the beam axis toward the
//! contour direction). Turning `t` by π is the same as changing the sign of θ.
//!
//! Voigt order everywhere in this module and the solver: (xx, yy, zz, yz, xz, xy) with engineering
//! shear strains, z along the beam.

use crate::error::{Error, Result};
use nalgebra::{Matrix3, Matrix6};

/// An orthotropic material in its axes (moduli in Pa, density in kg/m³). `nu_ij` is the
/// contraction along j under stress along i (so `ν_ji = ν_ij E_j/E_i`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orthotropic {
    pub e1: f64,
    pub e2: f64,
    pub e3: f64,
    pub g12: f64,
    pub g13: f64,
    pub g23: f64,
    pub nu12: f64,
    pub nu13: f64,
    pub nu23: f64,
    pub rho: f64,
}

impl Orthotropic {
    /// An isotropic material: `G = E/(2(1+ν))` on every plane.
    pub fn isotropic(e: f64, nu: f64, rho: f64) -> Orthotropic {
        let g = e / (2.0 * (1.0 + nu));
        Orthotropic {
            e1: e,
            e2: e,
            e3: e,
            g12: g,
            g13: g,
            g23: g,
            nu12: nu,
            nu13: nu,
            nu23: nu,
            rho,
        }
    }

    /// The compliance in material axes, Voigt order (11, 22, 33, 23, 13, 12).
    fn compliance(&self) -> Matrix6<f64> {
        let mut s = Matrix6::zeros();
        s[(0, 0)] = 1.0 / self.e1;
        s[(1, 1)] = 1.0 / self.e2;
        s[(2, 2)] = 1.0 / self.e3;
        s[(0, 1)] = -self.nu12 / self.e1;
        s[(0, 2)] = -self.nu13 / self.e1;
        s[(1, 2)] = -self.nu23 / self.e2;
        s[(1, 0)] = s[(0, 1)];
        s[(2, 0)] = s[(0, 2)];
        s[(2, 1)] = s[(1, 2)];
        s[(3, 3)] = 1.0 / self.g23;
        s[(4, 4)] = 1.0 / self.g13;
        s[(5, 5)] = 1.0 / self.g12;
        s
    }

    /// The stiffness in material axes, Voigt order (11, 22, 33, 23, 13, 12); an error unless
    /// every constant is finite, the moduli and density positive and the compliance positive
    /// definite (the Poisson ratios within their thermodynamic bounds).
    pub fn stiffness(&self) -> Result<Matrix6<f64>> {
        let named = [
            ("E1", self.e1),
            ("E2", self.e2),
            ("E3", self.e3),
            ("G12", self.g12),
            ("G13", self.g13),
            ("G23", self.g23),
            ("density", self.rho),
        ];
        if let Some((name, v)) = named.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(invalid(format!("{name} = {v} must be positive and finite")));
        }
        let ratios = [("ν12", self.nu12), ("ν13", self.nu13), ("ν23", self.nu23)];
        if let Some((name, v)) = ratios.iter().find(|(_, v)| !v.is_finite()) {
            return Err(invalid(format!("{name} = {v} is not finite")));
        }
        let s = self.compliance();
        let chol = s.cholesky().ok_or_else(|| {
            invalid(format!(
                "the Poisson ratios ν12 = {}, ν13 = {}, ν23 = {} with E1 = {}, E2 = {}, E3 = {} \
                 give a compliance that is not positive definite",
                self.nu12, self.nu13, self.nu23, self.e1, self.e2, self.e3
            ))
        })?;
        Ok(chol.inverse())
    }
}

fn invalid(message: String) -> Error {
    Error::Invalid {
        origin: "cross-section material".into(),
        message,
    }
}

/// The rows of `a` are the material axes `e₁, e₂, e₃` in section coordinates for a ply at fibre
/// angle `fibre` in a layer running along `orientation` (both rad); see the module notes.
pub fn material_axes(fibre: f64, orientation: f64) -> Matrix3<f64> {
    let (st, ct) = fibre.sin_cos();
    let (sa, ca) = orientation.sin_cos();
    let t = [ca, sa, 0.0];
    let ez = [0.0, 0.0, 1.0];
    let n = [-sa, ca, 0.0];
    let e1: [f64; 3] = std::array::from_fn(|k| ct * ez[k] + st * t[k]);
    let e2: [f64; 3] = std::array::from_fn(|k| -st * ez[k] + ct * t[k]);
    Matrix3::new(e1[0], e1[1], e1[2], e2[0], e2[1], e2[2], n[0], n[1], n[2])
}

/// Index pairs of the Voigt order (11, 22, 33, 23, 13, 12).
const VOIGT: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// The stress transformation `σ' = T σ` (Voigt, engineering shears) for new axes given by the
/// rows of `a` in the old ones: `σ'_ij = a_ik a_jl σ_kl`, the symmetric pairs gathered.
fn stress_rotation(a: &Matrix3<f64>) -> Matrix6<f64> {
    Matrix6::from_fn(|p, q| {
        let (i, j) = VOIGT[p];
        let (k, l) = VOIGT[q];
        if k == l {
            a[(i, k)] * a[(j, k)]
        } else {
            a[(i, k)] * a[(j, l)] + a[(i, l)] * a[(j, k)]
        }
    })
}

/// The stiffness `c` of a material (Voigt, material axes) in section axes, for a ply at fibre
/// angle `fibre` in a layer along `orientation` (rad): `T C Tᵀ` with `T` the stress rotation from
/// material to section axes (whose transpose carries section strains into material ones).
pub fn section_stiffness(c: &Matrix6<f64>, fibre: f64, orientation: f64) -> Matrix6<f64> {
    // Section axes in material coordinates: the transpose of the material axes in section ones.
    let to_section = material_axes(fibre, orientation).transpose();
    let t = stress_rotation(&to_section);
    let q = t * c * t.transpose();
    // Round-off asymmetry would leak into the assembled matrices.
    (q + q.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn ply() -> Orthotropic {
        Orthotropic {
            e1: 140e9,
            e2: 10e9,
            e3: 9e9,
            g12: 5e9,
            g13: 4.5e9,
            g23: 3.5e9,
            nu12: 0.3,
            nu13: 0.28,
            nu23: 0.45,
            rho: 1600.0,
        }
    }

    #[test]
    fn isotropic_stiffness_is_lame() {
        let (e, nu) = (70e9, 0.33);
        let c = Orthotropic::isotropic(e, nu, 2700.0).stiffness().unwrap();
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        assert!((c[(0, 0)] - (lambda + 2.0 * mu)).abs() < 1e-6 * e);
        assert!((c[(0, 1)] - lambda).abs() < 1e-6 * e);
        assert!((c[(3, 3)] - mu).abs() < 1e-6 * e);
        // An isotropic material looks the same in any axes.
        let q = section_stiffness(&c, 0.7, -1.1);
        assert!((q - c).abs().max() < 1e-6 * e);
    }

    #[test]
    fn zero_angles_put_the_fibre_along_the_beam() {
        let m = ply();
        let c = m.stiffness().unwrap();
        let q = section_stiffness(&c, 0.0, 0.0);
        // Section zz is the fibre, xx the layer direction (material 2), yy the normal (3).
        let s = q.try_inverse().unwrap();
        assert!((1.0 / s[(2, 2)] - m.e1).abs() < 1e-6 * m.e1);
        assert!((1.0 / s[(0, 0)] - m.e2).abs() < 1e-6 * m.e1);
        assert!((1.0 / s[(1, 1)] - m.e3).abs() < 1e-6 * m.e1);
        // Shear in the layer (xz, material 12) and through it (yz, material 13).
        assert!((1.0 / s[(4, 4)] - m.g12).abs() < 1e-6 * m.e1);
        assert!((1.0 / s[(3, 3)] - m.g13).abs() < 1e-6 * m.e1);
        assert!((1.0 / s[(5, 5)] - m.g23).abs() < 1e-6 * m.e1);
    }

    #[test]
    fn fibre_at_a_right_angle_runs_along_the_layer() {
        let m = ply();
        let c = m.stiffness().unwrap();
        // A layer along y with the fibre turned 90°: the fibre lies along +y.
        let s = section_stiffness(&c, FRAC_PI_2, FRAC_PI_2)
            .try_inverse()
            .unwrap();
        assert!((1.0 / s[(1, 1)] - m.e1).abs() < 1e-6 * m.e1);
        assert!((1.0 / s[(2, 2)] - m.e2).abs() < 1e-6 * m.e1);
    }

    #[test]
    fn an_off_axis_ply_couples_axial_stretch_and_layer_shear_as_laminate_theory() {
        // Stretching along the beam a ply at +θ (fibre turned toward the layer direction x) shears
        // it in the negative sense for a fibre-dominated ply: S16 of the rotated compliance.
        let m = ply();
        let c = m.stiffness().unwrap();
        let theta: f64 = 0.4;
        let s = section_stiffness(&c, theta, 0.0).try_inverse().unwrap();
        // Plane-stress transformed compliance (Jones Eq. 2.88) in (beam, layer) axes.
        let (sn, cs) = theta.sin_cos();
        let (s11, s22, s12, s66) = (1.0 / m.e1, 1.0 / m.e2, -m.nu12 / m.e1, 1.0 / m.g12);
        let s16 = (2.0 * s11 - 2.0 * s12 - s66) * cs.powi(3) * sn
            - (2.0 * s22 - 2.0 * s12 - s66) * cs * sn.powi(3);
        // Section xz shear (Voigt 4) against zz (Voigt 2).
        assert!(s16 < 0.0);
        assert!(
            (s[(2, 4)] - s16).abs() < 1e-9 * s16.abs(),
            "{} vs {s16}",
            s[(2, 4)]
        );
    }

    #[test]
    fn bad_constants_are_errors() {
        let mut m = ply();
        m.e2 = f64::NAN;
        assert!(m.stiffness().is_err());
        let mut m = ply();
        m.g23 = 0.0;
        assert!(m.stiffness().is_err());
        let mut m = ply();
        m.nu23 = 1.2;
        assert!(m.stiffness().is_err());
    }
}
