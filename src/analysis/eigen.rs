//! Eigen-analysis of the linearised aeroelastic system (MODEL.md §6).
//!
//! Input: the state matrix `A` at equilibrium ([`LinearSystem`]). Output: every root
//! `λ = σ ± iω` (one entry per conjugate pair) with frequency `ω/2π`, damping ratio `ζ = −σ/|λ|`,
//! a label from its eigenvector's Galerkin coefficients, its structural share (the participation
//! of `q, q̇` in the root, from left and right eigenvectors; roots with share < ½ are aero lags,
//! reported apart), and the stability verdict.
//!
//! Eigenvectors come from faer's dense real eigendecomposition (Hessenberg reduction, Francis
//! double-shift QR with an iteration cap, back-substitution for the vectors). Why not inverse
//! iteration on top of eigenvalues: that needs one complex LU per root (O(n⁴) for all of them
//! against O(n³) here), it is fragile for close or repeated roots (exactly the crossings mode
//! tracking must survive), and nalgebra's eigenvalue-only Schur solver has no iteration cap (it can
//! spin on NaN input). faer reports non-convergence as an error; we add finite checks on the input
//! and the output so every failure is an [`Error::Numerical`], never a hang or a panic.

use crate::error::{Error, Result};
use crate::physics::structure::mode_labels;
use crate::physics::system::{LinearSystem, System};
use crate::preset::Preset;
use nalgebra::{Complex, DMatrix};
use serde::Serialize;

/// The stability verdict of one operating point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Stable,
    /// An oscillatory mode (ω > 0) has σ ≥ 0.
    Flutter,
    /// A non-oscillatory mode (ω = 0) has σ ≥ 0.
    Divergence,
}

/// One eigenvalue λ = σ + iω with its identification.
#[derive(Debug, Clone, Serialize)]
pub struct Mode {
    /// σ (1/s).
    pub re: f64,
    /// ω (rad/s), ≥ 0 (one entry per conjugate pair).
    pub im: f64,
    /// ω / 2π.
    pub frequency_hz: f64,
    /// ζ = −σ/|λ|.
    pub damping_ratio: f64,
    /// `flap k` / `torsion k` from the eigenvector's Galerkin coefficients; `aero lag k` for
    /// aerodynamic-state roots.
    pub label: String,
    /// Share of the eigenvector's energy in the structural coordinates (0…1).
    pub structural_share: f64,
    /// Galerkin coefficients q = [q_φ; q_u] (2N) of the eigenvector, unit norm; used for MAC
    /// tracking and mode shapes.
    #[serde(skip)]
    pub shape: Vec<Complex<f64>>,
}

/// All eigenvalues of one operating point.
#[derive(Debug, Clone, Serialize)]
pub struct Stability {
    pub stable: bool,
    pub verdict: Verdict,
    /// Structural (aeroelastic) modes, sorted by σ descending.
    pub eigenvalues: Vec<Mode>,
    /// Roots dominated by aerodynamic lag states, reported apart, sorted by σ descending.
    pub aero_lags: Vec<Mode>,
}

impl Stability {
    /// The root with the largest σ, structural or aero lag (the stability margin).
    pub fn critical(&self) -> Option<&Mode> {
        self.eigenvalues
            .iter()
            .chain(&self.aero_lags)
            .max_by(|a, b| a.re.total_cmp(&b.re))
    }
    /// The largest σ over every root (−∞ when there is none).
    pub fn max_re(&self) -> f64 {
        self.critical().map_or(f64::NEG_INFINITY, |m| m.re)
    }
}

/// Eigenvalues with right and left eigenvectors of a real square matrix, one entry per real
/// root and one per complex-conjugate pair (the member with ω ≥ 0).
#[derive(Debug, Clone)]
pub struct Roots {
    pub values: Vec<Complex<f64>>,
    /// Column k is the right eigenvector of `values[k]`: `A r = λ r`.
    pub vectors: DMatrix<Complex<f64>>,
    /// Column k is the left eigenvector of `values[k]`: `lᴴ A = λ lᴴ`.
    pub left: DMatrix<Complex<f64>>,
}

