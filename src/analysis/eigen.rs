//! Eigen-analysis of the linearised aeroelastic system (docs/model.md §6).
//!
//! Input: the state matrix `A` at equilibrium ([`LinearSystem`]). Output: every root
//! `λ = σ ± iω` (one entry per conjugate pair) with frequency `ω/2π`, damping ratio `ζ = −σ/|λ|`,
//! its structural share (the participation of `q, q̇` in the root, from left and right
//! eigenvectors), its name and family from [`crate::analysis::identify`] (structural modes, an
//! overdamped pair as one mode; aerodynamic roots reported apart), and the stability verdict.
//!
//! The eigenvalues and eigenvectors come from [`crate::numeric::decompose`] (balancing, QR,
//! inverse iteration, faer's fallback), where every failure is an
//! [`Error::Numerical`](crate::error::Error::Numerical), never a hang or a panic; this module gives
//! the roots their aeroelastic meaning.

use crate::analysis::identify::{identify, Identified};
use crate::analysis::mode::Mode;
use crate::error::Result;
use crate::numeric::decompose;
use crate::physics::system::LinearSystem;
use crate::preset::ValidPreset;
use nalgebra::Complex;
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
    /// A free rotor's turning grows ([`Mode::rigid_body`]): open loop, the generator holds its
    /// torque while the aerodynamic torque rises with speed (docs/model.md §13.1).
    Runaway,
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
    let (system, equilibrium) = crate::model::system_with_equilibrium(p)?;
    crate::model::linearised(p, &system, equilibrium)
}

/// Eigen-analysis of an assembled linear system (sweeps reuse their own systems).
///
/// Left eigenvectors are computed only when there are aerodynamic states: without them every
/// state is structural and the participation share is 1 for every root by definition.
pub fn analyse_system(ls: &LinearSystem) -> Result<Stability> {
    let roots = decompose(&ls.a, ls.n_aero > 0)?;
    let nq = ls.nq;
    let structure = ls.structure.as_ref();
    let scale = roots.values.iter().map(|l| l.norm()).fold(1.0, f64::max);
    let tol = NEUTRAL_TOLERANCE * scale;
    let all: Vec<Mode> = roots
        .values
        .iter()
        .enumerate()
        .map(|(k, lambda)| {
            let q: Vec<Complex<f64>> = motion_pattern(&roots.vectors.column(k), nq);
            let left: Vec<Complex<f64>> = if roots.left.ncols() == 0 {
                Vec::new()
            } else {
                roots.left.column(k).rows(0, nq).iter().copied().collect()
            };
            // Structural states are q and q̇, the first 2·nq.
            let share: f64 = if roots.left.ncols() == 0 {
                1.0
            } else {
                roots.participation_of_first(k, 2 * nq)
            };
            let im = if lambda.im.abs() <= tol {
                0.0
            } else {
                lambda.im
            };
            Mode {
                // ζ from the exact λ: a root within the tolerance of the real axis is still
                // damped as its true |λ| says.
                damping_ratio: Mode::root(lambda.re, lambda.im).damping_ratio,
                shares: structure.shares(&q),
                components: structure.components(&q),
                structural_share: share,
                shape: normalised_shape(&q),
                left_shape: normalised_shape(&left),
                ..Mode::root(lambda.re, im)
            }
        })
        .collect();
    let all = without_rigid_body_roots(all, structure.rigid_body_roots(), tol);
    let Identified {
        structural: mut named,
        aero: mut lags,
    } = identify(all, nq, structure)?;
    for m in named
        .iter_mut()
        .filter(|m| m.im == 0.0 && m.re.abs() <= tol)
    {
        // A real root within round-off of zero (a free rotor's azimuth, alone or with the
        // aerodynamic torque's decay) neither decays nor grows.
        m.damping_ratio = 0.0;
    }
    for m in named.iter_mut() {
        m.rotating_hz = structure
            .rotating_shift_hz(&m.label)
            .map(|shift| m.frequency_hz + shift);
    }
    least_stable_first(&mut named);
    least_stable_first(&mut lags);
    for (k, m) in lags.iter_mut().enumerate() {
        m.label = format!("aero lag {}", k + 1);
    }
    let verdict = verdict_of(named.iter().chain(&lags), tol);
    Ok(Stability {
        stable: verdict == Verdict::Stable,
        verdict,
        eigenvalues: named,
        aero_lags: lags,
    })
}

