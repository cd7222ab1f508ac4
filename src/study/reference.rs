//! The independent reference a run is compared with.
//!
//! - **Exact** (no obstacles, no drag; gravity allowed): the barycenter follows
//!   `x(t) = x₀ + v₀ t + ½ g t²` and the rotation is the closed-form torque-free top
//!   ([`crate::physics::free_top`]): ω from Jacobi's elliptic functions, the orientation from the
//!   one-quadrature form. Gravity makes no torque about the barycenter, so the two decouple.
//! - **Numeric** (anything else: contact, drag): `rk4` at a tenth of the smallest swept step.
//!   Not independent of the integrators under study — the output says so.

use crate::physics::free_top::FreeBody;
use crate::physics::{Effect, Integrator};
use crate::scene::Scene;
use nalgebra::{UnitQuaternion, Vector3};

/// The reference pose and angular velocity at one sample time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub position: Vector3<f64>,
    pub orientation: UnitQuaternion<f64>,
    /// ω in the body frame, rad/s.
    pub omega_body: Vector3<f64>,
}

/// Which reference a scene gets.
#[derive(Debug, Clone)]
pub enum Reference {
    /// Closed forms (projectile + free top).
    Exact {
        free: Box<FreeBody>,
        position: Vector3<f64>,
        velocity: Vector3<f64>,
        gravity: Vector3<f64>,
    },
    /// A finer run of a chosen integrator, sampled at the study's sample times.
    Numeric {
        integrator: Integrator,
        dt: f64,
        samples: Vec<Pose>,
    },
}

/// True if the scene's motion has a closed form: no obstacles and no effect but gravity.
pub fn has_closed_form(scene: &Scene) -> bool {
    scene.obstacles.is_empty()
        && scene
            .effects
            .list()
            .iter()
            .all(|e| matches!(e, Effect::Gravity(_)))
}

impl Reference {
    /// The reference for `scene`, sampled at `times` (numeric references only).
    pub fn for_scene(scene: &Scene, times: &[f64], smallest_dt: f64) -> Reference {
        let initial = &scene.first().initial;
        if has_closed_form(scene) {
            let body = &scene.first().body;
            Reference::Exact {
                free: Box::new(FreeBody::new(
                    body,
                    initial.orientation.quaternion(),
                    initial.angular_momentum,
                )),
                position: initial.position,
                velocity: initial.linear_momentum * body.inv_mass,
                gravity: scene.effects.gravity().unwrap_or_else(Vector3::zeros),
            }
        } else {
            let integrator = Integrator::Rk4;
            let dt = smallest_dt / 10.0;
            let mut world = scene.world_with(integrator, dt);
            let samples = times
                .iter()
                .map(|&t| {
                    let target = (t / dt).round() as u64;
                    while world.step_count() < target {
                        world.step();
                    }
                    let s = world.snapshot();
                    Pose {
                        position: s.position,
                        orientation: s.quaternion,
                        omega_body: s.angular_velocity_body,
                    }
                })
                .collect();
            Reference::Numeric {
                integrator,
                dt,
                samples,
            }
        }
    }

    /// The reference at sample `index`, time `t`.
    pub fn at(&mut self, index: usize, t: f64) -> Pose {
        match self {
            Reference::Exact {
                free,
                position,
                velocity,
                gravity,
            } => Pose {
                position: *position + *velocity * t + *gravity * (0.5 * t * t),
                orientation: free.orientation(t),
                omega_body: free.omega_body(t),
            },
            Reference::Numeric { samples, .. } => samples[index],
        }
    }

    /// One line saying what the reference is.
    pub fn describe(&self) -> String {
        match self {
            Reference::Exact { free, gravity, .. } => {
                let rotation = match free.top().flip_half_period() {
                    Some(p) if p.is_finite() => format!(
                        "closed-form free top (Jacobi sn, cn, dn; 1 − m = {:.3e}, flip \
                         half-period 2K/λ = {:.6} s)",
                        free.top().complement().unwrap_or(f64::NAN),
                        p
                    ),
                    _ => "closed-form free top (symmetric or steady spin)".to_string(),
                };
                let translation = if gravity.norm() > 0.0 {
                    "exact projectile x₀ + v₀t + ½gt²"
                } else {
                    "exact uniform motion x₀ + v₀t"
                };
                format!("exact: {translation}; {rotation}")
            }
            Reference::Numeric { integrator, dt, .. } => format!(
                "numeric (no closed form: contact or drag): `{}` at dt = {dt:e} s, a tenth of \
                 the smallest swept step — not independent of the integrators under study",
                integrator.name()
            ),
        }
    }

    /// "exact" or "numeric".
    pub fn kind(&self) -> &'static str {
        match self {
            Reference::Exact { .. } => "exact",
            Reference::Numeric { .. } => "numeric",
        }
    }
}
