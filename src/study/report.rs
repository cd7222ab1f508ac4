//! The study as text: a table per scene (sorted by cost, frontier marked with `*`), CSV and JSON.
//!
//! CSV header (a contract; extra columns only ever go after the first nine):
//! `scene,integrator,dt,steps,ns_per_step,error,energy_drift,momentum_drift,orthonormality,…`
//!
//! The cloth case ([`super::cloth`]) prints its own section in the table; in the CSV its rows
//! have `case` = `cloth`, the particle integrator in `integrator`, the largest particle
//! distance from the reference (m) in `error` and `position_error`, NaN in the columns of a
//! body's rotation and contact, and its own columns at the end (NaN in a body's row).
//!
//! The contact solvers of a scene with contact ([`super::contact`]) print their own section
//! after the scene's table; in the CSV their rows have `case` = `contact-solver`, the scene's
//! integrator and dt, the response in `solver` (`impulse`, `soft-step`), its sub-steps in
//! `substeps` (0 for `impulse`) and the rest height below the reference (m) in `sink`; a body's
//! and a cloth's rows have the scene's response (or nothing) in `solver`, NaN in the other two.
//!
//! The contact methods asked for with `--response A,B` ([`super::methods`]) print their own
//! section too; in the CSV their rows have `case` = `contact-method`, the scene's integrator,
//! each swept dt, the method in `solver` (`soft-step`'s sub-steps in `substeps`), `reference`
//! `exact` when a straight bounce is measured against its closed form (the charted error is
//! then `error`) and `numeric` otherwise (the charted error is `contact_error`).

use super::analysis::{format_cost, format_dt, format_number};
use super::cloth::{ClothRow, ClothStudy};
use super::contact::ContactStudy;
use super::measure::{Row, Status};
use super::methods::MethodStudy;
use super::SceneStudy;
use crate::physics::Response;
use std::fmt::Write;

/// The CSV header.
pub const CSV_HEADER: &str = "scene,integrator,dt,steps,ns_per_step,error,energy_drift,\
momentum_drift,orthonormality,us_per_simulated_second,omega_error,position_error,penetration,\
impact_energy,rest_error,frontier,status,reference,angle_error,end_pose_error,contact_error,\
case,limit_ratio,drift_j,booked_losses,numerical_damping,energy_rise,solver,substeps,sink,\
below_floor";

/// A number as a CSV cell: full precision, empty where it does not apply (NaN).
fn cell(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else {
        x.to_string()
    }
}

/// A measured number in the table.
fn sci(x: f64) -> String {
    format_number(x)
}

/// A divergence in a few words: "DIVERGED at t = 1.2 s: rotation no longer resolved" (the CSV
/// and JSON keep the whole message).
pub fn short_divergence(message: &str) -> String {
    let time = message
        .split_once("(t = ")
        .and_then(|(_, rest)| rest.split_once(" s)"))
        .and_then(|(t, _)| t.parse::<f64>().ok());
    let what = message
        .split_once("): ")
        .map(|(_, rest)| {
            rest.rsplit_once(" (integrator")
                .or_else(|| rest.rsplit_once(" (cloth "))
                .map_or(rest, |(w, _)| w)
        })
        .map(|w| w.split(':').next().unwrap_or(w).trim());
    match (time, what) {
        (Some(t), Some(what)) => format!("DIVERGED at t = {} s: {what}", format_number(t)),
        _ => format!("DIVERGED: {message}"),
    }
}

