//! ADMM in body space: a method over the friction stage's rows (stage 2, after its direct
//! sticking solve declined), which finds the active set of many sliding contacts at once
//! where projected Gauss–Seidel and the subspace steps find it a contact at a time (a wall
//! knocked down, its bricks sliding on each other: hundreds of rows, each step spending its
//! whole work budget). The sweeps and the subspace steps ([`subspace`]) then finish from its
//! answer and judge convergence to the same tolerance as before.
//!
//! # The problem in body space
//!
//! Stage 2 minimises, over the impulses Λ of the rows (λₙ ≥ 0, |λ_t| ≤ r = μ λₙ of stage 1),
//! `F(Λ) = K + Σ λₙ gₙ/dt`. Its dual is a problem over the bodies' velocities x = (v, ω), 6
//! unknowns a body, with the rows' velocities `u = J x + b` (b = g/dt on a normal, 0 on a
//! tangent):
//!
//! ```text
//! min ½ (x − x₀)ᵀ M (x − x₀) + Σ r |u_t|      subject to uₙ ≥ 0
//! ```
//!
//! x₀ the velocities without any contact impulse, M the bodies' masses and inertias. The
//! contact-space matrix J M⁻¹ Jᵀ is rank-deficient when contacts are redundant (a brick on
//! two bricks has eight rows for six motions); M + Jᵀ ρ J is positive definite whatever the
//! contacts. ADMM (Boyd et al. 2011, scaled form) on `z = J x + b`:
//!
//! ```text
//! x ← (M + Jᵀ ρ J)⁻¹ (M x₀ + Jᵀ ρ (z − b − y))     one factorisation a solve, reused
//! z ← prox(J x + b + y):  zₙ = max(0, ·),  z_t = shrink(·, r/ρ)   per contact
//! y ← y + J x + b − z
//! ```
//!
//! with ρ = [`ADMM_PENALTY`]/kₙ per contact (kₙ its normal's effective inverse mass: the
//! diagonal scaling of J M⁻¹ Jᵀ). The impulses are `Λ = −ρ y`: after each z update they are
//! in their bounds (ρ y is a subgradient of the constraint term at z: λₙ ≥ 0, |λ_t| ≤ r),
//! whatever the iteration, so stopping early still gives admissible impulses.
//!
//! # Its promises
//!
//! It starts from the rows' impulses (y = −Λ/ρ) and stops when no row's velocity is further
//! than [`ADMM_TOLERANCE`] (m/s, plus the same fraction of the fastest approach) from its
//! projection and z no longer moves by as much, or after [`ADMM_ITERATIONS`]. Its answer
//! replaces the rows' impulses only if it lowers F (measured: K from the bodies, exactly as
//! everywhere else), so K still only goes down. The sweeps that follow decide convergence
//! to [`TOLERANCE`] as before: ADMM changes where they start, never what they accept.
//!
//! [`subspace`]: super::subspace
//! [`TOLERANCE`]: super::TOLERANCE

use super::Row;
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::envelope::Envelope;
use nalgebra::Matrix6;

/// The penalty ρ kₙ of every contact (dimensionless: ρ over the inverse of its normal's
/// effective inverse mass).
pub const ADMM_PENALTY: f64 = 1.0;

/// Most ADMM iterations of one friction stage (each a pair of triangular solves in body space
/// and a pass over the rows).
pub const ADMM_ITERATIONS: usize = 1000;

/// ADMM stops when every row's velocity is within this of its projection (m/s, plus the same
/// fraction of the fastest approach): close enough for the sweeps and subspace steps to find
/// the rest of the way.
pub const ADMM_TOLERANCE: f64 = 1e-7;

/// Most bodies an ADMM solve takes (6 unknowns each, in a banded system when the bodies are
/// numbered along the scene).
pub const ADMM_BODIES: usize = 512;

/// Residual balancing: the penalty changes when one residual exceeds the other this many
/// times, by [`ADMM_BALANCE_STEP`], at most every [`ADMM_BALANCE_EVERY`] iterations (each
/// change a factorisation of H, small beside the iterations: a wall of 33 bricks stores
/// about 6000 entries).
pub const ADMM_BALANCE: f64 = 10.0;
pub const ADMM_BALANCE_STEP: f64 = 4.0;
pub const ADMM_BALANCE_EVERY: usize = 10;

/// One row of J: the normal or a tangent of a contact, on its (one or two) moving bodies.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Constraint {
    /// The local body and the row's six entries (±d, r×(±d)) at each end; `ends` of them.
    pub(super) ends: [(usize, [f64; 6]); 2],
    pub(super) count: usize,
    pub(super) bias: f64,
    /// Scaled dual y (λ = −ρ y) and the projected velocity z.
    y: f64,
    z: f64,
}

