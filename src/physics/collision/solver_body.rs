//! Solver bodies and constraint axes: what every contact solver (`impulse`, `soft_step`)
//! works on while it applies impulses.
//!
//! A **solver body** is a body's velocities and inverse mass properties over one collide
//! phase: v, ω, L (ω = I⁻¹ L kept in step), 1/M and the world inverse inertia I⁻¹ of the
//! pose the solver works at. A fixed body (1/M = 0, I⁻¹ = 0) is the world: no axis has an end
//! on it, so it takes no impulse. A cloth's particle is a solver body without rotational
//! inertia (I⁻¹ = 0, every lever 0): `cloth_coupling`'s contact sweeps between particles and
//! bodies run on the same solver bodies and axes as the bodies' contacts.
//!
//! An **axis** is one scalar constraint direction between two ends: the unit d on body A at
//! lever r_A and −d on body B (if any) at r_B. Its rate and effective inverse mass are
//!
//! ```text
//! u = d·v_A + (r_A×d)·ω_A − d·v_B − (r_B×d)·ω_B          (relative velocity along d)
//! k = 1/M_A + (r_A×d)·I_A⁻¹(r_A×d) + 1/M_B + (r_B×d)·I_B⁻¹(r_B×d)
//! ```
//!
//! and an impulse j along it changes `v_A += j d/M_A`, `L_A += j (r_A×d)`,
//! `ω_A += j I_A⁻¹(r_A×d)`, and the opposite on B: equal and opposite at the same point, so
//! the total linear and angular momentum are kept. Two axes sharing a body are coupled by
//! `Σ_shared (±d)·(±d')/M + (r×(±d))·I⁻¹(r×(±d'))`: the entries of the contact-space inverse
//! mass A of the direct solves.

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

/// One end of an axis: a body, `r × d` (d signed for this end) and `I⁻¹(r × d)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct End {
    pub body: usize,
    pub rd: Vector3<f64>,
    pub w: Vector3<f64>,
}

/// A direction d between two ends: +d on body A at lever r_A, −d on body B (if any, and not
/// fixed) at r_B, and its effective inverse mass k (module doc).
#[derive(Debug, Clone, Copy, Default)]
pub struct Axis {
    pub d: Vector3<f64>,
    pub a: End,
    pub b: Option<End>,
    pub k: f64,
    /// 1/k: NaN until [`Axis::with_inverse`] (a direct solve never divides by k).
    pub inv_k: f64,
}

impl Axis {
    /// The axis d from body `a` at lever `lever_a` to body `b` (if any) at its lever, over
    /// `bodies` (indexed as `a` and `b` are). A fixed B gets no end.
    #[inline]
    pub fn new(
        d: Vector3<f64>,
        (a, lever_a): (usize, &Vector3<f64>),
        b: Option<(usize, &Vector3<f64>)>,
        bodies: &[SolverBody],
    ) -> Axis {
        let end = |body: usize, lever: &Vector3<f64>, d: Vector3<f64>| {
            let s = &bodies[body];
            let rd = lever.cross(&d);
            let w = s.inv_inertia * rd;
            (End { body, rd, w }, s.inv_mass + rd.dot(&w))
        };
        let (a, mut k) = end(a, lever_a, d);
        let b = b.filter(|(b, _)| !bodies[*b].fixed()).map(|(b, lever_b)| {
            let (end, kb) = end(b, lever_b, -d);
            k += kb;
            end
        });
        Axis {
            d,
            a,
            b,
            k,
            inv_k: f64::NAN,
        }
    }

    /// Fills in 1/k (0 if k is: an axis between two fixed ends takes no impulse).
    pub fn with_inverse(&mut self) {
        self.inv_k = if self.k > 0.0 { 1.0 / self.k } else { 0.0 };
    }

    /// The relative velocity along d, A relative to B:
    /// `d·v_A + (r_A×d)·ω_A − d·v_B + (r_B×(−d))·ω_B`.
    #[inline]
    pub fn velocity(&self, bodies: &[SolverBody]) -> f64 {
        let a = &bodies[self.a.body];
        let mut u = self.d.dot(&a.v) + self.a.rd.dot(&a.omega);
        if let Some(b) = &self.b {
            let s = &bodies[b.body];
            u += -self.d.dot(&s.v) + b.rd.dot(&s.omega);
        }
        u
    }

    /// Applies the impulse j d: +j d to A at r_A, −j d to B at r_B.
    #[inline]
    pub fn apply(&self, j: f64, bodies: &mut [SolverBody]) {
        let touched = j != 0.0;
        let a = &mut bodies[self.a.body];
        a.v += self.d * (j * a.inv_mass);
        a.l += self.a.rd * j;
        a.omega += self.a.w * j;
        a.touched |= touched;
        if let Some(b) = &self.b {
            let s = &mut bodies[b.body];
            s.v += self.d * (-j * s.inv_mass);
            s.l += b.rd * j;
            s.omega += b.w * j;
            s.touched |= touched;
        }
    }

