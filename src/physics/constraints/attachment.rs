//! Attachments: a particle held at a body's point, three equality rows between a particle end
//! and a body end.
//!
//! An attachment holds particle p (a solver body without rotational inertia,
//! [`SolverBody::particle`]) at the point of body b at lever r from b's barycenter. Its rows
//! are the three axes e_x, e_y, e_z from the particle (lever 0) to the body (lever r), each
//! λ ∈ (−∞, ∞) ([`Row::equality`]); together their rates are the relative velocity
//!
//! ```text
//! u = v_p − (V_b + ω_b × r)
//! ```
//!
//! and an impulse J (three λ) gives the particle +J and the body −J at r. Two attachments a, c
//! couple through the ends they share ([`Axis::coupling`]); taken three rows at a time, their
//! block of K = J W Jᵀ is the 3 × 3
//!
//! ```text
//! K_ac = δ_{p_a p_c} I/m_p + f δ_{b_a b_c} (I/M − [r_a]× I⁻¹ [r_c]×)
//! ```
//!
//! ([`Attachment::block`]). f weighs the body's share: the part of its velocity change its
//! position takes over the step (the bodies' integrator's position factor: 1 for symplectic
//! Euler, ½ for rk4 and the splittings, 0 for explicit Euler), so a hold aiming at where the
//! particle *ends* sees the body's point move by f h (ΔV + Δω × r); f = 1 is the velocity
//! rows' own K. A static body end (a fixed body, [`SolverBody::fixed_thing`]) adds nothing:
//! K_aa = I/m_p.
//!
//! The block is formed as 3 × 3 matrices, `(−[r_a]× I⁻¹) [r_c]× + I/M`, not row by row: the
//! nine couplings give the same numbers to round-off (test) but sum each entry's products in
//! another order, and the explicit cloth's per-body direct solve (`cloth_coupling::attachments`)
//! keeps the bits it always had.

use super::{Axis, Row, SolverBody};
use nalgebra::{Matrix3, Matrix3x6, Vector3};

/// A particle held at a body's point: solver body `particle` (a particle) at lever 0, solver
/// body `body` at lever `arm`, both indices into one table of solver bodies (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    pub particle: usize,
    pub body: usize,
    /// The point's lever from the body's barycenter, in world axes, m.
    pub arm: Vector3<f64>,
}

impl Attachment {
    /// Its three equality rows along e_x, e_y, e_z (module doc), each with owner `owner`, no
    /// position error and no bias.
    pub fn rows(&self, bodies: &[SolverBody], owner: usize) -> [Row; 3] {
        let zero = Vector3::zeros();
        [Vector3::x(), Vector3::y(), Vector3::z()].map(|d| {
            let axis = Axis::new(
                d,
                (self.particle, &zero),
                Some((self.body, &self.arm)),
                bodies,
            );
            Row::equality(axis, 0.0, 0.0, owner)
        })
    }

    /// The rates of its rows, u = v_p − (V_b + ω_b × r) (module doc).
    pub fn rate(&self, bodies: &[SolverBody]) -> Vector3<f64> {
        bodies[self.particle].v - bodies[self.body].point_velocity(&self.arm)
    }

