//! Layup → section: classical lamination theory on a single-cell thin-walled closed contour
//! (docs/model.md §2.1), and the mass properties of the same contour (docs/model.md §2).
//!
//! The chain is `ply_stiffness` (Q) → `rotated_ply_stiffness` (Q̄(θ)) → `membrane_stiffness` (A)
//! → `reduced_wall_stiffness` (K11, K12, K22, hoop resultant free) → `cas_stiffness` (C22, C23,
//! C33 from closed-contour integrals). Contours are polylines; their geometric moments are
//! computed once per contour (`contour_moments`) and the stiffness integrals reduce to them,
//! because the wall stiffness is constant on each of the two CAS halves.
//!
//! Conventions:
//! - Wall axes: 1 = beam axis x, 2 = contour direction s; ply angle θ from the beam axis toward s.
//!   The contour is traversed counterclockwise in (y chordwise, z thickness), so `A_e > 0`.
//! - CAS (docs/model.md §2.1): `[θ]ₙ` where the mid-line lies at `z ≥ 0`, `[−θ]ₙ` where `z < 0`,
//!   `z` measured from the contour centroid. **Side walls** (a box's vertical walls, any segment
//!   that straddles `z = 0`) are split at `z = 0`: each half takes the angle of its side. This is
//!   the literal reading of the §2.1 rule and it reproduces Table 1 (see `tests/integration/laminate.rs`).
//! - Sign of C23: the paper's (docs/model.md §2): `C23 < 0` for `0 < θ < 70°` with `[θ]` on the upper
//!   wall. With the orientation above the thin-walled integral `2A_e∮(K12 z/K22)ds/∮ds/K22` is
//!   positive there, so we report its negative; the convention is fixed here, once, for every
//!   caller (the table source carries the paper's sign too).
//! - Elastic axis: at the contour's shear centre, taken equal to its centroid. That is exact for
//!   the box and the ellipse (doubly symmetric) and an approximation for the paper's contour,
//!   whose Eq. (1) mid-line has a slight camber (symmetric about a curved line, not a straight one).
//! - Thin walls: every area integral `∬ f dA` is `t∮ f ds` (docs/model.md §2.1 item 4); the walls' own
//!   through-thickness terms (order t²) are neglected, consistently with the stiffness formulas,
//!   which carry no wall bending (D) stiffness.

use crate::error::{Error, Result};
use crate::physics::section::{SectionProps, TABLE1_ANGLES};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Polyline segments for the smooth contours (ellipse, paper Eq. 1) at the coarse level; the fine
/// level doubles it and the two are Richardson-combined (see [`contour_moments_with`]). Measured
/// worst relative error of any contour moment at 512 (against 32× finer): 5e-10 for an ellipse
/// of aspect 20, 1.4e-9 at aspect 50, 2.5e-7 for the paper's contour (its z = 0 cuts fall
/// between nodes); 256 would leave the paper's contour at 1.05e-6, above [`CONTOUR_TOLERANCE`].
/// The box is exact with its four corners.
pub const SMOOTH_SEGMENTS: usize = 512;

/// Relative tolerance the contour integrals are converged to (tested in `tests/integration/laminate.rs`).
pub const CONTOUR_TOLERANCE: f64 = 1e-6;

/// The shape of a closed contour's mid-line (docs/model.md §2.1 "Contours").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContourShape {
    /// Rectangle of mid-line `width × height`.
    Box,
    /// Ellipse of mid-line semi-axes `a` (chordwise) and `b` (thickness).
    Ellipse,
    /// The paper's "integration line" Eq. (1), scaled by e = chord/4.
    Paper,
}

/// A closed contour's mid-line: its shape and the dimensions that shape reads (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contour {
    pub shape: ContourShape,
    /// Box mid-line width and height.
    pub width: f64,
    pub height: f64,
    /// Ellipse chordwise and thickness semi-axes.
    pub a: f64,
    pub b: f64,
    /// The section's chord: it scales the paper's contour (e = chord/4).
    pub chord: f64,
}

