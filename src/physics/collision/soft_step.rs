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
//! between the same two bodies together with the bodies' motions copied in once; each row
//! keeps the total it applied along each axis, Λ, so the step's L is
//! `L₀ + ΔL + Σ_rows Σ_axes (r×d) Λ` and the row's impulse `n Λ₀ + t₁ Λ₁ + t₂ Λ₂`. Friction
//! reads the point's relative velocity once for both tangents.
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
//! (Box2D's "static softness"). Friction: two tangent rows, the accumulated tangent impulse
//! kept in the disk `|λ_t| ≤ μ λ`. The frequency is capped at a quarter of the sub-step rate,
//! `hertz ≤ n/(4 dt)`: stiffer than that, one sweep per sub-step cannot follow it.
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
//! with `K_cm + s² K_rel = K_free`: the total linear momentum is kept), and restitution is Poisson's `e·λ` at most, so a step gains at most
//! `Σ M |g|·Δy` where Δy is how much higher than its free flight the contacts left a body.
//! Over a run the total energy stays below `E(0) + Σ M|g|·d_max`, d_max the deepest
//! penetration reached (a test).

use super::contacts;
use super::impulse::tangents;
use super::kept::Kept;
use super::solver_body::{Axis, SolverBody};
use super::warm::WarmCache;
use super::{CollideInput, Contact, EnergyChange};
use crate::physics::derive::derive;
use crate::physics::energy::{kinetic_energy_with, Energy};
use crate::physics::state::{Orientation, State};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
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

/// Where a solver body is within the sub-steps (its velocities are the [`SolverBody`] of the
/// same index).
#[derive(Debug, Clone, Copy)]
struct Placement {
    position: Vector3<f64>,
    q: UnitQuaternion<f64>,
    /// The detection pose.
    detected_position: Vector3<f64>,
    detected_inverse: UnitQuaternion<f64>,
    /// Rotation since the detection pose, minus 𝟙.
    turned: Matrix3<f64>,
    /// The external velocity change per sub-step: Δv/n, ΔL/n and I₀⁻¹ ΔL/n.
    dv: Vector3<f64>,
    dl: Vector3<f64>,
    dw: Vector3<f64>,
}

/// One contact as the sub-steps see it.
#[derive(Debug, Clone, Copy)]
struct Row {
    normal: Axis,
    tangents: [Axis; 2],
    lever: Vector3<f64>,
    lever_other: Vector3<f64>,
    /// Separation at the detection pose, m.
    separation: f64,
    /// Separation at the bodies' current poses, m: refreshed whenever the poses move (once
    /// per sub-step), read by every sweep.
    gap: f64,
    /// Normal velocity before the response, m/s.
    approach: f64,
    soft: Softness,
    lambda: f64,
    lambda_tangent: [f64; 2],
    max_lambda: f64,
    /// Every impulse applied over the step along the normal and the two tangents (N·s, on
    /// A): the row's impulse is `n Λ₀ + t₁ Λ₁ + t₂ Λ₂`, and its share of each body's angular
    /// momentum `(r×d) Λ` summed over the three axes.
    applied: [f64; 3],
}

/// A body's motion inside the sub-steps: v, ω (= I₀⁻¹ L) and 1/M. Its angular momentum is
/// not kept in step impulse by impulse: L at the end is L₀ plus the external change plus each
/// row's `(r×d) Λ` ([`Row::applied`]).
#[derive(Debug, Clone, Copy, Default)]
struct Motion {
    v: Vector3<f64>,
    omega: Vector3<f64>,
    inv_mass: f64,
}

impl Motion {
    /// The rate of `axis`, A relative to B (`b` unread when the axis has no B end):
    /// `d·v_A + (r_A×d)·ω_A − d·v_B + (r_B×(−d))·ω_B`.
    #[inline]
    fn rate(axis: &Axis, a: &Motion, b: &Motion) -> f64 {
        let mut u = axis.d.dot(&a.v) + axis.a.rd.dot(&a.omega);
        if let Some(e) = &axis.b {
            u += -axis.d.dot(&b.v) + e.rd.dot(&b.omega);
        }
        u
    }

