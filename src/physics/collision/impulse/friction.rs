//! The friction row: Coulomb's disk |λ_t| ≤ μ λₙ at each contact (stage 2). Its verbs:
//! `prepare` (the two tangent axes and the disk's bound), `warm_start`, `update` and `sweep`,
//! and `store`; no restitution (a bounce is along the normal).
//!
//! # The disk
//!
//! Two tangent impulses per contact (if μ > 0), kept in the disk `|λ_t| ≤ μ λᵢ` with λᵢ from
//! stage 1 (fixed bounds, so the feasible set is convex and fixed). The sweep updates the
//! normal impulse as in stage 1 (the normal row's `update`), then both tangent impulses at
//! once: the exact minimum of K over the contact's disk (`update`). Still exact block
//! minimisations of the same convex K over a convex set containing the current value: K
//! still only goes down, and block coordinate descent reaches the unique minimising
//! velocity whatever the order of the contacts. It gets there linearly, and slowly when
//! bodies slide on each other (a row of dominoes): the subspace steps ([`subspace`]) speed it
//! up. Stage 2 runs only when some pushing contact slides (a body at rest has nothing to do).
//!
//! # The disk update
//!
//! The exact minimisation of K over one contact's friction disk `|λ_t| ≤ bound`, the other
//! impulses fixed (a block of block coordinate descent):
//!
//! ```text
//! K_t = [[k₁, c], [c, k₂]],  c = (r×t₁)·I⁻¹(r×t₂)        tangent inverse mass (t₁ ⟂ t₂)
//! x*  = λ_t − K_t⁻¹ u_t                                  the unconstrained minimum
//! |x*| ≤ bound: x = x*;  else x(ν) = (K_t + ν𝟙)⁻¹ K_t x*  with ν ≥ 0 and |x(ν)| = bound
//! ```
//!
//! |x(ν)| decreases with ν. ν is the root of the secular equation (Moré–Sorensen)
//!
//! ```text
//! ψ(ν) = 1/|x(ν)| − 1/bound,   ψ'(ν) = q/|x|³,   q = xᵀ (K_t + ν𝟙)⁻¹ x
//! ν ← ν + (|x| − bound)/bound · |x|²/q                    (Newton: ν − ψ/ψ')
//! ```
//!
//! ψ is increasing, concave and nearly linear in ν (exactly linear when k₁ = k₂, c = 0), so
//! Newton from ν = 0 (where ψ < 0) stays below the root and converges quadratically: 2 to 5
//! iterations to round-off. It is safeguarded in the bracket `[low, high]`, `high =
//! |K_t x*|/bound` (there `|x| ≤ |K_t x*|/(σ_min + ν) < bound`): a step that would leave it
//! bisects instead. An answer left outside the disk by round-off is scaled onto its edge,
//! `x ← x·bound/|x|` (a change of a few ulps). Updating the two tangent
//! directions one at a time instead can stall on the disk's edge at a point that is not the
//! minimum, and where it stalls depends on the contact order. The step is taken only if it
//! does not raise K.
//!
//! [`subspace`]: super::subspace

use super::{axis_at, normal, Row};
use crate::physics::collision::solver_body::{Axis, SolverBody};
use crate::physics::collision::Contact;
use nalgebra::Vector3;

/// The friction disk update's Newton iteration stops when |x(ν)| is within this fraction of
/// the disk's radius (a few ulps: round-off).
const DISK_TOLERANCE: f64 = 16.0 * f64::EPSILON;

/// At most this many Newton (or bisection) steps for one disk update; Newton needs 2 to 5,
/// and 60 bisections would narrow the bracket by 2⁻⁶⁰.
const MAX_DISK_ITERATIONS: usize = 60;

/// Whether a contact pushes (after stage 1) and slides faster than `tolerance`: stage 2 runs
/// only if one does.
#[inline]
pub(super) fn sliding(
    row: &Row,
    contact: &Contact,
    motions: &[SolverBody],
    tolerance: f64,
) -> bool {
    let pushes = row.normal.lambda > 0.0;
    if !pushes {
        return false;
    }
    let (a, b) = (&motions[contact.body], &motions[contact.other]);
    let mut u = a.v + a.omega.cross(&contact.lever);
    // A static B (1/M = 0: its v and ω are 0, up to the sign of a zero, which the squared
    // norm below does not see) adds nothing: the resting body's every step skips it.
    if !b.fixed() {
        u -= b.v + b.omega.cross(&contact.lever_other);
    }
    (u - contact.normal * u.dot(&contact.normal)).norm_squared() > tolerance * tolerance
}

