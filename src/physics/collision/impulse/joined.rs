//! Joint rows inside the contacts' exact solve: a contact impulse on a jointed body and the
//! joint reactions it causes are one solution.
//!
//! A body held by joints (a pendulum's bob, a chain's link) does not answer a contact
//! impulse with its own inverse mass W but with the *constrained* one: the joints push back
//! at once. So the joints' equality rows J_j (bounds (−∞, ∞), `constraints::Row`) join the
//! contact rows J_c of the stages that solve exactly ([`super`]):
//!
//! ```text
//! stage 1 (direct)  find (μ_j, λ_c ≥ 0):  J_j u⁺ = 0,  w_c = J_c u⁺ + b_c ≥ 0,  λ_c w_c = 0,
//!                   u⁺ = u + W (J_jᵀ μ_j + J_cᵀ λ_c)
//!                   — one LDLᵀ of  A = [J_j; J_c] W [J_j; J_c]ᵀ  on the joint rows (always
//!                   active, first in the envelope) and the active contact rows
//! stage 3           Poisson's restitution e λ_c at the bouncing contacts, and the joints'
//!                   reaction to it:  (J_j W J_jᵀ) μ_r = −J_j W J_cᵀ (e λ_c),
//!                   the energy clamp on the sum (K never rises)
//! ```
//!
//! Stage 1 is the minimum of K over the convex set {J_j u⁺ = 0, J_c u⁺ ≥ −b} ∋ 0 (b ≥ 0 the
//! speculative gaps over dt): K never rises. Stage 3's change lies in J_j's null space, so the
//! joints stay held, and its scale is the contacts' clamp on K. At e = 1 without friction the
//! reflection argument of [`super::propagate`] holds with the joint rows among the active
//! ones: J_j u = 0 before and after stage 1 gives J_j W Jᵀ Λ* = 0, so the doubled impulse
//! keeps both K and the joints (a cradle ball on its rod bounces exactly as a free one).
//!
//! Which joint rows: those of every *cluster* (bodies linked through joint rows) that one of
//! the stage's contact rows touches; an impact round of `propagate` on one pair takes the
//! rows of that pair's clusters only (a cradle's round: one contact and two rods).
//!
//! Where: in an *impact* (a row approaching faster than the bounce speed: every impact round
//! of `propagate`, a simultaneous solve that bounces) without friction (μ = 0: a cradle, a
//! bob striking a wall). Elsewhere every stage is the contacts' alone, as before, and the
//! joints' contact pass after the response (`joints::contact::hold`) holds the joints again,
//! as it always did (it also holds, in every case, the positions the push-out moved along
//! straight lines):
//!
//! - with μ > 0 the friction stage (stage 2) acts as if the links were free (its sticking
//!   solve, sweeps and subspace steps know no joint rows); a stage 1 with the joints followed
//!   by a stage 2 without them is neither one solution nor cheaper (the landing chain,
//!   measured: 2.2× the instructions);
//! - at rest (nothing bounces) the contacts' solve alone and the pass after it keep a
//!   touching cradle's balls exactly touching while they swing together; with the joints in
//!   the resting solve the speculative gaps between them grew to about 1 µm, and Poisson's
//!   restitution across such a gap at impact loses 2 λ·gap/dt (6.6e-4 of K with three balls
//!   pulled, against 1e-6 kept);
//! - the sweeps a declined direct solve falls back to.

use crate::physics::constraints::{Axis, End, Row as ConstraintRow, SolverBody};
use crate::physics::envelope::{Envelope, Pivots};
use nalgebra::Vector3;

/// The joint rows of one response, weighed over the step's motions, and what they gave.
#[derive(Debug, Clone, Default)]
pub struct Joined {
    /// Every joint row of the scene (its axis weighed: w = I⁻¹ g, k = J W Jᵀ; ends on fixed
    /// bodies dropped), with the joint it belongs to.
    all: Vec<(Axis, usize)>,
    /// Per body: its cluster's root (bodies linked through joint rows), `usize::MAX` for a
    /// body no joint row moves.
    cluster: Vec<usize>,
    /// The clusters the current stage touches.
    pub(super) marked: Vec<bool>,
    /// The rows of the current stage (from `all`), their owners, and their impulses.
    pub(super) axes: Vec<Axis>,
    owners: Vec<usize>,
    pub(super) lambda: Vec<f64>,
    /// Per joint: the impulse its rows gave its body A in this response (linear N·s,
    /// angular N·m·s).
    pub impulses: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Whether a stage of this response took joint rows.
    pub(super) used: bool,
    system: Envelope,
}

