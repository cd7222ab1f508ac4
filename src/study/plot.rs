//! `--svg PATH`: error against cost on log–log axes, one panel per scene, one line per
//! integrator (its points in order of dt, each labelled with its dt); frontier runs are ringed.
//! Beside each scene's cost panel, its error against dt (log–log, the same markers and colours),
//! on the same row of the grid; in both the fitted order p beside each line (the slope of the
//! dt panel's line). A cloth case's panels are drawn the same way (`Sweep`), one line per
//! particle integrator (error in m; runs past the explicit limit that diverged have no point
//! and are listed), the dt panel with the explicit limit 2/ω_max drawn and the floor band at
//! 3 × the reference's spread. The contact solvers'
//! panels: error against cost, and against the solver's own step h = dt / sub-steps
//! (`impulse` at dt, `soft-step ×n` at dt/n, its fitted order beside its line).

use super::analysis::format_dt;
use super::cloth::ClothStudy;
use super::contact::ContactStudy;
use super::methods::MethodStudy;
use super::SceneStudy;
use crate::physics::cloth::ClothIntegrator;
use crate::physics::{Integrator, Response, SoftStep};
use plotters::prelude::*;
use std::path::Path;

/// The colour of an integrator's line (the same in every panel): its descriptor's.
pub fn color(integrator: Integrator) -> RGBColor {
    let (r, g, b) = integrator.descriptor().colour;
    RGBColor(r, g, b)
}

/// The colour of a particle integrator: `symplectic-euler` as the body integrator of that
/// name, `implicit-euler` its own.
pub fn cloth_color(integrator: ClothIntegrator) -> RGBColor {
    match integrator {
        ClothIntegrator::SymplecticEuler => color(Integrator::SymplecticEuler),
        ClothIntegrator::ImplicitEuler => RGBColor(200, 30, 160),
    }
}

/// Smallest error drawn (exact zeros are drawn here).
const FLOOR: f64 = 1e-16;

/// One panel of the picture.
enum Panel<'s> {
    /// A scene's integrators: error against cost, or against dt.
    Bodies(&'s SceneStudy, Against),
    /// A cloth case's particle integrators: error against cost, or against dt.
    Cloth(&'s SceneStudy, &'s ClothStudy, Against),
    /// A contact scene's collision responses at its own integrator and dt: error against
    /// cost, or against the solver's step dt / sub-steps.
    Solvers(&'s SceneStudy, &'s ContactStudy, Against),
    /// The contact methods asked for (`--response A,B`): each over the dt sweep at the
    /// scene's integrator, error against cost, or against dt.
    Methods(&'s SceneStudy, &'s MethodStudy, Against),
    /// A blank slot, so that a scene's cost and dt panels share a row.
    Blank,
}

/// The horizontal axis of a scene's integrators' panel.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Against {
    /// µs of wall time per simulated second (frontier ringed, points labelled with dt).
    Cost,
    /// The time step (its slope is the fitted order; no timing in it).
    Dt,
}

/// What the legend lists: only what some panel draws.
struct Entries {
    integrators: Vec<Integrator>,
    implicit_euler: bool,
    solvers: bool,
    /// The contact methods some chart draws, in the list's order.
    methods: Vec<Response>,
}

impl Entries {
    fn of(studies: &[SceneStudy]) -> Entries {
        let drawn = |i: &Integrator| {
            studies
                .iter()
                .any(|s| s.rows.iter().any(|r| r.integrator == *i && drawable(r)))
        };
        Entries {
            integrators: Integrator::ALL.into_iter().filter(drawn).collect(),
            implicit_euler: studies.iter().any(|s| {
                s.cloth.as_ref().is_some_and(|c| {
                    c.rows
                        .iter()
                        .any(|r| r.integrator == ClothIntegrator::ImplicitEuler && r.ok())
                })
            }),
            solvers: studies.iter().any(|s| s.contact_solvers.is_some()),
            methods: Response::ALL
                .into_iter()
                .filter(|m| {
                    studies.iter().any(|s| {
                        s.methods
                            .as_ref()
                            .is_some_and(|c| c.rows.iter().any(|r| r.response.name() == m.name()))
                    })
                })
                .collect(),
        }
    }

