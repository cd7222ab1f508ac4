//! The known mistakes of the report's loop, each planted alone in a copy of the loop.
//!
//! A mistake is one small function below, returning what it is, the phase it is in, its fix in
//! one line, the lesson that shows it, and how to plant it: [`Knobs`] turned in the variant loop
//! [`Planted`] (derive → forces → integrate → collide for one body, written here with the
//! physics core's functions, so that the core's hot paths carry no mistake), or a run of the
//! scene at another time step. `tumble diff` steps the scene once per mistake and reports the
//! ones that reproduce their numbers; a mistake not on the list is reported as unknown, never
//! as the nearest one.
//!
//! The variant loop knows the report's explicit loops: `euler-seed` (R a matrix), `euler` and
//! `symplectic-euler` (a quaternion). With any other integrator, or joints, springs, cloths or
//! several bodies, only the time step can be planted (that runs the scene itself).
//!
//! | mistake | phase | planted as |
//! |---|---|---|
//! | torque about the origin | forces | τ += x × F (per vertex: Σ pᵢ × F with pᵢ = x + R r₀ᵢ) |
//! | the per-vertex torque | forces | τ += Σ (R r₀ᵢ) × F where the loop has none; none where `euler-seed` has it |
//! | ω from I⁻¹_body L | derive | I⁻¹_world = I⁻¹_body (no R · … · Rᵀ) |
//! | the other velocity for x | integrate | x += dt·P_new/M (or P_old/M under `symplectic-euler`) |
//! | R kept a rotation, or not | integrate | `euler-seed`: R re-orthonormalised (Gram–Schmidt, or the nearest rotation); quaternion loops: q not normalised |
//! | gravity on every point | forces | F = N·M g (N points) |
//! | the time step off by a factor | integrate | the scene run at c·dt (c from their t, their first step, or 2, ½, 10, …) |

use crate::physics::collision::{collide, impulse, CollideInput, ContactModel, Obstacle};
use crate::physics::derive::congruence;
use crate::physics::effects::{Effects, Loads};
use crate::physics::integrators::Integrator;
use crate::physics::state::{Orientation, State};
use crate::physics::{Body, Phase};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// How the variant loop keeps its orientation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Rotation {
    /// As the integrator does (`euler-seed`: R as it drifts; quaternions: normalised).
    #[default]
    AsIntegrator,
    /// `euler-seed`'s R re-orthonormalised by Gram–Schmidt on its columns each step.
    GramSchmidt,
    /// `euler-seed`'s R replaced by its nearest rotation each step.
    Nearest,
    /// A quaternion loop's q never normalised; R from q by `w² + x² − y² − z², …`.
    Unnormalised,
    /// A quaternion loop's q never normalised; R from q by `1 − 2(y² + z²), …`.
    UnnormalisedUnitFormula,
}

/// The knobs a mistake turns in the variant loop (all off: the scene's own loop).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Knobs {
    pub torque_about_origin: bool,
    pub vertex_torque_swapped: bool,
    pub omega_from_body_inertia: bool,
    pub position_velocity_swapped: bool,
    pub rotation: Rotation,
    pub gravity_per_point: bool,
}

/// How a mistake is planted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Plant {
    /// In the variant loop.
    Knobs(Knobs),
    /// The scene itself at `factor · dt`.
    TimeStep(f64),
}

/// A known mistake.
#[derive(Debug, Clone, PartialEq)]
pub struct Mistake {
    /// What the loop does wrong, in one line.
    pub what: String,
    /// The phase it is in.
    pub phase: Phase,
    /// The fix, in one line.
    pub fix: String,
    /// The bundled lesson that shows it.
    pub lesson: &'static str,
    pub plant: Plant,
}

/// Whether the variant loop can step this integrator.
pub fn plantable(integrator: Integrator) -> bool {
    matches!(
        integrator,
        Integrator::EulerSeed | Integrator::Euler | Integrator::SymplecticEuler
    )
}