/// The human-readable report: per scene, the table, the sentence and the fitted orders.
pub fn table(studies: &[SceneStudy]) -> String {
    let mut out = String::new();
    for study in studies {
        if let Some(cloth) = &study.cloth {
            cloth_table(&mut out, study, cloth);
            continue;
        }
        let contact = study.contact();
        let response = study
            .response
            .map(|r| format!(", response {}", r.name()))
            .unwrap_or_default();
        let _ = writeln!(
            out,
            "== {} ({} s{response}): {}",
            study.name, study.duration, study.description
        );
        let _ = writeln!(out, "reference: {}", study.reference);
        let _ = writeln!(
            out,
            "{ERROR_MEASURE}; angle = max angle(q_ref⁻¹q) (rad), pos = max |x − x_ref| (m), \
             ω = max |ω − ω_ref| (rad/s), the same maxima; drifts are relative maxima"
        );
        if contact {
            let _ = writeln!(
                out,
                "contact (every body, the worst one's): end pose = largest vertex height error at \
                 the end, in radii (the rest pose; where it slid and its heading are left out); \
                 penetr. = deepest depth a step reaches before the response (m); gain = energy \
                 the collide phases add to the scene (J); rest = |v| + radius·|ω| at the end \
                 (m/s); contact err = end + ‖RᵀR−I‖ + penetr./radius + gain/Σ(M·g·radius): the \
                 pose along the way depends on when each impact falls, so * ranks by the \
                 contact error"
            );
        }
        let _ = writeln!(
            out,
            "* = Pareto frontier: no run is both cheaper and more accurate (by {}); ~ = error at \
             or below the floor {} (round-off or the reference's own error): not ranked",
            if contact {
                "the contact error"
            } else {
                "angle + pos/radius"
            },
            format_number(study.floor)
        );
        let mut header = format!(
            "  {:<17}{:>6}{:>9}{:>9}{:>11}{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
            "integrator",
            "dt",
            "steps",
            "ns/step",
            "µs/sim-s",
            "angle rad",
            "pos m",
            "ω rad/s",
            "ΔE/E",
            "Δ|L|/|L|",
            "‖RᵀR−I‖"
        );
        if contact {
            let _ = write!(
                header,
                "{:>10}{:>10}{:>10}{:>10}{:>12}",
                "end pose", "penetr. m", "gain J", "rest m/s", "contact err"
            );
        }
        let _ = writeln!(out, "{header}");
        for row in &study.rows {
            let _ = writeln!(out, "{}", table_row(row, contact));
        }
        let _ = writeln!(out, "{}", study.sentence);
        let orders: Vec<String> = study
            .orders
            .iter()
            .map(|o| match o.slope {
                _ if o.exact => format!("{} exact (error = round-off)", o.integrator.name()),
                Some(s) => format!("{} {:.2} ({} runs)", o.integrator.name(), s, o.points),
                None => format!(
                    "{} none ({})",
                    o.integrator.name(),
                    o.why_not().unwrap_or_default()
                ),
            })
            .collect();
        if !contact {
            let _ = writeln!(
                out,
                "observed order (least-squares slope of log error vs log dt, runs not diverged \
                 with floor < error ≤ 1e-1): {}",
                orders.join("; ")
            );
        }
        if let Some(chart) = &study.contact_solvers {
            solver_table(&mut out, chart);
        }
        if let Some(chart) = &study.methods {
            methods_table(&mut out, chart);
        }
        let _ = writeln!(out);
    }
    out
}

/// The contact solvers' section of a scene's table.
fn solver_table(out: &mut String, chart: &ContactStudy) {
    let _ = writeln!(
        out,
        "contact solvers ({}, dt = {} s; reference: {}); sink = how much lower than the \
         reference the body rests at the end (m)",
        chart.integrator.name(),
        format_dt(chart.dt),
        chart.reference
    );
    let _ = writeln!(
        out,
        "  {:<15}{:>9}{:>10}{:>10}{:>10}{:>10}{:>12}",
        "solver", "ns/step", "end pose", "sink m", "penetr. m", "gain J", "contact err"
    );
    for row in &chart.rows {
        let mark = if row.frontier { '*' } else { ' ' };
        let r = &row.run;
        let line = match &r.status {
            Status::Ok => format!(
                "{mark} {:<15}{:>9.0}{:>10}{:>10}{:>10}{:>10}{:>12}",
                row.solver,
                r.ns_per_step,
                sci(r.end_pose_error),
                sci(row.sink),
                sci(r.penetration),
                sci(r.impact_energy),
                sci(r.contact_error)
            ),
            Status::Diverged(message) => {
                format!("{mark} {:<15}  {}", row.solver, short_divergence(message))
            }
        };
        let _ = writeln!(out, "{line}");
    }
    let _ = writeln!(out, "{}", chart.sentence);
}

