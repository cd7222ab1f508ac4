//! `tumble walk` snapshots: one per bundled lesson (`insta::glob!`), over its first frames
//! (phase by phase for lesson 1). A new lesson gets its snapshot automatically; every number in
//! a snapshot was checked by hand against the formulas before it was accepted (see the lesson
//! pages, which quote the same numbers).

use std::path::Path;
use tumble::cli::walk::write_walk;

/// Frames walked per lesson: lesson 1 phase by phase, the others frame by frame.
fn plan(path: &Path) -> (u64, bool) {
    let name = path.file_name().unwrap().to_string_lossy();
    if name.starts_with("01-") {
        (2, true)
    } else {
        (3, false)
    }
}

#[test]
fn walk_snapshot_of_every_bundled_lesson() {
    insta::glob!("../../lessons", "*.toml", |path| {
        let lesson = tumble::scene::load(path).unwrap_or_else(|e| panic!("{e}"));
        let (frames, phases) = plan(path);
        let mut out = Vec::new();
        if let Err(e) = write_walk(&lesson, frames, phases, &mut out) {
            panic!("walk of {} stopped: {e:?}", path.display());
        }
        let text = String::from_utf8(out).expect("walk prints UTF-8");
        insta::assert_snapshot!("walk", text);
    });
}

#[test]
fn walk_is_identical_when_run_twice() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/lessons/03-rotation-drift.toml"
    ));
    let lesson = tumble::scene::load(path).unwrap();
    let run = || {
        let mut out = Vec::new();
        write_walk(&lesson, 50, true, &mut out).unwrap();
        out
    };
    assert_eq!(run(), run());
}
