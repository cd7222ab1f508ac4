//! The error beside every number (`tumble walk --error`, the app's `±` key): a reference run of
//! the same scene advances beside the shown one, and each number of the state, angular
//! velocity, momentum and energy tables gets its measured error.
//!
//! ```text
//! reference  = the same scene (same model: bodies, joints, springs, contact, effects) stepped
//!              by rk4 at dt / SUBSTEPS, SUBSTEPS steps per shown step;
//!              checked by a second run at dt / (2·SUBSTEPS)
//! ± (each number c)  = |c_shown − c_finer|        (q: the reference's sign, q and −q are one
//!                                                   rotation)
//! spread (each row)  = max_c |c_fine − c_finer|   (how much halving the reference moved it)
//! the row's reference has converged  ⇔  spread ≤ max(½ · max_c ±, 1000 · ROUND_OFF · scale)
//! ```
//!
//! Where it has not (an impact or a stick–slip switch falls between the reference's steps and
//! the shown one's, or the motion amplifies differences faster than the reference converges)
//! the row says so instead of printing a number. The cost of this accuracy: the reference
//! takes SUBSTEPS (and its check 2·SUBSTEPS) steps of rk4 per shown step; `walk` prints that
//! ratio (deterministic), the app measures ns per step of both.

use crate::physics::{Integrator, Snapshot, World};
use crate::scene::Scene;
use crate::tables::{number, number_plain, resolved, Panel, Row, ROUND_OFF};

/// Reference steps per shown step.
pub const SUBSTEPS: u64 = 10;

/// The reference's integrator.
pub const INTEGRATOR: Integrator = Integrator::Rk4;

/// The reference run and its halving check.
#[derive(Debug, Clone)]
pub struct ReferenceRun {
    fine: World,
    finer: World,
}

/// The measured error of one row of numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct RowError {
    /// The panel's title (`state`, `energy`, …) and the row's label (`x`, `K, V, E`, …).
    pub panel: String,
    pub label: String,
    /// One per printed number: |shown − reference|.
    pub errors: Vec<f64>,
    /// max |fine − finer| over the row.
    pub spread: f64,
    /// The reference resolves these errors.
    pub converged: bool,
}

impl ReferenceRun {
    /// The reference of `scene` shown at time step `dt` (the shown world's).
    pub fn new(scene: &Scene, dt: f64) -> ReferenceRun {
        ReferenceRun {
            fine: scene.world_with(INTEGRATOR, dt / SUBSTEPS as f64),
            finer: scene.world_with(INTEGRATOR, dt / (2 * SUBSTEPS) as f64),
        }
    }

    /// Advances the reference by one shown step.
    pub fn advance(&mut self) {
        for _ in 0..SUBSTEPS {
            self.fine.step();
        }
        for _ in 0..2 * SUBSTEPS {
            self.finer.step();
        }
    }

    /// The reference's time, s.
    pub fn time(&self) -> f64 {
        self.finer.time()
    }

    /// One line naming the reference and what it costs.
    pub fn describe(&self, shown: &World) -> String {
        format!(
            "± = |shown − reference|; reference: the same scene stepped by {} at dt = {} s \
             ({SUBSTEPS} steps per shown step of {} at {} s; checked by halving its step to {} s \
             — a row whose reference moved by more than half its error says so); cost: {} \
             reference steps ({}) per shown step",
            INTEGRATOR.name(),
            number_plain(self.fine.dt()),
            shown.integrator().name(),
            number_plain(shown.dt()),
            number_plain(self.finer.dt()),
            3 * SUBSTEPS,
            INTEGRATOR.name(),
        )
    }

    /// The errors of body `index`'s numbers in `shown` (which must be at the same step).
    pub fn errors(&self, shown: &World, index: usize) -> Vec<RowError> {
        let diverged = self.fine.divergence().is_some() || self.finer.divergence().is_some();
        let a = values(&shown.snapshot_of(index));
        let fine = values(&self.fine.snapshot_of(index));
        let finer = values(&self.finer.snapshot_of(index));
        a.into_iter()
            .map(|(panel, label, shown)| {
                let find = |list: &[(String, String, Vec<f64>)]| {
                    list.iter()
                        .find(|(p, l, v)| *p == panel && *l == label && v.len() == shown.len())
                        .map(|e| e.2.clone())
                };
                let (Some(mut fine), Some(mut finer)) = (find(&fine), find(&finer)) else {
                    return RowError {
                        panel,
                        label,
                        errors: Vec::new(),
                        spread: f64::INFINITY,
                        converged: false,
                    };
                };
                if label == "q" {
                    // q and −q are one rotation: compare with the reference's sign.
                    let dot =
                        |u: &[f64], w: &[f64]| -> f64 { u.iter().zip(w).map(|(x, y)| x * y).sum() };
                    for r in [&mut fine, &mut finer] {
                        if dot(r, &shown) < 0.0 {
                            r.iter_mut().for_each(|x| *x = -*x);
                        }
                    }
                }
                let scale = finer.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let resolution = ROUND_OFF * scale;
                let errors: Vec<f64> = shown
                    .iter()
                    .zip(&finer)
                    .map(|(s, r)| resolved((s - r).abs(), resolution))
                    .collect();
                let spread = fine
                    .iter()
                    .zip(&finer)
                    .map(|(f, r)| (f - r).abs())
                    .fold(0.0, f64::max);
                let largest = errors.iter().copied().fold(0.0, f64::max);
                let converged = !diverged
                    && spread.is_finite()
                    && spread <= (0.5 * largest).max(1000.0 * resolution);
                RowError {
                    panel,
                    label,
                    errors,
                    spread,
                    converged,
                }
            })
            .collect()
    }
}

