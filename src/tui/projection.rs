//! The side projection: an orthographic view of the body's edges (or mass points), the cloths'
//! grids, the ground line, sphere and box obstacles, the contact points of the last collide phase, the barycenter
//! trail and, in compare mode, the ghost body. Pure ASCII (`--ascii`) or Braille dots.
//!
//! Depth cue: an edge whose two faces both turn away from the viewer is hidden behind the body
//! and drawn dimmed and dashed (dotted `.` in ASCII) (a box's faces come from its corner numbering; for other shapes
//! the edges behind the barycenter are dimmed). With arrows on (key `a`), the body axes x, y, z
//! are drawn from the barycenter in red, green, blue, and ω and L as labelled arrows of fixed
//! length (their directions matter: lesson 2 is about L not being parallel to ω).
//!
//! One body is drawn by [`add_body`] from a [`BodyPicture`] (vertices, edges, pose, colour),
//! so a scene with several bodies calls it once per body. A cloth is drawn by [`add_cloth`]:
//! its grid of particles joined along x and z, pinned particles marked `x`; in compare mode
//! the ghost's cloths too, in the ghost's colour. Joints and springs are drawn by
//! [`add_links`]: pivots, rods, hinge axes, springs as zigzags.

use super::app::App;
use super::theme;
use super::viewport::{Axis, Mapping, Viewport};
use crate::physics::body::box_edges;
use crate::physics::collision::geometry::Shape;
use crate::physics::snapshot::BodyView;
pub use crate::physics::wire::{wire, Wire};
use crate::physics::ClothView;
use crate::physics::{Outline, Snapshot};
use nalgebra::{Matrix3, Vector3};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{self, Canvas, Circle, Points};
use ratatui::widgets::{Block, Widget};

/// How many past barycenter positions the trail shows.
pub const TRAIL_LENGTH: usize = 400;

/// Length of the body axes, in body radii (they poke out of the body).
pub const AXIS_LENGTH: f64 = 1.25;
/// Length of the ω arrow, in body radii (L's is longer, so both tips show when parallel).
pub const OMEGA_LENGTH: f64 = 1.6;
pub const MOMENTUM_LENGTH: f64 = 2.0;

/// The smallest body the arrows are drawn on, in columns of its radius: on a smaller body
/// the axes, ω, L and their labels would cover it (a teacher found lesson 14's cubes hidden
/// under them), so they are left out and the legend says so.
pub const MIN_ARROW_RADIUS_COLUMNS: f64 = 3.0;

/// Whether the selected body is large enough on screen (`scale` m per column) for its arrows.
pub fn arrows_fit(app: &App, scale: f64) -> bool {
    app.session
        .snapshot
        .bodies
        .get(app.session.selected)
        .is_some_and(|b| b.radius >= MIN_ARROW_RADIUS_COLUMNS * scale)
}

/// The drawing's cells inside the projection pane `area` (its border and legend line left
/// out), None when too small to draw.
fn drawing_area(area: Rect) -> Option<Rect> {
    let inner = Block::bordered().inner(area);
    if inner.width < 4 || inner.height < 3 {
        return None;
    }
    Some(Rect {
        height: inner.height - 1,
        ..inner
    })
}

/// Where the projection pane `area` draws the world: its drawing's cells and their mapping
/// (the view region fitted, then the user's zoom). What the mouse points at
/// ([`Viewport::world_at`]).
pub fn viewport(app: &App, area: Rect) -> Option<Viewport> {
    let drawing = drawing_area(area)?;
    let mapping = Mapping::fit(
        &app.ui.region,
        app.prefs.axis,
        drawing.width,
        drawing.height,
    );
    Some(Viewport {
        area: drawing,
        mapping: mapping.zoomed(&app.ui.zoom),
        axis: app.prefs.axis,
    })
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let title = format!(" {} ({}) ", app.prefs.axis.name(), app.prefs.axis.legend());
    let block = Block::bordered().title(title);
    let inner = block.inner(area);
    block.render(area, buf);
    let Some(Viewport {
        area: drawing,
        mapping,
        ..
    }) = viewport(app, area)
    else {
        return;
    };
    let mut scene = scene_2d(app, mapping.scale);
    let forces = if app.prefs.forces {
        add_forces(app, &mapping, &mut scene)
    } else {
        None
    };
    add_hand(app, &mut scene);
    if app.prefs.ascii {
        draw_ascii(&scene, &mapping, drawing, buf);
    } else {
        draw_braille(&scene, &mapping, drawing, buf);
    }
    legend(
        app,
        &mapping,
        forces,
        Rect {
            y: inner.y + inner.height - 1,
            height: 1,
            ..inner
        },
        buf,
    );
}

/// A round length (1, 2 or 5 × 10ⁿ m) that spans between 4 and 10 columns at `scale` m per
/// column, and its width in columns.
pub fn scale_bar(scale: f64) -> (f64, usize) {
    let target = 6.0 * scale;
    let decade = 10f64.powf(target.log10().floor());
    let length = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .min_by(|a, b| (a / target).ln().abs().total_cmp(&(b / target).ln().abs()))
        .unwrap_or(decade);
    (length, (length / scale).round().max(1.0) as usize)
}

