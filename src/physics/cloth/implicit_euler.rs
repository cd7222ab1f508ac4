//! `implicit-euler` for particles: backward Euler linearised once per step (Baraff & Witkin
//! 1998, "Large Steps in Cloth Simulation").
//!
//! Backward Euler asks for v₁ = v₀ + h M⁻¹ f(x₀ + h v₁, v₁). One Newton step from (x₀, v₀):
//!
//! ```text
//! f(x₀ + Δx, v₀ + Δv) ≈ f₀ + ∂f/∂x Δx + ∂f/∂v Δv,      Δx = h (v₀ + Δv)
//! (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f₀ + h ∂f/∂x v₀)
//! v₁ = v₀ + Δv,      x₁ = x₀ + h v₁
//! ```
//!
//! With K = −∂f/∂x (the springs' clamped stiffness blocks k J, see `spring`) and
//! C = −∂f/∂v (the springs' c d̂d̂ᵀ and the drag k_drag,i I), the matrix
//! `A = M + h C + h² K` is symmetric positive definite: it is solved by conjugate gradients
//! (`conjugate_gradient`), with pinned particles filtered out (Δv = 0 there) and the last
//! step's Δv as the starting guess.
//!
//! **Momentum.** Spring blocks annihilate a uniform translation, so the exact solution has
//! `Σ a_i Δv_i = Σ b_i`: with nothing pinned, the momentum changes only by the external
//! forces. Conjugate gradients stopped at a tolerance leave a residual whose sum is not zero;
//! when nothing is pinned the step adds to every Δv_i the uniform correction
//! `(Σ b_i − Σ a_i Δv_i)/Σ a_i` (a translation, which changes no spring), so the linear momentum
//! is kept to round-off whatever the tolerance. (Angular momentum is not kept exactly by
//! backward Euler: its per-step change is O(h²), from the springs' transverse stiffness.)
//!
//! Stable for every h, first order. On a linear undamped mode of frequency ω the step's
//! amplification factors are 1/(1 ± ihω), of modulus 1/√(1 + h²ω²) < 1: the mode loses energy
//! by the factor 1/(1 + h²ω²) per step, numerical damping that grows with h. So the energy of an undamped sheet never rises (up to the
//! linearisation and the solver's tolerance) — it falls, which is the method's known artifact.
//!
//! Losses: damping and drag enter the step evaluated at the *new* velocities (at the start's
//! directions d̂₀: the linearisation of the damping force, exact for it); their work along the
//! step's displacement is what they took (`sheet`), with Δx = h v₁ never negative:
//! `W = h Σ_springs c ((v₁_j − v₁_i)·d̂₀)² + h Σ_i k_drag,i |v₁_i|²`.

use super::conjugate_gradient::Block;
use super::energy::Losses;
use super::loads::ClothLoads;
use super::sheet::{Cloth, StepReport};
use nalgebra::Vector3;

/// The velocity half of a step of length `h`: v ← v₀ + Δv (positions move in
/// [`Cloth::advance_positions`]). Leaves in the scratch the damping magnitudes
/// `c (v₁_j − v₁_i)·d̂₀` and drag velocities v₁ the step used, for the loss accounting.
pub(super) fn velocities(cloth: &mut Cloth, loads: &ClothLoads, h: f64) -> StepReport {
    cloth.compute_forces(loads);
    let n = cloth.positions.len();
    let scratch = &mut cloth.scratch;
    let work = &mut scratch.solver;
    work.resize(n);
    // a_i = m_i + h k_drag,i;  b = h f₀ − h² K v₀.
    for i in 0..n {
        work.diagonal[i] =
            cloth.masses[i] + h * loads.particle_drag(cloth.masses[i], cloth.total_mass);
        work.rhs[i] = scratch.force[i] * h;
    }
    work.blocks.clear();
    let v0 = &cloth.velocities;
    for (s, axis) in cloth.springs.iter().zip(&scratch.axes) {
        let kv = s.stiffness_times(axis, &(v0[s.i] - v0[s.j])) * (h * h);
        work.rhs[s.i] -= kv;
        work.rhs[s.j] += kv;
        // S = h c d̂d̂ᵀ + h² k ((1 − t) d̂d̂ᵀ + t I)
        let t = s.transverse(axis);
        work.blocks.push(Block {
            direction: axis.direction,
            along: h * s.damping + h * h * s.stiffness * (1.0 - t),
            across: h * h * s.stiffness * t,
        });
    }
    let outcome = work.solve(
        &cloth.springs,
        &cloth.pinned,
        cloth.solver.tolerance,
        cloth.solver.max_iterations,
    );
    if !cloth.pinned.iter().any(|&p| p) {
        // Translation correction (module doc): Σ a_i Δv_i = Σ b_i exactly.
        let a: f64 = work.diagonal.iter().sum();
        let mut gap = Vector3::zeros();
        for i in 0..n {
            gap += work.rhs[i] - work.solution[i] * work.diagonal[i];
        }
        let shift = gap / a;
        work.solution.iter_mut().for_each(|x| *x += shift);
    }
    for i in 0..n {
        if !cloth.pinned[i] {
            cloth.velocities[i] += work.solution[i];
        }
    }
    // What the step's damping and drag forces were: at v₁, along d̂₀.
    let v1 = &cloth.velocities;
    if !scratch.damping_force.is_empty() {
        scratch
            .damping_force
            .iter_mut()
            .for_each(|f| *f = Vector3::zeros());
        for (s, axis) in cloth.springs.iter().zip(&scratch.axes) {
            let f = axis.direction * s.damping_magnitude(axis, v1);
            scratch.damping_force[s.i] += f;
            scratch.damping_force[s.j] -= f;
        }
    }
    if loads.drag.is_some() {
        scratch.drag_velocity.clone_from(v1);
    }
    StepReport {
        iterations: outcome.iterations,
        residual: outcome.relative_residual,
        dissipated: Losses::default(),
    }
}
