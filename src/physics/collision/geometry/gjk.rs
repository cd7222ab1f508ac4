//! How far apart two convex shapes are, or how deep they overlap, from their support
//! functions alone: GJK (Gilbert–Johnson–Keerthi) for the distance, EPA (the expanding polytope
//! algorithm) for the depth. Used where no closed form is written: a cylinder against a box,
//! a hull or another cylinder.
//!
//! ```text
//! support s_K(u) = the point of K farthest along u
//!   box (centre c, axes eₖ, half-extents hₖ):  c + Σₖ sign(u·eₖ) hₖ eₖ
//!   hull:                                      the vertex of largest u·v
//!   cylinder (centre c, unit axis a, radius ρ, half-length h), u⊥ = u − (u·a) a:
//!                                              c + sign(u·a) h a + ρ u⊥/|u⊥|
//! the Minkowski difference D = A − B = {p − q}: its support is s_A(u) − s_B(−u);
//!   A and B overlap ⇔ the origin is in D
//! GJK: a simplex (1–4 points of D) walks toward the origin: v = its point nearest the origin,
//!   w = s_D(−v) the new point; stop when |v|² − v·w ≤ ε |v|² (no progress: distance |v|) or
//!   when the simplex holds the origin (overlap); v·w/|v| > margin proves them apart
//! EPA: from GJK's tetrahedron, grow a polytope inside D toward its boundary: take the face
//!   nearest the origin (unit outward normal n, distance δ); w = s_D(n); if n·w − δ ≤ ε the face
//!   lies on D's boundary: depth δ; else replace the faces w sees by a fan from w to their
//!   horizon
//! result: normal from B toward A (A moves along it to separate): apart v/|v|, overlapping −n;
//!   depth −|v| or δ; the witness points on A and B from the barycentric weights of v on the
//!   simplex (or of δ n on the face)
//! ```
//!
//! Ericson, *Real-Time Collision Detection* (2005), §9.5 (GJK) and van den Bergen (2003) §4.3
//! (EPA).

use super::polyhedron::{BoxView, HullView};
use nalgebra::{Matrix3, Vector3};

type V = Vector3<f64>;

/// A convex shape given by its support function.
pub trait Support {
    /// The point of the shape farthest along `u` (world frame; `u` need not be unit).
    fn support(&self, u: &V) -> V;
    /// A point inside the shape (the first search direction runs between the two).
    fn inner(&self) -> V;
}

impl Support for BoxView {
    fn support(&self, u: &V) -> V {
        let local = self.axes.tr_mul(u);
        let corner = local.zip_map(&self.half, |l, h| if l >= 0.0 { h } else { -h });
        self.center + self.axes * corner
    }
    fn inner(&self) -> V {
        self.center
    }
}

impl Support for HullView<'_> {
    fn support(&self, u: &V) -> V {
        let local = self.pose.rotation.tr_mul(u);
        let mut best = (f64::NEG_INFINITY, V::zeros());
        for v in &self.hull.vertices {
            let h = local.dot(v);
            if h > best.0 {
                best = (h, *v);
            }
        }
        self.pose.to_world(&best.1)
    }
    fn inner(&self) -> V {
        self.pose.position
    }
}

/// A cylinder placed in the world.
#[derive(Debug, Clone, Copy)]
pub struct CylinderView {
    /// Barycenter, m.
    pub center: V,
    /// Rotation body → world (the axis is its y column).
    pub rotation: Matrix3<f64>,
    /// Radius ρ, m.
    pub radius: f64,
    /// Half-length h, m.
    pub half: f64,
}

impl CylinderView {
    /// The unit axis a = R ŷ.
    pub fn axis(&self) -> V {
        self.rotation.column(1).into_owned()
    }

    /// The unit part of `u` across the axis, None when `u` is along it.
    pub fn across(&self, u: &V) -> Option<V> {
        let a = self.axis();
        let perp = u - a * u.dot(&a);
        let n = perp.norm();
        (n > 1e-12 * u.norm()).then(|| perp / n)
    }
}

