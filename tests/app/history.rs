//! The app with cloths (issue 11, item 7): keyframes plus exact replay keep the step-back ring
//! under its byte budget, and stepping back gives bit for bit the states the forward run had;
//! compare mode with another particle integrator; the settings form's cloth integrator,
//! applied and written.
#![cfg(feature = "tui")]

use crossterm::event::{KeyCode, KeyEvent, KeyModifiers};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;
use tumble::physics::cloth::ClothIntegrator;
use tumble::physics::{Checkpoint, Integrator, World};
use tumble::scene::Lesson;
use tumble::tui::history::{History, DEFAULT_BUDGET, DEFAULT_CAPACITY};
use tumble::tui::{App, Comparison, Effect, Options, Overlay};

/// Counts the bytes this thread allocates (the other tests run on other threads).
struct Counting;

thread_local! {
    static ALLOCATED: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATED.try_with(|a| a.set(a.get() + layout.size()));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Bytes allocated on this thread while `f` runs.
fn allocated_by<T>(f: impl FnOnce() -> T) -> (T, usize) {
    let before = ALLOCATED.with(Cell::get);
    let out = f();
    (out, ALLOCATED.with(Cell::get) - before)
}

/// A cube above a 30 × 30 sheet pinned on its edges; dt is a quarter of the sheet's explicit
/// limit (`tumble walk` shows 2/ω_max = 2.1e-3 s), so `symplectic-euler` is stable.
const SHEET: &str = r#"title = "History: a cube on a 30 × 30 sheet"

[scene]
dt = 0.0005
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.3, friction = 0.5 }

[body]
name = "cube"
shape = "box"
size = [0.3, 0.3, 0.3]
mass = 1.0
position = [0.1, 0.3, 0.0]
angular_velocity = [1.0, 2.0, 0.5]

[[cloth]]
name = "sheet"
size = [1.5, 1.5]
count = [30, 30]
mass = 2.0
stretch = 400.0
shear = 100.0
bend = 20.0
damping = 0.02
pinned = "edges"
integrator = "INTEGRATOR"
"#;

fn lesson(integrator: ClothIntegrator) -> Lesson {
    let source = SHEET.replace("INTEGRATOR", integrator.name());
    tumble::scene::parse(&source, Path::new("history-sheet.toml")).unwrap_or_else(|e| panic!("{e}"))
}

fn app(integrator: ClothIntegrator) -> App {
    App::new(
        lesson(integrator),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    )
}

/// Every particle's position and velocity, and every body state, as bits.
fn bits(world: &World) -> Vec<u64> {
    let mut out = Vec::new();
    for c in world.cloths() {
        for v in c.positions.iter().chain(&c.velocities) {
            out.extend(v.iter().map(|x| x.to_bits()));
        }
    }
    for s in world.states() {
        out.extend(
            s.position
                .iter()
                .chain(s.linear_momentum.iter())
                .chain(s.angular_momentum.iter())
                .map(|x| x.to_bits()),
        );
    }
    out
}

/// The checkpoints of a plain world stepped `frames` frames, at the frames asked for.
fn forward(world: &mut World, frames: u64, at: &[u64]) -> Vec<(Checkpoint, Vec<u64>)> {
    let mut kept = Vec::new();
    while world.step_count() < frames {
        if at.contains(&world.step_count()) {
            kept.push((world.checkpoint(), bits(world)));
        }
        world.step();
    }
    kept
}

#[test]
fn restoring_a_cloth_checkpoint_and_stepping_gives_the_same_bits() {
    // What replay rests on: the world is deterministic from a checkpoint.
    for integrator in ClothIntegrator::ALL {
        let mut world = lesson(integrator).scene.world();
        for _ in 0..50 {
            world.step();
        }
        let mark = world.checkpoint();
        for _ in 0..30 {
            world.step();
        }
        let once = bits(&world);
        world.restore(&mark);
        for _ in 0..30 {
            world.step();
        }
        assert_eq!(bits(&world), once, "{}", integrator.name());
    }
}

