//! The domino run (issue 17): 8 dominoes 2 × 20 × 10 cm, 50 g, 12 cm apart, the first tipped
//! 10°: the last one falls flat. The scene is `tumble::contact_scenes::dominoes`, the one the
//! contact benchmarks time.

use nalgebra::Vector3;
use tumble::contact_scenes::{dominoes, dominoes_tipped, DOMINO};
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

#[test]
fn the_fallen_row_rests_on_the_direct_solve_and_does_not_move() {
    // Once fallen, seven dominoes lean on each other and the last lies flat: every contact
    // sticks. Before the load-weighted sticking solve, the minimum-norm one asked a disk for more
    // than it holds (beside a neighbour with room) and the sweeps crawled along the disks' edges
    // for ever: 17–80 friction sweeps and 10–40 subspace steps a step, 0.7–2.8 ms, while no
    // body moved. Now every step at rest is one direct solve. Two runs: the first tipped 10°
    // (the bench's) and 15° (the one whose rest asked the most of the second try).
    for degrees in [10.0, 15.0] {
        let mut w = dominoes_tipped(degrees, Response::Impulse);
        for _ in 0..2500 {
            w.step();
        }
        let (before, start) = (w.contact_counters(), w.states().to_vec());
        for _ in 0..500 {
            w.step();
        }
        let after = w.contact_counters();
        let moved = w
            .states()
            .iter()
            .zip(&start)
            .map(|(s, s0)| (s.position - s0.position).norm())
            .fold(0.0, f64::max);
        println!("{degrees}°: {before:?} → {after:?}, moved {moved:.3e} m");
        assert_eq!(
            (after.friction_sweeps, after.friction_subspace),
            (before.friction_sweeps, before.friction_subspace),
            "{degrees}°: the friction sweeps ran at rest"
        );
        assert_eq!(
            after.friction_direct - before.friction_direct,
            500,
            "{degrees}°: a step at rest without the direct friction solve"
        );
        assert!(
            moved < 1e-9,
            "{degrees}°: a domino moved {moved:.3e} m at rest"
        );
    }
}
