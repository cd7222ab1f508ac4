//! Issue 21's findings in the app, each against what a teacher saw: the view growing by
//! doubling mid-flight, the arrows covering small bodies.

use std::path::Path;
use tumble::tui::export;
use tumble::tui::viewport::shown_points;
use tumble::tui::{App, Options};

fn lesson_app(name: &str) -> App {
    App::new(
        tumble::lessons::load(Path::new(name)).unwrap_or_else(|e| panic!("{e}")),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    )
}

fn screen(app: &App, width: u16, height: u16) -> String {
    let buf = export::render(app, width, height);
    (0..buf.area.height)
        .map(|y| {
            let row: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
            row.trim_end().to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_view_grows_a_little_at_a_time_and_keeps_every_body_in_it() {
    // Lesson 14's three cubes fly apart, lesson 20's ball rolls away: the region the view
    // keeps grows, but never by more than an eighth of itself past the point that crossed
    // it (by doubling it jumped ×2 at once), and every body stays inside at every frame.
    for (name, frames) in [("14-head-on", 2000), ("20-bowling-ball", 1500)] {
        let mut app = lesson_app(name);
        let mut worst: f64 = 1.0;
        for _ in 0..frames {
            let before = app.region;
            app.step_frames(1);
            let after = app.region;
            for i in 0..3 {
                let (e0, e1) = (before.max[i] - before.min[i], after.max[i] - after.min[i]);
                worst = worst.max(e1 / e0);
            }
            for p in shown_points(&app.world) {
                for i in 0..3 {
                    assert!(
                        p[i] >= app.region.min[i] && p[i] <= app.region.max[i],
                        "{name} t = {}: {p:?} outside {:?}",
                        app.world.time(),
                        app.region
                    );
                }
            }
        }
        assert!(
            worst < 1.25,
            "{name}: the view grew ×{worst} in one frame (doubling was ×2)"
        );
    }
}

#[test]
fn arrows_are_left_off_a_body_too_small_for_them_and_the_legend_says_so() {
    // Lesson 14's 0.2 m cubes in a 3 m view: about 1.6 columns of radius at 120×40, under
    // the 3 the arrows need; lesson 2's mass points fill the view and keep them.
    let small = screen(&lesson_app("14-head-on"), 120, 40);
    assert!(small.contains("ω L hidden: body small"), "{small}");
    assert!(!small.contains("ang. vel."), "{small}");
    assert!(!small.contains("->x") && !small.contains("<-x"), "{small}");
    let large = screen(&lesson_app("02-rigid-body-from-points"), 120, 40);
    assert!(large.contains("ω ang. vel."), "{large}");
    assert!(!large.contains("hidden: body small"), "{large}");
}
