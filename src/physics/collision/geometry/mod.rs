//! Contact geometry between convex shapes: where two shapes touch, along which normal, how deep.
//! Pure geometry: no masses, no velocities, no impulses (the response reads these points).
//!
//! A shape (box, hull, ball, capsule, cylinder, plane) is placed in the world by a [`Pose`].
//! Every query appends [`ContactPoint`]s with the normal pointing from B toward A (an obstacle
//! is always B) and the point midway between the two surfaces. Obstacles are static bodies of
//! this table ([`Obstacle::shape`], [`Obstacle::contact`]): the ground and ramps are planes,
//! the sphere obstacle a ball, box obstacles boxes.
//!
//! One table of pair functions, in the manner of Box2D v3's shape-pair table: each pair is
//! written once with the rounder shape as A (ball < capsule < cylinder < box, hull < plane);
//! the swapped pair is the same function with its normals flipped ([`ContactPoint::swapped`]).
//! Everything here is written by hand; no pair comes from a crate (GJK/EPA included: a
//! support function per shape, ~300 lines, rather than a new dependency of the core).
//!
//! | A against B | method | points |
//! |---|---|---|
//! | box or hull – box or hull | separating axes, then clip the incident face to the reference face, or one edge–edge point (`polyhedra`) | face 3–4, edge 2, vertex 1, edge–edge 1 |
//! | box or hull – plane | vertices behind the plane (`obstacles`) | ≤ 4 |
//! | box or hull – ball | surface point closest to the centre (`closest`, `obstacles`) | 1 |
//! | ball – anything | the other's surface point closest to the centre (`round`) | 1 |
//! | capsule – anything | closest points of the core segment: both ends, or the deepest inner point (`round`) | 1–2 |
//! | cylinder – plane | the lowest rim points (`cylinder_plane`) | lying 2, standing 4 |
//! | cylinder – box, hull or cylinder | GJK/EPA for the normal, then the flat features clipped: a box face against the rim octagon and the lowest generator, or the cylinder's end against the other's face (`cylinder`, `gjk`) | lying 2, standing 4, else 1 |
//! | a particle | [`point_shape`] | 1 |
//!
//! [`Obstacle::shape`]: super::Obstacle::shape
//! [`Obstacle::contact`]: super::Obstacle::contact
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
//! | `closest` | closest surface point of every shape (balls, capsules, particles) |
//! | `obstacles` | polyhedra against the ground, planes and balls |
//! | `round` | balls and capsules against any shape |
//! | `cylinder_plane` | a cylinder on a plane: line contact lying, rim patch standing |
//! | `gjk` | distance (GJK) and depth (EPA) of any two convex shapes from their support points |
//! | `cylinder` | a cylinder against a box, a hull or a cylinder: GJK/EPA's normal, clipped features |
//!
//! The report's vertex test (`detect`) is separate and unchanged: it is the `seed` response's
//! own detection.

pub mod clip;
pub mod closest;
pub mod cylinder;
pub mod cylinder_plane;
pub mod gjk;
pub mod hull;
pub mod obstacles;
pub mod polygon;
pub mod polyhedra;
pub mod polyhedron;
pub mod round;
pub mod sat;
pub mod segments;
pub mod shape;

pub use hull::{ConvexHull, HullError};
pub use shape::{deepest, ContactPoint, Feature, Pose, Shape};

use closest::{
    closest_on_ball, closest_on_box, closest_on_capsule, closest_on_cylinder, closest_on_plane,
    closest_on_polyhedron, Closest,
};
use gjk::CylinderView;
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
        _ if rank(a) <= rank(b) => ordered(a, pa, b, pb, margin, out),
        _ => {
            // The swapped pair: computed once, seen from the other side.
            let first = out.len();
            ordered(b, pb, a, pa, margin, out);
            for p in &mut out[first..] {
                *p = p.swapped();
            }
        }
    }
}

/// The order of the pair table: the rounder shape is A.
fn rank(shape: &Shape) -> u8 {
    match shape {
        Shape::Ball { .. } => 0,
        Shape::Capsule { .. } => 1,
        Shape::Cylinder { .. } => 2,
        Shape::Box { .. } | Shape::Hull(_) => 3,
        Shape::Plane { .. } => 4,
    }
}

