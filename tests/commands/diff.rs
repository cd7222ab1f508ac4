//! `tumble diff FILE THEIRS.csv`: a student's own loop against tumble's.
//!
//! The student's loops below are written here, independently of tumble's code: plain `f64`
//! arrays, the report's loop as its text gives it (CalculStateX, CalculDeriveeStateX, Solve,
//! then the ground collision), printed as CSV. The correct loop must agree with tumble's run at
//! 1e-9 over 500 steps; each known mistake planted alone must part at the step where it first
//! shows, in the right quantity and phase, and be named; a mistake off the list is unknown.

// Index loops read like the formulas they write (cᵢⱼ = Σₖ aᵢₖ bₖⱼ).
#![allow(clippy::needless_range_loop)]

use assert_cmd::Command;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

type V = [f64; 3];
type M = [[f64; 3]; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn sub(a: V, b: V) -> V {
    add(a, scale(b, -1.0))
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn mat_vec(m: M, v: V) -> V {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}
fn mat_mul(a: M, b: M) -> M {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}
fn transpose(a: M) -> M {
    let mut t = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            t[i][j] = a[j][i];
        }
    }
    t
}
fn mat_add(a: M, b: M, s: f64) -> M {
    let mut c = a;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] += s * b[i][j];
        }
    }
    c
}
/// The inverse by the adjugate.
fn inverse(m: M) -> M {
    let c = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    let mut inv = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            inv[j][i] = c(i, j) / det;
        }
    }
    inv
}
/// The report's StarMatrix: ω* v = ω × v.
fn star(w: V) -> M {
    [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]]
}
const IDENTITY: M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// A rigid body of mass points: `_ROi` about the barycenter, `_Mass`, `_Ibody`.
struct Body {
    mass: f64,
    points: Vec<V>,
    ibody: M,
}

/// The hammer of lessons 2 and 4: five points of unequal mass (Σ rᵢ ≠ 0).
fn hammer() -> Body {
    let points = [
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [0.5, 0.15, 0.0],
        [0.5, -0.15, 0.0],
        [0.25, 0.0, 0.05],
    ];
    let masses = [0.1, 0.1, 0.3, 0.3, 0.2];
    let mass: f64 = masses.iter().sum();
    let mut center = [0.0; 3];
    for (p, m) in points.iter().zip(masses) {
        center = add(center, scale(*p, m / mass));
    }
    let points: Vec<V> = points.iter().map(|p| sub(*p, center)).collect();
    let mut ibody = [[0.0; 3]; 3];
    for (r, m) in points.iter().zip(masses) {
        for i in 0..3 {
            for j in 0..3 {
                let delta = if i == j { dot(*r, *r) } else { 0.0 };
                ibody[i][j] += m * (delta - r[i] * r[j]);
            }
        }
    }
    Body {
        mass,
        points,
        ibody,
    }
}

/// A solid box (its 8 corners for the collisions, in binary order: bit 0 x, bit 1 y, bit 2 z).
fn solid_box(size: V, mass: f64) -> Body {
    let [a, b, c] = size;
    let points = (0..8)
        .map(|i| {
            let s = |bit: usize| if i & (1 << bit) != 0 { 0.5 } else { -0.5 };
            [s(0) * a, s(1) * b, s(2) * c]
        })
        .collect();
    let k = mass / 12.0;
    Body {
        mass,
        points,
        ibody: [
            [k * (b * b + c * c), 0.0, 0.0],
            [0.0, k * (a * a + c * c), 0.0],
            [0.0, 0.0, k * (a * a + b * b)],
        ],
    }
}

