//! A shape against the fixed obstacles of a scene (always B: normals point from the obstacle
//! toward the shape).
//!
//! ```text
//! ground y = h (solid below):  every vertex v with depth = h − v.y ≥ −margin is a point
//!     normal +y, point = v + (depth/2) ŷ; more than 4 (a hull's large face) thinned to 4;
//!     a box face down gives its 4 corners, an edge down 2, a corner down 1
//! sphere (c, ρ):  q = the shape's surface point closest to c (closest.rs), signed distance δ
//!     (< 0: the centre is inside the shape), outward normal m at q
//!     depth = ρ − δ,  normal = −m,  point = (q + (c − ρ m))/2   (midway between q and the
//!     sphere's surface point facing it); one point
//! box [min, max]:  a box with identity rotation: the polyhedron routine (polyhedra.rs)
//! ```

use super::clip::reduce_to_four;
use super::closest::Closest;
use super::polygon::CAPACITY;
use super::polyhedron::{Polygon, Polyhedron};
use super::shape::{ContactPoint, Feature};
use nalgebra::Vector3;

/// The vertices of `shape` at or below `height + margin`.
pub fn against_ground(
    shape: &impl Polyhedron,
    height: f64,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    let mut points = Polygon::new();
    let mut depths = [0.0; CAPACITY];
    shape.for_each_vertex(&mut |v| {
        let depth = height - v.y;
        if depth >= -margin && points.len() < CAPACITY {
            depths[points.len()] = depth;
            points.push(v);
        }
    });
    let up = Vector3::y();
    let count = points.len();
    reduce_to_four(&mut points, &mut depths[..count], &up);
    let feature = Feature::of_face_contact(points.len());
    out.extend(points.iter().zip(&depths).map(|(v, &depth)| ContactPoint {
        point: v + up * (depth / 2.0),
        normal: up,
        depth,
        feature,
    }));
}

/// The contact of a shape whose surface point closest to the sphere's centre is `closest`.
pub fn against_sphere(
    closest: &Closest,
    center: &Vector3<f64>,
    radius: f64,
    margin: f64,
) -> Option<ContactPoint> {
    let depth = radius - closest.distance;
    (depth >= -margin).then(|| ContactPoint {
        point: (closest.point + center - closest.normal * radius) / 2.0,
        normal: -closest.normal,
        depth,
        feature: Feature::Sphere,
    })
}

/// The vertices of `shape` behind the plane through `origin` with unit normal `normal` by at
/// least −margin: as [`against_ground`] with depth = n·(origin − v) and normal n.
pub fn against_plane(
    shape: &impl Polyhedron,
    origin: &Vector3<f64>,
    normal: &Vector3<f64>,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    let mut points = Polygon::new();
    let mut depths = [0.0; CAPACITY];
    shape.for_each_vertex(&mut |v| {
        let depth = normal.dot(&(origin - v));
        if depth >= -margin && points.len() < CAPACITY {
            depths[points.len()] = depth;
            points.push(v);
        }
    });
    let count = points.len();
    reduce_to_four(&mut points, &mut depths[..count], normal);
    let feature = Feature::of_face_contact(points.len());
    out.extend(points.iter().zip(&depths).map(|(v, &depth)| ContactPoint {
        point: v + normal * (depth / 2.0),
        normal: *normal,
        depth,
        feature,
    }));
}
