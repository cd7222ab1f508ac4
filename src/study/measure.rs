//! One run of the study: a scene with one integrator and one time step, measured twice over.
//!
//! 1. **Accuracy run** (once, instrumented): at every sample time, the pose is compared with the
//!    reference and the conserved quantities with their initial values; contact scenes are
//!    stepped phase by phase to see the energy each collide phase adds. The divergence guard is
//!    checked at every sample.
//! 2. **Timed runs** (a short warm-up, then up to `repeats` runs of plain [`World::step`],
//!    nothing observed): ns per step is the minimum over the runs of each run's median
//!    1000-step chunk (robust to other processes taking the CPU on a shared machine). A run of many chunks is timed fewer
//!    times: `TIMED_CHUNKS` (100) chunks are enough for the median, so a 100 000-step run is timed
//!    once, a 100-step run `repeats` times.
//!
//! ```text
//! error           = max over samples (every 0.1 s and the end) and bodies of
//!                   angle(q_ref⁻¹ q) + |x − x_ref| / radius      (rad; x the barycenter)
//! angle_error     = max angle(q_ref⁻¹ q)   (rad)      position_error = max |x − x_ref|   (m)
//! omega_error     = max |ω_body − ω_body,ref|                                          (rad/s)
//!                   (the same maxima: over the samples and every body)
//! energy_drift    = max |drift| / |E₀|         momentum_drift = max | |L| − |L₀| | / |L₀|
//!                   drift = E − E₀ − W_drag − ΔE_contacts (the energy ledger's remainder)
//! orthonormality  = max ‖RᵀR − 𝟙‖
//! penetration     = deepest vertex depth a step reaches, before the response pushes out  (m)
//! impact_energy   = Σ max(0, E after collide − E before collide)                       (J)
//! rest_error      = max over bodies |v| + radius·|ω| at the end (the fastest point)     (m/s)
//! end_pose_error  = max over bodies and their vertices |(pᵢ − pᵢ,ref)·up| / radius at the end
//!                   (up = −g/|g|; each body in its own radius)
//! contact_error   = end_pose_error + orthonormality + max over bodies penetration / radius
//!                   + impact_energy / Σ (M·|g|·radius)        (contact scenes only; else NaN)
//!                   (every body counts: orthonormality, penetration and impact_energy are
//!                   the worst body's, the last the whole scene's energy gained)
//! ```
//!
//! With contact the path is not smooth: a step size that moves an impact by a step changes
//! everything after it, and the pose along the way measures luck more than accuracy. What a
//! contact scene must get right is the pose the body comes to rest in, against a converged
//! reference: which face is down, how it tilts, how high it stands — the heights of its
//! vertices (where it slid to and its heading on the ground depend on when each impact falls,
//! and are left out); a body that keeps its shape (‖RᵀR − 𝟙‖ is an error of every vertex, in
//! units of the radius); no sinking in (penetration, in radii) and no energy from nowhere
//! (energy gained at impacts, in units of the work that lifts the body by its radius). Each
//! term is dimensionless, so they add up to `contact_error`, the measure the frontier ranks
//! contact scenes by ([`Row::measure`]).

use super::reference::Reference;
use crate::physics::snapshot::vertex_penetration;
use crate::physics::{Integrator, Phase, World};
use crate::scene::Scene;
use nalgebra::Vector3;
use std::time::Instant;

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Ran to the end.
    Ok,
    /// The divergence guard tripped (the message names step, quantity, integrator and dt).
    Diverged(String),
}

/// Everything measured for one (scene, integrator, dt).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub scene: String,
    pub integrator: Integrator,
    pub dt: f64,
    /// Steps to cover the scene's duration.
    pub steps: u64,
    /// Median wall time per step over the timed repeats, ns.
    pub ns_per_step: f64,
    /// Wall time per simulated second, µs (= ns_per_step / dt / 1000).
    pub us_per_simulated_second: f64,
    pub error: f64,
    /// Max orientation error, rad.
    pub angle_error: f64,
    pub omega_error: f64,
    pub position_error: f64,
    pub energy_drift: f64,
    pub momentum_drift: f64,
    pub orthonormality: f64,
    pub penetration: f64,
    pub impact_energy: f64,
    pub rest_error: f64,
    /// Rest-pose error at the end: the largest vertex height error, in radii.
    pub end_pose_error: f64,
    /// The contact scenes' measure (see the module doc); NaN without obstacles.
    pub contact_error: f64,
    pub status: Status,
    /// No other run of the scene has both a smaller cost and a smaller error.
    pub frontier: bool,
    /// The error is inside the floor band (round-off, or the reference's own uncertainty):
    /// not resolved, so not ranked against the other runs inside it and not fitted.
    pub below_floor: bool,
}

