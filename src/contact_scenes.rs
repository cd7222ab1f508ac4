//! The contact scaling set (issue 17): the scenes the contact benches, tests and the study
//! share, built in code so every one of them measures the same world.
//!
//! - `stack(n)`: n cubes of 0.2 m and 1 kg standing on each other on the ground, barycenters at
//!   0.1, 0.3, … m;
//! - `pyramid(rows, gap)`: a 2-D pyramid of such cubes, `rows` on the bottom row, each row
//!   above one cube shorter and centred, neighbours `gap` apart (0 or 1 cm);
//! - `dominoes()`: 8 dominoes 2 × 20 × 10 cm (thickness along x), 50 g, 12 cm apart along x,
//!   the first tipped 10° about z towards the others (`domino_run`: any number of them).
//!
//! Every scene: μ = 0.5, e = 0, dt = 1e-3, `rk4`, gravity −9.81 m/s² along y.
//!
//! Issue 35's scenes, on the same terms unless they say otherwise: `wall` (30 bricks in
//! running bond, dt = 5 ms, optionally hit by a heavy ball), `knife_edge_wall` (the same
//! bricks turned 90° about y, so that each upper brick rests on two bare edges), `cradle` (a
//! touching Newton's cradle of five balls on rods, e = 1, μ = 0) and `domino_run(16, …)`.

use crate::physics::collision::obstacle::Ground;
use crate::physics::joints::{Joint, Links};
use crate::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, NamedBody, Obstacle, Orientation,
    Response, State, World,
};
use nalgebra::{UnitQuaternion, Vector3};

/// The cubes' side, m.
pub const SIDE: f64 = 0.2;
/// The scenes' time step, s.
pub const DT: f64 = 1e-3;
/// Gravity, m/s².
pub const G: f64 = 9.81;

/// The scenes' contact law with the given response: μ = 0.5, e = 0.
pub fn model(response: Response) -> ContactModel {
    ContactModel {
        response,
        restitution: 0.0,
        friction: 0.5,
        impacts: Impacts::default(),
    }
}

fn body_at(name: String, body: &Body, position: Vector3<f64>, q: UnitQuaternion<f64>) -> NamedBody {
    NamedBody {
        name,
        initial: State {
            position,
            orientation: Orientation::Quaternion(q),
            ..State::at_rest()
        },
        body: body.clone(),
    }
}

fn world(bodies: Vec<NamedBody>, response: Response) -> World {
    World::with_bodies(
        bodies,
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(model(response)),
        Integrator::Rk4,
        DT,
    )
}

fn cube() -> Body {
    Body::solid_box(Vector3::repeat(SIDE), 1.0).expect("a valid box")
}

/// `count` cubes standing on each other on the ground.
pub fn stack(count: usize, response: Response) -> World {
    let cube = cube();
    let bodies = (0..count)
        .map(|i| {
            let y = SIDE / 2.0 + SIDE * i as f64;
            body_at(
                format!("cube{i}"),
                &cube,
                Vector3::new(0.0, y, 0.0),
                UnitQuaternion::identity(),
            )
        })
        .collect();
    world(bodies, response)
}

