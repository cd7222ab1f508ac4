//! `soft-step` on a particle (`collision::particle`): the body law's soft normal row, for a
//! particle that steps once per dt (a cloth does not sub-step).
//!
//! A particle at depth d = −s > 0 moving at u = v·n (against a body: its own v_p·n) takes,
//! in pass 1, the soft row's update from λ = 0 over one step h = dt (`soft_step`'s module
//! doc, "One soft row"), the push-out speed capped at [`MAX_PUSH`]:
//!
//! ```text
//! ω = 2π f,  a₁ = 2ζ + h ω,  a₂ = h ω a₁,  a₃ = 1/(1 + a₂)
//! u' = u + max(0, a₂a₃ (min(ω d/a₁, MAX_PUSH) − u))
//! ```
//!
//! with f = `SoftStep::hertz_at(dt)`, doubled against an obstacle or a fixed body (the body
//! law's static softness). Touching (s = 0) is soft too; apart (s > 0) the row is rigid and speculative: u' = −s/h, it
//! may close its gap within the step and no more (as the body law's). In pass 2 the
//! particle is not projected: its approach is removed by the rigid, unbiased row (the body
//! law's relax), with restitution e on a fast approach and Coulomb friction within μ Δu_n
//! (`particle::rigid_bounce`, `particle::rigid_collide_target`); a fast approach is left by
//! pass 1 to pass 2, to bounce.
//!
//! # The sag it accepts
//!
//! At rest the velocity half gives u = −g h; the row takes it to u' = −a₃ g h + a₂a₃ ω d/a₁,
//! and the particle rests where u' = 0:
//!
//! ```text
//! d = a₃ g h a₁/(a₂ a₃ ω) = g h a₁/(h ω a₁ ω) = g/ω²
//! ```
//!
//! whatever h: against the ground (f doubled) g/(4 ω_c²), ω_c = 2π hertz — the body law's
//! sag of a cube on the ground (`N g/(4 ω_c²)` with N = 1). A test checks it.
//!
//! # The implicit cloth
//!
//! Not a tie: the soft row's target depends on the velocity the linear solve is finding, so
//! an `implicit-euler` cloth's solve holds its attachments only and these passes follow it,
//! as for an explicit cloth.

use super::super::particle::{ParticleLaw, Touch};
use super::super::StepContext;
use super::{Softness, SoftStep, MAX_PUSH};

/// `soft-step`'s particle law (module doc), with the scene's parameters.
#[derive(Debug, Clone, Copy)]
pub struct Soft(pub SoftStep);

/// The particle verb `responses!` dispatches (`collision::particle`).
pub fn particle(params: &SoftStep) -> Soft {
    Soft(*params)
}

impl Soft {
    /// Pass 1's target (module doc): None for a fast approach (left to pass 2, to bounce),
    /// the rigid speculative one outside, the soft row's inside; `fixed`: static softness.
    fn target(&self, touch: &Touch, context: &StepContext, fixed: bool) -> Option<f64> {
        if context.restitution > 0.0 && -touch.approach > context.bounce_speed {
            return None;
        }
        if touch.gap > 0.0 {
            return Some(-touch.gap / context.dt);
        }
        let h = context.dt;
        let hertz = self.0.hertz_at(h) * if fixed { 2.0 } else { 1.0 };
        let soft = Softness::new(hertz, self.0.damping_ratio, h);
        let push = (soft.bias_rate * touch.depth).min(MAX_PUSH);
        let u = touch.normal_velocity;
        Some(u + soft.mass_scale * (push - u))
    }

    /// The depth at which a particle rests on an obstacle under gravity g at step dt (module
    /// doc, "The sag it accepts"), m: g/ω², ω = 2π·2·`hertz_at(dt)`.
    pub fn resting_depth(&self, g: f64, dt: f64) -> f64 {
        let omega = 2.0 * std::f64::consts::PI * 2.0 * self.0.hertz_at(dt);
        g / (omega * omega)
    }
}

impl ParticleLaw for Soft {
    fn velocity_target_static(&self, touch: &Touch, context: &StepContext) -> Option<f64> {
        self.target(touch, context, true)
    }

    fn velocity_target_body(&self, touch: &Touch, context: &StepContext) -> Option<f64> {
        self.target(touch, context, touch.fixed)
    }

    fn push_out(&self, _depth: f64) -> f64 {
        0.0
    }

    fn ties(&self) -> bool {
        false
    }

    fn formulas(&self) -> [&'static str; 2] {
        [
            "particle in an obstacle: soft row u' = u + a₂a₃(ω·d/a₁ − u), not pushed out; v·n ← −e·v·n if fast, else 0 (+ friction)",
            "particle in a body: the same soft row on u = v_p − (v_b + ω×r),  +J on the particle, −J on the body",
        ]
    }
}