/// One pair of the table, rank(a) ≤ rank(b), polyhedron pairs excepted (handled above).
fn ordered(a: &Shape, pa: &Pose, b: &Shape, pb: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
    match a {
        Shape::Ball { radius } => {
            let closest = closest_point(b, pb, &pa.position);
            out.extend(round::ball_against(&closest, &pa.position, *radius, margin));
        }
        Shape::Capsule {
            radius,
            half_length,
        } => {
            let core = core_segment(pa, *half_length);
            // The parameter along the core of its point nearest to `p`.
            let along = |p: &Vector3<f64>| {
                let d = core.1 - core.0;
                ((p - core.0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0)
            };
            let nearest = match b {
                Shape::Plane { .. } => round::Nearest::Ends,
                Shape::Ball { .. } => round::Nearest::At(along(&pb.position)),
                Shape::Capsule { half_length, .. } => {
                    let other = core_segment(pb, *half_length);
                    let on_a = segments::closest_points(&core.0, &core.1, &other.0, &other.1).0;
                    round::Nearest::At(along(&on_a))
                }
                _ => round::Nearest::Search,
            };
            round::capsule_against(
                &core,
                *radius,
                margin,
                nearest,
                |p| closest_point(b, pb, p),
                out,
            )
        }
        Shape::Cylinder {
            radius,
            half_length,
        } => {
            let view = CylinderView {
                center: pa.position,
                rotation: pa.rotation,
                radius: *radius,
                half: *half_length,
            };
            match b {
                Shape::Plane { normal } => cylinder_plane::cylinder_plane(
                    *radius,
                    *half_length,
                    pa,
                    &pb.position,
                    &(pb.rotation * normal),
                    margin,
                    out,
                ),
                Shape::Box { half } => {
                    cylinder::cylinder_polyhedron(&view, &BoxView::new(half, pb), margin, out)
                }
                Shape::Hull(hull) => {
                    cylinder::cylinder_polyhedron(&view, &HullView { hull, pose: pb }, margin, out)
                }
                Shape::Cylinder {
                    radius,
                    half_length,
                } => {
                    let other = CylinderView {
                        center: pb.position,
                        rotation: pb.rotation,
                        radius: *radius,
                        half: *half_length,
                    };
                    cylinder::cylinder_cylinder(&view, &other, margin, out)
                }
                // Balls and capsules rank before cylinders: handled as A.
                Shape::Ball { .. } | Shape::Capsule { .. } => {}
            }
        }
        Shape::Box { half } => match b {
            Shape::Plane { normal } => obstacles::against_plane(
                &BoxView::new(half, pa),
                &pb.position,
                &(pb.rotation * normal),
                margin,
                out,
            ),
            Shape::Ball { radius } => {
                let closest = closest_point(a, pa, &pb.position);
                out.extend(obstacles::against_sphere(
                    &closest,
                    &pb.position,
                    *radius,
                    margin,
                ));
            }
            _ => {}
        },
        Shape::Hull(hull) => match b {
            Shape::Plane { normal } => obstacles::against_plane(
                &HullView { hull, pose: pa },
                &pb.position,
                &(pb.rotation * normal),
                margin,
                out,
            ),
            Shape::Ball { radius } => {
                let closest = closest_point(a, pa, &pb.position);
                out.extend(obstacles::against_sphere(
                    &closest,
                    &pb.position,
                    *radius,
                    margin,
                ));
            }
            _ => {}
        },
        Shape::Plane { .. } => {}
    }
}

/// The end points of a capsule's core segment, world frame: x ∓ h R ŷ.
fn core_segment(pose: &Pose, half_length: f64) -> (Vector3<f64>, Vector3<f64>) {
    let axis = pose.rotation * Vector3::y() * half_length;
    (pose.position - axis, pose.position + axis)
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
pub fn closest_point(a: &Shape, pa: &Pose, p: &Vector3<f64>) -> Closest {
    match a {
        Shape::Box { half } => closest_on_box(&BoxView::new(half, pa), p),
        Shape::Hull(hull) => closest_on_polyhedron(&HullView { hull, pose: pa }, p),
        Shape::Ball { radius } => closest_on_ball(&pa.position, *radius, p),
        Shape::Capsule {
            radius,
            half_length,
        } => closest_on_capsule(
            &core_segment(pa, *half_length),
            &(pa.rotation * Vector3::x()),
            *radius,
            p,
        ),
        Shape::Cylinder {
            radius,
            half_length,
        } => closest_on_cylinder(pa, *radius, *half_length, p),
        Shape::Plane { normal } => closest_on_plane(&pa.position, &(pa.rotation * normal), p),
    }
}
