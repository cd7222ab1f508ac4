//! The contact solver alone on recorded contact sets (issue 17, item 7): a stack and a pyramid
//! at rest are stepped once to their collide phase, their contact rows are recorded (the rows
//! detection gives there, speculative ones included), and only the response is timed on them —
//! the velocity stages, restitution, the position fix and the energy guards of `impulse`, or
//! `soft-step`'s sub-steps — never detection (`CollideInput::recorded`).
//!
//! Each iteration starts from the same recorded states; the solver's warm start is the last
//! iteration's answer, as at rest in a run. Scenes from `tumble::contact_scenes` (0.2 m, 1 kg
//! cubes, μ = 0.5, e = 0, dt = 1e-3), settled for 0.5 s first. Compare with `benches/contact.rs`
//! (a whole step) to see what detection and integration add. Run one filter with short times,
//! e.g. `cargo bench --bench solver -- impulse --warm-up-time 1 --measurement-time 3`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use tumble::contact_scenes::{pyramid, stack};
use tumble::physics::collision::broad_phase::BroadPhase;
use tumble::physics::collision::{collide, contacts, impulse, CollideInput, Contact};
use tumble::physics::effects::Loads;
use tumble::physics::{Phase, Response, State, World};

/// A scene stopped at its collide phase, with the rows detection found there.
struct Recorded {
    name: String,
    world: World,
    before: Vec<State>,
    after: Vec<State>,
    loads: Vec<Loads>,
    rows: Vec<Contact>,
}

/// The speculative margin each response detects with (`impulse::respond`, `soft_step::respond`).
fn margin(response: Response, gravity: f64, dt: f64) -> f64 {
    let bounce = impulse::BOUNCE_STEPS * gravity * dt;
    match response {
        Response::SoftStep(_) => (bounce * dt).max(1e-3),
        _ => bounce * dt,
    }
}

fn record(name: &str, mut world: World, response: Response) -> Recorded {
    for _ in 0..500 {
        world.step();
    }
    let before = world.states().to_vec();
    while world.next_phase() != Phase::Collide {
        world.step_phase();
    }
    let after = world.states().to_vec();
    let loads = vec![Loads::default(); after.len()];
    let initial: Vec<_> = world.initial_states().iter().map(|s| s.position).collect();
    let gravity = world.effects().gravity();
    let input = CollideInput {
        bodies: world.bodies(),
        obstacles: world.obstacles(),
        model: world.contact_model().expect("a contact scene"),
        before: &before,
        loads: &loads,
        initial_positions: &initial,
        context: tumble::physics::collision::StepContext::new(
            world.dt(),
            gravity,
            world.contact_model(),
        ),
        joined: &[],
        joints: None,
        recorded: None,
    };
    let g = gravity.map_or(0.0, |g| g.norm());
    let mut rows = Vec::new();
    contacts::find(
        &input,
        &after,
        margin(response, g, world.dt()),
        &mut rows,
        &mut Vec::new(),
        &mut BroadPhase::default(),
    );
    Recorded {
        name: name.into(),
        world,
        before,
        after,
        loads,
        rows,
    }
}

fn solver(c: &mut Criterion) {
    for response in ["impulse", "soft-step"]
        .into_iter()
        .filter_map(Response::from_name)
    {
        let mut group = c.benchmark_group(format!("solver/{}", response.name()));
        group
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2))
            .sample_size(10);
        let scenes = [
            ("stack-10", stack(10, response)),
            ("stack-20", stack(20, response)),
            ("stack-40", stack(40, response)),
            ("pyramid-5", pyramid(5, 0.0, response)),
            ("pyramid-10", pyramid(10, 0.0, response)),
        ];
        for (name, world) in scenes {
            let r = record(name, world, response);
            let initial: Vec<_> = r
                .world
                .initial_states()
                .iter()
                .map(|s| s.position)
                .collect();
            let input = CollideInput {
                bodies: r.world.bodies(),
                obstacles: r.world.obstacles(),
                model: r.world.contact_model().expect("a contact scene"),
                before: &r.before,
                loads: &r.loads,
                initial_positions: &initial,
                context: tumble::physics::collision::StepContext::new(
                    r.world.dt(),
                    r.world.effects().gravity(),
                    r.world.contact_model(),
                ),
                joined: &[],
                joints: None,
                recorded: Some(&r.rows),
            };
            let mut states = r.after.clone();
            let mut found = Vec::new();
            let mut scratch = impulse::Scratch::default();
            let label = format!("{}-{}rows", r.name, r.rows.len());
            group.bench_function(label, |b| {
                b.iter(|| {
                    states.copy_from_slice(&r.after);
                    black_box(collide(&input, &mut states, &mut found, &mut scratch));
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, solver);
criterion_main!(benches);
