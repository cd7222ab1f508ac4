//! Their rows against tumble's: the same numbers `run` prints, at the same steps, each column
//! measured on its quantity's scale.
//!
//! ```text
//! apart(c, row) = |theirs − ours| / scale(quantity of c)
//! scale = the largest norm of the quantity's vector over the run: |x|, |v|, |ω|, |P|, |L|,
//!         |E|, the deepest penetration, the last t; 1 for a rotation (q and −q are one
//!         rotation: their quaternion is compared with the sign that brings it nearest ours);
//!         a quantity that stays 0 over the whole run is compared absolutely (scale 1)
//! a column parts at the first row where apart > REL (or their number is not finite)
//! ```

use super::theirs::{Column, Quantity, Theirs};
use crate::physics::{BodyView, Phase, Snapshot, World};
use nalgebra::{Matrix3, Vector3};

/// Every number a row of `run` holds, and what `run` does not print (R, P).
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub t: f64,
    pub position: Vector3<f64>,
    /// (w, x, y, z).
    pub quaternion: [f64; 4],
    pub rotation: Matrix3<f64>,
    pub velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
    pub momentum: Vector3<f64>,
    pub angular_momentum: Vector3<f64>,
    pub energy: f64,
    pub penetration: f64,
}

impl Sample {
    /// The row `run` prints for body `index` of a world now (plus R and P).
    pub fn of(world: &World, index: usize) -> Sample {
        let s = Snapshot::of_body(world, index);
        let q = s.quaternion.quaternion();
        Sample {
            t: s.time,
            position: s.position,
            quaternion: [q.w, q.i, q.j, q.k],
            rotation: s.rotation,
            velocity: s.velocity,
            angular_velocity: s.angular_velocity,
            momentum: s.linear_momentum,
            angular_momentum: s.angular_momentum,
            energy: s.system.energy.total,
            penetration: s.penetration,
        }
    }

    /// The number in column `c` (`step` has none: NaN).
    pub fn value(&self, c: Column) -> f64 {
        match c {
            Column::Step => f64::NAN,
            Column::T => self.t,
            Column::X(i) => self.position[i],
            Column::Q(i) => self.quaternion[i],
            Column::R(i, j) => self.rotation[(i, j)],
            Column::V(i) => self.velocity[i],
            Column::W(i) => self.angular_velocity[i],
            Column::P(i) => self.momentum[i],
            Column::L(i) => self.angular_momentum[i],
            Column::Energy => self.energy,
            Column::Penetration => self.penetration,
        }
    }
}

/// The scale each quantity is compared on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    largest: [f64; Quantity::ALL.len()],
}

impl Default for Scales {
    fn default() -> Scales {
        Scales {
            largest: [0.0; Quantity::ALL.len()],
        }
    }
}

impl Scales {
    /// Takes the norms of one state of the run into account.
    pub fn observe(&mut self, quantity: Quantity, norm: f64) {
        let k = quantity as usize;
        if norm.is_finite() && norm > self.largest[k] {
            self.largest[k] = norm;
        }
    }

    /// The scale of a quantity: its largest norm over the run, 1 for a rotation, 1 when it
    /// stayed 0.
    pub fn of(&self, quantity: Quantity) -> f64 {
        let largest = self.largest[quantity as usize];
        if quantity == Quantity::Rotation || largest == 0.0 {
            1.0
        } else {
            largest
        }
    }
}

/// tumble's run at their rows' steps.
#[derive(Debug, Clone)]
pub struct Ours {
    /// One per row of theirs.
    pub samples: Vec<Sample>,
    /// Per row: whether the collide phase changed the body's state at that step.
    pub collided: Vec<bool>,
    pub scales: Scales,
}

/// Steps `world` to their last row, keeping body `index`'s rows at their steps; Err with the
/// divergence's message when the run diverges first.
pub fn run_ours(mut world: World, index: usize, theirs: &Theirs) -> Result<Ours, String> {
    let mut samples = Vec::with_capacity(theirs.rows.len());
    let mut collided = Vec::with_capacity(theirs.rows.len());
    let mut scales = Scales::default();
    let last = theirs.rows.last().map_or(0, |r| r.step);
    let mut rows = theirs.rows.iter().peekable();
    let mut changed = false;
    for step in 0..=last {
        if step > 0 {
            // The four phases, the state kept before the collide phase.
            while world.step_phase() != Phase::Integrate {}
            let before = world.states()[index];
            world.step_phase();
            changed = world.states()[index] != before;
            if let Some(divergence) = world.divergence() {
                return Err(divergence.to_string());
            }
        }
        observe(&world, index, &mut scales);
        if rows.peek().is_some_and(|r| r.step == step) {
            rows.next();
            let sample = Sample::of(&world, index);
            scales.observe(Quantity::Penetration, sample.penetration);
            samples.push(sample);
            collided.push(changed);
        }
    }
    Ok(Ours {
        samples,
        collided,
        scales,
    })
}

