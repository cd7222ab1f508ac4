//! `tumble walk FILE --frames N [--phases]`: the loop's numbers as plain text, frame by frame
//! (or phase by phase), for a handout.
//!
//! Each block is headed by the time, the frame and the loop phase just completed, then the
//! lesson page that applies at that time (its full text the first time it applies, its title
//! afterwards), then the numeric panels of [`crate::tables`], the formatter the terminal app
//! uses — so the handout and the screen show the same digits. Scenes with obstacles also get
//! the contacts panel.

use super::{load_with, Failure, Overrides, EXIT_DIVERGED};
use crate::physics::World;
use crate::scene::{printable, Lesson};
use crate::tables::{
    cloth_panel, contact_panel, number_plain, panel_text, panels, Frame, BODY_PANELS,
};
use std::io::Write;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct WalkArgs {
    /// The lesson or scene file.
    pub file: PathBuf,
    /// Number of frames to walk through.
    #[arg(long, allow_negative_numbers = true, value_parser = super::parse_count)]
    pub frames: u64,
    /// Print the tables after every phase (derive, forces, integrate, collide), not only after
    /// each frame.
    #[arg(long)]
    pub phases: bool,
    /// With several bodies, print only this body's tables (default: every body's, in turn).
    #[arg(long)]
    pub body: Option<String>,
    /// Under each number of the state, angular velocity, momentum and energy tables, its
    /// measured error (a `±` row): the difference from a converged reference run of the same
    /// scene (rk4 at a tenth of the step, checked by halving it; the header names it and its
    /// cost in steps). Where no reference converges (an impact, a stick–slip switch) the row
    /// says so. With --phases, the errors are printed after each whole frame.
    #[arg(long)]
    pub error: bool,
    #[command(flatten)]
    pub overrides: Overrides,
}

/// Why a walk stopped early.
#[derive(Debug)]
pub enum WalkError {
    /// The simulation diverged (its message names step, quantity, integrator and dt).
    Diverged(String),
    /// The output could not be written.
    Io(std::io::Error),
}

impl From<std::io::Error> for WalkError {
    fn from(e: std::io::Error) -> WalkError {
        WalkError::Io(e)
    }
}

/// Runs `tumble walk`.
pub fn walk(args: &WalkArgs) -> Result<(), Failure> {
    let lesson = load_with(&args.file, &args.overrides)?;
    let bodies = match &args.body {
        None => None,
        Some(name) => Some(vec![super::body_named(&lesson, name)?]),
    };
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    let result = write_walk_with(
        &lesson,
        args.frames,
        args.phases,
        bodies.as_deref(),
        args.error,
        &mut out,
    );
    let flushed = out.flush();
    match result {
        Ok(()) => flushed.map_err(super::output::failure),
        Err(WalkError::Diverged(message)) => Err(Failure {
            code: EXIT_DIVERGED,
            message,
        }),
        Err(WalkError::Io(e)) => Err(super::output::failure(e)),
    }
}

/// Writes the walk of `frames` frames of a lesson (every phase when `phases`), every body's
/// tables.
pub fn write_walk(
    lesson: &Lesson,
    frames: u64,
    phases: bool,
    out: &mut impl Write,
) -> Result<(), WalkError> {
    write_walk_bodies(lesson, frames, phases, None, out)
}

/// [`write_walk`] with the tables of the given bodies only (None: every body).
pub fn write_walk_bodies(
    lesson: &Lesson,
    frames: u64,
    phases: bool,
    bodies: Option<&[usize]>,
    out: &mut impl Write,
) -> Result<(), WalkError> {
    write_walk_with(lesson, frames, phases, bodies, false, out)
}

