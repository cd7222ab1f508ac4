//! Thin, fast bodies do not pass through each other within one step (issue 17, item 5).
//!
//! Detection looks at the poses the integrate phase reached. A 1 cm plate closing at 30 m/s on
//! another 1 cm plate at dt = 1e-3 moves 3 cm per step, more than both thicknesses together: at
//! the end of one step the pair overlaps past its middle (the least-penetration normal points
//! the wrong way and pushes it through) or does not overlap at all (no contact). The tests below
//! start the pair at several heights so that every such case occurs, and check the independent
//! truths of an inelastic, frictional head-on impact: the order along the line of approach is
//! kept (A stays above B), momentum is kept exactly, and no energy is made.

use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::{Response, World};
use tumble::scene::parse;

/// A world from scene-file text.
fn world(source: &str) -> World {
    parse(source, Path::new("t.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
        .world()
}

/// Two 20 × 1 × 20 cm plates, 1 kg each, no gravity: A at height `y` falling at `speed`, B at
/// the origin rising at `speed`.
fn two_plates(y: f64, speed: f64, response: &str) -> World {
    world(&format!(
        r#"
title = "plates"
[scene]
dt = 0.001
integrator = "rk4"
contact = {{ response = "{response}", restitution = 0.0, friction = 0.5 }}
[[body]]
name = "a"
shape = "box"
size = [0.2, 0.01, 0.2]
mass = 1.0
position = [0.0, {y}, 0.0]
velocity = [0.0, -{speed}, 0.0]
[[body]]
name = "b"
shape = "box"
size = [0.2, 0.01, 0.2]
mass = 1.0
velocity = [0.0, {speed}, 0.0]
"#
    ))
}

#[test]
fn a_thin_plate_closing_at_30_m_per_s_does_not_pass_through_a_thin_plate() {
    // 15 m/s each: 3 cm per step closing, three times the 1 cm the two plates need to cross
    // (their centres are 1 cm apart when the faces touch). Starting heights 1 mm apart cover
    // every phase of the step: past the middle at the end of a step, and clean through.
    const CLOSING_PER_STEP: f64 = 0.03;
    let mut failures = Vec::new();
    for response in ["impulse", "soft-step"] {
        for k in 0..30 {
            let y = 0.05 + 1e-3 * k as f64;
            let mut w = two_plates(y, 15.0, response);
            let p0: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
            let e0 = w.total_energy().total;
            let mut lowest = f64::INFINITY;
            let mut highest_energy = e0;
            for _ in 0..40 {
                w.step();
                let gap = w.states()[0].position.y - w.states()[1].position.y;
                lowest = lowest.min(gap);
                highest_energy = highest_energy.max(w.total_energy().total);
            }
            let gap = w.states()[0].position.y - w.states()[1].position.y;
            let p: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
            let speeds = w
                .states()
                .iter()
                .map(|s| s.linear_momentum.norm())
                .fold(0.0, f64::max);
            // Touching faces: centres 1 cm apart; passing through makes the gap negative.
            // `impulse` with e = 0 may stop up to one step's travel short (see `sweep`);
            // `soft-step` closes that gap within its sub-steps.
            let short = if response == "impulse" {
                CLOSING_PER_STEP
            } else {
                0.0
            };
            let checks = [
                (
                    lowest > 0.01 - 2e-3,
                    format!("centres came within {lowest} m"),
                ),
                (
                    gap > 0.01 - 1e-3 && gap < 0.01 + short + 1e-3,
                    format!("centres {gap} m apart after the impact"),
                ),
                ((p - p0).norm() < 1e-9, format!("P {p0:?} → {p:?}")),
                (
                    highest_energy <= e0 * (1.0 + 1e-12),
                    format!("E {e0} → {highest_energy}"),
                ),
                // Equal masses, head on, e = 0: both stop.
                // (soft-step: its springs relax the last 1e-5 over a few more steps.)
                (
                    speeds < 1e-4,
                    format!("|P| {speeds} left after an inelastic impact"),
                ),
            ];
            for (ok, what) in checks {
                if !ok {
                    failures.push(format!("{response}, y0 {y:.3}: {what}"));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A 2 cm, 0.1 kg box falling at `speed` from `y` onto a 1 × 0.01 × 1 m plate at the origin:
/// a fixed body (`fixed = true`) or a box obstacle.
fn box_onto_plate(y: f64, speed: f64, plate_is_body: bool, response: &str) -> World {
    let plate = if plate_is_body {
        r#"
[[body]]
name = "plate"
shape = "box"
size = [1.0, 0.01, 1.0]
fixed = true
"#
    } else {
        r#"
[[obstacle]]
type = "box"
min = [-0.5, -0.005, -0.5]
max = [0.5, 0.005, 0.5]
"#
    };
    world(&format!(
        r#"
title = "box onto plate"
[scene]
dt = 0.001
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = {{ response = "{response}", restitution = 0.0, friction = 0.5 }}
[[body]]
name = "box"
shape = "box"
size = [0.02, 0.02, 0.02]
mass = 0.1
position = [0.0, {y}, 0.0]
velocity = [0.0, -{speed}, 0.0]
{plate}
"#
    ))
}

#[test]
fn a_small_box_at_50_m_per_s_does_not_pass_through_a_thin_fixed_plate() {
    // 5 cm per step against a 1 cm plate and a 2 cm box: the box's centre must stay above the
    // plate's top face (0.005 m) by its half side (0.01 m), and end resting there.
    let mut failures = Vec::new();
    for response in ["impulse", "soft-step"] {
        for plate_is_body in [true, false] {
            for k in 0..25 {
                let y = 0.1 + 2e-3 * k as f64;
                let mut w = box_onto_plate(y, 50.0, plate_is_body, response);
                let mut lowest = f64::INFINITY;
                for _ in 0..1000 {
                    w.step();
                    lowest = lowest.min(w.states()[0].position.y);
                }
                let what = if plate_is_body {
                    "fixed body"
                } else {
                    "obstacle"
                };
                let end = w.states()[0].position.y;
                if lowest < 0.015 - 2e-3 {
                    failures.push(format!(
                        "{response}, {what}, y0 {y:.3}: the box went down to {lowest} m"
                    ));
                }
                // soft-step sags a little under the box's weight (far below a millimetre).
                if (end - 0.015).abs() > 1e-3 {
                    failures.push(format!(
                        "{response}, {what}, y0 {y:.3}: the box ended at {end} m, not on the plate"
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_responses_are_the_ones_named() {
    // Guards the scene text above: a misspelt response would make every test here vacuous.
    let w = two_plates(0.05, 15.0, "soft-step");
    assert_eq!(w.contact_model().unwrap().response.name(), "soft-step");
    assert!(matches!(
        box_onto_plate(0.1, 50.0, true, "impulse")
            .contact_model()
            .unwrap()
            .response,
        Response::Impulse
    ));
}

#[test]
fn a_fast_ball_does_not_pass_through_a_thin_box_obstacle() {
    // A round body has no vertices to sweep: a 2 cm ball at 50 m/s (5 cm a step) against a
    // 1 cm box obstacle. Its centre must stay above the top face (0.005 m) by its radius.
    let mut failures = Vec::new();
    for response in ["impulse", "soft-step"] {
        for k in 0..25 {
            let y = 0.1 + 2e-3 * k as f64;
            let mut w = world(&format!(
                r#"
title = "ball onto plate"
[scene]
dt = 0.001
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = {{ response = "{response}", restitution = 0.0, friction = 0.5 }}
[body]
shape = "sphere"
radius = 0.01
mass = 0.05
position = [0.0, {y}, 0.0]
velocity = [0.0, -50.0, 0.0]
[[obstacle]]
type = "box"
min = [-0.5, -0.005, -0.5]
max = [0.5, 0.005, 0.5]
"#
            ));
            let mut lowest = f64::INFINITY;
            for _ in 0..1000 {
                w.step();
                lowest = lowest.min(w.states()[0].position.y);
            }
            if lowest < 0.015 - 2e-3 {
                failures.push(format!("{response}, y0 {y:.3}: went down to {lowest} m"));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
