//! Every independent error of a scene file, for `tumble check`: one line each.
//!
//! The loader ([`super::parse`]) stops at the first error. To find the next, the part of the
//! file at fault is blanked out (its bytes become spaces, so every other line and column stays
//! where it was) and the file is parsed again:
//!
//! ```text
//! error inside a key of a section ([scene], [body], an [[obstacle]], a [[page]], …)
//!     → blank that key = value (an unknown key), or write a value that passes in its place
//!       (a number → 1, numbers → as many 1s, a misspelt name → the suggested one)
//! error at a section itself, or caused by blanking one of its keys ("needs `size`")
//!     → blank the whole section; a required one ([scene], [body]) is replaced by a
//!       placeholder appended after the end of the file
//! ```
//!
//! An error that only the blanking caused is never reported: it names a blanked key, or has
//! no place in the file, or lies in the appended placeholder (the search stops there), or
//! calls unknown a body that the blanking removed (a joint, a spring, an `attach` entry or a
//! live number naming a body whose `[[body]]` was blanked for its own error). The same error
//! (place and message) is reported once; two keys with the same mistake are two lines. An
//! error asking for a `contact` in [scene] (bodies, obstacles, a cloth need one) is answered
//! by appending one, so each is reported once and the search goes on.
//! An error about a limit on the whole file (more joints than the limit) stops the search.
//! A TOML syntax error stops the search: nothing after it can be trusted.

use super::{parse, LoadError};
use std::ops::Range;
use std::path::Path;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// Placeholders for required sections, appended when a broken one is blanked out.
const PLACEHOLDERS: &[(&str, &str)] = &[
    (
        "scene",
        "\n[scene]\ndt = 0.001\nintegrator = \"symplectic-euler\"\n\
         contact = { response = \"impulse\" }\n",
    ),
    ("body", BODY_PLACEHOLDER),
];

/// The `[body]` placeholder: a box far from everything.
const BODY_PLACEHOLDER: &str = "\n[body]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n\
                                position = [1.0e6, 1.0e6, 1.0e6]\n";

/// Every independent error of `source` (empty if it loads), in the order of the file.
pub fn check(source: &str, path: &Path) -> Vec<LoadError> {
    let first = match parse(source, path) {
        Ok(_) => return Vec::new(),
        Err(e) => e,
    };
    if first.location.is_none()
        || first.message.contains(LIMIT_WORDS)
        || DeTable::parse(source).is_err()
    {
        return vec![first];
    }
    let mut text = source.to_string();
    let mut errors = vec![first.clone()];
    let mut current = first;
    let mut touched: Vec<Touched> = Vec::new();
    let names = body_names(source);
    for _ in 0..200 {
        let Some(offset) = offset_of(&text, current.location) else {
            break;
        };
        let Some(section) = section_at(&text, offset) else {
            break;
        };
        // A table missing from the file as a whole has no part to blank.
        let whole_file = current.message.starts_with("missing table")
            || (section.bare && current.message.starts_with("this table has no"))
            || current.message.contains(LIMIT_WORDS);
        if whole_file {
            break;
        }
        let caused = caused_by(&touched, &section, offset, &current.message);
        let untouched = |r: &Range<usize>| !touched.iter().any(|t| t.entry == *r);
        let entry = section
            .entries
            .iter()
            .find(|e| e.contains(&offset))
            .filter(|e| untouched(e))
            .cloned();
        // The innermost value at fault (inside an inline table too), and a value that passes.
        let value = section
            .values
            .iter()
            .filter(|(span, _)| span.contains(&offset))
            .min_by_key(|(span, _)| span.len())
            .filter(|(span, _)| untouched(span))
            .and_then(|(span, key)| {
                let value = neutral(&text[span.clone()], &current.message)?;
                (value.len() <= span.len()).then(|| (span.clone(), key.clone(), value))
            })
            .filter(|_| !current.message.starts_with("unknown key"));
        // A value replaced by one that passes and still at fault (a length the neutral value
        // could not guess): its whole entry goes, not the whole section.
        let still = touched
            .iter()
            .position(|t| t.entry.contains(&offset) && t.header == section.header);
        let retry = still.and_then(|i| {
            let t = &touched[i];
            section
                .entries
                .iter()
                .find(|e| e.start <= t.entry.start && t.entry.end <= e.end && **e != t.entry)
                .filter(|e| untouched(e))
                .cloned()
        });
        match (value, entry) {
            // "… need(s) a collision response: add `contact = …` to [scene]": the file gets
            // one (a sub-table after its end), so the next body, obstacle or cloth is checked
            // for its own errors, not for the same missing key.
            _ if current.message.contains(ADD_CONTACT) && !text.contains(CONTACT_PLACEHOLDER) => {
                text.push_str(CONTACT_PLACEHOLDER);
            }
            _ if retry.is_some() => {
                let entry = retry.unwrap_or_default();
                let key = key_name(&text[entry.clone()]);
                blank(&mut text, entry.clone());
                touched.push(Touched {
                    header: section.header.clone(),
                    entry,
                    key,
                    renamed: false,
                    suggested: suggestion(&current.message),
                });
            }
            (Some((span, key, value)), _) if !caused => {
                blank(&mut text, span.clone());
                text.replace_range(span.start..span.start + value.len(), &value);
                touched.push(Touched {
                    header: section.header.clone(),
                    entry: span,
                    key,
                    renamed: value.starts_with('"'),
                    suggested: None,
                });
            }
            (None, Some(entry)) if !caused => {
                let key = key_name(&text[entry.clone()]);
                blank(&mut text, entry.clone());
                touched.push(Touched {
                    header: section.header.clone(),
                    entry,
                    key,
                    renamed: false,
                    suggested: suggestion(&current.message),
                });
            }
            _ => {
                for region in section.regions() {
                    blank(&mut text, region);
                }
                if section.required_alone {
                    match PLACEHOLDERS.iter().find(|(name, _)| *name == section.name) {
                        Some((_, placeholder)) => text.push_str(placeholder),
                        None => break,
                    }
                }
            }
        }
        let mut next = match parse(&text, path) {
            Ok(_) => break,
            Err(e) => e,
        };
        // A file of cloths only needs no [body]; once a broken cloth is blanked out, it does:
        // the body placeholder stands in, so the search goes on past a false "missing table".
        if next.message.starts_with("missing table `[body]`") && !text.contains(BODY_PLACEHOLDER) {
            text.push_str(BODY_PLACEHOLDER);
            next = match parse(&text, path) {
                Ok(_) => break,
                Err(e) => e,
            };
        }
        let Some(next_offset) = offset_of(&text, next.location).filter(|&o| o < source.len())
        else {
            break;
        };
        if DeTable::parse(&text).is_err() {
            break;
        }
        let caused = section_at(&text, next_offset)
            .is_some_and(|s| caused_by(&touched, &s, next_offset, &next.message))
            || names_a_removed_body(&names, &text, &next.message);
        if !caused && !errors.contains(&next) {
            errors.push(next.clone());
        }
        current = next;
    }
    errors.sort_by_key(|e| e.location);
    errors
}

