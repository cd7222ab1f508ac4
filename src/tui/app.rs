//! The app's state and its update function (the Elm architecture): a key becomes a
//! [`Message`], [`App::update`] changes the state, and rendering (`screen.rs`) is a pure
//! function of the state. The simulation is a [`World`] (and, in compare mode, a second one in
//! lock-step); every number shown comes from their snapshots.

use super::history::{Entry, History, DEFAULT_CAPACITY};
use super::keys::{self, Context, Message};
use super::series::EnergySeries;
use super::viewport::{Axis, Region};
use crate::physics::{Divergence, Integrator, Phase, Response, Snapshot, World};
use crate::scene::Lesson;
use crate::tables::Frame;
use crossterm::event::KeyEvent;
use std::path::PathBuf;
use std::time::Instant;

/// What runs beside the lesson's own settings in compare mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    Integrator(Integrator),
    Response(Response),
}

impl Comparison {
    /// An integrator or a collision response, by name.
    pub fn from_name(name: &str) -> Option<Comparison> {
        Integrator::from_name(name)
            .map(Comparison::Integrator)
            .or_else(|| Response::from_name(name).map(Comparison::Response))
    }

    pub fn name(self) -> &'static str {
        match self {
            Comparison::Integrator(i) => i.name(),
            Comparison::Response(r) => r.name(),
        }
    }
}

/// The main area's content. A new view is a variant here, a render file, and a key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Projection, numeric panels, loop strip and lesson page.
    Loop,
    /// The energy graph in place of the projection.
    Energy,
    /// Error against cost of every integrator × dt (computed in the background).
    Study,
}

/// A window over the main screen.
#[derive(Debug, Clone, PartialEq)]
pub enum Overlay {
    None,
    Help,
    /// The bundled lessons (path, title or load error) and the selected line.
    Picker {
        lessons: Vec<(PathBuf, String)>,
        selected: usize,
    },
}

/// Start-up options.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Pure-ASCII projection (what the snapshots use) instead of Braille.
    pub ascii: bool,
    /// Start in compare mode.
    pub compare: Option<Comparison>,
    /// Show measured timing (off when rendering for tests: it varies between runs).
    pub show_timing: bool,
}

/// Simulation speeds, frames per wall-clock second: from slow motion to faster than real time.
pub const SPEEDS: [f64; 16] = [
    1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1e3, 2e3, 5e3, 1e4, 2e4, 5e4, 1e5,
];

/// The compare world and what it runs.
#[derive(Debug, Clone)]
pub struct Ghost {
    pub comparison: Comparison,
    pub world: World,
    pub snapshot: Snapshot,
}

/// The whole app state.
#[derive(Debug, Clone)]
pub struct App {
    pub lesson: Lesson,
    pub world: World,
    pub snapshot: Snapshot,
    /// The snapshot before the last action (changed cells are highlighted).
    pub previous: Option<Snapshot>,
    pub ghost: Option<Ghost>,
    pub history: History,
    pub series: EnergySeries,
    pub region: Region,
    pub axis: Axis,
    pub frame: Frame,
    pub view: View,
    pub overlay: Overlay,
    pub running: bool,
    /// Index into [`SPEEDS`].
    pub speed: usize,
    pub trail: bool,
    pub divergence: Option<Divergence>,
    /// A one-line notice (e.g. "no earlier frame kept").
    pub notice: Option<String>,
    pub lesson_scroll: u16,
    /// The lesson page shown (the scroll starts over when it changes).
    pub page: Option<usize>,
    pub ascii: bool,
    pub show_timing: bool,
    /// Measured physics cost, ns per frame (all four phases), when running.
    pub ns_per_step: Option<f64>,
    /// The study of this scene, once asked for (key `s`); it runs on its own thread.
    pub study: Option<crate::study::background::Job>,
    /// Body axes and the ω and L arrows drawn (key `a`).
    pub arrows: bool,
    /// The screen layout (key `L`).
    pub layout: super::layout::ScreenLayout,
    /// Key `x` asked for an SVG of the screen; the event loop writes it (it knows the size).
    pub export_requested: bool,
    pub quit: bool,
}

