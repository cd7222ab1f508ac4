//! Particles against bodies, both ways: a cloth particle is a point, a body its convex shape.
//!
//! Which path a cloth takes depends on its integrator:
//! - `implicit-euler`: [`tied_step`] holds every contact (bodies and obstacles) and every
//!   attachment *inside* backward Euler's linear solve (`cloth::ties`, Baraff & Witkin's
//!   constraint filter with the body's velocity change as an unknown of the same solve),
//!   each tied particle ending the step on the body's surface; the velocity pass below is
//!   not used, and the collide phase's push-out only handles what is still more than
//!   [`SLOP`] inside after the positions moved (nothing, on lesson 16).
//! - `symplectic-euler`: the two passes below for contacts, and [`hold_attachments`] for
//!   its attachments (impulses after the velocity half, one small solve per body).
//!
//! Attached bodies stay consistent within the step: the joints on a body that moves in the
//! implicit solve are held inside it ([`tied_step`], "Joints"), and particles attached to a
//! body the rigid collide phase then moves are carried with it ([`carry_attachments`]),
//! having aimed at where its last move put it ([`BodyMove`]).
//!
//! # Two passes, on velocities first (as for obstacles, `cloth::contact`)
//!
//! A push-out that moves a particle out of a body stretches its springs: energy made by the
//! contact, taken again by the springs' damping a step later — a resting cube would trade
//! millijoules with the sheet every step and tremble. So contacts act on the velocities
//! *before* the particles move ([`approach_bodies`], in the integrate phase, after the bodies
//! and the particles' velocities were stepped). The body is then already where it ends the
//! step, so a free particle at signed gap g from the body's new pose (g < 0: inside it) must
//! end outside it:
//!
//! ```text
//! v_p·n ≥ −g/h + b,   b = −e u₀,n if it touches (g ≤ 0) after a fast approach u₀,n, else 0
//! ```
//!
//! with u₀,n the relative normal velocity at the start of the step (a particle carrying the
//! body's weight is driven into it within every step, and that is no impact). The sweeps
//! below reach it with impulses +J on the particle (Δv_p·n = Δj/m_p) and −J on the body at
//! the contact point, friction on the relative slip within μ j_n. Known limit: the particle's
//! own mass takes the impulse, not the sheet behind it, so its springs reach the body only
//! through later steps (the implicit path, [`tied_step`], does it within the step).
//!
//! # The second pass, after the positions moved
//!
//! In the collide phase, every free particle inside a body's shape
//! (`geometry::point_shape`: depth > 0, normal n out of the body, contact point c on its
//! surface, r = c − x_body) gets an impulse J, and the body −J at c, so the momentum of
//! particle + body is kept to round-off by every contact:
//!
//! ```text
//! u    = v_p − (v_b + ω × r)                    relative velocity, u_n = u·n < 0: approaching
//! k(d) = 1/m_p + 1/M + d·((I⁻¹(r × d)) × r)     effective inverse mass along a unit d
//! j_n  = −(1 + e) u_n / k(n)                     e = restitution if −u_n > BOUNCE_STEPS·|g|·dt, else 0
//! t    = u_t/|u_t|,  u_t = u − u_n n
//! j_t  = min(|u_t| / k(t), μ j_n)                Coulomb: stop the slip, within the cone
//! J    = j_n n − j_t t
//!
//! With several particles on one body the impulses are found by a few sequential sweeps
//! ([`SWEEPS`]) over its contacts with accumulated impulses (projected Gauss–Seidel: each
//! sweep corrects the impulse found so far, the normal total stays ≥ 0 and aims at the
//! velocity −e·u_n the contact started with, the tangential total stays in the cone μ j_n), so
//! that a body resting on many particles is held by all of them, not the first one met.
//! They run on the contact solvers' solver bodies and axes (`collision::solver_body`): the
//! body and each touching particle are solver bodies (a particle has no rotational inertia
//! and lever 0), k(n) is the normal axis's k, and each impulse is applied to both ends at once.
//! v_p ← v_p + J/m_p,   P ← P − J,   L ← L − r × J
//! x_p ← x_p + depth n                            the particle is pushed out, not the body
//! ```
//!
//! A point against a rigid body is one contact with a lever arm, so the rule above is the
//! exact two-body impulse (no energy made for e ≤ 1, μ ≥ 0). The push-out moves a light
//! particle, never the body (moving the body would make it jitter on a sheet of hundreds of
//! particles). The world measures the energy of the whole collide phase before and after and
//! books the change in its ledger.

use super::body::Body;
use super::cloth::{BodyJoints, Cloth, Held, Tie, TiedBody};
use super::collision::geometry::{point_shape, Pose};
use super::collision::solver_body::{Axis, SolverBody};
use super::effects::Loads;
use super::joints::{rows_of, Links, Pose as JointPose, Row};
use super::state::State;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// Sweeps over a body's contacts (module doc): one sweep lets the first particle met take
/// all of a resting body's weight and tilts it; a few sweeps with accumulated impulses share it.
pub const SWEEPS: usize = 4;

