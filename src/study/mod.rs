//! `tumble study`: what accuracy costs in time.
//!
//! For each scene, each integrator and each time step of a sweep, the scene is run to its
//! duration and measured against an independent reference ([`mod@reference`]): error, drift of the
//! conserved quantities, and nanoseconds per step ([`measure`]). [`analysis`] marks the Pareto
//! frontier, fits the observed orders of convergence and writes one plain sentence per scene;
//! on a scene with contact, [`contact`] charts the collision responses (`impulse`, `soft-step`
//! at 1–8 sub-steps) at the scene's own integrator and dt;
//! asked (`--response A,B`), [`methods`] charts contact methods as the integrators are
//! charted: each over the dt sweep, error against cost (a straight bounce against its closed
//! form, [`bounce`]);
//! [`report`] prints the table, CSV or JSON and [`plot`] the log–log SVG of error against cost.
//!
//! The study only drives [`crate::physics::World`] and reads its [`crate::physics::Snapshot`]:
//! it never steps the physics itself.

pub mod analysis;
pub mod background;
pub mod bounce;
pub mod cancel;
pub mod cloth;
pub mod contact;
pub mod measure;
pub mod methods;
pub mod plot;
pub mod reference;
pub mod report;
pub mod scenes;

pub use analysis::{fit_order, mark_frontier, Order};
pub use cloth::{ClothConfig, ClothRow, ClothStudy};
pub use contact::{ContactStudy, SolverRow};
pub use measure::{Row, Status, Timing};
pub use methods::MethodStudy;
pub use reference::Reference;

use crate::physics::{Integrator, Response};
use crate::scene::{Lesson, Scene};
use std::path::Path;

/// How long a scene without a `duration` is studied, s.
pub const DEFAULT_DURATION: f64 = 5.0;

/// A scene to study.
#[derive(Debug, Clone)]
pub struct Case {
    /// Short name (the CSV's `scene` column).
    pub name: String,
    /// One line saying what it is.
    pub description: String,
    pub scene: Scene,
    /// Simulated time of every run, s.
    pub duration: f64,
}

impl Case {
    /// The one way a lesson becomes a study case (the command line, the app and the built-in
    /// scenes): named after its file, described by its title, run for its `duration` or, when
    /// it has none, [`DEFAULT_DURATION`] (the description says so).
    pub fn from_lesson(lesson: &Lesson) -> Case {
        let name = file_name(&lesson.path).unwrap_or_else(|| lesson.title.clone());
        let (duration, description) = match lesson.scene.duration {
            Some(d) => (d, lesson.title.clone()),
            None => (
                DEFAULT_DURATION,
                format!(
                    "{} (no `duration` in [scene]: studied over {DEFAULT_DURATION} s)",
                    lesson.title
                ),
            ),
        };
        Case {
            name,
            description,
            scene: lesson.scene.clone(),
            duration,
        }
    }

    /// The same case with another collision response; `None` if the scene has no contact.
    pub fn with_response(mut self, response: Response) -> Option<Case> {
        let model = self.scene.contact.as_mut()?;
        model.response = response;
        Some(self)
    }
}

/// A file's name without its extension.
fn file_name(path: &Path) -> Option<String> {
    path.file_stem().map(|s| s.to_string_lossy().into_owned())
}

/// What to sweep and how to time it.
#[derive(Debug, Clone)]
pub struct Config {
    pub integrators: Vec<Integrator>,
    /// Time steps, s.
    pub dts: Vec<f64>,
    pub timing: Timing,
    /// The error the per-scene sentence asks each integrator to stay under.
    pub target_error: f64,
}

impl Default for Config {
    /// Every integrator, dt = 1e-1 … 1e-4, 5 timed repeats, samples every 0.1 s, target 1e-6.
    fn default() -> Config {
        Config {
            integrators: Integrator::ALL.to_vec(),
            dts: vec![1e-1, 1e-2, 1e-3, 1e-4],
            timing: Timing {
                repeats: 5,
                sample_interval: 0.1,
            },
            target_error: 1e-6,
        }
    }
}

