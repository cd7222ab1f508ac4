//! The *integrate* phase (the report's `Solve`): one step of a chosen integrator.
//!
//! Every integrator takes the states of the whole system at the start of the step with what
//! the derive and forces phases computed from them (`system::Start`) and makes them the states
//! one step `dt` later. It is written once, against the system's derivative (`system`): a
//! world without springs or joints is a system whose evaluation is per body. One file per
//! method; each module doc gives its update equations, its order and what it conserves or
//! breaks.

mod euler;
mod euler_seed;
mod exact_splitting;
mod exact_splitting_4;
mod rk4;
mod splitting;
mod symplectic_euler;
pub mod system;

pub use euler_seed::vertex_torque;

use super::body::Body;
use super::derive::Kinematics;
use super::effects::{Effects, Loads};
use super::state::{Orientation, State};
use super::system::System;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use system::{Buffers, Start};

/// Everything the front ends say about an integrator, in one place: the scene-file name, the
/// order, the formulas the loop strip shows, the README's row, the study's colour. Adding an
/// integrator is its file (a `step` over the whole system, from `system`'s pieces), one
/// variant in `integrators!`, one descriptor in [`Integrator::descriptor`] and one arm in
/// [`Integrator::advance`] (a missing one does not compile).
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

/// Declares the enum and [`Integrator::ALL`] from one list, so that no variant can be left out
/// of `ALL` (and so out of the `i` cycle, the study and the name lookup).
macro_rules! integrators {
    ($($(#[$doc:meta])* $variant:ident,)*) => {
        /// The integrators `tumble` offers, selectable by name.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum Integrator {
            $($(#[$doc])* $variant,)*
        }

        impl Integrator {
            /// Every integrator, in teaching order.
            pub const ALL: [Integrator; [$(Integrator::$variant,)*].len()] =
                [$(Integrator::$variant,)*];
        }
    };
}

integrators! {
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
    /// Kick–drift–kick whose drift is the exact torque-free flow (Jacobi elliptic functions).
    ExactSplitting,
    /// A fourth-order composition of `exact-splitting` (Omelyan, Mryglod & Folk 2002).
    ExactSplitting4,
}

/// The quaternion integrators' orientation rate, as the loop strip shows it.
const QUATERNION_RATE: &str = "q̇ = ½·ω⊗q   (how the orientation turns)";

impl Integrator {
    /// Its descriptor.
    pub fn descriptor(self) -> &'static Descriptor {
        match self {
            Integrator::EulerSeed => &Descriptor {
                name: "euler-seed",
                order: 1,
                summary: "the original report's loop: explicit Euler on x, the rotation *matrix* R, P and L",
                keeps: "nothing: R drifts away from a rotation",
                rate: "Ṙ = ω*·R   (ω* the cross-product matrix of ω: how R turns)",
                formula: "euler-seed: x += dt·v,  R += dt·ω*·R,  P += dt·F,  L += dt·τ   (R not re-orthonormalised)",
                colour: (200, 30, 30),
                position_factor: 0.0,
                exact_without_torque: false,
            },
            Integrator::Euler => &Descriptor {
                name: "euler",
                order: 1,
                summary: "explicit Euler with a unit quaternion",
                keeps: "L when torque-free; energy grows",
                rate: QUATERNION_RATE,
                formula: "euler: x += dt·v,  q += dt·½ω⊗q (renormalised),  P += dt·F,  L += dt·τ",
                colour: (230, 140, 0),
                position_factor: 0.0,
                exact_without_torque: false,
            },
            Integrator::SymplecticEuler => &Descriptor {
                name: "symplectic-euler",
                order: 1,
                summary: "momenta first, then positions with the new velocities",
                keeps: "bounded energy error in translation",
                rate: QUATERNION_RATE,
                formula: "symplectic-euler: P += dt·F, L += dt·τ first; then x += dt·P/M, q += dt·½ω⊗q with the new ω",
                colour: (30, 150, 60),
                position_factor: 1.0,
                exact_without_torque: false,
            },
            Integrator::Rk4 => &Descriptor {
                name: "rk4",
                order: 4,
                summary: "classical Runge–Kutta over the whole state",
                keeps: "very small drift at moderate dt",
                rate: QUATERNION_RATE,
                formula: "rk4: k₁…k₄ = f(X) at t, t+dt/2, t+dt/2, t+dt;  X += dt/6·(k₁ + 2k₂ + 2k₃ + k₄)",
                colour: (30, 80, 210),
                position_factor: 0.5,
                exact_without_torque: false,
            },
            Integrator::Splitting => &Descriptor {
                name: "splitting",
                order: 2,
                summary: "kick–drift–kick with the free rotation split into exact rotations about the principal axes",
                keeps: "L exactly, energy bounded (symplectic)",
                rate: QUATERNION_RATE,
                formula: "splitting: kick P,L by dt/2; drift x; exact rotations about the principal axes; kick dt/2",
                colour: (150, 40, 170),
                position_factor: 0.5,
                exact_without_torque: false,
            },
            Integrator::ExactSplitting => &Descriptor {
                name: "exact-splitting",
                order: 2,
                summary: "kick–drift–kick whose drift is the exact torque-free rotation (Jacobi elliptic functions)",
                keeps: "L and energy to round-off when torque-free, at any dt; exact under gravity",
                rate: QUATERNION_RATE,
                formula: "exact-splitting: kick P,L by dt/2; drift x and the exact free rotation (sn, cn, dn); kick dt/2",
                colour: (0, 160, 170),
                position_factor: 0.5,
                exact_without_torque: true,
            },
            Integrator::ExactSplitting4 => &Descriptor {
                name: "exact-splitting-4",
                order: 4,
                summary: "exact-splitting composed fourth order: five kicks, four exact free rotations (Omelyan–Mryglod–Folk)",
                keeps: "as exact-splitting; fourth order under drag",
                rate: QUATERNION_RATE,
                formula: "exact-splitting-4: kicks ξ,χ,1−2(ξ+χ),χ,ξ·dt around exact free rotations (1−2λ)/2,λ,λ,(1−2λ)/2·dt",
                colour: (120, 90, 20),
                position_factor: 0.5,
                exact_without_torque: true,
            },
        }
    }

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
    pub fn loads(self, body: &Body, effects: &Effects, kinematics: &Kinematics) -> Loads {
        let mut loads = effects.loads(body, kinematics);
        if self == Integrator::EulerSeed {
            loads.torque += euler_seed::vertex_torque(body, &kinematics.rotation, &loads.force);
        }
        loads
    }

    /// One step of length `dt` of the whole system, in place: `states` become the states one
    /// step later, from the forces phase's results at the start (`start`); `buffers` says
    /// what the joints and springs did over the step.
    pub fn advance(
        self,
        system: &System,
        states: &mut [State],
        start: &Start,
        dt: f64,
        buffers: &mut Buffers,
    ) {
        let (s, b) = (states, buffers);
        match self {
            Integrator::EulerSeed => euler_seed::step(system, s, start, dt, b),
            Integrator::Euler => euler::step(system, s, start, dt, b),
            Integrator::SymplecticEuler => symplectic_euler::step(system, s, start, dt, b),
            Integrator::Rk4 => rk4::step(system, s, start, dt, b),
            Integrator::Splitting => splitting::step(system, s, start, dt, b),
            Integrator::ExactSplitting => exact_splitting::step(system, s, start, dt, b),
            Integrator::ExactSplitting4 => exact_splitting_4::step(system, s, start, dt, b),
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
