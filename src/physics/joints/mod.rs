//! Joints and springs: what couples two bodies, or a body and the world.
//!
//! **Springs** are force elements. Between anchor points `p_A = x_A + R_A a_A` and
//! `p_B = x_B + R_B a_B` (world points when B is the world), with `d = p_B − p_A`, `n = d/|d|`:
//!
//! ```text
//! F_A = k (|d| − ℓ₀) n + c (ḋ·n) n,    F_B = −F_A        (Hooke, damping along the spring)
//! τ_A = r_A × F_A,                      τ_B = r_B × F_B   (r = R a, the lever from the barycenter)
//! V   = ½ k (|d| − ℓ₀)²                 (potential, part of the scene's energy)
//! P_c = −c (ḋ·n)²  ≤ 0                  (damping power, booked as drag work)
//! ```
//!
//! **Joints** are ideal constraints C(Y) = 0 held by forces computed inside the derivative
//! f(Y) — Lagrange multipliers — so every integrator steps the same constrained ODE
//! (`super::system`). With the stacked velocities `u = (v_A, ω_A, v_B, ω_B)`, each joint
//! gives rows `J` with `Ċ = J u`, and `W = diag(1/m, I⁻¹_world)` per body:
//!
//! ```text
//! u̇ = a_free + W Jᵀ λ            a_free = (F/m, I⁻¹(τ − ω × L)) of the applied loads
//! C̈ = J u̇ + J̇ u = 0        ⇒    (J W Jᵀ) λ = −(J a_free + J̇ u) − correction
//! Ṗ += J_linᵀ λ,   L̇ += J_angᵀ λ  (the reaction force and torque on each body)
//! ```
//!
//! `J W Jᵀ` is the effective mass the contact impulse already uses (`1/m_A + 1/m_B +
//! (r×n)·I⁻¹(r×n)` for one contact row): a contact solves it for an impulse that stops a
//! velocity, a joint for a force that keeps an acceleration on the constraint. The rows
//! (C, its gradient J, the bias J̇u: the constraint layer's `Row`, bounds (−∞, ∞)) of each
//! kind, with `r = R a` (one file per kind under `kinds`, with the same verbs):
//!
//! ```text
//! ball      C = x_A + r_A − x_B − r_B                    3 rows e_k: (e_k, r_A×e_k | −e_k, −r_B×e_k)
//!           J̇u = ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)
//! hinge     ball + u_A·t = 0 for t ∈ {p_B, q_B} ⊥ the axis u_B:   (0, u_A×t | 0, −u_A×t)
//!           J̇u = (ω_A − ω_B)·((ω_A×u_A)×t + u_A×(ω_B×t))
//! fixed     ball + the skew part of R_A (R_B R₀)ᵀ = 0:    3 rows (0, e_k | 0, −e_k),  J̇u = 0
//! distance  C = |d| − ℓ, d = p_A − p_B, n = d/|d|:       (n, r_A×n | −n, −r_B×n)
//!           J̇u = n·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + (|ḋ|² − (n·ḋ)²)/|d|
//! slider    C = t·d for t ∈ {t₁, t₂} = R_B n_B ⊥ the rail (2 rows):
//!                                                      (t, r_A×t | −t, −r_B×t + t×d)
//!           J̇u = t·(ω_A×(ω_A×r_A) − ω_B×(ω_B×r_B)) + 2 (ω_B×t)·ḋ + (ω_B×(ω_B×t))·d
//!           + fixed's 3 orientation rows (0, e_k | 0, −e_k), J̇u = 0
//!           error: the anchor's distance from the rail + the relative turn (rad) × 1 m
//! ```
//!
//! A hinge's or slider's limits and motor are rows with bounds, solved as impulses at the end
//! of the step with these rows held (`drive`); a stop within 1e-9 of its limit is also a
//! one-sided row of the contacts' exact solve (`collision::impulse::joined`) and of the
//! contact pass (`contact`), so a contact cannot turn a joint past its stop.
//!
//! Holding C̈ = 0 keeps C and Ċ where they started only up to the integrator's error: they
//! drift. `joint_correction` chooses what is done about it:
//!
//! ```text
//! none        nothing: |C| grows (explicit euler makes a pendulum's rod lengthen visibly)
//! baumgarte   C̈ = −2α Ċ − β² C  (α = β = 1/(10 dt): critically damped, ten steps' time
//!             constant) — the rhs gets −2α Ċ − β² C; the drift is pulled back, not removed
//! projection  after each step, positions back onto C = 0 (Newton: (J W Jᵀ) μ = −C,
//!             δx = W J_linᵀ μ, δθ = W J_angᵀ μ, repeated to |C| < 1e-12 m), then velocities
//!             onto J u = 0 (one linear solve, ΔP = J_linᵀ μ, ΔL = J_angᵀ μ); under
//!             `symplectic-euler` the positions move along the step's start rows and the
//!             momenta take the same correction over dt (SHAKE, then RATTLE's velocity half:
//!             `projection::shake`), which keeps that method symplectic
//! ```
//!
//! Contacts: after the contact response, the joint rows and the contact normals are solved
//! together, positions then velocities, as one mixed complementarity problem (`contact`), so
//! a chain that lands keeps its links while the contacts act.
//!
//! An ideal joint does no work (Jᵀλ · u = λ·(J u) = 0 on the constraint): the energy the
//! correction changes is numerical, booked apart (`EnergyLedger::joint_correction`) and still
//! counted in the drift.

