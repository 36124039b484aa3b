//! A section's 6×6 (Timoshenko) stiffness reduced to the Euler–Bernoulli section of
//! docs/model.md §11.2, and the turn from a file's section frame into ours (§11.5, §11.6).
//!
//! A 6×6 stiffness relates the forces and moments `(F₁, F₂, F₃, M₁, M₂, M₃)` at its origin to the
//! strains `(γ₁, γ₂, ε₃, κ₁, κ₂, κ₃)`: transverse shear along the file's axes 1 and 2, extension,
//! and the rotation rates about axes 1, 2 and 3 (bending and twist). The file's `(1, 2, 3)` is
//! right-handed with 3 along the blade. The Euler–Bernoulli section keeps the curvatures and the
//! twist rate and lets shear and extension follow them: a slender blade carries its shear and
//! axial forces with strains far below the bending ones, so the bending–torsion stiffness is the
//! one with those forces zero, the Schur complement `C = K_bb − K_ba K_aa⁻¹ K_ab` (b: bending
//! and twist, a: shear and extension). Moments about any point agree when the forces are zero,
//! so `C` does not depend on the origin the file chose. What does depend on it, where the
//! forces act, becomes two offsets: the shear centre (a transverse force through it does not
//! twist the section) and the tension centre (an axial force through it does not bend it), both
//! read from the flexibility `S = K⁻¹`. With no shear or extension coupling (`K_ab = 0`) `C` is
//! exactly `K_bb` and both centres are the origin.

use super::{BeamSection, ShearFlexibility};
use nalgebra::{Matrix2, Matrix3, Matrix5, Matrix6};

/// How a file's section axes lie in ours: `ours = A · file` for positions, `A` orthogonal.
///
/// Our frame (docs/model.md §11.1) has ξ normal to the chord (downwind) and η along the chord
/// toward the leading edge; the files' right-handed frames put their chordwise axis toward the
/// trailing edge (BeamDyn) or swap the two (HAWC2), so `A` may be a reflection (`det A = −1`),
/// which reverses the sense of a twist about the span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FileFrame {
    a: Matrix2<f64>,
}

/// The bending–torsion part of a section in our frame (docs/model.md §11.2) and where the shear
/// and tension centres lie from the file's origin (m, `[ξ, η]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClassicalSection {
    pub ei_flap: f64,
    pub ei_edge: f64,
    pub ei_cross: f64,
    pub gj: f64,
    pub flap_twist: f64,
    pub edge_twist: f64,
    pub shear_centre: [f64; 2],
    pub tension_centre: [f64; 2],
    /// The transverse-shear flexibility about the shear centre (docs/model.md §11.2).
    pub shear: ShearFlexibility,
}

impl ClassicalSection {
    /// The table station at span `z` with this stiffness part, the structural `twist` and the
    /// mass part (`mass`, centre of mass `cg`, second moments `inertia`, in our frame).
    pub fn at_station(
        self,
        z: f64,
        twist: f64,
        mass: f64,
        cg: [f64; 2],
        inertia: [f64; 3],
    ) -> BeamSection {
        BeamSection {
            z,
            mass,
            cg,
            inertia,
            ei_flap: self.ei_flap,
            ei_edge: self.ei_edge,
            ei_cross: self.ei_cross,
            gj: self.gj,
            flap_twist: self.flap_twist,
            edge_twist: self.edge_twist,
            twist,
            shear_centre: self.shear_centre,
            tension_centre: self.tension_centre,
            shear: self.shear,
        }
    }
}

impl FileFrame {
    /// `ours = A · file` with `A` given row by row; it must be orthogonal (checked to 1e-12).
    pub fn new(rows: [[f64; 2]; 2]) -> Option<FileFrame> {
        let a = Matrix2::new(rows[0][0], rows[0][1], rows[1][0], rows[1][1]);
        let off = (a.transpose() * a - Matrix2::identity()).abs().max();
        (off <= 1e-12).then_some(FileFrame { a })
    }

