//! The period timer (issue 38's measuring tools, the logic without its panel yet): successive
//! upward crossings of a quantity's mean, linearly interpolated between samples, and the
//! periods between them.
//!
//! ```text
//! mean m = (max q + min q) / 2 over the samples
//! crossing tₖ: q(tᵢ) < m ≤ q(tᵢ₊₁),   tₖ = tᵢ + (m − q(tᵢ)) / (q(tᵢ₊₁) − q(tᵢ)) · (tᵢ₊₁ − tᵢ)
//! periods Tₖ = tₖ₊₁ − tₖ;  mean T̄ and spread max |Tₖ − T̄|
//! ```
//!
//! The mid-range rather than the average is the level: an anharmonic swing spends longer
//! near its turning points, and only a level that crosses each swing once per period counts.

/// Periods found in a series: their mean and spread (s), and how many.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Periods {
    pub mean: f64,
    /// The largest distance of a period from the mean, s.
    pub spread: f64,
    pub count: usize,
}

/// The upward crossings of the mid-range of `q` sampled at times `t` (same length).
pub fn upward_crossings(t: &[f64], q: &[f64]) -> Vec<f64> {
    let n = t.len().min(q.len());
    if n < 2 {
        return Vec::new();
    }
    let (lo, hi) = q[..n]
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let level = 0.5 * (lo + hi);
    (0..n - 1)
        .filter(|&i| q[i] < level && q[i + 1] >= level)
        .map(|i| t[i] + (level - q[i]) / (q[i + 1] - q[i]) * (t[i + 1] - t[i]))
        .collect()
}

/// The periods between successive upward crossings (None: fewer than two crossings).
pub fn periods(t: &[f64], q: &[f64]) -> Option<Periods> {
    let crossings = upward_crossings(t, q);
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
    fn no_period_from_a_monotone_series() {
        let t = [0.0, 1.0, 2.0];
        assert_eq!(periods(&t, &[0.0, 1.0, 2.0]), None);
    }
}
