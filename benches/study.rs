//! The wall time of the default `tumble study` (the budget: under 10 s on 2 cores), and
//! the study's own ns/step per integrator on the tumbling box, printed before the measurement.
//!
//! `cargo bench --bench study`. The per-step criterion benches of the core live in
//! `benches/step.rs`; this one does not repeat them, it reports what the study measured.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use std::time::Duration;
use tumble::study::{self, scenes, Config};

fn default_study(c: &mut Criterion) {
    let cases = scenes::builtin();
    let config = Config::default();
    // What the study itself measures on the tumbling box (median of its timed 1000-step chunks).
    let tumbling = study::study_case(&cases[0], &config, &mut |_, _| {});
    eprintln!("ns/step on {} (study's own timing):", tumbling.name);
    let mut rows: Vec<_> = tumbling.rows.iter().filter(|r| r.ok()).collect();
    rows.sort_by(|a, b| {
        (a.integrator.name(), b.dt)
            .partial_cmp(&(b.integrator.name(), a.dt))
            .unwrap()
    });
    for r in rows {
        eprintln!(
            "  {:<17} dt {:>7e}  {:>6.0} ns/step  {:>9.1} µs per simulated second",
            r.integrator.name(),
            r.dt,
            r.ns_per_step,
            r.us_per_simulated_second
        );
    }
    let mut group = c.benchmark_group("study");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(1));
    group.measurement_time(Duration::from_secs(45));
    group.bench_function("default", |b| {
        b.iter(|| black_box(study::study(&cases, &config, &mut |_, _| {})))
    });
    group.finish();
}

criterion_group!(benches, default_study);
criterion_main!(benches);
