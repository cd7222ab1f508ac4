//! The mouse, fed through the app's update loop as messages (no terminal): a click selects
//! the body under the pointer, a drag pulls it with the hand's spring (its work booked as the
//! ledger's hand row, against the impulse–energy theorem), the wheel zooms about the pointer,
//! a click on a panel row graphs that quantity.

use crate::common::screen;
use nalgebra::Vector3;
use tumble::physics::derive::derive;
use tumble::tui::keys::Message;
use tumble::tui::mouse::{Action, Mouse};
use tumble::tui::{App, View};

fn app_of_(source: &str) -> App {
    crate::common::app_of(source, "mouse.toml")
}

fn mouse(app: &mut App, action: Action, (col, row): (u16, u16)) {
    app.update(Message::Mouse(Mouse { action, col, row }));
}

/// The mouse at the cell where a world point is drawn.
fn at(app: &mut App, action: Action, p: Vector3<f64>) {
    let cell = cell_of(app, p);
    mouse(app, action, cell);
}

/// The terminal cell a world point is drawn in.
fn cell_of(app: &App, p: Vector3<f64>) -> (u16, u16) {
    app.viewport()
        .and_then(|v| v.terminal_cell(&p))
        .unwrap_or_else(|| panic!("{p} is not drawn"))
}

/// Two 0.4 m cubes 2 m apart in empty space.
const TWO_CUBES: &str = r#"
title = "two cubes"
[scene]
dt = 0.01
integrator = "rk4"
contact = { response = "impulse", restitution = 0.5, friction = 0.3 }
[[body]]
name = "left"
shape = "box"
size = [0.4, 0.4, 0.4]
mass = 1.0
position = [-1.0, 0.0, 0.0]
[[body]]
name = "right"
shape = "box"
size = [0.4, 0.4, 0.4]
mass = 1.0
position = [1.0, 0.0, 0.0]
"#;

/// A 2 kg cube resting on the ground.
const RESTING: &str = r#"
title = "a cube on the ground"
[scene]
dt = 0.01
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.0, friction = 0.5 }
[body]
name = "cube"
shape = "box"
size = [0.4, 0.4, 0.4]
mass = 2.0
position = [0.0, 0.2, 0.0]
[[obstacle]]
type = "ground"
height = 0.0
"#;

/// A box in empty space, no gravity: its energy is all kinetic, changed only by the hand.
const FREE_BOX: &str = r#"
title = "a free box"
[scene]
dt = 0.01
integrator = "rk4"
[body]
name = "box"
shape = "box"
size = [0.6, 0.3, 0.2]
mass = 2.0
position = [0.0, 0.0, 0.0]
"#;

#[test]
fn a_click_selects_the_body_under_the_pointer_and_not_empty_space() {
    let mut app = app_of_(TWO_CUBES);
    screen(&app, 120, 40);
    assert_eq!(app.session.selected, 0);
    // A click on `right`'s barycenter, then near its corner (0.15 m from its centre along
    // both axes): `right`, held by the hand where clicked.
    at(&mut app, Action::Press, Vector3::new(1.0, 0.0, 0.0));
    assert_eq!(app.session.selected, 1);
    assert_eq!(app.session.snapshot.body_name, "right");
    assert_eq!(app.session.world.hand().map(|h| h.body), Some(1));
    mouse(&mut app, Action::Release, (0, 0));
    assert!(app.session.world.hand().is_none(), "released: let go");
    at(&mut app, Action::Press, Vector3::new(-0.85, 0.15, 0.0));
    assert_eq!(app.session.snapshot.body_name, "left");
    mouse(&mut app, Action::Release, (0, 0));
    // Empty space between them (0.6 m from either cube's side): nothing selected, nothing held.
    at(&mut app, Action::Press, Vector3::new(0.0, 0.0, 0.0));
    assert_eq!(app.session.selected, 0, "still left");
    assert!(app.session.world.hand().is_none());
    // A click never moved anything: the hand did no work, the ledger has no hand row.
    assert_eq!(app.session.world.energy_balance().hand, None);
}

