//! The torque-free asymmetric top in closed form: an independent reference for free rotation.
//!
//! In the principal frame (moments I₁ < I₂ < I₃), a torque-free body obeys Euler's equations
//!
//! ```text
//! I₁ ω̇₁ = (I₂ − I₃) ω₂ ω₃     I₂ ω̇₂ = (I₃ − I₁) ω₃ ω₁     I₃ ω̇₃ = (I₁ − I₂) ω₁ ω₂
//! ```
//!
//! which keep 2E = Σ Iᵢ ωᵢ² and M² = |L|² = Σ Iᵢ² ωᵢ². Their solution (Landau & Lifshitz,
//! *Mechanics* §37) uses Jacobi's elliptic functions sn, cn, dn of parameter m = k²:
//!
//! ```text
//! M² > 2E I₂ (L nearer the major axis 3):
//!   ω₁ = A₁ cn u     ω₂ = s A₂ sn u     ω₃ = s A₃ dn u        s = sign ω₃(0)
//!   A₁² = (2EI₃ − M²) / (I₁(I₃ − I₁))   A₂² = (2EI₃ − M²) / (I₂(I₃ − I₂))
//!   A₃² = (M² − 2EI₁) / (I₃(I₃ − I₁))
//!   u = λ t + u₀,   λ² = (I₃ − I₂)(M² − 2EI₁) / (I₁I₂I₃)
//!   m = (I₂ − I₁)(2EI₃ − M²) / ((I₃ − I₂)(M² − 2EI₁))
//!   1 − m = (I₃ − I₁)(M² − 2EI₂) / ((I₃ − I₂)(M² − 2EI₁))
//! M² < 2E I₂ (L nearer the minor axis 1): the same with the indices 1 and 3 swapped
//!   (ω₃ = A₃ cn u, ω₂ = s A₂ sn u, ω₁ = s A₁ dn u, s = sign ω₁(0)).
//! ```
//!
//! The differences M² − 2EIᵢ are computed from the ω components directly
//! (e.g. `M² − 2EI₂ = I₁(I₁ − I₂)ω₁² + I₃(I₃ − I₂)ω₃²`), so nothing cancels near the separatrix
//! M² = 2EI₂, where 1 − m → 0. The initial phase is `u₀ = F(φ₀ | m)`, the incomplete elliptic
//! integral of the amplitude φ₀ = atan2(sn u₀, cn u₀) read off ω(0).
//!
//! ω₂ ∝ sn u changes sign every half-period of sn: the **flip half-period** of the
//! intermediate-axis (tennis-racket) instability is `2K(m)/λ`, K the complete elliptic integral.
//!
//! Symmetric tops (two equal moments) precess at a constant rate, a spherical top or a spin about a
//! principal axis keeps ω constant; both are handled exactly.
//!
//! **Orientation.** The orientation also has a closed form (with theta functions); instead, this
//! module uses the *one-quadrature* form, just as exact up to quadrature error: L is fixed in the
//! world, so the body is known up to a rotation angle ψ about L, and ψ obeys
//!
//! ```text
//! ψ̇ = M (2E − I_e ω_e²) / (M² − I_e² ω_e²)        (e a principal axis L never aligns with)
//! R(t) = R(0) T(0) Rz(ψ(t)) T(t)ᵀ,   T = [a b n],  n = L_body/M,
//!        a = normalise(e − (e·n) n),  b = n × a
//! ```
//!
//! (the general form of L&L's `φ̇`). ψ is integrated by composite 8-point Gauss–Legendre
//! quadrature on sub-intervals of at most `0.05 / max(|ω|, λ)`, so its error is at round-off level.
//!
//! Jacobi functions use the descending Landen (AGM) transformation (Abramowitz & Stegun 16.4),
//! K uses the arithmetic–geometric mean (A&S 17.6), and F uses Carlson's symmetric integral R_F.
//!
//! ```
//! use nalgebra::Vector3;
//! use tumble::physics::free_top::FreeTop;
//! // The box 1.0 × 0.4 × 0.1 m, 1 kg: I = M/12 (b² + c², a² + c², a² + b²), ω_body(0) = (1, 10, 1).
//! let moments = Vector3::new(0.17, 1.01, 1.16) / 12.0;
//! let top = FreeTop::new(moments, Vector3::new(1.0, 10.0, 1.0));
//! let half_period = top.flip_half_period().unwrap(); // 2K(m)/λ, s
//! assert!((half_period - 1.094917).abs() < 1e-6);
//! let omega = top.omega(0.25); // ω in the principal frame at t = 0.25 s
//! assert!(omega.y > 0.0);
//! ```

use super::body::Body;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::f64::consts::FRAC_PI_2;

/// `(sn u, cn u, dn u)` for parameter `m = k²`, 0 ≤ m ≤ 1.
pub fn jacobi(u: f64, m: f64) -> (f64, f64, f64) {
    jacobi_complement(u, m, 1.0 - m)
}

