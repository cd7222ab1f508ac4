//! The bundled lessons: the `lessons/` folder of this repository, in teaching order.
//!
//! The folder is found at `$TUMBLE_LESSONS` if set, else where the crate was built from.

use std::path::PathBuf;

/// The folder holding the bundled lessons.
pub fn folder() -> PathBuf {
    std::env::var_os("TUMBLE_LESSONS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/lessons")))
}

/// The bundled lesson files (`*.toml`), sorted by name (their number prefix gives the order).
pub fn bundled() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder())
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}