impl App {
    pub fn new(lesson: Lesson, options: Options) -> App {
        let world = lesson.scene.world();
        let snapshot = world.snapshot();
        let region = Region::initial(
            &lesson.scene.first().body,
            &snapshot.vertices,
            world.obstacles(),
        );
        let series = EnergySeries::new(&snapshot, lesson.scene.duration);
        let real_time = 1.0 / lesson.scene.dt;
        let speed = SPEEDS
            .iter()
            .rposition(|&s| s <= real_time * 1.000001)
            .unwrap_or(0);
        let mut app = App {
            lesson,
            world,
            snapshot,
            previous: None,
            ghost: None,
            history: History::new(DEFAULT_CAPACITY),
            series,
            region,
            axis: Axis::Front,
            frame: Frame::World,
            view: View::Loop,
            overlay: Overlay::None,
            running: false,
            speed,
            trail: true,
            divergence: None,
            notice: None,
            lesson_scroll: 0,
            page: None,
            ascii: options.ascii,
            show_timing: options.show_timing,
            ns_per_step: None,
            study: None,
            arrows: true,
            layout: Default::default(),
            export_requested: false,
            quit: false,
        };
        if let Some(comparison) = options.compare {
            app.start_compare(comparison);
        }
        app.refresh();
        app
    }

    /// The context keys are read in.
    pub fn context(&self) -> Context {
        match self.overlay {
            Overlay::Picker { .. } => Context::Picker,
            _ => Context::Main,
        }
    }

    /// A key event: looked up in the key table, then applied.
    pub fn handle_key(&mut self, event: &KeyEvent) {
        if let Some(message) = keys::message(event, self.context()) {
            self.update(message);
        }
    }

    /// Takes the study thread's news (progress, result); never blocks.
    pub fn poll_study(&mut self) {
        if let Some(job) = &self.study {
            job.poll();
        }
    }

    /// A study is running: the event loop must wake up to show its progress.
    pub fn study_running(&self) -> bool {
        self.study.as_ref().is_some_and(|job| !job.finished())
    }

    /// Frames per wall-clock second while running.
    pub fn frames_per_second(&self) -> f64 {
        SPEEDS[self.speed]
    }

    /// Applies a message.
    pub fn update(&mut self, message: Message) {
        self.notice = None;
        if self.overlay == Overlay::Help && matches!(message, Message::ToggleHelp | Message::Quit) {
            // `?`, q and Esc close the help first.
            self.overlay = Overlay::None;
            return;
        }
        match message {
            Message::TogglePause => {
                if self.divergence.is_some() {
                    self.blocked();
                } else {
                    self.running = !self.running;
                }
            }
            Message::StepFrame => {
                self.running = false;
                self.step_frames(1);
            }
            Message::StepPhase => {
                self.running = false;
                self.step_phase();
            }
            Message::StepBack => {
                self.running = false;
                self.step_back();
            }
            Message::Faster => self.speed = (self.speed + 1).min(SPEEDS.len() - 1),
            Message::Slower => self.speed = self.speed.saturating_sub(1),
            Message::Reset => self.reset(),
            Message::NextIntegrator => {
                let next = self.world.integrator().next();
                self.before_change();
                self.world.set_integrator(next);
                self.refresh();
            }
            Message::NextResponse => self.next_response(),
            Message::NextCompare => self.next_compare(),
            Message::NextAxis => self.axis = self.axis.next(),
            Message::ToggleFrame => self.frame = self.frame.toggle(),
            Message::ToggleTrail => self.trail = !self.trail,
            Message::ToggleEnergy => {
                self.view = match self.view {
                    View::Energy => View::Loop,
                    _ => View::Energy,
                }
            }
            Message::ToggleStudy => {
                if self.view == View::Study {
                    self.view = View::Loop;
                } else {
                    if !self
                        .study
                        .as_ref()
                        .is_some_and(|job| super::study_view::is_current(job, self))
                    {
                        self.study = Some(super::study_view::spawn(self));
                    }
                    self.view = View::Study;
                }
            }
            Message::OpenPicker => self.open_picker(),
            Message::ScrollUp => self.lesson_scroll = self.lesson_scroll.saturating_sub(3),
            Message::ScrollDown => self.lesson_scroll = self.lesson_scroll.saturating_add(3),
            Message::ToggleHelp => self.overlay = Overlay::Help,
            Message::Quit => self.quit = true,
            Message::PickerUp | Message::PickerDown => {
                if let Overlay::Picker { lessons, selected } = &mut self.overlay {
                    let n = lessons.len().max(1);
                    *selected = if message == Message::PickerUp {
                        (*selected + n - 1) % n
                    } else {
                        (*selected + 1) % n
                    };
                }
            }
            Message::PickerOpen => self.open_selected(),
            Message::Close => self.overlay = Overlay::None,
            Message::ToggleArrows => self.arrows = !self.arrows,
            Message::NextLayout => self.layout = self.layout.next(),
            Message::ExportSvg => self.export_requested = true,
        }
    }