    fn list(&self) -> Vec<(String, RGBColor)> {
        let mut entries: Vec<(String, RGBColor)> = self
            .integrators
            .iter()
            .map(|&i| (i.name().to_string(), color(i)))
            .collect();
        if self.implicit_euler {
            let i = ClothIntegrator::ImplicitEuler;
            entries.push((i.name().to_string(), cloth_color(i)));
        }
        if self.solvers {
            // Every charted response, as the contact chart runs them (`contact::solvers`).
            for response in Response::ALL.into_iter().filter(|r| r.descriptor().charted) {
                let name = match response {
                    Response::SoftStep(_) => "soft-step ×n".to_string(),
                    r => r.name().to_string(),
                };
                entries.push((format!("{name} (contact)"), response_color(response)));
            }
        }
        for &m in &self.methods {
            entries.push((format!("{} (method)", m.name()), response_color(m)));
        }
        entries
    }
}

/// The colour of a collision response in the contact solvers' panel: its descriptor's.
fn response_color(response: Response) -> RGBColor {
    let (r, g, b) = response.descriptor().colour;
    RGBColor(r, g, b)
}

/// A body row the panels draw.
fn drawable(r: &super::measure::Row) -> bool {
    r.ok() && r.measure().is_finite() && r.us_per_simulated_second > 0.0
}

/// The title, in lines that fit a picture `width` px wide (about 8 px a character at 16 px).
fn title_lines(width: u32) -> Vec<&'static str> {
    const FIRST: &str = "tumble study: error against cost and against dt, log–log";
    const SECOND: &str =
        "(lower left is better; ringed = Pareto frontier; labels = dt in s; p = fitted order)";
    if (FIRST.chars().count() + SECOND.chars().count() + 1) * 8 + 32 <= width as usize {
        vec!["tumble study: error against cost and against dt, log–log (lower left is better; ringed = Pareto frontier; labels = dt in s; p = fitted order)", super::report::ERROR_MEASURE]
    } else {
        vec![FIRST, SECOND, super::report::ERROR_MEASURE]
    }
}

