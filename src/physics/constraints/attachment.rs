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
//! rows' own K. It enters as the body's solver body weighed by f ([`weighed`]: 1/M and I⁻¹
//! times f), so K is the rows' own J W Jᵀ over the weighed table. A static body end (a fixed
//! body, [`SolverBody::fixed_thing`], or a body weighed by f = 0) adds nothing: K_aa = I/m_p.
//!
//! Every entry of K is a coupling of two rows ([`Axis::coupling`]), over the ends the two rows
//! share: the particle's term first, then the body's, `(r_a × e_i)·(f I⁻¹ (r_c × e_j))` — the
//! same numbers as the matrix form above to round-off, each entry's products grouped
//! `a·(I⁻¹ c)`. [`system`] is K of a set of attachments, the explicit cloth's per-body direct
//! solve (`cloth_coupling::attachments`).

use super::{Axis, Row, SolverBody};
use nalgebra::{DMatrix, Matrix3, Matrix3x6, Vector3};

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

    /// G = `[I, −[r]×]` (3 × 6) at its arm ([`point_jacobian`]).
    pub fn point_jacobian(&self) -> Matrix3x6<f64> {
        point_jacobian(&self.arm)
    }

    /// The 3 × 3 block K_ac of this attachment's rows against `other`'s (module doc): entry
    /// (i, j) the coupling of this one's row i with `other`'s row j over `bodies` (the body's
    /// share weighed as the table holds it, [`weighed`]).
    pub fn block(&self, other: &Attachment, bodies: &[SolverBody]) -> Matrix3<f64> {
        let (rows, others) = (self.rows(bodies, 0), other.rows(bodies, 0));
        Matrix3::from_fn(|i, j| rows[i].axis.coupling(&others[j].axis, bodies))
    }
}

/// G = `[I, −[r]×]` (3 × 6): the velocity of a body's point at lever r from the body's
/// (V; ω), `V + ω × r = G (V; ω)`. An attachment's rows have the Jacobian I on the particle end
/// and −G on the body end; a solve whose body unknowns are not a solver body's (a
/// joint-filtered one, the implicit cloth's tied solve) forms its terms from G.
pub fn point_jacobian(arm: &Vector3<f64>) -> Matrix3x6<f64> {
    let mut g = Matrix3x6::zeros();
    g.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&Matrix3::identity());
    g.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(-arm.cross_matrix()));
    g
}

/// A body's share weighed by `factor` (module doc): its solver body with 1/M and I⁻¹ times
/// f. Weighed by 0 it is static, and its attachments' rows have no body end.
pub fn weighed(body: &SolverBody, factor: f64) -> SolverBody {
    SolverBody {
        inv_mass: body.inv_mass * factor,
        inv_inertia: body.inv_inertia * factor,
        ..*body
    }
}

/// K = J W Jᵀ of the rows of `holds` over `bodies`, 3k × 3k (module doc): block (a, c) is
/// [`Attachment::block`]. The lower blocks are the rows' couplings, the upper ones their
/// transposes (K exactly symmetric).
pub fn system(holds: &[Attachment], bodies: &[SolverBody]) -> DMatrix<f64> {
    let rows: Vec<[Row; 3]> = (holds.iter().enumerate())
        .map(|(a, hold)| hold.rows(bodies, a))
        .collect();
    let mut k = DMatrix::zeros(3 * holds.len(), 3 * holds.len());
    for (a, ra) in rows.iter().enumerate() {
        for (c, rc) in rows.iter().enumerate().take(a + 1) {
            for (i, row) in ra.iter().enumerate() {
                for (j, other) in rc.iter().enumerate() {
                    let coupling = row.axis.coupling(&other.axis, bodies);
                    k[(3 * a + i, 3 * c + j)] = coupling;
                    k[(3 * c + j, 3 * a + i)] = coupling;
                }
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rows_couplings_are_the_closed_form_block_and_the_rates_the_relative_velocity() {
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
        // K_ac from the rows' couplings against its closed form, δ_pp I/m_p + f (I/M −
        // [r_a]× I⁻¹ [r_c]×) on the shared body, for f = 1 and f = ½ (the weighed table).
        let closed = |x: &Attachment, y: &Attachment, f: f64| {
            let shared = Matrix3::identity() * 0.5
                - x.arm.cross_matrix() * inv_inertia * y.arm.cross_matrix();
            let particle = if x.particle == y.particle {
                Matrix3::identity() * bodies[x.particle].inv_mass
            } else {
                Matrix3::zeros()
            };
            particle + shared * f
        };
        let mut half = bodies.clone();
        half[0] = weighed(&bodies[0], 0.5);
        assert_eq!(half[0].inv_mass, 0.25);
        for (x, y) in [(a, a), (a, c), (c, a), (c, c)] {
            for (table, f) in [(&bodies, 1.0), (&half, 0.5)] {
                let block = x.block(&y, table);
                assert!((block - closed(&x, &y, f)).norm() < 1e-13, "{block} f {f}");
            }
        }
        // The system is the blocks, exactly symmetric.
        let k = system(&[a, c], &half);
        assert_eq!(k, k.transpose());
        for (p, x) in [a, c].iter().enumerate() {
            for (q, y) in [a, c].iter().enumerate() {
                let block = k.fixed_view::<3, 3>(3 * p, 3 * q).into_owned();
                assert!((block - closed(x, y, 0.5)).norm() < 1e-13);
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
        // A fixed body end adds nothing, and neither does a body weighed by 0.
        let fixed = Attachment { body: 3, ..a };
        assert_eq!(fixed.block(&fixed, &bodies), Matrix3::identity() * 20.0);
        assert!(fixed.rows(&bodies, 0).iter().all(|r| r.axis.b.is_none()));
        let mut still = bodies.clone();
        still[0] = weighed(&bodies[0], 0.0);
        assert_eq!(a.block(&a, &still), Matrix3::identity() * 20.0);
        assert_eq!(a.block(&c, &still), Matrix3::zeros());
        // Solving K J = −u for one attachment stops the particle on the point (f = 1).
        let mut after = bodies.clone();
        let j = a.block(&a, &bodies).try_inverse().unwrap() * (-u);
        after[1].apply_at(&j, &Vector3::zeros());
        after[0].apply_at(&-j, &a.arm);
        assert!(a.rate(&after).norm() < 1e-14);
    }
}
