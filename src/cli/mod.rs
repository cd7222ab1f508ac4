//! The command line: `tumble [FILE]`, `run`, `check`, `lessons`, `walk`, `study`, `shot`,
//! `record`, `diff`.
//!
//! Exit codes: 0 ok, 2 bad input (one line on stderr), 3 the simulation diverged.

mod check;
pub mod diff;
mod lessons;
pub mod output;
#[cfg(feature = "tui")]
mod record;
mod run;
#[cfg(feature = "tui")]
mod shot;
pub mod study;
pub mod walk;

use crate::physics::cloth::ClothIntegrator;
use crate::physics::{Integrator, Response};
use crate::scene::{did_you_mean, Lesson, LoadError};
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
    /// A lesson or scene file, or a bundled lesson's name (`tumble lessons`), to open in the
    /// terminal app (default: the first bundled lesson).
    pub file: Option<PathBuf>,
    /// Draw the projection in pure ASCII instead of Braille dots.
    #[arg(long)]
    pub ascii: bool,
    /// Run a second world in lock-step with this integrator or collision response (a ghost).
    #[arg(long, value_name = "NAME")]
    pub compare: Option<String>,
    /// Draw a run computed elsewhere (a CSV as `tumble diff` reads it) as the ghost, and pause
    /// at the first step where it parts from tumble's.
    #[arg(long, value_name = "THEIRS.csv")]
    pub against: Option<PathBuf>,
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Step a scene and print its trajectory as CSV.
    Run(run::RunArgs),
    /// Validate scene files; errors name file:line:column.
    Check {
        /// Files (or bundled lessons' names) to validate.
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// What accuracy costs in time: every integrator × time step, error against an independent
    /// reference, drift of conserved quantities, ns per step.
    ///
    /// The error is the maximum, over the samples (every 0.1 s and the end) and every body, of
    /// angle(q_ref⁻¹q) + |x − x_ref|/radius (rad; x the barycenter). Its reference: a free
    /// body's closed form; with joints, springs, drag or several bodies the same model stepped
    /// by rk4 at a tenth of the finest step, checked by halving it (errors within 3× of what
    /// halving moved it, or with joints within 2 × 1e-12 m / radius — the projection's
    /// tolerance — are below the floor: not ranked, not fitted; a reference that does not
    /// converge is named so); with contact, the rest pose of every body (the worst body's
    /// vertex heights, shape and penetration, and the energy the scene gained at impacts)
    /// against rk4 at a tenth of the finest step.
    Study(study::StudyArgs),
    /// List the bundled lessons with their summaries.
    Lessons,
    /// Print the loop's numbers frame by frame (or phase by phase) as plain text.
    Walk(walk::WalkArgs),
    /// Check a trajectory computed elsewhere (your own loop's CSV) against tumble's run of
    /// the same scene, step by step, and name the known mistake that reproduces it.
    Diff(diff::DiffArgs),
    /// The app's screen at time T as an SVG (for slides and handouts).
    #[cfg(feature = "tui")]
    Shot(shot::ShotArgs),
    /// A run of the app as an asciicast v2 recording (for players and GIF converters).
    #[cfg(feature = "tui")]
    Record(record::RecordArgs),
}

/// Overrides of a scene's settings from the command line.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Overrides {
    /// Time step, s (overrides the file's `dt`).
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Integrator (overrides the file's `integrator`).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Collision response (overrides the file's `contact.response`).
    #[arg(long)]
    pub response: Option<String>,
}