    fn blocked(&mut self) {
        self.running = false;
        self.notice = Some("the simulation diverged: step back (←) or reset (r)".into());
    }

    /// Whether the world sits between two frames.
    fn at_frame_start(&self) -> bool {
        matches!(self.world.last_phase(), None | Some(Phase::Collide))
    }

    /// Saves the current frame start in the history (if at one).
    fn remember(&mut self) {
        if self.at_frame_start() {
            self.history.push(Entry {
                world: self.world.checkpoint(),
                compare: self.ghost.as_ref().map(|g| g.world.checkpoint()),
                position: self.world.state().position,
            });
        }
    }

    fn before_change(&mut self) {
        self.previous = Some(self.snapshot.clone());
    }

    /// Re-reads the snapshots and keeps the bodies in frame.
    fn refresh(&mut self) {
        self.snapshot = self.world.snapshot();
        if let Some(ghost) = &mut self.ghost {
            ghost.snapshot = ghost.world.snapshot();
            let both = [&self.snapshot.vertices[..], &ghost.snapshot.vertices[..]].concat();
            self.region.include(&both);
        } else {
            self.region.include(&self.snapshot.vertices);
        }
        let page = self.lesson.page_at(self.snapshot.time).map(|(i, _)| i);
        if page != self.page {
            self.page = page;
            self.lesson_scroll = 0;
        }
    }

    /// Checks both worlds after a frame; pauses with a dialog on divergence.
    fn check_divergence(&mut self) -> bool {
        let diverged = self.world.divergence().or_else(|| {
            self.ghost.as_ref().and_then(|g| {
                g.world.divergence().map(|mut d| {
                    d.quantity = format!("compare world ({}): {}", g.comparison.name(), d.quantity);
                    d
                })
            })
        });
        if let Some(d) = diverged {
            self.divergence = Some(d);
            self.running = false;
            true
        } else {
            false
        }
    }

    /// Records the frame just finished in the energy series.
    fn record_frame(&mut self) {
        let energy = self.world.energy_of(self.world.state());
        let ghost = self
            .ghost
            .as_ref()
            .map(|g| g.world.energy_of(g.world.state()).total);
        self.series
            .record(self.world.step_count(), self.world.dt(), &energy, ghost);
    }

    /// Runs up to `frames` whole frames (both worlds); stops at a divergence.
    pub fn step_frames(&mut self, frames: u64) {
        if self.divergence.is_some() {
            self.blocked();
            return;
        }
        let mut cost = 0.0;
        let mut done = 0u64;
        for i in 0..frames {
            if i + 1 == frames {
                self.before_change();
            }
            self.remember();
            let start = Instant::now();
            self.world.step();
            cost += start.elapsed().as_secs_f64();
            done += 1;
            if let Some(ghost) = &mut self.ghost {
                ghost.world.step();
            }
            self.record_frame();
            if self.check_divergence() {
                break;
            }
        }
        if frames > 1 && done > 0 {
            let ns = cost * 1e9 / done as f64;
            self.ns_per_step = Some(match self.ns_per_step {
                Some(old) => 0.8 * old + 0.2 * ns,
                None => ns,
            });
        }
        self.refresh();
    }

    /// Runs the next phase (both worlds).
    pub fn step_phase(&mut self) {
        if self.divergence.is_some() {
            self.blocked();
            return;
        }
        self.before_change();
        self.remember();
        let phase = self.world.step_phase();
        if let Some(ghost) = &mut self.ghost {
            ghost.world.step_phase();
        }
        if phase == Phase::Collide {
            self.record_frame();
            self.check_divergence();
        }
        self.refresh();
    }

    /// Back to the start of the previous frame (or of the current one, mid-frame).
    pub fn step_back(&mut self) {
        let Some(entry) = self.history.pop() else {
            self.notice = Some("no earlier frame kept".into());
            return;
        };
        self.before_change();
        self.world.restore(&entry.world);
        if let Some(ghost) = &mut self.ghost {
            match &entry.compare {
                Some(c) => ghost.world.restore(c),
                None => {
                    ghost.world = self.world.clone();
                    apply(&mut ghost.world, ghost.comparison);
                }
            }
        }
        self.divergence = None;
        self.series.truncate_after(self.world.time());
        self.refresh();
    }

