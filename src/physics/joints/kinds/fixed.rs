//! Fixed joint: a common point and orientation, 6 rows.
//!
//! ```text
//! ball's 3 point rows
//! + the skew part of R_A (R_B R₀)ᵀ = 0:    3 rows (0, e_k | 0, −e_k),  J̇u = 0
//! ```
//!
//! Residual: the anchors' separation. No coordinate.

use super::{Anchors, JointKind, Kind};
use crate::physics::constraints::Row;
use crate::physics::joints::written::{Between, Keys, Written};
use crate::physics::joints::Joint;
use nalgebra::Vector3;

pub const ROWS: usize = 6;

/// `type = "fixed"`, `anchor` (world, t = 0); the orientation is held as it is at t = 0.
pub struct Fixed;

impl Kind for Fixed {
    const WRITTEN: Written = Written {
        name: "fixed",
        keys: &["anchor"],
    };
    const ROWS: usize = ROWS;

    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error> {
        let anchor = keys.point("anchor")?;
        Ok(on.at_point(JointKind::Fixed, anchor, Vector3::z()))
    }

    #[inline]
    fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
        rows(joint, at, out);
    }
}

/// Its rows at the anchors `at`.
#[inline]
pub fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
    at.point_rows(out);
    at.orientation_rows(&joint.rest, out);
}
