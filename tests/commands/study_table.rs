//! The study table's layout, from hand-made rows (measured tables vary with the machine's
//! timings, so they are not snapshotted): separate angle and position columns, plain numbers
//! where they fit, short DIVERGED lines, the contact columns, the cloth case's section.

use tumble::physics::cloth::ClothIntegrator;
use tumble::physics::{Integrator, Response};
use tumble::study::cloth::{self, ClothOrder, ClothRow, ClothStudy};
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
        below_floor: false,
    }
}

fn study(rows: Vec<Row>, response: Option<Response>) -> SceneStudy {
    SceneStudy {
        name: "s".to_string(),
        description: "a hand-made study".to_string(),
        duration: 1.0,
        reference: "exact: by hand".to_string(),
        reference_kind: "exact",
        floor: 1e-11,
        rows,
        orders: Vec::new(),
        sentence: "One sentence.".to_string(),
        response,
        cloth: None,
        contact_solvers: None,
        methods: None,
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
                 |ω|·dt = 6.1206 rad per step, more than half a turn (π) (integrator \
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

fn cloth_row(integrator: ClothIntegrator, dt: f64, error: f64, status: Status) -> ClothRow {
    let limit = 3.69e-3;
    ClothRow {
        scene: "t".to_string(),
        integrator,
        dt,
        steps: (1.0 / dt).round() as u64,
        limit_ratio: dt / limit,
        ns_per_step: if status == Status::Ok {
            2500.0
        } else {
            f64::NAN
        },
        us_per_simulated_second: 2500.0 / dt / 1000.0,
        error,
        energy_drift: 2.6e-4,
        drift_j: 5.2e-4,
        numerical_damping: 1.3e-4,
        booked_losses: 0.00836,
        energy_rise: -3.2e-6,
        status,
        frontier: false,
    }
}

#[test]
fn cloth_table() {
    // Hand-made rows of a sheet with 2/ω_max = 3.69e-3 s and h* = 3.01e-3 s: one explicit run
    // past 2/ω_max, one between h* and 2/ω_max (both diverged), one stable; two implicit runs.
    let diverged = |dt: f64, t: f64| {
        Status::Diverged(format!(
            "simulation diverged at step 7 (t = {t:.6} s): energy ran away: E = 1.1e0 J \
             against a budget of 1.9e0 J, held as kinetic + spring energy by the cloth (cloth t, \
             integrator symplectic-euler, dt = {dt} s)"
        ))
    };
    let mut stable = cloth_row(
        ClothIntegrator::SymplecticEuler,
        1.5625e-3,
        0.00135,
        Status::Ok,
    );
    stable.frontier = true;
    let rows = vec![
        cloth_row(
            ClothIntegrator::SymplecticEuler,
            6.25e-3,
            f64::NAN,
            diverged(6.25e-3, 0.04375),
        ),
        cloth_row(
            ClothIntegrator::SymplecticEuler,
            3.125e-3,
            f64::NAN,
            diverged(3.125e-3, 0.121875),
        ),
        stable,
        cloth_row(ClothIntegrator::ImplicitEuler, 5e-2, 0.0576, Status::Ok),
        cloth_row(
            ClothIntegrator::ImplicitEuler,
            3.90625e-4,
            0.0103,
            Status::Ok,
        ),
    ];
    let (limit, damped_limit) = (3.69e-3, 3.01e-3);
    let comparison = cloth::compare(&rows, limit);
    let sentence = cloth::sentence(&rows, &comparison, limit, damped_limit, 1.0);
    let orders = ClothIntegrator::ALL
        .map(|i| cloth::fit_order(i, &rows, limit, 0.0))
        .to_vec();
    assert_eq!(
        orders[0],
        ClothOrder {
            integrator: ClothIntegrator::SymplecticEuler,
            slope: None,
            points: 1
        }
    );
    let study = SceneStudy {
        cloth: Some(ClothStudy {
            limit,
            damped_limit,
            limiting_cloth: "t".to_string(),
            ladder: vec![5e-2, 6.25e-3, 3.125e-3, 1.5625e-3, 3.90625e-4],
            reference: "numeric: by hand".to_string(),
            reference_spread: 1.9e-5,
            rows,
            orders,
            comparison,
            sentence: sentence.clone(),
        }),
        sentence,
        ..study(Vec::new(), None)
    };
    insta::assert_snapshot!("study_table_cloth", report::table(&[study]));
}

#[test]
fn a_cloth_order_fit_leaves_out_the_runs_inside_the_floor_band() {
    // A first-order method, error = 2 dt, measured against a reference whose spread is 1e-3 m:
    // from dt = 1.25e-3 s on its errors reach 2.5e-3 m, inside the band 3 × 1e-3 m, and the
    // finer runs' stop falling there. Fitted over every run the slope is flattened; over the
    // three runs above the band it is the method's order, 1, exactly.
    let integrator = ClothIntegrator::ImplicitEuler;
    let mut rows: Vec<ClothRow> = [1e-2, 5e-3, 2.5e-3, 1.25e-3]
        .iter()
        .map(|&dt| cloth_row(integrator, dt, 2.0 * dt, Status::Ok))
        .collect();
    rows.extend(
        [6.25e-4, 3.125e-4]
            .iter()
            .map(|&dt| cloth_row(integrator, dt, 2.5e-3, Status::Ok)),
    );
    let spread = 1e-3;
    let everything = cloth::fit_order(integrator, &rows, 1.0, 0.0);
    let above = cloth::fit_order(integrator, &rows, 1.0, cloth::FLOOR_SPREADS * spread);
    assert_eq!((everything.points, above.points), (6, 3));
    assert!(everything.slope.unwrap() < 0.8, "{everything:?}");
    assert!((above.slope.unwrap() - 1.0).abs() < 1e-12, "{above:?}");
}
