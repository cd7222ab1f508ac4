//! Hostile input, round four (issue 39): the keys and commands this round adds, the reads of
//! every input, the cost of checking, and `check` and `run` agreeing. Every case asserts exit
//! code 2, exactly one line on stderr, the file:line:column (or the flag, or the path) and the
//! limit where one applies; and — through [`tumble`] — that the process neither panicked, was
//! killed by a signal, nor ran past a timeout (a hang).
//!
//! Classes: a false second line from `check` (a body blanked for its own error called unknown);
//! unbounded reads and special files (`/dev/zero`, FIFOs, sockets, `/dev/stdin`); the count of
//! bodies and links and a check linear in them; one table of the keys each shape and joint
//! takes (and arrays of exactly their length); the wrong thing blamed; command-line limits.

use super::hostile::{tumble, tumble_with, Output};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// A scratch folder of this test binary (under target/).
fn scratch() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("hostile4");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `text` to scratch/NAME and returns the path as a string.
fn file(name: &str, text: impl AsRef<[u8]>) -> String {
    let path = scratch().join(name);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Exit 2, exactly one line on stderr, and it contains every `words`.
fn refused(out: &Output, words: &[&str]) {
    assert_eq!(out.code, 2, "expected exit 2:\n{}", out.stderr);
    assert_eq!(
        out.stderr.lines().count(),
        1,
        "exactly one line:\n{}",
        out.stderr
    );
    for w in words {
        assert!(
            out.stderr.contains(w),
            "`{w}` missing from:\n{}",
            out.stderr
        );
    }
}

/// `tumble check PATH` refuses it with one line containing every `words` (the first a
/// `:line:column:`), and `tumble run PATH` prints that same line.
fn check_and_run_refuse(path: &str, words: &[&str]) {
    let check = tumble(&["check", path]);
    refused(&check, words);
    let run = tumble(&["run", path, "--steps", "1"]);
    refused(&run, words);
    assert_eq!(check.stderr, run.stderr, "check and run agree");
}

/// The head of a scene: [scene] with `scene` extra lines.
fn head(scene: &str) -> String {
    format!("title = \"hostile\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n{scene}\n")
}

/// A `[[body]]` named `name` (a unit box at x) — 6 lines.
fn boxed(name: &str, x: f64) -> String {
    format!(
        "[[body]]\nname = \"{name}\"\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n\
         position = [{x}, 0.0, 0.0]\n"
    )
}

/// A one-body scene whose [body] (line 6) has `body` as its lines 7….
fn one_body(body: &str) -> String {
    format!("{}[body]\n{body}\n", head(""))
}

// --- 1. `check` and `run` agree line for line ----------------------------------------------

#[test]
fn a_body_with_its_own_error_is_not_unknown_to_the_joints_springs_and_pages_naming_it() {
    // Three bodies, no `contact`: the error is the second body's (line 12). The joint, the
    // spring, the page's live number and the prediction name `b` rightly.
    let scene = format!(
        "{}{}{}{}[[joint]]\ntype = \"ball\"\nbodies = [\"a\", \"b\"]\nanchor = [1.5, 0.0, 0.0]\n\
         [[spring]]\nbodies = [\"b\", \"c\"]\nanchors = [[3.0, 0.0, 0.0], [6.0, 0.0, 0.0]]\n\
         stiffness = 10.0\n[[page]]\nat = 0.0\ntitle = \"p\"\ntext = \"b is at {{{{b.x}}}}\"\n\
         predict = {{ quantity = \"b.y\", at = 1.0 }}\n",
        head(""),
        boxed("a", 0.0),
        boxed("b", 3.0),
        boxed("c", 6.0)
    );
    let path = file("false-second-line.toml", scene);
    check_and_run_refuse(
        &path,
        &[":12:1:", "several bodies need a collision response"],
    );
}

#[test]
fn a_cloth_attached_to_a_body_with_its_own_error_gives_one_line() {
    // The body's `size` is wrong (line 8); the cloth's `attach` names it rightly.
    let scene = format!(
        "{}[[body]]\nname = \"bob\"\nshape = \"box\"\nsize = [1.0, 0.0, 1.0]\nmass = 1.0\n\
         [[cloth]]\nsize = [1.0, 1.0]\ncount = [3, 3]\nmass = 1.0\nstretch = 100.0\n\
         integrator = \"symplectic-euler\"\nposition = [0.0, 5.0, 0.0]\n\
         attach = [{{ particle = [0, 0], body = \"bob\" }}]\n",
        head("contact = { response = \"impulse\" }")
    );
    let path = file("attach-to-broken-body.toml", scene);
    check_and_run_refuse(&path, &[":9:8:", "box `size` needs three sides > 0 m"]);
}

#[test]
fn many_bodies_without_a_contact_table_are_one_line_at_once() {
    // 200 bodies apart, no `contact`: one error, not 199 (the search used to blank body
    // after body).
    let mut scene = head("");
    for i in 0..200 {
        scene.push_str(&boxed(&format!("b{i}"), 3.0 * f64::from(i)));
    }
    let path = file("many-no-contact.toml", scene);
    check_and_run_refuse(
        &path,
        &[":12:1:", "several bodies need a collision response"],
    );
}

#[test]
fn two_keys_with_the_same_mistake_are_two_lines_of_check() {
    // `size` and `position` both with 4 numbers: `check` reports both (the same message at
    // two places is two errors), `run` the first.
    let path = file(
        "two-same-mistakes.toml",
        one_body(
            "shape = \"box\"\nsize = [1.0, 1.0, 1.0, 1.0]\nmass = 1.0\n\
             position = [0.0, 0.0, 0.0, 0.0]",
        ),
    );
    let check = tumble(&["check", &path]);
    assert_eq!(check.code, 2);
    let lines: Vec<&str> = check.stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{}", check.stderr);
    assert!(lines[0].contains(":8:8: wrong length: expected an array of 3 numbers, found 4"));
    assert!(lines[1].contains(":10:12: wrong length"), "{}", lines[1]);
}

// --- 2. Bounded reads; special files refused by their type ---------------------------------

#[test]
fn dev_zero_is_refused_by_every_command_without_reading_it() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    let svg = scratch().join("z.svg").to_string_lossy().into_owned();
    for args in [
        &["check", "/dev/zero"][..],
        &["run", "/dev/zero", "--steps", "1"],
        &["walk", "/dev/zero", "--frames", "1"],
        &["study", "/dev/zero"],
        &["shot", "/dev/zero", "--svg", &svg],
    ] {
        let out = tumble(args);
        refused(
            &out,
            &["/dev/zero: is a character device", "not a regular file"],
        );
    }
}

