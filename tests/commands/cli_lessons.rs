//! The `lessons`, `walk` and `check` commands as a user runs them: output and exit codes.

use assert_cmd::Command;
use std::path::PathBuf;

fn tumble() -> Command {
    Command::cargo_bin("tumble").unwrap()
}

fn lesson(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("lessons")
        .join(name)
}

fn stdout(output: &std::process::Output) -> String {
    String::from_utf8(output.stdout.clone()).unwrap()
}

fn stderr(output: &std::process::Output) -> String {
    String::from_utf8(output.stderr.clone()).unwrap()
}

#[test]
fn lessons_lists_every_bundled_lesson_with_its_title_and_summary() {
    let output = tumble().arg("lessons").output().unwrap();
    assert_eq!(output.status.code(), Some(0), "stderr: {}", stderr(&output));
    let text = stdout(&output);
    for path in tumble::lessons::bundled() {
        let lesson = tumble::scene::load(&path).unwrap();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        let line = text
            .lines()
            .find(|l| l.starts_with(&stem))
            .unwrap_or_else(|| panic!("no line for {stem} in:\n{text}"));
        assert!(line.contains(&lesson.title), "{line}");
        assert!(line.contains(&lesson.summary), "{line}");
    }
    // In teaching order: 01 comes before 02, which comes before 10.
    let first = text.find("01-the-loop").unwrap();
    let second = text.find("02-rigid-body-from-points").unwrap();
    let tenth = text.find("10-tennis-racket").unwrap();
    assert!(first < second && second < tenth, "{text}");
}

