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
    let mut world = lesson.scene.world();
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let write = |out: &mut BufWriter<_>, s: &Snapshot| -> std::io::Result<()> {
        writeln!(out, "{}", row(s))
    };
    let io = super::output::failure;
    let first = world.snapshot_of(body);
    initial_finite(values(&first).iter().all(|v| v.is_finite()))?;
    writeln!(out, "{HEADER}").map_err(io)?;
    write(&mut out, &first).map_err(io)?;
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
            let s = world.snapshot_of(body);
            if !values(&s).iter().all(|v| v.is_finite()) {
                // The guard missed it (a number overflowed without the state doing so): the
                // row is not printed either.
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
            }
            write(&mut out, &s).map_err(io)?;
        }
    }
    out.flush().map_err(io)
}

/// The `--joint` rows: joint `index`, every kept step.
fn run_joint(
    args: &RunArgs,
    mut world: crate::physics::World,
    index: usize,
) -> Result<(), Failure> {
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let io = |e: std::io::Error| Failure::bad_input(format!("cannot write output: {e}"));
    let write = |out: &mut BufWriter<_>, s: &Snapshot| -> std::io::Result<()> {
        let j = &s.joints[index];
        let (f, t) = (j.force, j.torque);
        writeln!(
            out,
            "{},{},{},{},{},{},{},{},{}",
            s.step, s.time, j.error, f.x, f.y, f.z, t.x, t.y, t.z
        )
    };
    writeln!(out, "{JOINT_HEADER}").map_err(io)?;
    write(&mut out, &world.snapshot()).map_err(io)?;
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
            write(&mut out, &world.snapshot()).map_err(io)?;
        }
    }
    out.flush().map_err(io)
}

/// The `--cloth` rows: every particle of cloth `index`, every kept step.
fn run_cloth(
    args: &RunArgs,
    mut world: crate::physics::World,
    index: usize,
) -> Result<(), Failure> {
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let io = super::output::failure;
    let write = |out: &mut BufWriter<_>, world: &crate::physics::World| -> std::io::Result<()> {
        let cloth = &world.cloths()[index];
        let energy = world.total_energy().total;
        for (k, (x, v)) in cloth.positions.iter().zip(&cloth.velocities).enumerate() {
            let (i, j) = cloth.grid(k);
            writeln!(
                out,
                "{},{},{i},{j},{},{},{},{},{},{},{energy}",
                world.step_count(),
                world.time(),
                x.x,
                x.y,
                x.z,
                v.x,
                v.y,
                v.z
            )?;
        }
        Ok(())
    };
    let cloth = &world.cloths()[index];
    initial_finite(
        world.total_energy().total.is_finite()
            && cloth
                .positions
                .iter()
                .chain(&cloth.velocities)
                .all(|v| v.iter().all(|c| c.is_finite())),
    )?;
    writeln!(out, "{CLOTH_HEADER}").map_err(io)?;
    write(&mut out, &world).map_err(io)?;
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
            write(&mut out, &world).map_err(io)?;
        }
    }
    out.flush().map_err(io)
}

/// The guard before row 0: a run never prints a non-finite number. The loader refuses the
/// initial states it can name a key for; anything else not finite at t = 0 (an energy that
/// overflows) stops the run here, exit 3, before the header.
fn initial_finite(finite: bool) -> Result<(), Failure> {
    if finite {
        Ok(())
    } else {
        Err(Failure {
            code: EXIT_DIVERGED,
            message: "the initial state is not finite (a number overflowed at t = 0): nothing \
                      was run"
                .to_string(),
        })
    }
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

/// One CSV row of a snapshot (`energy`: the whole scene's).
pub fn row(s: &Snapshot) -> String {
    let mut line = s.step.to_string();
    for v in values(s) {
        line.push(',');
        line.push_str(&v.to_string());
    }
    line
}
