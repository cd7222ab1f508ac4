//! `impulse`: a physically based response with restitution e and Coulomb friction μ that never
//! adds kinetic energy (for 0 ≤ e ≤ 1, μ ≥ 0), whatever the number of contacts.
//!
//! # One contact
//!
//! A point at lever arm r from the barycenter, contact normal n (out of the obstacle). An
//! impulse j n there changes the momenta by `ΔP = j n`, `ΔL = r × (j n)`, so the normal velocity
//! of the point `u_n = (v + ω × r)·n` changes by `j·k` with
//!
//! ```text
//! k = 1/M + n·((I⁻¹(r×n)) × r) = 1/M + (r×n)·I⁻¹(r×n)       (the denominator, 1/kg)
//! j = −(1 + e) u_n / k                                      (Newton's law for one contact)
//! ```
//!
//! # Two bodies
//!
//! Between bodies A and B (n from B to A) the impulse is j n on A at r_A and −j n on B at r_B:
//! equal and opposite, so the total linear momentum `P_A + P_B` is unchanged, and the total
//! angular momentum about any point too (`r_A × jn + x_A × jn − r_B × jn − x_B × jn = 0` since
//! both act at the same point). The relative normal velocity
//! `u_n = (v_A + ω_A × r_A − v_B − ω_B × r_B)·n` changes by `j·k` with
//!
//! ```text
//! k = 1/M_A + (r_A×n)·I_A⁻¹(r_A×n) + 1/M_B + (r_B×n)·I_B⁻¹(r_B×n)
//! ```
//!
//! and every stage below is written for such two-sided rows (an obstacle is a B of infinite
//! mass). A resting body, a stack, a body on a body: one solver.
//!
//! # Many contacts (a face landing flat has 4), in three stages
//!
//! Applying that formula to one vertex after the other makes the result depend on the vertex
//! order, and a single pass leaves later contacts approaching. Instead:
//!
//! 1. **Inelastic normal impulses** λᵢ ≥ 0 by projected Gauss–Seidel (sequential impulses with
//!    *accumulated* clamping): sweep the contacts, set each one's normal velocity to zero,
//!    `λᵢ ← max(0, λᵢ − u_nᵢ / kᵢ)`, and sweep again until no impulse changes any velocity by
//!    more than a tolerance. The solution (the velocities) does not depend on the order.
//!    The kinetic energy after a set of impulses Λ is a convex quadratic in Λ,
//!    `K(Λ) = K₀ + Λ·u₀ + ½ Λᵀ A Λ` (A the contact-space inverse mass, positive semi-definite),
//!    and each update is the exact minimisation of K along one coordinate over an interval
//!    that contains the current value: K can only go down. When the answer is "every
//!    approaching contact stops and pushes" (a face landing, a body at rest: the usual case),
//!    the same minimum is computed at once by a small LDLᵀ solve and checked against the
//!    conditions above (`direct_inelastic`); the sweeps run only when that check fails.
//!    A large system whose rows are *wide* in contact order (a pyramid: each cube touches the
//!    row below and its neighbours; [`WIDE_ENVELOPE`]) first tries [`TRIAL_SWEEPS`] sweeps from
//!    the last step's impulses: at rest they are already the answer, one sweep over the rows
//!    confirms it to the same tolerance, where a factorisation costs rows · width². Only when
//!    they do not converge does the direct solve run (and a failed trial waits a few steps
//!    before the next, so a scene whose warm start is poor stops paying for it). Such a
//!    system's direct solve starts its active set from the rows that pushed last step as well
//!    as the approaching ones (a settling pyramid of 20 rows otherwise adds a row per pair of
//!    bodies a round, needs about three rounds per row of cubes, and runs out of rounds), and
//!    if it still declines, its sweeps take subspace steps (as stage 2's below, on the
//!    pushing normals alone, the whole step first projected onto λ ≥ 0, at most
//!    [`NORMAL_SUBSPACE_MAX`] a step). Every bundled lesson and every stack (banded) keeps the
//!    direct solve first and the plain sweeps. The friction stage below does the same.
//! 2. **Coulomb friction** (if μ > 0): two tangent impulses per contact, kept in the disk
//!    `|λ_t| ≤ μ λᵢ` with λᵢ from stage 1 (fixed bounds, so the feasible set is convex and fixed).
//!    The sweep updates the normal impulse as in stage 1, then both tangent impulses at once:
//!    the exact minimum of K over the contact's disk (`friction_update`). Still exact block
//!    minimisations of the same convex K over a convex set containing the current value: K
//!    still only goes down, and block coordinate descent reaches the unique minimising
//!    velocity whatever the order of the contacts. It gets there linearly, and slowly when
//!    bodies slide on each other (a row of dominoes); every [`SUBSPACE_EVERY`] sweeps a
//!    subspace step (`subspace_step`) solves the active set the sweeps have found
//!    directly, with a Newton step along the sliding disks' edges, and is kept only if it
//!    lowers the same objective. The sweeps still decide convergence, to the same tolerance.
//! 3. **Restitution** (Poisson's: the restitution impulse is e times the compression impulse,
//!    the frictionless λᵢ of stage 1 — unique, unlike the stage-2 λᵢ when several contacts share
//!    a load, so the bounce cannot depend on the vertex order),
//!    only at contacts that approached faster than [`BOUNCE_STEPS`]·|g|·dt (slower ones are
//!    resting contact: they do not bounce, which is what keeps a body lying on the ground from
//!    jittering). With one frictionless contact that is Newton's `j = −(1+e) u_n/k` and loses
//!    energy for e ≤ 1; with friction or several contacts it can *gain* energy. Along the line
//!    `Λ_inelastic + s Λ_restitution` the energy is a quadratic `K(s) = a s² + b s + c`, with
//!    `c = K(Λ_inelastic) ≤ K₀`; if `K(1) > K₀` the restitution part is scaled to the largest
//!    `s = (−b + √(b² − 4a(c − K₀))) / 2a` with `K(s) = K₀`.
//!
//!    The push-out below lifts the body against gravity by Δx: its work `ΔV = −M g·Δx` is paid
//!    from the bounce, so the clamp's target is `K₀ − max(0, ΔV)`, not K₀. Otherwise an elastic
//!    bounce keeps K while the push-out adds M g d per bounce (d the depth reached within the
//!    step): a body bouncing with e = 1 would gain energy at every bounce.
//!
//! A last check measures K exactly as the energy panel does and, if round-off alone left it
//! above K₀, scales P and L by `√(K₀/K)` (K is quadratic in (P, L)).
//!
//! # Speculative contacts
//!
//! A resting body falls only ½|g|dt² per step under `rk4` and `splitting` (free fall from
//! rest), |g|dt² under `symplectic-euler`. A body a few µrad off flat then touches with one
//! edge only, the other edge being still a few µm up; that edge's impulse alone tips the body
//! over onto the other edge, which then touches alone, and so on: it rocks for ever. So once a
//! vertex touches, every vertex closer to a surface than
//! `BOUNCE_STEPS·|g|·dt²` (the distance a non-bouncing contact covers in a step) and approaching
//! slower than the bounce speed joins the solve as a *speculative* contact with gap g ≥ 0 and
//! the condition `u_n ≥ −g/dt`: it may close its gap within the next step, no more. In the
//! stages above its update is `λ ← max(0, λ − (u_n + g/dt)/k)`. That minimises
//! `K(Λ) + Σ λᵢ gᵢ/dt ≥ K(Λ)` (λ, g ≥ 0), which starts at K₀, so K still never rises; it never
//! bounces (it is below the bounce speed) and is never pushed out (it is not inside). One that
//! received no impulse is dropped from the reported contacts.
//!
//! # Positions
//!
//! After the velocities, `position` moves the bodies: a body that did not bounce advances from
//! where it was at the start of the step with its *corrected* velocity (no creep at rest, on a
//! slope or on a sphere), and what penetration is left is removed by translation (see there).

use super::contacts;
use super::position::{self, Fix};
use super::solver_body::{Axis, End, SolverBody};
use super::warm::WarmCache;
use super::{CollideInput, Contact, EnergyChange};
use crate::physics::derive::derive;
use crate::physics::energy::{kinetic_energy_with, Energy};
use crate::physics::envelope::{Envelope, Pivots};
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

pub use super::step_context::BOUNCE_STEPS;

/// The sweeps stop when no impulse changed a contact velocity by more than this (m/s), plus the
/// same fraction of the fastest approach speed.
pub const TOLERANCE: f64 = 1e-10;

/// At most this many Gauss–Seidel sweeps per stage. A stack of 10 cubes needs about 800 the
/// first time it is loaded, then 1 to 10 a step from the warm start; a cap below the first
/// number would leave every later step unconverged too.
pub const MAX_SWEEPS: usize = 2000;

/// Most contacts in a step to try the direct inelastic solve for (a stack of 10 cubes has 40,
/// a pyramid of 20 rows about 1600; the system is banded or nearly so there and only its
/// envelope is stored and factored, see [`Envelope`]).
pub const DIRECT_MAX: usize = 4096;

