//! A cylinder against a plane (the ground, a ramp): the lowest points of its two rims.
//!
//! ```text
//! axis a = R ŷ, cap centres k± = x ± h a, plane normal n, origin o
//! u = the unit part of −n across the axis: u = −(n − (n·a) a)/|n − (n·a) a|   (downhill in
//!     the cap's plane), w = a × u
//! rim candidates on each cap: k± + ρ u (the lowest rim point), k± − ρ u, k± ± ρ w
//! depth of a point v: d = n·(o − v); kept when d ≥ −margin; point = v + (d/2) n
//! ```
//!
//! Lying on its side (a ⟂ n) the two lowest rim points touch: a 2-point line contact along the
//! generator. Standing on an end (a ∥ n, u undefined: any u across the axis) the four rim
//! points of the lower cap touch: a patch. Tilted, the lowest rim point alone.

use super::shape::{ContactPoint, Feature, Pose};
use nalgebra::Vector3;

/// The contact points of a cylinder (radius, half-length) at `pose` against the half-space
/// behind the plane through `origin` with unit normal `normal`.
pub fn cylinder_plane(
    radius: f64,
    half: f64,
    pose: &Pose,
    origin: &Vector3<f64>,
    normal: &Vector3<f64>,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    let axis = pose.rotation * Vector3::y();
    let across = normal - axis * normal.dot(&axis);
    let u = if across.norm() > 1e-12 * normal.norm() {
        -across.normalize()
    } else {
        pose.rotation * Vector3::x()
    };
    let w = axis.cross(&u);
    for sign in [-1.0, 1.0] {
        let cap = pose.position + axis * (sign * half);
        for offset in [u, -u, w, -w] {
            let v = cap + offset * radius;
            let depth = normal.dot(&(origin - v));
            if depth >= -margin {
                out.push(ContactPoint {
                    point: v + normal * (depth / 2.0),
                    normal: *normal,
                    depth,
                    feature: Feature::Round,
                });
            }
        }
    }
}
