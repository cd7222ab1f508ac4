//! The energy ledger: where the energy of a world went since t = 0, so that only what no physics
//! accounts for is called drift.
//!
//! Gravity is in the energy itself (its potential `−M g·x`). The other effects move energy in or
//! out of the body, and each is booked where it acts:
//!
//! ```text
//! E(t) − E₀ = W_drag + ΔE_contacts + ΔE_springs + drift
//!
//! W_drag      = ∫ (F_drag·v + τ_drag·ω) dt = −∫ (k |v|² + k_a |ω|²) dt      ≤ 0
//!               booked per integrate phase by the corrected trapezoid rule (Hermite) on the
//!               step's own start and end states:
//!                 ½ dt (p₀ + p₁) + dt²/12 (ṗ₀ − ṗ₁)
//!               p = −(k |v|² + k_a |ω|²),  ṗ = −2 (k v·a + k_a ω·ω̇),
//!               a = F/M,  ω̇ = I⁻¹_world (τ − ω × L)   (from L̇ = τ and L = I_world ω)
//! ΔE_contacts = Σ over collide phases (E after the response − E before it)
//!               (the response's own measurement, `EnergyChange`, when it has one)
//! ΔE_springs  = energy stored in springs (none in a world of rigid bodies: absent)
//! W_motor     = Σ over the joints' motor rows, per step, λ (J u⁻ + J u⁺)/2: the kinetic
//!               energy the motor's impulse λ changes, exactly (`joints::drive`)
//! W_hand      = Σ over the hand's kicks (K after − K before): the work of the mouse's drag
//!               spring, exactly (`hand`)
//! drift       = the remainder: what the integrator itself created or destroyed
//! ```
//!
//! (`E − E₀` then also has `+ W_motor + W_hand`; a joint's limit stop is booked with the contacts.)
//!
//! The corrected trapezoid rule is fourth-order accurate (local error `dt⁵/720 · p⁽⁴⁾`), as
//! accurate as `rk4`, so the booked drag work never passes the quadrature's own error off as the
//! integrator's (the plain trapezoid, second order, would show a drift of `dt²/12 · Δṗ` on an
//! exact trajectory: 1e-4 J in lesson 9). For a first-order method the remainder is that
//! method's error: explicit Euler on `v̇ = −(k/M) v` keeps `(1 − h)² = 1 − 2h + h²` of the
//! energy per step, h = k dt/M, where the exact flow keeps `e^{−2h} = 1 − 2h + 2h² − …`; the
//! difference, `−h²` per step, is the drift. A body under drag alone, with linear drag k and angular drag k_a on an isotropic
//! inertia I, loses exactly
//!
//! ```text
//! E(t) = ½ M v₀² e^{−2kt/M} + ½ I ω₀² e^{−2 k_a t/I}        (the drag work is E(t) − E₀)
//! ```
//!
//! Contacts are booked as what they gave and what they took, separately: the divergence guard
//! ([`super::divergence`]) asks whether the body holds more energy than the scene ever
//! supplied, [`EnergyLedger::supplied`] = `E₀ + Σ max(0, ΔE_collide)`. Energy an integrator
//! creates and a contact then takes again (explicit Euler on a body at rest creates
//! `½ M g² dt²` per step, which the contact absorbs) is drift, and shown as such, but not a
//! runaway. The study measures its energy drift as the ledger's drift: one bookkeeping
//! everywhere.

use super::body::Body;
use super::derive::Kinematics;
use super::effects::{Effect, Effects};
use super::snapshot::Energy;
use nalgebra::Vector3;

/// Energy booked since t = 0, J. Part of a world's checkpoint, so stepping back restores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyLedger {
    /// E₀: the total energy at t = 0, J.
    pub initial: f64,
    /// W_drag: work done by drag since t = 0 (≤ 0), J.
    pub drag_work: f64,
    /// Energy the collide phases gave: Σ max(0, ΔE_collide) ≥ 0, J.
    pub contact_gain: f64,
    /// Energy the collide phases took: Σ min(0, ΔE_collide) ≤ 0, J.
    pub contact_loss: f64,
    /// Energy the joints' projection changed (numerical: an ideal joint does no work; still
    /// part of the drift, booked here to show how much of it the correction made), J.
    pub joint_correction: f64,
    /// W_motor: work done by the joints' motors since t = 0, J (`joints::drive`).
    pub motor_work: f64,
    /// W_hand: work done by the hand (the mouse's drag spring) since t = 0, J (`hand`).
    pub hand_work: f64,
    /// The part of it that gave energy: Σ max(0, ΔK_kick) ≥ 0, J (for `supplied`).
    pub hand_gain: f64,
}

