//! `impulse`: a physically based response with restitution e and Coulomb friction μ that never
//! adds kinetic energy (for 0 ≤ e ≤ 1, μ ≥ 0), whatever the number of contacts.
//!
//! # One contact
//!
//! A vertex at lever arm r from the barycenter, contact normal n (out of the obstacle). An
//! impulse j n there changes the momenta by `ΔP = j n`, `ΔL = r × (j n)`, so the normal velocity
//! of the point `u_n = (v + ω × r)·n` changes by `j·k` with
//!
//! ```text
//! k = 1/M + n·((I⁻¹(r×n)) × r) = 1/M + (r×n)·I⁻¹(r×n)       (the denominator, 1/kg)
//! j = −(1 + e) u_n / k                                      (Newton's law for one contact)
//! ```
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
//! 2. **Coulomb friction** (if μ > 0): two tangent impulses per contact, kept in the disk
//!    `|λ_t| ≤ μ λᵢ` with λᵢ from stage 1 (fixed bounds, so the feasible set is convex and fixed).
//!    The sweep updates the normal impulse as in stage 1, then both tangent impulses at once:
//!    the exact minimum of K over the contact's disk (`friction_update`). Still exact block
//!    minimisations of the same convex K over a convex set containing the current value: K
//!    still only goes down, and block coordinate descent reaches the unique minimising
//!    velocity whatever the order of the contacts.
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
//! # Position correction
//!
//! The penetration left by the step is removed by *moving* the body, never by biasing
//! velocities (a velocity bias — Baumgarte — turns penetration into kinetic energy and makes
//! resting bodies jitter). The body is translated by the shortest Δx with `nᵢ·Δx ≥ dᵢ` for
//! every contact (the unique shortest one, by Hildreth's method; for the ground alone,
//! `Δx = max dᵢ · y`). A translation
//! changes neither P nor L, so no kinetic energy, and along the contact normal only, so a body
//! at rest on a face cannot creep sideways. (Rotating the body instead would change
//! `I⁻¹_world` and so `½ L·I⁻¹L`.)

use super::detect::{inside, near, swept};
use super::{CollideInput, Contact, EnergyChange, Obstacle};
use crate::physics::derive::derive_with_rotation;
use crate::physics::snapshot::{kinetic_energy_with, Energy};
use crate::physics::state::State;
use nalgebra::{Matrix3, Vector3};

/// Contacts approaching slower than this many `|g| dt` do not bounce: one step of free fall
/// gives an approach speed of `|g| dt`, so a resting body is always below the threshold.
/// Vertices within `BOUNCE_STEPS·|g|·dt²` of a surface are speculative contacts.
pub const BOUNCE_STEPS: f64 = 3.0;

/// The sweeps stop when no impulse changed a contact velocity by more than this (m/s), plus the
/// same fraction of the fastest approach speed.
pub const TOLERANCE: f64 = 1e-10;

/// At most this many Gauss–Seidel sweeps per stage.
pub const MAX_SWEEPS: usize = 200;

/// One contact as the solver sees it.
#[derive(Debug, Clone, Copy, Default)]
struct Row {
    /// Unit normal n, r × n and I⁻¹(r × n), and k = 1/M + (r×n)·I⁻¹(r×n).
    normal: Direction,
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
}

/// A direction d at lever arm r: d, r × d, I⁻¹(r × d) and the effective inverse mass along it.
#[derive(Debug, Clone, Copy, Default)]
struct Direction {
    d: Vector3<f64>,
    rd: Vector3<f64>,
    w: Vector3<f64>,
    k: f64,
    /// 1/k, for the sweeps only: NaN until [`Direction::with_inverse`] (the direct solve, the
    /// usual resting step, never divides by k).
    inv_k: f64,
}

impl Direction {
    fn new(
        d: Vector3<f64>,
        lever: &Vector3<f64>,
        inv_inertia: &Matrix3<f64>,
        inv_mass: f64,
    ) -> Self {
        let rd = lever.cross(&d);
        let w = inv_inertia * rd;
        let k = inv_mass + rd.dot(&w);
        Direction {
            d,
            rd,
            w,
            k,
            inv_k: f64::NAN,
        }
    }

