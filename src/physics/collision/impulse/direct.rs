//! The direct solves: methods over the rows, not a constraint kind. When the answer of a
//! stage is "every approaching contact stops and pushes" (stage 1: a face landing, a body at
//! rest, the usual case) or "every pushing contact sticks" (stage 2: a body at rest on a
//! slope), the minimum of K the sweeps converge to is computed at once by a small LDLᵀ solve
//! ([`Envelope`], only each row's envelope stored) and checked against the conditions of the
//! whole problem; the sweeps run only when that check fails.
//!
//! - `inelastic` (stage 1): `(A + ε𝟙) λ = −u` over an active set of normal rows, changed by
//!   principal pivoting (at most [`PIVOT_ROUNDS`] changes); a *wide* system (a pyramid) starts
//!   its active set from the rows that pushed last step as well as the approaching ones.
//! - `sticking` (stage 2): `(A + ε𝟙) Δλ = −u` over the rows (n, t₁, t₂) of each pushing
//!   contact, then a load-weighted second try (`Sticking::Resting`, gaps below
//!   [`RESTING_GAP`] held closed).
//! - `mean_envelope`: how wide the rows are in contact order, which decides whether a large
//!   system tries the sweeps first ([`WIDE_ENVELOPE`]).
//!
//! Their formulas are on the functions. Here
//!
//! ```text
//! A_ij = Σ_shared bodies (±dᵢ)·(±dⱼ)/M + (r×(±dᵢ))·I⁻¹(r×(±dⱼ))     (Axis::coupling)
//! ```
//!
//! is the contact-space inverse mass over the rows' axes, and ε = 1e-10 · max Aᵢᵢ picks the
//! minimum-norm answer of a semi-definite A (4 coplanar contacts constrain 3 motions).
//!
//! [`Envelope`]: crate::physics::envelope::Envelope
//! [`WIDE_ENVELOPE`]: super::WIDE_ENVELOPE

#[cfg(doc)]
use super::GAP_ROUND_OFF;
use super::{Direct, Row, ENVELOPE_MAX};
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::envelope::{Envelope, Pivots};

/// Most contacts in a step to try the direct inelastic solve for (a stack of 10 cubes has 40,
/// a pyramid of 20 rows about 1600; the system is banded or nearly so there and only its
/// envelope is stored and factored, see [`Envelope`]).
///
/// [`Envelope`]: crate::physics::envelope::Envelope
pub const DIRECT_MAX: usize = 4096;

/// How many changes of its active set the direct inelastic solve may make (one row out or in
/// per pair of bodies each) before it gives way to the sweeps (a pyramid of 10 rows needed
/// more than 12 while it settles).
pub const PIVOT_ROUNDS: usize = 40;

/// Most pushing contacts to try the direct sticking-friction solve for (three rows each).
pub const STICKING_MAX: usize = DIRECT_MAX / 3;

/// The direct sticking solve's second try (`Sticking::Resting`) holds a pushing speculative
/// contact still if its gap is below this (m): bodies at rest on redundant contacts (a face's
/// four corners, dominoes lying on each other) keep gaps of nanometres to a tenth of a micrometre
/// where their edges are not quite parallel, and closing each within the step asks for motions
/// no rigid body has. Within the micrometre to which bodies stand.
pub const RESTING_GAP: f64 = 1e-6;

/// The mean width of the rows' envelope in contact order, `Σ_p (p − first(p) + 1) / m`, with
/// first(p) the first row acting on one of row p's bodies (as [`Envelope`] stores it).
///
/// [`Envelope`]: crate::physics::envelope::Envelope
#[inline]
pub(super) fn mean_envelope(rows: &[Row], body_first: &mut Vec<usize>) -> f64 {
    body_first.clear();
    let mut sum = 0usize;
    for (p, row) in rows.iter().enumerate() {
        let mut first = p;
        for b in row.normal.axis.bodies().into_iter().flatten() {
            if b >= body_first.len() {
                body_first.resize(b + 1, usize::MAX);
            }
            first = first.min(body_first[b]);
            body_first[b] = body_first[b].min(p);
        }
        sum += p - first + 1;
    }
    sum as f64 / rows.len().max(1) as f64
}

