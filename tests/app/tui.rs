//! The terminal app, driven by key events and rendered to ratatui's `TestBackend`: snapshots of
//! each numeric panel and of whole screens (ASCII projection, no timing), and the app's logic.
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::Terminal;
use std::path::Path;
use tumble::physics::{Integrator, Phase};
use tumble::tables;
use tumble::tui::keys::{Context, KEYS};
use tumble::tui::panels::PanelView;
use tumble::tui::{App, Comparison, Options, View};

fn fixture(name: &str) -> tumble::scene::Lesson {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn app(name: &str) -> App {
    App::new(
        fixture(name),
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

fn keys(app: &mut App, text: &str) {
    for c in text.chars() {
        let code = match c {
            '>' => KeyCode::Right,
            '<' => KeyCode::Left,
            c => KeyCode::Char(c),
        };
        press(app, code);
    }
}

/// The buffer as text, trailing spaces trimmed.
fn text(buf: &Buffer) -> String {
    let area = buf.area;
    (0..area.height)
        .map(|y| {
            let row: String = (0..area.width).map(|x| buf[(x, y)].symbol()).collect();
            row.trim_end().to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn screen(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|f| f.render_widget(app, f.area())).unwrap();
    text(terminal.backend().buffer())
}

/// The fixed key sequence of the snapshots: frame 1 phase by phase, three more frames, then
/// frame 5 up to its integrate phase (t = 0.05 s, mid-frame).
const SEQUENCE: &str = "nnn>>>>nnn";

#[test]
fn whole_screen_at_120x40_after_a_fixed_key_sequence() {
    let mut app = app("tui-box.toml");
    keys(&mut app, SEQUENCE);
    assert_eq!(app.session.snapshot.step, 5);
    assert_eq!(app.session.snapshot.phase, Some(Phase::Integrate));
    insta::assert_snapshot!("screen_120x40", screen(&app, 120, 40));
}

#[test]
fn each_numeric_panel_after_a_fixed_key_sequence() {
    let mut app = app("tui-box.toml");
    keys(&mut app, SEQUENCE);
    let panels = tables::panels(&app.session.snapshot, tables::Frame::World);
    let previous = tables::panels(app.session.previous.as_ref().unwrap(), tables::Frame::World);
    assert_eq!(panels.len(), 7);
    for (panel, before) in panels.iter().zip(&previous) {
        let view = PanelView {
            panel,
            previous: Some(before),
            compare: None,
        };
        let height = view.lines().len() as u16;
        let mut terminal = Terminal::new(TestBackend::new(72, height)).unwrap();
        terminal.draw(|f| f.render_widget(view, f.area())).unwrap();
        let name = format!("panel_{}", panel.title.replace(' ', "_"));
        insta::assert_snapshot!(name, text(terminal.backend().buffer()));
    }
}

#[test]
fn panels_show_the_same_text_as_the_tables_module() {
    // The app must not reformat numbers: every line of `tables::panel_text` appears verbatim
    // on screen (the screen adds only styling).
    let mut app = app("tui-box.toml");
    keys(&mut app, SEQUENCE);
    let panels = tables::panels(&app.session.snapshot, tables::Frame::World);
    for panel in &panels {
        let view = PanelView {
            panel,
            previous: None,
            compare: None,
        };
        let mut terminal = Terminal::new(TestBackend::new(80, 12)).unwrap();
        terminal.draw(|f| f.render_widget(view, f.area())).unwrap();
        let shown = text(terminal.backend().buffer());
        for line in tables::panel_text(panel).iter().skip(1) {
            assert!(
                shown.contains(line.trim_start()),
                "`{line}` not in\n{shown}"
            );
        }
    }
}

#[test]
fn compare_mode_draws_the_ghost_numbers_under_the_first() {
    let mut app = App::new(
        fixture("tui-box.toml"),
        Options {
            ascii: true,
            compare: Some(Comparison::Integrator(Integrator::EulerSeed)),
            show_timing: false,
        },
    );
    keys(&mut app, ">>>>>>>>>>");
    let ghost = app.session.ghost.as_ref().expect("compare mode on");
    assert_eq!(ghost.snapshot.step, 10, "the ghost runs in lock-step");
    assert_eq!(ghost.snapshot.integrator, Integrator::EulerSeed);
    // euler-seed's matrix drifts from a rotation, rk4's quaternion does not.
    assert!(
        ghost.snapshot.orthonormality_error > 1e-6,
        "euler-seed drift {}",
        ghost.snapshot.orthonormality_error
    );
    assert!(app.session.snapshot.orthonormality_error < 1e-12);
    insta::assert_snapshot!("screen_compare_120x40", screen(&app, 120, 40));
}

#[test]
fn space_runs_and_pauses() {
    let mut app = app("tui-box.toml");
    assert!(!app.ui.running);
    keys(&mut app, " ");
    assert!(app.ui.running);
    app.step_frames(3); // what the event loop does while running
    assert_eq!(app.session.snapshot.step, 3);
    keys(&mut app, " ");
    assert!(!app.ui.running);
}

#[test]
fn n_runs_the_phases_in_loop_order() {
    let mut app = app("tui-box.toml");
    let mut seen = Vec::new();
    for _ in 0..5 {
        keys(&mut app, "n");
        seen.push((app.session.snapshot.phase, app.session.snapshot.step));
    }
    use Phase::*;
    assert_eq!(
        seen,
        vec![
            (Some(Derive), 0),
            (Some(Forces), 0),
            (Some(Integrate), 1),
            (Some(Collide), 1),
            (Some(Derive), 1)
        ]
    );
}

#[test]
fn stepping_back_restores_the_exact_previous_state() {
    let mut app = app("tui-box.toml");
    keys(&mut app, ">>>>");
    let before = app.session.world.checkpoint();
    let snapshot = app.session.snapshot.clone();
    keys(&mut app, ">");
    assert_ne!(app.session.world.checkpoint(), before);
    keys(&mut app, "<");
    assert_eq!(
        app.session.world.checkpoint(),
        before,
        "bit-for-bit the state of frame 4"
    );
    assert_eq!(app.session.snapshot, snapshot);
    // Mid-frame, ← goes back to the start of the current frame.
    keys(&mut app, "nn<");
    assert_eq!(app.session.world.checkpoint(), before);
    // Back to t = 0, then nothing earlier is kept.
    keys(&mut app, "<<<<<");
    assert_eq!(app.session.snapshot.step, 0);
    assert_eq!(app.ui.notice.as_deref(), Some("no earlier frame kept"));
}

#[test]
fn reset_returns_to_t_zero_and_pauses() {
    let mut app = app("tui-box.toml");
    let start = app.session.world.checkpoint();
    keys(&mut app, ">>>nn ");
    keys(&mut app, "r");
    assert!(!app.ui.running);
    assert_eq!(app.session.world.checkpoint(), start);
    assert!(app.session.history.is_empty());
}

#[test]
fn switching_integrator_keeps_time_and_state() {
    let mut app = app("tui-box.toml");
    keys(&mut app, ">>>>>>>>>>");
    let before = app.session.snapshot.clone();
    keys(&mut app, "i");
    let after = &app.session.snapshot;
    // rk4 → splitting (the next in Integrator::ALL); both use a quaternion, so nothing moves.
    assert_eq!(after.integrator, Integrator::Splitting);
    assert_eq!(after.time, before.time);
    assert_eq!(after.position, before.position);
    assert_eq!(after.linear_momentum, before.linear_momentum);
    assert_eq!(after.angular_momentum, before.angular_momentum);
    // Then exact-splitting, exact-splitting-4, and euler-seed: R becomes a matrix equal to the
    // rotation of q.
    keys(&mut app, "ii");
    assert_eq!(app.session.snapshot.integrator, Integrator::ExactSplitting4);
    keys(&mut app, "i");
    assert_eq!(app.session.snapshot.integrator, Integrator::EulerSeed);
    let dr = (app.session.snapshot.rotation - before.rotation)
        .abs()
        .max();
    assert!(dr < 1e-12, "rotation changed by {dr}");
    keys(&mut app, ">");
    assert_eq!(app.session.snapshot.step, 11);
    assert!(app.session.snapshot.energy.total.is_finite());
    // Energy stays within 1 % over one 10 ms frame of a 2 kg box (E ≈ 30 J).
    let drift = (app.session.snapshot.energy.total - before.energy.total).abs();
    assert!(
        drift < 0.01 * before.energy.total.abs(),
        "energy changed by {drift} J"
    );
}

#[test]
fn help_overlay_lists_every_bound_key() {
    // The main screen's keys in the help; the picker's, the form's and the prompt's in their
    // own windows.
    let mut app = app("tui-box.toml");
    let shown_in = |context: Context, app: &mut App| {
        press(app, KeyCode::Esc);
        let open = match context {
            Context::Main => "?",
            Context::Picker => "l",
            Context::Form => "e",
            Context::Prompt => "J",
            Context::PlotPicker => "p",
        };
        keys(app, open);
        // At 200×60 the main help is one column, every line whole (at 120×40 it is two, long
        // lines wrapped: checked below).
        if context == Context::Main {
            screen(app, 200, 60)
        } else {
            screen(app, 120, 40)
        }
    };
    for b in KEYS {
        let shown = shown_in(b.context, &mut app);
        assert!(
            shown.contains(b.label),
            "help lacks `{}`:\n{shown}",
            b.label
        );
        let help = b.help.split_once(": ").map_or(b.help, |(_, rest)| rest);
        assert!(shown.contains(help), "help lacks `{}`:\n{shown}", b.help);
    }
    press(&mut app, KeyCode::Esc);
    keys(&mut app, "?");
    let small = screen(&app, 120, 40);
    assert!(small.contains("help — ? or Esc closes"));
    // At 120×40 in two columns: every key is there, and every help's last word (nothing cut
    // off at a column's edge or the bottom).
    for b in KEYS
        .iter()
        .filter(|b| b.context == Context::Main && !b.help.is_empty())
    {
        assert!(
            small.contains(b.label),
            "120×40 help lacks `{}`:\n{small}",
            b.label
        );
        let last = b.help.split(' ').next_back().unwrap_or_default();
        assert!(
            small.contains(last),
            "120×40 help cuts `{}`:\n{small}",
            b.help
        );
    }
    keys(&mut app, "?");
    assert!(!screen(&app, 120, 40).contains("help — ? or Esc closes"));
}

#[test]
fn status_bar_hints_come_from_the_key_table() {
    let app = app("tui-box.toml");
    let shown = screen(&app, 200, 60);
    for b in KEYS
        .iter()
        .filter(|b| b.context == Context::Main && !b.hint.is_empty())
    {
        let (key, what) = b.hint.split_once(' ').unwrap();
        assert!(
            shown.contains(&format!("{key} {what}")),
            "no hint `{}`",
            b.hint
        );
    }
}

#[test]
fn works_at_80x24() {
    let mut app = app("tui-box.toml");
    keys(&mut app, SEQUENCE);
    let shown = screen(&app, 80, 24);
    // The panels that fit (the state's q row is wider than 80 columns leave; the constant
    // inertia tensor yields first).
    for part in [
        "front x–y",
        "angular velocity",
        "energy",
        "integrate",
        "? help",
        "t 0.050000 s",
    ] {
        assert!(shown.contains(part), "no `{part}` at 80×24:\n{shown}");
    }
    insta::assert_snapshot!("screen_80x24", shown);
}

#[test]
fn below_80x24_asks_to_enlarge_the_terminal() {
    let app = app("tui-box.toml");
    let shown = screen(&app, 60, 20);
    assert!(shown.contains("Please enlarge the terminal"), "{shown}");
    assert!(shown.contains("60×20"), "{shown}");
    // Degenerate sizes never panic.
    for (w, h) in [(0, 0), (1, 1), (79, 40), (200, 23)] {
        screen(&app, w, h);
    }
}

#[test]
fn a_cube_is_drawn_square() {
    // A unit cube at rest, seen from the front: a 1 m × 1 m square. Terminal cells are about
    // twice as tall as wide, so the square must span twice as many columns as rows, give or
    // take the rounding of each corner to a cell (±1 cell on each side of the ratio).
    let app = app("tui-cube.toml");
    for (width, height) in [(120, 40), (160, 50), (80, 24)] {
        let shown = screen(&app, width, height);
        // Only inside the projection's box: from its top line to its bottom line, between
        // its two side borders.
        let lines: Vec<Vec<char>> = shown.lines().map(|l| l.chars().collect()).collect();
        let top = lines
            .iter()
            .position(|l| l.starts_with(&['┌', ' ', 'f']))
            .unwrap();
        let bottom = top + lines[top..].iter().position(|l| l[0] == '└').unwrap();
        let right = lines[top].iter().position(|c| *c == '┐').unwrap();
        let corners: Vec<(usize, usize)> = (top + 1..bottom)
            .flat_map(|row| {
                (1..right)
                    .filter(|&col| lines[row][col] == '+')
                    .map(|col| (row, col))
                    .collect::<Vec<_>>()
            })
            .collect();
        let rows =
            corners.iter().map(|c| c.0).max().unwrap() - corners.iter().map(|c| c.0).min().unwrap();
        let cols =
            corners.iter().map(|c| c.1).max().unwrap() - corners.iter().map(|c| c.1).min().unwrap();
        assert!(
            rows >= if width >= 120 { 4 } else { 2 },
            "{width}×{height}: cube only {rows} rows tall:\n{shown}"
        );
        assert!(
            (cols as i64 - 2 * rows as i64).abs() <= 2,
            "{width}×{height}: cube spans {cols} columns × {rows} rows, want 2:1:\n{shown}"
        );
    }
}

#[test]
fn views_cycle_front_side_top() {
    let mut app = app("tui-box.toml");
    for name in ["side z–y", "top x–z", "front x–y"] {
        keys(&mut app, "v");
        assert!(screen(&app, 120, 40).contains(name), "no `{name}`");
    }
    keys(&mut app, "f");
    assert!(screen(&app, 120, 40).contains("inertia tensor (body frame)"));
}

#[test]
fn energy_graph_replaces_the_projection() {
    let mut app = app("tui-box.toml");
    keys(&mut app, ">>>>>g");
    assert_eq!(app.ui.view, View::Energy);
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("energy, J"), "{shown}");
    assert!(shown.contains("drift (E − E₀ not booked), J"), "{shown}");
    // The time axis ends at the scene's duration, 2 s, and does not move while running.
    let axis = app.session.series.time_axis;
    keys(&mut app, ">>>>>");
    assert_eq!(app.session.series.time_axis, axis);
    assert_eq!(axis.hi, 2.0);
    keys(&mut app, "g");
    assert_eq!(app.ui.view, View::Loop);
}

#[test]
fn a_diverging_run_pauses_with_a_dialog_and_the_app_keeps_going() {
    let mut app = app("tui-diverge.toml");
    keys(&mut app, " ");
    app.step_frames(100);
    let d = app
        .session
        .divergence
        .clone()
        .expect("euler-seed at dt = 0.1 with ω = 20 rad/s diverges");
    assert!(!app.ui.running, "paused by the divergence");
    assert_eq!(
        app.session.snapshot.step, d.step,
        "stopped at the step that diverged"
    );
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("The simulation diverged"), "{shown}");
    assert!(shown.contains("euler-seed"), "{shown}");
    keys(&mut app, ">");
    assert_eq!(
        app.session.snapshot.step, d.step,
        "no stepping past a divergence"
    );
    keys(&mut app, "<");
    assert!(app.session.divergence.is_none());
    assert_eq!(app.session.snapshot.step, d.step - 1);
    keys(&mut app, "r");
    assert_eq!(app.session.snapshot.step, 0);
}

#[test]
fn quit_keys_and_key_releases() {
    let mut app = app("tui-box.toml");
    press(&mut app, KeyCode::Char('q'));
    assert!(app.ui.quit);
    let mut app = self::app("tui-box.toml");
    press(&mut app, KeyCode::Esc);
    assert!(!app.ui.quit, "Esc never quits");
    assert_eq!(app.ui.notice.as_deref(), Some("nothing to close: q quits"));
    let mut app = self::app("tui-box.toml");
    app.handle_key(&KeyEvent::new(KeyCode::Char('c'), KeyModifiers::CONTROL));
    assert!(app.ui.quit, "Ctrl-C quits");
    let mut app = self::app("tui-box.toml");
    let mut release = KeyEvent::new(KeyCode::Right, KeyModifiers::NONE);
    release.kind = KeyEventKind::Release;
    app.handle_key(&release);
    assert_eq!(app.session.snapshot.step, 0, "only key presses count");
}

#[test]
fn speed_is_bounded_and_starts_at_real_time() {
    let mut app = app("tui-box.toml");
    // dt = 0.01 s: real time is 100 frames/s.
    assert_eq!(app.frames_per_second(), 100.0);
    keys(&mut app, &"-".repeat(30));
    assert_eq!(
        app.frames_per_second(),
        1.0,
        "slowest: one frame per second"
    );
    keys(&mut app, &"+".repeat(30));
    assert!(
        app.frames_per_second() >= 1e4,
        "fastest: far faster than real time"
    );
}

#[test]
fn lesson_picker_lists_and_opens_bundled_lessons() {
    let mut app = app("tui-box.toml");
    keys(&mut app, "l");
    let shown = screen(&app, 120, 40);
    let first = tumble::lessons::bundled().into_iter().next().unwrap();
    let name = first.file_name().unwrap().to_string_lossy().into_owned();
    assert!(shown.contains(&name), "{shown}");
    // The fixture is not bundled: the first lesson is selected; Enter opens it.
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.session.lesson.path.file_name(), first.file_name());
    assert_eq!(app.session.snapshot.step, 0);
}

#[test]
fn preferences_carry_to_the_next_lesson_and_the_run_starts_over() {
    use tumble::tui::keys::Message;
    let mut app = app("tui-box.toml");
    for m in [
        Message::NextAxis,
        Message::ToggleFrame,
        Message::ToggleTrail,
        Message::ToggleArrows,
        Message::ToggleForces,
        Message::NextLayout,
    ] {
        app.update(m);
    }
    app.prefs.write_dir = std::path::PathBuf::from("elsewhere");
    let chosen = app.prefs.clone();
    assert_ne!(chosen, self::app("tui-box.toml").prefs);
    app.step_frames(5);
    // The picker's second lesson: another scene, at t = 0, seen as the student set it.
    app.update(Message::OpenPicker);
    app.update(Message::PickerDown);
    app.update(Message::PickerOpen);
    let second = tumble::lessons::bundled().into_iter().nth(1).unwrap();
    assert_eq!(app.session.lesson.path.file_name(), second.file_name());
    assert_eq!(app.session.snapshot.step, 0);
    assert_eq!(app.prefs, chosen);
}

#[test]
fn cells_changed_by_the_last_action_are_highlighted() {
    use ratatui::style::Color;
    let mut app = app("tui-box.toml");
    keys(&mut app, ">");
    let panels = tables::panels(&app.session.snapshot, tables::Frame::World);
    let previous = tables::panels(app.session.previous.as_ref().unwrap(), tables::Frame::World);
    // Panel "force and torque": F = M g did not change over the frame; "state": x did.
    let style_of_first_cell = |i: usize| {
        let view = PanelView {
            panel: &panels[i],
            previous: Some(&previous[i]),
            compare: None,
        };
        let mut terminal = Terminal::new(TestBackend::new(72, 8)).unwrap();
        terminal.draw(|f| f.render_widget(view, f.area())).unwrap();
        let buf = terminal.backend().buffer().clone();
        // Row 1 is the first data row; the last character of its first number cell.
        // The label ends at the first space after column 1; the first number follows.
        let symbol = |x: u16| buf[(x, 1)].symbol().to_string();
        let label_end = (2..72).find(|&x| symbol(x) == " ").unwrap();
        let number_start = (label_end..72).find(|&x| symbol(x) != " ").unwrap();
        let first_cell_end = (number_start..72).find(|&x| symbol(x + 1) == " ").unwrap();
        buf[(first_cell_end, 1)].fg
    };
    assert_eq!(
        style_of_first_cell(0),
        Color::Yellow,
        "x changed: highlighted"
    );
    assert_eq!(style_of_first_cell(3), Color::Reset, "F unchanged: plain");
}

#[test]
fn bad_files_and_options_fail_with_one_line_before_the_terminal_is_touched() {
    use assert_cmd::Command;
    let missing = Command::cargo_bin("tumble")
        .unwrap()
        .arg("no/such/lesson.toml")
        .assert()
        .code(2);
    let out = missing.get_output();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    assert!(stderr.contains("no/such/lesson.toml"), "{stderr}");
    // No escape sequence (alternate screen, raw mode) was written.
    assert!(out.stdout.is_empty(), "stdout: {:?}", out.stdout);
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tui-cube.toml");
    for (flag, expected) in [
        ("bogus", "unknown --compare `bogus`"),
        ("seed", "needs a scene with obstacles"),
    ] {
        let bad = Command::cargo_bin("tumble")
            .unwrap()
            .arg(&fixture)
            .args(["--compare", flag])
            .assert()
            .code(2);
        let out = bad.get_output();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(expected), "{stderr}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(out.stdout.is_empty());
    }
}

#[test]
fn the_lesson_page_follows_time_and_scrolls() {
    // The fixture has one page from t = 0; scrolling is clamped to the text, and a reset keeps
    // the same page (so the scroll stays where it was).
    let mut app = app("tui-box.toml");
    press(&mut app, KeyCode::PageDown);
    assert_eq!(app.ui.lesson_scroll, 3);
    assert!(screen(&app, 120, 40).contains("page 1/1: Fixture"));
    press(&mut app, KeyCode::PageUp);
    press(&mut app, KeyCode::PageUp);
    assert_eq!(app.ui.lesson_scroll, 0);
}

#[test]
fn the_first_screen_explains_the_loop_before_anything_runs() {
    let app = app("tui-box.toml");
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("t = 0, nothing has run yet"), "{shown}");
    assert!(shown.contains("Press n to run one phase"), "{shown}");
    insta::assert_snapshot!("screen_start_120x40", shown);
}

// ---------------------------------------------------------------------------------------------
// Esc, pauses, jumps and the settings form (issue 13)

use tumble::tui::keys::Message;
use tumble::tui::{Effect, Overlay};

#[test]
fn esc_closes_what_is_open_innermost_first_and_never_quits() {
    let mut app = app("tui-box.toml");
    // The help over the graph: Esc closes the help, then the graph, then nothing.
    keys(&mut app, "g?");
    assert_eq!(app.ui.overlay, Overlay::Help);
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.ui.overlay, Overlay::None);
    assert_eq!(app.ui.view, View::Energy);
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.ui.view, View::Loop);
    // The study view (set directly: `s` would start the background study).
    app.ui.view = View::Study;
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.ui.view, View::Loop);
    // The picker, the form, the jump prompt.
    for open in ["l", "e", "J"] {
        keys(&mut app, open);
        assert_ne!(app.ui.overlay, Overlay::None, "`{open}` opens a window");
        press(&mut app, KeyCode::Esc);
        assert_eq!(
            app.ui.overlay,
            Overlay::None,
            "Esc closes what `{open}` opened"
        );
    }
    press(&mut app, KeyCode::Esc);
    assert!(!app.ui.quit);
    insta::assert_snapshot!("screen_after_esc_120x40", screen(&app, 120, 40));
    // q quits from any window.
    keys(&mut app, "e");
    keys(&mut app, "q");
    assert!(app.ui.quit, "q quits from the form");
}

