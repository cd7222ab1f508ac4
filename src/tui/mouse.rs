//! The mouse (crossterm's mouse capture; every key still does all it did): a click on a drawn
//! body selects it (as Tab does) and holds it with the hand, dragging pulls it towards the
//! pointer with a stiff damped spring (`physics::hand`: drawn, its pull shown, its work booked
//! in the energy ledger as the hand's), the wheel zooms the drawing about the pointer, and a
//! click on a panel row graphs that quantity (the choice the quantity picker `p` makes).
//!
//! A mouse event becomes a [`Message::Mouse`] ([`message`]) and goes through
//! [`App::update`] like a key, so tests drive it without a terminal. Where things are is read
//! from the screen as last drawn ([`Ui::screen_area`](super::app::Ui::screen_area)): the same layout functions the
//! rendering uses, recomputed.

use super::app::{App, Overlay, View};
use super::keys::Message;
use super::layout::ScreenLayout;
use super::panels::{self, RowHit};
use super::plot::{Measure, PlotChoice, Quantity};
use super::screen;
use super::viewport::{Mapping, Viewport};
use crate::physics::hand::Hand;
use crate::scene::PagePanel;
use crate::tables::Frame;
use crossterm::event::{MouseButton, MouseEvent, MouseEventKind};
use nalgebra::Vector3;

/// What the mouse did, at which terminal cell (column, row).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mouse {
    pub action: Action,
    pub col: u16,
    pub row: u16,
}

/// The mouse actions the app answers (moves without a button are not reported).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    /// The left button went down.
    Press,
    /// Moved with the left button down.
    Drag,
    /// The left button came up.
    Release,
    /// The wheel, away from the user: zoom in.
    WheelUp,
    /// The wheel, towards the user: zoom out.
    WheelDown,
}

/// The message a mouse event sends (None: another button, or a move without a button).
pub fn message(event: &MouseEvent) -> Option<Message> {
    let action = match event.kind {
        MouseEventKind::Down(MouseButton::Left) => Action::Press,
        MouseEventKind::Drag(MouseButton::Left) => Action::Drag,
        MouseEventKind::Up(MouseButton::Left) => Action::Release,
        MouseEventKind::ScrollUp => Action::WheelUp,
        MouseEventKind::ScrollDown => Action::WheelDown,
        _ => return None,
    };
    Some(Message::Mouse(Mouse {
        action,
        col: event.column,
        row: event.row,
    }))
}

/// Where on the screen as last drawn a cell is.
enum Place {
    Drawing(Viewport),
    Panels(RowHit),
    Elsewhere,
}

impl App {
    /// Applies a mouse message (from [`App::update`]).
    pub(super) fn mouse(&mut self, m: Mouse) {
        if m.action == Action::Release {
            // Whatever is open, a released button lets go.
            self.let_go();
            return;
        }
        if self.ui.overlay != Overlay::None {
            return;
        }
        match (m.action, self.place(m.col, m.row)) {
            (Action::Press, Place::Drawing(view)) => self.press(&view, m.col, m.row),
            (Action::Press, Place::Panels(hit)) => self.graph_row(&hit),
            (Action::Drag, Place::Drawing(view)) => self.drag(&view, m.col, m.row),
            (Action::Drag, _) => {
                // Beyond the drawing the mapping goes on: the hand still follows.
                if let Some(view) = self.viewport() {
                    self.drag(&view, m.col, m.row);
                }
            }
            (Action::WheelUp | Action::WheelDown, Place::Drawing(view)) => {
                let notches = if m.action == Action::WheelUp { 1 } else { -1 };
                self.zoom_by(notches, Some(view.cell_of(m.col, m.row)));
            }
            _ => {}
        }
    }

    /// The projection as last drawn: its cells and their mapping to the world (None: another
    /// view, or nothing drawn yet). [`Viewport::world_at`] turns a clicked cell into a point.
    pub fn viewport(&self) -> Option<Viewport> {
        if self.ui.view != View::Loop {
            return None;
        }
        let [_, main, _] = screen::split(self, self.ui.screen_area.get())?;
        super::projection::viewport(self, screen::main_areas(self, main).drawing)
    }

