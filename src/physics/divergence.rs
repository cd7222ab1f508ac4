//! The divergence guard: a state that is no longer finite, or energy that grew far beyond
//! anything the scene can supply.
//!
//! Gravity is conservative and drag only dissipates, so the total energy E of a scene can only
//! grow by what a collision response gives (the `seed` response's push-out and
//! force-as-impulse). The energy ledger ([`super::energy_ledger`]) books that, `E_supplied =
//! E₀ + Σ max(0, ΔE_collide)`; the guard adds the largest kinetic energy the scene's own
//! physics could have given the body so far — the energy an exact integrator would show as
//! kinetic at the position the body has reached:
//!
//! ```text
//! K_scale(t)   = max( M|g|·radius,  max_{s ≤ t} (E_supplied(s) − V(x(s))),  K after a collide )
//! runaway  ⇔  E(t) − E_supplied(t) > K_scale(t)
//! ```
//!
//! (Losses are not subtracted: energy an integrator creates and a contact or drag takes again
//! is the ledger's drift, shown in the energy panel, but the body does not hold it.)
//!
//! That is: the integrator alone has created more energy than the most kinetic energy the body
//! has legitimately had — a relative energy error above 100 %. No correct run comes near it
//! (a first-order method on a free fall errs by ½ M g² dt·t against a kinetic energy ½ M g² t²,
//! a relative dt/t), while a method that has stopped simulating the scene crosses it quickly.
//! For a free body the rule has a plain meaning: in momentum form with a unit quaternion, L is
//! fixed and `|L|²/2I₃ ≤ E ≤ |L|²/2I₁`; explicit `euler` pumps a spin about the major axis
//! (E₀ = |L|²/2I₃) towards the minor axis, and E > 2E₀ says the body is no longer spinning the
//! way it was started. (`euler-seed`'s matrix grows without bound instead, and E with it.)
//! `M|g|·radius` — lifting the body by its own size — is the floor for a body started at rest.
//!
//! Energy cannot see a `seed` collision that keeps injecting spin (its budget grows with every
//! injection), so the guard also watches the rotation per step:
//!
//! ```text
//! unresolved  ⇔  |ω|·dt > π
//! ```
//!
//! Past half a turn per step no integrator can tell the motion from a slower turn the other way
//! (aliasing): the time step no longer resolves the rotation, whatever produced it.
use super::energy::Energy;
use super::energy_ledger::EnergyLedger;
use super::integrators::Integrator;
use super::state::State;
use std::fmt;

/// Largest rotation per step the guard accepts, rad: half a turn.
pub const MAX_TURN_PER_STEP: f64 = std::f64::consts::PI;

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
    /// What diverged when it is not a body: e.g. "cloth `sheet`, integrator symplectic-euler"
    /// (then shown instead of the bodies' integrator).
    pub subject: Option<String>,
}

impl fmt::Display for Divergence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let integrator = match &self.subject {
            Some(subject) => subject.clone(),
            None => format!("integrator {}", self.integrator.name()),
        };
        // Short numbers whatever their size (a dt of 1e300 is one word, not 300 digits).
        let time = if self.time.abs() < 1e6 {
            format!("{:.6}", self.time)
        } else {
            format!("{:.6e}", self.time)
        };
        let dt = if (1e-6..1e6).contains(&self.dt.abs()) {
            self.dt.to_string()
        } else {
            format!("{:e}", self.dt)
        };
        write!(
            f,
            "simulation diverged at step {} (t = {time} s): {} ({integrator}, dt = {dt} s)",
            self.step, self.quantity
        )
    }
}

/// The kinetic-energy scale a world's drift is measured against (the energy budget itself is
/// the ledger's).
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyGuard {
    /// K_scale: the largest kinetic energy the scene could have supplied so far, J.
    reference: f64,
}

impl EnergyGuard {
    /// The scale at t = 0, from the scene's energy then and `weight`, the work that would
    /// lift every body by its own size (Σ M|g|·radius; 0 without gravity).
    pub fn new(energy: &Energy, weight: f64) -> EnergyGuard {
        let Energy { kinetic, .. } = *energy;
        EnergyGuard {
            reference: kinetic.max(weight).max(f64::MIN_POSITIVE),
        }
    }

    /// Accounts for the position reached: an exact integrator would show at most
    /// `E_supplied − V(x)` as kinetic energy there, so errors are measured against that much.
    pub fn observe(&mut self, ledger: &EnergyLedger, potential: f64) {
        let kinetic = ledger.supplied() - potential;
        if kinetic > self.reference {
            self.reference = kinetic;
        }
    }

    /// Accounts for the kinetic energy a collision response left (the ledger books the change).
    pub fn after_collision(&mut self, after: &Energy) {
        self.reference = self.reference.max(after.kinetic);
    }

    /// The diverged quantity, if any: `energy` is the scene's, `turn_per_step` the largest
    /// |ω|·dt of its bodies, rad (check each state with [`not_finite`] first).
    pub fn check(
        &self,
        energy: &Energy,
        ledger: &EnergyLedger,
        turn_per_step: f64,
    ) -> Option<String> {
        if !energy.total.is_finite() {
            return Some("energy is not finite".into());
        }
        if turn_per_step > MAX_TURN_PER_STEP {
            // Above π and below 1e3 in practice: 4 decimals read better than `3.4937e0`.
            let turn = if turn_per_step < 1e3 {
                format!("{turn_per_step:.4}")
            } else {
                format!("{turn_per_step:.4e}")
            };
            return Some(format!(
                "rotation no longer resolved: |ω|·dt = {turn} rad per step, more than half a \
                 turn (π)"
            ));
        }
        let supplied = ledger.supplied();
        let excess = energy.total - supplied;
        if excess > self.reference {
            return Some(format!(
                "energy ran away: E = {:.4e} J against a budget of {:.4e} J; the integrator \
                 created {:.4e} J, more than the largest kinetic energy the scene supplied \
                 ({:.4e} J)",
                energy.total, supplied, excess, self.reference
            ));
        }
        None
    }
}

/// The first quantity of a state that is no longer finite, if any.
pub fn not_finite(state: &State) -> Option<&'static str> {
    let finite = |v: &nalgebra::Vector3<f64>| v.iter().all(|c| c.is_finite());
    if !finite(&state.position) {
        return Some("position is not finite");
    }
    if !state.orientation.matrix().iter().all(|c| c.is_finite()) {
        return Some("orientation is not finite");
    }
    if !finite(&state.linear_momentum) {
        return Some("linear momentum is not finite");
    }
    if !finite(&state.angular_momentum) {
        return Some("angular momentum is not finite");
    }
    None
}
