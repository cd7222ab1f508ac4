//! Rapier beside `tumble`'s contact scaling set (issue 17), for ratios measured in one run.
//! Not part of tumble's build or CI.
//!
//! ```text
//! cd benches/rapier && cargo run --release -- SCENE STEPS   # SCENE: stack-N, pyramid-R[-gap], dominoes
//! ../../target/release/examples/contact_steps SCENE STEPS   # tumble on the same scene, same run
//! ```
//!
//! The scenes are `tumble::contact_scenes`': 0.2 m cubes of 1 kg (dominoes 2 × 20 × 10 cm,
//! 50 g, 12 cm apart, the first tipped 10°), μ = 0.5, e = 0, dt = 1e-3, gravity −9.81 along y,
//! the ground a half-space at y = 0; sleeping off. Prints CPU µs per step and the largest
//! displacement of a body from its start (the sink of a stack's top).

use rapier3d_f64::prelude::*;

fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

struct Scene {
    bodies: RigidBodySet,
    colliders: ColliderSet,
    handles: Vec<(RigidBodyHandle, Vector)>,
}

impl Scene {
    fn new() -> Scene {
        let mut colliders = ColliderSet::new();
        colliders.insert(
            ColliderBuilder::halfspace(nalgebra::Unit::new_unchecked(Vector::Y))
                .friction(0.5)
                .restitution(0.0)
                .build(),
        );
        Scene {
            bodies: RigidBodySet::new(),
            colliders,
            handles: Vec::new(),
        }
    }

    fn add(&mut self, half: [f64; 3], mass: f64, at: Vector, tilt_z: f64) {
        let rb = RigidBodyBuilder::dynamic()
            .translation(at)
            .rotation(Vector::new(0.0, 0.0, tilt_z))
            .can_sleep(false)
            .build();
        let h = self.bodies.insert(rb);
        let c = ColliderBuilder::cuboid(half[0], half[1], half[2])
            .mass(mass)
            .friction(0.5)
            .restitution(0.0)
            .build();
        self.colliders.insert_with_parent(c, h, &mut self.bodies);
        self.handles.push((h, at));
    }
}

fn scene(name: &str) -> Scene {
    let mut s = Scene::new();
    let side = 0.2;
    if let Some(n) = name.strip_prefix("stack-") {
        let n: usize = n.parse().expect("stack-N");
        for i in 0..n {
            s.add(
                [0.1; 3],
                1.0,
                Vector::new(0.0, side / 2.0 + side * i as f64, 0.0),
                0.0,
            );
        }
    } else if let Some(rest) = name.strip_prefix("pyramid-") {
        let (rows, gap) = match rest.strip_suffix("-gap") {
            Some(r) => (r, 0.01),
            None => (rest, 0.0),
        };
        let rows: usize = rows.parse().expect("pyramid-R");
        let pitch = side + gap;
        for row in 0..rows {
            let count = rows - row;
            for i in 0..count {
                let x = (i as f64 - (count as f64 - 1.0) / 2.0) * pitch;
                let y = side / 2.0 + side * row as f64;
                s.add([0.1; 3], 1.0, Vector::new(x, y, 0.0), 0.0);
            }
        }
    } else if name == "dominoes" {
        let (t, h, w) = (0.02, 0.2, 0.1);
        let tilt = 10f64.to_radians();
        for i in 0..8 {
            let x = i as f64 * 0.12;
            if i == 0 {
                let (sn, c) = tilt.sin_cos();
                let offset =
                    Vector::new(-t / 2.0 * c + h / 2.0 * sn, t / 2.0 * sn + h / 2.0 * c, 0.0);
                s.add(
                    [t / 2.0, h / 2.0, w / 2.0],
                    0.05,
                    Vector::new(x + t / 2.0, 0.0, 0.0) + offset,
                    -tilt,
                );
            } else {
                s.add(
                    [t / 2.0, h / 2.0, w / 2.0],
                    0.05,
                    Vector::new(x, h / 2.0, 0.0),
                    0.0,
                );
            }
        }
    } else {
        panic!("unknown scene {name}");
    }
    s
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).expect("SCENE STEPS");
    let steps: usize = args.get(2).expect("SCENE STEPS").parse().expect("STEPS");
    let mut s = scene(name);
    let mut params = IntegrationParameters::default();
    params.dt = 1e-3;
    let gravity = Vector::new(0.0, -9.81, 0.0);
    let mut pipeline = PhysicsPipeline::new();
    let mut islands = IslandManager::new();
    let mut broad = BroadPhaseBvh::new();
    let mut narrow = NarrowPhase::new();
    let mut impulse_joints = ImpulseJointSet::new();
    let mut multibody_joints = MultibodyJointSet::new();
    let mut ccd = CCDSolver::new();
    let mut soft = SoftBodySet::new();
    let start = cpu_seconds();
    let mut last = start;
    for step in 1..=steps {
        pipeline.step(
            gravity,
            &params,
            &mut islands,
            &mut broad,
            &mut narrow,
            &mut s.bodies,
            &mut s.colliders,
            &mut impulse_joints,
            &mut multibody_joints,
            &mut soft,
            &mut ccd,
            &(),
            &(),
        );
        if step % 1000 == 0 {
            let now = cpu_seconds();
            println!(
                "t {:6.1} s  {:10.1} µs/step",
                step as f64 * 1e-3,
                (now - last) * 1e6 / 1000.0
            );
            last = now;
        }
    }
    let total = cpu_seconds() - start;
    let moved = s
        .handles
        .iter()
        .map(|(h, at)| (s.bodies[*h].translation() - *at).length())
        .fold(0.0, f64::max);
    let sideways = s
        .handles
        .iter()
        .map(|(h, at)| {
            let d = s.bodies[*h].translation() - *at;
            (d.x * d.x + d.z * d.z).sqrt()
        })
        .fold(0.0, f64::max);
    println!(
        "{name}: {:.2} µs/step over {steps} steps (CPU); largest displacement {moved:.3e} m, sideways {sideways:.3e} m",
        total * 1e6 / steps as f64
    );
}
