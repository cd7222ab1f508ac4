//! `tumble lessons`: the bundled lessons, in teaching order, with their summaries and the names
//! every command accepts.

use super::output::{print, warn};
use super::Failure;
use crate::lessons;
use crate::scene::printable;

/// Prints one line per bundled lesson: file name, title, summary.
pub fn list() -> Result<(), Failure> {
    let files = lessons::bundled();
    if files.is_empty() {
        return Err(Failure::bad_input("this build has no bundled lessons"));
    }
    let mut rows = Vec::new();
    let mut broken = 0;
    for path in &files {
        let name = path
            .file_stem()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        match lessons::load(path) {
            Ok(lesson) => rows.push((
                printable(&name).into_owned(),
                printable(&lesson.title).into_owned(),
                printable(&lesson.summary).into_owned(),
            )),
            Err(e) => {
                warn(&e.to_string());
                broken += 1;
            }
        }
    }
    let name_width = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let title_width = rows.iter().map(|r| r.1.chars().count()).max().unwrap_or(0);
    let mut text = String::new();
    for (name, title, summary) in &rows {
        let line = format!(
            "{name}{}  {title}{}  {summary}",
            " ".repeat(name_width - name.chars().count()),
            " ".repeat(title_width - title.chars().count()),
        );
        text.push_str(line.trim_end());
        text.push('\n');
    }
    let example = rows.first().map_or("01-the-loop", |r| r.0.as_str());
    text.push_str(&format!(
        "\nOpen one in the app with `tumble NAME` (say `tumble {example}`), print it with \
         `tumble walk NAME --frames N`; a file lessons/NAME.toml in this folder is used instead.\n"
    ));
    print(&text)?;
    if broken == 0 {
        Ok(())
    } else {
        Err(Failure::bad_input(format!(
            "{broken} of {} bundled lessons have errors",
            files.len()
        )))
    }
}
