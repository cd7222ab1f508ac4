//! The cloth case: each particle integrator on a ladder of time steps around the sheets'
//! explicit limit, measured against a converged reference — error, energy and ns/step.
//!
//! ```text
//! limit      L = 2/ω_max of the stiffest cloth (physics::cloth::stability): symplectic-euler is
//!            unstable for every dt > L; with spring damping or drag it is stable for dt below
//!            h* = 4/(γ + √(γ² + 4ω²)) ≤ L (a safe bound: between h* and L it may or may not be)
//! ladder     dt_k = top / 2^k, k = 0, 1, …, where top is the smallest 1·10ⁿ, 2·10ⁿ or 5·10ⁿ
//!            ≥ ABOVE·L, down to the first dt ≤ L/BELOW
//! explicit   every ladder dt < L, and the `past` smallest ones above it (they must diverge)
//! implicit   every ladder dt (well past the limit, and below it)
//! reference  symplectic-euler at h_r = (smallest dt)/REFERENCE_DIVISOR and at h_r/2,
//!            extrapolated (Richardson): x_ref = 2 x(h_r/2) − x(h_r), its error O(h_r²) for a
//!            first-order method on a smooth motion; when a contact can make the motion
//!            non-smooth (obstacles or bodies in the scene), x(h_r/2) alone
//! error      = max over the sample times and the particles (and bodies' barycenters) of
//!              |x − x_ref|                                                              (m)
//! drift(t)   = E − (E₀ + W_damping+drag + ΔE_contacts): E minus the ledger's booked losses (J)
//! energy_drift      = max |drift| / |E₀|            (the bodies' definition)
//! drift_j           = max |drift|                                                        (J)
//! numerical_damping = −drift at the end: energy lost that nothing declared booked        (J)
//! energy_rise       = the largest rise of E + booked losses in one step (≤ 0: never rose)  (J)
//! order      least-squares slope of ln error against ln dt over the runs below L that did
//!            not diverge
//! ```
//!
//! The sentence ([`compare`]): the target error e* is what the explicit integrator makes at
//! its largest stable dt h_e (its cheapest run); h_i is the dt at which the implicit one makes
//! e*, with ln error interpolated linearly in ln dt between its measured points; an explicit
//! run needs h_i/h_e times as many steps as an implicit one for the same error. When the
//! implicit integrator never gets down to e* within the ladder, the line through its two
//! smallest-dt points is extrapolated, and said to be. Then, past the limit: the implicit
//! integrator's largest dt that did not diverge against h_e (the explicit one cannot step
//! further), with both errors.

use super::analysis::{format_dt, format_number};
use super::measure::{cost_per_step, sample_times, Status, Timing};
use crate::physics::cloth::ClothIntegrator;
use crate::physics::snapshot::particle_positions;
use crate::physics::{ClothView, World};
use crate::scene::Scene;
use nalgebra::Vector3;

/// The ladder's largest dt is at least this many times the explicit limit.
pub const ABOVE: f64 = 8.0;
/// The ladder goes down to a dt at most the explicit limit divided by this.
pub const BELOW: f64 = 8.0;
/// The reference's step is the smallest swept dt divided by this.
pub const REFERENCE_DIVISOR: f64 = 8.0;

/// What the cloth case sweeps and how it times it.
#[derive(Debug, Clone)]
pub struct ClothConfig {
    pub integrators: Vec<ClothIntegrator>,
    pub timing: Timing,
    /// How many ladder steps past the explicit limit an explicit integrator is run at.
    pub past: usize,
    /// The ladder, when not derived from the limit (tests), s.
    pub dts: Option<Vec<f64>>,
}

impl Default for ClothConfig {
    /// Both particle integrators, the ladder around the limit, two explicit runs past it,
    /// timed as the bodies' runs (5 repeats after a warm-up).
    fn default() -> ClothConfig {
        ClothConfig {
            integrators: ClothIntegrator::ALL.to_vec(),
            timing: Timing {
                repeats: 5,
                sample_interval: 0.1,
            },
            past: 2,
            dts: None,
        }
    }
}

