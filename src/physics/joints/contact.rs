//! Joints that hold while contacts act: after the contact response, one small mixed
//! complementarity problem over the joint rows (bilateral, = 0) and the contact normals
//! (unilateral, ≥, pushing only), at the position level and then at the velocity level.
//!
//! The contact response (`collision::impulse`, `soft_step`) moves each touched body on its
//! own: its impulses stop the links that touch, its push-out translates them. Alone it would
//! pull a chain's touching links off their neighbours. The joint projection alone
//! (`projection`) would put them back — and push a link back into the ground. So both rows
//! are solved together here, in the metric of the masses (W = diag(1/m, I⁻¹_world)):
//!
//! ```text
//! rows       J = (joint rows J_j ; contact rows J_c ; stops J_s), J_c = (n, r_A×n | −n, −r_B×n),
//!            J_s a limit's stop within 1e-9 of its limit (`drive::touching_stops`)
//! K = J W Jᵀ (the effective mass the contact impulse uses for one row)
//! find μ:    w = K μ + r,   w_j = 0,   w_c ≥ 0,  μ_c ≥ 0,  μ_c w_c = 0  (the stops as c)
//! positions  r_j = C_j, r_c = g_c + s_c, r_s = C_s  (δ = W Jᵀ μ; g_c ≥ 0 the speculative
//!            gap, s_c the contact point's normal motion so far: a pass never pushes a contact
//!            point deeper than the response left it); repeated (Newton) until |C_j| < 1e-12
//!            and no stop is past its limit by 1e-12
//! velocities r_j = J_j u, r_c = J_c u + g_c/dt, r_s = J_s u;   ΔP = J_linᵀ μ, ΔL = J_angᵀ μ
//! ```
//!
//! With the stops in it, a body resting on another that lies on its stop (a box on a flap)
//! does not turn the flap past its limit: the stop carries the box's weight with the flap's.
//!
//! The complementarity problem is solved exactly by an active set: solve `K_SS μ_S = −r_S`
//! (`solve::multipliers`, the same envelope Cholesky as the joints' forces) with S the joint
//! rows and the contacts held so far; drop the contact with the most negative μ, or add the
//! most violated w_c < 0, and solve again (K is positive definite: each change lowers the
//! quadratic, a few rounds suffice). The velocity pass is the projection of u onto the convex
//! cone {J_j u = 0, J_c u ≥ −g/dt} ∋ 0 in the kinetic-energy norm, so it never adds kinetic
//! energy. Its change is booked with the contact's (the response of a chain that lands is
//! contacts and joint rows together).
//!
//! Why not joint rows inside the contact solver itself: that solver (`collision::impulse`)
//! also carries friction, restitution and warm starts; this pass takes its result and adds the
//! joints, so friction is the response's, computed as if the links were free (the tangential
//! impulses are not re-solved with the joints: a chain sliding on the ground brakes a little
//! less exactly than Coulomb's law per link says).

use super::projection::{joint_rows, shift};
use super::rows::{rate, Pose, Row};
use super::solve::{multipliers, Inverse, Solver};
use super::Links;
use crate::physics::body::Body;
use crate::physics::collision::Contact;
use crate::physics::constraints::Axis;
use crate::physics::effects::Loads;
use crate::physics::state::State;
use nalgebra::Vector3;

/// Velocity violations below this are round-off, m/s (the contact solver's own tolerance).
const VELOCITY_TOLERANCE: f64 = 1e-10;

/// Position violations below this are round-off, m.
const POSITION_TOLERANCE: f64 = 1e-13;

/// Reused buffers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buffers {
    poses: Vec<Pose>,
    inverse: Vec<Inverse>,
    /// Joint rows, then one row per contact.
    rows: Vec<Row>,
    /// Per contact: its lever arms in the bodies' frames, its gap (≥ 0) and its normal motion.
    levers: Vec<(Vector3<f64>, Vector3<f64>)>,
    gaps: Vec<f64>,
    moved: Vec<f64>,
    r: Vec<f64>,
    mu: Vec<f64>,
    active: Vec<bool>,
    subset: Vec<Row>,
    rhs: Vec<f64>,
    delta: Vec<(Vector3<f64>, Vector3<f64>)>,
    solver: Solver,
    /// Per joint: the velocity impulse its stops gave in the last pass (≥ 0).
    stops: Vec<f64>,
}

impl Buffers {
    /// Per joint: the velocity impulse its limit's stops gave in the last [`hold`] (≥ 0, N·s
    /// or N·m·s along the stop's row; `drive::book_stops`).
    pub fn stops(&self) -> &[f64] {
        &self.stops
    }
}

/// What the pass did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Held {
    /// Active-set rounds over both passes.
    pub rounds: usize,
    /// Whether it changed a state.
    pub changed: bool,
}