#[test]
fn a_run_pauses_at_each_page_and_at_the_duration_and_enter_continues() {
    // dt = 0.01: the page at 0.5 s is step 50, the duration 1 s step 100.
    let mut app = app("tui-pages.toml");
    keys(&mut app, " ");
    app.step_frames(500); // what the event loop does while running
    assert!(!app.ui.running);
    assert_eq!(app.session.snapshot.step, 50);
    let notice = app.ui.notice.clone().unwrap();
    assert!(notice.contains("page 2/2 “Halfway”"), "{notice}");
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("Half a second has passed."), "{shown}");
    assert!(shown.contains("❚❚ paused: page 2/2"), "{shown}");
    press(&mut app, KeyCode::Enter);
    assert!(app.ui.running, "Enter continues");
    app.step_frames(500);
    assert_eq!(app.session.snapshot.step, 100);
    assert!(!app.ui.running);
    insta::assert_snapshot!("screen_end_of_scene_120x40", screen(&app, 120, 40));
    // Past the end it runs on when asked.
    keys(&mut app, " ");
    app.step_frames(10);
    assert_eq!(app.session.snapshot.step, 110);
    assert!(app.ui.running);
}

#[test]
fn j_jumps_forward_and_back_to_a_typed_time() {
    let mut app = app("tui-box.toml");
    keys(&mut app, "nJ1.25");
    assert_eq!(
        app.ui.overlay,
        Overlay::Jump {
            text: "1.25".into()
        }
    );
    insta::assert_snapshot!("screen_jump_prompt_80x24", screen(&app, 80, 24));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.session.snapshot.step, 125, "t = 1.25 s at dt = 0.01 s");
    assert_eq!(
        app.ui.notice.as_deref(),
        Some("jumped to t = 1.25 s (step 125)")
    );
    // Back to 0.3 s: replayed from t = 0, bit for bit the state 30 plain frames reach.
    keys(&mut app, "J0.3");
    press(&mut app, KeyCode::Enter);
    let mut plain = self::app("tui-box.toml");
    plain.step_frames(30);
    assert_eq!(app.session.snapshot.step, 30);
    assert_eq!(
        app.session.world.checkpoint(),
        plain.session.world.checkpoint()
    );
    keys(&mut app, "J");
    press(&mut app, KeyCode::Enter);
    assert!(app.ui.notice.unwrap().contains("is not a time"));
}

