//! The settings form (key `e`) edits the body the panels show (Tab picks it) and names it;
//! continuous values (g, drag, e, μ, a spring's k, a motor's speed) apply while the run goes
//! on, the others restart the scene.

use crate::common::{app_of, press, screen};
use crossterm::event::KeyCode;
use std::path::Path;
use tumble::tui::{App, Overlay};

const TWO: &str = r#"
title = "Two boxes fall"
[scene]
dt = 0.01
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.5, friction = 0.3 }
[[body]]
name = "left"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [-1.0, 10.0, 0.0]
[[body]]
name = "right"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 2.0
position = [1.0, 10.0, 0.0]
velocity = [0.0, 3.0, 0.0]
[[spring]]
name = "tie"
bodies = ["left", "right"]
anchors = [[-1.0, 10.0, 0.0], [1.0, 10.0, 0.0]]
stiffness = 50.0
"#;

fn app() -> App {
    app_of(TWO, "two.toml")
}

/// Selects the form's field labelled `label` and types `text` into it.
fn set_field(app: &mut App, label: &str, text: &str) {
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("the form is not open");
    };
    let at = form
        .fields
        .iter()
        .position(|f| form.label(f).0 == label)
        .unwrap_or_else(|| panic!("no field `{label}`"));
    while !matches!(&app.ui.overlay, Overlay::Settings(f) if f.selected == at) {
        press(app, KeyCode::Down);
    }
    for c in text.chars() {
        press(app, KeyCode::Char(c));
    }
}

#[test]
fn after_tab_the_form_edits_the_second_body_and_names_it() {
    let mut app = app();
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.session.selected, 1);
    press(&mut app, KeyCode::Char('e'));
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("settings of right"), "{shown}");
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("e opens the form");
    };
    let mass = form
        .fields
        .iter()
        .find(|f| form.label(f).0 == "mass M")
        .unwrap();
    assert_eq!(mass.text, "2", "the second body's mass");
    // The spring's fields are there too.
    assert!(form
        .fields
        .iter()
        .any(|f| form.label(f).0 == "spring tie stiffness k"));
    set_field(&mut app, "mass M", "5");
    set_field(&mut app, "size x", "0.4");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.ui.overlay, Overlay::None, "{:?}", app.ui.notice);
    // A mass restarts the scene: body 2 is 5 kg, body 1 is still 1 kg, and the panels still
    // show body 2.
    assert_eq!(app.session.snapshot.step, 0);
    assert_eq!(app.session.world.bodies()[1].mass, 5.0);
    assert_eq!(app.session.world.bodies()[0].mass, 1.0);
    assert_eq!(app.session.lesson.scene.bodies[0].body.mass, 1.0);
    assert_eq!(app.session.selected, 1);
    assert_eq!(app.session.snapshot.body_name, "right");
    // Its size: a solid 0.4 × 0.2 × 0.2 box of 5 kg, I_yy = M (a² + c²)/12 = 5 · 0.2/12.
    let i = app.session.world.bodies()[1].inertia_body;
    assert!(
        (i[(1, 1)] - 5.0 * (0.16 + 0.04) / 12.0).abs() < 1e-15,
        "{i}"
    );
    let original = tumble::scene::parse(TWO, Path::new("two.toml")).unwrap();
    assert_eq!(
        app.session.world.bodies()[0],
        original.scene.bodies[0].body,
        "body 1 untouched"
    );
    assert_eq!(
        app.session.world.states()[0],
        original.scene.world().states()[0]
    );
    // Its velocity was kept: P₀ = M' v₀ = 5 · 3.
    assert_eq!(app.session.snapshot.linear_momentum.y, 15.0);
    let notice = app.ui.notice.clone().unwrap();
    assert!(
        notice.contains("mass 2 → 5 kg") && notice.contains("restarted"),
        "{notice}"
    );
}

