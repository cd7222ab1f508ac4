//! `soft-step` (issue 17): the sag its module doc derives, its energy bound, its friction per face
//! against Coulomb's law at the corners (a spinning cube), the scene keys and
//! every bundled lesson with contact run through it.

use assert_cmd::Command;
use tumble::contact_scenes::{stack, DT, G, SIDE};
use tumble::physics::collision::obstacle::Ground;
use tumble::physics::{Response, SoftStep, World};

fn soft() -> Response {
    Response::SoftStep(SoftStep::DEFAULT)
}

/// The top cube's sink below its initial height after `seconds`, m.
fn top_sink(world: &mut World, seconds: f64) -> f64 {
    let top = world.body_count() - 1;
    let y0 = world.initial_states()[top].position.y;
    for _ in 0..(seconds / DT).round() as usize {
        world.step();
    }
    y0 - world.states()[top].position.y
}

#[test]
fn a_stack_sinks_by_the_soft_contacts_closed_form() {
    // N(N−1) g/ω² + N g/(4ω²), ω = 2π·60 Hz (module doc): 1.73e-5 m (N = 1), 2.24e-4 m (3),
    // 6.38e-3 m (10). The springs are overdamped (ζ = 10): the slowest mode of the stack of
    // 10 settles in about 2 s, so it is measured after 8 s.
    for (count, seconds) in [(1, 2.0), (3, 4.0), (10, 8.0)] {
        let expected = SoftStep::DEFAULT.stack_sag(count, G, DT);
        let sink = top_sink(&mut stack(count, soft()), seconds);
        println!("stack of {count}: sink {sink:.6e} m, closed form {expected:.6e} m");
        assert!(
            (sink - expected).abs() <= 0.02 * expected,
            "stack of {count}: top sank {sink:e} m, closed form {expected:e} m"
        );
    }
}

#[test]
fn the_sag_follows_the_contact_frequency() {
    // Four times the frequency, a sixteenth of the sag: 120 Hz on a stack of 3 is 5.6e-5 m.
    let params = SoftStep {
        hertz: 120.0,
        ..SoftStep::DEFAULT
    };
    let expected = params.stack_sag(3, G, DT);
    let sink = top_sink(&mut stack(3, Response::SoftStep(params)), 4.0);
    assert!(
        (sink - expected).abs() <= 0.02 * expected,
        "top sank {sink:e} m, closed form {expected:e} m"
    );
}

#[test]
fn the_stack_of_ten_stands_with_its_bottom_cube_on_the_ground() {
    // The stack stays upright: every cube within 1 mm of the stack's axis after 5 s.
    let mut world = stack(10, soft());
    for _ in 0..5000 {
        world.step();
    }
    for s in world.states() {
        assert!(
            s.position.x.abs() < 1e-3 && s.position.z.abs() < 1e-3,
            "{:?}",
            s.position
        );
    }
    // The bottom cube sits at SIDE/2 less its ground sag 10 g/(4ω²) = 98.1/(4·(2π·60)²)
    // = 1.73e-4 m (module doc: four corners of m = M/4 at twice the frequency).
    let omega = 2.0 * std::f64::consts::PI * SoftStep::DEFAULT.hertz;
    let expected = 10.0 * G / (4.0 * omega * omega);
    let sag = SIDE / 2.0 - world.states()[0].position.y;
    assert!(
        (sag - expected).abs() < 0.02 * expected,
        "bottom sags {sag:e} m, closed form {expected:e} m"
    );
}

/// A cube of 0.2 m and 1 kg dropped flat from rest with its bottom face 0.9 m above the
/// ground (lesson 32's), under soft-step with restitution `e` and friction `mu`.
fn flat_drop(e: f64, mu: f64) -> World {
    use nalgebra::Vector3;
    use tumble::physics::{
        Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, State,
    };
    World::with_bodies(
        vec![NamedBody {
            name: "cube".into(),
            body: Body::solid_box(Vector3::repeat(SIDE), 1.0).unwrap(),
            initial: State {
                position: Vector3::new(0.0, 0.9 + SIDE / 2.0, 0.0),
                ..State::at_rest()
            },
        }],
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            response: soft(),
            restitution: e,
            friction: mu,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        DT,
    )
}

