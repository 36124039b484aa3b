//! Eigenvalues of an upper Hessenberg matrix by the double-shift QR iteration without the Schur
//! form (a port of LAPACK's `dlahqr`), with its Householder reflector (`dlarfg`) and the
//! eigenvalues of a 2×2 block (`dlanv2`). The eigenvalue half of the fast eigendecomposition in
//! [`super::eigen`] (the reduction to Hessenberg form is `hessenberg_reduction.rs`); it returns no vectors,
//! which is most of its speed.

use nalgebra::{Complex, DMatrix};
use std::ops::RangeInclusive;

/// Iteration cap, as in LAPACK: an eigenvalue (or pair) that takes more than
/// `ITERATIONS_PER_EIGENVALUE · max(MIN_CAP_ORDER, n)` double-shift sweeps ends the iteration
/// with no result.
const ITERATIONS_PER_EIGENVALUE: usize = 30;
/// Below this order the cap no longer shrinks with n.
const MIN_CAP_ORDER: usize = 10;
/// Every this many sweeps without a deflation an exceptional shift breaks a possible cycle.
const EXCEPTIONAL_EVERY: usize = 10;
/// LAPACK's exceptional-shift coefficients.
const DAT1: f64 = 0.75;
const DAT2: f64 = -0.4375;

/// Every eigenvalue of an upper Hessenberg matrix (complex pairs as both members, adjacent),
/// by the double-shift QR iteration without the Schur form: a port of LAPACK `dlahqr` with
/// `wantt = wantz = false` (only the active block is updated).
///
/// Tolerance: a subdiagonal entry deflates when it is below the safe minimum n·MIN_POSITIVE/ε,
/// or below ε(|h_{k−1,k−1}| + |h_{k,k}|) and Ahues & Tisseur's conservative test. `None` when
/// an eigenvalue takes more than 30·max(10, n) sweeps ([`ITERATIONS_PER_EIGENVALUE`],
/// [`MIN_CAP_ORDER`]).
pub(super) fn hessenberg_eigenvalues(h: DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    hessenberg_eigenvalues_as_found(h, |_, _| {})
}

