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
use crate::scene::live::Measure;
use crate::scene::PagePanel;
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
        self.groups().into_iter().flatten().collect()
    }

    /// The title line, then each row's lines (the row, and its ghost row in compare mode).
    pub fn groups(&self) -> Vec<Vec<Line<'static>>> {
        let label_width = self
            .panel
            .rows
            .iter()
            .map(|r| r.label.chars().count())
            .max()
            .unwrap_or(0);
        let mut title = Line::from(vec![Span::styled(self.panel.title.clone(), TITLE)]);
        if let Some((_, name)) = self.compare {
            title.push_span(Span::styled(format!("   (second line: {name})"), GHOST));
        }
        let mut groups = vec![vec![title]];
        for (i, row) in self.panel.rows.iter().enumerate() {
            let before = self.previous.and_then(|p| p.rows.get(i));
            let mut group = vec![row_line(row, before, label_width, None)];
            if let Some((compare, _)) = self.compare {
                if let Some(ghost) = compare.rows.get(i) {
                    group.push(row_line(ghost, None, label_width, Some(GHOST)));
                }
            }
            groups.push(group);
        }
        groups
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

    /// The name a page gives it (`panels = [...]`).
    pub fn page_panel(self) -> PagePanel {
        match self {
            PanelId::State => PagePanel::State,
            PanelId::Inertia => PagePanel::Inertia,
            PanelId::AngularVelocity => PagePanel::AngularVelocity,
            PanelId::Forces => PagePanel::Forces,
            PanelId::Momentum => PagePanel::Momentum,
            PanelId::AngularMomentum => PagePanel::AngularMomentum,
            PanelId::Energy => PagePanel::Energy,
        }
    }
}

/// The panel of `tables::panels` at index `i` by the name a page gives it (the system panel
/// comes after the seven named ones).
fn page_panel_of(i: usize) -> PagePanel {
    PanelId::ALL
        .get(i)
        .map_or(PagePanel::System, |p| p.page_panel())
}

/// The panel where a quantity of the live numbers shows (None: the time, in the status line).
/// `several`: the scene has several bodies (a body's energy is then in its own panel, the
/// scene's momentum in the system panel).
pub fn panel_of_measure(m: Measure, several: bool) -> Option<PagePanel> {
    Some(match m {
        Measure::Position(_) => PagePanel::State,
        Measure::Velocity(_) | Measure::Speed => PagePanel::Momentum,
        Measure::AngularVelocity(_) => PagePanel::AngularVelocity,
        Measure::AngularMomentum(_) | Measure::AngularMomentumNorm => PagePanel::AngularMomentum,
        Measure::Kinetic | Measure::Potential | Measure::Energy if several => PagePanel::BodyEnergy,
        Measure::Kinetic | Measure::Potential | Measure::Energy | Measure::SceneEnergy => {
            PagePanel::Energy
        }
        Measure::SceneMomentum(_) if several => PagePanel::System,
        Measure::SceneMomentum(_) => PagePanel::Momentum,
        Measure::Time | Measure::ContactTime | Measure::JointError(_) => return None,
    })
}

