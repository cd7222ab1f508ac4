//! A primal–dual interior-point method in body space: a start for stage 2's sweeps (its
//! normals and friction disks; with no friction directions it takes normals alone, as a
//! stage 1 would, which was tried and removed) when its direct solves declined, on the
//! stage's rows in body space ([`body_space`]). It finds the active set of all contacts at
//! once: it never walks along an active set's edge, so a contact closing or opening costs it
//! nothing extra (semismooth Newton's line search met them one at a time: module doc of
//! [`super`], *Tried and removed*).
//!
//! # The problem
//!
//! A stage minimises over the impulses Λ of its rows `F(Λ) = K + Σ λₙ gₙ/dt`, whose gradient
//! is the rows' velocities u = J x + b (x = x₀ + M⁻¹ Jᵀ Λ the bodies' velocities), subject
//! to λₙ ≥ 0 (Signorini) and, on a friction disk of fixed radius r, `q = r² − |λ_t|² ≥ 0`
//! (cone feasibility). Its conditions, with w the normal's dual (its velocity) and γ the
//! disk's multiplier:
//!
//! ```text
//! uₙ − w = 0,        λₙ w = 0,   λₙ, w ≥ 0
//! u_t + 2γ λ_t = 0,  γ q = 0,    q, γ ≥ 0     (maximal dissipation: λ_t opposite u_t on the edge)
//! ```
//!
//! # The method
//!
//! The products are relaxed to σμ (μ their mean, σ by Mehrotra's predictor: (μ_aff/μ)³) and
//! the conditions linearised; eliminating the duals leaves, per contact, a 3×3 positive
//! definite block `D` (`w/λₙ` on the normal; `2γ (𝟙 + 2 λ_t λ_tᵀ/q)` on the disk) and
//!
//! ```text
//! (W + D) ΔΛ = g,   W = J M⁻¹ Jᵀ,   gₙ = σμ/λₙ − uₙ,   g_t = −u_t − 2 λ_t σμ/q
//! ```
//!
//! solved in body space by Woodbury's identity: `H z = Jᵀ D⁻¹ g`, `ΔΛ = D⁻¹ (g − J z)`, with
//! `H = M + Jᵀ D⁻¹ J` (6 unknowns a body, positive definite whatever the contacts: a brick on
//! two bricks, eight rows for six motions, is no harder). One factorisation an iteration, two
//! substitutions (predictor and corrector). Each step goes 0.995 of the way to the nearest
//! bound (λₙ, w, γ > 0; |λ_t| < r), so every iterate is strictly in its set.
//!
//! # Its promises
//!
//! It stops when the natural residual (the change a Gauss–Seidel update of a row would make
//! to its velocity, `kₙ |P(Λ − u/kₙ) − Λ|`) is below half the sweeps' tolerance on every row; or
//! hands over to the sweeps once it is below [`INTERIOR_HANDOFF`] times that tolerance, or
//! when it stops gaining, or at [`INTERIOR_STEPS`] iterations, or at its work budget (then
//! with its best iterate). Each iterate is strictly inside its set, so whatever it hands
//! over is feasible. Its answer replaces the rows'
//! impulses only if it lowers F, so K still only goes down, and the sweeps that follow judge
//! convergence to the same tolerance as before.

use super::body_space::{self, add_blocks, add_transposed, velocities, velocity, Outcome};
use super::Row;
use crate::physics::collision::solver_body::{Axis, SolverBody};
use nalgebra::{Matrix2, Matrix3, Matrix6, Vector2, Vector6};

/// Most iterations (each a factorisation in body space) of one solve.
pub const INTERIOR_STEPS: usize = 40;

/// The residual (as a multiple of the sweeps' tolerance) at which it hands over to the
/// sweeps: below about 1e-7 m/s the products cancel in the right-hand side and the steps
/// lose accuracy (measured: it then stalls, and its best iterate is kept). 100, i.e.
/// 1e-8 m/s: fewer unconverged steps on the walls than 1e4 (wall-ball 27 of 200 against 60).
pub const INTERIOR_HANDOFF: f64 = 100.0;

/// The fraction of the way to the nearest bound a step goes.
const BOUNDARY: f64 = 0.995;

/// The start's products, as a fraction of load × residual.
const CENTRE: f64 = 0.1;

