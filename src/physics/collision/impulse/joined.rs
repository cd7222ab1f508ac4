//! Joint rows inside the contacts' exact solve: a contact impulse on a jointed body and the
//! joint reactions it causes are one solution.
//!
//! A body held by joints (a pendulum's bob, a chain's link) does not answer a contact
//! impulse with its own inverse mass W but with the *constrained* one: the joints push back
//! at once. So the joints' equality rows J_j (bounds (−∞, ∞), `constraints::Row`) join the
//! contact rows J_c of the stages that solve exactly ([`super`]):
//!
//! ```text
//! stage 1 (direct)  find (μ_j, λ_c ≥ 0):  J_j u⁺ = 0,  w_c = J_c u⁺ + b_c ≥ 0,  λ_c w_c = 0,
//!                   u⁺ = u + W (J_jᵀ μ_j + J_cᵀ λ_c)
//!                   — one LDLᵀ of  A = [J_j; J_c] W [J_j; J_c]ᵀ  on the joint rows (always
//!                   active, first in the envelope) and the active contact rows
//! stage 2 (μ > 0)   Coulomb's disks |λ_t| ≤ μ λ₁ and the normals again, with the joints
//!                   held: every contact impulse acts through its column Q Jᵀ,
//!                   Q = W − W J_jᵀ S⁻¹ J_j W,  S = J_j W J_jᵀ  (its joints' reaction in it);
//!                   an active-set start over G = J_c Q J_cᵀ, then block Gauss–Seidel
//!                   ([`Joined::friction`])
//! stage 3           Poisson's restitution e λ_c at the bouncing contacts, and the joints'
//!                   reaction to it:  (J_j W J_jᵀ) μ_r = −J_j W J_cᵀ (e λ_c),
//!                   the energy clamp on the sum (K never rises)
//! ```
//!
//! Stage 1 is the minimum of K over the convex set {J_j u⁺ = 0, J_c u⁺ ≥ −b} ∋ 0 (b ≥ 0 the
//! speculative gaps over dt): K never rises. Stage 3's change lies in J_j's null space, so the
//! joints stay held, and its scale is the contacts' clamp on K. At e = 1 without friction the
//! reflection argument of [`super::propagate`] holds with the joint rows among the active
//! ones: J_j u = 0 before and after stage 1 gives J_j W Jᵀ Λ* = 0, so the doubled impulse
//! keeps both K and the joints (a cradle ball on its rod bounces exactly as a free one).
//!
//! Which joint rows: those of every *cluster* (bodies linked through joint rows) that one of
//! the stage's contact rows touches; an impact round of `propagate` on one pair takes the
//! rows of that pair's clusters only (a cradle's round: one contact and two rods); a
//! resting stage (nothing approaches faster than the bounce speed) takes none.
//!
//! **Limits' stops** within 1e-9 of their limits come with the equality rows
//! (`joints::drive::touching_stops`: one-sided, λ ∈ [0, ∞), J the coordinate's rate
//! J u = q̇, signed so that it pushes away from the limit). Stage 1 takes them by an active
//! set around the direct solve (`Joined::inelastic`):
//!
//! ```text
//! find (μ_j, μ_s ≥ 0, λ_c ≥ 0):  J_j u⁺ = 0,  J_s u⁺ ≥ 0,  μ_s J_s u⁺ = 0,  (contacts as above)
//! ```
//!
//! a stop that pulls leaves, a stop left out that the answer turns past its limit joins, and
//! the stops that push are equality rows for stages 2 and 3. So a box landing on a flap
//! that lies on its stop is one problem: the box stops, the flap does not turn, and the
//! stop's angular impulse is the box's angular momentum about the hinge (`m v d`,
//! `tests/physics/joint_drives.rs`); the joints' drive pass alone would have let flap and box
//! turn on together. The stops' impulses go to [`Joined::stops`] (the joints panel's limit
//! force). A stop's own bounce (its restitution when it is struck) stays in the joints'
//! drive pass at the end of the integrate phase (`joints::drive`), before the contacts:
//! under `propagate` a door striking its stop with a box on it bounces first, and the box's
//! blow on the door then meets the stop here.
//!
//! **Motors** come with them too (`joints::drive::motor_rows`): a row J_q u = speed whose
//! impulse is bounded by what the drive pass left of ±max·dt this step,
//! [−max·dt − λ_drive, max·dt − λ_drive], so that the drive pass's impulse and this one sum
//! to the answer of the combined problem (u⁺ = u⁻ + W Jᵀ (λ_drive + λ) meets every row's
//! conditions with the motor's total in ±max·dt). `Joined::inelastic`'s active set takes a
//! motor inside its bounds as an equality row aiming at its speed (`direct::inelastic`'s
//! joint biases), one past a bound as a known impulse held there (applied before the
//! solve), freed when J u lands on the wrong side of its speed:
//!
//! ```text
//! motor   lo < λ < hi: J u⁺ = speed;   λ = lo: J u⁺ ≥ speed;   λ = hi: J u⁺ ≤ speed
//! ```
//!
//! A free motor is an equality row of stages 2 and 3 (its rate kept at its speed; the direct
//! sticking solve keeps its impulse within its bounds, `HeldJoints::ceiling`; the joints'
//! friction sweeps and stage 3's reaction do not check them, as they do not a stop's); a held
//! one keeps its bound's impulse. A motor pushing a free cube ahead of its cart is one
//! problem: the plastic blow with the motor at its bound leaves the pair at
//! V = (m v + F dt)/(m + m') (`tests/physics/joint_drives.rs`). Its rows are taken whenever
//! a stage's contacts touch a motored cluster, at rest too (a scene with motors builds its
//! joint rows at every response); the motors' impulses go to [`Joined::motors`] (the joints
//! panel's motor force) and their work λ J (u⁻ + u⁺)/2 over the response, λ its total and
//! u⁻, u⁺ the response's start and end (exact: ΔK splits by row over the totals), to
//! [`Joined::motor_work`] (the ledger's motor row; the contacts' row books the rest). The
//! round-off guard and a bounce's energy clamp let K rise by that work. Elsewhere, and under
//! `soft-step`, the motor is the drive pass's alone, as before.
//!
//! Where: in an *impact* (a row approaching faster than the bounce speed: every impact round
//! of `propagate`, a simultaneous solve that bounces); without friction whatever the
//! clusters' size. With friction, stage 2 first tries the direct sticking solve with the joint rows in the same
//! system (`direct::sticking` with `direct::HeldJoints`: every pushing contact sticks, one
//! factorisation, accepted when every normal pushes, every tangential impulse is inside its
//! disk, every stop pushes and nothing approaches: a pair of links landing flat; with modes,
//! a contact outside its disk slides at μ λ₁ against its slip, one that would pull separates,
//! a few rounds of the banded solve). When it declines:
//!
//! - on small clusters (at most [`JOINED_FRICTION_ROWS`] joint rows, the stage at most
//!   [`JOINED_FRICTION_CONTACTS`] contacts: a bob, a door, a pendulum pair) the joints'
//!   friction stage (`Joined::friction`: a spinning bob on a rod meets a tilted wall with its
//!   tangential impulse at μ λ₁ and the spin left by Coulomb's law,
//!   `tests/physics/impacts.rs`);
//! - larger clusters (a chain of 10 links landing: 27 rows) take no joint rows in an impact
//!   with friction (the cluster gate), and the joints' contact pass after the response
//!   (`joints::contact::hold`) holds the joints again, as it always did: the joints' friction
//!   sweeps crawl on a chain (every contact coupled to every other through the links; 61 of
//!   66 calls of the landing chain cycled at the active set's 24-round cap, hundreds of
//!   sweeps a step, 2.2× the instructions of the whole run), and a stage 1 with the joints
//!   followed by a stage 2 without them is neither one solution nor cheaper (taking them
//!   into the direct solves alone was tried: *Tried and removed* below).
//!
//! Elsewhere every stage is the contacts' alone, as before, and the pass after the response
//! holds the joints (it also holds, in every case, the positions the push-out moved along
//! straight lines, so it still runs after every response):
//!
//! - at rest (nothing bounces; but a motored cluster, above) the contacts' solve alone and
//!   the pass after it keep a
//!   touching cradle's balls exactly touching while they swing together; with the joints in
//!   the resting solve the speculative gaps between them grew to about 1 µm, and Poisson's
//!   restitution across such a gap at impact loses 2 λ·gap/dt (6.6e-4 of K with three balls
//!   pulled, against 1e-6 kept);
//! - the sweeps a declined direct solve falls back to.
//!
//! # Tried and removed
//!
//! **Large clusters in the direct solves alone** (`JOINED_DIRECT_LARGE`, off): an impact with
//! friction took the joint rows of clusters larger than the joints' friction sweeps take, its
//! stages 1 and 2 kept them only if the direct solves answered, else both ran again from
//! their start as the contacts' alone (`Joined::save`, `Joined::restore`). Measured on the
//! landing chain (`chain_steps landing 1000`, callgrind): 743.9M instructions against 494.5M
//! (+50 %); the direct solve with the joints and sliding modes answered 9 of its 73 stages,
//! and each declined one paid its rounds (up to [`SLIDE_ROUNDS`] factorisations a try, two
//! tries) and then the contacts' stages again. Every one of the 123 declined tries (traced at
//! 49f6e0c) ended at the [`SLIDE_ROUNDS`] cap with modes still changing: the slide
//! directions' fixed point diverging (the largest turn growing about 2.7× a round, the four
//! corners of a landing face turning each other's directions, each by about −3 times its own
//! error: [`direct::SLIDE_TURN`]), converging too slowly (ratio about 0.5), or the modes
//! cycling (a corner whose sticking normal pulls separates, approaches and joins again,
//! period 2–6 rounds). Also tried (today's path 497.1M): a secant scale of each round's turn
//! with a separated contact rejoining as a slider (8 rounds answer 25 of 71 stages, 32 rounds
//! 54 of 79, at 836M), one try with the budget given back on restore (667M, 8 of 74
//! answered; with the secant turns and 16 rounds 699M, 35 of 73), α = 1/4 (10 answered), a
//! reversing slider sticking (1007M). The cost is every round refactoring the whole banded
//! system (27 joint rows and the contacts). What would change that: an anti-cycling rule for
//! the modes, an update of the factor for the few unknowns a round changes, or one wrench row
//! set per face. Removed in the commit "impulse: delete the remaining switched-off paths";
//! the code is at bd48987 (`JOINED_DIRECT_LARGE`, `Joined::save`, `Joined::restore` in
//! `src/physics/collision/impulse/joined.rs`, the `direct_only` path of `stages` in
//! `impulse/mod.rs`).

