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
//! round body vs any  the contact geometry alone (a ball has no vertices): ground and planes,
//!                    spheres, boxes and other bodies; swept (`sweep`) against a sphere or box
//!                    when it moves fast
//! fast pairs         two bodies moving fast relative to each other: swept to their time of
//!                    impact (`sweep`), the rows carried to the end of the step
//! plane (ramp)       as the ground: the vertices behind it
//! fixed body         never against an obstacle; against a moving body it is B (the world)
//! ```
//!
//! Points closer than `margin` to a surface, outside it, are *speculative* rows (depth ≤ 0):
//! the solver may keep them from closing their gap within the next step (see `impulse`).

use super::broad_phase::BroadPhase;
use super::geometry::{shape_shape, ContactPoint, Pose};
use super::sweep;
use super::{Against, CollideInput, Contact, Feature};
use crate::physics::state::State;
use nalgebra::Matrix3;

/// Finds the rows for `states` (after the integrate phase) into `out`; returns whether any
/// row touches (depth > 0). Levers are filled in from the current barycenters; `points` is a
/// buffer for the contact geometry, `broad` the broad phase's. With `input.recorded`, those
/// rows are copied instead.
pub fn find(
    input: &CollideInput,
    states: &[State],
    margin: f64,
    out: &mut Vec<Contact>,
    points: &mut Vec<ContactPoint>,
    broad: &mut BroadPhase,
) -> bool {
    out.clear();
    if let Some(rows) = input.recorded {
        out.extend_from_slice(rows);
        return out.iter().any(|c| c.depth > 0.0);
    }
    against_obstacles(input, states, margin, out, points);
    between_bodies(input, states, margin, out, points, broad);
    out.iter().any(|c| c.depth > 0.0)
}

/// Each moving body against each obstacle (module doc: vertices, swept vertices, the contact
/// geometry, round bodies), appended to `out`.
fn against_obstacles(
    input: &CollideInput,
    states: &[State],
    margin: f64,
    out: &mut Vec<Contact>,
    points: &mut Vec<ContactPoint>,
) {
    for (index, (body, state)) in input.bodies.iter().zip(states).enumerate() {
        let rotation_now = state.orientation.matrix();
        if body.fixed {
            continue;
        }
        let round = body.shape.as_ref().is_some_and(|s| s.is_round());
        // The start of the step, for the swept tests (the ground needs none).
        let swept_tests = !round && input.obstacles.iter().any(|o| !o.is_half_space());
        let before = &input.before[index];
        let rotation_before = if swept_tests {
            before.orientation.matrix()
        } else {
            Matrix3::identity()
        };
        let pose = Pose {
            position: state.position,
            rotation: rotation_now,
        };
        for (obstacle_index, obstacle) in input.obstacles.iter().enumerate() {
            let first = out.len();
            // B: the obstacle, and its static entry in the solver body table.
            let against = Against::Obstacle(obstacle_index);
            let b_end = (against, input.end(against));
            if let (true, Some(shape)) = (round, &body.shape) {
                points.clear();
                // A fast round body is swept against a thin obstacle (`sweep`).
                if !obstacle.is_half_space() {
                    let (other, at) = obstacle.shape();
                    let thin = sweep::half_thickness(shape).min(sweep::half_thickness(&other));
                    if sweep::may_exceed(before, state, shape, sweep::FAST * thin) {
                        let a = sweep::Side {
                            shape,
                            path: sweep::Path::new(before, state, shape.bounding_radius()),
                        };
                        let b = sweep::Side {
                            shape: &other,
                            path: sweep::Path::still(&at),
                        };
                        if sweep::swept_rows(&a, &b, margin, points) {
                            out.extend(points.iter().map(|p| row(index, state, b_end, p, None)));
                            continue;
                        }
                    }
                }
                obstacle.contact(shape, &pose, margin, points);
                out.extend(points.iter().map(|p| row(index, state, b_end, p, None)));
                continue;
            }
            for (vertex, r0) in body.points_body.iter().enumerate() {
                let b = state.position + rotation_now * r0;
                // Half-spaces need no sweep (see `detect`): skip the vertex's start point.
                let hit = if obstacle.is_half_space() {
                    obstacle.inside(&b)
                } else {
                    obstacle.swept(&(before.position + rotation_before * r0), &b)
                };
                let (depth, normal) = match hit {
                    Some(hit) => (hit.depth, hit.normal),
                    None => match obstacle.near(&b, margin) {
                        Some((gap, normal)) => (-gap, normal),
                        None => continue,
                    },
                };
                out.push(Contact {
                    lever: b - state.position,
                    other: b_end.1,
                    ..Contact::new(index, against, Feature::Vertex(vertex), b, depth, normal)
                });
            }
            // No vertex inside: what do faces and edges see?
            let touched = out[first..].iter().any(|c| c.depth > 0.0);
            if let (false, false, Some(shape)) = (touched, obstacle.is_half_space(), &body.shape) {
                points.clear();
                obstacle.contact(shape, &pose, margin, points);
                if !points.is_empty() {
                    out.truncate(first);
                    out.extend(points.iter().map(|p| row(index, state, b_end, p, None)));
                }
            }
        }
    }
}

