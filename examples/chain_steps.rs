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
//! (`{:e}`), to compare runs. The last line gives the mean µs per step; with
//! `CHAIN_STEPS_COUNTERS` set, the contact solver's counters (its paths) are printed before it.

use std::time::Instant;
use tumble::joint_scenes::{chain, landing_chain};
use tumble::physics::joints::{Correction, JointKind};
use tumble::physics::Integrator;

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
        "ball" => (chain(10, JointKind::Ball, Correction::Projection), 2000),
        "hinge" => (chain(10, JointKind::Hinge, Correction::Projection), 2000),
        "landing" => (landing_chain(10, 0.3, 20.0_f64.to_radians(), 0.3), 3000),
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
    if std::env::var("CHAIN_STEPS_COUNTERS").is_ok() {
        eprintln!("{:?}", world.contact_counters());
    }
    eprintln!("{name} under {}: {per_step:.2} µs/step", integrator.name());
}
