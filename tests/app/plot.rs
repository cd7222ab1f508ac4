//! The graph of any quantity (key `p`): picked through the key table, drawn against time or
//! against another quantity (a phase portrait) at fixed sizes, and written as CSV (key `X`)
//! with the numbers the simulation's own snapshots give.

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use std::path::{Path, PathBuf};
use tumble::physics::World;
use tumble::tui::app::View;
use tumble::tui::export;
use tumble::tui::plot::{PlotChoice, Quantity};
use tumble::tui::{App, Options};

fn lesson_app(name: &str) -> App {
    App::new(
        tumble::lessons::load(Path::new(name)).unwrap_or_else(|e| panic!("{e}")),
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
    let buf = export::render(app, width, height);
    (0..buf.area.height)
        .map(|y| {
            let row: String = (0..buf.area.width).map(|x| buf[(x, y)].symbol()).collect();
            row.trim_end().to_string()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The picker's line of a quantity, by name.
fn column(app: &App, name: &str) -> usize {
    app.session
        .plot_series
        .columns
        .iter()
        .position(|c| c.name == name)
        .unwrap_or_else(|| panic!("no column {name}"))
}

/// Picks a quantity the way a user does: `p`, arrows down to it, then `x` (horizontal axis)
/// or Enter (graph it).
fn pick(app: &mut App, name: &str, key: KeyCode) {
    press(app, KeyCode::Char('p'));
    let target = column(app, name);
    // The picker opens on the current choice: go back to the top first.
    for _ in 0..app.session.plot_series.columns.len() {
        press(app, KeyCode::Up);
        if let tumble::tui::Overlay::PlotPicker { selected: 0, .. } = app.ui.overlay {
            break;
        }
    }
    for _ in 0..target {
        press(app, KeyCode::Down);
    }
    press(app, key);
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tumble-plot-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The CSV's rows as numbers (after its header).
fn rows(csv: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = csv.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    (header, rows)
}

/// The value the simulation's snapshot gives for a quantity, by independent reading: the
/// snapshot's own fields (what the panels show), not the plot's reader.
fn from_snapshot(world: &World, q: Quantity) -> f64 {
    match q {
        Quantity::Body { body, measure } => {
            let s = world.snapshot_of(body);
            use tumble::tui::plot::Measure::*;
            match measure {
                Position(i) => s.position[i],
                Velocity(i) => s.velocity[i],
                AngularVelocity(i) => s.angular_velocity[i],
                AngularMomentum(i) => s.angular_momentum[i],
                AngularMomentumNorm => s.angular_momentum.norm(),
                Speed => s.velocity.norm(),
                Kinetic => s.energy.kinetic,
                Potential => s.energy.potential,
                Energy => s.energy.total,
                _ => unreachable!("not a body's column"),
            }
        }
        Quantity::SceneEnergy => world.snapshot().system.energy.total,
        Quantity::SceneMomentum(i) => world.snapshot().system.linear_momentum[i],
        Quantity::JointError(j) => world.snapshot().joints[j].error,
    }
}

#[test]
fn the_quantity_graph_against_time_and_as_a_phase_portrait_at_three_sizes() {
    let mut app = lesson_app("32-predict-the-bounce");
    // The drop, the bounce (e = 0.5) and most of the climb back.
    app.step_frames(1100);
    pick(&mut app, "cube.y", KeyCode::Enter);
    assert_eq!(app.ui.view, View::Plot);
    assert_eq!(
        app.ui.plot,
        Some(PlotChoice {
            y: column(&app, "cube.y"),
            x: None
        })
    );
    for (w, h) in [(80, 24), (120, 40), (200, 60)] {
        let shown = screen(&app, w, h);
        let title = if w == 80 {
            "┌ cube.y"
        } else {
            "┌ cube.y, m against time ─"
        };
        assert!(shown.contains(title), "{w}x{h}: the graph's title\n{shown}");
        insta::assert_snapshot!(format!("plot_time_{w}x{h}"), shown);
    }
    // The phase portrait: vy against y (the bounce's loops).
    pick(&mut app, "cube.y", KeyCode::Char('x'));
    let list = screen(&app, 80, 24);
    assert!(list.contains("← horizontal axis"), "{list}");
    insta::assert_snapshot!("plot_picker_80x24", list);
    // y → z → vx → vy.
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Down);
    press(&mut app, KeyCode::Enter);
    assert_eq!(
        app.ui.plot,
        Some(PlotChoice {
            y: column(&app, "cube.vy"),
            x: Some(column(&app, "cube.y"))
        })
    );
    for (w, h) in [(80, 24), (120, 40), (200, 60)] {
        let shown = screen(&app, w, h);
        let title = if w == 80 {
            "┌ cube.vy vs cube.y ─"
        } else {
            "┌ cube.vy, m/s against cube.y, m (phase portrait) ─"
        };
        assert!(shown.contains(title), "{w}x{h}: the graph's title\n{shown}");
        insta::assert_snapshot!(format!("plot_phase_{w}x{h}"), shown);
    }
    // `t` in the picker brings time back on the horizontal axis; Esc leaves the graph.
    press(&mut app, KeyCode::Char('p'));
    press(&mut app, KeyCode::Char('t'));
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.ui.plot.unwrap().x, None);
    press(&mut app, KeyCode::Esc);
    assert_eq!(app.ui.view, View::Loop);
}

#[test]
fn the_csv_of_every_quantity_holds_the_simulations_numbers() {
    // Three bodies colliding (lesson 14) and a double pendulum with its joints (lesson 27):
    // every column the picker offers, written by the app, against a separate run's
    // snapshots at the same steps (bit for bit: the same state, read the panels' way).
    for (name, frames) in [("14-head-on", 700), ("27-the-double-pendulum", 300)] {
        let mut app = lesson_app(name);
        app.prefs.write_dir = scratch(name);
        app.step_frames(frames);
        let count = app.session.plot_series.columns.len();
        let mut reference = app.session.lesson.scene.world();
        let mut columns: Vec<(Quantity, Vec<Vec<f64>>)> = Vec::new();
        for c in 0..count {
            // Through the keys: p, down to it, Enter, then X writes the file.
            let wanted = app.session.plot_series.columns[c].name.clone();
            pick(&mut app, &wanted, KeyCode::Enter);
            press(&mut app, KeyCode::Char('X'));
            let path = app.csv_path().expect("a graph is shown");
            let notice = app.ui.notice.clone().unwrap_or_default();
            assert!(
                notice.starts_with(&format!("wrote {}", path.display())),
                "{notice}"
            );
            let text = std::fs::read_to_string(&path).unwrap();
            let (header, rows) = rows(&text);
            assert_eq!(
                header,
                [
                    "step",
                    "t",
                    app.session.plot_series.columns[c].name.as_str()
                ]
            );
            assert_eq!(rows.len(), frames as usize + 1, "every frame from t = 0");
            columns.push((app.session.plot_series.columns[c].quantity, rows));
        }
        for step in 0..=frames {
            if step > 0 {
                reference.step();
            }
            for (q, rows) in &columns {
                let row = &rows[step as usize];
                assert_eq!(row[0], step as f64);
                assert_eq!(row[1], reference.time());
                let truth = from_snapshot(&reference, *q);
                assert!(
                    row[2] == truth || (row[2].is_nan() && truth.is_nan()),
                    "{name} step {step} {q:?}: CSV {} against the simulation's {truth}",
                    row[2]
                );
            }
        }
        // The names cover the list: components, |L|, energy per body and the scene's,
        // and the joints' errors.
        let names: Vec<&str> = app
            .session
            .plot_series
            .columns
            .iter()
            .map(|c| c.name.as_str())
            .collect();
        for wanted in ["x", "vy", "wz", "Lz", "|L|", "energy", "kinetic"] {
            assert!(
                names.iter().any(|n| n.ends_with(&format!(".{wanted}"))),
                "{name}: {wanted} in {names:?}"
            );
        }
        assert!(names.contains(&"energy") && names.contains(&"Px"));
        if name.starts_with("27") {
            assert!(
                names.contains(&"top.error") && names.contains(&"middle.error"),
                "{names:?}"
            );
        }
        std::fs::remove_dir_all(&app.prefs.write_dir).ok();
    }
}

#[test]
fn the_phase_portrait_csv_has_both_columns_and_the_energy_graph_writes_its_own() {
    let mut app = lesson_app("05-ground-collision");
    app.prefs.write_dir = scratch("phase");
    app.step_frames(200);
    pick(&mut app, "body1.y", KeyCode::Char('x'));
    let vy = column(&app, "body1.vy");
    while !matches!(app.ui.overlay, tumble::tui::Overlay::PlotPicker { selected, .. } if selected == vy)
    {
        press(&mut app, KeyCode::Down);
    }
    press(&mut app, KeyCode::Enter);
    press(&mut app, KeyCode::Char('X'));
    let path = app.csv_path().unwrap();
    assert!(
        path.ends_with("tumble-05-ground-collision-body1.y-body1.vy.csv"),
        "{path:?}"
    );
    let (header, phase) = rows(&std::fs::read_to_string(&path).unwrap());
    assert_eq!(header, ["step", "t", "body1.y", "body1.vy"]);
    let last = phase.last().unwrap();
    assert_eq!(last[2], app.session.world.state().position.y);
    assert_eq!(last[3], app.session.snapshot.velocity.y);
    // The energy graph (g) writes its curves: K + V = E on every row, drift last.
    press(&mut app, KeyCode::Char('g'));
    press(&mut app, KeyCode::Char('X'));
    let path = app.csv_path().unwrap();
    assert!(
        path.ends_with("tumble-05-ground-collision-energy.csv"),
        "{path:?}"
    );
    let (header, energy) = rows(&std::fs::read_to_string(&path).unwrap());
    assert_eq!(
        header,
        ["step", "t", "kinetic", "potential", "total", "drift"]
    );
    assert_eq!(energy.len(), 201);
    for r in &energy {
        assert!(
            (r[2] + r[3] - r[4]).abs() <= 1e-12 * r[4].abs().max(1.0),
            "{r:?}"
        );
    }
    assert_eq!(energy[200][4], app.session.snapshot.energy.total);
    // On the loop view there is nothing to write: the notice says which keys graph.
    press(&mut app, KeyCode::Esc);
    press(&mut app, KeyCode::Char('X'));
    let notice = app.ui.notice.clone().unwrap();
    assert!(
        notice.contains("g shows") && notice.contains("p picks"),
        "{notice}"
    );
    std::fs::remove_dir_all(&app.prefs.write_dir).ok();
}

#[test]
fn stepping_back_and_resetting_cut_the_plotted_past() {
    let mut app = lesson_app("05-ground-collision");
    app.step_frames(50);
    assert_eq!(app.session.plot_series.len(), 51);
    app.step_back_frames(10);
    assert_eq!(app.session.plot_series.len(), 41);
    assert_eq!(
        *app.session.plot_series.times().last().unwrap(),
        app.session.world.time(),
        "the last row is the frame shown"
    );
    app.step_frames(10);
    assert_eq!(app.session.plot_series.len(), 51);
    app.reset();
    assert_eq!(app.session.plot_series.len(), 1);
}

#[test]
fn several_curves_share_one_graph_with_one_axis_per_unit() {
    let mut app = lesson_app("32-predict-the-bounce");
    app.prefs.write_dir = scratch("curves");
    app.step_frames(1100);
    pick(&mut app, "cube.y", KeyCode::Enter);
    // `a` adds cube.vy: another unit, so a right axis of its own.
    pick(&mut app, "cube.vy", KeyCode::Char('a'));
    assert_eq!(app.ui.view, View::Plot);
    let (y, vy) = (column(&app, "cube.y"), column(&app, "cube.vy"));
    assert_eq!(app.plot_curves(), [y, vy]);
    let notice = app.ui.notice.clone().unwrap();
    assert!(
        notice.contains("two axes, m on the left, m/s on the right"),
        "{notice}"
    );
    for (w, h) in [(80, 24), (120, 40)] {
        let shown = screen(&app, w, h);
        // The legend says which axis each curve reads on where it has room.
        let title = if w == 80 {
            "┌ • cube.y ▄ cube.vy ─"
        } else {
            "┌ • cube.y (left) ▄ cube.vy (right) ─"
        };
        assert!(shown.contains(title), "{w}x{h}: the legend\n{shown}");
        insta::assert_snapshot!(format!("plot_two_axes_{w}x{h}"), shown);
    }
    // The right axis's labels are cube.vy's range (-4.5 to 2.4 m/s, as the phase portrait's
    // vertical axis reads), the left one's cube.y's (0.06 to 1.04 m), on the same rows.
    let shown = screen(&app, 120, 40);
    let lines: Vec<&str> = shown.lines().collect();
    assert!(
        lines[2].starts_with("│1.04") && lines[2].contains("│2.4"),
        "{shown}"
    );
    let bottom = lines.iter().find(|l| l.starts_with("│0.06")).unwrap();
    assert!(bottom.contains("│-4.5"), "{shown}");
    let wide = screen(&app, 200, 60);
    assert!(
        wide.contains("┌ • cube.y, m (left) ▄ cube.vy, m/s (right) against time: two axes ─"),
        "{wide}"
    );
    // The picker marks the curves; a third unit (J) is refused.
    press(&mut app, KeyCode::Char('p'));
    let list = screen(&app, 120, 40);
    assert!(list.contains("← curve 2"), "{list}");
    press(&mut app, KeyCode::Esc);
    pick(&mut app, "cube.kinetic", KeyCode::Char('a'));
    assert_eq!(app.plot_curves(), [y, vy], "a third unit has no axis");
    let notice = app.ui.notice.clone().unwrap();
    assert!(notice.contains("two axes are in m and m/s"), "{notice}");
    // The CSV has every curve.
    press(&mut app, KeyCode::Char('X'));
    let path = app.csv_path().unwrap();
    assert!(
        path.ends_with("tumble-32-predict-the-bounce-cube.y-cube.vy.csv"),
        "{path:?}"
    );
    let (header, rows) = rows(&std::fs::read_to_string(&path).unwrap());
    assert_eq!(header, ["step", "t", "cube.y", "cube.vy"]);
    let last = rows.last().unwrap();
    assert_eq!(last[2], app.session.world.state().position.y);
    assert_eq!(last[3], app.session.snapshot.velocity.y);
    // `a` on a curve takes it off; Enter graphs one curve again.
    pick(&mut app, "cube.y", KeyCode::Char('a'));
    assert_eq!(app.plot_curves(), [vy]);
    // Same unit: one shared axis, said in the title.
    pick(&mut app, "cube.kinetic", KeyCode::Enter);
    pick(&mut app, "cube.potential", KeyCode::Char('a'));
    pick(&mut app, "cube.energy", KeyCode::Char('a'));
    assert_eq!(app.plot_curves().len(), 3);
    let shown = screen(&app, 200, 60);
    assert!(
        shown.contains("against time: one axis, J"),
        "one shared axis\n{shown}"
    );
    pick(&mut app, "cube.x", KeyCode::Enter);
    assert_eq!(app.plot_curves(), [column(&app, "cube.x")]);
    std::fs::remove_dir_all(&app.prefs.write_dir).ok();
}
