//! Every contact row of a world for the `impulse` response: each body against each obstacle,
//! and each pair of bodies.
//!
//! ```text
//! body vs ground     the body's vertices below the plane (exact for a convex body: a face
//!                    lying flat gives its 4 corners, an edge its 2 ends)
//! body vs sphere/box the report's vertex test, swept along each vertex's motion (it catches
//!                    fast vertices and knows which face they came in through); where no
//!                    vertex touches, the contact geometry finds what vertices miss: the
//!                    obstacle's own corners and edges inside the body's faces, edge across
//!                    edge, a sphere against the middle of a face
//! body vs body       the contact geometry (separating axes, clipped face manifolds)
//! ```
//!
//! Points closer than `margin` to a surface, outside it, are *speculative* rows (depth ≤ 0):
//! the solver may keep them from closing their gap within the next step (see `impulse`).

use super::detect::{inside, near, swept};
use super::{Against, CollideInput, Contact, Feature, Obstacle};
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

/// Finds the rows for `states` (after the integrate phase) into `out`; returns whether any
/// row touches (depth > 0). Levers are filled in from the current barycenters.
pub fn find(input: &CollideInput, states: &[State], margin: f64, out: &mut Vec<Contact>) -> bool {
    out.clear();
    for (index, (body, state)) in input.bodies.iter().zip(states).enumerate() {
        let rotation_now = state.orientation.matrix();
        // The start of the step, for the swept tests (the ground needs none).
        let swept_tests = input
            .obstacles
            .iter()
            .any(|o| !matches!(o, Obstacle::Ground { .. }));
        let before = &input.before[index];
        let rotation_before = if swept_tests {
            before.orientation.matrix()
        } else {
            Matrix3::identity()
        };
        for (obstacle_index, obstacle) in input.obstacles.iter().enumerate() {
            for (vertex, r0) in body.points_body.iter().enumerate() {
                let b = state.position + rotation_now * r0;
                // The ground needs no sweep (see `detect`): skip the vertex's start point.
                let hit = if let Obstacle::Ground { .. } = obstacle {
                    inside(obstacle, &b)
                } else {
                    swept(obstacle, &(before.position + rotation_before * r0), &b)
                };
                let (depth, normal) = match hit {
                    Some(hit) => (hit.depth, hit.normal),
                    None => match near(obstacle, &b, margin) {
                        Some((gap, normal)) => (-gap, normal),
                        None => continue,
                    },
                };
                out.push(Contact {
                    lever: b - state.position,
                    ..Contact::new(
                        index,
                        Against::Obstacle(obstacle_index),
                        Feature::Vertex(vertex),
                        b,
                        depth,
                        normal,
                    )
                });
            }
        }
    }
    out.iter().any(|c| c.depth > 0.0)
}

/// The lever arm from a barycenter to a point.
#[inline]
pub fn lever(point: &Vector3<f64>, state: &State) -> Vector3<f64> {
    point - state.position
}
