//! Fast pairs of bodies: the time of impact within the step, so that two thin, fast bodies
//! cannot pass through each other (issue 17, item 5).
//!
//! Detection looks at the poses the integrate phase reached. A 1 cm plate closing at 30 m/s on
//! another at dt = 1e-3 moves 3 cm in the step: at its end the pair overlaps past its middle —
//! the axis of least penetration then points the wrong way and the push-out sends A through B —
//! or does not overlap at all. `detect` sweeps vertices against obstacles; this file sweeps
//! whole shapes against each other (a fixed body is a B that does not move), and round bodies
//! (which have no vertices) against the obstacles that are not half-spaces.
//!
//! # Which pairs
//!
//! Over the step each body moves along a path: its barycenter from x₀ to x₁ in a straight
//! line, its rotation from R₀ to R₁ at a constant rate about one axis (angle θ, slerp). A point
//! of the body at most ρ (the bounding radius) from its barycenter moves at most
//! `|x₁ − x₀| + θ ρ`. A pair is *fast* when its points can move relative to each other by more
//! than a fraction [`FAST`] of the thinner body's half-thickness τ (the radius of the largest
//! ball about the barycenter inside the shape: a box's smallest half-extent):
//!
//! ```text
//! fast  ⇔  |Δx_A − Δx_B| + θ_A ρ_A + θ_B ρ_B > FAST · min(τ_A, τ_B)
//! ```
//!
//! Slower pairs cannot cross the middle of either body within a step, and detection at the end
//! pose is right for them: a resting stack, a pyramid, a domino run never pay for the sweep
//! (it costs one norm and one trace per body per step to tell).
//!
//! # Time of impact: conservative advancement
//!
//! For a fast pair that is apart at the start of the step, GJK gives the gap g(t) and its
//! normal n (B toward A) at the interpolated poses; no point can close the gap faster than
//!
//! ```text
//! c = max(0, −n·(Δx_A − Δx_B)) + θ_A ρ_A + θ_B ρ_B        (per unit of t ∈ [0, 1])
//! t ← t + (g − τ_min·TARGET/2) / c,  until g ≤ τ_min·TARGET (hit at t), or t > 1 (no hit)
//! ```
//!
//! (Mirtich's conservative advancement; a face closing face-on converges in one step, since
//! the bound is then exact.) A pair overlapping already at the start of the step is left to
//! detection at the end pose (it is a resting or sliding contact, not an arrival).
//!
//! # Rows carried to the end of the step
//!
//! At the time of impact the contact geometry gives the manifold (a face on a face: its 3–4
//! clipped corners, with the right normal). Each point p, at depth d along n, is a point
//! a = p − (d/2) n of A's surface and b = p + (d/2) n of B's. Both are carried with their
//! bodies to the end of the step, `a₁ = x_A1 + R_A1 R_Aᵀ(t)(a − x_A(t))` (and b₁ likewise),
//! and the row at the end pose is
//!
//! ```text
//! n₁ = R_B1 R_Bᵀ(t) n,   depth₁ = n₁·(b₁ − a₁),   point₁ = (a₁ + b₁)/2
//! ```
//!
//! — how far A has gone past B's surface along the normal it met, however far that is: the
//! same rule as a vertex swept into a box obstacle. The response then treats it as any
//! contact: impulses equal and opposite (momentum kept), never adding energy, the push-out
//! along n₁. With e = 0, `impulse` stops the pair and re-advances it from the start of the
//! step with the corrected velocity, so it may stop up to one step's travel short of touching
//! (as a fast vertex does against a box obstacle); `soft-step` tracks the separation through
//! its sub-steps and closes that gap.

use super::geometry::gjk::{separation, CylinderView, Support};
use super::geometry::polyhedron::{BoxView, HullView};
use super::geometry::{shape_shape, ContactPoint, Feature, Pose, Shape};
use crate::physics::state::State;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// A pair is swept when its points may move relative to each other by more than this fraction
/// of the thinner body's half-thickness within a step.
pub const FAST: f64 = 0.25;

/// The sweep stops when the gap is below this fraction of the thinner half-thickness.
pub const TARGET: f64 = 0.1;

/// Most advancement steps (a face-on approach takes one; a tumbling pair a few).
pub const ADVANCE_MAX: usize = 32;

/// How a body moves over the step (module doc): straight, and at a constant rate about one axis.
#[derive(Debug, Clone, Copy)]
pub struct Path {
    x0: Vector3<f64>,
    x1: Vector3<f64>,
    q0: UnitQuaternion<f64>,
    q1: UnitQuaternion<f64>,
    /// θ ρ: the most a point can move about the barycenter over the step, m.
    pub turn: f64,
}

