//! `soft-step`: sub-stepped soft contacts with a relax pass, in the manner of Box2D v3
//! (Catto, "Solver2D", 2024). Fast and approximate: contacts are stiff springs, not rigid
//! walls, so a stack sags by a known amount; `impulse` is the converged, rigid response.
//!
//! # The step
//!
//! Contacts are found once per step (the same rows as `impulse`, at the poses the integrate
//! phase reached). Every body in a contact is then taken back to the start of the step and
//! advanced again in `n` sub-steps of `h = dt/n` (`substeps`), its external velocity change
//! over the step (`Δv = v_free − v₀`, `ΔL = L_free − L₀`: gravity, drag, from the integrator)
//! spread evenly over them:
//!
//! ```text
//! per sub-step:  v += Δv/n, L += ΔL/n            (ω = I₀⁻¹ L, I₀⁻¹ the start pose's)
//!                warm start: apply every row's accumulated impulse (from the second
//!                  sub-step on: each body's change by the contacts over the last one)
//!                solve, biased and soft (one sweep)
//!                x += h v,  q ← normalise(q + ½ h ω q)
//!                relax: solve again, unbiased and rigid (one sweep)
//! then once:     restitution, store impulses (warm start of the next step)
//! ```
//!
//! The warm start of sub-steps after the first is per body, not per row: the rows' impulses
//! at the end of a sub-step, applied again, change each body's v and ω by exactly what the
//! contacts changed over that sub-step (its warm start plus its sweeps: the rows went from
//! last sub-step's λ to this one's), so the body takes that change again, `v += Δv_contacts`,
//! `ω += Δω_contacts` (O(bodies) instead of O(rows)).
//!
//! The sweeps work on v and ω alone (ω = I₀⁻¹ L, I₀⁻¹ fixed over the step), taking the rows
//! between the same two bodies together with the bodies' motions copied in once: their normal
//! rows, then their manifolds' friction (`patch`: the rows of one pair sharing a normal, held
//! by one tangent pair at the manifold's centre and one twist row about n). Each row and
//! manifold keeps the total it applied along each axis, Λ, so the step's L is
//! `L₀ + ΔL + Σ (r×d) Λ` over the rows' normals and the manifolds' three axes.
//!
//! No detection inside the sub-steps: a row's separation follows its bodies,
//! `s = s₀ + n·[(Δx_A + (D_A − 𝟙) r_A) − (Δx_B + (D_B − 𝟙) r_B)]`, with Δx and D the body's
//! translation and rotation since the detection pose, s₀ = −depth there.
//!
//! # One soft row
//!
//! A normal row with effective mass `m = 1/k` (`k` as in `impulse`), velocity `u` and
//! separation `s < 0` takes the update
//!
//! ```text
//! Δλ = −m·mass_scale·(u + bias_rate·s) − impulse_scale·λ,   λ ← max(0, λ + Δλ)
//! ω_c = 2π·hertz,  a₁ = 2ζ + h ω_c,  a₂ = h ω_c a₁,  a₃ = 1/(1 + a₂)
//! bias_rate = ω_c/a₁,  mass_scale = a₂ a₃,  impulse_scale = a₃
//! ```
//!
//! which is one implicit (backward-Euler) step of a damped spring of stiffness `m ω_c²` and
//! damping ratio ζ (`damping_ratio`) acting on the row: the softness is fixed in hertz, not by
//! the iteration count. The bias (push-out) speed is capped at [`MAX_PUSH`]. A speculative row
//! (`s > 0`) takes the rigid update with bias `s/h`: it may close its gap within the sub-step,
//! no more. The relax sweep uses bias 0, `mass_scale = 1`, `impulse_scale = 0`: it removes the
//! velocity the push-out added, so the push-out moves positions without feeding kinetic energy.
//! A row against an obstacle (or a body of zero inverse mass) uses twice the frequency
//! (Box2D's "static softness"). The frequency is capped at a quarter of the sub-step rate,
//! `hertz ≤ n/(4 dt)`: stiffer than that, one sweep per sub-step cannot follow it.
//!
//! # Friction, per manifold
//!
//! Friction is rigid (no softness, no bias) and taken per manifold, after the normal rows of
//! its run, in the solve and in the relax alike (`patch` has the formulas). With the
//! manifold's points r_i, their centre c (the mean) and their offsets across the normal d_i:
//!
//! ```text
//! tangents t₁, t₂ at c:   u_t = t·(v_A + ω_A×c_A − v_B − ω_B×c_B),   |λ_t| ≤ μ Σ λ_i  (a disk)
//! twist about n:          u_τ = n·(ω_A − ω_B),                       |λ_τ| ≤ μ Σ λ_i |d_i|
//! ```
//!
//! λ_i the manifold's normal impulses as the sweep left them. The twist bound is the most
//! torque about n the points' own Coulomb cones give; a single point (a sphere) has none, and
//! keeps its tangent pair at its point. A 4-point face thus takes 3 friction rows a sweep
//! where two tangents per point took 8 (Rapier's and Bepu's "twist friction"; Box2D v3 keeps
//! friction per point, as soft-step did before). What it changed, measured: a face's sliding
//! no longer turns it about n (the sequential tangent rows at four corners gave a resting
//! stack a yaw rate of 5.7e-4 rad/s in lesson 36's first frames; now below 5e-9), the stack
//! of 10 leans 0.059 mm after 5 s (0.084 mm with friction per point) and lesson 36's
//! sweep-order sway, listed top to bottom, peaks at 0.27 mm instead of 0.24 mm.
//!
//! # The sag it accepts
//!
//! At rest a sub-step's warm start cancels gravity's velocity increment exactly, so `u = 0`
//! and the solve leaves λ unchanged: `m·mass_scale·bias_rate·s = −impulse_scale·λ`, i.e.
//! `λ = −m·h·ω_c²·s` (`mass_scale·bias_rate/impulse_scale = h ω_c²`). λ per sub-step carries
//! the load W over h, `λ = W h`, so `s = −W/(m ω_c²)`: each point is a spring of stiffness
//! `m ω_c²`. For cube on cube (side 2a, mass M, I = ⅔ M a², corner r = (±a, −a, ±a), n = y):
//! `|r×n|² = 2a²`, so `k = 2·(1/M + 2a²/(⅔ M a²)) = 8/M` and m = M/8 per corner; the four
//! corners of a face, in parallel, are a spring of `M ω_c²/2`. The face under i cubes sags
//! `2 i g/ω_c²`; the ground face under N cubes (m = M/4 per corner, static frequency 2ω_c)
//! sags `N g/(4 ω_c²)`. The top of a stack of N sinks
//!
//! ```text
//! Σ_{i=1}^{N−1} 2 i g/ω_c² + N g/(4 ω_c²) = N(N−1) g/ω_c² + N g/(4 ω_c²)
//! ```
//!
//! At the default 60 Hz: 0.015 mm (N = 1), 0.23 mm (3), 6.3 mm (10); a test checks it.
//!
//! # The height it holds
//!
//! A soft face is also a tilt spring: turn the cubes above it by θ about the face's centre and
//! its corners (lever a) push back with the moment `4·(M ω_c²/8)·a²·θ = (M ω_c² a²/2)·θ`, where
//! a rigid face pushes back with whatever it takes. The weight above, shifted sideways by the
//! tilt, turns it further with a moment that grows as the square of the height. A stack is a
//! column of such joints, one per `2a`: bending stiffness `EI = (M ω_c² a²/2)·2a = M ω_c² a³`
//! and weight per length `q = M g/(2a)`. A column clamped at its foot buckles under its own
//! weight when `q ℓ³ = 7.837 EI` (Greenhill, 1881); with `ℓ = 2aN`, above
//!
//! ```text
//! N_c = (7.837 ω_c² a/(4 g))^(1/3) ≈ (1.96 ω_c² a/g)^(1/3)
//! ```
//!
//! cubes the stack leans off its axis at an exponential rate, from whatever asymmetry the
//! sweep order leaves (micrometres), and falls ([`SoftStep::buckling_count`]). For 0.2 m cubes:
//! 14.2 at 60 Hz, 22.5 at 120 Hz, 41.4 at 300 Hz. This is the law soft-step chose, not a
//! numerical instability: the same count follows from the discrete chain of joints (the
//! stiffness matrix of the tilts stops being positive definite), and the tests check both the
//! count and that the simulated stacks stand below it and lean away above it. `impulse` has
//! no tilt spring and no such height.
//!
//! # Energy
//!
//! The relax sweep takes back the push-out's velocity and ζ = 10 damps the springs, so the
//! contacts take energy out; what they can add is the work of lifting a body out of
//! penetration against gravity. Two guards make that the only gain: the kinetic energy after
//! the response is never above the free flight's (if it is, the motion of the bodies in
//! contact relative to their common barycenter is scaled, `v ← v_cm + s (v − v_cm)`, `L ← s L`,
//! with `K_cm + s² K_rel = K_free`: the total linear momentum is kept), and restitution asks
//! a row for no more than e times the speed it met (`bounce`), so a step gains at most
//! `Σ M |g|·Δy` where Δy is how much higher than its free flight the contacts left a body.
//! Over a run the total energy stays below `E(0) + Σ M|g|·d_max`, d_max the deepest
//! penetration reached (a test).
//!
//! # What it costs, against Rapier
//!
//! Measured on issue 35's scenes (callgrind, `World::step`, the difference of two runs): a
//! pyramid of 10 rows has 55 bodies and 580 rows, kept across steps (`kept`: detection runs
//! in few steps). With friction per point it cost 2.13M instructions a step: about 60 % in
//! the sweeps, 17 % in preparing the rows (`rows::build`, the separations, the lanes' packed
//! constants), 6 % in the warm-start cache, 5 % in carrying the kept rows; per manifold of 4
//! points and per sub-step it updated 24 rows (4 normal and 8 tangent, in each of the two
//! sweeps), Rapier 11 (4 normal in the solve; 4 normal, one tangent pair and one twist at the
//! manifold's centre in the relax). Per manifold (`patch`) it updates 14 (4 normal and 3
//! friction in each sweep), the friction scalar after the lanes' normal rows:
//!
//! ```text
//! instructions per step     per point → per manifold
//! stack-10                  172k → 160k    (−7 %)
//! pyramid-10               2.13M → 1.99M   (−7 %)
//! pyramid-20               9.45M → 8.76M   (−7 %)
//! wall                     1.38M → 1.29M   (−6 %)
//! dominoes16                234k → 232k    (−1 %)
//! stack-40                 1.16M → 1.01M   (−13 %)
//! wall-ball                1.78M → 1.54M   (−13 %)
//! ```
//!
//! and CPU time fell more than the count (not looked into further): against Rapier 0.36 f32,
//! in six rounds back to back (benches/rapier; each scene's median ratio), soft-step's time
//! over Rapier's went, per point → per manifold, stack-10 1.19 → 1.07, stack-40 1.75 → 1.42,
//! pyramid-10 1.93 → 1.50, pyramid-20 2.22 → 1.78, dominoes16 1.34 → 1.26, wall 2.19 → 1.86,
//! wall-ball 3.04 → 2.55; paired whole runs (farm-bench), per manifold over per point: 0.84
//! (pyramid-10, wall, wall-ball), 0.81 (pyramid-20), 0.89 (stack-10), 0.95 (dominoes16)
//! (a loaded machine: the ratios, not the times). The manifold's friction in the relax only,
//! as Rapier has it, saves another 9 % of the pyramid's instructions (1.81M) and lets a stack
//! of 10 lean 1.96 mm in 5 s (with friction per point in the relax only: 1.13 mm; the
//! tests allow 1 mm). The manifolds of two runs between two bodies each in four lanes
//! (as their normal rows are; the same bits) cost more, not less: pyramid-10 2.07M
//! instructions a step against 1.99M scalar, CPU time ×1.02–1.06 (paired runs, medians).
//! Earlier, with friction per point: in the solve only, lesson 36's sway
//! and axis claims and lesson 37's wave moved, and the contact study's box at one sub-step
//! sank 50 mm (closed form 0.017 mm). Kept bit for bit but measured dearer: the gap refresh
//! and the totals done run by run inside the relax sweep (+3 % instructions), skipping an
//! idle row's friction (+0.8 %), a warm-start lookup trying the row's own index first (+1 %).
//!
//! # Where it is done
//!
//! [`respond`] reads as the step above: `bodies` takes the bodies in contact back to the
//! start of the step and moves them through the sub-steps; `rows` prepares each contact once
//! per step into what the sweeps read (normal, levers, `r×n`, `I₀⁻¹(r×n)`, `1/k`: no matrix
//! work is left for the sweeps) and refreshes the separations; `patch` each manifold's
//! friction (its centre, tangents, twist and the impulses the points see); `sweep` holds the
//! passes over one row (warm start, soft solve and relax); `bounce` the restitution, each
//! manifold's bouncing rows solved together; `lanes` schedules the runs of rows so that two
//! runs sharing no body are solved side by side in SIMD lanes (`f2`), in an order that gives
//! the sequential sweep's numbers bit for bit (for a chain such as a stack, a whole sub-step
//! at once: the relax of the lower runs beside the solve of the upper ones; a run's friction
//! follows its normal rows, scalar). Everything after
//! detection is built twice, with AVX2 (taken at run time where the CPU has it) and for any
//! CPU: both do the same operations in the same order (no fused multiply-add), so their
//! numbers agree bit for bit (a test).

