//! The physics core: rigid bodies of mass points stepped through the animation loop.
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
//! | `energy` | kinetic, potential, total: of a body and of a world |
//! | `free_top` | the torque-free asymmetric top in closed form (a reference) |
//! | `free_flow` | the exact torque-free flow over one step (the drift of `exact-splitting`) |
//! | `integrators` | the integrate phase, one file per method |
//! | `joints` | joints (constraint rows, multipliers, projection) and springs |
//! | `envelope` | effective-mass systems J W Jᵀ: envelope LDLᵀ (contacts) or Cholesky (joints) |
//! | `system` | the derivative of the whole system when springs or joints couple bodies |
//! | `collision` | the collide phase: obstacles, detection, responses |
//! | `constraints` | the constraint layer: solver bodies (bodies, particles, static things) and rows with bounds |
//! | `world` | the loop, phase by phase, over every body |
//! | `snapshot` | every quantity a user is shown |
//! | `divergence` | the guard against non-finite or runaway states |
//! | `energy_ledger` | where the energy went: drag work, contacts, the hand, and the remainder (drift) |
//! | `hand` | the mouse's drag spring: a body pulled towards the pointer, its work booked |

pub mod body;
pub mod cloth;
pub mod cloth_coupling;
pub mod collision;
pub mod constraints;
pub mod derive;
pub mod divergence;
pub mod effects;
pub mod energy;
pub mod energy_ledger;
pub mod envelope;
pub mod force_arrows;
pub mod free_flow;
pub mod free_top;
pub mod hand;
pub mod integrators;
pub mod joints;
mod simd;
pub mod snapshot;
pub mod state;
pub mod system;
pub mod tuning;
pub mod wire;
pub mod world;

pub use body::{Body, BodyError, InertiaModel};
pub use collision::{
    Against, Contact, ContactModel, Feature, Impacts, Obstacle, Outline, Response, SoftStep,
};
pub use divergence::Divergence;
pub use effects::{Effect, Effects};
pub use energy::Energy;
pub use energy_ledger::{EnergyBalance, EnergyLedger};
pub use integrators::Integrator;
pub use snapshot::{BodyView, ClothView, FixedView, JointView, Snapshot, SpringView, SystemTotals};
pub use state::{Orientation, State};
pub use tuning::Tuning;
pub use world::{Checkpoint, NamedBody, Phase, Stepping, World};
