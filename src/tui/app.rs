//! The app's state and its update function (the Elm architecture): a key becomes a
//! [`Message`], [`App::update`] changes the state, and rendering (`screen.rs`) is a pure
//! function of the state. The run is a [`Session`] (the world and, in compare mode, a second
//! one in lock-step, with their history, series and jobs; `shot` and `record` drive the same
//! one); every number and shape drawn comes from its snapshots. [`Preferences`] carry from
//! lesson to lesson; [`Ui`] is the screen's own state.

use super::keys::{self, Context, Message};
use super::plot::{curve_axes, PlotChoice, MAX_CURVES};
use super::settings_form::{tidy, SettingsForm};
use super::timeline;
use super::viewport::{Axis, Region};
use crate::scene::{Lesson, SceneEdits};
use crate::session::Session;
pub use crate::session::{Comparison, Ghost, JumpJob};
use crate::tables::Frame;
use crossterm::event::KeyEvent;
use std::path::PathBuf;
use std::time::Instant;

/// The main area's content: a row of the view table (`views.rs`).
pub use super::views::View;

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

/// The whole app state: the run ([`Session`], shared with `shot` and `record`), the
/// preferences carried from lesson to lesson, and the state of the screen.
#[derive(Debug, Clone)]
pub struct App {
    pub session: Session,
    pub prefs: Preferences,
    pub ui: Ui,
}

/// How the user likes to see things: kept when another lesson is opened (the picker, or
/// settings applied), so a student never sets them twice.
#[derive(Debug, Clone, PartialEq)]
pub struct Preferences {
    /// The axis the projection looks along (`v`).
    pub axis: Axis,
    /// The numbers' frame, world or body (`f`).
    pub frame: Frame,
    /// The barycenter's trail drawn (`t`).
    pub trail: bool,
    /// Body axes and the ω and L arrows drawn (key `a`).
    pub arrows: bool,
    /// The force arrows drawn (key `F`): gravity, contacts, joint reactions, springs.
    pub forces: bool,
    /// The screen layout (key `L`).
    pub layout: super::layout::ScreenLayout,
    /// Pure-ASCII projection (what the snapshots use) instead of Braille.
    pub ascii: bool,
    /// Show measured timing (off when rendering for tests: it varies between runs).
    pub show_timing: bool,
    /// Where `W` and `X` write (the working folder).
    pub write_dir: PathBuf,
}

impl Preferences {
    fn of(options: &Options) -> Preferences {
        Preferences {
            axis: Axis::Front,
            frame: Frame::World,
            trail: true,
            arrows: true,
            forces: false,
            layout: Default::default(),
            ascii: options.ascii,
            show_timing: options.show_timing,
            write_dir: PathBuf::from("."),
        }
    }
}

/// The state of the screen for the lesson shown.
#[derive(Debug, Clone)]
pub struct Ui {
    /// Their run (`--against THEIRS.csv`): drawn as a ghost, its first parting step marked.
    pub against: Option<super::Against>,
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
    pub view: View,
    pub overlay: Overlay,
    pub running: bool,
    /// Index into [`SPEEDS`].
    pub speed: usize,
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
    /// Key `x` asked for an SVG of the screen; the event loop writes it (it knows the size).
    pub export_requested: bool,
    /// Each page's answer to its `predict` (Open for pages without one).
    pub guesses: Vec<Guess>,
    /// A run pauses by itself at pages, predictions and the scene's end (off for `tumble
    /// record`, which runs on and must never show a pause it does not make).
    pub pause_at_stops: bool,
    /// Simulated seconds per wall-clock second over the last second of running, measured by
    /// the event loop only (never in tests or exports: it varies between runs).
    pub measured_real_time: Option<f64>,
    /// The measuring tools (`tools.rs`): stopwatch, period timer, ruler, protractor.
    pub tools: super::tools::Tools,
    pub quit: bool,
}

