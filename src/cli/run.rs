//! `tumble run FILE --steps N`: the trajectory as CSV, one row per `--every` steps.
//!
//! Header (a contract): `step,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz,energy,penetration`.
//! Row 0 is the initial state; numbers are printed in full (shortest round-trip) precision.
//! With several bodies, `--body NAME` picks the body whose row is printed (default: the first);
//! `energy` is always the whole scene's.
//!
//! `--cloth NAME` prints instead one row per particle per kept step (a contract):
//! `step,t,i,j,x,y,z,vx,vy,vz,energy`, `energy` again the whole scene's. A scene of cloths
//! only prints its first cloth's rows without `--cloth`.
//!
//! `--joint NAME` prints one row per kept step for that joint (a contract):
//! `step,t,error,fx,fy,fz,tx,ty,tz`: its position error (m: ball, hinge, fixed the distance
//! between its two anchor points, distance |separation − length|) and the force (N) and
//! torque about the first body's barycenter (N·m) it applies to its first body, averaged over
//! the step (impulse / dt; row 0: the instantaneous reaction at t = 0).

use super::{load_with, Failure, Overrides, EXIT_DIVERGED};
use crate::physics::Snapshot;
use std::io::{BufWriter, Write};
use std::path::PathBuf;

/// The CSV header of `tumble run`.
pub const HEADER: &str = "step,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz,energy,penetration";

/// The CSV header of `tumble run --joint NAME`.
pub const JOINT_HEADER: &str = "step,t,error,fx,fy,fz,tx,ty,tz";

/// The CSV header of `tumble run --cloth NAME`.
pub const CLOTH_HEADER: &str = "step,t,i,j,x,y,z,vx,vy,vz,energy";

#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// The scene file.
    pub file: PathBuf,
    /// Number of steps to run.
    #[arg(long, allow_negative_numbers = true, value_parser = super::parse_count)]
    pub steps: u64,
    /// Print one row every K steps.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = super::parse_count)]
    pub every: u64,
    /// The body whose row is printed (default: the first).
    #[arg(long, conflicts_with = "cloth")]
    pub body: Option<String>,
    /// Print the particles of this cloth instead, one row each.
    #[arg(long, conflicts_with = "joint")]
    pub cloth: Option<String>,
    /// Print this joint's error and reaction instead.
    #[arg(long, conflicts_with = "body")]
    pub joint: Option<String>,
    #[command(flatten)]
    pub overrides: Overrides,
}

/// Runs the scene and prints its CSV.
pub fn run(args: &RunArgs) -> Result<(), Failure> {
    if args.every == 0 {
        return Err(Failure::bad_input("--every must be ≥ 1"));
    }
    let lesson = load_with(&args.file, &args.overrides)?;
    let cloth = match &args.cloth {
        Some(name) => Some(super::cloth_named(&lesson, name)?),
        None if lesson.scene.bodies.is_empty() => Some(0),
        None => None,
    };
    if let Some(cloth) = cloth {
        return run_cloth(args, lesson.scene.world(), cloth);
    }
    if let Some(name) = &args.joint {
        let index = super::joint_named(&lesson, name)?;
        return run_joint(args, lesson.scene.world(), index);
    }
    let body = match &args.body {
        Some(name) => super::body_named(&lesson, name)?,
        None => 0,
    };
    run_rows(args, lesson.scene.world(), HEADER, |world| {
        let s = world.snapshot_of(body);
        finite(&values(&s)).then(|| row(&s))
    })
}