use super::{direct, Direct, Row};
use crate::physics::constraints::{Axis, End, Row as ConstraintRow, SolverBody};
use crate::physics::envelope::{Envelope, Pivots};
use nalgebra::Vector3;

mod bounds;

/// Most joint rows an impact *with friction* takes into its solve (the clusters its contacts
/// touch); more, and the stage is the contacts' alone with `joints::contact::hold` after it,
/// as before. The friction stage with the joints is a projected Gauss–Seidel over columns
/// that reach the whole cluster (`Joined::friction`): a bob, a door, a pendulum pair take
/// a sweep or a few; a chain of 10 links landing (27 rows), measured, took hundreds of
/// sweeps a step, 2000 on some (the joints couple every contact of the chain), and 2.2× the
/// instructions of the whole run, with its active-set start settling in under 24 rounds on
/// few of its steps (the sliding directions' fixed point converges slowly).
pub const JOINED_FRICTION_ROWS: usize = 12;

/// Most contact rows a stage with friction may have to take the joint rows: the friction
/// stage's active-set start works on a dense G of 3 rows a contact (its rounds cost (3m)³/6),
/// so a small jointed body meeting a large pile in the same stage keeps today's path.
pub const JOINED_FRICTION_CONTACTS: usize = 16;

/// Rounds of the direct solve with joints and sliding contacts (`Joined::sticking`) before
/// it declines (more answer more stages of a chain landing, at a round's factorisation each:
/// module doc, *Tried and removed*).
pub const SLIDE_ROUNDS: usize = 8;

/// The joint rows of one response, weighed over the step's motions, and what they gave.
#[derive(Debug, Clone, Default)]
pub struct Joined {
    /// Every joint row of the scene (its axis weighed: w = I⁻¹ g, k = J W Jᵀ; ends on fixed
    /// bodies dropped), with the joint it belongs to and whether it is one-sided (a limit's
    /// stop, λ ∈ [0, ∞); else an equality row, λ free).
    all: Vec<(Axis, usize, Kind)>,
    /// Per cluster root: whether a motor row is in it (a resting stage takes such a
    /// cluster's rows when a contact touches it).
    motored: Vec<bool>,
    /// Per motor row of `all` (its owner), J u at the response's start (the motor's work).
    motor_start: Vec<(usize, Axis, f64)>,
    /// Per motor row of `all`: its joint's motor impulse and J u when the current stage
    /// started ([`Joined::mark_stage`]).
    motor_stage: Vec<(f64, f64)>,
    /// Per body: its cluster's root (bodies linked through joint rows), `usize::MAX` for a
    /// body no joint row moves.
    cluster: Vec<usize>,
    /// The clusters the current stage touches.
    pub(super) marked: Vec<bool>,
    /// The rows of the current stage (from `all`), their owners, and their impulses.
    pub(super) axes: Vec<Axis>,
    owners: Vec<usize>,
    /// Per row of the stage: what it is (an equality row, a stop, a motor).
    sides: Vec<Kind>,
    /// Per row of the stage: its bias b (it aims at J u = −b: −speed for a free motor, else 0).
    pub(super) biases: Vec<f64>,
    pub(super) lambda: Vec<f64>,
    /// Per joint: the impulse its rows gave its body A in this response (linear N·s,
    /// angular N·m·s).
    pub impulses: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Per joint: the impulse its limit's stops gave in this response (≥ 0, N·s or N·m·s
    /// along the stop's row; part of `impulses`).
    pub stops: Vec<f64>,
    /// Per joint: the impulse its motor gave in this response (N·s or N·m·s along its
    /// coordinate's row; part of `impulses`).
    pub motors: Vec<f64>,
    /// The motors' work in this response, Σ λ (J u⁻ + J u⁺)/2 over their rows with λ the
    /// response's total and u⁻, u⁺ its start and end (`Joined::finish`), J.
    pub motor_work: f64,
    /// Whether the scene has a motor (set by the world before each response): then a
    /// resting stage takes the rows of a motored cluster its contacts touch.
    pub scene_motored: bool,
    /// The stage's selection while its stops' active set is searched ([`Joined::inelastic`]).
    selection: Vec<(Axis, usize, Kind)>,
    /// Per row of `selection`, after a stage 1 that took stops or motors and answered: where
    /// it is in the active set and its impulse in the stage so far; stages 2 and 3 keep the
    /// bounds from there ([`Joined::friction`], [`Joined::react_bounded`]). Empty otherwise.
    bounded: Vec<(Held, f64)>,
    /// The held rows of the last active-set round (selection index, impulse): applied before
    /// the solve, booked with its answer.
    known: Vec<(usize, f64)>,
    /// Stage 1's tolerance (stage 3's active set measures rates with it).
    tolerance: f64,
    /// The selected rows' reaction to the held rows' impulses in a friction round.
    reaction: Vec<f64>,
    /// Whether a stage of this response took joint rows.
    pub(super) used: bool,
    /// Whether the current stage's inelastic solve held the joint rows (the direct solve
    /// answered with them): then its friction stage takes them too ([`Joined::friction`]).
    pub(super) held: bool,
    system: Envelope,
    /// The friction stage's columns ([`Joined::friction`]): per unknown its span of
    /// `entries` (body, Δv, ΔL, Δω), a dense per-body scratch and the bodies it touched.
    entries: Vec<(usize, Change)>,
    spans: Vec<(usize, usize)>,
    sum: Sum,
    /// Per contact: K over its (n, t₁, t₂) with the joints' reaction ([nn, n1, n2, 11, 12,
    /// 22]), and its impulses before the stage.
    blocks: Vec<[f64; 6]>,
    start: Vec<[f64; 3]>,
    rhs: Vec<f64>,
    /// The active-set start of the friction stage ([`ActiveSet`]).
    active: ActiveSet,
    /// Per selected row, the least and the largest change of its impulse in the direct
    /// sticking solve ([`Joined::sticking`]).
    floor: Vec<f64>,
    ceiling: Vec<f64>,
}

/// What a joint row of the contacts' solve is (its bounds and aim).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Kind {
    /// A joint's equality row: λ ∈ (−∞, ∞), J u = 0.
    Equality,
    /// A limit's stop: λ ∈ [0, ∞), J u ≥ 0.
    Stop,
    /// A motor: λ ∈ [lo, hi] (its bound ± max·dt less what the joints' drive pass gave it
    /// this step), J u = speed inside them (`joints::drive`).
    Motor { lo: f64, hi: f64, speed: f64 },
}

