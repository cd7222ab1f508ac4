//! The energy graph: kinetic, potential and total energy over time (and the compare world's
//! total), with their drift (E − E₀ less the drag work and contact energy the energy ledger
//! booked) below on its own scale; axes only grow, by doubling.

use super::app::App;
use super::series::Range;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Style;
use ratatui::symbols::Marker;
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, LegendPosition, Widget};

/// An axis label with the digits the axis needs: two significant digits of its span
/// (`172.7` on an axis spanning 3, not `172.741806`); scientific beyond 1e-4 and 1e5.
pub fn axis_label(x: f64, span: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    if !(1e-4..1e5).contains(&x.abs()) {
        return format!("{x:.1e}");
    }
    let decimals = (1.0 - span.abs().max(1e-12).log10().floor()).clamp(0.0, 6.0) as usize;
    let s = format!("{x:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".to_string()
    } else {
        s
    }
}

fn axis<'a>(title: &'a str, range: Range) -> Axis<'a> {
    let mid = 0.5 * (range.lo + range.hi);
    let span = range.hi - range.lo;
    Axis::default()
        .title(title)
        .style(theme::CHART_AXIS)
        .bounds([range.lo, range.hi])
        .labels([
            axis_label(range.lo, span),
            axis_label(mid, span),
            axis_label(range.hi, span),
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
        dataset("kinetic".into(), &kinetic, theme::KINETIC),
        dataset("potential".into(), &potential, theme::POTENTIAL),
        dataset("total".into(), &total, theme::TOTAL),
    ];
    if let Some(g) = &app.ghost {
        energies.push(dataset(
            format!("total ({})", g.comparison.name()),
            &compare,
            theme::GHOST,
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
    Chart::new(vec![dataset("drift".into(), &drift, theme::DRIFT)])
        .block(Block::bordered().title(" drift (E − E₀ not booked), J "))
        .x_axis(axis("t, s", series.time_axis))
        .y_axis(axis("J", series.drift_axis))
        .legend_position(None)
        .render(bottom, buf);
}

#[cfg(test)]
mod tests {
    use super::axis_label;

    #[test]
    fn axis_labels_carry_two_significant_digits_of_the_span() {
        // Span 10: the labels (lo, mid, hi) are 5 apart, so units are enough.
        assert_eq!(axis_label(172.741806, 10.0), "173");
        // Span 3: labels 1.5 apart, one decimal.
        assert_eq!(axis_label(172.741806, 3.0), "172.7");
        // Span 0.002: four decimals.
        assert_eq!(axis_label(30.692080, 0.002), "30.6921");
        // Whole numbers lose their zeros; zero prints as 0, -0 too.
        assert_eq!(axis_label(2.0, 2.0), "2");
        assert_eq!(axis_label(-0.00001, 100.0), "-1.0e-5");
        assert_eq!(axis_label(-0.01, 100.0), "0");
        assert_eq!(axis_label(1.5e-7, 1e-6), "1.5e-7");
    }
}
