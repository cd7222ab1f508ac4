//! The step context: the constants every contact pass of one step reads — bodies against
//! bodies and obstacles (`impulse`, `soft_step`), particles against obstacles (`cloth::contact`)
//! and against bodies (`cloth_coupling`) — computed in this one place:
//!
//! ```text
//! bounce speed        u_b = BOUNCE_STEPS·|g|·dt     slower approaches do not bounce
//! speculative margin  δ   = u_b·dt                  points this close join as speculative rows
//! ```
//!
//! One step of free fall from rest reaches |g|·dt, so a body resting on a surface (it falls
//! that far within each step and is stopped again) is always below the bounce speed and never
//! jitters; a contact that does not bounce covers at most δ within a step. Without declared
//! gravity both are 0: every approach bounces with the scene's restitution.
//!
//! The world builds it once per step (`World::step`) and hands it down as one value: to the
//! collide phase in [`CollideInput`](super::CollideInput), to the cloths' obstacle passes, to
//! the particle–body passes and to the implicit cloth's tied solve. No pass rebuilds it. It also
//! carries the scene's response, so that the particle passes touch as its method says
//! (`collision::particle`).

use super::{ContactModel, Response};
use nalgebra::Vector3;

/// Contacts approaching slower than this many `|g| dt` do not bounce: one step of free fall
/// gives an approach speed of `|g| dt`, so a resting body is always below the threshold.
/// Points within `BOUNCE_STEPS·|g|·dt²` of a surface are speculative contacts.
pub const BOUNCE_STEPS: f64 = 3.0;

/// The per-step constants of the contact passes (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepContext {
    /// Time step, s, and its inverse.
    pub dt: f64,
    pub inv_dt: f64,
    /// Declared gravity, if any.
    pub gravity: Option<Vector3<f64>>,
    /// u_b = BOUNCE_STEPS·|g|·dt, m/s.
    pub bounce_speed: f64,
    /// δ = u_b·dt, m.
    pub speculative_margin: f64,
    /// Coefficient of restitution e and Coulomb friction μ (0 without a contact model).
    pub restitution: f64,
    pub friction: f64,
    /// The scene's contact method (`impulse` without a contact model): the cloths' particle
    /// passes ask it how a particle touches (`collision::particle`).
    pub response: Response,
}

impl StepContext {
    /// The context of a step of `dt` under `gravity` with the scene's contact model.
    pub fn new(dt: f64, gravity: Option<Vector3<f64>>, model: Option<&ContactModel>) -> Self {
        let bounce_speed = gravity.map_or(0.0, |g| BOUNCE_STEPS * g.norm() * dt);
        StepContext {
            dt,
            inv_dt: 1.0 / dt,
            gravity,
            bounce_speed,
            speculative_margin: bounce_speed * dt,
            restitution: model.map_or(0.0, |m| m.restitution),
            friction: model.map_or(0.0, |m| m.friction),
            response: model.map_or(Response::Impulse, |m| m.response),
        }
    }

    /// The same step with restitution e and friction μ (a pass run without a scene's
    /// contact model: a cloth alone among obstacles).
    pub fn with_contact(self, restitution: f64, friction: f64) -> Self {
        StepContext {
            restitution,
            friction,
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::collision::{Impacts, Response};

    #[test]
    fn the_bounce_speed_is_three_steps_of_free_fall_and_the_margin_one_step_of_it() {
        let model = ContactModel {
            response: Response::Impulse,
            restitution: 0.4,
            friction: 0.5,
            impacts: Impacts::default(),
        };
        let c = StepContext::new(2e-3, Some(Vector3::new(0.0, -9.81, 0.0)), Some(&model));
        assert_eq!(c.bounce_speed, 3.0 * 9.81 * 2e-3);
        assert_eq!(c.speculative_margin, 3.0 * 9.81 * 2e-3 * 2e-3);
        assert_eq!((c.restitution, c.friction, c.inv_dt), (0.4, 0.5, 500.0));
        let weightless = StepContext::new(1e-3, None, None);
        assert_eq!(
            (weightless.bounce_speed, weightless.speculative_margin),
            (0.0, 0.0)
        );
        assert_eq!((weightless.restitution, weightless.friction), (0.0, 0.0));
    }
}
