//! `joint_correction = "projection"`: after a step, positions back onto C = 0, then velocities
//! onto J u = 0, each mass-weighted (the smallest change in the metric W⁻¹ that satisfies the
//! constraints, linearised):
//!
//! ```text
//! positions   repeat: (J W Jᵀ) μ = −C;  x += μ·J_lin / m;  q ← exp(I⁻¹_world J_angᵀ μ) q
//!             until max |C| < 1e-12 (at most 10 Newton steps; one or two after a normal step)
//! velocities  repeat: (J W Jᵀ) μ = −J u;  P += J_linᵀ μ;  L += J_angᵀ μ
//!             until max |J u| < 1e-12 (one solve with K here: J u is linear in u)
//! ```
//!
//! **A nearby factor.** The step's last evaluation of f factored K̃ = J W Jᵀ at its own stage
//! (rk4: X + dt k₃, O(dt²) from the step's end; a kick–drift–kick composition: at the end's
//! positions). The first position pass and the velocity passes solve with it instead of
//! factoring K here: a chord iteration, which converges by ‖1 − K K̃⁻¹‖ ~ |δx|/ℓ per pass
//! (δx the distance between the two configurations, ℓ the lever arms: about 1e-5 for rk4 at
//! dt = 1e-3), to the same tolerances, so the corrected state is the same to them. A pass
//! that leaves |C| ≥ 1e-12 is followed by Newton passes with K here; velocities still off
//! after three chord passes are solved with K here.
//!
//! Returns the velocity impulse each joint applied to its body A (its share of the reaction,
//! impulse / dt in `--joint`).

use super::chain::{Chain, Nearby, Solved, Wanted};
use super::rows::{rate, rows_of, Pose, Row};
use super::solve::{multipliers, Inverse, Solver};
use super::{turn, Links};
use crate::physics::body::Body;
use crate::physics::derive::derive;
use crate::physics::effects::Loads;
use crate::physics::energy::{kinetic_energy_at, kinetic_energy_with};
use crate::physics::state::{Orientation, State};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// Reused buffers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Buffers {
    rows: Vec<Row>,
    poses: Vec<Pose>,
    inverse: Vec<Inverse>,
    rhs: Vec<f64>,
    solver: Solver,
    /// Per body, Σ μ lin and Σ μ ang of a pass; a hinge chain's reduced solve: its move
    /// (Δx, θ).
    moves: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// A chain of ball and hinge joints: its compact rows (`chain`), used instead of `rows`
    /// when `chained`; per body and per joint, Σ μ Jᵀ of a pass.
    chain: Chain,
    chained: bool,
    moved: Vec<Loads>,
    reactions: Vec<Loads>,
    /// `shake`: the rows and inverse masses at the step's start.
    directions: Vec<Row>,
    start_inverse: Vec<Inverse>,
    /// Each body's kinetic energy at the states [`project`] started from
    /// ([`Buffers::kinetic_before`]).
    kinetic: Vec<f64>,
    /// Each body's orientation at the last build of the last [`project`] (empty until one
    /// has finished): `poses`' R and `inverse`'s I⁻¹_world are derive's at them
    /// ([`Buffers::derived`]).
    orientations: Vec<Orientation>,
}

impl Buffers {
    /// Body `i`'s R and I⁻¹_world from the last projection's last build, if its orientation
    /// is still `orientation` to the bit: derive's R and I⁻¹_world are functions of the
    /// orientation alone (and of the body, which a world keeps), so they are the numbers
    /// `derive` would compute, and the next step's derive phase takes them
    /// (`World::derive_phase`: a step after a projection derives no rotation again).
    #[inline(always)]
    pub fn derived(
        &self,
        i: usize,
        orientation: &Orientation,
    ) -> Option<(&Matrix3<f64>, &Matrix3<f64>)> {
        let kept = self.orientations.get(i)?;
        let same = match (kept, orientation) {
            (Orientation::Quaternion(a), Orientation::Quaternion(b)) => {
                let (a, b) = (a.coords, b.coords);
                (0..4).all(|k| a[k].to_bits() == b[k].to_bits())
            }
            (Orientation::Matrix(a), Orientation::Matrix(b)) => {
                (0..9).all(|k| a[k].to_bits() == b[k].to_bits())
            }
            _ => false,
        };
        same.then(|| (&self.poses[i].r, &self.inverse[i].inertia))
    }

