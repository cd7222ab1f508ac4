//! The normal contact row: non-penetration, λ ≥ 0, with a speculative gap's bias. Its verbs:
//! `prepare` (a [`Contact`] into a row), `warm_start`, `update` and `sweep` (stage 1, and
//! the normal half of every friction sweep), `restitution` (stage 3) and `store`.
//!
//! # One contact
//!
//! A point at lever arm r from the barycenter, contact normal n (out of the obstacle). An
//! impulse j n there changes the momenta by `ΔP = j n`, `ΔL = r × (j n)`, so the normal velocity
//! of the point `u_n = (v + ω × r)·n` changes by `j·k` with
//!
//! ```text
//! k = 1/M + n·((I⁻¹(r×n)) × r) = 1/M + (r×n)·I⁻¹(r×n)       (the denominator, 1/kg)
//! j = −(1 + e) u_n / k                                      (Newton's law for one contact)
//! ```
//!
//! # Two bodies
//!
//! Between bodies A and B (n from B to A) the impulse is j n on A at r_A and −j n on B at r_B:
//! equal and opposite, so the total linear momentum `P_A + P_B` is unchanged, and the total
//! angular momentum about any point too (`r_A × jn + x_A × jn − r_B × jn − x_B × jn = 0` since
//! both act at the same point). The relative normal velocity
//! `u_n = (v_A + ω_A × r_A − v_B − ω_B × r_B)·n` changes by `j·k` with
//!
//! ```text
//! k = 1/M_A + (r_A×n)·I_A⁻¹(r_A×n) + 1/M_B + (r_B×n)·I_B⁻¹(r_B×n)
//! ```
//!
//! and every stage is written for such two-sided rows (an obstacle is a B of infinite
//! mass). A resting body, a stack, a body on a body: one solver.
//!
//! # Solve: projected Gauss–Seidel (stage 1)
//!
//! Inelastic normal impulses λᵢ ≥ 0 by projected Gauss–Seidel (sequential impulses with
//! *accumulated* clamping): sweep the contacts, set each one's normal velocity to zero,
//! `λᵢ ← max(0, λᵢ − u_nᵢ / kᵢ)`, and sweep again until no impulse changes any velocity by
//! more than a tolerance. The solution (the velocities) does not depend on the order.
//! The kinetic energy after a set of impulses Λ is a convex quadratic in Λ,
//! `K(Λ) = K₀ + Λ·u₀ + ½ Λᵀ A Λ` (A the contact-space inverse mass, positive semi-definite),
//! and each update is the exact minimisation of K along one coordinate over an interval
//! that contains the current value: K can only go down.
//!
//! A speculative contact (gap g ≥ 0, the condition `u_n ≥ −g/dt`: see the overview, `impulse`)
//! has the bias g/dt: its update is `λ ← max(0, λ − (u_n + g/dt)/k)`. That minimises
//! `K(Λ) + Σ λᵢ gᵢ/dt ≥ K(Λ)` (λ, g ≥ 0), which starts at K₀, so K still never rises; it never
//! bounces (it is below the bounce speed) and is never pushed out (it is not inside). Gaps up
//! to [`GAP_ROUND_OFF`] are taken as touching (no bias).
//!
//! # Restitution (stage 3)
//!
//! Poisson's: the restitution impulse is e times the compression impulse, the frictionless λᵢ
//! of stage 1 — unique, unlike the stage-2 λᵢ when several contacts share a load, so the
//! bounce cannot depend on the vertex order — only at contacts that approached faster than
//! [`BOUNCE_STEPS`]·|g|·dt (slower ones are resting contact: they do not bounce, which is what
//! keeps a body lying on the ground from jittering). With one frictionless contact that is
//! Newton's `j = −(1+e) u_n/k` and loses energy for e ≤ 1; with friction or several contacts
//! it can *gain* energy. Along the line `Λ_inelastic + s Λ_restitution` the energy is a
//! quadratic `K(s) = a s² + b s + c`, with `c = K(Λ_inelastic) ≤ K₀`; if `K(1) > K₀` the
//! restitution part is scaled to the largest `s = (−b + √(b² − 4a(c − K₀))) / 2a` with
//! `K(s) = K₀`.
//!
//! The push-out (`position`) lifts the body against gravity by Δx: its work `ΔV = −M g·Δx` is
//! paid from the bounce, so the clamp's target is `K₀ − max(0, ΔV)`, not K₀. Otherwise an
//! elastic bounce keeps K while the push-out adds M g d per bounce (d the depth reached within
//! the step): a body bouncing with e = 1 would gain energy at every bounce.
//!
//! # Store
//!
//! Each contact gets its normal velocity before the response, its k (the denominator) and its
//! normal impulse `n (λ + λ_restitution)`; the friction row adds its tangent impulses.
//!
//! [`BOUNCE_STEPS`]: super::BOUNCE_STEPS

