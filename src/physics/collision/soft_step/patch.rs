//! `soft-step`'s friction, one block per manifold (Rapier's and Bepu's "twist friction"): the
//! rows of one pair that share a normal n (a face on a face: up to four points) hold
//! together, at the manifold's centre, instead of each point with two tangent rows of its own.
//!
//! # The rows
//!
//! With the points' levers r_A,i (r_B,i) and their mean, the centre `c_A` (`c_B`), each
//! point's offset across the normal `d_i = (r_A,i − c_A) − n (n·(r_A,i − c_A))` and its reach
//! `ρ_i = |d_i|`, a manifold has three friction rows:
//!
//! ```text
//! tangents t₁, t₂ at the centre:  u_t = t·(v_A + ω_A×c_A − v_B − ω_B×c_B)
//!                                 k_t = 1/M_A + (c_A×t)·I_A⁻¹(c_A×t) + (B's, with −t)
//! twist about n:                  u_τ = n·(ω_A − ω_B),   k_τ = n·I_A⁻¹n + n·I_B⁻¹n
//! bounds, with the rows' current normal impulses λ_i:
//!   |λ_t| ≤ μ Σ λ_i               (the tangent pair in a disk)
//!   |λ_τ| ≤ μ Σ λ_i ρ_i           (the most torque the points' own Coulomb cones give)
//! ```
//!
//! each taken as a rigid row (`Δλ = −u/k`, then clamped), tangents first, after the run's
//! normal rows, in the solve and in the relax alike. A single point has ρ = 0 and no twist:
//! a sphere keeps its one tangent pair at its point. Per 4-point manifold a sweep updates 4
//! normal rows and 3 friction rows, where friction per point took 4 + 8.
//!
//! # What the points see
//!
//! The contacts and the warm start keep an impulse per point: the manifold's tangent impulse
//! split evenly and its twist as point forces about the centre,
//!
//! ```text
//! j_i = n λ_i + (t₁ λ₁ + t₂ λ₂)/N + λ_τ (n×d_i)/Σ_k ρ_k²
//! ```
//!
//! which sum to the manifold's force (Σ d_i = 0) and give its torque about n
//! (`Σ d_i×(n×d_i)·n = Σ ρ_i²`); read back (`λ_t = Σ t·j_i`, `λ_τ = Σ n·(d_i×j_i)`) they give
//! the same impulses when the same points are found again.

use super::bodies::{Bodies, Motion};
use super::clamp_disk;
use super::rows::{end, Row, Run};
use crate::physics::collision::impulse::tangents;
use nalgebra::Vector3;
use std::ops::Range;

/// One manifold's friction as the sweeps see it.
#[derive(Debug, Clone)]
pub(super) struct Patch {
    /// The manifold's rows.
    pub rows: Range<usize>,
    pub normal: Vector3<f64>,
    pub tangents: [Vector3<f64>; 2],
    /// The centre's levers c_A and c_B.
    pub lever: Vector3<f64>,
    pub lever_other: Vector3<f64>,
    /// `I_A⁻¹(c_A×t₁)`, `I_A⁻¹(c_A×t₂)`, `I_A⁻¹ n`, and B's `I_B⁻¹(c_B×(−t₁))`, …, `I_B⁻¹(−n)`.
    pub w_a: [Vector3<f64>; 3],
    pub w_b: [Vector3<f64>; 3],
    /// 1/k along t₁, t₂ and the twist (0 when k is).
    pub inv_k: [f64; 3],
    /// The sub-step's impulses along t₁, t₂ (N·s) and about n (N·m·s), on A.
    pub lambda: [f64; 3],
}

/// What the sweeps do not read of a manifold's friction.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct PatchTotals {
    /// Per end, the angular axes `c_A×t₁`, `c_A×t₂`, `n` and `c_B×(−t₁)`, `c_B×(−t₂)`, `−n`.
    pub rd: [[Vector3<f64>; 3]; 2],
    /// Every impulse applied over the step along t₁, t₂ and about n, Λ.
    pub applied: [f64; 3],
}

/// Point i's offset from the centre across the normal, `d_i` (module doc).
#[inline(always)]
fn offset(lever: &Vector3<f64>, centre: &Vector3<f64>, n: &Vector3<f64>) -> Vector3<f64> {
    let d = lever - centre;
    d - n * n.dot(&d)
}

/// The manifold's bounds from its rows' current normal impulses: `(Σ λ_i, Σ λ_i ρ_i)`.
#[inline(always)]
fn load(rows: &[Row]) -> (f64, f64) {
    let (mut force, mut torque) = (0.0, 0.0);
    for row in rows {
        force += row.lambda;
        torque += row.lambda * row.reach;
    }
    (force, torque)
}

