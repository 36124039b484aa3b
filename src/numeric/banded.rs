//! Symmetric banded matrices: storage of the lower band, the product with a vector, and the
//! Cholesky factor `A = LLᵀ` with its solve. A finite-element matrix couples only the dofs of
//! neighbouring nodes, so its entries lie within a few places of the diagonal (the tabulated
//! blade's: half-bandwidth 9, docs/model.md §11.3); in band form a product or a solve costs
//! O(n·band) instead of O(n²), and the factor O(n·band²) instead of O(n³).

use nalgebra::DMatrix;

/// A symmetric `n × n` matrix whose entries vanish more than `band` places off the diagonal.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetricBand {
    n: usize,
    band: usize,
    /// Row `i` of the lower band, `(i, i − band) … (i, i)`, at `i·(band + 1)`; places left of
    /// column 0 hold zeros, so every row has the same length and the loops need no special start.
    lower: Vec<f64>,
}

/// The widest distance from the diagonal of a non-zero entry of `a`.
pub fn half_bandwidth(a: &DMatrix<f64>) -> usize {
    let mut band = 0;
    for j in 0..a.ncols() {
        for (i, v) in a.column(j).iter().enumerate() {
            if *v != 0.0 {
                band = band.max(i.abs_diff(j));
            }
        }
    }
    band
}

impl SymmetricBand {
    /// The band of `a` (square), each entry the mean of `a[(i, j)]` and `a[(j, i)]`: a matrix
    /// symmetric in exact arithmetic is made so in floating point, as the dense solvers do.
    /// Entries beyond `band` are ignored; [`half_bandwidth`] gives the band that keeps them all.
    pub fn from_dense(a: &DMatrix<f64>, band: usize) -> SymmetricBand {
        let n = a.nrows();
        let width = band + 1;
        let mut lower = vec![0.0; n * width];
        for i in 0..n {
            for j in i.saturating_sub(band)..=i {
                lower[i * width + j + band - i] = 0.5 * (a[(i, j)] + a[(j, i)]);
            }
        }
        SymmetricBand { n, band, lower }
    }

    /// The `n × n` zero matrix with room for entries `band` places off the diagonal.
    pub fn zeros(n: usize, band: usize) -> SymmetricBand {
        SymmetricBand {
            n,
            band,
            lower: vec![0.0; n * (band + 1)],
        }
    }

    /// Add `v` to entry `(i, j)` of the lower band and so to `(j, i)` (`j ≤ i ≤ j + band`).
    pub fn add_lower(&mut self, i: usize, j: usize, v: f64) {
        debug_assert!(
            j <= i && i - j <= self.band,
            "({i}, {j}) outside the lower band"
        );
        self.lower[i * (self.band + 1) + j + self.band - i] += v;
    }

    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.lower.iter().all(|v| v.is_finite())
    }

    pub fn size(&self) -> usize {
        self.n
    }

    pub fn band(&self) -> usize {
        self.band
    }

    /// `self + s·other` (same size; the result has the wider band).
    pub fn plus(&self, s: f64, other: &SymmetricBand) -> SymmetricBand {
        assert_eq!(self.n, other.n, "banded sum of different sizes");
        let band = self.band.max(other.band);
        let width = band + 1;
        let mut lower = vec![0.0; self.n * width];
        for i in 0..self.n {
            for d in 0..=self.band {
                lower[i * width + band - d] += self.lower[i * (self.band + 1) + self.band - d];
            }
            for d in 0..=other.band {
                lower[i * width + band - d] +=
                    s * other.lower[i * (other.band + 1) + other.band - d];
            }
        }
        SymmetricBand {
            n: self.n,
            band,
            lower,
        }
    }

    /// Entry `(i, j)` (zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > self.band {
            0.0
        } else {
            self.lower[i * (self.band + 1) + j + self.band - i]
        }
    }

    /// `y = A x`: [`Self::mul`]'s sums for one column, by scalars. Lanczos calls it for every
    /// Krylov vector, and the row-slice loops of `mul` with one value a row made the IEA 15MW
    /// modal basis half as slow again (56 ms against 38 ms, `blade › modal_basis_iea15mw`).
    pub fn mul_into(&self, x: &[f64], y: &mut [f64]) {
        let (n, band) = (self.n, self.band);
        let width = band + 1;
        y.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n {
            let row = &self.lower[i * width..(i + 1) * width];
            let lo = i.saturating_sub(band);
            let mut yi = row[band] * x[i];
            for j in lo..i {
                let a = row[j + band - i];
                yi += a * x[j];
                y[j] += a * x[i];
            }
            y[i] += yi;
        }
    }

    /// `A X` for every column of `x`, each band entry applied to a whole row of `X` at once (rows
    /// made contiguous by transposing), so the inner loop runs along memory over the columns;
    /// each column's sums in [`Self::mul_into`]'s order.
    pub fn mul(&self, x: &DMatrix<f64>) -> DMatrix<f64> {
        assert_eq!(
            x.nrows(),
            self.n,
            "banded product: {} rows for a {n} × {n} matrix",
            x.nrows(),
            n = self.n
        );
        let b = x.ncols();
        let mut yt = DMatrix::zeros(b, self.n);
        self.mul_rows(x.transpose().as_slice(), b, yt.as_mut_slice());
        yt.transpose()
    }

    /// `Y = A X` with `X` and `Y` stored by rows, `b` values a row: the row's lower band gives
    /// `Y`'s row `i`, its mirror image (the column above the diagonal) adds to the earlier rows.
    fn mul_rows(&self, xs: &[f64], b: usize, ys: &mut [f64]) {
        let (n, band) = (self.n, self.band);
        let width = band + 1;
        ys.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..n {
            let row = &self.lower[i * width..(i + 1) * width];
            let lo = i.saturating_sub(band);
            let xi = &xs[i * b..(i + 1) * b];
            // Row i is untouched until here: the earlier rows only add to rows before them.
            let (before, from_i) = ys.split_at_mut(i * b);
            let yi = &mut from_i[..b];
            for (v, x) in yi.iter_mut().zip(xi) {
                *v = row[band] * x;
            }
            for j in lo..i {
                let a = row[j + band - i];
                for (v, x) in yi.iter_mut().zip(&xs[j * b..(j + 1) * b]) {
                    *v += a * x;
                }
                for (y, x) in before[j * b..(j + 1) * b].iter_mut().zip(xi) {
                    *y += a * x;
                }
            }
        }
    }

    /// The Cholesky factor, or `None` when a pivot is not positive (the matrix is not positive
    /// definite) or not finite.
    pub fn cholesky(&self) -> Option<BandCholesky> {
        let (n, band) = (self.n, self.band);
        let width = band + 1;
        let mut l = self.lower.clone();
        for i in 0..n {
            let lo = i.saturating_sub(band);
            for j in lo..=i {
                // L_ij = (A_ij − Σ_k L_ik L_jk) / L_jj over the columns both rows reach.
                let start = lo.max(j.saturating_sub(band));
                let mut s = l[i * width + j + band - i];
                for k in start..j {
                    s -= l[i * width + k + band - i] * l[j * width + k + band - j];
                }
                if j == i {
                    if !(s > 0.0 && s.is_finite()) {
                        return None;
                    }
                    l[i * width + band] = s.sqrt();
                } else {
                    l[i * width + j + band - i] = s / l[j * width + band];
                }
            }
        }
        Some(BandCholesky { n, band, l })
    }
}

