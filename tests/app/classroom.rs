//! The classroom findings of issue 21 in the app: compare mode when one world diverges, the
//! settings form and the study on scenes of cloths only, the form's own checks.

use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::Path;
use tumble::physics::Response;
use tumble::tui::{App, Comparison, Options};

fn lesson_app(name: &str, compare: Option<Comparison>) -> App {
    App::new(
        tumble::lessons::load(Path::new(name)).unwrap_or_else(|e| panic!("{e}")),
        Options {
            ascii: true,
            compare,
            show_timing: false,
        },
    )
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
fn a_diverging_ghost_freezes_and_the_run_goes_on() {
    // Lesson 6 against seed: the seed ghost diverges (step 478 on main); impulse runs on.
    let mut app = lesson_app(
        "06-sphere-obstacle",
        Some(Comparison::Response(Response::Seed)),
    );
    app.running = true;
    app.pause_at_stops = false;
    app.step_frames(700);
    assert!(app.divergence.is_none(), "{:?}", app.divergence);
    assert_eq!(app.world.step_count(), 700, "the impulse run went on");
    let ghost = app.ghost.as_ref().expect("compare mode on");
    let at = ghost
        .diverged
        .as_ref()
        .expect("the seed ghost diverged")
        .step;
    assert!(at < 700, "diverged at {at}");
    assert_eq!(ghost.world.step_count(), at, "frozen at its divergence");
    assert!(app.running, "still running");
    // The run is the lesson's own impulse run, stepped alone.
    let mut alone = lesson_app("06-sphere-obstacle", None);
    alone.step_frames(700);
    assert_eq!(alone.world.checkpoint(), app.world.checkpoint());
    let shown = screen(&app, 200, 60);
    assert!(
        shown.contains(&format!("impulse vs seed (diverged at step {at})")),
        "{shown}"
    );
    // Stepping back before the divergence thaws the ghost; forward again, it freezes again.
    app.step_back_frames(700 - at as usize + 5);
    assert!(app.ghost.as_ref().unwrap().diverged.is_none());
    app.step_frames(20);
    assert_eq!(
        app.ghost.as_ref().unwrap().diverged.as_ref().unwrap().step,
        at
    );
}

#[test]
fn when_the_lessons_own_world_diverges_the_run_follows_the_ghost() {
    // Lesson 8 runs seed; the impulse ghost does not diverge: the two trade places.
    let mut app = lesson_app(
        "08-climbing-bug",
        Some(Comparison::Response(Response::Impulse)),
    );
    app.pause_at_stops = false;
    let mut alone = lesson_app("08-climbing-bug", None);
    alone.step_frames(3000);
    let at = alone.divergence.as_ref().expect("seed diverges alone").step;
    app.step_frames(at + 200);
    assert!(app.divergence.is_none(), "{:?}", app.divergence);
    assert_eq!(app.world.step_count(), at + 200);
    assert_eq!(
        app.world.contact_model().unwrap().response,
        Response::Impulse,
        "the run follows the impulse world"
    );
    let ghost = app.ghost.as_ref().unwrap();
    assert_eq!(ghost.comparison, Comparison::Response(Response::Seed));
    assert_eq!(ghost.diverged.as_ref().unwrap().step, at);
    assert_eq!(ghost.world.step_count(), at);
    // Exactly the impulse run alone.
    let mut impulse = lesson_app("08-climbing-bug", None);
    let mut model = *impulse.world.contact_model().unwrap();
    model.response = Response::Impulse;
    impulse.world.set_contact_model(model);
    impulse.step_frames(at + 200);
    assert_eq!(impulse.world.checkpoint(), app.world.checkpoint());
    // Step back across the swap: the impulse world's own earlier frames.
    app.step_back_frames(300);
    impulse.step_back_frames(300);
    assert_eq!(impulse.world.checkpoint(), app.world.checkpoint());
    assert!(app.ghost.as_ref().unwrap().diverged.is_none());
}
