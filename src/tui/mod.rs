//! The terminal app (ratatui + crossterm): step the animation loop phase by phase and watch the
//! body and its numbers.
//!
//! A thin state machine over the simulation. [`App`] holds the state; a key becomes a
//! [`keys::Message`] through the one key table, [`App::update`] applies it, and `&App` is a
//! widget (`screen.rs`) drawn from the world's snapshots — no physics is recomputed here.
//!
//! | file | what it shows or does |
//! |---|---|
//! | `app` | state and update |
//! | `keys` | the key table (status-bar hints and help overlay) |
//! | `history` | the ring of saved frames for stepping back |
//! | `series` | the energy series behind the graph |
//! | `plot` | every plottable quantity over the run, the quantity graph's choice and its CSV |
//! | `viewport` | view axis, region kept in frame, cell mapping |
//! | `layout` | where each pane goes (key `L`: all numbers, or a large drawing) |
//! | `theme` | every colour and text style |
//! | `export` | the screen as SVG (key `x`, `tumble shot`) and a run as asciicast (`tumble record`) |
//! | `screen` | the whole screen, overlays, the "enlarge" message |
//! | `header`, `status_bar` | top line; bottom lines |
//! | `views` | the view table: each view's key, render function, what showing and leaving it do |
//! | `panes` | the pane table: each box of the loop view, where it goes (the layout's area, or cut from one), what draws it |
//! | `loop_view`, `energy_view`, `study_view` | the views (one file each; `energy_view` draws either graph) |
//! | `projection`, `panels`, `cloth_panel`, `loop_strip`, `lesson_pane`, `energy_graph`, `plot_graph` | the panes |
//! | `help`, `picker`, `plot_picker`, `divergence_dialog` | the overlays |
//! | `settings_form`, `settings_view` | the settings form (`e`): its state; its overlay |
//! | `jump_prompt`, `timeline` | the jump prompt (`J`); where a run pauses by itself |
//! | `tools` | the measuring tools (`w` `o` `O` `T` `m` `M` `A` `V`): state, keys, readout panels |
//! | `mouse` | select, pull (the hand), zoom, graph a panel row: mouse events as messages |
//!
//! When paused the app blocks on input; when running it advances on a fixed dt, as many frames
//! as the chosen speed asks for since the last render (at most [`MAX_FRAMES_PER_RENDER`], and
//! at most [`MAX_STEP_TIME_PER_RENDER`] of measured physics: a heavy scene runs slower than
//! asked rather than freeze the screen).

pub mod against;
pub mod app;
pub mod cloth_panel;
pub mod divergence_dialog;
pub mod energy_bars;
pub mod energy_graph;
pub mod energy_view;
pub mod export;
pub mod header;
pub mod help;
pub mod jump_prompt;
pub mod keys;
pub mod layout;
pub mod lesson_pane;
pub mod loop_strip;
pub mod loop_view;
pub mod mouse;
pub mod panels;
pub mod panes;
pub mod period_timer;
pub mod picker;
pub mod plot_graph;
pub mod plot_picker;
pub mod projection;
pub mod screen;
pub mod settings_form;
pub mod settings_view;
pub mod status_bar;
pub mod study_view;
pub mod theme;
pub mod timeline;
pub mod tools;
pub mod viewport;
pub mod views;

pub use crate::session::{history, plot, series};
pub use against::Against;
pub use app::{App, Comparison, Effect, Options, Overlay, View};

use crate::scene::Lesson;
use crossterm::event::{self, Event};
use ratatui::DefaultTerminal;
use std::time::{Duration, Instant};

/// Time between renders while running.
pub const RENDER_INTERVAL: Duration = Duration::from_millis(33);
/// Most frames simulated per render; beyond that the simulation falls behind the clock.
pub const MAX_FRAMES_PER_RENDER: u64 = 5_000;

/// Most physics time between two renders while running: a scene whose frames cost more than
/// the clock gives them falls behind real time rather than leave keys and screen waiting.
pub const MAX_STEP_TIME_PER_RENDER: Duration = Duration::from_millis(50);

/// How many frames fit in [`MAX_STEP_TIME_PER_RENDER`] at the measured cost per frame (at
/// least one; unbounded before anything is measured).
pub fn affordable_frames(ns_per_step: Option<f64>) -> u64 {
    match ns_per_step {
        Some(ns) if ns > 0.0 => {
            let budget = MAX_STEP_TIME_PER_RENDER.as_secs_f64() * 1e9;
            ((budget / ns).floor() as u64).max(1)
        }
        _ => MAX_FRAMES_PER_RENDER,
    }
}

/// Runs the app on the terminal until the user quits; the terminal is always restored.
pub fn run(lesson: Lesson, options: Options) -> std::io::Result<()> {
    run_against(lesson, options, None)
}

