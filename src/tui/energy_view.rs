//! The graph views: the energy graph (key `g`) or the graph of a picked quantity (key `p`) in
//! place of the projection, beside the same panels and loop strip.

use super::app::App;
use super::app::View;
use super::layout::ScreenLayout;
use super::screen::main_areas;
use super::{energy_graph, loop_strip, panels, plot_graph};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let areas = main_areas(app, area);
    // The graph takes the drawing's place and, in the numbers layout, the page's under it (the
    // energy view shows no page there): a drift chart needs the rows.
    let graph = match areas.lesson {
        Some(l) if app.prefs.layout == ScreenLayout::Numbers && l.x == areas.drawing.x => {
            areas.drawing.union(l)
        }
        _ => areas.drawing,
    };
    if app.ui.view == View::Plot {
        plot_graph::render(app, graph, buf);
    } else {
        energy_graph::render(app, graph, buf);
    }
    if let (Some(l), ScreenLayout::Stage) = (areas.lesson, app.prefs.layout) {
        super::lesson_pane::render(app, l, buf);
    }
    if let Some(p) = areas.panels {
        match app.prefs.layout {
            ScreenLayout::Numbers => panels::render(app, p, buf),
            ScreenLayout::Stage => panels::render_essentials(app, p, buf),
        }
    }
    if let Some(strip) = areas.strip {
        loop_strip::render(app, strip, buf);
    }
    super::panes::render_cut(app, &areas, buf);
}