#[test]
fn dragging_pulls_a_resting_body_towards_the_pointer() {
    let mut app = app_of_(RESTING);
    screen(&app, 120, 40);
    let start = app.session.world.states()[0].position;
    at(&mut app, Action::Press, start);
    // Drag to 0.5 m right and 0.4 m up of where it rests.
    let cell = cell_of(&app, start + Vector3::new(0.5, 0.4, 0.0));
    mouse(&mut app, Action::Drag, cell);
    let target = app.session.world.hand().unwrap().target;
    assert!(
        (target - (start + Vector3::new(0.5, 0.4, 0.0))).norm() < 0.05,
        "{target}"
    );
    // 2 s: the critically damped spring (ω_h = 20 rad/s) has long settled; gravity sags the
    // held barycenter below the pointer by M g / k = g / ω_h² = 9.81 / 400 = 0.0245 m (the
    // grab is at the barycenter: m_eff = M).
    app.step_frames(200);
    let end = app.session.world.states()[0].position;
    let sag = 9.81 / 400.0;
    assert!(
        (end - (target - Vector3::new(0.0, sag, 0.0))).norm() < 0.01,
        "held at {end}, pointer at {target}"
    );
    // The hand lifted it: its work is at least the potential energy gained, M g Δy.
    let balance = app.session.world.energy_balance();
    let lifted = 2.0 * 9.81 * (end.y - start.y);
    let hand = balance.hand.expect("a hand row");
    assert!(hand >= lifted, "hand {hand} J < M g Δy = {lifted} J");
    // And the energy panel shows it beside the contacts.
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("  hand"), "{shown}");
    assert!(shown.contains("hand") && shown.contains(" N"), "{shown}");
    mouse(&mut app, Action::Release, cell);
    assert!(app.session.world.hand().is_none());
    assert_eq!(
        app.session.world.energy_balance().hand,
        Some(hand),
        "the work stays booked"
    );
}

#[test]
fn the_hands_work_is_the_ledgers_hand_row_and_the_balance_closes() {
    // The box held off-centre (it turns as well as moves), pulled 0.5 m for 1 s, then let go
    // for 0.5 s. Independent truth, frame by frame: the impulse–energy theorem. A kick J at a
    // point whose velocity goes from u⁻ to u⁺ does work J·(u⁻ + u⁺)/2, with
    //   u = v + ω × r,  v⁺ = v + J/M,  ω⁺ = I⁻¹_world (L + r × J).
    let mut app = app_of_(FREE_BOX);
    screen(&app, 120, 40);
    let grab = Vector3::new(0.25, 0.1, 0.0);
    at(&mut app, Action::Press, grab);
    at(&mut app, Action::Drag, Vector3::new(0.5, 0.4, 0.0));
    let body = app.session.world.bodies()[0].clone();
    let dt = app.session.world.dt();
    let mut expected = 0.0;
    let mut scale = 0.0_f64;
    for frame in 0..150 {
        if frame == 100 {
            mouse(&mut app, Action::Release, (0, 0));
        }
        if let Some(hand) = app.session.world.hand().copied() {
            let s = app.session.world.states()[0];
            let k = derive(&body, &s);
            let r = k.rotation * hand.point_body;
            let j = hand.pull(&body, &s).force * dt;
            let before = k.velocity + k.angular_velocity.cross(&r);
            let omega = k.inv_inertia_world * (s.angular_momentum + r.cross(&j));
            let after = k.velocity + j / body.mass + omega.cross(&r);
            expected += j.dot(&(before + after)) / 2.0;
            scale = scale.max(j.dot(&before).abs());
        }
        app.step_frames(1);
    }
    let balance = app.session.world.energy_balance();
    let booked = balance.hand.unwrap();
    assert!(booked > 0.1, "the hand set it moving: {booked} J");
    // The same sum two ways (the ledger: K after − K before): round-off only.
    assert!(
        (booked - expected).abs() <= 1e-9 * scale.max(booked),
        "ledger {booked} J, impulse–energy theorem {expected} J"
    );
    // No gravity, no drag, no contacts: E − E₀ is the hand's work plus rk4's own drift on the
    // free spin, O((ω dt)⁵) relative per step (ω ≈ 3 rad/s: ~1e-9 over 150 steps).
    assert!(
        (balance.change - booked).abs() <= 1e-6 * booked,
        "E − E₀ = {} J, hand {booked} J",
        balance.change
    );
    assert!(
        balance.drift.abs() <= 1e-6 * booked,
        "drift {}",
        balance.drift
    );
}

