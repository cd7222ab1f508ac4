//! Writing to stdout and stderr without ever panicking.
//!
//! `println!` panics when stdout is gone (`tumble lessons | head -1`, a full disk); every
//! command writes through these helpers instead. A write that fails ends the command:
//!
//! - stdout closed by its reader (a broken pipe): exit [`EXIT_BROKEN_PIPE`] = 141, the
//!   conventional code of a process ended by SIGPIPE (128 + 13), after one line on stderr;
//! - any other write error (no space left, an I/O error): exit 2 with
//!   "cannot write output: …".
//!
//! stderr is written with its errors ignored: there is nowhere left to report them.

use super::Failure;
use std::io::{self, Write};

/// Exit code when stdout was closed by its reader: 128 + SIGPIPE (13), as a shell reports a
/// process the signal ended.
pub const EXIT_BROKEN_PIPE: u8 = 141;

/// The failure a write error to stdout ends a command with.
pub fn failure(e: io::Error) -> Failure {
    if e.kind() == io::ErrorKind::BrokenPipe {
        Failure {
            code: EXIT_BROKEN_PIPE,
            message: "output closed early (broken pipe): stopped".to_string(),
        }
    } else {
        Failure::bad_input(format!("cannot write output: {e}"))
    }
}

/// Writes `text` to stdout and flushes it.
pub fn print(text: &str) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(failure)
}

/// Writes one line to stdout (a newline added) and flushes it.
pub fn line(text: &str) -> Result<(), Failure> {
    print(&format!("{text}\n"))
}

/// Writes one line to stderr, prefixed `tumble: `, control characters escaped; an error
/// writing it is ignored.
pub fn warn(text: &str) {
    let _ = writeln!(
        io::stderr().lock(),
        "tumble: {}",
        crate::scene::printable(text)
    );
}