/// The change of energy since t = 0, split by cause.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyBalance {
    /// E − E₀, J.
    pub change: f64,
    /// Work done by drag, J (None: the scene declares no drag).
    pub drag_work: Option<f64>,
    /// Energy taken (< 0) or given (> 0) by collision responses, J (None: no obstacles).
    pub contacts: Option<f64>,
    /// Energy stored in springs, J (None: no springs; cloths will fill it).
    pub springs: Option<f64>,
    /// Work done by the joints' motors, J (None: no motor).
    pub motor: Option<f64>,
    /// Work done by the hand (the mouse's drag spring), J (None: never held since t = 0).
    pub hand: Option<f64>,
    /// The remainder: the numerical drift of the integrator, J.
    pub drift: f64,
    /// drift / max(|E₀|, |K₀|): the drift relative to the scene's energy scale (0 when both are 0).
    pub relative_drift: f64,
}

/// The power of the declared drag at a state and its rate of change, W and W/s.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DragPower {
    /// `p = F_drag·v + τ_drag·ω = −(k |v|² + k_a |ω|²)`, W.
    pub power: f64,
    /// `ṗ = −2 (k v·a + k_a ω·ω̇)`, W/s.
    pub rate: f64,
}

/// The drag power at a state with derived kinematics `kinematics` and angular momentum L (0
/// without drag). The accelerations come from every declared effect: `a = F/M`,
/// `ω̇ = I⁻¹_world (τ − ω × L)`.
pub fn drag_power(
    body: &Body,
    effects: &Effects,
    kinematics: &Kinematics,
    angular_momentum: &Vector3<f64>,
) -> DragPower {
    let (v, w) = (&kinematics.velocity, &kinematics.angular_velocity);
    let loads = effects.loads_at(body, v, w);
    let acceleration = loads.force * body.inv_mass;
    let angular_acceleration =
        kinematics.inv_inertia_world * (loads.torque - w.cross(angular_momentum));
    let mut out = DragPower::default();
    for effect in effects.list() {
        if let Effect::Drag { linear, angular } = *effect {
            out.power -= linear * v.norm_squared() + angular * w.norm_squared();
            out.rate -=
                2.0 * (linear * v.dot(&acceleration) + angular * w.dot(&angular_acceleration));
        }
    }
    out
}

impl EnergyLedger {
    /// An empty ledger for a world whose total energy at t = 0 is `initial`.
    pub fn new(initial: f64) -> EnergyLedger {
        EnergyLedger {
            initial,
            drag_work: 0.0,
            contact_gain: 0.0,
            contact_loss: 0.0,
            joint_correction: 0.0,
            motor_work: 0.0,
            hand_work: 0.0,
            hand_gain: 0.0,
        }
    }

    /// Books the drag work of one integrate phase of length `dt` (corrected trapezoid rule),
    /// given the drag power at its start and at its end.
    pub fn book_drag(&mut self, start: &DragPower, end: &DragPower, dt: f64) {
        self.drag_work +=
            0.5 * dt * (start.power + end.power) + dt * dt / 12.0 * (start.rate - end.rate);
    }

    /// Books the energy change of one collide phase.
    pub fn book_contact(&mut self, total_before: f64, total_after: f64) {
        let change = total_after - total_before;
        if change > 0.0 {
            self.contact_gain += change;
        } else {
            self.contact_loss += change;
        }
    }

    /// Books the work of one kick of the hand (`hand::Hand::kick`).
    pub fn book_hand(&mut self, work: f64) {
        self.hand_work += work;
        self.hand_gain += work.max(0.0);
    }

    /// ΔE_contacts: the net energy change of every collide phase so far (< 0: taken), J.
    pub fn contacts(&self) -> f64 {
        self.contact_gain + self.contact_loss
    }