#[test]
fn a_live_g_does_not_restart_the_run() {
    let mut app = app();
    app.step_frames(100);
    let before = app.session.world.checkpoint();
    let (t, states) = (
        app.session.world.time(),
        app.session.world.states().to_vec(),
    );
    let drift_before = app.session.world.energy_balance().drift;
    press(&mut app, KeyCode::Char('e'));
    set_field(&mut app, "g y", "-1.62");
    set_field(&mut app, "spring tie stiffness k", "80");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.ui.overlay, Overlay::None, "{:?}", app.ui.notice);
    let notice = app.ui.notice.clone().unwrap();
    assert!(
        notice.contains("applied live") && notice.contains("t = 1 s"),
        "{notice}"
    );
    // Time and state go on from where they were.
    assert_eq!(app.session.world.step_count(), 100);
    assert_eq!(app.session.world.time(), t);
    assert_eq!(app.session.world.states(), &states[..]);
    assert_ne!(
        app.session.world.checkpoint(),
        before,
        "the ledger booked the change"
    );
    assert_eq!(app.session.world.effects().gravity().unwrap().y, -1.62);
    assert_eq!(app.session.world.links().springs[0].stiffness, 80.0);
    assert_eq!(
        app.session.lesson.scene.links.springs[0].stiffness, 80.0,
        "a reset keeps it"
    );
    // The drift (rk4's own, about 1e-7 J on the spring) did not jump by the new V and U
    // (about −190 J and +0.1 J): the ledger booked them into E₀.
    let drift = app.session.world.energy_balance().drift;
    assert!(
        (drift - drift_before).abs() < 1e-9,
        "drift {drift_before} → {drift}"
    );
    // From here the total momentum changes at M g = 3 kg · −1.62 m/s² (the spring's forces
    // are internal): over 50 frames, ΔP_y = −1.62 · 3 · 0.5 = −2.43 kg·m/s.
    let p = |app: &App| {
        app.session
            .world
            .states()
            .iter()
            .map(|s| s.linear_momentum.y)
            .sum::<f64>()
    };
    let p0 = p(&app);
    app.step_frames(50);
    assert!((p(&app) - p0 + 2.43).abs() < 1e-9, "ΔP {}", p(&app) - p0);
    assert_eq!(app.session.world.step_count(), 150);
    // rk4's own drift on the spring's oscillation (about 1e-7 J here), not a jump of ΔV.
    let drift = app.session.world.energy_balance().drift;
    assert!(drift.abs() < 1e-5, "drift {drift}");
    // Stepping back goes exactly to the change and no further: the frames before it ran
    // with the old g and k, which no replay under the new ones would give back.
    for _ in 0..60 {
        press(&mut app, KeyCode::Char(','));
    }
    assert_eq!(app.session.world.step_count(), 100);
    assert_eq!(app.session.world.states(), &states[..]);
    // A reset starts over with the new g.
    press(&mut app, KeyCode::Char('r'));
    assert_eq!(app.session.world.step_count(), 0);
    assert_eq!(app.session.world.effects().gravity().unwrap().y, -1.62);
}

#[test]
fn a_motors_speed_applies_live_and_w_writes_the_links_values() {
    // Lesson 44: a wheel on a hinge motor (10 rad/s, at most 2 N·m) against drag.
    let mut app = crate::common::lesson("44-a-motor");
    app.step_frames(200);
    let step = app.session.world.step_count();
    press(&mut app, KeyCode::Char('e'));
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("e opens the form");
    };
    let name = app.session.world.links().joints[0].name.clone();
    let speed = form
        .fields
        .iter()
        .find(|f| form.label(f).0 == format!("joint {name} motor speed"))
        .expect("the motor's speed field");
    assert_eq!(speed.text, "10");
    set_field(&mut app, &format!("joint {name} motor speed"), "4");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.session.world.step_count(), step, "{:?}", app.ui.notice);
    assert_eq!(
        app.session.world.links().joints[0].motor.unwrap().speed,
        4.0
    );
    // The motor now holds 4 rad/s, not 10 (the drag's 0.05 · 4 = 0.2 N·m is within its
    // 2 N·m): at about 4 rad/s² it gets there within a second.
    app.step_frames(2000);
    let w = app.session.snapshot.angular_velocity.norm();
    assert!((w - 4.0).abs() < 1e-3, "ω = {w} rad/s");
    // The bound restarts; W writes both into the file the loader reads back.
    press(&mut app, KeyCode::Char('e'));
    set_field(&mut app, &format!("joint {name} motor max torque"), "3");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.session.world.step_count(), 0, "{:?}", app.ui.notice);
    let dir = std::env::temp_dir().join(format!("tumble-settings-live-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    app.prefs.write_dir = dir.clone();
    press(&mut app, KeyCode::Char('W'));
    let written = tumble::scene::load(&app.write_path()).unwrap_or_else(|e| panic!("{e}"));
    let motor = written.scene.links.joints[0].motor.unwrap();
    assert_eq!((motor.speed, motor.max), (4.0, 3.0));
    std::fs::remove_dir_all(&dir).unwrap();
}
