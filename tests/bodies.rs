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

/// A scene with gravity, the impulse response and `bodies` (each a `[[body]]` table's keys).
fn with_gravity(gravity: [f64; 3], friction: f64, obstacles: &str, bodies: &[&str]) -> String {
    let mut s = format!(
        r#"
title = "t"
[scene]
dt = 0.001
integrator = "rk4"
gravity = {gravity:?}
contact = {{ response = "impulse", restitution = 0.0, friction = {friction} }}
{obstacles}
"#
    );
    for b in bodies {
        s.push_str("[[body]]\n");
        s.push_str(b);
        s.push('\n');
    }
    s
}

const GROUND: &str = "[[obstacle]]\ntype = \"ground\"\nheight = 0.0\n";

fn cube_at(y: f64) -> String {
    format!("shape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 1.0\nposition = [0.0, {y}, 0.0]")
}

#[test]
fn a_stack_of_three_cubes_stands_still_for_five_seconds() {
    let cubes: Vec<String> = (0..3).map(|i| cube_at(0.1 + 0.2 * i as f64)).collect();
    let refs: Vec<&str> = cubes.iter().map(String::as_str).collect();
    let mut w = world(&with_gravity([0.0, -9.81, 0.0], 0.5, GROUND, &refs));
    let start: Vec<Vector3<f64>> = w.states().iter().map(|s| s.position).collect();
    run(&mut w, 5.0);
    for (i, (s, x0)) in w.states().iter().zip(&start).enumerate() {
        let moved = (s.position - x0).norm();
        assert!(moved < 1e-3, "cube {i} moved {moved} m");
    }
}

/// 30° slope as tilted gravity: g = 9.81 (sin 30°, −cos 30°, 0) on flat ground.
fn slope(friction: f64) -> World {
    let t = 30f64.to_radians();
    let g = [9.81 * t.sin(), -9.81 * t.cos(), 0.0];
    world(&with_gravity(g, friction, GROUND, &[&cube_at(0.1)]))
}

#[test]
fn static_friction_holds_a_cube_on_a_slope_for_a_minute() {
    // tan 30° = 0.577 < μ = 0.7: the cube must not move at all (the creep was ½ g_t dt² per
    // step, 2.45 mm per simulated second).
    let mut w = slope(0.7);
    let x0 = w.state().position;
    run(&mut w, 60.0);
    let moved = (w.state().position - x0).norm();
    assert!(moved < 1e-4, "crept {moved} m in 60 s");
}

#[test]
fn above_the_friction_angle_the_cube_slides_with_g_sin_minus_mu_g_cos() {
    // μ = 0.3 < tan 30°: a = g (sin θ − μ cos θ) = 9.81 (0.5 − 0.3·0.8660) = 2.3563 m/s².
    let mut w = slope(0.3);
    let t = 30f64.to_radians();
    let a = 9.81 * (t.sin() - 0.3 * t.cos());
    let x0 = w.state().position.x;
    run(&mut w, 1.0);
    let v = velocity(&w, 0).x;
    let x = w.state().position.x - x0;
    assert!((v - a).abs() < 1e-3 * a, "v = {v}, expected {a}");
    // Position: ½ a t² to first order in dt (the contact step advances with the new velocity).
    assert!(
        (x - 0.5 * a).abs() < 2e-3 * a,
        "x = {x}, expected {}",
        0.5 * a
    );
}
