//! An infinite fixed plane, a ramp (`type = "plane"`, `point`, `normal`): everything behind it
//! is solid.
//!
//! ```text
//! inside  n·(p − p₀) < 0         depth = n·(p₀ − p), normal n
//! near    gap = n·(p − p₀)       normal n
//! ```

use crate::physics::collision::detect::{self, Penetration};
use crate::physics::collision::geometry::{Pose, Shape};
use crate::physics::collision::obstacle::{Key, Keys, Kind, Obstacle, Outline, Written};
use nalgebra::Vector3;

/// An infinite fixed plane through `point` with unit outward `normal`; everything behind it
/// is solid (a ramp).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub point: Vector3<f64>,
    pub normal: Vector3<f64>,
}

impl Kind for Plane {
    const WORD: &'static str = "plane";
    const WRITTEN: Option<Written> = Some(Written {
        listed: 3,
        keys: &[Key::vector("point"), Key::vector("normal")],
    });

    /// The normal is made a unit vector; a zero one is an error at `normal`.
    fn build<K: Keys>(keys: &K) -> Result<Obstacle, K::Error> {
        let normal = keys.vector("normal")?;
        let unit = normal.try_normalize(1e-12).ok_or_else(|| {
            keys.wrong(
                "normal",
                "plane `normal` has zero length: give the outward direction, e.g. [0.0, 1.0, 0.0]"
                    .to_string(),
            )
        })?;
        Ok(Obstacle::Plane(Plane {
            point: keys.vector("point")?,
            normal: unit,
        }))
    }

    fn is_half_space(&self) -> bool {
        true
    }

    fn shape(&self) -> (Shape, Pose) {
        (
            Shape::Plane {
                normal: self.normal,
            },
            Pose::at(self.point),
        )
    }

    fn depth(&self, p: &Vector3<f64>) -> f64 {
        self.normal.dot(&(self.point - p)).max(0.0)
    }

    #[inline]
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        detect::behind_plane(&self.point, &self.normal, p)
    }

    #[inline]
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        Some((self.normal.dot(&(p - self.point)), self.normal))
    }

    fn outline(&self) -> Outline {
        Outline::Plane {
            point: self.point,
            normal: self.normal,
        }
    }

    fn bounds(&self, _centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (self.point, self.point)
    }
}
