//! Every contact row of a world for the `impulse` response: each moving body against each
//! fixed thing (`fixed`: an obstacle or a fixed body, through one function, `against_fixed`),
//! and each pair of moving bodies.
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
//! fixed body         never against an obstacle; against a moving body it is B (the world),
//!                    a fixed thing as an obstacle is: the contact geometry (it has no exact
//!                    vertex test), swept when the body is fast
//! ```
//!
//! The rows come in this order (the solvers' sweeps follow it, so it fixes the numbers): each
//! moving body against each obstacle, then the pairs of the broad phase, a fixed body's pair
//! in its place among them.
//!
//! Points closer than `margin` to a surface, outside it, are *speculative* rows (depth ≤ 0):
//! the solver may keep them from closing their gap within the next step (see `impulse`).

use super::broad_phase::BroadPhase;
use super::fixed::{pose_of, Fixed};
use super::geometry::{shape_shape, ContactPoint, Pose};
use super::sweep;
use super::{Against, CollideInput, Contact, Feature, Obstacle};
use crate::physics::body::Body;
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

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

/// Each moving body against each obstacle ([`against_fixed`]), appended to `out`.
fn against_obstacles(
    input: &CollideInput,
    states: &[State],
    margin: f64,
    out: &mut Vec<Contact>,
    points: &mut Vec<ContactPoint>,
) {
    for (index, (body, state)) in input.bodies.iter().zip(states).enumerate() {
        if body.fixed {
            continue;
        }
        let a = Moving::new(input, index, state);
        for o in 0..input.obstacles.len() {
            against_fixed(&a, &input.obstacle(o), margin, out, points);
        }
    }
}

/// Body A as detection sees it: which body, where it is now and where it was at the start of
/// the step.
struct Moving<'a> {
    index: usize,
    body: &'a Body,
    state: &'a State,
    before: &'a State,
    pose: Pose,
    /// A round shape (no vertices: the contact geometry alone).
    round: bool,
}

impl<'a> Moving<'a> {
    #[inline]
    fn new(input: &'a CollideInput, index: usize, state: &'a State) -> Moving<'a> {
        let body = &input.bodies[index];
        Moving {
            index,
            body,
            state,
            before: &input.before[index],
            pose: pose_of(state),
            round: body.shape.as_ref().is_some_and(|s| s.is_round()),
        }
    }
}

/// A moving body A against a fixed thing B, obstacle or fixed body (`fixed`), appended to
/// `out` (module doc):
///
/// ```text
/// B has an exact vertex test, A has vertices   each vertex: static (half-space) or swept
///                                              test, else near; none inside and B no
///                                              half-space: the contact geometry instead
/// otherwise                                    swept if A is fast (`sweep`), else the
///                                              contact geometry, if the bounding spheres meet
/// ```
fn against_fixed(
    a: &Moving,
    b: &Fixed,
    margin: f64,
    out: &mut Vec<Contact>,
    points: &mut Vec<ContactPoint>,
) {
    let to = (b.against, b.end);
    let row = |p: &ContactPoint| row(a.index, a.state, to, p, b.lever(&p.point));
    if let (Some(exact), false) = (b.exact(), a.round) {
        let first = out.len();
        vertices(a, exact, to, margin, out);
        // No vertex inside: what do faces and edges see?
        let touched = out[first..].iter().any(|c| c.depth > 0.0);
        if let (false, false, Some(shape)) = (touched, exact.is_half_space(), &a.body.shape) {
            points.clear();
            b.contact(shape, &a.pose, margin, points);
            if !points.is_empty() {
                out.truncate(first);
                out.extend(points.iter().map(row));
            }
        }
        return;
    }
    let Some(shape) = &a.body.shape else {
        return;
    };
    if !b.sweep(shape, a.before, a.state, margin, points) {
        if b.beyond(&a.state.position, shape.bounding_radius(), margin) {
            return;
        }
        points.clear();
        b.contact(shape, &a.pose, margin, points);
    }
    out.extend(points.iter().map(row));
}

/// The report's vertex test of A's vertices against an obstacle's kind (`detect`): static at a
/// half-space, swept along the vertex's motion otherwise; a vertex outside within `margin` is
/// a speculative row.
fn vertices(
    a: &Moving,
    exact: &Obstacle,
    (against, other): (Against, usize),
    margin: f64,
    out: &mut Vec<Contact>,
) {
    // Half-spaces need no sweep (see `detect`): no start of the step.
    let half_space = exact.is_half_space();
    let rotation_before = if half_space {
        Matrix3::identity()
    } else {
        a.before.orientation.matrix()
    };
    let (x, rotation_now) = (a.state.position, a.pose.rotation);
    for (vertex, r0) in a.body.points_body.iter().enumerate() {
        let b = x + rotation_now * r0;
        let hit = if half_space {
            exact.inside(&b)
        } else {
            exact.swept(&(a.before.position + rotation_before * r0), &b)
        };
        let (depth, normal) = match hit {
            Some(hit) => (hit.depth, hit.normal),
            None => match exact.near(&b, margin) {
                Some((gap, normal)) => (-gap, normal),
                None => continue,
            },
        };
        out.push(Contact {
            lever: b - x,
            other,
            ..Contact::new(a.index, against, Feature::Vertex(vertex), b, depth, normal)
        });
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
    if states.len() < 2 {
        // One body: no pair (a resting cube's every step skips the broad phase).
        broad.pairs.clear();
        return;
    }
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
        // A fixed body is B, a fixed thing as an obstacle is (`fixed`): it takes no impulse.
        match (input.bodies[a].fixed, input.bodies[b].fixed) {
            (true, true) => continue,
            (false, false) => {}
            (fixed_a, _) => {
                let (a, b) = if fixed_a { (b, a) } else { (a, b) };
                if let Some(fixed) = input.fixed_body(b, states) {
                    let a = Moving::new(input, a, &states[a]);
                    against_fixed(&a, &fixed, margin, out, points);
                }
                continue;
            }
        }
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
                out.extend(points.iter().map(|p| body_row(a, sa, b, sb, p)));
                continue;
            }
        }
        let reach = shape_a.bounding_radius() + shape_b.bounding_radius() + margin;
        if (sa.position - sb.position).norm_squared() > reach * reach {
            continue;
        }
        points.clear();
        shape_shape(shape_a, &pose_of(sa), shape_b, &pose_of(sb), margin, points);
        out.extend(points.iter().map(|p| body_row(a, sa, b, sb, p)));
    }
}

/// A row of body `a` (at `sa`) against body `b` (at `sb`) from a point of the contact geometry.
fn body_row(a: usize, sa: &State, b: usize, sb: &State, p: &ContactPoint) -> Contact {
    row(a, sa, (Against::Body(b), b), p, p.point - sb.position)
}

/// A row from a point of the contact geometry: A is body `a` (at `state`), B is `against`
/// with its solver body `end` (`CollideInput::end`) and lever arm `lever_other` (r_B).
fn row(
    a: usize,
    state: &State,
    (against, end): (Against, usize),
    p: &ContactPoint,
    lever_other: Vector3<f64>,
) -> Contact {
    Contact {
        lever: p.point - state.position,
        lever_other,
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