/// [`hessenberg_eigenvalues`], telling `found` each eigenvalue as it deflates, with its place
/// on the diagonal (its index in the returned list): the bottom of the matrix converges first,
/// so another thread can start on those roots' vectors while the iteration goes on
/// (`eigenpairs.rs`). A converged value is final; if the iteration later fails, the result is
/// `None` all the same.
pub(super) fn hessenberg_eigenvalues_as_found(
    mut h: DMatrix<f64>,
    mut found: impl FnMut(usize, Complex<f64>),
) -> Option<Vec<Complex<f64>>> {
    let n = h.nrows();
    let mut out = vec![Complex::new(0.0, 0.0); n];
    if n == 0 {
        return Some(out);
    }
    let ulp = f64::EPSILON;
    let smlnum = f64::MIN_POSITIVE * (n as f64 / ulp);
    let itmax = ITERATIONS_PER_EIGENVALUE * n.max(MIN_CAP_ORDER);
    let mut kdefl = 0usize;
    let mut next = Some(n - 1);
    while let Some(i) = next {
        let mut l = 0;
        let mut converged = false;
        for _ in 0..=itmax {
            // Look for a single small subdiagonal element.
            let mut k = i;
            while k > l {
                let hk = h[(k, k - 1)].abs();
                if hk <= smlnum {
                    break;
                }
                let mut tst = h[(k - 1, k - 1)].abs() + h[(k, k)].abs();
                if tst == 0.0 {
                    if k >= 2 {
                        tst += h[(k - 1, k - 2)].abs();
                    }
                    if k + 1 < n {
                        tst += h[(k + 1, k)].abs();
                    }
                }
                // Ahues & Tisseur's conservative deflation criterion (LAWN 122).
                if hk <= ulp * tst {
                    let up = h[(k - 1, k)].abs();
                    let (ab, ba) = (hk.max(up), hk.min(up));
                    let diff = (h[(k - 1, k - 1)] - h[(k, k)]).abs();
                    let hkk = h[(k, k)].abs();
                    let (aa, bb) = (hkk.max(diff), hkk.min(diff));
                    let s = aa + ab;
                    if ba * (ab / s) <= smlnum.max(ulp * (bb * (aa / s))) {
                        break;
                    }
                }
                k -= 1;
            }
            l = k;
            if l > 0 {
                h[(l, l - 1)] = 0.0;
            }
            if l + 1 >= i {
                converged = true;
                break;
            }
            kdefl += 1;
            let (i1, i2) = (l, i);
            let (h11, h12, h21, h22) = if kdefl % (2 * EXCEPTIONAL_EVERY) == 0 {
                let s = h[(i, i - 1)].abs() + h[(i - 1, i - 2)].abs();
                let d = DAT1 * s + h[(i, i)];
                (d, DAT2 * s, s, d)
            } else if kdefl % EXCEPTIONAL_EVERY == 0 {
                let s = h[(l + 1, l)].abs() + h[(l + 2, l + 1)].abs();
                let d = DAT1 * s + h[(l, l)];
                (d, DAT2 * s, s, d)
            } else {
                (h[(i - 1, i - 1)], h[(i - 1, i)], h[(i, i - 1)], h[(i, i)])
            };
            let s = h11.abs() + h12.abs() + h21.abs() + h22.abs();
            let (rt1r, rt1i, rt2r, rt2i) = if s == 0.0 {
                (0.0, 0.0, 0.0, 0.0)
            } else {
                let (h11, h12, h21, h22) = (h11 / s, h12 / s, h21 / s, h22 / s);
                let tr = (h11 + h22) / 2.0;
                let det = (h11 - tr) * (h22 - tr) - h12 * h21;
                let rtdisc = det.abs().sqrt();
                if det >= 0.0 {
                    // Complex conjugate shifts.
                    (tr * s, rtdisc * s, tr * s, -rtdisc * s)
                } else {
                    // Real shifts: use the one closer to h22, twice.
                    let (a, b) = (tr + rtdisc, tr - rtdisc);
                    let r = if (a - h22).abs() <= (b - h22).abs() {
                        a * s
                    } else {
                        b * s
                    };
                    (r, 0.0, r, 0.0)
                }
            };
            // Look for two consecutive small subdiagonal elements.
            let mut v = [0.0f64; 3];
            let mut m = i - 2;
            loop {
                let h21s = h[(m + 1, m)];
                let s = (h[(m, m)] - rt2r).abs() + rt2i.abs() + h21s.abs();
                let h21s = h[(m + 1, m)] / s;
                v[0] = h21s * h[(m, m + 1)] + (h[(m, m)] - rt1r) * ((h[(m, m)] - rt2r) / s)
                    - rt1i * (rt2i / s);
                v[1] = h21s * (h[(m, m)] + h[(m + 1, m + 1)] - rt1r - rt2r);
                v[2] = h21s * h[(m + 2, m + 1)];
                let s = v[0].abs() + v[1].abs() + v[2].abs();
                for x in v.iter_mut() {
                    *x /= s;
                }
                if m == l {
                    break;
                }
                let h00 = h[(m, m - 1)].abs() * (v[1].abs() + v[2].abs());
                let h01 = ulp
                    * v[0].abs()
                    * (h[(m - 1, m - 1)].abs() + h[(m, m)].abs() + h[(m + 1, m + 1)].abs());
                if h00 <= h01 {
                    break;
                }
                m -= 1;
            }
            // Double-shift QR sweep: chase the bulge down the active block.
            for k in m..i {
                let nr = 3.min(i - k + 1);
                if k > m {
                    for (r, x) in v.iter_mut().enumerate().take(nr) {
                        *x = h[(k + r, k - 1)];
                    }
                }
                let t1 = householder(&mut v[..nr]);
                if k > m {
                    h[(k, k - 1)] = v[0];
                    h[(k + 1, k - 1)] = 0.0;
                    if k + 1 < i {
                        h[(k + 2, k - 1)] = 0.0;
                    }
                } else if m > l {
                    h[(k, k - 1)] *= 1.0 - t1;
                }
                let v2 = v[1];
                let t2 = t1 * v2;
                let reflector = Reflector {
                    size: nr,
                    v: [1.0, v2, if nr == 3 { v[2] } else { 0.0 }],
                    t: [t1, t2, if nr == 3 { t1 * v[2] } else { 0.0 }],
                };
                if nr >= 2 {
                    let bottom = if nr == 3 { (k + 3).min(i) } else { i };
                    reflector.on_rows(&mut h, k, k..=i2);
                    reflector.on_columns(&mut h, k, i1..=bottom);
                }
            }
        }
        if !converged {
            return None;
        }
        if l == i {
            out[i] = Complex::new(h[(i, i)], 0.0);
            found(i, out[i]);
        } else {
            let (a, b) =
                eigenvalues_2x2(h[(i - 1, i - 1)], h[(i - 1, i)], h[(i, i - 1)], h[(i, i)]);
            out[i - 1] = a;
            out[i] = b;
            found(i - 1, a);
            found(i, b);
        }
        kdefl = 0;
        next = l.checked_sub(1);
    }
    Some(out)
}