/// A CAS layup section (docs/model.md §2, §2.1): the laminate of each wall, the contour it is
/// laid on, the non-structural mass, and where the section sits relative to the aerodynamic
/// centre.
#[derive(Debug, Clone, PartialEq)]
pub struct LayupInput {
    pub material: PlyMaterial,
    /// Ply density ρ (kg/m³).
    pub density: f64,
    /// Ply thickness (m).
    pub ply_thickness: f64,
    /// Plies per wall.
    pub plies: usize,
    /// Ply angle θ (deg): `[θ]ₙ` on the upper wall, `[−θ]ₙ` on the lower.
    pub ply_angle: f64,
    /// Non-structural mass per length (kg/m) and its chordwise position from the elastic axis
    /// (m, positive aft).
    pub nonstructural_mass: f64,
    pub nonstructural_position: f64,
    pub contour: Contour,
    /// e_a = x_EA − x_AC (m).
    pub ea_offset: f64,
    /// The structural mass's centre from the elastic axis (m).
    pub cg_offset: f64,
    /// What the section belongs to, for messages.
    pub origin: String,
}

/// The paper's glass/epoxy ply (docs/model.md §2.1).
pub const PAPER_MATERIAL: PlyMaterial = PlyMaterial {
    e11: 25.8e9,
    e22: 8.7e9,
    nu12: 0.34,
    g12: 3.5e9,
};
/// The paper's ply density (kg/m³), ply thickness (m) and plies per wall.
pub const PAPER_DENSITY: f64 = 1672.0;
pub const PAPER_PLY_THICKNESS: f64 = 0.127e-3;
pub const PAPER_PLIES: usize = 6;

/// The flat box whose layup reproduces the paper's Table 1 (docs/model.md §2): mid-line
/// 18.33 × 2.470 mm, on the paper's chord.
pub const PAPER_BOX: Contour = Contour {
    shape: ContourShape::Box,
    width: 0.01833,
    height: 0.00247,
    a: 0.01833 / 2.0,
    b: 0.00247 / 2.0,
    chord: 0.01833,
};

impl LayupInput {
    /// The paper's laminate at `ply_angle` on [`PAPER_BOX`], elastic axis a quarter chord ahead
    /// of the aerodynamic centre.
    pub fn paper(ply_angle: f64) -> LayupInput {
        LayupInput {
            material: PAPER_MATERIAL,
            density: PAPER_DENSITY,
            ply_thickness: PAPER_PLY_THICKNESS,
            plies: PAPER_PLIES,
            ply_angle,
            nonstructural_mass: 0.0,
            nonstructural_position: 0.0,
            contour: PAPER_BOX,
            ea_offset: -PAPER_BOX.chord / 4.0,
            cg_offset: 0.0,
            origin: "paper Table 1 layup".into(),
        }
    }
}

/// Ply material in the wall's principal axes (docs/model.md §2.1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlyMaterial {
    /// E11 (Pa), fibre direction.
    pub e11: f64,
    /// E22 (Pa), transverse.
    pub e22: f64,
    /// ν12.
    pub nu12: f64,
    /// G12 (Pa).
    pub g12: f64,
}

/// Reduced (plane-stress) ply stiffness Q in its principal axes (Pa).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlyStiffness {
    pub q11: f64,
    pub q22: f64,
    pub q12: f64,
    pub q66: f64,
}

/// A 3×3 in-plane stiffness in Voigt order (1, 2, 6) = (x, s, xs).
pub type Stiffness3 = [[f64; 3]; 3];

/// Reduced wall stiffness with the hoop resultant N_ss free (N/m), docs/model.md §2.1 item 2.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallStiffness {
    pub k11: f64,
    pub k12: f64,
    pub k22: f64,
}

impl WallStiffness {
    /// Axial stiffness with the shear flow free, `K11 − K12²/K22` (the C33 integrand).
    pub fn axial_shear_free(&self) -> f64 {
        self.k11 - self.k12 * self.k12 / self.k22
    }
}