/// Writes the plot; the error is a one-line message.
pub fn svg(studies: &[SceneStudy], path: &Path) -> Result<(), String> {
    // Each chart's cost and dt panels side by side, on one row of the grid.
    fn pair<'s>(panels: &mut Vec<Panel<'s>>, make: impl Fn(Against) -> Panel<'s>) {
        if panels.len() % 2 == 1 {
            panels.push(Panel::Blank);
        }
        panels.push(make(Against::Cost));
        panels.push(make(Against::Dt));
    }
    let mut panels = Vec::new();
    for study in studies {
        match &study.cloth {
            Some(cloth) => pair(&mut panels, |a| Panel::Cloth(study, cloth, a)),
            None => pair(&mut panels, |a| Panel::Bodies(study, a)),
        }
        if let Some(chart) = &study.contact_solvers {
            pair(&mut panels, |a| Panel::Solvers(study, chart, a));
        }
        if let Some(chart) = &study.methods {
            pair(&mut panels, |a| Panel::Methods(study, chart, a));
        }
    }
    let count = panels.len().max(1);
    let columns = if count > 1 { 2 } else { 1 };
    let rows = count.div_ceil(columns);
    let width = 640 * columns as u32;
    let entries = Entries::of(studies).list();
    let header = header_height(width, entries.len());
    let size = (width, header + 480 * rows as u32);
    let root = SVGBackend::new(path, size).into_drawing_area();
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (header, body) = root.split_vertically(header);
    legend(&header, &entries).map_err(|e| fail(&e))?;
    let areas = body.split_evenly((rows, columns));
    for (panel, area) in panels.iter().zip(areas.iter()) {
        match panel {
            Panel::Bodies(study, against) => sweep_panel(&bodies_sweep(study), *against, area),
            Panel::Cloth(study, cloth, against) => {
                sweep_panel(&cloth_sweep(study, cloth), *against, area)
            }
            Panel::Solvers(study, chart, against) => solvers_panel(study, chart, *against, area),
            Panel::Methods(study, chart, against) => {
                sweep_panel(&methods_sweep(study, chart), *against, area)
            }
            Panel::Blank => Ok(()),
        }
        .map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// Width of one legend entry, px.
const LEGEND_ENTRY: u32 = 170;

/// Legend entries per row in a picture `width` px wide.
fn legend_per_row(width: u32) -> usize {
    ((width - 16) / LEGEND_ENTRY).max(1) as usize
}

/// Height of the title and shared legend strip, px: the title's lines, then rows of legend
/// entries.
fn header_height(width: u32, entries: usize) -> u32 {
    let rows = entries.div_ceil(legend_per_row(width)) as u32;
    16 + 20 * title_lines(width).len() as u32 + 20 * rows
}

/// The title and one legend for every panel (a legend inside a panel would hide its points).
fn legend(area: &Area, entries: &[(String, RGBColor)]) -> Result<(), Box<dyn std::error::Error>> {
    let width = area.dim_in_pixel().0;
    let lines = title_lines(width);
    for (k, line) in lines.iter().enumerate() {
        area.draw(&Text::new(
            *line,
            (16, 8 + 20 * k as i32),
            ("sans-serif", 16).into_font(),
        ))?;
    }
    let top = 20 + 20 * lines.len() as i32;
    let per_row = legend_per_row(width);
    for (k, (name, c)) in entries.iter().enumerate() {
        let x = 16 + (LEGEND_ENTRY * (k % per_row) as u32) as i32;
        let y = top + 20 * (k / per_row) as i32;
        area.draw(&PathElement::new(
            vec![(x, y), (x + 28, y)],
            c.stroke_width(3),
        ))?;
        area.draw(&Text::new(
            name.as_str(),
            (x + 34, y - 7),
            ("sans-serif", 14).into_font().color(c),
        ))?;
    }
    Ok(())
}

/// A point's label, set beside it (right of and above the point, clear of its frontier ring):
/// `label!(text, (x, y), &colour)`.
macro_rules! label {
    ($text:expr, $at:expr, $c:expr $(,)?) => {
        EmptyElement::at($at) + Text::new($text, (9, -14), ("sans-serif", 11).into_font().color($c))
    };
}

/// The cost axis of the panels that sweep dt.
const PER_SECOND: &str = "cost: µs of wall time per simulated second";

/// The time-step axis of the panels of error against dt.
pub const TIME_STEP: &str = "time step dt (s)";

/// Error against cost, both axes logarithmic.
type CostChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// A log–log chart of error against cost, framed around (µs per simulated second, error)
/// `points` (errors below [`FLOOR`] drawn at it), with its caption and axes drawn.
fn cost_chart<'a, 'b>(
    area: &'a Area<'b>,
    caption: &str,
    cost: &str,
    error: &str,
    points: impl Iterator<Item = (f64, f64)>,
) -> Result<CostChart<'a, 'b>, Box<dyn std::error::Error>> {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for (cost, e) in points {
        (x0, x1) = (x0.min(cost), x1.max(cost));
        (y0, y1) = (y0.min(e.max(FLOOR)), y1.max(e.max(FLOOR)));
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (1.0, 10.0, 1e-6, 1.0);
    }
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (x0 / 2.0..x1 * 3.0).log_scale(),
            (y0 / 10.0..y1 * 10.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc(cost)
        .y_desc(error)
        .x_labels(6)
        .y_labels(8)
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    Ok(chart)
}

/// One run as a sweep panel draws it.
struct Point {
    dt: f64,
    /// µs of wall time per simulated second.
    cost: f64,
    error: f64,
    frontier: bool,
}

/// One integrator's line in a sweep panel: its runs that did not diverge, largest dt first.
struct Line {
    color: RGBColor,
    points: Vec<Point>,
    /// The text beside its finest run (the fitted order), if any.
    order: Option<String>,
}

impl Line {
    /// The line through `runs` (dt, cost, error, frontier), sorted largest dt first.
    fn new(
        color: RGBColor,
        runs: impl Iterator<Item = (f64, f64, f64, bool)>,
        order: Option<String>,
    ) -> Line {
        let mut points: Vec<Point> = runs
            .map(|(dt, cost, error, frontier)| Point {
                dt,
                cost,
                error,
                frontier,
            })
            .collect();
        points.sort_by(|a, b| b.dt.total_cmp(&a.dt));
        Line {
            color,
            points,
            order,
        }
    }
}

/// A panel over a sweep of integrators × dt — a scene's bodies or its cloths: what differs
/// between the two, the drawing being the same ([`sweep_panel`]).
struct Sweep {
    /// Against cost, against dt.
    captions: (String, String),
    /// The error axis.
    error: &'static str,
    lines: Vec<Line>,
    /// The floor band's top, its note, and whether the cost panel has it too.
    band: Option<(f64, String, bool)>,
    /// The explicit limit, marked on the dt panel.
    limit: Option<f64>,
    /// "integrator dt" of each diverged run.
    diverged: Vec<String>,
    /// Each line's points ringed with its own size, so that lines whose points coincide stay
    /// apart (else filled dots).
    rings: bool,
}

/// The bodies' sweep of a scene: error in rad + m/radius, the floor band on both panels.
fn bodies_sweep(study: &SceneStudy) -> Sweep {
    let ok: Vec<_> = study.rows.iter().filter(|r| drawable(r)).collect();
    let lines = Integrator::ALL
        .into_iter()
        .filter(|i| ok.iter().any(|r| r.integrator == *i))
        .map(|integrator| {
            let points = ok
                .iter()
                .filter(|r| r.integrator == integrator)
                .map(|r| (r.dt, r.us_per_simulated_second, r.error, r.frontier));
            let order = study
                .orders
                .iter()
                .find(|o| o.integrator == integrator)
                .map(|o| match o.slope {
                    Some(p) => format!("{} p = {p:.2}", integrator.name()),
                    None if o.exact => format!("{} exact", integrator.name()),
                    None => format!("{} p: none", integrator.name()),
                });
            Line::new(color(integrator), points, order)
        })
        .collect();
    Sweep {
        captions: (
            format!(
                "{} ({} s, {} reference)",
                study.name, study.duration, study.reference_kind
            ),
            format!("{}: error against dt (slope = p)", study.name),
        ),
        error: "error = max angle + |x − x_ref|/radius",
        lines,
        band: (study.floor > FLOOR).then(|| {
            (
                study.floor,
                format!(
                    "grey band: below the floor {:.1e} (round-off or the reference's own error)",
                    study.floor
                ),
                true,
            )
        }),
        limit: None,
        diverged: study
            .rows
            .iter()
            .filter(|r| !r.ok())
            .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)))
            .collect(),
        rings: true,
    }
}

