//! Cancelling a study from another thread.
//!
//! A study thread runs its work inside [`run`] with a shared flag and a shared step counter;
//! the study's stepping loops call [`check`] with the steps they are about to make (every step,
//! or every timed chunk of 1000 steps): it adds them to the counter (a front end's estimate of
//! the time left reads it) and, once the flag is set, unwinds the thread's stack out of [`run`]
//! with no panic message. A study run outside [`run`] (the command line) never stops: [`check`]
//! then does nothing.

use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;

thread_local! {
    static FLAG: RefCell<Option<Control>> = const { RefCell::new(None) };
}

/// What a study thread shares with its front end.
#[derive(Debug, Clone, Default)]
pub struct Control {
    /// Set to stop the study.
    pub cancel: Arc<AtomicBool>,
    /// Steps made (or about to be) so far.
    pub steps: Arc<AtomicU64>,
}

/// The payload a cancelled study unwinds with.
struct Cancelled;

/// Runs `work` on this thread, stopping it at its next [`check`] once `control.cancel` is
/// set: `None` if it was cancelled. Any other panic goes on unwinding.
pub fn run<T>(control: Control, work: impl FnOnce() -> T) -> Option<T> {
    let previous = FLAG.with(|f| f.replace(Some(control)));
    let outcome = panic::catch_unwind(AssertUnwindSafe(work));
    FLAG.with(|f| *f.borrow_mut() = previous);
    match outcome {
        Ok(value) => Some(value),
        Err(payload) if payload.is::<Cancelled>() => None,
        Err(payload) => panic::resume_unwind(payload),
    }
}

/// Counts `steps` about to be made, and stops the study running on this thread if it was
/// cancelled (see [`run`]).
pub fn check(steps: u64) {
    let cancelled = FLAG.with(|f| {
        f.borrow().as_ref().is_some_and(|control| {
            control.steps.fetch_add(steps, Ordering::Relaxed);
            control.cancel.load(Ordering::Relaxed)
        })
    });
    if cancelled {
        // `resume_unwind` does not call the panic hook: nothing is printed.
        panic::resume_unwind(Box::new(Cancelled));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_flag_stops_the_work_at_its_next_check_and_other_work_runs_on() {
        let control = Control::default();
        let mut checks = 0;
        let stopped = run(control.clone(), || loop {
            check(10);
            checks += 1;
            if checks == 3 {
                control.cancel.store(true, Ordering::Relaxed);
            }
        });
        assert_eq!(stopped, None::<()>);
        assert_eq!(checks, 3, "stopped at the first check after the flag");
        assert_eq!(
            control.steps.load(Ordering::Relaxed),
            40,
            "4 checks of 10 steps"
        );
        assert_eq!(run(Control::default(), || 7), Some(7));
        check(1); // outside `run`: never stops
    }
}