#[test]
fn a_fifo_with_no_writer_is_refused_at_once() {
    let fifo = scratch().join("no-writer.fifo");
    let _ = std::fs::remove_file(&fifo);
    if !Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        return;
    }
    let path = fifo.to_string_lossy().into_owned();
    for args in [
        &["check", path.as_str()][..],
        &["run", &path, "--steps", "1"],
    ] {
        refused(&tumble(args), &["no-writer.fifo: is a named pipe (FIFO)"]);
    }
    // As a mesh too: the scene's `file` line is named.
    let scene = file(
        "fifo-mesh.toml",
        one_body("shape = \"mesh\"\nfile = \"no-writer.fifo\"\nmass = 1.0"),
    );
    refused(
        &tumble(&["check", &scene]),
        &[":8:8:", "is a named pipe (FIFO)"],
    );
}

#[test]
fn a_socket_and_a_device_as_a_mesh_are_refused() {
    let socket = scratch().join("a.sock");
    let _ = std::fs::remove_file(&socket);
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    let path = socket.to_string_lossy().into_owned();
    refused(&tumble(&["check", &path]), &["a.sock: is a socket"]);
    let zero_mesh = file(
        "zero-mesh.toml",
        one_body("shape = \"mesh\"\nfile = \"/dev/zero\"\nmass = 1.0"),
    );
    refused(
        &tumble(&["check", &zero_mesh]),
        &[":8:8:", "mesh `/dev/zero`", "character device"],
    );
}

#[test]
fn dev_stdin_is_read_with_the_same_bound() {
    // A scene on standard input: read, checked, run.
    let scene = file(
        "stdin.toml",
        one_body("shape = \"box\"\nsize = [1, 1, 1]\nmass = 1.0"),
    );
    let out = tumble_with(
        &["run", "/dev/stdin", "--steps", "1"],
        Stdio::from(std::fs::File::open(&scene).unwrap()),
    );
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(out.stdout.lines().count(), 3);
    // An endless standard input stops at the bound, naming it.
    if std::path::Path::new("/dev/zero").exists() {
        let out = tumble_with(
            &["check", "/dev/stdin"],
            Stdio::from(std::fs::File::open("/dev/zero").unwrap()),
        );
        refused(
            &out,
            &["/dev/stdin: more than the limit of 16777216 bytes for a scene file"],
        );
    }
    // `check` reads it once: the error is the file's, not an "empty file".
    let broken = file("stdin-broken.toml", one_body("shape = \"box\"\nmass = 1.0"));
    let out = tumble_with(
        &["check", "/dev/stdin"],
        Stdio::from(std::fs::File::open(&broken).unwrap()),
    );
    refused(&out, &["/dev/stdin:6:1:", "a box body needs `size`"]);
}

#[test]
fn a_proc_file_of_size_zero_is_read_not_trusted() {
    // /proc files say they are 0 bytes long: read (bounded), found not to be a scene.
    if !std::path::Path::new("/proc/self/status").exists() {
        return;
    }
    refused(
        &tumble(&["check", "/proc/self/status"]),
        &["/proc/self/status:1:", "TOML syntax error"],
    );
}

// --- 3. Counts of bodies and links; a check linear in them ---------------------------------