impl Support for CylinderView {
    fn support(&self, u: &V) -> V {
        let a = self.axis();
        let along = if u.dot(&a) >= 0.0 { 1.0 } else { -1.0 };
        let side = self.across(u).map_or(V::zeros(), |p| p * self.radius);
        self.center + a * (along * self.half) + side
    }
    fn inner(&self) -> V {
        self.center
    }
}

/// The result of [`separation`]: the smallest move that separates A from B, or their gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// Unit normal from B toward A.
    pub normal: V,
    /// > 0: overlap (A must move this far along `normal`); ≤ 0: minus the gap.
    pub depth: f64,
    /// The witness point on A's surface, m.
    pub on_a: V,
    /// The witness point on B's surface, m.
    pub on_b: V,
}

/// A point of D = A − B with the two support points it came from.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    w: V,
    a: V,
    b: V,
}

fn vertex(a: &impl Support, b: &impl Support, u: &V) -> Vertex {
    let pa = a.support(u);
    let pb = b.support(&-u);
    Vertex {
        w: pa - pb,
        a: pa,
        b: pb,
    }
}

/// GJK iterations (a polyhedron converges in a few; a cylinder's curved side in tens).
const GJK_STEPS: usize = 64;
/// EPA iterations (faces added one support point at a time).
const EPA_STEPS: usize = 64;

/// The separation of A and B, None when they are farther apart than `margin`.
pub fn separation(a: &impl Support, b: &impl Support, margin: f64) -> Option<Separation> {
    let mut v = a.inner() - b.inner();
    if v.norm_squared() < 1e-24 {
        v = V::y();
    }
    let mut simplex = [vertex(a, b, &-v); 4];
    let mut weights = [1.0, 0.0, 0.0, 0.0];
    let mut count = 1;
    v = simplex[0].w;
    let scale = 1.0 + simplex[0].w.norm();
    let tiny = (1e-12 * scale).powi(2);
    for _ in 0..GJK_STEPS {
        if v.norm_squared() <= tiny {
            break;
        }
        let w = vertex(a, b, &-v);
        let vw = v.dot(&w.w);
        // v·w/|v| is a lower bound of the gap.
        if vw > margin * v.norm() {
            return None;
        }
        let vv = v.norm_squared();
        if vv - vw <= 1e-10 * vv {
            return Some(apart(&simplex[..count], &weights[..count], v));
        }
        simplex[count] = w;
        count += 1;
        let (next, kept) = nearest_on_simplex(&mut simplex, count, &mut weights);
        count = kept;
        if count == 4 {
            break;
        }
        // No progress (round-off): the gap is |v|.
        if next.norm_squared() >= vv {
            return Some(apart(&simplex[..count], &weights[..count], next));
        }
        v = next;
    }
    if count < 4 && v.norm_squared() > tiny {
        return Some(apart(&simplex[..count], &weights[..count], v));
    }
    Some(expand(a, b, &mut simplex, count, scale))
}

/// The gap: normal v/|v|, depth −|v|, witnesses from the simplex weights.
fn apart(simplex: &[Vertex], weights: &[f64], v: V) -> Separation {
    let on_a = simplex.iter().zip(weights).map(|(s, &l)| s.a * l).sum();
    let on_b = simplex.iter().zip(weights).map(|(s, &l)| s.b * l).sum();
    let d = v.norm();
    Separation {
        normal: v / d,
        depth: -d,
        on_a,
        on_b,
    }
}

/// The point of the simplex's hull nearest the origin; the simplex is reduced to the points
/// that carry it (moved to the front) with their weights. Returns the point and the count.
fn nearest_on_simplex(s: &mut [Vertex; 4], count: usize, weights: &mut [f64; 4]) -> (V, usize) {
    match count {
        1 => {
            weights[0] = 1.0;
            (s[0].w, 1)
        }
        2 => segment(s, weights),
        3 => triangle(s, weights),
        _ => tetrahedron(s, weights),
    }
}