/// Each pair of bodies that may touch (module doc: bounding spheres, fast pairs swept),
/// appended to `out`.
fn between_bodies(
    input: &CollideInput,
    states: &[State],
    margin: f64,
    out: &mut Vec<Contact>,
    points: &mut Vec<ContactPoint>,
    broad: &mut BroadPhase,
) {
    // Body against body: pairs whose bounding spheres meet, and fast pairs (`sweep`) whose
    // paths over the step may meet. A pair is only swept when some body moved more than
    // `FAST` of the thinnest half-thickness: at rest nothing is swept.
    let moved = |i: usize| match &input.bodies[i].shape {
        Some(shape) if !input.bodies[i].fixed => {
            sweep::reach(&input.before[i], &states[i], shape.bounding_radius())
        }
        _ => 0.0,
    };
    let thin = |i: usize| {
        input.bodies[i]
            .shape
            .as_ref()
            .map_or(f64::INFINITY, sweep::half_thickness)
    };
    // No body moved more than half of FAST·(thinnest half-thickness): no pair can be fast.
    let sweeping = states.len() > 1 && {
        let thinnest = (0..states.len()).map(thin).fold(f64::INFINITY, f64::min);
        let limit = 0.5 * sweep::FAST * thinnest;
        (0..states.len()).any(|i| match &input.bodies[i].shape {
            Some(shape) if !input.bodies[i].fixed => {
                sweep::may_exceed(&input.before[i], &states[i], shape, limit)
            }
            _ => false,
        })
    };
    // The pairs to test, in the order of the double loop a < b: every pair when some pair may
    // be fast (its path, not its end pose, decides), else those whose bounding spheres may
    // meet (`broad_phase`).
    let pairs: &[(usize, usize)] = if sweeping {
        broad.pairs.clear();
        for a in 0..states.len() {
            broad.pairs.extend((a + 1..states.len()).map(|b| (a, b)));
        }
        &broad.pairs
    } else {
        broad.find(
            (0..states.len()).filter_map(|i| {
                let shape = input.bodies[i].shape.as_ref()?;
                Some((i, states[i].position, shape.bounding_radius()))
            }),
            margin,
        );
        &broad.pairs
    };
    for &(a, b) in pairs {
        let (Some(shape_a), Some(shape_b)) = (&input.bodies[a].shape, &input.bodies[b].shape)
        else {
            continue;
        };
        if input.joined.binary_search(&(a, b)).is_ok() {
            continue;
        }
        // A fixed body is B, the world's side: it takes no impulse.
        let (a, b, shape_a, shape_b) = match (input.bodies[a].fixed, input.bodies[b].fixed) {
            (true, true) => continue,
            (true, false) => (b, a, shape_b, shape_a),
            _ => (a, b, shape_a, shape_b),
        };
        let (sa, sb) = (&states[a], &states[b]);
        if sweeping && moved(a) + moved(b) > sweep::FAST * thin(a).min(thin(b)) {
            let side_a = sweep::Side {
                shape: shape_a,
                path: sweep::Path::new(&input.before[a], sa, shape_a.bounding_radius()),
            };
            let side_b = sweep::Side {
                shape: shape_b,
                path: sweep::Path::new(&input.before[b], sb, shape_b.bounding_radius()),
            };
            if sweep::swept_rows(&side_a, &side_b, margin, points) {
                out.extend(
                    points
                        .iter()
                        .map(|p| row(a, sa, (Against::Body(b), b), p, Some(sb))),
                );
                continue;
            }
        }
        let reach = shape_a.bounding_radius() + shape_b.bounding_radius() + margin;
        if (sa.position - sb.position).norm_squared() > reach * reach {
            continue;
        }
        points.clear();
        shape_shape(shape_a, &pose_of(sa), shape_b, &pose_of(sb), margin, points);
        out.extend(
            points
                .iter()
                .map(|p| row(a, sa, (Against::Body(b), b), p, Some(sb))),
        );
    }
}

/// Where a body's shape is.
fn pose_of(state: &State) -> Pose {
    Pose {
        position: state.position,
        rotation: state.orientation.matrix(),
    }
}

/// A row from a point of the contact geometry: A is body `a` (at `state`), B is `against`
/// with its solver body `end` (`CollideInput::end`), `other` B's state if it is a body.
fn row(
    a: usize,
    state: &State,
    (against, end): (Against, usize),
    p: &ContactPoint,
    other: Option<&State>,
) -> Contact {
    Contact {
        lever: p.point - state.position,
        lever_other: other.map_or_else(nalgebra::Vector3::zeros, |s| p.point - s.position),
        other: end,
        ..Contact::new(
            a,
            against,
            Feature::Geometry(p.feature),
            p.point,
            p.depth,
            p.normal,
        )
    }
}
