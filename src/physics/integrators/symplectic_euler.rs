//! `symplectic-euler`: semi-implicit Euler, momenta first.
//!
//! ```text
//! P ← P + dt F(X)                  L ← L + dt τ(X)
//! v = P / M                        ω = R I⁻¹_body Rᵀ L        (new momenta, old R)
//! x ← x + dt v                     q ← normalise(q + dt · ½ ω ⊗ q)
//! ```
//!
//! First order, one force evaluation per step, the cheapest stable choice for games. Using the
//! *new* velocities makes the translational part symplectic: a projectile's or an oscillator's
//! energy error stays bounded instead of growing. The rotational part is still a first-order
//! approximation of the free rotation, so torque-free energy is not kept to better than O(dt).

use super::super::body::Body;
use super::super::derive::Kinematics;
use super::super::effects::Loads;
use super::super::state::{Orientation, State};
use super::super::system::System;
use super::system::{each_moving, Buffers, Start};
use super::{advance_quaternion, quaternion_of};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "symplectic-euler",
        order: 1,
        summary: "momenta first, then positions with the new velocities",
        keeps: "bounded energy error in translation",
        rate: super::QUATERNION_RATE,
        formula: "symplectic-euler: P += dt·F, L += dt·τ first; then x += dt·P/M, q += dt·½ω⊗q with the new ω",
        colour: (30, 150, 60),
        position_factor: 1.0,
        exact_without_torque: false,
};

/// One semi-implicit Euler step over the whole system (F and τ from the start of the step).
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    b.clear(start);
    each_moving(system, states, |i, body, state| {
        body_step(body, state, &start.kinematics[i], &start.loads[i], dt)
    });
    b.book_start(start, dt);
}

/// One semi-implicit Euler step of one body, in place.
#[inline]
fn body_step(body: &Body, state: &mut State, start: &Kinematics, loads: &Loads, dt: f64) {
    state.linear_momentum += loads.force * dt;
    state.angular_momentum += loads.torque * dt;
    let velocity = state.linear_momentum * body.inv_mass;
    let angular_velocity = start.inv_inertia_world * state.angular_momentum;
    state.position += velocity * dt;
    state.orientation = Orientation::Quaternion(advance_quaternion(
        &quaternion_of(state),
        &angular_velocity,
        dt,
    ));
}