/// Everything measured for one (scene, particle integrator, dt).
#[derive(Debug, Clone, PartialEq)]
pub struct ClothRow {
    pub scene: String,
    pub integrator: ClothIntegrator,
    pub dt: f64,
    /// Steps to cover the scene's duration.
    pub steps: u64,
    /// dt / L (L = 2/ω_max): above 1 the explicit step is past its limit.
    pub limit_ratio: f64,
    /// Median wall time per step over the timed repeats, ns (NaN for a diverged run).
    pub ns_per_step: f64,
    /// Wall time per simulated second, µs.
    pub us_per_simulated_second: f64,
    /// Max particle distance from the reference, m.
    pub error: f64,
    /// Max |drift| / |E₀|.
    pub energy_drift: f64,
    /// Max |drift|, J.
    pub drift_j: f64,
    /// −drift at the end, J: energy lost that no booked loss accounts for.
    pub numerical_damping: f64,
    /// Energy the ledger booked as taken (spring damping, drag, contacts) by the end, J.
    pub booked_losses: f64,
    /// Largest rise of E + booked losses in one step, J.
    pub energy_rise: f64,
    pub status: Status,
    /// No other run of the cloth case has both a smaller cost and a smaller error.
    pub frontier: bool,
}

impl ClothRow {
    /// The run finished without diverging.
    pub fn ok(&self) -> bool {
        self.status == Status::Ok
    }

    /// The explicit step is past its stability limit at this dt.
    pub fn past_limit(&self) -> bool {
        self.limit_ratio > 1.0
    }
}

/// The round-off floor band of a cloth study in reference spreads: errors below
/// `FLOOR_SPREADS × reference_spread` are not told apart (drawn as a band, left out of the fit).
pub const FLOOR_SPREADS: f64 = 3.0;

/// The fitted order of one particle integrator.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClothOrder {
    pub integrator: ClothIntegrator,
    /// Least-squares slope of ln error against ln dt, if at least two runs qualify.
    pub slope: Option<f64>,
    /// How many runs the fit used.
    pub points: usize,
}

/// The explicit integrator against the implicit one for the same error (module doc).
#[derive(Debug, Clone, PartialEq)]
pub enum SameError {
    /// The implicit integrator makes the target error at `implicit_dt` (interpolated).
    Reached {
        target: f64,
        explicit_dt: f64,
        implicit_dt: f64,
        /// implicit_dt / explicit_dt: how many times more steps the explicit one takes.
        ratio: f64,
    },
    /// Even at its largest dt the implicit error is under the target: the ratio is at least
    /// implicit_dt / explicit_dt.
    AtLeast {
        target: f64,
        explicit_dt: f64,
        implicit_dt: f64,
        implicit_error: f64,
        ratio: f64,
    },
    /// The implicit integrator never gets down to the target within the ladder.
    NotReached {
        target: f64,
        explicit_dt: f64,
        /// Its smallest error, and where.
        best_error: f64,
        best_dt: f64,
        /// The dt the line through its two smallest-dt points reaches the target at (when it
        /// slopes down), and the ratio that would give.
        extrapolated: Option<(f64, f64)>,
    },
    /// Nothing to compare (an integrator was not run, or every run of one diverged).
    Missing(String),
}

/// Past the limit: the implicit integrator's largest dt that ran against the explicit one's
/// largest stable dt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PastLimit {
    pub implicit_dt: f64,
    pub implicit_error: f64,
    pub explicit_dt: f64,
    pub explicit_error: f64,
    /// implicit_dt / explicit_dt.
    pub ratio: f64,
}

/// What the sentence says.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    pub same_error: SameError,
    /// None when no implicit run past the limit finished or no explicit run did.
    pub past_limit: Option<PastLimit>,
}

