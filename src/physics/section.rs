//! Cross-section properties from the three stiffness sources (MODEL.md §2).

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
