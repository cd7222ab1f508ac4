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
use super::system::{
    body_rates, each_moving, rates_at, stage_rates, start_rates, write_back, Buffers, Flat, Start,
};

/// One RK4 step over the whole system, in place. Coupled: world stages (every body at
/// t + dt/2 together), so a spring or a joint between two bodies is integrated to fourth
/// order. Without links each body is a system of its own, stepped alone with the same
/// formulas in registers (world stages through the buffers cost 40 % more instructions on a
/// free body: `tumble run 10-tennis-racket`).
///
/// The sum `k₁ + 2k₂ + 2k₃ + k₄` is `k₁ + (k₂ + k₃)·2 + k₄` per body and
/// `((k₁ + 2k₂) + 2k₃) + k₄` coupled: the same to round-off, each the order its numbers
/// (the lessons', the joint benches') were made with.
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    b.clear(start);
    if system.coupled() {
        world_stages(system, states, start, dt, b);
        return;
    }
    each_moving(system, states, |i, body, state| {
        let y = Flat::of(state);
        let k1 = rates_at(&y, &start.kinematics[i], &start.loads[i]);
        let f = |y: &Flat| body_rates(body, system.effects, y);
        let k2 = f(&y.plus(&k1, dt / 2.0));
        let k3 = f(&y.plus(&k2, dt / 2.0));
        let k4 = f(&y.plus(&k3, dt));
        let sum = Flat::sum(&Flat::sum(&k1, &Flat::sum(&k2, &k3).scaled(2.0)), &k4);
        *state = y.plus(&sum, dt / 6.0).state();
    });
}

/// RK4's world stages over the coupled system, booking the joints' reactions and the
/// springs' damping with rk4's weights.
fn world_stages(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    let mut y = std::mem::take(&mut b.y);
    let mut k = std::mem::take(&mut b.k);
    let mut sum = std::mem::take(&mut b.sum);
    let mut stage = std::mem::take(&mut b.stage);
    y.clear();
    y.extend(states.iter().map(Flat::of));
    // k₁ from the forces phase.
    start_rates(&y, start, &mut k);
    sum.clone_from(&k);
    b.book_reactions(start.joint_loads, 1.0 / 6.0);
    let mut work = start.damping_power / 6.0;
    for (h, w) in [(0.5, 2.0), (0.5, 2.0), (1.0, 1.0)] {
        stage.clear();
        stage.extend(y.iter().zip(&k).map(|(y, ki)| y.plus(ki, h * dt)));
        stage_rates(system, &stage, b, &mut k);
        b.book_evaluation_reactions(w / 6.0);
        work += b.damping_power() * w / 6.0;
        for (s, ki) in sum.iter_mut().zip(&k) {
            *s = s.plus(ki, w);
        }
    }
    for (end, s) in y.iter_mut().zip(&sum) {
        *end = end.plus(s, dt / 6.0);
    }
    write_back(system, states, &y);
    b.damping_work = work * dt;
    (b.y, b.k, b.sum, b.stage) = (y, k, sum, stage);
}