#[test]
fn heap_bytes_bounds_what_a_checkpoint_allocates() {
    // The allocator's count of a checkpoint's copy is the truth; heap_bytes counts the
    // particles and springs exactly and the cloth's private scratch as an upper bound, so it
    // must be at least the truth and not far above it.
    for integrator in ClothIntegrator::ALL {
        let mut world = lesson(integrator).scene.world();
        for _ in 0..5 {
            world.step();
        }
        let (checkpoint, measured) = allocated_by(|| world.checkpoint());
        let counted = checkpoint.heap_bytes();
        assert!(
            counted >= measured && counted as f64 <= 1.1 * measured as f64,
            "{}: heap_bytes {counted} vs allocated {measured}",
            integrator.name()
        );
        eprintln!(
            "30 × 30 sheet + cube, {}: {measured} bytes per checkpoint (heap_bytes {counted})",
            integrator.name()
        );
    }
}

#[test]
fn a_30x30_sheet_keeps_the_ring_under_budget_and_steps_back_exactly() {
    const FRAMES: u64 = 2000;
    let mut app = app(ClothIntegrator::SymplecticEuler);
    app.step_frames(FRAMES);
    assert_eq!(app.session.world.step_count(), FRAMES);
    let history = &app.session.history;
    let one = app.session.world.checkpoint().heap_bytes();
    eprintln!(
        "after {FRAMES} frames: {} frames kept, K = {}, {} keyframes, {} bytes (budget {DEFAULT_BUDGET}, \
         one checkpoint {one} bytes)",
        history.len(),
        history.interval(),
        history.keyframes(),
        history.heap_bytes()
    );
    // Every frame whole would hold 2000 checkpoints: far over the budget.
    assert!(FRAMES as usize * one > 10 * DEFAULT_BUDGET);
    assert!(history.heap_bytes() <= DEFAULT_BUDGET);
    assert_eq!(history.len(), FRAMES as usize, "every frame start is kept");
    // K > 1 (history.rs: ⌈capacity / K⌉ + ⌈√K⌉ ≤ ⌊(budget − capacity · 32) / bytes⌋);
    // keyframes at 0, K, 2K, … — the keyframe of t = 0 is smaller (the sheet's step buffers
    // do not exist yet), so its K is smaller and one more keyframe can fit.
    assert!(history.interval() > 1);
    let uniform = (FRAMES as usize).div_ceil(history.interval());
    assert!(
        (uniform..=uniform + 1).contains(&history.keyframes()),
        "{} keyframes, K = {}",
        history.keyframes(),
        history.interval()
    );

    let mut plain = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    let back = [1u64, 37, 500];
    let at: Vec<u64> = back.iter().map(|b| FRAMES - b).collect();
    let expected = forward(&mut plain, FRAMES, &at);
    assert_eq!(
        bits(&plain),
        bits(&app.session.world),
        "the app steps as a plain world"
    );
    for (b, (checkpoint, bits_then)) in back.iter().zip(expected.iter().rev()) {
        let mut stepped = app.clone();
        stepped.step_back_frames(*b as usize);
        assert_eq!(stepped.session.world.step_count(), FRAMES - b);
        assert_eq!(bits(&stepped.session.world), *bits_then, "{b} frames back");
        assert_eq!(
            stepped.session.world.checkpoint(),
            *checkpoint,
            "{b} frames back"
        );
        assert_eq!(stepped.session.history.len(), (FRAMES - b) as usize);
    }
    // ← one frame at a time across a keyframe, every frame exact.
    let k = app.session.history.interval() as u64;
    let last_key = (FRAMES - 1) / k * k;
    let mut plain = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    let frames: Vec<u64> = (last_key - 3..FRAMES).collect();
    let expected = forward(&mut plain, FRAMES, &frames);
    // The rewind marks the first step back leaves: at most ⌈√K⌉ checkpoints.
    let marks = (k as f64).sqrt().ceil() as usize;
    for (frame, (_, bits_then)) in frames.iter().zip(&expected).rev() {
        app.step_back();
        assert_eq!(app.session.world.step_count(), *frame);
        assert_eq!(bits(&app.session.world), *bits_then, "frame {frame}");
        assert!(app.session.history.rewind_bytes() <= marks * (one + 1024));
    }
    // A frame pushed drops the marks.
    app.step_frames(1);
    assert_eq!(app.session.history.rewind_bytes(), 0);
}

