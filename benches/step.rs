//! What one `World::step()` costs, per integrator and per scene, in ns/step.
//!
//! Scenes (built with the physics API, no files):
//! - `free`: the torque-free tumbling box 1.0 × 0.4 × 0.1 m, 1 kg, ω_body = (0.01, 10, 0.01):
//!   no effects at all, so the forces phase evaluates nothing;
//! - `falling`: the same box under gravity;
//! - `falling+drag`: gravity and viscous drag: adding effects is what adds cost.
//! - `resting-cube`: a cube (side 0.2 m, 1 kg) lying on the ground under gravity, `impulse`
//!   response (e = 0.4, μ = 0.5): every step tests its 8 vertices and resolves the 4 resting
//!   contacts (issue 3's target: under 300 ns/step with `rk4`).
//!
//! Each world is stepped in place and put back at its start every [`RESTART_EVERY`] steps (so
//! `euler-seed`'s drifting matrix and a falling body's speed stay in a representative range).
//!
//! To add a scene, add a line to [`scenes`].
//!
//! `equal-error/*`: the cost of one simulated second of the fast tumble (the study's
//! `tumbling-box`, ω_body = (1, 10, 1), torque-free) at the time step where each integrator's
//! error over 10 s (max over samples every 0.1 s of the angle to the closed form) is at most
//! 1e-9 rad: `rk4` at the dt found by its fourth order (printed with its error), the
//! `exact-splitting` pair at dt = 0.1 s (exact: its error is round-off, printed too).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{UnitQuaternion, Vector3};
use std::hint::black_box;
use std::time::Duration;
use tumble::physics::collision::obstacle::Ground;
use tumble::physics::free_top::{rotation_angle_between, FreeBody};
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, Obstacle, Orientation, Response,
    State, World,
};

/// Steps between two restarts from the initial state (restoring costs one `Vec` clone).
const RESTART_EVERY: u64 = 10_000;

/// The box of the tennis-racket lesson.
fn tumbling_box() -> Body {
    Body::solid_box(Vector3::new(1.0, 0.4, 0.1), 1.0).expect("valid box")
}

/// The box spinning near its intermediate axis, at 2 m, at rest otherwise.
fn tumbling_state(body: &Body) -> State {
    let omega_body = Vector3::new(0.01, 10.0, 0.01);
    State {
        position: Vector3::new(0.0, 2.0, 0.0),
        orientation: Orientation::Quaternion(UnitQuaternion::identity()),
        linear_momentum: Vector3::zeros(),
        angular_momentum: body.inertia_body * omega_body,
    }
}

/// A world holding the tumbling box with the given effects.
fn box_world(effects: Vec<Effect>, integrator: Integrator) -> World {
    let body = tumbling_box();
    let state = tumbling_state(&body);
    World::new(
        body,
        Effects::new(effects),
        Vec::new(),
        None,
        integrator,
        1e-3,
        state,
    )
}

/// A 0.2 m cube at rest on the ground y = 0 (barycenter 0.1 m up), `impulse` contact.
fn resting_cube(integrator: Integrator) -> World {
    let body = Body::solid_box(Vector3::repeat(0.2), 1.0).expect("valid box");
    let state = State {
        position: Vector3::new(0.0, 0.1, 0.0),
        ..State::at_rest()
    };
    World::new(
        body,
        Effects::new(vec![GRAVITY]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            response: Response::Impulse,
            restitution: 0.4,
            friction: 0.5,
            impacts: Impacts::default(),
        }),
        integrator,
        1e-3,
        state,
    )
}

const GRAVITY: Effect = Effect::Gravity(Vector3::new(0.0, -9.81, 0.0));
const DRAG: Effect = Effect::Drag {
    linear: 0.05,
    angular: 0.01,
};

/// A benchmarked scene: its name and how to build its world for an integrator.
struct Case {
    name: &'static str,
    build: fn(Integrator) -> World,
}

