//! Helpers shared by the hard-case and property tests: free bodies, the closed-form free
//! asymmetric top, and sign-change detection.

#![allow(dead_code)]

use nalgebra::Vector3;
use tumble::physics::{Body, Effects, Integrator, State, World};

/// The issue's box: 1.0 × 0.4 × 0.1 m, 1 kg, uniform solid. Its principal axes are the body axes:
/// I = M/12 · diag(b² + c², a² + c², a² + b²) = diag(0.0141667, 0.0841667, 0.0966667) kg·m², so x
/// is the minor axis, y the intermediate, z the major.
pub fn racket() -> Body {
    Body::solid_box(Vector3::new(1.0, 0.4, 0.1), 1.0).expect("a valid box")
}

/// A torque-free world (no effects, no obstacles) with the body started at the origin, identity
/// orientation, spinning at `omega_body` (body = world frame at t = 0).
pub fn free_world(body: &Body, integrator: Integrator, dt: f64, omega_body: Vector3<f64>) -> World {
    let mut state = State::at_rest();
    state.angular_momentum = body.inertia_body * omega_body;
    World::new(
        body.clone(),
        Effects::default(),
        Vec::new(),
        None,
        integrator,
        dt,
        state,
    )
}

/// ω in the body frame: `ω_body = I⁻¹_body Rᵀ L`.
pub fn omega_body(world: &World) -> Vector3<f64> {
    let r = world.state().orientation.matrix();
    world.body().inv_inertia_body * (r.transpose() * world.state().angular_momentum)
}

/// Complete elliptic integral of the first kind K(k) from the complementary modulus k' = √(1−k²),
/// by the arithmetic–geometric mean: `K = π / (2 AGM(1, k'))`.
pub fn elliptic_k_from_complement(k_complement: f64) -> f64 {
    let (mut a, mut b) = (1.0_f64, k_complement);
    // Quadratic convergence: 6 rounds reach round-off for k' ≥ 1e-10; 40 is a safe cap, and
    // a ≥ b never stalls on a one-ulp oscillation.
    for _ in 0..40 {
        if a - b <= 4.0 * f64::EPSILON * a {
            break;
        }
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The closed-form time between successive sign changes of ω₂ (the intermediate-axis component)
/// of a free asymmetric top, `2K(k)/λ` (Landau & Lifshitz, Mechanics §37), from the principal
/// moments I₁ < I₂ < I₃ and the body-frame ω₀ in the principal frame.
///
/// ```text
/// M² = Σ Iᵢ² ωᵢ² (|L|²),  2E = Σ Iᵢ ωᵢ²,  D = M² − 2E I₂ = Σ Iᵢ (Iᵢ − I₂) ωᵢ²   (no cancellation)
/// polhode about I₃ if D > 0 (a = 3, c = 1), about I₁ if D < 0 (a = 1, c = 3)
/// λ   = √((I_a − I₂)(M² − 2E I_c) / (I₁ I₂ I₃))
/// k'² = 1 − k² = (I_a − I_c)(M² − 2E I₂) / ((I_a − I₂)(M² − 2E I_c))
/// ```
/// ω₂ ∝ sn(λt, k), which changes sign every 2K in its argument.
pub fn flip_spacing(moments: Vector3<f64>, omega: Vector3<f64>) -> f64 {
    let i = moments;
    let d: f64 = (0..3)
        .map(|n| i[n] * (i[n] - i[1]) * omega[n].powi(2))
        .sum();
    let (a, c) = if d > 0.0 { (2, 0) } else { (0, 2) };
    // M² − 2E I_c = Σ Iₙ (Iₙ − I_c) ωₙ², again without cancellation.
    let m2_minus_c: f64 = (0..3)
        .map(|n| i[n] * (i[n] - i[c]) * omega[n].powi(2))
        .sum();
    let lambda = ((i[a] - i[1]) * m2_minus_c / (i[0] * i[1] * i[2])).sqrt();
    let k_complement_sq = (i[a] - i[c]) * d / ((i[a] - i[1]) * m2_minus_c);
    2.0 * elliptic_k_from_complement(k_complement_sq.sqrt()) / lambda
}

/// Times at which `signal` changes sign between samples (linear interpolation).
pub fn sign_changes(samples: &[(f64, f64)]) -> Vec<f64> {
    samples
        .windows(2)
        .filter(|w| (w[0].1 > 0.0) != (w[1].1 > 0.0))
        .map(|w| {
            let ((t0, y0), (t1, y1)) = (w[0], w[1]);
            t0 + (t1 - t0) * y0 / (y0 - y1)
        })
        .collect()
}

/// Runs a world for `steps` steps, sampling ω_body after each.
pub fn omega_history(world: &mut World, steps: usize) -> Vec<(f64, Vector3<f64>)> {
    let mut out = Vec::with_capacity(steps + 1);
    out.push((world.time(), omega_body(world)));
    for _ in 0..steps {
        world.step();
        out.push((world.time(), omega_body(world)));
    }
    out
}
