//! Hostile input and faults (issue 22): nothing a file or a command line says can hang the
//! program, abort it or make it lie. Every case asserts the exit code and a message naming
//! what is wrong, and — through [`tumble`] — that the process neither panicked (exit 101, a
//! "panicked" line), was killed by a signal (an abort), nor ran past a timeout (a hang).
//!
//! Classes: the scene's rules from the command line; bounds on work and memory; exit codes;
//! closed and full stdout; negative numbers; overflow and underflow; non-finite numbers never
//! printed; control characters escaped; small ones (empty cloth name, `study --svg` into a
//! missing folder); TOML edge values and encodings; huge files; directories where files are
//! expected; every numeric flag at 0, negative, NaN and huge.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What one run of the binary gave.
pub(super) struct Output {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

/// The longest any hostile case may take: far above the milliseconds each needs, far below a
/// hang.
const TIMEOUT: Duration = Duration::from_secs(20);

fn binary() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_tumble"))
}

/// Runs `tumble ARGS` from the crate root with empty stdin; kills it past [`TIMEOUT`] and
/// fails. Never a panic, never a signal.
pub(super) fn tumble(args: &[&str]) -> Output {
    tumble_with(args, Stdio::null())
}

/// As [`tumble`], with `stdin` as its standard input (hostile_round4 feeds `/dev/zero`).
pub(super) fn tumble_with(args: &[&str], stdin: Stdio) -> Output {
    let mut child = Command::new(binary())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .stdin(stdin)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("tumble starts");
    let (mut out, mut err) = (child.stdout.take().unwrap(), child.stderr.take().unwrap());
    let reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = out.read_to_end(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = err.read_to_end(&mut s);
        s
    });
    let status = wait(&mut child, args);
    let stdout = String::from_utf8_lossy(&reader.join().unwrap()).into_owned();
    let stderr = String::from_utf8_lossy(&err_reader.join().unwrap()).into_owned();
    let code = status.code().unwrap_or_else(|| {
        panic!("tumble {args:?} was killed by a signal (an abort?): {status:?}\n{stderr}")
    });
    assert_ne!(code, 101, "tumble {args:?} panicked:\n{stderr}");
    assert!(!stderr.contains("panicked"), "tumble {args:?}:\n{stderr}");
    Output {
        code,
        stdout,
        stderr,
    }
}

/// Waits for `child`, killing it past [`TIMEOUT`] (then the test fails: a hang).
fn wait(child: &mut std::process::Child, args: &[&str]) -> std::process::ExitStatus {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("wait") {
            return status;
        }
        if started.elapsed() > TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("tumble {args:?} did not answer within {TIMEOUT:?} (a hang)");
        }
        std::thread::sleep(Duration::from_millis(2));
    }
}

