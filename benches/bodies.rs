//! What one `World::step()` costs with several bodies touching (issue 10), in ns/step, `rk4`,
//! dt = 1e-3, `impulse` response (e = 0.4, μ = 0.5 unless stated):
//!
//! - `resting-cube`: one 0.2 m cube of 1 kg at rest on the ground (issue 10's aim: < 500 ns);
//! - `stack-3`, `stack-10`: 3 and 10 such cubes standing on each other on the ground, e = 0
//!   (issue 10's aim for 10: ≤ 3 µs per step, its top within 1 mm after 5 s — that bound is a
//!   test in `tests/physics/bodies.rs`; for comparison, issue 10 quotes MuJoCo 4.0 at about 55 µs and
//!   Rapier 0.36 at about 21 µs per step on this machine);
//! - `colliding-cubes`: two cubes 2 cm apart closing at 2 m/s head-on, no gravity: they meet
//!   after 10 steps and part at 0.8 m/s; restarted every 100 steps, so every sample is an
//!   impact and the contact geometry of two near boxes.
//!
//! - `sphere-rolling`, `cylinder-rolling`: a solid ball (r = 0.1 m) and a solid cylinder
//!   (r = 0.1 m, length 0.2 m) of 1 kg rolling down a 20° plane obstacle from rest, μ = 0.5,
//!   e = 0; restarted every 1000 steps (1 s of rolling).
//!
//! Each world is stepped in place and put back at its start every `restart` steps.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use std::hint::black_box;
use std::time::Duration;
use tumble::physics::collision::obstacle::{Ground, Plane};
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Response, State,
    World,
};

const SIDE: f64 = 0.2;
const GRAVITY: Effect = Effect::Gravity(Vector3::new(0.0, -9.81, 0.0));

fn cube(name: String, position: Vector3<f64>, velocity: Vector3<f64>) -> NamedBody {
    let body = Body::solid_box(Vector3::repeat(SIDE), 1.0).expect("valid box");
    NamedBody {
        name,
        initial: State {
            position,
            linear_momentum: velocity * body.mass,
            ..State::at_rest()
        },
        body,
    }
}

fn model(restitution: f64) -> Option<ContactModel> {
    Some(ContactModel {
        response: Response::Impulse,
        restitution,
        friction: 0.5,
        impacts: Impacts::default(),
    })
}

/// `count` cubes touching on the ground, barycenters at 0.1, 0.3, … m.
fn stack(count: usize, restitution: f64) -> World {
    let bodies = (0..count)
        .map(|i| {
            let y = SIDE / 2.0 + SIDE * i as f64;
            cube(
                format!("cube{i}"),
                Vector3::new(0.0, y, 0.0),
                Vector3::zeros(),
            )
        })
        .collect();
    World::with_bodies(
        bodies,
        Effects::new(vec![GRAVITY]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        model(restitution),
        Integrator::Rk4,
        1e-3,
    )
}

fn colliding_cubes() -> World {
    let x = SIDE / 2.0 + 0.01;
    let bodies = vec![
        cube(
            "left".into(),
            Vector3::new(-x, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
        ),
        cube(
            "right".into(),
            Vector3::new(x, 0.0, 0.0),
            Vector3::new(-1.0, 0.0, 0.0),
        ),
    ];
    World::with_bodies(
        bodies,
        Effects::default(),
        Vec::new(),
        model(0.4),
        Integrator::Rk4,
        1e-3,
    )
}

/// A benchmarked scene: its name, its world, and how many steps between restarts.
struct Case {
    name: &'static str,
    world: World,
    restart: u64,
}

/// A round body of radius 0.1 m resting on a 20° ramp (turned to lie across the slope if
/// `lying`), about to roll.
fn rolling(body: Body, lying: bool) -> World {
    let theta = 20f64.to_radians();
    let normal = Vector3::new(theta.sin(), theta.cos(), 0.0);
    let orientation = if lying {
        nalgebra::UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
    } else {
        nalgebra::UnitQuaternion::identity()
    };
    let bodies = vec![NamedBody {
        name: "roller".into(),
        initial: State {
            position: normal * 0.1,
            orientation: tumble::physics::Orientation::Quaternion(orientation),
            ..State::at_rest()
        },
        body,
    }];
    World::with_bodies(
        bodies,
        Effects::new(vec![GRAVITY]),
        vec![Obstacle::Plane(Plane {
            point: Vector3::zeros(),
            normal,
        })],
        Some(ContactModel {
            response: Response::Impulse,
            restitution: 0.0,
            friction: 0.5,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        1e-3,
    )
}

fn bodies(c: &mut Criterion) {
    let cases = [
        Case {
            name: "resting-cube",
            world: stack(1, 0.4),
            restart: 10_000,
        },
        Case {
            name: "stack-3",
            world: stack(3, 0.0),
            restart: 10_000,
        },
        Case {
            name: "stack-10",
            world: stack(10, 0.0),
            restart: 10_000,
        },
        Case {
            name: "colliding-cubes",
            world: colliding_cubes(),
            restart: 100,
        },
        Case {
            name: "sphere-rolling",
            world: rolling(Body::sphere(0.1, 1.0, false).expect("valid ball"), false),
            restart: 1000,
        },
        Case {
            name: "cylinder-rolling",
            world: rolling(
                Body::cylinder(0.1, 0.2, 1.0, false).expect("valid cylinder"),
                true,
            ),
            restart: 1000,
        },
    ];
    let mut group = c.benchmark_group("bodies");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for Case {
        name,
        mut world,
        restart,
    } in cases
    {
        let start = world.checkpoint();
        let mut steps = 0u64;
        group.bench_function(name, |b| {
            b.iter(|| {
                steps += 1;
                if steps.is_multiple_of(restart) {
                    world.restore(&start);
                }
                black_box(&mut world).step();
                black_box(world.states());
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bodies);
criterion_main!(benches);
