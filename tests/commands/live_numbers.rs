//! Live numbers (`{{QUANTITY}}`, `{{QUANTITY@T}}`) and predictions in lesson pages: names
//! checked at file:line:column, values from simulating the scene, printed by `walk` with the
//! panels' formatter and unit.

use std::path::Path;
use tumble::cli::walk::write_walk;
use tumble::live::LiveValues;

/// A 1 kg cube dropped from y = 2 m under g = 9.81, symplectic Euler, dt = 0.01 s: no contact
/// before t = 0.6 s (it reaches y ≈ 0.2 m there), so every value has a closed form.
fn source(text: &str, predict: &str) -> String {
    format!(
        r#"title = "drop"
[scene]
dt = 0.01
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
text = "nothing yet"

[[page]]
at = 0.5
title = "Falling"
text = """{text}"""
{predict}
"#
    )
}

fn walk(source: &str, frames: u64) -> String {
    let lesson =
        tumble::scene::parse(source, Path::new("drop.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut out = Vec::new();
    write_walk(&lesson, frames, false, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

#[test]
fn walk_fills_live_numbers_with_the_simulated_values_and_units() {
    let text = walk(
        &source(
            "vy = {{cube.vy}}, y = {{y}}, y at 0.3 s = {{cube.y@0.3}}, t = {{t}}, P = {{Py}}, E = {{energy}}",
            "",
        ),
        50,
    );
    // Symplectic Euler: v_n = −g n dt, y_n = y₀ − g dt² n(n+1)/2.
    // n = 50: vy = −9.81·0.5 = −4.905; y = 2 − 9.81e-4·1275 = 0.749225.
    // n = 30: y = 2 − 9.81e-4·465 = 1.543835.
    // P_y = M vy = −4.905; E is conserved by nothing here: K + V = ½·4.905² + 9.81·0.749225
    //   = 12.029513 + 7.349897 = 19.379410 (below E₀ = 19.62: symplectic Euler's lag).
    assert!(
        text.contains(
            "  | vy = -4.905000 m/s, y = 0.749225 m, y at 0.3 s = 1.543835 m, t = 0.500000 s, \
             P = -4.905000 kg·m/s, E = 19.379410 J"
        ),
        "{text}"
    );
}

#[test]
fn t_contact_is_the_first_touch_and_says_so_before_it() {
    // The cube of `source` with a ground at y = 0 and an impulse response: its bottom (1.9 m up)
    // reaches the ground after √(2 h/g) = √(3.8/9.81) = 0.6224 s; the first step whose contact
    // impulse acts is within 2 dt of that (symplectic Euler lags, a speculative row may act
    // one step early). At 0.5 s it has not touched yet.
    let text = source("first touch {{cube.t_contact@1}}; at 0.5 s {{cube.t_contact}}", "")
        .replace(
            "gravity = [0.0, -9.81, 0.0]",
            "gravity = [0.0, -9.81, 0.0]\ncontact = { response = \"impulse\", restitution = 0.0, friction = 0.5 }",
        )
        .replace(
            "[[page]]\nat = 0.0",
            "[[obstacle]]\ntype = \"ground\"\nheight = 0.0\n\n[[page]]\nat = 0.0",
        );
    let out = walk(&text, 50);
    let line = out
        .lines()
        .find(|l| l.contains("first touch"))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(line.ends_with("at 0.5 s (no contact yet)"), "{line}");
    let t: f64 = line
        .split("first touch ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("{line}"));
    let closed = (2.0 * 1.9 / 9.81f64).sqrt();
    assert!(
        (t - closed).abs() <= 0.02 + 1e-9,
        "t_contact {t} against {closed}"
    );
}

#[test]
fn a_value_quoted_at_a_time_matches_the_panel_at_that_time() {
    // The page at 0.5 s quotes y at 0.3 s; the walk's own state panel at t = 0.3 s must agree.
    let text = walk(&source("{{y@0.3}}", ""), 50);
    let page_line = text
        .lines()
        .filter(|l| l.starts_with("  | "))
        .nth(1)
        .unwrap();
    let value = page_line.trim_start_matches("  | ").trim_end_matches(" m");
    let block = text.split("== t = 0.300000 s").nth(1).unwrap();
    let x_row = block
        .lines()
        .find(|l| l.trim_start().starts_with("x "))
        .unwrap();
    assert!(x_row.contains(value), "{x_row} vs {value}");
}

#[test]
fn walk_prints_the_prediction_with_its_value() {
    let text = walk(
        &source("How low?", r#"predict = { quantity = "cube.y", at = 0.6 }"#),
        1,
    );
    // n = 60: y = 2 − 9.81e-4·1830 = 0.204770 m. The page is at 0.5 s, after the one frame
    // walked, so only page 1 shows; the prediction shows with page 2.
    assert!(!text.contains("predict:"), "{text}");
    let text = walk(
        &source("How low?", r#"predict = { quantity = "cube.y", at = 0.6 }"#),
        50,
    );
    assert!(
        text.contains("  predict: cube.y at t = 0.600000 s → 0.204770 m"),
        "{text}"
    );
}

#[test]
fn unknown_quantities_and_bodies_are_refused_at_their_line_and_column() {
    let cases = [
        (
            "y is {{cube.height}}",
            "",
            "drop.toml:22:16: unknown quantity `cube.height`",
        ),
        (
            "y is {{ball.y}}",
            "",
            "drop.toml:22:16: unknown body `ball` in `ball.y`",
        ),
        (
            "{{y@soon}}",
            "",
            "drop.toml:22:11: `{{y@soon}}`: the time after @",
        ),
        (
            "fine",
            r#"predict = { quantity = "cube.hight", at = 0.6 }"#,
            "drop.toml:23:24: predict: unknown quantity `cube.hight`",
        ),
        (
            "fine",
            r#"panels = ["energy", "energie"]"#,
            "drop.toml:23:21: page `panels`: unknown panel `energie` (panels: state,",
        ),
    ];
    for (text, predict, expected) in cases {
        let e = tumble::scene::parse(&source(text, predict), Path::new("drop.toml"))
            .expect_err(text)
            .to_string();
        assert!(e.starts_with(expected), "{e}\nexpected: {expected}");
    }
}

#[test]
fn a_page_names_its_panels() {
    use tumble::scene::PagePanel;
    let lesson = tumble::scene::parse(
        &source("fine", r#"panels = ["body-energy", "angular-velocity"]"#),
        Path::new("drop.toml"),
    )
    .unwrap();
    assert_eq!(lesson.pages[0].panels, vec![]);
    assert_eq!(
        lesson.pages[1].panels,
        vec![PagePanel::BodyEnergy, PagePanel::AngularVelocity]
    );
}

#[test]
fn values_are_computed_once_per_lesson_and_only_at_quoted_times() {
    let lesson = tumble::scene::parse(&source("{{y@0.3}}", ""), Path::new("drop.toml")).unwrap();
    let live = LiveValues::compute(&lesson, lesson.scene.world());
    let q = &lesson.pages[1].live[0].quantity;
    // y at 0.3 s (step 30), as above; nothing was computed at 0.4 s.
    let Some(tumble::live::Value::Number(y)) = live.value(q, 0.3) else {
        panic!("no value at 0.3 s");
    };
    let expected = 2.0 - 9.81e-4 * 465.0;
    assert!((y - expected).abs() < 1e-12, "{y} vs {expected}");
    assert_eq!(live.value(q, 0.4), None);
}

#[test]
fn every_bundled_lesson_fills_its_live_numbers() {
    for path in tumble::lessons::bundled() {
        let lesson = tumble::lessons::load(&path).unwrap();
        if lesson.pages.iter().all(|p| p.live.is_empty()) {
            continue;
        }
        let live = LiveValues::compute(&lesson, lesson.scene.world());
        for page in &lesson.pages {
            let text = live.page_text(page);
            assert!(!text.contains("{{"), "{}: {text}", path.display());
            assert!(!text.contains("(diverged"), "{}: {text}", path.display());
        }
    }
}

#[cfg(feature = "tui")]
mod app {
    use super::source;
    use std::path::Path;
    use tumble::tui::keys::Message;
    use tumble::tui::{export, App, Options};

    fn app(text: &str, predict: &str) -> App {
        let lesson = tumble::scene::parse(&source(text, predict), Path::new("drop.toml")).unwrap();
        App::new(
            lesson,
            Options {
                ascii: true,
                compare: None,
                show_timing: false,
            },
        )
    }

    fn screen(app: &App) -> String {
        let buf = export::render(app, 160, 50);
        (0..buf.area.height)
            .map(|y| {
                (0..buf.area.width)
                    .map(|x| buf[(x, y)].symbol())
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("\n")
    }

    #[test]
    fn the_lesson_pane_shows_live_numbers_filled_in() {
        let mut app = app("vy = {{cube.vy}} here", "");
        app.jump_to(0.5);
        // vy = −g·0.5 = −4.905 m/s (see walk_fills_live_numbers…).
        let shown = screen(&app);
        assert!(shown.contains("vy = -4.905000 m/s here"), "{shown}");
        assert!(!shown.contains("{{"), "{shown}");
    }

    #[test]
    fn a_prediction_is_asked_then_set_beside_the_simulated_value() {
        let mut app = app(
            "How low at 0.6 s?",
            r#"predict = { quantity = "cube.y", at = 0.6 }"#,
        );
        app.update(Message::Continue);
        app.step_frames(1000);
        // The run stops at page 2 (t = 0.5 s); Enter asks for the guess instead of running.
        assert_eq!(app.session.world.step_count(), 50);
        assert!(screen(&app).contains("Enter asks for your guess"));
        app.update(Message::Continue);
        assert!(!app.ui.running);
        assert!(matches!(
            app.ui.overlay,
            tumble::tui::app::Overlay::Predict { .. }
        ));
        assert!(screen(&app).contains("what will cube.y be at t = 0.6 s (in m)?"));
        for c in "0.3".chars() {
            app.update(Message::Type(c));
        }
        app.update(Message::Submit);
        assert!(app.ui.running);
        app.step_frames(1000);
        // Stopped at t = 0.6 s (step 60): y = 0.204770 m; |0.3 − 0.20477| / 0.20477 = 46.5 %.
        assert_eq!(app.session.world.step_count(), 60);
        let expected =
            "cube.y at t = 0.6 s: your guess 0.3 m · simulated 0.204770 m · relative error 46.5 %";
        assert!(
            app.ui.notice.as_deref().unwrap_or("").contains(expected),
            "{:?}",
            app.ui.notice
        );
        assert!(screen(&app).contains(expected), "{}", screen(&app));
    }

    #[test]
    fn switching_the_integrator_requotes_the_pages_with_its_numbers() {
        let mut app = app("y = {{y}}", "");
        app.jump_to(0.5);
        assert!(screen(&app).contains("y = 0.749225 m"));
        // Explicit Euler (the next integrator after symplectic Euler? whichever `i` gives):
        // the page now quotes that integrator's value, simulated again from t = 0.
        app.update(Message::NextIntegrator);
        let mut world = app.session.world.clone();
        world.reset();
        for _ in 0..50 {
            world.step();
        }
        let y = tumble::tables::number_plain(world.state().position.y);
        assert_ne!(y, "0.749225");
        assert!(screen(&app).contains(&format!("y = {y} m")), "{y}");
    }
}

/// Every key the loader accepts (the fields of `src/scene/raw.rs`, by their TOML names)
/// appears in `docs/lesson-format.md` as `` `key` ``.
#[test]
fn every_key_the_loader_accepts_is_documented() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let raw = std::fs::read_to_string(root.join("src/scene/raw.rs")).unwrap();
    let docs = std::fs::read_to_string(root.join("docs/lesson-format.md")).unwrap();
    let mut rename = None;
    let mut keys = Vec::new();
    for line in raw.lines().map(str::trim) {
        if let Some(i) = line.find("rename = \"") {
            let rest = &line[i + 10..];
            rename = rest.split('"').next().map(str::to_string);
            continue;
        }
        if let Some(field) = line.strip_prefix("pub ").and_then(|l| l.split_once(':')) {
            let name = field.0.trim();
            if name.chars().all(|c| c.is_ascii_lowercase() || c == '_') && !name.is_empty() {
                keys.push(rename.take().unwrap_or_else(|| name.to_string()));
            }
        }
        if !line.starts_with("#[") {
            rename = None;
        }
    }
    assert!(keys.len() > 40, "found only {keys:?}");
    let missing: Vec<&String> = keys
        .iter()
        .filter(|k| {
            !docs.contains(&format!("`{k}`"))
                && !docs.contains(&format!("[{k}]"))
                && !docs.contains(&format!("[[{k}]]"))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "docs/lesson-format.md does not mention {missing:?}"
    );
}

/// A live number prints as its panel does: lesson 5 run with the impulse response (key `c`
/// in the app re-simulates the page's numbers for it) quoted `Px 1.0000e-10 kg·m/s` after
/// the bounce, where the momentum panel shows 0 (the contact solver's tolerance, 1e-10 m/s
/// per unit speed, is the round-off of a velocity it sets).
#[test]
fn a_live_number_below_its_panels_round_off_prints_as_zero() {
    let mut lesson = tumble::lessons::load(Path::new("05-ground-collision")).unwrap();
    let mut model = lesson.scene.contact.unwrap();
    model.response = tumble::physics::Response::Impulse;
    lesson.scene.contact = Some(model);
    let live = LiveValues::compute(&lesson, lesson.scene.world());
    let page = &lesson.pages[1];
    let text = live.page_text(page);
    assert!(text.contains("Px 0.000000 kg·m/s"), "{text}");
    // The panel at that step says the same: P's x cell is 0 there, and Px itself is not.
    let mut world = lesson.scene.world();
    while world.step_count() < tumble::live::step_at(page.at, world.dt()) {
        world.step();
    }
    let s = world.snapshot();
    assert!(s.linear_momentum.x != 0.0 && s.linear_momentum.x.abs() < 1e-9);
    let panels = tumble::tables::panels(&s, tumble::tables::Frame::World);
    let p = panels
        .iter()
        .flat_map(|p| &p.rows)
        .find(|r| r.label == "P")
        .unwrap();
    assert_eq!(p.cells[0].trim(), "0.000000");
}
