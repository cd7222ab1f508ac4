//! A read-only snapshot of every quantity a user is shown, after a phase of the loop.
//!
//! Mid-frame, the loop's own variables are shown as the loop holds them: after *integrate*,
//! ω and I⁻¹_world are still those the *derive* phase computed at the start of the frame, which
//! is exactly why the phase order matters. Between frames (after *collide*, or at t = 0) they
//! are those of the current state, i.e. what the next *derive* will compute.

use super::cloth::ClothIntegrator;
use super::collision::geometry::{deepest, shape_shape, ContactPoint, Pose, Shape};
use super::collision::impulse::StepReport;
use super::collision::{Against, Contact, ContactModel, Obstacle, Outline};
use super::derive::{congruence, derive};
use super::effects::Effects;
pub use super::energy::{energy, kinetic_energy, kinetic_energy_with, Energy};
use super::energy_ledger::EnergyBalance;
use super::hand::{Hand, Pull};
use super::integrators::Integrator;
use super::joints::drive::Drive;
use super::joints::written::Measure;
use super::joints::{coordinate, rate, Motor, Pose as LinkPose};
use super::state::State;
use super::wire::wire;
use super::world::{Phase, World};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Every loop quantity after a phase.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// The phase just completed (None at t = 0).
    pub phase: Option<Phase>,
    /// The phase that runs next.
    pub next_phase: Phase,
    /// Completed steps, and simulated time t = step·dt, s.
    pub step: u64,
    pub time: f64,
    pub dt: f64,
    pub integrator: Integrator,
    /// Barycenter x, m.
    pub position: Vector3<f64>,
    /// R, body → world (for `euler-seed`, the drifted matrix itself).
    pub rotation: Matrix3<f64>,
    /// q (w, x, y, z), or the nearest rotation to R for `euler-seed`.
    pub quaternion: UnitQuaternion<f64>,
    /// P, kg·m/s and L, kg·m²/s (world frame); L in the body frame is Rᵀ L.
    pub linear_momentum: Vector3<f64>,
    pub angular_momentum: Vector3<f64>,
    pub angular_momentum_body: Vector3<f64>,
    /// v = P/M, m/s.
    pub velocity: Vector3<f64>,
    /// ω world frame and ω_body = Rᵀ ω, rad/s.
    pub angular_velocity: Vector3<f64>,
    pub angular_velocity_body: Vector3<f64>,
    /// I_body, I_world = R I_body Rᵀ, I⁻¹_world (the loop's), kg·m² and 1/(kg·m²).
    pub inertia_body: Matrix3<f64>,
    pub inertia_world: Matrix3<f64>,
    pub inv_inertia_world: Matrix3<f64>,
    /// F, N and τ about the barycenter, N·m (world frame).
    pub force: Vector3<f64>,
    pub torque: Vector3<f64>,
    /// The contacts' force and torque about the barycenter on this body (world frame), N and
    /// N·m: the last collide phase's impulses over dt (see [`contact_loads`]).
    pub contact_force: Vector3<f64>,
    pub contact_torque: Vector3<f64>,
    /// Energy now and at t = 0.
    pub energy: Energy,
    pub initial_energy: Energy,
    /// The whole scene's E − E₀ split into drag work, contacts and the numerical drift (the
    /// energy ledger).
    pub energy_balance: EnergyBalance,
    /// ‖RᵀR − 𝟙‖.
    pub orthonormality_error: f64,
    /// Vertex positions pᵢ = x + R r₀ᵢ, m.
    pub vertices: Vec<Vector3<f64>>,
    /// Contacts handled by the last collide phase.
    pub contacts: Vec<Contact>,
    /// Deepest depth of the body inside any obstacle or other body, ≥ 0, m.
    pub penetration: f64,
    /// Which body the fields above describe: its index and name.
    pub body_index: usize,
    pub body_name: String,
    /// Every body, for drawing and for its numbers (the one above included).
    pub bodies: Vec<BodyView>,
    /// Every obstacle: the scene's fixed things that are not bodies, each with its shape
    /// (ground, ramp, sphere, box), as the collide phase meets them.
    pub obstacles: Vec<Obstacle>,
    /// Every fixed thing the front ends draw and frame: the obstacles, then the fixed bodies
    /// in body order (see [`FixedView`]).
    pub fixed: Vec<FixedView>,
    /// The whole scene: total momenta and energy.
    pub system: SystemTotals,
    /// Every cloth's numbers (empty without cloths).
    pub cloths: Vec<ClothView>,
    /// Every joint (empty without `[[joint]]`).
    pub joints: Vec<JointView>,
    /// Every spring (empty without `[[spring]]`).
    pub springs: Vec<SpringView>,
    /// The energy the joints' correction changed since t = 0, J (numerical, in the drift).
    pub joint_correction_work: f64,
    /// The declared effects (gravity, drag, …).
    pub effects: Effects,
    /// The contact parameters, if the scene declares contact.
    pub contact_model: Option<ContactModel>,
    /// What the `impulse` solver did in the last collide phase (work, unconverged residual).
    pub contact_report: StepReport,
    /// Every body's state, in order (the ruler and the protractor read their points from them).
    pub states: Vec<State>,
    /// The hand while a body is held (the mouse's drag spring), and its pull now.
    pub hand: Option<Hand>,
    pub hand_pull: Option<Pull>,
}

