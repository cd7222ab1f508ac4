//! The graph of any quantity (key `p`): what can be plotted, its values frame by frame, and the
//! CSV of what is plotted (key `X`).
//!
//! Every quantity of every moving body is recorded as the run goes (one row per kept frame,
//! thinned by halves when long, like the energy series), so picking another quantity shows its
//! whole past at once. Names are the live numbers' (`cube.y`, `cube.energy`, `energy`, `Px`),
//! plus `BODY.|L|` and `JOINT.error`:
//!
//! ```text
//! per body   x y z   vx vy vz = P/M   wx wy wz = I⁻¹L   Lx Ly Lz   |L|   speed = |v|
//!            kinetic = ½ M v·v + ½ ω·L   potential = −M g·x   energy = kinetic + potential
//! scene      energy (bodies, particles, springs)   Px Py Pz = Σ P
//! per joint  error: ball, hinge, fixed |anchor A − anchor B|; distance |separation − length|
//! ```
//!
//! Values are read from the world's snapshot between frames by the live numbers' reader
//! ([`crate::live::value`]), so a plotted number is the one the panels and the pages show at
//! that frame.

use crate::physics::Snapshot;
pub use crate::scene::live::Measure;

/// Rows kept before the series is thinned to every other row.
pub const MAX_ROWS: usize = 4096;

/// A plottable quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Of body `body`.
    Body { body: usize, measure: Measure },
    /// The whole scene's energy, J.
    SceneEnergy,
    /// The whole scene's linear momentum component, kg·m/s.
    SceneMomentum(usize),
    /// Joint `joint`'s position error, m.
    JointError(usize),
}

/// A column: the quantity, its name (as typed in a page: `cube.y`) and its unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Column {
    pub quantity: Quantity,
    pub name: String,
    pub unit: &'static str,
}

/// The per-body names and units, in the order the picker lists them.
const BODY_COLUMNS: [(&str, Measure, &str); 17] = [
    ("x", Measure::Position(0), "m"),
    ("y", Measure::Position(1), "m"),
    ("z", Measure::Position(2), "m"),
    ("vx", Measure::Velocity(0), "m/s"),
    ("vy", Measure::Velocity(1), "m/s"),
    ("vz", Measure::Velocity(2), "m/s"),
    ("wx", Measure::AngularVelocity(0), "rad/s"),
    ("wy", Measure::AngularVelocity(1), "rad/s"),
    ("wz", Measure::AngularVelocity(2), "rad/s"),
    ("Lx", Measure::AngularMomentum(0), "kg·m²/s"),
    ("Ly", Measure::AngularMomentum(1), "kg·m²/s"),
    ("Lz", Measure::AngularMomentum(2), "kg·m²/s"),
    ("|L|", Measure::AngularMomentumNorm, "kg·m²/s"),
    ("speed", Measure::Speed, "m/s"),
    ("kinetic", Measure::Kinetic, "J"),
    ("potential", Measure::Potential, "J"),
    ("energy", Measure::Energy, "J"),
];

impl Quantity {
    /// The body and measure the live numbers' reader takes (scene-wide ones of body 0).
    pub fn reading(self) -> (usize, Measure) {
        match self {
            Quantity::Body { body, measure } => (body, measure),
            Quantity::SceneEnergy => (0, Measure::SceneEnergy),
            Quantity::SceneMomentum(i) => (0, Measure::SceneMomentum(i)),
            Quantity::JointError(j) => (0, Measure::JointError(j)),
        }
    }
}

/// Every quantity a snapshot offers, in the picker's order: each moving body's, then the
/// scene's, then each joint's error.
pub fn columns(snapshot: &Snapshot) -> Vec<Column> {
    let mut out = Vec::new();
    for (body, view) in snapshot.bodies.iter().enumerate() {
        if view.fixed {
            continue;
        }
        for (what, measure, unit) in BODY_COLUMNS {
            out.push(Column {
                quantity: Quantity::Body { body, measure },
                name: format!("{}.{what}", view.name),
                unit,
            });
        }
    }
    out.push(Column {
        quantity: Quantity::SceneEnergy,
        name: "energy".into(),
        unit: "J",
    });
    for (i, axis) in ["Px", "Py", "Pz"].into_iter().enumerate() {
        out.push(Column {
            quantity: Quantity::SceneMomentum(i),
            name: axis.into(),
            unit: "kg·m/s",
        });
    }
    for (joint, j) in snapshot.joints.iter().enumerate() {
        out.push(Column {
            quantity: Quantity::JointError(joint),
            name: format!("{}.error", j.name),
            unit: "m",
        });
    }
    out
}

