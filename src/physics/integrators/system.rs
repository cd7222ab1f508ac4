//! What every integrator steps: the whole system's state Y and its derivative f(Y)
//! (`system::System`). A world without springs or joints is a system whose evaluation is per
//! body; with them, f is the forces of all bodies at once. Each integrator is written once,
//! against a `Block` of the system (a `Method`, or a `step(system, states, start, dt,
//! buffers)` over every moving body for the one-evaluation methods); `advance` runs it over
//! the blocks: the linked system as one block (`Linked`, in buffers), or each body of a system
//! without links as a block of its own (`OneBody`, in registers: world stages through buffers
//! cost +43 % instructions on a free body).
//!
//! ```text
//! start                 Y, and f(Y) from the forces phase's kinematics and loads (`Start`)
//! rates(Y)              f at a stage Y (rk4): one body's effects (body_rates), or the linked
//!                       system's evaluation (stage_rates)
//! plus(Y, k, h)         Y + h k (one body: in registers; linked: in the buffers' slots)
//! kick(h)               P, L += h (F, τ); per body the method's own kick (exact or midpoint),
//!                       coupled at the kick's midpoint P + h/2 F: the joints' reactions depend
//!                       on the velocities (the centripetal term), a kick at the start alone
//!                       would make the method first order; in a fourth-order composition,
//!                       when F depends on the momenta, rk4 over (P, L) (below)
//! drift(h)              each body's own free flow (its method's: split or exact rotation)
//! compose               kick · drift · kick · … · kick, each a fraction of dt
//! ```
//!
//! A composition is of its order only if every sub-flow it composes is exact, or at least
//! accurate to one order more than the composition's local error: `dt⁵` for a fourth-order one.
//! With x and R held, the coupled kick is the ODE `(Ṗ, L̇) = F(x, R, P, L)`. Its force is
//! constant over the kick when it does not depend on the momenta (undamped springs, gravity),
//! and the midpoint rule is then exact. A joint's multiplier depends on the velocities (the
//! distance joint's `|ḋ|²/|d|`, the `ω × L` of the free accelerations), and so do a damped
//! spring and drag: the midpoint kick's local error is then `O(h³)`, and it caps
//! `exact-splitting-4` at order 2 (order 3 with `projection`, which removes the velocity error
//! along the rows at the end of each step). Measured on a pendulum (θ₀ = 0.2 rad, L = 1 m, over
//! 2 s, against its minimal-coordinate solution): slopes 2.000 (`none`) and 3.000
//! (`projection`) with midpoint kicks; 4.000 (`none`) and 4.01 (`projection`) with rk4 kicks
//! (errors 3.8e-9 → 3.7e-11 m at dt = 1e-2), at 19 evaluations a step instead of 9.
//!
//! The reaction each joint applied is averaged over the step with the method's own weights
//! (rk4: (j₁ + 2j₂ + 2j₃ + j₄)/6; a kick: its midpoint's), so `--joint` prints impulse / dt;
//! the springs' damping work is summed with the same weights. A fixed body is never stepped.

use super::super::body::Body;
use super::super::derive::{derive, Kinematics};
use super::super::effects::{Effects, Loads};
use super::super::joints::Nearby;
use super::super::state::{Orientation, State};
use super::super::system::{kinematics, Scratch, System};
use super::exact_splitting::Kick;
use super::{normalize, quaternion_of, quaternion_rate, rotation_of, splitting};
use nalgebra::{Quaternion, Vector3};

/// What the forces phase computed at the start of the step.
#[derive(Debug, Clone, Copy)]
pub struct Start<'a> {
    pub kinematics: &'a [Kinematics],
    /// Total F and τ per body (effects, springs, joints).
    pub loads: &'a [Loads],
    /// Each joint's reaction on its body A (empty without joints).
    pub joint_loads: &'a [Loads],
    /// The springs' damping power, W.
    pub damping_power: f64,
}