/// A chain of `n` spheres 0.5 m apart along x, the first hung from the world by a ball joint
/// and each of the others jointed to the one before; `springs` springs added between the
/// first two bodies.
fn chain(n: usize, springs: usize) -> String {
    let mut s = head("gravity = [0.0, -9.81, 0.0]\ncontact = { response = \"impulse\" }");
    for i in 0..n {
        s.push_str(&format!(
            "[[body]]\nname = \"b{i}\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
             position = [{}, 0.0, 0.0]\n",
            0.5 * i as f64
        ));
    }
    s.push_str("[[joint]]\ntype = \"ball\"\nbodies = [\"b0\"]\nanchor = [0.0, 0.0, 0.0]\n");
    for i in 1..n {
        s.push_str(&format!(
            "[[joint]]\ntype = \"ball\"\nbodies = [\"b{}\", \"b{i}\"]\nanchor = [{}, 0.0, 0.0]\n",
            i - 1,
            0.5 * i as f64 - 0.25
        ));
    }
    for _ in 0..springs {
        s.push_str(
            "[[spring]]\nbodies = [\"b0\", \"b1\"]\nanchors = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0]]\n\
             stiffness = 10.0\n",
        );
    }
    s
}

#[test]
fn a_chain_at_the_limits_checks_and_one_past_them_is_refused_by_name() {
    // 1000 bodies and 1000 joints: the limits themselves (this took 0.65 s to check, cubic).
    let at_limit = file("chain-1000.toml", chain(1000, 0));
    let out = tumble(&["check", &at_limit]);
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("ok (hostile)"));
    // One spring more: 1001 links. The error is at the spring (line 6 + 6000 + 4000 + 1).
    let links = file("chain-1000-spring.toml", chain(1000, 1));
    check_and_run_refuse(
        &links,
        &[
            ":10007:1:",
            "1000 joints and 1 springs",
            "more than the limit of 1000 joints and springs",
        ],
    );
}

#[test]
fn ten_thousand_links_are_refused_by_the_limit_at_the_first_body_past_it() {
    // The 1001st [[body]] starts on line 6 + 6 · 1000 + 1.
    let path = file("chain-10000.toml", chain(10_000, 0));
    check_and_run_refuse(
        &path,
        &[
            ":6007:1:",
            "this scene has 10000 bodies, more than the limit of 1000 bodies",
        ],
    );
}

#[test]
fn a_thousand_links_between_two_bodies_are_within_the_limit_and_one_more_is_not() {
    // Springs alone count too: 1001 springs between two boxes.
    let mut s = format!(
        "{}{}{}",
        head("contact = { response = \"impulse\" }"),
        boxed("a", 0.0),
        boxed("b", 3.0)
    );
    for _ in 0..1001 {
        s.push_str(
            "[[spring]]\nbodies = [\"a\", \"b\"]\nanchors = [[0.5, 0.0, 0.0], [2.5, 0.0, 0.0]]\n\
             stiffness = 10.0\n",
        );
    }
    let path = file("springs-1001.toml", s);
    // The 1001st spring: line 6 + 12 + 4 · 1000.
    check_and_run_refuse(
        &path,
        &[":4018:1:", "0 joints and 1001 springs", "limit of 1000"],
    );
}

// --- 4. One table of keys per shape and joint type; exact array lengths --------------------

#[test]
fn a_key_of_another_shape_is_named_with_the_shape_that_takes_it() {
    // (body lines, the key's line:column, words).
    let cases: [(&str, &str, &[&str]); 8] = [
        (
            "shape = \"sphere\"\nradius = 0.5\nsize = [1.0, 1.0, 1.0]\nmass = 1.0",
            ":9:8:",
            &[
                "`size` does not apply to a sphere body",
                "a key of box",
                "radius",
            ],
        ),
        (
            "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\nradius = 0.5\nmass = 1.0",
            ":9:10:",
            &[
                "`radius` does not apply to a box body",
                "sphere, capsule, cylinder",
            ],
        ),
        (
            "shape = \"sphere\"\nradius = 0.5\nlength = 1.0\nmass = 1.0",
            ":9:10:",
            &[
                "`length` does not apply to a sphere body",
                "capsule, cylinder",
            ],
        ),
        (
            "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\npoints = [[0.0, 0.0, 0.0]]\nmass = 1.0",
            ":9:10:",
            &["`points` does not apply to a box body", "a key of points"],
        ),
        (
            "shape = \"sphere\"\nradius = 0.5\nfile = \"cube.obj\"\nmass = 1.0",
            ":9:8:",
            &["`file` does not apply to a sphere body", "a key of mesh"],
        ),
        (
            "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmasses = [1.0]\nmass = 1.0",
            ":9:10:",
            &["`masses` does not apply to a box body"],
        ),
        (
            "shape = \"capsule\"\nradius = 0.5\nlength = 1.0\nsize = [1.0, 1.0, 1.0]\nmass = 1.0",
            ":10:8:",
            &[
                "`size` does not apply to a capsule body",
                "valid keys of a capsule body",
            ],
        ),
        (
            "shape = \"mesh\"\nfile = \"x.obj\"\nradius = 0.5\nmass = 1.0",
            ":9:10:",
            &["`radius` does not apply to a mesh body"],
        ),
    ];
    for (i, (body, at, words)) in cases.into_iter().enumerate() {
        let path = file(&format!("shape-key-{i}.toml"), one_body(body));
        let mut all = vec![at];
        all.extend_from_slice(words);
        check_and_run_refuse(&path, &all);
    }
}

