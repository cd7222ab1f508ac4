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
//! the step's displacement Δx_i = h v_i(new) is what they took:
//! `W = Σ_springs c((v₀_j − v₀_i)·d̂) d̂·(Δx_j − Δx_i) + Σ_i k_i v₀_i·Δx_i`.

use super::energy::Losses;
use super::loads::ClothLoads;
use super::sheet::{Cloth, StepReport};

/// One step of length `h`, in place.
pub(super) fn step(cloth: &mut Cloth, loads: &ClothLoads, h: f64) -> StepReport {
    cloth.compute_forces(loads);
    let mut dissipated = Losses::default();
    let scratch = &mut cloth.scratch;
    scratch.start.clone_from(&cloth.positions);
    for i in 0..cloth.positions.len() {
        if cloth.pinned[i] {
            continue;
        }
        let v0 = cloth.velocities[i];
        let v1 = v0 + scratch.force[i] * (h / cloth.masses[i]);
        cloth.velocities[i] = v1;
        cloth.positions[i] += v1 * h;
        if loads.drag.is_some() {
            let k = loads.particle_drag(cloth.masses[i], cloth.total_mass);
            dissipated.drag += k * v0.dot(&v1) * h;
        }
    }
    if cloth.springs.iter().any(|s| s.damping > 0.0) {
        for (k, s) in cloth.springs.iter().enumerate() {
            let dx_i = cloth.positions[s.i] - scratch.start[s.i];
            let dx_j = cloth.positions[s.j] - scratch.start[s.j];
            let f_i = scratch.axes[k].direction * scratch.damping[k];
            // The force f_i on i and −f_i on j did work f_i·(Δx_i − Δx_j); the loss is minus it.
            dissipated.damping -= f_i.dot(&(dx_i - dx_j));
        }
    }
    StepReport {
        iterations: 0,
        residual: 0.0,
        dissipated,
    }
}