/// A length with the digits it needs: `0.5`, `20`, `1e-4`.
pub fn short_length(x: f64) -> String {
    if x != 0.0 && !(1e-3..1e4).contains(&x.abs()) {
        return format!("{x:e}");
    }
    let s = format!("{x:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn legend(
    app: &App,
    mapping: &Mapping,
    forces: Option<(f64, usize)>,
    area: Rect,
    buf: &mut Buffer,
) {
    let dim = theme::DIM;
    let item = |mark: &str, colour: Color, what: String| {
        vec![
            Span::styled(mark.to_string(), Style::new().fg(colour)),
            Span::styled(format!(" {what} "), dim),
        ]
    };
    let mut items = Vec::new();
    if let Some((newtons, cols)) = forces {
        // First: the force scale and the arrows' letters in their colours.
        let mut forces = vec![Span::styled(
            format!(
                "├{}┤ {} N ",
                "─".repeat(cols.saturating_sub(2)),
                short_length(newtons)
            ),
            dim,
        )];
        for (letter, colour) in [
            ("g", theme::FORCE_GRAVITY),
            ("c", theme::FORCE_CONTACT),
            ("j", theme::FORCE_JOINT),
            ("s", theme::FORCE_SPRING),
        ] {
            forces.push(Span::styled(letter, Style::new().fg(colour)));
        }
        forces.push(Span::styled(" forces ", dim));
        items.push(forces);
    }
    if app.session.snapshot.hand.is_some() {
        // First while a body is held: what the line from it to the pointer is.
        items.push(item("o~x", theme::HAND, "hand".into()));
    }
    let body = app.session.snapshot.bodies.get(app.session.selected);
    let arrows = app.prefs.arrows && arrows_fit(app, mapping.scale);
    if arrows {
        items.push(item("ω", theme::OMEGA, "ang. vel.".into()));
        items.push(item("L", theme::MOMENTUM, "ang. mom.".into()));
    } else if app.prefs.arrows && body.is_some() {
        items.push(item("ω L", Color::DarkGray, "hidden: body small".into()));
    }
    if body.is_some() {
        items.push(item("@", theme::BODY, "center".into()));
    }
    if !app.session.snapshot.cloths.is_empty() {
        items.push(item("#", theme::CLOTH, "cloth".into()));
        if app
            .session
            .snapshot
            .cloths
            .iter()
            .any(|c| c.pins.contains(&true))
        {
            items.push(item("x", theme::PINNED, "pinned".into()));
        }
    }
    if !app.session.snapshot.joints.is_empty() {
        items.push(item("o", theme::JOINT, "pivot, rod".into()));
    }
    if !app.session.snapshot.springs.is_empty() {
        items.push(item("/\\/", theme::SPRING, "spring".into()));
    }
    if body.is_some_and(|b| !b.edges.is_empty()) {
        let mark = if app.prefs.ascii { "..." } else { "- -" };
        items.push(item(mark, theme::HIDDEN, "hidden".into()));
    }
    if arrows {
        items.push(vec![
            Span::styled("x", Style::new().fg(theme::AXES[0])),
            Span::styled("y", Style::new().fg(theme::AXES[1])),
            Span::styled("z", Style::new().fg(theme::AXES[2])),
            Span::styled(" body axes ", dim),
        ]);
    }
    items.push(item("*", theme::CONTACT, "contact".into()));
    if app.prefs.trail && body.is_some() {
        items.push(item(".", theme::TRAIL, "trail".into()));
    }
    if let Some(g) = &app.session.ghost {
        items.push(item(":", theme::GHOST, g.comparison.name().into()));
    }
    if app.ui.against.is_some() {
        items.push(item(":", theme::GHOST, "theirs".into()));
    }
    let (length, cols) = scale_bar(mapping.scale);
    let bar = format!(
        "├{}┤ {} m ",
        "─".repeat(cols.saturating_sub(2)),
        short_length(length)
    );
    let bar_width = bar.chars().count() as u16;
    // Whole items only, left to right, as many as fit beside the scale bar.
    let mut spans = Vec::new();
    let mut used = 0u16;
    let room = area.width.saturating_sub(bar_width + 1);
    for it in items {
        let w = Line::from(it.clone()).width() as u16;
        if used + w > room {
            break;
        }
        used += w;
        spans.extend(it);
    }
    buf.set_line(area.x, area.y, &Line::from(spans), area.width);
    if area.width > bar_width {
        buf.set_string(area.x + area.width - bar_width, area.y, bar, dim);
    }
}

/// The longest force arrow, columns.
pub const FORCE_ARROW_COLUMNS: f64 = 8.0;

/// Adds the force arrows (key `F`, [`crate::physics::force_arrows`]) to the drawing: one
/// scale for all, the largest force [`FORCE_ARROW_COLUMNS`] long; a force under 2 % of the
/// largest is left out. Returns the legend's scale bar: a round force (1, 2 or 5 × 10ⁿ N) and
/// its width in columns (None: no force to draw).
fn add_forces(app: &App, mapping: &Mapping, scene: &mut Scene2d) -> Option<(f64, usize)> {
    use crate::physics::force_arrows::{force_arrows, ForceKind};
    let arrows = force_arrows(
        &app.session.snapshot,
        app.session.snapshot.effects.gravity(),
    );
    let largest = arrows.iter().map(|a| a.force.norm()).fold(0.0, f64::max);
    if largest <= 0.0 || !largest.is_finite() {
        return None;
    }
    // Metres of drawing per newton.
    let per_newton = FORCE_ARROW_COLUMNS * mapping.scale / largest;
    for a in arrows {
        let f = a.force.norm();
        if f < 0.02 * largest {
            continue;
        }
        let colour = match a.kind {
            ForceKind::Gravity => theme::FORCE_GRAVITY,
            ForceKind::Contact => theme::FORCE_CONTACT,
            ForceKind::Joint => theme::FORCE_JOINT,
            ForceKind::Spring => theme::FORCE_SPRING,
        };
        arrow(
            scene,
            app.prefs.axis,
            a.at,
            a.force / f,
            f * per_newton,
            colour,
            a.kind.letter(),
            2,
        );
    }
    // The bar: a round force near half the largest, in columns of its arrow length.
    let (newtons, _) = scale_bar(largest / 2.0 / 6.0);
    let cols = (newtons * per_newton / mapping.scale).round().max(2.0) as usize;
    Some((newtons, cols))
}

/// The hand (the mouse's drag spring, `physics::hand`), while a body is held: a line from the
/// grabbed point to the pointer, a mark at each end, and the pull's size at the pointer.
fn add_hand(app: &App, scene: &mut Scene2d) {
    let (Some(hand), Some(pull)) = (app.session.snapshot.hand, app.session.snapshot.hand_pull)
    else {
        return;
    };
    let (from, to) = (
        app.prefs.axis.project(&pull.at),
        app.prefs.axis.project(&hand.target),
    );
    scene.segments.push(Segment {
        from,
        to,
        colour: theme::HAND,
        ascii: Some('~'),
        dashed: false,
    });
    scene.points.push((from, theme::HAND, 'o'));
    scene.points.push((to, theme::HAND, 'x'));
    scene.labels.push(Label {
        at: to,
        colour: theme::HAND,
        text: format!("hand {} N", short_length(pull.force.norm())),
        past: None,
        shift: (1, 0),
    });
}

/// A screen segment: ends, colour, its ASCII character (None: chosen by slope), dashed.
#[derive(Debug, Clone, Copy)]
pub struct Segment {
    pub from: (f64, f64),
    pub to: (f64, f64),
    pub colour: Color,
    pub ascii: Option<char>,
    pub dashed: bool,
}

/// Everything drawn, as 2-D screen segments, points and labels (shared by both renderers).
#[derive(Debug, Default)]
pub struct Scene2d {
    pub segments: Vec<Segment>,
    /// (centre, radius, colour).
    pub circles: Vec<((f64, f64), f64, Color)>,
    /// (point, colour, ASCII char): `@ % * x o O` print as characters in Braille too; others
    /// are dots.
    pub points: Vec<((f64, f64), Color, char)>,
    /// Text printed at a point (arrow labels, arrow heads), in both renderers: point, colour,
    /// text, and a screen direction to move it one cell along (a label past an arrow's head).
    pub labels: Vec<Label>,
    /// y of the ground line, if visible.
    pub ground: Option<f64>,
}

/// Text at a point of the drawing.
#[derive(Debug, Clone)]
pub struct Label {
    pub at: (f64, f64),
    pub colour: Color,
    pub text: String,
    /// Move the text one cell this way (screen right, up) from `at`.
    pub past: Option<(f64, f64)>,
    /// Then move it by whole cells (columns, rows down).
    pub shift: (i16, i16),
}

/// The cell a label starts at.
fn label_cell(mapping: &Mapping, label: &Label) -> (f64, f64) {
    let (c, r) = mapping.cell(label.at.0, label.at.1);
    let (c, r) = (c + f64::from(label.shift.0), r + f64::from(label.shift.1));
    match label.past {
        None => (c, r),
        Some((dx, dy)) => {
            let n = dx.hypot(dy).max(1e-300);
            (c + (1.4 * dx / n).round(), r - (dy / n).round())
        }
    }
}

/// One body to draw.
#[derive(Debug, Clone, Copy)]
pub struct BodyPicture<'a> {
    /// World positions of the body's points.
    pub vertices: &'a [Vector3<f64>],
    /// Edges between points (empty: a bare point set, drawn as mass points).
    pub edges: &'a [(usize, usize)],
    /// Barycenter.
    pub position: Vector3<f64>,
    /// Body → world rotation (its columns are the body axes).
    pub rotation: Matrix3<f64>,
    /// Largest distance of a point from the barycenter, m (arrow lengths are in these).
    pub radius: f64,
    pub colour: Color,
    /// The ghost: every edge drawn with this ASCII character, no mass points.
    pub ascii: Option<char>,
    /// Body axes and the ω and L arrows (world frame), when shown.
    pub arrows: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl<'a> BodyPicture<'a> {
    /// The picture of a snapshot of a body with these edges.
    pub fn of(s: &'a Snapshot, edges: &'a [(usize, usize)], radius: f64) -> BodyPicture<'a> {
        BodyPicture {
            vertices: &s.vertices,
            edges,
            position: s.position,
            rotation: s.rotation,
            radius,
            colour: theme::BODY,
            ascii: None,
            arrows: None,
        }
    }
}

