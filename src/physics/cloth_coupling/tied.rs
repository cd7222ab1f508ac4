//! Contacts and attachments of an `implicit-euler` cloth *inside* its linear solve
//! (`cloth::ties`): [`tied_step`].

use super::attachments::BodyMove;
use super::{close_gap, move_body, solver_body, turn_gap, Attachment};
use crate::physics::body::Body;
use crate::physics::cloth::{BodyJoints, Cloth, Held, Tie, TieKind, TiedBody};
use crate::physics::collision::geometry::{point_shape, Pose};
use crate::physics::effects::Loads;
use crate::physics::joints::{rows_of, Links, Pose as JointPose, Row};
use crate::physics::state::State;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// The most solves of one step's tied system (each after the contact set changed: a contact
/// released because it pulled, a new one found because the particle would go inside, a stuck
/// contact that started to slide). What a last change leaves is for the collide phase.
pub const TIE_ROUNDS: usize = 5;

/// A gap (m) below which a particle counts as touching.
const TOUCHING: f64 = 1e-9;

/// A particle that may touch a body or an obstacle this step.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    particle: usize,
    body: Option<usize>,
    /// Signed gap from the particle's start position to the body's pose after its own step
    /// (< 0: inside), m.
    gap: f64,
    normal: Vector3<f64>,
    arm: Vector3<f64>,
    /// The body's material point at `arm`: its own-step displacement over h, m/s.
    drift: Vector3<f64>,
}

/// What the tied step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TiedReport {
    /// Contacts with bodies held at the end (attachments not counted).
    pub contacts: usize,
    /// Contacts with obstacles held at the end.
    pub obstacle_contacts: usize,
    /// Solves of the tied system (1 when the first contact set held).
    pub rounds: usize,
    /// CG iterations over all rounds.
    pub iterations: usize,
    /// Energy the contacts took, J: minus the work of their impulses along the relative
    /// motion, −Σ (λ + e)·(v_p − v_point) (0 for a resting contact, > 0 for friction).
    pub energy_taken: f64,
    /// What the attachments gave the cloth over the step: Σ λ_a (N·s) and its moment about
    /// the world origin, Σ x_a × λ_a (N·m·s), x_a the attachment's point on its body at the
    /// end of the step (the bodies took the opposite).
    pub attach_impulse: [Vector3<f64>; 2],
}

/// What a tied step reads: the step, the bodies and obstacles the cloth touches, its
/// attachments and the joints on the bodies (see [`tied_step`]).
#[derive(Debug, Clone, Copy)]
pub struct TiedScene<'a> {
    pub loads: &'a crate::physics::cloth::ClothLoads,
    /// The step's constants: dt and μ of the contacts (0: frictionless, normal ties only).
    pub context: &'a crate::physics::collision::StepContext,
    pub bodies: &'a [Body],
    /// The bodies' states at the start of the step.
    pub start: &'a [State],
    pub obstacles: &'a [crate::physics::collision::Obstacle],
    pub attachments: &'a [Attachment],
    /// The bodies' integrator's position factor (`Integrator::position_factor`).
    pub factor: f64,
    pub links: &'a Links,
    /// How the last collide phase moved each body (the attached particles' lead).
    pub predicted: &'a [BodyMove],
}

