//! Ball joint: a common point, 3 rows.
//!
//! ```text
//! C = x_A + r_A − x_B − r_B                    3 rows e_k: (e_k, r_A×e_k | −e_k, −r_B×e_k)
//! J̇u = ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)
//! ```
//!
//! Residual: the anchors' separation. No coordinate (no limit, no motor).

use super::Anchors;
use crate::physics::constraints::Row;

pub const ROWS: usize = 3;

/// Its rows at the anchors `at`.
#[inline(always)]
pub fn rows(at: &Anchors, out: &mut Vec<Row>) {
    at.point_rows(out);
}