    /// What the screen as last drawn shows at terminal cell (`col`, `row`).
    fn place(&self, col: u16, row: u16) -> Place {
        let Some([_, main, _]) = screen::split(self, self.ui.screen_area.get()) else {
            return Place::Elsewhere;
        };
        if self.ui.view != View::Loop {
            return Place::Elsewhere;
        }
        let areas = screen::main_areas(self, main);
        if let Some(view) = super::projection::viewport(self, areas.drawing) {
            if view.contains(col, row) {
                return Place::Drawing(view);
            }
        }
        if let Some(area) = areas.panels {
            let hit = match self.prefs.layout {
                ScreenLayout::Numbers => panels::row_at(self, area, col, row),
                ScreenLayout::Stage => panels::essentials_row_at(self, area, col, row),
            };
            if let Some(hit) = hit {
                return Place::Panels(hit);
            }
        }
        Place::Elsewhere
    }

    /// `notches` of zoom (in: > 0) about fractional cell `at` of the drawing (None: its centre).
    pub(super) fn zoom_by(&mut self, notches: i32, at: Option<(f64, f64)>) {
        let area = self
            .viewport()
            .map_or(ratatui::layout::Rect::new(0, 0, 80, 24), |v| v.area);
        let fit = Mapping::fit(&self.ui.region, self.prefs.axis, area.width, area.height);
        self.ui.zoom.wheel(&fit, notches, at);
        self.ui.notice = Some(if self.ui.zoom.steps == 0 {
            "the fitted view (z zooms in)".to_string()
        } else {
            format!(
                "zoom ×{}: z / Z or the wheel (as many Z as z: the fitted view)",
                super::settings_form::tidy((self.ui.zoom.factor() * 1000.0).round() / 1000.0)
            )
        });
    }

    /// A click in the drawing: the body under the pointer (the one nearest the viewer) is
    /// selected and held by the hand at the clicked point (in the plane through its
    /// barycenter). On empty space: an end of the ruler when it is shown (the first click its
    /// `from`, the next its `to`, and so on: a fixed point of the world), else nothing.
    fn press(&mut self, view: &Viewport, col: u16, row: u16) {
        let Some(index) = body_under(self, view, col, row) else {
            if self.tools_shown().contains(&PagePanel::Ruler) {
                if let Some(p) = view.world_at(col, row) {
                    let end = self.ui.tools.ruler_clicks % 2;
                    self.ui.tools.ruler_clicks += 1;
                    self.set_ruler_end(end, p, 0.0);
                    self.ui.notice = Some(format!(
                        "the ruler's {} end is the clicked point (a click on empty space sets \
                         the {} end next)",
                        ["first", "second"][end],
                        ["first", "second"][1 - end]
                    ));
                }
            }
            return;
        };
        if index != self.session.selected {
            self.session.selected = index;
            self.session.previous = None;
            self.refresh();
        }
        let name = self.session.snapshot.bodies[index].name.clone();
        let position = self.session.snapshot.bodies[index].position;
        let grabbed = view.world_through(col, row, &position);
        let Some(hand) = self.session.grab(index, grabbed) else {
            self.ui.notice = Some(format!(
                "the panels show body {name}: it is fixed, the hand cannot move it"
            ));
            return;
        };
        self.hold(Some(hand));
        self.ui.notice = Some(format!(
            "the panels show body {name}; drag to pull it (a spring of k = {} N/m){}",
            super::settings_form::tidy(round3(hand.stiffness)),
            if self.ui.running {
                ""
            } else {
                " · space runs"
            }
        ));
    }

