//! The reference a run is compared with.
//!
//! - **Exact** (one body, no joint, spring, obstacle or drag; gravity allowed): the barycenter
//!   follows `x(t) = x₀ + v₀ t + ½ g t²` and the rotation is the closed-form torque-free top
//!   ([`crate::physics::free_top`]): ω from Jacobi's elliptic functions, the orientation from the
//!   one-quadrature form. Gravity makes no torque about the barycenter, so the two decouple.
//! - **Converged** (joints, springs, drag, several bodies — no contact): the *same model* (the
//!   same [`crate::physics::World`]) stepped by `rk4` at a tenth of the smallest swept step,
//!   and again at half that step. The finer run is the reference; the two runs' difference
//!   (`spread`, measured as the runs' error is) bounds its error. A run whose error is within
//!   [`SPREAD_BAND`] × spread of it is not resolved by the reference; when no run is resolved,
//!   or the spread is above [`UNCONVERGED`], the reference has not converged (a chaotic
//!   motion's error grows until no reference holds) and the study says so. With joints
//!   corrected by projection (the default), the projection leaves |C| up to
//!   [`JOINT_TOLERANCE`] after every step, in the run and in the reference alike: an error
//!   within [`projection_floor`] = 2 × tol / (the smallest jointed body's radius) is not
//!   resolved either, however close the reference.
//! - **Numeric** (contact): `rk4` at a tenth of the smallest swept step, once — an impact moved
//!   by a step changes everything after it, so halving does not converge; contact scenes are
//!   ranked by their rest pose ([`super::measure`]).

use crate::physics::free_top::{rotation_angle_between, FreeBody};
use crate::physics::{BodyView, Effect, Integrator, World};
use crate::scene::Scene;
use nalgebra::{UnitQuaternion, Vector3};

/// A run's error is resolved by a converged reference when it is at least this many times the
/// reference's spread (the reference's own error is below the spread: rk4's at the finer step
/// is ≈ spread / 15).
pub const SPREAD_BAND: f64 = 3.0;

/// A reference whose halving moves it by more than this (the error measure: rad + m / radius)
/// has not converged.
pub const UNCONVERGED: f64 = 1e-3;

/// The joint projection's tolerance, m: it stops when every constraint has |C| < this
/// (`physics::joints::projection`, and the drive's position pass).
pub const JOINT_TOLERANCE: f64 = 1e-12;

/// The error (angle + |x − x_ref| / radius) below which the joint projection's tolerance hides
/// a run's difference from the reference: `2 × JOINT_TOLERANCE / r_min`, r_min the smallest
/// radius among the bodies a joint holds (the run and the reference are each left up to the
/// tolerance off the constraint after every step). 0 without joints or with another
/// correction (Baumgarte and none leave the drift in the motion, as the integrator makes it).
///
/// ```text
/// pendulum, 0.1 m box (radius 0.0866 m):  2 × 1e-12 / 0.0866 = 2.31e-11
/// ```
pub fn projection_floor(scene: &Scene) -> f64 {
    use crate::physics::joints::Correction;
    if scene.links.correction != Correction::Projection {
        return 0.0;
    }
    scene
        .links
        .joints
        .iter()
        .flat_map(|j| std::iter::once(j.a).chain(j.b))
        .filter_map(|i| scene.bodies.get(i))
        .map(|b| 2.0 * JOINT_TOLERANCE / b.body.radius.max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max)
}

/// One body's pose and angular velocity at one sample time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub position: Vector3<f64>,
    pub orientation: UnitQuaternion<f64>,
    /// ω in the body frame, rad/s.
    pub omega_body: Vector3<f64>,
}

/// Every body's pose in `world` now (after a whole step).
pub fn poses(world: &World) -> Vec<Pose> {
    world
        .states()
        .iter()
        .zip(BodyView::all(world))
        .map(|(state, body)| Pose {
            position: state.position,
            orientation: state.orientation.quaternion(),
            omega_body: body.angular_velocity_body(),
        })
        .collect()
}

