//! What the app's test files share: an app on a scene's text or on a bundled lesson, keys
//! pressed, and the screen as text.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::Path;
use tumble::tui::{App, Options};

/// ASCII drawing, no ghost, no timings (the screens are the same on every machine).
fn options() -> Options {
    Options {
        ascii: true,
        compare: None,
        show_timing: false,
    }
}

/// The app on the scene written in `source` (`file` names it in errors).
pub fn app_of(source: &str, file: &str) -> App {
    let lesson = tumble::scene::parse(source, Path::new(file)).unwrap_or_else(|e| panic!("{e}"));
    App::new(lesson, options())
}

/// The app on a bundled lesson or a lesson file.
pub fn lesson(name: &str) -> App {
    let lesson = tumble::lessons::load(Path::new(name)).unwrap_or_else(|e| panic!("{e}"));
    App::new(lesson, options())
}

pub fn press(app: &mut App, code: KeyCode) {
    app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
}

/// Each character of `text` as a key.
pub fn keys(app: &mut App, text: &str) {
    for c in text.chars() {
        press(app, KeyCode::Char(c));
    }
}

/// The screen drawn at `width` × `height` through a terminal (the app records where things
/// are, as the mouse reads them), rows trimmed at the right.
pub fn screen(app: &App, width: u16, height: u16) -> String {
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