/// The benchmarked scenes.
fn scenes() -> Vec<Case> {
    vec![
        Case {
            name: "free",
            build: |i| box_world(Vec::new(), i),
        },
        Case {
            name: "falling",
            build: |i| box_world(vec![GRAVITY], i),
        },
        Case {
            name: "falling+drag",
            build: |i| box_world(vec![GRAVITY, DRAG], i),
        },
        Case {
            name: "resting-cube",
            build: resting_cube,
        },
    ]
}

fn step(c: &mut Criterion) {
    for Case { name, build } in scenes() {
        let mut group = c.benchmark_group(format!("step/{name}"));
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2));
        for integrator in Integrator::ALL {
            let mut world = build(integrator);
            let start = world.checkpoint();
            let mut steps = 0u64;
            group.bench_function(BenchmarkId::from_parameter(integrator.name()), |b| {
                b.iter(|| {
                    steps += 1;
                    if steps.is_multiple_of(RESTART_EVERY) {
                        world.restore(&start);
                    }
                    black_box(&mut world).step();
                    black_box(world.state());
                })
            });
        }
        group.finish();
    }
}

/// The fast tumble: the box at ω_body = (1, 10, 1), torque-free.
fn fast_tumble(integrator: Integrator, dt: f64) -> World {
    let body = tumbling_box();
    let state = State {
        angular_momentum: body.inertia_body * Vector3::new(1.0, 10.0, 1.0),
        ..State::at_rest()
    };
    World::new(
        body,
        Effects::default(),
        Vec::new(),
        None,
        integrator,
        dt,
        state,
    )
}

/// The error over 10 s: max over samples every 0.1 s of the angle to the closed form, rad.
fn fast_tumble_error(integrator: Integrator, dt: f64) -> f64 {
    let mut world = fast_tumble(integrator, dt);
    let state = *world.state();
    let mut truth = FreeBody::new(
        world.body(),
        state.orientation.quaternion(),
        state.angular_momentum,
    );
    let per_sample = (0.1 / dt).round() as u64;
    let mut worst = 0.0f64;
    for _ in 0..100 {
        for _ in 0..per_sample {
            world.step();
        }
        let t = world.time();
        let q = world.state().orientation.quaternion();
        worst = worst.max(rotation_angle_between(&truth.orientation(t), &q));
    }
    worst
}

/// The largest dt = 0.1/n at which `integrator` (order `order`) keeps the error ≤ `target`,
/// found from its order and checked; with the error there.
fn step_for_error(integrator: Integrator, order: f64, target: f64) -> (f64, f64) {
    let error_at = |n: u64| fast_tumble_error(integrator, 0.1 / n as f64);
    // Grow n by the order's estimate until the error is under the target…
    let (mut failing, mut n) = (0u64, 1u64);
    let mut error = error_at(n);
    while error > target {
        failing = n;
        let guess = (n as f64 * (error / target).powf(1.0 / order)).ceil() as u64;
        n = guess.max(n + 1);
        error = error_at(n);
    }
    // …then bisect down to the fewest steps that still get there.
    while n - failing > 1 {
        let mid = (n + failing) / 2;
        let e = error_at(mid);
        if e <= target {
            (n, error) = (mid, e);
        } else {
            failing = mid;
        }
    }
    (0.1 / n as f64, error)
}

fn equal_error(c: &mut Criterion) {
    const TARGET: f64 = 1e-9;
    let mut group = c.benchmark_group("equal-error");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(20);
    for (integrator, order) in [
        (Integrator::Rk4, 4.0),
        (Integrator::ExactSplitting, 2.0),
        (Integrator::ExactSplitting4, 4.0),
    ] {
        let (dt, error) = step_for_error(integrator, order, TARGET);
        let steps = (1.0 / dt).round() as u64;
        println!(
            "equal-error/{}: dt = {dt:.3e} s ({steps} steps per simulated second), \
             error over 10 s {error:.2e} rad",
            integrator.name()
        );
        let mut world = fast_tumble(integrator, dt);
        let start = world.checkpoint();
        group.bench_function(
            BenchmarkId::new("one simulated second", integrator.name()),
            |b| {
                b.iter(|| {
                    world.restore(&start);
                    for _ in 0..steps {
                        black_box(&mut world).step();
                    }
                    black_box(world.state());
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, step, equal_error);
criterion_main!(benches);