/// The study's error of one body: `angle(q_ref⁻¹ q) + |x − x_ref| / radius`, with its two
/// terms `(angle rad, distance m)`.
pub fn pose_error(run: &Pose, reference: &Pose, radius: f64) -> (f64, f64, f64) {
    let angle = rotation_angle_between(&reference.orientation, &run.orientation);
    let distance = (run.position - reference.position).norm();
    (
        angle + distance / radius.max(f64::MIN_POSITIVE),
        angle,
        distance,
    )
}

/// How far halving the reference's step moved it: the error measure and the distance (m),
/// maxima over the samples and bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spread {
    /// max of angle + distance / radius between the reference at dt and at dt/2.
    pub error: f64,
    /// max distance, m.
    pub position: f64,
    /// The coarser of the two steps, s (the reference is the finer, dt/2).
    pub coarse_dt: f64,
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
    /// The closed-form straight bounce ([`super::bounce`]): the contact methods' chart of a
    /// bounce scene.
    Bounce(Box<super::bounce::Bounce>),
    /// A finer run of the same model, sampled at the study's sample times (every body).
    Numeric {
        integrator: Integrator,
        dt: f64,
        /// Per sample, per body.
        samples: Vec<Vec<Pose>>,
        /// The halving check (converged references; `None` with contact).
        spread: Option<Spread>,
        /// [`projection_floor`] of the scene.
        projection: f64,
    },
}

/// True if the scene's motion has a closed form: one body, no joint or spring, no obstacle and
/// no effect but gravity.
pub fn has_closed_form(scene: &Scene) -> bool {
    scene.bodies.len() == 1
        && scene.links.is_empty()
        && scene.cloths.is_empty()
        && scene.obstacles.is_empty()
        && scene
            .effects
            .list()
            .iter()
            .all(|e| matches!(e, Effect::Gravity(_)))
}

/// The poses of `scene` stepped by `integrator` at `dt`, at each of `times`.
fn sampled(scene: &Scene, integrator: Integrator, dt: f64, times: &[f64]) -> Vec<Vec<Pose>> {
    let mut world = scene.world_with(integrator, dt);
    times
        .iter()
        .map(|&t| {
            let target = (t / dt).round() as u64;
            while world.step_count() < target {
                super::cancel::check(1);
                world.step();
            }
            poses(&world)
        })
        .collect()
}

impl Reference {
    /// The reference for `scene`, sampled at `times` (numeric references only).
    pub fn for_scene(scene: &Scene, times: &[f64], smallest_dt: f64) -> Reference {
        let initial = &scene.first().initial;
        if has_closed_form(scene) {
            let body = &scene.first().body;
            return Reference::Exact {
                free: Box::new(FreeBody::new(
                    body,
                    initial.orientation.quaternion(),
                    initial.angular_momentum,
                )),
                position: initial.position,
                velocity: initial.linear_momentum * body.inv_mass,
                gravity: scene.effects.gravity().unwrap_or_else(Vector3::zeros),
            };
        }
        let integrator = Integrator::Rk4;
        let coarse_dt = smallest_dt / 10.0;
        let coarse = sampled(scene, integrator, coarse_dt, times);
        let projection = projection_floor(scene);
        if !scene.obstacles.is_empty() {
            return Reference::Numeric {
                integrator,
                dt: coarse_dt,
                samples: coarse,
                spread: None,
                projection,
            };
        }
        let dt = coarse_dt / 2.0;
        let samples = sampled(scene, integrator, dt, times);
        let mut spread = Spread {
            error: 0.0,
            position: 0.0,
            coarse_dt,
        };
        for (a, b) in coarse.iter().zip(&samples) {
            for ((pa, pb), body) in a.iter().zip(b).zip(&scene.bodies) {
                let (e, _, d) = pose_error(pa, pb, body.body.radius);
                // NaN (a diverged reference) counts as not converged.
                spread.error = if e.is_nan() {
                    f64::INFINITY
                } else {
                    spread.error.max(e)
                };
                spread.position = if d.is_nan() {
                    f64::INFINITY
                } else {
                    spread.position.max(d)
                };
            }
        }
        Reference::Numeric {
            integrator,
            dt,
            samples,
            spread: Some(spread),
            projection,
        }
    }

