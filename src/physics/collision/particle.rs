//! How a contact method treats a particle: the verb every method file gives
//! ([`ParticleLaw`], each module's `particle`), which the cloths' contact passes call through
//! [`Response::particle`](super::Response::particle), so that switching the scene's response
//! (scene key, `--response`, the app's `c` key) changes how cloth, rope and trampoline
//! particles touch obstacles and bodies, not only how bodies touch.
//!
//! # Where a particle meets a contact
//!
//! A cloth steps its velocities, then its positions (`cloth::contact`, `cloth_coupling`), and
//! its contacts act at two places in that step:
//!
//! | pass | when | against an obstacle | against a body |
//! |---|---|---|---|
//! | 1 | after the velocity half | [`ParticleLaw::velocity_target_static`]: a normal row [0, ∞) aims at it, Coulomb friction on what it took | [`ParticleLaw::velocity_target_body`]: the rows of `constraints::particle_contact`, solved by [`ParticleLaw::solve_body`] |
//! | 2 | after the positions moved | [`ParticleLaw::push_out`], then [`ParticleLaw::bounce_static`] | [`ParticleLaw::push_out`], [`ParticleLaw::collide_target_body`], [`ParticleLaw::solve_body`] |
//!
//! An `implicit-euler` cloth holds its contacts inside its linear solve when its law says
//! [`ParticleLaw::ties`] (a contact there is a tie: the particle ends on the surface,
//! released when it pulls, sliding out of its cone); a law that cannot be a tie (a momentum
//! flip, a spring whose target depends on the velocity the solve finds) leaves the implicit
//! solve holding the attachments only, and its contacts then act through the two passes
//! above, after the solve, as for an explicit cloth.
//!
//! # The laws
//!
//! | method | a particle's contact |
//! |---|---|
//! | `impulse` | rigid rows (`constraints::particle_contact`): pass 1 stops the particle on the surface, pass 2 projects it out and bounces a fast approach by e, Coulomb friction within μ·Δu_n; tied in the implicit solve |
//! | `seed` | the report's response on a particle: nothing in pass 1; pass 2 pushes it out by d² and reverses and scales its whole velocity (relative to a body's point) by −0.4 |
//! | `soft-step` | a soft normal row (a damped spring of `hertz`, doubled against static things, ζ `damping_ratio`) in pass 1, one backward-Euler step of length dt; pass 2 removes the approach (restitution e on a fast one) without projecting: a resting particle sags g/ω² |
//!
//! A new method's file says its law in a `particle` function next to its `collide`, and the
//! `responses!` line that lists the method dispatches it: nothing else changes.

use super::StepContext;
use crate::physics::constraints::particle_contact::{against_static, coulomb, ParticleContacts};
use nalgebra::Vector3;

/// A particle's contact as pass 1 finds it (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touch {
    /// Separation from the surface, m: ≥ 0 outside. A particle already inside an obstacle
    /// has gap 0 (and its depth below); against a body, gap = −depth.
    pub gap: f64,
    /// How far inside the particle is, m (0 outside).
    pub depth: f64,
    /// The normal velocity the row measures, m/s: v·n against an obstacle, the particle's
    /// own v_p·n against a body (the body is already where it ends the step).
    pub normal_velocity: f64,
    /// The pair's approach at the start of the step, min(0, u₀·n), m/s (against a body: a
    /// particle carrying a body's weight is driven into it within every step, and that is no
    /// impact); against an obstacle, min(0, v·n) now.
    pub approach: f64,
    /// Whether the other side is static (an obstacle or a fixed body).
    pub fixed: bool,
}

/// A particle found inside an obstacle after the positions moved, already moved out by
/// `moved` along `normal` (pass 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The particle's velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Unit normal out of the obstacle.
    pub normal: Vector3<f64>,
    /// How far it was moved out along the normal ([`ParticleLaw::push_out`]), m.
    pub moved: f64,
    /// Its mass, kg.
    pub mass: f64,
    /// The cloth's gravity, if any (the push-out's work against it is paid from a bounce).
    pub gravity: Option<Vector3<f64>>,
}

