//! Particles against bodies, both ways: a cloth particle is a point, a body its convex shape.
//!
//! Which path a cloth takes depends on its integrator:
//! - `implicit-euler`: [`tied_step`] holds every contact (bodies and obstacles) and every
//!   attachment *inside* backward Euler's linear solve (`cloth::ties`, Baraff & Witkin's
//!   constraint filter with the body's velocity change as an unknown of the same solve),
//!   each tied particle ending the step on the body's surface; the velocity pass below is
//!   not used, and the collide phase's push-out only handles what is still more than
//!   [`SLOP`] inside after the positions moved (nothing, on lesson 16). This is the path
//!   under a response whose particle law ties (`collision::particle`: `impulse`); under
//!   the others (`seed`, `soft-step`) the solve holds the attachments only and the contacts
//!   take the explicit passes below after it.
//! - `symplectic-euler`: two passes for contacts ([`explicit`]: on velocities, then what is
//!   left inside after the positions moved), and [`hold_attachments`] for its attachments
//!   (impulses after the velocity half, one small direct solve per body over the constraint
//!   layer's attachment rows, `constraints::attachment`).
//!
//! Attached bodies stay consistent within the step: the joints on a body that moves in the
//! implicit solve are held inside it ([`tied_step`], "Joints"), and particles attached to a
//! body the rigid collide phase then moves are carried with it ([`carry_attachments`]),
//! having aimed at where its last move put it ([`BodyMove`]).
//!
//! One file per path: [`explicit`] (the two passes of a `symplectic-euler` cloth), [`tied`]
//! (contacts and attachments inside an `implicit-euler` cloth's solve) and [`attachments`]
//! (an explicit cloth's attachments, and attached particles carried after the collide phase).

pub mod attachments;
pub mod explicit;
pub mod tied;

pub use attachments::{
    carry_attachments, hold_attachments, AttachReport, BodyMove, Carried, Holding,
};
pub use explicit::{approach_bodies, collide_bodies, Approach, SWEEPS};
pub use tied::{tied_step, TiedReport, TiedScene, TIE_ROUNDS};

use crate::physics::body::Body;
use crate::physics::cloth::Cloth;
use crate::physics::constraints::SolverBody;
use crate::physics::state::State;
use nalgebra::Vector3;

/// A depth (m) the collide phase leaves to an `implicit-euler` cloth's particles: its ties
/// put them on the surface, up to round-off (the body's turn is made up exactly, see the
/// end of [`tied_step`]); a particle a step's last round let go may end a few nm inside,
/// and the next step's tie moves it with the surface (pushing it out would stretch its
/// springs: energy made).
pub const SLOP: f64 = 1e-8;

/// A particle held to a body's point (`attach`): its offset in the body's frame at t = 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Attachment {
    pub particle: usize,
    pub body: usize,
    /// The particle's position in the body's frame (relative to the barycenter), m.
    pub offset_body: Vector3<f64>,
}

/// A body's solver body at `state` (the constraint layer's, `constraints::SolverBody`):
/// V = P/M, L, 1/M and ω = I⁻¹ L with I⁻¹ = R I⁻¹_body Rᵀ at its orientation. What every
/// path here reads a body's velocities and inverse mass properties from (a fixed body: all 0).
fn solver_body(body: &Body, state: &State) -> SolverBody {
    let rotation = state.orientation.matrix();
    SolverBody::new(
        state.linear_momentum * body.inv_mass,
        state.angular_momentum,
        body.inv_mass,
        rotation * body.inv_inertia_body * rotation.transpose(),
    )
}

/// Moves a body by the position part of a correction (Y_V, Y_ω) over a step of length h:
/// x += h Y_V, and a turn by the rotation of vector h Y_ω (exact, not linearised).
fn move_body(state: &mut State, y_v: &Vector3<f64>, y_w: &Vector3<f64>, dt: f64) {
    state.position += y_v * dt;
    let turn = nalgebra::UnitQuaternion::from_scaled_axis(y_w * dt);
    state.orientation = match state.orientation {
        super::state::Orientation::Quaternion(q) => super::state::Orientation::Quaternion(turn * q),
        super::state::Orientation::Matrix(m) => {
            super::state::Orientation::Matrix(turn.to_rotation_matrix().matrix() * m)
        }
    };
}

/// (R(h ω) − I) r − h ω × r: where a body's point at arm r ends after the exact turn by
/// h ω, less where its linearisation puts it, m.
fn turn_gap(omega: &Vector3<f64>, arm: &Vector3<f64>, dt: f64) -> Vector3<f64> {
    let turn = nalgebra::UnitQuaternion::from_scaled_axis(omega * dt);
    turn * arm - arm - omega.cross(arm) * dt
}

/// Moves particle `i`'s end of step by `gap` (its velocity by gap/h) and gives the body the
/// opposite momentum at its point, so that particle + body keep theirs.
/// Returns the impulse the particle took, N·s.
fn close_gap(
    cloth: &mut Cloth,
    i: usize,
    state: &mut State,
    arm: &Vector3<f64>,
    gap: &Vector3<f64>,
    dt: f64,
) -> Vector3<f64> {
    let impulse = gap * (cloth.masses[i] / dt);
    cloth.apply_impulse(i, &impulse);
    state.linear_momentum -= impulse;
    state.angular_momentum -= arm.cross(&impulse);
    impulse
}
