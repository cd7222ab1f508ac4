//! Steps one of the joint benches' chains (`benches/joints.rs`) a given number of times, for
//! instruction counts (`valgrind --tool=callgrind`, stable where wall-clock times are not) and
//! for comparing trajectories before and after a change of the joints' solver:
//!
//! ```text
//! cargo build --release --example chain_steps
//! target/release/examples/chain_steps CHAIN STEPS [INTEGRATOR]
//! ```
//!
//! CHAIN: `ball` (chain-10), `hinge` (chain-10-hinge: the same links on hinges about z, as
//! benches/mujoco/chain10.py's) or `landing` (chain-10-landing); INTEGRATOR: a scene-file name
//! (rk4 by default). The chains are put back at their start every 2000 steps (the landing every
//! 3000), as the bench does, unless `CHAIN_STEPS_CSV=N` is set: then the chain runs on and every
//! N steps one line `t,x,y,z,qw,qx,qy,qz,Px,Py,Pz,Lx,Ly,Lz` per body is printed, full precision
//! (`{:e}`), to compare runs. The last line gives the mean µs per step.

use nalgebra::Vector3;
use std::time::Instant;
use tumble::physics::joints::{Correction, Joint, JointKind, Links};
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Orientation,
    Response, State, World,
};

fn gravity() -> Effects {
    Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))])
}

/// `count` links of 0.5 m along x from the origin, `kind`-jointed end to end (axis z).
fn chain(count: usize, kind: JointKind) -> World {
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
            let at = Vector3::new(i as f64 * l, 0.0, 0.0);
            Joint::at_point(
                format!("j{i}"),
                kind,
                i,
                i.checked_sub(1),
                at,
                Vector3::z(),
                &states,
            )
        })
        .collect();
    World::with_bodies(bodies, gravity(), Vec::new(), None, Integrator::Rk4, 1e-3).with_links(
        Links {
            joints,
            springs: Vec::new(),
            correction: Correction::Projection,
        },
    )
}

/// The landing chain of benches/joints.rs.
fn landing(count: usize) -> World {
    let (l, tilt) = (0.3, 20.0_f64.to_radians());
    let along = Vector3::new(tilt.cos(), tilt.sin(), 0.0);
    let start = Vector3::new(0.0, 0.3, 0.0);
    let turn = nalgebra::UnitQuaternion::from_axis_angle(&Vector3::z_axis(), tilt);
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
        vec![Obstacle::Ground { height: 0.0 }],
        Some(contact),
        Integrator::Rk4,
        1e-3,
    )
    .with_links(Links {
        joints,
        ..Links::default()
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: chain_steps ball|hinge|landing STEPS [INTEGRATOR]";
    let name = args.get(1).expect(usage);
    let steps: u64 = args.get(2).and_then(|s| s.parse().ok()).expect(usage);
    let integrator = args.get(3).map_or(Integrator::Rk4, |s| {
        Integrator::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .expect("an integrator name")
    });
    let (mut world, period) = match name.as_str() {
        "ball" => (chain(10, JointKind::Ball), 2000),
        "hinge" => (chain(10, JointKind::Hinge), 2000),
        "landing" => (landing(10), 3000),
        _ => panic!("{usage}"),
    };
    world.set_integrator(integrator);
    let every: Option<u64> = std::env::var("CHAIN_STEPS_CSV")
        .ok()
        .and_then(|s| s.parse().ok());
    let start = world.checkpoint();
    let clock = Instant::now();
    for step in 1..=steps {
        if every.is_none() && step.is_multiple_of(period) {
            world.restore(&start);
        }
        world.step();
        if let Some(n) = every {
            if step.is_multiple_of(n) {
                for s in world.states() {
                    let q = s.orientation.quaternion();
                    let (p, l) = (s.linear_momentum, s.angular_momentum);
                    println!(
                        "{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
                        world.time(),
                        s.position.x,
                        s.position.y,
                        s.position.z,
                        q.w,
                        q.i,
                        q.j,
                        q.k,
                        p.x,
                        p.y,
                        p.z,
                        l.x,
                        l.y,
                        l.z
                    );
                }
            }
        }
    }
    let per_step = clock.elapsed().as_secs_f64() / steps as f64 * 1e6;
    eprintln!("{name} under {}: {per_step:.2} µs/step", integrator.name());
}
