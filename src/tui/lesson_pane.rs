//! The lesson pane: the page that applies at the current time (`Lesson::page_at`), wrapped at
//! the width pages are written for (86 columns) or the pane's when narrower — with hanging
//! indents, and never inside a formula when a better break exists — scrollable.

use super::app::App;
use super::theme;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Paragraph, Widget};

/// The page's title and text at the app's time.
fn page(app: &App) -> (String, String) {
    let lesson = &app.session.lesson;
    match lesson.page_at(app.session.snapshot.time) {
        Some((i, page)) => {
            // Live numbers filled in with the values simulated for the settings in use.
            let mut text = app
                .session
                .live
                .page_text(page)
                .trim_matches('\n')
                .to_string();
            if page.predict.is_some() {
                let line = match app.prediction_result(i) {
                    Some(result) => format!("Prediction: {result}."),
                    // A recording (`tumble record`) runs on and asks nothing.
                    None if app.ui.guesses[i] == super::app::Guess::Open
                        && app.ui.pause_at_stops =>
                    {
                        format!(
                            "Predict: {} Enter asks for your guess.",
                            app.prediction_question(i)
                        )
                    }
                    None => format!(
                        "Predict: {} (the run will tell)",
                        app.prediction_question(i)
                    ),
                };
                text.push_str("\n\n");
                text.push_str(&line);
            }
            // A guess of another page due at this page's time (lesson 32 asks on page 1 for
            // t = 0.643 s, page 3's time): its comparison shows here, where the run paused.
            let dt = app.session.snapshot.dt;
            let here = crate::live::step_at(page.at, dt);
            for (j, other) in lesson.pages.iter().enumerate() {
                let due_here = other
                    .predict
                    .as_ref()
                    .is_some_and(|p| crate::live::step_at(p.at, dt) == here);
                if j != i && due_here && matches!(app.ui.guesses[j], super::app::Guess::Given(_)) {
                    if let Some(result) = app.prediction_result(j) {
                        // First, where it is read before any scrolling.
                        text = format!("Prediction (page {}): {result}.\n\n{text}", j + 1);
                    }
                }
            }
            (
                format!(" page {}/{}: {} ", i + 1, lesson.pages.len(), page.title),
                text,
            )
        }
        None => (
            " lesson ".to_string(),
            if lesson.summary.is_empty() {
                "This scene has no lesson pages.".to_string()
            } else {
                lesson.summary.clone()
            },
        ),
    }
}

/// How many lines the page takes in a pane `width` columns wide (inside its border).
pub fn line_count(app: &App, width: u16) -> u16 {
    let (_, text) = page(app);
    wrap(
        &text,
        usize::from(width.clamp(1, super::layout::PAGE_WIDTH)),
    )
    .len() as u16
}

pub fn render(app: &App, area: Rect, buf: &mut Buffer) {
    let (title, text) = page(app);
    let block = Block::bordered()
        .title(title)
        .title_bottom(Line::styled(" PgUp/PgDn scroll ", theme::DIM).right_aligned())
        .title_style(Style::new().add_modifier(Modifier::BOLD));
    let inner = block.inner(area);
    let wrapped = wrap(
        &text,
        usize::from(inner.width.clamp(1, super::layout::PAGE_WIDTH)),
    );
    let cut = wrapped
        .iter()
        .any(|l| l.chars().count() > usize::from(inner.width));
    let lines: Vec<Line> = wrapped
        .iter()
        .map(|l| Line::from(fit(l, usize::from(inner.width), app.ui.lesson_hscroll)))
        .collect();
    let total = lines.len() as u16;
    let scroll = app.ui.lesson_scroll.min(total.saturating_sub(inner.height));
    app.ui
        .lesson_scroll_max
        .set(total.saturating_sub(inner.height));
    let mut block = block;
    // After i or c the page's numbers are another method's: the page says whose they are.
    if let Some(note) = app.page_settings_note() {
        block = block.title(Line::styled(note, theme::NOTICE).right_aligned());
    }
    if cut && inner.width >= 40 {
        block = block.title_bottom(Line::styled(" { } sideways ", theme::NOTICE).centered());
    }
    if total > inner.height {
        block = block.title_bottom(
            Line::styled(
                format!(
                    " {}-{} of {} ",
                    scroll + 1,
                    (scroll + inner.height).min(total),
                    total
                ),
                theme::NOTICE,
            )
            .left_aligned(),
        );
    }
    Paragraph::new(lines)
        .block(block)
        .scroll((scroll, 0))
        .render(area, buf);
}

/// A page line in `width` columns, seen from column `offset` (the sideways scroll, `{` `}`):
/// a line that does not fit is cut with `…` where text is hidden (left or right); a line that
/// fits is shown whole, unscrolled.
pub fn fit(line: &str, width: usize, offset: u16) -> String {
    let chars: Vec<char> = line.chars().collect();
    if chars.len() <= width || width < 2 {
        return line.to_string();
    }
    let offset = usize::from(offset).min(chars.len() - width);
    let mut shown: String = if offset > 0 {
        std::iter::once('…')
            .chain(chars[offset + 1..].iter().copied())
            .collect()
    } else {
        chars.iter().collect()
    };
    let count = shown.chars().count();
    if count > width {
        shown = shown.chars().take(width - 1).chain(['…']).collect();
    }
    shown
}

