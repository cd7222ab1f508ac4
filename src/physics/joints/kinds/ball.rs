//! Ball joint: a common point, 3 rows.
//!
//! ```text
//! C = x_A + r_A − x_B − r_B                    3 rows e_k: (e_k, r_A×e_k | −e_k, −r_B×e_k)
//! J̇u = ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)
//! ```
//!
//! Residual: the anchors' separation. No coordinate (no limit, no motor).

use super::{Anchors, JointKind, Kind};
use crate::physics::constraints::Row;
use crate::physics::joints::written::{Between, Keys, Written};
use crate::physics::joints::Joint;
use nalgebra::Vector3;

pub const ROWS: usize = 3;

/// `type = "ball"`, `anchor` (world, t = 0).
pub struct Ball;

impl Kind for Ball {
    const WRITTEN: Written = Written {
        name: "ball",
        keys: &["anchor"],
    };
    const ROWS: usize = ROWS;

    fn build<K: Keys>(keys: &K, on: Between) -> Result<Joint, K::Error> {
        let anchor = keys.point("anchor")?;
        Ok(on.at_point(JointKind::Ball, anchor, Vector3::z()))
    }

    #[inline(always)]
    fn rows(_joint: &Joint, at: &Anchors, out: &mut Vec<Row>) {
        rows(at, out);
    }
}

/// Its rows at the anchors `at`.
#[inline(always)]
pub fn rows(at: &Anchors, out: &mut Vec<Row>) {
    at.point_rows(out);
}
