//! What the numbers say: the Pareto frontier, the observed orders, one sentence per scene.
//!
//! ```text
//! frontier:  run r is on it  ⇔  no other run s has cost(s) ≤ cost(r) and error(s) ≤ error(r),
//!            one of them strictly    (cost = µs per simulated second; error = Row::measure:
//!            the pose error, or in a scene with contact the contact error)
//! floor:     max(FLOOR, SPREAD_BAND × the reference's spread): below it an error is round-off
//!            or the reference's own error, not the run's; runs below it are not ranked
//!            against each other (the frontier sees their error as the floor) nor fitted
//! order:     least-squares slope of ln(error) against ln(dt) over the asymptotic range:
//!            runs that did not diverge with floor < error ≤ CEILING (above the ceiling the
//!            error saturates — angles wrap at π); none (null) when fewer than two runs are
//!            in that range, and the output says why (diverged, saturated, below the floor;
//!            an integrator exact on the scene has only round-off)
//! ```

use super::measure::Row;
use crate::physics::Integrator;

/// Errors below this are round-off, not truncation.
pub const FLOOR: f64 = 1e-11;
/// Errors above this are not in the asymptotic range any more.
pub const CEILING: f64 = 1e-1;
/// The contact error the sentence of a contact scene asks for: a thousandth of the body's
/// radius at rest (0.3 mm for the dropped box), no more deformation, sinking or energy gained.
pub const CONTACT_TARGET: f64 = 1e-3;

/// The fitted order of convergence of one integrator on one scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Order {
    pub integrator: Integrator,
    /// The slope, if at least two runs lie in the asymptotic range.
    pub slope: Option<f64>,
    /// How many runs the fit used.
    pub points: usize,
    /// The integrator is exact on this scene (no torque, no drag: see
    /// [`crate::physics::integrators::Descriptor::exact_without_torque`]): its error is
    /// round-off, which grows with the number of steps, so no order is fitted.
    pub exact: bool,
    /// Runs left out of the fit because they diverged, saturated (error > CEILING) or lie
    /// below the floor.
    pub diverged: usize,
    pub saturated: usize,
    pub below_floor: usize,
}

impl Order {
    /// Why no order was fitted (`None` when one was).
    pub fn why_not(&self) -> Option<String> {
        if self.slope.is_some() {
            return None;
        }
        if self.exact {
            return Some("exact on this scene: its error is round-off, with no order".into());
        }
        Some(format!(
            "fewer than 2 runs in the asymptotic range ({} usable; {} diverged, {} saturated \
             above {CEILING:.0e}, {} below the floor)",
            self.points, self.diverged, self.saturated, self.below_floor
        ))
    }
}

/// The least-squares slope of y against x over `points` (x, y): Σ(x − x̄)(y − ȳ) / Σ(x − x̄)²;
/// `None` under two points. The orders are this slope over (ln dt, ln error).
pub fn slope(points: &[(f64, f64)]) -> Option<f64> {
    let n = points.len();
    (n >= 2).then(|| {
        let mx = points.iter().map(|p| p.0).sum::<f64>() / n as f64;
        let my = points.iter().map(|p| p.1).sum::<f64>() / n as f64;
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = points.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
        sxy / sxx
    })
}

/// Fits the observed order of `integrator` from the rows of one scene, over the runs with
/// `floor < error ≤ CEILING` that did not diverge.
pub fn fit_order(integrator: Integrator, rows: &[Row], floor: f64) -> Order {
    let floor = floor.max(FLOOR);
    let mine = || rows.iter().filter(|r| r.integrator == integrator);
    let points: Vec<(f64, f64)> = mine()
        .filter(|r| r.ok() && r.error > floor && r.error <= CEILING)
        .map(|r| (r.dt.ln(), r.error.ln()))
        .collect();
    let n = points.len();
    let slope = slope(&points);
    Order {
        integrator,
        slope,
        points: n,
        exact: false,
        diverged: mine().filter(|r| !r.ok()).count(),
        saturated: mine().filter(|r| r.ok() && r.error > CEILING).count(),
        below_floor: mine().filter(|r| r.ok() && r.error <= floor).count(),
    }
}

/// The order of an integrator that is exact on the scene: none to fit.
pub fn exact_order(integrator: Integrator) -> Order {
    Order {
        integrator,
        slope: None,
        points: 0,
        exact: true,
        diverged: 0,
        saturated: 0,
        below_floor: 0,
    }
}

