//! `exact-splitting`: kick, the *exact* torque-free flow, kick (Celledoni, Fassò, Säfström &
//! Zanna, SIAM J. Sci. Comput. 30, 2008; Strang composition, second order).
//!
//! ```text
//! kick   (P, L) ← K(dt/2)(P, L)                        x and R held
//! drift  x ← x + dt P / M
//!        R ← R · Φ(dt)      Φ the exact rotation of the free body with this L (super::super::free_flow)
//! kick   (P, L) ← K(dt/2)(P, L)                        at the new R
//!
//! K(h), the exact flow of Ṗ = M g − k v, L̇ = −kₐ ω with x and R held (Πᵢ = L in the principal frame):
//!   P ← P + (M g − k P/M) h φ(−k h/M)          φ(z) = (eᶻ − 1)/z,  φ(0) = 1
//!   Πᵢ ← Πᵢ e^(−kₐ h / Iᵢ)
//! ```
//!
//! Every sub-step is an exact flow, so the method is exact wherever the parts commute: a
//! torque-free body (no kick at all: the step *is* the closed form, at any dt) and uniform
//! gravity (it moves P only, and P does not turn the body) are reproduced to round-off. With
//! drag the kick and the rotation do not commute and the error is O(dt²); the composition
//! `exact-splitting-4` removes it to O(dt⁴).
//!
//! The rotation leaves the world L untouched (L is what the free flow keeps), so torque-free
//! |L| is kept to the last bit and the energy `½ ω·L` to round-off — no drift, no oscillation.
//! The price is one exact flow per step: a Jacobi evaluation and Carlson integrals, six to
//! seven `rk4` steps here; it pays as soon as it lets dt grow (on a free tumble, at 1e-9 rad
//! over 10 s, a simulated second costs about 60 times less than with `rk4`: `benches/step.rs`).

use super::super::body::Body;
use super::super::effects::{Effect, Effects};
use super::super::free_flow::free_flow;
use super::super::state::{Orientation, State};
use super::super::system::System;
use super::system::{advance, Buffers, Composed, Composition, KickRule, Start};
use super::{normalize, quaternion_of};
use nalgebra::{Matrix3, Vector3};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "exact-splitting",
        order: 2,
        summary: "kick–drift–kick whose drift is the exact torque-free rotation (Jacobi elliptic functions)",
        keeps: "L and energy to round-off when torque-free, at any dt; exact under gravity",
        rate: super::QUATERNION_RATE,
        formula: "exact-splitting: kick P,L by dt/2; drift x and the exact free rotation (sn, cn, dn); kick dt/2",
        colour: (0, 160, 170),
        position_factor: 0.5,
        exact_without_torque: true,
};

/// One kick–flow–kick step over the whole system, in place.
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    let plan = Composition {
        kicks: &[0.5, 0.5],
        flows: &[1.0],
        kick: KickRule::Exact,
        order: 2,
    };
    advance(
        &Composed { plan, drift },
        system,
        states,
        start,
        dt,
        b,
    );
}

/// The declared effects, summed: what the exact kick needs.
#[derive(Debug, Clone, Copy)]
pub(super) struct Kick {
    /// Σ g, m/s².
    gravity: Vector3<f64>,
    /// Σ k (linear drag), kg/s.
    linear: f64,
    /// Σ kₐ (angular drag), kg·m²/s.
    angular: f64,
}

impl Kick {
    /// The kick of the declared effects.
    pub(super) fn of(effects: &Effects) -> Kick {
        let mut kick = Kick {
            gravity: Vector3::zeros(),
            linear: 0.0,
            angular: 0.0,
        };
        for effect in effects.list() {
            match *effect {
                Effect::Gravity(g) => kick.gravity += g,
                Effect::Drag { linear, angular } => {
                    kick.linear += linear;
                    kick.angular += angular;
                }
            }
        }
        kick
    }

    /// Whether the kick changes anything.
    pub(super) fn acts(&self) -> bool {
        self.gravity != Vector3::zeros() || self.linear != 0.0 || self.angular != 0.0
    }

    /// `K(h)` in place; `rotation` is the held R (body → world).
    pub(super) fn apply(&self, body: &Body, state: &mut State, rotation: &Matrix3<f64>, h: f64) {
        if self.linear == 0.0 {
            state.linear_momentum += self.gravity * (body.mass * h);
        } else {
            let rate = self.linear * body.inv_mass;
            let force = self.gravity * body.mass - state.linear_momentum * rate;
            state.linear_momentum += force * (h * phi(-rate * h));
        }
        if self.angular != 0.0 {
            let axes = rotation * body.principal_axes.to_rotation_matrix().into_inner();
            let mut momentum = axes.tr_mul(&state.angular_momentum);
            for i in 0..3 {
                momentum[i] *= (-self.angular * h / body.principal_moments[i]).exp();
            }
            state.angular_momentum = axes * momentum;
        }
    }
}

/// `φ(z) = (eᶻ − 1)/z`, 1 at z = 0, without cancellation for small z.
fn phi(z: f64) -> f64 {
    if z == 0.0 {
        1.0
    } else {
        z.exp_m1() / z
    }
}

/// The free motion over `h` in place: x moves with P, the body turns by the exact free flow of
/// its L (which it keeps).
pub(super) fn drift(body: &Body, state: &mut State, h: f64) {
    state.position += state.linear_momentum * (body.inv_mass * h);
    let principal = quaternion_of(state) * body.principal_axes;
    let momentum = principal.inverse_transform_vector(&state.angular_momentum);
    let (_, turn) = free_flow(&body.principal_moments, &momentum, h);
    let q = principal * turn * body.principal_axes.inverse();
    state.orientation = Orientation::Quaternion(normalize(*q.quaternion()));
}
