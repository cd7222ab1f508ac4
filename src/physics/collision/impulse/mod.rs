//! `impulse`: a physically based response with restitution e and Coulomb friction μ that never
//! adds kinetic energy (for 0 ≤ e ≤ 1, μ ≥ 0), whatever the number of contacts.
//!
//! Each contact is a row between body A and body B (n from B to A; an obstacle is a B of
//! infinite mass): equal and opposite impulses at the same point, so linear and angular
//! momentum are kept (the impulse of one contact, `j = −(1 + e) u_n / k`, and its k: see
//! [`normal`]). A resting body, a stack, a body on a body: one solver.
//!
//! # Constraint kinds and methods, one file each
//!
//! Each constraint kind is one file with the same verbs; the solves over many rows at once
//! are methods, not kinds. `resolve` (here) runs them in stage order.
//!
//! | kind / method | file | verbs |
//! |---|---|---|
//! | normal row (the layer's `constraints::Row`): no penetration, λ ∈ [0, ∞), a speculative gap's bias | [`normal`] | `prepare`, `warm_start`, `update` and `sweep` (solve), `restitution`, `store` |
//! | friction rows (the layer's `constraints::Friction` pair): the Coulomb disk \|λ_t\| ≤ μ λₙ | [`friction`] | `prepare`, `warm_start`, `update` and `sweep` (solve), `store` (no restitution) |
//! | direct solves: LDLᵀ on an active set of rows | [`direct`] | `inelastic` (stage 1), `sticking` (stage 2), `mean_envelope` |
//! | subspace steps: Newton on the sweeps' active set | [`subspace`] | `sweep` (sweeps with steps), `step` |
//! | a stage's rows in body space (what the interior point works on) | [`body_space`] | `setup`, `velocities`, `fill`, `take` |
//! | primal–dual interior point in body space (stage 2: [`INTERIOR_STAGES`]) | [`interior`] | `solve` (a start for the friction sweeps) |
//! | impacts among touching bodies: `propagate` (the default) or `simultaneous` | [`propagate`] | `rounds` (before the stages), `add` |
//!
//! # Many contacts (a face landing flat has 4), in three stages
//!
//! Applying one contact's formula to one vertex after the other makes the result depend on
//! the vertex order, and a single pass leaves later contacts approaching. Instead:
//!
//! 1. **Inelastic normal impulses** λᵢ ≥ 0 by projected Gauss–Seidel ([`normal`]: the update,
//!    and why the kinetic energy K can only go down). When the answer is "every
//!    approaching contact stops and pushes" (a face landing, a body at rest: the usual case),
//!    the same minimum is computed at once by a small LDLᵀ solve and checked against the
//!    conditions of the whole problem ([`direct`]); the sweeps run only when that check fails.
//!    A large system whose rows are *wide* in contact order (a pyramid: each cube touches the
//!    row below and its neighbours; [`WIDE_ENVELOPE`]) first tries [`TRIAL_SWEEPS`] sweeps from
//!    the last step's impulses: at rest they are already the answer, one sweep over the rows
//!    confirms it to the same tolerance, where a factorisation costs rows · width². They go on
//!    while their rate of convergence reaches the tolerance within what the direct solve
//!    would cost (`trial_sweeps`). Only when they do not converge does the direct solve run
//!    (and a failed trial waits a few steps before the next, so a scene whose warm start is
//!    poor stops paying for it; a first touch, with no warm start at all, skips the trial and
//!    starts no wait). Such a
//!    system's direct solve starts its active set from the rows that pushed last step as well
//!    as the approaching ones (a settling pyramid of 20 rows otherwise adds a row per pair of
//!    bodies a round, needs about three rounds per row of cubes, and runs out of rounds), and
//!    if it still declines, its sweeps take subspace steps ([`subspace`]: as stage 2's, on the
//!    pushing normals alone, the whole step first projected onto λ ≥ 0, at most
//!    [`NORMAL_SUBSPACE_MAX`] a step). Every bundled lesson and every stack (banded) keeps the
//!    direct solve first and the plain sweeps. The friction stage below does the same.
//! 2. **Coulomb friction** (if μ > 0, and some pushing contact slides): two tangent impulses
//!    per contact in the disk `|λ_t| ≤ μ λᵢ`, λᵢ from stage 1 ([`friction`]: the exact
//!    minimum of K over a disk). The same order: a large wide system's trial sweeps from the
//!    last step's impulses, then the direct sticking solve ([`direct`]), else the sweeps with
//!    a subspace step every [`SUBSPACE_EVERY`] sweeps ([`subspace`]), from last step's
//!    friction impulses and, on a stage of [`WARM_NORMALS_ROWS`] rows or more, its normals.
//! 3. **Restitution** (Poisson's, e times the stage-1 impulse, only at contacts that
//!    approached faster than [`BOUNCE_STEPS`]·|g|·dt), scaled so that K does not exceed K₀ less
//!    the push-out's work against gravity ([`normal`]: the energy clamp).
//!
//! Under `impacts = "propagate"` (the default; [`propagate`]) with e > 0, when a contact
//! approaches faster than the bounce speed, the three stages first run in *impact rounds* on
//! the approaching pairs alone, until nothing approaches; then once more on every row, for
//! resting contact. A single body landing is one round on all its rows: the same numbers.
//!
//! Last, each row's impulses are stored into its contact (the normal row's `store`, then
//! the friction row's), where they also warm-start the next step ([`WarmCache`]).
//!
//! A last check measures K exactly as the energy panel does and, if round-off alone left it
//! above K₀, scales P and L by `√(K₀/K)` (K is quadratic in (P, L)).
//!
//! # Tried and removed
//!
//! Paths that were built, measured and switched off, then deleted so that the solver carries
//! only what runs; their code is in git history at the commit named.
//!
//! - **ADMM in body space** as the start of the sweeps of a large, wide system whose direct
//!   solve declined (stages 1 and 2; scaled ADMM on `z = J x + b` with `H = M + Jᵀ ρ J`
//!   factored once a penalty, ρ = 1/kₙ per contact, residual balancing). Measured on the
//!   knocked walls (issue 35, 2026-12-06, under load): it took stage 1 of the bonded wall
//!   from its cap (2000 sweeps and 32 subspace steps in half the steps) to 9–17 sweeps and
//!   halved the unconverged steps (71 → 31 of 100; wall-ball 150 → 96 of 200), but the CPU
//!   per step did not fall (bonded-wall-ball 42.5 → 45 ms, wall-ball 32 → 51 ms): it needs
//!   300 to 3000 iterations (about 25 µs each) to reach 1e-7 m/s, and the friction sweeps and
//!   subspace steps then still spent the budget closing 1e-7 to 1e-10 m/s. The interior point
//!   ([`INTERIOR_STAGES`]) does that job. Removed with `admm.rs` (654 lines) in 6776c0e;
//!   the code is at bd48987 (`src/physics/collision/impulse/admm.rs`).
//! - **Semismooth Newton in body space** as the start of the sweeps of any stage whose
//!   direct solve declined (the method of multipliers, each subproblem by semismooth Newton on
//!   `ψ(x)` with Hessian `M + Jᵀ ρ D J`, an exact line search, ρ = 1e5/kₙ). Measured (issue
//!   35, 2026-12-06, CPU per step under load, off → on): bonded-wall-ball 100 steps 44.5 →
//!   40.1 ms (worst step ×7.7 → ×4.0 the median's work, unconverged 71 → 55), wall-ball 200
//!   steps 43.6 → 51.0 ms (×8.1 → ×2.5, 150 → 166), dominoes16 1500 steps 1179 → 557 µs
//!   (×167 → ×48, 4 → 1). It took stage 1 of the walls to 1e-11 m/s in 10–50
//!   factorisations, not the few it should: with a stiff penalty each line search stopped
//!   where the next separating contact closed (s of 1e-4 to 1e-1), a contact at a time again,
//!   and a soft one (1–100, raised each outer iteration) needed more outer iterations; stage
//!   2 of the walls often reached its 60 steps at 1e-5 m/s. It halved the domino run's mean
//!   but doubled its median step (it factors where a few sweeps would do) and did not make
//!   the walls faster. The interior point ([`INTERIOR_STAGES`]), which takes the active set
//!   of all contacts at once, replaced it on stage 2; what they share is [`body_space`].
//!   Removed with `newton.rs` (586 lines) in 58c043b; the code is at bd48987
//!   (`src/physics/collision/impulse/newton.rs`).
//! - **The interior point on stage 1** too (`INTERIOR_NORMALS`, off): the normals' sweeps
//!   after a declined direct solve started from it. Measured with it on stage 1 alone,
//!   wall-ball's median work per step doubled (476 263 → 1 025 380 row updates) and its
//!   unconverged steps rose (299 → 450 of 600); on both stages wall-ball's median was 163 782
//!   against 29 037 on stage 2 alone. The dominoes' stage 1 rarely declines (4 steps in lesson
//!   37).
//! - **A budget of 20 medians** (`MEDIAN_BUDGET`, `budget.rs`, off): a step's budget 20 times
//!   the median work of the scene's steps so far (a histogram), at least 20 sweeps over its
//!   rows, at most [`WORK_BUDGET`], on the whole step or on stage 2 alone. Measured
//!   (2026-12-06, `contact_steps`, work in row updates; off → whole step: median, worst step
//!   after the first ÷ the run's median, unconverged steps): dominoes 3000 steps 993, ×268, 2
//!   → 615, ×89, 200 (largest residual **1.0e-2 m/s**); wall-ball 600 29 037, ×76, 59 → 36
//!   740, ×32, 67 (**0.28 m/s**); bonded-wall-ball 600 76 220, ×39, 187 → 72 840, ×43, 141
//!   (**7.3e-2 m/s**); uncut, no step of these scenes ended above 4.1e-4 m/s. A cut costs the
//!   next steps (the dominoes' steps 600–1000 5.4M against 1.8M uncut, and the row left its
//!   plane: a domino 1.05e-5 m sideways against 5e-10 m), a cut impact is a wrong answer
//!   (the ball's first steps against the wall stopped at 0.28, 0.073, 0.13 m/s), and a causal
//!   median still misses the ratio (a wall hit early has a dear median so far, the dominoes a
//!   cheap one); stage 2 alone did the same on the dominoes and worse on wall-ball. Bounding
//!   the dear steps needs them cheaper, not cut. What is kept: the budget of [`WORK_BUDGET`]
//!   sweeps over the rows, and a step that meets it unconverged says so ([`StepReport`]).
//! - **The friction sweeps' stall stop** (`STALL_BAND` = 0, `stall.rs`): a large stage's
//!   sweeps (≥ [`SWEEPS_FIRST_ROWS`] rows) also stopped when a sweep's row updates changed the
//!   rows' velocities by at most 10 tolerances while the whole sweep moved the bodies by less
//!   than one (the updates cancelling along a flat direction of a redundant contact set).
//!   Measured on the same states (each step taken twice), work −7 % to −45 % and no step
//!   dearer: wall-ball 600 steps 70.1M → 46.2M row updates, knife-wall 60.5M → 40.7M,
//!   bonded-wall-ball 145.9M → 111.6M, wall 34.6M → 19.2M, dominoes16 1500 9.98M → 9.28M.
//!   Switched off because it stops at rest too, where a brick may keep a velocity of the
//!   band's order (1e-9 m/s): lesson 41's claim that every brick lies still at 2.8 s failed
//!   and its walk snapshot moved. Next, if tried again: apply it only in steps where something
//!   moves, or end a stall by moving the impulses along the flat direction to their bound.
//!
//! The three above were removed in the commit "impulse: delete the remaining switched-off
//! paths"; the code is at bd48987 (`INTERIOR_NORMALS`, `MEDIAN_BUDGET` in
//! `src/physics/collision/impulse/mod.rs`, `budget.rs`, `stall.rs`; `World::set_median_budget`,
//! `World::set_stall_band`; `contact_steps`' `CONTACT_STEPS_BUDGET`, `CONTACT_STEPS_STALL`
//! and `CONTACT_STEPS_SHADOW`). The joints' large clusters in the direct solves alone:
//! [`joined`]'s module doc.
//!
//! Tried on 2026-12-07 and not committed, or committed restricted (issue 35, item 3; each
//! measured on `contact_steps`, work in row updates, deterministic; the first on top of the
//! search's cost counted whole, `subspace::sweeps_cheaper`, the others against 8ec18cf's
//! solver):
//!
//! - **No search again after one that raised the residual** on every stage (today limited
//!   to stages of [`SWEEPS_FIRST_ROWS`] rows or more: [`subspace::RAISED_SWEEPS`]). The
//!   trace it came from: dominoes16's dearest step (535, 62 rows, 952 sweeps, 620
//!   factorisations) ran 119 bursts ending at 1–3e-9 m/s (halving every 4 sweeps), each
//!   followed by a search of 2 to 8 rounds, lowering F but leaving the sweeps at 3–10e-9
//!   m/s; later in the same step the sweeps stall at 2.4e-10 m/s (the tolerance is 1e-10)
//!   and every search throws them back to 1e-8. Measured unrestricted (total; worst ÷
//!   median; unconverged): dominoes 3000 5.59M ×268 2 → 5.33M ×112 3; dominoes16 1500
//!   10.48M ×70.9 0 → 10.64M ×58.8 1; wall-ball 200 46.8M ×28.2 45 → 42.7M ×15.5 45;
//!   knife-wall 200 29.1M 8 → 28.4M 9; knife-wall-ball 100 7.47M 24 → 7.03M 20;
//!   bonded-wall-ball 100 44.6M 55 → 41.8M 60; wall 600 the same. Not kept unrestricted:
//!   it moved lesson 37's claim "rises after the landing" to 1.306e-3 (claimed 1.145e-3 ±
//!   5e-5). From 32 rows (2026-12-07, on top of the 64-row rule): dominoes16 9.81M ×70.9 0
//!   → 10.64M ×58.8 1, knife-wall-ball 7.47M → 7.03M (worst ×10.8 → ×17.0), dominoes 3000
//!   5.59M → 5.78M: not kept.
//! - **The whole projected step first in the friction search** (as stage 1 does): dominoes16
//!   10.19M, 0 unconverged → 14.59M, 33. **Searches every 4 or 16 sweeps** instead of
//!   [`SUBSPACE_EVERY`] = 8: dominoes16 9.0M and 11.8M, but wall-ball 200 245M at 4.
//!   **[`SUBSPACE_ROUNDS`] 2 or 32**: dominoes16 10.6M (4 unconverged) and 10.8M (worst ×185).
//!   **[`EDGE_TURN`] 1 or 0.1**: 11.3M and 9.8M. **A search from the warm start before any
//!   sweep** (the warm active set): every search needed its 8 rounds, one disk pinned per
//!   round, and the median step rose 3808 → 6292. **Pinning every disk and normal the ratio
//!   test would stop within 1e-3 or 1e-2 of the step** (several active-set changes a round):
//!   dominoes16 10.75M and 14.6M. The dominoes are chaotic, so a single run's total moves by
//!   ±5 % with any change of path; none of these is the different method item 3 asks for.
//!
//! **The median step of 16 dominoes** (2026-12-07, after [`WARM_NORMALS_ROWS`]: 3 900 row
//! updates, 62 rows; callgrind over steps 300–400, before it, 2.37M instructions a step):
//! stage 1's direct solve (0.10M); stage 2's two direct sticking solves, both declined
//! (0.69M, 29 %: 186 unknowns, 1 443 stored entries, each about 1 700 row updates'
//! worth of instructions against the 416 its estimate counts); the first burst of 8
//! sweeps; the interior point, 3 iterations (0.99M, 42 %: about 300 000 instructions an
//! iteration, 24 sweeps' worth, against the 460 row updates its estimate counts); then 1
//! to 9 sweeps and at most one search. Tried against it and not kept (work as above; total,
//! median, worst ÷ median): the interior point skipped when the burst's sweeps reach the
//! tolerance within 16, 32 or 64 more sweeps at their rate ([`INTERIOR_SKIP`] is 8), with
//! last step's normals on every stage (a pushing normal that pushed nothing last step set
//! to 0): dominoes16 7.18M 3 868 ×47 (8) → 7.24M 3 793 ×74
//! (16), 6.77M 2 758 ×142 (32), 7.23M 2 343 ×158 (64); knife-wall-ball 6.98M → 14.0M at 32.
//! The median falls by up to 40 % but the dear steps grow: the sweeps' rate after 8 sweeps
//! does not hold. **The direct sticking solves skipped after they declined** (on a stage
//! of [`WARM_NORMALS_ROWS`] rows or more, a wait doubled at each decline up to
//! [`TRIAL_WAIT_MAX`] steps, as stage 1's trial): dominoes16 7.24M, median 3 897, ×36.5 →
//! 6.99M, 3 029, ×106.5; knife-wall 25.5M ×28.6 → 22.7M ×36.9; wall-ball 42.7M → 41.8M;
//! knife-wall-ball 7.00M → 6.78M; bonded-wall-ball 41.8M → 44.3M: the median falls 22 %,
//! the dearest steps grow (a stage whose contacts stop sliding left to the sweeps), not
//! kept (not run through the claims tests). **The sticking solve with [`joined`]'s modes**
//! on the contacts alone (2026-12-07: after the exact sticking solve declined, up to 8 or 24
//! rounds of `direct::sticking` with `modes`, a contact outside its disk sliding at its bound
//! against its slip, one that would pull separating): every scene dearer, as on the landing
//! chain ([`joined`]'s module doc: the slide directions' fixed point does not settle). Total
//! work, off → 8 rounds → 24: dominoes16 1500 7.24M → 11.99M → 21.51M, dominoes 3000 5.59M →
//! 7.22M → 10.49M, wall-ball 100 19.41M → 26.96M → 42.05M, knife-wall 100 11.29M → 19.80M →
//! 36.84M. **The second sticking try skipped** when the first declined with some pair of
//! bodies' tangent impulses adding up to more than all its contacts' disks together (so no
//! sharing of them could fit): on 16 dominoes and the hit walls the second try never
//! answers after the first declined (1 213 of 1 213 declines; wall-ball 191 of 191), but in
//! 8 dominoes it answers 1 853 of 2 711, and the test is no predictor there (a domino
//! leaning on its neighbour and on the ground shares its friction between the two pairs
//! differently under the second try's weights): dominoes 3000 5.59M → 12.47M, wall 600
//! 19.9M → 29.9M, 16 dominoes 7.24M → 6.68M. A declined try also spends the step's budget,
//! so skipping one moves later paths even where it would have declined. What would cut the
//! median step: a sticking solve that does not decline where a few contacts slide and
//! converges where the modes do not (one wrench row set per face, or skip it when last
//! step's stage slid), and an interior-point iteration that costs what its estimate says.
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
//! the condition `u_n ≥ −g/dt`: it may close its gap within the next step, no more. In every
//! stage it is a normal row with a bias g/dt ([`normal`]: its update, and why K still never
//! rises). One that received no impulse is dropped from the reported contacts.
//!
//! # Positions
//!
//! After the velocities, `position` moves the bodies: a body that did not bounce advances from
//! where it was at the start of the step with its *corrected* velocity (no creep at rest, on a
//! slope or on a sphere), and what penetration is left is removed by translation (see there).

