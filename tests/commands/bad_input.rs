//! Bad input: every malformed file gives one line on stderr naming file:line:column (where the
//! file has a place at fault), what was expected and what was found; exit code 2; never a panic.
//!
//! Table-driven over `tests/fixtures/invalid/*.toml` (every fixture must be in the table), plus
//! the cases a fixture cannot hold (a missing file, a directory, an empty file, a binary file),
//! plus a fuzz-style proptest of the loader over arbitrary text and mutated bundled lessons.

use assert_cmd::Command;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

const INVALID: &str = "tests/fixtures/invalid";

/// (fixture, the one line `tumble check` prints on stderr after `tumble: `).
const TABLE: &[(&str, &str)] = &[
    (
        "syntax-error.toml",
        "5:18: TOML syntax error: invalid basic string, expected `\"`",
    ),
    (
        "wrong-type.toml",
        "4:6: wrong type: expected a number, found the string \"fast\"",
    ),
    (
        "unknown-key.toml",
        "6:1: unknown key `gravty` (did you mean `gravity`?); valid keys here: dt, duration, \
         integrator, gravity, drag, contact, joint_correction",
    ),
    (
        "unknown-integrator.toml",
        "5:14: unknown integrator `runge-kutta`; valid integrators: euler-seed, euler, \
         symplectic-euler, rk4, splitting, exact-splitting, exact-splitting-4",
    ),
    (
        "unknown-response.toml",
        "6:24: unknown collision response `bounce`; valid responses: seed, impulse, soft-step",
    ),
    ("negative-mass.toml", "10:8: mass must be > 0, found -1"),
    ("zero-mass.toml", "10:8: mass must be > 0, found 0"),
    (
        "nan-mass.toml",
        "10:8: mass must be a finite number, found NaN",
    ),
    (
        "zero-size.toml",
        "9:8: box `size` needs three sides > 0 m, found [1.0, 0.0, 0.1]",
    ),
    ("zero-dt.toml", "4:6: dt must be > 0, found 0"),
    ("negative-dt.toml", "4:6: dt must be > 0, found -0.01"),
    (
        "infinite-dt.toml",
        "4:6: dt must be a finite number, found inf",
    ),
    (
        "infinite-gravity.toml",
        "6:11: gravity must have finite components, found [0.0, -inf, 0.0]",
    ),
    (
        "zero-axis.toml",
        "11:24: orientation axis has zero length: give a non-zero axis",
    ),
    (
        "collinear-points.toml",
        "9:10: the inertia tensor is singular (principal moments -1.480e-16, 2.000e0, 2.000e0 \
         kg·m²): the points lie on one line or at one spot, so nothing resists rotation about \
         that line; add a point off the line or use a box",
    ),
    (
        "missing-mesh.toml",
        "9:8: mesh `tests/fixtures/invalid/meshes/nowhere.obj`: no such file",
    ),
    (
        "malformed-obj.toml",
        "9:8: mesh `tests/fixtures/invalid/meshes/broken.obj`: malformed .obj: line 3: vertex \
         coordinate `zero` is not a number",
    ),
    (
        "obstacles-without-contact.toml",
        "14:1: obstacles need a collision response: add `contact = { response = \"impulse\", \
         restitution = 0.4, friction = 0.5 }` to [scene]",
    ),
    (
        "negative-page-time.toml",
        "13:6: page time `at` must be ≥ 0 s, found -1",
    ),
    (
        "bodies-overlapping.toml",
        "15:1: body `right` starts inside body `left` (overlap 5.000e-2 m): move them apart so \
         that they at most touch",
    ),
    (
        "bodies-duplicate-name.toml",
        "15:8: duplicate body name `cube`: each [[body]] needs its own name",
    ),
    (
        "body-and-bodies.toml",
        "13:3: TOML syntax error: duplicate key `body`: give one [body], or a [[body]] for each \
         of several bodies, never both",
    ),
    (
        "bodies-with-seed.toml",
        "6:24: the `seed` response knows one body and fixed obstacles only, and this scene has 2 \
         bodies: use response = \"impulse\"",
    ),
    (
        "bodies-without-contact.toml",
        "12:1: several bodies need a collision response: add `contact = { response = \
         \"impulse\", restitution = 0.4, friction = 0.5 }` to [scene]",
    ),
    (
        "missing-body.toml",
        "1:1: missing table `[body]`: a scene file needs `title`, [scene] and [body] (or [[body]])",
    ),
    (
        "cloth-count-below-two.toml",
        "18:9: cloth `count` needs at least 1 particle along x and along z and 2 in all (a rope \
         is [n, 1] or [1, n]), found [0, 21]",
    ),
    (
        "cloth-duplicate-name.toml",
        "24:8: duplicate cloth name `trampoline`: cloth names must be unique in the file",
    ),
    (
        "cloth-negative-shear.toml",
        "21:9: shear must be ≥ 0, found -1",
    ),
    (
        "cloth-negative-stretch.toml",
        "20:11: stretch must be > 0, found -5000",
    ),
    (
        "cloth-no-particle-integrator.toml",
        "15:1: cloth `trampoline` has no `integrator` and the scene's `rk4` is not a particle \
         integrator: add `integrator = \"implicit-euler\"` to the cloth (valid: symplectic-euler, \
         implicit-euler)",
    ),
    (
        "cloth-pinned-out-of-range.toml",
        "21:10: pinned particle [21, 3] is outside the 21×21 grid: i must be in 0..21 and j in \
         0..21",
    ),
    (
        "cloth-unknown-integrator.toml",
        "21:14: unknown cloth integrator `rk4`; valid cloth integrators: symplectic-euler, \
         implicit-euler",
    ),
    (
        "cloth-unknown-pinned.toml",
        "21:10: unknown pinned `corner` (did you mean `corners`?); valid: corners, edges, none, \
         or a list [[i, j], …]",
    ),
    ("cloth-zero-mass.toml", "19:8: mass must be > 0, found 0"),
    (
        "cloth-attach-out-of-range.toml",
        "24:11: attached particle [11, 0] is outside the 11×7 grid: i must be in 0..11 and j in \
         0..7",
    ),
    (
        "cloth-attach-particle-and-edge.toml",
        "24:11: an attach entry needs one of `particle = [i, j]` or `edge = \"-x\"` (-x, +x, -z, \
         +z, all), not both",
    ),
    (
        "cloth-attach-pinned.toml",
        "25:11: particle [0, 0] is both pinned and attached: a particle is held by one of them",
    ),
    (
        "cloth-attach-twice.toml",
        "24:49: particle [0, 0] is attached twice",
    ),
    (
        "cloth-attach-unknown-body.toml",
        "24:33: attach: unknown body `mast`; bodies in this file: pole",
    ),
    (
        "cloth-attach-unknown-edge.toml",
        "24:20: unknown attach edge `top`; valid: -x, +x, -z, +z, all (-x is the edge i = 0, +x \
         i = 10, -z j = 0, +z j = 6, all the whole rim)",
    ),
    (
        "sphere-with-seed.toml",
        "7:24: the `seed` response tests vertices, and the sphere `body1` has none: use \
         response = \"impulse\"",
    ),
    (
        "plane-zero-normal.toml",
        "16:10: plane `normal` has zero length: give the outward direction, e.g. [0.0, 1.0, 0.0]",
    ),
    (
        "fixed-with-velocity.toml",
        "12:12: a fixed body never moves: remove its velocity (or `fixed = true`)",
    ),
];