/// One CAS wall: its ply angle, membrane matrix and reduced stiffnesses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WallLaminate {
    /// Ply angle of every ply in this wall (deg).
    pub angle_deg: f64,
    /// Membrane stiffness A (N/m), Voigt order (x, s, xs).
    pub a: Stiffness3,
    pub k: WallStiffness,
}

/// Geometric moments of one part of the contour (the `z ≥ 0` or `z < 0` half), about the
/// contour centroid.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct ArcMoments {
    /// ∫ds (m).
    pub length: f64,
    /// ∫z ds (m²).
    pub z1: f64,
    /// ∫z² ds (m³).
    pub z2: f64,
    /// ∫y² ds (m³).
    pub y2: f64,
}

impl ArcMoments {
    fn add(&mut self, o: &ArcMoments) {
        self.length += o.length;
        self.z1 += o.z1;
        self.z2 += o.z2;
        self.y2 += o.y2;
    }
    fn richardson(coarse: &ArcMoments, fine: &ArcMoments) -> ArcMoments {
        ArcMoments {
            length: richardson(coarse.length, fine.length),
            z1: richardson(coarse.z1, fine.z1),
            z2: richardson(coarse.z2, fine.z2),
            y2: richardson(coarse.y2, fine.y2),
        }
    }
}

/// Everything the section needs from the contour's shape.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContourMoments {
    pub shape: ContourShape,
    /// ∮ds (m).
    pub perimeter: f64,
    /// Enclosed area A_e (m²).
    pub enclosed_area: f64,
    /// Polyline segments of the finest level used (before splitting at z = 0).
    pub segments: usize,
    /// The `z ≥ 0` part (ply angle +θ).
    pub upper: ArcMoments,
    /// The `z < 0` part (ply angle −θ).
    pub lower: ArcMoments,
}

/// Stiffnesses of a closed CAS section (N·m²).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CasStiffness {
    pub c22: f64,
    pub c23: f64,
    pub c33: f64,
}

/// Everything the `section` command shows: laminate, walls, contour, stiffness, mass.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LayupSection {
    /// CAS ply angle θ (deg).
    pub ply_angle_deg: f64,
    pub material: PlyMaterial,
    /// Ply density (kg/m³).
    pub density: f64,
    pub plies: usize,
    /// Ply thickness (m).
    pub ply_thickness: f64,
    /// Wall thickness t = plies × ply thickness (m).
    pub wall_thickness: f64,
    pub q: PlyStiffness,
    /// `[θ]ₙ` wall (z ≥ 0).
    pub upper: WallLaminate,
    /// `[−θ]ₙ` wall (z < 0).
    pub lower: WallLaminate,
    pub contour: ContourMoments,
    /// Wall cross-section area A0 = t∮ds (m²).
    pub wall_area: f64,
    /// Structural mass per length ρ t ∮ds (kg/m), without the non-structural mass.
    pub structural_mass: f64,
    /// Everything the structure model consumes (SI).
    pub props: SectionProps,
}

// ---------------------------------------------------------------------------------------------
// Classical lamination theory (docs/model.md §2.1 items 1–2)
// ---------------------------------------------------------------------------------------------

/// Plane-stress ply stiffness: `ν21 = ν12 E22/E11`, `Δ = 1 − ν12ν21`,
/// `Q11 = E11/Δ, Q22 = E22/Δ, Q12 = ν12E22/Δ, Q66 = G12` (docs/model.md §2.1 item 1).
/// The material must have passed [`check_material`] (Δ > 0).
pub fn ply_stiffness(m: &PlyMaterial) -> PlyStiffness {
    let delta = poisson_determinant(m);
    PlyStiffness {
        q11: m.e11 / delta,
        q22: m.e22 / delta,
        q12: m.nu12 * m.e22 / delta,
        q66: m.g12,
    }
}