/// The inelastic problem solved directly, when its answer is "every approaching contact
/// stops": with the approaching contacts as the active set, solve
///
/// ```text
/// (A + ε𝟙) λ = −u,   A_ij = Σ_shared bodies (±nᵢ)·(±nⱼ)/M + (r×(±nᵢ))·I⁻¹(r×(±nⱼ)),
///                    ε = 1e-10 · max Aᵢᵢ
/// ```
///
/// by LDLᵀ (A is only semi-definite: 4 coplanar contacts constrain 3 motions; the tiny ε
/// picks the minimum-norm λ, which shares the load symmetrically whatever the contact order).
/// The result is accepted only if it is the solution of the whole problem — every λᵢ ≥ 0 and
/// no contact, active or not, still approaching — so it is the same minimum of K that the
/// sweeps converge to, reached at once. When a λᵢ comes out negative (at rest, a corner of a
/// 4-point face: four rows of rank three) or a contact outside the set still approaches, the
/// active set changes — by one row per pair of bodies, the pair's most negative one out or
/// its most approaching one in, so a pyramid whose every face has such a corner needs a few
/// rounds, not one per face — and the system is solved again, at most [`PIVOT_ROUNDS`]
/// times. The active rows stay in contact order (rows of a pair together), which keeps the
/// envelope of a stack banded. A `wide` system (a pyramid) starts its active set with the
/// rows that pushed last step too (their warm impulse along the normal is positive): its
/// answer at rest, where starting from the approaching rows alone would climb the pyramid a
/// row per pair per round. Returns false (and changes nothing) otherwise.
///
/// `joints` are joint rows (bounds (−∞, ∞), aiming at J_j u = −b_j with their biases
/// `joint_bias`, 0 but for a free motor's −speed, none given: all 0: [`super::joined`])
/// solved in the same system, always active, merged with the contact rows by their lowest
/// body (the envelope of a chain on the ground stays banded); their impulses go to
/// `joint_lambda`. None: the contacts' system alone, as written above.
pub(super) fn inelastic(
    wide: bool,
    rows: &mut [Row],
    (joints, joint_bias, joint_lambda): (&[Axis], &[f64], &mut Vec<f64>),
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers: &mut Direct,
) -> bool {
    let Direct {
        system,
        saved,
        active,
        lambda,
        entering,
        work,
        budget,
        merged,
        ..
    } = buffers;
    active.clear();
    let approaching = |r: &Row| r.approach + r.normal.bias < 0.0;
    if !rows.iter().any(approaching) {
        return true;
    }
    let start = |r: &Row| approaching(r) || (wide && r.warm.dot(&r.normal.axis.d) > 0.0);
    for (i, row) in rows.iter().enumerate() {
        if start(row) {
            active.push(i);
        }
    }
    let mut m = active.len();
    if m > DIRECT_MAX {
        return false;
    }
    // An active-set search (principal pivoting), at most PIVOT_ROUNDS changes: solve on the
    // active rows; if some λ < 0 (a corner of a 4-point face whose minimum-norm share came
    // out negative), take the most negative row out; else if a row outside the set still
    // approaches, take the most approaching one in; else accept. Every accepted answer passes
    // the same test as before (λ ≥ 0, nothing approaching): the solution of the whole problem.
    saved.clear();
    saved.extend_from_slice(motions);
    for round in 0..=PIVOT_ROUNDS {
        // Within the step's work budget (`WORK_BUDGET`): a search that has spent it gives way
        // to the sweeps (which then run their floor of sweeps, and say so if unconverged).
        if *work >= *budget {
            return false; // the motions are the saved ones at the start of every round
        }
        let system_work = (&mut *system, &mut *merged, &mut *work);
        if !solve_active(
            rows,
            active,
            (joints, joint_bias, &mut *joint_lambda),
            motions,
            saved,
            system_work,
            lambda,
        ) {
            return false;
        }
        let last = round == PIVOT_ROUNDS;
        let (_, most_negative) = (0..m).fold((0.0, None), |(w, at), p| {
            if lambda[p] < w {
                (lambda[p], Some(p))
            } else {
                (w, at)
            }
        });
        if let Some(p) = most_negative {
            if last || m == 1 {
                return false;
            }
            // Out: the most negative row of each pair of bodies that has one (each face's
            // corner whose minimum-norm share came out negative; the same row as "the most
            // negative" when one pair has them). The rows stay in contact order.
            let pair = |p: usize| {
                let n = &rows[active[p]].normal.axis;
                (n.a.body, n.b.map(|b| b.body))
            };
            let mut out = Vec::new();
            let mut q = 0;
            while q < m {
                let mut end = q;
                let mut worst = (0.0, None);
                while end < m && pair(end) == pair(q) {
                    if lambda[end] < worst.0 {
                        worst = (lambda[end], Some(end));
                    }
                    end += 1;
                }
                out.extend(worst.1);
                q = end;
            }
            debug_assert!(out.contains(&p));

            let mut k = 0;
            active.retain(|_| {
                let keep = out.binary_search(&k).is_err();
                k += 1;
                keep
            });
            m = active.len();
            continue;
        }
        for (axis, &mu) in joints.iter().zip(joint_lambda.iter()) {
            axis.apply(mu, motions);
        }
        for p in 0..m {
            rows[active[p]].normal.axis.apply(lambda[p], motions);
        }
        // The most approaching row of each pair of bodies that has one, in contact order
        // (the same row as "the most approaching" when one pair has them).
        let pair = |r: &Row| (r.normal.axis.a.body, r.normal.axis.b.map(|b| b.body));
        let mut worst: Option<(usize, f64)> = None;
        let mut group: Option<(usize, f64)> = None;
        entering.clear();
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && pair(r) != pair(&rows[i - 1]) {
                entering.extend(group.take().map(|(j, _)| j));
            }
            let u = r.normal.axis.velocity(motions) + r.normal.bias;
            if u < -tolerance {
                if group.is_none_or(|(_, w)| u < w) {
                    group = Some((i, u));
                }
                if worst.is_none_or(|(_, w)| u < w) {
                    worst = Some((i, u));
                }
            }
        }
        entering.extend(group.map(|(j, _)| j));
        let Some((i, _)) = worst else {
            for p in 0..m {
                rows[active[p]].normal.lambda = lambda[p];
            }
            return true;
        };
        motions.copy_from_slice(saved);
        if last || m + entering.len() > DIRECT_MAX || active.binary_search(&i).is_ok() {
            return false;
        }
        // In, in contact order (rows of a pair stay together: the envelope stays narrow).
        for &j in entering.iter() {
            if let Err(at) = active.binary_search(&j) {
                active.insert(at, j);
            }
        }
        m = active.len();
    }
    false
}