/// A joint as the panels, `walk` and `run --joint` show it.
#[derive(Debug, Clone, PartialEq)]
pub struct JointView {
    pub name: String,
    /// ball, hinge, fixed, distance, slider.
    pub kind: &'static str,
    /// Its first body's name, and the second's (None: the world).
    pub bodies: (String, Option<String>),
    /// The same bodies' indices.
    pub body_indices: (usize, Option<usize>),
    /// The anchor points now, world frame: on the first body, on the second (or the world).
    pub anchors: [Vector3<f64>; 2],
    /// The anchor points in their bodies' frames (the second in the world's without one).
    pub local_anchors: [Vector3<f64>; 2],
    /// Hinge: the axis now (the first body's), world frame; slider: the rail's (the second
    /// body's or the world's).
    pub axis: Option<Vector3<f64>>,
    /// Distance: the rod's length, m.
    pub length: Option<f64>,
    /// Position error, m: ball, hinge, fixed: |anchor A − anchor B|; distance:
    /// |separation − length|.
    pub error: f64,
    /// The reaction on the first body, N: averaged over the last step (impulse / dt), or at
    /// t = 0 the instantaneous one.
    pub force: Vector3<f64>,
    /// Its torque about the first body's barycenter, N·m (same convention).
    pub torque: Vector3<f64>,
    /// Hinge and slider: the coordinate q now and its rate q̇ (hinge: the angle from the
    /// t = 0 pose, rad, and rad/s; slider: the travel, m, and m/s).
    pub coordinate: Option<(f64, f64)>,
    /// What the coordinate measures (an angle, rad, or a travel, m); None without one.
    pub measure: Option<Measure>,
    /// Its limits [lo, hi] (rad or m).
    pub limits: Option<[f64; 2]>,
    /// Its motor.
    pub motor: Option<Motor>,
    /// What the limit and the motor applied over the last step, along the axis on the first
    /// body (N or N·m; part of `force` and `torque`).
    pub drive: Drive,
}

/// A spring as the panels and `walk` show it.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringView {
    pub name: String,
    pub bodies: (String, Option<String>),
    /// The same bodies' indices.
    pub body_indices: (usize, Option<usize>),
    /// Its ends in their bodies' frames (the second in the world's without one).
    pub local_anchors: [Vector3<f64>; 2],
    /// Its ends now, world frame.
    pub ends: [Vector3<f64>; 2],
    /// |d|, m.
    pub length: f64,
    pub rest_length: f64,
    /// Hooke's part k (|d| − ℓ₀), N (> 0 stretched).
    pub tension: f64,
    /// ½ k (|d| − ℓ₀)², J.
    pub potential: f64,
}