#[test]
fn an_unknown_shape_is_blamed_not_its_keys() {
    let path = file(
        "unknown-shape.toml",
        one_body("shape = \"sphre\"\nradius = 0.5\nmass = 1.0"),
    );
    check_and_run_refuse(
        &path,
        &[":7:9:", "unknown shape `sphre` (did you mean `sphere`?)"],
    );
    let path = file(
        "unknown-shape-size.toml",
        one_body("shape = \"cube\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0"),
    );
    check_and_run_refuse(
        &path,
        &[":7:9:", "unknown shape `cube`", "valid shapes: box"],
    );
}

#[test]
fn arrays_take_exactly_their_length() {
    let cases: [(String, &str, &str); 6] = [
        (
            one_body(
                "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\nposition = [0, 0, 0, 1]",
            ),
            ":10:12:",
            "expected an array of 3 numbers, found 4 elements",
        ),
        (
            one_body("shape = \"box\"\nsize = [1.0, 1.0]\nmass = 1.0"),
            ":8:8:",
            "expected an array of 3 numbers, found 2 elements",
        ),
        (
            one_body(
                "shape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n\
                 orientation = { quaternion = [1, 0, 0, 0, 0] }",
            ),
            ":10:30:",
            "expected an array of 4 numbers, found 5 elements",
        ),
        (
            one_body(
                "shape = \"points\"\npoints = [[0, 0, 0], [1, 0, 0, 9], [0, 1, 0], [0, 0, 1]]\n\
                 mass = 1.0",
            ),
            ":8:10:",
            "expected an array of 3 numbers, found 4 elements",
        ),
        (
            format!(
                "{}[[cloth]]\nsize = [1.0, 1.0, 1.0]\ncount = [3, 3]\nmass = 1.0\nstretch = 1.0\n\
                 integrator = \"symplectic-euler\"\n",
                head("contact = { response = \"impulse\" }")
            ),
            ":7:8:",
            "expected an array of 2 numbers, found 3 elements",
        ),
        (
            format!(
                "{}[[cloth]]\nsize = [1.0, 1.0]\ncount = [3, 3, 3]\nmass = 1.0\nstretch = 1.0\n\
                 integrator = \"symplectic-euler\"\n",
                head("contact = { response = \"impulse\" }")
            ),
            ":8:9:",
            "expected an array of 2 numbers, found 3 elements",
        ),
    ];
    for (i, (scene, at, words)) in cases.into_iter().enumerate() {
        let path = file(&format!("exact-{i}.toml"), scene);
        check_and_run_refuse(&path, &[at, words]);
    }
}

/// A cloth of 3 × 3 attached by `attach` (line 16) to a box `bob` (lines 6–10).
fn attached(attach: &str) -> String {
    format!(
        "{}[[body]]\nname = \"bob\"\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n\
         [[cloth]]\nsize = [1.0, 1.0]\ncount = [3, 3]\nmass = 1.0\nstretch = 100.0\n\
         position = [0.0, 5.0, 0.0]\nintegrator = \"symplectic-euler\"\nattach = [{attach}]\n",
        head("contact = { response = \"impulse\" }")
    )
}

#[test]
fn attach_entries_are_refused_for_their_own_faults() {
    let cases: [(&str, &str, &str); 5] = [
        // No `body`: the entry's fault, not a missing [body] table.
        (
            "{ particle = [0, 0] }",
            ":18:11:",
            "this attach entry has no `body`",
        ),
        (
            "{ particle = [0, 0, 1], body = \"bob\" }",
            ":18:24:",
            "expected an array of 2 numbers, found 3 elements",
        ),
        (
            "{ particle = [0], body = \"bob\" }",
            ":18:24:",
            "expected an array of 2 numbers, found 1 element",
        ),
        (
            "{ particle = [0, 0], body = \"bob\", mass = 1.0 }",
            ":18:",
            "unknown key `mass`",
        ),
        (
            "\"bob\"",
            ":18:11:",
            "expected a table `{ particle = [i, j]",
        ),
    ];
    for (i, (attach, at, words)) in cases.into_iter().enumerate() {
        let path = file(&format!("attach-{i}.toml"), attached(attach));
        check_and_run_refuse(&path, &[at, words]);
        assert!(!tumble(&["check", &path]).stderr.contains("[body]"));
    }
}

#[test]
fn a_predict_of_the_wrong_type_names_no_internal_type() {
    for (i, predict) in ["\"cube.y\"", "1.0", "true"].into_iter().enumerate() {
        let path = file(
            &format!("predict-{i}.toml"),
            format!(
                "{}[[page]]\nat = 0.0\ntitle = \"p\"\ntext = \"t\"\npredict = {predict}\n",
                one_body("shape = \"box\"\nsize = [1, 1, 1]\nmass = 1.0")
            ),
        );
        let out = tumble(&["check", &path]);
        refused(
            &out,
            &[
                ":14:11:",
                "expected a table `{ quantity = \"cube.y\", at = 1.0 }`",
            ],
        );
        assert!(!out.stderr.contains("Raw"), "{}", out.stderr);
    }
}

