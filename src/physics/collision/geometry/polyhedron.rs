//! One view of a convex polyhedron in the world, so that a single separating-axis routine serves
//! boxes and hulls alike: a box is a hull with 6 faces and 3 edge directions, answered in closed
//! form (no vertex loop, no allocation); a hull answers by walking its vertices.
//!
//! What the contact routine asks of a polyhedron P (world frame, n unit):
//!
//! ```text
//! extent(u)          = [min over P of u·p, max over P of u·p]      P's shadow on the axis u
//!   box (centre c, axes eₖ, half-extents hₖ):  u·c ∓ Σₖ hₖ |u·eₖ|
//!   hull (pose x, R; body vertices rᵢ):       u·x + min/max over i of (Rᵀu)·rᵢ
//! face i             = outward normal nᵢ, offset dᵢ (the face lies in nᵢ·p = dᵢ) and its
//!                      vertex loop, counter-clockwise seen from outside
//! edge directions    = the distinct edge directions up to sign (3 for a box)
//! support edge(k, u) = the edge of direction k farthest along u
//! ```

use super::hull::ConvexHull;
pub use super::polygon::Polygon;
use super::shape::Pose;
use nalgebra::{Matrix3, Vector3};

/// A convex polyhedron placed in the world.
pub trait Polyhedron {
    /// The barycenter, world frame.
    fn center(&self) -> Vector3<f64>;
    /// (min, max) of u·p over the polyhedron.
    fn extent(&self, u: &Vector3<f64>) -> (f64, f64);
    /// Number of faces.
    fn face_count(&self) -> usize;
    /// Outward unit normal and offset of face `i`, world frame.
    fn face_plane(&self, i: usize) -> (Vector3<f64>, f64);
    /// The vertex loop of face `i` (counter-clockwise seen from outside), world frame.
    fn face_polygon(&self, i: usize, out: &mut Polygon);
    /// Number of distinct edge directions.
    fn direction_count(&self) -> usize;
    /// Unit edge direction `k`, world frame.
    fn direction(&self, k: usize) -> Vector3<f64>;
    /// The end points of the edge of direction `k` farthest along `u`.
    fn support_edge(&self, k: usize, u: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>);
    /// Every vertex, world frame, passed to `visit` one at a time.
    fn for_each_vertex(&self, visit: &mut dyn FnMut(Vector3<f64>));

    /// The face whose normal is most anti-parallel to `n` (the face that meets a reference face
    /// of normal `n`: the *incident* face).
    fn incident_face(&self, n: &Vector3<f64>) -> usize {
        let mut best = 0;
        let mut lowest = f64::INFINITY;
        for i in 0..self.face_count() {
            let d = self.face_plane(i).0.dot(n);
            if d < lowest {
                lowest = d;
                best = i;
            }
        }
        best
    }
}

/// A box in the world: centre, axes (the columns of the rotation), half-extents.
#[derive(Debug, Clone, Copy)]
pub struct BoxView {
    pub center: Vector3<f64>,
    pub axes: Matrix3<f64>,
    pub half: Vector3<f64>,
}

impl BoxView {
    /// A body box with half-extents `half` at `pose`.
    pub fn new(half: &Vector3<f64>, pose: &Pose) -> BoxView {
        BoxView {
            center: pose.position,
            axes: pose.rotation,
            half: *half,
        }
    }

    /// The axis-aligned box [min, max].
    pub fn aligned(min: &Vector3<f64>, max: &Vector3<f64>) -> BoxView {
        BoxView {
            center: (min + max) / 2.0,
            axes: Matrix3::identity(),
            half: (max - min) / 2.0,
        }
    }

    /// Body axis k as a world vector.
    fn axis(&self, k: usize) -> Vector3<f64> {
        self.axes.column(k).into_owned()
    }

    /// Half the length of the box's shadow on u: Σₖ hₖ |u·eₖ|.
    fn radius(&self, u: &Vector3<f64>) -> f64 {
        let local = self.axes.tr_mul(u);
        local.abs().dot(&self.half)
    }
}

/// Faces are numbered 2k (the +eₖ face) and 2k + 1 (the −eₖ face).
impl Polyhedron for BoxView {
    fn center(&self) -> Vector3<f64> {
        self.center
    }

    fn extent(&self, u: &Vector3<f64>) -> (f64, f64) {
        let mid = u.dot(&self.center);
        let r = self.radius(u);
        (mid - r, mid + r)
    }

    fn face_count(&self) -> usize {
        6
    }

    fn face_plane(&self, i: usize) -> (Vector3<f64>, f64) {
        let k = i / 2;
        let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        let n = self.axis(k) * sign;
        (n, n.dot(&self.center) + self.half[k])
    }

