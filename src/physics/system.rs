//! Forces on the whole system: the derivative f(Y) of every body's state at once, when bodies
//! are coupled by springs or joints.
//!
//! ```text
//! Y = (x_i, q_i, P_i, L_i) for every body i
//! f(Y) = (v_i, ½ ω_i ⊗ q_i, F_i, τ_i)
//! F_i, τ_i = the declared effects (gravity, drag: `Effects`)          one body at a time
//!          + Σ springs acting on i (`joints::Spring::load`)            pairs of bodies
//!          + Σ joints' reactions J_iᵀ λ (`joints`: the multipliers)    all joints at once
//! ```
//!
//! The integrators step this f (`integrators::system`), so every stage of rk4 is a stage of
//! the whole world: a spring between two bodies, or a pendulum's rod, is then integrated to
//! the method's full order. A world without springs or joints is a system too, whose
//! evaluation is per body ([`System::coupled`] is false): each body's f is its effects alone,
//! and the integrators step each body as a block of its own (`integrators::system::Block`:
//! the exact kick of `exact-splitting`, ω from L without I⁻¹_world at rk4's stages).

use super::body::Body;
use super::derive::{congruence, Kinematics};
use super::effects::{Effects, Loads};
use super::integrators::Integrator;
use super::joints::solve::Inverse;
use super::joints::{multipliers, rows_of, Chain, Correction, Links, Nearby, Pose, Row, Solver};
use super::state::State;
use nalgebra::{Matrix3, Vector3};

/// What the derivative sees: the bodies, the declared effects, the links, and the integrator
/// (whose forces phase may add to the effects: `euler-seed`'s vertex torque).
#[derive(Debug, Clone, Copy)]
pub struct System<'a> {
    pub bodies: &'a [Body],
    pub effects: &'a Effects,
    pub links: &'a Links,
    pub integrator: Integrator,
    /// The step, s (sets Baumgarte's rates α = β = 1/(10 dt)).
    pub dt: f64,
}

/// Buffers of an evaluation, and its results.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scratch {
    poses: Vec<Pose>,
    inverse: Vec<Inverse>,
    rows: Vec<Row>,
    rhs: Vec<f64>,
    /// Per body: its free accelerations (v̇, ω̇) under the applied loads.
    free: Vec<(Vector3<f64>, Vector3<f64>)>,
    solver: Solver,
    /// A chain's compact rows (`joints::Chain`: no rows built).
    chain: Chain,
    positions: Vec<Vector3<f64>>,
    momenta: Vec<Vector3<f64>>,
    /// Result: the total force and torque on each body.
    pub loads: Vec<Loads>,
    /// Result: each joint's force and torque (about A's barycenter) on its body A.
    pub joint_loads: Vec<Loads>,
    /// Result: the springs' damping power, W (≤ 0).
    pub damping_power: f64,
}

/// A body's kinematics from (x, R, P, L), R a rotation.
#[inline]
pub fn kinematics(
    body: &Body,
    rotation: Matrix3<f64>,
    p: &Vector3<f64>,
    l: &Vector3<f64>,
) -> Kinematics {
    let inv_inertia_world = congruence(&rotation, &body.inv_inertia_body);
    Kinematics {
        rotation,
        inv_inertia_world,
        angular_velocity: inv_inertia_world * l,
        velocity: p * body.inv_mass,
    }
}

impl Scratch {
    /// Forgets the bodies of the last evaluation (before [`Scratch::push_body`]).
    #[inline]
    pub fn clear_bodies(&mut self) {
        self.poses.clear();
        self.inverse.clear();
    }

    /// The next body's pose (x, R, v, ω) and inverse mass (1/m, I⁻¹_world) for an evaluation
    /// ([`System::evaluate_bodies`]), from its position and kinematics.
    #[inline(always)]
    pub fn push_body(&mut self, body: &Body, x: &Vector3<f64>, k: &Kinematics) {
        self.poses.push(Pose {
            x: *x,
            r: k.rotation,
            v: k.velocity,
            w: k.angular_velocity,
        });
        self.inverse.push(Inverse {
            mass: body.inv_mass,
            inertia: k.inv_inertia_world,
        });
    }

    /// Each body's pose at the last evaluation (its v and ω: the rates' velocities).
    #[inline]
    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// The joints' solver, holding the factor of J W Jᵀ of the last evaluation (when banded:
    /// `joints::again`).
    pub fn solver_mut(&mut self) -> &mut Solver {
        &mut self.solver
    }

    /// The factor of J W Jᵀ of the last evaluation, banded (`joints::again`) or a hinge
    /// chain's reduced one (`joints::Chain::solve`), for the projection's chord passes.
    pub fn nearby(&mut self) -> Nearby<'_> {
        self.chain.nearby(&mut self.solver)
    }
}

