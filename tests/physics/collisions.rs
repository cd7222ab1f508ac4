//! Collisions: resting contact, obstacles, fast impacts, the report's climbing bug, and the
//! `impulse` response's energy guarantee. Bounds from issue 3; dt = 1e-3 unless stated.

use nalgebra::{UnitQuaternion, Vector3};
use proptest::prelude::*;
use tumble::physics::body::{box_corners, box_edges};
use tumble::physics::collision::obstacle::{AlignedBox, Ground, Sphere};
use tumble::physics::collision::{collide, Against, CollideInput};
use tumble::physics::effects::Loads;
use tumble::physics::snapshot::{deepest_penetration, kinetic_energy};
use tumble::physics::{
    Body, ContactModel, Effect, Effects, Impacts, Integrator, Obstacle, Orientation, Phase,
    Response, State, World,
};

const G: f64 = 9.81;
const SIDE: f64 = 0.2;
const GROUND: Obstacle = Obstacle::Ground(Ground { height: 0.0 });

fn impulse(restitution: f64, friction: f64) -> ContactModel {
    ContactModel {
        response: Response::Impulse,
        restitution,
        friction,
        impacts: Impacts::default(),
    }
}

fn cube() -> Body {
    Body::solid_box(Vector3::repeat(SIDE), 1.0).unwrap()
}

fn state(position: Vector3<f64>, orientation: UnitQuaternion<f64>) -> State {
    State {
        position,
        orientation: Orientation::Quaternion(orientation),
        ..State::at_rest()
    }
}

fn world(
    body: Body,
    initial: State,
    obstacles: Vec<Obstacle>,
    model: ContactModel,
    dt: f64,
) -> World {
    World::new(
        body,
        Effects::new(vec![Effect::Gravity(Vector3::new(0.0, -G, 0.0))]),
        obstacles,
        Some(model),
        Integrator::Rk4,
        dt,
        initial,
    )
}

/// Rotated 45° about z, then 30° about x: a corner lowest.
fn corner_down() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 30f64.to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 45f64.to_radians())
}

/// What a run saw: the deepest vertex after any step (the CSV's `penetration`) and the deepest
/// contact the collide phase found before correcting it.
#[derive(Debug, Default)]
struct Watch {
    after_step: f64,
    before_correction: f64,
}

fn run(world: &mut World, seconds: f64, watch: &mut Watch) {
    let steps = (seconds / world.dt()).round() as u64;
    for _ in 0..steps {
        world.step();
        assert!(world.divergence().is_none(), "{:?}", world.divergence());
        watch.after_step = watch
            .after_step
            .max(deepest_penetration(world.obstacles(), &world.vertices()));
        for c in world.contacts() {
            watch.before_correction = watch.before_correction.max(c.depth);
        }
    }
}

fn speed(world: &World) -> f64 {
    world.snapshot().velocity.norm()
}

fn angular_speed(world: &World) -> f64 {
    world.snapshot().angular_velocity.norm()
}

#[test]
fn a_cube_dropped_corner_first_comes_to_rest_on_a_face() {
    let mut w = world(
        cube(),
        state(Vector3::new(0.0, 1.0, 0.0), corner_down()),
        vec![GROUND],
        impulse(0.4, 0.5),
        1e-3,
    );
    let mut watch = Watch::default();
    run(&mut w, 5.0, &mut watch);
    let y = w.state().position.y;
    // Resting on a face, the barycenter is half a side above the ground: 0.1 m.
    assert!((y - 0.1).abs() < 5e-4, "barycenter height {y}");
    assert!(speed(&w) < 1e-3, "speed {}", speed(&w));
    assert!(
        angular_speed(&w) < 1e-2,
        "angular speed {}",
        angular_speed(&w)
    );
    // Resting on a face: the lowest face's normal is vertical, so some body axis is ±y.
    let r = w.state().orientation.matrix();
    let up = (0..3).map(|k| r[(1, k)].abs()).fold(0.0, f64::max);
    assert!(
        up > 1.0 - 1e-6,
        "no body axis is vertical: largest |R_yk| = {up}"
    );
    assert!(
        watch.after_step < 5e-3,
        "deepest after a step {}",
        watch.after_step
    );
    // Before correction: at most one step of travel, ≈ 4 m/s × 1 ms.
    assert!(
        watch.before_correction < 5e-3,
        "deepest contact {}",
        watch.before_correction
    );
}