fn tumble() -> Command {
    let mut command = Command::cargo_bin("tumble").expect("the tumble binary");
    command.current_dir(env!("CARGO_MANIFEST_DIR"));
    command
}

/// Runs `tumble ARGS` and returns (exit code, stdout, stderr).
fn outcome(args: &[&str]) -> (Option<i32>, String, String) {
    let output = tumble().args(args).output().expect("tumble runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// `check` and `run` both fail with exactly `expected` as the only stderr line, exit code 2.
fn assert_rejected(file: &str, expected: &str) {
    for args in [vec!["check", file], vec!["run", file, "--steps", "1"]] {
        let (code, stdout, stderr) = outcome(&args);
        assert_eq!(
            stderr,
            format!("{expected}\n"),
            "tumble {}: stderr differs",
            args.join(" ")
        );
        assert_eq!(code, Some(2), "tumble {}: exit code", args.join(" "));
        assert!(
            stdout.is_empty(),
            "tumble {}: printed {stdout:?}",
            args.join(" ")
        );
    }
}

#[test]
fn every_invalid_fixture_is_in_the_table() {
    let mut fixtures: Vec<String> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(INVALID))
            .expect("fixtures folder")
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".toml"))
            .collect();
    fixtures.sort();
    let mut listed: Vec<String> = TABLE.iter().map(|(f, _)| f.to_string()).collect();
    listed.sort();
    assert_eq!(fixtures, listed);
}

