//! The stopwatch, on simulated time: started, stopped and lapped by keys (or run by a page's
//! schedule), it reads the simulated seconds that passed while it ran — never wall-clock time,
//! so it reads the same at any speed, paused, stepped or jumped.
//!
//! ```text
//! reading(t) = banked + max(0, t − started)     while running (started at simulated time `started`)
//! reading(t) = banked                           stopped
//! lap k: the reading when it was pressed, rₖ;   split k = rₖ − rₖ₋₁ (r₀ = 0)
//! ```
//!
//! Stepping back below the start time reads the banked time (never less).

/// A stopwatch worked by keys.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Stopwatch {
    /// Simulated time at the last start, while running.
    started: Option<f64>,
    /// Time run before the last start, s.
    banked: f64,
    /// The readings at each lap, s, in order.
    laps: Vec<f64>,
}

impl Stopwatch {
    pub fn running(&self) -> bool {
        self.started.is_some()
    }

    /// Starts at simulated time `t` (running: nothing changes).
    pub fn start(&mut self, t: f64) {
        self.started.get_or_insert(t);
    }

    /// Stops at `t`, banking the time run (stopped: nothing changes).
    pub fn stop(&mut self, t: f64) {
        if self.started.is_some() {
            self.banked = self.reading(t);
            self.started = None;
        }
    }

    /// Start when stopped, stop when running.
    pub fn toggle(&mut self, t: f64) {
        if self.running() {
            self.stop(t);
        } else {
            self.start(t);
        }
    }

    /// Records the reading at `t` as a lap (the watch runs on).
    pub fn lap(&mut self, t: f64) {
        let r = self.reading(t);
        self.laps.push(r);
    }

    /// The simulated time run up to `t`, s.
    pub fn reading(&self, t: f64) -> f64 {
        match self.started {
            Some(s) => self.banked + (t - s).max(0.0),
            None => self.banked,
        }
    }

    /// The laps: (reading, split since the lap before), in order.
    pub fn laps(&self) -> Vec<(f64, f64)> {
        let mut before = 0.0;
        self.laps
            .iter()
            .map(|&r| {
                let split = r - before;
                before = r;
                (r, split)
            })
            .collect()
    }
}

/// A page's stopwatch (`stopwatch = { start = 0.5, stop = 2.0 }`): it runs on simulated time
/// from `start` (s; default the page's `at`) to `stop` (s; default never).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Schedule {
    pub start: f64,
    pub stop: Option<f64>,
}

impl Schedule {
    /// The reading at simulated time `t`: min(t, stop) − start, never below 0.
    pub fn reading(&self, t: f64) -> f64 {
        (self.stop.map_or(t, |s| t.min(s)) - self.start).max(0.0)
    }

    /// Whether it runs at `t`.
    pub fn running(&self, t: f64) -> bool {
        t >= self.start && self.stop.is_none_or(|s| t < s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_banks_the_time_run_between_starts_and_stops() {
        // Runs 0.5 → 1.25 (0.75 s) and 2.0 → 2.5 (0.5 s): 1.25 s.
        let mut w = Stopwatch::default();
        w.start(0.5);
        assert_eq!(w.reading(1.0), 0.5);
        w.stop(1.25);
        assert_eq!(w.reading(9.0), 0.75);
        w.toggle(2.0);
        w.lap(2.25);
        assert!(w.running());
        assert_eq!(w.reading(2.5), 1.25);
        w.lap(2.5);
        assert_eq!(w.laps(), vec![(1.0, 1.0), (1.25, 0.25)]);
        // Stepped back before the last start: the banked time.
        assert_eq!(w.reading(1.5), 0.75);
    }

    #[test]
    fn a_schedule_runs_from_start_to_stop() {
        let s = Schedule {
            start: 0.5,
            stop: Some(2.0),
        };
        assert_eq!(s.reading(0.2), 0.0);
        assert_eq!(s.reading(1.5), 1.0);
        assert_eq!(s.reading(3.0), 1.5);
        assert!(s.running(1.0) && !s.running(2.0) && !s.running(0.1));
    }
}