    /// Fills in 1/k.
    fn with_inverse(&mut self) {
        self.inv_k = 1.0 / self.k;
    }
}

/// The body's velocities while impulses are applied: v, ω and L (ω = I⁻¹ L kept in step).
#[derive(Debug, Clone, Copy)]
struct Motion {
    v: Vector3<f64>,
    omega: Vector3<f64>,
    l: Vector3<f64>,
    inv_mass: f64,
}

impl Motion {
    /// Velocity of the contact point along the direction: `d·v + (r×d)·ω`.
    fn along(&self, dir: &Direction) -> f64 {
        dir.d.dot(&self.v) + dir.rd.dot(&self.omega)
    }

    /// Applies the impulse j d at the contact point.
    fn apply(&mut self, j: f64, dir: &Direction) {
        self.v += dir.d * (j * self.inv_mass);
        self.l += dir.rd * j;
        self.omega += dir.w * j;
    }
}

/// Detects contacts (swept test, plus the speculative ones) and runs the response on `state`.
///
/// Returns the energy before and after (None when there was no contact: the state is unchanged).
pub fn respond(
    input: &CollideInput,
    state: &mut State,
    contacts: &mut Vec<Contact>,
) -> Option<EnergyChange> {
    let body = input.body;
    let rotation_now = state.orientation.matrix();
    // The start of the step, for the swept tests (the ground needs none).
    let swept_tests = input
        .obstacles
        .iter()
        .any(|o| !matches!(o, Obstacle::Ground { .. }));
    let rotation_before = if swept_tests {
        input.before.orientation.matrix()
    } else {
        Matrix3::identity()
    };
    let bounce_speed = input
        .gravity
        .map_or(0.0, |g| BOUNCE_STEPS * g.norm() * input.dt);
    // Vertices closer than this to a surface are speculative contacts (module doc).
    let margin = bounce_speed * input.dt;
    let mut speculative = false;
    for (index, obstacle) in input.obstacles.iter().enumerate() {
        for (vertex, r0) in body.points_body.iter().enumerate() {
            let b = state.position + rotation_now * r0;
            // The ground needs no sweep (see `detect`): skip the vertex's start point.
            let hit = if let Obstacle::Ground { .. } = obstacle {
                inside(obstacle, &b)
            } else {
                swept(
                    obstacle,
                    &(input.before.position + rotation_before * r0),
                    &b,
                )
            };
            let (depth, normal) = match hit {
                Some(hit) => (hit.depth, hit.normal),
                None => match near(obstacle, &b, margin) {
                    Some((gap, normal)) => {
                        speculative = true;
                        (-gap, normal)
                    }
                    None => continue,
                },
            };
            contacts.push(Contact {
                vertex,
                obstacle: index,
                point: b,
                depth,
                normal,
                lever: b - state.position,
                normal_velocity: 0.0,
                denominator: 0.0,
                impulse: Vector3::zeros(),
            });
        }
    }
    if !contacts.iter().any(|c| c.depth > 0.0) {
        // Nothing has touched: speculative contacts alone never act.
        contacts.clear();
        return None;
    }
    // I⁻¹_world exactly as the derive phase (and the energy panel) computes it.
    let inv_inertia = derive_with_rotation(body, state, rotation_now).inv_inertia_world;
    if speculative {
        // A vertex approaching at bouncing speed is left to touch and bounce next step.
        let v = state.linear_momentum * body.inv_mass;
        let omega = inv_inertia * state.angular_momentum;
        contacts.retain(|c| {
            c.depth > 0.0 || (v + omega.cross(&c.lever)).dot(&c.normal) >= -bounce_speed
        });
    }
    let kinetic = |s: &State| {
        kinetic_energy_with(body, &inv_inertia, &s.linear_momentum, &s.angular_momentum)
    };
    let potential = |x: &Vector3<f64>| input.gravity.map_or(0.0, |g| -body.mass * g.dot(x));
    let kinetic_before = kinetic(state);
    let potential_before = potential(&state.position);
    // The push-out depends on the geometry only: known before the velocities are solved, so
    // the work it does against gravity can be paid from the kinetic energy.
    let shift = push_out(contacts);
    let lift = (potential(&(state.position + shift)) - potential_before).max(0.0);
    let settings = Settings {
        restitution: input.model.restitution,
        friction: input.model.friction,
        bounce_speed,
        dt: input.dt,
        lift,
    };
    resolve(body.inv_mass, &inv_inertia, &settings, state, contacts);
    state.position += shift;
    // Round-off guard: K is quadratic in (P, L), so scaling both by √(K₀/K) gives K₀.
    let mut kinetic_after = kinetic(state);
    for _ in 0..4 {
        if kinetic_after <= kinetic_before {
            break;
        }
        let scale = (kinetic_before / kinetic_after).sqrt() * (1.0 - 4.0 * f64::EPSILON);
        state.linear_momentum *= scale;
        state.angular_momentum *= scale;
        kinetic_after = kinetic(state);
    }
    // Speculative contacts that were not needed are not contacts.
    if speculative {
        contacts.retain(|c| c.depth > 0.0 || c.impulse != Vector3::zeros());
    }
    let measured = |kinetic: f64, potential: f64| Energy {
        kinetic,
        potential,
        total: kinetic + potential,
    };
    Some(EnergyChange {
        before: measured(kinetic_before, potential_before),
        after: measured(kinetic_after, potential(&state.position)),
    })
}