    /// The coupling of two axes in the contact-space inverse mass A:
    /// `Σ over the bodies they share (±d)·(±d')/M + (r×(±d))·I⁻¹(r×(±d'))`.
    ///
    /// The pairs of ends are taken in the order (A, A'), (A, B'), (B, A'), (B, B'), each term
    /// added to a sum that starts at +0 (the order [`Axis::ends`] gives them).
    #[inline]
    pub fn coupling(&self, other: &Axis, bodies: &[SolverBody]) -> f64 {
        let mut sum = 0.0;
        let dot = self.d.dot(&other.d);
        let mut add = |e: &End, se: f64, f: &End, sf: f64| {
            if e.body == f.body {
                sum += se * sf * dot * bodies[e.body].inv_mass + e.rd.dot(&f.w);
            }
        };
        add(&self.a, 1.0, &other.a, 1.0);
        if let Some(fb) = &other.b {
            add(&self.a, 1.0, fb, -1.0);
        }
        if let Some(eb) = &self.b {
            add(eb, -1.0, &other.a, 1.0);
            if let Some(fb) = &other.b {
                add(eb, -1.0, fb, -1.0);
            }
        }
        sum
    }

    /// The bodies the axis acts on.
    pub fn bodies(&self) -> [Option<usize>; 2] {
        [Some(self.a.body), self.b.map(|b| b.body)]
    }

    /// Whether the two axes act on a common body (else their coupling is 0).
    #[inline]
    pub fn shares_a_body(&self, other: &Axis) -> bool {
        let acts_on = |axis: &Axis, body: usize| {
            axis.a.body == body || axis.b.as_ref().is_some_and(|b| b.body == body)
        };
        acts_on(other, self.a.body) || self.b.as_ref().is_some_and(|b| acts_on(other, b.body))
    }

    /// The ends with the sign of d at each.
    pub fn ends(&self) -> impl Iterator<Item = (&End, f64)> {
        std::iter::once((&self.a, 1.0)).chain(self.b.as_ref().map(|b| (b, -1.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(v: Vector3<f64>, l: Vector3<f64>) -> SolverBody {
        // A 2 kg cube of side 0.4 m: I = M s²/6 = 0.053̄ kg·m² about every axis.
        let inertia = 2.0 * 0.4 * 0.4 / 6.0;
        SolverBody::new(v, l, 0.5, Matrix3::identity() / inertia)
    }

    #[test]
    fn an_impulse_keeps_linear_and_angular_momentum_and_moves_the_rate_by_j_k() {
        let mut bodies = vec![
            cube(Vector3::new(0.1, -2.0, 0.3), Vector3::new(0.2, 0.0, -0.1)),
            cube(Vector3::new(0.0, 0.5, 0.0), Vector3::new(0.0, 0.3, 0.0)),
        ];
        let (xa, xb) = (Vector3::new(0.0, 0.4, 0.0), Vector3::zeros());
        let point = Vector3::new(0.05, 0.2, -0.1);
        let (ra, rb) = (point - xa, point - xb);
        let d = Vector3::new(0.0, 1.0, 0.0);
        let axis = Axis::new(d, (0, &ra), Some((1, &rb)), &bodies);
        // k by hand: 1/M_A + |r_A×d|²/I + 1/M_B + |r_B×d|²/I (isotropic inertia).
        let inertia = 2.0 * 0.4 * 0.4 / 6.0;
        let k = 0.5
            + ra.cross(&d).norm_squared() / inertia
            + 0.5
            + rb.cross(&d).norm_squared() / inertia;
        assert!((axis.k - k).abs() < 1e-14, "{} {k}", axis.k);
        let momentum = |b: &[SolverBody]| {
            let p: Vector3<f64> = b.iter().map(|s| s.v / s.inv_mass).sum();
            let l = b[0].l + xa.cross(&(b[0].v / 0.5)) + b[1].l + xb.cross(&(b[1].v / 0.5));
            (p, l)
        };
        let (p0, l0) = momentum(&bodies);
        let u0 = axis.velocity(&bodies);
        axis.apply(0.7, &mut bodies);
        let (p1, l1) = momentum(&bodies);
        assert!((p1 - p0).norm() < 1e-14 && (l1 - l0).norm() < 1e-14);
        assert!((axis.velocity(&bodies) - (u0 + 0.7 * k)).abs() < 1e-13);
        assert!(bodies[0].touched && bodies[1].touched);
        // An axis's coupling with itself is its k.
        assert!((axis.coupling(&axis, &bodies) - axis.k).abs() < 1e-14);
    }

    #[test]
    fn a_fixed_body_is_the_world() {
        let mut bodies = vec![
            cube(Vector3::new(0.0, -1.0, 0.0), Vector3::zeros()),
            SolverBody::new(Vector3::zeros(), Vector3::zeros(), 0.0, Matrix3::zeros()),
        ];
        let r = Vector3::new(0.2, -0.2, 0.2);
        let mut axis = Axis::new(Vector3::y(), (0, &r), Some((1, &r)), &bodies);
        assert!(axis.b.is_none());
        axis.with_inverse();
        // One body against the world: j = −u/k stops the point.
        let j = -axis.velocity(&bodies) * axis.inv_k;
        axis.apply(j, &mut bodies);
        assert!(axis.velocity(&bodies).abs() < 1e-15);
        assert_eq!(bodies[1].v, Vector3::zeros());
        assert_eq!(bodies[1].kinetic(), 0.0);
    }
}