/// The study of one scene.
#[derive(Debug, Clone)]
pub struct SceneStudy {
    pub name: String,
    pub description: String,
    pub duration: f64,
    /// What the errors are measured against.
    pub reference: String,
    /// "exact", "converged", "not-converged" (the same model at a finer step, checked by
    /// halving it) or "numeric" (contact).
    pub reference_kind: &'static str,
    /// Errors at or below this are round-off or the reference's own error: not ranked, not
    /// fitted ([`analysis`]).
    pub floor: f64,
    /// Sorted by cost (µs per simulated second), diverged runs last.
    pub rows: Vec<Row>,
    /// The observed order of each integrator.
    pub orders: Vec<Order>,
    /// "to keep the error under … over … s, `rk4` needs dt = … and costs …".
    pub sentence: String,
    /// The collision response of a scene with contact (measured by the contact error).
    pub response: Option<Response>,
    /// The cloth case: a scene with `[[cloth]]` sweeps the particle integrators instead of the
    /// bodies' (its `rows` and `orders` are then empty, its `sentence` is the cloth case's).
    pub cloth: Option<ClothStudy>,
    /// A scene with contact: its contact solvers charted at its own integrator and dt
    /// ([`contact`]).
    pub contact_solvers: Option<ContactStudy>,
    /// The contact methods asked for (`--response A,B`), each over the dt sweep at the
    /// scene's integrator ([`methods`]); None unless asked.
    pub methods: Option<MethodStudy>,
}

impl SceneStudy {
    /// The scene has contact: runs are ranked by the contact error.
    pub fn contact(&self) -> bool {
        self.response.is_some()
    }
}

/// What a front end can draw before a study ends ([`study_case_streaming`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Partial {
    /// The reference is made: the floor below which errors are not ranked, the reference's
    /// kind and one line saying what it is.
    Reference {
        floor: f64,
        kind: &'static str,
        description: String,
    },
    /// One run has finished (its accuracy and timing measured).
    Run(Box<Row>),
    /// A cloth case's reference is made: its limit, ladder and reference (a cloth study with
    /// no run yet).
    ClothReference(Box<ClothStudy>),
    /// One run of a cloth case has finished.
    ClothRun(Box<ClothRow>),
}

/// Studies one scene. `progress(done, total)` is called after each run.
pub fn study_case(
    case: &Case,
    config: &Config,
    progress: &mut dyn FnMut(usize, usize),
) -> SceneStudy {
    study_case_streaming(case, config, progress, &mut |_| {})
}

/// The orders of `integrators` from `rows` (against a reference of kind `reference_kind`,
/// errors above `floor`), and the rows marked (floor band, frontier) and sorted by cost: what
/// the study and a front end's partial chart ([`Partial`]) both do with finished runs.
pub fn summarise(
    integrators: &[Integrator],
    rows: &mut [Row],
    reference_kind: &str,
    floor: f64,
) -> Vec<Order> {
    let orders = integrators
        .iter()
        .map(|&i| {
            if reference_kind == "exact" && i.descriptor().exact_without_torque {
                analysis::exact_order(i)
            } else {
                fit_order(i, rows, floor)
            }
        })
        .collect();
    mark_frontier(rows, floor);
    analysis::sort_by_cost(rows);
    orders
}

