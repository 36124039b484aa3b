//! The cubic Hermite interpolation of a value and its slope over an interval: the beam
//! elements' bending shapes (docs/model.md §11.3) and the curved reference axis between its
//! stations (§11.9).

/// Hermite cubics (values, first and second z-derivatives) for `[w_a, w'_a, w_b, w'_b]` at local
/// `s` of an interval of length `h`.
pub fn hermite(s: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let (s2, s3) = (s * s, s * s * s);
    (
        [
            1.0 - 3.0 * s2 + 2.0 * s3,
            h * (s - 2.0 * s2 + s3),
            3.0 * s2 - 2.0 * s3,
            h * (s3 - s2),
        ],
        [
            (-6.0 * s + 6.0 * s2) / h,
            1.0 - 4.0 * s + 3.0 * s2,
            (6.0 * s - 6.0 * s2) / h,
            3.0 * s2 - 2.0 * s,
        ],
        [
            (-6.0 + 12.0 * s) / (h * h),
            (-4.0 + 6.0 * s) / h,
            (6.0 - 12.0 * s) / (h * h),
            (6.0 * s - 2.0) / h,
        ],
    )
}
