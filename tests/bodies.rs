//! Several bodies touching along faces and edges (issue 10): head-on collisions against the
//! closed-form exchange of momentum, momentum kept through contacts, stacks, plates on a pillar
//! and on a sphere, a bar across a ridge, static friction on a slope and on a sphere.
//! Scenes are written as scene files, exactly as a teacher would.

use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::World;
use tumble::scene::parse;

fn world(source: &str) -> World {
    parse(source, Path::new("test.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
        .world()
}

fn run(world: &mut World, seconds: f64) {
    let steps = (seconds / world.dt()).round() as u64;
    for _ in 0..steps {
        world.step();
        if let Some(d) = world.divergence() {
            panic!("{d}");
        }
    }
}

fn velocity(world: &World, body: usize) -> Vector3<f64> {
    world.states()[body].linear_momentum / world.bodies()[body].mass
}

/// Two 0.2 m cubes of 1 kg on the x axis, A moving at 2 m/s towards B at rest; no gravity.
fn head_on(restitution: f64) -> String {
    format!(
        r#"
title = "head-on"
[scene]
dt = 0.001
integrator = "rk4"
contact = {{ response = "impulse", restitution = {restitution}, friction = 0.0 }}
[[body]]
name = "a"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [-0.5, 0.0, 0.0]
velocity = [2.0, 0.0, 0.0]
[[body]]
name = "b"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [0.5, 0.0, 0.0]
"#
    )
}

#[test]
fn equal_cubes_head_on_exchange_velocities_when_elastic() {
    let mut w = world(&head_on(1.0));
    run(&mut w, 1.0);
    // e = 1, equal masses: A stops, B leaves at A's 2 m/s (Newton's cradle).
    let (va, vb) = (velocity(&w, 0), velocity(&w, 1));
    assert!(va.norm() < 1e-9, "A keeps {va:?}");
    assert!(
        (vb - Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-9,
        "B has {vb:?}"
    );
    // Kinetic energy ½·1·2² = 2 J, kept.
    let e = w.total_energy().kinetic;
    assert!((e - 2.0).abs() < 1e-9, "K = {e}");
}

#[test]
fn equal_cubes_head_on_share_velocity_and_lose_half_the_energy_when_inelastic() {
    let mut w = world(&head_on(0.0));
    run(&mut w, 1.0);
    // e = 0: both move on at (1·2 + 1·0)/2 = 1 m/s; K = 2·½·1·1² = 1 J of the 2 J.
    let (va, vb) = (velocity(&w, 0), velocity(&w, 1));
    assert!(
        (va - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-9,
        "A has {va:?}"
    );
    assert!(
        (vb - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-9,
        "B has {vb:?}"
    );
    let e = w.total_energy().kinetic;
    assert!((e - 1.0).abs() < 1e-9, "K = {e}");
}

#[test]
fn head_on_collisions_keep_total_momentum_to_round_off() {
    for e in [0.0, 0.5, 1.0] {
        let mut w = world(&head_on(e));
        let p0 = w.snapshot().system.linear_momentum;
        let l0 = w.snapshot().system.angular_momentum;
        for _ in 0..1000 {
            w.step();
            let s = w.snapshot().system;
            assert!(
                (s.linear_momentum - p0).norm() < 1e-12,
                "e = {e}: P {:?}",
                s.linear_momentum
            );
            assert!(
                (s.angular_momentum - l0).norm() < 1e-12,
                "e = {e}: L {:?}",
                s.angular_momentum
            );
        }
    }
}