/// [`write_walk_bodies`], with the `±` rows of [`crate::error_bars`] when `error`.
pub fn write_walk_with(
    lesson: &Lesson,
    frames: u64,
    phases: bool,
    bodies: Option<&[usize]>,
    error: bool,
    out: &mut impl Write,
) -> Result<(), WalkError> {
    let mut world = lesson.scene.world();
    let mut reference =
        error.then(|| crate::error_bars::ReferenceRun::new(&lesson.scene, world.dt()));
    let live = crate::live::LiveValues::compute(lesson, world.clone());
    let every: Vec<usize> = (0..world.body_count()).collect();
    let bodies = bodies.unwrap_or(&every);
    write_header(lesson, &world, out)?;
    if let Some(reference) = &reference {
        writeln!(out, "{}", reference.describe(&world))?;
    }
    let mut shown_page = None;
    write_block(
        lesson,
        &live,
        &world,
        bodies,
        reference.as_ref(),
        &mut shown_page,
        out,
    )?;
    // One block per frame, or one per phase of every frame.
    let blocks_per_frame = if phases { 4 } else { 1 };
    for _ in 0..frames {
        for _ in 0..blocks_per_frame {
            if phases {
                world.step_phase();
            } else {
                world.step();
            }
            // The reference keeps pace by whole frames: the errors are printed after each.
            let whole = matches!(
                world.last_phase(),
                None | Some(crate::physics::Phase::Collide)
            );
            if let (Some(reference), true) = (&mut reference, whole) {
                reference.advance();
            }
            let errors = reference.as_ref().filter(|_| whole);
            write_block(lesson, &live, &world, bodies, errors, &mut shown_page, out)?;
        }
        if let Some(divergence) = world.divergence() {
            writeln!(out)?;
            writeln!(out, "stopped: {divergence}")?;
            return Err(WalkError::Diverged(divergence.to_string()));
        }
    }
    Ok(())
}

/// The lesson's title, file name, summary and scene settings.
fn write_header(lesson: &Lesson, world: &World, out: &mut impl Write) -> std::io::Result<()> {
    let name = lesson
        .path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    writeln!(out, "{}", printable(&format!("{} ({name})", lesson.title)))?;
    if !lesson.summary.is_empty() {
        writeln!(out, "{}", printable(&lesson.summary))?;
    }
    let effects = world.effects().names();
    let effects = if effects.is_empty() {
        "none".to_string()
    } else {
        effects.join(", ")
    };
    let snapshot = world.snapshot();
    // The obstacles by type (the fixed bodies are listed with the bodies).
    let obstacles: Vec<&str> = (snapshot.fixed.iter())
        .filter(|f| f.body.is_none())
        .map(|f| f.kind)
        .collect();
    let obstacles = if obstacles.is_empty() {
        "none".to_string()
    } else {
        obstacles.join(", ")
    };
    let bodies: Vec<String> = lesson
        .scene
        .bodies
        .iter()
        .map(|b| {
            if lesson.scene.bodies.len() > 1 {
                format!(
                    "{} {} · M = {} kg",
                    b.name,
                    b.shape,
                    number_plain(b.body.mass)
                )
            } else {
                format!("body {} · M = {} kg", b.shape, number_plain(b.body.mass))
            }
        })
        .collect();
    let mut settings = if bodies.is_empty() {
        // A scene of cloths only: no body uses the scene's integrator; each cloth has its own.
        let cloths: Vec<String> = snapshot
            .cloths
            .iter()
            .map(|c| {
                format!(
                    "{}, {}",
                    crate::physics::cloth::label(&c.name),
                    c.integrator
                )
            })
            .collect();
        format!(
            "dt = {} s · {} · effects: {effects} · obstacles: {obstacles}",
            number_plain(world.dt()),
            cloths.join(" · "),
        )
    } else {
        format!(
            "integrator {} · dt = {} s · {} · effects: {effects} · obstacles: {obstacles}",
            world.integrator().name(),
            number_plain(world.dt()),
            bodies.join(" · "),
        )
    };
    if let Some(model) = world.contact_model() {
        settings.push_str(&format!(" · response {}", model.response.name()));
    }
    writeln!(out, "{}", printable(&settings))
}

