//! A lesson's run without a terminal: the world, the compare world (the ghost), the history
//! for stepping back, the series behind the graphs, the live numbers and the background jobs.
//! The terminal app, `tumble shot` and `tumble record` each drive one [`Session`] and draw
//! from its snapshots; nothing here knows a screen, a key or a terminal.

pub mod history;
pub mod plot;
pub mod series;

use crate::live::LiveValues;
use crate::physics::cloth::ClothIntegrator;
use crate::physics::snapshot::Methods;
use crate::physics::{Divergence, Integrator, Phase, Response, Snapshot, World};
use crate::scene::Lesson;
use history::{History, DEFAULT_CAPACITY};
use nalgebra::Vector3;
use plot::PlotSeries;
use series::{graphed_energy, EnergySeries};
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

/// A jump under way: from `from` to `target` (frame counts), asked for time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpJob {
    pub from: u64,
    pub target: u64,
    pub t: f64,
}

/// The settings live numbers were simulated with: they are simulated again when these change
/// (the integrator `i`, the response `c`, a cloth's integrator), so a page never narrates
/// another method's numbers.
type LiveSettings = Methods;

/// Live numbers being simulated on a thread.
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

/// What one frame run by [`Session::step_frame`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameRun {
    /// Wall-clock seconds the world's step took.
    pub cost: f64,
    /// The run stops here: the world diverged and no ghost took its place.
    pub diverged: bool,
    /// What the user should be told (the ghost diverged, or took the world's place).
    pub notice: Option<String>,
}

/// A lesson's run: what the app, `shot` and `record` share.
#[derive(Debug, Clone)]
pub struct Session {
    pub lesson: Lesson,
    pub world: World,
    /// The snapshot of the world now, of body [`Session::selected`]: what every pane reads.
    pub snapshot: Snapshot,
    /// The snapshot before the last action (changed cells are highlighted).
    pub previous: Option<Snapshot>,
    /// The body the snapshot's panels describe (Tab picks the next one).
    pub selected: usize,
    pub ghost: Option<Ghost>,
    pub history: History,
    pub series: EnergySeries,
    /// Every plottable quantity over the run.
    pub plot_series: PlotSeries,
    pub divergence: Option<Divergence>,
    /// The values of the pages' live numbers and predictions (see [`crate::live`]), simulated
    /// when the lesson is opened and when a setting they depend on changes; never per frame.
    pub live: std::sync::Arc<LiveValues>,
    live_settings: LiveSettings,
    /// The thread simulating them, when computed in the background: its result, and the flag
    /// that tells it its values went stale.
    live_job: Option<std::rc::Rc<LiveJob>>,
    /// Live numbers are simulated on a thread (the terminal app), not before the first frame.
    live_in_background: bool,
    /// Measured physics cost, ns per frame (all four phases), when running.
    pub ns_per_step: Option<f64>,
    /// The measured error under each number: a reference run that follows the world.
    pub error_bars: Option<crate::error_bars::Follow>,
    /// The study of this scene, once asked for; it runs on its own thread.
    pub study: Option<crate::study::background::Job>,
    /// A jump under way, run a slice at a time by the app's event loop.
    pub job: Option<JumpJob>,
    /// Jumps run as jobs a slice at a time (the terminal app), or at once (tests, `shot`,
    /// `record`: one call, one result).
    pub background_jobs: bool,
}

impl Session {
    /// A lesson at t = 0; live numbers simulated here, or on a thread (`live_in_background`).
    pub fn new(lesson: Lesson, live_in_background: bool) -> Session {
        let world = lesson.scene.world();
        let snapshot = world.snapshot();
        let series = EnergySeries::new(&snapshot, lesson.scene.duration);
        let plot_series = PlotSeries::new(&snapshot);
        let live_settings = LiveSettings::of(&world);
        let mut session = Session {
            lesson,
            world,
            snapshot,
            previous: None,
            selected: 0,
            ghost: None,
            history: History::new(DEFAULT_CAPACITY),
            series,
            plot_series,
            divergence: None,
            live: std::sync::Arc::new(LiveValues::computing()),
            live_settings,
            live_job: None,
            live_in_background,
            ns_per_step: None,
            error_bars: None,
            study: None,
            job: None,
            background_jobs: live_in_background,
        };
        session.start_live(session.world.clone());
        session
    }

    /// Whether live numbers and jobs run in the background (the terminal app).
    pub fn in_background(&self) -> bool {
        self.live_in_background
    }

