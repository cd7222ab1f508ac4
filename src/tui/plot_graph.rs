//! The graph of a picked quantity (key `p`): against time, or against another quantity (a
//! phase portrait), the current frame marked. The axes follow the data (its extent and a
//! twentieth either side), so they grow smoothly as the run goes; time runs to the scene's
//! duration, then with the run.

use super::app::App;
use super::energy_graph::{axis, axis_label, label_width};
use super::keys::{Message, KEYS};
use super::plot::{curve_axes, label, CurveAxes, PlotChoice, MAX_CURVES};
use super::series::Range;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Chart, Dataset, GraphType, Paragraph, Widget, Wrap};

/// The range a column's values need: their extent with a twentieth either side. A constant
/// gets ±10 % of its value (±1 for 0); a span below a billionth of the values' size (their
/// round-off, magnified) is widened to that, so noise never fills the graph.
pub fn data_range(values: impl Iterator<Item = f64>) -> Range {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if lo > hi {
        return Range { lo: -1.0, hi: 1.0 };
    }
    if lo == hi {
        let half = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        return Range {
            lo: lo - half,
            hi: hi + half,
        };
    }
    let scale = lo.abs().max(hi.abs());
    let least = 1e-9 * scale;
    if hi - lo < least {
        let mid = 0.5 * (lo + hi);
        (lo, hi) = (mid - 0.5 * least, mid + 0.5 * least);
    }
    let pad = 0.05 * (hi - lo);
    Range {
        lo: lo - pad,
        hi: hi + pad,
    }
}

/// The time axis: from 0 to the scene's duration (or 100 steps), or to now once past it.
pub fn time_range(app: &App) -> Range {
    let end = app
        .session
        .lesson
        .scene
        .duration
        .filter(|d| *d > 0.0)
        .unwrap_or(100.0 * app.session.snapshot.dt);
    let now = app
        .session
        .plot_series
        .times()
        .last()
        .copied()
        .unwrap_or(0.0);
    Range {
        lo: 0.0,
        hi: end.max(now),
    }
}

/// The label of the key that sends `message` on the main screen (from the key table).
fn key_of(message: Message) -> &'static str {
    KEYS.iter()
        .find(|b| b.message == message)
        .map_or("?", |b| b.label)
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let Some(choice) = app.ui.plot else {
        let text = format!(
            " nothing picked yet: {} lists the quantities",
            key_of(Message::OpenPlot)
        );
        Paragraph::new(text)
            .wrap(Wrap { trim: true })
            .block(Block::bordered().title(" graph "))
            .render(area, buf);
        return;
    };
    render_choice(app, choice, area, buf);
}

fn render_choice(app: &App, choice: PlotChoice, area: Rect, buf: &mut Buffer) {
    let curves = app.plot_curves();
    if curves.len() > 1 {
        render_curves(app, choice, &curves, area, buf);
        return;
    }
    let series = &app.session.plot_series;
    let columns = &series.columns;
    let points = series.points(choice);
    let finite: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let y_range = data_range(series.column(choice.y));
    let (x_range, x_title) = match choice.x {
        None => (time_range(app), "t, s".to_string()),
        Some(x) => (data_range(series.column(x)), label(&columns[x])),
    };
    let marker = if app.prefs.ascii {
        Marker::Dot
    } else {
        Marker::Braille
    };
    let now = finite.last().copied().into_iter().collect::<Vec<_>>();
    let curve = Dataset::default()
        .marker(marker)
        .graph_type(GraphType::Line)
        .style(Style::new().fg(theme::TOTAL))
        .data(&finite);
    let mark = Dataset::default()
        .marker(if app.prefs.ascii {
            Marker::Dot
        } else {
            Marker::Block
        })
        .graph_type(GraphType::Scatter)
        .style(Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD))
        .data(&now);
    let y = &columns[choice.y];
    let title = match choice.x {
        None => format!(" {} against time ", label(y)),
        Some(x) => format!(
            " {} against {} (phase portrait) ",
            label(y),
            label(&columns[x])
        ),
    };
    // Narrow: the names only (the axes carry the units).
    let title = if title.chars().count() + 2 > usize::from(area.width) {
        match choice.x {
            None => format!(" {} ", y.name),
            Some(x) => format!(" {} vs {} ", y.name, columns[x].name),
        }
    } else {
        title
    };
    let keys = format!(
        " {} another · {} CSV ",
        key_of(Message::OpenPlot),
        key_of(Message::ExportCsv)
    );
    let rows = area.height.saturating_sub(4);
    let columns_room = area.width.saturating_sub(12);
    Chart::new(vec![curve, mark])
        .block(
            Block::bordered()
                .title(Line::from(title))
                .title_bottom(Line::styled(keys, theme::SOFT)),
        )
        .x_axis(axis(&x_title, x_range, columns_room, label_width(x_range)))
        .y_axis(axis(y.unit, y_range, rows, 1))
        .legend_position(None)
        .render(area, buf);
}

