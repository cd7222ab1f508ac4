//! Semismooth Newton in body space: a method over a stage's rows (stage 1's normals, or stage
//! 2's normals and friction disks), for a system whose direct solve declined. Projected
//! Gauss–Seidel and the subspace steps ([`subspace`]) find the active set of many sliding
//! contacts a contact at a time (a wall knocked down, its bricks sliding on each other:
//! hundreds of rows, thousands of sweeps a step); Newton finds it for all contacts at once,
//! in tens of factorisations. The sweeps then confirm its answer to the same tolerance as
//! before ([`TOLERANCE`]), usually in one sweep.
//!
//! # The problem in body space
//!
//! A stage minimises, over the impulses Λ of its rows (λₙ ≥ 0, |λ_t| ≤ r with r = μ λₙ of
//! stage 1, or no tangents in stage 1), `F(Λ) = K + Σ λₙ gₙ/dt`. With the bodies' velocities
//! x = (v, ω) (6 unknowns a body), M their masses and inertias, J the rows and b their biases
//! (gₙ/dt on a normal, 0 on a tangent), u = J x + b the rows' velocities, its optimality
//! conditions are
//!
//! ```text
//! M (x − x₀) = Jᵀ Λ,     Λ_c = P_c(Λ_c − ρ_c u_c)   for every contact c and any ρ_c > 0
//! ```
//!
//! x₀ the velocities without any contact impulse, P_c the projection onto the contact's set
//! (λₙ ≥ 0: Signorini; the disk |λ_t| ≤ r: cone feasibility, and the fixed point is maximal
//! dissipation, λ_t opposite to the slip when it slides).
//!
//! # The method of multipliers, each subproblem by semismooth Newton
//!
//! The augmented Lagrangian (proximal point on Λ): from multipliers Λᵏ (each in its set),
//! minimise over x the convex, once-differentiable
//!
//! ```text
//! ψ(x) = ½ (x − x₀)ᵀ M (x − x₀) + Σ_c h_c(Λᵏ_c − ρ_c u_c(x)) / ρ_c,
//! h(z) = ½|z|² − ½ dist²(z, set):   h = ½ max(z, 0)² (normal),
//!                                    ½|z|² inside the disk, r|z| − ½r² outside (tangents)
//! ∇ψ = M (x − x₀) − Jᵀ P(z),        z = Λᵏ − ρ u
//! ∂²ψ = M + Jᵀ ρ D J,               D = ∂P(z): 1 on a pushing normal (z > 0), 0 on a
//!                                    separating one; 𝟙 on a sticking disk (|z| ≤ r),
//!                                    (r/|z|)(𝟙 − ẑẑᵀ) on a sliding one
//! ```
//!
//! then `Λᵏ⁺¹ = P(Λᵏ − ρ u(x))`. The Hessian is M plus a positive semi-definite term: positive
//! definite whatever the contacts (a brick on two bricks has eight rows for six motions,
//! rank-deficient in contact space), 6 unknowns a body, factored by the envelope
//! ([`Envelope`], regularised). Each Newton step `∂²ψ Δx = −∇ψ` is followed by an exact line
//! search: ψ′ along Δx is monotone (ψ convex), so the step s ∈ (0, 1] where it changes sign is
//! found by safeguarded regula falsi; s = 1 when ψ′(1) ≤ 0. The sets of pushing normals and
//! sliding disks are D's: Newton changes them all at once, and from the rows' impulses (last
//! step's, or stage 1's) it starts on last step's active set.
//!
//! The outer iterations contract the velocity error on every mode by `1/(1 + ρσ)` and the
//! rows' velocities by at least 1/ρ (σ an eigenvalue of J M⁻¹ Jᵀ, however small): with
//! ρ_c = [`NEWTON_PENALTY`]/kₙ (kₙ the contact's normal effective inverse mass) two or three
//! suffice; the penalty grows ×10 when one does not gain a factor of 10.
//!
//! # Its promises
//!
//! Every Λᵏ is in its set (λₙ ≥ 0, |λ_t| ≤ r) whatever the iteration. It stops when the
//! natural residual `kₙ |P(Λ − u/kₙ) − Λ|` (m/s: what a Gauss–Seidel update of the row would
//! change its velocity by) is below half the sweeps' tolerance on every row, or at
//! [`NEWTON_STEPS`] factorisations, or at its work budget. Its answer replaces the rows'
//! impulses only if it lowers F (measured: K from the bodies, exactly as everywhere else), so
//! K still only goes down. The sweeps that follow decide convergence to [`TOLERANCE`] as
//! before: Newton changes where they start, never what they accept.
//!
//! [`subspace`]: super::subspace
//! [`TOLERANCE`]: super::TOLERANCE

