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

use super::super::state::State;
use super::super::system::System;
use super::system::{advance, Block, Buffers, Method, Start};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "rk4",
        order: 4,
        summary: "classical Runge–Kutta over the whole state",
        keeps: "very small drift at moderate dt",
        rate: super::QUATERNION_RATE,
        formula: "rk4: k₁…k₄ = f(X) at t, t+dt/2, t+dt/2, t+dt;  X += dt/6·(k₁ + 2k₂ + 2k₃ + k₄)",
        colour: (30, 80, 210),
        position_factor: 0.5,
        exact_without_torque: false,
};

/// One RK4 step over the whole system, in place: each block of the system at once (linked,
/// its world stages: every body at t + dt/2 together, so a spring or a joint between two
/// bodies is integrated to fourth order; without links each body alone, in registers).
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    advance(&Rk4, system, states, start, dt, b);
}

/// The method, for any block; the joints' reactions and the springs' damping are booked with
/// rk4's weights `(1, 2, 2, 1) / 6`.
struct Rk4;

impl Method for Rk4 {
    #[inline]
    fn step<B: Block>(&self, block: &mut B, dt: f64) {
        let (y, k1) = block.start(1.0, 6.0);
        let y2 = block.plus(&y, &k1, dt / 2.0);
        let k2 = block.rates(&y2, 2.0, 6.0);
        let y3 = block.plus(&y, &k2, dt / 2.0);
        let k3 = block.rates(&y3, 2.0, 6.0);
        let y4 = block.plus(&y, &k3, dt);
        let k4 = block.rates(&y4, 1.0, 6.0);
        // k₁ + 2k₂ + 2k₃ + k₄, summed `k₁ + (k₂ + k₃)·2 + k₄` for one body and
        // `((k₁ + 2k₂) + 2k₃) + k₄` linked: the same to round-off, each the order its numbers
        // (the lessons', the joint benches') were made with.
        let end = if B::ONE_BODY {
            let middle = block.plus(&k2, &k3, 1.0);
            let first = block.plus(&k1, &middle, 2.0);
            let sum = block.plus(&first, &k4, 1.0);
            block.plus(&y, &sum, dt / 6.0)
        } else {
            block.plus_sum(&y, [&k1, &k2, &k3, &k4], dt / 6.0)
        };
        block.finish(&end, dt);
    }
}
