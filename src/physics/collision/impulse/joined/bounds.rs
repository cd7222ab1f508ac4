//! Stops and motors keep their bounds in stages 2 and 3 of the contacts' solve with joint
//! rows ([`super`]): the same active set as stage 1 (`Joined::inelastic`), around the joints'
//! friction sweeps and around stage 3's reaction.
//!
//! Stage 1 leaves each stop and motor *active* (an unknown: a stop that pushes, a motor
//! inside its bounds) or *held* (a stop that does not push, a motor at a bound, its impulse
//! known). Stages 2 and 3 keep every active row's rate (their changes lie in the null space
//! of the active rows' J), which a row with bounds may not afford: a motor holding a body
//! still against a sliding contact's friction would give μ λₙ whatever its bound, and a stop
//! could pull. So each stage solves, checks and solves again:
//!
//! ```text
//! stop    p + λ ≥ 0            p its impulse earlier in the stage (stage 1's)
//! motor   lo ≤ m + λ ≤ hi      m its impulse earlier in the response (the drive pass's
//!                              share is in lo, hi already: joints::drive)
//! ```
//!
//! an active row whose impulse λ in the stage passes a bound is held there (its impulse
//! applied before the solve, through its column: the other rows' reaction in it), a held row
//! whose rate the answer leaves on the wrong side of its aim (a stop's J u < 0, a motor's
//! J u below its speed at lo, above it at hi) is freed; the largest change first, each change
//! solved again from the stage's start, at most 2 r + 3 rounds for r stops and motors. A
//! stage whose rows all keep their bounds is solved once, as before: nothing changes where
//! no bound is reached.
//!
//! Stage 3's restitution impulses e λ_c are fixed, its joints' reaction the only unknowns:
//! the rounds solve `(J_a W J_aᵀ) μ = −J_a (Δu_c + W J_hᵀ λ_h)` over the active rows a, the
//! held rows h at their bounds, and its energy clamp scales the whole change (each bound's
//! interval holds 0, so a scaled impulse stays inside it).

use super::{Change, Held, Joined, Kind, Row};
use crate::physics::constraints::{Axis, SolverBody};

impl Joined {
    /// Whether stage 1 took stops or motors and answered (stages 2 and 3 then keep their
    /// bounds).
    pub(in crate::physics::collision::impulse) fn bounded(&self) -> bool {
        !self.bounded.is_empty()
    }

    /// The held states stages 2 and 3 start from: stage 1's, a stop left out being one held
    /// at its bound (its impulse in the stage, 0, kept).
    fn later_start(&self) -> Vec<Held> {
        (self.bounded.iter())
            .map(|&(h, _)| if h == Held::Out { Held::Low } else { h })
            .collect()
    }

    /// Adds a stage's answer to [`Joined::bounded`]: each row's state, and to its impulse
    /// the active rows' `lambda` (in selection order) and the held rows' known impulses,
    /// times `scale`.
    fn add_to_bounded(&mut self, held: &[Held], lambda: &[f64], scale: f64) {
        let mut free = lambda.iter();
        for (slot, &h) in self.bounded.iter_mut().zip(held) {
            slot.0 = h;
            if h == Held::Active {
                slot.1 += free.next().copied().unwrap_or(0.0) * scale;
            }
        }
        for &(i, j) in &self.known {
            self.bounded[i].1 += j * scale;
        }
    }

    /// Books the held rows' impulses of the last round ([`Joined::known`]) times `scale`.
    fn book_known(&mut self, scale: f64) {
        let known = std::mem::take(&mut self.known);
        for &(i, j) in &known {
            let (axis, owner, kind) = self.selection[i];
            self.book_row(&axis, owner, kind, j * scale);
        }
        self.known = known;
    }

    /// The direct sticking solve's answer (`delta`, per active row) added to
    /// [`Joined::bounded`] (stage 3's stops then count it).
    pub(super) fn sticking_answered(&mut self, delta: &[f64]) {
        if self.bounded.is_empty() {
            return;
        }
        let held: Vec<Held> = self.bounded.iter().map(|b| b.0).collect();
        self.known.clear();
        self.add_to_bounded(&held, delta, 1.0);
    }

