//! `seed`: the original report's collision response, reproduced on purpose, failures included.
//!
//! For each obstacle in turn, with the vertex positions the integrate phase computed:
//!
//! ```text
//! k     = the deepest vertex inside the obstacle (static test only; nothing if none is inside)
//! d     = its depth,  n = the obstacle's normal there (ground +y, sphere radial, box face)
//! x ← x + d² n                 pushed out by the SQUARED distance (the report's distance2)
//! L ← L + (pₖ − x₀) × (−F)     F the forces phase's force, x₀ the INITIAL barycenter
//! P ← −0.4 P                   the whole momentum reversed and scaled
//! ```
//!
//! What each rule does wrong, and what a class sees:
//!
//! - **Horizontal motion reversed.** `P ← −0.4 P` flips every component, not only the normal
//!   one: a box sliding right that touches the ground bounces back to the left.
//! - **Energy not conserved, and not only lost.** The 0.4 factor removes 84 % of the kinetic
//!   energy at each touch whatever the materials; but `L += r × (−F)` adds an angular momentum
//!   of size |r|·M g (a force, in N, added to a momentum, in N·m·s — the units do not even
//!   agree): at each touch the body is kicked into spin, and the kick grows with the lever arm.
//! - **The lever arm is measured from the initial barycenter.** `pₖ − x₀` includes the whole
//!   displacement of the body since t = 0: a body that has travelled 1 m sideways gets a kick
//!   five times larger than it would at its start, about an axis that has nothing to do with
//!   where it touches.
//! - **Jitter and sinking at rest.** A vertex only 1 mm deep is pushed out by 1 µm (d² ≪ d for
//!   d < 1 m), so it stays inside; the next step finds it again and reverses P again. Resting on
//!   the ground, each step does `P ← −0.4 (P + F dt)`, whose fixed point is the small upward
//!   momentum `P* = 0.4/1.4 · M g dt`: the body never rests, it hovers and shivers with a vertex
//!   inside the ground, while every touch adds another angular kick.
//! - **The climbing bug** (the report's own): a falling body whose corner grazes the top edge of
//!   an obstacle has that corner pushed up by a tiny d², keeps it inside, and every following
//!   step reverses its momentum again, i.e. turns its fall into a rise, and kicks its angular
//!   momentum. The body ratchets upward along the obstacle's side instead of falling past it,
//!   and climbs onto it.
//! - **No swept test**: a fast vertex that jumps over a thin obstacle within one step is
//!   never seen.
//!
//! Restitution and friction from the scene are ignored: the report's factor is always 0.4.

use super::particle::{Hit, ParticleLaw, Touch};
use super::response::Descriptor;
use super::StepContext;
use crate::physics::constraints::particle_contact::ParticleContacts;
use super::{vertices_into, CollideInput, Contact, EnergyChange, Feature};
use crate::physics::derive::derive;
use crate::physics::state::State;
use nalgebra::Vector3;

/// The report's momentum factor: `P ← −0.4 P`.
pub const MOMENTUM_FACTOR: f64 = -0.4;

/// What the front ends say about `seed` (`response`).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "seed",
    summary: "the original report's response: the whole momentum reversed and scaled by 0.4, a squared push-out, a force added to L (one body, obstacles only)",
    keeps: "nothing promised: it reproduces the report's failures (a landing kicks the body into a spin)",
    brief: "push vertices out of obstacles",
    formula: "seed (the report's): x += d²·n,  L += (pₖ − x₀)×(−F),  P ← −0.4·P",
    formula_bodies: "seed (the report's): x += d²·n,  L += (pₖ − x₀)×(−F),  P ← −0.4·P",
    impulses: false,
    colour: (200, 40, 40),
    charted: false,
};

/// The collide phase under `seed` (the entry point `responses!` calls): the last step's
/// contacts are dropped and body 0 responds ([`respond`]); it measures no energy.
pub fn collide(
    input: &CollideInput,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    _scratch: &mut super::impulse::Scratch,
) -> Option<EnergyChange> {
    contacts.clear();
    respond(input, &mut states[0], contacts);
    None
}

/// Runs the report's response on `state`, one fixed thing after the other (`fixed`: the
/// obstacles; the scene's rules allow `seed` no other body). Body 0 is the body: `seed` knows
/// one. A fixed thing answers the report's static test by its `inside` (an obstacle's kind's
/// exact formula); a fixed body is read at the start of the step, where it stays.
pub fn respond(input: &CollideInput, state: &mut State, contacts: &mut Vec<Contact>) {
    let body = &input.bodies[0];
    let mut points = Vec::with_capacity(body.points_body.len());
    vertices_into(body, state, &mut points);
    // Not body 0 itself, were it fixed (it responds, as it always has).
    let others = input.fixed_things(input.before).filter(|f| f.end != 0);
    for fixed in others {
        // The deepest vertex (the first one on a tie).
        let mut deepest = None;
        for (vertex, p) in points.iter().enumerate() {
            if let Some(hit) = fixed.inside(p) {
                if deepest.is_none_or(|(_, best): (usize, super::detect::Penetration)| {
                    hit.depth > best.depth
                }) {
                    deepest = Some((vertex, hit));
                }
            }
        }
        let Some((vertex, hit)) = deepest else {
            continue;
        };
        let point = points[vertex];
        let kinematics = derive(body, state);
        let point_velocity =
            kinematics.velocity + kinematics.angular_velocity.cross(&(point - state.position));
        let lever = point - input.initial_positions[0];
        let momentum_before = state.linear_momentum;
        state.position += hit.normal * (hit.depth * hit.depth);
        state.angular_momentum += lever.cross(&(-input.loads[0].force));
        state.linear_momentum *= MOMENTUM_FACTOR;
        contacts.push(Contact {
            lever,
            normal_velocity: point_velocity.dot(&hit.normal),
            impulse: state.linear_momentum - momentum_before,
            other: fixed.end,
            ..Contact::new(
                0,
                fixed.against,
                Feature::Vertex(vertex),
                point,
                hit.depth,
                hit.normal,
            )
        });
    }
}

