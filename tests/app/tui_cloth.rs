//! The app with cloths: a sheet alone (no rigid body) and a cube over a small trampoline, as
//! screens at 120×40 and 80×24; the cloth panel's numbers are `walk`'s; pinned particles are
//! drawn where their position projects; `shot` and `record` take a scene of cloths only.
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use std::path::PathBuf;
use tumble::tui::layout::ScreenLayout;
use tumble::tui::viewport::Mapping;
use tumble::tui::{cloth_panel, export, screen, status_bar, theme, App, Options, View};

const SHEET: &str = "tests/fixtures/tui-cloth-sheet.toml";
const TRAMPOLINE: &str = "tests/fixtures/tui-cloth-trampoline.toml";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn app(path: &str, ascii: bool) -> App {
    let lesson = tumble::scene::load(&root().join(path)).unwrap_or_else(|e| panic!("{e}"));
    App::new(
        lesson,
        Options {
            ascii,
            compare: None,
            show_timing: false,
        },
    )
}

fn keys(app: &mut App, text: &str) {
    for c in text.chars() {
        let code = match c {
            '>' => KeyCode::Right,
            '\t' => KeyCode::Tab,
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

fn screen_text(app: &App, width: u16, height: u16) -> String {
    text(&export::render(app, width, height))
}

/// `tumble walk FILE --frames N`'s output.
fn walk(path: &str, frames: u64) -> String {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(["walk", path, "--frames", &frames.to_string()])
        .current_dir(root())
        .output()
        .expect("tumble runs");
    assert_eq!(out.status.code(), Some(0));
    String::from_utf8(out.stdout).expect("utf-8")
}

/// The numbers of each row of the last cloth table in `walk`'s output: (label, numbers).
fn walk_cloth_rows(walk: &str, name: &str) -> Vec<(String, Vec<String>)> {
    let title = format!("cloth {name}: ");
    let start = walk.rfind(&title).expect("a cloth table");
    walk[start..]
        .lines()
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter(|l| !l.contains(':'))
        .map(|l| {
            let l = l.trim();
            // The label ends where the first number starts (two spaces or more before it).
            let cut = l.find("  ").unwrap_or(l.len());
            let label = l[..cut].trim().to_string();
            let numbers = l[cut..]
                .split_whitespace()
                .filter(|w| w.parse::<f64>().is_ok())
                .map(str::to_string)
                .collect();
            (label, numbers)
        })
        .collect()
}

/// The sheet after 25 frames (t = 0.05 s): sagging, the corners pinned.
fn sheet() -> App {
    let mut app = app(SHEET, true);
    app.step_frames(25);
    app
}

/// The cube over the trampoline after 150 frames (t = 0.3 s): the cube has just landed.
fn trampoline() -> App {
    let mut app = app(TRAMPOLINE, true);
    app.step_frames(150);
    app
}

#[test]
fn a_sheet_alone_at_120x40_and_80x24() {
    let mut app = sheet();
    insta::assert_snapshot!("sheet_120x40", screen_text(&app, 120, 40));
    insta::assert_snapshot!("sheet_80x24", screen_text(&app, 80, 24));
    // From above, the grid itself.
    keys(&mut app, "vv");
    insta::assert_snapshot!("sheet_top_120x40", screen_text(&app, 120, 40));
    // The particle step in the loop strip, after integrate.
    keys(&mut app, "nnn");
    insta::assert_snapshot!("sheet_after_integrate_120x40", screen_text(&app, 120, 40));
}

/// `c` changes how particles touch too (each response has a particle law): in a scene of
/// cloths only it cycles the response, the status bar names it and the collide strip shows
/// that law's formula.
#[test]
fn in_a_cloth_scene_c_changes_the_particles_contact_law_and_the_strip_says_which() {
    let mut app = sheet();
    keys(&mut app, "nnnn");
    let strip = |app: &App| screen_text(app, 120, 40);
    let first = strip(&app);
    assert!(first.contains("response impulse"), "{first}");
    assert!(first.contains("x ← x + depth·n"), "{first}");
    keys(&mut app, "c");
    let soft = strip(&app);
    assert!(soft.contains("response soft-step"), "{soft}");
    assert!(soft.contains("soft row u'"), "{soft}");
    assert!(!soft.contains("x ← x + depth·n"), "{soft}");
    keys(&mut app, "c");
    let seed = strip(&app);
    assert!(seed.contains("response seed"), "{seed}");
    assert!(seed.contains("v ← −0.4·v"), "{seed}");
    keys(&mut app, "c");
    assert!(strip(&app).contains("response impulse"));
}

#[test]
fn a_cube_over_a_trampoline_at_120x40_and_80x24() {
    let mut app = trampoline();
    insta::assert_snapshot!("trampoline_120x40", screen_text(&app, 120, 40));
    insta::assert_snapshot!("trampoline_80x24", screen_text(&app, 80, 24));
    keys(&mut app, "L");
    insta::assert_snapshot!("trampoline_stage_120x40", screen_text(&app, 120, 40));
    // Both methods in the strip after integrate: the body's, then the sheet's particle step.
    keys(&mut app, "Lnnn");
    insta::assert_snapshot!(
        "trampoline_after_integrate_120x40",
        screen_text(&app, 120, 40)
    );
}

#[test]
fn the_cloth_panel_shows_walks_numbers() {
    // The app and `walk` step the same world the same number of frames: every number of
    // walk's cloth table (max stretch, T and U, max speed, 2/ω_max, h*, dt, dt/h*) is on the
    // app's screen, on the line of the same label.
    for (path, name, frames) in [(SHEET, "sheet", 25), (TRAMPOLINE, "trampoline", 150)] {
        let mut app = app(path, true);
        app.step_frames(frames);
        let shown = screen_text(&app, 160, 60);
        let rows = walk_cloth_rows(&walk(path, frames), name);
        assert_eq!(rows.len(), 5, "{rows:?}");
        // The app shows `2/ω_max, h*, dt` as two rows: `2/ω_max, h*` and `dt`.
        let rows = rows
            .into_iter()
            .flat_map(|(label, numbers)| match label.strip_suffix(", dt") {
                Some(head) => vec![
                    (head.to_string(), numbers[..2].to_vec()),
                    ("dt".to_string(), numbers[2..].to_vec()),
                ],
                None => vec![(label, numbers)],
            });
        for (label, numbers) in rows {
            let line = shown
                .lines()
                .find(|l| l.contains(&format!("│ {label} ")))
                .unwrap_or_else(|| panic!("{path}: no `{label}` row:\n{shown}"));
            let expected = numbers.join(" ");
            let seen = line
                .split_whitespace()
                .filter(|w| w.parse::<f64>().is_ok())
                .collect::<Vec<_>>()
                .join(" ");
            assert!(
                seen.ends_with(&expected),
                "{path}: `{label}` shows `{seen}`, walk `{expected}`"
            );
        }
    }
}

#[test]
fn the_explicit_limit_is_named_when_dt_exceeds_it() {
    // The trampoline's h* = 1.4223e-3 s (walk: 2/ω_max, h*) < dt = 2e-3 s, but its
    // integrator is implicit-euler: not bounded. The sheet (symplectic-euler, h* =
    // 4.0352e-3 s) at dt = 2e-3 s is at 0.4956 ≈ 0.50 × h*.
    let shown = screen_text(&trampoline(), 160, 60);
    assert!(shown.contains("implicit: not bounded by h*"), "{shown}");
    let shown = screen_text(&sheet(), 160, 60);
    assert!(shown.contains("below the limit: dt = 0.50 × h*"), "{shown}");
    // A sheet above its limit (the CLI fixture: dt = 1.1 × 2/ω_max, undamped): said so.
    let above = app("tests/fixtures/cloth/sheet-alone.toml", true);
    let view = &above.session.snapshot.cloths[0];
    assert!(
        cloth_panel::verdict(view, above.session.snapshot.dt)
            .starts_with("above the limit: dt = 1.10"),
        "{}",
        cloth_panel::verdict(view, above.session.snapshot.dt)
    );
    assert!(screen_text(&above, 160, 60).contains("above the limit: dt = 1.10 × h*"));
}

/// The sheet drawn in Braille.
fn app_of_braille() -> App {
    app(SHEET, false)
}

/// The rectangle the projection draws in (inside its border, above its legend line).
fn drawing_rect(app: &App, width: u16, height: u16) -> Rect {
    let status = status_bar::height(app, width, height);
    let main = Rect::new(0, 1, width, height - 1 - status);
    let pane = screen::main_areas(app, main).drawing;
    Rect::new(pane.x + 1, pane.y + 1, pane.width - 2, pane.height - 3)
}

#[test]
fn pinned_particles_are_drawn_where_their_positions_project() {
    // From above (x → right, z down) the sheet's four pinned corners are four distinct cells:
    // each holds an `x` in the pinned colour, at the cell its position maps to.
    let mut app = sheet();
    keys(&mut app, "vv");
    let (width, height) = (120, 40);
    let buf = export::render(&app, width, height);
    let area = drawing_rect(&app, width, height);
    let mapping = Mapping::fit(&app.ui.region, app.prefs.axis, area.width, area.height);
    let cloth = &app.session.world.cloths()[0];
    let mut checked = 0;
    for (k, _) in cloth.pinned.iter().enumerate().filter(|(_, p)| **p) {
        let (h, v) = app.prefs.axis.project(&cloth.positions[k]);
        let (c, r) = mapping.cell(h, v);
        let cell = &buf[(area.x + c.floor() as u16, area.y + r.floor() as u16)];
        assert_eq!(
            (cell.symbol(), cell.fg),
            ("x", theme::PINNED),
            "pinned particle {k} at cell ({c:.1}, {r:.1}):\n{}",
            text(&buf)
        );
        checked += 1;
    }
    assert_eq!(checked, 4, "corners");
    // No other cell of the drawing is a pinned mark.
    let marks = (area.y..area.y + area.height)
        .flat_map(|y| (area.x..area.x + area.width).map(move |x| (x, y)))
        .filter(|&p| buf[p].fg == theme::PINNED)
        .count();
    assert_eq!(marks, 4, "{}", text(&buf));
    // In Braille the marks are printed by the canvas, which rounds positions its own way:
    // each corner's `x` is within one cell of where its position maps.
    let mut braille = app_of_braille();
    braille.step_frames(25);
    keys(&mut braille, "vv");
    let buf = export::render(&braille, width, height);
    let cloth = &braille.session.world.cloths()[0];
    for (k, _) in cloth.pinned.iter().enumerate().filter(|(_, p)| **p) {
        let (h, v) = braille.prefs.axis.project(&cloth.positions[k]);
        let (c, r) = mapping.cell(h, v);
        let near = (-1..=1).any(|dc: i32| {
            (-1..=1).any(|dr: i32| {
                let x = (i32::from(area.x) + c.floor() as i32 + dc) as u16;
                let y = (i32::from(area.y) + r.floor() as i32 + dr) as u16;
                let cell = &buf[(x, y)];
                cell.symbol() == "x" && cell.fg == theme::PINNED
            })
        });
        assert!(
            near,
            "Braille: no pinned mark near particle {k}:\n{}",
            text(&buf)
        );
    }
}

#[test]
fn a_scene_of_cloths_only_works_in_every_view_without_a_panic() {
    let mut app = app(SHEET, false);
    // Tab has no body to pick, and says so.
    keys(&mut app, "\t");
    assert_eq!(
        app.ui.notice.as_deref(),
        Some("no rigid body in this scene: Tab has nothing to pick")
    );
    // Phases, frames, step back, axes, frame, trail, arrows, layouts, compare, graph, study.
    keys(&mut app, "nnnn>>>>vvvftaic,,e");
    assert!(
        matches!(app.ui.overlay, tumble::tui::Overlay::Settings(_)),
        "the form opens on cloths only"
    );
    app.ui.overlay = tumble::tui::Overlay::None;
    for (w, h) in [(80, 24), (120, 40), (200, 60)] {
        for layout in [ScreenLayout::Numbers, ScreenLayout::Stage] {
            app.prefs.layout = layout;
            let shown = screen_text(&app, w, h);
            assert!(shown.contains("no rigid body in this scene"), "{shown}");
        }
    }
    keys(&mut app, "k");
    assert!(app.session.ghost.is_some());
    keys(&mut app, ">>");
    screen_text(&app, 120, 40);
    keys(&mut app, "g");
    assert_eq!(app.ui.view, View::Energy);
    screen_text(&app, 120, 40);
    keys(&mut app, "s");
    assert_eq!(app.ui.view, View::Study);
    let shown = screen_text(&app, 120, 40);
    assert!(shown.contains("study of"), "{shown}");
    assert!(
        app.session.study.is_some(),
        "the study runs on cloths only, as `tumble study` does"
    );
    keys(&mut app, "r");
    assert_eq!(app.session.snapshot.step, 0);
}

#[test]
fn the_ghost_draws_its_cloth_in_the_ghost_colour() {
    // Compare mode: a second world; its cloth is drawn with `:` in the ghost's colour, under
    // the first world's (which covers it where they coincide). The ghost runs a body
    // integrator, so its sheet moves as the first's until the cube lands: here the ghost is
    // taken 100 frames ahead by hand (the cube still falling, the sheet sagging more) so that
    // the two sheets part.
    let mut app = app(TRAMPOLINE, true);
    keys(&mut app, "k");
    app.step_frames(20);
    if let Some(g) = &mut app.session.ghost {
        for _ in 0..100 {
            g.world.step();
        }
        // Every pane draws from the snapshots: the ghost's is read again.
        g.snapshot = g.world.snapshot();
    }
    let buf = export::render(&app, 120, 40);
    let area = drawing_rect(&app, 120, 40);
    let ghost = (area.y..area.y + area.height)
        .flat_map(|y| (area.x..area.x + area.width).map(move |x| (x, y)))
        .filter(|&p| buf[p].fg == theme::GHOST && buf[p].symbol() == ":")
        .count();
    assert!(ghost > 0, "no ghost drawn:\n{}", text(&buf));
}

#[test]
fn shot_and_record_take_a_scene_of_cloths_only() {
    let dir = std::env::temp_dir().join(format!("tumble-cloth-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("sheet.svg");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(root())
        .args(["shot", SHEET, "--at", "0.1", "--svg"])
        .arg(&svg)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(picture.contains("no rigid body in this scene"));
    assert!(picture.contains("cloth sheet · symplectic-euler"));
    let cast = dir.join("sheet.cast");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(root())
        .args([
            "record",
            SHEET,
            "--duration",
            "0.05",
            "--size",
            "80x24",
            "--out",
        ])
        .arg(&cast)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let recording = std::fs::read_to_string(&cast).unwrap();
    let header: serde_json::Value =
        serde_json::from_str(recording.lines().next().unwrap()).unwrap();
    assert_eq!(header["version"], 2);
    // 0.05 s at 30 frames per second: frames at 0, 1/30 s and the end: 3 events at least.
    assert!(recording.lines().count() >= 3, "{recording}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_view_keeps_every_particle_in_frame() {
    // The sheet alone starts 0.6 m above the ground and sags: every particle's cell is inside
    // the drawing at every frame shown.
    let mut app = app(SHEET, true);
    for _ in 0..10 {
        app.step_frames(20);
        let area = drawing_rect(&app, 120, 40);
        let mapping = Mapping::fit(&app.ui.region, app.prefs.axis, area.width, area.height);
        for p in &app.session.world.cloths()[0].positions {
            let (h, v) = app.prefs.axis.project(p);
            let (c, r) = mapping.cell(h, v);
            assert!(
                (0.0..f64::from(area.width)).contains(&c)
                    && (0.0..f64::from(area.height)).contains(&r),
                "particle at {p:?} drawn at ({c}, {r}), outside {area:?}"
            );
        }
    }
}

#[test]
fn a_sheet_resting_on_the_ground_counts_every_particle_as_an_obstacle_contact() {
    // A free 5 × 5 sheet (nothing pinned) dropped from 5 cm lies flat on the ground after 1 s:
    // each step, gravity's velocity half pushes every particle into the ground and the
    // velocity pass stops all 25 at the surface; the position pass then finds none inside.
    // The panel says so.
    let dir = std::env::temp_dir().join(format!("tumble-rest-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("rest.toml");
    std::fs::write(
        &path,
        r#"title = "A sheet on the ground"
[scene]
dt = 0.002
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.0, friction = 0.5 }
[[obstacle]]
type = "ground"
height = 0.0
[[cloth]]
name = "rest"
size = [1.0, 1.0]
count = [5, 5]
position = [0.0, 0.05, 0.0]
mass = 0.25
stretch = 400.0
damping = 0.2
pinned = "none"
integrator = "implicit-euler"
"#,
    )
    .unwrap();
    let lesson = tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let mut app = App::new(
        lesson,
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    app.step_frames(500);
    assert_eq!(app.session.world.cloth_obstacle_contacts(0), [25, 0]);
    assert_eq!(app.session.snapshot.cloths[0].obstacle_contacts, [25, 0]);
    let shown = screen_text(&app, 120, 40);
    assert!(
        shown.contains("with obstacles: 25 integrate, 0 collide"),
        "{shown}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