/// The colours of a graph's curves, in order (the first is the single curve's).
pub const CURVE_COLOURS: [Color; MAX_CURVES] = [
    theme::TOTAL,
    theme::KINETIC,
    Color::LightRed,
    Color::LightCyan,
];

/// The markers of a graph's curves without Braille (`ascii`): each curve its own, so they
/// tell apart in text too; and the glyph the legend shows for each.
const ASCII_MARKERS: [(Marker, &str); MAX_CURVES] = [
    (Marker::Dot, "•"),
    (Marker::Bar, "▄"),
    (Marker::Block, "█"),
    (Marker::Dot, "•"),
];

/// `lo` to `hi` of `from` mapped onto `to` (a right-axis curve drawn on the left axis's scale).
fn rescale(y: f64, from: Range, to: Range) -> f64 {
    to.lo + (y - from.lo) * (to.hi - to.lo) / (from.hi - from.lo)
}

/// Several curves on one graph: one axis when they share a unit, else the first curve's unit
/// on the left and the other on a right axis (each curve drawn on its axis's scale); the
/// legend in the title names each curve in its colour and says which axis it reads on.
fn render_curves(app: &App, choice: PlotChoice, curves: &[usize], area: Rect, buf: &mut Buffer) {
    let series = &app.session.plot_series;
    let columns = &series.columns;
    let axes = curve_axes(columns, curves);
    let range_of = |right: bool| {
        data_range(
            axes.curves
                .iter()
                .zip(&axes.on_right)
                .filter(|(_, &r)| r == right)
                .flat_map(|(&c, _)| series.column(c)),
        )
    };
    let left_range = range_of(false);
    let right_range = axes.right.map(|_| range_of(true));
    let (x_range, x_title) = match choice.x {
        None => (time_range(app), "t, s".to_string()),
        Some(x) => (data_range(series.column(x)), label(&columns[x])),
    };
    let data: Vec<Vec<(f64, f64)>> = axes
        .curves
        .iter()
        .zip(&axes.on_right)
        .map(|(&c, &right)| {
            series
                .points(PlotChoice { y: c, x: choice.x })
                .into_iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|(x, y)| match (right, right_range) {
                    (true, Some(r)) => (x, rescale(y, r, left_range)),
                    _ => (x, y),
                })
                .collect()
        })
        .collect();
    let now: Vec<(f64, f64)> = data.iter().filter_map(|d| d.last().copied()).collect();
    let mut datasets: Vec<Dataset> = data
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let marker = if app.prefs.ascii {
                ASCII_MARKERS[i].0
            } else {
                Marker::Braille
            };
            Dataset::default()
                .marker(marker)
                .graph_type(GraphType::Line)
                .style(Style::new().fg(CURVE_COLOURS[i]))
                .data(d)
        })
        .collect();
    datasets.push(
        Dataset::default()
            .marker(if app.prefs.ascii {
                Marker::Dot
            } else {
                Marker::Block
            })
            .graph_type(GraphType::Scatter)
            .style(Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD))
            .data(&now),
    );
    let title = legend(
        app,
        &axes,
        choice,
        usize::from(area.width).saturating_sub(2),
    );
    let keys = format!(
        " {} another · {} CSV ",
        key_of(Message::OpenPlot),
        key_of(Message::ExportCsv)
    );
    let block = Block::bordered()
        .title(title)
        .title_bottom(Line::styled(keys, theme::SOFT));
    let inner = block.inner(area);
    block.render(area, buf);
    let rows = area.height.saturating_sub(4);
    // The right axis: its line, then its labels, in a strip of its own.
    let right = right_range.map(|r| {
        let labels = axis_labels(r, rows);
        let width = labels.iter().map(|l| l.chars().count()).max().unwrap_or(1) as u16;
        (r, labels, width + 1)
    });
    let strip = right.as_ref().map_or(0, |(_, _, w)| *w);
    let chart_area = Rect {
        width: inner.width.saturating_sub(strip),
        ..inner
    };
    let columns_room = chart_area.width.saturating_sub(10);
    Chart::new(datasets)
        .x_axis(axis(&x_title, x_range, columns_room, label_width(x_range)))
        .y_axis(axis(axes.left, left_range, rows, 1))
        .legend_position(None)
        .render(chart_area, buf);
    if let (Some((_, labels, _)), Some(unit)) = (right, axes.right) {
        draw_right_axis(buf, chart_area, &labels, unit);
    }
}