/// Which edges are hidden behind the body, seen from `toward` (unit vector to the viewer).
///
/// A box (8 corners numbered as in `box_corners`, its 12 edges): an edge joins two faces, and
/// is hidden when both face away from the viewer (outward normal · toward < 0, the normal
/// being the face centre minus the box centre). Other shapes: an edge is hidden when both its
/// ends lie behind the barycenter by more than a tenth of the body's radius.
pub fn hidden_edges(
    vertices: &[Vector3<f64>],
    edges: &[(usize, usize)],
    position: &Vector3<f64>,
    toward: &Vector3<f64>,
    radius: f64,
) -> Vec<bool> {
    let is_box = vertices.len() == 8 && edges == box_edges().as_slice();
    if is_box {
        let centre = vertices.iter().sum::<Vector3<f64>>() / 8.0;
        // Face (bit, side): the 4 corners whose `bit` is `side`.
        let faces_toward = |bit: usize, side: usize| {
            let c = (0..8)
                .filter(|k| (k >> bit) & 1 == side)
                .map(|k| vertices[k])
                .sum::<Vector3<f64>>()
                / 4.0;
            let n = c - centre;
            n.dot(toward) > 1e-9 * n.norm().max(1e-300)
        };
        edges
            .iter()
            .map(|&(i, j)| {
                let along = (0..3).find(|b| ((i ^ j) >> b) & 1 == 1).unwrap_or(0);
                !(0..3)
                    .filter(|&b| b != along)
                    .any(|b| faces_toward(b, (i >> b) & 1))
            })
            .collect()
    } else {
        let behind = |v: &Vector3<f64>| (v - position).dot(toward) < -0.1 * radius;
        edges
            .iter()
            .map(|&(i, j)| match (vertices.get(i), vertices.get(j)) {
                (Some(a), Some(b)) => behind(a) && behind(b),
                _ => false,
            })
            .collect()
    }
}

