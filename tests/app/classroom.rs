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
    app.ui.running = true;
    app.ui.pause_at_stops = false;
    app.step_frames(700);
    assert!(
        app.session.divergence.is_none(),
        "{:?}",
        app.session.divergence
    );
    assert_eq!(
        app.session.world.step_count(),
        700,
        "the impulse run went on"
    );
    let ghost = app.session.ghost.as_ref().expect("compare mode on");
    let at = ghost
        .diverged
        .as_ref()
        .expect("the seed ghost diverged")
        .step;
    assert!(at < 700, "diverged at {at}");
    assert_eq!(ghost.world.step_count(), at, "frozen at its divergence");
    assert!(app.ui.running, "still running");
    // The run is the lesson's own impulse run, stepped alone.
    let mut alone = lesson_app("06-sphere-obstacle", None);
    alone.step_frames(700);
    assert_eq!(
        alone.session.world.checkpoint(),
        app.session.world.checkpoint()
    );
    let shown = screen(&app, 200, 60);
    assert!(
        shown.contains(&format!("impulse vs seed (diverged at step {at})")),
        "{shown}"
    );
    // Stepping back before the divergence thaws the ghost; forward again, it freezes again.
    app.step_back_frames(700 - at as usize + 5);
    assert!(app.session.ghost.as_ref().unwrap().diverged.is_none());
    app.step_frames(20);
    assert_eq!(
        app.session
            .ghost
            .as_ref()
            .unwrap()
            .diverged
            .as_ref()
            .unwrap()
            .step,
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
    app.ui.pause_at_stops = false;
    let mut alone = lesson_app("08-climbing-bug", None);
    alone.step_frames(3000);
    let at = alone
        .session
        .divergence
        .as_ref()
        .expect("seed diverges alone")
        .step;
    app.step_frames(at + 200);
    assert!(
        app.session.divergence.is_none(),
        "{:?}",
        app.session.divergence
    );
    assert_eq!(app.session.world.step_count(), at + 200);
    assert_eq!(
        app.session.world.contact_model().unwrap().response,
        Response::Impulse,
        "the run follows the impulse world"
    );
    let ghost = app.session.ghost.as_ref().unwrap();
    assert_eq!(ghost.comparison, Comparison::Response(Response::Seed));
    assert_eq!(ghost.diverged.as_ref().unwrap().step, at);
    assert_eq!(ghost.world.step_count(), at);
    // Exactly the impulse run alone.
    let mut impulse = lesson_app("08-climbing-bug", None);
    let mut model = *impulse.session.world.contact_model().unwrap();
    model.response = Response::Impulse;
    impulse.session.world.set_contact_model(model);
    impulse.step_frames(at + 200);
    assert_eq!(
        impulse.session.world.checkpoint(),
        app.session.world.checkpoint()
    );
    // Step back across the swap: the impulse world's own earlier frames.
    app.step_back_frames(300);
    impulse.step_back_frames(300);
    assert_eq!(
        impulse.session.world.checkpoint(),
        app.session.world.checkpoint()
    );
    assert!(app.session.ghost.as_ref().unwrap().diverged.is_none());
}

fn press(app: &mut App, code: crossterm::event::KeyCode) {
    app.handle_key(&crossterm::event::KeyEvent::new(
        code,
        crossterm::event::KeyModifiers::NONE,
    ));
}

/// Selects the form's field labelled `label` and types `text` into it.
fn set_field(app: &mut App, label: &str, text: &str) {
    use crossterm::event::KeyCode;
    let tumble::tui::Overlay::Settings(form) = &app.ui.overlay else {
        panic!("the form is not open");
    };
    let at = form
        .fields
        .iter()
        .position(|f| form.label(f).0 == label)
        .unwrap_or_else(|| panic!("no field `{label}`"));
    while !matches!(&app.ui.overlay, tumble::tui::Overlay::Settings(f) if f.selected == at) {
        press(app, KeyCode::Down);
    }
    for c in text.chars() {
        press(app, KeyCode::Char(c));
    }
}

