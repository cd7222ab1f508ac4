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
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Widget};

/// An axis label with the digits the axis needs: the value rounded to two significant digits
/// of the span (`172.7` on an axis spanning 3, not `172.741806`), so a value within that
/// rounding of 0 prints `0` (the middle of a range symmetric about 0 is `2e-14` in floating
/// point, not a number to print). Scientific below 1e-4 and from 1e5, with the mantissa
/// digits the span needs (`1.5e-7` on a span of 1e-6).
pub fn axis_label(x: f64, span: f64) -> String {
    if !x.is_finite() {
        return crate::tables::number_plain(x);
    }
    let span = span.abs();
    // The place of the span's second significant digit (the span of |x| itself when the
    // axis has none).
    let scale = if span > 0.0 && span.is_finite() {
        span
    } else {
        x.abs()
    };
    if scale == 0.0 {
        return "0".to_string();
    }
    let step = scale.log10().floor() as i32 - 1;
    if x.abs() < 0.5 * 10f64.powi(step) {
        return "0".to_string();
    }
    let s = if (1e-4..1e5).contains(&x.abs()) && step >= -12 {
        let decimals = (-step).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let exponent = x.abs().log10().floor() as i32;
        let digits = (exponent - step).clamp(1, 12) as usize;
        format!("{x:.digits$e}")
    };
    if s == "-0" {
        "0".to_string()
    } else {
        s
    }
}

/// An axis with its labels at the ends and, when `room` (rows of a vertical axis, columns of
/// a horizontal one) leaves a gap between them, in the middle: labels never share a row or
/// run into each other (a drift chart 3 rows tall printed `0` over `-9.9e-6`).
pub(super) fn axis<'a>(title: &'a str, range: Range, room: u16, label_width: usize) -> Axis<'a> {
    let mid = 0.5 * (range.lo + range.hi);
    let span = range.hi - range.lo;
    let (lo, hi) = (axis_label(range.lo, span), axis_label(range.hi, span));
    let mut labels = vec![lo];
    if usize::from(room) >= 3 * label_width.max(1) + 2 {
        labels.push(axis_label(mid, span));
    }
    labels.push(hi);
    Axis::default()
        .title(title)
        .style(theme::CHART_AXIS)
        .bounds([range.lo, range.hi])
        .labels(labels)
}

/// The widest label of an axis over `range`.
pub(super) fn label_width(range: Range) -> usize {
    let span = range.hi - range.lo;
    [range.lo, 0.5 * (range.lo + range.hi), range.hi]
        .iter()
        .map(|&x| axis_label(x, span).chars().count())
        .max()
        .unwrap_or(1)
}

/// The block title: the chart's name, then each curve's name in its colour (the legend, kept
/// out of the plot so that no curve runs over it).
fn title_with_legend(name: &str, curves: &[(String, ratatui::style::Color)]) -> Line<'static> {
    let mut spans = vec![Span::raw(format!(" {name} "))];
    for (label, colour) in curves {
        spans.push(Span::styled("━ ", Style::new().fg(*colour)));
        spans.push(Span::styled(format!("{label} "), Style::new().fg(*colour)));
    }
    Line::from(spans)
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let series = &app.session.series;
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
    let marker = if app.prefs.ascii {
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
    let mut curves = vec![
        ("kinetic".to_string(), theme::KINETIC),
        ("potential".to_string(), theme::POTENTIAL),
        ("total".to_string(), theme::TOTAL),
    ];
    if let Some(g) = &app.session.ghost {
        curves.push((format!("total ({})", g.comparison.name()), theme::GHOST));
    }
    let data = [&kinetic, &potential, &total, &compare];
    let energies: Vec<Dataset> = curves
        .iter()
        .zip(data)
        .map(|((name, colour), d)| dataset(name.clone(), d, *colour))
        .collect();
    let [top, bottom] =
        Layout::vertical([Constraint::Percentage(65), Constraint::Percentage(35)]).areas(area);
    // Rows of each plot inside its border, less the x axis's line and labels.
    let rows = |r: Rect| r.height.saturating_sub(4);
    let columns = area.width.saturating_sub(12);
    // The curves' names, or in a narrow chart their symbols (K, V, E).
    let mut title = title_with_legend("energy, J", &curves);
    if title.width() + 2 > usize::from(top.width) {
        let short: Vec<(String, ratatui::style::Color)> = curves
            .iter()
            .zip(["K", "V", "E", "E"])
            .enumerate()
            .map(|(i, ((_, colour), symbol))| {
                let label = match (i, &app.session.ghost) {
                    (3, Some(g)) => format!("{symbol} {}", g.comparison.name()),
                    _ => symbol.to_string(),
                };
                (label, *colour)
            })
            .collect();
        title = title_with_legend("energy, J", &short);
    }
    Chart::new(energies)
        .block(Block::bordered().title(title))
        .x_axis(axis(
            "t, s",
            series.time_axis,
            columns,
            label_width(series.time_axis),
        ))
        .y_axis(axis("J", series.energy_axis, rows(top), 1))
        .legend_position(None)
        .render(top, buf);
    Chart::new(vec![dataset("drift".into(), &drift, theme::DRIFT)])
        .block(Block::bordered().title(" drift (E − E₀ not booked), J "))
        .x_axis(axis(
            "t, s",
            series.time_axis,
            columns,
            label_width(series.time_axis),
        ))
        .y_axis(axis("J", series.drift_axis, rows(bottom), 1))
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
        assert_eq!(axis_label(-0.0, 2.0), "0");
        assert_eq!(axis_label(-0.01, 100.0), "0");
        assert_eq!(axis_label(1.5e-7, 1e-6), "1.5e-7");
        assert_eq!(axis_label(3.0e6, 1e6), "3.0e6");
        assert_eq!(axis_label(3.25e6, 1e5), "3.25e6");
    }

    #[test]
    fn zero_prints_as_0_whatever_its_round_off() {
        // The middle of a phase portrait's range symmetric about 0 (issue 38: "2.0e-14").
        let (lo, hi) = (-4.7, 4.7 + 4e-14);
        assert_eq!(axis_label(0.5 * (lo + hi), hi - lo), "0");
        // Round-off far below the span's digits, of either sign, on any span.
        assert_eq!(axis_label(-0.00001, 100.0), "0");
        assert_eq!(axis_label(5e-21, 4e-5), "0");
        assert_eq!(axis_label(-3e-17, 0.3), "0");
        // A small value the span resolves is not 0.
        assert_eq!(axis_label(2e-5, 4e-5), "2.0e-5");
        assert_eq!(axis_label(0.01, 0.1), "0.01");
    }

    #[test]
    fn a_middle_label_carries_the_spans_digits_not_the_sums_round_off() {
        // 0.1 + 0.2 = 0.30000000000000004: on a span of 0.6 it prints 0.3.
        assert_eq!(axis_label(0.5 * (0.1 + 0.5), 0.4), "0.3");
        assert_eq!(axis_label(0.1 + 0.2, 0.6), "0.3");
        // A flat line widened to a billionth around 1 m: the labels tell its ends apart.
        let (lo, hi) = (1.0 - 0.5e-9, 1.0 + 0.5e-9);
        let labels = [lo, 1.0, hi].map(|x| axis_label(x, hi - lo));
        assert_eq!(labels, ["0.9999999995", "1", "1.0000000005"]);
    }
}
