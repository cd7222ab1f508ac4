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
//! **The solver's tolerance, and why it does not change the physics.** The step above is
//! backward Euler linearised once (one Newton step), whatever the solver; conjugate gradients
//! only approximate its Δv, stopping when the preconditioned residual falls below ε times the
//! right-hand side's, √(rᵀP⁻¹r) ≤ ε √(bᵀP⁻¹b) (`conjugate_gradient`), from the last step's Δv.
//! The default ε = 1e-3 ([`SolverSettings`](super::sheet::SolverSettings)) leaves each step's
//! Δv within ~ε of the exact linearised step, far inside the method's own first-order error,
//! which is ~hω/2 of Δv per step for a motion of frequency ω. Measured on the bench's cube on
//! the 21 × 21 trampoline (dt = 1e-3 s, 2 s: fall, bounces, rest): the cube's height at 2 s
//! moves by 2.0e-5 m between ε = 1e-3 and ε = 1e-10, while backward Euler's own error there is
//! ~1e-2 m (the same run at dt = 5e-4 s and 2.5e-4 s ends 5.9e-3 m and 8.0e-3 m higher:
//! first order, extrapolated 1.0e-2 m) — the solver adds 0.2 % of the method's error (ε = 1e-2
//! would add 5 %, ε = 1e-6 0.0001 % at 5× the iterations: 16.4 per step instead of 3.4). The
//! test `the_default_tolerance_adds_little_to_the_step_error` checks this on a small sheet.
//! A sheet at rest stays exactly at rest (b = 0 gives Δv = 0), and an equilibrium is reached
//! exactly: ε is relative to b, which vanishes there (tests that compare with an independent
//! equilibrium or check the energy step by step set ε = 1e-10). With nothing pinned the
//! translation correction below keeps the momentum exact whatever ε.
//!
//! Losses: damping and drag enter the step evaluated at the *new* velocities (at the start's
//! directions d̂₀: the linearisation of the damping force, exact for it); their work along the
//! step's displacement is what they took (`sheet`), with Δx = h v₁ never negative:
//! `W = h Σ_springs c ((v₁_j − v₁_i)·d̂₀)² + h Σ_i k_drag,i |v₁_i|²`.

use super::conjugate_gradient::{Block, SpringOrder, Symmetric3};
use super::energy::Losses;
use super::loads::ClothLoads;
use super::sheet::{Cloth, StepReport};
use super::ties::{BodyJoints, Tie, TiedBody};
use nalgebra::Vector3;

/// The velocity half of a step of length `h`: v ← v₀ + Δv (positions move in
/// [`Cloth::advance_positions`]). Leaves in the scratch the damping forces
/// `c ((v₁_j − v₁_i)·d̂₀) d̂₀` and drag velocities v₁ the step used, for the loss accounting.
pub(super) fn velocities(cloth: &mut Cloth, loads: &ClothLoads, h: f64) -> StepReport {
    assemble(cloth, loads, h);
    let work = &mut cloth.scratch.solver;
    let outcome = work.solve(cloth.solver.tolerance, cloth.solver.max_iterations);
    let n = cloth.positions.len();
    if work.pinned.is_empty() {
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
    finish(cloth, loads);
    StepReport {
        iterations: outcome.iterations,
        residual: outcome.relative_residual,
        dissipated: Losses::default(),
    }
}

/// The tied step (`ties`): after [`assemble`], solves with the ties and sets
/// v = v₀ + Δv (v₀ the velocities at the start of the step); may be called again with other
/// ties (a released contact) before [`finish`].
pub(super) fn solve_tied(
    cloth: &mut Cloth,
    ties: &mut [Tie],
    bodies: &mut [TiedBody],
    joints: &BodyJoints,
) -> StepReport {
    let work = &mut cloth.scratch.solver;
    let v0 = &cloth.scratch.start_velocity;
    let outcome = work.solve_tied(
        ties,
        bodies,
        joints,
        v0,
        cloth.solver.tolerance,
        cloth.solver.max_iterations,
    );
    for ((v, &pinned), (v0, dv)) in (cloth.velocities.iter_mut())
        .zip(&cloth.pinned)
        .zip(v0.iter().zip(&work.solution))
    {
        *v = if pinned { Vector3::zeros() } else { v0 + dv };
    }
    StepReport {
        iterations: outcome.iterations,
        residual: outcome.relative_residual,
        dissipated: Losses::default(),
    }
}

/// The step's setup: a_i, b_i, the springs' blocks and the block-Jacobi preconditioner.
pub(super) fn assemble(cloth: &mut Cloth, loads: &ClothLoads, h: f64) {
    #[cfg(target_arch = "x86_64")]
    if super::avx2() {
        // SAFETY: `assemble_avx2` is safe but for its target feature: calling it needs a CPU
        // with AVX2, which `avx2` checked just above.
        unsafe { assemble_avx2(cloth, loads, h) };
        return;
    }
    assemble_plain(cloth, loads, h);
}

/// [`assemble`] compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn assemble_avx2(cloth: &mut Cloth, loads: &ClothLoads, h: f64) {
    assemble_plain(cloth, loads, h);
}

