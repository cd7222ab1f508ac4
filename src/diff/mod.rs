//! Checking a loop written elsewhere: their trajectory (THEIRS.csv) against tumble's run of the
//! same scene, step by step, and the known mistake that reproduces theirs, if one does.
//!
//! | file | idea |
//! |---|---|
//! | `theirs` | THEIRS.csv: columns (`run`'s, `R11 … R33`, the report's member names), rows, errors by line |
//! | `compare` | tumble's rows at their steps, each column on its quantity's scale, the phase that writes it |
//! | `mistakes` | the known mistakes, one function each, planted in a copy of the loop |
//!
//! [`check`] runs it all and writes the report `tumble diff` prints.

pub mod compare;
pub mod mistakes;
pub mod theirs;

use crate::physics::{Integrator, World};
use crate::scene::Scene;
use compare::{compare, loop_phase, row_differences, run_ours, written_by, Ours, Sample, Scales};
use mistakes::{Knobs, Mistake, Plant, Planted};
use std::fmt::Write as _;
use theirs::{Column, Theirs};

/// The default tolerance, relative to each quantity's largest norm over the run.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// What a check found.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub ours: Ours,
    pub comparison: compare::Comparison,
    /// The first row (index into theirs) where some column parts.
    pub first_row: Option<usize>,
    /// The known mistakes that reproduce their numbers (empty: none, or they agree).
    pub causes: Vec<Mistake>,
    /// The mistakes tried.
    pub tried: usize,
    /// The report, as `tumble diff` prints it.
    pub text: String,
}

impl Outcome {
    /// Whether every given column agrees on every row.
    pub fn agrees(&self) -> bool {
        self.first_row.is_none()
    }
}

/// What the check is run on (for the report's first lines).
pub struct Subject<'a> {
    pub scene: &'a Scene,
    /// The scene file as given.
    pub scene_name: &'a str,
    /// THEIRS.csv as given.
    pub theirs_name: &'a str,
    /// The compared body.
    pub body: usize,
}

/// Steps the scene to their last row, compares every row, looks for the known mistake when
/// they part, and writes the report. Err: tumble's own run diverged (its message).
pub fn check(subject: &Subject, theirs: &Theirs, tolerance: f64) -> Result<Outcome, String> {
    let scene = subject.scene;
    let world = scene.world();
    let ours = run_ours(world.clone(), subject.body, theirs)?;
    let comparison = compare(theirs, &ours.samples, &ours.scales, tolerance);
    let first_row = comparison.first_row();
    let mut causes = Vec::new();
    let mut tried = 0;
    let state_parts = first_row.is_some()
        && comparison
            .columns
            .iter()
            .any(|c| c.first.is_some() && matched(c.column));
    if state_parts {
        let candidates = candidates(subject, &world, theirs, &ours);
        tried = candidates.len();
        for mistake in candidates {
            if reproduces(subject, &world, theirs, &ours.scales, tolerance, &mistake) {
                causes.push(mistake);
            }
        }
    }
    let mut outcome = Outcome {
        ours,
        comparison,
        first_row,
        causes,
        tried,
        text: String::new(),
    };
    outcome.text = report(subject, &world, theirs, tolerance, &outcome, state_parts);
    Ok(outcome)
}

/// The columns a planted mistake must reproduce: the state and its velocities (t, the energy
/// and the penetration are measured, each loop its own way).
fn matched(c: Column) -> bool {
    !matches!(c, Column::T | Column::Energy | Column::Penetration)
}

