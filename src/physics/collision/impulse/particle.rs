//! `impulse` on a particle (`collision::particle`): the constraint layer's rigid particle
//! rows, as every cloth has always touched.
//!
//! ```text
//! pass 1, obstacle   v·n ← −g/h (arrive on the surface, no further); a fast approach
//!                    (−v·n > u_b) with e > 0 is left to pass 2, to bounce
//! pass 1, body       v_p·n ≥ −g/h + b,  b = −e u₀,n if it touches (g ≤ 0) after a fast
//!                    approach u₀,n (at the start of the step), else 0
//! pass 2             x ← x + depth n;  Δu_n = −u_n;  v_t within μ Δu_n (Coulomb);
//!                    u_n' = e Δu_n on a fast approach (paid for the push-out's lift)
//! implicit cloth     ties inside the linear solve (plastic: the sheet's springs rebound)
//! ```

use super::super::particle::{ParticleLaw, Touch};
use super::super::StepContext;

/// `impulse`'s particle law (module doc).
#[derive(Debug, Clone, Copy, Default)]
pub struct Rigid;

/// The particle verb `responses!` dispatches (`collision::particle`).
pub fn particle() -> Rigid {
    Rigid
}

impl ParticleLaw for Rigid {
    fn velocity_target_static(&self, touch: &Touch, context: &StepContext) -> Option<f64> {
        if context.restitution > 0.0 && -touch.normal_velocity > context.bounce_speed {
            return None;
        }
        Some(-touch.gap / context.dt)
    }

    fn velocity_target_body(&self, touch: &Touch, context: &StepContext) -> Option<f64> {
        // The body is already where it ends the step: the particle must end outside it,
        // and leave at e times a fast approach when it touches.
        let bounce = if touch.gap <= 0.0 && -touch.approach > context.bounce_speed {
            -context.restitution * touch.approach
        } else {
            0.0
        };
        Some(-touch.gap / context.dt + bounce)
    }

    fn push_out(&self, depth: f64) -> f64 {
        depth
    }

    fn ties(&self) -> bool {
        true
    }

    fn formulas(&self) -> [&'static str; 2] {
        [
            "particle in an obstacle: x ← x + depth·n,  v·n ← −(1+e)·v·n if fast, else 0  (+ friction)",
            "particle still in a body: u = v_p − (v_b + ω×r),  j = −(1+e)·uₙ/k,  +J on the particle, −J on the body",
        ]
    }
}
