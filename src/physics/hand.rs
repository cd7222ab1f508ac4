//! The hand: a body pulled towards a point (the mouse pointer) by a stiff damped spring, as
//! myPhysicsLab's drag spring does. A force element of its own: it acts only while a front end
//! has set one ([`super::World::set_hand`]) and costs nothing otherwise.
//!
//! The spring joins a material point of the body, `r` in the body frame (the grabbed point),
//! to the target `p*`:
//!
//! ```text
//! p = x + R r                       the grabbed point, world frame
//! u = v + ω × (R r)                 its velocity
//! F = k (p* − p) − c u              the hand's force, applied at p
//! ```
//!
//! **Stiffness from the body's mass and the scene's dt.** The grabbed point moves as a point of
//! effective mass `m` along F; the lightest it can be (the grab point's effective mass along
//! the worst direction) is
//!
//! ```text
//! 1/m = 1/M + |r|² / I_min           (I_min: the smallest principal moment)
//! ```
//!
//! and the spring is tuned on it, critically damped, with a natural frequency `ω_h` that is
//! quick to follow the pointer but kept to `ω_h dt ≤ h_max`:
//!
//! ```text
//! ω_h = min(OMEGA_MAX, H_MAX / dt)     (20 rad/s, 0.5)
//! k   = m ω_h²
//! c   = 2 ζ m ω_h,   ζ = 1
//! ```
//!
//! **Applied as a kick** at the start of each frame (before the derive phase), whatever the
//! integrator: `P += F dt`, `L += (R r) × F dt`, then the integrator moves the body with the new
//! momenta. For the grabbed point this is symplectic Euler on `m ẍ = −k x − c ẋ`, whose update
//! matrix has trace `2 − 2ζh − h²` and determinant `1 − 2ζh` (h = ω_h dt): stable while
//! `h² + 4ζh < 4`, i.e. h < 0.83 at ζ = 1. With h ≤ 0.5 the margin covers the heavier
//! directions too (a larger m only lowers h there).
//!
//! **Its work** is the kinetic energy the kick changes, exactly (the kick moves nothing, so
//! the potential energy is unchanged):
//!
//! ```text
//! W_hand = Σ over kicks (K after − K before) = Σ J·(u⁻ + u⁺)/2,   J = F dt
//! ```
//!
//! booked in the energy ledger as the hand's row, so `E − E₀` still closes with only the
//! integrator's drift left over.

use super::body::Body;
use super::derive::derive;
use super::energy::kinetic_energy;
use super::state::State;
use nalgebra::Vector3;

/// The hand's largest natural frequency, rad/s (it settles in about 4/ω_h = 0.2 s).
pub const OMEGA_MAX: f64 = 20.0;
/// The largest `ω_h dt` (see the module: stable below 0.83 with critical damping).
pub const H_MAX: f64 = 0.5;

/// A body held by the hand.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hand {
    /// The body held.
    pub body: usize,
    /// The grabbed material point, body frame, about the barycenter, m.
    pub point_body: Vector3<f64>,
    /// Where the hand pulls it (the pointer), world frame, m.
    pub target: Vector3<f64>,
    /// k, N/m.
    pub stiffness: f64,
    /// c, N·s/m.
    pub damping: f64,
}

/// The hand's pull on a body now.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pull {
    /// The grabbed point, world frame, m.
    pub at: Vector3<f64>,
    /// F = k (p* − p) − c u, N.
    pub force: Vector3<f64>,
}

impl Hand {
    /// A hand on `body` (index `index`) at world point `grabbed` of state `state`, pulling
    /// towards `target`, tuned for steps of `dt` (see the module).
    pub fn new(
        index: usize,
        body: &Body,
        state: &State,
        grabbed: Vector3<f64>,
        target: Vector3<f64>,
        dt: f64,
    ) -> Hand {
        let rotation = state.orientation.matrix();
        let point_body = rotation.transpose() * (grabbed - state.position);
        let mass = effective_mass(body, &point_body);
        let omega = OMEGA_MAX.min(H_MAX / dt);
        Hand {
            body: index,
            point_body,
            target,
            stiffness: mass * omega * omega,
            damping: 2.0 * mass * omega,
        }
    }