/// What the page shown quotes: the panels of its live numbers and its prediction, and the
/// panels it names (`panels = [...]`), each once, in stacking order.
pub fn quoted(app: &App) -> Vec<PagePanel> {
    let (named, measures) = page_quotes(app);
    let several = app.session.snapshot.bodies.len() > 1;
    // The measuring tools shown (by a key or by the page) are quoted too: shown first.
    let mut quoted: Vec<PagePanel> = measures
        .iter()
        .filter_map(|&(m, _)| panel_of_measure(m, several))
        .chain(named)
        .chain(app.tools_shown())
        .collect();
    quoted.sort();
    quoted.dedup();
    quoted
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

/// One panel in the stack: which panel it is (None: the line saying there is no body), its
/// title, and its lines in groups — the title line, then each row with its ghost row (a cloth
/// panel is one group: it is shown whole or not at all).
pub struct Stacked {
    pub key: Option<PagePanel>,
    pub title: String,
    pub groups: Vec<Vec<Line<'static>>>,
    /// The label of each group after the first (its row), to name rows left out.
    pub labels: Vec<String>,
}

impl Stacked {
    fn of(key: PagePanel, panel: &Panel, view: &PanelView) -> Stacked {
        Stacked {
            key: Some(key),
            title: panel.title.clone(),
            groups: view.groups(),
            labels: panel
                .rows
                .iter()
                .map(|r| r.label.trim().to_string())
                .collect(),
        }
    }

    fn whole(key: Option<PagePanel>, lines: Vec<Line<'static>>, title: String) -> Stacked {
        Stacked {
            key,
            title,
            groups: vec![lines],
            labels: Vec::new(),
        }
    }

    fn lines(&self) -> Vec<Line<'static>> {
        self.groups.iter().flatten().cloned().collect()
    }
}

/// Every panel in stacking order: the body's state, one panel per cloth, the joints and
/// springs, the body's other panels, each body's energy (several bodies) and the system panel
/// (with no body: one line saying so, the cloth panels, the scene's energy).
fn views(app: &App) -> Vec<Stacked> {
    let mut panels = tables::panels(&app.session.snapshot, app.prefs.frame);
    let mut previous = app
        .session
        .previous
        .as_ref()
        .map(|p| tables::panels(p, app.prefs.frame));
    let mut compare = app.session.ghost.as_ref().map(|g| {
        (
            tables::panels(&g.snapshot, app.prefs.frame),
            g.comparison.name(),
        )
    });
    // Key `u`: the ± rows (world frame only: the errors are of the world-frame numbers), in
    // every copy of the panels so that rows still line up for the highlight and the ghost.
    let bars = app
        .session
        .error_bars
        .as_ref()
        .filter(|_| app.prefs.frame == Frame::World);
    if let Some(errors) = bars.and_then(|b| b.errors.as_ref()) {
        crate::error_bars::annotate(&mut panels, errors);
        if let Some(p) = &mut previous {
            crate::error_bars::annotate(p, errors);
        }
        if let Some((p, _)) = &mut compare {
            crate::error_bars::annotate(p, errors);
        }
    }
    let no_body = app.session.snapshot.bodies.is_empty();
    let shown: Vec<usize> = if no_body {
        vec![PanelId::Energy.index()]
    } else {
        order(panels.len(), compare.is_some())
    };
    let mut views: Vec<Stacked> = Vec::new();
    if no_body {
        views.push(Stacked::whole(
            None,
            vec![Line::styled(NO_BODY.to_string(), UNIT)],
            NO_BODY.to_string(),
        ));
    }
    if let Some(bars) = &app.session.error_bars {
        let line = if app.prefs.frame == Frame::World {
            bars.describe(app.session.snapshot.integrator, app.session.ns_per_step)
        } else {
            "± shown in the world frame only (f)".to_string()
        };
        views.push(Stacked::whole(
            None,
            vec![Line::styled(line.clone(), UNIT)],
            line,
        ));
    }
    let energy_at = PanelId::Energy.index();
    let several = app.session.snapshot.bodies.len() > 1;
    for i in shown {
        let view = PanelView {
            panel: &panels[i],
            previous: previous.as_ref().and_then(|p| p.get(i)),
            compare: compare
                .as_ref()
                .and_then(|(c, name)| c.get(i).map(|p| (p, *name))),
        };
        views.push(Stacked::of(page_panel_of(i), &panels[i], &view));
        if i == energy_at && several {
            // Each body's own energy, under the scene's.
            let own = tables::body_energy_panel(&app.session.snapshot);
            let before = app.session.previous.as_ref().map(tables::body_energy_panel);
            let ghost = app
                .session
                .ghost
                .as_ref()
                .map(|g| (tables::body_energy_panel(&g.snapshot), g.comparison.name()));
            let view = PanelView {
                panel: &own,
                previous: before.as_ref(),
                compare: ghost.as_ref().map(|(p, name)| (p, *name)),
            };
            views.push(Stacked::of(PagePanel::BodyEnergy, &own, &view));
        }
    }
    // The cloth panels come second: after the body's state, or after the line saying there
    // is no body (a scene with a cloth is about it: in a small terminal the other panels are
    // left out before them).
    let s = &app.session.snapshot;
    let at = views.len().min(1);
    let cloths = s.cloths.iter().enumerate().map(|(k, c)| {
        let before = app.session.previous.as_ref().and_then(|p| p.cloths.get(k));
        let ghost = app
            .session
            .ghost
            .as_ref()
            .and_then(|g| g.snapshot.cloths.get(k).map(|c| (c, g.comparison.name())));
        let (lines, title) = cloth_panel::lines(c, s.dt, before, ghost);
        Stacked::whole(Some(PagePanel::Cloth), lines, title)
    });
    let cloths: Vec<_> = cloths.collect();
    let after_cloths = at + cloths.len();
    views.splice(at..at, cloths);
    // Then the joints and springs (`tables::joint_panel`, `spring_panel`: the numbers `walk`
    // prints): a pendulum's lesson is about the rod's pull and its error |C|.
    let links = link_panels(s);
    let before = app.session.previous.as_ref().map(link_panels);
    let ghost = app
        .session
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
        Stacked::of(PagePanel::Joints, panel, &view)
    });
    views.splice(after_cloths..after_cloths, links.collect::<Vec<_>>());
    // The measuring tools shown come first: what the class is measuring now.
    let tools = app.tools_shown().into_iter().map(|tool| {
        let panel = app.tool_panel(tool);
        let view = PanelView {
            panel: &panel,
            previous: None,
            compare: None,
        };
        Stacked::of(tool, &panel, &view)
    });
    views.splice(0..0, tools.collect::<Vec<_>>());
    // The energy bars, when the page names them.
    if page_quotes(app).0.contains(&PagePanel::EnergyBars) {
        let lines = super::energy_bars::lines(s);
        let title = lines.first().map_or_else(String::new, |l| {
            l.spans.iter().map(|s| s.content.clone()).collect()
        });
        views.push(Stacked::whole(Some(PagePanel::EnergyBars), lines, title));
    }
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
        .map(|v| widest(&v.lines()))
        .max()
        .unwrap_or(0)
        + 1
}

