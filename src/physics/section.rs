//! Cross-section properties from the three stiffness sources (docs/model.md §2).

use crate::error::{Error, Result};

/// Per-length section properties in SI, whatever their source.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SectionProps {
    /// m (kg/m).
    pub m: f64,
    /// I (kg·m), polar mass moment about the elastic axis.
    pub i: f64,
    /// K_A² (m²).
    pub ka2: f64,
    /// K_m1² (m²).
    pub km1_2: f64,
    /// K_m2² (m²).
    pub km2_2: f64,
    /// Chord c (m).
    pub chord: f64,
    /// e_a = x_EA − x_AC (m).
    pub ea_offset: f64,
    /// d = x_cg − x_EA (m).
    pub cg_offset: f64,
    /// Torsion stiffness (N·m²).
    pub c22: f64,
    /// Bending–twist coupling (N·m²); the paper's sign (< 0 for 0 < θ < 70°).
    pub c23: f64,
    /// Flap bending stiffness (N·m²).
    pub c33: f64,
}

/// `s`, if every property is finite: a non-finite one would poison every matrix downstream, so
/// stop here with its name.
pub fn checked(s: SectionProps) -> Result<SectionProps> {
    check_finite(&s)?;
    Ok(s)
}

fn check_finite(s: &SectionProps) -> Result<()> {
    let fields = [
        ("m", s.m),
        ("I", s.i),
        ("K_A²", s.ka2),
        ("K_m1²", s.km1_2),
        ("K_m2²", s.km2_2),
        ("chord", s.chord),
        ("e_a", s.ea_offset),
        ("d", s.cg_offset),
        ("C22", s.c22),
        ("C23", s.c23),
        ("C33", s.c33),
    ];
    match fields.iter().find(|(_, v)| !v.is_finite()) {
        Some((name, v)) => Err(Error::numerical(format!(
            "section property {name} = {v} is not finite"
        ))),
        None => Ok(()),
    }
}

/// Ply angles (deg) of the paper's Table 1.
pub const TABLE1_ANGLES: [f64; 7] = [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0];

/// The paper's Table 1 as printed (its mixed units; docs/model.md §2): rows C22, C23, C33.
pub const TABLE1_PRINTED: [[f64; 7]; 3] = [
    [
        5.2588e5, 6.6934e5, 9.0369e5, 9.0509e5, 7.3084e5, 5.7973e5, 5.2588e5,
    ],
    [
        -1.1764e-2, -2.6511e2, -3.1014e2, -1.5919e2, -3.0458e1, 9.0908, 3.9370e-15,
    ],
    [
        1.1491, 9.8755e-1, 6.8027e-1, 4.5931e-1, 3.8620e-1, 3.8264e-1, 3.8749e-1,
    ],
];

/// SI factors that correct Table 1's units (docs/model.md §2): C22 ×1e-6, C23 ×1e-3, C33 ×1.
pub const TABLE1_UNIT_FACTORS: [f64; 3] = [1e-6, 1e-3, 1.0];

/// Table 1 in SI at its own ply angles: rows C22, C23, C33 (N·m²).
pub fn table1_si() -> [[f64; 7]; 3] {
    let mut t = TABLE1_PRINTED;
    for (row, f) in t.iter_mut().zip(TABLE1_UNIT_FACTORS) {
        row.iter_mut().for_each(|v| *v *= f);
    }
    t
}

/// `[C22, C23, C33]` (N·m²) at ply angle `theta_deg` ∈ [0°, 90°] (the range of
/// `section.ply_angle`) from Table 1 (docs/model.md §2), by a
/// cubic spline whose end conditions come from the symmetry of a CAS section rather than being
/// invented: flipping every ply angle mirrors the section, so C22 and C33 are even in θ and C23 is
/// odd; fibre directions repeat every 180°, so θ = 90° is a symmetry point too. Hence C22 and C33
/// have zero slope at 0° and 90° (clamped spline, f' = 0) and C23 has zero curvature there (natural
/// spline, f'' = 0) — both exact properties of the true curves. The result is C², passes through
/// every table entry, and reproduces the table exactly at its nodes.
pub fn table1_stiffness(theta_deg: f64) -> [f64; 3] {
    let t = table1_si();
    [
        CubicSpline::new(&TABLE1_ANGLES, &t[0], EndCondition::ZeroSlope).eval(theta_deg),
        CubicSpline::new(&TABLE1_ANGLES, &t[1], EndCondition::ZeroCurvature).eval(theta_deg),
        CubicSpline::new(&TABLE1_ANGLES, &t[2], EndCondition::ZeroSlope).eval(theta_deg),
    ]
}

