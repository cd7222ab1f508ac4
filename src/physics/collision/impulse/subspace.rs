//! Subspace steps: a method over the rows, not a constraint kind. Projected Gauss–Seidel (the
//! normal and friction rows' `sweep`) converges linearly, and slowly when bodies slide on each
//! other (a row of dominoes) or when a large system settles (a pyramid); the sweeps find the
//! active set long before they converge on it. Every [`SUBSPACE_EVERY`] sweeps that did not
//! converge, a subspace step (`step`) solves the active set the sweeps have found directly,
//! with a Newton step along the sliding disks' edges, and is kept only if it lowers the same
//! objective. The sweeps still decide convergence, to the same tolerance (`sweep`).
//!
//! A large friction stage ([`SWEEPS_FIRST_ROWS`] rows or more) skips a search when its sweeps
//! are about to converge anyway: at the rate of the last burst's second half they reach the
//! tolerance for less work than the last search cost, all its rounds' factorisations
//! (`sweeps_cheaper`). Once one of its searches has left the sweeps after it above where
//! they stood before it, it searches again only when its sweeps, at their rate, need more
//! than [`RAISED_SWEEPS`] sweeps to the tolerance: on the knocked wall a search often throws
//! sweeps at 2e-10 m/s back to 1e-8 (wall-ball 200 steps 46.8M → 42.7M row updates, its
//! worst step ×28.2 → ×15.5 the median; bonded-wall-ball 100 44.6M → 41.8M, 55 → 60 steps
//! unconverged at the budget; knife-wall 200 29.1M → 28.4M, 8 → 9).
//!
//! Stage 2 (friction) takes them whenever its direct solve declined. Stage 1 takes them only
//! in a large, *wide* system whose direct solve declined: the same step on the pushing normals
//! alone, the whole step first projected onto λ ≥ 0, at most [`NORMAL_SUBSPACE_MAX`] a step.
//! The step's formulas (the objective F, the edge unknowns' curvature, the ratio test and the
//! exact measure of the change of F) are on `step`.

#[cfg(doc)]
use super::WORK_BUDGET;
use super::{
    factorisation_work, friction, normal, Counters, Direct, Row, ENVELOPE_MAX, MAX_SWEEPS,
    SWEEPS_FIRST_ROWS,
};
use crate::physics::collision::solver_body::{Axis, End, SolverBody};
use crate::physics::envelope::{Envelope, Pivots};

/// The friction sweeps take a subspace step (`step`) after this many sweeps
/// that did not converge.
pub const SUBSPACE_EVERY: u64 = 8;

/// A large stage ([`SWEEPS_FIRST_ROWS`] rows or more) one of whose searches left the sweeps
/// after it above where they stood before it searches again only when its sweeps, at their
/// rate, need more than this many sweeps to the tolerance.
pub const RAISED_SWEEPS: u64 = 64;

/// Most changes of the active set one friction subspace search makes (each a direct solve).
pub const SUBSPACE_ROUNDS: usize = 8;

/// Most subspace steps the normal sweeps of one step take (each a factorisation of the
/// pushing rows): a settling pyramid of 20 rows needs 6; where they stop helping (rows on the
/// edge of degeneracy) the plain sweeps go on.
pub const NORMAL_SUBSPACE_MAX: usize = 32;

/// How many times a friction subspace step that did not lower F is tried again, 8 times
/// shorter.
pub const SUBSPACE_BACKTRACKS: usize = 3;

/// The largest turn of a sliding disk's impulse along its edge in one subspace step, rad.
pub const EDGE_TURN: f64 = 0.25;

/// A friction disk whose impulse is within this fraction of its bound is on its edge
/// (sliding) for the subspace step; further inside, it sticks.
const SLIDING_EDGE: f64 = 1e-9;

/// Sweeps with a subspace step ([`step`]) after every [`SUBSPACE_EVERY`]
/// sweeps that did not converge, at most [`MAX_SWEEPS`] sweeps in all and within the step's
/// work budget ([`WORK_BUDGET`]: once it is spent, no more subspace steps, and the sweeps
/// stop); returns whether they converged, how many sweeps ran and the last sweep's residual. With friction directions these are the friction sweeps
/// ([`friction::sweep`]); with none (stage 1, every friction bound 0) the normal sweeps
/// ([`normal::sweep`]), and the subspace step solves the pushing normals alone. A system too
/// wide for the direct solve ([`ENVELOPE_MAX`]) stops trying the subspace steps.
pub(super) fn sweep(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers: &mut Direct,
    counters: &mut Counters,
) -> (bool, u64, f64) {
    sweep_after(rows, directions, motions, tolerance, (buffers, counters), 0)
}

