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
//! ≈ 540 multiply–adds instead of a dense 30³/6 ≈ 4500. Only the envelope is stored (skyline:
//! 141 numbers for the chain, not 900), and each pivot's reciprocal is kept, so one square
//! root and one division per row sit on the critical path, not one division per entry.
//! The factor is not reused across rk4's stages: each stage's K is at its own configuration,
//! and an old factor would make λ, hence the method, inexact.

use super::rows::Row;
use nalgebra::{Matrix3, Vector3};

/// A row touching a body: (row, linear part, I⁻¹ · angular part, angular part).
type Touch = (usize, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    /// K's lower triangle inside its envelope, then its factor: row i holds columns
    /// `first[i]..=i` from `start[i]` on (skyline storage).
    matrix: Vec<f64>,
    /// Per body: the rows touching it, (row, linear part, I⁻¹ angular part, angular part).
    touching: Vec<Vec<Touch>>,
    /// Per row: its first column inside the envelope.
    first: Vec<usize>,
    /// Per row: where it starts in `matrix`; one more entry, the total.
    start: Vec<usize>,
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
    for (i, r) in rows.iter().enumerate() {
        let wa = inverse[r.a].inertia * r.ang_a;
        solver.touching[r.a].push((i, r.lin_a, wa, r.ang_a));
        if let Some(b) = r.b {
            let wb = inverse[b].inertia * r.ang_b;
            solver.touching[b].push((i, r.lin_b, wb, r.ang_b));
        }
    }
    // The envelope: row i reaches back to the first row of every body it touches (rows are
    // pushed in order, so a body's list starts with its first row).
    solver.first.clear();
    solver.first.extend(0..n);
    for list in &solver.touching {
        if let Some(&(f, ..)) = list.first() {
            for &(i, ..) in list {
                solver.first[i] = solver.first[i].min(f);
            }
        }
    }
    solver.start.clear();
    solver.start.push(0);
    for i in 0..n {
        let next = solver.start[i] + i - solver.first[i] + 1;
        solver.start.push(next);
    }
    solver.matrix.clear();
    solver.matrix.resize(solver.start[n], 0.0);
    let k = &mut solver.matrix;
    for (body, list) in solver.touching.iter().enumerate() {
        let inv_mass = inverse.get(body).map_or(0.0, |b| b.mass);
        for (p, &(i, lin_i, w_i, _)) in list.iter().enumerate() {
            let row = solver.start[i] - solver.first[i];
            for &(j, lin_j, _, ang_j) in &list[..=p] {
                // Rows are pushed in order: j ≤ i.
                k[row + j] += lin_i.dot(&lin_j) * inv_mass + w_i.dot(&ang_j);
            }
        }
    }
    factor_and_solve(k, &solver.first, &solver.start, rhs);
}

/// In place Cholesky `K = L Lᵀ` of the symmetric `k` (lower triangle, skyline storage: row i
/// holds columns `first[i]..=i` from `start[i]` on) inside its envelope — a chain's rows only
/// touch their neighbours', so the work is n·b² for a bandwidth b, not n³/6 — then the solve
/// of `k x = rhs`. A pivot below 1e-12 of the largest diagonal entry is a redundant row: its
/// reciprocal is set to 0, which makes its multiplier 0.
fn factor_and_solve(k: &mut [f64], first: &[usize], start: &[usize], rhs: &mut [f64]) {
    let n = first.len();
    let diagonal = |i: usize| start[i + 1] - 1;
    let largest = (0..n).map(|i| k[diagonal(i)].abs()).fold(0.0, f64::max);
    let tiny = 1e-12 * largest;
    // The pivots' reciprocals (0 for a redundant row) are kept on the diagonal: the solves
    // then multiply, and a division or square root sits on the critical path once per row,
    // not once per entry (their latency, not the multiply–adds, was the cost).
    for i in 0..n {
        let fi = first[i];
        let (head, tail) = k.split_at_mut(start[i]);
        let row_i = &mut tail[..=i - fi];
        for j in fi..i {
            let fj = first[j];
            let from = fi.max(fj);
            let row_j = &head[start[j]..=start[j] + j - fj];
            let dot: f64 = row_i[from - fi..j - fi]
                .iter()
                .zip(&row_j[from - fj..j - fj])
                .map(|(a, b)| a * b)
                .sum();
            // row_j[j − fj] is 1/L_jj (0 when row j was redundant: then L_ij = 0 too).
            row_i[j - fi] = (row_i[j - fi] - dot) * row_j[j - fj];
        }
        let dot: f64 = row_i[..i - fi].iter().map(|a| a * a).sum();
        let value = row_i[i - fi] - dot;
        row_i[i - fi] = if value > tiny {
            1.0 / value.sqrt()
        } else {
            0.0
        };
    }
    // L y = rhs, then Lᵀ x = y.
    for i in 0..n {
        let fi = first[i];
        let row = &k[start[i]..start[i + 1]];
        let dot: f64 = row[..i - fi]
            .iter()
            .zip(&rhs[fi..i])
            .map(|(a, b)| a * b)
            .sum();
        rhs[i] = (rhs[i] - dot) * row[i - fi];
    }
    for i in (0..n).rev() {
        let fi = first[i];
        let row = &k[start[i]..start[i + 1]];
        rhs[i] *= row[i - fi];
        let x = rhs[i];
        for (r, l) in rhs[fi..i].iter_mut().zip(row) {
            *r -= l * x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_and_solve_inverts_a_symmetric_positive_definite_matrix() {
        // K = [[4, 2, 0], [2, 5, 1], [0, 1, 3]], x = (1, −2, 3): K x = (0, −5, 7).
        // Skyline: row 0 from column 0, rows 1 and 2 from column 1 (K_20 = 0 is outside).
        let mut k = vec![4.0, 2.0, 5.0, 1.0, 3.0];
        let mut rhs = vec![0.0, -5.0, 7.0];
        factor_and_solve(&mut k, &[0, 0, 1], &[0, 1, 3, 5], &mut rhs);
        for (x, want) in rhs.iter().zip([1.0, -2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{rhs:?}");
        }
    }

    #[test]
    fn a_redundant_row_gets_a_zero_multiplier() {
        // Two equal rows: K = [[2, 2], [2, 2]], rhs (2, 2): λ = (1, 0) solves it.
        let mut k = vec![2.0, 2.0, 2.0];
        let mut rhs = vec![2.0, 2.0];
        factor_and_solve(&mut k, &[0, 0], &[0, 1, 3], &mut rhs);
        assert!((rhs[0] - 1.0).abs() < 1e-14 && rhs[1] == 0.0, "{rhs:?}");
    }
}
