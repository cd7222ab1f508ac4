//! A joint's constraint rows at a configuration: C, its gradient J and the bias J̇u (the
//! equations are in the parent module's doc, each kind's in its file under `kinds`). A row is
//! the constraint layer's [`Row`]: a joint's equality rows have bounds (−∞, ∞), a limit's
//! stops [0, ∞), a motor ±(its force × dt) (`drive`).

use super::kinds::{self, Anchors};
use super::Joint;
pub use crate::physics::constraints::Row;
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

/// Where a body is and how it moves: barycenter x, rotation R, velocity v, angular velocity ω
/// (world frame). The world is [`Pose::WORLD`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub x: Vector3<f64>,
    pub r: Matrix3<f64>,
    pub v: Vector3<f64>,
    pub w: Vector3<f64>,
}

impl Pose {
    /// The world: at the origin, unturned, at rest.
    pub const WORLD: Pose = Pose {
        x: Vector3::new(0.0, 0.0, 0.0),
        r: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        v: Vector3::new(0.0, 0.0, 0.0),
        w: Vector3::new(0.0, 0.0, 0.0),
    };

    /// A state's position and rotation, velocities left at zero (for what depends on
    /// positions only).
    pub fn of_state(state: &State) -> Pose {
        Pose {
            x: state.position,
            r: state.orientation.matrix(),
            ..Pose::WORLD
        }
    }
}

/// `J u`: a row's rate Ċ at the poses' velocities (B's ignored when the row holds A to the
/// world).
#[inline]
pub fn rate(row: &Row, a: &Pose, b: &Pose) -> f64 {
    row.axis.rate((&a.v, &a.w), Some((&b.v, &b.w)))
}

/// Appends joint `index`'s rows at poses `a`, `b` (B the world's pose when the joint holds A
/// to the world) to `out`.
#[inline(always)]
pub fn rows_of(joint: &Joint, index: usize, a: &Pose, b: &Pose, out: &mut Vec<Row>) {
    let at = Anchors::of(joint, index, a, b);
    kinds::rows(joint, &at, out);
}

/// A hinge's or slider's coordinate at poses `a`, `b` and the row of its rate, J u = q̇
/// (`drive`'s limit and motor rows; the row's owner is `index`); None for kinds without one.
pub fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> Option<(Row, f64)> {
    kinds::coordinate(joint, index, a, b)
}
