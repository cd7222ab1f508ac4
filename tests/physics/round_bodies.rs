//! Round bodies, ramps and fixed bodies against closed forms (references.md "Round bodies"):
//! rolling down a plane obstacle, the bowling ball, sliding with spin-up, a box held or sliding
//! on a ramp, equal spheres head-on, a capsule at rest, a fixed body under a load.

use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::{Body, World};
use tumble::scene::parse;

const G: f64 = 9.81;

/// A world from scene-file text.
fn world(source: &str) -> World {
    parse(source, Path::new("t.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
        .world()
}

fn error(source: &str) -> String {
    match parse(source, Path::new("t.toml")) {
        Ok(_) => panic!("the scene must be refused"),
        Err(e) => e.to_string(),
    }
}

/// A ramp at `degrees` descending toward +x: normal (sin θ, cos θ, 0), through the origin.
fn ramp(degrees: f64) -> (Vector3<f64>, String) {
    let t = degrees.to_radians();
    let n = Vector3::new(t.sin(), t.cos(), 0.0);
    let text = format!(
        "[[obstacle]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [{:?}, {:?}, 0.0]\n",
        n.x, n.y
    );
    (n, text)
}

fn scene(friction: f64, restitution: f64, gravity: bool) -> String {
    let g = if gravity {
        "gravity = [0.0, -9.81, 0.0]\n"
    } else {
        ""
    };
    format!(
        "title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"symplectic-euler\"\n{g}\
         contact = {{ response = \"impulse\", restitution = {restitution:?}, friction = {friction:?} }}\n"
    )
}

fn run(world: &mut World, seconds: f64) {
    let steps = (seconds / world.dt()).round() as usize;
    for _ in 0..steps {
        world.step();
    }
}

fn vec(v: &Vector3<f64>) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// The acceleration along a ramp at θ of a body released at rest, from its speed after 1 s.
fn rolling_acceleration(body: &str, radius: f64, degrees: f64) -> f64 {
    let (n, plane) = ramp(degrees);
    let source = format!(
        "{}[body]\n{body}\nposition = {}\n{plane}",
        scene(0.5, 0.0, true),
        vec(&(n * radius))
    );
    let mut w = world(&source);
    run(&mut w, 1.0);
    let downhill = Vector3::new(n.y, -n.x, 0.0);
    w.state().linear_momentum.dot(&downhill) / w.body().mass
}

#[test]
fn a_solid_ball_rolls_down_a_ramp_at_five_sevenths_of_g_sin_theta() {
    // a = g sin θ/(1 + I/(M r²)) = 9.81 · sin 20° · 5/7 = 2.39656 m/s².
    let expected = G * 20f64.to_radians().sin() * 5.0 / 7.0;
    let a = rolling_acceleration("shape = \"sphere\"\nradius = 0.1\nmass = 1.0", 0.1, 20.0);
    assert!(
        (a / expected - 1.0).abs() < 0.01,
        "a = {a}, expected {expected}"
    );
}

#[test]
fn a_hollow_ball_rolls_at_three_fifths_of_g_sin_theta() {
    // I = ⅔ M r²: a = g sin θ · 3/5 = 2.01311 m/s².
    let expected = G * 20f64.to_radians().sin() * 3.0 / 5.0;
    let a = rolling_acceleration(
        "shape = \"sphere\"\nradius = 0.1\nmass = 1.0\ninertia = \"shell\"",
        0.1,
        20.0,
    );
    assert!(
        (a / expected - 1.0).abs() < 0.01,
        "a = {a}, expected {expected}"
    );
}

#[test]
fn a_solid_cylinder_lying_across_the_slope_rolls_at_two_thirds_of_g_sin_theta() {
    // I_axis = ½ M r²: a = g sin θ · 2/3 = 2.23679 m/s². Axis along z (body y turned by 90°
    // about x).
    let expected = G * 20f64.to_radians().sin() * 2.0 / 3.0;
    let a = rolling_acceleration(
        "shape = \"cylinder\"\nradius = 0.1\nlength = 0.2\nmass = 1.0\n\
         orientation = { axis = [1.0, 0.0, 0.0], degrees = 90.0 }",
        0.1,
        20.0,
    );
    assert!(
        (a / expected - 1.0).abs() < 0.01,
        "a = {a}, expected {expected}"
    );
}

#[test]
fn a_cylinder_lying_on_a_plane_touches_along_a_line_and_standing_on_its_rim() {
    let (n, plane) = ramp(0.0);
    let lying = format!(
        "{}[body]\nshape = \"cylinder\"\nradius = 0.1\nlength = 0.4\nmass = 1.0\n\
         orientation = {{ axis = [1.0, 0.0, 0.0], degrees = 90.0 }}\nposition = {}\n{plane}",
        scene(0.5, 0.0, true),
        vec(&(n * 0.1))
    );
    let mut w = world(&lying);
    run(&mut w, 0.2);
    // Two points, one at each end of the generator (z = ±0.2).
    let zs: Vec<f64> = w.contacts().iter().map(|c| c.point.z).collect();
    assert_eq!(zs.len(), 2, "{zs:?}");
    assert!(zs.iter().all(|z| (z.abs() - 0.2).abs() < 1e-9), "{zs:?}");
    let standing = format!(
        "{}[body]\nshape = \"cylinder\"\nradius = 0.1\nlength = 0.4\nmass = 1.0\n\
         position = [0.0, 0.2, 0.0]\n{plane}",
        scene(0.5, 0.0, true)
    );
    let mut w = world(&standing);
    run(&mut w, 0.2);
    // The rim patch: 4 points on the lower rim, at distance r from the axis.
    let contacts = w.contacts();
    assert_eq!(contacts.len(), 4);
    for c in contacts {
        assert!(
            (c.point.x.hypot(c.point.z) - 0.1).abs() < 1e-9,
            "{:?}",
            c.point
        );
    }
    // At rest: the centre stays at 0.2 m (within a micrometre), upright.
    assert!((w.state().position.y - 0.2).abs() < 1e-6, "{:?}", w.state());
}

#[test]
fn the_bowling_ball_slides_then_rolls_at_five_sevenths_of_its_speed() {
    // v₀ = 5 m/s, no spin, μ = 0.2: rolling from t = 2 v₀/(7 μ g) = 0.72812 s at
    // 5/7 v₀ = 3.57143 m/s; 2/7 of the kinetic energy ½ M v₀² = 12.5 J goes to friction.
    let source = format!(
        "{}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\nposition = [0.0, 0.1, 0.0]\n\
         velocity = [5.0, 0.0, 0.0]\n[[obstacle]]\ntype = \"ground\"\nheight = 0.0\n",
        scene(0.2, 0.0, true)
    );
    let mut w = world(&source);
    let e0 = w.total_energy().total;
    let mut rolling_from = None;
    while w.time() < 1.5 {
        w.step();
        let s = w.snapshot();
        // Slip of the contact point: v_x + ω_z r (rolling toward +x has ω_z = −v/r).
        let slip = s.velocity.x + s.angular_velocity.z * 0.1;
        if rolling_from.is_none() && slip.abs() < 1e-3 {
            rolling_from = Some(w.time());
        }
    }
    let t = rolling_from.expect("the ball ends up rolling");
    let expected_t = 2.0 * 5.0 / (7.0 * 0.2 * G);
    assert!(
        (t / expected_t - 1.0).abs() < 0.01,
        "rolling from {t} s, expected {expected_t}"
    );
    let v = w.snapshot().velocity.x;
    assert!((v / (25.0 / 7.0) - 1.0).abs() < 0.005, "v = {v}");
    // Rolling costs nothing: E = 5/7 of the initial (potential is 0.981 J on both sides).
    let lost = e0 - w.total_energy().total;
    assert!(
        (lost / (12.5 * 2.0 / 7.0) - 1.0).abs() < 0.01,
        "lost {lost} J"
    );
}

#[test]
fn a_ball_below_the_rolling_limit_slides_and_spins_up_at_the_coulomb_rates() {
    // θ = 30°, μ = 0.05 < (2/7) tan 30° = 0.165: a = g (sin θ − μ cos θ) = 4.47023 m/s²,
    // α = μ g cos θ M r / I = μ g cos θ · 5/(2 r) = 10.6192 rad/s² (r = 0.1 m).
    let (n, plane) = ramp(30.0);
    let source = format!(
        "{}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\nposition = {}\n{plane}",
        scene(0.05, 0.0, true),
        vec(&(n * 0.1))
    );
    let mut w = world(&source);
    run(&mut w, 0.5);
    let t = 30f64.to_radians();
    let downhill = Vector3::new(t.cos(), -t.sin(), 0.0);
    let a = w.snapshot().velocity.dot(&downhill) / 0.5;
    let expected_a = G * (t.sin() - 0.05 * t.cos());
    assert!(
        (a / expected_a - 1.0).abs() < 0.01,
        "a = {a}, expected {expected_a}"
    );
    let alpha = -w.snapshot().angular_velocity.z / 0.5;
    let expected_alpha = 0.05 * G * t.cos() * 2.5 / 0.1;
    assert!(
        (alpha / expected_alpha - 1.0).abs() < 0.01,
        "α = {alpha}, expected {expected_alpha}"
    );
}

/// A 0.2 m cube resting on a 20° ramp, face down, after `seconds`: how far it moved.
fn box_on_ramp(friction: f64, seconds: f64) -> (Vector3<f64>, World) {
    let (n, plane) = ramp(20.0);
    let start = n * 0.1;
    let source = format!(
        "{}[body]\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 1.0\nposition = {}\n\
         orientation = {{ axis = [0.0, 0.0, 1.0], degrees = -20.0 }}\n{plane}",
        scene(friction, 0.0, true),
        vec(&start)
    );
    let mut w = world(&source);
    run(&mut w, seconds);
    (w.state().position - start, w)
}

#[test]
fn a_box_held_by_friction_on_a_ramp_does_not_creep() {
    // μ = 0.6 > tan 20° = 0.364: static friction holds it.
    let (moved, _) = box_on_ramp(0.6, 2.0);
    assert!(moved.norm() < 1e-6, "moved {moved:?}");
}

#[test]
fn a_box_slides_down_a_ramp_at_g_sin_minus_mu_cos() {
    // μ = 0.2: a = g (sin 20° − 0.2 cos 20°) = 1.51151 m/s²; from v after 1 s.
    let (_, w) = box_on_ramp(0.2, 1.0);
    let t = 20f64.to_radians();
    let downhill = Vector3::new(t.cos(), -t.sin(), 0.0);
    let a = w.snapshot().velocity.dot(&downhill);
    let expected = G * (t.sin() - 0.2 * t.cos());
    assert!(
        (a / expected - 1.0).abs() < 0.01,
        "a = {a}, expected {expected}"
    );
}

#[test]
fn a_cube_slides_down_a_rotated_box_obstacle() {
    // The same 20° slope as the top face of a box obstacle turned by −20° about z: μ = 0.2,
    // a = 1.51151 m/s².
    let t = 20f64.to_radians();
    let n = Vector3::new(t.sin(), t.cos(), 0.0);
    let start = n * 0.6; // the block's top face is 0.5 m above its centre
    let source = format!(
        "{}[body]\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 1.0\nposition = {}\n\
         orientation = {{ axis = [0.0, 0.0, 1.0], degrees = -20.0 }}\n\
         [[obstacle]]\ntype = \"box\"\nmin = [-5.0, -0.5, -1.0]\nmax = [5.0, 0.5, 1.0]\n\
         orientation = {{ axis = [0.0, 0.0, 1.0], degrees = -20.0 }}\n",
        scene(0.2, 0.0, true),
        vec(&start)
    );
    let mut w = world(&source);
    run(&mut w, 1.0);
    let downhill = Vector3::new(t.cos(), -t.sin(), 0.0);
    let a = w.snapshot().velocity.dot(&downhill);
    let expected = G * (t.sin() - 0.2 * t.cos());
    assert!(
        (a / expected - 1.0).abs() < 0.01,
        "a = {a}, expected {expected}"
    );
    // On the face, not in it.
    assert!(
        w.snapshot().penetration < 1e-4,
        "{}",
        w.snapshot().penetration
    );
}

/// Two equal 0.1 m balls, the first at 1 m/s toward the second at rest, after 1 s.
fn head_on(restitution: f64) -> (f64, f64) {
    let source = format!(
        "{}[[body]]\nname = \"a\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
         position = [-0.5, 0.0, 0.0]\nvelocity = [1.0, 0.0, 0.0]\n\
         [[body]]\nname = \"b\"\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
         position = [0.5, 0.0, 0.0]\n",
        scene(0.0, restitution, false)
    );
    let mut w = world(&source);
    run(&mut w, 1.5);
    let v = |i: usize| w.states()[i].linear_momentum.x / w.bodies()[i].mass;
    (v(0), v(1))
}

#[test]
fn equal_balls_head_on_exchange_their_speeds_at_e_1_and_share_them_at_e_0() {
    // e = 1: momentum 1 and energy ½ kept: (0, 1). e = 0: one speed, momentum kept: (½, ½).
    let (a, b) = head_on(1.0);
    assert!(a.abs() < 1e-9 && (b - 1.0).abs() < 1e-9, "e = 1: {a}, {b}");
    let (a, b) = head_on(0.0);
    assert!(
        (a - 0.5).abs() < 1e-9 && (b - 0.5).abs() < 1e-9,
        "e = 0: {a}, {b}"
    );
}

#[test]
fn a_capsule_rests_on_its_side_and_on_its_end() {
    // r = 0.05, L = 0.3: on its side the centre is r above the ground, on its end r + L/2.
    for (orientation, height, points) in [
        (
            "orientation = { axis = [0.0, 0.0, 1.0], degrees = 90.0 }",
            0.05,
            2,
        ),
        ("", 0.2, 1),
    ] {
        let source = format!(
            "{}[body]\nshape = \"capsule\"\nradius = 0.05\nlength = 0.3\nmass = 1.0\n\
             position = [0.0, {height:?}, 0.0]\n{orientation}\n\
             [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n",
            scene(0.5, 0.0, true)
        );
        let mut w = world(&source);
        let q0 = w.state().orientation.quaternion();
        run(&mut w, 1.0);
        let s = w.snapshot();
        assert!(
            (s.position.y - height).abs() < 1e-6,
            "{orientation}: y = {}",
            s.position.y
        );
        assert!(s.quaternion.angle_to(&q0) < 1e-6, "{orientation}: turned");
        assert_eq!(w.contacts().len(), points, "{orientation}");
    }
}

/// A cylinder (r = 0.1, L = 0.4, 1 kg) placed touching on top of `below` (scene-file bodies
/// listed before it) at height `y`, run 1 s: its contacts with body 0 after 0.5 s and 1 s,
/// and how far it moved and turned in the second half.
fn cylinder_on(below: &str, orientation: &str, y: f64) -> (usize, f64, f64, Vector3<f64>) {
    let source = format!(
        "{}{below}[[body]]\nname = \"c\"\nshape = \"cylinder\"\nradius = 0.1\nlength = 0.4\n\
         mass = 1.0\nposition = [0.0, {y:?}, 0.0]\n{orientation}\n",
        scene(0.5, 0.0, true)
    );
    let mut w = world(&source);
    let last = w.bodies().len() - 1;
    run(&mut w, 0.5);
    let (x0, q0) = (
        w.states()[last].position,
        w.states()[last].orientation.quaternion(),
    );
    run(&mut w, 0.5);
    let s = &w.states()[last];
    let count = w
        .contacts()
        .iter()
        .filter(|c| {
            c.body == last && matches!(c.against, tumble::physics::Against::Body(0))
                || c.body == 0
                    && matches!(c.against, tumble::physics::Against::Body(b) if b == last)
        })
        .count();
    (
        count,
        (s.position - x0).norm(),
        s.orientation.quaternion().angle_to(&q0),
        s.position,
    )
}

const LYING: &str = "orientation = { axis = [0.0, 0.0, 1.0], degrees = 90.0 }";
/// A fixed 1 m × 0.2 m × 1 m table, its top at y = 0.2.
const TABLE: &str = "[[body]]\nname = \"table\"\nshape = \"box\"\nsize = [1.0, 0.2, 1.0]\n\
                     fixed = true\nposition = [0.0, 0.1, 0.0]\n";

#[test]
fn a_cylinder_rests_on_a_box_on_its_side_along_two_points_and_on_its_end_along_its_rim() {
    // On its side the axis is 0.1 (the radius) above the top y = 0.2; on its end 0.2 (L/2).
    // At rest: nothing moves (no creep) and the contact is 2 points lying, 4 standing.
    for (orientation, y, points) in [(LYING, 0.3, 2), ("", 0.4, 4)] {
        let (count, moved, turned, at) = cylinder_on(TABLE, orientation, y);
        assert_eq!(count, points, "{orientation:?}");
        assert!(
            moved < 1e-7 && turned < 1e-7,
            "{orientation:?}: {moved} m, {turned} rad"
        );
        // Resting where it was put, within the solver's allowed overlap (≤ 1 mm).
        assert!((at.y - y).abs() < 1e-3, "{orientation:?}: y = {}", at.y);
    }
}

#[test]
fn a_cylinder_rests_on_a_box_body_that_rests_on_the_ground() {
    // The same on a free 5 kg box (0.2 m high) standing on the ground: both at rest.
    let block = "[[body]]\nname = \"block\"\nshape = \"box\"\nsize = [1.0, 0.2, 1.0]\n\
                 mass = 5.0\nposition = [0.0, 0.1, 0.0]\n\
                 [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n";
    for (orientation, y, points) in [(LYING, 0.3, 2), ("", 0.4, 4)] {
        let (count, moved, turned, at) = cylinder_on(block, orientation, y);
        assert_eq!(count, points, "{orientation:?}");
        assert!(
            moved < 1e-6 && turned < 1e-6,
            "{orientation:?}: {moved} m, {turned} rad"
        );
        assert!((at.y - y).abs() < 2e-3, "{orientation:?}: y = {}", at.y);
    }
}

#[test]
fn a_cylinder_rests_on_a_cylinder_end_on_end_and_lying_across_its_top() {
    // A fixed post (r = 0.3, L = 0.4, top at y = 0.4): a cylinder standing on it (centre at
    // 0.4 + 0.2) touches along its rim, 4 points; lying across it (centre at 0.4 + 0.1) along
    // its lowest generator, 2 points (the ends, x = ±0.2, lie on the post's top).
    let post = "[[body]]\nname = \"post\"\nshape = \"cylinder\"\nradius = 0.3\nlength = 0.4\n\
                fixed = true\nposition = [0.0, 0.2, 0.0]\n";
    for (orientation, y, points) in [("", 0.6, 4), (LYING, 0.5, 2)] {
        let (count, moved, turned, at) = cylinder_on(post, orientation, y);
        assert_eq!(count, points, "{orientation:?}");
        assert!(
            moved < 1e-7 && turned < 1e-7,
            "{orientation:?}: {moved} m, {turned} rad"
        );
        assert!((at.y - y).abs() < 1e-3, "{orientation:?}: y = {}", at.y);
    }
}

#[test]
fn a_fixed_body_never_moves_under_a_load() {
    // A 10 kg cube dropped on a fixed 0.5 m ball: the ball stays exactly where it was, the cube
    // comes to rest on it (a fixed body is the world: it carries no momentum and no energy).
    let source = format!(
        "{}[[body]]\nname = \"post\"\nshape = \"sphere\"\nradius = 0.5\nfixed = true\n\
         position = [0.0, 0.5, 0.0]\n\
         [[body]]\nname = \"cube\"\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 10.0\n\
         position = [0.0, 1.3, 0.0]\n",
        scene(0.8, 0.0, true)
    );
    let mut w = world(&source);
    run(&mut w, 2.0);
    assert_eq!(w.states()[0].position, Vector3::new(0.0, 0.5, 0.0));
    assert_eq!(w.states()[0].linear_momentum, Vector3::zeros());
    assert_eq!(w.states()[0].angular_momentum, Vector3::zeros());
    // The cube's bottom face rests on the top of the ball: centre at 1.0 + 0.1 m.
    let y = w.states()[1].position.y;
    assert!((y - 1.1).abs() < 1e-3, "cube at {y}");
}

#[test]
fn rolling_makes_no_energy() {
    // A solid ball rolling down a 20° ramp for 2 s: the energy never rises above where it
    // started (rolling without slipping does no work; the integrator's error may only lose).
    let (n, plane) = ramp(20.0);
    let source = format!(
        "{}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\nposition = {}\n{plane}",
        scene(0.5, 0.0, true),
        vec(&(n * 0.1))
    );
    let mut w = world(&source);
    let e0 = w.total_energy().total;
    for _ in 0..2000 {
        w.step();
        let e = w.total_energy().total;
        assert!(e <= e0 + 1e-12, "t = {}: E = {e} > E₀ = {e0}", w.time());
    }
}

#[test]
fn a_ball_rolling_without_slipping_keeps_its_energy() {
    // A solid ball (1 kg, r = 0.1) rolling down a 20° ramp for 2 s under every integrator that
    // steps a round body: rolling without slipping does no work, so E stays E₀. Advancing the
    // position with the end-of-step velocity alone (x + dt v₁) would lose ½ M_eff a² dt² a
    // step, M_eff = (7/5) M, a = (5/7) g sin θ = 2.3966 m/s²: 4.0 mJ/s at dt = 1 ms
    // (8.0 mJ in 2 s); the trapezoid x + dt (v₀ + v₁)/2 along the surface loses nothing.
    let (n, plane) = ramp(20.0);
    for integrator in ["symplectic-euler", "rk4"] {
        let source = format!(
            "{}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\nposition = {}\n{plane}",
            scene(0.5, 0.0, true).replace("symplectic-euler", integrator),
            vec(&(n * 0.1))
        );
        let mut w = world(&source);
        let e0 = w.total_energy().total;
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            w.step();
            worst = worst.max((w.total_energy().total - e0).abs());
        }
        // Moved: 2 s at 2.3966 m/s² is ½ a t² = 4.79 m down the slope (the test is not idle).
        let s = (w.state().position - n * 0.1).norm();
        assert!(
            (s - 0.5 * 2.396_584 * 4.0).abs() < 1e-3,
            "{integrator}: s = {s}"
        );
        assert!(worst < 1e-6, "{integrator}: |E − E₀| reached {worst} J");
    }
}

#[test]
fn round_inertia_tensors_match_their_closed_forms() {
    // M = 2 kg, r = 0.1 m, L = 0.4 m.
    let close = |a: f64, b: f64| (a - b).abs() < 1e-15;
    let solid = Body::sphere(0.1, 2.0, false).unwrap();
    // ⅖ · 2 · 0.01 = 0.008
    assert!(
        close(solid.inertia_body[(0, 0)], 0.008),
        "{}",
        solid.inertia_body
    );
    let shell = Body::sphere(0.1, 2.0, true).unwrap();
    // ⅔ · 2 · 0.01 = 0.013333…
    assert!(close(shell.inertia_body[(2, 2)], 2.0 / 3.0 * 0.02));
    let cylinder = Body::cylinder(0.1, 0.4, 2.0, false).unwrap();
    // I_y = ½ · 2 · 0.01 = 0.01; I_x = 2 (0.01/4 + 0.16/12) = 0.031667
    assert!(close(cylinder.inertia_body[(1, 1)], 0.01));
    assert!(close(
        cylinder.inertia_body[(0, 0)],
        2.0 * (0.0025 + 0.16 / 12.0)
    ));
    let tube = Body::cylinder(0.1, 0.4, 2.0, true).unwrap();
    // I_y = 2 · 0.01 = 0.02; I_x = 2 (0.01/2 + 0.16/12) = 0.036667
    assert!(close(tube.inertia_body[(1, 1)], 0.02));
    assert!(close(
        tube.inertia_body[(2, 2)],
        2.0 * (0.005 + 0.16 / 12.0)
    ));
    // Capsule: volumes π r² L = 0.0125664 and 4/3 π r³ = 0.0041888 (ratio L : 4r/3 = 3 : 1),
    // so m_c = 1.5 kg, m_s = 0.5 kg.
    // I_y = 1.5 · 0.01/2 + 0.5 · 0.4 · 0.01 = 0.0075 + 0.002 = 0.0095
    // I_x = 1.5 (0.0025 + 0.013333) + 0.5 (0.004 + 0.04 + 0.015) = 0.02375 + 0.0295 = 0.05325
    let capsule = Body::capsule(0.1, 0.4, 2.0).unwrap();
    assert!((capsule.inertia_body[(1, 1)] - 0.0095).abs() < 1e-15);
    assert!(
        (capsule.inertia_body[(0, 0)] - 0.05325).abs() < 1e-15,
        "{}",
        capsule.inertia_body
    );
    // The hemisphere's shift checked against the long way round: a hemisphere of mass m
    // about its own centre of mass (83/320 m r²) moved to L/2 + 3r/8 = 0.2375 m.
    let hemisphere = 0.25 * (83.0 / 320.0 * 0.01 + 0.2375f64.powi(2));
    assert!((1.5 * (0.0025 + 0.16 / 12.0) + 2.0 * hemisphere - 0.05325).abs() < 1e-15);
}

#[test]
fn round_bodies_and_their_keys_are_checked_at_file_line_column() {
    let base = scene(0.5, 0.0, true);
    let seed = base.replace("\"impulse\"", "\"seed\"");
    let ball = "[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
                [[obstacle]]\ntype = \"ground\"\nheight = -1.0\n";
    assert_eq!(
        error(&format!("{seed}{ball}")),
        "t.toml:6:24: the `seed` response tests vertices, and the sphere `body1` has none: \
         use response = \"impulse\""
    );
    assert_eq!(
        error(&format!(
            "{base}[body]\nshape = \"capsule\"\nradius = 0.1\nlength = 0.2\nmass = 1.0\n\
             inertia = \"shell\"\n"
        )),
        "t.toml:12:11: `inertia = \"shell\"` is for a sphere or a cylinder, not a capsule body"
    );
    assert_eq!(
        error(&format!(
            "{base}[body]\nshape = \"cylinder\"\nradius = 0.1\nmass = 1.0\n"
        )),
        "t.toml:7:1: a cylinder body needs `length`"
    );
    assert_eq!(
        error(&format!(
            "{base}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\n\
             [[obstacle]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 0.0]\n"
        )),
        "t.toml:14:10: plane `normal` has zero length: give the outward direction, e.g. \
         [0.0, 1.0, 0.0]"
    );
}

mod random_pairs {
    //! Two bodies of any shape kinds (ball, capsule, cylinder, box, hull) thrown at each other in
    //! empty space, under `impulse` and under `soft-step`: momentum is kept,
    //! the energy never rises, nothing panics and no overlap deeper than a few millimetres is
    //! left after the meeting (0.5–2 kg bodies of about 0.1 m at 0.5–3 m/s, dt = 1 ms).

    use nalgebra::{Unit, UnitQuaternion, Vector3};
    use proptest::prelude::*;
    use tumble::physics::snapshot::geometric_penetration;
    use tumble::physics::{
        Body, ContactModel, Effects, Impacts, Integrator, NamedBody, Orientation, Response,
        SoftStep, State, World,
    };

    fn body(kind: usize, mass: f64) -> Body {
        match kind {
            0 => Body::sphere(0.1, mass, false),
            1 => Body::capsule(0.06, 0.15, mass),
            2 => Body::cylinder(0.08, 0.15, mass, false),
            3 => Body::solid_box(Vector3::new(0.2, 0.12, 0.16), mass),
            // A hull: an octahedron of mass points (uneven, so it is no box).
            _ => Body::from_points(
                &[
                    Vector3::new(0.12, 0.0, 0.0),
                    Vector3::new(-0.1, 0.0, 0.0),
                    Vector3::new(0.0, 0.09, 0.0),
                    Vector3::new(0.0, -0.11, 0.0),
                    Vector3::new(0.0, 0.0, 0.1),
                    Vector3::new(0.0, 0.0, -0.08),
                ],
                &[],
                mass,
                vec![],
            ),
        }
        .unwrap()
    }

    fn turn(axis: (f64, f64, f64), angle: f64) -> UnitQuaternion<f64> {
        let axis = Vector3::new(axis.0, axis.1, axis.2 + 1e-3);
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), angle)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]

        #[test]
        fn any_two_shapes_keep_momentum_and_make_no_energy(
            kinds in (0usize..5, 0usize..5),
            masses in (0.5..2.0f64, 0.5..2.0f64),
            axes in ((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)),
            angles in (0.0..6.3f64, 0.0..6.3f64),
            offset in (-0.1..0.1f64, -0.1..0.1f64),
            speed in 0.5..3.0f64,
            spin in (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64),
            restitution in 0.0..=1.0f64,
            friction in 0.0..1.0f64,
        ) {
            let (a, b) = (body(kinds.0, masses.0), body(kinds.1, masses.1));
            let named = |name: &str, body: Body, x: f64, v: f64, q: UnitQuaternion<f64>, w: Vector3<f64>| {
                let r = q.to_rotation_matrix().into_inner();
                NamedBody {
                    name: name.into(),
                    initial: State {
                        // a off the line by `offset` (glancing blows), b on it.
                        position: if x < 0.0 {
                            Vector3::new(x, offset.0, offset.1)
                        } else {
                            Vector3::new(x, 0.0, 0.0)
                        },
                        orientation: Orientation::Quaternion(q),
                        linear_momentum: Vector3::new(v * body.mass, 0.0, 0.0),
                        angular_momentum: r * body.inertia_body * r.transpose() * w,
                    },
                    body,
                }
            };
            let spin = Vector3::new(spin.0, spin.1, spin.2);
            // Both responses. `soft-step`'s documented bound (collision/soft_step.rs, "Energy"):
            // E ≤ E₀ + Σ M|g|·d_max; without gravity that is E₀, as for `impulse`.
            for response in [Response::Impulse, Response::SoftStep(SoftStep::DEFAULT)] {
            let bodies = vec![
                named("a", a.clone(), -0.3, speed, turn(axes.0, angles.0), spin),
                named("b", b.clone(), 0.3, -speed, turn(axes.1, angles.1), -spin),
            ];
            let name = response.name();
            let model = ContactModel { response, restitution, friction, impacts: Impacts::default() };
            let mut w = World::with_bodies(
                bodies, Effects::new(vec![]), vec![], Some(model), Integrator::Rk4, 1e-3,
            );
            let p0: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
            let e0 = w.total_energy().total;
            let mut deepest: f64 = 0.0;
            let mut touched = false;
            // 0.7 s: the slowest pair (1 m/s closing) broadside (0.06 m half-extents) closes
            // its 0.48 m gap by 0.48 s.
            for step in 0..700 {
                w.step();
                // Met: an impulse passed between them (a speculative contact may stop the pair
                // at depth ≤ 0, before any overlap).
                touched |= w.contacts().iter().any(|c| c.impulse.norm() > 0.0);
                let e = w.total_energy().total;
                prop_assert!(e.is_finite() && e <= e0 * (1.0 + 1e-9) + 1e-12,
                    "{name} step {step}: E = {e} > E₀ = {e0}");
                if step > 600 {
                    deepest = deepest.max(geometric_penetration(&w, 0, &w.vertices_of(0)));
                }
            }
            let p: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
            prop_assert!((p - p0).norm() < 1e-9 * (1.0 + p0.norm()), "{name}: P {p0:?} → {p:?}");
            prop_assert!(deepest < 5e-3, "{name}: left {deepest} m deep");
            // Nearly on the line of centres, every pair meets (the test is not vacuous).
            if offset.0.abs() < 0.02 && offset.1.abs() < 0.02 {
                prop_assert!(touched, "{name}: a head-on pair never touched");
            }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The contacts' force and torque (the snapshot's F_c, τ_c: Σ J/dt and Σ r × J/dt)
// ---------------------------------------------------------------------------------------------

#[test]
fn a_box_resting_on_the_ground_gets_m_g_up_from_its_contacts_and_no_torque() {
    // At rest, the collide phase takes away exactly what gravity gave in the step: Σ J = M g dt
    // up, F_c = M g = 2 × 9.81 = 19.62 N; the four corners carry it symmetrically about the
    // barycenter, so τ_c = Σ r × J/dt = 0.
    let source = format!(
        "{}[body]\nshape = \"box\"\nsize = [0.2, 0.2, 0.2]\nmass = 2.0\nposition = [0.0, 0.1, 0.0]\n\
         [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n",
        scene(0.5, 0.0, true)
    );
    let mut w = world(&source);
    run(&mut w, 0.5);
    let s = w.snapshot();
    assert!(!s.contacts.is_empty(), "the box touches the ground");
    let expected = Vector3::new(0.0, 2.0 * G, 0.0);
    assert!(
        (s.contact_force - expected).norm() < 1e-6 * expected.norm(),
        "F_c = {:?}, expected {expected:?}",
        s.contact_force
    );
    assert!(
        s.contact_torque.norm() < 1e-9,
        "τ_c = {:?}",
        s.contact_torque
    );
    // The effects' force is gravity alone: F + F_c = 0 for a body at rest.
    assert!((s.force + s.contact_force).norm() < 1e-6);
}

#[test]
fn a_ball_rolling_down_a_ramp_gets_two_sevenths_m_g_sin_theta_of_friction_up_the_slope() {
    // A solid ball (M = 1, r = 0.1, I = ⅖ M r²) rolling on a 20° ramp: a = 5/7 g sin θ, so the
    // contact pushes M g cos θ = 9.218381 N along n and friction f = M g sin θ − M a
    // = (2/7) M g sin θ = 0.958636 N up the slope; its torque about the centre is r × f with
    // r = −0.1 n: |τ_c| = 0.1 f = 0.0958636 N·m, along −z (it spins the ball toward +x).
    let (n, plane) = ramp(20.0);
    let source = format!(
        "{}[body]\nshape = \"sphere\"\nradius = 0.1\nmass = 1.0\nposition = {}\n{plane}",
        scene(0.5, 0.0, true),
        vec(&(n * 0.1))
    );
    let mut w = world(&source);
    run(&mut w, 0.5);
    let s = w.snapshot();
    let t = 20f64.to_radians();
    let uphill = Vector3::new(-n.y, n.x, 0.0);
    let f = 2.0 / 7.0 * G * t.sin();
    let normal = G * t.cos();
    let fc = s.contact_force;
    assert!(
        (fc.dot(&n) - normal).abs() < 1e-3 * normal,
        "normal part {} N, expected {normal}",
        fc.dot(&n)
    );
    assert!(
        (fc.dot(&uphill) - f).abs() < 1e-3 * f,
        "friction {} N, expected {f}",
        fc.dot(&uphill)
    );
    let expected_torque = (-n * 0.1).cross(&(uphill * f));
    assert!(
        (s.contact_torque - expected_torque).norm() < 1e-3 * expected_torque.norm(),
        "τ_c = {:?}, expected {expected_torque:?}",
        s.contact_torque
    );
    assert!(expected_torque.z < 0.0);
}
