//! The physics core: a rigid body of mass points stepped through the animation loop.
//!
//! Depends on nalgebra only: no terminal, no file formats, no printing. One file per idea:
//!
//! | file | idea |
//! |---|---|
//! | `body` | mass points, barycenter, inertia tensor |
//! | `cloth` | mass–spring sheets: particles, springs, their integrators |
//! | `state` | (x, R or q, P, L) |
//! | `derive` | the derive phase: I⁻¹_world, ω, v |
//! | `effects` | the forces phase: gravity and drag, only when declared |
//! | `free_top` | the torque-free asymmetric top in closed form (a reference) |
//! | `integrators` | the integrate phase, one file per method |
//! | `collision` | the collide phase: obstacles, detection, responses |
//! | `world` | the loop, phase by phase |
//! | `snapshot` | every quantity a user is shown |
//! | `divergence` | the guard against non-finite or runaway states |

pub mod body;
pub mod cloth;
pub mod collision;
pub mod derive;
pub mod divergence;
pub mod effects;
pub mod free_top;
pub mod integrators;
pub mod snapshot;
pub mod state;
pub mod world;

pub use body::{Body, BodyError, InertiaModel};
pub use collision::{Contact, ContactModel, Obstacle, Response};
pub use divergence::Divergence;
pub use effects::{Effect, Effects};
pub use integrators::Integrator;
pub use snapshot::{Energy, Snapshot};
pub use state::{Orientation, State};
pub use world::{Checkpoint, Phase, World};