/// Largest envelope (stored entries of [`Envelope`], 8 bytes each) the direct solves take on;
/// beyond it the sweeps run. A stack of 40 (banded) stays far below it; a pyramid of 20 rows,
/// whose rows in contact order reach back over a whole row of cubes, stores about 250 000
/// while it settles (about 5 ms a factorisation, against seconds of capped sweeps).
pub const ENVELOPE_MAX: usize = 1 << 20;

/// Gaps up to this are round-off of touching, m: positions of order 1 m carry errors of
/// about 1e-14 m after a few operations, so the corners of a face lying flat on another come
/// out ±1e-14 m apart, and the sweeps' tolerance ([`TOLERANCE`], 1e-10 m/s) lets a body at rest
/// creep by up to 1e-13 m a step: after a few seconds a face's corners are up to a nanometre
/// apart. Their bias (gap/dt) would make the four rows of a face manifold — which constrain
/// three motions — inconsistent, and the direct solve's minimum-norm answer would blow that
/// up by 1/ε into impulses of ±100 N·s of opposite signs; a pyramid of 20 rows whose corners
/// came 1e-11 m apart declined its direct solve and spent seconds a step in the sweeps.
/// Treated as touching (no bias), the rows stay consistent. A nanometre is far below anything
/// a panel shows (0.1 µm).
pub const GAP_ROUND_OFF: f64 = 1e-9;

/// How many changes of its active set the direct inelastic solve may make (one row out or in
/// per pair of bodies each) before it gives way to the sweeps (a pyramid of 10 rows needed
/// more than 12 while it settles).
pub const PIVOT_ROUNDS: usize = 40;

/// Most pushing contacts to try the direct sticking-friction solve for (three rows each).
pub const STICKING_MAX: usize = DIRECT_MAX / 3;

/// The direct sticking solve's second try (`Sticking::Resting`) holds a pushing speculative
/// contact still if its gap is below this (m): bodies at rest on redundant contacts (a face's
/// four corners, dominoes lying on each other) keep gaps of nanometres to a tenth of a micrometre
/// where their edges are not quite parallel, and closing each within the step asks for motions
/// no rigid body has. Within the micrometre to which bodies stand.
pub const RESTING_GAP: f64 = 1e-6;

/// Above this many rows (and when the rows are wide, [`WIDE_ENVELOPE`]) a stage first tries
/// [`TRIAL_SWEEPS`] sweeps from the last step's
/// impulses before any factorisation: at rest (or sliding steadily) they are already the answer,
/// and confirming it costs one pass over the rows, where the direct solve costs a factorisation
/// whose envelope grows with the width of the scene (a pyramid of 10 rows has about 450 rows).
/// Smaller systems (every bundled lesson) keep the direct solve first.
pub const SWEEPS_FIRST_ROWS: usize = 64;

/// A system whose rows, in contact order, reach back further than this many rows on average
/// (its envelope over its rows) is *wide*: its factorisation costs about rows · width², and
/// it tries the sweeps first. A stack is banded (about 6: a cube's rows reach back to the
/// rows of the pair below it) and keeps the direct solve first, whose minimum-norm impulses
/// leave no tangent drift; a pyramid of 10 rows reaches back about 40.
pub const WIDE_ENVELOPE: f64 = 16.0;

/// The sweeps a large system's warm start may take to converge before the direct solve is
/// tried instead (a scene at rest needs 1 or 2).
pub const TRIAL_SWEEPS: u64 = 8;

/// The longest wait, in steps, between stage-1 trials that keep failing.
pub const TRIAL_WAIT_MAX: u32 = 32;

/// The friction sweeps take a subspace step (`subspace_step`) after this many sweeps
/// that did not converge.
pub const SUBSPACE_EVERY: u64 = 8;

/// Most changes of the active set one friction subspace search makes (each a direct solve).
pub const SUBSPACE_ROUNDS: usize = 8;

/// Most subspace steps the normal sweeps of one step take (each a factorisation of the
/// pushing rows): a settling pyramid of 20 rows needs 6; where they stop helping (rows on the
/// edge of degeneracy) the plain sweeps go on.
pub const NORMAL_SUBSPACE_MAX: usize = 32;

/// How many times a friction subspace step that did not lower F is tried again, 8 times
/// shorter.
pub const SUBSPACE_BACKTRACKS: usize = 3;

/// The largest turn of a sliding disk's impulse along its edge in one subspace step, rad.
pub const EDGE_TURN: f64 = 0.25;

/// A friction disk whose impulse is within this fraction of its bound is on its edge
/// (sliding) for the subspace step; further inside, it sticks.
const SLIDING_EDGE: f64 = 1e-9;

/// The friction disk update's Newton iteration stops when |x(ν)| is within this fraction of
/// the disk's radius (a few ulps: round-off).
const DISK_TOLERANCE: f64 = 16.0 * f64::EPSILON;

/// At most this many Newton (or bisection) steps for one disk update; Newton needs 2 to 5,
/// and 60 bisections would narrow the bracket by 2⁻⁶⁰.
const MAX_DISK_ITERATIONS: usize = 60;

/// Buffers reused from step to step (nothing in them outlives a collide phase).
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    rows: Vec<Row>,
    tangents: Vec<[Axis; 2]>,
    motions: Vec<SolverBody>,
    previous: Vec<Contact>,
    /// The last step's impulses by pair and feature (warm starts in O(1) per contact).
    warm: WarmCache,
    points: Vec<super::geometry::ContactPoint>,
    /// The broad phase's buffers (`broad_phase`).
    broad: super::broad_phase::BroadPhase,
    fix: position::Scratch,
    /// The direct solves' buffers.
    direct: Direct,
    /// The restitution impulses' change to each body: Δv, ΔL, Δω.
    change: Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    /// Which bodies the position fix advances from the start of the step.
    advanced: Vec<bool>,
    /// What the solver did since the world was built (the solver path, for tests).
    pub counters: Counters,
    /// The `soft-step` response's buffers (the world keeps one scratch for the collide phase).
    pub(super) soft: super::soft_step::Scratch,
}

/// The direct solves' buffers: the system, the motions saved to undo a rejected solve, the
/// active rows (in contact order), their impulses, and the rows entering the active set.
#[derive(Debug, Clone, Default)]
struct Direct {
    system: Envelope,
    saved: Vec<SolverBody>,
    active: Vec<usize>,
    lambda: Vec<f64>,
    entering: Vec<usize>,
    /// The motions and (λ, λ_t) before a large system's trial sweeps, to undo them.
    trial: Vec<SolverBody>,
    trial_rows: Vec<(f64, [f64; 2])>,
    /// Steps left before stage 1's trial sweeps run again, and the wait after the last
    /// failure (doubled at each failure up to [`TRIAL_WAIT_MAX`], 0 after a success): a scene
    /// whose warm start does not converge in a few sweeps stops paying for them.
    trial_skip: u32,
    trial_wait: u32,
    /// The first row acting on each body (the envelope's estimate).
    body_first: Vec<usize>,
    /// The friction subspace step's unknowns, and the impulses before it (to undo it).
    unknowns: Vec<Unknown>,
    /// The disks an active-set search moved onto their edge (held there for its next rounds).
    pinned: Vec<usize>,
    /// The rows in the order the subspace step takes its unknowns.
    order: Vec<usize>,
    subspace_rows: Vec<(f64, [f64; 2])>,
}

/// Counts of the solver's paths, summed over steps: a resting scene that keeps its cost keeps
/// these rates flat.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Steps whose stage 1 the direct solve answered.
    pub direct: u64,
    /// Steps whose stage 1 the direct solve declined (the sweeps ran).
    pub declined: u64,
    /// Gauss–Seidel sweeps run, normal (stage 1) and friction (stage 2).
    pub normal_sweeps: u64,
    pub friction_sweeps: u64,
    /// Steps whose stage 1 a large system's warm-started trial sweeps answered.
    pub warm: u64,
    /// Steps whose friction stage the trial sweeps answered, and the direct solve.
    pub friction_warm: u64,
    pub friction_direct: u64,
    /// Subspace steps the friction sweeps took (each a direct solve on the sweeps' active set,
    /// see `subspace_step`).
    pub friction_subspace: u64,
    /// Subspace steps the normal sweeps of a large system took (stage 1: the same step with
    /// no friction unknowns).
    pub normal_subspace: u64,
}

/// The axis d at a contact: +d on A at its lever, −d on B (if any, not fixed) at its own.
fn axis_at(d: Vector3<f64>, contact: &Contact, motions: &[SolverBody]) -> Axis {
    Axis::new(
        d,
        (contact.body, &contact.lever),
        contact.other_body().map(|b| (b, &contact.lever_other)),
        motions,
    )
}

/// One contact as the solver sees it.
#[derive(Debug, Clone, Copy, Default)]
struct Row {
    /// Unit normal n with its ends and k.
    normal: Axis,
    /// Accumulated normal impulse λ ≥ 0 and tangent impulses, N·s.
    lambda: f64,
    lambda_tangent: [f64; 2],
    /// λ at the end of stage 1 (the frictionless compression impulse).
    compression: f64,
    /// μ λ from stage 1: the radius of the friction disk.
    friction_bound: f64,
    /// Restitution impulse e λ (scaled by the energy clamp).
    lambda_restitution: f64,
    /// Normal velocity before the response, m/s.
    approach: f64,
    /// The normal velocity the contact may keep: gap/dt for a speculative contact (it may
    /// close its gap within the next step, no more), 0 for a touching one, m/s.
    bias: f64,
    /// The last step's impulse at the same contact, if any (warm start of the sweeps).
    warm: Vector3<f64>,
}

