//! Particle contacts: a particle (a solver body without rotational inertia) against a body or
//! a static thing, as rows of the layer (`row`): a normal row with bounds [0, ∞) aiming at a
//! target normal velocity, and friction within the cone μ λ_n.
//!
//! # Against a body: [`ParticleContacts`]
//!
//! The body is solver body 0 and each touching particle one after it (1/m_p, I⁻¹ = 0). A
//! contact at the body's point r (from its barycenter), normal n out of the body, is the row
//! along the axis +n on the particle (lever 0) and −n on the body at r:
//!
//! ```text
//! u    = v_p − (v_b + ω × r)                    relative velocity, u_n = u·n
//! k(d) = 1/m_p + 1/M + (r×d)·I⁻¹(r×d)           the axis's k = J W Jᵀ along a unit d
//! λ_n' = clamp(λ_n − (u_n − target)/k(n), 0, ∞)   the normal row (b = −target)
//! t    = u_t/|u_t|,  u_t = u − u_n n
//! j_t' = j_t − t |u_t|/k(t),  then within the disc |j_t'| ≤ μ λ_n'     friction
//! J    = (λ_n' − λ_n) n + (j_t' − j_t)         to the particle, −J to the body at r
//! ```
//!
//! [`ParticleContacts::solve`] sweeps the rows [`SWEEPS`] times (projected Gauss–Seidel with
//! accumulated impulses, forward then backward so that no particle of a grid is favoured by
//! its index), so that a body resting on many particles is held by all of them, not the first
//! one met. An *absolute* row measures the particle's own normal velocity v_p·n with
//! k = 1/m_p (its Jacobian on the particle's end only) while its impulse still acts on both
//! ends: the body is already where it ends the step, so where the particle ends is the
//! particle's business (`cloth_coupling::explicit`, pass 1).
//!
//! # Against a static thing: [`against_static`]
//!
//! A static thing (an obstacle, a fixed body: `SolverBody::fixed_thing`) is the row's B end
//! as in every other row, and [`Axis::new`] gives it none, so a lone particle's row is solved
//! exactly by its one update. Per unit mass (the row scaled by m_p: k = 1, λ a velocity change, the cone
//! μ λ_n scales with it), aiming at v·n = target:
//!
//! ```text
//! λ_n = clamp(0 − (v·n − target)/1, 0, ∞) = max(target − v·n, 0)
//! v'  = v_t' + target n,   v_t = v − (v·n) n,   v_t' = 0 if |v_t| ≤ μ λ_n else v_t (1 − μ λ_n/|v_t|)
//! ```
//!
//! (v + λ_n n written as v_t + target n, its closed form: the numbers the cloth's obstacle
//! contacts have always computed).

use super::{within_disc, Axis, Row, SolverBody};
use nalgebra::{Matrix3, Vector3};

/// Sweeps over a body's particle rows: one sweep lets the first particle met take all of a
/// resting body's weight and tilts it; a few with accumulated impulses share it.
pub const SWEEPS: usize = 4;

/// The lone particle's normal row against a static thing, per unit mass (module doc): the
/// velocity change λ_n ≥ 0 along n that brings v·n to `target`; None when the bound holds
/// (v·n ≥ target: the contact would pull).
#[inline]
pub fn against_static(v: &Vector3<f64>, n: &Vector3<f64>, target: f64) -> Option<f64> {
    // The solver bodies of the row: the particle per unit mass (0) and the static thing (1),
    // which `Axis::new` gives no end, as it gives none to a fixed body or an obstacle in the
    // rigid solvers. The particle's lever is 0 (no rotational inertia), so k = 1/m = 1.
    let ends = [SolverBody::particle(*v, 1.0), SolverBody::fixed_thing()];
    let zero = Vector3::zeros();
    let axis = Axis::new(*n, (0, &zero), Some((1, &zero)), &ends);
    let stop = Row::contact(axis, target).update(axis.velocity(&ends), axis.k);
    (stop > 0.0).then_some(stop)
}

/// The tangential velocity after Coulomb friction with a normal velocity change `stop` ≥ 0
/// (module doc, per unit mass): stopped within the cone μ·stop, else slowed by it.
#[inline]
pub fn coulomb(v: &Vector3<f64>, n: &Vector3<f64>, friction: f64, stop: f64) -> Vector3<f64> {
    let tangential = v - n * v.dot(n);
    let slip = tangential.norm();
    if slip <= friction * stop {
        Vector3::zeros()
    } else {
        tangential * (1.0 - friction * stop / slip)
    }
}