/// The 6 orientations that put each face of the cube down.
fn faces_down() -> Vec<UnitQuaternion<f64>> {
    let q = UnitQuaternion::from_axis_angle;
    let half = std::f64::consts::FRAC_PI_2;
    vec![
        UnitQuaternion::identity(),
        q(&Vector3::x_axis(), 2.0 * half),
        q(&Vector3::x_axis(), half),
        q(&Vector3::x_axis(), -half),
        q(&Vector3::z_axis(), half),
        q(&Vector3::z_axis(), -half),
    ]
}

#[test]
fn a_cube_dropped_flat_on_each_face_rests_without_creeping() {
    for (face, orientation) in faces_down().into_iter().enumerate() {
        let mut w = world(
            cube(),
            state(Vector3::new(0.0, 1.0, 0.0), orientation),
            vec![GROUND],
            impulse(0.4, 0.5),
            1e-3,
        );
        let mut watch = Watch::default();
        run(&mut w, 2.0, &mut watch);
        let settled = w.state().position;
        run(&mut w, 10.0, &mut watch);
        let drift = (w.state().position - settled).xz().norm();
        // Nothing pushes sideways: the drift over 10 s of rest must stay below 1 mm.
        assert!(drift < 1e-3, "face {face}: horizontal drift {drift} m");
        let y = w.state().position.y;
        assert!((y - 0.1).abs() < 5e-4, "face {face}: height {y}");
        assert!(speed(&w) < 1e-3, "face {face}: speed {}", speed(&w));
        assert!(
            watch.after_step < 5e-3,
            "face {face}: depth {}",
            watch.after_step
        );
    }
}

#[test]
fn the_result_does_not_depend_on_the_order_of_the_vertices() {
    // The same cube as 8 equal mass points, once in binary order, once shuffled. It lands
    // flat (4 corners at once), sliding (so friction acts at all 4), then tips and rocks.
    let corners = box_corners(Vector3::repeat(SIDE));
    let order = [5usize, 2, 7, 0, 3, 6, 1, 4];
    let shuffled: Vec<_> = order.iter().map(|&i| corners[i]).collect();
    let ends: Vec<(State, usize)> = [corners, shuffled]
        .into_iter()
        .map(|points| {
            let body = Body::from_points(&points, &[], 1.0, box_edges()).unwrap();
            let mut initial = state(Vector3::new(0.0, 0.6, 0.0), UnitQuaternion::identity());
            initial.linear_momentum = Vector3::new(1.5, 0.0, 0.7);
            let mut w = world(body, initial, vec![GROUND], impulse(0.4, 0.5), 1e-3);
            let mut most_contacts = 0;
            for _ in 0..800 {
                w.step();
                most_contacts = most_contacts.max(w.contacts().len());
            }
            (*w.state(), most_contacts)
        })
        .collect();
    assert_eq!(
        ends[0].1, 4,
        "the landing must put 4 corners in contact at once"
    );
    let (a, b) = (ends[0].0, ends[1].0);
    // The contact solve is order-independent (minimum-norm direct solve, or sweeps converged
    // to 1e-10 m/s): the two runs may differ only by round-off grown over 800 steps.
    let dx = (a.position - b.position).norm();
    let dp = (a.linear_momentum - b.linear_momentum).norm();
    let dl = (a.angular_momentum - b.angular_momentum).norm();
    assert!(
        dx < 1e-6 && dp < 1e-5 && dl < 1e-6,
        "dx {dx}, dP {dp}, dL {dl}"
    );
}

