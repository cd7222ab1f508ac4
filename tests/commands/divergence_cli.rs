//! The divergence guard on the command line: a diverging run stops with one line naming the
//! step, the quantity, the integrator and dt, and exit code 3; the rows before it are printed.

use assert_cmd::Command;

/// Runs `tumble run FILE --steps N` from the crate root: (exit code, stdout, stderr).
fn run(file: &str, steps: &str, extra: &[&str]) -> (Option<i32>, String, String) {
    let output = Command::cargo_bin("tumble")
        .expect("the tumble binary")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["run", file, "--steps", steps])
        .args(extra)
        .output()
        .expect("tumble runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn euler_seed_on_a_fast_spin_at_a_large_step_exits_3_naming_step_quantity_integrator_and_dt() {
    // det(𝟙 + dt ω*) = 1 + (dt ω)² = 2 per step at dt = 0.01 s, ω = 100 rad/s: the matrix, and
    // ω = R I⁻¹ Rᵀ L with it, blow up within a handful of steps. At step 5 both rules of the
    // guard are crossed (E = 5397 J > 2 E₀, and |ω|·dt = 22 rad per step); the rotation rule is
    // checked first.
    let (code, stdout, stderr) = run(
        "tests/fixtures/diverging/euler-seed-fast-spin.toml",
        "1000",
        &[],
    );
    assert_eq!(code, Some(3), "stderr: {stderr}");
    assert_eq!(
        stderr,
        "tumble: simulation diverged at step 5 (t = 0.050000 s): rotation no longer resolved: \
         |ω|·dt = 21.9734 rad per step, more than half a turn (π) (integrator euler-seed, \
         dt = 0.01 s)\n"
    );
    // The header and the rows of steps 0 to 4, all finite.
    let rows: Vec<&str> = stdout.lines().collect();
    assert_eq!(rows.len(), 6, "{stdout}");
    assert!(rows[5].starts_with("4,0.04,"), "{}", rows[5]);
    assert!(
        !stdout.contains("NaN") && !stdout.contains("inf"),
        "{stdout}"
    );
}

#[test]
fn the_same_scene_with_splitting_runs_to_the_end() {
    let (code, stdout, stderr) = run(
        "tests/fixtures/diverging/euler-seed-fast-spin.toml",
        "1000",
        &["--integrator", "splitting", "--every", "1000"],
    );
    assert_eq!(code, Some(0), "stderr: {stderr}");
    assert_eq!(stdout.lines().count(), 3, "header, row 0 and row 1000");
}

#[test]
fn an_overflowing_state_is_refused_before_row_0() {
    // ω = 1e160 rad/s: L = I ω is finite but ½ ω·L = 4.8e318 J is not. Row 0 would print an
    // infinite energy, so the file is refused when it loads, naming the key (exit 2), and
    // nothing is printed on stdout.
    let (code, stdout, stderr) = run("tests/fixtures/diverging/overflowing-spin.toml", "10", &[]);
    assert_eq!(code, Some(2), "stderr: {stderr}");
    assert_eq!(stdout, "");
    assert_eq!(
        stderr,
        "tumble: tests/fixtures/diverging/overflowing-spin.toml:8:1: body `body1`: its \
         rotational energy ½ ω·L overflows: `angular_velocity` (and `mass`) (a number beyond \
         ±1.8e308): give smaller values\n"
    );
}
