//! Steps one of the contact benches' scenes (`tumble::contact_scenes`) a given number of times
//! and prints the solver's path counters, for profiles (`perf record`) or instruction counts
//! (`valgrind --tool=callgrind`), stable where wall-clock times are not:
//!
//! ```text
//! cargo build --release --example contact_steps
//! target/release/examples/contact_steps SCENE STEPS [RESPONSE]
//! ```
//!
//! SCENE: `stack-N`, `pyramid-R`, `pyramid-R-gap`, `dominoes` (or `dominoes-D`, the first
//! tipped D°), `dominoes16` (16 of them, or `dominoes16-D`), `bonded-wall` or `edge-wall`
//! (walls at rest: a running bond closed with half bricks; turned bricks each on 1 mm of two
//! bricks; `-ball`: hit by the ball), `wall` (30 bricks in running bond, dt 5 ms: its shifted
//! courses' end bricks balance on an edge and topple) or `wall-ball` (hit by a 50 kg ball at
//! 6 m/s), `knife-wall` or `knife-wall-ball` (the bricks turned 90°, each upper one on two bare
//! edges), their restitution `WALL_E` (0) and impact law `WALL_IMPACTS` (propagate), `cradle`
//! (a touching Newton's cradle, e = 1); RESPONSE: `impulse` (default) or `soft-step`, whose
//! parameters `SOFT_HERTZ`, `SOFT_ZETA` and `SOFT_SUBSTEPS` set (its defaults otherwise).
//! Every `CONTACT_STEPS_EVERY` steps (1000) a line gives the largest sideways (x–z) distance
//! of a body from its start (a stack's lean), the solver's path counters and µs/step; the
//! last lines the mean CPU time per step (the thread's run time, Linux, beside
//! benches/rapier's) and the work per step (median, max, unconverged steps);
//! `CONTACT_STEPS_STATES` prints the final states;
//! `CONTACT_STEPS_WORK=FILE` writes each step's work, rows, unconverged residual (0:
//! converged) and work budget to FILE, one step a line, then the solver's path counters so
//! far (summed over steps: interior solves and their steps, friction sweeps and subspace
//! steps, stage-1 direct answers and declines, warm trials answered, normal sweeps and
//! subspace steps, friction warm trials and direct answers).

