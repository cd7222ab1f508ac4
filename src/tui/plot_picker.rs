//! The quantity picker (key `p`): every quantity the graph can show, with its unit; Enter
//! graphs the selected one, `x` makes it the horizontal axis (a phase portrait), `a` adds it
//! to the graph shown as another curve (or takes it off). Its keys are
//! listed at its bottom, from the key table.

use super::keys::{Context, KEYS};
use super::plot::Column;
use super::screen::centered;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

/// `curves`: the curves on the graph shown (marked when there are several).
pub fn render(
    columns: &[Column],
    selected: usize,
    x: Option<usize>,
    curves: &[usize],
    area: Rect,
    buf: &mut Buffer,
) {
    let name_width = columns
        .iter()
        .map(|c| c.name.chars().count())
        .max()
        .unwrap_or(0);
    let lines: Vec<Line> = columns
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let curve = curves
                .iter()
                .position(|&c| c == i)
                .filter(|_| curves.len() > 1);
            let axis = if Some(i) == x {
                "  ← horizontal axis".to_string()
            } else if let Some(k) = curve {
                format!("  ← curve {}", k + 1)
            } else {
                String::new()
            };
            let text = format!(" {:<name_width$}  {}{axis} ", c.name, c.unit);
            if i == selected {
                Line::styled(text, theme::SELECTED)
            } else {
                Line::raw(text)
            }
        })
        .collect();
    let footer: Vec<String> = KEYS
        .iter()
        .filter(|b| b.context == Context::PlotPicker && b.label != "q")
        .map(|b| format!("{} {}", b.label, b.help.trim_start_matches("plot: ")))
        .collect();
    let against = match x {
        None => "time".to_string(),
        Some(i) => columns.get(i).map_or("time".into(), |c| c.name.clone()),
    };
    let title = format!(" graph: against {against} ");
    // The footer wraps onto two lines when the popup is narrower than it.
    let footer_lines = wrap(&footer, area.width.saturating_sub(4).into());
    let width = lines
        .iter()
        .map(|l| l.width())
        .chain(footer_lines.iter().map(|l| l.chars().count()))
        .chain([title.chars().count()])
        .max()
        .unwrap_or(0) as u16
        + 2;
    let room = area
        .height
        .saturating_sub(4 + footer_lines.len() as u16)
        .max(1);
    let visible = usize::from(room).min(lines.len()).max(1);
    // The window of lines shown keeps the selected one in view.
    let first = selected.saturating_sub(visible - 1);
    let mut shown: Vec<Line> = lines.into_iter().skip(first).take(visible).collect();
    shown.push(Line::raw(""));
    for f in footer_lines {
        shown.push(Line::styled(f, theme::SOFT));
    }
    let popup = centered(area, width, shown.len() as u16 + 2);
    Clear.render(popup, buf);
    Paragraph::new(shown)
        .block(
            Block::bordered()
                .title(title)
                .border_style(theme::PICKER_BORDER),
        )
        .render(popup, buf);
}

/// Items joined by ` · ` on lines of at most `width` characters.
fn wrap(items: &[String], width: usize) -> Vec<String> {
    let mut lines: Vec<String> = vec![String::new()];
    for item in items {
        let line = lines.last_mut().expect("one line at least");
        if !line.is_empty() && line.chars().count() + 3 + item.chars().count() + 1 > width {
            lines.push(format!(" {item}"));
        } else if line.is_empty() {
            line.push_str(&format!(" {item}"));
        } else {
            line.push_str(&format!(" · {item}"));
        }
    }
    lines
}
