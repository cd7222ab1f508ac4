//! The numeric panels: the tables of `tables::panels` (state, inertia tensor, angular velocity,
//! force and torque, momenta, energy), cells changed by the last action highlighted, and in
//! compare mode the ghost's numbers on a line under each of the first's.

use super::app::App;
use crate::tables::{self, Panel, Row};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Borders, Paragraph, Widget};

const LABEL: Style = Style::new().fg(Color::Cyan);
const UNIT: Style = Style::new().fg(Color::DarkGray);
const CHANGED: Style = Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD);
const GHOST: Style = Style::new().fg(Color::Magenta);
const TITLE: Style = Style::new().add_modifier(Modifier::BOLD);

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

/// Panel order in compare mode: what differs between two integrators first.
const COMPARE_ORDER: [usize; 7] = [0, 2, 5, 6, 4, 3, 1];

/// All panels, stacked; what does not fit is named on the last line.
pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let block = Block::new()
        .borders(Borders::LEFT)
        .border_style(Style::new().fg(Color::DarkGray));
    let inner = block.inner(area);
    block.render(area, buf);
    let panels = tables::panels(&app.snapshot, app.frame);
    let previous = app.previous.as_ref().map(|p| tables::panels(p, app.frame));
    let compare = app
        .ghost
        .as_ref()
        .map(|g| (tables::panels(&g.snapshot, app.frame), g.comparison.name()));
    let order: Vec<usize> = if compare.is_some() {
        COMPARE_ORDER.to_vec()
    } else {
        (0..panels.len()).collect()
    };
    let views: Vec<(Vec<Line>, &str)> = order
        .iter()
        .map(|&i| {
            let view = PanelView {
                panel: &panels[i],
                previous: previous.as_ref().map(|p| &p[i]),
                compare: compare.as_ref().map(|(c, name)| (&c[i], *name)),
            };
            (view.lines(), panels[i].title.as_str())
        })
        .collect();
    // Stack in order, skipping panels that do not fit; if any is skipped, keep a line to say so.
    let stack = |room: usize| {
        let mut lines: Vec<Line> = Vec::new();
        let mut left_out: Vec<&str> = Vec::new();
        for (panel_lines, title) in &views {
            if lines.len() + panel_lines.len() <= room {
                lines.extend(panel_lines.iter().cloned());
            } else {
                left_out.push(title);
            }
        }
        (lines, left_out)
    };
    let height = usize::from(inner.height);
    let (mut lines, left_out) = stack(height);
    if !left_out.is_empty() && lines.len() < height {
        lines.push(Line::styled(
            format!("… not shown (enlarge): {}", left_out.join(", ")),
            UNIT,
        ));
    }
    Paragraph::new(lines).render(inner, buf);
}