pub mod body_space;
pub mod direct;
pub mod friction;
pub mod interior;
pub mod joined;
pub mod normal;
pub mod particle;
pub mod propagate;
pub mod subspace;

use super::contacts;
use super::position::{self, Fix};
use super::response::Descriptor;
use super::solver_body::{Axis, SolverBody};
use super::warm::WarmCache;
use super::{CollideInput, Contact, EnergyChange};
use crate::physics::constraints;
use crate::physics::derive::derive;
use crate::physics::energy::{kinetic_energy_with, Energy};
use crate::physics::envelope::Envelope;
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

pub use super::step_context::BOUNCE_STEPS;
pub use direct::{DIRECT_MAX, PIVOT_ROUNDS, RESTING_GAP, STICKING_MAX};
pub(super) use friction::tangents;
pub use normal::GAP_ROUND_OFF;
pub use particle::particle;
pub use propagate::{Impacts, IMPACT_ROUNDS};
pub use subspace::{
    EDGE_TURN, NORMAL_SUBSPACE_MAX, SUBSPACE_BACKTRACKS, SUBSPACE_EVERY, SUBSPACE_ROUNDS,
};

/// The sweeps stop when no impulse changed a contact velocity by more than this (m/s), plus the
/// same fraction of the fastest approach speed.
pub const TOLERANCE: f64 = 1e-10;

