//! Eigen-analysis of the linearised aeroelastic system (MODEL.md §6).
//!
//! Input: the state matrix `A` at equilibrium ([`LinearSystem`]). Output: every root
//! `λ = σ ± iω` (one entry per conjugate pair) with frequency `ω/2π`, damping ratio `ζ = −σ/|λ|`,
//! a label from its eigenvector's Galerkin coefficients, its structural share (the participation
//! of `q, q̇` in the root, from left and right eigenvectors; roots with share < ½ are aero lags,
//! reported apart), and the stability verdict.
//!
//! Eigenvectors: balancing, Hessenberg reduction, LAPACK-style double-shift QR for the
//! eigenvalues (iteration cap), then inverse iteration per root with residual checks; faer's full
//! real eigendecomposition is the robust fallback whenever the fast path fails (see
//! [`decompose`]). nalgebra alone would not do: it has no non-symmetric eigenvectors and its
//! eigenvalue-only Schur solver has no iteration cap (it can spin on NaN input). Input and output
//! are checked for finiteness, so every failure is an [`Error::Numerical`], never a hang or a
//! panic.

use crate::analysis::tracking::hungarian;
use crate::error::{Error, Result};
use crate::physics::structure::StructuralModel;
use crate::physics::system::{LinearSystem, System};
use crate::preset::ValidPreset;
use nalgebra::{Complex, ComplexField, DMatrix, DVector};
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
pub fn analyse(p: &ValidPreset) -> Result<Stability> {
    analyse_system(&linear_system(p)?)
}

/// The linearised system of a preset (assemble, equilibrium, state matrix).
pub fn linear_system(p: &ValidPreset) -> Result<LinearSystem> {
    System::new(p)?.linearise()
}

/// Eigen-analysis of an assembled linear system (sweeps reuse their own systems).
///
/// Left eigenvectors are computed only when there are aerodynamic states: without them every
/// state is structural and the participation share is 1 for every root by definition.
pub fn analyse_system(ls: &LinearSystem) -> Result<Stability> {
    let roots = decompose(&ls.a, ls.n_aero > 0)?;
    let nq = ls.nq;
    let scale = roots.values.iter().map(|l| l.norm()).fold(1.0, f64::max);
    let tol = NEUTRAL_TOLERANCE * scale;
    let mut structural: Vec<Mode> = Vec::new();
    let mut lags: Vec<Mode> = Vec::new();
    for (k, lambda) in roots.values.iter().enumerate() {
        let v = roots.vectors.column(k);
        let q: Vec<Complex<f64>> = v.rows(0, nq).iter().copied().collect();
        // Structural states are q and q̇, the first 2·nq.
        let share: f64 = if roots.left.ncols() == 0 {
            1.0
        } else {
            roots.participation(k)[..2 * nq].iter().sum()
        };
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
            structural.push(mode);
        } else {
            lags.push(mode);
        }
    }
    label_structural_roots(&mut structural, &ls.structure)?;
    structural.sort_by(|a, b| b.re.total_cmp(&a.re));
    lags.sort_by(|a, b| b.re.total_cmp(&a.re));
    for (k, m) in lags.iter_mut().enumerate() {
        m.label = format!("aero lag {}", k + 1);
    }
    let verdict = verdict_of(structural.iter().chain(&lags), tol);
    Ok(Stability {
        stable: verdict == Verdict::Stable,
        verdict,
        eigenvalues: structural,
        aero_lags: lags,
    })
}

/// Suffix of a structural root left over after the one-to-one assignment (there are more
/// structural roots than natural modes only when some mode is non-oscillatory: an overdamped
/// or divergent mode has two real roots). The least stable of a mode's real roots carries the
/// plain label; the other is primed, `"torsion 4'"` (short, so it survives the explorer's narrow
/// modes column, where a longer suffix would be cut to a duplicate of the plain label).
pub const SECOND_ROOT_SUFFIX: &str = "'";