/// A scene of one sphere `arm` (lines 6–10) and one joint (`[[joint]]` on line 11) of these
/// lines.
fn jointed(joint: &str) -> String {
    format!(
        "{}[[body]]\nname = \"arm\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
         [[joint]]\n{joint}\n",
        head("")
    )
}

#[test]
fn a_key_of_another_joint_type_is_named_with_a_suggestion() {
    let cases: [(&str, &str, &[&str]); 5] = [
        (
            "type = \"ball\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]",
            ":15:8:",
            &["`axis` does not apply to a ball joint", "a key of hinge"],
        ),
        (
            "type = \"ball\"\nbodies = [\"arm\"]\nanchors = [[0, 0, 0], [1, 0, 0]]",
            ":14:11:",
            &["`anchors` does not apply to a ball joint (did you mean `anchor`?"],
        ),
        (
            "type = \"hinge\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]\nlength = 1.0",
            ":16:10:",
            &["`length` does not apply to a hinge joint", "a key of distance"],
        ),
        (
            "type = \"distance\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]",
            ":14:10:",
            &["`anchor` does not apply to a distance joint (did you mean `anchors`?"],
        ),
        (
            "type = \"hing\"\nbodies = [\"arm\"]\naxis = [0, 0, 1]",
            ":12:8:",
            &["unknown joint type `hing` (did you mean `hinge`?)"],
        ),
    ];
    for (i, (joint, at, words)) in cases.into_iter().enumerate() {
        let path = file(&format!("joint-key-{i}.toml"), jointed(joint));
        let mut all = vec![at];
        all.extend_from_slice(words);
        let out = tumble(&["run", &path, "--steps", "1"]);
        refused(&out, &all);
    }
}

#[test]
fn spring_and_joint_points_take_three_numbers() {
    let spring = file(
        "spring-4.toml",
        format!(
            "{}[[spring]]\nbodies = [\"arm\"]\nanchors = [[0, 0, 0], [1, 0, 0, 0]]\n\
             stiffness = 1.0\n",
            jointed("type = \"ball\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]")
        ),
    );
    check_and_run_refuse(
        &spring,
        &[":17:11:", "expected an array of 3 numbers, found 4"],
    );
    let anchor = file(
        "anchor-2.toml",
        jointed("type = \"ball\"\nbodies = [\"arm\"]\nanchor = [0, 0]"),
    );
    check_and_run_refuse(
        &anchor,
        &[":14:10:", "expected an array of 3 numbers, found 2"],
    );
}

// --- 5. The command line names its limits, in one line --------------------------------------

#[test]
fn screen_sizes_past_the_limits_name_them() {
    let svg = scratch().join("s.svg").to_string_lossy().into_owned();
    let cast = scratch().join("s.cast").to_string_lossy().into_owned();
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &[
                "shot",
                "01-the-loop",
                "--svg",
                &svg,
                "--size",
                "99999x99999",
            ],
            &["--size", "limit of 4000 cells a side"],
        ),
        (
            &[
                "record",
                "01-the-loop",
                "--duration",
                "0.1",
                "--out",
                &cast,
                "--size",
                "99999x99999",
            ],
            &["--size", "limit of 4000 cells a side"],
        ),
        (
            &[
                "shot",
                "01-the-loop",
                "--svg",
                &svg,
                "--size",
                "123456789012345678901234567890x40",
            ],
            &[
                "--size",
                "123456789012345678901234567890x40",
                "limit of 4000",
            ],
        ),
        (
            &["shot", "01-the-loop", "--svg", &svg, "--size", "2000x1000"],
            &["--size", "2000000 cells, more than the limit of 1000000"],
        ),
        (
            &["shot", "01-the-loop", "--svg", &svg, "--size", "12x"],
            &["--size", "size must be COLSxROWS"],
        ),
    ];
    for (args, words) in cases {
        let out = tumble(args);
        refused(&out, words);
        assert!(!out.stderr.contains("malformed"), "{}", out.stderr);
    }
}

#[test]
fn usage_errors_are_one_line_naming_the_flag() {
    let svg = scratch().join("u.svg").to_string_lossy().into_owned();
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["shot", "01-the-loop", "--svg", &svg, "--plot-x", "cube.x"],
            &["--plot <QUANTITY>", "not provided"],
        ),
        (
            &["run", "01-the-loop"],
            &["--steps <STEPS>", "not provided"],
        ),
        (
            &["run", "01-the-loop", "--stepz", "3"],
            &["--stepz", "similar argument exists: '--steps'"],
        ),
        (
            &["walk", "01-the-loop", "--frames", "x"],
            &["invalid value 'x' for '--frames"],
        ),
    ];
    for (args, words) in cases {
        let out = tumble(args);
        refused(&out, words);
        assert!(
            !out.stderr.contains("For more information"),
            "{}",
            out.stderr
        );
    }
}

// --- 6. This round's keys: joint limits, motors, sliders, impacts ---------------------------

/// Runs `check` and `run` on `jointed(joint)` for each case: (joint lines, at, words).
fn joint_cases(name: &str, cases: &[(&str, &str, &[&str])]) {
    for (i, (joint, at, words)) in cases.iter().enumerate() {
        let path = file(&format!("{name}-{i}.toml"), jointed(joint));
        let mut all = vec![*at];
        all.extend_from_slice(words);
        check_and_run_refuse(&path, &all);
    }
}

