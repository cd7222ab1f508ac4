//! The measuring tools (keys `w` `o` `O` `T` `m` `M` `A` `V`, pages' `stopwatch`, `period`,
//! `ruler`, `protractor`): readings against closed forms and hand-computed poses, and the
//! screens that show them.

use crate::common::{keys, lesson, screen};
use nalgebra::Vector3;
use tumble::scene::PagePanel;
use tumble::tui::plot::PlotChoice;
use tumble::tui::App;

/// T = 4 √(L/g) K(sin(θ₀/2)), K by the arithmetic–geometric mean: K(k) = π / (2 AGM(1, √(1−k²))).
fn exact_period(length: f64, g: f64, theta0: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - (theta0 / 2.0).sin().powi(2)).sqrt());
    for _ in 0..30 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    4.0 * (length / g).sqrt() * std::f64::consts::PI / (2.0 * a)
}

#[test]
fn a_hand_on_the_stopwatch_times_the_pendulum_to_a_frame() {
    // Lesson 25 from the horizontal: T = 4 √(1/9.81) K(sin 45°) = 2.367842 s. A student starts
    // the stopwatch (w) at t = 0 and laps (o) at the first frame after each upward crossing of
    // x = 0 (1.776, 4.144, 6.511 s): each lap's split after the first is a period, read to
    // the frame it was pressed at, so within dt = 1 ms of T.
    let exact = exact_period(1.0, 9.81, std::f64::consts::FRAC_PI_2);
    assert!((exact - 2.367842).abs() < 1e-6, "{exact}");
    let mut app = lesson("25-the-pendulum");
    keys(&mut app, "w");
    let mut x = app.session.snapshot.position.x;
    for _ in 0..7000 {
        app.step_frames(1);
        let now = app.session.snapshot.position.x;
        if x < 0.0 && now >= 0.0 {
            keys(&mut app, "o");
        }
        x = now;
    }
    keys(&mut app, "w");
    let laps = app.ui.tools.stopwatch.laps();
    assert_eq!(laps.len(), 3, "{laps:?}");
    assert!((laps[0].0 - 0.75 * exact).abs() <= 1e-3, "{laps:?}");
    for &(_, split) in &laps[1..] {
        assert!((split - exact).abs() <= 1e-3, "{split} against {exact}");
    }
    // Stopped at t = 7 s: it reads the 7 s it ran, and no more as the run goes on.
    assert!((app.stopwatch_reading().0 - 7.0).abs() < 1e-9);
    app.step_frames(10);
    assert!((app.stopwatch_reading().0 - 7.0).abs() < 1e-9);
    assert!(screen(&app, 120, 40).contains("lap 3"));
}

#[test]
fn t_times_the_quantity_graphed_to_the_elliptic_integral() {
    // Lesson 25, x of the bob graphed (p), then T: from the horizontal the exact period
    // 2.367842 s (the small-angle 2π √(L/g) = 2.006067 s is 18 % short); over 7 s, three
    // upward crossings of the mid-range (x = 0 by symmetry), two periods.
    let mut app = lesson("25-the-pendulum");
    let x = app
        .session
        .plot_series
        .columns
        .iter()
        .position(|c| c.name == "bob.x")
        .unwrap();
    app.ui.plot = Some(PlotChoice { y: x, x: None });
    keys(&mut app, "T");
    assert_eq!(app.tools_shown(), vec![PagePanel::Period]);
    app.step_frames(7000);
    let (p, level) = app.period_reading();
    let p = p.unwrap();
    let exact = exact_period(1.0, 9.81, std::f64::consts::FRAC_PI_2);
    assert_eq!(p.count, 2, "{p:?}");
    assert!((p.mean - exact).abs() < 1e-5, "{p:?} against {exact}");
    assert!(p.spread < 1e-5, "{p:?}");
    assert!(level.unwrap().abs() < 1e-6, "{level:?}");
    keys(&mut app, "T");
    assert!(app.tools_shown().is_empty());
}

