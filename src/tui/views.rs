//! The views of the main area, one row each in [`VIEWS`]: its name, the key that shows it, what
//! draws it, what showing and leaving it do, whether another lesson keeps it. The screen draws
//! the row of the view shown, the key table lists the rows' keys ([`super::keys::KEYS`]), the
//! app's [`Message::ToggleView`] shows and leaves them.
//!
//! A new view touches three files: its own (the render function), `mod.rs` (its `pub mod`
//! line) and its row here.

use super::app::App;
use super::keys::{Binding, Context, Message};
use super::{energy_view, loop_view, study_view};
use crossterm::event::KeyCode::{self, Char};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// A view of the main area, by its row's name in [`VIEWS`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct View(pub &'static str);

#[allow(non_upper_case_globals)]
impl View {
    /// Projection, numeric panels, loop strip and lesson page.
    pub const Loop: View = View("loop");
    /// The energy graph in place of the projection.
    pub const Energy: View = View("energy");
    /// The graph of a picked quantity (key `p`) in place of the projection.
    pub const Plot: View = View("plot");
    /// Error against cost of every integrator × dt (computed in the background).
    pub const Study: View = View("study");

    /// Its row of [`VIEWS`] (the loop view's for a name no row has).
    pub fn pane(self) -> &'static ViewPane {
        VIEWS.iter().find(|p| p.view == self).unwrap_or(&VIEWS[0])
    }
}

/// The key that shows a view (pressed again, or Esc, it shows the loop view): as a row of
/// the key table ([`Binding`]), listed after the row labelled `after`.
#[derive(Debug, Clone, Copy)]
pub struct ViewKey {
    pub keys: &'static [KeyCode],
    pub label: &'static str,
    /// The status bar's hint (empty: not in the bar).
    pub hint: &'static str,
    pub help: &'static str,
    /// The label of the main-screen row it is listed after in the status bar and the help (a
    /// row of the key table, or another view's key); a label no row has does not compile.
    pub after: &'static str,
}

/// One view: a row of [`VIEWS`].
#[derive(Debug, Clone, Copy)]
pub struct ViewPane {
    pub view: View,
    /// The key that shows it (None: reached another way, e.g. the quantity graph by its
    /// picker).
    pub key: Option<ViewKey>,
    /// Draws the main area.
    pub render: fn(&App, Rect, &mut Buffer),
    /// What its key does before showing it (the study starts its job).
    pub open: fn(&mut App),
    /// What Esc does when it leaves it (the study stops its job).
    pub leave: fn(&mut App),
    /// Another lesson (the picker, or the settings form applied) opens in it too.
    pub carried: bool,
}

/// Showing or leaving the view does nothing more.
fn nothing(_: &mut App) {}

/// The study of the scene as it runs, started unless the one kept is of the collision
/// response in use.
fn open_study(app: &mut App) {
    let current = app
        .session
        .study
        .as_ref()
        .is_some_and(|job| study_view::is_current(job, app));
    if !current {
        app.session.study = Some(study_view::spawn(app));
    }
}

/// Esc leaves the study and stops its work (`s` leaves it running).
fn leave_study(app: &mut App) {
    if app.study_running() {
        app.cancel_study();
        app.ui.notice = Some("study cancelled: s starts it again".into());
    }
}

/// Every view; the first is the one a lesson opens in.
pub const VIEWS: &[ViewPane] = &[
    ViewPane {
        view: View::Loop,
        key: None,
        render: loop_view::render,
        open: nothing,
        leave: nothing,
        carried: false,
    },
    ViewPane {
        view: View::Energy,
        key: Some(ViewKey {
            keys: &[Char('g')],
            label: "g",
            hint: "g graph",
            help: "energy graph: kinetic, potential, total, drift",
            after: "t",
        }),
        render: energy_view::render,
        open: nothing,
        leave: nothing,
        carried: true,
    },
    ViewPane {
        view: View::Plot,
        key: None,
        render: energy_view::render,
        open: nothing,
        leave: nothing,
        carried: false,
    },
    ViewPane {
        view: View::Study,
        key: Some(ViewKey {
            keys: &[Char('s')],
            label: "s",
            hint: "",
            help: "study: error against cost of every integrator × dt on this scene (runs in \
                   the background)",
            after: "u",
        }),
        render: study_view::render,
        open: open_study,
        leave: leave_study,
        carried: false,
    },
];

/// How many views have a key.
pub const KEY_COUNT: usize = {
    let mut count = 0;
    let mut i = 0;
    while i < VIEWS.len() {
        if VIEWS[i].key.is_some() {
            count += 1;
        }
        i += 1;
    }
    count
};

/// The key-table row of a view's key.
pub const fn binding(pane: &ViewPane) -> Option<Binding> {
    match pane.key {
        Some(k) => Some(Binding {
            keys: k.keys,
            label: k.label,
            hint: k.hint,
            help: k.help,
            message: Message::ToggleView(pane.view),
            context: Context::Main,
        }),
        None => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_view_has_one_row_and_every_key_a_place() {
        for (i, a) in VIEWS.iter().enumerate() {
            assert!(
                VIEWS[i + 1..].iter().all(|b| b.view != a.view),
                "{:?} twice",
                a.view
            );
            assert_eq!(a.view.pane().view, a.view);
            if let Some(key) = a.key {
                let listed = super::super::keys::KEYS
                    .iter()
                    .filter(|b| b.message == Message::ToggleView(a.view))
                    .count();
                assert_eq!(listed, 1, "{:?}'s key after `{}`", a.view, key.after);
            }
        }
        assert_eq!(VIEWS[0].view, View::Loop);
    }
}
