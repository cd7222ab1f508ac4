//! The bundled lessons: the `lessons/` folder of this repository, in teaching order, compiled
//! into the binary (`build.rs`), so that an installed `tumble` has them in any folder.
//!
//! A bundled lesson is named by its path `lessons/NAME.toml` (errors name that path too), or by
//! its name as `tumble lessons` prints it, with or without `.toml`. A file on disk wins: the
//! argument as a path, then `lessons/NAME.toml` under the current folder (a teacher editing a
//! clone sees the edits), then the copy compiled in. Meshes a bundled lesson refers to
//! (`lessons/meshes/*.obj`) are compiled in the same way.

use crate::scene::{self, did_you_mean, Lesson, LoadError};
use std::path::{Component, Path, PathBuf};

/// The folder the bundled lessons are named under.
pub const FOLDER: &str = "lessons";

/// Every bundled file, `(path under the crate, text)`, sorted by path.
static FILES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The folder the bundled lessons are named under, as a path (relative: `lessons`).
pub fn folder() -> PathBuf {
    PathBuf::from(FOLDER)
}

/// The bundled lesson files, `lessons/NAME.toml`, sorted by name (their number prefix gives the
/// order). Load them with [`load`], which falls back on the compiled-in copy.
pub fn bundled() -> Vec<PathBuf> {
    FILES
        .iter()
        .filter(|(path, _)| is_lesson(path))
        .map(|(path, _)| PathBuf::from(path))
        .collect()
}

/// The names `tumble lessons` prints (`01-the-loop`, …), in teaching order.
pub fn names() -> Vec<&'static str> {
    FILES
        .iter()
        .filter(|(path, _)| is_lesson(path))
        .filter_map(|(path, _)| path.strip_prefix("lessons/")?.strip_suffix(".toml"))
        .collect()
}

fn is_lesson(path: &str) -> bool {
    path.ends_with(".toml") && path.matches('/').count() == 1
}

/// The compiled-in text of a bundled file, by its path (`lessons/…`, `./lessons/…`).
pub fn embedded(path: &Path) -> Option<&'static str> {
    let parts: Vec<String> = path
        .components()
        .filter(|c| !matches!(c, Component::CurDir))
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    let key = parts.join("/");
    FILES
        .iter()
        .find(|(path, _)| *path == key)
        .map(|(_, text)| *text)
}

/// The bundled lesson an argument names: `NAME`, `NAME.toml` or `lessons/NAME.toml`.
pub fn named(argument: &Path) -> Option<PathBuf> {
    if embedded(argument).is_some() {
        return Some(argument.to_path_buf());
    }
    let text = argument.to_str()?;
    let name = text.strip_suffix(".toml").unwrap_or(text);
    names()
        .contains(&name)
        .then(|| Path::new(FOLDER).join(format!("{name}.toml")))
}

/// Where an argument's lesson is: a file on disk, or a bundled lesson's compiled-in text.
enum Found {
    Disk(PathBuf),
    Compiled(PathBuf, &'static str),
}

fn find(argument: &Path) -> Option<Found> {
    if argument.exists() {
        return Some(Found::Disk(argument.to_path_buf()));
    }
    let path = named(argument)?;
    if path.is_file() {
        return Some(Found::Disk(path));
    }
    embedded(&path).map(|text| Found::Compiled(path, text))
}

/// Loads a lesson or scene file, or a bundled lesson by name (see the module doc); an unknown
/// name gets a suggestion among the bundled ones.
pub fn load(argument: &Path) -> Result<Lesson, LoadError> {
    let (path, text) = read(argument)?;
    scene::parse(&text, &path)
}

/// The path (as errors name it) and text of the lesson an argument names: the one read every
/// command goes through (a file is read once: `/dev/stdin` cannot be read twice).
pub fn read(argument: &Path) -> Result<(PathBuf, String), LoadError> {
    match find(argument) {
        Some(Found::Disk(path)) => scene::read(&path).map(|text| (path, text)),
        Some(Found::Compiled(path, text)) => Ok((path, text.to_string())),
        None => Err(not_found(argument)),
    }
}

/// [`read`], when it can be read.
pub fn source(argument: &Path) -> Option<(PathBuf, String)> {
    read(argument).ok()
}

/// "no such file" for an argument that is neither a file nor a bundled lesson.
fn not_found(argument: &Path) -> LoadError {
    let text = argument.to_string_lossy();
    let stem = argument
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let looks_like_a_name = argument.extension().is_none_or(|x| x == "toml");
    match did_you_mean(&stem, names()).filter(|_| looks_like_a_name) {
        Some(name) => LoadError::file(
            argument,
            format!("no such file or bundled lesson (did you mean `{name}`?); `tumble lessons` lists them"),
        ),
        None if !text.contains(['/', '\\']) && argument.extension().is_none() => LoadError::file(
            argument,
            "no such file or bundled lesson; `tumble lessons` lists the bundled lessons",
        ),
        None => LoadError::file(argument, "cannot read: no such file"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_lesson_file_of_the_repository_is_compiled_in_with_the_same_text() {
        let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join(FOLDER);
        let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
            .unwrap()
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        on_disk.sort();
        let compiled: Vec<String> = names().iter().map(|n| format!("{n}.toml")).collect();
        assert_eq!(compiled, on_disk);
        for path in bundled() {
            let text =
                std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(&path)).unwrap();
            assert_eq!(embedded(&path), Some(text.as_str()), "{}", path.display());
        }
    }

    #[test]
    fn a_lesson_is_named_with_or_without_its_folder_and_extension() {
        let expected = Some(PathBuf::from("lessons/01-the-loop.toml"));
        assert_eq!(named(Path::new("01-the-loop")), expected);
        assert_eq!(named(Path::new("01-the-loop.toml")), expected);
        assert_eq!(named(Path::new("lessons/01-the-loop.toml")), expected);
        assert_eq!(
            named(Path::new("./lessons/01-the-loop.toml")),
            Some(PathBuf::from("./lessons/01-the-loop.toml"))
        );
        assert_eq!(named(Path::new("01-the-lop")), None);
        assert!(embedded(Path::new("lessons/meshes/house.obj")).is_some());
    }

    #[test]
    fn an_unknown_name_suggests_the_closest_lesson() {
        assert_eq!(
            not_found(Path::new("01-the-lop")).to_string(),
            "01-the-lop: no such file or bundled lesson (did you mean `01-the-loop`?); \
             `tumble lessons` lists them"
        );
        assert_eq!(
            not_found(Path::new("somewhere/else.obj")).to_string(),
            "somewhere/else.obj: cannot read: no such file"
        );
    }
}
