//! The world: one body, its declared effects and obstacles, stepped through the animation loop
//! one phase at a time.
//!
//! ```text
//! derive → forces → integrate → collide      (one frame, dt)
//! ```
//!
//! [`World::step`] runs a whole frame; [`World::step_phase`] runs one phase. Front ends read
//! [`World::snapshot`] and never recompute physics.

use super::body::Body;
use super::collision::{collide, CollideInput, Contact, ContactModel, EnergyChange, Obstacle};
use super::derive::{derive, Kinematics};
use super::divergence::{Divergence, EnergyGuard};
use super::effects::{Effects, Loads};
use super::energy_ledger::{drag_power, EnergyBalance, EnergyLedger};
use super::integrators::Integrator;
use super::snapshot::{energy, Energy, Snapshot};
use super::state::State;
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
    /// Collision detection and response (a no-op without obstacles).
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
    state: State,
    /// The state at the start of the last integrate phase (kept only when there are obstacles:
    /// the collide phase's swept tests are its only reader).
    before: State,
    step: u64,
    last: Option<Phase>,
    kinematics: Kinematics,
    loads: Loads,
    contacts: Vec<Contact>,
    guard: EnergyGuard,
    /// Drag work and contact energy booked since t = 0 (see `energy_ledger`).
    ledger: EnergyLedger,
}

/// A body in a scene, stepped through the loop.
#[derive(Debug, Clone)]
pub struct World {
    body: Body,
    effects: Effects,
    obstacles: Vec<Obstacle>,
    contact: Option<ContactModel>,
    integrator: Integrator,
    dt: f64,
    initial: State,
    now: Checkpoint,
}

impl World {
    /// A world at its initial state. `contact` must be given when there are obstacles; the
    /// orientation is converted to what `integrator` steps.
    pub fn new(
        body: Body,
        effects: Effects,
        obstacles: Vec<Obstacle>,
        contact: Option<ContactModel>,
        integrator: Integrator,
        dt: f64,
        initial: State,
    ) -> World {
        let initial = State {
            orientation: integrator.orientation_for(&initial.orientation),
            ..initial
        };
        let kinematics = derive(&body, &initial);
        let loads = integrator.loads(&body, &effects, &kinematics);
        let guard = EnergyGuard::new(&body, &effects, &initial);
        let ledger = EnergyLedger::new(energy(&body, &effects, &initial).total);
        World {
            body,
            effects,
            obstacles,
            contact,
            integrator,
            dt,
            initial,
            now: Checkpoint {
                state: initial,
                before: initial,
                step: 0,
                last: None,
                kinematics,
                loads,
                contacts: Vec::new(),
                guard,
                ledger,
            },
        }
    }

    /// Runs the rest of the current frame (all four phases from the start of a frame).
    ///
    /// From the start of a frame this is exactly `derive`, `forces`, `integrate`, `collide` as
    /// [`World::step_phase`] runs them, without dispatching on the phase in between.
    pub fn step(&mut self) {
        if self.next_phase() != Phase::Derive {
            while self.step_phase() != Phase::Collide {}
            return;
        }
        self.derive_phase();
        self.forces_phase();
        self.integrate_phase();
        self.collide_phase();
        self.now.last = Some(Phase::Collide);
    }

    /// Runs the next phase of the loop; returns the phase it ran.
    pub fn step_phase(&mut self) -> Phase {
        let phase = self.next_phase();
        match phase {
            Phase::Derive => self.derive_phase(),
            Phase::Forces => self.forces_phase(),
            Phase::Integrate => self.integrate_phase(),
            Phase::Collide => self.collide_phase(),
        }
        self.now.last = Some(phase);
        phase
    }

    /// *derive*: I⁻¹_world, ω and v from the current state.
    #[inline]
    fn derive_phase(&mut self) {
        self.now.kinematics = derive(&self.body, &self.now.state);
    }

    /// *forces*: F and τ of the declared effects at the derived velocities (for `euler-seed`,
    /// plus the report's per-vertex torque sum: see [`Integrator::loads`]).
    #[inline]
    fn forces_phase(&mut self) {
        self.now.loads = self
            .integrator
            .loads(&self.body, &self.effects, &self.now.kinematics);
    }

    /// *integrate*: one integrator step (the state before it is kept for swept collisions).
    #[inline]
    fn integrate_phase(&mut self) {
        let now = &mut self.now;
        if !self.obstacles.is_empty() {
            now.before = now.state;
        }
        // Energy ledger: the drag power at the start of the step (see `energy_ledger`).
        let drag = self.effects.depends_on_velocity();
        let drag_start = drag.then(|| {
            drag_power(
                &self.body,
                &self.effects,
                &now.kinematics,
                &now.state.angular_momentum,
            )
        });
        self.integrator.advance(
            &self.body,
            &self.effects,
            &mut now.state,
            &now.kinematics,
            &now.loads,
            self.dt,
        );
        now.step += 1;
        // Energy ledger: the drag work of this step, from its start and end states.
        if let Some(start) = drag_start {
            let end = drag_power(
                &self.body,
                &self.effects,
                &derive(&self.body, &now.state),
                &now.state.angular_momentum,
            );
            now.ledger.book_drag(&start, &end, self.dt);
        }
        now.guard.observe(
            &now.ledger,
            self.effects
                .potential_energy(&self.body, &now.state.position),
        );
    }

