//! The study's cloth case: a converged reference, explicit runs past the limit marked diverged,
//! backward Euler never gaining energy without damping, and the sentence's steps ratio taken
//! from the rows. Untimed (`repeats = 0`): only errors and structure are checked, never times.
//! The fixtures are 5 × 5 sheets over 0.2 s (a fraction of a second in release).

use assert_cmd::Command;
use std::path::Path;
use tumble::physics::cloth::ClothIntegrator;
use tumble::study::analysis::format_number;
use tumble::study::cloth::{self, ClothConfig, ClothStudy, SameError};
use tumble::study::{Status, Timing};

const SHEET: &str = "tests/fixtures/study/small-sheet.toml";
const UNDAMPED: &str = "tests/fixtures/study/small-sheet-undamped.toml";

fn untimed(dts: Option<Vec<f64>>) -> ClothConfig {
    ClothConfig {
        timing: Timing {
            repeats: 0,
            sample_interval: 0.1,
        },
        dts,
        ..ClothConfig::default()
    }
}

fn study(file: &str, dts: Option<Vec<f64>>) -> ClothStudy {
    let lesson = tumble::scene::load(Path::new(file)).expect("fixture loads");
    let duration = lesson.scene.duration.expect("fixture has a duration");
    cloth::study(
        "fixture",
        &lesson.scene,
        duration,
        &untimed(dts),
        &mut |_, _| {},
    )
}

fn errors(study: &ClothStudy, integrator: ClothIntegrator) -> Vec<(f64, f64)> {
    study
        .rows
        .iter()
        .filter(|r| r.integrator == integrator && r.ok())
        .map(|r| (r.dt, r.error))
        .collect()
}

