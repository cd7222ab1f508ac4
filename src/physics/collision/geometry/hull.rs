//! The convex hull of a point set: the smallest convex polyhedron holding every point, as
//! vertices, polygonal faces and edges.
//!
//! # Construction: incremental ("beneath–beyond"), by hand
//!
//! ```text
//! 1. start from a tetrahedron of four extreme points:
//!      p₀ = lowest x;  p₁ = farthest from p₀;  p₂ = farthest from the line p₀p₁;
//!      p₃ = farthest from the plane p₀p₁p₂      (any of them ≈ 0 → the set is degenerate)
//! 2. for every other point p:
//!      the faces that *see* p:  n·p − d > ε      (p beyond their plane)
//!      none → p is inside, skip it
//!      the horizon: edges a→b of seen faces whose twin b→a belongs to an unseen face
//!      remove the seen faces; add a triangle (a, b, p) per horizon edge (keeps the
//!      counter-clockwise order seen from outside, so normals stay outward)
//! 3. merge neighbouring triangles that lie in one plane into one polygonal face (a cube gives
//!    6 squares, not 12 triangles): its loop is the chain of the group's edges a→b whose twin
//!    b→a is not in the group; drop loop vertices on a straight run; normal by Newell's formula
//!       n ∝ Σᵢ (yᵢ − yᵢ₊₁)(zᵢ + zᵢ₊₁), (zᵢ − zᵢ₊₁)(xᵢ + xᵢ₊₁), (xᵢ − xᵢ₊₁)(yᵢ + yᵢ₊₁)
//! 4. edges: each pair of consecutive loop vertices (a, b) with a < b (each edge is in two
//!    loops, once each way); directions: the distinct edge directions up to sign
//! ```
//!
//! ε = 1e-9 × the size of the point set. Cost O(n·f) for n points and f faces: fine for the
//! few hundred vertices of a teaching mesh (quickhull's outside sets would make it O(n log n)).
//! A hull is built once per body, not per step.

use nalgebra::Vector3;
use std::collections::HashMap;

/// Why a point set has no hull with volume.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HullError {
    #[error("a convex hull needs at least 4 points, got {count}")]
    TooFewPoints { count: usize },
    #[error("point {index} is not finite: a convex hull needs finite coordinates")]
    NotFinite { index: usize },
    #[error("all points coincide: a convex hull needs volume")]
    Coincident,
    #[error("all points lie on one line: a convex hull needs volume")]
    Collinear,
    #[error("all points lie in one plane: a convex hull needs volume")]
    Coplanar,
}

/// One polygonal face of a hull.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    /// Outward unit normal, body frame.
    pub normal: Vector3<f64>,
    /// The face lies in the plane normal·p = offset.
    pub offset: f64,
    /// Indices into the hull's vertices, counter-clockwise seen from outside.
    pub vertices: Vec<usize>,
}

/// One edge of a hull.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// Its two end vertices (smaller index first).
    pub vertices: [usize; 2],
    /// Index of its direction in the hull's `directions`.
    pub direction: usize,
}

/// A convex polyhedron in its body frame.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexHull {
    /// Corner points (only true corners: points inside, on a face or along an edge are dropped).
    pub vertices: Vec<Vector3<f64>>,
    pub faces: Vec<Face>,
    /// Every edge once.
    pub edges: Vec<Edge>,
    /// The distinct edge directions up to sign, unit.
    pub directions: Vec<Vector3<f64>>,
}

/// A triangle during construction: vertex indices (counter-clockwise from outside) and plane.
#[derive(Debug, Clone, Copy)]
struct Triangle {
    v: [usize; 3],
    normal: Vector3<f64>,
    offset: f64,
}

impl Triangle {
    fn new(points: &[Vector3<f64>], v: [usize; 3]) -> Triangle {
        let [a, b, c] = v.map(|i| points[i]);
        let normal = (b - a).cross(&(c - a)).normalize();
        Triangle {
            v,
            normal,
            offset: normal.dot(&a),
        }
    }

    fn height(&self, p: &Vector3<f64>) -> f64 {
        self.normal.dot(p) - self.offset
    }

    fn edges(&self) -> [(usize, usize); 3] {
        let [a, b, c] = self.v;
        [(a, b), (b, c), (c, a)]
    }
}

