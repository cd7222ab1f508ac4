//! The *integrate* phase (the report's `Solve`): one step of a chosen integrator.
//!
//! Every integrator takes the states of the whole system at the start of the step with what
//! the derive and forces phases computed from them (`system::Start`) and makes them the states
//! one step `dt` later. It is written once, against the system's derivative (`system`): a
//! world without springs or joints is a system whose evaluation is per body. One file per
//! method; each module doc gives its update equations, its order and what it conserves or
//! breaks.

pub mod system;

pub use euler_seed::vertex_torque;

use super::body::Body;
use super::derive::Kinematics;
use super::effects::{Effects, Loads};
use super::state::{Orientation, State};
use super::system::System;
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use system::{Buffers, Start};

/// Everything the front ends say about an integrator, in one place: the scene-file name, the
/// order, the formulas the loop strip shows, the README's row, the study's colour. Adding an
/// integrator is its file (its `DESCRIPTOR` and a `step` over the whole system: a
/// `system::Method` run by `system::advance`, or a loop over the moving bodies) and one line
/// `Variant => module` in `integrators!` (a missing `DESCRIPTOR` or `step` does not compile),
/// plus its row in the README's table (a test checks it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Descriptor {
    /// The name used in scene files and on the command line.
    pub name: &'static str,
    /// Order of accuracy of the global error when torques act.
    pub order: u32,
    /// What it is, in one line (the README's integrator table).
    pub summary: &'static str,
    /// What it keeps (the README's integrator table).
    pub keeps: &'static str,
    /// How the orientation turns, as the loop strip's forces phase shows it.
    pub rate: &'static str,
    /// The update, as the loop strip's integrate phase shows it.
    pub formula: &'static str,
    /// Its colour in the study's chart and SVG, (r, g, b).
    pub colour: (u8, u8, u8),
    /// Exact (to round-off, at any dt) when nothing exerts a torque and no drag acts: a free
    /// body, or one under uniform gravity. Its error there is round-off, not truncation, and
    /// has no order to fit.
    pub exact_without_torque: bool,
    /// How far a body's position moves under a constant extra force F over a step, in units
    /// of h²F/M: what the method makes of an impulse J = F h applied as ΔV = J/M after the
    /// step (`cloth_coupling`'s ties). Symplectic Euler drifts with the new velocity: 1;
    /// rk4 and the kick–drift–kick splittings: ½; explicit Euler: 0.
    pub position_factor: f64,
}

/// Declares the integrators from one list, `Variant => module`: the modules, the enum,
/// [`Integrator::ALL`] (so that none can be left out of the `i` cycle, the study and the name
/// lookup), [`Integrator::descriptor`] (each module's `DESCRIPTOR`) and
/// [`Integrator::advance`] (each module's `step`).
macro_rules! integrators {
    ($($(#[$doc:meta])* $variant:ident => $module:ident,)*) => {
        $(mod $module;)*

        /// The integrators `tumble` offers, selectable by name.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Integrator {
            $($(#[$doc])* $variant,)*
        }

        impl Integrator {
            /// Every integrator, in teaching order.
            pub const ALL: [Integrator; [$(Integrator::$variant,)*].len()] =
                [$(Integrator::$variant,)*];

            /// Its descriptor.
            pub fn descriptor(self) -> &'static Descriptor {
                match self {
                    $(Integrator::$variant => &$module::DESCRIPTOR,)*
                }
            }

            /// One step of length `dt` of the whole system, in place: `states` become the
            /// states one step later, from the forces phase's results at the start (`start`);
            /// `buffers` says what the joints and springs did over the step.
            pub fn advance(
                self,
                system: &System,
                states: &mut [State],
                start: &Start,
                dt: f64,
                buffers: &mut Buffers,
            ) {
                match self {
                    $(Integrator::$variant => $module::step(system, states, start, dt, buffers),)*
                }
            }
        }
    };
}

integrators! {
    /// The original loop: explicit Euler on (x, R, P, L), R a plain matrix.
    EulerSeed => euler_seed,
    /// Explicit Euler with a unit quaternion, renormalised each step.
    Euler => euler,
    /// Semi-implicit Euler: momenta first, then positions with the new velocities.
    SymplecticEuler => symplectic_euler,
    /// Classical fourth-order Runge–Kutta over the whole state.
    Rk4 => rk4,
    /// Kick–drift–kick with the free rotation split into exact rotations about the principal axes.
    Splitting => splitting,
    /// Kick–drift–kick whose drift is the exact torque-free flow (Jacobi elliptic functions).
    ExactSplitting => exact_splitting,
    /// A fourth-order composition of `exact-splitting` (Omelyan, Mryglod & Folk 2002).
    ExactSplitting4 => exact_splitting_4,
}

/// The quaternion integrators' orientation rate, as the loop strip shows it.
const QUATERNION_RATE: &str = "q̇ = ½·ω⊗q   (how the orientation turns)";

impl Integrator {
    /// The name used in scene files and on the command line.
    pub fn name(self) -> &'static str {
        self.descriptor().name
    }

    /// The integrator with this name.
    pub fn from_name(name: &str) -> Option<Integrator> {
        Integrator::ALL.into_iter().find(|i| i.name() == name)
    }

    /// Every valid name, comma-separated (for error messages).
    pub fn names() -> String {
        Integrator::ALL.map(Integrator::name).join(", ")
    }

    /// How far a body moves under a constant extra force over a step, in h²F/M
    /// ([`Descriptor::position_factor`]).
    pub fn position_factor(self) -> f64 {
        self.descriptor().position_factor
    }

    /// Order of accuracy of the global error.
    pub fn order(self) -> u32 {
        self.descriptor().order
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
    #[inline]
    pub fn loads(self, body: &Body, effects: &Effects, kinematics: &Kinematics) -> Loads {
        let k = kinematics;
        self.loads_moving(body, effects, &k.rotation, &k.velocity, &k.angular_velocity)
    }

    /// [`Integrator::loads`] of a body turned by R moving at v and ω.
    #[inline]
    pub fn loads_moving(
        self,
        body: &Body,
        effects: &Effects,
        rotation: &Matrix3<f64>,
        velocity: &Vector3<f64>,
        angular_velocity: &Vector3<f64>,
    ) -> Loads {
        let mut loads = effects.loads_at(body, velocity, angular_velocity);
        if self == Integrator::EulerSeed {
            loads.torque += euler_seed::vertex_torque(body, rotation, &loads.force);
        }
        loads
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