/// One block: time, frame and phase, the page that applies, the panels of each body in
/// `bodies` (headed by its name when the scene has several), then the scene's.
fn write_block(
    lesson: &Lesson,
    live: &crate::live::LiveValues,
    world: &World,
    bodies: &[usize],
    reference: Option<&crate::error_bars::ReferenceRun>,
    shown_page: &mut Option<usize>,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let snapshot = &world.snapshot_of(bodies.first().copied().unwrap_or(0));
    let obstacles = snapshot.obstacles_fixed().next().is_some();
    writeln!(out)?;
    let when = format!("t = {} s", number_plain(snapshot.time));
    let line = match snapshot.phase {
        None => format!(
            "== {when} · initial state · next phase: {}",
            snapshot.next_phase
        ),
        Some(phase) => {
            // The frame a phase belongs to: integrate counts the step, so before it the step
            // count is one behind.
            let frame = match phase {
                crate::physics::Phase::Derive | crate::physics::Phase::Forces => snapshot.step + 1,
                _ => snapshot.step,
            };
            format!("== {when} · frame {frame} · phase done: {phase}")
        }
    };
    writeln!(out, "{line}")?;
    if let Some((index, page)) = lesson.page_at(snapshot.time) {
        let count = lesson.pages.len();
        if *shown_page == Some(index) {
            writeln!(
                out,
                "page {}/{count}: {} (text above)",
                index + 1,
                printable(&page.title)
            )?;
        } else {
            writeln!(
                out,
                "page {}/{count} (from t = {} s): {}",
                index + 1,
                number_plain(page.at),
                printable(&page.title)
            )?;
            for text_line in live.page_text(page).trim_end().lines() {
                let text_line = printable(text_line);
                writeln!(out, "{}", format!("  | {text_line}").trim_end())?;
            }
            if let Some(line) = live.prediction_line(page) {
                writeln!(out, "  {line}")?;
            }
            *shown_page = Some(index);
        }
    }
    let several = world.body_count() > 1;
    let mut write = |panel: &crate::tables::Panel| -> std::io::Result<()> {
        for text_line in panel_text(panel) {
            writeln!(out, "{}", printable(&text_line))?;
        }
        Ok(())
    };
    let mut scene_panels = Vec::new();
    if world.body_count() == 0 {
        // Cloths only: the scene's panels (energy), no body's.
        scene_panels = panels(snapshot, Frame::World).split_off(BODY_PANELS);
    }
    for &index in bodies {
        let snapshot = world.snapshot_of(index);
        if several {
            write(&crate::tables::Panel {
                title: format!("-- body {} --", snapshot.body_name),
                rows: Vec::new(),
            })?;
        }
        let mut all = panels(&snapshot, Frame::World);
        if several {
            scene_panels = all.split_off(BODY_PANELS);
            // Each body's own energy under the scene's (as the app shows it): a heavy body's
            // share would swamp the others in the total.
            let at = scene_panels.len().min(1);
            scene_panels.insert(at, crate::tables::body_energy_panel(&snapshot));
        }
        if let Some(reference) = reference {
            let errors = reference.errors(world, index);
            crate::error_bars::annotate(&mut all, &errors);
            crate::error_bars::annotate(&mut scene_panels, &errors);
        }
        if obstacles || several {
            all.push(contact_panel(&snapshot));
        }
        for panel in &all {
            write(panel)?;
        }
    }
    for cloth in &snapshot.cloths {
        write(&cloth_panel(cloth, snapshot.dt))?;
    }
    for joint in &snapshot.joints {
        write(&crate::tables::joint_panel(joint))?;
    }
    if !snapshot.joints.is_empty() {
        write(&crate::tables::correction_panel(snapshot))?;
    }
    for spring in &snapshot.springs {
        write(&crate::tables::spring_panel(spring))?;
    }
    for panel in &scene_panels {
        write(panel)?;
    }
    Ok(())
}