/// `Δ = 1 − ν12ν21` with `ν21 = ν12 E22/E11`; positive for a physical ply.
pub fn poisson_determinant(m: &PlyMaterial) -> f64 {
    1.0 - m.nu12 * m.nu12 * m.e22 / m.e11
}

/// Q̄(θ): the ply stiffness rotated by θ (rad) from the beam axis toward the contour direction
/// (the standard transformation, e.g. Jones, *Mechanics of Composite Materials*, Eq. 2.84).
pub fn rotated_ply_stiffness(q: &PlyStiffness, theta: f64) -> Stiffness3 {
    let (n, m) = theta.sin_cos();
    let (m2, n2) = (m * m, n * n);
    let (m4, n4, m2n2) = (m2 * m2, n2 * n2, m2 * n2);
    let (q11, q22, q12, q66) = (q.q11, q.q22, q.q12, q.q66);
    let b11 = q11 * m4 + 2.0 * (q12 + 2.0 * q66) * m2n2 + q22 * n4;
    let b22 = q11 * n4 + 2.0 * (q12 + 2.0 * q66) * m2n2 + q22 * m4;
    let b12 = (q11 + q22 - 4.0 * q66) * m2n2 + q12 * (m4 + n4);
    let b66 = (q11 + q22 - 2.0 * q12 - 2.0 * q66) * m2n2 + q66 * (m4 + n4);
    let b16 = (q11 - q12 - 2.0 * q66) * m2 * m * n + (q12 - q22 + 2.0 * q66) * m * n2 * n;
    let b26 = (q11 - q12 - 2.0 * q66) * m * n2 * n + (q12 - q22 + 2.0 * q66) * m2 * m * n;
    [[b11, b12, b16], [b12, b22, b26], [b16, b26, b66]]
}

/// Membrane stiffness `A = Σ Q̄(θ_k) t_k` of a wall of `plies` identical plies at angle θ (rad).
pub fn membrane_stiffness(
    q: &PlyStiffness,
    theta: f64,
    plies: usize,
    ply_thickness: f64,
) -> Stiffness3 {
    let qb = rotated_ply_stiffness(q, theta);
    let t = plies as f64 * ply_thickness;
    qb.map(|row| row.map(|v| v * t))
}

/// Reduced wall stiffness with the hoop resultant free (docs/model.md §2.1 item 2):
/// `K11 = A11 − A12²/A22`, `K12 = A16 − A12A26/A22`, `K22 = A66 − A26²/A22`.
pub fn reduced_wall_stiffness(a: &Stiffness3) -> WallStiffness {
    let (a11, a12, a16) = (a[0][0], a[0][1], a[0][2]);
    let (a22, a26, a66) = (a[1][1], a[1][2], a[2][2]);
    WallStiffness {
        k11: a11 - a12 * a12 / a22,
        k12: a16 - a12 * a26 / a22,
        k22: a66 - a26 * a26 / a22,
    }
}

/// One wall of the CAS layup at ply angle `angle_deg` (degrees, kept as given for reports).
pub fn wall_laminate(
    q: &PlyStiffness,
    angle_deg: f64,
    plies: usize,
    ply_thickness: f64,
) -> WallLaminate {
    let a = membrane_stiffness(q, angle_deg.to_radians(), plies, ply_thickness);
    WallLaminate {
        angle_deg,
        a,
        k: reduced_wall_stiffness(&a),
    }
}

// ---------------------------------------------------------------------------------------------
// Closed-contour stiffness (docs/model.md §2.1 item 3)
// ---------------------------------------------------------------------------------------------

