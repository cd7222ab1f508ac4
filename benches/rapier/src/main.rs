//! Rapier beside `tumble`'s contact benches (issues 17 and 35), in f64 and f32, for ratios
//! measured in one run. Not part of tumble's build or CI.
//!
//! ```text
//! cd benches/rapier && cargo run --release -- SCENE STEPS [f64|f32]
//! ../../target/release/examples/contact_steps SCENE STEPS [RESPONSE]   # tumble, same run
//! ```
//!
//! SCENE: `stack-N`, `pyramid-R[-gap]`, `dominoes[-D]`, `dominoes16[-D]`, `wall`,
//! `wall-ball`, `knife-wall`, `knife-wall-ball`, `cradle`: `tumble::contact_scenes`' scenes.
//! 0.2 m cubes of 1 kg (dominoes 2 × 20 × 10 cm, 50 g, 12 cm apart, the first tipped 10°),
//! μ = 0.5, e = 0, dt = 1e-3, gravity −9.81 along y, the ground a half-space at y = 0; walls:
//! 30 bricks 0.4 × 0.2 × 0.2 m of 2 kg in running bond (knife-edge: each turned 90° about y,
//! so each upper brick rests on two bare edges), dt = 5 ms, optionally hit by a 50 kg ball
//! (r 0.25 m) at 6 m/s; cradle: five touching 1 kg balls (r 5 cm) on 1 m rope joints, the
//! first released from 30°, e = 1, μ = 0, no ground. Sleeping off. Prints CPU µs per step
//! (every `RAPIER_EVERY` steps, 1000, and overall) and the largest displacement of a body from
//! its start (the sink of a stack's top); `RAPIER_VELOCITIES_AT=K` prints the bodies'
//! velocities after step K.
//!
//! What Rapier runs here (0.36.1, `IntegrationParameters::default()` but dt): 4 sub-steps
//! (`num_solver_iterations`), each one biased solve and one relax (`num_internal_pgs_iterations`,
//! `num_internal_stabilization_iterations`), friction in the relax only
//! (`friction_in_bias_pass = false`), one tangent pair and one twist row per manifold of up to
//! 4 points (`FrictionModel::Simplified`), pairs that barely moved recycled
//! (`contact_recycling`). Its contact rows are solved four manifolds at a time in SIMD lanes
//! (`ContactWithTwistFriction<WideF32x4>` in f32, `<WideF64x4>` in f64: parry's `SimdReal`,
//! 4 lanes whatever the crate features), the manifolds of a lane group coloured so they share
//! no body. So neither build is a scalar solver.

mod f64 {
    use rapier3d_f64 as rapier;
    include!("anchor.rs");
}

mod f32 {
    use rapier3d as rapier;
    include!("anchor.rs");
}

fn cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: rapier-anchor SCENE STEPS [f64|f32]";
    let name = args.get(1).expect(usage);
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).expect(usage);
    let var = |name: &str| {
        std::env::var(name)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
    };
    let every = var("RAPIER_EVERY").unwrap_or(1000).max(1);
    let at = var("RAPIER_VELOCITIES_AT");
    match args.get(3).map_or("f64", String::as_str) {
        "f64" => f64::run(name, steps, every, at),
        "f32" => f32::run(name, steps, every, at),
        other => panic!("{usage} (not {other})"),
    }
}
