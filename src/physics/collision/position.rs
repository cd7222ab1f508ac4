//! The position fix after the `impulse` response's velocities: where the bodies end the step.
//!
//! # No creep: advance with the corrected velocity
//!
//! The integrate phase advanced every body with the velocity it had *before* the contacts
//! acted: a body at rest on a slope slid by `½ g_t dt²` (`rk4`) or `g_t dt²` (symplectic
//! Euler) in that step, and cancelling its velocity afterwards does not bring it back — it
//! creeps down the slope at every step. So a body the contacts acted on, and that did not
//! bounce, ends the step where its corrected velocity takes it from the start of the step:
//!
//! ```text
//! x_{n+1} = x_n + dt · (v_{n+1} + ½ P (v_n − v_{n+1}))       (the rotation is kept)
//! P = the projection across the body's contact normals (what is left of a vector once its
//!     parts along the normals, made orthonormal, are taken out)
//! ```
//!
//! Across the normals (along the surface) this is the trapezoid rule, dt (v_n + v_{n+1})/2:
//! exact when the velocity changes linearly, as rolling or sliding down a slope does, so the
//! work of gravity m g·Δx equals the kinetic energy gained — a ball rolling without slipping
//! keeps its energy. Advancing with v_{n+1} alone (velocity-level time stepping) would lose
//! ½ M_eff a² dt² a step (M_eff = M + I/r²): 4.0 mJ/s for a 1 kg ball rolling on 20° at
//! dt = 1 ms, first order in dt. Along the normals it stays dt · v_{n+1}, which the
//! speculative contacts make exact (a landing body stops at the surface, not half a step
//! inside it). A body held by static friction has `v_n = v_{n+1} = 0` and stays exactly
//! where it was. The
//! contacts' depths move with the bodies: `d ← d − n·(Δx_A − Δx_B)`. A bouncing body keeps
//! the integrator's position (re-advancing it with its rebound velocity would lift it by
//! `2 |u| dt` at every bounce, energy from nothing).
//!
//! The rotation is the integrator's, from the ω before the contacts acted. Turning the body
//! back by what the contacts changed was tried and measured (2026-12-06, branch
//! `wt-posfix-turn`). Turned by `c dt Δω` (Δω = I⁻¹ ΔL, c = 1 or ½), lesson 41's wall with the
//! ball first stops rocking (largest rise of E in a step 3.9e-5 → 2e-13 J), but what the
//! impulses were solved for at the integrator's pose no longer holds at the new one: a
//! spinning top's Jellett integral, kept to 1.5e-7 of itself by this order (kick at the pose
//! of the drift), moves by 3.6e-5 (c = ½) to 7.3e-5 (c = 1), its precession goes 1.80202 →
//! 1.80234–1.80262 rad/s (slow root 1.802051), and lesson 37's domino changes its first-order
//! errors in kind (c = 1: the edge creeps back). Turned only over the part of the step the
//! contacts stopped (`s dt Δω`, s = −Δω·ω/|ω|² in [0, 1]), those hold, but a turn made after
//! detection can drive corners the contacts did not see into their supports: a run of the
//! same wall in the lesson's order then raised E by 6.1e-4 J in a step.
//!
//! # Penetration removed by translation
//!
//! What penetration is left is removed by *moving* the bodies, never by biasing velocities (a
//! velocity bias — Baumgarte — turns penetration into kinetic energy and makes resting bodies
//! jitter). The bodies move by the mass-weighted shortest translations that separate every
//! contact (Hildreth's method, Gauss–Seidel on the multipliers):
//!
//! ```text
//! minimise ½ Σ_b M_b |Δx_b|²   subject to   nᵢ·(Δx_A − Δx_B) ≥ dᵢ
//! M_b Δx_b = Σ_{i: b is A} μᵢ nᵢ − Σ_{i: b is B} μᵢ nᵢ,   μᵢ ≥ 0
//! μᵢ ← max(0, μᵢ + (dᵢ − nᵢ·(Δx_A − Δx_B)) / kᵢ),        kᵢ = 1/M_A + 1/M_B
//! ```
//!
//! B is the row's solver body entry ([`Contact::other`]); a static one (an obstacle's entry,
//! or a fixed body: 1/M = 0, it never moves) is no end, so its terms drop and a body against
//! the ground obstacle and against a fixed slab take the same path, bit for bit. Rows with
//! two moving ends are solved directly (below); rows against static things only by the
//! sweeps. (Measured when a fixed B stopped being an end, 2026-12-06: a body touching fixed
//! bodies only, which took the direct solve before, moves by round-off: over 1000–2000 steps
//! of a box at 50 m/s onto a fixed plate, a cube on a fixed ball, on a fixed table, and into
//! a table–wall corner, |Δx| ≤ 1.5e-10 m, |Δq| ≤ 5.5e-10, |Δv| ≤ 6.9e-9 m/s, |ΔE| ≤ 1.2e-9 J;
//! no lesson has such a contact.)
//!
//! The answer is unique, so it does not depend on the contact order (projecting onto one
//! half-space after the other would: two radial normals on a sphere would push the body
//! sideways); for one body on the ground it is exactly `max dᵢ · n`. Between two bodies,
//! `M_A Δx_A + M_B Δx_B = 0`: their common barycenter does not move. A translation changes
//! neither P nor L, so no kinetic energy, and along the contact normals only, so a body at
//! rest on a face cannot creep sideways. (Rotating the body instead would change `I⁻¹_world`
//! and so `½ L·I⁻¹L`.)
//!
//! # Several bodies: the same answer, solved directly
//!
//! Rows of one pair of bodies with the same normal (a face manifold's 3–4 points) constrain
//! the same translation: only the deepest one counts, so they merge into one row of depth
//! `max dᵢ`, exactly. What is left — one row per pair in a stack — is solved at once with the
//! rows that penetrate as the active set: `B μ = d`, `B_ij = Σ_shared b (±nᵢ)·(±nⱼ)/M_b`
//! (`envelope`); a row the answer leaves penetrating joins the set and it is solved again (a
//! cube pushed up pushes the one above), a row whose μ comes out negative leaves it (a pair
//! the others' push-outs already separate: in a pyramid, a cube lifted by one of its two
//! supports). Accepted when every μ ≥ 0 and every row is separated — the optimality
//! conditions of the minimisation above, so the same unique answer the sweeps converge to;
//! otherwise (after [`PASSES_MAX`] changes, and for a single body, which the sweeps finish
//! in one or two) Hildreth's sweeps run. Hildreth on a
//! stack of n bodies converges by a factor about cos²(π/(n+1)) a sweep: hundreds of sweeps
//! for 10 cubes.

