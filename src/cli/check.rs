//! `tumble check FILE...`: validate scene files (or bundled lessons by name). Every independent
//! error of a file is one line on stderr ([`crate::scene::check_every_error`]); a valid file is
//! an `ok` line on stdout.

use super::output::{line, warn};
use super::Failure;
use crate::lessons;
use crate::scene::{self, LoadError};
use std::path::PathBuf;

/// The lesson of one argument, or every error of it (at least one): the file is read once,
/// as every command reads it, and `check` lists each independent error of the text the
/// loader refused ([`crate::scene::check_every_error`]), the loader's own error among them.
fn errors(argument: &std::path::Path) -> Result<scene::Lesson, Vec<LoadError>> {
    let (path, text) = lessons::read(argument).map_err(|e| vec![e])?;
    scene::parse(&text, &path).map_err(|first| {
        let all = scene::check_every_error(&text, &path);
        if all.is_empty() {
            vec![first]
        } else {
            all
        }
    })
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
        return match errors(path) {
            Ok(lesson) => ok(path, &lesson.title),
            Err(mut all) => {
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
        match errors(path) {
            Ok(lesson) => ok(path, &lesson.title)?,
            Err(all) => {
                for e in all {
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