use super::joined::Joined;
use super::{axis_at, Row};
use crate::physics::collision::solver_body::SolverBody;
use crate::physics::constraints;
use crate::physics::collision::warm::WarmCache;
use crate::physics::collision::Contact;
use nalgebra::Vector3;

/// Gaps up to this are round-off of touching, m: positions of order 1 m carry errors of
/// about 1e-14 m after a few operations, so the corners of a face lying flat on another come
/// out ±1e-14 m apart, and the sweeps' tolerance ([`TOLERANCE`], 1e-10 m/s) lets a body at rest
/// creep by up to 1e-13 m a step: after a few seconds a face's corners are up to a nanometre
/// apart. Their bias (gap/dt) would make the four rows of a face manifold — which constrain
/// three motions — inconsistent, and the direct solve's minimum-norm answer would blow that
/// up by 1/ε into impulses of ±100 N·s of opposite signs; a pyramid of 20 rows whose corners
/// came 1e-11 m apart declined its direct solve and spent seconds a step in the sweeps.
/// Treated as touching (no bias), the rows stay consistent. A nanometre is far below anything
/// a panel shows (0.1 µm).
///
/// [`TOLERANCE`]: super::TOLERANCE
pub const GAP_ROUND_OFF: f64 = 1e-9;

/// The row of a contact (point, depth, normal and levers filled in): its normal axis, its
/// approach, its bias (gap/dt, a speculative contact) and the last step's impulse there.
/// (Inlined into the caller's `extend`, the row is written in place: returned through the
/// stack, its 280 bytes cost a `memcpy` each.)
#[inline(always)]
pub(super) fn prepare(c: &Contact, previous: &WarmCache, dt: f64, motions: &[SolverBody]) -> Row {
    let normal = axis_at(c.normal, c, motions);
    let warm = previous.find(c);
    let gap = (-c.depth - GAP_ROUND_OFF).max(0.0);
    Row {
        normal: constraints::Row::contact(normal, -(gap / dt)),
        friction: constraints::Friction::default(),
        compression: 0.0,
        lambda_restitution: 0.0,
        approach: normal.velocity(motions),
        warm: warm.unwrap_or_else(Vector3::zeros),
    }
}

/// Starts the normal sweeps from the last step's normal impulses (kept ≥ 0).
pub(super) fn warm_start(rows: &mut [Row], motions: &mut [SolverBody]) {
    for row in rows.iter_mut() {
        row.normal.axis.with_inverse();
        let warm = row.warm.dot(&row.normal.axis.d).max(0.0);
        if warm > 0.0 {
            row.normal.lambda = warm;
            row.normal.axis.apply(warm, motions);
        }
    }
}

/// Sets every normal impulse, whatever it is, to the last step's (kept ≥ 0): the friction
/// stage's trial sweeps start from last step's normal impulses as well as its friction.
pub(super) fn warm_start_again(rows: &mut [Row], motions: &mut [SolverBody]) {
    for row in rows.iter_mut() {
        let warm = row.warm.dot(&row.normal.axis.d).max(0.0);
        if warm != row.normal.lambda {
            row.normal.axis.apply(warm - row.normal.lambda, motions);
            row.normal.lambda = warm;
        }
    }
}