#[test]
fn the_settings_form_changes_the_body_and_restarts_the_scene() {
    let mut app = app("tui-box.toml");
    keys(&mut app, ">>>v");
    keys(&mut app, "e");
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("e opens the form");
    };
    assert_eq!(form.fields[0].text, "0.5", "restitution of the fixture");
    // restitution → 0.8, then down to the mass → 3.
    keys(&mut app, "0.8");
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    keys(&mut app, "3");
    insta::assert_snapshot!("screen_settings_form_120x40", screen(&app, 120, 40));
    insta::assert_snapshot!("screen_settings_form_80x24", screen(&app, 80, 24));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.ui.overlay, Overlay::None);
    assert_eq!(app.session.snapshot.step, 0, "restarted at t = 0");
    assert_eq!(app.session.world.body().mass, 3.0);
    assert_eq!(app.session.world.contact_model().unwrap().restitution, 0.8);
    // The velocity was kept: P₀ = M' v₀ = 3 · (0.3, 1, 0).
    let p = app.session.snapshot.linear_momentum;
    assert!(
        (p - nalgebra::Vector3::new(0.9, 3.0, 0.0)).norm() < 1e-12,
        "{p}"
    );
    assert_eq!(
        app.ui.notice.as_deref(),
        Some("settings applied (e 0.5 → 0.8, mass 2 → 3 kg): the scene restarted at t = 0")
    );
    assert_eq!(
        app.prefs.axis,
        tumble::tui::viewport::Axis::Side,
        "the view axis is kept"
    );
}

