//! `tumble check FILE...`: validate scene files, one line per file.

use super::Failure;
use crate::scene;
use std::path::PathBuf;

/// Validates every file; prints `ok` lines on stdout and errors on stderr (for several files,
/// then a summary line).
pub fn check(files: &[PathBuf]) -> Result<(), Failure> {
    if let [path] = files {
        // One file: its error is the one line (no summary line after it).
        let lesson = scene::load(path)?;
        println!("{}: ok ({})", path.display(), lesson.title);
        return Ok(());
    }
    let mut failed = 0;
    for path in files {
        match scene::load(path) {
            Ok(lesson) => println!("{}: ok ({})", path.display(), lesson.title),
            Err(e) => {
                eprintln!("tumble: {e}");
                failed += 1;
            }
        }
    }
    if failed == 0 {
        Ok(())
    } else {
        Err(Failure::bad_input(format!(
            "{failed} of {} files have errors",
            files.len()
        )))
    }
}