/// One particle's contact with the body: its normal row and accumulated friction impulse.
#[derive(Debug, Clone, Copy)]
struct Touch {
    /// The particle's index in its cloth.
    particle: usize,
    /// Its solver body in [`ParticleContacts`] (≥ 1).
    index: usize,
    /// The normal row: axis d = n out of the body, k = 1/m_p + 1/M + (r×n)·I⁻¹(r×n), bounds
    /// [0, ∞), λ the accumulated normal impulse.
    normal: Row,
    /// Contact point relative to the body's barycenter, m.
    arm: Vector3<f64>,
    /// The row measures v_p·n with k = 1/m_p (module doc), not the relative u·n.
    absolute: bool,
    /// Accumulated tangential impulse, N·s (within the disc μ λ_n).
    tangential_impulse: Vector3<f64>,
}

/// One body's contacts with particles (module doc): the body is solver body 0, each touching
/// particle a solver body after it.
#[derive(Debug, Clone, Default)]
pub struct ParticleContacts {
    bodies: Vec<SolverBody>,
    touches: Vec<Touch>,
}

impl ParticleContacts {
    /// Starts a body's contacts, the body's solver body first (a fixed body is static: no
    /// inverse mass, no inverse inertia).
    pub fn start(&mut self, body: SolverBody) {
        self.touches.clear();
        self.bodies.clear();
        self.bodies.push(body);
    }

    /// Adds particle `particle`'s contact (velocity `velocity`, inverse mass `inv_mass`) at the
    /// body's point `arm` with normal n out of the body, aiming at `target` (relative normal
    /// velocity, or the particle's own when `absolute`).
    pub fn touch(
        &mut self,
        (particle, velocity, inv_mass): (usize, Vector3<f64>, f64),
        normal: &Vector3<f64>,
        arm: Vector3<f64>,
        (target, absolute): (f64, bool),
    ) {
        let index = self.bodies.len();
        self.bodies.push(SolverBody::particle(velocity, inv_mass));
        let axis = Axis::new(
            *normal,
            (index, &Vector3::zeros()),
            Some((0, &arm)),
            &self.bodies,
        );
        self.touches.push(Touch {
            particle,
            index,
            normal: Row::contact(axis, target),
            arm,
            absolute,
            tangential_impulse: Vector3::zeros(),
        });
    }

    /// u = v_p − (v_b + ω × r) of a particle moving at `velocity` at the body's point `arm`
    /// (before it is a contact), m/s.
    pub fn approach(&self, velocity: &Vector3<f64>, arm: &Vector3<f64>) -> Vector3<f64> {
        velocity - self.bodies[0].point_velocity(arm)
    }

    /// u = v_p − (v_b + ω × r) of a contact, m/s.
    fn relative_velocity(&self, t: &Touch) -> Vector3<f64> {
        self.bodies[t.index].v - self.bodies[0].point_velocity(&t.arm)
    }

    /// The number of contacts.
    pub fn len(&self) -> usize {
        self.touches.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.touches.is_empty()
    }

    /// The normal axis's k of the last contact added (NaN if none).
    pub fn last_k(&self) -> f64 {
        self.touches.last().map_or(f64::NAN, |t| t.normal.axis.k)
    }

    /// The body's solver body.
    pub fn body(&self) -> &SolverBody {
        &self.bodies[0]
    }

