//! The world: its bodies, their declared effects and obstacles, stepped through the animation
//! loop one phase at a time. Every phase runs over every body; the collide phase sees them all
//! at once (bodies touch each other).
//!
//! ```text
//! derive → forces → integrate → collide      (one frame, dt)
//! ```
//!
//! [`World::step`] runs a whole frame; [`World::step_phase`] runs one phase. Front ends read
//! [`World::snapshot`] and never recompute physics.
//!
//! **Cloths** ([`World::with_cloths`]) are stepped in the integrate phase, each by its own
//! particle integrator under the declared gravity and drag (`ClothLoads::from_effects`):
//! the velocity half, the obstacles' first contact pass (on velocities), the position half.
//! Their second obstacle pass and their contacts with bodies (`cloth_coupling`) run in the
//! collide phase. The particles' kinetic, spring and gravitational energy is part of the
//! scene's energy; the ledger books the springs' damping and the drag on particles as drag
//! work, and what the contacts took or gave as contact energy. A world without cloths does
//! none of this (one emptiness test per phase).

use super::body::Body;
use super::cloth::{Cloth, ClothIntegrator, ClothLoads, ExplicitLimit, ParticleContact};
use super::cloth_coupling::{
    approach_bodies, carry_attachments, collide_bodies, hold_attachments, tied_step, Attachment,
    BodyMove, Carried, Holding, TiedScene,
};
use super::collision::impulse::Scratch;
use super::collision::StepContext;
use super::collision::{collide, CollideInput, Contact, ContactModel, EnergyChange, Obstacle};
use super::derive::{derive, derive_with_inverse, Kinematics};
use super::divergence::{not_finite, Divergence, EnergyGuard};
use super::effects::{Effect, Effects, Loads};
use super::energy::{energy, Energy};
use super::energy_ledger::{drag_power, DragPower, EnergyBalance, EnergyLedger};
use super::hand::{Hand, Pull};
use super::integrators::system::{Buffers as SystemBuffers, Start};
use super::integrators::Integrator;
use super::joints::contact::equality_rows;
use super::joints::drive::{
    book_stops, drive, Buffers as DriveBuffers, Drive, Scene as DriveScene,
};
use super::joints::{
    hold, project, shake, ContactBuffers, Correction, Links, ProjectionBuffers, Row as JointRow,
};
use super::snapshot::Snapshot;
use super::state::State;
use super::system::{Scratch as SystemScratch, System};
use nalgebra::Vector3;
use std::fmt;

/// One phase of the animation loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Phase {
    /// `I⁻¹_world = R I⁻¹_body Rᵀ`, `ω = I⁻¹_world L`, `v = P/M` (CalculStateX).
    Derive,
    /// Force and torque of the declared effects: the state derivative (CalculDeriveeStateX).
    Forces,
    /// One integrator step; vertex positions `pᵢ = x + R r₀ᵢ` (Solve).
    Integrate,
    /// Collision detection and response (a no-op when nothing can touch).
    Collide,
}

impl Phase {
    /// The four phases in loop order.
    pub const ALL: [Phase; 4] = [
        Phase::Derive,
        Phase::Forces,
        Phase::Integrate,
        Phase::Collide,
    ];

    /// The phase's name.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Derive => "derive",
            Phase::Forces => "forces",
            Phase::Integrate => "integrate",
            Phase::Collide => "collide",
        }
    }

    /// The phase after this one, wrapping to the next frame.
    pub fn next(self) -> Phase {
        match self {
            Phase::Derive => Phase::Forces,
            Phase::Forces => Phase::Integrate,
            Phase::Integrate => Phase::Collide,
            Phase::Collide => Phase::Derive,
        }
    }
}

impl fmt::Display for Phase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Everything needed to put a world back exactly where it was (for stepping back in time).
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// One state per body.
    states: Vec<State>,
    /// The states at the start of the last integrate phase (kept only when something can
    /// touch: the collide phase's swept tests and position fix are their only readers).
    before: Vec<State>,
    step: u64,
    last: Option<Phase>,
    kinematics: Vec<Kinematics>,
    loads: Vec<Loads>,
    contacts: Vec<Contact>,
    guard: EnergyGuard,
    /// Drag work and contact energy booked since t = 0 (see `energy_ledger`).
    ledger: EnergyLedger,
    /// The cloths, whole (positions, velocities, losses and the implicit step's warm-start
    /// buffers: restoring them makes the next step exactly the same).
    cloths: Cloths,
    /// Per cloth: particle–body contacts in the last collide phase.
    cloth_body_contacts: Vec<usize>,
    /// Per cloth: the force its attachments gave it, averaged over the last step (N), and
    /// that force's moment about the world origin (N·m).
    cloth_attach_loads: Vec<[Vector3<f64>; 2]>,
    /// Per cloth: particle–obstacle contacts of the last step's velocity pass (integrate)
    /// and position pass (collide).
    cloth_obstacle_contacts: Vec<[usize; 2]>,
    /// Per cloth: its energy after the last integrate phase (the collide phase starts from it
    /// instead of measuring it again).
    cloth_energies: Vec<Energy>,
    /// Per joint: its reaction on its body A at the forces phase (start of the step).
    start_joint_loads: Vec<Loads>,
    /// The springs' damping power at the forces phase, W.
    start_damping_power: f64,
    /// Per joint: its reaction on its body A averaged over the last step (impulse / dt).
    joint_loads: Vec<Loads>,
    /// Per joint: what its limit and motor applied over the last step (`joints::drive`).
    joint_drives: Vec<Drive>,
    /// Per body, when some body holds attached particles: how the last collide phase moved
    /// it (the attached particles' lead in the next step, `cloth_coupling::tied_step`).
    collide_moves: Vec<BodyMove>,
}

impl Checkpoint {
    /// The heap bytes this checkpoint holds (what keeping it costs beyond its own
    /// `size_of`): every `Vec`'s capacity × its element size. Of a cloth, the particles, the
    /// springs and its name are counted exactly; its step's scratch buffers (private to the
    /// cloth module) are counted as what a step fills — per particle the force, the start
    /// positions and velocities, the damping force and drag velocities, per spring its axis,
    /// and with `implicit-euler` the solver's blocks, preconditioner and six vectors — an upper
    /// bound on them once the cloth has stepped (`tests/app/history.rs` measures it against the
    /// allocator).
    pub fn heap_bytes(&self) -> usize {
        bytes_of(&self.states)
            + bytes_of(&self.before)
            + bytes_of(&self.kinematics)
            + bytes_of(&self.loads)
            + bytes_of(&self.contacts)
            + bytes_of(&self.cloths.0)
            + self.cloths.0.iter().map(Cloth::heap_bytes).sum::<usize>()
            + bytes_of(&self.cloth_body_contacts)
            + bytes_of(&self.cloth_attach_loads)
            + bytes_of(&self.cloth_obstacle_contacts)
            + bytes_of(&self.cloth_energies)
            + bytes_of(&self.collide_moves)
    }

    /// Whether the checkpoint holds any cloth.
    pub fn has_cloths(&self) -> bool {
        !self.cloths.0.is_empty()
    }
}

/// A `Vec`'s heap bytes: its capacity × its element size.
fn bytes_of<T>(v: &Vec<T>) -> usize {
    v.capacity() * std::mem::size_of::<T>()
}

/// The cloths of a checkpoint; two are equal when every particle's position and velocity and
/// the losses are (the solver's scratch buffers are not compared).
#[derive(Debug, Clone, Default)]
struct Cloths(Vec<Cloth>);

impl PartialEq for Cloths {
    fn eq(&self, other: &Cloths) -> bool {
        self.0.len() == other.0.len()
            && self.0.iter().zip(&other.0).all(|(a, b)| {
                a.positions == b.positions && a.velocities == b.velocities && a.losses == b.losses
            })
    }
}

/// The settings a world steps with beside its checkpoint ([`World::stepping`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stepping {
    pub integrator: Integrator,
    pub contact: Option<ContactModel>,
}

/// A body of a world, with its name and its state at t = 0.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedBody {
    /// Unique in the world (scene files: `name`, default body1, body2, …).
    pub name: String,
    pub body: Body,
    pub initial: State,
}