    /// G = `[I, −[r]×]` (3 × 6): the body point's velocity from the body's (V; ω),
    /// `V + ω × r = G (V; ω)`. The rows' Jacobian is I on the particle end and −G on the body
    /// end (a solve whose body unknowns are not a solver body's, as a joint-filtered one, forms
    /// its K from G).
    pub fn point_jacobian(&self) -> Matrix3x6<f64> {
        let mut g = Matrix3x6::zeros();
        g.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::identity());
        g.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-self.arm.cross_matrix()));
        g
    }

    /// The 3 × 3 block K_ac of this attachment's rows against `other`'s, the body's share
    /// weighed by `factor` (module doc): the body's part first, `(−[r_a]× I⁻¹ [r_c]× + I/M) f`
    /// on a shared body (±0 on a static one: 1/M = 0, I⁻¹ = 0), then `I/m_p` added on a
    /// shared particle.
    pub fn block(&self, other: &Attachment, bodies: &[SolverBody], factor: f64) -> Matrix3<f64> {
        let mut block = Matrix3::zeros();
        let body = &bodies[self.body];
        if self.body == other.body {
            block = -self.arm.cross_matrix() * body.inv_inertia * other.arm.cross_matrix()
                + Matrix3::identity() * body.inv_mass;
            block *= factor;
        }
        if self.particle == other.particle {
            block += Matrix3::identity() * bodies[self.particle].inv_mass;
        }
        block
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_block_is_the_rows_couplings_and_the_rates_are_the_relative_velocity() {
        // A 2 kg box, tilted, spinning, with two particles (50 g and 30 g) held at two points.
        let rotation = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1).into_inner();
        let inertia_body = Matrix3::from_diagonal(&Vector3::new(0.02, 0.05, 0.04));
        let inv_inertia = rotation * inertia_body.try_inverse().unwrap() * rotation.transpose();
        let bodies = vec![
            SolverBody::new(
                Vector3::new(0.3, -1.0, 0.2),
                Vector3::new(0.01, 0.02, -0.03),
                0.5,
                inv_inertia,
            ),
            SolverBody::particle(Vector3::new(1.0, 0.5, -0.5), 20.0),
            SolverBody::particle(Vector3::new(-0.2, 0.0, 0.4), 1.0 / 0.03),
            SolverBody::fixed_thing(),
        ];
        let a = Attachment {
            particle: 1,
            body: 0,
            arm: Vector3::new(0.2, 0.1, -0.15),
        };
        let c = Attachment {
            particle: 2,
            body: 0,
            arm: Vector3::new(-0.1, 0.25, 0.05),
        };
        // Each entry of K_ac is the coupling of a's row i with c's row j (f = 1).
        for (x, y) in [(a, a), (a, c), (c, a), (c, c)] {
            let (rx, ry) = (x.rows(&bodies, 0), y.rows(&bodies, 1));
            let block = x.block(&y, &bodies, 1.0);
            for i in 0..3 {
                for j in 0..3 {
                    let coupling = rx[i].axis.coupling(&ry[j].axis, &bodies);
                    assert!((block[(i, j)] - coupling).abs() < 1e-13, "{i} {j}");
                }
            }
        }
        // The rows' rates: u = v_p − (V + ω × r), component by component.
        let u = a.rate(&bodies);
        let expected = bodies[1].v - (bodies[0].v + bodies[0].omega.cross(&a.arm));
        for (k, row) in a.rows(&bodies, 0).iter().enumerate() {
            assert!((row.axis.velocity(&bodies) - u[k]).abs() < 1e-15);
            assert!((u[k] - expected[k]).abs() < 1e-15);
            assert_eq!((row.lo, row.hi), (f64::NEG_INFINITY, f64::INFINITY));
        }
        // G (V; ω) is the point's velocity; the rows' body ends are −G, row by row.
        let g = c.point_jacobian();
        let (v, w) = (bodies[0].v, bodies[0].omega);
        let point = g * nalgebra::Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z);
        assert!((point - bodies[0].point_velocity(&c.arm)).norm() < 1e-15);
        for (k, row) in c.rows(&bodies, 0).iter().enumerate() {
            let end = row.axis.b.unwrap();
            let d = -row.axis.d;
            let body_end: Vec<f64> = d.iter().chain(end.rd.iter()).copied().collect();
            let minus_g: Vec<f64> = g.row(k).iter().map(|x| -x).collect();
            assert_eq!(body_end, minus_g);
        }
        // Weighed by f = ½ the body's share halves; a fixed body end adds nothing.
        let half = a.block(&c, &bodies, 0.5);
        assert_eq!(half, a.block(&c, &bodies, 1.0) * 0.5);
        let fixed = Attachment { body: 3, ..a };
        assert_eq!(
            fixed.block(&fixed, &bodies, 1.0),
            Matrix3::identity() * 20.0
        );
        assert!(fixed.rows(&bodies, 0).iter().all(|r| r.axis.b.is_none()));
        // Solving K J = −u for one attachment stops the particle on the point (f = 1).
        let mut after = bodies.clone();
        let j = a.block(&a, &bodies, 1.0).try_inverse().unwrap() * (-u);
        after[1].apply_at(&j, &Vector3::zeros());
        after[0].apply_at(&-j, &a.arm);
        assert!(a.rate(&after).norm() < 1e-14);
    }
}