#[test]
fn a_small_budget_drops_the_oldest_frames_with_their_keyframe() {
    // Room for ten checkpoints and 100 frames: K = 20 (5 keyframes in any 100 frames in a
    // row, and ⌈√20⌉ = 5 rewind marks; K = 17 would need 6 + 5).
    let mut world = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    // After one step: the sheet's step buffers exist from then on (a checkpoint of t = 0 is
    // smaller by them).
    world.step();
    let one = world.checkpoint().heap_bytes();
    let capacity = 100;
    // Each checkpoint kept also counts its own size (< 1 kB): room for exactly ten.
    let budget = capacity * 32 + 10 * (one + 1024);
    let mut history = History::with_budget(capacity, budget);
    for _ in 0..400 {
        history.push(world.state().position, &world, None);
        world.step();
    }
    let k = history.interval();
    assert_eq!(k, 20);
    assert!(history.heap_bytes() <= budget, "{}", history.heap_bytes());
    assert!(
        history.len() <= capacity && history.len() > capacity - k,
        "{} frames kept, K = {k}, {} keyframes",
        history.len(),
        history.keyframes()
    );
    // The oldest frame kept can be rebuilt: step back to it exactly (frames 1..=400 were
    // pushed, the world is at step 401).
    let oldest = 401 - history.len() as u64;
    let mut plain = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    let expected = forward(&mut plain, 401, &[oldest]);
    // Stepping back into the newest segment leaves rewind marks: still under budget.
    let mut back = world.clone();
    history.pop_into(&mut back, None).unwrap();
    assert!(history.rewind_bytes() > 0);
    assert!(history.heap_bytes() <= budget, "{}", history.heap_bytes());
    history
        .pop_frames_into(history.len(), &mut world, None)
        .unwrap();
    assert_eq!(world.step_count(), oldest);
    assert_eq!(bits(&world), expected[0].1);
    assert!(history.is_empty());
}

#[test]
fn a_switch_of_body_integrator_mid_segment_is_replayed_with_the_old_one() {
    // Frames 0..30 under rk4, then euler: stepping back to frame 20 must replay rk4.
    let mut app = app(ClothIntegrator::SymplecticEuler);
    assert!(app.session.history.is_empty());
    app.step_frames(30);
    app.update(tumble::tui::keys::Message::NextIntegrator);
    let switched = app.session.world.integrator();
    assert_ne!(switched, Integrator::Rk4);
    app.step_frames(10);
    let mut plain = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    let expected = forward(&mut plain, 30, &[20]);
    app.step_back_frames(20);
    assert_eq!(app.session.world.step_count(), 20);
    assert_eq!(bits(&app.session.world), expected[0].1);
    assert_eq!(
        app.session.world.integrator(),
        switched,
        "the world keeps the integrator chosen last"
    );
}

#[test]
fn compare_ghost_with_implicit_euler_on_a_symplectic_sheet_runs_and_differs() {
    let mut app = app(ClothIntegrator::SymplecticEuler);
    let offered = app.comparisons();
    assert!(offered.contains(&Comparison::ClothIntegrator(ClothIntegrator::ImplicitEuler)));
    assert!(!offered.contains(&Comparison::ClothIntegrator(
        ClothIntegrator::SymplecticEuler
    )));
    assert!(offered.contains(&Comparison::Integrator(Integrator::Euler)));
    app.start_compare(Comparison::ClothIntegrator(ClothIntegrator::ImplicitEuler));
    let ghost = app.session.ghost.as_ref().expect("a ghost");
    assert_eq!(
        ghost.world.cloths()[0].integrator,
        ClothIntegrator::ImplicitEuler
    );
    assert_eq!(
        app.session.world.cloths()[0].integrator,
        ClothIntegrator::SymplecticEuler
    );
    app.step_frames(200);
    assert!(app.session.divergence.is_none());
    let ghost = &app.session.ghost.as_ref().unwrap().world;
    assert_eq!(ghost.step_count(), 200);
    // Backward Euler damps the sheet's fast modes: the two sheets part.
    let apart = app.session.world.cloths()[0]
        .positions
        .iter()
        .zip(&ghost.cloths()[0].positions)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(apart > 1e-6, "sheets {apart} m apart");
    // The ghost's own implicit run, alone, is what compare mode shows.
    let mut alone = lesson(ClothIntegrator::ImplicitEuler).scene.world();
    for _ in 0..200 {
        alone.step();
    }
    assert_eq!(bits(ghost), bits(&alone));
    let shown = status(&app);
    assert!(
        shown.contains("cloth symplectic-euler vs implicit-euler"),
        "{shown}"
    );
    // Stepping back rebuilds the ghost too, bit for bit.
    let mut alone = lesson(ClothIntegrator::ImplicitEuler).scene.world();
    let expected = forward(&mut alone, 200, &[147, 148, 149, 150]);
    app.step_back_frames(50);
    assert_eq!(
        bits(&app.session.ghost.as_ref().unwrap().world),
        expected[3].1
    );
    for back in (0..3).rev() {
        app.step_back();
        assert_eq!(
            bits(&app.session.ghost.as_ref().unwrap().world),
            expected[back].1
        );
    }
}

