//! The divergence guard: a state that is no longer finite, or energy that grew far beyond
//! anything the scene can supply.
//!
//! Gravity is conservative and drag and the `impulse` response only dissipate, so the total
//! energy E of a scene can only grow by what a `seed` collision injects (its push-out and its
//! force-as-impulse). The guard keeps that budget:
//!
//! ```text
//! E_allowed = E₀ + Σ max(0, ΔE_collide)
//! runaway  ⇔  E > E_allowed + E_ref,   E_ref = max(K₀, M|g|·radius, largest K after a collision)
//! ```
//!
//! That is: the integrator alone has created more energy than the body had to start with.

use super::body::Body;
use super::collision::Obstacle;
use super::effects::Effects;
use super::integrators::Integrator;
use super::snapshot::{energy, Energy};
use super::state::State;
use std::fmt;

/// A diverged simulation: where, what and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Divergence {
    /// Step at which the guard tripped.
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// What went wrong (e.g. "angular momentum is not finite").
    pub quantity: String,
    /// The integrator in use.
    pub integrator: Integrator,
    /// The time step, s.
    pub dt: f64,
}

impl fmt::Display for Divergence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "simulation diverged at step {} (t = {:.6} s): {} (integrator {}, dt = {} s)",
            self.step,
            self.time,
            self.quantity,
            self.integrator.name(),
            self.dt
        )
    }
}

/// The energy budget of a world.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyGuard {
    allowed: f64,
    reference: f64,
}

impl EnergyGuard {
    /// The budget at t = 0.
    pub fn new(
        body: &Body,
        effects: &Effects,
        _obstacles: &[Obstacle],
        state: &State,
    ) -> EnergyGuard {
        let Energy { kinetic, total, .. } = energy(body, effects, state);
        let weight = effects
            .gravity()
            .map_or(0.0, |g| body.mass * g.norm() * body.radius);
        EnergyGuard {
            allowed: total,
            reference: kinetic.max(weight).max(f64::MIN_POSITIVE),
        }
    }

    /// Accounts for the energy a collision response changed.
    pub fn after_collision(&mut self, total_before: f64, after: &Energy) {
        self.allowed += (after.total - total_before).max(0.0);
        self.reference = self.reference.max(after.kinetic);
    }

    /// The diverged quantity, if any.
    pub fn check(&self, state: &State, energy: &Energy) -> Option<String> {
        let finite = |v: &nalgebra::Vector3<f64>| v.iter().all(|c| c.is_finite());
        if !finite(&state.position) {
            return Some("position is not finite".into());
        }
        if !state.orientation.matrix().iter().all(|c| c.is_finite()) {
            return Some("orientation is not finite".into());
        }
        if !finite(&state.linear_momentum) {
            return Some("linear momentum is not finite".into());
        }
        if !finite(&state.angular_momentum) {
            return Some("angular momentum is not finite".into());
        }
        if !energy.total.is_finite() {
            return Some("energy is not finite".into());
        }
        let excess = energy.total - self.allowed;
        if excess > self.reference {
            return Some(format!(
                "energy ran away: {:.6e} J more than the scene can supply ({:.6e} J)",
                excess, self.allowed
            ));
        }
        None
    }
}