/// A running-bond wall as a mason lays it (issue 35, item 2): six courses 2 m long of
/// [`BRICK`]s, every other course shifted by half a brick with a half brick (0.2 m, 1 kg) at
/// each end, so every brick rests on the full width of the bricks below and no end brick is
/// balanced on an edge (33 bodies: 3 courses of 5 bricks, 3 of 4 bricks and 2 halves). Each
/// brick above the first course rests on two bricks: 8 contact points, a rank-deficient set.
/// Otherwise as [`wall`] (dt = 5 ms, μ = 0.5; with `ball`, the same 50 kg ball at 6 m/s).
pub fn bonded_wall(ball: bool, restitution: f64, impacts: Impacts, response: Response) -> World {
    let [length, height, depth] = BRICK;
    let brick = Body::solid_box(Vector3::from(BRICK), BRICK_MASS).expect("a valid box");
    let half = Body::solid_box(Vector3::new(length / 2.0, height, depth), BRICK_MASS / 2.0)
        .expect("a valid box");
    let mut bodies = Vec::new();
    for course in 0..6 {
        let y = height / 2.0 + height * course as f64;
        let mut lay = |name: String, body: &Body, x: f64| {
            bodies.push(body_at(
                name,
                body,
                Vector3::new(x, y, 0.0),
                UnitQuaternion::identity(),
            ))
        };
        if course % 2 == 0 {
            for i in 0..5 {
                lay(format!("c{course}b{i}"), &brick, (i as f64 - 2.0) * length);
            }
        } else {
            lay(format!("c{course}h0"), &half, -2.5 * length + length / 4.0);
            for i in 0..4 {
                lay(format!("c{course}b{i}"), &brick, (i as f64 - 1.5) * length);
            }
            lay(format!("c{course}h1"), &half, 2.5 * length - length / 4.0);
        }
    }
    brick_world(bodies, ball, restitution, impacts, response)
}

/// The distance between neighbouring bricks of [`edge_wall`]'s courses, m: 2 mm less than
/// twice their 0.2 m width, so each brick above overlaps each below by 1 mm.
pub const EDGE_PITCH: f64 = 0.398;

/// A wall of bricks on their edges (issue 35, item 2): [`BRICK`]s turned 90° about y (0.2 m
/// along x, 0.4 m deep), courses of 6, 5, … 1 bricks [`EDGE_PITCH`] apart, each brick above
/// the first course spanning the gap between two bricks below and resting on 1 mm of each
/// (two supports of almost zero width, 4 contact points each along a 1 mm strip). With no
/// overlap at all the corners would meet exactly and the sides touch as well: the least
/// penetration axis is then the sides' (the bricks are pushed apart, not held up). Stable,
/// unlike the same bricks laid at [`wall`]'s places (whose end bricks rest on one edge).
/// Otherwise as [`wall`].
pub fn edge_wall(ball: bool, restitution: f64, impacts: Impacts, response: Response) -> World {
    let [length, height, depth] = BRICK;
    let brick =
        Body::solid_box(Vector3::new(depth, height, length), BRICK_MASS).expect("a valid box");
    let mut bodies = Vec::new();
    for course in 0..6 {
        let count = 6 - course;
        for i in 0..count {
            let x = (i as f64 - (count as f64 - 1.0) / 2.0) * EDGE_PITCH;
            let y = height / 2.0 + height * course as f64;
            bodies.push(body_at(
                format!("c{course}b{i}"),
                &brick,
                Vector3::new(x, y, 0.0),
                UnitQuaternion::identity(),
            ));
        }
    }
    brick_world(bodies, ball, restitution, impacts, response)
}

/// `bodies` on the ground with [`wall`]'s ball (if `ball`: 50 kg, r = 0.25 m, at 6 m/s along
/// z towards x = 0.1, y = 0.6, 0.3 m from a 0.2 m deep face), dt = 5 ms, `rk4`, μ = 0.5.
fn brick_world(
    mut bodies: Vec<NamedBody>,
    ball: bool,
    restitution: f64,
    impacts: Impacts,
    response: Response,
) -> World {
    if ball {
        let radius = 0.25;
        let body = Body::sphere(radius, 50.0, false).expect("a valid ball");
        bodies.push(NamedBody {
            name: "ball".into(),
            initial: State {
                position: Vector3::new(0.1, 0.6, -(BRICK[2] / 2.0 + radius + 0.3)),
                linear_momentum: Vector3::new(0.0, 0.0, 50.0 * 6.0),
                ..State::at_rest()
            },
            body,
        });
    }
    World::with_bodies(
        bodies,
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        vec![Obstacle::Ground(Ground { height: 0.0 })],
        Some(ContactModel {
            restitution,
            impacts,
            ..model(response)
        }),
        Integrator::Rk4,
        5e-3,
    )
}

