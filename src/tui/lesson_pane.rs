//! The lesson pane: the page that applies at the current time (`Lesson::page_at`), wrapped and
//! scrollable.

use super::app::App;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Paragraph, Widget, Wrap};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let lesson = &app.lesson;
    let (title, lines) = match lesson.page_at(app.snapshot.time) {
        Some((i, page)) => (
            format!(" page {}/{}: {} ", i + 1, lesson.pages.len(), page.title),
            page.text
                .lines()
                .map(|l| Line::from(l.to_string()))
                .collect::<Vec<_>>(),
        ),
        None => (
            " lesson ".to_string(),
            vec![Line::styled(
                if lesson.summary.is_empty() {
                    "This scene has no lesson pages.".to_string()
                } else {
                    lesson.summary.clone()
                },
                Style::new().fg(Color::Gray),
            )],
        ),
    };
    let block = Block::bordered()
        .title(title)
        .title_bottom(
            Line::styled(" PgUp/PgDn scroll ", Style::new().fg(Color::DarkGray)).right_aligned(),
        )
        .title_style(Style::new().add_modifier(Modifier::BOLD));
    let inner_width = block.inner(area).width.max(1);
    // Wrapped height, estimated from line widths (word wrapping may add a line here and there).
    let total: u16 = lines
        .iter()
        .map(|l| (l.width() as u16).max(1).div_ceil(inner_width))
        .sum();
    let paragraph = Paragraph::new(lines).wrap(Wrap { trim: false });
    let visible = block.inner(area).height;
    let scroll = app.lesson_scroll.min(total.saturating_sub(visible));
    paragraph.block(block).scroll((scroll, 0)).render(area, buf);
}