use super::warm::FastMap;
use super::{moves, Contact};
use crate::physics::body::Body;
use crate::physics::envelope::{Envelope, Pivots};
use crate::physics::state::State;
use nalgebra::Vector3;
use std::collections::hash_map::Entry;

/// Most merged rows the direct push-out takes on (a stack of 10 cubes has 10, a pyramid of
/// 20 rows about 400; only the system's envelope is stored, see [`Envelope`]).
pub const DIRECT_MAX: usize = 4096;

/// Largest envelope (stored entries of [`Envelope`]) the direct push-out takes on.
pub const ENVELOPE_MAX: usize = 1 << 20;

/// Up to this many contacts the rows are merged by a scan, above it through a hash map.
pub const MERGE_SCAN_MAX: usize = 32;

/// At most this many changes of the direct push-out's active set before the sweeps run.
pub const PASSES_MAX: usize = 64;

/// At most this many Gauss–Seidel sweeps of the push-out.
pub const MAX_SWEEPS: usize = 200;

/// Buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    multipliers: Vec<f64>,
    shifts: Vec<Vector3<f64>>,
    /// Per contact: B's end in the fix, if it moves (`Fix::other`).
    others: Vec<Option<usize>>,
    depths: Vec<f64>,
    /// Per body: orthonormal contact normals and how many.
    normals: Vec<([Vector3<f64>; 3], usize)>,
    /// The direct solve: merged rows (first contact, depth), the active ones, the system.
    merged: Vec<(usize, f64)>,
    /// Where each pair (A, B's solver body entry) and normal sits in `merged` (the merge in
    /// O(1) per contact).
    merged_at: FastMap<(usize, usize, [u64; 3]), usize>,
    active: Vec<usize>,
    system: Envelope,
}

/// What the position fix reads: the bodies, their states at the start of the step, dt.
pub struct Fix<'a> {
    pub bodies: &'a [Body],
    pub before: &'a [State],
    pub dt: f64,
}

