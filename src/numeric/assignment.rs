//! Optimal assignment (Kuhn–Munkres): the one-to-one pairing of rows and columns of minimum total
//! cost. Mode labelling pairs roots with natural modes by it, mode tracking pairs the modes of
//! consecutive sweep points; both need the optimum, not a greedy pick.

/// Minimum-cost assignment of every row to its own column (Kuhn–Munkres with potentials,
/// O(n²m) for n rows and m ≥ n columns). Returns the column assigned to each row. Fewer columns
/// than rows count as padded with zero-cost columns: the rows left over get indices from m on.
/// The caller's candidates are rows and its names columns (with a column per candidate for being
/// left unnamed): no padding rows, so a third of the work of the square form on a turbine.
///
/// Exact (comparisons only, no tolerance) and finite without an iteration cap: each pass of a
/// row's search marks one more column as used, and with finite costs a free column is reached
/// before every column is, so a row takes at most m + 1 passes. A NaN or infinite cost (which a
/// caller should never produce) is replaced by a finite cost above any complete assignment of
/// the finite ones, so such a pairing is taken only when nothing else is possible.
pub fn hungarian(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    if n == 0 {
        return Vec::new();
    }
    let m = cost.iter().map(Vec::len).max().unwrap_or(0).max(n);
    let largest = cost
        .iter()
        .flatten()
        .filter(|c| c.is_finite())
        .fold(0.0_f64, |m, c| m.max(c.abs()));
    let worst = (1.0 + 2.0 * n as f64 * largest).min(f64::MAX / 4.0);
    let sane: Vec<Vec<f64>>;
    let cost = if cost
        .iter()
        .all(|row| row.len() == m && row.iter().all(|c| c.is_finite()))
    {
        cost
    } else {
        sane = cost
            .iter()
            .map(|row| {
                (0..m)
                    .map(|j| match row.get(j) {
                        Some(&c) if !c.is_finite() => worst,
                        Some(&c) => c,
                        None => 0.0,
                    })
                    .collect()
            })
            .collect();
        &sane
    };
    // 1-based arrays as in the classic formulation; column 0 is the virtual start.
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; m + 1];
    let mut owner = vec![0usize; m + 1];
    let mut way = vec![0usize; m + 1];
    for row in 1..=n {
        owner[0] = row;
        let mut j0 = 0;
        let mut minv = vec![f64::INFINITY; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = owner[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0;
            for j in 1..=m {
                if used[j] {
                    continue;
                }
                let reduced = cost[i0 - 1][j - 1] - u[i0] - v[j];
                if reduced < minv[j] {
                    minv[j] = reduced;
                    way[j] = j0;
                }
                if minv[j] < delta {
                    delta = minv[j];
                    j1 = j;
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[owner[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if owner[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            owner[j0] = owner[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut assignment = vec![0; n];
    for j in 1..=m {
        if owner[j] > 0 {
            assignment[owner[j] - 1] = j - 1;
        }
    }
    assignment
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hungarian_beats_greedy() {
        // Greedy on row 0 takes column 0 (cost 1) and forces row 1 onto column 1 (cost 10):
        // total 11. The optimum is 2 + 2 = 4.
        let cost = vec![vec![1.0, 2.0], vec![2.0, 10.0]];
        assert_eq!(hungarian(&cost), vec![1, 0]);
    }

    #[test]
    fn non_finite_costs_end_in_a_permutation_that_avoids_them() {
        let cost = vec![
            vec![f64::NAN, 1.0, 5.0],
            vec![2.0, f64::INFINITY, 1.0],
            vec![1.0, 3.0, f64::NAN],
        ];
        let a = hungarian(&cost);
        let mut seen = a.clone();
        seen.sort();
        assert_eq!(seen, vec![0, 1, 2]);
        assert_eq!(a, vec![1, 2, 0]);
        // All non-finite: still a permutation, no hang, no panic.
        let a = hungarian(&vec![vec![f64::NAN; 3]; 3]);
        let mut seen = a.clone();
        seen.sort();
        assert_eq!(seen, vec![0, 1, 2]);
    }

    /// Rows fewer than columns take the cheapest distinct columns; more rows than columns leave
    /// the rows that fit worst beyond the last column, as zero-cost padding would.
    #[test]
    fn rectangular_costs_assign_every_row_once() {
        let wide = vec![vec![4.0, 1.0, 3.0, 9.0], vec![2.0, 0.5, 5.0, 9.0]];
        assert_eq!(hungarian(&wide), vec![1, 0]);
        let tall = vec![vec![1.0, 7.0], vec![6.0, 2.0], vec![5.0, 5.0]];
        let a = hungarian(&tall);
        assert_eq!(&a[..2], &[0, 1]);
        assert!(a[2] >= 2);
        // The wide matrix padded square with zero-cost rows gives the same rows' columns.
        let mut square = wide.clone();
        square.extend([vec![0.0; 4], vec![0.0; 4]]);
        assert_eq!(&hungarian(&square)[..2], &hungarian(&wide)[..]);
    }
}
