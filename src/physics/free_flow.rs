//! The exact torque-free flow over one step: from any body angular momentum, over any time h,
//! the new angular momentum and the rotation the body turns by — to round-off, in closed form.
//!
//! This is the drift of the `exact-splitting` integrators (Celledoni, Fassò, Säfström & Zanna,
//! SIAM J. Sci. Comput. 30, 2008). Principal frame, moments I₁ ≤ I₂ ≤ I₃, angular momentum Π,
//! ω = Π / I, 2E = Π·ω, M = |Π|. The differences, each a sum without cancellation:
//!
//! ```text
//! D₁ = M² − 2EI₁ = I₂(I₂−I₁)ω₂² + I₃(I₃−I₁)ω₃²   ≥ 0
//! D₃ = 2EI₃ − M² = I₁(I₃−I₁)ω₁² + I₂(I₃−I₂)ω₂²   ≥ 0
//! D₂ = M² − 2EI₂ = I₁(I₁−I₂)ω₁² + I₃(I₃−I₂)ω₃²   (its sign picks the side of the separatrix)
//! ```
//!
//! **Angular momentum** (Landau & Lifshitz §37, as in [`super::free_top`]). With a the "cn" axis
//! and e the "dn" axis — (a, e) = (1, 3) when D₂ ≥ 0 (L circles the major axis), (3, 1) when
//! D₂ < 0 (the minor axis) — and s = sign ωₑ:
//!
//! ```text
//! ω_a = A_a cn u,   ω₂ = s A₂ sn u,   ωₑ = s Aₑ dn u,   u = u₀ + λ t
//! D₂ ≥ 0: A₁² = D₃/(I₁(I₃−I₁))  A₂² = D₃/(I₂(I₃−I₂))  A₃² = D₁/(I₃(I₃−I₁))
//!         λ² = (I₃−I₂)D₁/(I₁I₂I₃)   m = (I₂−I₁)D₃/((I₃−I₂)D₁)   1−m = (I₃−I₁)D₂/((I₃−I₂)D₁)
//! D₂ < 0: A₃² = D₁/(I₃(I₃−I₁))  A₂² = D₁/(I₂(I₂−I₁))  A₁² = D₃/(I₁(I₃−I₁))
//!         λ² = (I₂−I₁)D₃/(I₁I₂I₃)   m = (I₃−I₂)D₁/((I₂−I₁)D₃)   1−m = (I₃−I₁)(−D₂)/((I₂−I₁)D₃)
//! u₀ = F(φ₀ | m),  φ₀ = atan2(sn u₀, cn u₀) read off ω;   then sn, cn, dn and φ₁ = am u₁ at u₁ = u₀ + λh.
//! ```
//!
//! The limits need no special case: two equal moments make m = 0 (sn, cn = sin, cos: the
//! symmetric top's precession), the separatrix makes m = 1 (tanh, sech). Only ω ∥ L (a sphere, or
//! a spin about a principal axis, where the amplitudes vanish) is its own, trivial, case: the
//! body turns about the fixed ω by |ω| h.
//!
//! **Attitude.** L is fixed in the world, so over the step the principal frame turns by
//! `Q = T(n₀) · Rot(ê, ψ) · T(n₁)⁻¹` (then `R ← R Q`), where n = Π/M, ê = s eₑ (the axis L circles,
//! on L's side: ê·n = Lₑ/M > 0), T(n) the smallest rotation taking ê to n (quaternion
//! `(1 + ê·n, ê × n)` normalised: never near its singularity, since ê·n > 0), and
//!
//! ```text
//! ψ̇ = (2E + M ωₑ) / (M + Lₑ)  =  M/Iₑ + (2EIₑ − M²) / (Iₑ (M + Lₑ))          (Lₑ = Iₑ ωₑ > 0)
//! ```
//!
//! (the body's spin about L, 2E/M, plus the twist of the frame T along the path of n;
//! a steady spin about eₑ gives ψ̇ = |ω|, a symmetric top the precession M/I₁ minus the body
//! rate). With `Lₑ = c dn u`, `c = Iₑ Aₑ`, `a = M² − c² = I_a² A_a²`, `b = c² m`,
//! `1/(M + Lₑ) = (M − c dn u)/(a + b sn²u)` and `dn u du = dφ`:
//!
//! ```text
//! ∫₀ʰ dt/(M + Lₑ) = (1/λ) [ (M/a) ∫ du/(1 + N sn²u)  −  c ∫ dφ/(a + b sin²φ) ],   N = b/a
//! ∫_{u₀}^{u₁} du/(1 + N sn²u) = λh − (N/3) [H(φ₁) − H(φ₀)]               (Π(−N; φ | m) − F(φ | m))
//! H(jπ + r) = 2j R_J(0, 1−m, 1, 1+N) + sin³r R_J(cos²r, cos²r + (1−m) sin²r, 1, 1 + N sin²r),  |r| ≤ π/2
//! ∫ dφ/(a + b sin²φ) = Θ(φ)/√(a(a+b)),   Θ(jπ + r) = jπ + atan2(√(a+b) sin r, √a cos r)
//! ```
//!
//! (Carlson's R_J: [`super::free_top::carlson_rj`]; the complete integral only when the step
//! crosses φ = π/2 + jπ). Near a steady spin about eₑ (a → 0) the two integrals grow like 1/a
//! but 2EIₑ − M² shrinks like a: the angle stays accurate to round-off in absolute terms.
//!
//! Cost: one `F` (R_F), one `sn, cn, dn` (Landen descent), two or three R_J, no quadrature.

