//! What one `World::step()` costs with joints (issue 19), in ns/step, `rk4`, dt = 1e-3,
//! gravity, `joint_correction = projection` unless stated:
//!
//! - `pendulum`: one 0.1 m box on a distance joint to the world (1 row);
//! - `chain-10`: 10 links of 0.5 m (0.5 × 0.05 × 0.05 m, 0.1 kg), ball-jointed end to end and
//!   to the world, released horizontal (30 rows: a skyline Cholesky of J W Jᵀ, 6 wide, in each
//!   of rk4's four evaluations, then the projection's); issue 19's aim: ≤ 10 µs per step;
//! - `chain-10-hinge`: the same links on hinges about z (50 rows: 5 per hinge), as
//!   benches/mujoco/chain10.py's hinge chain (MuJoCo 11.5 µs/step under RK4); solved
//!   through its joint coordinates (`joints::reduced`: one coordinate per hinge, H = Nᵀ M N
//!   10 × 10); callgrind 114.5k instructions per step against MuJoCo 4.0.1's 115.1k;
//! - `chain-10-baumgarte`: the same with Baumgarte's correction (no projection);
//! - `chain-10-landing`: 10 links of 0.3 m (0.3 × 0.05 × 0.05 m, 0.1 kg) ball-jointed end to
//!   end (free), tilted 20°, the low end 0.3 m above the ground, `impulse` contacts (e = 0,
//!   μ = 0.5): it lands end first and comes to rest; the contacts and joints are solved
//!   together after the response (`joints::contact`). Averaged over the whole 3 s (about
//!   0.3 s of fall, then contact).
//!
//! The first three have no contact response: the links do not collide; they are put back at
//! their start every 2000 steps (2 s, before the chain has folded onto itself), the landing
//! every 3000.

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use std::hint::black_box;
use std::time::Duration;
use tumble::joint_scenes::{chain, landing_chain};
use tumble::physics::joints::{Correction, Joint, JointKind, Links};
use tumble::physics::{Body, Effect, Effects, Integrator, NamedBody, State, World};

fn gravity() -> Effects {
    Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))])
}

fn pendulum() -> World {
    let x0 = Vector3::new(1.0, 0.0, 0.0);
    let bob = NamedBody {
        name: "bob".into(),
        body: Body::solid_box(Vector3::repeat(0.1), 1.0).expect("a box"),
        initial: State {
            position: x0,
            ..State::at_rest()
        },
    };
    let states = vec![bob.initial];
    let rod = Joint::distance("rod".into(), 0, None, [x0, Vector3::zeros()], None, &states);
    World::with_bodies(
        vec![bob],
        gravity(),
        Vec::new(),
        None,
        Integrator::Rk4,
        1e-3,
    )
    .with_links(Links {
        joints: vec![rod],
        ..Links::default()
    })
}

fn joints(c: &mut Criterion) {
    let mut group = c.benchmark_group("joints");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(2));
    let cases = [
        ("pendulum", pendulum()),
        (
            "chain-10",
            chain(10, JointKind::Ball, Correction::Projection),
        ),
        (
            "chain-10-hinge",
            chain(10, JointKind::Hinge, Correction::Projection),
        ),
        (
            "chain-10-baumgarte",
            chain(10, JointKind::Ball, Correction::Baumgarte),
        ),
        (
            "chain-10-landing",
            landing_chain(10, 0.3, 20.0_f64.to_radians(), 0.3),
        ),
    ];
    for (name, mut world) in cases {
        let period = if name == "chain-10-landing" {
            3000
        } else {
            2000
        };
        let start = world.checkpoint();
        let mut steps = 0u64;
        group.bench_function(name, |b| {
            b.iter(|| {
                steps += 1;
                if steps.is_multiple_of(period) {
                    world.restore(&start);
                }
                world.step();
                black_box(world.state());
            })
        });
    }
    group.finish();
}

criterion_group!(benches, joints);
criterion_main!(benches);