/// What a contact-method chart's error is, in one line.
fn methods_measure(chart: &MethodStudy) -> &'static str {
    match chart.measure {
        "error" => "error = max over samples of angle(q_ref⁻¹q) + |x − x_ref|/radius against the closed form",
        _ => "error = the contact error (end pose + ‖RᵀR−I‖ + penetr./radius + gain/Σ(M·g·radius))",
    }
}

/// The contact methods' section of a scene's table (`--response A,B`): each method over the
/// dt sweep, as the integrators' rows.
fn methods_table(out: &mut String, chart: &MethodStudy) {
    let _ = writeln!(
        out,
        "contact methods ({}, every swept dt; reference: {}); {}; * = Pareto frontier of these \
         runs; ~ = at or below the floor {}",
        chart.integrator.name(),
        chart.reference,
        methods_measure(chart),
        format_number(chart.floor)
    );
    let _ = writeln!(
        out,
        "  {:<15}{:>6}{:>9}{:>9}{:>11}{:>10}{:>10}{:>10}{:>12}",
        "method",
        "dt",
        "steps",
        "ns/step",
        "µs/sim-s",
        "error",
        "pos m",
        "penetr. m",
        "contact err"
    );
    for row in &chart.rows {
        let r = &row.run;
        let mark = if r.frontier {
            '*'
        } else if r.below_floor {
            '~'
        } else {
            ' '
        };
        let line = match &r.status {
            Status::Ok => format!(
                "{mark} {:<15}{:>6}{:>9}{:>9.0}{:>11}{:>10}{:>10}{:>10}{:>12}",
                row.response.name(),
                format_dt(r.dt),
                r.steps,
                r.ns_per_step,
                format_cost(r.us_per_simulated_second),
                sci(row.error),
                sci(r.position_error),
                sci(r.penetration),
                sci(r.contact_error)
            ),
            Status::Diverged(message) => format!(
                "{mark} {:<15}{:>6}  {}",
                row.response.name(),
                format_dt(r.dt),
                short_divergence(message)
            ),
        };
        let _ = writeln!(out, "{line}");
    }
    let orders: Vec<String> = chart
        .orders
        .iter()
        .map(|o| match o.slope {
            Some(p) => format!("{} {p:.2} ({} runs)", o.response.name(), o.points),
            None => format!(
                "{} none ({} runs above the floor)",
                o.response.name(),
                o.points
            ),
        })
        .collect();
    let _ = writeln!(out, "{}", chart.sentence);
    let _ = writeln!(
        out,
        "observed order of each method (least-squares slope of log error vs log dt, runs not \
         diverged with floor < error ≤ 1e-1): {}",
        orders.join("; ")
    );
}