impl JointView {
    /// Every joint of a world.
    pub fn all(world: &World) -> Vec<JointView> {
        let links = world.links();
        if links.joints.is_empty() {
            return Vec::new();
        }
        let states = world.states();
        let names = world.body_names();
        let bodies = world.bodies();
        let instant = (world.step_count() == 0).then(|| world.system_loads_now().1);
        links
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| {
                let load = match &instant {
                    Some(loads) => loads[i],
                    None => world.joint_load(i),
                };
                let pose = |i: usize| {
                    let k = derive(&bodies[i], &states[i]);
                    LinkPose {
                        x: states[i].position,
                        r: k.rotation,
                        v: k.velocity,
                        w: k.angular_velocity,
                    }
                };
                let (pa, pb) = (pose(j.a), j.b.map_or(LinkPose::WORLD, pose));
                JointView {
                    name: j.name.clone(),
                    kind: j.kind.name(),
                    bodies: (names[j.a].clone(), j.b.map(|b| names[b].clone())),
                    body_indices: (j.a, j.b),
                    anchors: j.anchors(states),
                    local_anchors: [j.anchor_a, j.anchor_b],
                    axis: j.drawn_axis(&pa, &pb),
                    length: j
                        .kind
                        .written()
                        .keys
                        .contains(&"length")
                        .then_some(j.length),
                    error: j.error(states),
                    force: load.force,
                    torque: load.torque,
                    coordinate: coordinate(j, i, &pa, &pb)
                        .map(|(row, q)| (q, rate(&row, &pa, &pb))),
                    measure: j.kind.measure(),
                    limits: j.limits,
                    motor: j.motor,
                    drive: world.joint_drive(i),
                }
            })
            .collect()
    }
}

impl SpringView {
    /// Every spring of a world.
    pub fn all(world: &World) -> Vec<SpringView> {
        let states = world.states();
        let names = world.body_names();
        world
            .links()
            .springs
            .iter()
            .map(|s| {
                let a = LinkPose::of_state(&states[s.a]);
                let b =
                    s.b.map_or(LinkPose::WORLD, |b| LinkPose::of_state(&states[b]));
                let load = s.load(&a, &b).0;
                SpringView {
                    name: s.name.clone(),
                    bodies: (names[s.a].clone(), s.b.map(|b| names[b].clone())),
                    body_indices: (s.a, s.b),
                    local_anchors: [s.anchor_a, s.anchor_b],
                    ends: load.ends,
                    length: load.length,
                    rest_length: s.rest_length,
                    tension: s.stiffness * (load.length - s.rest_length),
                    potential: load.potential,
                }
            })
            .collect()
    }
}

/// What a table shows of one cloth.
#[derive(Debug, Clone, PartialEq)]
pub struct ClothView {
    pub name: String,
    pub integrator: &'static str,
    /// The same particle integrator (its formulas).
    pub method: ClothIntegrator,
    /// Particles along the sheet's two sides: particle (i, j) is `positions[j·nx + i]`.
    pub grid: [usize; 2],
    /// Every particle's position now, m, and velocity, m/s.
    pub positions: Vec<Vector3<f64>>,
    pub velocities: Vec<Vector3<f64>>,
    /// Which particles are pinned.
    pub pins: Vec<bool>,
    pub particles: usize,
    pub springs: usize,
    pub pinned: usize,
    /// Largest (ℓ − ℓ₀)/ℓ₀ over the springs, as a percentage.
    pub max_stretch_percent: f64,
    /// T and U, J.
    pub kinetic: f64,
    pub spring: f64,
    /// Largest particle speed, m/s.
    pub max_speed: f64,
    /// 2/ω_max at rest, s, and the damped limit h* (see `cloth::stability`), s.
    pub stiffness_limit: f64,
    pub explicit_limit: f64,
    /// Particle–body contacts in the last collide phase.
    pub body_contacts: usize,
    /// Particle–obstacle contacts in the last step: velocity pass (integrate), position pass
    /// (collide).
    pub obstacle_contacts: [usize; 2],
    /// Whether the particle integrator is explicit (then bounded by `explicit_limit`).
    pub explicit: bool,
    /// Particles attached to bodies (`attach`).
    pub attached: usize,
    /// The force the attachments gave the cloth over the last step (impulse / dt), N.
    pub attach_force: Vector3<f64>,
    /// The largest distance of an attached particle from its point on its body, m.
    pub attach_error: f64,
}