/// The study of a scene's cloths.
#[derive(Debug, Clone, PartialEq)]
pub struct ClothStudy {
    /// L = 2/ω_max, s: the smallest of the scene's cloths (symplectic-euler diverges above).
    pub limit: f64,
    /// h* of the same cloth, s (= L without damping; stable below).
    pub damped_limit: f64,
    /// The cloth the limit belongs to.
    pub limiting_cloth: String,
    /// The swept dts, largest first, s.
    pub ladder: Vec<f64>,
    /// What the errors are measured against.
    pub reference: String,
    /// max |x(h_r/2) − x(h_r)| over samples and particles, m: the first-order error of the
    /// finer reference run (the extrapolated one is far smaller).
    pub reference_spread: f64,
    /// Sorted by integrator, then dt (largest first).
    pub rows: Vec<ClothRow>,
    pub orders: Vec<ClothOrder>,
    pub comparison: Comparison,
    pub sentence: String,
}

/// The reference particle positions (and bodies' barycenters) at each sample time.
struct ClothReference {
    samples: Vec<Vec<Vector3<f64>>>,
    description: String,
    spread: f64,
}

/// The same scene with every cloth stepped by `integrator` (bodies keep the scene's).
pub fn with_integrator(scene: &Scene, integrator: ClothIntegrator) -> Scene {
    let mut scene = scene.clone();
    for cloth in &mut scene.cloths {
        cloth.integrator = integrator;
    }
    scene
}

/// Every particle of every cloth, then every body's barycenter.
fn points(world: &World) -> Vec<Vector3<f64>> {
    let mut points = particle_positions(world);
    points.extend(world.states().iter().map(|s| s.position));
    points
}

/// The largest distance between corresponding points, m.
fn distance(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

/// The explicit limit L = 2/ω_max of the scene's stiffest cloth, its damped limit h*, and
/// its name.
pub fn explicit_limit(scene: &Scene) -> (f64, f64, String) {
    ClothView::all(&scene.world())
        .into_iter()
        .map(|c| (c.stiffness_limit, c.explicit_limit, c.name))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((f64::INFINITY, f64::INFINITY, String::new()))
}

/// The dt ladder around the limit `h` (module doc), largest first.
pub fn ladder(h: f64) -> Vec<f64> {
    if !(h.is_finite() && h > 0.0) {
        return vec![1e-2, 5e-3, 2.5e-3, 1.25e-3];
    }
    let floor = ABOVE * h;
    let decade = 10f64.powf(floor.log10().floor());
    let top = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&t| t >= floor * (1.0 - 1e-12))
        .unwrap_or(10.0 * decade);
    let mut dts = vec![top];
    while dts[dts.len() - 1] > h / BELOW {
        let next = dts[dts.len() - 1] / 2.0;
        dts.push(next);
    }
    dts
}

/// The ladder dts an integrator runs at: all of them for an implicit one; for an explicit one
/// those below the limit `h` and the `past` smallest above it. Largest first.
pub fn dts_for(integrator: ClothIntegrator, ladder: &[f64], h: f64, past: usize) -> Vec<f64> {
    if !integrator.is_explicit() {
        return ladder.to_vec();
    }
    let above: Vec<f64> = ladder.iter().copied().filter(|&dt| dt > h).collect();
    let skip = above.len().saturating_sub(past);
    ladder.iter().copied().skip(skip).collect()
}

/// Studies the cloths of `case`'s scene. `progress(done, total)` after each run.
pub fn study(
    name: &str,
    scene: &Scene,
    duration: f64,
    config: &ClothConfig,
    progress: &mut dyn FnMut(usize, usize),
) -> ClothStudy {
    study_streaming(name, scene, duration, config, progress, &mut |_| {})
}