/// A hinge about z at the origin, with `extra` (line 16).
const HINGE: &str = "type = \"hinge\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]";
/// A slider along x at the origin, with `extra` (line 16).
const SLIDER: &str = "type = \"slider\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [1, 0, 0]";

#[test]
fn joint_limits_out_of_order_malformed_or_misplaced() {
    let with = |extra: &str| format!("{HINGE}\n{extra}");
    let cases: Vec<(String, &str, &[&str])> = vec![
        (
            with("limits = [10, 90]"),
            ":16:10:",
            &["hinge `limits` must hold 0", "lo ≤ 0 ≤ hi"],
        ),
        (
            with("limits = [-90, -10]"),
            ":16:10:",
            &["hinge `limits` must hold 0"],
        ),
        (
            with("limits = [\"a\", 1]"),
            ":16:11:",
            &["expected a number, found the string \"a\""],
        ),
        (
            with("limits = [-1, 0, 1]"),
            ":16:10:",
            &["needs two numbers [lo, hi] (degrees), found 3 numbers"],
        ),
        (with("limits = [-1]"), ":16:10:", &["found 1 number"]),
        (with("limits = []"), ":16:10:", &["found 0 numbers"]),
        (
            with("limits = [-200, 200]"),
            ":16:10:",
            &["less than a full turn apart (hi − lo < 360°)"],
        ),
        (
            with("limits = [-inf, 1]"),
            ":16:10:",
            &["must be finite numbers"],
        ),
        (
            with("limits = [nan, 1]"),
            ":16:10:",
            &["must be finite numbers"],
        ),
        (with("limits = \"wide\""), ":16:10:", &["expected an array"]),
        (
            format!("{SLIDER}\nlimits = [0.5, 1.0]"),
            ":16:10:",
            &["slider `limits` must hold 0"],
        ),
        (
            "type = \"ball\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\nlimits = [-1, 1]".into(),
            ":15:10:",
            &[
                "`limits` does not apply to a ball joint",
                "a key of hinge, slider",
            ],
        ),
        (
            "type = \"distance\"\nbodies = [\"arm\"]\nanchors = [[0, 0, 0], [1, 0, 0]]\n\
             limits = [-1, 1]"
                .into(),
            ":15:10:",
            &["`limits` does not apply to a distance joint"],
        ),
    ];
    let cases: Vec<(&str, &str, &[&str])> =
        cases.iter().map(|(j, a, w)| (j.as_str(), *a, *w)).collect();
    joint_cases("limits", &cases);
}

#[test]
fn joint_motors_with_wrong_bounds_missing_keys_or_on_the_wrong_joint() {
    let hinge = |extra: &str| format!("{HINGE}\n{extra}");
    let slider = |extra: &str| format!("{SLIDER}\n{extra}");
    let cases: Vec<(String, &str, &[&str])> = vec![
        (
            hinge("motor = { speed = 1.0, max_torque = -5.0 }"),
            ":16:37:",
            &["motor `max_torque` must be > 0, found -5"],
        ),
        (
            slider("motor = { speed = 1.0, max_force = -1.0 }"),
            ":16:36:",
            &["motor `max_force` must be > 0, found -1"],
        ),
        (
            slider("motor = { speed = 1.0, max_force = 0.0 }"),
            ":16:36:",
            &["motor `max_force` must be > 0, found 0"],
        ),
        (
            hinge("motor = { max_torque = 5.0 }"),
            ":16:9:",
            &["a hinge joint's `motor` needs `speed`"],
        ),
        (
            slider("motor = { speed = 1.0 }"),
            ":16:9:",
            &["a slider joint's `motor` needs `max_force`"],
        ),
        (
            slider("motor = { speed = 1.0, max_torque = 5.0 }"),
            ":16:37:",
            &["a slider's motor takes `max_force` (N), not `max_torque`"],
        ),
        (
            hinge("motor = { speed = 1.0, max_force = 5.0 }"),
            ":16:36:",
            &["a hinge's motor takes `max_torque` (N·m), not `max_force`"],
        ),
        (
            slider("motor = { speed = nan, max_force = 5.0 }"),
            ":16:19:",
            &["motor `speed` must be a finite number"],
        ),
        (
            slider("motor = { speed = \"fast\", max_force = 5.0 }"),
            ":16:19:",
            &["expected a number, found the string \"fast\""],
        ),
        (
            slider("motor = { speed = 1.0, max_force = 5.0, torque = 1 }"),
            ":16:41:",
            &["unknown key `torque`", "speed, max_force, max_torque"],
        ),
        (
            slider("motor = 5.0"),
            ":16:9:",
            &["expected a table `{ speed = …, max_force = … }` (slider)"],
        ),
        (
            "type = \"distance\"\nbodies = [\"arm\"]\nanchors = [[0, 0, 0], [1, 0, 0]]\n\
             motor = { speed = 1.0, max_force = 5.0 }"
                .into(),
            ":15:9:",
            &[
                "`motor` does not apply to a distance joint",
                "a key of hinge, slider",
            ],
        ),
        (
            "type = \"fixed\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\n\
             motor = { speed = 1.0, max_torque = 5.0 }"
                .into(),
            ":15:9:",
            &["`motor` does not apply to a fixed joint"],
        ),
        (
            "type = \"ball\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\n\
             motor = { speed = 1.0, max_torque = 5.0 }"
                .into(),
            ":15:9:",
            &["`motor` does not apply to a ball joint"],
        ),
    ];
    let cases: Vec<(&str, &str, &[&str])> =
        cases.iter().map(|(j, a, w)| (j.as_str(), *a, *w)).collect();
    joint_cases("motor", &cases);
}

