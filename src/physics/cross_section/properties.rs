//! Engineering properties from a section's 6×6 matrices (docs/model.md §11.11): centres, axial,
//! bending, torsion and shear stiffnesses, principal axes, mass and its centre.

use super::solve::BeamMatrices;
use crate::error::{Error, Result};
use nalgebra::{Matrix2, Matrix3, Matrix6, Vector2};

/// A section's properties; positions in the mesh's coordinates (m), angles in rad.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SectionProperties {
    /// Axial stiffness with every other force and moment zero, the axial force through the
    /// elastic centre (N): `1/F₃₃` there.
    pub ea: f64,
    /// The bending–torsion stiffness of the Euler–Bernoulli section over `(κ_x, κ_y, κ_z)`
    /// (N·m²): the Schur complement `K_bb − K_ba K_aa⁻¹ K_ab` that leaves the shear and axial
    /// forces zero, the same about any point (as `classical::reduce` takes it from a file).
    pub bending_torsion: [[f64; 3]; 3],
    /// Bending stiffnesses about the principal axes (N·m²), the larger first.
    pub ei_principal: [f64; 2],
    /// The first principal axis's angle from x, counterclockwise (rad, in (−π/2, π/2]).
    pub principal_angle: f64,
    /// Torsional stiffness `bending_torsion[2][2]` (N·m²).
    pub gj: f64,
    /// Transverse shear stiffness about the shear centre (N): the inverse of the compliance's
    /// shear block there, `[[k_x GA, ·], [·, k_y GA]]`.
    pub shear_stiffness: [[f64; 2]; 2],
    /// Where an axial force stretches the section without bending it.
    pub elastic_centre: [f64; 2],
    /// Where a transverse force bends the section without twisting it.
    pub shear_centre: [f64; 2],
    /// Mass per length (kg/m).
    pub mass: f64,
    pub centre_of_mass: [f64; 2],
    /// Mass moments per length about the centre of mass (kg·m): `[∫ρ(y−y_c)², ∫ρ(x−x_c)²,
    /// ∫ρ(x−x_c)(y−y_c)]`.
    pub mass_moments: [f64; 3],
}

fn to_matrix(a: &[[f64; 6]; 6]) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| a[i][j])
}

