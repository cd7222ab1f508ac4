//! The app's screens at several sizes and in both layouts (key `L`), the drawing (depth cue,
//! arrows, mass points), and the pictures for slides: the SVG of a screen (key `x`,
//! `tumble shot`) and the asciicast of a run (`tumble record`).
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::buffer::Buffer;
use std::path::{Path, PathBuf};
use tumble::tables::{self, Frame};
use tumble::tui::export;
use tumble::tui::layout::ScreenLayout;
use tumble::tui::{cloth_panel, loop_strip, panels, App, Comparison, Options};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn load(path: &Path) -> tumble::scene::Lesson {
    tumble::scene::load(path).unwrap_or_else(|e| panic!("{e}"))
}

fn app_of(path: &Path, compare: Option<Comparison>) -> App {
    App::new(
        load(path),
        Options {
            ascii: true,
            compare,
            show_timing: false,
        },
    )
}

fn fixture(name: &str) -> App {
    app_of(&root().join("tests/fixtures").join(name), None)
}

fn lesson(name: &str) -> App {
    app_of(&root().join("lessons").join(name), None)
}

fn keys(app: &mut App, text: &str) {
    for c in text.chars() {
        let code = match c {
            '>' => KeyCode::Right,
            c => KeyCode::Char(c),
        };
        app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
    }
}

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
    text(&export::render(app, width, height))
}

/// Lesson 2 (mass points, L not parallel to ω) after 30 frames (t = 0.15 s).
fn lesson_two() -> App {
    let mut app = lesson("02-rigid-body-from-points.toml");
    app.step_frames(30);
    app
}

#[test]
fn screens_at_80x24_120x40_and_200x60() {
    let mut app = fixture("tui-box.toml");
    keys(&mut app, "nnn>>>>nnn");
    for (w, h) in [(80, 24), (120, 40), (200, 60)] {
        insta::assert_snapshot!(format!("numbers_{w}x{h}"), screen(&app, w, h));
    }
    keys(&mut app, "L");
    assert_eq!(app.prefs.layout, ScreenLayout::Stage);
    for (w, h) in [(80, 24), (120, 40)] {
        insta::assert_snapshot!(format!("stage_{w}x{h}"), screen(&app, w, h));
    }
    keys(&mut app, "L");
    assert_eq!(app.prefs.layout, ScreenLayout::Numbers);
}

#[test]
fn lesson_two_shows_its_mass_points_and_the_omega_and_l_arrows() {
    let mut app = lesson_two();
    keys(&mut app, "L");
    let shown = screen(&app, 120, 40);
    insta::assert_snapshot!("lesson2_stage_120x40", shown);
    // Five mass points, drawn as `O` (ASCII) — not single dots.
    let drawing: String = shown
        .lines()
        .take_while(|l| !l.starts_with('└'))
        .collect::<Vec<_>>()
        .join("\n");
    let points = drawing.matches('O').count();
    assert!(
        (3..=5).contains(&points),
        "{points} mass points (5, some may overlap):\n{drawing}"
    );
    // ω and L labelled (ω is `w` in ASCII), and told apart in the legend.
    assert!(drawing.contains('w') && drawing.contains('L'), "{drawing}");
    assert!(shown.contains("ω ang. vel.") && shown.contains("L ang. mom."));
    // `a` hides the arrows and the body axes.
    keys(&mut app, "a");
    let plain = screen(&app, 120, 40);
    assert!(!plain.contains("ang. vel."), "{plain}");
}

#[test]
fn the_omega_and_l_arrows_point_along_their_vectors() {
    // Lesson 2 at t = 0: ω = (0, 0, 8) rad/s and L = (0.012, 0, 0.328) kg·m²/s both point
    // (nearly) along z. From the front (looking along −z) both are seen end-on, towards the
    // viewer: labels `wo` and `Lo` (ω is `w` in ASCII). From the side (z to the right) both
    // are arrows pointing right: heads `>` followed by their labels.
    let mut app = lesson("02-rigid-body-from-points.toml");
    let front = screen(&app, 200, 60);
    assert!(front.contains("wo") && front.contains("Lo"), "{front}");
    keys(&mut app, "v");
    let side = screen(&app, 200, 60);
    for label in [">w", ">L"] {
        let found = side.lines().any(|l| {
            let t: String = l
                .split(' ')
                .filter(|w| !w.is_empty())
                .collect::<Vec<_>>()
                .join("");
            t.contains(label)
        });
        assert!(found, "no arrow head then `{label}` from the side:\n{side}");
    }
}

#[test]
fn hidden_edges_of_the_box_are_dashed() {
    // The fixture's box is turned about z and x: seen from the front, some edges are behind
    // the body and drawn dimmed (dark grey) and dashed.
    let mut app = fixture("tui-box.toml");
    keys(&mut app, ">>>>>t"); // no trail: its dots are grey too
    let buf = export::render(&app, 200, 60);
    let grey = (0..buf.area.height)
        .flat_map(|y| (0..buf.area.width).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let c = &buf[(x, y)];
            c.fg == tumble::tui::theme::HIDDEN && c.symbol() == "."
        })
        .count();
    assert!(grey > 0, "no hidden edge drawn:\n{}", text(&buf));
}