impl Roots {
    /// Participation of state `i` in root `k`, `|l_i| |r_i|`, normalised over the states.
    /// Unlike eigenvector magnitudes, participation factors do not depend on the units or scaling
    /// of the states, so they tell a structural root from an aerodynamic-lag root without
    /// arbitrary weights.
    pub fn participation(&self, k: usize) -> Vec<f64> {
        let raw: Vec<f64> = self
            .vectors
            .column(k)
            .iter()
            .zip(self.left.column(k).iter())
            .map(|(r, l)| r.norm() * l.norm())
            .collect();
        let total: f64 = raw.iter().sum();
        if total > 0.0 {
            raw.iter().map(|p| p / total).collect()
        } else {
            raw
        }
    }
}

/// A root counts as unstable when σ exceeds this fraction of the spectral scale `max |λ|`:
/// exactly neutral roots (no structural damping, zero airspeed) come out of the QR iteration
/// with σ of the order of round-off times |λ|, and must not flip the verdict.
pub const NEUTRAL_TOLERANCE: f64 = 1e-9;

/// Stability of a preset's operating point.
pub fn analyse(p: &Preset) -> Result<Stability> {
    analyse_system(&linear_system(p)?)
}

/// The linearised system of a preset (assemble, equilibrium, state matrix).
pub fn linear_system(p: &Preset) -> Result<LinearSystem> {
    System::new(p)?.linearise()
}

/// Eigen-analysis of an assembled linear system (sweeps reuse their own systems).
pub fn analyse_system(ls: &LinearSystem) -> Result<Stability> {
    let roots = eigen_decomposition(&ls.a)?;
    let nq = ls.nq;
    let scale = roots.values.iter().map(|l| l.norm()).fold(1.0, f64::max);
    let tol = NEUTRAL_TOLERANCE * scale;
    let mut structural: Vec<(Mode, f64)> = Vec::new();
    let mut lags: Vec<Mode> = Vec::new();
    for (k, lambda) in roots.values.iter().enumerate() {
        let v = roots.vectors.column(k);
        let q: Vec<Complex<f64>> = v.rows(0, nq).iter().copied().collect();
        // Structural states are q and q̇, the first 2·nq.
        let share: f64 = roots.participation(k)[..2 * nq].iter().sum();
        let im = if lambda.im.abs() <= tol {
            0.0
        } else {
            lambda.im
        };
        let magnitude = lambda.norm();
        let mode = Mode {
            re: lambda.re,
            im,
            frequency_hz: im / std::f64::consts::TAU,
            damping_ratio: if magnitude > 0.0 {
                -lambda.re / magnitude
            } else {
                0.0
            },
            label: String::new(),
            structural_share: share,
            shape: normalised_shape(&q),
        };
        if share >= 0.5 {
            let torsion = ls.structure.torsion_share(&q);
            structural.push((mode, torsion));
        } else {
            lags.push(mode);
        }
    }
    // Labels count modes of each kind in order of natural frequency |λ| (= ω_n for a damped
    // oscillator), not of ω: heavily damped or overdamped modes (stiffness-proportional damping
    // on a blade whose torsion is far above its flap) would otherwise jump to the front.
    structural.sort_by(|a, b| {
        let (la, lb) = (a.0.re.hypot(a.0.im), b.0.re.hypot(b.0.im));
        la.total_cmp(&lb).then(b.0.re.total_cmp(&a.0.re))
    });
    let shares: Vec<f64> = structural.iter().map(|(_, t)| *t).collect();
    let labels = mode_labels(&shares);
    let mut eigenvalues: Vec<Mode> = structural
        .into_iter()
        .zip(labels)
        .map(|((mut m, _), label)| {
            m.label = label;
            m
        })
        .collect();
    eigenvalues.sort_by(|a, b| b.re.total_cmp(&a.re));
    lags.sort_by(|a, b| b.re.total_cmp(&a.re));
    for (k, m) in lags.iter_mut().enumerate() {
        m.label = format!("aero lag {}", k + 1);
    }
    let verdict = verdict_of(eigenvalues.iter().chain(&lags), tol);
    Ok(Stability {
        stable: verdict == Verdict::Stable,
        verdict,
        eigenvalues,
        aero_lags: lags,
    })
}