impl Row {
    /// The run finished without diverging.
    pub fn ok(&self) -> bool {
        self.status == Status::Ok
    }

    /// The number runs are ranked by (frontier, sentence, charts): `contact_error` in a scene
    /// with contact, else `error`.
    pub fn measure(&self) -> f64 {
        if self.contact_error.is_nan() {
            self.error
        } else {
            self.contact_error
        }
    }
}

/// How long to run and how to time it.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    /// Timed repeats after the warm-up (0: time the accuracy run only).
    pub repeats: usize,
    /// Simulated seconds between samples (each swept dt should divide it).
    pub sample_interval: f64,
}

/// Steps to cover `duration` at `dt` (at least one).
pub fn steps_for(duration: f64, dt: f64) -> u64 {
    (duration / dt).round().max(1.0) as u64
}

/// A world of `scene` stepped by `integrator` at `dt`.
pub fn world_for(scene: &Scene, integrator: Integrator, dt: f64) -> World {
    scene.world_with(integrator, dt)
}

/// The sample times of a run of length `duration`: every `interval`, and the end.
pub fn sample_times(duration: f64, interval: f64) -> Vec<f64> {
    let count = (duration / interval - 1e-9).floor() as usize;
    let mut times: Vec<f64> = (1..=count).map(|k| k as f64 * interval).collect();
    times.push(duration);
    times
}

/// Measures one run.
#[allow(clippy::too_many_arguments)]
pub fn measure(
    name: &str,
    scene: &Scene,
    duration: f64,
    integrator: Integrator,
    dt: f64,
    reference: &mut Reference,
    times: &[f64],
    timing: Timing,
) -> Row {
    let steps = steps_for(duration, dt);
    let mut row = Row {
        scene: name.to_string(),
        integrator,
        dt,
        steps,
        ns_per_step: f64::NAN,
        us_per_simulated_second: f64::NAN,
        error: 0.0,
        angle_error: 0.0,
        omega_error: 0.0,
        position_error: 0.0,
        energy_drift: 0.0,
        momentum_drift: 0.0,
        orthonormality: 0.0,
        penetration: 0.0,
        impact_energy: 0.0,
        rest_error: f64::NAN,
        end_pose_error: f64::NAN,
        contact_error: f64::NAN,
        status: Status::Ok,
        frontier: false,
        below_floor: false,
    };
    let started = Instant::now();
    accuracy_run(scene, integrator, dt, steps, reference, times, &mut row);
    let accuracy_ns = started.elapsed().as_nanos() as f64 / steps as f64;
    if !row.ok() {
        // A diverged run has no meaningful cost: it stopped early.
        return row;
    }
    if timing.repeats > 0 {
        let world = || world_for(scene, integrator, dt);
        row.ns_per_step = cost_per_step(world, steps, &timing, accuracy_ns);
    } else {
        // Untimed studies (tests): the instrumented run's time, reference included.
        row.ns_per_step = accuracy_ns;
    }
    row.us_per_simulated_second = row.ns_per_step / dt / 1000.0;
    row
}

/// Steps per timed chunk: ≈ 0.2 ms, far shorter than a scheduler time slice.
const CHUNK: u64 = 1000;

/// Chunks a row's median is taken over, at least (a run shorter than this is repeated, up to
/// `Timing::repeats` times): enough that the chunks another process held the CPU during do not
/// move the median.
pub(super) const TIMED_CHUNKS: u64 = 100;

/// Steps of the warm-up before the timed runs (caches, branch predictors, clock).
const WARM_UP: u64 = 10 * CHUNK;

/// Steps a run of `steps` steps makes in all: the accuracy run, then (when timed) the warm-up
/// and the timed runs of `cost_per_step` — what a front end scales its estimate of the time
/// left by.
pub fn steps_made(steps: u64, timing: &Timing) -> u64 {
    if timing.repeats == 0 {
        return steps;
    }
    let runs = TIMED_CHUNKS
        .div_ceil(steps.div_ceil(CHUNK))
        .clamp(1, timing.repeats.max(1) as u64);
    steps + steps.min(WARM_UP) + runs * steps
}

