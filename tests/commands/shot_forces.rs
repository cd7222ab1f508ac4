//! `tumble shot --forces` and `tumble record --forces`: the force arrows' scale and legend.

fn run(args: &[&str], out: &std::path::Path) -> String {
    let done = std::process::Command::new(env!("CARGO_BIN_EXE_tumble"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .arg(out)
        .output()
        .unwrap();
    assert_eq!(
        done.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&done.stderr)
    );
    let text = std::fs::read_to_string(out).unwrap();
    std::fs::remove_file(out).unwrap();
    text
}

#[test]
fn shot_and_record_draw_the_forces_when_asked() {
    // tui-spring at t = 0: the spring's 50 N is the largest force; the scale bar is 20 N.
    let dir = std::env::temp_dir();
    let pid = std::process::id();
    let spring = "tests/fixtures/tui-spring.toml";
    let svg = dir.join(format!("tumble-forces-{pid}.svg"));
    let with = run(&["shot", spring, "--at", "0", "--forces", "--svg"], &svg);
    assert!(
        with.contains("┤ 20 N") && with.contains(" forces "),
        "{with}"
    );
    let without = run(&["shot", spring, "--at", "0", "--svg"], &svg);
    assert!(!without.contains(" N "), "no force scale without --forces");
    let cast = dir.join(format!("tumble-forces-{pid}.cast"));
    let recorded = run(
        &["record", spring, "--duration", "0.01", "--forces", "--out"],
        &cast,
    );
    assert!(recorded.contains("20 N"));
}
