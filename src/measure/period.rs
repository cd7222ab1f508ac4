//! The period timer: successive upward crossings of a level by a sampled quantity (by default
//! its mid-range), linearly interpolated between samples, and the periods between them.
//!
//! ```text
//! level m = (max q + min q) / 2 over the samples, or a level given (a page's `level`)
//! crossing tₖ: q(tᵢ) < m ≤ q(tᵢ₊₁),   tₖ = tᵢ + (m − q(tᵢ)) / (q(tᵢ₊₁) − q(tᵢ)) · (tᵢ₊₁ − tᵢ)
//! periods Tₖ = tₖ₊₁ − tₖ;  mean T̄ and spread max |Tₖ − T̄|
//! ```
//!
//! The mid-range rather than the average is the default level: an anharmonic swing spends
//! longer near its turning points, and only a level that crosses each swing once per period
//! counts.

/// Periods found in a series: their mean and spread (s), and how many.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Periods {
    pub mean: f64,
    /// The largest distance of a period from the mean, s.
    pub spread: f64,
    pub count: usize,
}

/// What the period timer watches: a quantity of the plot list by name (`bob.x`), and the
/// level whose upward crossings it times (None: the samples' mid-range).
#[derive(Debug, Clone, PartialEq)]
pub struct Watch {
    pub quantity: String,
    pub level: Option<f64>,
}

/// The mid-range (max + min) / 2 of the samples (None: no sample).
pub fn mid_range(q: &[f64]) -> Option<f64> {
    let (lo, hi) = q
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    (lo <= hi).then_some(0.5 * (lo + hi))
}

/// The upward crossings of the mid-range of `q` sampled at times `t` (same length).
pub fn upward_crossings(t: &[f64], q: &[f64]) -> Vec<f64> {
    let n = t.len().min(q.len());
    match mid_range(&q[..n]) {
        Some(level) => crossings_of(t, q, level),
        None => Vec::new(),
    }
}

/// The upward crossings of `level` by `q` sampled at times `t`.
pub fn crossings_of(t: &[f64], q: &[f64], level: f64) -> Vec<f64> {
    let n = t.len().min(q.len());
    if n < 2 {
        return Vec::new();
    }
    (0..n - 1)
        .filter(|&i| q[i] < level && q[i + 1] >= level)
        .map(|i| t[i] + (level - q[i]) / (q[i + 1] - q[i]) * (t[i + 1] - t[i]))
        .collect()
}

/// The periods between successive upward crossings of the mid-range (None: fewer than two
/// crossings).
pub fn periods(t: &[f64], q: &[f64]) -> Option<Periods> {
    of_crossings(&upward_crossings(t, q))
}

/// The periods between successive upward crossings of `level` (None: the mid-range), with the
/// level used.
pub fn periods_at(t: &[f64], q: &[f64], level: Option<f64>) -> (Option<Periods>, Option<f64>) {
    let n = t.len().min(q.len());
    let level = level.or_else(|| mid_range(&q[..n]));
    match level {
        Some(level) => (of_crossings(&crossings_of(t, q, level)), Some(level)),
        None => (None, None),
    }
}

/// The periods between successive crossing times (None: fewer than two).
pub fn of_crossings(crossings: &[f64]) -> Option<Periods> {
    if crossings.len() < 2 {
        return None;
    }
    let each: Vec<f64> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
    let mean = each.iter().sum::<f64>() / each.len() as f64;
    let spread = each.iter().map(|p| (p - mean).abs()).fold(0.0, f64::max);
    Some(Periods {
        mean,
        spread,
        count: each.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_sampled_coarsely_gives_its_period() {
        // sin(2π t / 1.7 + 0.3) sampled every 0.01 s to 9.99 s: upward crossings at
        // (k − 0.048) × 1.7 s for k = 1…5, so 4 periods of 1.7 s; the linear
        // interpolation of each crossing off by O(dt²) of the curvature (zero at a sine's
        // crossing), so far better than a step.
        let t: Vec<f64> = (0..1000).map(|i| i as f64 * 0.01).collect();
        let q: Vec<f64> = t
            .iter()
            .map(|t| (2.0 * std::f64::consts::PI * t / 1.7 + 0.3).sin())
            .collect();
        let p = periods(&t, &q).unwrap();
        assert_eq!(p.count, 4);
        assert!((p.mean - 1.7).abs() < 1e-4, "{p:?}");
        assert!(p.spread < 1e-4, "{p:?}");
    }

    #[test]
    fn a_level_given_is_the_one_crossed() {
        // 1 + sin(2π t): mid-range 1 crossed upward at t = 0, 1, 2 (from the first sample
        // below it); the level 1.5 = 1 + sin(2π t) at t = 1/12 (+ k), so the same 1 s period
        // from crossings 1/12, 13/12, 25/12.
        let t: Vec<f64> = (0..301).map(|i| i as f64 * 0.01 - 0.005).collect();
        let q: Vec<f64> = t
            .iter()
            .map(|t| 1.0 + (2.0 * std::f64::consts::PI * t).sin())
            .collect();
        let (p, level) = periods_at(&t, &q, Some(1.5));
        assert_eq!(level, Some(1.5));
        let c = crossings_of(&t, &q, 1.5);
        assert_eq!(c.len(), 3, "{c:?}");
        assert!((c[0] - 1.0 / 12.0).abs() < 1e-4, "{c:?}");
        let p = p.unwrap();
        assert_eq!(p.count, 2);
        assert!((p.mean - 1.0).abs() < 1e-4, "{p:?}");
        let (_, mid) = periods_at(&t, &q, None);
        assert!((mid.unwrap() - 1.0).abs() < 1e-3, "{mid:?}");
    }

    #[test]
    fn no_period_from_a_monotone_series() {
        let t = [0.0, 1.0, 2.0];
        assert_eq!(periods(&t, &[0.0, 1.0, 2.0]), None);
    }
}
