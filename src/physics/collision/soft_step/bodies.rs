//! `soft-step`'s bodies: every body in contact taken back to the start of the step, moved
//! through the sub-steps, and written back into the states (module doc of `soft_step`).
//!
//! Per body, once per step: v₀, ω₀ = I₀⁻¹ L₀ and I₀⁻¹ (the start pose's world inverse
//! inertia, fixed over the step), and the external change per sub-step `Δv/n`, `ΔL/n`,
//! `I₀⁻¹ ΔL/n`. Per sub-step: `x += h v`, `q ← normalise(q + ½ h ω q)`, and the rotation
//! since the detection pose minus 𝟙, `D − 𝟙`, with the shift `x − x_det`, which every row's
//! separation reads.

use crate::physics::body::Body;
use crate::physics::derive::derive;
use crate::physics::state::{Orientation, State};
use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// A body's motion inside the sub-steps: v, ω (= I₀⁻¹ L) and 1/M. Its angular momentum is
/// not kept impulse by impulse: L at the end is L₀ plus the external change plus each row's
/// `(r×d) Λ` (the rows' totals).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Motion {
    pub v: Vector3<f64>,
    pub omega: Vector3<f64>,
    pub inv_mass: f64,
}

/// Where a solver body is within the sub-steps (its velocities are the [`Motion`] of the same
/// index).
#[derive(Debug, Clone, Copy)]
pub(super) struct Placement {
    pub position: Vector3<f64>,
    pub q: UnitQuaternion<f64>,
    /// The detection pose.
    detected_position: Vector3<f64>,
    detected_inverse: UnitQuaternion<f64>,
    /// Translation since the detection pose, `x − x_det`.
    pub shift: Vector3<f64>,
    /// Rotation since the detection pose, minus 𝟙.
    pub turned: Matrix3<f64>,
    /// The external velocity change per sub-step: Δv/n, ΔL/n and I₀⁻¹ ΔL/n.
    dv: Vector3<f64>,
    dl: Vector3<f64>,
    dw: Vector3<f64>,
}

impl Placement {
    /// Refreshes `shift` and `turned` from the pose.
    #[inline]
    fn measure(&mut self) {
        self.shift = self.position - self.detected_position;
        self.turned = (self.q * self.detected_inverse)
            .to_rotation_matrix()
            .into_inner()
            - Matrix3::identity();
    }
}

/// The bodies in contact during one step, as solver bodies (indexed by slot).
#[derive(Debug, Clone, Default)]
pub(super) struct Bodies {
    /// Index of each world body among the solver bodies (usize::MAX: not in contact).
    pub slot: Vec<usize>,
    /// The world index of each solver body.
    pub members: Vec<usize>,
    pub motions: Vec<Motion>,
    pub places: Vec<Placement>,
    /// Angular momentum L of each solver body (the external change added per sub-step, the
    /// rows' `(r×d) Λ` at the end).
    pub l: Vec<Vector3<f64>>,
    /// I₀⁻¹ in world axes, at the start pose.
    pub inv_inertia: Vec<Matrix3<f64>>,
    /// Each solver body's free flight (the integrate phase's result): v, ω and world I⁻¹.
    pub flight: Vec<(Vector3<f64>, Vector3<f64>, Matrix3<f64>)>,
    /// Per solver body, what the contacts changed of its v and ω over the last sub-step.
    kicks: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// Per solver body, its kinetic energy in the free flight (`gather`), then in the states
    /// written back (`soft_step::cap_kinetic`): what the energy of the step reuses.
    pub kinetic: Vec<f64>,
}

