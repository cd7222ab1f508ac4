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
//! **AVX2 builds.** The implicit step's hot functions (`stencil`'s product, `implicit_euler`'s
//! assemble and finish, `conjugate_gradient`'s solve, `ties`' solve) are compiled twice, for
//! any x86-64 CPU (SSE2) and with AVX2 (`#[target_feature]`), and run the AVX2 build when the
//! CPU has it (checked at run time; each call's `SAFETY` comment says why it is sound). The
//! same source, the same operations on each number in the same order (a sum stays a
//! sequential sum; AVX2 has no FMA to contract into, FMA is a feature of its own, not enabled):
//! the same bits on either build (tests compare them: the stencil's product, and the cube
//! landing on the trampoline with the sheet alone, AVX2 against plain; `examples/cloth_steps`
//! prints the checksums). Measured by callgrind on the cube on the 21 × 21 trampoline: −29 %
//! instructions over the 2 s cycle.

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

#[cfg(target_arch = "x86_64")]
use super::simd::avx2;

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

    /// The bits of lesson 16's cube on the 21 × 21 trampoline (the tied solve) after its
    /// landing, and of the sheet alone after 50 steps of 5 ms (the untied
    /// solve), with the AVX2 builds or the plain ones (`plain`).
    fn bits(plain: bool) -> Vec<u64> {
        use nalgebra::Vector3;
        crate::physics::simd::set_plain(plain);
        let path = std::path::Path::new("lessons/16-trampoline.toml");
        let lesson = include_str!("../../../lessons/16-trampoline.toml");
        let mut world = crate::scene::parse(lesson, path).unwrap().scene.world();
        let mut touched = false;
        for _ in 0..300 {
            world.step();
            touched |= world.cloth_body_contacts(0) > 0;
        }
        assert!(touched, "the cube lands within 0.3 s");
        let mut spec = super::ClothSpec::new([2.0, 2.0], [21, 21], 2.0, 5000.0);
        spec.shear = 1000.0;
        spec.damping = 0.5;
        spec.pinned = super::Pinning::Edges;
        spec.integrator = super::ClothIntegrator::ImplicitEuler;
        let mut sheet = super::Cloth::new(&spec).unwrap();
        let loads = super::ClothLoads {
            gravity: Some(Vector3::new(0.0, -9.81, 0.0)),
            drag: None,
        };
        for _ in 0..50 {
            sheet.step(&loads, 5e-3);
        }
        crate::physics::simd::set_plain(false);
        let (cloth, state) = (&world.cloths()[0], world.state());
        let vectors = (cloth.positions.iter().chain(&cloth.velocities))
            .chain(sheet.positions.iter().chain(&sheet.velocities))
            .chain([
                &state.position,
                &state.linear_momentum,
                &state.angular_momentum,
            ]);
        let rotation = state.orientation.matrix();
        (vectors.flat_map(|v| v.iter()).chain(rotation.iter()))
            .map(|x| x.to_bits())
            .chain([
                cloth.losses.damping.to_bits(),
                sheet.losses.damping.to_bits(),
            ])
            .collect()
    }

    #[test]
    fn the_avx2_builds_have_the_bits_of_the_plain_ones() {
        // On a CPU without AVX2 both runs are plain: the test then holds trivially.
        assert!(bits(false) == bits(true), "AVX2 and plain builds differ");
    }

    #[test]
    fn a_cloth_is_named_once() {
        assert_eq!(label("sheet"), "cloth sheet");
        assert_eq!(label("cloth"), "cloth");
        assert_eq!(label("cloth2"), "cloth2");
        assert_eq!(label("Cloth of gold"), "Cloth of gold");
    }
}