/// [`sweep`] after its first burst of `swept` sweeps already ran (and did not converge; 0:
/// none ran): the subspace search first, then on as [`sweep`], bit for bit; the sweeps
/// counted are those run here.
pub(super) fn sweep_after(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    (buffers, counters): (&mut Direct, &mut Counters),
    swept: u64,
) -> (bool, u64, f64) {
    let cap = MAX_SWEEPS as u64;
    let normals_only = directions.is_empty();
    let mut total = swept;
    let mut skip_burst = swept > 0;
    let rows_count = rows.len();
    let mut subspace = true;
    let mut steps_left = if normals_only {
        NORMAL_SUBSPACE_MAX
    } else {
        usize::MAX
    };
    // The work of this stage's last search, its rounds' factorisations together (none yet:
    // the first search runs).
    let mut last_search = None;
    // The sweeps' residual just before the last search, until the burst after it ends; and
    // whether a search of this stage has left the sweeps above where they stood
    // ([`RAISED_SWEEPS`]).
    let mut before_search: Option<f64> = None;
    let mut raised = false;
    loop {
        subspace &= steps_left > 0 && !buffers.spent();
        if !std::mem::take(&mut skip_burst) {
            let burst = if subspace { SUBSPACE_EVERY } else { cap }.min(cap - total);
            // The first burst always runs; later ones only within the budget.
            let burst = if total == 0 {
                buffers.sweeps_left(rows_count, burst)
            } else {
                burst.min(buffers.budget.saturating_sub(buffers.work) / rows_count.max(1) as u64)
            };
            if burst == 0 {
                return (false, total - swept, buffers.residual);
            }
            let (converged, sweeps, residual, middle) = if normals_only {
                let (converged, sweeps, residual) = normal::sweep(rows, motions, tolerance, burst);
                (converged, sweeps, residual, None)
            } else {
                friction_burst(rows, directions, motions, tolerance, burst)
            };
            buffers.work += sweeps * rows_count as u64;
            buffers.residual = residual;
            total += sweeps;
            if converged || total >= cap {
                return (converged, total - swept, residual);
            }
            let large = rows_count >= SWEEPS_FIRST_ROWS;
            raised |= large && before_search.take().is_some_and(|before| residual > before);
            if large
                && middle.zip(last_search).is_some_and(|((middle, sweeps), search)| {
                    sweeps_cheaper((middle, residual, sweeps), tolerance, rows_count, search)
                        || (raised && sweeps_needed(middle, residual, sweeps, tolerance)
                            <= RAISED_SWEEPS as f64)
                })
            {
                continue;
            }
        }
        before_search = Some(buffers.residual);
        // An active-set search: a step cut short by a normal reaching 0 or a sticking disk
        // reaching its edge changes the active set; solve again on the new one.
        buffers.pinned.clear();
        let mut search = 0;
        for _ in 0..SUBSPACE_ROUNDS {
            if buffers.spent() {
                break;
            }
            let outcome = step(rows, directions, motions, buffers);
            if !buffers.unknowns.is_empty() && outcome != Subspace::TooWide {
                search += factorisation_work(buffers.system.stored(), buffers.unknowns.len());
                last_search = Some(search);
            }
            match outcome {
                Subspace::Taken { whole } => {
                    steps_left = steps_left.saturating_sub(1);
                    if normals_only {
                        counters.normal_subspace += 1;
                    } else {
                        counters.friction_subspace += 1;
                    }
                    if whole || steps_left == 0 {
                        break;
                    }
                }
                Subspace::Declined => break,
                Subspace::TooWide => {
                    subspace = false;
                    break;
                }
            }
        }
    }
}