/// The value of every column in a snapshot, in the columns' order.
pub fn values(snapshot: &Snapshot, columns: &[Column]) -> Vec<f64> {
    columns
        .iter()
        .map(|c| {
            let (body, measure) = c.quantity.reading();
            crate::live::value(snapshot, body, measure)
        })
        .collect()
}

/// What is plotted: a quantity against time, or against another quantity (a phase portrait).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlotChoice {
    /// Column index of the vertical axis.
    pub y: usize,
    /// Column index of the horizontal axis; None: time.
    pub x: Option<usize>,
}

/// Most curves one graph shows (the picker's `a` adds them after the first).
pub const MAX_CURVES: usize = 4;

/// Which axis each curve of a graph reads on: the first curve's unit on the left axis, a
/// second unit on a right axis of its own; a curve of a third unit has no axis and is left
/// out (the picker refuses to add it).
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAxes {
    /// The curves kept, in order (column indices).
    pub curves: Vec<usize>,
    /// The left axis's unit (the first curve's).
    pub left: &'static str,
    /// The right axis's unit, when some curve's unit differs from the first's.
    pub right: Option<&'static str>,
    /// Per kept curve: it reads on the right axis.
    pub on_right: Vec<bool>,
}

/// The axes of a graph of `curves` (column indices, the first one's unit on the left).
pub fn curve_axes(columns: &[Column], curves: &[usize]) -> CurveAxes {
    let mut out = CurveAxes {
        curves: Vec::new(),
        left: curves
            .first()
            .and_then(|&c| columns.get(c))
            .map_or("", |c| c.unit),
        right: None,
        on_right: Vec::new(),
    };
    for &c in curves {
        let Some(column) = columns.get(c) else {
            continue;
        };
        if out.curves.contains(&c) || out.curves.len() == MAX_CURVES {
            continue;
        }
        let right = if column.unit == out.left {
            false
        } else if out.right.is_none_or(|r| r == column.unit) {
            out.right = Some(column.unit);
            true
        } else {
            continue;
        };
        out.curves.push(c);
        out.on_right.push(right);
    }
    out
}

/// Every column's values over the run, one row per kept frame.
#[derive(Debug, Clone)]
pub struct PlotSeries {
    pub columns: Vec<Column>,
    steps: Vec<u64>,
    times: Vec<f64>,
    /// Row-major: `columns.len()` values per row.
    values: Vec<f64>,
    /// Record one frame in `stride`.
    stride: u64,
}

impl PlotSeries {
    /// A series holding the snapshot of the world now (t = 0).
    pub fn new(snapshot: &Snapshot) -> PlotSeries {
        let mut series = PlotSeries {
            columns: columns(snapshot),
            steps: Vec::new(),
            times: Vec::new(),
            values: Vec::new(),
            stride: 1,
        };
        series.record(snapshot);
        series
    }

    /// Whether the frame of `step` is one kept (one in `stride`): only then does
    /// [`PlotSeries::record`] need its snapshot.
    pub fn keeps(&self, step: u64) -> bool {
        step.is_multiple_of(self.stride)
    }

    /// Records the snapshot of a world after a whole frame, if its step is one kept (one in
    /// `stride`).
    pub fn record(&mut self, snapshot: &Snapshot) {
        let step = snapshot.step;
        if !step.is_multiple_of(self.stride) {
            return;
        }
        if self.steps.last().is_some_and(|&s| s >= step) {
            self.truncate_after_step(step.saturating_sub(1));
        }
        self.steps.push(step);
        self.times.push(snapshot.time);
        self.values.extend(values(snapshot, &self.columns));
        if self.steps.len() > MAX_ROWS {
            self.stride *= 2;
            let n = self.columns.len();
            let keep: Vec<bool> = self
                .steps
                .iter()
                .map(|s| s.is_multiple_of(self.stride))
                .collect();
            let mut row = 0;
            self.values.retain(|_| {
                let k = keep[row / n.max(1)];
                row += 1;
                k
            });
            let mut i = 0;
            self.times.retain(|_| {
                i += 1;
                keep[i - 1]
            });
            self.steps.retain(|s| s.is_multiple_of(self.stride));
        }
    }