/// The width the panels the page quotes need to show their title and one row each (their
/// narrowest row), with the border.
pub fn quoted_width(app: &App) -> u16 {
    let quoted = quoted(app);
    views(app)
        .iter()
        .filter(|v| v.key.is_some_and(|k| quoted.contains(&k)))
        .map(|v| {
            let row = v
                .groups
                .iter()
                .skip(1)
                .map(|g| widest(g))
                .min()
                .unwrap_or(0);
            row.max(widest(&v.groups[0]).min(row))
        })
        .max()
        .map_or(0, |w| w + 1)
}

/// The essential numbers (the stage layout): position, velocity, ω, L, total energy and its
/// change since t = 0 — rows of `tables::panels`, formatted by it.
pub fn essentials(s: &Snapshot, frame: Frame) -> Panel {
    essentials_for(s, frame, &[], &[])
}

/// The essentials, with what a page quotes: every row of the panels it names (`named`), and
/// for its live numbers (`measures`, with the body each is about) the row that shows each
/// when the defaults do not (a body's own energy, the momentum P).
pub fn essentials_for(
    s: &Snapshot,
    frame: Frame,
    named: &[PagePanel],
    measures: &[(Measure, usize)],
) -> Panel {
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
    let several = s.bodies.len() > 1;
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
    // What the page quotes.
    let body_energy = || tables::body_energy_panel(s).rows;
    let mut extra: Vec<Row> = Vec::new();
    for &(m, body) in measures {
        match panel_of_measure(m, several) {
            Some(PagePanel::BodyEnergy) => extra.extend(body_energy().into_iter().nth(body)),
            Some(PagePanel::System) => extra.extend(
                tables::system_panel(s)
                    .rows
                    .into_iter()
                    .filter(|r| r.label == "P total"),
            ),
            Some(PagePanel::Momentum) if matches!(m, Measure::SceneMomentum(_)) => {
                extra.extend(pick(PanelId::Momentum, &["P"]))
            }
            _ => {}
        }
    }
    for &name in named {
        match name {
            PagePanel::BodyEnergy if several => extra.extend(body_energy()),
            PagePanel::System if several => extra.extend(tables::system_panel(s).rows),
            PagePanel::Joints => {
                for p in link_panels(s) {
                    extra.extend(p.rows.into_iter().take(2));
                }
            }
            // The tools' rows come from the app (`essentials_of`).
            PagePanel::BodyEnergy
            | PagePanel::System
            | PagePanel::Cloth
            | PagePanel::EnergyBars => {}
            _ if name.is_tool() => {}
            _ if s.bodies.is_empty() && name != PagePanel::Energy => {}
            _ => {
                let id = PanelId::ALL
                    .into_iter()
                    .find(|p| p.page_panel() == name)
                    .expect("every other page panel is one of tables::panels");
                extra.extend(
                    panels
                        .get(id.index())
                        .into_iter()
                        .flat_map(|p| p.rows.clone()),
                );
            }
        }
    }
    for row in extra {
        if !rows.contains(&row) {
            rows.push(row);
        }
    }
    Panel {
        title: match frame {
            Frame::World => "essentials".to_string(),
            Frame::Body => "essentials (body frame: v, L)".to_string(),
        },
        rows,
    }
}