/// The loop every mode of `run` shares: the header, row 0, then a step at a time, the rows of
/// every kept step. `rows(world)` is the text of a step's rows, or `None` when one of its
/// numbers is not finite: a run never prints a non-finite number, it stops with exit 3 —
/// before the header when it is so at t = 0 (the loader refuses the initial states it can name
/// a key for; this catches what overflows later, an energy of 1e308 kg), at the step it
/// happens otherwise (the divergence guard usually stops it first; this catches a number that
/// overflowed without the state doing so).
fn run_rows(
    args: &RunArgs,
    mut world: crate::physics::World,
    header: &str,
    rows: impl Fn(&crate::physics::World) -> Option<String>,
) -> Result<(), Failure> {
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let io = super::output::failure;
    let Some(first) = rows(&world) else {
        return Err(Failure {
            code: EXIT_DIVERGED,
            message: "the initial state is not finite (a number overflowed at t = 0): nothing \
                      was run"
                .to_string(),
        });
    };
    writeln!(out, "{header}").map_err(io)?;
    out.write_all(first.as_bytes()).map_err(io)?;
    for step in 1..=args.steps {
        world.step();
        if let Some(divergence) = world.divergence() {
            out.flush().map_err(io)?;
            return Err(Failure {
                code: EXIT_DIVERGED,
                message: divergence.to_string(),
            });
        }
        if step % args.every == 0 || step == args.steps {
            let Some(text) = rows(&world) else {
                out.flush().map_err(io)?;
                return Err(Failure {
                    code: EXIT_DIVERGED,
                    message: format!(
                        "simulation diverged at step {step}: a number of its row is not finite \
                         (integrator {}, dt = {} s)",
                        world.integrator().name(),
                        crate::limits::short(world.dt())
                    ),
                });
            };
            out.write_all(text.as_bytes()).map_err(io)?;
        }
    }
    out.flush().map_err(io)
}

/// Every number is finite.
fn finite(values: &[f64]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// The `--joint` rows: joint `index`, every kept step.
///
/// A joint with limits has the column `limit` appended, one with a motor `motor` (after
/// `limit` when both): what the stops and the motor applied over the step along the axis on the
/// first body (N for a slider, N·m for a hinge; already part of its force and torque).
fn run_joint(args: &RunArgs, world: crate::physics::World, index: usize) -> Result<(), Failure> {
    let joint = &world.snapshot().joints[index];
    let (limited, motorised) = (joint.limits.is_some(), joint.motor.is_some());
    let mut header = JOINT_HEADER.to_string();
    if limited {
        header.push_str(",limit");
    }
    if motorised {
        header.push_str(",motor");
    }
    run_rows(args, world, &header, |world| {
        let s = world.snapshot();
        let j = &s.joints[index];
        let (f, t) = (j.force, j.torque);
        let mut numbers = vec![s.time, j.error, f.x, f.y, f.z, t.x, t.y, t.z];
        if limited {
            numbers.push(j.drive.limit);
        }
        if motorised {
            numbers.push(j.drive.motor);
        }
        finite(&numbers).then(|| csv_line(s.step, &numbers))
    })
}

/// The `--cloth` rows: every particle of cloth `index`, every kept step.
fn run_cloth(args: &RunArgs, world: crate::physics::World, index: usize) -> Result<(), Failure> {
    run_rows(args, world, CLOTH_HEADER, |world| {
        let s = world.snapshot();
        let cloth = &s.cloths[index];
        let energy = s.system.energy.total;
        let mut text = String::new();
        for (k, (x, v)) in cloth.positions.iter().zip(&cloth.velocities).enumerate() {
            let (i, j) = cloth.cell(k);
            let numbers = [x.x, x.y, x.z, v.x, v.y, v.z, energy];
            if !finite(&numbers) || !world.time().is_finite() {
                return None;
            }
            text.push_str(&format!("{},{},{i},{j}", world.step_count(), world.time()));
            for n in numbers {
                text.push_str(&format!(",{n}"));
            }
            text.push('\n');
        }
        Some(text)
    })
}

/// `step` then the numbers, comma-separated, in full precision, with its newline.
fn csv_line(step: u64, numbers: &[f64]) -> String {
    let mut line = step.to_string();
    for v in numbers {
        line.push(',');
        line.push_str(&v.to_string());
    }
    line.push('\n');
    line
}

/// The numbers of a row, after `step`.
fn values(s: &Snapshot) -> [f64; 19] {
    let q = s.quaternion.quaternion();
    [
        s.time,
        s.position.x,
        s.position.y,
        s.position.z,
        q.w,
        q.i,
        q.j,
        q.k,
        s.velocity.x,
        s.velocity.y,
        s.velocity.z,
        s.angular_velocity.x,
        s.angular_velocity.y,
        s.angular_velocity.z,
        s.angular_momentum.x,
        s.angular_momentum.y,
        s.angular_momentum.z,
        s.system.energy.total,
        s.penetration,
    ]
}

/// One CSV row of a snapshot (`energy`: the whole scene's), with its newline.
pub fn row(s: &Snapshot) -> String {
    csv_line(s.step, &values(s))
}