/// Detects contacts (swept vertex tests, contact geometry, speculative rows) and runs the
/// response on `states`. On entry `contacts` holds the last step's contacts (they warm-start
/// the sweeps).
///
/// Returns the energy of all bodies before and after (None when nothing touched: the states
/// are unchanged).
pub fn respond(
    input: &CollideInput,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> Option<EnergyChange> {
    let bounce_speed = input
        .gravity
        .map_or(0.0, |g| BOUNCE_STEPS * g.norm() * input.dt);
    // Points closer than this to a surface are speculative contacts (module doc).
    let margin = bounce_speed * input.dt;
    std::mem::swap(&mut scratch.previous, contacts);
    if !contacts::find(
        input,
        states,
        margin,
        contacts,
        &mut scratch.points,
        &mut scratch.broad,
    ) {
        // Nothing has touched: speculative contacts alone never act.
        contacts.clear();
        return None;
    }
    // Every body's velocities, with I⁻¹_world exactly as the derive phase (and the energy
    // panel) computes it.
    let motions = &mut scratch.motions;
    motions.clear();
    motions.extend(input.bodies.iter().zip(states.iter()).map(|(body, state)| {
        let k = derive(body, state);
        SolverBody {
            v: k.velocity,
            omega: k.angular_velocity,
            l: state.angular_momentum,
            inv_mass: body.inv_mass,
            inv_inertia: k.inv_inertia_world,
            touched: false,
        }
    }));
    if contacts.iter().any(|c| c.depth <= 0.0) {
        // A point approaching at bouncing speed is left to touch and bounce next step.
        contacts.retain(|c| c.depth > 0.0 || relative_velocity(c, motions) >= -bounce_speed);
    }
    let kinetic = |i: usize, s: &State, inv_inertia: &Matrix3<f64>| {
        kinetic_energy_with(
            &input.bodies[i],
            inv_inertia,
            &s.linear_momentum,
            &s.angular_momentum,
        )
    };
    let potential = |i: usize, x: &Vector3<f64>| {
        input
            .gravity
            .map_or(0.0, |g| -input.bodies[i].mass * g.dot(x))
    };
    let total = |states: &[State], motions: &[SolverBody]| {
        let mut e = Energy::default();
        for (i, s) in states.iter().enumerate() {
            let k = kinetic(i, s, &motions[i].inv_inertia);
            let v = potential(i, &s.position);
            e = e + Energy {
                kinetic: k,
                potential: v,
                total: k + v,
            };
        }
        e
    };
    let before = total(states, motions);
    // The push-out depends on the geometry only: known before the velocities are solved, so
    // the work it does against gravity can be paid from the kinetic energy.
    let fix = Fix {
        bodies: input.bodies,
        before: input.before,
        dt: input.dt,
    };
    // Only a bounce pays it (stage 3): with e = 0, or no contact approaching near the bounce
    // speed, it is not needed, and it is a whole push-out (a pyramid at rest penetrates by
    // ½|g|dt² at every support after the integrator: a factorisation a step).
    let may_bounce = input.model.restitution > 0.0
        && contacts
            .iter()
            .any(|c| relative_velocity(c, &scratch.motions) < -0.5 * bounce_speed);
    let lift = if may_bounce {
        fix.lift(contacts, states, &potential, &mut scratch.fix)
    } else {
        0.0
    };
    let settings = Settings {
        restitution: input.model.restitution,
        friction: input.model.friction,
        bounce_speed,
        dt: input.dt,
        lift,
    };
    let Scratch {
        rows,
        tangents,
        motions,
        previous,
        warm,
        fix: fs,
        direct,
        change,
        advanced,
        counters,
        ..
    } = scratch;
    advanced.clear();
    advanced.resize(motions.len(), false);
    let buffers = Buffers {
        rows,
        tangents,
        motions,
        direct,
        change,
        bounced: advanced,
        counters,
    };
    // A bounce says nothing about the next step's load: stored as no impulse.
    warm.store(previous.iter().map(|p| {
        let j = if p.normal_velocity >= -bounce_speed {
            p.impulse
        } else {
            Vector3::zeros()
        };
        (p, j)
    }));
    resolve(&settings, contacts, warm, buffers);
    for (state, m) in states.iter_mut().zip(motions.iter()) {
        if m.touched {
            state.linear_momentum = m.v / m.inv_mass;
            state.angular_momentum = m.l;
        }
    }
    // Advanced from the start of the step: touched and not bounced (`advanced` held the
    // bounce flags).
    for (advance, m) in advanced.iter_mut().zip(motions.iter()) {
        *advance = m.touched && !*advance;
    }
    fix.apply(contacts, states, advanced, fs);
    // Round-off guard: K is quadratic in (P, L), so scaling both by √(K₀/K) gives K₀.
    let mut after = total(states, motions);
    for _ in 0..4 {
        if after.kinetic <= before.kinetic {
            break;
        }
        let scale = (before.kinetic / after.kinetic).sqrt() * (1.0 - 4.0 * f64::EPSILON);
        for (state, m) in states.iter_mut().zip(motions.iter()) {
            if m.touched {
                state.linear_momentum *= scale;
                state.angular_momentum *= scale;
            }
        }
        after = total(states, motions);
    }
    // Speculative contacts that were not needed are not contacts.
    contacts.retain(|c| c.depth > 0.0 || c.impulse != Vector3::zeros());
    Some(EnergyChange { before, after })
}

/// The relative velocity of a contact point along its normal (A relative to B).
fn relative_velocity(c: &Contact, motions: &[SolverBody]) -> f64 {
    let a = &motions[c.body];
    let mut u = a.v + a.omega.cross(&c.lever);
    if let Some(b) = c.other_body() {
        let m = &motions[b];
        u -= m.v + m.omega.cross(&c.lever_other);
    }
    u.dot(&c.normal)
}

/// The scratch buffers the velocity stages use.
struct Buffers<'a> {
    rows: &'a mut Vec<Row>,
    tangents: &'a mut Vec<[Axis; 2]>,
    motions: &'a mut Vec<SolverBody>,
    direct: &'a mut Direct,
    change: &'a mut Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    /// Per body: whether a restitution impulse acted on it (then the position fix does not
    /// re-advance it).
    bounced: &'a mut Vec<bool>,
    counters: &'a mut Counters,
}

/// What the velocity stages need besides the bodies and the contacts.
#[derive(Debug, Clone, Copy)]
struct Settings {
    /// Coefficient of restitution e and Coulomb friction μ.
    restitution: f64,
    friction: f64,
    /// Contacts approaching slower than this do not bounce, m/s.
    bounce_speed: f64,
    /// Time step, s (a speculative contact may close its gap within it).
    dt: f64,
    /// The push-out's work against gravity, J: paid from the bounce.
    lift: f64,
}

