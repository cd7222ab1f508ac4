//! The energy view: the energy graph in place of the projection, beside the same panels and
//! loop strip.

use super::app::App;
use super::screen::main_areas;
use super::{energy_graph, loop_strip, panels};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let areas = main_areas(area);
    energy_graph::render(app, areas.left, buf);
    panels::render(app, areas.panels, buf);
    loop_strip::render(app, areas.strip, buf);
}
