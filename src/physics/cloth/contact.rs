//! Particles against fixed obstacles (ground, sphere, box), and the cloth's side of a contact
//! with a body.
//!
//! What each pass does to a particle is the scene's response's particle law
//! (`collision::particle`, read from the step context): the formulas below are `impulse`'s,
//! the law of every bundled cloth lesson; `seed` does nothing in pass 1 and in pass 2 pushes
//! out by d² and reverses the whole velocity ×0.4; `soft-step` gives pass 1 a soft row and
//! does not project in pass 2.
//!
//! # Two passes per step, on velocities first
//!
//! A step that moves a resting particle into the obstacle and a contact that pushes it back
//! out trade energy every step (the step lowers the springs' and gravity's energy, the
//! push-out raises it again): an artifact, not a loss. So, as rigid engines do, contacts act
//! on the velocities *before* the positions move ([`Cloth::step_with_obstacles`]):
//!
//! 1. [`Cloth::contact_velocities`], after the velocity half of the step: a free particle at
//!    gap g ≥ 0 from an obstacle (`detect::near`, normal n) whose new velocity would carry it
//!    inside, `h v·n < −g`, gets v·n ← −g/h (it arrives on the surface, no further), and
//!    Coulomb friction on the tangential velocity with the impulse that took (below).
//!    Fast approaches (−v·n > the bounce speed) with e > 0 are left to pass 2, to bounce.
//! 2. [`Cloth::collide_obstacles`], after the positions moved: a particle found inside
//!    (swept test, so a fast one cannot jump a thin box; or inside by the curvature of a
//!    sphere) is projected out and its approach removed, with restitution when fast:
//!
//! ```text
//! x ← x + depth n                                  projected onto the surface
//! u_n = v·n < 0 (approaching):
//!   Δu_n = −(1 + e) u_n   if −u_n > 3|g| dt        fast approach: restitution e
//!   Δu_n = −u_n           otherwise                resting: no bounce
//!   v ← v + Δu_n n
//! v_t = v − (v·n) n,  |v_t| ≤ μ Δu_n ? v_t ← 0 : v_t ← v_t (1 − μ Δu_n/|v_t|)    (Coulomb)
//! ```
//!
//! The bounce threshold is the bodies' (`collision::step_context`: both passes read the step's
//! one context). A point mass has
//! no lever arm, so this one-contact rule is exact and never adds kinetic energy (e ≤ 1,
//! μ ≥ 0); the push-out lifts the particle by `depth n` against gravity, and that work
//! `ΔV = −m g·(depth n)` is paid from the bounce (the restitution part is scaled down so that
//! T_after ≤ T_before − max(0, ΔV)), as for bodies.
//!
//! Each contact is the constraint layer's particle contact against a static thing
//! (`constraints::particle_contact::against_static`): a normal row with bounds [0, ∞) from a
//! solver body without rotational inertia (the particle) to the obstacle as a static solver
//! body (`SolverBody::fixed_thing`, no end, as in the rigid solvers' body table), solved
//! exactly by its one update, per unit mass (Δu_n above is its λ), and Coulomb friction
//! within μ λ. The same rows with a body's solver body as B are `cloth_coupling`'s.
//!
//! The energy the contacts took is measured, not assumed: T + U + V before minus after, over
//! the touched particles and the springs attached to them.
//!
//! The particle ↔ body coupling belongs to the world: it uses [`Cloth::inv_mass`],
//! [`Cloth::particle_velocity`], [`Cloth::apply_impulse`] and [`Cloth::displace`], and applies the
//! opposite impulse to the body.

use super::loads::ClothLoads;
use super::sheet::{Cloth, StepReport};
use crate::physics::collision::detect;
use crate::physics::collision::particle::{Hit, Touch};
use crate::physics::collision::Obstacle;
use crate::physics::collision::StepContext;
use crate::physics::constraints::particle_contact::{against_static, coulomb};
use nalgebra::Vector3;

/// One particle found inside an obstacle, and what the response did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleContact {
    pub particle: usize,
    /// Index of the obstacle in the scene's list.
    pub obstacle: usize,
    /// Penetration depth before the projection, m (pass 1: minus the gap, ≤ 0).
    pub depth: f64,
    /// Unit normal out of the obstacle.
    pub normal: Vector3<f64>,
    /// v·n before the response, m/s (negative: approaching).
    pub normal_velocity: f64,
}

