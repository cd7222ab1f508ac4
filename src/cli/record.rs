//! `tumble record FILE --duration T --out OUT.cast [--size COLSxROWS] [--view front|side|top]`:
//! a run of the app (set as `shot` sets it: [`super::shot::ScreenArgs`]) as an asciicast v2
//! recording (header line, then `[time, "o", data]` events with increasing times),
//! rendered without a terminal, at real time. Its steps and frames are bounded before it
//! starts ([`crate::limits`]); a divergence ends the recording where it happens, exit 3.

use super::shot::ScreenArgs;
use super::{load_with, Failure, Overrides};
use crate::tui::export;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct RecordArgs {
    /// The lesson or scene file.
    pub file: PathBuf,
    /// Simulated time to record, s (played back at real time).
    #[arg(long, allow_negative_numbers = true)]
    pub duration: f64,
    /// Where to write the recording (.cast).
    #[arg(long, value_name = "OUT.cast")]
    pub out: PathBuf,
    /// Screen size, COLSxROWS.
    #[arg(long, default_value = "120x40", value_parser = export::parse_size)]
    pub size: (u16, u16),
    #[command(flatten)]
    pub screen: ScreenArgs,
    #[command(flatten)]
    pub overrides: Overrides,
}

pub fn record(args: &RecordArgs) -> Result<(), Failure> {
    if !(args.duration > 0.0 && args.duration.is_finite()) {
        return Err(Failure::bad_input(format!(
            "--duration must be > 0 and finite, found {}",
            args.duration
        )));
    }
    let lesson = load_with(&args.file, &args.overrides)?;
    let mut app = args.screen.app(lesson)?;
    let what = format!("--duration {} s", crate::limits::short(args.duration));
    let steps = crate::limits::steps(
        args.duration,
        app.session.snapshot.dt,
        &what,
        "record a shorter time or use a larger time step (--dt)",
    )
    .map_err(Failure::bad_input)?;
    // One frame of the recording every `frames_per_second / CAST_FPS` steps (at least one
    // frame per step).
    let per_frame = app.frames_per_second() / export::CAST_FPS;
    crate::limits::count(
        (steps as f64 / per_frame).ceil(),
        crate::limits::MAX_CAST_FRAMES,
        &format!(
            "{what} at {} frames/s of simulation",
            app.frames_per_second()
        ),
        "recording frames",
        "record a shorter time",
    )
    .map_err(Failure::bad_input)?;
    let (cols, rows) = args.size;
    let cast = export::record(&mut app, args.duration, cols, rows);
    std::fs::write(&args.out, &cast)
        .map_err(|e| Failure::bad_input(format!("cannot write {}: {e}", args.out.display())))?;
    super::output::warn(&format!(
        "wrote {} ({cols}x{rows}, {} frames, t = {} s)",
        args.out.display(),
        cast.lines().count() - 1,
        crate::tables::number_plain(app.session.snapshot.time)
    ));
    super::diverged(app.session.divergence.as_ref())
}
