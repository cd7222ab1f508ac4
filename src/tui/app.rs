//! The app's state and its update function (the Elm architecture): a key becomes a
//! [`Message`], [`App::update`] changes the state, and rendering (`screen.rs`) is a pure
//! function of the state. The simulation is a [`World`] (and, in compare mode, a second one in
//! lock-step); every number shown comes from their snapshots.

use super::history::{History, DEFAULT_CAPACITY};
use super::keys::{self, Context, Message};
use super::plot::{curve_axes, PlotChoice, PlotSeries, MAX_CURVES};
use super::series::{graphed_energy, EnergySeries};
use super::settings_form::{tidy, SettingsForm};
use super::timeline;
use super::viewport::{shown_points, Axis, Region};
use crate::live::LiveValues;
use crate::physics::cloth::ClothIntegrator;
use crate::physics::{Divergence, Integrator, Phase, Response, Snapshot, World};
use crate::scene::{Lesson, SceneEdits};
use crate::tables::Frame;
use crossterm::event::KeyEvent;
use std::path::PathBuf;
use std::time::Instant;

/// What runs beside the lesson's own settings in compare mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    Integrator(Integrator),
    Response(Response),
    /// Another particle integrator for every cloth.
    ClothIntegrator(ClothIntegrator),
}

impl Comparison {
    /// An integrator, a collision response or a particle integrator, by name.
    pub fn from_name(name: &str) -> Option<Comparison> {
        Integrator::from_name(name)
            .map(Comparison::Integrator)
            .or_else(|| Response::from_name(name).map(Comparison::Response))
            .or_else(|| ClothIntegrator::from_name(name).map(Comparison::ClothIntegrator))
    }

    pub fn name(self) -> &'static str {
        match self {
            Comparison::Integrator(i) => i.name(),
            Comparison::Response(r) => r.name(),
            Comparison::ClothIntegrator(c) => c.name(),
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
    /// The graph of a picked quantity (key `p`) in place of the projection.
    Plot,
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
    /// The settings form (key `e`).
    Settings(Box<SettingsForm>),
    /// The jump-to-time prompt (key `J`) and the time typed so far.
    Jump {
        text: String,
    },
    /// The prediction prompt of page `page` (its `predict`), and the number typed so far.
    Predict {
        page: usize,
        text: String,
    },
    /// The quantity picker (key `p`): the selected line, and the horizontal axis chosen so
    /// far (None: time).
    PlotPicker {
        selected: usize,
        x: Option<usize>,
    },
}

/// A student's answer to a page's `predict`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Guess {
    /// Not asked yet.
    Open,
    /// Esc: the run went on without a guess.
    Skipped,
    Given(f64),
}

/// The settings live numbers were simulated with: they are simulated again when these change
/// (the integrator `i`, the response `c`, a cloth's integrator), so a page never narrates
/// another method's numbers.
#[derive(Debug, Clone, PartialEq)]
struct LiveSettings {
    integrator: Integrator,
    response: Option<Response>,
    cloths: Vec<ClothIntegrator>,
}

impl LiveSettings {
    fn of(world: &World) -> LiveSettings {
        LiveSettings {
            integrator: world.integrator(),
            response: world.contact_model().map(|m| m.response),
            cloths: world.cloths().iter().map(|c| c.integrator).collect(),
        }
    }
}

/// What [`App::update`] asks of the world outside the app state (files); [`App::perform`]
/// does it. `update` itself only changes the state, so tests can drive it without touching
/// the disk.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    /// Write the scene file with these values to `to` (the lesson's own file is the source, so
    /// its comments and pages are kept), then load it back to check it.
    WriteScene { edits: Box<SceneEdits>, to: PathBuf },
    /// Write what the graph plots, as CSV, to `to`.
    WriteCsv { text: String, to: PathBuf },
}

/// Most frames a jump (`J`) runs at once.
pub const MAX_JUMP_FRAMES: u64 = 10_000_000;

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
    /// Where the compare world diverged: it stays frozen there (its last finite state) while
    /// the other world runs on.
    pub diverged: Option<Divergence>,
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
    /// Their run (`--against THEIRS.csv`): drawn as a ghost, its first parting step marked.
    pub against: Option<super::Against>,
    pub history: History,
    pub series: EnergySeries,
    /// Every plottable quantity over the run (key `p` picks which one the graph shows).
    pub plot_series: PlotSeries,
    /// What the quantity graph shows (None until picked).
    pub plot: Option<PlotChoice>,
    /// Further curves on the quantity graph after `plot`'s own (column indices; the picker's
    /// `a` adds and removes them, see [`App::plot_curves`]).
    pub plot_extra: Vec<usize>,
    pub region: Region,
    /// The user's zoom over the fitted region (mouse wheel, `z` / `Z`).
    pub zoom: super::viewport::Zoom,
    /// The whole screen as last drawn (set by the rendering: the mouse reads where things are
    /// from it).
    pub screen_area: std::cell::Cell<ratatui::layout::Rect>,
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
    /// Where the run paused by itself (a page, the scene's end), until the next key.
    pub stop: Option<timeline::Stop>,
    pub lesson_scroll: u16,
    /// The largest useful scroll of the page as last drawn (its lines less the pane's height),
    /// set by the lesson pane when it renders, so PgDn stops at the page's end.
    pub lesson_scroll_max: std::cell::Cell<u16>,
    /// How far the page's long formula and table lines are scrolled sideways (`{` `}`).
    pub lesson_hscroll: u16,
    /// The lesson page shown (the scroll starts over when it changes).
    pub page: Option<usize>,
    pub ascii: bool,
    pub show_timing: bool,
    /// Measured physics cost, ns per frame (all four phases), when running.
    pub ns_per_step: Option<f64>,
    /// The measured error under each number (key `u`): a reference run that follows the world.
    pub error_bars: Option<crate::error_bars::Follow>,
    /// The study of this scene, once asked for (key `s`); it runs on its own thread.
    pub study: Option<crate::study::background::Job>,
    /// Body axes and the ω and L arrows drawn (key `a`).
    pub arrows: bool,
    /// The force arrows drawn (key `F`): gravity, contacts, joint reactions, springs.
    pub forces: bool,
    /// The screen layout (key `L`).
    pub layout: super::layout::ScreenLayout,
    /// Key `x` asked for an SVG of the screen; the event loop writes it (it knows the size).
    pub export_requested: bool,
    /// Where `W` writes the edited scene (the working folder).
    pub write_dir: PathBuf,
    /// The body the panels show (Tab picks the next one).
    pub selected: usize,
    /// The values of the pages' live numbers and predictions (see [`crate::live`]), simulated
    /// when the lesson is opened and when a setting they depend on changes; never per frame.
    pub live: std::sync::Arc<LiveValues>,
    live_settings: LiveSettings,
    /// The thread simulating them, when the app computes them in the background
    /// ([`App::interactive`]): its result, and the flag that tells it its values went stale.
    live_job: Option<std::rc::Rc<LiveJob>>,
    /// Live numbers are simulated on a thread (the terminal app), not before the first frame.
    live_in_background: bool,
    /// Each page's answer to its `predict` (Open for pages without one).
    pub guesses: Vec<Guess>,
    /// A run pauses by itself at pages, predictions and the scene's end (off for `tumble
    /// record`, which runs on and must never show a pause it does not make).
    pub pause_at_stops: bool,
    /// Simulated seconds per wall-clock second over the last second of running, measured by
    /// the event loop only (never in tests or exports: it varies between runs).
    pub measured_real_time: Option<f64>,
    /// A jump (`J`) under way: the event loop runs it a slice at a time ([`App::work`]) so
    /// keys and the screen never wait on it; Esc cancels it, `q` quits at once.
    pub job: Option<JumpJob>,
    /// Jumps run as jobs a slice at a time (the terminal app), or at once (tests, `shot`,
    /// `record`: one call, one result).
    pub background_jobs: bool,
    /// The measuring tools (`tools.rs`): stopwatch, period timer, ruler, protractor.
    pub tools: super::tools::Tools,
    pub quit: bool,
}