/// The velocity stages (module doc) for `contacts` (point, depth, normal and levers filled
/// in); fills in each contact's normal velocity, denominator and impulse, and the motions.
fn resolve(settings: &Settings, contacts: &mut [Contact], previous: &WarmCache, buffers: Buffers) {
    let Settings {
        restitution,
        friction,
        bounce_speed,
        dt,
        lift,
    } = *settings;
    let Buffers {
        rows,
        tangents: tangent_directions,
        motions,
        direct: buffers_direct,
        change,
        bounced,
        counters,
    } = buffers;
    // The energy the velocities may keep: K₀ less the push-out's work against gravity.
    let kinetic_allowed = motions.iter().map(SolverBody::kinetic).sum::<f64>() - lift;
    rows.clear();
    rows.extend(contacts.iter().map(|c| {
        let normal = axis_at(c.normal, c, motions);
        let warm = previous.find(c);
        Row {
            normal,
            lambda: 0.0,
            lambda_tangent: [0.0; 2],
            compression: 0.0,
            friction_bound: 0.0,
            lambda_restitution: 0.0,
            approach: normal.velocity(motions),
            bias: (-c.depth - GAP_ROUND_OFF).max(0.0) / dt,
            warm: warm.unwrap_or_else(Vector3::zeros),
        }
    }));
    let fastest = rows.iter().map(|r| -r.approach).fold(0.0, f64::max);
    let tolerance = TOLERANCE * (1.0 + fastest);

    // Stage 1: inelastic normal impulses, λ ≥ 0. A large system first tries a few sweeps from
    // the last step's impulses (a scene at rest: they are the answer, and one sweep over the
    // rows confirms it for far less than a factorisation); then the direct solve when it
    // applies; else projected Gauss–Seidel, warm-started from the last step's impulses.
    let large = rows.len() > SWEEPS_FIRST_ROWS
        && mean_envelope(rows, &mut buffers_direct.body_first) > WIDE_ENVELOPE;
    let mut answered = false;
    if large && buffers_direct.trial_skip > 0 {
        buffers_direct.trial_skip -= 1;
    } else if large {
        buffers_direct.trial.clear();
        buffers_direct.trial.extend_from_slice(motions);
        warm_start_normals(rows, motions);
        let (converged, sweeps) = sweep_normals(rows, motions, tolerance, TRIAL_SWEEPS);
        counters.normal_sweeps += sweeps;
        if converged {
            counters.warm += 1;
            answered = true;
            buffers_direct.trial_wait = 0;
        } else {
            let wait = (2 * buffers_direct.trial_wait).clamp(1, TRIAL_WAIT_MAX);
            buffers_direct.trial_wait = wait;
            buffers_direct.trial_skip = wait;
            motions.copy_from_slice(&buffers_direct.trial);
            for row in rows.iter_mut() {
                row.lambda = 0.0;
            }
        }
    }
    if !answered {
        let direct = direct_inelastic(large, rows, motions, tolerance, buffers_direct);
        if direct {
            counters.direct += 1;
        } else {
            counters.declined += 1;
            warm_start_normals(rows, motions);
            let (_, sweeps) = if large {
                sweep_with_subspace(rows, &[], motions, tolerance, buffers_direct, counters)
            } else {
                sweep_normals(rows, motions, tolerance, MAX_SWEEPS as u64)
            };
            counters.normal_sweeps += sweeps;
        }
    }

    for row in rows.iter_mut() {
        row.compression = row.lambda;
    }

    // Stage 2: friction in the fixed disks |λ_t| ≤ μ λ, normal impulses still kept ≥ 0.
    // Skipped when no pushing contact slides (a body at rest): there is nothing to do.
    let sliding = |row: &Row, contact: &Contact, motions: &[SolverBody]| {
        let a = &motions[contact.body];
        let mut u = a.v + a.omega.cross(&contact.lever);
        if let Some(b) = contact.other_body() {
            let m = &motions[b];
            u -= m.v + m.omega.cross(&contact.lever_other);
        }
        row.lambda > 0.0
            && (u - contact.normal * u.dot(&contact.normal)).norm_squared() > tolerance * tolerance
    };
    tangent_directions.clear();
    if friction > 0.0
        && rows
            .iter()
            .zip(contacts.iter())
            .any(|(r, c)| sliding(r, c, motions))
    {
        for (row, contact) in rows.iter_mut().zip(contacts.iter()) {
            row.friction_bound = friction * row.lambda;
            let (t1, t2) = tangents(&contact.normal);
            tangent_directions.push([axis_at(t1, contact, motions), axis_at(t2, contact, motions)]);
        }
        // A large system: a few sweeps from the last step's impulses first (at rest or
        // sliding steadily they are the answer). Then the direct solve (everything sticks);
        // else the sweeps, warm-started from the last step's friction
        // impulses (kept in their disks).
        let mut solved = false;
        if large {
            let Direct {
                trial, trial_rows, ..
            } = &mut *buffers_direct;
            trial.clear();
            trial.extend_from_slice(motions);
            trial_rows.clear();
            trial_rows.extend(rows.iter().map(|r| (r.lambda, r.lambda_tangent)));
            // From last step's normal impulses as well as its friction: stage 1's answer,
            // when its direct solve gave it, shares the loads its own way (the minimum norm),
            // and at rest last step's friction holds last step's shares, not those (a pyramid
            // of 20 rows standing past 3.25 s: its sweeps then hit their cap on every step).
            for row in rows.iter_mut() {
                let warm = row.warm.dot(&row.normal.d).max(0.0);
                if warm != row.lambda {
                    row.normal.apply(warm - row.lambda, motions);
                    row.lambda = warm;
                }
            }
            warm_start_friction(rows, tangent_directions, motions);
            let (converged, sweeps) =
                sweep_friction(rows, tangent_directions, motions, tolerance, TRIAL_SWEEPS);
            counters.friction_sweeps += sweeps;
            if converged {
                counters.friction_warm += 1;
                solved = true;
            } else {
                motions.copy_from_slice(trial);
                for (row, &(lambda, tangent)) in rows.iter_mut().zip(trial_rows.iter()) {
                    row.lambda = lambda;
                    row.lambda_tangent = tangent;
                }
            }
        }
        for how in [Sticking::Exact, Sticking::Resting { dt }] {
            if !solved {
                solved = direct_sticking(
                    rows,
                    tangent_directions,
                    motions,
                    tolerance,
                    how,
                    buffers_direct,
                );
                if solved {
                    counters.friction_direct += 1;
                }
            }
        }
        if !solved {
            warm_start_friction(rows, tangent_directions, motions);
            let (_, sweeps) = sweep_with_subspace(
                rows,
                tangent_directions,
                motions,
                tolerance,
                buffers_direct,
                counters,
            );
            counters.friction_sweeps += sweeps;
        }
    }

    // Stage 3: Poisson restitution e λ where the approach was fast, scaled so that K ≤ K₀.
    if restitution > 0.0 && rows.iter().any(|r| bounces(r, bounce_speed)) {
        // The restitution impulses' changes to each body: Δv, ΔL, Δω.
        change.clear();
        change.resize(
            motions.len(),
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
        );
        for row in rows.iter_mut() {
            if bounces(row, bounce_speed) {
                let j = restitution * row.compression;
                row.lambda_restitution = j;
                for (end, sign) in row.normal.ends() {
                    let m = &motions[end.body];
                    let c = &mut change[end.body];
                    c.0 += row.normal.d * (sign * j * m.inv_mass);
                    c.1 += end.rd * j;
                    c.2 += end.w * j;
                }
            }
        }
        // K(s) = a s² + b s + c along Λ_inelastic + s Λ_restitution.
        let (mut a, mut b) = (0.0, 0.0);
        for (m, (dv, dl, domega)) in motions.iter().zip(change.iter()) {
            if m.inv_mass == 0.0 {
                continue; // a fixed body takes no impulse
            }
            a += 0.5 * (dv.norm_squared() / m.inv_mass + domega.dot(dl));
            b += dv.dot(&m.v) / m.inv_mass + m.omega.dot(dl);
        }
        let c: f64 = motions.iter().map(SolverBody::kinetic).sum();
        let scale = if a + b + c <= kinetic_allowed || a <= 0.0 {
            1.0
        } else {
            let slack = (kinetic_allowed - c).max(0.0);
            ((-b + (b * b + 4.0 * a * slack).sqrt()) / (2.0 * a)).clamp(0.0, 1.0)
        };
        for ((m, bounce), (dv, dl, domega)) in motions
            .iter_mut()
            .zip(bounced.iter_mut())
            .zip(change.iter())
        {
            if *dl != Vector3::zeros() || *dv != Vector3::zeros() {
                m.v += dv * scale;
                m.l += dl * scale;
                m.omega += domega * scale;
                *bounce = true;
            }
        }
        for row in rows.iter_mut() {
            row.lambda_restitution *= scale;
        }
    }

    for (index, (contact, row)) in contacts.iter_mut().zip(rows.iter()).enumerate() {
        contact.normal_velocity = row.approach;
        contact.denominator = row.normal.k;
        contact.impulse = row.normal.d * (row.lambda + row.lambda_restitution);
        if let Some([t1, t2]) = tangent_directions.get(index) {
            contact.impulse += t1.d * row.lambda_tangent[0] + t2.d * row.lambda_tangent[1];
        }
    }
}

/// The mean width of the rows' envelope in contact order, `Σ_p (p − first(p) + 1) / m`, with
/// first(p) the first row acting on one of row p's bodies (as [`Envelope`] stores it).
fn mean_envelope(rows: &[Row], body_first: &mut Vec<usize>) -> f64 {
    body_first.clear();
    let mut sum = 0usize;
    for (p, row) in rows.iter().enumerate() {
        let mut first = p;
        for b in row.normal.bodies().into_iter().flatten() {
            if b >= body_first.len() {
                body_first.resize(b + 1, usize::MAX);
            }
            first = first.min(body_first[b]);
            body_first[b] = body_first[b].min(p);
        }
        sum += p - first + 1;
    }
    sum as f64 / rows.len().max(1) as f64
}

/// Starts the normal sweeps from the last step's normal impulses (kept ≥ 0).
fn warm_start_normals(rows: &mut [Row], motions: &mut [SolverBody]) {
    for row in rows.iter_mut() {
        row.normal.with_inverse();
        let warm = row.warm.dot(&row.normal.d).max(0.0);
        if warm > 0.0 {
            row.lambda = warm;
            row.normal.apply(warm, motions);
        }
    }
}

/// Projected Gauss–Seidel on the normal impulses, at most `cap` sweeps; returns whether they
/// converged and how many ran.
fn sweep_normals(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    tolerance: f64,
    cap: u64,
) -> (bool, u64) {
    for sweep in 1..=cap {
        let mut largest: f64 = 0.0;
        for row in rows.iter_mut() {
            largest = largest.max(normal_update(row, motions));
        }
        if largest <= tolerance {
            return (true, sweep);
        }
    }
    (false, cap)
}