/// Adds one body to the scene: hidden edges first (dimmed, dashed), then the visible ones, the
/// mass points of a point set, the barycenter, and the arrows when asked for.
pub fn add_body(scene: &mut Scene2d, axis: Axis, body: &BodyPicture) {
    let p: Vec<(f64, f64)> = body.vertices.iter().map(|v| axis.project(v)).collect();
    let hidden = hidden_edges(
        body.vertices,
        body.edges,
        &body.position,
        &axis.toward_viewer(),
        body.radius,
    );
    let centre = axis.project(&body.position);
    for pass_hidden in [true, false] {
        for (k, &(a, b)) in body.edges.iter().enumerate() {
            if hidden[k] != pass_hidden {
                continue;
            }
            if let (Some(&pa), Some(&pb)) = (p.get(a), p.get(b)) {
                let (colour, ascii) = match (pass_hidden, body.ascii) {
                    (true, None) => (theme::HIDDEN, Some('.')),
                    _ => (body.colour, body.ascii),
                };
                scene.segments.push(Segment {
                    from: pa,
                    to: pb,
                    colour,
                    ascii,
                    dashed: pass_hidden,
                });
            }
        }
    }
    if body.edges.is_empty() {
        // A point set: spokes from the barycenter (the body is rigid), the points as discs.
        for &q in &p {
            if body.ascii.is_none() {
                scene.segments.push(Segment {
                    from: centre,
                    to: q,
                    colour: theme::HIDDEN,
                    ascii: Some('.'),
                    dashed: false,
                });
            }
        }
        let (colour, mark) = match body.ascii {
            Some(c) => (body.colour, c),
            None => (theme::MASS_POINT, 'O'),
        };
        for &q in &p {
            scene.points.push((q, colour, mark));
        }
    } else if body.ascii.is_none() {
        for &q in &p {
            scene.points.push((q, body.colour, '+'));
        }
    }
    if let Some((omega, momentum)) = body.arrows {
        let r = body.radius.max(1e-6);
        for (i, name) in ["x", "y", "z"].iter().enumerate() {
            let d = body.rotation.column(i).into_owned();
            arrow(
                scene,
                axis,
                body.position,
                d,
                AXIS_LENGTH * r,
                theme::AXES[i],
                name,
                -1,
            );
        }
        for (v, length, colour, name, row) in [
            (omega, OMEGA_LENGTH, theme::OMEGA, "ω", 1),
            (momentum, MOMENTUM_LENGTH, theme::MOMENTUM, "L", 2),
        ] {
            if v.norm() > 1e-12 {
                arrow(
                    scene,
                    axis,
                    body.position,
                    v.normalize(),
                    length * r,
                    colour,
                    name,
                    row,
                );
            }
        }
    }
    let mark = if body.ascii.is_some() { '%' } else { '@' };
    scene.points.push((centre, body.colour, mark));
}

/// An arrow from `from` along the unit vector `d`, `length` long, labelled at its tip. Seen
/// end-on (shorter on screen than a tenth of its length) only the label is drawn, beside the
/// base, `end_on_row` rows below it (so end-on labels do not cover each other), with ⊙ when it
/// points towards the viewer, ⊗ away.
#[allow(clippy::too_many_arguments)]
fn arrow(
    scene: &mut Scene2d,
    axis: Axis,
    from: Vector3<f64>,
    d: Vector3<f64>,
    length: f64,
    colour: Color,
    name: &str,
    end_on_row: i16,
) {
    let a = axis.project(&from);
    let b = axis.project(&(from + d * length));
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let shown = (dx * dx + dy * dy).sqrt();
    if shown < 0.1 * length {
        let toward = d.dot(&axis.toward_viewer());
        let mark = if toward > 0.0 { "⊙" } else { "⊗" };
        scene.labels.push(Label {
            at: a,
            colour,
            text: format!("{name}{mark}"),
            past: None,
            shift: (1, end_on_row),
        });
        return;
    }
    scene.segments.push(Segment {
        from: a,
        to: b,
        colour,
        ascii: None,
        dashed: false,
    });
    // The head by the arrow's direction as seen (screen units are square).
    let head = if dx.abs() >= dy.abs() {
        if dx > 0.0 {
            '>'
        } else {
            '<'
        }
    } else if dy > 0.0 {
        '^'
    } else {
        'v'
    };
    scene.labels.push(Label {
        at: b,
        colour,
        text: head.to_string(),
        past: None,
        shift: (0, 0),
    });
    // The name one cell past the head.
    scene.labels.push(Label {
        at: b,
        colour,
        text: name.to_string(),
        past: Some((dx, dy)),
        shift: (0, 0),
    });
}

