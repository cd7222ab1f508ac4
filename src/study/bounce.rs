//! The closed form of a straight bounce: the reference the contact methods' chart
//! ([`super::methods`]) measures a bounce against, so that each method's error is its distance
//! from the physics, not from another method.
//!
//! A scene is a straight bounce when one body falls under gravity g = (0, −g, 0) onto the one
//! ground plane y = h, without spin (L = 0), its lowest vertices centred under its barycenter
//! (a face or a vertex straight down: the contact impulses make no torque), and either no
//! friction or no horizontal velocity (friction then has nothing to act on). Its barycenter
//! then moves as a point on a floor at `y_c = h + c` (c its height above its lowest vertex):
//!
//! ```text
//! flight from (t₀, y, v):   y(t) = y + v s − ½ g s²,   s = t − t₀
//! touch after               τ = (v + √(v² + 2 g (y − y_c))) / g,   v_in = v − g τ
//! rebound                   v ← −e · v_in,   y ← y_c     (Newton's law of restitution)
//! rest                      when the rebound is below 1e-12 m/s: y = y_c after it
//! horizontal                x(t) = x₀ + vₓ t,  z(t) = z₀ + v_z t;  orientation constant
//! ```
//!
//! With e < 1 the bounces add up to a finite time (t_k + 2 v_k / (g (1 − e)) after the k-th),
//! after which the body rests; a solver stops bouncing sooner (`impulse`: approaches slower
//! than 3 g dt do not bounce), which is part of its error.

use crate::physics::collision::obstacle::Ground;
use crate::physics::collision::Obstacle;
use crate::physics::Effect;
use crate::scene::Scene;
use nalgebra::{UnitQuaternion, Vector3};

/// A rebound slower than this (m/s) ends the bouncing: the body rests.
const REST_SPEED: f64 = 1e-12;

/// The closed form of one scene's straight bounce (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Bounce {
    /// Barycenter and velocity at t = 0.
    pub position: Vector3<f64>,
    pub velocity: Vector3<f64>,
    pub orientation: UnitQuaternion<f64>,
    /// |g|, m/s².
    pub g: f64,
    /// The barycenter's height when the lowest vertex touches the ground, m.
    pub touch: f64,
    /// The coefficient of restitution e.
    pub restitution: f64,
}

impl Bounce {
    /// The scene's straight bounce, if it is one (module doc).
    pub fn of(scene: &Scene) -> Option<Bounce> {
        let model = scene.contact?;
        if scene.bodies.len() != 1 || !scene.links.is_empty() || !scene.cloths.is_empty() {
            return None;
        }
        let [Obstacle::Ground(Ground { height })] = scene.obstacles[..] else {
            return None;
        };
        if !scene
            .effects
            .list()
            .iter()
            .all(|e| matches!(e, Effect::Gravity(_)))
        {
            return None;
        }
        let gravity = scene.effects.gravity()?;
        let g = -gravity.y;
        if gravity.x != 0.0 || gravity.z != 0.0 || g <= 0.0 || !g.is_finite() {
            return None;
        }
        let first = scene.first();
        let (body, state) = (&first.body, &first.initial);
        let velocity = state.linear_momentum * body.inv_mass;
        let sliding = velocity.x != 0.0 || velocity.z != 0.0;
        if state.angular_momentum != Vector3::zeros() || (sliding && model.friction != 0.0) {
            return None;
        }
        let rotation = state.orientation.matrix();
        let offsets: Vec<Vector3<f64>> = body.points_body.iter().map(|r| rotation * r).collect();
        let lowest = offsets.iter().map(|r| r.y).fold(f64::INFINITY, f64::min);
        if !lowest.is_finite() {
            return None;
        }
        // The vertices within round-off of the lowest: their centre straight below the
        // barycenter, or the touch makes a torque.
        let tolerance = 1e-12 * body.radius.max(f64::MIN_POSITIVE);
        let bottom: Vec<&Vector3<f64>> = offsets
            .iter()
            .filter(|r| r.y <= lowest + tolerance)
            .collect();
        let centre = bottom.iter().fold(Vector3::zeros(), |s, r| s + **r) / bottom.len() as f64;
        if centre.x.abs() > tolerance || centre.z.abs() > tolerance {
            return None;
        }
        let touch = height - lowest;
        if state.position.y < touch {
            return None;
        }
        Some(Bounce {
            position: state.position,
            velocity,
            orientation: state.orientation.quaternion(),
            g,
            touch,
            restitution: model.restitution,
        })
    }

    /// The barycenter's height at time `t` (module doc).
    pub fn height(&self, t: f64) -> f64 {
        let (mut start, mut y, mut v) = (0.0, self.position.y, self.velocity.y);
        // e = 1 bounces forever: each flight is at least 2 v / g, so this bounds the count.
        for _ in 0..1_000_000 {
            let gap = (y - self.touch).max(0.0);
            let flight = (v + (v * v + 2.0 * self.g * gap).sqrt()) / self.g;
            // No flight left (at the floor, not rising), or NaN: it rests.
            if flight.is_nan() || flight <= 0.0 {
                return self.touch;
            }
            if t <= start + flight {
                let s = t - start;
                return y + v * s - 0.5 * self.g * s * s;
            }
            start += flight;
            let v_in = v - self.g * flight;
            v = -self.restitution * v_in;
            y = self.touch;
            if v < REST_SPEED {
                return self.touch;
            }
        }
        self.touch
    }

    /// The barycenter at time `t`.
    pub fn position(&self, t: f64) -> Vector3<f64> {
        Vector3::new(
            self.position.x + self.velocity.x * t,
            self.height(t),
            self.position.z + self.velocity.z * t,
        )
    }

    /// One line saying what it is.
    pub fn describe(&self) -> String {
        format!(
            "exact: the closed-form bounce (flights y + v s − ½ g s², rebounds v ← −e v_in with \
             e = {}, touching at barycenter height {} m)",
            self.restitution,
            super::analysis::format_number(self.touch)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_bounce(e: f64) -> Bounce {
        Bounce {
            position: Vector3::new(0.0, 1.0, 0.0),
            velocity: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            g: 9.81,
            touch: 0.1,
            restitution: e,
        }
    }

    #[test]
    fn the_first_rebound_climbs_e_squared_of_the_drop() {
        // Lesson 32's numbers: drop 0.9 m, e = 0.5: lands at √(2 g 0.9), climbs a quarter of
        // the drop, 0.225 m, at the top t = t₁ + e v₁ / g.
        let b = cube_bounce(0.5);
        let v1 = (2.0 * 9.81 * 0.9f64).sqrt();
        let t1 = v1 / 9.81;
        assert!((b.height(t1) - 0.1).abs() < 1e-12);
        let top = t1 + 0.5 * v1 / 9.81;
        assert!(
            (b.height(top) - (0.1 + 0.225)).abs() < 1e-12,
            "{}",
            b.height(top)
        );
        // Rests after t₁ + 2 e v₁ / (g (1 − e)).
        let rest = t1 + 2.0 * 0.5 * v1 / (9.81 * 0.5);
        assert_eq!(b.height(rest + 1e-6), 0.1);
        assert!(b.height(rest - 0.01) > 0.1);
    }

    #[test]
    fn without_restitution_it_stays_down() {
        let b = cube_bounce(0.0);
        let t1 = (2.0 * 0.9 / 9.81f64).sqrt();
        assert!((b.height(0.5 * t1) - (1.0 - 0.5 * 9.81 * 0.25 * t1 * t1)).abs() < 1e-12);
        assert_eq!(b.height(t1 + 0.1), 0.1);
    }
}
