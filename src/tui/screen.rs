//! The whole screen: header, the current view, status bar, and the overlays (help, lesson
//! picker, divergence dialog) — or, in a terminal too small, a message asking to enlarge it.

use super::app::{App, Overlay};
use super::layout::{self, Areas, ScreenLayout};
use super::theme;
use super::{
    divergence_dialog, header, help, jump_prompt, lesson_pane, panels, picker, plot_picker,
    settings_view, status_bar,
};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget, Wrap};

/// The smallest usable terminal.
pub const MIN_WIDTH: u16 = 80;
pub const MIN_HEIGHT: u16 = 24;

/// The header line, the main area and the status bar of a screen `area` (None: too small, the
/// "enlarge" message instead).
pub fn split(app: &App, area: Rect) -> Option<[Rect; 3]> {
    if area.width < MIN_WIDTH || area.height < MIN_HEIGHT {
        return None;
    }
    Some(
        Layout::vertical([
            Constraint::Length(1),
            Constraint::Min(0),
            Constraint::Length(status_bar::height(app, area.width, area.height)),
        ])
        .areas(area),
    )
}

impl Widget for &App {
    fn render(self, area: Rect, buf: &mut Buffer) {
        // The mouse reads the screen as last drawn.
        self.ui.screen_area.set(area);
        let Some([top, main, status]) = split(self, area) else {
            enlarge_message(area, buf);
            return;
        };
        header::render(self, top, buf);
        (self.ui.view.pane().render)(self, main, buf);
        status_bar::render(self, status, buf);
        if let Some(d) = &self.session.divergence {
            divergence_dialog::render(d, area, buf);
        }
        match &self.ui.overlay {
            Overlay::None => {}
            Overlay::Help => help::render(area, buf),
            Overlay::Picker { lessons, selected } => picker::render(lessons, *selected, area, buf),
            Overlay::PlotPicker { selected, x } => {
                let curves = self.plot_curves();
                plot_picker::render(
                    &self.session.plot_series.columns,
                    *selected,
                    *x,
                    &curves,
                    area,
                    buf,
                )
            }
            Overlay::Settings(form) => settings_view::render(form, area, buf),
            Overlay::Jump { text } => {
                jump_prompt::render(text, self.session.snapshot.time, area, buf)
            }
            Overlay::Predict { page, text } => {
                jump_prompt::render_predict(&self.prediction_question(*page), text, area, buf)
            }
        }
    }
}

/// The panes of the main area in the app's layout (see [`super::layout`]), with the boxes of
/// the pane table cut from them (`panes.rs`).
pub fn main_areas(app: &App, area: Rect) -> Areas {
    let essentials = match app.prefs.layout {
        ScreenLayout::Stage => panels::essentials_size(app),
        ScreenLayout::Numbers => (0, 0),
    };
    let panels_width = match app.prefs.layout {
        ScreenLayout::Numbers => panels::width(app),
        ScreenLayout::Stage => 0,
    };
    let quoted_width = match app.prefs.layout {
        ScreenLayout::Numbers => panels::quoted_width(app),
        ScreenLayout::Stage => 0,
    };
    let page_lines = match app.prefs.layout {
        ScreenLayout::Stage => lesson_pane::line_count(app, area.width.saturating_sub(2)),
        ScreenLayout::Numbers => 0,
    };
    let mut areas = layout::areas(
        area,
        app.prefs.layout,
        panels_width,
        quoted_width,
        essentials,
        page_lines,
    );
    super::panes::cut(app, &mut areas);
    areas
}

/// A rectangle of at most `width × height` centred in `area`.
pub fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let w = width.min(area.width);
    let h = height.min(area.height);
    Rect {
        x: area.x + (area.width - w) / 2,
        y: area.y + (area.height - h) / 2,
        width: w,
        height: h,
    }
}

fn enlarge_message(area: Rect, buf: &mut Buffer) {
    let text = vec![
        Line::styled(
            "Please enlarge the terminal",
            Style::new().add_modifier(Modifier::BOLD),
        ),
        Line::from(format!(
            "tumble needs at least {MIN_WIDTH}×{MIN_HEIGHT}; this one is {}×{}.",
            area.width, area.height
        )),
        Line::from("q quits."),
    ];
    let box_area = centered(area, area.width, 4);
    Paragraph::new(text)
        .style(theme::ACCENT)
        .centered()
        .wrap(Wrap { trim: true })
        .render(box_area, buf);
}