/// The buffers of an interior-point solve (reused from step to step).
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    base: body_space::Scratch,
    /// Per local body: M⁻¹.
    inverse: Vec<Matrix6<f64>>,
    /// Per contact: the normal's dual w and the disk's multiplier γ.
    dual: Vec<[f64; 2]>,
    /// Per contact: D⁻¹, the right-hand side g, and the step ΔΛ, (Δw, Δγ).
    inverse_d: Vec<Matrix3<f64>>,
    rhs: Vec<[f64; 3]>,
    step: Vec<[f64; 3]>,
    dual_step: Vec<[f64; 2]>,
    /// Per contact: the target products of the normal and the disk (σμ less the
    /// predictor's second-order terms).
    target: Vec<[f64; 2]>,
    /// A body vector, and H's Jacobi scaling 1/√Hᵢᵢ.
    body: Vec<f64>,
    scale: Vec<f64>,
    /// The impulses of the iterate with the smallest residual.
    best: Vec<[f64; 3]>,
}

/// The disk's slack q = r² − |λ_t|².
#[inline]
fn slack(bound: f64, l: &[f64; 3]) -> f64 {
    bound * bound - (l[1] * l[1] + l[2] * l[2])
}

/// The largest s with `r² − |t + s d|² ≥ 0` (∞ when d = 0).
fn disk_reach(bound: f64, t: [f64; 2], d: [f64; 2]) -> f64 {
    let dd = d[0] * d[0] + d[1] * d[1];
    if dd == 0.0 {
        return f64::INFINITY;
    }
    let td = t[0] * d[0] + t[1] * d[1];
    let inside = (bound * bound - (t[0] * t[0] + t[1] * t[1])).max(0.0);
    (-td + (td * td + dd * inside).sqrt()) / dd
}

/// The interior-point solve (module doc) from the rows' impulses, within `budget` row
/// updates; with no `directions` (stage 1) the rows are normals alone. Declines (changes
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
    if !body_space::setup(rows, directions, motions, &mut scratch.base) || !start(motions, scratch) {
        return outcome;
    }
    let stop = 0.5 * tolerance;
    let pass = rows.len() as u64;
    let mut last_reach = 1.0;
    let mut best_residual = f64::INFINITY;
    scratch.best.clear();
    loop {
        velocities(&mut scratch.base);
        outcome.work += pass;
        let residual = natural_residual(&scratch.base);
        let mu = complementarity(scratch, [0.0; 3], 0.0);
        if residual <= stop {
            outcome.converged = true;
            keep(&scratch.base, &mut scratch.best);
            break;
        }
        if residual < best_residual {
            best_residual = residual;
            keep(&scratch.base, &mut scratch.best);
        }
        // Hand over to the sweeps once near (the products then cancel in H's right-hand side
        // and the steps lose their accuracy), or when the steps stop gaining.
        if residual <= INTERIOR_HANDOFF * tolerance
            || residual > 100.0 * best_residual
            || outcome.steps >= INTERIOR_STEPS
            || outcome.work >= budget
        {
            break;
        }
        if !factor(scratch, &mut outcome) {
            return outcome;
        }
        outcome.steps += 1;
        // Predictor (σ = 0), then the corrector with σ = (μ_aff/μ)³ and the predictor's
        // second-order terms (Mehrotra).
        scratch.target.clear();
        scratch.target.resize(scratch.base.groups.len(), [0.0; 2]);
        direction(scratch);
        let reach = step_length(scratch);
        let mu_aff = complementarity(scratch, [reach; 3], 1.0);
        let mut sigma = (mu_aff / mu).powi(3).min(1.0);
        if last_reach < 0.1 {
            sigma = sigma.max(0.3);
        }
        corrector_targets(scratch, sigma * mu);
        direction(scratch);
        let reach = step_length(scratch);
        last_reach = reach;
        outcome.work += 4 * pass;
        advance(scratch, reach);
    }
    restore(&mut scratch.base, &scratch.best);
    body_space::take(rows, directions, motions, &scratch.base, &mut outcome);
    outcome
}

/// The best iterate's impulses and duals, kept.
fn keep(base: &body_space::Scratch, best: &mut Vec<[f64; 3]>) {
    best.clear();
    best.extend(base.groups.iter().map(|g| g.lambda));
}

fn restore(base: &mut body_space::Scratch, best: &[[f64; 3]]) {
    if best.len() == base.groups.len() {
        for (g, l) in base.groups.iter_mut().zip(best) {
            g.lambda = *l;
        }
    }
}

