//! The protractor: the angle between a body axis and the vertical (y is up), or between two
//! bodies' axes, read from the bodies' orientations:
//!
//! ```text
//! a body's axis k (x, y or z) in the world: u = R eₖ (column k of R)
//! angle between u and w:  θ = atan2(|u × w|, u · w)       in [0°, 180°]
//! ```
//!
//! atan2 rather than acos(u·w): it keeps its accuracy near 0° and 180°, where acos loses half
//! the digits.

use crate::physics::State;
use nalgebra::Vector3;

/// A body's axis: body index and axis (0 x, 1 y, 2 z of its frame).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BodyAxis {
    pub body: usize,
    pub axis: usize,
}

impl BodyAxis {
    /// Its direction in the world for these states (None: no such body).
    pub fn direction(&self, states: &[State]) -> Option<Vector3<f64>> {
        let m = states.get(self.body)?.orientation.matrix();
        Some(m.column(self.axis.min(2)).into_owned())
    }
}

/// What the axis is measured against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reference {
    /// The world's y axis (up).
    Vertical,
    /// Another body's axis.
    Axis(BodyAxis),
}

/// The protractor: a body axis against a reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Protractor {
    pub axis: BodyAxis,
    pub against: Reference,
}

/// The angle between two directions, radians in [0, π] (0 for a zero vector).
pub fn angle_between(u: &Vector3<f64>, w: &Vector3<f64>) -> f64 {
    u.cross(w).norm().atan2(u.dot(w))
}

impl Protractor {
    /// The angle, degrees in [0, 180] (None: a body is not in the states).
    pub fn degrees(&self, states: &[State]) -> Option<f64> {
        let u = self.axis.direction(states)?;
        let w = match self.against {
            Reference::Vertical => Vector3::y(),
            Reference::Axis(a) => a.direction(states)?,
        };
        Some(angle_between(&u, &w).to_degrees())
    }
}

/// An axis by its letter.
pub fn axis_name(axis: usize) -> &'static str {
    ["x", "y", "z"][axis.min(2)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::Orientation;
    use nalgebra::UnitQuaternion;

    fn turned(axis: Vector3<f64>, degrees: f64) -> State {
        State {
            orientation: Orientation::Quaternion(UnitQuaternion::from_axis_angle(
                &nalgebra::Unit::new_normalize(axis),
                degrees.to_radians(),
            )),
            ..State::at_rest()
        }
    }

    #[test]
    fn a_body_turned_about_z_leans_its_y_axis_by_the_turn() {
        // Turned 30° about z: its y axis (−sin 30°, cos 30°, 0) is 30° from the vertical; its
        // x axis (cos 30°, sin 30°, 0) is 60° from it (cos θ = sin 30°).
        let states = [turned(Vector3::z(), 30.0)];
        let y = Protractor {
            axis: BodyAxis { body: 0, axis: 1 },
            against: Reference::Vertical,
        };
        assert!((y.degrees(&states).unwrap() - 30.0).abs() < 1e-12);
        let x = Protractor {
            axis: BodyAxis { body: 0, axis: 0 },
            ..y
        };
        assert!((x.degrees(&states).unwrap() - 60.0).abs() < 1e-12);
        // Upside down: 180°, where acos would lose digits.
        let flipped = [turned(Vector3::x(), 180.0)];
        assert!((y.degrees(&flipped).unwrap() - 180.0).abs() < 1e-12);
        assert_eq!(y.degrees(&[]), None);
    }

    #[test]
    fn two_bodies_axes_make_the_angle_between_their_turns() {
        // Body 0 turned 30° about z, body 1 turned 75° about z: their x axes are 45° apart.
        // Body 2 turned 90° about x: its z axis is (0, −1, 0), the y axis of body 0 is
        // (−sin 30°, cos 30°, 0): cos θ = −cos 30°, θ = 150°.
        let states = [
            turned(Vector3::z(), 30.0),
            turned(Vector3::z(), 75.0),
            turned(Vector3::x(), 90.0),
        ];
        let p = Protractor {
            axis: BodyAxis { body: 1, axis: 0 },
            against: Reference::Axis(BodyAxis { body: 0, axis: 0 }),
        };
        assert!((p.degrees(&states).unwrap() - 45.0).abs() < 1e-12);
        let q = Protractor {
            axis: BodyAxis { body: 0, axis: 1 },
            against: Reference::Axis(BodyAxis { body: 2, axis: 2 }),
        };
        assert!((q.degrees(&states).unwrap() - 150.0).abs() < 1e-12);
    }
}