mod bodies;
mod bounce;
mod f2;
mod f4;
mod lanes;
pub mod particle;
mod patch;
mod rows;
mod sweep;

use super::contacts;
use super::kept::Kept;
use super::response::Descriptor;
use super::warm::WarmCache;
use super::{CollideInput, Contact, EnergyChange};
use crate::physics::derive::derive;
use crate::physics::energy::{kinetic_energy_with, Energy};
#[cfg(target_arch = "x86_64")]
use crate::physics::simd::avx2;
use crate::physics::state::State;
use bodies::Bodies;
use lanes::Lanes;
use nalgebra::Vector3;
pub use particle::particle;
use rows::Rows;
use std::hash::{Hash, Hasher};

/// The highest push-out speed a soft row may ask for, m/s (Box2D's `contactPushMaxVelocity`).
pub const MAX_PUSH: f64 = 3.0;

/// Sweeps per sub-step (solve and relax each) in a step where a contact meets faster than the
/// bounce speed (an impact); one otherwise. Measured on a 2 cm box landing at 50 m/s on a 1 cm
/// plate: with one sweep a quarter of the starting heights went through the plate.
pub const IMPACT_SWEEPS: usize = 8;

/// Most sub-steps a scene may ask for.
pub const MAX_SUBSTEPS: u32 = 64;