/// M⁻¹ per body, and the start: the rows' impulses moved inside their sets, x from them,
/// and the duals from the rows' velocities there; false if a body has no inverse.
fn start(motions: &[SolverBody], scratch: &mut Scratch) -> bool {
    let Scratch {
        base,
        inverse,
        dual,
        ..
    } = scratch;
    inverse.clear();
    for &b in &base.bodies {
        let s = &motions[b];
        let mut block = Matrix6::zeros();
        for k in 0..3 {
            block[(k, k)] = s.inv_mass;
        }
        block.fixed_view_mut::<3, 3>(3, 3).copy_from(&s.inv_inertia);
        inverse.push(block);
    }
    velocities(base);
    let n = base.groups.len().max(1) as f64;
    let speed = base
        .groups
        .iter()
        .map(|g| base.u[g.first].abs())
        .sum::<f64>()
        / n;
    let load = base.groups.iter().map(|g| g.lambda[0]).sum::<f64>() / n;
    let load = load.max(
        base.groups
            .iter()
            .map(|g| base.u[g.first].abs() / g.k)
            .sum::<f64>()
            / n,
    );
    let (floor_load, floor_speed) = (1e-2 * load.max(1e-300), 1e-2 * speed.max(1e-300));
    for g in base.groups.iter_mut() {
        g.lambda[0] = g.lambda[0].max(floor_load);
        if g.tangents {
            let size = Vector2::new(g.lambda[1], g.lambda[2]).norm();
            if size > 0.9 * g.bound {
                let s = 0.9 * g.bound / size;
                g.lambda[1] *= s;
                g.lambda[2] *= s;
            }
        }
    }
    body_velocities(base, inverse);
    velocities(base);
    // The products start no smaller than μ₀ = load × the largest natural residual (a start
    // far from the answer starts far from the bounds: centred).
    let mu0 = CENTRE * load * natural_residual(base).max(floor_speed);
    dual.clear();
    for g in &base.groups {
        let u = &base.u[g.first..];
        let w = u[0].max(floor_speed).max(mu0 / g.lambda[0]);
        let gamma = if g.tangents {
            (Vector2::new(u[1], u[2]).norm().max(floor_speed) / (2.0 * g.bound))
                .max(mu0 / slack(g.bound, &g.lambda))
        } else {
            0.0
        };
        dual.push([w, gamma]);
    }
    true
}

/// x = M⁻¹ (M x₀ + Jᵀ Λ).
fn body_velocities(base: &mut body_space::Scratch, inverse: &[Matrix6<f64>]) {
    let mut y = base.mx0.clone();
    for g in &base.groups {
        let count = if g.tangents { 3 } else { 1 };
        add_transposed(
            &base.constraints[g.first..g.first + count],
            &g.lambda[..count],
            1.0,
            &mut y,
        );
    }
    for (i, m) in inverse.iter().enumerate() {
        let v = m * Vector6::from_column_slice(&y[6 * i..6 * i + 6]);
        base.x[6 * i..6 * i + 6].copy_from_slice(v.as_slice());
    }
}

/// The largest natural residual `kₙ |P(Λ − u/kₙ) − Λ|` of a contact (m/s).
fn natural_residual(base: &body_space::Scratch) -> f64 {
    let mut residual: f64 = 0.0;
    for g in &base.groups {
        let u = &base.u[g.first..];
        let pn = (g.lambda[0] - u[0] / g.k).max(0.0);
        let mut gap = (pn - g.lambda[0]).abs();
        if g.tangents {
            let t = Vector2::new(g.lambda[1] - u[1] / g.k, g.lambda[2] - u[2] / g.k);
            let size = t.norm();
            let p = if size > g.bound {
                t * (g.bound / size)
            } else {
                t
            };
            gap = gap.max((p - Vector2::new(g.lambda[1], g.lambda[2])).norm());
        }
        residual = residual.max(gap * g.k);
    }
    residual
}

/// The mean complementarity product (λₙ w and γ q) at the iterate moved `reach` (primal,
/// dual, unused) along the step scaled by `scale` (0: at the iterate).
fn complementarity(scratch: &Scratch, reach: [f64; 3], scale: f64) -> f64 {
    let (sp, sd) = (reach[0] * scale, reach[1] * scale);
    let mut sum = 0.0;
    let mut count = 0usize;
    for (i, g) in scratch.base.groups.iter().enumerate() {
        let (d, dd) = if scale == 0.0 {
            ([0.0; 3], [0.0; 2])
        } else {
            (scratch.step[i], scratch.dual_step[i])
        };
        let l = [
            g.lambda[0] + sp * d[0],
            g.lambda[1] + sp * d[1],
            g.lambda[2] + sp * d[2],
        ];
        let du = &scratch.dual[i];
        sum += l[0] * (du[0] + sd * dd[0]);
        count += 1;
        if g.tangents {
            sum += (du[1] + sd * dd[1]) * slack(g.bound, &l);
            count += 1;
        }
    }
    sum / count.max(1) as f64
}