impl Path {
    /// The path from `before` to `after` of a shape with bounding radius ρ.
    pub fn new(before: &State, after: &State, radius: f64) -> Path {
        let q0 = before.orientation.quaternion();
        let q1 = after.orientation.quaternion();
        Path {
            x0: before.position,
            x1: after.position,
            q0,
            q1,
            turn: q0.angle_to(&q1) * radius,
        }
    }

    /// A shape that does not move (an obstacle).
    pub fn still(pose: &Pose) -> Path {
        let q = UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(
            pose.rotation,
        ));
        Path {
            x0: pose.position,
            x1: pose.position,
            q0: q,
            q1: q,
            turn: 0.0,
        }
    }

    /// Where the body is at t ∈ [0, 1] of the step.
    pub fn at(&self, t: f64) -> Pose {
        let q = self.q0.try_slerp(&self.q1, t, 1e-12).unwrap_or(self.q1);
        Pose {
            position: self.x0 + (self.x1 - self.x0) * t,
            rotation: q.to_rotation_matrix().into_inner(),
        }
    }

    /// The barycenter's displacement over the step, m.
    pub fn displacement(&self) -> Vector3<f64> {
        self.x1 - self.x0
    }
}

/// An upper bound of the most any point of a body moves over the step, m (`|Δx| + θ ρ`), from
/// the two states alone: cheap enough to ask of every body at every step (no trigonometry).
///
/// ```text
/// quaternions: cos(θ/2) = |q₀·q₁|,  θ ≤ π sin(θ/2) = π √(1 − (q₀·q₁)²)     (θ ∈ [0, π])
/// matrices:    cos θ = (tr(R₀ᵀ R₁) − 1)/2,  tr(R₀ᵀ R₁) = Σᵢⱼ R₀ᵢⱼ R₁ᵢⱼ
/// ```
pub fn reach(before: &State, after: &State, radius: f64) -> f64 {
    use crate::physics::state::Orientation;
    let turn = match (&before.orientation, &after.orientation) {
        (Orientation::Quaternion(q0), Orientation::Quaternion(q1)) => {
            let c = q0.coords.dot(&q1.coords);
            std::f64::consts::PI * (1.0 - c * c).max(0.0).sqrt()
        }
        (o0, o1) => {
            let (r0, r1) = (o0.matrix(), o1.matrix());
            ((r0.component_mul(&r1).sum() - 1.0) / 2.0)
                .clamp(-1.0, 1.0)
                .acos()
        }
    };
    (after.position - before.position).norm() + turn * radius
}

/// Whether a body's points may have moved more than `limit` over the step (`reach > limit`),
/// told without a square root or a trigonometric function: at rest, every body of a stack asks
/// this once per step. If |Δx| ≤ limit/2 and θ ρ ≤ limit/2 the reach is at most `limit`, so
///
/// ```text
/// may exceed  ⇔  |Δx|² > limit²/4  or  π² ρ² (1 − (q₀·q₁)²) > limit²/4
/// ```
///
/// (quaternions; a matrix orientation asks [`reach`]).
pub fn may_exceed(before: &State, after: &State, shape: &Shape, limit: f64) -> bool {
    use crate::physics::state::Orientation;
    let quarter = 0.25 * limit * limit;
    if (after.position - before.position).norm_squared() > quarter {
        return true;
    }
    match (&before.orientation, &after.orientation) {
        (Orientation::Quaternion(q0), Orientation::Quaternion(q1)) => {
            let c = q0.coords.dot(&q1.coords);
            let pi2 = std::f64::consts::PI * std::f64::consts::PI;
            pi2 * radius_squared(shape) * (1.0 - c * c) > quarter
        }
        _ => reach(before, after, shape.bounding_radius()) > limit,
    }
}

/// ρ², the squared bounding radius (no square root for a box or a cylinder).
fn radius_squared(shape: &Shape) -> f64 {
    match shape {
        Shape::Box { half } => half.norm_squared(),
        Shape::Cylinder {
            radius,
            half_length,
        } => radius * radius + half_length * half_length,
        other => other.bounding_radius().powi(2),
    }
}

/// The half-thickness τ of a shape: the radius of the largest ball about its barycenter that it
/// holds, m (module doc).
pub fn half_thickness(shape: &Shape) -> f64 {
    match shape {
        Shape::Box { half } => half.min(),
        Shape::Hull(hull) => hull
            .faces
            .iter()
            .map(|f| f.offset)
            .fold(f64::INFINITY, f64::min)
            .max(0.0),
        Shape::Ball { radius } | Shape::Capsule { radius, .. } => *radius,
        Shape::Cylinder {
            radius,
            half_length,
        } => radius.min(*half_length),
        Shape::Plane { .. } => f64::INFINITY,
    }
}

/// A shape placed at a pose, as GJK sees it (its support function).
struct Placed<'a> {
    shape: &'a Shape,
    pose: &'a Pose,
}