/// The mistakes worth planting in this scene: every known one the variant loop can step, and
/// the time step by the factors their numbers suggest and the usual ones.
fn candidates(subject: &Subject, world: &World, theirs: &Theirs, ours: &Ours) -> Vec<Mistake> {
    let integrator = world.integrator();
    let plantable = plantable_scene(subject, world);
    let mut factors: Vec<f64> = Vec::new();
    let dt = world.dt();
    // Their t at their last row, if it says another dt.
    if let (Some(k), Some(row)) = (
        theirs.columns.iter().position(|&c| c == Column::T),
        theirs.rows.iter().rev().find(|r| r.step > 0),
    ) {
        factors.push(row.values[k] / (row.step as f64 * dt));
    }
    // Their first step against ours: explicit Euler moves x (and P, L) by c·dt·(rate).
    if let (Some(r0), Some(r1)) = (theirs.rows.first(), theirs.rows.get(1)) {
        if r0.step == 0 && r1.step == 1 {
            for (k, &c) in theirs.columns.iter().enumerate() {
                if matches!(c, Column::X(_) | Column::V(_) | Column::P(_) | Column::L(_)) {
                    let mine = ours.samples[1].value(c) - ours.samples[0].value(c);
                    let yours = r1.values[k] - r0.values[k];
                    if mine.abs() > 0.0 {
                        factors.push(yours / mine);
                    }
                }
            }
        }
    }
    factors.extend([
        2.0, 0.5, 10.0, 0.1, 4.0, 0.25, 5.0, 0.2, 100.0, 0.01, 1000.0, 0.001,
    ]);
    let mut kept: Vec<f64> = Vec::new();
    for f in factors {
        let usable = f.is_finite() && f > 0.0 && (f - 1.0).abs() > 1e-9 && f * dt > 0.0;
        if usable && !kept.iter().any(|k| (k - f).abs() <= 1e-9 * f) {
            kept.push(f);
        }
    }
    mistakes::known(integrator, plantable, &kept, dt)
}

/// Whether the variant loop can run this scene: one body, no joints, springs or cloths, and
/// one of the report's explicit integrators.
fn plantable_scene(subject: &Subject, world: &World) -> bool {
    mistakes::plantable(world.integrator())
        && world.body_count() == 1
        && subject.scene.links.is_empty()
        && subject.scene.cloths.is_empty()
}

/// Whether the mistake, planted alone, gives their numbers on every row (the matched columns,
/// to the tolerance).
fn reproduces(
    subject: &Subject,
    world: &World,
    theirs: &Theirs,
    scales: &Scales,
    tolerance: f64,
    mistake: &Mistake,
) -> bool {
    // On the quantity's scale, or on the number itself where the planted run has grown past
    // it (a mistake that blows up grows far beyond tumble's scales).
    let agrees = |values: &[f64], sample: &Sample| {
        let abs = row_differences(&theirs.columns, values, sample);
        (theirs.columns.iter().zip(abs)).all(|(&c, a)| {
            let scale = c.quantity().map_or(1.0, |q| scales.of(q));
            !matched(c) || a / scale.max(sample.value(c).abs()) <= tolerance
        })
    };
    // A planted run whose numbers overflow at step s reproduces a run of theirs that does so
    // too: every row before s agrees, and theirs is not finite at one of its next two rows.
    let blows_up_too = |step: u64| {
        (theirs.rows.iter())
            .filter(|r| r.step >= step)
            .take(2)
            .any(|r| r.values.iter().any(|v| !v.is_finite()))
    };
    let dt = world.dt();
    let plantable = plantable_scene(subject, world);
    let (knobs, dt) = match mistake.plant {
        Plant::Knobs(knobs) => (Some(knobs), dt),
        Plant::TimeStep(factor) if plantable => (Some(Knobs::default()), factor * dt),
        Plant::TimeStep(factor) => (None, factor * dt),
    };
    match knobs {
        Some(knobs) => {
            // The obstacles as the snapshot carries them (the scene's, unchanged by a run).
            let obstacles = world.snapshot().obstacles;
            let mut planted = Planted::new(
                world.body(),
                world.effects(),
                &obstacles,
                world.contact_model(),
                world.integrator(),
                dt,
                world.initial_state(),
                knobs,
            );
            let mut step = 0;
            for row in &theirs.rows {
                while step < row.step {
                    planted.step();
                    step += 1;
                    if !planted.is_finite() {
                        return blows_up_too(step);
                    }
                }
                if !agrees(&row.values, &planted.sample(step as f64 * dt)) {
                    return false;
                }
            }
            true
        }
        None => {
            // Another integrator: the scene itself at the other dt (its guard stops a run that
            // blows up before its numbers overflow, so such a run is not matched).
            let mut world = subject.scene.world_with(world.integrator(), dt);
            let mut step = 0;
            for row in &theirs.rows {
                while step < row.step {
                    world.step();
                    step += 1;
                    if world.divergence().is_some() {
                        return false;
                    }
                }
                if !agrees(&row.values, &Sample::of(&world, subject.body)) {
                    return false;
                }
            }
            true
        }
    }
}