/// Reused buffers, and what the step did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buffers {
    eval: Scratch,
    momenta: Vec<Vector3<f64>>,
    y: Vec<Flat>,
    stage: Vec<Flat>,
    /// The linked block's flat states and rates of a step (`Slot`).
    slots: Vec<Vec<Flat>>,
    loads: Vec<Loads>,
    reactions: Vec<Loads>,
    /// The rk4 kick's `k₁ + 2k₂ + 2k₃ + k₄` per body.
    kick_sum: Vec<Loads>,
    /// Result: each joint's reaction on its body A, averaged over the step.
    pub joint_loads: Vec<Loads>,
    /// Result: the springs' damping work over the step, J (≤ 0).
    pub damping_work: f64,
    /// Whether `eval` was evaluated during this step (its solver then holds the factor of K at
    /// the step's last stage: [`Buffers::last_factor`]).
    evaluated: bool,
}

impl Buffers {
    /// Clears the step's results (one reaction per joint of `start`).
    pub(super) fn clear(&mut self, start: &Start) {
        self.joint_loads.clear();
        self.joint_loads
            .resize(start.joint_loads.len(), Loads::default());
        self.damping_work = 0.0;
        self.evaluated = false;
    }

    /// The joints' solver of this step's last evaluation, which holds the factor of J W Jᵀ at
    /// that stage's configuration (rk4: X + dt k₃, O(dt²) from the step's end; a kick–drift–kick
    /// composition: the end's own positions); None when no evaluation ran during the step
    /// (`euler`, `symplectic-euler`: only the forces phase's, at the step's start). The
    /// projection takes it as a nearby factor (`joints::project`).
    pub fn last_factor(&mut self) -> Option<Nearby<'_>> {
        self.evaluated.then(|| self.eval.nearby())
    }

    /// Books `w ×` the last evaluation's reactions and damping power.
    pub(super) fn book_evaluation(&mut self, w: f64) {
        self.book_evaluation_reactions(w);
        self.damping_work += self.eval.damping_power * w;
    }

    /// Books `w ×` the last evaluation's reactions.
    pub(super) fn book_evaluation_reactions(&mut self, w: f64) {
        accumulate(&mut self.joint_loads, &self.eval.joint_loads, w);
    }

    /// Books `w ×` these reactions.
    pub(super) fn book_reactions(&mut self, reactions: &[Loads], w: f64) {
        accumulate(&mut self.joint_loads, reactions, w);
    }

    /// The last evaluation's damping power, W.
    pub(super) fn damping_power(&self) -> f64 {
        self.eval.damping_power
    }

    /// Books the start's reactions as the step's, and its damping power over dt (the
    /// one-evaluation methods).
    pub(super) fn book_start(&mut self, start: &Start, dt: f64) {
        self.joint_loads.copy_from_slice(start.joint_loads);
        self.damping_work = start.damping_power * dt;
    }
}

/// One body's state as a vector-space element (quaternion not normalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Flat {
    pub x: Vector3<f64>,
    pub q: Quaternion<f64>,
    pub p: Vector3<f64>,
    pub l: Vector3<f64>,
}

impl Flat {
    /// `self + h k`.
    #[inline]
    pub fn plus(&self, k: &Flat, h: f64) -> Flat {
        Flat {
            x: self.x + k.x * h,
            q: self.q + k.q * h,
            p: self.p + k.p * h,
            l: self.l + k.l * h,
        }
    }

    /// A state as a flat element.
    #[inline]
    pub fn of(s: &State) -> Flat {
        Flat {
            x: s.position,
            q: *quaternion_of(s).quaternion(),
            p: s.linear_momentum,
            l: s.angular_momentum,
        }
    }

    /// The state of a flat element (q normalised).
    #[inline]
    pub fn state(&self) -> State {
        State {
            position: self.x,
            orientation: Orientation::Quaternion(normalize(self.q)),
            linear_momentum: self.p,
            angular_momentum: self.l,
        }
    }
}

/// Adds `w ×` the reactions in `from` to `into`.
fn accumulate(into: &mut [Loads], from: &[Loads], w: f64) {
    for (a, b) in into.iter_mut().zip(from) {
        a.force += b.force * w;
        a.torque += b.torque * w;
    }
}