/// The essentials of the app's page (see [`essentials_for`]) for snapshot `s` of the app.
pub fn essentials_of(app: &App, s: &Snapshot) -> Panel {
    let (named, measures) = page_quotes(app);
    let mut panel = essentials_for(s, app.prefs.frame, &named, &measures);
    // The measuring tools shown: their readouts (of the world now).
    for tool in app.tools_shown() {
        let readout = app.tool_panel(tool);
        // One row each: the time, the mean period (or the count, 0), the distance, the angle.
        let first = readout.rows.into_iter().next().map(|mut r| {
            r.label = match tool {
                PagePanel::Stopwatch => "stopwatch",
                PagePanel::Period => "period",
                PagePanel::Ruler => "ruler",
                _ => "angle",
            }
            .to_string();
            r
        });
        panel.rows.extend(first);
    }
    panel
}

/// The page's `panels`, and its live numbers' and prediction's quantities with their body.
fn page_quotes(app: &App) -> (Vec<PagePanel>, Vec<(Measure, usize)>) {
    let Some((_, page)) = app.session.lesson.page_at(app.session.snapshot.time) else {
        return (Vec::new(), Vec::new());
    };
    let mut measures: Vec<(Measure, usize)> = page
        .live
        .iter()
        .map(|n| &n.quantity)
        .chain(page.predict.iter().map(|p| &p.quantity))
        .map(|q| (q.measure, q.body))
        .collect();
    measures.sort();
    measures.dedup();
    (page.panels.clone(), measures)
}

/// The essentials panel's lines (with the ghost's in compare mode).
fn essentials_lines(app: &App) -> Vec<Line<'static>> {
    essentials_groups(app).0.into_iter().flatten().collect()
}

