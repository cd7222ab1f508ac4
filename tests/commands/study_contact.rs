//! The study's contact-solver chart (issue 17, item 4): on the built-in `dropped-box`, `impulse`
//! and `soft-step` at 1, 2, 4 and 8 sub-steps, measured against a converged `impulse`
//! reference. Numbers only, never timings (the study runs untimed).

use nalgebra::Vector3;
use tumble::physics::{Integrator, Response, SoftStep};
use tumble::study::{self, contact, scenes, Config, Timing};

/// The rest sag of a box on a face under `soft-step` (collision/soft_step.rs, "The sag it
/// accepts"): the face's 4 corners are springs of stiffness m ω² each, m = 1/k,
/// k = 1/M + (r×n)·I⁻¹(r×n), at the static frequency 2ω_c. With half-extents (a, b, c), b the
/// half-height and n = y, r×n = (∓c, 0, ±a): k = (1 + 3c²/(b² + c²) + 3a²/(a² + b²))/M, and the
/// load M g shared by the four: s = M g k / (4 (2ω_c)²).
fn box_sag(half: [f64; 3], g: f64, hertz: f64) -> f64 {
    let [a, b, c] = half;
    let mk = 1.0 + 3.0 * c * c / (b * b + c * c) + 3.0 * a * a / (a * a + b * b);
    let omega = 2.0 * std::f64::consts::PI * hertz;
    mk * g / (16.0 * omega * omega)
}

#[test]
fn the_contact_chart_shows_both_responses_against_a_converged_reference() {
    let case = scenes::builtin()
        .into_iter()
        .find(|c| c.name == "dropped-box")
        .unwrap();
    let config = Config {
        integrators: vec![Integrator::Rk4],
        dts: vec![1e-3],
        timing: Timing {
            repeats: 0,
            sample_interval: 0.1,
        },
        target_error: 1e-6,
    };
    let study = study::study_case(&case, &config, &mut |_, _| {});
    let chart = study
        .contact_solvers
        .clone()
        .expect("dropped-box has contact");
    let names: Vec<&str> = chart.rows.iter().map(|r| r.solver.as_str()).collect();
    assert_eq!(
        names,
        [
            "impulse",
            "soft-step×1",
            "soft-step×2",
            "soft-step×4",
            "soft-step×8"
        ]
    );
    assert_eq!((chart.integrator, chart.dt), (Integrator::Rk4, 1e-3));

    // Which face it rests on: the body axis along the vertical at the end (from the `impulse`
    // run of the scene itself).
    let mut world = case.scene.world_with(Integrator::Rk4, 1e-3);
    while world.time() < case.duration - 1e-9 {
        world.step();
    }
    let r = world.state().orientation.matrix();
    let up = (0..3)
        .max_by(|&i, &j| r[(1, i)].abs().total_cmp(&r[(1, j)].abs()))
        .unwrap();
    let size = Vector3::new(0.4, 0.2, 0.3) / 2.0;
    let (b, others): (f64, Vec<f64>) = (
        size[up],
        (0..3).filter(|&i| i != up).map(|i| size[i]).collect(),
    );
    let g = 9.81;
    let sag = box_sag([others[0], b, others[1]], g, SoftStep::DEFAULT.hertz);
    // The two orderings of (a, c) give the same k: the formula is symmetric in them.
    assert!((sag - box_sag([others[1], b, others[0]], g, 60.0)).abs() < 1e-18);

    for row in &chart.rows {
        let run = &row.run;
        assert!(run.ok(), "{}: {:?}", row.solver, run.status);
        // Energy: never more than the documented bound, M|g| times the deepest penetration.
        assert!(
            run.impact_energy <= 1.0 * g * run.penetration + 1e-12,
            "{}: gained {} J, bound {} J",
            row.solver,
            run.impact_energy,
            g * run.penetration
        );
        match row.response {
            // Rigid: rests where the converged reference rests, to micrometres.
            Response::Impulse => assert!(row.sink.abs() < 1e-5, "impulse sink {}", row.sink),
            // Soft: sags by the closed form, whatever the sub-step count.
            Response::SoftStep(p) => {
                assert_eq!(row.substeps, p.substeps);
                assert!(
                    (row.sink - sag).abs() < 0.05 * sag,
                    "{}: sink {} m, closed form {} m",
                    row.solver,
                    row.sink,
                    sag
                );
            }
            // Another charted method (a new one compiles here): the energy bound above.
            _ => {}
        }
    }
    // The frontier: no marked row is beaten on both cost and contact error.
    for a in chart.rows.iter().filter(|r| r.frontier) {
        assert!(!chart.rows.iter().any(|b| {
            b.run.ns_per_step < a.run.ns_per_step && b.run.contact_error < a.run.contact_error
        }));
    }
    assert!(chart.sentence.contains("soft-step×"), "{}", chart.sentence);
    assert_eq!(contact::solvers().len(), 5);

    // The SVG: beside the solvers' error against cost, error against their own step
    // h = dt / sub-steps, with soft-step's fitted order beside its line; one filled marker per
    // solver run in each chart (the integrators' markers are rings, the frontier's black).
    let svg = std::env::temp_dir().join(format!("tumble-contact-{}.svg", std::process::id()));
    tumble::study::plot::svg(std::slice::from_ref(&study), &svg).unwrap();
    let picture = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_file(&svg).ok();
    assert_eq!(
        picture.matches(tumble::study::plot::SOLVER_STEP).count(),
        1,
        "no solver-step chart"
    );
    assert_eq!(
        picture
            .lines()
            .filter(|l| l.starts_with("soft-step p"))
            .count(),
        1,
        "soft-step's order beside its line"
    );
    let filled = picture
        .lines()
        .filter(|l| l.contains("<circle") && !l.contains("fill=\"none\""))
        .count();
    let ok = chart.rows.iter().filter(|r| r.run.ok()).count();
    assert_eq!(
        (ok, filled),
        (5, 2 * ok),
        "one marker per solver run in each chart"
    );
}