/// A count on the command line (`--steps`, `--frames`, `--every`): a whole number ≥ 0; the
/// error says which rule the text broke (clap names the flag).
pub fn parse_count(text: &str) -> Result<u64, String> {
    let t = text.trim();
    t.parse::<u64>().map_err(|_| {
        if t.starts_with('-') {
            "must be a whole number ≥ 0".to_string()
        } else if t.parse::<f64>().is_ok_and(|v| v.is_finite() && v >= 0.0) {
            if t.parse::<f64>().is_ok_and(|v| v > u64::MAX as f64) {
                format!("must be a whole number at most {}", u64::MAX)
            } else {
                "must be a whole number (no decimal point or exponent)".to_string()
            }
        } else {
            "must be a whole number ≥ 0".to_string()
        }
    })
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

/// Exit 3 with the divergence's message when the run diverged (`shot`, `record`: the file is
/// written first, up to where it stopped).
pub fn diverged(divergence: Option<&impl std::fmt::Display>) -> Result<(), Failure> {
    match divergence {
        None => Ok(()),
        Some(d) => Err(Failure {
            code: EXIT_DIVERGED,
            message: d.to_string(),
        }),
    }
}

impl From<LoadError> for Failure {
    fn from(e: LoadError) -> Failure {
        Failure::bad_input(e.to_string())
    }
}

/// "unknown integrator `rk5` (did you mean `rk4`?); valid integrators: …": the wording of a
/// scene file's unknown names, for a name given on the command line.
pub fn unknown_name<'a>(
    what: &str,
    valid: &str,
    name: &str,
    candidates: impl IntoIterator<Item = &'a str> + Clone,
) -> String {
    let hint = did_you_mean(name, candidates.clone())
        .map(|s| format!(" (did you mean `{s}`?)"))
        .unwrap_or_default();
    let names: Vec<&str> = candidates.into_iter().collect();
    format!(
        "unknown {what} `{name}`{hint}; {valid}: {}",
        names.join(", ")
    )
}

/// An integrator named on the command line.
/// The index of the body named `name` in a lesson's scene, or a one-line error listing the
/// names (with a "did you mean").
pub fn body_named(lesson: &Lesson, name: &str) -> Result<usize, Failure> {
    lesson.scene.body_index(name).ok_or_else(|| {
        let names: Vec<&str> = lesson
            .scene
            .bodies
            .iter()
            .map(|b| b.name.as_str())
            .collect();
        let hint = crate::scene::did_you_mean(name, names.iter().copied())
            .map(|s| format!(" (did you mean `{s}`?)"))
            .unwrap_or_default();
        Failure::bad_input(format!(
            "{}: no body named `{name}`{hint}; bodies: {}",
            lesson.path.display(),
            names.join(", ")
        ))
    })
}

/// The index of the cloth named `name` in a lesson's scene, or a one-line error listing the
/// names (with a "did you mean").
pub fn cloth_named(lesson: &Lesson, name: &str) -> Result<usize, Failure> {
    let cloths = &lesson.scene.cloths;
    cloths.iter().position(|c| c.name == name).ok_or_else(|| {
        let names: Vec<&str> = cloths.iter().map(|c| c.name.as_str()).collect();
        let hint = did_you_mean(name, names.iter().copied())
            .map(|s| format!(" (did you mean `{s}`?)"))
            .unwrap_or_default();
        let list = if names.is_empty() {
            "the scene has none".to_string()
        } else {
            format!("cloths: {}", names.join(", "))
        };
        Failure::bad_input(format!(
            "{}: no cloth named `{name}`{hint}; {list}",
            lesson.path.display()
        ))
    })
}

/// The index of the joint with this name, or a one-line error listing the scene's joints.
pub fn joint_named(lesson: &Lesson, name: &str) -> Result<usize, Failure> {
    let joints = &lesson.scene.links.joints;
    joints.iter().position(|j| j.name == name).ok_or_else(|| {
        let names: Vec<&str> = joints.iter().map(|j| j.name.as_str()).collect();
        let hint = did_you_mean(name, names.iter().copied())
            .map(|s| format!(" (did you mean `{s}`?)"))
            .unwrap_or_default();
        let list = if names.is_empty() {
            "the scene has none".to_string()
        } else {
            format!("joints: {}", names.join(", "))
        };
        Failure::bad_input(format!(
            "{}: no joint named `{name}`{hint}; {list}",
            lesson.path.display()
        ))
    })
}

pub fn integrator_named(name: &str) -> Result<Integrator, Failure> {
    Integrator::from_name(name).ok_or_else(|| {
        let names = Integrator::ALL.map(Integrator::name);
        Failure::bad_input(unknown_name("integrator", "valid integrators", name, names))
    })
}

/// A collision response named on the command line.
pub fn response_named(name: &str) -> Result<Response, Failure> {
    Response::from_name(name).ok_or_else(|| {
        let names = Response::ALL.map(Response::name);
        Failure::bad_input(unknown_name(
            "collision response",
            "valid responses",
            name,
            names,
        ))
    })
}