    /// `E₀ + W_drag + ΔE_contacts + W_motor + W_hand`: the energy the world would have if the
    /// integrator were exact, J.
    pub fn accounted(&self) -> f64 {
        self.initial + self.drag_work + self.contacts() + self.motor_work + self.hand_work
    }

    /// `E₀ + Σ max(0, ΔE_collide) + max(0, W_motor) + Σ max(0, ΔK_hand)`: the most energy
    /// the scene has supplied (drag only takes), J.
    pub fn supplied(&self) -> f64 {
        self.initial + self.contact_gain + self.motor_work.max(0.0) + self.hand_gain
    }

    /// The split of `E − E₀`. `initial` and `now` are the energies at t = 0 and now; `has_drag`
    /// and `has_contacts` say whether the scene declares drag and obstacles (absent causes are
    /// None, never a misleading 0).
    pub fn balance(
        &self,
        initial: &Energy,
        now: &Energy,
        has_drag: bool,
        has_contacts: bool,
    ) -> EnergyBalance {
        let change = now.total - initial.total;
        let drift = now.total - self.accounted();
        let scale = initial.total.abs().max(initial.kinetic.abs());
        EnergyBalance {
            change,
            drag_work: has_drag.then_some(self.drag_work),
            contacts: has_contacts.then_some(self.contacts()),
            springs: None,
            motor: None,
            hand: None,
            drift,
            relative_drift: if scale > 0.0 { drift / scale } else { 0.0 },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drag_power_is_minus_k_v_squared_minus_ka_omega_squared() {
        // k = 0.5, k_a = 0.02, |v|² = 2² + 5² = 29, |ω|² = 36: −(14.5 + 0.72) = −15.22 W
        // (the number lesson 9 quotes). A unit cube of 6 kg has I = 1 kg·m² (isotropic), so
        // ω × L = 0 and ω̇ = −k_a ω / I; a = g − k v / M:
        // ṗ = −2 (k v·a + k_a ω·ω̇) = −2 (0.5 (−9.81·5 − 0.5·29/6) + 0.02·(−0.02·36))
        //   = −2 (−25.733333 − 0.0144) = 51.495467 W/s.
        let body = Body::solid_box(Vector3::repeat(1.0), 6.0).unwrap();
        let effects = Effects::new(vec![
            Effect::Gravity(Vector3::new(0.0, -9.81, 0.0)),
            Effect::Drag {
                linear: 0.5,
                angular: 0.02,
            },
        ]);
        let kinematics = Kinematics {
            rotation: nalgebra::Matrix3::identity(),
            inv_inertia_world: body.inv_inertia_body,
            angular_velocity: Vector3::new(0.0, 0.0, 6.0),
            velocity: Vector3::new(2.0, 5.0, 0.0),
        };
        let p = drag_power(&body, &effects, &kinematics, &Vector3::new(0.0, 0.0, 6.0));
        assert!((p.power + 15.22).abs() < 1e-12, "{p:?}");
        assert!((p.rate - 51.495467).abs() < 1e-6, "{p:?}");
        let none = drag_power(&body, &Effects::default(), &kinematics, &Vector3::zeros());
        assert_eq!(none, DragPower::default());
    }

    #[test]
    fn the_balance_leaves_only_the_unbooked_change_as_drift() {
        // E₀ = 10 J; drag booked −2 J, contacts −3 J; E now 4.5 J: E − E₀ = −5.5 J, of which
        // −5 J is accounted for, so drift = −0.5 J and drift/E₀ = −0.05.
        let mut ledger = EnergyLedger::new(10.0);
        let power = |power| DragPower { power, rate: 0.0 };
        ledger.book_drag(&power(-3.0), &power(-1.0), 1.0);
        ledger.book_contact(8.0, 5.0);
        let e0 = Energy {
            kinetic: 10.0,
            potential: 0.0,
            total: 10.0,
        };
        let now = Energy {
            kinetic: 4.5,
            potential: 0.0,
            total: 4.5,
        };
        let b = ledger.balance(&e0, &now, true, false);
        assert_eq!(b.change, -5.5);
        assert_eq!(b.drag_work, Some(-2.0));
        assert_eq!(b.contacts, None, "no obstacles: no contact row");
        assert!((b.drift + 0.5).abs() < 1e-12, "{}", b.drift);
        assert!((b.relative_drift + 0.05).abs() < 1e-12);
    }
}