    /// Each body's kinetic energy `½ M v·v + ½ ω·L` at the states the last [`project`] started
    /// from, with its first build's I⁻¹_world: `energy::kinetic_energy`'s arithmetic on the
    /// same I⁻¹_world (both `derive`'s), so the same bits, without deriving each body again.
    pub fn kinetic_before(&self) -> &[f64] {
        &self.kinetic
    }

    /// Each body's kinetic energy at `states`, which must be the states the last [`project`]
    /// left: its last build was at their positions (the velocity passes change only the
    /// momenta), so its I⁻¹_world is theirs; the same bits as `energy::kinetic_energy`.
    pub fn kinetic_after<'a>(
        &'a self,
        bodies: &'a [Body],
        states: &'a [State],
    ) -> impl Iterator<Item = f64> + 'a {
        kinetic(bodies, states, &self.inverse)
    }
}

/// Each body's kinetic energy at `states` from its I⁻¹_world in `inverse`.
#[inline(always)]
fn kinetic<'a>(
    bodies: &'a [Body],
    states: &'a [State],
    inverse: &'a [Inverse],
) -> impl Iterator<Item = f64> + 'a {
    bodies
        .iter()
        .zip(states)
        .zip(inverse)
        .map(|((body, s), inv)| {
            kinetic_energy_with(body, &inv.inertia, &s.linear_momentum, &s.angular_momentum)
        })
}

/// The factor the velocity pass solves with first.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Held {
    /// The nearby factor (the positions' chord pass used it, or no pass ran).
    Nearby,
    /// The positions' last Newton factor, whose pass corrected less than [`REUSE_BELOW`].
    Own,
    /// None: K is factored here.
    Anew,
}

/// The rows at `states`, with their velocities.
#[inline(always)]
fn build_rows(links: &Links, bodies: &[Body], states: &[State], b: &mut Buffers) {
    joint_rows(
        links,
        bodies,
        states,
        (&mut b.poses, &mut b.inverse, &mut b.rows),
    );
    b.chained = false;
}

/// The rows at `states`, with their velocities: a chain's compact rows when the joints are a
/// chain of ball and hinge joints (`chain`), else rows.
#[inline(always)]
fn build(links: &Links, bodies: &[Body], states: &[State], b: &mut Buffers) {
    poses_of(bodies, states, (&mut b.poses, &mut b.inverse));
    b.chained = b.chain.build_for_projection(&links.joints, &b.poses);
    b.rows.clear();
    if !b.chained {
        rows_into(links, &b.poses, &mut b.rows);
    }
}

/// How many rows the last build has.
#[inline(always)]
fn count(b: &Buffers) -> usize {
    if b.chained {
        b.chain.rows()
    } else {
        b.rows.len()
    }
}

/// The chain's Σ μ Jᵀ per body into `b.moved` (force: Σ μ lin, torque: Σ μ ang) and per
/// joint (its share on A) added to `reactions`.
#[inline(always)]
fn chain_moves(b: &mut Buffers, reactions: Option<&mut [Loads]>) {
    b.moved.clear();
    b.moved.resize(b.poses.len(), Loads::default());
    let reactions: &mut [Loads] = match reactions {
        Some(r) => r,
        None => {
            b.reactions.clear();
            b.reactions.resize(b.chain.links.len(), Loads::default());
            &mut b.reactions
        }
    };
    b.chain.apply(&b.rhs, &mut b.moved, reactions);
}

/// Each body's pose and inverse mass at `states`, and the joints' rows there, with their
/// velocities (the rows the projection and the contact pass both start from).
#[inline(always)]
pub(super) fn joint_rows(
    links: &Links,
    bodies: &[Body],
    states: &[State],
    (poses, inverse, rows): (&mut Vec<Pose>, &mut Vec<Inverse>, &mut Vec<Row>),
) {
    poses_of(bodies, states, (poses, inverse));
    rows.clear();
    rows_into(links, poses, rows);
}