fn verdict_of<'a>(roots: impl Iterator<Item = &'a Mode>, tol: f64) -> Verdict {
    match roots.max_by(|a, b| a.re.total_cmp(&b.re)) {
        Some(m) if m.re > tol => {
            if m.im > 0.0 {
                Verdict::Flutter
            } else {
                Verdict::Divergence
            }
        }
        _ => Verdict::Stable,
    }
}

/// Unit norm, phase turned so the largest coefficient is real and positive (a canonical form for
/// plotting; MAC does not depend on it).
fn normalised_shape(q: &[Complex<f64>]) -> Vec<Complex<f64>> {
    let norm = q.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt();
    let Some(big) = q
        .iter()
        .max_by(|a, b| a.norm_sqr().total_cmp(&b.norm_sqr()))
    else {
        return Vec::new();
    };
    if norm == 0.0 || big.norm() == 0.0 {
        return q.to_vec();
    }
    let rotate = big.conj() / (big.norm() * norm);
    q.iter().map(|c| c * rotate).collect()
}

/// All eigenvalues and right eigenvectors of a real square matrix (faer, sequential).
///
/// Errors: a non-square or non-finite matrix, no convergence of the QR iteration, or non-finite
/// output.
pub fn eigen_decomposition(a: &DMatrix<f64>) -> Result<Roots> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{self, ComputeEigenvectors};

    let n = a.nrows();
    if a.ncols() != n {
        return Err(Error::numerical(format!(
            "eigen-analysis needs a square matrix, got {}×{}",
            n,
            a.ncols()
        )));
    }
    if let Some(((i, j), v)) = a
        .iter()
        .enumerate()
        .map(|(k, v)| ((k % n.max(1), k / n.max(1)), v))
        .find(|(_, v)| !v.is_finite())
    {
        return Err(Error::numerical(format!(
            "state matrix entry ({i}, {j}) is {v}; cannot compute eigenvalues"
        )));
    }
    if n == 0 {
        return Ok(Roots {
            values: Vec::new(),
            vectors: DMatrix::zeros(0, 0),
            left: DMatrix::zeros(0, 0),
        });
    }
    // Balance first: D⁻¹AD has the same eigenvalues, rows and columns of comparable norm, and
    // the QR iteration converges faster and more accurately on it (state matrices mix 1 and
    // 10⁵ rad/s roots). Right vectors map back as D r, left vectors as D⁻¹ l.
    let scale = balancing_scale(a);
    let fa = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)] * scale[j] / scale[i]);
    let mut s_re = faer::diag::Diag::<f64>::zeros(n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(n);
    let mut u = faer::Mat::<f64>::zeros(n, n);
    let mut ul = faer::Mat::<f64>::zeros(n, n);
    // Sequential: the matrices are small and sweeps already use every core across points.
    let par = faer::Par::Seq;
    let mut buffer = MemBuffer::new(evd::evd_scratch::<f64>(
        n,
        ComputeEigenvectors::Yes,
        ComputeEigenvectors::Yes,
        par,
        Default::default(),
    ));
    evd::evd_real(
        fa.as_ref(),
        s_re.as_mut(),
        s_im.as_mut(),
        Some(ul.as_mut()),
        Some(u.as_mut()),
        par,
        MemStack::new(&mut buffer),
        Default::default(),
    )
    .map_err(|e| Error::numerical(format!("eigenvalue iteration failed: {e:?}")))?;

    let mut values = Vec::with_capacity(n);
    let mut right: Vec<Vec<Complex<f64>>> = Vec::with_capacity(n);
    let mut left: Vec<Vec<Complex<f64>>> = Vec::with_capacity(n);
    let mut j = 0;
    while j < n {
        let (re, im) = (s_re[j], s_im[j]);
        if im == 0.0 || j + 1 == n {
            values.push(Complex::new(re, 0.0));
            right.push((0..n).map(|i| Complex::new(u[(i, j)], 0.0)).collect());
            left.push((0..n).map(|i| Complex::new(ul[(i, j)], 0.0)).collect());
            j += 1;
        } else {
            // A complex pair occupies columns j (real part) and j + 1 (imaginary part) for the
            // eigenvalue re + i·s_im[j] (left and right alike); keep the member with ω > 0.
            let sign = im.signum();
            values.push(Complex::new(re, im.abs()));
            let pack = |m: &faer::Mat<f64>| -> Vec<Complex<f64>> {
                (0..n)
                    .map(|i| Complex::new(m[(i, j)], sign * m[(i, j + 1)]))
                    .collect()
            };
            right.push(pack(&u));
            left.push(pack(&ul));
            j += 2;
        }
    }
    let vectors = DMatrix::from_fn(n, right.len(), |i, k| right[k][i] * scale[i]);
    let left = DMatrix::from_fn(n, left.len(), |i, k| left[k][i] / scale[i]);
    let finite = |c: &Complex<f64>| c.re.is_finite() && c.im.is_finite();
    if !values.iter().all(finite) || !vectors.iter().all(finite) || !left.iter().all(finite) {
        return Err(Error::numerical(
            "eigen-analysis produced non-finite eigenvalues or eigenvectors",
        ));
    }
    Ok(Roots {
        values,
        vectors,
        left,
    })
}