mod chain;
pub mod contact;
pub mod drive;
mod kinds;
mod projection;
mod reduced;
mod rows;
pub mod solve;
pub mod written;

pub use chain::{Chain, Nearby};
pub use contact::{hold, Buffers as ContactBuffers};
pub use kinds::JointKind;
pub use projection::{project, shake, Buffers as ProjectionBuffers};
pub use rows::{coordinate, rate, rows_of, Pose, Row};
pub use solve::{again, multipliers, Solver};

use super::state::State;
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// How joint drift is removed (`[scene] joint_correction`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Correction {
    /// Positions onto C = 0 and velocities onto J u = 0 after every step (the default).
    #[default]
    Projection,
    /// The stabilised C̈ = −2α Ċ − β² C inside the derivative.
    Baumgarte,
    /// Nothing: the drift grows.
    None,
}

impl Correction {
    /// Every correction, as scene files name them.
    pub const ALL: [Correction; 3] = [
        Correction::Projection,
        Correction::Baumgarte,
        Correction::None,
    ];

    /// The scene-file name.
    pub fn name(self) -> &'static str {
        match self {
            Correction::Projection => "projection",
            Correction::Baumgarte => "baumgarte",
            Correction::None => "none",
        }
    }

    /// The correction with this name.
    pub fn from_name(name: &str) -> Option<Correction> {
        Correction::ALL.into_iter().find(|c| c.name() == name)
    }
}

/// An ideal joint between body `a` and body `b`, or `a` and the world (`b = None`). Every
/// vector is stored in its body's frame (from its barycenter), or in the world frame for the
/// world's side.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Unique among the world's joints.
    pub name: String,
    pub kind: JointKind,
    pub a: usize,
    pub b: Option<usize>,
    /// The anchor on A, A's frame, m.
    pub anchor_a: Vector3<f64>,
    /// The anchor on B (B's frame) or in the world, m.
    pub anchor_b: Vector3<f64>,
    /// Hinge: the axis in A's frame (unit).
    pub axis_a: Vector3<f64>,
    /// Hinge: two unit vectors ⊥ the axis, in B's frame or the world's.
    pub normals_b: [Vector3<f64>; 2],
    /// Fixed: R₀ = R_Bᵀ R_A at t = 0 (A's orientation seen from B).
    pub rest: Matrix3<f64>,
    /// Distance: the rod's length, m.
    pub length: f64,
    /// Slider: the rail's direction in B's frame or the world's (unit).
    pub axis_b: Vector3<f64>,
    /// Hinge: a unit vector ⊥ the axis in A's frame, along `normals_b[0]` at t = 0 (where the
    /// angle is 0).
    pub reference_a: Vector3<f64>,
    /// Hinge (rad) or slider (m): the stops [lo, hi] of its coordinate, lo ≤ 0 ≤ hi
    /// (`drive`).
    pub limits: Option<[f64; 2]>,
    /// Hinge or slider: its motor (`drive`).
    pub motor: Option<Motor>,
}

/// A joint's motor: drives the rate of the joint's coordinate (hinge: the angle, rad/s;
/// slider: the travel, m/s) towards `speed` with a force (N) or torque (N·m) of at most `max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motor {
    pub speed: f64,
    pub max: f64,
}

/// The pose of a body at t = 0 or of the world.
fn frame_of(states: &[State], body: Option<usize>) -> (Vector3<f64>, Matrix3<f64>) {
    match body {
        Some(i) => (states[i].position, states[i].orientation.matrix()),
        None => (Vector3::zeros(), Matrix3::identity()),
    }
}

/// A world point seen from a frame (x, R): `Rᵀ (p − x)`.
fn local(frame: &(Vector3<f64>, Matrix3<f64>), p: &Vector3<f64>) -> Vector3<f64> {
    frame.1.tr_mul(&(p - frame.0))
}

