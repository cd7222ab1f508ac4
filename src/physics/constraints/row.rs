//! Constraint rows: one scalar constraint between two ends of solver bodies, with bounds.
//!
//! An **axis** ([`Axis`]) is one constraint direction between two ends: the unit d on body A
//! at lever r_A and −d on body B (if any) at r_B. Its Jacobian is the row
//! J = [dᵀ, (r_A×d)ᵀ, −dᵀ, (r_B×(−d))ᵀ] over (v_A, ω_A, v_B, ω_B); its rate and effective
//! inverse mass are
//!
//! ```text
//! u = J·v = d·v_A + (r_A×d)·ω_A − d·v_B − (r_B×d)·ω_B          (relative velocity along d)
//! k = J W Jᵀ = 1/M_A + (r_A×d)·I_A⁻¹(r_A×d) + 1/M_B + (r_B×d)·I_B⁻¹(r_B×d)
//! ```
//!
//! (W the block-diagonal inverse mass, diag(1/M_A, I_A⁻¹, 1/M_B, I_B⁻¹)), and an impulse j
//! along it changes `v_A += j d/M_A`, `L_A += j (r_A×d)`, `ω_A += j I_A⁻¹(r_A×d)`, and the
//! opposite on B: equal and opposite at the same point, so the total linear and angular
//! momentum are kept, and u moves by exactly j k. A particle end has no rotational inertia
//! (its I⁻¹ = 0, so its lever drops out of k); a static end (1/M = 0, I⁻¹ = 0) is no end at
//! all. Two axes sharing a body are coupled by
//! `Σ_shared (±d)·(±d')/M + (r×(±d))·I⁻¹(r×(±d'))`: the entries of the contact-space inverse
//! mass A = J W Jᵀ of the direct solves.
//!
//! A **row** ([`Row`]) is an axis with what a solver needs to apply it: bounds [lo, hi] on its
//! accumulated impulse λ and a bias b (the rate it aims at is J·v = −b):
//!
//! | constraint | [lo, hi] | b |
//! |---|---|---|
//! | contact normal | [0, ∞): it pushes, never pulls | −(target rate): −e·u₀ to bounce, −gap/h to arrive |
//! | friction (a pair, [`Friction`]) | within the cone, \|λ_t\| ≤ μ λ_n: the disk ([`within_disc`]) | 0 |
//! | joint | (−∞, ∞) | Baumgarte or position error over h |
//! | limit | one-sided, [0, ∞) or (−∞, 0] | as a contact |
//! | motor | [−F_max h, F_max h] | −(target speed) |
//!
//! One projected Gauss–Seidel update of a row, from the rate J·v at the current velocities:
//!
//! ```text
//! λ' = clamp(λ − (J·v + b)/k, lo, hi),    apply Δλ = λ' − λ along the axis,    λ ← λ'
//! ```
//!
//! After it the row's rate is −b exactly (to round-off) unless a bound held, and the
//! accumulated λ stays within [lo, hi]: a contact never pulls, friction never leaves its
//! cone, a motor never exceeds its force.

use super::SolverBody;
use nalgebra::Vector3;

/// One end of an axis: a body, `r × d` (d signed for this end) and `I⁻¹(r × d)`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct End {
    pub body: usize,
    pub rd: Vector3<f64>,
    pub w: Vector3<f64>,
}