impl Kind {
    /// The kind of a joint row by its bounds: (−∞, ∞) an equality row, [0, ∞) a stop, any
    /// other a motor aiming at J u = −bias.
    fn of(row: &ConstraintRow) -> Kind {
        if row.lo == 0.0 && row.hi == f64::INFINITY {
            Kind::Stop
        } else if row.lo == f64::NEG_INFINITY && row.hi == f64::INFINITY {
            Kind::Equality
        } else {
            Kind::Motor {
                lo: row.lo,
                hi: row.hi,
                speed: -row.bias,
            }
        }
    }
}

/// Where a stop's or a motor's multiplier is in [`Joined::inelastic`]'s active set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Held {
    /// An unknown of the solve (a stop that pushes, a motor inside its bounds, an equality
    /// row).
    Active,
    /// Out of the solve: a stop that does not push, or a motor held at its bound (its
    /// impulse known, applied before the solve).
    Out,
    Low,
    High,
}

/// A body's change (Δv, ΔL, Δω).
type Change = (Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// Per-body changes summed over impulses, and the bodies they touched (to clear them).
#[derive(Debug, Clone, Default)]
struct Sum {
    dense: Vec<Change>,
    marked: Vec<bool>,
    touched: Vec<usize>,
}

impl Sum {
    /// Sized for `bodies` bodies, all zero.
    fn start(&mut self, bodies: usize) {
        self.clear();
        self.dense.resize(bodies, zero());
        self.marked.resize(bodies, false);
    }

    /// Adds `W Jᵀ j` of a weighed axis.
    fn add(&mut self, axis: &Axis, j: f64, motions: &[SolverBody]) {
        if j == 0.0 {
            return;
        }
        for (end, sign) in axis.ends() {
            if !self.marked[end.body] {
                self.marked[end.body] = true;
                self.touched.push(end.body);
            }
            let c = &mut self.dense[end.body];
            c.0 += axis.d * (sign * j * motions[end.body].inv_mass);
            c.1 += end.rd * j;
            c.2 += end.w * j;
        }
    }

    /// Back to zero.
    fn clear(&mut self) {
        for &b in &self.touched {
            self.dense[b] = zero();
            self.marked[b] = false;
        }
        self.touched.clear();
    }
}

impl Joined {
    /// Takes the scene's joint rows (`rows`, unweighed: `Axis::jacobian`) for a response over
    /// `motions`, with `joints` joints; no rows: every stage is the contacts' alone.
    #[inline(always)]
    pub fn prepare(&mut self, rows: &[ConstraintRow], motions: &[SolverBody], joints: usize) {
        self.all.clear();
        self.impulses.clear();
        self.impulses
            .resize(joints, (Vector3::zeros(), Vector3::zeros()));
        self.stops.clear();
        self.stops.resize(joints, 0.0);
        self.motors.clear();
        self.motors.resize(joints, 0.0);
        self.motor_work = 0.0;
        self.motor_start.clear();
        self.motored.clear();
        self.cluster.clear();
        self.axes.clear();
        self.owners.clear();
        self.sides.clear();
        self.biases.clear();
        self.lambda.clear();
        self.used = false;
        self.held = false;
        self.bounded.clear();
        self.known.clear();
        if !rows.is_empty() {
            self.take_rows(rows, motions);
        }
    }

    /// [`Joined::prepare`]'s rows and clusters, when the scene has joint rows (outlined: a
    /// world without joints pays only the clearing, every step).
    #[inline(never)]
    fn take_rows(&mut self, rows: &[ConstraintRow], motions: &[SolverBody]) {
        self.all.extend(
            rows.iter()
                .filter_map(|r| weigh(&r.axis, motions).map(|a| (a, r.owner, Kind::of(r)))),
        );
        // Clusters by union–find over the rows' two ends.
        self.cluster.resize(motions.len(), usize::MAX);
        fn root(cluster: &mut [usize], mut i: usize) -> usize {
            while cluster[i] != i {
                cluster[i] = cluster[cluster[i]];
                i = cluster[i];
            }
            i
        }
        for (axis, _, _) in &self.all {
            for b in axis.bodies().into_iter().flatten() {
                if self.cluster[b] == usize::MAX {
                    self.cluster[b] = b;
                }
            }
            if let Some(b) = axis.b {
                let (x, y) = (
                    root(&mut self.cluster, axis.a.body),
                    root(&mut self.cluster, b.body),
                );
                self.cluster[x.max(y)] = x.min(y);
            }
        }
        for i in 0..self.cluster.len() {
            if self.cluster[i] != usize::MAX {
                self.cluster[i] = root(&mut self.cluster, i);
            }
        }
        // The motors: their clusters, and their rates at the start (their work).
        for (axis, owner, kind) in &self.all {
            if let Kind::Motor { .. } = kind {
                self.motored.resize(self.cluster.len(), false);
                self.motored[self.cluster[axis.a.body]] = true;
                self.motor_start
                    .push((*owner, *axis, axis.velocity(motions)));
            }
        }
    }

    /// Whether this response has joint rows ([`Joined::prepare`]).
    #[inline]
    pub(super) fn has_rows(&self) -> bool {
        !self.all.is_empty()
    }

    /// Keeps each motor's impulse and rate at the start of a stage ([`Joined::stage_work`]).
    #[inline] // a scene without motors: a length test, every step
    pub(super) fn mark_stage(&mut self, motions: &[SolverBody]) {
        self.motor_stage.clear();
        for (owner, axis, _) in &self.motor_start {
            self.motor_stage
                .push((self.motors[*owner], axis.velocity(motions)));
        }
    }

    /// The motors' work in the stage so far (`motions` now): Σ Δλ (J u_stage + J u)/2 over
    /// the impulses Δλ the stage gave them. What a bounce's energy clamp lets the kinetic
    /// energy gain over its start (the motors push; the contacts never give).
    #[inline] // a scene without motors: a length test, every step
    pub(super) fn stage_work(&self, motions: &[SolverBody]) -> f64 {
        let mut work = 0.0;
        for ((owner, axis, _), (impulse, rate)) in self.motor_start.iter().zip(&self.motor_stage)
        {
            let lambda = self.motors[*owner] - impulse;
            if lambda != 0.0 {
                work += lambda * 0.5 * (rate + axis.velocity(motions));
            }
        }
        work
    }

    /// The motors' work over the response (`motions` at its end): Σ λ (J u⁻ + J u⁺)/2 per
    /// motor row, λ its impulse in the response (exact: u⁺ − u⁻ = W Σ Jᵀ λ over every row,
    /// so ΔK = Σ λ J (u⁻ + u⁺)/2 splits by row), into [`Joined::motor_work`].
    #[inline] // a scene without motors: a length test, every step
    pub(super) fn finish(&mut self, motions: &[SolverBody]) {
        self.motor_work = 0.0;
        for (owner, axis, start) in &self.motor_start {
            let lambda = self.motors[*owner];
            if lambda != 0.0 {
                self.motor_work += lambda * 0.5 * (start + axis.velocity(motions));
            }
        }
    }

    /// Selects the joint rows of every cluster one of `bodies` belongs to (a stage's contact
    /// rows' bodies) into [`Joined::axes`], in the scene's row order.
    ///
    /// More than `most` rows: none (the stage is the contacts' alone). With `motored_only`,
    /// only the clusters with a motor row (a resting stage).
    pub(super) fn select(
        &mut self,
        bodies: impl Iterator<Item = usize>,
        most: usize,
        motored_only: bool,
    ) {
        self.held = false;
        self.axes.clear();
        self.owners.clear();
        self.sides.clear();
        self.biases.clear();
        self.lambda.clear();
        if self.all.is_empty() {
            return;
        }
        self.bounded.clear();
        self.known.clear();
        self.marked.clear();
        self.marked.resize(self.cluster.len(), false);
        let mut any = false;
        for b in bodies {
            if let Some(&c) = self.cluster.get(b).filter(|&&c| c != usize::MAX) {
                if !motored_only || self.motored.get(c).copied().unwrap_or(false) {
                    self.marked[c] = true;
                    any = true;
                }
            }
        }
        if !any {
            return;
        }
        for &(axis, owner, kind) in &self.all {
            if self.marked[self.cluster[axis.a.body]] {
                self.axes.push(axis);
                self.owners.push(owner);
                self.sides.push(kind);
                self.biases.push(0.0);
            }
        }
        if self.axes.len() > most {
            self.axes.clear();
            self.owners.clear();
            self.sides.clear();
            self.biases.clear();
        }
        self.used |= !self.axes.is_empty();
    }

    /// Stage 2 solved directly with the selected rows held (`direct::sticking`: every
    /// pushing contact sticks, the equality rows, the pushing stops and the free motors in
    /// the same system, a stop's impulse kept ≥ 0 and a motor's within its bounds); their
    /// change booked. False (nothing changed) when it declines.
    pub(super) fn sticking(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        how: direct::Sticking,
        buffers: &mut Direct,
    ) -> bool {
        self.floor.clear();
        self.ceiling.clear();
        for ((&kind, &mu), &owner) in self.sides.iter().zip(&self.lambda).zip(&self.owners) {
            let (floor, ceiling) = match kind {
                Kind::Stop => (-mu, f64::INFINITY),
                Kind::Equality => (f64::NEG_INFINITY, f64::INFINITY),
                // Its room: the bounds less what this response gave it so far.
                Kind::Motor { lo, hi, .. } => (lo - self.motors[owner], hi - self.motors[owner]),
            };
            self.floor.push(floor);
            self.ceiling.push(ceiling);
        }
        let joints = direct::HeldJoints {
            axes: &self.axes,
            floor: &self.floor,
            ceiling: &self.ceiling,
            bias: &self.biases,
            modes: true,
        };
        buffers.slides.clear();
        buffers.slides.extend(rows.iter().map(|r| {
            if r.normal.lambda > 0.0 {
                direct::Hold::Stick
            } else {
                direct::Hold::Off
            }
        }));
        for _ in 0..SLIDE_ROUNDS {
            match direct::sticking(rows, directions, joints, motions, tolerance, how, buffers) {
                direct::Answer::Accepted => {
                    let delta = std::mem::take(&mut buffers.joint_delta);
                    self.book(&delta, 1.0);
                    self.sticking_answered(&delta);
                    buffers.joint_delta = delta;
                    return true;
                }
                direct::Answer::Declined => return false,
                direct::Answer::Changed => {}
            }
        }
        false
    }

    /// Books the selected rows' impulses `lambda` (scaled by `scale`) to their joints.
    pub(super) fn book(&mut self, lambda: &[f64], scale: f64) {
        for (i, &mu) in lambda.iter().enumerate().take(self.axes.len()) {
            let (axis, owner, kind) = (self.axes[i], self.owners[i], self.sides[i]);
            self.book_row(&axis, owner, kind, mu * scale);
        }
    }

    /// Books the impulse `j` of one row (`axis`, joint `owner`, `kind`) to its joint.
    fn book_row(&mut self, axis: &Axis, owner: usize, kind: Kind, j: f64) {
        let (force, torque) = &mut self.impulses[owner];
        *force += axis.d * j;
        *torque += axis.a.rd * j;
        match kind {
            Kind::Stop => self.stops[owner] += j,
            Kind::Motor { .. } => self.motors[owner] += j,
            Kind::Equality => {}
        }
    }

    /// Books the stage's own impulses ([`Joined::lambda`]) to their joints.
    pub(super) fn book_stage(&mut self, scale: f64) {
        let lambda = std::mem::take(&mut self.lambda);
        self.book(&lambda, scale);
        self.lambda = lambda;
    }

    /// Stage 1 with the selected rows ([`direct::inelastic`], the equality rows always
    /// active): the stops (one-sided rows) and the motors (bounded rows) by an active set
    /// around it. A stop takes part while it pushes (λ ≥ 0) and joins when the answer
    /// without it turns its coordinate past the limit (J u < −tolerance; the joints' drive
    /// pass left every touching stop at J u ≥ 0). A motor takes part as an equality row
    /// aiming at J u = speed while its impulse is inside its bounds [lo, hi] (less what this
    /// response gave it before); past one it is held there, its impulse known and applied
    /// before the solve, and it is freed when the answer leaves J u on the wrong side of its
    /// speed (below it at lo, above it at hi). Each change solves again from the stage's
    /// start, at most 2 r + 3 times for r stops and motors. The answer is then the minimum
    /// of K over {J_j u = 0, J_stop u ≥ 0, J_c u ≥ −b} with the motors' bounded rows (the
    /// complementarity conditions of every row checked), and the stops that push and the
    /// free motors stay in [`Joined::axes`] as equality rows for stages 2 and 3 (a held
    /// motor keeps its bound's impulse there). Without stops or motors:
    /// `direct::inelastic` alone. False (the motions as they were) when it declines.
    #[inline(always)]
    pub(super) fn inelastic(
        &mut self,
        large: bool,
        rows: &mut [Row],
        motions: &mut [SolverBody],
        tolerance: f64,
        buffers: &mut Direct,
    ) -> bool {
        if self.sides.iter().all(|&k| k == Kind::Equality) {
            let mut lambda = std::mem::take(&mut self.lambda);
            let answered = direct::inelastic(
                large,
                rows,
                (&self.axes, &[], &mut lambda),
                motions,
                tolerance,
                buffers,
            );
            self.lambda = lambda;
            return answered;
        }
        self.inelastic_with_stops(large, rows, motions, tolerance, buffers)
    }

    /// [`Joined::inelastic`] when some selected row is a stop or a motor: the active set over
    /// them around the direct solve.
    #[inline(never)]
    fn inelastic_with_stops(
        &mut self,
        large: bool,
        rows: &mut [Row],
        motions: &mut [SolverBody],
        tolerance: f64,
        buffers: &mut Direct,
    ) -> bool {
        let mut lambda = std::mem::take(&mut self.lambda);
        let mut selection = std::mem::take(&mut self.selection);
        selection.clear();
        selection.extend(
            (self.axes.iter().zip(&self.owners).zip(&self.sides)).map(|((a, &o), &s)| (*a, o, s)),
        );
        let saved: Vec<SolverBody> = motions.to_vec();
        let saved_rows: Vec<f64> = rows.iter().map(|r| r.normal.lambda).collect();
        // Active: every equality row and motor, and the stops that approach at the start.
        let mut held: Vec<Held> = (selection.iter())
            .map(|(axis, _, kind)| match kind {
                Kind::Stop if axis.velocity(motions) >= -tolerance => Held::Out,
                _ => Held::Active,
            })
            .collect();
        let changing = selection.iter().filter(|s| s.2 != Kind::Equality).count();
        let mut answered = false;
        for _ in 0..2 * changing + 3 {
            let known = self.stage_rows(&selection, &held, motions);
            if !direct::inelastic(
                large,
                rows,
                (&self.axes, &self.biases, &mut lambda),
                motions,
                tolerance,
                buffers,
            ) {
                break;
            }
            if lambda.len() != self.axes.len() {
                // Nothing approached: no solve and no impulse (a held motor's would need one).
                if known {
                    break;
                }
                lambda.clear();
            }
            match self.next_change(&selection, &held, &lambda, |a| a.velocity(motions), tolerance) {
                Some((i, to)) => {
                    held[i] = to;
                    motions.copy_from_slice(&saved);
                    for (row, &l) in rows.iter_mut().zip(&saved_rows) {
                        row.normal.lambda = l;
                    }
                }
                None => {
                    answered = true;
                    break;
                }
            }
        }
        if answered {
            // Where each row is, and its impulse, for stages 2 and 3 (their bounds).
            let mut free = lambda.iter();
            self.bounded.clear();
            for (&(_, owner, kind), &h) in selection.iter().zip(&held) {
                let j = match h {
                    Held::Active => free.next().copied().unwrap_or(0.0),
                    _ => self.held_impulse(owner, kind, h).unwrap_or(0.0),
                };
                self.bounded.push((h, j));
            }
            self.tolerance = tolerance;
            // The held motors' impulses (the free rows' are booked with the stage's).
            for (&(axis, owner, kind), &h) in selection.iter().zip(&held) {
                if let Some(j) = self.held_impulse(owner, kind, h) {
                    self.book_row(&axis, owner, kind, j);
                }
            }
        } else {
            motions.copy_from_slice(&saved);
            for (row, &l) in rows.iter_mut().zip(&saved_rows) {
                row.normal.lambda = l;
            }
        }
        self.known.clear();
        self.selection = selection;
        self.lambda = lambda;
        answered
    }

    /// The rows of one round of [`Joined::inelastic`] into [`Joined::axes`] (the active
    /// ones, a free motor with its bias −speed), and the held motors' impulses applied to
    /// `motions`; returns whether there were any.
    fn stage_rows(
        &mut self,
        selection: &[(Axis, usize, Kind)],
        held: &[Held],
        motions: &mut [SolverBody],
    ) -> bool {
        self.take_active(selection, held);
        for &(i, j) in &self.known {
            selection[i].0.apply(j, motions);
        }
        !self.known.is_empty()
    }

    /// The active rows of `held` into [`Joined::axes`] (a free motor with its bias −speed),
    /// and the held rows' impulses into [`Joined::known`].
    fn take_active(&mut self, selection: &[(Axis, usize, Kind)], held: &[Held]) {
        self.axes.clear();
        self.owners.clear();
        self.sides.clear();
        self.biases.clear();
        self.known.clear();
        for (i, (&(axis, owner, kind), &h)) in selection.iter().zip(held).enumerate() {
            if h == Held::Active {
                self.axes.push(axis);
                self.owners.push(owner);
                self.sides.push(kind);
                self.biases.push(match kind {
                    Kind::Motor { speed, .. } => -speed,
                    _ => 0.0,
                });
            } else if let Some(j) = self.held_impulse_at(i, owner, kind, h) {
                self.known.push((i, j));
            }
        }
    }

    /// A row's bounds on its impulse from here and the rate it aims at: a motor's [lo, hi]
    /// less what this response gave it so far, at its speed; a stop's [−p, ∞) at rate 0,
    /// p its impulse earlier in this stage (stage 1: 0; stages 2 and 3: [`Joined::bounded`],
    /// so that the stage's total stays ≥ 0); an equality row's (−∞, ∞).
    fn limits(&self, i: usize, owner: usize, kind: Kind) -> (f64, f64, f64) {
        match kind {
            Kind::Motor { lo, hi, speed } => {
                (lo - self.motors[owner], hi - self.motors[owner], speed)
            }
            Kind::Stop => {
                let p = self.bounded.get(i).map_or(0.0, |b| b.1);
                (-p, f64::INFINITY, 0.0)
            }
            Kind::Equality => (f64::NEG_INFINITY, f64::INFINITY, 0.0),
        }
    }

    /// The impulse of a motor held at a bound in stage 1 (None for any other row).
    fn held_impulse(&self, owner: usize, kind: Kind, h: Held) -> Option<f64> {
        match kind {
            Kind::Motor { .. } => self.held_impulse_at(usize::MAX, owner, kind, h),
            _ => None,
        }
    }

    /// The impulse of row `i` (of the selection) held at a bound (None when it is not).
    fn held_impulse_at(&self, i: usize, owner: usize, kind: Kind, h: Held) -> Option<f64> {
        let (lo, hi, _) = self.limits(i, owner, kind);
        match h {
            Held::Low => Some(lo),
            Held::High => Some(hi),
            _ => None,
        }
    }

    /// The change of the active set after a round (`lambda` the active rows' impulses,
    /// `rate` each row's J u after them): a stop that pulls past its bound leaves (stage 1:
    /// [`Held::Out`], no impulse; stages 2 and 3: held at its bound) or a motor past a bound
    /// is held there (the largest first); else a stop left out that the answer turns past
    /// its limit joins, or a held motor whose rate is on the wrong side of its speed is freed
    /// (the most violated first). None: the answer.
    fn next_change(
        &self,
        selection: &[(Axis, usize, Kind)],
        held: &[Held],
        lambda: &[f64],
        rate: impl Fn(&Axis) -> f64,
        tolerance: f64,
    ) -> Option<(usize, Held)> {
        // The first of the largest (ties go to the earlier row).
        let mut leave: Option<(usize, Held, f64)> = None;
        let keep = |slot: &mut Option<(usize, Held, f64)>, i: usize, to: Held, size: f64| {
            if slot.is_none_or(|(_, _, s)| size > s) {
                *slot = Some((i, to, size));
            }
        };
        let later = !self.bounded.is_empty();
        let active = (0..selection.len()).filter(|&i| held[i] == Held::Active);
        for (i, &mu) in active.zip(lambda) {
            let (_, owner, kind) = selection[i];
            let (lo, hi, _) = self.limits(i, owner, kind);
            match kind {
                Kind::Stop if mu < lo => {
                    let to = if later { Held::Low } else { Held::Out };
                    keep(&mut leave, i, to, lo - mu);
                }
                Kind::Motor { .. } => {
                    if mu < lo {
                        keep(&mut leave, i, Held::Low, lo - mu);
                    } else if mu > hi {
                        keep(&mut leave, i, Held::High, mu - hi);
                    }
                }
                _ => {}
            }
        }
        if leave.is_some() {
            return leave.map(|(i, to, _)| (i, to));
        }
        let mut join: Option<(usize, Held, f64)> = None;
        for (i, &(axis, owner, kind)) in selection.iter().enumerate() {
            if held[i] == Held::Active || kind == Kind::Equality {
                continue;
            }
            let u = rate(&axis);
            let (_, _, speed) = self.limits(i, owner, kind);
            match held[i] {
                Held::Out | Held::Low if u < speed - tolerance => {
                    keep(&mut join, i, Held::Active, speed - u);
                }
                Held::High if u > speed + tolerance => {
                    keep(&mut join, i, Held::Active, u - speed);
                }
                _ => {}
            }
        }
        join.map(|(i, to, _)| (i, to))
    }

    /// The joints' reaction to a change of the bodies' motions (`change`: Δv, ΔL, Δω per
    /// body, the restitution impulses'): μ with `(J_j W J_jᵀ) μ = −J_j Δu`, added to
    /// `change` (`W J_jᵀ μ`), so that the change keeps J_j u. Leaves μ in
    /// [`Joined::lambda`].
    pub(super) fn react(
        &mut self,
        change: &mut [(Vector3<f64>, Vector3<f64>, Vector3<f64>)],
        motions: &[SolverBody],
    ) {
        self.lambda.clear();
        let m = self.axes.len();
        if m == 0 {
            return;
        }
        let rate = |axis: &Axis, change: &[(Vector3<f64>, Vector3<f64>, Vector3<f64>)]| {
            let (dv, _, dw) = &change[axis.a.body];
            let mut u = axis.d.dot(dv) + axis.a.rd.dot(dw);
            if let Some(b) = &axis.b {
                let (dv, _, dw) = &change[b.body];
                u += -axis.d.dot(dv) + b.rd.dot(dw);
            }
            u
        };
        self.system.reset(m);
        for p in 0..m {
            let jp = &self.axes[p];
            self.system.rhs[p] = -rate(jp, change);
            let axes = &self.axes;
            self.system.fill_row(p, jp.bodies(), |q| {
                jp.shares_a_body(&axes[q])
                    .then(|| jp.coupling(&axes[q], motions))
            });
        }
        let Some(mu) = self.system.solve(Pivots::Dropped) else {
            return;
        };
        self.lambda.extend_from_slice(&mu[..m]);
        for (axis, &mu) in self.axes.iter().zip(&self.lambda) {
            for (end, sign) in axis.ends() {
                let c = &mut change[end.body];
                c.0 += axis.d * (sign * mu * motions[end.body].inv_mass);
                c.1 += end.rd * mu;
                c.2 += end.w * mu;
            }
        }
    }
}

impl Joined {
    /// Stage 2 (friction) with the selected joint rows held (module doc): projected block
    /// Gauss–Seidel over the contacts' (n, t₁, t₂), each unknown's impulse acting through its
    /// *column* `c = Q Jᵀ`, `Q = W − W J_jᵀ S⁻¹ J_j W`, `S = J_j W J_jᵀ` (the joints' reaction
    /// to a unit impulse along it, so that every change keeps J_j u), with the block of K
    /// `G = J_c Q J_cᵀ` of each contact:
    ///
    /// ```text
    /// normal   λₙ ← max(0, λₙ − (uₙ + b)/Gₙₙ)                 (b = gap/dt)
    /// friction λ_t ← the minimum of K over |λ_t| ≤ μ λₙ¹ with K_t = G_tt  (friction::disk_step)
    /// ```
    ///
    /// Each update is the exact minimum of K over its block with the joints held, so K only
    /// goes down and the fixed point is the solution of stage 2 with the joints: what the
    /// contacts' stage 2 solves for free bodies, over the motions that keep J_j u = 0. The
    /// joints' impulses, `S μ = −J_j W J_cᵀ Δλ` over the stage's change Δλ, are booked.
    /// At most `cap` sweeps; returns whether they converged, how many ran, the residual (the
    /// largest change of a contact velocity the last sweep made) and the work (row updates);
    /// None (nothing changed) when S gives no factor.
    ///
    /// With stops or motors among the rows (stage 1 took them: [`Joined::bounded`]), an
    /// active set around the sweeps keeps their bounds ([`Joined::friction_bounded`]).
    pub(super) fn friction(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        cap: u64,
    ) -> Option<(bool, u64, f64, u64)> {
        if !self.bounded.is_empty() {
            return self.friction_bounded(rows, directions, motions, tolerance, cap);
        }
        let answer = self.friction_round(rows, directions, motions, tolerance, cap)?;
        let lambda = std::mem::take(&mut self.rhs);
        self.book(&lambda, 1.0);
        self.rhs = lambda;
        Some(answer)
    }

    /// [`Joined::friction`]'s sweeps over the selected rows, with the held rows' impulses
    /// ([`Joined::known`]) applied first through their columns (the selected rows' reaction
    /// in them); leaves the selected rows' impulses in `rhs` (not booked).
    fn friction_round(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        cap: u64,
    ) -> Option<(bool, u64, f64, u64)> {
        let mj = self.axes.len();
        self.system.reset(mj);
        for p in 0..mj {
            let jp = &self.axes[p];
            let axes = &self.axes;
            self.system.fill_row(p, jp.bodies(), |q| {
                jp.shares_a_body(&axes[q])
                    .then(|| jp.coupling(&axes[q], motions))
            });
        }
        if !self.system.factor_regularised() {
            return None;
        }
        let mut work = super::factorisation_work(self.system.stored(), mj);
        self.sum.start(motions.len());
        // The held rows' impulses, and the selected rows' reaction to them.
        let mut reaction = std::mem::take(&mut self.reaction);
        reaction.clear();
        if !self.known.is_empty() {
            for &(i, j) in &self.known {
                self.sum.add(&self.selection[i].0, j, motions);
            }
            self.react_dense(motions);
            reaction.extend_from_slice(&self.rhs);
            for &b in &self.sum.touched {
                let (dv, dl, dw) = self.sum.dense[b];
                let m = &mut motions[b];
                m.v += dv;
                m.l += dl;
                m.omega += dw;
                m.touched = true;
            }
            self.sum.clear();
        }
        // The columns, three per contact.
        self.entries.clear();
        self.spans.clear();
        for (row, [t1, t2]) in rows.iter().zip(directions) {
            for axis in [&row.normal.axis, t1, t2] {
                self.sum.add(axis, 1.0, motions);
                self.react_dense(motions);
                let from = self.entries.len();
                let sum = &self.sum;
                self.entries
                    .extend(sum.touched.iter().map(|&b| (b, sum.dense[b])));
                self.sum.clear();
                self.spans.push((from, self.entries.len()));
                work += mj as u64;
            }
        }
        // Each contact's block of G = J_c Q J_cᵀ.
        self.blocks.clear();
        self.start.clear();
        for (i, (row, [t1, t2])) in rows.iter().zip(directions).enumerate() {
            let g = |a: &Axis, k: usize| {
                let (from, to) = self.spans[3 * i + k];
                rate_on(a, &self.entries[from..to])
            };
            self.blocks.push([
                g(&row.normal.axis, 0),
                g(&row.normal.axis, 1),
                g(&row.normal.axis, 2),
                g(t1, 1),
                g(t1, 2),
                g(t2, 2),
            ]);
            self.start
                .push([row.normal.lambda, row.friction.lambda[0], row.friction.lambda[1]]);
        }
        // A start from the active set (exact when it settles: the sweeps then confirm it),
        // taken only if it lowers K (the sweeps then keep lowering it: K never rises).
        work += self
            .active
            .solve(rows, directions, motions, &self.entries, &self.spans, tolerance);
        let kinetic = |m: &[SolverBody]| m.iter().map(SolverBody::kinetic).sum::<f64>();
        let before = kinetic(motions);
        self.move_to(rows, motions, &self.active.lambda);
        if kinetic(motions) > before {
            self.move_to(rows, motions, &self.start);
        }
        // The sweeps.
        let (mut converged, mut sweeps, mut largest) = (false, 0, 0.0);
        while sweeps < cap {
            sweeps += 1;
            largest = 0.0f64;
            for (i, (row, [t1, t2])) in rows.iter_mut().zip(directions).enumerate() {
                let [gnn, _, _, g11, g12, g22] = self.blocks[i];
                if gnn > 1e-12 * row.normal.axis.k {
                    let u = row.normal.axis.velocity(motions) + row.normal.bias;
                    let new = (row.normal.lambda - u / gnn).max(0.0);
                    let change = new - row.normal.lambda;
                    if change != 0.0 {
                        row.normal.lambda = new;
                        self.apply_column(3 * i, change, motions);
                        largest = largest.max(change.abs() * gnn);
                    }
                }
                let bound = row.friction.bound;
                if bound == 0.0 {
                    continue;
                }
                let u = [t1.velocity(motions), t2.velocity(motions)];
                let old = row.friction.lambda;
                if let Some((new, step)) =
                    super::friction::disk_step(u, (g11, g22, g12), old, bound)
                {
                    row.friction.lambda = new;
                    self.apply_column(3 * i + 1, step[0], motions);
                    self.apply_column(3 * i + 2, step[1], motions);
                    largest = largest.max(
                        (step[0].abs() * g11 + step[1].abs() * g12.abs())
                            .max(step[1].abs() * g22 + step[0].abs() * g12.abs()),
                    );
                }
            }
            work += rows.len() as u64;
            if largest <= tolerance {
                converged = true;
                break;
            }
        }
        // The joints' impulses over the stage's change.
        for (i, (row, [t1, t2])) in rows.iter().zip(directions).enumerate() {
            let [n0, a0, b0] = self.start[i];
            self.sum.add(&row.normal.axis, row.normal.lambda - n0, motions);
            self.sum.add(t1, row.friction.lambda[0] - a0, motions);
            self.sum.add(t2, row.friction.lambda[1] - b0, motions);
        }
        self.react_dense(motions);
        self.sum.clear();
        for (y, r) in self.rhs.iter_mut().zip(&reaction) {
            *y += r;
        }
        self.reaction = reaction;
        Some((converged, sweeps, largest, work))
    }

    /// The joints' reaction (S factored) to the changes summed in `sum`, added to it: y
    /// with `S y = −J_j Δu`, then `W J_jᵀ y`; leaves y in `rhs`.
    fn react_dense(&mut self, motions: &[SolverBody]) {
        let mj = self.axes.len();
        self.rhs.clear();
        let dense = &self.sum.dense;
        self.rhs.extend(self.axes.iter().map(|axis| {
            let mut u = 0.0;
            for (end, sign) in axis.ends() {
                let (dv, _, dw) = &dense[end.body];
                u += sign * axis.d.dot(dv) + end.rd.dot(dw);
            }
            -u
        }));
        if self.rhs.iter().all(|&r| r == 0.0) {
            return;
        }
        self.system.substitute_regularised(&mut self.rhs[..mj]);
        for (axis, &y) in self.axes.iter().zip(&self.rhs) {
            self.sum.add(axis, y, motions);
        }
    }

    /// Sets the rows' impulses to `to` (per contact [n, t₁, t₂]), their change applied
    /// through the columns.
    fn move_to(&self, rows: &mut [Row], motions: &mut [SolverBody], to: &[[f64; 3]]) {
        for (i, row) in rows.iter_mut().enumerate() {
            let [n, t1, t2] = to[i];
            let [n0, a0, b0] = [row.normal.lambda, row.friction.lambda[0], row.friction.lambda[1]];
            row.normal.lambda = n;
            row.friction.lambda = [t1, t2];
            self.apply_column(3 * i, n - n0, motions);
            self.apply_column(3 * i + 1, t1 - a0, motions);
            self.apply_column(3 * i + 2, t2 - b0, motions);
        }
    }

    /// Adds `j` times unknown `k`'s column to the motions.
    fn apply_column(&self, k: usize, j: f64, motions: &mut [SolverBody]) {
        let (from, to) = self.spans[k];
        for (b, (dv, dl, dw)) in &self.entries[from..to] {
            let m = &mut motions[*b];
            m.v += dv * j;
            m.l += dl * j;
            m.omega += dw * j;
            m.touched |= j != 0.0;
        }
    }
}

/// How a contact takes part in the friction stage's active set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// No impulse (it separates).
    Off,
    /// It pushes and sticks: u_n = −b, u_t = 0.
    Stick,
    /// It pushes and slides: λ_t = bound · d, d the unit direction opposite its slip.
    Slide([f64; 2]),
}