/// Bodies in a scene, stepped through the loop.
#[derive(Debug, Clone)]
pub struct World {
    bodies: Vec<Body>,
    names: Vec<String>,
    effects: Effects,
    obstacles: Vec<Obstacle>,
    contact: Option<ContactModel>,
    integrator: Integrator,
    dt: f64,
    initial: Vec<State>,
    initial_positions: Vec<Vector3<f64>>,
    now: Checkpoint,
    scratch: Scratch,
    /// The cloths at t = 0.
    initial_cloths: Vec<Cloth>,
    /// Gravity and drag as they act on particles.
    cloth_loads: ClothLoads,
    /// Reused by the cloths' obstacle contact passes.
    particle_contacts: Vec<ParticleContact>,
    /// Each cloth's explicit limit at rest (computed once: a few ms of power iterations).
    cloth_limits: Vec<ExplicitLimit>,
    /// Per cloth: its attached particles' offsets in their bodies' frames at t = 0.
    cloth_attachments: Vec<Vec<Attachment>>,
    /// Joints and springs (empty: every body is stepped on its own).
    links: Links,
    /// The pairs of bodies joined directly (they do not collide).
    joined: Vec<(usize, usize)>,
    /// A parameter was changed while running ([`World::tune`]): E₀ is the ledger's (which
    /// booked the change) until the next reset.
    tuned: bool,
    system_scratch: SystemScratch,
    system_buffers: SystemBuffers,
    projection_buffers: ProjectionBuffers,
    /// The projection's impulse on each joint's body A, and each body's potential energy
    /// before it (the energy ledger's correction), reused step to step.
    projection_impulses: Vec<Loads>,
    projection_potential: Vec<f64>,
    /// The joints held while the contacts act (`joints::contact`).
    contact_joint_buffers: ContactBuffers,
    /// `symplectic-euler` with projection, or a joint with a limit or a motor: the states at
    /// the step's start (`joints::shake`, `joints::drive`).
    step_start: Vec<State>,
    /// The joints' limits and motors (`joints::drive`).
    drive_buffers: DriveBuffers,
    /// The states before the rigid response, when some body holds attached particles
    /// (`carry_attached`).
    carry_start: Vec<State>,
    /// The hand (the mouse's drag spring), while a front end holds a body (`hand`): an input,
    /// like the pointer, so no part of a checkpoint.
    hand: Option<Hand>,
}

impl World {
    /// A world of one body (named `body1`) at its initial state. `contact` must be given when
    /// there are obstacles; the orientation is converted to what `integrator` steps.
    pub fn new(
        body: Body,
        effects: Effects,
        obstacles: Vec<Obstacle>,
        contact: Option<ContactModel>,
        integrator: Integrator,
        dt: f64,
        initial: State,
    ) -> World {
        let one = NamedBody {
            name: "body1".into(),
            body,
            initial,
        };
        World::with_bodies(vec![one], effects, obstacles, contact, integrator, dt)
    }

    /// A world of several bodies at their initial states. `contact` must be given when
    /// something can touch (obstacles, or more than one body).
    pub fn with_bodies(
        bodies: Vec<NamedBody>,
        effects: Effects,
        obstacles: Vec<Obstacle>,
        contact: Option<ContactModel>,
        integrator: Integrator,
        dt: f64,
    ) -> World {
        let mut names = Vec::with_capacity(bodies.len());
        let mut models = Vec::with_capacity(bodies.len());
        let mut initial = Vec::with_capacity(bodies.len());
        for b in bodies {
            names.push(b.name);
            initial.push(State {
                orientation: integrator.orientation_for(&b.initial.orientation),
                ..b.initial
            });
            models.push(b.body);
        }
        let now = fresh(&models, &effects, integrator, &initial, &[]);
        World {
            initial_positions: initial.iter().map(|s| s.position).collect(),
            bodies: models,
            names,
            effects,
            obstacles,
            contact,
            integrator,
            dt,
            initial,
            now,
            scratch: Scratch::default(),
            initial_cloths: Vec::new(),
            cloth_loads: ClothLoads::default(),
            particle_contacts: Vec::new(),
            cloth_limits: Vec::new(),
            cloth_attachments: Vec::new(),
            links: Links::default(),
            joined: Vec::new(),
            tuned: false,
            system_scratch: SystemScratch::default(),
            system_buffers: SystemBuffers::default(),
            projection_buffers: ProjectionBuffers::default(),
            projection_impulses: Vec::new(),
            projection_potential: Vec::new(),
            contact_joint_buffers: ContactBuffers::default(),
            step_start: Vec::new(),
            drive_buffers: DriveBuffers::default(),
            carry_start: Vec::new(),
            hand: None,
        }
    }

    /// The same world with these joints and springs (built against its bodies' t = 0 states):
    /// the integrators then step the whole system at once (`integrators::system`).
    pub fn with_links(mut self, links: Links) -> World {
        self.joined = links.joined_pairs();
        self.links = links;
        self.reset();
        self
    }

    /// The joints and springs.
    pub fn links(&self) -> &Links {
        &self.links
    }

    /// Joint `index`'s reaction on its body A averaged over the last step (impulse / dt):
    /// force, and torque about A's barycenter. Zero before the first step.
    pub fn joint_load(&self, index: usize) -> Loads {
        self.now.joint_loads.get(index).copied().unwrap_or_default()
    }

    /// What joint `index`'s limit and motor applied over the last step, along its axis
    /// (`joints::drive`; zero before the first step).
    pub fn joint_drive(&self, index: usize) -> Drive {
        self.now
            .joint_drives
            .get(index)
            .copied()
            .unwrap_or_default()
    }

    /// The whole system's loads at the current states, as the next forces phase will compute
    /// them: (per body, per joint's reaction on its body A).
    pub fn system_loads_now(&self) -> (Vec<Loads>, Vec<Loads>) {
        let system = System {
            bodies: &self.bodies,
            effects: &self.effects,
            links: &self.links,
            integrator: self.integrator,
            dt: self.dt,
        };
        let mut scratch = SystemScratch::default();
        let mut kinematics = Vec::new();
        system.evaluate_states(&self.now.states, &mut kinematics, &mut scratch);
        (scratch.loads, scratch.joint_loads)
    }

    /// The forces phase over the whole system: every body's F and τ (the declared effects, and
    /// for `euler-seed` the report's per-vertex torque sum: see [`Integrator::loads`]), with
    /// the springs and joints when there are any.
    fn system_loads(&mut self) {
        let system = System {
            bodies: &self.bodies,
            effects: &self.effects,
            links: &self.links,
            integrator: self.integrator,
            dt: self.dt,
        };
        let now = &mut self.now;
        let scratch = &mut self.system_scratch;
        system.evaluate_at(&now.states, &now.kinematics, &mut now.loads, scratch);
        now.start_joint_loads.clone_from(&scratch.joint_loads);
        now.start_damping_power = scratch.damping_power;
    }

    /// The same world with these cloths at their initial states (particles under the declared
    /// gravity and drag; `contact` must be given when they can touch an obstacle or a body).
    pub fn with_cloths(mut self, cloths: Vec<Cloth>) -> World {
        self.cloth_loads = ClothLoads::from_effects(&self.effects);
        self.cloth_limits = cloths
            .iter()
            .map(|c| c.explicit_limit(&self.cloth_loads))
            .collect();
        self.initial_cloths = cloths;
        self.reset();
        // Attachments: each particle's offset in its body's frame at t = 0 (a body index out
        // of range is ignored: the scene checks names).
        let states = &self.now.states;
        self.cloth_attachments = (self.initial_cloths.iter())
            .map(|c| {
                c.attached
                    .iter()
                    .filter(|&&(_, b)| b < states.len())
                    .map(|&(particle, body)| {
                        let s = &states[body];
                        Attachment {
                            particle,
                            body,
                            offset_body: s.orientation.matrix().transpose()
                                * (c.positions[particle] - s.position),
                        }
                    })
                    .collect()
            })
            .collect();
        self
    }

    /// The attachment error of cloth `index`: the largest distance of an attached particle
    /// from its point on its body, m (0 without attachments).
    pub fn attach_error(&self, index: usize) -> f64 {
        let (Some(c), Some(list)) = (
            self.now.cloths.0.get(index),
            self.cloth_attachments.get(index),
        ) else {
            return 0.0;
        };
        list.iter()
            .map(|a| {
                let s = &self.now.states[a.body];
                let target = s.position + s.orientation.matrix() * a.offset_body;
                (c.positions[a.particle] - target).norm()
            })
            .fold(0.0, f64::max)
    }

