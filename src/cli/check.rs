//! `tumble check FILE...`: validate scene files (or bundled lessons by name). Every independent
//! error of a file is one line on stderr ([`crate::scene::check_every_error`]); a valid file is
//! an `ok` line on stdout.

use super::output::{line, warn};
use super::Failure;
use crate::lessons;
use crate::scene::{self, LoadError};
use std::path::PathBuf;

/// Every error of one file (at least one when it does not load).
fn errors(path: &std::path::Path, first: LoadError) -> Vec<LoadError> {
    let all = lessons::source(path)
        .map(|(path, text)| scene::check_every_error(&text, &path))
        .unwrap_or_default();
    if all.is_empty() {
        vec![first]
    } else {
        all
    }
}

/// The `ok` line of a valid file (its title's control characters escaped).
fn ok(path: &std::path::Path, title: &str) -> Result<(), Failure> {
    line(&scene::printable(&format!(
        "{}: ok ({title})",
        path.display()
    )))
}

/// Validates every file; prints `ok` lines on stdout and errors on stderr (for several files,
/// then a summary line).
pub fn check(files: &[PathBuf]) -> Result<(), Failure> {
    if let [path] = files {
        // One file: its errors are the lines (no summary line after them).
        return match lessons::load(path) {
            Ok(lesson) => ok(path, &lesson.title),
            Err(first) => {
                let mut all = errors(path, first);
                let last = all.pop().map(|e| e.to_string()).unwrap_or_default();
                for e in all {
                    warn(&e.to_string());
                }
                Err(Failure::bad_input(last))
            }
        };
    }
    let mut failed = 0;
    for path in files {
        match lessons::load(path) {
            Ok(lesson) => ok(path, &lesson.title)?,
            Err(first) => {
                for e in errors(path, first) {
                    warn(&e.to_string());
                }
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
