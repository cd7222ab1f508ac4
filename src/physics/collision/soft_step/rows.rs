//! `soft-step`'s rows, prepared once per step into what the sweeps read and nothing more
//! (Box2D v3's contact constraints): per contact the normal n and tangents t₁, t₂, the levers
//! r_A, r_B, each end's `r×d` for the normal and `I₀⁻¹(r×d)` for the three axes, and the three
//! effective masses `1/k`,
//!
//! ```text
//! k = 1/M_A + (r_A×d)·I_A⁻¹(r_A×d) + 1/M_B + (r_B×(−d))·I_B⁻¹(r_B×(−d))
//! ```
//!
//! with I₀⁻¹ the start pose's world inverse inertia, fixed over the step: no matrix work is
//! left for the sweeps. Consecutive rows between the same two bodies form a [`Run`]: a sweep
//! copies the two bodies' motions in once, and a run against an obstacle or a fixed body (no
//! B end) takes a path that reads no B. What the sweeps do not read (the approach, the totals
//! Λ) is kept beside, in [`Totals`].

use super::bodies::{Bodies, Placement};
use super::{clamp_disk, Softness};
use crate::physics::collision::impulse::tangents;
use crate::physics::collision::warm::WarmCache;
use crate::physics::collision::Contact;
use nalgebra::{Matrix3, Vector3};
use std::ops::Range;

/// One contact as the sweeps see it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Row {
    pub normal: Vector3<f64>,
    pub tangents: [Vector3<f64>; 2],
    pub lever: Vector3<f64>,
    pub lever_other: Vector3<f64>,
    /// `r_A×n` and `r_B×(−n)`.
    pub rn: [Vector3<f64>; 2],
    /// `I_A⁻¹(r_A×d)` for d = n, t₁, t₂ (A's end), and `I_B⁻¹(r_B×(−d))` (B's; zero without B).
    pub w_a: [Vector3<f64>; 3],
    pub w_b: [Vector3<f64>; 3],
    /// 1/k along n, t₁, t₂ (0 when k is).
    pub inv_k: [f64; 3],
    /// Separation at the detection pose, m.
    pub separation: f64,
    /// Separation at the bodies' current poses, m: refreshed once per sub-step.
    pub gap: f64,
    pub lambda: f64,
    pub lambda_tangent: [f64; 2],
    pub max_lambda: f64,
}

/// What the sweeps do not read: the approach and the step's totals.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Totals {
    /// Normal velocity before the response, m/s.
    pub approach: f64,
    /// `r_A×t` and `r_B×(−t)` for the two tangents (the normal's are the row's `rn`).
    pub rt: [[Vector3<f64>; 2]; 2],
    /// Every impulse applied over the step along the normal and the two tangents (N·s, on
    /// A): the row's impulse is `n Λ₀ + t₁ Λ₁ + t₂ Λ₂`, and its share of each body's angular
    /// momentum `(r×d) Λ` summed over the three axes.
    pub applied: [f64; 3],
}

/// Consecutive rows between the same two bodies (B: None for an obstacle or a fixed body),
/// with their softness.
#[derive(Debug, Clone)]
pub(super) struct Run {
    pub a: usize,
    pub b: Option<usize>,
    pub rows: Range<usize>,
    pub soft: Softness,
}

/// The step's rows, their totals and runs.
#[derive(Debug, Clone, Default)]
pub(super) struct Rows {
    pub rows: Vec<Row>,
    pub totals: Vec<Totals>,
    pub runs: Vec<Run>,
}

/// One end of an axis d at lever r on a body of 1/M `inv_mass` and world I⁻¹ `inv_inertia`:
/// `r×d`, `I⁻¹(r×d)` and its share of k, `1/M + (r×d)·I⁻¹(r×d)`.
#[inline(always)]
fn end(
    inv_mass: f64,
    inv_inertia: &Matrix3<f64>,
    lever: &Vector3<f64>,
    d: Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>, f64) {
    let rd = lever.cross(&d);
    let w = inv_inertia * rd;
    (rd, w, inv_mass + rd.dot(&w))
}

