//! A root of a scalar function inside a bracket, by Brent's method (inverse quadratic
//! interpolation and secant steps, falling back to bisection whenever they would leave the
//! bracket or shrink it too slowly).
//!
//! Why Brent and no crate: the steady BEM solves one residual per blade station and the pitch
//! search of the operating curve wraps the whole BEM in another root find, so the finder runs
//! thousands of times per operating curve. A bracket guarantees convergence (the BEM's residual
//! is continuous on each of its brackets, Ning 2014), and Brent converges superlinearly on the
//! smooth stretches in between. No well-kept crate offers just this without a large numerics
//! framework around it; the method is the textbook one (Brent 1973, ch. 4).

/// The root of `f` between `a` and `b`, where `f(a)` and `f(b)` differ in sign (or one is zero),
/// to an absolute tolerance `tol` in x. `None` when the ends do not bracket a sign change or `f`
/// returns a non-finite value.
pub fn brent(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> Option<f64> {
    let (fa, fb) = (f(a), f(b));
    brent_with_values(&mut f, a, fa, b, fb, tol)
}

/// [`brent`] when `f(a) = fa` and `f(b) = fb` are already known (the caller's bracket search
/// evaluated them).
pub fn brent_with_values(
    f: &mut impl FnMut(f64) -> f64,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    tol: f64,
) -> Option<f64> {
    let (mut a, mut fa, mut b, mut fb) = (a, fa, b, fb);
    if !(fa.is_finite() && fb.is_finite()) {
        return None;
    }
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    if fa.signum() == fb.signum() {
        return None;
    }
    // c: the previous iterate, the other end of the bracket [b, c]; d, e: the last two steps.
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..MAX_ITERATIONS {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let m = 0.5 * (c - b);
        if m.abs() <= tol1 || fb == 0.0 {
            return Some(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            // Interpolate: secant with two points, inverse quadratic with three.
            let s = fb / fa;
            let (mut p, mut q) = if a == c {
                (2.0 * m * s, 1.0 - s)
            } else {
                let q = fa / fc;
                let r = fb / fc;
                (
                    s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0)),
                    (q - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(m) };
        fb = f(b);
        if !fb.is_finite() {
            return None;
        }
    }
    Some(b)
}

/// Iterations at most: bisection alone halves a bracket of π to 1e-12 in 42 steps, and Brent
/// takes at most about three times as many as bisection.
const MAX_ITERATIONS: usize = 200;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_smooth_root() {
        let mut calls = 0;
        let x = brent(
            |x| {
                calls += 1;
                x.cos() - x
            },
            0.0,
            1.0,
            1e-14,
        )
        .unwrap();
        assert!((x - 0.739_085_133_215_160_6).abs() < 1e-13, "{x}");
        assert!(calls < 15, "{calls} evaluations");
    }

    #[test]
    fn finds_a_root_at_a_jump_by_bisection() {
        let x = brent(|x| if x < 0.3 { -1.0 } else { 2.0 }, 0.0, 1.0, 1e-12).unwrap();
        assert!((x - 0.3).abs() < 1e-11, "{x}");
    }

    #[test]
    fn refuses_a_bracket_without_a_sign_change() {
        assert_eq!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12), None);
        assert_eq!(brent(|_| f64::NAN, -1.0, 1.0, 1e-12), None);
        assert_eq!(brent(|x| x - 1.0, 1.0, 2.0, 1e-12), Some(1.0));
    }
}
