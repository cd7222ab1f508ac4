//! Contacts of a `symplectic-euler` cloth's particles with bodies (and of an `implicit-euler`
//! one under a response whose contacts are not ties): two passes, on velocities then on
//! positions, with the sweeps on the constraint layer's rows and solver bodies.
//!
//! Each pass's targets, push-out and solve are the scene's response's particle law
//! (`collision::particle`); the formulas below are `impulse`'s (every bundled lesson's).
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
//! through later steps (the implicit path, [`tied_step`](super::tied_step), does it within the step).
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
//! They are the constraint layer's particle contacts (`constraints::particle_contact`): the
//! body and each touching particle are solver bodies (a particle has no rotational inertia
//! and lever 0), each contact a normal row with bounds [0, ∞) whose k(n) is its axis's k,
//! friction within the disc μ j_n, and each impulse is applied to both ends at once.
//! v_p ← v_p + J/m_p,   P ← P − J,   L ← L − r × J
//! x_p ← x_p + depth n                            the particle is pushed out, not the body
//! ```
//!
//! A point against a rigid body is one contact with a lever arm, so the rule above is the
//! exact two-body impulse (no energy made for e ≤ 1, μ ≥ 0). The push-out moves a light
//! particle, never the body (moving the body would make it jitter on a sheet of hundreds of
//! particles). The world measures the energy of the whole collide phase before and after and
//! books the change in its ledger.

use super::SLOP;
use crate::physics::body::Body;
use crate::physics::cloth::Cloth;
use crate::physics::collision::geometry::{point_shape, Pose, Shape};
use crate::physics::collision::particle::{ParticleLaw, Touch};
use crate::physics::collision::StepContext;
use crate::physics::constraints::particle_contact::{body_of, ParticleContacts};
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

/// Sweeps over a body's contacts (module doc): the constraint layer's
/// (`constraints::particle_contact`).
pub use crate::physics::constraints::particle_contact::SWEEPS;

/// Starts a body's particle contacts: its solver body from its momenta, at the pose of
/// `inv_inertia` (a fixed body is static: no inverse mass, no inverse inertia).
fn start_body(
    sweeps: &mut ParticleContacts,
    body: &Body,
    state: &State,
    inv_inertia: &Matrix3<f64>,
) {
    sweeps.start(body_of(
        &state.linear_momentum,
        state.angular_momentum,
        body.inv_mass,
        inv_inertia,
    ));
}

/// Adds particle `i`'s contact at the body's point `arm`, normal n out of the body.
fn touch(
    sweeps: &mut ParticleContacts,
    cloth: &Cloth,
    i: usize,
    n: &Vector3<f64>,
    arm: Vector3<f64>,
    target: (f64, bool),
) {
    let particle = (i, cloth.particle_velocity(i), cloth.inv_mass(i));
    sweeps.touch(particle, n, arm, target);
}

/// Runs the sweeps (`ParticleContacts::solve`), then the particles' velocities and the
/// body's momenta take what they applied (the body −ΣJ, so particle + body keep their
/// momentum to round-off).
fn solve(
    law: &dyn ParticleLaw,
    sweeps: &mut ParticleContacts,
    cloth: &mut Cloth,
    state: &mut State,
    friction: f64,
) {
    law.solve_body(sweeps, friction);
    for (particle, velocity) in sweeps.particles() {
        cloth.velocities[particle] = velocity;
    }
    let total = sweeps.total_impulse();
    if !sweeps.body().fixed() {
        state.linear_momentum -= total;
        state.angular_momentum = sweeps.body().l;
    }
}

/// A body's contact shape at its pose in `state`, and its world inverse inertia
/// `R I⁻¹_body Rᵀ`; None for a body without a shape.
fn shape_at<'a>(body: &'a Body, state: &State) -> Option<(&'a Shape, Pose, Matrix3<f64>)> {
    let shape = body.shape.as_ref()?;
    let rotation = state.orientation.matrix();
    let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
    let pose = Pose {
        position: state.position,
        rotation,
    };
    Some((shape, pose, inv_inertia))
}