fn to_array(m: &Matrix6<f64>) -> [[f64; 6]; 6] {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// `Λ` with `r_O = Λ r_P` for the rigid motions at `O` and at `P = O + p`; strains transform the
/// same way (`ψ_O = Λ ψ_P`), so both matrices about `P` are `Λᵀ X Λ`.
fn shift(p: [f64; 2]) -> Matrix6<f64> {
    let mut l = Matrix6::identity();
    // p̃ θ = p × θ with p = (p_x, p_y, 0).
    l[(0, 5)] = p[1];
    l[(1, 5)] = -p[0];
    l[(2, 3)] = -p[1];
    l[(2, 4)] = p[0];
    l
}

impl BeamMatrices {
    /// The same matrices about `point` (m).
    pub fn about(&self, point: [f64; 2]) -> BeamMatrices {
        let l = shift([point[0] - self.reference[0], point[1] - self.reference[1]]);
        let sym = |m: Matrix6<f64>| (m + m.transpose()) * 0.5;
        BeamMatrices {
            stiffness: to_array(&sym(l.transpose() * to_matrix(&self.stiffness) * l)),
            mass: to_array(&sym(l.transpose() * to_matrix(&self.mass) * l)),
            reference: point,
        }
    }

    /// The section's properties (see [`SectionProperties`]).
    pub fn properties(&self) -> Result<SectionProperties> {
        let numerical = |what: &str| Error::numerical(format!("cross-section properties: {what}"));
        let k = to_matrix(&self.stiffness);
        let f = k
            .cholesky()
            .ok_or_else(|| numerical("the stiffness is not positive definite"))?
            .inverse();
        let [x0, y0] = self.reference;
        let shear_centre = [x0 - f[(5, 1)] / f[(5, 5)], y0 + f[(5, 0)] / f[(5, 5)]];
        // No curvature under an axial force at (e_x, e_y): F₄₃ + F₄₄e_y − F₄₅e_x = 0 and
        // F₅₃ + F₅₄e_y − F₅₅e_x = 0.
        let a = Matrix2::new(-f[(3, 4)], f[(3, 3)], -f[(4, 4)], f[(4, 3)]);
        let e = a
            .lu()
            .solve(&Vector2::new(-f[(3, 2)], -f[(4, 2)]))
            .ok_or_else(|| numerical("the bending compliance is singular"))?;
        let elastic_centre = [x0 + e[0], y0 + e[1]];
        let at_elastic = self.about(elastic_centre);
        let fe = to_matrix(&at_elastic.stiffness)
            .cholesky()
            .ok_or_else(|| numerical("the stiffness is not positive definite"))?
            .inverse();
        let ea = 1.0 / fe[(2, 2)];

        let kaa = k.fixed_view::<3, 3>(0, 0).into_owned();
        let kab = k.fixed_view::<3, 3>(0, 3).into_owned();
        let kbb = k.fixed_view::<3, 3>(3, 3).into_owned();
        let c: Matrix3<f64> = kbb
            - kab.transpose()
                * kaa
                    .cholesky()
                    .ok_or_else(|| {
                        numerical("the shear and axial stiffness is not positive definite")
                    })?
                    .solve(&kab);
        let c = (c + c.transpose()) * 0.5;
        let (c44, c55, c45) = (c[(0, 0)], c[(1, 1)], c[(0, 1)]);
        let principal_angle = 0.5 * (2.0 * c45).atan2(c44 - c55);
        let mean = 0.5 * (c44 + c55);
        let radius = (0.25 * (c44 - c55).powi(2) + c45 * c45).sqrt();

        let at_shear = self.about(shear_centre);
        let fs = to_matrix(&at_shear.stiffness)
            .cholesky()
            .ok_or_else(|| numerical("the stiffness is not positive definite"))?
            .inverse();
        let shear = Matrix2::new(fs[(0, 0)], fs[(0, 1)], fs[(1, 0)], fs[(1, 1)])
            .try_inverse()
            .ok_or_else(|| numerical("the shear compliance is singular"))?;

        let m = self.mass[0][0];
        if !(m.is_finite() && m > 0.0) {
            return Err(numerical("the mass per length is not positive"));
        }
        let centre_of_mass = [x0 + self.mass[1][5] / m, y0 - self.mass[0][5] / m];
        let at_mass = self.about(centre_of_mass);
        let out = SectionProperties {
            ea,
            bending_torsion: std::array::from_fn(|i| std::array::from_fn(|j| c[(i, j)])),
            ei_principal: [mean + radius, mean - radius],
            principal_angle,
            gj: c[(2, 2)],
            shear_stiffness: [
                [shear[(0, 0)], shear[(0, 1)]],
                [shear[(1, 0)], shear[(1, 1)]],
            ],
            elastic_centre,
            shear_centre,
            mass: m,
            centre_of_mass,
            mass_moments: [at_mass.mass[3][3], at_mass.mass[4][4], -at_mass.mass[3][4]],
        };
        let all = [
            out.ea,
            out.gj,
            out.ei_principal[0],
            out.ei_principal[1],
            out.principal_angle,
            out.elastic_centre[0],
            out.elastic_centre[1],
            out.shear_centre[0],
            out.shear_centre[1],
        ];
        if all.iter().any(|v| !v.is_finite()) {
            return Err(numerical("non-finite properties"));
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::super::material::Orthotropic;
    use super::super::mesh::{graded, Mesh, Ply};
    use super::super::solve::analyse;

    /// A `b × h` rectangle centred at `centre`, its long side turned by `angle` from x.
    fn turned_rectangle(b: f64, h: f64, centre: [f64; 2], angle: f64) -> Mesh {
        let xs = graded(&[-b / 2.0, b / 2.0], &[16]);
        let ys = graded(&[-h / 2.0, h / 2.0], &[8]);
        let mut m = Mesh::grid(
            &xs,
            &ys,
            vec![Orthotropic::isotropic(70e9, 0.3, 2700.0)],
            |_| {
                Some(Ply {
                    material: 0,
                    fibre_angle: 0.0,
                    orientation: 0.0,
                })
            },
        )
        .unwrap();
        let (s, c) = angle.sin_cos();
        for p in &mut m.nodes {
            *p = [
                centre[0] + c * p[0] - s * p[1],
                centre[1] + s * p[0] + c * p[1],
            ];
        }
        m
    }

    #[test]
    fn principal_axes_turn_with_the_section() {
        let (b, h) = (0.2, 0.1);
        let straight = analyse(&turned_rectangle(b, h, [0.0, 0.0], 0.0), [0.0, 0.0])
            .unwrap()
            .properties()
            .unwrap();
        let angle = 0.3;
        let turned = analyse(&turned_rectangle(b, h, [0.4, -0.1], angle), [0.0, 0.0])
            .unwrap()
            .properties()
            .unwrap();
        // The stiffer axis is across the long side: at angle + π/2, wrapped to (−π/2, π/2].
        let expected = angle - std::f64::consts::FRAC_PI_2;
        assert!(
            (turned.principal_angle - expected).abs() < 1e-9,
            "{}",
            turned.principal_angle
        );
        for k in 0..2 {
            let (a, t) = (straight.ei_principal[k], turned.ei_principal[k]);
            assert!((a - t).abs() < 1e-9 * a, "EI {k}: {a} vs {t}");
        }
        assert!((turned.gj - straight.gj).abs() < 1e-9 * straight.gj);
        for c in [
            turned.elastic_centre,
            turned.shear_centre,
            turned.centre_of_mass,
        ] {
            assert!(
                (c[0] - 0.4).abs() < 1e-9 && (c[1] + 0.1).abs() < 1e-9,
                "{c:?}"
            );
        }
        let m = straight.mass_moments;
        assert!((m[0] - 2700.0 * b * h * h * h / 12.0).abs() < 1e-9 * m[0]);
        assert!((m[1] - 2700.0 * h * b * b * b / 12.0).abs() < 1e-9 * m[1]);
    }

    #[test]
    fn moving_there_and_back_changes_nothing() {
        let a = analyse(&turned_rectangle(0.2, 0.1, [0.1, 0.2], 0.7), [0.0, 0.0]).unwrap();
        let back = a.about([0.3, -0.5]).about([0.0, 0.0]);
        let worst = a
            .stiffness
            .iter()
            .flatten()
            .zip(back.stiffness.iter().flatten())
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        let scale = a
            .stiffness
            .iter()
            .flatten()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(worst < 1e-12 * scale);
    }
}
