//! The main view: the projection of the body above the lesson page, the numeric panels on the
//! right, the loop strip along the bottom.

use super::app::App;
use super::screen::main_areas;
use super::{lesson_pane, loop_strip, panels, projection};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let areas = main_areas(area);
    let lesson_height = (areas.left.height * 2 / 5).clamp(4, 16);
    let [stage, lesson] =
        Layout::vertical([Constraint::Min(0), Constraint::Length(lesson_height)]).areas(areas.left);
    projection::render(app, stage, buf);
    lesson_pane::render(app, lesson, buf);
    panels::render(app, areas.panels, buf);
    loop_strip::render(app, areas.strip, buf);
}