/// Applies `update` to every body that moves (a fixed body never does), with its index.
#[inline]
pub(super) fn each_moving(
    system: &System,
    states: &mut [State],
    mut update: impl FnMut(usize, &Body, &mut State),
) {
    for (i, (state, body)) in states.iter_mut().zip(system.bodies).enumerate() {
        if !body.fixed {
            update(i, body, state);
        }
    }
}

/// Writes flat elements back into the states of the bodies that move.
fn write_back(system: &System, states: &mut [State], y: &[Flat]) {
    each_moving(system, states, |i, _, state| *state = y[i].state());
}

/// f's rates at the start of the step, at flat states `y`.
fn start_rates(y: &[Flat], start: &Start, out: &mut Vec<Flat>) {
    rates(y, start.kinematics, start.loads, out);
}

/// The rates `(v, ½ ω ⊗ q, F, τ)` at flat states `y` from their kinematics and loads.
fn rates(y: &[Flat], kinematics: &[Kinematics], loads: &[Loads], out: &mut Vec<Flat>) {
    out.clear();
    out.extend(
        y.iter()
            .zip(kinematics)
            .zip(loads)
            .map(|((s, k), f)| rates_at(s, k, f)),
    );
}

/// The rates `(v, ½ ω ⊗ q, F, τ)` of one body at flat state `y` from its kinematics and loads.
#[inline]
fn rates_at(y: &Flat, k: &Kinematics, f: &Loads) -> Flat {
    Flat {
        x: k.velocity,
        q: quaternion_rate(&k.angular_velocity, &y.q),
        p: f.force,
        l: f.torque,
    }
}

/// f(Y) of the coupled system at a stage `y` (q not normalised: R is that of q/|q|): the
/// whole system's evaluation, whose reactions [`Buffers::book_evaluation`] books.
fn stage_rates(system: &System, y: &[Flat], b: &mut Buffers, out: &mut Vec<Flat>) {
    evaluate_flat(system, y, b);
    out.clear();
    out.extend(
        (y.iter().zip(b.eval.poses()))
            .zip(&b.eval.loads)
            .map(|((s, pose), f)| Flat {
                x: pose.v,
                q: quaternion_rate(&pose.w, &s.q),
                p: f.force,
                l: f.torque,
            }),
    );
}

/// f of one body alone at a flat state `y` (q not normalised: R is that of q/|q|): the
/// derive phase's `v = P/M`, `ω = R I⁻¹_body Rᵀ L` (three matrix–vector products: a stage
/// needs ω, not I⁻¹_world), then its effects.
#[inline]
fn body_rates(body: &Body, effects: &Effects, y: &Flat) -> Flat {
    let rotation = rotation_of(&y.q);
    let angular_velocity = rotation * (body.inv_inertia_body * rotation.tr_mul(&y.l));
    let velocity = y.p * body.inv_mass;
    let loads = effects.loads_at(body, &velocity, &angular_velocity);
    Flat {
        x: velocity,
        q: quaternion_rate(&angular_velocity, &y.q),
        p: loads.force,
        l: loads.torque,
    }
}

/// Evaluates the coupled system's forces at flat states (q normalised on the way).
fn evaluate_flat(system: &System, y: &[Flat], b: &mut Buffers) {
    b.eval.clear_bodies();
    b.momenta.clear();
    for (body, s) in system.bodies.iter().zip(y) {
        let k = kinematics(body, rotation_of(&s.q), &s.p, &s.l);
        b.eval.push_body(body, &s.x, &k);
        b.momenta.push(s.l);
    }
    system.evaluate_bodies(&b.momenta, &mut b.eval);
    b.evaluated = true;
}

/// How a kick changes the momenta when the forces are the declared effects alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum KickRule {
    /// `P, L += h F(P + h/2 F, L + h/2 τ)`: exact for constant loads, second order with drag.
    Midpoint,
    /// The exact flow of gravity and drag with x and R held (`exact_splitting::Kick`).
    Exact,
}

