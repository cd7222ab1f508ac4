//! A study of one scene on a background thread, for front ends that must stay responsive.
//!
//! [`Job::spawn`] starts the thread; [`Job::poll`] drains its messages without blocking and
//! keeps the latest progress, an estimate of the time left and, at the end, the result. The
//! runs are made the cheapest first ([`super::sweep`]). A job is a cheap handle (clones share
//! one thread and one result). [`Job::cancel`] stops the thread at its next step (the study's
//! loops check the flag, [`super::cancel`]); dropping every handle cancels it too.
//!
//! ```text
//! time left ≈ (wall time since the runs started) / (steps made by the finished runs)
//!             × (steps the remaining runs will make)      ([`super::run_steps`])
//! ```

use super::{cancel, study_case, Case, Config, SceneStudy};
use std::sync::atomic::{AtomicBool, Ordering};
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
        at: Instant,
    },
    Done(Box<SceneStudy>),
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
    /// Set to stop the thread ([`Job::cancel`]).
    cancel: Arc<AtomicBool>,
    /// The study thread, until joined ([`Job::join`]).
    thread: Option<JoinHandle<()>>,
    /// Steps each run makes, in the order they are made ([`super::run_steps`]).
    steps: Vec<u64>,
    /// When the first run started (the reference was made) and when the last one finished.
    started: Option<Instant>,
    latest: Option<Instant>,
}

impl Drop for Inner {
    /// The last handle is gone: nobody will read the result, so stop the work.
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
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
                    cancel: Arc::new(AtomicBool::new(true)),
                    thread: None,
                    steps: Vec::new(),
                    started: None,
                    latest: None,
                })),
            };
        }
        let total = super::runs(&case, &config);
        let steps = super::run_steps(&case, &config);
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = cancel.clone();
        let thread = thread::spawn(move || {
            let mut report = |done, total| {
                let at = Instant::now();
                let _ = sender.send(Message::Progress { done, total, at });
            };
            if let Some(study) = cancel::run(flag, || study_case(&case, &config, &mut report)) {
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
                cancel,
                thread: Some(thread),
                steps,
                // Until the study says its reference is made (a cloth case does not).
                started: Some(Instant::now()),
                latest: None,
            })),
        }
    }

    /// Stops the study at its next step (the thread then ends; see [`Job::join`]).
    pub fn cancel(&self) {
        self.with(|inner| inner.cancel.store(true, Ordering::Relaxed));
    }

    /// The study was cancelled.
    pub fn cancelled(&self) -> bool {
        self.with(|inner| inner.cancel.load(Ordering::Relaxed))
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

    /// The estimated wall time left, once a run has finished ([`estimate`]).
    pub fn time_left(&self) -> Option<Duration> {
        self.with(|inner| {
            if inner.result.is_some() || inner.cancel.load(Ordering::Relaxed) {
                return None;
            }
            let (started, latest) = (inner.started?, inner.latest?);
            estimate(
                &inner.steps,
                inner.done,
                latest.duration_since(started),
                latest.elapsed(),
            )
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
                Ok(Message::Progress { done, total, at }) => {
                    if done == 0 {
                        inner.started = Some(at);
                    } else {
                        inner.latest = Some(at);
                    }
                    (inner.done, inner.total) = (done, total);
                }
                Ok(Message::Done(study)) => {
                    inner.done = inner.total;
                    inner.result = Some(*study);
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    inner.lost = inner.result.is_none() && !inner.cancel.load(Ordering::Relaxed);
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
            inner.result.is_some() || inner.lost || inner.cancel.load(Ordering::Relaxed)
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

/// The wall time left when the first `done` runs (of the runs making `steps` steps each)
/// took `spent`, and `since` has passed since the last one finished: the cost per step of the
/// finished runs times the steps of the others, less `since`; `None` before a run finished.
pub fn estimate(steps: &[u64], done: usize, spent: Duration, since: Duration) -> Option<Duration> {
    let made: u64 = steps.iter().take(done).sum();
    if done == 0 || made == 0 {
        return None;
    }
    let left: u64 = steps.iter().skip(done).sum();
    let per_step = spent.as_secs_f64() / made as f64;
    Some(Duration::from_secs_f64(
        (per_step * left as f64 - since.as_secs_f64()).max(0.0),
    ))
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
    fn the_time_left_scales_the_finished_runs_cost_per_step_by_the_steps_left() {
        let steps = [10, 90, 900, 9000];
        let s = Duration::from_secs_f64;
        assert_eq!(estimate(&steps, 0, s(1.0), s(0.0)), None, "no run finished");
        // 100 steps in 2 s: 20 ms a step; 9900 steps left: 198 s, less the 8 s since.
        let left = estimate(&steps, 2, s(2.0), s(8.0)).unwrap();
        assert!((left.as_secs_f64() - 190.0).abs() < 1e-9, "{left:?}");
        assert_eq!(estimate(&steps, 4, s(2.0), s(0.0)), Some(Duration::ZERO));
        assert_eq!(
            estimate(&steps, 2, s(0.1), s(20.0)),
            Some(Duration::ZERO),
            "overdue"
        );
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
        assert_eq!(crate::study::run_steps(&case, &config), [10, 10, 100, 100]);
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
