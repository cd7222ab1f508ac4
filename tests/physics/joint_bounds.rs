//! A motor's bound kept everywhere in the contacts' solve (`impulse::joined::bounds`): in the
//! friction stage (a ball sliding across a motored cart) and in the bounce (a ball bouncing off
//! a motored cart), each blow against its closed form, the motor's work booked in its ledger
//! row and the rest in the contacts'.

use nalgebra::Vector3;
use tumble::physics::joints::{Correction, Joint, JointKind, Links, Motor};
use tumble::physics::{Body, ContactModel, Effects, Integrator, NamedBody, Response, State, World};

const DT: f64 = 1e-3;

/// A 1 kg cart (40 × 10 × 40 cm) at rest on a rail along x whose motor holds it still
/// (speed 0, at most `max` N), and a 1 kg ball of radius 5 cm (I = 2/5 m r²) in state
/// `ball`; no gravity, restitution `e`, friction `mu`.
fn cart_and_ball(max: f64, ball: State, e: f64, mu: f64) -> World {
    let bodies = vec![
        NamedBody {
            name: "cart".into(),
            body: Body::solid_box(Vector3::new(0.4, 0.1, 0.4), 1.0).expect("a box"),
            initial: State::at_rest(),
        },
        NamedBody {
            name: "ball".into(),
            body: Body::sphere(0.05, 1.0, false).expect("a ball"),
            initial: ball,
        },
    ];
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let mut rail = Joint::at_point(
        "rail".into(),
        JointKind::Slider,
        0,
        None,
        Vector3::zeros(),
        Vector3::x(),
        &states,
    );
    rail.motor = Some(Motor { speed: 0.0, max });
    let contact = ContactModel {
        response: Response::Impulse,
        restitution: e,
        friction: mu,
        impacts: tumble::physics::Impacts::default(),
    };
    World::with_bodies(
        bodies,
        Effects::new(Vec::new()),
        Vec::new(),
        Some(contact),
        Integrator::Rk4,
        DT,
    )
    .with_links(Links {
        joints: vec![rail],
        springs: Vec::new(),
        correction: Correction::Projection,
    })
}

/// What one step of the blow did: the cart's and the ball's velocities after it, the ball's
/// spin about z, the motor's force in it, and the motor's and the contacts' work in it
/// (ledger rows) with the kinetic energy's change.
#[derive(Debug)]
struct Blow {
    cart: Vector3<f64>,
    ball: Vector3<f64>,
    spin: f64,
    motor: f64,
    motor_work: f64,
    contacts_work: f64,
    kinetic_change: f64,
}

/// Steps `world` until the ball's velocity changes (the blow) and returns that step.
fn blow(world: &mut World) -> Blow {
    let kinetic = |w: &World| {
        let s = w.states();
        (s[0].linear_momentum.norm_squared() + s[1].linear_momentum.norm_squared()) / 2.0
            + s[1].angular_momentum.norm_squared() / (2.0 * 0.4 * 0.05 * 0.05)
    };
    let ledger = |w: &World| {
        let b = w.energy_balance();
        (b.motor.unwrap_or(0.0), b.contacts.unwrap_or(0.0))
    };
    for _ in 0..200 {
        let (k0, (m0, c0)) = (kinetic(world), ledger(world));
        let before = world.states()[1].linear_momentum;
        world.step();
        let s = world.states();
        if (s[1].linear_momentum - before).norm() > 1e-9 {
            let (m1, c1) = ledger(world);
            return Blow {
                cart: s[0].linear_momentum,
                ball: s[1].linear_momentum,
                spin: s[1].angular_momentum.z / (0.4 * 0.05 * 0.05),
                motor: world.snapshot().joints[0].drive.motor,
                motor_work: m1 - m0,
                contacts_work: c1 - c0,
                kinetic_change: kinetic(world) - k0,
            };
        }
    }
    panic!("no blow");
}