/// Labels structural roots by the in-vacuo natural modes of (M, K_e + K_c) at the same rotor
/// speed (MODEL.md §6): each root's q-part is expanded on the mass-normalised natural modes,
/// η = Φᵀ M q, and roots are assigned to modes one-to-one maximising the summed energy share
/// |η_k|² / Σ|η|² (Kuhn–Munkres), so no label repeats and none names a mode that does not
/// exist. Reading the label off the natural modes rather than off the root's own torsion
/// share matters on blades whose aerodynamic torsional stiffness dwarfs the structural one
/// (the paper's blade): there the torsion roots' shapes and frequencies move far from the
/// in-vacuo torsion modes, but their modal content still identifies them. For the weak
/// (symmetric) form η are the exact modal coordinates; for the strong form an M-weighted
/// projection, which is all the assignment needs.
fn label_structural_roots(roots: &mut [Mode], structure: &StructuralModel) -> Result<()> {
    if roots.is_empty() {
        return Ok(());
    }
    let natural = structure.natural_modes()?;
    let mass = &structure.mass;
    // Columns of W = M Φ̂ with Φ̂ mass-normalised: η_k = W_kᵀ q.
    let weights: Vec<DVector<f64>> = natural
        .iter()
        .map(|m| {
            let mphi = mass * &m.shape;
            let modal_mass = m.shape.dot(&mphi);
            if modal_mass > 0.0 {
                mphi / modal_mass.sqrt()
            } else {
                mphi
            }
        })
        .collect();
    let shares: Vec<Vec<f64>> = roots
        .iter()
        .map(|r| {
            let energy: Vec<f64> = weights
                .iter()
                .map(|w| {
                    w.iter()
                        .zip(&r.shape)
                        .map(|(wi, qi)| qi * *wi)
                        .sum::<Complex<f64>>()
                        .norm_sqr()
                })
                .collect();
            let total: f64 = energy.iter().sum();
            if total > 0.0 {
                energy.iter().map(|e| e / total).collect()
            } else {
                energy
            }
        })
        .collect();
    let size = roots.len().max(natural.len());
    let cost: Vec<Vec<f64>> = (0..size)
        .map(|i| {
            (0..size)
                .map(|k| match (shares.get(i), natural.get(k)) {
                    (Some(s), Some(_)) => -s[k],
                    _ => 0.0,
                })
                .collect()
        })
        .collect();
    let assigned = hungarian(&cost);
    let mut owner: Vec<Option<usize>> = vec![None; natural.len()];
    let mut mode_of: Vec<Option<usize>> = (0..roots.len())
        .map(|i| Some(assigned[i]).filter(|&k| k < natural.len()))
        .collect();
    for (i, k) in mode_of.iter().enumerate() {
        if let Some(k) = k {
            owner[*k] = Some(i);
        }
    }
    // Left-over roots (more structural roots than modes): the second real root of an
    // overdamped or divergent mode. Pair them, again one-to-one by share, with the modes whose
    // assigned root is real (aerodynamic coupling can leave such a root with little of its own
    // mode's shape, so its best share alone would misname it); any still left take the mode
    // they share most with.
    let leftover: Vec<usize> = (0..roots.len()).filter(|&i| mode_of[i].is_none()).collect();
    let real_modes: Vec<usize> = (0..natural.len())
        .filter(|&k| owner[k].is_some_and(|j| roots[j].im == 0.0))
        .collect();
    let mut second: Vec<Option<usize>> = vec![None; roots.len()];
    let size = leftover.len().max(real_modes.len());
    let cost: Vec<Vec<f64>> = (0..size)
        .map(|a| {
            (0..size)
                .map(|b| match (leftover.get(a), real_modes.get(b)) {
                    (Some(&i), Some(&k)) if roots[i].im == 0.0 => -shares[i][k],
                    (Some(_), Some(_)) => 1.0,
                    _ => 0.0,
                })
                .collect()
        })
        .collect();
    for (a, b) in hungarian(&cost).into_iter().enumerate() {
        if let (Some(&i), Some(&k)) = (leftover.get(a), real_modes.get(b)) {
            if roots[i].im == 0.0 {
                second[i] = Some(k);
            }
        }
    }
    for &i in &leftover {
        if second[i].is_none() {
            second[i] = (0..natural.len()).max_by(|&a, &b| shares[i][a].total_cmp(&shares[i][b]));
        }
    }
    // Of a mode's two real roots the less stable one carries the plain label: it is the one
    // that decides stability (and the flutter search reports).
    for &i in &leftover {
        if let Some(k) = second[i] {
            if let Some(j) = owner[k] {
                if roots[i].im == 0.0 && roots[j].im == 0.0 && roots[i].re > roots[j].re {
                    mode_of[i] = Some(k);
                    mode_of[j] = None;
                    second[j] = Some(k);
                    owner[k] = Some(i);
                }
            }
        }
    }
    for (i, root) in roots.iter_mut().enumerate() {
        root.label = match (mode_of[i], second[i]) {
            (Some(k), _) => natural[k].label.clone(),
            (None, Some(k)) => format!("{}{SECOND_ROOT_SUFFIX}", natural[k].label),
            (None, None) => "structural".to_string(),
        };
    }
    Ok(())
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

/// All eigenvalues with right and left eigenvectors of a real square matrix.
///
/// Errors: a non-square or non-finite matrix, no convergence of the QR iteration, or non-finite
/// output. See [`decompose`] for the method.
pub fn eigen_decomposition(a: &DMatrix<f64>) -> Result<Roots> {
    decompose(a, true)
}

/// Eigenvalues with right eigenvectors, and left eigenvectors when `want_left` (otherwise
/// [`Roots::left`] is empty, n × 0).
///
/// Method (chosen by measurement, `cargo bench --bench stability`, `part_eigen_*`): the matrix is
/// balanced (D⁻¹AD) and reduced to Hessenberg form H = QᵀD⁻¹ADQ; the eigenvalues come from the
/// double-shift QR iteration on H *without* accumulating the Schur form or its vectors (a port
/// of LAPACK's `dlahqr` with `wantt = wantz = false`: Ahues–Tisseur deflation, exceptional shifts,
/// an iteration cap of 30·max(10, n) per eigenvalue). Each eigenvector, one per real root or
/// conjugate pair, then comes from inverse iteration with the converged eigenvalue as shift
/// (LAPACK `dhsein`/`dlaein`): one LU factorisation of the Hessenberg H − λI, O(n²), with tiny
/// pivots replaced by ε‖H‖, then one or two solves; the left vector reuses the same factors
/// (transposed solve). Both are accepted only when their residual ‖Hx − λx‖ is at round-off
/// level; vectors map back by Q and D.
///
/// Against faer's full decomposition (what this replaced: Schur form with its vectors, then
/// back-substitution for all vectors) this does a fraction of the flops on our small matrices:
/// measured single-threaded, 20-state quasi-steady system ≈ 110 µs → ≈ 65 µs without left
/// vectors (what [`analyse_system`] asks for when there are no aero states), 56-state
/// theodorsen system ≈ 1.7 ms → ≈ 1.2 ms with both (`part_eigen_*` in the stability bench).
/// nalgebra's bounded `Schur::try_new` was also measured and is slower than faer here (it
/// always accumulates Q, and it has no exceptional shifts). Roots of (nearly) equal value get
/// different start vectors and are orthogonalised against each other, so an exactly repeated root still returns a basis of
/// its eigenspace. Whenever the fast path fails — the QR iteration hits its cap, or a residual
/// check fails (defective or extremely ill-conditioned roots) — the matrix goes to faer's
/// robust full decomposition (Francis QR with aggressive deflation, also capped) instead; if
/// that fails too the result is an [`Error::Numerical`]. Non-finite input is rejected up
/// front, so neither path can spin on NaN.
pub fn decompose(a: &DMatrix<f64>, want_left: bool) -> Result<Roots> {
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
    let balanced = DMatrix::from_fn(n, n, |i, j| a[(i, j)] * scale[j] / scale[i]);
    let (values, right, left) = match fast_decomposition(&balanced, want_left) {
        Some(r) => r,
        None => faer_decomposition(&balanced, want_left)?,
    };
    let vectors = DMatrix::from_fn(n, right.ncols(), |i, k| right[(i, k)] * scale[i]);
    let left = DMatrix::from_fn(n, left.ncols(), |i, k| left[(i, k)] / scale[i]);
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

type Decomposition = (
    Vec<Complex<f64>>,
    DMatrix<Complex<f64>>,
    DMatrix<Complex<f64>>,
);

/// Hessenberg reduction, eigenvalue-only QR, inverse iteration (see [`decompose`]). `None` when
/// the QR iteration does not converge or a vector fails its residual check.
fn fast_decomposition(b: &DMatrix<f64>, want_left: bool) -> Option<Decomposition> {
    let n = b.nrows();
    let (q, h) = nalgebra::linalg::Hessenberg::new(b.clone()).unpack();
    let all = hessenberg_eigenvalues(h.clone())?;
    // One entry per real root and per conjugate pair (the member with ω > 0).
    let values: Vec<Complex<f64>> = all.into_iter().filter(|l| l.im >= 0.0).collect();
    let hnorm = h.norm().max(f64::MIN_POSITIVE);
    let k = values.len();
    let mut xr = DMatrix::<f64>::zeros(n, k);
    let mut xi = DMatrix::<f64>::zeros(n, k);
    let (mut yr, mut yi) = if want_left {
        (DMatrix::<f64>::zeros(n, k), DMatrix::<f64>::zeros(n, k))
    } else {
        (DMatrix::zeros(n, 0), DMatrix::zeros(n, 0))
    };
    // Real roots in real arithmetic (a quarter of the work), pairs in complex.
    let mut real = InverseIteration::<f64>::new(&h, hnorm);
    let mut complex = InverseIteration::<Complex<f64>>::new(&h, hnorm);
    for (c, &lambda) in values.iter().enumerate() {
        let (x, w): (Vec<Complex<f64>>, Option<Vec<Complex<f64>>>) = if lambda.im == 0.0 {
            let (x, w) = real.vectors(lambda.re, want_left)?;
            let up = |v: Vec<f64>| v.into_iter().map(|r| Complex::new(r, 0.0)).collect();
            (up(x), w.map(up))
        } else {
            complex.vectors(lambda, want_left)?
        };
        for i in 0..n {
            xr[(i, c)] = x[i].re;
            xi[(i, c)] = x[i].im;
        }
        if let Some(w) = w {
            // wᵀH = λwᵀ, so l = w̄ satisfies lᴴH = λlᴴ.
            for i in 0..n {
                yr[(i, c)] = w[i].re;
                yi[(i, c)] = -w[i].im;
            }
        }
    }
    let combine = |re: DMatrix<f64>, im: DMatrix<f64>| {
        DMatrix::from_fn(re.nrows(), re.ncols(), |i, j| {
            Complex::new(re[(i, j)], im[(i, j)])
        })
    };
    let right = combine(&q * xr, &q * xi);
    let left = combine(&q * yr, &q * yi);
    Some((values, right, left))
}

/// Inverse iteration on one upper Hessenberg matrix for a sequence of shifts (real `f64` or
/// complex), remembering earlier roots' vectors to separate (numerically) repeated roots.
struct InverseIteration<'a, T> {
    h: &'a DMatrix<f64>,
    hnorm: f64,
    lu: HessenbergLu<T>,
    right: Vec<(T, Vec<T>)>,
    left: Vec<(T, Vec<T>)>,
}

impl<'a, T: ComplexField<RealField = f64> + Copy> InverseIteration<'a, T> {
    fn new(h: &'a DMatrix<f64>, hnorm: f64) -> Self {
        InverseIteration {
            h,
            hnorm,
            lu: HessenbergLu {
                n: 0,
                u: Vec::new(),
                mult: Vec::new(),
                swapped: Vec::new(),
            },
            right: Vec::new(),
            left: Vec::new(),
        }
    }

    /// Right eigenvector x (Hx = λx) and, if asked, w with wᵀH = λwᵀ; unit 2-norm.
    fn vectors(&mut self, lambda: T, want_left: bool) -> Option<(Vec<T>, Option<Vec<T>>)> {
        let eps3 = f64::EPSILON * self.hnorm;
        self.lu.factor(self.h, lambda, eps3);
        // Earlier roots this close share (numerically) an eigenspace with this one.
        let near = |done: &[(T, Vec<T>)]| -> Vec<Vec<T>> {
            done.iter()
                .filter(|(l, _)| (*l - lambda).modulus() <= 1e3 * eps3)
                .map(|(_, v)| v.clone())
                .collect()
        };
        let cluster = near(&self.right);
        let x = self.iterate(lambda, &cluster, false)?;
        self.right.push((lambda, x.clone()));
        let w = if want_left {
            let cluster = near(&self.left);
            let w = self.iterate(lambda, &cluster, true)?;
            self.left.push((lambda, w.clone()));
            Some(w)
        } else {
            None
        };
        Some((x, w))
    }

    /// At most four solves from the current factors, until the residual is at round-off level
    /// (LAPACK `dlaein`). Without a cluster the residual of the normalised iterate is known
    /// without a product: (H − λI)(x/‖x‖) = v/‖x‖ for the unit right-hand side v, up to the ε‖H‖
    /// pivot perturbation, so the growth ‖x‖ decides; inside a cluster the orthogonalisation
    /// changes the iterate and the residual is computed.
    fn iterate(&self, lambda: T, cluster: &[Vec<T>], transposed: bool) -> Option<Vec<T>> {
        let n = self.h.nrows();
        let tolerance = 64.0 * (n as f64) * f64::EPSILON * self.hnorm;
        // Start: all ones (LAPACK), or, inside a cluster, a vector that differs from the ones
        // used before so repeated roots get independent iterates.
        let mut x: Vec<T> = (0..n)
            .map(|i| {
                let t = if cluster.is_empty() {
                    1.0
                } else {
                    1.0 + ((i * (cluster.len() + 1) * 7919) % 101) as f64 / 101.0
                };
                T::from_real(t)
            })
            .collect();
        // The first right solve skips G: its right-hand side is G⁻¹·start, whose norm the
        // growth test needs (O(n)).
        let mut rhs_norm = if transposed || !cluster.is_empty() {
            (n as f64).sqrt()
        } else {
            self.lu.start_norm(&x)
        };
        let mut best = (f64::INFINITY, Vec::new());
        for iteration in 0..4 {
            if transposed {
                self.lu.solve_transposed(&mut x);
            } else {
                self.lu.solve(&mut x, iteration > 0);
            }
            for c in cluster {
                let dot = c
                    .iter()
                    .zip(&x)
                    .fold(T::zero(), |s, (a, b)| s + a.conjugate() * *b);
                for (xi, ci) in x.iter_mut().zip(c) {
                    *xi -= dot * *ci;
                }
            }
            let norm = x.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt();
            if !(norm.is_finite() && norm > 0.0) {
                return None;
            }
            for c in x.iter_mut() {
                *c = c.unscale(norm);
            }
            let res = if cluster.is_empty() {
                rhs_norm / norm + 2.0 * eps_pivot(self.hnorm)
            } else {
                residual(self.h, &x, lambda, transposed)
            };
            if res <= tolerance {
                return Some(x);
            }
            if !cluster.is_empty() && res < best.0 {
                best = (res, x.clone());
            }
            rhs_norm = 1.0;
        }
        // Inside a large cluster of repeated roots (the identical lag and stall roots of many
        // ONERA stations at one inflow speed) each earlier member is exact only to round-off,
        // and orthogonalising against dozens of them leaves a residual floor a few times the
        // tolerance. An iterate at √ε‖H‖ is still an eigenvector to eight digits: ample for
        // labels, participation and tracking.
        (best.0 <= f64::EPSILON.sqrt() * self.hnorm).then_some(best.1)
    }
}

/// The pivot perturbation ε‖H‖ of [`HessenbergLu::factor`].
fn eps_pivot(hnorm: f64) -> f64 {
    f64::EPSILON * hnorm
}

/// LU factors of the Hessenberg matrix H − λI with adjacent-row partial pivoting:
/// G (H − λI) = U, G = M_{n−2}P_{n−2}⋯M_0P_0, each M_k one multiplier below the diagonal.
struct HessenbergLu<T> {
    n: usize,
    /// U, column-major n × n (upper triangle used).
    u: Vec<T>,
    mult: Vec<T>,
    swapped: Vec<bool>,
}

impl<T: ComplexField<RealField = f64> + Copy> HessenbergLu<T> {
    fn factor(&mut self, h: &DMatrix<f64>, lambda: T, eps3: f64) {
        let n = h.nrows();
        self.n = n;
        self.u.clear();
        self.u.extend(h.as_slice().iter().map(|&v| T::from_real(v)));
        for i in 0..n {
            self.u[i + i * n] -= lambda;
        }
        self.mult.clear();
        self.mult.resize(n.saturating_sub(1), T::zero());
        self.swapped.clear();
        self.swapped.resize(n.saturating_sub(1), false);
        let u = &mut self.u;
        let tiny = T::from_real(eps3);
        for k in 0..n.saturating_sub(1) {
            if u[k + 1 + k * n].modulus_squared() > u[k + k * n].modulus_squared() {
                for j in k..n {
                    u.swap(k + j * n, k + 1 + j * n);
                }
                self.swapped[k] = true;
            }
            if u[k + k * n].modulus_squared() < eps3 * eps3 {
                // A (numerically) exact shift: the standard perturbation of inverse iteration.
                u[k + k * n] = tiny;
            }
            let m = u[k + 1 + k * n] / u[k + k * n];
            self.mult[k] = m;
            u[k + 1 + k * n] = T::zero();
            for j in k + 1..n {
                let ukj = u[k + j * n];
                u[k + 1 + j * n] -= m * ukj;
            }
        }
        if n > 0 && u[(n - 1) * (n + 1)].modulus_squared() < eps3 * eps3 {
            u[(n - 1) * (n + 1)] = tiny;
        }
    }

    /// ‖G⁻¹v‖₂: the right-hand side that a solve with `apply_g = false` actually solves for.
    fn start_norm(&self, v: &[T]) -> f64 {
        let mut w = v.to_vec();
        for k in (0..self.n.saturating_sub(1)).rev() {
            let wk = w[k];
            w[k + 1] += self.mult[k] * wk;
            if self.swapped[k] {
                w.swap(k, k + 1);
            }
        }
        w.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt()
    }

    /// Solves (H − λI) x = v in place; with `apply_g = false` solves U x = v (the first step of
    /// LAPACK's inverse iteration, whose start vector is then G⁻¹v).
    fn solve(&self, v: &mut [T], apply_g: bool) {
        let n = self.n;
        if apply_g {
            for k in 0..n.saturating_sub(1) {
                if self.swapped[k] {
                    v.swap(k, k + 1);
                }
                let vk = v[k];
                v[k + 1] -= self.mult[k] * vk;
            }
        }
        for j in (0..n).rev() {
            v[j] /= self.u[j + j * n];
            let vj = v[j];
            let col = &self.u[j * n..j * n + j];
            for (vi, uij) in v[..j].iter_mut().zip(col) {
                *vi -= *uij * vj;
            }
        }
    }

    /// Solves (H − λI)ᵀ w = v in place: Uᵀz = v, then w = Gᵀz. (Gᵀ comes after the triangular
    /// solve here, so unlike [`Self::solve`] it cannot be folded into the start vector.)
    fn solve_transposed(&self, v: &mut [T]) {
        let n = self.n;
        for j in 0..n {
            let col = &self.u[j * n..j * n + j];
            let s = col
                .iter()
                .zip(&v[..j])
                .fold(v[j], |s, (uij, vi)| s - *uij * *vi);
            v[j] = s / self.u[j + j * n];
        }
        for k in (0..n.saturating_sub(1)).rev() {
            let vk1 = v[k + 1];
            v[k] -= self.mult[k] * vk1;
            if self.swapped[k] {
                v.swap(k, k + 1);
            }
        }
    }
}

/// ‖Hx − λx‖₂ (or ‖Hᵀx − λx‖₂) for upper Hessenberg H.
fn residual<T: ComplexField<RealField = f64> + Copy>(
    h: &DMatrix<f64>,
    x: &[T],
    lambda: T,
    transposed: bool,
) -> f64 {
    let n = h.nrows();
    let mut r: Vec<T> = x.iter().map(|&v| -(lambda * v)).collect();
    for j in 0..n {
        let col = &h.as_slice()[j * n..j * n + (j + 2).min(n)];
        if transposed {
            // (Hᵀx)_j = Σ_i H_ij x_i.
            r[j] += col
                .iter()
                .zip(x)
                .fold(T::zero(), |s, (hij, xi)| s + xi.scale(*hij));
        } else {
            let xj = x[j];
            for (ri, hij) in r.iter_mut().zip(col) {
                *ri += xj.scale(*hij);
            }
        }
    }
    r.iter().map(|c| c.modulus_squared()).sum::<f64>().sqrt()
}

/// Every eigenvalue of an upper Hessenberg matrix (complex pairs as both members, adjacent),
/// by the double-shift QR iteration without the Schur form: a port of LAPACK `dlahqr` with
/// `wantt = wantz = false` (only the active block is updated). `None` when an eigenvalue takes
/// more than 30·max(10, n) iterations.
fn hessenberg_eigenvalues(mut h: DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    const EXCEPTIONAL_EVERY: usize = 10;
    const DAT1: f64 = 0.75;
    const DAT2: f64 = -0.4375;
    let n = h.nrows();
    let mut out = vec![Complex::new(0.0, 0.0); n];
    if n == 0 {
        return Some(out);
    }
    let ulp = f64::EPSILON;
    let smlnum = f64::MIN_POSITIVE * (n as f64 / ulp);
    let itmax = 30 * n.max(10);
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
                // Ahues & Kressner's conservative deflation criterion.
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
                if nr == 3 {
                    let v3 = v[2];
                    let t3 = t1 * v3;
                    for j in k..=i2 {
                        let sum = h[(k, j)] + v2 * h[(k + 1, j)] + v3 * h[(k + 2, j)];
                        h[(k, j)] -= sum * t1;
                        h[(k + 1, j)] -= sum * t2;
                        h[(k + 2, j)] -= sum * t3;
                    }
                    for j in i1..=(k + 3).min(i) {
                        let sum = h[(j, k)] + v2 * h[(j, k + 1)] + v3 * h[(j, k + 2)];
                        h[(j, k)] -= sum * t1;
                        h[(j, k + 1)] -= sum * t2;
                        h[(j, k + 2)] -= sum * t3;
                    }
                } else if nr == 2 {
                    for j in k..=i2 {
                        let sum = h[(k, j)] + v2 * h[(k + 1, j)];
                        h[(k, j)] -= sum * t1;
                        h[(k + 1, j)] -= sum * t2;
                    }
                    for j in i1..=i {
                        let sum = h[(j, k)] + v2 * h[(j, k + 1)];
                        h[(j, k)] -= sum * t1;
                        h[(j, k + 1)] -= sum * t2;
                    }
                }
            }
        }
        if !converged {
            return None;
        }
        if l == i {
            out[i] = Complex::new(h[(i, i)], 0.0);
        } else {
            let (a, b) =
                eigenvalues_2x2(h[(i - 1, i - 1)], h[(i - 1, i)], h[(i, i - 1)], h[(i, i)]);
            out[i - 1] = a;
            out[i] = b;
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

/// faer's full real eigendecomposition (the robust fallback of [`decompose`]), sequential:
/// the matrices are small and sweeps already use every core across points.
fn faer_decomposition(b: &DMatrix<f64>, want_left: bool) -> Result<Decomposition> {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::evd::{self, ComputeEigenvectors};

    let n = b.nrows();
    let fa = faer::Mat::<f64>::from_fn(n, n, |i, j| b[(i, j)]);
    let mut s_re = faer::diag::Diag::<f64>::zeros(n);
    let mut s_im = faer::diag::Diag::<f64>::zeros(n);
    let mut u = faer::Mat::<f64>::zeros(n, n);
    let mut ul = faer::Mat::<f64>::zeros(n, if want_left { n } else { 0 });
    let par = faer::Par::Seq;
    let left_flag = if want_left {
        ComputeEigenvectors::Yes
    } else {
        ComputeEigenvectors::No
    };
    let mut buffer = MemBuffer::new(evd::evd_scratch::<f64>(
        n,
        left_flag,
        ComputeEigenvectors::Yes,
        par,
        Default::default(),
    ));
    evd::evd_real(
        fa.as_ref(),
        s_re.as_mut(),
        s_im.as_mut(),
        if want_left { Some(ul.as_mut()) } else { None },
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
            if want_left {
                left.push((0..n).map(|i| Complex::new(ul[(i, j)], 0.0)).collect());
            }
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
            if want_left {
                left.push(pack(&ul));
            }
            j += 2;
        }
    }
    let right = DMatrix::from_fn(n, right.len(), |i, k| right[k][i]);
    let left = DMatrix::from_fn(n, left.len(), |i, k| left[k][i]);
    Ok((values, right, left))
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

    /// Every returned pair satisfies A r = λ r (and lᴴ A = λ lᴴ) to round-off.
    fn assert_eigenpairs(a: &DMatrix<f64>, r: &Roots, tol: f64) {
        let ac = a.map(|v| Complex::new(v, 0.0));
        let scale = a.norm();
        for (k, l) in r.values.iter().enumerate() {
            let v = r.vectors.column(k);
            let res = &ac * v - v * *l;
            assert!(
                res.norm() <= tol * scale * v.norm(),
                "right {k}: {}",
                res.norm()
            );
            if r.left.ncols() > 0 {
                let w = r.left.column(k);
                let res = w.adjoint() * &ac - w.adjoint() * *l;
                assert!(res.norm() <= tol * scale * w.norm(), "left {k}");
            }
        }
    }

    #[test]
    fn fast_path_handles_state_matrices_and_agrees_with_faer() {
        use crate::preset::Preset;
        let cases: [(&str, &[&str]); 4] = [
            ("liu2017", &[]),
            ("demo-blade", &["aero.stations=16"]),
            ("goland", &[]),
            ("liu2017", &["aero.model=none", "structure.loss_factor=0"]),
        ];
        for (name, o) in cases {
            let o: Vec<String> = o.iter().map(|s| s.to_string()).collect();
            let a = linear_system(&Preset::load(name, &o).unwrap()).unwrap().a;
            let n = a.nrows();
            let d = balancing_scale(&a);
            let b = DMatrix::from_fn(n, n, |i, j| a[(i, j)] * d[j] / d[i]);
            // The fast path must not fall back on the matrices we actually solve.
            let (fast, _, _) = fast_decomposition(&b, true).expect(name);
            let (slow, _, _) = faer_decomposition(&b, true).unwrap();
            assert_eq!(fast.len(), slow.len(), "{name}");
            let big = slow.iter().map(|l| l.norm()).fold(0.0, f64::max);
            for x in &fast {
                let d = slow
                    .iter()
                    .map(|y| (x - y).norm())
                    .fold(f64::INFINITY, f64::min);
                assert!(d <= 1e-9 * big, "{name}: {x} not among faer's roots");
            }
            assert_eigenpairs(&a, &eigen_decomposition(&a).unwrap(), 1e-10);
        }
    }

    #[test]
    fn repeated_roots_get_independent_vectors() {
        // Two identical decoupled oscillators and a triple real root.
        let mut a = DMatrix::<f64>::zeros(7, 7);
        for k in 0..2 {
            a[(2 * k, 2 * k + 1)] = 1.0;
            a[(2 * k + 1, 2 * k)] = -4.0;
            a[(2 * k + 1, 2 * k + 1)] = -0.2;
        }
        for k in 4..7 {
            a[(k, k)] = -3.0;
        }
        assert!(fast_decomposition(&a, true).is_some());
        let r = eigen_decomposition(&a).unwrap();
        assert_eq!(r.values.len(), 5);
        assert_eigenpairs(&a, &r, 1e-10);
        // The eigenvectors of each repeated root span its eigenspace.
        let rank = |cols: Vec<usize>| {
            let m = DMatrix::from_fn(7, cols.len(), |i, j| r.vectors[(i, cols[j])]);
            m.svd(false, false)
                .singular_values
                .iter()
                .filter(|s| **s > 1e-8)
                .count()
        };
        let osc: Vec<usize> = (0..5).filter(|&k| r.values[k].im > 0.0).collect();
        let real: Vec<usize> = (0..5).filter(|&k| r.values[k].im == 0.0).collect();
        assert_eq!((rank(osc), rank(real)), (2, 3));
    }

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