/// At most this many Gauss–Seidel sweeps per stage. A stack of 10 cubes needs about 800 the
/// first time it is loaded, then 1 to 10 a step from the warm start; a cap below the first
/// number would leave every later step unconverged too.
pub const MAX_SWEEPS: usize = 2000;

/// Largest envelope (stored entries of [`Envelope`], 8 bytes each) the direct solves take on;
/// beyond it the sweeps run. A stack of 40 (banded) stays far below it; a pyramid of 20 rows,
/// whose rows in contact order reach back over a whole row of cubes, stores about 250 000
/// while it settles (about 5 ms a factorisation, against seconds of capped sweeps).
pub const ENVELOPE_MAX: usize = 1 << 20;

/// A friction stage of at least this many rows whose direct solves declined starts its
/// sweeps from last step's normal impulses (`friction::warm_normals`), unless it is large
/// and wide (its trial sweeps already started from them and failed).
///
/// Measured (issue 35, 2026-12-07, work in row updates, deterministic; total, worst after
/// the first step ÷ median, unconverged): on 16 dominoes the first burst of the sweeps from
/// stage 1's normals ended at about 1.3e-4 m/s, from last step's at about 3e-6 m/s, and the
/// sweeps after the interior point then need one sweep instead of 8 and a search:
/// dominoes16 1500 9.81M ×70.9 0 → 7.24M ×36.5 0; knife-wall 200 28.36M ×25.8 9 →
/// 25.55M ×28.6 9; knife-wall-ball 100 7.47M ×10.8 24 → 7.00M ×11.6 26; wall-ball,
/// bonded-wall-ball (large and wide) and dominoes (36 rows) the same. For every stage
/// (no row limit): dominoes 3000 5.59M ×268 → 4.34M ×87, but lesson 37's claim "rises after
/// the landing" read 0.709e-3 J against 1.145e-3 ± 5e-5 and lesson 15's walk snapshot moved
/// (the corners' shares of a face's load); with the large and wide stages too: wall-ball
/// 42.7M → 64.5M (69 unconverged against 45). Lesson 41's walk snapshot moves: its
/// predicted P_z at 2.8 s (a knocked wall's chaotic fall) 232.531014 → 232.494780 kg·m/s.
pub const WARM_NORMALS_ROWS: usize = 48;

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
/// tried instead (a scene at rest needs 1 or 2), unless their rate of convergence says they
/// reach the tolerance for less than the direct solve would cost (`trial_sweeps`).
pub const TRIAL_SWEEPS: u64 = 8;

/// The longest wait, in steps, between stage-1 trials that keep failing.
pub const TRIAL_WAIT_MAX: u32 = 32;

/// The largest work budget of one step, in sweeps over its rows: the sweeps, subspace steps
/// and pivot rounds of all stages together may do at most `WORK_BUDGET · rows` row updates
/// (one sweep over the rows costs `rows`, a factorisation its estimate `factorisation_work`;
/// each checks the budget before it starts, so a step overshoots by one at most). A step
/// that spends it, or whose sweeps reach their cap ([`MAX_SWEEPS`]), stops where it is —
/// every impulse still in its bounds (λ ≥ 0, |λ_t| ≤ μ λ), so K still only went down — and
/// says so: its [`StepReport`] carries the residual, the loop strip and `tumble walk`'s
/// contact panel show it, [`Counters::unconverged`] counts it. Never silent.
///
/// Measured (issue 35): the bonded wall knocked down by the ball, its bricks tumbling on
/// each other, ran each stage to its cap with subspace steps between, 0.1 to 1.7 s a step.
/// A budget of 1000 sweeps held it to 5–12 ms a step, 2000 (with this estimate of a
/// factorisation) to 35–70 ms; but either also cut the dominoes' sliding steps (84 of 3000
/// unconverged) and moved lesson 37's claim "rises after the landing" from 0.00163 to
/// 0.00100–0.00132 m. Relative to a running median of the scene's steps (16×) it did the
/// same, and cost the dominoes 11 % more instructions in all (a cut step's warm start is
/// worse for the next). So the budget is set where no bundled lesson nor scaling scene meets
/// it: it bounds the worst step rather than making a tumbling wall cheap (that needs a better
/// friction method: issue 35, item 3). Since the interior point ([`INTERIOR_STAGES`]) the
/// dominoes' median step is 993 row updates and its dearest 265 689; a budget of 20
/// medians cuts it, and does harm (module doc, *Tried and removed*).
pub const WORK_BUDGET: u64 = 20_000;

/// The sweeps a stage runs even when the budget is spent (the last stage of a step always
/// gets some work done).
pub const BUDGET_FLOOR: u64 = 8;

/// The work of one factorisation of `m` unknowns whose envelope stores `stored` entries, in
/// row updates (a friction sweep's row update is about 200 instructions): filling it (a
/// coupling an entry, about a quarter of a row update) plus the factorisation's
/// `Σ width²/2 ≈ stored²/2m` multiply–adds at about 100 to a row update.
#[inline]
pub(super) fn factorisation_work(stored: usize, m: usize) -> u64 {
    let (stored, m) = (stored as u64, m.max(1) as u64);
    stored / 4 + stored * stored / (200 * m)
}