/// `A = LLᵀ` of a [`SymmetricBand`], `L` lower with the same band.
#[derive(Debug, Clone)]
pub struct BandCholesky {
    n: usize,
    band: usize,
    /// Rows of `L` in the layout of [`SymmetricBand`].
    l: Vec<f64>,
}

impl BandCholesky {
    /// Overwrite `b` with `A⁻¹ b`.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, band) = (self.n, self.band);
        let width = band + 1;
        for i in 0..n {
            let row = &self.l[i * width..(i + 1) * width];
            let mut s = b[i];
            for k in i.saturating_sub(band)..i {
                s -= row[k + band - i] * b[k];
            }
            b[i] = s / row[band];
        }
        // Lᵀ x = y by columns of Lᵀ (rows of L), so the stored rows are read in order.
        for i in (0..n).rev() {
            let row = &self.l[i * width..(i + 1) * width];
            let xi = b[i] / row[band];
            b[i] = xi;
            for k in i.saturating_sub(band)..i {
                b[k] -= row[k + band - i] * xi;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    /// A symmetric positive definite matrix with half-bandwidth 3, as dense.
    fn banded_spd(n: usize) -> DMatrix<f64> {
        DMatrix::from_fn(n, n, |i, j| match i.abs_diff(j) {
            0 => 10.0 + i as f64,
            1 => -2.0 + 0.1 * (i + j) as f64,
            2 => 0.5,
            3 => -0.25,
            _ => 0.0,
        })
    }

    #[test]
    fn product_solve_and_sum_match_the_dense_matrix() {
        let a = banded_spd(12);
        assert_eq!(half_bandwidth(&a), 3);
        let b = SymmetricBand::from_dense(&a, 3);
        let x = DVector::from_fn(12, |i, _| (i as f64 * 0.7).sin());
        let mut y = vec![0.0; 12];
        b.mul_into(x.as_slice(), &mut y);
        assert!((DVector::from_vec(y) - &a * &x).norm() < 1e-13);
        // Many columns at once: each the single-vector product, to the bit.
        let xs = DMatrix::from_fn(12, 5, |i, c| ((i * 3 + c) as f64 * 0.37).cos());
        let ys = b.mul(&xs);
        assert!((&ys - &a * &xs).norm() < 1e-13);
        for c in 0..5 {
            let mut yc = vec![0.0; 12];
            b.mul_into(xs.column(c).as_slice(), &mut yc);
            assert_eq!(ys.column(c).as_slice(), &yc[..], "column {c}");
        }

        let mut z = x.as_slice().to_vec();
        b.cholesky().unwrap().solve_in_place(&mut z);
        let dense = a.clone().cholesky().unwrap().solve(&x);
        assert!((DVector::from_vec(z) - dense).norm() < 1e-13);

        let identity = SymmetricBand::from_dense(&DMatrix::identity(12, 12), 0);
        let sum = identity.plus(-2.0, &b);
        let expected = DMatrix::identity(12, 12) - &a * 2.0;
        for i in 0..12 {
            for j in 0..12 {
                assert_eq!(sum.get(i, j), expected[(i, j)], "({i}, {j})");
            }
        }
    }

    #[test]
    fn an_indefinite_matrix_has_no_factor() {
        let mut a = banded_spd(8);
        a[(5, 5)] = -1.0;
        assert!(SymmetricBand::from_dense(&a, 3).cholesky().is_none());
    }
}
