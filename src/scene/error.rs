//! Load errors: one line, naming file:line:column where there is one.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Why a scene or lesson file could not be loaded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LoadError {
    /// The file at fault.
    pub path: PathBuf,
    /// 1-based line and column, when the error has a place in the file.
    pub location: Option<(usize, usize)>,
    /// What was expected and what was found, on one line.
    pub message: String,
}

impl LoadError {
    /// An error about the whole file.
    pub fn file(path: &Path, message: impl Into<String>) -> LoadError {
        LoadError {
            path: path.to_path_buf(),
            location: None,
            message: one_line(&message.into()),
        }
    }

    /// An error at a byte span of `source`.
    pub fn at(
        path: &Path,
        source: &str,
        span: Range<usize>,
        message: impl Into<String>,
    ) -> LoadError {
        LoadError {
            path: path.to_path_buf(),
            location: Some(line_column(source, span.start)),
            message: one_line(&message.into()),
        }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Some((line, column)) => {
                write!(
                    f,
                    "{}:{}:{}: {}",
                    printable(&self.path.display().to_string()),
                    line,
                    column,
                    printable(&self.message)
                )
            }
            None => write!(
                f,
                "{}: {}",
                printable(&self.path.display().to_string()),
                printable(&self.message)
            ),
        }
    }
}

impl std::error::Error for LoadError {}

/// 1-based line and column (in characters) of a byte offset.
pub fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(source.len());
    let before = &source[..floor_char_boundary(source, offset)];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Text from a file made safe to print on a terminal: every control character (escape,
/// carriage return, backspace, bell, newline, …) and every bidirectional-override character
/// written as a visible escape (`\u{1b}`), tabs kept. One helper for every command that
/// prints text it did not write itself (titles, summaries, pages, names, errors).
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    let unsafe_char = |c: char| {
        (c.is_control() && c != '\t')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{200e}' | '\u{200f}')
    };
    if !text.chars().any(unsafe_char) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if unsafe_char(c) {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// Collapses a message onto one line.
fn one_line(message: &str) -> String {
    message.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely typo.
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (edit_distance(word, c), c))
        .filter(|(d, c)| *d <= (c.len().max(word.len()) / 3).max(1))
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// Levenshtein distance between two strings, in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitution = previous + usize::from(ca != *cb);
            previous = row[j + 1];
            row[j + 1] = substitution.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_are_one_based_and_count_characters() {
        let source = "a = 1\nbé = 2\n";
        assert_eq!(line_column(source, 0), (1, 1));
        assert_eq!(line_column(source, 6), (2, 1));
        assert_eq!(line_column(source, source.find('=').unwrap()), (1, 3));
        let second_equals = source.rfind('=').unwrap();
        assert_eq!(line_column(source, second_equals), (2, 4));
    }

    #[test]
    fn control_characters_are_escaped_tabs_and_plain_text_kept() {
        // ESC ] 0 ; … BEL sets a terminal's title; ESC [ 2 J clears the screen.
        assert_eq!(
            printable("a\u{1b}]0;pwned\u{7}b\u{1b}[2J"),
            "a\\u{1b}]0;pwned\\u{7}b\\u{1b}[2J"
        );
        assert_eq!(printable("x\ry\nz"), "x\\ry\\nz");
        assert_eq!(printable("\u{202e}abc"), "\\u{202e}abc");
        assert_eq!(printable("été\tω = 2"), "été\tω = 2");
    }

    #[test]
    fn a_typo_suggests_the_intended_key() {
        assert_eq!(
            did_you_mean("gravty", ["dt", "gravity", "drag"]),
            Some("gravity")
        );
        assert_eq!(did_you_mean("zzzzzz", ["dt", "gravity"]), None);
    }
}