/// [`study`], telling `partial` of the study's frame once the reference is made (limit,
/// ladder, reference: [`super::Partial::ClothReference`], a study with no run yet) and of each run as it finishes
/// ([`super::Partial::ClothRun`]); the runs are made the cheapest first ([`sweep`]), so that a
/// front end's chart fills early, and the rows come back in the plan's order (integrator by
/// integrator, dt largest first), as if run in it.
pub fn study_streaming(
    name: &str,
    scene: &Scene,
    duration: f64,
    config: &ClothConfig,
    progress: &mut dyn FnMut(usize, usize),
    partial: &mut dyn FnMut(super::Partial),
) -> ClothStudy {
    let (limit, damped_limit, limiting_cloth) = explicit_limit(scene);
    let ladder = config.dts.clone().unwrap_or_else(|| ladder(limit));
    let times = sample_times(duration, config.timing.sample_interval);
    let smallest = ladder.iter().copied().fold(f64::INFINITY, f64::min);
    let reference = reference(scene, &times, smallest / REFERENCE_DIVISOR);
    let runs = sweep(scene, duration, config);
    let frame = summarise(
        ClothStudy {
            limit,
            damped_limit,
            limiting_cloth,
            ladder,
            reference: reference.description.clone(),
            reference_spread: reference.spread,
            rows: Vec::new(),
            orders: Vec::new(),
            comparison: compare(&[], limit),
            sentence: String::new(),
        },
        Vec::new(),
        &config.integrators,
    );
    partial(super::Partial::ClothReference(Box::new(frame.clone())));
    progress(0, runs.len());
    let mut measured: Vec<(usize, ClothRow)> = Vec::with_capacity(runs.len());
    for &(index, integrator, dt) in &runs {
        let row = measure(
            name,
            &with_integrator(scene, integrator),
            duration,
            integrator,
            dt,
            limit,
            &reference.samples,
            &times,
            config.timing,
        );
        partial(super::Partial::ClothRun(Box::new(row.clone())));
        measured.push((index, row));
        progress(measured.len(), runs.len());
    }
    let rows = measured.into_iter().map(|(_, row)| row).collect();
    let mut study = summarise(frame, rows, &config.integrators);
    study.sentence = sentence(
        &study.rows,
        &study.comparison,
        limit,
        damped_limit,
        duration,
    );
    study
}

/// `frame` (a study's limit, ladder and reference) with `rows` (finished runs, in any order):
/// sorted in the plan's order (by `integrators`, then as on the ladder), frontier marked,
/// orders fitted, the two integrators compared. What [`study`] and a front end's partial chart
/// both do with finished runs; the sentence is left empty (the caller writes it: [`sentence`]
/// once every run has finished).
pub fn summarise(
    frame: ClothStudy,
    mut rows: Vec<ClothRow>,
    integrators: &[ClothIntegrator],
) -> ClothStudy {
    let rank = |r: &ClothRow| {
        (
            integrators.iter().position(|&i| i == r.integrator),
            frame.ladder.iter().position(|&dt| dt == r.dt),
        )
    };
    rows.sort_by_key(rank);
    mark_frontier(&mut rows);
    let orders = integrators
        .iter()
        .map(|&i| {
            fit_order(
                i,
                &rows,
                frame.limit,
                FLOOR_SPREADS * frame.reference_spread,
            )
        })
        .collect();
    let comparison = compare(&rows, frame.limit);
    ClothStudy {
        rows,
        orders,
        comparison,
        sentence: String::new(),
        ..frame
    }
}

/// The runs [`study`] makes on `scene`, in the order it makes them: (index in the plan's order —
/// integrator by integrator, dt largest first; integrator; dt), the fewest steps first, ties
/// in the plan's order.
pub fn sweep(
    scene: &Scene,
    duration: f64,
    config: &ClothConfig,
) -> Vec<(usize, ClothIntegrator, f64)> {
    let (limit, _, _) = explicit_limit(scene);
    let ladder = config.dts.clone().unwrap_or_else(|| ladder(limit));
    let mut runs: Vec<(usize, ClothIntegrator, f64)> = plan(config, &ladder, limit)
        .into_iter()
        .enumerate()
        .map(|(index, (integrator, dt))| (index, integrator, dt))
        .collect();
    runs.sort_by_key(|&(index, _, dt)| (super::measure::steps_for(duration, dt), index));
    runs
}

