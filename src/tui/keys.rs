//! The key table: every binding with its status-bar hint and its help line. The status bar and
//! the help overlay are both generated from [`KEYS`], so they can never drift from what the keys
//! really do.

use crossterm::event::{KeyCode, KeyEvent, KeyEventKind, KeyModifiers};

/// What a key asks the app to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message {
    TogglePause,
    StepFrame,
    StepPhase,
    StepBack,
    Faster,
    Slower,
    Reset,
    NextIntegrator,
    NextResponse,
    NextCompare,
    NextAxis,
    ToggleFrame,
    ToggleTrail,
    ToggleEnergy,
    ToggleStudy,
    OpenPicker,
    ScrollUp,
    ScrollDown,
    ToggleHelp,
    Quit,
    PickerUp,
    PickerDown,
    PickerOpen,
    Close,
    ToggleArrows,
    NextLayout,
    ExportSvg,
}

/// Where a binding applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Context {
    /// The main screen (also under the help overlay and the divergence dialog).
    Main,
    /// The lesson picker.
    Picker,
}

/// One row of the key table.
#[derive(Debug, Clone, Copy)]
pub struct Binding {
    /// Keys that trigger it (any of them).
    pub keys: &'static [KeyCode],
    /// How the keys are written, e.g. `→ .`.
    pub label: &'static str,
    /// The status bar's hint, key first (empty: not in the bar).
    pub hint: &'static str,
    /// What the help overlay says.
    pub help: &'static str,
    pub message: Message,
    pub context: Context,
}

const fn bind(
    keys: &'static [KeyCode],
    label: &'static str,
    hint: &'static str,
    help: &'static str,
    message: Message,
) -> Binding {
    Binding {
        keys,
        label,
        hint,
        help,
        message,
        context: Context::Main,
    }
}

const fn pick(
    keys: &'static [KeyCode],
    label: &'static str,
    help: &'static str,
    message: Message,
) -> Binding {
    Binding {
        keys,
        label,
        hint: "",
        help,
        message,
        context: Context::Picker,
    }
}

use KeyCode::{Char, Down, Enter, Esc, Left, PageDown, PageUp, Right, Up};

/// Every binding, in the order the status bar and the help overlay list them.
pub const KEYS: &[Binding] = &[
    bind(
        &[Char('?')],
        "?",
        "? help",
        "help: this list of keys",
        Message::ToggleHelp,
    ),
    bind(
        &[Char('q'), Esc],
        "q Esc",
        "q quit",
        "quit (also Ctrl-C)",
        Message::Quit,
    ),
    bind(
        &[Char(' ')],
        "space",
        "space run",
        "run / pause",
        Message::TogglePause,
    ),
    bind(
        &[Right, Char('.')],
        "→ .",
        "→ frame",
        "one frame (all four phases)",
        Message::StepFrame,
    ),
    bind(
        &[Char('n')],
        "n",
        "n phase",
        "one phase: derive → forces → integrate → collide",
        Message::StepPhase,
    ),
    bind(
        &[Left, Char(',')],
        "← ,",
        "← back",
        "one frame back (exact saved state)",
        Message::StepBack,
    ),
    bind(
        &[Char('+'), Char('=')],
        "+",
        "+/- speed",
        "faster (up to faster than real time)",
        Message::Faster,
    ),
    bind(
        &[Char('-'), Char('_')],
        "-",
        "",
        "slower (down to one frame per second)",
        Message::Slower,
    ),
    bind(
        &[Char('r')],
        "r",
        "r reset",
        "reset to t = 0",
        Message::Reset,
    ),
    bind(
        &[Char('i')],
        "i",
        "i integrator",
        "next integrator (keeps t and the state)",
        Message::NextIntegrator,
    ),
    bind(
        &[Char('c')],
        "c",
        "c response",
        "next collision response",
        Message::NextResponse,
    ),
    bind(
        &[Char('k')],
        "k",
        "k compare",
        "compare: cycle the ghost's integrator or response, then off",
        Message::NextCompare,
    ),
    bind(
        &[Char('v')],
        "v",
        "v view",
        "next view: front x–y, side z–y, top x–z",
        Message::NextAxis,
    ),
    bind(
        &[Char('f')],
        "f",
        "f body/world",
        "numbers in the body or the world frame",
        Message::ToggleFrame,
    ),
    bind(
        &[Char('t')],
        "t",
        "",
        "barycenter trail on / off",
        Message::ToggleTrail,
    ),
    bind(
        &[Char('g')],
        "g",
        "g graph",
        "energy graph: kinetic, potential, total, drift",
        Message::ToggleEnergy,
    ),
    bind(
        &[Char('s')],
        "s",
        "",
        "study: error against cost of every integrator × dt on this scene (runs in the background)",
        Message::ToggleStudy,
    ),
    bind(
        &[Char('l')],
        "l",
        "l lessons",
        "lesson picker",
        Message::OpenPicker,
    ),
    bind(
        &[Char('a')],
        "a",
        "a arrows",
        "body axes and the ω and L arrows on / off",
        Message::ToggleArrows,
    ),
    bind(
        &[Char('L')],
        "L",
        "L layout",
        "layout: all the numbers, or a large drawing with the essential numbers",
        Message::NextLayout,
    ),
    bind(
        &[Char('x')],
        "x",
        "x svg",
        "export the screen as SVG (tumble-<lesson>-t<time>.svg in the current folder)",
        Message::ExportSvg,
    ),
    bind(
        &[PageUp, Char('[')],
        "PgUp [",
        "",
        "scroll the lesson page up",
        Message::ScrollUp,
    ),
    bind(
        &[PageDown, Char(']')],
        "PgDn ]",
        "",
        "scroll the lesson page down",
        Message::ScrollDown,
    ),
    pick(
        &[Up, Char('k')],
        "↑",
        "lesson picker: previous lesson",
        Message::PickerUp,
    ),
    pick(
        &[Down, Char('j')],
        "↓",
        "lesson picker: next lesson",
        Message::PickerDown,
    ),
    pick(
        &[Enter],
        "Enter",
        "lesson picker: open the lesson",
        Message::PickerOpen,
    ),
    pick(
        &[Esc, Char('q'), Char('l')],
        "Esc",
        "lesson picker: close",
        Message::Close,
    ),
];

/// The message a key event sends in a context (None: unbound, or not a key press).
pub fn message(event: &KeyEvent, context: Context) -> Option<Message> {
    if event.kind != KeyEventKind::Press {
        return None;
    }
    if event.modifiers.contains(KeyModifiers::CONTROL) {
        return (event.code == Char('c')).then_some(Message::Quit);
    }
    KEYS.iter()
        .filter(|b| b.context == context)
        .find(|b| b.keys.contains(&event.code))
        .map(|b| b.message)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_key_is_bound_twice_in_one_context() {
        for (i, a) in KEYS.iter().enumerate() {
            for b in &KEYS[i + 1..] {
                if a.context == b.context {
                    for key in a.keys {
                        assert!(
                            !b.keys.contains(key),
                            "{key:?} bound to {:?} and {:?}",
                            a.message,
                            b.message
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn s_opens_the_study_view() {
        let study: Vec<_> = KEYS
            .iter()
            .filter(|b| b.keys.contains(&Char('s')))
            .collect();
        assert_eq!(study.len(), 1);
        assert_eq!(study[0].message, Message::ToggleStudy);
    }
}
