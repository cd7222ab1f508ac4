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
//! invents a torque that gravity does not exert.

use super::super::body::Body;
use super::super::derive::Kinematics;
use super::super::effects::Loads;
use super::super::state::{Orientation, State};

/// One step of the original loop.
#[inline]
pub fn step(body: &Body, state: &State, start: &Kinematics, loads: &Loads, dt: f64) -> State {
    let r = start.rotation;
    let vertex_torque = body
        .points_body
        .iter()
        .fold(nalgebra::Vector3::zeros(), |acc, r0| {
            acc + (r * r0).cross(&loads.force)
        });
    State {
        position: state.position + start.velocity * dt,
        orientation: Orientation::Matrix(r + start.angular_velocity.cross_matrix() * r * dt),
        linear_momentum: state.linear_momentum + loads.force * dt,
        angular_momentum: state.angular_momentum + (loads.torque + vertex_torque) * dt,
    }
}