/// One projected Gauss–Seidel update of a contact's normal impulse; returns the change it made
/// to the contact's normal velocity (m/s).
#[inline]
pub(super) fn update(row: &mut Row, motions: &mut [SolverBody]) -> f64 {
    let normal = &mut row.normal;
    let dir = &normal.axis;
    // λ ∈ [lo, ∞): a contact's normal row has no upper bound (`constraints::Row::contact`).
    let new = (normal.lambda - (dir.velocity(motions) + normal.bias) * dir.inv_k).max(normal.lo);
    let change = new - normal.lambda;
    if change == 0.0 {
        return 0.0;
    }
    normal.lambda = new;
    dir.apply(change, motions);
    change.abs() * dir.k
}

/// Projected Gauss–Seidel on the normal impulses, at most `cap` sweeps; returns whether they
/// converged, how many ran, and the residual: the largest change of a contact velocity the
/// last sweep made (m/s; 0 when none ran).
pub(super) fn sweep(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    tolerance: f64,
    cap: u64,
) -> (bool, u64, f64) {
    let mut largest: f64 = 0.0;
    for sweep in 1..=cap {
        largest = 0.0;
        for row in rows.iter_mut() {
            largest = largest.max(update(row, motions));
        }
        if largest <= tolerance {
            return (true, sweep, largest);
        }
    }
    (false, cap, largest)
}

/// Whether a row bounces: it approached faster than the bounce speed and pushed.
fn bounces(row: &Row, bounce_speed: f64) -> bool {
    row.approach < -bounce_speed && row.compression > 0.0
}

/// What stage 3 works to: the coefficient e, the speed below which nothing bounces, and the
/// kinetic energy the velocities may keep (K₀ less the push-out's work against gravity).
#[derive(Debug, Clone, Copy)]
pub(super) struct Bounce {
    pub restitution: f64,
    pub bounce_speed: f64,
    pub kinetic_allowed: f64,
}

/// Stage 3: Poisson restitution e λ where the approach was fast, scaled so that the kinetic
/// energy stays within `kinetic_allowed`. `change` is a buffer (the restitution impulses'
/// changes to each body: Δv, ΔL, Δω); `bounced` is set for each body a restitution impulse
/// acted on. With `joints` ([`super::joined`]) the joints' reaction to the impulses joins
/// the change before the clamp (their impulses left in `joints.lambda`, unscaled). Returns
/// the clamp's scale when something bounced. Inlined: most steps (a body at rest) bounce
/// nothing and return at the test.
#[inline]
pub(super) fn restitution(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    bounce: Bounce,
    change: &mut Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    bounced: &mut [bool],
    joints: Option<&mut Joined>,
) -> Option<f64> {
    let (e, speed) = (bounce.restitution, bounce.bounce_speed);
    if !(e > 0.0 && rows.iter().any(|r| bounces(r, speed))) {
        return None;
    }
    bounce_rows(rows, motions, bounce, change, bounced, joints)
}

