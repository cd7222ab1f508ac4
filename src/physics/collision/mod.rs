//! The *collide* phase: obstacles, contact detection, and the two responses.
//!
//! Detection produces contact *rows* — body A; body B or an obstacle; point; normal; depth;
//! lever arms — and a response turns rows into impulses and position fixes. The phase runs
//! only when something can touch: obstacles, or several bodies.
//!
//! A row reaches B through the **solver body table** ([`CollideInput::end`]): the world's
//! bodies, then one static entry per obstacle (1/M = 0, I⁻¹ = 0, at rest). A fixed body and
//! an obstacle are the same kind of static thing there ([`moves`]): no end of a row, exact
//! zeros in a relative velocity, so the responses (`impulse`, `soft_step`) have no
//! body-against-obstacle branch. Detection and `seed` reach a fixed body and an obstacle the
//! same way too, as a fixed thing (`fixed`), which keeps each obstacle kind's closed-form tests
//! (`obstacle/kinds/`: a plane stays a plane); the row label [`Against`] still says what B is
//! for the front ends.
//!
//! | file | idea |
//! |---|---|
//! | `obstacle` | the scene's fixed things, each a static body of the shape table: one file per kind in `obstacle/kinds/` (shape, point tests, contact, outline, scene words), listed by `build.rs` |
//! | `detect` | the report's test: is a vertex inside an obstacle; the swept test along its motion (the formulas per shape) |
//! | `fixed` | a fixed thing, obstacle or fixed body: B that never moves, as one static entry of the shape table (its label, solver body entry, pair, sweep, point test) for detection and `seed` |
//! | `contacts` | every contact row of a world: vertices, faces and edges, bodies against fixed things and against bodies |
//! | `response` | the responses a scene can choose: the `responses!` list (below: `Variant => module`) and the descriptor each module holds (name, formulas, README row, colour) |
//! | `seed` | the report's response, reproduced with its failures (one body, its own detection) |
//! | `impulse` | one impulse solver for every row: restitution, Coulomb friction, no energy added; a file per constraint kind (`normal`, `friction`), per method (`direct`, `subspace`) and for the impact law (`propagate`) |
//! | `particle` | how a contact method treats a particle: the verb each method file gives (`ParticleLaw`), dispatched by `responses!` to the cloths' contact passes |
//! | `position` | the position fix: no creep at rest, penetration removed by translation |
//! | `solver_body` | solver bodies and constraint axes, re-exported from the constraint layer (`physics::constraints`) |
//! | `step_context` | the constants every contact pass of a step reads (bounce speed, margins, e, μ), computed once |
//! | `soft_step` | sub-stepped soft contacts with a relax pass (Box2D v3's soft step): fast, sags |
//! | `sweep` | fast pairs of bodies: time of impact, rows carried to the end of the step (no tunnelling) |
//! | `warm` | warm starts by contact feature: last step's impulses by pair, in a hash map |
//! | `kept` | `soft-step`'s rows carried across steps while the bodies barely move (contact recycling) |
//!
#[macro_use]
pub mod response;
pub mod broad_phase;
pub mod contacts;
pub mod detect;
pub mod fixed;
pub mod geometry;
pub mod kept;
pub mod obstacle;
pub mod particle;
pub mod position;
pub mod solver_body;
pub mod step_context;
pub mod sweep;
pub mod warm;

pub use impulse::propagate::Impacts;
pub use obstacle::{Obstacle, Outline};
pub use response::Descriptor as ResponseDescriptor;
pub use soft_step::SoftStep;
pub use step_context::StepContext;

use super::body::Body;
use super::effects::Loads;
use super::energy::Energy;
use super::state::State;
use nalgebra::Vector3;

// The collision responses, one file each (`response`): a new one is its file and one line here.
responses! {
    /// The original report's response, reproduced with its failures.
    Seed => seed,
    /// Sequential impulses with restitution and Coulomb friction.
    Impulse => impulse,
    /// Sub-stepped soft contacts with a relax pass (Box2D v3): fast, approximate, sags.
    SoftStep(params: SoftStep = SoftStep::DEFAULT) => soft_step,
}

/// The contact parameters of a scene (`contact = { ... }`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel {
    /// Which response runs.
    pub response: Response,
    /// Coefficient of restitution e, 0 ≤ e ≤ 1 (`impulse`, `soft-step`; `seed` always uses 0.4).
    pub restitution: f64,
    /// Coulomb friction coefficient μ ≥ 0 (`impulse`, `soft-step`).
    pub friction: f64,
    /// How `impulse` answers impacts among touching bodies (`impulse::propagate`); the other
    /// responses ignore it.
    pub impacts: Impacts,
}

/// What body A touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Against {
    /// A fixed obstacle: its index in the scene's list.
    Obstacle(usize),
    /// Another body: its index in the world.
    Body(usize),
}

/// Which features of the two surfaces meet at a contact point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Feature {
    /// Body A's vertex inside B (the report's per-vertex test), with the vertex index.
    Vertex(usize),
    /// Found by the contact geometry: vertex–face, edge–face, edge–edge, face–face, sphere.
    Geometry(geometry::Feature),
}