const HAMMER_SCENE: &str = r#"title = "diff: the hammer"
[scene]
dt = 0.001
integrator = "euler-seed"
gravity = [0.0, -9.81, 0.0]
[body]
shape = "points"
points = [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.5, 0.15, 0.0], [0.5, -0.15, 0.0], [0.25, 0.0, 0.05]]
masses = [0.1, 0.1, 0.3, 0.3, 0.2]
inertia = "points"
position = [0.003, 2.0, 0.001]
velocity = [0.0, 3.0, 0.0]
angular_velocity = [1.0, 2.0, 4.0]
"#;
/// The hammer's x, v, ω at t = 0.
/// Thrown straight up from nearly above the origin: the torque about the origin, N x × F, stays
/// small enough that the loop with it planted does not blow up within 500 steps.
const HAMMER: (V, V, V) = ([0.003, 2.0, 0.001], [0.0, 3.0, 0.0], [1.0, 2.0, 4.0]);

const BOX_SCENE: &str = r#"title = "diff: a box dropped with seed"
[scene]
dt = 0.001
integrator = "euler-seed"
gravity = [0.0, -9.81, 0.0]
contact = { response = "seed", restitution = 0.4, friction = 0.5 }
[body]
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
inertia = "solid"
position = [0.0, 0.2, 0.0]
velocity = [0.0, 0.0, 0.0]
angular_velocity = [1.0, 2.0, 0.5]
[[obstacle]]
type = "ground"
height = 0.0
"#;

const G: V = [0.0, -9.81, 0.0];
const DT: f64 = 0.001;
const STEPS: usize = 500;
/// The seed box: it touches near step 125 and the report's kicks spin it past what any step
/// resolves near step 163 (tumble stops there): 150 steps.
const BOX_STEPS: usize = 150;
const BOX_X: V = [0.0, 0.2, 0.0];
const BOX_V: V = [0.0, 0.0, 0.0];
const BOX_W: V = [1.0, 2.0, 0.5];

/// The mistakes a student's loop can have planted (all false: the report's loop).
#[derive(Clone, Copy, Default)]
struct Plant {
    torque_about_origin: bool,
    no_vertex_torque: bool,
    omega_from_body: bool,
    new_velocity_for_x: bool,
    gram_schmidt: bool,
    gravity_on_every_point: bool,
    /// 0: none (the scene's dt).
    dt_factor: f64,
    /// Off the list: a drag nobody declared, P ← 0.999 P.
    hidden_drag: bool,
    /// Off the list, in the collision: P ← −0.5 P instead of −0.4 P.
    bounce_half: bool,
}

/// One printed row: step, t, x, R (rows), v, ω, L.
struct Row {
    step: usize,
    t: f64,
    x: V,
    r: M,
    q: [f64; 4],
    v: V,
    w: V,
    l: V,
}

