//! The physics core against independent truth: hand-computed inertia tensors, closed-form
//! trajectories, conservation laws, and the loop's phase-by-phase contract.
//!
//! Worlds are built with the physics API (small helpers below); the scene loader and the `run`
//! command are exercised on a few files at the end.

use assert_cmd::cargo::cargo_bin_cmd;
use nalgebra::{Matrix3, Unit, UnitQuaternion, Vector3};
use std::path::{Path, PathBuf};
use tumble::physics::derive::derive;
use tumble::physics::{
    Body, BodyError, Effect, Effects, Integrator, Orientation, Phase, State, World,
};

// ---------------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------------

const GRAVITY: Vector3<f64> = Vector3::new(0.0, -9.81, 0.0);

/// The integrators that step a unit quaternion (all but `euler-seed`).
const QUATERNION_INTEGRATORS: [Integrator; 4] = [
    Integrator::Euler,
    Integrator::SymplecticEuler,
    Integrator::Rk4,
    Integrator::Splitting,
];

/// A state from velocities: P = M v, L = I_world ω with I_world = R I_body Rᵀ.
fn state_from_velocities(
    body: &Body,
    position: Vector3<f64>,
    orientation: UnitQuaternion<f64>,
    velocity: Vector3<f64>,
    angular_velocity: Vector3<f64>,
) -> State {
    let r = orientation.to_rotation_matrix().into_inner();
    State {
        position,
        orientation: Orientation::Quaternion(orientation),
        linear_momentum: velocity * body.mass,
        angular_momentum: r * body.inertia_body * r.transpose() * angular_velocity,
    }
}

/// A world without obstacles.
fn world(body: Body, effects: Vec<Effect>, integrator: Integrator, dt: f64, state: State) -> World {
    World::new(
        body,
        Effects::new(effects),
        Vec::new(),
        None,
        integrator,
        dt,
        state,
    )
}

/// The tennis-racket box: 1.0 × 0.4 × 0.1 m, 1 kg, uniform solid.
fn racket() -> Body {
    Body::solid_box(Vector3::new(1.0, 0.4, 0.1), 1.0).unwrap()
}

/// The torque-free racket spun near its intermediate axis: ω_body(0) = (0.01, 10, 0.01).
fn tumbling(integrator: Integrator) -> World {
    let body = racket();
    let state = state_from_velocities(
        &body,
        Vector3::zeros(),
        UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::new(0.01, 10.0, 0.01),
    );
    world(body, Vec::new(), integrator, 1e-3, state)
}

/// The spinning projectile: cube of side 0.2 m, 1 kg, x₀ (0, 1, 0), v₀ (2, 5, 0), ω (0, 0, 3).
fn projectile(integrator: Integrator) -> World {
    let body = Body::solid_box(Vector3::new(0.2, 0.2, 0.2), 1.0).unwrap();
    let state = state_from_velocities(
        &body,
        Vector3::new(0.0, 1.0, 0.0),
        UnitQuaternion::identity(),
        Vector3::new(2.0, 5.0, 0.0),
        Vector3::new(0.0, 0.0, 3.0),
    );
    world(
        body,
        vec![Effect::Gravity(GRAVITY)],
        integrator,
        1e-3,
        state,
    )
}

/// Rotational kinetic energy ½ ω·L of the current state, measured from the state.
fn rotational_energy(world: &World) -> f64 {
    let k = derive(world.body(), world.state());
    0.5 * k.angular_velocity.dot(&world.state().angular_momentum)
}

/// Largest absolute entry of a matrix difference.
fn max_abs(m: Matrix3<f64>) -> f64 {
    m.iter().fold(0.0, |acc, x| acc.max(x.abs()))
}

fn assert_matrix_near(seen: &Matrix3<f64>, expected: &Matrix3<f64>, tol: f64, what: &str) {
    let err = max_abs(seen - expected);
    assert!(
        err <= tol,
        "{what}: largest entry error {err:e} > {tol:e}\nseen {seen}\nexpected {expected}"
    );
}

fn assert_vector_near(seen: &Vector3<f64>, expected: &Vector3<f64>, tol: f64, what: &str) {
    let err = (seen - expected).amax();
    assert!(
        err <= tol,
        "{what}: error {err:e} > {tol:e}, seen {seen:?}, expected {expected:?}"
    );
}

/// Rodrigues' formula, written out independently of nalgebra's conversions:
/// `R = cos θ 𝟙 + sin θ [k]ₓ + (1 − cos θ) k kᵀ`.
fn rodrigues(axis: Vector3<f64>, angle: f64) -> Matrix3<f64> {
    let k = axis.normalize();
    let kx = Matrix3::new(0.0, -k.z, k.y, k.z, 0.0, -k.x, -k.y, k.x, 0.0);
    Matrix3::identity() * angle.cos() + kx * angle.sin() + k * k.transpose() * (1.0 - angle.cos())
}

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

/// A scene parsed from source text (`path` only names it and anchors relative meshes).
fn scene(source: &str) -> tumble::scene::Scene {
    tumble::scene::parse(source, &fixtures().join("inline.toml"))
        .unwrap_or_else(|e| panic!("scene should load: {e}"))
        .scene
}

// ---------------------------------------------------------------------------------------------
// Inertia
// ---------------------------------------------------------------------------------------------

#[test]
fn box_corners_as_mass_points_give_the_hand_computed_tensor() {
    // 8 corners (±a/2, ±b/2, ±c/2), each m/8. I_xx = Σ mᵢ (yᵢ² + zᵢ²) = m (b²/4 + c²/4);
    // every product Σ mᵢ xᵢ yᵢ cancels by symmetry. For a, b, c = 1, 0.4, 0.1 and m = 1:
    // I = diag((0.16 + 0.01)/4, (1 + 0.01)/4, (1 + 0.16)/4) = diag(0.0425, 0.2525, 0.29).
    let body = Body::box_of_corners(Vector3::new(1.0, 0.4, 0.1), 1.0).unwrap();
    let expected = Matrix3::from_diagonal(&Vector3::new(0.0425, 0.2525, 0.29));
    assert_matrix_near(&body.inertia_body, &expected, 1e-16, "corner inertia");
    assert_vector_near(&body.barycenter, &Vector3::zeros(), 1e-17, "barycenter");
    assert_eq!(body.points_body.len(), 8);
    assert_eq!(body.edges.len(), 12, "a box has 12 edges");
    let inverse = Matrix3::from_diagonal(&Vector3::new(1.0 / 0.0425, 1.0 / 0.2525, 1.0 / 0.29));
    assert_matrix_near(&body.inv_inertia_body, &inverse, 1e-12, "inverse");
    // Principal moments ascending.
    assert_vector_near(
        &body.principal_moments,
        &Vector3::new(0.0425, 0.2525, 0.29),
        1e-16,
        "principal moments",
    );
}

