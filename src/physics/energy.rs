//! Energy of a body and of a world of bodies: kinetic, potential and their sum.
//!
//! ```text
//! K = ½ M v·v + ½ ω·L          v = P/M,  ω = I⁻¹_world L
//! V = −M g·x                   only when gravity is declared
//! E = K + V                    a world's E is the sum over its bodies (and its cloths)
//! ```
//!
//! The world, the collision responses, the divergence guard and the snapshot all measure energy
//! here, with the same arithmetic, so that their numbers agree to the last bit.

use super::body::Body;
use super::derive::derive;
use super::effects::Effects;
use super::state::State;
use nalgebra::{Matrix3, Vector3};
use std::ops::Add;

/// Kinetic `½ M v·v + ½ ω·L`, potential `−M g·x` and their sum, J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    pub kinetic: f64,
    pub potential: f64,
    pub total: f64,
}

impl Add for Energy {
    type Output = Energy;
    fn add(self, other: Energy) -> Energy {
        Energy {
            kinetic: self.kinetic + other.kinetic,
            potential: self.potential + other.potential,
            total: self.total + other.total,
        }
    }
}

/// The energy of a state, measured from the state itself.
pub fn energy(body: &Body, effects: &Effects, state: &State) -> Energy {
    let kinetic = kinetic_energy(body, state);
    let potential = effects.potential_energy(body, &state.position);
    Energy {
        kinetic,
        potential,
        total: kinetic + potential,
    }
}

/// Kinetic energy `½ M v·v + ½ ω·L` of a state, J.
pub fn kinetic_energy(body: &Body, state: &State) -> f64 {
    let kinematics = derive(body, state);
    kinetic_energy_with(
        body,
        &kinematics.inv_inertia_world,
        &state.linear_momentum,
        &state.angular_momentum,
    )
}

/// `½ M v·v + ½ ω·L` with `v = P/M`, `ω = I⁻¹_world L` for a known `I⁻¹_world`: the same
/// arithmetic as [`kinetic_energy`], so the two agree to the last bit.
#[inline]
pub fn kinetic_energy_with(
    body: &Body,
    inv_inertia_world: &Matrix3<f64>,
    linear_momentum: &Vector3<f64>,
    angular_momentum: &Vector3<f64>,
) -> f64 {
    let velocity = linear_momentum * body.inv_mass;
    let angular_velocity = inv_inertia_world * angular_momentum;
    kinetic_energy_at(body, &velocity, &angular_velocity, angular_momentum)
}

/// `½ M v·v + ½ ω·L` from v and ω already known (`v = P/M`, `ω = I⁻¹_world L`, computed as
/// [`kinetic_energy_with`] computes them: then the same bits).
#[inline]
pub fn kinetic_energy_at(
    body: &Body,
    velocity: &Vector3<f64>,
    angular_velocity: &Vector3<f64>,
    angular_momentum: &Vector3<f64>,
) -> f64 {
    0.5 * body.mass * velocity.norm_squared() + 0.5 * angular_velocity.dot(angular_momentum)
}