/// The steps [`study`] makes on `scene` over `duration`: its reference's (symplectic-euler at
/// h_r and h_r/2), then each run's in the order they are made ([`sweep`]) — the accuracy run
/// and, when timed, the warm-up and timed runs ([`super::measure::steps_made`]). An explicit
/// run past the limit is counted without them: it diverges, and a diverged run is not timed
/// (it stops at its divergence, so its count is an upper bound).
pub fn planned_steps(scene: &Scene, duration: f64, config: &ClothConfig) -> (u64, Vec<u64>) {
    let (limit, _, _) = explicit_limit(scene);
    let ladder = config.dts.clone().unwrap_or_else(|| ladder(limit));
    let steps = |dt: f64| (duration / dt).round().max(1.0) as u64;
    let h = ladder.iter().copied().fold(f64::INFINITY, f64::min) / REFERENCE_DIVISOR;
    let reference = steps(h) + steps(h / 2.0);
    let runs = sweep(scene, duration, config)
        .into_iter()
        .map(|(_, i, dt)| {
            if i.is_explicit() && dt > limit {
                steps(dt)
            } else {
                super::measure::steps_made(steps(dt), &config.timing)
            }
        })
        .collect();
    (reference, runs)
}

/// How many runs [`study`] makes with `config` on `scene`.
pub fn runs(scene: &Scene, config: &ClothConfig) -> usize {
    let (limit, _, _) = explicit_limit(scene);
    let ladder = config.dts.clone().unwrap_or_else(|| ladder(limit));
    plan(config, &ladder, limit).len()
}

/// The runs [`study`] makes, in the plan's order: each integrator's time steps on `ladder`
/// ([`dts_for`]).
fn plan(config: &ClothConfig, ladder: &[f64], limit: f64) -> Vec<(ClothIntegrator, f64)> {
    config
        .integrators
        .iter()
        .flat_map(|&i| {
            dts_for(i, ladder, limit, config.past)
                .into_iter()
                .map(move |dt| (i, dt))
        })
        .collect()
}

/// The steps of a run at `dt` at which each sample time falls (the last is the run's end).
fn sample_steps(times: &[f64], dt: f64, steps: u64) -> Vec<u64> {
    let mut out: Vec<u64> = times
        .iter()
        .map(|&t| ((t / dt).round() as u64).clamp(1, steps))
        .collect();
    if let Some(last) = out.last_mut() {
        *last = steps;
    }
    out
}

/// Points of a symplectic-euler run at step `h`, at each sample time.
fn reference_run(scene: &Scene, times: &[f64], h: f64) -> Vec<Vec<Vector3<f64>>> {
    let scene = with_integrator(scene, ClothIntegrator::SymplecticEuler);
    let duration = times.last().copied().unwrap_or(0.0);
    let steps = (duration / h).round().max(1.0) as u64;
    let mut world = scene.world_with(scene.integrator, h);
    sample_steps(times, h, steps)
        .into_iter()
        .map(|target| {
            while world.step_count() < target {
                super::cancel::check(1);
                world.step();
            }
            points(&world)
        })
        .collect()
}

fn reference(scene: &Scene, times: &[f64], h: f64) -> ClothReference {
    let coarse = reference_run(scene, times, h);
    let fine = reference_run(scene, times, h / 2.0);
    let spread = coarse
        .iter()
        .zip(&fine)
        .map(|(a, b)| distance(a, b))
        .fold(0.0, f64::max);
    let smooth = scene.obstacles.is_empty() && scene.bodies.is_empty();
    if smooth {
        let samples = coarse
            .iter()
            .zip(&fine)
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| 2.0 * y - x).collect())
            .collect();
        ClothReference {
            samples,
            description: format!(
                "numeric: `symplectic-euler` at dt = {} and {} s, extrapolated (Richardson: \
                 2 x(h/2) − x(h), error O(h²)); the two runs differ by {} m at most",
                format_number(h),
                format_number(h / 2.0),
                format_number(spread)
            ),
            spread,
        }
    } else {
        ClothReference {
            samples: fine,
            description: format!(
                "numeric: `symplectic-euler` at dt = {} s (contact possible: not extrapolated); \
                 it differs from the run at {} s by {} m at most",
                format_number(h / 2.0),
                format_number(h),
                format_number(spread)
            ),
            spread,
        }
    }
}

