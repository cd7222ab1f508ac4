//! The key table: every binding with its status-bar hint and its help line. The status bar and
//! the help overlay are both generated from [`KEYS`], so they can never drift from what the keys
//! really do.

use super::tools::ToolKey;
use super::views;
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
    /// Tab: the next body in the panels (scenes with several bodies).
    NextBody,
    NextCompare,
    NextAxis,
    ToggleFrame,
    ToggleTrail,
    /// A view's key (its row in `views.rs`): shows it, or (shown) the loop view.
    ToggleView(super::views::View),
    /// `u`: the measured error (±) under each number of the panels.
    ToggleErrors,
    OpenPicker,
    ScrollUp,
    ScrollDown,
    /// `{` `}`: the page's long formula and table lines, sideways.
    ScrollLeft,
    ScrollRight,
    ToggleHelp,
    Quit,
    PickerUp,
    PickerDown,
    PickerOpen,
    Close,
    ToggleArrows,
    /// `F`: the force arrows.
    ToggleForces,
    NextLayout,
    ExportSvg,
    /// Esc: closes the innermost window (help, picker, form, prompt), else the graph or the
    /// study; never quits.
    Back,
    /// Enter on the main screen: run on after a pause (at a page or the scene's end).
    Continue,
    /// `J`: the prompt for a time to jump to.
    OpenJump,
    /// `e`: the settings form.
    OpenSettings,
    /// `W`: write the scene (as run, or as in the form) to a TOML file.
    WriteScene,
    /// A character typed into the form or the prompt (the key table binds a placeholder; the
    /// character is the key's).
    Type(char),
    /// Backspace in the form or the prompt.
    Erase,
    /// Previous / next field of the form.
    FieldUp,
    FieldDown,
    /// Enter in the form (apply and restart) or the prompt (jump).
    Submit,
    /// `p`: the quantity picker for the graph of any quantity.
    OpenPlot,
    /// In the quantity picker: graph the selected quantity (against the horizontal axis
    /// chosen, time unless `x` chose one).
    PlotY,
    /// In the quantity picker: the selected quantity becomes the horizontal axis (a phase
    /// portrait once the vertical one is picked).
    PlotAsX,
    /// In the quantity picker: the horizontal axis is time again.
    PlotAgainstTime,
    /// In the quantity picker: the selected quantity joins the graph shown as another curve
    /// (or, on the graph already, leaves it).
    PlotAdd,
    /// `X`: what the graph shown plots, as CSV.
    ExportCsv,
    /// The measuring tools' keys (`w` `o` `O` `T` `m` `M` `A` `V`: `tools.rs`).
    Tool(ToolKey),
    /// `z` / `Z`: the drawing larger / smaller, about its centre (the wheel zooms about the
    /// pointer).
    ZoomIn,
    ZoomOut,
    /// A mouse event (never from the key table: see `mouse::message`).
    Mouse(super::mouse::Mouse),
}

/// Where a binding applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Context {
    /// The main screen (also under the help overlay and the divergence dialog).
    Main,
    /// The lesson picker.
    Picker,
    /// The settings form (`e`).
    Form,
    /// The jump-to-time prompt (`J`).
    Prompt,
    /// The quantity picker of the graph (`p`).
    PlotPicker,
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
    within(Context::Picker, keys, label, help, message)
}

const fn within(
    context: Context,
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
        context,
    }
}

/// The characters a value is typed with: numbers (with exponents, `1e-4`) and names.
const VALUE_KEYS: &[KeyCode] = &[
    Char('0'),
    Char('1'),
    Char('2'),
    Char('3'),
    Char('4'),
    Char('5'),
    Char('6'),
    Char('7'),
    Char('8'),
    Char('9'),
    Char('.'),
    Char('-'),
    Char('+'),
    Char('e'),
    Char('E'),
    // Names (a cloth's particle integrator): every lowercase letter but `q` (quit).
    Char('a'),
    Char('b'),
    Char('c'),
    Char('d'),
    Char('f'),
    Char('g'),
    Char('h'),
    Char('i'),
    Char('j'),
    Char('k'),
    Char('l'),
    Char('m'),
    Char('n'),
    Char('o'),
    Char('p'),
    Char('r'),
    Char('s'),
    Char('t'),
    Char('u'),
    Char('v'),
    Char('w'),
    Char('x'),
    Char('y'),
    Char('z'),
];

/// The characters a time is typed with.
const TIME_KEYS: &[KeyCode] = &[
    Char('0'),
    Char('1'),
    Char('2'),
    Char('3'),
    Char('4'),
    Char('5'),
    Char('6'),
    Char('7'),
    Char('8'),
    Char('9'),
    Char('.'),
    Char('-'),
    Char('e'),
];

use KeyCode::{Backspace, Char, Down, Enter, Esc, Left, PageDown, PageUp, Right, Tab, Up};

/// Every binding, in the order the status bar and the help overlay list them: the table
/// below with each view's key (`views.rs`) after the row its [`ViewKey::after`] names.
///
/// [`ViewKey::after`]: super::views::ViewKey::after
pub const KEYS: &[Binding] = &ALL;