/// A kick–drift composition: `kicks[0]` · `flows[0]` · `kicks[1]` · … · `kicks[last]`,
/// each a fraction of dt.
#[derive(Debug, Clone, Copy)]
pub(super) struct Composition<'a> {
    pub kicks: &'a [f64],
    pub flows: &'a [f64],
    pub kick: KickRule,
    /// The composition's order: above 2, a coupled kick whose forces depend on the momenta is
    /// integrated by rk4 ([`rk4_kick`]), the midpoint's local `O(h³)` being too coarse.
    pub order: u32,
}

/// Whether the system's forces depend on the momenta with x and R held: joints (their
/// multipliers see the velocities), damped springs, drag.
fn forces_depend_on_momenta(system: &System) -> bool {
    !system.links.joints.is_empty()
        || system.links.springs.iter().any(|s| s.damping != 0.0)
        || system.effects.depends_on_velocity()
}

/// An integrator written once: one step of a block of the system (`Block`), whatever the
/// block is. [`advance`] runs it over the blocks.
pub(super) trait Method {
    /// One step of length `dt` of `block`, in place.
    fn step<B: Block>(&self, block: &mut B, dt: f64);
}

/// What a method steps at once: the bodies whose f(Y) is evaluated together. A system with
/// links is one block, every body (`Linked`: `System::evaluate`, in buffers); a system without
/// links is a block per moving body (`OneBody`: its f is its effects, in registers).
///
/// A stage method works on the block's flat state `Y` (`start`, `rates`, `finish`); a
/// composition on the states in place (`kick`, `drift`, `end_kicks`). The booking weights are
/// fractions `w / d` of the step, so that each sum is the method's own (rk4: `w / 6`).
pub(super) trait Block {
    /// The block's flat state, and its rates: one body's `Flat`, or a slot of the buffers.
    type Y;
    /// Whether the block is one body alone (rk4 sums its stages in that body's order).
    const ONE_BODY: bool;
    /// Y at the start of the step and k₁ = f(Y) from the forces phase, booked with `w / d`.
    fn start(&mut self, w: f64, d: f64) -> (Self::Y, Self::Y);
    /// f at a stage `y` (q not normalised), booked with `w / d`.
    fn rates(&mut self, y: &Self::Y, w: f64, d: f64) -> Self::Y;
    /// `y + h k`.
    fn plus(&mut self, y: &Self::Y, k: &Self::Y, h: f64) -> Self::Y;
    /// `y + h (((k₁ + 2k₂) + 2k₃) + k₄)`: rk4's end in the linked order, each sum as
    /// [`Block::plus`] makes it (one pass over the block where it can: the same bits).
    fn plus_sum(&mut self, y: &Self::Y, [k1, k2, k3, k4]: [&Self::Y; 4], h: f64) -> Self::Y {
        let first = self.plus(k1, k2, 2.0);
        let second = self.plus(&first, k3, 2.0);
        let sum = self.plus(&second, k4, 1.0);
        self.plus(y, &sum, h)
    }
    /// Writes the end of the step `y` back (q normalised); the booked work becomes the step's.
    fn finish(&mut self, y: &Self::Y, dt: f64);
    /// The kick `(P, L) ← K(h)` of a composition (x and R held); `first`: at the start of the
    /// step, with the forces phase's loads.
    fn kick(&mut self, plan: &Composition, first: bool, h: f64);
    /// Each body's free flow over `h`.
    fn drift(&mut self, drift: &impl Fn(&Body, &mut State, f64), h: f64);
    /// After the last kick: the booked impulses become the step's mean reactions.
    fn end_kicks(&mut self, dt: f64);
}

/// One step of `method` over every block of the system, in place: the linked system at once,
/// or each moving body alone (a fixed body is never stepped).
pub(super) fn advance<M: Method>(
    method: &M,
    system: &System,
    states: &mut [State],
    start: &Start,
    dt: f64,
    b: &mut Buffers,
) {
    b.clear(start);
    if system.coupled() {
        let mut block = Linked {
            system,
            states,
            start,
            b,
            work: 0.0,
            used: 0,
        };
        method.step(&mut block, dt);
        return;
    }
    let exact = Kick::of(system.effects);
    each_moving(system, states, |i, body, state| {
        let mut block = OneBody {
            system,
            i,
            body,
            state,
            start,
            exact: &exact,
        };
        method.step(&mut block, dt);
    });
}