/// Marks the runs below `floor` and the runs no other run beats on both error and cost; an
/// error below the floor counts as the floor (runs inside it are not ranked by their
/// round-off: the cheapest of them is the frontier's end).
pub fn mark_frontier(rows: &mut [Row], floor: f64) {
    let floor = floor.max(FLOOR);
    for row in rows.iter_mut() {
        row.below_floor = row.ok() && row.measure() <= floor;
    }
    let usable =
        |r: &Row| r.ok() && r.measure().is_finite() && r.us_per_simulated_second.is_finite();
    let candidates: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| usable(r))
        .map(|r| (r.us_per_simulated_second, r.measure().max(floor)))
        .collect();
    for row in rows.iter_mut() {
        let (cost, error) = (row.us_per_simulated_second, row.measure().max(floor));
        row.frontier = usable(row)
            && !candidates
                .iter()
                .any(|&(c, e)| c <= cost && e <= error && (c < cost || e < error));
    }
}

/// Sorts by cost, diverged runs last.
pub fn sort_by_cost(rows: &mut [Row]) {
    rows.sort_by(|a, b| {
        (!a.ok()).cmp(&!b.ok()).then(
            a.us_per_simulated_second
                .total_cmp(&b.us_per_simulated_second),
        )
    });
}

/// A time step as `1e-3` (or in full when it is not a power of ten).
pub fn format_dt(dt: f64) -> String {
    let exponent = dt.log10().round();
    if (dt / 10f64.powf(exponent) - 1.0).abs() < 1e-9 {
        format!("1e{}", exponent as i32)
    } else {
        format!("{dt:e}")
    }
}

/// A measured number in a table: three significant digits, in plain decimals where that
/// takes at most 7 characters (0.00123 … 9999), else as `1.23e-8`; 0 as `0`, NaN as `—`.
pub fn format_number(x: f64) -> String {
    let a = x.abs();
    if x.is_nan() {
        "—".to_string()
    } else if x == 0.0 {
        "0".to_string()
    } else if (1e-3..9999.5).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.2e}")
    }
}

/// A cost in µs, with three significant digits.
pub fn format_cost(us: f64) -> String {
    if us >= 100.0 {
        format!("{us:.0}")
    } else if us >= 10.0 {
        format!("{us:.1}")
    } else {
        format!("{us:.2}")
    }
}

/// One plain sentence: the largest swept dt at which each integrator keeps the error under
/// `target`, and what that costs; cheapest first, then the integrators that never get there.
pub fn sentence(rows: &[Row], integrators: &[Integrator], target: f64, duration: f64) -> String {
    let contact = rows.iter().any(|r| !r.contact_error.is_nan());
    let target = if contact { CONTACT_TARGET } else { target };
    let mut reached = Vec::new();
    let mut missed = Vec::new();
    for &integrator in integrators {
        let best = rows
            .iter()
            .filter(|r| r.integrator == integrator && r.ok() && r.measure() < target)
            .max_by(|a, b| a.dt.total_cmp(&b.dt));
        match best {
            Some(r) => reached.push((r.us_per_simulated_second, integrator, r.dt)),
            None => {
                let smallest = rows
                    .iter()
                    .filter(|r| r.integrator == integrator)
                    .min_by(|a, b| a.dt.total_cmp(&b.dt));
                missed.push((integrator, smallest.cloned()));
            }
        }
    }
    reached.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut parts: Vec<String> = reached
        .iter()
        .map(|(cost, integrator, dt)| {
            format!(
                "`{}` needs dt = {} and costs {} µs per simulated second",
                integrator.name(),
                format_dt(*dt),
                format_cost(*cost)
            )
        })
        .collect();
    for (integrator, smallest) in missed {
        parts.push(match smallest {
            Some(r) if r.ok() => format!(
                "`{}` does not get there even at dt = {} (error {})",
                integrator.name(),
                format_dt(r.dt),
                format_number(r.measure())
            ),
            Some(r) => format!(
                "`{}` diverges even at dt = {}",
                integrator.name(),
                format_dt(r.dt)
            ),
            None => format!("`{}` was not run", integrator.name()),
        });
    }
    if contact {
        format!(
            "To keep the contact error (end pose, shape, penetration, energy gained) under \
             {target:.0e} over {duration} s, {}.",
            parts.join("; ")
        )
    } else {
        format!(
            "To keep the error under {target:.0e} rad over {duration} s, {}.",
            parts.join("; ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_plain_where_they_fit() {
        assert_eq!(format_number(3.114), "3.11");
        assert_eq!(format_number(0.0167), "0.0167");
        assert_eq!(format_number(0.00311), "0.00311");
        assert_eq!(format_number(130.4), "130");
        assert_eq!(format_number(-0.5), "-0.500");
        assert_eq!(format_number(1.38e-15), "1.38e-15");
        assert_eq!(format_number(2.5e5), "2.50e5");
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(f64::NAN), "—");
    }
}