/// [`study_case`], telling `partial` of the reference once it is made and of each run as it
/// finishes (the cheapest first: a front end's chart fills early); a cloth case, of its frame
/// and its runs ([`cloth::study_streaming`]).
pub fn study_case_streaming(
    case: &Case,
    config: &Config,
    progress: &mut dyn FnMut(usize, usize),
    partial: &mut dyn FnMut(Partial),
) -> SceneStudy {
    if !case.scene.cloths.is_empty() {
        return study_cloth_case(case, config, progress, partial);
    }
    let times = measure::sample_times(case.duration, config.timing.sample_interval);
    let smallest = config.dts.iter().copied().fold(f64::INFINITY, f64::min);
    let mut reference = Reference::for_scene(&case.scene, &times, smallest);
    let floor = analysis::FLOOR.max(reference.floor());
    partial(Partial::Reference {
        floor,
        kind: reference.kind(),
        description: reference.describe(),
    });
    let total = config.integrators.len() * config.dts.len();
    // The reference is made: the runs start. The cheapest runs first ([`sweep`]), so that a
    // front end's progress moves early; the rows then go back to the sweep's order
    // (integrator by integrator), as if run in it.
    progress(0, total);
    let mut measured: Vec<(usize, Row)> = Vec::with_capacity(total);
    for (index, integrator, dt) in sweep(case, config) {
        let row = measure::measure(
            &case.name,
            &case.scene,
            case.duration,
            integrator,
            dt,
            &mut reference,
            &times,
            config.timing,
        );
        partial(Partial::Run(Box::new(row.clone())));
        measured.push((index, row));
        progress(measured.len(), total);
    }
    measured.sort_by_key(|&(index, _)| index);
    let mut rows: Vec<Row> = measured.into_iter().map(|(_, row)| row).collect();
    let response = case
        .scene
        .contact
        .filter(|_| !case.scene.obstacles.is_empty())
        .map(|m| m.response);
    let sentence = match response {
        Some(response) if rows.iter().all(|r| !r.ok()) => format!(
            "Every integrator diverges at every time step with the `{}` collision response: \
             the response, not the integration, is the cause.",
            response.name()
        ),
        _ => analysis::sentence(
            &rows,
            &config.integrators,
            config.target_error,
            case.duration,
        ),
    };
    let orders = summarise(&config.integrators, &mut rows, reference.kind(), floor);
    let sentence = match (reference.kind(), reference.spread()) {
        ("not-converged", Some(spread)) => format!(
            "No converged reference: halving rk4's step from {} s moved the reference by {} \
             (angle + pos/radius) over {} s — the motion amplifies every difference (chaos) until \
             no reference holds, so these errors measure the reference as much as the runs. {sentence}",
            analysis::format_dt(spread.coarse_dt),
            analysis::format_number(spread.error),
            case.duration
        ),
        _ if rows.iter().all(|r| !r.ok() || r.below_floor) && rows.iter().any(|r| r.ok()) => {
            format!(
                "Every run that finished is within the floor ({}): the reference does not \
                 resolve their errors. {sentence}",
                analysis::format_number(floor)
            )
        }
        _ => sentence,
    };
    let contact_solvers = response.map(|_| {
        let chart = contact::study(
            &case.name,
            &case.scene,
            case.duration,
            &times,
            config.timing,
        );
        progress(total + chart.rows.len(), runs(case, config));
        chart
    });
    SceneStudy {
        name: case.name.clone(),
        description: case.description.clone(),
        duration: case.duration,
        reference: reference.describe(),
        reference_kind: reference.kind(),
        floor,
        rows,
        orders,
        sentence,
        response,
        cloth: None,
        contact_solvers,
        methods: None,
    }
}

/// Refuses, before anything runs, a case whose study would keep too many samples or whose
/// finest run would take too many steps ([`crate::limits`]): the error names `duration`.
pub fn check_work(case: &Case, config: &Config) -> Result<(), String> {
    use crate::limits::{self, short};
    let duration = short(case.duration);
    let interval = config.timing.sample_interval;
    limits::count(
        case.duration / interval,
        limits::MAX_SAMPLES,
        &format!(
            "`duration` = {duration} s (a sample every {} s)",
            short(interval)
        ),
        "samples",
        "give the scene a shorter `duration` to study it",
    )?;
    let finest = if case.scene.cloths.is_empty() {
        config.dts.iter().copied().fold(f64::INFINITY, f64::min)
    } else {
        let cloth = cloth_config(config);
        let ladder = cloth
            .dts
            .unwrap_or_else(|| cloth::ladder(cloth::explicit_limit(&case.scene).0));
        ladder.into_iter().fold(f64::INFINITY, f64::min)
    };
    if finest.is_finite() {
        limits::steps(
            case.duration,
            finest,
            &format!("a study of `duration` = {duration} s"),
            "its finest run is at that dt; give the scene a shorter `duration` to study it",
        )?;
    }
    Ok(())
}

