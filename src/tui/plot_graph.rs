//! The graph of a picked quantity (key `p`): against time, or against another quantity (a
//! phase portrait), the current frame marked. The axes follow the data (its extent and a
//! twentieth either side), so they grow smoothly as the run goes; time runs to the scene's
//! duration, then with the run.

use super::app::App;
use super::energy_graph::{axis, label_width};
use super::keys::{Message, KEYS};
use super::plot::{label, PlotChoice};
use super::series::Range;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::Line;
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
        .lesson
        .scene
        .duration
        .filter(|d| *d > 0.0)
        .unwrap_or(100.0 * app.world.dt());
    let now = app.plot_series.times().last().copied().unwrap_or(0.0);
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
    let Some(choice) = app.plot else {
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
    let series = &app.plot_series;
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
    let marker = if app.ascii {
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
        .marker(if app.ascii {
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