/// Measures one run: the instrumented accuracy run, then (if it did not diverge) the timed runs.
#[allow(clippy::too_many_arguments)]
fn measure(
    name: &str,
    scene: &Scene,
    duration: f64,
    integrator: ClothIntegrator,
    dt: f64,
    limit: f64,
    reference: &[Vec<Vector3<f64>>],
    times: &[f64],
    timing: Timing,
) -> ClothRow {
    let steps = (duration / dt).round().max(1.0) as u64;
    let mut row = ClothRow {
        scene: name.to_string(),
        integrator,
        dt,
        steps,
        limit_ratio: dt / limit,
        ns_per_step: f64::NAN,
        us_per_simulated_second: f64::NAN,
        error: 0.0,
        energy_drift: 0.0,
        drift_j: 0.0,
        numerical_damping: f64::NAN,
        booked_losses: f64::NAN,
        energy_rise: f64::NEG_INFINITY,
        status: Status::Ok,
        frontier: false,
    };
    let started = std::time::Instant::now();
    let mut world = scene.world_with(scene.integrator, dt);
    let e0 = world.initial_total_energy().total;
    let mut previous = 0.0;
    let targets = sample_steps(times, dt, steps);
    let mut sample = 0;
    while world.step_count() < steps {
        super::cancel::check(1);
        world.step();
        if let Some(divergence) = world.divergence() {
            row.status = Status::Diverged(divergence.to_string());
            row.error = f64::NAN;
            if row.energy_rise == f64::NEG_INFINITY {
                row.energy_rise = f64::NAN;
            }
            return row;
        }
        let ledger = world.energy_ledger();
        let drift = world.total_energy().total - ledger.accounted();
        row.energy_rise = row.energy_rise.max(drift - previous);
        previous = drift;
        row.drift_j = row.drift_j.max(drift.abs());
        let step = world.step_count();
        while sample < targets.len() && targets[sample] == step {
            let now = points(&world);
            row.error = row.error.max(distance(&now, &reference[sample]));
            sample += 1;
        }
        if step == steps {
            row.numerical_damping = -drift;
            row.booked_losses = ledger.initial - ledger.accounted();
        }
    }
    row.energy_drift = if e0 != 0.0 {
        row.drift_j / e0.abs()
    } else {
        row.drift_j
    };
    let accuracy_ns = started.elapsed().as_nanos() as f64 / steps as f64;
    row.ns_per_step = if timing.repeats > 0 {
        let world = || scene.world_with(scene.integrator, dt);
        cost_per_step(world, steps, &timing, accuracy_ns)
    } else {
        accuracy_ns
    };
    row.us_per_simulated_second = row.ns_per_step / dt / 1000.0;
    row
}

/// Marks the runs no other run beats on both error and cost.
fn mark_frontier(rows: &mut [ClothRow]) {
    let usable = |r: &ClothRow| r.ok() && r.error.is_finite() && r.us_per_simulated_second > 0.0;
    let candidates: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| usable(r))
        .map(|r| (r.us_per_simulated_second, r.error))
        .collect();
    for row in rows.iter_mut() {
        let (cost, error) = (row.us_per_simulated_second, row.error);
        row.frontier = usable(row)
            && !candidates
                .iter()
                .any(|&(c, e)| c <= cost && e <= error && (c < cost || e < error));
    }
}

/// The least-squares slope of ln error against ln dt over an integrator's runs below the limit
/// that did not diverge and whose error is above the floor: round-off (1e-12 m) or `floor`,
/// the band the charts draw (3 × the reference's spread), inside which the reference cannot
/// tell runs apart, so a run there would flatten the slope.
pub fn fit_order(
    integrator: ClothIntegrator,
    rows: &[ClothRow],
    limit: f64,
    floor: f64,
) -> ClothOrder {
    let floor = floor.max(1e-12);
    let points: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.integrator == integrator && r.ok() && r.error > floor && r.dt < limit)
        .map(|r| (r.dt.ln(), r.error.ln()))
        .collect();
    let n = points.len();
    let slope = super::analysis::slope(&points);
    ClothOrder {
        integrator,
        slope,
        points: n,
    }
}

/// An integrator's runs that did not diverge, as (dt, error), largest dt first.
fn curve(rows: &[ClothRow], integrator: ClothIntegrator) -> Vec<(f64, f64)> {
    let mut points: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.integrator == integrator && r.ok() && r.error > 0.0)
        .map(|r| (r.dt, r.error))
        .collect();
    points.sort_by(|a, b| b.0.total_cmp(&a.0));
    points
}

