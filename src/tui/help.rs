//! The help overlay: every binding of the key table, with what it does.

use super::keys::{Context, KEYS};
use super::screen::centered;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

/// The help text, one line per binding (also what the tests read).
pub fn lines() -> Vec<Line<'static>> {
    let key = theme::ACCENT.add_modifier(Modifier::BOLD);
    let mut lines = Vec::new();
    for (context, heading) in [
        (Context::Main, "Keys"),
        (Context::Picker, "In the lesson picker"),
    ] {
        if !lines.is_empty() {
            lines.push(Line::raw(""));
        }
        lines.push(Line::styled(
            heading,
            Style::new().add_modifier(Modifier::UNDERLINED),
        ));
        for b in KEYS.iter().filter(|b| b.context == context) {
            lines.push(Line::from(vec![
                Span::styled(format!("  {:<8}", b.label), key),
                Span::raw(b.help),
            ]));
        }
    }
    lines
}

pub fn render(area: Rect, buf: &mut Buffer) {
    let lines = lines();
    let width = lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16 + 4;
    let popup = centered(area, width, lines.len() as u16 + 2);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(" help — ? or Esc closes ")
                .border_style(theme::ACCENT),
        )
        .render(popup, buf);
}
