//! Joints and springs against independent truth: closed forms, conservation laws, and a
//! minimal-coordinate ODE solved here by a high-order method.

use nalgebra::{UnitQuaternion, Vector3};
use tumble::joint_scenes::landing_chain;
use tumble::physics::joints::{Correction, Joint, JointKind, Links, Spring, SpringLaw};
use tumble::physics::Orientation;
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
        eprintln!(
            "pendulum {degrees}°: T = {measured:.7} s, T/T₀ = {:.6}",
            measured / t0
        );
        assert!(
            (measured - exact).abs() < 1e-5,
            "{degrees}°: T = {measured:.7} s, 4√(L/g) K = {exact:.7} s (T/T₀ = {:.6})",
            measured / t0
        );
    }
}

/// The pendulum through its lowest point: the largest rod tension of a swing.
#[test]
fn the_tension_at_the_bottom_is_m_g_3_minus_2_cos_theta0() {
    // Energy: v² = 2 g L (1 − cos θ₀) at the bottom; radial Newton: T − m g = m v²/L, so
    // T = m g (3 − 2 cos θ₀): 3 m g = 29.43 N from 90°, m g (3 − √3) = 12.4337 N from 30°.
    for degrees in [30.0_f64, 90.0] {
        let theta0 = degrees.to_radians();
        let want = G * (3.0 - 2.0 * theta0.cos());
        let mut world = simple_pendulum(1.0, theta0, Integrator::Rk4, 1e-3, Correction::Projection);
        let mut peak: f64 = 0.0;
        for _ in 0..3000 {
            world.step();
            peak = peak.max(world.joint_load(0).force.norm());
        }
        eprintln!("tension {degrees}°: {peak:.6} N (want {want:.6})");
        // The step-averaged force near the flat maximum is within O(dt²) of it.
        assert!(
            (peak - want).abs() < 1e-4 * want,
            "{degrees}°: peak tension {peak:.6} N, m g (3 − 2 cos θ₀) = {want:.6} N"
        );
    }
}

/// A 1 m, 1 kg cube hung on a hinge along one of its edges, swinging by `theta0`.
fn cube_on_an_edge(theta0: f64, integrator: Integrator, dt: f64) -> World {
    // The edge through the pivot (origin) along z; the centre hangs d = √2/2 m below it when
    // θ = 0 (the cube turned 45° about z puts an edge on top).
    let d = 0.5_f64.sqrt();
    let turn =
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_4 + theta0);
    let cube = NamedBody {
        name: "cube".into(),
        body: Body::solid_box(Vector3::new(1.0, 1.0, 1.0), 1.0).expect("a cube"),
        initial: State {
            position: Vector3::new(d * theta0.sin(), -d * theta0.cos(), 0.0),
            orientation: Orientation::Quaternion(turn),
            ..State::at_rest()
        },
    };
    let states = vec![cube.initial];
    let hinge = Joint::at_point(
        "edge".into(),
        JointKind::Hinge,
        0,
        None,
        Vector3::zeros(),
        Vector3::z(),
        &states,
    );
    World::with_bodies(vec![cube], gravity(), Vec::new(), None, integrator, dt).with_links(Links {
        joints: vec![hinge],
        ..Links::default()
    })
}

