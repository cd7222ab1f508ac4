//! The contact methods charted as the integrators are (`tumble study FILE --response A,B`):
//! each method over the dt sweep at the scene's integrator, its error against the closed form
//! of a straight bounce (lesson 32: a cube dropped flat, e = 0.5, no friction).

use assert_cmd::Command;
use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::{Response, SoftStep};
use tumble::study::{methods, Case, Timing};

const G: f64 = 9.81;

/// The barycenter's height of a point dropped from rest at `y0` onto a floor it touches at
/// `touch`, restitution `e`, at time `t`: flights of `y − ½ g s²` and `v s − ½ g s²` between
/// touches, each rebound e times the speed it landed with (written here from the law, not
/// from the study's `bounce`).
fn bounce_height(y0: f64, touch: f64, e: f64, t: f64) -> f64 {
    let mut land = (2.0 * (y0 - touch) / G).sqrt();
    if t <= land {
        return y0 - 0.5 * G * t * t;
    }
    let mut speed = e * G * land;
    while speed > 1e-12 {
        let flight = 2.0 * speed / G;
        if t <= land + flight {
            let s = t - land;
            return touch + speed * s - 0.5 * G * s * s;
        }
        land += flight;
        speed *= e;
    }
    touch
}

fn bounce_case() -> Case {
    let lesson = tumble::lessons::load(Path::new("32-predict-the-bounce")).unwrap();
    Case::from_lesson(&lesson)
}

/// The study's error of `response` at `dt` worked out here: the scene stepped to every sample
/// time (every 0.1 s and the end), angle(q₀⁻¹q) + |x − x_cf| / radius against the closed form,
/// the largest.
fn closed_form_error(case: &Case, response: Response, dt: f64) -> f64 {
    let mut scene = case.scene.clone();
    scene.contact.as_mut().unwrap().response = response;
    let body = &scene.first().body;
    let (radius, x0, q0) = (
        body.radius,
        scene.first().initial.position,
        scene.first().initial.orientation.quaternion(),
    );
    let mut world = scene.world_with(scene.integrator, dt);
    let mut times: Vec<f64> = (1..12).map(|k| k as f64 * 0.1).collect();
    times.push(case.duration);
    let mut worst: f64 = 0.0;
    for t in times {
        while world.step_count() < (t / dt).round() as u64 {
            world.step();
        }
        let state = world.state();
        let truth = Vector3::new(x0.x, bounce_height(x0.y, 0.1, 0.5, t), x0.z);
        let angle = q0.angle_to(&state.orientation.quaternion());
        worst = worst.max(angle + (state.position - truth).norm() / radius);
    }
    worst
}

#[test]
fn each_methods_error_is_its_distance_from_the_closed_form_bounce() {
    let case = bounce_case();
    let methods_charted = [Response::Impulse, Response::SoftStep(SoftStep::DEFAULT)];
    let dts = [1e-2, 1e-3, 1e-4];
    let timing = Timing {
        repeats: 0,
        sample_interval: 0.1,
    };
    let chart = methods::study(&case, &methods_charted, &dts, timing);
    assert_eq!((chart.reference_kind, chart.measure), ("exact", "error"));
    assert!(
        chart.reference.contains("closed-form bounce"),
        "{}",
        chart.reference
    );
    assert_eq!(chart.rows.len(), 6);
    for row in &chart.rows {
        assert!(row.run.ok(), "{:?}", row.run.status);
        let expected = closed_form_error(&case, row.response, row.run.dt);
        assert!(
            (row.error - expected).abs() <= 1e-12 * expected.max(1.0),
            "{} at dt {}: study {} against {} from the closed form",
            row.response.name(),
            row.run.dt,
            row.error,
            expected
        );
        // A touch is found within a step of when it falls: the rebound leaves at most a step
        // late or early, v₁ = √(2 g 0.9) = 4.2 m/s, so the barycenter is within about
        // (1 + e) v₁ dt of the closed form (in radii: the cube's is 0.1732 m). soft-step's
        // corners bounce together (a face that lands flat leaves flat), so it is held to the
        // same bound; they once bounced one by one and turned the cube a radian off.
        let bound = (1.0 + 0.5) * (2.0 * G * 0.9f64).sqrt() * row.run.dt / 0.1732;
        assert!(
            row.error < bound && row.error > 1e-6,
            "{} at dt {}: error {} (bound {bound})",
            row.response.name(),
            row.run.dt,
            row.error
        );
    }
    let order = |r: Response| chart.orders.iter().find(|o| o.response == r).unwrap();
    for response in methods_charted {
        let p = order(response).slope.expect("three runs fitted");
        assert!((0.5..1.5).contains(&p), "{} order {p}", response.name());
    }
    // soft-step's error falls with dt: at least 10× from dt = 1e-2 to 1e-4 (35× measured).
    let soft = |dt: f64| {
        let row = chart
            .rows
            .iter()
            .find(|r| r.response == methods_charted[1] && r.run.dt.to_bits() == dt.to_bits());
        row.unwrap().error
    };
    assert!(
        soft(1e-2) > 10.0 * soft(1e-4),
        "soft-step errs {} at dt 1e-2, {} at 1e-4",
        soft(1e-2),
        soft(1e-4)
    );
}

#[test]
fn a_comma_list_names_each_method_once() {
    let run = |list: &str| {
        Command::cargo_bin("tumble")
            .unwrap()
            .args(["study", "32-predict-the-bounce", "--response", list])
            .output()
            .unwrap()
    };
    let out = run("impulse,soft-stp");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("unknown collision response `soft-stp` (did you mean `soft-step`?)"),
        "{stderr}"
    );
    let out = run("impulse,,soft-step");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("an empty name in the list"));
    let out = run("impulse,impulse");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("`impulse` is listed twice"));
}