#[test]
fn a_scene_of_bodies_only_offers_no_particle_integrator() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/tui-box.toml");
    let app = App::new(
        tumble::scene::load(&path).unwrap(),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    assert!(app
        .comparisons()
        .iter()
        .all(|c| !matches!(c, Comparison::ClothIntegrator(_))));
    assert!(!status(&app).contains("cloth"));
}

#[test]
fn switching_the_particle_integrator_starts_the_solver_cold() {
    // After 40 explicit steps, switch to implicit-euler: the next step is exactly that of a
    // fresh implicit sheet put at the same positions and velocities (empty scratch, Δv₀ = 0).
    let mut world = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    for _ in 0..40 {
        world.step();
    }
    world.set_cloth_integrator(0, ClothIntegrator::ImplicitEuler);
    let mut fresh =
        tumble::physics::cloth::Cloth::new(&lesson(ClothIntegrator::ImplicitEuler).scene.cloths[0])
            .unwrap();
    fresh.positions.clone_from(&world.cloths()[0].positions);
    fresh.velocities.clone_from(&world.cloths()[0].velocities);
    let loads = *world.cloth_loads();
    fresh.step(&loads, world.dt());
    // Twice switched (implicit → symplectic → implicit) gives the same again.
    let mut again = world.clone();
    again.set_cloth_integrator(0, ClothIntegrator::SymplecticEuler);
    again.set_cloth_integrator(0, ClothIntegrator::ImplicitEuler);
    // Keep the cube away: compare the sheet stepped alone.
    let mut sheet = world.cloths()[0].clone();
    sheet.step(&loads, world.dt());
    assert_eq!(sheet.positions, fresh.positions);
    assert_eq!(sheet.velocities, fresh.velocities);
    let mut sheet = again.cloths()[0].clone();
    sheet.step(&loads, world.dt());
    assert_eq!(sheet.positions, fresh.positions);
    // A reset keeps the switch.
    world.reset();
    assert_eq!(world.cloths()[0].integrator, ClothIntegrator::ImplicitEuler);
}