    /// Simulates the live numbers from `world` (at t = 0): here, or on a thread.
    pub fn start_live(&mut self, world: World) {
        if !self.live_in_background {
            self.live = std::sync::Arc::new(LiveValues::compute(&self.lesson, world));
            return;
        }
        let (send, result) = std::sync::mpsc::channel();
        let cancel = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let (lesson, stop) = (self.lesson.clone(), cancel.clone());
        std::thread::spawn(move || {
            if let Some(values) = LiveValues::compute_unless(&lesson, world, &stop) {
                // The session may be gone, or want newer values: then nobody reads this.
                let _ = send.send(values);
            }
        });
        // The old job, if any, is dropped (with the last copy of the session holding it):
        // told to stop.
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

    /// The world's completed frames now: current inside a run of frames too, where the
    /// snapshot is read again only at the run's end (see [`Session::refresh`]).
    pub fn step_count(&self) -> u64 {
        self.world.step_count()
    }

    /// Simulated time now, t = step·dt, s (current as [`Session::step_count`]).
    pub fn time(&self) -> f64 {
        self.world.time()
    }

    /// The measured error (±) under each number on or off: a reference run that follows the
    /// world from here (see [`crate::error_bars`]). The snapshot is not re-read.
    pub fn toggle_error_bars(&mut self) {
        self.error_bars = match self.error_bars {
            Some(_) => None,
            None => Some(crate::error_bars::Follow::new(
                &self.lesson.scene,
                &self.world,
            )),
        };
    }

    /// Continuous values (g, drag, e, μ, a spring's k, a motor's speed) changed where the run
    /// is ([`World::tune`]), in both worlds, between frames; the lesson's scene becomes `scene`
    /// (a reset keeps them). Frames before the change could only be replayed with the new
    /// values (a keyframe keeps the state, not g, k or a motor's speed): stepping back stops
    /// here. The pages' live numbers are simulated again; the ± (its reference ran the old
    /// values) is dropped: Ok(true) when it was shown. Err: the first value the world refused
    /// (those before it are kept; nothing else changes). The snapshot is not re-read.
    pub fn tune(
        &mut self,
        scene: crate::scene::Scene,
        tunings: &[crate::physics::Tuning],
    ) -> Result<bool, String> {
        for &tuning in tunings {
            self.world.tune(tuning)?;
            if let Some(ghost) = &mut self.ghost {
                ghost.world.tune(tuning).ok();
            }
        }
        self.lesson.scene = scene;
        self.history.clear();
        self.start_live(self.lesson.scene.world());
        Ok(self.error_bars.take().is_some())
    }

    /// Whether the world sits between two frames.
    pub fn at_frame_start(&self) -> bool {
        matches!(self.world.last_phase(), None | Some(Phase::Collide))
    }

    /// The hand on both worlds (the compare world is pulled the same way), from the next frame
    /// on; the snapshots show it at once. Stepping back rebuilds frames from keyframes by
    /// stepping them again, which cannot know where the pointer was: the next frame start is
    /// kept whole (and while a body is held, every one), so no frame the hand pulled is ever
    /// replayed, and none it did not is replayed with it.
    pub fn set_hand(&mut self, hand: Option<crate::physics::hand::Hand>) {
        self.history.break_segment();
        self.world.set_hand(hand);
        self.snapshot.hand = self.world.hand().copied();
        self.snapshot.hand_pull = self.world.hand_pull();
        if let Some(ghost) = &mut self.ghost {
            ghost.world.set_hand(hand);
            ghost.snapshot.hand = ghost.world.hand().copied();
            ghost.snapshot.hand_pull = ghost.world.hand_pull();
        }
    }

    /// Keeps the snapshot now as the one before the next action.
    pub fn before_change(&mut self) {
        self.previous = Some(self.snapshot.clone());
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

    /// Re-reads the snapshots (the live numbers simulated again if a setting they depend on
    /// changed); returns the points the view must keep in frame.
    pub fn refresh(&mut self) -> Vec<Vector3<f64>> {
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
        shown
    }

    /// Checks both worlds after a frame. A compare world that diverges is frozen there and
    /// marked (the run goes on); when the world itself diverges beside a compare world that
    /// has not, the two trade places (the run follows the one still running, the diverged one
    /// stays as the frozen ghost). Only when nothing runs on does it return true (the run
    /// pauses). The notice says what happened.
    fn check_divergence(&mut self, notice: &mut Option<String>) -> bool {
        if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
            if let Some(d) = ghost.world.divergence() {
                *notice = Some(format!(
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
        if healthy {
            if let Some(swapped) = self.swap_with_ghost(&d) {
                *notice = Some(swapped);
                return false;
            }
        }
        self.divergence = Some(d);
        true
    }

    /// The world diverged (`d`) and the compare world has not: they trade places, so the run
    /// follows the compare world and the diverged world is the frozen ghost. The ghost's
    /// comparison becomes the diverged world's setting. None when the settings cannot be told
    /// apart by one comparison (then nothing changes).
    fn swap_with_ghost(&mut self, d: &Divergence) -> Option<String> {
        let ghost = self.ghost.as_mut()?;
        let own = match ghost.comparison {
            Comparison::Integrator(_) => Comparison::Integrator(self.world.integrator()),
            Comparison::Response(_) => Comparison::Response(self.world.contact_model()?.response),
            Comparison::ClothIntegrator(_) => {
                Comparison::ClothIntegrator(*Methods::of(&self.world).cloths.first()?)
            }
        };
        let running = ghost.comparison;
        std::mem::swap(&mut self.world, &mut ghost.world);
        ghost.comparison = own;
        ghost.diverged = Some(d.clone());
        self.history.swap_worlds();
        Some(format!(
            "{} diverged at step {} ({}): the run follows the ghost ({}) now, the diverged \
             world stays frozen as the ghost",
            own.name(),
            d.step,
            d.quantity,
            running.name()
        ))
    }

    /// Records the frame just finished in the energy series and the plot's.
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

    /// Runs one whole frame (both worlds), recorded in the history and the series; the
    /// snapshots are not re-read (see [`Session::refresh`]).
    pub fn step_frame(&mut self) -> FrameRun {
        self.remember();
        let start = Instant::now();
        self.world.step();
        let cost = start.elapsed().as_secs_f64();
        if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
            ghost.world.step();
        }
        self.record_frame();
        let mut notice = None;
        let diverged = self.check_divergence(&mut notice);
        FrameRun {
            cost,
            diverged,
            notice,
        }
    }

    /// Folds a run of `frames` frames that cost `cost` s into the measured ns per frame.
    pub fn measured(&mut self, cost: f64, frames: u64) {
        if frames > 0 {
            let ns = cost * 1e9 / frames as f64;
            self.ns_per_step = Some(match self.ns_per_step {
                Some(old) => 0.8 * old + 0.2 * ns,
                None => ns,
            });
        }
    }

    /// Runs the next phase (both worlds); the notice says what a divergence did.
    pub fn step_phase(&mut self) -> Option<String> {
        self.before_change();
        self.remember();
        let phase = self.world.step_phase();
        if let Some(ghost) = self.ghost.as_mut().filter(|g| g.diverged.is_none()) {
            ghost.world.step_phase();
        }
        let mut notice = None;
        if phase == Phase::Collide {
            self.record_frame();
            self.check_divergence(&mut notice);
        }
        notice
    }

    /// `frames` steps back at once (at most to the oldest frame kept); with cloths this costs
    /// one replay from a keyframe, not `frames` of them. Err when no earlier frame is kept.
    pub fn step_back_frames(&mut self, frames: usize) -> Result<(), String> {
        if self.history.is_empty() {
            return Err("no earlier frame kept".into());
        }
        if frames == 0 {
            return Ok(());
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
        Ok(())
    }

    /// Back to t = 0 (both worlds); the series start over.
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
        self.snapshot = self.world.snapshot_of(self.selected);
        self.series = EnergySeries::new(&self.snapshot, self.lesson.scene.duration);
        self.plot_series = PlotSeries::new(&self.snapshot);
    }

    /// The next collision response the scene's rules allow; the notice says why one was
    /// skipped, or why there is none.
    pub fn next_response(&mut self) -> Option<String> {
        match self.world.contact_model().copied() {
            Some(_)
                if self.world.body_count() == 0 && Methods::of(&self.world).cloths.is_empty() =>
            {
                Some("nothing in this scene can touch: no body, no particle".into())
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
                if model.response != start {
                    self.world.set_contact_model(model);
                }
                refused.map(|why| format!("skipped: {why}"))
            }
            None => Some("no obstacles in this scene: no collision response".into()),
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
        for (a, b) in scene.cloths.iter().zip(Methods::of(&self.world).cloths) {
            if a.integrator != b {
                own.push(a.integrator.name());
                now.push(b.name());
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
    pub fn rules_with(&self, response: Response) -> Result<(), String> {
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

    /// Starts a compare world at the current moment: a copy of the world with `comparison`
    /// applied at the start of the current frame, brought to the same phase. Err: why not
    /// (nothing changes); Ok with a notice when the ghost runs the world's own setting.
    pub fn start_compare(&mut self, comparison: Comparison) -> Result<Option<String>, String> {
        let missing = match comparison {
            Comparison::Response(_) if self.world.contact_model().is_none() => Some("obstacles"),
            Comparison::Integrator(_) | Comparison::Response(_) if self.world.body_count() == 0 => {
                Some("bodies")
            }
            Comparison::ClothIntegrator(_) if Methods::of(&self.world).cloths.is_empty() => {
                Some("cloths")
            }
            _ => None,
        };
        if let Some(missing) = missing {
            return Err(format!(
                "no {missing} in this scene: nothing to compare with `{}`",
                comparison.name()
            ));
        }
        if let Comparison::Response(response) = comparison {
            self.rules_with(response)
                .map_err(|why| format!("no ghost: {why}"))?;
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
        let notice = same.then(|| {
            format!(
                "the ghost runs `{}` too: press k for another",
                comparison.name()
            )
        });
        let snapshot = world.snapshot();
        let diverged = world.divergence();
        self.ghost = Some(Ghost {
            comparison,
            world,
            snapshot,
            diverged,
        });
        self.history.break_segment();
        Ok(notice)
    }

    /// The next comparison of [`Session::comparisons`] (None: compare mode ends).
    pub fn next_comparison(&self) -> Option<Comparison> {
        let list = self.comparisons();
        match &self.ghost {
            None => list.first().copied(),
            Some(g) => list
                .iter()
                .position(|&c| c == g.comparison)
                .and_then(|i| list.get(i + 1).copied()),
        }
    }

    /// Ends compare mode.
    pub fn stop_compare(&mut self) {
        self.ghost = None;
        self.history.break_segment();
        self.before_change();
    }

    /// The next body integrator (or, cloths only, the next particle integrator of every
    /// cloth), for the world from the next frame on.
    pub fn next_integrator(&mut self) {
        self.before_change();
        if self.world.body_count() == 0 {
            let next = Methods::of(&self.world)
                .cloths
                .first()
                .map_or(ClothIntegrator::SymplecticEuler, |c| c.next());
            apply(&mut self.world, Comparison::ClothIntegrator(next));
            // Replay from an earlier keyframe would step the old integrator.
            self.history.break_segment();
        } else {
            let next = self.world.integrator().next();
            self.world.set_integrator(next);
        }
    }

    /// The hand takes body `index` at world point `grabbed` (None when the body is fixed).
    pub fn grab(
        &mut self,
        index: usize,
        grabbed: Vector3<f64>,
    ) -> Option<crate::physics::hand::Hand> {
        let body = &self.world.bodies()[index];
        if body.fixed {
            return None;
        }
        let state = self.world.states()[index];
        Some(crate::physics::hand::Hand::new(
            index,
            body,
            &state,
            grabbed,
            grabbed,
            self.world.dt(),
        ))
    }
}

/// Whether every cloth of the world runs `integrator` already (true without cloths).
fn same_cloth_integrator(world: &World, integrator: ClothIntegrator) -> bool {
    Methods::of(world).cloths.iter().all(|&c| c == integrator)
}

/// Applies a comparison to a world.
pub fn apply(world: &mut World, comparison: Comparison) {
    match comparison {
        Comparison::Integrator(i) => world.set_integrator(i),
        Comparison::ClothIntegrator(c) => {
            for i in 0..Methods::of(world).cloths.len() {
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

/// What the view keeps in frame: every body's vertices, every cloth's particles, every
/// joint's anchors and every spring's ends.
pub fn shown_points(snapshot: &Snapshot) -> Vec<Vector3<f64>> {
    let mut points: Vec<Vector3<f64>> = snapshot
        .bodies
        .iter()
        .flat_map(|b| b.vertices.iter().copied())
        .collect();
    // A round body has no vertices: its extreme points along the world axes.
    for body in &snapshot.bodies {
        if body.points_body.is_empty() && body.shape.is_some() {
            for axis in [Vector3::x(), Vector3::y(), Vector3::z()] {
                points.push(body.position + axis * body.radius);
                points.push(body.position - axis * body.radius);
            }
        }
    }
    for c in &snapshot.cloths {
        points.extend_from_slice(&c.positions);
    }
    // The joints' anchors and the springs' ends (a pendulum's pivot is in no body).
    for j in &snapshot.joints {
        points.extend(j.anchors);
    }
    for s in &snapshot.springs {
        points.extend(s.ends);
    }
    points
}