#[test]
fn a_cube_swinging_on_an_edge_has_the_parallel_axis_period() {
    // Parallel axes: I_edge = m a²/6 + m d² = 1/6 + 1/2 = 2/3 kg·m², d = √2/2 m, so
    // T₀ = 2π √(I/(m g d)) = 2π √((2/3)/(9.81 · 0.707107)) = 1.94790 s. At amplitude θ₀ the
    // equation is the simple pendulum's with L = I/(m d): T = 4 √(I/(m g d)) K(sin(θ₀/2)).
    let inertia = 2.0 / 3.0;
    let d = 0.5_f64.sqrt();
    let t0 = 2.0 * std::f64::consts::PI * (inertia / (G * d)).sqrt();
    assert!((t0 - 1.9479).abs() < 5e-5, "T₀ = {t0}");
    let theta0 = 5.0_f64.to_radians();
    let exact = 4.0 * (inertia / (G * d)).sqrt() * elliptic_k((theta0 / 2.0).sin());
    for integrator in [
        Integrator::Rk4,
        Integrator::Splitting,
        Integrator::ExactSplitting,
        Integrator::ExactSplitting4,
    ] {
        let mut world = cube_on_an_edge(theta0, integrator, 1e-3);
        let measured = period(&mut world, 8_000);
        eprintln!(
            "cube {}: T = {measured:.6} s (closed form {exact:.6})",
            integrator.name()
        );
        assert!(
            (measured - exact).abs() < 2e-5,
            "{}: T = {measured:.6} s, closed form {exact:.6} s (T₀ = {t0:.6} s)",
            integrator.name()
        );
    }
}

/// Two point masses m on massless rods l (distance joints between barycenters, so the bobs'
/// rotations are uncoupled), started along a normal mode: θ₂ = ratio · θ₁.
fn double_pendulum(theta1: f64, ratio: f64, integrator: Integrator, dt: f64) -> World {
    let l = 1.0;
    let theta2 = ratio * theta1;
    let x1 = Vector3::new(l * theta1.sin(), -l * theta1.cos(), 0.0);
    let x2 = x1 + Vector3::new(l * theta2.sin(), -l * theta2.cos(), 0.0);
    let bodies = vec![bob("upper", x1), bob("lower", x2)];
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joints = vec![
        Joint::distance("top".into(), 0, None, [x1, Vector3::zeros()], None, &states),
        Joint::distance("middle".into(), 1, Some(0), [x2, x1], None, &states),
    ];
    World::with_bodies(bodies, gravity(), Vec::new(), None, integrator, dt).with_links(Links {
        joints,
        ..Links::default()
    })
}

#[test]
fn the_double_pendulum_has_its_two_normal_modes() {
    // Linearised Lagrangian of two equal masses on equal rods: M θ̈ + K θ = 0 with
    // M = m l² [[2, 1], [1, 1]], K = m g l diag(2, 1); det(K − ω² M) = 0 gives
    // ω² = (2 ∓ √2) g/l, mode shapes θ₂/θ₁ = ±√2 (in phase: slow; opposite: fast).
    let root2 = 2.0_f64.sqrt();
    for (ratio, omega2) in [(root2, 2.0 - root2), (-root2, 2.0 + root2)] {
        let want = 2.0 * std::f64::consts::PI / (omega2 * G).sqrt();
        let mut world = double_pendulum(0.001, ratio, Integrator::Rk4, 1e-3);
        let measured = period(&mut world, 12_000);
        eprintln!("double pendulum mode {ratio:+.4}: T = {measured:.6} s, want {want:.6}");
        // Amplitude 0.001 rad: the nonlinear shift is O(θ²) ≈ 1e-6 of T (at 0.005 rad the fast
        // mode is already 4.7e-5 slow).
        assert!(
            (measured - want).abs() < 2e-5 * want,
            "mode θ₂/θ₁ = {ratio:+.4}: T = {measured:.6} s, 2π/√((2∓√2) g/l) = {want:.6} s"
        );
    }
}

