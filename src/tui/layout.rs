//! Where each pane goes, for each screen layout (key `L` switches):
//!
//! - [`ScreenLayout::Numbers`]: the drawing above the lesson page on the left, every numeric
//!   panel on the right, the loop strip along the bottom. When the left column is at least
//!   [`PAGE_WIDTH`] + 2 wide the page sits under the drawing; otherwise it keeps the left column
//!   and wraps without breaking formulas.
//! - [`ScreenLayout::Stage`]: a large drawing with the essential numbers beside it (the loop
//!   strip under them where there is room) or under it in a narrow terminal (left out when
//!   the drawing would keep fewer than [`MIN_DRAWING_HEIGHT`] rows), and the lesson page across
//!   the whole width below — wide enough for its authors' lines from 88 columns on, a third of
//!   the height (two fifths below 30 rows). For a class.
//!
//! Panels never get cut: a panel wider or taller than its room is left out whole (and named).

use super::panes::CUT_COUNT;
use ratatui::layout::{Constraint, Layout, Rect};

/// The width lesson pages are written for (`docs/lesson-format.md`: lines under about 86
/// characters); pages wrap at this width or the pane's, whichever is narrower.
pub const PAGE_WIDTH: u16 = 86;

/// The lowest drawing over the essentials in the stage layout, rows (with its border).
pub const MIN_DRAWING_HEIGHT: u16 = 8;

/// The narrowest drawing beside the panels, columns.
pub const MIN_DRAWING_WIDTH: u16 = 26;

/// The narrowest drawing beside panels a page quotes, which may take columns from the
/// drawing down to this (a quoted panel is shown at any size).
pub const MIN_DRAWING_WIDTH_QUOTED: u16 = 20;

/// The arrangement of the main area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ScreenLayout {
    /// Every panel, the loop strip and the lesson page beside the drawing.
    #[default]
    Numbers,
    /// A large drawing, the essential numbers, the lesson page at full width.
    Stage,
}

impl ScreenLayout {
    pub fn next(self) -> ScreenLayout {
        match self {
            ScreenLayout::Numbers => ScreenLayout::Stage,
            ScreenLayout::Stage => ScreenLayout::Numbers,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            ScreenLayout::Numbers => "numbers",
            ScreenLayout::Stage => "stage",
        }
    }
}

/// The panes of the main area (an absent pane is not drawn).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Areas {
    /// The projection (or, in the energy view, the graph).
    pub drawing: Rect,
    pub lesson: Option<Rect>,
    /// The numeric panels (all of them, or the essentials in the stage layout).
    pub panels: Option<Rect>,
    pub strip: Option<Rect>,
    /// The boxes cut from the areas above (`panes::cut`), in the pane table's order.
    pub cut: [Option<Rect>; CUT_COUNT],
}

/// Splits the main area. `panels_width` is the width the numeric panels ask for (their widest
/// line plus the border) and `quoted_width` the width the panels the page quotes need to show
/// a row each (the drawing gives up columns for it, down to [`MIN_DRAWING_WIDTH_QUOTED`]);
/// `essentials` the width and height of the essentials panel;
/// `page_lines` how many lines the lesson page takes at the full width (stage layout).
pub fn areas(
    area: Rect,
    layout: ScreenLayout,
    panels_width: u16,
    quoted_width: u16,
    essentials: (u16, u16),
    page_lines: u16,
) -> Areas {
    match layout {
        ScreenLayout::Numbers => {
            let strip_height = if area.height >= 30 { 6 } else { 4 };
            let [upper, strip] =
                Layout::vertical([Constraint::Min(0), Constraint::Length(strip_height)])
                    .areas(area);
            let panels = panels_width
                .min(upper.width.saturating_sub(MIN_DRAWING_WIDTH))
                .max(quoted_width.min(upper.width.saturating_sub(MIN_DRAWING_WIDTH_QUOTED)));
            let [left, right] =
                Layout::horizontal([Constraint::Min(0), Constraint::Length(panels)]).areas(upper);
            let lesson_height = (left.height * 2 / 5).clamp(4, 16);
            let [drawing, lesson] =
                Layout::vertical([Constraint::Min(0), Constraint::Length(lesson_height)])
                    .areas(left);
            Areas {
                drawing,
                lesson: Some(lesson),
                panels: Some(right),
                strip: Some(strip),
                cut: [None; CUT_COUNT],
            }
        }
        ScreenLayout::Stage => {
            // A short terminal (80×24) gives the page two fifths of the height: the page is
            // what a class reads.
            let share = if area.height >= 30 {
                area.height / 3
            } else {
                area.height * 2 / 5
            };
            let lesson_height = (page_lines + 2).clamp(4, share.max(4)).min(area.height);
            let [upper, lesson] =
                Layout::vertical([Constraint::Min(0), Constraint::Length(lesson_height)])
                    .areas(area);
            let (ew, eh) = essentials;
            let lesson = (lesson_height > 0).then_some(lesson);
            if upper.width >= ew + 40 {
                // Side by side: the essentials, then the loop strip under them if it has room.
                let [drawing, right] =
                    Layout::horizontal([Constraint::Min(0), Constraint::Length(ew)]).areas(upper);
                let [panels, rest] =
                    Layout::vertical([Constraint::Length(eh), Constraint::Min(0)]).areas(right);
                Areas {
                    drawing,
                    lesson,
                    panels: Some(panels),
                    strip: (rest.height >= 4).then_some(rest),
                    cut: [None; CUT_COUNT],
                }
            } else if upper.height >= eh + MIN_DRAWING_HEIGHT {
                let [drawing, panels] =
                    Layout::vertical([Constraint::Min(0), Constraint::Length(eh)]).areas(upper);
                Areas {
                    drawing,
                    lesson,
                    panels: Some(panels),
                    strip: None,
                    cut: [None; CUT_COUNT],
                }
            } else {
                // No room for the essentials under the drawing: the drawing and the page (the
                // numbers layout, L, shows every number).
                Areas {
                    drawing: upper,
                    lesson,
                    panels: None,
                    strip: None,
                    cut: [None; CUT_COUNT],
                }
            }
        }
    }
}
