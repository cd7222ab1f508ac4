//! The top line: the lesson's title and summary, and whether the simulation runs, at what speed.

use super::app::App;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let fps = app.frames_per_second();
    let real = fps * app.session.snapshot.dt;
    let state = if app.session.divergence.is_some() {
        Span::styled(" ✖ diverged ", theme::DIVERGED)
    } else if let (false, Some(stop)) = (app.ui.running, &app.ui.stop) {
        Span::styled(format!(" ❚❚ paused: {} ", stop.label), theme::PAUSED)
    } else if app.ui.running {
        Span::styled(" ▶ running ", theme::RUNNING)
    } else {
        Span::styled(" ❚❚ paused ", theme::PAUSED)
    };
    let measured = app.ui.measured_real_time.filter(|_| app.ui.running);
    let speed = speed_text(fps, real, measured);
    let right = Line::from(vec![state, Span::raw(speed)]);
    let right_width = right.width() as u16;
    let left_width = area.width.saturating_sub(right_width + 1);
    let title = format!(" {} ", app.session.lesson.title);
    // The summary ends with `…` where it is cut.
    let room = usize::from(left_width).saturating_sub(8 + title.chars().count());
    let mut summary = format!("— {}", app.session.lesson.summary);
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

/// ` 100 frames/s (×1 real time) `; when the physics cannot keep up (a measured multiple of
/// real time below 90 % of the one asked for), the measured one: ` 100 frames/s asked · ×0.03
/// real time `.
pub fn speed_text(fps: f64, real: f64, measured: Option<f64>) -> String {
    let frames = if fps == 1.0 { "frame" } else { "frames" };
    match measured {
        Some(m) if m < 0.9 * real => {
            format!(" {fps} {frames}/s asked · ×{} real time measured ", trim(m))
        }
        _ => format!(" {fps} {frames}/s (×{} real time) ", trim(real)),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_shows_the_measured_multiple_when_the_physics_cannot_keep_up() {
        // Asked: 1000 frames/s at dt = 1 ms, ×1; measured ×0.03: the header says ×0.03.
        assert_eq!(
            speed_text(1000.0, 1.0, Some(0.03)),
            " 1000 frames/s asked · ×0.03 real time measured "
        );
        // Keeping up (within 10 %), or nothing measured: the multiple asked for.
        assert_eq!(
            speed_text(1000.0, 1.0, Some(0.95)),
            " 1000 frames/s (×1 real time) "
        );
        assert_eq!(
            speed_text(1000.0, 1.0, None),
            " 1000 frames/s (×1 real time) "
        );
        // One frame per second is a frame, not frames.
        assert_eq!(speed_text(1.0, 0.01, None), " 1 frame/s (×0.01 real time) ");
    }
}