/// τ about the world origin instead of the barycenter.
pub fn torque_about_origin(integrator: Integrator) -> Mistake {
    let seed = integrator == Integrator::EulerSeed;
    Mistake {
        what: if seed {
            "the torque taken about the origin instead of the barycenter: Σ pᵢ × F with the \
             vertices' world positions pᵢ"
                .into()
        } else {
            "the torque taken about the origin instead of the barycenter: x × F".into()
        },
        phase: Phase::Forces,
        fix: if seed {
            "lever arms from the barycenter: τ = Σ (pᵢ − x) × F, not Σ pᵢ × F".into()
        } else {
            "take moments about the barycenter x: gravity at x makes no torque there".into()
        },
        lesson: "04-gravity-no-torque",
        plant: Plant::Knobs(Knobs {
            torque_about_origin: true,
            ..Knobs::default()
        }),
    }
}

/// The report's per-vertex torque, where the scene's loop has none (or none where it has it).
pub fn per_vertex_torque(integrator: Integrator) -> Mistake {
    let seed = integrator == Integrator::EulerSeed;
    Mistake {
        what: if seed {
            "no per-vertex torque, where the report's loop (euler-seed) sums Σ (R r₀ᵢ) × F".into()
        } else {
            "the report's per-vertex gravity torque Σ (R r₀ᵢ) × F (the total force at every \
             vertex)"
                .into()
        },
        phase: Phase::Forces,
        fix: if seed {
            "euler-seed reproduces the report, which adds Σ (R r₀ᵢ) × F to τ; without it you \
             run another loop (`--integrator euler` is the closest)"
                .into()
        } else {
            "drop the vertex sum: a uniform gravity makes no torque about the barycenter \
             (Σ mᵢ rᵢ = 0, not Σ rᵢ = 0)"
                .into()
        },
        lesson: "04-gravity-no-torque",
        plant: Plant::Knobs(Knobs {
            vertex_torque_swapped: true,
            ..Knobs::default()
        }),
    }
}

/// ω = I⁻¹_body L, the inverse inertia never turned into the world frame.
pub fn omega_from_body_inertia(_: Integrator) -> Mistake {
    Mistake {
        what: "ω from I⁻¹_body L: the inverse inertia never turned into the world frame".into(),
        phase: Phase::Derive,
        fix: "I⁻¹_world = R I⁻¹_body Rᵀ, then ω = I⁻¹_world L".into(),
        lesson: "02-rigid-body-from-points",
        plant: Plant::Knobs(Knobs {
            omega_from_body_inertia: true,
            ..Knobs::default()
        }),
    }
}

/// The position advanced with the other velocity (new for old, or old for new).
pub fn velocity_for_position(integrator: Integrator) -> Mistake {
    let symplectic = integrator == Integrator::SymplecticEuler;
    Mistake {
        what: if symplectic {
            "the old velocity used for the position, where symplectic-euler moves x with the \
             new one"
                .into()
        } else {
            format!(
                "the new velocity used for the position, where {} moves x with the old one",
                integrator.name()
            )
        },
        phase: Phase::Integrate,
        fix: if symplectic {
            "update P first, then x += dt·P_new/M".into()
        } else {
            "x += dt·v with v = P/M from the start of the step, before P += dt·F".into()
        },
        lesson: "01-the-loop",
        plant: Plant::Knobs(Knobs {
            position_velocity_swapped: true,
            ..Knobs::default()
        }),
    }
}

/// R kept a rotation where the scene's loop lets it drift, or q left to drift where the
/// scene's loop normalises it.
pub fn rotation_kept(integrator: Integrator) -> Vec<Mistake> {
    let make = |what: &str, fix: &str, rotation| Mistake {
        what: what.into(),
        phase: Phase::Integrate,
        fix: fix.into(),
        lesson: "03-rotation-drift",
        plant: Plant::Knobs(Knobs {
            rotation,
            ..Knobs::default()
        }),
    };
    if integrator == Integrator::EulerSeed {
        let fix = "euler-seed reproduces the report, whose R is never re-orthonormalised: \
                   compare a re-orthonormalised loop with `--integrator euler`";
        vec![
            make(
                "R re-orthonormalised each step (Gram–Schmidt on its columns), where the \
                 report's loop lets it drift",
                fix,
                Rotation::GramSchmidt,
            ),
            make(
                "R replaced by its nearest rotation each step, where the report's loop lets \
                 it drift",
                fix,
                Rotation::Nearest,
            ),
        ]
    } else {
        let fix = "normalise q after each step: q ← q / |q|";
        vec![
            make(
                "q never normalised (R from q by w² + x² − y² − z², …)",
                fix,
                Rotation::Unnormalised,
            ),
            make(
                "q never normalised (R from q by 1 − 2(y² + z²), …)",
                fix,
                Rotation::UnnormalisedUnitFormula,
            ),
        ]
    }
}

