//! Impacts among touching bodies (`contact = { impacts = "propagate" | "simultaneous" }`):
//! a touching Newton's cradle, a touching row in empty space, a rack of balls and the
//! superball stack against their closed forms and conservation laws.

use nalgebra::Vector3;
use std::fmt::Write;
use tumble::physics::World;

const G: f64 = 9.81;
/// Ball radius and rod length of the cradle, m.
const R: f64 = 0.05;
const L: f64 = 1.0;

fn world(source: &str) -> World {
    tumble::scene::parse(source, std::path::Path::new("impacts.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
        .world()
}

fn header(gravity: bool, restitution: f64, impacts: &str) -> String {
    let mut s = String::from("title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"rk4\"\n");
    if gravity {
        s += "gravity = [0.0, -9.81, 0.0]\n";
    }
    writeln!(
        s,
        "contact = {{ response = \"impulse\", restitution = {restitution}, friction = 0.0, impacts = \"{impacts}\" }}"
    )
    .unwrap();
    s
}

fn ball(s: &mut String, name: &str, radius: f64, mass: f64, at: Vector3<f64>, v: Vector3<f64>) {
    writeln!(
        s,
        "[[body]]\nname = \"{name}\"\nshape = \"sphere\"\nradius = {radius}\nmass = {mass}\n\
         position = [{}, {}, {}]\nvelocity = [{}, {}, {}]",
        at.x, at.y, at.z, v.x, v.y, v.z
    )
    .unwrap();
}

/// Five balls touching in a row on 1 m rods, the first `pulled` released from θ₀ = 30°.
fn cradle(restitution: f64, impacts: &str, pulled: usize) -> String {
    let mut s = header(true, restitution, impacts);
    let theta: f64 = 30f64.to_radians();
    for i in 0..5 {
        let pivot = Vector3::new(2.0 * R * i as f64, 0.0, 0.0);
        let at = if i < pulled {
            pivot + Vector3::new(-L * theta.sin(), -L * theta.cos(), 0.0)
        } else {
            pivot - Vector3::new(0.0, L, 0.0)
        };
        ball(&mut s, &format!("b{i}"), R, 1.0, at, Vector3::zeros());
        writeln!(
            s,
            "[[joint]]\ntype = \"distance\"\nbodies = [\"b{i}\"]\nanchors = [[{}, {}, 0.0], [{}, 0.0, 0.0]]",
            at.x, at.y, pivot.x
        )
        .unwrap();
    }
    s
}

fn speeds(w: &World) -> Vec<f64> {
    w.states()
        .iter()
        .zip(w.bodies())
        .map(|(s, b)| s.linear_momentum.x / b.mass)
        .collect()
}

/// Steps until the last ball moves (the impact and its rounds happen within that step), then
/// 5 ms more (balls pulled aside together may meet a step apart). Returns the scene's energy
/// before the impact and after, and the kinetic energy before.
fn impact(w: &mut World) -> (f64, f64, f64) {
    for _ in 0..2000 {
        let before = w.total_energy();
        w.step();
        if speeds(w)[4].abs() > 1e-3 {
            for _ in 0..5 {
                w.step();
            }
            return (before.total, w.total_energy().total, before.kinetic);
        }
    }
    panic!("no impact");
}

#[test]
fn a_touching_cradle_sends_the_last_ball_off_with_the_first_ones_speed() {
    let arrival = (2.0 * G * L * (1.0 - 30f64.to_radians().cos())).sqrt();
    let mut w = world(&cradle(1.0, "propagate", 1));
    let (e0, e, k) = impact(&mut w);
    let v = speeds(&w);
    println!("cradle propagate: v = {v:?}, arrival {arrival}, E {e0} -> {e} (K {k})");
    assert!(v[4] >= 0.99 * arrival, "last ball {} of {arrival}", v[4]);
    for (i, vi) in v[..4].iter().enumerate() {
        assert!(vi.abs() <= 0.01 * arrival, "ball {i} keeps {vi}");
    }
    assert!(((e - e0) / e0).abs() < 1e-6, "E {e0} -> {e}");
}

#[test]
fn under_simultaneous_impact_a_touching_cradle_acts_as_one_block() {
    let arrival = (2.0 * G * L * (1.0 - 30f64.to_radians().cos())).sqrt();
    let mut w = world(&cradle(1.0, "simultaneous", 1));
    impact(&mut w);
    let v = speeds(&w);
    println!("cradle simultaneous: v = {v:?}");
    // The first ball bounces back, the other four leave together, slower.
    assert!(v[0] < -0.2 * arrival, "{v:?}");
    assert!(
        v[1..].iter().all(|x| (x - v[4]).abs() < 1e-3 * arrival),
        "{v:?}"
    );
    assert!(v[4] < 0.5 * arrival, "{v:?}");
}

#[test]
fn pulling_two_and_three_aside_sends_two_and_three_off() {
    let arrival = (2.0 * G * L * (1.0 - 30f64.to_radians().cos())).sqrt();
    for pulled in [2, 3] {
        let mut w = world(&cradle(1.0, "propagate", pulled));
        let (e0, e, k) = impact(&mut w);
        let v = speeds(&w);
        println!("{pulled} pulled: v = {v:?}, E {e0} -> {e} (K {k})");
        for (i, vi) in v.iter().enumerate() {
            if i >= 5 - pulled {
                assert!(*vi >= 0.99 * arrival, "{pulled} pulled: ball {i} at {vi}");
            } else {
                assert!(
                    vi.abs() <= 0.01 * arrival,
                    "{pulled} pulled: ball {i} at {vi}"
                );
            }
        }
        assert!(((e - e0) / e0).abs() < 1e-6, "E {e0} -> {e}");
    }
}

/// Five balls touching in empty space, the first arriving at `v0` from 1 cm away.
fn row(restitution: f64, impacts: &str, v0: f64) -> String {
    let mut s = header(false, restitution, impacts);
    for i in 0..5 {
        let x = 2.0 * R * i as f64 + if i == 0 { -0.01 } else { 0.0 };
        let v = if i == 0 { v0 } else { 0.0 };
        ball(
            &mut s,
            &format!("b{i}"),
            R,
            1.0,
            Vector3::new(x, 0.0, 0.0),
            Vector3::new(v, 0.0, 0.0),
        );
    }
    s
}

#[test]
fn a_touching_row_in_empty_space_keeps_momentum_and_only_the_last_ball_moves() {
    let v0 = 1.0;
    let mut w = world(&row(1.0, "propagate", v0));
    let p0: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
    let e0 = w.total_energy().total;
    for _ in 0..100 {
        w.step();
    }
    let p: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
    let v = speeds(&w);
    println!("row: v = {v:?}, P {p0:?} -> {p:?}");
    assert!((p - p0).norm() < 1e-9, "P {p0:?} -> {p:?}");
    assert!((w.total_energy().total - e0).abs() < 1e-9 * e0);
    assert!((v[4] - v0).abs() < 1e-9, "{v:?}");
    assert!(v[..4].iter().all(|x| x.abs() < 1e-9), "{v:?}");
}

#[test]
fn at_e_0_both_laws_share_the_blow_among_all_five() {
    let v0 = 1.0;
    for impacts in ["propagate", "simultaneous"] {
        let mut w = world(&row(0.0, impacts, v0));
        for _ in 0..100 {
            w.step();
        }
        let v = speeds(&w);
        println!("e = 0, {impacts}: v = {v:?}");
        assert!(
            v.iter().all(|x| (x - v0 / 5.0).abs() < 1e-9),
            "{impacts}: {v:?}"
        );
    }
}

/// A touching triangle rack of `rows` rows in empty space (apex towards −x), hit along its
/// axis by a cue ball at 2 m/s.
fn rack(rows: usize) -> String {
    let mut s = header(false, 1.0, "propagate");
    let r = 0.0286;
    let dx = 2.0 * r * 3f64.sqrt() / 2.0;
    for k in 0..rows {
        for j in 0..=k {
            let z = (j as f64 - k as f64 / 2.0) * 2.0 * r;
            ball(
                &mut s,
                &format!("r{k}_{j}"),
                r,
                0.17,
                Vector3::new(k as f64 * dx, 0.0, z),
                Vector3::zeros(),
            );
        }
    }
    ball(
        &mut s,
        "cue",
        r,
        0.17,
        Vector3::new(-2.0 * r - 0.01, 0.0, 0.0),
        Vector3::new(2.0, 0.0, 0.0),
    );
    s
}

#[test]
fn a_touching_rack_breaks_with_momentum_and_energy_kept_and_mirror_symmetric() {
    let rows = 4;
    let mut w = world(&rack(rows));
    let p0: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
    let e0 = w.total_energy().total;
    for _ in 0..300 {
        w.step();
    }
    let p: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
    let e = w.total_energy().total;
    // Ball (k, j) mirrors ball (k, k − j) about the cue line z = 0.
    let mut worst: f64 = 0.0;
    let mut i = 0;
    for k in 0..rows {
        for j in 0..=k {
            let mirror = i - j + (k - j);
            let (a, b) = (w.states()[i].position, w.states()[mirror].position);
            worst = worst
                .max((a.x - b.x).abs())
                .max((a.z + b.z).abs())
                .max((a.y - b.y).abs());
            i += 1;
        }
    }
    let cue = w.states()[i].linear_momentum / 0.17;
    println!("rack: P {p0:?} -> {p:?}, E {e0} -> {e}, mirror error {worst:e} m, cue {cue:?}");
    assert!((p - p0).norm() < 1e-9, "P {p0:?} -> {p:?}");
    assert!(((e - e0) / e0).abs() < 1e-6, "E {e0} -> {e}");
    assert!(worst < 1e-6, "mirror error {worst} m");
    // The break happened: the rack moves.
    assert!(cue.x < 1.0, "cue {cue:?}");
}

#[test]
fn the_superball_stack_throws_the_small_ball_up_at_the_closed_form_speed() {
    // A small ball (m₂) resting on a big one (m₁), dropped together from 1 m.
    let (m1, m2, r1, r2, h) = (1.0, 0.1, 0.1, 0.03, 1.0);
    let mut s = header(true, 1.0, "propagate");
    s += "[[obstacle]]\ntype = \"ground\"\nheight = 0.0\n";
    ball(
        &mut s,
        "big",
        r1,
        m1,
        Vector3::new(0.0, h + r1, 0.0),
        Vector3::zeros(),
    );
    ball(
        &mut s,
        "small",
        r2,
        m2,
        Vector3::new(0.0, h + 2.0 * r1 + r2, 0.0),
        Vector3::zeros(),
    );
    let mut w = world(&s);
    let v = (2.0 * G * h).sqrt();
    let expected = v * (3.0 * m1 - m2) / (m1 + m2);
    let mut top: f64 = 0.0;
    let mut launch: f64 = 0.0;
    // Down 1 m (0.45 s), then up about 7 m (1.2 s); the small ball comes down on the big one
    // later.
    for _ in 0..1700 {
        w.step();
        let small = w.states()[1];
        if w.time() < 0.6 {
            launch = launch.max(small.linear_momentum.y / m2);
        }
        top = top.max(small.position.y);
    }
    let rise = top - (2.0 * r1 + r2);
    let expected_rise = expected * expected / (2.0 * G);
    println!(
        "superball: leaves at {launch} (closed form {expected}), rises {rise} m of {expected_rise}"
    );
    assert!(
        (rise / expected_rise - 1.0).abs() < 0.02,
        "rise {rise} of {expected_rise}"
    );
}

#[test]
fn the_impacts_key_is_checked_where_it_is_written() {
    let error = |source: &str| {
        tumble::scene::parse(source, std::path::Path::new("impacts.toml"))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    let scene = |contact: &str| {
        format!(
            "title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"rk4\"\ncontact = {{ {contact} }}\n\
             [[obstacle]]\ntype = \"ground\"\nheight = 0.0\n[body]\nshape = \"box\"\nsize = [0.1, 0.1, 0.1]\nmass = 1.0\n"
        )
    };
    let typo = error(&scene(r#"response = "impulse", impacts = "propagated""#));
    assert!(
        typo.ends_with(
            "impacts.toml:5:45: unknown impact law `propagated` (did you mean `propagate`?); \
             valid laws: propagate, simultaneous"
        ),
        "{typo}"
    );
    let seed = error(&scene(r#"response = "seed", impacts = "simultaneous""#));
    assert!(
        seed.ends_with(
            "impacts.toml:5:42: `impacts` is a key of the `impulse` response, not of `seed`"
        ),
        "{seed}"
    );
    let soft = error(&scene(r#"response = "soft-step", impacts = "propagate""#));
    assert!(soft.contains("not of `soft-step`"), "{soft}");
    for law in ["propagate", "simultaneous"] {
        let ok = error(&scene(&format!(
            r#"response = "impulse", impacts = "{law}""#
        )));
        assert!(ok.is_empty(), "{ok}");
    }
}

/// A bob of radius R on a rod of L = 1 m from the pivot (0, L), released from 30° on the
/// left, meets at the bottom a wall tilted 45° (a plane facing up and back, n = (−1, 1)/√2).
fn bob_and_tilted_wall(restitution: f64) -> String {
    let mut s = header(true, restitution, "propagate");
    let theta: f64 = 30f64.to_radians();
    let pivot = Vector3::new(0.0, L, 0.0);
    let at = pivot + Vector3::new(-L * theta.sin(), -L * theta.cos(), 0.0);
    ball(&mut s, "bob", R, 1.0, at, Vector3::zeros());
    let n = Vector3::new(-1.0, 1.0, 0.0) / 2f64.sqrt();
    let point = -n * R; // touches the bob at the bottom, (0, 0)
    writeln!(
        s,
        "[[joint]]\ntype = \"distance\"\nbodies = [\"bob\"]\nanchors = [[{}, {}, 0.0], [0.0, {L}, 0.0]]\n\
         [[obstacle]]\ntype = \"plane\"\npoint = [{}, {}, 0.0]\nnormal = [{}, {}, 0.0]",
        at.x, at.y, point.x, point.y, n.x, n.y
    )
    .unwrap();
    s
}

#[test]
fn a_bob_on_a_rod_bounces_off_a_tilted_wall_with_e_times_its_speed() {
    // The rod keeps the bob's velocity along the circle's tangent t = x̂ at the bottom; the
    // wall's normal n is at 45° to it. One solution of the contact and the rod's reaction
    // (`impulse::joined`): the bob's tangential speed s obeys the contact law along n,
    // s⁺ (n·t) = −e s⁻ (n·t), so s⁺ = −e s⁻ at any tilt, and the energy lost is (1 − e²) K.
    // (Contacts first, the rod after: s⁺ = s⁻ (1 − (1 + e) (n·t)²) = 0 at e = 1, 45°.)
    for e in [1.0, 0.5] {
        let mut w = world(&bob_and_tilted_wall(e));
        let (before, after, k0, e0, e1) = (0..1000)
            .find_map(|_| {
                let (v0, e0) = (w.states()[0].linear_momentum, w.total_energy());
                w.step();
                let v1 = w.states()[0].linear_momentum;
                (v1.x < 0.0).then(|| (v0, v1, e0.kinetic, e0.total, w.total_energy().total))
            })
            .expect("the bob meets the wall");
        let ratio = after.norm() / before.norm();
        println!(
            "bob on a tilted wall, e = {e}: v {before:?} -> {after:?}, |v⁺|/|v⁻| = {ratio}, \
             E {e0} -> {e1} (K {k0})"
        );
        // Less by the push-out's lift, paid from the bounce (the energy clamp): the bob is
        // found up to v·dt·cos 45° = 1.1 mm inside the wall, m g Δh ≈ 0.5 % of K.
        assert!((ratio - e).abs() < 5e-3, "e = {e}: |v⁺|/|v⁻| = {ratio}");
        // Along the tangent: the rod holds it (|v_y| is the arc's, v_x ≈ |v|).
        assert!(after.y.abs() < 2e-3 * after.norm(), "{after:?}");
        let lost = e0 - e1;
        let want = (1.0 - e * e) * k0;
        assert!(
            (lost - want).abs() < 5e-3 * k0,
            "e = {e}: lost {lost} J, (1 − e²) K = {want} J"
        );
        assert!(w.links().joints[0].error(w.states()) < 1e-9);
    }
}

#[test]
fn a_spinning_bob_on_a_rod_meets_a_tilted_wall_with_friction_in_one_solve() {
    // The bob of `bob_and_tilted_wall` (m = 1 kg, R = 0.05 m, I = 0.4 m R²) spinning at ω₀
    // about z, the wall's friction μ = 0.2 (`impulse::joined`: the rod's reaction inside the
    // friction stage). The rod leaves the bob x and its spin: stopping the contact's normal
    // (λ₁ = m s / cos 45°) stops v_x, and the contact point still slides at ω₀ R along the
    // wall. With the rod held, K over (λₙ, λ_t) near the contact is
    // G = [[c²/m, −cs/m], [−cs/m, s²/m + r²/I]] (c = s = cos 45°): sticking takes
    // λ_t = −ω₀ I / r (ω⁺ = 0; r the contact's lever) if that is within μ λ₁, else
    // λ_t = −μ λ₁ and ω⁺ = ω₀ − μ λ₁ r / I; the normal keeps v_x = 0, and the restitution e λ₁ then leaves
    // v_x⁺ = −e s (friction has taken energy from the spin: the clamp does not bind).
    let (m, mu, inertia) = (1.0, 0.2, 0.4 * R * R);
    for (e, spin) in [(1.0, 50.0), (0.5, 50.0), (0.5, 10.0)] {
        let scene = bob_and_tilted_wall(e)
            .replace("friction = 0.0", &format!("friction = {mu}"))
            .replacen(
                "velocity = [0, 0, 0]",
                &format!("velocity = [0, 0, 0]\nangular_velocity = [0.0, 0.0, {spin}]"),
                1,
            );
        assert!(scene.contains("angular_velocity"), "{scene}");
        let mut w = world(&scene);
        let (before, after, w1, e0, e1) = (0..1000)
            .find_map(|_| {
                let (v0, e0) = (w.states()[0].linear_momentum, w.total_energy());
                w.step();
                let s1 = w.states()[0];
                (s1.linear_momentum.x < 0.0).then(|| {
                    let omega = s1.angular_momentum.z / inertia;
                    (
                        v0,
                        s1.linear_momentum,
                        omega,
                        e0.total,
                        w.total_energy().total,
                    )
                })
            })
            .expect("the bob meets the wall");
        // The lever r of the contact point (the bob is found a little inside the wall, so r
        // is a fraction of a millimetre short of R).
        let c = w.contacts()[0];
        let r = c.lever.norm();
        let speed = before.norm() / m;
        let lambda1 = m * speed * 2f64.sqrt();
        let stick = spin * inertia / r;
        let (want_omega, want_tangent) = if stick <= mu * lambda1 {
            (0.0, stick)
        } else {
            (spin - mu * lambda1 * r / inertia, mu * lambda1)
        };
        let tangent = (spin - w1) * inertia / r;
        println!(
            "spinning bob, e = {e}, ω₀ = {spin}: v {before:?} -> {after:?}, ω⁺ = {w1} \
             (closed form {want_omega}), λ_t = {tangent} (closed form {want_tangent}, \
             μ λ₁ = {}), E {e0} -> {e1}",
            mu * lambda1
        );
        // Coulomb at the contact: the tangential impulse within μ times the normal one.
        let normal = c.impulse.dot(&c.normal);
        let sliding = (c.impulse - c.normal * normal).norm();
        assert!(
            sliding <= mu * normal,
            "|J_t| {sliding} > μ Jₙ = {}",
            mu * normal
        );
        assert!(
            (sliding - tangent).abs() < 1e-6,
            "J_t {sliding}, from the spin {tangent}"
        );
        assert!(
            (tangent - want_tangent).abs() < 5e-3 * want_tangent,
            "λ_t {tangent}, closed form {want_tangent}"
        );
        assert!(
            (after.x / m + e * speed).abs() < 5e-3 * speed,
            "v_x⁺ {} against −e s = {}",
            after.x / m,
            -e * speed
        );
        assert!(e1 <= e0, "the energy rose: {e0} -> {e1}");
        assert!(w.links().joints[0].error(w.states()) < 1e-9);
    }
}

#[test]
fn a_jointed_pair_landing_flat_with_friction_sticks_in_the_solve_that_holds_its_joint() {
    // Two links (0.3 × 0.05 × 0.05 m, 0.1 kg) on a ball joint, lying flat 0.5 mm above the
    // ground and moving at v = (0.5, −2, 0) m/s, e = 0, μ = 0.5: sticking needs the tangential
    // impulse m v_x = 0.1 N·s against μ m |v_y| ≈ 0.2 N·s, so the landing step stops both links
    // dead (the momentum theorem: the contacts' impulses are −P⁻ less gravity's m g dt),
    // solved by the direct sticking solve with the joint's rows in the same system
    // (`impulse::joined`), and nothing slides afterwards.
    let (m, mu, v) = (0.1, 0.5, Vector3::new(0.5, -2.0, 0.0));
    let mut s = String::from("title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"rk4\"\n");
    s += "gravity = [0.0, -9.81, 0.0]\n";
    writeln!(
        s,
        "contact = {{ response = \"impulse\", restitution = 0.0, friction = {mu} }}"
    )
    .unwrap();
    for (name, x) in [("a", -0.15), ("b", 0.15)] {
        writeln!(
            s,
            "[[body]]\nname = \"{name}\"\nshape = \"box\"\nsize = [0.3, 0.05, 0.05]\nmass = {m}\n\
             position = [{x}, 0.0255, 0.0]\nvelocity = [{}, {}, {}]",
            v.x, v.y, v.z
        )
        .unwrap();
    }
    s += "[[joint]]\ntype = \"ball\"\nbodies = [\"b\", \"a\"]\nanchor = [0.0, 0.0255, 0.0]\n";
    s += "[[obstacle]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";
    let mut w = world(&s);
    let p0: Vector3<f64> = w.states().iter().map(|s| s.linear_momentum).sum();
    let mut landed = None;
    for step in 0..10 {
        w.step();
        if !w.contacts().is_empty() {
            landed = Some(step);
            break;
        }
    }
    assert!(landed.is_some(), "the pair never touched");
    let counters = w.contact_counters();
    let impulse: Vector3<f64> = w.contacts().iter().map(|c| c.impulse).sum();
    let normal = impulse.y;
    let tangential = Vector3::new(impulse.x, 0.0, impulse.z).norm();
    let speed = w
        .states()
        .iter()
        .map(|s| s.linear_momentum.norm() / m)
        .fold(0.0, f64::max);
    let spin = w
        .states()
        .iter()
        .map(|s| s.angular_momentum.norm())
        .fold(0.0, f64::max);
    println!(
        "jointed pair landing: {counters:?}, impulse {impulse:?} (P⁻ {p0:?}), speed after \
         {speed:e} m/s, |L| {spin:e}"
    );
    assert!(counters.joined_sticking >= 1, "{counters:?}");
    // Stopped in the landing step.
    assert!(speed < 1e-8, "a link still moves at {speed:e} m/s");
    assert!(spin < 1e-10, "a link still turns: |L| = {spin:e}");
    // The momentum theorem: the contacts took −P⁻ (gravity's m g dt per step on top of the
    // normal one) — the tangential part exactly, within μ times the normal one.
    assert!(
        (tangential - 2.0 * m * v.x).abs() < 1e-9,
        "J_t = {tangential}"
    );
    assert!(
        tangential <= mu * normal,
        "|J_t| {tangential} > μ Jₙ {normal}"
    );
    assert!(
        (normal + p0.y).abs() < 2.0 * m * 9.81 * 2e-3,
        "Jₙ = {normal} against −P⁻_y = {}",
        -p0.y
    );
    // Nothing slides after it, and the joint holds.
    let x0: Vec<Vector3<f64>> = w.states().iter().map(|s| s.position).collect();
    for _ in 0..500 {
        w.step();
    }
    for (s, x) in w.states().iter().zip(&x0) {
        let slid = Vector3::new(s.position.x - x.x, 0.0, s.position.z - x.z).norm();
        assert!(slid < 1e-9, "slid {slid:e} m in 0.5 s");
    }
    assert!(w.links().joints[0].error(w.states()) < 1e-9);
}
