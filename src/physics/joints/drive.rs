//! Joint limits and motors: rows with bounds, solved at the end of each step together with the
//! joints' equality rows (so those stay held), as impulses — like contacts.
//!
//! A hinge's or slider's coordinate q (the angle θ, rad, or the travel s, m: `rows::coordinate`)
//! has the row J_q with J_q u = q̇. Its limit [lo, hi] is two one-sided stops, and its motor one
//! row whose impulse is bounded:
//!
//! ```text
//! lower stop   C = q − lo ≥ 0,  row  J_q        λ ≥ 0
//! upper stop   C = hi − q ≥ 0,  row −J_q        λ ≥ 0
//! motor        J_q u⁺ = speed                   |λ| ≤ max · dt     (max: N or N·m)
//! joint rows   J_j u⁺ = 0                       λ free
//! ```
//!
//! After the step (and the joints' projection), two passes over these rows, in the metric of
//! the masses (W = diag(1/m, I⁻¹_world), K = J W Jᵀ), each a bounded mixed complementarity
//! problem — find λ with lo ≤ λ ≤ hi, w = K λ + r: w_i = 0 where lo < λ_i < hi, w_i ≥ 0 at
//! lo, w_i ≤ 0 at hi — solved exactly by an active set (`solve::multipliers` on the free rows,
//! the others held at a bound):
//!
//! ```text
//! positions   r_stop = C, r_joint = C (projection) or 0;  δ = W Jᵀ λ (Newton, to |C| < 1e-12):
//!             removes any overshoot past a stop, the joints kept
//! velocities  r_stop = J u⁻ + e·min(J u⁻, 0) on every stop at C ≤ 1e-9 (Newton's restitution:
//!             J u⁺ ≥ −e J u⁻), r_motor = J u⁻ − speed, r_joint = J u⁻;
//!             ΔP = J_linᵀ λ, ΔL = J_angᵀ λ
//! ```
//!
//! The stops within `TOUCHING` of their limits are also one-sided rows of the contacts'
//! exact solve (`collision::impulse::joined`, in an impact) and of the contact pass after it
//! (`contact::hold`): what a contact does to a body on its stop is answered by the stop there
//! (`touching_stops`, [`book_stops`]).
//!
//! The motors are rows of the contacts' exact solve too, with what this pass left of their
//! bounds (`motor_rows`): where a contact touches a motored body's cluster, the motor's
//! push and the contact's blow are one problem (`collision::impulse::joined`); its force
//! there is added to [`Drive::motor`] and its work to the ledger's motor row by the world.
//!
//! e is the scene's contact restitution (0 without a contact model), and 0 for a slow approach,
//! |J u⁻| < 3 |J u⁻ − J u₀| (u₀ the step's start: the approach is less than three steps of
//! what the loads give, a body resting on its stop) — as contacts do below their bounce speed.
//!
//! Energy, exactly: u⁺ = u⁻ + W Jᵀ λ changes the kinetic energy by
//! ΔK = λᵀ J (u⁻ + u⁺)/2 = Σ_rows λ_i (J_i u⁻ + J_i u⁺)/2. The motor rows' terms are the
//! motor's work (the ledger's `motor` row); a stop's term is λ (1 − e) J u⁻/2 ≤ 0 when it
//! strikes and is booked with the contacts, with what the position pass changed; the joint
//! rows' terms (≈ 0: J u⁻ = 0 after the projection) with the joints' correction.
//!
//! The energy clamp: a stop struck within the step put back on its limit by the position pass
//! keeps the work the loads did past it (m g δh for a weight); when the stops' total
//! (position change + their ΔK shares) would be a gain, their restitution is lowered to
//! e'² = e² − 2 excess / Σ m_e r⁻² and the velocities solved again, so a stop never makes
//! energy at e ≤ 1 (a bob on a hinge bouncing off a 60° stop at e = 1 gives back 1e-11 J).

use super::contact::{along, apply};
use super::projection::{joint_rows, shift};
use super::rows::{coordinate, rate, Pose, Row};
use super::solve::{multipliers, Inverse, Solver};
use super::{Correction, Links};
use crate::physics::body::Body;
use crate::physics::derive::derive;
use crate::physics::effects::Effects;
use crate::physics::effects::Loads;
use crate::physics::energy::energy;
use crate::physics::state::State;
use nalgebra::Vector3;

/// A stop within this of its limit is touching (m or rad).
const TOUCHING: f64 = 1e-9;

/// Position violations below this are round-off (m or rad).
const POSITION_TOLERANCE: f64 = 1e-12;