#[test]
fn the_wheel_zooms_about_the_pointer_and_z_zooms_about_the_centre() {
    let mut app = app_of_(TWO_CUBES);
    screen(&app, 120, 40);
    let before = app.viewport().unwrap();
    let at = cell_of(&app, Vector3::new(1.0, 0.1, 0.0));
    let under = before.world_at(at.0, at.1).unwrap();
    mouse(&mut app, Action::WheelUp, at);
    assert_eq!(app.ui.zoom.steps, 1);
    screen(&app, 120, 40);
    let after = app.viewport().unwrap();
    assert!((after.mapping.scale - before.mapping.scale / 1.25).abs() < 1e-12);
    // The point under the pointer stays under it (to the cell's centre).
    assert!((after.world_at(at.0, at.1).unwrap() - under).norm() < 1e-9);
    mouse(&mut app, Action::WheelDown, at);
    screen(&app, 120, 40);
    assert_eq!(app.ui.zoom.steps, 0);
    assert_eq!(app.viewport().unwrap(), before, "back to the fitted view");
    // Keys: z in, Z out, about the centre.
    app.update(Message::ZoomIn);
    app.update(Message::ZoomIn);
    screen(&app, 120, 40);
    let zoomed = app.viewport().unwrap();
    assert!((zoomed.mapping.scale - before.mapping.scale / 1.5625).abs() < 1e-12);
    assert!(
        (zoomed.mapping.centre().0 - before.mapping.centre().0).abs() < 1e-12
            && (zoomed.mapping.centre().1 - before.mapping.centre().1).abs() < 1e-12
    );
    app.update(Message::ZoomOut);
    app.update(Message::ZoomOut);
    assert_eq!(app.ui.zoom.steps, 0);
}

/// The column of the `n`-th number (0-based) right of column `from` in a line's characters.
fn number_col(chars: &[char], from: usize, n: usize) -> u16 {
    let mut found = 0;
    let mut col = from;
    while col < chars.len() {
        if chars[col] == ' ' {
            col += 1;
            continue;
        }
        let start = col;
        while col < chars.len() && chars[col] != ' ' {
            col += 1;
        }
        let token: String = chars[start..col].iter().collect();
        if token.parse::<f64>().is_ok() {
            if found == n {
                return start as u16;
            }
            found += 1;
        }
    }
    panic!("no number {n} in {}", chars.iter().collect::<String>());
}

/// The terminal cell of the `n`-th number (0-based) of the panel row whose label is `label`,
/// found in the drawn screen (the panels column is right of the drawing's border).
fn number_cell(shown: &str, panel_title: &str, label: &str, n: usize) -> (u16, u16) {
    let lines: Vec<&str> = shown.lines().collect();
    let title = lines
        .iter()
        .position(|l| l.contains(panel_title))
        .unwrap_or_else(|| panic!("no {panel_title}:\n{shown}"));
    for (y, line) in lines.iter().enumerate().skip(title + 1) {
        let chars: Vec<char> = line.chars().collect();
        let text: String = chars.iter().collect();
        if let Some(at) = text.find(&format!("│ {label} ")) {
            let col = text[..at].chars().count() + 2 + label.chars().count();
            return (number_col(&chars, col, n), y as u16);
        }
    }
    panic!("no row {label} under {panel_title}:\n{shown}");
}

#[test]
fn a_click_on_a_panel_row_graphs_that_quantity() {
    let mut app = app_of_(FREE_BOX);
    let shown = screen(&app, 120, 40);
    // ω_z of the angular-velocity table: box.wz against time, as the picker (p) sets it.
    mouse(
        &mut app,
        Action::Press,
        number_cell(&shown, "angular velocity", "ω", 2),
    );
    assert_eq!(app.ui.view, View::Plot);
    let plot = app.ui.plot.unwrap();
    assert_eq!(app.session.plot_series.columns[plot.y].name, "box.wz");
    assert_eq!(plot.x, None);
    // Back (Esc), then x's y component and the energy row's K.
    app.update(Message::Back);
    let shown = screen(&app, 120, 40);
    mouse(
        &mut app,
        Action::Press,
        number_cell(&shown, "state", "x", 1),
    );
    assert_eq!(
        app.session.plot_series.columns[app.ui.plot.unwrap().y].name,
        "box.y"
    );
    app.update(Message::Back);
    let shown = screen(&app, 120, 40);
    mouse(
        &mut app,
        Action::Press,
        number_cell(&shown, "energy", "K, V, E", 0),
    );
    assert_eq!(
        app.session.plot_series.columns[app.ui.plot.unwrap().y].name,
        "box.kinetic"
    );
    // A row the plot list lacks (ωbody): no graph, and a notice saying so.
    app.update(Message::Back);
    let shown = screen(&app, 120, 40);
    mouse(
        &mut app,
        Action::Press,
        number_cell(&shown, "angular velocity", "ωbody", 0),
    );
    assert_eq!(app.ui.view, View::Loop);
    assert!(app.ui.notice.as_deref().unwrap_or("").contains("no graph"));
}