/// What the solver did in the last step: its work, and whether it stopped at its budget
/// ([`WORK_BUDGET`]) or its caps before converging.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepReport {
    /// The work done, in row updates (sweeps × rows, factorisations by their estimate).
    pub work: u64,
    /// The rows (contacts) solved.
    pub rows: usize,
    /// The step's work budget, in row updates ([`WORK_BUDGET`] · rows).
    pub budget: u64,
    /// `Some(residual)` when a stage stopped unconverged: the largest change of a contact
    /// velocity its last sweep made, m/s (converged means below [`TOLERANCE`], 1e-10 m/s,
    /// plus the same fraction of the fastest approach).
    pub unconverged: Option<f64>,
}

/// Whether stage 2 (friction), when its direct solves declined and the sweeps' first burst
/// ([`SUBSPACE_EVERY`] sweeps, as `subspace::sweep` starts) did not converge, starts the
/// sweeps that follow from a primal–dual interior-point solve in body space ([`interior`],
/// where ADMM and semismooth Newton were tried: module doc, *Tried and removed*). It finds
/// the active set of all contacts at once, where Newton's line search met them one at a
/// time. A step whose first burst converges is bit
/// for bit as without it.
///
/// Measured (issue 35, 2026-12-06, one binary, this machine under load; CPU µs per step,
/// then the work per step in row updates, deterministic: median, worst ÷ median, and the
/// steps that stopped unconverged at the work budget):
///
/// | scene, steps | off | on |
/// |---|---|---|
/// | dominoes, 3000 | 168 µs; 1027, ×181, 5 | 98 µs; 1027, ×83, 2 |
/// | dominoes16, 3000 | 1113 µs; 2432, ×239, 10 | 338 µs; 2976, ×119, 0 |
/// | wall, 600 | 2669 µs; 1776, ×841, 0 | 3343 µs; 1776, ×2775, 0 |
/// | wall-ball, 600 | 20.6 ms; 476 263, ×10.2, 299 | 5.4 ms; 29 037, ×76, 59 |
/// | bonded-wall-ball, 600 | 74.7 ms; 1 853 379, ×3.6, 568 | 17.1 ms; 76 220, ×39, 187 |
/// | knife-wall, 600 | 107 ms; 2 562 799, ×1.0, 521 | 8.2 ms; 96 295, ×28, 23 |
///
/// stack-40 and pyramid-20 never reach it (their direct solves answer): the same work, and
/// the stack-10 and pyramid-10 md5s are unchanged. The walls' worst steps cost 2–2.5× less
/// work (the `wall`'s one worst step 3.3× more); their ratios grow because the median
/// falls 16–27×. Running it without the burst first (every declined stage 2) was a little
/// faster on the dominoes (70 and 281 µs, ×78 and ×55) but left lesson 41's wall moving at
/// 2.8 s (c2b1 pushed along by the ball), lesson 37's hit of d5 one step late and the row's
/// last domino 11.5 mm up. **On** since 2026-12-06 (committed form: after the burst). Three
/// numbers moved, each by what a chaotic fall or a non-unique load split allows:
///
/// - lesson 37's "rises after the landing" reads 1.31e-3 J (1.63e-3 before): the position
///   step lifts the leaning row less; the page now quotes 1.3e-3 J;
/// - lesson 15's walk snapshot moves by round-off: the stack's tangential contact force
///   8e-11 → 1.3e-8 N (of a 10 N load), and the corners' shares of each face's load (not
///   unique on four coplanar corners) differ;
/// - the sliding block of `tests/app`'s energy bars drifted 5.9e-12 m sideways and turned
///   1.9e-11 rad (0 before: Coulomb's answer is straight); 0 again since sweeps about to
///   converge skip it ([`INTERIOR_SKIP`]);
/// - the dominoes md5 changes (4c55f4a0… → ace9e8b5…).
///
/// The sweeps converge from its answers to the same tolerance; where the answer is not
/// unique (redundant contacts) they end on another one, and a chaotic fall carries the
/// difference.
pub const INTERIOR_STAGES: bool = true;

/// The most sweeps the friction sweeps may still need, at the rate of the first burst's
/// second half, to go on without the interior-point start ([`INTERIOR_STAGES`]), as before
/// it: the subspace search right after the burst, then the sweeps. A block sliding on its
/// four corners needs this: every step of the energy bars' slide leaves its burst at
/// 1.3e-8 m/s, falling ×0.11 a sweep (2.2 more sweeps to 1e-10). Measured, the interior
/// point did not move it (the same digits with it skipped); what did was the search coming
/// 8 sweeps later, after a fresh burst: the sweeps then converge on their own to the
/// tolerance on a split of the four corners' load that is not quite symmetric (the slide
/// drifted 5.9e-12 m sideways and turned 1.9e-11 rad), where the search's direct solve
/// lands on the straight answer (0, bit for bit as before the interior point).
pub const INTERIOR_SKIP: f64 = 8.0;


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
    /// The impact rounds' buffers (`propagate`).
    impacts: propagate::Scratch,
    /// What the solver did since the world was built (the solver path, for tests).
    pub counters: Counters,
    /// What it did in the last step (its work, whether it converged).
    pub report: StepReport,
    /// The `soft-step` response's buffers (the world keeps one scratch for the collide phase).
    pub(super) soft: super::soft_step::Scratch,
    /// The joint rows solved with the contacts ([`joined`]), and the impulses they gave.
    pub joined: joined::Joined,
    joint_rows: Vec<crate::physics::constraints::Row>,
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
    /// This step's mean envelope of the rows in contact order (`direct::mean_envelope`; 0
    /// at or below [`SWEEPS_FIRST_ROWS`] rows).
    width: f64,
    /// The first row acting on each body (the envelope's estimate).
    body_first: Vec<usize>,
    /// The friction subspace step's unknowns, and the impulses before it (to undo it).
    unknowns: Vec<subspace::Unknown>,
    /// The disks an active-set search moved onto their edge (held there for its next rounds).
    pinned: Vec<usize>,
    /// The rows in the order the subspace step takes its unknowns.
    order: Vec<usize>,
    /// The inelastic direct solve's rows in system order: joint rows (< their count), then
    /// contact rows by their place in the active set (`direct::inelastic`).
    merged: Vec<usize>,
    /// The change of the joint rows' impulses a direct sticking solve with joints gave
    /// (`direct::sticking`).
    joint_delta: Vec<f64>,
    /// Per row, a sliding contact's direction in the direct sticking solve with joints
    /// (`direct::HeldJoints`).
    slides: Vec<direct::Hold>,
    subspace_rows: Vec<(f64, [f64; 2])>,
    /// The interior-point solve's buffers ([`INTERIOR_STAGES`]).
    interior: interior::Scratch,
    /// This step's work so far and its budget, in row updates ([`budget`]).
    work: u64,
    budget: u64,
    /// The last sweeps' residual (m/s), and this step's largest residual of a stage that
    /// stopped unconverged.
    residual: f64,
    unconverged: Option<f64>,
}

impl Direct {
    /// A new step's budget over `rows` rows: [`WORK_BUDGET`] sweeps over them.
    fn start(&mut self, rows: usize) {
        self.work = 0;
        self.residual = 0.0;
        self.unconverged = None;
        self.budget = WORK_BUDGET * rows as u64;
    }

    /// Whether this step's work budget is spent.
    fn spent(&self) -> bool {
        self.work >= self.budget
    }

    /// The sweeps a stage over `rows` rows may run now, at most `cap`: what the budget has
    /// left, but at least [`BUDGET_FLOOR`].
    fn sweeps_left(&self, rows: usize, cap: u64) -> u64 {
        let left = self.budget.saturating_sub(self.work) / rows.max(1) as u64;
        cap.min(left.max(BUDGET_FLOOR))
    }

    /// An interior-point solve ([`interior`]) from the rows' impulses, within what is left
    /// of the budget; its work is counted, and the solves it took and their iterations.
    fn interior(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        counters: &mut Counters,
    ) {
        let left = self.budget.saturating_sub(self.work);
        let outcome = interior::solve(
            rows,
            directions,
            motions,
            tolerance,
            left,
            &mut self.interior,
        );
        self.work += outcome.work;
        counters.interior_steps += outcome.steps as u64;
        if outcome.taken {
            counters.interior += 1;
        }
    }

