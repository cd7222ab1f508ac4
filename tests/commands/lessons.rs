//! Every bundled lesson loads, and runs its whole `duration` without diverging — except the
//! lessons whose point is a divergence, which must diverge with the message they promise.

use tumble::lessons;

/// Lessons that are meant to diverge, with the start of the message their pages quote.
const DIVERGING: &[(&str, &str)] = &[
    // Lessons 5 and 8: seed adds a force to L at every step a corner is inside, spinning the
    // cube up until it turns more than half a turn per step; their pages say where the guard
    // stops the run.
    (
        "05-ground-collision.toml",
        "simulation diverged at step 440 (t = 0.440000 s): rotation no longer resolved",
    ),
    (
        "08-climbing-bug.toml",
        "simulation diverged at step 460 (t = 0.460000 s): rotation no longer resolved",
    ),
    // Lesson 11: explicit Euler pumps energy into a fast spin about the major axis; its pages
    // say the guard stops the run at step 532 (t = 0.532 s).
    (
        "11-fast-spin.toml",
        "simulation diverged at step 532 (t = 0.532000 s): energy ran away",
    ),
];

fn name(path: &std::path::Path) -> String {
    path.file_name().unwrap().to_string_lossy().into_owned()
}

#[test]
fn there_are_at_least_the_lessons_of_this_branch() {
    let names: Vec<String> = lessons::bundled().iter().map(|p| name(p)).collect();
    for expected in [
        "01-the-loop.toml",
        "02-rigid-body-from-points.toml",
        "03-rotation-drift.toml",
        "04-gravity-no-torque.toml",
        "09-viscosity.toml",
        "10-tennis-racket.toml",
        "11-fast-spin.toml",
        "12-accuracy-cost.toml",
    ] {
        assert!(
            names.iter().any(|n| n == expected),
            "{expected} missing from {names:?}"
        );
    }
}

#[test]
fn every_bundled_lesson_has_a_title_summary_duration_and_pages() {
    for path in lessons::bundled() {
        let lesson = tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        assert!(!lesson.summary.is_empty(), "{}: no summary", path.display());
        assert!(
            lesson.scene.duration.is_some(),
            "{}: no duration",
            path.display()
        );
        assert!(!lesson.pages.is_empty(), "{}: no pages", path.display());
        assert_eq!(
            lesson.pages[0].at,
            0.0,
            "{}: first page must start at t = 0",
            path.display()
        );
        let duration = lesson.scene.duration.unwrap();
        for page in &lesson.pages {
            assert!(
                page.at < duration,
                "{}: page `{}` at {} s is after the end ({duration} s)",
                path.display(),
                page.title,
                page.at
            );
        }
    }
}

#[test]
fn every_bundled_lesson_runs_its_duration_or_diverges_as_promised() {
    for path in lessons::bundled() {
        let lesson = tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let scene = &lesson.scene;
        let steps = (scene.duration.unwrap() / scene.dt).round() as u64;
        let mut world = scene.world();
        let mut diverged = None;
        for _ in 0..steps {
            world.step();
            if let Some(d) = world.divergence() {
                diverged = Some(d.to_string());
                break;
            }
        }
        let expected = DIVERGING.iter().find(|(n, _)| *n == name(&path));
        match (expected, diverged) {
            (None, None) => {}
            (None, Some(message)) => panic!("{}: {message}", path.display()),
            (Some((_, promised)), Some(message)) => assert!(
                message.starts_with(promised),
                "{}: diverged with `{message}`, the lesson promises `{promised}`",
                path.display()
            ),
            (Some(_), None) => panic!(
                "{}: was meant to diverge and ran {steps} steps",
                path.display()
            ),
        }
    }
}

#[test]
fn the_readme_table_lists_every_bundled_lesson_with_its_summary() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    for path in lessons::bundled() {
        let lesson = tumble::scene::load(&path).unwrap();
        let row = format!("| {} | {} |", lesson.title, lesson.summary);
        assert!(
            readme.contains(&row),
            "README.md's lesson table has no row ending `{row}` for {}",
            path.display()
        );
    }
}

#[test]
fn the_readme_integrator_table_has_every_integrators_descriptor_row() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    for integrator in tumble::physics::Integrator::ALL {
        let d = integrator.descriptor();
        let row = format!(
            "| `{}` | {} | {} | {} |",
            d.name, d.summary, d.order, d.keeps
        );
        assert!(
            readme.contains(&row),
            "README.md's integrator table has no row `{row}`"
        );
    }
}

#[test]
fn the_readme_response_table_has_every_responses_descriptor_row() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    for response in tumble::physics::Response::ALL {
        let d = response.descriptor();
        let row = format!("| `{}` | {} | {} |", d.name, d.summary, d.keeps);
        assert!(
            readme.contains(&row),
            "README.md's response table has no row `{row}`"
        );
    }
}

#[test]
fn the_complete_example_of_the_lesson_format_doc_is_a_valid_lesson() {
    let doc = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/lesson-format.md"
    ))
    .unwrap();
    let (_, rest) = doc
        .split_once("## A complete example")
        .expect("docs/lesson-format.md has a complete example");
    let start = rest.find("```toml\n").unwrap() + "```toml\n".len();
    let source = &rest[start..start + rest[start..].find("```").unwrap()];
    let lesson = tumble::scene::parse(source, std::path::Path::new("example.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    // Its page says L stays constant: drag without `angular` makes no torque.
    let mut world = lesson.scene.world();
    let l0 = world.state().angular_momentum;
    for _ in 0..400 {
        world.step();
    }
    assert_eq!(world.state().angular_momentum, l0);
}

/// Pages written before the 11-line limit, which scroll in the app's lesson pane.
const LONG_PAGES: &[(&str, &str)] = &[
    ("10-tennis-racket.toml", "Integrators compared"),
    ("12-accuracy-cost.toml", "The orders, measured"),
    ("12-accuracy-cost.toml", "What an answer costs"),
    (
        "12-accuracy-cost.toml",
        "Measure it yourself: the study view",
    ),
];

#[test]
fn every_page_fits_86_columns_and_11_lines() {
    for path in lessons::bundled() {
        let lesson = tumble::scene::load(&path).unwrap();
        // As shown: live numbers filled in.
        let live = tumble::live::LiveValues::compute(&lesson, lesson.scene.world());
        for page in &lesson.pages {
            let filled = live.page_text(page);
            let text = filled.trim_matches('\n');
            for line in text.lines() {
                assert!(
                    line.chars().count() <= 86,
                    "{}: page `{}` has a line of {} columns: {line}",
                    path.display(),
                    page.title,
                    line.chars().count()
                );
            }
            let long = LONG_PAGES.contains(&(name(&path).as_str(), page.title.as_str()));
            assert!(
                long || text.lines().count() <= 11,
                "{}: page `{}` has {} lines (at most 11)",
                path.display(),
                page.title,
                text.lines().count()
            );
        }
    }
}
