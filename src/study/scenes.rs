//! The default study's built-in scenes, as scene files (parsed by the same loader as a user's).
//!
//! | name | what it shows |
//! |---|---|
//! | `tumbling-box` | torque-free box 1.0×0.4×0.1 m, ω_body(0) = (1, 10, 1): the intermediate-axis flip, away from the separatrix |
//! | `near-separatrix` | the same box at ω_body(0) = (0.01, 10, 0.01): the flip period is ill-conditioned, errors are amplified |
//! | `projectile` | a spinning 0.2 m cube thrown under gravity: exact reference for translation and rotation |
//! | `dropped-box` | a tilted box dropped on the ground: contact (penetration, energy gained at impacts, rest) |
//! | `trampoline` | the cloth case: an 8 × 8 sheet held by its edges sagging under gravity, for the particle integrators around their explicit limit |

use super::Case;
use crate::scene;
use std::path::Path;

const TUMBLING_BOX: &str = r#"
title = "Tumbling box"
summary = "Torque-free box 1.0×0.4×0.1 m, 1 kg, ω_body(0) = (1, 10, 1) rad/s"
[scene]
dt = 0.001
duration = 10.0
integrator = "rk4"
[body]
shape = "box"
size = [1.0, 0.4, 0.1]
mass = 1.0
inertia = "solid"
angular_velocity_body = [1.0, 10.0, 1.0]
"#;

const NEAR_SEPARATRIX: &str = r#"
title = "Near the separatrix"
summary = "The same box at ω_body(0) = (0.01, 10, 0.01) rad/s: flips amplify every error"
[scene]
dt = 0.001
duration = 10.0
integrator = "rk4"
[body]
shape = "box"
size = [1.0, 0.4, 0.1]
mass = 1.0
inertia = "solid"
angular_velocity_body = [0.01, 10.0, 0.01]
"#;

const PROJECTILE: &str = r#"
title = "Spinning projectile"
summary = "Cube 0.2 m, 1 kg, x₀ = (0, 1, 0), v₀ = (2, 5, 0) m/s, ω = (0, 0, 3) rad/s, g = −9.81"
[scene]
dt = 0.001
duration = 1.0
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
[body]
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
inertia = "solid"
position = [0.0, 1.0, 0.0]
velocity = [2.0, 5.0, 0.0]
angular_velocity = [0.0, 0.0, 3.0]
"#;

const DROPPED_BOX: &str = r#"
title = "Dropped box"
summary = "Box 0.4×0.2×0.3 m, 1 kg, tilted 30°, dropped from 1 m onto the ground (impulse, e = 0.4, μ = 0.5)"
[scene]
dt = 0.001
duration = 2.0
integrator = "rk4"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.4, friction = 0.5 }
[body]
shape = "box"
size = [0.4, 0.2, 0.3]
mass = 1.0
inertia = "solid"
position = [0.0, 1.0, 0.0]
orientation = { axis = [1.0, 0.0, 1.0], degrees = 30.0 }
angular_velocity = [0.5, 0.0, 1.0]
[[obstacle]]
type = "ground"
height = 0.0
"#;

const TRAMPOLINE: &str = r#"
title = "Trampoline"
summary = "Sheet 0.5 × 0.5 m, 8 × 8 particles, 0.2 kg, stretch 200 N/m, shear 50 N/m, damping 0.1 N·s/m, edges pinned, falling flat into its sag under gravity"
[scene]
dt = 0.001
duration = 1.0
integrator = "symplectic-euler"
gravity = [0.0, -9.81, 0.0]
contact = { response = "impulse", restitution = 0.4, friction = 0.5 }
[[cloth]]
name = "trampoline"
size = [0.5, 0.5]
count = [8, 8]
position = [0.0, 1.0, 0.0]
mass = 0.2
stretch = 200.0
shear = 50.0
damping = 0.1
pinned = "edges"
"#;

/// The built-in scenes, in the order they are studied.
pub fn builtin() -> Vec<Case> {
    [
        ("tumbling-box", TUMBLING_BOX),
        ("near-separatrix", NEAR_SEPARATRIX),
        ("projectile", PROJECTILE),
        ("dropped-box", DROPPED_BOX),
        ("trampoline", TRAMPOLINE),
    ]
    .into_iter()
    .map(|(name, source)| {
        let lesson = scene::parse(source, Path::new(name))
            .unwrap_or_else(|e| panic!("built-in scene {name} is invalid: {e}"));
        Case {
            description: lesson.summary.clone(),
            ..Case::from_lesson(&lesson)
        }
    })
    .collect()
}