#[test]
fn a_cube_dropped_off_centre_on_a_sphere_slides_off_and_rests_on_the_ground() {
    let sphere = Obstacle::Sphere(Sphere {
        center: Vector3::new(0.0, 0.5, 0.0),
        radius: 0.5,
    });
    let mut w = world(
        cube(),
        state(Vector3::new(0.3, 2.0, 0.0), UnitQuaternion::identity()),
        vec![GROUND, sphere],
        impulse(0.4, 0.5),
        1e-3,
    );
    let mut deepest_in_sphere: f64 = 0.0;
    let mut deepest_contact: f64 = 0.0;
    for _ in 0..10_000 {
        w.step();
        for p in w.vertices() {
            deepest_in_sphere = deepest_in_sphere.max(sphere.depth(&p));
        }
        for c in w
            .contacts()
            .iter()
            .filter(|c| c.against == Against::Obstacle(1))
        {
            deepest_contact = deepest_contact.max(c.depth);
        }
    }
    let x = w.state().position;
    let out = (x - Vector3::new(0.0, x.y, 0.0)).norm();
    // On the ground: barycenter 0.1 m up; outside the sphere: its axis is > 0.5 + 0.1 m away
    // (the sphere touches the ground at the origin, and the cube must clear it).
    assert!((x.y - 0.1).abs() < 5e-4, "height {}", x.y);
    assert!(
        out > 0.5,
        "horizontal distance from the sphere's axis {out}"
    );
    assert!(speed(&w) < 1e-3, "speed {}", speed(&w));
    assert!(
        deepest_in_sphere <= 5e-3,
        "sphere depth after a step {deepest_in_sphere}"
    );
    assert!(
        deepest_contact <= 5e-3,
        "sphere depth before correction {deepest_contact}"
    );
}

#[test]
fn a_cube_landing_on_a_box_top_stays_on_it() {
    let block = Obstacle::AlignedBox(AlignedBox {
        min: Vector3::new(-0.5, 0.0, -0.5),
        max: Vector3::new(0.5, 0.5, 0.5),
    });
    let mut w = world(
        cube(),
        state(Vector3::new(0.1, 1.5, -0.05), corner_down()),
        vec![GROUND, block],
        impulse(0.4, 0.5),
        1e-3,
    );
    let mut watch = Watch::default();
    run(&mut w, 5.0, &mut watch);
    let x = w.state().position;
    // On the top face (y = 0.5): barycenter at 0.5 + 0.1, inside the top's footprint.
    assert!((x.y - 0.6).abs() < 5e-4, "height {}", x.y);
    assert!(x.x.abs() < 0.5 && x.z.abs() < 0.5, "fell off: {x:?}");
    assert!(speed(&w) < 1e-3, "speed {}", speed(&w));
    assert!(watch.after_step < 5e-3, "depth {}", watch.after_step);
}

/// A 50 m/s vertical impact, face down, at `dt`: returns the lowest any vertex got below
/// `top` after any step, and the barycenter height at the end.
fn fast_impact(obstacle: Obstacle, top: f64, dt: f64) -> (f64, f64) {
    let mut initial = state(
        Vector3::new(0.0, top + 1.0, 0.0),
        UnitQuaternion::identity(),
    );
    initial.linear_momentum = Vector3::new(0.0, -50.0, 0.0);
    let mut w = world(cube(), initial, vec![obstacle], impulse(0.0, 0.5), dt);
    let mut lowest = f64::INFINITY;
    let steps = (1.0 / dt) as usize;
    for _ in 0..steps {
        w.step();
        for p in w.vertices() {
            lowest = lowest.min(p.y);
        }
    }
    (top - lowest, w.state().position.y)
}