/// Starts the friction sweeps from the last step's friction impulses, kept in their disks.
fn warm_start_friction(rows: &mut [Row], directions: &[[Axis; 2]], motions: &mut [SolverBody]) {
    for (row, directions) in rows.iter_mut().zip(directions.iter()) {
        row.normal.with_inverse();
        let [t1, t2] = directions;
        let mut warm = [row.warm.dot(&t1.d), row.warm.dot(&t2.d)];
        let size = (warm[0] * warm[0] + warm[1] * warm[1]).sqrt();
        if size > row.friction_bound {
            let scale = row.friction_bound / size;
            warm = [warm[0] * scale, warm[1] * scale];
        }
        let step = [
            warm[0] - row.lambda_tangent[0],
            warm[1] - row.lambda_tangent[1],
        ];
        if step != [0.0; 2] {
            row.lambda_tangent = warm;
            t1.apply(step[0], motions);
            t2.apply(step[1], motions);
        }
    }
}

/// Block coordinate descent on the normal and friction impulses, at most `cap` sweeps;
/// returns whether they converged and how many ran.
fn sweep_friction(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    cap: u64,
) -> (bool, u64) {
    for sweep in 1..=cap {
        let mut largest: f64 = 0.0;
        for (row, directions) in rows.iter_mut().zip(directions.iter()) {
            let bound = row.friction_bound;
            largest = largest.max(normal_update(row, motions));
            if bound == 0.0 {
                continue;
            }
            let change = friction_update(row, directions, bound, motions);
            largest = largest.max(change);
        }
        if largest <= tolerance {
            return (true, sweep);
        }
    }
    (false, cap)
}

/// Sweeps with a subspace step ([`subspace_step`]) after every [`SUBSPACE_EVERY`]
/// sweeps that did not converge, at most [`MAX_SWEEPS`] sweeps in all; returns whether they
/// converged and how many sweeps ran. With friction directions these are the friction sweeps
/// ([`sweep_friction`]); with none (stage 1, every friction bound 0) the normal sweeps
/// ([`sweep_normals`]), and the subspace step solves the pushing normals alone. A system too
/// wide for the direct solve ([`ENVELOPE_MAX`]) stops trying the subspace steps.
fn sweep_with_subspace(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers: &mut Direct,
    counters: &mut Counters,
) -> (bool, u64) {
    let cap = MAX_SWEEPS as u64;
    let normals_only = directions.is_empty();
    let mut total = 0;
    let mut subspace = true;
    let mut steps_left = if normals_only {
        NORMAL_SUBSPACE_MAX
    } else {
        usize::MAX
    };
    loop {
        subspace &= steps_left > 0;
        let burst = if subspace { SUBSPACE_EVERY } else { cap }.min(cap - total);
        let (converged, sweeps) = if normals_only {
            sweep_normals(rows, motions, tolerance, burst)
        } else {
            sweep_friction(rows, directions, motions, tolerance, burst)
        };
        total += sweeps;
        if converged || total >= cap {
            return (converged, total);
        }
        // An active-set search: a step cut short by a normal reaching 0 or a sticking disk
        // reaching its edge changes the active set; solve again on the new one.
        buffers.pinned.clear();
        for _ in 0..SUBSPACE_ROUNDS {
            match subspace_step(rows, directions, motions, buffers) {
                Subspace::Taken { whole } => {
                    steps_left = steps_left.saturating_sub(1);
                    if normals_only {
                        counters.normal_subspace += 1;
                    } else {
                        counters.friction_subspace += 1;
                    }
                    if whole || steps_left == 0 {
                        break;
                    }
                }
                Subspace::Declined => break,
                Subspace::TooWide => {
                    subspace = false;
                    break;
                }
            }
        }
    }
}

/// What a subspace step did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Subspace {
    /// Taken, whole (α = 1) or cut short by the ratio test.
    Taken { whole: bool },
    /// Nothing to solve, a singular system, no room to move, or no descent (round-off).
    Declined,
    /// The system's envelope is over [`ENVELOPE_MAX`].
    TooWide,
}