    /// Each contact's particle (its index in the cloth) and its velocity now.
    pub fn particles(&self) -> impl Iterator<Item = (usize, Vector3<f64>)> + '_ {
        (self.touches.iter()).map(|t| (t.particle, self.bodies[t.index].v))
    }

    /// ΣJ, the impulse the particles took (the body took −ΣJ), N·s: each contact's
    /// λ_n n + j_t, summed in order.
    pub fn total_impulse(&self) -> Vector3<f64> {
        let mut total = Vector3::zeros();
        for t in &self.touches {
            total += t.normal.axis.d * t.normal.lambda + t.tangential_impulse;
        }
        total
    }

    /// Scales each contact's whole relative velocity u = v_p − (v_b + ω × r) by `factor`
    /// (`seed`'s law on a particle), one contact after the other: the impulse J on the
    /// particle (−J on the body at r) solves
    ///
    /// ```text
    /// K J = (factor − 1) u,   K = (1/m_p + 1/M) 𝟙 − [r]× I⁻¹ [r]×
    /// ```
    ///
    /// (K the point's inverse mass matrix, symmetric positive definite for a particle of
    /// finite mass), and is recorded as the contact's normal and tangential impulses.
    pub fn scale_relative(&mut self, factor: f64) {
        for k in 0..self.touches.len() {
            let t = self.touches[k];
            let u = self.relative_velocity(&t);
            let body = &self.bodies[0];
            let cross = t.arm.cross_matrix();
            let w = Matrix3::identity() * (self.bodies[t.index].inv_mass + body.inv_mass)
                - cross * body.inv_inertia * cross;
            let Some(impulse) = w.cholesky().map(|c| c.solve(&(u * (factor - 1.0)))) else {
                continue;
            };
            let n = t.normal.axis.d;
            let along = impulse.dot(&n);
            self.touches[k].normal.lambda += along;
            self.touches[k].tangential_impulse += impulse - n * along;
            self.bodies[t.index].apply_at(&impulse, &Vector3::zeros());
            self.bodies[0].apply_at(&-impulse, &t.arm);
        }
    }

    /// [`SWEEPS`] projected Gauss–Seidel sweeps over the rows (module doc), forward then
    /// backward; friction with coefficient μ = `friction`.
    pub fn solve(&mut self, friction: f64) {
        let count = self.touches.len();
        for pass in 0..SWEEPS {
            for k in 0..count {
                let k = if pass % 2 == 0 { k } else { count - 1 - k };
                self.sweep_one(k, friction);
            }
        }
    }

    /// One contact's update within a sweep: the normal row, then friction in its disc, the
    /// impulse applied to the particle and the opposite to the body.
    #[inline]
    fn sweep_one(&mut self, k: usize, friction: f64) {
        let t = self.touches[k];
        let n = t.normal.axis.d;
        let u = self.relative_velocity(&t);
        // Normal: reach the target velocity, the accumulated impulse never pulls.
        let particle = &self.bodies[t.index];
        let total = if t.absolute {
            t.normal.update(particle.v.dot(&n), particle.inv_mass)
        } else {
            t.normal.update(u.dot(&n), t.normal.axis.k)
        };
        let mut impulse = n * (total - t.normal.lambda);
        self.touches[k].normal.lambda = total;
        // Tangential: stop the slip, within the cone μ λ_n.
        if friction > 0.0 {
            let ut = u - n * u.dot(&n);
            let slip = ut.norm();
            let mut jt = t.tangential_impulse;
            if slip > 0.0 {
                let d = ut / slip;
                let along = Axis::new(
                    d,
                    (t.index, &Vector3::zeros()),
                    Some((0, &t.arm)),
                    &self.bodies,
                );
                jt -= d * (slip / along.k);
            }
            within_disc(&mut jt, friction * total);
            impulse += jt - t.tangential_impulse;
            self.touches[k].tangential_impulse = jt;
        }
        self.bodies[t.index].apply_at(&impulse, &Vector3::zeros());
        self.bodies[0].apply_at(&-impulse, &t.arm);
    }
}

