//! The *integrate* phase (the report's `Solve`): one step of a chosen integrator.
//!
//! Every integrator takes the state at the start of the step with what the derive and forces
//! phases computed from it (`start`, `loads`) and returns the state one step `dt` later.
//! One file per method; each module doc gives its update equations, its order and what it
//! conserves or breaks.

mod euler;
mod euler_seed;
mod rk4;
mod splitting;
mod symplectic_euler;

use super::body::Body;
use super::derive::Kinematics;
use super::effects::{Effects, Loads};
use super::state::{Orientation, State};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// The integrators `tumble` offers, selectable by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// The original loop: explicit Euler on (x, R, P, L), R a plain matrix.
    EulerSeed,
    /// Explicit Euler with a unit quaternion, renormalised each step.
    Euler,
    /// Semi-implicit Euler: momenta first, then positions with the new velocities.
    SymplecticEuler,
    /// Classical fourth-order Runge–Kutta over the whole state.
    Rk4,
    /// Kick–drift–kick with the free rotation split into exact rotations about the principal axes.
    Splitting,
}

impl Integrator {
    /// Every integrator, in teaching order.
    pub const ALL: [Integrator; 5] = [
        Integrator::EulerSeed,
        Integrator::Euler,
        Integrator::SymplecticEuler,
        Integrator::Rk4,
        Integrator::Splitting,
    ];

    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::EulerSeed => "euler-seed",
            Integrator::Euler => "euler",
            Integrator::SymplecticEuler => "symplectic-euler",
            Integrator::Rk4 => "rk4",
            Integrator::Splitting => "splitting",
        }
    }

    /// The integrator with this name.
    pub fn from_name(name: &str) -> Option<Integrator> {
        Integrator::ALL.into_iter().find(|i| i.name() == name)
    }

    /// Every valid name, comma-separated (for error messages).
    pub fn names() -> String {
        Integrator::ALL.map(Integrator::name).join(", ")
    }

    /// Order of accuracy of the global error.
    pub fn order(self) -> u32 {
        match self {
            Integrator::EulerSeed | Integrator::Euler | Integrator::SymplecticEuler => 1,
            Integrator::Splitting => 2,
            Integrator::Rk4 => 4,
        }
    }

    /// The next integrator in [`Integrator::ALL`], wrapping around.
    pub fn next(self) -> Integrator {
        let i = Integrator::ALL.iter().position(|&x| x == self).unwrap_or(0);
        Integrator::ALL[(i + 1) % Integrator::ALL.len()]
    }

    /// The orientation representation this integrator steps.
    pub fn orientation_for(self, orientation: &Orientation) -> Orientation {
        match self {
            Integrator::EulerSeed => orientation.as_matrix(),
            _ => orientation.as_quaternion(),
        }
    }

    /// The *forces* phase as this integrator's loop computes it: F and τ of the declared effects
    /// and, for `euler-seed`, the report's per-vertex torque sum `Σᵢ (R r₀ᵢ) × F` added to τ
    /// (the report computed it in its forces phase, `CalculDeriveeStateX`).
    pub fn loads(self, body: &Body, effects: &Effects, kinematics: &Kinematics) -> Loads {
        let mut loads = effects.loads(body, kinematics);
        if self == Integrator::EulerSeed {
            loads.torque += euler_seed::vertex_torque(body, &kinematics.rotation, &loads.force);
        }
        loads
    }

    /// One step of length `dt` from `state`, given the derive and forces phases' results there.
    #[inline]
    pub fn step(
        self,
        body: &Body,
        effects: &Effects,
        state: &State,
        start: &Kinematics,
        loads: &Loads,
        dt: f64,
    ) -> State {
        let mut next = *state;
        self.advance(body, effects, &mut next, start, loads, dt);
        next
    }

    /// [`Integrator::step`] in place: `state` becomes the state one step `dt` later (the loop's
    /// integrate phase uses this, so the state is not copied through a temporary).
    #[inline]
    pub fn advance(
        self,
        body: &Body,
        effects: &Effects,
        state: &mut State,
        start: &Kinematics,
        loads: &Loads,
        dt: f64,
    ) {
        match self {
            Integrator::EulerSeed => euler_seed::step(state, start, loads, dt),
            Integrator::Euler => euler::step(state, start, loads, dt),
            Integrator::SymplecticEuler => symplectic_euler::step(body, state, start, loads, dt),
            Integrator::Rk4 => *state = rk4::step(body, effects, state, start, loads, dt),
            Integrator::Splitting => {
                *state = splitting::step(body, effects, state, start, loads, dt)
            }
        }
    }
}

/// The quaternion of a state; the matrix form is only stepped by `euler-seed`.
#[inline]
fn quaternion_of(state: &State) -> UnitQuaternion<f64> {
    state.orientation.quaternion()
}

/// `q̇ = ½ ω ⊗ q` (ω world frame, q body → world), as a plain quaternion.
#[inline]
fn quaternion_rate(omega: &Vector3<f64>, q: &Quaternion<f64>) -> Quaternion<f64> {
    Quaternion::from_imag(*omega) * q * 0.5
}

/// One explicit step `q + dt·q̇`, renormalised.
#[inline]
fn advance_quaternion(
    q: &UnitQuaternion<f64>,
    omega: &Vector3<f64>,
    dt: f64,
) -> UnitQuaternion<f64> {
    let q = q.quaternion();
    normalize(q + quaternion_rate(omega, q) * dt)
}

/// `q / |q|`, with one division.
#[inline]
fn normalize(q: Quaternion<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::new_unchecked(q * (1.0 / q.norm()))
}

/// The rotation matrix of a quaternion that need not be unit (it is normalised on the way):
///
/// ```text
/// s = 2 / |q|²,   R = ⎡1 − s(y²+z²)   s(xy − wz)    s(xz + wy) ⎤
///                     ⎢s(xy + wz)     1 − s(x²+z²)  s(yz − wx) ⎥
///                     ⎣s(xz − wy)     s(yz + wx)    1 − s(x²+y²)⎦
/// ```
#[inline]
fn rotation_of(q: &Quaternion<f64>) -> nalgebra::Matrix3<f64> {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    let s = 2.0 / (w * w + x * x + y * y + z * z);
    let (xs, ys, zs) = (x * s, y * s, z * s);
    let (wx, wy, wz) = (w * xs, w * ys, w * zs);
    let (xx, xy, xz) = (x * xs, x * ys, x * zs);
    let (yy, yz, zz) = (y * ys, y * zs, z * zs);
    nalgebra::Matrix3::new(
        1.0 - (yy + zz),
        xy - wz,
        xz + wy,
        xy + wz,
        1.0 - (xx + zz),
        yz - wx,
        xz - wy,
        yz + wx,
        1.0 - (xx + yy),
    )
}