/// The cloth case's section of the table.
fn cloth_table(out: &mut String, study: &SceneStudy, cloth: &ClothStudy) {
    let _ = writeln!(
        out,
        "== {} ({} s, cloth case): {}",
        study.name, study.duration, study.description
    );
    let _ = writeln!(out, "reference: {}", cloth.reference);
    let _ = writeln!(
        out,
        "cloth `{}`: 2/ω_max = {} s{}; ×lim = dt / (2/ω_max); the bodies (if any) keep the \
         scene's integrator",
        cloth.limiting_cloth,
        format_number(cloth.limit),
        if (cloth.damped_limit - cloth.limit).abs() > 1e-12 * cloth.limit {
            format!(
                ", with damping stable below h* = {} s",
                format_number(cloth.damped_limit)
            )
        } else {
            String::new()
        }
    );
    let _ = writeln!(
        out,
        "error = max particle distance from the reference over samples every 0.1 s (m); E drift \
         = max |E − E₀ − booked| (J), ΔE/E = that over |E₀|; booked = energy the ledger booked \
         as taken (spring damping, drag, contacts, J); num. damp = energy lost by the end that \
         nothing booked (J); E rise = largest rise of E + booked in one step (J)"
    );
    let _ = writeln!(
        out,
        "* = Pareto frontier: no run is both cheaper and more accurate (by the particle error)"
    );
    let _ = writeln!(
        out,
        "  {:<17}{:>12}{:>7}{:>8}{:>9}{:>11}{:>10}{:>10}{:>10}{:>10}{:>11}{:>10}",
        "integrator",
        "dt",
        "×lim",
        "steps",
        "ns/step",
        "µs/sim-s",
        "error m",
        "ΔE/E",
        "E drift J",
        "booked J",
        "num.damp J",
        "E rise J"
    );
    for row in &cloth.rows {
        let _ = writeln!(out, "{}", cloth_row(row, cloth.damped_limit));
    }
    let _ = writeln!(out, "{}", cloth.sentence);
    let orders: Vec<String> = cloth
        .orders
        .iter()
        .map(|o| match o.slope {
            Some(s) => format!("{} {:.2} ({} runs)", o.integrator.name(), s, o.points),
            None => format!("{} not resolved", o.integrator.name()),
        })
        .collect();
    let _ = writeln!(
        out,
        "observed order (slope of log error vs log dt, runs below 2/ω_max): {}",
        orders.join(", ")
    );
    let _ = writeln!(out);
}

fn cloth_row(row: &ClothRow, damped_limit: f64) -> String {
    let mark = if row.frontier { '*' } else { ' ' };
    let (ns, cost) = if row.ns_per_step.is_finite() {
        (
            format!("{:.0}", row.ns_per_step),
            format_cost(row.us_per_simulated_second),
        )
    } else {
        ("—".to_string(), "—".to_string())
    };
    let mut line = format!(
        "{mark} {:<17}{:>12}{:>7}{:>8}{:>9}{:>11}",
        row.integrator.name(),
        format_dt(row.dt),
        format_number(row.limit_ratio),
        row.steps,
        ns,
        cost,
    );
    match &row.status {
        Status::Ok => {
            let _ = write!(
                line,
                "{:>10}{:>10}{:>10}{:>10}{:>11}{:>10}",
                sci(row.error),
                sci(row.energy_drift),
                sci(row.drift_j),
                sci(row.booked_losses),
                sci(row.numerical_damping),
                sci(row.energy_rise)
            );
        }
        Status::Diverged(message) => {
            let past = match (row.integrator.is_explicit(), row.past_limit()) {
                (true, true) => " (past 2/ω_max)",
                (true, false) if row.dt > damped_limit => " (past h*)",
                _ => "",
            };
            let _ = write!(line, "  {}{past}", short_divergence(message));
        }
    }
    line
}

fn table_row(row: &Row, contact: bool) -> String {
    let mark = match (row.frontier, row.below_floor) {
        (true, _) => '*',
        (false, true) => '~',
        _ => ' ',
    };
    let (ns, cost) = if row.ns_per_step.is_finite() {
        (
            format!("{:.0}", row.ns_per_step),
            format_cost(row.us_per_simulated_second),
        )
    } else {
        ("—".to_string(), "—".to_string())
    };
    let mut line = format!(
        "{mark} {:<17}{:>6}{:>9}{:>9}{:>11}",
        row.integrator.name(),
        format_dt(row.dt),
        row.steps,
        ns,
        cost,
    );
    match &row.status {
        Status::Ok => {
            let _ = write!(
                line,
                "{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
                sci(row.angle_error),
                sci(row.position_error),
                sci(row.omega_error),
                sci(row.energy_drift),
                sci(row.momentum_drift),
                sci(row.orthonormality)
            );
            if contact {
                let _ = write!(
                    line,
                    "{:>10}{:>10}{:>10}{:>10}{:>12}",
                    sci(row.end_pose_error),
                    sci(row.penetration),
                    sci(row.impact_energy),
                    sci(row.rest_error),
                    sci(row.contact_error)
                );
            }
        }
        Status::Diverged(message) => {
            let _ = write!(line, "  {}", short_divergence(message));
        }
    }
    line
}