impl ClothView {
    /// The views of every cloth of a world now.
    pub fn all(world: &World) -> Vec<ClothView> {
        world
            .cloths()
            .iter()
            .enumerate()
            .map(|(k, c)| {
                let limit = world.cloth_limit(k);
                ClothView {
                    name: c.name.clone(),
                    integrator: c.integrator.name(),
                    method: c.integrator,
                    grid: c.count,
                    positions: c.positions.clone(),
                    velocities: c.velocities.clone(),
                    pins: c.pinned.clone(),
                    particles: c.len(),
                    springs: c.springs.len(),
                    pinned: c.pinned.iter().filter(|&&p| p).count(),
                    max_stretch_percent: 100.0 * c.max_stretch(),
                    kinetic: c.kinetic_energy(),
                    spring: c.spring_energy(),
                    max_speed: c.max_speed(),
                    stiffness_limit: limit.stiffness_limit(),
                    explicit_limit: limit.dt(),
                    body_contacts: world.cloth_body_contacts(k),
                    obstacle_contacts: world.cloth_obstacle_contacts(k),
                    explicit: c.integrator.is_explicit(),
                    attached: c.attached.len(),
                    attach_force: world.cloth_attach_load(k)[0],
                    attach_error: world.attach_error(k),
                }
            })
            .collect()
    }
}

impl ClothView {
    /// The index of particle (i, j).
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.grid[0] + i
    }

    /// The (i, j) of particle `k`.
    pub fn cell(&self, k: usize) -> (usize, usize) {
        (k % self.grid[0], k / self.grid[0])
    }
}

/// What a view needs to draw one body, and its numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyView {
    pub name: String,
    /// Barycenter x, m.
    pub position: Vector3<f64>,
    /// v = P/M and ω = I⁻¹_world L (world frame), m/s and rad/s: between frames those of the
    /// current state (what the next *derive* computes), mid-frame the loop's own (as the
    /// snapshot's top fields).
    pub velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
    /// P, kg·m/s and L about the barycenter, kg·m²/s (world frame).
    pub linear_momentum: Vector3<f64>,
    pub angular_momentum: Vector3<f64>,
    /// The radius of its bounding sphere about the barycenter, m.
    pub radius: f64,
    /// Its points in the body frame r₀ᵢ, and its edges (pairs of point indices).
    pub points_body: Vec<Vector3<f64>>,
    pub edges: Vec<(usize, usize)>,
    /// Vertex positions pᵢ = x + R r₀ᵢ, m (none for a round body: draw its `shape`).
    pub vertices: Vec<Vector3<f64>>,
    /// R, body → world.
    pub rotation: Matrix3<f64>,
    /// The contact shape in the body frame (box, hull, ball, capsule, cylinder), so that a
    /// front end draws what the physics touches and never guesses from vertices.
    pub shape: Option<Shape>,
    /// Whether the body is fixed (drawn as an obstacle).
    pub fixed: bool,
    /// The body's own kinetic, potential and total energy.
    pub energy: Energy,
    /// M |g| |x|, J: the size of the terms `−M g·x` adds up (0 without gravity or when
    /// fixed). Positions carry a round-off of ε |x|, so this is the scale of the potential
    /// energy's round-off: a double pendulum hanging 1 m and 2 m from the origin has
    /// E − E₀ ≈ 1e-15 J of round-off while its V is only 1e-4 J.
    pub potential_scale: f64,
    /// M, kg (infinite or unused for a fixed body).
    pub mass: f64,
}