/// The report's loop (euler-seed) with the seed ground collision when `ground`, as a student
/// writes it. Returns the rows and the first step a vertex touched the ground.
fn report_loop(
    body: &Body,
    (x0, v0, w0): (V, V, V),
    ground: bool,
    plant: Plant,
) -> (Vec<Row>, Option<usize>) {
    let steps = if ground { BOX_STEPS } else { STEPS };
    let dt = if plant.dt_factor > 0.0 {
        DT * plant.dt_factor
    } else {
        DT
    };
    let ibody_inv = inverse(body.ibody);
    let mut x = x0;
    let mut r = IDENTITY;
    let mut p = scale(v0, body.mass);
    let mut l = mat_vec(body.ibody, w0);
    let mut rows = Vec::new();
    let mut touched = None;
    let derive = |r: M, l: V, p: V| {
        let inv = if plant.omega_from_body {
            ibody_inv
        } else {
            mat_mul(mat_mul(r, ibody_inv), transpose(r))
        };
        (mat_vec(inv, l), scale(p, 1.0 / body.mass))
    };
    for step in 0..=steps {
        if step > 0 {
            // CalculStateX
            let (w, v) = derive(r, l, p);
            // CalculDeriveeStateX
            let r_dot = mat_mul(star(w), r);
            let points = body.points.len() as f64;
            let force = if plant.gravity_on_every_point {
                scale(G, body.mass * points)
            } else {
                scale(G, body.mass)
            };
            let mut torque = [0.0; 3];
            if !plant.no_vertex_torque {
                for r0 in &body.points {
                    let ri = mat_vec(r, *r0);
                    let lever = if plant.torque_about_origin {
                        add(ri, x)
                    } else {
                        ri
                    };
                    torque = add(torque, cross(lever, force));
                }
            }
            // Solve
            if plant.new_velocity_for_x {
                p = add(p, scale(force, dt));
                x = add(x, scale(p, dt / body.mass));
            } else {
                x = add(x, scale(v, dt));
                p = add(p, scale(force, dt));
            }
            r = mat_add(r, r_dot, dt);
            if plant.gram_schmidt {
                r = gram_schmidt(r);
            }
            l = add(l, scale(torque, dt));
            if plant.hidden_drag {
                p = scale(p, 0.999);
            }
            if ground {
                // The report's ground test: the deepest vertex below y = 0.
                let mut deepest: Option<(usize, f64)> = None;
                for (i, r0) in body.points.iter().enumerate() {
                    let pi = add(x, mat_vec(r, *r0));
                    if pi[1] < 0.0 {
                        let d = -pi[1];
                        if deepest.is_none_or(|(_, best)| d > best) {
                            deepest = Some((i, d));
                        }
                    }
                }
                if let Some((i, d)) = deepest {
                    touched.get_or_insert(step);
                    let pk = add(x, mat_vec(r, body.points[i]));
                    x[1] += d * d;
                    l = add(cross(sub(pk, x0), scale(force, -1.0)), l);
                    p = scale(p, if plant.bounce_half { -0.5 } else { -0.4 });
                }
            }
        }
        let (w, v) = derive(r, l, p);
        rows.push(Row {
            step,
            t: step as f64 * dt,
            x,
            r,
            q: [f64::NAN; 4],
            v,
            w,
            l,
        });
    }
    (rows, touched)
}

/// Gram–Schmidt on the columns of R.
fn gram_schmidt(r: M) -> M {
    let t = transpose(r);
    let c0 = scale(t[0], 1.0 / dot(t[0], t[0]).sqrt());
    let c1 = sub(t[1], scale(c0, dot(c0, t[1])));
    let c1 = scale(c1, 1.0 / dot(c1, c1).sqrt());
    let c2 = cross(c0, c1);
    transpose([c0, c1, c2])
}

/// Explicit Euler with a unit quaternion (`euler`): no vertex torque, q normalised.
fn quaternion_loop(body: &Body, (x0, v0, w0): (V, V, V)) -> Vec<Row> {
    let ibody_inv = inverse(body.ibody);
    let (mut x, mut q, mut p) = (x0, [1.0, 0.0, 0.0, 0.0], scale(v0, body.mass));
    let l = mat_vec(body.ibody, w0);
    let rotation = |q: [f64; 4]| {
        let [w, a, b, c] = q;
        [
            [
                1.0 - 2.0 * (b * b + c * c),
                2.0 * (a * b - w * c),
                2.0 * (a * c + w * b),
            ],
            [
                2.0 * (a * b + w * c),
                1.0 - 2.0 * (a * a + c * c),
                2.0 * (b * c - w * a),
            ],
            [
                2.0 * (a * c - w * b),
                2.0 * (b * c + w * a),
                1.0 - 2.0 * (a * a + b * b),
            ],
        ]
    };
    let derive = |q: [f64; 4], l: V, p: V| {
        let r = rotation(q);
        let inv = mat_mul(mat_mul(r, ibody_inv), transpose(r));
        (mat_vec(inv, l), scale(p, 1.0 / body.mass))
    };
    let mut rows = Vec::new();
    for step in 0..=STEPS {
        if step > 0 {
            let (w, v) = derive(q, l, p);
            x = add(x, scale(v, DT));
            // q̇ = ½ (0, ω) ⊗ q
            let qv = [q[1], q[2], q[3]];
            let rate_w = -0.5 * dot(w, qv);
            let rate_v = scale(add(scale(w, q[0]), cross(w, qv)), 0.5);
            let next = [
                q[0] + DT * rate_w,
                q[1] + DT * rate_v[0],
                q[2] + DT * rate_v[1],
                q[3] + DT * rate_v[2],
            ];
            let norm = next.iter().map(|c| c * c).sum::<f64>().sqrt();
            q = next.map(|c| c / norm);
            p = add(p, scale(G, body.mass * DT));
        }
        let (w, v) = derive(q, l, p);
        rows.push(Row {
            step,
            t: step as f64 * DT,
            x,
            r: rotation(q),
            q,
            v,
            w,
            l,
        });
    }
    rows
}

