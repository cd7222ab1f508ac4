//! Attached particles: an explicit cloth's attachments held by impulses after its velocity
//! half ([`hold_attachments`]), and attached particles carried with their bodies after the
//! collide phase moved them ([`carry_attachments`]).

use super::tied::HeldJoints;
use super::{close_gap, move_body, solver_body, turn_gap, Attachment};
use crate::physics::body::Body;
use crate::physics::cloth::Cloth;
use crate::physics::constraints::{attachment, Attachment as Hold, SolverBody};
use crate::physics::effects::Loads;
use crate::physics::joints::Links;
use crate::physics::state::State;
use nalgebra::{DMatrix, DVector, Matrix3, Matrix6, Vector3};

/// What the attachments of an explicit cloth did over a step ([`hold_attachments`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AttachReport {
    /// Σ J_a on the particles (N·s) and its moment about the world origin, Σ x_a × J_a
    /// (N·m·s), x_a the attachment's point.
    pub impulse: [Vector3<f64>; 2],
}

/// How the collide phase moved a body: its barycenter by `shift`, its orientation by the
/// rotation `turn` about the barycenter (R ← turn R). An attached particle's tie aims at its
/// point after the body's own step moved on by the body's last move ([`tied_step`](super::tied_step), "Bodies
/// the collide phase moves"), which [`carry_attachments`] then corrects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMove {
    pub shift: Vector3<f64>,
    pub turn: Matrix3<f64>,
}

impl BodyMove {
    /// No move.
    pub const NONE: BodyMove = BodyMove {
        shift: Vector3::new(0.0, 0.0, 0.0),
        turn: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
    };

    /// The move from state `before` to `after`.
    pub fn between(before: &State, after: &State) -> BodyMove {
        BodyMove {
            shift: after.position - before.position,
            turn: after.orientation.matrix() * before.orientation.matrix().transpose(),
        }
    }

    /// How far it moves the body's point at arm r (from the barycenter): shift + turn r − r.
    pub fn of_point(&self, arm: &Vector3<f64>) -> Vector3<f64> {
        self.shift + self.turn * arm - arm
    }
}

/// What carrying a body's attached particles gave them ([`carry_attachments`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Carried {
    /// Σ m_p Δv_p over the body's attached particles, N·s.
    pub impulse: Vector3<f64>,
    /// Σ r_p × m_p Δv_p about the body's barycenter (r_p = x_p − x_b), N·m·s.
    pub moment: Vector3<f64>,
}

/// Attached particles carried with their bodies after the rigid collide phase moved them.
///
/// The cloth's step ends its attached particles on their points (`tied_step`), but the rigid
/// contact response runs after it, in the collide phase, and may move a body again: a frame
/// resting on the floor falls ½ a h² within its own step (a = g + its load / M: 5.27e-6 m for
/// lesson 35's frame) and the floor's contact puts it back, leaving its 80 rim particles that
/// far below their points at the end of every step. So each attached particle p of a body b
/// the response moved (`moved[b]`) is put back on its point and given the point's velocity:
///
/// ```text
/// x_p = x_b + R_b o_p,    v_p = V_b + ω_b × (R_b o_p)      (o_p: its offset in b's frame)
/// ```
///
/// This is what the response would have done had it seen the body and its attached particles
/// as one rigid body: the momentum the particles take, Σ m_p Δv_p (returned per body in
/// `carried`, with its moment about the body's barycenter), came through the body from what it
/// touches. The caller books it (`World`: into the body's contacts with what cannot move,
/// which then report the support of the body and its particles together) and books the
/// energy the move changes as the contacts' energy. Returned, J: the carried particles'
/// kinetic and gravitational energy, and the springs that touch them,
///
/// ```text
/// ΔE = Σ_p [½ m_p (|v_p'|² − |v_p|²) − m_p g·(x_p' − x_p)] + Σ_{springs at a carried p} ΔU_s
/// ```
///
/// (what measuring the whole sheet's energy before and after would give, without the other
/// particles and springs, which do not change).
pub fn carry_attachments(
    cloth: &mut Cloth,
    gravity: Option<Vector3<f64>>,
    bodies: &[Body],
    states: &[State],
    attachments: &[Attachment],
    moved: &[bool],
    carried: &mut [Carried],
) -> f64 {
    let carries = |a: &Attachment| moved.get(a.body).copied().unwrap_or(false);
    if !attachments.iter().any(carries) {
        return 0.0;
    }
    // The springs at a carried particle, before and after.
    let mut at_carried = vec![false; cloth.len()];
    for a in attachments.iter().filter(|a| carries(a)) {
        at_carried[a.particle] = true;
    }
    let springs_energy = |cloth: &Cloth| -> f64 {
        (cloth.springs.iter())
            .filter(|s| at_carried[s.i] || at_carried[s.j])
            .map(|s| s.energy(&cloth.positions))
            .sum()
    };
    let mut change = -springs_energy(cloth);
    for a in attachments {
        if !moved.get(a.body).copied().unwrap_or(false) {
            continue;
        }
        let state = &states[a.body];
        let arm = state.orientation.matrix() * a.offset_body;
        let velocity = solver_body(&bodies[a.body], state).point_velocity(&arm);
        let p = a.particle;
        let (m, position) = (cloth.masses[p], state.position + arm);
        let momentum = (velocity - cloth.velocities[p]) * m;
        change += 0.5 * m * (velocity.norm_squared() - cloth.velocities[p].norm_squared());
        if let Some(g) = gravity {
            change -= m * g.dot(&(position - cloth.positions[p]));
        }
        cloth.positions[p] = position;
        cloth.velocities[p] = velocity;
        carried[a.body].impulse += momentum;
        carried[a.body].moment += arm.cross(&momentum);
    }
    change + springs_energy(cloth)
}

