//! The domino run (issue 17): 8 dominoes 2 × 20 × 10 cm, 50 g, 12 cm apart, the first tipped
//! 10°: the last one falls flat. The scene is `tumble::contact_scenes::dominoes`, the one the
//! contact benchmarks time.

use nalgebra::Vector3;
use tumble::contact_scenes::{dominoes, DOMINO};
use tumble::physics::{Response, SoftStep};

/// Steps the run (dt = 1e-3) until the last domino lies still, at most `seconds`; returns its
/// tilt (the angle of its long axis from the vertical, degrees), its barycenter height and the
/// time it took.
fn run(response: Response, seconds: f64) -> (f64, f64, f64) {
    let mut w = dominoes(response);
    let last = w.states().len() - 1;
    let steps = (seconds / w.dt()).round() as usize;
    let mut t = 0.0;
    for step in 0..steps {
        w.step();
        t = (step + 1) as f64 * w.dt();
        let s = &w.states()[last];
        let lying = (s.orientation.matrix() * Vector3::y()).y.abs() < 0.05;
        if lying && s.linear_momentum.norm() + s.angular_momentum.norm() < 1e-6 {
            break;
        }
    }
    let s = &w.states()[last];
    let axis = s.orientation.matrix() * Vector3::y();
    (axis.y.abs().acos().to_degrees(), s.position.y, t)
}

#[test]
fn the_last_domino_falls_flat() {
    // Lying flat on its broad face: the long axis horizontal (tilt 90°) and the barycenter at
    // half the thickness above the ground, 1 cm. (Standing it would be at 10 cm, tilt 0°; leaning
    // on a neighbour, in between.)
    let [thickness, _, _] = DOMINO;
    for response in [Response::Impulse, Response::SoftStep(SoftStep::DEFAULT)] {
        let (tilt, height, t) = run(response, 3.0);
        println!(
            "{}: tilt {tilt:.3}°, height {height:.5} m at {t:.3} s",
            response.name()
        );
        assert!(
            tilt > 89.0,
            "{}: the last domino is tilted {tilt}°, not flat",
            response.name()
        );
        assert!(
            (height - thickness / 2.0).abs() < 1e-3,
            "{}: its barycenter is {height} m up, not {}",
            response.name(),
            thickness / 2.0
        );
    }
}
