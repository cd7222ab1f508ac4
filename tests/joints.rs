//! Joints and springs against independent truth: closed forms, conservation laws, and a
//! minimal-coordinate ODE solved here by a high-order method.

use nalgebra::{UnitQuaternion, Vector3};
use tumble::physics::joints::{Correction, Joint, JointKind, Links, Spring};
use tumble::physics::{Body, Effect, Effects, Integrator, NamedBody, State, World};

const G: f64 = 9.81;

/// A small box bob (0.1 m, 1 kg) at `position`, at rest.
fn bob(name: &str, position: Vector3<f64>) -> NamedBody {
    NamedBody {
        name: name.into(),
        body: Body::solid_box(Vector3::new(0.1, 0.1, 0.1), 1.0).expect("a box"),
        initial: State {
            position,
            ..State::at_rest()
        },
    }
}

fn gravity() -> Effects {
    Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))])
}

/// A simple pendulum of length `l` from the pivot at the origin, released at rest at `theta0`
/// from the vertical: a distance joint from the world pivot to the bob's barycenter, so the
/// bob's own rotation is uncoupled (the anchor is its barycenter) and it moves exactly as a
/// point mass on a massless rod.
fn simple_pendulum(
    l: f64,
    theta0: f64,
    integrator: Integrator,
    dt: f64,
    correction: Correction,
) -> World {
    let x0 = Vector3::new(l * theta0.sin(), -l * theta0.cos(), 0.0);
    let bodies = vec![bob("bob", x0)];
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joint = Joint::distance("rod".into(), 0, None, [x0, Vector3::zeros()], None, &states);
    World::with_bodies(bodies, gravity(), Vec::new(), None, integrator, dt).with_links(Links {
        joints: vec![joint],
        springs: Vec::new(),
        correction,
    })
}

/// The times x crosses 0 upward (linear interpolation between steps), over `steps` steps.
fn upward_crossings(
    world: &mut World,
    steps: usize,
    coordinate: impl Fn(&World) -> f64,
) -> Vec<f64> {
    let mut out = Vec::new();
    let mut last = coordinate(world);
    for _ in 0..steps {
        let t0 = world.time();
        world.step();
        let now = coordinate(world);
        if last < 0.0 && now >= 0.0 {
            out.push(t0 + world.dt() * (-last) / (now - last));
        }
        last = now;
    }
    out
}

/// The complete elliptic integral of the first kind K(k) by the arithmetic–geometric mean:
/// K = π / (2 AGM(1, √(1 − k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The measured period: the mean spacing of upward crossings of x = 0.
fn period(world: &mut World, steps: usize) -> f64 {
    let c = upward_crossings(world, steps, |w| w.state().position.x);
    assert!(c.len() >= 3, "too few crossings: {c:?}");
    (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
}

#[test]
fn the_large_amplitude_pendulum_period_follows_the_elliptic_integral() {
    // T = 4 √(L/g) K(sin(θ₀/2)); T/T₀ with T₀ = 2π √(L/g): 1.017409 at 30°, 1.180341 at 90°.
    let l = 1.0;
    let t0 = 2.0 * std::f64::consts::PI * (l / G).sqrt();
    for (degrees, ratio) in [(30.0_f64, 1.017409), (90.0, 1.180341)] {
        let theta0 = degrees.to_radians();
        let exact = 4.0 * (l / G).sqrt() * elliptic_k((theta0 / 2.0).sin());
        assert!(
            (exact / t0 - ratio).abs() < 1e-6,
            "K itself: {}",
            exact / t0
        );
        let mut world = simple_pendulum(l, theta0, Integrator::Rk4, 1e-3, Correction::Projection);
        let measured = period(&mut world, 12_000);
        assert!(
            (measured - exact).abs() < 1e-5,
            "{degrees}°: T = {measured:.7} s, 4√(L/g) K = {exact:.7} s (T/T₀ = {:.6})",
            measured / t0
        );
    }
}