#[test]
fn a_cube_landing_flat_leaves_flat_at_e_times_its_speed() {
    // The closed form: a face landing flat on the ground at v₁ = √(2 g 0.9) = 4.20 m/s leaves
    // at e·v₁ without turning, its four corners meeting the ground together. The touch falls
    // within one step, whose free flight ends at a speed within g·dt of v₁, and the bounce
    // sends the corners off at e times that: |v⁺ − e v₁| ≤ e g dt (at e = 0, a tenth of g dt:
    // the relax sweeps stop the corners, 9.5e-6 m/s measured). The spin: solved together
    // (`bounce`), the corners leave at one rate, ω = 0 to round-off (1.7e-14 rad/s measured;
    // the corners bounced one by one left at ω = 4.2 rad/s). With friction, or at e = 0 in the
    // steps at rest that follow, the sweeps' one-row-at-a-time order loads the corners
    // unevenly for a while: ω up to 2.3e-3 rad/s measured (a corner speed of 3e-4 m/s, 8e-5 of
    // v₁), so the bound is 5e-3 rad/s there, a thousandth of the spin the bug gave.
    let v1 = (2.0 * G * 0.9f64).sqrt();
    let inertia = SIDE * SIDE / 6.0;
    for (e, mu, spin_bound) in [
        (0.5, 0.0, 1e-9),
        (0.5, 0.5, 5e-3),
        (0.0, 0.0, 5e-3),
        (0.0, 0.5, 5e-3),
    ] {
        let mut world = flat_drop(e, mu);
        let mut spin: f64 = 0.0;
        let mut rebound = None;
        let mut vy_last = 0.0;
        // 1 s: the first touch at 0.43 s, the second (e = 0.5) at 1.07 s.
        for _ in 0..1000 {
            world.step();
            let s = world.state();
            spin = spin.max(s.angular_momentum.norm() / inertia);
            let vy = s.linear_momentum.y;
            if rebound.is_none() && vy_last < -1.0 && vy > -1.0 {
                rebound = Some(vy);
            }
            vy_last = vy;
        }
        let vy = rebound.expect("the cube landed");
        let what = format!("e = {e}, μ = {mu}: spin {spin:e} rad/s, rebound {vy} m/s");
        assert!(spin < spin_bound, "{what} (bound {spin_bound:e})");
        assert!(
            (vy - e * v1).abs() <= e.max(0.1) * G * DT,
            "{what}, e·v₁ = {}",
            e * v1
        );
    }
}

#[test]
fn a_cube_landing_flat_on_a_resting_cube_leaves_flat() {
    // A manifold between two bodies: a cube dropped from rest 0.5 m above a cube resting on
    // the ground lands flat at 3.1 m/s (e = 0.5, μ = 0); by symmetry neither turns. The
    // bounce solves the four corner rows together (`bounce`); the lower cube's ground rows,
    // which do not bounce, follow in the sweeps' one-row-at-a-time order: 3.8e-3 rad/s
    // measured until just before the second touch (0.45 s), where the corners bounced one by
    // one gave 2.7 rad/s. Bound: 1e-2 rad/s.
    use nalgebra::Vector3;
    use tumble::physics::{
        Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, State,
    };
    let cube = Body::solid_box(Vector3::repeat(SIDE), 1.0).unwrap();
    let at = |name: &str, y: f64| NamedBody {
        name: name.into(),
        body: cube.clone(),
        initial: State {
            position: Vector3::new(0.0, y, 0.0),
            ..State::at_rest()
        },
    };
    let mut world = World::with_bodies(
        vec![at("low", SIDE / 2.0), at("high", 0.8)],
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            response: soft(),
            restitution: 0.5,
            friction: 0.0,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        DT,
    );
    let inertia = SIDE * SIDE / 6.0;
    let (mut spin, mut bounced): (f64, bool) = (0.0, false);
    for _ in 0..450 {
        world.step();
        for s in world.states() {
            spin = spin.max(s.angular_momentum.norm() / inertia);
        }
        bounced |= world.states()[1].linear_momentum.y > 0.5;
    }
    assert!(bounced, "the upper cube bounced");
    assert!(spin < 1e-2, "spin {spin:e} rad/s");
}

/// The deepest contact depth of the last step, m.
fn deepest(world: &World) -> f64 {
    world.contacts().iter().map(|c| c.depth).fold(0.0, f64::max)
}

