//! The divergence dialog: which quantity diverged, at which step, with which integrator and dt;
//! the app stays paused until the user steps back, resets or quits.

use super::keys::{Message, KEYS};
use super::screen::centered;
use super::theme;
use crate::physics::Divergence;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget, Wrap};

pub fn render(d: &Divergence, area: Rect, buf: &mut Buffer) {
    let label = |m: Message| KEYS.iter().find(|b| b.message == m).map_or("", |b| b.label);
    let lines = vec![
        Line::styled(
            "The simulation diverged",
            Style::new().add_modifier(Modifier::BOLD),
        ),
        Line::raw(""),
        Line::raw(d.to_string()),
        Line::raw(""),
        Line::styled(
            format!(
                "{} step back · {} reset · {} quit",
                label(Message::StepBack),
                label(Message::Reset),
                label(Message::Quit)
            ),
            theme::ACCENT,
        ),
    ];
    let popup = centered(area, 72, 9);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .wrap(Wrap { trim: true })
        .block(
            Block::bordered()
                .title(" diverged ")
                .border_style(theme::ERROR),
        )
        .render(popup, buf);
}
