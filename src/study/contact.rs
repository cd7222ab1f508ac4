//! The contact solvers charted (issue 17, item 4): on a scene with contact, what accuracy
//! costs in time for the collision response itself. The scene's own integrator and dt are
//! kept; the response changes: `impulse`, then `soft-step` at 1, 2, 4 and 8 sub-steps (its
//! other keys at their documented defaults).
//!
//! Every solver's run is measured by [`measure`](super::measure::measure) against one converged
//! reference — the scene under `impulse` with `rk4` at a tenth of its dt — and by the rest
//! height at the end:
//!
//! ```text
//! end_pose_error = largest vertex height error at the end, in radii (the rest pose)
//! sink           = (x_ref − x)·up at the end, m: how much lower than the reference the body
//!                  rests (> 0 sank; soft contacts sag by design)
//! penetration    = deepest depth a step reaches before the response, m
//! impact_energy  = energy added by collide phases, J
//! contact_error  = as the body rows' (end pose + ‖RᵀR − 𝟙‖ + penetration/radius + gain/(M g radius))
//! cost           = ns per step of plain World::step (minimum over runs of the median 1000-step chunk)
//! ```
//!
//! `*` marks the solvers no other solver beats on both cost and contact error.

use super::measure::{self, Row, Status, Timing};
use super::reference::Reference;
use crate::physics::{Integrator, Response, SoftStep};
use crate::scene::Scene;
use nalgebra::Vector3;

/// The sub-step counts `soft-step` is charted at.
pub const SUBSTEPS: [u32; 4] = [1, 2, 4, 8];

/// The solvers charted, in the list's order ([`Response::ALL`]): every response whose
/// descriptor says `charted` (`impulse`, then `soft-step` at each of [`SUBSTEPS`]).
pub fn solvers() -> Vec<Response> {
    Response::ALL
        .into_iter()
        .filter(|r| r.descriptor().charted)
        .flat_map(|response| match response {
            Response::SoftStep(defaults) => SUBSTEPS
                .iter()
                .map(|&substeps| {
                    Response::SoftStep(SoftStep {
                        substeps,
                        ..defaults
                    })
                })
                .collect(),
            other => vec![other],
        })
        .collect()
}

/// A solver's label: `impulse`, `soft-step×4`.
pub fn label(response: Response) -> String {
    match response {
        Response::SoftStep(p) => format!("soft-step×{}", p.substeps),
        r => r.name().to_string(),
    }
}

/// One solver's run.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverRow {
    pub scene: String,
    pub response: Response,
    /// [`label`] of the response.
    pub solver: String,
    /// Sub-steps (`soft-step`), 0 for `impulse`.
    pub substeps: u32,
    /// The measured run (its integrator and dt are the scene's).
    pub run: Row,
    /// How much lower than the reference the body rests at the end, m (module doc).
    pub sink: f64,
    /// No other solver is both cheaper and more accurate (by the contact error).
    pub frontier: bool,
}

/// The contact solvers' chart of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactStudy {
    pub integrator: Integrator,
    pub dt: f64,
    /// What the runs are measured against.
    pub reference: String,
    pub rows: Vec<SolverRow>,
    /// One plain sentence: what the fast solver buys and what it costs in accuracy.
    pub sentence: String,
}

/// The scene with another response (its restitution and friction kept).
pub(super) fn with_response(scene: &Scene, response: Response) -> Scene {
    let mut scene = scene.clone();
    if let Some(model) = scene.contact.as_mut() {
        model.response = response;
    }
    scene
}

/// Charts the contact solvers on `scene` (which has contact with obstacles) over `duration`,
/// sampling at `times`.
pub fn study(
    name: &str,
    scene: &Scene,
    duration: f64,
    times: &[f64],
    timing: Timing,
) -> ContactStudy {
    let (integrator, dt) = (scene.integrator, scene.dt);
    let reference_scene = with_response(scene, Response::Impulse);
    let mut reference = Reference::for_scene(&reference_scene, times, dt);
    let last = times.len() - 1;
    let truth = reference.at(last, duration)[0].position;
    let up = scene
        .effects
        .gravity()
        .and_then(|g| (-g).try_normalize(0.0))
        .unwrap_or_else(Vector3::y);
    let mut rows: Vec<SolverRow> = solvers()
        .into_iter()
        .map(|response| {
            let solver_scene = with_response(scene, response);
            let run = measure::measure(
                name,
                &solver_scene,
                duration,
                integrator,
                dt,
                &mut reference,
                times,
                timing,
            );
            let sink = if run.ok() {
                let mut world = solver_scene.world_with(integrator, dt);
                while world.step_count() < run.steps {
                    super::cancel::check(1);
                    world.step();
                }
                (truth - world.state().position).dot(&up)
            } else {
                f64::NAN
            };
            SolverRow {
                scene: name.to_string(),
                response,
                solver: label(response),
                substeps: match response {
                    Response::SoftStep(p) => p.substeps,
                    _ => 0,
                },
                run,
                sink,
                frontier: false,
            }
        })
        .collect();
    mark_frontier(&mut rows);
    let sentence = sentence(&rows);
    ContactStudy {
        integrator,
        dt,
        reference: format!(
            "impulse with rk4 at dt = {:e} s (a tenth of the scene's)",
            dt / 10.0
        ),
        rows,
        sentence,
    }
}

/// Marks the rows no other finished row beats on both cost and contact error.
pub fn mark_frontier(rows: &mut [SolverRow]) {
    let points: Vec<(f64, f64, bool)> = rows
        .iter()
        .map(|r| (r.run.ns_per_step, r.run.contact_error, r.run.ok()))
        .collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let (cost, error, ok) = points[i];
        row.frontier = ok
            && !points.iter().enumerate().any(|(j, &(c, e, o))| {
                j != i && o && c <= cost && e <= error && (c < cost || e < error)
            });
    }
}

/// "`soft-step×1` costs 0.41× `impulse` per step; it rests 0.02 mm lower than the reference
/// (`impulse` 0 mm) and its contact error is 3e-4 against 1e-6."
fn sentence(rows: &[SolverRow]) -> String {
    let Some(impulse) = rows
        .iter()
        .find(|r| r.response == Response::Impulse && r.run.ok())
    else {
        return "`impulse` did not finish: no comparison.".to_string();
    };
    let cheapest = rows
        .iter()
        .filter(|r| r.response != Response::Impulse && r.run.ok())
        .min_by(|a, b| a.run.ns_per_step.total_cmp(&b.run.ns_per_step));
    match cheapest {
        None => "No `soft-step` run finished.".to_string(),
        Some(soft) => format!(
            "The cheapest soft solver, `{}`, costs {:.2}× `impulse` per step; it rests {} mm \
             lower than the reference (`impulse` {} mm), penetrates {} mm at most (`impulse` {} \
             mm), and its contact error is {:.1e} against `impulse`'s {:.1e}.",
            soft.solver,
            soft.run.ns_per_step / impulse.run.ns_per_step,
            millimetres(soft.sink),
            millimetres(impulse.sink),
            millimetres(soft.run.penetration),
            millimetres(impulse.run.penetration),
            soft.run.contact_error,
            impulse.run.contact_error
        ),
    }
}

/// A length in mm, three significant digits.
fn millimetres(x: f64) -> String {
    super::analysis::format_number(x * 1e3)
}

/// Whether a diverged solver row says why.
pub fn diverged(row: &SolverRow) -> Option<&str> {
    match &row.run.status {
        Status::Ok => None,
        Status::Diverged(m) => Some(m),
    }
}