/// Velocity violations below this are round-off (m/s or rad/s).
const VELOCITY_TOLERANCE: f64 = 1e-12;

/// Restitution applies only when the approach is at least this many steps of what the loads
/// give along the row.
const BOUNCE_STEPS: f64 = 3.0;

/// What a row is, for the booking (its bounds are the row's own: `Row::equality`,
/// `Row::stop`, `Row::motor`).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// A joint's equality row: λ ∈ (−∞, ∞).
    Joint,
    /// A stop: λ ∈ [0, ∞); +1 the lower stop (pushes q up), −1 the upper one.
    Stop(f64),
    /// A motor: λ ∈ ±(its force × dt), aiming at J u = its speed (bias −speed).
    Motor,
}

/// Where a row's multiplier is in the active set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Free,
    Low,
    High,
}

/// Reused buffers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buffers {
    poses: Vec<Pose>,
    inverse: Vec<Inverse>,
    rows: Vec<Row>,
    kinds: Vec<Kind>,
    /// Per joint: its coordinate's rate at the step's start (the bounce test).
    start_rates: Vec<f64>,
    r: Vec<f64>,
    /// The velocity pass: per row J u⁻ and its restitution.
    before: Vec<f64>,
    restitution: Vec<f64>,
    mu: Vec<f64>,
    sides: Vec<Side>,
    subset: Vec<Row>,
    rhs: Vec<f64>,
    delta: Vec<(Vector3<f64>, Vector3<f64>)>,
    solver: Solver,
}

/// What the pass did to the energy, J.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Driven {
    /// The motors' work: Σ λ (J u⁻ + J u⁺)/2 over the motor rows.
    pub motor_work: f64,
    /// The stops: their rows' share of ΔK and the position pass's change of the energy.
    pub stops: f64,
    /// The joint rows' share of ΔK (numerical).
    pub joints: f64,
}

/// The scene's pieces the pass reads.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    pub links: &'a Links,
    pub bodies: &'a [Body],
    pub effects: &'a Effects,
    /// The contact model's restitution (0 without one).
    pub restitution: f64,
    pub dt: f64,
}

/// What each driven joint applied over the step, averaged (impulse / dt): along its axis, on
/// its body A (+: towards larger q), N or N·m.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Drive {
    /// The stops' force or torque.
    pub limit: f64,
    /// The motor's force or torque.
    pub motor: f64,
}

/// Runs both passes on `states` (`start`: the states at the step's start). Adds each joint's
/// reaction of the pass to `loads` (impulse / dt) and writes `drives`.
pub fn drive(
    scene: &Scene,
    states: &mut [State],
    start: &[State],
    loads: &mut [Loads],
    drives: &mut Vec<Drive>,
    b: &mut Buffers,
) -> Driven {
    let links = scene.links;
    drives.clear();
    drives.resize(links.joints.len(), Drive::default());
    let mut out = Driven::default();
    if !links.driven() {
        return out;
    }
    // The coordinates' rates at the step's start.
    poses_of(scene.bodies, start, b);
    b.start_rates.clear();
    for (i, joint) in links.joints.iter().enumerate() {
        let pb = joint.b.map_or(Pose::WORLD, |j| b.poses[j]);
        let rate = match coordinate(joint, i, &b.poses[joint.a], &pb) {
            Some((row, _)) if joint.limits.is_some() => rate(&row, &b.poses[joint.a], &pb),
            _ => 0.0,
        };
        b.start_rates.push(rate);
    }
    let moved = positions(scene, states, b);
    out.stops += moved;
    // Velocities, at the last build's positions.
    build(scene, states, TOUCHING, true, b);
    b.before.clear();
    b.restitution.clear();
    for (row, kind) in b.rows.iter().zip(&b.kinds) {
        let pb = row.b().map_or(Pose::WORLD, |j| b.poses[j]);
        let rate = rate(row, &b.poses[row.a()], &pb);
        b.before.push(rate);
        b.restitution.push(match *kind {
            Kind::Stop(sign) => {
                let from_loads = rate - sign * b.start_rates[row.owner];
                if -rate > BOUNCE_STEPS * from_loads.abs() {
                    scene.restitution
                } else {
                    0.0
                }
            }
            _ => 0.0,
        });
    }
    let mut shares = velocities(b);
    // The energy clamp: a stop struck within the step was met before the step's end, and the
    // position pass put the body back on it without taking the work the loads did past it
    // (m g δh for a weight). If the stops would then give energy, their restitution is
    // lowered so that they give none: a stop's share is −½ m_e r⁻² (1 − e²) (m_e its
    // effective mass, r⁻ = J u⁻), and λ = m_e (1 + e)(−r⁻), so e'² = e² − 2 excess / Σ m_e r⁻²
    // with Σ m_e r⁻² = Σ λ (−r⁻)/(1 + e) over the stops that bounce.
    let excess = moved + shares.stops;
    if excess > 0.0 {
        let mut struck = 0.0;
        for (i, kind) in b.kinds.iter().enumerate() {
            if matches!(kind, Kind::Stop(_)) && b.restitution[i] > 0.0 && b.mu[i] > 0.0 {
                struck += b.mu[i] * (-b.before[i]) / (1.0 + b.restitution[i]);
            }
        }
        if struck > 0.0 {
            for (i, kind) in b.kinds.iter().enumerate() {
                if matches!(kind, Kind::Stop(_)) && b.restitution[i] > 0.0 {
                    let e = b.restitution[i];
                    b.restitution[i] = (e * e - 2.0 * excess / struck).max(0.0).sqrt();
                }
            }
            shares = velocities(b);
        }
    }
    let dt = scene.dt;
    for (i, (row, &mu)) in b.rows.iter().zip(&b.mu).enumerate() {
        if mu == 0.0 {
            continue;
        }
        apply(row, mu, states);
        loads[row.owner].force += row.lin_a() * (mu / dt);
        loads[row.owner].torque += row.ang_a() * (mu / dt);
        match b.kinds[i] {
            Kind::Joint => {}
            Kind::Stop(sign) => drives[row.owner].limit += sign * mu / dt,
            Kind::Motor => drives[row.owner].motor += mu / dt,
        }
    }
    out.stops += shares.stops;
    out.motor_work += shares.motor_work;
    out.joints += shares.joints;
    out
}