#[test]
fn walk_prints_the_page_the_phase_and_the_panels() {
    let output = tumble()
        .args([
            "walk",
            lesson("01-the-loop.toml").to_str().unwrap(),
            "--frames",
            "1",
            "--phases",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "stderr: {}", stderr(&output));
    let text = stdout(&output);
    for expected in [
        "The animation loop (01-the-loop.toml)",
        "== t = 0.000000 s · initial state · next phase: derive",
        "== t = 0.000000 s · frame 1 · phase done: derive",
        "== t = 0.000000 s · frame 1 · phase done: forces",
        "== t = 0.010000 s · frame 1 · phase done: integrate",
        "== t = 0.010000 s · frame 1 · phase done: collide",
        "page 1/5 (from t = 0.000000 s): One frame, four phases",
        "page 2/5 (from t = 0.010000 s): What integrate did",
        // P_y after one frame: 3 − 9.81 × 0.01 = 2.9019 kg·m/s.
        "  P     0.500000    2.901900    0.000000  kg·m/s",
    ] {
        assert!(text.contains(expected), "missing `{expected}` in:\n{text}");
    }
    // 1 initial block + 4 phases.
    assert_eq!(text.matches("\n== ").count(), 5, "{text}");
}

#[test]
fn walk_is_byte_for_byte_the_library_walk() {
    let path = lesson("10-tennis-racket.toml");
    let output = tumble()
        .args(["walk", path.to_str().unwrap(), "--frames", "5"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0));
    let mut expected = Vec::new();
    tumble::cli::walk::write_walk(
        &tumble::scene::load(&path).unwrap(),
        5,
        false,
        &mut expected,
    )
    .unwrap();
    assert_eq!(output.stdout, expected);
}

#[test]
fn walk_of_a_diverging_lesson_stops_with_exit_code_3() {
    let output = tumble()
        .args([
            "walk",
            lesson("11-fast-spin.toml").to_str().unwrap(),
            "--frames",
            "1000",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(3));
    let err = stderr(&output);
    assert!(
        err.contains("simulation diverged at step 532")
            && err.contains("integrator euler, dt = 0.001 s"),
        "{err}"
    );
    // The frames before the divergence were printed, the last one being frame 532.
    let text = stdout(&output);
    assert!(
        text.contains("frame 532 · phase done: collide"),
        "{}",
        &text[text.len().saturating_sub(400)..]
    );
    assert!(!text.contains("frame 533"));
}

#[test]
fn walk_overrides_the_integrator_like_run() {
    let output = tumble()
        .args([
            "walk",
            lesson("11-fast-spin.toml").to_str().unwrap(),
            "--frames",
            "1000",
            "--integrator",
            "splitting",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(stdout(&output).contains("integrator splitting"));
}

#[test]
fn walk_of_a_bad_file_names_file_line_and_column_with_exit_code_2() {
    let dir = std::env::temp_dir().join(format!("tumble-walk-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "title = \"x\"\n[scene]\ndt = 0.01\nintegrator = \"rk5\"\n[body]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n").unwrap();
    let output = tumble()
        .args(["walk", bad.to_str().unwrap(), "--frames", "1"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(
        err.contains("bad.toml:4:14: unknown integrator `rk5`"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(stdout(&output).is_empty());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn walk_without_frames_is_a_usage_error() {
    let output = tumble()
        .args(["walk", lesson("01-the-loop.toml").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("--frames"), "{}", stderr(&output));
}

#[test]
fn check_accepts_every_bundled_lesson() {
    let files = tumble::lessons::bundled();
    let output = tumble().arg("check").args(&files).output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_eq!(stdout(&output).matches(": ok (").count(), files.len());
}

#[test]
fn check_reports_a_lesson_page_out_of_order_with_exit_code_2() {
    let dir = std::env::temp_dir().join(format!("tumble-check-pages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("pages.toml");
    std::fs::write(
        &bad,
        "title = \"x\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n[body]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n\
         [[page]]\nat = 1.0\ntitle = \"b\"\ntext = \"b\"\n[[page]]\nat = 0.5\ntitle = \"a\"\ntext = \"a\"\n",
    )
    .unwrap();
    let good = lesson("01-the-loop.toml");
    let output = tumble()
        .args(["check", good.to_str().unwrap(), bad.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let err = stderr(&output);
    assert!(
        err.contains("pages.toml:13:1: pages must be in order of `at`"),
        "{err}"
    );
    assert!(stdout(&output).contains("01-the-loop.toml: ok (The animation loop)"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn walk_of_a_scene_with_obstacles_shows_each_contact() {
    // A box (half height 0.1 m) at y = 0.105 m falling at 1 m/s, no gravity: after one frame
    // (dt = 0.01 s) its 4 bottom corners (vertices 0, 1, 4, 5) are 0.005 m deep. With e = 0
    // the impulse response stops the box: total impulse M·1 m/s = 1 N·s, 0.25 N·s per corner,
    // and pushes it out (penetration 0 afterwards).
    let dir = std::env::temp_dir().join(format!("tumble-walk-contacts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("drop.toml");
    std::fs::write(
        &scene,
        "title = \"drop\"\n[scene]\ndt = 0.01\nintegrator = \"symplectic-euler\"\n\
         contact = { response = \"impulse\", restitution = 0.0 }\n[body]\nshape = \"box\"\n\
         size = [0.4, 0.2, 0.3]\nmass = 1.0\nposition = [0.0, 0.105, 0.0]\nvelocity = [0.0, -1.0, 0.0]\n\
         [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n",
    )
    .unwrap();
    let output = tumble()
        .args(["walk", scene.to_str().unwrap(), "--frames", "1"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let text = stdout(&output);
    let (before, after) = text.split_once("frame 1 · phase done: collide").unwrap();
    assert!(
        before.contains("contacts (last collide)\n  penetration     0.000000  m\n  no contact"),
        "{before}"
    );
    for vertex in [0, 1, 4, 5] {
        let block = format!(
            "  vertex {vertex} in ground 0\n    depth                  0.005000  m\n    v·n                   -1.000000  m/s\n    J                      0.000000    0.250000    0.000000  N·s"
        );
        assert!(after.contains(&block), "missing\n{block}\nin\n{after}");
    }
    assert_eq!(after.matches("  vertex ").count(), 4, "{after}");
    std::fs::remove_dir_all(&dir).unwrap();
}
