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
    let rail = (JointKind::Slider, Vector3::x(), Motor { speed: 0.0, max });
    motored_world(bodies, rail, e, mu)
}

/// Two bodies, the first on a joint of `kind` at the origin along `axis` (to the world) with
/// `motor`; no gravity, restitution `e`, friction `mu`, `rk4` at [`DT`], joints projected.
fn motored_world(
    bodies: Vec<NamedBody>,
    (kind, axis, motor): (JointKind, Vector3<f64>, Motor),
    e: f64,
    mu: f64,
) -> World {
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let mut joint = Joint::at_point(
        kind.name().into(),
        kind,
        0,
        None,
        Vector3::zeros(),
        axis,
        &states,
    );
    joint.motor = Some(motor);
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
        joints: vec![joint],
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

/// The paddle: 1 kg, 50 × 2 × 10 cm, on a hinge along z at its end (the origin), turning at
/// `omega` about it with its motor at that speed and at most `max` N·m; a 0.2 kg ball of
/// radius 5 cm at rest just above its top face, 0.4 m from the hinge; no gravity, e, μ = 0.
fn paddle_and_ball(omega: f64, max: f64, e: f64) -> World {
    let paddle = State {
        position: Vector3::new(0.25, 0.0, 0.0),
        linear_momentum: Vector3::new(0.0, 0.25 * omega, 0.0),
        angular_momentum: Vector3::new(0.0, 0.0, PADDLE_INERTIA * omega),
        ..State::at_rest()
    };
    let ball = State {
        position: Vector3::new(0.4, 0.01 + 0.05 + 2e-4, 0.0),
        ..State::at_rest()
    };
    let bodies = vec![
        NamedBody {
            name: "paddle".into(),
            body: Body::solid_box(Vector3::new(0.5, 0.02, 0.1), 1.0).expect("a box"),
            initial: paddle,
        },
        NamedBody {
            name: "ball".into(),
            body: Body::sphere(0.05, BALL, false).expect("a ball"),
            initial: ball,
        },
    ];
    let hinge = (JointKind::Hinge, Vector3::z(), Motor { speed: omega, max });
    motored_world(bodies, hinge, e, 0.0)
}

/// The paddle's moment of inertia about its centre (z): M (a² + b²)/12.
const PADDLE_INERTIA: f64 = (0.25 + 0.0004) / 12.0;
/// About the hinge: plus M (a/2)².
const HINGE_INERTIA: f64 = PADDLE_INERTIA + 0.0625;
/// The ball's mass, kg.
const BALL: f64 = 0.2;

/// The paddle strikes the ball: the paddle's rate after the blow, the ball's speed and its
/// lever about the hinge ℓ = (c × v̂)_z (its centre's coordinate along the paddle: the ball
/// leaves along the face's normal, so moving it along its velocity keeps ℓ), the motor's
/// torque in that step, and the angular momentum about the hinge axis of both bodies.
fn strike(world: &mut World) -> Strike {
    for _ in 0..50 {
        world.step();
        let (paddle, ball) = (world.states()[0], world.states()[1]);
        let v = ball.linear_momentum / BALL;
        if v.norm() > 1e-9 {
            let snapshot = world.snapshot();
            let joint = &snapshot.joints[0];
            let (_, rate) = joint.coordinate.expect("an angle");
            let about_hinge = paddle.angular_momentum.z
                + paddle.position.cross(&paddle.linear_momentum).z
                + ball.position.cross(&ball.linear_momentum).z;
            let strike = Strike {
                rate,
                speed: v.norm(),
                lever: ball.position.cross(&v.normalize()).z,
                torque: joint.drive.motor,
                about_hinge,
            };
            eprintln!("{strike:?}");
            assert!((strike.lever - 0.4).abs() < 1e-3, "ℓ = {}", strike.lever);
            return strike;
        }
    }
    panic!("no blow");
}

/// What [`strike`] measures.
#[derive(Debug)]
struct Strike {
    rate: f64,
    speed: f64,
    lever: f64,
    torque: f64,
    about_hinge: f64,
}

#[test]
fn a_motored_paddle_strikes_a_ball_at_its_speed_or_with_its_torque_bound_and_no_more() {
    // The paddle turns at ω = 2 rad/s and strikes the ball (m = 0.2 kg) at rest at ℓ ≈ 0.4 m
    // from the hinge, e = 0. Free motor (1000 N·m, room 1 N·m·s): the paddle keeps ω, the
    // ball leaves at ω ℓ, and the motor's angular impulse is the ball's angular momentum
    // about the hinge, m ω ℓ² = 0.064 N·m·s. Motor at its bound (30 N·m, 0.03 N·m·s < 0.064):
    // its impulse is τ dt exactly, so the angular momentum about the hinge goes from I_h ω to
    // I_h ω + τ dt = (I_h + m ℓ²) ω', the ball at ω' ℓ.
    //
    // Measured: the free case and both motor impulses within 1e-9 (τ = 30.000000000 N·m);
    // the angular momentum about the hinge within 2.6e-9 N·m·s of I_h ω + τ dt; but the
    // paddle's ω' = 1.7050021 against 1.7050046 (−1.5e-6 relative) and the ball 2.6e-6 m/s
    // faster than the face under it (ω' ℓ), so those to 1e-5 relative. The same with
    // joint_correction = none; the motor held in stage 3 instead (the bounce below) is
    // within 3.4e-8. Not traced: stage 1's direct solve once the motor is held is the
    // suspect (its ε = 1e-10 max Aᵢᵢ, `joined`'s unit test of a held motor).
    let omega = 2.0;
    let free = strike(&mut paddle_and_ball(omega, 1000.0, 0.0));
    assert!((free.rate - omega).abs() < 1e-9, "{free:?}");
    assert!((free.speed - omega * free.lever).abs() < 1e-9, "{free:?}");
    let impulse = BALL * omega * free.lever * free.lever;
    assert!((free.torque * DT - impulse).abs() < 1e-9, "{free:?}");
    let before = HINGE_INERTIA * omega;
    assert!(
        (free.about_hinge - before - impulse).abs() < 1e-8,
        "{free:?}"
    );

    let tau = 30.0;
    let held = strike(&mut paddle_and_ball(omega, tau, 0.0));
    assert!((held.torque - tau).abs() < 1e-9, "{held:?}");
    assert!(
        (held.about_hinge - before - tau * DT).abs() < 1e-8,
        "{held:?}"
    );
    let l = held.lever;
    let after = (before + tau * DT) / (HINGE_INERTIA + BALL * l * l);
    assert!(
        (held.rate - after).abs() < 1e-5 * after,
        "ω' {after}: {held:?}"
    );
    assert!(
        (held.speed - after * l).abs() < 1e-5 * after * l,
        "{held:?}"
    );
}

#[test]
fn a_motored_paddle_bouncing_a_ball_holds_its_speed_until_its_torque_bound() {
    // As above with e = 0.5 and τ_max dt = 0.08 N·m·s: compression needs m ω ℓ² = 0.064
    // (free: the paddle keeps ω, λ_c = m ω ℓ), the restitution e λ_c would need 0.032 more;
    // the motor gives 0.016 and no more, so the ball leaves at (1 + e) ω ℓ and
    // I_h ω' = I_h ω + τ dt − m (1 + e) ω ℓ² (K after 0.280 J within K₀ + the motor's
    // work 0.295 J: no clamp). Measured: τ and the ball's speed within 1e-9, the angular
    // momentum about the hinge within 5.1e-9 N·m·s, ω' within 3.4e-8 relative. Before the
    // active set in the bounce's reaction the motor, an equality row there, gave
    // 90.6 N·m and the paddle kept ω (the energy clamp cut the ball to 1.13 m/s).
    let (omega, tau, e) = (2.0, 80.0, 0.5);
    let b = strike(&mut paddle_and_ball(omega, tau, e));
    assert!((b.torque - tau).abs() < 1e-9, "{b:?}");
    assert!(
        (b.speed - (1.0 + e) * omega * b.lever).abs() < 1e-9,
        "{b:?}"
    );
    let before = HINGE_INERTIA * omega;
    assert!((b.about_hinge - before - tau * DT).abs() < 1e-8, "{b:?}");
    let l = b.lever;
    let after = omega + (tau * DT - BALL * (1.0 + e) * omega * l * l) / HINGE_INERTIA;
    assert!((b.rate - after).abs() < 1e-7 * after, "ω' {after}: {b:?}");
}