/// A number in full (shortest round-trip) precision; very small or large ones in scientific
/// notation (`2.675688237956691e-6`), so that the digits stay readable.
fn full(v: f64) -> String {
    let a = v.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e15).contains(&a) {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

/// A difference in three digits.
fn brief(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.is_infinite() {
        "not finite".into()
    } else {
        format!("{v:.2e}")
    }
}

/// The report `tumble diff` prints.
fn report(
    subject: &Subject,
    world: &World,
    theirs: &Theirs,
    tolerance: f64,
    outcome: &Outcome,
    state_parts: bool,
) -> String {
    let mut out = String::new();
    let integrator = world.integrator();
    let names: Vec<String> = theirs.columns.iter().map(|c| c.name()).collect();
    let first = theirs.rows.first().map_or(0, |r| r.step);
    let last = theirs.rows.last().map_or(0, |r| r.step);
    let _ = writeln!(
        out,
        "tumble diff: {} against {}, body `{}`, {}, dt = {} s{}",
        subject.theirs_name,
        subject.scene_name,
        world.body_names()[subject.body],
        integrator.name(),
        crate::limits::short(world.dt()),
        world
            .contact_model()
            .filter(|_| !world.snapshot().obstacles.is_empty())
            .map(|m| format!(", response {}", m.response.name()))
            .unwrap_or_default()
    );
    let _ = writeln!(
        out,
        "{} rows (steps {first} to {last}); columns: {}; tolerance {} of each quantity's \
         largest norm over the run (1 for a rotation)",
        theirs.rows.len(),
        names.join(" "),
        brief(tolerance).replace(".00e", "e")
    );
    let _ = writeln!(out);
    let comparison = &outcome.comparison;
    let row_at = |r: usize| &theirs.rows[r];
    match outcome.first_row {
        None => {
            let _ = writeln!(
                out,
                "They agree: every given column, on every row, within the tolerance."
            );
        }
        Some(r) => {
            let parted = comparison.parted_at(r, tolerance);
            let (phase, why) = loop_phase(&parted, outcome.ours.collided[r]);
            let _ = writeln!(
                out,
                "They part at step {} (t = {} s), in the {} phase: {}.",
                row_at(r).step,
                full(outcome.ours.samples[r].t),
                phase.name(),
                why
            );
        }
    }
    let _ = writeln!(out);
    // Per quantity: its first parting row.
    if outcome.first_row.is_some() {
        write_per_quantity(&mut out, theirs, outcome, integrator);
        let _ = writeln!(out);
    }
    write_table(&mut out, theirs, comparison);
    if outcome.first_row.is_none() {
        return out;
    }
    let _ = writeln!(out);
    write_cause(
        &mut out,
        subject,
        theirs,
        tolerance,
        outcome,
        state_parts,
        integrator,
    );
    out
}

/// The per-quantity lines: where each quantity first parts, theirs, ours, the phase.
fn write_per_quantity(
    out: &mut String,
    theirs: &Theirs,
    outcome: &Outcome,
    integrator: Integrator,
) {
    let comparison = &outcome.comparison;
    let row_at = |r: usize| &theirs.rows[r];
    let _ = writeln!(out, "first parting, per quantity:");
    let per = comparison.per_quantity();
    let _ = writeln!(
        out,
        "  {:<17} {:<7} {:>6}  {:<10} {:<24} {:<24} written by",
        "quantity", "column", "step", "t", "theirs", "ours"
    );
    for (quantity, parting) in &per {
        match parting {
            None => {
                let _ = writeln!(out, "  {:<17} agrees on every row", quantity.name());
            }
            Some((r, column)) => {
                let k = theirs
                    .columns
                    .iter()
                    .position(|c| c == column)
                    .expect("a given column");
                let sample = &outcome.ours.samples[*r];
                let mut yours = row_at(*r).values[k];
                if let Column::Q(_) = column {
                    // Shown with the sign nearest ours (q and −q: one rotation).
                    let dot: f64 = (theirs.columns.iter().zip(&row_at(*r).values))
                        .filter_map(|(c, v)| match c {
                            Column::Q(i) => Some(v * sample.quaternion[*i]),
                            _ => None,
                        })
                        .sum();
                    if dot < 0.0 {
                        yours = -yours;
                    }
                }
                let (phase, formula) = written_by(*quantity, integrator, outcome.ours.collided[*r]);
                let _ = writeln!(
                    out,
                    "  {:<17} {:<7} {:>6}  {:<10} {:<24} {:<24} {} ({formula})",
                    quantity.name(),
                    column.name(),
                    row_at(*r).step,
                    full(sample.t),
                    full(yours),
                    full(sample.value(*column)),
                    phase.name()
                );
            }
        }
    }
}

/// The table of how far apart each column is over the run.
fn write_table(out: &mut String, theirs: &Theirs, comparison: &compare::Comparison) {
    let _ = writeln!(out, "how far apart, per column, over the run:");
    let _ = writeln!(
        out,
        "  {:<11} {:>20} {:>14}  first parting step",
        "column", "max |theirs − ours|", "max relative"
    );
    for c in &comparison.columns {
        let _ = writeln!(
            out,
            "  {:<11} {:>20} {:>14}  {}",
            c.column.name(),
            brief(c.max_abs),
            brief(c.max_rel),
            c.first
                .map_or("—".to_string(), |r| theirs.rows[r].step.to_string())
        );
    }
}

/// The cause: the known mistakes that reproduce theirs, or unknown.
fn write_cause(
    out: &mut String,
    subject: &Subject,
    theirs: &Theirs,
    tolerance: f64,
    outcome: &Outcome,
    state_parts: bool,
    integrator: Integrator,
) {
    if !state_parts {
        let _ = writeln!(
            out,
            "cause: not searched: only t, the energy or the penetration part, while the state \
             and its velocities agree (check how your loop measures them)"
        );
        return;
    }
    if outcome.causes.is_empty() {
        let _ = writeln!(
            out,
            "cause: unknown: none of the {} known mistakes tried reproduces your numbers to {}{}",
            outcome.tried,
            brief(tolerance).replace(".00e", "e"),
            if mistakes::plantable(integrator) {
                ""
            } else {
                " (with this integrator only the time step can be planted: the other mistakes \
                 are of the report's explicit loops, euler-seed, euler and symplectic-euler)"
            }
        );
        let _ = writeln!(
            out,
            "  step to the first parting frame phase by phase: tumble walk {} --frames {} \
             --phases",
            subject.scene_name,
            outcome.first_row.map_or(0, |r| theirs.rows[r].step)
        );
        return;
    }
    let _ = writeln!(
        out,
        "cause: {} reproduces your numbers (every row, to {}):",
        if outcome.causes.len() == 1 {
            "a known mistake"
        } else {
            "each of these known mistakes"
        },
        brief(tolerance).replace(".00e", "e")
    );
    for m in &outcome.causes {
        let _ = writeln!(out, "  {}", m.what);
        let _ = writeln!(out, "  phase:  {}", m.phase.name());
        let _ = writeln!(out, "  fix:    {}", m.fix);
        let _ = writeln!(out, "  lesson: tumble {}", m.lesson);
    }
}

#[cfg(test)]
mod tests {
    use super::mistakes::{Knobs, Planted};
    use crate::physics::Integrator;

    /// The variant loop with no mistake planted is the scene's own loop: every integrator it
    /// knows, with gravity, drag and the seed response, to round-off over 300 steps.
    #[test]
    fn the_loop_with_no_mistake_planted_is_the_worlds() {
        for (lesson, integrator) in [
            ("03-rotation-drift", Integrator::EulerSeed),
            ("04-gravity-no-torque", Integrator::EulerSeed),
            ("01-the-loop", Integrator::SymplecticEuler),
            ("01-the-loop", Integrator::Euler),
            ("09-viscosity", Integrator::Euler),
            ("05-ground-collision", Integrator::EulerSeed),
        ] {
            let lesson = crate::lessons::load(std::path::Path::new(lesson)).unwrap();
            let mut world = lesson.scene.world_with(integrator, lesson.scene.dt);
            let scene = world.clone();
            let obstacles = scene.snapshot().obstacles;
            let mut planted = Planted::new(
                scene.body(),
                scene.effects(),
                &obstacles,
                scene.contact_model(),
                integrator,
                scene.dt(),
                scene.initial_state(),
                Knobs::default(),
            );
            for step in 1..=300 {
                world.step();
                planted.step();
                let ours = super::compare::Sample::of(&world, 0);
                let theirs = planted.sample(world.time());
                let gap = (ours.position - theirs.position).norm()
                    + (ours.rotation - theirs.rotation).norm()
                    + (ours.momentum - theirs.momentum).norm()
                    + (ours.angular_momentum - theirs.angular_momentum).norm();
                assert!(
                    gap <= 1e-12,
                    "{} {}: step {step}: the planted loop is {gap:e} away",
                    lesson.path.display(),
                    integrator.name()
                );
            }
        }
    }
}