/// [`assemble`] for any CPU.
#[inline(always)]
fn assemble_plain(cloth: &mut Cloth, loads: &ClothLoads, h: f64) {
    let n = cloth.positions.len();
    let scratch = &mut cloth.scratch;
    let work = &mut scratch.solver;
    work.resize(&cloth.pinned);
    work.ties.new_step();
    let (x, v0) = (&cloth.positions, &cloth.velocities);
    // a_i = m_i + h k_drag,i;  b_i = h (m_i g − k_drag,i v₀_i);  P_i = a_i I.
    let gravity = loads.gravity.unwrap_or_else(Vector3::zeros);
    for (((a, b), p), (&m, v)) in (work.diagonal.iter_mut())
        .zip(work.rhs.iter_mut())
        .zip(work.preconditioner.iter_mut())
        .zip(cloth.masses.iter().zip(v0))
    {
        let drag = loads.particle_drag(m, cloth.total_mass);
        *a = m + h * drag;
        *b = (gravity * m - v * drag) * h;
        *p = Symmetric3::diagonal(*a);
    }
    // One pass over the springs: b_s = h f₀ − h² K v₀ (f₀ with the damping at v₀) and the
    // block S = h c d̂d̂ᵀ + h² k ((1 − t) d̂d̂ᵀ + t I); then per particle b_i ± Σ b_s and
    // P_i = a_i I + Σ S, summed in the mirror-symmetric order of `conjugate_gradient` (or
    // scattered when the springs are not the grid's). A spring with both ends pinned gets an
    // empty block (it acts on no free particle).
    let springs = &cloth.springs;
    if work.order.springs != springs.len() || work.order.slots.len() != n {
        work.order = SpringOrder::of_grid(cloth.count, springs.iter().map(|s| (s.i, s.j, s.kind)))
            .unwrap_or_default();
    }
    let gathered = work.order.springs == springs.len() && work.order.slots.len() == n;
    let pinned = &cloth.pinned[..n];
    work.blocks.resize(springs.len(), Block::default());
    work.terms.terms.resize(springs.len() + 1, Vector3::zeros());
    work.matrices
        .resize(springs.len() + 1, Symmetric3::default());
    let (x, v0) = (&x[..n], &v0[..n]);
    let rhs = &mut work.rhs[..n];
    let preconditioner = &mut work.preconditioner[..n];
    for (((s, block), term), matrix) in springs
        .iter()
        .zip(work.blocks.iter_mut())
        .zip(work.terms.terms.iter_mut())
        .zip(work.matrices.iter_mut())
    {
        let (i, j) = (s.i, s.j);
        let d = x[j] - x[i];
        let length = d.norm();
        let (direction, t) = if length > 0.0 {
            let inverse = 1.0 / length;
            (d * inverse, (1.0 - s.rest_length * inverse).max(0.0))
        } else {
            (Vector3::zeros(), 0.0)
        };
        let dv = v0[j] - v0[i];
        let dv_along = direction.dot(&dv);
        let hhk = h * h * s.stiffness;
        let along = h * s.damping + hhk * (1.0 - t);
        let across = hhk * t;
        // h k (ℓ − ℓ₀) d̂ + [h c + h² k (1 − t)] (d̂·Δv) d̂ + h² k t Δv,   Δv = v₀_j − v₀_i
        let b = direction * (h * s.stiffness * (length - s.rest_length) + along * dv_along)
            + dv * across;
        *block = if pinned[i] && pinned[j] {
            Block::default()
        } else {
            Block {
                i: i as u32,
                j: j as u32,
                along,
                across,
                direction,
            }
        };
        *matrix = Symmetric3::of(block);
        if gathered {
            *term = b;
        } else {
            rhs[i] += b;
            rhs[j] -= b;
            preconditioner[i].add(matrix);
            preconditioner[j].add(matrix);
        }
    }
    if let Some(stencil) = work.order.stencil.as_mut() {
        stencil.load(&work.blocks);
    }
    if gathered {
        work.terms.terms[springs.len()] = Vector3::zeros();
        work.matrices[springs.len()] = Symmetric3::default();
        // (Two slices of one length read at the same slots: one bounds check serves both.)
        let terms = &work.terms.terms[..=springs.len()];
        let matrices = &work.matrices[..=springs.len()];
        for (k, (b, p)) in rhs.iter_mut().zip(preconditioner.iter_mut()).enumerate() {
            *b += work.order.gather(k, terms);
            p.add(&work.order.gather_blocks(k, matrices));
        }
    }
}