#[test]
fn energy_never_rises_above_the_documented_bound() {
    // Module doc: E(t) ≤ E(0) + Σ M|g|·d_max, d_max the deepest penetration reached.
    // A cube dropped from 0.3 m (edge first, tilted 20°) with e = 0, 0.5 and 1, and a stack.
    use nalgebra::{UnitQuaternion, Vector3};
    use tumble::physics::{
        Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Orientation,
        State,
    };
    let cube = Body::solid_box(Vector3::repeat(SIDE), 1.0).unwrap();
    for restitution in [0.0, 0.5, 1.0] {
        let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 20f64.to_radians());
        let mut world = World::with_bodies(
            vec![NamedBody {
                name: "cube".into(),
                body: cube.clone(),
                initial: State {
                    position: Vector3::new(0.0, 0.4, 0.0),
                    orientation: Orientation::Quaternion(q),
                    ..State::at_rest()
                },
            }],
            Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
            vec![Obstacle::Ground(Ground { height: 0.0 })],
            Some(ContactModel {
                response: soft(),
                restitution,
                friction: 0.5,
                impacts: Impacts::default(),
            }),
            Integrator::Rk4,
            DT,
        );
        check_energy(&mut world, 3000, &format!("cube, e = {restitution}"));
    }
    check_energy(&mut stack(10, soft()), 3000, "stack of 10");
}

fn check_energy(world: &mut World, steps: usize, what: &str) {
    let e0 = world.total_energy().total;
    let mass: f64 = world.bodies().iter().map(|b| b.mass).sum();
    let mut d_max: f64 = 0.0;
    let mut worst: f64 = f64::NEG_INFINITY;
    for _ in 0..steps {
        world.step();
        d_max = d_max.max(deepest(world));
        let rise = world.total_energy().total - e0;
        worst = worst.max(rise);
        // Round-off of E of order 1e-12 J beside.
        assert!(
            rise <= mass * G * d_max + 1e-9,
            "{what}: energy rose by {rise:e} J, bound {:e} J",
            mass * G * d_max
        );
    }
    println!(
        "{what}: largest rise {worst:e} J, bound {:e} J",
        mass * G * d_max
    );
}

#[test]
fn every_bundled_lesson_with_contact_runs_to_its_duration_under_soft_step() {
    let mut ran = 0;
    for path in tumble::lessons::bundled() {
        let lesson = tumble::lessons::load(&path).unwrap();
        let scene = &lesson.scene;
        if scene.contact.is_none() {
            continue;
        }
        let duration = scene.duration.unwrap_or(10.0);
        let steps = (duration / scene.dt).round() as u64;
        let output = Command::cargo_bin("tumble")
            .unwrap()
            .args(["run", path.to_str().unwrap(), "--response", "soft-step"])
            .args(["--steps", &steps.to_string(), "--every", &steps.to_string()])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{}: {err}", path.display());
        let out = String::from_utf8_lossy(&output.stdout);
        // The last row is the last step's (a body's row, or a cloth's last particle).
        let last = out.lines().last().unwrap();
        assert!(
            last.starts_with(&format!("{steps},")),
            "{}: {last}",
            path.display()
        );
        ran += 1;
    }
    // Lessons 05–08, 13–17 have contact.
    assert!(ran >= 8, "only {ran} lessons with contact");
}

#[test]
fn the_scene_file_takes_soft_step_and_its_keys_with_range_checks() {
    let scene = |contact: &str| {
        format!(
            "title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"rk4\"\ncontact = {contact}\n\
             [body]\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 1.0\n\
             [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n"
        )
    };
    let path = std::path::Path::new("scene.toml");
    let ok = tumble::scene::parse(
        &scene("{ response = \"soft-step\", friction = 0.5, hertz = 90.0, damping_ratio = 2.0, substeps = 8 }"),
        path,
    )
    .unwrap();
    assert_eq!(
        ok.scene.contact.unwrap().response,
        Response::SoftStep(SoftStep {
            hertz: 90.0,
            damping_ratio: 2.0,
            substeps: 8
        })
    );
    let defaults = tumble::scene::parse(&scene("{ response = \"soft-step\" }"), path).unwrap();
    assert_eq!(defaults.scene.contact.unwrap().response, soft());
    for (contact, message) in [
        (
            "{ response = \"soft-step\", hertz = 0.0 }",
            "hertz must be > 0",
        ),
        (
            "{ response = \"soft-step\", damping_ratio = -1.0 }",
            "damping_ratio must be ≥ 0",
        ),
        (
            "{ response = \"soft-step\", substeps = 0 }",
            "substeps must be a whole number from 1 to 64",
        ),
        (
            "{ response = \"soft-step\", substeps = 65 }",
            "substeps must be a whole number from 1 to 64",
        ),
        (
            "{ response = \"impulse\", hertz = 30.0 }",
            "`hertz` is a key of the `soft-step` response",
        ),
    ] {
        let err = tumble::scene::parse(&scene(contact), path)
            .unwrap_err()
            .to_string();
        assert!(err.contains(message), "{contact}: {err}");
        assert!(err.contains("scene.toml:5:"), "{contact}: {err}");
    }
}