    /// Runs the rest of the current frame (all four phases from the start of a frame).
    ///
    /// From the start of a frame this is exactly `derive`, `forces`, `integrate`, `collide` as
    /// [`World::step_phase`] runs them, without dispatching on the phase in between.
    ///
    /// The step's contact constants are built here, once ([`StepContext`]), and handed down
    /// as one value to every contact pass of the step.
    pub fn step(&mut self) {
        if self.next_phase() != Phase::Derive {
            while self.step_phase() != Phase::Collide {}
            return;
        }
        let context = self.step_context();
        self.derive_phase();
        self.forces_phase();
        self.integrate_phase(&context);
        self.collide_phase(&context);
        self.now.last = Some(Phase::Collide);
    }

    /// Runs the next phase of the loop; returns the phase it ran.
    pub fn step_phase(&mut self) -> Phase {
        let phase = self.next_phase();
        match phase {
            Phase::Derive => self.derive_phase(),
            Phase::Forces => self.forces_phase(),
            Phase::Integrate => self.integrate_phase(&self.step_context()),
            Phase::Collide => self.collide_phase(&self.step_context()),
        }
        self.now.last = Some(phase);
        phase
    }

    /// *derive*: I⁻¹_world, ω and v of every body from its state (after the hand's kick, while
    /// a body is held: see `hand`).
    #[inline]
    fn derive_phase(&mut self) {
        if let Some(hand) = self.hand {
            self.kick_hand(&hand);
        }
        let now = &mut self.now;
        let kept = &self.projection_buffers;
        let each = now.kinematics.iter_mut().zip(&self.bodies).zip(&now.states);
        for (i, ((k, body), state)) in each.enumerate() {
            // After a projection, R and I⁻¹_world as its last build derived them.
            *k = match kept.derived(i, &state.orientation) {
                Some((r, inverse)) => derive_with_inverse(body, state, *r, *inverse),
                None => derive(body, state),
            };
        }
    }

    /// The hand's kick at the start of a frame, its work booked (`hand`).
    fn kick_hand(&mut self, hand: &Hand) {
        let (Some(body), Some(state)) = (
            self.bodies.get(hand.body),
            self.now.states.get_mut(hand.body),
        ) else {
            return;
        };
        let work = hand.kick(body, state, self.dt);
        self.now.ledger.book_hand(work);
    }

    /// Holds a body with the hand (the mouse's drag spring) from the next frame on, or lets
    /// go (None). See `hand`.
    pub fn set_hand(&mut self, hand: Option<Hand>) {
        self.hand = hand;
    }

    /// The hand, while a body is held.
    pub fn hand(&self) -> Option<&Hand> {
        self.hand.as_ref()
    }

    /// Where the hand holds its body and how hard it pulls now (None: nothing held).
    pub fn hand_pull(&self) -> Option<Pull> {
        let hand = self.hand.as_ref()?;
        Some(hand.pull(self.bodies.get(hand.body)?, self.now.states.get(hand.body)?))
    }

    /// *forces*: f(Y)'s forces at the derived velocities, the whole system's
    /// (`System::evaluate`: per body without links).
    #[inline]
    fn forces_phase(&mut self) {
        self.system_loads();
    }

    /// *integrate*: one integrator step of the whole system, then the cloths (the states
    /// before it are kept for the collide phase).
    #[inline]
    fn integrate_phase(&mut self, context: &StepContext) {
        // Energy ledger: the drag power at the start of the step (see `energy_ledger`).
        let drag = self.effects.depends_on_velocity();
        let drag_start = drag.then(|| self.drag_power());
        let can_touch = self.can_touch();
        let now = &mut self.now;
        if can_touch || !now.cloths.0.is_empty() {
            now.before.clone_from(&now.states);
        }
        let has_cloths = !now.cloths.0.is_empty();
        let mut potential = self.integrate_bodies();
        if has_cloths {
            potential += self.integrate_cloths(context);
        }
        let now = &mut self.now;
        now.step += 1;
        now.guard.observe(&now.ledger, potential);
        // Energy ledger: the drag work of this step, from its start and end states.
        if let Some(start) = drag_start {
            let end = self.drag_power();
            self.now.ledger.book_drag(&start, &end, self.dt);
        }
        if self.links.driven() {
            self.drive_joints();
        }
    }

    /// The joints' limits and motors at the end of the step, with the joints held
    /// (`joints::drive`: after the drag is booked, whose quadrature is over the step's own
    /// flow); books the motors' work, the stops' energy with the contacts.
    fn drive_joints(&mut self) {
        let now = &mut self.now;
        let scene = DriveScene {
            links: &self.links,
            bodies: &self.bodies,
            effects: &self.effects,
            restitution: self.contact.as_ref().map_or(0.0, |m| m.restitution),
            dt: self.dt,
        };
        let done = drive(
            &scene,
            &mut now.states,
            &self.step_start,
            &mut now.joint_loads,
            &mut now.joint_drives,
            &mut self.drive_buffers,
        );
        now.ledger.motor_work += done.motor_work;
        now.ledger.book_contact(0.0, done.stops);
        now.ledger.joint_correction += done.joints;
    }

    /// One integrator step of every body, the whole system at once (`integrators::system`);
    /// with joints, then their correction, booking the springs' damping as drag work and the
    /// projection's energy change as the correction's work. Returns the potential energy
    /// after the step (gravity and springs, for the guard).
    fn integrate_bodies(&mut self) -> f64 {
        let system = System {
            bodies: &self.bodies,
            effects: &self.effects,
            links: &self.links,
            integrator: self.integrator,
            dt: self.dt,
        };
        let now = &mut self.now;
        let shaken = self.integrator == Integrator::SymplecticEuler
            && self.links.correction == Correction::Projection
            && !self.links.joints.is_empty();
        let driven = self.links.driven();
        if shaken || driven {
            self.step_start.clone_from(&now.states);
        }
        let start = Start {
            kinematics: &now.kinematics,
            loads: &now.loads,
            joint_loads: &now.start_joint_loads,
            damping_power: now.start_damping_power,
        };
        self.integrator.advance(
            &system,
            &mut now.states,
            &start,
            self.dt,
            &mut self.system_buffers,
        );
        now.joint_loads.clone_from(&self.system_buffers.joint_loads);
        now.ledger.drag_work += self.system_buffers.damping_work;
        if self.links.correction == Correction::Projection && !self.links.joints.is_empty() {
            let (bodies, effects) = (&self.bodies, &self.effects);
            let impulses = &mut self.projection_impulses;
            let (before, after) = if shaken {
                let before = total_energy(bodies, effects, &now.states).total
                    + self.links.potential(&now.states);
                shake(
                    &self.links,
                    bodies,
                    &mut now.states,
                    &self.step_start,
                    self.dt,
                    impulses,
                    &mut self.projection_buffers,
                );
                let after = total_energy(bodies, effects, &now.states).total
                    + self.links.potential(&now.states);
                (before, after)
            } else {
                // The potential energies before; the kinetic ones from the projection's own
                // I⁻¹_world before and after: the same sums as `total_energy`'s, bit for bit.
                let potential = &mut self.projection_potential;
                potential.clear();
                potential.extend(
                    (bodies.iter().zip(&now.states))
                        .map(|(b, s)| effects.potential_energy(b, &s.position)),
                );
                let links_before = self.links.potential(&now.states);
                // The step's last evaluation's factor, a nearby K for the projection.
                project(
                    &self.links,
                    bodies,
                    &mut now.states,
                    impulses,
                    &mut self.projection_buffers,
                    self.system_buffers.last_factor(),
                );
                let projected = &self.projection_buffers;
                let kinetic = projected.kinetic_before().iter().copied();
                let before = energy_sum(kinetic, potential.iter().copied()) + links_before;
                let kinetic = projected.kinetic_after(bodies, &now.states);
                let potential = (bodies.iter().zip(&now.states))
                    .map(|(b, s)| effects.potential_energy(b, &s.position));
                let after = energy_sum(kinetic, potential) + self.links.potential(&now.states);
                (before, after)
            };
            for (load, impulse) in now.joint_loads.iter_mut().zip(impulses.iter()) {
                load.force += impulse.force / self.dt;
                load.torque += impulse.torque / self.dt;
            }
            now.ledger.joint_correction += after - before;
        }
        // Fixed bodies are the world: no potential energy booked.
        let moving = (self.bodies.iter().zip(&now.states)).filter(|(b, _)| !b.fixed);
        let gravity = moving.fold(0.0, |u, (b, s)| {
            u + self.effects.potential_energy(b, &s.position)
        });
        gravity + self.links.potential(&now.states)
    }

