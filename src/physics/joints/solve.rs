//! The multipliers: `(J W Jᵀ) λ = rhs`, a small dense symmetric solve over every joint row.
//!
//! ```text
//! K_ij = Σ over the bodies rows i and j share:  lin_i·lin_j / m + ang_i·I⁻¹_world ang_j
//! K = L D Lᵀ (in place, no pivoting: K is symmetric positive definite when the rows are
//!             independent; a pivot below 1e-12 of the diagonal's largest is a redundant row,
//!             whose multiplier is set to 0)
//! ```
//!
//! The matrix is rebuilt and factored at every evaluation of f(Y) (rk4: four times a step);
//! for a chain of 10 ball joints, 30 rows, that is 30³/6 ≈ 4500 multiply–adds.

use super::rows::Row;
use nalgebra::{Matrix3, Vector3};

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    /// K, then its factor, row-major n × n.
    matrix: Vec<f64>,
    /// Per row: W applied to its angular parts, (I⁻¹_A ang_a, I⁻¹_B ang_b).
    weighted: Vec<(Vector3<f64>, Vector3<f64>)>,
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
    solver.weighted.clear();
    solver.weighted.extend(rows.iter().map(|r| {
        let wa = inverse[r.a].inertia * r.ang_a;
        let wb =
            r.b.map_or(Vector3::zeros(), |b| inverse[b].inertia * r.ang_b);
        (wa, wb)
    }));
    solver.matrix.clear();
    solver.matrix.resize(n * n, 0.0);
    let k = &mut solver.matrix;
    for i in 0..n {
        let ri = &rows[i];
        let (wai, wbi) = solver.weighted[i];
        for j in 0..=i {
            let rj = &rows[j];
            let mut sum = 0.0;
            // Body A of row i against both bodies of row j, then body B of row i.
            let mut side = |body: usize, lin_i: &Vector3<f64>, w_i: &Vector3<f64>| {
                if rj.a == body {
                    sum += lin_i.dot(&rj.lin_a) * inverse[body].mass + w_i.dot(&rj.ang_a);
                }
                if rj.b == Some(body) {
                    sum += lin_i.dot(&rj.lin_b) * inverse[body].mass + w_i.dot(&rj.ang_b);
                }
            };
            side(ri.a, &ri.lin_a, &wai);
            if let Some(b) = ri.b {
                side(b, &ri.lin_b, &wbi);
            }
            k[i * n + j] = sum;
            k[j * n + i] = sum;
        }
    }
    factor_and_solve(k, n, rhs);
}

/// In place L D Lᵀ of the symmetric `k` (lower triangle used), then the solve of `k x = rhs`.
fn factor_and_solve(k: &mut [f64], n: usize, rhs: &mut [f64]) {
    let largest = (0..n).map(|i| k[i * n + i].abs()).fold(0.0, f64::max);
    let tiny = 1e-12 * largest;
    for j in 0..n {
        let mut d = k[j * n + j];
        for p in 0..j {
            d -= k[j * n + p] * k[j * n + p] * k[p * n + p];
        }
        // A redundant row: an infinite pivot makes its multiplier 0.
        let d = if d > tiny { d } else { f64::INFINITY };
        k[j * n + j] = d;
        for i in j + 1..n {
            let mut s = k[i * n + j];
            for p in 0..j {
                s -= k[i * n + p] * k[j * n + p] * k[p * n + p];
            }
            k[i * n + j] = if d.is_finite() { s / d } else { 0.0 };
        }
    }
    for i in 0..n {
        let mut s = rhs[i];
        for p in 0..i {
            s -= k[i * n + p] * rhs[p];
        }
        rhs[i] = s;
    }
    for i in 0..n {
        rhs[i] /= k[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = rhs[i];
        for p in i + 1..n {
            s -= k[p * n + i] * rhs[p];
        }
        rhs[i] = s;
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
        factor_and_solve(&mut k, 3, &mut rhs);
        for (x, want) in rhs.iter().zip([1.0, -2.0, 3.0]) {
            assert!((x - want).abs() < 1e-14, "{rhs:?}");
        }
    }

    #[test]
    fn a_redundant_row_gets_a_zero_multiplier() {
        // Two equal rows: K = [[2, 2], [2, 2]], rhs (2, 2): λ = (1, 0) solves it.
        let mut k = vec![2.0, 2.0, 2.0, 2.0];
        let mut rhs = vec![2.0, 2.0];
        factor_and_solve(&mut k, 2, &mut rhs);
        assert!((rhs[0] - 1.0).abs() < 1e-14 && rhs[1] == 0.0, "{rhs:?}");
    }
}