/// Diagonal similarity scaling (powers of two, so exact in floating point) that equalises the
/// off-diagonal row and column norms (Parlett & Reinsch, as in LAPACK's gebal, without the
/// permutation step).
fn balancing_scale(a: &DMatrix<f64>) -> Vec<f64> {
    let n = a.nrows();
    let mut d = vec![1.0f64; n];
    const RADIX: f64 = 2.0;
    for _ in 0..100 {
        let mut converged = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    c += (a[(j, i)] * d[i] / d[j]).abs();
                    r += (a[(i, j)] * d[j] / d[i]).abs();
                }
            }
            if c == 0.0 || r == 0.0 {
                continue;
            }
            let (mut f, total) = (1.0, c + r);
            let (mut cc, mut rr) = (c, r);
            while cc < rr / RADIX {
                cc *= RADIX;
                rr /= RADIX;
                f *= RADIX;
            }
            while cc >= rr * RADIX {
                cc /= RADIX;
                rr *= RADIX;
                f /= RADIX;
            }
            if cc + rr < 0.95 * total {
                d[i] *= f;
                converged = false;
            }
        }
        if converged {
            break;
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decomposes_a_damped_oscillator_and_a_real_root() {
        // ẍ + 2ζω ẋ + ω² x = 0 (ζ = 0.1, ω = 3) plus ẏ = −2y.
        let (z, w) = (0.1, 3.0);
        let a = DMatrix::from_row_slice(
            3,
            3,
            &[0.0, 1.0, 0.0, -w * w, -2.0 * z * w, 0.0, 0.0, 0.0, -2.0],
        );
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.values.len(), 2);
        let osc = r.values.iter().find(|l| l.im > 0.0).unwrap();
        assert!((osc.re + z * w).abs() < 1e-12);
        assert!((osc.im - w * (1.0 - z * z).sqrt()).abs() < 1e-12);
        // A r = λ r and lᴴ A = λ lᴴ for every returned root.
        let ac = a.map(|v| Complex::new(v, 0.0));
        for (k, l) in r.values.iter().enumerate() {
            let v = r.vectors.column(k);
            let res = &ac * v - v * *l;
            assert!(res.norm() < 1e-10 * v.norm());
            let w = r.left.column(k);
            let res = w.adjoint() * &ac - w.adjoint() * *l;
            assert!(res.norm() < 1e-10 * w.norm());
        }
        // The real root lives in the third state only.
        let k = r.values.iter().position(|l| l.im == 0.0).unwrap();
        let p = r.participation(k);
        assert!((p[2] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_non_finite_and_non_square() {
        let mut a = DMatrix::<f64>::identity(4, 4);
        a[(2, 1)] = f64::NAN;
        assert!(matches!(eigen_decomposition(&a), Err(Error::Numerical(_))));
        a[(2, 1)] = f64::INFINITY;
        assert!(matches!(eigen_decomposition(&a), Err(Error::Numerical(_))));
        assert!(matches!(
            eigen_decomposition(&DMatrix::<f64>::zeros(2, 3)),
            Err(Error::Numerical(_))
        ));
    }
}