    /// A move with the button down: the hand's target follows the pointer (in the plane
    /// through the grabbed point).
    fn drag(&mut self, view: &Viewport, col: u16, row: u16) {
        let (Some(hand), Some(pull)) =
            (self.session.snapshot.hand, self.session.snapshot.hand_pull)
        else {
            return;
        };
        let target = view.world_through(col, row, &pull.at);
        self.hold(Some(Hand { target, ..hand }));
        self.ui.notice = Some(format!(
            "the hand pulls {} towards the pointer (its pull is drawn; its work is the energy \
             panel's hand row){}",
            self.session.snapshot.bodies[hand.body].name,
            if self.ui.running {
                ""
            } else {
                " · space runs"
            }
        ));
    }

    /// The button came up: the hand lets go (the ledger keeps its work).
    fn let_go(&mut self) {
        if self.session.snapshot.hand.is_some() {
            self.hold(None);
            self.ui.notice = Some("the hand let go".into());
        }
    }

    /// The hand on both worlds: [`crate::session::Session::set_hand`] (and while a body is
    /// held, every frame start is kept whole: `App::remember`).
    fn hold(&mut self, hand: Option<Hand>) {
        self.session.set_hand(hand);
    }

    /// A click on a panel row: the graph of its quantity, as the quantity picker (`p`) would
    /// set it; a row no plotted quantity matches says so.
    fn graph_row(&mut self, hit: &RowHit) {
        let column = quantity_of(self, hit).and_then(|q| {
            self.session
                .plot_series
                .columns
                .iter()
                .position(|c| c.quantity == q)
        });
        match column {
            Some(y) => self.graph(PlotChoice { y, x: None }),
            None => {
                self.ui.notice = Some(format!(
                    "`{}` has no graph (p lists what can be graphed)",
                    hit.label
                ))
            }
        }
    }
}

fn round3(x: f64) -> f64 {
    let digits = 3 - x.abs().log10().ceil() as i32;
    let scale = 10f64.powi(digits.max(0));
    (x * scale).round() / scale
}

/// The plotted quantity a panel row shows (None: none of the plot list's). Vectors in the
/// world frame only (the plot list's components are world components); the panels show the
/// selected body.
fn quantity_of(app: &App, hit: &RowHit) -> Option<Quantity> {
    let body = app.session.selected;
    let world_frame = app.prefs.frame == Frame::World;
    let i = hit.cell.min(2);
    let own = |measure| Some(Quantity::Body { body, measure });
    let several = app.session.snapshot.bodies.len() > 1;
    match (hit.panel?, hit.label.as_str()) {
        (PagePanel::State, "x") => own(Measure::Position(i)),
        (PagePanel::AngularVelocity, "ω") => own(Measure::AngularVelocity(i)),
        (PagePanel::Momentum, "v") if world_frame => own(Measure::Velocity(i)),
        (PagePanel::Momentum, "P") if world_frame && !several => Some(Quantity::SceneMomentum(i)),
        (PagePanel::AngularMomentum, "L") if world_frame => own(Measure::AngularMomentum(i)),
        (PagePanel::AngularMomentum, "|L|") => own(Measure::AngularMomentumNorm),
        (PagePanel::Energy, "K, V, E") if !several => own(energy_measure(i)),
        (PagePanel::Energy, "K, V, E") if i == 2 => Some(Quantity::SceneEnergy),
        (PagePanel::BodyEnergy, name) => Some(Quantity::Body {
            body: app
                .session
                .snapshot
                .bodies
                .iter()
                .position(|b| b.name == name)?,
            measure: energy_measure(i),
        }),
        (PagePanel::System, "P total") => Some(Quantity::SceneMomentum(i)),
        _ => None,
    }
}

fn energy_measure(cell: usize) -> Measure {
    match cell {
        0 => Measure::Kinetic,
        1 => Measure::Potential,
        _ => Measure::Energy,
    }
}