/// C22, C23, C33 of a closed CAS section with wall stiffness `upper` on `z ≥ 0` and `lower` on
/// `z < 0` (docs/model.md §2.1 item 3). Because K is constant on each part, the contour integrals
/// reduce to the parts' moments:
/// `∮ds/K22 = Σ L/K22`, `∮K12 z/K22 ds = Σ (K12/K22) ∫z ds`, `∮(K11 − K12²/K22)z² ds = Σ K̃11 ∫z² ds`.
/// C23 carries the paper's sign (see the module doc).
pub fn closed_section_stiffness(
    g: &ContourMoments,
    upper: &WallStiffness,
    lower: &WallStiffness,
) -> CasStiffness {
    let compliance = g.upper.length / upper.k22 + g.lower.length / lower.k22;
    let coupling = upper.k12 / upper.k22 * g.upper.z1 + lower.k12 / lower.k22 * g.lower.z1;
    let ae = g.enclosed_area;
    CasStiffness {
        c22: 4.0 * ae * ae / compliance,
        // `+ 0.0` turns the −0.0 of an uncoupled layup into 0.0 for display.
        c23: -2.0 * ae * coupling / compliance + 0.0,
        c33: upper.axial_shear_free() * g.upper.z2
            + lower.axial_shear_free() * g.lower.z2
            + coupling * coupling / compliance,
    }
}

/// C22, C23, C33 of a CAS section `[θ]ₙ` upper / `[−θ]ₙ` lower, θ in radians of any sign (the
/// preset key is limited to 0–90°; negative θ mirrors the layup and flips C23).
pub fn cas_stiffness(
    q: &PlyStiffness,
    theta: f64,
    plies: usize,
    ply_thickness: f64,
    g: &ContourMoments,
) -> CasStiffness {
    let wall = |t: f64| reduced_wall_stiffness(&membrane_stiffness(q, t, plies, ply_thickness));
    closed_section_stiffness(g, &wall(theta), &wall(-theta))
}

// ---------------------------------------------------------------------------------------------
// Contours (docs/model.md §2.1 "Contours")
// ---------------------------------------------------------------------------------------------

/// The contour as a closed polyline, counterclockwise, `segments` points for the smooth shapes
/// (the box is exact with its four corners and ignores `segments`).
pub fn contour_polyline(c: &Contour, segments: usize) -> Vec<[f64; 2]> {
    let mut pts: Vec<[f64; 2]> = match c.shape {
        ContourShape::Box => {
            let (w, h) = (c.width / 2.0, c.height / 2.0);
            vec![[w, -h], [w, h], [-w, h], [-w, -h]]
        }
        ContourShape::Ellipse => (0..segments)
            .map(|k| {
                let (s, co) = (2.0 * PI * k as f64 / segments as f64).sin_cos();
                [c.a * co, c.b * s]
            })
            .collect(),
        ContourShape::Paper => {
            let e = c.chord / 4.0;
            (0..segments)
                .map(|k| paper_midline(e, 2.0 * PI * k as f64 / segments as f64))
                .collect()
        }
    };
    if signed_area(&pts) < 0.0 {
        pts.reverse();
    }
    pts
}

/// The paper's Eq. (1) "integration line" as read in docs/model.md §2.1:
/// `y = e[exp(0.1(1−cosθ)) + exp(−0.1(1−cosθ)) cosθ]`, `z = e[exp(0.1(1−cosθ)) − exp(−0.1(1−cosθ)) sinθ]`.
pub fn paper_midline(e: f64, theta: f64) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    let grow = (0.1 * (1.0 - c)).exp();
    let decay = 1.0 / grow;
    [e * (grow + decay * c), e * (grow - decay * s)]
}