#[test]
fn the_period_timer_of_a_page_times_a_small_swing() {
    // Lesson 46's last page watches rod.x across 0: a rod (1 m × 5 cm × 5 cm, 1 kg) on a
    // hinge at its end, I = m(a² + b²)/12 + m d² = 0.333542 kg·m², d = 0.5 m, equivalent
    // length L = I/(m d) = 0.667083 m, from 30°: T = 4 √(L/g) K(sin 15°) = 1.666982 s
    // (small-angle 2π √(L/g) = 1.638458 s, 1.7 % short: the timer tells them apart).
    let mut app = lesson("46-measuring-a-swing");
    app.step_frames(5000);
    assert!(app.tools_shown().contains(&PagePanel::Period));
    let length = ((0.05f64.powi(2) + 1.0) / 12.0 + 0.25) / 0.5;
    let exact = exact_period(length, 9.81, 30f64.to_radians());
    let small = 2.0 * std::f64::consts::PI * (length / 9.81).sqrt();
    let (p, level) = app.period_reading();
    let p = p.unwrap();
    assert_eq!((p.count, level), (2, Some(0.0)), "{p:?}");
    assert!((p.mean - exact).abs() < 1e-6, "{p:?} against {exact}");
    assert!((p.mean - small).abs() > 0.02, "{p:?}");
}

#[test]
fn the_ruler_and_the_protractor_read_the_poses_by_hand() {
    // Lesson 46 at t = 0: the rod turned 30° about z, its centre at (0.25, −0.433013, 0),
    // 0.5 m from the hinge at the origin: ruler pivot.b → rod reads Δ = (0.25, −0.433013, 0),
    // 0.5 m; the rod's y axis (−sin 30°, cos 30°, 0) is 30° from the vertical.
    let app = lesson("46-measuring-a-swing");
    let r = app.ruler().read(app.session.world.states()).unwrap();
    assert!((r.distance - 0.5).abs() < 1e-15, "{r:?}");
    assert!((r.delta - Vector3::new(0.25, -0.4330127018922193, 0.0)).norm() < 1e-15);
    let angle = app
        .protractor()
        .unwrap()
        .degrees(app.session.world.states())
        .unwrap();
    assert!((angle - 30.0).abs() < 1e-12, "{angle}");

    // Lesson 26 (no tool on its pages): the cube turned 50° about z. A shows the protractor
    // on cube.y: 50°; A again: cube.z, along the hinge, 90° from the vertical; A again: off.
    let mut app = lesson("26-the-physical-pendulum");
    keys(&mut app, "A");
    let read = |app: &App| {
        app.protractor()
            .unwrap()
            .degrees(app.session.world.states())
            .unwrap()
    };
    assert!((read(&app) - 50.0).abs() < 1e-12, "{}", read(&app));
    keys(&mut app, "A");
    assert!((read(&app) - 90.0).abs() < 1e-12, "{}", read(&app));
    keys(&mut app, "A");
    assert!(!app.tools_shown().contains(&PagePanel::Protractor));
    // m shows the ruler: cube → edge.a (the hinge's point on the cube, at the origin at
    // t = 0): |(0.0616284, −0.7044160, 0)| = a √2/2 = 0.707107 m; M moves its second end to
    // edge.b, the hinge's point on the world: the same point, as long as the hinge holds.
    keys(&mut app, "m");
    let r = app.ruler();
    assert_eq!(
        (r.from.name.as_str(), r.to.name.as_str()),
        ("cube", "edge.a")
    );
    let d = r.read(app.session.world.states()).unwrap().distance;
    assert!((d - 0.5f64.sqrt()).abs() < 1e-12, "{d}");
    keys(&mut app, "M");
    assert_eq!(app.ruler().to.name, "edge.b");
}

