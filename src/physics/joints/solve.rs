//! The multipliers: `(J W Jᵀ) λ = rhs`, a small symmetric solve over every joint row.
//!
//! ```text
//! K_ij = Σ over the bodies rows i and j share:  lin_i·lin_j / m + ang_i·I⁻¹_world ang_j
//! K λ = rhs   (envelope Cholesky K = L Lᵀ, redundant rows dropped: `physics::envelope`)
//! ```
//!
//! K is symmetric positive definite when the rows are independent; a redundant row (a pivot
//! below 1e-12 of the diagonal's largest) gets the multiplier 0 and the others carry the load
//! ([`Pivots::Dropped`]). K is summed body by body, over the pairs of rows that share it, into
//! the envelope of each row (its columns from the first row sharing one of its bodies).
//!
//! The matrix is rebuilt and factored at every evaluation of f(Y) (rk4: four times a step);
//! for a chain of 10 ball joints, 30 rows whose envelope is 6 wide, that is about 30 · 6²/2
//! ≈ 540 multiply–adds instead of a dense 30³/6 ≈ 4500, and 141 stored numbers, not 900.
//! The factor is not reused across rk4's stages: each stage's K is at its own configuration,
//! and an old factor would make λ, hence the method, inexact.

use super::rows::Row;
use crate::physics::envelope::{Envelope, Pivots};
use nalgebra::{Matrix3, Vector3};

/// A row touching a body: (row, linear part, I⁻¹ · angular part, angular part).
type Touch = (usize, Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// Reused buffers of the solve (no allocation once sized).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Solver {
    /// K inside its envelope, then its factor.
    system: Envelope,
    /// Per body: the rows touching it, (row, linear part, I⁻¹ angular part, angular part).
    touching: Vec<Vec<Touch>>,
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
    // The envelope: row i reaches back to the first row of every body it touches; K starts
    // at 0 inside it.
    let system = &mut solver.system;
    system.reset(n);
    for (i, r) in rows.iter().enumerate() {
        system.fill_row(i, [Some(r.a), r.b], |_| None);
    }
    for (body, list) in solver.touching.iter().enumerate() {
        let inv_mass = inverse.get(body).map_or(0.0, |b| b.mass);
        for (p, &(i, lin_i, w_i, _)) in list.iter().enumerate() {
            let (first, row) = system.row_mut(i);
            for &(j, lin_j, _, ang_j) in &list[..=p] {
                // Rows are pushed in order: first(i) ≤ j ≤ i.
                row[j - first] += lin_i.dot(&lin_j) * inv_mass + w_i.dot(&ang_j);
            }
        }
    }
    // The dropped policy always answers.
    let solved = system.solve_into(Pivots::Dropped, rhs);
    debug_assert!(solved);
}
