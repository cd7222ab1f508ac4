//! The study as text: a table per scene (sorted by cost, frontier marked with `*`), CSV and JSON.
//!
//! CSV header (a contract; extra columns only ever go after the first nine):
//! `scene,integrator,dt,steps,ns_per_step,error,energy_drift,momentum_drift,orthonormality,…`

use super::analysis::{format_cost, format_dt};
use super::measure::{Row, Status};
use super::SceneStudy;
use std::fmt::Write;

/// The CSV header.
pub const CSV_HEADER: &str = "scene,integrator,dt,steps,ns_per_step,error,energy_drift,\
momentum_drift,orthonormality,us_per_simulated_second,omega_error,position_error,penetration,\
impact_energy,rest_error,frontier,status,reference";

/// A measured number in the table: 3 significant digits, NaN as `—`.
fn sci(x: f64) -> String {
    if x.is_nan() {
        "—".to_string()
    } else if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.2e}")
    }
}

/// The human-readable report: per scene, the table, the sentence and the fitted orders.
pub fn table(studies: &[SceneStudy]) -> String {
    let mut out = String::new();
    for study in studies {
        let contact = study
            .rows
            .iter()
            .any(|r| r.penetration > 0.0 || r.impact_energy > 0.0)
            || study.reference_kind == "numeric";
        let _ = writeln!(
            out,
            "== {} ({} s): {}",
            study.name, study.duration, study.description
        );
        let _ = writeln!(out, "reference: {}", study.reference);
        let _ = writeln!(
            out,
            "error = max over samples every 0.1 s of angle(q_ref⁻¹q) + |x − x_ref|/radius (rad); \
             drifts are relative maxima; * = Pareto frontier (no run is both cheaper and more accurate)"
        );
        let mut header = format!(
            "  {:<17}{:>6}{:>9}{:>9}{:>11}{:>10}{:>10}{:>10}{:>10}{:>10}",
            "integrator",
            "dt",
            "steps",
            "ns/step",
            "µs/sim-s",
            "error",
            "ω error",
            "ΔE/E",
            "Δ|L|/|L|",
            "‖RᵀR−I‖"
        );
        if contact {
            let _ = write!(
                header,
                "{:>11}{:>11}{:>10}",
                "penetr. m", "gain J", "rest m/s"
            );
        }
        if contact {
            let _ = writeln!(
                out,
                "contact: penetr. = deepest vertex depth a step reaches before the response; \
                 gain = energy added by collide phases; rest = |v| + radius·|ω| at the end"
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
                None => format!("{} not resolved", o.integrator.name()),
            })
            .collect();
        let _ = writeln!(
            out,
            "observed order (slope of log error vs log dt, errors in [1e-11, 1e-1]): {}",
            orders.join(", ")
        );
        let _ = writeln!(out);
    }
    out
}

fn table_row(row: &Row, contact: bool) -> String {
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
                "{:>10}{:>10}{:>10}{:>10}{:>10}",
                sci(row.error),
                sci(row.omega_error),
                sci(row.energy_drift),
                sci(row.momentum_drift),
                sci(row.orthonormality)
            );
            if contact {
                let _ = write!(
                    line,
                    "{:>11}{:>11}{:>10}",
                    sci(row.penetration),
                    sci(row.impact_energy),
                    sci(row.rest_error)
                );
            }
        }
        Status::Diverged(message) => {
            let _ = write!(line, "  DIVERGED: {message}");
        }
    }
    line
}

/// The raw numbers as CSV, full precision.
pub fn csv(studies: &[SceneStudy]) -> String {
    let mut out = String::from(CSV_HEADER);
    out.push('\n');
    for study in studies {
        for r in &study.rows {
            let status = match &r.status {
                Status::Ok => "ok".to_string(),
                Status::Diverged(m) => format!("\"diverged: {}\"", m.replace('"', "'")),
            };
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                r.scene,
                r.integrator.name(),
                r.dt,
                r.steps,
                r.ns_per_step,
                r.error,
                r.energy_drift,
                r.momentum_drift,
                r.orthonormality,
                r.us_per_simulated_second,
                r.omega_error,
                r.position_error,
                r.penetration,
                r.impact_energy,
                r.rest_error,
                r.frontier,
                status,
                study.reference_kind
            );
        }
    }
    out
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
                        "omega_error": r.omega_error,
                        "position_error": r.position_error,
                        "energy_drift": r.energy_drift,
                        "momentum_drift": r.momentum_drift,
                        "orthonormality": r.orthonormality,
                        "penetration": r.penetration,
                        "impact_energy": r.impact_energy,
                        "rest_error": r.rest_error,
                        "frontier": r.frontier,
                        "diverged": match &r.status {
                            Status::Ok => serde_json::Value::Null,
                            Status::Diverged(m) => m.clone().into(),
                        },
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
                        "points": o.points,
                        "exact": o.exact,
                    })
                })
                .collect();
            serde_json::json!({
                "scene": s.name,
                "description": s.description,
                "duration": s.duration,
                "reference": s.reference,
                "reference_kind": s.reference_kind,
                "sentence": s.sentence,
                "orders": orders,
                "runs": rows,
            })
        })
        .collect();
    let mut text = serde_json::to_string_pretty(&serde_json::json!({ "scenes": scenes }))
        .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    text.push('\n');
    text
}
