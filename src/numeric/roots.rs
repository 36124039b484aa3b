//! The roots of a dense real eigenproblem as the solvers hand them on: eigenvalues (one per real
//! root and per conjugate pair) with right and left eigenvectors, which solver found them, and
//! the participation of each state in each root.

use nalgebra::{Complex, DMatrix};

/// Eigenvalues with right and left eigenvectors of a real square matrix, one entry per real
/// root and one per complex-conjugate pair (the member with ω ≥ 0).
#[derive(Debug, Clone)]
pub struct Roots {
    pub values: Vec<Complex<f64>>,
    /// Column k is the right eigenvector of `values[k]`: `A r = λ r`.
    pub vectors: DMatrix<Complex<f64>>,
    /// Column k is the left eigenvector of `values[k]`: `lᴴ A = λ lᴴ`.
    pub left: DMatrix<Complex<f64>>,
    /// Which solver found the roots of the active block, so callers and tests can count
    /// fallbacks instead of timing them.
    pub solver: Solver,
}

/// The solver behind a [`Roots`] (see [`super::decompose`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solver {
    /// Balancing, Hessenberg QR eigenvalues, inverse iteration (or nothing left to iterate on).
    Fast,
    /// faer's full decomposition, the first choice on a large active block.
    Schur,
    /// The other of the two, after the first choice failed.
    Fallback,
}

impl Roots {
    /// Participation of state `i` in root `k`, `|l_i| |r_i|`, normalised over the states.
    /// Unlike eigenvector magnitudes, participation factors do not depend on the units or scaling
    /// of the states, so they tell a structural root from an aerodynamic-lag root without
    /// arbitrary weights.
    pub fn participation(&self, k: usize) -> Vec<f64> {
        shares(self.raw_participation(k).collect())
    }

    /// The summed participation share of the first `states` states in root `k` (0 when no
    /// state participates), without the per-state vector.
    pub fn participation_of_first(&self, k: usize, states: usize) -> f64 {
        let (mut part, mut total) = (0.0, 0.0);
        for (i, p) in self.raw_participation(k).enumerate() {
            total += p;
            if i < states {
                part += p;
            }
        }
        if total > 0.0 {
            part / total
        } else {
            part
        }
    }

    /// `|l_i| |r_i|` of root `k`, state by state (one square root a state, not two).
    fn raw_participation<'a>(&'a self, k: usize) -> impl Iterator<Item = f64> + 'a {
        let n = self.vectors.nrows();
        let (right, left) = (self.vectors.as_slice(), self.left.as_slice());
        let column = |m: &'a [Complex<f64>]| m.get(k * n..(k + 1) * n).unwrap_or(&[]);
        column(right)
            .iter()
            .zip(column(left))
            .map(|(r, l)| (r.norm_sqr() * l.norm_sqr()).sqrt())
    }
}

/// Non-negative `parts` divided by their sum, so they add up to 1 (left as they are when they sum
/// to zero).
pub fn shares(parts: Vec<f64>) -> Vec<f64> {
    let total: f64 = parts.iter().sum();
    if total > 0.0 {
        parts.iter().map(|p| p / total).collect()
    } else {
        parts
    }
}
