//! `walk --error`: the `±` beside each number against independent truth, solved here by the
//! tests' own adaptive extrapolation solver ([`super::ode`], independent of tumble's
//! integrators and of its closed-form top) to 1e-13 per step: for a tumbling box, Euler's
//! equations I ω̇ = (I ω) × ω with q̇ = ½ q ⊗ (0, ω) (checked by the conservation of |L| and E),
//! and its energy against E₀ (conservation: the true error of E is |E − E₀|); for a pendulum,
//! θ'' = −(g/L) sin θ. Each ± must be within a factor 3 of the true error wherever the true
//! error is above round-off (1e-9).

use super::ode;
use std::path::Path;
use tumble::error_bars::{ReferenceRun, RowError};
use tumble::physics::Integrator;
use tumble::scene::Scene;

fn scene(source: &str) -> Scene {
    tumble::scene::parse(source, Path::new("inline.toml"))
        .expect("valid scene")
        .scene
}

fn row<'a>(errors: &'a [RowError], panel: &str, label: &str) -> &'a RowError {
    errors
        .iter()
        .find(|e| e.panel == panel && e.label == label)
        .unwrap_or_else(|| panic!("no ± for {panel} {label}"))
}

/// Each shown ± against the true error, component by component.
fn assert_within_3(what: &str, shown: &RowError, truth: &[f64]) -> usize {
    assert!(
        shown.converged,
        "{what}: reference not converged ({shown:?})"
    );
    let mut checked = 0;
    for (k, (&e, &t)) in shown.errors.iter().zip(truth).enumerate() {
        if t > 1e-9 {
            println!("{what}[{k}]: ± {e:.4e}, true {t:.4e}, ratio {:.4}", e / t);
            let ratio = e / t;
            assert!(
                (1.0 / 3.0..=3.0).contains(&ratio),
                "{what}[{k}]: ± {e:.4e}, true {t:.4e}"
            );
            checked += 1;
        }
    }
    checked
}

#[test]
fn the_error_of_a_tumbling_box_is_the_distance_from_eulers_equations_solved_here() {
    // A 3:2:1 box spun near its middle axis (the tennis racket): no torque, no gravity.
    let scene = scene(
        r#"title = "tumble"
[scene]
dt = 0.01
integrator = "euler"
[body]
shape = "box"
size = [0.3, 0.2, 0.1]
mass = 1.0
angular_velocity_body = [0.05, 6.0, 0.05]
"#,
    );
    // The solid box's principal moments m (b² + c²) / 12 …, its axes the body frame.
    let (a, b, c) = (0.3f64, 0.2f64, 0.1f64);
    let moments = [
        (b * b + c * c) / 12.0,
        (a * a + c * c) / 12.0,
        (a * a + b * b) / 12.0,
    ];
    let first = scene.first();
    assert!(
        (first.initial.orientation.quaternion().w - 1.0).abs() < 1e-15,
        "the box starts unrotated"
    );
    // y = (ω_body, q = w x y z).
    let euler = move |y: &[f64; 7]| {
        let [w1, w2, w3, qw, qx, qy, qz] = *y;
        let [i1, i2, i3] = moments;
        [
            (i2 - i3) * w2 * w3 / i1,
            (i3 - i1) * w3 * w1 / i2,
            (i1 - i2) * w1 * w2 / i3,
            0.5 * (-qx * w1 - qy * w2 - qz * w3),
            0.5 * (qw * w1 + qy * w3 - qz * w2),
            0.5 * (qw * w2 + qz * w1 - qx * w3),
            0.5 * (qw * w3 + qx * w2 - qy * w1),
        ]
    };
    let y0 = [0.05, 6.0, 0.05, 1.0, 0.0, 0.0, 0.0];
    let invariants = |y: &[f64; 7]| {
        let l: f64 = (0..3).map(|i| (moments[i] * y[i]).powi(2)).sum();
        let e: f64 = (0..3).map(|i| 0.5 * moments[i] * y[i] * y[i]).sum();
        (l.sqrt(), e)
    };
    let times = [0.5, 1.0, 1.5];
    let truth = ode::samples(&euler, y0, &times, 1e-13, &|y| y.to_vec(), 1e-11);
    let (l0, e0) = invariants(&y0);
    for y in &truth {
        let (l, e) = invariants(y);
        assert!((l - l0).abs() < 1e-12 && (e - e0).abs() < 1e-12, "{l} {e}");
    }
    for integrator in [Integrator::Euler, Integrator::Splitting] {
        let mut world = scene.world_with(integrator, 0.01);
        let mut reference = ReferenceRun::new(&scene, 0.01);
        let energy0 = world.snapshot().system.energy.total;
        let mut checked = 0;
        for frame in 1..=150 {
            world.step();
            reference.advance();
            if frame % 50 != 0 {
                continue;
            }
            let t = world.time();
            let y = truth[frame / 50 - 1];
            let errors = reference.errors(&world, 0);
            let s = world.snapshot();
            let shown = s.quaternion.quaternion();
            let sign = if shown.w * y[3] + shown.i * y[4] + shown.j * y[5] + shown.k * y[6] < 0.0 {
                -1.0
            } else {
                1.0
            };
            let true_q = [
                (shown.w - sign * y[3]).abs(),
                (shown.i - sign * y[4]).abs(),
                (shown.j - sign * y[5]).abs(),
                (shown.k - sign * y[6]).abs(),
            ];
            checked += assert_within_3(
                &format!("box {} q at t = {t}", integrator.name()),
                row(&errors, "state", "q"),
                &true_q,
            );
            let w = s.angular_velocity_body;
            checked += assert_within_3(
                &format!("box {} ωbody at t = {t}", integrator.name()),
                row(&errors, "angular velocity", "ωbody"),
                &[(w.x - y[0]).abs(), (w.y - y[1]).abs(), (w.z - y[2]).abs()],
            );
            // Conservation: the true energy is E₀ at every t (no torque, no gravity).
            let energy = &row(&errors, "energy", "K, V, E");
            let shown_e = s.system.energy.total;
            checked += assert_within_3(
                &format!("box {} E at t = {t}", integrator.name()),
                &RowError {
                    errors: vec![energy.errors[2]],
                    ..(*energy).clone()
                },
                &[(shown_e - energy0).abs()],
            );
        }
        assert!(
            checked >= 6,
            "{}: only {checked} numbers checked",
            integrator.name()
        );
    }
}

