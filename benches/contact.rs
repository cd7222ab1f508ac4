//! The contact scaling set (issue 17), per response: what one `World::step()` costs, `rk4`,
//! dt = 1e-3, μ = 0.5, e = 0 (scenes in `tumble::contact_scenes`):
//!
//! - `stack-N`: N = 1, 3, 10, 20, 40 cubes of 0.2 m, 1 kg on each other on the ground
//!   (`soft-step` on 20 and 40 at the frequency that holds 25 and 50 cubes, 141 and 398 Hz:
//!   at 60 Hz they buckle, see `soft_step`'s "The height it holds");
//! - `pyramid-R` / `pyramid-R-gap`: R = 5, 10, 20 cubes on the bottom row, touching or 1 cm
//!   apart;
//! - `dominoes`: 8 dominoes 2 × 20 × 10 cm, 50 g, 12 cm apart, the first tipped 10°; restarted
//!   every 1.3 s, so the figure is the mean over the fall.
//!
//! Anchors (issue 17, `references.md`, Rapier 0.36 f64 / f32 / MuJoCo 4.0 on this machine):
//! stack 10: 18.7 / 10.8 / 22.9 µs; stack 20: 31.7 / 18.4 / 44.7 µs; stack 40: 55 / 34 / 123 µs;
//! pyramid 10: 0.14 / 0.08 / 0.38 ms; pyramid 20: 0.59 / 0.33 / 2.0–2.6 ms.
//!
//! Issue 35's scenes, each stepped over a whole run (restarted at its end, so the figure is
//! the mean over the run):
//!
//! - `wall` / `wall-ball`: 30 bricks (0.4 × 0.2 × 0.2 m, 2 kg) in running bond, dt = 5 ms, at
//!   rest / hit by a 50 kg ball at 6 m/s, over 2 s. Not quite at rest: the last brick of the
//!   top course (shifted half a brick) has its barycenter right above the edge of the brick
//!   below, so it topples whatever the solver (soft-step and Rapier within 1 s, `impulse`
//!   after 3–4 s, when its cost jumps);
//! - `knife-wall` / `knife-wall-ball`: the same bricks turned 90° about y, each upper brick on
//!   two bare edges, at rest / hit, over 1 s;
//! - `cradle`: a touching Newton's cradle of five balls on rods, e = 1, μ = 0, over 3 s;
//! - `dominoes16`: 16 dominoes over their whole fall, 2.5 s.
//!
//! The same scenes run in Rapier with `benches/rapier` (`cargo run --release -- SCENE STEPS
//! f32|f64`). Measured in one run (CPU µs per step over the whole run, `contact_steps` beside
//! `benches/rapier`, this loaded 2-core machine; soft-step with its kept rows):
//!
//! | scene (steps) | impulse | soft-step | Rapier f32 | Rapier f64 |
//! |---|---|---|---|---|
//! | stack-10 (3000) | 12.8 | 22.4 | 14.2 | 23.8 |
//! | pyramid-10 (1000) | 119 | 290 | 114 | 199 |
//! | dominoes (1300) | 312 | 22.1 | 13.3 | 21.4 |
//! | dominoes16 (2500) | 1,300 | 46.5 | 25.9 | 38.7 |
//! | wall (400) | 535 | 162 | 61.1 | 105 |
//! | wall-ball (400) | 42,626 | 156 | 52.7 | 84.7 |
//! | knife-wall (200) | 154,289 | 160 | 59.1 | 96.7 |
//! | knife-wall-ball (200) | 44,652 | 201 | 55.1 | 83.8 |
//! | cradle (3000) | 4.1 | 5.6 | 7.0 | 8.5 |
//!
//! `contact/at-rest`: a stack of 10 in its first second and after standing 99 s (the cost of a
//! scene at rest stays flat).
//!
//! Each world is stepped in place and put back at its start every `restart` steps. Run one
//! filter with short times, e.g.
//! `cargo bench --bench contact -- impulse/stack --warm-up-time 1 --measurement-time 3`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use tumble::contact_scenes::{
    cradle, domino_run, dominoes, knife_edge_wall, pyramid, stack, wall, DT, G, SIDE,
};
use tumble::physics::{Impacts, Response, SoftStep, World};