/// Holds the joints of `links` at `states` together with `contacts` (as the response left
/// them): positions, then velocities. `impulses[j]` receives joint j's velocity impulse on its
/// body A (added to what is there).
pub fn hold(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    contacts: &[Contact],
    dt: f64,
    impulses: &mut [Loads],
    b: &mut Buffers,
) -> Held {
    let mut held = Held::default();
    b.stops.clear();
    if links.joints.is_empty() {
        return held;
    }
    b.stops.resize(links.joints.len(), 0.0);
    b.levers.clear();
    b.gaps.clear();
    for c in contacts {
        let ra = states[c.body].orientation.matrix().tr_mul(&c.lever);
        // B by its solver body entry: a body (fixed or not), or an obstacle's static entry
        // after the bodies, which has no end here (the world).
        let rb = states.get(c.other).map_or(Vector3::zeros(), |o| {
            o.orientation.matrix().tr_mul(&c.lever_other)
        });
        b.levers.push((ra, rb));
        b.gaps.push((-c.depth).max(0.0));
    }
    b.moved.clear();
    b.moved.resize(contacts.len(), 0.0);
    let joint_rows = links.row_count();
    let stops_from = joint_rows + contacts.len();
    for pass in 0..=10 {
        build(links, bodies, states, contacts, b);
        let worst = b.rows[..joint_rows]
            .iter()
            .map(|r| r.error.abs())
            .chain(b.rows[stops_from..].iter().map(|r| -r.error))
            .fold(0.0, f64::max);
        if worst < 1e-12 || pass == 10 {
            break;
        }
        b.r.clear();
        b.r.extend(b.rows[..joint_rows].iter().map(|r| r.error));
        b.r.extend((0..contacts.len()).map(|i| b.gaps[i] + b.moved[i]));
        b.r.extend(b.rows[stops_from..].iter().map(|r| r.error));
        held.rounds += complementarity(joint_rows, POSITION_TOLERANCE, b);
        for (row, &mu) in b.rows.iter().zip(&b.mu) {
            if mu != 0.0 {
                shift(states, &b.inverse, row.a(), &row.lin_a(), &row.ang_a(), mu);
                if let Some(j) = row.b() {
                    shift(states, &b.inverse, j, &row.lin_b(), &row.ang_b(), mu);
                }
            }
        }
        // The contact points' normal motion: J_c δ.
        for (i, row) in b.rows[joint_rows..stops_from].iter().enumerate() {
            b.moved[i] += along(row, &b.delta);
        }
        held.changed = true;
    }
    // Velocities: the last build is at the projected positions.
    b.r.clear();
    for (i, row) in b.rows.iter().enumerate() {
        let pb = row.b().map_or(Pose::WORLD, |j| b.poses[j]);
        let rate = rate(row, &b.poses[row.a()], &pb);
        b.r.push(if i < joint_rows || i >= stops_from {
            rate
        } else {
            rate + b.gaps[i - joint_rows] / dt
        });
    }
    let violated = b.r[..joint_rows]
        .iter()
        .any(|r| r.abs() > VELOCITY_TOLERANCE)
        || b.r[joint_rows..].iter().any(|&r| r < -VELOCITY_TOLERANCE);
    if !violated {
        return held;
    }
    held.rounds += complementarity(joint_rows, VELOCITY_TOLERANCE, b);
    for (row, &mu) in b.rows.iter().zip(&b.mu) {
        apply(row, mu, states);
    }
    let held_rows = b.rows.iter().zip(&b.mu).enumerate();
    for (i, (row, &mu)) in held_rows.filter(|(i, _)| *i < joint_rows || *i >= stops_from) {
        impulses[row.owner].force += row.lin_a() * mu;
        impulses[row.owner].torque += row.ang_a() * mu;
        if i >= stops_from {
            b.stops[row.owner] += mu;
        }
    }
    held.changed = true;
    held
}

/// The joints' equality rows at `states` into `rows` (what the contact solve takes with its
/// contact rows: `collision::impulse::joined`), then every limit's stop within
/// `drive::TOUCHING` of its limit (one-sided, λ ∈ [0, ∞): `drive::touching_stops`), so that
/// a contact's impulse on a body resting on its stop is answered by the stop in the same
/// solve, then every motor's row with what is left of its bounds after the drive pass's
/// impulse `given[j]` (`drive::motor_rows`; `given` empty: no motor rows), so that a motor
/// pushing what it touches is solved with the contacts.
pub fn equality_rows(
    links: &Links,
    bodies: &[Body],
    states: &[State],
    (given, dt): (&[f64], f64),
    rows: &mut Vec<Row>,
) {
    let (mut poses, mut inverse) = (Vec::new(), Vec::new());
    joint_rows(links, bodies, states, (&mut poses, &mut inverse, rows));
    super::drive::touching_stops(links, &poses, rows);
    if !given.is_empty() {
        super::drive::motor_rows(links, &poses, (given, dt), rows);
    }
}