/// Characters that make a space next to them part of a formula (`a = b`, `x + y`).
const OPERATORS: &str = "=+−-×·/<>≤≥≈→⊗∝";

/// Word-wraps `text` to `width` columns without breaking formulas: a line that starts with
/// spaces (a formula, a table row) is kept whole (the pane cuts it with a marker, [`fit`]).
///
/// A continuation line is indented like the text after the first gap of two or more spaces on
/// its line (`  x  where the…` continues under `where`), or, for an indented line (a formula),
/// two columns deeper than the line. Where a line breaks, best first:
/// 1. an indented line: at a gap of two or more spaces, or before a `=` outside brackets;
/// 2. a space outside brackets, not next to an operator (`=`, `+`, `×`, …);
/// 3. a space not next to an operator;
/// 4. any space;
/// 5. mid-word (a word longer than the line).
///
/// Choices 2–4 are taken only if they keep at least a third of the line filled.
///
/// When a line is wider than `width`, the prose is reflowed first (`reflow`): the author's
/// line breaks inside a paragraph would otherwise leave a short orphan after every wrapped line.
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    wrap_with(text, width, true)
}

/// As [`wrap`], and an indented line is wrapped too (with the hanging indents below) when
/// `keep_indented` is false (the loop strip, whose lines are indented prose).
pub fn wrap_with(text: &str, width: usize, keep_indented: bool) -> Vec<String> {
    let width = width.max(1);
    let reflowed;
    let text = if text.lines().all(|l| l.trim_end().chars().count() <= width) {
        text
    } else {
        reflowed = reflow(text);
        &reflowed
    };
    let mut out = Vec::new();
    for line in text.lines() {
        let chars: Vec<char> = line.trim_end().chars().collect();
        if chars.len() <= width {
            out.push(chars.iter().collect());
            continue;
        }
        let lead = chars.iter().take_while(|c| **c == ' ').count();
        if lead > 0 && keep_indented {
            // A formula or a table row keeps its line: the pane cuts it with a marker and
            // scrolls sideways ([`fit`]).
            out.push(chars.iter().collect());
            continue;
        }
        let formula = lead > 0;
        let gap = (lead..chars.len().saturating_sub(2))
            .find(|&i| chars[i] == ' ' && chars[i + 1] == ' ' && i > lead)
            .map(|i| i + chars[i..].iter().take_while(|c| **c == ' ').count());
        let gap = gap.filter(|&h| h < width / 2);
        let hang = gap
            .or(formula.then_some(lead + 2))
            .filter(|&h| h < width / 2)
            .unwrap_or(lead.min(width / 2));
        let mut rest: Vec<char> = chars.clone();
        // Where `rest` starts in `chars` (breaks before the hanging gap are no use).
        let mut offset = 0usize;
        let mut indent = 0;
        loop {
            let room = width - indent;
            if rest.len() <= room {
                out.push(" ".repeat(indent) + &rest.iter().collect::<String>());
                break;
            }
            let cut = break_at(&rest, room, formula, gap.map(|g| g.saturating_sub(offset)));
            let head: String = rest[..cut].iter().collect();
            out.push(" ".repeat(indent) + head.trim_end());
            let mut skip = cut;
            while rest.get(skip) == Some(&' ') {
                skip += 1;
            }
            rest.drain(..skip);
            offset += skip;
            if rest.is_empty() {
                break;
            }
            indent = hang;
        }
    }
    out
}

/// Joins the lines of each prose paragraph into one line. Prose is a line that starts with a
/// letter, a digit or an opening quote or bracket and is not a list item (`- `, `• `, `1. `);
/// an indented line (a formula, a table row), an empty line or a list item is kept as it is
/// and ends the paragraph.
fn reflow(text: &str) -> String {
    let prose = |l: &str| {
        let first = l.chars().next();
        let item = l.starts_with("- ")
            || l.starts_with("• ")
            || l.split_once(". ")
                .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        first.is_some_and(|c| !c.is_whitespace()) && !item
    };
    let mut out: Vec<String> = Vec::new();
    let mut open = false;
    for line in text.lines() {
        let line = line.trim_end();
        let continues = open && prose(line);
        match out.last_mut() {
            Some(last) if continues => {
                last.push(' ');
                last.push_str(line);
            }
            _ => out.push(line.to_string()),
        }
        // A list item's own continuation lines are prose too.
        open = !line.is_empty() && !line.starts_with(' ');
    }
    out.join("\n")
}