    /// The step's contact constants (bounce speed, margins, e, μ): `collision::step_context`.
    /// Built once per step ([`World::step`]).
    fn step_context(&self) -> StepContext {
        StepContext::new(self.dt, self.effects.gravity(), self.contact.as_ref())
    }

    /// One step of every cloth but its last contact pass: velocity half, the obstacles'
    /// velocity pass, position half. Books the damping and drag losses as drag work and the
    /// velocity pass's energy as contact energy; returns the cloths' spring and gravitational
    /// energy after the step (for the guard).
    fn integrate_cloths(&mut self, context: &StepContext) -> f64 {
        let loads = &self.cloth_loads;
        let now = &mut self.now;
        let mut potential = 0.0;
        let mut joint_impulses = Vec::new();
        now.cloth_obstacle_contacts
            .resize(now.cloths.0.len(), [0, 0]);
        now.cloth_energies.clear();
        now.cloth_body_contacts.clear();
        now.cloth_body_contacts.resize(now.cloths.0.len(), 0);
        now.cloth_attach_loads.clear();
        now.cloth_attach_loads
            .resize(now.cloths.0.len(), [Vector3::zeros(); 2]);
        for (k, cloth) in now.cloths.0.iter_mut().enumerate() {
            if cloth.integrator == ClothIntegrator::ImplicitEuler && self.contact.is_some() {
                // Contacts (and attachments) inside backward Euler's solve (`cloth::ties`).
                let scene = TiedScene {
                    loads,
                    context,
                    bodies: &self.bodies,
                    start: &now.before,
                    obstacles: &self.obstacles,
                    attachments: self.cloth_attachments.get(k).map_or(&[][..], |a| &a[..]),
                    factor: self.integrator.position_factor(),
                    links: &self.links,
                    predicted: &now.collide_moves,
                };
                let tied = tied_step(cloth, &scene, &mut now.states, &mut joint_impulses);
                // The joints held inside the solve: their share of the step's reaction.
                for (load, impulse) in now.joint_loads.iter_mut().zip(&joint_impulses) {
                    load.force += impulse.force / self.dt;
                    load.torque += impulse.torque / self.dt;
                }
                now.cloth_body_contacts[k] = tied.contacts;
                now.cloth_attach_loads[k] = tied.attach_impulse.map(|j| j / self.dt);
                now.cloth_obstacle_contacts[k] = [tied.obstacle_contacts, 0];
                if tied.energy_taken != 0.0 {
                    now.ledger.book_contact(tied.energy_taken, 0.0);
                }
                if !context.response.particle().ties() {
                    // A response whose particle contacts are not ties (`collision::particle`):
                    // the solve held the attachments only, its contacts act after it, as an
                    // explicit cloth's.
                    let passes = VelocityPasses {
                        obstacles: &self.obstacles,
                        bodies: &self.bodies,
                        start: &now.before,
                        context,
                    };
                    let counts = passes.run(
                        cloth,
                        &mut now.states,
                        &mut self.particle_contacts,
                        &mut now.ledger,
                    );
                    now.cloth_obstacle_contacts[k] = [counts[0], 0];
                    now.cloth_body_contacts[k] = counts[1];
                }
                let lost = cloth.advance_positions(loads, self.dt);
                now.ledger.drag_work -= lost.damping + lost.drag;
                let e = cloth_energy(cloth, loads);
                potential += e.potential;
                now.cloth_energies.push(e);
                continue;
            }
            cloth.velocity_step(loads, self.dt);
            let passes = VelocityPasses {
                obstacles: &self.obstacles,
                bodies: if self.contact.is_some() {
                    &self.bodies
                } else {
                    &[]
                },
                start: &now.before,
                context,
            };
            let counts = passes.run(
                cloth,
                &mut now.states,
                &mut self.particle_contacts,
                &mut now.ledger,
            );
            if !self.obstacles.is_empty() {
                now.cloth_obstacle_contacts[k] = [counts[0], 0];
            }
            if self.contact.is_some() && !self.bodies.is_empty() {
                now.cloth_body_contacts[k] = counts[1];
            }
            if let Some(list) = self.cloth_attachments.get(k).filter(|l| !l.is_empty()) {
                // An explicit cloth's attachments: impulses after the velocity half.
                let holding = Holding {
                    bodies: &self.bodies,
                    attachments: list,
                    dt: self.dt,
                    factor: self.integrator.position_factor(),
                    links: &self.links,
                };
                let held = hold_attachments(cloth, &holding, &mut now.states, &mut joint_impulses);
                // The joints that hold the attachments' bodies: their share of the reaction.
                for (load, impulse) in now.joint_loads.iter_mut().zip(&joint_impulses) {
                    load.force += impulse.force / self.dt;
                    load.torque += impulse.torque / self.dt;
                }
                // An ideal hold does no work: the particle ends on the body's point, and the
                // pair's impulses ±J act at the same velocity. The kinetic energy the velocity
                // half gave the particle off its point is symplectic Euler's splitting, left to
                // the drift, not booked as a contact's loss.
                now.cloth_attach_loads[k] = held.impulse.map(|j| j / self.dt);
            }
            let lost = cloth.advance_positions(loads, self.dt);
            now.ledger.drag_work -= lost.damping + lost.drag;
            let e = cloth_energy(cloth, loads);
            potential += e.potential;
            now.cloth_energies.push(e);
        }
        potential
    }

    /// The collide phase of the cloths: the obstacles' position pass, then the particles
    /// against the bodies (`cloth_coupling`). Books the measured energy change as contact
    /// energy.
    fn collide_cloths(&mut self, context: &StepContext) {
        if self.contact.is_none() {
            return;
        }
        if self.obstacles.is_empty() && self.bodies.is_empty() {
            return;
        }
        // The cloths' energy as the integrate phase left it (measured there).
        let bodies_before = total_energy(&self.bodies, &self.effects, &self.now.states);
        let before = if self.now.cloth_energies.len() == self.now.cloths.0.len() {
            let cloths =
                (self.now.cloth_energies.iter()).fold(Energy::default(), |sum, &e| sum + e);
            bodies_before + cloths
        } else {
            self.total_energy()
        };
        let mut touched = false;
        let now = &mut self.now;
        now.cloth_obstacle_contacts
            .resize(now.cloths.0.len(), [0, 0]);
        for (k, cloth) in now.cloths.0.iter_mut().enumerate() {
            if !self.obstacles.is_empty() {
                now.cloth_obstacle_contacts[k][1] = cloth
                    .collide_obstacles(
                        &self.obstacles,
                        context,
                        &self.cloth_loads,
                        &mut self.particle_contacts,
                    )
                    .contacts;
                touched |= !self.particle_contacts.is_empty();
            }
            let touching = collide_bodies(cloth, &self.bodies, &mut now.states, context);
            now.cloth_body_contacts[k] += touching;
            touched |= touching > 0;
        }
        // Nothing touched: nothing changed.
        let after = if touched { self.total_energy() } else { before };
        if after.total != before.total {
            let now = &mut self.now;
            now.ledger.book_contact(before.total, after.total);
            now.guard.after_collision(&after);
        }
    }

    /// The drag power of every body together, at the current states.
    fn drag_power(&self) -> DragPower {
        let mut sum = DragPower::default();
        for (body, state) in self.bodies.iter().zip(&self.now.states) {
            let p = drag_power(
                body,
                &self.effects,
                &derive(body, state),
                &state.angular_momentum,
            );
            sum.power += p.power;
            sum.rate += p.rate;
        }
        sum
    }