/// One body of a system without links: its f is its declared effects.
struct OneBody<'s, 'a> {
    system: &'s System<'a>,
    i: usize,
    body: &'s Body,
    state: &'s mut State,
    start: &'s Start<'s>,
    /// The exact kick of the declared effects.
    exact: &'s Kick,
}

impl Block for OneBody<'_, '_> {
    type Y = Flat;
    const ONE_BODY: bool = true;

    #[inline]
    fn start(&mut self, _: f64, _: f64) -> (Flat, Flat) {
        let y = Flat::of(self.state);
        let k = rates_at(
            &y,
            &self.start.kinematics[self.i],
            &self.start.loads[self.i],
        );
        (y, k)
    }

    #[inline]
    fn rates(&mut self, y: &Flat, _: f64, _: f64) -> Flat {
        body_rates(self.body, self.system.effects, y)
    }

    #[inline]
    fn plus(&mut self, y: &Flat, k: &Flat, h: f64) -> Flat {
        y.plus(k, h)
    }

    #[inline]
    fn finish(&mut self, y: &Flat, _: f64) {
        *self.state = y.state();
    }

    #[inline]
    fn kick(&mut self, plan: &Composition, first: bool, h: f64) {
        let start = first.then_some(self.start);
        let (i, body) = (self.i, self.body);
        match plan.kick {
            KickRule::Exact => exact_kick(
                self.exact,
                body,
                self.state,
                start.map(|s| &s.kinematics[i]),
                h,
            ),
            KickRule::Midpoint => body_midpoint_kick(self.system, i, body, self.state, start, h),
        }
    }

    #[inline]
    fn drift(&mut self, drift: &impl Fn(&Body, &mut State, f64), h: f64) {
        drift(self.body, self.state, h);
    }

    #[inline]
    fn end_kicks(&mut self, _: f64) {}
}

/// The bodies of a system with links, evaluated together; books the joints' reactions and the
/// springs' damping.
struct Linked<'s, 'a> {
    system: &'s System<'a>,
    states: &'s mut [State],
    start: &'s Start<'s>,
    b: &'s mut Buffers,
    /// The damping work booked by the stages, in units of dt.
    work: f64,
    /// How many of the buffers' slots this step holds.
    used: usize,
}

/// A flat state of the linked system (or its rates), held in the buffers' slot of this index.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slot(usize);

impl Linked<'_, '_> {
    /// A new slot, its vector taken out of the buffers (empty, its capacity kept): fill it and
    /// give it back with `Linked::put`.
    fn take(&mut self) -> (Slot, Vec<Flat>) {
        if self.used == self.b.slots.len() {
            self.b.slots.push(Vec::new());
        }
        let slot = Slot(self.used);
        self.used += 1;
        let mut v = std::mem::take(&mut self.b.slots[slot.0]);
        v.clear();
        (slot, v)
    }

    fn put(&mut self, slot: Slot, v: Vec<Flat>) -> Slot {
        self.b.slots[slot.0] = v;
        slot
    }
}

impl Block for Linked<'_, '_> {
    type Y = Slot;
    const ONE_BODY: bool = false;

    fn start(&mut self, w: f64, d: f64) -> (Slot, Slot) {
        self.used = 0;
        let (y, mut yv) = self.take();
        yv.extend(self.states.iter().map(Flat::of));
        let (k, mut kv) = self.take();
        start_rates(&yv, self.start, &mut kv);
        self.b.book_reactions(self.start.joint_loads, w / d);
        self.work = self.start.damping_power * w / d;
        (self.put(y, yv), self.put(k, kv))
    }

    fn rates(&mut self, y: &Slot, w: f64, d: f64) -> Slot {
        let (k, mut kv) = self.take();
        let yv = std::mem::take(&mut self.b.slots[y.0]);
        stage_rates(self.system, &yv, self.b, &mut kv);
        self.b.slots[y.0] = yv;
        self.b.book_evaluation_reactions(w / d);
        self.work += self.b.damping_power() * w / d;
        self.put(k, kv)
    }