/// D⁻¹ per contact and `H = M + Jᵀ D⁻¹ J`, factored; false if it fails.
fn factor(scratch: &mut Scratch, outcome: &mut Outcome) -> bool {
    let Scratch {
        base,
        dual,
        inverse_d,
        scale,
        ..
    } = scratch;
    let nb = base.bodies.len();
    let body_space::Scratch {
        blocks,
        system,
        mass,
        constraints,
        groups,
        ..
    } = base;
    blocks.resize_with(nb.max(blocks.len()), Vec::new);
    for (i, (list, m)) in blocks.iter_mut().zip(mass.iter()).enumerate() {
        list.clear();
        list.push((i, *m));
    }
    inverse_d.clear();
    for (g, du) in groups.iter().zip(dual.iter()) {
        let mut d = Matrix3::zeros();
        d[(0, 0)] = g.lambda[0] / du[0];
        let count = if g.tangents {
            let t = Vector2::new(g.lambda[1], g.lambda[2]);
            let q = slack(g.bound, &g.lambda);
            let dt = (Matrix2::identity() + t * t.transpose() * (2.0 / q)) * (2.0 * du[1]);
            let Some(inverse) = dt.try_inverse() else {
                return false;
            };
            d.fixed_view_mut::<2, 2>(1, 1).copy_from(&inverse);
            3
        } else {
            1
        };
        add_blocks(blocks, &constraints[g.first..g.first + count], &d);
        inverse_d.push(d);
    }
    // H's entries grow like λₙ/w as a contact's product goes to 0: scaled to a unit
    // diagonal, so that the factor's ε (1e-10 of the largest diagonal entry) stays 1e-10 of
    // every one.
    scale.clear();
    scale.resize(6 * nb, 1.0);
    for (i, list) in blocks[..nb].iter().enumerate() {
        if let Some((_, b)) = list.iter().find(|(j, _)| *j == i) {
            for k in 0..6 {
                scale[6 * i + k] = 1.0 / b[(k, k)].sqrt();
            }
        }
    }
    for (i, list) in blocks[..nb].iter_mut().enumerate() {
        for (j, b) in list.iter_mut() {
            for r in 0..6 {
                for c in 0..6 {
                    b[(r, c)] *= scale[6 * i + r] * scale[6 * *j + c];
                }
            }
        }
    }
    if !body_space::fill(&blocks[..nb], system) {
        return false;
    }
    outcome.work += super::factorisation_work(system.stored(), 6 * nb);
    system.factor_regularised()
}

/// The step (ΔΛ, Δw, Δγ) for the target products (module doc).
fn direction(scratch: &mut Scratch) {
    let Scratch {
        base,
        dual,
        inverse_d,
        rhs,
        step,
        dual_step,
        body,
        target,
        scale,
        ..
    } = scratch;
    let nb = base.bodies.len();
    rhs.clear();
    body.clear();
    body.resize(6 * nb, 0.0);
    for (i, g) in base.groups.iter().enumerate() {
        let u = &base.u[g.first..];
        let [tn, tt] = target[i];
        let mut r = [tn / g.lambda[0] - u[0], 0.0, 0.0];
        let count = if g.tangents {
            let q = slack(g.bound, &g.lambda);
            r[1] = -u[1] - 2.0 * g.lambda[1] * tt / q;
            r[2] = -u[2] - 2.0 * g.lambda[2] * tt / q;
            3
        } else {
            1
        };
        rhs.push(r);
        let v = inverse_d[i] * nalgebra::Vector3::from(r);
        add_transposed(
            &base.constraints[g.first..g.first + count],
            &v.as_slice()[..count],
            1.0,
            body,
        );
    }
    for (b, s) in body.iter_mut().zip(scale.iter()) {
        *b *= s;
    }
    base.system.substitute_regularised(body);
    for (b, s) in body.iter_mut().zip(scale.iter()) {
        *b *= s;
    }
    step.clear();
    dual_step.clear();
    for (i, g) in base.groups.iter().enumerate() {
        let count = if g.tangents { 3 } else { 1 };
        let mut r = rhs[i];
        for (k, c) in base.constraints[g.first..g.first + count]
            .iter()
            .enumerate()
        {
            r[k] -= velocity(c, body) - c.bias;
        }
        let d = inverse_d[i] * nalgebra::Vector3::from(r);
        let d = [d[0], d[1], d[2]];
        let [w, gamma] = dual[i];
        let [tn, tt] = target[i];
        let dw = tn / g.lambda[0] - w - w / g.lambda[0] * d[0];
        let dg = if g.tangents {
            let q = slack(g.bound, &g.lambda);
            (tt - gamma * q + 2.0 * gamma * (g.lambda[1] * d[1] + g.lambda[2] * d[2])) / q
        } else {
            0.0
        };
        step.push(d);
        dual_step.push([dw, dg]);
    }
}