impl Joint {
    /// A ball, hinge, fixed or slider joint at world point `anchor` (t = 0 poses `states`);
    /// `axis` (world, non-zero) for a hinge or a slider.
    pub fn at_point(
        name: String,
        kind: JointKind,
        a: usize,
        b: Option<usize>,
        anchor: Vector3<f64>,
        axis: Vector3<f64>,
        states: &[State],
    ) -> Joint {
        let fa = frame_of(states, Some(a));
        let fb = frame_of(states, b);
        let axis = axis.try_normalize(1e-300).unwrap_or(Vector3::z());
        let seed = if axis.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let p = axis.cross(&seed).normalize();
        let q = axis.cross(&p);
        Joint {
            name,
            kind,
            a,
            b,
            anchor_a: local(&fa, &anchor),
            anchor_b: local(&fb, &anchor),
            axis_a: fa.1.tr_mul(&axis),
            normals_b: [fb.1.tr_mul(&p), fb.1.tr_mul(&q)],
            rest: fb.1.tr_mul(&fa.1),
            length: 0.0,
            axis_b: fb.1.tr_mul(&axis),
            reference_a: fa.1.tr_mul(&p),
            limits: None,
            motor: None,
        }
    }

    /// A distance joint between world points `anchor_a` (on A) and `anchor_b` (on B or the
    /// world); `length` None: their distance at t = 0.
    pub fn distance(
        name: String,
        a: usize,
        b: Option<usize>,
        [anchor_a, anchor_b]: [Vector3<f64>; 2],
        length: Option<f64>,
        states: &[State],
    ) -> Joint {
        let fa = frame_of(states, Some(a));
        let fb = frame_of(states, b);
        Joint {
            name,
            kind: JointKind::Distance,
            a,
            b,
            anchor_a: local(&fa, &anchor_a),
            anchor_b: local(&fb, &anchor_b),
            axis_a: Vector3::zeros(),
            normals_b: [Vector3::zeros(); 2],
            rest: Matrix3::identity(),
            length: length.unwrap_or((anchor_a - anchor_b).norm()),
            axis_b: Vector3::zeros(),
            reference_a: Vector3::zeros(),
            limits: None,
            motor: None,
        }
    }

    /// The two anchor points now, world frame: (on A, on B or the world).
    pub fn anchors(&self, states: &[State]) -> [Vector3<f64>; 2] {
        let (xa, ra) = frame_of(states, Some(self.a));
        let (xb, rb) = frame_of(states, self.b);
        [xa + ra * self.anchor_a, xb + rb * self.anchor_b]
    }

    /// The joint's position error, m: for ball, hinge and fixed the distance between its two
    /// anchor points, for distance |separation − length|; for a slider the distance of A's
    /// anchor from the rail (the line through B's anchor along the axis) plus the angle (rad)
    /// A has turned away from its orientation relative to B, times 1 m (how far a point 1 m
    /// from the anchor has drifted, to first order).
    pub fn error(&self, states: &[State]) -> f64 {
        let pa = Pose::of_state(&states[self.a]);
        let pb = self.b.map_or(Pose::WORLD, |b| Pose::of_state(&states[b]));
        kinds::error(self, &pa, &pb)
    }

    /// Hinge: the angle A has turned about the axis relative to B since t = 0, rad; slider: the
    /// travel of A's anchor along the axis relative to B's, m (`drive`). None for other kinds.
    pub fn coordinate(&self, states: &[State]) -> Option<f64> {
        let pa = Pose::of_state(&states[self.a]);
        let pb = self.b.map_or(Pose::WORLD, |b| Pose::of_state(&states[b]));
        rows::coordinate(self, usize::MAX, &pa, &pb).map(|(_, value)| value)
    }

    /// Whether it has a limit or a motor.
    pub fn driven(&self) -> bool {
        self.limits.is_some() || self.motor.is_some()
    }

    /// Hinge: its axis now, world frame (A's axis).
    pub fn axis(&self, states: &[State]) -> Vector3<f64> {
        states[self.a].orientation.matrix() * self.axis_a
    }

    /// The axis a front end draws at poses `a`, `b`, world frame (hinge: A's axis; slider: the
    /// rail); None for a kind without one.
    pub fn drawn_axis(&self, a: &Pose, b: &Pose) -> Option<Vector3<f64>> {
        kinds::axis(self, a, b)
    }
}

/// A Hooke spring with damping between two bodies or a body and the world.
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    /// Unique among the world's springs.
    pub name: String,
    pub a: usize,
    pub b: Option<usize>,
    /// The end on A, A's frame, m.
    pub anchor_a: Vector3<f64>,
    /// The end on B (B's frame) or in the world, m.
    pub anchor_b: Vector3<f64>,
    /// k, N/m (> 0).
    pub stiffness: f64,
    /// c, N·s/m along the spring (≥ 0).
    pub damping: f64,
    /// ℓ₀, m.
    pub rest_length: f64,
}

