//! `walk --error`: the `±` beside each number against independent truth — the closed-form free
//! top for a tumbling box, the pendulum's θ'' = −(g/L) sin θ solved here by RK4 at a step
//! whose halving changes nothing above 1e-12 m. Each ± must be within a factor 3 of the true
//! error wherever the true error is above round-off (1e-9).

use std::path::Path;
use tumble::error_bars::{ReferenceRun, RowError};
use tumble::physics::free_top::FreeBody;
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
            println!("{what}[{k}]: ± {e:.4e}, true {t:.4e}");
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
fn the_error_of_a_tumbling_box_is_the_distance_from_the_free_top() {
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
    for integrator in [Integrator::Euler, Integrator::Splitting] {
        let mut world = scene.world_with(integrator, 0.01);
        let mut reference = ReferenceRun::new(&scene, 0.01);
        let first = scene.first();
        let mut truth = FreeBody::new(
            &first.body,
            first.initial.orientation.quaternion(),
            first.initial.angular_momentum,
        );
        let mut checked = 0;
        for frame in 1..=150 {
            world.step();
            reference.advance();
            if frame % 50 != 0 {
                continue;
            }
            let t = world.time();
            let errors = reference.errors(&world, 0);
            let s = world.snapshot();
            let mut q = truth.orientation(t).quaternion().coords;
            let shown = s.quaternion.quaternion().coords;
            if q.dot(&shown) < 0.0 {
                q = -q;
            }
            // nalgebra stores (x, y, z, w); the table prints w x y z.
            let d = shown - q;
            let true_q = [d[3].abs(), d[0].abs(), d[1].abs(), d[2].abs()];
            checked += assert_within_3(
                &format!("{} q at t = {t}", integrator.name()),
                row(&errors, "state", "q"),
                &true_q,
            );
            let w = (s.angular_velocity_body - truth.omega_body(t)).abs();
            checked += assert_within_3(
                &format!("{} ωbody at t = {t}", integrator.name()),
                row(&errors, "angular velocity", "ωbody"),
                &[w.x, w.y, w.z],
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
    let solve = |t: f64, n: usize| {
        let f = |y: [f64; 2]| [y[1], -9.81 * y[0].sin()];
        let h = t / n as f64;
        let mut y = [std::f64::consts::FRAC_PI_2, 0.0];
        for _ in 0..n {
            let k1 = f(y);
            let k2 = f([y[0] + h / 2.0 * k1[0], y[1] + h / 2.0 * k1[1]]);
            let k3 = f([y[0] + h / 2.0 * k2[0], y[1] + h / 2.0 * k2[1]]);
            let k4 = f([y[0] + h * k3[0], y[1] + h * k3[1]]);
            for i in 0..2 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    };
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
            let (y, half) = (solve(t, 20_000), solve(t, 40_000));
            let x_true = [y[0].sin(), -y[0].cos()];
            assert!(
                (half[0] - y[0]).abs() < 1e-12,
                "the test's solution is not converged"
            );
            let v_true = [y[1] * y[0].cos(), y[1] * y[0].sin()];
            let s = world.snapshot();
            let errors = reference.errors(&world, 0);
            checked += assert_within_3(
                &format!("{} x at t = {t}", integrator.name()),
                row(&errors, "state", "x"),
                &[
                    (s.position.x - x_true[0]).abs(),
                    (s.position.y - x_true[1]).abs(),
                ],
            );
            checked += assert_within_3(
                &format!("{} v at t = {t}", integrator.name()),
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