    /// Every body's reference pose at sample `index`, time `t`.
    pub fn at(&mut self, index: usize, t: f64) -> Vec<Pose> {
        match self {
            Reference::Exact {
                free,
                position,
                velocity,
                gravity,
            } => vec![Pose {
                position: *position + *velocity * t + *gravity * (0.5 * t * t),
                orientation: free.orientation(t),
                omega_body: free.omega_body(t),
            }],
            Reference::Bounce(bounce) => vec![Pose {
                position: bounce.position(t),
                orientation: bounce.orientation,
                omega_body: Vector3::zeros(),
            }],
            Reference::Numeric { samples, .. } => samples[index].clone(),
        }
    }

    /// The halving check of a converged reference.
    pub fn spread(&self) -> Option<Spread> {
        match self {
            Reference::Numeric { spread, .. } => *spread,
            Reference::Exact { .. } | Reference::Bounce(_) => None,
        }
    }

    /// The error below which a run is not resolved by the reference (0 for an exact one):
    /// [`SPREAD_BAND`] × its spread, or the joints' [`projection_floor`] if larger.
    pub fn floor(&self) -> f64 {
        let projection = match self {
            Reference::Numeric { projection, .. } => *projection,
            Reference::Exact { .. } | Reference::Bounce(_) => 0.0,
        };
        self.spread()
            .map_or(0.0, |s| SPREAD_BAND * s.error)
            .max(projection)
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
            Reference::Bounce(bounce) => bounce.describe(),
            Reference::Numeric {
                integrator,
                dt,
                spread: None,
                ..
            } => format!(
                "numeric (contact: no closed form, and an impact moved by a step does not \
                 converge): `{}` at dt = {dt:e} s, a tenth of the smallest swept step — not \
                 independent of the integrators under study",
                integrator.name()
            ),
            Reference::Numeric {
                integrator,
                dt,
                spread: Some(s),
                ..
            } => format!(
                "the same model (joints, springs, drag) stepped by `{}` at dt = {dt:e} s; \
                 halving its step from {:e} s moved it by {} (angle + pos/radius; {} m): {}",
                integrator.name(),
                s.coarse_dt,
                super::analysis::format_number(s.error),
                super::analysis::format_number(s.position),
                if s.error <= UNCONVERGED {
                    format!(
                        "errors below {} are not resolved by it{}",
                        super::analysis::format_number(self.floor()),
                        if self.floor() > SPREAD_BAND * s.error {
                            format!(
                                " (the joints' projection leaves |C| up to {JOINT_TOLERANCE:e} m \
                                 after each step, in the run and the reference: 2 × \
                                 {JOINT_TOLERANCE:e} m / the smallest jointed body's radius)"
                            )
                        } else {
                            String::new()
                        }
                    )
                } else {
                    "NOT CONVERGED — no reference holds over this duration, the errors below \
                     measure the reference as much as the run"
                        .to_string()
                }
            ),
        }
    }

    /// "exact", "converged", "not-converged" or "numeric" (contact).
    pub fn kind(&self) -> &'static str {
        match self {
            Reference::Exact { .. } | Reference::Bounce(_) => "exact",
            Reference::Numeric { spread: None, .. } => "numeric",
            Reference::Numeric {
                spread: Some(s), ..
            } if s.error <= UNCONVERGED => "converged",
            Reference::Numeric { .. } => "not-converged",
        }
    }
}
