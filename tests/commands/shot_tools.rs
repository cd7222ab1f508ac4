//! `tumble shot --tool NAME` (and `record`): the measuring tools on a slide of any scene.

use std::process::Command;

fn shot(args: &[&str]) -> (Option<i32>, String, String) {
    let dir = std::env::temp_dir().join(format!("tumble-shot-tools-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("s.svg");
    let out = Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args(["shot", "26-the-physical-pendulum", "--svg"])
        .arg(&svg)
        .args(args)
        .output()
        .unwrap();
    let picture = std::fs::read_to_string(&svg).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&dir);
    (
        out.status.code(),
        picture,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn tools_named_on_the_command_line_are_on_the_slide() {
    // Lesson 26 at t = 0 (no tool on its pages): the cube turned 50° about z, its centre
    // a √2/2 = 0.707107 m from the hinge's point on it (edge.a); the stopwatch started at 0.
    let (code, svg, err) = shot(&[
        "--at",
        "0",
        "--tool",
        "stopwatch",
        "--tool",
        "ruler",
        "--tool",
        "protractor",
    ]);
    assert_eq!(code, Some(0), "{err}");
    for text in [
        "stopwatch (running: w stops, o laps)",
        "ruler cube → edge.a",
        "0.707107",
        "protractor cube.y ∠ the vertical",
        "50.000000",
    ] {
        assert!(svg.contains(text), "no `{text}` in the slide");
    }
}

#[test]
fn an_unknown_tool_is_a_usage_error() {
    let (code, _, err) = shot(&["--tool", "clock"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("unknown tool `clock` (tools: stopwatch, period, ruler, protractor)"),
        "{err}"
    );
}