/// [`solve_active`] without joint rows: the active contact rows in contact order, the same
/// operations in the same order as its merged path with no joints, without the merge's
/// indirection (a resting body's step, every step: issue 35's resting-cube aim).
fn solve_contacts(
    rows: &[Row],
    active: &[usize],
    motions: &[SolverBody],
    (system, work): (&mut Envelope, &mut u64),
    lambda: &mut Vec<f64>,
) -> bool {
    let m = active.len();
    system.reset(m);
    for p in 0..m {
        let ni = &rows[active[p]].normal;
        system.rhs[p] = -ni.axis.velocity(motions) - ni.bias;
        system.fill_row(p, ni.axis.bodies(), |q| {
            let nj = &rows[active[q]].normal.axis;
            ni.axis.shares_a_body(nj).then(|| ni.axis.coupling(nj, motions))
        });
        if system.stored() > ENVELOPE_MAX {
            return false;
        }
    }
    *work += super::factorisation_work(system.stored(), m);
    let Some(solution) = system.solve(Pivots::Regularised) else {
        return false;
    };
    lambda.clear();
    lambda.extend_from_slice(&solution[..m]);
    true
}

/// One round of [`inelastic`]: the system of the joint rows and the active contact rows
/// (`active`, into `rows`) at `motions` (= `saved`) assembled, factored (its work added to
/// `work`) and solved into `lambda` (contacts) and `joint_lambda`; false when it gives no
/// answer or its envelope is too large.
fn solve_active(
    rows: &[Row],
    active: &[usize],
    (joints, joint_bias, joint_lambda): (&[Axis], &[f64], &mut Vec<f64>),
    motions: &mut [SolverBody],
    saved: &[SolverBody],
    (system, merged, work): (&mut Envelope, &mut Vec<usize>, &mut u64),
    lambda: &mut Vec<f64>,
) -> bool {
    let m = active.len();
    let mj = joints.len();
    if mj == 0 {
        // No joint multipliers, as the merged path leaves them (an empty `joint_lambda` after
        // a solve tells `Joined::inelastic` that a solve ran).
        joint_lambda.clear();
        return solve_contacts(rows, active, motions, (system, work), lambda);
    }
    // The system's rows: the joint rows and the active contact rows merged by their
    // lowest body (a chain lying on the ground stays banded); without joints, the
    // active contact rows in contact order.
    merged.clear();
    let low = |a: &Axis| a.b.map_or(a.a.body, |b| a.a.body.min(b.body));
    let (mut i, mut p) = (0, 0);
    while i < mj || p < m {
        if p == m || (i < mj && low(&joints[i]) <= low(&rows[active[p]].normal.axis)) {
            merged.push(i);
            i += 1;
        } else {
            merged.push(mj + p);
            p += 1;
        }
    }
    let axis = |s: usize| match s.checked_sub(mj) {
        Some(p) => &rows[active[p]].normal.axis,
        None => &joints[s],
    };
    system.reset(mj + m);
    for (p, &s) in merged.iter().enumerate() {
        let ni = axis(s);
        system.rhs[p] = match s.checked_sub(mj) {
            Some(q) => -ni.velocity(motions) - rows[active[q]].normal.bias,
            None => -aimed(ni.velocity(motions), joint_bias, s),
        };
        system.fill_row(p, ni.bodies(), |q| {
            let nj = axis(merged[q]);
            ni.shares_a_body(nj).then(|| ni.coupling(nj, motions))
        });
        if system.stored() > ENVELOPE_MAX {
            return false;
        }
    }
    *work += super::factorisation_work(system.stored(), mj + m);
    let Some(solution) = system.solve(Pivots::Regularised) else {
        return false;
    };
    lambda.clear();
    lambda.resize(m, 0.0);
    joint_lambda.clear();
    joint_lambda.resize(mj, 0.0);
    for (&s, &x) in merged.iter().zip(solution) {
        match s.checked_sub(mj) {
            Some(p) => lambda[p] = x,
            None => joint_lambda[s] = x,
        }
    }
    if mj > 0 {
        // One step of refinement: the ε that picks the minimum-norm answer leaves a
        // residual ε·x, which the joints' coupling lifts above the tolerance (a bob on
        // a rod against a tilted wall: 2e-10 m/s). The rates after x are A x − rhs.
        let at = |s: usize, lambda: &[f64], joint_lambda: &[f64]| match s.checked_sub(mj) {
            Some(p) => lambda[p],
            None => joint_lambda[s],
        };
        for &s in merged.iter() {
            axis(s).apply(at(s, lambda, joint_lambda), motions);
        }
        let mut w: Vec<f64> = (merged.iter())
            .map(|&s| {
                let bias = s.checked_sub(mj).map_or_else(
                    || joint_bias.get(s).copied().unwrap_or(0.0),
                    |q| rows[active[q]].normal.bias,
                );
                -(axis(s).velocity(motions) + bias)
            })
            .collect();
        motions.copy_from_slice(saved);
        system.substitute_regularised(&mut w);
        for (&s, dx) in merged.iter().zip(&w) {
            match s.checked_sub(mj) {
                Some(p) => lambda[p] += dx,
                None => joint_lambda[s] += dx,
            }
        }
    }

    true
}

