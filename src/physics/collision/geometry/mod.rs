//! Contact geometry between convex shapes: where two shapes touch, along which normal, how deep.
//! Pure geometry: no masses, no velocities, no impulses (the response reads these points).
//!
//! A shape is a box or a convex hull in its body frame, placed in the world by a [`Pose`]. Every
//! query appends [`ContactPoint`]s with the normal pointing from B toward A (an obstacle is
//! always B) and the point midway between the two surfaces:
//!
//! | A against | method | points |
//! |---|---|---|
//! | box or hull | separating axes, then clip the incident face to the reference face, or one edge–edge point (`polyhedra`) | face 3–4, edge 2, vertex 1, edge–edge 1 |
//! | ground | vertices below the plane (`obstacles`) | ≤ 4 |
//! | sphere obstacle | surface point closest to the centre (`closest`) | 1 |
//! | box obstacle | a box with identity rotation: as box | as box |
//! | a particle | [`point_shape`] | 1 |
//!
//! Points within `margin` of touching are returned too, with depth in [−margin, 0] (speculative
//! contacts: the response may hold them back before they meet).
//!
//! | file | idea |
//! |---|---|
//! | `shape` | shapes, poses, contact points |
//! | `hull` | the convex hull of a point set (incremental construction, coplanar faces merged) |
//! | `polygon` | a short list of points on the stack (no allocation per contact) |
//! | `polyhedron` | boxes and hulls answering the same questions (shadow on an axis, faces, edges) |
//! | `sat` | the separating-axis test and the axis of least penetration |
//! | `clip` | Sutherland–Hodgman clipping of the incident face; thinning to 4 points |
//! | `segments` | closest points of two segments (edge–edge) |
//! | `polyhedra` | polyhedron against polyhedron: the whole contact |
//! | `closest` | closest surface point (sphere obstacle, particles) |
//! | `obstacles` | ground and sphere obstacles |
//!
//! The report's vertex test (`detect`) is separate and unchanged: it is the `seed` response's
//! own detection.

pub mod clip;
pub mod closest;
pub mod hull;
pub mod obstacles;
pub mod polygon;
pub mod polyhedra;
pub mod polyhedron;
pub mod sat;
pub mod segments;
pub mod shape;

pub use hull::{ConvexHull, HullError};
pub use shape::{deepest, ContactPoint, Feature, Pose, Shape};

use super::Obstacle;
use closest::{closest_on_box, closest_on_polyhedron, Closest};
use nalgebra::Vector3;
use polyhedron::{BoxView, HullView};

/// Appends the contact points between shape A at `pa` and shape B at `pb` to `out`.
pub fn shape_shape(
    a: &Shape,
    pa: &Pose,
    b: &Shape,
    pb: &Pose,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    use polyhedra::contact;
    match (a, b) {
        (Shape::Box { half: ha }, Shape::Box { half: hb }) => {
            polyhedra::box_box(&BoxView::new(ha, pa), &BoxView::new(hb, pb), margin, out)
        }
        (Shape::Box { half }, Shape::Hull(hull)) => contact(
            &BoxView::new(half, pa),
            &HullView { hull, pose: pb },
            margin,
            out,
        ),
        (Shape::Hull(hull), Shape::Box { half }) => contact(
            &HullView { hull, pose: pa },
            &BoxView::new(half, pb),
            margin,
            out,
        ),
        (Shape::Hull(ha), Shape::Hull(hb)) => contact(
            &HullView { hull: ha, pose: pa },
            &HullView { hull: hb, pose: pb },
            margin,
            out,
        ),
    }
}

/// Appends the contact points between shape A at `pa` and a fixed obstacle (B) to `out`.
pub fn shape_obstacle(
    a: &Shape,
    pa: &Pose,
    obstacle: &Obstacle,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    match (*obstacle, a) {
        (Obstacle::Ground { height }, Shape::Box { half }) => {
            obstacles::against_ground(&BoxView::new(half, pa), height, margin, out)
        }
        (Obstacle::Ground { height }, Shape::Hull(hull)) => {
            obstacles::against_ground(&HullView { hull, pose: pa }, height, margin, out)
        }
        (Obstacle::Sphere { center, radius }, _) => {
            let closest = closest_point(a, pa, &center);
            out.extend(obstacles::against_sphere(&closest, &center, radius, margin));
        }
        (Obstacle::Box { min, max }, Shape::Box { half }) => polyhedra::box_box(
            &BoxView::new(half, pa),
            &BoxView::aligned(&min, &max),
            margin,
            out,
        ),
        (Obstacle::Box { min, max }, Shape::Hull(hull)) => polyhedra::contact(
            &HullView { hull, pose: pa },
            &BoxView::aligned(&min, &max),
            margin,
            out,
        ),
    }
}

/// A particle at `p` against shape A: None when it is farther than `margin` outside. The normal
/// points out of the shape (the way the particle must move), the depth is how far inside it is,
/// and `point` is the shape's surface point nearest to `p` (a particle has no surface of its
/// own).
pub fn point_shape(p: &Vector3<f64>, a: &Shape, pa: &Pose, margin: f64) -> Option<ContactPoint> {
    let closest = closest_point(a, pa, p);
    let depth = -closest.distance;
    (depth >= -margin).then_some(ContactPoint {
        point: closest.point,
        normal: closest.normal,
        depth,
        feature: Feature::VertexFace,
    })
}

/// The surface point of A nearest to `p`.
fn closest_point(a: &Shape, pa: &Pose, p: &Vector3<f64>) -> Closest {
    match a {
        Shape::Box { half } => closest_on_box(&BoxView::new(half, pa), p),
        Shape::Hull(hull) => closest_on_polyhedron(&HullView { hull, pose: pa }, p),
    }
}
