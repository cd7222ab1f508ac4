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
use crate::study::cloth::ClothStudy;
use crate::study::{plot, Case, Config, SceneStudy};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::Line;
use ratatui::widgets::{Axis, Block, Chart, Dataset, Gauge, GraphType, Paragraph, Widget, Wrap};

/// Starts the study of a lesson's scene (every integrator, dt = 1e-1 … 1e-4) with the
/// collision response in use.
pub fn spawn(app: &App) -> Job {
    let mut case = Case::from_lesson(&app.lesson);
    case.scene.contact = app.world.contact_model().copied();
    Job::spawn(case, Config::default())
}

/// The study was made with the collision response in use (else it must be made again).
pub fn is_current(job: &Job, app: &App) -> bool {
    job.response == app.world.contact_model().map(|m| m.response)
}

/// The colour of an integrator, as in the SVG plot.
fn colour(integrator: Integrator) -> Color {
    let plotters::style::RGBColor(r, g, b) = plot::color(integrator);
    Color::Rgb(r, g, b)
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let Some(job) = &app.study else {
        Paragraph::new("press s to study this scene")
            .block(Block::bordered().title(" study "))
            .render(area, buf);
        return;
    };
    match job.result() {
        Some(study) => render_study(app, &study, area, buf),
        None => render_progress(job, area, buf),
    }
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
             (the fastest of up to 5 timed runs), the cheapest runs first: the chart appears \
             when all are done.",
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

/// Axis labels at a few decades: "1e-3" …
fn labels(lo: f64, hi: f64) -> Vec<String> {
    let span = (hi - lo).round() as i32;
    let stride = (span / 5 + 1).max(1);
    let mut out = Vec::new();
    let mut e = lo.round() as i32;
    while e <= hi.round() as i32 {
        out.push(format!("1e{e}"));
        e += stride;
    }
    if out.len() == 1 {
        out.push(format!("1e{}", hi.round() as i32));
    }
    out
}

/// The colour of a particle integrator, as in the SVG plot.
fn cloth_colour(integrator: ClothIntegrator) -> Color {
    let plotters::style::RGBColor(r, g, b) = plot::cloth_color(integrator);
    Color::Rgb(r, g, b)
}

/// The cloth case: max particle error against cost, one line per particle integrator.
fn render_cloth_study(
    app: &App,
    study: &SceneStudy,
    cloth: &ClothStudy,
    area: Rect,
    buf: &mut Buffer,
) {
    let text_height = (area.height / 3).clamp(4, 9);
    let [chart_area, text_area] =
        Layout::vertical([Constraint::Min(8), Constraint::Length(text_height)]).areas(area);
    let points = |integrator: Option<ClothIntegrator>, frontier_only: bool| -> Vec<(f64, f64)> {
        let mut rows: Vec<_> = cloth
            .rows
            .iter()
            .filter(|r| r.ok() && r.error > 0.0 && r.us_per_simulated_second > 0.0)
            .filter(|r| integrator.is_none_or(|i| r.integrator == i))
            .filter(|r| !frontier_only || r.frontier)
            .collect();
        rows.sort_by(|a, b| b.dt.total_cmp(&a.dt));
        rows.iter()
            .map(|r| (r.us_per_simulated_second.log10(), r.error.log10()))
            .collect()
    };
    let all = points(None, false);
    let ((x0, x1), (y0, y1)) = bounds(&all);
    let marker = if app.ascii {
        Marker::Dot
    } else {
        Marker::Braille
    };
    let lines: Vec<(ClothIntegrator, Vec<(f64, f64)>)> = ClothIntegrator::ALL
        .into_iter()
        .map(|i| (i, points(Some(i), false)))
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let frontier = points(None, true);
    let mut datasets: Vec<Dataset> = lines
        .iter()
        .map(|(i, p)| {
            Dataset::default()
                .name(i.name())
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(cloth_colour(*i)))
                .data(p)
        })
        .collect();
    datasets.push(
        Dataset::default()
            .name("frontier")
            .marker(Marker::Block)
            .graph_type(GraphType::Scatter)
            .style(theme::FRONTIER)
            .data(&frontier),
    );
    let axis = |title: &'static str, lo: f64, hi: f64| {
        Axis::default()
            .title(title)
            .style(theme::CHART_AXIS)
            .bounds([lo, hi])
            .labels(labels(lo, hi))
    };
    Chart::new(datasets)
        .block(Block::bordered().title(format!(
            " study of {} ({} s, cloth case, 2/ω_max = {} s): particle error against cost, \
             log–log ",
            study.name,
            study.duration,
            format_number(cloth.limit)
        )))
        .x_axis(axis("µs per simulated s", x0, x1))
        .y_axis(axis("error, m", y0, y1))
        .legend_position(None)
        .render(chart_area, buf);
    let mut legend: Vec<ratatui::text::Span> = vec![ratatui::text::Span::raw(" ")];
    for (i, _) in &lines {
        legend.push(ratatui::text::Span::styled(
            format!("── {}  ", i.name()),
            Style::new().fg(cloth_colour(*i)),
        ));
    }
    legend.push(ratatui::text::Span::raw("█ frontier"));
    let orders: Vec<String> = cloth
        .orders
        .iter()
        .map(|o| match o.slope {
            Some(s) => format!("{} {:.1}", o.integrator.name(), s),
            None => format!("{} –", o.integrator.name()),
        })
        .collect();
    let diverged: Vec<String> = cloth
        .rows
        .iter()
        .filter(|r| !r.ok())
        .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)))
        .collect();
    let text = vec![
        Line::from(legend),
        Line::from(cloth.sentence.clone()),
        Line::styled(
            format!(
                "observed orders below 2/ω_max: {}; diverged (no point): {}",
                orders.join(", "),
                if diverged.is_empty() {
                    "none".to_string()
                } else {
                    diverged.join(", ")
                }
            ),
            Style::new().add_modifier(Modifier::DIM),
        ),
    ];
    Paragraph::new(text)
        .block(Block::bordered().title(" reference: numeric (converged symplectic-euler) "))
        .wrap(Wrap { trim: true })
        .render(text_area, buf);
}