/// One fixed thing, as the front ends draw it and frame the view around it: an obstacle
/// (`body` None) or a fixed body (`body` its index in [`Snapshot::bodies`]), each by its
/// [`Outline`] in world coordinates. A fixed body's outline is [`Outline::Body`]: the wire
/// of its shape at its pose, its vertices and edges for a polyhedron.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedView {
    /// The obstacle's scene-file type (`ground`, `box`, …), or `body`.
    pub kind: &'static str,
    /// The fixed body's index in the snapshot's bodies (None for an obstacle).
    pub body: Option<usize>,
    pub outline: Outline,
    /// The corners (low, high) of a box the view must hold to show it (the ground's, an
    /// unbounded level, at the origin: see [`FixedView::bounds`]).
    extent: (Vector3<f64>, Vector3<f64>),
}

impl FixedView {
    /// The obstacles in the scene's order, then the fixed bodies in body order.
    pub fn all(obstacles: &[Obstacle], bodies: &[BodyView]) -> Vec<FixedView> {
        let origin = Vector3::zeros();
        let mut fixed: Vec<FixedView> = (obstacles.iter())
            .map(|o| FixedView {
                kind: o.kind(),
                body: None,
                outline: o.outline(),
                extent: o.bounds(&origin),
            })
            .collect();
        for (i, view) in bodies.iter().enumerate().filter(|(_, v)| v.fixed) {
            let wire = (view.shape.as_ref()).and_then(|s| wire(s, &view.position, &view.rotation));
            let (corners, edges) =
                wire.unwrap_or_else(|| (view.vertices.clone(), view.edges.clone()));
            let silhouette = match view.shape {
                Some(Shape::Ball { radius }) => Some(radius),
                _ => None,
            };
            // The box of its vertices, or of a round body's extreme points along the axes.
            let none = (
                Vector3::repeat(f64::INFINITY),
                Vector3::repeat(f64::NEG_INFINITY),
            );
            let extent = if view.points_body.is_empty() && view.shape.is_some() {
                let r = Vector3::repeat(view.radius);
                (view.position - r, view.position + r)
            } else {
                (view.vertices.iter()).fold(none, |(lo, hi), p| (lo.inf(p), hi.sup(p)))
            };
            fixed.push(FixedView {
                kind: "body",
                body: Some(i),
                outline: Outline::Body {
                    corners,
                    edges,
                    center: view.position,
                    radius: view.radius,
                    silhouette,
                },
                extent,
            });
        }
        fixed
    }

    /// The corners (low, high) of a box the view must hold to show this thing; `centre` is
    /// where the bodies are (the ground, unbounded, is held at its level there).
    pub fn bounds(&self, centre: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        match self.outline {
            Outline::Level(height) => {
                let p = Vector3::new(centre.x, height, centre.z);
                (p, p)
            }
            _ => self.extent,
        }
    }
}

/// The scene as a whole.
///
/// ```text
/// P_total = Σ P_b + Σ m_i v_i         L_total = Σ (x_b × P_b + L_b) + Σ x_i × m_i v_i
/// E_total = Σ E_b + Σ (T + U + V) of the cloths                        (about the origin)
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SystemTotals {
    pub linear_momentum: Vector3<f64>,
    pub angular_momentum: Vector3<f64>,
    pub energy: Energy,
    pub initial_energy: Energy,
}

impl SystemTotals {
    /// The totals of a world now.
    pub fn of(world: &World) -> SystemTotals {
        let mut linear_momentum = Vector3::zeros();
        let mut angular_momentum = Vector3::zeros();
        for s in world.states() {
            linear_momentum += s.linear_momentum;
            angular_momentum += s.position.cross(&s.linear_momentum) + s.angular_momentum;
        }
        for c in world.cloths() {
            linear_momentum += c.linear_momentum();
            angular_momentum += c.angular_momentum();
        }
        SystemTotals {
            linear_momentum,
            angular_momentum,
            energy: world.total_energy(),
            initial_energy: world.initial_total_energy(),
        }
    }
}

/// M |g| |x| of body `index` now (see [`BodyView::potential_scale`]).
fn potential_scale(world: &World, index: usize) -> f64 {
    let body = &world.bodies()[index];
    let scale = world.effects().gravity().map_or(0.0, |g| {
        body.mass * g.norm() * world.states()[index].position.norm()
    });
    if body.fixed || !scale.is_finite() {
        0.0
    } else {
        scale
    }
}