impl ConvexHull {
    /// The box with half-extents `half`, as a hull (its 8 corners).
    pub fn cuboid(half: &Vector3<f64>) -> ConvexHull {
        let corners: Vec<Vector3<f64>> = (0..8)
            .map(|i| {
                let s = |bit: usize| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
                Vector3::new(s(0) * half.x, s(1) * half.y, s(2) * half.z)
            })
            .collect();
        ConvexHull::from_points(&corners).expect("a box with positive half-extents has volume")
    }

    /// The convex hull of `points` (body frame). Fails on fewer than 4 points, non-finite
    /// coordinates, or a set without volume (all coincident, collinear or coplanar).
    pub fn from_points(points: &[Vector3<f64>]) -> Result<ConvexHull, HullError> {
        if points.len() < 4 {
            return Err(HullError::TooFewPoints {
                count: points.len(),
            });
        }
        if let Some(index) = points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(HullError::NotFinite { index });
        }
        let (lo, hi) = points.iter().fold(
            (points[0], points[0]),
            |(lo, hi): (Vector3<f64>, Vector3<f64>), p| (lo.inf(p), hi.sup(p)),
        );
        let size = (hi - lo).norm();
        let eps = 1e-9 * size.max(f64::MIN_POSITIVE);

        let seed = initial_tetrahedron(points, eps)?;
        let mut triangles: Vec<Triangle> = Vec::new();
        let centroid = seed.iter().map(|&i| points[i]).sum::<Vector3<f64>>() / 4.0;
        for [a, b, c] in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
            let mut t = Triangle::new(points, [seed[a], seed[b], seed[c]]);
            if t.height(&centroid) > 0.0 {
                t = Triangle::new(points, [seed[a], seed[c], seed[b]]);
            }
            triangles.push(t);
        }

        for (index, p) in points.iter().enumerate() {
            if seed.contains(&index) {
                continue;
            }
            let seen: Vec<bool> = triangles.iter().map(|t| t.height(p) > eps).collect();
            if !seen.iter().any(|&s| s) {
                continue;
            }
            let seen_edges: Vec<(usize, usize)> = triangles
                .iter()
                .zip(&seen)
                .filter(|(_, &s)| s)
                .flat_map(|(t, _)| t.edges())
                .collect();
            let horizon: Vec<(usize, usize)> = seen_edges
                .iter()
                .copied()
                .filter(|&(a, b)| !seen_edges.contains(&(b, a)))
                .collect();
            let mut kept: Vec<Triangle> = triangles
                .iter()
                .zip(&seen)
                .filter(|(_, &s)| !s)
                .map(|(t, _)| *t)
                .collect();
            kept.extend(
                horizon
                    .iter()
                    .map(|&(a, b)| Triangle::new(points, [a, b, index])),
            );
            triangles = kept;
        }
        Ok(merge_coplanar(points, &triangles, eps))
    }

    /// (min, max) of u·r over the vertices (u in the body frame).
    pub fn extent(&self, u: &Vector3<f64>) -> (f64, f64) {
        self.vertices
            .iter()
            .map(|v| u.dot(v))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    }
}

/// Four points spanning a volume, or why there are none.
fn initial_tetrahedron(points: &[Vector3<f64>], eps: f64) -> Result<[usize; 4], HullError> {
    let farthest = |score: &dyn Fn(&Vector3<f64>) -> f64| {
        points.iter().enumerate().map(|(i, p)| (i, score(p))).fold(
            (0, f64::NEG_INFINITY),
            |best, x| if x.1 > best.1 { x } else { best },
        )
    };
    let (i0, _) = farthest(&|p| -p.x);
    let p0 = points[i0];
    let (i1, d1) = farthest(&|p| (p - p0).norm());
    if d1 <= eps {
        return Err(HullError::Coincident);
    }
    let line = (points[i1] - p0) / d1;
    let (i2, d2) = farthest(&|p| (p - p0).cross(&line).norm());
    if d2 <= eps {
        return Err(HullError::Collinear);
    }
    let normal = (points[i1] - p0).cross(&(points[i2] - p0)).normalize();
    let (i3, d3) = farthest(&|p| (p - p0).dot(&normal).abs());
    if d3 <= eps {
        return Err(HullError::Coplanar);
    }
    Ok([i0, i1, i2, i3])
}

