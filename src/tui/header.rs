//! The top line: the lesson's title and summary, and whether the simulation runs, at what speed.

use super::app::App;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let fps = app.frames_per_second();
    let real = fps * app.snapshot.dt;
    let state = if app.divergence.is_some() {
        Span::styled(" ✖ diverged ", theme::DIVERGED)
    } else if let (false, Some(stop)) = (app.running, &app.stop) {
        Span::styled(format!(" ❚❚ paused: {} ", stop.label), theme::PAUSED)
    } else if app.running {
        Span::styled(" ▶ running ", theme::RUNNING)
    } else {
        Span::styled(" ❚❚ paused ", theme::PAUSED)
    };
    let speed = format!(" {fps} frames/s (×{} real time) ", trim(real));
    let right = Line::from(vec![state, Span::raw(speed)]);
    let right_width = right.width() as u16;
    let left_width = area.width.saturating_sub(right_width + 1);
    let title = format!(" {} ", app.lesson.title);
    // The summary ends with `…` where it is cut.
    let room = usize::from(left_width).saturating_sub(8 + title.chars().count());
    let mut summary = format!("— {}", app.lesson.summary);
    if summary.chars().count() > room {
        summary = summary
            .chars()
            .take(room.saturating_sub(1))
            .collect::<String>();
        summary = format!("{}…", summary.trim_end());
    }
    let left = Line::from(vec![
        Span::styled(" tumble ", theme::BRAND),
        Span::styled(title, Style::new().add_modifier(Modifier::BOLD)),
        Span::styled(summary, theme::SOFT),
    ]);
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