/// A subspace step of the friction stage (projected Gauss–Seidel with subspace minimisation,
/// Silcowitz, Niebe & Erleben 2010, with a Newton step along the sliding disks' edges):
/// block Gauss–Seidel converges linearly, and slowly when contacts are stiffly coupled or sit
/// on the edge of their friction disk with almost no slip (a domino leaning on the next: its
/// floor contacts at the stick–slip limit); the sweeps find the active set long before they
/// converge on it. With the active set the sweeps left, the stage-2 objective
///
/// ```text
/// F(Λ) = K(Λ) + Σ λₙ gₙ/dt           (the objective the sweeps minimise, ≥ K)
/// ```
///
/// is minimised by one Newton step, a direct solve over these unknowns:
///
/// - each pushing normal (λₙ > 0), its row `uₙ + gₙ/dt = 0`; the normals at 0 are held;
/// - each sticking disk (|λ_t| < bound, or on the edge with the slip along λ_t: it wants
///   in), both tangents, rows `u_t = 0`;
/// - each sliding disk (on its edge |λ_t| = bound, slip u_t against λ_t): its impulse may
///   move along the edge, `λ_t = bound (s cos θ + s⊥ sin θ)` with `s = λ_t/|λ_t|`, `s⊥` s
///   turned by 90°; the unknown is the arc δ = bound·θ along s⊥, whose row carries the
///   edge's curvature: `∂²F/∂δ² = s⊥ᵀ K_t s⊥ + κ`, `κ = −u_t·s / bound ≥ 0` (the slip speed
///   over the bound: the Lagrange multiplier ν of the disk update), right-hand side `−u_t·s⊥`.
///
/// ```text
/// (H + ε𝟙) Δ = −∇F      H: the rows' couplings A (the same minimum-norm LDLᵀ as the direct
///                       solves), plus κ on each edge unknown's diagonal
/// ```
///
/// The step is `αΔ` with the largest α ≤ 1 that keeps every free normal ≥ 0 and every
/// sticking disk inside its bound, `|λ_t + αΔ_t| ≤ bound` (the positive root of a quadratic
/// in α); an edge unknown moves its impulse along the circle, `λ_t ← bound (λ_t + αδ s⊥)/|·|`.
/// The change of F is then measured exactly — F is quadratic in Λ, so
/// `F(Λ + ΔΛ) − F(Λ) = ΔΛ·(∇F(Λ) + ∇F(Λ + ΔΛ))/2`, with ∇F the rows' velocities (plus gₙ/dt),
/// summed over the rows that moved: no cancellation against F itself, so even a step of
/// 1e-20 J is judged right — and a step that did not lower F (H nearly singular, solved
/// inaccurately) is undone and tried 8 times shorter, [`SUBSPACE_BACKTRACKS`] times at most.
/// Like every sweep update, an accepted step only lowers F, so K stays below K₀. A step cut
/// short by the ratio test changes the active set (that normal is held at 0, that disk is
/// held on its edge whatever its slip says) and the caller solves again, up to
/// [`SUBSPACE_ROUNDS`] times. The sweeps go on from there and judge convergence as before,
/// to the same tolerance: the steps change only how fast they get there. The unknowns are
/// ordered by the last body their row acts on, so a chain of bodies has a banded envelope.
fn subspace_step(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    buffers: &mut Direct,
) -> Subspace {
    let Direct {
        system,
        saved,
        unknowns,
        subspace_rows,
        pinned,
        order,
        ..
    } = buffers;
    // Rows ordered by the last body they act on (stable: a pair's rows stay together), so
    // a body's floor contacts sit beside its contacts with its neighbours: a chain of bodies
    // (a row of dominoes, a stack) gets a banded envelope, where contact order (every floor
    // contact first) would reach back over all of them.
    order.clear();
    order.extend(0..rows.len());
    order.sort_by_key(|&i| {
        let n = &rows[i].normal;
        n.b.map_or(n.a.body, |b| b.body.max(n.a.body))
    });
    unknowns.clear();
    for &i in order.iter() {
        let row = &rows[i];
        if row.lambda > 0.0 {
            let gradient = row.normal.velocity(motions) + row.bias;
            unknowns.push(Unknown {
                row: i,
                tangent: None,
                before: [gradient, 0.0],
                direction: row.normal,
            });
        }
        let bound = row.friction_bound;
        if bound == 0.0 {
            continue;
        }
        let [t1, t2] = &directions[i];
        let u = [t1.velocity(motions), t2.velocity(motions)];
        let l = row.lambda_tangent;
        let size = (l[0] * l[0] + l[1] * l[1]).sqrt();
        let slip_along = (u[0] * l[0] + u[1] * l[1]) / size;
        if size >= bound * (1.0 - SLIDING_EDGE) && (slip_along <= 0.0 || pinned.contains(&i)) {
            let s = [l[0] / size, l[1] / size];
            let c = [-s[1], s[0]];
            unknowns.push(Unknown {
                row: i,
                tangent: Some((c, (-slip_along / bound).max(0.0))),
                before: u,
                direction: combined(&directions[i], c),
            });
        } else {
            for (k, c) in [[1.0, 0.0], [0.0, 1.0]].into_iter().enumerate() {
                unknowns.push(Unknown {
                    row: i,
                    tangent: Some((c, 0.0)),
                    before: u,
                    direction: directions[i][k],
                });
            }
        }
    }
    let m = unknowns.len();
    if m == 0 {
        return Subspace::Declined;
    }
    // H_pq: the couplings of the unknowns' directions (a tangent unknown is c₁ t₁ + c₂ t₂,
    // combined once: the coupling is bilinear).
    system.reset(m);
    for p in 0..m {
        let up = &unknowns[p];
        let dp = &up.direction;
        system.rhs[p] = -match up.tangent {
            None => up.before[0],
            Some((c, _)) => c[0] * up.before[0] + c[1] * up.before[1],
        };
        system.fill_row(p, dp.bodies(), |q| {
            let dq = &unknowns[q].direction;
            if q == p {
                Some(dp.coupling(dp, motions) + up.tangent.map_or(0.0, |(_, kappa)| kappa))
            } else {
                dp.shares_a_body(dq).then(|| dp.coupling(dq, motions))
            }
        });
        if system.stored() > ENVELOPE_MAX {
            return Subspace::TooWide;
        }
    }
    let Some(delta) = system.solve(Pivots::Regularised) else {
        return Subspace::Declined;
    };
    // The ratio test: the largest α ≤ 1 keeping the free normals ≥ 0 and the sticking disks
    // inside their bounds (an edge unknown stays on its circle whatever α).
    let mut alpha: f64 = 1.0;
    let mut blocking = None;
    let mut p = 0;
    while p < m {
        let unknown = &unknowns[p];
        let row = &rows[unknown.row];
        match unknown.tangent {
            None => {
                if row.lambda + delta[p] < 0.0 && row.lambda / -delta[p] < alpha {
                    alpha = row.lambda / -delta[p];
                    blocking = Some(p);
                }
                p += 1;
            }
            Some(_) if unknowns.get(p + 1).is_none_or(|u| u.row != unknown.row) => {
                // An edge unknown: the model is quadratic in the arc, the edge is a circle;
                // turn by at most EDGE_TURN radians, where they agree to second order.
                let reach = EDGE_TURN * row.friction_bound / delta[p].abs();
                if reach < alpha {
                    alpha = reach;
                    blocking = None;
                }
                p += 1;
            }
            Some(_) => {
                // |t + α d|² = bound²: α = (−t·d + √((t·d)² + |d|²(bound² − |t|²))) / |d|².
                let (t, d) = (row.lambda_tangent, [delta[p], delta[p + 1]]);
                let dd = d[0] * d[0] + d[1] * d[1];
                let td = t[0] * d[0] + t[1] * d[1];
                let inside = row.friction_bound.powi(2) - (t[0] * t[0] + t[1] * t[1]);
                if dd > 0.0 {
                    let reach = (-td + (td * td + dd * inside.max(0.0)).sqrt()) / dd;
                    if reach < alpha {
                        alpha = reach;
                        blocking = Some(p);
                    }
                }
                p += 2;
            }
        }
    }
    if alpha.is_nan() || alpha <= 0.0 {
        return Subspace::Declined;
    }
    // Stage 1 (no friction unknowns) first tries the whole step projected onto λ ≥ 0, which
    // changes many normals at once (a pyramid settling changes hundreds); the ratio-test step
    // follows if that one does not lower F.
    let ratio = (alpha, blocking);
    let projected_first = directions.is_empty() && alpha < 1.0;
    if projected_first {
        (alpha, blocking) = (1.0, None);
    }
    saved.clear();
    saved.extend_from_slice(motions);
    subspace_rows.clear();
    subspace_rows.extend(rows.iter().map(|r| (r.lambda, r.lambda_tangent)));
    // Backtracking: a step that did not lower F (a nearly singular H solved inaccurately) is
    // undone and tried again 8 times shorter, a few times.
    for attempt in 0..SUBSPACE_BACKTRACKS {
        let mut p = 0;
        while p < m {
            let unknown = unknowns[p];
            let row = &mut rows[unknown.row];
            match unknown.tangent {
                None => {
                    // The normal that cut the step short leaves the active set at exactly 0.
                    let new = if blocking == Some(p) {
                        0.0
                    } else {
                        (row.lambda + alpha * delta[p]).max(0.0)
                    };
                    let step = new - row.lambda;
                    row.lambda = new;
                    row.normal.apply(step, motions);
                    p += 1;
                }
                Some((c, _)) => {
                    let pair = unknowns.get(p + 1).is_some_and(|u| u.row == unknown.row);
                    let old = row.lambda_tangent;
                    let step = if pair {
                        [alpha * delta[p], alpha * delta[p + 1]]
                    } else {
                        [alpha * delta[p] * c[0], alpha * delta[p] * c[1]]
                    };
                    let mut new = [old[0] + step[0], old[1] + step[1]];
                    let size = (new[0] * new[0] + new[1] * new[1]).sqrt();
                    if size > row.friction_bound || !pair || blocking == Some(p) {
                        // Back onto the edge: a sticking disk that reached it (round-off), or an
                        // edge unknown moved along its tangent.
                        let scale = row.friction_bound / size;
                        new = [new[0] * scale, new[1] * scale];
                    }
                    row.lambda_tangent = new;
                    let [t1, t2] = &directions[unknown.row];
                    t1.apply(new[0] - old[0], motions);
                    t2.apply(new[1] - old[1], motions);
                    p += if pair { 2 } else { 1 };
                }
            }
        }
        // ΔF = ΔΛ·(∇F before + ∇F after)/2 over the rows that moved (exact: F is quadratic).
        let mut change = 0.0;
        let mut p = 0;
        while p < m {
            let unknown = &unknowns[p];
            let row = &rows[unknown.row];
            let (lambda, tangent) = subspace_rows[unknown.row];
            match unknown.tangent {
                None => {
                    let after = row.normal.velocity(motions) + row.bias;
                    change += (row.lambda - lambda) * 0.5 * (unknown.before[0] + after);
                    p += 1;
                }
                Some(_) => {
                    let [t1, t2] = &directions[unknown.row];
                    let after = [t1.velocity(motions), t2.velocity(motions)];
                    let moved = [
                        row.lambda_tangent[0] - tangent[0],
                        row.lambda_tangent[1] - tangent[1],
                    ];
                    change += 0.5
                        * (moved[0] * (unknown.before[0] + after[0])
                            + moved[1] * (unknown.before[1] + after[1]));
                    p += if unknowns.get(p + 1).is_some_and(|u| u.row == unknown.row) {
                        2
                    } else {
                        1
                    };
                }
            }
        }
        if change < 0.0 {
            if let Some(p) = blocking.filter(|&p| unknowns[p].tangent.is_some()) {
                pinned.push(unknowns[p].row);
            }
            return Subspace::Taken {
                whole: alpha == 1.0 && attempt == 0 && !projected_first,
            };
        }
        motions.copy_from_slice(saved);
        for (row, &(lambda, tangent)) in rows.iter_mut().zip(subspace_rows.iter()) {
            row.lambda = lambda;
            row.lambda_tangent = tangent;
        }
        if projected_first && attempt == 0 {
            (alpha, blocking) = ratio;
        } else {
            alpha /= 8.0;
            blocking = None;
        }
    }
    Subspace::Declined
}

/// One unknown of the friction subspace step: row `row`'s normal impulse (`tangent` None), or
/// its tangent impulse along `c₁ t₁ + c₂ t₂` with the curvature κ added to its diagonal
/// (`tangent` Some((c, κ)): a sticking disk has two, c = (1, 0) and (0, 1), κ = 0; a sliding
/// one has one, along its edge).
#[derive(Debug, Clone, Copy)]
struct Unknown {
    row: usize,
    tangent: Option<([f64; 2], f64)>,
    /// ∇F along the row's directions before the step: (uₙ + gₙ/dt, 0), or u_t.
    before: [f64; 2],
    /// The row's normal, or its tangent `c₁ t₁ + c₂ t₂` with its ends (for the couplings).
    direction: Axis,
}

/// The direction `c₁ t₁ + c₂ t₂` of two tangent directions at one contact (the same ends):
/// d, r×d and I⁻¹(r×d) are linear in d (its k is not used).
fn combined(t: &[Axis; 2], c: [f64; 2]) -> Axis {
    let [t1, t2] = t;
    let end = |e: &End, f: &End| End {
        body: e.body,
        rd: e.rd * c[0] + f.rd * c[1],
        w: e.w * c[0] + f.w * c[1],
    };
    Axis {
        d: t1.d * c[0] + t2.d * c[1],
        a: end(&t1.a, &t2.a),
        b: t1.b.as_ref().zip(t2.b.as_ref()).map(|(e, f)| end(e, f)),
        k: f64::NAN,
        inv_k: f64::NAN,
    }
}

/// Whether a row bounces: it approached faster than the bounce speed and pushed.
fn bounces(row: &Row, bounce_speed: f64) -> bool {
    row.approach < -bounce_speed && row.compression > 0.0
}