impl Joined {
    /// Takes the scene's joint rows (`rows`, unweighed: `Axis::jacobian`) for a response over
    /// `motions`, with `joints` joints; no rows: every stage is the contacts' alone.
    pub fn prepare(&mut self, rows: &[ConstraintRow], motions: &[SolverBody], joints: usize) {
        self.all.clear();
        self.impulses.clear();
        self.impulses
            .resize(joints, (Vector3::zeros(), Vector3::zeros()));
        self.cluster.clear();
        self.axes.clear();
        self.owners.clear();
        self.lambda.clear();
        self.used = false;
        if rows.is_empty() {
            return;
        }
        self.all.extend(
            rows.iter()
                .filter_map(|r| weigh(&r.axis, motions).map(|a| (a, r.owner))),
        );
        // Clusters by union–find over the rows' two ends.
        self.cluster.resize(motions.len(), usize::MAX);
        fn root(cluster: &mut [usize], mut i: usize) -> usize {
            while cluster[i] != i {
                cluster[i] = cluster[cluster[i]];
                i = cluster[i];
            }
            i
        }
        for (axis, _) in &self.all {
            for b in axis.bodies().into_iter().flatten() {
                if self.cluster[b] == usize::MAX {
                    self.cluster[b] = b;
                }
            }
            if let Some(b) = axis.b {
                let (x, y) = (
                    root(&mut self.cluster, axis.a.body),
                    root(&mut self.cluster, b.body),
                );
                self.cluster[x.max(y)] = x.min(y);
            }
        }
        for i in 0..self.cluster.len() {
            if self.cluster[i] != usize::MAX {
                self.cluster[i] = root(&mut self.cluster, i);
            }
        }
    }

    /// Selects the joint rows of every cluster one of `bodies` belongs to (a stage's contact
    /// rows' bodies) into [`Joined::axes`], in the scene's row order.
    pub(super) fn select(&mut self, bodies: impl Iterator<Item = usize>) {
        self.axes.clear();
        self.owners.clear();
        self.lambda.clear();
        if self.all.is_empty() {
            return;
        }
        self.marked.clear();
        self.marked.resize(self.cluster.len(), false);
        let mut any = false;
        for b in bodies {
            if let Some(&c) = self.cluster.get(b).filter(|&&c| c != usize::MAX) {
                self.marked[c] = true;
                any = true;
            }
        }
        if !any {
            return;
        }
        for (axis, owner) in &self.all {
            if self.marked[self.cluster[axis.a.body]] {
                self.axes.push(*axis);
                self.owners.push(*owner);
            }
        }
        self.used |= !self.axes.is_empty();
    }

    /// Books the selected rows' impulses `lambda` (scaled by `scale`) to their joints.
    pub(super) fn book(&mut self, lambda: &[f64], scale: f64) {
        for ((axis, &owner), &mu) in self.axes.iter().zip(&self.owners).zip(lambda) {
            let j = mu * scale;
            let (force, torque) = &mut self.impulses[owner];
            *force += axis.d * j;
            *torque += axis.a.rd * j;
        }
    }

    /// The joints' reaction to a change of the bodies' motions (`change`: Δv, ΔL, Δω per
    /// body, the restitution impulses'): μ with `(J_j W J_jᵀ) μ = −J_j Δu`, added to
    /// `change` (`W J_jᵀ μ`), so that the change keeps J_j u. Leaves μ in
    /// [`Joined::lambda`].
    pub(super) fn react(
        &mut self,
        change: &mut [(Vector3<f64>, Vector3<f64>, Vector3<f64>)],
        motions: &[SolverBody],
    ) {
        self.lambda.clear();
        let m = self.axes.len();
        if m == 0 {
            return;
        }
        let rate = |axis: &Axis, change: &[(Vector3<f64>, Vector3<f64>, Vector3<f64>)]| {
            let (dv, _, dw) = &change[axis.a.body];
            let mut u = axis.d.dot(dv) + axis.a.rd.dot(dw);
            if let Some(b) = &axis.b {
                let (dv, _, dw) = &change[b.body];
                u += -axis.d.dot(dv) + b.rd.dot(dw);
            }
            u
        };
        self.system.reset(m);
        for p in 0..m {
            let jp = &self.axes[p];
            self.system.rhs[p] = -rate(jp, change);
            let axes = &self.axes;
            self.system.fill_row(p, jp.bodies(), |q| {
                jp.shares_a_body(&axes[q])
                    .then(|| jp.coupling(&axes[q], motions))
            });
        }
        let Some(mu) = self.system.solve(Pivots::Dropped) else {
            return;
        };
        self.lambda.extend_from_slice(&mu[..m]);
        for (axis, &mu) in self.axes.iter().zip(&self.lambda) {
            for (end, sign) in axis.ends() {
                let c = &mut change[end.body];
                c.0 += axis.d * (sign * mu * motions[end.body].inv_mass);
                c.1 += end.rd * mu;
                c.2 += end.w * mu;
            }
        }
    }
}