/// Each body's pose and inverse mass at `states`.
#[inline(always)]
fn poses_of(
    bodies: &[Body],
    states: &[State],
    (poses, inverse): (&mut Vec<Pose>, &mut Vec<Inverse>),
) {
    poses.clear();
    inverse.clear();
    for (body, state) in bodies.iter().zip(states) {
        let k = derive(body, state);
        poses.push(Pose {
            x: state.position,
            r: k.rotation,
            v: k.velocity,
            w: k.angular_velocity,
        });
        inverse.push(Inverse {
            mass: body.inv_mass,
            inertia: k.inv_inertia_world,
        });
    }
}

/// The joints' rows at `poses`, appended to `rows`.
#[inline(always)]
fn rows_into(links: &Links, poses: &[Pose], rows: &mut Vec<Row>) {
    for (index, joint) in links.joints.iter().enumerate() {
        let pb = joint.b.map_or(&Pose::WORLD, |j| &poses[j]);
        rows_of(joint, index, &poses[joint.a], pb, rows);
    }
}

/// Projects `states` onto the joints' constraints; `impulses` receives each joint's velocity
/// impulse on its body A (force: N·s, torque: N·m·s). `nearby`: the solver of the step's last
/// evaluation of f (module doc), or None. Keeps each body's kinetic energy before and after
/// for the energy ledger ([`Buffers::kinetic_before`], [`Buffers::kinetic_after`]).
pub fn project(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    impulses: &mut Vec<Loads>,
    b: &mut Buffers,
    nearby: Option<Nearby>,
) {
    #[cfg(target_arch = "x86_64")]
    if crate::physics::simd::avx2() {
        // SAFETY: the CPU has AVX2.
        return unsafe { project_avx2(links, bodies, states, impulses, b, nearby) };
    }
    project_plain(links, bodies, states, impulses, b, nearby);
}

/// [`project`] compiled with AVX2 (no fused multiply–add: the same bits; `physics::simd`).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn project_avx2(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    impulses: &mut Vec<Loads>,
    b: &mut Buffers,
    nearby: Option<Nearby>,
) {
    project_plain(links, bodies, states, impulses, b, nearby);
}

/// [`project`] for any CPU.
#[inline(always)]
fn project_plain(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    impulses: &mut Vec<Loads>,
    b: &mut Buffers,
    mut nearby: Option<Nearby>,
) {
    impulses.clear();
    impulses.resize(links.joints.len(), Loads::default());
    b.orientations.clear();
    if links.joints.is_empty() {
        return;
    }
    let held = positions(links, bodies, states, b, nearby.as_mut());
    // The velocity passes leave the positions as the last build found them.
    b.orientations.extend(states.iter().map(|s| s.orientation));
    velocities(states, impulses, held, nearby, b);
}

/// `symplectic-euler`'s projection (SHAKE, then RATTLE's velocity half): the positions are put
/// on C = 0 along the rows at the step's start `start`, W J(q₀)ᵀ μ, and the momenta take the
/// same correction over dt — which makes it the constraint force of the step itself,
/// `P₁ = P₀ + dt (F + J(q₀)ᵀ Λ)`, `x₁ = x₀ + dt P₁/m` with Λ such that C(x₁) = 0 — then the
/// velocities onto J(q₁) u = 0. Symplectic Euler with SHAKE and this velocity projection is
/// symplectic on the constraint manifold (Hairer, Lubich, Wanner, *Geometric Numerical
/// Integration*, VII.1): its energy error stays bounded instead of growing. The fixed
/// directions J(q₀) make the Newton iteration a chord method: it converges by about |v| dt / L
/// per pass (a few passes).
pub fn shake(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    start: &[State],
    dt: f64,
    impulses: &mut Vec<Loads>,
    b: &mut Buffers,
) {
    impulses.clear();
    impulses.resize(links.joints.len(), Loads::default());
    b.orientations.clear();
    if links.joints.is_empty() {
        return;
    }
    build_rows(links, bodies, start, b);
    let mut directions = std::mem::take(&mut b.directions);
    directions.clone_from(&b.rows);
    let mut start_inverse = std::mem::take(&mut b.start_inverse);
    start_inverse.clone_from(&b.inverse);
    for pass in 0..=20 {
        build_rows(links, bodies, states, b);
        let worst = b.rows.iter().map(|r| r.error.abs()).fold(0.0, f64::max);
        if worst < 1e-12 || pass == 20 {
            break;
        }
        b.rhs.clear();
        b.rhs.extend(b.rows.iter().map(|r| -r.error));
        multipliers(&directions, &start_inverse, &mut b.rhs, &mut b.solver);
        for (row, &mu) in directions.iter().zip(&b.rhs) {
            shift(
                states,
                &start_inverse,
                row.a(),
                &row.lin_a(),
                &row.ang_a(),
                mu,
            );
            let impulse = mu / dt;
            states[row.a()].linear_momentum += row.lin_a() * impulse;
            states[row.a()].angular_momentum += row.ang_a() * impulse;
            impulses[row.owner].force += row.lin_a() * impulse;
            impulses[row.owner].torque += row.ang_a() * impulse;
            if let Some(j) = row.b() {
                shift(states, &start_inverse, j, &row.lin_b(), &row.ang_b(), mu);
                states[j].linear_momentum += row.lin_b() * impulse;
                states[j].angular_momentum += row.ang_b() * impulse;
            }
        }
    }
    b.directions = directions;
    b.start_inverse = start_inverse;
    velocities(states, impulses, Held::Anew, None, b);
}