impl Fix<'_> {
    /// B's end in the fix: its solver body entry ([`Contact::other`]) when it moves. A fixed
    /// body and an obstacle's static entry are the world (1/M = 0, no shift): no end.
    #[inline]
    fn other(&self, c: &Contact) -> Option<usize> {
        moves(self.bodies, c.other).then_some(c.other)
    }

    /// The work the push-out of the current depths would do against gravity (≥ 0), J: the
    /// response pays it from the bounce. `potential(b, x)` is body b's potential energy at x.
    pub fn lift(
        &self,
        contacts: &[Contact],
        states: &[State],
        potential: &dyn Fn(usize, &Vector3<f64>) -> f64,
        scratch: &mut Scratch,
    ) -> f64 {
        scratch.depths.clear();
        scratch.depths.extend(contacts.iter().map(|c| c.depth));
        self.push_out(contacts, scratch);
        let mut work = 0.0;
        for (b, (state, shift)) in states.iter().zip(&scratch.shifts).enumerate() {
            if *shift != Vector3::zeros() {
                work += potential(b, &(state.position + shift)) - potential(b, &state.position);
            }
        }
        work.max(0.0)
    }

    /// Moves the bodies (module doc): bodies marked `advanced` go from their start-of-step
    /// position with their new velocity, then every body is pushed out of what it still
    /// penetrates.
    pub fn apply(
        &self,
        contacts: &[Contact],
        states: &mut [State],
        advanced: &[bool],
        scratch: &mut Scratch,
    ) {
        let mut moved = false;
        scratch.shifts.clear();
        scratch.shifts.resize(states.len(), Vector3::zeros());
        // Up to three orthonormal contact normals per body (the directions the trapezoid
        // leaves out: module doc).
        scratch.normals.clear();
        scratch
            .normals
            .resize(states.len(), ([Vector3::zeros(); 3], 0));
        for c in contacts {
            for b in std::iter::once(c.body).chain(self.other(c)) {
                let (basis, count) = &mut scratch.normals[b];
                let mut r = c.normal;
                for e in &basis[..*count] {
                    r -= e * e.dot(&r);
                }
                if *count < 3 && r.norm() > 1e-6 {
                    basis[*count] = r.normalize();
                    *count += 1;
                }
            }
        }
        for (b, state) in states.iter_mut().enumerate() {
            if advanced[b] {
                let body = &self.bodies[b];
                let v1 = state.linear_momentum * body.inv_mass;
                let mut along = self.before[b].linear_momentum * body.inv_mass - v1;
                let (basis, count) = &scratch.normals[b];
                for e in &basis[..*count] {
                    along -= e * e.dot(&along);
                }
                let x = self.before[b].position + (v1 + along / 2.0) * self.dt;
                scratch.shifts[b] = x - state.position;
                state.position = x;
                moved = true;
            }
        }
        scratch.depths.clear();
        scratch.depths.extend(contacts.iter().map(|c| {
            if !moved {
                return c.depth;
            }
            let mut delta = scratch.shifts[c.body];
            if let Some(other) = self.other(c) {
                delta -= scratch.shifts[other];
            }
            c.depth - c.normal.dot(&delta)
        }));
        self.push_out(contacts, scratch);
        for (state, shift) in states.iter_mut().zip(&scratch.shifts) {
            state.position += shift;
        }
    }

    /// The mass-weighted shortest translations for `scratch.depths` (module doc), into
    /// `scratch.shifts`.
    fn push_out(&self, contacts: &[Contact], scratch: &mut Scratch) {
        scratch.shifts.clear();
        scratch.shifts.resize(self.bodies.len(), Vector3::zeros());
        let deepest = scratch.depths.iter().copied().fold(0.0, f64::max);
        if deepest <= 0.0 {
            return;
        }
        let tolerance = 1e-12 * (1.0 + deepest);
        // Rows between two moving bodies are solved directly; rows against the world only
        // (static ends: obstacles, fixed bodies) by the sweeps, which finish them in one or two.
        // A step whose Bs are all static (a body on the ground) needs no list of B's ends.
        if !contacts.iter().any(|c| self.other(c).is_some()) {
            return self.sweep_out(contacts, scratch, tolerance, |_| None);
        }
        let mut others = std::mem::take(&mut scratch.others);
        others.clear();
        others.extend(contacts.iter().map(|c| self.other(c)));
        if !self.push_out_directly(contacts, &others, scratch, tolerance) {
            self.sweep_out(contacts, scratch, tolerance, |i| others[i]);
        }
        scratch.others = others;
    }

    /// Hildreth's sweeps (module doc) for `scratch.depths`, into `scratch.shifts`; `other(i)`
    /// is contact i's B end when it moves ([`Fix::other`]).
    fn sweep_out(
        &self,
        contacts: &[Contact],
        scratch: &mut Scratch,
        tolerance: f64,
        other: impl Fn(usize) -> Option<usize>,
    ) {
        let Scratch {
            multipliers,
            shifts,
            depths,
            ..
        } = scratch;
        shifts.fill(Vector3::zeros());
        multipliers.clear();
        multipliers.resize(contacts.len(), 0.0);
        let inv_mass = |b: usize| self.bodies[b].inv_mass;
        for _ in 0..MAX_SWEEPS {
            let mut largest: f64 = 0.0;
            for (i, ((c, mu), depth)) in contacts
                .iter()
                .zip(multipliers.iter_mut())
                .zip(depths.iter())
                .enumerate()
            {
                let other = other(i);
                let mut separation = shifts[c.body];
                let mut k = inv_mass(c.body);
                if let Some(other) = other {
                    separation -= shifts[other];
                    k += inv_mass(other);
                }
                let new = (*mu + (depth - c.normal.dot(&separation)) / k).max(0.0);
                let change = new - *mu;
                if change != 0.0 {
                    shifts[c.body] += c.normal * (change * inv_mass(c.body));
                    if let Some(other) = other {
                        shifts[other] -= c.normal * (change * inv_mass(other));
                    }
                    *mu = new;
                    largest = largest.max((change * k).abs());
                }
            }
            if largest <= tolerance {
                break;
            }
        }
    }

    /// The push-out solved directly (module doc), into `scratch.shifts`; false (shifts left
    /// at zero) when no active set of penetrating rows gives the answer.
    fn push_out_directly(
        &self,
        contacts: &[Contact],
        others: &[Option<usize>],
        scratch: &mut Scratch,
        tolerance: f64,
    ) -> bool {
        let Scratch {
            shifts,
            depths,
            merged,
            merged_at,
            active,
            system,
            ..
        } = scratch;
        // One row per pair and normal (bit for bit), with the deepest depth, in the order of
        // their first contacts.
        merged.clear();
        merged_at.clear();
        for (i, (c, &depth)) in contacts.iter().zip(depths.iter()).enumerate() {
            if contacts.len() <= MERGE_SCAN_MAX {
                // Few contacts: a scan is cheaper than hashing.
                let same = merged.iter_mut().find(|(j, _)| {
                    let o = &contacts[*j];
                    o.body == c.body && o.other == c.other && o.normal == c.normal
                });
                match same {
                    Some((_, d)) => *d = d.max(depth),
                    None => merged.push((i, depth)),
                }
                continue;
            }
            // +0.0 and −0.0 compare equal: one key for both.
            let bits = c.normal.map(|x| (x + 0.0).to_bits());
            match merged_at.entry((c.body, c.other, [bits.x, bits.y, bits.z])) {
                Entry::Occupied(at) => {
                    let d = &mut merged[*at.get()].1;
                    *d = d.max(depth);
                }
                Entry::Vacant(slot) => {
                    slot.insert(merged.len());
                    merged.push((i, depth));
                }
            }
        }
        if merged.len() > DIRECT_MAX {
            return false;
        }
        active.clear();
        active.extend((0..merged.len()).filter(|&r| merged[r].1 > 0.0));
        let inv_mass = |b: usize| self.bodies[b].inv_mass;
        // The ends of contact i that move: (body, sign of n on it), A then B.
        let ends = |i: usize| {
            [Some((contacts[i].body, 1.0)), others[i].map(|b| (b, -1.0))]
                .into_iter()
                .flatten()
        };
        // Each pass adds rows, takes out pulling ones, or ends: a cube pushed up pushes the
        // next one, so a stack of n takes up to n passes.
        for _ in 0..=merged.len().min(PASSES_MAX) {
            let m = active.len();
            system.reset(m);
            for p in 0..m {
                let (i, depth) = merged[active[p]];
                let ci = &contacts[i];
                system.rhs[p] = depth;
                system.fill_row(p, [Some(ci.body), others[i]], |q| {
                    let j = merged[active[q]].0;
                    let cj = &contacts[j];
                    let mut sum = None;
                    for (a, sa) in ends(i) {
                        for (b, sb) in ends(j) {
                            if a == b {
                                let term = sa * sb * ci.normal.dot(&cj.normal) * inv_mass(a);
                                sum = Some(sum.unwrap_or(0.0) + term);
                            }
                        }
                    }
                    sum
                });
                if system.stored() > ENVELOPE_MAX {
                    return false;
                }
            }
            let Some(mu) = system.solve(Pivots::Regularised) else {
                return false;
            };
            if mu.iter().any(|&x| x < 0.0) {
                // Out: the rows pulling (a pair that the others' push-outs already separate).
                let mut p = 0;
                active.retain(|_| {
                    p += 1;
                    mu[p - 1] >= 0.0
                });
                continue;
            }
            shifts.fill(Vector3::zeros());
            for (p, &x) in mu.iter().enumerate() {
                let i = merged[active[p]].0;
                let c = &contacts[i];
                for (b, sign) in ends(i) {
                    shifts[b] += c.normal * (sign * x * inv_mass(b));
                }
            }
            // A merged row left penetrating joins the active set (kept in row order).
            let before = active.len();
            for (r, &(i, depth)) in merged.iter().enumerate() {
                let c = &contacts[i];
                let mut separation = shifts[c.body];
                if let Some(other) = others[i] {
                    separation -= shifts[other];
                }
                if c.normal.dot(&separation) < depth - tolerance
                    && active[..before].binary_search(&r).is_err()
                {
                    active.push(r);
                }
            }
            if active.len() == before {
                // Every merged row holds, so does every row it stands for.
                return true;
            }
            active.sort_unstable();
        }
        shifts.fill(Vector3::zeros());
        false
    }
}