    /// This frame followed by a turn of the file's axes by `angle` (rad) about its axis 3, in the
    /// file's own (right-hand) sense: the frame of a matrix given along principal axes turned by
    /// `angle` from the file's section axes.
    pub fn turned(&self, angle: f64) -> FileFrame {
        let (s, c) = angle.sin_cos();
        FileFrame {
            a: self.a * Matrix2::new(c, -s, s, c),
        }
    }

    /// A file position (a vector in the section plane) in our frame (docs/model.md §11.5–§11.6).
    pub fn position(&self, file: [f64; 2]) -> [f64; 2] {
        let p = self.a * nalgebra::Vector2::new(file[0], file[1]);
        [p[0], p[1]]
    }

    /// The second moments `[∫ρξ², ∫ρη², ∫ρξη]` of a mass given as the file's symmetric
    /// `[[∫ρx₁², ∫ρx₁x₂], [∫ρx₁x₂, ∫ρx₂²]]`: `A J Aᵀ` (docs/model.md §11.5–§11.6).
    pub fn second_moments(&self, file: [[f64; 2]; 2]) -> [f64; 3] {
        let j = Matrix2::new(file[0][0], file[0][1], file[1][0], file[1][1]);
        let o = self.a * j * self.a.transpose();
        [o[(0, 0)], o[(1, 1)], o[(0, 1)]]
    }

    /// `κ_file = T (κ_ξ, κ_η, φ')`: see [`FileFrame::bending_torsion`].
    fn curvature_map(&self) -> Matrix3<f64> {
        let j = Matrix2::new(0.0, -1.0, 1.0, 0.0);
        let mut t = Matrix3::zeros();
        t.fixed_view_mut::<2, 2>(0, 0)
            .copy_from(&(j * self.a.transpose()));
        t[(2, 2)] = self.a.determinant().signum();
        t
    }

    /// The shear flexibility in our terms of a file's flexibility `s` of the strains
    /// `(γ₁, γ₂, κ₁, κ₂, κ₃)` about the shear centre. A shear strain is a displacement slope, so
    /// `γ_file = Aᵀ γ`; with the curvatures' map `T` the strains map by `G = diag(Aᵀ, T)`,
    /// orthogonal, and the flexibility in ours is `Gᵀ s G` (docs/model.md §11.5).
    pub fn shear_flexibility(&self, s: &Matrix5<f64>) -> ShearFlexibility {
        let mut g = Matrix5::zeros();
        g.fixed_view_mut::<2, 2>(0, 0)
            .copy_from(&self.a.transpose());
        g.fixed_view_mut::<3, 3>(2, 2)
            .copy_from(&self.curvature_map());
        let o = g.transpose() * s * g;
        ShearFlexibility {
            strain: [o[(0, 0)], o[(1, 1)], o[(0, 1)]],
            coupling: [
                o[(0, 2)],
                o[(0, 3)],
                o[(0, 4)],
                o[(1, 2)],
                o[(1, 3)],
                o[(1, 4)],
            ],
        }
    }

    /// The shear flexibility of shear stiffnesses `k₁, k₂` (N) along the file's axes 1, 2 at the
    /// shear centre, uncoupled (a HAWC2 classic row's `k_x G A`, `k_y G A`).
    pub fn shear_stiffness(&self, k: [f64; 2]) -> ShearFlexibility {
        let mut s = Matrix5::zeros();
        s[(0, 0)] = 1.0 / k[0];
        s[(1, 1)] = 1.0 / k[1];
        self.shear_flexibility(&s)
    }

    /// The bending–torsion stiffness `C` (file axes, strains `κ₁, κ₂, κ₃`) in our terms.
    ///
    /// A displacement curvature `w''` in the file's axes is `Aᵀ` of ours, and the file's bending
    /// strains are rotation rates, `κ₁ = −w₂''`, `κ₂ = w₁''`; the twist keeps its sense when
    /// `det A = 1` and reverses it otherwise. So `κ_file = T (κ_ξ, κ_η, φ')` with
    /// `T = diag(J Aᵀ, det A)`, `J = [[0, −1], [1, 0]]`, and our energy matrix is `Tᵀ C T`, read
    /// against docs/model.md §11.2's `EI_ξ, EI_η, EI_ξη, GJ, −g_ξ, −g_η`.
    pub fn bending_torsion(&self, c: &Matrix3<f64>) -> [f64; 6] {
        let t = self.curvature_map();
        let o = t.transpose() * c * t;
        [
            o[(0, 0)],
            o[(1, 1)],
            o[(0, 1)],
            o[(2, 2)],
            -o[(0, 2)],
            -o[(1, 2)],
        ]
    }
}

