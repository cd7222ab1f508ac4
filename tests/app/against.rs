//! `tumble FILE --against THEIRS.csv`: their run drawn as the ghost, the run pausing at the
//! first step where it parts from tumble's, the status line naming it.

use std::fmt::Write as _;
use std::path::Path;
use tumble::diff::{check, theirs, Subject};
use tumble::tui::{Against, App, Options};

#[test]
fn the_app_pauses_where_their_run_parts_and_names_it() {
    let lesson = tumble::lessons::load(Path::new("04-gravity-no-torque")).unwrap();
    // Their run: tumble's own positions, pushed 1 cm along x from step 30 on.
    let mut world = lesson.scene.world();
    let mut text = String::from("step,x,y,z\n");
    for step in 0..=60 {
        if step > 0 {
            world.step();
        }
        let x = world.state().position;
        let shift = if step >= 30 { 0.01 } else { 0.0 };
        writeln!(text, "{step},{},{},{}", x.x + shift, x.y, x.z).unwrap();
    }
    let rows = theirs::parse(&text, lesson.scene.dt).unwrap();
    let subject = Subject {
        scene: &lesson.scene,
        scene_name: "04-gravity-no-torque",
        theirs_name: "theirs.csv",
        body: 0,
    };
    let outcome = check(&subject, &rows, 1e-6).unwrap();
    let against = Against::new("theirs.csv".into(), &rows, &outcome);
    assert_eq!(against.parting, Some((30, "x".to_string())));
    // Their pose at step 45 is their row 45: tumble's x + 1 cm.
    let (x, _) = against.pose_at(45).expect("x y z given");
    let mut app = App::new(lesson, Options::default());
    app.ui.against = Some(against);
    // Run on through the lesson's page stops until the run pauses by itself at step 30.
    for _ in 0..10 {
        if app.session.world.step_count() >= 30 {
            break;
        }
        app.ui.running = true;
        app.step_frames(100);
    }
    assert_eq!(app.session.world.step_count(), 30);
    assert!(!app.ui.running);
    assert_eq!(
        app.ui.stop.as_ref().map(|s| s.label.as_str()),
        Some("they part")
    );
    let screen = screen(&app);
    assert!(screen.contains("theirs part at step 30 (x)"), "{screen}");
    assert!(screen.contains("theirs"), "{screen}");
    app.ui.running = true;
    app.step_frames(15);
    assert!((x.x - app.session.snapshot.position.x - 0.01).abs() < 1e-12);
}

/// The screen's text at 200 × 50.
fn screen(app: &App) -> String {
    use ratatui::backend::TestBackend;
    use ratatui::Terminal;
    let mut terminal = Terminal::new(TestBackend::new(200, 50)).unwrap();
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
