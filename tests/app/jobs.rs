//! Long work never holds the keys (issue 38): a jump runs as a job, a slice at a time; q quits
//! in the same update call whatever runs, Esc cancels where the jump got to.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use std::path::Path;
use std::time::Duration;
use tumble::tui::{App, Options};

fn lesson_app(name: &str) -> App {
    let mut app = App::new(
        tumble::lessons::load(Path::new(name)).unwrap_or_else(|e| panic!("{e}")),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    app.session.background_jobs = true;
    app
}

fn press(app: &mut App, code: KeyCode) {
    app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
}

fn jump(app: &mut App, t: &str) {
    press(app, KeyCode::Char('J'));
    for c in t.chars() {
        press(app, KeyCode::Char(c));
    }
    press(app, KeyCode::Enter);
}

#[test]
fn a_long_jump_is_a_job_and_q_quits_in_the_same_update() {
    // Lesson 16, J 5000 Enter: 500 000 frames of a trampoline, minutes of stepping. Enter
    // returns after one slice with the job under way and its progress in the status line.
    let mut app = lesson_app("16-trampoline");
    jump(&mut app, "5000");
    let job = app.session.job.expect("the jump runs as a job");
    assert_eq!(job.target, (5000.0 / app.session.world.dt()).round() as u64);
    assert!(
        app.session.world.step_count() < job.target,
        "not done in one slice"
    );
    let notice = app.ui.notice.clone().unwrap();
    assert!(notice.starts_with("jumping to t = 5000 s: "), "{notice}");
    assert!(notice.contains("Esc cancels, q quits"), "{notice}");
    // A slice more runs frames and returns.
    let before = app.session.world.step_count();
    assert!(app.work(Duration::from_millis(5)));
    assert!(app.session.world.step_count() > before);
    // q: handled in this very call, the job is dropped (nothing steps it any more).
    press(&mut app, KeyCode::Char('q'));
    assert!(app.ui.quit);
    assert!(app.session.job.is_none(), "the job is told to stop");
    let stopped = app.session.world.step_count();
    assert!(!app.work(Duration::from_millis(5)));
    assert_eq!(app.session.world.step_count(), stopped);
}

#[test]
fn ctrl_c_quits_and_esc_cancels_a_jump_where_it_got_to() {
    let mut app = lesson_app("16-trampoline");
    jump(&mut app, "5000");
    // Other keys wait for the job (and say so); Esc cancels it.
    press(&mut app, KeyCode::Char(' '));
    assert!(!app.ui.running);
    assert!(app.ui.notice.as_deref().unwrap().contains("Esc cancels"));
    press(&mut app, KeyCode::Esc);
    assert!(app.session.job.is_none());
    assert!(!app.ui.quit);
    let at = app.session.world.step_count();
    assert!(at > 0);
    assert_eq!(
        app.ui.notice.as_deref().unwrap(),
        format!(
            "jump cancelled at t = {} s (step {at})",
            tumble::tui::settings_form::tidy(app.session.world.time())
        )
    );
    // The app goes on from there; a second jump is quit with Ctrl-C.
    jump(&mut app, "5000");
    assert!(app.session.job.is_some());
    app.handle_key(&KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL));
    assert!(app.ui.quit && app.session.job.is_none());
}

#[test]
fn a_short_jump_as_a_job_ends_where_the_direct_jump_does() {
    let mut direct = lesson_app("16-trampoline");
    direct.session.background_jobs = false;
    jump(&mut direct, "0.5");
    let mut job = lesson_app("16-trampoline");
    jump(&mut job, "0.5");
    while job.work(Duration::from_millis(20)) {}
    assert_eq!(
        job.session.world.checkpoint(),
        direct.session.world.checkpoint()
    );
    assert_eq!(job.ui.notice, direct.ui.notice);
    assert_eq!(
        direct.ui.notice.as_deref(),
        Some("jumped to t = 0.5 s (step 500)")
    );
}