#[test]
fn a_clicked_point_on_a_body_moves_with_it() {
    // Lesson 26: the ruler from the hinge's world point (edge.b) to a point clicked 0.1 m
    // right of the cube's centre (front view, depth unknown): a point of the cube, so its
    // distance to the hinge is the same after the swing, while the point itself has moved.
    let mut app = lesson("26-the-physical-pendulum");
    keys(&mut app, "mM");
    assert_eq!(app.ruler().to.name, "edge.b");
    let centre = app.session.snapshot.position;
    app.set_ruler_end(0, centre + Vector3::new(0.1, 0.0, 3.0), 0.3);
    let before = app.ruler().read(app.session.world.states()).unwrap();
    assert!(
        app.ruler().from.name.starts_with("cube+("),
        "{:?}",
        app.ruler()
    );
    assert!((before.from - (centre + Vector3::new(0.1, 0.0, 0.0))).norm() < 1e-12);
    app.step_frames(500);
    let after = app.ruler().read(app.session.world.states()).unwrap();
    assert!(
        (after.from - before.from).norm() > 0.01,
        "{before:?} {after:?}"
    );
    assert!(
        (after.distance - before.distance).abs() < 1e-9,
        "{before:?} {after:?}"
    );
    // Far from the cube: a fixed point of the world.
    app.set_ruler_end(1, Vector3::new(3.0, 1.0, 0.0), 0.3);
    assert_eq!(app.ruler().to.name, "(3, 1, 0)");
}

/// Lesson 46 at t = 5 s (its period page), with every tool shown: the stopwatch started at
/// 0.4 s and lapped at 1.0 s, the ruler (m) and the protractor (A) from the keys.
fn every_tool() -> App {
    let mut app = lesson("46-measuring-a-swing");
    app.step_frames(400);
    keys(&mut app, "w");
    app.step_frames(600);
    keys(&mut app, "o");
    app.step_frames(4000);
    keys(&mut app, "mA");
    app
}

#[test]
fn the_tools_are_shown_first_at_every_size() {
    let app = every_tool();
    insta::assert_snapshot!("tools_80x24", screen(&app, 80, 24));
    insta::assert_snapshot!("tools_120x40", screen(&app, 120, 40));
    insta::assert_snapshot!("tools_200x60", screen(&app, 200, 60));
    let mut stage = every_tool();
    keys(&mut stage, "L");
    insta::assert_snapshot!("tools_stage_120x40", screen(&stage, 120, 40));
}

#[test]
fn v_measures_against_the_other_bodys_axes_then_the_vertical_again() {
    // Lesson 27 at t = 0: both bobs unturned (identity). A: upper.y against the vertical, 0°;
    // V: against lower.x, 90°; V: lower.y, 0°; V: lower.z, 90°; V: the vertical again.
    let mut app = lesson("27-the-double-pendulum");
    let read = |app: &App| {
        app.protractor()
            .unwrap()
            .degrees(app.session.world.states())
            .unwrap()
    };
    keys(&mut app, "A");
    assert_eq!(read(&app), 0.0);
    for (expected, name) in [(90.0, "lower.x"), (0.0, "lower.y"), (90.0, "lower.z")] {
        keys(&mut app, "V");
        assert_eq!(read(&app), expected, "{name}");
        let title = app.tool_panel(PagePanel::Protractor).title;
        assert_eq!(title, format!("protractor upper.y ∠ {name}"));
    }
    keys(&mut app, "V");
    let title = app.tool_panel(PagePanel::Protractor).title;
    assert_eq!(title, "protractor upper.y ∠ the vertical");
    // O zeroes and hides the stopwatch; r starts it over.
    keys(&mut app, "w");
    app.step_frames(5);
    assert!(app.stopwatch_reading().0 > 0.0);
    keys(&mut app, "r");
    assert_eq!(app.stopwatch_reading(), (0.0, false));
    assert!(app.tools_shown().contains(&PagePanel::Stopwatch));
    keys(&mut app, "O");
    assert!(!app.tools_shown().contains(&PagePanel::Stopwatch));
}