/// A burst of `burst` friction sweeps ([`friction::sweep`]) run as two halves, the same
/// sweeps bit for bit: whether they converged, how many ran, the last sweep's residual,
/// and (when both halves ran) the residual after the first half with the sweeps after it.
fn friction_burst(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    burst: u64,
) -> (bool, u64, f64, Option<(f64, u64)>) {
    let half = burst / 2;
    if half == 0 {
        let (converged, sweeps, residual) =
            friction::sweep(rows, directions, motions, tolerance, burst);
        return (converged, sweeps, residual, None);
    }
    let (converged, sweeps, middle) = friction::sweep(rows, directions, motions, tolerance, half);
    if converged {
        return (converged, sweeps, middle, None);
    }
    let (converged, more, residual) =
        friction::sweep(rows, directions, motions, tolerance, burst - half);
    (converged, sweeps + more, residual, Some((middle, more)))
}

/// Whether sweeps whose residual fell from `middle` to `last` over their last `sweeps`
/// sweeps reach `tolerance`, at that rate (linear convergence, `r_{k+n} = r_k ρⁿ`), for
/// less work than `factor` row updates (the last search's cost: the estimates of all the
/// factorisations its rounds took), `rows` a sweep: then the subspace search is skipped
/// (module doc). Stalled or rising sweeps never skip it.
///
/// Measured (issue 35): the running-bond wall whose end bricks topple, its worst step (2.0 s)
/// took 24 factorisations of 700 unknowns (75 000 stored entries, about 58 000 row updates
/// each) while its sweeps sat at 1.6–2.9e-10 m/s against a tolerance of 1.05e-10, falling
/// about 3 % a sweep: some 36 sweeps of 296 rows (11 000 row updates) to go.
///
/// A search is compared by all its rounds, not its last factorisation alone, since
/// 2026-12-07: a search on the knocked wall (`contact_steps wall-ball`) takes several rounds
/// (one factorisation each) and is then followed by sweeps that restart from a residual it
/// raised, so a sweep rate that reaches the tolerance within one factorisation's work was
/// often searched again. Measured (work in row updates, deterministic; total, median, steps
/// unconverged at the budget), one factorisation → the whole search: wall-ball 200 steps
/// 90.6M → 46.8M, median 278 079 → 72 998, 91 → 45 unconverged (CPU 34.4 → 19.3 ms a
/// step, one run each under load); knife-wall 200 32.9M → 29.1M, 11 → 8;
/// knife-wall-ball 100 6.93M → 7.47M (+8 %), 23 → 24; bonded-wall-ball 100 37.6M → 44.6M
/// (+19 %), 49 → 55; dominoes16 1500 10.19M → 10.48M (+3 %; its steps of 64 rows or more),
/// 0 → 0; wall 600 and dominoes 3000 bit for bit the same (dominoes' 30 rows are below
/// [`SWEEPS_FIRST_ROWS`]). Callgrind over `World::step`: wall-ball 200 50.7G → 26.3G
/// instructions (−48 %), dominoes16 1500 8.41G → 8.64G (+2.7 %).
fn sweeps_cheaper(
    (middle, last, sweeps): (f64, f64, u64),
    tolerance: f64,
    rows: usize,
    factor: u64,
) -> bool {
    sweeps_needed(middle, last, sweeps, tolerance) * rows as f64 <= factor as f64
}

/// The sweeps still needed to reach `tolerance` at the rate of sweeps whose residual fell
/// from `middle` to `last` over their last `sweeps` (linear convergence, `r_{k+n} = r_k ρⁿ`,
/// `n = ln(tolerance/last)/ln ρ`); infinite when they stalled, rose or none ran.
fn sweeps_needed(middle: f64, last: f64, sweeps: u64, tolerance: f64) -> f64 {
    if sweeps == 0 || last >= middle || last <= 0.0 {
        return f64::INFINITY;
    }
    let rate_log = (last / middle).ln() / sweeps as f64;
    (tolerance / last).ln() / rate_log
}

/// What a subspace step did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Subspace {
    /// Taken, whole (α = 1) or cut short by the ratio test.
    Taken { whole: bool },
    /// Nothing to solve, a singular system, no room to move, or no descent (round-off).
    Declined,
    /// The system's envelope is over [`ENVELOPE_MAX`].
    TooWide,
}