/// `(sn u, cn u, dn u)` given both `m` and its complement `mc = 1 − m` (pass `mc` computed
/// without cancellation when m is close to 1).
///
/// Descending Landen (A&S 16.4.2–16.4.4): AGM `a₀ = 1, b₀ = √mc, c₀ = √m`, then
/// `φ_N = 2ᴺ a_N u`, `φₙ₋₁ = ½ (φₙ + asin(cₙ/aₙ sin φₙ))`, `sn = sin φ₀`, `cn = cos φ₀`,
/// and `dn = √(cn² + mc sn²)` (a sum of non-negative terms, accurate even when dn is small).
pub fn jacobi_complement(u: f64, m: f64, mc: f64) -> (f64, f64, f64) {
    let (sn, cn, dn, _) = jacobi_amplitude(u, m, mc);
    (sn, cn, dn)
}

/// `(sn u, cn u, dn u, am u)`: [`jacobi_complement`] with the amplitude `φ = am u` as well,
/// continuous in u (`am(u + 2K) = am u + π`), as the Landen descent produces it.
pub fn jacobi_amplitude(u: f64, m: f64, mc: f64) -> (f64, f64, f64, f64) {
    if m <= 0.0 {
        let (sn, cn) = u.sin_cos();
        return (sn, cn, 1.0, u);
    }
    if mc <= 0.0 {
        let sech = 1.0 / u.cosh();
        return (u.tanh(), sech, sech, u.sinh().atan());
    }
    const LEVELS: usize = 16;
    let mut a = [0.0; LEVELS];
    let mut c = [0.0; LEVELS];
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = mc.sqrt();
    let mut n = 0;
    while n + 1 < LEVELS && c[n].abs() > f64::EPSILON * a[n] {
        a[n + 1] = 0.5 * (a[n] + b);
        c[n + 1] = 0.5 * (a[n] - b);
        b = (a[n] * b).sqrt();
        n += 1;
    }
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for level in (1..=n).rev() {
        let s = (c[level] / a[level] * phi.sin()).clamp(-1.0, 1.0);
        phi = 0.5 * (phi + s.asin());
    }
    let (sn, cn) = phi.sin_cos();
    let dn = (cn * cn + mc * sn * sn).sqrt();
    (sn, cn, dn, phi)
}

/// The arithmetic–geometric mean of a, b ≥ 0.
pub fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..64 {
        if (a - b).abs() <= f64::EPSILON * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    a
}

/// The complete elliptic integral of the first kind `K(m) = ∫₀^{π/2} dθ / √(1 − m sin²θ)`,
/// by `K = π / (2 AGM(1, √(1 − m)))`. Infinite at m = 1.
pub fn complete_k(m: f64) -> f64 {
    complete_k_complement(1.0 - m)
}

/// K given the complementary parameter `mc = 1 − m`.
pub fn complete_k_complement(mc: f64) -> f64 {
    if mc <= 0.0 {
        return f64::INFINITY;
    }
    FRAC_PI_2 / agm(1.0, mc.sqrt())
}

/// Carlson's symmetric elliptic integral `R_F(x, y, z)` (duplication theorem; Carlson 1995).
pub fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    for _ in 0..64 {
        let mean = (x + y + z) / 3.0;
        let (dx, dy, dz) = (1.0 - x / mean, 1.0 - y / mean, 1.0 - z / mean);
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-4 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 + (e2 / 24.0 - 0.1 - 3.0 * e3 / 44.0) * e2 + e3 / 14.0) / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sx * sz + sy * sz;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
    1.0 / ((x + y + z) / 3.0).sqrt()
}

/// Carlson's degenerate integral `R_C(x, y) = R_F(x, y, y)`, x ≥ 0, y > 0, in closed form:
/// with `r = √(|y − x| / x)`, `R_C = atan(r) / (r √x)` for y > x and `atanh(r) / (r √x)` for
/// y < x (both tend to `1/√x` as r → 0, and are computed as such ratios without cancellation);
/// `R_C(0, y) = π / (2√y)`.
pub fn carlson_rc(x: f64, y: f64) -> f64 {
    if x <= 0.0 {
        return FRAC_PI_2 / y.sqrt();
    }
    let difference = y - x;
    if difference == 0.0 {
        return 1.0 / x.sqrt();
    }
    let r = (difference.abs() / x).sqrt();
    let angle = if difference > 0.0 {
        r.atan()
    } else {
        r.atanh()
    };
    angle / (r * x.sqrt())
}