/// One velocity half of an `implicit-euler` cloth with its contacts against the bodies and
/// the obstacles, and its attachments, all inside the linear solve (`cloth::ties`). `start`:
/// the bodies' states at the start of the step; `states`: after their own step, where the
/// contacts are measured. The cloth's positions are not moved (the caller's position half).
///
/// # Where the particle must end: positions, not velocities
///
/// The body has already moved by its own step when the cloth steps; what its correction
/// (ΔV, Δω) adds to its position is `factor`·h·(ΔV, Δω) ([`Integrator::position_factor`](crate::physics::Integrator::position_factor)). So a particle
/// at gap g from the body's new pose ends on its surface when
///
/// ```text
/// n·v₁ = −g/h + n·(Y_V + Y_ω × r),     (Y_V, Y_ω) = factor·(ΔV, Δω)
/// ```
///
/// (not n·(V + ΔV + …): the body's own velocity V is already in its pose; following it once
/// more left a particle a step's travel h|V| inside a body moving away from it, for the
/// collide phase to push out — energy made). A sticking particle also follows the body's
/// point along the surface: its tangential velocity is the point's own-step displacement
/// over h, plus the same correction. The solve's unknown is Y: the impulse J on the body
/// gives M ΔV = J, i.e. M/factor · Y = J, so the body enters the solve with mass M/factor and
/// inertia I/factor, and takes P += (M/factor) Y_V, L += (I/factor) Y_ω, x += h Y_V, and
/// turns by h Y_ω. A body whose integrator ignores the correction in its position (factor 0)
/// is not an unknown: it is held still in the solve and takes the impulses afterwards.
///
/// Energy the contacts take: the work of the impulses along the particle's motion relative
/// to the body's material point over the step, −Σ (λ + e)·(v₁ − d/h − Y_V − Y_ω × r) (d the
/// point's own-step displacement): a contact arriving from a gap g₀ at the start takes λ_n
/// g₀/h, a resting one (g₀ = 0, sticking) none, a sliding one what its friction did.
///
/// # Joints
///
/// The joints on the bodies that move in the solve are held inside it (`HeldJoints`):
/// their rows filter the bodies' corrections, and `joint_impulses` receives each joint's
/// impulse on its body A over the step (N·s, torque about A's barycenter).
///
/// # Bodies the collide phase moves
///
/// The rigid contact response runs after this step, and may move a body again: a frame
/// resting on the floor falls ½ a h² within its own step and the floor puts it back. An
/// attached particle tied to the fallen point would be left that far from it at the end of
/// the step, and carried back after the response ([`carry_attachments`](super::carry_attachments)) it would be pulled
/// down again the next step — a 5 µm vibration of lesson 35's rim every step, whose damping
/// the ledger books while nothing visibly moves. So an attached particle aims at its point
/// after the body's own step moved on by the move the collide phase gave the body the step
/// before, `predicted` ([`BodyMove`]; none: no lead),
///
/// ```text
/// target_a = (x_b + r_a + m_b(r_a) − x_p)/h,   m_b(r) = shift_b + turn_b r − r
/// ```
///
/// For a body at rest the move repeats exactly and the particle ends the step on its point
/// with the body's velocity; what a changing move leaves is carried after the response.
/// Energy: the lead is motion of the particle relative to the body's material point, so the
/// tie's work along it, −λ·lead h, is booked with the contacts like any tie's (above); it is
/// what the body takes from the sheet's pull over the lead, and the response's own booking
/// takes it back when it puts the body where the lead said (at rest the two cancel exactly).
pub fn tied_step(
    cloth: &mut Cloth,
    scene: &TiedScene,
    states: &mut [State],
    joint_impulses: &mut Vec<Loads>,
) -> TiedReport {
    cloth.begin_tied_step(scene.loads, scene.context.dt);
    let mut solver_bodies = scene.solver_bodies(states);
    // The joints on the bodies that move in the solve, held inside it (`cloth::ties`,
    // "Joints on the bodies").
    let held_joints = HeldJoints::new(scene.links, states, |b| solver_bodies[b].mass > 0.0);
    let held: Vec<Held> = cloth.held().to_vec();
    let candidates = scene.candidates(cloth, states, &solver_bodies);
    let mut report = TiedReport::default();
    let ties = scene.solve_rounds(
        cloth,
        states,
        &Contacts {
            candidates: &candidates,
            held: &held,
        },
        &mut solver_bodies,
        &held_joints,
        &mut report,
    );
    cloth.finish_tied_step(scene.loads);
    cloth.record_solves(crate::physics::cloth::SolveCounts {
        solves: report.rounds,
        iterations: report.iterations,
    });
    scene.book_ties(cloth, states, &ties, &solver_bodies, &mut report);
    cloth.set_held(
        candidates.iter().map(|c| c.particle),
        ties.iter().filter(|t| !t.permanent).map(|t| t.particle),
    );
    joint_impulses.clear();
    joint_impulses.resize(scene.links.joints.len(), Loads::default());
    held_joints.impulses(&ties, &solver_bodies, joint_impulses);
    scene.push_bodies(states, &ties, &solver_bodies);
    scene.close_turns(cloth, states, &ties, &solver_bodies, &mut report);
    scene.attach_reactions(states, &ties, &mut report);
    report
}