/// One contact of a particle with a body, while the sweeps run: a row between two solver
/// bodies ([`Sweeps`]), the particle's (A, lever 0) and the body's (B, lever `arm`).
#[derive(Debug, Clone, Copy)]
struct Touch {
    particle: usize,
    /// The particle's solver body in [`Sweeps::motions`].
    index: usize,
    /// The normal axis: d = n out of the body, k = 1/m_p + 1/M + (r×n)·I⁻¹(r×n).
    normal: Axis,
    /// Contact point relative to the barycenter, m.
    arm: Vector3<f64>,
    /// The normal velocity the sweeps aim at, −e·u_n at the start (0 for a resting contact).
    target: f64,
    /// The target is the particle's own normal velocity, not the relative one (pass 1: the
    /// body is already at the end of its step, so where the particle ends is its business).
    absolute: bool,
    /// Accumulated normal impulse (≥ 0) and tangential impulse, N·s.
    normal_impulse: f64,
    tangential_impulse: Vector3<f64>,
}

/// One body's contacts with a cloth's particles on solver bodies (`collision::solver_body`):
/// the body at index 0, each touching particle after it, a point mass with no rotational
/// inertia.
#[derive(Debug, Clone, Default)]
struct Sweeps {
    motions: Vec<SolverBody>,
    touches: Vec<Touch>,
}

impl Sweeps {
    /// Starts a body's contacts: its solver body from its momenta, at the pose of `inv_inertia`
    /// (a fixed body is the world: no inverse mass, no inverse inertia).
    fn start(&mut self, body: &Body, state: &State, inv_inertia: &Matrix3<f64>) {
        self.touches.clear();
        self.motions.clear();
        self.motions.push(SolverBody::new(
            state.linear_momentum * body.inv_mass,
            state.angular_momentum,
            body.inv_mass,
            *inv_inertia,
        ));
    }

    /// Adds particle `particle`'s contact at `arm` with normal n (out of the body).
    fn touch(
        &mut self,
        cloth: &Cloth,
        particle: usize,
        normal: &Vector3<f64>,
        arm: Vector3<f64>,
        (target, absolute): (f64, bool),
    ) {
        let index = self.motions.len();
        self.motions.push(SolverBody::new(
            cloth.particle_velocity(particle),
            Vector3::zeros(),
            cloth.inv_mass(particle),
            Matrix3::zeros(),
        ));
        let normal = Axis::new(
            *normal,
            (index, &Vector3::zeros()),
            Some((0, &arm)),
            &self.motions,
        );
        self.touches.push(Touch {
            particle,
            index,
            normal,
            arm,
            target,
            absolute,
            normal_impulse: 0.0,
            tangential_impulse: Vector3::zeros(),
        });
    }

    /// u = v_p − (v_b + ω × r) of particle `particle` at the body's point `arm` (before it
    /// is a contact), m/s.
    fn approach(&self, cloth: &Cloth, particle: usize, arm: &Vector3<f64>) -> Vector3<f64> {
        cloth.particle_velocity(particle) - self.motions[0].point_velocity(arm)
    }

    /// u = v_p − (v_b + ω × r) of a contact, m/s.
    fn relative_velocity(&self, t: &Touch) -> Vector3<f64> {
        self.motions[t.index].v - self.motions[0].point_velocity(&t.arm)
    }

    /// [`SWEEPS`] projected Gauss–Seidel sweeps over the contacts (module doc), forward then
    /// backward so that no particle of the grid is favoured by its index; then the particles'
    /// velocities and the body's momenta take what the sweeps applied (the body −ΣJ, so
    /// particle + body keep their momentum to round-off).
    fn solve(&mut self, cloth: &mut Cloth, state: &mut State, friction: f64) {
        let count = self.touches.len();
        for pass in 0..SWEEPS {
            for k in 0..count {
                let k = if pass % 2 == 0 { k } else { count - 1 - k };
                let t = self.touches[k];
                let n = t.normal.d;
                let u = self.relative_velocity(&t);
                // Normal: reach the target velocity, the accumulated impulse never pulls.
                let particle = &self.motions[t.index];
                let total = if t.absolute {
                    let vn = particle.v.dot(&n);
                    t.normal_impulse + (t.target - vn) / particle.inv_mass
                } else {
                    t.normal_impulse + (t.target - u.dot(&n)) / t.normal.k
                }
                .max(0.0);
                let mut impulse = n * (total - t.normal_impulse);
                let touch = &mut self.touches[k];
                touch.normal_impulse = total;
                // Tangential: stop the slip, within the cone μ j_n.
                if friction > 0.0 {
                    let ut = u - n * u.dot(&n);
                    let slip = ut.norm();
                    let mut jt = t.tangential_impulse;
                    if slip > 0.0 {
                        let d = ut / slip;
                        let along = Axis::new(
                            d,
                            (t.index, &Vector3::zeros()),
                            Some((0, &t.arm)),
                            &self.motions,
                        );
                        jt -= d * (slip / along.k);
                    }
                    let limit = friction * total;
                    if jt.norm() > limit {
                        jt *= limit / jt.norm();
                    }
                    impulse += jt - t.tangential_impulse;
                    self.touches[k].tangential_impulse = jt;
                }
                self.motions[t.index].apply_at(&impulse, &Vector3::zeros());
                self.motions[0].apply_at(&-impulse, &t.arm);
            }
        }
        let mut total = Vector3::zeros();
        for t in &self.touches {
            cloth.velocities[t.particle] = self.motions[t.index].v;
            total += t.normal.d * t.normal_impulse + t.tangential_impulse;
        }
        if !self.motions[0].fixed() {
            state.linear_momentum -= total;
            state.angular_momentum = self.motions[0].l;
        }
    }
}

