//! Bounds on the work and the memory one command may ask for, checked before it starts.
//!
//! A scene file or a command line can ask for any amount of work: `shot --at 1e12`, a scene
//! with `dt = 1e-300`, `record --duration 1e7`, `study` on a scene of `duration = 1e9`. Each
//! command turns what it is asked for into a count — steps, frames, samples, screen cells —
//! and checks it here before it allocates or steps anything; past a bound it refuses with a
//! one-line error naming the flag or key, the count and the limit. The bounds are far above
//! any lesson (the longest bundled study runs 10⁵ steps) and far below what would exhaust the
//! memory or the patience of the machine.
//!
//! | count | bound | who asks |
//! |---|---|---|
//! | steps of one run | [`MAX_STEPS`] = 10⁷ | `shot --at`, `record --duration`, the app's jump, a study's finest run |
//! | frames of a recording | [`MAX_CAST_FRAMES`] = 108 000 (an hour at 30 fps) | `record --duration` |
//! | samples of a study run | [`MAX_SAMPLES`] = 10⁶ | `study`, the app's `s` (duration / 0.1 s) |
//! | bytes of a scene file | [`MAX_FILE_BYTES`] = 16 MiB | every command that reads one |
//! | bytes of a mesh or a CSV | [`MAX_FILE_BYTES`] = 16 MiB | `.obj` meshes, `diff`'s CSV |
//! | bodies of a scene | [`MAX_BODIES`] = 1000 | every command that loads one |
//! | joints and springs of a scene | [`MAX_LINKS`] = 1000 | every command that loads one |
//!
//! Every input file is read through [`read_bounded`]: the bound is on the bytes actually
//! read (a file's size in its metadata may be 0 and the file endless: `/dev/zero`, files
//! under `/proc`), and a file that is not a regular file is refused by its type before it is
//! opened — a FIFO with no writer would block the open forever, a device may never end:
//!
//! | the path is | read |
//! |---|---|
//! | a regular file (or a link to one) | up to the bound; past it, an error naming the path and the bound |
//! | `/dev/stdin`, `/dev/fd/0`, `/proc/self/fd/0` | the process's standard input, up to the bound (`tumble check /dev/stdin < scene.toml`) |
//! | a directory | refused: "is a directory" |
//! | a FIFO, a socket, a character or block device (`/dev/zero`, `/dev/tty`, `<(…)`) | refused by its type, never opened |
//! | cells of a rendered screen | [`MAX_CELLS`] = 10⁶, at most [`MAX_SIDE`] a side | `--size` of `shot` and `record` |

/// The largest scene file read, bytes (16 MiB: the longest bundled lesson is a few kB).
pub const MAX_FILE_BYTES: u64 = 16 << 20;

/// The most bodies a scene may have: far above any lesson (a chain of a few dozen links),
/// below what makes the pairwise contact tests of every step (n²/2 pairs) a wait.
pub const MAX_BODIES: usize = 1_000;

/// The most joints and springs together a scene may have (their rows are solved together at
/// every evaluation of the derivative).
pub const MAX_LINKS: usize = 1_000;

/// Why [`read_bounded`] could not read a file: `Display` is one line naming the path (and the
/// bound, where it is the reason).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReadError {
    pub path: std::path::PathBuf,
    /// The reason alone, without the path ("is a named pipe (FIFO) …").
    pub reason: String,
}

impl std::fmt::Display for ReadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.reason)
    }
}

impl std::error::Error for ReadError {}

/// Whether `path` names this process's standard input.
fn is_stdin(path: &std::path::Path) -> bool {
    ["/dev/stdin", "/dev/fd/0", "/proc/self/fd/0"]
        .iter()
        .any(|p| path == std::path::Path::new(p))
}