#[test]
fn sliders_without_an_axis_or_anchor_or_with_keys_of_other_joints() {
    joint_cases(
        "slider",
        &[
            (
                "type = \"slider\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 0]",
                ":15:8:",
                &["slider `axis` has zero length"],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\"]\naxis = [1, 0, 0]",
                ":11:1:",
                &["a slider joint needs `anchor`"],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]",
                ":11:1:",
                &["a slider joint needs `axis`"],
            ),
            (
                "type = \"slidr\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [1, 0, 0]",
                ":12:8:",
                &[
                    "unknown joint type `slidr` (did you mean `slider`?)",
                    "slider",
                ],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\"]\nanchors = [[0, 0, 0], [1, 0, 0]]\n\
                 axis = [1, 0, 0]",
                ":14:11:",
                &["`anchors` does not apply to a slider joint (did you mean `anchor`?"],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [1, 0, 0]\n\
                 length = 1.0",
                ":16:10:",
                &[
                    "`length` does not apply to a slider joint",
                    "a key of distance",
                ],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\"]\nanchor = [0, 0, 0]\naxis = [1, 0, 0, 0]",
                ":15:8:",
                &["expected an array of 3 numbers, found 4 elements"],
            ),
            (
                "type = \"slider\"\nbodies = [\"arm\", \"arm\"]\nanchor = [0, 0, 0]\n\
                 axis = [1, 0, 0]",
                ":13:18:",
                &["a joint's two bodies must differ, found `arm` twice"],
            ),
        ],
    );
}

#[test]
fn impacts_words_on_every_response() {
    // (response, impacts value, column, words); the contact table is line 5.
    let cases: [(&str, &str, &str, &[&str]); 8] = [
        (
            "impulse",
            "\"propogate\"",
            ":5:45:",
            &["unknown impact law `propogate` (did you mean `propagate`?)"],
        ),
        (
            "impulse",
            "\"PROPAGATE\"",
            ":5:45:",
            &["unknown impact law `PROPAGATE`", "propagate, simultaneous"],
        ),
        ("impulse", "\"\"", ":5:45:", &["unknown impact law ``"]),
        (
            "impulse",
            "1",
            ":5:45:",
            &["expected a string, found the integer 1"],
        ),
        (
            "impulse",
            "[\"propagate\"]",
            ":5:45:",
            &["expected a string, found an array"],
        ),
        (
            "impulse",
            "true",
            ":5:45:",
            &["expected a string, found the boolean true"],
        ),
        (
            "seed",
            "\"propagate\"",
            ":5:42:",
            &["`impacts` is a key of the `impulse` response, not of `seed`"],
        ),
        (
            "soft-step",
            "\"simultaneous\"",
            ":5:47:",
            &["`impacts` is a key of the `impulse` response, not of `soft-step`"],
        ),
    ];
    for (i, (response, value, at, words)) in cases.into_iter().enumerate() {
        let scene = format!(
            "{}[body]\nshape = \"box\"\nsize = [1, 1, 1]\nmass = 1.0\n",
            head(&format!(
                "contact = {{ response = \"{response}\", impacts = {value} }}"
            ))
        );
        let path = file(&format!("impacts-{i}.toml"), scene);
        let mut all = vec![at];
        all.extend_from_slice(words);
        check_and_run_refuse(&path, &all);
    }
}

// --- 7. `diff`: the hostile extras (its own suite tests malformed CSVs) ---------------------

#[test]
fn diff_reads_its_csv_bounded_and_refuses_special_files() {
    let mut cases: Vec<(String, Vec<&str>)> = Vec::new();
    if std::path::Path::new("/dev/zero").exists() {
        cases.push(("/dev/zero".into(), vec!["/dev/zero: is a character device"]));
    }
    let fifo = scratch().join("diff.fifo");
    let _ = std::fs::remove_file(&fifo);
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        cases.push((
            fifo.to_string_lossy().into_owned(),
            vec!["diff.fifo: is a named pipe (FIFO)"],
        ));
    }
    // A 1 GB file (sparse: nothing written): refused before it is read, naming the limit.
    let huge = scratch().join("huge.csv");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    cases.push((
        huge.to_string_lossy().into_owned(),
        vec!["1073741824 bytes, more than the limit of 268435456 for a CSV"],
    ));
    cases.push((
        scratch().to_string_lossy().into_owned(),
        vec!["is a directory, not a CSV"],
    ));
    cases.push((
        scratch().join("none.csv").to_string_lossy().into_owned(),
        vec!["none.csv: cannot read: no such file"],
    ));
    for (csv, words) in &cases {
        let out = tumble(&["diff", "01-the-loop", csv]);
        refused(&out, words);
        assert!(!out.stderr.contains(":0:"), "{}", out.stderr);
    }
    // An endless standard input: stopped at the bound.
    if std::path::Path::new("/dev/zero").exists() {
        let out = tumble_with(
            &["diff", "01-the-loop", "/dev/stdin"],
            Stdio::from(std::fs::File::open("/dev/zero").unwrap()),
        );
        refused(
            &out,
            &["/dev/stdin: more than the limit of 268435456 bytes for a CSV"],
        );
    }
}