/// A joint row's rate `u` less its aim: u + b with b = `biases[s]` (none given, or 0: u
/// itself, not u + 0, so that rows without a bias keep their bits).
#[inline]
fn aimed(u: f64, biases: &[f64], s: usize) -> f64 {
    match biases.get(s) {
        Some(&b) if b != 0.0 => u + b,
        _ => u,
    }
}

/// Friction solved directly, when its answer is "every pushing contact sticks" (a body at rest
/// on a slope, the usual case with friction): with the contacts that push after stage 1, find
/// the increments of their normal impulses and their tangent impulses that stop every tangent
/// velocity and keep every normal one,
///
/// ```text
/// (A + ε𝟙) Δλ = −u      over the rows (n, t₁, t₂) of each pushing contact
/// ```
///
/// (the same minimum-norm LDLᵀ as the inelastic solve). Accepted only if it is the solution
/// of the stage-2 problem: every λₙ ≥ 0, every |λ_t| inside its disk μ λ_stage1, and no
/// contact approaching; then it is the minimum of K the sweeps converge to, reached at once.
/// Returns false (and changes nothing) otherwise.
///
/// Bodies at rest on redundant contacts (dominoes lying on each other: two floor contacts
/// and two contacts with the next domino each) have many impulses that hold them; the
/// minimum-norm one shares each load evenly and can leave a disk whose neighbour has room
/// (measured: 1.938e-5 N·s asked of a disk of 1.898e-5 beside one of 2.125e-5), and the sweeps
/// then crawl along the disks' edges for ever (40–80 sweeps and 20–40 subspace steps a step,
/// 0.7–2.8 ms, while no body moves by 1e-12 m/s). So a second try, [`Sticking::Resting`],
/// weights the minimum norm by each contact's stage-1 load ℓ: with `Δλ = S y`,
/// `S = diag(ℓ)`, it solves `(S A S + ε𝟙) y = −S u`, the change minimising `Σ (Δλᵢ/ℓᵢ)²`, so
/// each contact takes a share of the load in proportion to its disk. It also holds still every
/// pushing speculative contact whose gap is below [`RESTING_GAP`] (target `uₙ = 0` instead of
/// `−g/dt`): such gaps (nm to 0.1 µm, left where edges are not quite parallel) make the rows
/// ask for motions no rigid body has, and the minimum-norm answer then grows without bound
/// (measured |Δλ| of 10–500 N·s against impulses of 1e-4). The same acceptance checks follow;
/// with a gap held closed, what they accept is the stage-2 solution with that gap taken as 0
/// (as [`GAP_ROUND_OFF`] does for every solve at 1 nm): the contact may push across up to
/// 1 µm, where the exact problem would let the body close that gap first. Velocities are the
/// same either way once no gap is held (the weights move only how the impulses are shared).
///
/// `joints` are joint rows held in the same system ([`super::joined`]: equality rows, and
/// limits' stops that push), targets `J_j Δu = −J_j u` (their rate kept at 0), a joint row
/// scaled by the largest load in the second try; each stop's total impulse must stay ≥ 0.
/// One factorisation then answers "everything sticks" for a chain lying on the ground, where
/// the joints' projected Gauss–Seidel (`Joined::friction`) crawls (every contact coupled to
/// every other through the links). Their impulses' change goes to `Direct::joint_delta`.
pub(super) fn sticking(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    joints: HeldJoints,
    motions: &mut [SolverBody],
    tolerance: f64,
    how: Sticking,
    buffers: &mut Direct,
) -> Answer {
    let Direct {
        system,
        saved,
        active,
        lambda: delta,
        work,
        budget,
        merged,
        joint_delta,
        slides,
        ..
    } = buffers;
    let HeldJoints {
        axes: joints,
        floor,
        ceiling,
        bias: joint_bias,
        modes,
    } = joints;
    // The pushing contacts (with modes, every contact: those that do not push start as
    // separated, `Hold::Off`, and join when they approach).
    active.clear();
    active.extend((0..rows.len()).filter(|&i| modes || rows[i].normal.lambda > 0.0));
    let m = active.len();
    let mj = joints.len();
    if m == 0 || m > STICKING_MAX || *work >= *budget {
        return Answer::Declined;
    }
    // Ordered by the last body each acts on (stable), as the subspace step's unknowns: a chain
    // of bodies (a row of dominoes, a stack) gets a banded envelope.
    let last = |a: &Axis| a.b.map_or(a.a.body, |b| b.body.max(a.a.body));
    active.sort_by_key(|&i| last(&rows[i].normal.axis));
    // Unknowns 3p (normal), 3p + 1, 3p + 2 (tangents) for the p-th pushing contact (its
    // normal alone when it slides), then 3m + j for joint row j; with joint rows the system
    // takes them in `merged` order (each joint row before the contacts with the same last
    // body: a chain on the ground stays banded), without them in this order.
    if mj > 0 {
        // A sliding contact's tangent impulse (`modes`: bound · d, fixed this round).
        let mode = |k: usize| if modes { slides[active[k]] } else { Hold::Stick };
        let key = |k: usize| last(&rows[active[k]].normal.axis);
        order_with_joints(m, key, mode, (joints, last), merged);
    }
    let u = Unknowns {
        rows,
        directions,
        joints,
        joint_bias,
        active: &active[..],
        merged: &merged[..],
        slides: &slides[..],
        m,
        mj,
        n: if mj == 0 { 3 * m } else { merged.len() },
        how,
        largest: active.iter().map(|&i| rows[i].normal.lambda).fold(0.0, f64::max),
        modes,
    };
    if mj > 0 {
        saved.clear();
        saved.extend_from_slice(motions);
        u.apply_fixed(motions);
    }
    if !u.assemble(system, motions) {
        if mj > 0 {
            motions.copy_from_slice(saved);
        }
        return Answer::Declined;
    }
    *work += super::factorisation_work(system.stored(), u.n);
    let Some(solution) = system.solve(Pivots::Regularised) else {
        if mj > 0 {
            motions.copy_from_slice(saved);
        }
        return Answer::Declined;
    };
    delta.clear();
    delta.resize(3 * m + mj, 0.0);
    for (p, y) in solution.iter().enumerate() {
        let s = u.slot(p);
        delta[s] = u.scale(s) * y;
    }
    if mj > 0 {
        u.refine(system, delta, motions, saved);
    }
    // The modes that change (row, new mode), written into `slides` before Changed returns.
    let Some(changes) = u.changes_before(delta) else {
        return Answer::Declined;
    };
    // A stop (one-sided joint row) may not come to pull, nor a motor pass its bound.
    if (delta[3 * m..].iter().zip(floor)).any(|(d, f)| d < f)
        || (delta[3 * m..].iter().zip(ceiling)).any(|(d, c)| d > c)
    {
        return Answer::Declined;
    }
    if !changes.is_empty() {
        for &(i, mode) in &changes {
            slides[i] = mode;
        }
        return Answer::Changed;
    }
    saved.clear();
    saved.extend_from_slice(motions);
    for (s, d) in delta.iter().enumerate() {
        u.direction(s).apply(*d, motions);
    }
    let changes = u.changes_after(motions, tolerance);
    if !changes.is_empty() {
        for &(i, mode) in &changes {
            slides[i] = mode;
        }
        motions.copy_from_slice(saved);
        return Answer::Changed;
    }
    if rows
        .iter()
        .any(|r| r.normal.axis.velocity(motions) + u.bias(r) < -tolerance)
    {
        motions.copy_from_slice(saved);
        return Answer::Declined;
    }
    for k in 0..m {
        let row = &mut rows[active[k]];
        row.normal.lambda += delta[3 * k];
        row.friction.lambda = [delta[3 * k + 1], delta[3 * k + 2]];
    }
    joint_delta.clear();
    joint_delta.extend_from_slice(&delta[3 * m..]);
    Answer::Accepted
}