/// One particle–body contact pass over a cloth: returns the number of contacts.
///
/// `bounce_speed`: approaches slower than this do not bounce.
pub fn collide_bodies(
    cloth: &mut Cloth,
    bodies: &[Body],
    states: &mut [State],
    restitution: f64,
    friction: f64,
    bounce_speed: f64,
) -> usize {
    let mut count = 0;
    let mut sweeps = Sweeps::default();
    for (body, state) in bodies.iter().zip(states.iter_mut()) {
        let Some(shape) = body.shape.as_ref() else {
            continue;
        };
        let rotation = state.orientation.matrix();
        let pose = Pose {
            position: state.position,
            rotation,
        };
        // A quick reject: particles farther than the body's radius from its barycenter.
        let reach = body.radius;
        let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
        sweeps.start(body, state, &inv_inertia);
        // An implicit-euler cloth's ties end its particles on the surface: what is left
        // inside at round-off is not a contact.
        let slop = if cloth.integrator == crate::physics::cloth::ClothIntegrator::ImplicitEuler {
            SLOP
        } else {
            0.0
        };
        for i in 0..cloth.len() {
            // Attached particles are held inside the solve, not pushed out.
            if cloth.inv_mass(i) == 0.0 || cloth.attached.iter().any(|a| a.0 == i) {
                continue;
            }
            let x = cloth.positions[i];
            if (x - state.position).norm_squared() > reach * reach {
                continue;
            }
            let Some(cp) = point_shape(&x, shape, &pose, 0.0) else {
                continue;
            };
            if cp.depth <= slop {
                continue;
            }
            let n = cp.normal;
            cloth.displace(i, &(n * cp.depth));
            let arm = cp.point - state.position;
            let un = sweeps.approach(cloth, i, &arm).dot(&n);
            let e = if -un > bounce_speed { restitution } else { 0.0 };
            sweeps.touch(cloth, i, &n, arm, ((-e * un).max(0.0), false));
        }
        count += sweeps.touches.len();
        sweeps.solve(cloth, state, friction);
    }
    count
}

/// What the velocity pass against bodies did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Approach {
    /// Particle–body contacts of the pass.
    pub contacts: usize,
    /// Energy the pass took, J: the kinetic energy of the approaches the contacts had at the
    /// start of the step, and what friction removed (see [`approach_bodies`]).
    pub energy_taken: f64,
}

/// Pass 1 against bodies (module doc): between the particles' velocity half-step and their
/// positions' update, with every body already at the end of its step (`states`; `start` are
/// the bodies' states at the start of the step). Each free particle whose velocity would
/// carry it into a body within the step is stopped on its surface (or bounces off it) by
/// equal and opposite impulses.
///
/// Energy taken, as for obstacles: the measured kinetic energy the impulses removed from the
/// touched particles and the body, less what the step's own forces added to the approach
/// within the step (a resting contact cancels that before it exists: booking it would count a
/// resting cube's weight as a loss every step),
///
/// ```text
/// taken = (T_before − T_after) − Σ_contacts ½ (min(0, u_n)² − min(0, u₀,n)²) / k(n)
/// ```
///
/// with u_n the relative normal velocity after the velocity half, u₀,n at the start of the step.
#[allow(clippy::too_many_arguments)]
pub fn approach_bodies(
    cloth: &mut Cloth,
    bodies: &[Body],
    start: &[State],
    states: &mut [State],
    restitution: f64,
    friction: f64,
    bounce_speed: f64,
    dt: f64,
) -> Approach {
    let mut report = Approach::default();
    let mut sweeps = Sweeps::default();
    for ((body, state), before) in bodies.iter().zip(states.iter_mut()).zip(start) {
        let Some(shape) = body.shape.as_ref() else {
            continue;
        };
        let rotation = state.orientation.matrix();
        let pose = Pose {
            position: state.position,
            rotation,
        };
        let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
        let omega = inv_inertia * state.angular_momentum;
        let body_speed = state.linear_momentum.norm() * body.inv_mass + omega.norm() * body.radius;
        let start_rotation = before.orientation.matrix();
        let start_inv_inertia = start_rotation * body.inv_inertia_body * start_rotation.transpose();
        let start_omega = start_inv_inertia * before.angular_momentum;
        let start_velocity = before.linear_momentum * body.inv_mass;
        sweeps.start(body, state, &inv_inertia);
        let mut within = 0.0;
        for i in 0..cloth.len() {
            if cloth.inv_mass(i) == 0.0 {
                continue;
            }
            let x = cloth.positions[i];
            // What the particle and the body's surface can close within the step.
            let margin = (cloth.velocities[i].norm() + body_speed) * dt;
            let reach = body.radius + margin;
            if (x - state.position).norm_squared() > reach * reach {
                continue;
            }
            let Some(cp) = point_shape(&x, shape, &pose, margin) else {
                continue;
            };
            // Signed: < 0 when the body's new pose already holds the particle inside.
            let gap = -cp.depth;
            let n = cp.normal;
            let arm = cp.point - state.position;
            let un = sweeps.approach(cloth, i, &arm).dot(&n);
            // Bounce or rest is decided by the approach the pair had at the start of the
            // step: a particle carrying the body's weight is driven into it at h·F/m_p within
            // every step (0.3 m/s on a trampoline), and that is no impact.
            let u0 = cloth.start_velocity(i) - (start_velocity + start_omega.cross(&arm));
            let approach = u0.dot(&n).min(0.0);
            // The body is already where it ends the step: the particle must end outside it,
            // v_p·n ≥ −gap/h, and leave at e times a fast approach when it touches.
            let bounce = if gap <= 0.0 && -approach > bounce_speed {
                -restitution * approach
            } else {
                0.0
            };
            let target = -gap / dt + bounce;
            if cloth.velocities[i].dot(&n) >= target {
                continue;
            }
            sweeps.touch(cloth, i, &n, arm, (target, true));
            let k_n = sweeps.touches.last().map_or(f64::NAN, |t| t.normal.k);
            within += 0.5 * (un.min(0.0).powi(2) - approach * approach) / k_n;
        }
        if sweeps.touches.is_empty() {
            continue;
        }
        let kinetic = |cloth: &Cloth, state: &State, touches: &[Touch]| {
            let rigid = 0.5 * state.linear_momentum.norm_squared() * body.inv_mass
                + 0.5
                    * state
                        .angular_momentum
                        .dot(&(inv_inertia * state.angular_momentum));
            touches.iter().fold(rigid, |t, c| {
                t + 0.5 * cloth.masses[c.particle] * cloth.velocities[c.particle].norm_squared()
            })
        };
        let before_sweeps = kinetic(cloth, state, &sweeps.touches);
        sweeps.solve(cloth, state, friction);
        let after_sweeps = kinetic(cloth, state, &sweeps.touches);
        report.contacts += sweeps.touches.len();
        report.energy_taken += before_sweeps - after_sweeps - within;
    }
    report
}