    /// *collide*: detection and response, only when something can touch (obstacles, or
    /// several bodies) and the scene gives a response.
    #[inline]
    fn collide_phase(&mut self, context: &StepContext) {
        if !self.now.cloths.0.is_empty() {
            self.collide_cloths(context);
        }
        let (true, Some(model)) = (self.can_touch(), &self.contact) else {
            return;
        };
        let now = &mut self.now;
        let (links, bodies, dt) = (&self.links, &self.bodies, self.dt);
        // The motors' impulses the drive pass gave this step (what is left of their bounds
        // goes to the contacts' solve); none without motors.
        let motored = links.joints.iter().any(|j| j.motor.is_some());
        let given: Vec<f64> = if motored {
            now.joint_drives.iter().map(|d| d.motor * dt).collect()
        } else {
            Vec::new()
        };
        self.scratch.joined.scene_motored = motored;
        // The joints' rows, solved with the contacts (`collision::impulse::joined`).
        let joint_rows = |states: &[State], rows: &mut Vec<JointRow>| {
            equality_rows(links, bodies, states, (&given, dt), rows);
        };
        let input = CollideInput {
            bodies: &self.bodies,
            obstacles: &self.obstacles,
            model,
            before: &now.before,
            loads: &now.loads,
            initial_positions: &self.initial_positions,
            context: *context,
            joined: &self.joined,
            joints: (!links.joints.is_empty())
                .then_some(&joint_rows as &dyn Fn(&[State], &mut Vec<JointRow>)),
            recorded: None,
        };
        let states_before = if model.response == super::collision::Response::Seed {
            Some(now.states[0])
        } else {
            None
        };
        // Bodies holding attached particles: their states before the response, to carry the
        // particles if it moves them (`carry_attached`).
        let carrying = self.cloth_attachments.iter().any(|l| !l.is_empty());
        if carrying {
            self.carry_start.clone_from(&now.states);
        }
        self.scratch.joined.impulses.clear();
        self.scratch.joined.stops.clear();
        self.scratch.joined.motors.clear();
        self.scratch.joined.motor_work = 0.0;
        let mut measured = collide(
            &input,
            &mut now.states,
            &mut now.contacts,
            &mut self.scratch,
        );
        // The joints' impulses in the contacts' solve (`impulse::joined`), as forces over
        // the step.
        for (load, impulse) in now
            .joint_loads
            .iter_mut()
            .zip(&self.scratch.joined.impulses)
        {
            load.force += impulse.0 / self.dt;
            load.torque += impulse.1 / self.dt;
        }
        // Its stops' share (`joints::drive::touching_stops`), on the joints panel.
        let stops = &self.scratch.joined.stops;
        book_stops(links, &now.states, stops, &mut now.joint_drives, self.dt);
        // Its motors' share: their force on the panel, their work in the ledger (taken out of
        // the response's change, which the contacts' row books).
        for (drive, &impulse) in now.joint_drives.iter_mut().zip(&self.scratch.joined.motors) {
            drive.motor += impulse / self.dt;
        }
        let motor_work = self.scratch.joined.motor_work;
        if !self.links.joints.is_empty() && !now.contacts.is_empty() && states_before.is_none() {
            // The joints held with the contacts (`joints::contact`); booked with the response.
            let before = total_energy(&self.bodies, &self.effects, &now.states);
            let mut impulses = vec![Loads::default(); self.links.joints.len()];
            let held = hold(
                &self.links,
                &self.bodies,
                &mut now.states,
                &now.contacts,
                self.dt,
                &mut impulses,
                &mut self.contact_joint_buffers,
            );
            if held.changed {
                for (load, impulse) in now.joint_loads.iter_mut().zip(&impulses) {
                    load.force += impulse.force / self.dt;
                    load.torque += impulse.torque / self.dt;
                }
                let stops = self.contact_joint_buffers.stops();
                book_stops(links, &now.states, stops, &mut now.joint_drives, self.dt);
                let after = total_energy(&self.bodies, &self.effects, &now.states);
                measured = Some(match measured {
                    Some(change) => EnergyChange { after, ..change },
                    None => EnergyChange { before, after },
                });
            }
        }
        let change = match (measured, states_before) {
            (Some(change), _) => Some(change),
            // `seed` measures nothing: measured here when it changed the state.
            (None, Some(before)) if before != now.states[0] => Some(EnergyChange {
                before: energy(&self.bodies[0], &self.effects, &before) + self.others_energy(),
                after: self.total_energy(),
            }),
            _ => None,
        };
        if let Some(change) = change {
            // Energy ledger: what the response took or gave.
            let now = &mut self.now;
            now.ledger.motor_work += motor_work;
            now.ledger
                .book_contact(change.before.total, change.after.total - motor_work);
            now.guard.after_collision(&change.after);
        }
        if carrying {
            self.carry_attached();
        }
    }

    /// After the rigid response: the attached particles of every body it moved go back on
    /// their points with their points' velocities (`cloth_coupling::carry_attachments`). The
    /// momentum they take came through the body from what it touches: it is added to the
    /// body's contacts this step with obstacles and fixed bodies, shared as their normal
    /// impulses share the load, so that the contacts report the support of the body and its
    /// particles together — exactly what one rigid body of both would have received from
    /// contacts that hold it still (a frame at rest on the floor). A body the response moved
    /// without such a contact (pushed by another moving body) gives the particles their
    /// momentum itself (P −= Σ m Δv, L −= Σ r × m Δv): momentum is kept, and the particles
    /// then lag its point velocity by that small change (O(m/M)), their positions exact. The
    /// energy the carrying changes (kinetic, gravitational, spring; the body's in that last
    /// case) is booked with the contacts, measured on what it moved (`carry_attachments`).
    fn carry_attached(&mut self) {
        let now = &mut self.now;
        let moves: Vec<BodyMove> = (self.carry_start.iter())
            .zip(&now.states)
            .map(|(before, after)| {
                if before != after {
                    BodyMove::between(before, after)
                } else {
                    BodyMove::NONE
                }
            })
            .collect();
        // Carried: what the response moved, and what this step's ties led by the last move
        // (a body moved then and not now: its particles went one move too far).
        let led = std::mem::replace(&mut now.collide_moves, moves);
        let moved: Vec<bool> = (now.collide_moves.iter())
            .enumerate()
            .map(|(b, m)| *m != BodyMove::NONE || led.get(b).is_some_and(|l| *l != BodyMove::NONE))
            .collect();
        if !moved.iter().any(|&m| m) {
            return;
        }
        let gravity = self.cloth_loads.gravity;
        let mut energy_change = 0.0;
        let mut carried = vec![Carried::default(); self.bodies.len()];
        for (k, (cloth, list)) in (now.cloths.0.iter_mut())
            .zip(&self.cloth_attachments)
            .enumerate()
        {
            let mut mine = vec![Carried::default(); self.bodies.len()];
            energy_change += carry_attachments(
                cloth,
                gravity,
                &self.bodies,
                &now.states,
                list,
                &moved,
                &mut mine,
            );
            // Part of what the attachments gave the cloth this step (about the origin:
            // Σ x_p × m Δv = Σ (x_b × J + r × J)).
            if let Some(load) = now.cloth_attach_loads.get_mut(k) {
                for (b, c) in mine.iter().enumerate() {
                    load[0] += c.impulse / self.dt;
                    load[1] += (now.states[b].position.cross(&c.impulse) + c.moment) / self.dt;
                }
            }
            for (sum, c) in carried.iter_mut().zip(&mine) {
                sum.impulse += c.impulse;
                sum.moment += c.moment;
            }
        }
        let bodies = &self.bodies;
        let holds =
            |c: &Contact, b: usize| c.body == b && !super::collision::moves(bodies, c.other);
        for (b, carry) in carried.iter().enumerate() {
            if carry.impulse == Vector3::zeros() && carry.moment == Vector3::zeros() {
                continue;
            }
            let load: f64 = (now.contacts.iter())
                .filter(|c| holds(c, b))
                .map(|c| c.impulse.dot(&c.normal).max(0.0))
                .sum();
            if load > 0.0 {
                for c in now.contacts.iter_mut().filter(|c| holds(c, b)) {
                    let share = c.impulse.dot(&c.normal).max(0.0) / load;
                    c.impulse += carry.impulse * share;
                }
            } else {
                let (body, state) = (&self.bodies[b], &mut now.states[b]);
                let before = energy(body, &self.effects, state).total;
                state.linear_momentum -= carry.impulse;
                state.angular_momentum -= carry.moment;
                energy_change += energy(body, &self.effects, state).total - before;
            }
        }
        if energy_change != 0.0 {
            now.ledger.book_contact(0.0, energy_change);
        }
    }

