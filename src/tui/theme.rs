//! The app's colours and text styles, in one place: every pane takes its colours from here, so
//! the ghost (compare world) has one colour everywhere, and the SVG export
//! ([`super::export`]) maps the same names to the same RGB values as the terminal.

use ratatui::style::{Color, Modifier, Style};

/// The body's edges and points, and its barycenter `@`.
pub const BODY: Color = Color::White;
/// Bodies other than the one the panels show.
pub const OTHER_BODY: Color = Color::LightCyan;
/// The body's hidden edges (behind the body, seen from the view direction): dimmed and dashed.
pub const HIDDEN: Color = Color::DarkGray;
/// The compare world (ghost body, its numbers, its energy curve).
pub const GHOST: Color = Color::Magenta;
/// Sphere and box obstacles.
pub const OBSTACLE: Color = Color::Blue;
/// The ground line.
pub const GROUND: Color = Color::Green;
/// Contact points of the last collide phase.
pub const CONTACT: Color = Color::Red;
/// The barycenter trail.
pub const TRAIL: Color = Color::DarkGray;
/// The body axes x, y, z (body frame, drawn from the barycenter).
pub const AXES: [Color; 3] = [Color::LightRed, Color::LightGreen, Color::LightBlue];
/// The angular velocity arrow ω.
pub const OMEGA: Color = Color::Yellow;
/// The angular momentum arrow L.
pub const MOMENTUM: Color = Color::Cyan;
/// Mass points of a `points` body.
pub const MASS_POINT: Color = Color::LightYellow;
/// A cloth's grid: the springs between neighbouring particles along x and z.
pub const CLOTH: Color = Color::LightGreen;
/// A cloth's pinned particles (held in place), drawn as `x`.
pub const PINNED: Color = Color::LightRed;
/// Joints: a pivot `o` at each anchor, the rods (distance joints, and from each body's
/// barycenter to its anchor), a hinge's axis.
pub const JOINT: Color = Color::Gray;
/// Springs, drawn as a zigzag between their ends.
pub const SPRING: Color = Color::LightMagenta;
/// The force arrows (key `F`): gravity, contacts, joint reactions, springs.
pub const FORCE_GRAVITY: Color = Color::LightYellow;
pub const FORCE_CONTACT: Color = Color::LightRed;
pub const FORCE_JOINT: Color = Color::LightBlue;
pub const FORCE_SPRING: Color = Color::LightMagenta;
/// The hand (the mouse's drag spring) and its pull.
pub const HAND: Color = Color::LightCyan;

/// Row labels of the numeric panels.
pub const LABEL: Style = Style::new().fg(Color::Cyan);
/// Units, legends and other secondary text.
pub const DIM: Style = Style::new().fg(Color::DarkGray);
/// A number changed by the last action.
pub const CHANGED: Style = Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD);
/// The ghost's numbers.
pub const GHOST_TEXT: Style = Style::new().fg(GHOST);
/// Panel titles.
pub const TITLE: Style = Style::new().add_modifier(Modifier::BOLD);
/// A notice in the status line.
pub const NOTICE: Style = Style::new().fg(Color::Yellow);
/// Key names in the status bar.
pub const KEY: Style = Style::new().fg(Color::Black).bg(Color::Gray);
/// Formulas in the loop strip.
pub const FORMULA: Style = Style::new().fg(Color::Cyan);

/// Header badges: the app's name, and whether it runs, is paused or diverged.
pub const BRAND: Style = Style::new().fg(Color::Black).bg(Color::Cyan);
pub const RUNNING: Style = Style::new().fg(Color::Black).bg(Color::Green);
pub const PAUSED: Style = Style::new().fg(Color::Black).bg(Color::Yellow);
pub const DIVERGED: Style = Style::new().fg(Color::White).bg(Color::Red);
/// Secondary text that must stay readable (the lesson summary, the phases not run).
pub const SOFT: Style = Style::new().fg(Color::Gray);
/// A highlighted line or the phase just run: black on yellow, bold.
pub const SELECTED: Style = Style::new()
    .fg(Color::Black)
    .bg(Color::Yellow)
    .add_modifier(Modifier::BOLD);
/// Keys in the help overlay, the phase to come, the "enlarge" message.
pub const ACCENT: Style = Style::new().fg(Color::Yellow);
/// Borders of overlays: help (accent), lesson picker, divergence dialog (error).
pub const PICKER_BORDER: Style = Style::new().fg(Color::Cyan);
pub const ERROR: Style = Style::new().fg(Color::Red);
/// The loop strip's title.
pub const STRIP_TITLE: Style = Style::new().fg(Color::White).add_modifier(Modifier::BOLD);
/// The study's progress gauge and frontier marks.
pub const GAUGE: Style = Style::new().fg(Color::Cyan);
pub const FRONTIER: Style = Style::new().fg(Color::White);

/// Energy curves.
pub const KINETIC: Color = Color::Green;
pub const POTENTIAL: Color = Color::Blue;
pub const TOTAL: Color = Color::White;
pub const DRIFT: Color = Color::Red;
/// Axes of the charts.
pub const CHART_AXIS: Style = Style::new().fg(Color::Gray);

/// The terminal colours as RGB (xterm's default palette), for the SVG export: `None` is the
/// default colour (`Reset`).
pub fn rgb(colour: Color) -> Option<(u8, u8, u8)> {
    Some(match colour {
        Color::Reset => return None,
        Color::Black => (0, 0, 0),
        Color::Red => (205, 0, 0),
        Color::Green => (0, 205, 0),
        Color::Yellow => (205, 205, 0),
        Color::Blue => (59, 120, 255),
        Color::Magenta => (205, 0, 205),
        Color::Cyan => (0, 205, 205),
        Color::Gray => (229, 229, 229),
        Color::DarkGray => (127, 127, 127),
        Color::LightRed => (255, 85, 85),
        Color::LightGreen => (85, 255, 85),
        Color::LightYellow => (255, 255, 85),
        Color::LightBlue => (92, 150, 255),
        Color::LightMagenta => (255, 85, 255),
        Color::LightCyan => (85, 255, 255),
        Color::White => (255, 255, 255),
        Color::Rgb(r, g, b) => (r, g, b),
        Color::Indexed(i) => indexed(i),
    })
}

/// The 256-colour palette: 16 system colours, the 6×6×6 cube, 24 greys.
fn indexed(i: u8) -> (u8, u8, u8) {
    const SYSTEM: [Color; 16] = [
        Color::Black,
        Color::Red,
        Color::Green,
        Color::Yellow,
        Color::Blue,
        Color::Magenta,
        Color::Cyan,
        Color::Gray,
        Color::DarkGray,
        Color::LightRed,
        Color::LightGreen,
        Color::LightYellow,
        Color::LightBlue,
        Color::LightMagenta,
        Color::LightCyan,
        Color::White,
    ];
    match i {
        0..=15 => rgb(SYSTEM[usize::from(i)]).unwrap_or((0, 0, 0)),
        16..=231 => {
            let level = |v: u8| if v == 0 { 0 } else { 55 + 40 * v };
            let j = i - 16;
            (level(j / 36), level(j / 6 % 6), level(j % 6))
        }
        _ => {
            let g = 8 + 10 * (i - 232);
            (g, g, g)
        }
    }
}