/// The `soft-step` parameters (`contact = { response = "soft-step", hertz, damping_ratio,
/// substeps }`).
#[derive(Debug, Clone, Copy)]
pub struct SoftStep {
    /// Contact frequency f, Hz (ω_c = 2π f), > 0; capped at `substeps/(4 dt)`.
    pub hertz: f64,
    /// Damping ratio ζ of the contact spring, ≥ 0.
    pub damping_ratio: f64,
    /// Sub-steps per step, 1 ..= [`MAX_SUBSTEPS`].
    pub substeps: u32,
}

impl SoftStep {
    /// The documented defaults: 60 Hz, ζ = 10 (Box2D's contact damping ratio), 4 sub-steps
    /// (Box2D's count). Box2D and Rapier use 30 Hz at 60 steps/s; at dt = 1e-3 twice that
    /// costs nothing and quarters the sag.
    pub const DEFAULT: SoftStep = SoftStep {
        hertz: 60.0,
        damping_ratio: 10.0,
        substeps: 4,
    };

    /// The frequency used at time step dt: `hertz`, capped at a quarter of the sub-step rate.
    pub fn hertz_at(&self, dt: f64) -> f64 {
        self.hertz.min(0.25 * self.substeps as f64 / dt)
    }

    /// The sag the module doc derives for the top of a stack of `count` cubes under gravity g,
    /// at time step dt, m: `N(N−1) g/ω_c² + N g/(4 ω_c²)`.
    pub fn stack_sag(&self, count: usize, g: f64, dt: f64) -> f64 {
        let omega = 2.0 * std::f64::consts::PI * self.hertz_at(dt);
        let n = count as f64;
        (n * (n - 1.0) + n / 4.0) * g / (omega * omega)
    }
}