/// A study row's status as a CSV cell: `ok`, or the divergence message quoted.
fn csv_status(status: &Status) -> String {
    match status {
        Status::Ok => "ok".to_string(),
        Status::Diverged(m) => format!("\"diverged: {}\"", m.replace('"', "'")),
    }
}

/// The CSV columns from `scene` to `rest_error` that every rigid-body row shares.
fn run_columns(r: &Row) -> String {
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
        r.scene,
        r.integrator.name(),
        r.dt,
        r.steps,
        cell(r.ns_per_step),
        cell(r.error),
        cell(r.energy_drift),
        cell(r.momentum_drift),
        cell(r.orthonormality),
        cell(r.us_per_simulated_second),
        cell(r.omega_error),
        cell(r.position_error),
        cell(r.penetration),
        cell(r.impact_energy),
        cell(r.rest_error)
    )
}

/// The raw numbers as CSV, full precision.
pub fn csv(studies: &[SceneStudy]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for study in studies {
        for r in &study.rows {
            let status = csv_status(&r.status);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},body,,,,,,{},,,{}",
                run_columns(r),
                r.frontier,
                status,
                study.reference_kind,
                cell(r.angle_error),
                cell(r.end_pose_error),
                cell(r.contact_error),
                study.response.map_or("", |r| r.name()),
                r.below_floor
            );
        }
        for row in study.contact_solvers.iter().flat_map(|c| &c.rows) {
            let r = &row.run;
            let status = csv_status(&r.status);
            let _ = writeln!(
                out,
                "{},{},{},numeric,{},{},{},contact-solver,,,,,,{},{},{},",
                run_columns(r),
                row.frontier,
                status,
                cell(r.angle_error),
                cell(r.end_pose_error),
                cell(r.contact_error),
                row.response.name(),
                row.substeps,
                cell(row.sink)
            );
        }
        for chart in study.methods.iter() {
            for row in &chart.rows {
                let r = &row.run;
                let _ = writeln!(
                    out,
                    "{},{},{},{},{},{},{},contact-method,,,,,,{},{},,{}",
                    run_columns(r),
                    r.frontier,
                    csv_status(&r.status),
                    chart.reference_kind,
                    cell(r.angle_error),
                    cell(r.end_pose_error),
                    cell(r.contact_error),
                    row.response.name(),
                    match row.response {
                        Response::SoftStep(p) => p.substeps.to_string(),
                        _ => String::new(),
                    },
                    r.below_floor
                );
            }
        }
        for r in study.cloth.iter().flat_map(|c| &c.rows) {
            let status = csv_status(&r.status);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},,,{},,{},,,,{},{},{},,\
                 ,,cloth,{},{},{},{},{},,,,",
                r.scene,
                r.integrator.name(),
                r.dt,
                r.steps,
                cell(r.ns_per_step),
                cell(r.error),
                cell(r.energy_drift),
                cell(r.us_per_simulated_second),
                cell(r.error),
                r.frontier,
                status,
                study.reference_kind,
                cell(r.limit_ratio),
                cell(r.drift_j),
                cell(r.booked_losses),
                cell(r.numerical_damping),
                cell(r.energy_rise)
            );
        }
    }
    out
}

/// What a study's `error` is, in one line (the table, the JSON, the charts, `--help`).
pub const ERROR_MEASURE: &str = "error = max over samples (every 0.1 s and the end) and \
bodies of angle(q_ref⁻¹q) + |x − x_ref|/radius (rad; x the barycenter, radius the body's \
bounding radius)";

/// A run's divergence message, or null.
fn divergence(status: &Status) -> serde_json::Value {
    match status {
        Status::Ok => serde_json::Value::Null,
        Status::Diverged(m) => m.clone().into(),
    }
}

