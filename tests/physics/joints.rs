//! Joints and springs against independent truth: closed forms, conservation laws, and a
//! minimal-coordinate ODE solved here by a high-order method.

use nalgebra::{UnitQuaternion, Vector3};
use tumble::physics::joints::{Correction, Joint, JointKind, Links, Spring};
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
        k,
        c,
        Some(1.0),
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
            50.0,
            0.5,
            Some(0.8),
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