/// The words of the errors whose fix is a `contact` table in [scene] (several bodies,
/// obstacles, a cloth), and that table, appended as a sub-table after the end of the file.
const ADD_CONTACT: &str = "add `contact = {";
const CONTACT_PLACEHOLDER: &str = "\n[scene.contact]\nresponse = \"impulse\"\n";

/// The words of an error about a limit on the file as a whole ("… more than the limit of
/// 1000 joints"): blanking one table past it would only find the next.
const LIMIT_WORDS: &str = "more than the limit of";

/// The names of the bodies of a document, as the loader names them: `name`, else `body{n}`
/// for the n-th (1-based).
fn body_names(text: &str) -> Vec<String> {
    let Ok(document) = DeTable::parse(text) else {
        return Vec::new();
    };
    let named = |table: &DeTable<'_>, n: usize| {
        table
            .iter()
            .find(|(k, _)| k.get_ref() == "name")
            .and_then(|(_, v)| match v.get_ref() {
                DeValue::String(s) => Some(s.to_string()),
                _ => None,
            })
            .unwrap_or_else(|| format!("body{n}"))
    };
    let body = document
        .get_ref()
        .iter()
        .find(|(k, _)| k.get_ref() == "body")
        .map(|(_, v)| v.get_ref());
    match body {
        Some(DeValue::Table(table)) => vec![named(table, 1)],
        Some(DeValue::Array(array)) => array
            .iter()
            .enumerate()
            .filter_map(|(i, e)| match e.get_ref() {
                DeValue::Table(t) => Some(named(t, i + 1)),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// An error calling unknown (or missing) a body of the original file that blanking removed:
/// the body exists, and its own error was reported already.
fn names_a_removed_body(original: &[String], text: &str, message: &str) -> bool {
    if !(message.contains("unknown body") || message.contains("no body")) {
        return false;
    }
    let now = body_names(text);
    let removed: Vec<&String> = original.iter().filter(|n| !now.contains(n)).collect();
    !removed.is_empty()
        && (message.contains("has no body")
            || removed.iter().any(|n| message.contains(&format!("`{n}`"))))
}

/// An entry blanked or replaced by a value that passes.
struct Touched {
    /// The header of its section.
    header: Range<usize>,
    entry: Range<usize>,
    key: String,
    /// Replaced by the suggested name (say `type = "ground"`): what the section needs then is
    /// not the author's error.
    renamed: bool,
    /// A blanked key whose error suggested another (`anchors` on a ball joint: "did you mean
    /// `anchor`?"): that the section then lacks the suggested key is the same mistake.
    suggested: Option<String>,
}

/// The key an error suggests: "(did you mean `anchor`?".
fn suggestion(message: &str) -> Option<String> {
    let (_, rest) = message.split_once("(did you mean `")?;
    rest.split_once('`').map(|(key, _)| key.to_string())
}

/// An error that blanking or replacing an entry made: it lies in a replaced entry, names a key
/// blanked in the same section, or is about the section of a replaced name. An error asking
/// to add a blanked key (`contact = { … }`, which several bodies need) is caused by the
/// blanking wherever it lies.
fn caused_by(touched: &[Touched], section: &Section, offset: usize, message: &str) -> bool {
    touched.iter().any(|t| {
        (t.header == section.header
            && (t.entry.contains(&offset)
                || t.suggested
                    .as_ref()
                    .is_some_and(|k| message.contains(&format!("needs `{k}`")))
                || message.contains(&format!("`{}`", t.key))
                || (t.renamed && section.header.contains(&offset))))
            || message.contains(&format!("add `{} = ", t.key))
    })
}

/// A value that passes validation in place of a wrong one, where one is obvious: a number
/// becomes 1, an array of numbers as many 1s, an unknown name the suggested one (else the
/// first valid one the message lists).
fn neutral(value: &str, message: &str) -> Option<String> {
    let value = value.trim();
    if value.starts_with('"') {
        let suggested = message
            .split_once("(did you mean `")
            .and_then(|(_, rest)| rest.split_once('`'))
            .map(|(name, _)| name);
        let first_valid = message
            .starts_with("unknown ")
            .then(|| message.rsplit_once(": "))
            .flatten()
            .and_then(|(_, list)| list.split(", ").next());
        let name = suggested.or(first_valid)?;
        return Some(format!("\"{name}\""));
    }
    if let Some(inner) = value.strip_prefix('[').and_then(|v| v.strip_suffix(']')) {
        let items: Vec<&str> = inner.split(',').map(str::trim).collect();
        let numeric = items.iter().all(|i| looks_numeric(i));
        // "expected an array of 3 numbers": as many as asked for, if they fit.
        let asked = message
            .split_once("expected an array of ")
            .and_then(|(_, rest)| rest.split_once(' '))
            .and_then(|(n, _)| n.parse::<usize>().ok())
            .unwrap_or(items.len());
        let text = format!("[{}]", vec!["1"; asked].join(","));
        return (numeric && text.len() <= value.len()).then_some(text);
    }
    looks_numeric(value).then(|| "1".to_string())
}

fn looks_numeric(value: &str) -> bool {
    let v = value.trim_start_matches(['+', '-']);
    !v.is_empty() && (v.parse::<f64>().is_ok() || v == "inf" || v == "nan")
}

/// A key's name from its `key = value` text.
fn key_name(entry: &str) -> String {
    entry
        .split('=')
        .next()
        .unwrap_or("")
        .trim()
        .trim_matches('"')
        .to_string()
}

/// Replaces the bytes of `range` by spaces, keeping line breaks.
fn blank(text: &mut String, range: Range<usize>) {
    let replaced: String = text[range.clone()]
        .chars()
        .map(|c| {
            if c == '\n' {
                "\n".to_string()
            } else {
                " ".repeat(c.len_utf8())
            }
        })
        .collect();
    text.replace_range(range, &replaced);
}

/// The byte offset of a 1-based (line, column in characters).
fn offset_of(text: &str, location: Option<(usize, usize)>) -> Option<usize> {
    let (line, column) = location?;
    let start = if line == 1 {
        0
    } else {
        text.match_indices('\n').nth(line - 2)?.0 + 1
    };
    let rest = &text[start..];
    let within = rest
        .char_indices()
        .nth(column - 1)
        .map_or(rest.len(), |(i, _)| i);
    Some(start + within)
}

/// A part of the file that is checked on its own: a top-level `key = value`, a `[table]`, or
/// one element of an `[[array]]`.
#[derive(Debug)]
struct Section {
    name: String,
    /// The `[header]` (or the top-level `key = value`).
    header: Range<usize>,
    /// Each `key = value` of the section (and of its sub-tables).
    entries: Vec<Range<usize>>,
    /// Other headers of the section (`[scene.sub]`).
    headers: Vec<Range<usize>>,
    /// Every value with its key, inline tables' included.
    values: Vec<(Range<usize>, String)>,
    /// Blanking it leaves the file without a required section.
    required_alone: bool,
    /// A top-level `key = value`, not a table.
    bare: bool,
}

impl Section {
    fn regions(&self) -> Vec<Range<usize>> {
        let mut all = vec![self.header.clone()];
        all.extend(self.entries.iter().cloned());
        all.extend(self.headers.iter().cloned());
        all
    }

    fn contains(&self, offset: usize) -> bool {
        self.regions().iter().any(|r| r.contains(&offset))
    }
}

/// The section of the file that holds `offset`.
fn section_at(text: &str, offset: usize) -> Option<Section> {
    let document = DeTable::parse(text).ok()?;
    sections(document.get_ref())
        .into_iter()
        .find(|s| s.contains(offset))
}

/// Every section of a document.
fn sections(document: &DeTable<'_>) -> Vec<Section> {
    let mut out = Vec::new();
    for (key, value) in document.iter() {
        let name = key.get_ref().to_string();
        let required = PLACEHOLDERS.iter().any(|(n, _)| *n == name);
        match value.get_ref() {
            DeValue::Table(table) if value.span().start < key.span().start => {
                out.push(table_section(&name, value.span(), table, required));
            }
            DeValue::Array(array)
                if array
                    .iter()
                    .all(|e| matches!(e.get_ref(), DeValue::Table(_)))
                    && value.span().start < key.span().start =>
            {
                let alone = array.len() == 1;
                for element in array.iter() {
                    if let DeValue::Table(table) = element.get_ref() {
                        out.push(table_section(
                            &name,
                            element.span(),
                            table,
                            required && alone,
                        ));
                    }
                }
            }
            _ => out.push(Section {
                values: vec![(value.span(), name.clone())],
                name,
                header: key.span().start..value.span().end,
                entries: Vec::new(),
                headers: Vec::new(),
                required_alone: false,
                bare: true,
            }),
        }
    }
    out
}

fn table_section(name: &str, header: Range<usize>, table: &DeTable<'_>, required: bool) -> Section {
    let mut section = Section {
        name: name.to_string(),
        header,
        entries: Vec::new(),
        headers: Vec::new(),
        values: Vec::new(),
        required_alone: required,
        bare: false,
    };
    collect(table, &mut section);
    section
}

/// The entries and sub-table headers of a table defined by a header.
fn collect(table: &DeTable<'_>, section: &mut Section) {
    for (key, value) in table.iter() {
        collect_entry(key, value, section);
    }
}

fn collect_entry(
    key: &Spanned<std::borrow::Cow<'_, str>>,
    value: &Spanned<DeValue<'_>>,
    section: &mut Section,
) {
    let header_defined = value.span().start < key.span().start;
    match value.get_ref() {
        DeValue::Table(sub) if header_defined => {
            section.headers.push(value.span());
            collect(sub, section);
        }
        _ => {
            section.entries.push(key.span().start..value.span().end);
            inline_values(key, value, section);
        }
    }
}

/// A value and, in an inline table, the values inside it.
fn inline_values(
    key: &Spanned<std::borrow::Cow<'_, str>>,
    value: &Spanned<DeValue<'_>>,
    section: &mut Section,
) {
    section
        .values
        .push((value.span(), key.get_ref().to_string()));
    if let DeValue::Table(table) = value.get_ref() {
        for (k, v) in table.iter() {
            inline_values(k, v, section);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(source: &str) -> Vec<String> {
        check(source, Path::new("s.toml"))
            .iter()
            .map(|e| e.to_string())
            .collect()
    }

    const GOOD_BODY: &str = "[body]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n";

    #[test]
    fn a_valid_file_has_no_errors() {
        let source =
            format!("title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n{GOOD_BODY}");
        assert!(lines(&source).is_empty());
    }

    #[test]
    fn independent_errors_in_scene_body_obstacles_and_pages_are_all_reported() {
        let source = "title = \"t\"\n\
            [scene]\n\
            dt = -0.01\n\
            integrator = \"rk5\"\n\
            gravty = [0.0, -9.81, 0.0]\n\
            contact = { response = \"impulse\" }\n\
            [body]\n\
            shape = \"box\"\n\
            size = [1.0, 0.0, 1.0]\n\
            mass = 1.0\n\
            [[obstacle]]\n\
            type = \"grund\"\n\
            [[obstacle]]\n\
            type = \"sphere\"\n\
            center = [0.0, 0.0, 0.0]\n\
            radius = -1.0\n\
            [[page]]\n\
            at = -1.0\n\
            title = \"p\"\n\
            text = \"p\"\n";
        let found = lines(source);
        let expected = [
            "s.toml:5:1: unknown key `gravty` (did you mean `gravity`?); valid keys here: dt, \
             duration, integrator, gravity, drag, contact, joint_correction",
            "s.toml:3:6: dt must be > 0, found -0.01",
            "s.toml:4:14: unknown integrator `rk5` (did you mean `rk4`?); valid integrators: \
             euler-seed, euler, symplectic-euler, rk4, splitting, exact-splitting, \
             exact-splitting-4",
            "s.toml:9:8: box `size` needs three sides > 0 m, found [1.0, 0.0, 1.0]",
            "s.toml:12:8: unknown obstacle type `grund` (did you mean `ground`?); valid types: \
             ground, sphere, box, plane",
            "s.toml:16:10: radius must be > 0, found -1",
            "s.toml:18:6: page time `at` must be ≥ 0 s, found -1",
        ];
        for line in expected {
            assert!(
                found.iter().any(|f| f == line),
                "missing {line} in {found:#?}"
            );
        }
        assert_eq!(found.len(), expected.len(), "{found:#?}");
    }

    #[test]
    fn a_missing_table_is_one_error() {
        let source = "title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n";
        assert_eq!(lines(source).len(), 1, "{:?}", lines(source));
    }

    #[test]
    fn a_syntax_error_stops_at_the_first() {
        let source = "title = \"t\n[scene]\ndt = =\n";
        assert_eq!(lines(source).len(), 1);
    }

    #[test]
    fn an_error_caused_by_blanking_is_not_reported() {
        // Blanking `size` would make "a box body needs `size`": a consequence, not an error.
        let source = "title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n\
             [body]\nshape = \"box\"\nsize = [1.0, 0.0, 1.0]\nmass = -1.0\n";
        assert_eq!(
            lines(source),
            [
                "s.toml:7:8: box `size` needs three sides > 0 m, found [1.0, 0.0, 1.0]",
                "s.toml:8:8: mass must be > 0, found -1",
            ]
        );
    }

    #[test]
    fn a_body_blanked_for_its_own_error_is_not_unknown_to_joints_and_springs() {
        // The second body carries the error (several bodies, no `contact`); the joint and
        // the spring naming it are right, and `run` reports only the first line.
        let body = |name: &str, x: f64| {
            format!(
                "[[body]]\nname = \"{name}\"\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\n\
                 mass = 1.0\nposition = [{x}, 0.0, 0.0]\n"
            )
        };
        let source = format!(
            "title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n{}{}{}\
             [[joint]]\ntype = \"ball\"\nbodies = [\"a\", \"b\"]\nanchor = [1.5, 0.0, 0.0]\n\
             [[spring]]\nbodies = [\"b\", \"c\"]\nanchors = [[3.0, 0.0, 0.0], [6.0, 0.0, 0.0]]\n\
             stiffness = 10.0\n",
            body("a", 0.0),
            body("b", 3.0),
            body("c", 6.0)
        );
        let found = lines(&source);
        assert_eq!(found.len(), 1, "{found:#?}");
        assert!(found[0].contains("several bodies need a collision response"));
        let first = parse(&source, Path::new("s.toml")).unwrap_err().to_string();
        assert_eq!(found[0], first);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        /// Any mutation of a bundled lesson: `check` never panics, finds nothing exactly when
        /// the loader accepts the file, and its first line is the loader's own error when there
        /// is a single one.
        #[test]
        fn check_agrees_with_the_loader_on_mutated_lessons(
            lesson in 0usize..12,
            at in 0.0f64..1.0,
            cut in 0usize..40,
            insert in "[ -~]{0,12}",
        ) {
            let paths = crate::lessons::bundled();
            let path = &paths[lesson % paths.len()];
            let text = crate::lessons::embedded(path).unwrap();
            let mut start = (at * text.len() as f64) as usize;
            while !text.is_char_boundary(start) {
                start -= 1;
            }
            let mut end = (start + cut).min(text.len());
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            let mutated = format!("{}{insert}{}", &text[..start], &text[end..]);
            let found = check(&mutated, path);
            match parse(&mutated, path) {
                Ok(_) => proptest::prop_assert!(found.is_empty(), "{found:?}"),
                Err(e) => {
                    proptest::prop_assert!(!found.is_empty());
                    proptest::prop_assert!(found.contains(&e), "{e} not in {found:?}");
                }
            }
        }
    }
}