impl System<'_> {
    /// Whether springs or joints couple the bodies (otherwise each body's f is its own).
    #[inline]
    pub fn coupled(&self) -> bool {
        !self.links.is_empty()
    }

    /// f(Y)'s forces: fills `scratch.loads` (total F, τ per body), `scratch.joint_loads` and
    /// `scratch.damping_power`, from each body's position, kinematics and angular momentum.
    pub fn evaluate(
        &self,
        positions: &[Vector3<f64>],
        kinematics: &[Kinematics],
        angular_momenta: &[Vector3<f64>],
        scratch: &mut Scratch,
    ) {
        scratch.clear_bodies();
        for ((body, x), k) in self.bodies.iter().zip(positions).zip(kinematics) {
            scratch.push_body(body, x, k);
        }
        self.evaluate_bodies(angular_momenta, scratch);
    }

    /// [`System::evaluate`] at the bodies' poses and inverse masses already in `scratch`
    /// ([`Scratch::push_body`], every body in order): a stage's evaluation builds them from
    /// its kinematics as it makes them, with no list of kinematics copied.
    pub fn evaluate_bodies(&self, angular_momenta: &[Vector3<f64>], scratch: &mut Scratch) {
        self.effect_loads(scratch);
        self.add_springs(scratch);
        scratch.joint_loads.clear();
        scratch
            .joint_loads
            .resize(self.links.joints.len(), Loads::default());
        if !self.links.joints.is_empty() {
            self.add_joint_reactions(angular_momenta, scratch);
        }
    }

    /// Each body's F and τ of the declared effects (and the integrator's forces phase:
    /// `euler-seed`'s vertex torque), at its pose.
    fn effect_loads(&self, scratch: &mut Scratch) {
        scratch.loads.clear();
        scratch
            .loads
            .extend(self.bodies.iter().zip(&scratch.poses).map(|(b, p)| {
                self.integrator
                    .loads_moving(b, self.effects, &p.r, &p.v, &p.w)
            }));
    }

    /// Springs: equal and opposite forces at the two ends; their damping power.
    fn add_springs(&self, scratch: &mut Scratch) {
        scratch.damping_power = 0.0;
        for spring in &self.links.springs {
            let a = &scratch.poses[spring.a];
            let b = spring.b.map_or(&Pose::WORLD, |b| &scratch.poses[b]);
            let (load, ra, rb) = spring.load(a, b);
            scratch.damping_power += load.damping_power;
            let f = load.force_a;
            scratch.loads[spring.a].force += f;
            scratch.loads[spring.a].torque += ra.cross(&f);
            if let Some(b) = spring.b {
                scratch.loads[b].force -= f;
                scratch.loads[b].torque -= rb.cross(&f);
            }
        }
    }

    /// Joints: (J W Jᵀ) λ = −(J a_free + J̇ u) − correction; each row's J_iᵀ λ added to its
    /// bodies' loads and to its joint's reaction on A. Compiled twice, plain and with AVX2
    /// (no fused multiply–add: the same bits; `physics::simd`).
    fn add_joint_reactions(&self, angular_momenta: &[Vector3<f64>], scratch: &mut Scratch) {
        #[cfg(target_arch = "x86_64")]
        if super::simd::avx2() {
            // SAFETY: the CPU has AVX2.
            return unsafe { self.joint_reactions_avx2(angular_momenta, scratch) };
        }
        self.joint_reactions(angular_momenta, scratch);
    }

    /// [`System::joint_reactions`] compiled with AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn joint_reactions_avx2(&self, angular_momenta: &[Vector3<f64>], scratch: &mut Scratch) {
        self.joint_reactions(angular_momenta, scratch);
    }

    /// [`System::add_joint_reactions`] for any CPU.
    #[inline(always)]
    fn joint_reactions(&self, angular_momenta: &[Vector3<f64>], scratch: &mut Scratch) {
        let n = self.bodies.len();
        let chain = self.links.correction != Correction::Baumgarte
            && scratch
                .chain
                .build_for_forces(&self.links.joints, &scratch.poses);
        scratch.rows.clear();
        if !chain {
            for (index, joint) in self.links.joints.iter().enumerate() {
                let a = &scratch.poses[joint.a];
                let b = joint.b.map_or(&Pose::WORLD, |b| &scratch.poses[b]);
                rows_of(joint, index, a, b, &mut scratch.rows);
            }
        }
        if chain {
            // A hinge tree rooted in the world: through its joint coordinates.
            let poses = &scratch.poses;
            let gyroscopic = |i: usize| poses[i].w.cross(&angular_momenta[i]);
            let (loads, reactions) = (&mut scratch.loads, &mut scratch.joint_loads);
            let solver = &mut scratch.solver;
            if (scratch.chain).react(&scratch.inverse, solver, gyroscopic, loads, reactions) {
                return;
            }
        }
        // Free accelerations (v̇, ω̇) = (F/m, I⁻¹(τ − ω × L)), once per body.
        scratch.free.clear();
        scratch.free.extend((0..n).map(|i| {
            let loads = &scratch.loads[i];
            (
                loads.force * self.bodies[i].inv_mass,
                scratch.inverse[i].inertia
                    * (loads.torque - scratch.poses[i].w.cross(&angular_momenta[i])),
            )
        }));
        if chain {
            // The same numbers as the rows' path below, from the compact rows.
            scratch.chain.rhs(&scratch.free, &mut scratch.rhs);
            let solver = &mut scratch.solver;
            scratch
                .chain
                .solve(&scratch.inverse, &mut scratch.rhs, solver);
            let (loads, reactions) = (&mut scratch.loads, &mut scratch.joint_loads);
            scratch.chain.apply(&scratch.rhs, loads, reactions);
            return;
        }
        let rate = 1.0 / (10.0 * self.dt);
        scratch.rhs.clear();
        for row in &scratch.rows {
            let (la, aa) = &scratch.free[row.a()];
            let mut j_a = row.lin_a().dot(la) + row.ang_a().dot(aa);
            let b = match row.b() {
                Some(b) => {
                    let (lb, ab) = &scratch.free[b];
                    j_a += row.lin_b().dot(lb) + row.ang_b().dot(ab);
                    &scratch.poses[b]
                }
                None => &Pose::WORLD,
            };
            let mut rhs = -(j_a + row.bias);
            if self.links.correction == Correction::Baumgarte {
                let c_dot = super::joints::rate(row, &scratch.poses[row.a()], b);
                rhs -= 2.0 * rate * c_dot + rate * rate * row.error;
            }
            scratch.rhs.push(rhs);
        }
        multipliers(
            &scratch.rows,
            &scratch.inverse,
            &mut scratch.rhs,
            &mut scratch.solver,
        );
        for (row, &lambda) in scratch.rows.iter().zip(&scratch.rhs) {
            let (f, t) = (row.lin_a() * lambda, row.ang_a() * lambda);
            scratch.loads[row.a()].force += f;
            scratch.loads[row.a()].torque += t;
            let reaction = &mut scratch.joint_loads[row.owner];
            reaction.force += f;
            reaction.torque += t;
            if let Some(b) = row.b() {
                scratch.loads[b].force += row.lin_b() * lambda;
                scratch.loads[b].torque += row.ang_b() * lambda;
            }
        }
    }

    /// f(Y)'s forces at states whose kinematics the derive phase computed (the forces phase):
    /// each body's total F and τ into `loads`, the joints' reactions and the damping power
    /// into `scratch` as [`System::evaluate`]. Without links each body's f is its effects
    /// alone, evaluated in place.
    #[inline]
    pub fn evaluate_at(
        &self,
        states: &[State],
        kinematics: &[Kinematics],
        loads: &mut [Loads],
        scratch: &mut Scratch,
    ) {
        if !self.coupled() {
            for ((l, b), k) in loads.iter_mut().zip(self.bodies).zip(kinematics) {
                *l = self.integrator.loads(b, self.effects, k);
            }
            scratch.joint_loads.clear();
            scratch.damping_power = 0.0;
            return;
        }
        let mut positions = std::mem::take(&mut scratch.positions);
        let mut momenta = std::mem::take(&mut scratch.momenta);
        positions.clear();
        positions.extend(states.iter().map(|s| s.position));
        momenta.clear();
        momenta.extend(states.iter().map(|s| s.angular_momentum));
        self.evaluate(&positions, kinematics, &momenta, scratch);
        (scratch.positions, scratch.momenta) = (positions, momenta);
        loads.copy_from_slice(&scratch.loads);
    }

    /// f(Y)'s forces at states (orientations as stored: a drifted `euler-seed` matrix is used
    /// as it is, as the report's loop would).
    pub fn evaluate_states(
        &self,
        states: &[State],
        kinematics: &mut Vec<Kinematics>,
        scratch: &mut Scratch,
    ) {
        kinematics.clear();
        kinematics.extend(
            self.bodies
                .iter()
                .zip(states)
                .map(|(b, s)| kinematics_of_state(b, s)),
        );
        let positions: Vec<Vector3<f64>> = states.iter().map(|s| s.position).collect();
        let momenta: Vec<Vector3<f64>> = states.iter().map(|s| s.angular_momentum).collect();
        self.evaluate(&positions, kinematics, &momenta, scratch);
    }
}

/// The derive phase of a state (its orientation's matrix, as `derive` takes it).
#[inline]
fn kinematics_of_state(body: &Body, state: &State) -> Kinematics {
    super::derive::derive(body, state)
}
