//! A fixed box turned about its centre: a `box` obstacle written with an `orientation`
//! (built by [`AlignedBox`], which reads the `box` keys).
//!
//! Every point test is the aligned box's in the box's own frame, l = Rᵀ(p − c), with the
//! normal turned back, n = R n_l.

use super::aligned_box::AlignedBox;
use crate::physics::body::{box_corners, box_edges};
use crate::physics::collision::detect::{self, Penetration};
use crate::physics::collision::geometry::{Pose, Shape};
use crate::physics::collision::obstacle::{Kind, Outline, Written};
use nalgebra::{Matrix3, Vector3};

/// A fixed box turned about its centre: half-extents `half` along the columns of `rotation`
/// (box → world). A box obstacle written without `orientation` stays an [`AlignedBox`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotatedBox {
    pub center: Vector3<f64>,
    pub half: Vector3<f64>,
    pub rotation: Matrix3<f64>,
}

impl Kind for RotatedBox {
    const WORD: &'static str = "box";
    /// Not a type of its own in the scene file: a `box` with an `orientation`.
    const WRITTEN: Option<Written> = None;

    fn shape(&self) -> (Shape, Pose) {
        (
            Shape::Box { half: self.half },
            Pose {
                position: self.center,
                rotation: self.rotation,
            },
        )
    }

    fn depth(&self, p: &Vector3<f64>) -> f64 {
        let local = self.rotation.tr_mul(&(p - self.center));
        (self.half - local.abs()).min().max(0.0)
    }

    #[inline]
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        detect::inside_box(
            &-self.half,
            &self.half,
            &self.rotation.tr_mul(&(p - self.center)),
        )
        .map(|hit| hit.turned(&self.rotation))
    }

    fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
        // The box test in the box's own frame, the normal turned back.
        let local = AlignedBox {
            min: -self.half,
            max: self.half,
        };
        let to_local = |x: &Vector3<f64>| self.rotation.tr_mul(&(x - self.center));
        (local.swept(&to_local(a), &to_local(b))).map(|hit| hit.turned(&self.rotation))
    }

    #[inline]
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        let l = self.rotation.tr_mul(&(p - self.center));
        let (gap, n) = detect::off_box(&-self.half, &self.half, &l)?;
        Some((gap, self.rotation * n))
    }

    fn outline(&self) -> Outline {
        Outline::Wire {
            corners: (box_corners(self.half * 2.0).iter())
                .map(|c| self.center + self.rotation * c)
                .collect(),
            edges: box_edges(),
        }
    }

    fn bounds(&self, _centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (
            self.center - Vector3::repeat(self.half.norm()),
            self.center + Vector3::repeat(self.half.norm()),
        )
    }
}