impl Rows {
    /// The rows of `contacts` over `bodies` (gathered from the same contacts), warm-started
    /// from `warm` (last step's per-sub-step impulse at the same feature and point, its
    /// tangent part kept in the friction disk `μ λ`); each contact's denominator set to k.
    #[inline(always)]
    pub fn build(
        &mut self,
        contacts: &mut [Contact],
        bodies: &Bodies,
        warm: &WarmCache,
        friction: f64,
        (dynamic, fixed): (Softness, Softness),
    ) {
        let Rows { rows, totals, runs } = self;
        rows.clear();
        totals.clear();
        runs.clear();
        for c in contacts.iter_mut() {
            let a = bodies.slot[c.body];
            let b = bodies.moving(c.other);
            let (t1, t2) = tangents(&c.normal);
            let (ia, ma) = (&bodies.inv_inertia[a], bodies.motions[a].inv_mass);
            let (rn_a, wn_a, kn) = end(ma, ia, &c.lever, c.normal);
            let (r1_a, w1_a, k1) = end(ma, ia, &c.lever, t1);
            let (r2_a, w2_a, k2) = end(ma, ia, &c.lever, t2);
            let mut k = [kn, k1, k2];
            let zero = Vector3::zeros();
            let (mut rn_b, mut w_b, mut rt_b) = (zero, [zero; 3], [zero; 2]);
            if let Some(b) = b {
                let (ib, mb) = (&bodies.inv_inertia[b], bodies.motions[b].inv_mass);
                let (rn, wn, kn) = end(mb, ib, &c.lever_other, -c.normal);
                let (r1, w1, k1) = end(mb, ib, &c.lever_other, -t1);
                let (r2, w2, k2) = end(mb, ib, &c.lever_other, -t2);
                k[0] += kn;
                k[1] += k1;
                k[2] += k2;
                (rn_b, w_b, rt_b) = (rn, [wn, w1, w2], [r1, r2]);
            }
            let w = warm.find(c).unwrap_or_else(Vector3::zeros);
            let lambda = w.dot(&c.normal).max(0.0);
            let mut lambda_tangent = [w.dot(&t1), w.dot(&t2)];
            clamp_disk(&mut lambda_tangent, friction * lambda);
            let inv = |k: f64| if k > 0.0 { 1.0 / k } else { 0.0 };
            rows.push(Row {
                normal: c.normal,
                tangents: [t1, t2],
                lever: c.lever,
                lever_other: c.lever_other,
                rn: [rn_a, rn_b],
                w_a: [wn_a, w1_a, w2_a],
                w_b,
                inv_k: [inv(k[0]), inv(k[1]), inv(k[2])],
                separation: -c.depth,
                gap: 0.0,
                lambda,
                lambda_tangent,
                max_lambda: 0.0,
            });
            totals.push(Totals {
                approach: 0.0,
                rt: [[r1_a, r2_a], rt_b],
                applied: [0.0; 3],
            });
            c.denominator = k[0];
            let i = rows.len() - 1;
            match runs.last_mut() {
                Some(run) if run.a == a && run.b == b => run.rows.end = i + 1,
                _ => runs.push(Run {
                    a,
                    b,
                    rows: i..i + 1,
                    soft: if b.is_none() { fixed } else { dynamic },
                }),
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

    /// Adds each row's impulses of the sub-step to its totals Λ.
    #[inline(always)]
    pub fn add_totals(&mut self) {
        for (row, t) in self.rows.iter().zip(self.totals.iter_mut()) {
            t.applied[0] += row.lambda;
            t.applied[1] += row.lambda_tangent[0];
            t.applied[2] += row.lambda_tangent[1];
        }
    }

    /// Each row's share of its bodies' angular momentum, `Σ_axes (r×d) Λ`, added to `l`: a
    /// run's two bodies (never the same) held in hand over its rows, the terms added in the
    /// rows' and axes' order.
    #[inline(always)]
    pub fn add_angular_momentum(&self, l: &mut [Vector3<f64>]) {
        for run in &self.runs {
            let range = run.rows.clone();
            let rows = self.rows[range.clone()].iter().zip(&self.totals[range]);
            let mut la = l[run.a];
            match run.b {
                Some(b) => {
                    let mut lb = l[b];
                    for (row, t) in rows {
                        let rd_a = [row.rn[0], t.rt[0][0], t.rt[0][1]];
                        let rd_b = [row.rn[1], t.rt[1][0], t.rt[1][1]];
                        for i in 0..3 {
                            la += rd_a[i] * t.applied[i];
                            lb += rd_b[i] * t.applied[i];
                        }
                    }
                    l[b] = lb;
                }
                None => {
                    for (row, t) in rows {
                        let rd_a = [row.rn[0], t.rt[0][0], t.rt[0][1]];
                        for (rd, applied) in rd_a.iter().zip(&t.applied) {
                            la += rd * *applied;
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