#[test]
fn each_invalid_fixture_gives_its_one_line_and_exit_code_2() {
    for (fixture, message) in TABLE {
        let file = format!("{INVALID}/{fixture}");
        assert_rejected(&file, &format!("tumble: {file}:{message}"));
    }
}

/// A scratch folder for files a fixture cannot hold.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bad_input");
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir.join(name)
}

#[test]
fn a_missing_file_is_named() {
    let file = scratch("does-not-exist.toml");
    let _ = std::fs::remove_file(&file);
    let file = file.to_string_lossy().into_owned();
    assert_rejected(&file, &format!("tumble: {file}: cannot read: no such file"));
}

#[test]
fn a_directory_is_not_a_scene() {
    let dir = scratch("a-folder.toml");
    std::fs::create_dir_all(&dir).expect("folder");
    let dir = dir.to_string_lossy().into_owned();
    assert_rejected(
        &dir,
        &format!("tumble: {dir}: is a directory, not a scene file"),
    );
}

#[test]
fn an_empty_file_says_what_a_scene_needs() {
    let file = scratch("empty.toml");
    std::fs::write(&file, "  \n\n").expect("write");
    let file = file.to_string_lossy().into_owned();
    assert_rejected(
        &file,
        &format!(
            "tumble: {file}: empty file: expected a TOML scene with at least `title`, [scene] \
             and [body]"
        ),
    );
}

#[test]
fn a_binary_file_is_not_text() {
    let file = scratch("binary.toml");
    std::fs::write(&file, [0x7f, b'E', b'L', b'F', 0, 1, 0xff, 0xfe, 0x80]).expect("write");
    let file = file.to_string_lossy().into_owned();
    assert_rejected(
        &file,
        &format!("tumble: {file}: not a text file (invalid UTF-8): expected a TOML scene"),
    );
    // Valid UTF-8 with NUL bytes is not a scene either.
    let file = scratch("nul.toml");
    std::fs::write(&file, "title = \"x\"\0\0\n").expect("write");
    let file = file.to_string_lossy().into_owned();
    assert_rejected(
        &file,
        &format!("tumble: {file}: not a text file (contains NUL bytes): expected a TOML scene"),
    );
}

#[test]
fn several_files_get_one_line_each_and_a_summary() {
    let bad = format!("{INVALID}/zero-dt.toml");
    let good = "lessons/01-the-loop.toml";
    let (code, stdout, stderr) = outcome(&["check", good, &bad]);
    assert_eq!(code, Some(2));
    assert!(stdout.starts_with(&format!("{good}: ok (")), "{stdout}");
    assert_eq!(
        stderr,
        format!("tumble: {bad}:4:6: dt must be > 0, found 0\ntumble: 1 of 2 files have errors\n")
    );
}

#[test]
fn bad_command_line_overrides_are_one_line_and_exit_code_2() {
    let lesson = "lessons/01-the-loop.toml";
    for (args, expected) in [
        (
            vec!["run", lesson, "--steps", "1", "--dt", "0"],
            "tumble: --dt must be > 0 and finite, found 0\n",
        ),
        (
            vec!["run", lesson, "--steps", "1", "--integrator", "verlet"],
            "tumble: unknown integrator `verlet`; valid integrators: euler-seed, euler, \
             symplectic-euler, rk4, splitting, exact-splitting, exact-splitting-4\n",
        ),
    ] {
        let (code, _, stderr) = outcome(&args);
        assert_eq!(stderr, expected);
        assert_eq!(code, Some(2));
    }
}

// ---------------------------------------------------------------------------------------------
// Fuzz: the loader never panics
// ---------------------------------------------------------------------------------------------

/// The bundled lessons' sources, the seeds of the mutations.
fn lesson_sources() -> Vec<(PathBuf, String)> {
    tumble::lessons::bundled()
        .into_iter()
        .map(|p| {
            let source = std::fs::read_to_string(&p).expect("lesson text");
            (p, source)
        })
        .collect()
}

