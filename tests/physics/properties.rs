//! Properties over random bodies (point sets and boxes), random initial states, integrators and
//! steps: the rotation stays a rotation; torque-free motion keeps the L vector; an `impulse`
//! collision with e ≤ 1 never adds kinetic energy; with drag, energy never increases.
//!
//! Case counts are bounded so that the file runs in a few seconds in release.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use tumble::physics::collision::obstacle::{Ground, Sphere};
use tumble::physics::snapshot::kinetic_energy;
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, Obstacle, Orientation, Phase,
    Response, State, World,
};

/// A fixed seed: CI explores the same cases every run (change it locally to explore others).
const SEED: u64 = 20_261_122;

fn vector(range: f64) -> impl Strategy<Value = Vector3<f64>> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vector3::new(x, y, z))
}

/// A box (sides 1 cm to 2 m, 10 g to 100 kg, solid or corner points) or a cloud of 4 to 8 mass
/// points with their own masses. Point sets with a (nearly) singular inertia are rejected by
/// `Body::from_points` and skipped.
fn body() -> impl Strategy<Value = Option<Body>> {
    let solid = (vector(1.0), 0.01..100.0f64, any::<bool>()).prop_map(|(s, mass, corners)| {
        let size = s.map(|c| 0.01 + c.abs() * 2.0);
        Some(if corners {
            Body::box_of_corners(size, mass).expect("valid box")
        } else {
            Body::solid_box(size, mass).expect("valid box")
        })
    });
    let cloud = prop::collection::vec((vector(1.0), 0.1..10.0f64), 4..9).prop_map(|points| {
        let (p, m): (Vec<_>, Vec<_>) = points.into_iter().unzip();
        Body::from_points(&p, &m, 0.0, Vec::new()).ok()
    });
    prop_oneof![solid, cloud]
}

fn orientation() -> impl Strategy<Value = UnitQuaternion<f64>> {
    (vector(1.0), -1.0..1.0f64).prop_map(|(v, w)| {
        UnitQuaternion::from_quaternion(Quaternion::new(w + 1e-3, v.x, v.y, v.z))
    })
}

fn integrator() -> impl Strategy<Value = Integrator> {
    prop::sample::select(Integrator::ALL.to_vec())
}

/// The initial state: at `position`, turned by `q`, with velocity `v` and angular velocity `w`
/// (world frame).
fn state(
    body: &Body,
    position: Vector3<f64>,
    q: UnitQuaternion<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
) -> State {
    let r = q.to_rotation_matrix().into_inner();
    State {
        position,
        orientation: Orientation::Quaternion(q),
        linear_momentum: v * body.mass,
        angular_momentum: r * body.inertia_body * r.transpose() * w,
    }
}

