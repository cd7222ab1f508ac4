//! The force arrows (key `F`, `shot --forces`): each force where it acts, as the physics
//! wrote it, against closed forms.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use nalgebra::Vector3;
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::Path;
use tumble::physics::force_arrows::{force_arrows, ForceKind};
use tumble::tui::{App, Options};

fn app_of(lesson: tumble::scene::Lesson) -> App {
    App::new(
        lesson,
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    )
}

fn fixture(name: &str) -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    app_of(tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

fn screen(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|f| f.render_widget(app, f.area())).unwrap();
    let buf = terminal.backend().buffer();
    (0..buf.area.height)
        .map(|y| {
            let row: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
            row.trim_end().to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn a_stretched_spring_pulls_k_times_its_stretch_and_gravity_m_g() {
    // tui-spring: 1 kg hanging 1 m below (0, 1, 0) on k = 100 N/m, ℓ₀ = 0.5 m: at t = 0 the
    // spring pulls (0, 50, 0) N at the block's anchor, gravity (0, −9.81, 0) N at x.
    let app = fixture("tui-spring.toml");
    let arrows = force_arrows(&app.session.snapshot, app.session.world.effects().gravity());
    assert_eq!(arrows.len(), 2, "{arrows:?}");
    let spring = arrows.iter().find(|a| a.kind == ForceKind::Spring).unwrap();
    assert!((spring.force - Vector3::new(0.0, 50.0, 0.0)).norm() < 1e-12);
    assert!(spring.at.norm() < 1e-12);
    let gravity = arrows
        .iter()
        .find(|a| a.kind == ForceKind::Gravity)
        .unwrap();
    assert!((gravity.force - Vector3::new(0.0, -9.81, 0.0)).norm() < 1e-12);
}

#[test]
fn the_pendulums_rod_pulls_3_m_g_at_the_bottom() {
    // Lesson 25: released from the horizontal, T = m g (3 − 2 cos 90°) = 29.43 N at the
    // bottom (t = 0.592 s, the step containing it), up the rod, at the bob.
    let mut app = app_of(
        tumble::lessons::load(Path::new("25-the-pendulum")).unwrap_or_else(|e| panic!("{e}")),
    );
    app.step_frames(592);
    let arrows = force_arrows(&app.session.snapshot, app.session.world.effects().gravity());
    let joint = arrows.iter().find(|a| a.kind == ForceKind::Joint).unwrap();
    assert!((joint.force.y - 29.43).abs() < 0.01, "{joint:?}");
    assert!(joint.force.x.abs() < 0.1, "{joint:?}");
    assert!((joint.at - app.session.snapshot.position).norm() < 1e-9);
    assert_eq!(arrows.len(), 2, "the rod and gravity: {arrows:?}");
}

#[test]
fn f_draws_the_arrows_with_a_scale_and_a_legend() {
    let mut app = fixture("tui-spring.toml");
    let before = screen(&app, 80, 24);
    assert!(!before.contains("gcjs forces"));
    app.handle_key(&KeyEvent::new(KeyCode::Char('F'), KeyModifiers::NONE));
    assert!(app.prefs.forces);
    let after = screen(&app, 80, 24);
    insta::assert_snapshot!("forces_spring_80x24", after);
    insta::assert_snapshot!("forces_spring_120x40", screen(&app, 120, 40));
}

#[test]
fn the_period_timer_times_the_pendulum_from_the_horizontal_to_the_elliptic_integral() {
    // Lesson 25: L = 1 m, g = 9.81, θ₀ = 90°: T = 4 √(L/g) K(sin 45°) = 4 × 0.3192754 ×
    // 1.8540747 = 2.367842 s (the small-angle 2π√(L/g) = 2.006 s is 18 % short). Timed on the
    // bob's x over 8 s (3 periods), dt = 1 ms.
    use tumble::tui::period_timer::periods;
    let mut app = app_of(
        tumble::lessons::load(Path::new("25-the-pendulum")).unwrap_or_else(|e| panic!("{e}")),
    );
    let (mut t, mut x) = (
        vec![app.session.snapshot.time],
        vec![app.session.snapshot.position.x],
    );
    for _ in 0..8000 {
        app.session.world.step();
        t.push(app.session.world.time());
        x.push(app.session.world.states()[0].position.x);
    }
    let p = periods(&t, &x).unwrap();
    assert_eq!(p.count, 2, "{p:?}");
    let exact = 4.0 * (1.0f64 / 9.81).sqrt() * 1.854_074_677;
    assert!((p.mean - exact).abs() < 1e-4, "{p:?} against {exact}");
    assert!(p.spread < 1e-4, "{p:?}");
}