#[test]
fn solid_box_uses_the_m_over_12_formulas() {
    // Uniform solid box: I = m/12 · diag(b² + c², a² + c², a² + b²). For 1.0 × 0.4 × 0.1, m = 2:
    // diag(0.17, 1.01, 1.16) / 6.
    let body = Body::solid_box(Vector3::new(1.0, 0.4, 0.1), 2.0).unwrap();
    let expected = Matrix3::from_diagonal(&Vector3::new(0.17, 1.01, 1.16)) / 6.0;
    assert_matrix_near(&body.inertia_body, &expected, 1e-16, "solid box inertia");
    assert_eq!(body.mass, 2.0);
    assert_eq!(body.inv_mass, 0.5);
}

#[test]
fn solid_box_matches_a_fine_grid_of_point_masses() {
    // Independent check of the closed form: n³ equal masses at the cell centres of the box.
    // The midpoint sum of y² over n cells of [−b/2, b/2] is exactly b²/12 · (1 − 1/n²), so the
    // grid's tensor is the solid's scaled by (1 − 1/n²) — to round-off, not to a tolerance.
    let (size, mass, n) = (Vector3::new(1.0, 0.4, 0.1), 1.0, 12usize);
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let cell = |idx: usize, side: f64| ((idx as f64 + 0.5) / n as f64 - 0.5) * side;
                points.push(Vector3::new(
                    cell(i, size.x),
                    cell(j, size.y),
                    cell(k, size.z),
                ));
            }
        }
    }
    let grid = Body::from_points(&points, &[], mass, Vec::new()).unwrap();
    let solid = Body::solid_box(size, mass).unwrap();
    let scale = 1.0 - 1.0 / (n * n) as f64;
    assert_matrix_near(
        &grid.inertia_body,
        &(solid.inertia_body * scale),
        1e-14,
        "grid vs solid·(1 − 1/n²)",
    );
}

/// The off-centre point set used by two tests: four points with masses 2, 1, 1, 4.
fn off_centre_points() -> (Vec<Vector3<f64>>, Vec<f64>) {
    (
        vec![
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(1.0, 1.0, 1.0),
        ],
        vec![2.0, 1.0, 1.0, 4.0],
    )
}

/// The off-centre set's tensor about its barycenter, by hand.
///
/// M = 8, c = (2·(1,0,0) + (0,1,0) + (0,0,1) + 4·(1,1,1)) / 8 = (6, 5, 5) / 8.
/// About the origin, I_O = Σ mᵢ (|pᵢ|² 𝟙 − pᵢpᵢᵀ):
///   2·diag(0,1,1) + diag(1,0,1) + diag(1,1,0) + 4·(3·𝟙 − ones)
///   = [[10, −4, −4], [−4, 11, −4], [−4, −4, 11]].
/// Parallel axes: I_c = I_O − M|c|² 𝟙 + M c cᵀ, with M|c|² = 86/8 = 10.75 and
/// M c cᵀ = [[36, 30, 30], [30, 25, 25], [30, 25, 25]] / 8:
///   I_c = [[3.75, −0.25, −0.25], [−0.25, 3.375, −0.875], [−0.25, −0.875, 3.375]].
fn off_centre_expected() -> (Vector3<f64>, Matrix3<f64>) {
    (
        Vector3::new(0.75, 0.625, 0.625),
        Matrix3::new(
            3.75, -0.25, -0.25, //
            -0.25, 3.375, -0.875, //
            -0.25, -0.875, 3.375,
        ),
    )
}

#[test]
fn off_centre_points_with_their_own_masses_give_the_hand_computed_barycenter_and_tensor() {
    let (points, masses) = off_centre_points();
    let body = Body::from_points(&points, &masses, 0.0, Vec::new()).unwrap();
    let (barycenter, inertia) = off_centre_expected();
    assert_eq!(body.mass, 8.0, "total mass is the sum of the point masses");
    assert_vector_near(&body.barycenter, &barycenter, 1e-15, "barycenter");
    assert_matrix_near(&body.inertia_body, &inertia, 1e-14, "inertia about c");
    for (r0, p) in body.points_body.iter().zip(&points) {
        assert_vector_near(r0, &(p - barycenter), 1e-15, "r₀ᵢ = pᵢ − c");
    }
    // Σ mᵢ r₀ᵢ = 0: the barycenter is where the first moment vanishes.
    let moment = body
        .points_body
        .iter()
        .zip(&masses)
        .fold(Vector3::zeros(), |acc, (r, m)| acc + r * *m);
    assert_vector_near(&moment, &Vector3::zeros(), 1e-14, "Σ mᵢ r₀ᵢ");
    assert_matrix_near(
        &(body.inertia_body * body.inv_inertia_body),
        &Matrix3::identity(),
        1e-14,
        "I · I⁻¹",
    );
}

#[test]
fn a_rotated_point_set_has_the_rotated_non_diagonal_tensor() {
    // The box corners turned by R (40° about (1, 2, 3)): I' = R I Rᵀ with I the diagonal tensor
    // of the first test; the principal moments stay (0.0425, 0.2525, 0.29).
    let size = Vector3::new(1.0, 0.4, 0.1);
    let r = rodrigues(Vector3::new(1.0, 2.0, 3.0), 40f64.to_radians());
    let corners = Body::box_of_corners(size, 1.0).unwrap();
    let turned: Vec<Vector3<f64>> = corners.points_body.iter().map(|p| r * p).collect();
    let body = Body::from_points(&turned, &[], 1.0, Vec::new()).unwrap();
    let diagonal = Matrix3::from_diagonal(&Vector3::new(0.0425, 0.2525, 0.29));
    let expected = r * diagonal * r.transpose();
    assert_matrix_near(&body.inertia_body, &expected, 1e-15, "R I Rᵀ");
    let off_diagonal = body.inertia_body[(0, 1)]
        .abs()
        .max(body.inertia_body[(0, 2)].abs())
        .max(body.inertia_body[(1, 2)].abs());
    assert!(
        off_diagonal > 1e-2,
        "the rotated tensor must not be diagonal, largest product of inertia {off_diagonal}"
    );
    assert_vector_near(
        &body.principal_moments,
        &Vector3::new(0.0425, 0.2525, 0.29),
        1e-14,
        "principal moments",
    );
    // The principal frame E is a proper rotation with I = E diag(moments) Eᵀ.
    let e = body.principal_axes.to_rotation_matrix().into_inner();
    assert!((e.determinant() - 1.0).abs() < 1e-12);
    assert_matrix_near(
        &(e * Matrix3::from_diagonal(&body.principal_moments) * e.transpose()),
        &body.inertia_body,
        1e-14,
        "E diag Eᵀ",
    );
}