impl Snapshot {
    /// The obstacles among the fixed things, in the scene's order (obstacle i of a contact's
    /// `Against::Obstacle(i)` is the i-th).
    pub fn obstacles_fixed(&self) -> impl Iterator<Item = &FixedView> {
        self.fixed.iter().filter(|f| f.body.is_none())
    }

    /// The snapshot of a world after its last phase, the panels showing the first body.
    pub fn of(world: &World) -> Snapshot {
        Snapshot::of_body(world, 0)
    }

    /// The snapshot of a world after its last phase, the panels showing body `index`.
    pub fn of_body(world: &World, index: usize) -> Snapshot {
        if world.body_count() == 0 {
            return Snapshot::without_body(world);
        }
        let state = &world.states()[index];
        let body = &world.bodies()[index];
        let between_frames = matches!(world.last_phase(), None | Some(Phase::Collide));
        let (kinematics, loads) = if between_frames {
            let kinematics = derive(body, state);
            let loads = if world.links().is_empty() {
                world.integrator().loads(body, world.effects(), &kinematics)
            } else {
                world.system_loads_now().0[index]
            };
            (kinematics, loads)
        } else {
            (*world.kinematics_of(index), *world.loads_of(index))
        };
        let rotation = state.orientation.matrix();
        let (contact_force, contact_torque) = contact_loads(world.contacts(), index, world.dt());
        let vertices = world.vertices_of(index);
        let penetration = geometric_penetration(world, index, &vertices);
        let bodies: Vec<BodyView> = (0..world.body_count())
            .map(|i| {
                if i == index {
                    BodyView::with(world, i, kinematics, vertices.clone())
                } else {
                    BodyView::of(world, i)
                }
            })
            .collect();
        // The scene's fields are the scene-only snapshot's; the body's replace its zeros.
        Snapshot {
            position: state.position,
            rotation,
            quaternion: state.orientation.quaternion(),
            linear_momentum: state.linear_momentum,
            angular_momentum: state.angular_momentum,
            angular_momentum_body: rotation.transpose() * state.angular_momentum,
            velocity: kinematics.velocity,
            angular_velocity: kinematics.angular_velocity,
            angular_velocity_body: rotation.transpose() * kinematics.angular_velocity,
            inertia_body: body.inertia_body,
            inertia_world: congruence(&rotation, &body.inertia_body),
            inv_inertia_world: kinematics.inv_inertia_world,
            force: loads.force,
            torque: loads.torque,
            contact_force,
            contact_torque,
            energy: energy(body, world.effects(), state),
            initial_energy: energy(body, world.effects(), &world.initial_states()[index]),
            orthonormality_error: state.orientation.orthonormality_error(),
            vertices,
            contacts: world.contacts().to_vec(),
            penetration,
            body_index: index,
            body_name: world.body_names()[index].clone(),
            fixed: FixedView::all(world.obstacles(), &bodies),
            bodies,
            ..Snapshot::without_body(world)
        }
    }
}