const ALL: [Binding; TABLE.len() + views::KEY_COUNT] = with_views();

/// [`TABLE`] with the views' keys put in: each after the main-screen row (of the table, or
/// another view's key) labelled its `after`.
const fn with_views<const N: usize>() -> [Binding; N] {
    let mut all = [TABLE[0]; N];
    let (mut i, mut n) = (0, 0);
    while i < TABLE.len() {
        all[n] = TABLE[i];
        n += 1;
        // The row just put in, then the views' keys put in after it, in turn.
        let mut j = n - 1;
        while j < n {
            let mut v = 0;
            while v < views::VIEWS.len() {
                let pane = &views::VIEWS[v];
                if let (Some(key), Some(binding)) = (pane.key, views::binding(pane)) {
                    if same(key.after, all[j].label) && matches!(all[j].context, Context::Main) {
                        all[n] = binding;
                        n += 1;
                    }
                }
                v += 1;
            }
            j += 1;
        }
        i += 1;
    }
    assert!(
        n == N,
        "a view's key is listed after a label the key table lacks"
    );
    all
}

/// Whether two strings are the same (in a constant).
const fn same(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// The key table but the views' keys.
const TABLE: &[Binding] = &[
    bind(
        &[Char('?')],
        "?",
        "? help",
        "help: this list of keys",
        Message::ToggleHelp,
    ),
    bind(
        &[Char('q')],
        "q",
        "q quit",
        "quit (also Ctrl-C), from every window",
        Message::Quit,
    ),
    bind(
        &[Esc],
        "Esc",
        "",
        "close the help, picker, form, graph or study (never quits)",
        Message::Back,
    ),
    bind(
        &[Char(' ')],
        "space",
        "space run",
        "run / pause (a run pauses at each page and at the end)",
        Message::TogglePause,
    ),
    bind(
        &[Enter],
        "Enter",
        "",
        "continue after such a pause",
        Message::Continue,
    ),
    bind(
        &[Char('J')],
        "J",
        "",
        "jump to a typed time (an earlier one is replayed from 0)",
        Message::OpenJump,
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
        &[Tab],
        "Tab",
        "Tab body",
        "next body in the panels (several bodies); the system panel shows them all",
        Message::NextBody,
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
        &[Char('u')],
        "u",
        "",
        "± under each number: its error against a reference run (rk4 at dt/10), and its cost",
        Message::ToggleErrors,
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
        &[Char('F')],
        "F",
        "",
        "force arrows on / off: gravity g, contacts c, joint reactions j, springs s (one scale)",
        Message::ToggleForces,
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
        &[Char('e')],
        "e",
        "e settings",
        "settings of the body Tab picks: g, drag, e, μ, k, motors live; mass, dt, x₀, v₀… restart",
        Message::OpenSettings,
    ),
    bind(
        &[Char('W')],
        "W",
        "",
        "write the scene as it runs to ./NAME-edited.toml",
        Message::WriteScene,
    ),
    bind(
        &[Char('p')],
        "p",
        "p plot",
        "graph any quantity against t, or two against each other (a phase portrait)",
        Message::OpenPlot,
    ),
    bind(
        &[Char('X')],
        "X",
        "",
        "write what the graph plots as CSV (./tumble-LESSON-QUANTITY.csv)",
        Message::ExportCsv,
    ),
    // The measuring tools (`tools.rs`): two help lines, on the first key's binding of each
    // group (the others' help is empty: the help overlay lists a binding only with its text;
    // at 120×40 the overlay's one column is full, 38 rows).
    bind(
        &[Char('w')],
        "w o O",
        "",
        "stopwatch on simulated time: start / stop (w), lap (o), zero and hide (O)",
        Message::Tool(ToolKey::StartStop),
    ),
    bind(&[Char('o')], "o", "", "", Message::Tool(ToolKey::Lap)),
    bind(&[Char('O')], "O", "", "", Message::Tool(ToolKey::Zero)),
    bind(
        &[Char('T')],
        "T m M A V",
        "",
        "period timer (T, of the quantity graphed), ruler ends (m M), protractor (A axis, V against)",
        Message::Tool(ToolKey::Period),
    ),
    bind(&[Char('m')], "m", "", "", Message::Tool(ToolKey::RulerFrom)),
    bind(&[Char('M')], "M", "", "", Message::Tool(ToolKey::RulerTo)),
    bind(&[Char('A')], "A", "", "", Message::Tool(ToolKey::ProtractorAxis)),
    bind(&[Char('V')], "V", "", "", Message::Tool(ToolKey::ProtractorAgainst)),
    bind(
        &[Char('z')],
        "z Z",
        "",
        "zoom in / out (as many Z as z: the fitted view; the wheel zooms about the pointer)",
        Message::ZoomIn,
    ),
    bind(&[Char('Z')], "Z", "", "", Message::ZoomOut),
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
    bind(
        &[Char('{')],
        "{",
        "",
        "scroll the page's cut formula and table lines left (marked …)",
        Message::ScrollLeft,
    ),
    bind(
        &[Char('}')],
        "}",
        "",
        "scroll the page's cut formula and table lines right",
        Message::ScrollRight,
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
        &[Esc, Char('l')],
        "Esc",
        "lesson picker: close",
        Message::Close,
    ),
    pick(&[Char('q')], "q", "quit", Message::Quit),
    within(
        Context::PlotPicker,
        &[Up],
        "↑",
        "plot: previous quantity",
        Message::PickerUp,
    ),
    within(
        Context::PlotPicker,
        &[Down],
        "↓",
        "plot: next quantity",
        Message::PickerDown,
    ),
    within(
        Context::PlotPicker,
        &[Enter],
        "Enter",
        "plot: graph it",
        Message::PlotY,
    ),
    within(
        Context::PlotPicker,
        &[Char('x')],
        "x",
        "plot: make it the horizontal axis (phase portrait)",
        Message::PlotAsX,
    ),
    within(
        Context::PlotPicker,
        &[Char('t')],
        "t",
        "plot: time on the horizontal axis",
        Message::PlotAgainstTime,
    ),
    within(
        Context::PlotPicker,
        &[Char('a'), Char('+')],
        "a",
        "plot: add as another curve (again: remove)",
        Message::PlotAdd,
    ),
    within(
        Context::PlotPicker,
        &[Esc],
        "Esc",
        "plot: close",
        Message::Close,
    ),
    within(
        Context::PlotPicker,
        &[Char('q')],
        "q",
        "quit",
        Message::Quit,
    ),
    within(
        Context::Form,
        &[Up],
        "↑",
        "settings: previous field",
        Message::FieldUp,
    ),
    within(
        Context::Form,
        &[Down],
        "↓",
        "settings: next field",
        Message::FieldDown,
    ),
    within(
        Context::Form,
        VALUE_KEYS,
        "0-9 . - a-z",
        "settings: type a number or a name",
        Message::Type(' '),
    ),
    within(
        Context::Form,
        &[Backspace],
        "Backspace",
        "settings: erase",
        Message::Erase,
    ),
    within(
        Context::Form,
        &[Enter],
        "Enter",
        "settings: apply (~ live, else restart at t = 0)",
        Message::Submit,
    ),
    within(
        Context::Form,
        &[Char('W')],
        "W",
        "settings: write them to a file",
        Message::WriteScene,
    ),
    within(
        Context::Form,
        &[Esc],
        "Esc",
        "settings: close, nothing applied",
        Message::Back,
    ),
    within(Context::Form, &[Char('q')], "q", "quit", Message::Quit),
    within(
        Context::Prompt,
        TIME_KEYS,
        "0-9 . - e",
        "jump: type t in s",
        Message::Type(' '),
    ),
    within(
        Context::Prompt,
        &[Backspace],
        "Backspace",
        "jump: erase",
        Message::Erase,
    ),
    within(
        Context::Prompt,
        &[Enter],
        "Enter",
        "jump: go there",
        Message::Submit,
    ),
    within(
        Context::Prompt,
        &[Esc],
        "Esc",
        "jump: cancel",
        Message::Back,
    ),
    within(Context::Prompt, &[Char('q')], "q", "quit", Message::Quit),
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
        .map(|b| match (b.message, event.code) {
            (Message::Type(_), Char(c)) => Message::Type(c),
            (message, _) => message,
        })
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
    fn esc_never_quits_and_q_always_does() {
        let press = |code| KeyEvent::new(code, KeyModifiers::NONE);
        for context in [
            Context::Main,
            Context::Picker,
            Context::Form,
            Context::Prompt,
            Context::PlotPicker,
        ] {
            let esc = message(&press(Esc), context);
            assert!(
                matches!(esc, Some(Message::Back | Message::Close)),
                "{context:?}: Esc sends {esc:?}"
            );
            assert_eq!(message(&press(Char('q')), context), Some(Message::Quit));
            let ctrl_c = KeyEvent::new(Char('c'), KeyModifiers::CONTROL);
            assert_eq!(message(&ctrl_c, context), Some(Message::Quit));
        }
    }

    #[test]
    fn typed_characters_reach_the_form_and_the_prompt() {
        let press = |c| KeyEvent::new(Char(c), KeyModifiers::NONE);
        assert_eq!(
            message(&press('7'), Context::Form),
            Some(Message::Type('7'))
        );
        assert_eq!(
            message(&press('e'), Context::Form),
            Some(Message::Type('e')),
            "an exponent in the form, not the form key"
        );
        assert_eq!(
            message(&press('e'), Context::Main),
            Some(Message::OpenSettings)
        );
        assert_eq!(
            message(&press('.'), Context::Prompt),
            Some(Message::Type('.'))
        );
        assert_eq!(message(&press('x'), Context::Prompt), None);
    }

    #[test]
    fn s_opens_the_study_view() {
        let study: Vec<_> = KEYS
            .iter()
            .filter(|b| b.context == Context::Main && b.keys.contains(&Char('s')))
            .collect();
        assert_eq!(study.len(), 1);
        assert_eq!(study[0].message, Message::ToggleView(views::View::Study));
    }
}
