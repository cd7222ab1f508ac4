//! The sweeps' stall stop (switched off: [`STALL_BAND`] = 0): a method over the rows, not a
//! constraint kind. A large friction stage's sweeps (`friction::sweep`) also stop
//! when a sweep's row updates changed the rows' velocities by at most [`STALL_BAND`]
//! tolerances while the whole sweep moved the bodies by less than one tolerance: every row's
//! velocity, from the bodies at the sweep's start to those at its end, changed by at most
//! the tolerance (`net_change`). The row updates then cancel in body space: the impulses move
//! along a flat direction of a redundant contact set (four coplanar corners of a brick on a
//! brick, a brick on two bricks), where F falls only by the set's inconsistency, and creep
//! towards a bound for hundreds of sweeps while no body's velocity changes.
//!
//! Such a stop meets `|Δu| ≤ STALL_BAND · tolerance` at each row update (1e-9 m/s) and the
//! bodies' velocities to the tolerance (1e-10 m/s); every impulse is in its bounds as always
//! (λ ≥ 0, |λ_t| ≤ μ λ: Signorini and cone feasibility hold exactly, K only went down).

use super::SWEEPS_FIRST_ROWS;
use crate::physics::collision::solver_body::{Axis, SolverBody};

/// The stall band, in tolerances (module doc), for stages of [`SWEEPS_FIRST_ROWS`] rows or
/// more; 0: no stall stop. **Off** (measured with 10, `World::set_stall_band`): on the same
/// states it cuts the work of the walls and dominoes by 7 % to 45 % (table below), but it
/// stops at rest too, where a brick may then keep a velocity of the band's order (1e-9 m/s):
/// lesson 41's claim that every brick lies still at 2.8 s (|p| < 1e-9 N·s) failed with it on
/// ("c2b1 still moving"), and its walk snapshot moved. Next: apply it only in steps where
/// something moves (an impact, a slide), or end a stall by moving the impulses along the
/// flat direction to their bound.
///
/// Measured (issue 35, wall-ball 600 steps, this rule off): of the sweeps whose row changes
/// were 1e-10 to 1e-7 m/s, 80 % moved the bodies by less than 1e-10 m/s, most by 1e-12 to
/// 1e-16. Work in row updates (deterministic), off → on, each step taken twice from the same
/// state (`contact_steps` with `CONTACT_STEPS_SHADOW`: the scenes are chaotic, two free runs
/// soon solve different problems), no step dearer in any scene:
///
/// | scene, steps | off | on | steps cheaper | unconverged steps |
/// |---|---|---|---|---|
/// | wall-ball, 600 | 70.1M | 46.2M (−34 %) | 299 | 67 → 42 |
/// | knife-wall, 600 | 60.5M | 40.7M (−33 %) | 93 | 15 → 7 |
/// | knife-wall-ball, 600 | 121.1M | 86.8M (−28 %) | 244 | 49 → 39 |
/// | bonded-wall-ball, 600 | 145.9M | 111.6M (−24 %) | 152 | 104 → 90 |
/// | edge-wall-ball, 600 | 26.9M | 23.2M (−14 %) | 51 | 36 → 35 |
/// | wall, 600 | 34.6M | 19.2M (−45 %) | 89 | 0 |
/// | dominoes16, 1500 | 9.98M | 9.28M (−7 %) | 169 | 0 |
///
/// Stack-40, pyramid-20, bonded-wall and edge-wall at rest never stall: bit-identical. Smaller
/// systems (every contact md5 baseline, the dominoes of lesson 37) keep the old test. The
/// same stop on stage 1's normal sweeps added almost nothing (wall-ball 46.2M → 46.3M,
/// bonded-wall-ball 111.6M → 111.6M, a few steps dearer): not kept.
pub const STALL_BAND: f64 = 0.0;

/// A stage's watch for a stall: the bodies at the start of a sweep, kept once the last
/// sweep's changes fell within the band.
pub(super) struct Stall {
    band: f64,
    watch: bool,
    before: Vec<SolverBody>,
}

impl Stall {
    /// A watch with `band` (0: none) over a stage of `rows` rows (none under
    /// [`SWEEPS_FIRST_ROWS`]).
    pub(super) fn new(band: f64, rows: usize) -> Stall {
        Stall {
            band: if rows >= SWEEPS_FIRST_ROWS { band } else { 0.0 },
            watch: false,
            before: Vec::new(),
        }
    }

    /// Before a sweep: keeps the bodies when the last sweep ended within the band.
    #[inline]
    pub(super) fn start(&mut self, motions: &[SolverBody]) {
        if self.watch {
            self.before.clear();
            self.before.extend_from_slice(motions);
        }
    }

    /// After a sweep whose largest row change was `largest` (over the tolerance): whether it
    /// ends a stall, `net` giving the largest change of a row's velocity from the bodies at
    /// the sweep's start (`net_change`).
    #[inline]
    pub(super) fn stalled(
        &mut self,
        largest: f64,
        tolerance: f64,
        net: impl FnOnce(&[SolverBody]) -> f64,
    ) -> bool {
        let in_band = self.band > 1.0 && largest <= self.band * tolerance;
        let stalled = self.watch && in_band && net(&self.before) <= tolerance;
        self.watch = in_band;
        stalled
    }
}

/// The largest change of the velocity along any of `axes` from the bodies `before` to the
/// bodies `after` (m/s).
pub(super) fn net_change<'a>(
    axes: impl IntoIterator<Item = &'a Axis>,
    before: &[SolverBody],
    after: &[SolverBody],
) -> f64 {
    axes.into_iter()
        .map(|axis| (axis.velocity(after) - axis.velocity(before)).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::net_change;
    use crate::physics::collision::impulse::admm::tests::sliding_cube;
    use crate::physics::collision::impulse::Row;
    use crate::physics::collision::solver_body::Axis;

    /// Each row's normal and tangent axes.
    fn axes<'a>(rows: &'a [Row], directions: &'a [[Axis; 2]]) -> impl Iterator<Item = &'a Axis> {
        rows.iter()
            .zip(directions)
            .flat_map(|(row, [t1, t2])| [&row.normal.axis, t1, t2])
    }

    #[test]
    fn impulses_along_a_flat_direction_of_four_corners_move_no_body() {
        // The cube (2 kg, 0.2 m: I = m s²/6, 1/I = 75) on its four bottom corners, n = y.
        // One corner's impulse j changes its own normal velocity the most, by k j with
        // k = 1/m + |r×n|²/I = 0.5 + 0.02 · 75 = 2 (the others by 0.5 j, −1.0 j, and
        // tangentially by at most 0.75·√2 j).
        let (rows, directions, motions) = sliding_cube(0.0);
        let j = 1e-3;
        let mut after = motions.clone();
        rows[0].normal.axis.apply(j, &mut after);
        let net = net_change(axes(&rows, &directions), &motions, &after);
        assert!((net - 2.0 * j).abs() < 1e-15, "{net}");
        // +j at two diagonal corners, −j at the other two: Σ ±n = 0 and Σ ±r×n = 0, a flat
        // direction of the redundant set. Each of these row updates changes its own row's
        // velocity by 2j; together they move no body (round-off on velocities of 0.05 m/s).
        let mut after = motions.clone();
        for (i, sign) in [(0, 1.0), (3, 1.0), (1, -1.0), (2, -1.0)] {
            rows[i].normal.axis.apply(sign * j, &mut after);
        }
        let net = net_change(axes(&rows, &directions), &motions, &after);
        assert!(net < 1e-15, "{net}");
    }
}