/// Wall time per step of `steps` plain steps of fresh worlds made by `world`, ns: after a
/// warm-up of [`WARM_UP`] steps, ⌈[`TIMED_CHUNKS`] / chunks per run⌉ runs (at least one, at
/// most `timing.repeats`), each timed as the median of its `CHUNK`-step chunks; the result is
/// the minimum over the runs (the work–precision convention: the least the machine needed —
/// other processes only ever add time). `hint_ns`, the accuracy run's time per step, shortens
/// the chunks of a heavy scene to about [`MAX_CHUNK_NS`] ([`chunk_steps`]).
pub(super) fn cost_per_step(
    world: impl Fn() -> World,
    steps: u64,
    timing: &Timing,
    hint_ns: f64,
) -> f64 {
    let chunk = chunk_steps(hint_ns);
    time_chunks(world(), steps.min(WARM_UP), chunk, &mut Vec::new());
    let chunks_per_run = steps.div_ceil(CHUNK);
    let runs = TIMED_CHUNKS
        .div_ceil(chunks_per_run)
        .clamp(1, timing.repeats.max(1) as u64);
    let mut best = f64::INFINITY;
    let mut chunks = Vec::with_capacity(chunks_per_run as usize);
    for _ in 0..runs {
        chunks.clear();
        time_chunks(world(), steps, chunk, &mut chunks);
        best = best.min(median(&mut chunks));
    }
    best
}

/// The longest a timed chunk should take, ns: a cancelled study stops at the end of its chunk
/// (its check is per chunk, not per step, to keep the clock off the timed steps), so a heavy
/// scene's chunks are shortened to this (a cloth's implicit step takes 0.5 ms: 1000 of them
/// would hold a cancelled study for half a second).
pub const MAX_CHUNK_NS: f64 = 2e6;

/// Steps per timed chunk for a step that took about `hint_ns`: `CHUNK`, or fewer (at least
/// one) so that a chunk takes at most about [`MAX_CHUNK_NS`]. Steps up to 2 µs keep `CHUNK`.
pub fn chunk_steps(hint_ns: f64) -> u64 {
    if hint_ns.is_finite() && hint_ns * CHUNK as f64 > MAX_CHUNK_NS {
        ((MAX_CHUNK_NS / hint_ns) as u64).clamp(1, CHUNK)
    } else {
        CHUNK
    }
}

/// Steps `world` `steps` times, pushing the wall time per step of each chunk of `chunk` steps
/// (ns) onto `chunks`; the world's last state goes through `black_box`, so no step is
/// optimised away.
fn time_chunks(mut world: World, steps: u64, chunk: u64, chunks: &mut Vec<f64>) {
    let mut left = steps;
    while left > 0 {
        let n = left.min(chunk);
        super::cancel::check(n);
        let started = Instant::now();
        for _ in 0..n {
            world.step();
        }
        chunks.push(started.elapsed().as_nanos() as f64 / n as f64);
        left -= n;
    }
    std::hint::black_box(world.state());
}

