//! The side projection: an orthographic view of the body's edges (or points), the ground line,
//! sphere and box obstacles, the contact points of the last collide phase, the barycenter trail
//! and, in compare mode, the ghost body. Pure ASCII (`--ascii`) or Braille dots.

use super::app::App;
use super::viewport::{Axis, Mapping};
use crate::physics::{Obstacle, Snapshot};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{self, Canvas, Circle, Points};
use ratatui::widgets::{Block, Widget};

/// How many past barycenter positions the trail shows.
pub const TRAIL_LENGTH: usize = 400;

const BODY: Color = Color::White;
const GHOST: Color = Color::Magenta;
const OBSTACLE: Color = Color::Blue;
const GROUND: Color = Color::Green;
const CONTACT: Color = Color::Red;
const TRAIL: Color = Color::DarkGray;

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let title = format!(" {} ({}) ", app.axis.name(), app.axis.legend());
    let block = Block::bordered().title(title);
    let inner = block.inner(area);
    block.render(area, buf);
    if inner.width < 4 || inner.height < 3 {
        return;
    }
    let drawing = Rect {
        height: inner.height - 1,
        ..inner
    };
    let mapping = Mapping::fit(&app.region, app.axis, drawing.width, drawing.height);
    if app.ascii {
        draw_ascii(app, &mapping, drawing, buf);
    } else {
        draw_braille(app, &mapping, drawing, buf);
    }
    legend(
        app,
        &mapping,
        Rect {
            y: inner.y + inner.height - 1,
            height: 1,
            ..inner
        },
        buf,
    );
}

fn legend(app: &App, mapping: &Mapping, area: Rect, buf: &mut Buffer) {
    let dim = Style::new().fg(Color::DarkGray);
    let mut spans = vec![
        Span::styled("@", Style::new().fg(BODY)),
        Span::styled(" center ", dim),
        Span::styled("*", Style::new().fg(CONTACT)),
        Span::styled(" contact ", dim),
    ];
    if app.trail {
        spans.push(Span::styled(".", Style::new().fg(TRAIL)));
        spans.push(Span::styled(" trail ", dim));
    }
    if let Some(g) = &app.ghost {
        spans.push(Span::styled(":", Style::new().fg(GHOST)));
        spans.push(Span::styled(format!(" {} ", g.comparison.name()), dim));
    }
    let scale = format!(
        "10 cols = {} m ",
        crate::tables::number_plain(10.0 * mapping.scale)
    );
    let width = scale.chars().count() as u16;
    let legend = Line::from(spans);
    if area.width > width + legend.width() as u16 {
        buf.set_string(area.x + area.width - width, area.y, scale, dim);
    }
    buf.set_line(area.x, area.y, &legend, area.width);
}

/// A segment: from, to, colour, and its ASCII character (None: chosen by slope).
type Segment = ((f64, f64), (f64, f64), Color, Option<char>);

/// Everything drawn, as 2-D screen segments and points (shared by both renderers).
struct Scene2d {
    segments: Vec<Segment>,
    /// (centre, radius, colour).
    circles: Vec<((f64, f64), f64, Color)>,
    /// (point, colour, ASCII char).
    points: Vec<((f64, f64), Color, char)>,
    /// y of the ground line, if visible.
    ground: Option<f64>,
}

fn body_segments(
    scene: &mut Scene2d,
    axis: Axis,
    s: &Snapshot,
    edges: &[(usize, usize)],
    colour: Color,
    ascii: Option<char>,
) {
    let p: Vec<(f64, f64)> = s.vertices.iter().map(|v| axis.project(v)).collect();
    for &(a, b) in edges {
        if let (Some(&pa), Some(&pb)) = (p.get(a), p.get(b)) {
            scene.segments.push((pa, pb, colour, ascii));
        }
    }
    if edges.is_empty() {
        for &q in &p {
            scene.points.push((q, colour, ascii.unwrap_or('o')));
        }
    }
}

