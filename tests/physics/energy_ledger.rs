//! The energy ledger: E − E₀ split into drag work, contact energy and the remainder, the
//! numerical drift. Physical losses must never be called drift.

use nalgebra::{UnitQuaternion, Vector3};
use tumble::physics::collision::obstacle::Ground;
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, Obstacle, Orientation, Phase,
    Response, State, World,
};

const G: f64 = 9.81;

/// A solid cube of side 0.5 m and mass 2 kg: I = M a²/6 = 2·0.25/6 = 1/12 kg·m² about every
/// axis (isotropic), so ω keeps its direction under angular drag.
fn cube() -> Body {
    Body::solid_box(Vector3::repeat(0.5), 2.0).unwrap()
}

const K: f64 = 0.5; // linear drag, kg/s
const KA: f64 = 0.02; // angular drag, kg·m²/s

/// The cube under drag only (no gravity), started with v₀ = (1, 2, −1) m/s and
/// ω₀ = (0, 3, 4) rad/s.
fn dragged(integrator: Integrator, dt: f64) -> World {
    let body = cube();
    let inertia = body.inertia_body[(0, 0)];
    let initial = State {
        position: Vector3::zeros(),
        orientation: Orientation::Quaternion(UnitQuaternion::identity()),
        linear_momentum: Vector3::new(1.0, 2.0, -1.0) * body.mass,
        angular_momentum: Vector3::new(0.0, 3.0, 4.0) * inertia,
    };
    World::new(
        body,
        Effects::new(vec![Effect::Drag {
            linear: K,
            angular: KA,
        }]),
        Vec::new(),
        None,
        integrator,
        dt,
        initial,
    )
}

/// Closed form: v = v₀ e^{−kt/M}, ω = ω₀ e^{−k_a t/I}, so
/// E(t) = ½ M |v₀|² e^{−2kt/M} + ½ I |ω₀|² e^{−2 k_a t/I}.
fn exact_energy(t: f64) -> f64 {
    let (m, i) = (2.0, 2.0 * 0.25 / 6.0);
    0.5 * m * 6.0 * (-2.0 * K * t / m).exp() + 0.5 * i * 25.0 * (-2.0 * KA * t / i).exp()
}

#[test]
fn under_drag_alone_the_drag_work_is_the_energy_lost_and_the_drift_stays_near_zero() {
    // E₀ = ½·2·6 + ½·(1/12)·25 = 6 + 1.041667 = 7.041667 J. After 2 s the linear part keeps
    // e^{−1} and the angular part e^{−0.96}: E = 2.207277 + 0.398888 = 2.606165 J.
    let mut world = dragged(Integrator::Rk4, 1e-3);
    let e0 = exact_energy(0.0);
    for _ in 0..2000 {
        world.step();
    }
    let b = world.energy_balance();
    let lost = exact_energy(2.0) - e0;
    let drag = b.drag_work.expect("drag is declared");
    assert!(
        (drag - lost).abs() < 1e-8 * e0,
        "drag work {drag} J, closed form {lost} J"
    );
    assert!(
        b.drift.abs() < 1e-9 * e0,
        "rk4 at dt = 1e-3: drift {:e} J should be round-off sized",
        b.drift
    );
    assert_eq!(b.contacts, None, "no obstacles: no contact entry");
    assert!((b.change - (drag + b.drift)).abs() < 1e-12);
    // The panel shows the same split.
    assert_eq!(world.snapshot().energy_balance, b);
}