use std::time::Instant;
use tumble::contact_scenes::{
    bonded_wall, cradle, domino_run, dominoes, dominoes_tipped, edge_wall, knife_edge_wall,
    pyramid, stack, wall,
};
use tumble::physics::{Impacts, Response};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: contact_steps SCENE STEPS [RESPONSE]";
    let scene = args.get(1).expect(usage);
    let steps: u64 = args.get(2).and_then(|s| s.parse().ok()).expect(usage);
    let mut response = Response::from_name(args.get(3).map_or("impulse", String::as_str))
        .expect("a response name");
    // SOFT_HERTZ, SOFT_ZETA, SOFT_SUBSTEPS: soft-step's parameters (defaults otherwise).
    if let Response::SoftStep(soft) = &mut response {
        let var = |name: &str| std::env::var(name).ok().and_then(|s| s.parse::<f64>().ok());
        soft.hertz = var("SOFT_HERTZ").unwrap_or(soft.hertz);
        soft.damping_ratio = var("SOFT_ZETA").unwrap_or(soft.damping_ratio);
        soft.substeps = var("SOFT_SUBSTEPS").map_or(soft.substeps, |n| n as u32);
    }
    let wall_e = || std::env::var("WALL_E").ok().and_then(|s| s.parse().ok());
    let wall_impacts = || {
        let impacts = std::env::var("WALL_IMPACTS").ok();
        impacts.as_deref().map_or(Impacts::Propagate, |name| {
            Impacts::from_name(name).expect("propagate or simultaneous")
        })
    };
    let mut world = if let Some(rest) = scene.strip_prefix("bonded-wall") {
        bonded_wall(
            rest == "-ball",
            wall_e().unwrap_or(0.0),
            wall_impacts(),
            response,
        )
    } else if let Some(rest) = scene.strip_prefix("edge-wall") {
        edge_wall(
            rest == "-ball",
            wall_e().unwrap_or(0.0),
            wall_impacts(),
            response,
        )
    } else if let Some(n) = scene.strip_prefix("stack-") {
        stack(n.parse().expect(usage), response)
    } else if let Some(rest) = scene.strip_prefix("pyramid-") {
        let (rows, gap) = match rest.strip_suffix("-gap") {
            Some(rows) => (rows, 0.01),
            None => (rest, 0.0),
        };
        pyramid(rows.parse().expect(usage), gap, response)
    } else if let Some(kind) = ["wall", "knife-wall"].into_iter().find(|w| {
        scene
            .strip_prefix(w)
            .is_some_and(|r| r.is_empty() || r == "-ball")
    }) {
        let e = std::env::var("WALL_E").ok().and_then(|s| s.parse().ok());
        let impacts = std::env::var("WALL_IMPACTS").ok();
        let impacts = impacts.as_deref().map_or(Impacts::Propagate, |name| {
            Impacts::from_name(name).expect("propagate or simultaneous")
        });
        let build = if kind == "wall" {
            wall
        } else {
            knife_edge_wall
        };
        build(
            scene.ends_with("-ball"),
            e.unwrap_or(0.0),
            impacts,
            response,
        )
    } else if scene == "cradle" {
        cradle(response)
    } else if scene == "dominoes16" {
        domino_run(16, 10.0, response)
    } else if let Some(degrees) = scene.strip_prefix("dominoes16-") {
        domino_run(16, degrees.parse().expect(usage), response)
    } else if scene == "dominoes" {
        dominoes(response)
    } else if let Some(degrees) = scene.strip_prefix("dominoes-") {
        dominoes_tipped(degrees.parse().expect(usage), response)
    } else {
        panic!("{usage}")
    };
    let every: u64 = std::env::var("CONTACT_STEPS_EVERY")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    let cpu_start = cpu_seconds();
    let start = Instant::now();
    // Per step: the solver's work (row updates, deterministic) and the wall-clock time.
    let mut works = Vec::new();
    let mut times = Vec::new();
    // Formatted only when asked: the formatting would cost more than a resting cube's step.
    let work_file = std::env::var_os("CONTACT_STEPS_WORK");
    let mut per_step = String::new();
    let mut last = world.contact_counters();
    let mut last_time = start;
    for step in 1..=steps {
        let t0 = Instant::now();
        world.step();
        times.push(t0.elapsed().as_secs_f64() * 1e6);
        let report = world.contact_report();
        let c = world.contact_counters();
        works.push(report.work);
        if work_file.is_some() {
            per_step.push_str(&format!(
                "{step} {} {} {:e} {} {} {} {} {} {} {} {} {} {} {} {}\n",
                report.work,
                report.rows,
                report.unconverged.unwrap_or(0.0),
                report.budget,
                c.interior,
                c.interior_steps,
                c.friction_sweeps,
                c.friction_subspace,
                c.direct,
                c.declined,
                c.warm,
                c.normal_sweeps,
                c.normal_subspace,
                c.friction_warm,
                c.friction_direct
            ));
        }
        if step % every == 0 || step == steps {
            let now = world.contact_counters();
            let t = Instant::now();
            let sideways = world
                .states()
                .iter()
                .zip(world.initial_states())
                .map(|(s, s0)| (s.position - s0.position).xz().norm())
                .fold(0.0, f64::max);
            println!(
                "t {:6.3} s  sideways {:9.3e} m  direct {:5} declined {:5} warm {:5} normal sweeps {:7} friction warm {:5} direct {:5} sweeps {:7} subspace {:6}+{:5} interior {:5}/{:6}  {:9.1} µs/step",
                world.time(),
                sideways,
                now.direct - last.direct,
                now.declined - last.declined,
                now.warm - last.warm,
                now.normal_sweeps - last.normal_sweeps,
                now.friction_warm - last.friction_warm,
                now.friction_direct - last.friction_direct,
                now.friction_sweeps - last.friction_sweeps,
                now.friction_subspace - last.friction_subspace,
                now.normal_subspace - last.normal_subspace,
                now.interior - last.interior,
                now.interior_steps - last.interior_steps,
                (t - last_time).as_secs_f64() * 1e6 / every as f64,
            );
            last = now;
            last_time = t;
        }
    }
    let drift = world
        .states()
        .iter()
        .zip(world.initial_states())
        .map(|(s, s0)| (s.position - s0.position).norm())
        .fold(0.0, f64::max);
    let cpu = cpu_seconds().zip(cpu_start).map(|(end, start)| end - start);
    if let Some(cpu) = cpu {
        println!(
            "{scene}: {:.2} µs/step over {steps} steps (CPU)",
            cpu * 1e6 / steps as f64
        );
    }
    println!("largest displacement {drift:.3e} m");
    // The work budget (issue 35): no step far above the scene's median.
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[v.len() / 2], v[v.len() - 1])
    };
    // The worst step after the first (issue 35's aim excludes step 1) and where it is.
    let (worst_step, worst_after_first) = works
        .iter()
        .enumerate()
        .skip(1)
        .map(|(i, &w)| (i + 1, w as f64))
        .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    let (work_median, work_max) = median(&mut works.iter().map(|&w| w as f64).collect());
    println!(
        "work per step after step 1 (issue 35: ≤ 20× median): max {worst_after_first} (×{:.1} median) at step {worst_step}; first step {}",
        worst_after_first / work_median.max(1.0),
        works.first().copied().unwrap_or_default()
    );
    let (time_median, time_max) = median(&mut times);
    println!(
        "work per step (row updates): median {work_median} max {work_max} (×{:.1}); time per step median {time_median:.1} µs max {time_max:.1} µs (×{:.1}); unconverged steps {}",
        work_max / work_median.max(1.0),
        time_max / time_median.max(1e-9),
        world.contact_counters().unconverged
    );
    if let Some(path) = work_file {
        std::fs::write(path, per_step).expect("CONTACT_STEPS_WORK: a writable file");
    }
    if std::env::var_os("CONTACT_STEPS_STATES").is_some() {
        for s in world.states() {
            println!(
                "{:?} {:?} {:?} {:?}",
                s.position, s.orientation, s.linear_momentum, s.angular_momentum
            );
        }
    }
}

/// The thread's CPU run time so far, s (`/proc/thread-self/schedstat`, Linux), None elsewhere.
fn cpu_seconds() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}