    /// Stage 2 after its direct solves declined: the sweeps' first burst
    /// ([`SUBSPACE_EVERY`] sweeps, as `subspace::sweep` starts), and only if it did not
    /// converge an interior-point solve ([`Direct::interior`]) as the start of the sweeps
    /// that follow, unless the burst's sweeps are about to converge ([`converging`]): then
    /// they go on as without the interior point. True when the stage is done (converged, or
    /// the sweeps ran and noted an unconverged end).
    fn interior_after_burst(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        counters: &mut Counters,
    ) -> bool {
        // The burst in two halves (the same sweeps): the second half's fall of the residual
        // is the sweeps' rate of convergence.
        let burst = self.sweeps_left(rows.len(), SUBSPACE_EVERY);
        let half = burst / 2;
        let (mut converged, mut sweeps, first) =
            friction::sweep(rows, directions, motions, tolerance, half);
        let mut residual = first;
        if !converged {
            let more;
            (converged, more, residual) =
                friction::sweep(rows, directions, motions, tolerance, burst - half);
            sweeps += more;
        }
        self.work += sweeps * rows.len() as u64;
        self.residual = residual;
        counters.friction_sweeps += sweeps;
        if converged {
            return true;
        }
        if converging(first, residual, burst - half, tolerance) {
            // The sweeps go on as `subspace::sweep` after its first burst (bit for bit).
            let (converged, more, residual) = subspace::sweep_after(
                rows,
                directions,
                motions,
                tolerance,
                (&mut *self, &mut *counters),
                sweeps,
            );
            counters.friction_sweeps += more;
            if !converged {
                self.unconverged(residual);
            }
            return true;
        }
        self.interior(rows, directions, motions, tolerance, counters);
        false
    }

    /// Notes a stage that ended unconverged with `residual`.
    fn unconverged(&mut self, residual: f64) {
        self.unconverged = Some(self.unconverged.map_or(residual, |r| r.max(residual)));
    }
}


/// Whether sweeps whose residual fell from `first` to `last` over their last `sweeps` sweeps
/// reach `tolerance` within [`INTERIOR_SKIP`] more at that rate (linear convergence:
/// r_{k+n} = r_k ρⁿ, ρ = (last/first)^{1/sweeps}); then they go on without the
/// interior-point start (module doc of [`INTERIOR_STAGES`]).
fn converging(first: f64, last: f64, sweeps: u64, tolerance: f64) -> bool {
    if sweeps == 0 || last >= first || last <= 0.0 {
        return false;
    }
    let rate_log = (last / first).ln() / sweeps as f64;
    (tolerance / last).ln() / rate_log <= INTERIOR_SKIP
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
    /// see [`subspace`]).
    pub friction_subspace: u64,
    /// Subspace steps the normal sweeps of a large system took (stage 1: the same step with
    /// no friction unknowns).
    pub normal_subspace: u64,
    /// Impact rounds run (`propagate`), and steps whose rounds hit [`IMPACT_ROUNDS`] with a
    /// contact still approaching (the final simultaneous solve took the rest).
    pub impact_rounds: u64,
    pub impacts_unconverged: u64,
    /// Steps in which a stage stopped unconverged (its work budget spent, [`WORK_BUDGET`], or
    /// its sweeps' cap reached).
    pub unconverged: u64,
    /// Interior-point solves ([`interior`]) whose answer the stage took, and their
    /// iterations (factorisations in body space).
    pub interior: u64,
    pub interior_steps: u64,
    /// Stages 2 with joint rows that the direct sticking solve with them answered
    /// ([`joined`]).
    pub joined_sticking: u64,
}

/// The axis d at a contact: +d on A at its lever, −d on B at its own (B's solver body
/// `other`; a static one, a fixed body or an obstacle, is no end: [`Axis::new`]).
fn axis_at(d: Vector3<f64>, contact: &Contact, motions: &[SolverBody]) -> Axis {
    Axis::new(
        d,
        (contact.body, &contact.lever),
        Some((contact.other, &contact.lever_other)),
        motions,
    )
}

/// One contact as the solver sees it: its normal row on the constraint layer's [`Row`]
/// (λ ∈ [0, ∞), the bias gap/dt), its friction pair (the layer's [`Friction`]: two tangent
/// impulses bounded by the disk), and what the stages keep about it.
///
/// [`Row`]: constraints::Row
/// [`Friction`]: constraints::Friction
#[derive(Debug, Clone, Copy)]
struct Row {
    /// The normal row (`constraints::Row::contact`): unit normal n with its ends and k, the
    /// accumulated normal impulse λ ∈ [lo, hi] = [0, ∞) (N·s), and its bias b = gap/dt: the
    /// normal velocity the contact may keep is −b, so b ≥ 0 lets a speculative contact close
    /// its gap within the next step, no more (0 for a touching one), m/s.
    normal: constraints::Row,
    /// The friction pair (`constraints::Friction`): the accumulated tangent impulses along
    /// the two tangent axes (kept in stage 2's `tangents`), N·s, within the disk of radius
    /// μ λ from stage 1.
    friction: constraints::Friction,
    /// λ at the end of stage 1 (the frictionless compression impulse).
    compression: f64,
    /// Restitution impulse e λ (scaled by the energy clamp).
    lambda_restitution: f64,
    /// Normal velocity before the response, m/s.
    approach: f64,
    /// The last step's impulse at the same contact, if any (warm start of the sweeps).
    warm: Vector3<f64>,
}

impl Default for Row {
    /// A contact on the zero axis: touching (b = 0), no impulse.
    fn default() -> Row {
        Row {
            normal: constraints::Row::contact(Axis::default(), 0.0),
            friction: constraints::Friction::default(),
            compression: 0.0,
            lambda_restitution: 0.0,
            approach: 0.0,
            warm: Vector3::zeros(),
        }
    }
}

/// What the front ends say about `impulse` (`response`).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "impulse",
    summary: "impulses at every contact together, converged: restitution e, Coulomb friction μ, penetration removed by moving the body, speculative contacts within a step's reach",
    keeps: "never adds kinetic energy (a bounce pays for its lift); momentum between bodies; stacks stand to micrometres",
    brief: "impulses at every contact",
    formula: "uₙ = (v + ω×r)·n,  k = 1/M + n·((I⁻¹(r×n))×r),  j = −(1+e)·uₙ/k  (all contacts together, + friction)",
    formula_bodies: "uₙ = (v_A + ω_A×r_A − v_B − ω_B×r_B)·n,  k = Σ 1/M + (r×n)·I⁻¹(r×n),  j = −(1+e)·uₙ/k  on A, −j on B (all contacts together, + friction)",
    impulses: true,
    colour: (0, 0, 0),
    charted: true,
};

/// The collide phase under `impulse` (the entry point `responses!` calls): [`respond`].
pub fn collide(
    input: &CollideInput,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> Option<EnergyChange> {
    respond(input, states, contacts, scratch)
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
    let context = input.context;
    let bounce_speed = context.bounce_speed;
    // Points closer than this to a surface are speculative contacts (module doc).
    let margin = context.speculative_margin;
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
        scratch.report = StepReport::default();
        return None;
    }
    let motions = &mut scratch.motions;
    solver_bodies(input, states, motions);
    if contacts.iter().any(|c| c.depth <= 0.0) {
        // A point approaching at bouncing speed is left to touch and bounce next step.
        contacts.retain(|c| c.depth > 0.0 || relative_velocity(c, motions) >= -bounce_speed);
    }
    prepare_joints(input, states, contacts, bounce_speed, scratch);
    let motions = &scratch.motions;
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
            .context
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
        dt: context.dt,
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
        dt: context.dt,
        lift,
        impacts: input.model.impacts,
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
        impacts,
        report,
        joined,
        ..
    } = scratch;
    advanced.clear();
    advanced.resize(motions.len(), false);
    let buffers = Buffers {
        rows,
        tangents,
        motions,
        direct: &mut *direct,
        change,
        bounced: advanced,
        counters: &mut *counters,
        impacts,
        joined,
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
    *report = StepReport {
        work: direct.work,
        rows: contacts.len(),
        budget: direct.budget,
        unconverged: direct.unconverged,
    };
    if direct.unconverged.is_some() {
        counters.unconverged += 1;
    }
    scratch.joined.finish(motions); // the motors' work in it (`joined`)
    store_momenta(states, motions);
    mark_advanced(advanced, motions, contacts, &mut scratch.joined);
    fix.apply(contacts, states, advanced, fs);
    // Round-off guard: K is quadratic in (P, L), so scaling both by √(K₀/K) gives K₀.
    let allowed = (before.kinetic, scratch.joined.motor_work);
    let after = round_off_guard(allowed, states, motions, total);
    // Speculative contacts that were not needed are not contacts.
    let needed = |c: &Contact| c.depth > 0.0 || c.impulse != Vector3::zeros();
    if !contacts.iter().all(needed) {
        contacts.retain(needed);
    }
    Some(EnergyChange { before, after })
}