    /// [`Joined::friction`] with stops or motors among the rows: the sweeps inside the active
    /// set of the module doc. The answer's impulses are booked; None (nothing changed, the
    /// rows those of stage 1) when S gives no factor or the active set does not settle.
    pub(super) fn friction_bounded(
        &mut self,
        rows: &mut [Row],
        directions: &[[Axis; 2]],
        motions: &mut [SolverBody],
        tolerance: f64,
        cap: u64,
    ) -> Option<(bool, u64, f64, u64)> {
        let selection = self.selection.clone();
        let saved: Vec<SolverBody> = motions.to_vec();
        let saved_rows: Vec<(f64, [f64; 2])> =
            rows.iter().map(|r| (r.normal.lambda, r.friction.lambda)).collect();
        let restore = |rows: &mut [Row], motions: &mut [SolverBody]| {
            motions.copy_from_slice(&saved);
            for (row, &(n, t)) in rows.iter_mut().zip(&saved_rows) {
                row.normal.lambda = n;
                row.friction.lambda = t;
            }
        };
        let start = self.later_start();
        let mut held = start.clone();
        let changing = selection.iter().filter(|s| s.2 != Kind::Equality).count();
        let (mut sweeps, mut work) = (0, 0);
        let mut answer = None;
        for _ in 0..2 * changing + 3 {
            self.take_active(&selection, &held);
            let left = cap.saturating_sub(sweeps);
            let Some((converged, s, residual, w)) =
                self.friction_round(rows, directions, motions, tolerance, left)
            else {
                break;
            };
            sweeps += s;
            work += w;
            let rate = |a: &Axis| a.velocity(motions);
            match self.next_change(&selection, &held, &self.rhs, rate, tolerance) {
                Some((i, to)) => {
                    held[i] = to;
                    restore(rows, motions);
                }
                None => {
                    answer = Some((converged, sweeps, residual, work));
                    break;
                }
            }
        }
        if answer.is_some() {
            let lambda = std::mem::take(&mut self.rhs);
            self.book(&lambda, 1.0);
            self.book_known(1.0);
            self.add_to_bounded(&held, &lambda, 1.0);
            self.rhs = lambda;
        } else {
            restore(rows, motions);
            let stage_one: Vec<Held> = self.bounded.iter().map(|b| b.0).collect();
            self.take_active(&selection, &stage_one);
        }
        self.known.clear();
        answer
    }

    /// Stage 3's joints' reaction to the restitution impulses' `change` (Δv, ΔL, Δω per
    /// body), added to it: with stops or motors among the rows, the active set of the module
    /// doc around [`Joined::react`] (the held rows' impulses added to `change` first, and left
    /// in [`Joined::known`] for [`Joined::book_bounce`]); else `react` alone.
    pub(in crate::physics::collision::impulse) fn react_bounded(
        &mut self,
        change: &mut [Change],
        motions: &[SolverBody],
    ) {
        self.known.clear();
        if self.bounded.is_empty() {
            return self.react(change, motions);
        }
        let selection = self.selection.clone();
        let base: Vec<Change> = change.to_vec();
        let mut held = self.later_start();
        let changing = selection.iter().filter(|s| s.2 != Kind::Equality).count();
        let mut settled = false;
        for _ in 0..2 * changing + 3 {
            change.copy_from_slice(&base);
            self.take_active(&selection, &held);
            for &(i, j) in &self.known {
                add_impulse(&selection[i].0, j, change, motions);
            }
            self.react(change, motions);
            if self.lambda.len() != self.axes.len() {
                break; // no factor
            }
            let rate = |a: &Axis| a.velocity(motions) + rate_of(a, change);
            match self.next_change(&selection, &held, &self.lambda, rate, self.tolerance) {
                Some((i, to)) => held[i] = to,
                None => {
                    settled = true;
                    break;
                }
            }
        }
        if !settled {
            // As before: stage 1's active rows held as equality rows.
            change.copy_from_slice(&base);
            let stage_one: Vec<Held> = self.bounded.iter().map(|b| b.0).collect();
            self.take_active(&selection, &stage_one);
            self.known.clear();
            self.react(change, motions);
        }
    }

    /// Books stage 3's joint impulses times the energy clamp's `scale`: the active rows'
    /// reaction ([`Joined::lambda`]) and the held rows' impulses ([`Joined::known`]).
    pub(in crate::physics::collision::impulse) fn book_bounce(&mut self, scale: f64) {
        self.book_stage(scale);
        if !self.known.is_empty() {
            self.book_known(scale);
            self.known.clear();
        }
    }
}

/// Adds `W Jᵀ j` of a weighed axis to per-body changes.
fn add_impulse(axis: &Axis, j: f64, change: &mut [Change], motions: &[SolverBody]) {
    for (end, sign) in axis.ends() {
        let c = &mut change[end.body];
        c.0 += axis.d * (sign * j * motions[end.body].inv_mass);
        c.1 += end.rd * j;
        c.2 += end.w * j;
    }
}

/// J Δu of an axis over per-body changes.
fn rate_of(axis: &Axis, change: &[Change]) -> f64 {
    let mut u = 0.0;
    for (end, sign) in axis.ends() {
        let (dv, _, dw) = &change[end.body];
        u += sign * axis.d.dot(dv) + end.rd.dot(dw);
    }
    u
}