/// The bytes of the file at `path`, at most `limit` of them: see the module doc for what is
/// read and what is refused. `what` names the kind of file in the messages ("scene file",
/// "mesh", "CSV").
pub fn read_bounded_bytes(
    path: &std::path::Path,
    limit: u64,
    what: &str,
) -> Result<Vec<u8>, ReadError> {
    use std::io::Read;
    let fail = |reason: String| ReadError {
        path: path.to_path_buf(),
        reason,
    };
    let mut bytes = Vec::new();
    let read = if is_stdin(path) {
        std::io::stdin()
            .lock()
            .take(limit + 1)
            .read_to_end(&mut bytes)
    } else {
        let meta = std::fs::metadata(path).map_err(|e| {
            fail(match e.kind() {
                std::io::ErrorKind::NotFound => "cannot read: no such file".to_string(),
                _ => format!("cannot read: {e}"),
            })
        })?;
        let kind = meta.file_type();
        if kind.is_dir() {
            return Err(fail(format!("is a directory, not a {what}")));
        }
        if !kind.is_file() {
            return Err(fail(format!(
                "is {}, not a regular file: a {what} is read from a file (or from /dev/stdin)",
                special_kind(&kind)
            )));
        }
        if meta.len() > limit {
            return Err(fail(format!(
                "file is {} bytes, more than the limit of {limit} for a {what}",
                meta.len()
            )));
        }
        std::fs::File::open(path).and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
    };
    read.map_err(|e| fail(format!("cannot read: {e}")))?;
    if bytes.len() as u64 > limit {
        return Err(fail(format!(
            "more than the limit of {limit} bytes for a {what} (the read stopped there)"
        )));
    }
    Ok(bytes)
}

/// The text of the file at `path` (UTF-8), at most `limit` bytes: [`read_bounded_bytes`],
/// then UTF-8 checked.
pub fn read_bounded(path: &std::path::Path, limit: u64, what: &str) -> Result<String, ReadError> {
    let bytes = read_bounded_bytes(path, limit, what)?;
    String::from_utf8(bytes).map_err(|_| ReadError {
        path: path.to_path_buf(),
        reason: format!("not a text file (invalid UTF-8): expected a {what}"),
    })
}

/// A file type that is not a regular file or a directory, in words.
fn special_kind(kind: &std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a named pipe (FIFO)"
    } else if kind.is_socket() {
        "a socket"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else {
        "a special file"
    }
}

/// The most steps one run may take (the app's own jump limit is the same number).
pub const MAX_STEPS: u64 = 10_000_000;

/// The most frames a recording may hold: an hour at 30 frames per second.
pub const MAX_CAST_FRAMES: u64 = 108_000;

/// The most sample times a study run may keep.
pub const MAX_SAMPLES: u64 = 1_000_000;

/// The most character cells a rendered screen may have.
pub const MAX_CELLS: u64 = 1_000_000;

/// The longest side of a rendered screen, in cells.
pub const MAX_SIDE: u16 = 4_000;

/// A count as a float, for counts that may be astronomically large (`1e12 / 1e-300`):
/// printed as an integer while it is one, else in scientific notation.
fn count_text(count: f64) -> String {
    if count < 1e15 {
        format!("{count:.0}")
    } else {
        format!("{count:.1e}")
    }
}

/// A short form of a number a user gave (no 300-digit lines): as written when short, else
/// in scientific notation.
pub fn short(value: f64) -> String {
    let plain = value.to_string();
    if plain.len() <= 12 {
        plain
    } else {
        format!("{value:.3e}")
    }
}

/// The steps needed to cover `duration` seconds at `dt` (rounded to the nearest step), or an
/// error when they are more than [`MAX_STEPS`]. `what` names what was asked for (a flag or a
/// key, with its value), `fix` what to do about it.
pub fn steps(duration: f64, dt: f64, what: &str, fix: &str) -> Result<u64, String> {
    let count = (duration / dt).round();
    if count.is_nan() || count > MAX_STEPS as f64 {
        return Err(format!(
            "{what} at dt = {} s is {} steps, more than the limit of {MAX_STEPS}: {fix}",
            short(dt),
            if count.is_nan() {
                "too many".to_string()
            } else {
                count_text(count)
            },
        ));
    }
    Ok(count.max(0.0) as u64)
}

