//! The *derive* phase (the report's `CalculStateX`): velocities from momenta.
//!
//! ```text
//! I⁻¹_world = R · I⁻¹_body · Rᵀ
//! ω         = I⁻¹_world · L
//! v         = P / M
//! ```
//!
//! With a drifted `euler-seed` matrix R these formulas are applied as they stand, as the report
//! does: the drift then leaks into ω.

use super::body::Body;
use super::state::State;
use nalgebra::{Matrix3, Vector3};

/// What the derive phase computes from the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// R, body → world.
    pub rotation: Matrix3<f64>,
    /// I⁻¹_world = R I⁻¹_body Rᵀ (the report's `_InertieTenseurInv`).
    pub inv_inertia_world: Matrix3<f64>,
    /// ω = I⁻¹_world L, rad/s, world frame.
    pub angular_velocity: Vector3<f64>,
    /// v = P / M, m/s.
    pub velocity: Vector3<f64>,
}

/// Runs the derive phase on a state.
pub fn derive(body: &Body, state: &State) -> Kinematics {
    let rotation = state.orientation.matrix();
    derive_with_rotation(body, state, rotation)
}

/// The derive phase when R is already known.
pub fn derive_with_rotation(body: &Body, state: &State, rotation: Matrix3<f64>) -> Kinematics {
    let inv_inertia_world = rotation * body.inv_inertia_body * rotation.transpose();
    Kinematics {
        rotation,
        inv_inertia_world,
        angular_velocity: inv_inertia_world * state.angular_momentum,
        velocity: state.linear_momentum * body.inv_mass,
    }
}