/// The norms of body `index`'s state now.
fn observe(world: &World, index: usize, scales: &mut Scales) {
    let body = BodyView::of(world, index);
    scales.observe(Quantity::Time, world.time());
    scales.observe(Quantity::Position, body.position.norm());
    scales.observe(Quantity::Velocity, body.velocity.norm());
    scales.observe(Quantity::AngularVelocity, body.angular_velocity.norm());
    scales.observe(Quantity::Momentum, body.linear_momentum.norm());
    scales.observe(Quantity::AngularMomentum, body.angular_momentum.norm());
    scales.observe(Quantity::Energy, world.total_energy().total.abs());
}

/// How far apart one column is over the run.
#[derive(Debug, Clone, PartialEq)]
pub struct ColumnDiff {
    pub column: Column,
    /// max |theirs − ours|.
    pub max_abs: f64,
    /// max of that over the quantity's scale.
    pub max_rel: f64,
    /// The first row (index into theirs) where it parts.
    pub first: Option<usize>,
}

/// Their rows against a run's samples (tumble's, or a planted mistake's).
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    pub columns: Vec<ColumnDiff>,
    /// Per row, per column: |theirs − ours| / scale (∞ when theirs is not finite).
    pub apart: Vec<Vec<f64>>,
}

/// |theirs − ours| per column of one row, with a quaternion's sign brought nearest ours (∞
/// when one of the two is not finite, 0 when neither is).
pub fn row_differences(columns: &[Column], values: &[f64], ours: &Sample) -> Vec<f64> {
    // q and −q: one rotation.
    let dot: f64 = (columns.iter().zip(values))
        .filter_map(|(&c, v)| match c {
            Column::Q(i) => Some(v * ours.quaternion[i]),
            _ => None,
        })
        .sum();
    let sign = if dot < 0.0 { -1.0 } else { 1.0 };
    columns
        .iter()
        .zip(values)
        .map(|(&c, &v)| {
            let theirs = if matches!(c, Column::Q(_)) {
                sign * v
            } else {
                v
            };
            let mine = ours.value(c);
            match (theirs.is_finite(), mine.is_finite()) {
                (true, true) => (theirs - mine).abs(),
                // Both blew up (a planted run that overflows as theirs does).
                (false, false) => 0.0,
                _ => f64::INFINITY,
            }
        })
        .collect()
}

/// Compares every row; `columns` limits which columns count (None: all).
pub fn compare(theirs: &Theirs, ours: &[Sample], scales: &Scales, tolerance: f64) -> Comparison {
    let mut columns: Vec<ColumnDiff> = (theirs.columns.iter())
        .map(|&column| ColumnDiff {
            column,
            max_abs: 0.0,
            max_rel: 0.0,
            first: None,
        })
        .collect();
    let mut apart = Vec::with_capacity(ours.len());
    for (r, (row, sample)) in theirs.rows.iter().zip(ours).enumerate() {
        let abs = row_differences(&theirs.columns, &row.values, sample);
        let mut rel_row = Vec::with_capacity(abs.len());
        for (d, a) in columns.iter_mut().zip(abs) {
            let scale = d.column.quantity().map_or(1.0, |q| scales.of(q));
            let rel = a / scale;
            d.max_abs = d.max_abs.max(a);
            d.max_rel = d.max_rel.max(rel);
            if rel > tolerance && d.first.is_none() {
                d.first = Some(r);
            }
            rel_row.push(rel);
        }
        apart.push(rel_row);
    }
    Comparison { columns, apart }
}

impl Comparison {
    /// Whether every column agrees on every row.
    pub fn agrees(&self) -> bool {
        self.columns.iter().all(|c| c.first.is_none())
    }

    /// The first row where some column parts.
    pub fn first_row(&self) -> Option<usize> {
        self.columns.iter().filter_map(|c| c.first).min()
    }

