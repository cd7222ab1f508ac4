//! The main view: the projection of the body, the lesson page, the numeric panels (or, in the
//! stage layout, the essential numbers) and the loop strip, where the layout puts them.

use super::app::App;
use super::layout::ScreenLayout;
use super::screen::main_areas;
use super::{lesson_pane, loop_strip, panels, projection};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let areas = main_areas(app, area);
    projection::render(app, areas.drawing, buf);
    if let Some(lesson) = areas.lesson {
        lesson_pane::render(app, lesson, buf);
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
}
