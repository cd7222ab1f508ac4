//! The work budget of a step (issue 35): no step may cost more than [`BUDGET_MEDIANS`] times
//! the scene's typical step, and a step that meets its budget unconverged says so. Where it
//! applies is [`Applies`]; by default nowhere (`MEDIAN_BUDGET`, whose doc has the
//! measurements: cut steps leave residuals up to 0.28 m/s and make later steps dearer), and
//! every step keeps the largest budget, `WORK_BUDGET` sweeps over its rows.
//!
//! Work is counted in *row updates* (a sweep over m rows costs m; a factorisation its estimate,
//! `factorisation_work`): deterministic, unlike time. The scene's typical step is the median
//! of the work of every step it has solved so far (steps with contacts), kept in a histogram
//! ([`WorkMedian`]) that lives in the solver's scratch from step to step. The budget of a step
//! over m rows is
//!
//! ```text
//! B = min( WORK_BUDGET · m,  max( BUDGET_MEDIANS · median,  BUDGET_FLOOR_SWEEPS · m ) )
//! ```
//!
//! - the first step (no history yet) has the absolute cap `WORK_BUDGET · m`, as have the next
//!   ones while the first steps dominate the median: a pyramid loading its rows spends about
//!   as much in steps 2–5 as in step 1, and the median of those steps lets them converge;
//! - the floor of [`BUDGET_FLOOR_SWEEPS`] sweeps over the rows keeps a scene whose median is
//!   tiny (a body at rest answered by one small factorisation, a Newton's cradle whose direct
//!   solves cost a few row updates) from being starved;
//! - a step that does not need its budget is bit for bit what it was without one.
//!
//! The median is *causal* (the steps so far): a scene whose first steps are cheap and later
//! steps dear (dominoes standing, then sliding) gets the early median; one knocked at once (a
//! wall hit in its first steps) the dear one. Measured against the median of a whole run, a
//! step may then exceed the ratio; `contact_steps` prints both.
//!
//! The histogram has [`BINS_PER_OCTAVE`] bins per power of two (linear within the octave: a
//! bin's width is at most 1/16 of its lower edge, and work below 32 has a bin each), so the
//! median it gives is the lower edge of the median's bin: less than 6 % below the exact one
//! (the budget errs on the strict side). The bin of the median is moved as steps are added, so
//! a query costs O(1) amortised.

/// Which stages the budget of [`BUDGET_MEDIANS`] medians bounds (the others keep the largest,
/// `WORK_BUDGET`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Applies {
    /// None: every step has the largest budget.
    Off,
    /// Stage 2 (friction) alone: the step's work, stage 1 included, may reach the budget
    /// before stage 2 stops (stage 1, the normals that keep bodies apart, is never cut).
    Friction,
    /// The whole step.
    Whole,
}

impl Default for Applies {
    /// [`super::MEDIAN_BUDGET`].
    fn default() -> Self {
        super::MEDIAN_BUDGET
    }
}

/// A step may cost at most this many times the median work of the scene's steps so far.
pub const BUDGET_MEDIANS: u64 = 20;

/// The budget is never below this many sweeps over the step's rows (module doc).
pub const BUDGET_FLOOR_SWEEPS: u64 = 20;

/// Bins per power of two of work.
pub const BINS_PER_OCTAVE: usize = 16;

/// Bits of the work below its leading one that choose the bin within its octave.
const SUB_BITS: u32 = BINS_PER_OCTAVE.trailing_zeros();

/// Bin 0 holds work 0; bin 1 + 16 e + s work in `[2^e (1 + s/16), 2^e (1 + (s+1)/16))`.
const BINS: usize = 1 + 64 * BINS_PER_OCTAVE;

/// The median of the work of the steps so far, by a histogram (module doc).
#[derive(Debug, Clone, Default)]
pub struct WorkMedian {
    /// Steps per bin (allocated at the first step).
    counts: Vec<u32>,
    /// Steps added.
    steps: u64,
    /// The bin holding the step of rank ⌊steps/2⌋ (the upper median), and the steps in the
    /// bins below it.
    median: usize,
    below: u64,
}

