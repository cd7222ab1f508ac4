//! Slider joint: a common orientation and a rail, 5 rows; its coordinate is the travel.
//!
//! ```text
//! C = t·d for t ∈ {t₁, t₂} = R_B n_B ⊥ the rail (2 rows), d = p_A − p_B:
//!                                              (t, r_A×t | −t, −r_B×t + t×d)
//!   J̇u = t·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + 2 (ω_B×t)·ḋ + (ω_B×(ω_B×t))·d
//! + fixed's 3 orientation rows (0, e_k | 0, −e_k), J̇u = 0
//! s = a·d     a = R_B a_B the rail's axis
//! ṡ = a·ḋ + (ω_B×a)·d:                         (a, r_A×a | −a, −r_B×a + a×d)
//! ```
//!
//! Residual: the anchor's distance from the rail + the relative turn (rad) × 1 m (how far a
//! point 1 m from the anchor has drifted, to first order).

use super::{anchor_points, coordinate_row, turned, Anchors, JointKind, Kind};
use crate::physics::constraints::Row;
use crate::physics::joints::written::{Between, Keys, Measure, Written};
use crate::physics::joints::{Joint, Pose};
use nalgebra::Vector3;

pub const ROWS: usize = 5;

/// `type = "slider"`, `anchor` and the rail's `axis` (world, t = 0); `limits` in m, `motor`
/// with `max_force`.
pub struct Slider;

impl Kind for Slider {
    const WRITTEN: Written = Written {
        name: "slider",
        keys: &["anchor", "axis", "limits", "motor"],
    };
    const ROWS: usize = ROWS;
    const MEASURE: Option<Measure> = Some(Measure::Travel);

    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error> {
        let anchor = keys.point("anchor")?;
        let axis = keys.direction("axis")?;
        Ok(on.at_point(JointKind::Slider, anchor, axis))
    }

    #[inline]
    fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
        rows(joint, at, out);
    }

    fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
        error(joint, a, b)
    }

    fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> Option<(Row, f64)> {
        Some(coordinate(joint, index, a, b))
    }

    /// The rail (B's axis).
    fn axis(joint: &Joint, _a: &Pose, b: &Pose) -> Option<Vector3<f64>> {
        Some(b.r * joint.axis_b)
    }
}

/// Its rows at the anchors `at`.
#[inline]
pub fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
    let (a, b, ra, rb) = (at.a, at.b, &at.ra, &at.rb);
    let separation = &at.separation;
    let rate = a.v + a.w.cross(ra) - b.v - b.w.cross(rb);
    for normal in &joint.normals_b {
        let t = b.r * normal;
        let wt = b.w.cross(&t);
        out.push(at.row(
            t,
            ra.cross(&t),
            t.cross(separation) - rb.cross(&t),
            t.dot(separation),
            t.dot(&at.centripetal) + 2.0 * wt.dot(&rate) + b.w.cross(&wt).dot(separation),
        ));
    }
    at.orientation_rows(&joint.rest, out);
}

/// The travel s (m) of A's anchor along the rail relative to B's, and its row.
pub fn coordinate(joint: &Joint, index: usize, a: &Pose, b: &Pose) -> (Row, f64) {
    let ra = a.r * joint.anchor_a;
    let rb = b.r * joint.anchor_b;
    let d = a.x + ra - b.x - rb;
    let axis = b.r * joint.axis_b;
    let travel = axis.dot(&d);
    let ang_b = axis.cross(&d) - rb.cross(&axis);
    coordinate_row(joint, index, (axis, ra.cross(&axis), ang_b), travel)
}

/// The anchor's distance from the rail plus the relative turn × 1 m.
pub fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
    let [pa, pb] = anchor_points(joint, a, b);
    let axis = b.r * joint.axis_b;
    let d = pa - pb;
    let lateral = (d - axis * axis.dot(&d)).norm();
    lateral + turned(&a.r, &b.r, &joint.rest)
}