/// Positions onto C = 0 by Newton's method on the rows at the current positions, its first
/// pass a chord step with the `nearby` factor when there is one (module doc). Returns which
/// factor the velocity pass starts from.
#[inline(always)]
fn positions(
    links: &Links,
    bodies: &[Body],
    states: &mut [State],
    b: &mut Buffers,
    mut nearby: Option<&mut Nearby>,
) -> Held {
    // The rows are built with velocities: the last build, on C = 0, serves the velocity pass.
    let mut held = Held::Nearby;
    for pass in 0..=10 {
        build(links, bodies, states, b);
        if pass == 0 {
            b.kinetic.clear();
            // The build's poses hold v = P/m and ω = I⁻¹_world L at `states`, as
            // `kinetic_energy_with` would compute them.
            let at = bodies.iter().zip(states.iter()).zip(&b.poses);
            b.kinetic.extend(
                at.map(|((body, s), p)| kinetic_energy_at(body, &p.v, &p.w, &s.angular_momentum)),
            );
        }
        let worst = if b.chained {
            b.chain.errors(&mut b.rhs)
        } else {
            let worst = b.rows.iter().map(|r| r.error.abs()).fold(0.0, f64::max);
            b.rhs.clear();
            b.rhs.extend(b.rows.iter().map(|r| -r.error));
            worst
        };
        if worst < 1e-12 || pass == 10 {
            break;
        }
        let rows = count(b);
        let mut solved = match nearby.as_deref_mut() {
            Some(s) if pass == 0 => s.again_for(rows, &mut b.rhs, Wanted::Moves(&mut b.moves)),
            _ => Solved::Not,
        };
        if solved == Solved::Not {
            solved = solve_for(b, None);
            held = if worst < REUSE_BELOW {
                Held::Own
            } else {
                Held::Anew
            };
        }
        if solved == Solved::Answered {
            move_bodies(states, &b.moves);
        } else {
            shift_bodies(states, b);
        }
    }
    held
}

/// (J W Jᵀ) μ = `b.rhs` at the last build, μ over `b.rhs`, the factor kept in `b.solver`
/// (or in the chain's reduced factor: then, instead of μ, each body's move into `b.moves`,
/// or with `impulses` each body's Jᵀ μ into `b.moved` and the joints' shares into
/// `impulses`: `chain::Chain::solve_for`).
#[inline(always)]
fn solve_for(b: &mut Buffers, impulses: Option<&mut [Loads]>) -> Solved {
    if b.chained {
        let wanted = match impulses {
            None => Wanted::Moves(&mut b.moves),
            Some(impulses) => Wanted::Impulses(&mut b.moved, impulses),
        };
        b.chain
            .solve_for(&b.inverse, &mut b.rhs, &mut b.solver, wanted)
    } else {
        multipliers(&b.rows, &b.inverse, &mut b.rhs, &mut b.solver);
        Solved::Multipliers
    }
}

