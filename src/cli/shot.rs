//! `tumble shot FILE --at T --svg OUT [--size COLSxROWS] [--view front|side|top]`: the app's
//! screen at time T as an SVG, rendered without a terminal (text kept as text, colours as in the
//! terminal). The screen is set as in the app: the view (`--view`, key `v`), the arrows
//! (`--no-arrows`, key `a`), the energy graph (`--graph`, key `g`), the compare ghost
//! (`--compare NAME`, key `k`), the stage layout (`--stage`, key `L`), the graph of a quantity
//! (`--plot NAME`, against another with `--plot-x NAME`: key `p`), the measuring tools
//! (`--tool NAME`: keys `w` `T` `m` `A`); `tumble record` takes the same options
//! ([`ScreenArgs`]).

use super::{load_with, Failure, Overrides};
use crate::tui::export;
use crate::tui::layout::ScreenLayout;
use crate::tui::viewport::Axis;
use crate::tui::{App, Comparison, Options, View};
use std::path::PathBuf;

/// How the exported screen is set: the options of `shot` and `record`, each a key of the app.
#[derive(Debug, Clone, clap::Args)]
pub struct ScreenArgs {
    /// Draw the projection in pure ASCII instead of Braille dots.
    #[arg(long)]
    pub ascii: bool,
    /// The large-drawing layout (key `L` in the app) instead of every panel.
    #[arg(long)]
    pub stage: bool,
    /// The view direction (key `v`): front (x–y), side (z–y) or top (x–z).
    #[arg(long, default_value = "front", value_parser = parse_view)]
    pub view: Axis,
    /// Leave out the body axes and the ω and L arrows (key `a`).
    #[arg(long)]
    pub no_arrows: bool,
    /// Draw the force arrows (key `F`): gravity, contacts, joint reactions, springs.
    #[arg(long)]
    pub forces: bool,
    /// The energy graph in place of the drawing (key `g`).
    #[arg(long)]
    pub graph: bool,
    /// Run a ghost beside the scene with another integrator, collision response or cloth
    /// integrator (key `k`), drawn and tabulated as in the app's compare mode.
    #[arg(long, value_name = "NAME", value_parser = parse_comparison)]
    pub compare: Option<Comparison>,
    /// The graph of a quantity in place of the drawing (key `p`): BODY.NAME (x y z vx vy vz
    /// wx wy wz Lx Ly Lz |L| speed kinetic potential energy), the scene's energy Px Py Pz, or
    /// JOINT.error; against time unless `--plot-x` is given.
    #[arg(long, value_name = "QUANTITY", conflicts_with = "graph")]
    pub plot: Option<String>,
    /// With `--plot`: the quantity on the horizontal axis (a phase portrait).
    #[arg(long, value_name = "QUANTITY", requires = "plot")]
    pub plot_x: Option<String>,
    /// Show a measuring tool (keys `w` `T` `m` `A`), as set by the page or by default: the
    /// stopwatch (started at t = 0), the period timer (of the quantity `--plot` graphs, else
    /// the page's or the first), the ruler, the protractor. Repeat for several.
    #[arg(long = "tool", value_name = "NAME", value_parser = parse_tool)]
    pub tools: Vec<crate::scene::PagePanel>,
}

fn parse_tool(name: &str) -> Result<crate::scene::PagePanel, String> {
    crate::scene::PagePanel::from_name(name)
        .ok()
        .filter(|p| p.is_tool())
        .ok_or_else(|| {
            format!("unknown tool `{name}` (tools: stopwatch, period, ruler, protractor)")
        })
}

fn parse_view(name: &str) -> Result<Axis, String> {
    match name {
        "front" => Ok(Axis::Front),
        "side" => Ok(Axis::Side),
        "top" => Ok(Axis::Top),
        _ => Err(format!("unknown view `{name}` (front, side or top)")),
    }
}

fn parse_comparison(name: &str) -> Result<Comparison, String> {
    Comparison::from_name(name).ok_or_else(|| {
        format!("unknown integrator, collision response or cloth integrator `{name}`")
    })
}

impl ScreenArgs {
    /// The app for `lesson`, set as these options say.
    pub fn app(&self, lesson: crate::scene::Lesson) -> Result<App, Failure> {
        let mut app = App::new(
            lesson,
            Options {
                ascii: self.ascii,
                compare: None,
                show_timing: false,
            },
        );
        if let Some(comparison) = self.compare {
            if !app.comparisons().contains(&comparison) {
                return Err(Failure::bad_input(format!(
                    "--compare {}: this scene cannot be compared with it (it is its own setting, or \
                     it does not apply here)",
                    comparison.name()
                )));
            }
            app.start_compare(comparison);
        }
        if self.stage {
            app.prefs.layout = ScreenLayout::Stage;
        }
        app.prefs.axis = self.view;
        app.prefs.arrows = !self.no_arrows;
        app.prefs.forces = self.forces;
        if self.graph {
            app.ui.view = View::Energy;
        }
        if let Some(y) = &self.plot {
            let column = |name: &str, flag: &str| -> Result<usize, Failure> {
                let columns = &app.session.plot_series.columns;
                columns.iter().position(|c| c.name == name).ok_or_else(|| {
                    let names: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
                    Failure::bad_input(format!(
                        "{flag} {name}: no such quantity in this scene (it has {})",
                        names.join(" ")
                    ))
                })
            };
            let y = column(y, "--plot")?;
            let x = match &self.plot_x {
                Some(x) => Some(column(x, "--plot-x")?),
                None => None,
            };
            app.ui.plot = Some(crate::tui::plot::PlotChoice { y, x });
            app.ui.view = View::Plot;
        }
        for tool in &self.tools {
            app.show_tool(*tool);
        }
        Ok(app)
    }
}

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
    #[command(flatten)]
    pub screen: ScreenArgs,
    #[command(flatten)]
    pub overrides: Overrides,
}

/// The app for `file`, run to the frame nearest `at` seconds.
pub fn app_at(
    file: &std::path::Path,
    overrides: &Overrides,
    at: f64,
    screen: &ScreenArgs,
) -> Result<App, Failure> {
    if !(at >= 0.0 && at.is_finite()) {
        return Err(Failure::bad_input(format!(
            "--at must be ≥ 0 and finite, found {at}"
        )));
    }
    let lesson = load_with(file, overrides)?;
    let mut app = screen.app(lesson)?;
    let steps = crate::limits::steps(
        at,
        app.session.snapshot.dt,
        &format!("--at {} s", crate::limits::short(at)),
        "choose a nearer time or a larger time step (--dt)",
    )
    .map_err(Failure::bad_input)?;
    // In chunks, so a divergence stops the run where it happens.
    let mut left = steps;
    while left > 0 && app.session.divergence.is_none() {
        let n = left.min(10_000);
        app.step_frames(n);
        left -= n;
    }
    Ok(app)
}

/// Writes the picture; a run that diverged on the way still gets its picture (the moment it
/// stopped), then exits 3 as `run` does.
pub fn shot(args: &ShotArgs) -> Result<(), Failure> {
    let app = app_at(&args.file, &args.overrides, args.at, &args.screen)?;
    let (cols, rows) = args.size;
    let picture = export::svg(&export::render(&app, cols, rows));
    std::fs::write(&args.svg, picture)
        .map_err(|e| Failure::bad_input(format!("cannot write {}: {e}", args.svg.display())))?;
    super::output::warn(&format!(
        "wrote {} ({cols}x{rows}, t = {} s)",
        args.svg.display(),
        crate::tables::number_plain(app.session.snapshot.time)
    ));
    super::diverged(app.session.divergence.as_ref())
}