/// The contact methods' sweep of a scene: one line per method (its descriptor's colour), the
/// error its chart's (against a bounce's closed form, or the contact error), the floor band on
/// both panels.
fn methods_sweep(study: &SceneStudy, chart: &MethodStudy) -> Sweep {
    let mut methods: Vec<Response> = Vec::new();
    for r in &chart.rows {
        if !methods.contains(&r.response) {
            methods.push(r.response);
        }
    }
    let lines = methods
        .iter()
        .map(|&method| {
            let points = chart
                .rows
                .iter()
                .filter(|r| r.response == method && super::methods::usable(r))
                .map(|r| {
                    (
                        r.run.dt,
                        r.run.us_per_simulated_second,
                        r.error,
                        r.run.frontier,
                    )
                });
            let order = chart
                .orders
                .iter()
                .find(|o| o.response == method)
                .map(|o| order_text(method.name(), o.slope));
            Line::new(response_color(method), points, order)
        })
        .collect();
    Sweep {
        captions: (
            format!(
                "{}: contact methods ({}, {} reference)",
                study.name,
                chart.integrator.name(),
                chart.reference_kind
            ),
            format!(
                "{}: contact methods' error against dt (slope = p)",
                study.name
            ),
        ),
        error: match chart.measure {
            "error" => "error against the closed form = max angle + |x − x_ref|/radius",
            _ => "contact error (end pose, shape, penetration; gain)",
        },
        lines,
        band: (chart.floor > FLOOR).then(|| {
            (
                chart.floor,
                format!("grey band: below the floor {:.1e}", chart.floor),
                true,
            )
        }),
        limit: None,
        diverged: chart
            .rows
            .iter()
            .filter(|r| !r.run.ok())
            .map(|r| format!("{} {}", r.response.name(), format_dt(r.run.dt)))
            .collect(),
        rings: true,
    }
}