/// The unknowns of one `sticking` solve and how each enters its system: `active` the pushing
/// contacts (the p-th owns unknowns 3p, 3p + 1, 3p + 2: its normal, then its two tangents
/// `directions`), then 3m + j for joint row j of `joints`; `merged` their system order with
/// joint rows (without them, the system takes the `n` = 3m unknowns in this order).
struct Unknowns<'a> {
    rows: &'a [Row],
    directions: &'a [[Axis; 2]],
    joints: &'a [Axis],
    /// The joint rows' biases (`HeldJoints::bias`).
    joint_bias: &'a [f64],
    active: &'a [usize],
    merged: &'a [usize],
    /// Each row's mode (`Direct::slides`), read only with `modes`.
    slides: &'a [Hold],
    /// How many pushing contacts, and joint rows.
    m: usize,
    mj: usize,
    /// How many unknowns the system has.
    n: usize,
    how: Sticking,
    /// The largest stage-1 load of the pushing contacts (a joint row's scale when resting).
    largest: f64,
    modes: bool,
}

impl<'a> Unknowns<'a> {
    /// The unknown at place `p` of the system.
    fn slot(&self, p: usize) -> usize {
        if self.mj == 0 {
            p
        } else {
            self.merged[p]
        }
    }

    /// The axis of unknown `s`: a contact's normal or tangent, or a joint row.
    fn direction(&self, s: usize) -> &'a Axis {
        let m = self.m;
        if s >= 3 * m {
            return &self.joints[s - 3 * m];
        }
        let i = self.active[s / 3];
        match s % 3 {
            0 => &self.rows[i].normal.axis,
            t => &self.directions[i][t - 1],
        }
    }

    /// The scale of unknown `s`: 1, or its contact's stage-1 load (the weighted minimum
    /// norm); a joint row's: the largest load.
    fn scale(&self, s: usize) -> f64 {
        match self.how {
            Sticking::Exact => 1.0,
            Sticking::Resting { .. } if s >= 3 * self.m => self.largest,
            Sticking::Resting { .. } => {
                self.rows[self.active[s / 3]].normal.lambda.max(1e-6 * self.largest)
            }
        }
    }

    /// The bias a pushing contact's normal velocity is held to (`uₙ = −bias`): −g/dt, or 0
    /// for a gap below [`RESTING_GAP`] in the second try.
    fn bias(&self, row: &Row) -> f64 {
        match self.how {
            Sticking::Resting { dt } if row.normal.bias * dt < RESTING_GAP => 0.0,
            _ => row.normal.bias,
        }
    }

    /// The velocity bias of unknown `s`: its contact's bias for a normal, a joint row's own
    /// (a free motor's −speed), 0 otherwise.
    fn target(&self, s: usize) -> f64 {
        if s < 3 * self.m && s.is_multiple_of(3) {
            self.bias(&self.rows[self.active[s / 3]])
        } else if s >= 3 * self.m {
            self.joint_bias.get(s - 3 * self.m).copied().unwrap_or(0.0)
        } else {
            0.0
        }
    }

    /// The mode of the k-th pushing contact (sticking without `modes`).
    fn mode(&self, k: usize) -> Hold {
        if self.modes {
            self.slides[self.active[k]]
        } else {
            Hold::Stick
        }
    }

    /// The sliding and separating contacts' fixed impulses, applied before the system is
    /// assembled.
    fn apply_fixed(&self, motions: &mut [SolverBody]) {
        let rows = self.rows;
        for k in (0..self.m).filter(|_| self.modes) {
            let i = self.active[k];
            match self.mode(k) {
                Hold::Stick => {}
                Hold::Slide(d) => {
                    let bound = rows[i].friction.bound;
                    self.directions[i][0].apply(bound * d[0], motions);
                    self.directions[i][1].apply(bound * d[1], motions);
                }
                Hold::Off => rows[i].normal.axis.apply(-rows[i].normal.lambda, motions),
            }
        }
    }

    /// The scaled system `(S A S + ε𝟙) y = −S (u + target)` at `motions` into `system`;
    /// false when its envelope grows above `ENVELOPE_MAX`.
    fn assemble(&self, system: &mut Envelope, motions: &[SolverBody]) -> bool {
        system.reset(self.n);
        for p in 0..self.n {
            let sp_slot = self.slot(p);
            let dp = self.direction(sp_slot);
            let sp = self.scale(sp_slot);
            system.rhs[p] = -sp * (dp.velocity(motions) + self.target(sp_slot));
            system.fill_row(p, dp.bodies(), |q| {
                let sq = self.slot(q);
                let dq = self.direction(sq);
                dp.shares_a_body(dq)
                    .then(|| sp * self.scale(sq) * dp.coupling(dq, motions))
            });
            if system.stored() > ENVELOPE_MAX {
                return false;
            }
        }
        true
    }

    /// With joint rows: one step of refinement of `delta` on the factored `system`, then the
    /// sliding and separating contacts' fixed impulses written into it. `motions` (the
    /// fixed impulses applied) are back at `saved` after.
    fn refine(
        &self,
        system: &mut Envelope,
        delta: &mut [f64],
        motions: &mut [SolverBody],
        saved: &[SolverBody],
    ) {
        // One step of refinement, as the inelastic solve's with joints: the ε that picks the
        // minimum-norm answer leaves a residual ε·x that the joints' coupling lifts above the
        // tolerance. The rates after Δλ are measured, then put back.
        for p in 0..self.n {
            let s = self.slot(p);
            self.direction(s).apply(delta[s], motions);
        }
        let mut w: Vec<f64> = (0..self.n)
            .map(|p| {
                let s = self.slot(p);
                -self.scale(s) * (self.direction(s).velocity(motions) + self.target(s))
            })
            .collect();
        motions.copy_from_slice(saved);
        system.substitute_regularised(&mut w);
        for (p, y) in w.iter().enumerate() {
            let s = self.slot(p);
            delta[s] += self.scale(s) * y;
        }
        for k in 0..self.m {
            let row = &self.rows[self.active[k]];
            match self.mode(k) {
                Hold::Stick => {}
                Hold::Slide(d) => {
                    delta[3 * k + 1] = row.friction.bound * d[0];
                    delta[3 * k + 2] = row.friction.bound * d[1];
                }
                Hold::Off => delta[3 * k] = -row.normal.lambda,
            }
        }
    }

    /// The modes that change before `delta` is applied (row, new mode): a contact whose
    /// normal would pull separates, a sticking one outside its disk slides along its own
    /// impulse. None (decline) when one would change without `modes`.
    fn changes_before(&self, delta: &[f64]) -> Option<Vec<(usize, Hold)>> {
        let mut changes: Vec<(usize, Hold)> = Vec::new();
        for k in 0..self.m {
            let row = &self.rows[self.active[k]];
            let (dn, t1, t2) = (delta[3 * k], delta[3 * k + 1], delta[3 * k + 2]);
            if row.normal.lambda + dn < 0.0 {
                if !self.modes {
                    return None;
                }
                // It would pull: it separates.
                changes.push((self.active[k], Hold::Off));
                continue;
            }
            let size = (t1 * t1 + t2 * t2).sqrt();
            if self.mode(k) == Hold::Stick && size > row.friction.bound {
                if !self.modes {
                    return None;
                }
                // It slides, along its own impulse for a start.
                changes.push((self.active[k], Hold::Slide([t1 / size, t2 / size])));
            }
        }
        Some(changes)
    }

    /// The modes that change once `delta` is applied to `motions` (row, new mode): a sliding
    /// contact slips against its impulse (d = −u_t/|u_t|, to [`SLIDE_TURN`]), a separated
    /// one does not approach, or they change.
    fn changes_after(&self, motions: &[SolverBody], tolerance: f64) -> Vec<(usize, Hold)> {
        let rows = self.rows;
        let mut changes: Vec<(usize, Hold)> = Vec::new();
        for k in (0..self.m).filter(|_| self.modes) {
            let i = self.active[k];
            match self.mode(k) {
                Hold::Stick => {}
                Hold::Off => {
                    if rows[i].normal.axis.velocity(motions) + self.bias(&rows[i]) < -tolerance {
                        changes.push((i, Hold::Stick));
                    }
                }
                // No disk (it did not push in stage 1): no friction to turn.
                Hold::Slide(_) if rows[i].friction.bound == 0.0 => {}
                Hold::Slide(d) => {
                    let u = [
                        self.directions[i][0].velocity(motions),
                        self.directions[i][1].velocity(motions),
                    ];
                    let speed = (u[0] * u[0] + u[1] * u[1]).sqrt();
                    if speed <= tolerance {
                        changes.push((i, Hold::Stick));
                    } else {
                        let e = [-u[0] / speed, -u[1] / speed];
                        if (e[0] - d[0]).abs().max((e[1] - d[1]).abs()) > SLIDE_TURN {
                            changes.push((i, Hold::Slide(e)));
                        }
                    }
                }
            }
        }
        changes
    }
}