/// The velocity pass's problem at the rows built (`b.before` = J u⁻, `b.restitution` per
/// row): solves it for `b.mu` and returns each kind's share of ΔK, λ (J u⁻ + J u⁺)/2 with
/// J u⁺ = J u⁻ + J δ (`stops`: the stops' rows only).
fn velocities(b: &mut Buffers) -> Driven {
    b.r.clear();
    for (i, (kind, row)) in b.kinds.iter().zip(&b.rows).enumerate() {
        let rate = b.before[i];
        b.r.push(match *kind {
            Kind::Joint => rate,
            Kind::Stop(_) => rate + b.restitution[i] * rate.min(0.0),
            Kind::Motor => rate + row.bias,
        });
    }
    bounded(VELOCITY_TOLERANCE, b);
    let mut out = Driven::default();
    for (i, (row, &mu)) in b.rows.iter().zip(&b.mu).enumerate() {
        if mu == 0.0 {
            continue;
        }
        let share = mu * (b.before[i] + 0.5 * along(row, &b.delta));
        match b.kinds[i] {
            Kind::Joint => out.joints += share,
            Kind::Stop(_) => out.stops += share,
            Kind::Motor => out.motor_work += share,
        }
    }
    out
}

/// Each body's pose (with velocities) and inverse mass at `states`.
fn poses_of(bodies: &[Body], states: &[State], b: &mut Buffers) {
    b.poses.clear();
    b.inverse.clear();
    for (body, state) in bodies.iter().zip(states) {
        let k = derive(body, state);
        b.poses.push(Pose {
            x: state.position,
            r: k.rotation,
            v: k.velocity,
            w: k.angular_velocity,
        });
        b.inverse.push(Inverse {
            mass: body.inv_mass,
            inertia: k.inv_inertia_world,
        });
    }
}

/// The joints' rows at `states`, then every stop within `touching` of its limit (its C in the
/// row), then (`motors`) every motor row.
fn build(scene: &Scene, states: &[State], touching: f64, motors: bool, b: &mut Buffers) {
    joint_rows(
        scene.links,
        scene.bodies,
        states,
        (&mut b.poses, &mut b.inverse, &mut b.rows),
    );
    b.kinds.clear();
    b.kinds.resize(b.rows.len(), Kind::Joint);
    for (i, joint) in scene.links.joints.iter().enumerate() {
        if !joint.driven() {
            continue;
        }
        let pb = joint.b.map_or(Pose::WORLD, |j| b.poses[j]);
        let Some((row, q)) = coordinate(joint, i, &b.poses[joint.a], &pb) else {
            continue;
        };
        if let Some([lo, hi]) = joint.limits {
            for (sign, c) in [(1.0, q - lo), (-1.0, hi - q)] {
                if c <= touching {
                    b.rows.push(Row::stop(&row, sign, c));
                    b.kinds.push(Kind::Stop(sign));
                }
            }
        }
        if let (Some(motor), true) = (joint.motor, motors) {
            b.rows
                .push(Row::motor(&row, motor.speed, motor.max * scene.dt));
            b.kinds.push(Kind::Motor);
        }
    }
}