/// One particle–body contact pass over a cloth: returns the number of contacts.
///
/// `context`: e, μ and the bounce speed (approaches slower than it do not bounce).
pub fn collide_bodies(
    cloth: &mut Cloth,
    bodies: &[Body],
    states: &mut [State],
    context: &StepContext,
) -> usize {
    let friction = context.friction;
    let law = context.response.particle();
    let mut count = 0;
    let mut sweeps = ParticleContacts::default();
    for (body, state) in bodies.iter().zip(states.iter_mut()) {
        let Some((shape, pose, inv_inertia)) = shape_at(body, state) else {
            continue;
        };
        // A quick reject: particles farther than the body's radius from its barycenter.
        let reach = body.radius;
        start_body(&mut sweeps, body, state, &inv_inertia);
        // An implicit-euler cloth's ties end its particles on the surface: what is left
        // inside at round-off is not a contact.
        let slop = if cloth.integrator == crate::physics::cloth::ClothIntegrator::ImplicitEuler
            && law.ties()
        {
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
            // The response's push-out and target (`collision::particle`): `impulse` pushes
            // the particle out by its depth and aims at −e u_n on a fast approach, else 0.
            cloth.displace(i, &(n * law.push_out(cp.depth)));
            let arm = cp.point - state.position;
            let un = sweeps.approach(&cloth.particle_velocity(i), &arm).dot(&n);
            let target = law.collide_target_body(un, context);
            touch(&mut sweeps, cloth, i, &n, arm, (target, false));
        }
        count += sweeps.len();
        solve(&*law, &mut sweeps, cloth, state, friction);
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
/// the bodies' states at the start of the step; `context` gives e, μ, the bounce speed and h). Each free particle whose velocity would
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
pub fn approach_bodies(
    cloth: &mut Cloth,
    bodies: &[Body],
    start: &[State],
    states: &mut [State],
    context: &StepContext,
) -> Approach {
    let StepContext { friction, dt, .. } = *context;
    let law = context.response.particle();
    let mut report = Approach::default();
    let mut sweeps = ParticleContacts::default();
    // Attached particles are held to their points (`hold_attachments`), not pushed out of
    // the body they are sewn into, as in the collide phase (`collide_bodies`).
    let mut attached = vec![false; cloth.len()];
    for &(i, _) in &cloth.attached {
        attached[i] = true;
    }
    for ((body, state), before) in bodies.iter().zip(states.iter_mut()).zip(start) {
        let Some((shape, pose, inv_inertia)) = shape_at(body, state) else {
            continue;
        };
        let omega = inv_inertia * state.angular_momentum;
        let body_speed = state.linear_momentum.norm() * body.inv_mass + omega.norm() * body.radius;
        let start_rotation = before.orientation.matrix();
        let start_inv_inertia = start_rotation * body.inv_inertia_body * start_rotation.transpose();
        let start_omega = start_inv_inertia * before.angular_momentum;
        let start_velocity = before.linear_momentum * body.inv_mass;
        start_body(&mut sweeps, body, state, &inv_inertia);
        let mut within = 0.0;
        #[allow(clippy::needless_range_loop)] // the particle index reaches several arrays
        for i in 0..cloth.len() {
            if cloth.inv_mass(i) == 0.0 || attached[i] {
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
            let un = sweeps.approach(&cloth.particle_velocity(i), &arm).dot(&n);
            // Bounce or rest is decided by the approach the pair had at the start of the
            // step: a particle carrying the body's weight is driven into it at h·F/m_p within
            // every step (0.3 m/s on a trampoline), and that is no impact.
            let u0 = cloth.start_velocity(i) - (start_velocity + start_omega.cross(&arm));
            let approach = u0.dot(&n).min(0.0);
            // The response's target for v_p·n (`collision::particle`): under `impulse` the
            // particle must end outside the body, v_p·n ≥ −gap/h, and leave at e times a
            // fast approach when it touches.
            let touch_at = Touch {
                gap,
                depth: (-gap).max(0.0),
                normal_velocity: cloth.velocities[i].dot(&n),
                approach,
                fixed: sweeps.body().fixed(),
            };
            let Some(target) = law.velocity_target_body(&touch_at, context) else {
                continue;
            };
            if cloth.velocities[i].dot(&n) >= target {
                continue;
            }
            touch(&mut sweeps, cloth, i, &n, arm, (target, true));
            let k_n = sweeps.last_k();
            within += 0.5 * (un.min(0.0).powi(2) - approach * approach) / k_n;
        }
        if sweeps.is_empty() {
            continue;
        }
        let kinetic = |cloth: &Cloth, state: &State, sweeps: &ParticleContacts| {
            let rigid = 0.5 * state.linear_momentum.norm_squared() * body.inv_mass
                + 0.5
                    * state
                        .angular_momentum
                        .dot(&(inv_inertia * state.angular_momentum));
            sweeps.particles().fold(rigid, |t, (p, _)| {
                t + 0.5 * cloth.masses[p] * cloth.velocities[p].norm_squared()
            })
        };
        let before_sweeps = kinetic(cloth, state, &sweeps);
        solve(&*law, &mut sweeps, cloth, state, friction);
        let after_sweeps = kinetic(cloth, state, &sweeps);
        report.contacts += sweeps.len();
        report.energy_taken += before_sweeps - after_sweeps - within;
    }
    report
}