impl Snapshot {
    /// The scene's fields of a world (phase, clock, ledger, obstacles, totals, cloths, joints,
    /// springs, effects, contact model and report, states, hand), the body fields zeros (a
    /// body at rest at the origin, no mass): a world of cloths only, and the base
    /// [`Snapshot::of_body`] puts a body's fields on.
    fn without_body(world: &World) -> Snapshot {
        let zero = Vector3::zeros();
        let state = world.state();
        Snapshot {
            phase: world.last_phase(),
            next_phase: world.next_phase(),
            step: world.step_count(),
            time: world.time(),
            dt: world.dt(),
            integrator: world.integrator(),
            position: state.position,
            rotation: Matrix3::identity(),
            quaternion: UnitQuaternion::identity(),
            linear_momentum: zero,
            angular_momentum: zero,
            angular_momentum_body: zero,
            velocity: zero,
            angular_velocity: zero,
            angular_velocity_body: zero,
            inertia_body: Matrix3::zeros(),
            inertia_world: Matrix3::zeros(),
            inv_inertia_world: Matrix3::zeros(),
            force: zero,
            torque: zero,
            contact_force: zero,
            contact_torque: zero,
            energy: Energy::default(),
            initial_energy: Energy::default(),
            energy_balance: world.energy_balance(),
            orthonormality_error: 0.0,
            vertices: Vec::new(),
            contacts: Vec::new(),
            penetration: 0.0,
            body_index: 0,
            body_name: String::new(),
            bodies: Vec::new(),
            obstacles: world.obstacles().to_vec(),
            fixed: FixedView::all(world.obstacles(), &[]),
            system: SystemTotals::of(world),
            cloths: ClothView::all(world),
            joints: JointView::all(world),
            springs: SpringView::all(world),
            joint_correction_work: world.energy_ledger().joint_correction,
            effects: world.effects().clone(),
            contact_model: world.contact_model().copied(),
            contact_report: world.contact_report(),
            states: world.states().to_vec(),
            hand: world.hand().copied(),
            hand_pull: world.hand_pull(),
        }
    }
}

/// The contacts' force and torque on body `index`, N and N·m (world frame): the impulses the
/// last collide phase applied, over dt, summed over the body's contacts, as A (impulse J, lever
/// r_A) and as B (−J, lever r_B), the torque about the barycenter.
///
/// ```text
/// F_c = Σ J / dt        τ_c = Σ r × J / dt
/// ```
///
/// A mean over the step: a resting contact gives F_c = −(the other forces), e.g. M g up for
/// a box on the ground. For `seed` the impulse is its change of the whole momentum and the
/// lever is measured from the initial barycenter (the report's), so τ_c is about x₀.
pub fn contact_loads(contacts: &[Contact], index: usize, dt: f64) -> (Vector3<f64>, Vector3<f64>) {
    let mut impulse = Vector3::zeros();
    let mut moment = Vector3::zeros();
    for c in contacts {
        if c.body == index {
            impulse += c.impulse;
            moment += c.lever.cross(&c.impulse);
        } else if c.against == Against::Body(index) {
            impulse -= c.impulse;
            moment -= c.lever_other.cross(&c.impulse);
        }
    }
    if dt > 0.0 {
        (impulse / dt, moment / dt)
    } else {
        (Vector3::zeros(), Vector3::zeros())
    }
}

/// Deepest geometric depth of body `index` inside any obstacle or other body, ≥ 0, m: the
/// contact geometry's depth (vertices, edges and faces alike, so a pillar inside a plate's
/// face counts). A body without a convex shape falls back to its vertices against obstacles.
///
/// ```text
/// penetration = max(0, max over obstacles and other bodies B of depth(shape ∩ B))
/// ```
pub fn geometric_penetration(world: &World, index: usize, vertices: &[Vector3<f64>]) -> f64 {
    let bodies = world.bodies();
    let states = world.states();
    let Some(shape) = &bodies[index].shape else {
        return deepest_penetration(world.obstacles(), vertices);
    };
    let pose = pose_of(&states[index]);
    let mut points: Vec<ContactPoint> = Vec::new();
    let mut depth: f64 = 0.0;
    for obstacle in world.obstacles() {
        points.clear();
        obstacle.contact(shape, &pose, 0.0, &mut points);
        depth = depth.max(deepest(&points));
    }
    for (other, (body, state)) in bodies.iter().zip(states).enumerate() {
        let Some(other_shape) = body.shape.as_ref().filter(|_| other != index) else {
            continue;
        };
        let reach = shape.bounding_radius() + other_shape.bounding_radius();
        if (state.position - pose.position).norm_squared() > reach * reach {
            continue;
        }
        points.clear();
        shape_shape(shape, &pose, other_shape, &pose_of(state), 0.0, &mut points);
        depth = depth.max(deepest(&points));
    }
    depth
}

/// Where a body's shape is.
fn pose_of(state: &State) -> Pose {
    Pose {
        position: state.position,
        rotation: state.orientation.matrix(),
    }
}