/// A scratch folder of this test binary (under target/).
fn scratch() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("hostile");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to scratch/NAME and returns the path as a string.
fn file(name: &str, text: impl AsRef<[u8]>) -> String {
    let path = scratch().join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// A one-box scene with `scene` extra lines in [scene] and `body` in [body].
fn box_scene(scene: &str, body: &str) -> String {
    format!(
        "title = \"hostile\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n{scene}\n[body]\n\
         shape = \"box\"\nsize = [1.0, 1.0, 1.0]\n{body}\n"
    )
}

/// Exit 2 and the one stderr line contains every `words`.
fn refused(out: &Output, words: &[&str]) {
    assert_eq!(out.code, 2, "expected exit 2:\n{}", out.stderr);
    for w in words {
        assert!(
            out.stderr.contains(w),
            "`{w}` missing from:\n{}",
            out.stderr
        );
    }
}

// --- 1. The scene's rules hold for the flags too ------------------------------------------

#[test]
fn response_seed_on_several_bodies_is_refused_from_every_command() {
    // 14-head-on has 3 bodies; seed knows one body (the file's own rule).
    for args in [
        &["run", "14-head-on", "--steps", "1", "--response", "seed"][..],
        &["walk", "14-head-on", "--frames", "1", "--response", "seed"],
        &["study", "14-head-on", "--response", "seed"],
        &[
            "shot",
            "14-head-on",
            "--svg",
            "/dev/null",
            "--response",
            "seed",
        ],
    ] {
        let out = tumble(args);
        refused(&out, &["seed", "3 bodies", "--response impulse"]);
        assert_eq!(out.stdout, "", "{args:?}");
    }
}

// --- 2. Bounds on work and memory, checked before anything runs ---------------------------

#[test]
fn work_past_the_bounds_is_refused_at_once_naming_the_flag_or_key() {
    let tiny_dt = file(
        "tiny-dt.toml",
        box_scene("", "mass = 1.0").replace("0.01", "1e-300"),
    );
    let long = file("long.toml", box_scene("duration = 1e9", "mass = 1.0"));
    let svg = scratch().join("x.svg").to_string_lossy().into_owned();
    let cast = scratch().join("x.cast").to_string_lossy().into_owned();
    let cases: [(&[&str], &[&str]); 7] = [
        // 1e12 s / 0.001 s = 1e15 steps > 1e7.
        (
            &["shot", "01-the-loop", "--at", "1e12", "--svg", &svg],
            &["--at", "10000000"],
        ),
        // 1 s / 1e-300 s = 1e300 steps.
        (
            &["shot", &tiny_dt, "--at", "1", "--svg", &svg],
            &["--at", "1.0e300 steps"],
        ),
        (
            &["record", "01-the-loop", "--duration", "1e7", "--out", &cast],
            &["--duration", "10000000"],
        ),
        (
            &["record", &tiny_dt, "--duration", "1", "--out", &cast],
            &["--duration"],
        ),
        // 1e9 s / 0.1 s = 1e10 samples > 1e6 (this aborted with an 80 GB allocation).
        (&["study", &long], &["duration", "1000000"]),
        // 30000 × 30000 cells (this aborted too).
        (
            &[
                "shot",
                "01-the-loop",
                "--size",
                "30000x30000",
                "--svg",
                &svg,
            ],
            &["--size", "4000"],
        ),
        (
            &[
                "record",
                "01-the-loop",
                "--duration",
                "1",
                "--size",
                "1001x1000",
                "--out",
                &cast,
            ],
            &["1000000"],
        ),
    ];
    for (args, words) in cases {
        let started = Instant::now();
        let out = tumble(args);
        refused(&out, words);
        assert!(out.stderr.len() < 300, "a short message: {}", out.stderr);
        // Refused before any work: well under a second even on a loaded machine.
        assert!(started.elapsed() < Duration::from_secs(5), "{args:?}");
    }
}

#[test]
fn a_study_past_its_bounds_is_refused_in_the_app_too() {
    // The app's `s` key spawns this job: refused at once, no thread, a reason to show.
    let lesson = tumble::lessons::load(std::path::Path::new(&file(
        "long-app.toml",
        box_scene("duration = 1e9", "mass = 1.0"),
    )))
    .expect("a valid file");
    let case = tumble::study::Case::from_lesson(&lesson);
    let job = tumble::study::background::Job::spawn(case, tumble::study::Config::default());
    assert!(job.failed());
    let why = job.refusal().expect("a reason");
    assert!(why.contains("`duration` = 1000000000 s"), "{why}");
}

// --- 3. Exit codes: 3 on a divergence, for shot and record too ----------------------------

#[test]
fn shot_and_record_exit_3_on_a_divergence() {
    // euler-seed on a 100 rad/s spin at dt = 0.01 s diverges within a few steps.
    let file = "tests/fixtures/diverging/euler-seed-fast-spin.toml";
    let svg = scratch().join("div.svg").to_string_lossy().into_owned();
    let cast = scratch().join("div.cast").to_string_lossy().into_owned();
    let shot = tumble(&["shot", file, "--at", "0.5", "--svg", &svg]);
    assert_eq!(shot.code, 3, "{}", shot.stderr);
    assert!(
        shot.stderr.contains("simulation diverged at step"),
        "{}",
        shot.stderr
    );
    let record = tumble(&["record", file, "--duration", "0.5", "--out", &cast]);
    assert_eq!(record.code, 3, "{}", record.stderr);
    assert!(record.stderr.contains("simulation diverged at step"));
}

// --- 4. Closed and full stdout: never a panic ---------------------------------------------

#[test]
fn a_closed_stdout_ends_the_command_with_exit_141() {
    for args in [
        &["walk", "01-the-loop", "--frames", "100000"][..],
        &["run", "01-the-loop", "--steps", "1000000"],
    ] {
        let mut child = Command::new(binary())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reader goes away after one read (as `| head -1` does).
        let mut first = [0u8; 16];
        let mut out = child.stdout.take().unwrap();
        let _ = out.read(&mut first);
        drop(out);
        let mut err = child.stderr.take().unwrap();
        let status = wait(&mut child, args);
        let mut stderr = String::new();
        let _ = err.read_to_string(&mut stderr);
        assert_eq!(status.code(), Some(141), "{args:?}: {stderr}");
        assert!(stderr.contains("broken pipe"), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn a_full_disk_on_stdout_is_exit_2_naming_the_write() {
    if !std::path::Path::new("/dev/full").exists() {
        return;
    }
    for args in [
        &["check", "01-the-loop"][..],
        &["lessons"],
        &["run", "01-the-loop", "--steps", "3"],
        &["walk", "01-the-loop", "--frames", "1"],
    ] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let output = Command::new(binary())
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("cannot write output"), "{stderr}");
    }
}

// --- 5. Negative numbers with a space name their flag -------------------------------------

#[test]
fn negative_numbers_name_their_flag() {
    let svg = scratch().join("n.svg").to_string_lossy().into_owned();
    let cast = scratch().join("n.cast").to_string_lossy().into_owned();
    let cases: [(&[&str], &str); 6] = [
        (&["run", "01-the-loop", "--steps", "-1"], "--steps"),
        (
            &["run", "01-the-loop", "--steps", "1", "--every", "-1"],
            "--every",
        ),
        (
            &["run", "01-the-loop", "--steps", "1", "--dt", "-1"],
            "--dt must be > 0",
        ),
        (&["walk", "01-the-loop", "--frames", "-2"], "--frames"),
        (
            &["shot", "01-the-loop", "--at", "-1", "--svg", &svg],
            "--at must be ≥ 0",
        ),
        (
            &["record", "01-the-loop", "--duration", "-1", "--out", &cast],
            "--duration must be > 0",
        ),
    ];
    for (args, flag) in cases {
        let out = tumble(args);
        refused(&out, &[flag]);
        assert!(
            !out.stderr.contains("-- -1"),
            "no wrong tip: {}",
            out.stderr
        );
    }
}

#[test]
fn every_numeric_flag_at_zero_nan_and_huge() {
    let svg = scratch().join("f.svg").to_string_lossy().into_owned();
    let cast = scratch().join("f.cast").to_string_lossy().into_owned();
    // Accepted: 0 steps (header and row 0), 0 frames (the initial block), a shot at t = 0.
    let zero = tumble(&["run", "01-the-loop", "--steps", "0"]);
    assert_eq!(zero.code, 0, "{}", zero.stderr);
    assert_eq!(zero.stdout.lines().count(), 2, "header and row 0");
    assert_eq!(tumble(&["walk", "01-the-loop", "--frames", "0"]).code, 0);
    assert_eq!(
        tumble(&["shot", "01-the-loop", "--at", "0", "--svg", &svg]).code,
        0
    );
    // Refused, naming the flag.
    let cases: [(&[&str], &str); 12] = [
        (
            &["run", "01-the-loop", "--steps", "1", "--every", "0"],
            "--every",
        ),
        (&["run", "01-the-loop", "--steps", "1", "--dt", "0"], "--dt"),
        (
            &["run", "01-the-loop", "--steps", "1", "--dt", "NaN"],
            "--dt",
        ),
        (
            &["run", "01-the-loop", "--steps", "1", "--dt", "inf"],
            "--dt",
        ),
        (&["run", "01-the-loop", "--steps", "1e3"], "--steps"),
        (
            &["run", "01-the-loop", "--steps", "99999999999999999999999"],
            "--steps",
        ),
        (
            &["shot", "01-the-loop", "--at", "NaN", "--svg", &svg],
            "--at",
        ),
        (
            &["shot", "01-the-loop", "--at", "1e308", "--svg", &svg],
            "--at",
        ),
        (
            &["record", "01-the-loop", "--duration", "0", "--out", &cast],
            "--duration",
        ),
        (
            &["record", "01-the-loop", "--duration", "NaN", "--out", &cast],
            "--duration",
        ),
        (
            &["shot", "01-the-loop", "--size", "0x0", "--svg", &svg],
            "--size",
        ),
        (
            &["run", "01-the-loop", "--steps", "1", "--integrator", "rk5"],
            "rk4",
        ),
    ];
    for (args, flag) in cases {
        refused(&tumble(args), &[flag]);
    }
    // A dt of 1e300 runs and diverges at once, with a short message (no 300-digit number).
    let huge = tumble(&["run", "01-the-loop", "--steps", "2", "--dt", "1e300"]);
    assert_eq!(huge.code, 3, "{}", huge.stderr);
    assert!(huge.stderr.len() < 200, "{}", huge.stderr);
    assert!(huge.stderr.contains("dt = 1e300 s"), "{}", huge.stderr);
}

// --- 6. Overflow and underflow, named where they are formed -------------------------------

#[test]
fn overflow_and_underflow_are_named_not_blamed_on_collinear_points() {
    let points = file(
        "points-1e200.toml",
        "title = \"p\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n[body]\nshape = \"points\"\n\
         points = [[1e200, 0, 0], [0, 1e200, 0], [0, 0, 1e200], [1e200, 1e200, 1e200]]\nmass = 1.0\n",
    );
    let big_box = file(
        "box-1e200.toml",
        box_scene("", "mass = 1.0").replace("[1.0, 1.0, 1.0]", "[1e200, 1.0, 1.0]"),
    );
    let subnormal = file("subnormal.toml", box_scene("", "mass = 5e-324"));
    let fast = file(
        "fast.toml",
        box_scene("", "mass = 1.0\nvelocity = [1e308, 1e308, 0]"),
    );
    let heavy_g = file(
        "heavy-gravity.toml",
        box_scene("gravity = [0.0, -9.81, 0.0]", "mass = 1e308"),
    );
    // (file, the key's line:column, words of the message); box_scene puts [body] on line 6,
    // `size` on line 8 and the body's keys from line 9.
    let cases: [(&str, &str, &[&str]); 5] = [
        (&points, ":7:10:", &["inertia tensor overflows"]),
        (&big_box, ":8:8:", &["inertia tensor overflows"]),
        (&subnormal, ":9:8:", &["mass 5e-324 kg is too small"]),
        (&fast, ":6:1:", &["kinetic energy", "`velocity`"]),
        (
            &heavy_g,
            ":6:1:",
            &["weight M·g overflows", "`mass` × `gravity`"],
        ),
    ];
    for (path, at, words) in cases {
        let out = tumble(&["check", path]);
        refused(&out, words);
        assert!(out.stderr.contains(at), "{at}: {}", out.stderr);
        assert!(!out.stderr.contains("one line"), "{}", out.stderr);
    }
}

#[test]
fn extreme_but_valid_bodies_run() {
    // 1e308 kg at rest, no gravity: nothing moves, nothing diverges (the inverse inertia
    // 6/1e308 is formed in the principal frame: the determinant, ~(1e307)³, overflows).
    let heavy = file("heavy.toml", box_scene("", "mass = 1e308"));
    let out = tumble(&["run", &heavy, "--steps", "3"]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(
        out.stdout.lines().last(),
        Some("3,0.03,0,0,0,1,0,0,0,0,0,0,0,0,0,0,0,0,0,0")
    );
    // A quaternion [1e300, 0, 0, 1e300] is a rotation of 90° about z: (√½, 0, 0, √½).
    let quat = file(
        "quaternion.toml",
        box_scene(
            "",
            "mass = 1.0\norientation = { quaternion = [1e300, 0, 0, 1e300] }",
        ),
    );
    let out = tumble(&["run", &quat, "--steps", "1"]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let row0: Vec<&str> = out.stdout.lines().nth(1).unwrap().split(',').collect();
    let qw: f64 = row0[5].parse().unwrap();
    let qz: f64 = row0[8].parse().unwrap();
    assert!((qw - 0.5f64.sqrt()).abs() < 1e-15 && (qz - 0.5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn mesh_files_directories_and_f64_vertices() {
    let dir = scratch().join("a-folder.obj");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = |name: &str, mesh: &str| {
        file(
            name,
            format!(
                "title = \"m\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n[body]\nshape = \"mesh\"\n\
                 file = \"{mesh}\"\nmass = 1.0\n"
            ),
        )
    };
    let out = tumble(&["check", &scene("mesh-dir.toml", "a-folder.obj")]);
    refused(&out, &["is a directory"]);
    // A tetrahedron of side ~1e39 m: finite as f64 (f32 stops at 3.4e38).
    file(
        "big.obj",
        "v 1e39 0 0\nv 0 1e39 0\nv 0 0 1e39\nv 0 0 0\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n",
    );
    let out = tumble(&["check", &scene("mesh-big.toml", "big.obj")]);
    assert!(!out.stderr.contains("not finite"), "{}", out.stderr);
}

// --- 7. Non-finite numbers are never printed ----------------------------------------------

#[test]
fn run_never_prints_a_non_finite_number() {
    // A sheet of 1e200 m: its particles are finite, its energy is not; refused at load.
    let sheet = file(
        "huge-sheet.toml",
        "title = \"c\"\n[scene]\ndt = 0.002\nintegrator = \"rk4\"\ngravity = [0.0, -9.81, 0.0]\n\
         contact = { response = \"impulse\" }\n[[obstacle]]\ntype = \"ground\"\nheight = 0.0\n\
         [[cloth]]\nname = \"s\"\nsize = [1e200, 1e200]\ncount = [3, 3]\nposition = [0.0, 0.6, 0.0]\n\
         mass = 0.25\nstretch = 400.0\nintegrator = \"symplectic-euler\"\n",
    );
    for path in [
        sheet.as_str(),
        "tests/fixtures/diverging/overflowing-spin.toml",
    ] {
        let out = tumble(&["run", path, "--steps", "5"]);
        assert_ne!(out.code, 0, "{}", out.stdout);
        for word in ["inf", "NaN"] {
            assert!(!out.stdout.contains(word), "{path}: {}", out.stdout);
        }
    }
}

// --- 8. Control characters from files are escaped everywhere ------------------------------

#[test]
fn control_characters_from_files_are_escaped_in_every_command() {
    // ESC ] 0 ; … BEL sets the terminal's title, ESC [ 2 J clears the screen.
    let path = file(
        "escapes.toml",
        "title = \"t\\u001b]0;pwned\\u0007\\u001b[2J\"\nsummary = \"s\\u001b[31m\"\n[scene]\n\
         dt = 0.01\nintegrator = \"rk4\"\n[body]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1.0\n\
         [[page]]\nat = 0.0\ntitle = \"p\\u001b[31m\"\ntext = \"line\\u001b[2J\\rback\"\n",
    );
    let bad_name = file(
        "escaped-integrator.toml",
        box_scene("", "mass = 1.0").replace("\"rk4\"", "\"rk\\u001b[2J\""),
    );
    for args in [
        &["check", path.as_str()][..],
        &["walk", &path, "--frames", "1"],
        &["study", &bad_name],
        &["check", &bad_name],
    ] {
        let out = tumble(args);
        let all = format!("{}{}", out.stdout, out.stderr);
        assert!(
            !all.contains('\u{1b}') && !all.contains('\u{7}') && !all.contains('\r'),
            "{args:?}"
        );
        assert!(
            all.contains("\\u{1b}"),
            "{args:?}: the escape is shown: {all}"
        );
    }
}

// --- 9. Small ones ------------------------------------------------------------------------

#[test]
fn an_empty_cloth_name_is_refused() {
    let path = file(
        "empty-cloth-name.toml",
        "title = \"c\"\n[scene]\ndt = 0.002\nintegrator = \"symplectic-euler\"\n\
         contact = { response = \"impulse\" }\n[[cloth]]\nname = \" \"\nsize = [1.0, 1.0]\n\
         count = [3, 3]\nmass = 0.25\nstretch = 400.0\n",
    );
    let out = tumble(&["check", &path]);
    refused(&out, &[":7:8:", "cloth `name` must not be empty"]);
}

#[test]
fn study_svg_into_a_missing_folder_fails_before_the_study() {
    let started = Instant::now();
    let out = tumble(&["study", "--svg", "/no/such/folder/plot.svg"]);
    refused(&out, &["--svg", "no such folder"]);
    assert_eq!(out.stdout, "", "nothing was studied");
    assert!(started.elapsed() < Duration::from_secs(5));
}

// --- 10. TOML edge values, encodings, huge files, directories ------------------------------

#[test]
fn toml_edge_values_and_encodings() {
    let nesting = format!(
        "title = \"d\"\nx = {}{}\n",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    let valid = box_scene("", "mass = 1.0");
    let cases: Vec<(String, &[&str])> = vec![
        (
            file("nan.toml", valid.replace("0.01", "nan")),
            &[":3:6:", "dt must be a finite number"],
        ),
        (
            file("inf.toml", valid.replace("0.01", "inf")),
            &[":3:6:", "dt must be a finite number"],
        ),
        (
            file("neg-inf.toml", valid.replace("mass = 1.0", "mass = -inf")),
            &["mass"],
        ),
        (
            file(
                "dup.toml",
                valid.replace("dt = 0.01", "dt = 0.01\ndt = 0.02"),
            ),
            &["duplicate key"],
        ),
        (file("deep.toml", nesting), &["recursion"]),
        (file("utf16.toml", utf16(&valid)), &["UTF-16"]),
        (
            file("binary.toml", [0u8, 159, 146, 150]),
            &["not a text file"],
        ),
        (file("empty.toml", ""), &["empty file"]),
    ];
    for (path, words) in &cases {
        refused(&tumble(&["check", path]), words);
    }
    // A byte-order mark and CRLF line ends are fine.
    let bom = file("bom.toml", format!("\u{feff}{valid}"));
    let crlf = file("crlf.toml", valid.replace('\n', "\r\n"));
    for path in [bom, crlf] {
        let out = tumble(&["check", &path]);
        assert_eq!(out.code, 0, "{}", out.stderr);
    }
    // 1e308 as dt: valid; one step overflows the fall at once and says so, briefly.
    let huge_dt = file(
        "dt-1e308.toml",
        box_scene("gravity = [0.0, -9.81, 0.0]", "mass = 1.0").replace("0.01", "1e308"),
    );
    let out = tumble(&["run", &huge_dt, "--steps", "1"]);
    assert_eq!(out.code, 3, "{}", out.stderr);
    assert!(out.stderr.len() < 200);
}

/// UTF-16 little-endian with its byte-order mark.
fn utf16(text: &str) -> Vec<u8> {
    let mut bytes = vec![0xff, 0xfe];
    for unit in text.encode_utf16() {
        bytes.extend(unit.to_le_bytes());
    }
    bytes
}

#[test]
fn huge_files_and_directories_where_files_are_expected() {
    // A 100 MB file (sparse: nothing is written) is refused before it is read.
    let path = scratch().join("huge.toml");
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(100 << 20).unwrap();
    let huge = path.to_string_lossy().into_owned();
    let started = Instant::now();
    refused(
        &tumble(&["check", &huge]),
        &["more than the limit of 16777216"],
    );
    refused(
        &tumble(&["run", &huge, "--steps", "1"]),
        &["more than the limit"],
    );
    assert!(started.elapsed() < Duration::from_secs(5));
    let dir = scratch().to_string_lossy().into_owned();
    refused(&tumble(&["check", &dir]), &["is a directory"]);
    refused(&tumble(&["run", &dir, "--steps", "1"]), &["is a directory"]);
    refused(
        &tumble(&["shot", "01-the-loop", "--svg", &dir]),
        &["cannot write"],
    );
    refused(
        &tumble(&["record", "01-the-loop", "--duration", "0.1", "--out", &dir]),
        &["cannot write"],
    );
    refused(&tumble(&["study", "--svg", &dir]), &["is a directory"]);
}
