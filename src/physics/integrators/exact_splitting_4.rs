//! `exact-splitting-4`: `exact-splitting`'s kicks and exact free rotations composed to fourth
//! order (Omelyan, Mryglod & Folk, Comput. Phys. Commun. 146, 2002: the optimised
//! "extended Forest–Ruth-like" coefficients, with the exact rotation in the role of their
//! force step).
//!
//! ```text
//! K(ξ dt) Φ((1−2λ)/2 dt) K(χ dt) Φ(λ dt) K((1 − 2(χ+ξ)) dt) Φ(λ dt) K(χ dt) Φ((1−2λ)/2 dt) K(ξ dt)
//! ξ = 0.1786178958448091,  λ = −0.2123418310626054,  χ = −0.06626458266981849
//! ```
//!
//! K is the exact kick and Φ the exact free flow (with the drift of x) of `exact-splitting`.
//! The composition is symmetric and satisfies the fourth-order conditions whichever of its two
//! flows plays which part; two of the rotations run backwards (λ < 0), which the exact flow does
//! as well as forwards. OMF report their optimised coefficients about ten times as efficient as
//! Yoshida's triple jump (w₁ = 1/(2 − 2^⅓), three flows) in their own roles; with the roles
//! swapped that factor is not measured here. Torque-free or under gravity alone it is exact like
//! `exact-splitting` (four times the work for nothing); with drag it is fourth order (the
//! observed slope is 3.99 in `tests/physics/exact_splitting.rs`).
//!
//! Coupled by joints, damped springs or drag, the kick is the whole system's, and its force
//! depends on the momenta (a rod pulls with m v²/L): the composition is of order 4 only if each
//! kick is accurate to O(dt⁵), so it is rk4 over (P, L) with x and R held there
//! (`system::rk4_kick`; the midpoint kick's O(dt³) made it order 2, or 3 after projection).
//! A pendulum measures 4.00 (`tests/commands/study_models.rs`).

use super::super::state::State;
use super::super::system::System;
use super::exact_splitting;
use super::system::{advance, Buffers, Composed, Composition, KickRule, Start};
use super::Descriptor;

/// Its descriptor (`super::Descriptor`).
pub(super) const DESCRIPTOR: Descriptor = Descriptor {
        name: "exact-splitting-4",
        order: 4,
        summary: "exact-splitting composed fourth order: five kicks, four exact free rotations (Omelyan–Mryglod–Folk)",
        keeps: "as exact-splitting; fourth order under drag",
        rate: super::QUATERNION_RATE,
        formula: "exact-splitting-4: kicks ξ,χ,1−2(ξ+χ),χ,ξ·dt around exact free rotations (1−2λ)/2,λ,λ,(1−2λ)/2·dt",
        colour: (120, 90, 20),
        position_factor: 0.5,
        exact_without_torque: true,
};

const XI: f64 = 0.178_617_895_844_809_1;
const LAMBDA: f64 = -0.212_341_831_062_605_4;
const CHI: f64 = -0.066_264_582_669_818_5;

/// Fractions of dt of the five kicks.
const KICKS: [f64; 5] = [XI, CHI, 1.0 - 2.0 * (CHI + XI), CHI, XI];
/// Fractions of dt of the four free rotations.
const FLOWS: [f64; 4] = [
    0.5 * (1.0 - 2.0 * LAMBDA),
    LAMBDA,
    LAMBDA,
    0.5 * (1.0 - 2.0 * LAMBDA),
];

/// One fourth-order step over the whole system, in place.
pub fn step(system: &System, states: &mut [State], start: &Start, dt: f64, b: &mut Buffers) {
    let plan = Composition {
        kicks: &KICKS,
        flows: &FLOWS,
        kick: KickRule::Exact,
        order: 4,
    };
    advance(
        &Composed {
            plan,
            drift: exact_splitting::drift,
        },
        system,
        states,
        start,
        dt,
        b,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fractions_add_up_to_one_step() {
        let kicks: f64 = KICKS.iter().sum();
        let flows: f64 = FLOWS.iter().sum();
        assert!((kicks - 1.0).abs() < 1e-15 && (flows - 1.0).abs() < 1e-15);
    }
}