/// Everything as JSON (NaN as null).
pub fn json(studies: &[SceneStudy]) -> String {
    let scenes: Vec<serde_json::Value> = studies
        .iter()
        .map(|s| {
            let rows: Vec<serde_json::Value> = s
                .rows
                .iter()
                .map(|r| {
                    serde_json::json!({
                        "integrator": r.integrator.name(),
                        "dt": r.dt,
                        "steps": r.steps,
                        "ns_per_step": r.ns_per_step,
                        "us_per_simulated_second": r.us_per_simulated_second,
                        "error": r.error,
                        "angle_error": r.angle_error,
                        "end_pose_error": r.end_pose_error,
                        "contact_error": r.contact_error,
                        "omega_error": r.omega_error,
                        "position_error": r.position_error,
                        "energy_drift": r.energy_drift,
                        "momentum_drift": r.momentum_drift,
                        "orthonormality": r.orthonormality,
                        "penetration": r.penetration,
                        "impact_energy": r.impact_energy,
                        "rest_error": r.rest_error,
                        "frontier": r.frontier,
                        "below_floor": r.below_floor,
                        "diverged": !r.ok(),
                        "divergence": divergence(&r.status),
                    })
                })
                .collect();
            let orders: Vec<serde_json::Value> = s
                .orders
                .iter()
                .map(|o| {
                    serde_json::json!({
                        "integrator": o.integrator.name(),
                        "order": o.slope,
                        "order_note": o.why_not(),
                        "points": o.points,
                        "exact": o.exact,
                    })
                })
                .collect();
            let mut scene = serde_json::json!({
                "scene": s.name,
                "description": s.description,
                "duration": s.duration,
                "reference": s.reference,
                "reference_kind": s.reference_kind,
                "error_measure": ERROR_MEASURE,
                "floor": s.floor,
                "sentence": s.sentence,
                "orders": orders,
                "runs": rows,
            });
            if let Some(cloth) = &s.cloth {
                scene["cloth"] = cloth_json(cloth);
            }
            if let Some(chart) = &s.contact_solvers {
                scene["contact_solvers"] = solvers_json(chart);
            }
            if let Some(chart) = &s.methods {
                scene["contact_methods"] = methods_json(chart);
            }
            scene
        })
        .collect();
    let mut text = serde_json::to_string_pretty(&serde_json::json!({ "scenes": scenes }))
        .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    text.push('\n');
    text
}

/// The contact solvers' chart as JSON (NaN as null).
fn solvers_json(chart: &ContactStudy) -> serde_json::Value {
    let runs: Vec<serde_json::Value> = chart
        .rows
        .iter()
        .map(|row| {
            let r = &row.run;
            serde_json::json!({
                "solver": row.response.name(),
                "label": row.solver,
                "substeps": row.substeps,
                "ns_per_step": r.ns_per_step,
                "end_pose_error": r.end_pose_error,
                "sink": row.sink,
                "penetration": r.penetration,
                "impact_energy": r.impact_energy,
                "contact_error": r.contact_error,
                "rest_error": r.rest_error,
                "frontier": row.frontier,
                "diverged": !r.ok(),
                "divergence": divergence(&r.status),
            })
        })
        .collect();
    serde_json::json!({
        "integrator": chart.integrator.name(),
        "dt": chart.dt,
        "reference": chart.reference,
        "sentence": chart.sentence,
        "runs": runs,
    })
}

/// The contact methods' chart as JSON (NaN as null): each run's `error` is the charted one
/// (`error_measure` says which).
fn methods_json(chart: &MethodStudy) -> serde_json::Value {
    let runs: Vec<serde_json::Value> = chart
        .rows
        .iter()
        .map(|row| {
            let r = &row.run;
            serde_json::json!({
                "response": row.response.name(),
                "integrator": r.integrator.name(),
                "dt": r.dt,
                "steps": r.steps,
                "ns_per_step": r.ns_per_step,
                "us_per_simulated_second": r.us_per_simulated_second,
                "error": row.error,
                "trajectory_error": r.error,
                "position_error": r.position_error,
                "angle_error": r.angle_error,
                "contact_error": r.contact_error,
                "end_pose_error": r.end_pose_error,
                "penetration": r.penetration,
                "impact_energy": r.impact_energy,
                "frontier": r.frontier,
                "below_floor": r.below_floor,
                "diverged": !r.ok(),
                "divergence": divergence(&r.status),
            })
        })
        .collect();
    let orders: Vec<serde_json::Value> = chart
        .orders
        .iter()
        .map(|o| {
            serde_json::json!({
                "response": o.response.name(),
                "order": o.slope,
                "points": o.points,
            })
        })
        .collect();
    serde_json::json!({
        "integrator": chart.integrator.name(),
        "reference": chart.reference,
        "reference_kind": chart.reference_kind,
        "error_measure": methods_measure(chart),
        "floor": chart.floor,
        "sentence": chart.sentence,
        "orders": orders,
        "runs": runs,
    })
}

