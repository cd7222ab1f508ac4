//! Pages a class reads (issue 38): a prediction due at a page's own time is still compared;
//! a value a page quotes at its pause is the value the panels show there; at 80×24 the stage
//! layout gives the page the full width.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::Path;
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

fn press(app: &mut App, code: KeyCode) {
    app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
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

/// Runs until the run pauses by itself.
fn run_to_pause(app: &mut App) {
    assert!(app.ui.running);
    while app.ui.running {
        app.step_frames(10);
    }
}

#[test]
fn lesson_32s_guess_is_compared_at_page_3s_own_time() {
    // Page 1 asks for cube.y at t = 0.643 s, the time page 3 starts: the run pauses there
    // for page 3, and the comparison is in the status line and on page 3.
    let mut app = lesson_app("32-predict-the-bounce");
    press(&mut app, KeyCode::Enter);
    for c in "0.3".chars() {
        press(&mut app, KeyCode::Char(c));
    }
    press(&mut app, KeyCode::Enter);
    run_to_pause(&mut app); // page 2, the touch
    assert_eq!(app.session.world.step_count(), 429);
    press(&mut app, KeyCode::Enter);
    run_to_pause(&mut app);
    assert_eq!(app.session.world.step_count(), 643);
    let notice = app.ui.notice.clone().unwrap();
    assert!(
        notice.starts_with("cube.y at t = 0.643 s: your guess 0.3 m · simulated "),
        "{notice}"
    );
    assert!(notice.ends_with("page 3/3 “The top” (t = 0.643 s): Enter continues"));
    let shown = screen(&app, 200, 60);
    assert!(shown.contains("page 3/3: The top"), "{shown}");
    assert!(
        shown.contains("Prediction (page 1): cube.y at t = 0.643 s: your guess 0.3 m"),
        "{shown}"
    );
}

#[test]
fn lesson_16_quotes_at_its_touch_the_velocity_the_panel_shows() {
    // Page 2 pauses at t = 0.272 s, the step of the touch: the page's {{vy}} is the panel's
    // v_y there (after that step's contact), not the free fall's −g t = −2.66832 m/s.
    let mut app = lesson_app("16-trampoline");
    press(&mut app, KeyCode::Char(' '));
    run_to_pause(&mut app);
    assert_eq!(app.session.world.step_count(), 272);
    let vy = app.session.snapshot.velocity.y;
    assert!((vy - -2.570462).abs() < 1e-6, "{vy}");
    let shown = screen(&app, 200, 60);
    assert!(
        shown.contains("the panel reads v_y = -2.570462 m/s"),
        "{shown}"
    );
}

#[test]
fn the_stage_layout_shows_the_page_across_80_columns() {
    let mut app = lesson_app("02-rigid-body-from-points");
    press(&mut app, KeyCode::Char('L'));
    let shown = screen(&app, 80, 24);
    let title = shown
        .lines()
        .find(|l| l.contains("page 1/"))
        .unwrap_or_else(|| panic!("{shown}"));
    assert_eq!(title.chars().count(), 80, "{shown}");
}
