//! `soft-step` (issue 17): the sag its module doc derives, its energy bound, the scene keys and
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