/// [`restitution`] once some row bounces.
fn bounce_rows(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    bounce: Bounce,
    change: &mut Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    bounced: &mut [bool],
    joints: Option<&mut Joined>,
) -> Option<f64> {
    let Bounce {
        restitution,
        bounce_speed,
        kinetic_allowed,
    } = bounce;
    // The restitution impulses' changes to each body: Δv, ΔL, Δω.
    change.clear();
    change.resize(
        motions.len(),
        (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
    );
    for row in rows.iter_mut() {
        if bounces(row, bounce_speed) {
            let j = restitution * row.compression;
            row.lambda_restitution = j;
            for (end, sign) in row.normal.axis.ends() {
                let m = &motions[end.body];
                let c = &mut change[end.body];
                c.0 += row.normal.axis.d * (sign * j * m.inv_mass);
                c.1 += end.rd * j;
                c.2 += end.w * j;
            }
        }
    }
    if let Some(joints) = joints {
        joints.react_bounded(change, motions);
    }
    // K(s) = a s² + b s + c along Λ_inelastic + s Λ_restitution.
    let (mut a, mut b) = (0.0, 0.0);
    for (m, (dv, dl, domega)) in motions.iter().zip(change.iter()) {
        if m.inv_mass == 0.0 {
            continue; // a fixed body takes no impulse
        }
        a += 0.5 * (dv.norm_squared() / m.inv_mass + domega.dot(dl));
        b += dv.dot(&m.v) / m.inv_mass + m.omega.dot(dl);
    }
    let c: f64 = motions.iter().map(SolverBody::kinetic).sum();
    let scale = if a + b + c <= kinetic_allowed || a <= 0.0 {
        1.0
    } else {
        let slack = (kinetic_allowed - c).max(0.0);
        ((-b + (b * b + 4.0 * a * slack).sqrt()) / (2.0 * a)).clamp(0.0, 1.0)
    };
    for ((m, bounce), (dv, dl, domega)) in motions
        .iter_mut()
        .zip(bounced.iter_mut())
        .zip(change.iter())
    {
        if *dl != Vector3::zeros() || *dv != Vector3::zeros() {
            m.v += dv * scale;
            m.l += dl * scale;
            m.omega += domega * scale;
            *bounce = true;
        }
    }
    for row in rows.iter_mut() {
        row.lambda_restitution *= scale;
    }
    Some(scale)
}

/// Writes each row back into its contact: the normal velocity before the response, the
/// denominator k, and the normal impulse (compression and restitution). The friction row's
/// `store` adds the tangent impulses after it.
pub(super) fn store(contacts: &mut [Contact], rows: &[Row]) {
    for (contact, row) in contacts.iter_mut().zip(rows.iter()) {
        contact.normal_velocity = row.approach;
        contact.denominator = row.normal.axis.k;
        contact.impulse = row.normal.axis.d * (row.normal.lambda + row.lambda_restitution);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::{Against, Feature};
    use nalgebra::Matrix3;

    /// A contact's normal row is the layer's row: λ ∈ [0, ∞), b = gap/dt. A 2 kg block (1/M =
    /// 0.5, no rotation) 4 mm above the ground (a speculative contact), dt = 10 ms: falling at
    /// 1 m/s, the sweep lets it close its gap within the step and no more, u = −b ≈ −0.4 m/s,
    /// λ = (u − u₀)/k ≈ 1.2 N·s; rising at 1 m/s it takes nothing (λ stays at lo = 0).
    #[test]
    fn a_speculative_contact_is_a_layer_row_that_closes_its_gap_and_no_more() {
        let (dt, gap) = (0.01, 0.004);
        let mut contact = Contact::new(
            0,
            Against::Obstacle(0),
            Feature::Vertex(0),
            Vector3::zeros(),
            -gap,
            Vector3::y(),
        );
        contact.other = 1;
        let run = |vy: f64| {
            let mut motions = vec![
                SolverBody::new(Vector3::new(0.0, vy, 0.0), Vector3::zeros(), 0.5, Matrix3::zeros()),
                SolverBody::fixed_thing(),
            ];
            let mut rows = [prepare(&contact, &WarmCache::default(), dt, &motions)];
            warm_start(&mut rows, &mut motions);
            assert!(sweep(&mut rows, &mut motions, 1e-12, 10).0);
            (rows[0], motions[0].v.y)
        };
        let (row, v) = run(-1.0);
        let bias = (gap - GAP_ROUND_OFF) / dt;
        assert_eq!(
            (row.normal.lo, row.normal.hi, row.normal.bias, row.approach),
            (0.0, f64::INFINITY, bias, -1.0)
        );
        assert!((v + bias).abs() < 1e-12, "{v}");
        assert!((row.normal.lambda - (1.0 - bias) / 0.5).abs() < 1e-12);
        let (row, v) = run(1.0);
        assert_eq!((row.normal.lambda, v), (0.0, 1.0));
    }
}
