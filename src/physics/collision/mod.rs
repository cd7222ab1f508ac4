//! The *collide* phase: obstacles, contact detection per body vertex, and the two responses.
//!
//! Detection follows the report: every body vertex `pᵢ = x + R r₀ᵢ` is tested against every
//! declared obstacle. The phase runs only when the scene declares obstacles.
//!
//! | file | idea |
//! |---|---|
//! | `detect` | is a vertex inside an obstacle (depth, normal); the swept test along its motion |
//! | `seed` | the report's response, reproduced with its failures |
//! | `impulse` | impulses with restitution and Coulomb friction, energy never added |

pub mod detect;
pub mod geometry;
pub mod impulse;
pub mod seed;

use super::body::Body;
use super::effects::Loads;
use super::snapshot::Energy;
use super::state::State;
use nalgebra::Vector3;

/// A fixed obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// The plane y = `height`; everything below is solid.
    Ground { height: f64 },
    /// A fixed sphere.
    Sphere { center: Vector3<f64>, radius: f64 },
    /// A fixed axis-aligned box.
    Box {
        min: Vector3<f64>,
        max: Vector3<f64>,
    },
}

impl Obstacle {
    /// The scene-file name of this obstacle's type.
    pub fn kind(&self) -> &'static str {
        match self {
            Obstacle::Ground { .. } => "ground",
            Obstacle::Sphere { .. } => "sphere",
            Obstacle::Box { .. } => "box",
        }
    }
}

/// Which collision response runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Response {
    /// The original report's response, reproduced with its failures.
    Seed,
    /// Sequential impulses with restitution and Coulomb friction.
    Impulse,
}

impl Response {
    /// Every response, in teaching order.
    pub const ALL: [Response; 2] = [Response::Seed, Response::Impulse];

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Response::Seed => "seed",
            Response::Impulse => "impulse",
        }
    }

    /// The response with this name.
    pub fn from_name(name: &str) -> Option<Response> {
        Response::ALL.into_iter().find(|r| r.name() == name)
    }

    /// Every valid name, comma-separated.
    pub fn names() -> String {
        Response::ALL.map(Response::name).join(", ")
    }

    /// The next response, wrapping around.
    pub fn next(self) -> Response {
        match self {
            Response::Seed => Response::Impulse,
            Response::Impulse => Response::Seed,
        }
    }
}

/// The contact parameters of a scene (`contact = { ... }`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel {
    /// Which response runs.
    pub response: Response,
    /// Coefficient of restitution e, 0 ≤ e ≤ 1 (`impulse` only; `seed` always uses 0.4).
    pub restitution: f64,
    /// Coulomb friction coefficient μ ≥ 0 (`impulse` only).
    pub friction: f64,
}

/// One body vertex found inside an obstacle, and what the response did there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Index of the body vertex.
    pub vertex: usize,
    /// Index of the obstacle in the scene's list.
    pub obstacle: usize,
    /// Vertex position (world), m.
    pub point: Vector3<f64>,
    /// Penetration depth, m: > 0 inside the obstacle; ≤ 0 (minus the gap) for a vertex just
    /// outside that the `impulse` response held back (a speculative contact, see `impulse`).
    pub depth: f64,
    /// Unit contact normal, pointing out of the obstacle.
    pub normal: Vector3<f64>,
    /// Lever arm r to the point, m: from the current barycenter (`impulse`), or from the
    /// *initial* barycenter x₀ as the report measures it (`seed`).
    pub lever: Vector3<f64>,
    /// Normal velocity of the point `(v + ω × (p − x))·n` before the response, m/s
    /// (negative: approaching).
    pub normal_velocity: f64,
    /// 1/M + n·((I⁻¹(r×n))×r), 1/kg: the denominator of the impulse formula (`impulse`;
    /// 0 for `seed`, which has no impulse formula).
    pub denominator: f64,
    /// Impulse applied at this point, N·s: normal (with restitution) plus friction for
    /// `impulse`; for `seed`, the change it made to the whole momentum, −1.4 P.
    pub impulse: Vector3<f64>,
}

/// Everything the collide phase needs besides the state it corrects.
pub struct CollideInput<'a> {
    pub body: &'a Body,
    pub obstacles: &'a [Obstacle],
    pub model: &'a ContactModel,
    /// The state at the start of the step (for swept tests).
    pub before: &'a State,
    /// The forces phase's loads (the `seed` response adds a force to L).
    pub loads: &'a Loads,
    /// The barycenter at t = 0 (the `seed` response measures its lever arm from there).
    pub initial_position: &'a Vector3<f64>,
    /// Declared gravity, if any (sets the speed below which contacts do not bounce).
    pub gravity: Option<Vector3<f64>>,
    pub dt: f64,
}

/// The energy of the state before and after a response, measured as [`energy`] measures it
/// (same arithmetic, to the last bit), by a response that had the numbers at hand.
///
/// [`energy`]: super::snapshot::energy
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyChange {
    pub before: Energy,
    pub after: Energy,
}

/// Runs detection and the chosen response on `state`; `contacts` is cleared and filled with the
/// contacts it handled (a buffer reused from step to step). Returns the energy before and after
/// when the response measured it (`impulse`, when it changed the state); None otherwise.
pub fn collide(
    input: &CollideInput,
    state: &mut State,
    contacts: &mut Vec<Contact>,
) -> Option<EnergyChange> {
    contacts.clear();
    match input.model.response {
        Response::Seed => {
            seed::respond(input, state, contacts);
            None
        }
        Response::Impulse => impulse::respond(input, state, contacts),
    }
}

/// Vertex positions `pᵢ = x + R r₀ᵢ` of a state, written into `out`.
pub(crate) fn vertices_into(body: &Body, state: &State, out: &mut Vec<Vector3<f64>>) {
    let r = state.orientation.matrix();
    out.clear();
    out.extend(body.points_body.iter().map(|r0| state.position + r * r0));
}

impl Obstacle {
    /// How deep a point lies inside the obstacle (0 when outside), m.
    pub fn depth(&self, p: &Vector3<f64>) -> f64 {
        match *self {
            Obstacle::Ground { height } => (height - p.y).max(0.0),
            Obstacle::Sphere { center, radius } => (radius - (p - center).norm()).max(0.0),
            Obstacle::Box { min, max } => {
                let inside = (p - min).inf(&(max - p));
                inside.min().max(0.0)
            }
        }
    }
}
