//! Two lists made from folders, so that adding a file is all it takes:
//!
//! - the bundled lessons: every `lessons/*.toml` and `lessons/meshes/*` becomes an entry
//!   `("lessons/NAME", include_str!(…))` of `$OUT_DIR/bundled.rs`, so that an installed `tumble`
//!   (`cargo install`) finds them from any folder;
//! - the obstacle kinds: every `src/physics/collision/obstacle/kinds/NAME.rs` becomes a module
//!   of `$OUT_DIR/obstacle_kinds.rs` and an entry `NAME::Name` of `obstacle_kinds!` (its struct is
//!   named as its file, in CamelCase), so a new kind is its one file.

use std::fmt::Write as _;
use std::path::Path;

fn main() {
    bundle_lessons();
    list_obstacle_kinds();
}

fn bundle_lessons() {
    println!("cargo:rerun-if-changed=lessons");
    // Read when the script runs, not when it was compiled: a build script compiled in another
    // checkout (a copied target/, a worktree) must still bundle this checkout's lessons.
    let manifest_dir = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = Path::new(&manifest_dir);
    let mut files = Vec::new();
    for folder in ["lessons", "lessons/meshes"] {
        let Ok(entries) = std::fs::read_dir(root.join(folder)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let wanted = path.extension().is_some_and(|x| x == "toml" || x == "obj");
            if path.is_file() && wanted {
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                files.push((format!("{folder}/{name}"), path));
            }
        }
    }
    files.sort();
    let mut out = String::from("&[\n");
    for (name, path) in &files {
        let _ = writeln!(
            out,
            "    ({name:?}, include_str!({:?})),",
            path.display().to_string()
        );
    }
    out.push(']');
    let target = Path::new(&std::env::var("OUT_DIR").unwrap()).join("bundled.rs");
    std::fs::write(target, out).unwrap();
}

/// `src/physics/collision/obstacle/kinds/*.rs`, in file-name order: `pub mod kinds { … }` with a
/// module per file (by its absolute path: the list is included from `$OUT_DIR`), then
/// `obstacle_kinds!(module::Struct, …)`.
fn list_obstacle_kinds() {
    const FOLDER: &str = "src/physics/collision/obstacle/kinds";
    println!("cargo:rerun-if-changed={FOLDER}");
    let manifest_dir = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let folder = Path::new(&manifest_dir).join(FOLDER);
    let mut modules: Vec<(String, std::path::PathBuf)> = std::fs::read_dir(&folder)
        .expect("the obstacle kinds' folder")
        .flatten()
        .map(|entry| entry.path())
        .filter(|path| path.is_file() && path.extension().is_some_and(|x| x == "rs"))
        .map(|path| {
            let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
            (stem, path)
        })
        .collect();
    modules.sort();
    let mut out = String::from("pub mod kinds {\n");
    for (module, path) in &modules {
        let _ = writeln!(
            out,
            "    #[path = {:?}]\n    pub mod {module};",
            path.display().to_string()
        );
    }
    out.push_str("}\n\nobstacle_kinds!(\n");
    for (module, _) in &modules {
        let _ = writeln!(out, "    {module}::{},", camel_case(module));
    }
    out.push_str(");\n");
    let target = Path::new(&std::env::var("OUT_DIR").unwrap()).join("obstacle_kinds.rs");
    std::fs::write(target, out).unwrap();
}

/// `aligned_box` → `AlignedBox`.
fn camel_case(snake: &str) -> String {
    snake
        .split('_')
        .map(|word| {
            let mut chars = word.chars();
            chars
                .next()
                .map(|first| first.to_uppercase().chain(chars).collect::<String>())
                .unwrap_or_default()
        })
        .collect()
}