/// `seed`'s particle law (`collision::particle`): the report's response applied to a cloth
/// particle. Nothing before the positions move (the report only looks for vertices inside);
/// after they moved, a particle found inside is pushed out by d² (the report's distance²) and
/// its whole velocity, relative to the thing it is in (a body's point: the body takes the
/// opposite impulse there, so momentum is kept), is reversed and scaled by
/// [`MOMENTUM_FACTOR`]: `u ← −0.4 u`, its tangential part too. A particle has no angular
/// momentum, so the report's `L += (pₖ − x₀) × (−F)` has nothing to kick. Not a tie: an
/// `implicit-euler` cloth's solve under `seed` holds its attachments only, and this acts
/// after it, as for an explicit cloth.
#[derive(Debug, Clone, Copy, Default)]
pub struct Reversed;

/// The particle verb `responses!` dispatches (`collision::particle`).
pub fn particle() -> Reversed {
    Reversed
}

impl ParticleLaw for Reversed {
    fn velocity_target_static(&self, _: &Touch, _: &StepContext) -> Option<f64> {
        None
    }

    fn velocity_target_body(&self, _: &Touch, _: &StepContext) -> Option<f64> {
        None
    }

    fn push_out(&self, depth: f64) -> f64 {
        depth * depth
    }

    fn bounce_static(&self, hit: &Hit, _: &StepContext) -> Option<Vector3<f64>> {
        Some(hit.velocity * MOMENTUM_FACTOR)
    }

    fn collide_target_body(&self, _: f64, _: &StepContext) -> f64 {
        0.0
    }

    fn solve_body(&self, rows: &mut ParticleContacts, _: f64) {
        rows.scale_relative(MOMENTUM_FACTOR);
    }

    fn ties(&self) -> bool {
        false
    }

    fn formulas(&self) -> [&'static str; 2] {
        [
            "particle in an obstacle: x ← x + depth²·n,  v ← −0.4·v  (the whole velocity, as the report's bodies)",
            "particle in a body: u = v_p − (v_b + ω×r),  u ← −0.4·u,  +J on the particle, −J on the body",
        ]
    }
}

#[cfg(test)]
mod tests {
    use crate::physics::collision::obstacle::Ground;
    use super::*;
    use crate::physics::body::Body;
    use crate::physics::collision::{ContactModel, Impacts, Obstacle, Response};
    use crate::physics::effects::Loads;
    use crate::physics::state::State;
    use nalgebra::Vector3;

    #[test]
    fn the_deepest_vertex_pushes_by_its_squared_depth_and_reverses_the_whole_momentum() {
        let body = Body::solid_box(Vector3::repeat(0.2), 1.0).unwrap();
        // Bottom face 5 mm below the ground: the 4 bottom corners tie, the first (index 0,
        // the −x −y −z corner, at (0.9, −0.005, −0.1)) counts.
        let mut state = State {
            position: Vector3::new(1.0, 0.095, 0.0),
            linear_momentum: Vector3::new(2.0, -3.0, 0.5),
            ..State::at_rest()
        };
        let before = state;
        let model = ContactModel {
            response: Response::Seed,
            restitution: 0.9,
            friction: 0.9,
            impacts: Impacts::default(),
        };
        let loads = Loads {
            force: Vector3::new(0.0, -9.81, 0.0),
            torque: Vector3::zeros(),
        };
        let obstacles = [Obstacle::Ground(Ground { height: 0.0 })];
        let input = CollideInput {
            bodies: std::slice::from_ref(&body),
            obstacles: &obstacles,
            model: &model,
            before: std::slice::from_ref(&before),
            loads: std::slice::from_ref(&loads),
            initial_positions: &[Vector3::new(0.0, 1.0, 0.0)],
            context: crate::physics::collision::StepContext::new(
                1e-3,
                Some(Vector3::new(0.0, -9.81, 0.0)),
                Some(&model),
            ),
            joined: &[],
            joints: None,
            recorded: None,
        };
        let mut contacts = Vec::new();
        respond(&input, &mut state, &mut contacts);
        // y: 0.095 + 0.005² = 0.095025 (a metre-squared added to metres).
        assert!(
            (state.position.y - 0.095025).abs() < 1e-15,
            "{}",
            state.position.y
        );
        // P ← −0.4 P: every component, the horizontal ones too.
        let expected_p = Vector3::new(-0.8, 1.2, -0.2);
        assert!((state.linear_momentum - expected_p).norm() < 1e-15);
        // L += (p − x₀) × (−F) = (0.9, −1.005, −0.1) × (0, 9.81, 0) = (0.981, 0, 8.829).
        let expected_l = Vector3::new(0.981, 0.0, 8.829);
        assert!(
            (state.angular_momentum - expected_l).norm() < 1e-12,
            "{:?}",
            state.angular_momentum
        );
        assert_eq!(contacts.len(), 1);
        assert_eq!(contacts[0].feature, Feature::Vertex(0));
        assert!((contacts[0].impulse - (expected_p - before.linear_momentum)).norm() < 1e-15);
    }
}