/// The corrector's target products: `centre` = σμ less the predictor step's second-order
/// terms, Δλₙ Δw on a normal and `Δγ Δq − γ |Δλ_t|²` on a disk (Δq = −2 λ_t·Δλ_t).
fn corrector_targets(scratch: &mut Scratch, centre: f64) {
    for (i, g) in scratch.base.groups.iter().enumerate() {
        let d = scratch.step[i];
        let dd = scratch.dual_step[i];
        let tn = centre - d[0] * dd[0];
        let tt = if g.tangents {
            let dq = -2.0 * (g.lambda[1] * d[1] + g.lambda[2] * d[2]);
            centre - (dd[1] * dq - scratch.dual[i][1] * (d[1] * d[1] + d[2] * d[2]))
        } else {
            0.0
        };
        scratch.target[i] = [tn, tt];
    }
}

/// The primal and dual step lengths: `BOUNDARY` of the way to the nearest bound, at most 1.
fn step_length(scratch: &Scratch) -> f64 {
    let mut reach: f64 = 1.0 / BOUNDARY;
    for (i, g) in scratch.base.groups.iter().enumerate() {
        let d = scratch.step[i];
        let dd = scratch.dual_step[i];
        let du = scratch.dual[i];
        if d[0] < 0.0 {
            reach = reach.min(-g.lambda[0] / d[0]);
        }
        if dd[0] < 0.0 {
            reach = reach.min(-du[0] / dd[0]);
        }
        if g.tangents {
            reach = reach.min(disk_reach(
                g.bound,
                [g.lambda[1], g.lambda[2]],
                [d[1], d[2]],
            ));
            if dd[1] < 0.0 {
                reach = reach.min(-du[1] / dd[1]);
            }
        }
    }
    (BOUNDARY * reach).min(1.0)
}

/// Λ, the duals and x moved `s` along the step.
fn advance(scratch: &mut Scratch, s: f64) {
    let Scratch {
        base,
        dual,
        step,
        dual_step,
        inverse,
        ..
    } = scratch;
    for (i, g) in base.groups.iter_mut().enumerate() {
        for (l, d) in g.lambda.iter_mut().zip(step[i]) {
            *l += s * d;
        }
        if !g.tangents {
            g.lambda[1] = 0.0;
            g.lambda[2] = 0.0;
        }
        dual[i][0] += s * dual_step[i][0];
        dual[i][1] += s * dual_step[i][1];
    }
    body_velocities(base, inverse);
}

#[cfg(test)]
mod tests {
    use super::super::body_space::objective;
    use super::super::body_space::tests::{assert_in_cone, solved_cube};
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
        // 2 kg's momentum: vx 1 → 1 − 0.025; ω stays 0.
        let (rows, motions, outcome, before) = run(1.0);
        // It hands over at 1e-8 m/s (INTERIOR_HANDOFF × 1e-10), the sweeps finish.
        assert!(
            outcome.taken && outcome.steps <= INTERIOR_STEPS,
            "{outcome:?}"
        );
        let b = &motions[0];
        assert!(
            (b.v - Vector3::new(0.975, 0.0, 0.0)).norm() < 1e-7,
            "{:?}",
            b.v
        );
        assert!(b.omega.norm() < 1e-7, "{:?}", b.omega);
        assert!(objective(&rows, &motions) < before);
        assert_in_cone(&rows);
    }

    #[test]
    fn a_slow_cube_sticks() {
        // μ·0.1 N·s / 2 kg = 0.025 m/s > 0.01 m/s: friction stops it.
        let (_, motions, outcome, _) = run(0.01);
        assert!(outcome.taken, "{outcome:?}");
        assert!(motions[0].v.norm() < 1e-7, "{:?}", motions[0].v);
        assert!(motions[0].omega.norm() < 1e-7);
    }
}
