//! `soft-step`'s rows, prepared once per step into what the sweeps read and nothing more
//! (Box2D v3's contact constraints): per contact the normal n, the levers r_A, r_B, each
//! end's `r×n` and `I₀⁻¹(r×n)`, and the effective mass `1/k`,
//!
//! ```text
//! k = 1/M_A + (r_A×n)·I_A⁻¹(r_A×n) + 1/M_B + (r_B×(−n))·I_B⁻¹(r_B×(−n))
//! ```
//!
//! with I₀⁻¹ the start pose's world inverse inertia, fixed over the step: no matrix work is
//! left for the sweeps. Friction is not per row but per manifold (`patch`): the rows of one
//! pair sharing a normal. Consecutive rows between the same two bodies form a [`Run`]: a
//! sweep copies the two bodies' motions in once, and a run against an obstacle or a fixed
//! body (no B end) takes a path that reads no B. What the sweeps do not read (the approach,
//! the totals Λ) is kept beside, in [`Totals`].

use super::bodies::{Bodies, Placement};
use super::patch::{Patch, PatchTotals};
use super::Softness;
use crate::physics::collision::warm::WarmCache;
use crate::physics::collision::Contact;
use nalgebra::{Matrix3, Vector3};
use std::ops::Range;

/// One contact's normal row as the sweeps see it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Row {
    pub normal: Vector3<f64>,
    pub lever: Vector3<f64>,
    pub lever_other: Vector3<f64>,
    /// `r_A×n` and `r_B×(−n)`.
    pub rn: [Vector3<f64>; 2],
    /// `I_A⁻¹(r_A×n)` (A's end) and `I_B⁻¹(r_B×(−n))` (B's; zero without B).
    pub w_a: Vector3<f64>,
    pub w_b: Vector3<f64>,
    /// 1/k along n (0 when k is).
    pub inv_k: f64,
    /// The point's distance from its manifold's centre across the normal, m (`patch`).
    pub reach: f64,
    /// Separation at the detection pose, m.
    pub separation: f64,
    /// Separation at the bodies' current poses, m: refreshed once per sub-step.
    pub gap: f64,
    pub lambda: f64,
    pub max_lambda: f64,
}

/// What the sweeps do not read: the approach and the step's total.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Totals {
    /// Normal velocity before the response, m/s.
    pub approach: f64,
    /// Every normal impulse applied over the step (N·s, on A), Λ: the row's normal impulse
    /// is `n Λ` and its share of each body's angular momentum `(r×n) Λ`.
    pub applied: f64,
}

/// Consecutive rows between the same two bodies (B: None for an obstacle or a fixed body),
/// with their softness and their manifolds' friction (`patches`, into [`Rows::patches`]).
#[derive(Debug, Clone)]
pub(super) struct Run {
    pub a: usize,
    pub b: Option<usize>,
    pub rows: Range<usize>,
    pub patches: Range<usize>,
    pub soft: Softness,
}

/// The step's rows, their totals and runs, and the manifolds' friction.
#[derive(Debug, Clone, Default)]
pub(super) struct Rows {
    pub rows: Vec<Row>,
    pub totals: Vec<Totals>,
    pub runs: Vec<Run>,
    pub patches: Vec<Patch>,
    pub patch_totals: Vec<PatchTotals>,
    /// Per row, the impulse last step left at its feature (the warm start), while building.
    warm: Vec<Vector3<f64>>,
    /// Each manifold's rows and B's solver entry, while building.
    spans: Vec<(Range<usize>, usize)>,
}

/// One end of an axis d at lever r on a body of 1/M `inv_mass` and world I⁻¹ `inv_inertia`:
/// `r×d`, `I⁻¹(r×d)` and its share of k, `1/M + (r×d)·I⁻¹(r×d)`.
#[inline(always)]
pub(super) fn end(
    inv_mass: f64,
    inv_inertia: &Matrix3<f64>,
    lever: &Vector3<f64>,
    d: Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>, f64) {
    let rd = lever.cross(&d);
    let w = inv_inertia * rd;
    (rd, w, inv_mass + rd.dot(&w))
}

/// Whether two unit normals are those of one manifold (within 10⁻⁶ rad or so).
#[inline(always)]
fn same_normal(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    (a - b).norm_squared() < 1e-12
}

