//! The snapshot is the only read path (issue #36, item 4): no front end (the session, `diff`,
//! `study`, the terminal app, the text commands) reads the world's bodies, cloths, obstacles
//! or links itself; what they show, compare or measure comes from `physics::snapshot` (the
//! `Snapshot`, its views, and the small typed reads beside it). A source scan, so that the
//! rule cannot regress silently: a new call fails here, naming its file and line.

use std::path::{Path, PathBuf};

/// The front ends' source folders.
const FRONT_ENDS: [&str; 5] = ["src/session", "src/diff", "src/study", "src/tui", "src/cli"];

/// The world's accessors a front end may not call.
const ACCESSORS: [&str; 4] = ["cloths", "obstacles", "bodies", "links"];

/// The control uses left (the session editing its world, not a read for display): file, the
/// line's text, and why.
const CONTROL: [(&str, &str, &str); 1] = [(
    "src/session/mod.rs",
    "let body = &self.world.bodies()[index];",
    "grab: the hand (the mouse's drag spring) is built on the body it holds and set into \
     the world",
)];

/// Every `.name(` or `::name(` call of an accessor in `text`, as (line number, line), comment
/// lines skipped.
fn calls(text: &str) -> Vec<(usize, String)> {
    let mut found = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let hit = ACCESSORS.iter().any(|name| {
            [".", "::"].iter().any(|sep| {
                let call = format!("{sep}{name}");
                code.match_indices(&call)
                    .any(|(at, _)| code[at + call.len()..].trim_start().starts_with('('))
            })
        });
        if hit {
            found.push((n + 1, line.trim().to_string()));
        }
    }
    found
}

/// Every `.rs` file under `dir`.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn the_scan_finds_a_world_read() {
    let text = "let n = world.cloths().len();\n// world.bodies() in a comment\nlet o = self\n    .world\n    .obstacles ()\n    .first();\nlet c = scene.cloths.len();\nWorld::links(&w);";
    let lines: Vec<usize> = calls(text).into_iter().map(|(n, _)| n).collect();
    assert_eq!(lines, vec![1, 5, 8]);
}

#[test]
fn front_ends_read_the_world_only_through_the_snapshot() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in FRONT_ENDS {
        sources(&root.join(dir), &mut files);
    }
    files.sort();
    assert!(
        files.len() > 20,
        "the front ends' sources were not found under {}",
        root.display()
    );
    let mut unexpected = Vec::new();
    let mut control_seen = [0usize; CONTROL.len()];
    for path in &files {
        let relative = path
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(path).unwrap();
        for (line, code) in calls(&text) {
            match CONTROL
                .iter()
                .position(|(file, allowed, _)| relative == *file && code == *allowed)
            {
                Some(k) => control_seen[k] += 1,
                None => unexpected.push(format!("{relative}:{line}: {code}")),
            }
        }
    }
    assert!(
        unexpected.is_empty(),
        "front ends read the world's bodies, cloths, obstacles or links beside the snapshot \
         (read through physics::snapshot instead, or list a control use in CONTROL):\n{}",
        unexpected.join("\n")
    );
    for ((file, allowed, why), seen) in CONTROL.iter().zip(control_seen) {
        assert_eq!(
            seen, 1,
            "the control use `{allowed}` ({why}) is expected once in {file}: update CONTROL"
        );
    }
}