#[test]
fn in_the_stage_layout_a_click_on_an_essential_row_graphs_it() {
    // L: the essentials box beside the drawing; its ω row's z number is box.wz, its v row's
    // x number box.vx.
    let mut app = app_of_(FREE_BOX);
    app.update(Message::NextLayout);
    let shown = screen(&app, 120, 40);
    let essentials = |shown: &str, label: &str, n: usize| {
        let (y, line) = shown
            .lines()
            .enumerate()
            .find(|(_, l)| {
                l.contains(&format!("│ {label} ")) && l.contains("rad/s") == (label == "ω")
            })
            .unwrap_or_else(|| panic!("no {label}:\n{shown}"));
        let at = line.rfind(&format!("│ {label} ")).unwrap();
        let col = line[..at].chars().count() + 2 + label.chars().count();
        let chars: Vec<char> = line.chars().collect();
        (number_col(&chars, col, n), y as u16)
    };
    mouse(&mut app, Action::Press, essentials(&shown, "ω", 2));
    assert_eq!(app.ui.view, View::Plot, "{shown}");
    assert_eq!(
        app.session.plot_series.columns[app.ui.plot.unwrap().y].name,
        "box.wz"
    );
    app.update(Message::Back);
    let shown = screen(&app, 120, 40);
    mouse(&mut app, Action::Press, essentials(&shown, "v", 0));
    assert_eq!(
        app.session.plot_series.columns[app.ui.plot.unwrap().y].name,
        "box.vx"
    );
}

#[test]
fn a_drag_in_progress_at_120x40() {
    // The resting cube held at its top right corner and pulled up and right for 0.3 s: the
    // hand's line from the grabbed point (o) to the pointer (x), its pull in newtons, the
    // legend's hand entry and the energy panel's hand row.
    let mut app = app_of_(RESTING);
    screen(&app, 120, 40);
    at(&mut app, Action::Press, Vector3::new(0.15, 0.35, 0.0));
    at(&mut app, Action::Drag, Vector3::new(0.45, 0.7, 0.0));
    app.step_frames(30);
    // The label is the pull's size, k (p* − p) − c u at this state: pointer (0.437, 0.710),
    // grabbed corner (0.427, 0.658), k = 0.744 kg × 400 s⁻² = 297.7 N/m (1/m = 1/2 +
    // 0.045/0.0533), c = 29.8 N·s/m.
    let hand = *app.session.world.hand().unwrap();
    let pull = app.session.world.hand_pull().unwrap();
    let s = app.session.world.states()[0];
    let k = derive(&app.session.world.bodies()[0], &s);
    let r = pull.at - s.position;
    let u = k.velocity + k.angular_velocity.cross(&r);
    let force = hand.stiffness * (hand.target - pull.at) - hand.damping * u;
    assert!((force.norm() - 26.249).abs() < 1e-3, "{}", force.norm());
    insta::assert_snapshot!("drag_120x40", screen(&app, 120, 40));
}

#[test]
fn stepping_back_over_a_drag_restores_every_frame_exactly() {
    // A cube over a trampoline (a cloth: the history keeps a whole checkpoint only every K
    // frames and rebuilds the others by stepping again). A ring with room for twenty
    // checkpoints in 100 frames: K = 6 (⌈100/6⌉ + ⌈√6⌉ = 20). The hand pulls from frame 5 to
    // frame 15 (eleven keyframes kept whole); ← back to
    // t = 0 must give every frame's checkpoint bit for bit — replay cannot know the pointer,
    // so the frames it pulled, and the first after it let go, are kept whole.
    let mut app = crate::common::lesson(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/tui-cloth-trampoline.toml"
    ));
    let one = {
        let mut world = app.session.world.clone();
        world.step();
        world.checkpoint().heap_bytes()
    };
    app.session.history =
        tumble::tui::history::History::with_budget(100, 100 * 32 + 20 * (one + 1024));
    let mut expected = vec![app.session.world.checkpoint()];
    let step = |app: &mut App, frames: usize, expected: &mut Vec<_>| {
        for _ in 0..frames {
            app.step_frames(1);
            expected.push(app.session.world.checkpoint());
        }
    };
    step(&mut app, 5, &mut expected);
    screen(&app, 120, 40);
    let cube = app.session.world.states()[0].position;
    at(&mut app, Action::Press, cube);
    at(&mut app, Action::Drag, cube + Vector3::new(0.2, 0.1, 0.0));
    step(&mut app, 10, &mut expected);
    mouse(&mut app, Action::Release, (0, 0));
    step(&mut app, 10, &mut expected);
    assert_eq!(app.session.history.interval(), 6);
    assert!(app.session.world.energy_balance().hand.unwrap() != 0.0);
    for frame in (0..25).rev() {
        app.step_back();
        assert_eq!(app.session.world.step_count(), frame as u64);
        assert!(
            app.session.world.checkpoint() == expected[frame],
            "frame {frame}"
        );
    }
}