/// Shoelace area, positive for a counterclockwise polygon.
fn signed_area(pts: &[[f64; 2]]) -> f64 {
    let n = pts.len();
    (0..n)
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// Exact moments of a closed polygon, about its wall-line centroid, split into `z ≥ 0` and
/// `z < 0` parts. A segment that crosses `z = 0` is cut at the crossing so each piece goes to its
/// side (the side-wall rule of the module doc). On a straight segment `z` is linear, so
/// `∫z ds = L(z₁+z₂)/2` and `∫z² ds = L(z₁²+z₁z₂+z₂²)/3` are exact.
pub fn polyline_moments(shape: ContourShape, pts: &[[f64; 2]]) -> ContourMoments {
    let n = pts.len();
    let seg = |i: usize| (pts[i], pts[(i + 1) % n]);
    // Wall-line centroid: ∮y ds / ∮ds, ∮z ds / ∮ds.
    let (mut len, mut sy, mut sz) = (0.0, 0.0, 0.0);
    for i in 0..n {
        let (a, b) = seg(i);
        let l = segment_length(a, b);
        len += l;
        sy += l * (a[0] + b[0]) / 2.0;
        sz += l * (a[1] + b[1]) / 2.0;
    }
    let (yc, zc) = (sy / len, sz / len);
    let mut upper = ArcMoments::default();
    let mut lower = ArcMoments::default();
    for i in 0..n {
        let (a, b) = seg(i);
        let a = [a[0] - yc, a[1] - zc];
        let b = [b[0] - yc, b[1] - zc];
        if a[1] * b[1] < 0.0 {
            let f = a[1] / (a[1] - b[1]);
            let cut = [a[0] + f * (b[0] - a[0]), 0.0];
            add_segment(&mut upper, &mut lower, a, cut);
            add_segment(&mut upper, &mut lower, cut, b);
        } else {
            add_segment(&mut upper, &mut lower, a, b);
        }
    }
    ContourMoments {
        shape,
        perimeter: upper.length + lower.length,
        enclosed_area: signed_area(pts).abs(),
        segments: n,
        upper,
        lower,
    }
}

/// Chord length; plain `sqrt` rather than `hypot` (no overflow risk at section scales, and
/// `hypot` dominated the cost of a smooth contour).
fn segment_length(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dy, dz) = (b[0] - a[0], b[1] - a[1]);
    (dy * dy + dz * dz).sqrt()
}

/// Add one straight piece (which does not cross z = 0) to the part its midpoint lies in.
fn add_segment(upper: &mut ArcMoments, lower: &mut ArcMoments, a: [f64; 2], b: [f64; 2]) {
    let l = segment_length(a, b);
    let piece = ArcMoments {
        length: l,
        z1: l * (a[1] + b[1]) / 2.0,
        z2: l * (a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) / 3.0,
        y2: l * (a[0] * a[0] + a[0] * b[0] + b[0] * b[0]) / 3.0,
    };
    if a[1] + b[1] >= 0.0 {
        upper.add(&piece);
    } else {
        lower.add(&piece);
    }
}

/// `(4 f(h/2) − f(h))/3`: removes the h² error term of the polyline approximation.
fn richardson(coarse: f64, fine: f64) -> f64 {
    (4.0 * fine - coarse) / 3.0
}

/// The contour's moments, converged: the box's polyline is exact; a smooth contour is sampled
/// uniformly in its parameter with `2·segments` chords and, from every other point of the same
/// samples, `segments` chords. The polyline's error expands in even powers of the parameter step,
/// so the two are Richardson-combined (error O(h⁴), plus an O(h³) remainder from where a chord is
/// cut at z = 0, below 1e-7 relative at 512 segments).
pub fn contour_moments_with(c: &Contour, segments: usize) -> ContourMoments {
    let shape = c.shape;
    if shape == ContourShape::Box {
        return polyline_moments(shape, &contour_polyline(c, 4));
    }
    let fine_pts = contour_polyline(c, 2 * segments);
    let coarse_pts: Vec<[f64; 2]> = fine_pts.iter().step_by(2).copied().collect();
    let coarse = polyline_moments(shape, &coarse_pts);
    let fine = polyline_moments(shape, &fine_pts);
    ContourMoments {
        shape,
        perimeter: richardson(coarse.perimeter, fine.perimeter),
        enclosed_area: richardson(coarse.enclosed_area, fine.enclosed_area),
        segments: fine.segments,
        upper: ArcMoments::richardson(&coarse.upper, &fine.upper),
        lower: ArcMoments::richardson(&coarse.lower, &fine.lower),
    }
}

/// [`contour_moments_with`] at the production resolution [`SMOOTH_SEGMENTS`].
pub fn contour_moments(c: &Contour) -> ContourMoments {
    contour_moments_with(c, SMOOTH_SEGMENTS)
}