/// How the rotation is printed.
#[derive(Clone, Copy, PartialEq)]
enum Print {
    Matrix,
    Quaternion,
    /// The report's member names, C++ indices.
    ReportNames,
}

fn csv(rows: &[Row], print: Print) -> String {
    let mut out = String::new();
    match print {
        Print::Matrix => out.push_str(
            "step,t,x,y,z,R11,R12,R13,R21,R22,R23,R31,R32,R33,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz\n",
        ),
        Print::Quaternion => out.push_str("step,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz\n"),
        Print::ReportNames => {
            out.push_str("step,_Position.x,_Position.y,_Position.z");
            for i in 0..3 {
                for j in 0..3 {
                    let _ = write!(out, ",_Rotation[{i}][{j}]");
                }
            }
            for member in ["_Vitesse", "_VitesseAngulaire", "_MomentCinetique"] {
                for a in ["x", "y", "z"] {
                    let _ = write!(out, ",{member}.{a}");
                }
            }
            out.push('\n');
        }
    }
    for row in rows {
        let _ = write!(out, "{}", row.step);
        if print != Print::ReportNames {
            let _ = write!(out, ",{}", row.t);
        }
        let mut numbers: Vec<f64> = row.x.to_vec();
        if print == Print::Quaternion {
            numbers.extend(row.q);
        } else {
            numbers.extend(row.r.iter().flatten());
        }
        numbers.extend(row.v.iter().chain(&row.w).chain(&row.l));
        for n in numbers {
            let _ = write!(out, ",{n}");
        }
        out.push('\n');
    }
    out
}

