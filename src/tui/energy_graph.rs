//! The energy graph: kinetic, potential and total energy over time (and the compare world's
//! total), with their drift (E − E₀ less the drag work and contact energy the energy ledger
//! booked) below on its own scale; axes only grow, by doubling.

use super::app::App;
use super::series::Range;
use crate::tables::number_plain;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, LegendPosition, Widget};

fn axis<'a>(title: &'a str, range: Range) -> Axis<'a> {
    let mid = 0.5 * (range.lo + range.hi);
    Axis::default()
        .title(title)
        .style(Style::new().fg(Color::Gray))
        .bounds([range.lo, range.hi])
        .labels([
            number_plain(range.lo),
            number_plain(mid),
            number_plain(range.hi),
        ])
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let series = &app.series;
    let samples = series.samples();
    let pick = |f: &dyn Fn(&super::series::Sample) -> Option<f64>| -> Vec<(f64, f64)> {
        samples
            .iter()
            .filter_map(|s| f(s).map(|y| (s.t, y)))
            .collect()
    };
    let kinetic = pick(&|s| Some(s.kinetic));
    let potential = pick(&|s| Some(s.potential));
    let total = pick(&|s| Some(s.total));
    let compare = pick(&|s| s.compare_total);
    let drift = pick(&|s| Some(s.drift));
    let marker = if app.ascii {
        Marker::Dot
    } else {
        Marker::Braille
    };
    let dataset = |name: String, data, colour| {
        Dataset::default()
            .name(name)
            .marker(marker)
            .graph_type(GraphType::Line)
            .style(Style::new().fg(colour))
            .data(data)
    };
    let mut energies = vec![
        dataset("kinetic".into(), &kinetic, Color::Green),
        dataset("potential".into(), &potential, Color::Blue),
        dataset("total".into(), &total, Color::White),
    ];
    if let Some(g) = &app.ghost {
        energies.push(dataset(
            format!("total ({})", g.comparison.name()),
            &compare,
            Color::Magenta,
        ));
    }
    let [top, bottom] =
        Layout::vertical([Constraint::Percentage(65), Constraint::Percentage(35)]).areas(area);
    Chart::new(energies)
        .block(Block::bordered().title(" energy, J "))
        .x_axis(axis("t, s", series.time_axis))
        .y_axis(axis("J", series.energy_axis))
        .legend_position(Some(LegendPosition::TopRight))
        .hidden_legend_constraints((Constraint::Ratio(1, 1), Constraint::Ratio(1, 1)))
        .render(top, buf);
    Chart::new(vec![dataset("drift".into(), &drift, Color::Red)])
        .block(Block::bordered().title(" drift (E − E₀ not booked), J "))
        .x_axis(axis("t, s", series.time_axis))
        .y_axis(axis("J", series.drift_axis))
        .legend_position(None)
        .render(bottom, buf);
}