/// A contact's friction row: the disk's bound μ λ (λ from stage 1) into `row`, and the two
/// tangent axes.
#[inline]
pub(super) fn prepare(
    row: &mut Row,
    contact: &Contact,
    friction: f64,
    motions: &[SolverBody],
) -> [Axis; 2] {
    row.friction.bound = friction * row.normal.lambda;
    let (t1, t2) = tangents(&contact.normal);
    [axis_at(t1, contact, motions), axis_at(t2, contact, motions)]
}

/// Starts the friction sweeps from the last step's friction impulses, kept in their disks.
pub(super) fn warm_start(rows: &mut [Row], directions: &[[Axis; 2]], motions: &mut [SolverBody]) {
    for (row, directions) in rows.iter_mut().zip(directions.iter()) {
        row.normal.axis.with_inverse();
        let [t1, t2] = directions;
        let mut warm = [row.warm.dot(&t1.d), row.warm.dot(&t2.d)];
        let size = (warm[0] * warm[0] + warm[1] * warm[1]).sqrt();
        if size > row.friction.bound {
            let scale = row.friction.bound / size;
            warm = [warm[0] * scale, warm[1] * scale];
        }
        let step = [
            warm[0] - row.friction.lambda[0],
            warm[1] - row.friction.lambda[1],
        ];
        if step != [0.0; 2] {
            row.friction.lambda = warm;
            t1.apply(step[0], motions);
            t2.apply(step[1], motions);
        }
    }
}

/// Starts the normals of the friction sweeps from the last step's: each pushing normal that
/// pushed last step too takes last step's impulse (≥ 0, so still feasible). Stage 1 solved
/// the normals without friction, and where bodies lean and slide on each other (a row of
/// dominoes) friction moves their loads a long way from there, where last step's loads are
/// close to this step's; the disks' bounds stay μ λ from stage 1.
pub(super) fn warm_normals(rows: &mut [Row], motions: &mut [SolverBody]) {
    for row in rows.iter_mut() {
        let warm = row.warm.dot(&row.normal.axis.d);
        if row.normal.lambda > 0.0 && warm > 0.0 && warm != row.normal.lambda {
            row.normal.axis.apply(warm - row.normal.lambda, motions);
            row.normal.lambda = warm;
        }
    }
}

/// The exact minimisation of K over one contact's friction disk `|λ_t| ≤ bound`, the other
/// impulses fixed (module doc); returns the largest change it made to a tangent velocity
/// (m/s).
pub(super) fn update(
    row: &mut Row,
    directions: &[Axis; 2],
    bound: f64,
    motions: &mut [SolverBody],
) -> f64 {
    let [t1, t2] = directions;
    let u = [t1.velocity(motions), t2.velocity(motions)];
    let (k1, k2, c) = (t1.k, t2.k, t1.coupling(t2, motions));
    let Some((new, step)) = disk_step(u, (k1, k2, c), row.friction.lambda, bound) else {
        return 0.0;
    };
    row.friction.lambda = new;
    t1.apply(step[0], motions);
    t2.apply(step[1], motions);
    (step[0].abs() * k1 + step[1].abs() * c.abs()).max(step[1].abs() * k2 + step[0].abs() * c.abs())
}

/// The disk update's arithmetic (module doc) for tangent velocities `u`, the tangent inverse
/// mass `K_t = [[k₁, c], [c, k₂]]` and the impulses `old`: the new impulses and the step to
/// them, or None when K_t is singular or no step lowers K. (The joints' friction stage,
/// [`super::joined`], calls it with K_t taken with the joints' reaction.)
#[inline]
pub(super) fn disk_step(
    u: [f64; 2],
    (k1, k2, c): (f64, f64, f64),
    old: [f64; 2],
    bound: f64,
) -> Option<([f64; 2], [f64; 2])> {
    let det = k1 * k2 - c * c;
    if det <= 0.0 {
        return None;
    }
    // x* = λ − K⁻¹ u
    let target = [
        old[0] - (k2 * u[0] - c * u[1]) / det,
        old[1] - (k1 * u[1] - c * u[0]) / det,
    ];
    let norm = |x: [f64; 2]| (x[0] * x[0] + x[1] * x[1]).sqrt();
    let new = if norm(target) <= bound {
        target
    } else {
        // K x* once, then x(ν) = (K + ν𝟙)⁻¹ K x* on the disk's edge.
        let kx = [
            k1 * target[0] + c * target[1],
            c * target[0] + k2 * target[1],
        ];
        disk_edge(k1, k2, c, kx, bound)
    };
    let step = [new[0] - old[0], new[1] - old[1]];
    // ΔK = Δλ·u + ½ Δλᵀ K Δλ: never accept a step that raises K.
    let gain = step[0] * u[0]
        + step[1] * u[1]
        + 0.5 * (k1 * step[0] * step[0] + 2.0 * c * step[0] * step[1] + k2 * step[1] * step[1]);
    if gain >= 0.0 || gain.is_nan() {
        return None;
    }
    Some((new, step))
}