/// The cloth settings a study with `config` uses: its timing, the default ladder.
pub fn cloth_config(config: &Config) -> ClothConfig {
    ClothConfig {
        timing: config.timing,
        ..ClothConfig::default()
    }
}

/// The integrator runs of a study in the order they are made: (index in the order integrator
/// by integrator, then dt; integrator; dt), the fewest steps first (the largest dt), ties in
/// the integrators' order.
pub fn sweep(case: &Case, config: &Config) -> Vec<(usize, Integrator, f64)> {
    let mut runs: Vec<(usize, Integrator, f64)> = config
        .integrators
        .iter()
        .flat_map(|&integrator| config.dts.iter().map(move |&dt| (integrator, dt)))
        .enumerate()
        .map(|(index, (integrator, dt))| (index, integrator, dt))
        .collect();
    runs.sort_by_key(|&(index, _, dt)| (measure::steps_for(case.duration, dt), index));
    runs
}

/// The steps each run of a study makes in all ([`measure::steps_made`]: accuracy run, warm-up,
/// timed runs), in the order the runs are made ([`sweep`], then the contact solvers at the
/// scene's dt, the first with the contact chart's reference): what a front end's estimate of
/// the time left is scaled by. A cloth case's are its ladder's ([`cloth::planned_steps`]).
pub fn run_steps(case: &Case, config: &Config) -> Option<Vec<u64>> {
    if !case.scene.cloths.is_empty() {
        let (_, runs) = cloth::planned_steps(&case.scene, case.duration, &cloth_config(config));
        return Some(runs);
    }
    let made = |dt| measure::steps_made(measure::steps_for(case.duration, dt), &config.timing);
    let mut steps: Vec<u64> = sweep(case, config)
        .into_iter()
        .map(|(_, _, dt)| made(dt))
        .collect();
    let contact = case.scene.contact.is_some() && !case.scene.obstacles.is_empty();
    if contact {
        // Each solver: its accuracy and timed runs, and one more run to the end (the sink);
        // before the first, the chart's reference at a tenth of the scene's dt.
        let each = made(case.scene.dt) + measure::steps_for(case.duration, case.scene.dt);
        let first = each + measure::steps_for(case.duration, case.scene.dt / 10.0);
        steps.push(first);
        steps.extend(std::iter::repeat_n(each, contact::solvers().len() - 1));
    }
    Some(steps)
}

/// The steps of the reference a (non-cloth) study makes before its first run
/// ([`Reference::for_scene`]): none for a closed form, else rk4 at a tenth of the smallest dt
/// and, without obstacles, again at half that step; a cloth case's, symplectic-euler at
/// h_r and h_r/2 ([`cloth::planned_steps`]).
pub fn reference_steps(case: &Case, config: &Config) -> u64 {
    if !case.scene.cloths.is_empty() {
        return cloth::planned_steps(&case.scene, case.duration, &cloth_config(config)).0;
    }
    if reference::has_closed_form(&case.scene) {
        return 0;
    }
    let smallest = config.dts.iter().copied().fold(f64::INFINITY, f64::min);
    let coarse = measure::steps_for(case.duration, smallest / 10.0);
    if case.scene.obstacles.is_empty() {
        coarse + measure::steps_for(case.duration, smallest / 20.0)
    } else {
        coarse
    }
}

/// How many runs studying `case` with `config` makes.
pub fn runs(case: &Case, config: &Config) -> usize {
    if case.scene.cloths.is_empty() {
        let contact = case.scene.contact.is_some() && !case.scene.obstacles.is_empty();
        config.integrators.len() * config.dts.len()
            + if contact { contact::solvers().len() } else { 0 }
    } else {
        cloth::runs(&case.scene, &cloth_config(config))
    }
}