/// A cloth case's sweep: error in m, against dt the explicit limit 2/ω_max and the floor band
/// at 3 × the reference's spread.
fn cloth_sweep(study: &SceneStudy, cloth: &ClothStudy) -> Sweep {
    let lines = ClothIntegrator::ALL
        .into_iter()
        .map(|integrator| {
            let points = cloth
                .rows
                .iter()
                .filter(|r| r.integrator == integrator)
                .filter(|r| r.ok() && r.error.is_finite() && r.us_per_simulated_second > 0.0)
                .map(|r| (r.dt, r.us_per_simulated_second, r.error, r.frontier));
            let order = cloth
                .orders
                .iter()
                .find(|o| o.integrator == integrator)
                .map(|o| order_text(integrator.name(), o.slope));
            Line::new(cloth_color(integrator), points, order)
        })
        .collect();
    let band = crate::study::cloth::FLOOR_SPREADS * cloth.reference_spread;
    Sweep {
        captions: (
            format!(
                "{} ({} s, cloth case, 2/ω_max = {:.3e} s)",
                study.name, study.duration, cloth.limit
            ),
            format!("{}: cloth error against dt (slope = p)", study.name),
        ),
        error: "max particle error, m",
        lines,
        band: (band > FLOOR).then(|| {
            (
                band,
                format!("grey band: below 3 × the reference's spread, {band:.1e} m (not resolved)"),
                false,
            )
        }),
        limit: cloth.limit.is_finite().then_some(cloth.limit),
        diverged: cloth
            .rows
            .iter()
            .filter(|r| !r.ok())
            .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)))
            .collect(),
        rings: false,
    }
}