impl Bodies {
    /// Takes every moving body named by `contacts` (A, and B when it moves: a fixed body or an
    /// obstacle is static, gathered as neither, `collision::moves`) back to its start of step
    /// `before`, its free flight `states` giving the external change spread over `n` sub-steps.
    /// Returns the kinetic energy of the free flight of those bodies (each body's in
    /// `kinetic`).
    #[inline(always)]
    pub fn gather(
        &mut self,
        bodies: &[Body],
        before: &[State],
        states: &[State],
        contacts: &[super::Contact],
        n: u32,
    ) -> f64 {
        let Bodies {
            slot,
            members,
            motions,
            places,
            l,
            inv_inertia,
            flight,
            kicks,
            kinetic,
        } = self;
        slot.clear();
        slot.resize(states.len(), usize::MAX);
        members.clear();
        motions.clear();
        places.clear();
        l.clear();
        inv_inertia.clear();
        flight.clear();
        let inv = n as f64;
        for c in contacts {
            let b_moves = super::super::moves(bodies, c.other);
            for b in std::iter::once(c.body).chain(b_moves.then_some(c.other)) {
                if slot[b] != usize::MAX {
                    continue;
                }
                slot[b] = members.len();
                members.push(b);
                let body = &bodies[b];
                let start = &before[b];
                let free = &states[b];
                let k0 = derive(body, start);
                let k_free = derive(body, free);
                flight.push((
                    free.linear_momentum * body.inv_mass,
                    k_free.angular_velocity,
                    k_free.inv_inertia_world,
                ));
                motions.push(Motion {
                    v: start.linear_momentum * body.inv_mass,
                    omega: k0.angular_velocity,
                    inv_mass: body.inv_mass,
                });
                l.push(start.angular_momentum);
                inv_inertia.push(k0.inv_inertia_world);
                let q_free = free.orientation.quaternion();
                let mut place = Placement {
                    position: start.position,
                    q: start.orientation.quaternion(),
                    detected_position: free.position,
                    detected_inverse: q_free.inverse(),
                    shift: Vector3::zeros(),
                    turned: Matrix3::zeros(),
                    dv: (free.linear_momentum - start.linear_momentum) * body.inv_mass / inv,
                    dl: (free.angular_momentum - start.angular_momentum) / inv,
                    dw: k0.inv_inertia_world
                        * ((free.angular_momentum - start.angular_momentum) / inv),
                };
                place.measure();
                places.push(place);
            }
        }
        kicks.clear();
        kicks.resize(motions.len(), (Vector3::zeros(), Vector3::zeros()));
        kinetic.clear();
        kinetic.extend(
            members
                .iter()
                .zip(flight.iter())
                .map(|(&b, (_, _, inv_inertia))| {
                    let s = &states[b];
                    crate::physics::energy::kinetic_energy_with(
                        &bodies[b],
                        inv_inertia,
                        &s.linear_momentum,
                        &s.angular_momentum,
                    )
                }),
        );
        kinetic.iter().sum()
    }

    /// The start of a sub-step: the external change `Δv/n`, `ΔL/n`, then the warm start of a
    /// later sub-step, what the contacts did to the body over the last one (`kick` keeps the
    /// motion before it until the sub-step ends).
    #[inline(always)]
    pub fn begin_substep(&mut self) {
        for ((m, l), (p, kick)) in self
            .motions
            .iter_mut()
            .zip(self.l.iter_mut())
            .zip(self.places.iter().zip(self.kicks.iter_mut()))
        {
            m.v += p.dv;
            *l += p.dl;
            m.omega += p.dw;
            let start = (m.v, m.omega);
            m.v += kick.0;
            m.omega += kick.1;
            *kick = start;
        }
    }

    /// Every pose a sub-step of `h` further: `x += h v`, `q ← normalise(q + ½ h ω q)`.
    #[inline(always)]
    pub fn advance(&mut self, h: f64) {
        for i in 0..self.motions.len() {
            self.advance_one(i, h);
        }
    }

    /// Solver body i's pose a sub-step of `h` further (`advance`).
    #[inline(always)]
    pub fn advance_one(&mut self, i: usize, h: f64) {
        let (s, p) = (&self.motions[i], &mut self.places[i]);
        p.position += s.v * h;
        let w = s.omega * (0.5 * h);
        let dq = Quaternion::new(0.0, w.x, w.y, w.z) * p.q.into_inner();
        p.q = UnitQuaternion::new_normalize(p.q.into_inner() + dq);
        p.measure();
    }

    /// The end of a sub-step: each body's change by the contacts over it.
    #[inline(always)]
    pub fn end_substep(&mut self) {
        for (m, kick) in self.motions.iter().zip(self.kicks.iter_mut()) {
            *kick = (m.v - kick.0, m.omega - kick.1);
        }
    }

    /// B's slot, if B moves: a static B (a fixed body, an obstacle) is never gathered.
    #[inline(always)]
    pub fn moving(&self, other: usize) -> Option<usize> {
        self.slot.get(other).copied().filter(|&s| s != usize::MAX)
    }

    /// The poses, v and L back into `states` (every member moves: static things are never
    /// gathered).
    #[inline(always)]
    pub fn write_back(&self, bodies: &[Body], states: &mut [State]) {
        for (((&b, m), p), l) in self
            .members
            .iter()
            .zip(self.motions.iter())
            .zip(self.places.iter())
            .zip(self.l.iter())
        {
            let state = &mut states[b];
            state.position = p.position;
            state.orientation = match state.orientation {
                Orientation::Matrix(_) => {
                    Orientation::Matrix(p.q.to_rotation_matrix().into_inner())
                }
                Orientation::Quaternion(_) => Orientation::Quaternion(p.q),
            };
            state.linear_momentum = m.v * bodies[b].mass;
            state.angular_momentum = *l;
        }
    }
}
