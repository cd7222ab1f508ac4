//! Particles against fixed obstacles (ground, sphere, box), and the cloth's side of a contact
//! with a body.
//!
//! Each free particle is tested along its motion over the step (the swept test of
//! `collision::detect`, so a fast particle cannot jump a thin box); one found inside gets:
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
//! The bounce threshold is the bodies' (`collision::impulse::BOUNCE_STEPS`). A point mass has
//! no lever arm, so this one-contact rule is exact and never adds kinetic energy (e ≤ 1,
//! μ ≥ 0); the push-out lifts the particle by `depth n` against gravity, and that work
//! `ΔV = −m g·(depth n)` is paid from the bounce (the restitution part is scaled down so that
//! T_after ≤ T_before − max(0, ΔV)), as for bodies.
//!
//! The energy the contacts took is measured, not assumed: T + U + V before minus after, over
//! the touched particles and the springs attached to them.
//!
//! The particle ↔ body coupling belongs to the world: it uses [`Cloth::inv_mass`],
//! [`Cloth::particle_velocity`], [`Cloth::apply_impulse`] and [`Cloth::displace`], and applies the
//! opposite impulse to the body.

use super::loads::ClothLoads;
use super::sheet::Cloth;
use crate::physics::collision::detect;
use crate::physics::collision::impulse::BOUNCE_STEPS;
use crate::physics::collision::Obstacle;
use nalgebra::Vector3;

/// One particle found inside an obstacle, and what the response did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleContact {
    pub particle: usize,
    /// Index of the obstacle in the scene's list.
    pub obstacle: usize,
    /// Penetration depth before the projection, m.
    pub depth: f64,
    /// Unit normal out of the obstacle.
    pub normal: Vector3<f64>,
    /// v·n before the response, m/s (negative: approaching).
    pub normal_velocity: f64,
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
    /// Tests every free particle against every obstacle and responds (module doc); the
    /// contacts found are in `contacts` (cleared first). Adds the energy taken to
    /// `losses.contact`.
    pub fn collide_obstacles(
        &mut self,
        obstacles: &[Obstacle],
        restitution: f64,
        friction: f64,
        loads: &ClothLoads,
        dt: f64,
        contacts: &mut Vec<ParticleContact>,
    ) -> ContactReport {
        contacts.clear();
        if obstacles.is_empty() {
            return ContactReport::default();
        }
        let bounce_speed = loads.gravity.map_or(0.0, |g| BOUNCE_STEPS * g.norm() * dt);
        if self.scratch.start.len() != self.len() {
            self.scratch.start.clone_from(&self.positions);
        }
        let start = std::mem::take(&mut self.scratch.start);
        let mut before: Vec<(usize, Vector3<f64>, Vector3<f64>)> = Vec::new();
        for i in 0..self.len() {
            if self.pinned[i] {
                continue;
            }
            for (k, obstacle) in obstacles.iter().enumerate() {
                let Some(hit) = detect::swept(obstacle, &start[i], &self.positions[i]) else {
                    continue;
                };
                if before.last().is_none_or(|b| b.0 != i) {
                    before.push((i, self.positions[i], self.velocities[i]));
                }
                let n = hit.normal;
                let m = self.masses[i];
                let v = self.velocities[i];
                let un = v.dot(&n);
                contacts.push(ParticleContact {
                    particle: i,
                    obstacle: k,
                    depth: hit.depth,
                    normal: n,
                    normal_velocity: un,
                });
                self.positions[i] += n * hit.depth;
                if un >= 0.0 {
                    continue;
                }
                // Inelastic part: stop the approach, then friction within μ Δu_n.
                let stop = -un;
                let mut tangential = v - n * un;
                let slip = tangential.norm();
                if slip <= friction * stop {
                    tangential = Vector3::zeros();
                } else {
                    tangential *= 1.0 - friction * stop / slip;
                }
                // Restitution, paid for the push-out's work against gravity.
                let mut bounce = if -un > bounce_speed {
                    restitution * stop
                } else {
                    0.0
                };
                if bounce > 0.0 {
                    let lift = loads
                        .gravity
                        .map_or(0.0, |g| -m * g.dot(&(n * hit.depth)))
                        .max(0.0);
                    let budget = v.norm_squared() - 2.0 * lift / m - tangential.norm_squared();
                    bounce = bounce.min(budget.max(0.0).sqrt());
                }
                self.velocities[i] = tangential + n * bounce;
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