impl SoftStep {
    /// The number of cubes of side `side` a stack holds before its soft faces buckle under
    /// its weight (gravity g), at time step dt: `N_c = (7.837 ω_c² a/(4 g))^(1/3)`, a = side/2
    /// (module doc, "The height it holds"). A stack of fewer cubes stands; of more, it falls.
    pub fn buckling_count(&self, side: f64, g: f64, dt: f64) -> f64 {
        let omega = 2.0 * std::f64::consts::PI * self.hertz_at(dt);
        (GREENHILL * omega * omega * (0.5 * side) / (4.0 * g)).cbrt()
    }

    /// The lowest contact frequency at which a stack of `count` cubes of side `side` stands
    /// (its buckling count equals `count`), Hz: `ω_c = √(4 g N³/(7.837 a))`.
    pub fn hertz_to_hold(count: usize, side: f64, g: f64) -> f64 {
        let n = count as f64;
        (4.0 * g * n * n * n / (GREENHILL * 0.5 * side)).sqrt() / (2.0 * std::f64::consts::PI)
    }
}

/// Greenhill's constant: a uniform column clamped at its foot buckles under its own weight
/// when `q ℓ³ = 7.837 EI` (weight per length q, bending stiffness EI).
const GREENHILL: f64 = 7.837;

impl Default for SoftStep {
    fn default() -> Self {
        SoftStep::DEFAULT
    }
}

impl PartialEq for SoftStep {
    fn eq(&self, other: &Self) -> bool {
        self.hertz.to_bits() == other.hertz.to_bits()
            && self.damping_ratio.to_bits() == other.damping_ratio.to_bits()
            && self.substeps == other.substeps
    }
}

impl Eq for SoftStep {}

impl Hash for SoftStep {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.hertz.to_bits().hash(state);
        self.damping_ratio.to_bits().hash(state);
        self.substeps.hash(state);
    }
}

/// The three coefficients of one soft row at sub-step h (module doc).
#[derive(Debug, Clone, Copy, Default)]
struct Softness {
    bias_rate: f64,
    mass_scale: f64,
    impulse_scale: f64,
}

