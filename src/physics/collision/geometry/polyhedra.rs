//! Contact between two convex polyhedra (box–box, box–hull, hull–hull): the separating-axis
//! test picks the axis, then either a face manifold or one edge–edge point.
//!
//! ```text
//! 1. SAT (sat.rs): apart by more than the margin → no contact; else the axis of least
//!    penetration, a face of A, a face of B, or an edge pair
//! 2a. face axis: the reference face (normal n, plane n·p = d) belongs to the shape whose face
//!     won; the incident face is the other shape's face most anti-parallel to n;
//!     clip the incident face to the reference face's prism (clip.rs);
//!     keep the points p with depth = d − n·p ≥ −margin; thin to ≤ 4;
//!     contact point = p + (depth/2) n  (midway between the incident point and its projection
//!     on the reference plane); normal B → A = −n if the reference is A's face, +n if B's;
//!     if clipping leaves nothing (rare, deep overlaps), the incident shape's deepest vertex
//! 2b. edge axis (normal u from B toward A): A's edge of that direction deepest toward B
//!     (support along −u), B's edge of its direction farthest along +u; their closest points
//!     a, b (segments.rs); contact point = (a + b)/2, depth = −s (the SAT overlap)
//! ```

use super::clip::{clip_to_face, reduce_to_four};
use super::polygon::CAPACITY;
use super::polyhedron::{BoxView, Polygon, Polyhedron};
use super::sat::{least_penetration, least_penetration_boxes, Axis, Query};
use super::segments::closest_points;
use super::shape::{ContactPoint, Feature};
use nalgebra::Vector3;

/// Appends the contact points between A and B to `out` (nothing when apart by more than
/// `margin`).
pub fn contact(a: &impl Polyhedron, b: &impl Polyhedron, margin: f64, out: &mut Vec<ContactPoint>) {
    if let Some(query) = least_penetration(a, b, margin) {
        contact_along(a, b, &query, margin, out);
    }
}

/// The same for two boxes, with the separating-axis test in closed form.
pub fn box_box(a: &BoxView, b: &BoxView, margin: f64, out: &mut Vec<ContactPoint>) {
    if let Some(query) = least_penetration_boxes(a, b, margin) {
        contact_along(a, b, &query, margin, out);
    }
}

/// Step 2 of the module doc: the contact points along the chosen axis.
fn contact_along(
    a: &impl Polyhedron,
    b: &impl Polyhedron,
    query: &Query,
    margin: f64,
    out: &mut Vec<ContactPoint>,
) {
    match query.axis {
        Axis::FaceA { face } => face_contact(a, face, b, margin, false, out),
        Axis::FaceB { face } => face_contact(b, face, a, margin, true, out),
        Axis::Edges {
            a: ka,
            b: kb,
            normal,
        } => {
            let (a0, a1) = a.support_edge(ka, &-normal);
            let (b0, b1) = b.support_edge(kb, &normal);
            let (pa, pb) = closest_points(&a0, &a1, &b0, &b1);
            out.push(ContactPoint {
                point: (pa + pb) / 2.0,
                normal,
                depth: -query.separation,
                feature: Feature::EdgeEdge,
            });
        }
    }
}

/// The manifold of reference face `face` of `reference` against `incident`'s incident face.
/// `reference_is_b`: the reference shape is B (normal +n), else A (normal −n).
fn face_contact(
    reference: &impl Polyhedron,
    face: usize,
    incident: &impl Polyhedron,
    margin: f64,
    reference_is_b: bool,
    out: &mut Vec<ContactPoint>,
) {
    let (n, d) = reference.face_plane(face);
    let mut reference_loop = Polygon::new();
    reference.face_polygon(face, &mut reference_loop);
    let mut points = Polygon::new();
    incident.face_polygon(incident.incident_face(&n), &mut points);
    let mut scratch = Polygon::new();
    clip_to_face(&mut points, &mut scratch, &reference_loop, &n);

    // Keep the points below the reference face (or within the margin), with their depths.
    let mut depths = [0.0; CAPACITY];
    let mut kept = 0;
    for i in 0..points.len() {
        let depth = d - n.dot(&points[i]);
        if depth >= -margin {
            points[kept] = points[i];
            depths[kept] = depth;
            kept += 1;
        }
    }
    points.truncate(kept);
    if kept == 0 {
        // Clipping left nothing (a deep overlap where the incident face lies outside the
        // reference prism): fall back on the incident shape's deepest vertex.
        let mut deepest = (f64::NEG_INFINITY, Vector3::zeros());
        incident.for_each_vertex(&mut |v| {
            let depth = d - n.dot(&v);
            if depth > deepest.0 {
                deepest = (depth, v);
            }
        });
        if deepest.0 >= -margin {
            points.push(deepest.1);
            depths[0] = deepest.0;
            kept = 1;
        }
    }
    reduce_to_four(&mut points, &mut depths[..kept], &n);

    let feature = Feature::of_face_contact(points.len());
    let normal = if reference_is_b { n } else { -n };
    out.extend(points.iter().zip(&depths).map(|(p, &depth)| ContactPoint {
        point: p + n * (depth / 2.0),
        normal,
        depth,
        feature,
    }));
}
