//! The multipliers: `(J W Jᵀ) λ = rhs`, a small symmetric solve over every joint row.
//!
//! ```text
//! K_ij = Σ over the bodies rows i and j share:  lin_i·lin_j / m + ang_i·I⁻¹_world ang_j
//! K = L Lᵀ  (Cholesky in place, no pivoting: K is symmetric positive definite when the rows
//!             are independent; a pivot below 1e-12 of the diagonal's largest is a redundant
//!             row, whose multiplier is set to 0; only inside each row's envelope, from its
//!             first column that shares a body)
//! ```
//!
//! The matrix is rebuilt and factored at every evaluation of f(Y) (rk4: four times a step);
//! for a chain of 10 ball joints, 30 rows whose envelope is 6 wide, that is about 30 · 6²/2
//! ≈ 540 multiply–adds instead of a dense 30³/6 ≈ 4500.

use super::rows::Row;
use nalgebra::{Matrix3, Vector3};

/// A row touching a body: (row, linear part, I⁻¹ · angular part, angular part).
type Touch = (usize, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    /// K, then its factor, row-major n × n.
    matrix: Vec<f64>,
    /// Per body: the rows touching it, (row, linear part, I⁻¹ angular part, angular part).
    touching: Vec<Vec<Touch>>,
    /// Per row: its first column inside the envelope.
    first: Vec<usize>,
}

/// The inverse mass and world inverse inertia of each body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inverse {
    pub mass: f64,
    pub inertia: Matrix3<f64>,
}

/// Solves `(J W Jᵀ) λ = rhs` for λ, written over `rhs`.
pub fn multipliers(rows: &[Row], inverse: &[Inverse], rhs: &mut [f64], solver: &mut Solver) {
    let n = rows.len();
    // Per body, the rows that touch it (row, its linear part, W·its angular part, its
    // angular part): K is summed body by body, over pairs of rows that share it.
    solver.touching.resize_with(inverse.len(), Vec::new);
    for list in &mut solver.touching {
        list.clear();
    }
    solver.first.clear();
    solver.first.extend(0..n);
    for (i, r) in rows.iter().enumerate() {
        let wa = inverse[r.a].inertia * r.ang_a;
        solver.touching[r.a].push((i, r.lin_a, wa, r.ang_a));
        if let Some(b) = r.b {
            let wb = inverse[b].inertia * r.ang_b;
            solver.touching[b].push((i, r.lin_b, wb, r.ang_b));
        }
    }
    solver.matrix.clear();
    solver.matrix.resize(n * n, 0.0);
    let k = &mut solver.matrix;
    for (body, list) in solver.touching.iter().enumerate() {
        let inv_mass = inverse.get(body).map_or(0.0, |b| b.mass);
        for (p, &(i, lin_i, w_i, _)) in list.iter().enumerate() {
            for &(j, lin_j, _, ang_j) in &list[..=p] {
                // Rows are pushed in order: j ≤ i.
                k[i * n + j] += lin_i.dot(&lin_j) * inv_mass + w_i.dot(&ang_j);
                solver.first[i] = solver.first[i].min(j);
            }
        }
    }
    factor_and_solve(k, n, &solver.first, rhs);
}

/// In place Cholesky `K = L Lᵀ` of the symmetric `k` (lower triangle used) inside its
/// envelope — row i's entries from `first[i]`, its first non-zero column, on (a chain's rows
/// only touch their neighbours', so the work is n·b² for a bandwidth b, not n³/6) — then the
/// solve of `k x = rhs`. A pivot below 1e-12 of the largest diagonal entry is a redundant row:
/// its reciprocal is set to 0, which makes its multiplier 0.
fn factor_and_solve(k: &mut [f64], n: usize, first: &[usize], rhs: &mut [f64]) {
    let largest = (0..n).map(|i| k[i * n + i].abs()).fold(0.0, f64::max);
    let tiny = 1e-12 * largest;
    // The pivots' reciprocals (0 for a redundant row) are kept on the diagonal: the solves
    // then multiply, and a division or square root sits on the critical path once per row,
    // not once per entry (their latency, not the multiply–adds, was the cost).
    for i in 0..n {
        let fi = first[i];
        let (head, tail) = k.split_at_mut(i * n);
        let row_i = &mut tail[..n];
        for j in fi..i {
            let from = fi.max(first[j]);
            let row_j = &head[j * n..j * n + n];
            let dot: f64 = row_i[from..j]
                .iter()
                .zip(&row_j[from..j])
                .map(|(a, b)| a * b)
                .sum();
            // row_j[j] is 1/L_jj (0 when row j was redundant: then L_ij = 0 too).
            row_i[j] = (row_i[j] - dot) * row_j[j];
        }
        let dot: f64 = row_i[fi..i].iter().map(|a| a * a).sum();
        let value = row_i[i] - dot;
        row_i[i] = if value > tiny {
            1.0 / value.sqrt()
        } else {
            0.0
        };
    }
    // L y = rhs, then Lᵀ x = y.
    for i in 0..n {
        let row = &k[i * n..i * n + n];
        let dot: f64 = row[first[i]..i]
            .iter()
            .zip(&rhs[first[i]..i])
            .map(|(a, b)| a * b)
            .sum();
        rhs[i] = (rhs[i] - dot) * row[i];
    }
    for i in (0..n).rev() {
        let row = &k[i * n..i * n + n];
        rhs[i] *= row[i];
        let x = rhs[i];
        for p in first[i]..i {
            rhs[p] -= row[p] * x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_and_solve_inverts_a_symmetric_positive_definite_matrix() {
        // K = [[4, 2, 0], [2, 5, 1], [0, 1, 3]], x = (1, −2, 3): K x = (0, −5, 7).
        let mut k = vec![4.0, 2.0, 0.0, 2.0, 5.0, 1.0, 0.0, 1.0, 3.0];
        let mut rhs = vec![0.0, -5.0, 7.0];
        factor_and_solve(&mut k, 3, &[0, 0, 0], &mut rhs);
        for (x, want) in rhs.iter().zip([1.0, -2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{rhs:?}");
        }
    }

    #[test]
    fn a_redundant_row_gets_a_zero_multiplier() {
        // Two equal rows: K = [[2, 2], [2, 2]], rhs (2, 2): λ = (1, 0) solves it.
        let mut k = vec![2.0, 2.0, 2.0, 2.0];
        let mut rhs = vec![2.0, 2.0];
        factor_and_solve(&mut k, 2, &[0, 0], &mut rhs);
        assert!((rhs[0] - 1.0).abs() < 1e-14 && rhs[1] == 0.0, "{rhs:?}");
    }
}