/// A jump under way: from `from` to `target` (frame counts), asked for time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpJob {
    pub from: u64,
    pub target: u64,
    pub t: f64,
}

/// How long one slice of a job may run before the event loop looks at the keys again.
pub const JOB_SLICE: std::time::Duration = std::time::Duration::from_millis(40);

/// Live numbers being simulated on a thread ([`App::interactive`]).
#[derive(Debug)]
struct LiveJob {
    result: std::sync::mpsc::Receiver<LiveValues>,
    cancel: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl Drop for LiveJob {
    /// A job no longer wanted (stale settings, another lesson, quit) stops at its next step.
    fn drop(&mut self) {
        self.cancel
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }
}

impl App {
    /// The app with its live numbers simulated before it returns (tests, `shot`, `record`:
    /// every frame shows them).
    pub fn new(lesson: Lesson, options: Options) -> App {
        App::build(lesson, options, false)
    }

    /// The terminal app: the first frame is drawn at once and the pages' live numbers read
    /// "(computing…)" while a thread simulates them (lesson 35's pages quote t = 6 s:
    /// about 3 s of stepping); [`App::poll_live`] takes them when they are ready.
    pub fn interactive(lesson: Lesson, options: Options) -> App {
        App::build(lesson, options, true)
    }

    /// The pause at the first step where their run (`--against`) parts from tumble's.
    fn against_parts_here(&self) -> Option<timeline::Stop> {
        let (step, column) = self.against.as_ref()?.parting.as_ref()?;
        (*step == self.world.step_count()).then(|| timeline::Stop {
            label: "they part".into(),
            notice: format!(
                "their run parts from tumble's here (step {step}, column {column}): n steps \
                 phase by phase, ← back, Enter runs on"
            ),
        })
    }

    fn build(lesson: Lesson, options: Options, live_in_background: bool) -> App {
        let world = lesson.scene.world();
        let snapshot = world.snapshot();
        let region = Region::of_world(&snapshot);
        let series = EnergySeries::new(&snapshot, lesson.scene.duration);
        let plot_series = PlotSeries::new(&snapshot);
        let live_settings = LiveSettings::of(&world);
        let guesses = vec![Guess::Open; lesson.pages.len()];
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
            against: None,
            history: History::new(DEFAULT_CAPACITY),
            series,
            plot_series,
            plot: None,
            plot_extra: Vec::new(),
            region,
            zoom: Default::default(),
            screen_area: Default::default(),
            axis: Axis::Front,
            frame: Frame::World,
            view: View::Loop,
            overlay: Overlay::None,
            running: false,
            speed,
            trail: true,
            divergence: None,
            notice: None,
            stop: None,
            lesson_scroll: 0,
            lesson_scroll_max: std::cell::Cell::new(u16::MAX),
            lesson_hscroll: 0,
            page: None,
            ascii: options.ascii,
            show_timing: options.show_timing,
            ns_per_step: None,
            study: None,
            error_bars: None,
            arrows: true,
            forces: false,
            layout: Default::default(),
            export_requested: false,
            write_dir: PathBuf::from("."),
            selected: 0,
            live: std::sync::Arc::new(LiveValues::computing()),
            live_settings,
            live_job: None,
            live_in_background,
            guesses,
            pause_at_stops: true,
            measured_real_time: None,
            job: None,
            background_jobs: live_in_background,
            tools: Default::default(),
            quit: false,
        };
        app.start_live(app.world.clone());
        if let Some(comparison) = options.compare {
            app.start_compare(comparison);
        }
        app.refresh();
        app
    }

    /// Simulates the live numbers from `world` (at t = 0): here, or on a thread.
    fn start_live(&mut self, world: World) {
        if !self.live_in_background {
            self.live = std::sync::Arc::new(LiveValues::compute(&self.lesson, world));
            return;
        }
        let (send, result) = std::sync::mpsc::channel();
        let cancel = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let (lesson, stop) = (self.lesson.clone(), cancel.clone());
        std::thread::spawn(move || {
            if let Some(values) = LiveValues::compute_unless(&lesson, world, &stop) {
                // The app may be gone, or want newer values: then nobody reads this.
                let _ = send.send(values);
            }
        });
        // The old job, if any, is dropped (with the last copy of the app holding it): told
        // to stop.
        self.live_job = Some(std::rc::Rc::new(LiveJob { result, cancel }));
        self.live = std::sync::Arc::new(LiveValues::computing());
    }