#[test]
fn a_ball_sliding_across_a_motored_cart_moves_it_once_the_motor_is_at_its_bound() {
    // The ball lands on the cart's top at (vx, −vy) = (4, −1) m/s, e = 0, μ = 0.5; the cart's
    // motor holds it still with at most F = 10 N, F dt = 0.01 N·s. The rail takes the normal
    // blow, λₙ = m vy = 1 N·s; the ball slides throughout, so friction gives μ λₙ = 0.5 N·s
    // along x, far past the motor's bound: the cart leaves at V = (μ λₙ − F dt)/m_c =
    // 0.49 m/s, the ball at vx − μ vy = 3.5 m/s spinning at ℓ μ λₙ/I (ℓ ≈ r: 25 rad/s; its
    // contact point's slip 4 − 3.5 (0.5) − 0.49 = 1.76 m/s > 0: it slides). The motor's work
    // is −F dt (0 + V)/2; the contacts' −m vy²/2 − μ λₙ (vx + slip)/2 = −1.94 J. Before the
    // active set in the joints' friction sweeps the motor, an equality row there, gave
    // 0.5 N·s (500 N) and the cart did not move.
    let (vx, vy, mu, max) = (4.0, 1.0, 0.5, 10.0);
    let ball = State {
        position: Vector3::new(0.0, 0.05 + 0.05 + 2e-4, 0.0),
        linear_momentum: Vector3::new(vx, -vy, 0.0),
        ..State::at_rest()
    };
    let mut world = cart_and_ball(max, ball, 0.0, mu);
    let b = blow(&mut world);
    eprintln!("{b:?}");
    let p = max * DT;
    let speed = mu * vy - p;
    assert!((b.motor + max).abs() < 1e-9, "motor {} N", b.motor);
    assert!((b.cart.x - speed).abs() < 1e-9, "cart {:?}", b.cart);
    assert!(
        (b.ball.x - (vx - mu * vy)).abs() < 1e-9,
        "ball {:?}",
        b.ball
    );
    assert!(b.ball.y.abs() < 1e-9, "ball {:?}", b.ball);
    // The spin's lever ℓ = ω I/(μ λₙ) is the contact point's depth below the ball's centre:
    // r less half the step's overlap (the blow is found 0.8 mm into the top), so within 1 mm.
    let lever = -b.spin * 0.4 * 0.05 * 0.05 / (mu * vy);
    assert!(lever <= 0.05 && lever > 0.049, "lever {lever} m");
    let slip = vx - mu * vy + b.spin * lever - speed;
    assert!(slip > 1.7, "slip {slip} m/s: the ball slides");
    let motor_work = -p * speed / 2.0;
    let contacts_work = -vy * vy / 2.0 - mu * vy * (vx + slip) / 2.0;
    assert!((b.motor_work - motor_work).abs() < 1e-9, "{b:?}");
    assert!((b.contacts_work - contacts_work).abs() < 1e-9, "{b:?}");
    assert!(
        (b.motor_work + b.contacts_work - b.kinetic_change).abs() < 1e-9,
        "{b:?}"
    );
}

#[test]
fn a_ball_bouncing_off_a_motored_cart_takes_the_motor_to_its_bound_and_no_further() {
    // The ball runs along −x at v = 1 m/s into the cart's end, e = 0.5, μ = 0; the motor
    // holds the cart still with at most F dt = 1.2 N·s. Compression: the ball stops, the
    // motor holds the cart with m v = 1 N·s (inside its bound). Restitution: e m v = 0.5 N·s
    // more on each, and the motor would need 1.5 N·s in all: it gives 1.2 and no more, so the
    // ball leaves at e v = 0.5 m/s and the cart at V = −((1 + e) m v − F dt)/m_c = −0.3 m/s
    // (K after 0.17 J < 0.5 J: no clamp). The motor's work 1.2 (0 + V)/2 = −0.18 J, the
    // contacts' (1 + e) m v (−v + e v − V)/2 = −0.15 J. Before the active set in the bounce's
    // reaction the motor, an equality row there, gave 1.5 N·s and the cart did not move.
    let (v, e, p) = (1.0, 0.5, 1.2);
    let ball = State {
        position: Vector3::new(0.2 + 0.05 + 2e-4, 0.0, 0.0),
        linear_momentum: Vector3::new(-v, 0.0, 0.0),
        ..State::at_rest()
    };
    let mut world = cart_and_ball(p / DT, ball, e, 0.0);
    let b = blow(&mut world);
    eprintln!("{b:?}");
    let speed = -((1.0 + e) * v - p);
    assert!((b.motor * DT - p).abs() < 1e-9, "motor {} N", b.motor);
    assert!((b.ball.x - e * v).abs() < 1e-9, "ball {:?}", b.ball);
    assert!((b.cart.x - speed).abs() < 1e-9, "cart {:?}", b.cart);
    let motor_work = p * speed / 2.0;
    let contacts_work = (1.0 + e) * v * (-v + e * v - speed) / 2.0;
    assert!((b.motor_work - motor_work).abs() < 1e-9, "{b:?}");
    assert!((b.contacts_work - contacts_work).abs() < 1e-9, "{b:?}");
    assert!(
        (b.motor_work + b.contacts_work - b.kinetic_change).abs() < 1e-9,
        "{b:?}"
    );
}
