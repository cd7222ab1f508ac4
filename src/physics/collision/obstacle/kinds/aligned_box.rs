//! A fixed axis-aligned box between its corners `min` and `max` (`type = "box"`); written
//! with an `orientation`, the box is turned about its centre ([`RotatedBox`]).
//!
//! ```text
//! inside  min < p < max          depth = the nearest face's distance, normal its outward one
//! swept   the segment a → b through the faces: the face it entered by
//! ```
//!
//! Its faces stay at the written `min` and `max` to the last bit (centre ± half is off by
//! round-off): the lessons' numbers were computed so.

use super::rotated_box::RotatedBox;
use crate::physics::collision::detect::{self, Penetration};
use crate::physics::collision::geometry::{
    polyhedra, polyhedron::BoxView, polyhedron::HullView, shape_shape, ContactPoint, Pose, Shape,
};
use crate::physics::collision::obstacle::{Key, Keys, Kind, Obstacle, Outline, Written};
use nalgebra::Vector3;

/// A fixed axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlignedBox {
    pub min: Vector3<f64>,
    pub max: Vector3<f64>,
}

impl Kind for AlignedBox {
    const WORD: &'static str = "box";
    const WRITTEN: Option<Written> = Some(Written {
        listed: 2,
        keys: &[
            Key::vector("min"),
            Key::vector("max"),
            Key::rotation("orientation").optional(),
        ],
    });

    /// `min < max` on every axis (an error at `max`); with an `orientation`, a [`RotatedBox`].
    fn build<K: Keys>(keys: &K) -> Result<Obstacle, K::Error> {
        let min = keys.vector("min")?;
        let max = keys.vector("max")?;
        if !(0..3).all(|i| min[i] < max[i]) {
            return Err(keys.wrong(
                "max",
                format!(
                    "box obstacle needs min < max on every axis, found min {:?} and max {:?}",
                    [min.x, min.y, min.z],
                    [max.x, max.y, max.z]
                ),
            ));
        }
        Ok(match keys.rotation("orientation")? {
            None => Obstacle::AlignedBox(AlignedBox { min, max }),
            Some(orientation) => Obstacle::RotatedBox(RotatedBox {
                center: (min + max) / 2.0,
                half: (max - min) / 2.0,
                rotation: orientation.to_rotation_matrix().into_inner(),
            }),
        })
    }

    fn shape(&self) -> (Shape, Pose) {
        (
            Shape::Box {
                half: (self.max - self.min) / 2.0,
            },
            Pose::at((self.min + self.max) / 2.0),
        )
    }

    /// A box's and a hull's polyhedral contact against the aligned box; the shape table
    /// otherwise.
    fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        match a {
            Shape::Box { half } => polyhedra::box_box(
                &BoxView::new(half, pa),
                &BoxView::aligned(&self.min, &self.max),
                margin,
                out,
            ),
            Shape::Hull(hull) => polyhedra::contact(
                &HullView { hull, pose: pa },
                &BoxView::aligned(&self.min, &self.max),
                margin,
                out,
            ),
            _ => {
                let (shape, pose) = self.shape();
                shape_shape(a, pa, &shape, &pose, margin, out);
            }
        }
    }

    fn depth(&self, p: &Vector3<f64>) -> f64 {
        let inside = (p - self.min).inf(&(self.max - p));
        inside.min().max(0.0)
    }

    #[inline]
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        detect::inside_box(&self.min, &self.max, p)
    }

    fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
        if self.depth(a) > 0.0 {
            return self.inside(b);
        }
        detect::swept_box(&self.min, &self.max, a, b)
    }

    #[inline]
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        detect::off_box(&self.min, &self.max, p)
    }

    fn outline(&self) -> Outline {
        Outline::Aligned {
            min: self.min,
            max: self.max,
        }
    }

    fn bounds(&self, _centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (self.min, self.max)
    }
}