/// The cloth case of a scene with `[[cloth]]` ([`cloth`]): the particle integrators over a
/// ladder of dt around the sheets' explicit limit; the bodies (if any) keep the scene's
/// integrator.
fn study_cloth_case(
    case: &Case,
    config: &Config,
    progress: &mut dyn FnMut(usize, usize),
    partial: &mut dyn FnMut(Partial),
) -> SceneStudy {
    let cloth = cloth::study_streaming(
        &case.name,
        &case.scene,
        case.duration,
        &cloth_config(config),
        progress,
        partial,
    );
    cloth_scene_study(
        case.name.clone(),
        case.description.clone(),
        case.duration,
        cloth,
    )
}

/// The [`SceneStudy`] of a cloth case named `name`: its cloth study, the sentence the cloth
/// study's.
pub fn cloth_scene_study(
    name: String,
    description: String,
    duration: f64,
    cloth: ClothStudy,
) -> SceneStudy {
    SceneStudy {
        name,
        description,
        duration,
        reference: cloth.reference.clone(),
        reference_kind: "numeric",
        floor: analysis::FLOOR,
        rows: Vec::new(),
        orders: Vec::new(),
        sentence: cloth.sentence.clone(),
        response: None,
        cloth: Some(cloth),
        contact_solvers: None,
        methods: None,
    }
}

/// Studies every case, on as many threads as there are cores (one case per thread at a
/// time, the longest cases first); the studies come back in the order of `cases`.
/// `progress(done, total)` counts runs over all cases, called on the caller's thread.
///
/// Each run is still timed alone on its thread: a case's rows compare integrators measured
/// under the same conditions, and its ns/step is the minimum over its timed runs of each
/// one's median 1000-step chunk ([`measure`]), which a neighbour on the other core does not
/// shift the way a shared time slice would.
pub fn study(
    cases: &[Case],
    config: &Config,
    progress: &mut dyn FnMut(usize, usize),
) -> Vec<SceneStudy> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::mpsc;
    let counts: Vec<usize> = cases.iter().map(|c| runs(c, config)).collect();
    let total = counts.iter().sum();
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(cases.len());
    if workers <= 1 {
        let mut before = 0;
        return cases
            .iter()
            .zip(&counts)
            .map(|(case, &count)| {
                let study = study_case(case, config, &mut |done, _| progress(before + done, total));
                before += count;
                study
            })
            .collect();
    }
    // The longest cases (most steps over all runs) first, so that no thread is left with a
    // long case at the end.
    let mut order: Vec<usize> = (0..cases.len()).collect();
    let cost = |i: usize| counts[i] as f64 * cases[i].duration * cloth_weight(&cases[i]);
    order.sort_by(|&a, &b| cost(b).total_cmp(&cost(a)));
    let next = AtomicUsize::new(0);
    let (sender, receiver) = mpsc::channel::<(usize, Option<Box<SceneStudy>>)>();
    let mut results: Vec<Option<SceneStudy>> = (0..cases.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let sender = sender.clone();
            let (next, order) = (&next, &order);
            scope.spawn(move || loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = order.get(k) else { break };
                let study = study_case(&cases[i], config, &mut |done, _| {
                    if done > 0 {
                        let _ = sender.send((i, None));
                    }
                });
                let _ = sender.send((i, Some(Box::new(study))));
            });
        }
        drop(sender);
        let mut done = 0;
        for (i, study) in receiver {
            match study {
                None => {
                    done += 1;
                    progress(done, total);
                }
                Some(study) => results[i] = Some(*study),
            }
        }
    });
    results.into_iter().flatten().collect()
}

/// A rough weight of a case's cost per run and simulated second: a cloth's particles make
/// every step dearer than a body's.
fn cloth_weight(case: &Case) -> f64 {
    1.0 + case
        .scene
        .cloths
        .iter()
        .map(|c| (c.count[0] * c.count[1]) as f64)
        .sum::<f64>()
}