use super::free_top::{carlson_rj, elliptic_f_complement, jacobi_amplitude};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::f64::consts::PI;

/// The exact torque-free motion over `h` (s, any sign) of a body with principal moments
/// `moments` (I₁ ≤ I₂ ≤ I₃, kg·m²) and angular momentum `momentum` in its principal frame
/// (kg·m²/s): the angular momentum in the principal frame after `h`, and the rotation `Q` the
/// principal frame turns by (principal → world becomes `before · Q`).
pub fn free_flow(
    moments: &Vector3<f64>,
    momentum: &Vector3<f64>,
    h: f64,
) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let omega = momentum.component_div(moments);
    let m2 = momentum.norm_squared();
    let big_m = m2.sqrt();
    let (i1, i2, i3) = (moments.x, moments.y, moments.z);
    let (w1, w2, w3) = (omega.x, omega.y, omega.z);
    let d1 = i2 * (i2 - i1) * w2 * w2 + i3 * (i3 - i1) * w3 * w3;
    let d3 = i1 * (i3 - i1) * w1 * w1 + i2 * (i3 - i2) * w2 * w2;
    let d2 = i1 * (i1 - i2) * w1 * w1 + i3 * (i3 - i2) * w3 * w3;
    // ω ∥ L: a spin about a principal axis or a spherical top (the amplitudes of the elliptic
    // motion vanish, so it is not the limit of the formulas below but their exact solution).
    let steady = omega.cross(momentum).norm() <= 1e-15 * omega.norm() * big_m;
    if big_m == 0.0 || steady {
        return (*momentum, UnitQuaternion::from_scaled_axis(omega * h));
    }
    let major = d2 >= 0.0;
    // (cn axis, dn axis), squared amplitudes, λ, m, 1 − m, 2EIₑ − M².
    let (a_axis, e_axis, amplitude2, lambda2, m, mc, twice_e_ie_minus_m2) = if major {
        let denominator = (i3 - i2) * d1;
        (
            0,
            2,
            Vector3::new(
                d3 / (i1 * (i3 - i1)),
                d3 / (i2 * (i3 - i2)),
                d1 / (i3 * (i3 - i1)),
            ),
            denominator / (i1 * i2 * i3),
            (i2 - i1) * d3 / denominator,
            (i3 - i1) * d2 / denominator,
            d3,
        )
    } else {
        let denominator = (i2 - i1) * d3;
        (
            2,
            0,
            Vector3::new(
                d3 / (i1 * (i3 - i1)),
                d1 / (i2 * (i2 - i1)),
                d1 / (i3 * (i3 - i1)),
            ),
            denominator / (i1 * i2 * i3),
            (i3 - i2) * d1 / denominator,
            -(i3 - i1) * d2 / denominator,
            -d1,
        )
    };
    let amplitude = amplitude2.map(f64::sqrt);
    let lambda = lambda2.sqrt();
    let sign = if omega[e_axis] < 0.0 { -1.0 } else { 1.0 };
    // Where the motion is now: φ₀ = am u₀, and u₀.
    let sn0 = sign * w2 / amplitude.y;
    let cn0 = omega[a_axis] / amplitude[a_axis];
    let phi0 = sn0.atan2(cn0);
    let u0 = elliptic_f_complement(phi0, mc);
    let (sn1, cn1, dn1, phi1) = jacobi_amplitude(u0 + lambda * h, m, mc);
    let mut omega1 = Vector3::zeros();
    omega1[a_axis] = amplitude[a_axis] * cn1;
    omega1.y = sign * amplitude.y * sn1;
    omega1[e_axis] = sign * amplitude[e_axis] * dn1;
    let momentum1 = moments.component_mul(&omega1);

    // ψ over the step.
    let ie = moments[e_axis];
    let c = ie * amplitude[e_axis];
    let a = moments[a_axis] * moments[a_axis] * amplitude2[a_axis];
    let b = c * c * m;
    let n = b / a;
    let (j0, r0) = reduce(phi0);
    let (j1, r1) = reduce(phi1);
    let h_part = |r: f64| {
        let (s, co) = r.sin_cos();
        let s3 = s * s * s;
        if s3 == 0.0 {
            0.0
        } else {
            s3 * carlson_rj(co * co, co * co + mc * s * s, 1.0, 1.0 + n * s * s)
        }
    };
    let mut delta_h = h_part(r1) - h_part(r0);
    if j1 != j0 {
        delta_h += 2.0 * (j1 - j0) as f64 * carlson_rj(0.0, mc, 1.0, 1.0 + n);
    }
    let theta = |j: i64, r: f64| {
        let (s, co) = r.sin_cos();
        j as f64 * PI + ((a + b).sqrt() * s).atan2(a.sqrt() * co)
    };
    let delta_theta = theta(j1, r1) - theta(j0, r0);
    let third_kind = lambda * h - n / 3.0 * delta_h;
    let integral = (big_m / a * third_kind - c * delta_theta / (a * (a + b)).sqrt()) / lambda;
    let psi = big_m / ie * h + twice_e_ie_minus_m2 / ie * integral;

    let mut axis = Vector3::zeros();
    axis[e_axis] = sign;
    let (sp, cp) = (0.5 * psi).sin_cos();
    let turn = Quaternion::from_parts(cp, axis * sp);
    let q = minimal_rotation(&axis, &(momentum / big_m))
        * turn
        * minimal_rotation(&axis, &(momentum1 / momentum1.norm())).conjugate();
    (momentum1, UnitQuaternion::new_normalize(q))
}

