//! The numeric panels: the tables of `tables::panels` (state, inertia tensor, angular velocity,
//! force and torque, momenta, energy), then one cloth panel per cloth (`cloth_panel`), cells
//! changed by the last action highlighted, one panel per joint and per spring
//! (`tables::joint_panel`, `tables::spring_panel`: |C|, reaction force and torque, anchors), and in compare mode the ghost's numbers on a line
//! under each of the first's. A scene of cloths only shows one line saying it has no rigid
//! body, the scene's energy and the cloth panels.

use super::app::App;
use super::cloth_panel;
use super::theme;
use crate::physics::Snapshot;
use crate::tables::{self, Frame, Panel, Row};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Style;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Widget};

const LABEL: Style = theme::LABEL;
const UNIT: Style = theme::DIM;
const CHANGED: Style = theme::CHANGED;
const GHOST: Style = theme::GHOST_TEXT;
const TITLE: Style = theme::TITLE;

/// One panel: its rows, the same panel before the last action (to highlight changes) and the
/// compare world's panel with the comparison's name.
pub struct PanelView<'a> {
    pub panel: &'a Panel,
    pub previous: Option<&'a Panel>,
    pub compare: Option<(&'a Panel, &'a str)>,
}

impl PanelView<'_> {
    /// The panel as lines: title, then each row (and its ghost row in compare mode).
    pub fn lines(&self) -> Vec<Line<'static>> {
        let label_width = self
            .panel
            .rows
            .iter()
            .map(|r| r.label.chars().count())
            .max()
            .unwrap_or(0);
        let mut lines = vec![Line::from(vec![Span::styled(
            self.panel.title.clone(),
            TITLE,
        )])];
        if let Some((_, name)) = self.compare {
            lines[0].push_span(Span::styled(format!("   (second line: {name})"), GHOST));
        }
        for (i, row) in self.panel.rows.iter().enumerate() {
            let before = self.previous.and_then(|p| p.rows.get(i));
            lines.push(row_line(row, before, label_width, None));
            if let Some((compare, _)) = self.compare {
                if let Some(ghost) = compare.rows.get(i) {
                    lines.push(row_line(ghost, None, label_width, Some(GHOST)));
                }
            }
        }
        lines
    }
}

fn row_line(
    row: &Row,
    before: Option<&Row>,
    label_width: usize,
    ghost: Option<Style>,
) -> Line<'static> {
    let pad = label_width - row.label.chars().count().min(label_width);
    let label = if ghost.is_some() {
        " ".repeat(label_width)
    } else {
        format!("{}{}", row.label, " ".repeat(pad))
    };
    let mut spans = vec![Span::raw(" "), Span::styled(label, LABEL), Span::raw(" ")];
    for (j, cell) in row.cells.iter().enumerate() {
        let changed = before.is_some_and(|b| b.cells.get(j) != Some(cell));
        let style = match (ghost, changed) {
            (Some(g), _) => g,
            (None, true) => CHANGED,
            (None, false) => Style::new(),
        };
        spans.push(Span::styled(cell.clone(), style));
    }
    if !row.unit.is_empty() && ghost.is_none() {
        spans.push(Span::styled(format!("  {}", row.unit), UNIT));
    }
    Line::from(spans)
}

impl Widget for PanelView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        Paragraph::new(self.lines()).render(area, buf);
    }
}

/// The numeric panels of `tables::panels`, by name (their index there is the variant's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PanelId {
    State,
    Inertia,
    AngularVelocity,
    Forces,
    Momentum,
    AngularMomentum,
    Energy,
}

impl PanelId {
    /// Display order: the order of `tables::panels`.
    pub const ALL: [PanelId; 7] = [
        PanelId::State,
        PanelId::Inertia,
        PanelId::AngularVelocity,
        PanelId::Forces,
        PanelId::Momentum,
        PanelId::AngularMomentum,
        PanelId::Energy,
    ];
    /// Order in compare mode: what differs between two integrators first.
    pub const COMPARE_ORDER: [PanelId; 7] = [
        PanelId::State,
        PanelId::AngularVelocity,
        PanelId::AngularMomentum,
        PanelId::Energy,
        PanelId::Momentum,
        PanelId::Forces,
        PanelId::Inertia,
    ];

