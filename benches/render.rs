//! Rendering one full frame of the terminal app at 160×50 into a `TestBackend` (target < 1 ms),
//! and the same with a 30 × 30 cloth (900 particles, 1740 grid segments) under a cube.

use criterion::{criterion_group, criterion_main, Criterion};
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::hint::black_box;
use std::path::Path;
use tumble::tui::{App, Comparison, Options};

fn app(ascii: bool, compare: Option<Comparison>) -> App {
    app_of("tui-box.toml", ascii, compare)
}

fn app_of(fixture: &str, ascii: bool, compare: Option<Comparison>) -> App {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(fixture);
    let lesson = tumble::scene::load(&path).expect("fixture loads");
    let mut app = App::new(
        lesson,
        Options {
            ascii,
            compare,
            show_timing: true,
        },
    );
    // Some history (trail) and a mid-frame state.
    app.step_frames(200);
    app.step_phase();
    app
}

fn render(c: &mut Criterion) {
    let mut group = c.benchmark_group("render_160x50");
    for (name, app) in [
        ("braille", app(false, None)),
        ("ascii", app(true, None)),
        (
            "braille_compare",
            app(
                false,
                Some(Comparison::Integrator(
                    tumble::physics::Integrator::EulerSeed,
                )),
            ),
        ),
        (
            "braille_cloth_30x30",
            app_of("tui-cloth-30x30.toml", false, None),
        ),
        (
            "ascii_cloth_30x30",
            app_of("tui-cloth-30x30.toml", true, None),
        ),
    ] {
        let mut terminal = Terminal::new(TestBackend::new(160, 50)).unwrap();
        group.bench_function(name, |b| {
            b.iter(|| {
                terminal
                    .draw(|f| f.render_widget(black_box(&app), f.area()))
                    .unwrap();
            })
        });
    }
    // The widget alone, into a reused buffer (no terminal diff).
    let app = app(false, None);
    let area = ratatui::layout::Rect::new(0, 0, 160, 50);
    let mut buf = ratatui::buffer::Buffer::empty(area);
    group.bench_function("braille_widget_only", |b| {
        b.iter(|| {
            buf.reset();
            ratatui::widgets::Widget::render(black_box(&app), area, &mut buf);
        })
    });
    group.finish();
}

criterion_group!(benches, render);
criterion_main!(benches);