/// `--integrator NAME`: replaces the scene's integrator (its bodies') and every cloth's own.
/// A body or a cloth that has no such integrator is an error.
fn override_integrators(
    path: &Path,
    scene: &mut crate::scene::Scene,
    name: &str,
) -> Result<(), Failure> {
    let body = Integrator::from_name(name);
    let cloth = ClothIntegrator::from_name(name);
    if body.is_none() && cloth.is_none() {
        if scene.cloths.is_empty() {
            return integrator_named(name).map(|_| ());
        }
        let body_names = Integrator::ALL.map(Integrator::name);
        let names = body_names.into_iter().chain(
            ClothIntegrator::ALL
                .map(ClothIntegrator::name)
                .into_iter()
                .filter(move |n| !body_names.contains(n)),
        );
        return Err(Failure::bad_input(unknown_name(
            "integrator",
            "valid integrators",
            name,
            names,
        )));
    }
    if let Some(first) = scene.bodies.first() {
        let Some(integrator) = body else {
            return Err(Failure::bad_input(format!(
                "{}: body `{}` has no integrator `{name}` (a particle integrator); valid \
                 integrators: {}",
                path.display(),
                first.name,
                Integrator::names()
            )));
        };
        scene.integrator = integrator;
    }
    if let Some(first) = scene.cloths.first() {
        let Some(integrator) = cloth else {
            return Err(Failure::bad_input(format!(
                "{}: cloth `{}` has no integrator `{name}`; particle integrators: {}",
                path.display(),
                first.name,
                ClothIntegrator::names()
            )));
        };
        for c in &mut scene.cloths {
            c.integrator = integrator;
        }
    }
    Ok(())
}

/// Loads a lesson (a file, or a bundled lesson by name) and applies command-line overrides;
/// the scene then passes the same rules as a file does ([`crate::scene::Scene::check_rules`]).
pub fn load_with(path: &Path, overrides: &Overrides) -> Result<Lesson, Failure> {
    let mut lesson = crate::lessons::load(path)?;
    apply(path, &mut lesson.scene, overrides)?;
    Ok(lesson)
}

/// Applies command-line overrides to a loaded scene and checks the scene's rules again.
pub fn apply(
    path: &Path,
    scene: &mut crate::scene::Scene,
    overrides: &Overrides,
) -> Result<(), Failure> {
    if let Some(dt) = overrides.dt {
        scene.dt = dt;
    }
    if let Some(name) = &overrides.integrator {
        override_integrators(path, scene, name)?;
    }
    if let Some(name) = &overrides.response {
        let response = response_named(name)?;
        match &mut scene.contact {
            // The same name keeps the scene's own soft-step parameters.
            Some(model) if model.response.name() == response.name() => {}
            Some(model) => model.response = response,
            None => {
                return Err(Failure::bad_input(format!(
                    "{}: --response needs a scene with obstacles and a `contact` table",
                    path.display()
                )))
            }
        }
    }
    scene
        .check_rules(crate::scene::Naming::Flags)
        .map_err(|(setting, message)| {
            // A rule the file itself breaks was refused when it loaded: this one is the flag's.
            match setting {
                crate::scene::Setting::Dt => Failure::bad_input(message),
                crate::scene::Setting::Response => {
                    Failure::bad_input(format!("{}: {message}", path.display()))
                }
            }
        })
}

/// The file the terminal app opens: the given one, else the first bundled lesson.
fn app_file(file: Option<&Path>) -> Result<PathBuf, Failure> {
    match file {
        Some(f) => Ok(f.to_path_buf()),
        None => crate::lessons::bundled()
            .into_iter()
            .next()
            .ok_or_else(|| Failure::bad_input("this build has no bundled lessons: give a FILE")),
    }
}

