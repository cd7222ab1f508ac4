//! The study view (key `s`): error against cost of every integrator × time step on the current
//! scene, as a log–log chart — the same numbers as `tumble study FILE`, computed on a background
//! thread ([`crate::study::background`]) while the rest of the app keeps running. Until the
//! study is done, a gauge shows its progress ("k of N runs · about … left", the cheapest runs
//! first); `s` leaves the view with the study going on, Esc leaves it and cancels the study.
//! The study uses the collision response in use (after `c`, entering the view again studies
//! the new one) and marks the integrator in use. A scene with cloths shows the cloth case: one
//! line per particle integrator ([`crate::study::cloth`]).

use super::app::App;
use super::theme;
use crate::physics::cloth::ClothIntegrator;
use crate::physics::Integrator;
use crate::study::analysis::{format_dt, format_number};
use crate::study::background::Job;
use crate::study::cloth::{ClothOrder, ClothStudy};
use crate::study::{plot, Case, Config, SceneStudy};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::{Block, Gauge, Paragraph, Widget, Wrap};

/// Starts the study of a lesson's scene (every integrator, dt = 1e-1 … 1e-4) with the
/// collision response in use.
pub fn spawn(app: &App) -> Job {
    let mut case = Case::from_lesson(&app.session.lesson);
    case.scene.contact = app.session.snapshot.contact_model;
    Job::spawn(case, Config::default())
}

/// The study was made with the collision response in use (else it must be made again).
pub fn is_current(job: &Job, app: &App) -> bool {
    job.response == app.session.snapshot.contact_model.map(|m| m.response)
}

/// The colour of an integrator, as in the SVG plot.
fn colour(integrator: Integrator) -> Color {
    let plotters::style::RGBColor(r, g, b) = plot::color(integrator);
    Color::Rgb(r, g, b)
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let Some(job) = &app.session.study else {
        Paragraph::new("press s to study this scene")
            .block(Block::bordered().title(" study "))
            .render(area, buf);
        return;
    };
    let shown = Shown {
        ascii: app.prefs.ascii,
        in_use: app.session.snapshot.integrator,
        dt: app.session.snapshot.dt,
    };
    match (job.result(), job.partial()) {
        (Some(study), _) => draw_study(&study, &shown, None, area, buf),
        // The runs finished so far, the chart filling as the others finish.
        (None, Some(partial)) if job.refusal().is_none() && !job.failed() => {
            let (done, total) = job.progress();
            let progress = Progress {
                done,
                total,
                left: job.time_left(),
            };
            draw_study(&partial, &shown, Some(progress), area, buf)
        }
        _ => render_progress(job, area, buf),
    }
}

/// With `progress`, the gauge on the first row of `area` ("k of N runs · about … left"); the
/// rest of the area.
fn gauge_row(progress: Option<Progress>, area: Rect, buf: &mut Buffer) -> Rect {
    let Some(p) = progress else {
        return area;
    };
    let [gauge, rest] = Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(area);
    Gauge::default()
        .gauge_style(theme::GAUGE)
        .ratio(if p.total == 0 {
            0.0
        } else {
            (p.done as f64 / p.total as f64).min(1.0)
        })
        .label(progress_label(p.done, p.total, p.left))
        .render(gauge, buf);
    rest
}

fn render_progress(job: &Job, area: Rect, buf: &mut Buffer) {
    let block = Block::bordered().title(format!(" study of {} ", job.name));
    let inner = block.inner(area);
    block.render(area, buf);
    let [gauge, text] = Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(inner);
    let (done, total) = job.progress();
    if let Some(why) = job.refusal() {
        Paragraph::new(format!("the study cannot run: {why}"))
            .wrap(Wrap { trim: true })
            .style(theme::ERROR)
            .render(inner, buf);
        return;
    }
    if job.failed() {
        Paragraph::new("the study stopped unexpectedly (see the terminal after quitting)")
            .style(theme::ERROR)
            .render(inner, buf);
        return;
    }
    Gauge::default()
        .gauge_style(theme::GAUGE)
        .ratio(if total == 0 {
            0.0
        } else {
            done as f64 / total as f64
        })
        .label(progress_label(done, total, job.time_left()))
        .render(gauge, buf);
    Paragraph::new(vec![
        Line::from(""),
        Line::from(
            "Every integrator at dt = 1e-1 … 1e-4 (with cloths: each particle integrator on a \
             ladder of dt around 2/ω_max), each run measured against a reference and timed \
             (the fastest of up to 5 timed runs), the cheapest runs first: the reference is \
             being made, then the chart fills as the runs finish.",
        ),
        Line::from(
            "The simulation and every other key keep working meanwhile; s leaves this view \
             (the study goes on), Esc leaves it and cancels the study.",
        ),
    ])
    .wrap(Wrap { trim: true })
    .render(text, buf);
}