/// Adds one cloth: its grid (a segment between each particle and its neighbour along x and
/// along z, the stretch springs' rest pattern — not the shear or bend springs), and its
/// pinned particles as `x` in [`theme::PINNED`]. `ascii`: the ghost's cloth, every segment
/// drawn with this character in `colour`, pinned particles not marked.
pub fn add_cloth(
    scene: &mut Scene2d,
    axis: Axis,
    cloth: &ClothView,
    colour: Color,
    ascii: Option<char>,
) {
    let [nx, nz] = cloth.grid;
    let p: Vec<(f64, f64)> = cloth.positions.iter().map(|x| axis.project(x)).collect();
    scene.segments.reserve(2 * nx * nz);
    for j in 0..nz {
        for i in 0..nx {
            let a = p[cloth.index(i, j)];
            let mut to = |b: usize| {
                scene.segments.push(Segment {
                    from: a,
                    to: p[b],
                    colour,
                    ascii,
                    dashed: false,
                })
            };
            if i + 1 < nx {
                to(cloth.index(i + 1, j));
            }
            if j + 1 < nz {
                to(cloth.index(i, j + 1));
            }
        }
    }
    if ascii.is_none() {
        for (k, &pinned) in cloth.pins.iter().enumerate() {
            if pinned {
                scene.points.push((p[k], theme::PINNED, 'x'));
            }
        }
    }
}

/// Half-turns of a spring's zigzag: about one per two columns of its length, 4 to 16.
fn zigzag_turns(columns: f64) -> usize {
    ((columns / 2.0).round() as usize).clamp(4, 16)
}

/// Adds the joints and springs of a snapshot, in [`theme::JOINT`] and [`theme::SPRING`];
/// `scale` is the view's metres per column (the marks' size on screen).
///
/// - a pivot `o` at each anchor on the world, and at a ball, hinge or fixed joint's anchor
///   between two bodies;
/// - a rod: a distance joint's, between its two anchors, and for every joint the arm from each
///   body's barycenter to its anchor (a physical pendulum's arm);
/// - a hinge's axis: a short line through the anchor along it, or seen end-on `⊙` (towards the
///   viewer) or `⊗` (away) on the pivot;
/// - a spring: a zigzag between its ends, one column to either side of the line.
pub fn add_links(scene: &mut Scene2d, axis: Axis, s: &Snapshot, scale: f64) {
    let centre_of = |name: &str| s.bodies.iter().find(|b| b.name == name).map(|b| b.position);
    let rod = |scene: &mut Scene2d, from: &Vector3<f64>, to: &Vector3<f64>| {
        let (a, b) = (axis.project(from), axis.project(to));
        if (a.0 - b.0).hypot(a.1 - b.1) > 1e-12 {
            scene.segments.push(Segment {
                from: a,
                to: b,
                colour: theme::JOINT,
                ascii: None,
                dashed: false,
            });
        }
    };
    for j in &s.joints {
        let [pa, pb] = j.anchors;
        if let Some(x) = centre_of(&j.bodies.0) {
            rod(scene, &x, &pa);
        }
        if let Some(x) = j.bodies.1.as_deref().and_then(centre_of) {
            rod(scene, &x, &pb);
        }
        if j.length.is_some() {
            rod(scene, &pa, &pb);
        }
        let pivot = if j.bodies.1.is_none() || j.length.is_none() {
            Some(pb)
        } else {
            None
        };
        if let Some(p) = pivot {
            scene.points.push((axis.project(&p), theme::JOINT, 'o'));
        }
        if let Some(h) = &j.axis {
            let half = h * (1.5 * scale);
            let (a, b) = (axis.project(&(pb - half)), axis.project(&(pb + half)));
            if (a.0 - b.0).hypot(a.1 - b.1) < 0.3 * scale {
                let mark = if h.dot(&axis.toward_viewer()) > 0.0 {
                    "⊙"
                } else {
                    "⊗"
                };
                scene.labels.push(Label {
                    at: axis.project(&pb),
                    colour: theme::JOINT,
                    text: mark.to_string(),
                    past: None,
                    shift: (0, 0),
                });
            } else {
                scene.segments.push(Segment {
                    from: a,
                    to: b,
                    colour: theme::JOINT,
                    ascii: Some('='),
                    dashed: false,
                });
            }
        }
    }
    for sp in &s.springs {
        let (a, b) = (axis.project(&sp.ends[0]), axis.project(&sp.ends[1]));
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let shown = dx.hypot(dy);
        if shown < 1e-12 {
            continue;
        }
        let turns = zigzag_turns(shown / scale.max(1e-300));
        // One column to either side, across the line as seen.
        let (nx, ny) = (-dy / shown * scale, dx / shown * scale);
        let at = |k: usize| {
            let f = k as f64 / (turns + 1) as f64;
            let side = match k {
                0 => 0.0,
                k if k == turns + 1 => 0.0,
                k if k % 2 == 1 => 1.0,
                _ => -1.0,
            };
            (a.0 + f * dx + side * nx, a.1 + f * dy + side * ny)
        };
        for k in 0..=turns {
            scene.segments.push(Segment {
                from: at(k),
                to: at(k + 1),
                colour: theme::SPRING,
                ascii: None,
                dashed: false,
            });
        }
    }
}