    /// Per quantity given: the first row where one of its columns parts, and the column that
    /// is farthest apart there (None: it agrees).
    pub fn per_quantity(&self) -> Vec<(Quantity, Option<(usize, Column)>)> {
        let mut out = Vec::new();
        for q in Quantity::ALL {
            let mine: Vec<(usize, &ColumnDiff)> = (self.columns.iter().enumerate())
                .filter(|(_, c)| c.column.quantity() == Some(q))
                .collect();
            if mine.is_empty() {
                continue;
            }
            let first = mine.iter().filter_map(|(_, c)| c.first).min();
            let parting = first.map(|row| {
                let (k, _) = mine
                    .iter()
                    .max_by(|a, b| self.apart[row][a.0].total_cmp(&self.apart[row][b.0]))
                    .expect("the quantity has a column");
                (row, self.columns[*k].column)
            });
            out.push((q, parting));
        }
        out
    }

    /// The quantities that part at row `row`.
    pub fn parted_at(&self, row: usize, tolerance: f64) -> Vec<Quantity> {
        let mut out: Vec<Quantity> = (self.columns.iter().zip(&self.apart[row]))
            .filter(|(_, &a)| a > tolerance)
            .filter_map(|(c, _)| c.column.quantity())
            .collect();
        out.sort();
        out.dedup();
        out
    }
}

/// The phase of the loop that writes a quantity at a step (`collided`: the collide phase
/// changed the body then), with the formula.
pub fn written_by(
    quantity: Quantity,
    integrator: crate::physics::Integrator,
    collided: bool,
) -> (Phase, String) {
    use crate::physics::Integrator as I;
    let euler = matches!(integrator, I::EulerSeed | I::Euler | I::SymplecticEuler);
    let step = |formula: &str| {
        if euler {
            formula.to_string()
        } else {
            format!("one {} step", integrator.name())
        }
    };
    match quantity {
        Quantity::Time => (Phase::Integrate, "t = step·dt".into()),
        Quantity::Position if collided => (Phase::Collide, "the response moves x".into()),
        Quantity::Position if integrator == I::SymplecticEuler => {
            (Phase::Integrate, "x += dt·v (the new v)".into())
        }
        Quantity::Position => (Phase::Integrate, step("x += dt·v")),
        Quantity::Rotation if integrator == I::EulerSeed => {
            (Phase::Integrate, "R += dt·ω*·R".into())
        }
        Quantity::Rotation => (Phase::Integrate, step("q += dt·½ω⊗q, normalised")),
        Quantity::Velocity => (Phase::Derive, "v = P/M".into()),
        Quantity::AngularVelocity => (Phase::Derive, "ω = R I⁻¹_body Rᵀ L".into()),
        Quantity::Momentum | Quantity::AngularMomentum if collided => {
            (Phase::Collide, "the response changes P and L".into())
        }
        Quantity::Momentum => (Phase::Integrate, step("P += dt·F")),
        Quantity::AngularMomentum => (Phase::Integrate, step("L += dt·τ")),
        Quantity::Energy => (Phase::Derive, "E = ½M v² + ½ω·L − M g·x".into()),
        Quantity::Penetration => (Phase::Collide, "the deepest depth after the step".into()),
    }
}

/// The phase where the loop first goes wrong, read from the quantities that part at the first
/// parting row (the loop's data flow: derive reads x, R, P, L and writes v, ω; forces writes
/// F, τ, which only P and L show; integrate writes x, R, P, L):
///
/// - the collide phase acted at that step and a state quantity parts → collide;
/// - the position, the rotation or t parts → integrate (only it writes them without a contact);
/// - the momenta part (v, P, L) while x and R agree → forces (F or τ);
/// - only ω or the energy parts, the state agreeing → derive.
pub fn loop_phase(parted: &[Quantity], collided: bool) -> (Phase, &'static str) {
    let any = |qs: &[Quantity]| parted.iter().any(|p| qs.contains(p));
    if collided && parted.iter().any(|q| q.is_state()) {
        return (
            Phase::Collide,
            "a contact acted at this step and the state parts",
        );
    }
    if any(&[Quantity::Position, Quantity::Rotation, Quantity::Time]) {
        return (
            Phase::Integrate,
            "the position or the rotation parts: only the integrate phase writes them",
        );
    }
    if any(&[
        Quantity::Velocity,
        Quantity::Momentum,
        Quantity::AngularMomentum,
    ]) {
        return (
            Phase::Forces,
            "the momenta part while x and R agree: a different F or τ",
        );
    }
    if any(&[Quantity::Penetration]) {
        return (Phase::Collide, "only the penetration parts");
    }
    (
        Phase::Derive,
        "only ω or the energy parts while the state agrees: ω = I⁻¹_world L computed otherwise",
    )
}
