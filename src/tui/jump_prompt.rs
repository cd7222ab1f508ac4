//! The jump prompt (`J`): the time typed so far, and what Enter does.

use super::keys::{Context, KEYS};
use super::screen::centered;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

pub fn render(text: &str, now: f64, area: Rect, buf: &mut Buffer) {
    let keys: Vec<String> = KEYS
        .iter()
        .filter(|b| {
            b.context == Context::Prompt && b.label != "q" && !b.help.starts_with("predict:")
        })
        .map(|b| format!("{} {}", b.label, b.help.trim_start_matches("jump: ")))
        .collect();
    let lines = vec![
        Line::raw(format!(
            " jump to t = {text}▏ s   (now {} s; an earlier t replays from 0)",
            super::settings_form::tidy(now)
        )),
        Line::styled(
            format!(" {}", keys.join(" · ")),
            Style::new().fg(Color::DarkGray),
        ),
    ];
    let width = lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16 + 3;
    let popup = centered(area, width, 4);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(" jump ")
                .border_style(Style::new().fg(Color::Yellow)),
        )
        .render(popup, buf);
}

/// The prediction prompt of a page's `predict`: the question, the number typed so far.
pub fn render_predict(question: &str, text: &str, area: Rect, buf: &mut Buffer) {
    let lines = vec![
        Line::raw(format!(" {question}")),
        Line::raw(format!(" your guess: {text}▏")),
        Line::styled(
            " 0-9 . - e type · Enter run and see · Esc no guess",
            Style::new().fg(Color::DarkGray),
        ),
    ];
    let width = lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16 + 3;
    let popup = centered(area, width, 5);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(" predict ")
                .border_style(Style::new().fg(Color::Yellow)),
        )
        .render(popup, buf);
}