/// Tokens that make a TOML scene interesting: numbers at the edges, wrong types, structure.
const TOKENS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "\"x\"",
    "[",
    "]",
    "{",
    "}",
    "=",
    ",",
    "\n",
    "[[obstacle]]\ntype = \"box\"\n",
    "[[obstacle]]\ntype = \"ground\"\nheight = 0\n",
    "[[page]]\nat = -1\n",
    "[body]\n",
    "[scene]\n",
    "\"\"\"",
    "#",
    "é",
    "\u{0}",
    "true",
    "[0.0, 0.0, 0.0]",
    "[1e308, 1e308, 1e308]",
    "shape = \"points\"",
    "shape = \"mesh\"",
    "file = \"/\"",
    "file = \"../lessons\"",
    "inertia = \"points\"",
    "integrator = \"euler-seed\"",
    "contact = { response = \"seed\" }",
    "{ quaternion = [0, 0, 0, 0] }",
];

/// A mutation of a source text: cut a range, insert a token, or duplicate a line.
#[derive(Debug, Clone)]
enum Mutation {
    Cut { at: usize, len: usize },
    Insert { at: usize, token: usize },
    DuplicateLine { line: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..40).prop_map(|(at, len)| Mutation::Cut { at, len }),
        (any::<usize>(), 0..TOKENS.len()).prop_map(|(at, token)| Mutation::Insert { at, token }),
        any::<usize>().prop_map(|line| Mutation::DuplicateLine { line }),
    ]
}

fn boundary(source: &str, at: usize) -> usize {
    let mut i = at % (source.len() + 1);
    while !source.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn apply(source: &str, mutation: &Mutation) -> String {
    match *mutation {
        Mutation::Cut { at, len } => {
            let start = boundary(source, at);
            let end = boundary(source, (start + len).min(source.len()));
            format!("{}{}", &source[..start], &source[end.max(start)..])
        }
        Mutation::Insert { at, token } => {
            let at = boundary(source, at);
            format!("{}{}{}", &source[..at], TOKENS[token], &source[at..])
        }
        Mutation::DuplicateLine { line } => {
            let lines: Vec<&str> = source.lines().collect();
            if lines.is_empty() {
                return source.to_string();
            }
            let k = line % lines.len();
            let mut out: Vec<&str> = lines[..=k].to_vec();
            out.extend_from_slice(&lines[k..]);
            out.join("\n")
        }
    }
}

/// Loads a text; if it is a valid scene, also builds its world and steps it a little: neither
/// may panic, and an error is one line.
fn load_never_panics(source: &str, path: &Path) -> Result<(), TestCaseError> {
    match tumble::scene::parse(source, path) {
        Ok(lesson) => {
            let mut world = lesson.scene.world();
            for _ in 0..3 {
                world.step();
                let _ = world.divergence();
            }
            let _ = world.snapshot();
        }
        Err(e) => {
            let line = e.to_string();
            prop_assert!(!line.contains('\n'), "a two-line error: {line:?}");
            prop_assert!(line.starts_with(&path.display().to_string()), "{line}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, failure_persistence: None, rng_seed: proptest::test_runner::RngSeed::Fixed(20_261_122), ..ProptestConfig::default() })]

    #[test]
    fn the_loader_never_panics_on_arbitrary_text(source in any::<String>()) {
        load_never_panics(&source, Path::new("fuzz.toml"))?;
    }

    #[test]
    fn the_loader_never_panics_on_toml_like_text(source in "([a-z_]{1,8} = (-?[0-9.e]{1,6}|\"[a-z]{0,6}\"|\\[[0-9., -]{0,12}\\]|nan|inf)\n|\\[{1,2}[a-z]{1,8}\\]{1,2}\n){0,12}") {
        load_never_panics(&source, Path::new("fuzz.toml"))?;
    }

    #[test]
    fn the_loader_never_panics_on_mutated_lessons(
        lesson in any::<prop::sample::Index>(),
        mutations in prop::collection::vec(mutation(), 1..6),
    ) {
        let sources = lesson_sources();
        prop_assume!(!sources.is_empty());
        let (path, source) = &sources[lesson.index(sources.len())];
        let mutated = mutations.iter().fold(source.clone(), |s, m| apply(&s, m));
        load_never_panics(&mutated, path)?;
    }
}