/// The Euler–Bernoulli section of a 6×6 stiffness `k` (docs/model.md §11.2, module docs) whose
/// axes lie in ours as `frame` says; centres from the matrix's origin. `Err` names what is
/// singular.
pub fn reduce(k: &[[f64; 6]; 6], frame: &FileFrame) -> Result<ClassicalSection, String> {
    let block = |r: usize, c: usize| Matrix3::from_fn(|i, j| k[r + i][c + j]);
    let (k_aa, k_ab, k_bb) = (block(0, 0), block(0, 3), block(3, 3));
    let k_aa_inv = k_aa
        .try_inverse()
        .ok_or("the shear–extension block K11…K33 is singular")?;
    // X = K_aa⁻¹ K_ab: exactly zero when nothing couples shear or extension to bending.
    let x = k_aa_inv * k_ab;
    let c = k_bb - k_ab.transpose() * x;
    let s_bb = c
        .try_inverse()
        .ok_or("the bending–torsion stiffness (Schur complement of K44…K66) is singular")?;
    // Flexibility between (F₁, F₂, F₃) and (κ₁, κ₂, κ₃): S_ab = −X S_bb.
    let s_ab = -x * s_bb;
    let (s66, s44, s55, s45) = (s_bb[(2, 2)], s_bb[(0, 0)], s_bb[(1, 1)], s_bb[(0, 1)]);
    // A transverse force through (s₁, s₂) adds M₃ = s₁F₂ − s₂F₁; no twist rate for either force.
    let shear = [-s_ab[(1, 2)] / s66, s_ab[(0, 2)] / s66];
    // An axial force through (e₁, e₂) adds M₁ = e₂F₃, M₂ = −e₁F₃; no curvature κ₁ or κ₂.
    let (s43, s53) = (s_ab[(2, 0)], s_ab[(2, 1)]);
    let det = s44 * s55 - s45 * s45;
    let tension = [(s44 * s53 - s45 * s43) / det, (s45 * s53 - s55 * s43) / det];
    if !(s66.is_finite() && s66 > 0.0 && det.is_finite() && det > 0.0) {
        return Err("the bending–torsion flexibility is not positive definite".into());
    }
    let [ei_flap, ei_edge, ei_cross, gj, flap_twist, edge_twist] = frame.bending_torsion(&c);
    Ok(ClassicalSection {
        ei_flap,
        ei_edge,
        ei_cross,
        gj,
        flap_twist,
        edge_twist,
        shear_centre: frame.position(shear),
        tension_centre: frame.position(tension),
        shear: frame.shear_flexibility(&shear_centre_flexibility(k, shear)?),
    })
}