impl WorkMedian {
    /// The bin of `work` (module doc).
    fn bin(work: u64) -> usize {
        if work == 0 {
            return 0;
        }
        let e = 63 - work.leading_zeros();
        let sub = if e >= SUB_BITS {
            (work >> (e - SUB_BITS)) as usize & (BINS_PER_OCTAVE - 1)
        } else {
            ((work << (SUB_BITS - e)) as usize) & (BINS_PER_OCTAVE - 1)
        };
        1 + e as usize * BINS_PER_OCTAVE + sub
    }

    /// The smallest work in bin `bin`.
    fn lower_edge(bin: usize) -> u64 {
        if bin == 0 {
            return 0;
        }
        let (e, sub) = ((bin - 1) / BINS_PER_OCTAVE, (bin - 1) % BINS_PER_OCTAVE);
        (((BINS_PER_OCTAVE + sub) as u128) << e >> SUB_BITS) as u64
    }

    /// Adds a step's work.
    pub fn add(&mut self, work: u64) {
        if self.counts.is_empty() {
            self.counts.resize(BINS, 0);
        }
        let bin = Self::bin(work);
        self.counts[bin] += 1;
        self.steps += 1;
        if bin < self.median {
            self.below += 1;
        }
        // Move the median's bin until it holds the step of rank ⌊steps/2⌋.
        let rank = self.steps / 2;
        while self.below > rank {
            self.median -= 1;
            self.below -= u64::from(self.counts[self.median]);
        }
        while self.below + u64::from(self.counts[self.median]) <= rank {
            self.below += u64::from(self.counts[self.median]);
            self.median += 1;
        }
    }

    /// The median work of the steps added (the lower edge of its bin), None before the first.
    pub fn median(&self) -> Option<u64> {
        (self.steps > 0).then(|| Self::lower_edge(self.median))
    }

    /// The steps added.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

/// The budget of a step over `rows` rows (module doc): `cap` (`WORK_BUDGET · rows`) before
/// any step is known, else `BUDGET_MEDIANS · median`, but at least
/// `BUDGET_FLOOR_SWEEPS · rows` and at most `cap`.
pub fn budget(median: Option<u64>, rows: usize, cap: u64) -> u64 {
    let Some(median) = median else {
        return cap;
    };
    let floor = BUDGET_FLOOR_SWEEPS * rows as u64;
    (BUDGET_MEDIANS.saturating_mul(median)).max(floor).min(cap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_histogram_median_is_within_a_bin_below_the_exact_median() {
        // Work from a spread of magnitudes, added in a scrambled order: after each step the
        // median it gives is the exact upper median's bin edge, ≤ it and ≥ 16/17 of it.
        let mut median = WorkMedian::default();
        let mut seen = Vec::new();
        let mut x: u64 = 12345;
        for i in 0..3000u64 {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            let work = match i % 5 {
                0 => 0,
                1 => (x >> 40) % 40,
                _ => (x >> 20) % (1 << (i % 23)),
            };
            median.add(work);
            seen.push(work);
            let mut sorted = seen.clone();
            sorted.sort_unstable();
            let exact = sorted[sorted.len() / 2];
            let estimate = median.median().unwrap();
            assert!(estimate <= exact, "step {i}: {estimate} > {exact}");
            assert!(17 * estimate >= 16 * exact, "step {i}: {estimate} ≪ {exact}");
            if exact < 32 {
                assert_eq!(estimate, exact, "step {i}: small work is exact");
            }
        }
        assert_eq!(median.steps(), 3000);
    }

    #[test]
    fn the_budget_is_twenty_medians_between_its_floor_and_its_cap() {
        let cap = 20_000 * 40;
        // No step yet: the cap. Then 20 × the median, at least 20 sweeps over the rows.
        assert_eq!(budget(None, 40, cap), cap);
        assert_eq!(budget(Some(1000), 40, cap), 20_000);
        assert_eq!(budget(Some(10), 40, cap), 20 * 40);
        assert_eq!(budget(Some(0), 40, cap), 20 * 40);
        assert_eq!(budget(Some(100_000), 40, cap), cap);
        // A scene of 36 rows whose steps cost 993 row updates (8 dominoes, 3000 steps):
        // its dearest step (265 689 row updates) gets 19 860.
        let mut median = WorkMedian::default();
        for w in (0..999).map(|i| 900 + (i % 7) * 31) {
            median.add(w);
        }
        let b = budget(median.median(), 36, 20_000 * 36);
        assert!((16 * 20 * 993 / 17..=20 * 993).contains(&b), "{b}");
    }
}