/// Appends each limit's stop within [`TOUCHING`] of its limit at `poses` (the bodies' poses,
/// `projection::joint_rows`) to `rows`: the one-sided rows (λ ∈ [0, ∞)) the contacts' exact
/// solve takes with the joints' equality rows (`collision::impulse::joined`).
pub(super) fn touching_stops(links: &Links, poses: &[Pose], rows: &mut Vec<Row>) {
    for (i, joint) in links.joints.iter().enumerate() {
        let Some([lo, hi]) = joint.limits else {
            continue;
        };
        let pb = joint.b.map_or(Pose::WORLD, |j| poses[j]);
        let Some((row, q)) = coordinate(joint, i, &poses[joint.a], &pb) else {
            continue;
        };
        for (sign, c) in [(1.0, q - lo), (-1.0, hi - q)] {
            if c <= TOUCHING {
                rows.push(Row::stop(&row, sign, c));
            }
        }
    }
}

/// Appends each motor's row at `poses` to `rows`: J_q u = speed with its impulse bounded by
/// [−max·dt − given, max·dt − given] (`given[j]`: the impulse the drive pass gave joint j's
/// motor this step), so that what the drive pass gave and what the contacts' exact solve
/// adds (`collision::impulse::joined`) stay within ±max·dt together.
pub(super) fn motor_rows(
    links: &Links,
    poses: &[Pose],
    (given, dt): (&[f64], f64),
    rows: &mut Vec<Row>,
) {
    for (i, joint) in links.joints.iter().enumerate() {
        let Some(motor) = joint.motor else {
            continue;
        };
        let pb = joint.b.map_or(Pose::WORLD, |j| poses[j]);
        let Some((row, _)) = coordinate(joint, i, &poses[joint.a], &pb) else {
            continue;
        };
        // Finite, so that the row stays a motor's (`joined::Kind`).
        let bound = (motor.max * dt).min(f64::MAX);
        let given = given.get(i).copied().unwrap_or(0.0);
        rows.push(Row {
            lo: -bound - given,
            hi: bound - given,
            ..Row::motor(&row, motor.speed, bound)
        });
    }
}

/// Adds the stops' impulses the contacts' exact solve gave (`stops[j]` ≥ 0 per joint,
/// `collision::impulse::joined`) to `drives` as forces over the step, signed as
/// [`Drive::limit`] is (+: the lower stop, nearer its limit at `states`).
pub fn book_stops(links: &Links, states: &[State], stops: &[f64], drives: &mut [Drive], dt: f64) {
    for ((joint, &impulse), drive) in links.joints.iter().zip(stops).zip(drives) {
        if impulse == 0.0 {
            continue;
        }
        let (Some([lo, hi]), Some(q)) = (joint.limits, joint.coordinate(states)) else {
            continue;
        };
        let sign = if q - lo <= hi - q { 1.0 } else { -1.0 };
        drive.limit += sign * impulse / dt;
    }
}

/// The position pass: removes any overshoot past a stop with the joints held (Newton, at most
/// 10 passes). Returns the change of the energy (kinetic, gravity, springs) it made, J.
fn positions(scene: &Scene, states: &mut [State], b: &mut Buffers) -> f64 {
    let project = scene.links.correction == Correction::Projection;
    let mut before = None;
    for _ in 0..10 {
        build(scene, states, 0.0, false, b);
        let stops = b.kinds.iter().any(|k| matches!(k, Kind::Stop(_)));
        let violated = b.rows.iter().zip(&b.kinds).any(|(row, kind)| match kind {
            Kind::Stop(_) => row.error < -POSITION_TOLERANCE,
            _ => project && row.error.abs() > POSITION_TOLERANCE,
        });
        if !stops || !violated {
            break;
        }
        before.get_or_insert_with(|| total(scene, states));
        b.r.clear();
        for (row, kind) in b.rows.iter().zip(&b.kinds) {
            b.r.push(match kind {
                Kind::Stop(_) => row.error,
                _ if project => row.error,
                _ => 0.0,
            });
        }
        bounded(POSITION_TOLERANCE, b);
        for (row, &mu) in b.rows.iter().zip(&b.mu) {
            if mu != 0.0 {
                shift(states, &b.inverse, row.a(), &row.lin_a(), &row.ang_a(), mu);
                if let Some(j) = row.b() {
                    shift(states, &b.inverse, j, &row.lin_b(), &row.ang_b(), mu);
                }
            }
        }
    }
    before.map_or(0.0, |e| total(scene, states) - e)
}