/// The cloth case as JSON (NaN as null).
fn cloth_json(cloth: &ClothStudy) -> serde_json::Value {
    use super::cloth::SameError;
    let runs: Vec<serde_json::Value> = cloth
        .rows
        .iter()
        .map(|r| {
            serde_json::json!({
                "integrator": r.integrator.name(),
                "dt": r.dt,
                "steps": r.steps,
                "limit_ratio": r.limit_ratio,
                "past_limit": r.past_limit(),
                "ns_per_step": r.ns_per_step,
                "us_per_simulated_second": r.us_per_simulated_second,
                "error": r.error,
                "energy_drift": r.energy_drift,
                "drift_j": r.drift_j,
                "booked_losses": r.booked_losses,
                "numerical_damping": r.numerical_damping,
                "energy_rise": r.energy_rise,
                "frontier": r.frontier,
                "diverged": r.status != Status::Ok,
                "divergence": divergence(&r.status),
            })
        })
        .collect();
    let orders: Vec<serde_json::Value> = cloth
        .orders
        .iter()
        .map(|o| {
            serde_json::json!({
                "integrator": o.integrator.name(),
                "order": o.slope,
                "order_note": o.slope.is_none().then(|| format!(
                    "fewer than 2 runs below 2/ω_max that did not diverge ({} usable)",
                    o.points
                )),
                "points": o.points,
            })
        })
        .collect();
    let same_error = match &cloth.comparison.same_error {
        SameError::Reached {
            target,
            explicit_dt,
            implicit_dt,
            ratio,
        } => serde_json::json!({
            "kind": "reached", "target": target, "explicit_dt": explicit_dt,
            "implicit_dt": implicit_dt, "ratio": ratio,
        }),
        SameError::AtLeast {
            target,
            explicit_dt,
            implicit_dt,
            implicit_error,
            ratio,
        } => serde_json::json!({
            "kind": "at_least", "target": target, "explicit_dt": explicit_dt,
            "implicit_dt": implicit_dt, "implicit_error": implicit_error, "ratio": ratio,
        }),
        SameError::NotReached {
            target,
            explicit_dt,
            best_error,
            best_dt,
            extrapolated,
        } => serde_json::json!({
            "kind": "not_reached", "target": target, "explicit_dt": explicit_dt,
            "best_error": best_error, "best_dt": best_dt,
            "extrapolated_dt": extrapolated.map(|e| e.0),
            "extrapolated_ratio": extrapolated.map(|e| e.1),
        }),
        SameError::Missing(why) => serde_json::json!({ "kind": "missing", "why": why }),
    };
    let past_limit = cloth.comparison.past_limit.map(|p| {
        serde_json::json!({
            "implicit_dt": p.implicit_dt, "implicit_error": p.implicit_error,
            "explicit_dt": p.explicit_dt, "explicit_error": p.explicit_error, "ratio": p.ratio,
        })
    });
    serde_json::json!({
        "limit": cloth.limit,
        "damped_limit": cloth.damped_limit,
        "limiting_cloth": cloth.limiting_cloth,
        "ladder": cloth.ladder,
        "reference": cloth.reference,
        "reference_spread": cloth.reference_spread,
        "orders": orders,
        "same_error": same_error,
        "past_limit": past_limit,
        "sentence": cloth.sentence,
        "runs": runs,
    })
}
