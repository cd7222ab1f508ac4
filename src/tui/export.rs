//! Pictures for slides and handouts, rendered headlessly (ratatui's `TestBackend`, no
//! terminal): the screen as SVG (key `x`, `tumble shot`) and a run as an asciicast v2 recording
//! (`tumble record`), the format terminal players and GIF converters read.
//!
//! SVG: one monospace grid of [`CELL_WIDTH`] × [`CELL_HEIGHT`] px cells; text stays text (one
//! `<text>` per run of cells of one style, stretched to its cells so the grid holds whatever
//! the font), colours as in the terminal ([`theme::rgb`]).
//!
//! asciicast v2: a header line `{"version": 2, "width": …, "height": …, …}`, then one event
//! `[time, "o", data]` per frame, `data` the whole frame as ANSI text (cursor home, SGR
//! colours), times increasing by 1/fps.

use super::app::App;
use super::theme;
use ratatui::backend::TestBackend;
use ratatui::buffer::{Buffer, Cell};
use ratatui::style::{Color, Modifier};
use ratatui::text::Span;
use ratatui::Terminal;
use std::fmt::Write as _;

/// Width of a cell in the SVG, px (a 14 px monospace font's advance).
pub const CELL_WIDTH: f64 = 8.4;
/// Height of a cell in the SVG, px.
pub const CELL_HEIGHT: f64 = 17.0;
/// Font size in the SVG, px.
pub const FONT_SIZE: f64 = 14.0;
/// The terminal's default colours in the SVG (a dark theme).
pub const BACKGROUND: (u8, u8, u8) = (24, 24, 24);
pub const FOREGROUND: (u8, u8, u8) = (210, 210, 210);
/// Frames per second of a recording.
pub const CAST_FPS: f64 = 30.0;

/// The app's screen at `width × height`, as the terminal would show it.
pub fn render(app: &App, width: u16, height: u16) -> Buffer {
    let mut terminal =
        Terminal::new(TestBackend::new(width, height)).expect("a test backend never fails");
    terminal
        .draw(|frame| frame.render_widget(app, frame.area()))
        .expect("a test backend never fails");
    terminal.backend().buffer().clone()
}

/// A cell's display width (a wide character covers the next cell too).
fn symbol_width(symbol: &str) -> usize {
    Span::raw(symbol).width().max(1)
}

fn hex((r, g, b): (u8, u8, u8)) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if (c as u32) < 0x20 => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// An RGB colour.
type Rgb = (u8, u8, u8);

/// Foreground and background of a cell, reversed video applied, defaults resolved (no
/// background: the terminal's).
fn colours(cell: &Cell) -> (Rgb, Option<Rgb>) {
    let fg = theme::rgb(cell.fg).unwrap_or(FOREGROUND);
    let bg = theme::rgb(cell.bg);
    if cell.modifier.contains(Modifier::REVERSED) {
        (bg.unwrap_or(BACKGROUND), Some(fg))
    } else {
        (fg, bg)
    }
}

/// One run of cells with the same style on a row.
struct Run {
    col: usize,
    cells: usize,
    text: String,
    fg: (u8, u8, u8),
    bg: Option<(u8, u8, u8)>,
    modifier: Modifier,
}

fn runs(buf: &Buffer, row: u16) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    let width = usize::from(buf.area.width);
    let mut x = 0usize;
    // A wide character gets a run of its own, covering its cells.
    let mut last_wide = false;
    while x < width {
        let cell = &buf[(buf.area.x + x as u16, buf.area.y + row)];
        let symbol = cell.symbol();
        let w = symbol_width(symbol).min(width - x);
        let (fg, bg) = colours(cell);
        let modifier = cell.modifier;
        match runs.last_mut() {
            Some(r)
                if r.fg == fg && r.bg == bg && r.modifier == modifier && w == 1 && !last_wide =>
            {
                r.cells += 1;
                r.text.push_str(symbol);
            }
            _ => runs.push(Run {
                col: x,
                cells: w,
                text: symbol.to_string(),
                fg,
                bg,
                modifier,
            }),
        }
        last_wide = w > 1;
        x += w;
    }
    runs.retain(|r| r.cells > 0);
    runs
}