/// Carlson's symmetric integral of the third kind
/// `R_J(x, y, z, p) = 3/2 ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z)))`, x, y, z ≥ 0 (at most
/// one zero), p > 0: the duplication theorem (Carlson 1979; Press et al., *Numerical Recipes*
/// §6.11) until every argument is within 1e-3 of their weighted mean, then its fifth-order
/// series (error ≈ 1e-3⁶).
pub fn carlson_rj(mut x: f64, mut y: f64, mut z: f64, mut p: f64) -> f64 {
    const C1: f64 = 3.0 / 14.0;
    const C2: f64 = 1.0 / 3.0;
    const C3: f64 = 3.0 / 22.0;
    const C4: f64 = 3.0 / 26.0;
    const C5: f64 = 0.75 * C3;
    const C6: f64 = 1.5 * C4;
    const C7: f64 = 0.5 * C2;
    const C8: f64 = C3 + C3;
    let (mut sum, mut factor) = (0.0, 1.0);
    for _ in 0..64 {
        let mean = 0.2 * (x + y + z + p + p);
        let (dx, dy, dz, dp) = (
            (mean - x) / mean,
            (mean - y) / mean,
            (mean - z) / mean,
            (mean - p) / mean,
        );
        if dx.abs().max(dy.abs()).max(dz.abs()).max(dp.abs()) < 1e-3 {
            let ea = dx * (dy + dz) + dy * dz;
            let eb = dx * dy * dz;
            let ec = dp * dp;
            let ed = ea - 3.0 * ec;
            let ee = eb + 2.0 * dp * (ea - ec);
            let series = 1.0
                + ed * (-C1 + C5 * ed - C6 * ee)
                + eb * (C7 + dp * (-C8 + dp * C4))
                + dp * ea * (C2 - dp * C3)
                - C2 * dp * ec;
            return 3.0 * sum + factor * series / (mean * mean.sqrt());
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * (sy + sz) + sy * sz;
        let alpha = p * (sx + sy + sz) + sx * sy * sz;
        let beta = p * (p + lambda) * (p + lambda);
        sum += factor * carlson_rc(alpha * alpha, beta);
        factor *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
        p = 0.25 * (p + lambda);
    }
    3.0 * sum + factor / (p * p.sqrt())
}

/// The incomplete elliptic integral of the first kind `F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ)`,
/// any real φ (`F(φ + nπ) = F(φ) + 2nK`).
pub fn elliptic_f(phi: f64, m: f64) -> f64 {
    elliptic_f_complement(phi, 1.0 - m)
}

/// F given the complementary parameter `mc = 1 − m`:
/// `F(φ) = sin φ · R_F(cos²φ, cos²φ + mc sin²φ, 1)` on |φ| ≤ π/2, extended by periodicity.
pub fn elliptic_f_complement(phi: f64, mc: f64) -> f64 {
    let turns = (phi / std::f64::consts::PI).round();
    let reduced = phi - turns * std::f64::consts::PI;
    let (s, c) = reduced.sin_cos();
    let local = s * carlson_rf(c * c, c * c + mc * s * s, 1.0);
    if turns == 0.0 {
        local
    } else {
        local + 2.0 * turns * complete_k_complement(mc)
    }
}

/// How a torque-free body moves, by the shape of its inertia.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Motion {
    /// ω ∥ L (spin about a principal axis, or a spherical top): ω constant.
    Steady,
    /// Two equal moments: the two components ⊥ the symmetry axis `axis` turn at `rate`.
    Symmetric { axis: usize, rate: f64 },
    /// The asymmetric top: `ω[cn_axis] = A cn u`, `ω₂ = s A₂ sn u`, `ω[dn_axis] = s A dn u`.
    Elliptic {
        cn_axis: usize,
        dn_axis: usize,
        amplitude: Vector3<f64>,
        sign: f64,
        lambda: f64,
        m: f64,
        mc: f64,
        u0: f64,
    },
}

/// The closed-form angular velocity of a torque-free body in its principal frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeTop {
    moments: Vector3<f64>,
    omega0: Vector3<f64>,
    motion: Motion,
}

/// Relative difference below which two principal moments are taken as equal.
const EQUAL_MOMENTS: f64 = 1e-12;

impl FreeTop {
    /// The top with principal moments `I₁ ≤ I₂ ≤ I₃` (kg·m², positive) and angular velocity
    /// `omega0` in the principal frame at t = 0 (rad/s).
    pub fn new(moments: Vector3<f64>, omega0: Vector3<f64>) -> FreeTop {
        let [i1, i2, i3] = [moments.x, moments.y, moments.z];
        let [w1, w2, w3] = [omega0.x, omega0.y, omega0.z];
        let momentum = moments.component_mul(&omega0);
        let steady = omega0.cross(&momentum).norm() <= 1e-15 * omega0.norm() * momentum.norm();
        let equal12 = i2 - i1 <= EQUAL_MOMENTS * i3;
        let equal23 = i3 - i2 <= EQUAL_MOMENTS * i3;
        let motion = if steady || (equal12 && equal23) {
            Motion::Steady
        } else if equal12 {
            let ia = 0.5 * (i1 + i2);
            Motion::Symmetric {
                axis: 2,
                rate: (i3 - ia) / ia * w3,
            }
        } else if equal23 {
            let ib = 0.5 * (i2 + i3);
            Motion::Symmetric {
                axis: 0,
                rate: (ib - i1) / ib * w1,
            }
        } else {
            // The differences, each a sum without cancellation.
            let m2_minus_2e_i1 = i2 * (i2 - i1) * w2 * w2 + i3 * (i3 - i1) * w3 * w3;
            let two_e_i3_minus_m2 = i1 * (i3 - i1) * w1 * w1 + i2 * (i3 - i2) * w2 * w2;
            let m2_minus_2e_i2 = i1 * (i1 - i2) * w1 * w1 + i3 * (i3 - i2) * w3 * w3;
            let amplitude_1 = (two_e_i3_minus_m2 / (i1 * (i3 - i1))).sqrt();
            let amplitude_3 = (m2_minus_2e_i1 / (i3 * (i3 - i1))).sqrt();
            let product = i1 * i2 * i3;
            let (cn_axis, dn_axis, amplitude, lambda, m, mc) = if m2_minus_2e_i2 >= 0.0 {
                let denominator = (i3 - i2) * m2_minus_2e_i1;
                (
                    0,
                    2,
                    Vector3::new(
                        amplitude_1,
                        (two_e_i3_minus_m2 / (i2 * (i3 - i2))).sqrt(),
                        amplitude_3,
                    ),
                    (denominator / product).sqrt(),
                    (i2 - i1) * two_e_i3_minus_m2 / denominator,
                    (i3 - i1) * m2_minus_2e_i2 / denominator,
                )
            } else {
                let denominator = (i2 - i1) * two_e_i3_minus_m2;
                (
                    2,
                    0,
                    Vector3::new(
                        amplitude_1,
                        (m2_minus_2e_i1 / (i2 * (i2 - i1))).sqrt(),
                        amplitude_3,
                    ),
                    (denominator / product).sqrt(),
                    (i3 - i2) * m2_minus_2e_i1 / denominator,
                    -(i3 - i1) * m2_minus_2e_i2 / denominator,
                )
            };
            let sign = if omega0[dn_axis] < 0.0 { -1.0 } else { 1.0 };
            let phi0 = (sign * w2 / amplitude.y).atan2(omega0[cn_axis] / amplitude[cn_axis]);
            Motion::Elliptic {
                cn_axis,
                dn_axis,
                amplitude,
                sign,
                lambda,
                m,
                mc,
                u0: elliptic_f_complement(phi0, mc),
            }
        };
        FreeTop {
            moments,
            omega0,
            motion,
        }
    }

