//! Settings changed while a world runs, as PhET's sliders change them: the continuous
//! parameters — gravity g, drag k and k_a, restitution e, friction μ, a spring's stiffness k,
//! a motor's speed — take effect from the next step on; t and the state are kept
//! ([`World::tune`]).
//!
//! A change of g or of a spring's k changes the energy the state holds without any motion
//! (`V = −M g·x`, `U = ½ k (|d| − ℓ₀)²`). That jump is the work of turning the knob, not the
//! integrator's: the energy ledger books it into E₀,
//!
//! ```text
//! E₀ ← E₀ + (E after the change − E before it)        (same state, new parameters)
//! ```
//!
//! so the drift (E − E₀ less what the ledger booked) carries on where it was.
//!
//! [`World::tune`]: super::World::tune

use nalgebra::Vector3;

/// One continuous parameter and its new value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tuning {
    /// Uniform gravity g, m/s² (None: no gravity).
    Gravity(Option<Vector3<f64>>),
    /// Drag coefficients: linear k (kg/s, F = −k v) and angular k_a (kg·m²/s, τ = −k_a ω),
    /// each ≥ 0 (None: no drag).
    Drag(Option<(f64, f64)>),
    /// Coefficient of restitution e, 0 ≤ e ≤ 1 (the scene must have a contact model).
    Restitution(f64),
    /// Coulomb friction μ ≥ 0 (the scene must have a contact model).
    Friction(f64),
    /// Spring `spring`'s stiffness k, N/m, > 0.
    SpringStiffness { spring: usize, stiffness: f64 },
    /// Joint `joint`'s motor speed (hinge rad/s, slider m/s); the joint must have a motor.
    MotorSpeed { joint: usize, speed: f64 },
}

impl Tuning {
    /// Why this value cannot be set (a world without the thing it names is the caller's to
    /// check: [`World::tune`] says so too).
    ///
    /// [`World::tune`]: super::World::tune
    pub fn problem(&self) -> Option<String> {
        let finite = |x: f64| x.is_finite();
        match *self {
            Tuning::Gravity(Some(g)) if !g.iter().all(|c| finite(*c)) => {
                Some("gravity must be finite".into())
            }
            Tuning::Drag(Some((linear, angular))) => [("linear", linear), ("angular", angular)]
                .into_iter()
                .find(|(_, k)| !(*k >= 0.0 && finite(*k)))
                .map(|(what, k)| format!("drag.{what} must be ≥ 0, found {k}")),
            Tuning::Restitution(e) if !(0.0..=1.0).contains(&e) => {
                Some(format!("restitution must be between 0 and 1, found {e}"))
            }
            Tuning::Friction(mu) if !(mu >= 0.0 && finite(mu)) => {
                Some(format!("friction must be ≥ 0, found {mu}"))
            }
            Tuning::SpringStiffness { stiffness, .. }
                if !(stiffness > 0.0 && finite(stiffness)) =>
            {
                Some(format!("stiffness must be > 0, found {stiffness}"))
            }
            Tuning::MotorSpeed { speed, .. } if !finite(speed) => {
                Some(format!("motor speed must be finite, found {speed}"))
            }
            _ => None,
        }
    }
}