/// [`run`] with their run drawn as the ghost (`tumble FILE --against THEIRS.csv`).
pub fn run_against(
    lesson: Lesson,
    options: Options,
    against: Option<Against>,
) -> std::io::Result<()> {
    let mut app = App::interactive(lesson, options);
    app.ui.against = against;
    let terminal = ratatui::init();
    let capture = MouseCapture::enable();
    let result = event_loop(terminal, &mut app);
    drop(capture);
    ratatui::restore();
    result
}

/// Mouse capture while the app runs: disabled again when dropped, and by the panic hook
/// (before ratatui's, which restores the rest of the terminal), so a shell never inherits it.
struct MouseCapture;

impl MouseCapture {
    fn enable() -> MouseCapture {
        static HOOK: std::sync::Once = std::sync::Once::new();
        HOOK.call_once(|| {
            let previous = std::panic::take_hook();
            std::panic::set_hook(Box::new(move |info| {
                disable_mouse_capture();
                previous(info);
            }));
        });
        // A terminal without mouse support still runs the app, by keys.
        let _ = crossterm::execute!(std::io::stdout(), crossterm::event::EnableMouseCapture);
        MouseCapture
    }
}

impl Drop for MouseCapture {
    fn drop(&mut self) {
        disable_mouse_capture();
    }
}

fn disable_mouse_capture() {
    let _ = crossterm::execute!(std::io::stdout(), crossterm::event::DisableMouseCapture);
}

fn handle(app: &mut App, event: Event) {
    match event {
        Event::Key(key) => app.handle_key(&key),
        Event::Mouse(mouse) => app.handle_mouse(&mouse),
        // Resize: the next draw uses the new size.
        _ => {}
    }
}

fn event_loop(mut terminal: DefaultTerminal, app: &mut App) -> std::io::Result<()> {
    let mut last = Instant::now();
    let mut pending = 0.0_f64;
    // Wall-clock measure of the simulated time run (the header's ×real time when the
    // physics cannot keep up): a window of at least a second, started over at each pause.
    let mut window: Option<(Instant, f64)> = None;
    loop {
        app.poll_study();
        app.poll_live();
        // A jump under way runs a slice, then the screen and the keys have their turn.
        app.work(app::JOB_SLICE);
        if app.ui.export_requested {
            app.ui.export_requested = false;
            let size = terminal.size()?;
            app.ui.notice = Some(export::save_screen(app, size.width, size.height));
        }
        terminal.draw(|frame| frame.render_widget(&*app, frame.area()))?;
        if app.ui.quit {
            return Ok(());
        }
        if !app.ui.running {
            // Paused: block until something happens (or, while a study runs, until its
            // progress is worth redrawing).
            let waiting = app.study_running() || app.live_pending();
            if app.session.job.is_some() {
                if !event::poll(Duration::ZERO)? {
                    continue;
                }
            } else if waiting && !event::poll(RENDER_INTERVAL * 3)? {
                continue;
            }
            handle(app, event::read()?);
            last = Instant::now();
            pending = 0.0;
            window = None;
            app.ui.measured_real_time = None;
            continue;
        }
        let deadline = Instant::now() + RENDER_INTERVAL;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() || !event::poll(left)? {
                break;
            }
            handle(app, event::read()?);
            if app.ui.quit || !app.ui.running {
                break;
            }
        }
        if !app.ui.running {
            continue;
        }
        let now = Instant::now();
        pending += now.duration_since(last).as_secs_f64() * app.frames_per_second();
        last = now;
        let frames = (pending.floor() as u64).min(MAX_FRAMES_PER_RENDER);
        pending -= frames as f64;
        if pending > MAX_FRAMES_PER_RENDER as f64 {
            pending = 0.0; // too slow to keep up: drop the backlog rather than stall
        }
        // A heavy scene (a large cloth) must not freeze the screen: at most
        // MAX_STEP_TIME_PER_RENDER of physics between renders, the backlog dropped.
        let affordable = affordable_frames(app.session.ns_per_step);
        let frames = if frames > affordable {
            pending = 0.0;
            affordable
        } else {
            frames
        };
        if frames > 0 {
            app.step_frames(frames);
        }
        let (start, simulated) = *window.get_or_insert((now, app.session.snapshot.time));
        let wall = now.duration_since(start).as_secs_f64();
        if wall >= 1.0 {
            app.ui.measured_real_time = Some((app.session.snapshot.time - simulated) / wall);
            window = Some((now, app.session.snapshot.time));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_render_affords_the_frames_that_fit_in_its_physics_budget() {
        // 50 ms per render: at 1.25 ms per frame (a 30 × 30 implicit sheet), 40 frames; at
        // 1 µs, 50 000 (the cap MAX_FRAMES_PER_RENDER applies separately); a frame slower
        // than the budget still runs, one per render; nothing measured yet: no bound.
        assert_eq!(affordable_frames(Some(1.25e6)), 40);
        assert_eq!(affordable_frames(Some(1e3)), 50_000);
        assert_eq!(affordable_frames(Some(1e9)), 1);
        assert_eq!(affordable_frames(None), MAX_FRAMES_PER_RENDER);
    }
}