fn scene_2d(app: &App, scale: f64) -> Scene2d {
    let axis = app.prefs.axis;
    let mut scene = Scene2d::default();
    // The obstacles under everything; the fixed bodies in their place among the bodies.
    let snapshot = &app.session.snapshot;
    let extent = app.ui.region.max_extent;
    for f in snapshot.fixed.iter().filter(|f| f.body.is_none()) {
        add_fixed(&mut scene, axis, &f.outline, extent);
    }
    if app.prefs.trail && !app.session.snapshot.bodies.is_empty() {
        for p in app.session.history.trail(TRAIL_LENGTH) {
            scene.points.push((axis.project(p), theme::TRAIL, '.'));
        }
    }
    // The cloths under the bodies (a body resting on a sheet is drawn on top of it).
    if let Some(g) = &app.session.ghost {
        for cloth in &g.snapshot.cloths {
            add_cloth(&mut scene, axis, cloth, theme::GHOST, Some(':'));
        }
    }
    for cloth in &app.session.snapshot.cloths {
        add_cloth(&mut scene, axis, cloth, theme::CLOTH, None);
    }
    // The joints and springs under the bodies they hold.
    add_links(&mut scene, axis, &app.session.snapshot, scale);
    // Every other body, in its own colour (the panels show the selected one); a fixed body
    // as the fixed thing it is.
    for (i, view) in app.session.snapshot.bodies.iter().enumerate() {
        if i == app.session.selected {
            continue;
        }
        if view.fixed {
            for f in snapshot.fixed.iter().filter(|f| f.body == Some(i)) {
                add_fixed(&mut scene, axis, &f.outline, extent);
            }
            continue;
        }
        let other = view;
        let wire = view
            .shape
            .as_ref()
            .and_then(|s| wire(s, &view.position, &view.rotation));
        let (vertices, edges) = match &wire {
            Some((v, e)) => (v.as_slice(), e.as_slice()),
            None => (view.vertices.as_slice(), other.edges.as_slice()),
        };
        let picture = BodyPicture {
            vertices,
            edges,
            position: view.position,
            rotation: view.rotation,
            radius: other.radius,
            colour: theme::OTHER_BODY,
            ascii: None,
            arrows: None,
        };
        add_outline(&mut scene, axis, view);
        add_body(&mut scene, axis, &picture);
    }
    if let Some(body) = app.session.snapshot.bodies.get(app.session.selected) {
        let view = Some(body);
        if let Some(g) = &app.session.ghost {
            let ghost_wire = g
                .snapshot
                .bodies
                .get(app.session.selected)
                .and_then(|v| v.shape.as_ref().map(|s| wire(s, &v.position, &v.rotation)))
                .flatten();
            let mut ghost = BodyPicture::of(&g.snapshot, &body.edges, body.radius);
            if let Some((v, e)) = &ghost_wire {
                (ghost.vertices, ghost.edges) = (v, e);
            }
            ghost.colour = theme::GHOST;
            ghost.ascii = Some(':');
            add_body(&mut scene, axis, &ghost);
        }
        // Their run (`--against`): the body's points at their pose, in the ghost's colour.
        let theirs = (app.ui.against.as_ref())
            .and_then(|a| a.pose_at(app.session.snapshot.step))
            .map(|(x, r)| {
                let points: Vec<_> = body.points_body.iter().map(|p| x + r * p).collect();
                (x, r, points)
            });
        if let Some((position, rotation, vertices)) = &theirs {
            let picture = BodyPicture {
                vertices,
                edges: &body.edges,
                position: *position,
                rotation: *rotation,
                radius: body.radius,
                colour: theme::GHOST,
                ascii: Some(':'),
                arrows: None,
            };
            add_body(&mut scene, axis, &picture);
        }
        let own_wire = view
            .and_then(|v| v.shape.as_ref().map(|s| wire(s, &v.position, &v.rotation)))
            .flatten();
        let mut picture = BodyPicture::of(&app.session.snapshot, &body.edges, body.radius);
        if let Some((v, e)) = &own_wire {
            (picture.vertices, picture.edges) = (v, e);
        }
        if body.fixed {
            picture.colour = theme::OBSTACLE;
        }
        if app.prefs.arrows && arrows_fit(app, scale) {
            picture.arrows = Some((
                app.session.snapshot.angular_velocity,
                app.session.snapshot.angular_momentum,
            ));
        }
        if let Some(view) = view {
            add_outline(&mut scene, axis, view);
        }
        add_body(&mut scene, axis, &picture);
    }
    for c in &app.session.snapshot.contacts {
        scene
            .points
            .push((axis.project(&c.point), theme::CONTACT, '*'));
    }
    scene
}

/// One fixed thing (`Snapshot::fixed`) in the obstacles' colour: the ground's level, a
/// plane's trace, a sphere's circle, a box's rectangle or wire, and a fixed body's wire with
/// its hidden edges dashed and its barycenter marked (a fixed ball also its silhouette).
fn add_fixed(scene: &mut Scene2d, axis: Axis, outline: &Outline, extent: f64) {
    match outline {
        Outline::Level(height) => {
            if axis.shows_ground_line() {
                scene.ground = Some(*height);
            }
        }
        Outline::Ball { center, radius } => {
            scene
                .circles
                .push((axis.project(center), *radius, theme::OBSTACLE))
        }
        Outline::Aligned { min, max } => {
            let (a0, b0) = axis.project(min);
            let (a1, b1) = axis.project(max);
            let corners = [(a0, b0), (a1, b0), (a1, b1), (a0, b1)];
            for i in 0..4 {
                scene.segments.push(Segment {
                    from: corners[i],
                    to: corners[(i + 1) % 4],
                    colour: theme::OBSTACLE,
                    ascii: Some('#'),
                    dashed: false,
                });
            }
        }
        Outline::Wire { corners, edges } => {
            let corners: Vec<_> = corners.iter().map(|c| axis.project(c)).collect();
            for &(i, j) in edges {
                scene.segments.push(Segment {
                    from: corners[i],
                    to: corners[j],
                    colour: theme::OBSTACLE,
                    ascii: Some('#'),
                    dashed: false,
                });
            }
        }
        Outline::Plane { point, normal } => {
            add_plane(scene, axis, point, normal, extent);
        }
        Outline::Body {
            corners,
            edges,
            center,
            radius,
            silhouette,
        } => {
            if let Some(r) = silhouette {
                scene
                    .circles
                    .push((axis.project(center), *r, theme::OBSTACLE));
            }
            let picture = BodyPicture {
                vertices: corners,
                edges,
                position: *center,
                rotation: Matrix3::identity(),
                radius: *radius,
                colour: theme::OBSTACLE,
                ascii: Some('#'),
                arrows: None,
            };
            add_body(scene, axis, &picture);
        }
    }
}