    /// Forgets the rows after time `t` (stepping back).
    pub fn truncate_after(&mut self, t: f64) {
        let keep = self.times.partition_point(|&x| x <= t + 1e-12);
        self.cut(keep);
    }

    fn truncate_after_step(&mut self, step: u64) {
        let keep = self.steps.partition_point(|&s| s <= step);
        self.cut(keep);
    }

    fn cut(&mut self, rows: usize) {
        self.steps.truncate(rows);
        self.times.truncate(rows);
        self.values.truncate(rows * self.columns.len());
    }

    /// Rows kept.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Column `c`'s values, one per row.
    pub fn column(&self, c: usize) -> impl Iterator<Item = f64> + '_ {
        let n = self.columns.len();
        (0..self.len()).map(move |row| self.values[row * n + c])
    }

    /// The points of a choice: (t or x, y) per row.
    pub fn points(&self, choice: PlotChoice) -> Vec<(f64, f64)> {
        let y = self.column(choice.y);
        match choice.x {
            None => self.times.iter().copied().zip(y).collect(),
            Some(x) => self.column(x).zip(y).collect(),
        }
    }

    /// The CSV of what is plotted: `step,t,` then the x column (if any) and the y column's
    /// name; every value printed in full (the shortest text that reads back to the same f64).
    pub fn csv(&self, choice: PlotChoice) -> String {
        self.csv_of(choice.x, &[choice.y])
    }

    /// The CSV of several curves: `step,t,` then the x column (if any) and each curve's.
    pub fn csv_of(&self, x: Option<usize>, curves: &[usize]) -> String {
        let picked: Vec<usize> = x.into_iter().chain(curves.iter().copied()).collect();
        let mut out = String::from("step,t");
        for &c in &picked {
            out.push(',');
            out.push_str(&self.columns[c].name);
        }
        out.push('\n');
        let n = self.columns.len();
        for row in 0..self.len() {
            out.push_str(&format!("{},{}", self.steps[row], self.times[row]));
            for &c in &picked {
                out.push_str(&format!(",{}", self.values[row * n + c]));
            }
            out.push('\n');
        }
        out
    }
}

/// A column's label on an axis: `cube.y, m`.
pub fn label(column: &Column) -> String {
    format!("{}, {}", column.name, column.unit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_of_one_unit_share_an_axis_a_second_unit_takes_the_right_one() {
        let lesson =
            crate::lessons::load(std::path::Path::new("lessons/05-ground-collision.toml")).unwrap();
        let columns = columns(&lesson.scene.world().snapshot());
        let at = |name: &str| columns.iter().position(|c| c.name == name).unwrap();
        let (y, x, vy, k) = (
            at("body1.y"),
            at("body1.x"),
            at("body1.vy"),
            at("body1.kinetic"),
        );
        let axes = curve_axes(&columns, &[y, x]);
        assert_eq!((axes.left, axes.right), ("m", None));
        assert_eq!(axes.on_right, [false, false]);
        // m/s goes right; J would be a third unit: left out; a repeat is kept once.
        let axes = curve_axes(&columns, &[y, vy, k, x, y]);
        assert_eq!(axes.curves, [y, vy, x]);
        assert_eq!((axes.left, axes.right), ("m", Some("m/s")));
        assert_eq!(axes.on_right, [false, true, false]);
    }

    #[test]
    fn thinning_keeps_every_other_row_and_the_columns_aligned() {
        let lesson =
            crate::lessons::load(std::path::Path::new("lessons/05-ground-collision.toml")).unwrap();
        let mut world = lesson.scene.world();
        let mut series = PlotSeries::new(&world.snapshot());
        let t = series
            .columns
            .iter()
            .position(|c| c.name.ends_with(".y"))
            .unwrap();
        for _ in 0..(MAX_ROWS as u64 + 10) {
            world.step();
            series.record(&world.snapshot());
        }
        // 4107 rows were offered; past 4096 the stride doubled: even steps only.
        assert!(series.len() <= MAX_ROWS && series.len() > MAX_ROWS / 2);
        assert!(series.steps.iter().all(|s| s % 2 == 0));
        // The last row is the world now (step 4106 is even).
        let last_y = series.column(t).last().unwrap();
        assert_eq!(last_y, world.states()[0].position.y);
        assert_eq!(*series.times.last().unwrap(), world.time());
    }
}
