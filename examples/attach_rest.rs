//! The two attach scenes of issue 20 that rest on something other than the cloth's own solve,
//! run to rest with their numbers printed: a flag on a hinged pole (the hinge carries pole and
//! flag) and lesson 35's trampoline whose frame rests on the floor.
//!
//! ```text
//! cargo build --release --example attach_rest
//! target/release/examples/attach_rest [hinge|floor]
//! ```
//!
//! For each: the last second's rate of every ledger row (J/s: at rest each should be 0), the
//! supports' forces against their statics, the resting body's velocities and the attach error.
//! `TOLERANCE=1e-8` sets the cloths' CG tolerance (default 1e-3), to tell what the solve's
//! truncation makes from what the coupling makes.

use nalgebra::Vector3;
use std::path::Path;
use tumble::physics::{Against, World};

const G: f64 = 9.81;

/// The flag of `tests/physics/cloth_attach.rs` on a 2 kg pole hinged at the wall about x.
const HINGED_FLAG: &str = r#"
title = "A flag on a hinged pole"
[scene]
dt = 0.001
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
drag = { linear = 1.0, angular = 0.05 }
contact = { response = "impulse", restitution = 0.0, friction = 0.5 }

[[body]]
name = "pole"
shape = "box"
size = [1.6, 0.04, 0.04]
mass = 2.0
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
attach = [{ edge = "-z", body = "pole" }]

[[joint]]
name = "hinge"
type = "hinge"
bodies = ["pole"]
anchor = [0.0, 2.0, 0.0]
axis = [1.0, 0.0, 0.0]
"#;

/// The ledger's rows now: drag, contacts, joint correction, drift (J).
fn rows(w: &World) -> [f64; 4] {
    let b = w.energy_balance();
    [
        b.drag_work.unwrap_or(0.0),
        b.contacts.unwrap_or(0.0),
        w.energy_ledger().joint_correction,
        b.drift,
    ]
}

/// Steps `seconds`, then one more second, and prints the rows' rates over that second.
fn settle(w: &mut World, seconds: f64) -> [f64; 4] {
    let steps = (seconds / w.dt()).round() as usize;
    for _ in 0..steps {
        w.step();
    }
    let start = rows(w);
    let mut worst_attach = 0.0_f64;
    for _ in 0..(1.0 / w.dt()).round() as usize {
        w.step();
        worst_attach = worst_attach.max(w.attach_error(0));
    }
    let end = rows(w);
    let rate: Vec<f64> = end.iter().zip(&start).map(|(e, s)| e - s).collect();
    println!(
        "  ledger at {:.0} s: drag {:.6e}, contacts {:.6e}, joint correction {:.6e}, drift {:.6e} J",
        w.time(),
        end[0],
        end[1],
        end[2],
        end[3]
    );
    println!(
        "  rates over the last second: drag {:.3e}, contacts {:.3e}, joint correction {:.3e}, \
         drift {:.3e} J/s",
        rate[0], rate[1], rate[2], rate[3]
    );
    println!("  attach error over the last second ≤ {worst_attach:e} m");
    [rate[0], rate[1], rate[2], rate[3]]
}

/// (x, y, z) with three digits, exponent form.
fn e3(v: &Vector3<f64>) -> String {
    format!("({:.3e}, {:.3e}, {:.3e})", v.x, v.y, v.z)
}

fn world(source: &str) -> World {
    let mut scene = tumble::scene::parse(source, Path::new("attach_rest.toml"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let Some(tolerance) = std::env::var("TOLERANCE").ok().and_then(|t| t.parse().ok()) else {
        return scene.world();
    };
    let specs = std::mem::take(&mut scene.cloths);
    let cloths = specs
        .iter()
        .map(|s| {
            let mut c = tumble::physics::cloth::Cloth::new(s).expect("valid");
            c.solver.tolerance = tolerance;
            c
        })
        .collect();
    scene.world().with_cloths(cloths)
}

fn hinge() {
    println!("flag on a hinged pole (M = 2 kg, m = 0.3 kg):");
    let mut w = world(HINGED_FLAG);
    settle(&mut w, 7.0);
    let hinge = w.joint_load(0).force;
    let weight = 2.3 * G;
    let [attached, _] = w.cloth_attach_load(0);
    let s = &w.states()[0];
    let omega = w.kinematics_of(0).angular_velocity;
    println!(
        "  hinge {hinge:.9?} N against (M + m) g = {weight:.6} N: relative {:.3e}",
        (hinge - Vector3::new(0.0, weight, 0.0)).norm() / weight
    );
    println!(
        "  attachments carry {attached:.9?} N (m g = {:.6})",
        0.3 * G
    );
    let flag = &w.cloths()[0];
    println!(
        "  flag: fastest particle {:e} m/s, momentum {} kg·m/s",
        flag.max_speed(),
        e3(&flag.linear_momentum())
    );
    println!(
        "  pole ω {} rad/s, v {} m/s, joint error {:e} m",
        e3(&omega),
        e3(&(s.linear_momentum / 2.0)),
        w.links().joints[0].error(w.states())
    );
}

fn floor() {
    println!("lesson 35's trampoline on the floor (frame 40 kg, sheet 2 kg, cube 1 kg):");
    let source = std::fs::read_to_string("lessons/35-a-trampoline-on-the-floor.toml")
        .expect("run from the repository's root");
    let mut w = world(&source);
    settle(&mut w, 5.0);
    let ground: Vector3<f64> = w
        .contacts()
        .iter()
        .filter(|c| matches!(c.against, Against::Obstacle(_)))
        .map(|c| c.impulse)
        .sum::<Vector3<f64>>()
        / w.dt();
    let [rim, _] = w.cloth_attach_load(0);
    let frame = &w.states()[0];
    let cube = &w.states()[1];
    println!("  ground carries {ground:.6?} N (43 g = {:.4})", 43.0 * G);
    println!("  rim carries {rim:.6?} N (3 g = {:.4})", 3.0 * G);
    println!(
        "  frame y {:.9} m, v {} m/s; cube v {} m/s; attach error now {:e} m",
        frame.position.y,
        e3(&(frame.linear_momentum / 40.0)),
        e3(&cube.linear_momentum),
        w.attach_error(0)
    );
}

fn main() {
    let which = std::env::args().nth(1);
    if which.as_deref() != Some("floor") {
        hinge();
    }
    if which.as_deref() != Some("hinge") {
        floor();
    }
}