/// A ball's silhouette: the circle of its radius about its centre, seen from any side.
fn add_outline(scene: &mut Scene2d, axis: Axis, view: &BodyView) {
    if let Some(Shape::Ball { radius }) = view.shape {
        let colour = if view.fixed {
            theme::OBSTACLE
        } else {
            theme::BODY
        };
        scene
            .circles
            .push((axis.project(&view.position), radius, colour));
    }
}

/// A plane obstacle: its trace in the view (a line through the plane's point, across the
/// projected normal) with short hatches every so often on the solid side. Seen edge-on
/// only: a plane facing the viewer has no trace to draw.
fn add_plane(
    scene: &mut Scene2d,
    axis: Axis,
    point: &Vector3<f64>,
    normal: &Vector3<f64>,
    extent: f64,
) {
    let origin = axis.project(point);
    let tip = axis.project(&(point + normal));
    let n = (tip.0 - origin.0, tip.1 - origin.1);
    let length = n.0.hypot(n.1);
    if length < 0.2 {
        return;
    }
    let n = (n.0 / length, n.1 / length);
    let along = (-n.1, n.0);
    let reach = 4.0 * extent.max(1e-3);
    let at = |s: f64| (origin.0 + along.0 * s, origin.1 + along.1 * s);
    scene.segments.push(Segment {
        from: at(-reach),
        to: at(reach),
        colour: theme::OBSTACLE,
        ascii: None,
        dashed: false,
    });
    // Hatches: 40 per reach, each a twentieth of the extent long, slanted into the solid.
    let hatch = extent / 20.0;
    let slant = (
        (-n.0 - along.0) * std::f64::consts::FRAC_1_SQRT_2,
        (-n.1 - along.1) * std::f64::consts::FRAC_1_SQRT_2,
    );
    // In ASCII each hatch is one character leaning its way (screen y is up).
    let lean = if slant.0 * slant.1 < 0.0 { '\\' } else { '/' };
    for k in -40..=40 {
        let from = at(k as f64 * reach / 40.0);
        scene.segments.push(Segment {
            from,
            to: (from.0 + slant.0 * hatch, from.1 + slant.1 * hatch),
            colour: theme::OBSTACLE,
            ascii: Some(lean),
            dashed: false,
        });
    }
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

/// Text at a cell, clipped to the area (whole characters).
fn put_text(buf: &mut Buffer, area: Rect, col: f64, row: f64, text: &str, colour: Color) {
    for (i, ch) in text.chars().enumerate() {
        put(buf, area, col + i as f64, row, ch, colour);
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

fn draw_ascii(scene: &Scene2d, mapping: &Mapping, area: Rect, buf: &mut Buffer) {
    if let Some(height) = scene.ground {
        let (_, row) = mapping.cell(0.0, height);
        for col in 0..area.width {
            put(buf, area, f64::from(col), row, '=', theme::GROUND);
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
    for s in &scene.segments {
        let (c0, r0) = mapping.cell(s.from.0, s.from.1);
        let (c1, r1) = mapping.cell(s.to.0, s.to.1);
        let (dc, dr) = (c1 - c0, r1 - r0);
        let n = (dc.abs().max(dr.abs()) * 2.0).ceil().clamp(1.0, 4096.0) as usize;
        let ch = s.ascii.unwrap_or_else(|| slope_char(dc, dr));
        for i in 0..=n {
            // Dashed: every other cell along the segment (a dotted `.` line stays whole).
            if s.dashed && s.ascii != Some('.') && (i / 2) % 2 == 1 {
                continue;
            }
            let f = i as f64 / n as f64;
            put(buf, area, c0 + f * dc, r0 + f * dr, ch, s.colour);
        }
    }
    for &(p, colour, ch) in &scene.points {
        let (c, r) = mapping.cell(p.0, p.1);
        put(buf, area, c, r, ch, colour);
    }
    for label in &scene.labels {
        let (c, r) = label_cell(mapping, label);
        put_text(buf, area, c, r, &ascii_label(&label.text), label.colour);
    }
}

/// Labels in pure ASCII: ω is `w`, ⊙/⊗ (seen end-on, towards/away from the viewer) `o`/`x`.
fn ascii_label(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            'ω' => 'w',
            '⊙' => 'o',
            '⊗' => 'x',
            c => c,
        })
        .collect()
}

fn draw_braille(scene: &Scene2d, mapping: &Mapping, area: Rect, buf: &mut Buffer) {
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
                    theme::GROUND,
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
            for s in &scene.segments {
                if s.dashed {
                    // Pieces of one column, every other one.
                    let (dx, dy) = (s.to.0 - s.from.0, s.to.1 - s.from.1);
                    let cells = (dx.abs() / mapping.scale).max(dy.abs() / (2.0 * mapping.scale));
                    let n = (cells.ceil() as usize).clamp(1, 4096);
                    for i in (0..n).step_by(2) {
                        let (f0, f1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                        ctx.draw(&canvas::Line::new(
                            s.from.0 + f0 * dx,
                            s.from.1 + f0 * dy,
                            s.from.0 + f1 * dx,
                            s.from.1 + f1 * dy,
                            s.colour,
                        ));
                    }
                } else {
                    ctx.draw(&canvas::Line::new(
                        s.from.0, s.from.1, s.to.0, s.to.1, s.colour,
                    ));
                }
            }
            for &(p, colour, ch) in &scene.points {
                match ch {
                    '@' | '%' | '*' | 'x' | 'o' => ctx.print(
                        p.0,
                        p.1,
                        Span::styled(ch.to_string(), Style::new().fg(colour)),
                    ),
                    'O' => ctx.print(p.0, p.1, Span::styled("●", Style::new().fg(colour))),
                    '+' => {}
                    _ => ctx.draw(&Points {
                        coords: &[p],
                        color: colour,
                    }),
                }
            }
        });
    canvas.render(area, buf);
    // Labels on top, at whole cells (as in the ASCII drawing).
    for label in &scene.labels {
        let (c, r) = label_cell(mapping, label);
        put_text(buf, area, c, r, &label.text, label.colour);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::body::box_corners;
    use crate::physics::wire::WIRE_STEPS;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn a_balls_equator_and_meridian_turn_with_it() {
        // Turned 90° about z: the meridian's body point (r, 0, 0) (its first point) is carried
        // to (0, r, 0) above the centre; the equator stays a circle of radius r about it.
        let r = 0.1;
        let c = Vector3::new(1.0, 2.0, 3.0);
        let q = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), FRAC_PI_2).into_inner();
        let (points, edges) = wire(&Shape::Ball { radius: r }, &c, &q).unwrap();
        assert_eq!(
            (points.len(), edges.len()),
            (2 * WIRE_STEPS, 2 * WIRE_STEPS)
        );
        let meridian_start = points[WIRE_STEPS];
        assert!(
            (meridian_start - (c + Vector3::y() * r)).norm() < 1e-12,
            "{meridian_start}"
        );
        assert!(points.iter().all(|p| ((p - c).norm() - r).abs() < 1e-12));
    }

    #[test]
    fn a_plane_is_a_line_through_its_point_with_hatches_on_the_solid_side() {
        // A 45° ramp seen from the front: its trace passes through the origin along (1, −1)/√2,
        // and every hatch goes below-left of the line (into the solid, n = (1, 1)/√2).
        let mut scene = Scene2d::default();
        let n = Vector3::new(1.0, 1.0, 0.0).normalize();
        add_plane(&mut scene, Axis::Front, &Vector3::zeros(), &n, 1.0);
        let line = &scene.segments[0];
        let cross = line.from.0 * line.to.1 - line.from.1 * line.to.0;
        assert!(cross.abs() < 1e-9, "the line passes through the origin");
        assert_eq!(scene.segments.len(), 1 + 81);
        for hatch in &scene.segments[1..] {
            let d = (hatch.to.0 - hatch.from.0, hatch.to.1 - hatch.from.1);
            assert!(
                d.0 * n.x + d.1 * n.y < 0.0,
                "hatch {d:?} points out of the solid"
            );
        }
    }

    #[test]
    fn a_box_seen_face_on_hides_only_its_back_face_edges() {
        // An axis-aligned box seen from the front (viewer at +z): the face z = −h faces
        // away, as do the four side faces (their normals are ⟂ to the view: n·toward = 0, not
        // > 0). An edge is hidden when both its faces face away: the 4 edges of the back face
        // (both of its faces are the back face and a side face). The 4 front edges border the
        // front face, and the 4 edges along z border two side faces: hidden too. So 8 hidden,
        // the 4 front-face edges visible.
        let v = box_corners(Vector3::new(1.0, 0.4, 0.1));
        let hidden = hidden_edges(&v, &box_edges(), &Vector3::zeros(), &Vector3::z(), 0.5);
        let visible: Vec<_> = box_edges()
            .into_iter()
            .zip(&hidden)
            .filter(|(_, h)| !**h)
            .map(|(e, _)| e)
            .collect();
        assert_eq!(visible.len(), 4, "{visible:?}");
        for (i, j) in visible {
            assert!(
                i & 4 != 0 && j & 4 != 0,
                "edge {i}-{j} not on the z = +h face"
            );
        }
    }

    #[test]
    fn a_turned_box_shows_nine_edges_and_hides_three() {
        // Seen along a body diagonal (viewer at (1, 1, 1)/√3), three faces face the viewer;
        // the 3 edges meeting at the far corner (0, all bits clear) are hidden, the other 9
        // are visible — the classic picture of a cube.
        let v = box_corners(Vector3::new(1.0, 1.0, 1.0));
        let toward = Vector3::new(1.0, 1.0, 1.0).normalize();
        let hidden = hidden_edges(&v, &box_edges(), &Vector3::zeros(), &toward, 0.87);
        let hidden_edges: Vec<_> = box_edges()
            .into_iter()
            .zip(&hidden)
            .filter(|(_, h)| **h)
            .map(|(e, _)| e)
            .collect();
        assert_eq!(hidden_edges, vec![(0, 1), (0, 2), (0, 4)]);
    }

    #[test]
    fn scale_bars_are_round_lengths_of_a_few_columns() {
        // 0.0315451 m per column: 6 columns ≈ 0.19 m, the nearest round length is 0.2 m,
        // 0.2 / 0.0315451 = 6.3 → 6 columns.
        assert_eq!(scale_bar(0.0315451), (0.2, 6));
        // 1 m per column: 6 m → 5 m in 5 columns.
        assert_eq!(scale_bar(1.0), (5.0, 5));
        assert_eq!(short_length(0.2), "0.2");
        assert_eq!(short_length(20.0), "20");
        assert_eq!(short_length(1e-4), "1e-4");
    }
}