    /// The principal moments.
    pub fn moments(&self) -> Vector3<f64> {
        self.moments
    }

    /// Twice the kinetic energy, `2E = Σ Iᵢ ωᵢ²`, J.
    pub fn twice_energy(&self) -> f64 {
        self.moments.dot(&self.omega0.component_mul(&self.omega0))
    }

    /// |L| = M, kg·m²/s.
    pub fn momentum(&self) -> f64 {
        self.moments.component_mul(&self.omega0).norm()
    }

    /// The parameter m = k² of the elliptic functions (None unless the top is asymmetric and
    /// not in a steady spin).
    pub fn parameter(&self) -> Option<f64> {
        match self.motion {
            Motion::Elliptic { m, .. } => Some(m),
            _ => None,
        }
    }

    /// The complementary parameter 1 − m, computed without cancellation (small near the
    /// separatrix).
    pub fn complement(&self) -> Option<f64> {
        match self.motion {
            Motion::Elliptic { mc, .. } => Some(mc),
            _ => None,
        }
    }

    /// The rate λ of the elliptic argument u = λt + u₀, 1/s.
    pub fn rate(&self) -> Option<f64> {
        match self.motion {
            Motion::Elliptic { lambda, .. } => Some(lambda),
            _ => None,
        }
    }

    /// The flip half-period `2K(m)/λ`: the time between successive sign changes of ω₂ (the
    /// intermediate axis), s. None when ω₂ does not oscillate (symmetric or steady tops);
    /// infinite on the separatrix.
    pub fn flip_half_period(&self) -> Option<f64> {
        match self.motion {
            Motion::Elliptic { lambda, mc, .. } => Some(2.0 * complete_k_complement(mc) / lambda),
            _ => None,
        }
    }

    /// The angular velocity in the principal frame at time t, rad/s.
    pub fn omega(&self, t: f64) -> Vector3<f64> {
        match self.motion {
            Motion::Steady => self.omega0,
            Motion::Symmetric { axis, rate } => {
                let (s, c) = (rate * t).sin_cos();
                let w = self.omega0;
                if axis == 2 {
                    Vector3::new(w.x * c - w.y * s, w.x * s + w.y * c, w.z)
                } else {
                    Vector3::new(w.x, w.y * c + w.z * s, -w.y * s + w.z * c)
                }
            }
            Motion::Elliptic {
                cn_axis,
                dn_axis,
                amplitude,
                sign,
                lambda,
                m,
                mc,
                u0,
            } => {
                let (sn, cn, dn) = jacobi_complement(lambda * t + u0, m, mc);
                let mut w = Vector3::zeros();
                w[cn_axis] = amplitude[cn_axis] * cn;
                w[1] = sign * amplitude.y * sn;
                w[dn_axis] = sign * amplitude[dn_axis] * dn;
                w
            }
        }
    }

    /// The principal axis that the body-frame L never aligns with (None for steady motion).
    fn reference_axis(&self) -> Option<usize> {
        match self.motion {
            Motion::Steady => None,
            Motion::Symmetric { axis, .. } => Some(axis),
            Motion::Elliptic { dn_axis, .. } => Some(dn_axis),
        }
    }

    /// A time scale of the motion: `1 / max(|ω|, λ)`, s.
    fn time_scale(&self) -> f64 {
        let lambda = self.rate().unwrap_or(0.0);
        1.0 / self.omega0.norm().max(lambda).max(f64::MIN_POSITIVE)
    }
}

