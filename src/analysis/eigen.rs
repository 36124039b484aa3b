//! Eigen-analysis of the linearised aeroelastic system (docs/model.md §6).
//!
//! Input: the state matrix `A` at equilibrium ([`LinearSystem`]). Output: every root
//! `λ = σ ± iω` (one entry per conjugate pair) with frequency `ω/2π`, damping ratio `ζ = −σ/|λ|`,
//! a label from its eigenvector's Galerkin coefficients, its structural share (the participation
//! of `q, q̇` in the root, from left and right eigenvectors; roots with share < ½ are aero lags,
//! reported apart), and the stability verdict.
//!
//! The eigenvalues and eigenvectors come from [`crate::numeric::decompose`] (balancing, QR,
//! inverse iteration, faer's fallback), where every failure is an
//! [`Error::Numerical`](crate::error::Error::Numerical), never a hang or a panic; this module gives
//! the roots their aeroelastic meaning.

use crate::error::Result;
use crate::numeric::{decompose, hungarian, shares};
use crate::physics::structure::Structure;
use crate::physics::system::{LinearSystem, System};
use crate::preset::ValidPreset;
use nalgebra::{Complex, DVector};
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
    label_structural_roots(&mut structural, ls.structure.as_ref())?;
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
/// speed (docs/model.md §6): each root's q-part is expanded on the mass-normalised natural modes,
/// η = Φᵀ M q, and roots are assigned to modes one-to-one maximising the summed energy share
/// |η_k|² / Σ|η|² (Kuhn–Munkres), so no label repeats and none names a mode that does not
/// exist. Reading the label off the natural modes rather than off the root's own torsion
/// share matters on blades whose aerodynamic torsional stiffness dwarfs the structural one
/// (the paper's blade): there the torsion roots' shapes and frequencies move far from the
/// in-vacuo torsion modes, but their modal content still identifies them. For the weak
/// (symmetric) form η are the exact modal coordinates; for the strong form an M-weighted
/// projection, which is all the assignment needs.
fn label_structural_roots(roots: &mut [Mode], structure: &dyn Structure) -> Result<()> {
    if roots.is_empty() {
        return Ok(());
    }
    let natural = structure.natural_modes()?;
    let mass = structure.mass();
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
            shares(energy)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::balance::{balanced, balancing_scale};
    use crate::numeric::eigen::tests::assert_eigenpairs;
    use crate::numeric::eigen::{faer_decomposition, fast_decomposition};
    use crate::numeric::eigen_decomposition;

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
            let b = balanced(&a, &balancing_scale(&a));
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
}