/// A joint row's axis over `motions`: its ends on fixed bodies dropped (a row whose A is
/// fixed is taken from its B's side), each end's `w = I⁻¹ g` and the row's
/// `k = Σ |d|²/M + g·I⁻¹ g` filled in; None when no end moves.
fn weigh(axis: &Axis, motions: &[SolverBody]) -> Option<Axis> {
    let moving = |e: &End| !motions[e.body].fixed();
    let (d, a, b) = match (moving(&axis.a), axis.b.filter(moving)) {
        (true, b) => (axis.d, axis.a, b),
        // A fixed: the row is −d on B with B's angular part (J's B block alone).
        (false, Some(b)) => (-axis.d, b, None),
        (false, None) => return None,
    };
    let weighed = |e: &End| {
        let s = &motions[e.body];
        let w = s.inv_inertia * e.rd;
        (
            End { w, ..*e },
            s.inv_mass * d.norm_squared() + e.rd.dot(&w),
        )
    };
    let (a, mut k) = weighed(&a);
    let b = b.map(|e| {
        let (end, kb) = weighed(&e);
        k += kb;
        end
    });
    Some(Axis {
        d,
        a,
        b,
        k,
        inv_k: f64::NAN,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// A 1 kg ball (I = 0.001 kg·m²) at rest.
    fn ball() -> SolverBody {
        SolverBody::new(
            Vector3::zeros(),
            Vector3::zeros(),
            1.0,
            Matrix3::identity() * 1000.0,
        )
    }

    #[test]
    fn clusters_take_the_rows_of_the_touched_bodies_only() {
        // Bodies 0–1 joined, 2 alone on a rod to the world, 3 free.
        let motions = vec![ball(), ball(), ball(), ball()];
        let row = |a: usize, b: Option<usize>, owner: usize| {
            let axis = Axis::jacobian(
                Vector3::x(),
                (a, Vector3::zeros()),
                b.map(|b| (b, Vector3::zeros())),
            );
            ConstraintRow::equality(axis, 0.0, 0.0, owner)
        };
        let rows = [row(0, Some(1), 0), row(2, None, 1)];
        let mut joined = Joined::default();
        joined.prepare(&rows, &motions, 2);
        joined.select([1].into_iter());
        assert_eq!(joined.axes.len(), 1);
        assert_eq!(joined.axes[0].a.body, 0);
        joined.select([3].into_iter());
        assert!(joined.axes.is_empty());
        joined.select([3, 2].into_iter());
        assert_eq!(joined.axes.len(), 1);
        assert_eq!(joined.axes[0].a.body, 2);
        // Weighed: k = 1/m + 1/m for the pair, 1/m for the rod.
        joined.select([0, 2].into_iter());
        assert_eq!(
            joined.axes.iter().map(|a| a.k).collect::<Vec<_>>(),
            [2.0, 1.0]
        );
    }

    #[test]
    fn the_reaction_keeps_the_joint_rate() {
        // Two balls joined along x; the first kicked along x by 1 m/s: the joint shares it.
        let motions = vec![ball(), ball()];
        let rows = [ConstraintRow::equality(
            Axis::jacobian(
                Vector3::x(),
                (0, Vector3::zeros()),
                Some((1, Vector3::zeros())),
            ),
            0.0,
            0.0,
            0,
        )];
        let mut joined = Joined::default();
        joined.prepare(&rows, &motions, 1);
        joined.select([0].into_iter());
        let mut change = vec![
            (Vector3::x(), Vector3::zeros(), Vector3::zeros()),
            (Vector3::zeros(), Vector3::zeros(), Vector3::zeros()),
        ];
        joined.react(&mut change, &motions);
        assert!((change[0].0.x - 0.5).abs() < 1e-15);
        assert!((change[1].0.x - 0.5).abs() < 1e-15);
        assert!((joined.lambda[0] + 0.5).abs() < 1e-15);
    }
}