/// A buffer as an SVG document (text as text, colours as in the terminal).
pub fn svg(buf: &Buffer) -> String {
    let (w, h) = (buf.area.width, buf.area.height);
    let (pw, ph) = (f64::from(w) * CELL_WIDTH, f64::from(h) * CELL_HEIGHT);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{pw:.1}" height="{ph:.1}" viewBox="0 0 {pw:.1} {ph:.1}" font-family="DejaVu Sans Mono, Menlo, Consolas, monospace" font-size="{FONT_SIZE}" xml:space="preserve">"#
    );
    let _ = writeln!(
        out,
        r#"<rect width="100%" height="100%" fill="{}"/>"#,
        hex(BACKGROUND)
    );
    for row in 0..h {
        let y = f64::from(row) * CELL_HEIGHT;
        for run in runs(buf, row) {
            let x = run.col as f64 * CELL_WIDTH;
            let width = run.cells as f64 * CELL_WIDTH;
            if let Some(bg) = run.bg {
                let _ = writeln!(
                    out,
                    r#"<rect x="{x:.1}" y="{y:.1}" width="{width:.1}" height="{CELL_HEIGHT:.1}" fill="{}"/>"#,
                    hex(bg)
                );
            }
            if run.text.trim().is_empty() {
                continue;
            }
            let mut attributes = format!(r#" fill="{}""#, hex(run.fg));
            if run.modifier.contains(Modifier::BOLD) {
                attributes.push_str(r#" font-weight="bold""#);
            }
            if run.modifier.contains(Modifier::DIM) {
                attributes.push_str(r#" opacity="0.6""#);
            }
            if run.modifier.contains(Modifier::ITALIC) {
                attributes.push_str(r#" font-style="italic""#);
            }
            if run.modifier.contains(Modifier::UNDERLINED) {
                attributes.push_str(r#" text-decoration="underline""#);
            }
            let _ = writeln!(
                out,
                r#"<text x="{x:.1}" y="{:.1}" textLength="{width:.1}" lengthAdjust="spacingAndGlyphs"{attributes}>{}</text>"#,
                y + 0.78 * CELL_HEIGHT,
                escape(&run.text)
            );
        }
    }
    out.push_str("</svg>\n");
    out
}

/// The SGR parameters of a colour (`base` 30 for foreground, 40 for background).
fn sgr_colour(colour: Color, base: u8) -> String {
    let system = |i: u8| (base + i).to_string();
    let bright = |i: u8| (base + 60 + i).to_string();
    match colour {
        Color::Reset => (base + 9).to_string(),
        Color::Black => system(0),
        Color::Red => system(1),
        Color::Green => system(2),
        Color::Yellow => system(3),
        Color::Blue => system(4),
        Color::Magenta => system(5),
        Color::Cyan => system(6),
        Color::Gray => system(7),
        Color::DarkGray => bright(0),
        Color::LightRed => bright(1),
        Color::LightGreen => bright(2),
        Color::LightYellow => bright(3),
        Color::LightBlue => bright(4),
        Color::LightMagenta => bright(5),
        Color::LightCyan => bright(6),
        Color::White => bright(7),
        Color::Rgb(r, g, b) => format!("{};2;{r};{g};{b}", base + 8),
        Color::Indexed(i) => format!("{};5;{i}", base + 8),
    }
}

/// A buffer as one ANSI frame: cursor home, then each row with SGR colours, rows joined by
/// CR LF, attributes reset at the end.
pub fn ansi(buf: &Buffer) -> String {
    let mut out = String::from("\x1b[H");
    let width = usize::from(buf.area.width);
    for row in 0..buf.area.height {
        if row > 0 {
            out.push_str("\r\n");
        }
        let mut current: Option<(Color, Color, Modifier)> = None;
        let mut x = 0usize;
        while x < width {
            let cell = &buf[(buf.area.x + x as u16, buf.area.y + row)];
            let style = (cell.fg, cell.bg, cell.modifier);
            if current != Some(style) {
                let mut codes = vec!["0".to_string()];
                for (m, code) in [
                    (Modifier::BOLD, "1"),
                    (Modifier::DIM, "2"),
                    (Modifier::ITALIC, "3"),
                    (Modifier::UNDERLINED, "4"),
                    (Modifier::REVERSED, "7"),
                ] {
                    if cell.modifier.contains(m) {
                        codes.push(code.to_string());
                    }
                }
                codes.push(sgr_colour(cell.fg, 30));
                codes.push(sgr_colour(cell.bg, 40));
                let _ = write!(out, "\x1b[{}m", codes.join(";"));
                current = Some(style);
            }
            out.push_str(cell.symbol());
            x += symbol_width(cell.symbol());
        }
    }
    out.push_str("\x1b[0m");
    out
}

/// A file name for the current screen: `tumble-<lesson>-t<time>.svg` (time in s, 3 decimals).
pub fn screen_file_name(app: &App) -> String {
    let stem = app
        .session
        .lesson
        .path
        .file_stem()
        .map_or_else(|| "scene".to_string(), |s| s.to_string_lossy().into_owned());
    format!("tumble-{stem}-t{:.3}.svg", app.session.snapshot.time)
}

/// Writes the screen as SVG in the current folder (key `x`); returns the line for the status
/// bar saying where it went, or why it could not.
pub fn save_screen(app: &App, width: u16, height: u16) -> String {
    let name = screen_file_name(app);
    let picture = svg(&render(app, width, height));
    match std::fs::write(&name, picture) {
        Ok(()) => format!("wrote {name} ({width}×{height})"),
        Err(e) => format!("could not write {name}: {e}"),
    }
}

/// Runs the app for `duration` simulated seconds at its speed (real time unless changed),
/// one frame every 1/[`CAST_FPS`] s, and returns the asciicast v2 recording (header line, then
/// one event per frame). Stops early at a divergence.
pub fn record(app: &mut App, duration: f64, width: u16, height: u16) -> String {
    let header = serde_json::json!({
        "version": 2,
        "width": width,
        "height": height,
        "title": format!("tumble — {}", app.session.lesson.title),
        "env": { "TERM": "xterm-256color" },
    });
    let mut out = header.to_string();
    out.push('\n');
    let event = |out: &mut String, frame: u64, data: String| {
        let t = (frame as f64 / CAST_FPS * 1e6).round() / 1e6;
        out.push_str(&serde_json::json!([t, "o", data]).to_string());
        out.push('\n');
    };
    // The recording runs on through pages (a pause would freeze the picture while the
    // header said "paused … Enter continues" and the time kept going).
    app.ui.running = true;
    app.ui.pause_at_stops = false;
    let first = format!("\x1b[2J{}", ansi(&render(app, width, height)));
    event(&mut out, 0, first);
    let mut pending = 0.0;
    let mut frame = 0u64;
    let end = duration - 0.5 * app.session.snapshot.dt;
    while app.session.snapshot.time < end && app.session.divergence.is_none() {
        pending += app.frames_per_second() / CAST_FPS;
        let left = ((duration - app.session.snapshot.time) / app.session.snapshot.dt)
            .round()
            .max(1.0);
        let steps = pending.floor().min(left) as u64;
        pending -= steps as f64;
        if steps > 0 {
            let before = app.session.snapshot.time;
            app.step_frames(steps);
            if app.session.snapshot.time <= before && app.session.divergence.is_none() {
                break;
            }
        }
        frame += 1;
        if app.session.snapshot.time >= end || app.session.divergence.is_some() {
            app.ui.running = false;
        }
        event(&mut out, frame, ansi(&render(app, width, height)));
    }
    out
}

/// Parses `COLSxROWS` (e.g. `120x40`), at least 80×24 (the app's smallest screen), at most
/// the bounds of [`crate::limits::screen`].
pub fn parse_size(text: &str) -> Result<(u16, u16), String> {
    let bad = || format!("size must be COLSxROWS, e.g. 120x40, found `{text}`");
    let (c, r) = text.split_once(['x', 'X', '×']).ok_or_else(bad)?;
    // Any run of digits is a size (past u64, larger than any limit): a size over the limits
    // is refused by them, naming them, not called malformed.
    let number = |t: &str| {
        let t = t.trim();
        (!t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()))
            .then(|| t.parse::<u64>().unwrap_or(u64::MAX))
            .ok_or_else(bad)
    };
    let (cols, rows) = (number(c)?, number(r)?);
    crate::limits::screen(cols, rows)
        .map_err(|e| e.replace(&format!("{cols}x{rows}"), text.trim()))?;
    // Within MAX_SIDE (4000): both fit in u16.
    let (cols, rows) = (cols as u16, rows as u16);
    if cols < super::screen::MIN_WIDTH || rows < super::screen::MIN_HEIGHT {
        return Err(format!(
            "size {cols}x{rows} is below the app's smallest screen, {}x{}",
            super::screen::MIN_WIDTH,
            super::screen::MIN_HEIGHT
        ));
    }
    Ok((cols, rows))
}