    fn plus(&mut self, y: &Slot, k: &Slot, h: f64) -> Slot {
        let (out, mut v) = self.take();
        let slots = &self.b.slots;
        v.extend(
            slots[y.0]
                .iter()
                .zip(&slots[k.0])
                .map(|(y, k)| y.plus(k, h)),
        );
        self.put(out, v)
    }

    fn plus_sum(&mut self, y: &Slot, [k1, k2, k3, k4]: [&Slot; 4], h: f64) -> Slot {
        let (out, mut v) = self.take();
        let s = &self.b.slots;
        let ks = (s[k1.0].iter().zip(&s[k2.0])).zip(s[k3.0].iter().zip(&s[k4.0]));
        v.extend(s[y.0].iter().zip(ks).map(|(y, ((k1, k2), (k3, k4)))| {
            y.plus(&k1.plus(k2, 2.0).plus(k3, 2.0).plus(k4, 1.0), h)
        }));
        self.put(out, v)
    }

    fn finish(&mut self, y: &Slot, dt: f64) {
        write_back(self.system, self.states, &self.b.slots[y.0]);
        self.b.damping_work = self.work * dt;
    }

    fn kick(&mut self, plan: &Composition, first: bool, h: f64) {
        let start = first.then_some(self.start);
        if plan.order > 2 && forces_depend_on_momenta(self.system) {
            rk4_kick(self.system, self.states, start, h, self.b);
        } else {
            midpoint_kick(self.system, self.states, start, h, self.b);
        }
    }

    fn drift(&mut self, drift: &impl Fn(&Body, &mut State, f64), h: f64) {
        each_moving(self.system, self.states, |_, body, state| {
            drift(body, state, h)
        });
    }

    fn end_kicks(&mut self, dt: f64) {
        for j in &mut self.b.joint_loads {
            j.force /= dt;
            j.torque /= dt;
        }
    }
}

/// A composition and its drift, as a method.
pub(super) struct Composed<'a, D> {
    pub plan: Composition<'a>,
    /// The free flow of one body over h.
    pub drift: D,
}

impl<D: Fn(&Body, &mut State, f64)> Method for Composed<'_, D> {
    #[inline]
    fn step<B: Block>(&self, block: &mut B, dt: f64) {
        compose(&self.plan, &self.drift, block, dt);
    }
}

/// One step of a kick–drift composition of a block, in place; `drift` is the free flow of one
/// body over h. Linked, every kick is the whole system's (at its midpoint, or rk4 over the
/// momenta: [`Composition::order`]); one body alone is kicked by the method's own rule.
#[inline]
fn compose<B: Block>(
    plan: &Composition,
    drift: impl Fn(&Body, &mut State, f64),
    block: &mut B,
    dt: f64,
) {
    for (j, &kick) in plan.kicks.iter().enumerate() {
        block.kick(plan, j == 0, kick * dt);
        if let Some(&flow) = plan.flows.get(j) {
            block.drift(&drift, flow * dt);
        }
    }
    block.end_kicks(dt);
}

/// The exact kick of the declared effects on one body (none when they do nothing); R held
/// is the start's when given.
#[inline]
fn exact_kick(kick: &Kick, body: &Body, state: &mut State, start: Option<&Kinematics>, h: f64) {
    if !kick.acts() {
        return;
    }
    let rotation = start.map_or_else(|| state.orientation.matrix(), |k| k.rotation);
    kick.apply(body, state, &rotation, h);
}

/// The midpoint kick of the declared effects on body `i` (none without effects); the loads
/// and I⁻¹_world at the kick's start are the start's when given.
#[inline]
fn body_midpoint_kick(
    system: &System,
    i: usize,
    body: &Body,
    state: &mut State,
    start: Option<&Start>,
    h: f64,
) {
    let effects = system.effects;
    let (loads, inv_inertia_world) = match start {
        Some(s) => (s.loads[i], s.kinematics[i].inv_inertia_world),
        None if effects.list().is_empty() => return,
        None => {
            let k = derive(body, state);
            (effects.loads(body, &k), k.inv_inertia_world)
        }
    };
    let momenta = (state.linear_momentum, state.angular_momentum);
    (state.linear_momentum, state.angular_momentum) =
        splitting::kick(body, effects, momenta, &inv_inertia_world, &loads, h);
}