/// Least-squares slope of ln e against ln dt.
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let xs: Vec<f64> = points.iter().map(|p| p.0.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn the_ladder_brackets_the_limit_with_round_halvings() {
    // L = 6.85e-3 s: the top is the smallest 1-2-5 number ≥ 8 L = 0.0548, i.e. 0.1; halvings
    // down to the first dt ≤ L/8 = 8.56e-4: 0.1/2⁷ = 7.8125e-4.
    let ladder = cloth::ladder(6.85e-3);
    let expected: Vec<f64> = (0..8).map(|k| 0.1 / f64::powi(2.0, k)).collect();
    assert_eq!(ladder, expected);
    // The explicit integrator: every dt below L, and the two smallest above it.
    let explicit = cloth::dts_for(ClothIntegrator::SymplecticEuler, &ladder, 6.85e-3, 2);
    assert_eq!(explicit, expected[2..].to_vec());
    let implicit = cloth::dts_for(ClothIntegrator::ImplicitEuler, &ladder, 6.85e-3, 2);
    assert_eq!(implicit, expected);
}

#[test]
fn errors_against_the_reference_halve_with_dt_for_both_first_order_integrators() {
    // Below the explicit limit (h* = 4.47e-3 s for this sheet), both integrators are first
    // order: halving dt halves the error, if the reference has converged.
    let dts = vec![2e-3, 1e-3, 5e-4, 2.5e-4];
    let study = study(SHEET, Some(dts.clone()));
    assert!(dts[0] < study.damped_limit, "all runs below the limit");
    for integrator in ClothIntegrator::ALL {
        let points = errors(&study, integrator);
        assert_eq!(points.len(), dts.len(), "{} diverged", integrator.name());
        let order = slope(&points);
        assert!(
            (0.8..=1.3).contains(&order),
            "{}: order {order:.3} from {points:?}",
            integrator.name()
        );
        let fitted = study
            .orders
            .iter()
            .find(|o| o.integrator == integrator)
            .and_then(|o| o.slope)
            .expect("an order is fitted");
        assert!((fitted - order).abs() < 1e-12, "{fitted} vs {order}");
        // The reference itself: its two runs (h_r = 2.5e-4/8 and half that) differ by the
        // first-order error of the finer one, far below the smallest error measured.
        let smallest = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!(
            study.reference_spread < 0.2 * smallest,
            "reference spread {:e} m against a smallest error of {smallest:e} m",
            study.reference_spread
        );
    }
}

#[test]
fn explicit_runs_past_the_limit_are_marked_diverged_and_named_in_the_sentence() {
    let study = study(UNDAMPED, None);
    // Undamped: h* = 2/ω_max.
    assert_eq!(study.limit, study.damped_limit);
    let past: Vec<_> = study
        .rows
        .iter()
        .filter(|r| r.integrator == ClothIntegrator::SymplecticEuler && r.dt > study.limit)
        .collect();
    assert_eq!(past.len(), 2, "two explicit runs past the limit");
    for r in &past {
        assert!(r.past_limit());
        assert!(
            matches!(&r.status, Status::Diverged(m) if m.contains("cloth sheet, integrator symplectic-euler")),
            "dt = {:e} ({}× the limit): {:?}",
            r.dt,
            r.limit_ratio,
            r.status
        );
        assert!(r.error.is_nan() && r.ns_per_step.is_nan());
        assert!(
            study.sentence.contains(&format!(
                "{} ({}×)",
                tumble::study::analysis::format_dt(r.dt),
                format_number(r.limit_ratio)
            )),
            "{}",
            study.sentence
        );
    }
    assert!(
        study
            .sentence
            .contains("`symplectic-euler` diverged at every dt past it"),
        "{}",
        study.sentence
    );
    // Below the limit it runs (L/8 … just under L).
    let below: Vec<_> = study
        .rows
        .iter()
        .filter(|r| r.integrator == ClothIntegrator::SymplecticEuler && r.dt < study.limit)
        .collect();
    assert!(
        below.len() >= 3 && below.iter().all(|r| r.ok()),
        "{below:?}"
    );
}

#[test]
fn implicit_euler_never_gains_energy_without_damping() {
    // Nothing declared dissipates (no damping, no drag, no contact): backward Euler's energy
    // E − E₀ can only fall, step after step, and what it loses is numerical damping. At most
    // 4 × 2/ω_max: further, the first steps of a flat sheet — slack, so the linearised step
    // sees no transverse stiffness — overshoot its stretch (see tests/cloth.rs), which the
    // study shows in its `E rise` column.
    let study = study(UNDAMPED, None);
    let rows: Vec<_> = study
        .rows
        .iter()
        .filter(|r| r.integrator == ClothIntegrator::ImplicitEuler && r.limit_ratio <= 4.0)
        .collect();
    assert!(rows.len() >= 5, "{rows:?}");
    for r in rows {
        assert!(r.ok(), "{r:?}");
        assert_eq!(r.booked_losses, 0.0, "nothing declared takes energy");
        // E₀ ≈ M g y = 0.1 · 9.81 · 1 ≈ 1 J: a rise of 1e-10 J is round-off.
        assert!(
            r.energy_rise <= 1e-10,
            "dt = {:e}: E rose by {:e} J in one step",
            r.dt,
            r.energy_rise
        );
        assert!(r.numerical_damping > 0.0, "dt = {:e}: {r:?}", r.dt);
    }
}

#[test]
fn the_sentence_ratio_is_the_rows_interpolated_in_log_log() {
    // The default ladder of this sheet (0.1 s halved down to 7.8125e-4 s), two halvings longer
    // so that implicit-euler gets down to the explicit error.
    let ladder: Vec<f64> = (0..10).map(|k| 0.1 / f64::powi(2.0, k)).collect();
    let study = study(SHEET, Some(ladder));
    // Independently: the explicit integrator's largest dt that ran, and its error…
    let explicit = errors(&study, ClothIntegrator::SymplecticEuler);
    let &(h_e, target) = explicit
        .iter()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .expect("an explicit run");
    // …the implicit runs bracketing that error, and the straight line through them in
    // (ln dt, ln e): ln e = ln e₁ + (ln e₂ − ln e₁)(ln dt − ln d₁)/(ln d₂ − ln d₁).
    let mut implicit = errors(&study, ClothIntegrator::ImplicitEuler);
    implicit.sort_by(|a, b| b.0.total_cmp(&a.0));
    let (d1, e1, d2, e2) = implicit
        .windows(2)
        .find(|w| w[0].1 >= target && w[1].1 <= target)
        .map(|w| (w[0].0, w[0].1, w[1].0, w[1].1))
        .expect("implicit-euler reaches the explicit error on this damped sheet");
    let h_i = (d1.ln() + (d2.ln() - d1.ln()) * (target / e1).ln() / (e2 / e1).ln()).exp();
    let expected = h_i / h_e;
    let SameError::Reached {
        ratio,
        explicit_dt,
        implicit_dt,
        ..
    } = study.comparison.same_error
    else {
        panic!("expected a reached comparison: {:?}", study.comparison);
    };
    assert_eq!(explicit_dt, h_e);
    assert!(
        (implicit_dt / h_i - 1.0).abs() < 1e-12,
        "{implicit_dt} vs {h_i}"
    );
    assert!(
        (ratio / expected - 1.0).abs() < 1e-12,
        "{ratio} vs {expected}"
    );
    // On this sheet the implicit step's numerical damping costs more than the explicit
    // limit: the ratio is below 1 and the sentence says so.
    assert!(expected < 1.0);
    let said = format!(
        "`implicit-euler` takes {} times as many steps as `symplectic-euler` (ratio {} < 1)",
        format_number(1.0 / expected),
        format_number(expected)
    );
    assert!(
        study.sentence.contains(&said),
        "{}\nlacks: {said}",
        study.sentence
    );
    assert!(
        study.sentence.starts_with(&format!(
            "Explicit limit 2/ω_max = {} s (with damping, stable below h* = {} s)",
            format_number(study.limit),
            format_number(study.damped_limit)
        )),
        "{}",
        study.sentence
    );
}

#[test]
fn study_of_a_cloth_file_extends_the_csv_and_json_and_draws_its_panel() {
    let dir = std::env::temp_dir().join(format!("tumble-study-cloth-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("plot.svg");
    let run = |format: &str| {
        let output = Command::cargo_bin("tumble")
            .unwrap()
            .args(["study", UNDAMPED, "--format", format, "--svg"])
            .arg(&svg)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        String::from_utf8(output.stdout).unwrap()
    };
    let csv = run("csv");
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    // The bodies' header, unchanged, then the cloth columns, then the contact solvers'.
    assert_eq!(
        header,
        format!(
            "{},case,limit_ratio,drift_j,booked_losses,numerical_damping,energy_rise,solver,\
             substeps,sink,below_floor",
            "scene,integrator,dt,steps,ns_per_step,error,energy_drift,momentum_drift,\
             orthonormality,us_per_simulated_second,omega_error,position_error,penetration,\
             impact_energy,rest_error,frontier,status,reference,angle_error,end_pose_error,\
             contact_error"
        )
    );
    let columns = header.split(',').count();
    let rows: Vec<&str> = lines.collect();
    // 6 explicit (4 below the limit, 2 past it) + 8 implicit runs.
    assert_eq!(rows.len(), 14, "{csv}");
    for row in &rows {
        // Diverged rows quote their message, which has commas: count the unquoted fields.
        let (before, after) = match row.split_once('"') {
            Some((b, rest)) => (b, rest.rsplit_once('"').map_or("", |(_, a)| a)),
            None => (*row, ""),
        };
        let fields = before.split(',').count() + after.split(',').count() - 1;
        assert_eq!(fields, columns, "{row}");
        assert!(row.starts_with("small-sheet-undamped,"), "{row}");
        assert_eq!(
            row.split(',')
                .nth(1)
                .map(|i| ClothIntegrator::from_name(i).is_some()),
            Some(true)
        );
    }
    assert!(rows.iter().all(|r| r.contains(",cloth,")), "{csv}");
    let json: serde_json::Value = serde_json::from_str(&run("json")).unwrap();
    let cloth = &json["scenes"][0]["cloth"];
    assert_eq!(cloth["runs"].as_array().map(Vec::len), Some(14));
    assert_eq!(cloth["limiting_cloth"], "sheet");
    assert_eq!(json["scenes"][0]["sentence"], cloth["sentence"]);
    let table = run("table");
    assert!(table.contains("cloth case"), "{table}");
    assert!(table.contains("DIVERGED at t = "), "{table}");
    assert!(table.contains("(past 2/ω_max)"), "{table}");
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.contains("implicit-euler") && picture.contains("cloth case"));
    // Beside error against cost, error against dt: its axis, the explicit limit, each particle
    // integrator's fitted order beside its line in both charts, the two diverged runs listed in
    // both charts,
    // and one marker per run that did not diverge in each chart (11: implicit-euler at 0.1 s
    // diverges too).
    assert_eq!(
        picture.matches("time step dt (s)").count(),
        1,
        "no dt chart"
    );
    assert!(picture.contains("2/ω_max</text>") || picture.contains("\n2/ω_max\n"));
    for integrator in ClothIntegrator::ALL {
        let beside = format!("{} p", integrator.name());
        assert_eq!(
            picture.lines().filter(|l| l.starts_with(&beside)).count(),
            2,
            "{beside}"
        );
    }
    assert_eq!(picture.matches("diverged: symplectic-euler").count(), 2);
    let markers = picture
        .lines()
        .filter(|l| l.contains("<circle") && !l.contains("stroke=\"#000000\""))
        .count();
    let ok = cloth["runs"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["diverged"] == false)
        .count();
    assert_eq!(
        (ok, markers),
        (11, 2 * ok),
        "one marker per run in each chart"
    );
    std::fs::remove_dir_all(&dir).ok();
}
