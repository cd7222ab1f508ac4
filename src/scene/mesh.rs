//! Wavefront `.obj` meshes: their vertices become the body's mass points, their face edges
//! are drawn.

use nalgebra::Vector3;
use std::collections::BTreeSet;
use std::path::Path;

/// A mesh's vertices and its unique edges (pairs of vertex indices).
pub type Mesh = (Vec<Vector3<f64>>, Vec<(usize, usize)>);

/// Vertices and unique edges of every model in an `.obj` file: on disk, or else one that a
/// bundled lesson refers to (compiled in, see [`crate::lessons`]).
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    if path.is_dir() {
        return Err("is a directory, not an .obj file".to_string());
    }
    // Anything on disk (a FIFO, a device too) is read as every input is: bounded, special
    // files refused by their type.
    let text = if std::fs::symlink_metadata(path).is_ok() {
        let bytes = crate::limits::read_bounded_bytes(path, crate::limits::MAX_FILE_BYTES, "mesh")
            .map_err(|e| e.reason)?;
        String::from_utf8(bytes)
            .map_err(|_| "malformed .obj: not a text file (invalid UTF-8)".to_string())?
    } else {
        crate::lessons::embedded(path)
            .ok_or_else(|| "no such file".to_string())?
            .to_string()
    };
    check_vertex_lines(&text)?;
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: false,
        ignore_points: true,
        ignore_lines: false,
    };
    // Materials are not read (`mtllib` lines are ignored): only the geometry matters.
    let no_materials = |_: &Path| Err(tobj::LoadError::OpenFileFailed);
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, no_materials)
        .map_err(|e| format!("malformed .obj: {e}"))?;
    let mut points = Vec::new();
    let mut edges = BTreeSet::new();
    for model in &models {
        let mesh = &model.mesh;
        let base = points.len();
        for p in mesh.positions.chunks_exact(3) {
            // tobj's `use_f64` feature: coordinates read as f64, as the scene's numbers.
            points.push(Vector3::new(p[0], p[1], p[2]));
        }
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&a| a as usize).collect()
        };
        let mut start = 0;
        for arity in arities {
            let face = &mesh.indices[start..start + arity];
            for k in 0..arity {
                let (a, b) = (
                    face[k] as usize + base,
                    face[(k + 1) % arity] as usize + base,
                );
                if a != b {
                    edges.insert((a.min(b), a.max(b)));
                }
            }
            start += arity;
        }
    }
    if points.is_empty() {
        return Err("malformed .obj: no vertices (`v x y z` lines)".to_string());
    }
    if points.iter().any(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(
            "malformed .obj: a vertex coordinate is not finite (beyond ±1.8e308)".to_string(),
        );
    }
    Ok((points, edges.into_iter().collect()))
}

/// Every `v x y z [w]` line has at least three numbers: names the first line that does not
/// (the .obj reader itself only says "position parse error").
fn check_vertex_lines(text: &str) -> Result<(), String> {
    for (index, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("v") {
            continue;
        }
        let coordinates: Vec<&str> = words.take(3).collect();
        if let Some(bad) = coordinates.iter().find(|w| w.parse::<f64>().is_err()) {
            return Err(format!(
                "malformed .obj: line {}: vertex coordinate `{bad}` is not a number",
                index + 1
            ));
        }
        if coordinates.len() < 3 {
            return Err(format!(
                "malformed .obj: line {}: a vertex needs 3 coordinates, found {}",
                index + 1,
                coordinates.len()
            ));
        }
    }
    Ok(())
}