// ---------------------------------------------------------------------------------------------
// The section
// ---------------------------------------------------------------------------------------------

/// Everything about a layup section (docs/model.md §2, §2.1): laminate, walls, contour,
/// stiffnesses, mass properties.
///
/// Mass (thin walls, elastic axis at the centroid): `m = ρt∮ds + m_ns`,
/// `I = ρt∮(y²+z²)ds + m_ns x_ns²`, `m K_m1² = ρt∮z²ds`, `m K_m2² = ρt∮y²ds + m_ns x_ns²`,
/// `K_A² = ∮(y²+z²)ds / ∮ds` (wall area only, `A0 = t∮ds`). The non-structural mass `m_ns` is a
/// line mass at chordwise `x_ns` from the elastic axis. `cg_offset` is the centre of the
/// structural mass relative to the elastic axis; the non-structural mass moves it to the
/// mass-weighted mean `d = d_p + m_ns (x_ns − d_p)/m`.
pub fn layup_section(l: &LayupInput) -> Result<LayupSection> {
    let material = l.material;
    let q = ply_stiffness(&material);
    let angle = l.ply_angle;
    let upper = wall_laminate(&q, angle, l.plies, l.ply_thickness);
    let lower = wall_laminate(&q, -angle, l.plies, l.ply_thickness);
    let g = contour_moments(&l.contour);
    let stiff = closed_section_stiffness(&g, &upper.k, &lower.k);

    let t = l.plies as f64 * l.ply_thickness;
    let wall_area = t * g.perimeter;
    let structural_mass = l.density * wall_area;
    let (m_ns, x_ns) = (l.nonstructural_mass, l.nonstructural_position);
    let m = structural_mass + m_ns;
    let y2 = g.upper.y2 + g.lower.y2;
    let z2 = g.upper.z2 + g.lower.z2;
    let ns_inertia = m_ns * x_ns * x_ns;
    let d_p = l.cg_offset;
    let props = SectionProps {
        m,
        i: l.density * t * (y2 + z2) + ns_inertia,
        ka2: (y2 + z2) / g.perimeter,
        km1_2: l.density * t * z2 / m,
        km2_2: (l.density * t * y2 + ns_inertia) / m,
        chord: l.contour.chord,
        ea_offset: l.ea_offset,
        cg_offset: d_p + m_ns * (x_ns - d_p) / m,
        c22: stiff.c22,
        c23: stiff.c23,
        c33: stiff.c33,
    };
    if ![props.m, props.i, props.c22, props.c23, props.c33]
        .iter()
        .all(|v| v.is_finite())
    {
        return Err(Error::numerical(format!(
            "{}: layup section gave non-finite properties {props:?}",
            l.origin
        )));
    }
    Ok(LayupSection {
        ply_angle_deg: l.ply_angle,
        material,
        density: l.density,
        plies: l.plies,
        ply_thickness: l.ply_thickness,
        wall_thickness: t,
        q,
        upper,
        lower,
        contour: g,
        wall_area,
        structural_mass,
        props,
    })
}

/// The section properties the structure model consumes, from the layup: m, I, K_A², K_m1²,
/// K_m2² from the contour, C22/C23/C33 from CLT; chord and e_a as given; d as in
/// [`layup_section`].
pub fn layup_section_props(l: &LayupInput) -> Result<SectionProps> {
    Ok(layup_section(l)?.props)
}

/// The paper's Table 1 recomputed from the layup: the paper's laminate on its flat box
/// ([`LayupInput::paper`]) at each of [`TABLE1_ANGLES`]. Named rather than taken from the
/// defaults, so it stays the paper's.
pub fn paper_table1_from_layup() -> Result<Vec<(f64, SectionProps)>> {
    TABLE1_ANGLES
        .iter()
        .map(|&deg| Ok((deg, layup_section_props(&LayupInput::paper(deg))?)))
        .collect()
}