/// The scene's energy at `states`: the bodies' (kinetic and gravity) and the springs', J.
fn total(scene: &Scene, states: &[State]) -> f64 {
    let bodies: f64 = scene
        .bodies
        .iter()
        .zip(states)
        .map(|(body, s)| energy(body, scene.effects, s).total)
        .sum();
    bodies + scene.links.potential(states)
}

/// Solves the bounded mixed problem of the module doc for `b.mu` (rows `b.rows`, offsets
/// `b.r`, bounds [lo, hi] each row's own); leaves W Jᵀ μ per body in `b.delta`. Returns the rounds it took.
///
/// Active set: the free rows solve `K_FF λ_F = −(r_F + K_FB λ_B)` with the others held at a
/// bound; the free row furthest past a bound is held at it, else the held row whose w has the
/// wrong sign (the most) is freed; until neither happens (or 4·rows + 4 rounds).
fn bounded(tolerance: f64, b: &mut Buffers) -> usize {
    let n = b.rows.len();
    b.sides.clear();
    b.sides.extend(b.rows.iter().zip(&b.r).map(|(row, &r)| {
        if row.lo == 0.0 && r >= -tolerance {
            Side::Low
        } else {
            Side::Free
        }
    }));
    let most = 4 * n + 4;
    let mut rounds = 0;
    loop {
        rounds += 1;
        // The held rows' multipliers and their change W Jᵀ λ_B.
        b.mu.clear();
        b.mu.extend(b.sides.iter().zip(&b.rows).map(|(side, row)| match side {
            Side::Free => 0.0,
            Side::Low => row.lo,
            Side::High => row.hi,
        }));
        spread(b);
        b.subset.clear();
        b.rhs.clear();
        for i in (0..n).filter(|&i| b.sides[i] == Side::Free) {
            b.subset.push(b.rows[i]);
            b.rhs.push(-(b.r[i] + along(&b.rows[i], &b.delta)));
        }
        if !b.subset.is_empty() {
            multipliers(&b.subset, &b.inverse, &mut b.rhs, &mut b.solver);
        }
        let mut next = b.rhs.iter();
        for i in 0..n {
            if b.sides[i] == Side::Free {
                b.mu[i] = *next.next().unwrap_or(&0.0);
            }
        }
        spread(b);
        if rounds >= most {
            return rounds;
        }
        // A free row past a bound is held there (the furthest first).
        let past = (0..n)
            .filter(|&i| b.sides[i] == Side::Free)
            .map(|i| {
                let row = &b.rows[i];
                (i, (row.lo - b.mu[i]).max(b.mu[i] - row.hi))
            })
            .filter(|&(_, excess)| excess > 0.0)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((i, _)) = past {
            b.sides[i] = if b.mu[i] < b.rows[i].lo {
                Side::Low
            } else {
                Side::High
            };
            continue;
        }
        // A held row whose w points the wrong way is freed (the most violated first).
        let wrong = (0..n)
            .filter_map(|i| {
                let w = along(&b.rows[i], &b.delta) + b.r[i];
                match b.sides[i] {
                    Side::Low if w < -tolerance => Some((i, -w)),
                    Side::High if w > tolerance => Some((i, w)),
                    _ => None,
                }
            })
            .max_by(|x, y| x.1.total_cmp(&y.1));
        match wrong {
            Some((i, _)) => b.sides[i] = Side::Free,
            None => return rounds,
        }
    }
}

/// δ = W Jᵀ μ per body, into `b.delta`.
fn spread(b: &mut Buffers) {
    b.delta.clear();
    b.delta
        .resize(b.inverse.len(), (Vector3::zeros(), Vector3::zeros()));
    for (row, &mu) in b.rows.iter().zip(&b.mu) {
        if mu == 0.0 {
            continue;
        }
        let mut add = |i: usize, lin: &Vector3<f64>, ang: &Vector3<f64>| {
            let inv = &b.inverse[i];
            b.delta[i].0 += lin * (mu * inv.mass);
            b.delta[i].1 += inv.inertia * (ang * mu);
        };
        add(row.a(), &row.lin_a(), &row.ang_a());
        if let Some(j) = row.b() {
            add(j, &row.lin_b(), &row.ang_b());
        }
    }
}
