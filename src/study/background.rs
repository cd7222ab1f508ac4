//! A study of one scene on a background thread, for front ends that must stay responsive.
//!
//! [`Job::spawn`] starts the thread; [`Job::poll`] drains its messages without blocking and
//! keeps the latest progress, an estimate of the time left and, at the end, the result. The
//! runs are made the cheapest first ([`super::sweep`]). A job is a cheap handle (clones share
//! one thread and one result). [`Job::cancel`] stops the thread at its next step (the study's
//! loops check the flag, [`super::cancel`]); dropping every handle cancels it too.
//!
//! ```text
//! time left ≈ (wall time so far) / (steps made so far)
//!             × (steps the reference and the unfinished runs will still make)
//! ```
//!
//! the steps counted as the study makes them ([`super::cancel::check`]) and planned from the
//! scene ([`super::reference_steps`], [`super::run_steps`]): the cost per step measured so far,
//! scaled by each remaining run's steps; a cloth case's from its ladder
//! ([`super::cloth::planned_steps`]).

use super::cloth::{ClothRow, ClothStudy};
use super::measure::Row;
use super::{cancel, study_case_streaming, Case, Config, Partial, SceneStudy};
use std::sync::atomic::Ordering;
use std::sync::mpsc::{self, Receiver, TryRecvError};
use std::sync::{Arc, Mutex};
use std::thread::{self, JoinHandle};
use std::time::{Duration, Instant};

/// What the study thread reports.
#[derive(Debug)]
enum Message {
    Progress {
        done: usize,
        total: usize,
        /// Steps made when the message was sent.
        made: u64,
    },
    /// The reference, then each finished run.
    Partial(Partial),
    Done(Box<SceneStudy>),
}

/// A case's name, description, duration and (with contact) collision response.
type About = (String, String, f64, Option<crate::physics::Response>);

/// The [`About`] of `case`.
fn about(case: &Case) -> About {
    let contact = case
        .scene
        .contact
        .filter(|_| !case.scene.obstacles.is_empty());
    (
        case.name.clone(),
        case.description.clone(),
        case.duration,
        contact.map(|m| m.response),
    )
}

/// What has finished so far, to draw before the end ([`Job::partial`]).
#[derive(Debug, Clone)]
enum Finished {
    /// The bodies' integrators: the reference, then the runs so far.
    Bodies {
        floor: f64,
        kind: &'static str,
        description: String,
        rows: Vec<Row>,
    },
    /// A cloth case: its frame (limit, ladder, reference; no run), then the runs so far.
    Cloth {
        frame: Box<ClothStudy>,
        rows: Vec<ClothRow>,
    },
}

/// A running (or finished) study of one scene.
#[derive(Debug, Clone)]
pub struct Job {
    /// The scene's name.
    pub name: String,
    /// The collision response the scene was studied with (scenes with contact).
    pub response: Option<crate::physics::Response>,
    inner: Arc<Mutex<Inner>>,
}

#[derive(Debug)]
struct Inner {
    receiver: Receiver<Message>,
    done: usize,
    total: usize,
    result: Option<SceneStudy>,
    lost: bool,
    /// Why the study was refused before it started ([`super::check_work`]).
    refused: Option<String>,
    /// The cancel flag ([`Job::cancel`]) and the steps made so far.
    control: cancel::Control,
    /// The study thread, until joined ([`Job::join`]).
    thread: Option<JoinHandle<()>>,
    /// Steps of the reference, then of each run in the order they are made.
    plan: Option<(u64, Vec<u64>)>,
    /// The reference is made (the study said "0 runs done").
    reference_made: bool,
    /// Steps made at the latest message.
    made_at_latest: u64,
    spawned: Instant,
    /// The case (name, description, duration, the response of a scene with contact) and the
    /// integrators swept, for the partial chart.
    case: About,
    integrators: Vec<crate::physics::Integrator>,
    /// The reference and the runs finished so far.
    finished: Option<Finished>,
}

impl Drop for Inner {
    /// The last handle is gone: nobody will read the result, so stop the work.
    fn drop(&mut self) {
        self.control.cancel.store(true, Ordering::Relaxed);
    }
}

