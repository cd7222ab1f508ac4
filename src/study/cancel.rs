//! Cancelling a study from another thread.
//!
//! A study thread runs its work inside [`run`] with a shared flag; the study's stepping loops
//! call [`check`] (every step, or every timed chunk of 1000 steps), which, once the flag is set,
//! unwinds the thread's stack out of [`run`] with no panic message. A study run outside [`run`]
//! (the command line) never stops: [`check`] then does nothing.

use std::cell::RefCell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

thread_local! {
    static FLAG: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

/// The payload a cancelled study unwinds with.
struct Cancelled;

/// Runs `work` on this thread, stopping it at its next [`check`] once `flag` is set:
/// `None` if it was cancelled. Any other panic goes on unwinding.
pub fn run<T>(flag: Arc<AtomicBool>, work: impl FnOnce() -> T) -> Option<T> {
    let previous = FLAG.with(|f| f.replace(Some(flag)));
    let outcome = panic::catch_unwind(AssertUnwindSafe(work));
    FLAG.with(|f| *f.borrow_mut() = previous);
    match outcome {
        Ok(value) => Some(value),
        Err(payload) if payload.is::<Cancelled>() => None,
        Err(payload) => panic::resume_unwind(payload),
    }
}

/// Stops the study running on this thread if it was cancelled (see [`run`]).
pub fn check() {
    let cancelled = FLAG.with(|f| {
        f.borrow()
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::Relaxed))
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
        let flag = Arc::new(AtomicBool::new(false));
        let mut checks = 0;
        let stopped = run(flag.clone(), || loop {
            check();
            checks += 1;
            if checks == 3 {
                flag.store(true, Ordering::Relaxed);
            }
        });
        assert_eq!(stopped, None::<()>);
        assert_eq!(checks, 3, "stopped at the first check after the flag");
        assert_eq!(run(Arc::new(AtomicBool::new(false)), || 7), Some(7));
        check(); // outside `run`: never stops
    }
}
