//! `euler-seed`: the original practical's loop, kept on purpose.
//!
//! ```text
//! x ← x + dt v
//! R ← R + dt ω* R          ω* the cross-product matrix (StarMatrix)
//! P ← P + dt F
//! L ← L + dt τ,   τ = τ_effects + Σᵢ (R r₀ᵢ) × F      (the report's per-vertex torque sum)
//! ```
//!
//! First order. Nothing keeps R a rotation: each step multiplies it by `𝟙 + dt ω*`, whose
//! determinant is `1 + dt²|ω|²`, so R grows and shears (‖RᵀR − 𝟙‖ ≈ dt²|ω|² per step, and the
//! drawn shape stretches). The drift then leaks into `I⁻¹_world = R I⁻¹_body Rᵀ` and ω.
//!
//! The torque sum applies the *total* force at every vertex: `Σ rᵢ × F = (Σ rᵢ) × F`, zero only
//! when the points have equal masses (then `Σ rᵢ = 0`); with unequal point masses the loop
//! invents a torque that gravity does not exert. As in the report, the sum belongs to the
//! *forces* phase ([`super::Integrator::loads`] adds it to τ), so the torque panel shows it.

use super::super::body::Body;
use super::super::derive::Kinematics;
use super::super::effects::Loads;
use super::super::state::{Orientation, State};
use super::super::system::System;
use super::system::{each_moving, Buffers, Start};
use nalgebra::{Matrix3, Vector3};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "euler-seed",
        order: 1,
        summary: "the original report's loop: explicit Euler on x, the rotation *matrix* R, P and L",
        keeps: "nothing: R drifts away from a rotation",
        rate: "Ṙ = ω*·R   (ω* the cross-product matrix of ω: how R turns)",
        formula: "euler-seed: x += dt·v,  R += dt·ω*·R,  P += dt·F,  L += dt·τ   (R not re-orthonormalised)",
        colour: (200, 30, 30),
        position_factor: 0.0,
        exact_without_torque: false,
};

/// One step of the original loop over the whole system (F and τ from the start of the step).
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    b.clear(start);
    each_moving(system, states, |i, _, state| {
        body_step(state, &start.kinematics[i], &start.loads[i], dt)
    });
    b.book_start(start, dt);
}

/// The report's torque: the total force applied at every vertex, `Σᵢ (R r₀ᵢ) × F`, N·m.
pub fn vertex_torque(body: &Body, rotation: &Matrix3<f64>, force: &Vector3<f64>) -> Vector3<f64> {
    body.points_body.iter().fold(Vector3::zeros(), |acc, r0| {
        acc + (rotation * r0).cross(force)
    })
}

/// One step of the original loop, in place; `loads` already holds the vertex torque sum
/// (see [`super::Integrator::loads`]).
#[inline]
fn body_step(state: &mut State, start: &Kinematics, loads: &Loads, dt: f64) {
    let r = start.rotation;
    state.position += start.velocity * dt;
    state.orientation = Orientation::Matrix(r + start.angular_velocity.cross_matrix() * r * dt);
    state.linear_momentum += loads.force * dt;
    state.angular_momentum += loads.torque * dt;
}