/// A start this close to a surface (m) counts as on it.
const ON_SURFACE: f64 = 1e-9;

/// Is a particle that moved from `a` to `b` inside `obstacle`? The swept test when `a` is
/// clearly outside; the static test at `b` when `a` is on the surface (a resting particle:
/// `detect::swept` takes its start to be outside, and for a sphere a start on the surface up
/// to round-off can give the far side's entry point).
fn penetration(
    obstacle: &Obstacle,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> Option<detect::Penetration> {
    if obstacle.depth(a) > 0.0 || obstacle.near(a, ON_SURFACE).is_some() {
        obstacle.inside(b)
    } else {
        obstacle.swept(a, b)
    }
}

/// What one contact pass did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactReport {
    pub contacts: usize,
    /// Deepest penetration found (before projection), m.
    pub deepest: f64,
    /// Energy the contacts took, J (T + U + V before minus after).
    pub energy_taken: f64,
}

impl Cloth {
    /// One whole step among fixed obstacles: the velocity half, pass 1 (velocities), the
    /// position half, pass 2 (projection). Contacts of both passes are in `contacts`.
    /// `context`: the step's dt, bounce speed, e and μ (its gravity should be `loads`').
    pub fn step_with_obstacles(
        &mut self,
        loads: &ClothLoads,
        context: &StepContext,
        obstacles: &[Obstacle],
        contacts: &mut Vec<ParticleContact>,
    ) -> (StepReport, ContactReport) {
        let dt = context.dt;
        let mut report = self.velocity_step(loads, dt);
        let first = self.contact_velocities(obstacles, context, contacts);
        report.dissipated = self.advance_positions(loads, dt);
        let mut second = Vec::new();
        let after = self.collide_obstacles(obstacles, context, loads, &mut second);
        contacts.extend(second);
        (
            report,
            ContactReport {
                contacts: first.contacts + after.contacts,
                deepest: after.deepest,
                energy_taken: first.energy_taken + after.energy_taken,
            },
        )
    }

    /// Pass 1 (module doc): between the velocity half of a step and the positions' update,
    /// stops each free particle whose velocity would carry it into an obstacle at the surface,
    /// with friction. `contacts` is cleared and filled. Adds the energy taken to
    /// `losses.contact`: across n the kinetic energy friction removed; along n the kinetic
    /// energy of the approach the particle had at the start of the step, ½ m (min(0, v₀·n)² −
    /// (g/h)²) — what the step's forces pushed into the surface within the step, a resting
    /// contact cancels as it arises (counting it would book a resting sheet's weight as a loss
    /// every step).
    pub fn contact_velocities(
        &mut self,
        obstacles: &[Obstacle],
        context: &StepContext,
        contacts: &mut Vec<ParticleContact>,
    ) -> ContactReport {
        contacts.clear();
        let StepContext { dt, friction, .. } = *context;
        let law = context.response.particle();
        let mut taken = 0.0;
        for i in 0..self.len() {
            if self.pinned[i] {
                continue;
            }
            for (k, obstacle) in obstacles.iter().enumerate() {
                let x = self.positions[i];
                let v = self.velocities[i];
                let reach = v.norm() * dt;
                let (gap, depth, n) = match obstacle.inside(&x) {
                    Some(p) => (0.0, p.depth, p.normal),
                    None => match obstacle.near(&x, reach) {
                        Some((gap, n)) => (gap, 0.0, n),
                        None => continue,
                    },
                };
                let un = v.dot(&n);
                // The response's target for v·n (`collision::particle`): `impulse` arrives on
                // the surface, −gap/h, and leaves a fast approach to pass 2.
                let touch = Touch {
                    gap,
                    depth,
                    normal_velocity: un,
                    approach: un.min(0.0),
                    fixed: true,
                };
                let Some(target) = law.velocity_target_static(&touch, context) else {
                    continue;
                };
                // The normal row against a static thing, per unit mass: λ = target − u_n.
                let Some(stop) = against_static(&v, &n, target) else {
                    continue;
                };
                let tangential = coulomb(&v, &n, friction, stop);
                let after = tangential + n * target;
                // Along n, only the approach the particle had at the start of the step is
                // taken (what the forces added within the step, a resting contact cancels
                // before it exists); across n, what friction removed.
                let approach = self
                    .scratch
                    .start_velocity
                    .get(i)
                    .map_or(un, |v0| v0.dot(&n))
                    .min(0.0);
                taken += 0.5
                    * self.masses[i]
                    * (approach * approach - target * target + (v - n * un).norm_squared()
                        - tangential.norm_squared());
                self.velocities[i] = after;
                contacts.push(ParticleContact {
                    particle: i,
                    obstacle: k,
                    depth: -gap,
                    normal: n,
                    normal_velocity: un,
                });
            }
        }
        self.losses.contact += taken;
        ContactReport {
            contacts: contacts.len(),
            deepest: 0.0,
            energy_taken: taken,
        }
    }

