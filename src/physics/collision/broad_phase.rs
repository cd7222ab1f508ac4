//! Which pairs of bodies may touch: sort and sweep along one axis (Baraff 1992, "Dynamic
//! simulation of non-penetrating rigid bodies", §4; Cohen et al. 1995, I-COLLIDE).
//!
//! Every pair of N bodies is N(N−1)/2 distance tests: 21 945 for a pyramid of 210 cubes, more
//! than its contact solve at rest. Each body instead gets an interval along the axis where the
//! bodies spread most, its barycenter ± (its bounding radius + half the contact margin),
//! padded by [`PAD`]; the intervals are sorted by their lower ends and swept once, and only
//! pairs whose intervals overlap and whose padded spheres meet are returned (then sorted):
//!
//! ```text
//! |x_a − x_b| ≤ r_a + r_b + margin    (necessary for |p_a − p_b| ≤ r_a + r_b + margin)
//! ```
//!
//! A superset of the pairs whose bounding spheres meet (the padding covers the round-off of
//! the interval ends), in the order of the double loop `a < b`, so the caller's exact test
//! and everything after it see the same pairs in the same order as before. A stack is swept
//! along its height (each cube overlaps its two neighbours), a domino run along the run.

use nalgebra::Vector3;

/// Relative padding of each interval: far above the round-off of `x ± r` (1e-16), far
/// below anything a contact margin resolves.
pub const PAD: f64 = 1e-9;

/// One body's interval along the sweep axis.
#[derive(Debug, Clone, Copy)]
struct Interval {
    low: f64,
    high: f64,
    body: usize,
    centre: Vector3<f64>,
    /// Bounding radius + margin/2, padded.
    reach: f64,
}

/// Buffers reused from step to step.
#[derive(Debug, Clone, Default)]
pub struct BroadPhase {
    centres: Vec<(usize, Vector3<f64>, f64)>,
    intervals: Vec<Interval>,
    /// The pairs (a < b) whose intervals overlap, sorted.
    pub pairs: Vec<(usize, usize)>,
}

impl BroadPhase {
    /// Fills [`BroadPhase::pairs`] with the pairs among `bodies` (index, barycenter, bounding
    /// radius) whose bounding spheres, grown by `margin`, may meet (module doc).
    pub fn find(&mut self, bodies: impl Iterator<Item = (usize, Vector3<f64>, f64)>, margin: f64) {
        self.intervals.clear();
        self.pairs.clear();
        let centres = &mut self.centres;
        centres.clear();
        centres.extend(bodies);
        if centres.len() < 2 {
            return;
        }
        // The axis along which the barycenters spread most.
        let mut low = centres[0].1;
        let mut high = low;
        for (_, p, _) in centres.iter() {
            low = low.inf(p);
            high = high.sup(p);
        }
        let axis = (high - low).imax();
        for (body, p, radius) in centres.drain(..) {
            let reach = (radius + 0.5 * margin) * (1.0 + PAD) + PAD * p[axis].abs();
            self.intervals.push(Interval {
                low: p[axis] - reach,
                high: p[axis] + reach,
                body,
                centre: p,
                reach,
            });
        }
        self.intervals
            .sort_unstable_by(|a, b| a.low.total_cmp(&b.low).then(a.body.cmp(&b.body)));
        for (k, a) in self.intervals.iter().enumerate() {
            for b in &self.intervals[k + 1..] {
                if b.low > a.high {
                    break;
                }
                // The padded spheres, so that only pairs that may meet are sorted.
                let reach = a.reach + b.reach;
                if (a.centre - b.centre).norm_squared() <= reach * reach {
                    self.pairs.push((a.body.min(b.body), a.body.max(b.body)));
                }
            }
        }
        self.pairs.sort_unstable();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pairs a double loop finds with the exact sphere test.
    fn every_pair(bodies: &[(Vector3<f64>, f64)], margin: f64) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for a in 0..bodies.len() {
            for b in a + 1..bodies.len() {
                let reach = bodies[a].1 + bodies[b].1 + margin;
                if (bodies[a].0 - bodies[b].0).norm_squared() <= reach * reach {
                    pairs.push((a, b));
                }
            }
        }
        pairs
    }

    #[test]
    fn the_sweep_keeps_every_pair_whose_spheres_meet_and_drops_most_others() {
        // 400 spheres on a jittered 20 × 20 grid in the x–z plane, some just touching
        // (distance = r_a + r_b + margin to the last bit), radii 0.1 to 0.2.
        let mut bodies = Vec::new();
        let mut seed = 12345u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for i in 0..20 {
            for j in 0..20 {
                let r = 0.1 + 0.1 * next();
                let p = Vector3::new(0.3 * i as f64 + 0.05 * next(), 0.0, 0.3 * j as f64);
                bodies.push((p, r));
            }
        }
        // A pair exactly at reach: the test `≤` keeps it, so the sweep must too.
        bodies.push((Vector3::new(10.0, 0.0, 0.0), 0.25));
        bodies.push((Vector3::new(10.0 + 0.25 + 0.25 + 1e-3, 0.0, 0.0), 0.25));
        let margin = 1e-3;
        let mut broad = BroadPhase::default();
        broad.find(
            bodies.iter().enumerate().map(|(i, (p, r))| (i, *p, *r)),
            margin,
        );
        let exact = every_pair(&bodies, margin);
        assert!(exact.contains(&(400, 401)));
        for pair in &exact {
            assert!(broad.pairs.contains(pair), "{pair:?} missing");
        }
        assert!(
            broad.pairs.windows(2).all(|w| w[0] < w[1]),
            "sorted, no repeats"
        );
        // Swept along x (the pair at x = 10 makes it the widest spread): each sphere's
        // interval meets those of its own column and the neighbouring ones, not all 400.
        let all = bodies.len() * (bodies.len() - 1) / 2;
        assert!(
            broad.pairs.len() * 4 < all,
            "{} candidate pairs of {all}",
            broad.pairs.len()
        );
    }
}
