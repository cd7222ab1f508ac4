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
    ];
    for (text, predict, expected) in cases {
        let e = tumble::scene::parse(&source(text, predict), Path::new("drop.toml"))
            .expect_err(text)
            .to_string();
        assert!(e.starts_with(expected), "{e}\nexpected: {expected}");
    }
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