#[test]
fn for_explicit_euler_the_drift_is_its_first_order_error_and_halves_with_dt() {
    // Explicit Euler on v̇ = −(k/M)v keeps (1 − h)² = 1 − 2h + h² of the kinetic energy per step
    // (h = k dt/M) where the exact flow keeps e^{−2h} = 1 − 2h + 2h² − …: it loses too much, by
    // ≈ h² E per step, so after a fixed time the drift is negative and proportional to dt. The
    // drag work booked along its own trajectory stays at the closed form to O(dt).
    let drift = |dt: f64| {
        let mut world = dragged(Integrator::Euler, dt);
        let steps = (1.0 / dt).round() as u64;
        for _ in 0..steps {
            world.step();
        }
        let b = world.energy_balance();
        let lost = exact_energy(1.0) - exact_energy(0.0);
        let drag = b.drag_work.unwrap();
        assert!(
            (drag - lost).abs() < 0.01 * lost.abs(),
            "dt {dt}: drag work {drag} J vs closed form {lost} J"
        );
        b.drift
    };
    let (coarse, fine) = (drift(0.01), drift(0.005));
    // Summed over the steps, −h² E per step is −(k dt/M²)·k ∫ E_lin dt (and likewise for the
    // spin): at dt = 0.01 over 1 s,
    //   linear  −(0.5² · 0.01 / 2²) · 6 · 2 (1 − e^{−0.5})              = −2.951e-3 J
    //   angular −(0.02² · 0.01 · 12²) · (25/24) (1 − e^{−0.48}) / 0.48  = −0.465e-3 J
    let predicted = -2.951e-3 - 0.465e-3;
    assert!(
        (coarse - predicted).abs() < 0.02 * predicted.abs(),
        "Euler loses too much energy: drift {coarse:e} J, predicted {predicted:e} J"
    );
    let ratio = coarse / fine;
    assert!(
        (ratio - 2.0).abs() < 0.1,
        "first order: drift {coarse:e} then {fine:e}, ratio {ratio}"
    );
}

/// The cube dropped flat from 1 m (its bottom face at 0.75 m) onto the ground, `impulse` with
/// restitution 0.5 and no friction, under gravity.
fn dropped(response: Response) -> World {
    World::new(
        cube(),
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            response,
            restitution: 0.5,
            friction: 0.0,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        1e-3,
        State {
            position: Vector3::new(0.0, 1.0, 0.0),
            ..State::at_rest()
        },
    )
}

#[test]
fn a_lossy_bounce_books_the_measured_loss_as_contacts_and_leaves_no_drift() {
    // Impact speed after falling 0.75 m: v = √(2·9.81·0.75) = 3.8361 m/s, K = ½·2·v² = 14.715 J;
    // a flat frictionless impact with e = 0.5 keeps e² = 1/4 of it: the contacts take
    // (1 − e²) K = 11.036 J (to within the step's g·dt of impact speed, ~0.5 %).
    let mut world = dropped(Response::Impulse);
    let mut measured = 0.0;
    // Independent measurement: the energy just before and after every collide phase.
    for _ in 0..500 {
        let mut before = 0.0;
        loop {
            let phase = world.next_phase();
            if phase == Phase::Collide {
                before = world.energy_of(world.state()).total;
            }
            world.step_phase();
            if phase == Phase::Collide {
                break;
            }
        }
        measured += world.energy_of(world.state()).total - before;
    }
    let b = world.energy_balance();
    let contacts = b.contacts.expect("obstacles declared");
    assert_eq!(
        world.energy_ledger().contact_gain,
        0.0,
        "impulse never adds energy here"
    );
    assert!(
        (contacts - measured).abs() < 1e-12,
        "ledger {contacts} J, measured {measured} J"
    );
    let expected = -(1.0 - 0.25) * 0.5 * 2.0 * 2.0 * G * 0.75;
    assert!(
        (contacts - expected).abs() < 0.01 * expected.abs(),
        "contacts {contacts} J, closed form {expected} J"
    );
    assert!(
        b.drift.abs() < 1e-9,
        "rk4 is exact on a parabola: drift {:e} J",
        b.drift
    );
    assert_eq!(b.drag_work, None, "no drag declared");
    assert!(world.snapshot().velocity.y > 0.0, "bounced up");
}

#[test]
fn the_seed_response_is_booked_too_and_its_losses_are_not_drift() {
    // The report's response reverses P, scales it by 0.4 and pushes out by a squared distance:
    // whatever it does to E (here it injects energy) is the contacts' doing, so the free flight before and after leaves only round-off.
    let mut world = dropped(Response::Seed);
    for _ in 0..600 {
        world.step();
    }
    let b = world.energy_balance();
    assert!(
        b.contacts.unwrap() != 0.0,
        "seed changed E: {:?}",
        b.contacts
    );
    assert!(b.drift.abs() < 1e-9, "drift {:e} J", b.drift);
}

#[test]
fn stepping_back_restores_the_ledger() {
    let mut world = dragged(Integrator::Rk4, 1e-2);
    for _ in 0..10 {
        world.step();
    }
    let saved = world.checkpoint();
    let ledger = *world.energy_ledger();
    for _ in 0..10 {
        world.step();
    }
    assert_ne!(*world.energy_ledger(), ledger);
    world.restore(&saved);
    assert_eq!(*world.energy_ledger(), ledger);
    world.reset();
    assert_eq!(world.energy_ledger().drag_work, 0.0);
}
