//! Particles against bodies, both ways: a cloth particle is a point, a body its convex shape.
//!
//! After the positions moved (collide phase), every free particle inside a body's shape
//! (`geometry::point_shape`: depth > 0, normal n out of the body, contact point c on its
//! surface, r = c − x_body) gets an impulse J, and the body −J at c, so the momentum of
//! particle + body is kept to round-off by every contact:
//!
//! ```text
//! u    = v_p − (v_b + ω × r)                    relative velocity, u_n = u·n < 0: approaching
//! k(d) = 1/m_p + 1/M + d·((I⁻¹(r × d)) × r)     effective inverse mass along a unit d
//! j_n  = −(1 + e) u_n / k(n)                     e = restitution if −u_n > BOUNCE_STEPS·|g|·dt, else 0
//! t    = u_t/|u_t|,  u_t = u − u_n n
//! j_t  = min(|u_t| / k(t), μ j_n)                Coulomb: stop the slip, within the cone
//! J    = j_n n − j_t t
//!
//! With several particles on one body the impulses are found by a few sequential sweeps
//! ([`SWEEPS`]) over its contacts with accumulated impulses (projected Gauss–Seidel: each
//! sweep corrects the impulse found so far, the normal total stays ≥ 0 and aims at the
//! velocity −e·u_n the contact started with, the tangential total stays in the cone μ j_n), so
//! that a body resting on many particles is held by all of them, not the first one met.
//! v_p ← v_p + J/m_p,   P ← P − J,   L ← L − r × J
//! x_p ← x_p + depth n                            the particle is pushed out, not the body
//! ```
//!
//! A point against a rigid body is one contact with a lever arm, so the rule above is the
//! exact two-body impulse (no energy made for e ≤ 1, μ ≥ 0). The push-out moves a light
//! particle, never the body (moving the body would make it jitter on a sheet of hundreds of
//! particles). The world measures the energy of the whole collide phase before and after and
//! books the change in its ledger.

use super::body::Body;
use super::cloth::Cloth;
use super::collision::geometry::{point_shape, Pose};
use super::state::State;
use nalgebra::Vector3;

/// Sweeps over a body's contacts (module doc): one sweep lets the first particle met take
/// all of a resting body's weight and tilts it; a few sweeps with accumulated impulses share it.
pub const SWEEPS: usize = 4;

/// One contact of a particle with a body, while the sweeps run.
struct Touch {
    particle: usize,
    normal: Vector3<f64>,
    /// Contact point relative to the barycenter, m.
    arm: Vector3<f64>,
    /// The normal velocity the sweeps aim at, −e·u_n at the start (0 for a resting contact).
    target: f64,
    /// Accumulated normal impulse (≥ 0) and tangential impulse, N·s.
    normal_impulse: f64,
    tangential_impulse: Vector3<f64>,
}

/// One particle–body contact pass over a cloth: returns the number of contacts.
///
/// `bounce_speed`: approaches slower than this do not bounce.
pub fn collide_bodies(
    cloth: &mut Cloth,
    bodies: &[Body],
    states: &mut [State],
    restitution: f64,
    friction: f64,
    bounce_speed: f64,
) -> usize {
    let mut count = 0;
    let mut touches: Vec<Touch> = Vec::new();
    for (body, state) in bodies.iter().zip(states.iter_mut()) {
        let Some(shape) = body.shape.as_ref() else {
            continue;
        };
        let rotation = state.orientation.matrix();
        let pose = Pose {
            position: state.position,
            rotation,
        };
        // A quick reject: particles farther than the body's radius from its barycenter.
        let reach = body.radius;
        let inv_inertia = rotation * body.inv_inertia_body * rotation.transpose();
        touches.clear();
        for i in 0..cloth.len() {
            if cloth.inv_mass(i) == 0.0 {
                continue;
            }
            let x = cloth.positions[i];
            if (x - state.position).norm_squared() > reach * reach {
                continue;
            }
            let Some(cp) = point_shape(&x, shape, &pose, 0.0) else {
                continue;
            };
            if cp.depth <= 0.0 {
                continue;
            }
            let n = cp.normal;
            cloth.displace(i, &(n * cp.depth));
            let arm = cp.point - state.position;
            let u = relative_velocity(cloth, i, body, state, &inv_inertia, &arm);
            let un = u.dot(&n);
            let e = if -un > bounce_speed { restitution } else { 0.0 };
            touches.push(Touch {
                particle: i,
                normal: n,
                arm,
                target: (-e * un).max(0.0),
                normal_impulse: 0.0,
                tangential_impulse: Vector3::zeros(),
            });
        }
        count += touches.len();
        for sweep in 0..SWEEPS {
            // Forward, then backward: no particle of the grid is favoured by its index.
            let order: Box<dyn Iterator<Item = &mut Touch>> = if sweep % 2 == 0 {
                Box::new(touches.iter_mut())
            } else {
                Box::new(touches.iter_mut().rev())
            };
            for t in order {
                let (i, n, r) = (t.particle, t.normal, t.arm);
                let w_p = cloth.inv_mass(i);
                let k = |d: &Vector3<f64>| {
                    w_p + body.inv_mass + d.dot(&(inv_inertia * r.cross(d)).cross(&r))
                };
                let u = relative_velocity(cloth, i, body, state, &inv_inertia, &r);
                // Normal: reach the target velocity, the accumulated impulse never pulls.
                let total = (t.normal_impulse + (t.target - u.dot(&n)) / k(&n)).max(0.0);
                let mut impulse = n * (total - t.normal_impulse);
                t.normal_impulse = total;
                // Tangential: stop the slip, within the cone μ j_n.
                let ut = u - n * u.dot(&n);
                let slip = ut.norm();
                if friction > 0.0 {
                    let mut jt = t.tangential_impulse;
                    if slip > 0.0 {
                        let d = ut / slip;
                        jt -= d * (slip / k(&d));
                    }
                    let limit = friction * t.normal_impulse;
                    if jt.norm() > limit {
                        jt *= limit / jt.norm();
                    }
                    impulse += jt - t.tangential_impulse;
                    t.tangential_impulse = jt;
                }
                cloth.apply_impulse(i, &impulse);
                state.linear_momentum -= impulse;
                state.angular_momentum -= r.cross(&impulse);
            }
        }
    }
    count
}

/// u = v_p − (v_b + ω × r), m/s.
fn relative_velocity(
    cloth: &Cloth,
    i: usize,
    body: &Body,
    state: &State,
    inv_inertia: &nalgebra::Matrix3<f64>,
    arm: &Vector3<f64>,
) -> Vector3<f64> {
    let omega = inv_inertia * state.angular_momentum;
    cloth.particle_velocity(i) - (state.linear_momentum * body.inv_mass + omega.cross(arm))
}
