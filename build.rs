//! Compiles the bundled lessons into the binary: every `lessons/*.toml` and `lessons/meshes/*`
//! becomes an entry `("lessons/NAME", include_str!(…))` of `$OUT_DIR/bundled.rs`, so that an
//! installed `tumble` (`cargo install`) finds them from any folder.

use std::fmt::Write as _;
use std::path::Path;

fn main() {
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
