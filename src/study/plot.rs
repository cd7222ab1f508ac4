//! `--svg PATH`: error against cost on log–log axes, one panel per scene, one line per
//! integrator (its points in order of dt, each labelled with its dt); frontier runs are ringed.
//! A cloth case's panel has one line per particle integrator (error in m; runs past the
//! explicit limit that diverged have no point).

use super::analysis::format_dt;
use super::cloth::ClothStudy;
use super::SceneStudy;
use crate::physics::cloth::ClothIntegrator;
use crate::physics::Integrator;
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

/// Writes the plot; the error is a one-line message.
pub fn svg(studies: &[SceneStudy], path: &Path) -> Result<(), String> {
    let panels = studies.len().max(1);
    let columns = if panels > 1 { 2 } else { 1 };
    let rows = panels.div_ceil(columns);
    let width = 640 * columns as u32;
    let header = header_height(width, studies.iter().any(|s| s.cloth.is_some()));
    let size = (width, header + 480 * rows as u32);
    let root = SVGBackend::new(path, size).into_drawing_area();
    let fail = |e: &dyn std::fmt::Display| format!("cannot draw {}: {e}", path.display());
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let (header, body) = root.split_vertically(header);
    legend(&header, studies.iter().any(|s| s.cloth.is_some())).map_err(|e| fail(&e))?;
    let areas = body.split_evenly((rows, columns));
    for (study, area) in studies.iter().zip(areas.iter()) {
        match &study.cloth {
            Some(cloth) => cloth_panel(study, cloth, area),
            None => panel(study, area),
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

/// Height of the title and shared legend strip, px: the title, then rows of legend entries.
fn header_height(width: u32, cloth: bool) -> u32 {
    let entries = Integrator::ALL.len() + usize::from(cloth);
    let rows = entries.div_ceil(legend_per_row(width)) as u32;
    36 + 20 * rows
}

/// The title and one legend for every panel (a legend inside a panel would hide its points).
fn legend(area: &Area, cloth: bool) -> Result<(), Box<dyn std::error::Error>> {
    area.draw(&Text::new(
        "tumble study: error against cost, log–log (lower left is better; ringed = Pareto \
         frontier; labels = dt in s)",
        (16, 8),
        ("sans-serif", 16).into_font(),
    ))?;
    let per_row = legend_per_row(area.dim_in_pixel().0);
    let mut entries: Vec<(&str, RGBColor)> = Integrator::ALL
        .into_iter()
        .map(|i| (i.name(), color(i)))
        .collect();
    if cloth {
        let i = ClothIntegrator::ImplicitEuler;
        entries.push((i.name(), cloth_color(i)));
    }
    for (k, (name, c)) in entries.into_iter().enumerate() {
        let x = 16 + (LEGEND_ENTRY * (k % per_row) as u32) as i32;
        let y = 40 + 20 * (k / per_row) as i32;
        area.draw(&PathElement::new(
            vec![(x, y), (x + 28, y)],
            c.stroke_width(3),
        ))?;
        area.draw(&Text::new(
            name,
            (x + 34, y - 7),
            ("sans-serif", 14).into_font().color(&c),
        ))?;
    }
    Ok(())
}

/// Error against cost, both axes logarithmic.
type CostChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// A log–log chart of error against cost, framed around (µs per simulated second, error)
/// `points` (errors below [`FLOOR`] drawn at it), with its caption and axes drawn.
fn cost_chart<'a, 'b>(
    area: &'a Area<'b>,
    caption: &str,
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
        .x_desc("cost: µs of wall time per simulated second")
        .y_desc(error)
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;
    Ok(chart)
}

fn panel(study: &SceneStudy, area: &Area) -> Result<(), Box<dyn std::error::Error>> {
    let ok: Vec<_> = study
        .rows
        .iter()
        .filter(|r| r.ok() && r.error.is_finite() && r.us_per_simulated_second > 0.0)
        .collect();
    let caption = format!(
        "{} ({} s, {} reference)",
        study.name, study.duration, study.reference_kind
    );
    let points = ok.iter().map(|r| (r.us_per_simulated_second, r.error));
    let mut chart = cost_chart(area, &caption, "error, rad", points)?;
    let mut integrators: Vec<Integrator> = ok.iter().map(|r| r.integrator).collect();
    integrators.dedup();
    integrators.sort_by_key(|i| Integrator::ALL.iter().position(|a| a == i));
    integrators.dedup();
    for integrator in integrators {
        let c = color(integrator);
        let mut points: Vec<_> = ok.iter().filter(|r| r.integrator == integrator).collect();
        points.sort_by(|a, b| b.dt.total_cmp(&a.dt));
        let xy: Vec<(f64, f64)> = points
            .iter()
            .map(|r| (r.us_per_simulated_second, r.error.max(FLOOR)))
            .collect();
        chart.draw_series(LineSeries::new(xy.clone(), c.stroke_width(2)))?;
        chart.draw_series(xy.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
        chart.draw_series(points.iter().map(|r| {
            Text::new(
                format_dt(r.dt),
                (r.us_per_simulated_second, r.error.max(FLOOR)),
                ("sans-serif", 11).into_font().color(&c),
            )
        }))?;
    }
    chart.draw_series(ok.iter().filter(|r| r.frontier).map(|r| {
        Circle::new(
            (r.us_per_simulated_second, r.error.max(FLOOR)),
            7,
            BLACK.stroke_width(1),
        )
    }))?;
    Ok(())
}

/// The cloth case's panel: error (m) against cost, one line per particle integrator.
fn cloth_panel(
    study: &SceneStudy,
    cloth: &ClothStudy,
    area: &Area,
) -> Result<(), Box<dyn std::error::Error>> {
    let ok: Vec<_> = cloth
        .rows
        .iter()
        .filter(|r| r.ok() && r.error.is_finite() && r.us_per_simulated_second > 0.0)
        .collect();
    let caption = format!(
        "{} ({} s, cloth case, 2/ω_max = {:.3e} s)",
        study.name, study.duration, cloth.limit
    );
    let points = ok.iter().map(|r| (r.us_per_simulated_second, r.error));
    let mut chart = cost_chart(area, &caption, "max particle error, m", points)?;
    for integrator in ClothIntegrator::ALL {
        let c = cloth_color(integrator);
        let points: Vec<_> = ok.iter().filter(|r| r.integrator == integrator).collect();
        let xy: Vec<(f64, f64)> = points
            .iter()
            .map(|r| (r.us_per_simulated_second, r.error.max(FLOOR)))
            .collect();
        chart.draw_series(LineSeries::new(xy.clone(), c.stroke_width(2)))?;
        chart.draw_series(xy.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
        chart.draw_series(points.iter().map(|r| {
            Text::new(
                format_dt(r.dt),
                (r.us_per_simulated_second, r.error.max(FLOOR)),
                ("sans-serif", 11).into_font().color(&c),
            )
        }))?;
    }
    chart.draw_series(ok.iter().filter(|r| r.frontier).map(|r| {
        Circle::new(
            (r.us_per_simulated_second, r.error.max(FLOOR)),
            7,
            BLACK.stroke_width(1),
        )
    }))?;
    Ok(())
}