/// A subspace step of the friction stage (projected Gauss–Seidel with subspace minimisation,
/// Silcowitz, Niebe & Erleben 2010, with a Newton step along the sliding disks' edges):
/// block Gauss–Seidel converges linearly, and slowly when contacts are stiffly coupled or sit
/// on the edge of their friction disk with almost no slip (a domino leaning on the next: its
/// floor contacts at the stick–slip limit); the sweeps find the active set long before they
/// converge on it. With the active set the sweeps left, the stage-2 objective
///
/// ```text
/// F(Λ) = K(Λ) + Σ λₙ gₙ/dt           (the objective the sweeps minimise, ≥ K)
/// ```
///
/// is minimised by one Newton step, a direct solve over these unknowns:
///
/// - each pushing normal (λₙ > 0), its row `uₙ + gₙ/dt = 0`; the normals at 0 are held;
/// - each sticking disk (|λ_t| < bound, or on the edge with the slip along λ_t: it wants
///   in), both tangents, rows `u_t = 0`;
/// - each sliding disk (on its edge |λ_t| = bound, slip u_t against λ_t): its impulse may
///   move along the edge, `λ_t = bound (s cos θ + s⊥ sin θ)` with `s = λ_t/|λ_t|`, `s⊥` s
///   turned by 90°; the unknown is the arc δ = bound·θ along s⊥, whose row carries the
///   edge's curvature: `∂²F/∂δ² = s⊥ᵀ K_t s⊥ + κ`, `κ = −u_t·s / bound ≥ 0` (the slip speed
///   over the bound: the Lagrange multiplier ν of the disk update), right-hand side `−u_t·s⊥`.
///
/// ```text
/// (H + ε𝟙) Δ = −∇F      H: the rows' couplings A (the same minimum-norm LDLᵀ as the direct
///                       solves), plus κ on each edge unknown's diagonal
/// ```
///
/// The step is `αΔ` with the largest α ≤ 1 that keeps every free normal ≥ 0 and every
/// sticking disk inside its bound, `|λ_t + αΔ_t| ≤ bound` (the positive root of a quadratic
/// in α); an edge unknown moves its impulse along the circle, `λ_t ← bound (λ_t + αδ s⊥)/|·|`.
/// The change of F is then measured exactly — F is quadratic in Λ, so
/// `F(Λ + ΔΛ) − F(Λ) = ΔΛ·(∇F(Λ) + ∇F(Λ + ΔΛ))/2`, with ∇F the rows' velocities (plus gₙ/dt),
/// summed over the rows that moved: no cancellation against F itself, so even a step of
/// 1e-20 J is judged right — and a step that did not lower F (H nearly singular, solved
/// inaccurately) is undone and tried 8 times shorter, [`SUBSPACE_BACKTRACKS`] times at most.
/// Like every sweep update, an accepted step only lowers F, so K stays below K₀. A step cut
/// short by the ratio test changes the active set (that normal is held at 0, that disk is
/// held on its edge whatever its slip says) and the caller solves again, up to
/// [`SUBSPACE_ROUNDS`] times. The sweeps go on from there and judge convergence as before,
/// to the same tolerance: the steps change only how fast they get there. The unknowns are
/// ordered by the last body their row acts on, so a chain of bodies has a banded envelope.
fn step(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    buffers: &mut Direct,
) -> Subspace {
    let Direct {
        system,
        saved,
        unknowns,
        subspace_rows,
        pinned,
        order,
        work,
        ..
    } = buffers;
    gather_unknowns(rows, directions, motions, order, unknowns, pinned);
    let m = unknowns.len();
    if m == 0 {
        return Subspace::Declined;
    }
    // H_pq: the couplings of the unknowns' directions (a tangent unknown is c₁ t₁ + c₂ t₂,
    // combined once: the coupling is bilinear).
    if !assemble(system, unknowns, motions) {
        return Subspace::TooWide;
    }
    *work += super::factorisation_work(system.stored(), m);
    let Some(delta) = system.solve(Pivots::Regularised) else {
        return Subspace::Declined;
    };
    // The ratio test: the largest α ≤ 1 keeping the free normals ≥ 0 and the sticking disks
    // inside their bounds (an edge unknown stays on its circle whatever α).
    let (mut alpha, mut blocking) = ratio_test(rows, unknowns, delta);
    if alpha.is_nan() || alpha <= 0.0 {
        return Subspace::Declined;
    }
    // Stage 1 (no friction unknowns) first tries the whole step projected onto λ ≥ 0, which
    // changes many normals at once (a pyramid settling changes hundreds); the ratio-test step
    // follows if that one does not lower F.
    let ratio = (alpha, blocking);
    let projected_first = directions.is_empty() && alpha < 1.0;
    if projected_first {
        (alpha, blocking) = (1.0, None);
    }
    saved.clear();
    saved.extend_from_slice(motions);
    subspace_rows.clear();
    subspace_rows.extend(rows.iter().map(|r| (r.normal.lambda, r.friction.lambda)));
    // Backtracking: a step that did not lower F (a nearly singular H solved inaccurately) is
    // undone and tried again 8 times shorter, a few times.
    for attempt in 0..SUBSPACE_BACKTRACKS {
        apply_step(rows, directions, motions, unknowns, delta, alpha, blocking);
        // ΔF = ΔΛ·(∇F before + ∇F after)/2 over the rows that moved (exact: F is quadratic).
        let change = objective_change(rows, directions, motions, unknowns, subspace_rows);
        if change < 0.0 {
            if let Some(p) = blocking.filter(|&p| unknowns[p].tangent.is_some()) {
                pinned.push(unknowns[p].row);
            }
            return Subspace::Taken {
                whole: alpha == 1.0 && attempt == 0 && !projected_first,
            };
        }
        motions.copy_from_slice(saved);
        for (row, &(lambda, tangent)) in rows.iter_mut().zip(subspace_rows.iter()) {
            row.normal.lambda = lambda;
            row.friction.lambda = tangent;
        }
        if projected_first && attempt == 0 {
            (alpha, blocking) = ratio;
        } else {
            alpha /= 8.0;
            blocking = None;
        }
    }
    Subspace::Declined
}