// ---------------------------------------------------------------------------------------------
// Contacts inside the implicit solve (`cloth::ties`)
// ---------------------------------------------------------------------------------------------

/// The most solves of one step's tied system (each after the contact set changed: a contact
/// released because it pulled, a new one found because the particle would go inside, a stuck
/// contact that started to slide). What a last change leaves is for the collide phase.
pub const TIE_ROUNDS: usize = 5;

/// A gap (m) below which a particle counts as touching.
const TOUCHING: f64 = 1e-9;

/// A depth (m) the collide phase leaves to an `implicit-euler` cloth's particles: its ties
/// put them on the surface, up to round-off (the body's turn is made up exactly, see the
/// end of [`tied_step`]); a particle a step's last round let go may end a few nm inside,
/// and the next step's tie moves it with the surface (pushing it out would stretch its
/// springs: energy made).
pub const SLOP: f64 = 1e-8;

/// How far a body's position moves under a constant extra force F over a step, in units of
/// h²F/M: what its integrator makes of the ties' impulse J = F h when the correction
/// ΔV = J/M is applied after the step (symplectic Euler drifts with the new velocity: 1;
/// rk4 and the kick–drift–kick splittings: ½; explicit Euler: 0).
pub fn position_factor(integrator: super::integrators::Integrator) -> f64 {
    use super::integrators::Integrator as I;
    match integrator {
        I::EulerSeed | I::Euler => 0.0,
        I::SymplecticEuler => 1.0,
        I::Rk4 | I::Splitting | I::ExactSplitting | I::ExactSplitting4 => 0.5,
    }
}

/// A particle held to a body's point (`attach`): its offset in the body's frame at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    pub particle: usize,
    pub body: usize,
    /// The particle's position in the body's frame (relative to the barycenter), m.
    pub offset_body: Vector3<f64>,
}

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

/// What the attachments of an explicit cloth did over a step ([`hold_attachments`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AttachReport {
    /// The kinetic energy the impulses took, J (≥ 0).
    pub taken: f64,
    /// Σ J_a on the particles (N·s) and its moment about the world origin, Σ x_a × J_a
    /// (N·m·s), x_a the attachment's point.
    pub impulse: [Vector3<f64>; 2],
}