/// Deepest depth of any vertex inside any obstacle (0 when none is inside): the report's
/// per-vertex measure (what `seed` sees; faces and edges escape it).
pub fn deepest_penetration(obstacles: &[Obstacle], vertices: &[Vector3<f64>]) -> f64 {
    let mut deepest: f64 = 0.0;
    for obstacle in obstacles {
        for p in vertices {
            deepest = deepest.max(obstacle.depth(p));
        }
    }
    deepest
}

// ---------------------------------------------------------------------------------------------
// The front ends' own reads (issue #36, item 4). Beside a whole `Snapshot`, the session, `diff`
// and `study` measure a few things per step or per sample; each is a small typed view built
// here, so that no front end reads the world's bodies, cloths, obstacles or links itself
// (`tests/commands/read_path.rs` scans for it). Every number is the one the snapshot shows.
// ---------------------------------------------------------------------------------------------

/// The methods a world runs with: what compare mode offers and swaps, what the page's
/// settings note names, and what the live numbers were simulated with.
#[derive(Debug, Clone, PartialEq)]
pub struct Methods {
    /// The bodies' integrator.
    pub integrator: Integrator,
    /// The collision response (None without contact).
    pub response: Option<super::collision::Response>,
    /// Every cloth's particle integrator, in order (empty without cloths).
    pub cloths: Vec<ClothIntegrator>,
}

impl Methods {
    /// The methods of a world now.
    pub fn of(world: &World) -> Methods {
        Methods {
            integrator: world.integrator(),
            response: world.contact_model().map(|m| m.response),
            cloths: world.cloths().iter().map(|c| c.integrator).collect(),
        }
    }
}

impl BodyView {
    /// Body `index` of a world now, as [`Snapshot::of_body`] shows it: between frames its
    /// kinematics derived from the current state, mid-frame the loop's own.
    pub fn of(world: &World, index: usize) -> BodyView {
        let between_frames = matches!(world.last_phase(), None | Some(Phase::Collide));
        let kinematics = if between_frames {
            derive(&world.bodies()[index], &world.states()[index])
        } else {
            *world.kinematics_of(index)
        };
        BodyView::with(world, index, kinematics, world.vertices_of(index))
    }

    /// Every body of a world now (see [`BodyView::of`]).
    pub fn all(world: &World) -> Vec<BodyView> {
        (0..world.body_count())
            .map(|i| BodyView::of(world, i))
            .collect()
    }

    /// Body `index` with the given kinematics (ω, v) and vertices.
    fn with(
        world: &World,
        i: usize,
        k: super::derive::Kinematics,
        vertices: Vec<Vector3<f64>>,
    ) -> BodyView {
        let body = &world.bodies()[i];
        let state = &world.states()[i];
        BodyView {
            name: world.body_names()[i].clone(),
            position: state.position,
            velocity: k.velocity,
            angular_velocity: k.angular_velocity,
            linear_momentum: state.linear_momentum,
            angular_momentum: state.angular_momentum,
            radius: body.radius,
            points_body: body.points_body.clone(),
            edges: body.edges.clone(),
            vertices,
            rotation: state.orientation.matrix(),
            shape: body.shape.clone(),
            fixed: body.fixed,
            energy: world.body_energy(i),
            potential_scale: potential_scale(world, i),
            mass: body.mass,
        }
    }

    /// ω in the body frame, Rᵀ ω, rad/s.
    pub fn angular_velocity_body(&self) -> Vector3<f64> {
        self.rotation.transpose() * self.angular_velocity
    }
}

/// The deepest depth of any vertex of body `index` inside any obstacle now, ≥ 0, m: the
/// per-vertex measure of [`deepest_penetration`] (what `seed` sees), without the body's other
/// numbers.
pub fn vertex_penetration(world: &World, index: usize) -> f64 {
    deepest_penetration(world.obstacles(), &world.vertices_of(index))
}

/// Every particle of every cloth now, cloth after cloth, m.
pub fn particle_positions(world: &World) -> Vec<Vector3<f64>> {
    world
        .cloths()
        .iter()
        .flat_map(|c| c.positions.iter().copied())
        .collect()
}
