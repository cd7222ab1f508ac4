//! The status bar: t, step, dt, integrator, collision response, declared effects, measured
//! cost per step, then key hints generated from the key table.

use super::app::{App, Comparison};
use super::keys::{Context, KEYS};
use super::theme;
use crate::tables::number_plain;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::{Line, Span};

const KEY: Style = theme::KEY;
const DIM: Style = theme::DIM;

/// The status fields, each a group of spans (the notice last, when `notice` and there is one).
fn fields(app: &App, notice: bool) -> Vec<Vec<Span<'static>>> {
    let s = &app.session.snapshot;
    let effects = s.effects.names();
    let response = s.contact_model.map_or("—", |m| m.response.name());
    let mut fields: Vec<(&str, String)> = Vec::new();
    let no_body = s.bodies.is_empty();
    if no_body {
        fields.push(("", super::panels::NO_BODY.to_string()));
    }
    if s.bodies.len() > 1 {
        fields.push((
            "body",
            format!("{} ({}/{})", s.body_name, s.body_index + 1, s.bodies.len()),
        ));
    }
    let comparison = app.session.ghost.as_ref().map(|g| g.comparison);
    // A diverged ghost is marked where its name is shown.
    let frozen = app
        .session
        .ghost
        .as_ref()
        .and_then(|g| g.diverged.as_ref())
        .map_or_else(String::new, |d| format!(" (diverged at step {})", d.step));
    fields.extend([
        ("t", format!("{} s", number_plain(s.time))),
        ("step", s.step.to_string()),
        ("dt", format!("{} s", number_plain(s.dt))),
    ]);
    // In compare mode, "A vs B" on the setting the ghost differs by, and only there. The
    // body integrator only when there are bodies, the response when bodies or particles can
    // touch (each response has a particle law), the particle integrator only with cloths.
    let bodies = !s.bodies.is_empty();
    if bodies {
        fields.push((
            "integrator",
            match comparison {
                Some(Comparison::Integrator(i)) => {
                    format!("{} vs {}{frozen}", s.integrator.name(), i.name())
                }
                _ => s.integrator.name().to_string(),
            },
        ));
    }
    if bodies || (!s.cloths.is_empty() && s.contact_model.is_some()) {
        fields.push((
            "response",
            match comparison {
                Some(Comparison::Response(r)) => format!("{response} vs {}{frozen}", r.name()),
                _ => response.to_string(),
            },
        ));
    }
    if let Some(own) = cloth_integrators(app) {
        fields.push((
            "cloth",
            match comparison {
                Some(Comparison::ClothIntegrator(c)) => format!("{own} vs {}{frozen}", c.name()),
                _ => own,
            },
        ));
    }
    if let Some(against) = &app.ui.against {
        fields.push(("theirs", against.status()));
    }
    fields.push((
        "effects",
        if effects.is_empty() {
            "none".to_string()
        } else {
            effects.join(", ")
        },
    ));
    if app.prefs.show_timing {
        if let Some(ns) = app.session.ns_per_step {
            fields.push(("", format!("{ns:.0} ns/step")));
        }
    }
    let mut items: Vec<Vec<Span<'static>>> = Vec::new();
    for (name, value) in fields {
        let mut item = Vec::new();
        if !name.is_empty() {
            item.push(Span::styled(format!("{name} "), DIM));
        }
        item.push(Span::styled(
            value,
            Style::new().add_modifier(Modifier::BOLD),
        ));
        items.push(item);
    }
    if let Some(notice) = app.ui.notice.as_ref().filter(|_| notice) {
        items.push(vec![Span::styled(notice.clone(), theme::NOTICE)]);
    }
    items
}

/// The particle integrators of the cloths, each named once in cloth order (None without
/// cloths).
fn cloth_integrators(app: &App) -> Option<String> {
    let mut names: Vec<&str> = Vec::new();
    for c in &app.session.snapshot.cloths {
        if !names.contains(&c.integrator) {
            names.push(c.integrator);
        }
    }
    (!names.is_empty()).then(|| names.join(" + "))
}

/// The status fields and the notice, whole, on as many lines of `width` columns as they need
/// (a field is never cut; one wider than the line is the only one on its line).
pub fn field_lines(app: &App, width: u16) -> Vec<Line<'static>> {
    lines_of(fields(app, true), width)
}

fn fields_without_notice(app: &App) -> Vec<Vec<Span<'static>>> {
    fields(app, false)
}

fn lines_of(fields: Vec<Vec<Span<'static>>>, width: u16) -> Vec<Line<'static>> {
    let mut lines: Vec<Line<'static>> = vec![Line::raw(" ")];
    for item in fields {
        let w: usize = item.iter().map(|s| s.width()).sum();
        let line = lines.last_mut().expect("one line at least");
        let used = line.width();
        if used > 1 && used + 3 + w > usize::from(width) {
            lines.push(Line::from(vec![Span::raw(" ")]));
        } else if used > 1 {
            line.push_span(Span::styled(" · ", DIM));
        }
        let line = lines.last_mut().expect("one line at least");
        for span in item {
            line.push_span(span);
        }
    }
    lines
}

/// Rows the status bar takes at this size: the fields, then one or two lines of hints (the
/// whole bar at most 3 rows in a terminal under 30 rows). The notice (a pause, a refused key)
/// is not counted: it takes a row of the hints, so a notice never takes a row from the panels
/// or the drawing above.
pub fn height(app: &App, width: u16, screen_height: u16) -> u16 {
    let fields = lines_of(fields(app, false), width).len();
    let hints = hints(width, 2).len();
    let cap = if screen_height < 30 { 3 } else { 4 };
    (fields + hints).min(cap).max(fields.min(cap)) as u16
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let mut fields = field_lines(app, area.width);
    if fields.len() > usize::from(area.height) {
        // No hint row left for the notice: it takes the last row (what the user must read).
        if let Some(notice) = &app.ui.notice {
            fields = lines_of(fields_without_notice(app), area.width);
            fields.truncate(usize::from(area.height).saturating_sub(1));
            fields.push(Line::from(vec![
                Span::raw(" "),
                Span::styled(notice.clone(), theme::NOTICE),
            ]));
        }
    }
    let mut row = area.y;
    for line in fields.iter().take(usize::from(area.height)) {
        buf.set_line(area.x, row, line, area.width);
        row += 1;
    }
    let rows = usize::from(area.y + area.height - row);
    for line in hints(area.width, rows) {
        if row >= area.y + area.height {
            break;
        }
        buf.set_line(area.x, row, &line, area.width);
        row += 1;
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
