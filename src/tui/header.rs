//! The top line: the lesson's title and summary, and whether the simulation runs, at what speed.

use super::app::App;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let fps = app.frames_per_second();
    let real = fps * app.snapshot.dt;
    let state = if app.divergence.is_some() {
        Span::styled(" ✖ diverged ", Style::new().fg(Color::White).bg(Color::Red))
    } else if let (false, Some(stop)) = (app.running, &app.stop) {
        Span::styled(
            format!(" ❚❚ paused: {} ", stop.label),
            Style::new().fg(Color::Black).bg(Color::Yellow),
        )
    } else if app.running {
        Span::styled(
            " ▶ running ",
            Style::new().fg(Color::Black).bg(Color::Green),
        )
    } else {
        Span::styled(
            " ❚❚ paused ",
            Style::new().fg(Color::Black).bg(Color::Yellow),
        )
    };
    let speed = format!(" {fps} frames/s (×{} real time) ", trim(real));
    let right = Line::from(vec![state, Span::raw(speed)]);
    let right_width = right.width() as u16;
    let left = Line::from(vec![
        Span::styled(" tumble ", Style::new().fg(Color::Black).bg(Color::Cyan)),
        Span::styled(
            format!(" {} ", app.lesson.title),
            Style::new().add_modifier(Modifier::BOLD),
        ),
        Span::styled(
            format!("— {}", app.lesson.summary),
            Style::new().fg(Color::Gray),
        ),
    ]);
    let left_width = area.width.saturating_sub(right_width + 1);
    buf.set_line(area.x, area.y, &left, left_width);
    if area.width > right_width {
        buf.set_line(
            area.x + area.width - right_width,
            area.y,
            &right,
            right_width,
        );
    }
}

/// A ratio with at most 3 significant digits, no trailing zeros.
fn trim(x: f64) -> String {
    let s = if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 1.0 {
        format!("{x:.2}")
    } else {
        format!("{x:.3}")
    };
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}
