//! The status bar: t, step, dt, integrator, collision response, declared effects, measured
//! cost per step, then key hints generated from the key table.

use super::app::{App, Comparison};
use super::keys::{Context, KEYS};
use crate::tables::number_plain;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

const KEY: Style = Style::new().fg(Color::Black).bg(Color::Gray);
const DIM: Style = Style::new().fg(Color::DarkGray);

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let s = &app.snapshot;
    let effects = app.world.effects().names();
    let response = app.world.contact_model().map_or("—", |m| m.response.name());
    let mut fields: Vec<(&str, String)> = vec![
        ("t", format!("{} s", number_plain(s.time))),
        ("step", s.step.to_string()),
        ("dt", format!("{} s", number_plain(s.dt))),
        // In compare mode, "A vs B" on the setting the ghost differs by, and only there.
        (
            "integrator",
            match app.ghost.as_ref().map(|g| g.comparison) {
                Some(Comparison::Integrator(i)) => {
                    format!("{} vs {}", s.integrator.name(), i.name())
                }
                _ => s.integrator.name().to_string(),
            },
        ),
        (
            "response",
            match app.ghost.as_ref().map(|g| g.comparison) {
                Some(Comparison::Response(r)) => format!("{response} vs {}", r.name()),
                _ => response.to_string(),
            },
        ),
        (
            "effects",
            if effects.is_empty() {
                "none".to_string()
            } else {
                effects.join(", ")
            },
        ),
    ];
    if app.show_timing {
        if let Some(ns) = app.ns_per_step {
            fields.push(("", format!("{ns:.0} ns/step")));
        }
    }
    let mut spans = vec![Span::raw(" ")];
    for (i, (name, value)) in fields.into_iter().enumerate() {
        if i > 0 {
            spans.push(Span::styled(" · ", DIM));
        }
        if !name.is_empty() {
            spans.push(Span::styled(format!("{name} "), DIM));
        }
        spans.push(Span::styled(
            value,
            Style::new().add_modifier(Modifier::BOLD),
        ));
    }
    buf.set_line(area.x, area.y, &Line::from(spans), area.width);
    // A notice (a pause, an applied setting, a file written) takes the first hint line, so it
    // is never cut off the end of a long status line; the hints come back at the next key.
    let mut y = area.y + 1;
    if let Some(notice) = &app.notice {
        if y < area.y + area.height {
            let line = Line::from(vec![
                Span::raw(" "),
                Span::styled(notice.clone(), Style::new().fg(Color::Yellow)),
            ]);
            buf.set_line(area.x, y, &line, area.width);
            y += 1;
        }
    }
    let rows = usize::from(area.y + area.height - y);
    for (i, line) in hints(area.width, rows).iter().take(rows).enumerate() {
        buf.set_line(area.x, y + i as u16, line, area.width);
    }
}

/// The key hints in key-table order (the key itself highlighted), wrapped onto lines of
/// `width` columns; hints that do not fit in `max_lines` are left to the help overlay.
pub fn hints(width: u16, max_lines: usize) -> Vec<Line<'static>> {
    let mut lines: Vec<Line<'static>> = vec![Line::raw(" ")];
    let mut used = 1usize;
    for b in KEYS
        .iter()
        .filter(|b| b.context == Context::Main && !b.hint.is_empty())
    {
        let item = b.hint.chars().count() + 2;
        if used + item > usize::from(width) {
            if lines.len() == max_lines {
                break;
            }
            lines.push(Line::raw(" "));
            used = 1;
        }
        used += item;
        let (key, what) = b.hint.split_once(' ').unwrap_or((b.hint, ""));
        let line = lines.last_mut().expect("one line at least");
        line.push_span(Span::styled(key.to_string(), KEY));
        line.push_span(Span::raw(format!(" {what}  ")));
    }
    lines
}
