//! Distance joint: a rod of fixed length ℓ between two anchors, 1 row.
//!
//! ```text
//! C = |d| − ℓ, d = p_A − p_B, n = d/|d|:       (n, r_A×n | −n, −r_B×n)
//! J̇u = n·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + (|ḋ|² − (n·ḋ)²)/|d|
//! ```
//!
//! Residual: | |d| − ℓ |. No coordinate.

use super::{anchor_points, Anchors};
use crate::physics::constraints::Row;
use crate::physics::joints::{Joint, Pose};
use nalgebra::Vector3;

pub const ROWS: usize = 1;

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