    /// The energy of every body but the first, and of the cloths (`seed` changes the first
    /// body only).
    fn others_energy(&self) -> Energy {
        self.bodies
            .iter()
            .zip(&self.now.states)
            .skip(1)
            .fold(self.cloths_energy(&self.now.cloths.0), |e, (b, s)| {
                e + energy(b, &self.effects, s)
            })
    }

    /// Σ over cloths of T (kinetic) and U + V (potential).
    fn cloths_energy(&self, cloths: &[Cloth]) -> Energy {
        cloths.iter().fold(Energy::default(), |sum, c| {
            sum + cloth_energy(c, &self.cloth_loads)
        })
    }

    /// The cloths, in order.
    pub fn cloths(&self) -> &[Cloth] {
        &self.now.cloths.0
    }

    /// The index of the cloth with this name.
    pub fn cloth_index(&self, name: &str) -> Option<usize> {
        self.now.cloths.0.iter().position(|c| c.name == name)
    }

    /// The explicit stability limit of cloth `index` at rest (`symplectic-euler` is stable
    /// for dt below its [`ExplicitLimit::dt`]).
    pub fn cloth_limit(&self, index: usize) -> &ExplicitLimit {
        &self.cloth_limits[index]
    }

    /// Gravity and drag as they act on particles.
    pub fn cloth_loads(&self) -> &ClothLoads {
        &self.cloth_loads
    }

    /// The force the attachments of cloth `index` gave it, averaged over the last step (its
    /// attachment impulses over dt; the bodies took the opposite), N, and that force's moment
    /// about the world origin, Σ x_a × F_a (x_a each attachment's point), N·m. Zero before
    /// the first step and without attachments.
    pub fn cloth_attach_load(&self, index: usize) -> [Vector3<f64>; 2] {
        self.now
            .cloth_attach_loads
            .get(index)
            .copied()
            .unwrap_or([Vector3::zeros(); 2])
    }

    /// Particle–body contacts of cloth `index` in the last step: the velocity pass of the
    /// integrate phase and the collide phase together (`cloth_coupling`).
    pub fn cloth_body_contacts(&self, index: usize) -> usize {
        self.now
            .cloth_body_contacts
            .get(index)
            .copied()
            .unwrap_or(0)
    }

    /// Particle–obstacle contacts of cloth `index` in the last step: `[velocity pass,
    /// position pass]` — particles stopped at an obstacle's surface within the integrate
    /// phase, and particles pushed back out by the collide phase.
    pub fn cloth_obstacle_contacts(&self, index: usize) -> [usize; 2] {
        self.now
            .cloth_obstacle_contacts
            .get(index)
            .copied()
            .unwrap_or([0, 0])
    }

    /// Whether anything can touch: obstacles, or more than one body.
    #[inline]
    fn can_touch(&self) -> bool {
        (!self.obstacles.is_empty() && !self.bodies.is_empty()) || self.bodies.len() > 1
    }

    /// The phase that [`World::step_phase`] will run next.
    pub fn next_phase(&self) -> Phase {
        self.now.last.map_or(Phase::Derive, Phase::next)
    }

    /// The phase just completed (None before the first).
    pub fn last_phase(&self) -> Option<Phase> {
        self.now.last
    }

    /// Completed integrate phases.
    pub fn step_count(&self) -> u64 {
        self.now.step
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        self.now.step as f64 * self.dt
    }

    /// Time step, s.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// How many bodies.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// The bodies' names, in order.
    pub fn body_names(&self) -> &[String] {
        &self.names
    }

    /// The index of the body with this name.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The current state of the first body (a world of cloths only: at rest at the origin).
    pub fn state(&self) -> &State {
        self.now.states.first().unwrap_or(&REST)
    }

    /// The current states, one per body.
    pub fn states(&self) -> &[State] {
        &self.now.states
    }

    /// The state of the first body at t = 0 (a world of cloths only: at rest at the origin).
    pub fn initial_state(&self) -> &State {
        self.initial.first().unwrap_or(&REST)
    }

    /// The states at t = 0, one per body.
    pub fn initial_states(&self) -> &[State] {
        &self.initial
    }

    /// The first body (a world of cloths only has none: check [`World::body_count`]).
    pub fn body(&self) -> &Body {
        &self.bodies[0]
    }

    /// The bodies, in order.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The declared effects.
    pub fn effects(&self) -> &Effects {
        &self.effects
    }

    /// The declared obstacles.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// The contact parameters, if the scene has obstacles.
    pub fn contact_model(&self) -> Option<&ContactModel> {
        self.contact.as_ref()
    }

    /// The integrator in use.
    pub fn integrator(&self) -> Integrator {
        self.integrator
    }

    /// Contacts handled by the last collide phase.
    pub fn contacts(&self) -> &[Contact] {
        &self.now.contacts
    }

    /// What the `impulse` solver did since the world was built: direct solves, declined ones,
    /// sweeps (issue 17: a resting scene's solver path must not degrade).
    pub fn contact_counters(&self) -> super::collision::impulse::Counters {
        self.scratch.counters
    }

    /// What the `impulse` solver did in the last collide phase: its work and, when it stopped
    /// at its work budget unconverged, the residual (the loop strip shows it).
    pub fn contact_report(&self) -> super::collision::impulse::StepReport {
        self.scratch.report
    }

    /// Switches integrator, keeping t and the state (the orientation changes representation;
    /// a drifted `euler-seed` matrix becomes the nearest rotation). The current frame restarts
    /// at its derive phase.
    pub fn set_integrator(&mut self, integrator: Integrator) {
        self.integrator = integrator;
        let now = &mut self.now;
        if now.last != Some(Phase::Collide) && now.last.is_some() {
            now.last = Some(Phase::Collide);
        }
        for (i, body) in self.bodies.iter().enumerate() {
            let state = &mut now.states[i];
            state.orientation = integrator.orientation_for(&state.orientation);
            now.kinematics[i] = derive(body, state);
        }
        self.system_loads();
    }

    /// Changes one continuous parameter while the world runs (module `tuning`): it acts from
    /// the next step on, with t and the state kept; the energy the change itself adds or
    /// removes (a new g moves V, a new k moves U) is booked into the ledger's E₀, so the drift
    /// stays the integrator's. As with [`World::set_integrator`], a frame in progress counts
    /// as done, and the forces are evaluated anew with the new value.
    pub fn tune(&mut self, tuning: super::tuning::Tuning) -> Result<(), String> {
        use super::tuning::Tuning;
        if let Some(problem) = tuning.problem() {
            return Err(problem);
        }
        let before = self.total_energy().total;
        match tuning {
            Tuning::Gravity(g) => {
                let mut list: Vec<Effect> = (self.effects.list().iter())
                    .filter(|e| !matches!(e, Effect::Gravity(_)))
                    .copied()
                    .collect();
                list.extend(g.map(Effect::Gravity));
                self.effects = Effects::new(list);
            }
            Tuning::Drag(drag) => {
                let mut list: Vec<Effect> = (self.effects.list().iter())
                    .filter(|e| !matches!(e, Effect::Drag { .. }))
                    .copied()
                    .collect();
                list.extend(drag.map(|(linear, angular)| Effect::Drag { linear, angular }));
                self.effects = Effects::new(list);
            }
            Tuning::Restitution(e) => {
                self.contact
                    .as_mut()
                    .ok_or("the scene has no contact model: no restitution to change")?
                    .restitution = e;
            }
            Tuning::Friction(mu) => {
                self.contact
                    .as_mut()
                    .ok_or("the scene has no contact model: no friction to change")?
                    .friction = mu;
            }
            Tuning::SpringStiffness { spring, stiffness } => {
                self.links
                    .springs
                    .get_mut(spring)
                    .ok_or_else(|| format!("the scene has no spring number {}", spring + 1))?
                    .stiffness = stiffness;
            }
            Tuning::MotorSpeed { joint, speed } => {
                self.links
                    .joints
                    .get_mut(joint)
                    .and_then(|j| j.motor.as_mut())
                    .ok_or_else(|| format!("the scene has no motor on joint number {}", joint + 1))?
                    .speed = speed;
            }
        }
        self.cloth_loads = ClothLoads::from_effects(&self.effects);
        // The forces at the current state, with the new value (a frame in progress counts
        // as done).
        let now = &mut self.now;
        if now.last != Some(Phase::Collide) && now.last.is_some() {
            now.last = Some(Phase::Collide);
        }
        for (i, body) in self.bodies.iter().enumerate() {
            now.kinematics[i] = derive(body, &now.states[i]);
        }
        self.system_loads();
        let after = self.total_energy().total;
        self.now.ledger.initial += after - before;
        self.tuned = true;
        Ok(())
    }