/// Words of `lines`, in order.
fn words(lines: &[String]) -> Vec<String> {
    lines
        .iter()
        .flat_map(|l| l.split_whitespace().map(str::to_string))
        .collect::<Vec<_>>()
}

/// Checks that no number or unit is cut on `shown`: every panel whose title line is shown has
/// every row of `tables::panel_text` in full (the cloth panels too, and their text lines); the
/// status fields are whole; and the loop strip's words, as far as shown, are the words of its
/// full text (a cut word would differ).
fn assert_nothing_cut(app: &App, shown: &str, context: &str) {
    let lines: Vec<&str> = shown.lines().collect();
    let mut all = tables::panels(&app.session.snapshot, app.prefs.frame);
    all.push(panels::essentials_of(app, &app.session.snapshot));
    all.push(tables::body_energy_panel(&app.session.snapshot));
    for c in &app.session.snapshot.cloths {
        let (panel, text) = cloth_panel::panel(c, app.session.snapshot.dt);
        let title = format!("│{}", panel.title);
        if lines.iter().any(|l| l.ends_with(&title)) {
            for t in &text {
                assert!(
                    shown.contains(t.as_str()),
                    "{context}: cloth panel shown without `{t}` in full:\n{shown}"
                );
            }
        }
        all.push(panel);
    }
    for panel in &all {
        let title = format!("│{}", panel.title);
        if !lines.iter().any(|l| l.ends_with(&title)) {
            continue;
        }
        for row in tables::panel_text(panel).iter().skip(1) {
            assert!(
                shown.contains(row.trim_start()),
                "{context}: panel `{}` shown without `{}` in full:\n{shown}",
                panel.title,
                row.trim_start()
            );
        }
    }
    let s = &app.session.snapshot;
    for field in [
        format!("t {} s", tables::number_plain(s.time)),
        format!("dt {} s", tables::number_plain(s.dt)),
        format!("step {}", s.step),
        if s.bodies.is_empty() {
            format!("cloth {}", s.cloths[0].integrator)
        } else {
            format!("integrator {}", s.integrator.name())
        },
    ] {
        assert!(shown.contains(&field), "{context}: no `{field}`:\n{shown}");
    }
    // The strip: under its title line, from the title's column to the right edge, down to
    // the lesson page or the status line.
    let title = lines.iter().enumerate().find_map(|(i, l)| {
        l.find(" the loop —")
            .map(|byte| (i, l[..byte].chars().count()))
    });
    if let Some((top, col)) = title {
        let strip: Vec<String> = lines[top + 1..]
            .iter()
            .take_while(|l| {
                !l.starts_with(" t ")
                    && !l.starts_with(" body ")
                    && !l.starts_with(&format!(" {}", panels::NO_BODY))
                    && !l.starts_with('┌')
            })
            .map(|l| l.chars().skip(col).collect::<String>())
            .collect();
        let full: Vec<String> = loop_strip::lines(app)
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.as_ref()).collect())
            .collect();
        let (shown_words, full_words) = (words(&strip), words(&full));
        for (i, w) in shown_words.iter().enumerate() {
            assert_eq!(
                Some(w),
                full_words.get(i),
                "{context}: loop strip word {i} cut or changed:\n{shown}"
            );
        }
    }
}

#[test]
fn no_number_or_unit_is_cut_at_any_width_from_80_to_240() {
    let mut box_app = fixture("tui-box.toml");
    keys(&mut box_app, "nnn>>>>nnn");
    let mut compare = app_of(
        &root().join("tests/fixtures/tui-box.toml"),
        Some(Comparison::Integrator(
            tumble::physics::Integrator::EulerSeed,
        )),
    );
    keys(&mut compare, ">>>>>nn");
    let mut sheet = fixture("tui-cloth-sheet.toml");
    sheet.step_frames(25);
    let mut trampoline = fixture("tui-cloth-trampoline.toml");
    keys(&mut trampoline, "k");
    trampoline.step_frames(150);
    keys(&mut trampoline, "nnn");
    let mut apps = vec![
        ("box", box_app),
        ("compare", compare),
        ("lesson 2", lesson_two()),
        ("cloth alone", sheet),
        ("cube over a trampoline, compare", trampoline),
    ];
    for (name, app) in &mut apps {
        for layout in [ScreenLayout::Numbers, ScreenLayout::Stage] {
            app.prefs.layout = layout;
            for height in [24, 31, 40, 60] {
                for width in 80..=240 {
                    let shown = screen(app, width, height);
                    let context = format!("{name}, {layout:?}, {width}×{height}");
                    assert_nothing_cut(app, &shown, &context);
                }
            }
        }
    }
}

#[test]
fn at_120x40_the_status_line_is_whole_even_in_compare_mode() {
    let mut app = app_of(
        &root().join("tests/fixtures/tui-box.toml"),
        Some(Comparison::Integrator(
            tumble::physics::Integrator::EulerSeed,
        )),
    );
    keys(&mut app, ">");
    let shown = screen(&app, 120, 40);
    for field in [
        "integrator rk4 vs euler-seed",
        "response impulse",
        "effects gravity",
    ] {
        assert!(shown.contains(field), "no `{field}`:\n{shown}");
    }
}