/// One contact row, two-sided: body A against an obstacle or body B, and what the response
/// did there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Body A: its index in the world.
    pub body: usize,
    /// B: an obstacle or another body.
    pub against: Against,
    /// B's entry in the solver body table ([`CollideInput::end`]): another body's own index,
    /// or for obstacle o the static entry `bodies + o` after the world's bodies (1/M = 0,
    /// I⁻¹ = 0, at rest). The solvers reach B through it alone, so a row against an obstacle
    /// and one against a fixed body take the same path.
    pub other: usize,
    /// The features that meet.
    pub feature: Feature,
    /// Contact point (world), m.
    pub point: Vector3<f64>,
    /// Penetration depth, m: > 0 overlapping; ≤ 0 (minus the gap) for a point just outside
    /// that the `impulse` response held back (a speculative contact, see `impulse`).
    pub depth: f64,
    /// Unit contact normal, pointing from B to A (out of the obstacle): the way A must move
    /// to separate.
    pub normal: Vector3<f64>,
    /// Lever arm r_A from A's barycenter to the point, m: from the current barycenter
    /// (`impulse`), or from the *initial* barycenter x₀ as the report measures it (`seed`).
    pub lever: Vector3<f64>,
    /// Lever arm r_B from B's barycenter to the point, m (zero for an obstacle).
    pub lever_other: Vector3<f64>,
    /// Relative normal velocity of the point `(v_A + ω_A × r_A − v_B − ω_B × r_B)·n` before
    /// the response, m/s (negative: approaching).
    pub normal_velocity: f64,
    /// k = 1/M_A + (r_A×n)·I_A⁻¹(r_A×n) [+ the same for B], 1/kg: the denominator of the
    /// impulse formula (`impulse`; 0 for `seed`, which has no impulse formula).
    pub denominator: f64,
    /// Impulse applied to A at this point, N·s (B receives its opposite): normal (with
    /// restitution) plus friction for `impulse`; for `seed`, the change it made to the whole
    /// momentum, −1.4 P.
    pub impulse: Vector3<f64>,
}

impl Contact {
    /// A contact of body A against B at a point, before any response: no velocity, no
    /// impulse yet. B's solver body `other` is another body's index; for an obstacle it is
    /// left unset (`usize::MAX`) and detection sets it ([`CollideInput::end`]).
    #[inline]
    pub fn new(
        body: usize,
        against: Against,
        feature: Feature,
        point: Vector3<f64>,
        depth: f64,
        normal: Vector3<f64>,
    ) -> Contact {
        Contact {
            body,
            against,
            other: match against {
                Against::Body(b) => b,
                Against::Obstacle(_) => usize::MAX,
            },
            feature,
            point,
            depth,
            normal,
            lever: Vector3::zeros(),
            lever_other: Vector3::zeros(),
            normal_velocity: 0.0,
            denominator: 0.0,
            impulse: Vector3::zeros(),
        }
    }

    /// The other body, if B is one.
    pub fn other_body(&self) -> Option<usize> {
        match self.against {
            Against::Body(b) => Some(b),
            Against::Obstacle(_) => None,
        }
    }
}

/// The joints' equality rows at given states, written into the buffer (`impulse::joined`).
pub type JointRows<'a> = dyn Fn(&[State], &mut Vec<crate::physics::constraints::Row>) + 'a;

/// Everything the collide phase reads besides the states it corrects.
pub struct CollideInput<'a> {
    /// The world's bodies, in order (contact rows name them by index).
    pub bodies: &'a [Body],
    pub obstacles: &'a [Obstacle],
    pub model: &'a ContactModel,
    /// The states at the start of the step (for swept tests and the position fix).
    pub before: &'a [State],
    /// The forces phase's loads, per body (the `seed` response adds a force to L).
    pub loads: &'a [Loads],
    /// The barycenters at t = 0 (the `seed` response measures its lever arm from there).
    pub initial_positions: &'a [Vector3<f64>],
    /// The step's constants (dt, gravity, bounce speed, margins, e, μ), built once per step
    /// by the world (`step_context`).
    pub context: StepContext,
    /// Pairs of bodies (low, high index) joined directly by a joint: they do not collide.
    pub joined: &'a [(usize, usize)],
    /// The joints' equality rows at given states (`constraints::Row`, `Axis::jacobian`),
    /// solved with the contacts (`impulse::joined`); None without joints.
    pub joints: Option<&'a JointRows<'a>>,
    /// Recorded contact rows: when given, detection is skipped and these are the step's rows
    /// (a bench of the response alone, `benches/solver.rs`); None in every simulation.
    pub recorded: Option<&'a [Contact]>,
}

/// Whether solver body `end` ([`CollideInput::end`]) moves: a body that is not fixed. A fixed
/// body and an obstacle's static entry (`end ≥ bodies.len()`) are the world, one kind of
/// static thing: no impulse moves them, and a row has no end on them.
pub fn moves(bodies: &[Body], end: usize) -> bool {
    bodies.get(end).is_some_and(|b| !b.fixed)
}

/// The energy of the bodies before and after a response, measured as [`energy`] measures it
/// (same arithmetic, to the last bit), by a response that had the numbers at hand.
///
/// [`energy`]: super::energy::energy
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyChange {
    pub before: Energy,
    pub after: Energy,
}

/// Runs detection and the chosen response on `states`; `contacts` is cleared and filled with
/// the contacts it handled (a buffer reused from step to step; on entry it holds the last
/// step's contacts, which warm-start the solver). Returns the energy before and after when the
/// response measured it (`impulse`, when it changed a state); None otherwise.
///
/// `seed` knows one body and obstacles only (the scene loader refuses more).
pub fn collide(
    input: &CollideInput,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut impulse::Scratch,
) -> Option<EnergyChange> {
    input
        .model
        .response
        .collide(input, states, contacts, scratch)
}

/// Vertex positions `pᵢ = x + R r₀ᵢ` of a state, written into `out`.
pub(crate) fn vertices_into(body: &Body, state: &State, out: &mut Vec<Vector3<f64>>) {
    let r = state.orientation.matrix();
    out.clear();
    out.extend(body.points_body.iter().map(|r0| state.position + r * r0));
}
