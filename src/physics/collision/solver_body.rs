//! Solver bodies and constraint axes, where the contact solvers (`impulse`, `soft_step`)
//! have always found them: they live in the constraint layer (`physics::constraints`), shared
//! with the particle contacts, and are re-exported here.

pub use crate::physics::constraints::{Axis, End, SolverBody};