impl Patch {
    /// The friction of `run`'s manifold of rows `span` (setting their reach), warm-started
    /// from the impulses last step left at its points (`found`, per row) and kept within its
    /// bounds (μ `friction`).
    #[inline(always)]
    pub fn build(
        run: &Run,
        span: Range<usize>,
        rows: &mut [Row],
        found: &[Vector3<f64>],
        bodies: &Bodies,
        friction: f64,
    ) -> (Patch, PatchTotals) {
        let n = rows[span.start].normal;
        let (t1, t2) = tangents(&n);
        let count = span.len() as f64;
        let mut lever = Vector3::zeros();
        let mut lever_other = Vector3::zeros();
        for row in &rows[span.clone()] {
            lever += row.lever;
            lever_other += row.lever_other;
        }
        lever /= count;
        lever_other /= count;
        // Warm start: λ_t = Σ t·j_i, λ_τ = Σ n·(d_i×j_i).
        let mut lambda = [0.0; 3];
        for (row, j) in rows[span.clone()].iter_mut().zip(&found[span.clone()]) {
            let d = offset(&row.lever, &lever, &n);
            row.reach = d.norm();
            lambda[0] += t1.dot(j);
            lambda[1] += t2.dot(j);
            lambda[2] += n.dot(&d.cross(j));
        }
        let (force, torque) = load(&rows[span.clone()]);
        let mut tangent = [lambda[0], lambda[1]];
        clamp_disk(&mut tangent, friction * force);
        let twist = friction * torque;
        lambda = [tangent[0], tangent[1], lambda[2].clamp(-twist, twist)];
        let (ia, ma) = (&bodies.inv_inertia[run.a], bodies.motions[run.a].inv_mass);
        let (r1_a, w1_a, mut k1) = end(ma, ia, &lever, t1);
        let (r2_a, w2_a, mut k2) = end(ma, ia, &lever, t2);
        let wt_a = ia * n;
        let mut kt = n.dot(&wt_a);
        let zero = Vector3::zeros();
        let (mut w_b, mut rd_b) = ([zero; 3], [zero; 3]);
        if let Some(b) = run.b {
            let (ib, mb) = (&bodies.inv_inertia[b], bodies.motions[b].inv_mass);
            let (r1, w1, c1) = end(mb, ib, &lever_other, -t1);
            let (r2, w2, c2) = end(mb, ib, &lever_other, -t2);
            let wt = ib * (-n);
            k1 += c1;
            k2 += c2;
            kt += n.dot(&(ib * n));
            (w_b, rd_b) = ([w1, w2, wt], [r1, r2, -n]);
        }
        let inv = |k: f64| if k > 0.0 { 1.0 / k } else { 0.0 };
        let patch = Patch {
            rows: span,
            normal: n,
            tangents: [t1, t2],
            lever,
            lever_other,
            w_a: [w1_a, w2_a, wt_a],
            w_b,
            inv_k: [inv(k1), inv(k2), inv(kt)],
            lambda,
        };
        let totals = PatchTotals {
            rd: [[r1_a, r2_a, n], rd_b],
            applied: [0.0; 3],
        };
        (patch, totals)
    }

    /// Applies the impulses `j` (along t₁, t₂, about n) to the two motions (`pair`: B is
    /// there and takes the opposite).
    #[inline(always)]
    pub fn push(&self, j: [f64; 3], a: &mut Motion, b: &mut Motion, pair: bool) {
        let [t1, t2] = &self.tangents;
        let p = t1 * j[0] + t2 * j[1];
        a.v += p * a.inv_mass;
        a.omega += self.w_a[0] * j[0] + self.w_a[1] * j[1] + self.w_a[2] * j[2];
        if pair {
            b.v -= p * b.inv_mass;
            b.omega += self.w_b[0] * j[0] + self.w_b[1] * j[1] + self.w_b[2] * j[2];
        }
    }

    /// One sweep's friction update of the manifold (module doc), after its rows' normal
    /// updates (`rows`: the step's rows), μ `friction`.
    #[inline(always)]
    pub fn solve<const PAIR: bool>(
        &mut self,
        rows: &[Row],
        a: &mut Motion,
        b: &mut Motion,
        friction: f64,
    ) {
        let (force, torque) = load(&rows[self.rows.clone()]);
        let [t1, t2] = &self.tangents;
        let old = [self.lambda[0], self.lambda[1]];
        let mut slip = a.v + a.omega.cross(&self.lever);
        if PAIR {
            slip = slip - b.v - b.omega.cross(&self.lever_other);
        }
        let mut new = [
            old[0] - self.inv_k[0] * t1.dot(&slip),
            old[1] - self.inv_k[1] * t2.dot(&slip),
        ];
        clamp_disk(&mut new, friction * force);
        let step = [new[0] - old[0], new[1] - old[1]];
        if step != [0.0; 2] {
            self.push([step[0], step[1], 0.0], a, b, PAIR);
            self.lambda[0] = new[0];
            self.lambda[1] = new[1];
        }
        let bound = friction * torque;
        let mut spin = self.normal.dot(&a.omega);
        if PAIR {
            spin -= self.normal.dot(&b.omega);
        }
        let old = self.lambda[2];
        let new = (old - self.inv_k[2] * spin).clamp(-bound, bound);
        if new != old {
            let step = new - old;
            a.omega += self.w_a[2] * step;
            if PAIR {
                b.omega += self.w_b[2] * step;
            }
            self.lambda[2] = new;
        }
    }

    /// The share of the manifold's friction impulses `j` (along t₁, t₂, about n) at its
    /// point with lever `r_A` (module doc, "What the points see").
    #[inline(always)]
    pub fn share(&self, rows: &[Row], lever: &Vector3<f64>, j: [f64; 3]) -> Vector3<f64> {
        let rows = &rows[self.rows.clone()];
        let [t1, t2] = &self.tangents;
        let mut share = (t1 * j[0] + t2 * j[1]) / rows.len() as f64;
        let spread: f64 = rows.iter().map(|r| r.reach * r.reach).sum();
        if spread > 0.0 && j[2] != 0.0 {
            let d = offset(lever, &self.lever, &self.normal);
            share += self.normal.cross(&d) * (j[2] / spread);
        }
        share
    }
}
