//! The app's study view (key `s`): the study runs on its own thread while the app stays usable,
//! the view can be left and re-entered, and the finished chart shows every integrator. Content
//! checks only: the cost axis is measured time, so no snapshot of it can be deterministic.
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::path::Path;
use std::time::{Duration, Instant};
use tumble::physics::Integrator;
use tumble::tui::{App, Options, View};

fn app(name: &str) -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    let lesson = tumble::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    App::new(
        lesson,
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    )
}

fn press(app: &mut App, code: KeyCode) {
    app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
}

fn screen(app: &App, width: u16, height: u16) -> String {
    let mut terminal = Terminal::new(TestBackend::new(width, height)).unwrap();
    terminal.draw(|f| f.render_widget(app, f.area())).unwrap();
    let buf = terminal.backend().buffer();
    (0..buf.area.height)
        .map(|y| {
            (0..buf.area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn wait_for_study(app: &mut App) {
    let started = Instant::now();
    while app.study_running() {
        app.poll_study();
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "the study never finished"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    app.poll_study();
}

#[test]
fn the_study_runs_in_the_background_while_the_app_keeps_working() {
    let mut app = app("study/short-tumble.toml");
    assert!(app.session.study.is_none(), "nothing is studied before `s`");
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.ui.view, View::Study);
    let job = app.session.study.clone().expect("`s` starts a study");
    assert_eq!(
        job.progress().1,
        Integrator::ALL.len() * 4,
        "every integrator × 4 time steps"
    );
    // The first frame is drawn at once (progress or, on a fast machine, the finished chart).
    let first = screen(&app, 120, 40);
    assert!(first.contains("study of short-tumble"), "{first}");

    // The rest of the app answers meanwhile: a frame steps, another view opens.
    press(&mut app, KeyCode::Right);
    assert_eq!(
        app.session.snapshot.step, 1,
        "stepping works while the study runs"
    );
    press(&mut app, KeyCode::Char('g'));
    assert_eq!(
        app.ui.view,
        View::Energy,
        "the study view can be left while it runs"
    );
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.ui.view, View::Study);
    assert_eq!(
        app.session.study.as_ref().map(|j| j.name.clone()),
        Some(job.name.clone())
    );
    assert!(
        !app.study_running() || app.session.study.as_ref().unwrap().progress().0 <= 20,
        "re-entering keeps the same study"
    );

    wait_for_study(&mut app);
    let result = app
        .session
        .study
        .as_ref()
        .unwrap()
        .result()
        .expect("a finished study");
    assert_eq!(result.rows.len(), Integrator::ALL.len() * 4);
    let shown = screen(&app, 160, 50);
    assert!(shown.contains("error against cost, log–log"), "{shown}");
    assert!(shown.contains("error against dt: slope = p"), "{shown}");
    assert!(
        shown.contains("To keep the error under 1e-6 rad over 0.2 s"),
        "{shown}"
    );
    // The fitted order beside each integrator that has one (rk4 on a tumble: about 4).
    assert!(shown.contains("── rk4 (in use) p 4."), "{shown}");
    for integrator in Integrator::ALL {
        assert!(
            shown.contains(integrator.name()),
            "legend lacks {}:\n{shown}",
            integrator.name()
        );
    }
    // `s` again goes back to the loop view; the finished study is kept for next time.
    press(&mut app, KeyCode::Char('s'));
    assert_eq!(app.ui.view, View::Loop);
    assert!(app.session.study.as_ref().unwrap().result().is_some());
    // The small terminal still renders the view.
    press(&mut app, KeyCode::Char('s'));
    let small = screen(&app, 80, 24);
    assert!(small.contains("study of short-tumble"), "{small}");
}

#[test]
fn the_study_follows_the_response_in_use_and_blames_it_when_every_integrator_diverges() {
    // Lesson 5 starts with the report's `seed` response: every run of its study diverges (as
    // `tumble study 05-ground-collision` shows), and the view says the response is the cause
    // instead of blaming each integrator. After `c` (seed → impulse), entering the view again
    // studies the new response.
    let lesson = tumble::lessons::load(Path::new("05-ground-collision")).unwrap();
    let mut app = App::new(
        lesson,
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    press(&mut app, KeyCode::Char('s'));
    let first = app.session.study.clone().expect("a study started");
    assert_eq!(first.response, Some(tumble::physics::Response::Seed));
    wait_for_study(&mut app);
    let shown = screen(&app, 160, 50);
    for expected in [
        "Every integrator diverges at every time step with the `seed` collision response",
        "the response, not the integration, is the cause",
        "press c for another collision response",
    ] {
        assert!(
            shown.contains(expected),
            "missing `{expected}` in:\n{shown}"
        );
    }
    press(&mut app, KeyCode::Char('s')); // leave the view
    press(&mut app, KeyCode::Char('c')); // seed → impulse
    press(&mut app, KeyCode::Char('s')); // the study is made again, with impulse
    let job = app.session.study.clone().unwrap();
    assert_eq!(job.response, Some(tumble::physics::Response::Impulse));
    press(&mut app, KeyCode::Char('s'));
    press(&mut app, KeyCode::Char('s')); // re-entering with the same response keeps the study
    assert!(job.same(app.session.study.as_ref().unwrap()));
}

#[test]
fn the_chart_marks_the_integrator_in_use() {
    let mut app = app("study/short-tumble.toml");
    press(&mut app, KeyCode::Char('s'));
    wait_for_study(&mut app);
    let in_use = app.session.world.integrator().name();
    let shown = screen(&app, 160, 50);
    assert!(
        shown.contains(&format!("{in_use} (in use)")),
        "no `(in use)` mark in:\n{shown}"
    );
    assert!(
        shown.contains(&format!("in use: {in_use} at dt = ")),
        "{shown}"
    );
}

#[test]
fn a_scene_with_a_cloth_shows_the_cloth_case() {
    // A cube on a 3 × 3 trampoline: the study sweeps the particle integrators (the cube keeps
    // rk4) and the chart has one line per particle integrator.
    let mut app = app("cloth/cube-on-sheet.toml");
    press(&mut app, KeyCode::Char('s'));
    wait_for_study(&mut app);
    let text = screen(&app, 140, 40);
    assert!(text.contains("cloth case"), "{text}");
    assert!(text.contains("── symplectic-euler"), "{text}");
    assert!(text.contains("── implicit-euler"), "{text}");
    assert!(text.contains("Explicit limit 2/ω_max ="), "{text}");
}

#[test]
fn esc_cancels_a_heavy_study_and_its_thread_ends_and_q_quits_meanwhile() {
    // Lesson 38: a 16-body tower over 12 s; its study (every integrator down to dt = 1e-4,
    // then the contact solvers) is minutes of stepping.
    let lesson = tumble::lessons::load(Path::new("38-a-tower-that-buckles"))
        .unwrap_or_else(|e| panic!("{e}"));
    let options = || Options {
        ascii: true,
        compare: None,
        show_timing: false,
    };
    let mut app = App::new(lesson.clone(), options());
    press(&mut app, KeyCode::Char('s'));
    let job = app.session.study.clone().expect("`s` starts a study");
    let runs = Integrator::ALL.len() * 4 + tumble::study::contact::solvers().len();
    assert_eq!(job.progress(), (0, runs), "nothing done yet");
    // The progress is on the screen: runs done of all (the reference comes first).
    let shown = screen(&app, 120, 40);
    assert!(shown.contains(&format!("0 of {runs} runs")), "{shown}");
    assert!(shown.contains("Esc leaves it and"), "{shown}");
    // After its first second the gauge estimates the time left (the reference's and every
    // run's steps at the pace measured so far).
    let started = Instant::now();
    while job.time_left().is_none() {
        assert!(started.elapsed() < Duration::from_secs(60), "no estimate");
        std::thread::sleep(Duration::from_millis(50));
        app.poll_study();
    }
    let shown = screen(&app, 120, 40);
    assert!(shown.contains(" runs · about "), "{shown}");
    assert!(shown.contains(" left"), "{shown}");
    // Every key answers meanwhile.
    press(&mut app, KeyCode::Right);
    assert_eq!(
        app.session.snapshot.step, 1,
        "stepping works while the study runs"
    );
    app.poll_study();
    assert!(app.study_running(), "not done in a moment");
    // Esc: the view closes, the study is cancelled and forgotten, its thread ends.
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.ui.view, View::Loop);
    assert!(app.session.study.is_none(), "the study is dropped");
    assert!(job.cancelled());
    job.join();
    assert!(job.ended(), "the study thread ended after the cancel");
    job.poll();
    assert!(!job.failed() && job.result().is_none());
    assert_eq!(
        app.ui.notice.as_deref(),
        Some("study cancelled: s starts it again")
    );

    // q while a study runs: quits in the same call, and the study's thread stops.
    let mut app = App::new(lesson, options());
    press(&mut app, KeyCode::Char('s'));
    let job = app.session.study.clone().unwrap();
    press(&mut app, KeyCode::Char('q'));
    assert!(app.ui.quit);
    assert!(job.cancelled());
    job.join();
    assert!(job.ended());
}

#[test]
fn the_progress_label_gives_the_time_left_while_runs_are_left() {
    use tumble::tui::study_view::progress_label;
    let s = Duration::from_secs;
    assert_eq!(progress_label(0, 36, None), "0 of 36 runs");
    assert_eq!(
        progress_label(5, 36, Some(s(200))),
        "5 of 36 runs · about 3 min 20 s left"
    );
    assert_eq!(
        progress_label(35, 36, Some(s(42))),
        "35 of 36 runs · about 42 s left"
    );
    assert_eq!(progress_label(36, 36, Some(s(0))), "36 of 36 runs");
}

/// The study of a spring (ω = 10 rad/s, under gravity, 2 s) by every integrator at dt = 1e-1 …
/// 1e-4, untimed, its cost made deterministic: each integrator's force evaluations per step
/// (euler-seed, euler, symplectic-euler 1; splitting, exact-splitting 2; rk4 4; exact-splitting-4 6) ×
/// 100 ns, per simulated second. Euler at 0.1 s diverges (its energy doubles every step,
/// 1 + (ω dt)²), rk4 and exact-splitting-4 reach the floor at the finest steps.
fn spring_study() -> tumble::study::SceneStudy {
    use tumble::study::{self, Case, Config, Timing};
    let scene = tumble::scene::parse(
        r#"title = "spring"
[scene]
dt = 0.001
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
[body]
name = "block"
shape = "box"
size = [0.1, 0.1, 0.1]
mass = 1.0
position = [0.0, 0.0, 0.0]
[[spring]]
bodies = ["block"]
anchors = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
stiffness = 100.0
rest_length = 0.5
"#,
        Path::new("spring.toml"),
    )
    .unwrap()
    .scene;
    let case = Case {
        name: "spring".into(),
        description: "a block on a spring".into(),
        scene,
        duration: 2.0,
    };
    let config = Config {
        integrators: Integrator::ALL.to_vec(),
        dts: vec![1e-1, 1e-2, 1e-3, 1e-4],
        timing: Timing {
            repeats: 0,
            sample_interval: 0.1,
        },
        target_error: 1e-6,
    };
    let mut study = study::study_case(&case, &config, &mut |_, _| {});
    for row in &mut study.rows {
        let evaluations = match row.integrator {
            Integrator::EulerSeed | Integrator::Euler | Integrator::SymplecticEuler => 1.0,
            Integrator::Splitting | Integrator::ExactSplitting => 2.0,
            Integrator::Rk4 => 4.0,
            Integrator::ExactSplitting4 => 6.0,
        };
        row.ns_per_step = 100.0 * evaluations;
        row.us_per_simulated_second = row.ns_per_step / row.dt / 1000.0;
    }
    // Ties of cost keep the integrators' order (the untimed study sorted by measured time).
    study.rows.sort_by(|a, b| {
        let index = |i: Integrator| Integrator::ALL.iter().position(|&x| x == i);
        index(a.integrator)
            .cmp(&index(b.integrator))
            .then(b.dt.total_cmp(&a.dt))
    });
    // The sentence again, from the deterministic costs.
    study.sentence =
        study::analysis::sentence(&study.rows, &config.integrators, 1e-6, case.duration);
    study::summarise(
        &config.integrators,
        &mut study.rows,
        study.reference_kind,
        study.floor,
    );
    study
}

fn draw(study: &tumble::study::SceneStudy, width: u16, height: u16, done: Option<usize>) -> String {
    use tumble::tui::study_view::{draw_study, Progress, Shown};
    let area = ratatui::layout::Rect::new(0, 0, width, height);
    let mut buf = ratatui::buffer::Buffer::empty(area);
    let shown = Shown {
        ascii: false,
        in_use: Integrator::Rk4,
        dt: 0.001,
    };
    let progress = done.map(|done| Progress {
        done,
        total: 28,
        left: Some(Duration::from_secs(75)),
    });
    draw_study(study, &shown, progress, area, &mut buf);
    (0..height)
        .map(|y| {
            (0..width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
                .trim_end()
                .to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_study_view_draws_both_charts_the_floor_band_the_orders_and_the_diverged_runs() {
    let study = spring_study();
    // The numbers the snapshots show, checked first.
    let diverged: Vec<_> = study.rows.iter().filter(|r| !r.ok()).collect();
    let diverged: Vec<_> = diverged.iter().map(|r| (r.integrator, r.dt)).collect();
    // Explicit Euler's energy grows by 1 + (ω dt)² a step: ×2 at 0.1 s, ×1.01 at 0.01 s (×3.6
    // by step 130, where the guard trips); no other run diverges.
    assert_eq!(diverged.len(), 4, "{diverged:?}");
    for run in [
        (Integrator::EulerSeed, 0.1),
        (Integrator::Euler, 0.1),
        (Integrator::EulerSeed, 0.01),
        (Integrator::Euler, 0.01),
    ] {
        assert!(diverged.contains(&run), "{run:?} in {diverged:?}");
    }
    let order = |i: Integrator| {
        study
            .orders
            .iter()
            .find(|o| o.integrator == i)
            .unwrap()
            .slope
    };
    assert!((order(Integrator::Rk4).unwrap() - 4.0).abs() < 0.5);
    assert!((order(Integrator::Splitting).unwrap() - 2.0).abs() < 0.2);
    assert!(
        study.rows.iter().any(|r| r.below_floor),
        "a run inside the band"
    );
    let wide = draw(&study, 120, 40, None);
    for expected in [
        "error against cost, log–log",
        "error against dt: slope = p",
        "── rk4 (in use) p 3.98",
        "── splitting p 2.00",
        "grey band: below the floor",
        "diverged (no point): euler-seed 1e-1, euler 1e-1",
        "splitting and exact-splitting coincide at every dt",
        "◆",
        "·",
    ] {
        assert!(wide.contains(expected), "no `{expected}` in:\n{wide}");
    }
    insta::assert_snapshot!("study_view_spring_120x40", wide);
    insta::assert_snapshot!("study_view_spring_80x24", draw(&study, 80, 24, None));
}

#[test]
fn the_chart_fills_as_runs_finish_cheapest_first() {
    // The runs as the study tells them: the reference first, then each run, the largest dt
    // (fewest steps) first; the partial chart of the first runs is drawn under the gauge.
    use tumble::study::{self, Config, Partial, Timing};
    let case = tumble::study::scenes::builtin().remove(2); // the projectile, 1 s
    let config = Config {
        integrators: vec![Integrator::Rk4, Integrator::Splitting],
        dts: vec![1e-2, 1e-1],
        timing: Timing {
            repeats: 0,
            sample_interval: 0.1,
        },
        target_error: 1e-6,
    };
    let mut told = Vec::new();
    let full = study::study_case_streaming(&case, &config, &mut |_, _| {}, &mut |p| told.push(p));
    assert!(matches!(told[0], Partial::Reference { kind: "exact", .. }));
    let dts: Vec<f64> = told[1..]
        .iter()
        .map(|p| match p {
            Partial::Run(row) => row.dt,
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(dts, [1e-1, 1e-1, 1e-2, 1e-2]);
    for p in &told[1..] {
        let Partial::Run(row) = p else { unreachable!() };
        let same = full
            .rows
            .iter()
            .find(|r| r.integrator == row.integrator && r.dt == row.dt)
            .unwrap();
        assert_eq!(row.error, same.error, "the streamed run is the study's");
    }
    // A job's partial study grows with the runs done and gives way to the result.
    let job = tumble::study::background::Job::spawn(case, config);
    let started = Instant::now();
    let mut seen = Vec::new();
    while job.result().is_none() {
        job.poll();
        if let Some(partial) = job.partial() {
            assert_eq!(partial.rows.len(), job.progress().0.min(partial.rows.len()));
            seen.push(partial.rows.len());
        }
        assert!(started.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(1));
    }
    assert!(
        job.partial().is_none(),
        "the result replaces the partial study"
    );
    assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
    // The spring's first 14 runs (dt = 1e-1 and 1e-2), as the view draws them mid-study.
    let study = spring_study();
    let mut partial = study.clone();
    partial.rows.retain(|r| r.dt >= 1e-2);
    partial.orders = study::summarise(
        &Integrator::ALL,
        &mut partial.rows,
        partial.reference_kind,
        partial.floor,
    );
    partial.sentence = "14 of 28 runs finished".into();
    let text = draw(&partial, 120, 40, Some(14));
    assert!(
        text.contains("14 of 28 runs · about 1 min 15 s left"),
        "{text}"
    );
    assert!(text.contains("error against dt"), "{text}");
}

#[test]
fn a_cloth_study_streams_its_runs_cheapest_first_into_the_chart() {
    // The 5 × 5 sheet over 0.2 s, untimed: its frame once the reference is made, then each
    // run, the largest dt (fewest steps) first, each the study's own row; mid-study the view
    // draws the runs so far under the gauge.
    use tumble::study::{self, Case, Config, Partial, Timing};
    let lesson = tumble::scene::load(Path::new("tests/fixtures/study/small-sheet.toml"))
        .unwrap_or_else(|e| panic!("{e}"));
    let case = Case {
        name: "sheet".into(),
        description: "a small sheet".into(),
        scene: lesson.scene,
        duration: 0.2,
    };
    let config = Config {
        timing: Timing {
            repeats: 0,
            sample_interval: 0.1,
        },
        ..Config::default()
    };
    let mut told = Vec::new();
    let full = study::study_case_streaming(&case, &config, &mut |_, _| {}, &mut |p| told.push(p));
    let cloth = full.cloth.as_ref().expect("a cloth case");
    let Partial::ClothReference(frame) = &told[0] else {
        panic!("{:?}", told[0])
    };
    assert_eq!((frame.limit, &frame.ladder), (cloth.limit, &cloth.ladder));
    assert!(frame.rows.is_empty());
    let runs: Vec<_> = told[1..]
        .iter()
        .map(|p| match p {
            Partial::ClothRun(row) => row.as_ref().clone(),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(runs.len(), cloth.rows.len());
    let dts: Vec<f64> = runs.iter().map(|r| r.dt).collect();
    assert!(
        dts.windows(2).all(|w| w[0] >= w[1]),
        "the largest dt first: {dts:?}"
    );
    for row in &runs {
        let same = cloth
            .rows
            .iter()
            .find(|r| r.integrator == row.integrator && r.dt == row.dt)
            .expect("the study's row");
        assert_eq!(
            (row.error.to_bits(), &row.status),
            (same.error.to_bits(), &same.status),
            "the streamed run is the study's"
        );
    }
    // The first half of the runs, as the view draws them mid-study.
    let half = runs.len() / 2;
    let mut partial = full.clone();
    let mut so_far = study::cloth::summarise(
        (**frame).clone(),
        runs[..half].to_vec(),
        &tumble::physics::cloth::ClothIntegrator::ALL,
    );
    so_far.sentence = format!("{half} of {} runs finished", runs.len());
    assert_eq!(so_far.rows.len(), half);
    partial.cloth = Some(so_far);
    let text = draw(&partial, 120, 40, Some(half));
    assert!(
        text.contains(&format!("{half} of 28 runs · about 1 min 15 s left")),
        "{text}"
    );
    assert!(text.contains("cloth case"), "{text}");
    assert!(text.contains("── symplectic-euler"), "{text}");
    cloth_charts_are_honest(&text, &partial);
    // The whole study: the same drawing, every run in.
    let text = draw(&full, 120, 40, None);
    cloth_charts_are_honest(&text, &full);
    // Before the first run: the frame only, a word on the chart instead of an empty grid.
    let mut frame_only = full.clone();
    let mut empty = (**frame).clone();
    empty.sentence = format!("0 of {} runs finished", runs.len());
    frame_only.cloth = Some(empty);
    let text = draw(&frame_only, 120, 40, Some(0));
    assert!(
        text.contains("reference made: the first run is under way"),
        "{text}"
    );
    assert!(text.contains("error against dt"), "{text}");
    assert!(text.contains("2/ω_max"), "{text}");
}

/// The cloth case's view as the bodies': both charts, the explicit limit marked on the dt
/// chart, the floor band at 3 × the reference's spread, each integrator's fitted order beside
/// its line and in the legend, the diverged runs listed.
fn cloth_charts_are_honest(text: &str, study: &tumble::study::SceneStudy) {
    let cloth = study.cloth.as_ref().expect("a cloth case");
    assert!(text.contains("error against cost"), "{text}");
    assert!(text.contains("error against dt: slope = p"), "{text}");
    // The limit: a dashed column on the dt chart (right of the cost chart), named on top.
    let lines: Vec<&str> = text.lines().collect();
    let dashes = lines.iter().filter(|l| l.contains('┆')).count();
    assert!(dashes >= 3, "no dashed limit column:\n{text}");
    assert!(
        lines
            .iter()
            .any(|l| l.contains("┆2/ω_max") || l.contains("2/ω_max┆")),
        "the limit is not named on its column:\n{text}"
    );
    // The band: its dots on the charts and its line under them, at 3 × the spread.
    let band = 3.0 * cloth.reference_spread;
    assert!(
        text.contains(&format!(
            "grey band: below 3 × the reference's spread, {} m",
            tumble::study::analysis::format_number(band)
        )),
        "{text}"
    );
    assert!(text.contains("···"), "{text}");
    // Each order in the legend and beside its line on the dt chart.
    for order in &cloth.orders {
        let label = match order.slope {
            Some(s) => format!("p {s:.2}"),
            None => "p –".to_string(),
        };
        assert!(
            text.contains(&format!("── {} {label}", order.integrator.name())),
            "{text}"
        );
        let drawn = cloth
            .rows
            .iter()
            .any(|r| r.integrator == order.integrator && r.ok());
        if drawn {
            assert!(
                lines
                    .iter()
                    .take_while(|l| !l.contains("study of"))
                    .any(|l| l.contains(&label)),
                "no `{label}` beside {}'s line:\n{text}",
                order.integrator.name()
            );
        }
    }
    let diverged: Vec<_> = cloth.rows.iter().filter(|r| !r.ok()).collect();
    if diverged.is_empty() {
        assert!(text.contains("diverged (no point): none"), "{text}");
    } else {
        assert!(
            text.contains(&format!(
                "diverged (no point): {} {}",
                diverged[0].integrator.name(),
                tumble::study::analysis::format_dt(diverged[0].dt)
            )),
            "{text}"
        );
    }
}