fn render_study(app: &App, study: &SceneStudy, area: Rect, buf: &mut Buffer) {
    if let Some(cloth) = &study.cloth {
        render_cloth_study(app, study, cloth, area, buf);
        return;
    }
    let text_height = (area.height / 3).clamp(4, 9);
    let [chart_area, text_area] =
        Layout::vertical([Constraint::Min(8), Constraint::Length(text_height)]).areas(area);
    let points = |integrator: Option<Integrator>, frontier_only: bool| -> Vec<(f64, f64)> {
        let mut rows: Vec<_> = study
            .rows
            .iter()
            .filter(|r| r.ok() && r.measure().is_finite() && r.us_per_simulated_second > 0.0)
            .filter(|r| integrator.is_none_or(|i| r.integrator == i))
            .filter(|r| !frontier_only || r.frontier)
            .collect();
        rows.sort_by(|a, b| b.dt.total_cmp(&a.dt));
        rows.iter()
            .map(|r| {
                (
                    r.us_per_simulated_second.log10(),
                    r.measure().max(1e-16).log10(),
                )
            })
            .collect()
    };
    let all = points(None, false);
    let ((x0, x1), (y0, y1)) = bounds(&all);
    let marker = if app.ascii {
        Marker::Dot
    } else {
        Marker::Braille
    };
    let in_use = app.world.integrator();
    let names: Vec<String> = Integrator::ALL
        .into_iter()
        .map(|i| {
            if i == in_use {
                format!("{} (in use)", i.name())
            } else {
                i.name().to_string()
            }
        })
        .collect();
    let lines: Vec<(Integrator, Vec<(f64, f64)>)> = Integrator::ALL
        .into_iter()
        .map(|i| (i, points(Some(i), false)))
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let frontier = points(None, true);
    let mut datasets: Vec<Dataset> = lines
        .iter()
        .map(|(i, p)| {
            let index = Integrator::ALL.iter().position(|x| x == i).unwrap_or(0);
            let style = Style::new().fg(colour(*i));
            Dataset::default()
                .name(names[index].clone())
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(if *i == in_use {
                    style.add_modifier(Modifier::BOLD)
                } else {
                    style
                })
                .data(p)
        })
        .collect();
    datasets.push(
        Dataset::default()
            .name("frontier")
            .marker(Marker::Block)
            .graph_type(GraphType::Scatter)
            .style(theme::FRONTIER)
            .data(&frontier),
    );
    let axis = |title: &'static str, lo: f64, hi: f64| {
        Axis::default()
            .title(title)
            .style(theme::CHART_AXIS)
            .bounds([lo, hi])
            .labels(labels(lo, hi))
    };
    Chart::new(datasets)
        .block(Block::bordered().title(format!(
            " study of {} ({} s, {} reference): error against cost, log–log ",
            study.name, study.duration, study.reference_kind
        )))
        .x_axis(axis("µs per simulated s", x0, x1))
        .y_axis(axis(
            if study.contact() {
                "contact error"
            } else {
                "error, rad"
            },
            y0,
            y1,
        ))
        // The legend goes under the chart, where it cannot cover a curve.
        .legend_position(None)
        .render(chart_area, buf);
    let mut legend: Vec<ratatui::text::Span> = vec![ratatui::text::Span::raw(" ")];
    for (i, _) in &lines {
        let mark = if *i == in_use { " (in use)" } else { "" };
        legend.push(ratatui::text::Span::styled(
            format!("── {}{mark}  ", i.name()),
            Style::new().fg(colour(*i)),
        ));
    }
    legend.push(ratatui::text::Span::raw("█ frontier"));
    let orders: Vec<String> = study
        .orders
        .iter()
        .map(|o| match o.slope {
            _ if o.exact => format!("{} exact", o.integrator.name()),
            Some(s) => format!("{} {:.1}", o.integrator.name(), s),
            None => format!("{} –", o.integrator.name()),
        })
        .collect();
    let best = study
        .rows
        .iter()
        .filter(|r| r.frontier)
        .map(|r| format!("{} {}", r.integrator.name(), format_dt(r.dt)));
    let dt = app.world.dt();
    let nearest = study
        .rows
        .iter()
        .filter(|r| r.integrator == in_use)
        .min_by(|a, b| (a.dt / dt).ln().abs().total_cmp(&(b.dt / dt).ln().abs()));
    let in_use_line = match nearest {
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
        None => format!("in use: {} (not in the study)", in_use.name()),
    };
    let all_diverged = study.rows.iter().all(|r| !r.ok());
    let mut text = vec![Line::from(legend), Line::from(study.sentence.clone())];
    if all_diverged && study.contact() {
        text.push(Line::styled(
            "press c for another collision response, then s twice to study it",
            Style::new().fg(Color::Yellow),
        ));
    }
    if !study.contact() {
        text.push(Line::styled(
            format!("observed orders: {}", orders.join(", ")),
            Style::new().add_modifier(Modifier::DIM),
        ));
    }
    text.push(Line::from(in_use_line));
    text.push(Line::styled(
        format!(
            "frontier (█ on the chart, cheapest first): {}",
            best.collect::<Vec<_>>().join(", ")
        ),
        Style::new().add_modifier(Modifier::DIM),
    ));
    Paragraph::new(text)
        .block(Block::bordered().title(format!(" reference: {} ", study.reference_kind)))
        .wrap(Wrap { trim: true })
        .render(text_area, buf);
}
