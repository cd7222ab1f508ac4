//! Issue 13, the command line: bundled lessons by name from any folder (compiled in, a file on
//! disk wins), every independent error of a file, "did you mean" for names given on the
//! command line, and the app without a terminal. Exact messages and exit codes.

use assert_cmd::Command;
use std::path::{Path, PathBuf};

fn tumble() -> Command {
    Command::cargo_bin("tumble").unwrap()
}

/// A fresh empty folder, away from the repository (no `lessons/` in it).
fn empty_folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tumble-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// (exit code, stdout, stderr) of `tumble ARGS` run in `folder`.
fn outcome_in(folder: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let output = tumble().current_dir(folder).args(args).output().unwrap();
    (
        output.status.code(),
        String::from_utf8(output.stdout).unwrap(),
        String::from_utf8(output.stderr).unwrap(),
    )
}

fn outcome(args: &[&str]) -> (Option<i32>, String, String) {
    outcome_in(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

#[test]
fn walk_accepts_a_lesson_name_from_a_folder_without_lessons() {
    let dir = empty_folder("walk-by-name");
    let (code, by_name, stderr) = outcome_in(&dir, &["walk", "01-the-loop", "--frames", "3"]);
    assert_eq!(code, Some(0), "{stderr}");
    // The compiled-in lesson is the repository's file, byte for byte.
    let (_, by_path, _) = outcome(&["walk", "lessons/01-the-loop.toml", "--frames", "3"]);
    assert_eq!(by_name, by_path);
    assert!(
        by_name.starts_with("The animation loop (01-the-loop.toml)"),
        "{by_name}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn every_command_accepts_the_names_lessons_prints_with_or_without_toml() {
    let dir = empty_folder("names");
    let (code, listing, _) = outcome_in(&dir, &["lessons"]);
    assert_eq!(code, Some(0));
    let names: Vec<&str> = listing
        .lines()
        .take_while(|l| !l.is_empty())
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(names.len(), tumble::lessons::bundled().len(), "{listing}");
    let with_toml: Vec<String> = names.iter().map(|n| format!("{n}.toml")).collect();
    let mut args = vec!["check"];
    args.extend(names.iter().step_by(2));
    args.extend(with_toml.iter().skip(1).step_by(2).map(String::as_str));
    let (code, stdout, stderr) = outcome_in(&dir, &args);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stdout.matches(": ok (").count(), names.len(), "{stdout}");
    // Lesson 9 is a mesh: its .obj is compiled in too.
    assert!(stdout.contains("09-viscosity: ok (Viscosity)"), "{stdout}");
    let (code, csv, stderr) = outcome_in(
        &dir,
        &[
            "run",
            "05-ground-collision",
            "--steps",
            "2",
            "--response",
            "seed",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(csv.lines().count(), 4, "header + rows 0, 1, 2: {csv}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_lesson_file_on_disk_wins_over_the_compiled_in_copy() {
    let dir = empty_folder("disk-wins");
    std::fs::create_dir_all(dir.join("lessons")).unwrap();
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/01-the-loop.toml"),
    )
    .unwrap()
    .replacen(
        "title = \"The animation loop\"",
        "title = \"My own loop\"",
        1,
    );
    std::fs::write(dir.join("lessons/01-the-loop.toml"), text).unwrap();
    let (code, stdout, stderr) = outcome_in(&dir, &["check", "01-the-loop"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert_eq!(stdout, "01-the-loop: ok (My own loop)\n");
    // A broken copy on disk is reported under its path, line and column.
    std::fs::write(
        dir.join("lessons/01-the-loop.toml"),
        "title = \"x\"\n[scene]\ndt = 0\nintegrator = \"rk4\"\n[body]\nshape = \"box\"\n\
         size = [1.0, 1.0, 1.0]\nmass = 1.0\n",
    )
    .unwrap();
    let (code, _, stderr) = outcome_in(&dir, &["walk", "01-the-loop", "--frames", "1"]);
    assert_eq!(code, Some(2));
    assert_eq!(
        stderr,
        "tumble: lessons/01-the-loop.toml:3:6: dt must be > 0, found 0\n"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unknown_lesson_name_gets_a_suggestion_and_exit_code_2() {
    let dir = empty_folder("unknown-name");
    for args in [
        vec!["walk", "01-the-lop", "--frames", "1"],
        vec!["01-the-lop"],
        vec!["check", "01-the-lop"],
    ] {
        let (code, stdout, stderr) = outcome_in(&dir, &args);
        assert_eq!(code, Some(2), "{args:?}");
        assert_eq!(
            stderr,
            "tumble: 01-the-lop: no such file or bundled lesson (did you mean `01-the-loop`?); \
             `tumble lessons` lists them\n",
            "{args:?}"
        );
        assert!(stdout.is_empty());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn command_line_names_get_did_you_mean_like_files() {
    for (args, expected) in [
        (
            vec!["run", "01-the-loop", "--steps", "1", "--integrator", "rk5"],
            "tumble: unknown integrator `rk5` (did you mean `rk4`?); valid integrators: \
             euler-seed, euler, symplectic-euler, rk4, splitting, exact-splitting, \
             exact-splitting-4\n",
        ),
        (
            vec![
                "walk",
                "05-ground-collision",
                "--frames",
                "1",
                "--response",
                "sed",
            ],
            "tumble: unknown collision response `sed` (did you mean `seed`?); valid responses: \
             seed, impulse, soft-step\n",
        ),
        (
            vec!["study", "05-ground-collision", "--response", "impuls"],
            "tumble: unknown collision response `impuls` (did you mean `impulse`?); valid \
             responses: seed, impulse, soft-step\n",
        ),
        (
            vec!["01-the-loop", "--compare", "splittin"],
            "tumble: unknown --compare `splittin` (did you mean `splitting`?); valid: \
             integrators and responses: euler-seed, euler, symplectic-euler, rk4, splitting, \
             exact-splitting, exact-splitting-4, seed, impulse, soft-step\n",
        ),
        (
            vec!["study", "01-the-loop", "--response", "seed"],
            "tumble: 01-the-loop: --response needs a scene with obstacles and a `contact` table\n",
        ),
    ] {
        let (code, stdout, stderr) = outcome(&args);
        assert_eq!(stderr, expected, "{args:?}");
        assert_eq!(code, Some(2), "{args:?}");
        assert!(stdout.is_empty(), "{args:?}: {stdout}");
    }
}

#[test]
fn the_app_without_a_terminal_says_so_in_one_line_with_exit_code_2() {
    // assert_cmd gives the child no terminal: stdin is empty, stdout a pipe.
    for args in [vec![], vec!["05-ground-collision"]] {
        let output = tumble().args(&args).output().unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert_eq!(
            String::from_utf8(output.stderr).unwrap(),
            "tumble: the app needs a terminal (stdin and stdout are not one); for text use \
             `tumble walk FILE --frames N` or `tumble run FILE --steps N`\n"
        );
        assert!(output.stdout.is_empty(), "no escape sequences written");
    }
}

#[test]
fn check_reports_every_independent_error_one_line_each() {
    // Seven errors in four sections; each would be the only one `check` used to print.
    let file = "tests/fixtures/several/errors.toml";
    let (code, stdout, stderr) = outcome(&["check", file]);
    assert_eq!(code, Some(2));
    assert!(stdout.is_empty());
    let expected = [
        "4:6: dt must be > 0, found -0.01",
        "5:14: unknown integrator `rk5` (did you mean `rk4`?); valid integrators: euler-seed, \
         euler, symplectic-euler, rk4, splitting, exact-splitting, exact-splitting-4",
        "6:1: unknown key `gravty` (did you mean `gravity`?); valid keys here: dt, duration, \
         integrator, gravity, drag, contact, joint_correction",
        "11:8: box `size` needs three sides > 0 m, found [1.0, 0.0, 1.0]",
        "15:8: unknown obstacle type `grund` (did you mean `ground`?); valid types: ground, \
         sphere, box, plane",
        "20:10: radius must be > 0, found -1",
        "23:6: page time `at` must be ≥ 0 s, found -1",
    ]
    .map(|line| format!("tumble: {file}:{line}\n"))
    .concat();
    assert_eq!(stderr, expected);
    // With another file: the same lines, then the summary.
    let (code, _, stderr) = outcome(&["check", "01-the-loop", file]);
    assert_eq!(code, Some(2));
    assert_eq!(
        stderr,
        format!("{expected}tumble: 1 of 2 files have errors\n")
    );
}

#[test]
fn check_stops_at_a_syntax_error() {
    // Everything after a syntax error is unreliable: one line.
    let (code, _, stderr) = outcome(&["check", "tests/fixtures/invalid/syntax-error.toml"]);
    assert_eq!(code, Some(2));
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

#[test]
fn study_response_seed_on_the_ground_blames_the_response_when_every_integrator_diverges() {
    // Lesson 5 with the report's response: every run leaves the guard's bounds within 0.5 s
    // (the diverged runs stop there, so this study is short).
    let (code, stdout, stderr) = outcome(&["study", "05-ground-collision", "--response", "seed"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.starts_with("== 05-ground-collision (3 s, response seed): Hitting the ground\n"),
        "{stdout}"
    );
    let runs = 4 * tumble::physics::Integrator::ALL.len();
    assert_eq!(
        stdout.matches("  DIVERGED at t = ").count(),
        runs,
        "{stdout}"
    );
    assert!(
        stdout.contains(
            "Every integrator diverges at every time step with the `seed` collision response: \
             the response, not the integration, is the cause."
        ),
        "{stdout}"
    );
    // Short DIVERGED lines: no line of the table is longer than its header.
    let header = stdout
        .lines()
        .find(|l| l.starts_with("  integrator"))
        .unwrap();
    for line in stdout.lines().filter(|l| l.contains("DIVERGED")) {
        assert!(line.chars().count() < header.chars().count(), "{line}");
    }
}

#[test]
fn check_reports_errors_of_every_stage_in_one_pass() {
    // Types and keys (the TOML reader's stage), then dt and names, then ranges: one run of
    // `check` lists them all (it took three before: a wrong array length blanked [scene]).
    let file = "tests/fixtures/several/three-rounds.toml";
    let (code, stdout, stderr) = outcome(&["check", file]);
    assert_eq!(code, Some(2));
    assert!(stdout.is_empty());
    let expected = [
        "4:6: dt must be > 0, found 0",
        "5:12: duration must be > 0, found -3",
        "6:14: unknown integrator `rk5` (did you mean `rk4`?); valid integrators: euler-seed, \
         euler, symplectic-euler, rk4, splitting, exact-splitting, exact-splitting-4",
        "7:11: wrong length: expected an array of 3 numbers, found 2 elements",
        "8:24: unknown collision response `impulsive` (did you mean `impulse`?); valid \
         responses: seed, impulse, soft-step",
        "8:51: restitution must be between 0 and 1, found 2",
        "8:67: friction must be ≥ 0, found -0.5",
        "13:8: box `size` needs three sides > 0 m, found [1.0, -1.0, 1.0]",
        "14:8: wrong type: expected a number, found the string \"heavy\"",
        "16:1: unknown key `spin`; valid keys here: name, shape, size, points, masses, file, \
         radius, length, fixed, mass, inertia, position, orientation, velocity, \
         angular_velocity, angular_velocity_body",
        "21:10: radius must be > 0, found -1",
        "25:6: page time `at` must be ≥ 0 s, found -1",
    ]
    .map(|line| format!("tumble: {file}:{line}\n"))
    .concat();
    assert_eq!(stderr, expected);
}

#[test]
fn a_file_of_cloths_only_gets_its_cloth_errors_and_no_false_missing_body() {
    let file = "tests/fixtures/several/cloth-only-errors.toml";
    let (code, _, stderr) = outcome(&["check", file]);
    assert_eq!(code, Some(2));
    assert!(!stderr.contains("missing table"), "{stderr}");
    let expected = [
        "8:1: a cloth needs a collision response (its particles touch bodies and obstacles): \
         add `contact = { response = \"impulse\", restitution = 0.4, friction = 0.5 }` to [scene]",
        "14:11: stretch must be > 0, found -2000",
    ]
    .map(|line| format!("tumble: {file}:{line}\n"))
    .concat();
    assert_eq!(stderr, expected);
}
