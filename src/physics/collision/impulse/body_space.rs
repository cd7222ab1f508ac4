//! A stage's rows in body space: what the body-space solves ([`interior`], and [`newton`])
//! share. Their unknowns are the bodies' velocities x = (v, ω), 6 a body, where the sweeps'
//! are the rows' impulses.
//!
//! A stage minimises, over the impulses Λ of its rows (λₙ ≥ 0, and in stage 2 |λ_t| ≤ r =
//! μ λₙ of stage 1), `F(Λ) = K + Σ λₙ gₙ/dt` ([`objective`]). With M the bodies' masses and
//! inertias, J the rows (a row of J is a [`Constraint`]: (±d, r×(±d)) at each end that
//! moves) and b their biases (gₙ/dt on a normal, 0 on a tangent), the rows' velocities are
//! `u = J x + b` ([`velocity`]). The contact-space matrix J M⁻¹ Jᵀ is rank-deficient when
//! contacts are redundant (a brick on two bricks has eight rows for six motions); a body-space
//! matrix `M + Jᵀ D J` (D ≥ 0 per contact) is positive definite whatever the contacts, 6×6
//! blocks per pair of bodies, factored by the envelope ([`fill`]).
//!
//! A body-space solve's answer replaces the rows' impulses only if it lowers F
//! ([`take_if_lower`]: measured, K from the bodies exactly as everywhere else), so K still
//! only goes down; the sweeps that follow judge convergence to the same tolerance.
//!
//! [`interior`]: super::interior
//! [`newton`]: super::newton

use super::Row;
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::envelope::Envelope;
use nalgebra::Matrix6;

/// One row of J: the normal or a tangent of a contact, on its (one or two) moving bodies.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Constraint {
    /// The local body and the row's six entries (±d, r×(±d)) at each end; `ends` of them.
    pub(super) ends: [(usize, [f64; 6]); 2],
    pub(super) count: usize,
    pub(super) bias: f64,
}

/// The row of J of `axis` over the local bodies (module doc): (±d, r×(±d)) at each end that
/// moves.
pub(super) fn constraint(
    axis: &Axis,
    bias: f64,
    local: &[usize],
    motions: &[SolverBody],
) -> Constraint {
    let mut c = Constraint {
        bias,
        ..Constraint::default()
    };
    for (end, sign) in axis.ends() {
        if motions[end.body].fixed() {
            continue;
        }
        let d = axis.d * sign;
        c.ends[c.count] = (
            local[end.body],
            [d.x, d.y, d.z, end.rd.x, end.rd.y, end.rd.z],
        );
        c.count += 1;
    }
    c
}

/// `g · x` over a constraint's ends.
#[inline]
pub(super) fn velocity(c: &Constraint, x: &[f64]) -> f64 {
    let mut u = c.bias;
    for (i, g) in &c.ends[..c.count] {
        let xi = &x[6 * i..6 * i + 6];
        u += g.iter().zip(xi).map(|(a, b)| a * b).sum::<f64>();
    }
    u
}

/// Numbers the moving bodies the rows touch, in the scene's order: `local[b]` is body b's
/// number (`usize::MAX` if no row moves it), `bodies` lists them; returns how many.
pub(super) fn number_bodies(
    rows: &[Row],
    motions: &[SolverBody],
    local: &mut Vec<usize>,
    bodies: &mut Vec<usize>,
) -> usize {
    local.clear();
    local.resize(motions.len(), usize::MAX);
    for row in rows.iter() {
        for (end, _) in row.normal.axis.ends() {
            if !motions[end.body].fixed() {
                local[end.body] = 0;
            }
        }
    }
    bodies.clear();
    for (b, l) in local.iter_mut().enumerate() {
        if *l == 0 {
            *l = bodies.len();
            bodies.push(b);
        }
    }
    bodies.len()
}

/// F = K + Σ λₙ gₙ/dt over the bodies and rows (the objective of a stage).
pub(super) fn objective(rows: &[Row], motions: &[SolverBody]) -> f64 {
    motions.iter().map(SolverBody::kinetic).sum::<f64>()
        + rows.iter().map(|r| r.normal.lambda * r.normal.bias).sum::<f64>()
}

/// The 6×6 blocks of the bodies (per local body i, its blocks (j ≤ i, H_ij)) into the
/// envelope, body i's rows reaching back to its lowest neighbour's; false if it stores more
/// than [`ENVELOPE_MAX`](super::ENVELOPE_MAX).
pub(super) fn fill(blocks: &[Vec<(usize, Matrix6<f64>)>], system: &mut Envelope) -> bool {
    system.reset(6 * blocks.len());
    for (i, list) in blocks.iter().enumerate() {
        let lowest = list.iter().map(|(j, _)| *j).min().unwrap_or(i);
        for r in 0..6 {
            system.fill_row(6 * i + r, [Some(i), Some(lowest)], |q| {
                let j = q / 6;
                list.iter()
                    .find(|(k, _)| *k == j)
                    .map(|(_, block)| block[(r, q % 6)])
            });
        }
        if system.stored() > super::ENVELOPE_MAX {
            return false;
        }
    }
    true
}

