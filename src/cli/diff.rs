//! `tumble diff FILE THEIRS.csv`: a trajectory computed elsewhere (a student's own loop)
//! against tumble's run of the same scene, step by step, and the known mistake that
//! reproduces it (see [`crate::diff`]).
//!
//! Exit codes: 0 every given column agrees on every row, 1 they differ, 2 bad input (the CSV:
//! one line naming file:line), 3 tumble's own run diverged.

use super::{load_with, Failure, Overrides, EXIT_DIVERGED};
use crate::diff::{check, theirs, Subject, DEFAULT_TOLERANCE};
use std::path::PathBuf;

/// Exit code when the two runs differ.
pub const EXIT_DIFFER: u8 = 1;

#[derive(Debug, clap::Args)]
pub struct DiffArgs {
    /// The lesson or scene file both loops run.
    pub file: PathBuf,
    /// Their trajectory: a CSV with a header naming any of `run`'s columns (`step` or `t`
    /// required; `R11 … R33` accepted for the rotation), one row per kept step.
    pub theirs: PathBuf,
    /// The body their rows describe (default: the first).
    #[arg(long)]
    pub body: Option<String>,
    /// Largest difference that still agrees, relative to each quantity's largest norm over
    /// the run (1 for a rotation).
    #[arg(long, default_value_t = DEFAULT_TOLERANCE, value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub tolerance: f64,
    #[command(flatten)]
    pub overrides: Overrides,
}

/// `--tolerance`: a number > 0.
fn parse_tolerance(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err("must be a number > 0 (relative, e.g. 1e-6)".to_string()),
    }
}

/// Runs `tumble diff`.
pub fn diff(args: &DiffArgs) -> Result<(), Failure> {
    let lesson = load_with(&args.file, &args.overrides)?;
    if lesson.scene.bodies.is_empty() {
        return Err(Failure::bad_input(format!(
            "{}: the scene has no body: `diff` compares a body's trajectory",
            lesson.path.display()
        )));
    }
    let body = match &args.body {
        Some(name) => super::body_named(&lesson, name)?,
        None => 0,
    };
    let theirs = theirs::read(&args.theirs, lesson.scene.dt)
        .map_err(|e| Failure::bad_input(e.to_string()))?;
    let subject = Subject {
        scene: &lesson.scene,
        scene_name: &args.file.display().to_string(),
        theirs_name: &args.theirs.display().to_string(),
        body,
    };
    let outcome = check(&subject, &theirs, args.tolerance).map_err(|message| Failure {
        code: EXIT_DIVERGED,
        message: format!("tumble's own run diverged before their last row: {message}"),
    })?;
    super::output::print(&outcome.text)?;
    match outcome.first_row {
        None => Ok(()),
        Some(r) => Err(Failure {
            code: EXIT_DIFFER,
            message: format!(
                "{} parts from tumble's run at step {}",
                args.theirs.display(),
                theirs.rows[r].step
            ),
        }),
    }
}

/// `tumble FILE --against THEIRS.csv`: their rows checked as `tumble diff` checks them (the
/// first body, the scene's settings, the default tolerance), for the app to draw.
#[cfg(feature = "tui")]
pub fn against(
    path: &std::path::Path,
    lesson: &crate::scene::Lesson,
    csv: &std::path::Path,
) -> Result<crate::tui::Against, Failure> {
    if lesson.scene.bodies.is_empty() {
        return Err(Failure::bad_input(format!(
            "{}: --against needs a scene with a body",
            path.display()
        )));
    }
    let theirs =
        theirs::read(csv, lesson.scene.dt).map_err(|e| Failure::bad_input(e.to_string()))?;
    let subject = Subject {
        scene: &lesson.scene,
        scene_name: &path.display().to_string(),
        theirs_name: &csv.display().to_string(),
        body: 0,
    };
    let outcome = check(&subject, &theirs, DEFAULT_TOLERANCE).map_err(|message| Failure {
        code: EXIT_DIVERGED,
        message: format!("tumble's own run diverged before their last row: {message}"),
    })?;
    Ok(crate::tui::Against::new(
        csv.display().to_string(),
        &theirs,
        &outcome,
    ))
}
