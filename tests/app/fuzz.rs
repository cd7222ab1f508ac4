//! A seeded random-key and resize fuzz of the app's update loop, without a terminal: random
//! key events (every key of every context, with modifiers), random screen sizes (from 1 × 1
//! to 240 × 90), a few frames stepped while running and a slice of any jump under way, each
//! rendered to ratatui's `TestBackend` — as `tui::run`'s loop does. It asserts no panic, and
//! that `q` then ends the app, whatever window, prompt or form is open.
//!
//! Left out: `s` (a study starts a thread of many runs: minutes of CPU, not an input case)
//! and `q` and Ctrl-C, the quit keys, until the end. Files the app writes (`W`, `X`) go to a scratch folder.
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::{Path, PathBuf};
use std::time::Duration;
use tumble::tui::{App, Options};

/// xorshift64*: a small seeded generator, the same sequence on every machine.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// Every key the app's tables name, and some no table names.
fn key_codes() -> Vec<KeyCode> {
    let mut codes: Vec<KeyCode> = (b' '..=b'~')
        .map(char::from)
        .filter(|c| !matches!(c, 'q' | 's'))
        .map(KeyCode::Char)
        .collect();
    codes.extend([
        KeyCode::Char('é'),
        KeyCode::Char('ω'),
        KeyCode::Left,
        KeyCode::Right,
        KeyCode::Up,
        KeyCode::Down,
        KeyCode::Enter,
        KeyCode::Esc,
        KeyCode::Tab,
        KeyCode::BackTab,
        KeyCode::Backspace,
        KeyCode::Delete,
        KeyCode::Home,
        KeyCode::End,
        KeyCode::PageUp,
        KeyCode::PageDown,
        KeyCode::F(1),
    ]);
    codes
}

/// A scene of this repository, for the app.
fn lesson(path: &str) -> tumble::scene::Lesson {
    tumble::lessons::load(Path::new(path)).unwrap_or_else(|e| panic!("{e}"))
}

fn scratch() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `events` random events on the app of `path`, then `q`.
fn fuzz(path: &str, seed: u64, events: usize) {
    let mut rng = Rng(seed);
    let codes = key_codes();
    let modifiers = [
        KeyModifiers::NONE,
        KeyModifiers::NONE,
        KeyModifiers::NONE,
        KeyModifiers::SHIFT,
        KeyModifiers::CONTROL,
        KeyModifiers::ALT,
    ];
    let mut app = App::new(
        lesson(path),
        Options {
            ascii: rng.below(2) == 0,
            compare: None,
            show_timing: false,
        },
    );
    app.prefs.write_dir = scratch();
    let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
    let mut log: Vec<String> = Vec::new();
    for _ in 0..events {
        match rng.below(10) {
            // A resize: the next draw takes the new size.
            0 => {
                let (w, h) = (1 + rng.below(240) as u16, 1 + rng.below(90) as u16);
                log.push(format!("resize {w}x{h}"));
                terminal.backend_mut().resize(w, h);
            }
            _ => {
                let code = codes[rng.below(codes.len() as u64) as usize];
                let mut modifier = modifiers[rng.below(modifiers.len() as u64) as usize];
                // Ctrl-C quits, as in any terminal program: the other quit key, kept for the end.
                if code == KeyCode::Char('c') && modifier == KeyModifiers::CONTROL {
                    modifier = KeyModifiers::NONE;
                }
                log.push(format!("{code:?}+{modifier:?}"));
                app.handle_key(&KeyEvent::new(code, modifier));
            }
        }
        assert!(
            !app.ui.quit,
            "{path} seed {seed}: quit without q after {log:?}"
        );
        // As the event loop: a slice of a jump, a few frames while running, then a draw.
        app.work(Duration::from_millis(2));
        if app.ui.running && app.session.job.is_none() && app.session.divergence.is_none() {
            app.step_frames(1 + rng.below(3));
        }
        terminal
            .draw(|frame| frame.render_widget(&app, frame.area()))
            .unwrap();
    }
    app.handle_key(&KeyEvent::new(KeyCode::Char('q'), KeyModifiers::NONE));
    let tail = &log[log.len().saturating_sub(12)..];
    assert!(
        app.ui.quit,
        "{path} seed {seed}: q did not end the app after …{tail:?}"
    );
}

#[test]
fn random_keys_and_resizes_never_panic_and_q_always_ends_the_app() {
    // (scene, seeds): a box, the pendulum (a joint), the head-on row (contacts between
    // bodies), a cloth.
    let cases: [(&str, &[u64]); 4] = [
        ("tests/fixtures/tui-box.toml", &[1, 2, 3]),
        ("25-the-pendulum", &[4, 5]),
        ("14-head-on", &[6]),
        ("tests/fixtures/tui-cloth-sheet.toml", &[7]),
    ];
    for (path, seeds) in cases {
        let path = match path.strip_prefix("tests/") {
            Some(_) => format!("{}/{path}", env!("CARGO_MANIFEST_DIR")),
            None => path.to_string(),
        };
        for &seed in seeds {
            fuzz(&path, seed, 250);
        }
    }
}