    /// Switches the collision response (takes effect at the next collide phase).
    pub fn set_contact_model(&mut self, model: ContactModel) {
        self.contact = Some(model);
    }

    /// Switches the particle integrator of cloth `index` (and of its t = 0 state, so a reset
    /// keeps it), keeping its particles, velocities and losses. The step's scratch, the
    /// implicit step's warm start among it, starts over empty as for a new sheet: the next
    /// step sizes it and starts the solve from Δv = 0. As with [`World::set_integrator`], a
    /// frame in progress counts as done. (The integrator is part of the checkpoint: a history
    /// replaying frames from an earlier checkpoint must start anew from here.)
    pub fn set_cloth_integrator(&mut self, index: usize, integrator: ClothIntegrator) {
        self.initial_cloths[index].integrator = integrator;
        let now = &mut self.now;
        if now.cloths.0[index].integrator == integrator {
            return;
        }
        if now.last != Some(Phase::Collide) && now.last.is_some() {
            now.last = Some(Phase::Collide);
        }
        // The t = 0 sheet has never stepped: its scratch is empty.
        let mut fresh = self.initial_cloths[index].clone();
        let running = &mut now.cloths.0[index];
        std::mem::swap(&mut fresh.positions, &mut running.positions);
        std::mem::swap(&mut fresh.velocities, &mut running.velocities);
        fresh.losses = running.losses;
        fresh.solver = running.solver;
        *running = fresh;
    }

    /// What the world steps with besides its checkpoint: the body integrator and the contact
    /// model (both can be switched while it runs). A checkpoint and these replay the frames
    /// after it exactly.
    pub fn stepping(&self) -> Stepping {
        Stepping {
            integrator: self.integrator,
            contact: self.contact,
        }
    }

    /// Sets what the world steps with, leaving the state alone (unlike
    /// [`World::set_integrator`], which converts the orientation): for replaying frames from a
    /// checkpoint taken under these settings.
    pub fn set_stepping(&mut self, stepping: Stepping) {
        self.integrator = stepping.integrator;
        self.contact = stepping.contact;
    }

    /// A copy of everything that changes as the world steps.
    pub fn checkpoint(&self) -> Checkpoint {
        self.now.clone()
    }

    /// Puts the world back exactly at a checkpoint taken from it.
    pub fn restore(&mut self, checkpoint: &Checkpoint) {
        self.now.clone_from(checkpoint);
    }

    /// Back to t = 0.
    pub fn reset(&mut self) {
        self.tuned = false;
        let mut now = fresh(
            &self.bodies,
            &self.effects,
            self.integrator,
            &self.initial,
            &self.initial_cloths,
        );
        if !self.initial_cloths.is_empty() {
            let cloths = self.cloths_energy(&self.initial_cloths);
            let energy = total_energy(&self.bodies, &self.effects, &self.initial) + cloths;
            let weight = self.effects.gravity().map_or(0.0, |g| {
                self.bodies
                    .iter()
                    .map(|b| b.mass * g.norm() * b.radius)
                    .chain(self.initial_cloths.iter().map(|c| {
                        let span = c.positions.iter().map(|x| (x - c.positions[0]).norm());
                        c.total_mass * g.norm() * span.fold(0.0, f64::max)
                    }))
                    .sum()
            });
            now.ledger = EnergyLedger::new(energy.total);
            now.guard = EnergyGuard::new(&energy, weight);
        }
        self.now = now;
        if !self.links.is_empty() {
            let springs = self.links.potential(&self.initial);
            if springs != 0.0 {
                let energy = self.initial_total_energy();
                let weight = self.effects.gravity().map_or(0.0, |g| {
                    self.bodies
                        .iter()
                        .map(|b| b.mass * g.norm() * b.radius)
                        .sum()
                });
                let weight = weight + springs.abs();
                self.now.ledger = EnergyLedger::new(energy.total);
                self.now.guard = EnergyGuard::new(&energy, weight);
            }
            self.system_loads();
        }
    }

    /// Vertex positions `pᵢ = x + R r₀ᵢ` of the first body's current state.
    pub fn vertices(&self) -> Vec<Vector3<f64>> {
        self.vertices_of(0)
    }

    /// Vertex positions `pᵢ = x + R r₀ᵢ` of body `index`'s current state.
    pub fn vertices_of(&self, index: usize) -> Vec<Vector3<f64>> {
        let Some(state) = self.now.states.get(index) else {
            return Vec::new();
        };
        let r = state.orientation.matrix();
        let x = state.position;
        self.bodies[index]
            .points_body
            .iter()
            .map(|r0| x + r * r0)
            .collect()
    }

    /// Kinetic, potential and total energy of a state of the first body (measured from the
    /// state itself).
    pub fn energy_of(&self, state: &State) -> Energy {
        self.bodies
            .first()
            .map_or(Energy::default(), |b| energy(b, &self.effects, state))
    }

    /// Energy of body `index` now.
    pub fn body_energy(&self, index: usize) -> Energy {
        energy(&self.bodies[index], &self.effects, &self.now.states[index])
    }

    /// The whole scene's energy now: the sum over its bodies.
    pub fn total_energy(&self) -> Energy {
        let mut bodies = total_energy(&self.bodies, &self.effects, &self.now.states);
        if !self.links.springs.is_empty() {
            bodies = bodies + self.springs_energy(&self.now.states);
        }
        if self.now.cloths.0.is_empty() {
            bodies
        } else {
            bodies + self.cloths_energy(&self.now.cloths.0)
        }
    }

    /// Drag work and contact energy booked since t = 0.
    pub fn energy_ledger(&self) -> &EnergyLedger {
        &self.now.ledger
    }

    /// The change of the scene's energy since t = 0 split into drag work, contacts and the
    /// remainder, the numerical drift.
    pub fn energy_balance(&self) -> EnergyBalance {
        let cloths = &self.now.cloths.0;
        let damped = cloths
            .iter()
            .any(|c| c.springs.iter().any(|s| s.damping > 0.0));
        // After a live change of a parameter, E₀ is the ledger's, which booked it.
        let initial = match self.initial_total_energy() {
            e if self.tuned => Energy {
                total: self.now.ledger.initial,
                ..e
            },
            e => e,
        };
        let mut balance = self.now.ledger.balance(
            &initial,
            &self.total_energy(),
            self.effects.depends_on_velocity() || damped || self.links.damped(),
            self.can_touch()
                || (!cloths.is_empty() && self.contact.is_some())
                || self.links.joints.iter().any(|j| j.limits.is_some()),
        );
        if self.links.motorised() {
            balance.motor = Some(self.now.ledger.motor_work);
        }
        if self.hand.is_some() || self.now.ledger.hand_work != 0.0 {
            balance.hand = Some(self.now.ledger.hand_work);
        }
        if !cloths.is_empty() {
            // Shown, not subtracted: the springs' energy is part of E already.
            balance.springs = Some(cloths.iter().map(Cloth::spring_energy).sum());
        }
        if !self.links.springs.is_empty() {
            let v = self.links.potential(&self.now.states);
            balance.springs = Some(balance.springs.unwrap_or(0.0) + v);
        }
        balance
    }

    /// The whole scene's energy at t = 0.
    pub fn initial_total_energy(&self) -> Energy {
        total_energy(&self.bodies, &self.effects, &self.initial)
            + self.cloths_energy(&self.initial_cloths)
            + self.springs_energy(&self.initial)
    }

    /// The springs' potential energy at these states, as an [`Energy`].
    fn springs_energy(&self, states: &[State]) -> Energy {
        let v = self.links.potential(states);
        Energy {
            kinetic: 0.0,
            potential: v,
            total: v,
        }
    }

