//! The lesson picker: the bundled lessons by title; Enter opens the selected one.

use super::keys::{Context, KEYS};
use super::screen::centered;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget};
use std::path::PathBuf;

pub fn render(lessons: &[(PathBuf, String)], selected: usize, area: Rect, buf: &mut Buffer) {
    let name_width = lessons
        .iter()
        .map(|(p, _)| {
            p.file_name()
                .map_or(0, |n| n.to_string_lossy().chars().count())
        })
        .max()
        .unwrap_or(0);
    let mut lines: Vec<Line> = lessons
        .iter()
        .enumerate()
        .map(|(i, (path, title))| {
            let name = path
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            let text = format!(" {name:<name_width$}  {title} ");
            if i == selected {
                Line::styled(text, theme::SELECTED)
            } else {
                Line::raw(text)
            }
        })
        .collect();
    if lines.is_empty() {
        lines.push(Line::raw(" this build has no bundled lessons "));
    }
    let footer: Vec<String> = KEYS
        .iter()
        .filter(|b| b.context == Context::Picker)
        .map(|b| {
            format!(
                "{} {}",
                b.label,
                b.help.trim_start_matches("lesson picker: ")
            )
        })
        .collect();
    let footer_text = format!(" {} ", footer.join(" · "));
    let width = lines
        .iter()
        .map(|l| l.width())
        .chain([footer_text.chars().count()])
        .max()
        .unwrap_or(0) as u16
        + 2;
    let popup = centered(area, width, lines.len() as u16 + 2);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(" lessons ")
                .title_bottom(footer_text)
                .border_style(theme::PICKER_BORDER),
        )
        .render(popup, buf);
}
