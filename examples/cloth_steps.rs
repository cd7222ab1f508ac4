//! Steps the benches' cloth cases a given number of times, for instruction counts under
//! `valgrind --tool=callgrind` (stable where wall-clock times are not):
//!
//! ```text
//! cargo build --release --example cloth_steps
//! valgrind --tool=callgrind target/release/examples/cloth_steps CASE STEPS
//! ```
//!
//! CASE: `world-symplectic`, `world-implicit` (the cube on the 21 × 21 trampoline, as in
//! `benches/cloth.rs`: symplectic-euler at 0.9× its explicit limit, implicit-euler at 1e-3 s),
//! `sheet-symplectic`, `sheet-implicit-1e-3`, `sheet-implicit-5e-3` (the sheet alone).
//! Instructions per step = (count at STEPS − count at 0)/STEPS; 2000 steps is one restart
//! cycle of the benches (fall, bounces, rest). Each case prints `bits=`, a checksum of the
//! final state's bits (a change meant to leave the physics alone must leave it alone), and on
//! stderr the wall-clock µs per step of the steps alone (no setup; a shared machine's figure).
//! `FRICTION` (world cases) sets the contact's μ, `DT` the world-implicit step, `SKIP` a number
//! of steps run before the counted ones (`SKIP=3000` for the cube at rest: instructions per
//! step = (count at SKIP + STEPS − count at SKIP + 0)/STEPS).

use nalgebra::Vector3;
use std::hint::black_box;
use tumble::physics::cloth::{Cloth, ClothIntegrator, ClothLoads, ClothSpec, Pinning};

fn trampoline(integrator: ClothIntegrator) -> Cloth {
    let mut spec = ClothSpec::new([2.0, 2.0], [21, 21], 2.0, 5000.0);
    spec.position = Vector3::new(0.0, 1.0, 0.0);
    spec.shear = 1000.0;
    spec.damping = 0.5;
    spec.pinned = Pinning::Edges;
    spec.integrator = integrator;
    Cloth::new(&spec).expect("valid sheet")
}

fn cube_on_trampoline(integrator: &str, dt: f64) -> tumble::physics::World {
    // FRICTION: the contact's μ (0.5 unless given).
    let friction: f64 = std::env::var("FRICTION")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.5);
    let source = format!(
        r#"
title = "bench"
[scene]
dt = {dt}
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = {{ response = "impulse", restitution = 0.4, friction = {friction} }}
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

/// A checksum of the bits of every number listed (FNV-1a over their `to_bits`): two runs with
/// the same checksum computed the same numbers to the last bit.
fn checksum<'a>(numbers: impl IntoIterator<Item = &'a f64>) -> u64 {
    numbers.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, x| {
        (h ^ x.to_bits()).wrapping_mul(0x0100_0000_01b3)
    })
}