fn scene_2d(app: &App) -> Scene2d {
    let axis = app.axis;
    let mut scene = Scene2d {
        segments: Vec::new(),
        circles: Vec::new(),
        points: Vec::new(),
        ground: None,
    };
    for o in app.world.obstacles() {
        match *o {
            Obstacle::Ground { height } => {
                if axis.shows_ground_line() {
                    scene.ground = Some(height);
                }
            }
            Obstacle::Sphere { center, radius } => {
                scene
                    .circles
                    .push((axis.project(&center), radius, OBSTACLE))
            }
            Obstacle::Box { min, max } => {
                let (a0, b0) = axis.project(&min);
                let (a1, b1) = axis.project(&max);
                let corners = [(a0, b0), (a1, b0), (a1, b1), (a0, b1)];
                for i in 0..4 {
                    scene
                        .segments
                        .push((corners[i], corners[(i + 1) % 4], OBSTACLE, Some('#')));
                }
            }
        }
    }
    if app.trail {
        for p in app.history.trail(TRAIL_LENGTH) {
            scene.points.push((axis.project(p), TRAIL, '.'));
        }
    }
    let edges = &app.world.body().edges;
    if let Some(g) = &app.ghost {
        body_segments(&mut scene, axis, &g.snapshot, edges, GHOST, Some(':'));
        scene
            .points
            .push((axis.project(&g.snapshot.position), GHOST, '%'));
    }
    body_segments(&mut scene, axis, &app.snapshot, edges, BODY, None);
    if edges.is_empty() {
        // Bare points are drawn as points already.
    } else {
        for v in &app.snapshot.vertices {
            scene.points.push((axis.project(v), BODY, '+'));
        }
    }
    scene
        .points
        .push((axis.project(&app.snapshot.position), BODY, '@'));
    for c in &app.snapshot.contacts {
        scene.points.push((axis.project(&c.point), CONTACT, '*'));
    }
    scene
}

fn put(buf: &mut Buffer, area: Rect, col: f64, row: f64, ch: char, colour: Color) {
    if !(col.is_finite() && row.is_finite()) || col < 0.0 || row < 0.0 {
        return;
    }
    let (c, r) = (col.floor(), row.floor());
    if c >= f64::from(area.width) || r >= f64::from(area.height) {
        return;
    }
    if let Some(cell) = buf.cell_mut((area.x + c as u16, area.y + r as u16)) {
        cell.set_char(ch).set_style(Style::new().fg(colour));
    }
}

/// The ASCII character for a segment's slope, given its extent in columns and rows (a row is
/// twice as tall as a column is wide).
fn slope_char(dc: f64, dr: f64) -> char {
    let angle = (2.0 * dr).atan2(dc).to_degrees().rem_euclid(180.0);
    if !(22.5..157.5).contains(&angle) {
        '-'
    } else if (67.5..112.5).contains(&angle) {
        '|'
    } else if angle < 90.0 {
        '\\'
    } else {
        '/'
    }
}

fn draw_ascii(app: &App, mapping: &Mapping, area: Rect, buf: &mut Buffer) {
    let scene = scene_2d(app);
    if let Some(height) = scene.ground {
        let (_, row) = mapping.cell(0.0, height);
        for col in 0..area.width {
            put(buf, area, f64::from(col), row, '=', GROUND);
        }
    }
    for &(centre, radius, colour) in &scene.circles {
        let n = ((radius / mapping.scale) * 8.0).clamp(16.0, 720.0) as usize;
        for i in 0..n {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            let (c, r) = mapping.cell(centre.0 + radius * a.cos(), centre.1 + radius * a.sin());
            put(buf, area, c, r, 'o', colour);
        }
    }
    for &(a, b, colour, ch) in &scene.segments {
        let (c0, r0) = mapping.cell(a.0, a.1);
        let (c1, r1) = mapping.cell(b.0, b.1);
        let (dc, dr) = (c1 - c0, r1 - r0);
        let n = (dc.abs().max(dr.abs()) * 2.0).ceil().clamp(1.0, 4096.0) as usize;
        let ch = ch.unwrap_or_else(|| slope_char(dc, dr));
        for i in 0..=n {
            let f = i as f64 / n as f64;
            put(buf, area, c0 + f * dc, r0 + f * dr, ch, colour);
        }
    }
    for &(p, colour, ch) in &scene.points {
        let (c, r) = mapping.cell(p.0, p.1);
        put(buf, area, c, r, ch, colour);
    }
}

fn draw_braille(app: &App, mapping: &Mapping, area: Rect, buf: &mut Buffer) {
    let scene = scene_2d(app);
    let (x_bounds, y_bounds) = mapping.bounds();
    let canvas = Canvas::default()
        .marker(Marker::Braille)
        .x_bounds(x_bounds)
        .y_bounds(y_bounds)
        .paint(|ctx| {
            if let Some(height) = scene.ground {
                ctx.draw(&canvas::Line::new(
                    x_bounds[0],
                    height,
                    x_bounds[1],
                    height,
                    GROUND,
                ));
            }
            for &(centre, radius, colour) in &scene.circles {
                ctx.draw(&Circle {
                    x: centre.0,
                    y: centre.1,
                    radius,
                    color: colour,
                });
            }
            for &(a, b, colour, _) in &scene.segments {
                ctx.draw(&canvas::Line::new(a.0, a.1, b.0, b.1, colour));
            }
            for &(p, colour, ch) in &scene.points {
                match ch {
                    '@' | '%' | '*' => ctx.print(
                        p.0,
                        p.1,
                        Span::styled(ch.to_string(), Style::new().fg(colour)),
                    ),
                    '+' => {}
                    _ => ctx.draw(&Points {
                        coords: &[p],
                        color: colour,
                    }),
                }
            }
        });
    canvas.render(area, buf);
}