/// A direction d between two ends: +d on body A at lever r_A, −d on body B (if any, and not
/// fixed) at r_B, and its effective inverse mass k (module doc).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
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

    /// The Jacobian alone, J = [dᵀ, g_Aᵀ, −dᵀ, g_Bᵀ] over (v_A, ω_A, v_B, ω_B): d on body
    /// `a` with angular part g_A, −d on body `b` (if any: None is the world) with angular part
    /// g_B. For the rows whose angular part is not a lever's `r × d` (a hinge's or a fixed
    /// joint's angular rows: d = 0; a slider's rail rows, whose B lever moves with A), and for
    /// the direct solves, which form K = J W Jᵀ themselves: the axis is **not weighed**, its
    /// `w` and k are left 0 (an end's `rd` is its g).
    #[inline]
    pub fn jacobian(
        d: Vector3<f64>,
        (a, g_a): (usize, Vector3<f64>),
        b: Option<(usize, Vector3<f64>)>,
    ) -> Axis {
        let end = |body, rd| End {
            body,
            rd,
            w: Vector3::zeros(),
        };
        Axis {
            d,
            a: end(a, g_a),
            b: b.map(|(b, g_b)| end(b, g_b)),
            k: 0.0,
            inv_k: f64::NAN,
        }
    }

    /// The rate J·v at the velocities (v, ω) of A and of B (None: the world, at rest), summed
    /// in the order `d·v_A + g_A·ω_A + (−d)·v_B + g_B·ω_B`.
    #[inline]
    pub fn rate(
        &self,
        (va, wa): (&Vector3<f64>, &Vector3<f64>),
        b: Option<(&Vector3<f64>, &Vector3<f64>)>,
    ) -> f64 {
        let u = self.d.dot(va) + self.a.rd.dot(wa);
        match (&self.b, b) {
            (Some(end), Some((vb, wb))) => u + (-self.d).dot(vb) + end.rd.dot(wb),
            _ => u,
        }
    }

    /// The axis with J scaled by `sign` (−1: the same constraint, pushing the other way).
    #[inline]
    pub fn scaled(&self, sign: f64) -> Axis {
        let end = |e: &End| End {
            rd: e.rd * sign,
            ..*e
        };
        Axis {
            d: self.d * sign,
            a: end(&self.a),
            b: self.b.as_ref().map(end),
            ..*self
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

/// One row (module doc): an axis, the bounds [lo, hi] of its accumulated impulse λ, and its
/// bias b (it aims at the rate J·v = −b), with its position error C and the constraint it
/// belongs to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    pub axis: Axis,
    /// Lower and upper bound of λ, N·s (or N·m·s on an angular axis).
    pub lo: f64,
    pub hi: f64,
    /// b, m/s: the row aims at J·v = −b. A joint's row held inside f(Y) aims at
    /// J·v̇ = −b instead, b = J̇v (its velocity-product term, m/s²).
    pub bias: f64,
    /// The impulse accumulated so far, λ ∈ [lo, hi].
    pub lambda: f64,
    /// C, the position error the row holds at 0 (≥ 0 for a limit's stop; 0 for a contact,
    /// whose gap is in its bias), m or rad.
    pub error: f64,
    /// The constraint it belongs to (a joint's index), [`Row::NO_OWNER`] when none is kept.
    pub owner: usize,
}

impl Row {
    /// The owner of a row that keeps none.
    pub const NO_OWNER: usize = usize::MAX;

    /// A row on `axis` with bounds `[lo, hi]` aiming at the rate J·v = −`bias`, λ = 0.
    pub fn new(axis: Axis, [lo, hi]: [f64; 2], bias: f64) -> Row {
        Row {
            axis,
            lo,
            hi,
            bias,
            lambda: 0.0,
            error: 0.0,
            owner: Row::NO_OWNER,
        }
    }

    /// A joint's equality row of constraint `owner`: λ ∈ (−∞, ∞), position error C =
    /// `error`, velocity-product term J̇v = `bias`.
    pub fn equality(axis: Axis, error: f64, bias: f64, owner: usize) -> Row {
        Row {
            error,
            owner,
            ..Row::new(axis, [f64::NEG_INFINITY, f64::INFINITY], bias)
        }
    }

    /// A limit's stop on the coordinate row `row` (J u = q̇): one-sided, λ ∈ [0, ∞), J scaled
    /// by `sign` (+1 the lower stop, pushing q up; −1 the upper one), C = `gap` ≥ 0 the
    /// distance to the limit.
    pub fn stop(row: &Row, sign: f64, gap: f64) -> Row {
        Row {
            axis: row.axis.scaled(sign),
            lo: 0.0,
            hi: f64::INFINITY,
            error: gap,
            ..*row
        }
    }

    /// A motor on the coordinate row `row`: aims at J u = `speed`, its impulse bounded by
    /// ±`bound` (the largest force or torque times the step).
    pub fn motor(row: &Row, speed: f64, bound: f64) -> Row {
        Row {
            lo: -bound,
            hi: bound,
            bias: -speed,
            ..*row
        }
    }

    /// Its body A, and its body B (None: the world).
    #[inline]
    pub fn a(&self) -> usize {
        self.axis.a.body
    }

    #[inline]
    pub fn b(&self) -> Option<usize> {
        self.axis.b.map(|e| e.body)
    }

    /// J's parts on A: linear d, angular g_A.
    #[inline]
    pub fn lin_a(&self) -> Vector3<f64> {
        self.axis.d
    }

    #[inline]
    pub fn ang_a(&self) -> Vector3<f64> {
        self.axis.a.rd
    }

    /// J's parts on B: linear −d, angular g_B (0 on the world).
    #[inline]
    pub fn lin_b(&self) -> Vector3<f64> {
        -self.axis.d
    }

    #[inline]
    pub fn ang_b(&self) -> Vector3<f64> {
        self.axis.b.map_or(Vector3::zeros(), |e| e.rd)
    }

    /// A contact's normal row: λ ∈ [0, ∞) (it pushes, never pulls), aiming at J·v = `target`.
    pub fn contact(axis: Axis, target: f64) -> Row {
        Row::new(axis, [0.0, f64::INFINITY], -target)
    }

    /// The rate J·v = −b the row aims at.
    #[inline]
    pub fn target(&self) -> f64 {
        -self.bias
    }

    /// The projected update for the rate `rate` = J·v measured with effective inverse mass `k`:
    /// `clamp(λ − (J·v + b)/k, lo, hi)` (module doc, [`Row::clamp`]). λ itself is left as it
    /// was.
    #[inline]
    pub fn update(&self, rate: f64, k: f64) -> f64 {
        self.clamp(self.lambda - (rate + self.bias) / k)
    }

    /// An impulse `lambda` brought within the bounds [lo, hi], computed as `max(lo)` then
    /// `min(hi)` (a NaN gives lo, as `f64::max` does).
    #[inline]
    pub fn clamp(&self, lambda: f64) -> f64 {
        lambda.max(self.lo).min(self.hi)
    }

    /// One projected Gauss–Seidel update over `bodies` (module doc): the rate from the axis,
    /// λ' from [`Row::update`] with the axis's k, Δλ = λ' − λ applied along the axis, λ ← λ'.
    /// Returns Δλ.
    pub fn solve(&mut self, bodies: &mut [SolverBody]) -> f64 {
        let next = self.update(self.axis.velocity(bodies), self.axis.k);
        let change = next - self.lambda;
        self.lambda = next;
        self.axis.apply(change, bodies);
        change
    }
}

/// A contact's friction (module doc's table): two tangent rows t₁ ⟂ t₂ at the contact whose
/// accumulated impulses λ_t = (λ₁, λ₂) share one bound, the disk |λ_t| ≤ r = μ λ_n (Coulomb's
/// cone cut at the normal row's impulse λ_n). The pair's bounds are that disk, not an
/// interval per row, so a solver updates the two together ([`within_disc`] projects onto
/// it); the two axes are kept beside the pair by the solver, which builds them only when
/// something slides.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Friction {
    /// λ₁ and λ₂, the accumulated impulses along t₁ and t₂, N·s.
    pub lambda: [f64; 2],
    /// The disk's radius r = μ λ_n, N·s (0: no friction).
    pub bound: f64,
}

