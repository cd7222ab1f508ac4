//! A page's measuring tools (`stopwatch`, `period`, `ruler`, `protractor`): read into the
//! page, and every mistake refused at its file:line:column, exit 2.

use std::path::Path;
use tumble::measure::protractor::{BodyAxis, Reference};
use tumble::measure::ruler::Point;
use tumble::scene::PagePanel;

/// Lesson 46's scene (a rod on a hinge) with one page whose line 20 is `line`.
fn source(line: &str) -> String {
    format!(
        r#"title = "rod"
[scene]
dt = 0.001
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]

[body]
name = "rod"
shape = "box"
size = [0.05, 1.0, 0.05]
mass = 1.0
position = [0.25, -0.4330127018922193, 0.0]
orientation = {{ axis = [0.0, 0.0, 1.0], degrees = 30.0 }}

[[joint]]
name = "pivot"
type = "hinge"
bodies = ["rod"]
anchor = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]

[[page]]
at = 0.5
title = "Tools"
text = "measure"
{line}
"#
    )
}

#[test]
fn a_page_sets_its_tools_and_names_their_panels() {
    let text = source(
        r#"stopwatch = { stop = 2.0 }
period = { quantity = "rod.x", level = 0.0 }
ruler = { from = "rod", from_point = [0.0, -0.5, 0.0], to = "pivot.b" }
protractor = { axis = "rod.y" }"#,
    );
    let lesson = tumble::scene::parse(&text, Path::new("rod.toml")).unwrap();
    let page = &lesson.pages[0];
    assert_eq!(
        page.panels,
        vec![
            PagePanel::Stopwatch,
            PagePanel::Period,
            PagePanel::Ruler,
            PagePanel::Protractor
        ]
    );
    let t = &page.tools;
    // The stopwatch starts at the page's `at` unless told.
    let w = t.stopwatch.unwrap();
    assert_eq!((w.start, w.stop), (0.5, Some(2.0)));
    let p = t.period.as_ref().unwrap();
    assert_eq!((p.quantity.as_str(), p.level), ("rod.x", Some(0.0)));
    let r = t.ruler.as_ref().unwrap();
    assert_eq!(
        r.from.point,
        Point::Body {
            body: 0,
            offset: nalgebra::Vector3::new(0.0, -0.5, 0.0)
        }
    );
    assert_eq!(r.to.point, Point::World(nalgebra::Vector3::zeros()));
    // The rod's lower end, 1 m from the hinge at t = 0.
    let d = r.read(&[lesson.scene.bodies[0].initial]).unwrap().distance;
    assert!((d - 1.0).abs() < 1e-15, "{d}");
    let a = t.protractor.unwrap();
    assert_eq!(a.axis, BodyAxis { body: 0, axis: 1 });
    assert_eq!(a.against, Reference::Vertical);
}

#[test]
fn every_mistake_in_a_tool_is_refused_where_it_is() {
    let cases = [
        (
            r#"period = { quantity = "rod.q" }"#,
            "rod.toml:26:23: period: unknown quantity `rod.q` (did you mean `rod.x`?)",
        ),
        (
            r#"period = { quantity = "rod.x", levl = 0.0 }"#,
            "rod.toml:26:32: unknown key `levl` (did you mean `level`?)",
        ),
        (
            r#"ruler = { from = "rood", to = "pivot.b" }"#,
            "rod.toml:26:18: ruler `from`: unknown point `rood` (did you mean `rod`?): the named \
             points are rod, pivot.a, pivot.b",
        ),
        (
            r#"ruler = { to = "pivot.b" }"#,
            "rod.toml:26:9: ruler: `from` or `from_point` is required",
        ),
        (
            r#"ruler = { from = "pivot.a", from_point = [0.0, 0.0, 0.0], to = "rod" }"#,
            "rod.toml:26:42: ruler `from_point` goes with a body's name",
        ),
        (
            r#"ruler = { from = "rod", to_point = [0.0, 1.0] }"#,
            "rod.toml:26:36: wrong length: expected an array of 3 numbers",
        ),
        (
            r#"protractor = { axis = "rod.w" }"#,
            "rod.toml:26:23: protractor `axis`: `rod.w` is not BODY.x, BODY.y or BODY.z",
        ),
        (
            r#"protractor = { axis = "rod.x", against = "horizontal" }"#,
            "rod.toml:26:42: protractor `against` (`vertical` or BODY.x|y|z): unknown body \
             `horizontal`",
        ),
        (
            r#"stopwatch = { start = 2.0, stop = 1.0 }"#,
            "rod.toml:26:35: stopwatch `stop` (1 s) is before its start (2 s)",
        ),
        (
            r#"panels = ["stopwatch", "clock"]"#,
            "rod.toml:26:24: page `panels`: unknown panel `clock` (panels: state, inertia, \
             angular-velocity, forces, momentum, angular-momentum, energy, body-energy, system, \
             cloth, joints, stopwatch, period, ruler, protractor, energy-bars)",
        ),
    ];
    for (line, expected) in cases {
        let e = tumble::scene::parse(&source(line), Path::new("rod.toml"))
            .expect_err(line)
            .to_string();
        assert!(e.starts_with(expected), "{e}\nexpected: {expected}");
    }
}

#[test]
fn tumble_check_exits_2_on_an_unknown_tool_name() {
    let dir = std::env::temp_dir().join(format!("tumble-page-tools-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("rod.toml");
    std::fs::write(&file, source(r#"panels = ["stopwatch", "clock"]"#)).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .arg("check")
        .arg(&file)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("rod.toml:26:24: page `panels`: unknown panel `clock`"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}