#[test]
fn lesson_pages_keep_their_86_column_lines_where_the_pane_allows() {
    // Lesson 2's second page has a 71-character formula line; at 200 columns the page pane is
    // wider than 86 and the line shows whole, as written.
    let mut app = lesson("02-rigid-body-from-points.toml");
    app.step_frames(5); // t = 0.025 s ≥ 0.02: the page "L is not parallel to ω"
    let line = "L = I ω = (0.0015 × 8, 0, 0.041 × 8) = (0.012, 0, 0.328) kg·m²/s,";
    assert!(screen(&app, 200, 60).contains(line));
    // In the stage layout the page spans the whole width: whole at 120 columns too.
    keys(&mut app, "L");
    assert!(screen(&app, 120, 40).contains(line));
}

#[test]
fn the_scale_bar_prints_a_round_length() {
    let app = fixture("tui-box.toml");
    let shown = screen(&app, 120, 40);
    let bar = shown
        .lines()
        .find_map(|l| {
            l.find('├').map(|i| {
                l[i..]
                    .split('│')
                    .next()
                    .unwrap_or("")
                    .trim_end()
                    .to_string()
            })
        })
        .expect("a scale bar");
    let length = bar
        .split_whitespace()
        .nth(1)
        .unwrap_or_else(|| panic!("{bar}"));
    // 1, 2 or 5 times a power of ten, at most 3 characters after the point.
    let digits: String = length.chars().filter(|c| c.is_ascii_digit()).collect();
    let first = digits.trim_start_matches('0');
    assert!(
        ["1", "2", "5"].contains(&first.trim_end_matches('0')),
        "{bar}"
    );
    assert!(bar.ends_with(" m"), "{bar}");
}

/// A tiny XML well-formedness check: tags nest and close, attributes are quoted, `&` only
/// starts the five predefined entities. Returns the text content.
fn xml_text(doc: &str) -> String {
    let mut stack: Vec<String> = Vec::new();
    let mut content = String::new();
    let mut rest = doc;
    while let Some(open) = rest.find('<') {
        content.push_str(&check_text(&rest[..open]));
        let close = rest[open..].find('>').expect("unclosed tag") + open;
        let tag = &rest[open + 1..close];
        if let Some(name) = tag.strip_prefix('/') {
            assert_eq!(
                stack.pop().as_deref(),
                Some(name.trim()),
                "mismatched </{name}>"
            );
        } else {
            let name: String = tag
                .chars()
                .take_while(|c| !c.is_whitespace() && *c != '/')
                .collect();
            assert!(!name.is_empty(), "empty tag name in <{tag}>");
            assert_eq!(
                tag.matches('"').count() % 2,
                0,
                "unbalanced quotes in <{tag}>"
            );
            assert!(!tag.contains('<'), "`<` inside <{tag}>");
            if !tag.ends_with('/') {
                stack.push(name);
            }
        }
        rest = &rest[close + 1..];
        if stack.is_empty() {
            assert!(rest.trim().is_empty(), "content after the root element");
        }
    }
    assert!(stack.is_empty(), "unclosed elements {stack:?}");
    content
}

fn check_text(text: &str) -> String {
    assert!(
        !text.contains('>'),
        "raw `>` in text (escaped by the exporter)"
    );
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        let end = rest[i..].find(';').expect("unterminated entity") + i;
        out.push(match &rest[i + 1..end] {
            "amp" => '&',
            "lt" => '<',
            "gt" => '>',
            "quot" => '"',
            "apos" => '\'',
            e => panic!("unknown entity &{e};"),
        });
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    out
}

