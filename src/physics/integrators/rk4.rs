//! `rk4`: the classical fourth-order Runge–Kutta method over the whole state.
//!
//! With `f(X) = (v, ½ ω ⊗ q, F, τ)` evaluated by the derive and forces phases:
//!
//! ```text
//! k₁ = f(X)            k₂ = f(X + dt/2 k₁)
//! k₃ = f(X + dt/2 k₂)  k₄ = f(X + dt k₃)
//! X ← X + dt/6 (k₁ + 2k₂ + 2k₃ + k₄),   then q ← q / |q|
//! ```
//!
//! Fourth order, four force evaluations per step. Very accurate at moderate steps, but not
//! geometric: in torque-free motion the energy and |L| drift slowly (by O(dt⁴) per unit time),
//! and L changes only through round-off because τ = 0 at every stage.

use super::super::body::Body;
use super::super::derive::Kinematics;
use super::super::effects::{Effects, Loads};
use super::super::state::{Orientation, State};
use super::{normalize, quaternion_of, quaternion_rate, rotation_of};
use nalgebra::{Quaternion, Vector3};

/// The state as a plain vector space element, quaternion not yet normalised.
#[derive(Clone, Copy)]
struct Flat {
    x: Vector3<f64>,
    q: Quaternion<f64>,
    p: Vector3<f64>,
    l: Vector3<f64>,
}

impl Flat {
    #[inline]
    fn plus(&self, k: &Flat, h: f64) -> Flat {
        Flat {
            x: self.x + k.x * h,
            q: self.q + k.q * h,
            p: self.p + k.p * h,
            l: self.l + k.l * h,
        }
    }
}

/// The derivative of `state` given its kinematics and loads.
#[inline]
fn rate(q: &Quaternion<f64>, kinematics: &Kinematics, loads: &Loads) -> Flat {
    Flat {
        x: kinematics.velocity,
        q: quaternion_rate(&kinematics.angular_velocity, q),
        p: loads.force,
        l: loads.torque,
    }
}

/// `f(X)` at an intermediate stage: the derive phase's `v = P/M`, `ω = R I⁻¹_body Rᵀ L` (as
/// three matrix–vector products: a stage needs ω, not I⁻¹_world; R is that of q/|q|), then the
/// forces phase.
#[inline]
fn stage(body: &Body, effects: &Effects, y: &Flat) -> Flat {
    let rotation = rotation_of(&y.q);
    let angular_velocity = rotation * (body.inv_inertia_body * rotation.tr_mul(&y.l));
    let velocity = y.p * body.inv_mass;
    let loads = effects.loads_at(body, &velocity, &angular_velocity);
    Flat {
        x: velocity,
        q: quaternion_rate(&angular_velocity, &y.q),
        p: loads.force,
        l: loads.torque,
    }
}

/// One RK4 step.
pub fn step(
    body: &Body,
    effects: &Effects,
    state: &State,
    start: &Kinematics,
    loads: &Loads,
    dt: f64,
) -> State {
    let y = Flat {
        x: state.position,
        q: *quaternion_of(state).quaternion(),
        p: state.linear_momentum,
        l: state.angular_momentum,
    };
    let k1 = rate(&y.q, start, loads);
    let k2 = stage(body, effects, &y.plus(&k1, dt / 2.0));
    let k3 = stage(body, effects, &y.plus(&k2, dt / 2.0));
    let k4 = stage(body, effects, &y.plus(&k3, dt));
    let sum = Flat {
        x: k1.x + (k2.x + k3.x) * 2.0 + k4.x,
        q: k1.q + (k2.q + k3.q) * 2.0 + k4.q,
        p: k1.p + (k2.p + k3.p) * 2.0 + k4.p,
        l: k1.l + (k2.l + k3.l) * 2.0 + k4.l,
    };
    let end = y.plus(&sum, dt / 6.0);
    State {
        position: end.x,
        orientation: Orientation::Quaternion(normalize(end.q)),
        linear_momentum: end.p,
        angular_momentum: end.l,
    }
}
