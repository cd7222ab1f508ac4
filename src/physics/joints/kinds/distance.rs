//! Distance joint: a rod of fixed length ℓ between two anchors, 1 row.
//!
//! ```text
//! C = |d| − ℓ, d = p_A − p_B, n = d/|d|:       (n, r_A×n | −n, −r_B×n)
//! J̇u = n·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + (|ḋ|² − (n·ḋ)²)/|d|
//! ```
//!
//! Residual: | |d| − ℓ |. No coordinate.

use super::{anchor_points, Anchors, Kind};
use crate::physics::constraints::Row;
use crate::physics::joints::written::{Between, Keys, Written};
use crate::physics::joints::{Joint, Pose};
use nalgebra::Vector3;

pub const ROWS: usize = 1;

/// `type = "distance"`, `anchors` (one point on each side, world, t = 0) and `length` (default:
/// their distance at t = 0).
pub struct Distance;

impl Kind for Distance {
    const WRITTEN: Written = Written {
        name: "distance",
        keys: &["anchors", "length"],
    };
    const ROWS: usize = ROWS;

    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error> {
        let anchors = keys.two_points("anchors")?;
        let length = keys.optional_positive("length")?;
        if length.is_none() && (anchors[0] - anchors[1]).norm() < 1e-12 {
            return Err(keys.wrong(
                "anchors",
                "distance joint anchors coincide at t = 0: give `length` > 0 or two \
                 different points",
            ));
        }
        Ok(Joint::distance(
            on.name, on.a, on.b, anchors, length, on.states,
        ))
    }

    #[inline]
    fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
        rows(joint, at, out);
    }

    fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
        error(joint, a, b)
    }
}

/// Its row at the anchors `at`.
#[inline]
pub fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
    let (a, b, ra, rb) = (at.a, at.b, &at.ra, &at.rb);
    let length = at.separation.norm();
    let n = if length > 0.0 {
        at.separation / length
    } else {
        Vector3::y()
    };
    let rate = a.v + a.w.cross(ra) - b.v - b.w.cross(rb);
    let along = n.dot(&rate);
    let bending = if length > 0.0 {
        (rate.norm_squared() - along * along) / length
    } else {
        0.0
    };
    out.push(at.row(
        n,
        ra.cross(&n),
        -rb.cross(&n),
        length - joint.length,
        n.dot(&at.centripetal) + bending,
    ));
}

/// | |p_A − p_B| − ℓ |, m.
pub fn error(joint: &Joint, a: &Pose, b: &Pose) -> f64 {
    let [pa, pb] = anchor_points(joint, a, b);
    ((pa - pb).norm() - joint.length).abs()
}