/// An axis's labels as [`axis`] places them: the ends, and the middle when `room` rows leave
/// a gap between them.
fn axis_labels(range: Range, room: u16) -> Vec<String> {
    let span = range.hi - range.lo;
    let mut labels = vec![axis_label(range.lo, span)];
    if room >= 5 {
        labels.push(axis_label(0.5 * (range.lo + range.hi), span));
    }
    labels.push(axis_label(range.hi, span));
    labels
}

/// The right axis beside the chart drawn in `chart`: a line along the graph's rows, the
/// labels where the chart puts the left axis's (bottom to top), and the unit at the graph's
/// top right.
fn draw_right_axis(buf: &mut Buffer, chart: Rect, labels: &[String], unit: &str) {
    // The chart keeps its last two rows for the time axis's line and labels.
    if chart.height < 4 || labels.len() < 2 {
        return;
    }
    let graph_height = chart.height - 2;
    let x = chart.right();
    let style = theme::CHART_AXIS;
    for y in chart.top()..chart.top() + graph_height {
        buf[(x, y)].set_symbol("│").set_style(style);
    }
    buf[(x, chart.top() + graph_height)]
        .set_symbol("┘")
        .set_style(style);
    let n = labels.len() as u16;
    for (i, label) in labels.iter().enumerate() {
        let dy = i as u16 * (graph_height - 1) / (n - 1);
        let y = chart.top() + graph_height - 1 - dy;
        buf.set_string(x + 1, y, label, style);
    }
    let width = unit.chars().count() as u16;
    if width + 2 < chart.width {
        buf.set_string(x - width, chart.top(), unit, style);
    }
}

/// The graph's title: each curve's name in its colour (its glyph first), which axis it reads
/// on when there are two, and what the curves are against — shortened to fit `room`.
fn legend(app: &App, axes: &CurveAxes, choice: PlotChoice, room: usize) -> Line<'static> {
    let columns = &app.session.plot_series.columns;
    let two = axes.right.is_some();
    let against = match choice.x {
        None => "time".to_string(),
        Some(x) => label(&columns[x]),
    };
    // From the fullest to the shortest: names with units and axes, then names and axes,
    // then names only.
    for form in 0..3 {
        let mut spans = vec![Span::raw(" ")];
        for (i, (&c, &right)) in axes.curves.iter().zip(&axes.on_right).enumerate() {
            let colour = Style::new().fg(CURVE_COLOURS[i]);
            let glyph = if app.prefs.ascii {
                ASCII_MARKERS[i].1
            } else {
                "━"
            };
            let name = if form == 0 {
                label(&columns[c])
            } else {
                columns[c].name.clone()
            };
            let side = match (two && form < 2, right) {
                (true, false) => " (left)",
                (true, true) => " (right)",
                _ => "",
            };
            spans.push(Span::styled(format!("{glyph} {name}{side} "), colour));
        }
        let tail = match form {
            0 if two => format!("against {against}: two axes "),
            0 => format!("against {against}: one axis, {} ", axes.left),
            1 if two => String::new(),
            1 => format!("· one axis, {} ", axes.left),
            _ => String::new(),
        };
        spans.push(Span::raw(tail));
        let line = Line::from(spans);
        if line.width() <= room || form == 2 {
            return line;
        }
    }
    unreachable!("the last form is returned whatever its width")
}

#[cfg(test)]
mod tests {
    use super::data_range;

    #[test]
    fn the_range_holds_the_data_with_a_twentieth_either_side() {
        let r = data_range([1.0, 3.0].into_iter());
        assert_eq!((r.lo, r.hi), (0.9, 3.1));
        // A constant: ±10 % of it, ±1 for zero; nothing finite: ±1.
        let r = data_range([2.0, 2.0].into_iter());
        assert_eq!((r.lo, r.hi), (1.8, 2.2));
        let r = data_range([0.0].into_iter());
        assert_eq!((r.lo, r.hi), (-1.0, 1.0));
        let r = data_range([f64::NAN].into_iter());
        assert_eq!((r.lo, r.hi), (-1.0, 1.0));
        // Round-off around 1 m (1e-16) is widened to a billionth of a metre: a flat line.
        let r = data_range([1.0, 1.0 + 2.2e-16].into_iter());
        assert!(r.hi - r.lo > 1e-9 && r.hi - r.lo < 1.2e-9, "{r:?}");
    }
}