/// Adds under each row of `panels` that has a measured error a `±` row: one error per number,
/// in the panels' formatter, or what kept the reference from converging.
pub fn annotate(panels: &mut [Panel], errors: &[RowError]) {
    for panel in panels.iter_mut() {
        let mut rows = Vec::with_capacity(2 * panel.rows.len());
        for row in panel.rows.drain(..) {
            let error = errors
                .iter()
                .find(|e| panel.title.starts_with(&e.panel) && e.label == row.label);
            rows.push(row);
            let Some(error) = error else { continue };
            let cells = if error.converged {
                error.errors.iter().map(|e| number(*e)).collect()
            } else if error.spread.is_finite() {
                vec![format!(
                    "  no converged reference here (halving its step moved it by {})",
                    number_plain(error.spread)
                )]
            } else {
                vec!["  no converged reference here".to_string()]
            };
            rows.push(Row {
                label: "±".to_string(),
                cells,
                unit: "",
            });
        }
        panel.rows = rows;
    }
}

/// The numbers the tables print for one body, raw: (panel, label, values), in the tables' order
/// and world frame ([`crate::tables::panels`]).
pub fn values(s: &Snapshot) -> Vec<(String, String, Vec<f64>)> {
    let q = s.quaternion.quaternion();
    let v3 = |v: &nalgebra::Vector3<f64>| vec![v.x, v.y, v.z];
    let row = |p: &str, l: &str, v: Vec<f64>| (p.to_string(), l.to_string(), v);
    let b = &s.energy_balance;
    let e = &s.system.energy;
    let mut out = vec![
        row("state", "x", v3(&s.position)),
        row("state", "q", vec![q.w, q.i, q.j, q.k]),
        row("state", "‖RᵀR−1‖", vec![s.orthonormality_error]),
        row("angular velocity", "ω", v3(&s.angular_velocity)),
        row("angular velocity", "ωbody", v3(&s.angular_velocity_body)),
        row("angular velocity", "|ω|", vec![s.angular_velocity.norm()]),
        row("linear momentum", "P", v3(&s.linear_momentum)),
        row("linear momentum", "v", v3(&s.velocity)),
        row("angular momentum", "L", v3(&s.angular_momentum)),
        row("angular momentum", "|L|", vec![s.angular_momentum.norm()]),
        row("energy", "K, V, E", vec![e.kinetic, e.potential, e.total]),
        row("energy", "E − E₀", vec![b.change]),
    ];
    if let Some(springs) = b.springs {
        out.push(row("energy", "U springs", vec![springs]));
    }
    for (label, value) in [("  drag work", b.drag_work), ("  contacts", b.contacts)] {
        if let Some(value) = value {
            out.push(row("energy", label, vec![value]));
        }
    }
    out.push(row("energy", "  drift", vec![b.drift]));
    out.push(row("energy", "drift/E₀", vec![b.relative_drift]));
    out
}

/// The app's `±` (key `u`): a reference that follows the shown world frame by frame, with the
/// errors of the selected body's numbers and the measured cost of both runs.
#[derive(Debug, Clone)]
pub struct Follow {
    reference: ReferenceRun,
    /// Shown steps the reference has covered.
    steps: u64,
    dt: f64,
    /// The errors at `steps` (None while catching up).
    pub errors: Option<Vec<RowError>>,
    /// Wall time of the reference per shown step (both runs), ns, measured.
    pub reference_ns: Option<f64>,
}

/// Shown steps the app's reference catches up per refresh at most (a jump far ahead is
/// followed over several frames, the app answering keys meanwhile).
pub const CATCH_UP: u64 = 2000;

impl Follow {
    pub fn new(scene: &Scene, world: &World) -> Follow {
        let mut scene = scene.clone();
        scene.contact = world.contact_model().copied();
        Follow {
            reference: ReferenceRun::new(&scene, world.dt()),
            steps: 0,
            dt: world.dt(),
            errors: None,
            reference_ns: None,
        }
    }

    /// Brings the reference to the shown world's step (restarting it after a rewind or a new
    /// dt), then measures the selected body's errors; mid-frame the last errors stay.
    pub fn follow(&mut self, scene: &Scene, world: &World, selected: usize) {
        let whole = matches!(
            world.last_phase(),
            None | Some(crate::physics::Phase::Collide)
        );
        if !whole {
            return;
        }
        let target = world.step_count();
        if target < self.steps || (world.dt() - self.dt).abs() > 0.0 {
            *self = Follow::new(scene, world);
        }
        let todo = (target - self.steps).min(CATCH_UP);
        if todo > 0 {
            let started = std::time::Instant::now();
            for _ in 0..todo {
                self.reference.advance();
            }
            self.steps += todo;
            self.reference_ns = Some(started.elapsed().as_nanos() as f64 / todo as f64);
        }
        self.errors = (self.steps == target).then(|| self.reference.errors(world, selected));
    }

    /// One line: the reference and what both runs cost (`shown`: the integrator shown).
    pub fn describe(&self, shown: Integrator, shown_ns: Option<f64>) -> String {
        let cost = |ns: Option<f64>| ns.map_or("—".to_string(), |n| format!("{n:.0} ns"));
        format!(
            "± vs {} at dt = {} s (and {} s), {} steps per shown step · cost per shown step: \
             shown {} ({}), reference {}",
            INTEGRATOR.name(),
            number_plain(self.dt / SUBSTEPS as f64),
            number_plain(self.dt / (2 * SUBSTEPS) as f64),
            3 * SUBSTEPS,
            cost(shown_ns),
            shown.name(),
            if self.errors.is_none() {
                "catching up…".to_string()
            } else {
                cost(self.reference_ns)
            }
        )
    }
}