impl Softness {
    fn new(hertz: f64, zeta: f64, h: f64) -> Softness {
        let omega = 2.0 * std::f64::consts::PI * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

/// Buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    rows: Rows,
    bodies: Bodies,
    /// The runs' schedule for the sweeps (`lanes`).
    lanes: Lanes,
    points: Vec<super::geometry::ContactPoint>,
    /// The broad phase's buffers (`broad_phase`).
    broad: super::broad_phase::BroadPhase,
    /// Last step's per-sub-step impulses, by contact feature.
    warm: WarmCache,
    /// The last detection's rows, carried while the bodies barely move (`kept`).
    kept: Kept,
    /// The restitution's manifold solve (`bounce`).
    bounce: bounce::Block,
}

/// What the front ends say about `soft-step` (`response`).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "soft-step",
    summary: "sub-stepped soft contacts with a relax pass (Box2D v3): each contact a damped spring of `hertz` and `damping_ratio`, one sweep per sub-step, friction per face (a tangent pair and a twist at its centre)",
    keeps: "momentum between bodies; energy at most the lift out of penetration; sags N(N−1)g/ω² at the top of a stack of N, which buckles above (1.96 ω² a/g)^(1/3) cubes of side 2a",
    brief: "soft contacts over sub-steps",
    formula: "per sub-step h = dt/n:  Δλ = −m·a₂a₃·(uₙ + ω_c s/a₁) − a₃·λ,  λ ≥ 0;  x += h·v;  relax: Δλ = −m·uₙ  (m = 1/k, ω_c = 2π·hertz)",
    formula_bodies: "per sub-step h = dt/n:  Δλ = −m·a₂a₃·(uₙ + ω_c s/a₁) − a₃·λ on A, −Δλ on B;  x += h·v;  relax: Δλ = −m·uₙ  (m = 1/k, ω_c = 2π·hertz)",
    impulses: true,
    colour: (130, 130, 130),
    charted: true,
};

/// The collide phase under `soft-step` with `params` (the entry point `responses!` calls):
/// [`respond`] with the world's soft-step buffers.
pub fn collide(
    input: &CollideInput,
    params: &SoftStep,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut super::impulse::Scratch,
) -> Option<EnergyChange> {
    respond(input, params, states, contacts, &mut scratch.soft)
}