/// Every body moved by its (Δx, θ) of a hinge chain's reduced solve: `x += Δx`,
/// `q ← exp(θ) q`.
#[inline(always)]
fn move_bodies(states: &mut [State], moves: &[(Vector3<f64>, Vector3<f64>)]) {
    for (s, (dx, theta)) in states.iter_mut().zip(moves) {
        s.position += dx;
        s.orientation = match s.orientation {
            Orientation::Quaternion(q) => Orientation::Quaternion(small_turn(&q, theta)),
            Orientation::Matrix(m) => {
                Orientation::Matrix(nalgebra::Rotation3::from_scaled_axis(*theta).into_inner() * m)
            }
        };
    }
}

/// `exp(θ) q` as [`turn`], with exp(θ) = (cos a, sin a θ/|θ|), a = |θ|/2, by its Taylor
/// series when a < 1e-3 (cos a = 1 − a²/2 + a⁴/24, sin a / a = 1 − a²/6 + a⁴/120: the first
/// terms left out are below a⁶/720 < 2e-21), without the trigonometric calls.
#[inline(always)]
fn small_turn(q: &UnitQuaternion<f64>, theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    let a2 = 0.25 * theta.norm_squared();
    if a2 >= 1e-6 {
        return turn(q, theta);
    }
    let c = 1.0 - a2 * (0.5 - a2 / 24.0);
    let s = 0.5 * (1.0 - a2 * (1.0 / 6.0 - a2 / 120.0));
    let e = Quaternion::new(c, theta.x * s, theta.y * s, theta.z * s);
    UnitQuaternion::new_unchecked(e * q.quaternion())
}

/// Every body moved by the position multipliers μ in `b.rhs` at once:
/// `x += Σ μ lin / m`, `q ← exp(I⁻¹_world Σ μ ang) q` over the rows on it (one turn per
/// body: the rows' turns, each ~|C|, compose to their sum up to ~|C|², far below round-off
/// once |C| < 1e-8).
#[inline(always)]
fn shift_bodies(states: &mut [State], b: &mut Buffers) {
    if b.chained {
        chain_moves(b, None);
        for (i, m) in b.moved.iter().enumerate() {
            shift(states, &b.inverse, i, &m.force, &m.torque, 1.0);
        }
        return;
    }
    b.moves.clear();
    b.moves
        .resize(states.len(), (Vector3::zeros(), Vector3::zeros()));
    for (row, &mu) in b.rows.iter().zip(&b.rhs) {
        let m = &mut b.moves[row.a()];
        m.0 += row.lin_a() * mu;
        m.1 += row.ang_a() * mu;
        if let Some(j) = row.b() {
            let m = &mut b.moves[j];
            m.0 += row.lin_b() * mu;
            m.1 += row.ang_b() * mu;
        }
    }
    for (i, (lin, ang)) in b.moves.iter().enumerate() {
        shift(states, &b.inverse, i, lin, ang, 1.0);
    }
}

/// The velocity pass may start from the positions' last Newton factor when that pass
/// corrected less than this (m or rad): K then differs from the one at the corrected
/// positions by ~1e-9 relative.
const REUSE_BELOW: f64 = 1e-9;

/// The velocity passes with a held factor before K is factored here.
const CHORD_PASSES: usize = 3;

/// Velocities onto J u = 0 at the last build's rows (which must be at `states`' positions):
/// with the `held` factor (the nearby one or the positions' last, module doc) pass by pass
/// until max |J u| < 1e-12 — each pass leaves J u⁺ = (1 − K K̃⁻¹) J u⁻ —, and with K here
/// when there is none or it has not converged in [`CHORD_PASSES`].
#[inline(always)]
fn velocities(
    states: &mut [State],
    impulses: &mut [Loads],
    held: Held,
    nearby: Option<Nearby>,
    b: &mut Buffers,
) {
    rates_into(b);
    // The own factor is taken out of `b` while its passes run (and put back).
    let (mut own, mut own_reduced) = match held {
        Held::Own => (
            std::mem::take(&mut b.solver),
            std::mem::take(&mut b.chain.reduced),
        ),
        _ => Default::default(),
    };
    let rows = count(b);
    let factor = match held {
        Held::Own => Some(Nearby {
            solver: &mut own,
            reduced: &mut own_reduced,
        }),
        Held::Nearby => nearby,
        Held::Anew => None,
    }
    .filter(|s| s.holds(rows));
    let done = factor.is_some_and(|mut solver| {
        (0..CHORD_PASSES).any(|_| {
            let wanted = Wanted::Impulses(&mut b.moved, impulses);
            let solved = solver.again_for(rows, &mut b.rhs, wanted);
            commit(states, impulses, b, solved);
            refresh(states, b);
            rates_into(b);
            b.rhs.iter().fold(0.0_f64, |m, r| m.max(r.abs())) < 1e-12
        })
    });
    if held == Held::Own {
        b.solver = own;
        b.chain.reduced = own_reduced;
    }
    if done {
        return;
    }
    let solved = solve_for(b, Some(impulses));
    commit(states, impulses, b, solved);
}

