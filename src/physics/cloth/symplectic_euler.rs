//! `symplectic-euler` for particles: velocities first, then positions with the new velocities.
//!
//! ```text
//! v_i ← v_i + h f_i(x, v) / m_i        x_i ← x_i + h v_i          (free particles only)
//! ```
//!
//! Explicit, first order, one force evaluation per step. Without damping it is symplectic: the
//! energy error of a stable run stays bounded. It is stable only for h below the limit of
//! `stability` (2/ω_max without damping); above it the highest mode grows by a factor
//! |λ| > 1 every step and the sheet explodes within a few hundred steps.
//!
//! Losses: the damping and drag forces the step used were evaluated at v₀; their work along
//! the step's displacement Δx_i = h v_i(new) is what they took (`sheet`):
//! `W = Σ_springs c((v₀_j − v₀_i)·d̂) d̂·(Δx_j − Δx_i) + Σ_i k_i v₀_i·Δx_i`.

use super::energy::Losses;
use super::loads::ClothLoads;
use super::sheet::{Cloth, StepReport};

/// The velocity half of a step of length `h`: v ← v₀ + h f(x₀, v₀)/m (positions move in
/// [`Cloth::advance_positions`]). The damping magnitudes at v₀ stay in the scratch, and the
/// drag velocities v₀, for the loss accounting.
pub(super) fn velocities(cloth: &mut Cloth, loads: &ClothLoads, h: f64) -> StepReport {
    cloth.compute_forces(loads);
    let scratch = &mut cloth.scratch;
    if loads.drag.is_some() {
        scratch.drag_velocity.clone_from(&cloth.velocities);
    }
    for i in 0..cloth.positions.len() {
        if !cloth.pinned[i] {
            cloth.velocities[i] += scratch.force[i] * (h / cloth.masses[i]);
        }
    }
    StepReport {
        iterations: 0,
        residual: 0.0,
        dissipated: Losses::default(),
    }
}