/// The body drawn under terminal cell (`col`, `row`): the projected outline (convex hull of its
/// vertices, or its circle when round) contains the cell's centre, give or take a column; of
/// several, the one nearest the viewer.
fn body_under(app: &App, view: &Viewport, col: u16, row: u16) -> Option<usize> {
    let axis = view.axis;
    let pointer = view.world_through(col, row, &Vector3::zeros());
    let (h, v) = axis.project(&pointer);
    let tolerance = view.mapping.scale;
    let bodies = &app.session.snapshot.bodies;
    (0..bodies.len())
        .filter(|&i| {
            let body = &bodies[i];
            let outline: Vec<(f64, f64)> = if body.points_body.is_empty() {
                Vec::new()
            } else {
                body.vertices.iter().map(|p| axis.project(p)).collect()
            };
            if outline.is_empty() {
                let (ch, cv) = axis.project(&body.position);
                return (h - ch).hypot(v - cv) <= body.radius + tolerance;
            }
            distance_to_hull(&convex_hull(outline), (h, v)) <= tolerance
        })
        .max_by(|&a, &b| {
            let depth = |i: usize| bodies[i].position.dot(&axis.toward_viewer());
            depth(a).total_cmp(&depth(b))
        })
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    points.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// The distance from a point to a convex polygon (counter-clockwise; 0 inside); a polygon of
/// one or two points is a point or a segment.
fn distance_to_hull(hull: &[(f64, f64)], p: (f64, f64)) -> f64 {
    let n = hull.len();
    if n == 0 {
        return f64::INFINITY;
    }
    let segment = |a: (f64, f64), b: (f64, f64)| {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let length = dx * dx + dy * dy;
        let t = if length > 0.0 {
            (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / length).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
    };
    let inside = n >= 3
        && (0..n).all(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % n]);
            (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0) >= 0.0
        });
    if inside {
        return 0.0;
    }
    (0..n)
        .map(|i| segment(hull[i], hull[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn left_button_and_wheel_events_are_messages_moves_are_not() {
        use crossterm::event::KeyModifiers;
        let event = |kind| MouseEvent {
            kind,
            column: 7,
            row: 3,
            modifiers: KeyModifiers::NONE,
        };
        let at = |action| {
            Some(Message::Mouse(Mouse {
                action,
                col: 7,
                row: 3,
            }))
        };
        let left = MouseButton::Left;
        assert_eq!(
            message(&event(MouseEventKind::Down(left))),
            at(Action::Press)
        );
        assert_eq!(
            message(&event(MouseEventKind::Drag(left))),
            at(Action::Drag)
        );
        assert_eq!(
            message(&event(MouseEventKind::Up(left))),
            at(Action::Release)
        );
        assert_eq!(
            message(&event(MouseEventKind::ScrollUp)),
            at(Action::WheelUp)
        );
        assert_eq!(
            message(&event(MouseEventKind::ScrollDown)),
            at(Action::WheelDown)
        );
        // Moves without a button (any-event tracking reports every one) and other buttons
        // never reach the update loop: they would clear the status line.
        assert_eq!(message(&event(MouseEventKind::Moved)), None);
        let right = MouseButton::Right;
        assert_eq!(message(&event(MouseEventKind::Down(right))), None);
    }

    #[test]
    fn a_point_is_inside_the_hull_of_a_square_or_its_distance_away() {
        // The unit square's corners and its centre, shuffled: the hull is the four corners;
        // (0.5, 0.5) is inside, (2, 0.5) is 1 from the right side, (2, 2) √2 from a corner.
        let hull = convex_hull(vec![
            (1.0, 1.0),
            (0.5, 0.5),
            (0.0, 0.0),
            (1.0, 0.0),
            (0.0, 1.0),
        ]);
        assert_eq!(hull.len(), 4, "{hull:?}");
        assert_eq!(distance_to_hull(&hull, (0.5, 0.5)), 0.0);
        assert!((distance_to_hull(&hull, (2.0, 0.5)) - 1.0).abs() < 1e-12);
        assert!((distance_to_hull(&hull, (2.0, 2.0)) - 2f64.sqrt()).abs() < 1e-12);
    }
}