#[test]
fn diff_flags_and_scenes_are_refused_in_one_line() {
    let csv = file("ok.csv", "step,x\n0,0\n");
    let escape = file("escape.csv", "step,x\n0,1\u{1b}[2J\n");
    let utf16 = file("utf16.csv", [0xff, 0xfe, b's', 0, b't', 0]);
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["diff", "01-the-loop", &csv, "--tolerance", "-1"],
            &["--tolerance", "must be a number > 0"],
        ),
        (
            &["diff", "01-the-loop", &csv, "--tolerance", "nan"],
            &["--tolerance", "must be a number > 0"],
        ),
        (
            &["diff", "/dev/zero", &csv],
            &["/dev/zero: is a character device"],
        ),
        (
            &["diff", "01-the-loop", &csv, "--body", "cub"],
            &["no body named `cub`", "bodies: body1"],
        ),
        (&["diff", "01-the-loop", &escape], &["\\u{1b}[2J", ":2:"]),
        (
            &["diff", "01-the-loop", &utf16],
            &["utf16.csv:1:", "not UTF-8"],
        ),
    ];
    for (args, words) in cases {
        let out = tumble(args);
        refused(&out, words);
        assert!(
            !out.stderr.contains("-- -1"),
            "no wrong tip: {}",
            out.stderr
        );
        assert!(!out.stderr.contains('\u{1b}'));
    }
}

// --- 8. `walk --error` with bad frames and files --------------------------------------------

#[test]
fn walk_error_with_bad_frames_and_files_is_one_line() {
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["walk", "01-the-loop", "--frames", "x", "--error"],
            &["invalid value 'x' for '--frames"],
        ),
        (
            &["walk", "01-the-loop", "--frames", "-1", "--error"],
            &["'--frames", "must be a whole number ≥ 0"],
        ),
        (
            &["walk", "01-the-loop", "--frames", "1.5", "--error"],
            &["'--frames", "no decimal point or exponent"],
        ),
        (
            &[
                "walk",
                "01-the-loop",
                "--frames",
                "99999999999999999999",
                "--error",
            ],
            &["'--frames", "at most 18446744073709551615"],
        ),
        (
            &["walk", "01-the-loop", "--frames", "1", "--error", "--error"],
            &["--error", "cannot be used multiple times"],
        ),
        (
            &["walk", "/dev/zero", "--frames", "1", "--error"],
            &["/dev/zero: is a character device"],
        ),
    ];
    for (args, words) in cases {
        let out = tumble(args);
        refused(&out, words);
        assert_eq!(out.stdout, "", "{args:?}");
    }
    // A diverging scene: exit 3 with its one line, the frames before it printed.
    let out = tumble(&[
        "walk",
        "tests/fixtures/diverging/euler-seed-fast-spin.toml",
        "--frames",
        "100",
        "--error",
    ]);
    assert_eq!(out.code, 3, "{}", out.stderr);
    assert_eq!(out.stderr.lines().count(), 1, "{}", out.stderr);
    assert!(out.stderr.contains("simulation diverged at step 5"));
}

// --- The force arrows in `shot` and `record` (merged after the suite was written) -------------

#[test]
fn force_arrows_in_shot_and_record_refuse_bad_values_in_one_line() {
    let svg = scratch().join("f.svg").to_string_lossy().into_owned();
    let cast = scratch().join("f.cast").to_string_lossy().into_owned();
    let pendulum = "25-the-pendulum";
    let cases: [(&[&str], &[&str]); 5] = [
        (
            &["shot", pendulum, "--forces", "--at", "-1", "--svg", &svg],
            &["--at", "found -1"],
        ),
        (
            &["shot", pendulum, "--forces=yes", "--at", "1", "--svg", &svg],
            &["'yes'", "--forces"],
        ),
        (
            &[
                "shot", pendulum, "--forces", "--forces", "--at", "1", "--svg", &svg,
            ],
            &["--forces", "multiple times"],
        ),
        (
            &[
                "shot", pendulum, "--forces", "--at", "1", "--svg", &svg, "--size", "20x5",
            ],
            &["--size", "80x24"],
        ),
        (
            &[
                "record",
                pendulum,
                "--forces",
                "--duration",
                "nan",
                "--out",
                &cast,
            ],
            &["--duration", "NaN"],
        ),
    ];
    for (args, words) in cases {
        refused(&tumble(args), words);
    }
}
