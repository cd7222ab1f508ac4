//! A study of one scene on a background thread, for front ends that must stay responsive.
//!
//! [`Job::spawn`] starts the thread; [`Job::poll`] drains its messages without blocking and
//! keeps the latest progress and, at the end, the result. A job is a cheap handle (clones share
//! one thread and one result); dropping every handle detaches the thread: it finishes its scene
//! and its messages go nowhere.

use super::{study_case, Case, Config, SceneStudy};
use std::sync::mpsc::{self, Receiver, TryRecvError};
use std::sync::{Arc, Mutex};
use std::thread;

/// What the study thread reports.
#[derive(Debug)]
enum Message {
    Progress { done: usize, total: usize },
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
                })),
            };
        }
        let total = super::runs(&case, &config);
        thread::spawn(move || {
            let mut report = |done, total| {
                let _ = sender.send(Message::Progress { done, total });
            };
            let study = study_case(&case, &config, &mut report);
            let _ = sender.send(Message::Done(Box::new(study)));
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
            })),
        }
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
                Ok(Message::Progress { done, total }) => (inner.done, inner.total) = (done, total),
                Ok(Message::Done(study)) => {
                    inner.done = inner.total;
                    inner.result = Some(*study);
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    inner.lost = inner.result.is_none();
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

    /// Finished (with a result, or because the thread died).
    pub fn finished(&self) -> bool {
        self.with(|inner| inner.result.is_some() || inner.lost)
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
    }
}