/// A pyramid with `rows` cubes on its bottom row, neighbours `gap` m apart; `rows (rows + 1) / 2`
/// cubes.
pub fn pyramid(rows: usize, gap: f64, response: Response) -> World {
    let cube = cube();
    let pitch = SIDE + gap;
    let mut bodies = Vec::new();
    for row in 0..rows {
        let count = rows - row;
        for i in 0..count {
            let x = (i as f64 - (count as f64 - 1.0) / 2.0) * pitch;
            let y = SIDE / 2.0 + SIDE * row as f64;
            bodies.push(body_at(
                format!("r{row}c{i}"),
                &cube,
                Vector3::new(x, y, 0.0),
                UnitQuaternion::identity(),
            ));
        }
    }
    world(bodies, response)
}

/// The domino's size (thickness, height, width), m, and mass, kg.
pub const DOMINO: [f64; 3] = [0.02, 0.2, 0.1];
pub const DOMINO_MASS: f64 = 0.05;
/// Distance between neighbouring dominoes' centres, m.
pub const DOMINO_PITCH: f64 = 0.12;

/// 8 dominoes in a row along x; the first is tipped 10° towards the second about its bottom
/// edge at +x (it starts on that edge, touching the ground).
pub fn dominoes(response: Response) -> World {
    dominoes_tipped(10.0, response)
}

/// [`dominoes`] with the first tipped `degrees` instead of 10°: the same run along another
/// trajectory. The run is chaotic, so its cost is compared over a few of them
/// (`examples/contact_steps dominoes-D`); the resting test takes 10° and 15°.
pub fn dominoes_tipped(degrees: f64, response: Response) -> World {
    domino_run(8, degrees, response)
}

/// `count` dominoes in a row along x as in [`dominoes`], the first tipped `degrees`.
pub fn domino_run(count: usize, degrees: f64, response: Response) -> World {
    let [t, h, _] = DOMINO;
    let body = Body::solid_box(Vector3::from(DOMINO), DOMINO_MASS).expect("a valid box");
    let tilt = degrees.to_radians();
    let bodies = (0..count)
        .map(|i| {
            let x = i as f64 * DOMINO_PITCH;
            let (position, q) = if i == 0 {
                // Rotating by −θ about z the pivot at (x + t/2, 0): the barycenter sits at
                // pivot + R(−θ)·(−t/2, h/2).
                let (s, c) = tilt.sin_cos();
                let offset =
                    Vector3::new(-t / 2.0 * c + h / 2.0 * s, t / 2.0 * s + h / 2.0 * c, 0.0);
                (
                    Vector3::new(x + t / 2.0, 0.0, 0.0) + offset,
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), -tilt),
                )
            } else {
                (Vector3::new(x, h / 2.0, 0.0), UnitQuaternion::identity())
            };
            body_at(format!("domino{i}"), &body, position, q)
        })
        .collect();
    world(bodies, response)
}

/// A brick's size (length along x, height, depth), m, and mass, kg.
pub const BRICK: [f64; 3] = [0.4, 0.2, 0.2];
pub const BRICK_MASS: f64 = 2.0;

/// A running-bond wall of 30 bricks (6 courses of 5, every other course shifted by half a
/// brick) on the ground, dt = 5 ms; with `ball`, a 50 kg ball (r = 0.25 m) at 6 m/s along z
/// towards its middle, 0.3 m from its face. Contact: μ = 0.5 and restitution `restitution`
/// with the given impact law. Not a wall at rest: each shifted course's end brick has its
/// barycenter right above the edge of the brick below; the top course's end bricks, with
/// nothing on them, topple (an inverted pendulum about that edge, growing as e^(6.07 t)),
/// while the lower ones are held down by the course above; [`bonded_wall`] closes the
/// courses with half bricks.
pub fn wall(ball: bool, restitution: f64, impacts: Impacts, response: Response) -> World {
    brick_wall(BRICK, ball, restitution, impacts, response)
}