/// Where to break `chars` so that at most `room` characters stay on the line (see [`wrap`]).
fn break_at(chars: &[char], room: usize, formula: bool, gap_end: Option<usize>) -> usize {
    let mut depth = vec![0i32; chars.len() + 1];
    for (i, c) in chars.iter().enumerate() {
        depth[i + 1] = depth[i]
            + match c {
                '(' | '[' | '{' => 1,
                ')' | ']' | '}' => -1,
                _ => 0,
            };
    }
    let is_op = |i: usize| chars.get(i).is_some_and(|c| OPERATORS.contains(*c));
    let first_text = chars.iter().position(|c| *c != ' ').unwrap_or(0);
    // Spaces where a break leaves text on the line, nearest the end first.
    let spaces: Vec<usize> = (1..=room.min(chars.len() - 1))
        .rev()
        .filter(|&i| chars[i] == ' ' && i > first_text)
        .filter(|&i| gap_end.is_none_or(|g| i >= g))
        .collect();
    let flat = |i: usize| depth[i] <= 0;
    // Next to an operator, or between a number and what follows it (its unit).
    let near_op = |i: usize| is_op(i - 1) || is_op(i + 1) || chars[i - 1].is_ascii_digit();
    if formula {
        let preferred = spaces.iter().find(|&&i| {
            flat(i)
                && ((chars[i - 1] == ' ' || chars.get(i + 1) == Some(&' '))
                    || chars.get(i + 1) == Some(&'='))
        });
        if let Some(&i) = preferred {
            return i;
        }
    }
    let third = room / 3;
    let choices: [&dyn Fn(usize) -> bool; 3] =
        [&|i| flat(i) && !near_op(i), &|i| !near_op(i), &|_| true];
    for ok in choices {
        if let Some(&i) = spaces.iter().find(|&&i| ok(i)) {
            if i >= third {
                return i;
            }
        }
    }
    spaces.first().copied().unwrap_or(room)
}

#[cfg(test)]
mod tests {
    use super::wrap;

    #[test]
    fn an_indented_line_is_never_rewrapped_in_a_page_and_is_cut_with_a_marker() {
        let line = "  L = I ω = (0.0015 × 8, 0, 0.041 × 8) = (0.012, 0, 0.328) kg·m²/s,";
        assert_eq!(wrap(line, 50), vec![line.to_string()]);
        // 20 columns from the left: 19 characters and the marker; scrolled by 10, a marker
        // each side; scrolled past the end, the line's last 19 characters.
        assert_eq!(super::fit(line, 20, 0), "  L = I ω = (0.0015…");
        assert_eq!(super::fit(line, 20, 10), "… (0.0015 × 8, 0, 0…");
        assert_eq!(super::fit(line, 20, 200), "… 0, 0.328) kg·m²/s,");
        assert_eq!(super::fit("  short", 20, 5), "  short");
    }

    #[test]
    fn continuation_lines_hang_under_the_text_after_a_double_space() {
        // The second line has room for 19 columns: "turned (a unit" would break inside the
        // brackets; the break outside them, after "turned", still fills a third of the line.
        let lines = super::wrap_with("  q  how the body is turned (a unit quaternion)", 24, false);
        assert_eq!(
            lines,
            vec![
                "  q  how the body is",
                "     turned",
                "     (a unit quaternion)",
            ]
        );
    }

    #[test]
    fn a_formula_breaks_before_an_equals_sign_not_inside_brackets() {
        // Lesson 2's line is 71 characters; in 50 columns it breaks before the `=` outside the
        // brackets that keeps most on the first line, and continues 2 deeper than the line.
        let line = "  L = I ω = (0.0015 × 8, 0, 0.041 × 8) = (0.012, 0, 0.328) kg·m²/s,";
        assert_eq!(
            super::wrap_with(line, 50, false),
            vec![
                "  L = I ω = (0.0015 × 8, 0, 0.041 × 8)",
                "    = (0.012, 0, 0.328) kg·m²/s,",
            ]
        );
    }

    #[test]
    fn prose_avoids_breaking_next_to_an_operator() {
        // Width 30: the last space that fits is after `=` (col 30 would split `= 0.0279`);
        // the break moves back to the space before `I_yy`.
        let lines = wrap("Check by hand I_yy = 0.0279 kg·m² against the panel", 30);
        assert_eq!(lines[0], "Check by hand");
        assert!(lines[1].starts_with("I_yy = 0.0279"), "{lines:?}");
    }

    #[test]
    fn lines_within_the_page_width_are_kept_whole() {
        let line = "x".repeat(86);
        assert_eq!(wrap(&line, 86), vec![line.clone()]);
    }

    #[test]
    fn prose_is_reflowed_in_a_narrow_pane_and_formulas_stay_on_their_lines() {
        let page = "A cube falls from 1 m and\nhits the ground.\n  v = g t\nThen it rests.";
        // Wide enough: the author's lines are kept.
        assert_eq!(wrap(page, 30).len(), 4);
        // 20 columns: the first paragraph is one paragraph, the formula its own line.
        assert_eq!(
            wrap(page, 20),
            vec![
                "A cube falls from",
                "1 m and hits the",
                "ground.",
                "  v = g t",
                "Then it rests."
            ]
        );
    }

    #[test]
    fn a_word_longer_than_the_line_is_cut() {
        let lines = wrap("abcdefghij", 4);
        assert_eq!(lines, vec!["abcd", "efgh", "ij"]);
    }
}