/// A benchmarked scene: its name, its world, and how many steps between restarts.
struct Case {
    name: String,
    world: World,
    restart: u64,
}

fn cases(response: Response) -> Vec<Case> {
    let mut cases = Vec::new();
    for n in [1, 3, 10, 20, 40] {
        cases.push(Case {
            name: format!("stack-{n}"),
            world: stack(n, standing(n, response)),
            restart: 5_000,
        });
    }
    for rows in [5, 10, 20] {
        for (suffix, gap) in [("", 0.0), ("-gap", 0.01)] {
            cases.push(Case {
                name: format!("pyramid-{rows}{suffix}"),
                world: pyramid(rows, gap, response),
                restart: 5_000,
            });
        }
    }
    cases.push(Case {
        name: "dominoes".into(),
        world: dominoes(response),
        restart: 1_300,
    });
    cases.extend(issue_35(response));
    cases
}

/// Issue 35's scenes (module doc), each restarted at the end of its run.
fn issue_35(response: Response) -> Vec<Case> {
    let case = |name: &str, world: World, seconds: f64| Case {
        name: name.into(),
        restart: (seconds / world.dt()).round() as u64,
        world,
    };
    let e = 0.0;
    vec![
        case("wall", wall(false, e, Impacts::Propagate, response), 2.0),
        case(
            "wall-ball",
            wall(true, e, Impacts::Propagate, response),
            2.0,
        ),
        case(
            "knife-wall",
            knife_edge_wall(false, e, Impacts::Propagate, response),
            1.0,
        ),
        case(
            "knife-wall-ball",
            knife_edge_wall(true, e, Impacts::Propagate, response),
            1.0,
        ),
        case("cradle", cradle(response), 3.0),
        case("dominoes16", domino_run(16, 10.0, response), 2.5),
    ]
}

/// `response`, but for `soft-step` on a stack taller than its contacts hold (the module
/// doc's buckling count, 14 cubes at the default 60 Hz) the frequency that holds 1.25 times
/// the stack: a buckling stack falls within the bench's 5 s and would time a heap.
fn standing(count: usize, response: Response) -> Response {
    match response {
        Response::SoftStep(soft) if soft.buckling_count(SIDE, G, DT) < 1.25 * count as f64 => {
            let holding = (1.25 * count as f64).ceil() as usize;
            Response::SoftStep(SoftStep {
                hertz: SoftStep::hertz_to_hold(holding, SIDE, G),
                ..soft
            })
        }
        other => other,
    }
}

fn contact(c: &mut Criterion) {
    let responses = ["impulse", "soft-step"]
        .into_iter()
        .filter_map(Response::from_name);
    for response in responses {
        let mut group = c.benchmark_group(format!("contact/{}", response.name()));
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2))
            .sample_size(10);
        for Case {
            name,
            mut world,
            restart,
        } in cases(response)
        {
            let start = world.checkpoint();
            let mut steps = 0u64;
            group.bench_function(name, |b| {
                b.iter(|| {
                    steps += 1;
                    if steps.is_multiple_of(restart) {
                        world.restore(&start);
                    }
                    black_box(&mut world).step();
                    black_box(world.states());
                })
            });
        }
        group.finish();
    }
}

/// A scene at rest keeps its cost (issue 17): one step of a stack of 10 in its first second and
/// after it has stood for 99 s (`impulse`), each world stepped in place for the measurement
/// (put back at its start every 1000 steps). The two figures should match; the test
/// `contact_scaling::a_stack_of_ten_at_rest_keeps_its_solver_path_for_100_seconds` checks the
/// solver's path itself.
fn at_rest(c: &mut Criterion) {
    let mut group = c.benchmark_group("contact/at-rest");
    group
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(10);
    for (name, seconds) in [("stack-10-first-second", 0u64), ("stack-10-after-99-s", 99)] {
        let mut world = stack(10, Response::Impulse);
        for _ in 0..seconds * 1000 {
            world.step();
        }
        let start = world.checkpoint();
        let mut steps = 0u64;
        group.bench_function(name, |b| {
            b.iter(|| {
                steps += 1;
                if steps.is_multiple_of(1000) {
                    world.restore(&start);
                }
                black_box(&mut world).step();
                black_box(world.states());
            })
        });
    }
    group.finish();
}

criterion_group!(benches, contact, at_rest);
criterion_main!(benches);