impl Rows {
    /// The rows of `contacts` over `bodies` (gathered from the same contacts), warm-started
    /// from `warm` (last step's per-sub-step impulse at the same feature and point), and
    /// their manifolds (`patch`: consecutive rows against the same B with one normal), whose
    /// friction starts from the rows' impulses' tangent parts; each contact's denominator
    /// set to k.
    #[inline(always)]
    pub fn build(
        &mut self,
        contacts: &mut [Contact],
        bodies: &Bodies,
        warm: &WarmCache,
        friction: f64,
        (dynamic, fixed): (Softness, Softness),
    ) {
        let Rows {
            rows,
            totals,
            runs,
            patches,
            patch_totals,
            warm: found,
            spans,
        } = self;
        rows.clear();
        totals.clear();
        runs.clear();
        patches.clear();
        patch_totals.clear();
        found.clear();
        spans.clear();
        for c in contacts.iter_mut() {
            let a = bodies.slot[c.body];
            let b = bodies.moving(c.other);
            let (ia, ma) = (&bodies.inv_inertia[a], bodies.motions[a].inv_mass);
            let (rn_a, wn_a, mut k) = end(ma, ia, &c.lever, c.normal);
            let zero = Vector3::zeros();
            let (mut rn_b, mut w_b) = (zero, zero);
            if let Some(b) = b {
                let (ib, mb) = (&bodies.inv_inertia[b], bodies.motions[b].inv_mass);
                let (rn, wn, kn) = end(mb, ib, &c.lever_other, -c.normal);
                k += kn;
                (rn_b, w_b) = (rn, wn);
            }
            let w = warm.find(c).unwrap_or_else(Vector3::zeros);
            found.push(w);
            rows.push(Row {
                normal: c.normal,
                lever: c.lever,
                lever_other: c.lever_other,
                rn: [rn_a, rn_b],
                w_a: wn_a,
                w_b,
                inv_k: if k > 0.0 { 1.0 / k } else { 0.0 },
                reach: 0.0,
                separation: -c.depth,
                gap: 0.0,
                lambda: w.dot(&c.normal).max(0.0),
                max_lambda: 0.0,
            });
            totals.push(Totals::default());
            c.denominator = k;
            let i = rows.len() - 1;
            let new_run = !matches!(runs.last(), Some(run) if run.a == a && run.b == b);
            if new_run {
                runs.push(Run {
                    a,
                    b,
                    rows: i..i + 1,
                    patches: spans.len()..spans.len(),
                    soft: if b.is_none() { fixed } else { dynamic },
                });
            }
            let run = runs.last_mut().expect("a run");
            run.rows.end = i + 1;
            // The row joins the last manifold when it has the same B and normal.
            let last = spans.last_mut().filter(|(span, other)| {
                !new_run && *other == c.other && same_normal(&rows[span.start].normal, &c.normal)
            });
            match last {
                Some((span, _)) => span.end = i + 1,
                None => spans.push((i..i + 1, c.other)),
            }
            run.patches.end = spans.len();
        }
        for run in runs.iter() {
            for (span, _) in &spans[run.patches.clone()] {
                let (patch, t) = Patch::build(run, span.clone(), rows, found, bodies, friction);
                patches.push(patch);
                patch_totals.push(t);
            }
        }
    }

    /// Each row's approach, measured at the free flight's velocities (what the contact meets),
    /// and its separation at the start poses.
    #[inline(always)]
    pub fn measure(&mut self, contacts: &[Contact], bodies: &Bodies) {
        for (t, c) in self.totals.iter_mut().zip(contacts.iter()) {
            let (v, omega, _) = &bodies.flight[bodies.slot[c.body]];
            let mut u = v + omega.cross(&c.lever);
            if let Some(b) = bodies.moving(c.other) {
                let (v, omega, _) = &bodies.flight[b];
                u -= v + omega.cross(&c.lever_other);
            }
            t.approach = u.dot(&c.normal);
        }
        self.refresh_gaps(bodies);
    }

    /// Every row's separation at the bodies' current poses (`refresh_run`, run by run).
    #[inline(always)]
    pub fn refresh_gaps(&mut self, bodies: &Bodies) {
        for run in &self.runs {
            refresh_run(run, &mut self.rows, &bodies.places);
        }
    }

    /// Adds each row's and each manifold's impulses of the sub-step to their totals Λ.
    #[inline(always)]
    pub fn add_totals(&mut self) {
        for (row, t) in self.rows.iter().zip(self.totals.iter_mut()) {
            t.applied += row.lambda;
        }
        for (p, t) in self.patches.iter().zip(self.patch_totals.iter_mut()) {
            for (total, lambda) in t.applied.iter_mut().zip(&p.lambda) {
                *total += lambda;
            }
        }
    }

    /// Each row's and manifold's share of its bodies' angular momentum, `(r×n) Λ` and
    /// `Σ_axes (r×d) Λ` (`patch`), added to `l`: a run's two bodies (never the same) held in
    /// hand over its rows, then over its manifolds.
    #[inline(always)]
    pub fn add_angular_momentum(&self, l: &mut [Vector3<f64>]) {
        for run in &self.runs {
            let range = run.rows.clone();
            let rows = self.rows[range.clone()].iter().zip(&self.totals[range]);
            let patches = &self.patch_totals[run.patches.clone()];
            let mut la = l[run.a];
            match run.b {
                Some(b) => {
                    let mut lb = l[b];
                    for (row, t) in rows {
                        la += row.rn[0] * t.applied;
                        lb += row.rn[1] * t.applied;
                    }
                    for t in patches {
                        for i in 0..3 {
                            la += t.rd[0][i] * t.applied[i];
                            lb += t.rd[1][i] * t.applied[i];
                        }
                    }
                    l[b] = lb;
                }
                None => {
                    for (row, t) in rows {
                        la += row.rn[0] * t.applied;
                    }
                    for t in patches {
                        for i in 0..3 {
                            la += t.rd[0][i] * t.applied[i];
                        }
                    }
                }
            }
            l[run.a] = la;
        }
    }
}

/// The separation of each of `run`'s rows at its bodies' current poses (`places`),
/// `s = s₀ + n·[(Δx_A + (D_A − 𝟙) r_A) − (Δx_B + (D_B − 𝟙) r_B)]`.
#[inline(always)]
pub(super) fn refresh_run(run: &Run, rows: &mut [Row], places: &[Placement]) {
    let a = &places[run.a];
    let rows = &mut rows[run.rows.clone()];
    match run.b {
        Some(b) => {
            let b = &places[b];
            for row in rows {
                let mut d = a.shift + a.turned * row.lever;
                d -= b.shift + b.turned * row.lever_other;
                row.gap = row.separation + row.normal.dot(&d);
            }
        }
        None => {
            for row in rows {
                let d = a.shift + a.turned * row.lever;
                row.gap = row.separation + row.normal.dot(&d);
            }
        }
    }
}
