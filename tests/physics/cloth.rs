//! Mass–spring sheets against independent truth: a static equilibrium solved here by Newton's
//! method, the explicit stability limit crossed both ways, backward Euler's energy, momentum
//! conservation, pinned particles, losses and contacts.
//!
//! Everything runs in release in well under a second per test (CI budget).

use nalgebra::{DMatrix, DVector, Vector3};
use tumble::physics::cloth::{Cloth, ClothIntegrator, ClothLoads, ClothSpec, Pinning};
use tumble::physics::collision::obstacle::{Ground, Sphere};
use tumble::physics::collision::StepContext;
use tumble::physics::Obstacle;

const G: Vector3<f64> = Vector3::new(0.0, -9.81, 0.0);

fn gravity() -> ClothLoads {
    ClothLoads {
        gravity: Some(G),
        drag: None,
    }
}

// ---------------------------------------------------------------------------------------------
// Placement
// ---------------------------------------------------------------------------------------------

#[test]
fn particles_sit_where_the_design_says_and_share_the_mass() {
    let mut spec = ClothSpec::new([2.0, 1.0], [5, 3], 3.0, 100.0);
    spec.position = Vector3::new(1.0, 2.0, -1.0);
    spec.shear = 10.0;
    spec.bend = 1.0;
    let cloth = Cloth::new(&spec).unwrap();
    // x(i, j) = position + (−1 + i·0.5, 0, −0.5 + j·0.5); particle (3, 2) has index 2·5 + 3:
    // (1, 2, −1) + (0.5, 0, 0.5) = (1.5, 2, −0.5).
    assert_eq!(cloth.positions[13], Vector3::new(1.5, 2.0, -0.5));
    assert_eq!(cloth.grid(13), (3, 2));
    assert!(cloth.masses.iter().all(|&m| m == 3.0 / 15.0));
    // Springs: stretch 4·3 + 5·2 = 22; shear 2·(4·2) = 16; bend 3·3 + 5·1 = 14.
    assert_eq!(cloth.springs.len(), 22 + 16 + 14);
    let shear = cloth.springs.iter().find(|s| s.stiffness == 10.0).unwrap();
    assert!((shear.rest_length - (0.5f64 * 0.5 + 0.5 * 0.5).sqrt()).abs() < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Static sag against Newton's method
// ---------------------------------------------------------------------------------------------

/// The test's own model of the sheet: grid positions and springs (i, j, k, ℓ₀) built from the
/// design's placement rule, independently of `Cloth::new`.
struct Model {
    rest: Vec<Vector3<f64>>,
    springs: Vec<(usize, usize, f64, f64)>,
    pinned: Vec<bool>,
    mass: f64,
}

fn model(n: usize, size: f64, mass: f64, stretch: f64, shear: f64) -> Model {
    let at = |i: usize, j: usize| {
        let h = size / (n - 1) as f64;
        Vector3::new(-size / 2.0 + i as f64 * h, 1.0, -size / 2.0 + j as f64 * h)
    };
    let id = |i: usize, j: usize| j * n + i;
    let mut rest = Vec::new();
    let mut pinned = Vec::new();
    for j in 0..n {
        for i in 0..n {
            rest.push(at(i, j));
            pinned.push(i == 0 || j == 0 || i == n - 1 || j == n - 1);
        }
    }
    let mut springs = Vec::new();
    let mut spring = |a: usize, b: usize, k: f64| {
        let l0 = (rest[b] - rest[a]).norm();
        springs.push((a, b, k, l0));
    };
    for j in 0..n {
        for i in 0..n {
            if i + 1 < n {
                spring(id(i, j), id(i + 1, j), stretch);
            }
            if j + 1 < n {
                spring(id(i, j), id(i, j + 1), stretch);
            }
            if i + 1 < n && j + 1 < n {
                spring(id(i, j), id(i + 1, j + 1), shear);
                spring(id(i + 1, j), id(i, j + 1), shear);
            }
        }
    }
    Model {
        rest,
        springs,
        pinned,
        mass: mass / (n * n) as f64,
    }
}

/// Static equilibrium Σ springs + m g = 0 of the free particles by Newton's method with the
/// exact (unclamped) spring Jacobian and a backtracking line search on |F|.
fn newton_equilibrium(model: &Model, sag_guess: f64) -> Vec<Vector3<f64>> {
    let n = model.rest.len();
    let free: Vec<usize> = (0..n).filter(|&p| !model.pinned[p]).collect();
    let mut slot = vec![usize::MAX; n];
    for (k, &p) in free.iter().enumerate() {
        slot[p] = k;
    }
    let residual = |x: &[Vector3<f64>]| {
        let mut f = vec![G * model.mass; n];
        for &(a, b, k, l0) in &model.springs {
            let d = x[b] - x[a];
            let l = d.norm();
            let force = d * (k * (l - l0) / l);
            f[a] += force;
            f[b] -= force;
        }
        DVector::from_iterator(
            3 * free.len(),
            free.iter()
                .flat_map(|&p| f[p].iter().copied().collect::<Vec<_>>()),
        )
    };
    // Start from a dip (a flat sheet has no transverse stiffness: a singular Jacobian).
    let mut x: Vec<Vector3<f64>> = model
        .rest
        .iter()
        .enumerate()
        .map(|(p, r)| {
            if model.pinned[p] {
                *r
            } else {
                let bump = (1.0 - 4.0 * r.x * r.x) * (1.0 - 4.0 * r.z * r.z);
                r - Vector3::y() * sag_guess * bump
            }
        })
        .collect();
    for _ in 0..100 {
        let f = residual(&x);
        if f.norm() < 1e-11 {
            return x;
        }
        let mut jac = DMatrix::<f64>::zeros(3 * free.len(), 3 * free.len());
        for &(a, b, k, l0) in &model.springs {
            let d = x[b] - x[a];
            let l = d.norm();
            let u = d / l;
            let block = (u * u.transpose()) * k
                + (nalgebra::Matrix3::identity() - u * u.transpose()) * (k * (1.0 - l0 / l));
            // ∂f_a/∂x_b = block, ∂f_a/∂x_a = −block, and the opposite for f_b.
            for (row, sign_row) in [(a, 1.0), (b, -1.0)] {
                for (col, sign_col) in [(a, -1.0), (b, 1.0)] {
                    if slot[row] == usize::MAX || slot[col] == usize::MAX {
                        continue;
                    }
                    for r in 0..3 {
                        for c in 0..3 {
                            jac[(3 * slot[row] + r, 3 * slot[col] + c)] +=
                                sign_row * sign_col * block[(r, c)];
                        }
                    }
                }
            }
        }
        let step = jac.lu().solve(&(-&f)).expect("non-singular Jacobian");
        let mut t = 1.0;
        loop {
            let trial: Vec<Vector3<f64>> = x
                .iter()
                .enumerate()
                .map(|(p, xp)| {
                    if slot[p] == usize::MAX {
                        *xp
                    } else {
                        xp + Vector3::new(
                            step[3 * slot[p]],
                            step[3 * slot[p] + 1],
                            step[3 * slot[p] + 2],
                        ) * t
                    }
                })
                .collect();
            if residual(&trial).norm() < f.norm() || t < 1e-6 {
                x = trial;
                break;
            }
            t *= 0.5;
        }
    }
    panic!("Newton did not converge");
}

#[test]
fn a_sheet_held_on_its_edges_sags_to_the_newton_equilibrium() {
    // 11 × 11 sheet, 1 m × 1 m, 0.5 kg, stretch 200 N/m, shear 50 N/m, edges pinned, at y = 1.
    let truth = newton_equilibrium(&model(11, 1.0, 0.5, 200.0, 50.0), 0.05);
    let mut spec = ClothSpec::new([1.0, 1.0], [11, 11], 0.5, 200.0);
    spec.position = Vector3::new(0.0, 1.0, 0.0);
    spec.shear = 50.0;
    spec.damping = 0.5;
    spec.pinned = Pinning::Edges;
    spec.integrator = ClothIntegrator::ImplicitEuler;
    let mut cloth = Cloth::new(&spec).unwrap();
    cloth.solver.tolerance = 1e-10;
    let loads = gravity();
    let mut steps = 0;
    while steps < 4000 && (steps < 10 || cloth.max_speed() > 1e-12) {
        cloth.step(&loads, 0.01);
        steps += 1;
    }
    let error = cloth
        .positions
        .iter()
        .zip(&truth)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    let sag = 1.0 - truth.iter().map(|x| x.y).fold(f64::INFINITY, f64::min);
    eprintln!("sag {sag:.6} m, error {error:.3e} m after {steps} steps");
    // The centre sags by ~ cm; the damped implicit run must come to rest on the same shape.
    assert!(sag > 0.01, "sag {sag}");
    assert!(
        error < 1e-9,
        "max distance to the Newton equilibrium {error:e} m (sag {sag} m)"
    );
}

// ---------------------------------------------------------------------------------------------
// The explicit limit, both sides
// ---------------------------------------------------------------------------------------------

/// A 15 × 15 drum (edges pinned, stretch 2000, shear 500, 1 kg), struck: every free particle
/// starts at 1 cm/s upwards, which excites every mode (the jump at the pinned border).
fn struck_drum(integrator: ClothIntegrator, damping: f64) -> Cloth {
    let mut spec = ClothSpec::new([1.0, 1.0], [15, 15], 1.0, 2000.0);
    spec.shear = 500.0;
    spec.damping = damping;
    spec.pinned = Pinning::Edges;
    spec.velocity = Vector3::new(0.0, 0.01, 0.0);
    spec.integrator = integrator;
    Cloth::new(&spec).unwrap()
}

/// The largest total energy over `steps` steps of `dt` without gravity (∞ once non-finite).
fn peak_energy(cloth: &mut Cloth, dt: f64, steps: usize) -> f64 {
    let loads = ClothLoads::default();
    let mut peak: f64 = 0.0;
    for _ in 0..steps {
        cloth.step(&loads, dt);
        let e = cloth.energy(&loads).total();
        if !e.is_finite() {
            return f64::INFINITY;
        }
        peak = peak.max(e);
    }
    peak
}

#[test]
fn symplectic_euler_is_stable_just_below_the_explicit_limit_and_explodes_just_above() {
    let probe = struck_drum(ClothIntegrator::SymplecticEuler, 0.0);
    let limit = probe.explicit_limit(&ClothLoads::default());
    let e0 = probe.energy(&ClothLoads::default()).total();
    // Rule of thumb (stretch + shear, here shear = k/4): between 0.71 and 1.0 √(m/k).
    let m = 1.0 / 225.0;
    let scale = (m / 2000.0f64).sqrt();
    eprintln!(
        "drum: 2/ω_max = {:.4e} s = {:.3} √(m/k) ({} power iterations)",
        limit.dt(),
        limit.dt() / scale,
        limit.iterations
    );
    assert!(limit.dt() > 0.71 * scale && limit.dt() < 1.0 * scale);

    // 0.9×: bounded over 5000 steps (symplectic: the energy oscillates near E₀).
    let below = peak_energy(
        &mut struck_drum(ClothIntegrator::SymplecticEuler, 0.0),
        0.9 * limit.dt(),
        5000,
    );
    assert!(
        below < 1.5 * e0,
        "0.9× the limit: peak energy {below:e} J vs E₀ = {e0:e} J"
    );

    // 1.1×: past any bound within 300 steps.
    let above = peak_energy(
        &mut struck_drum(ClothIntegrator::SymplecticEuler, 0.0),
        1.1 * limit.dt(),
        300,
    );
    assert!(
        above > 1e6 * e0,
        "1.1× the limit: peak energy only {above:e} J vs E₀ = {e0:e} J"
    );
    eprintln!(
        "drum: peak energy / E₀ at 0.9×: {:.4}, at 1.1×: {above:.3e} / {e0:.3e}",
        below / e0
    );
}

#[test]
fn with_damping_the_combined_limit_holds_on_both_sides() {
    // Damping c on every spring adds γ: h* = 4/(γ + √(γ² + 4ω²)) < 2/ω_max.
    let probe = struck_drum(ClothIntegrator::SymplecticEuler, 0.5);
    let limit = probe.explicit_limit(&ClothLoads::default());
    let e0 = probe.energy(&ClothLoads::default()).total();
    assert!(limit.dt() < limit.stiffness_limit());
    eprintln!(
        "damped drum: 2/ω = {:.4e} s, 2/γ = {:.4e} s, combined {:.4e} s",
        limit.stiffness_limit(),
        limit.damping_limit(),
        limit.dt()
    );
    let below = peak_energy(
        &mut struck_drum(ClothIntegrator::SymplecticEuler, 0.5),
        0.9 * limit.dt(),
        3000,
    );
    assert!(below <= 1.01 * e0, "0.9×: peak {below:e} vs E₀ {e0:e}");
    let above = peak_energy(
        &mut struck_drum(ClothIntegrator::SymplecticEuler, 0.5),
        1.1 * limit.stiffness_limit(),
        300,
    );
    assert!(
        above > 1e6 * e0,
        "1.1× 2/ω_max: peak {above:e} vs E₀ {e0:e}"
    );
}

#[test]
fn implicit_euler_runs_at_ten_times_the_limit_and_its_energy_never_rises_without_damping() {
    // A drum under tension, as a trampoline is: the struck drum stretched by 5 % about its
    // centre (pinned rim included), so its springs resist transverse motion from the start.
    // (Flat and slack, a sheet has no transverse stiffness at all: the linearised step then
    // sees none, and the stretch the first steps cause raises the energy by O(h²).)
    let mut cloth = struck_drum(ClothIntegrator::ImplicitEuler, 0.0);
    cloth.positions.iter_mut().for_each(|x| *x *= 1.05);
    cloth.solver.tolerance = 1e-10;
    let loads = ClothLoads::default();
    let dt = 10.0 * cloth.explicit_limit(&loads).dt();
    // The stretched drum at rest is in equilibrium (every inner particle is pulled equally
    // both ways): its spring energy U_static is not part of the vibration.
    let at_rest = cloth.spring_energy();
    let mut previous = cloth.energy(&loads).total() - at_rest;
    let e0 = previous;
    for step in 0..1000 {
        cloth.step(&loads, dt);
        let e = cloth.energy(&loads).total() - at_rest;
        // (to the round-off of the whole energy, U_static included)
        assert!(
            e <= previous + 1e-13 * at_rest,
            "step {step}: vibration energy rose from {previous:e} to {e:e} J"
        );
        previous = e;
    }
    // Numerical damping: the vibration lost energy, though nothing declared dissipates.
    eprintln!(
        "implicit at 10× the limit: E/E₀ after 1000 steps {:.4}",
        previous / e0
    );
    assert!(previous < 0.5 * e0);
    assert_eq!(cloth.losses.total(), 0.0, "nothing declared dissipates");
}

// ---------------------------------------------------------------------------------------------
// Momentum
// ---------------------------------------------------------------------------------------------

/// A free 9 × 7 sheet (stretch, shear, bend, damping) at rest in shape but with a swirl and a
/// wave in its velocities, and a drift of (0.3, −0.2, 0.1) m/s.
fn free_sheet(integrator: ClothIntegrator) -> Cloth {
    let mut spec = ClothSpec::new([0.8, 0.6], [9, 7], 0.7, 800.0);
    spec.shear = 200.0;
    spec.bend = 50.0;
    spec.damping = 0.2;
    spec.integrator = integrator;
    let mut cloth = Cloth::new(&spec).unwrap();
    for p in 0..cloth.len() {
        let x = cloth.positions[p];
        cloth.velocities[p] = Vector3::new(0.3, -0.2, 0.1)
            + Vector3::new(0.0, 2.0, 0.0).cross(&x)
            + Vector3::new(0.0, (7.0 * x.x).sin() * (5.0 * x.z).cos(), 0.0);
    }
    cloth
}

#[test]
fn a_free_sheet_in_zero_gravity_keeps_its_momentum() {
    for integrator in ClothIntegrator::ALL {
        let mut cloth = free_sheet(integrator);
        let loads = ClothLoads::default();
        let (p0, l0) = (cloth.linear_momentum(), cloth.angular_momentum());
        let dt = 0.5 * cloth.explicit_limit(&loads).dt();
        for _ in 0..2000 {
            cloth.step(&loads, dt);
        }
        let dp = (cloth.linear_momentum() - p0).norm() / p0.norm();
        let dl = (cloth.angular_momentum() - l0).norm() / l0.norm();
        eprintln!(
            "{}: relative drift of P {dp:.2e}, of L {dl:.2e}",
            integrator.name()
        );
        assert!(
            dp < 1e-13,
            "{}: linear momentum drifted by {dp:e}",
            integrator.name()
        );
        if integrator == ClothIntegrator::SymplecticEuler {
            // Central forces at x₀ and x₁ = x₀ + h v₁: L₁ = Σ x₀ × m v₁ = L₀ exactly.
            assert!(dl < 1e-13, "angular momentum drifted by {dl:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Pinned particles, losses
// ---------------------------------------------------------------------------------------------

#[test]
fn pinned_particles_never_move() {
    for integrator in ClothIntegrator::ALL {
        let mut spec = ClothSpec::new([1.0, 1.0], [7, 7], 0.4, 500.0);
        spec.pinned = Pinning::List(vec![[0, 0], [6, 0], [3, 3]]);
        spec.velocity = Vector3::new(1.0, 2.0, 0.0);
        spec.integrator = integrator;
        let mut cloth = Cloth::new(&spec).unwrap();
        let held: Vec<usize> = [(0, 0), (6, 0), (3, 3)]
            .map(|(i, j)| cloth.index(i, j))
            .to_vec();
        let start: Vec<Vector3<f64>> = held.iter().map(|&p| cloth.positions[p]).collect();
        for _ in 0..500 {
            cloth.step(&gravity(), 1e-3);
        }
        assert!(cloth.apply_impulse(held[0], &Vector3::new(5.0, 5.0, 5.0)) == 0.0);
        assert_eq!(cloth.inv_mass(held[0]), 0.0);
        for (k, &p) in held.iter().enumerate() {
            assert_eq!(cloth.positions[p], start[k], "{}", integrator.name());
            assert_eq!(cloth.velocities[p], Vector3::zeros());
        }
    }
}

#[test]
fn damping_and_drag_are_losses_not_drift() {
    // At a twentieth of the explicit limit, E + losses stays at E₀ to the integrator's error
    // (implicit: plus its numerical damping), while the losses are a large part of T₀.
    for integrator in ClothIntegrator::ALL {
        let mut cloth = struck_drum(integrator, 0.3);
        cloth.velocities.iter_mut().for_each(|v| *v *= 100.0);
        let loads = ClothLoads {
            gravity: Some(G),
            drag: Some(0.5),
        };
        let e0 = cloth.energy(&loads).total();
        let dt = 0.05 * cloth.explicit_limit(&loads).dt();
        for _ in 0..4000 {
            cloth.step(&loads, dt);
        }
        let e = cloth.energy(&loads).total();
        let losses = cloth.losses;
        let kinetic0 = 0.5 * 1.0 * (13.0 * 13.0 / 225.0) * 1.0; // ½ Σ m v², v = 1 m/s on 169 of 225
        let drift = (e + losses.total() - e0).abs();
        eprintln!(
            "{}: losses damping {:.4e} drag {:.4e} J, drift {drift:.3e} J",
            integrator.name(),
            losses.damping,
            losses.drag
        );
        assert!(losses.damping > 0.0 && losses.drag > 0.0 && losses.total() > 0.1 * kinetic0);
        let bound = if integrator == ClothIntegrator::SymplecticEuler {
            0.01
        } else {
            0.2
        };
        assert!(
            drift < bound * losses.total(),
            "{}: drift {drift:e} J vs losses {:e} J",
            integrator.name(),
            losses.total()
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Contacts with obstacles
// ---------------------------------------------------------------------------------------------

#[test]
fn a_cloth_dropped_on_a_sphere_drapes_with_no_particle_inside() {
    for integrator in ClothIntegrator::ALL {
        let mut spec = ClothSpec::new([1.6, 1.6], [17, 17], 0.5, 400.0);
        spec.shear = 100.0;
        spec.bend = 5.0;
        spec.damping = 0.05;
        spec.position = Vector3::new(0.05, 1.3, 0.02);
        spec.integrator = integrator;
        let mut cloth = Cloth::new(&spec).unwrap();
        let obstacles = [
            Obstacle::Ground(Ground { height: 0.0 }),
            Obstacle::Sphere(Sphere {
                center: Vector3::new(0.0, 0.5, 0.0),
                radius: 0.5,
            }),
        ];
        let loads = gravity();
        let dt = match integrator {
            ClothIntegrator::SymplecticEuler => 0.5 * cloth.explicit_limit(&loads).dt(),
            ClothIntegrator::ImplicitEuler => 2e-3,
        };
        let mut contacts = Vec::new();
        let mut taken = 0.0;
        let steps = (2.0 / dt) as usize;
        let context = StepContext::new(dt, loads.gravity, None).with_contact(0.0, 0.3);
        for _ in 0..steps {
            let (_, report) =
                cloth.step_with_obstacles(&loads, &context, &obstacles, &mut contacts);
            taken += report.energy_taken;
            for o in &obstacles {
                for x in &cloth.positions {
                    assert!(
                        o.depth(x) < 1e-12,
                        "{}: a particle inside {o:?}",
                        integrator.name()
                    );
                }
            }
        }
        // Draped: the centre rests on top of the sphere (y = 1), the rim hangs well below it
        // (flat, it would be at 1; it swings, so the bound is loose).
        let centre = cloth.positions[cloth.index(8, 8)];
        let rim = cloth.positions[cloth.index(0, 8)];
        eprintln!(
            "{}: centre {centre:?}, rim {rim:?}, contact losses {taken:.4} J",
            integrator.name()
        );
        assert!((centre.y - 1.0).abs() < 0.02, "centre at {centre:?}");
        assert!(rim.y < 0.9, "rim at {rim:?}");
        assert!(taken > 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// Scene files
// ---------------------------------------------------------------------------------------------

#[test]
fn a_cloth_table_becomes_its_spec() {
    let source = r#"
title = "Trampoline"
[scene]
dt = 0.001
integrator = "symplectic-euler"
contact = { response = "impulse", restitution = 0.4, friction = 0.5 }
[body]
shape = "box"
size = [0.2, 0.2, 0.2]
mass = 1.0
[[cloth]]
name = "trampoline"
size = [2.0, 1.5]
count = [21, 16]
position = [0.0, 1.0, 0.0]
mass = 2.0
stretch = 5000.0
shear = 1000.0
damping = 0.5
pinned = "edges"
velocity = [0.0, 0.5, 0.0]
integrator = "implicit-euler"
[[cloth]]
size = [1.0, 1.0]
count = [3, 2]
mass = 0.1
stretch = 10.0
pinned = [[0, 0], [2, 1]]
"#;
    let lesson = tumble::scene::parse(source, std::path::Path::new("t.toml")).unwrap();
    let cloths = &lesson.scene.cloths;
    assert_eq!(cloths.len(), 2);
    let a = &cloths[0];
    assert_eq!(
        (
            a.name.as_str(),
            a.size,
            a.count,
            a.mass,
            a.stretch,
            a.shear,
            a.bend,
            a.damping
        ),
        (
            "trampoline",
            [2.0, 1.5],
            [21, 16],
            2.0,
            5000.0,
            1000.0,
            0.0,
            0.5
        )
    );
    assert_eq!(a.pinned, Pinning::Edges);
    assert_eq!(a.position, Vector3::new(0.0, 1.0, 0.0));
    assert_eq!(a.velocity, Vector3::new(0.0, 0.5, 0.0));
    assert_eq!(a.integrator, ClothIntegrator::ImplicitEuler);
    // The second: default name, the scene's integrator, a list of pinned particles.
    let b = &cloths[1];
    assert_eq!(b.name, "cloth2");
    assert_eq!(b.integrator, ClothIntegrator::SymplecticEuler);
    assert_eq!(b.pinned, Pinning::List(vec![[0, 0], [2, 1]]));
    assert!(Cloth::new(b).is_ok());
}

// ---------------------------------------------------------------------------------------------
// Ropes: count = [n, 1] and [1, n]
// ---------------------------------------------------------------------------------------------

/// A horizontal rope of `n` particles along x (or z when `along_z`), 1 m, 0.2 kg, k = 500 N/m,
/// pinned at its first particle, at rest at y = 1.
fn rope(n: usize, along_z: bool, integrator: ClothIntegrator) -> Cloth {
    let (size, count) = if along_z {
        ([0.0, 1.0], [1, n])
    } else {
        ([1.0, 0.0], [n, 1])
    };
    let mut spec = ClothSpec::new(size, count, 0.2, 500.0);
    spec.shear = 300.0; // a line has no cells: no shear spring is built
    spec.pinned = Pinning::List(vec![[0, 0]]);
    spec.position = Vector3::new(0.0, 1.0, 0.0);
    spec.integrator = integrator;
    Cloth::new(&spec).unwrap()
}

#[test]
fn a_rope_is_one_line_of_particles_with_stretch_and_bend_springs() {
    for along_z in [false, true] {
        let mut spec = ClothSpec::new(
            if along_z { [0.0, 1.0] } else { [1.0, 0.0] },
            if along_z { [1, 11] } else { [11, 1] },
            0.2,
            500.0,
        );
        spec.shear = 300.0;
        spec.bend = 50.0;
        let cloth = Cloth::new(&spec).unwrap();
        // 11 particles 0.1 m apart on the line through the centre; 10 stretch + 9 bend
        // springs, no shear (no cells).
        assert_eq!(cloth.len(), 11);
        assert_eq!(cloth.springs.len(), 10 + 9);
        for (k, x) in cloth.positions.iter().enumerate() {
            let along = -0.5 + 0.1 * k as f64;
            let expected = if along_z {
                Vector3::new(0.0, 0.0, along)
            } else {
                Vector3::new(along, 0.0, 0.0)
            };
            assert!((x - expected).norm() < 1e-15, "particle {k} at {x:?}");
        }
    }
}

#[test]
fn a_ropes_explicit_limit_is_the_chains_formula() {
    // Fixed–free chain of N = n − 1 free masses m (the rope at rest is straight, so only the
    // longitudinal stiffness k d̂d̂ᵀ is there): M⁻¹K = (k/m)·tridiag(−1, 2, −1) with 1 in its
    // last diagonal entry; its eigenvalues ω_j² = (4k/m) sin²((2j − 1)π/(2(2N + 1))), so
    // ω_max = 2√(k/m) sin((2N − 1)π/(2(2N + 1))) → 2√(k/m) as N grows.
    let (k, mass) = (500.0f64, 0.2);
    for n in [5, 20, 60] {
        for along_z in [false, true] {
            let cloth = rope(n, along_z, ClothIntegrator::SymplecticEuler);
            let m = mass / n as f64;
            let big_n = (n - 1) as f64;
            let chain = 2.0
                * (k / m).sqrt()
                * ((2.0 * big_n - 1.0) * std::f64::consts::PI / (2.0 * (2.0 * big_n + 1.0))).sin();
            let limit = cloth.explicit_limit(&gravity());
            let error = (limit.omega_max - chain).abs() / chain;
            eprintln!(
                "rope n = {n}: ω_max = {:.6} rad/s, chain formula {chain:.6}, 2√(k/m) = {:.6} \
                 (relative error {error:.1e})",
                limit.omega_max,
                2.0 * (k / m).sqrt()
            );
            assert!(
                error < 1e-6,
                "n = {n}: ω_max {} vs {chain}",
                limit.omega_max
            );
        }
    }
    // The limit itself approaches 2√(k/m): the sine is cos(π/(2N + 1)), 1 − π²/(2(2N + 1)²):
    // at N = 59, 1 − 3.48e-4.
    let big_n = 59.0;
    let s = ((2.0 * big_n - 1.0) * std::f64::consts::PI / (2.0 * (2.0 * big_n + 1.0))).sin();
    let expected = std::f64::consts::PI.powi(2) / (2.0 * (2.0 * big_n + 1.0f64).powi(2));
    assert!(((1.0 - s) - expected).abs() < 1e-7 && 1.0 - s < 3.5e-4);
}

/// The largest |E − E₀| over `steps` of `dt` under gravity (∞ once non-finite).
fn rope_energy_excursion(cloth: &mut Cloth, dt: f64, steps: usize) -> f64 {
    let loads = gravity();
    let e0 = cloth.energy(&loads).total();
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        cloth.step(&loads, dt);
        let e = cloth.energy(&loads).total();
        if !e.is_finite() {
            return f64::INFINITY;
        }
        worst = worst.max((e - e0).abs());
    }
    worst
}

#[test]
fn a_rope_pinned_at_one_end_swings_and_symplectic_euler_keeps_its_energy_below_the_limit() {
    let n = 20;
    let probe = rope(n, false, ClothIntegrator::SymplecticEuler);
    let h = probe.explicit_limit(&gravity()).dt();
    // The scale of the swing's energy: the rope's centre falls 0.5 m, m g ℓ/2 ≈ 0.98 J.
    let scale = 0.2 * 9.81 * 0.5;
    let seconds = 1.5;
    let steps = (seconds / (0.9 * h)) as usize;
    let mut swinging = rope(n, false, ClothIntegrator::SymplecticEuler);
    let below = rope_energy_excursion(&mut swinging, 0.9 * h, steps);
    // It swings: the free end has fallen well below the pin and moved towards it.
    let end = swinging.positions[n - 1];
    eprintln!(
        "rope: h* = {h:.3e} s; at 0.9 h* over {seconds} s max |E − E₀| = {below:.3e} J \
         ({:.2} % of m g ℓ/2); free end at {end:?}",
        100.0 * below / scale
    );
    assert!(
        end.y < 0.6 && end.x < 0.4,
        "the rope did not swing: end at {end:?}"
    );
    // Symplectic below the limit: the energy error stays bounded, a few % of the swing's.
    assert!(below < 0.05 * scale, "0.9 h*: max |E − E₀| = {below:e} J");
    // Above the limit (1.2 h*) the highest longitudinal mode grows from the start: it blows up.
    let above = rope_energy_excursion(
        &mut rope(n, false, ClothIntegrator::SymplecticEuler),
        1.2 * h,
        400,
    );
    assert!(above > 1e3 * scale, "1.2 h*: max |E − E₀| only {above:e} J");
}
