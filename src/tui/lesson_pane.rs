//! The lesson pane: the page that applies at the current time (`Lesson::page_at`), wrapped with
//! hanging indents (so indented formulas and tables stay readable in a narrow pane), scrollable.

use super::app::App;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Paragraph, Widget};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let lesson = &app.lesson;
    let (title, text) = match lesson.page_at(app.snapshot.time) {
        Some((i, page)) => (
            format!(" page {}/{}: {} ", i + 1, lesson.pages.len(), page.title),
            page.text.trim_matches('\n').to_string(),
        ),
        None => (
            " lesson ".to_string(),
            if lesson.summary.is_empty() {
                "This scene has no lesson pages.".to_string()
            } else {
                lesson.summary.clone()
            },
        ),
    };
    let block = Block::bordered()
        .title(title)
        .title_bottom(
            Line::styled(" PgUp/PgDn scroll ", Style::new().fg(Color::DarkGray)).right_aligned(),
        )
        .title_style(Style::new().add_modifier(Modifier::BOLD));
    let inner = block.inner(area);
    let lines: Vec<Line> = wrap(&text, usize::from(inner.width.max(1)))
        .into_iter()
        .map(Line::from)
        .collect();
    let total = lines.len() as u16;
    let scroll = app.lesson_scroll.min(total.saturating_sub(inner.height));
    let mut block = block;
    if total > inner.height {
        block = block.title_bottom(
            Line::styled(
                format!(
                    " {}-{} of {} ",
                    scroll + 1,
                    (scroll + inner.height).min(total),
                    total
                ),
                Style::new().fg(Color::Yellow),
            )
            .left_aligned(),
        );
    }
    Paragraph::new(lines)
        .block(block)
        .scroll((scroll, 0))
        .render(area, buf);
}

/// Word-wraps `text` to `width` columns. A continuation line is indented like the text after
/// the first gap of two or more spaces on its line (`  x  where the…` continues under
/// `where`), or like the line itself when there is no such gap in the first half.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let chars: Vec<char> = line.trim_end().chars().collect();
        if chars.len() <= width {
            out.push(chars.iter().collect());
            continue;
        }
        let lead = chars.iter().take_while(|c| **c == ' ').count();
        let hang = (lead..chars.len().saturating_sub(2))
            .find(|&i| chars[i] == ' ' && chars[i + 1] == ' ' && i > lead)
            .map(|i| i + chars[i..].iter().take_while(|c| **c == ' ').count())
            .filter(|&h| h < width / 2)
            .unwrap_or(lead.min(width / 2));
        let mut rest: &[char] = &chars;
        let mut indent = 0;
        loop {
            let room = width - indent;
            if rest.len() <= room {
                out.push(" ".repeat(indent) + &rest.iter().collect::<String>());
                break;
            }
            // Break at the last space that fits (not inside the indentation).
            let cut = (1..=room)
                .rev()
                .find(|&i| rest[i] == ' ' && rest[..i].iter().any(|c| *c != ' '))
                .unwrap_or(room);
            let head: String = rest[..cut].iter().collect();
            out.push(" ".repeat(indent) + head.trim_end());
            rest = &rest[cut..];
            while rest.first() == Some(&' ') {
                rest = &rest[1..];
            }
            if rest.is_empty() {
                break;
            }
            indent = hang;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::wrap;

    #[test]
    fn continuation_lines_hang_under_the_text_after_a_double_space() {
        let lines = wrap("  q  how the body is turned (a unit quaternion)", 24);
        assert_eq!(
            lines,
            vec![
                "  q  how the body is",
                "     turned (a unit",
                "     quaternion)",
            ]
        );
    }

    #[test]
    fn a_word_longer_than_the_line_is_cut() {
        let lines = wrap("abcdefghij", 4);
        assert_eq!(lines, vec!["abcd", "efgh", "ij"]);
    }
}