    /// Pass 2 (module doc): after the positions moved, tests every free particle against
    /// every obstacle along its motion and responds; the contacts found are in `contacts`
    /// (cleared first). Adds the energy taken to
    /// `losses.contact`.
    pub fn collide_obstacles(
        &mut self,
        obstacles: &[Obstacle],
        context: &StepContext,
        loads: &ClothLoads,
        contacts: &mut Vec<ParticleContact>,
    ) -> ContactReport {
        contacts.clear();
        if obstacles.is_empty() {
            return ContactReport::default();
        }
        let law = context.response.particle();
        if self.scratch.start.len() != self.len() {
            self.scratch.start.clone_from(&self.positions);
        }
        let start = std::mem::take(&mut self.scratch.start);
        let mut before: Vec<(usize, Vector3<f64>, Vector3<f64>)> = Vec::new();
        for (i, a) in start.iter().enumerate() {
            if self.pinned[i] {
                continue;
            }
            for (k, obstacle) in obstacles.iter().enumerate() {
                let Some(hit) = penetration(obstacle, a, &self.positions[i]) else {
                    continue;
                };
                if before.last().is_none_or(|b| b.0 != i) {
                    before.push((i, self.positions[i], self.velocities[i]));
                }
                let n = hit.normal;
                let v = self.velocities[i];
                contacts.push(ParticleContact {
                    particle: i,
                    obstacle: k,
                    depth: hit.depth,
                    normal: n,
                    normal_velocity: v.dot(&n),
                });
                // The response's push-out and velocity (`collision::particle`): `impulse`
                // projects onto the surface, then the normal row aiming at u_n = 0, friction
                // within μ Δu_n and restitution paid for the push-out's work against gravity.
                let moved = law.push_out(hit.depth);
                self.positions[i] += n * moved;
                let hit = Hit {
                    velocity: v,
                    normal: n,
                    moved,
                    mass: self.masses[i],
                    gravity: loads.gravity,
                };
                if let Some(after) = law.bounce_static(&hit, context) {
                    self.velocities[i] = after;
                }
            }
        }
        self.scratch.start = start;
        if before.is_empty() {
            return ContactReport::default();
        }
        // Energy taken: particles' T and V, and the springs touching a moved particle.
        let mut taken = 0.0;
        let mut moved = vec![usize::MAX; self.len()];
        for (slot, &(i, x0, v0)) in before.iter().enumerate() {
            moved[i] = slot;
            let m = self.masses[i];
            let (x1, v1) = (self.positions[i], self.velocities[i]);
            taken += 0.5 * m * (v0.norm_squared() - v1.norm_squared());
            if let Some(g) = loads.gravity {
                taken += m * g.dot(&(x1 - x0));
            }
        }
        let old = |p: usize| {
            if moved[p] == usize::MAX {
                self.positions[p]
            } else {
                before[moved[p]].1
            }
        };
        for s in &self.springs {
            if moved[s.i] != usize::MAX || moved[s.j] != usize::MAX {
                let strain = |a: Vector3<f64>, b: Vector3<f64>| (b - a).norm() - s.rest_length;
                let (e0, e1) = (
                    strain(old(s.i), old(s.j)),
                    strain(self.positions[s.i], self.positions[s.j]),
                );
                taken += 0.5 * s.stiffness * (e0 * e0 - e1 * e1);
            }
        }
        self.losses.contact += taken;
        ContactReport {
            contacts: contacts.len(),
            deepest: contacts.iter().map(|c| c.depth).fold(0.0, f64::max),
            energy_taken: taken,
        }
    }
}
