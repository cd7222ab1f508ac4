//! A stage's rows in body space: what the interior-point solve ([`interior`]) works on. Its
//! unknowns are the bodies' velocities x = (v, ω), 6 a body, where the sweeps' are the rows'
//! impulses.
//!
//! A stage minimises, over the impulses Λ of its rows (λₙ ≥ 0, and in stage 2 |λ_t| ≤ r =
//! μ λₙ of stage 1), `F(Λ) = K + Σ λₙ gₙ/dt` (`objective`). With M the bodies' masses and
//! inertias, J the rows (a row of J is a `Constraint`: (±d, r×(±d)) at each end that
//! moves) and b their biases (gₙ/dt on a normal, 0 on a tangent), the rows' velocities are
//! `u = J x + b` (`velocity`). The contact-space matrix J M⁻¹ Jᵀ is rank-deficient when
//! contacts are redundant (a brick on two bricks has eight rows for six motions); a body-space
//! matrix `M + Jᵀ D J` (D ≥ 0 per contact) is positive definite whatever the contacts, 6×6
//! blocks per pair of bodies, factored by the envelope (`fill`).
//!
//! A body-space solve's answer replaces the rows' impulses only if it lowers F
//! (`take_if_lower`: measured, K from the bodies exactly as everywhere else), so K still
//! only goes down; the sweeps that follow judge convergence to the same tolerance.
//!
//! The unknowns' start (`setup`): the moving bodies the rows touch, numbered in the
//! scene's order (`number_bodies`, at most `BODY_SPACE_BODIES`), M, x, `M x₀ = M x −
//! Jᵀ Λ` (x₀ the velocities without any contact impulse), and per contact a `Group`: its
//! constraints (the normal, then two tangents in stage 2) and its impulses Λ.
//!
//! [`interior`]: super::interior

use super::Row;
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::envelope::Envelope;
use nalgebra::{Matrix3, Matrix6, Matrix6x3, Vector6};

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
/// [`objective`] F (returns whether it did); else everything is put back.
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

/// Most bodies a body-space solve takes (6 unknowns each).
pub const BODY_SPACE_BODIES: usize = 512;

/// One contact: its constraints (the normal, then two tangents when `tangents`), its
/// impulses Λ (λₙ, λ_t), the disk's radius and kₙ (its normal's effective inverse mass).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Group {
    pub(super) first: usize,
    pub(super) tangents: bool,
    pub(super) lambda: [f64; 3],
    pub(super) bound: f64,
    pub(super) k: f64,
}

/// The buffers of a body-space solve (reused from step to step).
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    pub(super) local: Vec<usize>,
    pub(super) bodies: Vec<usize>,
    pub(super) blocks: Vec<Vec<(usize, Matrix6<f64>)>>,
    pub(super) system: Envelope,
    pub(super) mass: Vec<Matrix6<f64>>,
    pub(super) constraints: Vec<Constraint>,
    pub(super) groups: Vec<Group>,
    pub(super) mx0: Vec<f64>,
    pub(super) x: Vec<f64>,
    /// Per constraint: u(x).
    pub(super) u: Vec<f64>,
}

/// What a body-space solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Outcome {
    /// Whether its answer replaced the rows' impulses (it lowered F).
    pub taken: bool,
    /// Whether it met its residual (half the sweeps' tolerance on every row).
    pub converged: bool,
    /// Its steps (factorisations), and the work in row updates (module `WORK_BUDGET`).
    pub steps: usize,
    pub work: u64,
}