    /// Takes the live numbers' thread's values when they are ready; never blocks.
    pub fn poll_live(&mut self) {
        let Some(job) = &self.live_job else {
            return;
        };
        match job.result.try_recv() {
            Ok(values) => {
                self.live = std::sync::Arc::new(values);
                self.live_job = None;
            }
            Err(std::sync::mpsc::TryRecvError::Empty) => {}
            Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                // The thread ended without values (it panicked): they print as not computed.
                self.live = std::sync::Arc::new(LiveValues::default());
                self.live_job = None;
            }
        }
    }

    /// Live numbers are being simulated: the event loop must wake up to show them.
    pub fn live_pending(&self) -> bool {
        self.live_job.is_some()
    }

    /// The context keys are read in.
    pub fn context(&self) -> Context {
        match self.overlay {
            Overlay::Picker { .. } => Context::Picker,
            Overlay::PlotPicker { .. } => Context::PlotPicker,
            Overlay::Settings(_) => Context::Form,
            Overlay::Jump { .. } | Overlay::Predict { .. } => Context::Prompt,
            _ => Context::Main,
        }
    }

    /// A key event: looked up in the key table, applied, and what it asks of the outside world
    /// performed.
    pub fn handle_key(&mut self, event: &KeyEvent) {
        if let Some(message) = keys::message(event, self.context()) {
            if let Some(effect) = self.update(message) {
                self.perform(effect);
            }
        }
    }

    /// A mouse event: made a message ([`super::mouse::message`]) and applied like a key.
    pub fn handle_mouse(&mut self, event: &crossterm::event::MouseEvent) {
        if let Some(message) = super::mouse::message(event) {
            if let Some(effect) = self.update(message) {
                self.perform(effect);
            }
        }
    }

    /// Takes the study thread's news (progress, result); never blocks.
    pub fn poll_study(&mut self) {
        if let Some(job) = &self.study {
            job.poll();
        }
    }

    /// Stops the study's thread at its next step and forgets the study.
    pub fn cancel_study(&mut self) {
        if let Some(job) = self.study.take() {
            job.cancel();
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

    /// Applies a message; returns what the outside world must do, if anything (see [`Effect`]).
    pub fn update(&mut self, message: Message) -> Option<Effect> {
        self.notice = None;
        self.stop = None;
        if let Some(job) = self.job {
            // A jump under way: q quits at once (the job is dropped with it), Esc cancels it
            // where it is; other keys wait for it.
            match message {
                Message::Quit => {
                    self.job = None;
                    self.cancel_study();
                    self.quit = true;
                }
                Message::Back => {
                    self.job = None;
                    self.notice = Some(format!(
                        "jump cancelled at t = {} s (step {})",
                        tidy(self.world.time()),
                        self.world.step_count()
                    ));
                }
                _ => self.notice = Some(self.job_progress(&job)),
            }
            return None;
        }
        if self.overlay == Overlay::Help && matches!(message, Message::ToggleHelp | Message::Back) {
            // `?` and Esc close the help.
            self.overlay = Overlay::None;
            return None;
        }
        match message {
            Message::Back => self.back(),
            Message::Continue => {
                if self.divergence.is_some() {
                    self.blocked();
                } else if !self.ask_prediction() {
                    self.running = true;
                }
            }
            Message::OpenJump => {
                self.running = false;
                self.overlay = Overlay::Jump {
                    text: String::new(),
                };
            }
            Message::OpenSettings => {
                self.running = false;
                // The body the panels show (Tab picks it), named in the form's title.
                let body = self
                    .selected
                    .min(self.lesson.scene.bodies.len().saturating_sub(1));
                let mut form = SettingsForm::new(SceneEdits::of_body(&self.lesson.scene, body));
                form.body_name = self.lesson.scene.bodies.get(body).map(|b| b.name.clone());
                self.overlay = Overlay::Settings(Box::new(form));
            }
            Message::WriteScene => return self.write_scene(),
            Message::Type(c) => match &mut self.overlay {
                Overlay::Settings(form) => form.type_char(c),
                Overlay::Jump { text } if text.chars().count() < 16 => text.push(c),
                Overlay::Predict { text, .. } if text.chars().count() < 16 => text.push(c),
                _ => {}
            },
            Message::Erase => match &mut self.overlay {
                Overlay::Settings(form) => form.erase(),
                Overlay::Jump { text } | Overlay::Predict { text, .. } => {
                    text.pop();
                }
                _ => {}
            },
            Message::FieldUp | Message::FieldDown => {
                if let Overlay::Settings(form) = &mut self.overlay {
                    if message == Message::FieldUp {
                        form.up();
                    } else {
                        form.down();
                    }
                }
            }
            Message::Submit => match &self.overlay {
                Overlay::Settings(_) => self.apply_settings(),
                Overlay::Jump { text } => {
                    let text = text.clone();
                    self.overlay = Overlay::None;
                    match text.trim().parse::<f64>() {
                        Ok(t) if t >= 0.0 && t.is_finite() => self.jump_to(t),
                        _ => self.notice = Some(format!("jump: `{text}` is not a time ≥ 0 s")),
                    }
                }
                Overlay::Predict { page, text } => {
                    let (page, text) = (*page, text.clone());
                    match text.trim().parse::<f64>() {
                        Ok(guess) if guess.is_finite() => {
                            self.overlay = Overlay::None;
                            self.guesses[page] = Guess::Given(guess);
                            self.notice = Some(format!(
                                "your guess: {} — running to t = {} s to see",
                                text.trim(),
                                tidy(
                                    self.lesson.pages[page]
                                        .predict
                                        .as_ref()
                                        .map_or(0.0, |p| p.at)
                                )
                            ));
                            self.running = true;
                        }
                        _ => self.notice = Some(format!("predict: `{text}` is not a number")),
                    }
                }
                _ => {}
            },
            Message::TogglePause => {
                if self.divergence.is_some() {
                    self.blocked();
                } else if self.running || !self.ask_prediction() {
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
            Message::NextIntegrator if self.world.body_count() == 0 => {
                // Cloths only: the particle integrator of every cloth.
                let next = self
                    .world
                    .cloths()
                    .first()
                    .map_or(ClothIntegrator::SymplecticEuler, |c| c.integrator.next());
                self.before_change();
                apply(&mut self.world, Comparison::ClothIntegrator(next));
                // Replay from an earlier keyframe would step the old integrator.
                self.history.break_segment();
                self.refresh();
            }
            Message::NextIntegrator => {
                let next = self.world.integrator().next();
                self.before_change();
                self.world.set_integrator(next);
                self.refresh();
            }
            Message::NextResponse => self.next_response(),
            Message::NextBody => {
                let count = self.world.body_count();
                if count > 1 {
                    self.selected = (self.selected + 1) % count;
                    self.previous = None;
                    self.refresh();
                    self.notice = Some(format!(
                        "the panels show body {} ({} of {count})",
                        self.snapshot.body_name,
                        self.selected + 1
                    ));
                } else if count == 1 {
                    self.notice = Some("one body in this scene: Tab has nothing to pick".into());
                } else {
                    self.notice =
                        Some("no rigid body in this scene: Tab has nothing to pick".into());
                }
            }
            Message::NextCompare => self.next_compare(),
            Message::NextAxis => self.axis = self.axis.next(),
            Message::ToggleFrame => self.frame = self.frame.toggle(),
            Message::ToggleTrail => self.trail = !self.trail,
            Message::ToggleErrors => {
                self.error_bars = match self.error_bars {
                    Some(_) => None,
                    None => Some(crate::error_bars::Follow::new(
                        &self.lesson.scene,
                        &self.world,
                    )),
                };
                self.refresh();
            }
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
            Message::ScrollUp => {
                self.lesson_scroll = self
                    .lesson_scroll
                    .min(self.lesson_scroll_max.get())
                    .saturating_sub(3)
            }
            Message::ScrollDown => {
                self.lesson_scroll = self
                    .lesson_scroll
                    .saturating_add(3)
                    .min(self.lesson_scroll_max.get())
            }
            Message::ScrollLeft => self.lesson_hscroll = self.lesson_hscroll.saturating_sub(8),
            Message::ScrollRight => {
                self.lesson_hscroll = self.lesson_hscroll.saturating_add(8).min(200)
            }
            Message::ToggleHelp => self.overlay = Overlay::Help,
            Message::Quit => {
                self.cancel_study();
                self.quit = true;
            }
            Message::PickerUp | Message::PickerDown => {
                let n = match &self.overlay {
                    Overlay::Picker { lessons, .. } => lessons.len(),
                    _ => self.plot_series.columns.len(),
                }
                .max(1);
                if let Overlay::Picker { selected, .. } | Overlay::PlotPicker { selected, .. } =
                    &mut self.overlay
                {
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
            Message::ToggleForces => self.forces = !self.forces,
            Message::NextLayout => self.layout = self.layout.next(),
            Message::ExportSvg => self.export_requested = true,
            Message::OpenPlot => {
                let (selected, x) = self.plot.map_or((0, None), |p| (p.y, p.x));
                self.overlay = Overlay::PlotPicker { selected, x };
            }
            Message::PlotAgainstTime | Message::PlotAsX | Message::PlotY => {
                if let Overlay::PlotPicker { selected, x } = &mut self.overlay {
                    match message {
                        Message::PlotAgainstTime => *x = None,
                        Message::PlotAsX => *x = Some(*selected),
                        _ => {
                            let choice = PlotChoice {
                                y: *selected,
                                x: *x,
                            };
                            self.overlay = Overlay::None;
                            self.graph(choice);
                        }
                    }
                }
            }
            Message::PlotAdd => {
                if let Overlay::PlotPicker { selected, x } = self.overlay {
                    self.overlay = Overlay::None;
                    self.toggle_curve(selected, x);
                }
            }
            Message::ExportCsv => return self.export_csv(),
            Message::Tool(key) => self.tool_key(key),
            Message::ZoomIn => self.zoom_by(1, None),
            Message::ZoomOut => self.zoom_by(-1, None),
            Message::Mouse(m) => self.mouse(m),
        }
        None
    }

    /// Shows the quantity graph of `choice`, one curve (the picker's Enter).
    pub fn graph(&mut self, choice: PlotChoice) {
        self.plot = Some(choice);
        self.plot_extra.clear();
        self.view = View::Plot;
    }

    /// The curves of the quantity graph, first `plot`'s own, then the others (at most
    /// [`MAX_CURVES`], of at most two units: see [`curve_axes`]); empty before a pick.
    pub fn plot_curves(&self) -> Vec<usize> {
        let Some(choice) = self.plot else {
            return Vec::new();
        };
        let wanted: Vec<usize> = std::iter::once(choice.y)
            .chain(self.plot_extra.iter().copied())
            .collect();
        curve_axes(&self.plot_series.columns, &wanted).curves
    }

    /// The picker's `a`: column `column` joins the graph as another curve, or leaves it if it
    /// is on it; against `x` (the picker's horizontal axis) when nothing is graphed yet.
    fn toggle_curve(&mut self, column: usize, x: Option<usize>) {
        let name = |app: &App| app.plot_series.columns[column].name.clone();
        let Some(choice) = self.plot else {
            self.graph(PlotChoice { y: column, x });
            return;
        };
        let mut curves = self.plot_curves();
        self.view = View::Plot;
        if let Some(at) = curves.iter().position(|&c| c == column) {
            if curves.len() == 1 {
                self.notice = Some(format!(
                    "{} is the graph's only curve: Enter graphs another instead",
                    name(self)
                ));
                return;
            }
            curves.remove(at);
            self.plot = Some(PlotChoice {
                y: curves[0],
                x: choice.x,
            });
            self.plot_extra = curves[1..].to_vec();
            self.notice = Some(format!("{} taken off the graph", name(self)));
            return;
        }
        curves.push(column);
        let axes = curve_axes(&self.plot_series.columns, &curves);
        if !axes.curves.contains(&column) {
            let units = match axes.right {
                Some(right) => format!("{} and {right}", axes.left),
                None => axes.left.to_string(),
            };
            self.notice = Some(if axes.curves.len() == MAX_CURVES {
                format!("the graph has {MAX_CURVES} curves already: `a` on one takes it off")
            } else {
                format!(
                    "the graph's two axes are in {units}: {} needs a third (Enter graphs it \
                     alone)",
                    name(self)
                )
            });
            return;
        }
        self.plot_extra = axes.curves[1..].to_vec();
        self.notice = Some(match axes.right {
            Some(right) => format!(
                "{} added: two axes, {} on the left, {right} on the right",
                name(self),
                axes.left
            ),
            None => format!("{} added: one shared axis, {}", name(self), axes.left),
        });
    }

    /// The file `X` writes: `tumble-NAME-energy.csv`, or `tumble-NAME-Y.csv` /
    /// `tumble-NAME-X-Y.csv` for a quantity graph, in [`App::write_dir`] (characters other
    /// than letters, digits, `.`, `-` and `_` left out of the quantities' names).
    pub fn csv_path(&self) -> Option<PathBuf> {
        let stem = self
            .lesson
            .path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        let clean = |name: &str| -> String {
            name.chars()
                .filter(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_'))
                .collect()
        };
        let what = match self.view {
            View::Energy => "energy".to_string(),
            View::Plot => {
                let p = self.plot?;
                let columns = &self.plot_series.columns;
                p.x.into_iter()
                    .chain(self.plot_curves())
                    .map(|c| clean(&columns[c].name))
                    .collect::<Vec<_>>()
                    .join("-")
            }
            _ => return None,
        };
        Some(self.write_dir.join(format!("tumble-{stem}-{what}.csv")))
    }

    /// `X`: what the graph shown plots, as CSV (the energy graph, or the quantity graph).
    fn export_csv(&mut self) -> Option<Effect> {
        let text = match (self.view, self.plot) {
            (View::Energy, _) => self.series.csv(self.world.dt()),
            (View::Plot, Some(choice)) => self.plot_series.csv_of(choice.x, &self.plot_curves()),
            _ => {
                self.notice = Some(
                    "no graph shown: g shows the energy graph, p picks a quantity to graph".into(),
                );
                return None;
            }
        };
        Some(Effect::WriteCsv {
            text,
            to: self.csv_path()?,
        })
    }

    /// Does what [`App::update`] asked of the outside world; the status line says how it went.
    pub fn perform(&mut self, effect: Effect) {
        match effect {
            Effect::WriteScene { edits, to } => {
                let source = &self.lesson.path;
                // A bundled lesson outside a clone has no file on disk: its compiled-in text.
                let written = crate::lessons::source(source)
                    .map(|(_, text)| text)
                    .ok_or_else(|| format!("cannot read {}", source.display()))
                    .and_then(|text| {
                        edits.write_into(&text, edits.body.unwrap_or(0), source.parent())
                    })
                    .and_then(|text| std::fs::write(&to, text).map_err(|e| e.to_string()))
                    .and_then(|()| crate::scene::load(&to).map_err(|e| e.to_string()));
                self.notice = Some(match written {
                    Ok(_) => format!("wrote {} (tumble check accepts it)", to.display()),
                    Err(e) => format!("could not write {}: {e}", to.display()),
                });
            }
            Effect::WriteCsv { text, to } => {
                let rows = text.lines().count().saturating_sub(1);
                let header = text.lines().next().unwrap_or("").to_string();
                self.notice = Some(match std::fs::write(&to, text) {
                    Ok(()) => format!("wrote {} ({rows} rows: {header})", to.display()),
                    Err(e) => format!("could not write {}: {e}", to.display()),
                });
            }
        }
    }

    /// The page shown asks for a prediction not made yet, of a time still ahead: opens the
    /// prompt (and returns true) instead of running.
    fn ask_prediction(&mut self) -> bool {
        let Some(index) = self.page else {
            return false;
        };
        let Some(predict) = &self.lesson.pages[index].predict else {
            return false;
        };
        let ahead = self.world.step_count() < crate::live::step_at(predict.at, self.world.dt());
        if self.guesses[index] != Guess::Open || !ahead {
            return false;
        }
        self.running = false;
        self.overlay = Overlay::Predict {
            page: index,
            text: String::new(),
        };
        true
    }

    /// The question of page `page`'s prediction: `what will cube.y be at t = 1 s (m)?`.
    pub fn prediction_question(&self, page: usize) -> String {
        match self.lesson.pages.get(page).and_then(|p| p.predict.as_ref()) {
            Some(p) => format!(
                "what will {} be at t = {} s (in {})?",
                p.quantity.text,
                tidy(p.at),
                p.quantity.measure.unit()
            ),
            None => String::new(),
        }
    }

    /// The line that sets a prediction beside the simulated value, once the run has reached
    /// its time: `cube.y at t = 1 s: your guess 0.3 m · simulated 0.25 m · error 20 %`.
    pub fn prediction_result(&self, page: usize) -> Option<String> {
        let predict = self.lesson.pages.get(page)?.predict.as_ref()?;
        let reached = self.world.step_count() >= crate::live::step_at(predict.at, self.world.dt());
        if !reached {
            return None;
        }
        let value = self.live.value(&predict.quantity, predict.at);
        let unit = predict.quantity.measure.unit();
        let simulated = self.live.describe(&predict.quantity, predict.at);
        let head = format!("{} at t = {} s", predict.quantity.text, tidy(predict.at));
        Some(match (self.guesses[page], value) {
            (Guess::Given(guess), Some(crate::live::Value::Number(v))) => format!(
                "{head}: your guess {} {unit} · simulated {simulated} · relative error {:.1} %",
                tidy(guess),
                100.0 * crate::live::relative_error(guess, v)
            ),
            (Guess::Given(guess), _) => {
                format!(
                    "{head}: your guess {} {unit} · simulated {simulated}",
                    tidy(guess)
                )
            }
            _ => format!("{head}: simulated {simulated}"),
        })
    }

    /// Esc: closes the innermost window, else the graph or the study; never quits.
    fn back(&mut self) {
        if let Overlay::Settings(_) = self.overlay {
            self.notice = Some("settings closed: nothing applied".into());
        }
        if let Overlay::Predict { page, .. } = self.overlay {
            self.guesses[page] = Guess::Skipped;
            self.notice = Some("no guess: Enter runs on".into());
        }
        if self.overlay != Overlay::None {
            self.overlay = Overlay::None;
        } else if self.view != View::Loop {
            if self.view == View::Study && self.study_running() {
                // Esc leaves the study and stops its work (`s` leaves it running).
                self.cancel_study();
                self.notice = Some("study cancelled: s starts it again".into());
            }
            self.view = View::Loop;
        } else {
            self.notice = Some("nothing to close: q quits".into());
        }
    }

    /// The file `W` writes: `NAME-edited.toml` in [`App::write_dir`].
    pub fn write_path(&self) -> PathBuf {
        let stem = self
            .lesson
            .path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        let stem = stem.strip_suffix("-edited").unwrap_or(&stem).to_string();
        self.write_dir.join(format!("{stem}-edited.toml"))
    }

    /// `W`: the form's values (when it is open and they are valid), else the scene as it runs.
    fn write_scene(&mut self) -> Option<Effect> {
        let edits = match &mut self.overlay {
            Overlay::Settings(form) => match form.edits() {
                Ok(edits) => edits,
                Err(e) => {
                    form.error = Some(e);
                    return None;
                }
            },
            _ => SceneEdits::of_body(&self.lesson.scene, self.selected),
        };
        // The written file must pass what the loader checks: the same rules here.
        if let Err(e) = edits.apply(&self.lesson.scene) {
            match &mut self.overlay {
                Overlay::Settings(form) => form.error = Some(e),
                _ => self.notice = Some(format!("cannot write the scene: {e}")),
            }
            return None;
        }
        Some(Effect::WriteScene {
            edits: Box::new(edits),
            to: self.write_path(),
        })
    }

    /// Enter in the form: the scene restarts at t = 0 with the new values (the other settings
    /// are kept as when opening another lesson).
    fn apply_settings(&mut self) {
        let Overlay::Settings(form) = &mut self.overlay else {
            return;
        };
        let edits = match form.edits() {
            Ok(edits) => edits,
            Err(e) => {
                form.error = Some(e);
                return;
            }
        };
        let changes = form.changes(&edits);
        if form.live_only() {
            let tunings = form.tunings(&edits);
            self.apply_live(edits, tunings, changes);
            return;
        }
        match edits.apply(&self.lesson.scene) {
            Ok(scene) => {
                let mut lesson = self.lesson.clone();
                lesson.scene = scene;
                let selected = self.selected;
                self.open(lesson);
                // The body edited stays the one the panels show.
                if selected < self.world.body_count() {
                    self.selected = selected;
                    self.refresh();
                }
                self.notice = Some(format!(
                    "settings applied ({changes}): the scene restarted at t = 0"
                ));
            }
            Err(e) => form.error = Some(e),
        }
    }

    /// Enter in the form when only continuous values changed (g, drag, e, μ, a spring's k, a
    /// motor's speed): the world takes them where it is ([`World::tune`]) and the run goes
    /// on — t and the state kept, as PhET's sliders do; the scene keeps them for a reset.
    fn apply_live(
        &mut self,
        edits: SceneEdits,
        tunings: Vec<crate::physics::Tuning>,
        changes: String,
    ) {
        // The scene as edited (its bodies untouched: no body value changed).
        let scene = SceneEdits {
            body: None,
            ..edits
        }
        .apply(&self.lesson.scene);
        let scene = match scene {
            Ok(scene) => scene,
            Err(e) => {
                if let Overlay::Settings(form) = &mut self.overlay {
                    form.error = Some(e);
                }
                return;
            }
        };
        self.overlay = Overlay::None;
        if tunings.is_empty() {
            self.notice = Some("settings: no value changed".into());
            return;
        }
        // A frame in progress is finished first: the change acts between frames.
        while !self.at_frame_start() && self.divergence.is_none() {
            self.step_phase();
        }
        self.before_change();
        for &tuning in &tunings {
            if let Err(e) = self.world.tune(tuning) {
                self.notice = Some(format!("settings: {e}"));
                return;
            }
            if let Some(ghost) = &mut self.ghost {
                ghost.world.tune(tuning).ok();
            }
        }
        self.lesson.scene = scene;
        // Frames before the change could only be replayed with the new values (a keyframe
        // keeps the state, not g, k or a motor's speed): stepping back stops at the change.
        self.history.clear();
        // The pages' live numbers are simulated again with the new values; the ± reference
        // ran the old ones.
        self.start_live(self.lesson.scene.world());
        let bars = self.error_bars.take().is_some();
        self.refresh();
        self.notice = Some(format!(
            "applied live ({changes}): the run goes on from t = {} s (, steps back to here, \
             not before){}",
            tidy(self.world.time()),
            if bars { "; u shows the ± again" } else { "" }
        ));
    }

    /// Replaces the lesson, keeping what carries across lessons: the view axis, the numbers'
    /// frame, the trail, the graph view, the compare ghost (when the new scene offers it), the
    /// speed relative to real time, ASCII and timing. The run starts paused at t = 0.
    fn open(&mut self, lesson: Lesson) {
        let options = Options {
            ascii: self.ascii,
            compare: self.ghost.as_ref().map(|g| g.comparison),
            show_timing: self.show_timing,
        };
        let real_time = self.frames_per_second() * self.world.dt();
        let (axis, frame, trail, write_dir) =
            (self.axis, self.frame, self.trail, self.write_dir.clone());
        let (arrows, layout, forces) = (self.arrows, self.layout, self.forces);
        // The quantity graph's quantities are the old scene's: it does not carry over.
        let view = if self.view == View::Energy {
            View::Energy
        } else {
            View::Loop
        };
        *self = App::build(lesson, options, self.live_in_background);
        self.axis = axis;
        self.frame = frame;
        self.trail = trail;
        self.view = view;
        self.write_dir = write_dir;
        (self.arrows, self.layout, self.forces) = (arrows, layout, forces);
        let dt = self.world.dt();
        self.speed = (0..SPEEDS.len())
            .min_by(|&a, &b| {
                let off = |i: usize| (SPEEDS[i] * dt / real_time).ln().abs();
                off(a).total_cmp(&off(b))
            })
            .unwrap_or(self.speed);
    }

    /// Goes to time t (rounded to a step): forward from here, or replayed from t = 0 when t is
    /// earlier; paused there. A frame in progress is finished first. With
    /// [`App::background_jobs`] the frames are run by [`App::work`], a slice at a time.
    pub fn jump_to(&mut self, t: f64) {
        self.running = false;
        while !self.at_frame_start() && self.divergence.is_none() {
            self.step_phase();
        }
        let target = (t / self.world.dt()).round() as u64;
        if target < self.world.step_count() {
            self.reset();
        }
        let frames = target - self.world.step_count();
        if frames > MAX_JUMP_FRAMES {
            self.notice = Some(format!(
                "jump: t = {} s is {frames} frames away, more than {MAX_JUMP_FRAMES}: \
                 choose a larger dt (e) or a nearer time",
                tidy(t)
            ));
            return;
        }
        let job = JumpJob {
            from: self.world.step_count(),
            target,
            t,
        };
        if self.background_jobs {
            self.notice = Some(self.job_progress(&job));
            self.job = Some(job);
            self.work(JOB_SLICE);
            return;
        }
        self.step_frames(frames);
        self.jump_done();
    }

    fn jump_done(&mut self) {
        if self.divergence.is_none() {
            self.notice = Some(format!(
                "jumped to t = {} s (step {})",
                tidy(self.world.time()),
                self.world.step_count()
            ));
        }
    }

    /// The status line of a job under way: `jumping to t = 50 s: 12 % (t = 6.03 s) · Esc
    /// cancels, q quits`.
    fn job_progress(&self, job: &JumpJob) -> String {
        let done = self.world.step_count().saturating_sub(job.from);
        let all = job.target.saturating_sub(job.from).max(1);
        format!(
            "jumping to t = {} s: {} % (t = {} s) · Esc cancels, q quits",
            tidy(job.t),
            100 * done / all,
            tidy(self.world.time()),
        )
    }

    /// Runs the job under way (if any) for about `budget` of wall-clock time, in chunks of
    /// frames sized by the measured cost per frame; returns whether work is left. The event
    /// loop calls it between looking at the keys, so a key waits at most one slice.
    pub fn work(&mut self, budget: std::time::Duration) -> bool {
        let start = Instant::now();
        while let Some(job) = self.job {
            let left = job.target.saturating_sub(self.world.step_count());
            if left == 0 || self.divergence.is_some() {
                self.job = None;
                self.jump_done();
                return false;
            }
            // A chunk of about a quarter of the budget at the measured cost per frame.
            let chunk = match self.ns_per_step {
                Some(ns) if ns > 0.0 => ((budget.as_secs_f64() * 0.25e9 / ns) as u64).max(1),
                _ => 16,
            };
            self.step_frames(chunk.min(left));
            if start.elapsed() >= budget {
                break;
            }
        }
        match self.job {
            Some(job) => {
                self.notice = Some(self.job_progress(&job));
                true
            }
            None => false,
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

    /// Saves the current frame start in the history (if at one): whole at a keyframe, else
    /// its barycenter only (see `history`).
    fn remember(&mut self) {
        if self.at_frame_start() {
            if self.world.hand().is_some() {
                // The hand's pull follows the pointer, which replay cannot know: kept whole.
                self.history.break_segment();
            }
            self.history.push(
                self.world.state().position,
                &self.world,
                self.ghost.as_ref().map(|g| &g.world),
            );
        }
    }

    fn before_change(&mut self) {
        self.previous = Some(self.snapshot.clone());
    }

    /// Re-reads the snapshots and keeps the bodies in frame.
    pub(super) fn refresh(&mut self) {
        let settings = LiveSettings::of(&self.world);
        if settings != self.live_settings {
            let mut world = self.world.clone();
            world.reset();
            self.start_live(world);
            self.live_settings = settings;
        }
        self.snapshot = self.world.snapshot_of(self.selected);
        if let Some(bars) = &mut self.error_bars {
            bars.follow(&self.lesson.scene, &self.world, self.selected);
        }
        let mut shown = shown_points(&self.snapshot);
        if let Some(ghost) = &mut self.ghost {
            ghost.snapshot = ghost.world.snapshot_of(self.selected);
            // A diverged ghost's runaway positions would take the view with them.
            if ghost.diverged.is_none() {
                shown.extend(shown_points(&ghost.snapshot));
            }
        }
        self.region.include(&shown);
        let page = self.lesson.page_at(self.snapshot.time).map(|(i, _)| i);
        if page != self.page {
            self.page = page;
            self.lesson_scroll = 0;
            self.lesson_hscroll = 0;
        }
    }

    /// Checks both worlds after a frame. A compare world that diverges is frozen there and
    /// marked (the run goes on); when the world itself diverges beside a compare world that
    /// has not, the two trade places (the run follows the one still running, the diverged one
    /// stays as the frozen ghost). Only when nothing runs on does the run pause, with a dialog.
    fn check_divergence(&mut self) -> bool {
        if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
            if let Some(d) = ghost.world.divergence() {
                self.notice = Some(format!(
                    "the ghost ({}) diverged at step {} ({}): it stays frozen there, the run                      goes on",
                    ghost.comparison.name(),
                    d.step,
                    d.quantity
                ));
                ghost.diverged = Some(d);
            }
        }
        let Some(d) = self.world.divergence() else {
            return false;
        };
        let healthy = self.ghost.as_ref().is_some_and(|g| g.diverged.is_none());
        if healthy && self.swap_with_ghost(&d) {
            return false;
        }
        self.divergence = Some(d);
        self.running = false;
        true
    }

    /// The world diverged (`d`) and the compare world has not: they trade places, so the run
    /// follows the compare world and the diverged world is the frozen ghost. The ghost's
    /// comparison becomes the diverged world's setting. False when the settings cannot be told
    /// apart by one comparison (then nothing changes).
    fn swap_with_ghost(&mut self, d: &Divergence) -> bool {
        let Some(ghost) = self.ghost.as_mut() else {
            return false;
        };
        let own = match ghost.comparison {
            Comparison::Integrator(_) => Comparison::Integrator(self.world.integrator()),
            Comparison::Response(_) => match self.world.contact_model() {
                Some(m) => Comparison::Response(m.response),
                None => return false,
            },
            Comparison::ClothIntegrator(_) => match self.world.cloths().first() {
                Some(c) => Comparison::ClothIntegrator(c.integrator),
                None => return false,
            },
        };
        let running = ghost.comparison;
        std::mem::swap(&mut self.world, &mut ghost.world);
        ghost.comparison = own;
        ghost.diverged = Some(d.clone());
        self.history.swap_worlds();
        self.notice = Some(format!(
            "{} diverged at step {} ({}): the run follows the ghost ({}) now, the diverged \
             world stays frozen as the ghost",
            own.name(),
            d.step,
            d.quantity,
            running.name()
        ));
        true
    }

    /// Records the frame just finished in the energy series.
    fn record_frame(&mut self) {
        let energy = graphed_energy(&self.world);
        let drift = self.world.energy_balance().drift;
        let ghost = self.ghost.as_ref().map(|g| graphed_energy(&g.world).total);
        self.series.record(
            self.world.step_count(),
            self.world.dt(),
            &energy,
            drift,
            ghost,
        );
        if self.plot_series.keeps(self.world.step_count()) {
            self.plot_series.record(&self.world.snapshot());
        }
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
            if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
                ghost.world.step();
            }
            self.record_frame();
            if self.check_divergence() {
                break;
            }
            if self.running && self.pause_at_stops {
                let stop =
                    timeline::stop_at(&self.lesson, self.world.dt(), self.world.step_count());
                let stop = stop.or_else(|| self.against_parts_here());
                if let Some(stop) = stop {
                    self.running = false;
                    // A prediction due at a page's own time: its comparison comes first.
                    self.notice = Some(match self.prediction_reached() {
                        Some(result) => format!(
                            "{} · {}",
                            result.trim_end_matches(": Enter continues"),
                            stop.notice
                        ),
                        None => stop.notice.clone(),
                    });
                    self.stop = Some(stop);
                    break;
                }
                if let Some(result) = self.prediction_reached() {
                    self.running = false;
                    self.stop = Some(timeline::Stop {
                        label: "prediction".into(),
                        notice: result.clone(),
                    });
                    self.notice = Some(result);
                    break;
                }
            }
        }
        // Every run of frames is measured, one frame too: a heavy scene runs one frame per
        // render (`affordable_frames`), and its ns/step must not freeze at the last longer run.
        if done > 0 {
            let ns = cost * 1e9 / done as f64;
            self.ns_per_step = Some(match self.ns_per_step {
                Some(old) => 0.8 * old + 0.2 * ns,
                None => ns,
            });
        }
        self.refresh();
    }

    /// The result line of a guessed prediction whose time the run has just reached.
    fn prediction_reached(&self) -> Option<String> {
        let step = self.world.step_count();
        let dt = self.world.dt();
        (0..self.lesson.pages.len())
            .filter(|&i| matches!(self.guesses[i], Guess::Given(_)))
            .find(|&i| {
                self.lesson.pages[i]
                    .predict
                    .as_ref()
                    .is_some_and(|p| crate::live::step_at(p.at, dt) == step)
            })
            .and_then(|i| self.prediction_result(i))
            .map(|r| format!("{r}: Enter continues"))
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
        if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
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
        self.step_back_frames(1);
    }

    /// `frames` steps back at once (at most to the oldest frame kept); with cloths this costs
    /// one replay from a keyframe, not `frames` of them.
    pub fn step_back_frames(&mut self, frames: usize) {
        if self.history.is_empty() {
            self.notice = Some("no earlier frame kept".into());
            return;
        }
        if frames == 0 {
            return;
        }
        self.before_change();
        // Frames rebuilt from a keyframe are stepped again as they ran: frames the hand pulled
        // are keyframes (see `remember`), so the replayed ones ran without it.
        let hand = self.world.hand().copied();
        self.world.set_hand(None);
        if let Some(ghost) = &mut self.ghost {
            ghost.world.set_hand(None);
        }
        let restored = self.history.pop_frames_into(
            frames,
            &mut self.world,
            self.ghost.as_mut().map(|g| &mut g.world),
        );
        self.world.set_hand(hand);
        if let Some(ghost) = &mut self.ghost {
            ghost.world.set_hand(hand);
        }
        if let Some(ghost) = &mut self.ghost {
            if !restored.is_some_and(|r| r.compare) {
                ghost.world = self.world.clone();
                apply(&mut ghost.world, ghost.comparison);
                self.history.break_segment();
            }
            ghost.diverged = ghost.world.divergence();
        }
        self.divergence = None;
        self.series.truncate_after(self.world.time());
        self.plot_series.truncate_after(self.world.time());
        self.refresh();
    }

    /// Back to t = 0 (both worlds), paused; the view region starts over.
    pub fn reset(&mut self) {
        self.before_change();
        self.world.reset();
        if let Some(ghost) = &mut self.ghost {
            ghost.world = self.world.clone();
            apply(&mut ghost.world, ghost.comparison);
            ghost.diverged = None;
        }
        self.history.clear();
        self.divergence = None;
        self.running = false;
        self.snapshot = self.world.snapshot_of(self.selected);
        self.region = Region::of_world(&self.snapshot);
        self.series = EnergySeries::new(&self.snapshot, self.lesson.scene.duration);
        self.plot_series = PlotSeries::new(&self.snapshot);
        // The stopwatch's times were of the run replaced: it starts over (shown as it was).
        self.tools.stopwatch = Default::default();
        self.refresh();
    }

    fn next_response(&mut self) {
        match self.world.contact_model().copied() {
            Some(_) if self.world.body_count() == 0 => {
                self.notice = Some(
                    "no bodies in this scene: the collision response acts on bodies (particles \
                     use the restitution and friction)"
                        .into(),
                )
            }
            Some(mut model) => {
                // The next response the scene's rules allow (the rules the file and `--response`
                // pass); one they refuse is skipped, and the notice says why.
                let start = model.response;
                let mut refused = None;
                loop {
                    model.response = model.response.next();
                    if model.response == start {
                        break;
                    }
                    match self.rules_with(model.response) {
                        Ok(()) => break,
                        Err(why) => refused = refused.or(Some(why)),
                    }
                }
                if let Some(why) = refused {
                    self.notice = Some(format!("skipped: {why}"));
                }
                if model.response != start {
                    self.world.set_contact_model(model);
                }
            }
            None => self.notice = Some("no obstacles in this scene: no collision response".into()),
        }
    }

    /// The settings the run uses that the lesson's pages were not written for (after `i`,
    /// `c`): `the page describes rk4 + seed; running impulse`, or None when they are the
    /// lesson's own. The page's numbers are the lesson's settings', so the page says so.
    pub fn page_settings_note(&self) -> Option<String> {
        let scene = &self.lesson.scene;
        let (mut own, mut now) = (Vec::new(), Vec::new());
        if self.world.body_count() > 0 && self.world.integrator() != scene.integrator {
            own.push(scene.integrator.name());
            now.push(self.world.integrator().name());
        }
        if let (Some(a), Some(b)) = (scene.contact, self.world.contact_model()) {
            if a.response != b.response {
                own.push(a.response.name());
                now.push(b.response.name());
            }
        }
        for (a, b) in scene.cloths.iter().zip(self.world.cloths()) {
            if a.integrator != b.integrator {
                own.push(a.integrator.name());
                now.push(b.integrator.name());
                break;
            }
        }
        (!own.is_empty()).then(|| {
            format!(
                " the page describes {}; running {} ",
                own.join(" + "),
                now.join(" + ")
            )
        })
    }

    /// Whether the scene as it runs, with collision response `response`, passes the scene's
    /// rules ([`crate::scene::Scene::check_rules`], as a file and the command line do); the
    /// error names the app's keys.
    fn rules_with(&self, response: Response) -> Result<(), String> {
        let mut scene = self.lesson.scene.clone();
        scene.dt = self.world.dt();
        if let Some(model) = &mut scene.contact {
            model.response = response;
        }
        scene
            .check_rules(crate::scene::Naming::Keys)
            .map_err(|(_, why)| why)
    }

    /// The comparisons this scene offers, in cycling order: the other body integrators and
    /// collision responses when it has bodies (and obstacles), the other particle integrators
    /// when it has cloths.
    pub fn comparisons(&self) -> Vec<Comparison> {
        let mut list: Vec<Comparison> = Vec::new();
        if self.world.body_count() > 0 {
            list.extend(
                Integrator::ALL
                    .into_iter()
                    .filter(|&i| i != self.world.integrator())
                    .map(Comparison::Integrator),
            );
            if let Some(model) = self.world.contact_model() {
                list.extend(
                    Response::ALL
                        .into_iter()
                        .filter(|&r| r != model.response && self.rules_with(r).is_ok())
                        .map(Comparison::Response),
                );
            }
        }
        list.extend(
            ClothIntegrator::ALL
                .into_iter()
                .filter(|&c| !same_cloth_integrator(&self.world, c))
                .map(Comparison::ClothIntegrator),
        );
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
                self.history.break_segment();
                self.before_change();
                self.refresh();
            }
        }
    }

    /// Starts a compare world at the current moment: a copy of the world with `comparison`
    /// applied at the start of the current frame, brought to the same phase.
    pub fn start_compare(&mut self, comparison: Comparison) {
        let missing = match comparison {
            Comparison::Response(_) if self.world.contact_model().is_none() => Some("obstacles"),
            Comparison::Integrator(_) | Comparison::Response(_) if self.world.body_count() == 0 => {
                Some("bodies")
            }
            Comparison::ClothIntegrator(_) if self.world.cloths().is_empty() => Some("cloths"),
            _ => None,
        };
        if let Some(missing) = missing {
            self.notice = Some(format!(
                "no {missing} in this scene: nothing to compare with `{}`",
                comparison.name()
            ));
            return;
        }
        if let Comparison::Response(response) = comparison {
            if let Err(why) = self.rules_with(response) {
                self.notice = Some(format!("no ghost: {why}"));
                return;
            }
        }
        let mut world = self.world.clone();
        if !self.at_frame_start() {
            self.history.restore_last(&mut world, None);
        }
        apply(&mut world, comparison);
        while world.last_phase() != self.world.last_phase() {
            world.step_phase();
        }
        let same = match comparison {
            Comparison::Integrator(i) => i == self.world.integrator(),
            Comparison::Response(r) => Some(r) == self.world.contact_model().map(|m| m.response),
            Comparison::ClothIntegrator(c) => same_cloth_integrator(&self.world, c),
        };
        if same {
            self.notice = Some(format!(
                "the ghost runs `{}` too: press k for another",
                comparison.name()
            ));
        }
        let snapshot = world.snapshot();
        let diverged = world.divergence();
        self.ghost = Some(Ghost {
            comparison,
            world,
            snapshot,
            diverged,
        });
        self.history.break_segment();
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
            Ok(lesson) => self.open(lesson),
            Err(e) => {
                self.overlay = Overlay::None;
                self.notice = Some(e.to_string());
            }
        }
    }
}

/// Whether every cloth of the world runs `integrator` already (true without cloths).
fn same_cloth_integrator(world: &World, integrator: ClothIntegrator) -> bool {
    world.cloths().iter().all(|c| c.integrator == integrator)
}

/// Applies a comparison to a world.
fn apply(world: &mut World, comparison: Comparison) {
    match comparison {
        Comparison::Integrator(i) => world.set_integrator(i),
        Comparison::ClothIntegrator(c) => {
            for i in 0..world.cloths().len() {
                world.set_cloth_integrator(i, c);
            }
        }
        Comparison::Response(r) => {
            if let Some(mut model) = world.contact_model().copied() {
                model.response = r;
                world.set_contact_model(model);
            }
        }
    }
}
