//! `euler`: explicit (forward) Euler with a unit quaternion.
//!
//! ```text
//! x ← x + dt v          v = P / M            (at the start of the step)
//! q ← normalise(q + dt · ½ ω ⊗ q)            ω = I⁻¹_world L
//! P ← P + dt F
//! L ← L + dt τ
//! ```
//!
//! First order. The quaternion stays a rotation (renormalised), and torque-free L is kept
//! exactly, but the orientation lags behind the true motion: the kinetic energy `½ ω·L` drifts
//! upward, and a spin about the major axis (stable in reality) is pushed off it until the body
//! tumbles. It is the method to *watch fail*.

use super::super::derive::Kinematics;
use super::super::effects::Loads;
use super::super::state::{Orientation, State};
use super::super::system::System;
use super::system::{each_moving, Buffers, Start};
use super::{advance_quaternion, quaternion_of};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "euler",
        order: 1,
        summary: "explicit Euler with a unit quaternion",
        keeps: "L when torque-free; energy grows",
        rate: super::QUATERNION_RATE,
        formula: "euler: x += dt·v,  q += dt·½ω⊗q (renormalised),  P += dt·F,  L += dt·τ",
        colour: (230, 140, 0),
        position_factor: 0.0,
        exact_without_torque: false,
};

/// One explicit Euler step over the whole system (F and τ from the start of the step).
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    b.clear(start);
    each_moving(system, states, |i, _, state| {
        body_step(state, &start.kinematics[i], &start.loads[i], dt)
    });
    b.book_start(start, dt);
}

/// One explicit Euler step of one body, in place.
#[inline]
fn body_step(state: &mut State, start: &Kinematics, loads: &Loads, dt: f64) {
    state.position += start.velocity * dt;
    state.orientation = Orientation::Quaternion(advance_quaternion(
        &quaternion_of(state),
        &start.angular_velocity,
        dt,
    ));
    state.linear_momentum += loads.force * dt;
    state.angular_momentum += loads.torque * dt;
}