/// The inelastic problem solved directly, when its answer is "every approaching contact
/// stops": with the approaching contacts as the active set, solve
///
/// ```text
/// (A + ε𝟙) λ = −u,   A_ij = Σ_shared bodies (±nᵢ)·(±nⱼ)/M + (r×(±nᵢ))·I⁻¹(r×(±nⱼ)),
///                    ε = 1e-10 · max Aᵢᵢ
/// ```
///
/// by LDLᵀ (A is only semi-definite: 4 coplanar contacts constrain 3 motions; the tiny ε
/// picks the minimum-norm λ, which shares the load symmetrically whatever the contact order).
/// The result is accepted only if it is the solution of the whole problem — every λᵢ ≥ 0 and
/// no contact, active or not, still approaching — so it is the same minimum of K that the
/// sweeps converge to, reached at once. When a λᵢ comes out negative (at rest, a corner of a
/// 4-point face: four rows of rank three) or a contact outside the set still approaches, the
/// active set changes — by one row per pair of bodies, the pair's most negative one out or
/// its most approaching one in, so a pyramid whose every face has such a corner needs a few
/// rounds, not one per face — and the system is solved again, at most [`PIVOT_ROUNDS`]
/// times. The active rows stay in contact order (rows of a pair together), which keeps the
/// envelope of a stack banded. A `wide` system (a pyramid) starts its active set with the
/// rows that pushed last step too (their warm impulse along the normal is positive): its
/// answer at rest, where starting from the approaching rows alone would climb the pyramid a
/// row per pair per round. Returns false (and changes nothing) otherwise.
fn direct_inelastic(
    wide: bool,
    rows: &mut [Row],
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers: &mut Direct,
) -> bool {
    let Direct {
        system,
        saved,
        active,
        lambda,
        entering,
        ..
    } = buffers;
    active.clear();
    let approaching = |r: &Row| r.approach + r.bias < 0.0;
    if !rows.iter().any(approaching) {
        return true;
    }
    let start = |r: &Row| approaching(r) || (wide && r.warm.dot(&r.normal.d) > 0.0);
    active.extend((0..rows.len()).filter(|&i| start(&rows[i])));
    let mut m = active.len();
    if m > DIRECT_MAX {
        return false;
    }
    // An active-set search (principal pivoting), at most PIVOT_ROUNDS changes: solve on the
    // active rows; if some λ < 0 (a corner of a 4-point face whose minimum-norm share came
    // out negative), take the most negative row out; else if a row outside the set still
    // approaches, take the most approaching one in; else accept. Every accepted answer passes
    // the same test as before (λ ≥ 0, nothing approaching): the solution of the whole problem.
    saved.clear();
    saved.extend_from_slice(motions);
    for round in 0..=PIVOT_ROUNDS {
        system.reset(m);
        for p in 0..m {
            let ni = &rows[active[p]].normal;
            system.rhs[p] = -ni.velocity(motions) - rows[active[p]].bias;
            system.fill_row(p, ni.bodies(), |q| {
                let nj = &rows[active[q]].normal;
                ni.shares_a_body(nj).then(|| ni.coupling(nj, motions))
            });
            if system.stored() > ENVELOPE_MAX {
                return false;
            }
        }
        let Some(solution) = system.solve(Pivots::Regularised) else {
            return false;
        };
        lambda.clear();
        lambda.extend_from_slice(&solution[..m]);
        let last = round == PIVOT_ROUNDS;
        let (_, most_negative) = (0..m).fold((0.0, None), |(w, at), p| {
            if lambda[p] < w {
                (lambda[p], Some(p))
            } else {
                (w, at)
            }
        });
        if let Some(p) = most_negative {
            if last || m == 1 {
                return false;
            }
            // Out: the most negative row of each pair of bodies that has one (each face's
            // corner whose minimum-norm share came out negative; the same row as "the most
            // negative" when one pair has them). The rows stay in contact order.
            let pair = |p: usize| {
                let n = &rows[active[p]].normal;
                (n.a.body, n.b.map(|b| b.body))
            };
            let mut out = Vec::new();
            let mut q = 0;
            while q < m {
                let mut end = q;
                let mut worst = (0.0, None);
                while end < m && pair(end) == pair(q) {
                    if lambda[end] < worst.0 {
                        worst = (lambda[end], Some(end));
                    }
                    end += 1;
                }
                out.extend(worst.1);
                q = end;
            }
            debug_assert!(out.contains(&p));

            let mut k = 0;
            active.retain(|_| {
                let keep = out.binary_search(&k).is_err();
                k += 1;
                keep
            });
            m = active.len();
            continue;
        }
        for p in 0..m {
            rows[active[p]].normal.apply(lambda[p], motions);
        }
        // The most approaching row of each pair of bodies that has one, in contact order
        // (the same row as "the most approaching" when one pair has them).
        let pair = |r: &Row| (r.normal.a.body, r.normal.b.map(|b| b.body));
        let mut worst: Option<(usize, f64)> = None;
        let mut group: Option<(usize, f64)> = None;
        entering.clear();
        for (i, r) in rows.iter().enumerate() {
            if i > 0 && pair(r) != pair(&rows[i - 1]) {
                entering.extend(group.take().map(|(j, _)| j));
            }
            let u = r.normal.velocity(motions) + r.bias;
            if u < -tolerance {
                if group.is_none_or(|(_, w)| u < w) {
                    group = Some((i, u));
                }
                if worst.is_none_or(|(_, w)| u < w) {
                    worst = Some((i, u));
                }
            }
        }
        entering.extend(group.map(|(j, _)| j));
        let Some((i, _)) = worst else {
            for p in 0..m {
                rows[active[p]].lambda = lambda[p];
            }
            return true;
        };
        motions.copy_from_slice(saved);
        if last || m + entering.len() > DIRECT_MAX || active.binary_search(&i).is_ok() {
            return false;
        }
        // In, in contact order (rows of a pair stay together: the envelope stays narrow).
        for &j in entering.iter() {
            if let Err(at) = active.binary_search(&j) {
                active.insert(at, j);
            }
        }
        m = active.len();
    }
    false
}

/// Friction solved directly, when its answer is "every pushing contact sticks" (a body at rest
/// on a slope, the usual case with friction): with the contacts that push after stage 1, find
/// the increments of their normal impulses and their tangent impulses that stop every tangent
/// velocity and keep every normal one,
///
/// ```text
/// (A + ε𝟙) Δλ = −u      over the rows (n, t₁, t₂) of each pushing contact
/// ```
///
/// (the same minimum-norm LDLᵀ as the inelastic solve). Accepted only if it is the solution
/// of the stage-2 problem: every λₙ ≥ 0, every |λ_t| inside its disk μ λ_stage1, and no
/// contact approaching; then it is the minimum of K the sweeps converge to, reached at once.
/// Returns false (and changes nothing) otherwise.
///
/// Bodies at rest on redundant contacts (dominoes lying on each other: two floor contacts
/// and two contacts with the next domino each) have many impulses that hold them; the
/// minimum-norm one shares each load evenly and can leave a disk whose neighbour has room
/// (measured: 1.938e-5 N·s asked of a disk of 1.898e-5 beside one of 2.125e-5), and the sweeps
/// then crawl along the disks' edges for ever (40–80 sweeps and 20–40 subspace steps a step,
/// 0.7–2.8 ms, while no body moves by 1e-12 m/s). So a second try, [`Sticking::Resting`],
/// weights the minimum norm by each contact's stage-1 load ℓ: with `Δλ = S y`,
/// `S = diag(ℓ)`, it solves `(S A S + ε𝟙) y = −S u`, the change minimising `Σ (Δλᵢ/ℓᵢ)²`, so
/// each contact takes a share of the load in proportion to its disk. It also holds still every
/// pushing speculative contact whose gap is below [`RESTING_GAP`] (target `uₙ = 0` instead of
/// `−g/dt`): such gaps (nm to 0.1 µm, left where edges are not quite parallel) make the rows
/// ask for motions no rigid body has, and the minimum-norm answer then grows without bound
/// (measured |Δλ| of 10–500 N·s against impulses of 1e-4). The same acceptance checks follow;
/// with a gap held closed, what they accept is the stage-2 solution with that gap taken as 0
/// (as [`GAP_ROUND_OFF`] does for every solve at 1 nm): the contact may push across up to
/// 1 µm, where the exact problem would let the body close that gap first. Velocities are the
/// same either way once no gap is held (the weights move only how the impulses are shared).
fn direct_sticking(
    rows: &mut [Row],
    directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    how: Sticking,
    buffers: &mut Direct,
) -> bool {
    let Direct {
        system,
        saved,
        active,
        lambda: delta,
        ..
    } = buffers;
    active.clear();
    active.extend((0..rows.len()).filter(|&i| rows[i].lambda > 0.0));
    let m = active.len();
    if m == 0 || m > STICKING_MAX {
        return false;
    }
    // Ordered by the last body each acts on (stable), as the subspace step's unknowns: a chain
    // of bodies (a row of dominoes, a stack) gets a banded envelope.
    active.sort_by_key(|&i| {
        let n = &rows[i].normal;
        n.b.map_or(n.a.body, |b| b.body.max(n.a.body))
    });
    // Unknowns 3p (normal), 3p + 1, 3p + 2 (tangents) for the p-th pushing contact.
    let direction = |k: usize| -> &Axis {
        let i = active[k / 3];
        match k % 3 {
            0 => &rows[i].normal,
            t => &directions[i][t - 1],
        }
    };
    // The scale of each unknown (1, or its contact's stage-1 load: the weighted minimum norm),
    // and the normal velocity each pushing contact is held to, −g/dt or 0.
    let largest = active.iter().map(|&i| rows[i].lambda).fold(0.0, f64::max);
    let scale = |p: usize| match how {
        Sticking::Exact => 1.0,
        Sticking::Resting { .. } => rows[active[p / 3]].lambda.max(1e-6 * largest),
    };
    let bias = |row: &Row| match how {
        Sticking::Resting { dt } if row.bias * dt < RESTING_GAP => 0.0,
        _ => row.bias,
    };
    system.reset(3 * m);
    for p in 0..3 * m {
        let dp = direction(p);
        let sp = scale(p);
        let target = if p % 3 == 0 {
            bias(&rows[active[p / 3]])
        } else {
            0.0
        };
        system.rhs[p] = -sp * (dp.velocity(motions) + target);
        system.fill_row(p, dp.bodies(), |q| {
            let dq = direction(q);
            dp.shares_a_body(dq)
                .then(|| sp * scale(q) * dp.coupling(dq, motions))
        });
        if system.stored() > ENVELOPE_MAX {
            return false;
        }
    }
    let Some(solution) = system.solve(Pivots::Regularised) else {
        return false;
    };
    delta.clear();
    delta.extend(solution.iter().enumerate().map(|(p, y)| scale(p) * y));
    for k in 0..m {
        let row = &rows[active[k]];
        let (dn, t1, t2) = (delta[3 * k], delta[3 * k + 1], delta[3 * k + 2]);
        if row.lambda + dn < 0.0 || (t1 * t1 + t2 * t2).sqrt() > row.friction_bound {
            return false;
        }
    }
    saved.clear();
    saved.extend_from_slice(motions);
    for (p, d) in delta[..3 * m].iter().enumerate() {
        direction(p).apply(*d, motions);
    }
    if rows
        .iter()
        .any(|r| r.normal.velocity(motions) + bias(r) < -tolerance)
    {
        motions.copy_from_slice(saved);
        return false;
    }
    for k in 0..m {
        let row = &mut rows[active[k]];
        row.lambda += delta[3 * k];
        row.lambda_tangent = [delta[3 * k + 1], delta[3 * k + 2]];
    }
    true
}