/// The contact candidates of a step and which particles the last step held.
struct Contacts<'a> {
    candidates: &'a [Candidate],
    held: &'a [Held],
}

/// The correction's velocity at a candidate's point, (Y_V + Y_ω × r).
fn correction_at(sb: &[TiedBody], body: Option<usize>, arm: &Vector3<f64>) -> Vector3<f64> {
    body.map_or(Vector3::zeros(), |b| {
        let [dv, dw] = sb[b].correction;
        dv + dw.cross(arm)
    })
}

impl TiedScene<'_> {
    /// The bodies as the solve sees them: each its solver body (the constraint layer's: V and
    /// ω after its own step, 1/M, I⁻¹), and a body that moves in the solve mass M/factor and
    /// inertia I/factor (module doc of [`tied_step`]), its correction an unknown of the solve.
    fn solver_bodies(&self, states: &[State]) -> Vec<TiedBody> {
        let factor = self.factor;
        self.bodies
            .iter()
            .zip(states.iter())
            .map(|(body, state)| {
                let rotation = state.orientation.matrix();
                let moves = body.inv_mass > 0.0 && !body.fixed && factor > 0.0;
                let inertia = if moves {
                    rotation * body.inertia_body * rotation.transpose() / factor
                } else {
                    Matrix3::zeros()
                };
                TiedBody {
                    body: solver_body(body, state),
                    mass: if moves { body.mass / factor } else { 0.0 },
                    inertia,
                    correction: [Vector3::zeros(); 2],
                }
            })
            .collect()
    }

    /// A body's material point at `arm` (from its new barycenter): its own-step displacement.
    fn displacement(&self, states: &[State], b: usize, arm: &Vector3<f64>) -> Vector3<f64> {
        let (now, before) = (&states[b], self.start.get(b).unwrap_or(&states[b]));
        let back = before.orientation.matrix() * now.orientation.matrix().transpose();
        now.position + arm - (before.position + back * arm)
    }

    /// Candidates: the nearest surface of each free particle within what it can close.
    fn candidates(
        &self,
        cloth: &Cloth,
        states: &[State],
        solver_bodies: &[TiedBody],
    ) -> Vec<Candidate> {
        let (bodies, dt) = (self.bodies, self.context.dt);
        let gravity = self.loads.gravity.unwrap_or_else(Vector3::zeros);
        let mut candidates: Vec<Candidate> = Vec::new();
        // A response whose particle contacts are not ties (`collision::particle`): the solve
        // holds the attachments only, the contacts act after it (`World`'s velocity passes).
        if !self.context.response.particle().ties() {
            return candidates;
        }
        // A broad phase: each body's reach at the fastest free particle's speed bounds every
        // particle's reach below (sqrt, + and × by positive numbers round monotonically; a NaN
        // speed makes it NaN, which rejects nothing), so a particle farther than it from every
        // body is skipped with the same candidates as before.
        let fastest = (0..cloth.len())
            .filter(|&i| !cloth.pinned[i])
            .map(|i| cloth.start_velocity(i).norm_squared())
            .fold(0.0, |m: f64, v| if v > m || v.is_nan() { v } else { m })
            .sqrt();
        let body_speed =
            |body: &Body, sb: &TiedBody| sb.body.v.norm() + sb.body.omega.norm() * body.radius;
        let widest: Vec<f64> = (bodies.iter().zip(solver_bodies))
            .map(|(body, sb)| {
                let margin = (fastest + body_speed(body, sb) + gravity.norm() * dt) * dt + TOUCHING;
                let reach = body.radius + margin;
                reach * reach
            })
            .collect();
        for i in 0..cloth.len() {
            if cloth.inv_mass(i) == 0.0 || self.attachments.iter().any(|a| a.particle == i) {
                continue;
            }
            let x = cloth.positions[i];
            let far = (states.iter().zip(&widest))
                .all(|(state, &widest)| (x - state.position).norm_squared() > widest);
            if far && self.obstacles.is_empty() {
                continue;
            }
            let v = cloth.start_velocity(i);
            let mut best: Option<Candidate> = None;
            for (b, ((body, state), sb)) in bodies
                .iter()
                .zip(states.iter())
                .zip(solver_bodies)
                .enumerate()
            {
                let Some(shape) = body.shape.as_ref() else {
                    continue;
                };
                if (x - state.position).norm_squared() > widest[b] {
                    continue;
                }
                let margin =
                    (v.norm() + body_speed(body, sb) + gravity.norm() * dt) * dt + TOUCHING;
                let reach = body.radius + margin;
                if (x - state.position).norm_squared() > reach * reach {
                    continue;
                }
                let pose = Pose {
                    position: state.position,
                    rotation: state.orientation.matrix(),
                };
                let Some(cp) = point_shape(&x, shape, &pose, margin) else {
                    continue;
                };
                let arm = cp.point - state.position;
                let c = Candidate {
                    particle: i,
                    body: Some(b),
                    gap: -cp.depth,
                    normal: cp.normal,
                    arm,
                    drift: self.displacement(states, b, &arm) / dt,
                };
                if best.is_none_or(|o| c.gap < o.gap) {
                    best = Some(c);
                }
            }
            let margin = (v.norm() + gravity.norm() * dt) * dt + TOUCHING;
            self.nearest_obstacle(i, &x, margin, &mut best);
            candidates.extend(best);
        }
        candidates
    }

    /// Particle `i` at `x`: an obstacle surface within `margin` nearer than `best` becomes
    /// `best` (the first of equal gaps).
    fn nearest_obstacle(
        &self,
        i: usize,
        x: &Vector3<f64>,
        margin: f64,
        best: &mut Option<Candidate>,
    ) {
        for obstacle in self.obstacles {
            let (gap, normal) = match obstacle.inside(x) {
                Some(p) => (-p.depth, p.normal),
                None => match obstacle.near(x, margin) {
                    Some(near) => near,
                    None => continue,
                },
            };
            let c = Candidate {
                particle: i,
                body: None,
                gap,
                normal,
                arm: Vector3::zeros(),
                drift: Vector3::zeros(),
            };
            if best.is_none_or(|o| c.gap < o.gap) {
                *best = Some(c);
            }
        }
    }

    /// The tie of a candidate contact.
    fn tie_of(&self, c: &Candidate) -> Tie {
        // Arrive on the surface (−gap/h) and no faster: a plastic contact. The sheet's rebound
        // is its springs' (they are inside the same solve); a restitution rule on a 4.5 g
        // particle tied to the body would kick the patch apart step after step and make
        // energy at large steps (measured: +0.2 J at dt = 5 ms on lesson 16).
        // One already inside at the start of the step (gap₀ = gap + h n·drift < 0) is not
        // pushed out by a velocity (energy made): it moves with the surface, the collide
        // phase pushes it out. Against an obstacle (drift 0): stop there.
        let dt = self.context.dt;
        let start_gap = c.gap + dt * c.normal.dot(&c.drift);
        let along = c.normal * ((-c.gap + start_gap.min(0.0)) / dt);
        let kind = if self.context.friction > 0.0 {
            TieKind::Full
        } else {
            TieKind::Normal
        };
        Tie {
            particle: c.particle,
            body: c.body,
            arm: c.arm,
            normal: c.normal,
            kind,
            // Normal: −gap/h; tangent (sticking): the point's own-step drift.
            target: along + (c.drift - c.normal * c.normal.dot(&c.drift)),
            extra: Vector3::zeros(),
            permanent: false,
            impulse: Vector3::zeros(),
        }
    }

    /// Where the particle ends along n relative to the surface, for a velocity v₁ (< 0:
    /// inside).
    fn end_gap(&self, c: &Candidate, v: &Vector3<f64>, sb: &[TiedBody]) -> f64 {
        c.gap + self.context.dt * (v - correction_at(sb, c.body, &c.arm)).dot(&c.normal)
    }

    /// First guess of the contact set: touching, or carried inside by its start velocity and
    /// gravity; against a body also held at the end of the last step and still within a
    /// step's fall (g h²) of its surface (a warm start of the contact set: the rounds correct
    /// it). The gap is measured at the start of the step from the body's material point (it
    /// has moved by its own step since: a body pushed up by the sheet moves away from the
    /// particles that hold it by h·V every step). (Against a body only: an obstacle's
    /// contacts are found afresh each step.)
    fn first_guess(&self, cloth: &Cloth, contacts: &Contacts, sb: &[TiedBody]) -> Vec<bool> {
        let dt = self.context.dt;
        let gravity = self.loads.gravity.unwrap_or_else(Vector3::zeros);
        let was_held = |c: &Candidate| {
            let start_gap = c.gap + dt * c.normal.dot(&c.drift);
            c.body.is_some()
                && contacts.held.get(c.particle) == Some(&Held::Touching)
                && start_gap <= TOUCHING + gravity.norm() * dt * dt
        };
        contacts
            .candidates
            .iter()
            .map(|c| {
                let v = cloth.start_velocity(c.particle) + gravity * dt;
                was_held(c) || c.gap <= TOUCHING || self.end_gap(c, &v, sb) < 0.0
            })
            .collect()
    }

    /// Where each attached particle aims beyond its point after the body's own step: the move
    /// the collide phase gave the body last step ([`BodyMove`]), over h.
    fn leads(&self, states: &[State]) -> Vec<Vector3<f64>> {
        self.attachments
            .iter()
            .map(|a| {
                let state = &states[a.body];
                let arm = state.orientation.matrix() * a.offset_body;
                self.predicted
                    .get(a.body)
                    .map_or(Vector3::zeros(), |m| m.of_point(&arm) / self.context.dt)
            })
            .collect()
    }

    /// The attachments' ties, appended to `ties` in the order of `attachments`.
    fn attach_ties(
        &self,
        states: &[State],
        cloth: &Cloth,
        lead: &[Vector3<f64>],
        ties: &mut Vec<Tie>,
    ) {
        ties.extend(self.attachments.iter().zip(lead).map(|(a, lead)| {
            let state = &states[a.body];
            let arm = state.orientation.matrix() * a.offset_body;
            let target = state.position + arm;
            // The body is already at the end of its own step (`target`): the particle gets
            // there, plus what the collide phase is predicted to move it (`lead`), plus what
            // the correction moves the point.
            Tie {
                particle: a.particle,
                body: Some(a.body),
                arm,
                normal: Vector3::y(),
                kind: TieKind::Full,
                target: (target - cloth.positions[a.particle]) / self.context.dt + lead,
                extra: Vector3::zeros(),
                permanent: true,
                impulse: Vector3::zeros(),
            }
        }));
    }

    /// The rounds of the tied solve, each after the contact set changed (a contact released
    /// because it pulled, a new one found, a stuck one that started to slide), at most
    /// [`TIE_ROUNDS`]; returns the last round's ties (the contacts', then the attachments').
    fn solve_rounds(
        &self,
        cloth: &mut Cloth,
        states: &[State],
        contacts: &Contacts,
        solver_bodies: &mut [TiedBody],
        held_joints: &HeldJoints,
        report: &mut TiedReport,
    ) -> Vec<Tie> {
        let candidates = contacts.candidates;
        let mut active = self.first_guess(cloth, contacts, solver_bodies);
        let mut ties: Vec<Tie> = Vec::new();
        let mut kinds: Vec<(TieKind, Vector3<f64>)> = candidates
            .iter()
            .map(|c| (self.tie_of(c).kind, Vector3::zeros()))
            .collect();
        let lead = self.leads(states);
        let mut index: Vec<usize> = Vec::new();
        for round in 0..TIE_ROUNDS {
            ties.clear();
            index.clear();
            for (k, c) in candidates.iter().enumerate() {
                if active[k] {
                    let mut tie = self.tie_of(c);
                    (tie.kind, tie.extra) = kinds[k];
                    ties.push(tie);
                    index.push(k);
                }
            }
            self.attach_ties(states, cloth, &lead, &mut ties);
            let step = cloth.solve_tied(&mut ties, solver_bodies, &held_joints.filter);
            report.rounds = round + 1;
            report.iterations += step.iterations;
            let mut changed =
                self.release_or_slide(&ties, &index, candidates, &mut active, &mut kinds);
            for (k, c) in candidates.iter().enumerate() {
                if !active[k]
                    && self.end_gap(c, &cloth.velocities[c.particle], solver_bodies) < -TOUCHING
                {
                    active[k] = true;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        ties
    }

    /// After a solve: a contact that pulls lets go, one out of its friction cone slides with
    /// the bounded impulse, a sliding one's impulse follows its new direction. Whether the
    /// contact set changed.
    fn release_or_slide(
        &self,
        ties: &[Tie],
        index: &[usize],
        candidates: &[Candidate],
        active: &mut [bool],
        kinds: &mut [(TieKind, Vector3<f64>)],
    ) -> bool {
        let mut changed = false;
        for (tie, &k) in ties.iter().zip(index) {
            let n = tie.normal;
            let normal_impulse = tie.impulse.dot(&n);
            if normal_impulse < 0.0 {
                // It would pull the particle onto the body: let go (B&W §6.2).
                active[k] = false;
                kinds[k] = (self.tie_of(&candidates[k]).kind, Vector3::zeros());
                changed = true;
                continue;
            }
            if self.context.friction > 0.0 {
                let tangential = match tie.kind {
                    TieKind::Full => tie.impulse - n * normal_impulse,
                    TieKind::Normal => tie.extra,
                };
                let limit = self.context.friction * normal_impulse;
                let size = tangential.norm();
                if tie.kind == TieKind::Full && size > limit {
                    // Out of the cone: slide, with the bounded impulse.
                    kinds[k] = (TieKind::Normal, tangential * (limit / size));
                    changed = true;
                } else if tie.kind == TieKind::Normal && size > 0.0 {
                    let bounded = tangential * (limit / size);
                    if (bounded - tie.extra).norm() > 1e-12 {
                        kinds[k].1 = bounded;
                    }
                }
            }
        }
        changed
    }

    /// The energy the ties took (module doc of [`tied_step`]): the impulses' work along the
    /// particle's motion relative to the body's material point; and the contacts counted.
    fn book_ties(
        &self,
        cloth: &Cloth,
        states: &[State],
        ties: &[Tie],
        solver_bodies: &[TiedBody],
        report: &mut TiedReport,
    ) {
        for tie in ties {
            let drift = tie.body.map_or(Vector3::zeros(), |b| {
                self.displacement(states, b, &tie.arm) / self.context.dt
            });
            let u = cloth.velocities[tie.particle]
                - drift
                - correction_at(solver_bodies, tie.body, &tie.arm);
            report.energy_taken -= (tie.impulse + tie.extra).dot(&u);
        }
        report.contacts = ties
            .iter()
            .filter(|t| !t.permanent && t.body.is_some())
            .count();
        report.obstacle_contacts = ties.iter().filter(|t| t.body.is_none()).count();
    }

    /// The bodies take the opposite impulses: through their correction when they are
    /// unknowns of the solve, summed afterwards when they are not (factor 0).
    fn push_bodies(&self, states: &mut [State], ties: &[Tie], solver_bodies: &[TiedBody]) {
        let mut pushed = vec![[Vector3::zeros(); 2]; self.bodies.len()];
        for tie in ties {
            if let Some(b) = tie.body {
                let j = tie.impulse + tie.extra;
                pushed[b][0] -= j;
                pushed[b][1] -= tie.arm.cross(&j);
            }
        }
        for (((body, state), sb), push) in self
            .bodies
            .iter()
            .zip(states.iter_mut())
            .zip(solver_bodies)
            .zip(&pushed)
        {
            if body.fixed || body.inv_mass == 0.0 {
                continue;
            }
            if sb.mass == 0.0 {
                state.linear_momentum += push[0];
                state.angular_momentum += push[1];
                continue;
            }
            let [dv, dw] = sb.correction;
            if dv == Vector3::zeros() && dw == Vector3::zeros() {
                continue;
            }
            state.linear_momentum += dv * sb.mass;
            state.angular_momentum += sb.inertia * dw;
            move_body(state, &dv, &dw, self.context.dt);
        }
    }

    /// Tied particles: the body turned by the rotation h Y_ω, their tie moved them along its
    /// tangent h Y_ω × r; the difference in the tied components, (I − S)((R(h Y_ω) − I) r −
    /// h Y_ω × r) = O(h² |Y_ω|² r), is made up within the step (module doc of
    /// `hold_attachments`), so that an attached particle stays on its point and a contact on
    /// the surface to round-off.
    fn close_turns(
        &self,
        cloth: &mut Cloth,
        states: &mut [State],
        ties: &[Tie],
        solver_bodies: &[TiedBody],
        report: &mut TiedReport,
    ) {
        for tie in ties {
            let Some(b) = tie.body else { continue };
            let sb = &solver_bodies[b];
            if sb.mass == 0.0 {
                continue;
            }
            let mut gap = turn_gap(&sb.correction[1], &tie.arm, self.context.dt);
            if tie.kind == TieKind::Normal {
                gap = tie.normal * tie.normal.dot(&gap);
            }
            let made_up = close_gap(
                cloth,
                tie.particle,
                &mut states[b],
                &tie.arm,
                &gap,
                self.context.dt,
            );
            if tie.permanent {
                let point = states[b].position + tie.arm;
                report.attach_impulse[0] += made_up;
                report.attach_impulse[1] += point.cross(&made_up);
            }
        }
    }

    /// The attachments' reactions on the cloth (their point on the body at the step's end).
    /// (`attach_ties` appends them after the contacts, in the order of `attachments`.)
    fn attach_reactions(&self, states: &[State], ties: &[Tie], report: &mut TiedReport) {
        for (tie, a) in ties.iter().filter(|t| t.permanent).zip(self.attachments) {
            let state = &states[a.body];
            let point = state.position + state.orientation.matrix() * a.offset_body;
            let j = tie.impulse + tie.extra;
            report.attach_impulse[0] += j;
            report.attach_impulse[1] += point.cross(&j);
        }
    }
}

/// The joints' velocity rows on the bodies that move in a tied solve (`cloth::ties`, "Joints
/// on the bodies"): `J Y = 0` over the stacked corrections of the bodies any joint touches
/// (a fixed body, the world, or a body whose integrator ignores the correction, factor 0,
/// has no correction: its columns are dropped). The rows are `joints::rows_of` at the bodies'
/// poses after their own step, where the joints' own step left them (J u = 0).
///
/// Why inside the solve, not after it: the joints are stepped first (`integrators::system`,
/// then their projection), the cloth after. Held apart, the cloth's pull on a hinged pole
/// arrives after the hinge has been solved: the pull turns the pole within the cloth's step
/// (ω_z = −1.4e-3 rad/s after every step of a 2 kg pole under a 0.3 kg flag), the next step's
/// projection turns it back, the hinge reads (M + m) g a step late (6.5e-5 relative) and the
/// projection's energy, booked as the joint correction, climbs 0.055 J/s while nothing moves.
/// Projecting again after the cloth's step would stop the pole but not the work: the
/// projection would move the pole, and with it its attached particles, every step. Inside
/// the solve the pole never leaves the hinge's motions: at rest it does not move, the hinge
/// carries (M + m) g within the step, and no ledger row changes.
pub(super) struct HeldJoints {
    pub(super) filter: BodyJoints,
    /// The rows, each with its joint (`Row::joint`), and their matrix over the stacked
    /// corrections (rows × 6k).
    rows: Vec<Row>,
    matrix: DMatrix<f64>,
}

impl HeldJoints {
    /// The rows of the joints that touch a body for which `moves` holds, over the stacked
    /// corrections of those bodies.
    pub(super) fn new(
        links: &Links,
        states: &[State],
        moves: impl Fn(usize) -> bool,
    ) -> HeldJoints {
        let mut bodies: Vec<usize> = Vec::new();
        for joint in &links.joints {
            for b in std::iter::once(joint.a).chain(joint.b) {
                if moves(b) && !bodies.contains(&b) {
                    bodies.push(b);
                }
            }
        }
        let mut rows = Vec::new();
        if bodies.is_empty() {
            return HeldJoints {
                filter: BodyJoints::default(),
                rows,
                matrix: DMatrix::zeros(0, 0),
            };
        }
        bodies.sort_unstable();
        let poses: Vec<JointPose> = states.iter().map(JointPose::of_state).collect();
        for (index, joint) in links.joints.iter().enumerate() {
            if moves(joint.a) || joint.b.is_some_and(&moves) {
                let b = joint.b.map_or(JointPose::WORLD, |b| poses[b]);
                rows_of(joint, index, &poses[joint.a], &b, &mut rows);
            }
        }
        let column = |b: usize| bodies.iter().position(|&x| x == b);
        let mut matrix = DMatrix::zeros(rows.len(), 6 * bodies.len());
        for (k, row) in rows.iter().enumerate() {
            let sides = [
                (Some(row.a()), row.lin_a(), row.ang_a()),
                (row.b(), row.lin_b(), row.ang_b()),
            ];
            for (body, lin, ang) in sides {
                let Some(g) = body.and_then(column) else {
                    continue;
                };
                for c in 0..3 {
                    matrix[(k, 6 * g + c)] += lin[c];
                    matrix[(k, 6 * g + 3 + c)] += ang[c];
                }
            }
        }
        HeldJoints {
            filter: BodyJoints::new(bodies, &matrix),
            rows,
            matrix,
        }
    }

    /// Each joint's impulse on its body A over the step (force: N·s; torque about A's
    /// barycenter: N·m·s), added to `out` (one entry per joint): W = M_b Y_b + Σ_ties
    /// [λ + e; r × (λ + e)] on the held bodies, W = Jᵀ μ solved for μ by least squares
    /// (the part of W a solve stopped at its tolerance leaves outside range(Jᵀ) is no joint's),
    /// then Σ over each joint's rows of (lin_A μ, ang_A μ).
    fn impulses(&self, ties: &[Tie], solver_bodies: &[TiedBody], out: &mut [Loads]) {
        if self.filter.is_empty() || self.rows.is_empty() {
            return;
        }
        let bodies = &self.filter.bodies;
        let mut wrench = DVector::<f64>::zeros(6 * bodies.len());
        for (g, &b) in bodies.iter().enumerate() {
            let sb = &solver_bodies[b];
            let [dv, dw] = sb.correction;
            let (lin, ang) = (dv * sb.mass, sb.inertia * dw);
            for c in 0..3 {
                wrench[6 * g + c] += lin[c];
                wrench[6 * g + 3 + c] += ang[c];
            }
        }
        for tie in ties {
            let Some(g) = tie.body.and_then(|b| bodies.iter().position(|&x| x == b)) else {
                continue;
            };
            let j = tie.impulse + tie.extra;
            let t = tie.arm.cross(&j);
            for c in 0..3 {
                wrench[6 * g + c] += j[c];
                wrench[6 * g + 3 + c] += t[c];
            }
        }
        self.reactions(wrench, out);
    }

    /// The joints' share of the held bodies' wrench W (stacked as the corrections, N·s and
    /// N·m·s about each barycenter), added to `out` per joint: W = Jᵀ μ solved for μ by least
    /// squares, then Σ over each joint's rows of (lin_A μ, ang_A μ).
    pub(super) fn reactions(&self, wrench: DVector<f64>, out: &mut [Loads]) {
        let svd = self.matrix.transpose().svd(true, true);
        let largest = svd.singular_values.iter().fold(0.0_f64, |m, v| m.max(*v));
        let Ok(mu) = svd.solve(&wrench, 1e-12 * largest) else {
            return;
        };
        for (row, &m) in self.rows.iter().zip(mu.iter()) {
            if let Some(load) = out.get_mut(row.owner) {
                load.force += row.lin_a() * m;
                load.torque += row.ang_a() * m;
            }
        }
    }
}