/// The point `x(ν) = (K_t + ν𝟙)⁻¹ kx` (kx = K_t x*, |x(0)| > bound) with `|x(ν)| = bound`,
/// ν ≥ 0 by safeguarded Newton on the secular equation (module doc).
#[inline(always)]
fn disk_edge(k1: f64, k2: f64, c: f64, kx: [f64; 2], bound: f64) -> [f64; 2] {
    // (K_t + ν𝟙)⁻¹ y for a 2-vector y.
    let solve = |nu: f64, y: [f64; 2]| {
        let (a, d) = (k1 + nu, k2 + nu);
        let det = a * d - c * c;
        [(d * y[0] - c * y[1]) / det, (a * y[1] - c * y[0]) / det]
    };
    let norm = |x: [f64; 2]| (x[0] * x[0] + x[1] * x[1]).sqrt();
    let (mut low, mut high) = (0.0, norm(kx) / bound);
    let mut nu = 0.0;
    let mut x = solve(nu, kx);
    for _ in 0..MAX_DISK_ITERATIONS {
        let size = norm(x);
        if size <= bound {
            // Past the root (round-off, or a bisection): the feasible end.
            high = nu;
        } else {
            low = nu;
        }
        if size - bound <= DISK_TOLERANCE * bound && size >= bound * (1.0 - DISK_TOLERANCE) {
            break;
        }
        let y = solve(nu, x);
        let q = x[0] * y[0] + x[1] * y[1];
        let newton = nu + (size - bound) / bound * size * size / q;
        nu = if newton > low && newton < high {
            newton
        } else {
            0.5 * (low + high)
        };
        x = solve(nu, kx);
    }
    let size = norm(x);
    if size > bound {
        let scale = bound / size;
        x = [x[0] * scale, x[1] * scale];
    }
    // The feasible side: |x| ≤ bound as computed (scaling can leave it an ulp over).
    while norm(x) > bound {
        x = [x[0] * (1.0 - f64::EPSILON), x[1] * (1.0 - f64::EPSILON)];
    }
    x
}

/// Block coordinate descent on the normal and friction impulses, at most `cap` sweeps;
/// returns whether they converged, how many ran, and the residual (the largest change of a
/// contact velocity the last sweep made, m/s).
pub(super) fn sweep(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    cap: u64,
) -> (bool, u64, f64) {
    let mut largest: f64 = 0.0;
    for sweep in 1..=cap {
        largest = 0.0;
        for (row, directions) in rows.iter_mut().zip(directions.iter()) {
            let bound = row.friction.bound;
            largest = largest.max(normal::update(row, motions));
            if bound == 0.0 {
                continue;
            }
            let change = update(row, directions, bound, motions);
            largest = largest.max(change);
        }
        if largest <= tolerance {
            return (true, sweep, largest);
        }
    }
    (false, cap, largest)
}

/// Adds each row's tangent impulses to its contact's impulse (after the normal row's
/// `store`); nothing when stage 2 did not run (no `directions`).
pub(super) fn store(contacts: &mut [Contact], rows: &[Row], directions: &[[Axis; 2]]) {
    for ((contact, row), [t1, t2]) in contacts.iter_mut().zip(rows.iter()).zip(directions.iter()) {
        contact.impulse += t1.d * row.friction.lambda[0] + t2.d * row.friction.lambda[1];
    }
}

/// Two unit tangents completing n to an orthonormal basis.
#[inline]
pub(in crate::physics::collision) fn tangents(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = n.cross(&helper).normalize();
    (t1, n.cross(&t1))
}