    /// Its index in `tables::panels`.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// Indices into `tables::panels` in the order they are stacked; panels beyond the named ones
/// (a panel added to `tables` later) come last, never silently dropped.
fn order(count: usize, compare: bool) -> Vec<usize> {
    let named = if compare {
        PanelId::COMPARE_ORDER
    } else {
        PanelId::ALL
    };
    let mut order: Vec<usize> = named
        .iter()
        .map(|p| p.index())
        .filter(|&i| i < count)
        .collect();
    order.extend(PanelId::ALL.len()..count);
    order
}

/// Every panel's lines with its title, in stacking order: the body's state, one panel per
/// cloth, the body's other panels (with no body: one line saying so, the cloth panels, the
/// scene's energy).
fn views(app: &App) -> Vec<(Vec<Line<'static>>, String)> {
    let panels = tables::panels(&app.snapshot, app.frame);
    let previous = app.previous.as_ref().map(|p| tables::panels(p, app.frame));
    let compare = app
        .ghost
        .as_ref()
        .map(|g| (tables::panels(&g.snapshot, app.frame), g.comparison.name()));
    let no_body = app.snapshot.bodies.is_empty();
    let shown: Vec<usize> = if no_body {
        vec![PanelId::Energy.index()]
    } else {
        order(panels.len(), compare.is_some())
    };
    let mut views: Vec<(Vec<Line<'static>>, String)> = Vec::new();
    if no_body {
        views.push((
            vec![Line::styled(NO_BODY.to_string(), UNIT)],
            NO_BODY.to_string(),
        ));
    }
    views.extend(shown.into_iter().map(|i| {
        let view = PanelView {
            panel: &panels[i],
            previous: previous.as_ref().and_then(|p| p.get(i)),
            compare: compare
                .as_ref()
                .and_then(|(c, name)| c.get(i).map(|p| (p, *name))),
        };
        (view.lines(), panels[i].title.clone())
    }));
    // The cloth panels come second: after the body's state, or after the line saying there
    // is no body (a scene with a cloth is about it: in a small terminal the other panels are
    // left out before them).
    let s = &app.snapshot;
    let at = views.len().min(1);
    let cloths = s.cloths.iter().enumerate().map(|(k, c)| {
        let before = app.previous.as_ref().and_then(|p| p.cloths.get(k));
        let ghost = app
            .ghost
            .as_ref()
            .and_then(|g| g.snapshot.cloths.get(k).map(|c| (c, g.comparison.name())));
        cloth_panel::lines(c, s.dt, before, ghost)
    });
    let cloths: Vec<_> = cloths.collect();
    let after_cloths = at + cloths.len();
    views.splice(at..at, cloths);
    // Then the joints and springs (`tables::joint_panel`, `spring_panel`: the numbers `walk`
    // prints): a pendulum's lesson is about the rod's pull and its error |C|.
    let links = link_panels(s);
    let before = app.previous.as_ref().map(link_panels);
    let ghost = app
        .ghost
        .as_ref()
        .map(|g| (link_panels(&g.snapshot), g.comparison.name()));
    let links = links.iter().enumerate().map(|(k, panel)| {
        let view = PanelView {
            panel,
            previous: before.as_ref().and_then(|p| p.get(k)),
            compare: ghost
                .as_ref()
                .and_then(|(g, name)| g.get(k).map(|p| (p, *name))),
        };
        (view.lines(), panel.title.clone())
    });
    views.splice(after_cloths..after_cloths, links.collect::<Vec<_>>());
    views
}

/// One panel per joint, the joint correction's work when there are joints, then one panel
/// per spring (the order `walk` prints them in).
fn link_panels(s: &Snapshot) -> Vec<Panel> {
    s.joints
        .iter()
        .map(tables::joint_panel)
        .chain((!s.joints.is_empty()).then(|| tables::correction_panel(s)))
        .chain(s.springs.iter().map(tables::spring_panel))
        .collect()
}

/// What the panels say in a scene of cloths only.
pub const NO_BODY: &str = "no rigid body in this scene";

fn widest(lines: &[Line]) -> u16 {
    lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16
}

/// The width the panels column asks for: its widest line and the border.
pub fn width(app: &App) -> u16 {
    views(app)
        .iter()
        .map(|(lines, _)| widest(lines))
        .max()
        .unwrap_or(0)
        + 1
}

/// The essential numbers (the stage layout): position, velocity, ω, L, total energy and its
/// change since t = 0 — rows of `tables::panels`, formatted by it.
pub fn essentials(s: &Snapshot, frame: Frame) -> Panel {
    let panels = tables::panels(s, frame);
    let pick = |id: PanelId, labels: &[&str]| -> Vec<Row> {
        panels
            .get(id.index())
            .map(|p| {
                p.rows
                    .iter()
                    .filter(|r| labels.contains(&r.label.as_str()))
                    .cloned()
                    .collect()
            })
            .unwrap_or_default()
    };
    let mut rows = Vec::new();
    if !s.bodies.is_empty() {
        rows.extend(pick(PanelId::State, &["x"]));
        rows.extend(pick(PanelId::Momentum, &["v"]));
        rows.extend(pick(PanelId::AngularVelocity, &["ω"]));
        rows.extend(pick(PanelId::AngularMomentum, &["L"]));
    }
    rows.extend(pick(PanelId::Energy, &["K, V, E", "  drift"]));
    // Each cloth: how stretched, how fast, and dt against its explicit limit.
    for c in &s.cloths {
        let (panel, _) = cloth_panel::panel(c, s.dt);
        rows.extend(
            panel
                .rows
                .into_iter()
                .filter(|r| ["max stretch", "max speed", "dt/h*"].contains(&r.label.as_str())),
        );
    }
    Panel {
        title: match frame {
            Frame::World => "essentials".to_string(),
            Frame::Body => "essentials (body frame: v, L)".to_string(),
        },
        rows,
    }
}

/// The essentials panel's lines (with the ghost's in compare mode).
fn essentials_lines(app: &App) -> Vec<Line<'static>> {
    let panel = essentials(&app.snapshot, app.frame);
    let previous = app.previous.as_ref().map(|p| essentials(p, app.frame));
    let compare = app
        .ghost
        .as_ref()
        .map(|g| (essentials(&g.snapshot, app.frame), g.comparison.name()));
    PanelView {
        panel: &panel,
        previous: previous.as_ref(),
        compare: compare.as_ref().map(|(p, name)| (p, *name)),
    }
    .lines()
}

/// The essentials panel's size with its border: (width, height); its title goes in the border.
pub fn essentials_size(app: &App) -> (u16, u16) {
    let lines = essentials_lines(app);
    (widest(&lines) + 2, lines.len() as u16 + 1)
}

/// The essentials, in the stage layout, in a box titled by the panel's title line (whole, or
/// not at all when they do not fit).
pub fn render_essentials(app: &App, area: Rect, buf: &mut Buffer) {
    let mut lines = essentials_lines(app);
    let title = if lines.is_empty() {
        Line::raw("")
    } else {
        lines.remove(0)
    };
    let mut title = title;
    title.spans.insert(0, Span::raw(" "));
    title.spans.push(Span::raw(" "));
    let block = Block::bordered().title(title);
    let inner = block.inner(area);
    block.render(area, buf);
    if widest(&lines) <= inner.width && lines.len() <= usize::from(inner.height) {
        Paragraph::new(lines).render(inner, buf);
    } else {
        Paragraph::new(Line::styled("… enlarge for the numbers", UNIT)).render(inner, buf);
    }
}

/// All panels, stacked; a panel that does not fit (in height or in width) is left out whole,
/// and what is left out is named on the last line.
pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let block = Block::new().borders(Borders::LEFT).border_style(theme::DIM);
    let inner = block.inner(area);
    block.render(area, buf);
    let views = views(app);
    let height = usize::from(inner.height);
    let mut lines: Vec<Line> = Vec::new();
    let mut left_out: Vec<&str> = Vec::new();
    for (panel_lines, title) in &views {
        if lines.len() + panel_lines.len() <= height && widest(panel_lines) <= inner.width {
            lines.extend(panel_lines.iter().cloned());
        } else {
            left_out.push(title);
        }
    }
    if !left_out.is_empty() && lines.len() < height {
        lines.push(Line::styled(
            format!("… not shown (enlarge): {}", left_out.join(", ")),
            UNIT,
        ));
    }
    Paragraph::new(lines).render(inner, buf);
}