/// What the velocity stages need besides the body and the contacts.
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

/// The velocity stages (module doc) on `state` for `contacts` (point, depth, normal and lever
/// filled in); fills in each contact's normal velocity, denominator and impulse.
fn resolve(
    inv_mass: f64,
    inv_inertia: &Matrix3<f64>,
    settings: &Settings,
    state: &mut State,
    contacts: &mut [Contact],
) {
    let Settings {
        restitution,
        friction,
        bounce_speed,
        dt,
        lift,
    } = *settings;
    let l = state.angular_momentum;
    let mut motion = Motion {
        v: state.linear_momentum * inv_mass,
        omega: inv_inertia * l,
        l,
        inv_mass,
    };
    // The energy the velocities may keep: K₀ less the push-out's work against gravity.
    let kinetic_allowed = motion.kinetic(inv_mass) - lift;
    let row = |c: &Contact| {
        let normal = Direction::new(c.normal, &c.lever, inv_inertia, inv_mass);
        Row {
            normal,
            lambda: 0.0,
            lambda_tangent: [0.0; 2],
            compression: 0.0,
            friction_bound: 0.0,
            lambda_restitution: 0.0,
            approach: motion.along(&normal),
            bias: (-c.depth).max(0.0) / dt,
        }
    };
    // The rows on the stack when they fit (the usual case: no allocation per step).
    let mut stack_rows = [Row::default(); DIRECT_MAX];
    let mut heap_rows = Vec::new();
    let rows: &mut [Row] = if contacts.len() <= DIRECT_MAX {
        for (slot, c) in stack_rows.iter_mut().zip(contacts.iter()) {
            *slot = row(c);
        }
        &mut stack_rows[..contacts.len()]
    } else {
        heap_rows.extend(contacts.iter().map(row));
        &mut heap_rows
    };
    let fastest = rows.iter().map(|r| -r.approach).fold(0.0, f64::max);
    let tolerance = TOLERANCE * (1.0 + fastest);

    // Stage 1: inelastic normal impulses, λ ≥ 0: the direct solve when it applies, else
    // projected Gauss–Seidel from λ = 0.
    if !direct_inelastic(rows, &mut motion, tolerance) {
        for row in rows.iter_mut() {
            row.normal.with_inverse();
        }
        for _ in 0..MAX_SWEEPS {
            let mut largest: f64 = 0.0;
            for row in rows.iter_mut() {
                largest = largest.max(normal_update(row, &mut motion));
            }
            if largest <= tolerance {
                break;
            }
        }
    }

    for row in rows.iter_mut() {
        row.compression = row.lambda;
    }

    // Stage 2: friction in the fixed disks |λ_t| ≤ μ λ, normal impulses still kept ≥ 0.
    // Skipped when no pushing contact slides (a body at rest): there is nothing to do.
    let sliding = |row: &Row, contact: &Contact| {
        let u = motion.v + motion.omega.cross(&contact.lever);
        row.lambda > 0.0
            && (u - contact.normal * u.dot(&contact.normal)).norm_squared() > tolerance * tolerance
    };
    let mut tangent_directions: Vec<[Direction; 2]> = Vec::new();
    if friction > 0.0 && rows.iter().zip(contacts.iter()).any(|(r, c)| sliding(r, c)) {
        for (row, contact) in rows.iter_mut().zip(contacts.iter()) {
            row.normal.with_inverse();
            row.friction_bound = friction * row.lambda;
            let (t1, t2) = tangents(&contact.normal);
            tangent_directions.push([
                Direction::new(t1, &contact.lever, inv_inertia, inv_mass),
                Direction::new(t2, &contact.lever, inv_inertia, inv_mass),
            ]);
        }
        for _ in 0..MAX_SWEEPS {
            let mut largest: f64 = 0.0;
            for (row, directions) in rows.iter_mut().zip(&tangent_directions) {
                let bound = row.friction_bound;
                largest = largest.max(normal_update(row, &mut motion));
                if bound == 0.0 {
                    continue;
                }
                let change = friction_update(row, directions, bound, &mut motion);
                largest = largest.max(change);
            }
            if largest <= tolerance {
                break;
            }
        }
    }

    // Stage 3: Poisson restitution e λ where the approach was fast, scaled so that K ≤ K₀.
    if restitution > 0.0 {
        let mut dv = Vector3::zeros();
        let mut dl = Vector3::zeros();
        let mut domega = Vector3::zeros();
        for row in rows.iter_mut() {
            if row.approach < -bounce_speed && row.compression > 0.0 {
                let j = restitution * row.compression;
                row.lambda_restitution = j;
                dv += row.normal.d * (j * inv_mass);
                dl += row.normal.rd * j;
                domega += row.normal.w * j;
            }
        }
        if dl != Vector3::zeros() || dv != Vector3::zeros() {
            // K(s) = a s² + b s + c along Λ_inelastic + s Λ_restitution.
            let a = 0.5 * (dv.norm_squared() / inv_mass + domega.dot(&dl));
            let b = dv.dot(&motion.v) / inv_mass + motion.omega.dot(&dl);
            let c = motion.kinetic(inv_mass);
            let scale = if a + b + c <= kinetic_allowed || a <= 0.0 {
                1.0
            } else {
                let slack = (kinetic_allowed - c).max(0.0);
                ((-b + (b * b + 4.0 * a * slack).sqrt()) / (2.0 * a)).clamp(0.0, 1.0)
            };
            motion.v += dv * scale;
            motion.l += dl * scale;
            motion.omega += domega * scale;
            for row in rows.iter_mut() {
                row.lambda_restitution *= scale;
            }
        }
    }

    state.linear_momentum = motion.v / inv_mass;
    state.angular_momentum = motion.l;
    for (index, (contact, row)) in contacts.iter_mut().zip(rows.iter()).enumerate() {
        contact.normal_velocity = row.approach;
        contact.denominator = row.normal.k;
        contact.impulse = row.normal.d * (row.lambda + row.lambda_restitution);
        if let Some([t1, t2]) = tangent_directions.get(index) {
            contact.impulse += t1.d * row.lambda_tangent[0] + t2.d * row.lambda_tangent[1];
        }
    }
}