/// How far (in each component of the unit direction) a sliding contact's impulse direction
/// may be from against its slip for `sticking` with modes to accept it: its friction is then
/// Coulomb's to within this angle (rad). Tighter, the fixed point on the directions does not
/// settle: a face's four corners sliding together (a chain's link landing) turn the others'
/// directions by about −3 times their own error each round, so a start 1e-7 rad off from
/// round-off grows instead of shrinking.
pub const SLIDE_TURN: f64 = 1e-6;

/// How a pushing contact takes part in [`sticking`] with modes (`Direct::slides`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) enum Hold {
    /// Its normal and tangent impulses are unknowns: u_n = −b, u_t = 0.
    #[default]
    Stick,
    /// Its tangent impulse is bound · d (d a unit direction), its normal an unknown.
    Slide([f64; 2]),
    /// It separates: no impulse (its stage-1 impulse taken back).
    Off,
}

/// What [`sticking`] answered.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Answer {
    /// Solved: the impulses are in the rows (and `Direct::joint_delta`), the motions moved.
    Accepted,
    /// Not the solution, nothing changed.
    Declined,
    /// With modes: some contact's mode changed (`Direct::slides`); nothing else changed, solve
    /// again.
    Changed,
}

/// The joint rows a direct sticking solve holds with the contacts ([`super::joined`]): their
/// weighed axes, and the least change of each one's impulse (−∞ for an equality row, −μ₁ for
/// a limit's stop that pushed with μ₁ in stage 1: it may not come to pull). The change of
/// their impulses is left in `Direct::joint_delta`.
///
/// With `modes` (joint rows only) a contact whose sticking impulse leaves its disk slides
/// instead of declining the solve (`Direct::slides[i]`, [`Hold`]: its tangent impulse fixed
/// at bound · d, its normal the unknown), one whose normal would pull separates (no impulse),
/// and the solve says [`Answer::Changed`] until every sliding contact slips against its
/// impulse (to [`SLIDE_TURN`]), every sticking one is inside its disk and no separated one
/// approaches (the caller repeats it a few rounds: the active set of `Joined::friction`'s
/// start, on the banded system with the joint rows).
#[derive(Debug, Clone, Copy)]
pub(super) struct HeldJoints<'a> {
    pub axes: &'a [Axis],
    pub floor: &'a [f64],
    /// The largest change of each one's impulse (a free motor's room to its bound; none
    /// given: ∞).
    pub ceiling: &'a [f64],
    /// Each one's bias b (held at J u = −b: a free motor's −speed; none given: 0).
    pub bias: &'a [f64],
    pub modes: bool,
}