impl Job {
    /// Starts studying `case` on a new thread; a case past the bounds of
    /// [`super::check_work`] is refused at once (no thread, [`Job::refusal`] says why).
    pub fn spawn(case: Case, config: Config) -> Job {
        let (sender, receiver) = mpsc::channel();
        let name = case.name.clone();
        let response = case.scene.contact.map(|m| m.response);
        if let Err(why) = super::check_work(&case, &config) {
            return Job {
                name,
                response,
                inner: Arc::new(Mutex::new(Inner {
                    receiver,
                    done: 0,
                    total: 0,
                    result: None,
                    lost: true,
                    refused: Some(why),
                    control: cancel::Control::default(),
                    thread: None,
                    plan: None,
                    reference_made: false,
                    made_at_latest: 0,
                    spawned: Instant::now(),
                    case: about(&case),
                    integrators: config.integrators.clone(),
                    finished: None,
                })),
            };
        }
        let about = about(&case);
        let integrators = config.integrators.clone();
        let total = super::runs(&case, &config);
        let plan = super::run_steps(&case, &config)
            .map(|runs| (super::reference_steps(&case, &config), runs));
        let control = cancel::Control::default();
        let shared = control.clone();
        let thread = thread::spawn(move || {
            let steps = shared.steps.clone();
            let progress = sender.clone();
            let mut report = |done, total| {
                let made = steps.load(Ordering::Relaxed);
                let _ = progress.send(Message::Progress { done, total, made });
            };
            let partial = sender.clone();
            let mut partial = |p| {
                let _ = partial.send(Message::Partial(p));
            };
            if let Some(study) = cancel::run(shared, || {
                study_case_streaming(&case, &config, &mut report, &mut partial)
            }) {
                let _ = sender.send(Message::Done(Box::new(study)));
            }
        });
        Job {
            name,
            response,
            inner: Arc::new(Mutex::new(Inner {
                receiver,
                done: 0,
                total,
                result: None,
                lost: false,
                refused: None,
                control,
                thread: Some(thread),
                plan,
                reference_made: false,
                made_at_latest: 0,
                spawned: Instant::now(),
                case: about,
                integrators,
                finished: None,
            })),
        }
    }

    /// The study so far, before it ends: the runs finished (the cheapest first), their
    /// floor band, frontier and fitted orders ([`super::summarise`]; a cloth case's
    /// [`super::cloth::summarise`]), and a sentence saying how many runs are still to come.
    /// `None` before the reference is made and once the study is done ([`Job::result`]).
    pub fn partial(&self) -> Option<SceneStudy> {
        self.with(|inner| {
            if inner.result.is_some() {
                return None;
            }
            let (name, description, duration, response) = inner.case.clone();
            let left = |done: usize| {
                format!(
                    "{done} of {} runs finished (the cheapest first): the chart fills as the \
                     others finish; the orders are fitted on the runs so far.",
                    inner.total
                )
            };
            match inner.finished.as_ref()? {
                Finished::Bodies {
                    floor,
                    kind,
                    description: reference,
                    rows,
                } => {
                    let mut rows = rows.clone();
                    let orders = super::summarise(&inner.integrators, &mut rows, kind, *floor);
                    Some(SceneStudy {
                        name,
                        description,
                        duration,
                        reference: reference.clone(),
                        reference_kind: kind,
                        floor: *floor,
                        sentence: left(rows.len()),
                        rows,
                        orders,
                        response,
                        cloth: None,
                        contact_solvers: None,
                        methods: None,
                    })
                }
                Finished::Cloth { frame, rows } => {
                    let mut cloth = super::cloth::summarise(
                        frame.as_ref().clone(),
                        rows.clone(),
                        &super::ClothConfig::default().integrators,
                    );
                    cloth.sentence = left(rows.len());
                    Some(super::cloth_scene_study(name, description, duration, cloth))
                }
            }
        })
    }

    /// Stops the study at its next step (the thread then ends; see [`Job::join`]).
    pub fn cancel(&self) {
        self.with(|inner| inner.control.cancel.store(true, Ordering::Relaxed));
    }

    /// The study was cancelled.
    pub fn cancelled(&self) -> bool {
        self.with(|inner| inner.control.cancel.load(Ordering::Relaxed))
    }

    /// The study thread has ended (finished, cancelled or died), or never started.
    pub fn ended(&self) -> bool {
        self.with(|inner| inner.thread.as_ref().is_none_or(|t| t.is_finished()))
    }

    /// Waits for the study thread to end (after [`Job::cancel`], within a step of the scene).
    pub fn join(&self) {
        if let Some(thread) = self.with(|inner| inner.thread.take()) {
            let _ = thread.join();
        }
    }

    /// The estimated wall time left ([`estimate`], module doc), after the first second.
    pub fn time_left(&self) -> Option<Duration> {
        self.with(|inner| {
            if inner.result.is_some() || inner.control.cancel.load(Ordering::Relaxed) {
                return None;
            }
            let (reference, runs) = inner.plan.as_ref()?;
            let made = inner.control.steps.load(Ordering::Relaxed);
            let planned = if inner.reference_made { 0 } else { *reference }
                + runs.iter().skip(inner.done).sum::<u64>();
            let left = planned.saturating_sub(made - inner.made_at_latest.min(made));
            // The first second's pace (allocations, caches) says little of the rest.
            let spent = inner.spawned.elapsed();
            (spent >= Duration::from_secs(1)).then(|| estimate(left, made, spent))?
        })
    }

