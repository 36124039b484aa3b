//! LU factors with partial pivoting, `P A = L U`, by faer's blocked factorisation on the calling
//! thread. Blocked, it takes a quarter of the time of nalgebra's unblocked one on a turbine's
//! 263-state block; on this thread, because faer's `partial_piv_lu` runs on its global
//! parallelism, rayon's whole pool, and so took 2.3 ms against about 0.6 ms for that block on a
//! loaded 2-core machine. One factorisation serves many right-hand sides (a left-out block's
//! quasi-static and dynamic responses, an isolated root's vectors).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::{MatMut, MatRef};
use nalgebra::DMatrix;

pub(crate) struct Lu {
    /// L below the diagonal (unit diagonal implied), U on and above it.
    pub(crate) lu: faer::Mat<f64>,
    /// Row i of P A is row `from[i]` of A.
    pub(crate) from: Vec<usize>,
    /// Row i of A is row `to[i]` of P A.
    to: Vec<usize>,
}

impl Lu {
    /// The factors of the square matrix `lu`, in its place.
    pub(crate) fn of(mut lu: faer::Mat<f64>) -> Lu {
        let m = lu.nrows();
        let (mut from, mut to) = (vec![0usize; m], vec![0usize; m]);
        let par = faer::Par::Seq;
        let mut scratch = MemBuffer::new(factor::lu_in_place_scratch::<usize, f64>(
            m,
            m,
            par,
            Default::default(),
        ));
        factor::lu_in_place(
            lu.as_mut(),
            &mut from,
            &mut to,
            par,
            MemStack::new(&mut scratch),
            Default::default(),
        );
        Lu { lu, from, to }
    }

    /// The factors of `a`.
    pub(crate) fn of_matrix(a: &DMatrix<f64>) -> Lu {
        Lu::of(MatRef::from_column_major_slice(a.as_slice(), a.nrows(), a.ncols()).to_owned())
    }

    /// `A⁻¹ b` for every column of `b`; none where A is singular (a zero pivot).
    pub(crate) fn solve(&self, b: &DMatrix<f64>) -> Option<DMatrix<f64>> {
        let m = self.lu.nrows();
        if (0..m).any(|i| self.lu[(i, i)] == 0.0) {
            return None;
        }
        let mut x = b.clone();
        let par = faer::Par::Seq;
        let mut scratch = MemBuffer::new(solve::solve_in_place_scratch::<usize, f64>(
            m,
            b.ncols(),
            par,
        ));
        let perm = PermRef::new_checked(&self.from, &self.to, m);
        solve::solve_in_place(
            self.lu.as_ref(),
            self.lu.as_ref(),
            perm,
            MatMut::from_column_major_slice_mut(x.as_mut_slice(), m, b.ncols()),
            par,
            MemStack::new(&mut scratch),
        );
        Some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_pivoting_system_for_many_right_hand_sides() {
        // The zero in the corner forces a row exchange.
        let a = DMatrix::from_row_slice(3, 3, &[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 4.0]);
        let b = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 2.0, -1.0, 3.0, 5.0]);
        let x = Lu::of_matrix(&a).solve(&b).unwrap();
        assert!((&a * &x - &b).abs().max() < 1e-14, "{x}");
    }

    #[test]
    fn a_matrix_with_nan_does_not_panic() {
        let a = DMatrix::from_row_slice(2, 2, &[f64::NAN, 1.0, 1.0, 2.0]);
        if let Some(x) = Lu::of_matrix(&a).solve(&DMatrix::identity(2, 2)) {
            assert!(x.iter().any(|v| !v.is_finite()), "{x}");
        }
    }

    #[test]
    fn a_singular_matrix_has_no_solution() {
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(Lu::of_matrix(&a).solve(&DMatrix::identity(2, 2)).is_none());
    }
}