/// The status bar's text at 200 columns.
fn status(app: &App) -> String {
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

fn press(app: &mut App, code: KeyCode) {
    app.handle_key(&KeyEvent::new(code, KeyModifiers::NONE));
}

fn typed(app: &mut App, text: &str) {
    for c in text.chars() {
        press(app, KeyCode::Char(c));
    }
}

#[test]
fn the_form_switches_a_cloths_integrator_on_restart_and_w_writes_it() {
    let dir = std::env::temp_dir().join(format!("tumble-history-form-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = dir.join("sheet.toml");
    std::fs::write(&source, SHEET.replace("INTEGRATOR", "symplectic-euler")).unwrap();
    let mut app = App::new(
        tumble::scene::load(&source).unwrap(),
        Options {
            ascii: true,
            compare: None,
            show_timing: false,
        },
    );
    app.prefs.write_dir = dir.clone();
    app.step_frames(10);
    typed(&mut app, "e");
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("e opens the form");
    };
    // restitution, friction, mass, size ×3 (the box's sides), dt, x₀ ×3, axis ×3, angle,
    // v₀ ×3, ω₀ ×3, g ×3, drag ×2, then the cloth's integrator, stretch, shear and bend.
    assert_eq!(form.fields.len(), 29);
    assert_eq!(form.label(&form.fields[25]).0, "cloth sheet integrator");
    for _ in 0..4 {
        press(&mut app, KeyCode::Up);
    }
    typed(&mut app, "implicit-eulr");
    press(&mut app, KeyCode::Enter);
    let Overlay::Settings(form) = &app.ui.overlay else {
        panic!("a bad name keeps the form open");
    };
    assert!(
        form.error
            .as_deref()
            .unwrap()
            .contains("(did you mean `implicit-euler`?)"),
        "{:?}",
        form.error
    );
    press(&mut app, KeyCode::Backspace);
    typed(&mut app, "er");
    let Some(effect) = app.update(tumble::tui::keys::Message::WriteScene) else {
        panic!("W asks for a write");
    };
    let Effect::WriteScene { to, .. } = &effect else {
        panic!("W writes a scene");
    };
    let to = to.clone();
    app.perform(effect);
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.ui.overlay, Overlay::None);
    assert_eq!(app.session.world.step_count(), 0, "restarted at t = 0");
    assert_eq!(
        app.session.world.cloths()[0].integrator,
        ClothIntegrator::ImplicitEuler
    );
    assert_eq!(
        app.ui.notice.as_deref(),
        Some(
            "settings applied (cloth sheet symplectic-euler → implicit-euler): the scene \
             restarted at t = 0"
        )
    );
    let written = tumble::scene::load(&to).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        written.scene.cloths[0].integrator,
        ClothIntegrator::ImplicitEuler
    );
    assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .arg("check")
        .arg(&to)
        .assert()
        .code(0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lesson_18_in_the_form_past_the_limit_then_implicit_at_ten_times() {
    // The fixture sheet runs symplectic-euler at 1.1 × 2/ω_max (2/ω_max = 1.3047e-3 s): the
    // guard stops it. The form's values — implicit-euler at dt = 10 × 1.3047e-3 s — run
    // without divergence over the same simulated time.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/cloth/sheet-alone.toml");
    let lesson = tumble::scene::load(&path).unwrap();
    let mut world = lesson.scene.world();
    let limit = world.cloth_limit(0).dt();
    assert!((world.dt() / limit - 1.1).abs() < 1e-3);
    let steps = (0..2000).find(|_| {
        world.step();
        world.divergence().is_some()
    });
    assert!(steps.is_some(), "symplectic-euler past its limit diverges");
    let mut form =
        tumble::tui::settings_form::SettingsForm::new(tumble::scene::SceneEdits::of(&lesson.scene));
    let dt = form
        .fields
        .iter()
        .position(|f| f.kind == tumble::tui::settings_form::FieldKind::Dt)
        .unwrap();
    form.selected = dt;
    for c in format!("{}", 10.0 * limit).chars() {
        form.type_char(c);
    }
    form.selected = form
        .fields
        .iter()
        .position(|f| f.kind == tumble::tui::settings_form::FieldKind::ClothIntegrator(0))
        .unwrap();
    form.fresh = true;
    for c in "implicit-euler".chars() {
        form.type_char(c);
    }
    let scene = form.edits().unwrap().apply(&lesson.scene).unwrap();
    let mut world = scene.world();
    assert_eq!(world.cloths()[0].integrator, ClothIntegrator::ImplicitEuler);
    for _ in 0..200 {
        world.step();
        assert!(world.divergence().is_none(), "{:?}", world.divergence());
    }
}

#[test]
fn a_switch_of_particle_integrator_mid_segment_is_replayed_with_the_old_one() {
    // 30 frames symplectic, then implicit: K is far above 30, so without the break the frames
    // after the switch would be rebuilt from frame 0 with the integrator the checkpoint holds.
    let mut world = lesson(ClothIntegrator::SymplecticEuler).scene.world();
    let mut history = History::new(DEFAULT_CAPACITY);
    let mut kept = Vec::new();
    for frame in 0..40 {
        if frame == 30 {
            world.set_cloth_integrator(0, ClothIntegrator::ImplicitEuler);
            history.break_segment();
        }
        history.push(world.state().position, &world, None);
        kept.push(bits(&world));
        world.step();
    }
    assert!(history.interval() > 40);
    assert_eq!(history.keyframes(), 2, "frames 0 and 30");
    for back in [3, 12, 25] {
        let mut w = world.clone();
        let mut h = history.clone();
        h.pop_frames_into(back, &mut w, None).unwrap();
        assert_eq!(w.step_count(), 40 - back as u64);
        assert_eq!(bits(&w), kept[40 - back], "{back} frames back");
    }
}