/// A velocity pass's solve applied: P += J_linᵀ μ, L += J_angᵀ μ, from μ in `b.rhs`
/// ([`apply`]) or, when a reduced solve [`Solved::Answered`], from each body's Jᵀ μ in
/// `b.moved` (its reactions already in `impulses`).
#[inline(always)]
fn commit(states: &mut [State], impulses: &mut [Loads], b: &mut Buffers, solved: Solved) {
    if solved != Solved::Answered {
        apply(states, impulses, b);
        return;
    }
    for (state, m) in states.iter_mut().zip(&b.moved) {
        state.linear_momentum += m.force;
        state.angular_momentum += m.torque;
    }
}

/// `b.rhs` = −J u of every row at the poses' velocities.
#[inline(always)]
fn rates_into(b: &mut Buffers) {
    if b.chained {
        b.chain.rates(&b.poses, &mut b.rhs);
        return;
    }
    b.rhs.clear();
    b.rhs.extend(b.rows.iter().map(|r| {
        let pb = r.b().map_or(&Pose::WORLD, |j| &b.poses[j]);
        -rate(r, &b.poses[r.a()], pb)
    }));
}

/// The velocity multipliers μ in `b.rhs` applied: P += J_linᵀ μ, L += J_angᵀ μ on each row's
/// bodies, the joint's share on A into `impulses`.
#[inline(always)]
fn apply(states: &mut [State], impulses: &mut [Loads], b: &mut Buffers) {
    if b.chained {
        chain_moves(b, Some(impulses));
        for (state, m) in states.iter_mut().zip(&b.moved) {
            state.linear_momentum += m.force;
            state.angular_momentum += m.torque;
        }
        return;
    }
    for (row, &mu) in b.rows.iter().zip(&b.rhs) {
        states[row.a()].linear_momentum += row.lin_a() * mu;
        states[row.a()].angular_momentum += row.ang_a() * mu;
        impulses[row.owner].force += row.lin_a() * mu;
        impulses[row.owner].torque += row.ang_a() * mu;
        if let Some(j) = row.b() {
            states[j].linear_momentum += row.lin_b() * mu;
            states[j].angular_momentum += row.ang_b() * mu;
        }
    }
}

/// The poses' velocities from the states' momenta (positions unchanged since the last build):
/// v = P/m, ω = I⁻¹_world L.
#[inline(always)]
fn refresh(states: &[State], b: &mut Buffers) {
    for ((pose, state), inv) in b.poses.iter_mut().zip(states).zip(&b.inverse) {
        pose.v = state.linear_momentum * inv.mass;
        pose.w = inv.inertia * state.angular_momentum;
    }
}

/// Body `i` moved by one row's position multiplier μ: `x += μ lin / m`,
/// `q ← exp(I⁻¹_world ang μ) q`.
#[inline(always)]
pub(super) fn shift(
    states: &mut [State],
    inverse: &[Inverse],
    i: usize,
    lin: &Vector3<f64>,
    ang: &Vector3<f64>,
    mu: f64,
) {
    let s = &mut states[i];
    s.position += lin * (mu * inverse[i].mass);
    let theta = inverse[i].inertia * (ang * mu);
    s.orientation = match s.orientation {
        Orientation::Quaternion(q) => Orientation::Quaternion(turn(&q, &theta)),
        Orientation::Matrix(m) => {
            Orientation::Matrix(nalgebra::Rotation3::from_scaled_axis(theta).into_inner() * m)
        }
    };
}