/// The gauge's label: "k of N runs", and the estimated time left once there is one
/// ([`Job::time_left`]).
pub fn progress_label(done: usize, total: usize, left: Option<std::time::Duration>) -> String {
    let runs = format!("{done} of {total} runs");
    match left {
        Some(left) if done < total => format!("{runs} · about {} left", duration(left)),
        _ => runs,
    }
}

/// A wall-clock duration to the second: "45 s", "3 min 20 s", "1 h 05 min".
fn duration(d: std::time::Duration) -> String {
    let s = d.as_secs_f64().round() as u64;
    match s {
        0..60 => format!("{s} s"),
        60..3600 => format!("{} min {:02} s", s / 60, s % 60),
        _ => format!("{} h {:02} min", s / 3600, (s % 3600) / 60),
    }
}

/// Integer decades covering [lo, hi] (log10 values), at least one decade wide.
fn decades(lo: f64, hi: f64) -> (f64, f64) {
    let (a, b) = (lo.floor(), hi.ceil());
    if b > a {
        (a, b)
    } else {
        (a, a + 1.0)
    }
}

/// The whole decades around (log₁₀ cost, log₁₀ error) points: x range, y range.
fn bounds(points: &[(f64, f64)]) -> ((f64, f64), (f64, f64)) {
    if points.is_empty() {
        return ((0.0, 1.0), (-1.0, 0.0));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in points {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    (decades(x0, x1), decades(y0, y1))
}

/// The colour of a particle integrator, as in the SVG plot.
fn cloth_colour(integrator: ClothIntegrator) -> Color {
    let plotters::style::RGBColor(r, g, b) = plot::cloth_color(integrator);
    Color::Rgb(r, g, b)
}

/// The cloth case, drawn by the bodies' code ([`layout_study`], [`draw_charts`]): max particle
/// error against cost and against dt, one line per particle integrator with its fitted order
/// beside it, the explicit limit 2/ω_max marked on the dt chart, the floor band at 3 × the
/// reference's spread (as in the SVG, [`crate::study::plot`]), the diverged runs listed; with
/// `progress`, the runs finished so far under a gauge — before the first, a word saying so.
fn render_cloth_study(
    study: &SceneStudy,
    cloth: &ClothStudy,
    ascii: bool,
    progress: Option<Progress>,
    area: Rect,
    buf: &mut Buffer,
) {
    let area = gauge_row(progress, area, buf);
    let dim = Style::new().add_modifier(Modifier::DIM);
    let drawable: Vec<_> = cloth
        .rows
        .iter()
        .filter(|r| r.ok() && r.error.is_finite() && r.us_per_simulated_second > 0.0)
        .collect();
    let integrators: Vec<ClothIntegrator> = ClothIntegrator::ALL
        .into_iter()
        .filter(|i| {
            cloth.rows.iter().any(|r| r.integrator == *i)
                || cloth.orders.iter().any(|o| o.integrator == *i)
        })
        .collect();
    let order_of = |i: ClothIntegrator| match cloth.orders.iter().find(|o| o.integrator == i) {
        Some(ClothOrder { slope: Some(s), .. }) => format!("p {s:.2}"),
        _ => "p –".to_string(),
    };
    let limit = cloth.limit.is_finite().then_some(cloth.limit);
    let band = crate::study::cloth::FLOOR_SPREADS * cloth.reference_spread;
    let band = (band > 0.0 && band.is_finite()).then_some(band);
    let lines = integrators
        .iter()
        .map(|&i| {
            let mut runs: Vec<_> = drawable.iter().filter(|r| r.integrator == i).collect();
            runs.sort_by(|a, b| b.dt.total_cmp(&a.dt));
            SweepLine {
                color: cloth_colour(i),
                runs: runs
                    .iter()
                    .map(|r| (r.dt, r.us_per_simulated_second, r.error))
                    .collect(),
                label: vec![format!("{} {}", i.name(), order_of(i)), order_of(i)],
            }
        })
        .collect();
    let note = drawable.is_empty().then(|| {
        if cloth.rows.iter().any(|r| !r.ok()) && progress.is_none() {
            "every run diverged: nothing to draw".to_string()
        } else if cloth.rows.is_empty() {
            "reference made: the first run is under way …".to_string()
        } else {
            "no run finished yet".to_string()
        }
    });
    let sweep = Sweep {
        lines,
        rings: drawable
            .iter()
            .filter(|r| r.frontier)
            .map(|r| (r.us_per_simulated_second.log10(), log_error(r.error)))
            .collect(),
        band: band.map(f64::log10),
        show_band: true,
        limit,
        ladder: cloth.ladder.clone(),
        error_title: "max particle error, m",
        note,
    };
    let mut entries: Vec<ratatui::text::Span> = integrators
        .iter()
        .map(|&i| {
            ratatui::text::Span::styled(
                format!("── {} {}", i.name(), order_of(i)),
                Style::new().fg(cloth_colour(i)),
            )
        })
        .collect();
    if limit.is_some() {
        entries.push(ratatui::text::Span::styled(
            format!("{} 2/ω_max", if ascii { ":" } else { "┆" }),
            LIMIT,
        ));
    }
    entries.push(frontier_entry(ascii));
    let mut text = pack(entries, area);
    let diverged: Vec<String> = cloth
        .rows
        .iter()
        .filter(|r| !r.ok())
        .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)))
        .collect();
    text.push(diverged_line(&diverged));
    if let Some(l) = limit {
        text.push(Line::styled(
            format!(
                "{} explicit limit 2/ω_max = {} s ({}): symplectic-euler diverges at larger dt; \
                 the orders are fitted on the runs below it",
                if ascii { ":" } else { "┆" },
                format_number(l),
                cloth.limiting_cloth
            ),
            dim,
        ));
    }
    if let Some(b) = band {
        let inside = drawable.iter().filter(|r| r.error < b).count();
        text.push(Line::styled(
            format!(
                "{} grey band: below 3 × the reference's spread, {} m (not resolved): the \
                 {inside} run{} inside it are not ranked against each other",
                if ascii { "..." } else { "···" },
                format_number(b),
                if inside == 1 { "" } else { "s" },
            ),
            dim,
        ));
    }
    text.push(frontier_line(
        cloth
            .rows
            .iter()
            .filter(|r| r.frontier)
            .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt))),
    ));
    text.push(Line::styled(format!("reference: {}", cloth.reference), dim));
    text.push(Line::from(cloth.sentence.clone()));
    let title = format!(
        " study of {} ({} s, cloth case, 2/ω_max = {} s) ",
        study.name,
        study.duration,
        format_number(cloth.limit)
    );
    layout_study(&sweep, text, title, ascii, area, buf);
}