#[test]
fn a_chaotic_double_pendulum_keeps_its_energy_and_joints_over_20_s_with_rk4() {
    // Released horizontal (θ₁ = θ₂ = 90°): chaotic. No drag, no contact: E is a constant of
    // the motion, and projection holds C = 0.
    let mut world = double_pendulum(std::f64::consts::FRAC_PI_2, 1.0, Integrator::Rk4, 1e-3);
    let e0 = world.total_energy().total;
    let scale = 2.0 * 1.0 * G * 2.0; // m g (2 l): the energy's scale, J
    let mut worst_energy: f64 = 0.0;
    let mut worst_joint: f64 = 0.0;
    for _ in 0..20_000 {
        world.step();
        worst_energy = worst_energy.max((world.total_energy().total - e0).abs() / scale);
        let states = world.states();
        for j in &world.links().joints {
            worst_joint = worst_joint.max(j.error(states));
        }
    }
    eprintln!("chaotic double pendulum: energy {worst_energy:.3e}, joint {worst_joint:.3e} m");
    assert!(
        worst_energy < 1e-6,
        "relative energy error {worst_energy:.3e}"
    );
    assert!(worst_joint < 1e-6, "joint error {worst_joint:.3e} m");
}

#[test]
fn without_correction_explicit_euler_lets_the_rod_lengthen_and_projection_stops_it() {
    // Explicit Euler moves the bob along the tangent: each step lengthens the rod by about
    // v² dt² / (2L), so |C| grows; with projection it stays at round-off.
    let theta0 = 60.0_f64.to_radians();
    let mut free = simple_pendulum(1.0, theta0, Integrator::Euler, 1e-3, Correction::None);
    let mut held = simple_pendulum(1.0, theta0, Integrator::Euler, 1e-3, Correction::Projection);
    for _ in 0..2000 {
        free.step();
        held.step();
    }
    let drift = free.links().joints[0].error(free.states());
    let kept = held.links().joints[0].error(held.states());
    eprintln!("euler 60°, 2 s: |C| none {drift:.4e} m, projection {kept:.3e} m");
    assert!(
        drift > 1e-3,
        "without correction |C| = {drift:.3e} m after 2 s"
    );
    assert!(kept < 1e-12, "with projection |C| = {kept:.3e} m");
}

/// A body on a spring to the world (no gravity), pulled by `stretch` along x.
fn spring_body(k: f64, c: f64, stretch: f64, integrator: Integrator) -> World {
    let x0 = Vector3::new(1.0 + stretch, 0.0, 0.0);
    let bodies = vec![bob("mass", x0)];
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let spring = Spring::new(
        "s".into(),
        0,
        None,
        [x0, Vector3::zeros()],
        SpringLaw {
            stiffness: k,
            damping: c,
            rest_length: Some(1.0),
        },
        &states,
    );
    World::with_bodies(
        bodies,
        Effects::default(),
        Vec::new(),
        None,
        integrator,
        1e-3,
    )
    .with_links(Links {
        springs: vec![spring],
        ..Links::default()
    })
}