/// The dt at which a curve (largest dt first) first comes down to `target`, going from its
/// largest dt down: ln error linear in ln dt between neighbouring points.
pub fn crossing(curve: &[(f64, f64)], target: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((d1, e1), (d2, e2)) = (w[0], w[1]);
        if e1 >= target && e2 <= target {
            if e1 == e2 {
                return Some(d1);
            }
            let s = (target.ln() - e1.ln()) / (e2.ln() - e1.ln());
            Some((d1.ln() + s * (d2.ln() - d1.ln())).exp())
        } else {
            None
        }
    })
}

/// The explicit integrator against the implicit one (module doc); `limit` = L.
pub fn compare(rows: &[ClothRow], limit: f64) -> Comparison {
    let explicit = curve(rows, ClothIntegrator::SymplecticEuler);
    let implicit = curve(rows, ClothIntegrator::ImplicitEuler);
    let past_limit = match (explicit.first(), implicit.first()) {
        (Some(&(explicit_dt, explicit_error)), Some(&(implicit_dt, implicit_error)))
            if implicit_dt > limit =>
        {
            Some(PastLimit {
                implicit_dt,
                implicit_error,
                explicit_dt,
                explicit_error,
                ratio: implicit_dt / explicit_dt,
            })
        }
        _ => None,
    };
    Comparison {
        same_error: same_error(rows, &explicit, &implicit),
        past_limit,
    }
}

fn same_error(rows: &[ClothRow], explicit: &[(f64, f64)], implicit: &[(f64, f64)]) -> SameError {
    let ran = |i: ClothIntegrator| rows.iter().any(|r| r.integrator == i);
    let missing = |i: ClothIntegrator| {
        SameError::Missing(if ran(i) {
            format!("every `{}` run diverged", i.name())
        } else {
            format!("`{}` was not run", i.name())
        })
    };
    let Some(&(explicit_dt, target)) = explicit.first() else {
        return missing(ClothIntegrator::SymplecticEuler);
    };
    let Some(&(largest, largest_error)) = implicit.first() else {
        return missing(ClothIntegrator::ImplicitEuler);
    };
    if largest_error <= target {
        return SameError::AtLeast {
            target,
            explicit_dt,
            implicit_dt: largest,
            implicit_error: largest_error,
            ratio: largest / explicit_dt,
        };
    }
    if let Some(implicit_dt) = crossing(implicit, target) {
        return SameError::Reached {
            target,
            explicit_dt,
            implicit_dt,
            ratio: implicit_dt / explicit_dt,
        };
    }
    let &(best_dt, best_error) = implicit
        .iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or(&(largest, largest_error));
    let extrapolated = match implicit {
        [.., (d1, e1), (d2, e2)] if e2 < e1 => {
            let slope = (e1.ln() - e2.ln()) / (d1.ln() - d2.ln());
            let dt = (d2.ln() + (target.ln() - e2.ln()) / slope).exp();
            Some((dt, dt / explicit_dt))
        }
        _ => None,
    };
    SameError::NotReached {
        target,
        explicit_dt,
        best_error,
        best_dt,
        extrapolated,
    }
}

/// "4.2 times more steps" (ratio ≥ 1, the explicit one takes more) or "… fewer".
fn steps_ratio(ratio: f64) -> String {
    if ratio >= 1.0 {
        format!(
            "`symplectic-euler` takes {} times as many steps as `implicit-euler`",
            format_number(ratio)
        )
    } else {
        format!(
            "`implicit-euler` takes {} times as many steps as `symplectic-euler` (ratio {} < 1)",
            format_number(1.0 / ratio),
            format_number(ratio)
        )
    }
}