    /// The velocity of A's point at lever `ra` relative to B's at `rb`,
    /// `v_A + ω_A×r_A − v_B − ω_B×r_B` (B still when the row has no B end): any axis's rate
    /// is its `d·` this.
    #[inline]
    fn relative(a: &Motion, b: &Motion, ra: &Vector3<f64>, rb: &Vector3<f64>) -> Vector3<f64> {
        a.v + a.omega.cross(ra) - b.v - b.omega.cross(rb)
    }

    /// Applies the impulse j along `axis`: `v_A += j d/M_A`, `ω_A += j I_A⁻¹(r_A×d)`, the
    /// opposite on B.
    #[inline]
    fn push(axis: &Axis, j: f64, a: &mut Motion, b: &mut Motion) {
        a.v += axis.d * (j * a.inv_mass);
        a.omega += axis.a.w * j;
        if let Some(e) = &axis.b {
            b.v += axis.d * (-j * b.inv_mass);
            b.omega += e.w * j;
        }
    }
}

/// Consecutive rows between the same two bodies (B: None for an obstacle or a fixed body):
/// a sweep copies their motions in once, solves the rows, and copies them back.
#[derive(Debug, Clone, Copy)]
struct Run {
    a: usize,
    b: Option<usize>,
    rows: (usize, usize),
}

/// Calls `solve` on each row with its two bodies' motions, run by run (`b` is a still
/// stand-in when the row has no B end).
#[inline]
fn each_row(
    runs: &[Run],
    rows: &mut [Row],
    motions: &mut [Motion],
    mut solve: impl FnMut(&mut Row, &mut Motion, &mut Motion),
) {
    for run in runs {
        let mut a = motions[run.a];
        let mut b = run.b.map_or(Motion::default(), |b| motions[b]);
        for row in &mut rows[run.rows.0..run.rows.1] {
            solve(row, &mut a, &mut b);
        }
        motions[run.a] = a;
        if let Some(i) = run.b {
            motions[i] = b;
        }
    }
}

impl Row {
    /// The separation at the bodies' current poses.
    #[inline(always)]
    fn separation_now(&self, places: &[Placement]) -> f64 {
        let a = &places[self.normal.a.body];
        let mut d = a.position - a.detected_position + a.turned * self.lever;
        if let Some(b) = &self.normal.b {
            let s = &places[b.body];
            d -= s.position - s.detected_position + s.turned * self.lever_other;
        }
        self.separation + self.normal.d.dot(&d)
    }
}

/// Buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    rows: Vec<Row>,
    runs: Vec<Run>,
    /// Per solver body, what the contacts changed of its v and ω over the last sub-step.
    kicks: Vec<(Vector3<f64>, Vector3<f64>)>,
    bodies: Vec<SolverBody>,
    motions: Vec<Motion>,
    places: Vec<Placement>,
    /// Each solver body's free flight (the integrate phase's result): v, ω and world I⁻¹.
    flight: Vec<(Vector3<f64>, Vector3<f64>, Matrix3<f64>)>,
    /// Index of each world body among the solver bodies (usize::MAX: not in contact).
    slot: Vec<usize>,
    members: Vec<usize>,
    points: Vec<super::geometry::ContactPoint>,
    /// The broad phase's buffers (`broad_phase`).
    broad: super::broad_phase::BroadPhase,
    /// Last step's per-sub-step impulses, by contact feature.
    warm: WarmCache,
    /// The last detection's rows, carried while the bodies barely move (`kept`).
    kept: Kept,
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
    let context = input.context();
    let dt = context.dt;
    let n = params.substeps.max(1);
    let h = dt / n as f64;
    let bounce_speed = context.bounce_speed;
    // Speculative rows: anything a body could reach within the step at the bounce speed,
    // and at least a millimetre (the rows' separations are tracked within the step).
    let margin = (bounce_speed * dt).max(1e-3);
    // Last step's rows carried over while the bodies barely move (`kept`), else detected.
    let carried = match input.recorded {
        None => scratch
            .kept
            .carry(input.bodies, input.before, states, margin, contacts),
        Some(_) => None,
    };
    let touching = carried.unwrap_or_else(|| {
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
    });
    if !touching {
        contacts.clear();
        scratch.warm.clear();
        scratch.kept.ended_at(states);
        return None;
    }
    let potential = |i: usize, x: &Vector3<f64>| {
        input
            .gravity
            .map_or(0.0, |g| -input.bodies[i].mass * g.dot(x))
    };
    let total = |states: &[State]| {
        let mut e = Energy::default();
        for (i, s) in states.iter().enumerate() {
            let k = kinetic_energy_with(
                &input.bodies[i],
                &derive(&input.bodies[i], s).inv_inertia_world,
                &s.linear_momentum,
                &s.angular_momentum,
            );
            let v = potential(i, &s.position);
            e = e + Energy {
                kinetic: k,
                potential: v,
                total: k + v,
            };
        }
        e
    };
    let before = total(states);

    // The bodies in contact, as solver bodies at the start of the step.
    let Scratch {
        rows,
        runs,
        kicks,
        bodies,
        motions,
        places,
        flight,
        slot,
        members,
        warm,
        ..
    } = scratch;
    slot.clear();
    slot.resize(states.len(), usize::MAX);
    members.clear();
    bodies.clear();
    places.clear();
    flight.clear();
    let inv = n as f64;
    for c in contacts.iter() {
        for b in std::iter::once(c.body).chain(c.other_body()) {
            if slot[b] != usize::MAX {
                continue;
            }
            slot[b] = bodies.len();
            members.push(b);
            let body = &input.bodies[b];
            let start = &input.before[b];
            let free = &states[b];
            let k0 = derive(body, start);
            let k_free = derive(body, free);
            flight.push((
                free.linear_momentum * body.inv_mass,
                k_free.angular_velocity,
                k_free.inv_inertia_world,
            ));
            let q_free = free.orientation.quaternion();
            bodies.push(SolverBody {
                v: start.linear_momentum * body.inv_mass,
                omega: k0.angular_velocity,
                l: start.angular_momentum,
                inv_mass: body.inv_mass,
                inv_inertia: k0.inv_inertia_world,
                touched: false,
            });
            places.push(Placement {
                position: start.position,
                q: start.orientation.quaternion(),
                detected_position: free.position,
                detected_inverse: q_free.inverse(),
                turned: Matrix3::zeros(),
                dv: (free.linear_momentum - start.linear_momentum) * body.inv_mass / inv,
                dl: (free.angular_momentum - start.angular_momentum) / inv,
                dw: k0.inv_inertia_world * ((free.angular_momentum - start.angular_momentum) / inv),
            });
        }
    }
    let kinetic_free: f64 = members
        .iter()
        .zip(flight.iter())
        .map(|(&b, (_, _, inv_inertia))| {
            let s = &states[b];
            kinetic_energy_with(
                &input.bodies[b],
                inv_inertia,
                &s.linear_momentum,
                &s.angular_momentum,
            )
        })
        .sum();
    for p in places.iter_mut() {
        p.turned = turned(p);
    }

    let hertz = params.hertz_at(dt);
    let dynamic = Softness::new(hertz, params.damping_ratio, h);
    let fixed = Softness::new(2.0 * hertz, params.damping_ratio, h);
    let friction = context.friction;
    rows.clear();
    for c in contacts.iter_mut() {
        // Levers as solver-body indices.
        let b = c.other_body().map(|b| slot[b]);
        let a = (slot[c.body], &c.lever);
        let other = b.map(|b| (b, &c.lever_other));
        let axis = |d: Vector3<f64>| {
            let mut axis = Axis::new(d, a, other, bodies);
            axis.with_inverse();
            axis
        };
        let normal = axis(c.normal);
        let (t1, t2) = tangents(&c.normal);
        let tangents = [axis(t1), axis(t2)];
        let against_fixed = b.is_none_or(|b| bodies[b].inv_mass == 0.0);
        // The last step's per-sub-step impulse at the same feature and point.
        let w = warm.find(c).unwrap_or_else(Vector3::zeros);
        let lambda = w.dot(&c.normal).max(0.0);
        let mut lambda_tangent = [w.dot(&t1), w.dot(&t2)];
        clamp_disk(&mut lambda_tangent, friction * lambda);
        rows.push(Row {
            normal,
            tangents,
            lever: c.lever,
            lever_other: c.lever_other,
            separation: -c.depth,
            gap: 0.0,
            approach: 0.0,
            soft: if against_fixed { fixed } else { dynamic },
            lambda,
            lambda_tangent,
            max_lambda: 0.0,
            applied: [0.0; 3],
        });
        c.denominator = normal.k;
    }
    runs.clear();
    for (i, row) in rows.iter().enumerate() {
        let (a, b) = (row.normal.a.body, row.normal.b.map(|e| e.body));
        match runs.last_mut() {
            Some(run) if run.a == a && run.b == b => run.rows.1 = i + 1,
            _ => runs.push(Run {
                a,
                b,
                rows: (i, i + 1),
            }),
        }
    }
    motions.clear();
    motions.extend(bodies.iter().map(|s| Motion {
        v: s.v,
        omega: s.omega,
        inv_mass: s.inv_mass,
    }));

    // The approach is measured at the free flight's velocities (what the contact meets).
    for (row, c) in rows.iter_mut().zip(contacts.iter()) {
        let (v, omega, _) = &flight[slot[c.body]];
        let mut u = v + omega.cross(&c.lever);
        if let Some(b) = c.other_body() {
            let (v, omega, _) = &flight[slot[b]];
            u -= v + omega.cross(&c.lever_other);
        }
        row.approach = u.dot(&c.normal);
        row.gap = row.separation_now(places);
    }

    // An impact (a row meeting faster than the bounce speed) gets IMPACT_SWEEPS sweeps per
    // sub-step: one Gauss–Seidel sweep over a face's 4 coupled rows leaves part of a fast
    // approach, which then goes deep (or, for a thin body, through).
    let impact = rows.iter().any(|row| row.approach < -bounce_speed);
    let passes = if impact { IMPACT_SWEEPS } else { 1 };
    kicks.clear();
    kicks.resize(motions.len(), (Vector3::zeros(), Vector3::zeros()));
    for substep in 0..n {
        for ((m, s), (p, kick)) in motions
            .iter_mut()
            .zip(bodies.iter_mut())
            .zip(places.iter().zip(kicks.iter_mut()))
        {
            m.v += p.dv;
            s.l += p.dl;
            m.omega += p.dw;
            // The warm start of a later sub-step: what the contacts did to the body over the
            // last one (module doc); `kick` keeps the motion before it until the sub-step ends.
            let start = (m.v, m.omega);
            m.v += kick.0;
            m.omega += kick.1;
            *kick = start;
        }
        if substep == 0 {
            each_row(runs, rows, motions, |row, a, b| {
                let [t1, t2] = &row.tangents;
                Motion::push(&row.normal, row.lambda, a, b);
                Motion::push(t1, row.lambda_tangent[0], a, b);
                Motion::push(t2, row.lambda_tangent[1], a, b);
            });
        }
        for _ in 0..passes {
            sweep(runs, rows, motions, friction, h, true);
        }
        for (s, p) in motions.iter().zip(places.iter_mut()) {
            p.position += s.v * h;
            let w = s.omega * (0.5 * h);
            let dq = Quaternion::new(0.0, w.x, w.y, w.z) * p.q.into_inner();
            p.q = UnitQuaternion::new_normalize(p.q.into_inner() + dq);
            p.turned = turned(p);
        }
        for row in rows.iter_mut() {
            row.gap = row.separation_now(places);
        }
        for _ in 0..passes {
            sweep(runs, rows, motions, friction, h, false);
        }
        for (m, kick) in motions.iter().zip(kicks.iter_mut()) {
            *kick = (m.v - kick.0, m.omega - kick.1);
        }
        for row in rows.iter_mut() {
            row.applied[0] += row.lambda;
            row.applied[1] += row.lambda_tangent[0];
            row.applied[2] += row.lambda_tangent[1];
        }
    }
    // Restitution, once, from the approach the contact met (Poisson: e·λ at most).
    let restitution = context.restitution;
    if restitution > 0.0 {
        each_row(runs, rows, motions, |row, a, b| {
            if row.approach >= -bounce_speed || row.max_lambda == 0.0 {
                return;
            }
            let u = Motion::rate(&row.normal, a, b);
            let j = -row.normal.inv_k * (u + restitution * row.approach);
            let new = (row.lambda + j).max(0.0);
            let change = new - row.lambda;
            row.lambda = new;
            Motion::push(&row.normal, change, a, b);
            row.applied[0] += change;
        });
    }
    // The motions back into the solver bodies: v, ω, and L from each row's impulses.
    for (s, m) in bodies.iter_mut().zip(motions.iter()) {
        s.v = m.v;
        s.omega = m.omega;
    }
    for row in rows.iter() {
        let axes = [&row.normal, &row.tangents[0], &row.tangents[1]];
        for (axis, &total) in axes.into_iter().zip(row.applied.iter()) {
            bodies[axis.a.body].l += axis.a.rd * total;
            if let Some(e) = &axis.b {
                bodies[e.body].l += e.rd * total;
            }
        }
    }

    // Back into the states, the kinetic energy capped at the free flight's.
    for ((&b, s), p) in members.iter().zip(bodies.iter()).zip(places.iter()) {
        if s.fixed() {
            continue; // a fixed body does not move
        }
        let state = &mut states[b];
        state.position = p.position;
        state.orientation = match state.orientation {
            Orientation::Matrix(_) => Orientation::Matrix(p.q.to_rotation_matrix().into_inner()),
            Orientation::Quaternion(_) => Orientation::Quaternion(p.q),
        };
        state.linear_momentum = s.v * input.bodies[b].mass;
        state.angular_momentum = s.l;
    }
    let kinetic_of = |states: &[State]| -> f64 {
        members
            .iter()
            .map(|&b| {
                let s = &states[b];
                kinetic_energy_with(
                    &input.bodies[b],
                    &derive(&input.bodies[b], s).inv_inertia_world,
                    &s.linear_momentum,
                    &s.angular_momentum,
                )
            })
            .sum()
    };
    // The cap keeps the linear momentum: only the motion relative to the moving members'
    // common barycenter is scaled, K = K_cm + K_rel → K_cm + s² K_rel (module doc, "Energy").
    let moving = |b: &&usize| input.bodies[**b].inv_mass > 0.0;
    let mass: f64 = members
        .iter()
        .filter(moving)
        .map(|&b| input.bodies[b].mass)
        .sum();
    for _ in 0..4 {
        let kinetic = kinetic_of(states);
        if kinetic <= kinetic_free || mass == 0.0 {
            break;
        }
        let momentum: Vector3<f64> = members
            .iter()
            .filter(moving)
            .map(|&b| states[b].linear_momentum)
            .sum();
        let v_cm = momentum / mass;
        let k_cm = 0.5 * mass * v_cm.norm_squared();
        let k_rel = kinetic - k_cm;
        let scale = if k_rel > 0.0 && kinetic_free > k_cm {
            ((kinetic_free - k_cm) / k_rel).sqrt() * (1.0 - 4.0 * f64::EPSILON)
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

    // Store: the step's impulses on the contacts, the last sub-step's for the next warm start
    // (none after a bounce: it says nothing about the next step's load).
    for (c, row) in contacts.iter_mut().zip(rows.iter()) {
        c.normal_velocity = row.approach;
        let [t1, t2] = &row.tangents;
        c.impulse = row.normal.d * row.applied[0] + t1.d * row.applied[1] + t2.d * row.applied[2];
    }
    warm.store(
        contacts
            .iter()
            .zip(rows.iter())
            .filter(|(_, row)| row.approach >= -bounce_speed)
            .map(|(c, row)| {
                let [t1, t2] = &row.tangents;
                let j = row.normal.d * row.lambda
                    + t1.d * row.lambda_tangent[0]
                    + t2.d * row.lambda_tangent[1];
                (c, j)
            }),
    );
    contacts.retain(|c| c.depth > 0.0 || c.impulse != Vector3::zeros());
    scratch.kept.ended_at(states);
    let after = total(states);
    Some(EnergyChange { before, after })
}

/// One sweep over the rows: the soft, biased solve (`biased`) or the rigid relax.
fn sweep(
    runs: &[Run],
    rows: &mut [Row],
    motions: &mut [Motion],
    friction: f64,
    h: f64,
    biased: bool,
) {
    each_row(runs, rows, motions, |row, a, b| {
        let s = row.gap;
        let (bias, mass_scale, impulse_scale) = if s > 0.0 {
            (s / h, 1.0, 0.0)
        } else if biased {
            let soft = row.soft;
            (
                (soft.bias_rate * s).max(-MAX_PUSH),
                soft.mass_scale,
                soft.impulse_scale,
            )
        } else {
            (0.0, 1.0, 0.0)
        };
        let u = Motion::rate(&row.normal, a, b);
        let j = -row.normal.inv_k * mass_scale * (u + bias) - impulse_scale * row.lambda;
        let new = (row.lambda + j).max(0.0);
        let change = new - row.lambda;
        row.lambda = new;
        row.max_lambda = row.max_lambda.max(new);
        if change != 0.0 {
            Motion::push(&row.normal, change, a, b);
        }
        if friction > 0.0 {
            let bound = friction * row.lambda;
            let [t1, t2] = &row.tangents;
            let old = row.lambda_tangent;
            let slip = Motion::relative(a, b, &row.lever, &row.lever_other);
            let mut new = [
                old[0] - t1.inv_k * t1.d.dot(&slip),
                old[1] - t2.inv_k * t2.d.dot(&slip),
            ];
            clamp_disk(&mut new, bound);
            let step = [new[0] - old[0], new[1] - old[1]];
            if step != [0.0; 2] {
                // Both tangents at once: Δv_A = (t₁ s₁ + t₂ s₂)/M_A, Δω_A = I_A⁻¹(r_A×t₁) s₁ + …
                let p = t1.d * step[0] + t2.d * step[1];
                a.v += p * a.inv_mass;
                a.omega += t1.a.w * step[0] + t2.a.w * step[1];
                if let (Some(e1), Some(e2)) = (&t1.b, &t2.b) {
                    b.v -= p * b.inv_mass;
                    b.omega += e1.w * step[0] + e2.w * step[1];
                }
                row.lambda_tangent = new;
            }
        }
    });
}

/// Scales a tangent impulse into the disk of radius `bound`.
fn clamp_disk(t: &mut [f64; 2], bound: f64) {
    let size = (t[0] * t[0] + t[1] * t[1]).sqrt();
    if size > bound {
        let scale = if size > 0.0 { bound / size } else { 0.0 };
        *t = [t[0] * scale, t[1] * scale];
    }
}

/// The rotation since the detection pose, minus 𝟙.
fn turned(s: &Placement) -> Matrix3<f64> {
    (s.q * s.detected_inverse).to_rotation_matrix().into_inner() - Matrix3::identity()
}
