//! The contact methods charted as the integrators are (`tumble study FILE --response A,B`):
//! on one scene with contact, each listed collision response at the scene's own integrator
//! over the study's sweep of dt, its error against its cost — one line per method, as the
//! integrators' chart has one line per integrator, with the fitted order of each.
//!
//! The error is measured against one reference for every method, never against a method:
//!
//! - **a straight bounce** ([`super::bounce`]: one body dropped flat onto the ground) has a
//!   closed form, and the error is the study's trajectory error against it,
//!   `max over samples of angle(q_ref⁻¹q) + |x − x_ref| / radius`: when each touch falls and
//!   how high each rebound climbs;
//! - **any other scene with contact** is measured as the contact solvers' chart measures it
//!   ([`super::contact`]): the contact error (rest pose, shape, penetration, energy gained)
//!   against `impulse` with `rk4` at a tenth of the smallest swept dt.
//!
//! `*` marks the runs no other run beats on both cost and error; the order is the least-squares
//! slope of log error against log dt over a method's runs with floor < error ≤ 1e-1.

use super::contact::with_response;
use super::measure::{self, Row, Timing};
use super::reference::Reference;
use super::{analysis, Case};
use crate::physics::{Integrator, Response};

/// One method's run at one dt.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodRow {
    pub response: Response,
    /// The measured run (its integrator the scene's); `run.frontier` and `run.below_floor` are
    /// this chart's.
    pub run: Row,
    /// The error charted: `run.error` against a closed form, `run.contact_error` otherwise.
    pub error: f64,
}

/// One method's fitted order.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodOrder {
    pub response: Response,
    /// The slope of log error against log dt (None under two fitted runs).
    pub slope: Option<f64>,
    /// Runs fitted.
    pub points: usize,
}

/// The contact methods' chart of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodStudy {
    /// The scene's integrator, every run's.
    pub integrator: Integrator,
    /// What the runs are measured against, in one line.
    pub reference: String,
    /// "exact" (the closed-form bounce) or "numeric".
    pub reference_kind: &'static str,
    /// Which error is charted: "error" (trajectory, against the closed form) or
    /// "contact_error".
    pub measure: &'static str,
    /// Errors at or below this are not ranked, not fitted.
    pub floor: f64,
    /// Method by method, each over the dt sweep (largest dt first).
    pub rows: Vec<MethodRow>,
    pub orders: Vec<MethodOrder>,
    /// One plain sentence: which method is cheapest for an error, and each one's order.
    pub sentence: String,
}

/// The runs a chart of `methods` over `dts` makes.
pub fn runs(methods: &[Response], dts: &[f64]) -> usize {
    methods.len() * dts.len()
}

/// Charts `methods` on `case` (a scene with contact) at its integrator over `dts`.
pub fn study(case: &Case, methods: &[Response], dts: &[f64], timing: Timing) -> MethodStudy {
    let scene = &case.scene;
    let integrator = scene.integrator;
    let times = measure::sample_times(case.duration, timing.sample_interval);
    let smallest = dts.iter().copied().fold(f64::INFINITY, f64::min);
    let (mut reference, measure) = match super::bounce::Bounce::of(scene) {
        Some(bounce) => (Reference::Bounce(Box::new(bounce)), "error"),
        None => (
            Reference::for_scene(&with_response(scene, Response::Impulse), &times, smallest),
            "contact_error",
        ),
    };
    let floor = analysis::FLOOR.max(reference.floor());
    let mut rows: Vec<MethodRow> = methods
        .iter()
        .flat_map(|&response| dts.iter().map(move |&dt| (response, dt)))
        .map(|(response, dt)| {
            let run = measure::measure(
                &case.name,
                &with_response(scene, response),
                case.duration,
                integrator,
                dt,
                &mut reference,
                &times,
                timing,
            );
            let error = if measure == "error" {
                run.error
            } else {
                run.contact_error
            };
            MethodRow {
                response,
                run,
                error,
            }
        })
        .collect();
    mark_frontier(&mut rows, floor);
    let orders = methods
        .iter()
        .map(|&response| fit_order(response, &rows, floor))
        .collect::<Vec<_>>();
    let sentence = sentence(&rows, &orders, methods);
    let reference_description = match measure {
        "error" => reference.describe(),
        _ => format!(
            "`impulse` with `rk4` at dt = {:e} s (a tenth of the smallest swept step); the \
             contact error, as the contact solvers' chart",
            smallest / 10.0
        ),
    };
    MethodStudy {
        integrator,
        reference: reference_description,
        reference_kind: reference.kind(),
        measure,
        floor,
        rows,
        orders,
        sentence,
    }
}

/// Whether a row is drawn and ranked: finished, with a finite error and a cost.
pub fn usable(row: &MethodRow) -> bool {
    row.run.ok() && row.error.is_finite() && row.run.us_per_simulated_second.is_finite()
}

/// Marks the rows below `floor` and those no other usable row beats on both cost (µs per
/// simulated second) and error (an error below the floor counts as the floor).
pub fn mark_frontier(rows: &mut [MethodRow], floor: f64) {
    let points: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| usable(r))
        .map(|r| (r.run.us_per_simulated_second, r.error.max(floor)))
        .collect();
    for row in rows.iter_mut() {
        row.run.below_floor = row.run.ok() && row.error <= floor;
        let (cost, error) = (row.run.us_per_simulated_second, row.error.max(floor));
        row.run.frontier = usable(row)
            && !points
                .iter()
                .any(|&(c, e)| c <= cost && e <= error && (c < cost || e < error));
    }
}

/// The order of `response`: the least-squares slope of ln error against ln dt over its runs
/// with `floor < error ≤ 1e-1` that finished.
pub fn fit_order(response: Response, rows: &[MethodRow], floor: f64) -> MethodOrder {
    let points: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.response == response && usable(r))
        .filter(|r| r.error > floor && r.error <= analysis::CEILING)
        .map(|r| (r.run.dt.ln(), r.error.ln()))
        .collect();
    let n = points.len();
    let slope = analysis::slope(&points);
    MethodOrder {
        response,
        slope,
        points: n,
    }
}

/// "At the finest dt, `impulse` errs 2.1e-3 for 0.9 µs per simulated second, `soft-step`
/// 4.0e-3 for 2.3 µs; orders: impulse 1.02, soft-step 0.98."
fn sentence(rows: &[MethodRow], orders: &[MethodOrder], methods: &[Response]) -> String {
    let finest = |response: Response| {
        rows.iter()
            .filter(|r| r.response == response && usable(r))
            .min_by(|a, b| a.run.dt.total_cmp(&b.run.dt))
    };
    let at_finest: Vec<String> = methods
        .iter()
        .map(|&m| match finest(m) {
            Some(r) => format!(
                "`{}` errs {} at dt = {} s for {} µs per simulated second",
                m.name(),
                analysis::format_number(r.error),
                analysis::format_dt(r.run.dt),
                analysis::format_cost(r.run.us_per_simulated_second)
            ),
            None => format!("`{}` finished no run", m.name()),
        })
        .collect();
    let fitted: Vec<String> = orders
        .iter()
        .map(|o| match o.slope {
            Some(p) => format!("{} {p:.2}", o.response.name()),
            None => format!("{} none", o.response.name()),
        })
        .collect();
    format!(
        "At each method's finest finished run: {}. Observed orders: {}.",
        at_finest.join("; "),
        fitted.join(", ")
    )
}