#[test]
fn a_bad_value_stays_in_the_form_with_the_reason() {
    let mut app = app("tui-box.toml");
    keys(&mut app, "e2");
    press(&mut app, KeyCode::Enter);
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("the form stays open");
    };
    assert_eq!(
        form.error.as_deref(),
        Some("restitution must be between 0 and 1, found 2")
    );
    assert!(screen(&app, 120, 40).contains("✖ restitution must be between 0 and 1"));
    assert_eq!(app.session.world.contact_model().unwrap().restitution, 0.5);
}

#[test]
fn w_asks_for_a_write_and_the_written_scene_loads() {
    let dir = std::env::temp_dir().join(format!("tumble-tui-write-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut app = app("tui-box.toml");
    app.prefs.write_dir = dir.clone();
    keys(&mut app, "e");
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    keys(&mut app, "3");
    // `update` only asks; nothing is written until the effect is performed.
    let effect = app.update(Message::WriteScene).expect("W asks for a write");
    let Effect::WriteScene { edits, to } = &effect else {
        panic!("W writes a scene");
    };
    assert_eq!(edits.mass, 3.0);
    assert_eq!(*to, dir.join("tui-box-edited.toml"));
    assert!(!to.exists());
    app.perform(effect.clone());
    assert_eq!(
        app.ui.notice,
        Some(format!("wrote {} (tumble check accepts it)", to.display()))
    );
    let written = tumble::scene::load(to).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(written.scene.first().body.mass, 3.0);
    assert_eq!(written.title, "Fixture: a tossed box");
    let text = std::fs::read_to_string(to).unwrap();
    assert!(
        text.starts_with("# Fixture for tests/tui.rs"),
        "comments kept:\n{text}"
    );
    // `tumble check` accepts it.
    assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .arg("check")
        .arg(to)
        .assert()
        .code(0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_compare_label_names_what_differs() {
    let mut app = App::new(
        fixture("tui-box.toml"),
        Options {
            ascii: true,
            compare: Some(Comparison::Response(tumble::physics::Response::Seed)),
            show_timing: false,
        },
    );
    let shown = screen(&app, 160, 50);
    assert!(shown.contains("integrator rk4 ·"), "{shown}");
    assert!(shown.contains("response impulse vs seed"), "{shown}");
    app.start_compare(Comparison::Integrator(Integrator::Euler));
    let shown = screen(&app, 160, 50);
    assert!(shown.contains("integrator rk4 vs euler"), "{shown}");
    assert!(shown.contains("response impulse ·"), "{shown}");
}

#[test]
fn another_lesson_keeps_the_speed_relative_to_real_time() {
    let mut app = app("tui-box.toml");
    keys(&mut app, "++f");
    let ratio = app.frames_per_second() * app.session.world.dt();
    keys(&mut app, "l");
    press(&mut app, KeyCode::Enter);
    let after = app.frames_per_second() * app.session.world.dt();
    // SPEEDS steps by ×2 or ×2.5, so the nearest is within a factor 1.6.
    assert!(
        after / ratio < 1.6 && ratio / after < 1.6,
        "×{ratio} real time before, ×{after} after"
    );
    assert_eq!(
        app.prefs.frame,
        tumble::tables::Frame::Body,
        "the frame is kept"
    );
}

/// Lesson 14: three cubes in a row.
fn head_on_app() -> App {
    App::new(
        tumble::lessons::load(Path::new("14-head-on")).unwrap_or_else(|e| panic!("{e}")),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    )
}

#[test]
fn tab_picks_the_body_the_panels_show_and_every_body_is_drawn() {
    let mut app = head_on_app();
    assert_eq!(app.session.snapshot.body_name, "left");
    let shown = screen(&app, 160, 50);
    assert!(shown.contains("body left (1/3)"), "{shown}");
    assert!(shown.contains("system: 3 bodies"), "{shown}");
    // left starts at x = −0.7, middle at 0, right at 0.21: the panels show left's x.
    assert!(shown.contains("-0.700000"), "{shown}");
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.session.snapshot.body_name, "middle");
    assert_eq!(app.session.snapshot.position.x, 0.0);
    press(&mut app, KeyCode::Tab);
    press(&mut app, KeyCode::Tab);
    assert_eq!(app.session.snapshot.body_name, "left", "Tab wraps around");
    // Every body is in the drawing: each barycenter is marked '@' (not the legend's "@ center").
    let centres: usize = shown
        .lines()
        .take(30)
        .filter(|l| !l.contains("@ center"))
        .map(|l| l.split('│').nth(1).unwrap_or("").matches('@').count())
        .sum();
    assert_eq!(centres, 3, "three barycenters drawn:\n{shown}");
}

#[test]
fn with_several_bodies_c_skips_seed_and_says_why() {
    // impulse → soft-step → (seed, refused by the scene's rules) → impulse.
    let mut app = head_on_app();
    press(&mut app, KeyCode::Char('c'));
    assert_eq!(
        app.session.world.contact_model().map(|m| m.response.name()),
        Some("soft-step")
    );
    press(&mut app, KeyCode::Char('c'));
    assert_eq!(
        app.session.world.contact_model().map(|m| m.response.name()),
        Some("impulse")
    );
    assert!(
        app.ui
            .notice
            .as_deref()
            .unwrap_or("")
            .contains("the `seed` response knows one body"),
        "{:?}",
        app.ui.notice
    );
}

#[test]
fn stepping_back_restores_every_body_after_a_collision() {
    let mut app = head_on_app();
    // left meets middle at t = 0.5 s (step 500); run past it, then one frame back.
    for _ in 0..520 {
        press(&mut app, KeyCode::Right);
    }
    let later = app.session.world.states().to_vec();
    press(&mut app, KeyCode::Right);
    press(&mut app, KeyCode::Left);
    assert_eq!(
        app.session.world.states(),
        &later[..],
        "one frame back is exact for every body"
    );
}

#[test]
fn key_u_puts_the_measured_error_under_each_number_and_off_again() {
    let mut app = app("tui-spring.toml");
    keys(&mut app, "u>>>>>");
    let errors = app
        .session
        .error_bars
        .as_ref()
        .and_then(|b| b.errors.as_ref())
        .expect("errors measured after whole frames");
    let x = errors
        .iter()
        .find(|e| e.panel == "state" && e.label == "x")
        .unwrap();
    assert!(x.converged, "{x:?}");
    // rk4 at 1 ms on a spring, 5 steps: its error is tiny but not zero.
    assert!(x.errors[1] > 0.0 && x.errors[1] < 1e-9, "{x:?}");
    let shown = screen(&app, 160, 60);
    assert!(shown.contains("± vs rk4 at dt = 1.0000e-4 s"), "{shown}");
    assert!(shown.contains("│ ±  "), "{shown}");
    press(&mut app, KeyCode::Char('u'));
    assert!(app.session.error_bars.is_none());
    assert!(!screen(&app, 160, 60).contains("± vs rk4"));
}