/// The typed reads beside the snapshot give the snapshot's own numbers, bit for bit, between
/// frames and mid-frame: a trampoline on the floor (two bodies, a cloth, the ground).
#[test]
fn the_typed_reads_are_the_snapshots_numbers() {
    use tumble::physics::snapshot::{
        deepest_penetration, particle_positions, vertex_penetration, Methods,
    };
    use tumble::physics::BodyView;
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/35-a-trampoline-on-the-floor.toml");
    let mut world = tumble::scene::load(&path).unwrap().scene.world();
    for step in 0..=120 {
        if step > 0 {
            world.step();
        }
        // Between frames after whole steps, and at every phase of some of them.
        let phases = if step % 40 == 1 { 4 } else { 1 };
        for phase in 0..phases {
            if phase > 0 {
                world.step_phase();
            }
            let s = world.snapshot();
            assert_eq!(BodyView::all(&world), s.bodies, "step {step} phase {phase}");
            for (i, b) in s.bodies.iter().enumerate() {
                assert_eq!(BodyView::of(&world, i), *b);
                assert_eq!(
                    b.angular_velocity_body(),
                    world.snapshot_of(i).angular_velocity_body
                );
                assert_eq!(
                    vertex_penetration(&world, i).to_bits(),
                    deepest_penetration(&s.obstacles, &b.vertices).to_bits()
                );
            }
            let methods = Methods::of(&world);
            assert_eq!(methods.integrator, s.integrator);
            assert_eq!(methods.response, s.contact_model.map(|m| m.response));
            let cloths: Vec<_> = s.cloths.iter().map(|c| c.method).collect();
            assert_eq!(methods.cloths, cloths);
            let particles: Vec<_> = s.cloths.iter().flat_map(|c| c.positions.clone()).collect();
            assert_eq!(particle_positions(&world), particles);
        }
    }
    // The scene is what the test says it is: the cloth has been hit and is moving.
    let s = world.snapshot();
    assert_eq!(
        (s.bodies.len(), s.cloths.len(), s.obstacles.len()),
        (2, 1, 1)
    );
    assert!(s.cloths[0].max_speed > 0.0);
}

/// The snapshot's fixed things (`Snapshot::fixed`): the obstacles first, each with its own
/// outline and type, then each fixed body with its index, its vertices and edges as its
/// outline about its barycenter, and a box the view holds that holds every vertex; a moving
/// body is not among them.
#[test]
fn the_fixed_things_are_the_obstacles_then_the_fixed_bodies() {
    use tumble::physics::Outline;
    let source = r#"
title = "fixed"
summary = "fixed"
[scene]
dt = 0.01
duration = 1.0
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.0, friction = 0.5 }
[[body]]
name = "cube"
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
position = [0.0, 1.0, 0.0]
[[body]]
name = "slab"
shape = "box"
size = [2.0, 0.1, 1.0]
fixed = true
position = [0.0, 0.5, 0.0]
orientation = { axis = [0.0, 0.0, 1.0], degrees = 10.0 }
[[obstacle]]
type = "ground"
height = 0.0
[[obstacle]]
type = "sphere"
center = [2.0, 0.5, 0.0]
radius = 0.5
"#;
    let lesson = tumble::scene::parse(source, Path::new("fixed.toml")).unwrap();
    let mut world = lesson.scene.world();
    world.step();
    let s = world.snapshot();
    let kinds: Vec<_> = s.fixed.iter().map(|f| (f.kind, f.body)).collect();
    assert_eq!(
        kinds,
        [("ground", None), ("sphere", None), ("body", Some(1))]
    );
    for (f, o) in s.fixed.iter().zip(&s.obstacles) {
        assert_eq!(f.outline, o.outline());
    }
    assert_eq!(s.fixed[0].outline, Outline::Level(0.0));
    let slab = &s.bodies[1];
    let Outline::Body {
        corners,
        edges,
        center,
        radius,
        silhouette,
    } = &s.fixed[2].outline
    else {
        panic!("a fixed body's outline is Outline::Body");
    };
    assert_eq!((corners, edges), (&slab.vertices, &slab.edges));
    assert_eq!((corners.len(), edges.len()), (8, 12));
    assert_eq!(
        (*center, *radius, *silhouette),
        (slab.position, slab.radius, None)
    );
    let (low, high) = s.fixed[2].bounds(&s.position);
    for c in corners {
        assert!((c - center).norm() <= radius * (1.0 + 1e-12));
        assert!((0..3).all(|k| low[k] <= c[k] && c[k] <= high[k]));
    }
    // The sphere's box is its centre ± its radius; the ground's is its level where the bodies are.
    let (low, high) = s.fixed[1].bounds(&s.position);
    assert_eq!((low.x, high.y), (1.5, 1.0));
    let (low, high) = s.fixed[0].bounds(&s.position);
    let level = nalgebra::Vector3::new(s.position.x, 0.0, s.position.z);
    assert_eq!((low, high), (level, level));
}