/// The coupled kick: `P, L += h (F, τ)` evaluated at `P + h/2 F, L + h/2 τ` (x and q held);
/// the forces at the kick's start are `start`'s when given. Books h × the midpoint's
/// reactions and damping power.
fn midpoint_kick(
    system: &System,
    states: &mut [State],
    start: Option<&Start>,
    h: f64,
    b: &mut Buffers,
) {
    let mut y = std::mem::take(&mut b.y);
    let mut loads = std::mem::take(&mut b.loads);
    loads.clear();
    match start {
        Some(s) => loads.extend_from_slice(s.loads),
        None => {
            y.clear();
            y.extend(states.iter().map(Flat::of));
            evaluate_flat(system, &y, b);
            loads.extend_from_slice(&b.eval.loads);
        }
    }
    y.clear();
    y.extend(states.iter().zip(&loads).map(|(s, f)| {
        let mut y = Flat::of(s);
        y.p += f.force * (h / 2.0);
        y.l += f.torque * (h / 2.0);
        y
    }));
    evaluate_flat(system, &y, b);
    each_moving(system, states, |i, _, state| {
        let f = &b.eval.loads[i];
        state.linear_momentum += f.force * h;
        state.angular_momentum += f.torque * h;
    });
    b.book_evaluation(h);
    b.y = y;
    b.loads = loads;
}

/// The coupled kick by rk4 over the momenta (x and q held), local error `O(h⁵)`:
///
/// ```text
/// k₁ = F(P, L)              k₂ = F(P + h/2 k₁)     (each k a force and a torque per body)
/// k₃ = F(P + h/2 k₂)        k₄ = F(P + h k₃)
/// P, L += h/6 (k₁ + 2k₂ + 2k₃ + k₄)
/// ```
///
/// k₁ is `start`'s loads when given. Books the reactions and damping power with rk4's weights.
fn rk4_kick(system: &System, states: &mut [State], start: Option<&Start>, h: f64, b: &mut Buffers) {
    let mut y = std::mem::take(&mut b.y);
    let mut stage = std::mem::take(&mut b.stage);
    let mut loads = std::mem::take(&mut b.loads);
    let mut sum = std::mem::take(&mut b.kick_sum);
    y.clear();
    y.extend(states.iter().map(Flat::of));
    loads.clear();
    match start {
        Some(s) => {
            loads.extend_from_slice(s.loads);
            b.book_reactions(s.joint_loads, h / 6.0);
            b.damping_work += s.damping_power * (h / 6.0);
        }
        None => {
            evaluate_flat(system, &y, b);
            loads.extend_from_slice(&b.eval.loads);
            b.book_evaluation(h / 6.0);
        }
    }
    sum.clone_from(&loads);
    for (c, w) in [(0.5, 2.0), (0.5, 2.0), (1.0, 1.0)] {
        stage.clear();
        stage.extend(y.iter().zip(&loads).map(|(y, f)| {
            let mut s = *y;
            s.p += f.force * (c * h);
            s.l += f.torque * (c * h);
            s
        }));
        evaluate_flat(system, &stage, b);
        b.book_evaluation(w * h / 6.0);
        loads.clear();
        loads.extend_from_slice(&b.eval.loads);
        for (s, f) in sum.iter_mut().zip(&loads) {
            s.force += f.force * w;
            s.torque += f.torque * w;
        }
    }
    each_moving(system, states, |i, _, state| {
        state.linear_momentum += sum[i].force * (h / 6.0);
        state.angular_momentum += sum[i].torque * (h / 6.0);
    });
    (b.y, b.stage, b.loads, b.kick_sum) = (y, stage, loads, sum);
}