/// The moving bodies (local numbering), their M, x, M x₀ = M x − Jᵀ Λ, and the rows'
/// constraints and multipliers; false if there is nothing to solve or too much.
pub(super) fn setup(
    rows: &[Row],
    directions: &[[Axis; 2]],
    motions: &[SolverBody],
    scratch: &mut Scratch,
) -> bool {
    let nb = number_bodies(rows, motions, &mut scratch.local, &mut scratch.bodies);
    if nb == 0 || nb > BODY_SPACE_BODIES {
        return false;
    }
    scratch.constraints.clear();
    scratch.groups.clear();
    for (p, row) in rows.iter().enumerate() {
        let tangents = !directions.is_empty() && row.friction.bound > 0.0;
        scratch.groups.push(Group {
            first: scratch.constraints.len(),
            tangents,
            lambda: [row.normal.lambda, row.friction.lambda[0], row.friction.lambda[1]],
            bound: row.friction.bound,
            k: row.normal.axis.k,
        });
        if !tangents {
            scratch.groups.last_mut().unwrap().lambda[1..].fill(0.0);
        }
        let local = &scratch.local;
        scratch
            .constraints
            .push(constraint(&row.normal.axis, row.normal.bias, local, motions));
        if tangents {
            for t in &directions[p] {
                scratch.constraints.push(constraint(t, 0.0, local, motions));
            }
        }
        if row.normal.axis.k.is_nan() || row.normal.axis.k <= 0.0 {
            return false;
        }
    }
    scratch.mass.clear();
    scratch.mx0.clear();
    scratch.mx0.resize(6 * nb, 0.0);
    scratch.x.clear();
    scratch.x.resize(6 * nb, 0.0);
    for (i, &b) in scratch.bodies.iter().enumerate() {
        let s = &motions[b];
        let mass = 1.0 / s.inv_mass;
        let Some(inertia) = s.inv_inertia.try_inverse() else {
            return false;
        };
        let mut block = Matrix6::zeros();
        for k in 0..3 {
            block[(k, k)] = mass;
        }
        block.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia);
        scratch.mass.push(block);
        for k in 0..3 {
            scratch.mx0[6 * i + k] = s.v[k] * mass;
            scratch.mx0[6 * i + 3 + k] = s.l[k];
            scratch.x[6 * i + k] = s.v[k];
            scratch.x[6 * i + 3 + k] = s.omega[k];
        }
    }
    for g in &scratch.groups {
        let count = if g.tangents { 3 } else { 1 };
        for (c, lambda) in scratch.constraints[g.first..g.first + count]
            .iter()
            .zip(g.lambda)
        {
            for (i, gk) in &c.ends[..c.count] {
                for (mx, gk) in scratch.mx0[6 * i..6 * i + 6].iter_mut().zip(gk.iter()) {
                    *mx -= gk * lambda;
                }
            }
        }
    }
    true
}

/// u = J x + b for every constraint.
pub(super) fn velocities(scratch: &mut Scratch) {
    scratch.u.clear();
    let x = &scratch.x;
    scratch
        .u
        .extend(scratch.constraints.iter().map(|c| velocity(c, x)));
}

/// `Jᵀ v` of a contact's constraints added (times `scale`) into the body vector `out`.
pub(super) fn add_transposed(cs: &[Constraint], v: &[f64], scale: f64, out: &mut [f64]) {
    for (c, &vk) in cs.iter().zip(v) {
        let s = scale * vk;
        if s == 0.0 {
            continue;
        }
        for (i, g) in &c.ends[..c.count] {
            for (o, gk) in out[6 * i..6 * i + 6].iter_mut().zip(g.iter()) {
                *o += gk * s;
            }
        }
    }
}


/// H += Σ over pairs of ends G_e d G_fᵀ, G_e a contact's columns (its constraints `cs`, up
/// to 3) at end e, stored once below the diagonal (H = M + Jᵀ D J, module doc).
pub(super) fn add_blocks(
    blocks: &mut [Vec<(usize, Matrix6<f64>)>],
    cs: &[Constraint],
    d: &Matrix3<f64>,
) {
    let columns = |e: usize| {
        let mut m = Matrix6x3::zeros();
        for (k, c) in cs.iter().enumerate() {
            m.set_column(k, &Vector6::from_column_slice(&c.ends[e].1));
        }
        (cs[0].ends[e].0, m)
    };
    for e in 0..cs[0].count {
        let (i, ge) = columns(e);
        let gd = ge * d;
        for f in 0..=e {
            let (j, gf) = columns(f);
            let (i, j, block) = if i >= j {
                (i, j, gd * gf.transpose())
            } else {
                (j, i, gf * d * ge.transpose())
            };
            let list = &mut blocks[i];
            match list.iter_mut().find(|(k, _)| *k == j) {
                Some((_, b)) => *b += block,
                None => list.push((j, block)),
            }
        }
    }
}


/// Λ onto the rows and the bodies (see [`take_if_lower`]).
pub(super) fn take(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    scratch: &Scratch,
    outcome: &mut Outcome,
) {
    let taken = take_if_lower(rows, directions, motions, |p| {
        let g = &scratch.groups[p];
        (
            g.lambda[0],
            g.tangents.then_some([g.lambda[1], g.lambda[2]]),
        )
    });
    if taken {
        outcome.taken = true;
    }
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