/// Friction's bound (module doc): the accumulated tangential impulse `j_t` scaled back onto
/// the disc |j_t| ≤ `radius` (= μ λ_n) when it left it, its direction kept.
#[inline]
pub fn within_disc(jt: &mut Vector3<f64>, radius: f64) {
    if jt.norm() > radius {
        *jt *= radius / jt.norm();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

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

    #[test]
    fn a_jacobian_axis_gives_j_dot_v_and_a_stop_or_motor_takes_its_bounds() {
        // A hinge-like angular row (0, g | 0, −g) and a point row (e_x, r×e_x | −e_x, g_B):
        // J·v by hand, term by term.
        let (va, wa) = (Vector3::new(1.0, 2.0, 3.0), Vector3::new(-0.5, 0.25, 2.0));
        let (vb, wb) = (Vector3::new(0.5, -1.0, 0.0), Vector3::new(0.0, 1.0, -1.0));
        let g = Vector3::new(0.0, 0.6, 0.8);
        let angular = Axis::jacobian(Vector3::zeros(), (0, g), Some((1, -g)));
        // g·(ω_A − ω_B) = 0.6 × (−0.75) + 0.8 × 3 = 1.95.
        assert!((angular.rate((&va, &wa), Some((&vb, &wb))) - 1.95).abs() < 1e-15);
        let r = Vector3::new(0.0, 0.5, 0.0);
        let point = Axis::jacobian(Vector3::x(), (0, r.cross(&Vector3::x())), None);
        // r×e_x = (0, 0, −0.5): u = v_x − 0.5 ω_z; the world end takes nothing.
        assert_eq!(point.rate((&va, &wa), Some((&vb, &wb))), 1.0 - 0.5 * 2.0);
        assert!(point.b.is_none() && point.k == 0.0);
        // A joint row is free both ways; a stop on the coordinate row is one-sided with J
        // flipped for the upper stop; a motor aims at its speed within ±F dt.
        let row = Row::equality(angular, 0.1, 0.0, 4);
        assert_eq!(
            (row.lo, row.hi, row.error, row.owner),
            (f64::NEG_INFINITY, f64::INFINITY, 0.1, 4)
        );
        let upper = Row::stop(&row, -1.0, 0.02);
        assert_eq!(
            (upper.lo, upper.hi, upper.error),
            (0.0, f64::INFINITY, 0.02)
        );
        let rates = |r: &Row| r.axis.rate((&va, &wa), Some((&vb, &wb)));
        assert_eq!(rates(&upper), -rates(&row));
        assert_eq!(
            (upper.ang_a(), upper.ang_b(), upper.lin_b()),
            (-g, g, Vector3::zeros())
        );
        let motor = Row::motor(&row, 3.0, 0.5);
        assert_eq!((motor.lo, motor.hi, motor.target()), (-0.5, 0.5, 3.0));
        // Axis::new's end and the jacobian's agree on J.
        let bodies = vec![SolverBody::particle(Vector3::zeros(), 1.0); 2];
        let new = Axis::new(Vector3::x(), (0, &r), None, &bodies);
        assert_eq!((new.d, new.a.rd), (point.d, point.a.rd));
    }

    #[test]
    fn a_row_reaches_its_target_within_its_bounds() {
        // A 2 kg block (1/M = 0.5) falling at 1 m/s onto the world: a contact row aiming at
        // u = +0.3 m/s (a bounce) takes λ = (0.3 − (−1))/0.5 = 2.6 N·s and stops there.
        let mut bodies = vec![SolverBody::new(
            Vector3::new(0.0, -1.0, 0.0),
            Vector3::zeros(),
            0.5,
            Matrix3::zeros(),
        )];
        let axis = Axis::new(Vector3::y(), (0, &Vector3::zeros()), None, &bodies);
        let mut row = Row::contact(axis, 0.3);
        assert!((row.solve(&mut bodies) - 2.6).abs() < 1e-15);
        assert!((bodies[0].v.y - 0.3).abs() < 1e-15 && row.target() == 0.3);
        // Solved again, nothing changes: the rate is the target.
        assert!(row.solve(&mut bodies).abs() < 1e-15);
        // A contact never pulls: asked for u = −2 m/s, λ stops at 0 (the 2.6 N·s are undone).
        row.bias = 2.0;
        row.solve(&mut bodies);
        assert_eq!(row.lambda, 0.0);
        assert!((bodies[0].v.y + 1.0).abs() < 1e-15);
        // A motor bounded by ±0.4 N·s cannot reach 5 m/s: it gives its bound.
        let mut motor = Row::new(axis, [-0.4, 0.4], -5.0);
        motor.solve(&mut bodies);
        assert_eq!(motor.lambda, 0.4);
        assert!((bodies[0].v.y - (-1.0 + 0.4 * 0.5)).abs() < 1e-15);
        // Friction's disc: (3, 4) N·s scaled back to radius 1 keeps its direction.
        let mut jt = Vector3::new(3.0, 4.0, 0.0);
        within_disc(&mut jt, 1.0);
        assert!((jt - Vector3::new(0.6, 0.8, 0.0)).norm() < 1e-15);
    }
}