/// The marker of the explicit limit on the dt chart.
const LIMIT: Style = Style::new().fg(Color::Yellow);

/// The legend's frontier entry.
fn frontier_entry(ascii: bool) -> ratatui::text::Span<'static> {
    ratatui::text::Span::raw(if ascii { "O frontier" } else { "◆ frontier" })
}

/// Legend entries packed on lines of the text box's width (each entry whole on a line).
fn pack(entries: Vec<ratatui::text::Span<'static>>, area: Rect) -> Vec<Line<'static>> {
    let width = area.width.saturating_sub(2).max(1) as usize;
    let mut legend: Vec<Line> = vec![Line::default()];
    for entry in entries {
        let last = legend.last_mut().expect("one line at least");
        let used = last.width();
        if used > 0 && used + 2 + entry.width() > width {
            legend.push(Line::from(entry));
        } else {
            if used > 0 {
                last.push_span(ratatui::text::Span::raw("  "));
            }
            last.push_span(entry);
        }
    }
    legend
}

/// "diverged (no point): rk4 1e-1, …" (red), or "… none" (dim).
fn diverged_line(diverged: &[String]) -> Line<'static> {
    Line::styled(
        format!(
            "diverged (no point): {}",
            if diverged.is_empty() {
                "none".to_string()
            } else {
                diverged.join(", ")
            }
        ),
        if diverged.is_empty() {
            Style::new().add_modifier(Modifier::DIM)
        } else {
            Style::new().fg(Color::LightRed)
        },
    )
}