#[test]
fn soft_step_is_in_the_response_list() {
    assert_eq!(Response::names(), "seed, impulse, soft-step");
    assert_eq!(Response::from_name("soft-step"), Some(soft()));
    assert_eq!(Response::Impulse.next(), soft());
    assert_eq!(soft().next(), Response::Seed);
}

/// The largest sideways distance (x, z) of a cube from the stack's axis, m.
fn sideways(world: &World) -> f64 {
    world
        .states()
        .iter()
        .map(|s| s.position.x.hypot(s.position.z))
        .fold(0.0, f64::max)
}

/// The fewest cubes whose discrete chain of soft tilt joints is unstable at `hertz`: the tilt
/// θ_j of each cube, joints of stiffness M ω² a²/2 between cubes (four corners of M/8 at lever
/// a) and 4 M ω² a² at the ground (corners of M/4 at 2ω), gravity's −M g h_j on the diagonal
/// (h_j: the height of cube j's centre above the joint below the cubes it carries, summed:
/// 2a (N−1−j) + a). Stable while the tridiagonal stiffness matrix is positive definite: its
/// LDLᵀ pivots d_j = K_jj − K_j,j−1²/d_j−1 all positive.
fn chain_buckles_at(hertz: f64) -> usize {
    let (m, a) = (1.0, SIDE / 2.0);
    let omega = 2.0 * std::f64::consts::PI * hertz;
    let (joint, ground) = (
        m * omega * omega * a * a / 2.0,
        4.0 * m * omega * omega * a * a,
    );
    (1..200)
        .find(|&n| {
            let mut pivot = f64::INFINITY;
            (0..n).any(|j| {
                let below = if j == 0 { ground } else { joint };
                let above = if j + 1 < n { joint } else { 0.0 };
                let gravity = m * G * (2.0 * a * (n - 1 - j) as f64 + a);
                let coupling = if j == 0 { 0.0 } else { joint * joint / pivot };
                pivot = below + above - gravity - coupling;
                pivot <= 0.0
            })
        })
        .expect("a chain that buckles")
}

#[test]
fn the_buckling_count_matches_the_discrete_chain_of_tilt_joints() {
    // Greenhill's continuous column (module doc) against the chain of rigid cubes: the chain
    // holds `chain − 1` cubes and not `chain`; that boundary, `chain − ½`, lies within one cube
    // of the continuum's count.
    for hertz in [30.0, 60.0, 120.0, 240.0] {
        let params = SoftStep {
            hertz,
            ..SoftStep::DEFAULT
        };
        let count = params.buckling_count(SIDE, G, DT);
        let chain = chain_buckles_at(hertz);
        println!("{hertz} Hz: Greenhill {count:.2}, chain buckles at {chain}");
        assert!(
            (count - (chain as f64 - 0.5)).abs() <= 1.0,
            "{hertz} Hz: Greenhill {count}, chain {chain}"
        );
        let hold = SoftStep::hertz_to_hold(chain, SIDE, G);
        let params = SoftStep {
            hertz: hold,
            ..SoftStep::DEFAULT
        };
        assert!((params.buckling_count(SIDE, G, DT) - chain as f64).abs() < 1e-9);
    }
}

#[test]
fn a_soft_stack_stands_below_its_buckling_count_and_falls_above_it() {
    // Below N_c the lean the sweep order leaves (micrometres) stays; above, it grows
    // exponentially (×2.6 a second on 16 cubes at 60 Hz) until the stack falls. Doubling
    // the frequency raises N_c by 2^(2/3): the 16 that fall at 60 Hz stand at 120 Hz.
    for hertz in [60.0, 120.0] {
        let params = SoftStep {
            hertz,
            ..SoftStep::DEFAULT
        };
        let count = params.buckling_count(SIDE, G, DT).floor() as usize;
        for (n, falls) in [(count - 1, false), (count + 2, true)] {
            let mut world = stack(n, Response::SoftStep(params));
            let (mut at_4, mut largest) = (0.0, 0.0f64);
            for step in 1..=10_000 {
                world.step();
                largest = largest.max(sideways(&world));
                if step == 4000 {
                    at_4 = sideways(&world);
                }
            }
            let at_10 = sideways(&world);
            println!("{hertz} Hz, {n} cubes: sideways {at_4:.3e} m at 4 s, {at_10:.3e} m at 10 s");
            if falls {
                assert!(
                    at_10 > 0.01 && at_10 > 20.0 * at_4,
                    "{hertz} Hz, {n} cubes: {at_4:e} m at 4 s, {at_10:e} m at 10 s"
                );
            } else {
                assert!(largest < 5e-4, "{hertz} Hz, {n} cubes leaned {largest:e} m");
            }
        }
    }
}

