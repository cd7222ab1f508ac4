//! The constraint layer: what every constraint solver works on, whatever it holds.
//!
//! Every moving thing is a **solver body** (`solver_body`): a rigid body, a cloth particle
//! (one without rotational inertia), or a static thing (a fixed body or an obstacle: no
//! inverse mass, no inverse inertia). Every constraint is made of **rows** (`row`): one
//! scalar direction between two ends, with bounds [lo, hi] on its accumulated impulse and a
//! bias. For one row with Jacobian J over the velocities v of its two ends and W their
//! inverse masses,
//!
//! ```text
//! k  = J W Jᵀ                                    effective inverse mass
//! λ' = clamp(λ − (J·v + b)/k, lo, hi)            one projected Gauss–Seidel update
//! v ← v + W Jᵀ (λ' − λ),   λ ← λ'                equal and opposite on the two ends
//! ```
//!
//! | file | idea |
//! |---|---|
//! | `solver_body` | solver bodies (v, ω, L, 1/M, I⁻¹): a body, a particle, a static thing |
//! | `row` | axes between two ends (J, k, the rate J·v, an impulse along J) and rows (an axis with bounds [lo, hi], bias b, position error C and owner, the projected update): contact normals [0, ∞), joint rows (−∞, ∞), limits' stops [0, ∞), motors ±F dt; a contact's friction pair (two tangent impulses within the disk μ λ_n) |
//! | `attachment` | a particle held at a body's point: three equality rows between a particle end and a body end, their 3 × 3 block of K = J W Jᵀ |
//! | `particle_contact` | particles against a body (rows [0, ∞) along the normal, friction within the cone, swept) or a static thing (one exact update) |
//!
//! Users: the rigid contact solvers (`collision::impulse`, `collision::soft_step`, through
//! the re-export `collision::solver_body`; `impulse` keeps each contact's normal as a
//! [`Row`] and its friction as a [`Friction`] pair), and the particle contacts of a
//! `symplectic-euler` cloth (`cloth::contact` against obstacles, `cloth_coupling::explicit`
//! against bodies, through each response's particle law, `collision::particle`), an explicit
//! cloth's attachments (`cloth_coupling::attachments`: its per-body direct solve over the
//! rows' blocks), the implicit cloth's tied solve (`cloth::ties`: each body end a
//! [`SolverBody`] with the solve's mass matrix beside it), and the joints (`joints`: every equality, limit and motor row is a
//! [`Row`], built by one file per joint kind under `joints::kinds`). The layer depends on
//! nalgebra only, no other `physics` folder.

pub mod attachment;
pub mod particle_contact;
pub mod row;
pub mod solver_body;

pub use attachment::Attachment;
pub use row::{within_disc, Axis, End, Friction, Row};
pub use solver_body::SolverBody;