/// [`wall`] with each brick turned 90° about y (0.2 m along x, 0.4 m deep) but laid at the
/// same places, a teacher's first draft (issue 35): the bricks of a course stand 0.2 m apart
/// and each brick of the course above spans such a gap, so it rests on two bare edges
/// (supports of zero width) of the bricks below.
pub fn knife_edge_wall(
    ball: bool,
    restitution: f64,
    impacts: Impacts,
    response: Response,
) -> World {
    let [length, height, depth] = BRICK;
    brick_wall(
        [depth, height, length],
        ball,
        restitution,
        impacts,
        response,
    )
}

/// Six courses of five bricks of `size`, centred `BRICK[0]` apart along x, every other course
/// shifted by half of that; the ball, if any, `0.3 m` from the face of the running-bond wall.
fn brick_wall(
    size: [f64; 3],
    ball: bool,
    restitution: f64,
    impacts: Impacts,
    response: Response,
) -> World {
    let brick = Body::solid_box(Vector3::from(size), BRICK_MASS).expect("a valid box");
    let [length, height, _] = BRICK;
    let mut bodies = Vec::new();
    for course in 0..6 {
        let shift = if course % 2 == 1 { length / 2.0 } else { 0.0 };
        for i in 0..5 {
            let x = (i as f64 - 2.0) * length + shift;
            let y = height / 2.0 + height * course as f64;
            bodies.push(body_at(
                format!("c{course}b{i}"),
                &brick,
                Vector3::new(x, y, 0.0),
                UnitQuaternion::identity(),
            ));
        }
    }
    brick_world(bodies, ball, restitution, impacts, response)
}

/// Ball radius and rod length of [`cradle`], m.
pub const CRADLE_RADIUS: f64 = 0.05;
pub const CRADLE_ROD: f64 = 1.0;

/// A touching Newton's cradle (lesson 39): five balls of 1 kg, radius 5 cm, touching in a
/// row along x, each hanging from a pivot at y = 1 m on a rod of 1 m (a distance joint), the
/// first pulled aside to 30°; e = 1, μ = 0, no ground, dt = 1e-3, `rk4`.
pub fn cradle(response: Response) -> World {
    let ball = Body::sphere(CRADLE_RADIUS, 1.0, false).expect("a valid ball");
    let theta = 30f64.to_radians();
    let pivots: Vec<Vector3<f64>> = (0..5)
        .map(|i| Vector3::new(2.0 * CRADLE_RADIUS * i as f64, CRADLE_ROD, 0.0))
        .collect();
    let bodies: Vec<NamedBody> = pivots
        .iter()
        .enumerate()
        .map(|(i, pivot)| {
            let hang = if i == 0 {
                Vector3::new(-theta.sin(), -theta.cos(), 0.0)
            } else {
                -Vector3::y()
            };
            body_at(
                format!("b{}", i + 1),
                &ball,
                pivot + hang * CRADLE_ROD,
                UnitQuaternion::identity(),
            )
        })
        .collect();
    let states: Vec<State> = bodies.iter().map(|b| b.initial).collect();
    let joints = pivots
        .iter()
        .enumerate()
        .map(|(i, pivot)| {
            let at = states[i].position;
            Joint::distance(
                format!("rod{}", i + 1),
                i,
                None,
                [at, *pivot],
                None,
                &states,
            )
        })
        .collect();
    World::with_bodies(
        bodies,
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        Vec::new(),
        Some(ContactModel {
            response,
            restitution: 1.0,
            friction: 0.0,
            impacts: Impacts::default(),
        }),
        Integrator::Rk4,
        DT,
    )
    .with_links(Links {
        joints,
        ..Links::default()
    })
}