/// The two tries of [`direct_sticking`].
#[derive(Debug, Clone, Copy, PartialEq)]
enum Sticking {
    /// The minimum-norm change, every pushing contact held to `uₙ = −g/dt`: the exact solution.
    Exact,
    /// The load-weighted minimum-norm change, gaps below [`RESTING_GAP`] held closed (step dt).
    Resting { dt: f64 },
}

/// The exact minimisation of K over one contact's friction disk `|λ_t| ≤ bound`, the other
/// impulses fixed (a block of block coordinate descent); returns the largest change it made to
/// a tangent velocity (m/s).
///
/// ```text
/// K_t = [[k₁, c], [c, k₂]],  c = (r×t₁)·I⁻¹(r×t₂)        tangent inverse mass (t₁ ⟂ t₂)
/// x*  = λ_t − K_t⁻¹ u_t                                  the unconstrained minimum
/// |x*| ≤ bound: x = x*;  else x(ν) = (K_t + ν𝟙)⁻¹ K_t x*  with ν ≥ 0 and |x(ν)| = bound
/// ```
///
/// |x(ν)| decreases with ν. ν is the root of the secular equation (Moré–Sorensen)
///
/// ```text
/// ψ(ν) = 1/|x(ν)| − 1/bound,   ψ'(ν) = q/|x|³,   q = xᵀ (K_t + ν𝟙)⁻¹ x
/// ν ← ν + (|x| − bound)/bound · |x|²/q                    (Newton: ν − ψ/ψ')
/// ```
///
/// ψ is increasing, concave and nearly linear in ν (exactly linear when k₁ = k₂, c = 0), so
/// Newton from ν = 0 (where ψ < 0) stays below the root and converges quadratically: 2 to 5
/// iterations to round-off. It is safeguarded in the bracket `[low, high]`, `high =
/// |K_t x*|/bound` (there `|x| ≤ |K_t x*|/(σ_min + ν) < bound`): a step that would leave it
/// bisects instead. An answer left outside the disk by round-off is scaled onto its edge,
/// `x ← x·bound/|x|` (a change of a few ulps). Updating the two tangent
/// directions one at a time instead can stall on the disk's edge at a point that is not the
/// minimum, and where it stalls depends on the contact order. The step is taken only if it
/// does not raise K.
fn friction_update(
    row: &mut Row,
    directions: &[Axis; 2],
    bound: f64,
    motions: &mut [SolverBody],
) -> f64 {
    let [t1, t2] = directions;
    let u = [t1.velocity(motions), t2.velocity(motions)];
    let (k1, k2, c) = (t1.k, t2.k, t1.coupling(t2, motions));
    let det = k1 * k2 - c * c;
    if det <= 0.0 {
        return 0.0;
    }
    let old = row.lambda_tangent;
    // x* = λ − K⁻¹ u
    let target = [
        old[0] - (k2 * u[0] - c * u[1]) / det,
        old[1] - (k1 * u[1] - c * u[0]) / det,
    ];
    let norm = |x: [f64; 2]| (x[0] * x[0] + x[1] * x[1]).sqrt();
    let new = if norm(target) <= bound {
        target
    } else {
        // K x* once, then x(ν) = (K + ν𝟙)⁻¹ K x* on the disk's edge.
        let kx = [
            k1 * target[0] + c * target[1],
            c * target[0] + k2 * target[1],
        ];
        disk_edge(k1, k2, c, kx, bound)
    };
    let step = [new[0] - old[0], new[1] - old[1]];
    // ΔK = Δλ·u + ½ Δλᵀ K Δλ: never accept a step that raises K.
    let gain = step[0] * u[0]
        + step[1] * u[1]
        + 0.5 * (k1 * step[0] * step[0] + 2.0 * c * step[0] * step[1] + k2 * step[1] * step[1]);
    if gain >= 0.0 || gain.is_nan() {
        return 0.0;
    }
    row.lambda_tangent = new;
    t1.apply(step[0], motions);
    t2.apply(step[1], motions);
    (step[0].abs() * k1 + step[1].abs() * c.abs()).max(step[1].abs() * k2 + step[0].abs() * c.abs())
}

/// The point `x(ν) = (K_t + ν𝟙)⁻¹ kx` (kx = K_t x*, |x(0)| > bound) with `|x(ν)| = bound`,
/// ν ≥ 0 by safeguarded Newton on the secular equation (see [`friction_update`]).
fn disk_edge(k1: f64, k2: f64, c: f64, kx: [f64; 2], bound: f64) -> [f64; 2] {
    // (K_t + ν𝟙)⁻¹ y for a 2-vector y.
    let solve = |nu: f64, y: [f64; 2]| {
        let (a, d) = (k1 + nu, k2 + nu);
        let det = a * d - c * c;
        [(d * y[0] - c * y[1]) / det, (a * y[1] - c * y[0]) / det]
    };
    let norm = |x: [f64; 2]| (x[0] * x[0] + x[1] * x[1]).sqrt();
    let (mut low, mut high) = (0.0, norm(kx) / bound);
    let mut nu = 0.0;
    let mut x = solve(nu, kx);
    for _ in 0..MAX_DISK_ITERATIONS {
        let size = norm(x);
        if size <= bound {
            // Past the root (round-off, or a bisection): the feasible end.
            high = nu;
        } else {
            low = nu;
        }
        if size - bound <= DISK_TOLERANCE * bound && size >= bound * (1.0 - DISK_TOLERANCE) {
            break;
        }
        let y = solve(nu, x);
        let q = x[0] * y[0] + x[1] * y[1];
        let newton = nu + (size - bound) / bound * size * size / q;
        nu = if newton > low && newton < high {
            newton
        } else {
            0.5 * (low + high)
        };
        x = solve(nu, kx);
    }
    let size = norm(x);
    if size > bound {
        let scale = bound / size;
        x = [x[0] * scale, x[1] * scale];
    }
    // The feasible side: |x| ≤ bound as computed (scaling can leave it an ulp over).
    while norm(x) > bound {
        x = [x[0] * (1.0 - f64::EPSILON), x[1] * (1.0 - f64::EPSILON)];
    }
    x
}

/// One projected Gauss–Seidel update of a contact's normal impulse; returns the change it made
/// to the contact's normal velocity (m/s).
fn normal_update(row: &mut Row, motions: &mut [SolverBody]) -> f64 {
    let dir = &row.normal;
    let new = (row.lambda - (dir.velocity(motions) + row.bias) * dir.inv_k).max(0.0);
    let change = new - row.lambda;
    if change == 0.0 {
        return 0.0;
    }
    row.lambda = new;
    dir.apply(change, motions);
    change.abs() * dir.k
}

/// Two unit tangents completing n to an orthonormal basis.
pub(super) fn tangents(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = n.cross(&helper).normalize();
    (t1, n.cross(&t1))
}