#[test]
fn the_error_of_a_pendulum_is_the_distance_from_its_minimal_coordinate_solution() {
    let scene = scene(
        r#"title = "pendulum"
[scene]
dt = 0.001
integrator = "euler"
gravity = [0.0, -9.81, 0.0]
[body]
name = "bob"
shape = "box"
size = [0.1, 0.1, 0.1]
mass = 1.0
position = [1.0, 0.0, 0.0]
[[joint]]
type = "distance"
bodies = ["bob"]
anchors = [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
"#,
    );
    // θ from the downward vertical, released from 90°: x = (sin θ, −cos θ).
    let pendulum = |y: &[f64; 2]| [y[1], -9.81 * y[0].sin()];
    let solve =
        |t: f64, tol: f64| ode::solve(&pendulum, [std::f64::consts::FRAC_PI_2, 0.0], t, tol);
    // rk4 at a coarser step, so that its error is above round-off.
    for (integrator, dt) in [
        (Integrator::Euler, 1e-3),
        (Integrator::SymplecticEuler, 1e-3),
        (Integrator::Rk4, 1e-2),
    ] {
        let mut world = scene.world_with(integrator, dt);
        let mut reference = ReferenceRun::new(&scene, dt);
        let mut checked = 0;
        let frames = (0.6 / dt).round() as u64;
        for frame in 1..=frames {
            world.step();
            reference.advance();
            if frame % (frames / 3) != 0 {
                continue;
            }
            let t = world.time();
            let (y, finer) = (solve(t, 1e-13), solve(t, 1e-15));
            let x_true = [y[0].sin(), -y[0].cos()];
            assert!(
                (finer[0] - y[0]).abs() < 1e-12,
                "the test's solution is not converged"
            );
            let v_true = [y[1] * y[0].cos(), y[1] * y[0].sin()];
            let s = world.snapshot();
            let errors = reference.errors(&world, 0);
            checked += assert_within_3(
                &format!("pendulum {} x at t = {t}", integrator.name()),
                row(&errors, "state", "x"),
                &[
                    (s.position.x - x_true[0]).abs(),
                    (s.position.y - x_true[1]).abs(),
                ],
            );
            checked += assert_within_3(
                &format!("pendulum {} v at t = {t}", integrator.name()),
                row(&errors, "linear momentum", "v"),
                &[
                    (s.velocity.x - v_true[0]).abs(),
                    (s.velocity.y - v_true[1]).abs(),
                ],
            );
        }
        assert!(
            checked >= 6,
            "{}: only {checked} numbers checked",
            integrator.name()
        );
    }
}

#[test]
fn walk_error_names_its_reference_and_prints_a_plus_minus_row_per_table_row() {
    let output = assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .args(["walk", "25-the-pendulum", "--frames", "3", "--error"])
        .output()
        .unwrap();
    assert!(output.status.success());
    let text = String::from_utf8(output.stdout).unwrap();
    assert!(
        text.contains("reference: the same scene stepped by rk4 at dt = 1.0000e-4 s"),
        "{text}"
    );
    let lines: Vec<&str> = text.lines().collect();
    for (i, line) in lines.iter().enumerate() {
        if line.trim_start().starts_with("x ") && i > 0 {
            let next = lines[i + 1].trim_start();
            assert!(next.starts_with('±'), "no ± under {line}: {next}");
            // One ± per printed number.
            assert_eq!(
                next.split_whitespace().count(),
                line.split_whitespace().count() - 1,
                "{line}\n{next}"
            );
        }
    }
}