/// The unknowns of the subspace step, into `unknowns`: each row's normal while it pushes
/// (λ > 0), and its tangent impulse — one edge unknown when its disk is on its edge and it
/// slides against its impulse (u_t·λ_t ≤ 0) or is `pinned`, else two sticking unknowns.
/// Rows taken in `order`: sorted by the last body they act on.
fn gather_unknowns(
    rows: &[Row],
    directions: &[[Axis; 2]],
    motions: &[SolverBody],
    order: &mut Vec<usize>,
    unknowns: &mut Vec<Unknown>,
    pinned: &[usize],
) {
    // Rows ordered by the last body they act on (stable: a pair's rows stay together), so
    // a body's floor contacts sit beside its contacts with its neighbours: a chain of bodies
    // (a row of dominoes, a stack) gets a banded envelope, where contact order (every floor
    // contact first) would reach back over all of them.
    order.clear();
    order.extend(0..rows.len());
    order.sort_by_key(|&i| {
        let n = &rows[i].normal.axis;
        n.b.map_or(n.a.body, |b| b.body.max(n.a.body))
    });
    unknowns.clear();
    for &i in order.iter() {
        let row = &rows[i];
        if row.normal.lambda > 0.0 {
            let gradient = row.normal.axis.velocity(motions) + row.normal.bias;
            unknowns.push(Unknown {
                row: i,
                tangent: None,
                before: [gradient, 0.0],
                direction: row.normal.axis,
            });
        }
        let bound = row.friction.bound;
        if bound == 0.0 {
            continue;
        }
        let [t1, t2] = &directions[i];
        let u = [t1.velocity(motions), t2.velocity(motions)];
        let l = row.friction.lambda;
        let size = (l[0] * l[0] + l[1] * l[1]).sqrt();
        let slip_along = (u[0] * l[0] + u[1] * l[1]) / size;
        if size >= bound * (1.0 - SLIDING_EDGE) && (slip_along <= 0.0 || pinned.contains(&i)) {
            let s = [l[0] / size, l[1] / size];
            let c = [-s[1], s[0]];
            unknowns.push(Unknown {
                row: i,
                tangent: Some((c, (-slip_along / bound).max(0.0))),
                before: u,
                direction: combined(&directions[i], c),
            });
        } else {
            for (k, c) in [[1.0, 0.0], [0.0, 1.0]].into_iter().enumerate() {
                unknowns.push(Unknown {
                    row: i,
                    tangent: Some((c, 0.0)),
                    before: u,
                    direction: directions[i][k],
                });
            }
        }
    }
}