/// Roots by decay rate, the least stable first; roots whose rates agree to 1e-9 of the largest
/// root (a rotor's backward, forward and collective whirls of one blade mode in vacuo, whose
/// rates are one number up to round-off) by frequency, so that their order does not turn on
/// the last bits.
fn least_stable_first(modes: &mut [Mode]) {
    let scale = modes.iter().map(|m| m.re.hypot(m.im)).fold(0.0, f64::max);
    let grid = (1e-9 * scale).max(f64::MIN_POSITIVE);
    modes.sort_by(|a, b| {
        (b.re / grid)
            .round()
            .total_cmp(&(a.re / grid).round())
            .then(a.im.total_cmp(&b.im))
    });
}

/// `roots` less the `count` real roots nearest zero, where they lie within `tol` of it: the
/// azimuth of a free rotor ([`crate::physics::structure::Structure::rigid_body_roots`]),
/// neither a mode nor a stability margin.
fn without_rigid_body_roots(mut roots: Vec<Mode>, count: usize, tol: f64) -> Vec<Mode> {
    for _ in 0..count {
        let nearest = roots
            .iter()
            .enumerate()
            .filter(|(_, m)| m.im == 0.0 && m.re.abs() <= tol)
            .min_by(|a, b| a.1.re.abs().total_cmp(&b.1.re.abs()))
            .map(|(i, _)| i);
        if let Some(i) = nearest {
            roots.remove(i);
        }
    }
    roots
}

fn verdict_of<'a>(roots: impl Iterator<Item = &'a Mode>, tol: f64) -> Verdict {
    match roots.max_by(|a, b| a.re.total_cmp(&b.re)) {
        Some(m) if m.re > tol => {
            if m.im > 0.0 {
                Verdict::Flutter
            } else if m.rigid_body() {
                Verdict::Runaway
            } else {
                Verdict::Divergence
            }
        }
        _ => Verdict::Stable,
    }
}

/// The structural coordinates that name a root: its displacements, or, for a root whose
/// displacements vanish against its rates (the coasting root of a free body, a rotor's
/// rigid rotation at rest: its eigenvalue is zero and defective), its rates.
fn motion_pattern(v: &nalgebra::DVectorView<Complex<f64>>, nq: usize) -> Vec<Complex<f64>> {
    let q = v.rows(0, nq);
    let rate = v.rows(nq, nq);
    let pick = if q.norm() < 1e-8 * rate.norm() {
        rate
    } else {
        q
    };
    pick.iter().copied().collect()
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

    /// Three whirls of one blade mode whose rates differ in the last bits come out by
    /// frequency whichever bits they carry; a rate a millionth apart still decides.
    #[test]
    fn rates_equal_to_round_off_are_ordered_by_frequency() {
        let sigma = -1.3505234946235527;
        let order = |rates: [f64; 3]| {
            let mut modes: Vec<Mode> = rates
                .iter()
                .zip([36.3, 33.8, 35.0])
                .map(|(&re, im)| Mode::root(re, im))
                .collect();
            modes.push(Mode::root(sigma * (1.0 + 1e-6), 34.0));
            least_stable_first(&mut modes);
            modes.iter().map(|m| m.im).collect::<Vec<_>>()
        };
        let expected = vec![33.8, 35.0, 36.3, 34.0];
        let ulp = sigma * f64::EPSILON;
        assert_eq!(order([sigma, sigma + ulp, sigma - ulp]), expected);
        assert_eq!(order([sigma - ulp, sigma, sigma + 2.0 * ulp]), expected);
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