#[test]
fn the_settings_form_edits_a_scene_of_cloths_only() {
    use crossterm::event::KeyCode;
    use tumble::physics::cloth::ClothIntegrator;
    // Lesson 18 tells the student to switch the sheet to implicit-euler with `e`.
    let mut app = lesson_app("18-explicit-limit", None);
    assert_eq!(app.session.world.body_count(), 0);
    press(&mut app, KeyCode::Char('e'));
    assert!(
        matches!(app.ui.overlay, tumble::tui::Overlay::Settings(_)),
        "{:?}",
        app.ui.notice
    );
    let shown = screen(&app, 80, 24);
    assert!(shown.contains("time step dt"), "{shown}");
    let name = app.session.world.cloths()[0].name.clone();
    set_field(
        &mut app,
        &format!("cloth {name} integrator"),
        "implicit-euler",
    );
    set_field(&mut app, &format!("cloth {name} stretch"), "1500");
    set_field(&mut app, "time step dt", "0.01");
    press(&mut app, KeyCode::Enter);
    assert_eq!(
        app.ui.overlay,
        tumble::tui::Overlay::None,
        "{:?}",
        app.ui.notice
    );
    assert_eq!(app.session.world.dt(), 0.01);
    assert_eq!(
        app.session.world.cloths()[0].integrator,
        ClothIntegrator::ImplicitEuler
    );
    assert_eq!(app.session.lesson.scene.cloths[0].stretch, 1500.0);
    let notice = app.ui.notice.clone().unwrap();
    assert!(notice.contains("→ implicit-euler"), "{notice}");
    assert!(notice.contains("stretch"), "{notice}");
    // W writes a file the loader reads back with the same values.
    let dir = std::env::temp_dir().join(format!("tumble-classroom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    app.prefs.write_dir = dir.clone();
    press(&mut app, KeyCode::Char('W'));
    let written = tumble::scene::load(&app.write_path()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(written.scene.dt, 0.01);
    assert_eq!(
        written.scene.cloths[0].integrator,
        ClothIntegrator::ImplicitEuler
    );
    assert_eq!(written.scene.cloths[0].stretch, 1500.0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_in_app_study_runs_on_a_scene_of_cloths_only() {
    use crossterm::event::KeyCode;
    let mut app = lesson_app("18-explicit-limit", None);
    press(&mut app, KeyCode::Char('s'));
    let job = app.session.study.as_ref().expect("a study started");
    assert!(job.refusal().is_none(), "{:?}", job.refusal());
    let shown = screen(&app, 120, 40);
    assert!(shown.contains("study of"), "{shown}");
    assert!(
        !shown.contains("the study compares the body integrators"),
        "{shown}"
    );
}

#[test]
fn the_form_moves_orients_and_sets_gravity_and_drag() {
    use crossterm::event::KeyCode;
    let mut app = lesson_app("05-ground-collision", None);
    press(&mut app, KeyCode::Char('e'));
    set_field(&mut app, "position x₀ x", "0.5");
    set_field(&mut app, "angle about the axis", "45");
    set_field(&mut app, "orientation axis x", "1");
    set_field(&mut app, "axis y", "0");
    set_field(&mut app, "axis z", "0");
    set_field(&mut app, "gravity g x", "0");
    set_field(&mut app, "g y", "-1.62");
    set_field(&mut app, "drag k (F = −k v)", "0.2");
    press(&mut app, KeyCode::Enter);
    assert_eq!(
        app.ui.overlay,
        tumble::tui::Overlay::None,
        "{:?}",
        app.ui.notice
    );
    let initial = &app.session.lesson.scene.bodies[0].initial;
    assert_eq!(initial.position.x, 0.5);
    // 45° about x: the body's y axis goes to (0, cos 45°, sin 45°).
    let y = initial.orientation.matrix() * nalgebra::Vector3::y();
    let c = std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        (y - nalgebra::Vector3::new(0.0, c, c)).norm() < 1e-15,
        "{y}"
    );
    assert_eq!(
        app.session.lesson.scene.effects.gravity(),
        Some(nalgebra::Vector3::new(0.0, -1.62, 0.0))
    );
    assert!(app
        .session
        .lesson
        .scene
        .effects
        .list()
        .contains(&tumble::physics::Effect::Drag {
            linear: 0.2,
            angular: 0.0
        }));
    // One frame: the force panel's F = M g − k v with v = 0 at t = 0 is M g.
    let m = app.session.lesson.scene.bodies[0].body.mass;
    let force = app.session.snapshot.force;
    assert!((force.y + 1.62 * m).abs() < 1e-12, "{force}");
}

#[test]
fn the_apps_response_and_ghost_pass_the_scenes_rules() {
    use crossterm::event::KeyCode;
    // Lesson 14 has three bodies: the scene's rules refuse `seed` (a file saying so is refused,
    // and so is `--response seed`); `c` skips it and says why, the ghost refuses it.
    let mut app = lesson_app("14-head-on", None);
    let mut seen = Vec::new();
    for _ in 0..Response::ALL.len() {
        press(&mut app, KeyCode::Char('c'));
        let response = app.session.world.contact_model().unwrap().response;
        assert_ne!(response, Response::Seed, "{:?}", app.ui.notice);
        if let Some(notice) = &app.ui.notice {
            seen.push(notice.clone());
        }
    }
    assert!(
        seen.iter().any(|n| n
            == "skipped: the `seed` response knows one body and fixed obstacles only, and this \
                scene has 3 bodies: use the `impulse` response (c)"),
        "{seen:?}"
    );
    app.start_compare(Comparison::Response(Response::Seed));
    assert!(app.session.ghost.is_none());
    assert!(
        app.ui
            .notice
            .as_deref()
            .unwrap()
            .starts_with("no ghost: the `seed` response knows one body"),
        "{:?}",
        app.ui.notice
    );
    assert!(!app
        .comparisons()
        .contains(&Comparison::Response(Response::Seed)));
}

#[test]
fn compare_with_the_lessons_own_setting_is_refused() {
    use assert_cmd::Command;
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tui-box.toml");
    for (flag, other) in [("rk4", true), ("impulse", true), ("euler", false)] {
        let run = Command::cargo_bin("tumble")
            .unwrap()
            .arg(&fixture)
            .args(["--compare", flag])
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&run.get_output().stderr).to_string();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        if other {
            assert!(
                stderr.contains(&format!("the lesson runs `{flag}` already")),
                "{stderr}"
            );
        } else {
            // A different integrator passes the checks; only the missing terminal stops it.
            assert!(stderr.contains("the app needs a terminal"), "{stderr}");
        }
    }
}

/// The cells of the row labelled `label` in the panel titled `title` (its first match).
fn cells(app: &App, title: &str, label: &str) -> Vec<String> {
    tumble::tables::panels(&app.session.snapshot, tumble::tables::Frame::World)
        .into_iter()
        .filter(|p| p.title.starts_with(title))
        .flat_map(|p| p.rows)
        .find(|r| r.label.trim() == label)
        .unwrap_or_else(|| panic!("no row {label} in {title}"))
        .cells
        .iter()
        .map(|c| c.trim().to_string())
        .collect()
}

#[test]
fn round_off_prints_as_zero_and_is_never_highlighted() {
    use crossterm::event::KeyCode;
    // Lesson 14: after the first blow `left` stops; the solver stops within its tolerance,
    // 1e-10 m/s (impulse::TOLERANCE): the page says P = 0, and so does the panel.
    let mut app = lesson_app("14-head-on", None);
    app.ui.pause_at_stops = false;
    app.step_frames(505);
    assert_eq!(app.session.snapshot.body_name, "left");
    assert!(
        app.session.snapshot.linear_momentum.x.abs() > 0.0,
        "a residue is there"
    );
    assert!(app.session.snapshot.linear_momentum.x.abs() <= 2e-10);
    assert_eq!(cells(&app, "linear momentum", "P"), ["0.000000"; 3]);
    assert_eq!(cells(&app, "linear momentum", "v"), ["0.000000"; 3]);
    assert_eq!(cells(&app, "energy", "E − E₀"), ["0.000000"]);
    // The system's P is still 1 kg·m/s: the rule is relative to the scene's scale.
    assert_eq!(cells(&app, "system", "P total")[0], "1.000000");

    // A spinning box (lesson 7, impulse): the world inertia tensor's off-diagonal 1e-19
    // entries print as 0, so a frame never highlights them as changed.
    let mut app = lesson_app("07-box-obstacle", None);
    app.ui.pause_at_stops = false;
    app.step_frames(300);
    let before = cells(&app, "inertia tensor", "I");
    app.step_frames(1);
    let after = cells(&app, "inertia tensor", "I");
    assert_eq!(before[1..], after[1..], "off-diagonal entries");
    for c in &after[1..] {
        assert!(!c.contains('e'), "{after:?}");
    }
    // ‖RᵀR−1‖ of a quaternion (≈ 1e-16) is round-off of 1.
    assert_eq!(cells(&app, "state", "‖RᵀR−1‖"), ["0.000000"]);

    // Cycling the integrator at t = 0 never shows an E − E₀ of round-off.
    let mut app = lesson_app("10-tennis-racket", None);
    for _ in 0..tumble::physics::Integrator::ALL.len() {
        press(&mut app, KeyCode::Char('i'));
        assert_eq!(cells(&app, "energy", "E − E₀"), ["0.000000"]);
    }
}

#[test]
fn numbers_the_solver_or_the_integrator_really_made_are_kept() {
    // rk4's truncation error in free flight is no round-off: tui-box's drift shows.
    let mut app = App::new(
        tumble::scene::load(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tui-box.toml"),
        )
        .unwrap(),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    app.step_frames(5);
    let drift = &cells(&app, "energy", "drift/E₀")[0];
    assert!(drift.contains("e-13"), "{drift}");
    // A 4.86e-48 is round-off of 1; a 1e-3 (euler-seed's ‖RᵀR−1‖) is not.
    assert_eq!(
        tumble::tables::resolved(4.8598e-48, tumble::tables::ROUND_OFF),
        0.0
    );
    assert_eq!(
        tumble::tables::resolved(1e-3, tumble::tables::ROUND_OFF),
        1e-3
    );
}

#[test]
fn after_c_the_page_says_it_describes_the_lessons_own_settings() {
    use crossterm::event::KeyCode;
    let mut app = lesson_app("08-climbing-bug", None);
    assert!(app.page_settings_note().is_none());
    press(&mut app, KeyCode::Char('c'));
    let note = app.page_settings_note().expect("another response runs");
    assert_eq!(note, " the page describes seed; running impulse ");
    let shown = screen(&app, 200, 60);
    assert!(
        shown.contains("the page describes seed; running impulse"),
        "{shown}"
    );
}

#[test]
fn wording_of_the_loop_strip_and_the_divergence() {
    // |ω|·dt in fixed decimals, not `3.4937e0`.
    let mut app = lesson_app("05-ground-collision", None);
    app.ui.pause_at_stops = false;
    app.step_frames(3000);
    let d = app
        .session
        .divergence
        .as_ref()
        .expect("lesson 5 diverges with seed");
    assert!(!d.quantity.contains("e0 rad"), "{}", d.quantity);
    assert!(d.quantity.contains("|ω|·dt = 3."), "{}", d.quantity);
    // Particles touching bodies are counted as particles.
    let mut app = App::new(
        tumble::scene::load(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tui-cloth-trampoline.toml"),
        )
        .unwrap(),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    app.ui.pause_at_stops = false;
    let mut seen = false;
    for _ in 0..400 {
        app.step_frames(1);
        let shown = screen(&app, 200, 60);
        assert!(
            !shown.contains("touching bodies") || shown.contains("particles touching"),
            "{shown}"
        );
        seen |= shown.contains("particles touching bodies")
            || shown.contains("particle touching a body");
        if seen {
            break;
        }
    }
    assert!(seen, "the cube lands on the sheet");
}

#[test]
fn the_loop_strip_shows_the_chosen_responses_own_formula() {
    // Each response's collide line comes from its descriptor: soft-step's sub-stepped soft
    // update with its parameters, not the report's push-out (which it showed before).
    for (response, formula, numbers) in [
        (Response::Impulse, "j = −(1+e)·uₙ/k", "e = 0.400000"),
        (
            Response::SoftStep(tumble::physics::SoftStep::DEFAULT),
            "per sub-step h = dt/n",
            "e = 0.400000, hertz = 60.000000, ζ = 10.000000, n = 4",
        ),
    ] {
        let mut app = lesson_app("05-ground-collision", None);
        app.ui.pause_at_stops = false;
        let mut model = *app.session.world.contact_model().unwrap();
        model.response = response;
        app.session.world.set_contact_model(model);
        let mut touched = false;
        for _ in 0..2000 {
            app.step_frames(1);
            if !app.session.snapshot.contacts.is_empty() {
                touched = true;
                break;
            }
        }
        assert!(touched, "{}: the cube never landed", response.name());
        let strip: String = tumble::tui::loop_strip::lines(&app)
            .iter()
            .flat_map(|l| l.spans.iter().map(|s| s.content.to_string()))
            .collect();
        assert!(strip.contains(formula), "{}: {strip}", response.name());
        assert!(strip.contains(numbers), "{}: {strip}", response.name());
        assert!(!strip.contains("seed (the report's)"), "{strip}");
    }
}

#[test]
fn the_terminal_app_draws_at_once_and_fills_its_live_numbers_from_a_thread() {
    // `App::interactive` (the terminal app) simulates the pages' live numbers on a thread:
    // until they arrive a page reads "(computing…)"; then it reads exactly what `App::new`
    // (which simulates them first) shows.
    let lesson = tumble::lessons::load(Path::new("16-trampoline")).unwrap();
    let page = lesson
        .pages
        .iter()
        .position(|p| !p.live.is_empty())
        .unwrap();
    let options = Options {
        ascii: true,
        compare: None,
        show_timing: false,
    };
    let expected = App::new(lesson.clone(), options.clone());
    let expected = expected.session.live.page_text(&lesson.pages[page]);
    assert!(!expected.contains("(computing…)"), "{expected}");
    let mut app = App::interactive(lesson.clone(), options);
    assert!(app.live_pending());
    let waiting = app.session.live.page_text(&lesson.pages[page]);
    assert!(waiting.contains("(computing…)"), "{waiting}");
    // A guard against a hang, not a speed claim: the values take about half a second.
    let start = std::time::Instant::now();
    while app.live_pending() {
        app.poll_live();
        assert!(
            start.elapsed().as_secs() < 120,
            "the live numbers never came"
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    assert_eq!(app.session.live.page_text(&lesson.pages[page]), expected);
}