/// "frontier (cheapest first): …" (dim).
fn frontier_line(runs: impl Iterator<Item = String>) -> Line<'static> {
    Line::styled(
        format!(
            "frontier (cheapest first): {}",
            runs.collect::<Vec<_>>().join(", ")
        ),
        Style::new().add_modifier(Modifier::DIM),
    )
}

/// The study's text under its two charts: as many rows as the wrapped `text` needs, up to half
/// of `area`; the charts ([`draw_charts`]) keep the rest.
fn layout_study(
    sweep: &Sweep,
    text: Vec<Line>,
    title: String,
    ascii: bool,
    area: Rect,
    buf: &mut Buffer,
) {
    let width = area.width.saturating_sub(2).max(1) as usize;
    let needed: usize = text
        .iter()
        .map(|l| l.width().div_ceil(width).max(1))
        .sum::<usize>()
        + 2;
    let text_height = (needed as u16).clamp(5, (area.height / 2).max(5));
    let [charts, text_area] =
        Layout::vertical([Constraint::Min(8), Constraint::Length(text_height)]).areas(area);
    let [cost_area, dt_area] =
        Layout::horizontal([Constraint::Percentage(58), Constraint::Min(0)]).areas(charts);
    draw_charts(sweep, ascii, cost_area, dt_area, buf);
    Paragraph::new(text)
        .block(Block::bordered().title(title))
        .wrap(Wrap { trim: true })
        .render(text_area, buf);
}

/// One integrator's line in the two charts.
struct SweepLine {
    color: Color,
    /// (dt s, µs per simulated s, error), largest dt first.
    runs: Vec<(f64, f64, f64)>,
    /// Written beside the line's finest run on the dt chart (the fitted order), the first of
    /// these that fits; none for no label.
    label: Vec<String>,
}

/// What the two charts draw — a scene's bodies or its cloths, the drawing being the same.
struct Sweep {
    lines: Vec<SweepLine>,
    /// Frontier runs (log₁₀ cost, log₁₀ error), ringed on the cost chart.
    rings: Vec<(f64, f64)>,
    /// log₁₀ of the floor band's top.
    band: Option<f64>,
    /// The error axis reaches down into the band (else it spans the runs only).
    show_band: bool,
    /// The explicit limit, s, marked on the dt chart.
    limit: Option<f64>,
    /// The dts the dt chart spans even before a run is drawn, s.
    ladder: Vec<f64>,
    error_title: &'static str,
    /// Said in the charts' middle (nothing drawn).
    note: Option<String>,
}

/// What the view marks of the app's own run: the integrator and dt in use, and whether to
/// draw in ASCII.
#[derive(Debug, Clone, Copy)]
pub struct Shown {
    pub ascii: bool,
    pub in_use: Integrator,
    pub dt: f64,
}

/// A study still running: runs finished, runs in all, the estimated time left.
#[derive(Debug, Clone, Copy)]
pub struct Progress {
    pub done: usize,
    pub total: usize,
    pub left: Option<std::time::Duration>,
}

/// The background of the floor band's cells.
const BAND: Color = Color::Rgb(58, 58, 58);

/// One line of a chart: its colour and (log₁₀ x, log₁₀ y) points in order.
struct Series {
    color: Color,
    points: Vec<(f64, f64)>,
}

/// A log–log chart drawn on a [`Canvas`] with its own axes, so that the floor band can be laid
/// under the exact rows the canvas maps below the floor: y title on the first row, decade
/// labels left and under the plot, the x title in the bottom border.
struct LogChart<'a> {
    title: String,
    x_title: &'a str,
    y_title: &'a str,
    /// log₁₀ bounds, whole decades.
    x: (f64, f64),
    y: (f64, f64),
    /// log₁₀ of the floor: the rows at and below it are the band.
    band: Option<f64>,
    series: Vec<Series>,
    /// Frontier runs, ringed.
    rings: Vec<(f64, f64)>,
    /// log₁₀ x of a vertical dashed mark (the explicit limit 2/ω_max).
    limit: Option<f64>,
    /// Text beside a point (log₁₀ x, log₁₀ y) in a colour, the first of the texts that fits:
    /// each line's fitted order.
    labels: Vec<((f64, f64), Color, Vec<String>)>,
    /// Said in the plot's middle (nothing to draw).
    note: Option<String>,
    ascii: bool,
}

