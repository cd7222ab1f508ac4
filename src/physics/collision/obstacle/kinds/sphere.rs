//! A fixed sphere (`type = "sphere"`, `center`, `radius`).
//!
//! ```text
//! inside  |p − c| < r            depth = r − |p − c|, normal (p − c)/|p − c|
//! swept   the segment a → b against the sphere: the entry point's normal
//! ```

use crate::physics::collision::detect::{self, Penetration};
use crate::physics::collision::geometry::{
    closest_point, obstacles, shape_shape, ContactPoint, Pose, Shape,
};
use crate::physics::collision::obstacle::{Key, Keys, Kind, Obstacle, Outline, Written};
use nalgebra::Vector3;

/// A fixed sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub center: Vector3<f64>,
    pub radius: f64,
}

impl Kind for Sphere {
    const WORD: &'static str = "sphere";
    const WRITTEN: Option<Written> = Some(Written {
        listed: 1,
        keys: &[Key::vector("center"), Key::number("radius")],
    });

    fn build<K: Keys>(keys: &K) -> Result<Obstacle, K::Error> {
        Ok(Obstacle::Sphere(Sphere {
            center: keys.vector("center")?,
            radius: keys.positive("radius")?,
        }))
    }

    fn shape(&self) -> (Shape, Pose) {
        (
            Shape::Ball {
                radius: self.radius,
            },
            Pose::at(self.center),
        )
    }

    /// A box's and a hull's closest point against the ball; the shape table otherwise.
    fn contact(&self, a: &Shape, pa: &Pose, margin: f64, out: &mut Vec<ContactPoint>) {
        match a {
            Shape::Box { .. } | Shape::Hull(_) => {
                let closest = closest_point(a, pa, &self.center);
                out.extend(obstacles::against_sphere(
                    &closest,
                    &self.center,
                    self.radius,
                    margin,
                ));
            }
            _ => {
                let (shape, pose) = self.shape();
                shape_shape(a, pa, &shape, &pose, margin, out);
            }
        }
    }

    fn depth(&self, p: &Vector3<f64>) -> f64 {
        (self.radius - (p - self.center).norm()).max(0.0)
    }

    #[inline]
    fn inside(&self, p: &Vector3<f64>) -> Option<Penetration> {
        detect::inside_ball(&self.center, self.radius, p)
    }

    fn swept(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> Option<Penetration> {
        // Inside at the start, or not moved: the static test.
        if self.depth(a) > 0.0 || (b - a).norm_squared() == 0.0 {
            return self.inside(b);
        }
        detect::swept_ball(&self.center, self.radius, a, b)
    }

    #[inline]
    fn gap(&self, p: &Vector3<f64>) -> Option<(f64, Vector3<f64>)> {
        detect::off_ball(&self.center, self.radius, p)
    }

    fn outline(&self) -> Outline {
        Outline::Ball {
            center: self.center,
            radius: self.radius,
        }
    }

    fn bounds(&self, _centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        (
            self.center - Vector3::repeat(self.radius),
            self.center + Vector3::repeat(self.radius),
        )
    }
}
