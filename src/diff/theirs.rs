//! THEIRS.csv: a trajectory computed elsewhere, one row per kept step.
//!
//! The header names any subset of `run`'s columns (`step,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,
//! Lx,Ly,Lz,energy,penetration`), in any order; `step` or `t` is required. A rotation is given
//! whole, as `qw qx qy qz` or as the matrix `R11 … R33` (row, column; 1-based), or both. Beside
//! `run`'s names, `Px Py Pz` (the linear momentum, which `run` prints as v = P/M) and the
//! report's own member names are accepted:
//!
//! | report | tumble column |
//! |---|---|
//! | `_Position.x` (or `_Position[0]`) | `x` |
//! | `_Vitesse.x` | `vx` |
//! | `_VitesseAngulaire.x` | `wx` |
//! | `_QuantiteMouvement.x` | `Px` |
//! | `_MomentCinetique.x` | `Lx` |
//! | `_Rotation[0][0]` … `_Rotation[2][2]` (C++ indices, from 0) | `R11` … `R33` |
//!
//! Every cell is a number (`nan` and `inf` are numbers: a diverged loop is still compared);
//! `step` is a whole number ≥ 0; rows go forward in time (`step`, else `t`, increases). Each
//! failure is one line naming file:line.

use crate::scene::did_you_mean;
use std::fmt;
use std::path::Path;

/// What one column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Column {
    Step,
    T,
    /// Barycenter x, y, z.
    X(usize),
    /// Quaternion: 0 = w, 1..3 = x, y, z.
    Q(usize),
    /// The rotation matrix, row and column from 0.
    R(usize, usize),
    /// v = P/M.
    V(usize),
    /// ω, world frame.
    W(usize),
    /// P (not a `run` column: the report's `_QuantiteMouvement`).
    P(usize),
    /// L about the barycenter.
    L(usize),
    Energy,
    Penetration,
}

/// A quantity: the columns that make one vector (or scalar), compared on one scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    Time,
    Position,
    Rotation,
    Velocity,
    AngularVelocity,
    Momentum,
    AngularMomentum,
    Energy,
    Penetration,
}

impl Quantity {
    /// Every quantity, in the order the report lists them.
    pub const ALL: [Quantity; 9] = [
        Quantity::Time,
        Quantity::Position,
        Quantity::Rotation,
        Quantity::Velocity,
        Quantity::AngularVelocity,
        Quantity::Momentum,
        Quantity::AngularMomentum,
        Quantity::Energy,
        Quantity::Penetration,
    ];

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Time => "time",
            Quantity::Position => "position",
            Quantity::Rotation => "rotation",
            Quantity::Velocity => "velocity",
            Quantity::AngularVelocity => "angular velocity",
            Quantity::Momentum => "momentum",
            Quantity::AngularMomentum => "angular momentum",
            Quantity::Energy => "energy",
            Quantity::Penetration => "penetration",
        }
    }

    /// Whether the quantity is part of the state (x, R, P, L) rather than derived from it.
    pub fn is_state(self) -> bool {
        matches!(
            self,
            Quantity::Position
                | Quantity::Rotation
                | Quantity::Velocity
                | Quantity::Momentum
                | Quantity::AngularMomentum
        )
    }
}

const AXES: [&str; 3] = ["x", "y", "z"];
const QUATERNION: [&str; 4] = ["qw", "qx", "qy", "qz"];

impl Column {
    /// Its name as `run` prints it (`R11` … `R33` and `Px` … for the columns `run` does not
    /// print).
    pub fn name(self) -> String {
        match self {
            Column::Step => "step".into(),
            Column::T => "t".into(),
            Column::X(i) => AXES[i].into(),
            Column::Q(i) => QUATERNION[i].into(),
            Column::R(i, j) => format!("R{}{}", i + 1, j + 1),
            Column::V(i) => format!("v{}", AXES[i]),
            Column::W(i) => format!("w{}", AXES[i]),
            Column::P(i) => format!("P{}", AXES[i]),
            Column::L(i) => format!("L{}", AXES[i]),
            Column::Energy => "energy".into(),
            Column::Penetration => "penetration".into(),
        }
    }

