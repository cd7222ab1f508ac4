//! The wire of a round body: the circles and lines a front end draws for a ball, a cylinder
//! or a capsule, which have no vertices of their own (a polyhedron is drawn by its vertices
//! and edges).

use super::collision::geometry::Shape;
use nalgebra::{Matrix3, Vector3};

/// A wire drawing: world points and the segments between them (indices).
pub type Wire = (Vec<Vector3<f64>>, Vec<(usize, usize)>);

/// Points per circle of a round body's wire.
pub const WIRE_STEPS: usize = 24;

/// The wire of a round body, world frame: points and the segments between them. A ball: its
/// equator (body x–z plane) and a meridian (body x–y plane), which turn with it, so a rolling
/// ball is seen to roll. A cylinder: its two rims and four generators. A capsule: the rims of
/// its cylindrical part, four generators and the two meridian half-circles of each cap. None
/// for a polyhedron (drawn by its own vertices and edges).
pub fn wire(shape: &Shape, position: &Vector3<f64>, rotation: &Matrix3<f64>) -> Option<Wire> {
    let mut points: Vec<Vector3<f64>> = Vec::new();
    let mut edges = Vec::new();
    let to_world = |p: Vector3<f64>| position + rotation * p;
    // A closed (or open, for an arc) polyline through body-frame points.
    let mut polyline = |pts: Vec<Vector3<f64>>, closed: bool| {
        let first = points.len();
        let n = pts.len();
        points.extend(pts.into_iter().map(to_world));
        for k in 0..n {
            if k + 1 < n {
                edges.push((first + k, first + k + 1));
            } else if closed {
                edges.push((first + k, first));
            }
        }
    };
    let circle = |r: f64, y: f64, plane_xy: bool| -> Vec<Vector3<f64>> {
        (0..WIRE_STEPS)
            .map(|k| {
                let a = k as f64 / WIRE_STEPS as f64 * std::f64::consts::TAU;
                if plane_xy {
                    Vector3::new(r * a.cos(), y + r * a.sin(), 0.0)
                } else {
                    Vector3::new(r * a.cos(), y, r * a.sin())
                }
            })
            .collect()
    };
    match *shape {
        Shape::Ball { radius } => {
            polyline(circle(radius, 0.0, false), true);
            polyline(circle(radius, 0.0, true), true);
        }
        Shape::Cylinder {
            radius,
            half_length,
        }
        | Shape::Capsule {
            radius,
            half_length,
        } => {
            for y in [-half_length, half_length] {
                polyline(circle(radius, y, false), true);
            }
            for (x, z) in [(radius, 0.0), (-radius, 0.0), (0.0, radius), (0.0, -radius)] {
                polyline(
                    vec![
                        Vector3::new(x, -half_length, z),
                        Vector3::new(x, half_length, z),
                    ],
                    false,
                );
            }
            if matches!(shape, Shape::Capsule { .. }) {
                // Half-circles over each end, in the body x–y and z–y planes.
                for sign in [-1.0, 1.0] {
                    for in_x in [true, false] {
                        let arc = (0..=WIRE_STEPS / 2)
                            .map(|k| {
                                let a = k as f64 / WIRE_STEPS as f64 * std::f64::consts::TAU;
                                let (across, up) = (radius * a.cos(), sign * radius * a.sin());
                                let y = sign * half_length + up;
                                if in_x {
                                    Vector3::new(across, y, 0.0)
                                } else {
                                    Vector3::new(0.0, y, across)
                                }
                            })
                            .collect();
                        polyline(arc, false);
                    }
                }
            }
        }
        Shape::Box { .. } | Shape::Hull(_) | Shape::Plane { .. } => return None,
    }
    Some((points, edges))
}