/// How one contact method treats a particle (module doc). Every method file gives one
/// (`pub fn particle(…) -> impl ParticleLaw`), listed by `responses!`.
pub trait ParticleLaw {
    /// Pass 1 against an obstacle: the normal velocity v·n the particle ends its velocity
    /// half with (the row's target; the row never pulls); None leaves it to pass 2.
    fn velocity_target_static(&self, touch: &Touch, context: &StepContext) -> Option<f64>;

    /// Pass 1 against a body (already where it ends the step): the particle's own normal
    /// velocity v_p·n its row aims at; None leaves it to pass 2.
    fn velocity_target_body(&self, touch: &Touch, context: &StepContext) -> Option<f64>;

    /// Pass 2: how far a particle found `depth` inside is moved out along the normal, m.
    fn push_out(&self, depth: f64) -> f64;

    /// Pass 2 against an obstacle: the particle's velocity after (None: unchanged). By
    /// default the rigid row ([`rigid_bounce`]).
    fn bounce_static(&self, hit: &Hit, context: &StepContext) -> Option<Vector3<f64>> {
        rigid_bounce(hit, context)
    }

    /// Pass 2 against a body: the relative normal velocity the row aims at, for a particle
    /// meeting it at u_n = `normal_velocity`. By default the rigid row's
    /// ([`rigid_collide_target`]).
    fn collide_target_body(&self, normal_velocity: f64, context: &StepContext) -> f64 {
        rigid_collide_target(normal_velocity, context)
    }

    /// Both passes against a body: solves one body's particle rows (the body is solver body
    /// 0), Coulomb friction μ = `friction` where the law has friction. By default the rows'
    /// own solve (normal rows and Coulomb disks).
    fn solve_body(&self, rows: &mut ParticleContacts, friction: f64) {
        rows.solve(friction);
    }

    /// Whether an `implicit-euler` cloth holds these contacts inside its linear solve (as
    /// ties); if not, they act through the two passes after its velocity half.
    fn ties(&self) -> bool;

    /// The law in one line each, as the loop strip shows it: a particle in an obstacle, and
    /// a particle in a body.
    fn formulas(&self) -> [&'static str; 2];
}

/// The rigid pass 2 against an obstacle (`cloth::contact`): the normal row aiming at
/// u_n = 0 (Δu_n = λ = −u_n per unit mass), Coulomb friction within μ Δu_n, and restitution
/// e Δu_n on a fast approach (−u_n above the bounce speed), paid for the push-out's work
/// against gravity so that T_after ≤ T_before − max(0, ΔV):
///
/// ```text
/// v' = v_t' + n min(e Δu_n, √(|v|² − 2ΔV/m − |v_t'|²))
/// ```
///
/// None when the particle moves away already (v·n ≥ 0).
pub fn rigid_bounce(hit: &Hit, context: &StepContext) -> Option<Vector3<f64>> {
    let Hit {
        velocity: v,
        normal: n,
        moved,
        mass: m,
        gravity,
    } = *hit;
    let un = v.dot(&n);
    let stop = against_static(&v, &n, 0.0)?;
    let tangential = coulomb(&v, &n, context.friction, stop);
    // Restitution, paid for the push-out's work against gravity.
    let mut bounce = if -un > context.bounce_speed {
        context.restitution * stop
    } else {
        0.0
    };
    if bounce > 0.0 {
        let lift = gravity.map_or(0.0, |g| -m * g.dot(&(n * moved))).max(0.0);
        let budget = v.norm_squared() - 2.0 * lift / m - tangential.norm_squared();
        bounce = bounce.min(budget.max(0.0).sqrt());
    }
    Some(tangential + n * bounce)
}

/// The rigid pass 2 against a body: aim the relative normal velocity at −e u_n on a fast
/// approach (−u_n above the bounce speed), at 0 otherwise.
pub fn rigid_collide_target(normal_velocity: f64, context: &StepContext) -> f64 {
    let e = if -normal_velocity > context.bounce_speed {
        context.restitution
    } else {
        0.0
    };
    (-e * normal_velocity).max(0.0)
}