    fn face_polygon(&self, i: usize, out: &mut Polygon) {
        // With (k, k+1, k+2) cyclic, eₖ₊₁ × eₖ₊₂ = eₖ: the loop (+u+v, −u+v, −u−v, +u−v) turns
        // counter-clockwise about +eₖ; the −eₖ face runs it backwards.
        let k = i / 2;
        let sign = if i.is_multiple_of(2) { 1.0 } else { -1.0 };
        let (j, l) = ((k + 1) % 3, (k + 2) % 3);
        let c = self.center + self.axis(k) * (sign * self.half[k]);
        let u = self.axis(j) * self.half[j];
        let v = self.axis(l) * self.half[l];
        out.clear();
        if sign > 0.0 {
            out.extend([c + u + v, c - u + v, c - u - v, c + u - v]);
        } else {
            out.extend([c + u + v, c + u - v, c - u - v, c - u + v]);
        }
    }

    fn direction_count(&self) -> usize {
        3
    }

    fn direction(&self, k: usize) -> Vector3<f64> {
        self.axis(k)
    }

    fn support_edge(&self, k: usize, u: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        // The edge along eₖ whose other two coordinates are ±hⱼ with the sign of u·eⱼ.
        let mut mid = self.center;
        for j in 0..3 {
            if j != k {
                let e = self.axis(j);
                let sign = if u.dot(&e) >= 0.0 { 1.0 } else { -1.0 };
                mid += e * (sign * self.half[j]);
            }
        }
        let along = self.axis(k) * self.half[k];
        (mid - along, mid + along)
    }

    fn for_each_vertex(&self, visit: &mut dyn FnMut(Vector3<f64>)) {
        for corner in 0..8 {
            let s = |bit: usize| if corner & (1 << bit) != 0 { 1.0 } else { -1.0 };
            let local = Vector3::new(s(0) * self.half.x, s(1) * self.half.y, s(2) * self.half.z);
            visit(self.center + self.axes * local);
        }
    }

    fn incident_face(&self, n: &Vector3<f64>) -> usize {
        // The body axis most aligned with n, on the side facing against it.
        let local = self.axes.tr_mul(n);
        let k = local.iamax();
        if local[k] > 0.0 {
            2 * k + 1
        } else {
            2 * k
        }
    }
}

/// A hull at a pose.
#[derive(Debug, Clone, Copy)]
pub struct HullView<'a> {
    pub hull: &'a ConvexHull,
    pub pose: &'a Pose,
}

impl Polyhedron for HullView<'_> {
    fn center(&self) -> Vector3<f64> {
        self.pose.position
    }

    fn extent(&self, u: &Vector3<f64>) -> (f64, f64) {
        let local = self.pose.rotation.tr_mul(u);
        let (lo, hi) = self.hull.extent(&local);
        let mid = u.dot(&self.pose.position);
        (mid + lo, mid + hi)
    }

    fn face_count(&self) -> usize {
        self.hull.faces.len()
    }

    fn face_plane(&self, i: usize) -> (Vector3<f64>, f64) {
        let face = &self.hull.faces[i];
        let n = self.pose.rotation * face.normal;
        (n, face.offset + n.dot(&self.pose.position))
    }

    fn face_polygon(&self, i: usize, out: &mut Polygon) {
        out.clear();
        out.extend(
            self.hull.faces[i]
                .vertices
                .iter()
                .map(|&v| self.pose.to_world(&self.hull.vertices[v])),
        );
    }

    fn direction_count(&self) -> usize {
        self.hull.directions.len()
    }

    fn direction(&self, k: usize) -> Vector3<f64> {
        self.pose.rotation * self.hull.directions[k]
    }

    fn support_edge(&self, k: usize, u: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let local = self.pose.rotation.tr_mul(u);
        let mut best = (f64::NEG_INFINITY, [0, 0]);
        for edge in self.hull.edges.iter().filter(|e| e.direction == k) {
            let [a, b] = edge.vertices;
            let height = local.dot(&(self.hull.vertices[a] + self.hull.vertices[b]));
            if height > best.0 {
                best = (height, edge.vertices);
            }
        }
        let [a, b] = best.1;
        (
            self.pose.to_world(&self.hull.vertices[a]),
            self.pose.to_world(&self.hull.vertices[b]),
        )
    }

    fn for_each_vertex(&self, visit: &mut dyn FnMut(Vector3<f64>)) {
        for v in &self.hull.vertices {
            visit(self.pose.to_world(v));
        }
    }
}