impl HeldJoints<'_> {
    /// No joint rows: the contacts' sticking solve alone.
    pub const NONE: HeldJoints<'static> = HeldJoints {
        axes: &[],
        floor: &[],
        ceiling: &[],
        bias: &[],
        modes: false,
    };
}

/// The sticking solve's system order with joint rows (`merged`: slots 3p..3p + 3 for the p-th
/// of the m active contacts, only 3p when it slides and none when it separates (`modes`),
/// 3m + j for joint row j), every unit by
/// the last body it acts on (`key` for a contact, `last` for a joint row), a joint row before
/// contacts of the same key.
fn order_with_joints(
    m: usize,
    key: impl Fn(usize) -> usize,
    modes: impl Fn(usize) -> Hold,
    (joints, last): (&[Axis], impl Fn(&Axis) -> usize),
    merged: &mut Vec<usize>,
) {
    let mut by_key: Vec<(usize, usize)> = joints.iter().map(&last).zip(0..).collect();
    by_key.sort_by_key(|&(k, _)| k);
    merged.clear();
    let (mut j, mut p) = (0, 0);
    while j < by_key.len() || p < m {
        if p == m || (j < by_key.len() && by_key[j].0 <= key(p)) {
            merged.push(3 * m + by_key[j].1);
            j += 1;
        } else {
            match modes(p) {
                Hold::Stick => merged.extend([3 * p, 3 * p + 1, 3 * p + 2]),
                Hold::Slide(_) => merged.push(3 * p),
                Hold::Off => {}
            }
            p += 1;
        }
    }
}

/// The two tries of [`sticking`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Sticking {
    /// The minimum-norm change, every pushing contact held to `uₙ = −g/dt`: the exact solution.
    Exact,
    /// The load-weighted minimum-norm change, gaps below [`RESTING_GAP`] held closed (step dt).
    Resting { dt: f64 },
}