    /// The quantity it belongs to (`step` is the row's key: none).
    pub fn quantity(self) -> Option<Quantity> {
        Some(match self {
            Column::Step => return None,
            Column::T => Quantity::Time,
            Column::X(_) => Quantity::Position,
            Column::Q(_) | Column::R(..) => Quantity::Rotation,
            Column::V(_) => Quantity::Velocity,
            Column::W(_) => Quantity::AngularVelocity,
            Column::P(_) => Quantity::Momentum,
            Column::L(_) => Quantity::AngularMomentum,
            Column::Energy => Quantity::Energy,
            Column::Penetration => Quantity::Penetration,
        })
    }

    /// Every name a header may use: `run`'s, `R11` … `R33`, `Px` … `Pz`.
    fn tumble_names() -> Vec<(String, Column)> {
        let mut all = vec![("step".to_string(), Column::Step), ("t".into(), Column::T)];
        for i in 0..3 {
            all.push((Column::X(i).name(), Column::X(i)));
        }
        for i in 0..4 {
            all.push((Column::Q(i).name(), Column::Q(i)));
        }
        for make in [Column::V, Column::W, Column::L, Column::P] {
            for i in 0..3 {
                all.push((make(i).name(), make(i)));
            }
        }
        all.push(("energy".into(), Column::Energy));
        all.push(("penetration".into(), Column::Penetration));
        for i in 0..3 {
            for j in 0..3 {
                all.push((Column::R(i, j).name(), Column::R(i, j)));
            }
        }
        all
    }

    /// The column a header name means, if any: `run`'s names and the report's members.
    pub fn from_name(name: &str) -> Option<Column> {
        if let Some((_, c)) = Column::tumble_names().into_iter().find(|(n, _)| n == name) {
            return Some(c);
        }
        report_name(name)
    }
}

/// A vector column by its axis (`Column::X`, …).
type Axis = fn(usize) -> Column;

/// The report's member names: `_Position.x`, `_Position[0]`, `_Rotation[i][j]`, ….
fn report_name(name: &str) -> Option<Column> {
    if let Some(rest) = name.strip_prefix("_Rotation") {
        let digits: Vec<usize> = rest
            .split(['[', ']'])
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().ok().filter(|&d: &usize| d < 3))
            .collect::<Option<_>>()?;
        return match (digits.as_slice(), rest.starts_with('[')) {
            ([i, j], true) => Some(Column::R(*i, *j)),
            _ => None,
        };
    }
    let members: [(&str, Axis); 5] = [
        ("_Position", Column::X),
        ("_VitesseAngulaire", Column::W),
        ("_Vitesse", Column::V),
        ("_QuantiteMouvement", Column::P),
        ("_MomentCinetique", Column::L),
    ];
    for (member, make) in members {
        let Some(rest) = name.strip_prefix(member) else {
            continue;
        };
        let axis = match rest {
            ".x" | "[0]" => 0,
            ".y" | "[1]" => 1,
            ".z" | "[2]" => 2,
            _ => continue,
        };
        return Some(make(axis));
    }
    None
}

/// `run`'s columns, for error messages.
const RUN_COLUMNS: &str = "step t x y z qw qx qy qz vx vy vz wx wy wz Lx Ly Lz energy penetration";

/// One row of THEIRS.csv.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Its line in the file (1-based).
    pub line: usize,
    /// The step it is at: its `step` cell, else the nearest whole `t / dt`.
    pub step: u64,
    /// One number per compared column (every column but `step`), in [`Theirs::columns`] order.
    pub values: Vec<f64>,
}

/// THEIRS.csv, parsed.
#[derive(Debug, Clone, PartialEq)]
pub struct Theirs {
    /// The compared columns (every column of the header but `step`), in header order.
    pub columns: Vec<Column>,
    pub rows: Vec<Row>,
}

/// A CSV that cannot be compared: its file, line and why.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvError {
    pub file: String,
    pub line: usize,
    pub message: String,
}

