//! `splitting`: a geometric integrator — kick, drift, and the free rotation split into exact
//! rotations about the principal axes (Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107,
//! 1997; Strang composition, second order).
//!
//! ```text
//! kick   (P, L) ← K(dt/2)(P, L)      x and R held
//! drift  x ← x + dt P / M
//!        free rotation for dt with L fixed, split as  R₁(dt/2) R₂(dt/2) R₃(dt) R₂(dt/2) R₁(dt/2):
//!          Rᵢ(h): Π = (q E)⁻¹ L  (angular momentum in the principal frame, E the principal axes),
//!                 θ = h Πᵢ / Iᵢ,   q E ← q E · rotᵢ(θ)
//! kick   (P, L) ← K(dt/2)(P, L)      at the new x and R
//!
//! K(h): constant loads (gravity):   P ← P + h F,  L ← L + h τ                  (exact)
//!       velocity-dependent (drag):  P ← P + h F(P + h/2 F, L + h/2 τ), same for L  (midpoint)
//! ```
//!
//! Each sub-flow `Rᵢ` is the *exact* motion of a body whose energy is `Πᵢ²/2Iᵢ`: a rotation about
//! principal axis i at the constant rate Πᵢ/Iᵢ. It moves the body but not L, so torque-free L is
//! untouched — |L| is kept to the last bit — and, being a composition of exact Hamiltonian flows,
//! the method is symplectic: the energy error oscillates with amplitude O(dt²) and never drifts.
//! Drag has no exact kick in general; the midpoint rule keeps each kick's local error O(dt³), so
//! the composition stays second order with drag too (a plain Euler kick would make it first
//! order in the drag term), at the price of one more evaluation of the effects per kick.
//!
//! When it wins: long runs, fast spins, tumbling near the separatrix, large steps (a spin about
//! the major axis stays put at dt = 1e-2 and beyond). When it does not: short runs where a few
//! digits more per step matter — `rk4` is fourth order and reaches a small error faster once dt
//! is small — and dissipative scenes (drag), where there is no conserved quantity to protect
//! and its second order buys less than `rk4`'s fourth.

use super::super::body::Body;
use super::super::effects::{Effects, Loads};
use super::super::state::{Orientation, State};
use super::super::system::System;
use super::system::{advance, Buffers, Composed, Composition, KickRule, Start};
use super::{normalize, quaternion_of};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "splitting",
        order: 2,
        summary: "kick–drift–kick with the free rotation split into exact rotations about the principal axes",
        keeps: "L exactly, energy bounded (symplectic)",
        rate: super::QUATERNION_RATE,
        formula: "splitting: kick P,L by dt/2; drift x; exact rotations about the principal axes; kick dt/2",
        colour: (150, 40, 170),
        position_factor: 0.5,
        exact_without_torque: false,
};

/// One kick–drift–kick step with the split free rotation over the whole system, in place.
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    let plan = Composition {
        kicks: &[0.5, 0.5],
        flows: &[1.0],
        kick: KickRule::Midpoint,
        order: 2,
    };
    advance(
        &Composed { plan, drift },
        system,
        states,
        start,
        dt,
        b,
    );
}

/// The free motion over `h` in place: x moves with P, the body turns by the split free
/// rotation of its L (which it keeps).
fn drift(body: &Body, state: &mut State, h: f64) {
    state.position += state.linear_momentum * (body.inv_mass * h);
    let q = free_rotation(body, &quaternion_of(state), &state.angular_momentum, h);
    state.orientation = Orientation::Quaternion(q);
}

/// The kick `K(h)`: (P, L) under the declared effects with x and R held; `loads` are those at
/// (P, L) and `inv_inertia_world` that of the held R.
#[inline]
pub(super) fn kick(
    body: &Body,
    effects: &Effects,
    (p, l): (Vector3<f64>, Vector3<f64>),
    inv_inertia_world: &Matrix3<f64>,
    loads: &Loads,
    h: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    if !effects.depends_on_velocity() {
        return (p + loads.force * h, l + loads.torque * h);
    }
    let (p_mid, l_mid) = (p + loads.force * (h / 2.0), l + loads.torque * (h / 2.0));
    let mid = effects.loads_at(body, &(p_mid * body.inv_mass), &(inv_inertia_world * l_mid));
    (p + mid.force * h, l + mid.torque * h)
}

/// The Strang-split free rotation over `dt` with world angular momentum `l`.
fn free_rotation(
    body: &Body,
    q: &UnitQuaternion<f64>,
    l: &Vector3<f64>,
    dt: f64,
) -> UnitQuaternion<f64> {
    let inertia = body.principal_moments;
    // Orientation of the principal frame, and L seen in it.
    let mut qp = *q.quaternion() * body.principal_axes.quaternion();
    let mut pi = UnitQuaternion::new_unchecked(qp).inverse_transform_vector(l);
    sub_rotation::<0>(&mut qp, &mut pi, &inertia, 0.5 * dt);
    sub_rotation::<1>(&mut qp, &mut pi, &inertia, 0.5 * dt);
    sub_rotation::<2>(&mut qp, &mut pi, &inertia, dt);
    sub_rotation::<1>(&mut qp, &mut pi, &inertia, 0.5 * dt);
    sub_rotation::<0>(&mut qp, &mut pi, &inertia, 0.5 * dt);
    normalize(qp * body.principal_axes.quaternion().conjugate())
}

/// The exact flow `Rᵢ(h)` of `Πᵢ²/2Iᵢ`: the principal frame turns about its axis `I` by
/// `θ = h Πᵢ/Iᵢ` (`qp ← qp ⊗ (cos θ/2, sin θ/2 eᵢ)`), and Π, seen from the turning frame, turns by
/// `−θ` (`Π ← rotᵢ(−θ) Π`; Πᵢ itself is unchanged, so the angle is exact).
///
/// With (i, j, k) cyclic and `(c, s) = (cos θ/2, sin θ/2)`, the product written out is
/// `w ← c w − s vᵢ,  vᵢ ← c vᵢ + s w,  vⱼ ← c vⱼ + s vₖ,  vₖ ← c vₖ − s vⱼ`, and
/// `sin θ = 2 s c`, `cos θ = c² − s²` (one `sin_cos` per sub-rotation).
#[inline(always)]
fn sub_rotation<const I: usize>(
    qp: &mut Quaternion<f64>,
    pi: &mut Vector3<f64>,
    inertia: &Vector3<f64>,
    h: f64,
) {
    let (j, k) = ((I + 1) % 3, (I + 2) % 3);
    let theta = h * pi[I] / inertia[I];
    let (s, c) = (theta / 2.0).sin_cos();
    // nalgebra stores a quaternion as (i, j, k, w).
    let v = &mut qp.coords;
    let (w, vi, vj, vk) = (v[3], v[I], v[j], v[k]);
    v[3] = c * w - s * vi;
    v[I] = c * vi + s * w;
    v[j] = c * vj + s * vk;
    v[k] = c * vk - s * vj;
    let (st, ct) = (2.0 * s * c, c * c - s * s);
    let (pj, pk) = (pi[j], pi[k]);
    pi[j] = ct * pj + st * pk;
    pi[k] = -st * pj + ct * pk;
}
