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
            let before = app.ui.region;
            app.step_frames(1);
            let after = app.ui.region;
            for i in 0..3 {
                let (e0, e1) = (before.max[i] - before.min[i], after.max[i] - after.min[i]);
                worst = worst.max(e1 / e0);
            }
            for p in shown_points(&app.session.snapshot) {
                for i in 0..3 {
                    assert!(
                        p[i] >= app.ui.region.min[i] && p[i] <= app.ui.region.max[i],
                        "{name} t = {}: {p:?} outside {:?}",
                        app.session.world.time(),
                        app.ui.region
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
    // Lesson 14 at t = 0 at 120×40: the cubes fill the view (0.2 m per 8 columns), the arrows
    // are drawn. At t = 2 s the cubes are apart and at 80×24 a cube's radius is about one
    // column, under the 3 the arrows need: they are left off (before, the axes, ω, L and
    // their labels covered the cube).
    let mut app = lesson_app("14-head-on");
    let large = screen(&app, 120, 40);
    assert!(large.contains("ω ang. vel."), "{large}");
    assert!(large.contains("->x"), "{large}");
    assert!(!large.contains("hidden: body small"), "{large}");
    app.step_frames(2000);
    let small = screen(&app, 80, 24);
    assert!(!small.contains("ang. vel."), "{small}");
    assert!(!small.contains("->x") && !small.contains("<-x"), "{small}");
    // The pendulum's 0.1 m bob at the bottom of its swing (frame 592) in its 2 m view at
    // 120×40: the legend, which has room there, says why they are missing.
    let mut pendulum = lesson_app("25-the-pendulum");
    pendulum.step_frames(592);
    let shown = screen(&pendulum, 120, 40);
    assert!(shown.contains("ω L hidden: body small"), "{shown}");
    assert!(
        !shown.contains("ang. vel.") && !shown.contains("->x"),
        "{shown}"
    );
}

#[test]
fn a_stopped_bodys_energy_below_the_panels_round_off_prints_as_zero() {
    // Lesson 14 after the e = 1 collisions (t = 2 s): `left` and `middle` have handed on
    // their momentum; what they keep, K ≈ 5e-21 J, is round-off beside the 0.5 J the panel
    // shows for `right` (64 ε of it is 7e-15 J), so it prints as 0, as the page says.
    let mut app = lesson_app("14-head-on");
    app.step_frames(2000);
    let s = &app.session.snapshot;
    assert!(s.bodies[0].energy.kinetic.abs() < 1e-18 && s.bodies[0].energy.kinetic != 0.0);
    let panel = tumble::tables::body_energy_panel(s);
    let cells = |row: usize| -> Vec<String> {
        panel.rows[row]
            .cells
            .iter()
            .map(|c| c.trim().to_string())
            .collect()
    };
    assert_eq!(cells(0), ["0.000000", "0.000000", "0.000000"]);
    assert_eq!(cells(1), ["0.000000", "0.000000", "0.000000"]);
    assert_eq!(cells(2), ["0.500000", "0.000000", "0.500000"]);
}

#[test]
fn at_a_contact_page_the_inertia_tensor_yields_before_the_energy() {
    // Lesson 8 at 120×40, paused at its page 2 (the graze, t = 0.317 s): the contact adds the
    // Fc and τc rows, and not every panel fits. The cube's inertia tensor is constant (a cube
    // is isotropic): it yields first, the energy panel stays (it was left out before).
    let mut app = lesson_app("08-climbing-bug");
    app.ui.running = true;
    app.step_frames(1000);
    assert_eq!(app.session.world.step_count(), 317, "paused at page 2");
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("K, V, E"), "{shown}");
    assert!(shown.contains("Fc") && shown.contains("τc"), "{shown}");
    assert!(
        shown.contains("not shown (enlarge): inertia tensor"),
        "{shown}"
    );
}