    /// Back to t = 0 (both worlds), paused; the view region starts over.
    pub fn reset(&mut self) {
        self.before_change();
        self.world.reset();
        if let Some(ghost) = &mut self.ghost {
            ghost.world = self.world.clone();
            apply(&mut ghost.world, ghost.comparison);
        }
        self.history.clear();
        self.divergence = None;
        self.running = false;
        self.snapshot = self.world.snapshot();
        self.region = Region::initial(
            &self.lesson.scene.first().body,
            &self.snapshot.vertices,
            self.world.obstacles(),
        );
        self.series = EnergySeries::new(&self.snapshot, self.lesson.scene.duration);
        self.refresh();
    }

    fn next_response(&mut self) {
        match self.world.contact_model().copied() {
            Some(mut model) => {
                model.response = model.response.next();
                self.world.set_contact_model(model);
            }
            None => self.notice = Some("no obstacles in this scene: no collision response".into()),
        }
    }

    /// The comparisons this scene offers, in cycling order.
    fn comparisons(&self) -> Vec<Comparison> {
        let mut list: Vec<Comparison> = Integrator::ALL
            .into_iter()
            .filter(|&i| i != self.world.integrator())
            .map(Comparison::Integrator)
            .collect();
        if let Some(model) = self.world.contact_model() {
            list.extend(
                Response::ALL
                    .into_iter()
                    .filter(|&r| r != model.response)
                    .map(Comparison::Response),
            );
        }
        list
    }

    fn next_compare(&mut self) {
        let list = self.comparisons();
        let next = match &self.ghost {
            None => list.first().copied(),
            Some(g) => list
                .iter()
                .position(|&c| c == g.comparison)
                .and_then(|i| list.get(i + 1).copied()),
        };
        match next {
            Some(c) => self.start_compare(c),
            None => {
                self.ghost = None;
                self.before_change();
                self.refresh();
            }
        }
    }

    /// Starts a compare world at the current moment: a copy of the world with `comparison`
    /// applied at the start of the current frame, brought to the same phase.
    pub fn start_compare(&mut self, comparison: Comparison) {
        if let Comparison::Response(_) = comparison {
            if self.world.contact_model().is_none() {
                self.notice = Some(format!(
                    "no obstacles in this scene: nothing to compare with `{}`",
                    comparison.name()
                ));
                return;
            }
        }
        let mut world = self.world.clone();
        if !self.at_frame_start() {
            if let Some(entry) = self.history.last() {
                world.restore(&entry.world);
            }
        }
        apply(&mut world, comparison);
        while world.last_phase() != self.world.last_phase() {
            world.step_phase();
        }
        let same = match comparison {
            Comparison::Integrator(i) => i == self.world.integrator(),
            Comparison::Response(r) => Some(r) == self.world.contact_model().map(|m| m.response),
        };
        if same {
            self.notice = Some(format!(
                "the ghost runs `{}` too: press k for another",
                comparison.name()
            ));
        }
        let snapshot = world.snapshot();
        self.ghost = Some(Ghost {
            comparison,
            world,
            snapshot,
        });
        self.refresh();
    }

    fn open_picker(&mut self) {
        let lessons: Vec<(PathBuf, String)> = crate::lessons::bundled()
            .into_iter()
            .map(|path| {
                let title = match crate::lessons::load(&path) {
                    Ok(l) => l.title,
                    Err(e) => format!("(cannot load: {e})"),
                };
                (path, title)
            })
            .collect();
        let selected = lessons
            .iter()
            .position(|(p, _)| p.file_name() == self.lesson.path.file_name())
            .unwrap_or(0);
        self.overlay = Overlay::Picker { lessons, selected };
    }

    fn open_selected(&mut self) {
        let Overlay::Picker { lessons, selected } = &self.overlay else {
            return;
        };
        let Some((path, _)) = lessons.get(*selected) else {
            self.overlay = Overlay::None;
            return;
        };
        match crate::lessons::load(path) {
            Ok(lesson) => {
                let options = Options {
                    ascii: self.ascii,
                    compare: self.ghost.as_ref().map(|g| g.comparison),
                    show_timing: self.show_timing,
                };
                let (axis, frame) = (self.axis, self.frame);
                let (arrows, layout) = (self.arrows, self.layout);
                *self = App::new(lesson, options);
                self.axis = axis;
                self.frame = frame;
                (self.arrows, self.layout) = (arrows, layout);
            }
            Err(e) => {
                self.overlay = Overlay::None;
                self.notice = Some(e.to_string());
            }
        }
    }
}

/// Applies a comparison to a world.
fn apply(world: &mut World, comparison: Comparison) {
    match comparison {
        Comparison::Integrator(i) => world.set_integrator(i),
        Comparison::Response(r) => {
            if let Some(mut model) = world.contact_model().copied() {
                model.response = r;
                world.set_contact_model(model);
            }
        }
    }
}