/// One velocity half of an `implicit-euler` cloth with its contacts against the bodies and
/// the obstacles, and its attachments, all inside the linear solve (`cloth::ties`). `start`:
/// the bodies' states at the start of the step; `states`: after their own step, where the
/// contacts are measured. The cloth's positions are not moved (the caller's position half).
///
/// # Where the particle must end: positions, not velocities
///
/// The body has already moved by its own step when the cloth steps; what its correction
/// (ΔV, Δω) adds to its position is `factor`·h·(ΔV, Δω) ([`position_factor`]). So a particle
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
/// the step, and carried back after the response ([`carry_attachments`]) it would be pulled
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
#[allow(clippy::too_many_arguments)]
pub fn tied_step(
    cloth: &mut Cloth,
    loads: &crate::physics::cloth::ClothLoads,
    dt: f64,
    bodies: &[Body],
    start: &[State],
    states: &mut [State],
    obstacles: &[crate::physics::collision::Obstacle],
    attachments: &[Attachment],
    friction: f64,
    factor: f64,
    links: &Links,
    joint_impulses: &mut Vec<Loads>,
    predicted: &[BodyMove],
) -> TiedReport {
    use crate::physics::cloth::TieKind;
    use crate::physics::collision::detect;
    cloth.begin_tied_step(loads, dt);
    let gravity = loads.gravity.unwrap_or_else(Vector3::zeros);
    let mut solver_bodies: Vec<TiedBody> = bodies
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
            let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
            TiedBody {
                mass: if moves { body.mass / factor } else { 0.0 },
                inertia,
                velocity: state.linear_momentum * body.inv_mass,
                angular_velocity: inv_inertia * state.angular_momentum,
                correction: [Vector3::zeros(); 2],
            }
        })
        .collect();
    // The joints on the bodies that move in the solve, held inside it (`cloth::ties`,
    // "Joints on the bodies").
    let held_joints = HeldJoints::new(links, states, &solver_bodies);
    // A body's material point at `arm` (from its new barycenter): its own-step displacement.
    let displacement = |b: usize, arm: &Vector3<f64>| -> Vector3<f64> {
        let (now, before) = (&states[b], start.get(b).unwrap_or(&states[b]));
        let back = before.orientation.matrix() * now.orientation.matrix().transpose();
        now.position + arm - (before.position + back * arm)
    };
    // Candidates: the nearest surface of each free particle within what it can close.
    let held: Vec<Held> = cloth.held().to_vec();
    let mut candidates: Vec<Candidate> = Vec::new();
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
        |body: &Body, sb: &TiedBody| sb.velocity.norm() + sb.angular_velocity.norm() * body.radius;
    let widest: Vec<f64> = (bodies.iter().zip(&solver_bodies))
        .map(|(body, sb)| {
            let margin = (fastest + body_speed(body, sb) + gravity.norm() * dt) * dt + TOUCHING;
            let reach = body.radius + margin;
            reach * reach
        })
        .collect();
    for i in 0..cloth.len() {
        if cloth.inv_mass(i) == 0.0 || attachments.iter().any(|a| a.particle == i) {
            continue;
        }
        let x = cloth.positions[i];
        let far = (states.iter().zip(&widest))
            .all(|(state, &widest)| (x - state.position).norm_squared() > widest);
        if far && obstacles.is_empty() {
            continue;
        }
        let v = cloth.start_velocity(i);
        let mut best: Option<Candidate> = None;
        for (b, ((body, state), sb)) in bodies
            .iter()
            .zip(states.iter())
            .zip(&solver_bodies)
            .enumerate()
        {
            let Some(shape) = body.shape.as_ref() else {
                continue;
            };
            if (x - state.position).norm_squared() > widest[b] {
                continue;
            }
            let margin = (v.norm() + body_speed(body, sb) + gravity.norm() * dt) * dt + TOUCHING;
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
                drift: displacement(b, &arm) / dt,
            };
            if best.is_none_or(|o| c.gap < o.gap) {
                best = Some(c);
            }
        }
        for obstacle in obstacles {
            let margin = (v.norm() + gravity.norm() * dt) * dt + TOUCHING;
            let (gap, normal) = match detect::inside(obstacle, &x) {
                Some(p) => (-p.depth, p.normal),
                None => match detect::near(obstacle, &x, margin) {
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
                best = Some(c);
            }
        }
        candidates.extend(best);
    }
    // The correction's velocity at a candidate's point, (Y_V + Y_ω × r).
    let correction_at = |sb: &[TiedBody], body: Option<usize>, arm: &Vector3<f64>| {
        body.map_or(Vector3::zeros(), |b| {
            let [dv, dw] = sb[b].correction;
            dv + dw.cross(arm)
        })
    };
    let tie_of = |c: &Candidate| {
        // Arrive on the surface (−gap/h) and no faster: a plastic contact. The sheet's rebound
        // is its springs' (they are inside the same solve); a restitution rule on a 4.5 g
        // particle tied to the body would kick the patch apart step after step and make
        // energy at large steps (measured: +0.2 J at dt = 5 ms on lesson 16).
        // One already inside at the start of the step (gap₀ = gap + h n·drift < 0) is not
        // pushed out by a velocity (energy made): it moves with the surface, the collide
        // phase pushes it out. Against an obstacle (drift 0): stop there.
        let start_gap = c.gap + dt * c.normal.dot(&c.drift);
        let along = c.normal * ((-c.gap + start_gap.min(0.0)) / dt);
        let kind = if friction > 0.0 {
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
    };
    // Where the particle ends along n relative to the surface, for a velocity v₁ (< 0: inside).
    let end_gap = |c: &Candidate, v: &Vector3<f64>, sb: &[TiedBody]| {
        c.gap + dt * (v - correction_at(sb, c.body, &c.arm)).dot(&c.normal)
    };
    // First guess: touching, or carried inside by its start velocity and gravity; against a
    // body also held at the end of the last step and still within a step's fall (g h²) of
    // its surface (a warm start of the contact set: the rounds below correct it).
    // The gap is measured at the start of the step from the body's material point (it has
    // moved by its own step since: a body pushed up by the sheet moves away from the
    // particles that hold it by h·V every step).
    // (Against a body only: an obstacle's contacts are found afresh each step.)
    let was_held = |c: &Candidate| {
        let start_gap = c.gap + dt * c.normal.dot(&c.drift);
        c.body.is_some()
            && held.get(c.particle) == Some(&Held::Touching)
            && start_gap <= TOUCHING + gravity.norm() * dt * dt
    };
    let mut active: Vec<bool> = candidates
        .iter()
        .map(|c| {
            let v = cloth.start_velocity(c.particle) + gravity * dt;
            was_held(c) || c.gap <= TOUCHING || end_gap(c, &v, &solver_bodies) < 0.0
        })
        .collect();
    let mut ties: Vec<Tie> = Vec::new();
    let mut kinds: Vec<(TieKind, Vector3<f64>)> = candidates
        .iter()
        .map(|c| (tie_of(c).kind, Vector3::zeros()))
        .collect();
    let mut report = TiedReport::default();
    // Where each attached particle aims beyond its point after the body's own step: the move
    // the collide phase gave the body last step ([`BodyMove`]), over h.
    let lead: Vec<Vector3<f64>> = attachments
        .iter()
        .map(|a| {
            let state = &states[a.body];
            let arm = state.orientation.matrix() * a.offset_body;
            predicted
                .get(a.body)
                .map_or(Vector3::zeros(), |m| m.of_point(&arm) / dt)
        })
        .collect();
    let attach_ties = |states: &[State], cloth: &Cloth| -> Vec<Tie> {
        attachments
            .iter()
            .zip(&lead)
            .map(|(a, lead)| {
                let state = &states[a.body];
                let arm = state.orientation.matrix() * a.offset_body;
                let target = state.position + arm;
                // The body is already at the end of its own step (`target`): the particle
                // gets there, plus what the collide phase is predicted to move it (`lead`),
                // plus what the correction moves the point.
                Tie {
                    particle: a.particle,
                    body: Some(a.body),
                    arm,
                    normal: Vector3::y(),
                    kind: TieKind::Full,
                    target: (target - cloth.positions[a.particle]) / dt + lead,
                    extra: Vector3::zeros(),
                    permanent: true,
                    impulse: Vector3::zeros(),
                }
            })
            .collect()
    };
    let mut index: Vec<usize> = Vec::new();
    for round in 0..TIE_ROUNDS {
        ties.clear();
        index.clear();
        for (k, c) in candidates.iter().enumerate() {
            if active[k] {
                let mut tie = tie_of(c);
                (tie.kind, tie.extra) = kinds[k];
                ties.push(tie);
                index.push(k);
            }
        }
        ties.extend(attach_ties(states, cloth));
        let step = cloth.solve_tied(&mut ties, &mut solver_bodies, &held_joints.filter);
        report.rounds = round + 1;
        report.iterations += step.iterations;
        let mut changed = false;
        for (tie, &k) in ties.iter().zip(&index) {
            let n = tie.normal;
            let normal_impulse = tie.impulse.dot(&n);
            if normal_impulse < 0.0 {
                // It would pull the particle onto the body: let go (B&W §6.2).
                active[k] = false;
                kinds[k] = (tie_of(&candidates[k]).kind, Vector3::zeros());
                changed = true;
                continue;
            }
            if friction > 0.0 {
                let tangential = match tie.kind {
                    TieKind::Full => tie.impulse - n * normal_impulse,
                    TieKind::Normal => tie.extra,
                };
                let limit = friction * normal_impulse;
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
        for (k, c) in candidates.iter().enumerate() {
            if !active[k] && end_gap(c, &cloth.velocities[c.particle], &solver_bodies) < -TOUCHING {
                active[k] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    cloth.finish_tied_step(loads);
    cloth.record_solves(crate::physics::cloth::SolveCounts {
        solves: report.rounds,
        iterations: report.iterations,
    });
    // The energy the ties took (doc above): the impulses' work along the particle's motion
    // relative to the body's material point.
    for tie in &ties {
        let drift = tie
            .body
            .map_or(Vector3::zeros(), |b| displacement(b, &tie.arm) / dt);
        let u = cloth.velocities[tie.particle]
            - drift
            - correction_at(&solver_bodies, tie.body, &tie.arm);
        report.energy_taken -= (tie.impulse + tie.extra).dot(&u);
    }
    report.contacts = ties
        .iter()
        .filter(|t| !t.permanent && t.body.is_some())
        .count();
    report.obstacle_contacts = ties.iter().filter(|t| t.body.is_none()).count();
    cloth.set_held(
        candidates.iter().map(|c| c.particle),
        ties.iter().filter(|t| !t.permanent).map(|t| t.particle),
    );
    joint_impulses.clear();
    joint_impulses.resize(links.joints.len(), Loads::default());
    held_joints.impulses(&ties, &solver_bodies, joint_impulses);
    // The bodies take the opposite impulses: through their correction when they are unknowns
    // of the solve, summed afterwards when they are not (factor 0).
    let mut pushed = vec![[Vector3::zeros(); 2]; bodies.len()];
    for tie in &ties {
        if let Some(b) = tie.body {
            let j = tie.impulse + tie.extra;
            pushed[b][0] -= j;
            pushed[b][1] -= tie.arm.cross(&j);
        }
    }
    for (((body, state), sb), push) in bodies
        .iter()
        .zip(states.iter_mut())
        .zip(&solver_bodies)
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
        move_body(state, &dv, &dw, dt);
    }
    // Tied particles: the body turned by the rotation h Y_ω, their tie moved them along its
    // tangent h Y_ω × r; the difference in the tied components, (I − S)((R(h Y_ω) − I) r −
    // h Y_ω × r) = O(h² |Y_ω|² r), is made up within the step (module doc of
    // `hold_attachments`), so that an attached particle stays on its point and a contact on
    // the surface to round-off.
    for tie in &ties {
        let Some(b) = tie.body else { continue };
        let sb = &solver_bodies[b];
        if sb.mass == 0.0 {
            continue;
        }
        let mut gap = turn_gap(&sb.correction[1], &tie.arm, dt);
        if tie.kind == TieKind::Normal {
            gap = tie.normal * tie.normal.dot(&gap);
        }
        let made_up = close_gap(cloth, tie.particle, &mut states[b], &tie.arm, &gap, dt);
        if tie.permanent {
            let point = states[b].position + tie.arm;
            report.attach_impulse[0] += made_up;
            report.attach_impulse[1] += point.cross(&made_up);
        }
    }
    // The attachments' reactions on the cloth (their point on the body at the step's end).
    // (`attach_ties` appends them after the contacts, in the order of `attachments`.)
    for (tie, a) in ties.iter().filter(|t| t.permanent).zip(attachments) {
        let state = &states[a.body];
        let point = state.position + state.orientation.matrix() * a.offset_body;
        let j = tie.impulse + tie.extra;
        report.attach_impulse[0] += j;
        report.attach_impulse[1] += point.cross(&j);
    }
    report
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
struct HeldJoints {
    filter: BodyJoints,
    /// The rows, each with its joint (`Row::joint`), and their matrix over the stacked
    /// corrections (rows × 6k).
    rows: Vec<Row>,
    matrix: DMatrix<f64>,
}

impl HeldJoints {
    fn new(links: &Links, states: &[State], solver_bodies: &[TiedBody]) -> HeldJoints {
        let moves = |b: usize| solver_bodies[b].mass > 0.0;
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
            if moves(joint.a) || joint.b.is_some_and(moves) {
                let b = joint.b.map_or(JointPose::WORLD, |b| poses[b]);
                rows_of(joint, index, &poses[joint.a], &b, &mut rows);
            }
        }
        let column = |b: usize| bodies.iter().position(|&x| x == b);
        let mut matrix = DMatrix::zeros(rows.len(), 6 * bodies.len());
        for (k, row) in rows.iter().enumerate() {
            let sides = [
                (Some(row.a), row.lin_a, row.ang_a),
                (row.b, row.lin_b, row.ang_b),
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
        let svd = self.matrix.transpose().svd(true, true);
        let largest = svd.singular_values.iter().fold(0.0_f64, |m, v| m.max(*v));
        let Ok(mu) = svd.solve(&wrench, 1e-12 * largest) else {
            return;
        };
        for (row, &m) in self.rows.iter().zip(mu.iter()) {
            if let Some(load) = out.get_mut(row.joint) {
                load.force += row.lin_a * m;
                load.torque += row.ang_a * m;
            }
        }
    }
}

/// Moves a body by the position part of a correction (Y_V, Y_ω) over a step of length h:
/// x += h Y_V, and a turn by the rotation of vector h Y_ω (exact, not linearised).
fn move_body(state: &mut State, y_v: &Vector3<f64>, y_w: &Vector3<f64>, dt: f64) {
    state.position += y_v * dt;
    let turn = nalgebra::UnitQuaternion::from_scaled_axis(y_w * dt);
    state.orientation = match state.orientation {
        super::state::Orientation::Quaternion(q) => super::state::Orientation::Quaternion(turn * q),
        super::state::Orientation::Matrix(m) => {
            super::state::Orientation::Matrix(turn.to_rotation_matrix().matrix() * m)
        }
    };
}

/// (R(h ω) − I) r − h ω × r: where a body's point at arm r ends after the exact turn by
/// h ω, less where its linearisation puts it, m.
fn turn_gap(omega: &Vector3<f64>, arm: &Vector3<f64>, dt: f64) -> Vector3<f64> {
    let turn = nalgebra::UnitQuaternion::from_scaled_axis(omega * dt);
    turn * arm - arm - omega.cross(arm) * dt
}

/// Moves particle `i`'s end of step by `gap` (its velocity by gap/h) and gives the body the
/// opposite momentum at its point, so that particle + body keep theirs.
/// Returns the impulse the particle took, N·s.
fn close_gap(
    cloth: &mut Cloth,
    i: usize,
    state: &mut State,
    arm: &Vector3<f64>,
    gap: &Vector3<f64>,
    dt: f64,
) -> Vector3<f64> {
    let impulse = gap * (cloth.masses[i] / dt);
    cloth.apply_impulse(i, &impulse);
    state.linear_momentum -= impulse;
    state.angular_momentum -= arm.cross(&impulse);
    impulse
}

/// How the collide phase moved a body: its barycenter by `shift`, its orientation by the
/// rotation `turn` about the barycenter (R ← turn R). An attached particle's tie aims at its
/// point after the body's own step moved on by the body's last move ([`tied_step`], "Bodies
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
        let (body, state) = (&bodies[a.body], &states[a.body]);
        let rotation = state.orientation.matrix();
        let arm = rotation * a.offset_body;
        let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
        let omega = inv_inertia * state.angular_momentum;
        let velocity = state.linear_momentum * body.inv_mass + omega.cross(&arm);
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

/// Attachments of an explicit (`symplectic-euler`) cloth, held by impulses after its
/// velocity half and the bodies' own step (the implicit cloth holds them inside its solve,
/// [`tied_step`]).
///
/// Attachment a holds particle p at its body's point P_a = x_b + r_a (the body already at
/// the end of its own step). Unknown: the impulse J_a on the particle, −J_a on the body at
/// r_a. The body's correction ΔV = −Σ J/M, Δω = −I⁻¹ Σ r × J moves its position by
/// factor·h·(ΔV, Δω) ([`position_factor`]), so the particle ends on its point when
///
/// ```text
/// x_p + h (v_p + J_a/m_p) = P_a + factor h (ΔV + Δω × r_a)      (linearised turn)
/// Σ_c K_ac J_c = (P_a − x_p)/h − v_p
/// K_ac = δ_ac I/m_p + factor (I/M − [r_a]× I⁻¹ [r_c]×)
/// ```
///
/// one symmetric positive-definite 3k × 3k system per body with k attachments, solved
/// directly (Cholesky). The body's turn is then applied exactly and the particle moved by
/// what the linearisation missed, `(R(h Δω') − I) r − h Δω' × r` (Δω' = factor Δω),
/// with the opposite momentum to the body: the error left is round-off, and body +
/// particles keep their momentum. A fixed body takes nothing (K = I/m_p); a body whose
/// integrator ignores the correction in its position (factor 0) takes the impulses in its
/// momenta only.
///
/// Returns the kinetic energy the impulses took, J (a rigid hold is a perfectly plastic
/// impact between the particle and the body's point: ≥ 0), and the impulses' sum and moment.
pub fn hold_attachments(
    cloth: &mut Cloth,
    bodies: &[Body],
    states: &mut [State],
    attachments: &[Attachment],
    dt: f64,
    factor: f64,
) -> AttachReport {
    use nalgebra::{DMatrix, DVector};
    let mut report = AttachReport::default();
    for (b, (body, state)) in bodies.iter().zip(states.iter_mut()).enumerate() {
        let list: Vec<&Attachment> = attachments.iter().filter(|a| a.body == b).collect();
        if list.is_empty() {
            continue;
        }
        let rotation = state.orientation.matrix();
        let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
        let moves = !body.fixed && body.inv_mass > 0.0;
        let scale = if moves { factor } else { 0.0 };
        let arms: Vec<Vector3<f64>> = list.iter().map(|a| rotation * a.offset_body).collect();
        let k = list.len();
        let mut matrix = DMatrix::<f64>::zeros(3 * k, 3 * k);
        let mut rhs = DVector::<f64>::zeros(3 * k);
        for (a, (att, ra)) in list.iter().zip(&arms).enumerate() {
            let p = att.particle;
            let point = state.position + ra;
            let u = (point - cloth.positions[p]) / dt - cloth.velocities[p];
            rhs.fixed_rows_mut::<3>(3 * a).copy_from(&u);
            for (c, rc) in arms.iter().enumerate() {
                let mut block = -ra.cross_matrix() * inv_inertia * rc.cross_matrix()
                    + Matrix3::identity() * body.inv_mass;
                block *= scale;
                if a == c {
                    block += Matrix3::identity() * cloth.inv_mass(p);
                }
                matrix
                    .fixed_view_mut::<3, 3>(3 * a, 3 * c)
                    .copy_from(&block);
            }
        }
        let Some(cholesky) = matrix.cholesky() else {
            continue;
        };
        let impulses = cholesky.solve(&rhs);
        let kinetic = |cloth: &Cloth, state: &State| {
            let rigid = if moves {
                0.5 * state.linear_momentum.norm_squared() * body.inv_mass
                    + 0.5
                        * state
                            .angular_momentum
                            .dot(&(inv_inertia * state.angular_momentum))
            } else {
                0.0
            };
            list.iter().fold(rigid, |t, a| {
                t + 0.5 * cloth.masses[a.particle] * cloth.velocities[a.particle].norm_squared()
            })
        };
        let before = kinetic(cloth, state);
        let (mut total, mut torque) = (Vector3::zeros(), Vector3::zeros());
        for (a, (att, ra)) in list.iter().zip(&arms).enumerate() {
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
                let y_w = -(inv_inertia * torque) * scale;
                move_body(state, &y_v, &y_w, dt);
                for (att, ra) in list.iter().zip(&arms) {
                    let gap = turn_gap(&y_w, ra, dt);
                    let j = close_gap(cloth, att.particle, state, ra, &gap, dt);
                    report.impulse[0] += j;
                    report.impulse[1] += (state.position + ra).cross(&j);
                }
            }
        }
        report.taken += before - kinetic(cloth, state);
    }
    report
}