#[test]
fn world_inertia_in_a_snapshot_is_r_i_body_r_transpose() {
    // A quarter turn about z swaps the x and y axes: I_world = diag(I_yy, I_xx, I_zz).
    let body = racket();
    let quarter = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2);
    let state = state_from_velocities(
        &body,
        Vector3::zeros(),
        quarter,
        Vector3::zeros(),
        Vector3::new(1.0, 2.0, 3.0),
    );
    let snapshot = world(body.clone(), Vec::new(), Integrator::Rk4, 1e-3, state).snapshot();
    let i = body.inertia_body;
    let swapped = Matrix3::from_diagonal(&Vector3::new(i[(1, 1)], i[(0, 0)], i[(2, 2)]));
    assert_matrix_near(&snapshot.inertia_world, &swapped, 1e-15, "quarter turn");

    // A general orientation, against Rodrigues' R written out by hand.
    let (axis, angle) = (Vector3::new(-0.3, 0.8, 0.5), 1.1);
    let q = UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), angle);
    let omega = Vector3::new(0.4, -2.0, 7.0);
    let state = state_from_velocities(&body, Vector3::zeros(), q, Vector3::zeros(), omega);
    let snapshot = world(body.clone(), Vec::new(), Integrator::Rk4, 1e-3, state).snapshot();
    let r = rodrigues(axis, angle);
    let i_world = r * i * r.transpose();
    assert_matrix_near(&snapshot.inertia_world, &i_world, 1e-15, "R I_body Rᵀ");
    assert_matrix_near(
        &(snapshot.inertia_world * snapshot.inv_inertia_world),
        &Matrix3::identity(),
        1e-13,
        "I_world · I⁻¹_world",
    );
    assert_vector_near(&snapshot.angular_velocity, &omega, 1e-12, "ω = I⁻¹_world L");
    assert_vector_near(
        &snapshot.angular_velocity_body,
        &(r.transpose() * omega),
        1e-12,
        "ω_body = Rᵀ ω",
    );
}

#[test]
fn collinear_points_are_refused_with_a_message_that_says_why() {
    let points = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.0, 1.0, 0.0),
        Vector3::new(2.0, 2.0, 0.0),
    ];
    let error = Body::from_points(&points, &[], 1.0, Vec::new()).unwrap_err();
    assert!(
        matches!(error, BodyError::SingularInertia(..)),
        "expected a singular-inertia error, got {error:?}"
    );
    let message = error.to_string();
    for needle in ["singular", "one line", "add a point off the line"] {
        assert!(
            message.contains(needle),
            "message should say `{needle}`: {message}"
        );
    }
    // One point alone is singular too.
    let single = Body::from_points(&[Vector3::new(1.0, 2.0, 3.0)], &[], 1.0, Vec::new());
    assert!(matches!(single, Err(BodyError::SingularInertia(..))));
}

#[test]
fn a_mesh_body_loaded_through_a_scene_file_has_the_hand_computed_mass_properties() {
    // Vertices O, (1,0,0), (0,1,0), (0,0,1), each 1 kg (mass 4 shared equally).
    // c = (1,1,1)/4. About O: I_O = diag(0,1,1) + diag(1,0,1) + diag(1,1,0) = diag(2,2,2).
    // I_c = I_O − M|c|² 𝟙 + M c cᵀ, M|c|² = 4·3/16 = 0.75, M c cᵀ = ones/4:
    // I_c = 1.25·𝟙 + ones/4 → diagonal 1.5, products 0.25; principal moments 1.25, 1.25, 2.
    let lesson = tumble::scene::load(&fixtures().join("tetrahedron.toml")).unwrap();
    let body = &lesson.scene.first().body;
    assert_eq!(lesson.scene.first().shape, "mesh");
    assert_eq!(body.mass, 4.0);
    assert_eq!(body.points_body.len(), 4);
    assert_eq!(body.edges.len(), 6, "a tetrahedron has 6 edges");
    assert_vector_near(
        &body.barycenter,
        &Vector3::new(0.25, 0.25, 0.25),
        1e-16,
        "barycenter",
    );
    let expected = Matrix3::new(1.5, 0.25, 0.25, 0.25, 1.5, 0.25, 0.25, 0.25, 1.5);
    assert_matrix_near(&body.inertia_body, &expected, 1e-15, "tetrahedron inertia");
    assert_vector_near(
        &body.principal_moments,
        &Vector3::new(1.25, 1.25, 2.0),
        1e-14,
        "principal moments",
    );
    assert_vector_near(
        &body.points_body[0],
        &Vector3::new(-0.25, -0.25, -0.25),
        1e-16,
        "r₀ of the origin vertex",
    );
}

// ---------------------------------------------------------------------------------------------
// The spinning projectile
// ---------------------------------------------------------------------------------------------

/// x₀ + v₀ t + ½ g t².
fn parabola(t: f64) -> Vector3<f64> {
    Vector3::new(0.0, 1.0, 0.0) + Vector3::new(2.0, 5.0, 0.0) * t + GRAVITY * (0.5 * t * t)
}