    fn with<T>(&self, f: impl FnOnce(&mut Inner) -> T) -> T {
        let mut inner = self
            .inner
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        f(&mut inner)
    }

    /// Both handles are the same study (one thread, one result).
    pub fn same(&self, other: &Job) -> bool {
        Arc::ptr_eq(&self.inner, &other.inner)
    }

    /// Takes every message waiting; never blocks.
    pub fn poll(&self) {
        self.with(|inner| loop {
            match inner.receiver.try_recv() {
                Ok(Message::Progress { done, total, made }) => {
                    inner.reference_made = true;
                    inner.made_at_latest = made;
                    (inner.done, inner.total) = (done, total);
                }
                Ok(Message::Partial(Partial::Reference {
                    floor,
                    kind,
                    description,
                })) => {
                    inner.finished = Some(Finished::Bodies {
                        floor,
                        kind,
                        description,
                        rows: Vec::new(),
                    });
                }
                Ok(Message::Partial(Partial::Run(row))) => {
                    if let Some(Finished::Bodies { rows, .. }) = inner.finished.as_mut() {
                        rows.push(*row);
                    }
                }
                Ok(Message::Partial(Partial::ClothReference(frame))) => {
                    inner.finished = Some(Finished::Cloth {
                        frame,
                        rows: Vec::new(),
                    });
                }
                Ok(Message::Partial(Partial::ClothRun(row))) => {
                    if let Some(Finished::Cloth { rows, .. }) = inner.finished.as_mut() {
                        rows.push(*row);
                    }
                }
                Ok(Message::Done(study)) => {
                    inner.done = inner.total;
                    inner.result = Some(*study);
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    inner.lost =
                        inner.result.is_none() && !inner.control.cancel.load(Ordering::Relaxed);
                    break;
                }
            }
        })
    }

    /// Runs finished and runs in all.
    pub fn progress(&self) -> (usize, usize) {
        self.with(|inner| (inner.done, inner.total))
    }

    /// The study, once finished (a copy).
    pub fn result(&self) -> Option<SceneStudy> {
        self.with(|inner| inner.result.clone())
    }

    /// Finished (with a result, because the thread died, or cancelled).
    pub fn finished(&self) -> bool {
        self.with(|inner| {
            inner.result.is_some() || inner.lost || inner.control.cancel.load(Ordering::Relaxed)
        })
    }

    /// The thread ended without a result (it panicked), or the study was refused.
    pub fn failed(&self) -> bool {
        self.with(|inner| inner.lost)
    }

    /// Why the study was refused before it started (too much work for its bounds).
    pub fn refusal(&self) -> Option<String> {
        self.with(|inner| inner.refused.clone())
    }
}

