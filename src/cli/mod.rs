//! The command line: `tumble [FILE]`, `run`, `check`, `lessons`, `walk`, `study`.
//!
//! Exit codes: 0 ok, 2 bad input (one line on stderr), 3 the simulation diverged.

mod check;
mod lessons;
mod run;
pub mod study;
pub mod walk;

use crate::physics::{Integrator, Response};
use crate::scene::{self, Lesson, LoadError};
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit code for bad input.
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit code for a diverged simulation.
pub const EXIT_DIVERGED: u8 = 3;

/// Rigid-body dynamics, one phase of the animation loop at a time.
#[derive(Debug, Parser)]
#[command(
    name = "tumble",
    version,
    about,
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    /// A lesson or scene file to open in the terminal app (default: the first bundled lesson).
    pub file: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Step a scene and print its trajectory as CSV.
    Run(run::RunArgs),
    /// Validate scene files; errors name file:line:column.
    Check {
        /// Files to validate.
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// What accuracy costs in time: every integrator × time step, error against an independent
    /// reference, drift of conserved quantities, ns per step.
    Study(study::StudyArgs),
    /// List the bundled lessons with their summaries.
    Lessons,
    /// Print the loop's numbers frame by frame (or phase by phase) as plain text.
    Walk(walk::WalkArgs),
}

/// Overrides of a scene's settings from the command line.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Overrides {
    /// Time step, s (overrides the file's `dt`).
    #[arg(long)]
    pub dt: Option<f64>,
    /// Integrator (overrides the file's `integrator`).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Collision response (overrides the file's `contact.response`).
    #[arg(long)]
    pub response: Option<String>,
}

/// A one-line error for the user, with its exit code.
#[derive(Debug)]
pub struct Failure {
    pub code: u8,
    pub message: String,
}

impl Failure {
    pub fn bad_input(message: impl Into<String>) -> Failure {
        Failure {
            code: EXIT_BAD_INPUT,
            message: message.into(),
        }
    }
}

impl From<LoadError> for Failure {
    fn from(e: LoadError) -> Failure {
        Failure::bad_input(e.to_string())
    }
}

/// Loads a lesson and applies command-line overrides.
pub fn load_with(path: &Path, overrides: &Overrides) -> Result<Lesson, Failure> {
    let mut lesson = scene::load(path)?;
    let scene = &mut lesson.scene;
    if let Some(dt) = overrides.dt {
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(Failure::bad_input(format!(
                "--dt must be > 0 and finite, found {dt}"
            )));
        }
        scene.dt = dt;
    }
    if let Some(name) = &overrides.integrator {
        scene.integrator = Integrator::from_name(name).ok_or_else(|| {
            Failure::bad_input(format!(
                "unknown integrator `{name}`; valid integrators: {}",
                Integrator::names()
            ))
        })?;
    }
    if let Some(name) = &overrides.response {
        let response = Response::from_name(name).ok_or_else(|| {
            Failure::bad_input(format!(
                "unknown collision response `{name}`; valid responses: {}",
                Response::names()
            ))
        })?;
        match &mut scene.contact {
            Some(model) => model.response = response,
            None => {
                return Err(Failure::bad_input(format!(
                    "{}: --response needs a scene with obstacles and a `contact` table",
                    path.display()
                )))
            }
        }
    }
    Ok(lesson)
}

/// Runs the command line; returns the process exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_BAD_INPUT } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let result = match cli.command {
        Some(Command::Run(args)) => run::run(&args),
        Some(Command::Check { files }) => check::check(&files),
        Some(Command::Study(args)) => study::study(&args),
        Some(Command::Lessons) => lessons::list(),
        Some(Command::Walk(args)) => walk::walk(&args),
        None => Err(Failure::bad_input(
            "the terminal app is not built yet: use `tumble run FILE --steps N`".to_string(),
        )),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("tumble: {}", failure.message);
            ExitCode::from(failure.code)
        }
    }
}