/// What holding a cloth's attachments reads: the bodies, the attachments, the step, the
/// bodies' integrator's position factor (`Integrator::position_factor`) and the joints.
#[derive(Debug, Clone, Copy)]
pub struct Holding<'a> {
    pub bodies: &'a [Body],
    pub attachments: &'a [Attachment],
    pub dt: f64,
    pub factor: f64,
    pub links: &'a Links,
}

/// Attachments of an explicit (`symplectic-euler`) cloth, held by impulses after its
/// velocity half and the bodies' own step (the implicit cloth holds them inside its solve,
/// [`tied_step`](super::tied_step)).
///
/// Attachment a holds particle p at its body's point P_a = x_b + r_a (the body already at
/// the end of its own step). Unknown: the impulse J_a on the particle, −J_a on the body at
/// r_a. The body's correction ΔV = −Σ J/M, Δω = −I⁻¹ Σ r × J moves its position by
/// factor·h·(ΔV, Δω) ([`Integrator::position_factor`](crate::physics::Integrator::position_factor)), so the particle ends on its point when
///
/// ```text
/// x_p + h (v_p + J_a/m_p) = P_a + factor h (ΔV + Δω × r_a)      (linearised turn)
/// Σ_c K_ac J_c = (P_a − x_p)/h − v_p
/// K_ac = δ_ac I/m_p + factor (I/M − [r_a]× I⁻¹ [r_c]×)
/// ```
///
/// one symmetric positive-definite 3k × 3k system per body with k attachments, solved
/// directly (Cholesky). It is solved as rows of the constraint layer: the body and the
/// particles are solver bodies (`constraints::SolverBody`: the body first, its share weighed
/// by f = factor, `attachment::weighed`, then each attachment's particle), each attachment
/// three equality rows between a particle end and the body end (`constraints::Attachment`),
/// and K the rows' couplings (`attachment::system`: `Axis::coupling`, the particle's term
/// then the body's). The body's turn is then applied exactly and the particle moved by what
/// the linearisation missed, `(R(h Δω') − I) r − h Δω' × r` (Δω' = factor Δω), with the
/// opposite momentum to the body: the error left is round-off, and body + particles keep
/// their momentum. A fixed body takes nothing (K = I/m_p); a body whose integrator ignores
/// the correction in its position (factor 0: weighed by 0, its rows have no body end) takes
/// the impulses in its momenta only.
///
/// **Bodies held by joints** (a pole on a hinge): their corrections must keep the joints'
/// velocity rows, `J Y = 0` (`tied`'s `HeldJoints`, the rows at the bodies' poses after their
/// own step), as inside the implicit cloth's solve (`cloth::ties`, "Joints on the bodies").
/// The held bodies' attachments are solved together, each body's response `M_b⁻¹` replaced by
/// the joints' filtered inverse Q = N (Nᵀ D N)⁻¹ Nᵀ (N a basis of null(J), D = blockdiag(M_b)),
///
/// ```text
/// K = blockdiag(I/m_p) + factor G Q Gᵀ,   G_a Y = Y_V + Y_ω × r_a  (row a, body b(a)'s columns)
/// Y = −Q Gᵀ J,   ΔP_b = M Y_V,   ΔL_b = I Y_ω,   joint impulse Jᵀμ = D Y + Gᵀ J
/// ```
///
/// so the pull on the pole turns it only about its hinge, within the step; what the joints
/// gave is added to their reactions (`joint_impulses`, N·s, one per joint of `links`). A body
/// whose integrator ignores the correction (factor 0) takes the filtered Y in its momenta
/// only.
///
/// Returns the impulses' sum and moment. No energy is booked: an ideal hold does no work, and
/// what the velocity half gave a particle off its point is the splitting's error (the drift).
pub fn hold_attachments(
    cloth: &mut Cloth,
    holding: &Holding,
    states: &mut [State],
    joint_impulses: &mut Vec<Loads>,
) -> AttachReport {
    let Holding {
        bodies,
        attachments,
        dt,
        factor,
        links,
    } = *holding;
    let mut report = AttachReport::default();
    let moves = |b: usize| !bodies[b].fixed && bodies[b].inv_mass > 0.0;
    let held = HeldJoints::new(links, states, moves);
    let is_held = |b: usize| held.filter.bodies.contains(&b);
    joint_impulses.clear();
    joint_impulses.resize(links.joints.len(), Loads::default());
    if attachments.iter().any(|a| is_held(a.body)) {
        hold_on_joints(cloth, holding, &held, states, joint_impulses, &mut report);
    }
    for (b, (body, state)) in bodies.iter().zip(states.iter_mut()).enumerate() {
        let list: Vec<&Attachment> = attachments.iter().filter(|a| a.body == b).collect();
        if list.is_empty() || is_held(b) {
            continue;
        }
        let rotation = state.orientation.matrix();
        let moves = !body.fixed && body.inv_mass > 0.0;
        let scale = if moves { factor } else { 0.0 };
        // The solve's solver bodies: the body (0), its share weighed by the position factor
        // (`constraints::attachment::weighed`), then each attachment's particle (a + 1); each
        // attachment three equality rows between them (`constraints::attachment`).
        let own = solver_body(body, state);
        let mut ends = Vec::with_capacity(list.len() + 1);
        ends.push(attachment::weighed(&own, scale));
        ends.extend((list.iter()).map(|a| {
            SolverBody::particle(cloth.velocities[a.particle], cloth.inv_mass(a.particle))
        }));
        let holds: Vec<Hold> = (list.iter().enumerate())
            .map(|(a, att)| Hold {
                particle: a + 1,
                body: 0,
                arm: rotation * att.offset_body,
            })
            .collect();
        // K: the rows' couplings (`attachment::system`).
        let matrix = attachment::system(&holds, &ends);
        let mut rhs = DVector::<f64>::zeros(3 * list.len());
        for (a, (att, hold)) in list.iter().zip(&holds).enumerate() {
            // Where the particle must end: on the point, P_a − x_p over h, less its velocity.
            let point = state.position + hold.arm;
            let u = (point - cloth.positions[att.particle]) / dt - ends[hold.particle].v;
            rhs.fixed_rows_mut::<3>(3 * a).copy_from(&u);
        }
        let Some(cholesky) = matrix.cholesky() else {
            continue;
        };
        let impulses = cholesky.solve(&rhs);
        let (mut total, mut torque) = (Vector3::zeros(), Vector3::zeros());
        for (a, (att, Hold { arm: ra, .. })) in list.iter().zip(&holds).enumerate() {
            let j: Vector3<f64> = impulses.fixed_rows::<3>(3 * a).into_owned();
            cloth.apply_impulse(att.particle, &j);
            total += j;
            torque += ra.cross(&j);
            report.impulse[1] += (state.position + ra).cross(&j);
        }
        report.impulse[0] += total;
        if moves {
            state.linear_momentum -= total;
            state.angular_momentum -= torque;
            if scale > 0.0 {
                let y_v = -total * (body.inv_mass * scale);
                let y_w = -(own.inv_inertia * torque) * scale;
                move_body(state, &y_v, &y_w, dt);
                for (att, Hold { arm: ra, .. }) in list.iter().zip(&holds) {
                    let gap = turn_gap(&y_w, ra, dt);
                    let j = close_gap(cloth, att.particle, state, ra, &gap, dt);
                    report.impulse[0] += j;
                    report.impulse[1] += (state.position + ra).cross(&j);
                }
            }
        }
    }
    report
}