/// The cell (0 at the low end) a value falls in, as the canvas maps it: `sub` dots per cell
/// (braille: 2 across, 4 down; one per cell in ASCII), truncated as the canvas does.
fn cell(offset: f64, span: f64, cells: u16, sub: u16) -> u16 {
    let dots = f64::from(cells * sub);
    let dot = (offset * (dots - 1.0) / span).max(0.0) as u16;
    (dot / sub).min(cells.saturating_sub(1))
}

impl Widget for LogChart<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        use ratatui::widgets::canvas::{Canvas, Line as Segment};
        let block = Block::bordered()
            .title(self.title.clone())
            .title_bottom(Line::from(format!(" {} ", self.x_title)).right_aligned());
        let inner = block.inner(area);
        block.render(area, buf);
        let ((x0, x1), (y0, y1)) = (self.x, self.y);
        let y_labels: Vec<(f64, String)> = (y0.round() as i32..=y1.round() as i32)
            .map(|e| (f64::from(e), format!("1e{e}")))
            .collect();
        let gutter = y_labels.iter().map(|(_, l)| l.len()).max().unwrap_or(3) as u16 + 1;
        if inner.width < gutter + 8 || inner.height < 6 {
            return;
        }
        let axis = theme::CHART_AXIS;
        buf.set_stringn(inner.x, inner.y, self.y_title, inner.width as usize, axis);
        let plot = Rect {
            x: inner.x + gutter,
            y: inner.y + 1,
            width: inner.width - gutter,
            height: inner.height - 3,
        };
        let (sub_x, sub_y) = if self.ascii { (1, 1) } else { (2, 4) };
        let row = |y: f64| plot.bottom() - 1 - cell(y - y0, y1 - y0, plot.height, sub_y);
        let col = |x: f64| plot.x + cell(x - x0, x1 - x0, plot.width, sub_x);
        let marker = if self.ascii {
            Marker::Dot
        } else {
            Marker::Braille
        };
        let rings = if self.ascii { "O" } else { "◆" };
        Canvas::default()
            .x_bounds([x0, x1])
            .y_bounds([y0, y1])
            .marker(marker)
            .paint(|ctx| {
                for series in &self.series {
                    for pair in series.points.windows(2) {
                        ctx.draw(&Segment::new(
                            pair[0].0,
                            pair[0].1,
                            pair[1].0,
                            pair[1].1,
                            series.color,
                        ));
                    }
                    if let [only] = series.points[..] {
                        ctx.draw(&Segment::new(only.0, only.1, only.0, only.1, series.color));
                    }
                }
            })
            .render(plot, buf);
        // The band: every cell at or below the floor's row, a dot in each other empty one.
        if let Some(top) = self.band.filter(|&t| t > y0) {
            let first = if top >= y1 { plot.y } else { row(top) };
            for r in first..plot.bottom() {
                for c in plot.x..plot.right() {
                    let cell = &mut buf[(c, r)];
                    if cell.symbol() == " " && (c - plot.x).is_multiple_of(2) {
                        cell.set_symbol(if self.ascii { "." } else { "·" });
                        cell.set_fg(Color::Gray);
                    }
                    cell.set_bg(BAND);
                }
            }
        }
        for &(x, y) in &self.rings {
            if (x0..=x1).contains(&x) && (y0..=y1).contains(&y) {
                buf[(col(x), row(y))]
                    .set_symbol(rings)
                    .set_style(theme::FRONTIER);
            }
        }
        // The explicit limit: a dashed column in the empty cells, named on the top row.
        if let Some(l) = self.limit.filter(|l| (x0..=x1).contains(l)) {
            let c = col(l);
            for r in plot.y..plot.bottom() {
                let cell = &mut buf[(c, r)];
                if (r - plot.y).is_multiple_of(2) && matches!(cell.symbol(), " " | "·" | ".") {
                    cell.set_symbol(if self.ascii { ":" } else { "┆" });
                    cell.set_fg(LIMIT.fg.unwrap_or(Color::Yellow));
                }
            }
            let name = "2/ω_max";
            let width = name.chars().count() as u16;
            let x = if c + 1 + width <= plot.right() {
                c + 1
            } else {
                c.saturating_sub(width).max(plot.x)
            };
            buf.set_stringn(x, plot.y, name, width as usize, LIMIT);
        }
        // Each label beside its point over empty cells only: right of it, else left, on its
        // row, else on a row above or below (two at most).
        for ((x, y), color, texts) in &self.labels {
            if !((x0..=x1).contains(x) && (y0..=y1).contains(y)) {
                continue;
            }
            let (c, r) = (col(*x), row(*y));
            let spot = |width: u16, buf: &Buffer| {
                let rows = [
                    Some(r),
                    r.checked_sub(1),
                    Some(r + 1),
                    r.checked_sub(2),
                    Some(r + 2),
                ];
                let starts = [Some(c + 2), c.checked_sub(width + 1)];
                rows.into_iter().flatten().find_map(|r| {
                    starts.into_iter().flatten().find_map(|start| {
                        let fits = start >= plot.x
                            && start + width <= plot.right()
                            && (plot.y..plot.bottom()).contains(&r)
                            && (start..start + width)
                                .all(|k| matches!(buf[(k, r)].symbol(), " " | "·" | "."));
                        fits.then_some((start, r))
                    })
                })
            };
            for text in texts {
                if let Some((start, r)) = spot(text.chars().count() as u16, buf) {
                    buf.set_string(start, r, text, Style::new().fg(*color));
                    break;
                }
            }
        }
        // Axes and decade labels.
        for r in plot.y..plot.bottom() {
            buf[(plot.x - 1, r)].set_symbol("│").set_style(axis);
        }
        buf[(plot.x - 1, plot.bottom())]
            .set_symbol("└")
            .set_style(axis);
        for c in plot.x..plot.right() {
            buf[(c, plot.bottom())].set_symbol("─").set_style(axis);
        }
        let rows_per_decade = f64::from(plot.height) / (y1 - y0).max(1.0);
        let stride = (2.0 / rows_per_decade).ceil().max(1.0) as usize;
        let mut last_row = None;
        for (value, label) in y_labels.iter().rev().step_by(stride) {
            let r = row(*value);
            if last_row.is_some_and(|l: u16| r <= l) {
                continue;
            }
            last_row = Some(r);
            let x = plot.x - 1 - label.len() as u16;
            buf.set_string(x, r, label, axis);
        }
        let mut free = inner.x;
        for e in x0.round() as i32..=x1.round() as i32 {
            let label = format!("1e{e}");
            let width = label.len() as u16;
            let centre = col(f64::from(e));
            let start = centre
                .saturating_sub(width / 2)
                .clamp(inner.x, inner.right().saturating_sub(width));
            if start < free {
                continue;
            }
            buf.set_string(start, plot.bottom() + 1, &label, axis);
            free = start + width + 1;
        }
        if let Some(note) = &self.note {
            let width = note.chars().count().min(plot.width as usize) as u16;
            let x = plot.x + (plot.width - width) / 2;
            buf.set_stringn(
                x,
                plot.y + plot.height / 2,
                note,
                width as usize,
                theme::ERROR,
            );
        }
    }
}