/// What the step's damping and drag forces were: at v₁, along d̂₀ (a spring with both ends
/// pinned has v₁_j − v₁_i = 0: no force), for the loss accounting.
pub(super) fn finish(cloth: &mut Cloth, loads: &ClothLoads) {
    #[cfg(target_arch = "x86_64")]
    if super::avx2() {
        // SAFETY: `finish_avx2` is safe but for its target feature: calling it needs a CPU
        // with AVX2, which `avx2` checked just above.
        unsafe { finish_avx2(cloth, loads) };
        return;
    }
    finish_plain(cloth, loads);
}

/// [`finish`] compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn finish_avx2(cloth: &mut Cloth, loads: &ClothLoads) {
    finish_plain(cloth, loads);
}

/// [`finish`] for any CPU.
#[inline(always)]
fn finish_plain(cloth: &mut Cloth, loads: &ClothLoads) {
    let n = cloth.positions.len();
    let scratch = &mut cloth.scratch;
    let work = &scratch.solver;
    let springs = &cloth.springs;
    let v1 = &cloth.velocities;
    scratch.damping_force.clear();
    if springs.iter().any(|s| s.damping > 0.0) {
        scratch.damping_force.resize(n, Vector3::zeros());
        // (Both slices of length n: one bounds check per end serves the two.)
        let (v1, force) = (&v1[..n], &mut scratch.damping_force[..n]);
        for (s, b) in springs.iter().zip(&work.blocks) {
            let f = b.direction * (s.damping * (v1[s.j] - v1[s.i]).dot(&b.direction));
            force[s.i] += f;
            force[s.j] -= f;
        }
    }
    if loads.drag.is_some() {
        scratch.drag_velocity.clone_from(v1);
    }
}

#[cfg(test)]
mod tests {
    use super::super::sheet::SolverSettings;
    use super::super::spec::{ClothSpec, Pinning};
    use super::super::ClothIntegrator;
    use super::*;

    /// An 11 × 11 trampoline (edges pinned) thrown upwards, under gravity, with damping.
    fn thrown_trampoline(tolerance: f64) -> Cloth {
        let mut spec = ClothSpec::new([1.0, 1.0], [11, 11], 0.5, 2000.0);
        spec.shear = 500.0;
        spec.damping = 2.0;
        spec.pinned = Pinning::Edges;
        spec.velocity = Vector3::new(0.0, 1.0, 0.0);
        spec.integrator = ClothIntegrator::ImplicitEuler;
        let mut cloth = Cloth::new(&spec).unwrap();
        cloth.solver.tolerance = tolerance;
        cloth
    }

    /// The positions after `seconds` at step `dt`.
    fn run(mut cloth: Cloth, dt: f64, seconds: f64) -> Vec<Vector3<f64>> {
        let loads = ClothLoads {
            gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
            drag: None,
        };
        for _ in 0..(seconds / dt).round() as usize {
            cloth.step(&loads, dt);
        }
        cloth.positions
    }

    fn max_distance(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_default_tolerance_adds_little_to_the_step_error() {
        // The same linearised backward Euler solved to ε = 1e-12 is the reference of the
        // method; the method's own error at h is estimated by halving h (first order: the
        // error at h is about twice the change, so the change is a lower bound of it).
        let (h, seconds) = (2e-3, 0.3);
        let default = SolverSettings::default().tolerance;
        let exact = run(thrown_trampoline(1e-12), h, seconds);
        let solved = run(thrown_trampoline(default), h, seconds);
        let halved = run(thrown_trampoline(1e-12), h / 2.0, seconds);
        let solver_error = max_distance(&solved, &exact);
        let step_error = max_distance(&halved, &exact);
        eprintln!("ε = {default:e}: solver {solver_error:.3e} m, step {step_error:.3e} m");
        assert!(step_error > 1e-3, "the sheet moved: {step_error:e}");
        assert!(
            solver_error < 0.01 * step_error,
            "solver {solver_error:e} m vs the step's own {step_error:e} m"
        );
    }
}
