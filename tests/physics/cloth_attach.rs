//! Bodies hung from cloth (issue 20, item 4): a flag on a pole — fixed, falling, on a hinge —
//! and a trampoline whose frame is a body resting on the floor. Scenes are written as scene
//! files, as a teacher would (`attach = [{ edge = …, body = … }]`), and checked against
//! statics (the support carries m g and its moment), conservation (momentum in free fall, the
//! ground's impulse the only outside one), the attach constraint and the energy ledger.

use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::{Against, World};
use tumble::scene::parse;

const G: f64 = 9.81;

fn world(source: &str) -> World {
    parse(source, Path::new("test.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
        .world()
}

fn step(world: &mut World) {
    world.step();
    if let Some(d) = world.divergence() {
        panic!("{d}");
    }
}

/// P of every body and particle, kg·m/s.
fn total_momentum(world: &World) -> Vector3<f64> {
    let bodies: Vector3<f64> = world.states().iter().map(|s| s.linear_momentum).sum();
    bodies + world.cloths()[0].linear_momentum()
}

/// The barycentre of cloth 0 (its particles share its mass equally), m.
fn cloth_barycentre(world: &World) -> Vector3<f64> {
    let c = &world.cloths()[0];
    c.positions.iter().sum::<Vector3<f64>>() / c.len() as f64
}

/// A flag 1 m × 0.6 m (11 × 7 particles, 0.3 kg) sewn along its edge j = 0 onto a pole 1.6 m
/// long along x whose end x = 0 is at a wall, y = 2; the flag hangs from x = 0.5 to 1.5 m.
/// `pole` is the body's extra keys (fixed, or a mass), `drag` the scene's linear drag.
fn flag(pole: &str, drag: f64, extra: &str) -> String {
    let drag = if drag > 0.0 {
        format!("drag = {{ linear = {drag}, angular = 0.05 }}")
    } else {
        String::new()
    };
    format!(
        r#"
title = "A flag on a pole"
[scene]
dt = 0.001
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
{drag}
contact = {{ response = "impulse", restitution = 0.0, friction = 0.5 }}

[[body]]
name = "pole"
shape = "box"
size = [1.6, 0.04, 0.04]
{pole}
position = [0.8, 2.0, 0.0]

[[cloth]]
name = "flag"
size = [1.0, 0.6]
count = [11, 7]
position = [1.0, 2.0, 0.3]
mass = 0.3
stretch = 2000.0
shear = 500.0
bend = 20.0
damping = 1.0
integrator = "implicit-euler"
attach = [{{ edge = "-z", body = "pole" }}]
{extra}
"#
    )
}

#[test]
fn a_flag_on_a_fixed_pole_hangs_and_the_pole_carries_its_weight_and_its_moment() {
    let mut w = world(&flag("fixed = true", 1.0, ""));
    assert_eq!(
        w.cloths()[0].attached.len(),
        11,
        "edge -z: the 11 particles j = 0"
    );
    let mut worst = 0.0_f64;
    for _ in 0..8000 {
        step(&mut w);
        worst = worst.max(w.attach_error(0));
    }
    let c = &w.cloths()[0];
    let m = 0.3;
    // At rest (drag 1 kg/s on 0.3 kg: 3.3/s, over 8 s).
    assert!(c.max_speed() < 1e-5, "max speed {}", c.max_speed());
    // It hangs: every free particle below the pole, the lowest row about 0.6 m down.
    let lowest = c
        .positions
        .iter()
        .map(|x| x.y)
        .fold(f64::INFINITY, f64::min);
    assert!((2.0 - lowest - 0.6).abs() < 0.01, "lowest row at {lowest}");
    // The support: Σ F_a = −m g = (0, m g, 0) = (0, 2.943, 0) N.
    let [force, moment_origin] = w.cloth_attach_load(0);
    let weight = Vector3::new(0.0, m * G, 0.0);
    eprintln!("flag on a fixed pole: attachments carry {force:?} N (m g = 2.943 N)");
    // (To 1e-5 N: measured 4.4e-6 N sideways, the same at a CG tolerance of 1e-8: the flag
    // still sways at 8 s, its fastest particle at 1.9e-6 m/s, `examples/attach_rest`.)
    assert!((force - weight).norm() < 1e-5, "Σ F_a = {force:?}");
    // Their moment about the pole's root at the wall c = (0, 2, 0): M_c = M_O − c × F. The
    // flag's balance: M_c = −(x_G − c) × m g⃗ = (x_G − c) × (0, m g, 0), with x_G the flag's
    // barycentre; by hand (x_G = 1.0 m out along the pole, right below it) M_c ≈ (0, 0,
    // m g × 1.0 m) = (0, 0, 2.943) N·m: the cantilever moment the wall must hold.
    let root = Vector3::new(0.0, 2.0, 0.0);
    let moment = moment_origin - root.cross(&force);
    let expected = (cloth_barycentre(&w) - root).cross(&weight);
    eprintln!("moment about the root {moment:?} N·m, from the barycentre {expected:?}");
    assert!(
        (moment - expected).norm() < 1e-5,
        "{moment:?} vs {expected:?}"
    );
    assert!(
        (moment - Vector3::new(0.0, 0.0, 2.943)).norm() < 2e-3,
        "{moment:?}"
    );
    // The attached particles stay on their points.
    eprintln!("worst attach error {worst:e} m");
    assert!(worst < 1e-9, "attach error {worst:e} m");
    // The ledger closes: E − E₀ = drag + contacts + drift; a fixed attachment does no work
    // (contacts 0) and backward Euler only loses (drift ≤ 0).
    let b = w.energy_balance();
    let (drag, contacts) = (b.drag_work.unwrap(), b.contacts.unwrap_or(0.0));
    eprintln!(
        "E − E₀ {:.6} J = drag {drag:.6} + contacts {contacts:e} + drift {:.6}",
        b.change, b.drift
    );
    assert!((b.change - (drag + contacts + b.drift)).abs() < 1e-12);
    assert!(contacts.abs() < 1e-9, "contacts {contacts:e} J");
    assert!(
        b.drift <= 0.0 && b.drift > 0.05 * b.change,
        "drift {}",
        b.drift
    );
}

/// Pole (2 kg, spun about z and y, thrown up) + flag falling together without drag or
/// ground, stepped with `dt` for 1 s: the worst |P − P₀ − (M + m) g⃗ t|, the worst change of
/// the angular momentum about the common barycentre, its size, and the worst attach error.
fn falling_pole(dt: f64) -> (f64, f64, f64, f64) {
    let source = flag(
        "mass = 2.0\nangular_velocity = [0.0, 1.0, 2.0]\nvelocity = [0.5, 1.0, 0.0]",
        0.0,
        "",
    )
    .replace("dt = 0.001", &format!("dt = {dt}"));
    let mut w = world(&source);
    let total = 2.3;
    let p0 = total_momentum(&w);
    let spin = |w: &World| {
        let c = &w.cloths()[0];
        let s = &w.states()[0];
        let x_g =
            (s.position * 2.0 + c.positions.iter().sum::<Vector3<f64>>() * (0.3 / 77.0)) / total;
        let v_g = total_momentum(w) / total;
        let flag: Vector3<f64> = (c.positions.iter().zip(&c.velocities))
            .map(|(x, v)| (x - x_g).cross(&((v - v_g) * (0.3 / 77.0))))
            .sum();
        flag + s.angular_momentum + (s.position - x_g).cross(&(s.linear_momentum - v_g * 2.0))
    };
    let l0 = spin(&w);
    let (mut worst_p, mut worst_l, mut worst_attach) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..(1.0 / dt).round() as usize {
        step(&mut w);
        let expected = p0 + Vector3::new(0.0, -G, 0.0) * total * w.time();
        worst_p = worst_p.max((total_momentum(&w) - expected).norm());
        worst_l = worst_l.max((spin(&w) - l0).norm());
        worst_attach = worst_attach.max(w.attach_error(0));
    }
    // The ledger closes: no drag declared, so E − E₀ = springs' damping + contacts + drift;
    // the attachments do no work (contacts 0) and nothing makes energy (drift ≤ 0).
    let b = w.energy_balance();
    let (damping, contacts) = (b.drag_work.unwrap_or(0.0), b.contacts.unwrap_or(0.0));
    eprintln!(
        "dt {dt}: E − E₀ {:.6} J = springs' damping {damping:.6} + contacts {contacts:e} + \
         drift {:.6}",
        b.change, b.drift
    );
    assert!((b.change - (damping + contacts + b.drift)).abs() < 1e-12);
    assert!(contacts.abs() < 1e-12, "contacts {contacts:e}");
    assert!(damping <= 0.0 && b.drift <= 0.0, "{damping} {}", b.drift);
    (worst_p, worst_l, l0.norm(), worst_attach)
}

#[test]
fn a_flag_on_a_falling_pole_keeps_the_momentum_of_pole_and_flag() {
    // Gravity is the only outside force, so P(t) = P₀ + (M + m) g⃗ t exactly, and the angular
    // momentum about the common barycentre is constant (uniform gravity has no torque about it).
    let (worst_p, worst_l, l0, worst_attach) = falling_pole(0.001);
    let (_, half_l, _, _) = falling_pole(0.0005);
    eprintln!(
        "falling pole over 1 s: |P − P₀ − (M+m) g t| ≤ {worst_p:e} kg·m/s, |L_G − L_G₀| ≤ \
         {worst_l:e} kg·m²/s at 1 ms, {half_l:e} at 0.5 ms (|L_G₀| = {l0:.4}), attach error ≤ \
         {worst_attach:e} m"
    );
    assert!(worst_p < 1e-11, "momentum off by {worst_p:e}");
    assert!(worst_attach < 1e-9, "attach error {worst_attach:e}");
    // The impulses between pole and flag are equal and opposite at the attachment's point,
    // so what changes L_G is the step itself: backward Euler moves positions with the end
    // velocities (ΔL = −h² Σ v × F per step), first order in h: halving dt halves it.
    assert!(worst_l < 0.01 * l0, "|ΔL_G| {worst_l:e}");
    let order = worst_l / half_l;
    assert!((1.6..2.4).contains(&order), "ΔL_G(h)/ΔL_G(h/2) = {order}");
}

/// The ledger's rows now: drag, contacts, the joints' correction, drift (J).
/// A hinge holding the pole at the wall, (0, 2, 0), about `axis`.
fn wall_hinge(axis: [f64; 3]) -> String {
    format!(
        r#"
[[joint]]
name = "hinge"
type = "hinge"
bodies = ["pole"]
anchor = [0.0, 2.0, 0.0]
axis = {axis:?}
"#
    )
}

fn ledger_rows(w: &World) -> [f64; 4] {
    let b = w.energy_balance();
    [
        b.drag_work.unwrap_or(0.0),
        b.contacts.unwrap_or(0.0),
        w.energy_ledger().joint_correction,
        b.drift,
    ]
}

#[test]
fn a_flag_on_a_hinged_pole_hangs_and_the_hinge_carries_pole_and_flag() {
    // The pole turns about its own axis on a hinge at the wall: the flag swings down, turning
    // the pole, and hangs; the hinge then carries (M + m) g = (2 + 0.3) 9.81 = 22.563 N.
    let mut w = world(&flag("mass = 2.0", 1.0, &wall_hinge([1.0, 0.0, 0.0])));
    let mut worst = 0.0_f64;
    for _ in 0..7000 {
        step(&mut w);
        worst = worst.max(w.attach_error(0));
    }
    // The last second, at rest: the pole must not move after any step, and no ledger row
    // may move (an ideal hinge does no work; the flag hangs still).
    let start = ledger_rows(&w);
    let mut fastest = 0.0_f64;
    for _ in 0..1000 {
        step(&mut w);
        worst = worst.max(w.attach_error(0));
        let omega = w.kinematics_of(0).angular_velocity.norm();
        let speed = w.states()[0].linear_momentum.norm() / 2.0;
        fastest = fastest.max(omega).max(speed);
    }
    let end = ledger_rows(&w);
    let [force, moment_origin] = w.cloth_attach_load(0);
    let load = w.joint_load(0);
    let hinge = load.force;
    eprintln!(
        "hinged pole at 8 s: attachments {force:?} N, hinge {hinge:?} N ((M + m) g = 22.563), \
         attach error ≤ {worst:e} m, pole |ω|, |v| ≤ {fastest:e} over the last second; rows \
         drag, contacts, joint correction, drift moved {:?} J in it",
        [0, 1, 2, 3].map(|k| end[k] - start[k])
    );
    assert!(
        (force - Vector3::new(0.0, 0.3 * G, 0.0)).norm() < 1e-5,
        "{force:?}"
    );
    assert!(worst < 1e-9, "attach error {worst:e}");
    // The hinge is held inside the cloth's solve (`cloth::ties`, "Joints on the bodies"): it
    // carries pole and flag within the step (measured 4.4e-6 N sideways, 2e-7 of the load, as
    // the fixed pole's attachments: the flag still sways at 2e-6 m/s).
    assert!(
        (hinge - Vector3::new(0.0, 2.3 * G, 0.0)).norm() < 1e-6 * 2.3 * G,
        "{hinge:?}"
    );
    // Its torque about the pole's barycenter c balances the flag's pull on the pole there:
    // the pole takes −F at the attachments, whose moment about c is −(M_O − c × F); its own
    // weight has none. By hand: (0, 0, (x_G − c_x) m g) = (0, 0, 0.2 × 2.943) N·m.
    let c = w.states()[0].position;
    let balance = moment_origin - c.cross(&force);
    eprintln!(
        "hinge torque {:?} N·m, flag's pull about c {balance:?}",
        load.torque
    );
    assert!((load.torque - balance).norm() < 1e-5, "{:?}", load.torque);
    assert!(
        (load.torque.z - 0.2 * 0.3 * G).abs() < 2e-3,
        "{:?}",
        load.torque
    );
    // At rest nothing moves: the pole after every step, and every ledger row (J over 1 s).
    assert!(fastest < 1e-6, "pole |ω| or |v| {fastest:e}");
    for k in 0..4 {
        assert!(
            (end[k] - start[k]).abs() < 1e-6,
            "row {k} moved {:e} J in the last second",
            end[k] - start[k]
        );
    }
}

#[test]
fn an_explicit_flag_on_a_hinged_pole_keeps_the_hinge_for_every_body_integrator() {
    // The hinged pole above with a symplectic-euler flag (dt = 0.2 ms, inside its explicit
    // limit): its attachments are held by impulses after the velocity half
    // (`hold_attachments`), with the pole's response filtered by the hinge's rows, for the
    // pole stepped by each body integrator (position factors 1, ½ and 0). Before the filter
    // the pull moved the pole off its hinge by the step's correction: 1.1e-4 m (symplectic
    // Euler), 5.4e-5 m (rk4) at every step, and the hinge read the load a step late.
    for integrator in ["symplectic-euler", "rk4", "euler"] {
        let source = flag("mass = 2.0", 1.0, &wall_hinge([1.0, 0.0, 0.0]))
            .replace("dt = 0.001", "dt = 0.0002")
            .replace(
                "integrator = \"symplectic-euler\"",
                &format!("integrator = \"{integrator}\""),
            )
            .replace(
                "integrator = \"implicit-euler\"",
                "integrator = \"symplectic-euler\"",
            );
        let mut w = world(&source);
        let (mut worst_joint, mut worst_attach) = (0.0_f64, 0.0_f64);
        for _ in 0..35_000 {
            step(&mut w);
            worst_joint = worst_joint.max(w.links().joints[0].error(w.states()));
            worst_attach = worst_attach.max(w.attach_error(0));
        }
        // The last second, at rest: no ledger row moves (an ideal hinge does no work).
        let start = ledger_rows(&w);
        for _ in 0..5_000 {
            step(&mut w);
            worst_joint = worst_joint.max(w.links().joints[0].error(w.states()));
        }
        let end = ledger_rows(&w);
        let hinge = w.joint_load(0).force;
        eprintln!(
            "{integrator} pole, explicit flag, 8 s: hinge error ≤ {worst_joint:e} m, attach \
             error ≤ {worst_attach:e} m, hinge {hinge:?} N ((M + m) g = 22.563); rows drag, \
             contacts, joint correction, drift moved {:?} J in the last second",
            [0, 1, 2, 3].map(|k| end[k] - start[k])
        );
        assert!(
            worst_joint < 1e-9,
            "{integrator}: hinge error {worst_joint:e}"
        );
        assert!(
            worst_attach < 1e-9,
            "{integrator}: attach error {worst_attach:e}"
        );
        assert!(
            (hinge - Vector3::new(0.0, 2.3 * G, 0.0)).norm() < 1e-4 * 2.3 * G,
            "{integrator}: {hinge:?}"
        );
        for k in 0..4 {
            assert!(
                (end[k] - start[k]).abs() < 1e-6,
                "{integrator}: row {k} moved {:e} J in the last second",
                end[k] - start[k]
            );
        }
    }
}

#[test]
fn a_pole_swinging_down_on_a_hinge_with_its_flag_keeps_its_hinge_and_reports_its_reaction() {
    // The pole turns about z at the wall: it falls from level and swings like a pendulum,
    // carrying the flag (no drag: the springs' damping is the only loss). The hinge is held
    // inside the flag's solve: its point never moves, and what it reports is the reaction the
    // pole took in each step — the pole's momentum changes by h (M g⃗ + F_hinge − F_flag),
    // F_flag the force the attachments gave the flag (without the flag: to 1.7e-15 kg·m/s).
    let mut w = world(&flag("mass = 2.0", 0.0, &wall_hinge([0.0, 0.0, 1.0])));
    let (mut worst_joint, mut worst_attach, mut lowest) = (0.0_f64, 0.0_f64, f64::INFINITY);
    let mut worst_balance = 0.0_f64;
    let h = w.dt();
    for _ in 0..2000 {
        let before = w.states()[0].linear_momentum;
        step(&mut w);
        let change = w.states()[0].linear_momentum - before;
        let [flag, _] = w.cloth_attach_load(0);
        let expected = (Vector3::new(0.0, -2.0 * G, 0.0) + w.joint_load(0).force - flag) * h;
        worst_balance = worst_balance.max((change - expected).norm());
        worst_joint = worst_joint.max(w.links().joints[0].error(w.states()));
        worst_attach = worst_attach.max(w.attach_error(0));
        lowest = lowest.min(w.states()[0].position.y);
    }
    let [damping, contacts, correction, drift] = ledger_rows(&w);
    let b = w.energy_balance();
    eprintln!(
        "swinging pole over 2 s: lowest barycentre {lowest:.4} m, hinge error ≤ {worst_joint:e} \
         m, attach error ≤ {worst_attach:e} m, |ΔP − h(M g + F_hinge − F_flag)| ≤ \
         {worst_balance:e} kg·m/s; E − E₀ {:.6} J = damping {damping:.6} + contacts \
         {contacts:e} + drift {drift:.6} (joint correction {correction:e})",
        b.change
    );
    // It swings: the barycentre (0.8 m out) passes well below the hinge.
    assert!(lowest < 2.0 - 0.7, "lowest {lowest}");
    assert!(worst_joint < 1e-9, "hinge error {worst_joint:e}");
    assert!(worst_attach < 1e-9, "attach error {worst_attach:e}");
    assert!((b.change - (damping + contacts + drift)).abs() < 1e-12);
    assert!(contacts.abs() < 1e-9, "contacts {contacts:e}");
    // To the solve's tolerance: the hinge's impulse is read from the bodies' rows as the
    // ties' from the particles' (`cloth::ties`), and a solve stopped at a relative residual of
    // 1e-3 leaves in them up to 1e-3 of the step's impulses (the flag's pull, m g h = 2.9e-3
    // N·s at rest, a few times that in the swing); measured 2.1e-6 kg·m/s.
    assert!(
        worst_balance < 1e-5,
        "pole's momentum balance off by {worst_balance:e}"
    );
}

/// A trampoline whose frame is a body: the 21 × 21 sheet of lesson 16 (2 m, 2 kg, k = 5000,
/// shear 1000, c = 50) with its rim (`edge = "all"`, 80 particles) attached 0.55 m above a
/// 40 kg slab resting on the ground, and lesson 16's cube dropped from 0.5 m above the sheet.
const FLOOR_TRAMPOLINE: &str = r#"
title = "A trampoline on the floor"
[scene]
dt = 0.001
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.4, friction = 0.5 }

[[obstacle]]
type = "ground"
height = 0.0

[[body]]
name = "frame"
shape = "box"
size = [2.4, 0.1, 2.4]
mass = 40.0
position = [0.0, 0.05, 0.0]

[[body]]
name = "cube"
shape = "box"
size = [0.35, 0.35, 0.35]
mass = 1.0
position = [0.0, 1.1, 0.0]

[[cloth]]
name = "trampoline"
size = [2.0, 2.0]
count = [21, 21]
position = [0.0, 0.6, 0.0]
mass = 2.0
stretch = 5000.0
shear = 1000.0
damping = 50.0
attach = [{ edge = "all", body = "frame" }]
integrator = "implicit-euler"
"#;

/// The ground's impulses on the bodies in the last step, N·s.
fn ground_impulse(w: &World) -> Vector3<f64> {
    w.contacts()
        .iter()
        .filter(|c| matches!(c.against, Against::Obstacle(_)))
        .map(|c| c.impulse)
        .sum()
}

#[test]
fn a_trampoline_whose_frame_rests_on_the_floor_holds_the_cube_at_the_fixed_rim_statics() {
    let mut w = world(FLOOR_TRAMPOLINE);
    assert_eq!(
        w.cloths()[0].attached.len(),
        80,
        "the rim of a 21 × 21 sheet"
    );
    let total = 40.0 + 2.0 + 1.0;
    let p0 = total_momentum(&w);
    let mut ground = Vector3::zeros();
    let mut worst_p = 0.0_f64;
    let mut worst_attach = 0.0_f64;
    let mut landed = None;
    for _ in 0..6000 {
        step(&mut w);
        ground += ground_impulse(&w);
        // Momentum: gravity and the ground are the only outside forces.
        let expected = p0 + Vector3::new(0.0, -G, 0.0) * total * w.time() + ground;
        worst_p = worst_p.max((total_momentum(&w) - expected).norm());
        worst_attach = worst_attach.max(w.attach_error(0));
        if landed.is_none() && w.cloth_body_contacts(0) > 0 {
            landed = Some(w.time());
        }
    }
    eprintln!(
        "floor trampoline: cube lands at {landed:?} s; |P − P₀ − M g t − J_ground| ≤ \
         {worst_p:e} kg·m/s; attach error ≤ {worst_attach:e} m"
    );
    assert!(worst_p < 1e-9, "momentum off by {worst_p:e}");
    // The attached particles end every step on their points, also while the floor's contact
    // moves the frame after the sheet's step (`cloth_coupling::carry_attachments`).
    assert!(worst_attach < 1e-9, "attach error {worst_attach:e}");
    // The cube lands when its bottom (0.325 m up) meets the sheet, sagging under its own
    // weight: √(2 × 0.325/g) = 0.257 s before the sag; lesson 16: 0.272 s.
    let landed = landed.expect("the cube lands");
    assert!((landed - 0.272).abs() < 0.002, "landed at {landed}");
    // At rest the ground carries everything: its force over the last step (impulse / dt)
    // is (M_frame + m_sheet + M_cube) g = 43 × 9.81 = 421.83 N.
    let support = ground_impulse(&w) / w.dt();
    eprintln!("ground carries {support:?} N (43 g = 421.83 N)");
    assert!(
        (support - Vector3::new(0.0, total * G, 0.0)).norm() < 0.05,
        "{support:?}"
    );
    // The frame's attachments carry the sheet and the cube: (2 + 1) g = 29.43 N.
    let [rim, _] = w.cloth_attach_load(0);
    eprintln!("the rim carries {rim:?} N (3 g = 29.43 N)");
    assert!(
        (rim - Vector3::new(0.0, 3.0 * G, 0.0)).norm() < 0.02,
        "{rim:?}"
    );
    // The cube's bottom below the rim against the fixed-rim statics of the same network
    // (lesson 16's Newton solve, `tests/commands/lesson_claims.rs`: −0.116231 m): the rim
    // is where the frame holds it now.
    let frame = &w.states()[0];
    let cube = &w.states()[1];
    let c = &w.cloths()[0];
    let rim_height = c.positions[c.index(0, 10)].y;
    let bottom = cube.position.y - 0.175 - rim_height;
    eprintln!(
        "cube bottom {bottom:.6} m below the rim (statics −0.116231); frame at {:.9} m, cube \
         |v| {:e} m/s",
        frame.position.y,
        cube.linear_momentum.norm()
    );
    assert!((bottom + 0.116231).abs() < 1e-4, "bottom {bottom}");
    assert!(cube.linear_momentum.norm() < 1e-4);
    // The frame sags into the ground within each step: rk4 moves it down by ½ a h² under
    // a = g + (rim load)/M = 9.81 + 29.43/40 = 10.546 m/s² (5.27e-6 m), the collide phase
    // pushes it back after the sheet's step. The rim aims at where the frame ends (its last
    // move, `cloth_coupling::tied_step`), so at rest it stays still: the frame ends every
    // step where it started, at rest, and the springs' damping (the drag row) books nothing.
    assert!(
        (frame.position.y - 0.05).abs() < 1e-6,
        "frame at {}",
        frame.position.y
    );
    let frame_speed = frame.linear_momentum.norm() / 40.0;
    assert!(frame_speed < 1e-9, "frame |v| {frame_speed:e}");
    let damping = |w: &World| w.energy_balance().drag_work.unwrap_or(0.0);
    let before = damping(&w);
    for _ in 0..500 {
        step(&mut w);
    }
    let moved = damping(&w) - before;
    eprintln!("the springs' damping over 0.5 s at rest: {moved:e} J");
    assert!(moved.abs() < 1e-6, "damping {moved:e} J");
    assert!(w.attach_error(0) < 1e-9, "{:e}", w.attach_error(0));
}

#[test]
fn a_tilted_frame_dropped_on_the_floor_keeps_its_rim_on_its_points_while_it_lands() {
    // The floor trampoline's frame dropped 5 cm, tilted 1° about an axis in the floor, and
    // spinning a little: it lands on one corner, then an edge, then its face, and the collide
    // phase turns it as well as lifting it. Each rim particle still ends every step on its
    // point, and momentum changes only by gravity and the floor's impulses (the particles'
    // share counted in them).
    let source = FLOOR_TRAMPOLINE
        .replace(
            "position = [0.0, 0.05, 0.0]",
            "position = [0.0, 0.1, 0.0]\norientation = { axis = [0.8, 0.0, 1.0], degrees = 1.0 }\nangular_velocity = [0.0, 0.3, 0.0]",
        )
        .replace("position = [0.0, 0.6, 0.0]", "position = [0.0, 0.65, 0.0]")
        .replace("position = [0.0, 1.1, 0.0]", "position = [0.0, 1.15, 0.0]");
    let mut w = world(&source);
    let total = 43.0;
    let p0 = total_momentum(&w);
    let (mut ground, mut worst_p, mut worst_attach) = (Vector3::zeros(), 0.0_f64, 0.0_f64);
    let mut turned = 0.0_f64;
    for _ in 0..1000 {
        let before = w.states()[0].orientation.matrix();
        step(&mut w);
        ground += ground_impulse(&w);
        let expected = p0 + Vector3::new(0.0, -G, 0.0) * total * w.time() + ground;
        worst_p = worst_p.max((total_momentum(&w) - expected).norm());
        worst_attach = worst_attach.max(w.attach_error(0));
        let turn = w.states()[0].orientation.matrix() * before.transpose();
        turned = turned.max((turn - nalgebra::Matrix3::identity()).norm());
    }
    let b = w.energy_balance();
    eprintln!(
        "tilted frame over 1 s: attach error ≤ {worst_attach:e} m, |P − P₀ − M g t − J_ground| \
         ≤ {worst_p:e}, largest turn in a step {turned:e}; E − E₀ {:.6} = drag {:.6} + contacts \
         {:.6} + drift {:.6}, frame at y {:.6}",
        b.change,
        b.drag_work.unwrap_or(0.0),
        b.contacts.unwrap_or(0.0),
        b.drift,
        w.states()[0].position.y
    );
    assert!(
        turned > 1e-4,
        "the frame turns: {turned:e} per step at most"
    );
    assert!(worst_attach < 1e-9, "attach error {worst_attach:e}");
    assert!(worst_p < 1e-9, "momentum off by {worst_p:e}");
    // Nothing makes energy: the landing and the carrying are booked with the contacts, and
    // what is left, backward Euler's and the impacts' numerical loss, is ≤ 0.
    assert!(b.drift <= 0.0, "drift {}", b.drift);
}