/// The flexibility of `(γ₁, γ₂, κ₁, κ₂, κ₃)` about the shear centre `s` (from the matrix's
/// origin, file axes), with the axial force zero: the whole flexibility `K⁻¹` with the shear
/// strains carried to `s` (`γ₁ − κ₃s₂`, `γ₂ + κ₃s₁`), the axial row and column dropped.
fn shear_centre_flexibility(k: &[[f64; 6]; 6], s: [f64; 2]) -> Result<Matrix5<f64>, String> {
    let flexibility = Matrix6::from_fn(|i, j| k[i][j])
        .try_inverse()
        .ok_or("the 6×6 stiffness is singular")?;
    let mut carry = Matrix6::identity();
    carry[(0, 5)] = -s[1];
    carry[(1, 5)] = s[0];
    let at_shear_centre = carry * flexibility * carry.transpose();
    const KEPT: [usize; 5] = [0, 1, 3, 4, 5];
    Ok(Matrix5::from_fn(|i, j| at_shear_centre[(KEPT[i], KEPT[j])]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::SMatrix;

    /// A section whose shear part acts at `s` and axial part at `e` (from the origin): strains
    /// carried from the origin to those points, `γ₁ − κ₃s₂`, `γ₂ + κ₃s₁`, `ε + κ₁e₂ − κ₂e₁`.
    fn offset_section(s: [f64; 2], e: [f64; 2], diag: [f64; 6]) -> [[f64; 6]; 6] {
        let mut ts = SMatrix::<f64, 6, 6>::identity();
        ts[(0, 5)] = -s[1];
        ts[(1, 5)] = s[0];
        let mut te = SMatrix::<f64, 6, 6>::identity();
        te[(2, 3)] = e[1];
        te[(2, 4)] = -e[0];
        let part = |idx: [usize; 3]| {
            let mut d = SMatrix::<f64, 6, 6>::zeros();
            for i in idx {
                d[(i, i)] = diag[i];
            }
            d
        };
        let k = ts.transpose() * part([0, 1, 5]) * ts + te.transpose() * part([2, 3, 4]) * te;
        std::array::from_fn(|i| std::array::from_fn(|j| k[(i, j)]))
    }

    #[test]
    fn centres_and_stiffness_come_back_from_an_offset_matrix() {
        let (s, e) = ([0.3, -0.7], [-0.2, 0.45]);
        let diag = [4.0e8, 2.5e8, 2.0e10, 3.0e9, 8.0e9, 6.0e8];
        let k = offset_section(s, e, diag);
        let same = FileFrame::new([[1.0, 0.0], [0.0, 1.0]]).unwrap();
        let c = reduce(&k, &same).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
        assert!(
            close(c.shear_centre[0], s[0]) && close(c.shear_centre[1], s[1]),
            "{c:?}"
        );
        assert!(
            close(c.tension_centre[0], e[0]) && close(c.tension_centre[1], e[1]),
            "{c:?}"
        );
        // Bending about axis 1 curves the beam along axis 2 (our η): the edge stiffness.
        assert!(close(c.ei_edge, diag[3]) && close(c.ei_flap, diag[4]) && close(c.gj, diag[5]));
        assert!(c.ei_cross.abs() < 1e-6 * diag[3] && c.flap_twist.abs() < 1e-6 * diag[5]);
    }

    #[test]
    fn an_uncoupled_matrix_reduces_to_its_diagonal_exactly() {
        let diag = [4.0e8, 2.5e8, 2.0e10, 3.0e9, 8.0e9, 6.0e8];
        let k: [[f64; 6]; 6] =
            std::array::from_fn(|i| std::array::from_fn(|j| if i == j { diag[i] } else { 0.0 }));
        let reflected = FileFrame::new([[1.0, 0.0], [0.0, -1.0]]).unwrap();
        let c = reduce(&k, &reflected).unwrap();
        assert_eq!((c.ei_edge, c.ei_flap, c.gj), (diag[3], diag[4], diag[5]));
        assert_eq!(c.shear_centre, [0.0, 0.0]);
        assert_eq!(c.tension_centre, [0.0, 0.0]);
    }

    /// A reflection of the chordwise axis reverses the twist but not the flap curvature, so the
    /// flap–twist coupling changes sign with it; a turn of the principal axes by 90° swaps flap
    /// and edge.
    #[test]
    fn reflections_reverse_couplings_and_turns_swap_axes() {
        let c = Matrix3::new(3.0e9, 0.0, 0.0, 0.0, 8.0e9, 1.0e8, 0.0, 1.0e8, 6.0e8);
        let same = FileFrame::new([[1.0, 0.0], [0.0, 1.0]]).unwrap();
        let mirror = FileFrame::new([[1.0, 0.0], [0.0, -1.0]]).unwrap();
        let a = same.bending_torsion(&c);
        let b = mirror.bending_torsion(&c);
        assert!(a[4] != 0.0 && a[4] == -b[4], "{a:?} {b:?}");
        let turned = same.turned(std::f64::consts::FRAC_PI_2).bending_torsion(&c);
        assert!((turned[0] - a[1]).abs() < 1e-3 && (turned[1] - a[0]).abs() < 1e-3);
        assert!(FileFrame::new([[1.0, 1.0], [0.0, 1.0]]).is_none());
    }
}