/// A count of `unit`s (frames, samples) checked against its bound: `what` names what asked
/// for it (a flag or a key, with its value), `fix` what to do about it.
pub fn count(count: f64, limit: u64, what: &str, unit: &str, fix: &str) -> Result<u64, String> {
    if count.is_nan() || count > limit as f64 {
        return Err(format!(
            "{what} is {} {unit}, more than the limit of {limit}: {fix}",
            count_text(count)
        ));
    }
    Ok(count.max(0.0) as u64)
}

/// A screen size checked against [`MAX_SIDE`] and [`MAX_CELLS`] (any size a user can type:
/// `99999x99999` is over the limit, not malformed).
pub fn screen(cols: u64, rows: u64) -> Result<(), String> {
    if cols > u64::from(MAX_SIDE) || rows > u64::from(MAX_SIDE) {
        return Err(format!(
            "size {cols}x{rows} is larger than the limit of {MAX_SIDE} cells a side"
        ));
    }
    let cells = cols * rows;
    if cells > MAX_CELLS {
        return Err(format!(
            "size {cols}x{rows} is {cells} cells, more than the limit of {MAX_CELLS}"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_counted_and_bounded() {
        // 1 s at 1 ms: 1000 steps (the nearest step).
        assert_eq!(steps(1.0, 1e-3, "--at 1", "x"), Ok(1000));
        // 1e12 s at 1 ms: 1e15 steps, far over 1e7.
        let e = steps(1e12, 1e-3, "--at 1e12 s", "choose a nearer time").unwrap_err();
        assert!(e.contains("--at 1e12 s") && e.contains("10000000"), "{e}");
        // 1 s at 1e-300 s: 1e300 steps; the message stays short.
        let e = steps(1.0, 1e-300, "`dt`", "x").unwrap_err();
        assert!(e.len() < 150, "{e}");
        // inf / inf is NaN: refused, never cast to a number of steps.
        assert!(steps(f64::INFINITY, f64::INFINITY, "x", "y").is_err());
    }

    #[test]
    fn counts_and_screens_are_bounded() {
        let e = count(1e10, MAX_SAMPLES, "duration = 1e9 s", "samples", "z").unwrap_err();
        assert!(e.contains("samples, more than the limit of 1000000"), "{e}");
        assert_eq!(count(10.0, MAX_SAMPLES, "x", "samples", "z"), Ok(10));
        assert!(screen(120, 40).is_ok());
        assert!(screen(30000, 30000).is_err());
        assert!(screen(99999, 99999).unwrap_err().contains("limit of 4000"));
        // 1001 × 1000 = 1 001 000 cells > 10⁶.
        assert!(screen(1001, 1000).is_err());
    }

    #[test]
    fn reads_are_bounded_by_bytes_read_and_special_files_refused() {
        let dir = std::env::temp_dir().join(format!("tumble-limits-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let small = dir.join("small.txt");
        std::fs::write(&small, "abc").unwrap();
        assert_eq!(read_bounded(&small, 3, "scene file").unwrap(), "abc");
        let e = read_bounded(&small, 2, "scene file").unwrap_err();
        assert!(
            e.to_string().contains("small.txt") && e.reason.contains("limit of 2"),
            "{e}"
        );
        // /dev/zero says it is 0 bytes long and never ends: refused by its type.
        if std::path::Path::new("/dev/zero").exists() {
            let e = read_bounded(std::path::Path::new("/dev/zero"), 16, "CSV").unwrap_err();
            assert!(e.reason.contains("character device"), "{e}");
        }
        let e = read_bounded(&dir, 16, "mesh").unwrap_err();
        assert!(e.reason.contains("is a directory"), "{e}");
        let e = read_bounded(&dir.join("none"), 16, "mesh").unwrap_err();
        assert!(e.reason.contains("no such file"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_long_number_is_shortened() {
        assert_eq!(short(0.001), "0.001");
        assert_eq!(short(1e300), "1.000e300");
    }
}
