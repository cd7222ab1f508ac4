//! Hinge joint: a common point and a common axis, 5 rows; its coordinate is the angle.
//!
//! ```text
//! ball's 3 point rows
//! + u_A·t = 0 for t ∈ {t₁, t₂} = R_B n_B ⊥ the axis u_B:   (0, u_A×t | 0, −u_A×t)
//!   J̇u = (ω_A − ω_B)·((ω_A×u_A)×t + u_A×(ω_B×t))
//! θ = atan2(p·t₂, p·t₁)   p = R_A p_A (⊥ the axis, = t₁ at t = 0), wrapped to
//!     (c − π, c + π], c the limits' middle
//! θ̇ = u·(ω_A − ω_B):                     (0, u | 0, −u)
//! ```
//!
//! Residual: the anchors' separation.

use super::{coordinate_row, Anchors, JointKind, Kind};
use crate::physics::constraints::Row;
use crate::physics::joints::written::{Between, Keys, Measure, Written};
use crate::physics::joints::{Joint, Pose};
use nalgebra::Vector3;

pub const ROWS: usize = 5;

/// `type = "hinge"`, `anchor` and `axis` (world, t = 0); `limits` in degrees, `motor` with
/// `max_torque`.
pub struct Hinge;

impl Kind for Hinge {
    const WRITTEN: Written = Written {
        name: "hinge",
        keys: &["anchor", "axis", "limits", "motor"],
    };
    const ROWS: usize = ROWS;
    const MEASURE: Option<Measure> = Some(Measure::Angle);

    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error> {
        let anchor = keys.point("anchor")?;
        let axis = keys.direction("axis")?;
        Ok(on.at_point(JointKind::Hinge, anchor, axis))
    }

    #[inline(always)]
    fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
        rows(joint, at, out);
    }

    fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> Option<(Row, f64)> {
        Some(coordinate(joint, index, a, b))
    }

    /// A's axis.
    fn axis(joint: &Joint, a: &Pose, _b: &Pose) -> Option<Vector3<f64>> {
        Some(a.r * joint.axis_a)
    }
}

/// Its rows at the anchors `at`.
#[inline(always)]
pub fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
    at.point_rows(out);
    for (g, c, bias) in axes(joint, at.a, at.b) {
        out.push(at.row(Vector3::zeros(), g, -g, c, bias));
    }
}

/// The two axis rows at poses `a`, `b`: each one's angular part g = u_A × t on A (−g on B),
/// C = u_A·t and J̇u.
#[inline(always)]
pub fn axes(joint: &Joint, a: &Pose, b: &Pose) -> [(Vector3<f64>, f64, f64); 2] {
    let u = a.r * joint.axis_a;
    let du = a.w.cross(&u);
    let relative = a.w - b.w;
    let mut axes = [(Vector3::zeros(), 0.0, 0.0); 2];
    for (axis, normal) in axes.iter_mut().zip(&joint.normals_b) {
        let t = b.r * normal;
        let g = u.cross(&t);
        let dg = du.cross(&t) + u.cross(&b.w.cross(&t));
        *axis = (g, u.dot(&t), relative.dot(&dg));
    }
    axes
}

/// The angle θ (rad) A has turned about the axis relative to B since t = 0, and its row.
pub fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> (Row, f64) {
    let u = a.r * joint.axis_a;
    let p = a.r * joint.reference_a;
    let raw = p
        .dot(&(b.r * joint.normals_b[1]))
        .atan2(p.dot(&(b.r * joint.normals_b[0])));
    let middle = joint.limits.map_or(0.0, |[lo, hi]| 0.5 * (lo + hi));
    let turn = std::f64::consts::TAU;
    let angle = middle + (raw - middle + 0.5 * turn).rem_euclid(turn) - 0.5 * turn;
    coordinate_row(joint, index, (Vector3::zeros(), u, -u), angle)
}