/// How long one slice of a job may run before the event loop looks at the keys again.
pub const JOB_SLICE: std::time::Duration = std::time::Duration::from_millis(40);

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
        let (step, column) = self.ui.against.as_ref()?.parting.as_ref()?;
        (*step == self.session.step_count()).then(|| timeline::Stop {
            label: "they part".into(),
            notice: format!(
                "their run parts from tumble's here (step {step}, column {column}): n steps \
                 phase by phase, ← back, Enter runs on"
            ),
        })
    }

    fn build(lesson: Lesson, options: Options, live_in_background: bool) -> App {
        let session = Session::new(lesson, live_in_background);
        let prefs = Preferences::of(&options);
        App::with(session, prefs, options.compare)
    }

    /// The app of a session, with these preferences (and a compare world running
    /// `compare`), paused at t = 0 at the speed of real time.
    fn with(session: Session, prefs: Preferences, compare: Option<Comparison>) -> App {
        let real_time = 1.0 / session.lesson.scene.dt;
        let speed = SPEEDS
            .iter()
            .rposition(|&s| s <= real_time * 1.000001)
            .unwrap_or(0);
        let ui = Ui {
            against: None,
            plot: None,
            plot_extra: Vec::new(),
            region: Region::of_world(&session.snapshot),
            zoom: Default::default(),
            screen_area: Default::default(),
            view: View::Loop,
            overlay: Overlay::None,
            running: false,
            speed,
            notice: None,
            stop: None,
            lesson_scroll: 0,
            lesson_scroll_max: std::cell::Cell::new(u16::MAX),
            lesson_hscroll: 0,
            page: None,
            export_requested: false,
            guesses: vec![Guess::Open; session.lesson.pages.len()],
            pause_at_stops: true,
            measured_real_time: None,
            tools: Default::default(),
            quit: false,
        };
        let mut app = App { session, prefs, ui };
        if let Some(comparison) = compare {
            app.start_compare(comparison);
        }
        app.refresh();
        app
    }

    /// Takes the live numbers' thread's values when they are ready; never blocks.
    pub fn poll_live(&mut self) {
        self.session.poll_live();
    }

    /// Live numbers are being simulated: the event loop must wake up to show them.
    pub fn live_pending(&self) -> bool {
        self.session.live_pending()
    }

    /// The context keys are read in.
    pub fn context(&self) -> Context {
        match self.ui.overlay {
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
        self.session.poll_study();
    }

    /// Stops the study's thread at its next step and forgets the study.
    pub fn cancel_study(&mut self) {
        self.session.cancel_study();
    }

    /// A study is running: the event loop must wake up to show its progress.
    pub fn study_running(&self) -> bool {
        self.session.study_running()
    }

    /// Frames per wall-clock second while running.
    pub fn frames_per_second(&self) -> f64 {
        SPEEDS[self.ui.speed]
    }

    /// Applies a message; returns what the outside world must do, if anything (see [`Effect`]).
    pub fn update(&mut self, message: Message) -> Option<Effect> {
        self.ui.notice = None;
        self.ui.stop = None;
        if let Some(job) = self.session.job {
            self.job_key(message, job);
            return None;
        }
        if self.ui.overlay == Overlay::Help
            && matches!(message, Message::ToggleHelp | Message::Back)
        {
            // `?` and Esc close the help.
            self.ui.overlay = Overlay::None;
            return None;
        }
        match message {
            Message::Back => self.back(),
            Message::WriteScene => return self.write_scene(),
            Message::ExportCsv => return self.export_csv(),
            Message::OpenJump
            | Message::OpenSettings
            | Message::Type(_)
            | Message::Erase
            | Message::FieldUp
            | Message::FieldDown
            | Message::Submit
            | Message::OpenPicker
            | Message::ToggleHelp
            | Message::PickerUp
            | Message::PickerDown
            | Message::PickerOpen
            | Message::Close => self.overlay_key(message),
            Message::Continue
            | Message::TogglePause
            | Message::StepFrame
            | Message::StepPhase
            | Message::StepBack
            | Message::Faster
            | Message::Slower
            | Message::Reset
            | Message::NextIntegrator
            | Message::NextResponse
            | Message::NextBody
            | Message::NextCompare => self.run_key(message),
            Message::OpenPlot
            | Message::PlotAgainstTime
            | Message::PlotAsX
            | Message::PlotY
            | Message::PlotAdd => self.plot_key(message),
            _ => self.view_key(message),
        }
        None
    }

    /// A key while a jump is under way: q quits at once (the job is dropped with it), Esc
    /// cancels it where it is; other keys wait for it.
    fn job_key(&mut self, message: Message, job: JumpJob) {
        match message {
            Message::Quit => {
                self.session.job = None;
                self.cancel_study();
                self.ui.quit = true;
            }
            Message::Back => {
                self.session.job = None;
                self.ui.notice = Some(format!(
                    "jump cancelled at t = {} s (step {})",
                    tidy(self.session.time()),
                    self.session.step_count()
                ));
            }
            _ => self.ui.notice = Some(self.job_progress(&job)),
        }
    }

    /// The windows: typing in a prompt or the form, the pickers, opening and closing.
    fn overlay_key(&mut self, message: Message) {
        match message {
            Message::OpenJump => {
                self.ui.running = false;
                self.ui.overlay = Overlay::Jump {
                    text: String::new(),
                };
            }
            Message::OpenSettings => {
                self.ui.running = false;
                // The body the panels show (Tab picks it), named in the form's title.
                let body = self
                    .session
                    .selected
                    .min(self.session.lesson.scene.bodies.len().saturating_sub(1));
                let mut form =
                    SettingsForm::new(SceneEdits::of_body(&self.session.lesson.scene, body));
                form.body_name = self
                    .session
                    .lesson
                    .scene
                    .bodies
                    .get(body)
                    .map(|b| b.name.clone());
                self.ui.overlay = Overlay::Settings(Box::new(form));
            }
            Message::Type(c) => match &mut self.ui.overlay {
                Overlay::Settings(form) => form.type_char(c),
                Overlay::Jump { text } if text.chars().count() < 16 => text.push(c),
                Overlay::Predict { text, .. } if text.chars().count() < 16 => text.push(c),
                _ => {}
            },
            Message::Erase => match &mut self.ui.overlay {
                Overlay::Settings(form) => form.erase(),
                Overlay::Jump { text } | Overlay::Predict { text, .. } => {
                    text.pop();
                }
                _ => {}
            },
            Message::FieldUp | Message::FieldDown => {
                if let Overlay::Settings(form) = &mut self.ui.overlay {
                    if message == Message::FieldUp {
                        form.up();
                    } else {
                        form.down();
                    }
                }
            }
            Message::Submit => match &self.ui.overlay {
                Overlay::Settings(_) => self.apply_settings(),
                Overlay::Jump { text } => {
                    let text = text.clone();
                    self.ui.overlay = Overlay::None;
                    match text.trim().parse::<f64>() {
                        Ok(t) if t >= 0.0 && t.is_finite() => self.jump_to(t),
                        _ => self.ui.notice = Some(format!("jump: `{text}` is not a time ≥ 0 s")),
                    }
                }
                Overlay::Predict { page, text } => {
                    let (page, text) = (*page, text.clone());
                    match text.trim().parse::<f64>() {
                        Ok(guess) if guess.is_finite() => {
                            self.ui.overlay = Overlay::None;
                            self.ui.guesses[page] = Guess::Given(guess);
                            self.ui.notice = Some(format!(
                                "your guess: {} — running to t = {} s to see",
                                text.trim(),
                                tidy(
                                    self.session.lesson.pages[page]
                                        .predict
                                        .as_ref()
                                        .map_or(0.0, |p| p.at)
                                )
                            ));
                            self.ui.running = true;
                        }
                        _ => self.ui.notice = Some(format!("predict: `{text}` is not a number")),
                    }
                }
                _ => {}
            },
            Message::OpenPicker => self.open_picker(),
            Message::ToggleHelp => self.ui.overlay = Overlay::Help,
            Message::PickerUp | Message::PickerDown => {
                let n = match &self.ui.overlay {
                    Overlay::Picker { lessons, .. } => lessons.len(),
                    _ => self.session.plot_series.columns.len(),
                }
                .max(1);
                if let Overlay::Picker { selected, .. } | Overlay::PlotPicker { selected, .. } =
                    &mut self.ui.overlay
                {
                    *selected = if message == Message::PickerUp {
                        (*selected + n - 1) % n
                    } else {
                        (*selected + 1) % n
                    };
                }
            }
            Message::PickerOpen => self.open_selected(),
            Message::Close => self.ui.overlay = Overlay::None,
            _ => {}
        }
    }

    /// Running: pause, steps, speed, reset, and what the world runs (integrator, response, body shown, ghost).
    fn run_key(&mut self, message: Message) {
        match message {
            Message::Continue => {
                if self.session.divergence.is_some() {
                    self.blocked();
                } else if !self.ask_prediction() {
                    self.ui.running = true;
                }
            }
            Message::TogglePause => {
                if self.session.divergence.is_some() {
                    self.blocked();
                } else if self.ui.running || !self.ask_prediction() {
                    self.ui.running = !self.ui.running;
                }
            }
            Message::StepFrame => {
                self.ui.running = false;
                self.step_frames(1);
            }
            Message::StepPhase => {
                self.ui.running = false;
                self.step_phase();
            }
            Message::StepBack => {
                self.ui.running = false;
                self.step_back();
            }
            Message::Faster => self.ui.speed = (self.ui.speed + 1).min(SPEEDS.len() - 1),
            Message::Slower => self.ui.speed = self.ui.speed.saturating_sub(1),
            Message::Reset => self.reset(),
            Message::NextIntegrator => {
                self.session.next_integrator();
                self.refresh();
            }
            Message::NextResponse => self.next_response(),
            Message::NextBody => {
                let count = self.session.snapshot.bodies.len();
                if count > 1 {
                    self.session.selected = (self.session.selected + 1) % count;
                    self.session.previous = None;
                    self.refresh();
                    self.ui.notice = Some(format!(
                        "the panels show body {} ({} of {count})",
                        self.session.snapshot.body_name,
                        self.session.selected + 1
                    ));
                } else if count == 1 {
                    self.ui.notice = Some("one body in this scene: Tab has nothing to pick".into());
                } else {
                    self.ui.notice =
                        Some("no rigid body in this scene: Tab has nothing to pick".into());
                }
            }
            Message::NextCompare => self.next_compare(),
            _ => {}
        }
    }

    /// The quantity graph and its picker.
    fn plot_key(&mut self, message: Message) {
        match message {
            Message::OpenPlot => {
                let (selected, x) = self.ui.plot.map_or((0, None), |p| (p.y, p.x));
                self.ui.overlay = Overlay::PlotPicker { selected, x };
            }
            Message::PlotAgainstTime | Message::PlotAsX | Message::PlotY => {
                if let Overlay::PlotPicker { selected, x } = &mut self.ui.overlay {
                    match message {
                        Message::PlotAgainstTime => *x = None,
                        Message::PlotAsX => *x = Some(*selected),
                        _ => {
                            let choice = PlotChoice {
                                y: *selected,
                                x: *x,
                            };
                            self.ui.overlay = Overlay::None;
                            self.graph(choice);
                        }
                    }
                }
            }
            Message::PlotAdd => {
                if let Overlay::PlotPicker { selected, x } = self.ui.overlay {
                    self.ui.overlay = Overlay::None;
                    self.toggle_curve(selected, x);
                }
            }
            _ => {}
        }
    }

    /// What is drawn (views, arrows, layout, scroll, tools, zoom, mouse) and quitting.
    fn view_key(&mut self, message: Message) {
        match message {
            Message::NextAxis => self.prefs.axis = self.prefs.axis.next(),
            Message::ToggleFrame => self.prefs.frame = self.prefs.frame.toggle(),
            Message::ToggleTrail => self.prefs.trail = !self.prefs.trail,
            Message::ToggleErrors => {
                self.session.toggle_error_bars();
                self.refresh();
            }
            Message::ToggleView(view) => {
                if self.ui.view == view {
                    self.ui.view = View::Loop;
                } else {
                    (view.pane().open)(self);
                    self.ui.view = view;
                }
            }
            Message::ScrollUp => {
                self.ui.lesson_scroll = self
                    .ui
                    .lesson_scroll
                    .min(self.ui.lesson_scroll_max.get())
                    .saturating_sub(3)
            }
            Message::ScrollDown => {
                self.ui.lesson_scroll = self
                    .ui
                    .lesson_scroll
                    .saturating_add(3)
                    .min(self.ui.lesson_scroll_max.get())
            }
            Message::ScrollLeft => {
                self.ui.lesson_hscroll = self.ui.lesson_hscroll.saturating_sub(8)
            }
            Message::ScrollRight => {
                self.ui.lesson_hscroll = self.ui.lesson_hscroll.saturating_add(8).min(200)
            }
            Message::Quit => {
                self.cancel_study();
                self.ui.quit = true;
            }
            Message::ToggleArrows => self.prefs.arrows = !self.prefs.arrows,
            Message::ToggleForces => self.prefs.forces = !self.prefs.forces,
            Message::NextLayout => self.prefs.layout = self.prefs.layout.next(),
            Message::ExportSvg => self.ui.export_requested = true,
            Message::Tool(key) => self.tool_key(key),
            Message::ZoomIn => self.zoom_by(1, None),
            Message::ZoomOut => self.zoom_by(-1, None),
            Message::Mouse(m) => self.mouse(m),
            _ => {}
        }
    }

    /// Shows the quantity graph of `choice`, one curve (the picker's Enter).
    pub fn graph(&mut self, choice: PlotChoice) {
        self.ui.plot = Some(choice);
        self.ui.plot_extra.clear();
        self.ui.view = View::Plot;
    }

    /// The curves of the quantity graph, first `plot`'s own, then the others (at most
    /// [`MAX_CURVES`], of at most two units: see [`curve_axes`]); empty before a pick.
    pub fn plot_curves(&self) -> Vec<usize> {
        let Some(choice) = self.ui.plot else {
            return Vec::new();
        };
        let wanted: Vec<usize> = std::iter::once(choice.y)
            .chain(self.ui.plot_extra.iter().copied())
            .collect();
        curve_axes(&self.session.plot_series.columns, &wanted).curves
    }

    /// The picker's `a`: column `column` joins the graph as another curve, or leaves it if it
    /// is on it; against `x` (the picker's horizontal axis) when nothing is graphed yet.
    fn toggle_curve(&mut self, column: usize, x: Option<usize>) {
        let name = |app: &App| app.session.plot_series.columns[column].name.clone();
        let Some(choice) = self.ui.plot else {
            self.graph(PlotChoice { y: column, x });
            return;
        };
        let mut curves = self.plot_curves();
        self.ui.view = View::Plot;
        if let Some(at) = curves.iter().position(|&c| c == column) {
            if curves.len() == 1 {
                self.ui.notice = Some(format!(
                    "{} is the graph's only curve: Enter graphs another instead",
                    name(self)
                ));
                return;
            }
            curves.remove(at);
            self.ui.plot = Some(PlotChoice {
                y: curves[0],
                x: choice.x,
            });
            self.ui.plot_extra = curves[1..].to_vec();
            self.ui.notice = Some(format!("{} taken off the graph", name(self)));
            return;
        }
        curves.push(column);
        let axes = curve_axes(&self.session.plot_series.columns, &curves);
        if !axes.curves.contains(&column) {
            let units = match axes.right {
                Some(right) => format!("{} and {right}", axes.left),
                None => axes.left.to_string(),
            };
            self.ui.notice = Some(if axes.curves.len() == MAX_CURVES {
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
        self.ui.plot_extra = axes.curves[1..].to_vec();
        self.ui.notice = Some(match axes.right {
            Some(right) => format!(
                "{} added: two axes, {} on the left, {right} on the right",
                name(self),
                axes.left
            ),
            None => format!("{} added: one shared axis, {}", name(self), axes.left),
        });
    }

    /// The file `X` writes: `tumble-NAME-energy.csv`, or `tumble-NAME-Y.csv` /
    /// `tumble-NAME-X-Y.csv` for a quantity graph, in [`Preferences::write_dir`] (characters other
    /// than letters, digits, `.`, `-` and `_` left out of the quantities' names).
    pub fn csv_path(&self) -> Option<PathBuf> {
        let stem = self
            .session
            .lesson
            .path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        let clean = |name: &str| -> String {
            name.chars()
                .filter(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_'))
                .collect()
        };
        let what = match self.ui.view {
            View::Energy => "energy".to_string(),
            View::Plot => {
                let p = self.ui.plot?;
                let columns = &self.session.plot_series.columns;
                p.x.into_iter()
                    .chain(self.plot_curves())
                    .map(|c| clean(&columns[c].name))
                    .collect::<Vec<_>>()
                    .join("-")
            }
            _ => return None,
        };
        Some(
            self.prefs
                .write_dir
                .join(format!("tumble-{stem}-{what}.csv")),
        )
    }

    /// `X`: what the graph shown plots, as CSV (the energy graph, or the quantity graph).
    fn export_csv(&mut self) -> Option<Effect> {
        let text = match (self.ui.view, self.ui.plot) {
            (View::Energy, _) => self.session.series.csv(self.session.snapshot.dt),
            (View::Plot, Some(choice)) => self
                .session
                .plot_series
                .csv_of(choice.x, &self.plot_curves()),
            _ => {
                self.ui.notice = Some(
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
                let source = &self.session.lesson.path;
                // A bundled lesson outside a clone has no file on disk: its compiled-in text.
                let written = crate::lessons::source(source)
                    .map(|(_, text)| text)
                    .ok_or_else(|| format!("cannot read {}", source.display()))
                    .and_then(|text| {
                        edits.write_into(&text, edits.body.unwrap_or(0), source.parent())
                    })
                    .and_then(|text| std::fs::write(&to, text).map_err(|e| e.to_string()))
                    .and_then(|()| crate::scene::load(&to).map_err(|e| e.to_string()));
                self.ui.notice = Some(match written {
                    Ok(_) => format!("wrote {} (tumble check accepts it)", to.display()),
                    Err(e) => format!("could not write {}: {e}", to.display()),
                });
            }
            Effect::WriteCsv { text, to } => {
                let rows = text.lines().count().saturating_sub(1);
                let header = text.lines().next().unwrap_or("").to_string();
                self.ui.notice = Some(match std::fs::write(&to, text) {
                    Ok(()) => format!("wrote {} ({rows} rows: {header})", to.display()),
                    Err(e) => format!("could not write {}: {e}", to.display()),
                });
            }
        }
    }

    /// The page shown asks for a prediction not made yet, of a time still ahead: opens the
    /// prompt (and returns true) instead of running.
    fn ask_prediction(&mut self) -> bool {
        let Some(index) = self.ui.page else {
            return false;
        };
        let Some(predict) = &self.session.lesson.pages[index].predict else {
            return false;
        };
        let ahead =
            self.session.step_count() < crate::live::step_at(predict.at, self.session.snapshot.dt);
        if self.ui.guesses[index] != Guess::Open || !ahead {
            return false;
        }
        self.ui.running = false;
        self.ui.overlay = Overlay::Predict {
            page: index,
            text: String::new(),
        };
        true
    }

    /// The question of page `page`'s prediction: `what will cube.y be at t = 1 s (m)?`.
    pub fn prediction_question(&self, page: usize) -> String {
        match self
            .session
            .lesson
            .pages
            .get(page)
            .and_then(|p| p.predict.as_ref())
        {
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
        let predict = self.session.lesson.pages.get(page)?.predict.as_ref()?;
        let reached =
            self.session.step_count() >= crate::live::step_at(predict.at, self.session.snapshot.dt);
        if !reached {
            return None;
        }
        let value = self.session.live.value(&predict.quantity, predict.at);
        let unit = predict.quantity.measure.unit();
        let simulated = self.session.live.describe(&predict.quantity, predict.at);
        let head = format!("{} at t = {} s", predict.quantity.text, tidy(predict.at));
        Some(match (self.ui.guesses[page], value) {
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
        if let Overlay::Settings(_) = self.ui.overlay {
            self.ui.notice = Some("settings closed: nothing applied".into());
        }
        if let Overlay::Predict { page, .. } = self.ui.overlay {
            self.ui.guesses[page] = Guess::Skipped;
            self.ui.notice = Some("no guess: Enter runs on".into());
        }
        if self.ui.overlay != Overlay::None {
            self.ui.overlay = Overlay::None;
        } else if self.ui.view != View::Loop {
            (self.ui.view.pane().leave)(self);
            self.ui.view = View::Loop;
        } else {
            self.ui.notice = Some("nothing to close: q quits".into());
        }
    }

    /// The file `W` writes: `NAME-edited.toml` in [`Preferences::write_dir`].
    pub fn write_path(&self) -> PathBuf {
        let stem = self
            .session
            .lesson
            .path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        let stem = stem.strip_suffix("-edited").unwrap_or(&stem).to_string();
        self.prefs.write_dir.join(format!("{stem}-edited.toml"))
    }

    /// `W`: the form's values (when it is open and they are valid), else the scene as it runs.
    fn write_scene(&mut self) -> Option<Effect> {
        let edits = match &mut self.ui.overlay {
            Overlay::Settings(form) => match form.edits() {
                Ok(edits) => edits,
                Err(e) => {
                    form.error = Some(e);
                    return None;
                }
            },
            _ => SceneEdits::of_body(&self.session.lesson.scene, self.session.selected),
        };
        // The written file must pass what the loader checks: the same rules here.
        if let Err(e) = edits.apply(&self.session.lesson.scene) {
            match &mut self.ui.overlay {
                Overlay::Settings(form) => form.error = Some(e),
                _ => self.ui.notice = Some(format!("cannot write the scene: {e}")),
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
        let Overlay::Settings(form) = &mut self.ui.overlay else {
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
        match edits.apply(&self.session.lesson.scene) {
            Ok(scene) => {
                let mut lesson = self.session.lesson.clone();
                lesson.scene = scene;
                let selected = self.session.selected;
                self.open(lesson);
                // The body edited stays the one the panels show.
                if selected < self.session.snapshot.bodies.len() {
                    self.session.selected = selected;
                    self.refresh();
                }
                self.ui.notice = Some(format!(
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
        .apply(&self.session.lesson.scene);
        let scene = match scene {
            Ok(scene) => scene,
            Err(e) => {
                if let Overlay::Settings(form) = &mut self.ui.overlay {
                    form.error = Some(e);
                }
                return;
            }
        };
        self.ui.overlay = Overlay::None;
        if tunings.is_empty() {
            self.ui.notice = Some("settings: no value changed".into());
            return;
        }
        // A frame in progress is finished first: the change acts between frames.
        while !self.at_frame_start() && self.session.divergence.is_none() {
            self.step_phase();
        }
        self.before_change();
        // Stepping back stops at the change; the live numbers are simulated again; the ±
        // (its reference ran the old values) is dropped.
        let bars = match self.session.tune(scene, &tunings) {
            Ok(bars) => bars,
            Err(e) => {
                self.ui.notice = Some(format!("settings: {e}"));
                return;
            }
        };
        self.refresh();
        self.ui.notice = Some(format!(
            "applied live ({changes}): the run goes on from t = {} s (, steps back to here, \
             not before){}",
            tidy(self.session.time()),
            if bars { "; u shows the ± again" } else { "" }
        ));
    }

    /// Replaces the lesson, keeping what carries across lessons: the view axis, the numbers'
    /// frame, the trail, the graph view, the compare ghost (when the new scene offers it), the
    /// speed relative to real time, ASCII and timing. The run starts paused at t = 0.
    fn open(&mut self, lesson: Lesson) {
        let compare = self.session.ghost.as_ref().map(|g| g.comparison);
        let real_time = self.frames_per_second() * self.session.snapshot.dt;
        // The quantity graph's quantities are the old scene's: it does not carry over.
        let view = if self.ui.view.pane().carried {
            self.ui.view
        } else {
            View::Loop
        };
        let session = Session::new(lesson, self.session.in_background());
        *self = App::with(session, self.prefs.clone(), compare);
        self.ui.view = view;
        let dt = self.session.snapshot.dt;
        self.ui.speed = (0..SPEEDS.len())
            .min_by(|&a, &b| {
                let off = |i: usize| (SPEEDS[i] * dt / real_time).ln().abs();
                off(a).total_cmp(&off(b))
            })
            .unwrap_or(self.ui.speed);
    }

    /// Goes to time t (rounded to a step): forward from here, or replayed from t = 0 when t is
    /// earlier; paused there. A frame in progress is finished first. With
    /// [`Session::background_jobs`](crate::session::Session::background_jobs) the frames are run by [`App::work`], a slice at a time.
    pub fn jump_to(&mut self, t: f64) {
        self.ui.running = false;
        while !self.at_frame_start() && self.session.divergence.is_none() {
            self.step_phase();
        }
        let target = (t / self.session.snapshot.dt).round() as u64;
        if target < self.session.step_count() {
            self.reset();
        }
        let frames = target - self.session.step_count();
        if frames > MAX_JUMP_FRAMES {
            self.ui.notice = Some(format!(
                "jump: t = {} s is {frames} frames away, more than {MAX_JUMP_FRAMES}: \
                 choose a larger dt (e) or a nearer time",
                tidy(t)
            ));
            return;
        }
        let job = JumpJob {
            from: self.session.step_count(),
            target,
            t,
        };
        if self.session.background_jobs {
            self.ui.notice = Some(self.job_progress(&job));
            self.session.job = Some(job);
            self.work(JOB_SLICE);
            return;
        }
        self.step_frames(frames);
        self.jump_done();
    }

    fn jump_done(&mut self) {
        if self.session.divergence.is_none() {
            self.ui.notice = Some(format!(
                "jumped to t = {} s (step {})",
                tidy(self.session.time()),
                self.session.step_count()
            ));
        }
    }

    /// The status line of a job under way: `jumping to t = 50 s: 12 % (t = 6.03 s) · Esc
    /// cancels, q quits`.
    fn job_progress(&self, job: &JumpJob) -> String {
        let done = self.session.step_count().saturating_sub(job.from);
        let all = job.target.saturating_sub(job.from).max(1);
        format!(
            "jumping to t = {} s: {} % (t = {} s) · Esc cancels, q quits",
            tidy(job.t),
            100 * done / all,
            tidy(self.session.time()),
        )
    }

    /// Runs the job under way (if any) for about `budget` of wall-clock time, in chunks of
    /// frames sized by the measured cost per frame; returns whether work is left. The event
    /// loop calls it between looking at the keys, so a key waits at most one slice.
    pub fn work(&mut self, budget: std::time::Duration) -> bool {
        let start = Instant::now();
        while let Some(job) = self.session.job {
            let left = job.target.saturating_sub(self.session.step_count());
            if left == 0 || self.session.divergence.is_some() {
                self.session.job = None;
                self.jump_done();
                return false;
            }
            // A chunk of about a quarter of the budget at the measured cost per frame.
            let chunk = match self.session.ns_per_step {
                Some(ns) if ns > 0.0 => ((budget.as_secs_f64() * 0.25e9 / ns) as u64).max(1),
                _ => 16,
            };
            self.step_frames(chunk.min(left));
            if start.elapsed() >= budget {
                break;
            }
        }
        match self.session.job {
            Some(job) => {
                self.ui.notice = Some(self.job_progress(&job));
                true
            }
            None => false,
        }
    }

    fn blocked(&mut self) {
        self.ui.running = false;
        self.ui.notice = Some("the simulation diverged: step back (←) or reset (r)".into());
    }

    /// Whether the world sits between two frames.
    fn at_frame_start(&self) -> bool {
        self.session.at_frame_start()
    }

    fn before_change(&mut self) {
        self.session.before_change();
    }

    /// Re-reads the snapshots and keeps the bodies in frame.
    pub(super) fn refresh(&mut self) {
        let shown = self.session.refresh();
        self.ui.region.include(&shown);
        let page = self
            .session
            .lesson
            .page_at(self.session.snapshot.time)
            .map(|(i, _)| i);
        if page != self.ui.page {
            self.ui.page = page;
            self.ui.lesson_scroll = 0;
            self.ui.lesson_hscroll = 0;
        }
    }

    /// Runs up to `frames` whole frames (both worlds); stops at a divergence, or (running,
    /// with [`Ui::pause_at_stops`]) at a page, a prediction or the scene's end.
    pub fn step_frames(&mut self, frames: u64) {
        if self.session.divergence.is_some() {
            self.blocked();
            return;
        }
        let mut cost = 0.0;
        let mut done = 0u64;
        for i in 0..frames {
            if i + 1 == frames {
                self.before_change();
            }
            let run = self.session.step_frame();
            cost += run.cost;
            done += 1;
            if run.notice.is_some() {
                self.ui.notice = run.notice;
            }
            if run.diverged {
                self.ui.running = false;
                break;
            }
            if self.ui.running && self.ui.pause_at_stops && self.pause_here() {
                break;
            }
        }
        // Every run of frames is measured, one frame too: a heavy scene runs one frame per
        // render (`affordable_frames`), and its ns/step must not freeze at the last longer run.
        self.session.measured(cost, done);
        self.refresh();
    }

    /// Pauses the run if it has reached a page, their run's parting or a prediction's time
    /// (the notice says which); returns whether it did.
    fn pause_here(&mut self) -> bool {
        let session = &self.session;
        let stop = timeline::stop_at(&session.lesson, session.snapshot.dt, session.step_count());
        if let Some(stop) = stop.or_else(|| self.against_parts_here()) {
            self.ui.running = false;
            // A prediction due at a page's own time: its comparison comes first.
            self.ui.notice = Some(match self.prediction_reached() {
                Some(result) => format!(
                    "{} · {}",
                    result.trim_end_matches(": Enter continues"),
                    stop.notice
                ),
                None => stop.notice.clone(),
            });
            self.ui.stop = Some(stop);
            return true;
        }
        if let Some(result) = self.prediction_reached() {
            self.ui.running = false;
            self.ui.stop = Some(timeline::Stop {
                label: "prediction".into(),
                notice: result.clone(),
            });
            self.ui.notice = Some(result);
            return true;
        }
        false
    }

    /// The result line of a guessed prediction whose time the run has just reached.
    fn prediction_reached(&self) -> Option<String> {
        let step = self.session.step_count();
        let dt = self.session.snapshot.dt;
        (0..self.session.lesson.pages.len())
            .filter(|&i| matches!(self.ui.guesses[i], Guess::Given(_)))
            .find(|&i| {
                self.session.lesson.pages[i]
                    .predict
                    .as_ref()
                    .is_some_and(|p| crate::live::step_at(p.at, dt) == step)
            })
            .and_then(|i| self.prediction_result(i))
            .map(|r| format!("{r}: Enter continues"))
    }

    /// Runs the next phase (both worlds).
    pub fn step_phase(&mut self) {
        if self.session.divergence.is_some() {
            self.blocked();
            return;
        }
        if let Some(notice) = self.session.step_phase() {
            self.ui.notice = Some(notice);
        }
        if self.session.divergence.is_some() {
            self.ui.running = false;
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
        match self.session.step_back_frames(frames) {
            Err(why) => self.ui.notice = Some(why),
            Ok(()) if frames > 0 => self.refresh(),
            Ok(()) => {}
        }
    }

    /// Back to t = 0 (both worlds), paused; the view region starts over.
    pub fn reset(&mut self) {
        self.session.reset();
        self.ui.running = false;
        self.ui.region = Region::of_world(&self.session.snapshot);
        // The stopwatch's times were of the run replaced: it starts over (shown as it was).
        self.ui.tools.stopwatch = Default::default();
        self.refresh();
    }

    fn next_response(&mut self) {
        if let Some(notice) = self.session.next_response() {
            self.ui.notice = Some(notice);
        }
        // The status bar and the study read the response from the snapshot.
        self.refresh();
    }

    /// The settings the run uses that the lesson's pages were not written for (see
    /// [`Session::page_settings_note`]).
    pub fn page_settings_note(&self) -> Option<String> {
        self.session.page_settings_note()
    }

    /// The comparisons this scene offers, in cycling order (see [`Session::comparisons`]).
    pub fn comparisons(&self) -> Vec<Comparison> {
        self.session.comparisons()
    }

    fn next_compare(&mut self) {
        match self.session.next_comparison() {
            Some(c) => self.start_compare(c),
            None => {
                self.session.stop_compare();
                self.refresh();
            }
        }
    }

    /// Starts a compare world at the current moment (see [`Session::start_compare`]); the
    /// notice says why not, or that the ghost runs the world's own setting.
    pub fn start_compare(&mut self, comparison: Comparison) {
        match self.session.start_compare(comparison) {
            Ok(notice) => {
                if notice.is_some() {
                    self.ui.notice = notice;
                }
                self.refresh();
            }
            Err(why) => self.ui.notice = Some(why),
        }
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
            .position(|(p, _)| p.file_name() == self.session.lesson.path.file_name())
            .unwrap_or(0);
        self.ui.overlay = Overlay::Picker { lessons, selected };
    }

    fn open_selected(&mut self) {
        let Overlay::Picker { lessons, selected } = &self.ui.overlay else {
            return;
        };
        let Some((path, _)) = lessons.get(*selected) else {
            self.ui.overlay = Overlay::None;
            return;
        };
        match crate::lessons::load(path) {
            Ok(lesson) => self.open(lesson),
            Err(e) => {
                self.ui.overlay = Overlay::None;
                self.ui.notice = Some(e.to_string());
            }
        }
    }
}