/// Nearest point of segment s₀s₁ to the origin: t = −s₀·(s₁ − s₀)/|s₁ − s₀|².
fn segment(s: &mut [Vertex; 4], weights: &mut [f64; 4]) -> (V, usize) {
    let d = s[1].w - s[0].w;
    let t = -s[0].w.dot(&d) / d.norm_squared().max(1e-300);
    if t <= 0.0 {
        weights[0] = 1.0;
        (s[0].w, 1)
    } else if t >= 1.0 {
        s[0] = s[1];
        weights[0] = 1.0;
        (s[0].w, 1)
    } else {
        weights[0] = 1.0 - t;
        weights[1] = t;
        (s[0].w + d * t, 2)
    }
}

/// Nearest point of triangle s₀s₁s₂ to the origin (Ericson §5.1.5, Voronoi regions).
fn triangle(s: &mut [Vertex; 4], weights: &mut [f64; 4]) -> (V, usize) {
    let (a, b, c) = (s[0].w, s[1].w, s[2].w);
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    let keep = |s: &mut [Vertex; 4], idx: &[usize]| {
        let picked: Vec<Vertex> = idx.iter().map(|&i| s[i]).collect();
        s[..picked.len()].copy_from_slice(&picked);
    };
    if d1 <= 0.0 && d2 <= 0.0 {
        weights[0] = 1.0;
        return (a, 1);
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        keep(s, &[1]);
        weights[0] = 1.0;
        return (b, 1);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let t = d1 / (d1 - d3);
        weights[0] = 1.0 - t;
        weights[1] = t;
        return (a + ab * t, 2);
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        keep(s, &[2]);
        weights[0] = 1.0;
        return (c, 1);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let t = d2 / (d2 - d6);
        keep(s, &[0, 2]);
        weights[0] = 1.0 - t;
        weights[1] = t;
        return (a + ac * t, 2);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        keep(s, &[1, 2]);
        weights[0] = 1.0 - t;
        weights[1] = t;
        return (b + (c - b) * t, 2);
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    weights[0] = 1.0 - v - w;
    weights[1] = v;
    weights[2] = w;
    (a + ab * v + ac * w, 3)
}

/// Nearest point of tetrahedron s₀…s₃ to the origin: the nearest of its faces that have the
/// origin on their outer side; count 4 when the origin is inside.
fn tetrahedron(s: &mut [Vertex; 4], weights: &mut [f64; 4]) -> (V, usize) {
    const FACES: [[usize; 4]; 4] = [[0, 1, 2, 3], [0, 1, 3, 2], [0, 2, 3, 1], [1, 2, 3, 0]];
    // (squared distance, point, reduced face, weights, count) of the nearest face so far.
    type Candidate = (f64, V, [Vertex; 4], [f64; 4], usize);
    let mut best: Option<Candidate> = None;
    for [i, j, k, opposite] in FACES {
        let (a, b, c, d) = (s[i].w, s[j].w, s[k].w, s[opposite].w);
        let n = (b - a).cross(&(c - a));
        let origin_side = n.dot(&-a);
        let other_side = n.dot(&(d - a));
        // The origin outside this face: on the side away from the fourth point.
        if origin_side * other_side < 0.0 || (other_side == 0.0 && origin_side != 0.0) {
            let mut face = [s[i], s[j], s[k], s[opposite]];
            let mut w = [0.0; 4];
            let (p, kept) = triangle(&mut face, &mut w);
            let dist = p.norm_squared();
            if best.as_ref().is_none_or(|b| dist < b.0) {
                best = Some((dist, p, face, w, kept));
            }
        }
    }
    match best {
        Some((_, p, face, w, kept)) => {
            *s = face;
            *weights = w;
            (p, kept)
        }
        None => (V::zeros(), 4),
    }
}

/// One face of the EPA polytope: three vertex indices (counter-clockwise seen from outside),
/// its unit outward normal and its distance from the origin.
#[derive(Debug, Clone, Copy)]
struct Face {
    v: [usize; 3],
    n: V,
    d: f64,
}

fn face(points: &[Vertex], v: [usize; 3]) -> Option<Face> {
    let (a, b, c) = (points[v[0]].w, points[v[1]].w, points[v[2]].w);
    let n = (b - a).cross(&(c - a));
    let len = n.norm();
    (len > 1e-300).then(|| {
        let n = n / len;
        Face { v, n, d: n.dot(&a) }
    })
}

/// EPA from GJK's last simplex (which holds or touches the origin).
fn expand(
    a: &impl Support,
    b: &impl Support,
    simplex: &mut [Vertex; 4],
    mut count: usize,
    scale: f64,
) -> Separation {
    // Grow a degenerate simplex (the origin on a point, an edge or a face of D) to a
    // tetrahedron with support points along directions leaving its span.
    let axes = [V::x(), V::y(), V::z(), -V::x(), -V::y(), -V::z()];
    let flat = 1e-9 * scale;
    while count < 4 {
        let mut grown = false;
        let directions: Vec<V> = match count {
            1 => axes.to_vec(),
            2 => {
                let d = simplex[1].w - simplex[0].w;
                let e = d.cross(&V::x());
                let e = if e.norm() < 1e-6 * d.norm() {
                    d.cross(&V::y())
                } else {
                    e
                };
                let f = d.cross(&e);
                vec![e, -e, f, -f]
            }
            _ => {
                let n = (simplex[1].w - simplex[0].w).cross(&(simplex[2].w - simplex[0].w));
                vec![n, -n]
            }
        };
        for u in directions {
            let w = vertex(a, b, &u);
            let off = match count {
                1 => (w.w - simplex[0].w).norm(),
                2 => {
                    let d = (simplex[1].w - simplex[0].w).normalize();
                    let r = w.w - simplex[0].w;
                    (r - d * r.dot(&d)).norm()
                }
                _ => {
                    let n = (simplex[1].w - simplex[0].w)
                        .cross(&(simplex[2].w - simplex[0].w))
                        .normalize();
                    (w.w - simplex[0].w).dot(&n).abs()
                }
            };
            if off > flat {
                simplex[count] = w;
                count += 1;
                grown = true;
                break;
            }
        }
        if !grown {
            // D is flat here (cannot happen for solids): touching, depth 0.
            let n = (a.inner() - b.inner())
                .try_normalize(1e-300)
                .unwrap_or(V::y());
            let on = simplex[0];
            return Separation {
                normal: n,
                depth: 0.0,
                on_a: on.a,
                on_b: on.b,
            };
        }
    }
    let mut points: Vec<Vertex> = simplex.to_vec();
    // Orient the tetrahedron: faces counter-clockwise seen from outside.
    let (p0, p1, p2, p3) = (points[0].w, points[1].w, points[2].w, points[3].w);
    if (p1 - p0).cross(&(p2 - p0)).dot(&(p3 - p0)) > 0.0 {
        points.swap(1, 2);
    }
    let mut faces: Vec<Face> = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
        .iter()
        .filter_map(|&v| face(&points, v))
        .collect();
    let tolerance = 1e-10 * scale;
    let mut best = faces[0];
    for _ in 0..EPA_STEPS {
        best = *faces
            .iter()
            .min_by(|x, y| x.d.total_cmp(&y.d))
            .expect("a polytope has faces");
        let w = vertex(a, b, &best.n);
        if w.w.dot(&best.n) - best.d <= tolerance {
            break;
        }
        let index = points.len();
        points.push(w);
        // The faces w sees, removed; their edges seen once form the horizon.
        let mut horizon: Vec<[usize; 2]> = Vec::new();
        faces.retain(|f| {
            if f.n.dot(&(w.w - points[f.v[0]].w)) > 0.0 {
                for e in [[f.v[0], f.v[1]], [f.v[1], f.v[2]], [f.v[2], f.v[0]]] {
                    if let Some(at) = horizon.iter().position(|h| *h == [e[1], e[0]]) {
                        horizon.swap_remove(at);
                    } else {
                        horizon.push(e);
                    }
                }
                false
            } else {
                true
            }
        });
        faces.extend(
            horizon
                .iter()
                .filter_map(|e| face(&points, [e[0], e[1], index])),
        );
        if faces.is_empty() {
            break;
        }
    }
    // The origin's projection δ n on the face, in barycentric weights.
    let [i, j, k] = best.v;
    let (a0, b0, c0) = (points[i].w, points[j].w, points[k].w);
    let p = best.n * best.d;
    let l = barycentric(&p, &a0, &b0, &c0);
    let on_a = points[i].a * l[0] + points[j].a * l[1] + points[k].a * l[2];
    let on_b = points[i].b * l[0] + points[j].b * l[1] + points[k].b * l[2];
    Separation {
        normal: -best.n,
        depth: best.d,
        on_a,
        on_b,
    }
}

/// Barycentric weights of p (in the plane of a, b, c).
fn barycentric(p: &V, a: &V, b: &V, c: &V) -> [f64; 3] {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(&v0), v0.dot(&v1), v1.dot(&v1));
    let (d20, d21) = (v2.dot(&v0), v2.dot(&v1));
    let denom = d00 * d11 - d01 * d01;
    if denom.abs() < 1e-300 {
        return [1.0, 0.0, 0.0];
    }
    let v = (d11 * d20 - d01 * d21) / denom;
    let w = (d00 * d21 - d01 * d20) / denom;
    [1.0 - v - w, v, w]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::geometry::shape::Pose;

    fn cube(center: V) -> BoxView {
        BoxView::new(&V::new(0.5, 0.5, 0.5), &Pose::at(center))
    }

    #[test]
    fn two_unit_cubes_a_gap_apart_are_that_far_apart() {
        // Cubes of side 1 with centres 1.3 apart along x: gap 0.3, normal +x (B → A).
        let s = separation(&cube(V::new(1.3, 0.2, 0.0)), &cube(V::zeros()), 1.0).unwrap();
        assert!((s.depth + 0.3).abs() < 1e-9, "{s:?}");
        assert!((s.normal - V::x()).norm() < 1e-9, "{s:?}");
        assert!(separation(&cube(V::new(1.3, 0.0, 0.0)), &cube(V::zeros()), 0.2).is_none());
    }

    #[test]
    fn two_overlapping_cubes_separate_along_the_shallow_axis() {
        // Centres 0.9 apart along y (overlap 0.1) and 0.2 along x (overlap 0.8): depth 0.1, +y.
        let s = separation(&cube(V::new(0.2, 0.9, 0.0)), &cube(V::zeros()), 0.0).unwrap();
        assert!((s.depth - 0.1).abs() < 1e-9, "{s:?}");
        assert!((s.normal - V::y()).norm() < 1e-9, "{s:?}");
    }

    #[test]
    fn a_cylinder_lying_on_a_box_is_its_radius_minus_the_height_above() {
        // Cylinder of radius 0.3, axis along x, centre 0.29 above the top face y = 0.5 of a
        // unit cube: it sinks 0.3 − 0.29 = 0.01 into it; normal +y.
        let rotation =
            nalgebra::Rotation3::from_axis_angle(&V::z_axis(), std::f64::consts::FRAC_PI_2);
        let c = CylinderView {
            center: V::new(0.1, 0.79, 0.0),
            rotation: *rotation.matrix(),
            radius: 0.3,
            half: 0.4,
        };
        let s = separation(&c, &cube(V::zeros()), 0.0).unwrap();
        assert!((s.depth - 0.01).abs() < 1e-8, "{s:?}");
        assert!((s.normal - V::y()).norm() < 1e-6, "{s:?}");
        // Lifted to 0.35 above: a gap of 0.05.
        let lifted = CylinderView {
            center: V::new(0.1, 0.85, 0.0),
            ..c
        };
        let s = separation(&lifted, &cube(V::zeros()), 0.1).unwrap();
        assert!((s.depth + 0.05).abs() < 1e-8, "{s:?}");
    }

    #[test]
    fn two_cylinders_side_by_side_overlap_by_the_sum_of_radii_minus_the_distance() {
        // Parallel axes along y, radii 0.3 and 0.2, centres 0.45 apart along x: depth 0.05.
        let a = CylinderView {
            center: V::new(0.45, 0.0, 0.0),
            rotation: Matrix3::identity(),
            radius: 0.3,
            half: 0.5,
        };
        let b = CylinderView {
            center: V::zeros(),
            radius: 0.2,
            ..a
        };
        let s = separation(&a, &b, 0.0).unwrap();
        assert!((s.depth - 0.05).abs() < 1e-6, "{s:?}");
        assert!((s.normal - V::x()).norm() < 1e-3, "{s:?}");
    }
}
