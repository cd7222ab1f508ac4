//! `tumble shot FILE --at T --svg OUT [--size COLSxROWS]`: the app's screen at time T as an
//! SVG, rendered without a terminal (text kept as text, colours as in the terminal).

use super::{load_with, Failure, Overrides};
use crate::tui::export;
use crate::tui::layout::ScreenLayout;
use crate::tui::{App, Options};
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct ShotArgs {
    /// The lesson or scene file.
    pub file: PathBuf,
    /// Simulated time of the picture, s (the scene is run from t = 0 to the nearest step).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub at: f64,
    /// Where to write the SVG.
    #[arg(long, value_name = "OUT")]
    pub svg: PathBuf,
    /// Screen size, COLSxROWS.
    #[arg(long, default_value = "120x40", value_parser = export::parse_size)]
    pub size: (u16, u16),
    /// Draw the projection in pure ASCII instead of Braille dots.
    #[arg(long)]
    pub ascii: bool,
    /// The large-drawing layout (key `L` in the app) instead of every panel.
    #[arg(long)]
    pub stage: bool,
    #[command(flatten)]
    pub overrides: Overrides,
}

/// The app for `file`, run to the frame nearest `at` seconds.
pub fn app_at(
    file: &std::path::Path,
    overrides: &Overrides,
    at: f64,
    ascii: bool,
    stage: bool,
) -> Result<App, Failure> {
    if !(at >= 0.0 && at.is_finite()) {
        return Err(Failure::bad_input(format!(
            "--at must be ≥ 0 and finite, found {at}"
        )));
    }
    let lesson = load_with(file, overrides)?;
    let mut app = App::new(
        lesson,
        Options {
            ascii,
            compare: None,
            show_timing: false,
        },
    );
    if stage {
        app.layout = ScreenLayout::Stage;
    }
    let steps = crate::limits::steps(
        at,
        app.snapshot.dt,
        &format!("--at {} s", crate::limits::short(at)),
        "choose a nearer time or a larger time step (--dt)",
    )
    .map_err(Failure::bad_input)?;
    // In chunks, so a divergence stops the run where it happens.
    let mut left = steps;
    while left > 0 && app.divergence.is_none() {
        let n = left.min(10_000);
        app.step_frames(n);
        left -= n;
    }
    Ok(app)
}

/// Writes the picture; a run that diverged on the way still gets its picture (the moment it
/// stopped), then exits 3 as `run` does.
pub fn shot(args: &ShotArgs) -> Result<(), Failure> {
    let app = app_at(&args.file, &args.overrides, args.at, args.ascii, args.stage)?;
    let (cols, rows) = args.size;
    let picture = export::svg(&export::render(&app, cols, rows));
    std::fs::write(&args.svg, picture)
        .map_err(|e| Failure::bad_input(format!("cannot write {}: {e}", args.svg.display())))?;
    super::output::warn(&format!(
        "wrote {} ({cols}x{rows}, t = {} s)",
        args.svg.display(),
        crate::tables::number_plain(app.snapshot.time)
    ));
    super::diverged(app.divergence.as_ref())
}