/// H_pq into `system`, with the right-hand side −∇F along each unknown (`H Δ = −∇F`).
/// False when the envelope grows over [`ENVELOPE_MAX`].
fn assemble(system: &mut Envelope, unknowns: &[Unknown], motions: &[SolverBody]) -> bool {
    let m = unknowns.len();
    system.reset(m);
    for p in 0..m {
        let up = &unknowns[p];
        let dp = &up.direction;
        system.rhs[p] = -match up.tangent {
            None => up.before[0],
            Some((c, _)) => c[0] * up.before[0] + c[1] * up.before[1],
        };
        system.fill_row(p, dp.bodies(), |q| {
            let dq = &unknowns[q].direction;
            if q == p {
                Some(dp.coupling(dp, motions) + up.tangent.map_or(0.0, |(_, kappa)| kappa))
            } else {
                dp.shares_a_body(dq).then(|| dp.coupling(dq, motions))
            }
        });
        if system.stored() > ENVELOPE_MAX {
            return false;
        }
    }
    true
}

/// The ratio test on the step `delta`: the largest α ≤ 1 keeping the free normals ≥ 0 and
/// the sticking disks inside their bounds, an edge unknown turning at most [`EDGE_TURN`]
/// radians; with the unknown that blocks it (none for an edge's turn).
fn ratio_test(rows: &[Row], unknowns: &[Unknown], delta: &[f64]) -> (f64, Option<usize>) {
    let m = unknowns.len();
    let mut alpha: f64 = 1.0;
    let mut blocking = None;
    let mut p = 0;
    while p < m {
        let unknown = &unknowns[p];
        let row = &rows[unknown.row];
        match unknown.tangent {
            None => {
                if row.normal.lambda + delta[p] < 0.0 && row.normal.lambda / -delta[p] < alpha {
                    alpha = row.normal.lambda / -delta[p];
                    blocking = Some(p);
                }
                p += 1;
            }
            Some(_) if unknowns.get(p + 1).is_none_or(|u| u.row != unknown.row) => {
                // An edge unknown: the model is quadratic in the arc, the edge is a circle;
                // turn by at most EDGE_TURN radians, where they agree to second order.
                let reach = EDGE_TURN * row.friction.bound / delta[p].abs();
                if reach < alpha {
                    alpha = reach;
                    blocking = None;
                }
                p += 1;
            }
            Some(_) => {
                // |t + α d|² = bound²: α = (−t·d + √((t·d)² + |d|²(bound² − |t|²))) / |d|².
                let (t, d) = (row.friction.lambda, [delta[p], delta[p + 1]]);
                let dd = d[0] * d[0] + d[1] * d[1];
                let td = t[0] * d[0] + t[1] * d[1];
                let inside = row.friction.bound.powi(2) - (t[0] * t[0] + t[1] * t[1]);
                if dd > 0.0 {
                    let reach = (-td + (td * td + dd * inside.max(0.0)).sqrt()) / dd;
                    if reach < alpha {
                        alpha = reach;
                        blocking = Some(p);
                    }
                }
                p += 2;
            }
        }
    }
    (alpha, blocking)
}

/// Moves the impulses by `alpha delta` and the bodies with them: a normal clamped at 0 (at
/// exactly 0 when it is `blocking`), a sticking disk put back on its edge when it reached it,
/// an edge unknown moved along its tangent and back onto its circle.
fn apply_step(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    unknowns: &[Unknown],
    delta: &[f64],
    alpha: f64,
    blocking: Option<usize>,
) {
    let m = unknowns.len();
    let mut p = 0;
    while p < m {
        let unknown = unknowns[p];
        let row = &mut rows[unknown.row];
        match unknown.tangent {
            None => {
                // The normal that cut the step short leaves the active set at exactly 0.
                let new = if blocking == Some(p) {
                    0.0
                } else {
                    (row.normal.lambda + alpha * delta[p]).max(0.0)
                };
                let step = new - row.normal.lambda;
                row.normal.lambda = new;
                row.normal.axis.apply(step, motions);
                p += 1;
            }
            Some((c, _)) => {
                let pair = unknowns.get(p + 1).is_some_and(|u| u.row == unknown.row);
                let old = row.friction.lambda;
                let step = if pair {
                    [alpha * delta[p], alpha * delta[p + 1]]
                } else {
                    [alpha * delta[p] * c[0], alpha * delta[p] * c[1]]
                };
                let mut new = [old[0] + step[0], old[1] + step[1]];
                let size = (new[0] * new[0] + new[1] * new[1]).sqrt();
                if size > row.friction.bound || !pair || blocking == Some(p) {
                    // Back onto the edge: a sticking disk that reached it (round-off), or an
                    // edge unknown moved along its tangent.
                    let scale = row.friction.bound / size;
                    new = [new[0] * scale, new[1] * scale];
                }
                row.friction.lambda = new;
                let [t1, t2] = &directions[unknown.row];
                t1.apply(new[0] - old[0], motions);
                t2.apply(new[1] - old[1], motions);
                p += if pair { 2 } else { 1 };
            }
        }
    }
}

