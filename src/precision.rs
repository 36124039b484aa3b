//! Numbers with the precision they carry. A value computed from decimal inputs (a grid point
//! `from + (to − from)·i/(n − 1)`, the midpoint of a bracket) picks up float noise in its last
//! bits: `0.1 + 0.2` is `0.30000000000000004`, and a grid from −0.1 to 0.3 ends past 0.3 (out of
//! the key's range). Such a value is snapped to the decimal its inputs meant before it is used,
//! so everything that prints it afterwards (an error naming the value, a validation message)
//! prints the decimal, and says the truth about the value that was tried.

/// Significant digits a computed value keeps: float noise sits near the 16th, and no input of
/// the program carries more than 12.
pub const SIGNIFICANT: usize = 12;

/// `v` rounded to [`SIGNIFICANT`] significant digits: the nearest double to the decimal it
/// stands for (`0.30000000000000004` → `0.3`). Non-finite values and zero pass unchanged.
pub fn carried(v: f64) -> f64 {
    if !v.is_finite() || v == 0.0 {
        return v;
    }
    format!("{:.*e}", SIGNIFICANT - 1, v).parse().unwrap_or(v)
}

/// `points` evenly spaced values from `from` to `to`, both ends exact and every point
/// [`carried`] (at least the two ends).
pub fn grid(from: f64, to: f64, points: usize) -> Vec<f64> {
    let n = points.max(2);
    (0..n)
        .map(|i| match i {
            0 => from,
            _ if i == n - 1 => to,
            _ => carried(from + (to - from) * i as f64 / (n - 1) as f64),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_noise_is_dropped_and_the_decimal_kept() {
        assert_eq!(carried(0.1 + 0.2), 0.3);
        assert_eq!(carried(11.269_913_000_000_002).to_string(), "11.269913");
        assert_eq!(carried(1e-20 * 3.0), 3e-20);
        assert_eq!(carried(0.0), 0.0);
        assert!(carried(f64::NAN).is_nan());
    }

    #[test]
    fn a_grid_ends_where_it_is_asked_to() {
        // From −0.1 to 0.3 the plain formula ends at 0.30000000000000004.
        assert_eq!(-0.1 + (0.3 - -0.1) * 20.0 / 20.0, 0.300_000_000_000_000_04);
        let g = grid(-0.1, 0.3, 21);
        assert_eq!((g[0], g[20]), (-0.1, 0.3));
        assert_eq!(g[3].to_string(), "-0.04");
        assert_eq!(grid(0.0, 15.0, 41)[3], 1.125);
    }
}