/// The orientation of a torque-free top: R(t) from R(0) and the one-quadrature form of the
/// module doc. Keeps the last ψ so that increasing times cost only the new interval.
#[derive(Debug, Clone)]
pub struct FreeRotation {
    top: FreeTop,
    /// Principal frame → world at t = 0.
    start: UnitQuaternion<f64>,
    /// R(0) T(0) (None for steady motion).
    start_triad: Option<Matrix3<f64>>,
    axis: Option<usize>,
    last: (f64, f64),
}

/// 8-point Gauss–Legendre nodes and weights on [−1, 1].
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

impl FreeRotation {
    /// The rotation of `top` whose principal frame is turned by `start` (principal → world)
    /// at t = 0.
    pub fn new(top: FreeTop, start: UnitQuaternion<f64>) -> FreeRotation {
        let axis = top.reference_axis();
        let start_triad =
            axis.map(|e| start.to_rotation_matrix().into_inner() * triad(&top, 0.0, e));
        FreeRotation {
            top,
            start,
            start_triad,
            axis,
            last: (0.0, 0.0),
        }
    }

    /// The top.
    pub fn top(&self) -> &FreeTop {
        &self.top
    }

    /// ψ̇ = M (2E − I_e ω_e²) / (M² − I_e² ω_e²), written as sums over the two other axes.
    fn psi_rate(&self, t: f64, e: usize) -> f64 {
        let w = self.top.omega(t);
        let i = self.top.moments;
        let (mut energy_part, mut momentum_part) = (0.0, 0.0);
        for k in (0..3).filter(|&k| k != e) {
            energy_part += i[k] * w[k] * w[k];
            momentum_part += i[k] * i[k] * w[k] * w[k];
        }
        self.top.momentum() * energy_part / momentum_part
    }

    /// ψ(t) by composite Gauss–Legendre quadrature, continuing from the last time asked.
    fn psi(&mut self, t: f64, e: usize) -> f64 {
        let (mut t0, mut psi) = self.last;
        if t < t0 {
            (t0, psi) = (0.0, 0.0);
        }
        let span = t - t0;
        let pieces = (span / (0.05 * self.top.time_scale())).ceil().max(1.0) as usize;
        let h = span / pieces as f64;
        for piece in 0..pieces {
            let mid = t0 + (piece as f64 + 0.5) * h;
            psi += 0.5
                * h
                * GAUSS_8
                    .iter()
                    .map(|(x, w)| w * self.psi_rate(mid + 0.5 * h * x, e))
                    .sum::<f64>();
        }
        self.last = (t, psi);
        psi
    }

    /// Principal frame → world at time t.
    pub fn at(&mut self, t: f64) -> UnitQuaternion<f64> {
        match (self.axis, self.start_triad) {
            (Some(e), Some(start_triad)) => {
                let psi = self.psi(t, e);
                let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), psi).into_inner();
                let r = start_triad * turn * triad(&self.top, t, e).transpose();
                UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r))
            }
            _ => {
                let w = self.top.omega0;
                self.start * UnitQuaternion::from_scaled_axis(w * t)
            }
        }
    }
}

/// `T = [a b n]` in the principal frame: n = L/|L|, a = normalise(e − (e·n)n), b = n × a.
fn triad(top: &FreeTop, t: f64, e: usize) -> Matrix3<f64> {
    let l = top.moments.component_mul(&top.omega(t));
    let n = l / l.norm();
    let mut axis = Vector3::zeros();
    axis[e] = 1.0;
    let a = (axis - n * n[e]).normalize();
    Matrix3::from_columns(&[a, n.cross(&a), n])
}

/// The free motion of a [`Body`]: the closed form moved from the principal frame to the body
/// frame (`I_body = E diag(I₁,I₂,I₃) Eᵀ`, E = `body.principal_axes`).
#[derive(Debug, Clone)]
pub struct FreeBody {
    axes: UnitQuaternion<f64>,
    rotation: FreeRotation,
}

impl FreeBody {
    /// The body with orientation `orientation` (body → world) and world angular momentum
    /// `angular_momentum` at t = 0.
    pub fn new(
        body: &Body,
        orientation: UnitQuaternion<f64>,
        angular_momentum: Vector3<f64>,
    ) -> FreeBody {
        let axes = body.principal_axes;
        let principal_to_world = orientation * axes;
        let momentum_principal = principal_to_world.inverse_transform_vector(&angular_momentum);
        let omega0 = momentum_principal.component_div(&body.principal_moments);
        let top = FreeTop::new(body.principal_moments, omega0);
        FreeBody {
            axes,
            rotation: FreeRotation::new(top, principal_to_world),
        }
    }

    /// The top in the principal frame.
    pub fn top(&self) -> &FreeTop {
        self.rotation.top()
    }

    /// ω in the body frame at time t, rad/s.
    pub fn omega_body(&self, t: f64) -> Vector3<f64> {
        self.axes * self.rotation.top().omega(t)
    }

    /// The orientation (body → world) at time t.
    pub fn orientation(&mut self, t: f64) -> UnitQuaternion<f64> {
        self.rotation.at(t) * self.axes.inverse()
    }
}

