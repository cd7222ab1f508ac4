//! The joint benches' chains (issue 19, issue 36's hinge chain), built in code so the benches
//! (`benches/joints.rs`), the instruction-count example (`examples/chain_steps.rs`) and the
//! tests measure the same world:
//!
//! - `chain(count, kind, correction)`: `count` links of 0.5 × 0.05 × 0.05 m (0.1 kg) along x
//!   from the origin, `kind`-jointed end to end and the first to the world (axis z), released
//!   horizontal, no contact;
//! - `landing_chain(count, l, tilt, height)`: `count` links of `l` × 0.05 × 0.05 m (0.1 kg)
//!   ball-jointed end to end (not to the world), along a line tilted `tilt` from the
//!   horizontal with its low end `height` above the ground; `impulse` contacts (e = 0, μ = 0.5).
//!
//! Both: `rk4`, dt = 1e-3, gravity −9.81 m/s² along y.

use crate::physics::collision::obstacle::Ground;
use crate::physics::joints::{Correction, Joint, JointKind, Links};
use crate::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Orientation,
    Response, State, World,
};
use nalgebra::{UnitQuaternion, Vector3};

fn gravity() -> Effects {
    Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))])
}

/// `count` links of 0.5 m along x from the origin, `kind`-jointed end to end and the first to
/// the world (axis z), with the given joint correction.
pub fn chain(count: usize, kind: JointKind, correction: Correction) -> World {
    let l = 0.5;
    let bodies: Vec<NamedBody> = (0..count)
        .map(|i| NamedBody {
            name: format!("link{i}"),
            body: Body::solid_box(Vector3::new(l, 0.05, 0.05), 0.1).expect("a box"),
            initial: State {
                position: Vector3::new((i as f64 + 0.5) * l, 0.0, 0.0),
                ..State::at_rest()
            },
        })
        .collect();
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joints = (0..count)
        .map(|i| {
            Joint::at_point(
                format!("j{i}"),
                kind,
                i,
                i.checked_sub(1),
                Vector3::new(i as f64 * l, 0.0, 0.0),
                Vector3::z(),
                &states,
            )
        })
        .collect();
    World::with_bodies(bodies, gravity(), Vec::new(), None, Integrator::Rk4, 1e-3).with_links(
        Links {
            joints,
            springs: Vec::new(),
            correction,
        },
    )
}

/// `count` links of `l` × 0.05 × 0.05 m (0.1 kg) end to end, ball-jointed to each other (not
/// to the world), along a line tilted `tilt` (rad) from the horizontal with its low end at
/// `height` above the ground; impulse contacts (e = 0, μ = 0.5).
pub fn landing_chain(count: usize, l: f64, tilt: f64, height: f64) -> World {
    let along = Vector3::new(tilt.cos(), tilt.sin(), 0.0);
    let start = Vector3::new(0.0, height, 0.0);
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), tilt);
    let bodies: Vec<NamedBody> = (0..count)
        .map(|i| NamedBody {
            name: format!("link{i}"),
            body: Body::solid_box(Vector3::new(l, 0.05, 0.05), 0.1).expect("a box"),
            initial: State {
                position: start + along * ((i as f64 + 0.5) * l),
                orientation: Orientation::Quaternion(turn),
                ..State::at_rest()
            },
        })
        .collect();
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joints = (1..count)
        .map(|i| {
            let at = start + along * (i as f64 * l);
            Joint::at_point(
                format!("j{i}"),
                JointKind::Ball,
                i,
                Some(i - 1),
                at,
                Vector3::z(),
                &states,
            )
        })
        .collect();
    let contact = ContactModel {
        response: Response::Impulse,
        restitution: 0.0,
        friction: 0.5,
        impacts: Impacts::default(),
    };
    World::with_bodies(
        bodies,
        gravity(),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(contact),
        Integrator::Rk4,
        1e-3,
    )
    .with_links(Links {
        joints,
        ..Links::default()
    })
}