/// φ = jπ + r with |r| ≤ π/2.
fn reduce(phi: f64) -> (i64, f64) {
    let j = (phi / PI).round();
    (j as i64, phi - j * PI)
}

/// The smallest rotation taking the unit vector `from` to the unit vector `to` (`from·to > −1`),
/// as an unnormalised quaternion `(1 + from·to, from × to)` scaled to unit length.
fn minimal_rotation(from: &Vector3<f64>, to: &Vector3<f64>) -> Quaternion<f64> {
    let q = Quaternion::from_parts(1.0 + from.dot(to), from.cross(to));
    q / q.norm()
}

#[cfg(test)]
mod tests {
    use super::super::free_top::{rotation_angle_between, FreeRotation, FreeTop};
    use super::*;

    /// The tumbling box 1.0 × 0.4 × 0.1 m, 1 kg: I = M/12 (b²+c², a²+c², a²+b²).
    fn box_moments() -> Vector3<f64> {
        Vector3::new(0.17, 1.01, 1.16) / 12.0
    }

    /// Steps of `h` from ω₀ (principal frame) to `steps·h`, against the closed-form reference of
    /// `free_top` (ω from Jacobi functions, the attitude from a *different* triad integrated by
    /// Gauss–Legendre quadrature): worst relative ω error and worst attitude angle.
    fn against_reference(
        moments: Vector3<f64>,
        w0: Vector3<f64>,
        h: f64,
        steps: usize,
    ) -> (f64, f64) {
        let top = FreeTop::new(moments, w0);
        let start = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1);
        let mut reference = FreeRotation::new(top, start);
        let mut momentum = moments.component_mul(&w0);
        let mut q = start;
        let (mut omega_error, mut angle) = (0.0f64, 0.0f64);
        for k in 1..=steps {
            let (next, turn) = free_flow(&moments, &momentum, h);
            momentum = next;
            q *= turn;
            let t = k as f64 * h;
            let w = momentum.component_div(&moments);
            omega_error = omega_error.max((w - top.omega(t)).norm() / w0.norm());
            angle = angle.max(rotation_angle_between(&reference.at(t), &q));
        }
        (omega_error, angle)
    }

    #[test]
    fn the_flow_matches_the_closed_form_on_both_sides_of_the_separatrix() {
        // Over 5 s at h = 0.1 and 0.013. The flow is exact; what remains is the round-off of the
        // state after each step (≈ 1e-16 of |L|), which moves the invariants E and M, hence
        // the period. Its effect grows as the start nears the separatrix, like M²/|D₂|
        // (3e3 for ω₀ = (1, 10, 1), 4e6 for (0.01, 10, 0.01)): the tolerances say so.
        for (w0, tolerance) in [
            (Vector3::new(1.0, 10.0, 1.0), 1e-12), // major side (M² > 2EI₂), D₂/M² = 3e-4
            (Vector3::new(0.01, 10.0, 0.01), 1e-8), // very near the separatrix, 1 − m = 2e-7
            (Vector3::new(-3.0, 1.0, 0.2), 1e-12), // minor side
            (Vector3::new(0.5, -2.0, -3.0), 1e-12), // negative components
        ] {
            for h in [0.1, 0.013] {
                let steps = (5.0 / h) as usize;
                let (omega_error, angle) = against_reference(box_moments(), w0, h, steps);
                assert!(
                    omega_error < tolerance && angle < tolerance,
                    "ω0 = {:?}, h = {h}: relative ω error {omega_error:e}, attitude {angle:e} rad",
                    w0.as_slice()
                );
            }
        }
    }

    /// q̇ = ½ q ⊗ ω(t) with the closed-form ω, classical RK4 at 1e-4 s (error ≈ t |ω|⁵ h⁴).
    fn attitude_by_rk4(top: &FreeTop, duration: f64) -> UnitQuaternion<f64> {
        let f = |t: f64, q: &Quaternion<f64>| q * Quaternion::from_imag(top.omega(t)) * 0.5;
        let h = 1e-4;
        let mut q = *UnitQuaternion::identity().quaternion();
        for k in 0..(duration / h).round() as usize {
            let t = k as f64 * h;
            let k1 = f(t, &q);
            let k2 = f(t + h / 2.0, &(q + k1 * (h / 2.0)));
            let k3 = f(t + h / 2.0, &(q + k2 * (h / 2.0)));
            let k4 = f(t + h, &(q + k3 * h));
            q += (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
        }
        UnitQuaternion::new_normalize(q)
    }

    /// The flow from ω₀ in `steps` steps of `h`: the final ω and attitude.
    fn flow(
        moments: Vector3<f64>,
        w0: Vector3<f64>,
        h: f64,
        steps: usize,
    ) -> (Vector3<f64>, UnitQuaternion<f64>) {
        let mut momentum = moments.component_mul(&w0);
        let mut q = UnitQuaternion::identity();
        for _ in 0..steps {
            let (next, turn) = free_flow(&moments, &momentum, h);
            momentum = next;
            q *= turn;
        }
        (momentum.component_div(&moments), q)
    }

    #[test]
    fn near_a_steady_spin_the_flow_matches_a_fine_integration_of_the_attitude() {
        // L within 3e-5 rad of the major or the minor axis, |ω| = 5: RK4's error ≈ 5·5⁵·1e-16
        // ≈ 2e-12 rad; measured agreement 1e-14.
        for w0 in [Vector3::new(1e-4, 1e-4, 5.0), Vector3::new(5.0, 1e-4, 1e-4)] {
            let top = FreeTop::new(box_moments(), w0);
            let truth = attitude_by_rk4(&top, 5.0);
            for (h, steps) in [(5.0, 1), (0.1, 50)] {
                let (w, q) = flow(box_moments(), w0, h, steps);
                let angle = rotation_angle_between(&truth, &q);
                assert!(
                    angle < 1e-12,
                    "ω0 = {:?}, h = {h}: {angle:e} rad",
                    w0.as_slice()
                );
                assert!((w - top.omega(5.0)).norm() < 1e-13 * w0.norm());
            }
        }
    }

    #[test]
    fn symmetric_tops_and_spheres_follow_their_closed_forms() {
        // Two equal moments I₁ = I₂ = Iₐ: ω⊥ turns at Ω = (I₃ − Iₐ) ω₃ / Iₐ about e₃, and the body
        // is R(t) = Rot(L̂, M t / Iₐ) R₀ Rot(e₃, −Ω t) (precession about L, spin against it).
        let (ia, i3) = (1.0, 2.5);
        let w0 = Vector3::new(0.7, -0.4, 3.0);
        let moments = Vector3::new(ia, ia, i3);
        let l = moments.component_mul(&w0);
        let rate = (i3 - ia) * w0.z / ia;
        for (h, steps) in [(0.1, 37), (3.7, 1)] {
            let t = h * steps as f64;
            let (w, q) = flow(moments, w0, h, steps);
            let expected = UnitQuaternion::from_scaled_axis(l * (t / ia))
                * UnitQuaternion::from_scaled_axis(Vector3::z() * (-rate * t));
            let (s, c) = (rate * t).sin_cos();
            let w_expected = Vector3::new(w0.x * c - w0.y * s, w0.x * s + w0.y * c, w0.z);
            assert!(
                (w - w_expected).norm() < 1e-13 * w0.norm(),
                "ω {w} vs {w_expected}"
            );
            let angle = rotation_angle_between(&expected, &q);
            assert!(angle < 1e-13, "symmetric top, h = {h}: {angle:e} rad");
        }
        // The other symmetric case I₁ < I₂ = I₃ and the sphere: a sphere turns about ω by |ω| t.
        let (w, q) = flow(Vector3::repeat(2.0), w0, 0.25, 8);
        assert!((w - w0).norm() == 0.0);
        let angle = rotation_angle_between(&UnitQuaternion::from_scaled_axis(w0 * 2.0), &q);
        assert!(angle < 1e-14, "sphere: {angle:e} rad");
        let moments = Vector3::new(1.0, 2.5, 2.5);
        let rate = (ia - 2.5) * w0.x / 2.5; // ω⊥ = (ω₂, ω₃) turns at Ω = (I₁ − I_b) ω₁ / I_b about e₁
        let (w, _) = flow(moments, w0, 0.1, 20);
        let (s, c) = (-rate * 2.0).sin_cos();
        let w_expected = Vector3::new(w0.x, w0.y * c + w0.z * s, -w0.y * s + w0.z * c);
        assert!(
            (w - w_expected).norm() < 1e-13 * w0.norm(),
            "ω {w} vs {w_expected}"
        );
    }

    #[test]
    fn one_long_step_equals_many_short_ones_and_a_step_back_undoes_a_step() {
        // The flow is a one-parameter group: Φ(a + b) = Φ(b)∘Φ(a), Φ(−h)∘Φ(h) = id, across
        // many half-periods of sn (the crossings of φ = π/2 + jπ).
        for w0 in [Vector3::new(1.0, 10.0, 1.0), Vector3::new(-3.0, 1.0, 0.2)] {
            let (w_long, q_long) = flow(box_moments(), w0, 7.3, 1);
            let (w_short, q_short) = flow(box_moments(), w0, 0.73, 10);
            assert!((w_long - w_short).norm() < 1e-11 * w0.norm());
            assert!(rotation_angle_between(&q_long, &q_short) < 1e-11);
            let momentum = box_moments().component_mul(&w0);
            let (there, out) = free_flow(&box_moments(), &momentum, 2.9);
            let (back, home) = free_flow(&box_moments(), &there, -2.9);
            assert!((back - momentum).norm() < 1e-13 * momentum.norm());
            assert!(rotation_angle_between(&UnitQuaternion::identity(), &(out * home)) < 1e-13);
        }
    }

    #[test]
    fn carlson_integrals_match_tabulated_values() {
        // Carlson (1995), Numer. Algorithms 10, test values (14 digits); R_C(9/4, 2) = ln 2, R_C(0, 1/4) = π.
        use super::super::free_top::carlson_rc;
        let close = |a: f64, b: f64, what: &str| {
            assert!((a - b).abs() < 1e-13 * b.abs(), "{what}: {a} vs {b}")
        };
        close(carlson_rc(0.0, 0.25), PI, "R_C(0, 1/4)");
        close(carlson_rc(2.25, 2.0), 2f64.ln(), "R_C(9/4, 2)");
        close(
            carlson_rj(0.0, 1.0, 2.0, 3.0),
            0.776_886_237_785_82,
            "R_J(0, 1, 2, 3)",
        );
        close(
            carlson_rj(2.0, 3.0, 4.0, 5.0),
            0.142_975_796_671_57,
            "R_J(2, 3, 4, 5)",
        );
    }
}
