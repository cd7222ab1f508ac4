//! What one step of a sheet costs, per particle integrator, in µs/step.
//!
//! The sheet: the design's trampoline, 21 × 21 particles, 2 m × 2 m, 2 kg, stretch 5000 N/m,
//! shear 1000 N/m, damping 0.5 N·s/m, edges pinned, under gravity (no cube: the particle ↔
//! body coupling belongs to the world). It starts flat and sags; the world is put back at its
//! start every [`RESTART_EVERY`] steps.
//!
//! - `implicit-euler` at dt = 1e-3 s (the issue's step) and 5e-3 s (more CG iterations);
//! - `symplectic-euler` at 0.9× its explicit limit (≈ 0.53 ms: dt = 1e-3 is past the limit of
//!   this sheet, where it diverges); an explicit step's cost does not depend on dt.
//!
//! `explicit-limit`: the power iteration for 2/ω_max on the same sheet (done once per scene).
//!
//! `world/cube-on-trampoline-21x21/*`: one `World::step()` of the same sheet (damping 20 N·s/m)
//! with a 0.35 m, 1 kg cube dropped from 0.1 m above it, through the world's phases: body
//! step, sheet step, particle–body contacts (the issue's benchmark; its aim ≤ 50 µs/step at
//! dt = 1e-3). Restarted every [`RESTART_EVERY`] steps (2 s: the fall, the bounces, the rest).
//! `symplectic-euler` runs there at 0.9× that sheet's explicit limit: its damping
//! (20 N·s/m on particles of 4.5 g) makes 2/γ_max ≈ 5.7e-5 s the limit, so dt ≈ 5.1e-5 s and
//! its 2000 steps are the first 0.1 s (the fall, before the cube touches); per step it costs
//! what it costs at any dt, but one simulated second takes ~20× more of its steps than of
//! `implicit-euler`'s at 1e-3.
//!
//! Instruction counts (stable where wall-clock times on a shared machine are not):
//! `examples/cloth_steps.rs` under `valgrind --tool=callgrind`.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use std::hint::black_box;
use std::time::Duration;
use tumble::physics::cloth::{Cloth, ClothIntegrator, ClothLoads, ClothSpec, Pinning};

const RESTART_EVERY: u64 = 2_000;

fn trampoline(integrator: ClothIntegrator) -> Cloth {
    let mut spec = ClothSpec::new([2.0, 2.0], [21, 21], 2.0, 5000.0);
    spec.position = Vector3::new(0.0, 1.0, 0.0);
    spec.shear = 1000.0;
    spec.damping = 0.5;
    spec.pinned = Pinning::Edges;
    spec.integrator = integrator;
    Cloth::new(&spec).expect("valid sheet")
}

fn loads() -> ClothLoads {
    ClothLoads {
        gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
        drag: None,
    }
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("cloth/trampoline-21x21");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let explicit_dt = 0.9
        * trampoline(ClothIntegrator::SymplecticEuler)
            .explicit_limit(&loads())
            .dt();
    for (name, integrator, dt) in [
        (
            "symplectic-euler",
            ClothIntegrator::SymplecticEuler,
            explicit_dt,
        ),
        (
            "implicit-euler/dt=1e-3",
            ClothIntegrator::ImplicitEuler,
            1e-3,
        ),
        (
            "implicit-euler/dt=5e-3",
            ClothIntegrator::ImplicitEuler,
            5e-3,
        ),
    ] {
        let start = trampoline(integrator);
        let mut cloth = start.clone();
        let loads = loads();
        let mut steps = 0u64;
        group.bench_function(name, |b| {
            b.iter(|| {
                steps += 1;
                if steps.is_multiple_of(RESTART_EVERY) {
                    cloth.clone_from(&start);
                }
                black_box(black_box(&mut cloth).step(&loads, dt));
            })
        });
    }
    let sheet = trampoline(ClothIntegrator::SymplecticEuler);
    group.bench_function("explicit-limit", |b| {
        b.iter(|| black_box(black_box(&sheet).explicit_limit(&loads())))
    });
    group.finish();
}

/// The cube on the trampoline as a scene file, with the sheet's integrator and dt.
fn cube_on_trampoline(integrator: &str, dt: f64) -> tumble::physics::World {
    let source = format!(
        r#"
title = "bench"
[scene]
dt = {dt}
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = {{ response = "impulse", restitution = 0.4, friction = 0.5 }}
[body]
shape = "box"
size = [0.35, 0.35, 0.35]
mass = 1.0
position = [0.0, 1.275, 0.0]
[[cloth]]
size = [2.0, 2.0]
count = [21, 21]
position = [0.0, 1.0, 0.0]
mass = 2.0
stretch = 5000.0
shear = 1000.0
damping = 20.0
pinned = "edges"
integrator = "{integrator}"
"#
    );
    tumble::scene::parse(&source, std::path::Path::new("bench.toml"))
        .expect("valid scene")
        .scene
        .world()
}

fn world(c: &mut Criterion) {
    let mut group = c.benchmark_group("world/cube-on-trampoline-21x21");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    let probe = cube_on_trampoline("symplectic-euler", 1e-3);
    let explicit_dt = 0.9 * probe.cloth_limit(0).dt();
    for (name, integrator, dt) in [
        ("symplectic-euler", "symplectic-euler", explicit_dt),
        ("implicit-euler/dt=1e-3", "implicit-euler", 1e-3),
    ] {
        let mut w = cube_on_trampoline(integrator, dt);
        let start = w.checkpoint();
        let mut steps = 0u64;
        group.bench_function(name, |b| {
            b.iter(|| {
                steps += 1;
                if steps.is_multiple_of(RESTART_EVERY) {
                    w.restore(&start);
                }
                black_box(&mut w).step();
            })
        });
    }
    group.finish();
}

criterion_group!(benches, step, world);
criterion_main!(benches);