use super::admm::{constraint, fill, number_bodies, take_if_lower, velocity, Constraint};
use super::Row;
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::envelope::Envelope;
use nalgebra::{Matrix2, Matrix3, Matrix6, Matrix6x3, Vector2, Vector6};

/// The penalty ρ kₙ of every contact at the start (dimensionless). Measured on the bonded
/// wall knocked down (2026-12-06): 1e3 needs more outer iterations (each outer iteration
/// gains only 10–40×), 1e6 makes the subproblems stiff (more short line-search steps),
/// 1e5 fewest steps; starting at 1–100 and raising it ×30–100 an iteration (continuation)
/// took more steps in all.
pub const NEWTON_PENALTY: f64 = 1e5;

/// The largest penalty the outer iterations raise it to (×10 when one gains less than 10×).
pub const NEWTON_PENALTY_MAX: f64 = 1e8;

/// Most Newton steps (each a factorisation in body space) of one solve.
pub const NEWTON_STEPS: usize = 60;

/// Most bodies a Newton solve takes (6 unknowns each).
pub const NEWTON_BODIES: usize = 512;

/// The rows' velocities (m/s) a Newton step may still change when its subproblem counts as
/// solved, as a fraction of the sweeps' tolerance.
const INNER: f64 = 1e-3;

/// One contact: its constraints (the normal, then two tangents when `tangents`), its
/// multipliers Λᵏ (λₙ, λ_t), the disk's radius, kₙ and the penalty's base 1/kₙ.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Group {
    pub(super) first: usize,
    pub(super) tangents: bool,
    pub(super) lambda: [f64; 3],
    pub(super) bound: f64,
    pub(super) k: f64,
}

/// The buffers of a Newton solve (reused from step to step).
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
    pub(super) dx: Vec<f64>,
    /// Per constraint: u(x) and J Δx.
    pub(super) u: Vec<f64>,
    pub(super) du: Vec<f64>,
}

/// What [`solve`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Outcome {
    /// Whether its answer replaced the rows' impulses (it lowered F).
    pub taken: bool,
    /// Whether it met its residual (half the sweeps' tolerance on every row).
    pub converged: bool,
    /// Newton steps (factorisations), and the work in row updates (module `WORK_BUDGET`).
    pub steps: usize,
    pub work: u64,
}

/// The projection of z onto a contact's set (module doc) and its derivative D: normal
/// (z[0]) onto λ ≥ 0, tangents (z[1], z[2]) onto the disk of radius `bound`.
#[inline]
fn project(z: [f64; 3], tangents: bool, bound: f64) -> ([f64; 3], f64, Matrix2<f64>) {
    let (pn, dn) = if z[0] > 0.0 { (z[0], 1.0) } else { (0.0, 0.0) };
    if !tangents {
        return ([pn, 0.0, 0.0], dn, Matrix2::zeros());
    }
    let t = Vector2::new(z[1], z[2]);
    let size = t.norm();
    if size <= bound {
        ([pn, z[1], z[2]], dn, Matrix2::identity())
    } else {
        let e = t / size;
        let s = bound / size;
        (
            [pn, z[1] * s, z[2] * s],
            dn,
            (Matrix2::identity() - e * e.transpose()) * s,
        )
    }
}

