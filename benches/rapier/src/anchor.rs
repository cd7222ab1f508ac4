// The scenes and the stepping loop, written once against `rapier::prelude` and included by
// `main.rs` twice: with `rapier3d-f64` (Real = f64) and with `rapier3d` (Real = f32).

use rapier::prelude::*;

pub struct Scene {
    pub bodies: RigidBodySet,
    pub colliders: ColliderSet,
    pub joints: ImpulseJointSet,
    pub handles: Vec<(RigidBodyHandle, Vector)>,
    pub dt: Real,
}

impl Scene {
    fn new(dt: Real, ground: bool) -> Scene {
        let mut colliders = ColliderSet::new();
        if ground {
            colliders.insert(
                ColliderBuilder::halfspace(nalgebra::Unit::new_unchecked(Vector::Y))
                    .friction(0.5)
                    .restitution(0.0)
                    .build(),
            );
        }
        Scene {
            bodies: RigidBodySet::new(),
            colliders,
            joints: ImpulseJointSet::new(),
            handles: Vec::new(),
            dt,
        }
    }

    fn insert(
        &mut self,
        at: Vector,
        tilt_z: Real,
        velocity: Vector,
        collider: Collider,
    ) -> RigidBodyHandle {
        let rb = RigidBodyBuilder::dynamic()
            .translation(at)
            .rotation(Vector::new(0.0, 0.0, tilt_z))
            .linvel(velocity)
            .can_sleep(false)
            .build();
        let h = self.bodies.insert(rb);
        self.colliders
            .insert_with_parent(collider, h, &mut self.bodies);
        self.handles.push((h, at));
        h
    }

    fn add(&mut self, half: [Real; 3], mass: Real, at: Vector, tilt_z: Real) {
        let c = ColliderBuilder::cuboid(half[0], half[1], half[2])
            .mass(mass)
            .friction(0.5)
            .restitution(0.0)
            .build();
        self.insert(at, tilt_z, Vector::ZERO, c);
    }
}

/// Six courses of five bricks of half-size `half` (2 kg), centred 0.4 m apart along x, every
/// other course shifted by 0.2 m; with `ball`, a 50 kg ball (r 0.25 m) at 6 m/s along z towards
/// the wall's middle, 0.3 m from the running-bond wall's face. dt = 5 ms.
fn wall(half: [Real; 3], ball: bool) -> Scene {
    let mut s = Scene::new(5e-3, true);
    for course in 0..6 {
        let shift = if course % 2 == 1 { 0.2 } else { 0.0 };
        for i in 0..5 {
            let x = (i as Real - 2.0) * 0.4 + shift;
            let y = 0.1 + 0.2 * course as Real;
            s.add(half, 2.0, Vector::new(x, y, 0.0), 0.0);
        }
    }
    if ball {
        let r = 0.25;
        let c = ColliderBuilder::ball(r)
            .mass(50.0)
            .friction(0.5)
            .restitution(0.0)
            .build();
        s.insert(
            Vector::new(0.1, 0.6, -(0.1 + r + 0.3)),
            0.0,
            Vector::new(0.0, 0.0, 6.0),
            c,
        );
    }
    s
}