/// The buffers of an ADMM solve (reused from step to step).
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    /// Body → local index (usize::MAX: not in the solve), local → body.
    local: Vec<usize>,
    bodies: Vec<usize>,
    /// Per local body i, the 6×6 blocks (j ≤ i, H_ij) of `M + Jᵀ ρ J`.
    blocks: Vec<Vec<(usize, Matrix6<f64>)>>,
    system: Envelope,
    /// Per row of `rows`: its first constraint and whether its tangents are in the solve.
    first: Vec<(usize, bool)>,
    /// Per row: 1/kₙ (ρ = α/kₙ).
    rho: Vec<f64>,
    /// Per local body: M (6×6).
    mass: Vec<Matrix6<f64>>,
    constraints: Vec<Constraint>,
    mx0: Vec<f64>,
    x: Vec<f64>,
}

/// What [`solve`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Outcome {
    /// Whether its answer replaced the rows' impulses (it lowered F).
    pub taken: bool,
    /// Whether its residuals met [`ADMM_TOLERANCE`].
    pub converged: bool,
    /// The iterations run, and the work they cost in row updates (module `WORK_BUDGET`).
    pub iterations: usize,
    pub work: u64,
}

/// Adds `rho g_e g_fᵀ` to the block of bodies (e, f), stored once below the diagonal.
pub(super) fn add(
    blocks: &mut [Vec<(usize, Matrix6<f64>)>],
    (i, gi): (usize, &[f64; 6]),
    (j, gj): (usize, &[f64; 6]),
    rho: f64,
) {
    {
        let (i, gi, j, gj) = if i >= j {
            (i, gi, j, gj)
        } else {
            (j, gj, i, gi)
        };
        let list = &mut blocks[i];
        let at = match list.iter().position(|(k, _)| *k == j) {
            Some(at) => at,
            None => {
                list.push((j, Matrix6::zeros()));
                list.len() - 1
            }
        };
        let block = &mut list[at].1;
        for r in 0..6 {
            for c in 0..6 {
                block[(r, c)] += rho * gi[r] * gj[c];
            }
        }
    }
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

/// F = K + Σ λₙ gₙ/dt over the bodies and rows (the objective of stage 2).
pub(super) fn objective(rows: &[Row], motions: &[SolverBody]) -> f64 {
    motions.iter().map(SolverBody::kinetic).sum::<f64>()
        + rows.iter().map(|r| r.normal.lambda * r.normal.bias).sum::<f64>()
}

/// ADMM on the stage's rows (module doc), from their impulses; returns what it did. With no
/// `directions` (stage 1) the rows are normals alone. Declines (changes nothing) when the
/// bodies are too many or the factorisation fails.
pub(super) fn solve(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    scratch: &mut Scratch,
) -> Outcome {
    let mut outcome = Outcome {
        taken: false,
        converged: false,
        iterations: 0,
        work: 0,
    };
    let nb = number_bodies(rows, motions, &mut scratch.local, &mut scratch.bodies);
    if nb == 0 || nb > ADMM_BODIES {
        return outcome;
    }
    let mut alpha = ADMM_PENALTY;
    // The constraints, their duals from the rows' impulses (y = −λ/ρ).
    scratch.constraints.clear();
    scratch.first.clear();
    scratch.rho.clear();
    for (p, row) in rows.iter().enumerate() {
        let base = 1.0 / row.normal.axis.k;
        scratch.rho.push(base);
        let rho = alpha * base;
        let tangents = !directions.is_empty() && row.friction.bound > 0.0;
        scratch.first.push((scratch.constraints.len(), tangents));
        let mut c = constraint(&row.normal.axis, row.normal.bias, &scratch.local, motions);
        c.y = -row.normal.lambda / rho;
        scratch.constraints.push(c);
        if tangents {
            for (k, t) in directions[p].iter().enumerate() {
                let mut c = constraint(t, 0.0, &scratch.local, motions);
                c.y = -row.friction.lambda[k] / rho;
                scratch.constraints.push(c);
            }
        }
    }
    // M, x, and M x₀ = M x − Jᵀ Λ.
    scratch.mass.clear();
    scratch.mx0.clear();
    scratch.mx0.resize(6 * nb, 0.0);
    scratch.x.clear();
    scratch.x.resize(6 * nb, 0.0);
    for (i, &b) in scratch.bodies.iter().enumerate() {
        let s = &motions[b];
        let mass = 1.0 / s.inv_mass;
        let Some(inertia) = s.inv_inertia.try_inverse() else {
            return outcome;
        };
        let mut block = Matrix6::zeros();
        for k in 0..3 {
            block[(k, k)] = mass;
        }
        block.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia);
        scratch.mass.push(block);
        let (mx, x) = (
            &mut scratch.mx0[6 * i..6 * i + 6],
            &mut scratch.x[6 * i..6 * i + 6],
        );
        for k in 0..3 {
            mx[k] = s.v[k] * mass;
            mx[3 + k] = s.l[k];
            x[k] = s.v[k];
            x[3 + k] = s.omega[k];
        }
    }
    for (&(first, tangents), &base) in scratch.first.iter().zip(scratch.rho.iter()) {
        let count = if tangents { 3 } else { 1 };
        for c in &scratch.constraints[first..first + count] {
            let lambda = -alpha * base * c.y;
            for (i, g) in &c.ends[..c.count] {
                for (mx, gk) in scratch.mx0[6 * i..6 * i + 6].iter_mut().zip(g.iter()) {
                    *mx -= gk * lambda;
                }
            }
        }
    }
    let fastest = rows.iter().map(|r| -r.approach).fold(0.0, f64::max);
    let stop = (ADMM_TOLERANCE * (1.0 + fastest)).max(tolerance);
    let mut iteration = 0;
    // Phases of one penalty each: factor H, iterate until converged, out of iterations, or
    // the residuals ask for another penalty.
    loop {
        if !factor(scratch, alpha, &mut outcome) {
            return outcome;
        }
        match iterate(rows, scratch, alpha, stop, &mut iteration, &mut outcome) {
            None => break,
            Some(scale) => {
                for c in scratch.constraints.iter_mut() {
                    c.y /= scale;
                }
                alpha *= scale;
            }
        }
    }
    outcome.iterations = iteration;
    // Λ = −ρ y onto the rows and the bodies, kept only if F went down.
    take(rows, directions, motions, scratch, alpha, &mut outcome);
    outcome
}

