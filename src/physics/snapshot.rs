//! A read-only snapshot of every quantity a user is shown, after a phase of the loop.
//!
//! Mid-frame, the loop's own variables are shown as the loop holds them: after *integrate*,
//! ω and I⁻¹_world are still those the *derive* phase computed at the start of the frame, which
//! is exactly why the phase order matters. Between frames (after *collide*, or at t = 0) they
//! are those of the current state, i.e. what the next *derive* will compute.

use super::body::Body;
use super::collision::{Contact, Obstacle};
use super::derive::{congruence, derive};
use super::effects::Effects;
use super::energy_ledger::EnergyBalance;
use super::integrators::Integrator;
use super::state::State;
use super::world::{Phase, World};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Kinetic `½ M v·v + ½ ω·L`, potential `−M g·x` and their sum, J.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Energy {
    pub kinetic: f64,
    pub potential: f64,
    pub total: f64,
}

/// The energy of a state, measured from the state itself.
pub fn energy(body: &Body, effects: &Effects, state: &State) -> Energy {
    let kinetic = kinetic_energy(body, state);
    let potential = effects.potential_energy(body, &state.position);
    Energy {
        kinetic,
        potential,
        total: kinetic + potential,
    }
}

/// Kinetic energy `½ M v·v + ½ ω·L` of a state, J.
pub fn kinetic_energy(body: &Body, state: &State) -> f64 {
    let kinematics = derive(body, state);
    kinetic_energy_with(
        body,
        &kinematics.inv_inertia_world,
        &state.linear_momentum,
        &state.angular_momentum,
    )
}

/// `½ M v·v + ½ ω·L` with `v = P/M`, `ω = I⁻¹_world L` for a known `I⁻¹_world`: the same
/// arithmetic as [`kinetic_energy`], so the two agree to the last bit.
#[inline]
pub fn kinetic_energy_with(
    body: &Body,
    inv_inertia_world: &Matrix3<f64>,
    linear_momentum: &Vector3<f64>,
    angular_momentum: &Vector3<f64>,
) -> f64 {
    let velocity = linear_momentum * body.inv_mass;
    let angular_velocity = inv_inertia_world * angular_momentum;
    0.5 * body.mass * velocity.norm_squared() + 0.5 * angular_velocity.dot(angular_momentum)
}

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
    /// Energy now and at t = 0.
    pub energy: Energy,
    pub initial_energy: Energy,
    /// E − E₀ split into drag work, contacts and the numerical drift (the energy ledger).
    pub energy_balance: EnergyBalance,
    /// ‖RᵀR − 𝟙‖.
    pub orthonormality_error: f64,
    /// Vertex positions pᵢ = x + R r₀ᵢ, m.
    pub vertices: Vec<Vector3<f64>>,
    /// Contacts handled by the last collide phase.
    pub contacts: Vec<Contact>,
    /// Deepest vertex depth inside any obstacle, ≥ 0, m.
    pub penetration: f64,
}

impl Snapshot {
    /// The snapshot of a world after its last phase.
    pub fn of(world: &World) -> Snapshot {
        let state = world.state();
        let body = world.body();
        let between_frames = matches!(world.last_phase(), None | Some(Phase::Collide));
        let (kinematics, loads) = if between_frames {
            let kinematics = derive(body, state);
            (
                kinematics,
                world.integrator().loads(body, world.effects(), &kinematics),
            )
        } else {
            (*world.kinematics(), *world.loads())
        };
        let rotation = state.orientation.matrix();
        let vertices = world.vertices();
        let penetration = deepest_penetration(world.obstacles(), &vertices);
        let energy = world.energy_of(state);
        let initial_energy = world.energy_of(world.initial_state());
        let energy_balance = world.energy_ledger().balance(
            &initial_energy,
            &energy,
            world.effects().depends_on_velocity(),
            !world.obstacles().is_empty(),
        );
        Snapshot {
            phase: world.last_phase(),
            next_phase: world.next_phase(),
            step: world.step_count(),
            time: world.time(),
            dt: world.dt(),
            integrator: world.integrator(),
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
            energy,
            initial_energy,
            energy_balance,
            orthonormality_error: state.orientation.orthonormality_error(),
            vertices,
            contacts: world.contacts().to_vec(),
            penetration,
        }
    }
}

/// Deepest depth of any vertex inside any obstacle (0 when none is inside).
pub fn deepest_penetration(obstacles: &[Obstacle], vertices: &[Vector3<f64>]) -> f64 {
    let mut deepest: f64 = 0.0;
    for obstacle in obstacles {
        for p in vertices {
            deepest = deepest.max(obstacle.depth(p));
        }
    }
    deepest
}