/// Detects contacts and runs the sub-stepped soft response on `states` (module doc). Returns
/// the energy of all bodies before and after (None when nothing touched).
pub fn respond(
    input: &CollideInput,
    params: &SoftStep,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> Option<EnergyChange> {
    let context = input.context;
    // Speculative rows: anything a body could reach within the step at the bounce speed,
    // and at least a millimetre (the rows' separations are tracked within the step).
    let margin = (context.bounce_speed * context.dt).max(1e-3);
    if !detect(input, states, margin, contacts, scratch) {
        contacts.clear();
        scratch.warm.clear();
        scratch.kept.ended_at(states);
        return None;
    }
    let change = solve(input, params, states, contacts, scratch);
    scratch.kept.ended_at(states);
    Some(change)
}

/// The response to the step's rows (module doc, "The step"): compiled with AVX2 where the
/// CPU has it (the same arithmetic, operation by operation: no fused multiply-add).
fn solve(
    input: &CollideInput,
    params: &SoftStep,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> EnergyChange {
    #[cfg(target_arch = "x86_64")]
    if avx2() {
        // SAFETY: the CPU has AVX2.
        return unsafe { solve_avx2(input, params, states, contacts, scratch) };
    }
    solve_plain::<f4::Plain>(input, params, states, contacts, scratch)
}

/// [`solve`] compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn solve_avx2(
    input: &CollideInput,
    params: &SoftStep,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> EnergyChange {
    solve_plain::<f4::Avx>(input, params, states, contacts, scratch)
}

/// [`solve`] for any CPU, with `Q` the four lanes of the sweeps' pairs of runs (`f4`).
#[inline(always)]
fn solve_plain<Q: f4::Quad>(
    input: &CollideInput,
    params: &SoftStep,
    states: &mut [State],
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> EnergyChange {
    let context = input.context;
    let dt = context.dt;
    let n = params.substeps.max(1);
    let h = dt / n as f64;
    let bounce_speed = context.bounce_speed;
    // The bodies in contact taken back to the start of the step, and their rows.
    let Scratch {
        rows,
        bodies,
        warm,
        lanes,
        bounce,
        ..
    } = scratch;
    let kinetic_free = bodies.gather(input.bodies, input.before, states, contacts, n);
    let before = total_energy(input, states, &bodies.slot, &bodies.kinetic);
    let hertz = params.hertz_at(dt);
    let dynamic = Softness::new(hertz, params.damping_ratio, h);
    let fixed = Softness::new(2.0 * hertz, params.damping_ratio, h);
    let friction = context.friction;
    rows.build(contacts, bodies, warm, friction, (dynamic, fixed));
    rows.measure(contacts, bodies);

    // An impact (a row meeting faster than the bounce speed) gets IMPACT_SWEEPS sweeps per
    // sub-step: one Gauss–Seidel sweep over a face's 4 coupled rows leaves part of a fast
    // approach, which then goes deep (or, for a thin body, through).
    let impact = rows.totals.iter().any(|t| t.approach < -bounce_speed);
    let passes = if impact { IMPACT_SWEEPS } else { 1 };
    lanes.schedule(rows, bodies.members.len(), passes == 1 && piped());
    #[cfg(test)]
    PIPED_STEPS.with(|c| c.set(c.get() + usize::from(lanes.piped())));
    substeps::<Q>(rows, lanes, bodies, n, passes, friction, h);
    // Restitution, once, from the approach the contact met, a manifold at a time (`bounce`).
    if context.restitution > 0.0 {
        let motions = &mut bodies.motions;
        bounce::restitution(rows, motions, context.restitution, bounce_speed, bounce);
    }
    // L from each row's impulses, then back into the states, the kinetic energy capped at
    // the free flight's.
    rows.add_angular_momentum(&mut bodies.l);
    bodies.write_back(input.bodies, states);
    let known = cap_kinetic(
        input,
        &bodies.members,
        states,
        kinetic_free,
        &mut bodies.kinetic,
    );
    let slot: &[usize] = if known { &bodies.slot } else { &[] };
    let after = total_energy(input, states, slot, &bodies.kinetic);
    store(contacts, rows, warm, bounce_speed);
    EnergyChange { before, after }
}

/// The step's rows: last step's carried over while the bodies barely move (`kept`), else
/// detected (and kept). Whether any row touches.
fn detect(
    input: &CollideInput,
    states: &[State],
    margin: f64,
    contacts: &mut Vec<Contact>,
    scratch: &mut Scratch,
) -> bool {
    let carried = match input.recorded {
        None => scratch
            .kept
            .carry(input.bodies, input.before, states, margin, contacts),
        Some(_) => None,
    };
    carried.unwrap_or_else(|| {
        let touching = contacts::find(
            input,
            states,
            margin,
            contacts,
            &mut scratch.points,
            &mut scratch.broad,
        );
        if input.recorded.is_none() {
            scratch
                .kept
                .remember(input.bodies, states, margin, contacts);
        }
        touching
    })
}

/// The `n` sub-steps (module doc, "The step"), `passes` sweeps each of the solve and relax.
#[inline(always)]
fn substeps<Q: f4::Quad>(
    rows: &mut Rows,
    lanes: &Lanes,
    bodies: &mut Bodies,
    n: u32,
    passes: usize,
    friction: f64,
    h: f64,
) {
    for substep in 0..n {
        bodies.begin_substep();
        if substep == 0 {
            sweep::warm_start(rows, &mut bodies.motions);
        }
        if lanes.piped() {
            lanes.substep::<Q>(rows, bodies, friction, h);
        } else {
            for _ in 0..passes {
                lanes.sweep::<Q>(rows, &mut bodies.motions, friction, h, true);
            }
            bodies.advance(h);
            rows.refresh_gaps(bodies);
            for _ in 0..passes {
                lanes.sweep::<Q>(rows, &mut bodies.motions, friction, h, false);
            }
        }
        bodies.end_substep();
        rows.add_totals();
    }
}

/// Whether a sub-step of one sweep each runs piped (`Lanes::substep`: the same bits as the
/// sweeps one after the other); a test switches it off on its thread to compare.
#[inline(always)]
fn piped() -> bool {
    #[cfg(test)]
    if UNPIPED.with(std::cell::Cell::get) {
        return false;
    }
    true
}

#[cfg(test)]
thread_local! {
    /// Tests: the sweeps one after the other on this thread.
    static UNPIPED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Tests: the steps on this thread whose sub-steps ran piped.
    static PIPED_STEPS: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// The energy of every body: kinetic, and potential in the declared gravity. A body with a
/// solver slot (`slot`, indexed by body; shorter or `usize::MAX`: none) takes its kinetic
/// energy from `known` (per slot, computed from the same state), the others compute theirs.
#[inline(always)]
fn total_energy(input: &CollideInput, states: &[State], slot: &[usize], known: &[f64]) -> Energy {
    let mut e = Energy::default();
    for (i, s) in states.iter().enumerate() {
        let body = &input.bodies[i];
        let k = match slot.get(i).and_then(|&j| known.get(j)) {
            Some(&k) => k,
            None => kinetic_energy_with(
                body,
                &derive(body, s).inv_inertia_world,
                &s.linear_momentum,
                &s.angular_momentum,
            ),
        };
        let v = input
            .context
            .gravity
            .map_or(0.0, |g| -body.mass * g.dot(&s.position));
        e = e + Energy {
            kinetic: k,
            potential: v,
            total: k + v,
        };
    }
    e
}

/// Caps the kinetic energy of the bodies in contact (`members`) at the free flight's,
/// keeping the linear momentum: only the motion relative to the moving members' common
/// barycenter is scaled, K = K_cm + K_rel → K_cm + s² K_rel (module doc, "Energy"). Whether
/// `kinetic` (per member) holds each member's kinetic energy in the final states.
#[inline(always)]
fn cap_kinetic(
    input: &CollideInput,
    members: &[usize],
    states: &mut [State],
    free: f64,
    kinetic: &mut Vec<f64>,
) -> bool {
    let mut kinetic_of = |states: &[State]| -> f64 {
        kinetic.clear();
        kinetic.extend(members.iter().map(|&b| {
            let s = &states[b];
            kinetic_energy_with(
                &input.bodies[b],
                &derive(&input.bodies[b], s).inv_inertia_world,
                &s.linear_momentum,
                &s.angular_momentum,
            )
        }));
        kinetic.iter().sum()
    };
    let moving = |b: &&usize| input.bodies[**b].inv_mass > 0.0;
    let mass: f64 = members
        .iter()
        .filter(moving)
        .map(|&b| input.bodies[b].mass)
        .sum();
    for _ in 0..4 {
        let kinetic = kinetic_of(states);
        if kinetic <= free || mass == 0.0 {
            return true;
        }
        let momentum: Vector3<f64> = members
            .iter()
            .filter(moving)
            .map(|&b| states[b].linear_momentum)
            .sum();
        let v_cm = momentum / mass;
        let k_cm = 0.5 * mass * v_cm.norm_squared();
        let k_rel = kinetic - k_cm;
        let scale = if k_rel > 0.0 && free > k_cm {
            ((free - k_cm) / k_rel).sqrt() * (1.0 - 4.0 * f64::EPSILON)
        } else {
            0.0
        };
        for &b in members.iter().filter(moving) {
            let m = input.bodies[b].mass;
            let p = states[b].linear_momentum;
            states[b].linear_momentum = v_cm * m + (p - v_cm * m) * scale;
            states[b].angular_momentum *= scale;
        }
    }
    false
}

/// Stores the step's impulses on the contacts, and the last sub-step's for the next warm
/// start (none after a bounce: it says nothing about the next step's load); drops the
/// speculative rows that pushed nothing.
#[inline(always)]
fn store(contacts: &mut Vec<Contact>, rows: &Rows, warm: &mut WarmCache, bounce_speed: f64) {
    for (p, t) in rows.patches.iter().zip(&rows.patch_totals) {
        for i in p.rows.clone() {
            let row = &rows.rows[i];
            let c = &mut contacts[i];
            c.normal_velocity = rows.totals[i].approach;
            let friction = p.share(&rows.rows, &row.lever, t.applied);
            c.impulse = row.normal * rows.totals[i].applied + friction;
        }
    }
    let impulse = |p: &patch::Patch, i: usize| {
        let row = &rows.rows[i];
        row.normal * row.lambda + p.share(&rows.rows, &row.lever, p.lambda)
    };
    warm.store(
        rows.patches
            .iter()
            .flat_map(|p| p.rows.clone().map(move |i| (p, i)))
            .filter(|&(_, i)| rows.totals[i].approach >= -bounce_speed)
            .map(|(p, i)| (&contacts[i], impulse(p, i))),
    );
    contacts.retain(|c| c.depth > 0.0 || c.impulse != Vector3::zeros());
}

/// A factor just under 1, `1 − 2⁻⁵⁰`: `fl(fl(b·b)·INSIDE) < b²` exactly for any b whose
/// square is a normal number (each rounding is at most a factor `1 + 2⁻⁵³`).
const INSIDE: f64 = 1.0 - 1.0 / (1u64 << 50) as f64;

/// Scales a tangent impulse into the disk of radius `bound`.
///
/// The root `|t| = √(t₁² + t₂²)` is taken only near or outside the rim: when the rounded
/// square `q` is at most `fl(fl(b·b)·INSIDE)`, which is below b² exactly (b² normal), then
/// √q < b and the correctly rounded root is at most b, so `|t| > b` is false and nothing
/// would change; nor when q = 0 (a row that pushes nothing and holds nothing: √0 = 0 is not
/// above b ≥ 0). The result is the plain formula's to the bit; a resting contact well inside
/// its cone, or an idle speculative row, skips the root's 15–20 cycles.
#[inline(always)]
fn clamp_disk(t: &mut [f64; 2], bound: f64) {
    let square = t[0] * t[0] + t[1] * t[1];
    let inner = bound * bound * INSIDE;
    if bound >= 0.0 && (square == 0.0 || (inner >= f64::MIN_POSITIVE && square <= inner)) {
        return;
    }
    let size = square.sqrt();
    if size > bound {
        let scale = if size > 0.0 { bound / size } else { 0.0 };
        *t = [t[0] * scale, t[1] * scale];
    }
}

#[cfg(test)]
mod tests {
    /// The bits of a wall of bricks hit by a ball (resting rows, sliding rows, an impact)
    /// after 150 steps of soft-step, with the AVX2 build or the plain one (`plain`), and how
    /// far the bodies moved (m, the largest).
    fn bits(plain: bool) -> (Vec<u64>, f64) {
        use crate::contact_scenes::wall;
        use crate::physics::{Impacts, Response};
        crate::physics::simd::set_plain(plain);
        let soft = Response::SoftStep(super::SoftStep::DEFAULT);
        let mut world = wall(true, 0.0, Impacts::Propagate, soft);
        for _ in 0..150 {
            world.step();
        }
        crate::physics::simd::set_plain(false);
        let moved = world
            .states()
            .iter()
            .zip(world.initial_states())
            .map(|(s, s0)| (s.position - s0.position).norm())
            .fold(0.0, f64::max);
        let bits = world
            .states()
            .iter()
            .flat_map(|s| {
                let q = s.orientation.quaternion();
                let [x, p, l] = [s.position, s.linear_momentum, s.angular_momentum];
                [
                    x.x, x.y, x.z, p.x, p.y, p.z, l.x, l.y, l.z, q.i, q.j, q.k, q.w,
                ]
            })
            .map(f64::to_bits)
            .collect();
        (bits, moved)
    }

    /// The disk clamp with and without its short cut (`clamp_disk` skips the root well inside
    /// the rim) gives the same bits, on random impulses and on ones within a few ulps of the
    /// rim, tiny, huge, zero and negative-zero bounds.
    #[test]
    fn the_disk_clamp_gives_the_plain_formulas_bits() {
        fn plain(t: &mut [f64; 2], bound: f64) {
            let size = (t[0] * t[0] + t[1] * t[1]).sqrt();
            if size > bound {
                let scale = if size > 0.0 { bound / size } else { 0.0 };
                *t = [t[0] * scale, t[1] * scale];
            }
        }
        let mut seed = 11u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..200_000 {
            let angle = next() * std::f64::consts::TAU;
            let scale = [1.0, 1e-3, 1e-150, 1e150, 1e-160][i % 5];
            let bound = [next() * scale, 0.0, -0.0][usize::from(i % 97 == 0) + usize::from(i % 89 == 0)];
            // Within a few ulps of the rim, or anywhere inside and outside it.
            let r = if bound == 0.0 {
                next() * [0.0, 1e-200, 1.0][i % 3]
            } else if i % 2 == 0 {
                bound * (1.0 + (next() - 0.5) * 1e-15)
            } else {
                bound * next() * 2.0
            };
            let t = [r * angle.cos(), r * angle.sin()];
            let (mut fast, mut slow) = (t, t);
            super::clamp_disk(&mut fast, bound);
            plain(&mut slow, bound);
            assert_eq!(fast.map(f64::to_bits), slow.map(f64::to_bits), "{t:?} in {bound}");
        }
    }

    /// The piped sub-steps (`Lanes::substep`) give the bits of the sweeps, the move and the
    /// relax one after the other, on a stack of 20 (piped in every step) as it sags onto its
    /// soft contacts and settles.
    #[test]
    fn the_piped_substeps_give_the_sequential_bits() {
        use crate::contact_scenes::stack;
        use crate::physics::Response;
        let run = |unpiped: bool| {
            super::UNPIPED.with(|u| u.set(unpiped));
            super::PIPED_STEPS.with(|c| c.set(0));
            let mut world = stack(20, Response::SoftStep(super::SoftStep::DEFAULT));
            for _ in 0..200 {
                world.step();
            }
            super::UNPIPED.with(|u| u.set(false));
            let top = world.states()[19].position.y - world.initial_states()[19].position.y;
            assert!(top < -1e-3, "the top sagged {top} m");
            let bits: Vec<u64> = world
                .states()
                .iter()
                .flat_map(|s| {
                    let q = s.orientation.quaternion();
                    let [x, p, l] = [s.position, s.linear_momentum, s.angular_momentum];
                    [x.x, x.y, x.z, p.x, p.y, p.z, l.x, l.y, l.z, q.i, q.j, q.k, q.w]
                })
                .map(f64::to_bits)
                .collect();
            (bits, super::PIPED_STEPS.with(std::cell::Cell::get))
        };
        let (apart, none) = run(true);
        let (piped, count) = run(false);
        assert_eq!(none, 0);
        assert!(count >= 150, "{count} of 200 steps piped");
        assert_eq!(piped, apart);
    }

    #[test]
    fn the_avx2_build_gives_the_plain_builds_bits() {
        let (plain, moved) = bits(true);
        assert!(moved > 0.05, "the ball moved {moved} m");
        assert_eq!(bits(false).0, plain);
    }
}