#[test]
fn a_spring_oscillates_at_the_square_root_of_k_over_m() {
    // m ẍ = −k x: T = 2π √(m/k) = 2π/√100 = 0.628319 s for k = 100 N/m, m = 1 kg.
    let want = 2.0 * std::f64::consts::PI / 10.0;
    let mut world = spring_body(100.0, 0.0, 0.1, Integrator::Rk4);
    let c = upward_crossings(&mut world, 5000, |w| w.state().position.x - 1.0);
    let measured = (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64;
    assert!(
        (measured - want).abs() < 1e-6,
        "T = {measured:.8} s, 2π√(m/k) = {want:.8} s"
    );
    // Energy: ½ k s² = 0.5 J, kept by rk4 to O(dt⁴).
    let e = world.total_energy().total;
    assert!((e - 0.5).abs() < 1e-8, "E = {e}");
}

#[test]
fn a_damped_spring_decays_at_c_over_2m_and_books_its_damping() {
    // m ẍ + c ẋ + k x = 0: x ∝ e^{−γt} cos(ω_d t), γ = c/(2m) = 0.5/s for c = 1 N·s/m.
    // After whole periods of ω_d the displacement is s e^{−γt}; the energy lost is the
    // damping's work, booked as drag work, so the drift stays at the integrator's error.
    let (k, c, s): (f64, f64, f64) = (100.0, 1.0, 0.1);
    let gamma = c / 2.0;
    let omega_d = (k - gamma * gamma).sqrt();
    let mut world = spring_body(k, c, s, Integrator::Rk4);
    // 5 damped periods = 5 · 2π/ω_d; step to the nearest step.
    let t_end = 5.0 * 2.0 * std::f64::consts::PI / omega_d;
    let steps = (t_end / 1e-3).round() as usize;
    for _ in 0..steps {
        world.step();
    }
    let t = world.time();
    // The exact solution from rest at x = s: x = s e^{−γt} (cos ω_d t + γ/ω_d sin ω_d t).
    let exact =
        s * (-gamma * t).exp() * ((omega_d * t).cos() + gamma / omega_d * (omega_d * t).sin());
    let x = world.state().position.x - 1.0;
    assert!(
        (x - exact).abs() < 1e-8,
        "x = {x:.10}, closed form {exact:.10}"
    );
    let balance = world.energy_balance();
    let drag = balance.drag_work.expect("damping booked as drag work");
    assert!(drag < -0.4, "damping work {drag}");
    assert!(balance.drift.abs() < 1e-8, "drift {:.3e} J", balance.drift);
}

#[test]
fn two_bodies_on_a_spring_keep_their_total_momentum_to_round_off() {
    // Equal and opposite spring forces: Σ P is constant, whatever the integrator; the bodies
    // are off-axis, so the spring also turns them (torques r × F).
    for integrator in Integrator::ALL {
        let xa = Vector3::new(0.0, 0.0, 0.0);
        let xb = Vector3::new(1.0, 0.3, 0.0);
        let mut a = bob("a", xa);
        a.initial.linear_momentum = Vector3::new(0.2, -0.1, 0.3);
        let b = bob("b", xb);
        let states = vec![a.initial, b.initial];
        let spring = Spring::new(
            "s".into(),
            0,
            Some(1),
            [
                xa + Vector3::new(0.05, 0.05, 0.0),
                xb - Vector3::new(0.05, 0.0, 0.05),
            ],
            SpringLaw {
                stiffness: 50.0,
                damping: 0.5,
                rest_length: Some(0.8),
            },
            &states,
        );
        let mut world = World::with_bodies(
            vec![a, b],
            Effects::default(),
            Vec::new(),
            None,
            integrator,
            1e-3,
        )
        .with_links(Links {
            springs: vec![spring],
            ..Links::default()
        });
        let p0: Vector3<f64> = world.states().iter().map(|s| s.linear_momentum).sum();
        for _ in 0..2000 {
            world.step();
        }
        let p: Vector3<f64> = world.states().iter().map(|s| s.linear_momentum).sum();
        assert!(
            (p - p0).norm() < 1e-13,
            "{}: ΔP = {:.3e}",
            integrator.name(),
            (p - p0).norm()
        );
    }
}

#[test]
fn the_joint_column_of_run_is_the_anchors_real_separation() {
    // A ball joint whose pivot is 0.8 m above the bob's barycenter, stepped by explicit Euler
    // without correction so that the anchors drift apart; the error column must equal
    // |x + R a − pivot| rebuilt from the body's own CSV (x and q), a = (0, 0.8, 0) in the body.
    let dir = std::env::temp_dir().join(format!("tumble-joint-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("pendulum.toml");
    std::fs::write(
        &file,
        r#"title = "drifting pendulum"
[scene]
dt = 0.002
integrator = "euler"
gravity = [0.0, -9.81, 0.0]
joint_correction = "none"

[body]
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [0.4, -0.69282032302755, 0.0]
orientation = { axis = [0.0, 0.0, 1.0], degrees = 30.0 }

[[joint]]
name = "pivot"
type = "ball"
bodies = ["body1"]
anchor = [0.0, 0.0, 0.0]
"#,
    )
    .unwrap();
    let run = |extra: &[&str]| {
        let out = assert_cmd::Command::cargo_bin("tumble")
            .unwrap()
            .args([
                "run",
                file.to_str().unwrap(),
                "--steps",
                "500",
                "--every",
                "50",
            ])
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let joint = run(&["--joint", "pivot"]);
    let body = run(&[]);
    let mut lines = joint.lines();
    assert_eq!(lines.next(), Some("step,t,error,fx,fy,fz,tx,ty,tz"));
    let anchor = Vector3::new(0.0, 0.8, 0.0);
    let mut last = 0.0;
    for (j, b) in lines.zip(body.lines().skip(1)) {
        let j: Vec<f64> = j.split(',').map(|c| c.parse().unwrap()).collect();
        let b: Vec<f64> = b.split(',').map(|c| c.parse().unwrap()).collect();
        let x = Vector3::new(b[2], b[3], b[4]);
        let q = UnitQuaternion::new_normalize(nalgebra::Quaternion::new(b[5], b[6], b[7], b[8]));
        let separation = (x + q * anchor).norm();
        assert!(
            (j[2] - separation).abs() < 1e-12,
            "step {}: error {} vs {separation}",
            j[0],
            j[2]
        );
        last = j[2];
    }
    assert!(last > 1e-3, "the anchors should have drifted apart: {last}");
}

/// The lowest corner of a box of half-extents `half` at `state`, m.
fn lowest_corner(state: &State, half: &Vector3<f64>) -> f64 {
    let r = state.orientation.matrix();
    state.position.y - (0..3).map(|k| r[(1, k)].abs() * half[k]).sum::<f64>()
}

#[test]
fn a_chain_landing_on_the_ground_keeps_its_links_while_the_contacts_act() {
    // 10 links of 0.3 m tilted 20°, the low end 0.3 m up: it lands end first, link after
    // link. The contact response alone moves each touched link on its own (its impulse and
    // its push-out); `joints::contact` then solves the joint rows together with the contact
    // normals, so the joints stay closed (|C| at the projection's 1e-12 m) and no link is
    // pushed back into the ground.
    let (count, l) = (10, 0.3);
    let mut world = landing_chain(count, l, 20.0_f64.to_radians(), 0.3);
    let half = Vector3::new(l / 2.0, 0.025, 0.025);
    let (mut worst_joint, mut deepest, mut touching_steps): (f64, f64, usize) = (0.0, 0.0, 0);
    for _ in 0..3000 {
        world.step();
        if world.contacts().is_empty() {
            continue;
        }
        touching_steps += 1;
        let states = world.states();
        for j in &world.links().joints {
            worst_joint = worst_joint.max(j.error(states));
        }
        for s in states {
            deepest = deepest.max(-lowest_corner(s, &half));
        }
    }
    let states = world.states();
    let speed = states
        .iter()
        .map(|s| (s.linear_momentum / 0.1).norm())
        .fold(0.0, f64::max);
    let heights: Vec<f64> = states.iter().map(|s| s.position.y).collect();
    eprintln!(
        "chain landing: {touching_steps} steps in contact, |C| ≤ {worst_joint:.3e} m, \
         deepest {deepest:.3e} m, final speed {speed:.3e} m/s, heights {heights:.4?}"
    );
    assert!(
        touching_steps > 2000,
        "the chain touched only {touching_steps} steps"
    );
    assert!(
        worst_joint < 1e-9,
        "joint error {worst_joint:.3e} m while touching"
    );
    // Free fall lands at about √(2 g h) ≈ 4.5 m/s: a step covers 4.5 mm; what is left inside
    // the ground after a response is far less.
    assert!(
        deepest < 1e-3,
        "a link is {deepest:.3e} m inside the ground"
    );
    // At rest on the ground after 3 s: every barycenter at the half-thickness 0.025 m.
    for (i, y) in heights.iter().enumerate() {
        assert!((y - 0.025).abs() < 1e-3, "link {i} at y = {y:.5} m");
    }
    assert!(speed < 1e-2, "still moving at {speed:.3e} m/s");
}

#[test]
fn a_conical_pendulum_holds_its_angle_and_turns_at_the_square_root_of_g_over_l_cos_alpha() {
    // A point bob on a rod L = 1 m at α = 30° from the vertical, thrown sideways at
    // v = ω L sin α with ω² = g / (L cos α): the rod's tension T cos α = m g and
    // T sin α = m ω² L sin α balance, so it circles at constant height, period 2π/ω.
    let (l, alpha) = (1.0, 30.0_f64.to_radians());
    let omega = (G / (l * alpha.cos())).sqrt();
    let x0 = Vector3::new(l * alpha.sin(), -l * alpha.cos(), 0.0);
    let mut body = bob("bob", x0);
    body.initial.linear_momentum = Vector3::new(0.0, 0.0, -omega * l * alpha.sin()); // m = 1 kg
    let states = vec![body.initial];
    let rod = Joint::distance("rod".into(), 0, None, [x0, Vector3::zeros()], None, &states);
    let mut world = World::with_bodies(
        vec![body],
        gravity(),
        Vec::new(),
        None,
        Integrator::Rk4,
        1e-3,
    )
    .with_links(Links {
        joints: vec![rod],
        ..Links::default()
    });
    let mut worst_angle: f64 = 0.0;
    let mut crossings = Vec::new();
    let mut last = world.state().position.z;
    for _ in 0..10_000 {
        let t0 = world.time();
        world.step();
        let p = world.state().position;
        worst_angle = worst_angle.max(((-p.y / p.norm()).acos() - alpha).abs());
        if last < 0.0 && p.z >= 0.0 {
            crossings.push(t0 + world.dt() * (-last) / (p.z - last));
        }
        last = p.z;
    }
    let measured = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let want = 2.0 * std::f64::consts::PI / omega;
    eprintln!(
        "conical pendulum 30°: angle kept to {worst_angle:.3e} rad over 10 s, \
         T = {measured:.7} s, 2π √(L cos α / g) = {want:.7} s"
    );
    assert!(crossings.len() >= 4, "{crossings:?}");
    assert!(worst_angle < 1e-6, "angle drifted by {worst_angle:.3e} rad");
    assert!(
        (measured - want).abs() < 1e-6 * want,
        "T = {measured:.7} s, want {want:.7} s"
    );
}

/// The first angular frequency of `n` uniform rods (length l, width w, hanging from a pivot,
/// planar small swings) from the linearised Lagrangian, with the mode's shape (θ_i). With
/// a_ij = 1 for j < i, ½ for j = i: x_i = l Σ_j a_ij θ_j (barycenter i), so
/// T = ½ θ̇ᵀ M θ̇, M_jk = m l² Σ_i a_ij a_ik + δ_jk m (l² + w²)/12, and
/// V = ½ θᵀ K θ, K_jj = m g l ((n − 1 − j) + ½) (rod j lifts its own barycenter and all the
/// rods below it). K v = ω² M v, solved as the symmetric L⁻¹ K L⁻ᵀ with M = L Lᵀ.
fn chain_first_mode(n: usize, l: f64, w: f64, m: f64) -> (f64, Vec<f64>) {
    use nalgebra::DMatrix;
    let a = |i: usize, j: usize| match j.cmp(&i) {
        std::cmp::Ordering::Less => 1.0,
        std::cmp::Ordering::Equal => 0.5,
        std::cmp::Ordering::Greater => 0.0,
    };
    let mass = DMatrix::from_fn(n, n, |j, k| {
        let translation: f64 = (0..n).map(|i| a(i, j) * a(i, k)).sum();
        m * l * l * translation
            + if j == k {
                m * (l * l + w * w) / 12.0
            } else {
                0.0
            }
    });
    let stiffness = DMatrix::from_fn(n, n, |j, k| {
        if j == k {
            m * G * l * ((n - 1 - j) as f64 + 0.5)
        } else {
            0.0
        }
    });
    let chol = mass.cholesky().expect("M is positive definite");
    let lower = chol.l();
    let inv = lower.clone().try_inverse().expect("L invertible");
    let reduced = &inv * stiffness * inv.transpose();
    let eigen = nalgebra::SymmetricEigen::new(reduced);
    let (index, &omega2) = eigen
        .eigenvalues
        .iter()
        .enumerate()
        .min_by(|x, y| x.1.total_cmp(y.1))
        .expect("n > 0");
    let shape = inv.transpose() * eigen.eigenvectors.column(index);
    (omega2.sqrt(), shape.iter().copied().collect())
}

#[test]
fn a_chain_of_10_rods_swings_in_the_first_mode_of_its_linearised_lagrangian() {
    // 10 rods of 0.1 m (0.1 × 0.01 × 0.01 m boxes, 0.05 kg), ball-jointed end to end and
    // to a world pivot, started along the first mode shape with the largest angle 0.002
    // rad: every rod then swings at ω₁ (the nonlinear shift is O(θ²) ≈ 1e-7 of T).
    let (n, l, w, m) = (10, 0.1, 0.01, 0.05);
    let (omega, shape) = chain_first_mode(n, l, w, m);
    let largest = shape.iter().fold(0.0_f64, |a, s| a.max(s.abs()));
    let angles: Vec<f64> = shape.iter().map(|s| 0.002 * s / largest).collect();
    let mut top = Vector3::zeros();
    let mut bodies = Vec::new();
    let mut pivots = Vec::new();
    for (i, theta) in angles.iter().enumerate() {
        let down = Vector3::new(theta.sin(), -theta.cos(), 0.0);
        bodies.push(NamedBody {
            name: format!("rod{i}"),
            body: Body::solid_box(Vector3::new(w, l, w), m).expect("a box"),
            initial: State {
                position: top + down * (l / 2.0),
                orientation: Orientation::Quaternion(UnitQuaternion::from_axis_angle(
                    &Vector3::z_axis(),
                    *theta,
                )),
                ..State::at_rest()
            },
        });
        pivots.push(top);
        top += down * l;
    }
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joints = pivots
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let b = i.checked_sub(1);
            Joint::at_point(
                format!("j{i}"),
                JointKind::Ball,
                i,
                b,
                *p,
                Vector3::z(),
                &states,
            )
        })
        .collect();
    let mut world = World::with_bodies(bodies, gravity(), Vec::new(), None, Integrator::Rk4, 1e-3)
        .with_links(Links {
            joints,
            ..Links::default()
        });
    let want = 2.0 * std::f64::consts::PI / omega;
    // The lowest rod's barycenter, x: 5 periods of about 1.7 s.
    let crossings = upward_crossings(&mut world, 9_000, |w| w.states()[n - 1].position.x);
    assert!(crossings.len() >= 4, "{crossings:?}");
    let measured = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    eprintln!("chain of 10 rods: first mode T = {measured:.6} s, eigenproblem {want:.6} s");
    assert!(
        (measured - want).abs() < 2e-5 * want,
        "T = {measured:.6} s, 2π/ω₁ = {want:.6} s"
    );
}

/// The worst |E − E₀| over the first and the second half of `steps`, J.
fn energy_error_halves(world: &mut World, steps: usize) -> (f64, f64) {
    let e0 = world.total_energy().total;
    let mut worst = [0.0_f64; 2];
    for k in 0..steps {
        world.step();
        let half = usize::from(k >= steps / 2);
        worst[half] = worst[half].max((world.total_energy().total - e0).abs());
    }
    (worst[0], worst[1])
}

#[test]
fn symplectic_euler_with_its_shake_projection_keeps_the_pendulum_energy_bounded() {
    // The 90° pendulum (L = 1 m, 1 kg, m g L = 9.81 J) for 20 s at dt = 1 ms. Symplectic
    // Euler with SHAKE (positions along the step's start rows, momenta corrected alike) and
    // the velocity projection is symplectic on the constraint manifold: its energy error is
    // O(dt) and oscillates, the second 10 s no worse than the first. Explicit Euler with the
    // same rod gains energy every swing: its second half is worse than its first.
    let theta0 = std::f64::consts::FRAC_PI_2;
    let run = |integrator| {
        let mut world = simple_pendulum(1.0, theta0, integrator, 1e-3, Correction::Projection);
        energy_error_halves(&mut world, 20_000)
    };
    let (first, second) = run(Integrator::SymplecticEuler);
    let (euler_first, euler_second) = run(Integrator::Euler);
    eprintln!(
        "90° pendulum, 20 s: symplectic-euler |ΔE| ≤ {first:.4e} J then {second:.4e} J; \
         euler {euler_first:.4e} J then {euler_second:.4e} J"
    );
    // Its period over 10 s (lesson 25's table) against T = 4 √(L/g) K(sin 45°) = 2.367842 s
    // (measured 2.367839 s: the period is kept far better than E).
    let mut world = simple_pendulum(
        1.0,
        theta0,
        Integrator::SymplecticEuler,
        1e-3,
        Correction::Projection,
    );
    let measured = period(&mut world, 10_000);
    let ten_s = {
        let mut w = simple_pendulum(
            1.0,
            theta0,
            Integrator::SymplecticEuler,
            1e-3,
            Correction::Projection,
        );
        let (a, b) = energy_error_halves(&mut w, 10_000);
        a.max(b)
    };
    eprintln!("symplectic-euler, 90°, 10 s: T = {measured:.6} s, |ΔE| ≤ {ten_s:.4e} J");
    assert!(
        (measured - 2.367842).abs() < 0.01 * 2.367842,
        "T = {measured:.6} s"
    );
    // O(dt) of m g L: 9.81 J × 1e-3 × a few.
    assert!(second < 0.05, "symplectic-euler |ΔE| = {second:.4e} J");
    assert!(
        second < 1.2 * first,
        "grows: {first:.4e} J then {second:.4e} J"
    );
    assert!(
        euler_second > 1.5 * euler_first,
        "euler: {euler_first:.4e} then {euler_second:.4e}"
    );
}

/// The derive phase after a projection takes each body's R and I⁻¹_world from the
/// projection's last build (`projection::Buffers::derived`): they must be `derive`'s own, to
/// the bit, after a plain step and after going back to an earlier frame (whose orientations
/// the projection never saw).
#[test]
fn the_derive_phase_after_a_projection_is_derive_itself() {
    use tumble::joint_scenes::chain;
    use tumble::physics::derive::derive;
    use tumble::physics::Phase;
    let bits = |m: &nalgebra::Matrix3<f64>| m.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let check = |world: &mut World| {
        assert_eq!(world.step_phase(), Phase::Derive);
        for (i, (body, state)) in world.bodies().iter().zip(world.states()).enumerate() {
            let (got, want) = (world.kinematics_of(i), derive(body, state));
            assert_eq!(bits(&got.rotation), bits(&want.rotation), "R of body {i}");
            assert_eq!(
                bits(&got.inv_inertia_world),
                bits(&want.inv_inertia_world),
                "I⁻¹_world of body {i}"
            );
            assert_eq!(got.angular_velocity, want.angular_velocity, "ω of body {i}");
        }
        while world.step_phase() != Phase::Collide {}
    };
    let mut world = chain(10, JointKind::Hinge, Correction::Projection);
    let early = world.checkpoint();
    for _ in 0..50 {
        world.step();
    }
    check(&mut world);
    world.restore(&early);
    check(&mut world);
}