/// End condition of an interpolating cubic spline, applied at both ends.
#[derive(Debug, Clone, Copy)]
enum EndCondition {
    /// f' = 0 (clamped).
    ZeroSlope,
    /// f'' = 0 (natural).
    ZeroCurvature,
}

/// Interpolating cubic spline in the second-derivative form.
struct CubicSpline<'a> {
    x: &'a [f64],
    y: &'a [f64],
    /// Second derivatives at the knots.
    m: Vec<f64>,
}

impl<'a> CubicSpline<'a> {
    /// Solves the tridiagonal system for the knot curvatures (Thomas algorithm; the system is
    /// diagonally dominant for both end conditions).
    fn new(x: &'a [f64], y: &'a [f64], end: EndCondition) -> CubicSpline<'a> {
        let n = x.len();
        let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let slope: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
        let (mut sub, mut diag, mut sup, mut rhs) =
            (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 1..n - 1 {
            sub[i] = h[i - 1];
            diag[i] = 2.0 * (h[i - 1] + h[i]);
            sup[i] = h[i];
            rhs[i] = 6.0 * (slope[i] - slope[i - 1]);
        }
        match end {
            EndCondition::ZeroCurvature => {
                diag[0] = 1.0;
                diag[n - 1] = 1.0;
            }
            EndCondition::ZeroSlope => {
                diag[0] = 2.0 * h[0];
                sup[0] = h[0];
                rhs[0] = 6.0 * slope[0];
                sub[n - 1] = h[n - 2];
                diag[n - 1] = 2.0 * h[n - 2];
                rhs[n - 1] = -6.0 * slope[n - 2];
            }
        }
        for i in 1..n {
            let w = sub[i] / diag[i - 1];
            diag[i] -= w * sup[i - 1];
            rhs[i] -= w * rhs[i - 1];
        }
        let mut m = vec![0.0; n];
        m[n - 1] = rhs[n - 1] / diag[n - 1];
        for i in (0..n - 1).rev() {
            m[i] = (rhs[i] - sup[i] * m[i + 1]) / diag[i];
        }
        CubicSpline { x, y, m }
    }

    fn eval(&self, t: f64) -> f64 {
        let n = self.x.len();
        let i = self.x[..n - 1].iter().rposition(|&xi| xi <= t).unwrap_or(0);
        let h = self.x[i + 1] - self.x[i];
        let a = (self.x[i + 1] - t) / h;
        let b = (t - self.x[i]) / h;
        a * self.y[i]
            + b * self.y[i + 1]
            + ((a * a * a - a) * self.m[i] + (b * b * b - b) * self.m[i + 1]) * h * h / 6.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_source_is_exact_at_nodes() {
        let t = table1_si();
        for (k, &a) in TABLE1_ANGLES.iter().enumerate() {
            let c = table1_stiffness(a);
            for row in 0..3 {
                assert!((c[row] - t[row][k]).abs() <= 1e-12 * t[row][k].abs().max(1e-12));
            }
        }
    }

    #[test]
    fn spline_end_conditions_hold() {
        let d = 1e-4;
        let s0 = table1_stiffness(0.0);
        let s1 = table1_stiffness(d);
        // C22 and C33: zero slope at 0°, so a first difference is O(d) relative to the table step.
        assert!(((s1[0] - s0[0]) / d).abs() < 1e-6 * s0[0]);
        let e0 = table1_stiffness(90.0);
        let e1 = table1_stiffness(90.0 - d);
        assert!(((e1[2] - e0[2]) / d).abs() < 1e-6 * e0[2]);
    }

    #[test]
    fn spline_reproduces_a_cubic_with_matching_ends() {
        // f = x²(3 − 2x) on [0, 1] has f'(0) = f'(1) = 0: a clamped spline reproduces it exactly.
        let x = [0.0, 0.2, 0.5, 0.7, 1.0];
        let y: Vec<f64> = x.iter().map(|x| x * x * (3.0 - 2.0 * x)).collect();
        let s = CubicSpline::new(&x, &y, EndCondition::ZeroSlope);
        for t in [0.05, 0.33, 0.61, 0.93] {
            assert!((s.eval(t) - t * t * (3.0 - 2.0 * t)).abs() < 1e-13);
        }
    }
}