/// The solved velocities back into the touched bodies' momenta: P = v / m⁻¹, L.
fn store_momenta(states: &mut [State], motions: &[SolverBody]) {
    for (state, m) in states.iter_mut().zip(motions.iter()) {
        if m.touched {
            state.linear_momentum = m.v / m.inv_mass;
            state.angular_momentum = m.l;
        }
    }
}

/// The bodies advanced from the start of the step (the push-out moves only those): touched
/// and not bounced (`advanced` holds the bounce flags on entry), and with joint rows in use
/// only those a contact pushed.
fn mark_advanced(
    advanced: &mut [bool],
    motions: &[SolverBody],
    contacts: &[Contact],
    joined: &mut joined::Joined,
) {
    for (advance, m) in advanced.iter_mut().zip(motions.iter()) {
        *advance = m.touched && !*advance;
    }
    if joined.used {
        // A body only the joints' reactions moved keeps the integrator's position, as a
        // bounced one does (`joined`): it is not resting on anything.
        let mut pushed = std::mem::take(&mut joined.marked);
        pushed.clear();
        pushed.resize(advanced.len(), false);
        for c in contacts.iter().filter(|c| c.impulse != Vector3::zeros()) {
            pushed[c.body] = true;
            pushed[c.other] = true;
        }
        for (advance, pushed) in advanced.iter_mut().zip(&pushed) {
            *advance &= *pushed;
        }
        joined.marked = pushed;
    }
}

/// The joints' rows at `states`, solved with the contacts in an impact ([`joined`]; built
/// only then, or in a scene with motors: a later impact round follows a first one).
fn prepare_joints(
    input: &CollideInput,
    states: &[State],
    contacts: &[Contact],
    bounce_speed: f64,
    scratch: &mut Scratch,
) {
    let (joint_rows, motions) = (&mut scratch.joint_rows, &scratch.motions);
    joint_rows.clear();
    if let Some(rows_at) = input.joints {
        // In a scene with motors, at rest too (a motor pushing what it touches).
        if scratch.joined.scene_motored
            || contacts
                .iter()
                .any(|c| relative_velocity(c, motions) < -0.5 * bounce_speed)
        {
            rows_at(states, joint_rows);
        }
    }
    let joints = joint_rows.iter().map(|r| r.owner + 1).max().unwrap_or(0);
    scratch.joined.prepare(joint_rows, motions, joints);
}

/// The solver body table (`CollideInput::end`): every body's velocities, with I⁻¹_world
/// exactly as the derive phase (and the energy panel) computes it, then one static entry per
/// obstacle (1/M = 0, I⁻¹ = 0, at rest), so that a row reaches B the same way whatever B is.
fn solver_bodies(input: &CollideInput, states: &[State], motions: &mut Vec<SolverBody>) {
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
    motions.extend(input.obstacles.iter().map(|_| SolverBody::fixed_thing()));
}

/// The round-off guard (module doc): K is quadratic in (P, L), so scaling the touched
/// bodies' P and L by √(K₀/K) gives K₀ (K₀ with the motors' work in the response added,
/// when positive: `joined`); at most 4 times. Returns the energy after.
fn round_off_guard(
    (kinetic_before, motor_work): (f64, f64),
    states: &mut [State],
    motions: &[SolverBody],
    total: impl Fn(&[State], &[SolverBody]) -> Energy,
) -> Energy {
    // K₀ with the motors' work in the response (they push; the contacts never give).
    let kinetic_before = if motor_work > 0.0 {
        kinetic_before + motor_work
    } else {
        kinetic_before
    };
    let mut after = total(states, motions);
    for _ in 0..4 {
        if after.kinetic <= kinetic_before {
            break;
        }
        let scale = (kinetic_before / after.kinetic).sqrt() * (1.0 - 4.0 * f64::EPSILON);
        for (state, m) in states.iter_mut().zip(motions.iter()) {
            if m.touched {
                state.linear_momentum *= scale;
                state.angular_momentum *= scale;
            }
        }
        after = total(states, motions);
    }
    after
}

/// The relative velocity of a contact point along its normal (A relative to B; a static B,
/// at rest, subtracts exact zeros).
fn relative_velocity(c: &Contact, motions: &[SolverBody]) -> f64 {
    let (a, b) = (&motions[c.body], &motions[c.other]);
    let u = a.v + a.omega.cross(&c.lever) - (b.v + b.omega.cross(&c.lever_other));
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
    impacts: &'a mut propagate::Scratch,
    joined: &'a mut joined::Joined,
}

/// What the stages work on besides the rows and contacts (the bodies and the buffers).
pub(super) struct Stage<'a> {
    tangents: &'a mut Vec<[Axis; 2]>,
    motions: &'a mut [SolverBody],
    direct: &'a mut Direct,
    change: &'a mut Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    bounced: &'a mut [bool],
    counters: &'a mut Counters,
    /// The joint rows solved with the contacts ([`joined`]).
    joined: &'a mut joined::Joined,
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
    /// The impact law (`propagate`).
    impacts: Impacts,
}

/// The velocity stages (module doc) for `contacts` (point, depth, normal and levers filled
/// in), after the impact rounds when the law is `propagate` ([`propagate`]); fills in each
/// contact's normal velocity, denominator and impulse, and the motions.
fn resolve(settings: &Settings, contacts: &mut [Contact], previous: &WarmCache, buffers: Buffers) {
    let Buffers {
        rows,
        tangents,
        motions,
        direct,
        change,
        bounced,
        counters,
        impacts,
        joined,
    } = buffers;
    // The energy the velocities may keep: K₀ less the push-out's work against gravity.
    let kinetic_allowed = motions.iter().map(SolverBody::kinetic).sum::<f64>() - settings.lift;
    let prepare = |rows: &mut Vec<Row>, motions: &[SolverBody]| {
        rows.clear();
        rows.extend(
            contacts
                .iter()
                .map(|c| normal::prepare(c, previous, settings.dt, motions)),
        );
        let fastest = rows.iter().map(|r| -r.approach).fold(0.0, f64::max);
        TOLERANCE * (1.0 + fastest)
    };
    let tolerance = prepare(rows, motions);
    // This step's work budget (the impact rounds and the resting solve share it).
    direct.start(rows.len());
    let mut stage = Stage {
        tangents,
        motions,
        direct,
        change,
        bounced,
        counters,
        joined,
    };
    // Propagate: the impact rounds first, when something approaches faster than a resting
    // contact does (at e = 0 they are skipped: module doc of `propagate`).
    let threshold = settings.bounce_speed.max(tolerance);
    if settings.impacts == Impacts::Propagate
        && settings.restitution > 0.0
        && rows.iter().any(|r| r.approach + r.normal.bias < -threshold)
    {
        let bounds = propagate::Bounds {
            threshold,
            tolerance,
            kinetic_allowed,
        };
        propagate::rounds(
            settings, contacts, rows, previous, bounds, &mut stage, impacts,
        );
        // Then resting contact: every row at once, from the velocities the rounds left.
        let tolerance = prepare(rows, stage.motions);
        let left = stage.motions.iter().map(SolverBody::kinetic).sum::<f64>();
        stages(
            settings,
            rows,
            contacts,
            tolerance,
            kinetic_allowed.min(left),
            &mut stage,
        );
        normal::store(contacts, rows);
        friction::store(contacts, rows, stage.tangents);
        propagate::add(contacts, &impacts.records);
        return;
    }
    stages(
        settings,
        rows,
        contacts,
        tolerance,
        kinetic_allowed,
        &mut stage,
    );
    // Store: the impulses into the contacts (normal, then the tangents when stage 2 ran).
    normal::store(contacts, rows);
    friction::store(contacts, rows, stage.tangents);
}