    /// A non-finite or runaway state, if the simulation has diverged. With cloths, a
    /// non-finite particle or a runaway the cloths hold most of is named after its cloth and
    /// its particle integrator.
    pub fn divergence(&self) -> Option<Divergence> {
        let named = |quantity: String, body: usize| {
            if self.bodies.len() > 1 {
                format!("{quantity} (body {})", self.names[body])
            } else {
                quantity
            }
        };
        let mut subject = None;
        let quantity = self
            .now
            .states
            .iter()
            .enumerate()
            .find_map(|(i, s)| not_finite(s).map(|q| named(q.to_string(), i)))
            .or_else(|| {
                let (cloth, quantity) = self.cloth_not_finite()?;
                subject = Some(cloth_subject(cloth));
                Some(quantity)
            })
            .or_else(|| {
                let (turn, fastest) = self
                    .bodies
                    .iter()
                    .zip(&self.now.states)
                    .map(|(b, s)| derive(b, s).angular_velocity.norm() * self.dt)
                    .enumerate()
                    .fold(
                        (0.0, 0),
                        |best, (i, t)| if t > best.0 { (t, i) } else { best },
                    );
                let total = self.total_energy();
                self.now
                    .guard
                    .check(&total, &self.now.ledger, turn)
                    .map(|q| {
                        if q.starts_with("rotation") {
                            named(q, fastest)
                        } else if let Some(cloth) = self.runaway_cloth(&total) {
                            subject = Some(cloth_subject(cloth));
                            // The subject names the cloth: said once.
                            format!("{q}, held as kinetic + spring energy by the cloth")
                        } else {
                            q
                        }
                    })
            })?;
        Some(Divergence {
            step: self.now.step,
            time: self.time(),
            quantity,
            integrator: self.integrator,
            dt: self.dt,
            subject,
        })
    }

    /// The first cloth with a non-finite particle, and what is not finite.
    fn cloth_not_finite(&self) -> Option<(&Cloth, String)> {
        let finite = |v: &Vector3<f64>| v.iter().all(|c| c.is_finite());
        self.now.cloths.0.iter().find_map(|c| {
            let what = if !c.positions.iter().all(finite) {
                "particle position"
            } else if !c.velocities.iter().all(finite) {
                "particle velocity"
            } else {
                return None;
            };
            Some((
                c,
                format!("{what} is not finite ({})", super::cloth::label(&c.name)),
            ))
        })
    }

    /// The cloth holding the most kinetic and spring energy, when the cloths hold more of it
    /// than the bodies hold kinetic energy (then a runaway is theirs).
    fn runaway_cloth(&self, total: &Energy) -> Option<&Cloth> {
        let held = |c: &Cloth| c.kinetic_energy() + c.spring_energy();
        let cloths = &self.now.cloths.0;
        let all: f64 = cloths.iter().map(held).sum();
        let bodies = total.kinetic - cloths.iter().map(Cloth::kinetic_energy).sum::<f64>();
        if cloths.is_empty() || all <= bodies {
            return None;
        }
        cloths.iter().max_by(|a, b| held(a).total_cmp(&held(b)))
    }

    /// Every quantity a user is shown, after the last phase (the panels show the first body).
    pub fn snapshot(&self) -> Snapshot {
        Snapshot::of(self)
    }

    /// The same, with the panels showing body `index`.
    pub fn snapshot_of(&self, index: usize) -> Snapshot {
        Snapshot::of_body(self, index)
    }

    /// The derive phase's results for the current frame (first body).
    pub fn kinematics(&self) -> &Kinematics {
        &self.now.kinematics[0]
    }

    /// The derive phase's results for body `index`.
    pub fn kinematics_of(&self, index: usize) -> &Kinematics {
        &self.now.kinematics[index]
    }

    /// The forces phase's results for the current frame (first body).
    pub fn loads(&self) -> &Loads {
        &self.now.loads[0]
    }

    /// The forces phase's results for body `index`.
    pub fn loads_of(&self, index: usize) -> &Loads {
        &self.now.loads[index]
    }
}

/// "cloth NAME, integrator NAME": a cloth's divergence names its own integrator.
fn cloth_subject(cloth: &Cloth) -> String {
    format!(
        "{}, integrator {}",
        super::cloth::label(&cloth.name),
        cloth.integrator.name()
    )
}

/// What [`World::state`] shows for a world of cloths only.
static REST: State = State {
    position: Vector3::new(0.0, 0.0, 0.0),
    orientation: super::state::Orientation::Quaternion(nalgebra::UnitQuaternion::new_unchecked(
        nalgebra::Quaternion::new(1.0, 0.0, 0.0, 0.0),
    )),
    linear_momentum: Vector3::new(0.0, 0.0, 0.0),
    angular_momentum: Vector3::new(0.0, 0.0, 0.0),
};

/// Σ over bodies of K + V from each body's kinetic and potential energy: the same sum as
/// [`total_energy`]'s total, bit for bit.
fn energy_sum(kinetic: impl Iterator<Item = f64>, potential: impl Iterator<Item = f64>) -> f64 {
    kinetic.zip(potential).fold(0.0, |e, (k, v)| e + (k + v))
}

/// Σ over bodies of their energies.
fn total_energy(bodies: &[Body], effects: &Effects, states: &[State]) -> Energy {
    bodies
        .iter()
        .zip(states)
        .fold(Energy::default(), |e, (b, s)| e + energy(b, effects, s))
}

/// A cloth's T and U + V as the scene's energy.
fn cloth_energy(cloth: &Cloth, loads: &ClothLoads) -> Energy {
    let e = cloth.energy(loads);
    Energy {
        kinetic: e.kinetic,
        potential: e.spring + e.gravitational,
        total: e.total(),
    }
}

/// The checkpoint of a world at its initial states.
fn fresh(
    bodies: &[Body],
    effects: &Effects,
    integrator: Integrator,
    initial: &[State],
    cloths: &[Cloth],
) -> Checkpoint {
    let kinematics: Vec<Kinematics> = bodies
        .iter()
        .zip(initial)
        .map(|(b, s)| derive(b, s))
        .collect();
    let loads = bodies
        .iter()
        .zip(&kinematics)
        .map(|(b, k)| integrator.loads(b, effects, k))
        .collect();
    let weight = effects.gravity().map_or(0.0, |g| {
        bodies.iter().map(|b| b.mass * g.norm() * b.radius).sum()
    });
    let energy = total_energy(bodies, effects, initial);
    let guard = EnergyGuard::new(&energy, weight);
    Checkpoint {
        ledger: EnergyLedger::new(energy.total),
        states: initial.to_vec(),
        before: initial.to_vec(),
        step: 0,
        last: None,
        kinematics,
        loads,
        contacts: Vec::new(),
        guard,
        cloths: Cloths(cloths.to_vec()),
        cloth_body_contacts: vec![0; cloths.len()],
        cloth_attach_loads: vec![[Vector3::zeros(); 2]; cloths.len()],
        cloth_obstacle_contacts: vec![[0, 0]; cloths.len()],
        cloth_energies: Vec::new(),
        start_joint_loads: Vec::new(),
        start_damping_power: 0.0,
        joint_loads: Vec::new(),
        joint_drives: Vec::new(),
        collide_moves: Vec::new(),
    }
}

/// A cloth's contact passes on velocities (`cloth::contact`, `cloth_coupling::explicit`),
/// between its velocity half and its positions' update: against the obstacles, then the
/// bodies (none: no pass). Books each pass's energy as contact energy.
struct VelocityPasses<'a> {
    obstacles: &'a [Obstacle],
    bodies: &'a [Body],
    /// The bodies' states at the start of the step.
    start: &'a [State],
    context: &'a StepContext,
}

impl VelocityPasses<'_> {
    /// Runs the passes; returns the obstacle and body contacts (counted with the collide
    /// phase's own).
    fn run(
        &self,
        cloth: &mut Cloth,
        states: &mut [State],
        found: &mut Vec<ParticleContact>,
        ledger: &mut EnergyLedger,
    ) -> [usize; 2] {
        let mut counts = [0, 0];
        if !self.obstacles.is_empty() {
            let report = cloth.contact_velocities(self.obstacles, self.context, found);
            counts[0] = report.contacts;
            if report.energy_taken != 0.0 {
                ledger.book_contact(report.energy_taken, 0.0);
            }
        }
        if !self.bodies.is_empty() {
            let approach = approach_bodies(cloth, self.bodies, self.start, states, self.context);
            counts[1] = approach.contacts;
            if approach.energy_taken != 0.0 {
                ledger.book_contact(approach.energy_taken, 0.0);
            }
        }
        counts
    }
}
