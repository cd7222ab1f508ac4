//! Where a run pauses by itself: at each page's time `at` (after t = 0) and at the scene's
//! `duration`. A stop at time s is the first step whose time reaches s, `⌈s/dt⌉` (less a
//! round-off margin, so a time that is a whole number of steps stops exactly there).

use super::settings_form::tidy;
use crate::scene::Lesson;

/// The step at which a run reaches time `t`.
pub fn step_at(t: f64, dt: f64) -> u64 {
    (t / dt - 1e-9).ceil().max(0.0) as u64
}

/// Where a run paused by itself.
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    /// A few words for the header, e.g. `end of scene`, `page 2/3`.
    pub label: String,
    /// The status line's notice: where, and what continues.
    pub notice: String,
}

/// Why a run pauses after reaching `step` (None: it runs on).
pub fn stop_at(lesson: &Lesson, dt: f64, step: u64) -> Option<Stop> {
    if step == 0 {
        return None;
    }
    if let Some(duration) = lesson.scene.duration {
        if step == step_at(duration, dt) {
            return Some(Stop {
                label: "end of scene".into(),
                notice: format!(
                    "end of the scene (t = {} s): Enter runs on, r restarts",
                    tidy(duration)
                ),
            });
        }
    }
    let count = lesson.pages.len();
    lesson
        .pages
        .iter()
        .enumerate()
        .find(|(_, page)| page.at > 0.0 && step == step_at(page.at, dt))
        .map(|(i, page)| Stop {
            label: format!("page {}/{count}", i + 1),
            notice: format!(
                "page {}/{count} “{}” (t = {} s): Enter continues",
                i + 1,
                page.title,
                tidy(page.at)
            ),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_time_on_the_grid_stops_on_its_own_step() {
        // 1.5 / 0.01 = 150.00000000000003 in floating point: the stop is step 150, not 151.
        assert_eq!(step_at(1.5, 0.01), 150);
        // 0.105 s with dt = 0.01: the first step at or after it is step 11 (t = 0.11 s).
        assert_eq!(step_at(0.105, 0.01), 11);
        assert_eq!(step_at(0.0, 0.01), 0);
    }
}