/// Stages 1 to 3 (module doc) on `rows` (prepared from `contacts`, the same order), with
/// the sweeps' `tolerance` and the kinetic energy the velocities may keep; the joint rows
/// of the clusters the contacts touch in an impact ([`select_joints`]) solved with them.
fn stages(
    settings: &Settings,
    rows: &mut [Row],
    contacts: &[Contact],
    tolerance: f64,
    kinetic_allowed: f64,
    stage: &mut Stage,
) {
    select_joints(rows, settings.friction, settings.bounce_speed, stage.joined);
    stage.joined.mark_stage(stage.motions);
    // Stage 1: inelastic normal impulses, λ ≥ 0.
    let large = inelastic(rows, tolerance, stage);
    // Stage 2: friction in the fixed disks |λ_t| ≤ μ λ, normal impulses still kept ≥ 0.
    // Skipped when no pushing contact slides (a body at rest): there is nothing to do.
    friction_stage(settings, rows, contacts, tolerance, large, stage);

    // Stage 3: Poisson restitution e λ where the approach was fast, scaled so that K ≤ K₀
    // (with the joints' reaction to it, when there are joint rows), K₀ with what the motors
    // gave in this stage.
    let motors = stage.joined.stage_work(stage.motions);
    let bounce = normal::Bounce {
        restitution: settings.restitution,
        bounce_speed: settings.bounce_speed,
        kinetic_allowed: if motors > 0.0 {
            kinetic_allowed + motors
        } else {
            kinetic_allowed
        },
    };
    let Stage {
        motions,
        change,
        bounced,
        joined,
        ..
    } = stage;
    bounce_stage(rows, motions, bounce, change, bounced, joined);
}

/// Stage 1 ([`inelastic_stage`] within its budget), each row's compression kept; returns
/// whether the system is large and wide.
#[inline(always)]
fn inelastic(rows: &mut [Row], tolerance: f64, stage: &mut Stage) -> bool {
    let large = inelastic_stage(
        rows,
        stage.motions,
        tolerance,
        stage.direct,
        stage.counters,
        stage.joined,
    );
    for row in rows.iter_mut() {
        row.compression = row.normal.lambda;
    }
    large
}

/// Stage 2 (module doc) when μ > 0 and some pushing contact slides: with the joint rows held
/// in stage 1, the direct sticking solve with them, then the joints' friction sweeps
/// ([`joined`]); else a large wide system's trial sweeps, the direct sticking solve, the
/// sweeps.
fn friction_stage(
    settings: &Settings,
    rows: &mut [Row],
    contacts: &[Contact],
    tolerance: f64,
    large: bool,
    stage: &mut Stage,
) {
    let Stage {
        tangents: tangent_directions,
        motions,
        direct: buffers_direct,
        counters,
        joined,
        ..
    } = stage;
    let motions: &mut [SolverBody] = motions;
    let buffers_direct: &mut Direct = buffers_direct;
    let counters: &mut Counters = counters;
    let (friction, dt) = (settings.friction, settings.dt);
    tangent_directions.clear();
    if friction == 0.0
        || !rows
            .iter()
            .zip(contacts.iter())
            .any(|(r, c)| friction::sliding(r, c, motions, tolerance))
    {
        return;
    }
    tangent_directions.extend(
        rows.iter_mut()
            .zip(contacts.iter())
            .map(|(row, contact)| friction::prepare(row, contact, friction, motions)),
    );
    // With the joint rows held in stage 1: everything sticking, solved directly with them;
    // else the joints' friction stage ([`joined`]).
    let mut solved = false;
    if joined.held {
        for how in [direct::Sticking::Exact, direct::Sticking::Resting { dt }] {
            if !solved {
                solved =
                    joined.sticking(rows, tangent_directions, motions, tolerance, how, buffers_direct);
                if solved {
                    counters.friction_direct += 1;
                    counters.joined_sticking += 1;
                }
            }
        }
        solved = solved
            || joined_friction(
                rows,
                tangent_directions,
                motions,
                tolerance,
                (&mut *buffers_direct, &mut *counters),
                joined,
            );
    }
    // A large system: a few sweeps from the last step's impulses first (at rest or
    // sliding steadily they are the answer). Then the direct solve (everything sticks);
    // else the sweeps, warm-started from the last step's friction impulses (kept in their
    // disks).
    solved = solved
        || large
            && friction_trial(
                rows,
                tangent_directions,
                motions,
                tolerance,
                buffers_direct,
                counters,
            );
    for how in [direct::Sticking::Exact, direct::Sticking::Resting { dt }] {
        if !solved {
            solved = direct::sticking(
                rows,
                tangent_directions,
                direct::HeldJoints::NONE,
                motions,
                tolerance,
                how,
                buffers_direct,
            ) == direct::Answer::Accepted;
            if solved {
                counters.friction_direct += 1;
            }
        }
    }
    if !solved {
        if !large && rows.len() >= WARM_NORMALS_ROWS {
            // A large system's trial already started from last step's normals.
            friction::warm_normals(rows, motions);
        }
        friction::warm_start(rows, tangent_directions, motions);
        if INTERIOR_STAGES {
            solved = buffers_direct.interior_after_burst(
                rows,
                tangent_directions,
                motions,
                tolerance,
                counters,
            );
        }
    }
    if !solved {
        let (converged, sweeps, residual) = subspace::sweep(
            rows,
            tangent_directions,
            motions,
            tolerance,
            buffers_direct,
            counters,
        );
        if !converged {
            buffers_direct.unconverged(residual);
        }
        counters.friction_sweeps += sweeps;
    }
}

/// The joint rows of the clusters `rows` touch, in an impact (none without joints); at rest
/// only those of the clusters with a motor (the motor solved with the contacts it pushes:
/// [`joined`]), none in a scene without motors. With friction, more than the joints' friction sweeps take (more than
/// [`joined::JOINED_FRICTION_ROWS`] rows or [`joined::JOINED_FRICTION_CONTACTS`] contacts):
/// none; `joints::contact::hold` then holds the joints after the response.
fn select_joints(rows: &[Row], friction: f64, bounce_speed: f64, joined: &mut joined::Joined) {
    // A response without joint rows selects none (no scan of the rows).
    let impact = joined.has_rows() && rows.iter().any(|r| r.approach < -bounce_speed);
    if impact || joined.scene_motored {
        let most = if friction == 0.0 {
            usize::MAX
        } else if rows.len() > joined::JOINED_FRICTION_CONTACTS {
            0
        } else {
            joined::JOINED_FRICTION_ROWS
        };
        joined.select(
            rows.iter()
                .flat_map(|r| r.normal.axis.bodies().into_iter().flatten()),
            most,
            !impact,
        );
    } else {
        // At rest: the contacts' rows alone (also after `propagate`'s impact rounds, whose
        // last round's selection would otherwise stay).
        joined.select(std::iter::empty(), 0, false);
    }
}

/// Stage 2 with the joint rows held ([`joined::Joined::friction`]), within the step's budget;
/// false (nothing changed) when the joints' system gives no factor.
fn joined_friction(
    rows: &mut [Row],
    tangent_directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    (buffers_direct, counters): (&mut Direct, &mut Counters),
    joined: &mut joined::Joined,
) -> bool {
    let cap = buffers_direct.sweeps_left(rows.len(), MAX_SWEEPS as u64);
    let Some((converged, sweeps, residual, work)) =
        joined.friction(rows, tangent_directions, motions, tolerance, cap)
    else {
        return false;
    };
    buffers_direct.work += work;
    counters.friction_sweeps += sweeps;
    if !converged {
        buffers_direct.unconverged(residual);
    }
    true
}

/// Stage 2's trial on a large system: a few friction sweeps from the last step's normal and
/// friction impulses (at rest or sliding steadily they are the answer). True when they
/// converged; else the bodies and the rows are put back as they were.
fn friction_trial(
    rows: &mut [Row],
    tangent_directions: &[[Axis; 2]],
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers_direct: &mut Direct,
    counters: &mut Counters,
) -> bool {
        let width = buffers_direct.width;
        let Direct {
            trial,
            trial_rows,
            work,
            ..
        } = &mut *buffers_direct;
        trial.clear();
        trial.extend_from_slice(motions);
        trial_rows.clear();
        trial_rows.extend(rows.iter().map(|r| (r.normal.lambda, r.friction.lambda)));
        // From last step's normal impulses as well as its friction: stage 1's answer,
        // when its direct solve gave it, shares the loads its own way (the minimum norm),
        // and at rest last step's friction holds last step's shares, not those (a pyramid
        // of 20 rows standing past 3.25 s: its sweeps then hit their cap on every step).
        normal::warm_start_again(rows, motions);
        friction::warm_start(rows, tangent_directions, motions);
        let cap = trial_cap(rows.len(), width, 3);
        let (converged, sweeps) = trial_sweeps(cap, tolerance, |n| {
            friction::sweep(rows, tangent_directions, motions, tolerance, n)
        });
        *work += sweeps * rows.len() as u64;
        counters.friction_sweeps += sweeps;
        if converged {
            counters.friction_warm += 1;
        } else {
            motions.copy_from_slice(trial);
            for (row, &(lambda, tangent)) in rows.iter_mut().zip(trial_rows.iter()) {
                row.normal.lambda = lambda;
                row.friction.lambda = tangent;
            }
        }
        converged
}