/// The log₁₀ of an error as drawn (exact zeros at 1e-16).
fn log_error(e: f64) -> f64 {
    e.max(1e-16).log10()
}

/// The pairs of integrators whose drawn points coincide (the same dts, errors within 5 %):
/// one line hides the other on the chart.
fn coinciding(study: &SceneStudy) -> Vec<(Integrator, Integrator)> {
    let runs = |i: Integrator| -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = study
            .rows
            .iter()
            .filter(|r| r.integrator == i && r.ok() && r.measure().is_finite())
            .map(|r| (r.dt, r.measure()))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let mut pairs = Vec::new();
    for (k, &a) in Integrator::ALL.iter().enumerate() {
        for &b in &Integrator::ALL[k + 1..] {
            let (ra, rb) = (runs(a), runs(b));
            let same = !ra.is_empty()
                && ra.len() == rb.len()
                && ra.iter().zip(&rb).all(|(p, q)| {
                    p.0 == q.0 && (log_error(p.1) - log_error(q.1)).abs() < 1.05f64.log10()
                });
            if same {
                pairs.push((a, b));
            }
        }
    }
    pairs
}

/// The runs a chart draws (finished, with a finite error and a cost) and their integrators.
fn drawn(study: &SceneStudy) -> (Vec<&crate::study::Row>, Vec<Integrator>) {
    let drawable: Vec<_> = study
        .rows
        .iter()
        .filter(|r| r.ok() && r.measure().is_finite() && r.us_per_simulated_second > 0.0)
        .collect();
    let integrators = Integrator::ALL
        .into_iter()
        .filter(|i| drawable.iter().any(|r| r.integrator == *i))
        .collect();
    (drawable, integrators)
}

