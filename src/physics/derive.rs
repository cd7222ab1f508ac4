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
#[inline(always)]
pub fn derive(body: &Body, state: &State) -> Kinematics {
    let rotation = state.orientation.matrix();
    derive_with_rotation(body, state, rotation)
}

/// The derive phase when R is already known.
#[inline(always)]
pub fn derive_with_rotation(body: &Body, state: &State, rotation: Matrix3<f64>) -> Kinematics {
    let inv_inertia_world = congruence(&rotation, &body.inv_inertia_body);
    derive_with_inverse(body, state, rotation, inv_inertia_world)
}

/// The derive phase when R and I⁻¹_world = R I⁻¹_body Rᵀ are already known (an earlier
/// derive's at the same orientation: then the same numbers, to the bit).
#[inline(always)]
pub fn derive_with_inverse(
    body: &Body,
    state: &State,
    rotation: Matrix3<f64>,
    inv_inertia_world: Matrix3<f64>,
) -> Kinematics {
    Kinematics {
        rotation,
        inv_inertia_world,
        angular_velocity: inv_inertia_world * state.angular_momentum,
        velocity: state.linear_momentum * body.inv_mass,
    }
}

/// `R S Rᵀ` for a symmetric S: `A = R S`, then only the upper triangle of `A Rᵀ`
/// (`(A Rᵀ)ᵢⱼ = Aᵢ·Rⱼ`, rows), mirrored — the result is exactly symmetric and a third cheaper.
/// A diagonal S (a box's inertia) only scales the columns of R: the same numbers, sooner.
#[inline(always)]
pub fn congruence(r: &Matrix3<f64>, s: &Matrix3<f64>) -> Matrix3<f64> {
    let a = if s[(0, 1)] == 0.0 && s[(0, 2)] == 0.0 && s[(1, 2)] == 0.0 {
        // S diagonal (a box, any body given in its principal frame): R S scales R's columns.
        let mut a = *r;
        for j in 0..3 {
            a.column_mut(j).scale_mut(s[(j, j)]);
        }
        a
    } else {
        r * s
    };
    let entry =
        |i: usize, j: usize| a[(i, 0)] * r[(j, 0)] + a[(i, 1)] * r[(j, 1)] + a[(i, 2)] * r[(j, 2)];
    let (xx, xy, xz) = (entry(0, 0), entry(0, 1), entry(0, 2));
    let (yy, yz, zz) = (entry(1, 1), entry(1, 2), entry(2, 2));
    Matrix3::new(xx, xy, xz, xy, yy, yz, xz, yz, zz)
}
