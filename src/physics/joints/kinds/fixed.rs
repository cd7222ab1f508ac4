//! Fixed joint: a common point and orientation, 6 rows.
//!
//! ```text
//! ball's 3 point rows
//! + the skew part of R_A (R_B R₀)ᵀ = 0:    3 rows (0, e_k | 0, −e_k),  J̇u = 0
//! ```
//!
//! Residual: the anchors' separation. No coordinate.

use super::Anchors;
use crate::physics::constraints::Row;
use crate::physics::joints::Joint;

pub const ROWS: usize = 6;

/// Its rows at the anchors `at`.
#[inline]
pub fn rows(joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
    at.point_rows(out);
    at.orientation_rows(&joint.rest, out);
}