fn world(
    body: Body,
    effects: Vec<Effect>,
    integrator: Integrator,
    dt: f64,
    initial: State,
) -> World {
    World::new(
        body,
        Effects::new(effects),
        Vec::new(),
        None,
        integrator,
        dt,
        initial,
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, rng_seed: RngSeed::Fixed(SEED), ..ProptestConfig::default() })]

    /// Every integrator that steps a unit quaternion keeps R a rotation: RᵀR = 𝟙 to 1e-12 and
    /// det R = +1, whatever the body, the spin or the step (euler-seed steps a bare matrix and
    /// is documented to drift, so it is not held to this).
    #[test]
    fn the_rotation_stays_a_rotation(
        body in body(),
        q in orientation(),
        w in vector(20.0),
        integrator in prop::sample::select(vec![
            Integrator::Euler, Integrator::SymplecticEuler, Integrator::Rk4, Integrator::Splitting,
        ]),
        dt in 1e-4..2e-2f64,
        steps in 1usize..300,
        gravity in any::<bool>(),
    ) {
        let Some(body) = body else { return Ok(()) };
        let effects = if gravity { vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))] } else { vec![] };
        let initial = state(&body, Vector3::zeros(), q, Vector3::zeros(), w);
        let mut world = world(body, effects, integrator, dt, initial);
        for _ in 0..steps {
            world.step();
            let r = world.state().orientation.matrix();
            let error = world.state().orientation.orthonormality_error();
            prop_assert!(error < 1e-12, "{}: ‖RᵀR − 𝟙‖ = {error:e}", integrator.name());
            prop_assert!((r.determinant() - 1.0).abs() < 1e-12, "det R = {}", r.determinant());
        }
    }

    /// No torque, no change of L: every integrator adds τ·dt = 0 to L, so without effects the
    /// vector is kept to round-off — including euler-seed, whose matrix drifts but whose L does
    /// not. With gravity, every integrator but euler-seed still sees τ = 0 (euler-seed's
    /// per-vertex sum Σ rᵢ × M g is not zero for unequal point masses, by design).
    #[test]
    fn torque_free_motion_keeps_the_angular_momentum_vector(
        body in body(),
        q in orientation(),
        w in vector(20.0),
        v in vector(5.0),
        integrator in integrator(),
        dt in 1e-4..1e-2f64,
        steps in 1usize..300,
        gravity in any::<bool>(),
    ) {
        let Some(body) = body else { return Ok(()) };
        let gravity = gravity && integrator != Integrator::EulerSeed;
        let effects = if gravity { vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))] } else { vec![] };
        let initial = state(&body, Vector3::zeros(), q, v, w);
        let l0 = initial.angular_momentum;
        let mut world = world(body, effects, integrator, dt, initial);
        for _ in 0..steps {
            world.step();
            if world.divergence().is_some() {
                break; // euler-seed may blow up its matrix; L itself is still checked below
            }
        }
        let l = world.state().angular_momentum;
        prop_assert!((l - l0).norm() <= 1e-12 * l0.norm(), "{}: L {l0:?} → {l:?}", integrator.name());
    }

    /// With drag (and optionally gravity), the total energy never increases from one step to the
    /// next: the exact flow loses k|v|² + k_a|ω|² per second. Checked for rk4 and splitting at
    /// steps where their own energy error per step (O((|ω|dt)⁵) and O((|ω|dt)³)) stays below
    /// the dissipation: damping rates k/M and k_a/I₁ of 0.5 to 5 s⁻¹, |ω| ≤ 10 rad/s,
    /// dt ≤ 2e-3 s.
    #[test]
    fn energy_with_drag_never_increases(
        body in body(),
        q in orientation(),
        w in vector(10.0 / 3f64.sqrt()),
        v in vector(5.0),
        integrator in prop::sample::select(vec![Integrator::Rk4, Integrator::Splitting]),
        rate in 0.5..5.0f64,
        dt in 1e-4..2e-3f64,
        steps in 1usize..300,
        gravity in any::<bool>(),
    ) {
        let Some(body) = body else { return Ok(()) };
        let drag = Effect::Drag {
            linear: rate * body.mass,
            angular: rate * body.principal_moments.x,
        };
        let mut effects = vec![drag];
        if gravity {
            effects.push(Effect::Gravity(Vector3::new(0.0, -9.81, 0.0)));
        }
        let initial = state(&body, Vector3::new(0.0, 1.0, 0.0), q, v, w);
        let mut world = world(body, effects, integrator, dt, initial);
        let mut previous = world.energy_of(world.state()).total;
        for step in 1..=steps {
            world.step();
            let e = world.energy_of(world.state()).total;
            // Round-off: energies are sums of terms up to |E| + |V|; allow 1e-12 of that scale.
            let scale = previous.abs().max(world.energy_of(world.state()).kinetic) + 1e-300;
            prop_assert!(e <= previous + 1e-12 * scale,
                "{} step {step}: E {previous} → {e}", integrator.name());
            previous = e;
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, failure_persistence: None, rng_seed: RngSeed::Fixed(SEED), ..ProptestConfig::default() })]

    /// A random body thrown at the ground and a sphere under gravity, any 0 ≤ e ≤ 1, μ ≥ 0 and
    /// any integrator: no `impulse` collide phase ever ends with more kinetic energy than it
    /// started with.
    #[test]
    fn impulse_collisions_never_add_kinetic_energy(
        body in body(),
        q in orientation(),
        w in vector(10.0),
        v in vector(4.0),
        integrator in integrator(),
        restitution in 0.0..=1.0f64,
        friction in prop_oneof![Just(0.0), 0.0..2.0f64],
        dt in prop::sample::select(vec![1e-3, 5e-3, 1e-2]),
    ) {
        let Some(body) = body else { return Ok(()) };
        let height = body.radius + 0.01;
        let v = Vector3::new(v.x, -1.0 - v.y.abs(), v.z);
        let initial = state(&body, Vector3::new(0.0, height, 0.0), q, v, w);
        let obstacles = vec![
            Obstacle::Ground(Ground { height: 0.0 }),
            Obstacle::Sphere(Sphere { center: Vector3::new(0.4, 0.0, 0.0), radius: 0.3 }),
        ];
        let model = ContactModel { response: Response::Impulse, restitution, friction, impacts: Impacts::default() };
        let mut world = World::new(
            body,
            Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -9.81, 0.0))]),
            obstacles,
            Some(model),
            integrator,
            dt,
            initial,
        );
        let mut collisions = 0;
        let mut diverged = false;
        for _ in 0..(1.0 / dt) as usize {
            loop {
                let collide_next = world.next_phase() == Phase::Collide;
                let before = kinetic_energy(world.body(), world.state());
                world.step_phase();
                if collide_next {
                    let after = kinetic_energy(world.body(), world.state());
                    collisions += usize::from(!world.contacts().is_empty());
                    prop_assert!(after <= before, "{} e {restitution} μ {friction}: K {before} → {after}",
                        integrator.name());
                    break;
                }
            }
            if world.divergence().is_some() {
                diverged = true;
                break;
            }
        }
        // Starting 1 cm above the ground at ≥ 1 m/s downwards, the barycenter falls ≥ 5.9 m in
        // 1 s, far more than the body's radius (≤ 1.8 m): it must have touched.
        prop_assert!(collisions > 0 || diverged, "{}: never touched the ground", integrator.name());
    }
}
