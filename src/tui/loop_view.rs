//! The main view: the projection of the body, the lesson page, the numeric panels (or, in the
//! stage layout, the essential numbers), the loop strip and any other box of the pane table
//! (`panes.rs`), where the layout puts them.

use super::app::App;
use super::panes;
use super::screen::main_areas;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    panes::render(app, &main_areas(app, area), buf);
}