/// Householder reflector (LAPACK `dlarfg`): on input v = [α, x], on output [β, u] with
/// (I − τ[1; u][1; u]ᵀ)[α; x] = [β; 0]; returns τ (0 when x = 0: the identity).
fn householder(v: &mut [f64]) -> f64 {
    let alpha = v[0];
    // Plain sum of squares (no hypot): the entries are O(‖H‖) of a balanced, finite matrix.
    let xnorm = v[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
    if xnorm == 0.0 {
        return 0.0;
    }
    let beta = -(alpha * alpha + xnorm * xnorm).sqrt().copysign(alpha);
    let tau = (beta - alpha) / beta;
    let scal = 1.0 / (alpha - beta);
    for x in v[1..].iter_mut() {
        *x *= scal;
    }
    v[0] = beta;
    tau
}

/// Eigenvalues of [[a, b], [c, d]] (as LAPACK `dlanv2` computes them): a real pair, or a
/// complex pair with the positive imaginary part first.
fn eigenvalues_2x2(a: f64, b: f64, c: f64, d: f64) -> (Complex<f64>, Complex<f64>) {
    let real = |x: f64, y: f64| (Complex::new(x, 0.0), Complex::new(y, 0.0));
    if c == 0.0 || b == 0.0 {
        return real(a, d);
    }
    let p = 0.5 * (a - d);
    let bcmax = b.abs().max(c.abs());
    let bcmis = b.abs().min(c.abs()) * b.signum() * c.signum();
    let scale = p.abs().max(bcmax);
    let z = p / scale * p + bcmax / scale * bcmis;
    if z >= 0.0 {
        let z = p + (scale.sqrt() * z.sqrt()).copysign(p);
        real(d + z, d - bcmax / z * bcmis)
    } else {
        let re = 0.5 * (a + d);
        let im = scale.sqrt() * (-z).sqrt();
        (Complex::new(re, im), Complex::new(re, -im))
    }
}

/// A Householder reflector `I − t₁ vvᵀ` of `size` 2 or 3 with `v = [1, v₂, v₃]` and
/// `t = [t₁, t₁v₂, t₁v₃]` (unused entries zero), as the QR sweep applies it.
struct Reflector {
    size: usize,
    v: [f64; 3],
    t: [f64; 3],
}

impl Reflector {
    /// Applied from the left to rows `k..k + size` of the columns `cols`. Those entries of a
    /// column are adjacent in column-major storage, so the loop walks column slices instead of
    /// indexing H twice per entry: this and [`Reflector::on_columns`] are the QR iteration's
    /// hot loops.
    fn on_rows(&self, h: &mut DMatrix<f64>, k: usize, cols: RangeInclusive<usize>) {
        let n = h.nrows();
        let [_, v2, v3] = self.v;
        let (first, last) = (*cols.start(), *cols.end());
        for col in h.as_mut_slice()[first * n..(last + 1) * n].chunks_exact_mut(n) {
            let r = &mut col[k..k + self.size];
            let sum = if self.size == 3 {
                r[0] + v2 * r[1] + v3 * r[2]
            } else {
                r[0] + v2 * r[1]
            };
            for (x, t) in r.iter_mut().zip(self.t) {
                *x -= sum * t;
            }
        }
    }

    /// Applied from the right to columns `k..k + size` over the rows `rows`, each column a
    /// contiguous slice.
    fn on_columns(&self, h: &mut DMatrix<f64>, k: usize, rows: RangeInclusive<usize>) {
        let n = h.nrows();
        let [_, v2, v3] = self.v;
        let [t1, t2, t3] = self.t;
        let block = &mut h.as_mut_slice()[k * n..(k + self.size) * n];
        let (c0, rest) = block.split_at_mut(n);
        let (c1, c2) = rest.split_at_mut(n);
        let (c0, c1) = (&mut c0[rows.clone()], &mut c1[rows.clone()]);
        if self.size == 3 {
            for ((a, b), c) in c0.iter_mut().zip(c1).zip(&mut c2[rows]) {
                let sum = *a + v2 * *b + v3 * *c;
                *a -= sum * t1;
                *b -= sum * t2;
                *c -= sum * t3;
            }
        } else {
            for (a, b) in c0.iter_mut().zip(c1) {
                let sum = *a + v2 * *b;
                *a -= sum * t1;
                *b -= sum * t2;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::eigen::{eigen_decomposition, tests::assert_eigenpairs};

    #[test]
    fn hessenberg_qr_converges_on_a_cyclic_permutation() {
        // The classic stall case of the unshifted/standard-shift QR iteration: only the
        // exceptional shifts break the cycle. Eigenvalues: the 6th roots of unity.
        let n = 6;
        let a = DMatrix::from_fn(n, n, |i, j| if i == (j + 1) % n { 1.0 } else { 0.0 });
        assert!(hessenberg_eigenvalues(a.clone()).is_some());
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.values.len(), 4);
        for l in &r.values {
            assert!((l.norm() - 1.0).abs() < 1e-12);
        }
        assert_eigenpairs(&a, &r, 1e-10);
    }
}
