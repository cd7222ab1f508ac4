//! The energy view: the energy graph in place of the projection, beside the same panels and
//! loop strip.

use super::app::App;
use super::layout::ScreenLayout;
use super::screen::main_areas;
use super::{energy_graph, loop_strip, panels};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let areas = main_areas(app, area);
    energy_graph::render(app, areas.drawing, buf);
    if let Some(p) = areas.panels {
        match app.layout {
            ScreenLayout::Numbers => panels::render(app, p, buf),
            ScreenLayout::Stage => panels::render_essentials(app, p, buf),
        }
    }
    if let Some(strip) = areas.strip {
        loop_strip::render(app, strip, buf);
    }
}