/// The joint rows and the contact rows at `states`, with velocities.
fn build(links: &Links, bodies: &[Body], states: &[State], contacts: &[Contact], b: &mut Buffers) {
    joint_rows(
        links,
        bodies,
        states,
        (&mut b.poses, &mut b.inverse, &mut b.rows),
    );
    for (c, (la, lb)) in contacts.iter().zip(&b.levers) {
        let n = c.normal;
        let ra = b.poses[c.body].r * la;
        // B's end: its entry when it is one of the bodies (the pass's table); an obstacle's
        // static entry lies past them and gives no end.
        let other = (c.other < states.len()).then_some(c.other);
        let rb = other.map_or(Vector3::zeros(), |o| b.poses[o].r * lb);
        // A contact normal: [0, ∞), it pushes only.
        let axis = Axis::jacobian(n, (c.body, ra.cross(&n)), other.map(|o| (o, -rb.cross(&n))));
        b.rows.push(Row::new(axis, [0.0, f64::INFINITY], 0.0));
    }
    // The limits' stops within touching of their limits, one-sided like the contacts.
    super::drive::touching_stops(links, &b.poses, &mut b.rows);
}

/// Applies the impulse μ of one row to its bodies: `ΔP = J_linᵀ μ`, `ΔL = J_angᵀ μ` on each end.
pub(super) fn apply(row: &Row, mu: f64, states: &mut [State]) {
    if mu == 0.0 {
        return;
    }
    states[row.a()].linear_momentum += row.lin_a() * mu;
    states[row.a()].angular_momentum += row.ang_a() * mu;
    if let Some(j) = row.b() {
        states[j].linear_momentum += row.lin_b() * mu;
        states[j].angular_momentum += row.ang_b() * mu;
    }
}

/// `J δ` of one row for per-body changes δ = (linear, angular).
pub(super) fn along(row: &Row, delta: &[(Vector3<f64>, Vector3<f64>)]) -> f64 {
    let (la, aa) = &delta[row.a()];
    let mut s = row.lin_a().dot(la) + row.ang_a().dot(aa);
    if let Some(j) = row.b() {
        let (lb, ab) = &delta[j];
        s += row.lin_b().dot(lb) + row.ang_b().dot(ab);
    }
    s
}

/// Solves the mixed complementarity problem of the module doc for `b.mu` (rows `b.rows`, the
/// first `joint_rows` bilateral, offsets `b.r`); leaves the per-body change W Jᵀ μ in
/// `b.delta`. Returns the rounds it took.
fn complementarity(joint_rows: usize, tolerance: f64, b: &mut Buffers) -> usize {
    let n = b.rows.len();
    b.active.clear();
    b.active
        .extend((0..n).map(|i| i < joint_rows || b.r[i] < -tolerance));
    let most = 4 * (n - joint_rows) + 4;
    let mut rounds = 0;
    loop {
        rounds += 1;
        b.subset.clear();
        b.rhs.clear();
        for i in (0..n).filter(|&i| b.active[i]) {
            b.subset.push(b.rows[i]);
            b.rhs.push(-b.r[i]);
        }
        multipliers(&b.subset, &b.inverse, &mut b.rhs, &mut b.solver);
        b.mu.clear();
        b.mu.resize(n, 0.0);
        let mut next = b.rhs.iter();
        for i in 0..n {
            if b.active[i] {
                b.mu[i] = *next.next().unwrap_or(&0.0);
            }
        }
        // δ = W Jᵀ μ per body.
        b.delta.clear();
        b.delta
            .resize(b.inverse.len(), (Vector3::zeros(), Vector3::zeros()));
        for (row, &mu) in b.rows.iter().zip(&b.mu) {
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
        if rounds >= most {
            return rounds;
        }
        // A contact that pulls leaves the set; else the most violated one joins it.
        let pulling = (joint_rows..n)
            .filter(|&i| b.active[i] && b.mu[i] < 0.0)
            .min_by(|&i, &j| b.mu[i].total_cmp(&b.mu[j]));
        if let Some(i) = pulling {
            b.active[i] = false;
            continue;
        }
        let violated = (joint_rows..n)
            .filter(|&i| !b.active[i])
            .map(|i| (i, along(&b.rows[i], &b.delta) + b.r[i]))
            .filter(|&(_, w)| w < -tolerance)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        match violated {
            Some((i, _)) => b.active[i] = true,
            None => return rounds,
        }
    }
}
