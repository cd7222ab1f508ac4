//! The slider kind, `limits` and `motor`: each broken rule one error at the key at fault
//! (`scene::links`), and `run --joint` appends `limit` and `motor` only for a joint that has them.

use assert_cmd::Command;
use std::path::Path;

/// A one-body scene with this `[[joint]]` body (after `type`).
fn scene(joint: &str) -> String {
    format!(
        "title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n[body]\nname = \"cart\"\nshape = \"box\"\n\
         size = [0.2, 0.1, 0.1]\nmass = 1.0\n\n[[joint]]\nname = \"j\"\nbodies = [\"cart\"]\n\
         anchor = [0.0, 0.0, 0.0]\n{joint}\n"
    )
}

/// The loader's one-line error for this joint, without the file name.
fn error(joint: &str) -> String {
    let text = scene(joint);
    match tumble::scene::parse(&text, Path::new("j.toml")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => {
            let line = e.to_string();
            line.strip_prefix("j.toml:").unwrap_or(&line).to_string()
        }
    }
}

#[test]
fn a_slider_with_limits_and_a_motor_loads() {
    let text = scene(
        "type = \"slider\"\naxis = [0.0, 2.0, 0.0]\nlimits = [-0.5, 0.25]\n\
         motor = { speed = 1.5, max_force = 20.0 }",
    );
    let lesson = tumble::scene::parse(&text, Path::new("j.toml")).unwrap_or_else(|e| panic!("{e}"));
    let j = &lesson.scene.links.joints[0];
    assert_eq!(j.limits, Some([-0.5, 0.25]));
    let motor = j.motor.expect("a motor");
    assert_eq!((motor.speed, motor.max), (1.5, 20.0));
    // A hinge's limits are degrees, held in radians.
    let text = scene("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nlimits = [-90, 45]");
    let lesson = tumble::scene::parse(&text, Path::new("j.toml")).unwrap_or_else(|e| panic!("{e}"));
    let [lo, hi] = lesson.scene.links.joints[0].limits.expect("limits");
    assert!((lo + std::f64::consts::FRAC_PI_2).abs() < 1e-15, "{lo}");
    assert!((hi - std::f64::consts::FRAC_PI_4).abs() < 1e-15, "{hi}");
}

#[test]
fn every_broken_joint_key_rule_is_one_error_at_its_key() {
    for (joint, expected) in [
        ("type = \"slidr\"\naxis = [1.0, 0.0, 0.0]", "15:8: unknown joint type `slidr` (did you mean `slider`?); valid types: ball, hinge, fixed, distance, slider"),
        ("type = \"slider\"", "11:1: a slider joint needs `axis`"),
        ("type = \"slider\"\naxis = [0.0, 0.0, 0.0]", "16:8: slider `axis` has zero length: give a non-zero axis"),
        ("type = \"ball\"\nlimits = [-1.0, 1.0]", "16:10: `limits` does not apply to a ball joint (it is a key of hinge, slider); valid keys of a ball joint: name, type, bodies, anchor"),
        ("type = \"fixed\"\nmotor = { speed = 1.0, max_torque = 1.0 }", "16:9: `motor` does not apply to a fixed joint (it is a key of hinge, slider); valid keys of a fixed joint: name, type, bodies, anchor"),
        ("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nlimits = [10.0, 90.0]", "17:10: hinge `limits` must hold 0 (the t = 0 pose): lo ≤ 0 ≤ hi, found [10, 90]"),
        ("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nlimits = [-200.0, 170.0]", "17:10: hinge `limits` must be less than a full turn apart (hi − lo < 360°), found [-200, 170]"),
        ("type = \"slider\"\naxis = [1.0, 0.0, 0.0]\nlimits = [-1.0]", "17:10: slider `limits` needs two numbers [lo, hi] (m), found 1 number"),
        ("type = \"slider\"\naxis = [1.0, 0.0, 0.0]\nmotor = { speed = 1.0, max_torque = 5.0 }", "17:37: a slider's motor takes `max_force` (N), not `max_torque`"),
        ("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nmotor = { speed = 1.0 }", "17:9: a hinge joint's `motor` needs `max_torque`"),
        ("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nmotor = { max_torque = 1.0 }", "17:9: a hinge joint's `motor` needs `speed`"),
        ("type = \"hinge\"\naxis = [0.0, 0.0, 1.0]\nmotor = { speed = 1.0, max_torque = 0.0 }", "17:37: motor `max_torque` must be > 0, found 0"),
    ] {
        assert_eq!(error(joint), expected, "for\n{joint}");
    }
}

#[test]
fn run_joint_appends_limit_and_motor_only_for_a_joint_that_has_them() {
    let header = |joint: &str| {
        let dir = std::env::temp_dir().join(format!("tumble-joint-keys-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{}.toml", joint.len()));
        std::fs::write(&path, scene(joint)).unwrap();
        let out = Command::cargo_bin("tumble")
            .unwrap()
            .args([
                "run",
                path.to_str().unwrap(),
                "--steps",
                "1",
                "--joint",
                "j",
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8(out.stdout).unwrap();
        text.lines().next().unwrap().to_string()
    };
    let base = "step,t,error,fx,fy,fz,tx,ty,tz";
    assert_eq!(header("type = \"slider\"\naxis = [1.0, 0.0, 0.0]"), base);
    assert_eq!(
        header("type = \"slider\"\naxis = [1.0, 0.0, 0.0]\nlimits = [-1.0, 1.0]"),
        format!("{base},limit")
    );
    assert_eq!(
        header(
            "type = \"hinge\"\naxis = [1.0, 0.0, 0.0]\nmotor = { speed = 1.0, max_torque = 1.0 }"
        ),
        format!("{base},motor")
    );
    assert_eq!(
        header(
            "type = \"hinge\"\naxis = [1.0, 0.0, 0.0]\nlimits = [-10, 10]\n\
             motor = { speed = 1.0, max_torque = 1.0 }"
        ),
        format!("{base},limit,motor")
    );
}