/// The body's weight M g applied at every one of its N points: F = N·M g.
pub fn gravity_on_every_point(_: Integrator) -> Mistake {
    Mistake {
        what: "gravity as M g on every point: F = N·M g for N points".into(),
        phase: Phase::Forces,
        fix: "the weight is M g in all, mᵢ g on point i (Σ mᵢ = M)".into(),
        lesson: "04-gravity-no-torque",
        plant: Plant::Knobs(Knobs {
            gravity_per_point: true,
            ..Knobs::default()
        }),
    }
}

/// The loop stepped by `factor · dt` (rows still counted in the scene's steps).
pub fn time_step_factor(factor: f64, dt: f64) -> Mistake {
    Mistake {
        what: format!(
            "a time step off by a factor {}: yours steps {} s where the scene's dt is {} s",
            short(factor),
            short(factor * dt),
            short(dt)
        ),
        phase: Phase::Integrate,
        fix: format!("use the scene's dt = {} s in every update", short(dt)),
        lesson: "12-accuracy-cost",
        plant: Plant::TimeStep(factor),
    }
}

/// A number in a few digits.
fn short(value: f64) -> String {
    let text = format!("{value:.6}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "0" || text == "-0" {
        format!("{value:.3e}")
    } else {
        text.to_string()
    }
}

/// Every known mistake the scene's loop can have planted (`plantable`: the variant loop can
/// step it), and the time step by each factor.
pub fn known(integrator: Integrator, plantable: bool, factors: &[f64], dt: f64) -> Vec<Mistake> {
    let mut all = Vec::new();
    if plantable {
        all.push(torque_about_origin(integrator));
        all.push(per_vertex_torque(integrator));
        all.push(omega_from_body_inertia(integrator));
        all.push(velocity_for_position(integrator));
        all.extend(rotation_kept(integrator));
        all.push(gravity_on_every_point(integrator));
    }
    all.extend(factors.iter().map(|&f| time_step_factor(f, dt)));
    all
}

/// The orientation the variant loop steps.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Turn {
    Matrix(Matrix3<f64>),
    /// Not necessarily unit (with [`Rotation::Unnormalised`]).
    Quaternion(Quaternion<f64>),
}

/// The report's loop for one body with mistakes planted: derive, forces, integrate, collide.
#[derive(Debug, Clone)]
pub struct Planted<'a> {
    pub body: &'a Body,
    pub effects: &'a Effects,
    pub obstacles: &'a [Obstacle],
    pub contact: Option<&'a ContactModel>,
    pub integrator: Integrator,
    pub dt: f64,
    pub knobs: Knobs,
    position: Vector3<f64>,
    turn: Turn,
    momentum: Vector3<f64>,
    angular_momentum: Vector3<f64>,
    initial_position: Vector3<f64>,
    contacts: Vec<crate::physics::Contact>,
    scratch: impulse::Scratch,
}

/// What the variant's derive phase computes.
struct Derived {
    rotation: Matrix3<f64>,
    inv_inertia_world: Matrix3<f64>,
    angular_velocity: Vector3<f64>,
    velocity: Vector3<f64>,
}