impl Support for Placed<'_> {
    fn support(&self, u: &Vector3<f64>) -> Vector3<f64> {
        let pose = self.pose;
        let ball = |radius: f64| {
            let n = u.norm();
            if n > 0.0 {
                u * (radius / n)
            } else {
                Vector3::zeros()
            }
        };
        match self.shape {
            Shape::Box { half } => BoxView::new(half, pose).support(u),
            Shape::Hull(hull) => HullView { hull, pose }.support(u),
            Shape::Ball { radius } => pose.position + ball(*radius),
            Shape::Capsule {
                radius,
                half_length,
            } => {
                let axis: Vector3<f64> = pose.rotation.column(1).into_owned();
                let end = if u.dot(&axis) >= 0.0 { 1.0 } else { -1.0 };
                pose.position + axis * (end * half_length) + ball(*radius)
            }
            Shape::Cylinder {
                radius,
                half_length,
            } => CylinderView {
                center: pose.position,
                rotation: pose.rotation,
                radius: *radius,
                half: *half_length,
            }
            .support(u),
            // Half-spaces are never swept (nothing passes through them); a point far behind.
            Shape::Plane { normal } => pose.position - pose.rotation * normal * 1e6,
        }
    }

    fn inner(&self) -> Vector3<f64> {
        self.pose.position
    }
}

/// One side of a pair: its shape and its path over the step.
#[derive(Debug, Clone, Copy)]
pub struct Side<'a> {
    pub shape: &'a Shape,
    pub path: Path,
}

/// Whether the pair needs the sweep (module doc): its points may move relative to each other
/// by more than [`FAST`] of the thinner half-thickness.
pub fn is_fast(a: &Side, b: &Side) -> bool {
    let relative = (a.path.displacement() - b.path.displacement()).norm();
    let thin = half_thickness(a.shape).min(half_thickness(b.shape));
    relative + a.path.turn + b.path.turn > FAST * thin
}

/// The time of impact t ∈ [0, 1] of a pair apart at the start of the step, with the poses
/// there; None if it is not apart at the start, or never comes within reach in the step.
pub fn time_of_impact(a: &Side, b: &Side) -> Option<(f64, Pose, Pose)> {
    let thin = half_thickness(a.shape).min(half_thickness(b.shape));
    let target = TARGET * thin;
    let relative = a.path.displacement() - b.path.displacement();
    let turning = a.path.turn + b.path.turn;
    let mut t = 0.0;
    for _ in 0..ADVANCE_MAX {
        let (pa, pb) = (a.path.at(t), b.path.at(t));
        let gap = separation(
            &Placed {
                shape: a.shape,
                pose: &pa,
            },
            &Placed {
                shape: b.shape,
                pose: &pb,
            },
            f64::INFINITY,
        )?;
        if gap.depth >= 0.0 {
            // Overlapping: at the start, a contact that was already there; later, the bound's
            // round-off overshot the target: the pair met just before t.
            return (t > 0.0).then_some((t, pa, pb));
        }
        let g = -gap.depth;
        if g <= target {
            return Some((t, pa, pb));
        }
        let closing = (-gap.normal.dot(&relative)).max(0.0) + turning;
        if closing <= 0.0 {
            return None;
        }
        t += (g - 0.5 * target) / closing;
        if t > 1.0 {
            return None;
        }
    }
    None
}