/// H = M + Jᵀ ρ J (ρ = α/kₙ) in 6×6 blocks, into the envelope (the rows of body i reach back
/// to its lowest neighbour's), factored. False if too wide or not positive.
fn factor(scratch: &mut Scratch, alpha: f64, outcome: &mut Outcome) -> bool {
    let nb = scratch.bodies.len();
    scratch
        .blocks
        .resize_with(nb.max(scratch.blocks.len()), Vec::new);
    for (list, m) in scratch.blocks.iter_mut().zip(scratch.mass.iter()) {
        list.clear();
        list.push((usize::MAX, *m));
    }
    for (i, list) in scratch.blocks[..nb].iter_mut().enumerate() {
        list[0].0 = i;
    }
    for (&(first, tangents), &base) in scratch.first.iter().zip(scratch.rho.iter()) {
        let count = if tangents { 3 } else { 1 };
        for c in &scratch.constraints[first..first + count] {
            for e in 0..c.count {
                for f in 0..=e {
                    add(
                        &mut scratch.blocks,
                        (c.ends[e].0, &c.ends[e].1),
                        (c.ends[f].0, &c.ends[f].1),
                        alpha * base,
                    );
                }
            }
        }
    }
    let system = &mut scratch.system;
    if !fill(&scratch.blocks[..nb], system) {
        return false;
    }
    outcome.work += super::factorisation_work(system.stored(), 6 * nb);
    system.factor_regularised()
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

/// ADMM iterations at penalty α (module doc) from `iteration` on; None when converged or out
/// of iterations, Some(scale) when the residuals ask for the penalty α·scale.
fn iterate(
    rows: &[Row],
    scratch: &mut Scratch,
    alpha: f64,
    stop: f64,
    iteration: &mut usize,
    outcome: &mut Outcome,
) -> Option<f64> {
    let Scratch {
        system,
        constraints,
        first: firsts,
        rho: rhos,
        mx0,
        x,
        ..
    } = scratch;
    let n = x.len();
    let iteration_work = rows.len() as u64 + (system.stored() / 50) as u64;
    let started = *iteration;
    let mut rhs = std::mem::take(&mut system.rhs);
    let result = loop {
        // z, y from x.
        let (mut primal, mut dual): (f64, f64) = (0.0, 0.0);
        for ((row, &(first, tangents)), &base) in rows.iter().zip(firsts.iter()).zip(rhos.iter()) {
            let cn = &mut constraints[first];
            let u = velocity(cn, x);
            let w = u + cn.y;
            let z = w.max(0.0);
            dual = dual.max((z - cn.z).abs());
            primal = primal.max((u - z).abs());
            cn.z = z;
            cn.y = w - z;
            if tangents {
                let bound = row.friction.bound / (alpha * base);
                let u = [
                    velocity(&constraints[first + 1], x),
                    velocity(&constraints[first + 2], x),
                ];
                let w = [
                    u[0] + constraints[first + 1].y,
                    u[1] + constraints[first + 2].y,
                ];
                let size = (w[0] * w[0] + w[1] * w[1]).sqrt();
                let shrink = if size > bound {
                    1.0 - bound / size
                } else {
                    0.0
                };
                for k in 0..2 {
                    let c = &mut constraints[first + 1 + k];
                    let z = w[k] * shrink;
                    dual = dual.max((z - c.z).abs());
                    primal = primal.max((u[k] - z).abs());
                    c.z = z;
                    c.y = w[k] - z;
                }
            }
        }
        // The dual residual in velocity units: M⁻¹ Jᵀ ρ Δz, about α Δz.
        dual *= alpha;
        if *iteration > started && primal <= stop && dual <= stop {
            outcome.converged = true;
            break None;
        }
        if *iteration >= ADMM_ITERATIONS {
            break None;
        }
        // Residual balancing (Boyd et al. 2011, § 3.4.1): ρ up when the primal residual
        // leads, down when the dual does.
        if *iteration >= started + ADMM_BALANCE_EVERY {
            if primal > ADMM_BALANCE * dual {
                break Some(ADMM_BALANCE_STEP);
            }
            if dual > ADMM_BALANCE * primal {
                break Some(1.0 / ADMM_BALANCE_STEP);
            }
        }
        // x ← H⁻¹ (M x₀ + Jᵀ ρ (z − b − y))
        rhs.clear();
        rhs.extend_from_slice(mx0);
        for (&(first, tangents), &base) in firsts.iter().zip(rhos.iter()) {
            let count = if tangents { 3 } else { 1 };
            for c in &constraints[first..first + count] {
                let s = alpha * base * (c.z - c.bias - c.y);
                for (i, g) in &c.ends[..c.count] {
                    for (r, gk) in rhs[6 * i..6 * i + 6].iter_mut().zip(g.iter()) {
                        *r += gk * s;
                    }
                }
            }
        }
        system.substitute_regularised(&mut rhs);
        x.copy_from_slice(&rhs[..n]);
        outcome.work += iteration_work;
        *iteration += 1;
    };
    system.rhs = rhs;
    result
}

/// Λ = −ρ y onto the rows and the bodies (see [`take_if_lower`]).
fn take(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    scratch: &Scratch,
    alpha: f64,
    outcome: &mut Outcome,
) {
    let c = &scratch.constraints;
    let taken = take_if_lower(rows, directions, motions, |p| {
        let (first, tangents) = scratch.first[p];
        let rho = alpha * scratch.rho[p];
        let tangent = || [-rho * c[first + 1].y, -rho * c[first + 2].y];
        (-rho * c[first].y, tangents.then(tangent))
    });
    if taken {
        outcome.taken = true;
    }
}

/// Puts each row's impulses `impulse(p)` = (λₙ, the tangent pair where the row has friction)
/// onto the rows and the bodies, each in its bounds (λₙ ≥ 0, |λ_t| ≤ the row's friction
/// bound, scaled back along itself), and keeps them only if they lower the stage's
/// [`objective`] F (returns whether it did); else everything is put back. Shared by the body-space solves ([`solve`]
/// and `newton::solve`).
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

    #[test]
    fn a_sliding_cube_loses_mu_g_dt_of_its_speed_and_does_not_tip() {
        // Coulomb: the floor stops the fall (0.1 N·s) and friction takes μ·0.1 N·s of the
        // 2 kg's momentum: vx 1 → 1 − 0.025; the normals shift forward so that ω stays 0.
        let (mut rows, directions, mut motions) = sliding_cube(1.0);
        let before = objective(&rows, &motions);
        let outcome = solve(
            &mut rows,
            &directions,
            &mut motions,
            1e-10,
            &mut Scratch::default(),
        );
        assert!(outcome.taken && outcome.converged, "{outcome:?}");
        let b = &motions[0];
        assert!(
            (b.v - Vector3::new(0.975, 0.0, 0.0)).norm() < 1e-6,
            "{:?}",
            b.v
        );
        assert!(b.omega.norm() < 1e-5, "{:?}", b.omega);
        assert!(objective(&rows, &motions) < before);
        assert_in_cone(&rows);
        let total: f64 = rows.iter().map(|r| r.normal.lambda).sum();
        assert!((total - 0.1).abs() < 1e-6, "{total}");
    }

    #[test]
    fn a_slow_cube_sticks() {
        // μ·0.1 N·s / 2 kg = 0.025 m/s > 0.01 m/s: friction stops it.
        let (mut rows, directions, mut motions) = sliding_cube(0.01);
        let outcome = solve(
            &mut rows,
            &directions,
            &mut motions,
            1e-10,
            &mut Scratch::default(),
        );
        assert!(outcome.taken && outcome.converged, "{outcome:?}");
        assert!(motions[0].v.norm() < 1e-6, "{:?}", motions[0].v);
        assert!(motions[0].omega.norm() < 1e-5);
    }
}