#[test]
fn rk4_projectile_follows_the_parabola_and_spins_at_3_rad_per_s() {
    let mut world = projectile(Integrator::Rk4);
    for _ in 0..1000 {
        world.step();
    }
    let t = world.time();
    assert!((t - 1.0).abs() < 1e-12, "t = {t}");
    // RK4 is exact for a constant force: the barycenter is the parabola to round-off.
    assert_vector_near(
        &world.state().position,
        &parabola(t),
        1e-9,
        "rk4 barycenter",
    );
    // A cube is isotropic: ω stays (0, 0, 3) and q turns about z by 3t.
    let q = world.state().orientation.quaternion();
    let angle = 2.0 * q.k.atan2(q.w);
    assert!(
        (angle - 3.0 * t).abs() < 1e-9,
        "spin angle {angle} after t = {t}, expected {}",
        3.0 * t
    );
    assert!(q.i.abs() < 1e-15 && q.j.abs() < 1e-15, "axis left z: {q:?}");
    let snapshot = world.snapshot();
    assert_vector_near(
        &snapshot.angular_velocity,
        &Vector3::new(0.0, 0.0, 3.0),
        1e-12,
        "ω",
    );
    assert_vector_near(
        &snapshot.velocity,
        &(Vector3::new(2.0, 5.0, 0.0) + GRAVITY * t),
        1e-12,
        "v = v₀ + g t",
    );
}

#[test]
fn symplectic_euler_projectile_is_off_by_exactly_half_g_dt_t() {
    // Semi-implicit Euler kicks first: P_k = P₀ + k dt M g, so v_k = v₀ + k dt g, then drifts
    // with the new velocity: x_n = x₀ + dt Σ_{k=1..n} v_k = x₀ + n dt v₀ + dt² g n(n+1)/2
    //                             = x₀ + v₀ t_n + ½ g t_n² + ½ g dt t_n.
    // The first-order error is +½ g dt t_n: with g pointing down the body is *below* the
    // parabola by ½·9.81·dt·t (4.905 mm at t = 1 s with dt = 1 ms).
    let dt = 1e-3;
    let mut world = projectile(Integrator::SymplecticEuler);
    for n in 1..=1000u32 {
        world.step();
        if n % 250 == 0 {
            let t = world.time();
            let error = world.state().position - parabola(t);
            let predicted = GRAVITY * (0.5 * dt * t);
            assert_vector_near(&error, &predicted, 1e-11, &format!("error at t = {t}"));
        }
    }
    let error_y = world.state().position.y - parabola(1.0).y;
    assert!(
        (error_y + 0.004905).abs() < 1e-11,
        "y error at 1 s: {error_y}, expected −0.004905"
    );
}

// ---------------------------------------------------------------------------------------------
// Torque-free tumbling (the tennis-racket theorem)
// ---------------------------------------------------------------------------------------------

/// What a 20 s torque-free run measured.
struct Tumble {
    /// Sign changes of ω_body,y.
    flips: usize,
    /// Relative energy error |E − E₀|/E₀ at every step.
    energy_error: Vec<f64>,
    /// Signed relative energy change (E_end − E₀)/E₀.
    energy_gain: f64,
    /// Largest relative change of |L|.
    momentum_error: f64,
    /// Largest ‖RᵀR − 𝟙‖.
    orthonormality: f64,
}

fn tumble(integrator: Integrator, steps: usize) -> Tumble {
    let mut world = tumbling(integrator);
    let e0 = rotational_energy(&world);
    let l0 = world.state().angular_momentum.norm();
    let mut flips = 0;
    let mut last_sign = 1.0;
    let mut energy_error = Vec::with_capacity(steps);
    let mut momentum_error: f64 = 0.0;
    let mut orthonormality: f64 = 0.0;
    for _ in 0..steps {
        world.step();
        let state = world.state();
        let r = state.orientation.matrix();
        let omega_body = r.transpose() * derive(world.body(), state).angular_velocity;
        if omega_body.y.signum() != last_sign {
            flips += 1;
            last_sign = omega_body.y.signum();
        }
        energy_error.push((rotational_energy(&world) - e0).abs() / e0);
        momentum_error = momentum_error.max((state.angular_momentum.norm() - l0).abs() / l0);
        orthonormality = orthonormality.max(state.orientation.orthonormality_error());
    }
    Tumble {
        flips,
        energy_gain: (rotational_energy(&world) - e0) / e0,
        energy_error,
        momentum_error,
        orthonormality,
    }
}

fn max_of(values: &[f64]) -> f64 {
    values.iter().copied().fold(0.0, f64::max)
}

#[test]
fn rk4_tumbling_box_flips_and_keeps_energy_and_angular_momentum_to_1e_9() {
    let run = tumble(Integrator::Rk4, 20_000);
    // The intermediate axis is unstable: the e-folding rate is
    // ω_y √((I₂−I₁)(I₃−I₂)/(I₁I₃)) ≈ 8 /s, so the 0.01 rad/s seed turns over within ~1 s and
    // the body keeps flipping over 20 s (9 sign changes measured; the period is set by how
    // close to the separatrix the seed starts).
    assert!(
        run.flips >= 6,
        "ω_y should flip sign many times in 20 s, flipped {}",
        run.flips
    );
    let energy = max_of(&run.energy_error);
    println!(
        "rk4 20 s: {} flips, max relative energy error {energy:e}, |L| error {:e}",
        run.flips, run.momentum_error
    );
    assert!(energy < 1e-9, "rk4 relative energy drift {energy:e}");
    assert!(
        run.momentum_error < 1e-9,
        "rk4 |L| drift {:e}",
        run.momentum_error
    );
}

#[test]
fn splitting_keeps_angular_momentum_to_round_off_and_energy_in_a_band() {
    let run = tumble(Integrator::Splitting, 20_000);
    assert!(run.flips >= 6, "flipped {} times", run.flips);
    assert!(
        run.momentum_error < 1e-12,
        "splitting |L| drift {:e}",
        run.momentum_error
    );
    // Bounded, not drifting: the worst energy error of the last quarter is no larger than
    // that of the first quarter (up to a margin), and both are small.
    let quarter = run.energy_error.len() / 4;
    let first = max_of(&run.energy_error[..quarter]);
    let last = max_of(&run.energy_error[3 * quarter..]);
    println!("splitting 20 s: energy band first quarter {first:e}, last quarter {last:e}");
    assert!(first < 1e-3 && last < 1e-3, "band {first:e} / {last:e}");
    assert!(
        last < 1.5 * first,
        "energy error grows: first quarter {first:e}, last quarter {last:e}"
    );
    // The quaternion stays a rotation.
    assert!(
        run.orthonormality < 1e-12,
        "‖RᵀR − 𝟙‖ = {:e}",
        run.orthonormality
    );
}