#[test]
fn a_50_m_per_s_impact_does_not_pass_through_the_ground_or_a_1_cm_box() {
    let slab = Obstacle::AlignedBox(AlignedBox {
        min: Vector3::new(-1.0, 0.0, -1.0),
        max: Vector3::new(1.0, 0.01, 1.0),
    });
    for dt in [1e-3, 1e-2] {
        // 50 m/s × dt = 5 cm or 50 cm per step: a static test would miss the slab entirely.
        for (name, obstacle, top) in [("ground", GROUND, 0.0), ("1 cm box", slab, 0.01)] {
            let (below, height) = fast_impact(obstacle, top, dt);
            assert!(
                below < 1e-9,
                "{name}, dt {dt}: a vertex ended {below} m below the top"
            );
            // e = 0: it stops on the top face and stays there.
            assert!(
                (height - (top + 0.1)).abs() < 1e-3,
                "{name}, dt {dt}: barycenter at {height}"
            );
        }
    }
}

#[test]
fn kinetic_energy_never_grows_at_an_impulse_collision_in_a_tumbling_run() {
    let sphere = Obstacle::Sphere(Sphere {
        center: Vector3::new(0.3, 0.3, 0.0),
        radius: 0.3,
    });
    for (e, mu) in [(0.0, 0.0), (0.4, 0.5), (1.0, 0.0), (1.0, 1.0), (0.8, 3.0)] {
        let mut initial = state(Vector3::new(0.0, 1.0, 0.1), corner_down());
        initial.linear_momentum = Vector3::new(1.0, 0.0, -0.5);
        initial.angular_momentum = Vector3::new(0.02, -0.03, 0.05);
        let mut w = world(cube(), initial, vec![GROUND, sphere], impulse(e, mu), 1e-3);
        let mut collisions = 0;
        for _ in 0..3000 {
            loop {
                let collide_next = w.next_phase() == Phase::Collide;
                let before = kinetic_energy(w.body(), w.state());
                w.step_phase();
                if collide_next {
                    let after = kinetic_energy(w.body(), w.state());
                    if !w.contacts().is_empty() {
                        collisions += 1;
                    }
                    assert!(after <= before, "e {e}, μ {mu}: K {before} → {after}");
                    break;
                }
            }
        }
        assert!(
            collisions > 5,
            "e {e}, μ {mu}: only {collisions} collisions"
        );
    }
}