/// A cube of side [`SIDE`] and 1 kg resting flat on the ground, spinning about the vertical
/// at `omega` rad/s, under `response` with friction `mu` (e = 0).
fn spinning_cube(response: Response, mu: f64, omega: f64) -> World {
    use nalgebra::Vector3;
    use tumble::physics::{
        Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, State,
    };
    let body = Body::solid_box(Vector3::repeat(SIDE), 1.0).unwrap();
    let spin = SIDE * SIDE / 6.0 * omega; // L = I ω, I = m s²/6 about any axis
    World::with_bodies(
        vec![NamedBody {
            name: "cube".into(),
            body,
            initial: State {
                position: Vector3::new(0.0, SIDE / 2.0, 0.0),
                angular_momentum: Vector3::new(0.0, spin, 0.0),
                ..State::at_rest()
            },
        }],
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            response,
            restitution: 0.0,
            friction: mu,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        DT,
    )
}

#[test]
fn a_cube_spinning_flat_on_the_ground_stops_at_coulombs_twist_rate_under_both_responses() {
    // Each corner of the bottom face (ρ = s/√2 from its centre) carries m g/4 and slides on a
    // circle about the centre, so its friction μ m g/4 is tangent to that circle: no net force,
    // a torque μ m g s/√2 about the vertical, and ω falls at α = μ m g (s/√2)/(m s²/6) =
    // 3√2 μ g/s (104.1 rad/s² for μ = 0.5, s = 0.2 m) until it stops at t = ω₀/α, having
    // turned ω₀²/(2α). `impulse` takes Coulomb's law per corner; `soft-step` per face (a
    // tangent pair at the centre and a twist bounded by μ Σ λᵢ ρᵢ, its module doc): the same
    // torque here. Neither may push the cube sideways or tilt it.
    let (mu, omega0) = (0.5, 10.0);
    let alpha = 3.0 * 2f64.sqrt() * mu * G / SIDE;
    let stop = omega0 / alpha;
    for response in [Response::from_name("impulse").unwrap(), soft()] {
        let name = response.descriptor().name;
        let mut world = spinning_cube(response, mu, omega0);
        let (mut yaw, mut last) = (0.0, omega0);
        let mut stopped_at = None;
        for step in 1..=200 {
            world.step();
            // A cube's inertia is m s²/6 about every axis: ω = L/I whatever its orientation.
            let w = world.states()[0].angular_momentum / (SIDE * SIDE / 6.0);
            yaw += (last + w.y) / 2.0 * DT; // the trapezoid rule on ω_y
            last = w.y;
            let t = step as f64 * DT;
            if step == 50 {
                let expected = omega0 - alpha * t;
                assert!(
                    (w.y - expected).abs() <= 0.02 * omega0,
                    "{name}: ω_y {:.5} rad/s at t = {t} s, closed form {expected:.5}",
                    w.y
                );
            }
            if stopped_at.is_none() && w.y.abs() < 1e-6 {
                stopped_at = Some(t);
            }
        }
        let stopped_at = stopped_at.unwrap_or_else(|| panic!("{name}: still spinning at 0.2 s"));
        assert!(
            (stopped_at - stop).abs() <= 0.02 * stop,
            "{name}: stopped at {stopped_at} s, closed form {stop:.5} s"
        );
        let turned = omega0 * omega0 / (2.0 * alpha);
        assert!(
            (yaw - turned).abs() <= 0.002 * turned,
            "{name}: turned {yaw:.5} rad, closed form {turned:.5} rad"
        );
        let state = world.states()[0];
        let w = state.angular_momentum / (SIDE * SIDE / 6.0);
        let drift = (state.position.x.powi(2) + state.position.z.powi(2)).sqrt();
        println!(
            "{name}: stopped at {stopped_at} s ({stop:.5}), turned {yaw:.5} rad ({turned:.5}), drift {drift:.2e} m, ω {:.2e}",
            w.norm()
        );
        assert!(drift < 1e-6, "{name}: the cube slid {drift:e} m sideways");
        // soft-step's springs still settle (its sag): 1e-6 rad/s of tilt is left at 0.2 s.
        assert!(w.norm() < 1e-5, "{name}: ω {w:?} rad/s after stopping");
    }
}