impl<'a> Planted<'a> {
    /// The loop at `initial` (its orientation converted as the integrator steps it).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        body: &'a Body,
        effects: &'a Effects,
        obstacles: &'a [Obstacle],
        contact: Option<&'a ContactModel>,
        integrator: Integrator,
        dt: f64,
        initial: &State,
        knobs: Knobs,
    ) -> Planted<'a> {
        let turn = match integrator.orientation_for(&initial.orientation) {
            Orientation::Matrix(m) => Turn::Matrix(m),
            Orientation::Quaternion(q) => Turn::Quaternion(q.into_inner()),
        };
        Planted {
            body,
            effects,
            obstacles,
            contact,
            integrator,
            dt,
            knobs,
            position: initial.position,
            turn,
            momentum: initial.linear_momentum,
            angular_momentum: initial.angular_momentum,
            initial_position: initial.position,
            contacts: Vec::new(),
            scratch: impulse::Scratch::default(),
        }
    }

    /// R of the current orientation.
    fn rotation(&self) -> Matrix3<f64> {
        match self.turn {
            Turn::Matrix(m) => m,
            Turn::Quaternion(q) if self.knobs.rotation == Rotation::UnnormalisedUnitFormula => {
                unit_formula(&q)
            }
            Turn::Quaternion(q) => UnitQuaternion::new_unchecked(q)
                .to_rotation_matrix()
                .into_inner(),
        }
    }

    /// *derive*: I⁻¹_world, ω, v.
    fn derive(&self) -> Derived {
        let rotation = self.rotation();
        let inv_inertia_world = if self.knobs.omega_from_body_inertia {
            self.body.inv_inertia_body
        } else {
            congruence(&rotation, &self.body.inv_inertia_body)
        };
        Derived {
            rotation,
            inv_inertia_world,
            angular_velocity: inv_inertia_world * self.angular_momentum,
            velocity: self.momentum * self.body.inv_mass,
        }
    }

    /// *forces*: F and τ as the loop (and its mistakes) compute them.
    fn forces(&self, d: &Derived) -> Loads {
        let mut loads = self
            .effects
            .loads_at(self.body, &d.velocity, &d.angular_velocity);
        let points = self.body.points_body.len() as f64;
        if self.knobs.gravity_per_point {
            if let Some(g) = self.effects.gravity() {
                loads.force += g * self.body.mass * (points - 1.0);
            }
        }
        let vertex = (self.integrator == Integrator::EulerSeed) != self.knobs.vertex_torque_swapped;
        if vertex {
            loads.torque +=
                crate::physics::integrators::vertex_torque(self.body, &d.rotation, &loads.force);
        }
        if self.knobs.torque_about_origin {
            let count = if vertex { points } else { 1.0 };
            loads.torque += self.position.cross(&loads.force) * count;
        }
        loads
    }

    /// The state in the physics core's form (for the collide phase).
    fn state(&self) -> State {
        State {
            position: self.position,
            orientation: match self.turn {
                Turn::Matrix(m) => Orientation::Matrix(m),
                Turn::Quaternion(q) => Orientation::Quaternion(UnitQuaternion::new_unchecked(q)),
            },
            linear_momentum: self.momentum,
            angular_momentum: self.angular_momentum,
        }
    }

    /// One frame: derive, forces, integrate, collide.
    pub fn step(&mut self) {
        let d = self.derive();
        let loads = self.forces(&d);
        let before = self.state();
        self.integrate(&d, &loads);
        self.collide(&before, &loads);
    }

    /// *integrate*: the scene's explicit loop with the knobs turned.
    fn integrate(&mut self, d: &Derived, loads: &Loads) {
        let dt = self.dt;
        let swapped = self.knobs.position_velocity_swapped;
        match self.integrator {
            Integrator::SymplecticEuler => {
                self.momentum += loads.force * dt;
                self.angular_momentum += loads.torque * dt;
                let velocity = self.momentum * self.body.inv_mass;
                let angular_velocity = d.inv_inertia_world * self.angular_momentum;
                self.position += if swapped { d.velocity } else { velocity } * dt;
                self.turn_quaternion(&angular_velocity);
            }
            _ => {
                if swapped {
                    let momentum = self.momentum + loads.force * dt;
                    self.position += momentum * self.body.inv_mass * dt;
                } else {
                    self.position += d.velocity * dt;
                }
                match self.turn {
                    Turn::Matrix(r) => {
                        let r = r + d.angular_velocity.cross_matrix() * r * dt;
                        self.turn = Turn::Matrix(match self.knobs.rotation {
                            Rotation::GramSchmidt => gram_schmidt(&r),
                            Rotation::Nearest => Orientation::Matrix(r)
                                .quaternion()
                                .to_rotation_matrix()
                                .into_inner(),
                            _ => r,
                        });
                    }
                    Turn::Quaternion(_) => self.turn_quaternion(&d.angular_velocity),
                }
                self.momentum += loads.force * dt;
                self.angular_momentum += loads.torque * dt;
            }
        }
    }

    /// `q ← q + dt·½ ω⊗q`, normalised unless a knob says otherwise.
    fn turn_quaternion(&mut self, angular_velocity: &Vector3<f64>) {
        let Turn::Quaternion(q) = self.turn else {
            return;
        };
        let q = q + Quaternion::from_imag(*angular_velocity) * q * 0.5 * self.dt;
        self.turn = Turn::Quaternion(match self.knobs.rotation {
            Rotation::Unnormalised | Rotation::UnnormalisedUnitFormula => q,
            _ => q * (1.0 / q.norm()),
        });
    }

    /// *collide*: the scene's response, as the world runs it.
    fn collide(&mut self, before: &State, loads: &Loads) {
        let Some(model) = self.contact else {
            return;
        };
        if self.obstacles.is_empty() {
            return;
        }
        let mut state = self.state();
        let input = CollideInput {
            bodies: std::slice::from_ref(self.body),
            obstacles: self.obstacles,
            model,
            before: std::slice::from_ref(before),
            loads: std::slice::from_ref(loads),
            initial_positions: std::slice::from_ref(&self.initial_position),
            context: crate::physics::collision::StepContext::new(
                self.dt,
                self.effects.gravity(),
                Some(model),
            ),
            joined: &[],
            joints: None,
            recorded: None,
        };
        collide(
            &input,
            std::slice::from_mut(&mut state),
            &mut self.contacts,
            &mut self.scratch,
        );
        self.position = state.position;
        self.momentum = state.linear_momentum;
        self.angular_momentum = state.angular_momentum;
    }

    /// The row `run` would print for this loop now, at `t` (energy from the loop's own ω;
    /// penetration is not measured: NaN).
    pub fn sample(&self, t: f64) -> super::compare::Sample {
        let d = self.derive();
        let quaternion = match self.turn {
            Turn::Matrix(m) => {
                let q = Orientation::Matrix(m).quaternion().into_inner();
                [q.w, q.i, q.j, q.k]
            }
            Turn::Quaternion(q) => [q.w, q.i, q.j, q.k],
        };
        let kinetic = 0.5 * self.body.mass * d.velocity.norm_squared()
            + 0.5 * d.angular_velocity.dot(&self.angular_momentum);
        super::compare::Sample {
            t,
            position: self.position,
            quaternion,
            rotation: d.rotation,
            velocity: d.velocity,
            angular_velocity: d.angular_velocity,
            momentum: self.momentum,
            angular_momentum: self.angular_momentum,
            energy: kinetic + self.effects.potential_energy(self.body, &self.position),
            penetration: f64::NAN,
        }
    }

    /// Every number of the state is finite.
    pub fn is_finite(&self) -> bool {
        let turn = match self.turn {
            Turn::Matrix(m) => m.iter().all(|c| c.is_finite()),
            Turn::Quaternion(q) => q.coords.iter().all(|c| c.is_finite()),
        };
        turn && self.position.iter().all(|c| c.is_finite())
            && self.momentum.iter().all(|c| c.is_finite())
            && self.angular_momentum.iter().all(|c| c.is_finite())
    }
}

/// Gram–Schmidt on the columns: c₀ ← c₀/|c₀|, c₁ ← (c₁ − (c₀·c₁) c₀)/|…|, c₂ ← c₀ × c₁.
pub fn gram_schmidt(r: &Matrix3<f64>) -> Matrix3<f64> {
    let c0 = r.column(0).normalize();
    let c1 = r.column(1) - c0 * c0.dot(&r.column(1));
    let c1 = c1.normalize();
    let c2 = c0.cross(&c1);
    Matrix3::from_columns(&[c0, c1, c2])
}

/// R from a quaternion taken as unit: `1 − 2(y² + z²)`, ….
pub fn unit_formula(q: &Quaternion<f64>) -> Matrix3<f64> {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    Matrix3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}
