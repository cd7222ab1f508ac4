//! The ground: the plane y = `height`, everything below it solid (`type = "ground"`).
//!
//! ```text
//! inside  p.y < height           depth = height − p.y, normal +y
//! near    gap = p.y − height     normal +y
//! ```

use crate::physics::collision::detect::{self, Penetration};
use crate::physics::collision::geometry::{
    obstacles, polyhedron::BoxView, polyhedron::HullView, shape_shape, ContactPoint, Pose, Shape,
};
use crate::physics::collision::obstacle::{Key, Keys, Kind, Obstacle, Outline, Written};
use nalgebra::Vector3;

/// The plane y = `height`; everything below is solid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ground {
    pub height: f64,
}

impl Kind for Ground {
    const WORD: &'static str = "ground";
    const WRITTEN: Option<Written> = Some(Written {
        listed: 0,
        keys: &[Key::number("height")],
    });

    fn build<K: Keys>(keys: &K) -> Result<Obstacle, K::Error> {
        Ok(Obstacle::Ground(Ground {
            height: keys.finite("height")?,
        }))
    }

    fn is_half_space(&self) -> bool {
        true
    }

    fn shape(&self) -> (Shape, Pose) {
        (
            Shape::Plane {
                normal: Vector3::y(),
            },
            Pose::at(Vector3::new(0.0, self.height, 0.0)),
        )
    }

    /// A box's and a hull's own ground contact (no pose to build); the shape table otherwise.
    fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        match a {
            Shape::Box { half } => {
                obstacles::against_ground(&BoxView::new(half, pa), self.height, margin, out)
            }
            Shape::Hull(hull) => {
                obstacles::against_ground(&HullView { hull, pose: pa }, self.height, margin, out)
            }
            _ => {
                let (shape, pose) = self.shape();
                shape_shape(a, pa, &shape, &pose, margin, out);
            }
        }
    }

    fn depth(&self, p: &Vector3<f64>) -> f64 {
        (self.height - p.y).max(0.0)
    }

    #[inline]
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        detect::below_level(self.height, p)
    }

    #[inline]
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        Some((p.y - self.height, Vector3::y()))
    }

    fn outline(&self) -> Outline {
        Outline::Level(self.height)
    }

    fn bounds(&self, centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let p = Vector3::new(centre.x, self.height, centre.z);
        (p, p)
    }
}
