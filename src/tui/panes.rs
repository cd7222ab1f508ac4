//! The boxes of the loop view, one row each in [`PANES`]: its name, where it goes, what draws
//! it. The loop view draws the rows in order; the energy view draws the boxes cut from the
//! others ([`render_cut`]) beside its graph.
//!
//! A box goes either where the screen layout puts it ([`Place::Layout`]: the drawing, the
//! lesson page, the numbers, the loop strip — `layout.rs` places those for each layout), or
//! cut from one of those along one side ([`Place::Cut`]): it asks for rows or columns given the
//! app and the area it is cut from, and the area keeps the rest (the mouse and the projection
//! see the smaller drawing). A box that asks for all of its host's room is left out whole.
//!
//! A new box touches three files: its own (the render and size functions), `mod.rs` (its
//! `pub mod` line) and its row here.

use super::app::App;
use super::layout::{Areas, ScreenLayout};
use super::{lesson_pane, loop_strip, panels, projection};
use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Direction, Layout, Rect};

/// One box of the loop view: a row of [`PANES`].
#[derive(Debug, Clone, Copy)]
pub struct Pane {
    pub name: &'static str,
    pub place: Place,
    /// Draws the box in its area.
    pub render: fn(&App, Rect, &mut Buffer),
}

/// Where a box goes.
#[derive(Debug, Clone, Copy)]
pub enum Place {
    /// An area the screen layout gives (None: not in this layout or this terminal).
    Layout(fn(&Areas) -> Option<Rect>),
    /// Cut from the `from` area along `side`: `size` rows (top, bottom) or columns (left,
    /// right), given the app and that area (None: not shown).
    Cut {
        from: Host,
        side: Side,
        size: fn(&App, Rect) -> Option<u16>,
    },
}

/// An area of the screen layout a box can be cut from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Host {
    Drawing,
    Lesson,
    Panels,
    Strip,
}

/// The side of its host a cut box takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Top,
    Bottom,
    Left,
    Right,
}

/// The numeric panels, or in the stage layout the essential numbers.
fn numbers(app: &App, area: Rect, buf: &mut Buffer) {
    match app.prefs.layout {
        ScreenLayout::Numbers => panels::render(app, area, buf),
        ScreenLayout::Stage => panels::render_essentials(app, area, buf),
    }
}

/// Every box of the loop view, drawn in this order.
pub const PANES: &[Pane] = &[
    Pane {
        name: "drawing",
        place: Place::Layout(|a| Some(a.drawing)),
        render: projection::render,
    },
    Pane {
        name: "lesson",
        place: Place::Layout(|a| a.lesson),
        render: lesson_pane::render,
    },
    Pane {
        name: "numbers",
        place: Place::Layout(|a| a.panels),
        render: numbers,
    },
    Pane {
        name: "strip",
        place: Place::Layout(|a| a.strip),
        render: loop_strip::render,
    },
];

/// How many rows of [`PANES`] are cut from another box: the length of [`Areas::cut`].
pub const CUT_COUNT: usize = {
    let (mut count, mut i) = (0, 0);
    while i < PANES.len() {
        if let Place::Cut { .. } = PANES[i].place {
            count += 1;
        }
        i += 1;
    }
    count
};

/// Cuts the boxes of [`Place::Cut`] rows from the layout's areas, in table order: each one's
/// area goes to [`Areas::cut`] (in the order of those rows), its host keeps the rest.
pub fn cut(app: &App, areas: &mut Areas) {
    let rows = PANES.iter().filter_map(|p| match p.place {
        Place::Cut { from, side, size } => Some((from, side, size)),
        Place::Layout(_) => None,
    });
    for (i, (from, side, size)) in rows.enumerate() {
        let host = match from {
            Host::Drawing => Some(&mut areas.drawing),
            Host::Lesson => areas.lesson.as_mut(),
            Host::Panels => areas.panels.as_mut(),
            Host::Strip => areas.strip.as_mut(),
        };
        let Some(host) = host else { continue };
        let Some(n) = size(app, *host) else { continue };
        areas.cut[i] = split(host, side, n);
    }
}

/// Takes `n` rows or columns from `host` on `side`; None (and `host` kept whole) when that
/// is none or all of it.
fn split(host: &mut Rect, side: Side, n: u16) -> Option<Rect> {
    let extent = match side {
        Side::Top | Side::Bottom => host.height,
        Side::Left | Side::Right => host.width,
    };
    if n == 0 || n >= extent {
        return None;
    }
    let (direction, constraints) = match side {
        Side::Top => (
            Direction::Vertical,
            [Constraint::Length(n), Constraint::Fill(1)],
        ),
        Side::Bottom => (
            Direction::Vertical,
            [Constraint::Fill(1), Constraint::Length(n)],
        ),
        Side::Left => (
            Direction::Horizontal,
            [Constraint::Length(n), Constraint::Fill(1)],
        ),
        Side::Right => (
            Direction::Horizontal,
            [Constraint::Fill(1), Constraint::Length(n)],
        ),
    };
    let [first, second] = Layout::new(direction, constraints).areas(*host);
    let (taken, kept) = match side {
        Side::Top | Side::Left => (first, second),
        Side::Bottom | Side::Right => (second, first),
    };
    *host = kept;
    Some(taken)
}

/// The loop view: every row of [`PANES`] that has an area.
pub fn render(app: &App, areas: &Areas, buf: &mut Buffer) {
    let mut cut = areas.cut.iter();
    for pane in PANES {
        let area = match pane.place {
            Place::Layout(place) => place(areas),
            Place::Cut { .. } => cut.next().copied().flatten(),
        };
        if let Some(area) = area {
            (pane.render)(app, area, buf);
        }
    }
}

/// Only the boxes cut from the layout's areas (the views that draw the layout's areas their
/// own way).
pub fn render_cut(app: &App, areas: &Areas, buf: &mut Buffer) {
    let cut_rows = PANES
        .iter()
        .filter(|p| matches!(p.place, Place::Cut { .. }));
    for (pane, area) in cut_rows.zip(areas.cut) {
        if let Some(area) = area {
            (pane.render)(app, area, buf);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cut_takes_its_side_and_the_host_keeps_the_rest() {
        let whole = Rect::new(2, 3, 40, 20);
        for (side, taken, kept) in [
            (Side::Top, Rect::new(2, 3, 40, 5), Rect::new(2, 8, 40, 15)),
            (
                Side::Bottom,
                Rect::new(2, 18, 40, 5),
                Rect::new(2, 3, 40, 15),
            ),
            (Side::Left, Rect::new(2, 3, 5, 20), Rect::new(7, 3, 35, 20)),
            (
                Side::Right,
                Rect::new(37, 3, 5, 20),
                Rect::new(2, 3, 35, 20),
            ),
        ] {
            let mut host = whole;
            assert_eq!(split(&mut host, side, 5), Some(taken), "{side:?}");
            assert_eq!(host, kept, "{side:?}");
            assert_eq!(taken.area() + kept.area(), whole.area());
        }
        // Asking for none or all of the room: left out, the host whole.
        for n in [0, 20] {
            let mut host = whole;
            assert_eq!(split(&mut host, Side::Top, n), None);
            assert_eq!(host, whole);
        }
    }

    #[test]
    fn every_pane_is_named_once_and_the_drawing_comes_first() {
        for (i, a) in PANES.iter().enumerate() {
            assert!(
                PANES[i + 1..].iter().all(|b| b.name != a.name),
                "{}",
                a.name
            );
        }
        assert_eq!(PANES[0].name, "drawing");
    }
}
