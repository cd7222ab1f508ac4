//! Solver bodies: what every constraint row (`row`) works on while impulses are applied.
//!
//! A **solver body** is a moving thing's velocities and inverse mass properties over one
//! solve: v, ω, L (ω = I⁻¹ L kept in step), 1/M and the world inverse inertia I⁻¹ of the pose
//! the solver works at. Every kind of moving thing is one:
//!
//! | thing | 1/M | I⁻¹ | constructor |
//! |---|---|---|---|
//! | a rigid body | 1/M | R I⁻¹_body Rᵀ | [`SolverBody::new`] |
//! | a cloth particle | 1/m_p (0 when pinned) | 0: no rotational inertia | [`SolverBody::particle`] |
//! | a fixed body, an obstacle (static) | 0 | 0 | [`SolverBody::fixed_thing`] |
//!
//! An impulse j at lever r changes
//!
//! ```text
//! v += j/M,   L += r × j,   ω += I⁻¹ (r × j)
//! ```
//!
//! so a particle (I⁻¹ = 0) takes only `v += j/m_p` whatever its lever, and a static body
//! (1/M = 0, I⁻¹ = 0) takes nothing: it is the world, and a row gives it no end.

use nalgebra::{Matrix3, Vector3};

/// A body's velocities while impulses are applied: v, ω and L (ω = I⁻¹ L kept in step).
#[derive(Debug, Clone, Copy, Default)]
pub struct SolverBody {
    pub v: Vector3<f64>,
    pub omega: Vector3<f64>,
    pub l: Vector3<f64>,
    pub inv_mass: f64,
    /// I⁻¹ in world axes, at the pose the solver works at.
    pub inv_inertia: Matrix3<f64>,
    /// Whether an impulse touched this body.
    pub touched: bool,
}

impl SolverBody {
    /// A body of inverse mass `inv_mass` and world inverse inertia `inv_inertia` moving at
    /// v = `velocity` with angular momentum L = `angular_momentum` (ω = I⁻¹ L).
    pub fn new(
        velocity: Vector3<f64>,
        angular_momentum: Vector3<f64>,
        inv_mass: f64,
        inv_inertia: Matrix3<f64>,
    ) -> SolverBody {
        SolverBody {
            v: velocity,
            omega: inv_inertia * angular_momentum,
            l: angular_momentum,
            inv_mass,
            inv_inertia,
            touched: false,
        }
    }

    /// A particle: a point mass moving at `velocity`, inverse mass `inv_mass` (0 when pinned),
    /// no rotational inertia (I⁻¹ = 0, so ω = 0 and L = 0 stay).
    pub fn particle(velocity: Vector3<f64>, inv_mass: f64) -> SolverBody {
        SolverBody::new(velocity, Vector3::zeros(), inv_mass, Matrix3::zeros())
    }

    /// A static thing (a fixed body, an obstacle): 1/M = 0, I⁻¹ = 0, at rest. No impulse
    /// moves it, and [`Axis::new`](super::Axis::new) gives it no end.
    pub fn fixed_thing() -> SolverBody {
        SolverBody::new(Vector3::zeros(), Vector3::zeros(), 0.0, Matrix3::zeros())
    }

    /// Whether it is fixed (the world: no impulse moves it).
    #[inline]
    pub fn fixed(&self) -> bool {
        self.inv_mass == 0.0
    }

    /// The velocity of the point at lever r from the barycenter, `v + ω × r`.
    #[inline]
    pub fn point_velocity(&self, lever: &Vector3<f64>) -> Vector3<f64> {
        self.v + self.omega.cross(lever)
    }

    /// Applies the impulse j at the point at lever r: `v += j/M`, `L += r × j`,
    /// `ω += I⁻¹(r × j)`. Nothing on a fixed body (the world takes no impulse).
    #[inline]
    pub fn apply_at(&mut self, j: &Vector3<f64>, lever: &Vector3<f64>) {
        if self.fixed() {
            return;
        }
        let rj = lever.cross(j);
        self.v += j * self.inv_mass;
        self.l += rj;
        self.omega += self.inv_inertia * rj;
        self.touched |= *j != Vector3::zeros();
    }

    /// `½ M v·v + ½ ω·L` (0 for a fixed body).
    pub fn kinetic(&self) -> f64 {
        if self.fixed() {
            return 0.0;
        }
        0.5 * self.v.norm_squared() / self.inv_mass + 0.5 * self.omega.dot(&self.l)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_particle_takes_only_j_over_m_and_a_static_thing_nothing() {
        let mut p = SolverBody::particle(Vector3::new(0.0, -1.0, 0.0), 0.5);
        p.apply_at(&Vector3::new(0.2, 0.4, 0.0), &Vector3::new(1.0, 2.0, 3.0));
        // v += j/m with 1/m = 0.5, whatever the lever: no L, no ω.
        assert_eq!(p.v, Vector3::new(0.1, -0.8, 0.0));
        assert_eq!(p.omega, Vector3::zeros());
        assert!((p.kinetic() - 0.5 * (0.01 + 0.64) / 0.5).abs() < 1e-15);
        let mut world = SolverBody::fixed_thing();
        world.apply_at(&Vector3::new(5.0, 5.0, 5.0), &Vector3::x());
        assert!(world.fixed() && !world.touched);
        assert_eq!(
            (world.v, world.l, world.kinetic()),
            (Vector3::zeros(), Vector3::zeros(), 0.0)
        );
    }
}