/// The angle of the rotation `a⁻¹ b`, rad, accurate for tiny angles (`2 atan2(|v|, |w|)`
/// instead of `2 acos w`, which loses half the digits near 0).
pub fn rotation_angle_between(a: &UnitQuaternion<f64>, b: &UnitQuaternion<f64>) -> f64 {
    let delta = a.inverse() * b;
    let q = delta.quaternion();
    2.0 * q.imag().norm().atan2(q.w.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn close(a: f64, b: f64, tol: f64, what: &str) {
        assert!(
            (a - b).abs() <= tol,
            "{what}: {a} vs {b} (diff {:e})",
            (a - b).abs()
        );
    }

    #[test]
    fn jacobi_identities_hold_for_every_parameter() {
        // sn² + cn² = 1 and m sn² + dn² = 1 for all u and m.
        for &m in &[0.0, 1e-8, 0.1, 0.5, 0.9, 0.999, 1.0 - 1e-9, 1.0] {
            for i in -40..=40 {
                let u = i as f64 * 0.37;
                let (sn, cn, dn) = jacobi(u, m);
                close(
                    sn * sn + cn * cn,
                    1.0,
                    4e-15,
                    &format!("sn²+cn² m={m} u={u}"),
                );
                close(
                    m * sn * sn + dn * dn,
                    1.0,
                    4e-15,
                    &format!("m sn²+dn² m={m} u={u}"),
                );
            }
        }
    }

    #[test]
    fn jacobi_reduces_to_sin_and_tanh_at_the_ends() {
        for i in -20..=20 {
            let u = i as f64 * 0.3;
            let (sn, cn, dn) = jacobi(u, 0.0);
            close(sn, u.sin(), 1e-15, "sn(u|0) = sin u");
            close(cn, u.cos(), 1e-15, "cn(u|0) = cos u");
            close(dn, 1.0, 0.0, "dn(u|0) = 1");
            let (sn, cn, dn) = jacobi(u, 1.0);
            close(sn, u.tanh(), 1e-15, "sn(u|1) = tanh u");
            close(cn, 1.0 / u.cosh(), 1e-15, "cn(u|1) = sech u");
            close(dn, 1.0 / u.cosh(), 1e-15, "dn(u|1) = sech u");
            // Close to the ends, continuously.
            let (sn, _, _) = jacobi(u, 1e-12);
            close(sn, u.sin(), 1e-11, "sn(u|1e-12) ≈ sin u");
            let (sn, _, _) = jacobi_complement(u, 1.0 - 1e-14, 1e-14);
            close(sn, u.tanh(), 1e-12, "sn(u|1−1e-14) ≈ tanh u");
        }
    }

    #[test]
    fn jacobi_matches_tabulated_values() {
        // K(1/2) = 1.854 074 677 301 372 (A&S Table 17.1); sn(K|m) = 1, cn(K) = 0,
        // dn(K) = √(1 − m). sn, cn, dn(0.5 | 0.5) computed independently at 30 digits with
        // mpmath's `ellipfun`: 0.470 750 473 655 657 3, 0.882 266 394 890 440 3,
        // 0.942 972 425 777 385 7.
        close(complete_k(0.5), 1.854_074_677_301_372, 1e-15, "K(1/2)");
        let (sn, cn, dn) = jacobi(0.5, 0.5);
        close(sn, 0.470_750_473_655_657, 1e-15, "sn(0.5|0.5)");
        close(cn, 0.882_266_394_890_440, 1e-15, "cn(0.5|0.5)");
        close(dn, 0.942_972_425_777_386, 1e-15, "dn(0.5|0.5)");
        for &m in &[0.3, 0.7, 0.99] {
            let k = complete_k(m);
            let (sn, cn, dn) = jacobi(k, m);
            close(sn, 1.0, 1e-14, "sn(K) = 1");
            close(cn, 0.0, 1e-14, "cn(K) = 0");
            close(dn, (1.0 - m).sqrt(), 1e-14, "dn(K) = √(1−m)");
        }
    }

    #[test]
    fn complete_integral_known_values() {
        // K(0) = π/2; K(m) → ∞ as m → 1, like ln(4/√(1−m)).
        close(complete_k(0.0), PI / 2.0, 1e-16, "K(0)");
        assert!(complete_k(1.0).is_infinite());
        let mc: f64 = 1e-12;
        close(
            complete_k_complement(mc),
            (4.0 / mc.sqrt()).ln(),
            1e-10,
            "K near 1",
        );
        // Gamma-function value: K(1/2) = Γ(1/4)² / (4√π), Γ(1/4) = 3.625 609 908 221 908.
        let gamma = 3.625_609_908_221_908_f64;
        close(
            complete_k(0.5),
            gamma * gamma / (4.0 * PI.sqrt()),
            1e-14,
            "K(1/2) from Γ(1/4)",
        );
    }

    #[test]
    fn incomplete_integral_inverts_sn() {
        // F(φ|0) = φ; F(π/2|m) = K(m); sn(F(φ|m)|m) = sin φ, cn = cos φ for any φ.
        close(elliptic_f(1.0, 0.0), 1.0, 1e-15, "F(1|0)");
        close(
            elliptic_f(PI / 2.0, 0.8),
            complete_k(0.8),
            1e-14,
            "F(π/2|m)",
        );
        for &m in &[0.0, 0.2, 0.9, 0.999_999] {
            for i in -30..=30 {
                let phi = i as f64 * 0.21;
                let (sn, cn, _) = jacobi(elliptic_f(phi, m), m);
                close(sn, phi.sin(), 1e-13, &format!("sn(F(φ)) m={m} φ={phi}"));
                close(cn, phi.cos(), 1e-13, &format!("cn(F(φ)) m={m} φ={phi}"));
            }
        }
    }

    /// The tumbling box 1.0 × 0.4 × 0.1 m, 1 kg: I = M/12 (b²+c², a²+c², a²+b²).
    fn box_moments() -> Vector3<f64> {
        Vector3::new(0.17, 1.01, 1.16) / 12.0
    }

    fn euler_residual(top: &FreeTop, t: f64) -> f64 {
        // Central difference (error O(h²) ≈ 1e-10 relative with h = 1e-5 for |ω| ≈ 10) of
        // I ω̇ − (I ω) × ω … written per component as I₁ω̇₁ − (I₂ − I₃)ω₂ω₃ etc.
        let h = 1e-5;
        let i = top.moments();
        let w = top.omega(t);
        let dw = (top.omega(t + h) - top.omega(t - h)) / (2.0 * h);
        let r = Vector3::new(
            i.x * dw.x - (i.y - i.z) * w.y * w.z,
            i.y * dw.y - (i.z - i.x) * w.z * w.x,
            i.z * dw.z - (i.x - i.y) * w.x * w.y,
        );
        r.norm() / (i.component_mul(&w).norm() * w.norm())
    }

    #[test]
    fn closed_form_solves_eulers_equations_and_conserves_e_and_l() {
        let starts = [
            Vector3::new(1.0, 10.0, 1.0),   // M² > 2EI₂, away from the separatrix
            Vector3::new(0.01, 10.0, 0.01), // near the separatrix
            Vector3::new(-3.0, 1.0, 0.2),   // M² < 2EI₂ (near the minor axis)
            Vector3::new(0.5, -2.0, -3.0),  // negative components
            Vector3::new(2.0, 0.0, 0.0),    // steady spin about the minor axis
        ];
        for w0 in starts {
            let top = FreeTop::new(box_moments(), w0);
            let w = top.omega(0.0);
            assert!((w - w0).norm() <= 1e-13 * w0.norm(), "ω(0) {w} ≠ {w0}");
            let (two_e, m) = (top.twice_energy(), top.momentum());
            for k in 0..200 {
                let t = k as f64 * 0.1;
                let res = euler_residual(&top, t);
                assert!(res < 1e-8, "Euler residual {res:e} at t={t} for ω0={w0}");
                let w = top.omega(t);
                let i = top.moments();
                let e = i.dot(&w.component_mul(&w));
                let l = i.component_mul(&w).norm();
                assert!(
                    (e - two_e).abs() < 1e-13 * two_e,
                    "2E drift {:e}",
                    e - two_e
                );
                assert!((l - m).abs() < 1e-13 * m, "|L| drift {:e}", l - m);
            }
        }
    }

    #[test]
    fn symmetric_tops_precess_and_spheres_stay() {
        for (moments, w0) in [
            (Vector3::new(1.0, 1.0, 2.0), Vector3::new(1.0, 0.5, 3.0)),
            (Vector3::new(1.0, 2.0, 2.0), Vector3::new(1.0, 0.5, 3.0)),
            (Vector3::new(2.0, 2.0, 2.0), Vector3::new(1.0, 0.5, 3.0)),
        ] {
            let top = FreeTop::new(moments, w0);
            assert!(top.flip_half_period().is_none());
            for k in 0..50 {
                let res = euler_residual(&top, k as f64 * 0.13);
                assert!(res < 1e-9, "residual {res:e} for I={moments}");
            }
        }
    }

    #[test]
    fn flip_half_period_is_the_time_between_sign_changes_of_omega_2() {
        for w0 in [Vector3::new(1.0, 10.0, 1.0), Vector3::new(-3.0, 1.0, 0.2)] {
            let top = FreeTop::new(box_moments(), w0);
            let period = top.flip_half_period().unwrap();
            // Find sign changes of ω₂ by bisection over 10 half-periods.
            let mut crossings = Vec::new();
            let h = period / 50.0;
            let mut t = 0.0;
            while t < 10.0 * period {
                let (a, b) = (top.omega(t).y, top.omega(t + h).y);
                if a * b < 0.0 {
                    let (mut lo, mut hi) = (t, t + h);
                    for _ in 0..60 {
                        let mid = 0.5 * (lo + hi);
                        if top.omega(lo).y * top.omega(mid).y <= 0.0 {
                            hi = mid;
                        } else {
                            lo = mid;
                        }
                    }
                    crossings.push(0.5 * (lo + hi));
                }
                t += h;
            }
            assert!(crossings.len() >= 9, "{} crossings", crossings.len());
            for pair in crossings.windows(2) {
                close(
                    pair[1] - pair[0],
                    period,
                    1e-10,
                    "time between ω₂ sign changes",
                );
            }
        }
    }

    #[test]
    fn flip_period_near_the_separatrix_is_ill_conditioned_as_minus_one_over_2k() {
        // P = 2K/λ with K ≈ ln(4/k'), k'² ∝ D = M² − 2EI₂, so d ln P / d ln D ≈ −1/(2K).
        // Perturb ω₃ of the classic start (0.01, 10, 0.01) by ±0.5 % and compare slopes.
        let p = |w3: f64| {
            let top = FreeTop::new(box_moments(), Vector3::new(0.01, 10.0, w3));
            let w = Vector3::new(0.01, 10.0, w3);
            let i = box_moments();
            let d = i.x * (i.x - i.y) * w.x * w.x + i.z * (i.z - i.y) * w.z * w.z;
            (
                top.flip_half_period().unwrap(),
                d,
                top.complement().unwrap(),
            )
        };
        let (p1, d1, _) = p(0.01 * 0.995);
        let (p2, d2, _) = p(0.01 * 1.005);
        let (p0, _, mc) = p(0.01);
        let slope = (p2 / p1).ln() / (d2 / d1).ln();
        let k = complete_k_complement(mc);
        let expected = -1.0 / (2.0 * k);
        assert!(
            (slope - expected).abs() < 0.02 * expected.abs(),
            "d ln P / d ln D = {slope:.5}, −1/(2K) = {expected:.5} (K = {k:.4}, P = {p0:.4} s)"
        );
    }

    #[test]
    fn orientation_keeps_l_fixed_and_turns_at_omega() {
        for w0 in [
            Vector3::new(1.0, 10.0, 1.0),
            Vector3::new(0.01, 10.0, 0.01),
            Vector3::new(-3.0, 1.0, 0.2),
            Vector3::new(0.0, 0.0, 2.0),
        ] {
            let top = FreeTop::new(box_moments(), w0);
            let start = UnitQuaternion::from_euler_angles(0.3, -0.2, 1.1);
            let mut rotation = FreeRotation::new(top, start);
            let l_world = start * box_moments().component_mul(&w0);
            let h = 1e-5;
            for k in 1..100 {
                let t = k as f64 * 0.2;
                let q = rotation.at(t);
                let l = q * box_moments().component_mul(&top.omega(t));
                assert!(
                    (l - l_world).norm() < 1e-13 * l_world.norm(),
                    "L moved: {l} vs {l_world}"
                );
                // Body angular velocity from the rotation: q⁻¹ q̇ ≈ ½ ω_body, central difference.
                let (qa, qb) = (rotation.at(t - h), rotation.at(t + h));
                let rate = (qa.inverse() * qb).scaled_axis() / (2.0 * h);
                let err = (rate - top.omega(t)).norm() / w0.norm();
                assert!(err < 1e-8, "q⁻¹q̇ ≠ ω at t={t}: relative {err:e}");
            }
        }
    }

    #[test]
    fn orientation_agrees_with_a_fine_rk4_integration() {
        // q̇ = ½ q ⊗ ω_body(t) with the exact ω, RK4 at h = 1e-4 over 2 s: error ≈ t ω⁵ h⁴ ≈ 2e-11.
        let w0 = Vector3::new(1.0, 10.0, 1.0);
        let top = FreeTop::new(box_moments(), w0);
        let mut rotation = FreeRotation::new(top, UnitQuaternion::identity());
        let f = |t: f64, q: &nalgebra::Quaternion<f64>| {
            q * nalgebra::Quaternion::from_imag(top.omega(t)) * 0.5
        };
        let mut q = *UnitQuaternion::identity().quaternion();
        let h = 1e-4;
        for k in 0..20000 {
            let t = k as f64 * h;
            let k1 = f(t, &q);
            let k2 = f(t + h / 2.0, &(q + k1 * (h / 2.0)));
            let k3 = f(t + h / 2.0, &(q + k2 * (h / 2.0)));
            let k4 = f(t + h, &(q + k3 * h));
            q += (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
        }
        let angle = rotation_angle_between(&rotation.at(2.0), &UnitQuaternion::new_normalize(q));
        assert!(angle < 1e-10, "closed form vs RK4: {angle:e} rad");
    }

    #[test]
    fn free_body_maps_principal_frame_to_body_frame() {
        // A box whose sides are not in inertia order: principal axes are a permutation.
        let body = Body::solid_box(Vector3::new(0.4, 1.0, 0.1), 1.0).unwrap();
        let w_body = Vector3::new(10.0, 1.0, 1.0);
        let q0 = UnitQuaternion::from_euler_angles(0.1, 0.2, 0.3);
        let l = q0 * (body.inertia_body * w_body);
        let free = FreeBody::new(&body, q0, l);
        assert!((free.omega_body(0.0) - w_body).norm() < 1e-12);
        let mut free = free;
        assert!(rotation_angle_between(&free.orientation(0.0), &q0) < 1e-14);
        // L_world = R(t) I_body ω_body(t) stays put.
        for k in 1..20 {
            let t = k as f64 * 0.5;
            let l_t = free.orientation(t) * (body.inertia_body * free.omega_body(t));
            assert!((l_t - l).norm() < 1e-12 * l.norm(), "L moved at t={t}");
        }
    }
}