/// Union–find root with path halving.
fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Step 3 and 4 of the module doc: triangles → polygonal faces, edges, directions.
fn merge_coplanar(points: &[Vector3<f64>], triangles: &[Triangle], eps: f64) -> ConvexHull {
    // Which triangle owns each directed edge.
    let owner: HashMap<(usize, usize), usize> = triangles
        .iter()
        .enumerate()
        .flat_map(|(t, tri)| tri.edges().map(|e| (e, t)))
        .collect();
    let mut parent: Vec<usize> = (0..triangles.len()).collect();
    for (t, tri) in triangles.iter().enumerate() {
        for (a, b) in tri.edges() {
            let Some(&u) = owner.get(&(b, a)) else {
                continue;
            };
            let other = &triangles[u];
            let coplanar = tri.normal.dot(&other.normal) > 1.0 - 1e-12
                || other.v.iter().all(|&v| tri.height(&points[v]).abs() <= eps);
            if coplanar {
                let (ra, rb) = (root(&mut parent, t), root(&mut parent, u));
                parent[ra] = rb;
            }
        }
    }
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for t in 0..triangles.len() {
        groups.entry(root(&mut parent, t)).or_default().push(t);
    }
    let mut group_list: Vec<Vec<usize>> = groups.into_values().collect();
    group_list.sort();

    let mut loops: Vec<Vec<usize>> = Vec::new();
    for group in &group_list {
        let inside: Vec<(usize, usize)> =
            group.iter().flat_map(|&t| triangles[t].edges()).collect();
        let next: HashMap<usize, usize> = inside
            .iter()
            .copied()
            .filter(|&(a, b)| !inside.contains(&(b, a)))
            .collect();
        let start = *next.keys().min().expect("a face has a boundary");
        let mut ring = vec![start];
        let mut at = next[&start];
        while at != start && ring.len() <= next.len() {
            ring.push(at);
            at = next[&at];
        }
        // Drop vertices on a straight run (a point in the middle of an edge).
        let straight = |ring: &[usize], i: usize| {
            let n = ring.len();
            let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            (points[b] - points[a])
                .cross(&(points[c] - points[b]))
                .norm()
                <= eps * (points[c] - points[a]).norm()
        };
        let mut i = 0;
        while i < ring.len() && ring.len() > 3 {
            if straight(&ring, i) {
                ring.remove(i);
            } else {
                i += 1;
            }
        }
        loops.push(ring);
    }

    // Keep only the vertices that are loop corners, renumbered in input order.
    let mut used: Vec<usize> = loops.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let renumber: HashMap<usize, usize> = used.iter().enumerate().map(|(k, &i)| (i, k)).collect();
    let vertices: Vec<Vector3<f64>> = used.iter().map(|&i| points[i]).collect();

    let faces: Vec<Face> = loops
        .iter()
        .map(|ring| {
            let ring: Vec<usize> = ring.iter().map(|i| renumber[i]).collect();
            let n = ring.len();
            let mut normal = Vector3::zeros();
            for i in 0..n {
                let (p, q) = (vertices[ring[i]], vertices[ring[(i + 1) % n]]);
                normal += Vector3::new(
                    (p.y - q.y) * (p.z + q.z),
                    (p.z - q.z) * (p.x + q.x),
                    (p.x - q.x) * (p.y + q.y),
                );
            }
            let normal = normal.normalize();
            let offset = ring.iter().map(|&v| normal.dot(&vertices[v])).sum::<f64>() / n as f64;
            Face {
                normal,
                offset,
                vertices: ring,
            }
        })
        .collect();

    let mut directions: Vec<Vector3<f64>> = Vec::new();
    let mut edges = Vec::new();
    for face in &faces {
        let n = face.vertices.len();
        for i in 0..n {
            let (a, b) = (face.vertices[i], face.vertices[(i + 1) % n]);
            if a > b {
                continue;
            }
            let d = (vertices[b] - vertices[a]).normalize();
            let direction = match directions
                .iter()
                .position(|e: &Vector3<f64>| e.cross(&d).norm() < 1e-9)
            {
                Some(k) => k,
                None => {
                    directions.push(d);
                    directions.len() - 1
                }
            };
            edges.push(Edge {
                vertices: [a, b],
                direction,
            });
        }
    }
    ConvexHull {
        vertices,
        faces,
        edges,
        directions,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_points(h: f64) -> Vec<Vector3<f64>> {
        (0..8)
            .map(|i| {
                let s = |bit: usize| if i & (1 << bit) != 0 { h } else { -h };
                Vector3::new(s(0), s(1), s(2))
            })
            .collect()
    }

    #[test]
    fn a_cube_has_8_vertices_6_square_faces_12_edges_3_directions() {
        // Euler: V − E + F = 8 − 12 + 6 = 2.
        let mut points = cube_points(0.5);
        // Points inside, on a face and on an edge are not corners.
        points.push(Vector3::new(0.1, 0.2, -0.1));
        points.push(Vector3::new(0.5, 0.1, 0.2));
        points.push(Vector3::new(0.5, 0.5, 0.0));
        let hull = ConvexHull::from_points(&points).unwrap();
        assert_eq!(hull.vertices.len(), 8);
        assert_eq!(hull.faces.len(), 6);
        assert!(hull.faces.iter().all(|f| f.vertices.len() == 4));
        assert_eq!(hull.edges.len(), 12);
        assert_eq!(hull.directions.len(), 3);
        for face in &hull.faces {
            // Each face of the unit cube: normal ±eₖ, offset 0.5, every vertex on its plane.
            assert!((face.normal.abs().max() - 1.0).abs() < 1e-12, "{face:?}");
            assert!((face.offset - 0.5).abs() < 1e-12, "{face:?}");
            for &v in &face.vertices {
                assert!((face.normal.dot(&hull.vertices[v]) - 0.5).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn face_loops_turn_counter_clockwise_seen_from_outside() {
        let hull = ConvexHull::from_points(&cube_points(1.0)).unwrap();
        for face in &hull.faces {
            let v = |i: usize| hull.vertices[face.vertices[i]];
            // (v1 − v0) × (v2 − v1) points out (along the normal) for a CCW loop.
            let turn = (v(1) - v(0)).cross(&(v(2) - v(1)));
            assert!(turn.dot(&face.normal) > 0.0, "{face:?}");
        }
    }

    #[test]
    fn a_tetrahedron_has_4_triangles_and_6_directions() {
        let points = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(0.0, 0.0, 1.0),
        ];
        let hull = ConvexHull::from_points(&points).unwrap();
        assert_eq!(hull.faces.len(), 4);
        assert_eq!(hull.edges.len(), 6);
        assert_eq!(hull.directions.len(), 6);
        // The slanted face x + y + z = 1: normal (1,1,1)/√3, offset 1/√3.
        let slanted = hull
            .faces
            .iter()
            .find(|f| f.normal.x > 0.5)
            .expect("slanted face");
        assert!((slanted.offset - 1.0 / 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn degenerate_point_sets_are_errors() {
        let flat: Vec<Vector3<f64>> = cube_points(1.0).into_iter().filter(|p| p.z > 0.0).collect();
        assert_eq!(ConvexHull::from_points(&flat), Err(HullError::Coplanar));
        let mut more_flat = flat.clone();
        more_flat.push(Vector3::new(0.3, 0.2, 1.0));
        assert_eq!(
            ConvexHull::from_points(&more_flat),
            Err(HullError::Coplanar)
        );
        let line: Vec<Vector3<f64>> = (0..5).map(|i| Vector3::new(i as f64, 0.0, 0.0)).collect();
        assert_eq!(ConvexHull::from_points(&line), Err(HullError::Collinear));
        let same = vec![Vector3::new(1.0, 2.0, 3.0); 5];
        assert_eq!(ConvexHull::from_points(&same), Err(HullError::Coincident));
        assert_eq!(
            ConvexHull::from_points(&flat[..3]),
            Err(HullError::TooFewPoints { count: 3 })
        );
        let mut nan = cube_points(1.0);
        nan[2].y = f64::NAN;
        assert_eq!(
            ConvexHull::from_points(&nan),
            Err(HullError::NotFinite { index: 2 })
        );
        assert_eq!(
            HullError::Coplanar.to_string(),
            "all points lie in one plane: a convex hull needs volume"
        );
    }

    #[test]
    fn the_hull_of_a_sphere_sample_holds_every_point() {
        // 200 points on a sphere (Fibonacci lattice): every point lies on or inside every face
        // plane, and every vertex is one of the points.
        let n = 200;
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let points: Vec<Vector3<f64>> = (0..n)
            .map(|i| {
                let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
                let r = (1.0 - y * y).sqrt();
                let t = golden * i as f64;
                Vector3::new(r * t.cos(), y, r * t.sin())
            })
            .collect();
        let hull = ConvexHull::from_points(&points).unwrap();
        assert_eq!(
            hull.vertices.len(),
            n,
            "every point of a sphere is a corner"
        );
        for face in &hull.faces {
            for p in &points {
                assert!(face.normal.dot(p) - face.offset <= 1e-9);
            }
        }
        // Euler's formula V − E + F = 2 for a convex polyhedron.
        let euler = hull.vertices.len() as i64 - hull.edges.len() as i64 + hull.faces.len() as i64;
        assert_eq!(euler, 2);
    }
}