/// Sweeps a fast pair (module doc). Returns false when the pair is not fast or not apart at
/// the start of the step: detection at the end pose is then right. Returns true when the sweep
/// answered: `out` then holds the pair's rows carried to the end pose (none if it never came
/// within reach), depth ≥ −`margin`.
pub fn swept_rows(a: &Side, b: &Side, margin: f64, out: &mut Vec<ContactPoint>) -> bool {
    out.clear();
    if !is_fast(a, b) {
        return false;
    }
    // Broad phase over the step: the closest the barycenters come (relative motion in a line).
    let reach = a.shape.bounding_radius() + b.shape.bounding_radius() + margin;
    let start = a.path.x0 - b.path.x0;
    let relative = a.path.displacement() - b.path.displacement();
    let s = if relative.norm_squared() > 0.0 {
        (-start.dot(&relative) / relative.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    if (start + relative * s).norm() > reach + a.path.turn + b.path.turn {
        return true;
    }
    let Some((_, pa, pb)) = time_of_impact(a, b) else {
        // Apart at the start: no impact within the step (or overlapping at the start: the
        // end pose's detection decides).
        return separated_at_start(a, b);
    };
    let thin = half_thickness(a.shape).min(half_thickness(b.shape));
    shape_shape(a.shape, &pa, b.shape, &pb, TARGET * thin + margin, out);
    if out.is_empty() {
        // The manifold found nothing within reach: the GJK witnesses stand in (one point).
        if let Some(gap) = separation(
            &Placed {
                shape: a.shape,
                pose: &pa,
            },
            &Placed {
                shape: b.shape,
                pose: &pb,
            },
            f64::INFINITY,
        ) {
            out.push(ContactPoint {
                point: (gap.on_a + gap.on_b) / 2.0,
                normal: gap.normal,
                depth: gap.depth,
                feature: Feature::VertexFace,
            });
        }
    }
    let (a1, b1) = (a.path.at(1.0), b.path.at(1.0));
    let carry = |from: &Pose, to: &Pose, p: &Vector3<f64>| {
        to.position + to.rotation * from.rotation.tr_mul(&(p - from.position))
    };
    let turn_b: Matrix3<f64> = b1.rotation * pb.rotation.transpose();
    for c in out.iter_mut() {
        let on_a = carry(&pa, &a1, &(c.point - c.normal * (c.depth / 2.0)));
        let on_b = carry(&pb, &b1, &(c.point + c.normal * (c.depth / 2.0)));
        let normal = turn_b * c.normal;
        *c = ContactPoint {
            point: (on_a + on_b) / 2.0,
            normal,
            depth: normal.dot(&(on_b - on_a)),
            feature: c.feature,
        };
    }
    out.retain(|c| c.depth >= -margin);
    true
}

/// Whether the pair is apart at the start of the step.
fn separated_at_start(a: &Side, b: &Side) -> bool {
    let (pa, pb) = (a.path.at(0.0), b.path.at(0.0));
    separation(
        &Placed {
            shape: a.shape,
            pose: &pa,
        },
        &Placed {
            shape: b.shape,
            pose: &pb,
        },
        f64::INFINITY,
    )
    .is_none_or(|gap| gap.depth < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::state::Orientation;

    fn state(y: f64) -> State {
        State {
            position: Vector3::new(0.0, y, 0.0),
            orientation: Orientation::Quaternion(UnitQuaternion::identity()),
            linear_momentum: Vector3::zeros(),
            angular_momentum: Vector3::zeros(),
        }
    }

    fn plate() -> Shape {
        Shape::Box {
            half: Vector3::new(0.1, 0.005, 0.1),
        }
    }

    #[test]
    fn a_plate_that_jumped_over_a_plate_meets_it_on_its_top_face_with_four_corners() {
        let (pa, pb) = (plate(), plate());
        // A from 2.5 cm above B's centre to 1.5 cm below it: apart at both ends of the step.
        let a = Side {
            shape: &pa,
            path: Path::new(&state(0.025), &state(-0.015), pa.bounding_radius()),
        };
        let b = Side {
            shape: &pb,
            path: Path::new(&state(0.0), &state(0.0), pb.bounding_radius()),
        };
        let mut out = Vec::new();
        assert!(swept_rows(&a, &b, 1e-3, &mut out));
        assert_eq!(out.len(), 4, "{out:?}");
        for c in &out {
            assert!((c.normal - Vector3::y()).norm() < 1e-12, "{c:?}");
            // A's bottom face ends at −0.02; B's top face is at 0.005: 2.5 cm past it.
            assert!((c.depth - 0.025).abs() < 1e-9, "{c:?}");
        }
    }

    #[test]
    fn slow_pairs_and_pairs_touching_at_the_start_are_left_to_detection() {
        let (pa, pb) = (plate(), plate());
        let slow = Side {
            shape: &pa,
            path: Path::new(&state(0.0101), &state(0.0100), pa.bounding_radius()),
        };
        let still = Side {
            shape: &pb,
            path: Path::new(&state(0.0), &state(0.0), pb.bounding_radius()),
        };
        let mut out = Vec::new();
        assert!(!swept_rows(&slow, &still, 1e-3, &mut out));
        // Overlapping at the start, however fast: a contact already there.
        let through = Side {
            shape: &pa,
            path: Path::new(&state(0.009), &state(-0.03), pa.bounding_radius()),
        };
        assert!(!swept_rows(&through, &still, 1e-3, &mut out));
    }

    #[test]
    fn a_fast_pair_passing_beside_the_other_has_no_rows() {
        let (pa, pb) = (plate(), plate());
        let mut beside = state(0.05);
        beside.position.x = 0.5;
        let mut below = beside;
        below.position.y = -0.05;
        let a = Side {
            shape: &pa,
            path: Path::new(&beside, &below, pa.bounding_radius()),
        };
        let b = Side {
            shape: &pb,
            path: Path::new(&state(0.0), &state(0.0), pb.bounding_radius()),
        };
        let mut out = Vec::new();
        assert!(swept_rows(&a, &b, 1e-3, &mut out));
        assert!(out.is_empty(), "{out:?}");
    }
}