#[test]
fn the_svg_of_a_screen_parses_and_holds_the_panel_text() {
    let mut app = fixture("tui-box.toml");
    keys(&mut app, ">>>>>");
    let svg = export::svg(&export::render(&app, 120, 40));
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    let content = xml_text(&svg);
    // Every number of the state and energy panels, as the panel prints it.
    let panels = tables::panels(&app.session.snapshot, Frame::World);
    for panel in [&panels[0], &panels[6]] {
        for row in &panel.rows {
            for cell in &row.cells {
                assert!(
                    content.contains(cell.trim()),
                    "`{}` not in the SVG",
                    cell.trim()
                );
            }
        }
    }
    // Colours as in the terminal: the ghost-free body is white, contacts red; the header's
    // "tumble" sits on cyan.
    assert!(svg.contains(r##"fill="#00cdcd""##), "no cyan (the header)");
    // 120 × 40 cells of 8.4 × 17 px.
    assert!(svg.contains(r#"width="1008.0" height="680.0""#));
}

#[test]
fn x_asks_for_an_export_and_the_file_name_names_lesson_and_time() {
    let mut app = fixture("tui-box.toml");
    keys(&mut app, ">>>x");
    assert!(app.ui.export_requested);
    assert_eq!(export::screen_file_name(&app), "tumble-tui-box-t0.030.svg");
    // Rendering is untouched by the request; the event loop writes the file at the
    // terminal's size and clears the request.
    assert_eq!(app.session.snapshot.step, 3);
}

#[test]
fn a_recording_has_an_asciicast_header_and_increasing_event_times() {
    let mut app = fixture("tui-box.toml");
    let cast = export::record(&mut app, 0.2, 100, 30);
    let mut lines = cast.lines();
    let header: serde_json::Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    assert_eq!(header["width"], 100);
    assert_eq!(header["height"], 30);
    let mut last = -1.0;
    let mut events = 0;
    for line in lines {
        let e: serde_json::Value = serde_json::from_str(line).unwrap();
        let t = e[0].as_f64().expect("time");
        assert!(t > last, "time {t} after {last}");
        last = t;
        assert_eq!(e[1], "o");
        let data = e[2].as_str().expect("data");
        assert!(data.contains("\x1b[H") && data.contains("the loop"));
        events += 1;
    }
    // 0.2 s at real time, 30 frames per second: frames at 0, 1/30, …, 6/30 s: 7 events, and
    // the last frame shows t = 0.2 s (dt = 0.01 s: 20 steps).
    assert_eq!(events, 7);
    assert!((last - 0.2).abs() < 1e-6, "{last}");
    assert_eq!(app.session.snapshot.step, 20);
}

#[test]
fn a_recording_never_shows_a_pause_it_does_not_make() {
    // Lesson 1's pages start at 0.01, 0.25 and 0.5 s: a run of the app pauses at each, but the
    // recording runs on through them, so only its last frame (the end) may say "paused".
    let mut app = lesson("01-the-loop.toml");
    let cast = export::record(&mut app, 0.6, 120, 40);
    let frames: Vec<&str> = cast.lines().skip(1).collect();
    for (i, line) in frames[..frames.len() - 1].iter().enumerate() {
        assert!(!line.contains("paused"), "frame {i} shows a pause: {line}");
        assert!(!line.contains("Enter continues"), "frame {i}: {line}");
    }
    assert_eq!(app.session.snapshot.step, 60);
}

#[test]
fn shot_and_record_on_the_command_line() {
    use assert_cmd::Command;
    let dir = std::env::temp_dir().join(format!("tumble-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = root().join("tests/fixtures/tui-box.toml");
    let svg = dir.join("box.svg");
    Command::cargo_bin("tumble")
        .unwrap()
        .arg("shot")
        .arg(&file)
        .args(["--at", "0.5", "--size", "100x30", "--svg"])
        .arg(&svg)
        .assert()
        .success();
    let content = xml_text(&std::fs::read_to_string(&svg).unwrap());
    assert!(content.contains("0.500000 s"), "{content}");
    let cast = dir.join("box.cast");
    Command::cargo_bin("tumble")
        .unwrap()
        .arg("record")
        .arg(&file)
        .args(["--duration", "0.1", "--out"])
        .arg(&cast)
        .assert()
        .success();
    let text = std::fs::read_to_string(&cast).unwrap();
    let header: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(
        (header["width"].clone(), header["height"].clone()),
        (120.into(), 40.into())
    );
    // Bad sizes are one-line errors, exit 2.
    let bad = Command::cargo_bin("tumble")
        .unwrap()
        .arg("shot")
        .arg(&file)
        .args(["--size", "60x20", "--svg"])
        .arg(&svg)
        .assert()
        .code(2);
    let stderr = String::from_utf8_lossy(&bad.get_output().stderr).into_owned();
    assert!(stderr.contains("80x24"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_bowling_ball_is_a_circle_whose_meridian_turns_and_the_race_ramp_is_hatched() {
    // The bowling ball at 0.5 s, in the stage layout at 80×24: its silhouette and meridian (a
    // circle seen from the front) and its equator, edge-on, a line through the centre that
    // turns as the ball rolls (here by ½ α t² = 6.13 rad, nearly level again); the race at 1 s: the ramp's line with its `\` hatches (leaning
    // down-right, into the solid below a slope that goes down toward +x).
    let mut app = lesson("20-bowling-ball.toml");
    app.step_frames(500);
    keys(&mut app, "L");
    let ball = screen(&app, 80, 24);
    insta::assert_snapshot!("bowling_ball_stage_80x24", ball);
    let mut race = lesson("19-the-race.toml");
    race.step_frames(1000);
    keys(&mut race, "L");
    let ramp = screen(&race, 80, 24);
    assert!(ramp.contains('\\'), "{ramp}");
    insta::assert_snapshot!("race_stage_80x24", ramp);
}

/// The numbers of a row of `tumble walk FILE --frames N`'s output, by its label.
fn walk_row(file: &str, frames: u64, label: &str) -> Vec<String> {
    let out = assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .arg("walk")
        .arg(file)
        .args(["--frames", &frames.to_string()])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).into_owned();
    let line = text
        .lines()
        .rev()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no row {label} in\n{text}"));
    line.trim_start()[label.len()..]
        .split_whitespace()
        .filter(|w| w.parse::<f64>().is_ok())
        .map(str::to_string)
        .collect()
}

#[test]
fn the_pendulum_shows_its_pivot_rod_and_the_walks_joint_numbers() {
    // Lesson 25 after 592 frames (dt = 1 ms: t = 0.592 s, the bob at the bottom, a quarter
    // period T/4 = 2.367842/4 = 0.591960 s): the bob is under the pivot at the origin, the rod
    // vertical, the rod's pull 3 m g = 29.43 N up the rod (the lesson's second page); |C| is
    // rounding noise (projection keeps the length).
    let mut app = lesson("25-the-pendulum.toml");
    app.step_frames(592);
    let error = walk_row("25-the-pendulum", 592, "|C|");
    let force = walk_row("25-the-pendulum", 592, "F on bob");
    assert_eq!(force.len(), 3, "{force:?}");
    let fy: f64 = force[1].parse().unwrap();
    assert!((fy - 29.43).abs() < 0.01, "F_y = {fy}, 3 m g = 29.43 N");
    for (w, h) in [(120, 40), (80, 24)] {
        let shown = screen(&app, w, h);
        assert!(shown.contains("joint rod: distance"), "{w}x{h}\n{shown}");
        // The pivot `o` alone in its cell of the drawing, the vertical rod `|` under it.
        let rows: Vec<Vec<char>> = shown.lines().map(|l| l.chars().collect()).collect();
        let pivot = rows.iter().enumerate().find_map(|(r, row)| {
            let c = row.iter().position(|&ch| ch == 'o')?;
            let blank = |k: usize| row.get(k).is_some_and(|ch| *ch == ' ');
            (row.first() == Some(&'│') && blank(c - 1) && blank(c + 1)).then_some((r, c))
        });
        let (r, c) = pivot.unwrap_or_else(|| panic!("no pivot at {w}x{h}\n{shown}"));
        assert_eq!(rows[r + 1].get(c), Some(&'|'), "no rod at {w}x{h}\n{shown}");
        let c_line = shown
            .lines()
            .find(|l| l.contains("|C|"))
            .unwrap_or_else(|| panic!("no |C| at {w}x{h}\n{shown}"));
        assert!(c_line.contains(&error[0]), "{error:?} vs {c_line}");
        let f_line = shown
            .lines()
            .find(|l| l.contains("F on bob"))
            .unwrap_or_else(|| panic!("no F at {w}x{h}\n{shown}"));
        for cell in &force {
            assert!(f_line.contains(cell.as_str()), "{force:?} vs {f_line}");
        }
        insta::assert_snapshot!(format!("pendulum_592_{w}x{h}"), shown);
    }
}

#[test]
fn a_hinge_seen_end_on_is_a_circled_dot_and_a_spring_a_zigzag() {
    // Lesson 26: a cube on a hinge at the origin, axis z (towards the viewer of the front
    // view): the pivot is drawn `⊙` (ASCII `o`), the arm from the cube's barycenter to it.
    let app = lesson("26-the-physical-pendulum.toml");
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("joint edge: hinge"), "{shown}");
    assert!(shown.contains(" axis "), "{shown}");
    // The spring fixture at t = 0: the block at y = 0, the spring's world end at y = 1 straight
    // above; drawn as a zigzag, `/` and `\` alternating up the column between them.
    let app = fixture("tui-spring.toml");
    let shown = screen(&app, 80, 24);
    let drawing: Vec<&str> = shown.lines().skip(2).take(8).collect();
    let slashes = drawing.iter().filter(|l| l.contains('/')).count();
    let backslashes = drawing.iter().filter(|l| l.contains('\\')).count();
    assert!(slashes >= 2 && backslashes >= 2, "{shown}");
    assert!(shown.contains("spring s: block – world"), "{shown}");
    // tension = k (|d| − ℓ₀) = 100 · (1 − 0.5) = 50 N.
    assert!(shown.contains("50.000000"), "{shown}");
    insta::assert_snapshot!("spring_80x24", shown);
}

/// Runs the app as the event loop does (running, pausing at page times) to its next pause.
fn run_to_next_pause(app: &mut App) {
    app.ui.running = true;
    app.step_frames(10_000_000);
    app.ui.running = false;
}

#[test]
fn a_pause_line_never_hides_a_panel() {
    // At a page's pause the status line says "page 2/4 … Enter continues". That notice takes
    // a row of the key hints, never one of the main area: the drawing, panels, page and loop
    // strip are the same with the notice as without it (before, at 120×40 the energy panel of
    // lessons 5, 8, 13, 14 and 15 gave up its row at every pause).
    for name in [
        "05-ground-collision.toml",
        "08-climbing-bug.toml",
        "13-what-vertices-miss.toml",
        "14-head-on.toml",
        "15-stack.toml",
    ] {
        let mut app = lesson(name);
        for pause in 1..=2 {
            run_to_next_pause(&mut app);
            assert!(app.ui.notice.is_some(), "{name}: no pause {pause}");
            let mut quiet = app.clone();
            quiet.ui.notice = None;
            for layout in [ScreenLayout::Numbers, ScreenLayout::Stage] {
                app.prefs.layout = layout;
                quiet.prefs.layout = layout;
                for (w, h) in [(80, 24), (100, 31), (120, 40), (200, 60)] {
                    let (with, without) = (screen(&app, w, h), screen(&quiet, w, h));
                    let status = 4; // the status bar is at most 4 rows
                    let main = |s: &str| {
                        s.lines()
                            .take(usize::from(h) - status)
                            .map(str::to_string)
                            .collect::<Vec<_>>()
                    };
                    assert_eq!(
                        main(&with),
                        main(&without),
                        "{name} pause {pause}, {layout:?} {w}×{h}: the notice moved the screen:\n{with}"
                    );
                    let notice = app.ui.notice.clone().unwrap();
                    let head: String = notice.chars().take(20).collect();
                    assert!(
                        with.contains(&head),
                        "{name} {w}×{h}: no `{notice}`:\n{with}"
                    );
                }
            }
        }
    }
}

/// Whether the panel titled `title` is shown on `shown` (its title line, whole or with the
/// note of a panel shown in part).
fn panel_shown(shown: &str, title: &str) -> bool {
    let key = format!("│{title}");
    shown.lines().any(|l| {
        l.rfind(&key).is_some_and(|i| {
            let rest = &l[i + key.len()..];
            rest.is_empty() || rest.starts_with(" (")
        })
    })
}

#[test]
fn the_panels_a_page_quotes_are_shown_at_every_width_from_80_to_240() {
    // Each page of these lessons quotes panels: by its live numbers (lesson 1's {{Py}} and
    // {{y}}: momentum and state; lesson 16's {{vy@…}}, {{energy@4}}) or by its `panels` key
    // (lesson 1's first page: state, momentum, angular momentum; lesson 10: angular velocity,
    // for ωbody; lesson 14: each body's energy and the system's momentum). At every size each
    // quoted panel is shown (whole, or the rows that fit), the others yield.
    use tumble::scene::PagePanel;
    for name in [
        "01-the-loop.toml",
        "10-tennis-racket.toml",
        "14-head-on.toml",
        "16-trampoline.toml",
    ] {
        let mut app = lesson(name);
        let times: Vec<f64> = app.session.lesson.pages.iter().map(|p| p.at).collect();
        let mut quoting = 0;
        for at in times {
            let steps = tumble::tui::timeline::step_at(at, app.session.snapshot.dt);
            app.step_frames(steps - app.session.snapshot.step);
            let quoted = panels::quoted(&app);
            if quoted.is_empty() {
                continue;
            }
            quoting += 1;
            let titles = panels::titles(&app);
            for height in [24, 31, 40, 60] {
                for width in 80..=240 {
                    let shown = screen(&app, width, height);
                    for key in &quoted {
                        let wanted: Vec<&String> = titles
                            .iter()
                            .filter(|(k, _)| *k == Some(*key))
                            .map(|(_, t)| t)
                            .collect();
                        // Several cloths or joints: at least the first.
                        let first = wanted.first().unwrap_or_else(|| {
                            panic!("{name} at {at} s quotes {key:?}, which it has not")
                        });
                        assert!(
                            panel_shown(&shown, first),
                            "{name} at {at} s, {width}×{height}: quoted panel `{first}` not shown:\n{shown}"
                        );
                    }
                    assert_nothing_cut(
                        &app,
                        &shown,
                        &format!("{name} at {at} s, {width}×{height}"),
                    );
                }
            }
            // The stage layout's essentials hold the rows of the panels the page names.
            app.prefs.layout = ScreenLayout::Stage;
            let essentials = panels::essentials_of(&app, &app.session.snapshot);
            for key in &app
                .session
                .lesson
                .page_at(app.session.snapshot.time)
                .unwrap()
                .1
                .panels
            {
                if *key == PagePanel::AngularVelocity {
                    assert!(
                        essentials.rows.iter().any(|r| r.label == "ωbody"),
                        "{name} at {at} s: no ωbody in the essentials"
                    );
                    let shown = screen(&app, 120, 40);
                    assert!(shown.contains("ωbody"), "{name}:\n{shown}");
                }
            }
            app.prefs.layout = ScreenLayout::Numbers;
        }
        assert!(quoting >= 2, "{name}: {quoting} pages quote panels");
    }
}

#[test]
fn shot_and_record_set_the_screen_as_the_app_keys_do() {
    // `--view top` (key v twice), `--no-arrows` (key a), `--graph` (key g), `--compare NAME`
    // (key k): each shows in the exported text as it does on the app's screen.
    use assert_cmd::Command;
    let dir = std::env::temp_dir().join(format!("tumble-screen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = root().join("tests/fixtures/tui-box.toml");
    let shot = |args: &[&str]| -> String {
        let svg = dir.join("s.svg");
        Command::cargo_bin("tumble")
            .unwrap()
            .arg("shot")
            .arg(&file)
            .args(["--at", "0.05", "--svg"])
            .arg(&svg)
            .args(args)
            .assert()
            .success();
        xml_text(&std::fs::read_to_string(&svg).unwrap())
    };
    let plain = shot(&[]);
    assert!(
        plain.contains("front x–y") && plain.contains("ang. vel."),
        "{plain}"
    );
    let top = shot(&["--view", "top"]);
    assert!(
        top.contains("top x–z") && !top.contains("front x–y"),
        "{top}"
    );
    assert!(shot(&["--view", "side"]).contains("side z–y"));
    let bare = shot(&["--no-arrows"]);
    assert!(!bare.contains("ang. vel."), "{bare}");
    let graph = shot(&["--graph"]);
    assert!(
        graph.contains("energy, J") && !graph.contains("front x–y"),
        "{graph}"
    );
    let ghost = shot(&["--compare", "euler-seed"]);
    assert!(ghost.contains("vs euler-seed"), "{ghost}");
    // The same options for record; a bad one is a one-line error, exit 2.
    let cast = dir.join("r.cast");
    Command::cargo_bin("tumble")
        .unwrap()
        .arg("record")
        .arg(&file)
        .args(["--duration", "0.05", "--view", "top", "--out"])
        .arg(&cast)
        .assert()
        .success();
    let frames = std::fs::read_to_string(&cast).unwrap();
    assert!(
        frames.lines().skip(1).all(|l| l.contains("top x")),
        "{frames}"
    );
    for bad in [&["--view", "diagonal"][..], &["--compare", "rk4"][..]] {
        let out = Command::cargo_bin("tumble")
            .unwrap()
            .arg("shot")
            .arg(&file)
            .args(["--svg"])
            .arg(dir.join("bad.svg"))
            .args(bad)
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        assert!(stderr.contains(bad[1]), "{bad:?}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn several_bodies_flying_apart_all_stay_in_the_drawing() {
    // Lesson 14: `left` stops at x = −0.2 m, `right` leaves at 1 m/s (e = 1): by t = 2 s (the
    // lesson's duration) they are about 1.7 m apart, by t = 5 s 4.7 m — wider than the 8 body
    // diameters the view may otherwise grow to (8 × 2 × 0.173 = 2.77 m). Before, the view slid
    // to their middle and kept its size: part of one cube at 2 s, nothing at 5 s. Every
    // vertex of every body must map inside the drawing.
    let mut app = lesson("14-head-on.toml");
    for (frames, t) in [(2000, 2.0), (3000, 5.0)] {
        app.step_frames(frames);
        assert!((app.session.snapshot.time - t).abs() < 1e-9);
        for (w, h) in [(80, 24), (120, 40)] {
            let main = ratatui::layout::Rect::new(0, 1, w, h - 4);
            let drawing = tumble::tui::screen::main_areas(&app, main).drawing;
            let (cols, rows) = (drawing.width - 2, drawing.height - 2);
            let mapping =
                tumble::tui::viewport::Mapping::fit(&app.ui.region, app.prefs.axis, cols, rows);
            for body in &app.session.snapshot.bodies {
                for v in &body.vertices {
                    let (hx, vy) = app.prefs.axis.project(v);
                    let (c, r) = mapping.cell(hx, vy);
                    assert!(
                        (0.0..=f64::from(cols)).contains(&c)
                            && (0.0..=f64::from(rows)).contains(&r),
                        "t = {t} s, {w}×{h}: {} at cell ({c:.1}, {r:.1}) outside {cols}×{rows}",
                        body.name
                    );
                }
            }
            // And drawn: the cubes' barycenters `@` (at 80 columns a cube is a cell or two,
            // under the arrows).
            if w < 120 {
                continue;
            }
            let shown = screen(&app, w, h);
            let drawing_text: String = shown
                .lines()
                .take_while(|l| !l.starts_with('└'))
                .collect::<Vec<_>>()
                .join("\n");
            assert!(
                drawing_text.matches('@').count() >= 2,
                "t = {t} s:\n{shown}"
            );
        }
    }
}

#[test]
fn page_scrolling_stops_at_the_pages_end() {
    // Lesson 5's second page is 18 lines at 120×40 (its formulas kept whole, cut with `…`)
    // and its pane shows 10: PgDn stops at the last 10 (lines 9-18), however often it is pressed, so one PgUp moves the page back
    // at once (before, every extra PgDn had to be undone: five PgUp to come back).
    let mut app = lesson("05-ground-collision.toml");
    run_to_next_pause(&mut app);
    let pgdn = KeyEvent::new(KeyCode::PageDown, KeyModifiers::NONE);
    let pgup = KeyEvent::new(KeyCode::PageUp, KeyModifiers::NONE);
    let position = |s: &str| -> String {
        let l = s
            .lines()
            .find(|l| l.contains(" of 18 "))
            .unwrap_or_else(|| panic!("{s}"));
        let i = l.find(" of 18 ").unwrap();
        l[..i].rsplit(' ').next().unwrap().to_string()
    };
    screen(&app, 120, 40);
    for _ in 0..12 {
        app.handle_key(&pgdn);
        screen(&app, 120, 40);
    }
    let end = screen(&app, 120, 40);
    assert_eq!(position(&end), "9-18", "{end}");
    app.handle_key(&pgup);
    let back = screen(&app, 120, 40);
    assert_eq!(position(&back), "6-15", "{back}");
}

#[test]
fn the_energy_graphs_labels_never_overlap_and_its_legend_is_out_of_the_curves() {
    // Lesson 5 at t = 0.42 s, the energy view (key g). Each y-axis label is printed whole,
    // alone on its row: one of the axis's own labels (lo, mid, hi). Before, in a drift chart
    // three rows tall the mid label `0` was drawn over `-9.9e-6`: `09.9e-6`. The legend is
    // in the chart's title line, where no curve runs.
    use tumble::tui::energy_graph::axis_label;
    let mut app = lesson("05-ground-collision.toml");
    app.step_frames(420);
    keys(&mut app, "g");
    for (w, h) in [(80, 24), (100, 31), (120, 40), (200, 60)] {
        let shown = screen(&app, w, h);
        let mut allowed = Vec::new();
        for r in [
            app.session.series.energy_axis,
            app.session.series.drift_axis,
        ] {
            let span = r.hi - r.lo;
            for x in [r.lo, 0.5 * (r.lo + r.hi), r.hi] {
                allowed.push(axis_label(x, span));
            }
        }
        let mut labels = 0;
        for line in shown.lines().skip(1) {
            // A plot row: `│LABEL │…` (the label column, then the y axis).
            let Some(rest) = line.strip_prefix('│') else {
                continue;
            };
            let Some((label, _)) = rest.split_once('│') else {
                continue;
            };
            let label = label.trim();
            if label.is_empty() || label.contains('─') || label.len() > 12 {
                continue;
            }
            assert!(
                allowed.iter().any(|a| a == label),
                "{w}×{h}: y label `{label}` is none of {allowed:?}:\n{shown}"
            );
            labels += 1;
        }
        assert!(labels >= 4, "{w}×{h}: {labels} labels:\n{shown}");
        assert!(
            shown.contains("energy, J ━ kinetic ━ potential ━ total ")
                || shown.contains("energy, J ━ K ━ V ━ E "),
            "{w}×{h}: legend cut:\n{shown}"
        );
    }
}

/// A teacher's own lesson (a file of theirs, not a bundled one) with a live number and a
/// prediction: `shot` and `record` show the number filled in and the prediction's simulated
/// value, and a recording never asks for a guess it cannot take.
#[test]
fn a_teachers_lesson_with_live_numbers_and_a_prediction_in_shot_and_record() {
    use assert_cmd::Command;
    let dir = std::env::temp_dir().join(format!("tumble-teacher-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 1 kg cube dropped from y = 2 m, symplectic Euler, dt = 0.01 s: vy(0.5) = −g·0.5 =
    // −4.905 m/s, y(0.6) = 2 − g·0.01²·60·61/2 = 0.204770 m (no contact before).
    let file = dir.join("drop.toml");
    std::fs::write(
        &file,
        r#"title = "drop"
[scene]
dt = 0.01
duration = 0.8
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]

[[body]]
name = "cube"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [0.0, 2.0, 0.0]

[[page]]
at = 0.0
title = "Start"
text = "Let go."

[[page]]
at = 0.5
title = "Falling"
text = "vy = {{cube.vy}} now."
predict = { quantity = "cube.y", at = 0.6 }
"#,
    )
    .unwrap();
    let shot = |at: &str, args: &[&str]| -> String {
        let svg = dir.join("s.svg");
        Command::cargo_bin("tumble")
            .unwrap()
            .arg("shot")
            .arg(&file)
            .args(["--at", at, "--size", "160x50", "--svg"])
            .arg(&svg)
            .args(args)
            .assert()
            .success();
        xml_text(&std::fs::read_to_string(&svg).unwrap())
    };
    let before = shot("0.55", &[]);
    assert!(before.contains("vy = -4.905000 m/s now."), "{before}");
    assert!(
        before.contains("what will cube.y be at t = 0.6 s"),
        "{before}"
    );
    let after = shot("0.7", &[]);
    assert!(after.contains("simulated 0.204770 m"), "{after}");
    assert!(!after.contains("{{"), "{after}");
    // The quantity graph, as key p sets it; an unknown quantity is a one-line error, exit 2.
    let plot = shot("0.7", &["--plot", "cube.vy", "--plot-x", "cube.y"]);
    assert!(
        plot.contains("cube.vy, m/s against cube.y, m (phase portrait)"),
        "{plot}"
    );
    let bad = Command::cargo_bin("tumble")
        .unwrap()
        .arg("shot")
        .arg(&file)
        .args(["--plot", "cube.height", "--svg"])
        .arg(dir.join("bad.svg"))
        .assert()
        .code(2);
    let err = String::from_utf8_lossy(&bad.get_output().stderr).to_string();
    assert!(
        err.contains("--plot cube.height") && err.contains("cube.vy") && err.lines().count() == 1,
        "{err}"
    );
    // The recording: the number filled in on every frame of page 2, the prediction's value
    // at the end, never "Enter asks for your guess" (it runs on) nor a "{{".
    let cast = dir.join("r.cast");
    Command::cargo_bin("tumble")
        .unwrap()
        .arg("record")
        .arg(&file)
        .args(["--duration", "0.7", "--size", "160x50", "--out"])
        .arg(&cast)
        .assert()
        .success();
    let text = std::fs::read_to_string(&cast).unwrap();
    let frames: Vec<&str> = text.lines().skip(1).collect();
    assert!(frames.iter().any(|f| f.contains("vy = -4.905000 m/s now.")));
    assert!(frames
        .iter()
        .all(|f| !f.contains("Enter asks") && !f.contains("{{")));
    assert!(
        frames.last().unwrap().contains("simulated 0.204770 m"),
        "{}",
        frames.last().unwrap()
    );
    std::fs::remove_dir_all(&dir).ok();
}