/// The cloth case's sentence: the explicit limit, which dts were past it, the steps ratio for
/// the same error, and what the implicit step buys past the limit.
pub fn sentence(
    rows: &[ClothRow],
    comparison: &Comparison,
    limit: f64,
    damped_limit: f64,
    duration: f64,
) -> String {
    let mut limit_text = format!("Explicit limit 2/ω_max = {} s", format_number(limit));
    if (limit - damped_limit).abs() > 1e-12 * limit {
        limit_text = format!(
            "{limit_text} (with damping, stable below h* = {} s)",
            format_number(damped_limit)
        );
    }
    let past: Vec<String> = rows
        .iter()
        .filter(|r| r.integrator.is_explicit() && r.past_limit())
        .map(|r| {
            format!(
                "{} ({}×{})",
                format_dt(r.dt),
                format_number(r.limit_ratio),
                if r.ok() { ", did NOT diverge" } else { "" }
            )
        })
        .collect();
    let past_text = if past.is_empty() {
        "no `symplectic-euler` run was past it".to_string()
    } else if rows
        .iter()
        .filter(|r| r.integrator.is_explicit() && r.past_limit())
        .all(|r| !r.ok())
    {
        format!(
            "`symplectic-euler` diverged at every dt past it: {}",
            past.join(", ")
        )
    } else {
        format!("`symplectic-euler` past it at dt = {}", past.join(", "))
    };
    let between: Vec<String> = rows
        .iter()
        .filter(|r| r.integrator.is_explicit() && !r.past_limit() && r.dt > damped_limit)
        .map(|r| {
            format!(
                "{} ({}×, {})",
                format_dt(r.dt),
                format_number(r.limit_ratio),
                if r.ok() { "stable" } else { "diverged" }
            )
        })
        .collect();
    let past_text = if between.is_empty() {
        past_text
    } else {
        format!(
            "{past_text}; between h* and 2/ω_max, at dt = {}",
            between.join(", ")
        )
    };
    let same = match &comparison.same_error {
        SameError::Reached {
            target,
            explicit_dt,
            implicit_dt,
            ratio,
        } => format!(
            "For the same error ({} m over {duration} s: `symplectic-euler` at dt = {}, \
             `implicit-euler` at dt = {} s, interpolated) {}",
            format_number(*target),
            format_dt(*explicit_dt),
            format_number(*implicit_dt),
            steps_ratio(*ratio)
        ),
        SameError::AtLeast {
            target,
            explicit_dt,
            implicit_dt,
            implicit_error,
            ratio,
        } => format!(
            "`implicit-euler` at its largest dt = {} makes {} m, already under the {} m of \
             `symplectic-euler` at dt = {} (over {duration} s): `symplectic-euler` takes at \
             least {} times as many steps for the same error",
            format_dt(*implicit_dt),
            format_number(*implicit_error),
            format_number(*target),
            format_dt(*explicit_dt),
            format_number(*ratio)
        ),
        SameError::NotReached {
            target,
            explicit_dt,
            best_error,
            best_dt,
            extrapolated,
        } => {
            let guess = match extrapolated {
                Some((dt, ratio)) => format!(
                    "; extrapolating its two smallest dts it would need dt ≈ {} s: {}",
                    format_number(*dt),
                    steps_ratio(*ratio)
                ),
                None => String::new(),
            };
            format!(
                "`implicit-euler` never gets down to the error `symplectic-euler` makes at \
                 dt = {} ({} m over {duration} s) within the ladder: its smallest is {} m at \
                 dt = {}{guess}",
                format_dt(*explicit_dt),
                format_number(*target),
                format_number(*best_error),
                format_dt(*best_dt)
            )
        }
        SameError::Missing(why) => format!("No steps ratio for the same error: {why}"),
    };
    let beyond = match comparison.past_limit {
        Some(p) => format!(
            " Past the limit, `implicit-euler` runs at dt = {} ({}× 2/ω_max) with an error of \
             {} m, where `symplectic-euler` must stay at dt = {}: {} times as many steps, for \
             an error of {} m.",
            format_dt(p.implicit_dt),
            format_number(p.implicit_dt / limit),
            format_number(p.implicit_error),
            format_dt(p.explicit_dt),
            format_number(p.ratio),
            format_number(p.explicit_error)
        ),
        None => String::new(),
    };
    format!("{limit_text}: {past_text}. {same}.{beyond}")
}