/// The change of F from the impulses in `saved` (each row's (λ, λ_t) before the step) to the
/// rows' now: `ΔΛ·(∇F before + ∇F after)/2` over the unknowns' rows (exact: F is quadratic).
fn objective_change(
    rows: &[Row],
    directions: &[[Axis; 2]],
    motions: &[SolverBody],
    unknowns: &[Unknown],
    saved: &[(f64, [f64; 2])],
) -> f64 {
    let m = unknowns.len();
    let mut change = 0.0;
    let mut p = 0;
    while p < m {
        let unknown = &unknowns[p];
        let row = &rows[unknown.row];
        let (lambda, tangent) = saved[unknown.row];
        match unknown.tangent {
            None => {
                let after = row.normal.axis.velocity(motions) + row.normal.bias;
                change += (row.normal.lambda - lambda) * 0.5 * (unknown.before[0] + after);
                p += 1;
            }
            Some(_) => {
                let [t1, t2] = &directions[unknown.row];
                let after = [t1.velocity(motions), t2.velocity(motions)];
                let moved = [
                    row.friction.lambda[0] - tangent[0],
                    row.friction.lambda[1] - tangent[1],
                ];
                change += 0.5
                    * (moved[0] * (unknown.before[0] + after[0])
                        + moved[1] * (unknown.before[1] + after[1]));
                p += if unknowns.get(p + 1).is_some_and(|u| u.row == unknown.row) {
                    2
                } else {
                    1
                };
            }
        }
    }
    change
}

/// One unknown of the friction subspace step: row `row`'s normal impulse (`tangent` None), or
/// its tangent impulse along `c₁ t₁ + c₂ t₂` with the curvature κ added to its diagonal
/// (`tangent` Some((c, κ)): a sticking disk has two, c = (1, 0) and (0, 1), κ = 0; a sliding
/// one has one, along its edge).
#[derive(Debug, Clone, Copy)]
pub(super) struct Unknown {
    row: usize,
    tangent: Option<([f64; 2], f64)>,
    /// ∇F along the row's directions before the step: (uₙ + gₙ/dt, 0), or u_t.
    before: [f64; 2],
    /// The row's normal, or its tangent `c₁ t₁ + c₂ t₂` with its ends (for the couplings).
    direction: Axis,
}

/// The direction `c₁ t₁ + c₂ t₂` of two tangent directions at one contact (the same ends):
/// d, r×d and I⁻¹(r×d) are linear in d (its k is not used).
fn combined(t: &[Axis; 2], c: [f64; 2]) -> Axis {
    let [t1, t2] = t;
    let end = |e: &End, f: &End| End {
        body: e.body,
        rd: e.rd * c[0] + f.rd * c[1],
        w: e.w * c[0] + f.w * c[1],
    };
    Axis {
        d: t1.d * c[0] + t2.d * c[1],
        a: end(&t1.a, &t2.a),
        b: t1.b.as_ref().zip(t2.b.as_ref()).map(|(e, f)| end(e, f)),
        k: f64::NAN,
        inv_k: f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::sweeps_cheaper;

    #[test]
    fn a_search_is_skipped_only_when_the_sweeps_left_cost_less_than_a_factorisation() {
        // Halved every sweep (1.6e-7 → 1e-8 over 4 sweeps), 1e-8 → 1e-10 takes
        // log₂ 100 = 6.64 more sweeps: 664 row updates of 100 rows.
        let (middle, last, tolerance) = (1.6e-7, 1e-8, 1e-10);
        assert!(sweeps_cheaper((middle, last, 4), tolerance, 100, 700));
        assert!(!sweeps_cheaper((middle, last, 4), tolerance, 100, 600));
        // Stalled, rising or no sweeps: never skipped, whatever the factorisation costs.
        assert!(!sweeps_cheaper((last, last, 4), tolerance, 100, u64::MAX));
        assert!(!sweeps_cheaper((last, middle, 4), tolerance, 100, u64::MAX));
        assert!(!sweeps_cheaper((middle, last, 0), tolerance, 100, u64::MAX));
    }
}