/// The study view of a scene's integrators: error against cost and error against dt side by
/// side (the same error axis), the floor band under both, the fitted order beside each
/// integrator in the legend, the diverged runs listed; with `progress`, the runs finished so
/// far under a gauge (the chart fills as the others finish). A cloth case's chart is its
/// particle integrators' (`render_cloth_study`).
pub fn draw_study(
    study: &SceneStudy,
    shown: &Shown,
    progress: Option<Progress>,
    area: Rect,
    buf: &mut Buffer,
) {
    if let Some(cloth) = &study.cloth {
        return render_cloth_study(study, cloth, shown.ascii, progress, area, buf);
    }
    let area = gauge_row(progress, area, buf);
    let (drawable, integrators) = drawn(study);
    let dim = Style::new().add_modifier(Modifier::DIM);
    let order_of = |i: Integrator| {
        study
            .orders
            .iter()
            .find(|o| o.integrator == i)
            .map(|o| match o.slope {
                _ if o.exact => "exact".to_string(),
                Some(s) => format!("p {s:.2}"),
                None => "p –".to_string(),
            })
    };
    // The legend, each entry whole on a line (packed to the text's width).
    let mut entries: Vec<ratatui::text::Span> = integrators
        .iter()
        .map(|&i| {
            let mark = if i == shown.in_use { " (in use)" } else { "" };
            let order = match order_of(i) {
                Some(o) if !study.contact() => format!(" {o}"),
                _ => String::new(),
            };
            ratatui::text::Span::styled(
                format!("── {}{mark}{order}", i.name()),
                Style::new().fg(colour(i)),
            )
        })
        .collect();
    entries.push(frontier_entry(shown.ascii));
    let legend = pack(entries, area);
    let inside = drawable.iter().filter(|r| r.below_floor).count();
    let band_line = format!(
        "{} grey band: below the floor {} (round-off or the reference's own error): the {inside} \
         run{} inside it are not ranked against each other nor fitted",
        if shown.ascii { "..." } else { "···" },
        format_number(study.floor),
        if inside == 1 { "" } else { "s" },
    );
    let diverged: Vec<String> = study
        .rows
        .iter()
        .filter(|r| !r.ok())
        .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)))
        .collect();
    // The lines that matter most first: the legend with the orders, the run in use, the
    // diverged runs, the band; the sentence last (the longest, cut on a small screen).
    let mut text = legend;
    text.push(Line::from(in_use_line(study, shown)));
    text.push(diverged_line(&diverged));
    if study.contact() && study.rows.iter().all(|r| !r.ok()) && progress.is_none() {
        text.push(Line::styled(
            "press c for another collision response, then s twice to study it",
            Style::new().fg(Color::Yellow),
        ));
    }
    text.push(Line::styled(band_line, dim));
    for (a, b) in coinciding(study) {
        text.push(Line::styled(
            format!(
                "{} and {} coincide at every dt: one line hides the other",
                a.name(),
                b.name()
            ),
            dim,
        ));
    }
    text.push(frontier_line(
        study
            .rows
            .iter()
            .filter(|r| r.frontier)
            .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt))),
    ));
    text.push(Line::from(study.sentence.clone()));
    let title = format!(
        " study of {} ({} s, {} reference) ",
        study.name, study.duration, study.reference_kind
    );
    layout_study(&bodies_sweep(study), text, title, shown.ascii, area, buf);
}

/// The bodies' two charts: error against cost (frontier ringed) and against dt, the floor band
/// under both.
fn bodies_sweep(study: &SceneStudy) -> Sweep {
    let (drawable, integrators) = drawn(study);
    let lines = integrators
        .iter()
        .map(|&i| {
            let mut rows: Vec<_> = drawable.iter().filter(|r| r.integrator == i).collect();
            rows.sort_by(|a, b| b.dt.total_cmp(&a.dt));
            SweepLine {
                color: colour(i),
                runs: rows
                    .iter()
                    .map(|r| (r.dt, r.us_per_simulated_second, r.measure()))
                    .collect(),
                label: Vec::new(),
            }
        })
        .collect();
    let note = if drawable.is_empty() {
        Some(if study.rows.iter().any(|r| !r.ok()) {
            "every run diverged: nothing to draw".to_string()
        } else {
            "no run finished yet".to_string()
        })
    } else {
        None
    };
    Sweep {
        lines,
        rings: drawable
            .iter()
            .filter(|r| r.frontier)
            .map(|r| (r.us_per_simulated_second.log10(), log_error(r.measure())))
            .collect(),
        band: Some(study.floor.log10()),
        show_band: false,
        limit: None,
        ladder: Vec::new(),
        error_title: if study.contact() {
            "contact error (worst body)"
        } else {
            "error, rad (worst body)"
        },
        note,
    }
}