/// The wall time left when `made` steps took `spent` and `left` steps are still to make:
/// `spent / made × left`; `None` before any step.
pub fn estimate(left: u64, made: u64, spent: Duration) -> Option<Duration> {
    (made > 0).then(|| Duration::from_secs_f64(spent.as_secs_f64() / made as f64 * left as f64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Integrator;
    use crate::study::{scenes, Timing};
    use std::time::{Duration, Instant};

    #[test]
    fn a_job_reports_progress_then_its_result_without_blocking() {
        let mut case = scenes::builtin().remove(2); // the projectile, 1 s
        case.duration = 0.5;
        let config = Config {
            integrators: vec![Integrator::Rk4, Integrator::Splitting],
            dts: vec![1e-1, 1e-2],
            timing: Timing {
                repeats: 0,
                sample_interval: 0.1,
            },
            target_error: 1e-6,
        };
        let job = Job::spawn(case, config);
        assert_eq!(job.progress().1, 4, "2 integrators × 2 steps");
        let started = Instant::now();
        while job.result().is_none() {
            job.poll();
            assert!(!job.failed(), "the study thread died");
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "study never finished"
            );
            thread::sleep(Duration::from_millis(5));
        }
        assert_eq!(job.progress(), (4, 4));
        assert_eq!(job.result().map(|s| s.rows.len()), Some(4));
        assert!(job.time_left().is_none(), "nothing left");
        job.join();
        assert!(job.ended());
    }

    #[test]
    fn the_time_left_scales_the_cost_per_step_so_far_by_the_steps_left() {
        let s = Duration::from_secs_f64;
        assert_eq!(estimate(100, 0, s(1.0)), None, "no step made yet");
        // 100 steps in 2 s: 20 ms a step; 9900 steps left: 198 s.
        let left = estimate(9900, 100, s(2.0)).unwrap();
        assert!((left.as_secs_f64() - 198.0).abs() < 1e-9, "{left:?}");
        assert_eq!(estimate(0, 100, s(2.0)), Some(Duration::ZERO));
    }

    #[test]
    fn the_runs_go_cheapest_first_and_the_rows_come_back_in_the_sweep_order() {
        let case = scenes::builtin().remove(2); // the projectile, 1 s
        let config = Config {
            integrators: vec![Integrator::Rk4, Integrator::Splitting],
            dts: vec![1e-2, 1e-1],
            timing: Timing {
                repeats: 0,
                sample_interval: 0.1,
            },
            target_error: 1e-6,
        };
        let order: Vec<(usize, f64)> = crate::study::sweep(&case, &config)
            .into_iter()
            .map(|(index, _, dt)| (index, dt))
            .collect();
        assert_eq!(order, [(1, 1e-1), (3, 1e-1), (0, 1e-2), (2, 1e-2)]);
        assert_eq!(
            crate::study::run_steps(&case, &config),
            Some(vec![10, 10, 100, 100]),
            "untimed: the accuracy run only"
        );
        assert_eq!(
            crate::study::reference_steps(&case, &config),
            0,
            "a closed form"
        );
        let mut calls = Vec::new();
        let study = crate::study::study_case(&case, &config, &mut |done, _| calls.push(done));
        assert_eq!(calls, [0, 1, 2, 3, 4], "the reference, then each run");
        let rows: Vec<(Integrator, f64)> =
            study.rows.iter().map(|r| (r.integrator, r.dt)).collect();
        assert_eq!(rows.len(), 4);
        for pair in [(Integrator::Rk4, 1e-2), (Integrator::Splitting, 1e-1)] {
            assert!(rows.contains(&pair), "{pair:?} in {rows:?}");
        }
    }

    #[test]
    fn a_cloth_case_plans_the_steps_its_study_makes() {
        // The 5 × 5 sheet over 0.2 s, untimed: the reference and every run that does not
        // diverge make exactly their planned steps; a diverged run (explicit, past the limit)
        // makes at most its planned steps.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/study/small-sheet.toml");
        let lesson = crate::scene::load(&path).expect("fixture loads");
        let case = Case {
            name: "sheet".into(),
            description: "a small sheet".into(),
            scene: lesson.scene,
            duration: 0.2,
        };
        let config = Config {
            timing: Timing {
                repeats: 0,
                sample_interval: 0.1,
            },
            ..Config::default()
        };
        let reference = crate::study::reference_steps(&case, &config);
        let runs = crate::study::run_steps(&case, &config).expect("a cloth case has a plan");
        assert_eq!(runs.len(), crate::study::runs(&case, &config));
        let control = cancel::Control::default();
        let study = cancel::run(control.clone(), || {
            crate::study::study_case(&case, &config, &mut |_, _| {})
        })
        .expect("not cancelled");
        let made = control.steps.load(Ordering::Relaxed);
        let rows = &study.cloth.expect("the cloth case").rows;
        assert_eq!(rows.len(), runs.len());
        // The runs in the order they are made: rows[index] is the k-th run made.
        let made_order = crate::study::cloth::sweep(
            &case.scene,
            case.duration,
            &crate::study::cloth_config(&config),
        );
        let costs: Vec<u64> = made_order
            .iter()
            .map(|&(_, _, dt)| crate::study::measure::steps_for(case.duration, dt))
            .collect();
        assert!(costs.is_sorted(), "the cheapest runs first: {costs:?}");
        let row = |k: usize| &rows[made_order[k].0];
        for (k, &(_, integrator, dt)) in made_order.iter().enumerate() {
            assert_eq!((row(k).integrator, row(k).dt), (integrator, dt));
        }
        let sure: u64 = (0..runs.len())
            .filter(|&k| row(k).ok())
            .map(|k| runs[k])
            .sum();
        let all: u64 = runs.iter().sum();
        assert!(
            rows.iter().any(|r| !r.ok()),
            "explicit runs past the limit diverge"
        );
        assert!(
            (reference + sure..=reference + all).contains(&made),
            "made {made}, planned {reference} + {sure} … {all}"
        );
        // The timed plan adds the warm-up and timed runs of the runs below the limit only.
        let timed = crate::study::run_steps(&case, &Config::default()).expect("a plan");
        for (k, (&untimed, &timed)) in runs.iter().zip(&timed).enumerate() {
            let r = row(k);
            let below = !(r.integrator.is_explicit() && r.past_limit());
            assert_eq!(below, timed > untimed, "{:?} at {}", r.integrator, r.dt);
        }
    }

    #[test]
    fn a_cancelled_job_stops_and_its_thread_ends() {
        let mut case = scenes::builtin().remove(2);
        case.duration = 50.0; // 500 000 steps at 1e-4, several timed: far longer than the test
        let job = Job::spawn(case, Config::default());
        job.cancel();
        job.join();
        assert!(job.ended() && job.finished() && job.cancelled());
        job.poll();
        assert!(!job.failed(), "a cancelled study did not die");
        assert!(job.result().is_none());
    }
}