/// The attachments on the bodies the joints hold, solved together ([`hold_attachments`],
/// "Bodies held by joints").
fn hold_on_joints(
    cloth: &mut Cloth,
    holding: &Holding,
    held: &HeldJoints,
    states: &mut [State],
    joint_impulses: &mut [Loads],
    report: &mut AttachReport,
) {
    let Holding {
        bodies,
        attachments,
        dt,
        factor,
        ..
    } = *holding;
    let group = &held.filter.bodies;
    let column = |b: usize| group.iter().position(|&x| x == b);
    let list: Vec<(&Attachment, usize)> = (attachments.iter())
        .filter_map(|a| column(a.body).map(|g| (a, g)))
        .collect();
    let rotations: Vec<Matrix3<f64>> = (group.iter())
        .map(|&b| states[b].orientation.matrix())
        .collect();
    // D per body: diag(M, I) with I = R I_body Rᵀ.
    let inertia =
        |g: usize| rotations[g] * bodies[group[g]].inertia_body * rotations[g].transpose();
    let q = held.filter.filtered_inverse(|b| {
        let g = column(b).expect("a held body");
        let mut d = Matrix6::zeros();
        for k in 0..3 {
            d[(k, k)] = bodies[b].mass;
        }
        d.fixed_view_mut::<3, 3>(3, 3).copy_from(&inertia(g));
        d
    });
    // The layer's solver bodies: the held bodies (column g), then each attachment's particle
    // (n + a); each attachment three equality rows between them (`constraints::attachment`),
    // whose body ends are −G_a in its body's columns.
    let (k, n) = (list.len(), group.len());
    let mut ends: Vec<SolverBody> = (group.iter())
        .map(|&b| solver_body(&bodies[b], &states[b]))
        .collect();
    ends.extend((list.iter()).map(|(a, _)| {
        SolverBody::particle(cloth.velocities[a.particle], cloth.inv_mass(a.particle))
    }));
    let holds: Vec<Hold> = (list.iter().enumerate())
        .map(|(a, (att, g))| Hold {
            particle: n + a,
            body: *g,
            arm: rotations[*g] * att.offset_body,
        })
        .collect();
    // G: 3k × 6n, row block a = [I, −[r_a]×] in its body's columns.
    let mut g_matrix = DMatrix::<f64>::zeros(3 * k, 6 * n);
    let mut rhs = DVector::<f64>::zeros(3 * k);
    for (a, ((att, _), hold)) in list.iter().zip(&holds).enumerate() {
        g_matrix
            .fixed_view_mut::<3, 6>(3 * a, 6 * hold.body)
            .copy_from(&hold.point_jacobian());
        let point = states[group[hold.body]].position + hold.arm;
        let u = (point - cloth.positions[att.particle]) / dt - ends[hold.particle].v;
        rhs.fixed_rows_mut::<3>(3 * a).copy_from(&u);
    }
    let mut matrix = &g_matrix * &q * g_matrix.transpose() * factor;
    for (a, hold) in holds.iter().enumerate() {
        for c in 0..3 {
            matrix[(3 * a + c, 3 * a + c)] += ends[hold.particle].inv_mass;
        }
    }
    let Some(cholesky) = matrix.cholesky() else {
        return;
    };
    let impulses = cholesky.solve(&rhs);
    for (a, ((att, _), hold)) in list.iter().zip(&holds).enumerate() {
        let j: Vector3<f64> = impulses.fixed_rows::<3>(3 * a).into_owned();
        cloth.apply_impulse(att.particle, &j);
        report.impulse[0] += j;
        report.impulse[1] += (states[group[hold.body]].position + hold.arm).cross(&j);
    }
    // The particles' pull on the bodies, Gᵀ J; the bodies' filtered response Y = −Q Gᵀ J.
    let pull = g_matrix.transpose() * &impulses;
    let y = -(&q * &pull);
    let mut wrench = DVector::<f64>::zeros(6 * n);
    for (g, &b) in group.iter().enumerate() {
        let y_v = Vector3::new(y[6 * g], y[6 * g + 1], y[6 * g + 2]);
        let y_w = Vector3::new(y[6 * g + 3], y[6 * g + 4], y[6 * g + 5]);
        let (dp, dl) = (y_v * bodies[b].mass, inertia(g) * y_w);
        let state = &mut states[b];
        state.linear_momentum += dp;
        state.angular_momentum += dl;
        for c in 0..3 {
            wrench[6 * g + c] = dp[c] + pull[6 * g + c];
            wrench[6 * g + 3 + c] = dl[c] + pull[6 * g + 3 + c];
        }
        if factor > 0.0 {
            let (y_v, y_w) = (y_v * factor, y_w * factor);
            move_body(state, &y_v, &y_w, dt);
            for ((att, _), Hold { arm: ra, .. }) in
                list.iter().zip(&holds).filter(|(_, h)| h.body == g)
            {
                let gap = turn_gap(&y_w, ra, dt);
                let j = close_gap(cloth, att.particle, state, ra, &gap, dt);
                report.impulse[0] += j;
                report.impulse[1] += (state.position + ra).cross(&j);
            }
        }
    }
    held.reactions(wrench, joint_impulses);
}