    /// *collide*: detection and response, only when the scene declares obstacles.
    #[inline]
    fn collide_phase(&mut self) {
        let now = &mut self.now;
        if let (false, Some(model)) = (self.obstacles.is_empty(), &self.contact) {
            let input = CollideInput {
                body: &self.body,
                obstacles: &self.obstacles,
                model,
                before: &now.before,
                loads: &now.loads,
                initial_position: &self.initial.position,
                gravity: self.effects.gravity(),
                dt: self.dt,
            };
            let state_before = now.state;
            let measured = collide(&input, &mut now.state, &mut now.contacts);
            if now.state != state_before {
                // The response's own measurement when it has one (the same numbers `energy`
                // gives), else measured here.
                let change = measured.unwrap_or_else(|| EnergyChange {
                    before: energy(&self.body, &self.effects, &state_before),
                    after: energy(&self.body, &self.effects, &now.state),
                });
                // Energy ledger: what the response took or gave.
                now.ledger
                    .book_contact(change.before.total, change.after.total);
                now.guard.after_collision(&change.after);
            }
        }
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

    /// The current state.
    pub fn state(&self) -> &State {
        &self.now.state
    }

    /// The state at t = 0.
    pub fn initial_state(&self) -> &State {
        &self.initial
    }

    /// The body.
    pub fn body(&self) -> &Body {
        &self.body
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

    /// Switches integrator, keeping t and the state (the orientation changes representation;
    /// a drifted `euler-seed` matrix becomes the nearest rotation). The current frame restarts
    /// at its derive phase.
    pub fn set_integrator(&mut self, integrator: Integrator) {
        self.integrator = integrator;
        let now = &mut self.now;
        now.state.orientation = integrator.orientation_for(&now.state.orientation);
        if now.last != Some(Phase::Collide) && now.last.is_some() {
            now.last = Some(Phase::Collide);
        }
        now.kinematics = derive(&self.body, &now.state);
        now.loads = integrator.loads(&self.body, &self.effects, &now.kinematics);
    }

    /// Switches the collision response (takes effect at the next collide phase).
    pub fn set_contact_model(&mut self, model: ContactModel) {
        self.contact = Some(model);
    }

    /// A copy of everything that changes as the world steps.
    pub fn checkpoint(&self) -> Checkpoint {
        self.now.clone()
    }

    /// Puts the world back exactly at a checkpoint taken from it.
    pub fn restore(&mut self, checkpoint: &Checkpoint) {
        self.now = checkpoint.clone();
    }

    /// Back to t = 0.
    pub fn reset(&mut self) {
        let fresh = World::new(
            self.body.clone(),
            self.effects.clone(),
            self.obstacles.clone(),
            self.contact,
            self.integrator,
            self.dt,
            self.initial,
        );
        self.now = fresh.now;
    }

    /// Vertex positions `pᵢ = x + R r₀ᵢ` of the current state.
    pub fn vertices(&self) -> Vec<Vector3<f64>> {
        let r = self.now.state.orientation.matrix();
        let x = self.now.state.position;
        self.body.points_body.iter().map(|r0| x + r * r0).collect()
    }

    /// Kinetic, potential and total energy of a state (measured from the state itself).
    pub fn energy_of(&self, state: &State) -> Energy {
        energy(&self.body, &self.effects, state)
    }

    /// A non-finite or runaway state, if the simulation has diverged.
    pub fn divergence(&self) -> Option<Divergence> {
        let energy = self.energy_of(&self.now.state);
        let turn_per_step = derive(&self.body, &self.now.state).angular_velocity.norm() * self.dt;
        self.now
            .guard
            .check(&self.now.state, &energy, &self.now.ledger, turn_per_step)
            .map(|quantity| Divergence {
                step: self.now.step,
                time: self.time(),
                quantity,
                integrator: self.integrator,
                dt: self.dt,
            })
    }

    /// Drag work and contact energy booked since t = 0.
    pub fn energy_ledger(&self) -> &EnergyLedger {
        &self.now.ledger
    }

    /// The change of energy since t = 0 split into drag work, contacts and the remainder, the
    /// numerical drift.
    pub fn energy_balance(&self) -> EnergyBalance {
        self.now.ledger.balance(
            &self.energy_of(&self.initial),
            &self.energy_of(&self.now.state),
            self.effects.depends_on_velocity(),
            !self.obstacles.is_empty(),
        )
    }

    /// Every quantity a user is shown, after the last phase.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot::of(self)
    }

    /// The derive phase's results for the current frame.
    pub fn kinematics(&self) -> &Kinematics {
        &self.now.kinematics
    }

    /// The forces phase's results for the current frame.
    pub fn loads(&self) -> &Loads {
        &self.now.loads
    }
}