/// Rounds of the active set before the sweeps take what it has.
const ACTIVE_ROUNDS: usize = 24;

/// The friction stage's start with the joints held: an active-set solve in contact space
/// over the dense `G = J_c Q J_cᵀ` (3 unknowns a contact). Each round solves, for the
/// contacts that push, `u_n = −b` and (sticking) `u_t = 0` with the sliding ones' tangent
/// impulses fixed at `bound · d`; then a normal that pulls leaves, a separated contact that
/// approaches joins, a sticking impulse outside its disk slides along its own direction,
/// and a sliding one takes d = −u_t/|u_t| (or sticks when it stopped). When nothing
/// changes, the answer is stage 2's solution (Coulomb's disk with the slip opposite the
/// impulse, Signorini's normal): the sweeps confirm it in a sweep. Otherwise the last
/// answer, put inside its bounds, is where they start.
#[derive(Debug, Clone, Default)]
struct ActiveSet {
    /// G row-major (n × n), the velocities at the start u⁰ (bias in), the impulses at the
    /// start λ⁰, and the answer λ (per contact [n, t₁, t₂]).
    g: Vec<f64>,
    u0: Vec<f64>,
    lambda0: Vec<f64>,
    lambda: Vec<[f64; 3]>,
    modes: Vec<Mode>,
    /// The unknowns of a round, its system and its right-hand side.
    unknowns: Vec<usize>,
    system: Vec<f64>,
    rhs: Vec<f64>,
    x: Vec<f64>,
}