fn obstacles_for_property() -> Vec<Obstacle> {
    vec![
        GROUND,
        Obstacle::Sphere(Sphere {
            center: Vector3::new(0.15, 0.0, 0.0),
            radius: 0.12,
        }),
        Obstacle::AlignedBox(AlignedBox {
            min: Vector3::new(-0.3, -0.5, -0.08),
            max: Vector3::new(-0.05, 0.04, 0.3),
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Any state overlapping the ground, a sphere and a box at once, any 0 ≤ e ≤ 1, μ ≥ 0:
    /// the response never adds kinetic energy (measured exactly as the energy panel does).
    #[test]
    fn the_impulse_response_never_adds_kinetic_energy(
        position in (-0.1..0.1f64, -0.05..0.12f64, -0.1..0.1f64),
        axis in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        angle in 0.0..6.3f64,
        p in (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64),
        l in (-0.1..0.1f64, -0.1..0.1f64, -0.1..0.1f64),
        restitution in 0.0..=1.0f64,
        friction in prop_oneof![Just(0.0), 0.0..3.0f64],
        elongation in 0.2..3.0f64,
    ) {
        let body = Body::solid_box(Vector3::new(SIDE * elongation, SIDE, SIDE / elongation), 1.3)
            .unwrap();
        let axis = Vector3::new(axis.0, axis.1, axis.2 + 1e-3);
        let orientation = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(axis), angle);
        let mut now = state(Vector3::new(position.0, position.1, position.2), orientation);
        now.linear_momentum = Vector3::new(p.0, p.1, p.2);
        now.angular_momentum = Vector3::new(l.0, l.1, l.2);
        let mut before = now;
        before.position -= now.linear_momentum / body.mass * 1e-2;
        let obstacles = obstacles_for_property();
        let model = impulse(restitution, friction);
        let loads = Loads::default();
        let input = CollideInput {
            bodies: std::slice::from_ref(&body),
            obstacles: &obstacles,
            model: &model,
            before: std::slice::from_ref(&before),
            loads: std::slice::from_ref(&loads),
            initial_positions: &[Vector3::zeros()],
            context: tumble::physics::collision::StepContext::new(1e-2, Some(Vector3::new(0.0, -G, 0.0)), Some(&model)),
            joined: &[],
            joints: None,
            recorded: None,
        };
        let kinetic_before = kinetic_energy(&body, &now);
        let mut contacts = Vec::new();
        collide(&input, std::slice::from_mut(&mut now), &mut contacts, &mut Default::default());
        let kinetic_after = kinetic_energy(&body, &now);
        prop_assert!(kinetic_after <= kinetic_before,
            "K {} → {} with {} contacts", kinetic_before, kinetic_after, contacts.len());
        // And it stopped every approach (to the solver's tolerance), unless restitution
        // was scaled down: no contact may still be approaching after an inelastic solve.
        if restitution == 0.0 {
            let k = tumble::physics::derive::derive(&body, &now);
            for c in &contacts {
                let u = k.velocity + k.angular_velocity.cross(&c.lever);
                prop_assert!(u.dot(&c.normal) > -1e-6, "still approaching at {:?}: {}", c.feature, u.dot(&c.normal));
            }
        }
    }
}

/// Lesson 8: the cube leaving the ground at (0.35, 0.1001) m with v = (0.2, 2.5) m/s grazes
/// the edge of a step (x ≥ 0.5 m, 0.3 m high) on its way down, at t = 0.317 s.
fn climbing_world(response: Response) -> World {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/lessons/08-climbing-bug.toml");
    let lesson = tumble::scene::load(std::path::Path::new(path)).unwrap();
    let mut world = lesson.scene.world();
    let model = *world.contact_model().unwrap();
    world.set_contact_model(ContactModel { response, ..model });
    world
}

#[test]
fn the_climbing_scene_climbs_with_seed_and_not_with_impulse() {
    const STEP_TOP: f64 = 0.3;
    const STEP_SIDE: f64 = 0.5;
    // seed: once it has grazed the edge, the barycenter never drops below the step's top
    // (on the ground it would be at 0.1 m): the cube hangs on the edge.
    let mut seed = climbing_world(Response::Seed);
    let mut lowest_after_graze = f64::INFINITY;
    for step in 1..=2000 {
        seed.step();
        if step >= 400 {
            lowest_after_graze = lowest_after_graze.min(seed.state().position.y);
        }
    }
    assert!(
        lowest_after_graze > STEP_TOP,
        "seed: barycenter went down to {lowest_after_graze} m after the graze"
    );
    // impulse: it falls beside the step and rests on a face on the ground, all of it left
    // of the step's side (x + half a side < 0.5).
    let mut impulse = climbing_world(Response::Impulse);
    for _ in 0..2000 {
        impulse.step();
    }
    let x = impulse.state().position;
    assert!((x.y - 0.1).abs() < 1e-3, "impulse: height {}", x.y);
    assert!(
        x.x + 0.1 < STEP_SIDE,
        "impulse: x = {} is over the step",
        x.x
    );
    assert!(speed(&impulse) < 1e-3, "impulse: speed {}", speed(&impulse));
}

/// Issue 36, obstacles as static solver bodies: the same contact rows of a tilted cube
/// sliding into the ground, once against the ground obstacle and once against a fixed slab
/// whose top is the same plane, give the cube the same impulses, momenta and position fix bit
/// for bit (a static B is no end of a row however it is named; its solver body subtracts exact
/// zeros).
#[test]
fn rows_against_an_obstacle_and_against_a_fixed_body_give_the_same_impulses() {
    let body = cube();
    let dt = 1e-3;
    let model = impulse(0.0, 0.5);
    let context = tumble::physics::collision::StepContext::new(
        dt,
        Some(Vector3::new(0.0, -G, 0.0)),
        Some(&model),
    );
    // Tilted 0.5 rad about x: its lowest edge (two corners) 0.1 mm below y = 0, moving down
    // and sideways, turning.
    let q = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.5);
    let lowest = (box_corners(Vector3::repeat(SIDE)).iter())
        .map(|r| (q * r).y)
        .fold(f64::INFINITY, f64::min);
    let mut now = state(Vector3::new(0.0, -lowest - 1e-4, 0.0), q);
    now.linear_momentum = Vector3::new(1.5, -2.0, 0.4);
    now.angular_momentum = Vector3::new(0.01, -0.02, 0.005);
    let mut before = now;
    before.position -= now.linear_momentum / body.mass * dt;
    let loads = [Loads::default(), Loads::default()];
    let on_ground = CollideInput {
        bodies: std::slice::from_ref(&body),
        obstacles: &[GROUND],
        model: &model,
        before: std::slice::from_ref(&before),
        loads: &loads[..1],
        initial_positions: &[Vector3::zeros()],
        context,
        joined: &[],
        joints: None,
        recorded: None,
    };
    // The rows detection finds against the ground (obstacle 0: solver body 1, after the cube).
    let mut rows = Vec::new();
    tumble::physics::collision::contacts::find(
        &on_ground,
        std::slice::from_ref(&now),
        context.speculative_margin,
        &mut rows,
        &mut Vec::new(),
        &mut Default::default(),
    );
    assert_eq!(rows.len(), 2);
    assert!(rows.iter().all(|c| c.other == 1));
    // The same rows against a fixed 4 m slab whose top face is y = 0: body 1.
    let slab = Body::solid_box(Vector3::new(4.0, 1.0, 4.0), 1.0)
        .unwrap()
        .fixed();
    let slab_state = state(Vector3::new(0.0, -0.5, 0.0), UnitQuaternion::identity());
    let against_slab: Vec<_> = (rows.iter())
        .map(|c| tumble::physics::collision::Contact {
            against: Against::Body(1),
            other: 1,
            lever_other: c.point - slab_state.position,
            ..*c
        })
        .collect();
    let bodies = [body.clone(), slab];
    let befores = [before, slab_state];
    let on_slab = CollideInput {
        bodies: &bodies,
        obstacles: &[],
        before: &befores,
        loads: &loads,
        initial_positions: &[Vector3::zeros(), slab_state.position],
        recorded: Some(&against_slab),
        ..on_ground
    };
    let on_ground = CollideInput {
        recorded: Some(&rows),
        ..on_ground
    };
    let (mut a, mut b) = ([now], [now, slab_state]);
    let (mut ca, mut cb) = (Vec::new(), Vec::new());
    collide(&on_ground, &mut a, &mut ca, &mut Default::default());
    collide(&on_slab, &mut b, &mut cb, &mut Default::default());
    assert_eq!(a[0].linear_momentum, b[0].linear_momentum);
    assert_eq!(a[0].angular_momentum, b[0].angular_momentum);
    let impulses = |cs: &[tumble::physics::collision::Contact]| -> Vec<_> {
        cs.iter().map(|c| c.impulse).collect()
    };
    assert_eq!(impulses(&ca), impulses(&cb));
    // It stopped every approach (e = 0) and the slab did not move.
    let k = tumble::physics::derive::derive(&body, &a[0]);
    for c in &ca {
        let u = k.velocity + k.angular_velocity.cross(&c.lever);
        assert!(
            u.dot(&c.normal) > -1e-6,
            "{:?}: {}",
            c.feature,
            u.dot(&c.normal)
        );
    }
    assert!(ca.iter().any(|c| c.impulse != Vector3::zeros()));
    assert_eq!(b[1], slab_state);
    // The push-out: a static B is no end there either (obstacle or fixed body), so both take
    // the sweeps and end at the same place bit for bit.
    assert_eq!(a[0].position, b[0].position);
}
