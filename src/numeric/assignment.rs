//! Optimal assignment (Kuhn–Munkres): the one-to-one pairing of rows and columns of minimum total
//! cost. Mode labelling pairs roots with natural modes by it, mode tracking pairs the modes of
//! consecutive sweep points; both need the optimum, not a greedy pick.

/// Minimum-cost perfect assignment on a square cost matrix (Kuhn–Munkres with potentials,
/// O(n³)). Returns the column assigned to each row.
///
/// Exact (comparisons only, no tolerance) and finite without an iteration cap: each pass of a
/// row's search marks one more column as used, and with finite costs a free column is reached
/// before every column is, so a row takes at most n + 1 passes. A NaN or infinite cost could
/// leave no column to pick; that panics instead of looping.
pub fn hungarian(cost: &[Vec<f64>]) -> Vec<usize> {
    let n = cost.len();
    if n == 0 {
        return Vec::new();
    }
    // 1-based arrays as in the classic formulation; column 0 is the virtual start.
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; n + 1];
    let mut owner = vec![0usize; n + 1];
    let mut way = vec![0usize; n + 1];
    for row in 1..=n {
        owner[0] = row;
        let mut j0 = 0;
        let mut minv = vec![f64::INFINITY; n + 1];
        let mut used = vec![false; n + 1];
        loop {
            used[j0] = true;
            let i0 = owner[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0;
            for j in 1..=n {
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
            assert!(
                j1 != 0,
                "assignment cost matrix has NaN or infinite entries"
            );
            for j in 0..=n {
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
    for j in 1..=n {
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
}