/// `tumble [FILE] [--ascii] [--compare NAME]`: the terminal app. The file and the options are
/// checked before the terminal is touched.
#[cfg(feature = "tui")]
fn app(
    file: Option<&Path>,
    ascii: bool,
    compare: Option<&str>,
    against: Option<&Path>,
) -> Result<(), Failure> {
    use crate::tui::{Comparison, Options};
    use std::io::IsTerminal;
    let path = app_file(file)?;
    let lesson = crate::lessons::load(&path)?;
    let against = match against {
        None => None,
        Some(csv) => Some(diff::against(&path, &lesson, csv)?),
    };
    let compare = match compare {
        None => None,
        Some(name) => {
            let comparison = Comparison::from_name(name).ok_or_else(|| {
                let names = Integrator::ALL
                    .map(Integrator::name)
                    .into_iter()
                    .chain(Response::ALL.map(Response::name));
                Failure::bad_input(unknown_name(
                    "--compare",
                    "valid: integrators and responses",
                    name,
                    names,
                ))
            })?;
            if let Comparison::Response(response) = comparison {
                // The ghost's scene passes the same rules as a file or `--response`.
                let mut ghost = lesson.scene.clone();
                apply(
                    &path,
                    &mut ghost,
                    &Overrides {
                        response: Some(response.name().to_string()),
                        ..Overrides::default()
                    },
                )
                .map_err(|f| Failure::bad_input(f.message.replace("--response", "--compare")))?;
            }
            // A ghost running the lesson's own setting would compare a run with itself.
            let scene = &lesson.scene;
            let same = match comparison {
                Comparison::Integrator(i) => !scene.bodies.is_empty() && i == scene.integrator,
                Comparison::Response(r) => scene.contact.is_some_and(|m| m.response == r),
                Comparison::ClothIntegrator(c) => {
                    !scene.cloths.is_empty() && scene.cloths.iter().all(|cl| cl.integrator == c)
                }
            };
            if same {
                return Err(Failure::bad_input(format!(
                    "{}: --compare {name}: the lesson runs `{name}` already, so the ghost would \
                     run the same as the lesson; compare with another (k cycles them in the app)",
                    path.display()
                )));
            }
            Some(comparison)
        }
    };
    if !(std::io::stdin().is_terminal() && std::io::stdout().is_terminal()) {
        return Err(Failure::bad_input(
            "the app needs a terminal (stdin and stdout are not one); for text use \
             `tumble walk FILE --frames N` or `tumble run FILE --steps N`",
        ));
    }
    let options = Options {
        ascii,
        compare,
        show_timing: true,
    };
    crate::tui::run_against(lesson, options, against)
        .map_err(|e| Failure::bad_input(format!("terminal error: {e}")))
}

/// Without the `tui` feature there is no terminal app: the file is still checked.
#[cfg(not(feature = "tui"))]
fn app(
    file: Option<&Path>,
    _ascii: bool,
    _compare: Option<&str>,
    _against: Option<&Path>,
) -> Result<(), Failure> {
    let path = app_file(file)?;
    crate::lessons::load(&path)?;
    Err(Failure::bad_input(
        "this build has no terminal app (built without the `tui` feature); use `tumble run`",
    ))
}

/// A command-line parser's error (clap's paragraphs: `error: …`, a tip, `Usage: …`, "For
/// more information, try '--help'.") as the one line every bad input gets: the error, its
/// tip and the usage, joined.
pub fn usage_error(rendered: &str) -> String {
    let mut parts: Vec<String> = Vec::new();
    for paragraph in rendered.split("\n\n") {
        let text = paragraph.split_whitespace().collect::<Vec<_>>().join(" ");
        if text.is_empty() || text.starts_with("For more information") {
            continue;
        }
        let text = text.strip_prefix("error: ").unwrap_or(&text);
        match text.strip_prefix("Usage: ") {
            Some(usage) => parts.push(format!("(usage: {usage})")),
            None => parts.push(text.to_string()),
        }
    }
    parts.join("; ").replace("; (usage:", " (usage:")
}

/// Runs the command line; returns the process exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            output::warn(&usage_error(&e.render().to_string()));
            return ExitCode::from(EXIT_BAD_INPUT);
        }
        Err(e) => {
            // `--help | head -1`: a closed stdout ends the help quietly, never a panic.
            return match e.print() {
                Err(io) => ExitCode::from(output::failure(io).code),
                Ok(()) => ExitCode::SUCCESS,
            };
        }
    };
    let result = match cli.command {
        Some(Command::Run(args)) => run::run(&args),
        Some(Command::Check { files }) => check::check(&files),
        Some(Command::Study(args)) => study::study(&args),
        Some(Command::Lessons) => lessons::list(),
        Some(Command::Walk(args)) => walk::walk(&args),
        Some(Command::Diff(args)) => diff::diff(&args),
        #[cfg(feature = "tui")]
        Some(Command::Shot(args)) => shot::shot(&args),
        #[cfg(feature = "tui")]
        Some(Command::Record(args)) => record::record(&args),
        None => app(
            cli.file.as_deref(),
            cli.ascii,
            cli.compare.as_deref(),
            cli.against.as_deref(),
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            output::warn(&failure.message);
            ExitCode::from(failure.code)
        }
    }
}
