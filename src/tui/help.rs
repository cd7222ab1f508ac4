//! The help overlay: every binding of the main screen's key table, with what it does, and what
//! another lesson keeps. (The picker, the settings form and the jump prompt list their own keys,
//! from the same table, at their bottom.)

use super::keys::{Context, KEYS};
use super::screen::centered;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

/// What another lesson (or applying the settings form) keeps, and what starts over.
pub const CARRIED: [&str; 2] = [
    "Another lesson (l) or new settings (e) keep: view (v), frame (f), trail (t), graph (g),",
    "compare ghost (k), speed relative to real time, ASCII. They start paused at t = 0.",
];

/// What the mouse does (everything it does, a key does too).
pub const MOUSE: [&str; 3] = [
    "Mouse: click a body to select it; drag it to pull it with a spring (its work is the",
    "energy panel's hand row); the wheel zooms about the pointer; click a panel row (ω, L, x,",
    "v, K V E) to graph that quantity (as p does).",
];

/// The help text, one line per binding (also what the tests read).
pub fn lines() -> Vec<Line<'static>> {
    let key = theme::ACCENT.add_modifier(Modifier::BOLD);
    let mut lines = Vec::new();
    for (context, heading) in [(Context::Main, "Keys")] {
        if !lines.is_empty() {
            lines.push(Line::raw(""));
        }
        lines.push(Line::styled(
            heading,
            Style::new().add_modifier(Modifier::UNDERLINED),
        ));
        // A binding without help text is described on its group's first line (`w o O`).
        for b in KEYS
            .iter()
            .filter(|b| b.context == context && !b.help.is_empty())
        {
            lines.push(Line::from(vec![
                Span::styled(format!("  {:<9} ", b.label), key),
                Span::raw(b.help),
            ]));
        }
    }
    // The notes are paragraphs: `render` wraps them to the column.
    lines.push(Line::raw(""));
    lines.push(Line::styled(MOUSE.join(" "), theme::SOFT));
    lines.push(Line::raw(""));
    lines.push(Line::styled(CARRIED.join(" "), theme::SOFT));
    lines
}

/// `line` cut at word boundaries into lines at most `width` wide; a binding's continuation
/// lines are indented under its help text, the key column left blank.
fn wrap(line: Line<'static>, width: usize) -> Vec<Line<'static>> {
    if line.width() <= width {
        return vec![line];
    }
    let (lead, text, style) = match line.spans.as_slice() {
        [key, help] => (key.clone(), help.content.to_string(), help.style),
        _ => (
            Span::raw(""),
            line.spans.iter().map(|s| s.content.as_ref()).collect(),
            line.spans.first().map_or(line.style, |s| s.style),
        ),
    };
    let indent = lead.width();
    let room = width.saturating_sub(indent).max(8);
    let mut rows: Vec<String> = vec![String::new()];
    for word in text.split(' ') {
        let last = rows.last_mut().expect("one row at least");
        if !last.is_empty() && last.chars().count() + 1 + word.chars().count() > room {
            rows.push(word.to_string());
        } else {
            if !last.is_empty() {
                last.push(' ');
            }
            last.push_str(word);
        }
    }
    rows.into_iter()
        .enumerate()
        .map(|(i, row)| {
            let first = if i == 0 {
                lead.clone()
            } else {
                Span::raw(" ".repeat(indent))
            };
            Line::from(vec![first, Span::styled(row, style)])
        })
        .collect()
}

/// The help in one column, or in two side by side when one is taller than the screen (each
/// half the screen wide, long lines wrapped under their text).
pub fn render(area: Rect, buf: &mut Buffer) {
    let lines = lines();
    let room = usize::from(area.height.saturating_sub(2));
    // The widest key line sets the column (the notes wrap to it).
    let widest = lines
        .iter()
        .filter(|l| l.spans.len() == 2)
        .map(|l| l.width())
        .max()
        .unwrap_or(0);
    let one: Vec<Line> = lines
        .iter()
        .cloned()
        .flat_map(|l| wrap(l, widest))
        .collect();
    let columns: Vec<Vec<Line>> = if one.len() <= room && widest + 4 <= usize::from(area.width) {
        vec![one]
    } else {
        let half = usize::from(area.width.saturating_sub(4) / 2).saturating_sub(2);
        let lines: Vec<Line> = lines.into_iter().flat_map(|l| wrap(l, half)).collect();
        // Split at a blank line (between sections) near the middle, if there is one.
        let middle = lines.len().div_ceil(2);
        let split = (middle..lines.len())
            .find(|&i| lines[i].width() == 0)
            .filter(|&i| i <= room)
            .unwrap_or(middle);
        let mut left = lines;
        let right = left.split_off(split);
        vec![left, right]
    };
    let widths: Vec<u16> = columns
        .iter()
        .map(|c| c.iter().map(|l| l.width()).max().unwrap_or(0) as u16 + 2)
        .collect();
    let height = columns.iter().map(Vec::len).max().unwrap_or(0) as u16;
    let popup = centered(area, widths.iter().sum::<u16>() + 2, height + 2);
    Clear.render(popup, buf);
    let block = Block::bordered()
        .title(" help — ? or Esc closes ")
        .border_style(theme::ACCENT);
    let inner = block.inner(popup);
    block.render(popup, buf);
    let mut x = inner.x;
    for (column, width) in columns.into_iter().zip(widths) {
        let width = width.min(inner.x + inner.width - x);
        Paragraph::new(column).render(
            Rect {
                x,
                y: inner.y,
                width,
                height: inner.height,
            },
            buf,
        );
        x += width;
    }
}