/// `count` dominoes 2 × 20 × 10 cm, 50 g, 12 cm apart along x, the first tipped `degrees`.
fn dominoes(count: usize, degrees: Real) -> Scene {
    let mut s = Scene::new(1e-3, true);
    let (t, h, w): (Real, Real, Real) = (0.02, 0.2, 0.1);
    let tilt = degrees.to_radians();
    for i in 0..count {
        let x = i as Real * 0.12;
        if i == 0 {
            let (sn, c) = tilt.sin_cos();
            let offset = Vector::new(-t / 2.0 * c + h / 2.0 * sn, t / 2.0 * sn + h / 2.0 * c, 0.0);
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
    s
}

/// Five touching balls (1 kg, r 5 cm) on 1 m rods (rope joints to pivots at y = 1 m, 10 cm
/// apart), the first pulled aside to 30°; e = 1, μ = 0, no ground.
fn cradle() -> Scene {
    let mut s = Scene::new(1e-3, false);
    let (r, rod): (Real, Real) = (0.05, 1.0);
    let theta = (30.0 as Real).to_radians();
    let pivots = s.bodies.insert(RigidBodyBuilder::fixed().build());
    for i in 0..5 {
        let pivot = Vector::new(2.0 * r * i as Real, rod, 0.0);
        let hang = if i == 0 {
            Vector::new(-theta.sin(), -theta.cos(), 0.0)
        } else {
            Vector::new(0.0, -1.0, 0.0)
        };
        let c = ColliderBuilder::ball(r)
            .mass(1.0)
            .friction(0.0)
            .restitution(1.0)
            .build();
        let ball = s.insert(pivot + hang * rod, 0.0, Vector::ZERO, c);
        let joint = RopeJointBuilder::new(rod)
            .local_anchor1(pivot)
            .local_anchor2(Vector::ZERO);
        s.joints.insert(pivots, ball, joint, true);
    }
    s
}

pub fn scene(name: &str) -> Scene {
    let side: Real = 0.2;
    if let Some(n) = name.strip_prefix("stack-") {
        let n: usize = n.parse().expect("stack-N");
        let mut s = Scene::new(1e-3, true);
        for i in 0..n {
            s.add(
                [0.1; 3],
                1.0,
                Vector::new(0.0, side / 2.0 + side * i as Real, 0.0),
                0.0,
            );
        }
        s
    } else if let Some(rest) = name.strip_prefix("pyramid-") {
        let (rows, gap) = match rest.strip_suffix("-gap") {
            Some(r) => (r, 0.01),
            None => (rest, 0.0),
        };
        let rows: usize = rows.parse().expect("pyramid-R");
        let pitch = side + gap;
        let mut s = Scene::new(1e-3, true);
        for row in 0..rows {
            let count = rows - row;
            for i in 0..count {
                let x = (i as Real - (count as Real - 1.0) / 2.0) * pitch;
                let y = side / 2.0 + side * row as Real;
                s.add([0.1; 3], 1.0, Vector::new(x, y, 0.0), 0.0);
            }
        }
        s
    } else if name == "dominoes" {
        dominoes(8, 10.0)
    } else if let Some(rest) = name.strip_prefix("dominoes16") {
        let degrees = rest
            .strip_prefix('-')
            .map_or(10.0, |d| d.parse().expect("dominoes16-D"));
        dominoes(16, degrees)
    } else if let Some(degrees) = name.strip_prefix("dominoes-") {
        dominoes(8, degrees.parse().expect("dominoes-D"))
    } else if let Some(rest) = name.strip_prefix("wall") {
        wall([0.2, 0.1, 0.1], rest == "-ball")
    } else if let Some(rest) = name.strip_prefix("knife-wall") {
        wall([0.1, 0.1, 0.2], rest == "-ball")
    } else if name == "cradle" {
        cradle()
    } else {
        panic!("unknown scene {name}");
    }
}

/// Steps `name` `steps` times; prints CPU µs per step every `every` steps and at the end, the
/// largest displacement of a body from its start, and with `velocities_at` the bodies'
/// velocities after that many steps.
pub fn run(name: &str, steps: usize, every: usize, velocities_at: Option<usize>) {
    let mut s = scene(name);
    let mut params = IntegrationParameters::default();
    params.dt = s.dt;
    let gravity = Vector::new(0.0, -9.81, 0.0);
    let mut pipeline = PhysicsPipeline::new();
    let mut islands = IslandManager::new();
    let mut broad = BroadPhaseBvh::new();
    let mut narrow = NarrowPhase::new();
    let mut multibody_joints = MultibodyJointSet::new();
    let mut ccd = CCDSolver::new();
    let mut soft = SoftBodySet::new();
    let start = super::cpu_seconds();
    let mut last = start;
    let mut paused = 0.0;
    for step in 1..=steps {
        pipeline.step(
            gravity,
            &params,
            &mut islands,
            &mut broad,
            &mut narrow,
            &mut s.bodies,
            &mut s.colliders,
            &mut s.joints,
            &mut multibody_joints,
            &mut soft,
            &mut ccd,
            &(),
            &(),
        );
        if step % every == 0 {
            let now = super::cpu_seconds();
            println!(
                "t {:7.3} s  {:10.1} µs/step",
                step as f64 * s.dt as f64,
                (now - last) * 1e6 / every as f64
            );
            last = super::cpu_seconds();
            paused += last - now;
        }
        if velocities_at == Some(step) {
            let pause = super::cpu_seconds();
            let v: Vec<String> = s
                .handles
                .iter()
                .map(|(h, _)| {
                    let v = s.bodies[*h].linvel();
                    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
                })
                .collect();
            println!("velocities at step {step}: {}", v.join(" "));
            paused += super::cpu_seconds() - pause;
        }
    }
    let total = super::cpu_seconds() - start - paused;
    let moved = s
        .handles
        .iter()
        .map(|(h, at)| (s.bodies[*h].translation() - *at).length())
        .fold(0.0, Real::max);
    let sideways = s
        .handles
        .iter()
        .map(|(h, at)| {
            let d = s.bodies[*h].translation() - *at;
            (d.x * d.x + d.z * d.z).sqrt()
        })
        .fold(0.0, Real::max);
    println!(
        "{name}: {:.2} µs/step over {steps} steps (CPU, {}); largest displacement {moved:.3e} m, sideways {sideways:.3e} m",
        total * 1e6 / steps as f64,
        std::any::type_name::<Real>(),
    );
}