/// The checksum of a sheet's positions and velocities.
fn cloth_bits(c: &Cloth) -> u64 {
    checksum(
        c.positions
            .iter()
            .chain(&c.velocities)
            .flat_map(|v| v.iter()),
    )
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case = args.get(1).map_or("world-implicit", String::as_str);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2000);
    let loads = ClothLoads {
        gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
        drag: None,
    };
    match case {
        "world-symplectic" | "world-implicit" => {
            let probe = cube_on_trampoline("symplectic-euler", 1e-3);
            let (name, dt) = if case == "world-symplectic" {
                ("symplectic-euler", 0.9 * probe.cloth_limit(0).dt())
            } else {
                (
                    "implicit-euler",
                    std::env::var("DT")
                        .ok()
                        .and_then(|s| s.parse().ok())
                        .unwrap_or(1e-3),
                )
            };
            let mut w = cube_on_trampoline(name, dt);
            let (mut solves, mut iterations) = (0, 0);
            // Per number of solves in a step (0 contacts; 1, 2, 3+ solves with contacts):
            // steps and CG iterations.
            let mut by_solves = [(0usize, 0usize); 4];
            let skip: usize = std::env::var("SKIP")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(0);
            for _ in 0..skip {
                w.step();
            }
            let clock = std::time::Instant::now();
            for _ in 0..steps {
                black_box(&mut w).step();
                let counts = w.cloths()[0].solve_counts();
                solves += counts.solves;
                iterations += counts.iterations;
                let kind = if w.cloth_body_contacts(0) == 0 {
                    0
                } else {
                    counts.solves.min(3)
                };
                by_solves[kind].0 += 1;
                by_solves[kind].1 += counts.iterations;
            }
            let elapsed = clock.elapsed();
            if std::env::var("BREAKDOWN").is_ok() {
                for (k, (n, it)) in by_solves.iter().enumerate() {
                    println!("{k}: steps {n}, CG iterations {it}");
                }
            }
            let c = &w.cloths()[0];
            eprintln!(
                "{case}: {:.1} µs/step (wall clock, steps only)",
                elapsed.as_secs_f64() * 1e6 / steps.max(1) as f64
            );
            let s = w.state();
            let rotation = s.orientation.matrix();
            let body_bits = checksum(
                s.position
                    .iter()
                    .chain(rotation.iter())
                    .chain(s.linear_momentum.iter())
                    .chain(s.angular_momentum.iter()),
            );
            println!(
                "{case} dt={dt:.6e} steps={steps} solves={solves} cg_iterations={iterations} y_min={:.9} cube_y={:.9} bits={:016x}",
                c.positions
                    .iter()
                    .map(|x| x.y)
                    .fold(f64::INFINITY, f64::min),
                w.state().position.y,
                cloth_bits(c) ^ body_bits.rotate_left(1),
            );
        }
        "sheet-symplectic" | "sheet-implicit-1e-3" | "sheet-implicit-5e-3" => {
            let (integrator, dt) = match case {
                "sheet-symplectic" => (
                    ClothIntegrator::SymplecticEuler,
                    0.9 * trampoline(ClothIntegrator::SymplecticEuler)
                        .explicit_limit(&loads)
                        .dt(),
                ),
                "sheet-implicit-1e-3" => (ClothIntegrator::ImplicitEuler, 1e-3),
                _ => (ClothIntegrator::ImplicitEuler, 5e-3),
            };
            let mut cloth = trampoline(integrator);
            let mut iterations = 0;
            let clock = std::time::Instant::now();
            for _ in 0..steps {
                iterations += black_box(&mut cloth).step(&loads, dt).iterations;
            }
            eprintln!(
                "{case}: {:.1} µs/step (wall clock, steps only)",
                clock.elapsed().as_secs_f64() * 1e6 / steps.max(1) as f64
            );
            println!(
                "{case} dt={dt:.6e} steps={steps} cg_iterations={iterations} y_min={:.9} bits={:016x}",
                cloth
                    .positions
                    .iter()
                    .map(|x| x.y)
                    .fold(f64::INFINITY, f64::min),
                cloth_bits(&cloth),
            );
        }
        "lesson16" => {
            // Lesson 16 with DT and FRICTION from the environment: every 0.1 s the cube's
            // offset from the centre, its tilt, the energy and the ledger's contacts row.
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("lessons")
                .join("16-trampoline.toml");
            let mut scene = tumble::scene::load(&path).expect("lesson 16").scene;
            if let Some(dt) = std::env::var("DT").ok().and_then(|s| s.parse().ok()) {
                scene.dt = dt;
            }
            if let (Some(mu), Some(model)) = (
                std::env::var("FRICTION")
                    .ok()
                    .and_then(|s| s.parse::<f64>().ok()),
                scene.contact.as_mut(),
            ) {
                model.friction = mu;
            }
            // SEED: the cube moved this far off centre along x and z, m; TOL: the sheet's CG
            // tolerance.
            if let Some(seed) = std::env::var("SEED")
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
            {
                scene.bodies[0].initial.position += Vector3::new(seed, 0.0, seed);
            }
            if let Some(tol) = std::env::var("TOL")
                .ok()
                .and_then(|s| s.parse::<f64>().ok())
            {
                let specs = std::mem::take(&mut scene.cloths);
                let cloths = specs
                    .iter()
                    .map(|s| {
                        let mut c = Cloth::new(s).expect("valid");
                        c.solver.tolerance = tol;
                        c
                    })
                    .collect();
                let dt = scene.dt;
                let w = scene.world().with_cloths(cloths);
                return lesson16(w, dt, steps);
            }
            let dt = scene.dt;
            let w = scene.world();
            lesson16(w, dt, steps);
        }
        _ => eprintln!("unknown case {case}"),
    }
}

/// The `lesson16` case's loop.
fn lesson16(mut w: tumble::physics::World, dt: f64, steps: usize) {
    {
        {
            let every = std::env::var("EVERY")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or((0.1 / dt).round() as usize);
            // How far the sheet is from its mirror image under x → −x (particle (i, j) against
            // (nx − 1 − i, j)), m.
            let mirror = |c: &Cloth| {
                let nx = c.count[0];
                c.positions
                    .iter()
                    .enumerate()
                    .map(|(k, x)| {
                        let m = c.positions[k - k % nx + (nx - 1 - k % nx)];
                        (x - Vector3::new(-m.x, m.y, m.z)).norm()
                    })
                    .fold(0.0, f64::max)
            };
            let (mut touched, mut low, mut rise) = (false, f64::INFINITY, 0.0f64);
            for k in 0..steps {
                black_box(&mut w).step();
                if w.divergence().is_some() {
                    println!("diverged at step {k}");
                    break;
                }
                let e = w.total_energy().total;
                touched |= w.cloth_body_contacts(0) > 0;
                if touched {
                    low = low.min(e);
                    rise = rise.max(e - low);
                }
                if (k + 1) % every == 0 {
                    let s = w.states()[0];
                    let up = s.orientation.matrix() * Vector3::y();
                    let b = w.energy_balance();
                    println!(
                        "t={:.3} xz=({:+.3e},{:+.3e}) y={:.6} tilt={:.3e}deg |v|={:.2e} E={:.6} rise={:.3e} contacts={:+.6} drift={:+.6} mirror={:.2e} n={} cg={}",
                        w.time(),
                        s.position.x,
                        s.position.z,
                        s.position.y,
                        up.angle(&Vector3::y()).to_degrees(),
                        s.linear_momentum.norm(),
                        e,
                        rise,
                        b.contacts.unwrap_or(0.0),
                        b.drift,
                        mirror(&w.cloths()[0]),
                        w.cloth_body_contacts(0),
                        w.cloths()[0].solve_counts().iterations,
                    );
                }
            }
        }
    }
}