/// Most contacts in a step to try the direct solve for.
pub const DIRECT_MAX: usize = 8;

/// The inelastic problem solved directly, when its answer is "every approaching contact
/// stops": with the approaching contacts as the active set, solve
///
/// ```text
/// (A + ε𝟙) λ = −u,   A_ij = nᵢ·nⱼ/M + (rᵢ×nᵢ)·I⁻¹(rⱼ×nⱼ),  ε = 1e-10 · max Aᵢᵢ
/// ```
///
/// by LDLᵀ (A is only semi-definite: 4 coplanar contacts constrain 3 motions; the tiny ε
/// picks the minimum-norm λ, which shares the load symmetrically whatever the vertex order).
/// The result is accepted only if it is the solution of the whole problem — every λᵢ ≥ 0 and
/// no contact, active or not, still approaching — so it is the same minimum of K that the
/// sweeps converge to, reached at once. Returns false (and changes nothing) otherwise.
fn direct_inelastic(rows: &mut [Row], motion: &mut Motion, tolerance: f64) -> bool {
    let mut active = [0usize; DIRECT_MAX];
    let mut m = 0;
    for (i, row) in rows.iter().enumerate() {
        if row.approach + row.bias < 0.0 {
            if m == DIRECT_MAX {
                return false;
            }
            active[m] = i;
            m += 1;
        }
    }
    if m == 0 {
        return true;
    }
    let mut a = [[0.0f64; DIRECT_MAX]; DIRECT_MAX];
    let mut rhs = [0.0f64; DIRECT_MAX];
    let mut largest: f64 = 0.0;
    for p in 0..m {
        let ni = &rows[active[p]].normal;
        rhs[p] = -motion.along(ni) - rows[active[p]].bias;
        for q in 0..=p {
            let nj = &rows[active[q]].normal;
            let value = ni.d.dot(&nj.d) * motion.inv_mass + ni.rd.dot(&nj.w);
            a[p][q] = value;
        }
        largest = largest.max(a[p][p]);
    }
    let epsilon = 1e-10 * largest;
    // A + ε𝟙 = L D Lᵀ (L unit lower triangular, in place below the diagonal; D kept as 1/Dₚ):
    // no square roots. wₖ = L_pk D_k for the row being factored.
    let mut inv_diagonal = [0.0f64; DIRECT_MAX];
    for p in 0..m {
        let mut w = [0.0f64; DIRECT_MAX];
        let mut pivot = a[p][p] + epsilon;
        for q in 0..p {
            let dot: f64 = w[..q].iter().zip(&a[q][..q]).map(|(x, y)| x * y).sum();
            w[q] = a[p][q] - dot;
            let l = w[q] * inv_diagonal[q];
            pivot -= w[q] * l;
            a[p][q] = l;
        }
        if pivot <= 0.0 {
            return false;
        }
        inv_diagonal[p] = 1.0 / pivot;
    }
    // L y = rhs, then Lᵀ λ = D⁻¹ y.
    let mut lambda = rhs;
    for p in 0..m {
        let dot: f64 = a[p][..p].iter().zip(&lambda[..p]).map(|(x, y)| x * y).sum();
        lambda[p] -= dot;
    }
    for p in (0..m).rev() {
        let dot: f64 = (p + 1..m).map(|k| a[k][p] * lambda[k]).sum();
        lambda[p] = lambda[p] * inv_diagonal[p] - dot;
        if lambda[p] < 0.0 {
            return false;
        }
    }
    let start = *motion;
    for p in 0..m {
        motion.apply(lambda[p], &rows[active[p]].normal);
    }
    if rows
        .iter()
        .any(|r| motion.along(&r.normal) + r.bias < -tolerance)
    {
        *motion = start;
        return false;
    }
    for p in 0..m {
        rows[active[p]].lambda = lambda[p];
    }
    true
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
/// (|x(ν)| decreases with ν: ν is found by bisection, keeping the feasible end.) Updating the
/// two tangent directions one at a time instead can stall on the disk's edge at a point that is
/// not the minimum, and where it stalls depends on the contact order. The step is taken only
/// if it does not raise K.
fn friction_update(
    row: &mut Row,
    directions: &[Direction; 2],
    bound: f64,
    motion: &mut Motion,
) -> f64 {
    let [t1, t2] = directions;
    let u = [motion.along(t1), motion.along(t2)];
    let (k1, k2, c) = (t1.k, t2.k, t1.rd.dot(&t2.w));
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
        // K x* once, then x(ν) = (K + ν𝟙)⁻¹ K x*.
        let kx = [
            k1 * target[0] + c * target[1],
            c * target[0] + k2 * target[1],
        ];
        let at = |nu: f64| {
            let (a, d) = (k1 + nu, k2 + nu);
            let det = a * d - c * c;
            [(d * kx[0] - c * kx[1]) / det, (a * kx[1] - c * kx[0]) / det]
        };
        let (mut low, mut high) = (0.0, k1.max(k2));
        while norm(at(high)) > bound {
            high *= 2.0;
        }
        for _ in 0..40 {
            let mid = 0.5 * (low + high);
            if norm(at(mid)) > bound {
                low = mid;
            } else {
                high = mid;
            }
        }
        at(high)
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
    motion.apply(step[0], t1);
    motion.apply(step[1], t2);
    (step[0].abs() * k1 + step[1].abs() * c.abs()).max(step[1].abs() * k2 + step[0].abs() * c.abs())
}

/// One projected Gauss–Seidel update of a contact's normal impulse; returns the change it made
/// to the contact's normal velocity (m/s).
fn normal_update(row: &mut Row, motion: &mut Motion) -> f64 {
    let dir = &row.normal;
    let new = (row.lambda - (motion.along(dir) + row.bias) * dir.inv_k).max(0.0);
    let change = new - row.lambda;
    if change == 0.0 {
        return 0.0;
    }
    row.lambda = new;
    motion.apply(change, dir);
    change.abs() * dir.k
}

impl Motion {
    /// `½ M v·v + ½ ω·L`.
    fn kinetic(&self, inv_mass: f64) -> f64 {
        0.5 * self.v.norm_squared() / inv_mass + 0.5 * self.omega.dot(&self.l)
    }
}

/// Two unit tangents completing n to an orthonormal basis.
fn tangents(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = n.cross(&helper).normalize();
    (t1, n.cross(&t1))
}

/// Moves the body by the shortest translation Δx with nᵢ·Δx ≥ dᵢ for every contact:
///
/// ```text
/// minimise ½|Δx|²  subject to  nᵢ·Δx ≥ dᵢ     →   Δx = Σ μᵢ nᵢ,  μᵢ ≥ 0
/// μᵢ ← max(0, μᵢ + dᵢ − nᵢ·Δx)                   (Hildreth's method: Gauss–Seidel on the μᵢ)
/// ```
///
/// The shortest Δx is unique, so it does not depend on the contact order (projecting onto one
/// half-space after the other would: two radial normals on a sphere would push the body
/// sideways). With one normal direction (the ground) it is exactly `max dᵢ · n`.
fn push_out(contacts: &[Contact]) -> Vector3<f64> {
    let mut shift = Vector3::zeros();
    let mut multipliers = [0.0f64; DIRECT_MAX];
    let mut extra = Vec::new();
    if contacts.len() > DIRECT_MAX {
        extra = vec![0.0f64; contacts.len()];
    }
    let multipliers: &mut [f64] = if extra.is_empty() {
        &mut multipliers[..contacts.len()]
    } else {
        &mut extra
    };
    let deepest = contacts.iter().map(|c| c.depth).fold(0.0, f64::max);
    for _ in 0..MAX_SWEEPS {
        let mut largest: f64 = 0.0;
        for (c, mu) in contacts.iter().zip(multipliers.iter_mut()) {
            let new = (*mu + c.depth - c.normal.dot(&shift)).max(0.0);
            let change = new - *mu;
            if change != 0.0 {
                shift += c.normal * change;
                *mu = new;
                largest = largest.max(change.abs());
            }
        }
        if largest <= 1e-12 * (1.0 + deepest) {
            break;
        }
    }
    shift
}