impl ActiveSet {
    /// Solves (module doc of the type) into `lambda`; returns its work in row updates.
    fn solve(
        &mut self,
        rows: &[Row],
        directions: &[[Axis; 2]],
        motions: &[SolverBody],
        entries: &[(usize, Change)],
        spans: &[(usize, usize)],
        tolerance: f64,
    ) -> u64 {
        let m = rows.len();
        let n = 3 * m;
        let axis = |k: usize| -> &Axis {
            match k % 3 {
                0 => &rows[k / 3].normal.axis,
                t => &directions[k / 3][t - 1],
            }
        };
        self.g.clear();
        for q in 0..n {
            let aq = axis(q);
            self.g.extend((0..n).map(|p| {
                let (from, to) = spans[p];
                rate_on(aq, &entries[from..to])
            }));
        }
        self.u0.clear();
        self.lambda0.clear();
        for (row, _) in rows.iter().zip(directions) {
            self.lambda0
                .extend([row.normal.lambda, row.friction.lambda[0], row.friction.lambda[1]]);
        }
        for k in 0..n {
            let bias = if k % 3 == 0 { rows[k / 3].normal.bias } else { 0.0 };
            self.u0.push(axis(k).velocity(motions) + bias);
        }
        self.modes.clear();
        self.modes.extend((0..m).map(|i| {
            if rows[i].normal.lambda > 0.0 || self.u0[3 * i] < -tolerance {
                Mode::Stick
            } else {
                Mode::Off
            }
        }));
        self.lambda.clear();
        self.lambda
            .extend(rows.iter().map(|r| [r.normal.lambda, r.friction.lambda[0], r.friction.lambda[1]]));
        let mut work = (n * n / 4) as u64;
        let mut x = vec![0.0; n];
        for _ in 0..ACTIVE_ROUNDS {
            // Fixed values and unknowns.
            self.unknowns.clear();
            for (i, mode) in self.modes.iter().enumerate() {
                let bound = rows[i].friction.bound;
                match *mode {
                    Mode::Off => x[3 * i..3 * i + 3].fill(0.0),
                    Mode::Stick => self.unknowns.extend([3 * i, 3 * i + 1, 3 * i + 2]),
                    Mode::Slide(d) => {
                        self.unknowns.push(3 * i);
                        x[3 * i + 1] = bound * d[0];
                        x[3 * i + 2] = bound * d[1];
                    }
                }
                if bound == 0.0 && *mode == Mode::Stick {
                    // No friction here: its tangents stay 0.
                    self.unknowns.truncate(self.unknowns.len() - 2);
                    x[3 * i + 1] = 0.0;
                    x[3 * i + 2] = 0.0;
                }
            }
            let a = self.unknowns.len();
            let fixed = |k: usize, unknowns: &[usize]| unknowns.binary_search(&k).is_err();
            self.system.clear();
            self.rhs.clear();
            for &k in &self.unknowns {
                let row = &self.g[k * n..(k + 1) * n];
                self.system.extend(self.unknowns.iter().map(|&j| row[j]));
                let mut r = -self.u0[k];
                for j in 0..n {
                    r += row[j] * self.lambda0[j];
                    if fixed(j, &self.unknowns) {
                        r -= row[j] * x[j];
                    }
                }
                self.rhs.push(r);
            }
            self.x.clear();
            self.x.extend_from_slice(&self.rhs);
            if a > 0 && !dense_solve(&mut self.system, a, &mut self.x) {
                break;
            }
            work += (a * a * a / 600 + a * n / 4) as u64;
            for (&k, &v) in self.unknowns.iter().zip(&self.x) {
                x[k] = v;
            }
            // The velocities u = u⁰ + G (x − λ⁰), and the changes they ask for.
            let u = |k: usize| {
                let row = &self.g[k * n..(k + 1) * n];
                self.u0[k]
                    + row
                        .iter()
                        .zip(x.iter().zip(&self.lambda0))
                        .map(|(g, (x, l))| g * (x - l))
                        .sum::<f64>()
            };
            let mut changed = false;
            let mut next = std::mem::take(&mut self.modes);
            for (i, mode) in next.iter_mut().enumerate() {
                let bound = rows[i].friction.bound;
                let t = [x[3 * i + 1], x[3 * i + 2]];
                let size = (t[0] * t[0] + t[1] * t[1]).sqrt();
                let new = match *mode {
                    Mode::Off if u(3 * i) < -tolerance => Mode::Stick,
                    Mode::Off => Mode::Off,
                    _ if x[3 * i] < 0.0 => Mode::Off,
                    Mode::Stick if size > bound * (1.0 + 1e-12) => {
                        Mode::Slide([t[0] / size, t[1] / size])
                    }
                    Mode::Stick => Mode::Stick,
                    Mode::Slide(d) => {
                        let slip = [u(3 * i + 1), u(3 * i + 2)];
                        let speed = (slip[0] * slip[0] + slip[1] * slip[1]).sqrt();
                        if speed <= tolerance {
                            Mode::Stick
                        } else {
                            let e = [-slip[0] / speed, -slip[1] / speed];
                            if (e[0] - d[0]).abs().max((e[1] - d[1]).abs()) > 1e-12 {
                                Mode::Slide(e)
                            } else {
                                Mode::Slide(d)
                            }
                        }
                    }
                };
                changed |= new != *mode;
                *mode = new;
            }
            self.modes = next;
            for i in 0..m {
                let bound = rows[i].friction.bound;
                let (nl, t1, t2) = (x[3 * i].max(0.0), x[3 * i + 1], x[3 * i + 2]);
                let size = (t1 * t1 + t2 * t2).sqrt();
                let scale = if size > bound { bound / size } else { 1.0 };
                self.lambda[i] = [nl, t1 * scale, t2 * scale];
            }
            if !changed {
                break;
            }
        }
        work
    }
}