/// A body's solver body from its momenta P, L at the pose of `inv_inertia` (world I⁻¹), with
/// inverse mass `inv_mass`: v = P/M, ω = I⁻¹ L.
pub fn body_of(
    linear_momentum: &Vector3<f64>,
    angular_momentum: Vector3<f64>,
    inv_mass: f64,
    inv_inertia: &Matrix3<f64>,
) -> SolverBody {
    SolverBody::new(
        linear_momentum * inv_mass,
        angular_momentum,
        inv_mass,
        *inv_inertia,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_particle_on_a_resting_body_stops_and_momentum_is_kept() {
        // A 0.5 kg cube (1/M = 2) at rest, a 0.01 kg particle falling on it at 2 m/s at lever
        // (0.1, 0.2, 0): after the sweeps the relative normal velocity is 0 and P + p is kept.
        let inertia = 0.5 * 0.2 * 0.2 / 6.0;
        let mut contacts = ParticleContacts::default();
        contacts.start(body_of(
            &Vector3::zeros(),
            Vector3::zeros(),
            2.0,
            &(Matrix3::identity() / inertia),
        ));
        let arm = Vector3::new(0.1, 0.2, 0.0);
        let v = Vector3::new(0.3, -2.0, 0.0);
        contacts.touch((7, v, 100.0), &Vector3::y(), arm, (0.0, false));
        let mut rubbing = contacts.clone();
        contacts.solve(0.0);
        let (p, vp) = contacts.particles().next().unwrap();
        assert_eq!(p, 7);
        let u = contacts.approach(&vp, &arm);
        assert!(u.y.abs() < 1e-12, "{u}");
        let total = contacts.total_impulse();
        assert!((vp - (v + total * 100.0)).norm() < 1e-12);
        let momentum = 0.01 * vp + contacts.body().v / 2.0;
        assert!((momentum - 0.01 * v).norm() < 1e-15);
        // With friction μ = 0.5, within its cone: |j_t| ≤ μ λ_n.
        rubbing.solve(0.5);
        let total = rubbing.total_impulse();
        assert!(total.y > 0.0 && total.x.abs() <= 0.5 * total.y * (1.0 + 1e-15));
    }

    #[test]
    fn scaling_the_relative_velocity_reaches_the_factor_and_keeps_momentum() {
        // `seed`'s law on a particle touching a moving, spinning cube: u' = −0.4 u at the
        // contact point (all three components: K J = −1.4 u solved exactly), and P + p kept.
        let inertia = 0.5 * 0.2 * 0.2 / 6.0;
        let mut contacts = ParticleContacts::default();
        let p_body = Vector3::new(0.2, 0.0, -0.1);
        contacts.start(body_of(
            &p_body,
            Vector3::new(0.0, 0.003, 0.01),
            2.0,
            &(Matrix3::identity() / inertia),
        ));
        let arm = Vector3::new(0.1, 0.1, 0.05);
        let v = Vector3::new(0.3, -2.0, 0.4);
        let u = contacts.approach(&v, &arm);
        contacts.touch((3, v, 100.0), &Vector3::y(), arm, (0.0, false));
        contacts.scale_relative(-0.4);
        let (_, vp) = contacts.particles().next().unwrap();
        let after = contacts.approach(&vp, &arm);
        assert!(
            (after + 0.4 * u).norm() < 1e-12,
            "{after} against {}",
            -0.4 * u
        );
        let momentum = 0.01 * vp + contacts.body().v / 2.0;
        assert!((momentum - (0.01 * v + p_body)).norm() < 1e-15);
        assert!((contacts.total_impulse() - 0.01 * (vp - v)).norm() < 1e-15);
    }

    #[test]
    fn a_lone_particle_against_a_static_thing_lands_on_its_target() {
        let n = Vector3::y();
        let v = Vector3::new(1.0, -2.0, 0.0);
        // Aiming at v·n = 0: λ = 2 m/s; friction 0.25 takes 0.5 of the 1 m/s slip.
        let stop = against_static(&v, &n, 0.0).unwrap();
        assert_eq!(stop, 2.0);
        assert_eq!(coulomb(&v, &n, 0.25, stop), Vector3::new(0.5, 0.0, 0.0));
        // Moving away already: the bound holds, no contact.
        assert_eq!(against_static(&Vector3::new(0.0, 0.1, 0.0), &n, 0.0), None);
    }

    /// The exact update per unit mass is the body rows' answer with a static body 0: a
    /// 0.01 kg particle under a fixed thing's rows, swept, takes λ_n = m (target − v·n), and
    /// friction the same share of the slip.
    #[test]
    fn the_static_update_is_the_body_rows_against_a_fixed_thing() {
        let n = Vector3::new(0.6, 0.8, 0.0);
        let v = Vector3::new(1.0, -2.0, 0.5);
        let target = 0.05;
        let (m, friction) = (0.01, 0.3);
        let stop = against_static(&v, &n, target).unwrap();
        let after = coulomb(&v, &n, friction, stop) + n * target;
        let mut rows = ParticleContacts::default();
        rows.start(SolverBody::fixed_thing());
        let arm = Vector3::new(0.3, -0.2, 0.1);
        rows.touch((0, v, 1.0 / m), &n, arm, (target, false));
        assert_eq!(rows.last_k(), 1.0 / m);
        rows.solve(friction);
        let (_, swept) = rows.particles().next().unwrap();
        assert!((swept - after).norm() < 1e-14, "{swept} against {after}");
        assert!((rows.total_impulse().dot(&n) - m * stop).abs() < 1e-15);
        assert_eq!(rows.body().v, Vector3::zeros());
    }
}