#[test]
fn the_csv_and_json_carry_the_contact_solver_rows() {
    let output = assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .args([
            "study",
            "tests/fixtures/study/short-drop.toml",
            "--format",
            "csv",
        ])
        .output()
        .unwrap();
    assert!(output.status.success());
    let csv = String::from_utf8(output.stdout).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.ends_with(",solver,substeps,sink,below_floor"),
        "{header}"
    );
    let columns = header.split(',').count();
    let solver_rows: Vec<&str> = csv
        .lines()
        .filter(|l| l.contains(",contact-solver,"))
        .collect();
    assert_eq!(solver_rows.len(), 5, "{csv}");
    for row in &solver_rows {
        assert_eq!(row.split(',').count(), columns, "{row}");
    }
    let substeps: Vec<&str> = solver_rows
        .iter()
        .map(|r| r.split(',').nth(columns - 3).unwrap())
        .collect();
    assert_eq!(substeps, ["0", "1", "2", "4", "8"]);
    let output = assert_cmd::Command::cargo_bin("tumble")
        .unwrap()
        .args([
            "study",
            "tests/fixtures/study/short-drop.toml",
            "--format",
            "json",
            "--response",
            "soft-step",
        ])
        .output()
        .unwrap();
    assert!(output.status.success());
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let scene = &json["scenes"][0];
    let runs = scene["contact_solvers"]["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 5);
    assert_eq!(runs[0]["solver"], "impulse");
    assert_eq!(runs[4]["substeps"], 8);
    // `diverged` is true or false on every run, never null; the message goes in `divergence`.
    for run in scene["runs"].as_array().unwrap().iter().chain(runs) {
        assert!(run["diverged"].is_boolean(), "{run}");
        assert_eq!(
            run["diverged"].as_bool(),
            Some(!run["divergence"].is_null())
        );
    }
}