#[test]
fn explicit_euler_visibly_gains_energy_on_the_tumbling_box() {
    let run = tumble(Integrator::Euler, 20_000);
    println!("euler 20 s: relative energy gain {:e}", run.energy_gain);
    assert!(
        run.energy_gain > 1e-2,
        "explicit Euler should gain energy visibly, gained {:e}",
        run.energy_gain
    );
    // L is untouched (τ = 0), only the orientation — hence ω and E — is wrong.
    assert!(run.momentum_error < 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Orthonormality: euler-seed drifts, quaternions do not
// ---------------------------------------------------------------------------------------------

#[test]
fn euler_seed_drifts_away_from_a_rotation_at_the_predicted_rate() {
    let mut world = tumbling(Integrator::EulerSeed);
    // One step from R = 𝟙: R₁ = 𝟙 + dt ω*, and since ω*ᵀ = −ω*,
    // R₁ᵀR₁ − 𝟙 = dt² ω*ᵀω* = dt² (|ω|² 𝟙 − ω ωᵀ), whose Frobenius norm is dt² |ω|² √2
    // (|ω|² times a projector onto a plane). Here ω = (0.01, 10, 0.01): dt²|ω|² = 1.000002e-4.
    world.step();
    let omega_sq: f64 = 0.01 * 0.01 + 100.0 + 0.01 * 0.01;
    let predicted = 1e-6 * omega_sq * 2f64.sqrt();
    let seen = world.state().orientation.orthonormality_error();
    assert!(
        (seen - predicted).abs() < 1e-9 * predicted,
        "after one step ‖RᵀR − 𝟙‖ = {seen:e}, predicted {predicted:e}"
    );
    let mut previous = seen;
    for checkpoint in [10, 100, 300] {
        while world.step_count() < checkpoint {
            world.step();
        }
        let error = world.state().orientation.orthonormality_error();
        assert!(
            error > previous,
            "drift must grow: {error:e} after {previous:e}"
        );
        previous = error;
    }
    println!("euler-seed: ‖RᵀR − 𝟙‖ = {previous:e} after 300 steps");
    assert!(previous > 1e-6, "visible after 300 steps: {previous:e}");
    assert!(matches!(world.state().orientation, Orientation::Matrix(_)));
}

#[test]
fn every_quaternion_integrator_stays_a_rotation_to_1e_12() {
    for integrator in QUATERNION_INTEGRATORS {
        let run = tumble(integrator, 5_000);
        assert!(
            run.orthonormality < 1e-12,
            "{}: ‖RᵀR − 𝟙‖ reached {:e}",
            integrator.name(),
            run.orthonormality
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Effects: only what the scene declares
// ---------------------------------------------------------------------------------------------

#[test]
fn without_gravity_linear_momentum_is_exactly_constant() {
    for integrator in Integrator::ALL {
        let body = racket();
        let state = state_from_velocities(
            &body,
            Vector3::new(0.0, 3.0, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.3),
            Vector3::new(1.0, -2.0, 0.5),
            Vector3::new(0.3, 4.0, -1.0),
        );
        let p0 = state.linear_momentum;
        let mut world = world(body, Vec::new(), integrator, 1e-3, state);
        for _ in 0..1000 {
            world.step();
            assert_eq!(
                world.state().linear_momentum,
                p0,
                "{}: P changed without a declared force",
                integrator.name()
            );
        }
        let snapshot = world.snapshot();
        assert_eq!(snapshot.force, Vector3::zeros());
        assert_eq!(snapshot.torque, Vector3::zeros());
        assert_eq!(snapshot.energy.potential, 0.0, "no gravity, no potential");
    }
}

#[test]
fn a_scene_without_effect_keys_declares_no_effects() {
    let scene = scene(
        r#"title = "t"
[scene]
dt = 0.01
integrator = "rk4"
[body]
shape = "box"
size = [1.0, 1.0, 1.0]
mass = 1.0
"#,
    );
    assert!(scene.effects.list().is_empty(), "{:?}", scene.effects);
    assert!(scene.effects.gravity().is_none());
    let with = |extra: &str| {
        scene_effects(&format!(
            "title = \"t\"\n[scene]\ndt = 0.01\nintegrator = \"rk4\"\n{extra}\n[body]\nshape = \"box\"\nsize = [1.0, 1.0, 1.0]\nmass = 1.0\n"
        ))
    };
    assert_eq!(with("gravity = [0.0, -9.81, 0.0]"), vec!["gravity"]);
    assert_eq!(with("drag = { linear = 0.1 }"), vec!["drag"]);
}

fn scene_effects(source: &str) -> Vec<&'static str> {
    scene(source).effects.names()
}

#[test]
fn drag_alone_decays_momenta_exponentially_and_energy_monotonically() {
    // Linear drag only, free flight: Ṗ = −k P/M, so P(t) = P₀ e^{−k t/M}.
    // Angular drag on an isotropic cube (I = m s²/6 = 1/150): L̇ = −k_a L/I, L(t) = L₀ e^{−k_a t/I}.
    let body = Body::solid_box(Vector3::new(0.2, 0.2, 0.2), 1.0).unwrap();
    let (k, k_a, inertia) = (0.5, 0.001, 1.0 / 150.0);
    let state = state_from_velocities(
        &body,
        Vector3::zeros(),
        UnitQuaternion::identity(),
        Vector3::new(1.0, 2.0, -1.0),
        Vector3::new(0.0, 3.0, 4.0),
    );
    let (p0, l0) = (state.linear_momentum, state.angular_momentum);
    let drag = Effect::Drag {
        linear: k,
        angular: k_a,
    };
    let mut world = world(body, vec![drag], Integrator::Rk4, 1e-3, state);
    let mut energy = world.energy_of(world.state()).total;
    for _ in 0..2000 {
        world.step();
        let now = world.energy_of(world.state()).total;
        assert!(now < energy, "drag must dissipate: {now} after {energy}");
        energy = now;
    }
    let t = world.time();
    assert_vector_near(
        &world.state().linear_momentum,
        &(p0 * (-k * t).exp()),
        1e-12,
        "P(t)",
    );
    assert_vector_near(
        &world.state().angular_momentum,
        &(l0 * (-k_a * t / inertia).exp()),
        1e-12,
        "L(t)",
    );
}

// ---------------------------------------------------------------------------------------------
// The loop, phase by phase
// ---------------------------------------------------------------------------------------------

fn falling_with_drag(integrator: Integrator) -> World {
    let body = racket();
    let state = state_from_velocities(
        &body,
        Vector3::new(0.0, 5.0, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.4),
        Vector3::new(1.0, 0.0, 0.0),
        Vector3::new(0.01, 10.0, 0.01),
    );
    let effects = vec![
        Effect::Gravity(GRAVITY),
        Effect::Drag {
            linear: 0.1,
            angular: 0.01,
        },
    ];
    world(body, effects, integrator, 1e-3, state)
}

#[test]
fn step_phase_runs_derive_forces_integrate_collide_in_order() {
    let mut world = falling_with_drag(Integrator::Rk4);
    assert_eq!(world.last_phase(), None);
    assert_eq!(world.next_phase(), Phase::Derive);
    let start = *world.state();

    assert_eq!(world.step_phase(), Phase::Derive);
    // derive: ω = R I⁻¹_body Rᵀ L and v = P/M of the current state.
    let r = start.orientation.matrix();
    let omega = r * world.body().inv_inertia_body * r.transpose() * start.angular_momentum;
    assert_vector_near(&world.kinematics().angular_velocity, &omega, 1e-12, "ω");
    assert_eq!(
        world.kinematics().velocity,
        start.linear_momentum * world.body().inv_mass
    );
    assert_eq!(world.state(), &start, "derive does not move the body");
    assert_eq!(world.step_count(), 0);

    assert_eq!(world.step_phase(), Phase::Forces);
    // forces: F = M g − k v, τ = −k_a ω.
    let v = world.kinematics().velocity;
    assert_vector_near(&world.loads().force, &(GRAVITY - v * 0.1), 1e-15, "F");
    assert_vector_near(&world.loads().torque, &(-omega * 0.01), 1e-12, "τ");
    assert_eq!(world.state(), &start, "forces do not move the body");
    assert_eq!(world.snapshot().phase, Some(Phase::Forces));

    assert_eq!(world.step_phase(), Phase::Integrate);
    assert_eq!(world.step_count(), 1);
    assert_ne!(world.state(), &start, "integrate moves the body");
    assert!(world.state().position.y < start.position.y + 1e-3);

    assert_eq!(world.step_phase(), Phase::Collide);
    assert_eq!(world.step_count(), 1);
    assert_eq!(world.next_phase(), Phase::Derive);
    assert!(world.contacts().is_empty(), "no obstacles, no contacts");
    let snapshot = world.snapshot();
    assert_eq!(snapshot.phase, Some(Phase::Collide));
    assert_eq!(snapshot.step, 1);
}

#[test]
fn four_step_phase_calls_equal_one_step_bit_for_bit() {
    for integrator in Integrator::ALL {
        let mut whole = falling_with_drag(integrator);
        let mut phased = falling_with_drag(integrator);
        for _ in 0..200 {
            whole.step();
            for _ in 0..4 {
                phased.step_phase();
            }
        }
        assert_eq!(whole.state(), phased.state(), "{}", integrator.name());
        assert_eq!(
            whole.checkpoint(),
            phased.checkpoint(),
            "{}",
            integrator.name()
        );
        assert_eq!(whole.snapshot(), phased.snapshot(), "{}", integrator.name());
    }
    // From mid-frame, step() finishes the frame.
    let mut world = falling_with_drag(Integrator::Rk4);
    world.step_phase();
    world.step_phase();
    world.step();
    assert_eq!(world.last_phase(), Some(Phase::Collide));
    assert_eq!(world.step_count(), 1);
}

#[test]
fn restoring_a_checkpoint_replays_exactly_the_same_states() {
    let mut world = falling_with_drag(Integrator::Splitting);
    for _ in 0..50 {
        world.step();
    }
    world.step_phase(); // mid-frame on purpose
    let checkpoint = world.checkpoint();
    let snapshot = world.snapshot();
    let mut first = Vec::new();
    for _ in 0..100 {
        world.step();
        first.push(*world.state());
    }
    world.restore(&checkpoint);
    assert_eq!(world.snapshot(), snapshot);
    assert_eq!(world.next_phase(), Phase::Forces);
    for (i, expected) in first.iter().enumerate() {
        world.step();
        assert_eq!(world.state(), expected, "replayed step {i} differs");
    }
}

#[test]
fn set_integrator_keeps_time_and_state() {
    let mut world = tumbling(Integrator::Rk4);
    for _ in 0..100 {
        world.step();
    }
    let before = *world.state();
    let t = world.time();

    // quaternion → quaternion: nothing changes.
    world.set_integrator(Integrator::Splitting);
    assert_eq!(world.state(), &before);
    assert_eq!(world.time(), t);
    assert_eq!(world.integrator(), Integrator::Splitting);

    // quaternion → euler-seed: the same rotation as a matrix.
    world.set_integrator(Integrator::EulerSeed);
    let Orientation::Matrix(m) = world.state().orientation else {
        panic!("euler-seed steps a matrix");
    };
    assert_matrix_near(&m, &before.orientation.matrix(), 1e-15, "R of q");
    assert_eq!(world.state().position, before.position);
    assert_eq!(world.state().angular_momentum, before.angular_momentum);
    assert_eq!(world.time(), t);

    // Let the matrix drift, then back to a quaternion: the nearest rotation, t kept.
    for _ in 0..300 {
        world.step();
    }
    let drifted = *world.state();
    assert!(drifted.orientation.orthonormality_error() > 1e-3);
    let t = world.time();
    world.step_phase(); // mid-frame: switching restarts the frame at derive
    world.set_integrator(Integrator::Rk4);
    assert_eq!(world.next_phase(), Phase::Derive);
    assert_eq!(world.time(), t);
    assert_eq!(world.step_count(), 400);
    let Orientation::Quaternion(q) = world.state().orientation else {
        panic!("rk4 steps a quaternion");
    };
    assert!(world.state().orientation.orthonormality_error() < 1e-12);
    // The nearest rotation is the polar factor U of R = U S (S symmetric positive).
    let r = drifted.orientation.matrix();
    let svd = r.svd(true, true);
    let polar = svd.u.unwrap() * svd.v_t.unwrap();
    assert_matrix_near(
        &q.to_rotation_matrix().into_inner(),
        &polar,
        1e-9,
        "polar factor",
    );
    assert_eq!(world.state().linear_momentum, drifted.linear_momentum);
    assert_eq!(world.state().angular_momentum, drifted.angular_momentum);
}

// ---------------------------------------------------------------------------------------------
// Scene loader
// ---------------------------------------------------------------------------------------------

fn box_scene(body_extra: &str) -> tumble::scene::Scene {
    scene(&format!(
        "title = \"t\"\n[scene]\ndt = 0.001\nintegrator = \"rk4\"\n[body]\nshape = \"box\"\n\
         size = [1.0, 0.4, 0.1]\nmass = 1.0\n{body_extra}\n"
    ))
}

#[test]
fn orientation_as_axis_and_degrees_equals_the_same_quaternion() {
    // 90° about z is q = (cos 45°, 0, 0, sin 45°).
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let by_angle = box_scene("orientation = { axis = [0.0, 0.0, 2.0], degrees = 90.0 }");
    let by_quaternion = box_scene(&format!(
        "orientation = {{ quaternion = [{h}, 0.0, 0.0, {h}] }}"
    ));
    let a = by_angle.first().initial.orientation.quaternion();
    let b = by_quaternion.first().initial.orientation.quaternion();
    assert!(a.angle_to(&b) < 1e-15, "{a:?} vs {b:?}");
    assert!((a.w - h).abs() < 1e-15 && (a.k - h).abs() < 1e-15, "{a:?}");
    // A non-unit quaternion is normalised.
    let scaled = box_scene("orientation = { quaternion = [2.0, 0.0, 0.0, 2.0] }");
    assert!(scaled.first().initial.orientation.quaternion().angle_to(&a) < 1e-15);
}

#[test]
fn angular_velocity_body_is_turned_into_the_world_frame() {
    // Body x after a quarter turn about z points along world y: ω_body = (1, 0, 0) is
    // ω = (0, 1, 0), and L = I_world ω = I_xx (body) about world y.
    let quarter = "orientation = { axis = [0.0, 0.0, 1.0], degrees = 90.0 }";
    let body_frame = box_scene(&format!(
        "{quarter}\nangular_velocity_body = [1.0, 0.0, 0.0]"
    ));
    let world_frame = box_scene(&format!("{quarter}\nangular_velocity = [0.0, 1.0, 0.0]"));
    let i_xx = 0.17 / 12.0;
    assert_vector_near(
        &body_frame.first().initial.angular_momentum,
        &Vector3::new(0.0, i_xx, 0.0),
        1e-16,
        "L",
    );
    assert_vector_near(
        &body_frame.first().initial.angular_momentum,
        &world_frame.first().initial.angular_momentum,
        1e-16,
        "same L either way",
    );
    let snapshot = body_frame.world().snapshot();
    assert_vector_near(
        &snapshot.angular_velocity,
        &Vector3::new(0.0, 1.0, 0.0),
        1e-15,
        "ω",
    );
    assert_vector_near(
        &snapshot.angular_velocity_body,
        &Vector3::new(1.0, 0.0, 0.0),
        1e-15,
        "ω_body",
    );
}

#[test]
fn a_points_scene_with_per_point_masses_gives_the_hand_computed_body() {
    let scene = scene(
        r#"title = "t"
[scene]
dt = 0.001
integrator = "rk4"
[body]
shape = "points"
points = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]]
masses = [2.0, 1.0, 1.0, 4.0]
velocity = [1.0, 0.0, 0.0]
"#,
    );
    let (barycenter, inertia) = off_centre_expected();
    assert_eq!(scene.first().body.mass, 8.0);
    assert_vector_near(
        &scene.first().body.barycenter,
        &barycenter,
        1e-15,
        "barycenter",
    );
    assert_matrix_near(&scene.first().body.inertia_body, &inertia, 1e-14, "inertia");
    assert_eq!(
        scene.first().initial.linear_momentum,
        Vector3::new(8.0, 0.0, 0.0),
        "P = M v"
    );
}

// ---------------------------------------------------------------------------------------------
// `tumble run` and `tumble check`
// ---------------------------------------------------------------------------------------------

fn tumble_cmd() -> assert_cmd::Command {
    let mut cmd = cargo_bin_cmd!("tumble");
    cmd.current_dir(env!("CARGO_MANIFEST_DIR"));
    cmd
}

/// Runs `tumble` and returns its stdout; asserts the exit code.
fn run_ok(args: &[&str]) -> String {
    let output = tumble_cmd().args(args).output().unwrap();
    assert_eq!(
        output.status.code(),
        Some(0),
        "tumble {args:?}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

fn parse_row(line: &str) -> Vec<f64> {
    line.split(',').map(|v| v.parse().unwrap()).collect()
}

const RACKET: &str = "lessons/10-tennis-racket.toml";

#[test]
fn run_prints_the_contract_header_and_the_initial_state_as_row_0() {
    let csv = run_ok(&["run", RACKET, "--steps", "10", "--every", "5"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "step,t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,Lx,Ly,Lz,energy,penetration"
    );
    assert_eq!(lines.len(), 4, "header + steps 0, 5, 10:\n{csv}");
    let steps: Vec<f64> = lines[1..].iter().map(|l| parse_row(l)[0]).collect();
    assert_eq!(steps, vec![0.0, 5.0, 10.0]);
    // Row 0: at rest at the origin, identity orientation, ω = ω_body = (0.01, 10, 0.01),
    // L = I ω with I = diag(0.17, 1.01, 1.16)/12, E = ½ ω·L = (0.17e-4 + 101 + 1.16e-4)/24.
    let row = parse_row(lines[1]);
    let inertia = Vector3::new(0.17, 1.01, 1.16) / 12.0;
    let omega = Vector3::new(0.01, 10.0, 0.01);
    let l = inertia.component_mul(&omega);
    let expected = [
        0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, omega.x, omega.y, omega.z, l.x,
        l.y, l.z,
    ];
    for (i, (seen, want)) in row.iter().zip(expected.iter()).enumerate() {
        assert!(
            (seen - want).abs() <= 1e-15 * want.abs().max(1.0),
            "row 0 column {i}: {seen} vs {want}"
        );
    }
    let energy = (0.17e-4 + 101.0 + 1.16e-4) / 24.0;
    assert!(
        (row[18] - energy).abs() < 1e-14,
        "energy {} vs {energy}",
        row[18]
    );
    assert_eq!(row[19], 0.0, "no obstacles, no penetration");
    // Row 10 is the library's own state after 10 steps, to the last digit.
    let mut world =
        tumble::scene::load(Path::new(env!("CARGO_MANIFEST_DIR")).join(RACKET).as_path())
            .unwrap()
            .scene
            .world();
    for _ in 0..10 {
        world.step();
    }
    let last = parse_row(lines[3]);
    assert_eq!(last[2], world.state().position.x);
    assert_eq!(last[15], world.state().angular_momentum.x);
    assert_eq!(last[18], world.snapshot().energy.total);
}

#[test]
fn run_overrides_dt_and_integrator() {
    let csv = run_ok(&[
        "run",
        RACKET,
        "--steps",
        "4",
        "--dt",
        "0.125",
        "--integrator",
        "euler",
    ]);
    let rows: Vec<Vec<f64>> = csv.lines().skip(1).map(parse_row).collect();
    assert_eq!(rows.len(), 5);
    assert_eq!(rows[4][1], 0.5, "t = 4 · 0.125");
    // The same scene stepped in the library with those settings.
    let mut scene =
        tumble::scene::load(Path::new(env!("CARGO_MANIFEST_DIR")).join(RACKET).as_path())
            .unwrap()
            .scene;
    scene.dt = 0.125;
    scene.integrator = Integrator::Euler;
    let mut world = scene.world();
    for _ in 0..4 {
        world.step();
    }
    let q = world.state().orientation.quaternion();
    assert_eq!(rows[4][5], q.w, "qw after 4 explicit Euler steps");
    assert_eq!(rows[4][18], world.snapshot().energy.total);
    // And it differs from rk4 at the same dt: the override took effect.
    let rk4 = run_ok(&["run", RACKET, "--steps", "4", "--dt", "0.125"]);
    assert_ne!(rk4.lines().last(), csv.lines().last());
}

#[test]
fn run_and_check_exit_codes() {
    run_ok(&["check", RACKET, "lessons/01-the-loop.toml"]);
    let bad = |args: &[&str], needle: &str| {
        let output = tumble_cmd().args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "tumble {args:?}: {stderr}");
        assert!(
            stderr.contains(needle),
            "tumble {args:?}: `{needle}` not in {stderr}"
        );
        if args[0] == "run" {
            assert_eq!(stderr.trim().lines().count(), 1, "one line: {stderr}");
        }
    };
    bad(
        &["run", RACKET, "--steps", "1", "--integrator", "verlet"],
        "valid integrators: euler-seed, euler, symplectic-euler, rk4, splitting, exact-splitting, \
         exact-splitting-4",
    );
    bad(&["run", RACKET, "--steps", "1", "--dt=-1"], "--dt");
    bad(
        &["run", "no/such/scene.toml", "--steps", "1"],
        "no such file",
    );
    // Not a scene: the error names file:line:column.
    bad(
        &["check", "tests/fixtures/tetrahedron.obj"],
        "tetrahedron.obj:2:3:",
    );
}

// ---------------------------------------------------------------------------------------------
// Order of accuracy, on a body whose inertia is not diagonal
// ---------------------------------------------------------------------------------------------

/// The off-centre point body (I_body not diagonal, principal frame not the body frame),
/// spinning about a general axis, under gravity and drag.
fn lopsided(integrator: Integrator, dt: f64) -> World {
    let (points, masses) = off_centre_points();
    let body = Body::from_points(&points, &masses, 0.0, Vec::new()).unwrap();
    let state = state_from_velocities(
        &body,
        Vector3::new(0.0, 2.0, 0.0),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.7),
        Vector3::new(1.0, 3.0, 0.0),
        Vector3::new(1.0, -2.0, 3.0),
    );
    let effects = vec![
        Effect::Gravity(GRAVITY),
        Effect::Drag {
            linear: 0.2,
            angular: 0.3,
        },
    ];
    world(body, effects, integrator, dt, state)
}

/// Orientation error (rad) and barycenter error (m) after 1 s, against rk4 at dt = 1e-4.
fn errors_after_one_second(integrator: Integrator, dt: f64) -> (f64, f64) {
    let run = |integrator, dt: f64| {
        let mut world = lopsided(integrator, dt);
        let steps = (1.0 / dt).round() as usize;
        for _ in 0..steps {
            world.step();
        }
        *world.state()
    };
    let reference = run(Integrator::Rk4, 1e-4);
    let state = run(integrator, dt);
    (
        state
            .orientation
            .quaternion()
            .angle_to(&reference.orientation.quaternion()),
        (state.position - reference.position).norm(),
    )
}

#[test]
fn each_integrator_converges_at_its_stated_order() {
    // Halving dt divides a p-th order method's global error by 2^p. The reference is rk4 at
    // dt = 1e-4, whose own error (~(|ω| dt)⁴) is far below every error measured here.
    for (integrator, dt) in [
        (Integrator::Euler, 4e-3),
        (Integrator::SymplecticEuler, 4e-3),
        (Integrator::Splitting, 4e-3),
        (Integrator::Rk4, 2e-2),
    ] {
        let (angle_coarse, position_coarse) = errors_after_one_second(integrator, dt);
        let (angle_fine, position_fine) = errors_after_one_second(integrator, dt / 2.0);
        let expected = f64::from(integrator.order());
        for (what, coarse, fine) in [
            ("orientation", angle_coarse, angle_fine),
            ("barycenter", position_coarse, position_fine),
        ] {
            if coarse < 1e-10 {
                // rk4's barycenter (a linear ODE here) is already at round-off.
                assert!(fine < 1e-10, "{}: {what} error {fine:e}", integrator.name());
                continue;
            }
            let order = (coarse / fine).log2();
            println!(
                "{}: {what} error {coarse:e} at dt {dt}, {fine:e} at dt/2: order {order:.2}",
                integrator.name()
            );
            assert!(
                (order - expected).abs() < 0.25,
                "{}: {what} converges at order {order:.3}, stated {expected}",
                integrator.name()
            );
        }
    }
}