/// Puts each row's impulses `impulse(p)` = (λₙ, the tangent pair where the row has friction)
/// onto the rows and the bodies, each in its bounds (λₙ ≥ 0, |λ_t| ≤ the row's friction
/// bound, scaled back along itself), and keeps them only if they lower the stage's
/// [`objective`] F (returns whether it did); else everything is put back. Shared by the
/// body-space solves (`interior::solve`, `newton::solve`).
pub(super) fn take_if_lower(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    impulse: impl Fn(usize) -> (f64, Option<[f64; 2]>),
) -> bool {
    let before = objective(rows, motions);
    let saved: Vec<(f64, [f64; 2])> = rows.iter().map(|r| (r.normal.lambda, r.friction.lambda)).collect();
    let saved_motions = motions.to_vec();
    for (p, row) in rows.iter_mut().enumerate() {
        let (normal, tangent) = impulse(p);
        let lambda = normal.max(0.0);
        row.normal.axis.apply(lambda - row.normal.lambda, motions);
        row.normal.lambda = lambda;
        if let Some(mut t) = tangent {
            let [t1, t2] = &directions[p];
            let size = (t[0] * t[0] + t[1] * t[1]).sqrt();
            if size > row.friction.bound {
                let scale = row.friction.bound / size;
                t = [t[0] * scale, t[1] * scale];
            }
            t1.apply(t[0] - row.friction.lambda[0], motions);
            t2.apply(t[1] - row.friction.lambda[1], motions);
            row.friction.lambda = t;
        }
    }
    let lower = objective(rows, motions) < before;
    if !lower {
        motions.copy_from_slice(&saved_motions);
        for (row, &(lambda, tangent)) in rows.iter_mut().zip(saved.iter()) {
            row.normal.lambda = lambda;
            row.friction.lambda = tangent;
        }
    }
    lower
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::physics::collision::impulse::friction::tangents;
    use nalgebra::{Matrix3, Vector3};

    /// A cube (0.2 m, 2 kg) on the ground on its four bottom corners, moving at (vx, −0.05, 0)
    /// m/s, μ = 0.5, each corner's stage-1 load m·0.05/4: its stage-2 rows and bodies.
    pub(in super::super) fn sliding_cube(vx: f64) -> (Vec<Row>, Vec<[Axis; 2]>, Vec<SolverBody>) {
        let (m, side) = (2.0, 0.2);
        let inertia = m * side * side / 6.0;
        let motions = vec![SolverBody::new(
            Vector3::new(vx, -0.05, 0.0),
            Vector3::zeros(),
            1.0 / m,
            Matrix3::identity() / inertia,
        )];
        let n = Vector3::y();
        let (t1, t2) = tangents(&n);
        let (mut rows, mut directions) = (Vec::new(), Vec::new());
        for (x, z) in [(-0.1, -0.1), (-0.1, 0.1), (0.1, -0.1), (0.1, 0.1)] {
            let lever = Vector3::new(x, -0.1, z);
            let axis = |d| Axis::new(d, (0, &lever), None, &motions);
            let mut normal = axis(n);
            normal.with_inverse();
            rows.push(Row {
                normal: crate::physics::constraints::Row::contact(normal, 0.0),
                friction: crate::physics::constraints::Friction {
                    lambda: [0.0; 2],
                    bound: 0.5 * m * 0.05 / 4.0,
                },
                approach: -0.05,
                ..Row::default()
            });
            directions.push([axis(t1), axis(t2)]);
        }
        (rows, directions, motions)
    }

    /// The sliding cube at `vx` after `solve` (a body-space stage solve), with the stage
    /// objective before it.
    pub(in super::super) fn solved_cube<O>(
        vx: f64,
        solve: impl FnOnce(&mut [Row], &[[Axis; 2]], &mut [SolverBody]) -> O,
    ) -> (Vec<Row>, Vec<SolverBody>, O, f64) {
        let (mut rows, directions, mut motions) = sliding_cube(vx);
        let before = objective(&rows, &motions);
        let outcome = solve(&mut rows, &directions, &mut motions);
        (rows, motions, outcome, before)
    }

    /// Every row's impulse in its bounds: λₙ ≥ 0 and |λ_t| ≤ μ λₙ (the row's friction bound).
    pub(in super::super) fn assert_in_cone(rows: &[Row]) {
        for r in rows {
            let t = r.friction.lambda;
            assert!(r.normal.lambda >= 0.0 && (t[0] * t[0] + t[1] * t[1]).sqrt() <= r.friction.bound);
        }
    }
}