/// The median of a non-empty list (sorts it).
pub(super) fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The instrumented run; fills the row's accuracy columns.
fn accuracy_run(
    scene: &Scene,
    integrator: Integrator,
    dt: f64,
    steps: u64,
    reference: &mut Reference,
    times: &[f64],
    row: &mut Row,
) {
    let mut world = world_for(scene, integrator, dt);
    let contact = !scene.obstacles.is_empty();
    let start = world.snapshot();
    let (e0, l0) = (start.energy.total, start.angular_momentum.norm());
    let relative = |x: f64, x0: f64| {
        if x0.abs() > 0.0 {
            (x - x0).abs() / x0.abs()
        } else {
            (x - x0).abs()
        }
    };
    let mut sample = 0;
    // The deepest penetration of any body, in its own radii.
    let mut deepest = 0.0f64;
    while world.step_count() < steps {
        super::cancel::check(1);
        if contact {
            let mut before = 0.0;
            loop {
                match world.step_phase() {
                    Phase::Integrate => {
                        before = world.total_energy().total;
                        for (index, body) in scene.bodies.iter().enumerate() {
                            let depth = vertex_penetration(&world, index);
                            let radius = body.body.radius.max(f64::MIN_POSITIVE);
                            row.penetration = row.penetration.max(depth);
                            deepest = deepest.max(depth / radius);
                        }
                    }
                    Phase::Collide => break,
                    _ => {}
                }
            }
            if !world.contacts().is_empty() {
                let after = world.total_energy().total;
                row.impact_energy += (after - before).max(0.0);
            }
        } else {
            world.step();
        }
        let step = world.step_count();
        let now = world.time();
        let last = times.len() - 1;
        if step != steps && (sample > last || now < times[sample] - 0.5 * dt) {
            continue;
        }
        while sample < last && times[sample + 1] <= now + 0.5 * dt {
            sample += 1;
        }
        let index = if step == steps {
            last
        } else {
            sample.min(last)
        };
        sample = index + 1;
        if let Some(divergence) = world.divergence() {
            row.status = Status::Diverged(divergence.to_string());
            return;
        }
        let s = world.snapshot();
        // Exact references are evaluated at the run's own time, numeric ones at the sample.
        // Every body counts: the error is the worst body's.
        let truth = reference.at(index, now);
        for ((run, reference_pose), body) in super::reference::poses(&world)
            .iter()
            .zip(&truth)
            .zip(&scene.bodies)
        {
            let (error, angle, distance) =
                super::reference::pose_error(run, reference_pose, body.body.radius);
            row.error = row.error.max(error);
            row.angle_error = row.angle_error.max(angle);
            row.position_error = row.position_error.max(distance);
            row.omega_error = row
                .omega_error
                .max((run.omega_body - reference_pose.omega_body).norm());
        }
        // The energy ledger's drift: what drag and contacts did to E is not the integrator's.
        row.energy_drift = row
            .energy_drift
            .max(relative(e0 + s.energy_balance.drift, e0));
        row.momentum_drift = row
            .momentum_drift
            .max(relative(s.angular_momentum.norm(), l0));
        for index in 0..scene.bodies.len() {
            let error = if index == 0 {
                s.orthonormality_error
            } else {
                world.snapshot_of(index).orthonormality_error
            };
            row.orthonormality = row.orthonormality.max(error);
        }
        if step == steps {
            // The fastest point of any body.
            row.rest_error = (0..scene.bodies.len())
                .map(|index| {
                    let b = world.snapshot_of(index);
                    b.velocity.norm() + scene.bodies[index].body.radius * b.angular_velocity.norm()
                })
                .fold(0.0, f64::max);
        }
        if step == steps && contact {
            let up = scene
                .effects
                .gravity()
                .and_then(|g| (-g).try_normalize(0.0))
                .unwrap_or_else(Vector3::y);
            // Every body's vertex heights, each in its own radii; the worst body's.
            for (index, (body, pose)) in scene.bodies.iter().zip(&truth).enumerate() {
                let rotation = pose.orientation.to_rotation_matrix();
                let height = world
                    .vertices_of(index)
                    .iter()
                    .zip(&body.body.points_body)
                    .map(|(p, r0)| ((p - (pose.position + rotation * r0)).dot(&up)).abs())
                    .fold(0.0, f64::max);
                row.end_pose_error = row
                    .end_pose_error
                    .max(height / body.body.radius.max(f64::MIN_POSITIVE));
            }
        }
    }
    if contact {
        // The work that lifts every body by its own radius (or, without gravity, the initial
        // energy).
        let g = scene.effects.gravity().map_or(0.0, |g| g.norm());
        let lift: f64 = scene
            .bodies
            .iter()
            .map(|b| b.body.mass * g * b.body.radius)
            .filter(|w| w.is_finite())
            .sum();
        let scale = if lift > 0.0 { lift } else { e0.abs() };
        let gained = if scale > 0.0 {
            row.impact_energy / scale
        } else {
            0.0
        };
        row.contact_error = row.end_pose_error + row.orthonormality + deepest + gained;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heavy_step_gets_chunks_of_about_two_milliseconds() {
        // A free body's 50 ns step and a 2 µs one keep 1000-step chunks; a cloth's implicit
        // 0.5 ms step gets 4 steps a chunk (2 ms), a 10 ms step one.
        assert_eq!(chunk_steps(50.0), CHUNK);
        assert_eq!(chunk_steps(2000.0), CHUNK);
        assert_eq!(chunk_steps(5e5), 4);
        assert_eq!(chunk_steps(1e7), 1);
        assert_eq!(chunk_steps(f64::NAN), CHUNK);
    }
}