    /// The grabbed point and the spring's force at a state.
    pub fn pull(&self, body: &Body, state: &State) -> Pull {
        let k = derive(body, state);
        let arm = k.rotation * self.point_body;
        let at = state.position + arm;
        let velocity = k.velocity + k.angular_velocity.cross(&arm);
        Pull {
            at,
            force: self.stiffness * (self.target - at) - self.damping * velocity,
        }
    }

    /// The kick of one frame of length `dt`: `P += F dt`, `L += (R r) × F dt`. Returns the
    /// work done, the kinetic energy it changed, J (0 for a fixed body, which it leaves alone).
    pub fn kick(&self, body: &Body, state: &mut State, dt: f64) -> f64 {
        if body.fixed {
            return 0.0;
        }
        let Pull { at, force } = self.pull(body, state);
        let before = kinetic_energy(body, state);
        let impulse = force * dt;
        state.linear_momentum += impulse;
        state.angular_momentum += (at - state.position).cross(&impulse);
        kinetic_energy(body, state) - before
    }
}

/// The lightest effective mass of the body's point `r` (body frame, about the barycenter):
/// `1/m = 1/M + |r|²/I_min`, kg (M alone when the body has no finite smallest moment).
pub fn effective_mass(body: &Body, r: &Vector3<f64>) -> f64 {
    let i_min = body.principal_moments.min();
    let turn = if i_min > 0.0 && i_min.is_finite() {
        r.norm_squared() / i_min
    } else {
        0.0
    };
    1.0 / (body.inv_mass + turn).max(f64::MIN_POSITIVE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::State;

    #[test]
    fn the_spring_is_critically_damped_on_the_lightest_effective_mass() {
        // A 2 kg unit cube: I = 2/6 kg·m² about every axis. Grabbed at its centre: m = 2 kg;
        // at dt = 0.01 s, ω_h = min(20, 50) = 20 rad/s: k = 800 N/m, c = 80 N·s/m. At a
        // corner, |r|² = 3/4: 1/m = 1/2 + (3/4)/(1/3) = 2.75, m = 0.3636… kg.
        let body = Body::solid_box(Vector3::repeat(1.0), 2.0).unwrap();
        let state = State::at_rest();
        let hand = Hand::new(0, &body, &state, Vector3::zeros(), Vector3::x(), 0.01);
        assert!((hand.stiffness - 800.0).abs() < 1e-9, "{hand:?}");
        assert!((hand.damping - 80.0).abs() < 1e-9, "{hand:?}");
        let corner = Vector3::repeat(0.5);
        assert!((effective_mass(&body, &corner) - 1.0 / 2.75).abs() < 1e-12);
        // At dt = 0.1 s: ω_h = 0.5/0.1 = 5 rad/s, k = 2·25 = 50 N/m.
        let slow = Hand::new(0, &body, &state, Vector3::zeros(), Vector3::x(), 0.1);
        assert!((slow.stiffness - 50.0).abs() < 1e-9);
    }

    #[test]
    fn a_kick_at_the_centre_books_the_kinetic_energy_it_gives() {
        // Held at its centre, 1 m short of the target, at rest: F = k·1 = 800 N along x,
        // J = 8 N·s, ΔK = J²/2M = 16 J, no spin.
        let body = Body::solid_box(Vector3::repeat(1.0), 2.0).unwrap();
        let mut state = State::at_rest();
        let hand = Hand::new(0, &body, &state, Vector3::zeros(), Vector3::x(), 0.01);
        let work = hand.kick(&body, &mut state, 0.01);
        assert!((state.linear_momentum - Vector3::new(8.0, 0.0, 0.0)).norm() < 1e-12);
        assert_eq!(state.angular_momentum, Vector3::zeros());
        assert!((work - 16.0).abs() < 1e-12, "{work}");
    }
}
