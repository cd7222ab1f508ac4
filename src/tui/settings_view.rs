//! The settings form overlay: each field with its unit, the selected one highlighted, the
//! problem found (if any) and the form's keys from the key table. When the fields do not fit
//! the screen, a window of them around the selected one is shown, with how many are above and
//! below.

use super::keys::{Context, KEYS};
use super::screen::centered;
use super::settings_form::SettingsForm;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

pub fn render(form: &SettingsForm, area: Rect, buf: &mut Buffer) {
    let label_width = form
        .fields
        .iter()
        .map(|f| form.label(f).0.chars().count())
        .max()
        .unwrap_or(0);
    let selected = Style::new()
        .fg(Color::Black)
        .bg(Color::Yellow)
        .add_modifier(Modifier::BOLD);
    let keys: Vec<String> = KEYS
        .iter()
        .filter(|b| b.context == Context::Form && b.label != "q")
        .map(|b| format!("{} {}", b.label, b.help.trim_start_matches("settings: ")))
        .collect();
    let key_lines = keys.len().div_ceil(2);
    // Borders, the heading, the problem line and the key lines around the fields.
    let room = usize::from(area.height)
        .saturating_sub(4 + key_lines)
        .max(3);
    let n = form.fields.len();
    let (first, shown) = if n <= room {
        (0, n)
    } else {
        // Two lines say what is above and below.
        let shown = room - 2;
        let first = form.selected.saturating_sub(shown / 2).min(n - shown);
        (first, shown)
    };
    let mut lines = vec![Line::styled(
        " ~ applies live; the other values restart the scene.",
        Style::new().fg(Color::Gray),
    )];
    let dim = Style::new().fg(Color::DarkGray);
    if n > room {
        lines.push(Line::styled(format!(" ↑ {first} more (↑ ↓ move)"), dim));
    }
    for (i, field) in form.fields.iter().enumerate().skip(first).take(shown) {
        let (label, unit) = form.label(field);
        let value = format!(" {:<14}", field.text);
        // Live values are marked: they apply without a restart.
        let live = if field.kind.is_live() { " ~" } else { "  " };
        lines.push(Line::from(vec![
            Span::styled(
                format!(" {label:>label_width$}"),
                Style::new().fg(Color::Cyan),
            ),
            Span::styled(live, Style::new().fg(Color::Green)),
            if i == form.selected {
                Span::styled(value, selected)
            } else {
                Span::raw(value)
            },
            Span::styled(format!(" {unit}"), Style::new().fg(Color::DarkGray)),
        ]));
    }
    if n > room {
        lines.push(Line::styled(format!(" ↓ {} more", n - first - shown), dim));
    }
    lines.push(match &form.error {
        Some(e) => Line::styled(format!(" ✖ {e}"), Style::new().fg(Color::Red)),
        None => Line::raw(""),
    });
    for pair in keys.chunks(2) {
        lines.push(Line::styled(
            format!(" {}", pair.join(" · ")),
            Style::new().fg(Color::DarkGray),
        ));
    }
    let width = lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16 + 3;
    let popup = centered(area, width, lines.len() as u16 + 2);
    Clear.render(popup, buf);
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(match &form.body_name {
                    Some(name) => format!(" settings of {name} — Esc closes, nothing applied "),
                    None => " settings — Esc closes, nothing applied ".to_string(),
                })
                .border_style(Style::new().fg(Color::Yellow)),
        )
        .render(popup, buf);
}
