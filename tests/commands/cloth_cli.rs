//! Cloths on the command line: `run --cloth NAME` rows, `--integrator` replacing every cloth's
//! own, the divergence guard naming a cloth.

use assert_cmd::Command;

/// Runs `tumble ARGS` from the crate root: (exit code, stdout, stderr).
fn tumble(args: &[&str]) -> (Option<i32>, String, String) {
    let output = Command::cargo_bin("tumble")
        .expect("the tumble binary")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("tumble runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

const CUBE: &str = "tests/fixtures/cloth/cube-on-sheet.toml";

#[test]
fn run_cloth_prints_one_row_per_particle_per_kept_step() {
    let (code, stdout, stderr) = tumble(&[
        "run", CUBE, "--steps", "4", "--every", "2", "--cloth", "sheet",
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], "step,t,i,j,x,y,z,vx,vy,vz,energy");
    // Steps 0, 2, 4 × 9 particles.
    assert_eq!(lines.len(), 1 + 3 * 9);
    // Particle (1, 0) at step 0: x = −0.5 + 1·0.5 = 0, z = −0.5; pinned (edges), at rest.
    // energy: the cube's −M g·x = 9.81·0.5 = 4.905 J, the sheet at y = 0 holds none.
    assert_eq!(lines[2], "0,0,1,0,0,0,-0.5,0,0,0,4.905");
    // The centre (1, 1) is free: at step 2 it fell under gravity (v_y < 0).
    let centre: Vec<&str> = lines[1 + 9 + 4].split(',').collect();
    assert_eq!(&centre[..4], ["2", "0.002", "1", "1"]);
    assert!(centre[8].parse::<f64>().unwrap() < 0.0, "{centre:?}");
}

#[test]
fn run_cloth_with_an_unknown_name_is_a_one_line_error() {
    let (code, _, stderr) = tumble(&["run", CUBE, "--steps", "1", "--cloth", "shet"]);
    assert_eq!(code, Some(2));
    assert_eq!(
        stderr,
        format!("tumble: {CUBE}: no cloth named `shet` (did you mean `sheet`?); cloths: sheet\n")
    );
}

#[test]
fn integrator_override_must_fit_every_body_and_cloth() {
    // rk4 is a body integrator, the sheet has none such.
    let (code, _, stderr) = tumble(&["run", CUBE, "--steps", "1", "--integrator", "rk4"]);
    assert_eq!(code, Some(2));
    assert_eq!(
        stderr,
        format!(
            "tumble: {CUBE}: cloth `sheet` has no integrator `rk4`; particle integrators: \
             symplectic-euler, implicit-euler\n"
        )
    );
    // implicit-euler is a particle integrator, the cube has none such.
    let (code, _, stderr) = tumble(&[
        "run",
        CUBE,
        "--steps",
        "1",
        "--integrator",
        "implicit-euler",
    ]);
    assert_eq!(code, Some(2));
    assert!(
        stderr.contains("body `cube` has no integrator `implicit-euler`"),
        "{stderr}"
    );
    // A sheet alone takes either particle integrator.
    let alone = "tests/fixtures/cloth/sheet-alone.toml";
    let (code, _, stderr) = tumble(&[
        "run",
        alone,
        "--steps",
        "50",
        "--integrator",
        "implicit-euler",
    ]);
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn a_sheet_above_its_explicit_limit_exits_3_naming_the_cloth_its_integrator_and_dt() {
    let (code, stdout, stderr) = tumble(&[
        "run",
        "tests/fixtures/cloth/sheet-alone.toml",
        "--steps",
        "1000",
    ]);
    assert_eq!(code, Some(3), "{stderr}");
    assert!(
        stderr.starts_with("tumble: simulation diverged at step "),
        "{stderr}"
    );
    assert!(stderr.contains("energy ran away"), "{stderr}");
    assert!(
        stderr.ends_with("cloth sheet, integrator symplectic-euler, dt = 0.0014352 s)\n"),
        "{stderr}"
    );
    // A sheet alone prints its particles: header, then 121 rows per step.
    assert!(stdout.starts_with("step,t,i,j,x,y,z,vx,vy,vz,energy\n"));
}

#[test]
fn walk_shows_a_cloth_table_with_the_explicit_limit_next_to_dt() {
    let (code, stdout, stderr) = tumble(&["walk", CUBE, "--frames", "1"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.contains("cloth sheet: 9 particles (8 pinned), 12 springs · implicit-euler"),
        "{stdout}"
    );
    // The one free particle (the centre) has two stretch springs of k = 500 N/m along x (and
    // two along z), m = 0.9/9 = 0.1 kg: ω_max² = 2k/m = 10⁴ s⁻², 2/ω_max = 0.02 s; no damping,
    // so h* = 2/ω_max; dt = 0.001 s.
    assert!(
        stdout.contains("  2/ω_max, h*, dt             0.020000    0.020000    0.001000  s"),
        "{stdout}"
    );
    assert!(stdout.contains("  contacts with bodies: 0"), "{stdout}");
}

#[test]
fn shot_draws_a_scene_of_cloths_only() {
    // The app draws cloths: a sheet alone is a picture like any other scene (exit 0, an SVG),
    // its panels saying there is no rigid body.
    let svg = std::env::temp_dir().join(format!("tumble-sheet-alone-{}.svg", std::process::id()));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .args([
            "shot",
            "tests/fixtures/cloth/sheet-alone.toml",
            // The sheet diverges at t = 0.040 s (step 28; `shot` then exits 3): before that.
            "--at",
            "0.02",
            "--svg",
        ])
        .arg(&svg)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg"), "{picture}");
    assert!(picture.contains("no rigid body in this scene"));
    std::fs::remove_file(&svg).unwrap();
}