/// Semismooth Newton on the stage's rows (module doc), from their impulses, within `budget`
/// row updates; with no `directions` (stage 1) the rows are normals alone. Declines (changes
/// nothing) when the bodies are too many or a factorisation fails.
pub(super) fn solve(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    budget: u64,
    scratch: &mut Scratch,
) -> Outcome {
    let mut outcome = Outcome {
        taken: false,
        converged: false,
        steps: 0,
        work: 0,
    };
    if !setup(rows, directions, motions, scratch) {
        return outcome;
    }
    let stop = 0.5 * tolerance;
    let pass = rows.len() as u64;
    let mut alpha = NEWTON_PENALTY;
    let mut last = f64::INFINITY;
    'outer: loop {
        // The subproblem at Λᵏ: Newton steps until the rows' velocities stop changing.
        loop {
            if outcome.steps >= NEWTON_STEPS || outcome.work >= budget {
                break 'outer;
            }
            velocities(scratch);
            if !newton_step(scratch, alpha, &mut outcome) {
                return outcome;
            }
            outcome.steps += 1;
            let change = line_search(scratch, alpha);
            outcome.work += 4 * pass;
            for (x, dx) in scratch.x.iter_mut().zip(scratch.dx.iter()) {
                *x += change.0 * dx;
            }
            if change.1 <= INNER * tolerance {
                break;
            }
        }
        // Λᵏ⁺¹ = P(Λᵏ − ρ u(x)), and the natural residual at it.
        velocities(scratch);
        outcome.work += pass;
        let mut residual: f64 = 0.0;
        let Scratch { groups, u, .. } = &mut *scratch;
        for g in groups.iter_mut() {
            let rho = alpha / g.k;
            let uc = &u[g.first..g.first + if g.tangents { 3 } else { 1 }];
            let mut z = [g.lambda[0] - rho * uc[0], 0.0, 0.0];
            if g.tangents {
                z[1] = g.lambda[1] - rho * uc[1];
                z[2] = g.lambda[2] - rho * uc[2];
            }
            g.lambda = project(z, g.tangents, g.bound).0;
            let mut w = [g.lambda[0] - uc[0] / g.k, 0.0, 0.0];
            if g.tangents {
                w[1] = g.lambda[1] - uc[1] / g.k;
                w[2] = g.lambda[2] - uc[2] / g.k;
            }
            let p = project(w, g.tangents, g.bound).0;
            let gap = (p[0] - g.lambda[0])
                .abs()
                .max(Vector2::new(p[1] - g.lambda[1], p[2] - g.lambda[2]).norm());
            residual = residual.max(gap * g.k);
        }
        if residual <= stop {
            outcome.converged = true;
            break;
        }
        if residual > 0.1 * last {
            alpha = (alpha * 10.0).min(NEWTON_PENALTY_MAX);
        }
        last = residual;
    }
    take(rows, directions, motions, scratch, &mut outcome);
    outcome
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
    if nb == 0 || nb > NEWTON_BODIES {
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

/// The Newton direction Δx of ψ at x (module doc), into `dx`; false if the factorisation
/// fails or is too wide.
fn newton_step(scratch: &mut Scratch, alpha: f64, outcome: &mut Outcome) -> bool {
    let nb = scratch.bodies.len();
    let Scratch {
        blocks,
        system,
        mass,
        constraints,
        groups,
        mx0,
        x,
        dx,
        u,
        ..
    } = scratch;
    blocks.resize_with(nb.max(blocks.len()), Vec::new);
    for (i, (list, m)) in blocks.iter_mut().zip(mass.iter()).enumerate() {
        list.clear();
        list.push((i, *m));
    }
    // −∇ψ = Jᵀ P(z) − M (x − x₀), and H = M + Jᵀ ρ D J.
    dx.clear();
    dx.resize(6 * nb, 0.0);
    for (i, m) in mass.iter().enumerate() {
        let xi = Vector6::from_column_slice(&x[6 * i..6 * i + 6]);
        let mx = m * xi;
        for k in 0..6 {
            dx[6 * i + k] = mx0[6 * i + k] - mx[k];
        }
    }
    for g in groups.iter() {
        let rho = alpha / g.k;
        let count = if g.tangents { 3 } else { 1 };
        let cs = &constraints[g.first..g.first + count];
        let uc = &u[g.first..g.first + count];
        let mut z = [0.0; 3];
        for k in 0..count {
            z[k] = g.lambda[k] - rho * uc[k];
        }
        let (p, dn, dt) = project(z, g.tangents, g.bound);
        add_transposed(cs, &p[..count], 1.0, dx);
        // H += Σ over pairs of ends G_e (ρ D) G_fᵀ, G_e the contact's columns at end e.
        if dn == 0.0 && !g.tangents {
            continue;
        }
        let mut d = Matrix3::zeros();
        d[(0, 0)] = rho * dn;
        if g.tangents {
            d.fixed_view_mut::<2, 2>(1, 1).copy_from(&(dt * rho));
        }
        add_blocks(blocks, cs, &d);
    }
    if !fill(&blocks[..nb], system) {
        return false;
    }
    outcome.work += super::factorisation_work(system.stored(), 6 * nb);
    if !system.factor_regularised() {
        return false;
    }
    system.substitute_regularised(dx);
    true
}

/// H += Σ over pairs of ends G_e d G_fᵀ, G_e a contact's columns (its constraints `cs`, up
/// to 3) at end e, stored once below the diagonal (module doc).
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

/// The exact line search along Δx (module doc): the step s ∈ (0, 1] where ψ′ changes sign;
/// returns s and the largest change s·|J Δx| of a row's velocity.
fn line_search(scratch: &mut Scratch, alpha: f64) -> (f64, f64) {
    let Scratch {
        constraints,
        groups,
        mass,
        mx0,
        x,
        dx,
        u,
        du,
        ..
    } = scratch;
    du.clear();
    du.extend(constraints.iter().map(|c| velocity(c, dx) - c.bias));
    let largest = du.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    // ψ′(s) = s ΔxᵀMΔx + Δxᵀ(M x − M x₀) − Σ P(z − sρ JΔx)·JΔx.
    let (mut curvature, mut slope0) = (0.0, 0.0);
    for (i, m) in mass.iter().enumerate() {
        let d = Vector6::from_column_slice(&dx[6 * i..6 * i + 6]);
        let xi = Vector6::from_column_slice(&x[6 * i..6 * i + 6]);
        let md = m * d;
        curvature += d.dot(&md);
        slope0 += md.dot(&xi)
            - d.iter()
                .zip(&mx0[6 * i..6 * i + 6])
                .map(|(a, b)| a * b)
                .sum::<f64>();
    }
    let derivative = |s: f64| {
        let mut sum = s * curvature + slope0;
        for g in groups.iter() {
            let rho = alpha / g.k;
            let count = if g.tangents { 3 } else { 1 };
            let mut z = [0.0; 3];
            for k in 0..count {
                z[k] = g.lambda[k] - rho * (u[g.first + k] + s * du[g.first + k]);
            }
            let p = project(z, g.tangents, g.bound).0;
            for k in 0..count {
                sum -= p[k] * du[g.first + k];
            }
        }
        sum
    };
    let one = derivative(1.0);
    if one <= 0.0 {
        return (1.0, largest);
    }
    // Regula falsi (Illinois) on [0, 1]: ψ′(0) < 0 < ψ′(1).
    let (mut a, mut fa, mut b, mut fb) = (0.0, derivative(0.0), 1.0, one);
    if fa >= 0.0 {
        return (0.0, 0.0);
    }
    let mut side = 0;
    for _ in 0..60 {
        let s = (a * fb - b * fa) / (fb - fa);
        let fs = derivative(s);
        if fs == 0.0 || (b - a) < 1e-12 {
            a = s;
            break;
        }
        if fs < 0.0 {
            a = s;
            fa = fs;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = s;
            fb = fs;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
        if fs.abs() <= 1e-14 * (curvature.abs() + slope0.abs()) {
            a = s;
            break;
        }
    }
    (a, a * largest)
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
mod tests {
    use super::super::admm::objective;
    use super::super::admm::tests::{assert_in_cone, solved_cube};
    use super::*;
    use nalgebra::Vector3;

    fn run(vx: f64) -> (Vec<Row>, Vec<SolverBody>, Outcome, f64) {
        solved_cube(vx, |rows, directions, motions| {
            solve(rows, directions, motions, 1e-10, u64::MAX, &mut Scratch::default())
        })
    }

    #[test]
    fn a_sliding_cube_loses_mu_g_dt_of_its_speed_and_does_not_tip() {
        // Coulomb: the floor stops the fall (0.1 N·s) and friction takes μ·0.1 N·s of the
        // 2 kg's momentum: vx 1 → 1 − 0.025; the normals shift forward so that ω stays 0.
        let (rows, motions, outcome, before) = run(1.0);
        assert!(outcome.taken && outcome.converged, "{outcome:?}");
        assert!(outcome.steps <= 20, "{outcome:?}");
        let b = &motions[0];
        assert!(
            (b.v - Vector3::new(0.975, 0.0, 0.0)).norm() < 1e-9,
            "{:?}",
            b.v
        );
        assert!(b.omega.norm() < 1e-8, "{:?}", b.omega);
        assert!(objective(&rows, &motions) < before);
        assert_in_cone(&rows);
        let total: f64 = rows.iter().map(|r| r.normal.lambda).sum();
        assert!((total - 0.1).abs() < 1e-9, "{total}");
    }

    #[test]
    fn a_slow_cube_sticks() {
        // μ·0.1 N·s / 2 kg = 0.025 m/s > 0.01 m/s: friction stops it.
        let (_, motions, outcome, _) = run(0.01);
        assert!(outcome.taken && outcome.converged, "{outcome:?}");
        assert!(motions[0].v.norm() < 1e-9, "{:?}", motions[0].v);
        assert!(motions[0].omega.norm() < 1e-8);
    }
}
