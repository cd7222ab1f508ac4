//! Mass–spring sheets (`[[cloth]]`): particles on a grid joined by stretch, shear and bend
//! springs, stepped by their own particle integrator — the report's proposed next step.
//!
//! | file | idea |
//! |---|---|
//! | `spec` | the validated parameters of a sheet, pinning |
//! | `sheet` | particles and springs built from a spec; impulses for contacts with bodies |
//! | `spring` | one damped Hooke spring: force, energy, Jacobians |
//! | `loads` | the forces: springs, declared gravity and drag, nothing else |
//! | `integrator` | the particle integrators by name |
//! | `symplectic_euler` | the explicit step |
//! | `implicit_euler` | backward Euler linearised once (Baraff & Witkin 1998) |
//! | `conjugate_gradient` | the implicit step's solve: filtered block-Jacobi PCG |
//! | `stencil` | that solve's product on a grid sheet, by spring direction (same bits, faster) |
//! | `ties` | contacts and attachments inside that solve: Baraff–Witkin's filter, the body an unknown |
//! | `stability` | the explicit limit 2/ω_max by power iteration |
//! | `energy` | kinetic, spring and gravitational energy; losses |
//! | `contact` | particles against fixed obstacles |
//!
//! **AVX builds.** The implicit step's hot functions (`stencil`'s product, `implicit_euler`'s
//! assemble and finish, `conjugate_gradient`'s solve, `ties`' solve) are compiled twice, for
//! any x86-64 CPU (SSE2) and with AVX (`#[target_feature]`), and run the AVX build when the CPU
//! has it (checked at run time; each call's `SAFETY` comment says why it is sound). The same
//! source, the same operations on each number in the same order (a sum stays a sequential
//! sum; AVX alone has no FMA to contract into): the same bits on either build (the stencil's
//! test compares them; `examples/cloth_steps` prints the checksums). Measured by callgrind on
//! the cube on the 21 × 21 trampoline: −26 % instructions over the 2 s cycle.

mod conjugate_gradient;
pub mod contact;
pub mod energy;
pub mod implicit_euler;
pub mod integrator;
pub mod loads;
pub mod sheet;
pub mod spec;
pub mod spring;
pub mod stability;
mod stencil;
pub mod symplectic_euler;
pub mod ties;

pub use contact::{ContactReport, ParticleContact};
pub use energy::{ClothEnergy, Losses};
pub use integrator::ClothIntegrator;
pub use loads::ClothLoads;
pub use sheet::{Cloth, Held, SolveCounts, SolverSettings, StepReport};
pub use spec::{Attach, ClothSpec, ClothSpecError, Pinning};
pub use spring::{Spring, SpringKind};
pub use stability::ExplicitLimit;
pub use ties::{BodyJoints, Tie, TieKind, TiedBody};

/// How text names a cloth: "cloth sheet" for a cloth named `sheet`, but just "cloth" or
/// "cloth1" for one whose name already says it (never "cloth cloth").
pub fn label(name: &str) -> String {
    if name.to_lowercase().starts_with("cloth") {
        name.to_string()
    } else {
        format!("cloth {name}")
    }
}

#[cfg(test)]
mod tests {
    use super::label;

    #[test]
    fn a_cloth_is_named_once() {
        assert_eq!(label("sheet"), "cloth sheet");
        assert_eq!(label("cloth"), "cloth");
        assert_eq!(label("cloth2"), "cloth2");
        assert_eq!(label("Cloth of gold"), "Cloth of gold");
    }
}