/// The essentials panel's lines in groups (the title, then each row with its ghost row) and
/// its rows' labels.
fn essentials_groups(app: &App) -> (Vec<Vec<Line<'static>>>, Vec<String>) {
    let panel = essentials_of(app, &app.session.snapshot);
    let previous = app.session.previous.as_ref().map(|p| essentials_of(app, p));
    let compare = app
        .session
        .ghost
        .as_ref()
        .map(|g| (essentials_of(app, &g.snapshot), g.comparison.name()));
    let groups = PanelView {
        panel: &panel,
        previous: previous.as_ref(),
        compare: compare.as_ref().map(|(p, name)| (p, *name)),
    }
    .groups();
    let labels = panel
        .rows
        .iter()
        .map(|r| r.label.trim().to_string())
        .collect();
    (groups, labels)
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

/// What the panels column shows in `width × height`: for each panel of `views` (in
/// stacking order) the groups shown, None for a panel left out; and the title a quoted panel
/// shown in part takes.
///
/// The panels the page quotes ([`quoted`]) are placed first: whole if they fit, otherwise the
/// rows that fit (a quoted panel is never left out while one of its rows fits). Then the other
/// panels, in stacking order, each whole or not at all.
pub fn arrange(app: &App, width: u16, height: u16) -> Vec<(Stacked, Option<Vec<usize>>)> {
    let views = views(app);
    let quoted = quoted(app);
    let height = usize::from(height);
    let mut used = 0usize;
    let mut chosen: Vec<Option<Vec<usize>>> = vec![None; views.len()];
    let is_quoted = |v: &Stacked| v.key.is_some_and(|k| quoted.contains(&k));
    // The panels no page quotes take the room left in order of what they tell: the inertia
    // tensor (constant for a body that does not turn, or turns about a symmetric axis) yields
    // first, then the effects' forces; the others in stacking order. Shown in stacking order.
    let yields = |v: &Stacked| match v.key {
        Some(PagePanel::Inertia) => 2,
        Some(PagePanel::Forces) => 1,
        _ => 0,
    };
    let mut by_priority: Vec<usize> = (0..views.len()).collect();
    by_priority.sort_by_key(|&k| yields(&views[k]));
    for pass in [true, false] {
        for &k in &by_priority {
            let view = &views[k];
            if is_quoted(view) != pass {
                continue;
            }
            let lines = view.lines();
            if used + lines.len() <= height && widest(&lines) <= width {
                used += lines.len();
                chosen[k] = Some((0..view.groups.len()).collect());
            } else if pass && widest(&view.groups[0]) <= width {
                // The rows that fit, under the title.
                let mut rows = vec![0];
                let mut need = view.groups[0].len();
                for (g, group) in view.groups.iter().enumerate().skip(1) {
                    if widest(group) <= width && used + need + group.len() <= height {
                        need += group.len();
                        rows.push(g);
                    }
                }
                if rows.len() > 1 {
                    used += need;
                    chosen[k] = Some(rows);
                }
            }
        }
    }
    views.into_iter().zip(chosen).collect()
}

/// All panels, stacked as [`arrange`] chooses; what is left out is named on the last line, and
/// a quoted panel shown in part names the rows it leaves out in its title.
pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let block = Block::new().borders(Borders::LEFT).border_style(theme::DIM);
    let inner = block.inner(area);
    block.render(area, buf);
    let height = usize::from(inner.height);
    let mut lines: Vec<Line> = Vec::new();
    let mut left_out: Vec<String> = Vec::new();
    for (view, rows) in arrange(app, inner.width, inner.height) {
        let Some(rows) = rows else {
            left_out.push(view.title.clone());
            continue;
        };
        let missing: Vec<&str> = (1..view.groups.len())
            .filter(|g| !rows.contains(g))
            .filter_map(|g| view.labels.get(g - 1).map(String::as_str))
            .filter(|l| !l.is_empty())
            .collect();
        for &g in &rows {
            let mut group = view.groups[g].clone();
            if g == 0 && !missing.is_empty() {
                let note = format!(" (enlarge for {})", missing.join(", "));
                let fits =
                    |n: &str| group[0].width() + n.chars().count() <= usize::from(inner.width);
                let note = if fits(&note) {
                    note
                } else {
                    " (part)".to_string()
                };
                group[0].push_span(Span::styled(note, UNIT));
            }
            lines.extend(group);
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

/// Each panel of the stack (in stacking order) by the name a page gives it, with its title.
pub fn titles(app: &App) -> Vec<(Option<PagePanel>, String)> {
    views(app).into_iter().map(|v| (v.key, v.title)).collect()
}

/// A click on a panel row: which panel, the row's label (trimmed) and which of its numbers
/// (0 for a click on the label; the cell under the pointer otherwise, counted from the first
/// number, so the unit after the last number counts as one more).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowHit {
    pub panel: Option<PagePanel>,
    pub label: String,
    pub cell: usize,
}

/// The number under column `col` of a panel row's line drawn from column `x`: its spans are
/// " ", the label, " ", one per number, then the unit (0 on the label).
fn cell_at(line: &Line, mut x: u16, col: u16) -> usize {
    let mut span = line.spans.len();
    for (k, s) in line.spans.iter().enumerate() {
        let w = s.width() as u16;
        if col < x + w {
            span = k;
            break;
        }
        x += w;
    }
    span.saturating_sub(3)
}

/// The essentials row under terminal cell (`col`, `row`) in the stage layout's essentials box
/// `area`, as [`render_essentials`] draws it; its panel is the one each essential row comes
/// from (None: the border, or no row there).
pub fn essentials_row_at(app: &App, area: Rect, col: u16, row: u16) -> Option<RowHit> {
    let inner = Block::bordered().inner(area);
    if col < inner.x || col >= inner.x + inner.width || row < inner.y {
        return None;
    }
    let (groups, labels) = essentials_groups(app);
    let rows: Vec<&Line> = groups.iter().skip(1).flatten().collect();
    let widest_row = rows.iter().map(|l| l.width()).max().unwrap_or(0);
    if widest_row > usize::from(inner.width) || rows.len() > usize::from(inner.height) {
        return None; // "… enlarge for the numbers"
    }
    let mut y = inner.y;
    // The title line is the box's title; the rows follow inside.
    for (g, group) in groups.iter().enumerate().skip(1) {
        for line in group {
            if y == row {
                let label = labels.get(g - 1)?.clone();
                let panel = match label.as_str() {
                    "x" => PagePanel::State,
                    "v" | "P" => PagePanel::Momentum,
                    "ω" => PagePanel::AngularVelocity,
                    "L" => PagePanel::AngularMomentum,
                    "K, V, E" => PagePanel::Energy,
                    "P total" => PagePanel::System,
                    name if app.session.snapshot.bodies.iter().any(|b| b.name == name) => {
                        PagePanel::BodyEnergy
                    }
                    _ => return None,
                };
                return Some(RowHit {
                    panel: Some(panel),
                    label,
                    cell: cell_at(line, inner.x, col),
                });
            }
            y += 1;
        }
    }
    None
}

/// The panel row under terminal cell (`col`, `row`) in the panels column `area`, as
/// [`render`] lays them out (None: a title, a cloth panel, or no row there).
pub fn row_at(app: &App, area: Rect, col: u16, row: u16) -> Option<RowHit> {
    let inner = Block::new().borders(Borders::LEFT).inner(area);
    if col < inner.x || col >= inner.x + inner.width || row < inner.y {
        return None;
    }
    let mut y = inner.y;
    for (view, rows) in arrange(app, inner.width, inner.height) {
        let Some(rows) = rows else {
            continue;
        };
        for g in rows {
            for line in &view.groups[g] {
                if y == row {
                    let label = view.labels.get(g.checked_sub(1)?)?.clone();
                    return Some(RowHit {
                        panel: view.key,
                        label,
                        cell: cell_at(line, inner.x, col),
                    });
                }
                y += 1;
            }
        }
    }
    None
}