/// The two charts of a study: error against cost (frontier ringed) and against dt (the
/// explicit limit marked, each line's label beside its finest run), on the same error axis,
/// the floor band under both.
fn draw_charts(sweep: &Sweep, ascii: bool, cost_area: Rect, dt_area: Rect, buf: &mut Buffer) {
    let series = |x: &dyn Fn(&(f64, f64, f64)) -> f64| -> Vec<Series> {
        sweep
            .lines
            .iter()
            .map(|l| Series {
                color: l.color,
                points: l.runs.iter().map(|r| (x(r), log_error(r.2))).collect(),
            })
            .collect()
    };
    let cost = |r: &(f64, f64, f64)| r.1.log10();
    let step = |r: &(f64, f64, f64)| r.0.log10();
    let runs = || sweep.lines.iter().flat_map(|l| &l.runs);
    let all_cost: Vec<(f64, f64)> = runs().map(|r| (cost(r), log_error(r.2))).collect();
    // The band's top a little above the axis' foot, so that its rows show.
    let band_foot = sweep
        .band
        .filter(|_| sweep.show_band)
        .and_then(|b| all_cost.first().map(|p| (p.0, b - 0.3)));
    let framed: Vec<(f64, f64)> = all_cost.iter().copied().chain(band_foot).collect();
    let all_dt: Vec<(f64, f64)> = runs()
        .map(|r| (step(r), log_error(r.2)))
        .chain(
            sweep
                .ladder
                .iter()
                .chain(&sweep.limit)
                .map(|dt| (dt.log10(), all_cost.first().map_or(0.0, |p| p.1))),
        )
        .collect();
    let ((cx0, cx1), (ey0, ey1)) = bounds(&framed);
    let ((dx0, dx1), _) = bounds(&all_dt);
    LogChart {
        title: " error against cost, log–log ".to_string(),
        x_title: "µs per simulated s",
        y_title: sweep.error_title,
        x: (cx0, cx1),
        y: (ey0, ey1),
        band: sweep.band,
        series: series(&cost),
        rings: sweep.rings.clone(),
        limit: None,
        labels: Vec::new(),
        note: sweep.note.clone(),
        ascii,
    }
    .render(cost_area, buf);
    LogChart {
        title: " error against dt: slope = p ".to_string(),
        x_title: "dt, s",
        y_title: sweep.error_title,
        x: (dx0, dx1),
        y: (ey0, ey1),
        band: sweep.band,
        series: series(&step),
        rings: Vec::new(),
        limit: sweep.limit.map(f64::log10),
        labels: sweep
            .lines
            .iter()
            .filter_map(|l| {
                let finest = l.runs.last()?;
                (!l.label.is_empty()).then(|| {
                    (
                        (step(finest), log_error(finest.2)),
                        l.color,
                        l.label.clone(),
                    )
                })
            })
            .collect(),
        note: sweep.note.clone(),
        ascii,
    }
    .render(dt_area, buf);
}

/// "in use: rk4 at dt = 0.001 s; the study's nearest run (dt = 1e-3): error 3.1e-9".
fn in_use_line(study: &SceneStudy, shown: &Shown) -> String {
    let (in_use, dt) = (shown.in_use, shown.dt);
    let nearest = study
        .rows
        .iter()
        .filter(|r| r.integrator == in_use)
        .min_by(|a, b| (a.dt / dt).ln().abs().total_cmp(&(b.dt / dt).ln().abs()));
    match nearest {
        Some(r) if r.ok() => format!(
            "in use: {} at dt = {} s; the study's nearest run (dt = {}): {} {}",
            in_use.name(),
            format_number(dt),
            format_dt(r.dt),
            if study.contact() {
                "contact error"
            } else {
                "error"
            },
            format_number(r.measure()),
        ),
        Some(r) => format!(
            "in use: {} at dt = {} s; the study's nearest run (dt = {}) diverged",
            in_use.name(),
            format_number(dt),
            format_dt(r.dt)
        ),
        None => format!("in use: {} (not in the study yet)", in_use.name()),
    }
}
