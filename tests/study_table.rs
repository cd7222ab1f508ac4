//! The study table's layout, from hand-made rows (measured tables vary with the machine's
//! timings, so they are not snapshotted): separate angle and position columns, plain numbers
//! where they fit, short DIVERGED lines, the contact columns.

use tumble::physics::{Integrator, Response};
use tumble::study::{report, Row, SceneStudy, Status};

fn row(integrator: Integrator, dt: f64, ns_per_step: f64, error: f64, status: Status) -> Row {
    Row {
        scene: "s".to_string(),
        integrator,
        dt,
        steps: (1.0 / dt).round() as u64,
        ns_per_step,
        us_per_simulated_second: ns_per_step / dt / 1000.0,
        error,
        angle_error: error * 0.9,
        omega_error: error * 31.0,
        position_error: error * 0.05,
        energy_drift: 3.114,
        momentum_drift: 1.2e-12,
        orthonormality: 0.0,
        penetration: 0.0,
        impact_energy: 0.0,
        rest_error: f64::NAN,
        end_pose_error: f64::NAN,
        contact_error: f64::NAN,
        status,
        frontier: false,
    }
}

fn study(rows: Vec<Row>, response: Option<Response>) -> SceneStudy {
    SceneStudy {
        name: "s".to_string(),
        description: "a hand-made study".to_string(),
        duration: 1.0,
        reference: "exact: by hand".to_string(),
        reference_kind: "exact",
        rows,
        orders: Vec::new(),
        sentence: "One sentence.".to_string(),
        response,
    }
}

#[test]
fn free_motion_table() {
    let mut frontier = row(Integrator::Rk4, 1e-2, 250.0, 3.4e-9, Status::Ok);
    frontier.frontier = true;
    let rows = vec![
        frontier,
        row(Integrator::Euler, 1e-1, 90.0, 3.11, Status::Ok),
        row(
            Integrator::EulerSeed,
            1e-1,
            f64::NAN,
            0.0,
            Status::Diverged(
                "simulation diverged at step 12 (t = 1.200000 s): rotation no longer resolved: \
                 |ω|·dt = 6.1206e0 rad per step, more than half a turn (π) (integrator \
                 euler-seed, dt = 0.1 s)"
                    .to_string(),
            ),
        ),
    ];
    insta::assert_snapshot!(
        "study_table_free_motion",
        report::table(&[study(rows, None)])
    );
}

#[test]
fn contact_table() {
    let mut good = row(Integrator::Splitting, 1e-4, 700.0, 0.0057, Status::Ok);
    (good.penetration, good.impact_energy, good.rest_error) = (2.39e-4, 1.1e-6, 5.3e-11);
    (good.end_pose_error, good.contact_error, good.frontier) = (9.2e-8, 8.87e-4, true);
    let mut seed = row(Integrator::EulerSeed, 1e-4, 450.0, 0.0013, Status::Ok);
    (seed.orthonormality, seed.penetration, seed.rest_error) = (0.00311, 7.5e-5, 2.8e-11);
    (seed.end_pose_error, seed.contact_error) = (9.7e-4, 0.00436);
    let table = report::table(&[study(vec![good, seed], Some(Response::Impulse))]);
    insta::assert_snapshot!("study_table_contact", table);
}