impl fmt::Display for CsvError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Line 0: an error about the file as a whole (it cannot be read).
        match self.line {
            0 => write!(f, "{}: {}", self.file, self.message),
            line => write!(f, "{}:{line}: {}", self.file, self.message),
        }
    }
}

/// The largest THEIRS.csv read, bytes (it is read whole: 256 MiB is a million rows of every
/// column in full precision, far beyond any practical's run).
pub const MAX_CSV_BYTES: u64 = 256 << 20;

/// Reads and parses THEIRS.csv; `dt` turns a `t` into a step when there is no `step` column.
pub fn read(path: &Path, dt: f64) -> Result<Theirs, CsvError> {
    let file = path.display().to_string();
    let fail = |line: usize, message: String| CsvError {
        file: file.clone(),
        line,
        message,
    };
    // Read as every input is (`limits::read_bounded_bytes`): at most MAX_CSV_BYTES bytes
    // read, whatever the metadata says (/dev/zero says 0), FIFOs and devices refused by type.
    let text = crate::limits::read_bounded_bytes(path, MAX_CSV_BYTES, "CSV")
        .map_err(|e| fail(0, e.reason))?;
    let text = String::from_utf8(text).map_err(|e| {
        let line = 1 + e.as_bytes()[..e.utf8_error().valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        fail(line, "not UTF-8 text".into())
    })?;
    parse(&text, dt).map_err(|(line, message)| fail(line, message))
}

/// Parses the text of a CSV; errors are (line, message).
pub fn parse(text: &str, dt: f64) -> Result<Theirs, (usize, String)> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((header_line, header)) = lines.next() else {
        return Err((1, "empty: expected a header line naming the columns".into()));
    };
    let names: Vec<&str> = header
        .split(',')
        .map(|s| s.trim().trim_matches('"'))
        .collect();
    let mut all = Vec::with_capacity(names.len());
    for name in &names {
        let column = Column::from_name(name).ok_or_else(|| {
            let known = Column::tumble_names();
            let hint = did_you_mean(name, known.iter().map(|(n, _)| n.as_str()))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            (
                header_line,
                format!(
                    "unknown column `{}`{hint}; columns: {} (or R11 … R33, Px Py Pz, the \
                     report's _Position.x …)",
                    crate::scene::printable(name),
                    RUN_COLUMNS
                ),
            )
        })?;
        if all.contains(&column) {
            return Err((header_line, format!("column `{name}` is given twice")));
        }
        all.push(column);
    }
    let has_step = all.contains(&Column::Step);
    if !has_step && !all.contains(&Column::T) {
        return Err((
            header_line,
            "no `step` or `t` column: a row needs one to say when it is".into(),
        ));
    }
    let quaternion = (0..4).filter(|&i| all.contains(&Column::Q(i))).count();
    if quaternion != 0 && quaternion != 4 {
        return Err((
            header_line,
            "a quaternion needs all four columns qw, qx, qy, qz".into(),
        ));
    }
    let matrix = (0..9)
        .filter(|&k| all.contains(&Column::R(k / 3, k % 3)))
        .count();
    if matrix != 0 && matrix != 9 {
        return Err((
            header_line,
            "a rotation matrix needs all nine columns R11 … R33".into(),
        ));
    }
    let step_index = all.iter().position(|&c| c == Column::Step);
    let t_index = all.iter().position(|&c| c == Column::T);
    let columns: Vec<Column> = all.iter().copied().filter(|&c| c != Column::Step).collect();
    let mut rows: Vec<Row> = Vec::new();
    let mut last_t = f64::NEG_INFINITY;
    for (line, text) in lines {
        let cells: Vec<&str> = text.split(',').map(str::trim).collect();
        if cells.len() != all.len() {
            return Err((
                line,
                format!(
                    "{} cells, the header names {} columns",
                    cells.len(),
                    all.len()
                ),
            ));
        }
        let mut values = Vec::with_capacity(columns.len());
        let mut step = None;
        let mut t = None;
        for (k, cell) in cells.iter().enumerate() {
            let value: f64 = cell.parse().map_err(|_| {
                (
                    line,
                    format!(
                        "column `{}`: `{}` is not a number",
                        names[k],
                        crate::scene::printable(cell)
                    ),
                )
            })?;
            if Some(k) == step_index {
                if !(value >= 0.0
                    && value.fract() == 0.0
                    && value <= crate::limits::MAX_STEPS as f64)
                {
                    return Err((
                        line,
                        format!(
                            "column `step`: `{cell}` is not a whole number from 0 to {}",
                            crate::limits::MAX_STEPS
                        ),
                    ));
                }
                step = Some(value as u64);
            } else {
                if Some(k) == t_index {
                    t = Some(value);
                }
                values.push(value);
            }
        }
        let step = match (step, t) {
            (Some(step), _) => step,
            (None, Some(t)) => {
                let s = (t / dt).round();
                if !(s >= 0.0 && s <= crate::limits::MAX_STEPS as f64) {
                    return Err((
                        line,
                        format!(
                            "column `t`: {t} s is not a time of the run (t/dt must be a step \
                             from 0 to {})",
                            crate::limits::MAX_STEPS
                        ),
                    ));
                }
                s as u64
            }
            (None, None) => unreachable!("the header has step or t"),
        };
        if let Some(previous) = rows.last() {
            if step <= previous.step {
                return Err((
                    line,
                    if has_step {
                        format!(
                            "rows out of order: step {step} after step {} (line {})",
                            previous.step, previous.line
                        )
                    } else {
                        format!(
                            "rows out of order: t = {} after t = {last_t} (line {}): each row \
                             must be a later step",
                            t.unwrap_or(f64::NAN),
                            previous.line
                        )
                    },
                ));
            }
        }
        last_t = t.unwrap_or(last_t);
        rows.push(Row { line, step, values });
    }
    if rows.is_empty() {
        return Err((header_line, "no rows after the header".into()));
    }
    Ok(Theirs { columns, rows })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_names_map_to_run_columns() {
        assert_eq!(Column::from_name("_Position.y"), Some(Column::X(1)));
        assert_eq!(Column::from_name("_Position[2]"), Some(Column::X(2)));
        assert_eq!(Column::from_name("_Vitesse.x"), Some(Column::V(0)));
        assert_eq!(Column::from_name("_VitesseAngulaire.z"), Some(Column::W(2)));
        assert_eq!(
            Column::from_name("_QuantiteMouvement.z"),
            Some(Column::P(2))
        );
        assert_eq!(Column::from_name("_MomentCinetique.x"), Some(Column::L(0)));
        assert_eq!(Column::from_name("_Rotation[1][2]"), Some(Column::R(1, 2)));
        assert_eq!(Column::from_name("R23"), Some(Column::R(1, 2)));
        assert_eq!(Column::from_name("_Rotation[3][0]"), None);
        assert_eq!(Column::from_name("_Position.w"), None);
    }

    #[test]
    fn rows_keyed_by_t_alone_take_the_nearest_step() {
        let theirs = parse("t,x\n0,1\n0.01,2\n0.0200000001,3\n", 0.01).unwrap();
        assert_eq!(
            theirs.rows.iter().map(|r| r.step).collect::<Vec<_>>(),
            [0, 1, 2]
        );
        assert_eq!(theirs.columns, [Column::T, Column::X(0)]);
    }

    #[test]
    fn malformed_csvs_name_their_line() {
        let bad = |text: &str| parse(text, 0.01).unwrap_err();
        assert_eq!(bad("x,y\n1,2\n").0, 1);
        assert_eq!(bad("step,x\n0,1\n1,abc\n").0, 3);
        assert_eq!(bad("step,x,foo\n0,1,2\n").0, 1);
        assert_eq!(bad("step,x\n0,1\n2,1\n1,1\n").0, 4);
        assert_eq!(bad("step,x\n0,1\n1\n").0, 3);
        assert_eq!(bad("step,qw,qx\n0,1,0\n").0, 1);
    }
}