/// A fresh folder for one test's files.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tumble-diff-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `tumble diff SCENE THEIRS --tolerance 1e-9 [extra]`: (exit code, stdout, stderr).
fn diff(scene: &Path, theirs: &Path, extra: &[&str]) -> (i32, String, String) {
    let out = Command::cargo_bin("tumble")
        .unwrap()
        .arg("diff")
        .arg(scene)
        .arg(theirs)
        .args(["--tolerance", "1e-9"])
        .args(extra)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// The per-quantity line of a report: (column, step) where `quantity` first parts.
fn first_parting(report: &str, quantity: &str) -> Option<(String, u64)> {
    let line = report
        .lines()
        .find(|l| l.starts_with(&format!("  {quantity} ")))?;
    let rest: Vec<&str> = line[2 + quantity.len()..].split_whitespace().collect();
    if rest.first() == Some(&"agrees") {
        return None;
    }
    Some((rest[0].to_string(), rest[1].parse().ok()?))
}

#[test]
fn the_reports_loop_agrees_at_1e_9_over_500_steps_with_the_rotation_given_either_way() {
    let dir = folder("correct");
    let body = hammer();
    // euler-seed, R printed as a matrix (and with the report's own member names).
    let scene = write(&dir, "hammer.toml", HAMMER_SCENE);
    let (rows, _) = report_loop(&body, HAMMER, false, Plant::default());
    for print in [Print::Matrix, Print::ReportNames] {
        let theirs = write(&dir, "theirs.csv", &csv(&rows, print));
        let (code, out, err) = diff(&scene, &theirs, &[]);
        assert_eq!(code, 0, "{out}{err}");
        assert!(out.contains("They agree"), "{out}");
        assert!(out.contains("501 rows (steps 0 to 500)"), "{out}");
    }
    // euler (a quaternion), q printed.
    let rows = quaternion_loop(&body, HAMMER);
    let theirs = write(&dir, "theirs-q.csv", &csv(&rows, Print::Quaternion));
    let (code, out, err) = diff(&scene, &theirs, &["--integrator", "euler"]);
    assert_eq!(code, 0, "{out}{err}");
    // The same with −q on every other row: one rotation.
    let flipped: String = csv(&rows, Print::Quaternion)
        .lines()
        .enumerate()
        .map(|(i, line)| {
            if i % 2 == 1 {
                let mut cells: Vec<String> = line.split(',').map(String::from).collect();
                for c in &mut cells[5..9] {
                    *c = (-c.parse::<f64>().unwrap()).to_string();
                }
                cells.join(",") + "\n"
            } else {
                format!("{line}\n")
            }
        })
        .collect();
    let theirs = write(&dir, "theirs-minus-q.csv", &flipped);
    let (code, out, err) = diff(&scene, &theirs, &["--integrator", "euler"]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn the_reports_loop_with_its_ground_collision_agrees_with_seed() {
    let dir = folder("seed");
    let body = solid_box([0.2, 0.2, 0.2], 1.0);
    let scene = write(&dir, "box.toml", BOX_SCENE);
    let (rows, touched) = report_loop(&body, (BOX_X, BOX_V, BOX_W), true, Plant::default());
    let touched = touched.expect("the box reaches the ground within 150 steps");
    let theirs = write(&dir, "theirs.csv", &csv(&rows, Print::Matrix));
    let (code, out, err) = diff(&scene, &theirs, &[]);
    assert_eq!(code, 0, "{out}{err}");
    // A bounce of −0.5 P instead of −0.4 P: not a known mistake; it parts where the box first
    // touches, in the collide phase.
    let plant = Plant {
        bounce_half: true,
        ..Plant::default()
    };
    let (rows, _) = report_loop(&body, (BOX_X, BOX_V, BOX_W), true, plant);
    let theirs = write(&dir, "theirs-half.csv", &csv(&rows, Print::Matrix));
    let (code, out, err) = diff(&scene, &theirs, &[]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        out.contains(&format!("They part at step {touched} ")),
        "the box touches at step {touched}:\n{out}"
    );
    assert!(out.contains("in the collide phase"), "{out}");
    assert!(out.contains("cause: unknown"), "{out}");
}

/// One planted mistake: what the report must say.
struct Case {
    plant: Plant,
    step: u64,
    quantity: &'static str,
    phase: &'static str,
    cause: &'static str,
}

#[test]
fn each_known_mistake_planted_alone_parts_where_it_first_shows_and_is_named() {
    let dir = folder("mistakes");
    let body = hammer();
    let scene = write(&dir, "hammer.toml", HAMMER_SCENE);
    let none = Plant::default();
    let cases = [
        // τ = Σ pᵢ × F: L gains N x × F dt at the first step, x and R still agree.
        Case {
            plant: Plant {
                torque_about_origin: true,
                ..none
            },
            step: 1,
            quantity: "angular momentum",
            phase: "forces",
            cause: "the torque taken about the origin",
        },
        Case {
            plant: Plant {
                no_vertex_torque: true,
                ..none
            },
            step: 1,
            quantity: "angular momentum",
            phase: "forces",
            cause: "no per-vertex torque",
        },
        // R₀ = 𝟙: ω₀ is the same either way; from step 1 on R ≠ 𝟙 and ω parts while L agrees.
        Case {
            plant: Plant {
                omega_from_body: true,
                ..none
            },
            step: 1,
            quantity: "angular velocity",
            phase: "derive",
            cause: "ω from I⁻¹_body L",
        },
        // x₁ = x₀ + dt (v₀ + dt g) instead of x₀ + dt v₀.
        Case {
            plant: Plant {
                new_velocity_for_x: true,
                ..none
            },
            step: 1,
            quantity: "position",
            phase: "integrate",
            cause: "the new velocity used for the position",
        },
        // R₁ = 𝟙 + dt ω* is off a rotation by dt²|ω|² ≈ 2e-5: Gram–Schmidt moves it by that.
        Case {
            plant: Plant {
                gram_schmidt: true,
                ..none
            },
            step: 1,
            quantity: "rotation",
            phase: "integrate",
            cause: "Gram–Schmidt",
        },
        // F = 5 M g: P (so v) parts at step 1, x moved with the old v still agrees.
        Case {
            plant: Plant {
                gravity_on_every_point: true,
                ..none
            },
            step: 1,
            quantity: "velocity",
            phase: "forces",
            cause: "gravity as M g on every point",
        },
        Case {
            plant: Plant {
                dt_factor: 2.0,
                ..none
            },
            step: 1,
            quantity: "position",
            phase: "integrate",
            cause: "a time step off by a factor 2",
        },
    ];
    for case in cases {
        let (rows, _) = report_loop(&body, HAMMER, false, case.plant);
        let theirs = write(&dir, "theirs.csv", &csv(&rows, Print::Matrix));
        let (code, out, err) = diff(&scene, &theirs, &[]);
        assert_eq!(code, 1, "{}:\n{out}{err}", case.cause);
        assert!(
            out.contains(&format!(
                "They part at step {} (t = {} s), in the {} phase",
                case.step,
                case.step as f64 * DT,
                case.phase
            )),
            "{}:\n{out}",
            case.cause
        );
        let (_, step) = first_parting(&out, case.quantity)
            .unwrap_or_else(|| panic!("{}: {} agrees:\n{out}", case.cause, case.quantity));
        assert_eq!(step, case.step, "{}:\n{out}", case.cause);
        // The cause: one known mistake, named on the line after "cause:".
        let lines: Vec<&str> = out.lines().collect();
        let at = lines
            .iter()
            .position(|l| l.starts_with("cause: a known mistake reproduces"))
            .unwrap_or_else(|| panic!("{}: no single cause:\n{out}", case.cause));
        assert!(lines[at + 1].contains(case.cause), "{}:\n{out}", case.cause);
    }
}

#[test]
fn a_mistake_off_the_list_is_unknown_not_the_nearest() {
    let dir = folder("unknown");
    let scene = write(&dir, "hammer.toml", HAMMER_SCENE);
    let plant = Plant {
        hidden_drag: true,
        ..Plant::default()
    };
    let (rows, _) = report_loop(&hammer(), HAMMER, false, plant);
    let theirs = write(&dir, "theirs.csv", &csv(&rows, Print::Matrix));
    let (code, out, err) = diff(&scene, &theirs, &[]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("They part at step 1 "), "{out}");
    assert_eq!(
        first_parting(&out, "velocity").map(|p| p.1),
        Some(1),
        "{out}"
    );
    assert!(out.contains("cause: unknown"), "{out}");
}

#[test]
fn malformed_csvs_exit_2_naming_file_and_line() {
    let dir = folder("malformed");
    let scene = write(&dir, "hammer.toml", HAMMER_SCENE);
    let cases = [
        (
            "no-key.csv",
            "x,y,z\n0.3,2,0.1\n",
            1,
            "no `step` or `t` column",
        ),
        (
            "not-a-number.csv",
            "step,x\n0,0.3\n1,abc\n",
            3,
            "`abc` is not a number",
        ),
        (
            "unknown.csv",
            "step,x,spin\n0,0.3,1\n",
            1,
            "unknown column `spin`",
        ),
        (
            "out-of-order.csv",
            "step,x\n0,0.3\n2,0.302\n1,0.301\n",
            4,
            "rows out of order",
        ),
    ];
    for (name, text, line, what) in cases {
        let theirs = write(&dir, name, text);
        let (code, out, err) = diff(&scene, &theirs, &[]);
        assert_eq!(code, 2, "{name}: {out}{err}");
        assert!(
            err.contains(&format!("{}:{line}: ", theirs.display())) && err.contains(what),
            "{name}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{name}: one line: {err}");
        assert!(out.is_empty(), "{name}: {out}");
    }
}