/// A sweep's panel: error against cost (frontier ringed, points labelled with their dt) or
/// against dt (slope = order; the explicit limit dashed, if any); in both the fitted order
/// beside each line's finest run, the floor band and the diverged runs listed (a note when
/// nothing is drawn).
fn sweep_panel(
    sweep: &Sweep,
    against: Against,
    area: &Area,
) -> Result<(), Box<dyn std::error::Error>> {
    let x = |p: &Point| match against {
        Against::Cost => p.cost,
        Against::Dt => p.dt,
    };
    let (caption, x_desc) = match against {
        Against::Cost => (&sweep.captions.0, PER_SECOND),
        Against::Dt => (&sweep.captions.1, TIME_STEP),
    };
    let all = || sweep.lines.iter().flat_map(|l| &l.points);
    // Against dt the frame holds the limit too.
    let limit = sweep.limit.filter(|_| against == Against::Dt);
    let points = all().map(|p| (x(p), p.error)).chain(
        limit
            .into_iter()
            .flat_map(|l| all().next().map(|p| (l, p.error))),
    );
    let mut chart = cost_chart(area, caption, x_desc, sweep.error, points)?;
    let band = sweep
        .band
        .as_ref()
        .filter(|(_, _, on_cost)| *on_cost || against == Against::Dt);
    if let Some((top, _, _)) = band {
        floor_band(&mut chart, *top)?;
    }
    if let Some(l) = limit {
        let y = chart.plotting_area().get_y_range();
        chart.draw_series(DashedLineSeries::new(
            [(l, y.start), (l, y.end)],
            6,
            4,
            BLACK.stroke_width(1),
        ))?;
        chart.draw_series(std::iter::once(
            EmptyElement::at((l, y.end))
                + Text::new("2/ω_max", (4, 4), ("sans-serif", 11).into_font()),
        ))?;
    }
    for (k, line) in sweep.lines.iter().enumerate() {
        let c = line.color;
        let xy: Vec<(f64, f64)> = line
            .points
            .iter()
            .map(|p| (x(p), p.error.max(FLOOR)))
            .collect();
        chart.draw_series(LineSeries::new(xy.clone(), c.stroke_width(2)))?;
        if sweep.rings {
            // Lines whose points coincide stay apart: each has its own ring size.
            let size = 3 + 2 * k as i32;
            chart.draw_series(xy.iter().map(|&p| Circle::new(p, size, c.stroke_width(2))))?;
        } else {
            chart.draw_series(xy.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
        }
        if against == Against::Cost {
            chart.draw_series(
                line.points
                    .iter()
                    .zip(&xy)
                    .map(|(p, &at)| label!(format_dt(p.dt), at, &c)),
            )?;
        }
        if let (Some(last), Some(order)) = (xy.last(), &line.order) {
            chart.draw_series(std::iter::once(
                EmptyElement::at(*last)
                    + Text::new(
                        order.clone(),
                        (9, 2),
                        ("sans-serif", 11).into_font().color(&c),
                    ),
            ))?;
        }
    }
    if against == Against::Cost {
        let ring = 7 + if sweep.rings {
            2 * sweep.lines.len() as i32
        } else {
            0
        };
        chart.draw_series(
            all()
                .filter(|p| p.frontier)
                .map(|p| Circle::new((p.cost, p.error.max(FLOOR)), ring, BLACK.stroke_width(1))),
        )?;
    }
    let mut notes = Vec::new();
    if all().next().is_none() {
        notes.push(if sweep.diverged.is_empty() {
            "no run to draw".to_string()
        } else {
            "every run diverged: nothing to draw".to_string()
        });
    }
    notes.extend(diverged_notes(&sweep.diverged));
    if let Some((_, note, _)) = band {
        notes.push(note.clone());
    }
    draw_notes(area, &notes)
}

/// Draws the floor band (errors below `top` are not resolved) across `chart`.
fn floor_band(chart: &mut CostChart, top: f64) -> Result<(), Box<dyn std::error::Error>> {
    let (x_range, y_range) = (
        chart.plotting_area().get_x_range(),
        chart.plotting_area().get_y_range(),
    );
    let top = top.max(FLOOR).min(y_range.end);
    if top > y_range.start {
        chart.draw_series(std::iter::once(Rectangle::new(
            [(x_range.start, y_range.start), (x_range.end, top)],
            RGBColor(200, 200, 200).mix(0.35).filled(),
        )))?;
    }
    Ok(())
}

/// Writes `notes` in dark red at the panel's top left, one a line.
fn draw_notes(area: &Area, notes: &[String]) -> Result<(), Box<dyn std::error::Error>> {
    for (i, note) in notes.iter().enumerate() {
        area.draw(&Text::new(
            note.clone(),
            (80, 40 + 14 * i as i32),
            ("sans-serif", 12).into_font().color(&RGBColor(160, 0, 0)),
        ))?;
    }
    Ok(())
}

/// "diverged: a, b, c, d" then "  e, f, …", four a line.
fn diverged_notes(diverged: &[String]) -> Vec<String> {
    diverged
        .chunks(4)
        .enumerate()
        .map(|(k, chunk)| {
            let lead = if k == 0 { "diverged: " } else { "  " };
            format!("{lead}{}", chunk.join(", "))
        })
        .collect()
}

/// The fitted order's text beside a line's finest run.
fn order_text(name: &str, slope: Option<f64>) -> String {
    match slope {
        Some(p) => format!("{name} p = {p:.2}"),
        None => format!("{name} p: none"),
    }
}

/// The contact solvers' step axis.
pub const SOLVER_STEP: &str = "solver step h = dt / sub-steps (s)";

/// The least-squares slope of ln y against ln x (None under two points).
fn slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len() as f64;
    if points.len() < 2 {
        return None;
    }
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + x.ln() / n, b + y.ln() / n)
    });
    let sxy: f64 = points
        .iter()
        .map(|&(x, y)| (x.ln() - mx) * (y.ln() - my))
        .sum();
    let sxx: f64 = points.iter().map(|&(x, _)| (x.ln() - mx).powi(2)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The contact solvers' panel: contact error against cost, or against the solver's own step
/// h = dt / sub-steps (`impulse` at dt), at the scene's integrator and dt; `impulse` one point,
/// `soft-step` a line through its sub-step counts (against h, its fitted order beside it, over
/// its runs above the floor band).
fn solvers_panel(
    study: &SceneStudy,
    chart: &ContactStudy,
    against: Against,
    area: &Area,
) -> Result<(), Box<dyn std::error::Error>> {
    let ok: Vec<_> = chart.rows.iter().filter(|r| drawable(&r.run)).collect();
    let caption = match against {
        Against::Cost => format!(
            "{}: contact solvers ({}, dt = {} s)",
            study.name,
            chart.integrator.name(),
            format_dt(chart.dt)
        ),
        Against::Dt => format!("{}: contact error against the solver's step", study.name),
    };
    let at = |r: &super::SolverRow| {
        let x = match against {
            Against::Cost => r.run.us_per_simulated_second,
            Against::Dt => chart.dt / f64::from(r.substeps.max(1)),
        };
        (x, r.run.contact_error.max(FLOOR))
    };
    let mut plot = cost_chart(
        area,
        &caption,
        match against {
            Against::Cost => PER_SECOND,
            Against::Dt => SOLVER_STEP,
        },
        "contact error (worst body: end pose, shape, penetration; gain)",
        ok.iter().map(|r| at(r)),
    )?;
    if against == Against::Dt {
        floor_band(&mut plot, study.floor)?;
    }
    let mut soft: Vec<_> = ok.iter().filter(|r| r.substeps > 0).collect();
    soft.sort_by_key(|r| r.substeps);
    let soft_step = response_color(Response::SoftStep(SoftStep::DEFAULT));
    plot.draw_series(LineSeries::new(
        soft.iter().map(|r| at(r)),
        soft_step.stroke_width(2),
    ))?;
    for r in &ok {
        let c = response_color(r.response);
        plot.draw_series(std::iter::once(Circle::new(at(r), 3, c.filled())))?;
        let text = if r.substeps > 0 {
            format!("×{}", r.substeps)
        } else {
            r.solver.clone()
        };
        plot.draw_series(std::iter::once(label!(text, at(r), &c)))?;
    }
    match against {
        Against::Cost => {
            plot.draw_series(
                ok.iter()
                    .filter(|r| r.frontier)
                    .map(|r| Circle::new(at(r), 7, BLACK.stroke_width(1))),
            )?;
        }
        Against::Dt => {
            let fitted: Vec<(f64, f64)> = soft
                .iter()
                .map(|r| at(r))
                .filter(|&(_, e)| e > study.floor)
                .collect();
            if let Some(&last) = soft.last().map(|r| at(r)).as_ref() {
                plot.draw_series(std::iter::once(
                    EmptyElement::at(last)
                        + Text::new(
                            order_text("soft-step", slope(&fitted)),
                            (9, 2),
                            ("sans-serif", 11).into_font().color(&soft_step),
                        ),
                ))?;
            }
        }
    }
    let diverged: Vec<String> = chart
        .rows
        .iter()
        .filter(|r| !r.run.ok())
        .map(|r| r.solver.clone())
        .collect();
    let mut notes = Vec::new();
    if ok.is_empty() {
        notes.push("every run diverged: nothing to draw".to_string());
    }
    notes.extend(diverged_notes(&diverged));
    draw_notes(area, &notes)
}