/// One spring's state: ends, length, tension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringLoad {
    /// The ends, world frame.
    pub ends: [Vector3<f64>; 2],
    /// |d|, m.
    pub length: f64,
    /// The force on A (toward B when stretched), N.
    pub force_a: Vector3<f64>,
    /// ½ k (|d| − ℓ₀)², J.
    pub potential: f64,
    /// −c (ḋ·n)², W.
    pub damping_power: f64,
}

/// A spring's law: `F = −k (|d| − ℓ₀) − c ḋ·n` along the line of its ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringLaw {
    /// k, N/m.
    pub stiffness: f64,
    /// c, N·s/m.
    pub damping: f64,
    /// ℓ₀, m; None: the ends' distance at t = 0.
    pub rest_length: Option<f64>,
}

impl Spring {
    /// A spring between world points (t = 0 poses `states`) with its law.
    pub fn new(
        name: String,
        a: usize,
        b: Option<usize>,
        [anchor_a, anchor_b]: [Vector3<f64>; 2],
        law: SpringLaw,
        states: &[State],
    ) -> Spring {
        let SpringLaw {
            stiffness,
            damping,
            rest_length,
        } = law;
        Spring {
            name,
            a,
            b,
            anchor_a: local(&frame_of(states, Some(a)), &anchor_a),
            anchor_b: local(&frame_of(states, b), &anchor_b),
            stiffness,
            damping,
            rest_length: rest_length.unwrap_or((anchor_a - anchor_b).norm()),
        }
    }

    /// Its force on A, energy and damping power at two poses (B's is the world's when `b` is
    /// None).
    #[inline]
    pub fn load(&self, a: &Pose, b: &Pose) -> (SpringLoad, Vector3<f64>, Vector3<f64>) {
        let ra = a.r * self.anchor_a;
        let rb = b.r * self.anchor_b;
        let pa = a.x + ra;
        let pb = b.x + rb;
        let d = pb - pa;
        let length = d.norm();
        let n = if length > 0.0 {
            d / length
        } else {
            Vector3::zeros()
        };
        let rate = (b.v + b.w.cross(&rb) - a.v - a.w.cross(&ra)).dot(&n);
        let stretch = length - self.rest_length;
        let force_a = n * (self.stiffness * stretch + self.damping * rate);
        (
            SpringLoad {
                ends: [pa, pb],
                length,
                force_a,
                potential: 0.5 * self.stiffness * stretch * stretch,
                damping_power: -self.damping * rate * rate,
            },
            ra,
            rb,
        )
    }
}

/// Everything that couples bodies: joints, springs and how drift is corrected.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Links {
    pub joints: Vec<Joint>,
    pub springs: Vec<Spring>,
    pub correction: Correction,
}

impl Links {
    /// No joint and no spring: every body moves on its own (the system's evaluation is per body:
    /// `System::coupled`).
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty() && self.springs.is_empty()
    }

    /// Whether some joint has a limit or a motor (the `drive` pass runs).
    pub fn driven(&self) -> bool {
        self.joints.iter().any(Joint::driven)
    }

    /// Whether some joint has a motor (the ledger has its row).
    pub fn motorised(&self) -> bool {
        self.joints.iter().any(|j| j.motor.is_some())
    }

    /// Constraint rows in all.
    pub fn row_count(&self) -> usize {
        self.joints.iter().map(|j| j.kind.rows()).sum()
    }

    /// Whether bodies `i` and `j` are joined directly by a joint (then they do not collide).
    pub fn joined(&self, i: usize, j: usize) -> bool {
        self.joints
            .iter()
            .any(|k| (k.a == i && k.b == Some(j)) || (k.a == j && k.b == Some(i)))
    }

    /// The pairs of bodies joined directly, (low, high).
    pub fn joined_pairs(&self) -> Vec<(usize, usize)> {
        let mut pairs: Vec<(usize, usize)> = self
            .joints
            .iter()
            .filter_map(|k| k.b.map(|b| (k.a.min(b), k.a.max(b))))
            .collect();
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// The springs' potential energy at these states, J.
    pub fn potential(&self, states: &[State]) -> f64 {
        self.springs
            .iter()
            .map(|s| {
                let [pa, pb] = [
                    Pose::of_state(&states[s.a]),
                    s.b.map_or(Pose::WORLD, |b| Pose::of_state(&states[b])),
                ];
                s.load(&pa, &pb).0.potential
            })
            .sum()
    }

    /// Whether some spring is damped (its damping is booked as drag work).
    pub fn damped(&self) -> bool {
        self.springs.iter().any(|s| s.damping > 0.0)
    }
}

/// `exp(θ) q`: q turned by the world rotation vector θ.
#[inline]
pub(crate) fn turn(q: &UnitQuaternion<f64>, theta: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::from_scaled_axis(*theta) * q
}