/// The most sweeps a large system's trial may run: [`TRIAL_SWEEPS`], or more when one
/// factorisation of the direct solve that follows a failed trial costs more. Its system has
/// `unknowns` unknowns per row (1 in stage 1, 3 in the sticking solve) and a mean envelope of
/// `width` rows (`direct::mean_envelope`), so it stores about `unknowns² · width · rows`
/// entries and costs `factorisation_work` of that; the cap is that work over one sweep's
/// `rows` row updates. A direct solve takes one factorisation per round of its active-set
/// search (the resting wall's 5 to 9), so sweeps within the cap never cost more than it.
fn trial_cap(rows: usize, width: f64, unknowns: usize) -> u64 {
    let stored = (width * (unknowns * unknowns * rows) as f64) as usize;
    let factorisation = factorisation_work(stored, unknowns * rows);
    (factorisation / rows.max(1) as u64).max(TRIAL_SWEEPS)
}

/// The sweeps still needed to bring a residual from `last` to `tolerance` at the rate at
/// which the last `sweeps` sweeps brought it from `first` to `last` (linear convergence,
/// r_{k+n} = r_k ρⁿ: n = ln(tolerance / last) / ln ρ, ρ = (last/first)^{1/sweeps});
/// infinite when the residual did not fall.
fn sweeps_needed(first: f64, last: f64, sweeps: u64, tolerance: f64) -> f64 {
    if sweeps == 0 || last >= first || last <= 0.0 {
        return f64::INFINITY;
    }
    let rate_log = (last / first).ln() / sweeps as f64;
    ((tolerance / last).ln() / rate_log).max(0.0)
}

/// A large system's trial sweeps (`sweep(n)` runs at most n sweeps: converged, sweeps run,
/// residual), in bursts of half [`TRIAL_SWEEPS`]; after the first [`TRIAL_SWEEPS`] they go
/// on only while the last burst's rate of convergence ([`sweeps_needed`]) reaches the
/// tolerance within `cap` sweeps in all ([`trial_cap`]). With `cap` = [`TRIAL_SWEEPS`] they
/// are the fixed trial of [`TRIAL_SWEEPS`] sweeps, bit for bit (a sweep keeps nothing
/// between calls). The wall at rest whose top end bricks start to topple (`contact_steps
/// wall`, steps 343 to 385) needs 9 to 21 in stage 1 (its residual falls ×0.55 a sweep
/// from 4e-9 m/s), where each failed trial of 8 was followed by a direct solve of 6 to 9
/// factorisations (about 35 000 row updates, 60 times the scene's median step). Returns
/// whether they converged, and the sweeps run.
fn trial_sweeps(
    cap: u64,
    tolerance: f64,
    mut sweep: impl FnMut(u64) -> (bool, u64, f64),
) -> (bool, u64) {
    let burst = TRIAL_SWEEPS / 2;
    let (mut converged, mut sweeps, mut residual) = sweep(burst);
    while !converged && sweeps < cap {
        let first = residual;
        let more;
        (converged, more, residual) = sweep(burst.min(cap - sweeps));
        sweeps += more;
        if !converged
            && sweeps >= TRIAL_SWEEPS
            && sweeps as f64 + sweeps_needed(first, residual, more, tolerance) > cap as f64
        {
            break;
        }
    }
    (converged, sweeps)
}

/// Stage 3 ([`normal::restitution`]), the joints' reaction to it booked ([`joined`]).
fn bounce_stage(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    bounce: normal::Bounce,
    change: &mut Vec<(Vector3<f64>, Vector3<f64>, Vector3<f64>)>,
    bounced: &mut [bool],
    joined: &mut joined::Joined,
) {
    // With stops or motors taken in stage 1, their bounds kept (`joined::bounds`).
    let joints = (!joined.axes.is_empty() || joined.bounded()).then_some(&mut *joined);
    if let Some(scale) = normal::restitution(rows, motions, bounce, change, bounced, joints) {
        joined.book_bounce(scale);
    }
}

/// Stage 1 (module doc): inelastic normal impulses, λ ≥ 0, on `rows`; returns whether the
/// system is large and wide (stage 2 then tries its sweeps first too).
fn inelastic_stage(
    rows: &mut [Row],
    motions: &mut [SolverBody],
    tolerance: f64,
    buffers_direct: &mut Direct,
    counters: &mut Counters,
    joined: &mut joined::Joined,
) -> bool {
    // A large system first tries a few sweeps from
    // the last step's impulses (a scene at rest: they are the answer, and one sweep over the
    // rows confirms it for far less than a factorisation); then the direct solve when it
    // applies; else projected Gauss–Seidel, warm-started from the last step's impulses.
    let width = if rows.len() > SWEEPS_FIRST_ROWS {
        direct::mean_envelope(rows, &mut buffers_direct.body_first)
    } else {
        0.0
    };
    let large = width > WIDE_ENVELOPE;
    buffers_direct.width = width;
    let mut answered = false;
    // With joint rows the direct solve comes first (the sweeps know no joints).
    let joints = !joined.axes.is_empty();
    // A first touch (no row has a last-step impulse) has nothing to try from: the trial
    // would be plain sweeps from zero, and its failure would make the next step, the first
    // with a warm start, skip its trial.
    let first_touch = || rows.iter().all(|r| r.warm == Vector3::zeros());
    if large && !joints && buffers_direct.trial_skip > 0 {
        buffers_direct.trial_skip -= 1;
    } else if large && !joints && first_touch() {
        // Straight to the direct solve, no wait counted.
    } else if large && !joints {
        buffers_direct.trial.clear();
        buffers_direct.trial.extend_from_slice(motions);
        let cap = trial_cap(rows.len(), width, 1);
        normal::warm_start(rows, motions);
        let (converged, sweeps) = trial_sweeps(cap, tolerance, |n| {
            normal::sweep(rows, motions, tolerance, n)
        });
        buffers_direct.work += sweeps * rows.len() as u64;
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
                row.normal.lambda = 0.0;
            }
        }
    }
    if !answered {
        // With the joint rows (and their stops: `joined`).
        let direct = joined.inelastic(large, rows, motions, tolerance, buffers_direct);
        if direct && joints {
            joined.book_stage(1.0);
            joined.held = true;
        }
        if direct {
            counters.direct += 1;
        } else {
            counters.declined += 1;
            normal::warm_start(rows, motions);
            let (converged, sweeps, residual) = if large {
                subspace::sweep(rows, &[], motions, tolerance, buffers_direct, counters)
            } else {
                let cap = buffers_direct.sweeps_left(rows.len(), MAX_SWEEPS as u64);
                let swept = normal::sweep(rows, motions, tolerance, cap);
                buffers_direct.work += swept.1 * rows.len() as u64;
                swept
            };
            if !converged {
                buffers_direct.unconverged(residual);
            }
            counters.normal_sweeps += sweeps;
        }
    }
    large
}

#[cfg(test)]
mod converging_tests {
    use super::{converging, INTERIOR_SKIP};

    /// Linear convergence r_{k+n} = r_k ρⁿ: the sweeps still needed are ln(tol/r)/ln ρ.
    #[test]
    fn sweeps_about_to_converge_are_told_from_slow_and_stalled_ones() {
        // With INTERIOR_SKIP = 8 sweeps:
        assert!((INTERIOR_SKIP - 8.0).abs() < 1e-12);
        // ρ = 0.1 a sweep (1e-4 → 1e-8 in 4): 2 more sweeps to 1e-10.
        assert!(converging(1e-4, 1e-8, 4, 1e-10));
        // ρ = 0.5 (×1/16 in 4): 1e-8 → 1e-8·0.5⁸ in 8 more, → 1e-8·0.5⁹ in 9.
        assert!(converging(1.6e-7, 1e-8, 4, 1e-8 * 0.5f64.powi(8) * 1.001));
        assert!(!converging(1.6e-7, 1e-8, 4, 1e-8 * 0.5f64.powi(9)));
        // ρ = 0.9: about 44 more sweeps.
        assert!(!converging(1e-8 / 0.9f64.powi(4), 1e-8, 4, 1e-10));
        // Stalled, rising, or no sweeps: never.
        assert!(!converging(1e-8, 1e-8, 4, 1e-10));
        assert!(!converging(1e-9, 1e-8, 4, 1e-10));
        assert!(!converging(1e-4, 1e-8, 0, 1e-10));
    }
}
