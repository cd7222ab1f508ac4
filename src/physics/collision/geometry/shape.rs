//! What the contact geometry talks about: a convex [`Shape`] in its body frame, the [`Pose`] that
//! puts it in the world, and the [`ContactPoint`]s found between two shapes.
//!
//! ```text
//! world point  p = x + R r        r: body-frame point, x: barycenter, R: rotation body → world
//! normal n:    unit, from B toward A: moving A by a small δ n separates the pair
//! depth d:     > 0 penetrating (A must move d along n to just touch B);
//!              −margin ≤ d ≤ 0 a near (speculative) point: the gap is −d
//! point:       midway between the two surfaces: A's deepest point a and B's b = a + d n
//!              give point = (a + b)/2 = a + (d/2) n
//! ```

use super::hull::ConvexHull;
use nalgebra::{Matrix3, Vector3};

/// A convex shape in its body frame (barycenter at the origin).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A box with half-extents `half` along the body axes, centred on the origin.
    Box { half: Vector3<f64> },
    /// A convex polyhedron (from a point set or an `.obj` mesh).
    Hull(ConvexHull),
    /// A ball of radius `radius` about the origin.
    Ball { radius: f64 },
    /// The points within `radius` of the segment from −`half_length` ŷ to +`half_length` ŷ
    /// (a cylinder of length 2·half_length with a hemisphere on each end).
    Capsule { radius: f64, half_length: f64 },
    /// A solid cylinder of radius `radius` along the body's y axis, from −`half_length` to
    /// +`half_length`.
    Cylinder { radius: f64, half_length: f64 },
    /// The half-space behind the plane through the origin with unit outward normal `normal`
    /// (body frame): an obstacle only (ground, ramp), never a body.
    Plane { normal: Vector3<f64> },
}

impl Shape {
    /// The radius of the smallest origin-centred sphere holding the shape, m (for broad-phase
    /// tests: two shapes farther apart than the sum of their radii plus a margin cannot touch).
    pub fn bounding_radius(&self) -> f64 {
        match self {
            Shape::Box { half } => half.norm(),
            Shape::Hull(hull) => hull.vertices.iter().map(|v| v.norm()).fold(0.0, f64::max),
            Shape::Ball { radius } => *radius,
            Shape::Capsule {
                radius,
                half_length,
            } => radius + half_length,
            Shape::Cylinder {
                radius,
                half_length,
            } => radius.hypot(*half_length),
            Shape::Plane { .. } => f64::INFINITY,
        }
    }

    /// Whether the shape is curved (ball, capsule, cylinder): it has no vertices to test, so
    /// every contact of it comes from the contact geometry.
    pub fn is_round(&self) -> bool {
        matches!(
            self,
            Shape::Ball { .. } | Shape::Capsule { .. } | Shape::Cylinder { .. }
        )
    }

    /// The scene-file name of the shape kind.
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Box { .. } => "box",
            Shape::Hull(_) => "hull",
            Shape::Ball { .. } => "sphere",
            Shape::Capsule { .. } => "capsule",
            Shape::Cylinder { .. } => "cylinder",
            Shape::Plane { .. } => "plane",
        }
    }
}

/// Where a shape is: barycenter position and rotation body → world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Barycenter, world frame, m.
    pub position: Vector3<f64>,
    /// Rotation matrix body → world (orthonormal, det +1).
    pub rotation: Matrix3<f64>,
}

impl Pose {
    /// The pose at `position` with the body axes along the world axes.
    pub fn at(position: Vector3<f64>) -> Pose {
        Pose {
            position,
            rotation: Matrix3::identity(),
        }
    }

    /// A body-frame point in the world: x + R r.
    pub fn to_world(&self, r: &Vector3<f64>) -> Vector3<f64> {
        self.position + self.rotation * r
    }
}

/// Which features of the two shapes meet at a contact point (for the panels and the lessons).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    /// A single vertex against a face (a corner poking in; a particle inside a shape).
    VertexFace,
    /// An edge lying on a face: two points at the ends of the edge's part over the face.
    EdgeFace,
    /// Two edges crossing: one point midway between their closest points.
    EdgeEdge,
    /// A face on a face: a manifold of 3 or 4 points (the clipped overlap's corners).
    FaceFace,
    /// A curved surface (the sphere obstacle) against the shape: one point.
    Sphere,
    /// A round body (ball, capsule, cylinder) touching: the points of the curved surface
    /// nearest to the other shape (one for a ball, two for a capsule or cylinder lying along a
    /// face, a rim patch for a cylinder standing on its end).
    Round,
}

impl Feature {
    /// The short name used in panels and text output.
    pub fn name(self) -> &'static str {
        match self {
            Feature::VertexFace => "vertex-face",
            Feature::EdgeFace => "edge-face",
            Feature::EdgeEdge => "edge-edge",
            Feature::FaceFace => "face-face",
            Feature::Sphere => "sphere",
            Feature::Round => "round",
        }
    }

    /// The feature of a face contact that kept `count` points: one point is a vertex, two an
    /// edge, more a face.
    pub fn of_face_contact(count: usize) -> Feature {
        match count {
            0 | 1 => Feature::VertexFace,
            2 => Feature::EdgeFace,
            _ => Feature::FaceFace,
        }
    }
}

/// One contact point between shape A and shape B (or an obstacle, always B).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPoint {
    /// World point midway between the two surfaces, m.
    pub point: Vector3<f64>,
    /// Unit normal from B toward A (the direction A must move to separate).
    pub normal: Vector3<f64>,
    /// Penetration depth along `normal`, m: > 0 penetrating, in [−margin, 0] a near point.
    pub depth: f64,
    /// Which features meet.
    pub feature: Feature,
}

impl ContactPoint {
    /// The same contact seen from the other shape: normal flipped, same point and depth.
    pub fn swapped(&self) -> ContactPoint {
        ContactPoint {
            normal: -self.normal,
            ..*self
        }
    }
}

/// The geometric penetration depth of a set of contact points: the largest depth, 0 when none
/// penetrates (near points have depth ≤ 0).
pub fn deepest(points: &[ContactPoint]) -> f64 {
    points.iter().map(|c| c.depth).fold(0.0, f64::max)
}