/// x of `(A + ε𝟙) x = b` (A: a × a, row-major, symmetric positive semi-definite; ε = 1e-10
/// max Aᵢᵢ, the minimum-norm answer as the direct solves pick it) by LDLᵀ in place, then
/// one step of refinement against A; false when a pivot is not positive.
fn dense_solve(system: &mut [f64], a: usize, b: &mut [f64]) -> bool {
    let original: Vec<f64> = system.to_vec();
    let rhs: Vec<f64> = b.to_vec();
    let epsilon = 1e-10 * (0..a).map(|i| system[i * a + i]).fold(0.0, f64::max);
    for i in 0..a {
        system[i * a + i] += epsilon;
    }
    // L D Lᵀ in the lower triangle (D on the diagonal).
    for j in 0..a {
        let mut d = system[j * a + j];
        for k in 0..j {
            d -= system[j * a + k] * system[j * a + k] * system[k * a + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        system[j * a + j] = d;
        for i in j + 1..a {
            let mut s = system[i * a + j];
            for k in 0..j {
                s -= system[i * a + k] * system[j * a + k] * system[k * a + k];
            }
            system[i * a + j] = s / d;
        }
    }
    let substitute = |system: &[f64], x: &mut [f64]| {
        for i in 0..a {
            for k in 0..i {
                x[i] -= system[i * a + k] * x[k];
            }
        }
        for i in 0..a {
            x[i] /= system[i * a + i];
        }
        for i in (0..a).rev() {
            for k in i + 1..a {
                x[i] -= system[k * a + i] * x[k];
            }
        }
    };
    substitute(system, b);
    // One step of refinement: the residual of A x = b (ε's share ε x is taken back).
    let mut r: Vec<f64> = (0..a)
        .map(|i| rhs[i] - (0..a).map(|j| original[i * a + j] * b[j]).sum::<f64>())
        .collect();
    substitute(system, &mut r);
    for (x, dx) in b.iter_mut().zip(&r) {
        *x += dx;
    }
    true
}

fn zero() -> Change {
    (Vector3::zeros(), Vector3::zeros(), Vector3::zeros())
}

/// J·Δu of an axis over a column's entries (bodies it has no entry for do not move).
fn rate_on(axis: &Axis, entries: &[(usize, Change)]) -> f64 {
    let mut u = 0.0;
    for (end, sign) in axis.ends() {
        if let Some((_, (dv, _, dw))) = entries.iter().find(|(b, _)| *b == end.body) {
            u += sign * axis.d.dot(dv) + end.rd.dot(dw);
        }
    }
    u
}

/// A joint row's axis over `motions`: its ends on fixed bodies dropped (a row whose A is
/// fixed is taken from its B's side), each end's `w = I⁻¹ g` and the row's
/// `k = Σ |d|²/M + g·I⁻¹ g` filled in; None when no end moves.
fn weigh(axis: &Axis, motions: &[SolverBody]) -> Option<Axis> {
    let moving = |e: &End| !motions[e.body].fixed();
    let (d, a, b) = match (moving(&axis.a), axis.b.filter(moving)) {
        (true, b) => (axis.d, axis.a, b),
        // A fixed: the row is −d on B with B's angular part (J's B block alone).
        (false, Some(b)) => (-axis.d, b, None),
        (false, None) => return None,
    };
    let weighed = |e: &End| {
        let s = &motions[e.body];
        let w = s.inv_inertia * e.rd;
        (
            End { w, ..*e },
            s.inv_mass * d.norm_squared() + e.rd.dot(&w),
        )
    };
    let (a, mut k) = weighed(&a);
    let b = b.map(|e| {
        let (end, kb) = weighed(&e);
        k += kb;
        end
    });
    Some(Axis {
        d,
        a,
        b,
        k,
        inv_k: f64::NAN,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// A 1 kg ball (I = 0.001 kg·m²) at rest.
    fn ball() -> SolverBody {
        SolverBody::new(
            Vector3::zeros(),
            Vector3::zeros(),
            1.0,
            Matrix3::identity() * 1000.0,
        )
    }

    #[test]
    fn clusters_take_the_rows_of_the_touched_bodies_only() {
        // Bodies 0–1 joined, 2 alone on a rod to the world, 3 free.
        let motions = vec![ball(), ball(), ball(), ball()];
        let row = |a: usize, b: Option<usize>, owner: usize| {
            let axis = Axis::jacobian(
                Vector3::x(),
                (a, Vector3::zeros()),
                b.map(|b| (b, Vector3::zeros())),
            );
            ConstraintRow::equality(axis, 0.0, 0.0, owner)
        };
        let rows = [row(0, Some(1), 0), row(2, None, 1)];
        let mut joined = Joined::default();
        joined.prepare(&rows, &motions, 2);
        joined.select([1].into_iter(), usize::MAX, false);
        assert_eq!(joined.axes.len(), 1);
        assert_eq!(joined.axes[0].a.body, 0);
        joined.select([3].into_iter(), usize::MAX, false);
        assert!(joined.axes.is_empty());
        joined.select([3, 2].into_iter(), usize::MAX, false);
        assert_eq!(joined.axes.len(), 1);
        assert_eq!(joined.axes[0].a.body, 2);
        // Weighed: k = 1/m + 1/m for the pair, 1/m for the rod.
        joined.select([0, 2].into_iter(), usize::MAX, false);
        assert_eq!(joined.axes.len(), 2);
        joined.select([0, 2].into_iter(), 1, false);
        assert!(joined.axes.is_empty());
        joined.select([0, 2].into_iter(), usize::MAX, false);
        assert_eq!(
            joined.axes.iter().map(|a| a.k).collect::<Vec<_>>(),
            [2.0, 1.0]
        );
    }

    #[test]
    fn a_resting_stage_after_an_impact_takes_no_joint_rows() {
        // A ball on a rod (body 0) touching a free ball (body 1): an impact round takes the
        // rod's row; the resting stage after it (nothing approaches) takes none, with or
        // without friction (at μ = 0 the round's selection used to stay).
        let motions = vec![ball(), ball()];
        let rod = Axis::jacobian(Vector3::y(), (0, Vector3::zeros()), None);
        let rows = [ConstraintRow::equality(rod, 0.0, 0.0, 0)];
        let mut joined = Joined::default();
        joined.prepare(&rows, &motions, 1);
        let contact = |approach: f64| super::super::Row {
            normal: ConstraintRow::contact(
                Axis::jacobian(Vector3::x(), (0, Vector3::zeros()), Some((1, Vector3::zeros()))),
                0.0,
            ),
            approach,
            ..Default::default()
        };
        for friction in [0.0, 0.3] {
            super::super::select_joints(&[contact(-1.0)], friction, 0.1, &mut joined);
            assert_eq!(joined.axes.len(), 1, "μ = {friction}: the impact");
            super::super::select_joints(&[contact(0.0)], friction, 0.1, &mut joined);
            assert!(joined.axes.is_empty(), "μ = {friction}: at rest");
        }
    }

    #[test]
    fn a_motor_in_the_blow_gives_its_speed_or_its_bound_and_no_more() {
        // A 1 kg ball (body 0) driven along x by a motor at 1 m/s runs at 1 m/s into a free
        // 1 kg ball (body 1) at rest, e = 0. One problem: the contact makes their speeds
        // equal, V = (m v + λ_m)/(m + m'). A motor of bound 2 N·s (free) brings the pair to
        // its speed, V = 1, λ_m = 1 N·s, the contact's impulse 1 N·s; one of bound 0.3 N·s is
        // held there, V = (1 + 0.3)/2 = 0.65 m/s.
        for (bound, speed, motor) in [(2.0, 1.0, 1.0), (0.3, 0.65, 0.3)] {
            let mut motions = vec![
                SolverBody::new(Vector3::x(), Vector3::zeros(), 1.0, Matrix3::identity() * 1000.0),
                ball(),
            ];
            let drive = Axis::jacobian(Vector3::x(), (0, Vector3::zeros()), None);
            let rows = [ConstraintRow {
                lo: -bound,
                hi: bound,
                bias: -1.0,
                ..ConstraintRow::equality(drive, 0.0, 0.0, 0)
            }];
            let mut joined = Joined::default();
            joined.prepare(&rows, &motions, 1);
            // The contact: n = x from the ball ahead (A) to the driven one (B), approaching.
            let n = Axis::jacobian(Vector3::x(), (1, Vector3::zeros()), Some((0, Vector3::zeros())));
            let mut contacts = [super::super::Row {
                normal: ConstraintRow::contact(n, 0.0),
                approach: -1.0,
                ..Default::default()
            }];
            joined.select([0, 1].into_iter(), usize::MAX, false);
            let mut direct = Direct::default();
            direct.start(1);
            // The solver's tolerance for an approach of 1 m/s (`TOLERANCE` (1 + 1)); the
            // direct solve's ε = 1e-10 max Aᵢᵢ leaves its answer that close (no refinement
            // once the motor is held: no joint row is left), so 1e-9 below.
            let tolerance = super::super::TOLERANCE * 2.0;
            let answered =
                joined.inelastic(false, &mut contacts, &mut motions, tolerance, &mut direct);
            assert!(answered, "bound {bound}: declined, {:?}", (direct.work, direct.budget));
            joined.book_stage(1.0);
            for m in &motions {
                assert!((m.v.x - speed).abs() < 1e-9, "bound {bound}: v = {}", m.v.x);
            }
            assert!((joined.motors[0] - motor).abs() < 1e-9, "bound {bound}: {:?}", joined.motors);
            assert!((contacts[0].normal.lambda - speed).abs() < 1e-9);
            joined.finish(&motions);
            // Its work λ (J u⁻ + J u⁺)/2 = λ (1 + V)/2.
            let work = motor * (1.0 + speed) / 2.0;
            assert!((joined.motor_work - work).abs() < 1e-9, "{}", joined.motor_work);
        }
    }

    #[test]
    fn the_reaction_keeps_the_joint_rate() {
        // Two balls joined along x; the first kicked along x by 1 m/s: the joint shares it.
        let motions = vec![ball(), ball()];
        let rows = [ConstraintRow::equality(
            Axis::jacobian(
                Vector3::x(),
                (0, Vector3::zeros()),
                Some((1, Vector3::zeros())),
            ),
            0.0,
            0.0,
            0,
        )];
        let mut joined = Joined::default();
        joined.prepare(&rows, &motions, 1);
        joined.select([0].into_iter(), usize::MAX, false);
        let mut change = vec![
            (Vector3::x(), Vector3::zeros(), Vector3::zeros()),
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
        ];
        joined.react(&mut change, &motions);
        assert!((change[0].0.x - 0.5).abs() < 1e-15);
        assert!((change[1].0.x - 0.5).abs() < 1e-15);
        assert!((joined.lambda[0] + 0.5).abs() < 1e-15);
    }
}
